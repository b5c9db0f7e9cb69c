#!/bin/sh
# tests/stability/check.sh CSFC CSFVM DIR - the stability guard against known answers:
#  - a fixed step past the limit is refused before its rows (rk4 --step 0.5, and
#    verlet's own step at --tol 1e-3, on the oscillator), and the same scenes at a
#    stable step match the exact solution;
#  - the largest stable step reported is within 2 % of the analytic limit for each
#    fixed-step method, on the imaginary axis (oscillator) and the real axis (decay);
#    a real pair +-a limits rk4 by its decaying member and verlet not at all;
#  - implicit methods are not limited;
#  - a pendulum from near the top with verlet at 0.7 s halts when its swing makes the
#    step unstable, not before (every row before is stable, the next step is not);
#  - explicit adaptive methods on a stiff scene (eigenvalues -1, -1e6) warn within
#    the first 100 steps, naming the stiffness ratio 1e6;
#  - --stats reports rho, the stiffness ratio and h*rho against the limit;
#  - --method auto (the default) switches to bsimp on the stiff scene, and keeps
#    dop853's rows on one that is not;
#  - --compare-methods on the stiff scene: an exact reference, auto and bsimp
#    rows that agree with it, rk8pd's rows over budget;
#  - steps held a thousand times below the scene's time scale by the error control
#    (a chain at rest far from the origin) draw one warning; --atol 1e-9 runs it exactly;
#    steps held by the output interval (rows every 1e-4 s) draw none.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
D=tests/stability
for s in oscillator decay saddle pendulum_top; do "$CSFC" $D/$s.csf -o "$T/st_$s.csfb" || bad "$s does not compile"; done
"$CSFC" tests/runtime/stiff_warning.csf -o "$T/st_stiff.csfb" || bad "stiff_warning does not compile"

# run SCENE ARGS...: exit status in $st, stdout in $T/st.csv, stderr in $T/st.err
run() { s=$1; shift; timeout 60 "$CSFVM" "$@" "$T/st_$s.csfb" >"$T/st.csv" 2>"$T/st.err"; st=$?; }
rows() { echo $(($(wc -l <"$T/st.csv") - 1)); }

# 1. the two refusals of the issue, word for word where the numbers are exact
run oscillator --method rk4 --fixed --step 0.5
if [ $st -eq 1 ] && [ "$(rows)" -eq 0 ] && grep -Fxq "error: step 0.5 s is beyond the stability limit of rk4 for this scene (fastest time scale 0.125 s; largest stable step 0.354 s): use --step 0.3 or an adaptive method" "$T/st.err"
then ok; else bad "rk4 --step 0.5: exit $st, $(rows) rows, $(cat "$T/st.err")"; fi
run oscillator --method verlet --tol 1e-3
if [ $st -eq 1 ] && [ "$(rows)" -eq 0 ] && grep -q "^error: step 0.395 s (verlet's step for --tol 0.001) is beyond the stability limit of verlet for this scene (fastest time scale 0.125 s; largest stable step 0.25 s): use --step 0.2, --tol 0.0003 or an adaptive method$" "$T/st.err"
then ok; else bad "verlet --tol 1e-3: exit $st, $(rows) rows, $(cat "$T/st.err")"; fi

# 2. the largest stable step each method reports, against the analytic limit
limit() { # SCENE METHOD EXPECTED: a step of 0.5 s, past every limit here
	run $1 --method $2 --fixed --step 0.5
	got=$(sed -n 's/.*largest stable step \([0-9.e+-]*\) s.*/\1/p' "$T/st.err")
	if [ $st -eq 1 ] && awk -v g="$got" -v e=$3 'BEGIN { d = g / e - 1; exit !(g != "" && d < 0.02 && d > -0.02) }'
	then ok; else bad "$1 $2: largest stable step '$got', expected $3 within 2 % (exit $st: $(head -n 1 "$T/st.err"))"; fi
}
limit oscillator rk4 0.35355
limit oscillator verlet 0.25
limit oscillator rk2 0.21651
limit decay rk4 0.27853
limit decay rk2 0.25127
# a real pair +-2: the decaying member limits rk4 (step 2 s, by 2 s); verlet is not limited
run saddle --method rk4 --fixed --step 2
got=$(sed -n 's/.*largest stable step \([0-9.e+-]*\) s.*/\1/p' "$T/st.err")
if [ $st -eq 1 ] && awk -v g="$got" 'BEGIN { d = g / 1.3926 - 1; exit !(g != "" && d < 0.02 && d > -0.02) }'
then ok; else bad "saddle rk4: largest stable step '$got', expected 1.3926 (exit $st: $(head -n 1 "$T/st.err"))"; fi
run saddle --method verlet --step 2
if [ $st -eq 0 ] && [ "$(rows)" -eq 3 ]; then ok; else bad "saddle verlet --step 2: exit $st, $(head -n 1 "$T/st.err")"; fi

# 3. implicit methods are not limited; stable steps match the exact solution
for m in rk4imp bsimp; do
	run oscillator --method $m --fixed --step 0.5
	if [ $st -eq 0 ] && [ "$(rows)" -eq 21 ]; then ok; else bad "$m --fixed --step 0.5: exit $st, $(head -n 1 "$T/st.err")"; fi
done
exact_osc() { # TOL: every row of x and v within TOL of the exact motion
	awk -F, -v tol=$1 'NR > 1 { ex = 0.1 * cos(8 * $1); ev = -0.8 * sin(8 * $1)
		d = $2 - ex; if (d < 0) d = -d; e = $5 - ev; if (e < 0) e = -e; if (d > tol || e > 8 * tol) bad = 1; n++ }
		END { exit bad || n != 21 }' "$T/st.csv"
}
run oscillator --method rk4 --fixed --step 0.01
if [ $st -eq 0 ] && exact_osc 1e-5; then ok; else bad "oscillator rk4 --step 0.01: not the exact motion (exit $st)"; fi
run oscillator --method verlet
if [ $st -eq 0 ] && exact_osc 1e-6; then ok; else bad "oscillator verlet: not the exact motion (exit $st)"; fi
run decay --method rk4 --fixed --step 0.01
if [ $st -eq 0 ] && awk -F, 'NR > 1 { d = $2 - exp(-10 * $1); if (d < 0) d = -d; if (d > 1e-4 * exp(-10 * $1)) bad = 1; n++ } END { exit bad || n != 11 }' "$T/st.csv"
then ok; else bad "decay rk4 --step 0.01: not the exact solution (exit $st)"; fi

# 4. the pendulum: halts at the first step that ends where h^2 (g/L) cos(theta) >= 4
run pendulum_top --method verlet --step 0.7
th=$(sed -n 's/^error: at t=\([0-9.e+-]*\), step 0.7 s is beyond the stability limit of verlet.*/\1/p' "$T/st.err")
if [ $st -eq 1 ] && [ -n "$th" ] && awk -F, -v th="$th" '
	function a(x) { return -9.80665 * sin(x) }
	NR > 1 { if (cos($2) >= 0.83243) early = 1; t = $1; x = $2; w = $3; n++ }
	END {   # one verlet step of 0.7 s from the last row: the state the guard refused
		h = 0.7; x1 = x + h * w + h * h / 2 * a(x)
		exit !(n >= 2 && !early && cos(x1) >= 0.83243 && (th - t - h) ^ 2 < 1e-18) }' "$T/st.csv"
then ok; else bad "pendulum verlet --step 0.7: exit $st, halt at '$th', $(rows) rows: $(head -n 1 "$T/st.err")"; fi

# 5. stiff: every explicit adaptive method warns within 100 steps, naming the ratio
for m in dop853 dopri5 rk8pd rkf45 rkck; do
	run stiff --method $m
	n=$(sed -n 's/^warning: at t=[^,]*, after \([0-9]*\) steps, the problem looks stiff.*stiffness ratio 1e6).*/\1/p' "$T/st.err")
	if [ $st -eq 0 ] && [ -n "$n" ] && [ "$n" -le 100 ] && grep -q "try --method msbdf or --method bsimp" "$T/st.err"
	then ok; else bad "stiff $m: exit $st, warned after '$n' steps: $(head -n 1 "$T/st.err")"; fi
done
run stiff --method msbdf
if [ $st -eq 0 ] && ! grep -q "looks stiff" "$T/st.err"; then ok; else bad "stiff msbdf: exit $st, $(head -n 1 "$T/st.err")"; fi

# 6. --stats
run oscillator --method rk4 --fixed --step 0.1 --stats
if [ $st -eq 0 ] && grep -q "^stats: stability: rho 8 1/s (fastest time scale 0.125 s, dominant eigenvalues imaginary), stiffness ratio 1; step 0.1 s: h\*rho 0.8 against rk4's limit 2.83 there (largest stable step 0.354 s)" "$T/st.err"
then ok; else bad "oscillator --stats: $(grep stability "$T/st.err")"; fi
run stiff --method dop853 --stats
if [ $st -eq 0 ] && grep -q "^stats: stability: rho 1e+06 1/s (fastest time scale 1e-06 s, dominant eigenvalues real), stiffness ratio 1e6;" "$T/st.err"
then ok; else bad "stiff --stats: $(grep stability "$T/st.err")"; fi

# 7. --method auto, the default: the stiff scene switches to bsimp without a warning and says so in
# --stats; --method auto is the default spelt out; a scene that is not stiff stays on dop853, its rows
# those of --method dop853 byte for byte
run stiff --stats
if [ $st -eq 0 ] && ! grep -q "looks stiff" "$T/st.err" && grep -q "^stats: method auto (dop853 and bsimp), " "$T/st.err" &&
	grep -q "^stats: auto: 1 switch: at t=[0-9.e-]* to bsimp$" "$T/st.err"
then ok; else bad "stiff at the defaults: exit $st, $(cat "$T/st.err")"; fi
cp "$T/st.csv" "$T/st_default.csv"
run stiff --method auto
if [ $st -eq 0 ] && cmp -s "$T/st.csv" "$T/st_default.csv"; then ok; else bad "--method auto is not the default"; fi
run oscillator --stats
cp "$T/st.csv" "$T/st_default.csv"
if [ $st -eq 0 ] && grep -q "^stats: method auto (dop853), " "$T/st.err" && ! grep -q "^stats: auto:" "$T/st.err"
then ok; else bad "oscillator at the defaults: $(cat "$T/st.err")"; fi
run oscillator --method dop853
if [ $st -eq 0 ] && cmp -s "$T/st.csv" "$T/st_default.csv"; then ok; else bad "oscillator: auto's rows are not dop853's"; fi

# 8. --compare-methods on the stiff scene: the reference (auto at 1e-13) is the exact e^-t at the
# last row to 1e-9; auto's and bsimp's rows agree with it, at 1e-10, to 1e-9; rk8pd cannot get on
# and every one of its rows says "over budget" (100 times the reference's evaluations, at least 1e6)
run stiff --method auto --tol 1e-13
ref_ok=$(tail -n 1 "$T/st.csv" | awk -F, '{ e = exp(-$1); d = $2 - e; if (d < 0) d = -d; print (d < 1e-9 * e) }')
run stiff --compare-methods
if [ $st -eq 0 ] && [ "$ref_ok" = 1 ] && grep -q "^reference: auto at tol 1e-13" "$T/st.csv" &&
	awk '($1 == "auto" || $1 == "bsimp") && $2 == "1e-10" { n++; if ($6 + 0 < 1e-9 && $6 ~ /^[0-9.e+-]+$/) good++ }
		$1 == "rk8pd" { r++; if ($6 " " $7 == "over budget") over++ }
		END { exit !(n == 2 && good == 2 && r == 5 && over == 5) }' "$T/st.csv"
then ok; else bad "--compare-methods on the stiff scene: exit $st, reference exact: $ref_ok, $(head -n 4 "$T/st.csv" | tr '\n' ' ')"; fi

# 9. steps held far below the scene's time scale by the error control. A chain at rest 1 km from the
# origin (chain_at_rest.csf): the velocities, which start at 0, are held to the rounding of the spring
# forces that cancel on them; csfvm measures that rounding, raises those values' absolute tolerance to
# it (at most tol times their unit), says so under --stats, naming a mass's velocity along the chain,
# and runs at the defaults without a warning, every row within 1e-9 m of the normal mode's closed form
# (and the same rows without --stats, whose own looks are left out of the schedule of looks);
# with --atol 1e-9 the same. A mass shaken at 10 kHz (forced.csf) needs its short steps: no rounding
# holds them, nothing is raised, and the warning comes, once, naming its velocity; its last row is
# the closed form's to 1e-6 relative.
"$CSFC" $D/chain_at_rest.csf -o "$T/st_chain.csfb" || bad "chain_at_rest does not compile"
chain_ok() {
	awk -F, 'function abs(x) { return x < 0 ? -x : x }
	NR > 1 { w = 40 * sin(3.141592653589793 / 60)
		for (c = 0; c < 2; c++) { j = c ? 59 : 0
			x = 1000 + j * 0.01 + 0.001 * cos(3.141592653589793 * 2 * (2 * j + 1) / 120) * cos(w * $1)
			if (abs($(2 + c) - x) > 1e-9) exit 1 }
		n++ }
	END { exit n != 11 }' "$T/st.csv"
}
run chain --stats
if [ $st -eq 0 ] && ! grep -q '^warning' "$T/st.err" && chain_ok &&
	grep -q '^stats: rounding: at t=[0-9.e-]* the absolute tolerance of 60 values raised to the rounding of their derivatives over the scene.s time scale (node\[[0-9]*\]\.v\.x, whose error held the steps: 1e-12)$' "$T/st.err"
then ok; else bad "chain at rest: exit $st, $(grep -v '^stats: [ms]' "$T/st.err" | head -n 2)"; fi
# --stats's own looks do not steer the run: the same rows without it
cp "$T/st.csv" "$T/st_chain_stats.csv"
run chain
if [ $st -eq 0 ] && cmp -s "$T/st.csv" "$T/st_chain_stats.csv"
then ok; else bad "chain at rest: other rows with --stats than without"; fi
run chain --atol 1e-9
if [ $st -eq 0 ] && [ ! -s "$T/st.err" ] && chain_ok
then ok; else bad "chain at rest --atol 1e-9: exit $st, $(head -n 1 "$T/st.err")"; fi
"$CSFC" $D/forced.csf -o "$T/st_forced.csfb" || bad "forced does not compile"
run forced --stats
n=$(sed -n 's/^warning: at t=[^,]*, after \([0-9]*\) steps, the error control holds dop853 to steps of .* (the error of b\.v\.x holds them), .* times shorter than the fastest time scale of the scene (1 s), and some .* more are to go: .*/\1/p' "$T/st.err")
if [ $st -eq 0 ] && [ -n "$n" ] && [ "$n" -lt 10000 ] && [ "$(grep -c '^warning' "$T/st.err")" -eq 1 ] &&
	! grep -q '^stats: rounding' "$T/st.err" &&
	tail -n 1 "$T/st.csv" | awk -F, '{ w = 2 * 3.141592653589793 * 1e4; x = 1e-3 * w * sin(2) / (w * w - 1)
		d = $2 - x; if (d < 0) d = -d; exit !($1 == 2 && d <= 1e-6 * x) }'
then ok; else bad "forced at 10 kHz: exit $st, warned after '$n' steps, $(head -n 1 "$T/st.err"), last row $(tail -n 1 "$T/st.csv")"; fi
# a free mass shaken the same way: no time scale of its own (rho 0), so the steps are compared with the run
"$CSFC" $D/forced_free.csf -o "$T/st_forced_free.csfb" || bad "forced_free does not compile"
run forced_free
if [ $st -eq 0 ] && [ "$(grep -c '^warning' "$T/st.err")" -eq 1 ] &&
	grep -q '^warning: at t=[^,]*, after [0-9]* steps, the error control holds dop853 to steps of .* (the error of b\.v\.x holds them), .* times shorter than the run, as the scene.s dynamics have no shorter time scale (2 s), and some .* more are to go: ' "$T/st.err" &&
	tail -n 1 "$T/st.csv" | awk -F, '{ x = 2e-3 / (2 * 3.141592653589793 * 1e4)
		d = $2 - x; if (d < 0) d = -d; exit !($1 == 2 && d <= 1e-6 * x) }'
then ok; else bad "free mass forced at 10 kHz: exit $st, $(head -n 1 "$T/st.err"), last row $(tail -n 1 "$T/st.csv")"; fi
# ... and steps held by the output interval are not: the parachute (a when block, so steps of at
# most by) with rows every 1e-4 s for 15 s, 150001 rows, no warning
sed 's/^inc t till 60 s by 0.5 s/inc t till 15 s by 0.0001 s/' examples/parachute.csf >"$T/chute.csf"
"$CSFC" "$T/chute.csf" -o "$T/st_chute.csfb" || bad "the parachute does not compile"
run chute
if [ $st -eq 0 ] && [ ! -s "$T/st.err" ] && [ "$(rows)" -eq 150001 ]
then ok; else bad "parachute, rows every 1e-4 s: exit $st, $(rows) rows, $(head -n 1 "$T/st.err")"; fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
