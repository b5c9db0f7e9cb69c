#!/bin/sh
# tests/sweep/check.sh CSFC CSFVM DIR BUILD - parameters and sweeps:
#  - -D on the launch angle and speed of a projectile with drag (launch.csf),
#    every row against the closed form (launch.awk); -D with units (deg,
#    km/h, g/s^2, g, a vector), in mks and cgs, against the closed form;
#  - a wrong unit, an unknown name, a value folded at compile time or
#    computed by a rule: exit 2 naming it (and the expected unit);
#  - a sweep of 100 variants: every row against the closed form; -j 1 and
#    -j 2 byte-identical; every variant byte-identical to its -D run;
#  - --out-dir, --sweep-file, --sweep-summary, a failing variant (exit 1,
#    the others written);
#  - --sweep-binary: the same rows as doubles, a failing variant's and a summary's too;
#  - a generated program (csfc --emit-c) takes -D and --sweep and writes
#    csfvm's bytes;
#  - under mpirun -np 3 (BUILD/csfvm-mpi, where Open MPI is installed; SKIP
#    otherwise) the sweep's bytes are the local run's;
#  - a wide model (120 columns, whose own runs write through the row thread):
#    each variant's rows are its -D run's and follow x = A cos(w t).
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3 B=$4
HERE=$(dirname "$0")
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
L=$T/launch.csfb S=$T/spring.csfb F=$T/folded.csfb
"$CSFC" "$HERE/launch.csf" -o "$L" && "$CSFC" "$HERE/spring.csf" -o "$S" && "$CSFC" "$HERE/folded.csf" -o "$F" &&
	"$CSFC" --units cgs "$HERE/spring.csf" -o "$T/spring-cgs.csfb" || { echo "FAIL: the test scenes do not compile"; exit 1; }

# -D: the closed form for a few angles and speeds, given with units
dcheck() { # theta(rad) v0(m/s) x0 z0 -D...
	th=$1 v=$2 x0=$3 z0=$4
	shift 4
	if ! "$CSFVM" "$@" "$L" >"$T/d.csv" 2>"$T/d.err"; then bad "-D $*: $(head -n 1 "$T/d.err")"; return; fi
	if awk -v lead=0 -v theta="$th" -v v0="$v" -v x0="$x0" -v z0="$z0" -v expect=21 -f "$HERE/launch.awk" "$T/d.csv" >"$T/d.chk"; then ok
	else bad "-D $*: $(head -n 1 "$T/d.chk")"; fi
}
dcheck 0.785398163397448 20 0 0
dcheck 0.523598775598299 10 0 0 -D theta=30deg -D 'v0=36 km/h'
dcheck 1.2 7.5 0 0 -D theta=1.2 -D v0=7.5
dcheck 1.0471975511966 30 0 0 -D 'theta=60 deg' -D v0=30m/s
dcheck 0.785398163397448 20 1 2 -D 'ball.pos=(1, 0, 2) m'
dcheck 0.785398163397448 20 1 2 -D 'ball.pos=(100 cm, 0, 2000 mm)'
dcheck 0.785398163397448 20 0.3048 0 -D 'ball.pos=(1, 0, 0) ft'
dcheck 0.785398163397448 20 0 0 -D 'ball.m=500 g' -D 'ball.b=100 g/s'
# one component of a vector alone: NAME.x, .y, .z
dcheck 0.785398163397448 20 0 2 -D ball.pos.z=2
dcheck 0.785398163397448 20 1 2 -D 'ball.pos.x=100 cm' -D 'ball.pos.z = 2 m'
# a rate in 1/s, as the header prints it: phi' = Omega, phi = Omega t
printf 'global Omega = 1 1/s\nobject b: phi = 0\nrule: phi'"'"' = Omega\ninc t till 2 s by 1 s watch b.phi\n' >"$T/omega.csf"
if "$CSFC" "$T/omega.csf" -o "$T/omega.csfb" && "$CSFVM" -D 'Omega=1.8 1/s' "$T/omega.csfb" >"$T/o.csv" &&
	awk -F, 'NR > 1 { d = $2 - 1.8 * $1; if (d < 0) d = -d; if (d > 1e-12) exit 1 } END { if (NR != 4) exit 1 }' "$T/o.csv"; then ok
else bad "-D 'Omega=1.8 1/s': $(cat "$T/o.csv" | tr '\n' ' ')"; fi
# a spring: k = 2000 g/s^2 = 2 N/m, m = 500 g: x = cos(2 t); in cgs x is in cm
spring() { # what file scale -D...
	what=$1 file=$2 scale=$3
	shift 3
	if "$CSFVM" "$@" "$file" >"$T/s.csv" 2>"$T/s.err" &&
		awk -F, -v s="$scale" 'NR > 1 { e = s * cos(2 * $1); d = $2 - e; if (d < 0) d = -d; if (d > 1e-6 * s) { print "t " $1 ": " $2 ", expected " e; exit 1 } n++ }
			END { if (n != 11) { print n " rows"; exit 1 } }' "$T/s.csv" >"$T/s.chk"; then ok
	else bad "spring $what: $(cat "$T/s.err" "$T/s.chk" 2>/dev/null | head -n 1)"; fi
}
spring mks "$S" 1 -D 'k=2000 g/s^2' -D 'ball.m=500 g'
spring cgs "$T/spring-cgs.csfb" 100 -D 'k=2000 g/s^2' -D 'ball.m=500 g'
spring "cgs, N/m and kg" "$T/spring-cgs.csfb" 100 -D 'k=2 N/m' -D 'ball.m=0.5 kg'
spring "cgs, bare numbers in g and g/s^2" "$T/spring-cgs.csfb" 100 -D k=2000 -D ball.m=500
spring "--opt=value, -DNAME" "$S" 1 -Dk=2 --method=dopri5 --tol=1e-10 -D ball.m=0.5

# errors: exit 2 naming the value, the expected unit, or why it cannot be set
derr() { # file pattern -D...
	file=$1 pat=$2
	shift 2
	"$CSFVM" "$@" "$file" >"$T/e.out" 2>"$T/e.err"
	st=$?
	if [ $st -eq 2 ] && grep -q -- "$pat" "$T/e.err" && [ ! -s "$T/e.out" ]; then ok
	else bad "$*: exit $st, stderr '$(head -n 1 "$T/e.err")', expected exit 2 and '$pat'"; fi
}
derr "$L" "expected unit m/s" -D 'v0=3 kg'
derr "$L" "v0 is in m/s" -D 'v0=3 m'
derr "$L" "expected a bare number" -D 'theta=1 m'
derr "$L" "unknown name 'nosuch'" -D nosuch=1
derr "$L" "object 'ball' has no property 'zz'" -D ball.zz=1
derr "$L" "ball.pos is a vector" -D ball.pos=3
derr "$L" "cannot read" -D 'v0=fast'
derr "$L" "unknown unit" -D 'v0=3 furlong'
derr "$S" "expected unit kg/s^2" -D 'k=3 N'
derr "$F" "k cannot be overridden: its value is folded at compile time into the value of k2" -D k=1
derr "$F" "k2 cannot be overridden: its value is computed at compile time from k" -D k2=1
derr "$F" "ball.q cannot be overridden: its value is computed at compile time from k2" -D ball.q=1
derr "$F" "ball.a cannot be overridden: a rule computes it" -D 'ball.a=1 m/s^2'
derr "$L" "v0 is swept twice" --sweep v0=1:2:2 --sweep v0=1:2:2
derr "$L" "ball.pos.z is in m, '1 s' is not" -D 'ball.pos.z=1 s'
derr "$L" "ball.pos.z is a scalar" -D 'ball.pos.z=(1, 2, 3) m'
# a misspelt name: the nearest one suggested, as csfc does
derr "$L" "no global of that name; did you mean 'theta'?" -D thetta=1
derr "$L" "no object 'bal'; did you mean 'ball'?" -D bal.m=1
derr "$L" "no property 'poss.z' that the run uses; did you mean 'pos'?" -D ball.poss.z=1
derr "$L" "ball.pos is a vector" --sweep ball.pos=1:2:2
derr "$L" "expected NAME=FROM:TO:COUNT" --sweep v0=1:2
derr "$L" "not a watched column" --sweep v0=1:2:2 --sweep-summary 'max(ball.v.z)'
derr "$L" "need --sweep" --sweep-summary 'max(ball.pos.z)'

# a sweep of 100 variants: header, the closed form, -j 1 = -j 2, each variant = its -D run
SW="--sweep theta=0:90:10deg --sweep v0=5:50:10"
# shellcheck disable=SC2086 # SW holds the sweep options
"$CSFVM" $SW -j 1 "$L" >"$T/j1.csv" 2>"$T/j1.err" && "$CSFVM" $SW -j 2 "$L" >"$T/j2.csv" 2>"$T/j2.err" || bad "sweep: $(cat "$T/j1.err" "$T/j2.err" | head -n 1)"
if [ "$(head -n 1 "$T/j1.csv")" = "theta,v0 [m/s],t,ball.pos.x [m],ball.pos.y [m],ball.pos.z [m]" ]; then ok
else bad "sweep header: $(head -n 1 "$T/j1.csv")"; fi
if awk -v lead=2 -v expect=2100 -f "$HERE/launch.awk" "$T/j1.csv" >"$T/j.chk"; then ok; else bad "sweep, closed form: $(head -n 1 "$T/j.chk")"; fi
if cmp -s "$T/j1.csv" "$T/j2.csv"; then ok; else bad "sweep: -j 1 and -j 2 differ"; fi
# shellcheck disable=SC2086
if "$CSFVM" $SW "$L" | cmp -s - "$T/j1.csv"; then ok; else bad "sweep: the default -j differs from -j 1"; fi
# every variant alone: -D NAME=PRINTED with the printed values
awk -F, 'NR > 1 && $3 == 0 { print $1 " " $2 }' "$T/j1.csv" >"$T/variants"
n=0 same=0
while read -r th v; do
	n=$((n + 1))
	"$CSFVM" -D "theta=$th" -D "v0=$v" "$L" | tail -n +2 >"$T/alone.csv"
	awk -F, -v th="$th" -v v="$v" 'NR > 1 && $1 == th && $2 == v { sub(/^[^,]*,[^,]*,/, ""); print }' "$T/j1.csv" >"$T/part.csv"
	awk -F, -v th="$th" -v v="$v" 'NR > 1 && $1 == th && $2 == v' "$T/j1.csv" | cut -d, -f1,2 | sort -u | grep -qx "$th,$v" &&
		cmp -s "$T/alone.csv" "$T/part.csv" && same=$((same + 1))
done <"$T/variants"
if [ $n -eq 100 ] && [ $same -eq 100 ]; then ok; else bad "sweep: $same of $n variants equal their -D run (100 expected)"; fi

# --out-dir: one file per run, each its -D run's bytes; the index
# shellcheck disable=SC2086
if "$CSFVM" $SW -j 2 --out-dir "$T/runs" "$L" >"$T/od.out" 2>"$T/od.err" && [ ! -s "$T/od.out" ] &&
	[ "$(wc -l <"$T/runs/index.csv")" -eq 101 ] && [ "$(head -n 1 "$T/runs/index.csv")" = "run,file,status,theta,v0 [m/s]" ] &&
	line=$(sed -n '38p' "$T/runs/index.csv") && th=$(echo "$line" | cut -d, -f4) && v=$(echo "$line" | cut -d, -f5) &&
	"$CSFVM" -D "theta=$th" -D "v0=$v" "$L" | cmp -s - "$T/runs/run-00037.csv" &&
	[ "$(echo "$line" | cut -d, -f1-3)" = "37,run-00037.csv,0" ]; then ok
else bad "--out-dir: $(head -n 1 "$T/od.err")"; fi

# --sweep-file: rows with units, crossed with a --sweep
printf 'theta, v0\n30 deg, 36 km/h\n# a comment\n1.2, 7.5 m/s\n' >"$T/params.csv"
if "$CSFVM" --sweep-file "$T/params.csv" --sweep 'ball.m=0.5:0.5:1 kg' "$L" >"$T/sf.csv" 2>"$T/sf.err" &&
	[ "$(head -n 1 "$T/sf.csv")" = "theta,v0 [m/s],ball.m [kg],t,ball.pos.x [m],ball.pos.y [m],ball.pos.z [m]" ] &&
	awk -v lead=3 -v expect=42 -f "$HERE/launch.awk" "$T/sf.csv" >"$T/sf.chk" &&
	[ "$(awk -F, 'NR == 2 { print $1 "," $2 }' "$T/sf.csv")" = "0.5235987755982988,10" ]; then ok
else bad "--sweep-file: $(cat "$T/sf.err" "$T/sf.chk" 2>/dev/null | head -n 1)"; fi

# --sweep-file whose header is a sweep's own leading columns (NAME [UNIT]): the same variants,
# byte for byte; a header unit other than the parameter's applies to the bare values
"$CSFVM" --sweep 'v0=10:20:3' --sweep 'ball.m=0.5:1:2' "$L" >"$T/sw.csv" 2>/dev/null
if cut -d, -f1,2 "$T/sw.csv" | uniq >"$T/back.csv" && [ "$(head -n 1 "$T/back.csv")" = "v0 [m/s],ball.m [kg]" ] &&
	"$CSFVM" --sweep-file "$T/back.csv" "$L" 2>"$T/sf.err" | cmp -s - "$T/sw.csv"; then ok
else bad "--sweep-file of a sweep's header: $(head -n 1 "$T/sf.err")"; fi
printf 'v0 [km/h],ball.m [g]\n36,500\n54,500\n72, 0.5 kg\n' >"$T/kmh.csv"
if "$CSFVM" --sweep-file "$T/kmh.csv" "$L" 2>"$T/sf.err" | awk -F, 'NR > 1 { print $1 "," $2 }' | uniq >"$T/kmh.out" &&
	[ "$(cat "$T/kmh.out" | tr '\n' ' ')" = "10,0.5 15,0.5 20,0.5 " ]; then ok
else bad "--sweep-file with units in the header: $(cat "$T/sf.err" "$T/kmh.out" | head -n 2)"; fi
printf 'v0 [m/s\n1\n' >"$T/bad.csv"
derr "$L" "header 'v0 \[m/s': expected NAME or NAME \[UNIT\]" --sweep-file "$T/bad.csv"

# --sweep-summary: one row per variant, the max and final of the rows
# shellcheck disable=SC2086
if "$CSFVM" $SW --sweep-summary 'max(ball.pos.z), final(ball.pos.x),min(t)' "$L" >"$T/sum.csv" 2>"$T/sum.err" &&
	[ "$(head -n 1 "$T/sum.csv")" = "theta,v0 [m/s],max(ball.pos.z) [m],final(ball.pos.x) [m],min(t)" ] &&
	[ "$(wc -l <"$T/sum.csv")" -eq 101 ] &&
	awk -F, 'NR == FNR { if (FNR > 1) { key = $1 "," $2; if (!(key in mz) || $6 > mz[key]) mz[key] = $6; fx[key] = $4 } next }
		FNR > 1 { key = $1 "," $2; if ($3 != mz[key] || $4 != fx[key] || $5 != 0) { print "summary of " key ": " $0; exit 1 } n++ }
		END { if (n != 100) exit 1 }' "$T/j1.csv" "$T/sum.csv" >"$T/sum.chk"; then ok
else bad "--sweep-summary: $(cat "$T/sum.err" "$T/sum.chk" 2>/dev/null | head -n 1)"; fi

# --sweep-summary over a window of time, exact: x = u t (ramp.csf) gives mean = u (a + b)/2 over
# [a, b], the trapezoid rule's rms = u sqrt((b^3 - a^3)/(3 (b - a)) + h^2/6) with rows h = 0.5 s apart
R=$T/ramp.csfb
if "$CSFC" "$HERE/ramp.csf" -o "$R" &&
	"$CSFVM" --sweep u=1:3:3 --sweep-summary 'mean(p.x) from 2 s to 6 s, rms(p.x) from 2 s to 6000 ms, max(p.x) from 1 s to 3 s, min(p.x) from 0.05 min, final(p.x) to 4 s, mean(p.x)' "$R" >"$T/win.csv" 2>"$T/win.err" &&
	[ "$(head -n 1 "$T/win.csv")" = "u [m/s],mean(p.x) from 2 s to 6 s [m],rms(p.x) from 2 s to 6000 ms [m],max(p.x) from 1 s to 3 s [m],min(p.x) from 0.05 min [m],final(p.x) to 4 s [m],mean(p.x) [m]" ] &&
	awk -F, 'function bad(i, want) { d = $i - want; if (d < 0) d = -d; if (d > 1e-12 * want) { print "row " NR " column " i ": " $i ", exact " want; exit 1 } }
		NR > 1 { u = $1; bad(2, 4 * u); bad(3, u * sqrt(208 / 12 + 0.25 / 6)); bad(4, 3 * u); bad(5, 3 * u); bad(6, 4 * u); bad(7, 5 * u); n++ }
		END { if (n != 3) exit 1 }' "$T/win.csv" >"$T/win.chk"; then ok
else bad "--sweep-summary with a window: $(cat "$T/win.err" "$T/win.chk" 2>/dev/null | head -n 1)"; fi
# a resonance curve: the steady amplitude A of a driven oscillator (driven.csf) is max(x) from 60 s
# (to the rows' sampling, 1e-4) and sqrt(2) rms(x) over 20 s of whole periods (1e-6), with mean 0;
# the whole run's max, which the start-up transient sets, misses A by more than 1 % at some W
if "$CSFC" "$HERE/driven.csf" -o "$T/driven.csfb" &&
	"$CSFVM" --sweep 'W=1.5707963267948966:2.199114857512855:3' --sweep-summary \
		'max(osc.x) from 60 s, rms(osc.x) from 60 s to 80 s, mean(osc.x) from 60 s to 80 s, max(osc.x)' \
		"$T/driven.csfb" >"$T/res.csv" 2>"$T/res.err" &&
	awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { W = $1; A = 1 / sqrt((4 - W * W)^2 + (0.5 * W)^2)
			if (abs($2 / A - 1) > 1e-4 || abs($3 * sqrt(2) / A - 1) > 1e-6 || abs($4) > 1e-6 * A) { print "W=" W ": A=" A ", got " $0; exit 1 }
			if (abs($5 / A - 1) > 0.01) far++; n++ }
		END { if (n != 3 || !far) { print n " rows, " far + 0 " whole-run maxima off"; exit 1 } }' "$T/res.csv" >"$T/res.chk"; then ok
else bad "--sweep-summary, a resonance curve: $(cat "$T/res.err" "$T/res.chk" 2>/dev/null | head -n 1)"; fi
# a column named as the watch list names it (x: p.x, the one column ending so), the header the full name
if "$CSFVM" --sweep u=2:2:1 --sweep-summary 'mean(x) to 4 s' "$R" >"$T/sfx.csv" 2>"$T/sfx.err" &&
	[ "$(head -n 1 "$T/sfx.csv")" = "u [m/s],mean(p.x) to 4 s [m]" ] &&
	awk -F, 'NR == 2 { d = $2 - 4; exit !(d < 1e-12 && d > -1e-12) }' "$T/sfx.csv"; then ok
else bad "--sweep-summary 'mean(x)': $(cat "$T/sfx.err" "$T/sfx.csv" | head -n 2)"; fi
derr "$R" "did you mean 'p.x'?" --sweep u=1:2:2 --sweep-summary 'max(p.xx)'
derr "$R" "not a unit of time" --sweep u=1:2:2 --sweep-summary 'max(p.x) from 5 m'
derr "$R" "ends before it starts" --sweep u=1:2:2 --sweep-summary 'max(p.x) from 5 s to 2 s'
derr "$R" "starts after the run ends" --sweep u=1:2:2 --sweep-summary 'max(p.x) from 20 s'
derr "$R" "expected 'from TIME'" --sweep u=1:2:2 --sweep-summary 'max(p.x) form 5 s'

# a failing variant: reported with its run number, the others written, exit 1
"$CSFVM" --sweep 'ball.x=1:2:3 m' -j 2 "$F" >"$T/fail.csv" 2>"$T/fail.err"
st=$?
if [ $st -eq 1 ] && grep -q "^csfvm: run 2 (ball.x=1.5): .*assertion failed" "$T/fail.err" && grep -q "^csfvm: run 3 (ball.x=2): " "$T/fail.err" &&
	[ "$(grep -c '^1,' "$T/fail.csv")" -eq 3 ]; then ok
else bad "failing variant: exit $st, $(head -n 1 "$T/fail.err")"; fi

# --sweep-binary: the CSV's header line, then the rows as doubles, the same rows as the CSV (the values
# to 1e-15 here, read back by od; bit for bit in tests/python), with -j 2, a failing variant (its rows
# up to the failure) and a summary; exit 1 as the CSV's sweep; usage errors
bincheck() { # what CSV OPTIONS...: the binary sweep of OPTIONS has CSV's header and values
	what=$1 csv=$2
	shift 2
	"$CSFVM" --sweep-binary "$@" >"$T/b.bin" 2>"$T/b.err"
	bst=$?
	n=$(head -n 1 "$csv" | awk -F, '{ print NF }')
	hl=$(head -n 1 "$T/b.bin" | wc -c)
	if [ "$(head -n 1 "$T/b.bin")" = "$(head -n 1 "$csv")" ] &&
		tail -c +$((hl + 1)) "$T/b.bin" | od -An -v -tf8 -w8 | awk -v n="$n" '{ printf "%s%s", $1, ++k % n ? "," : "\n" }' >"$T/b.txt" &&
		awk -F, 'NR == FNR { if (FNR > 1) row[FNR - 1] = $0; next }
			{ m = split(row[FNR], w, ","); if (m != NF) { print "row " FNR ": " NF " values, the CSV " m; exit 1 }
			  for (i = 1; i <= NF; i++) { d = $i - w[i]; if (d < 0) d = -d; a = w[i] < 0 ? -w[i] : w[i]
				if (d > 1e-15 * a) { print "row " FNR " value " i ": " $i ", the CSV " w[i]; exit 1 } } }' \
			"$csv" "$T/b.txt" >"$T/b.chk" && [ "$(wc -l <"$T/b.txt")" -eq $(($(wc -l <"$csv") - 1)) ]; then
		echo "$bst"
	else
		echo "bad: $(cat "$T/b.err" "$T/b.chk" 2>/dev/null | head -n 1)"
	fi
}
# shellcheck disable=SC2086
r=$(bincheck "100 variants" "$T/j1.csv" $SW -j 2 "$L")
if [ "$r" = 0 ]; then ok; else bad "--sweep-binary of 100 variants: $r"; fi
r=$(bincheck "a failing variant" "$T/fail.csv" --sweep 'ball.x=1:2:3 m' -j 2 "$F")
if [ "$r" = 1 ]; then ok; else bad "--sweep-binary with a failing variant: $r"; fi
r=$(bincheck "a summary" "$T/win.csv" --sweep u=1:3:3 --sweep-summary 'mean(p.x) from 2 s to 6 s, rms(p.x) from 2 s to 6000 ms, max(p.x) from 1 s to 3 s, min(p.x) from 0.05 min, final(p.x) to 4 s, mean(p.x)' "$R")
if [ "$r" = 0 ]; then ok; else bad "--sweep-binary with --sweep-summary: $r"; fi
"$CSFVM" --sweep-binary "$L" >/dev/null 2>"$T/b.err"
st=$?
"$CSFVM" --sweep-binary --sweep v0=1:2:2 --out-dir "$T/bdir" "$L" >/dev/null 2>"$T/b2.err"
if [ $st -eq 2 ] && grep -q "need --sweep or --sweep-file" "$T/b.err" &&
	grep -q "csfvm: --sweep-binary writes one stream, not --out-dir's files" "$T/b2.err" && [ ! -e "$T/bdir" ]; then ok
else bad "--sweep-binary's usage errors: $(cat "$T/b.err" "$T/b2.err" | head -n 2)"; fi

# a generated program: -D and --sweep as csfvm
if timeout 120 "$CSFC" --emit-c "$HERE/launch.csf" -o "$T/launch" 2>"$T/ec.err"; then
	# shellcheck disable=SC2086
	if timeout 60 "$T/launch" -D theta=30deg -D 'v0=36 km/h' >"$T/g1.csv" && "$CSFVM" -D theta=30deg -D 'v0=36 km/h' "$L" | cmp -s - "$T/g1.csv" &&
		timeout 60 "$T/launch" $SW -j 2 | cmp -s - "$T/j1.csv"; then ok
	else bad "generated program: -D or --sweep differs from csfvm"; fi
	timeout 60 "$T/launch" -D 'v0=1 kg' >/dev/null 2>"$T/ge.err"
	st=$?
	if [ $st -eq 2 ] && grep -q "expected unit m/s" "$T/ge.err"; then ok; else bad "generated program: a wrong unit: exit $st"; fi
else
	bad "csfc --emit-c launch.csf: $(head -n 1 "$T/ec.err")"
fi

# MPI: the same sweep under mpirun -np 3 (rank 0 gathers in order)
if [ -x "$B/csfvm-mpi" ] && command -v mpirun >/dev/null 2>&1; then
	# shellcheck disable=SC2086
	if ASAN_OPTIONS=detect_leaks=0 timeout 120 mpirun --allow-run-as-root --oversubscribe -np 3 "$B/csfvm-mpi" $SW "$L" >"$T/mpi.csv" 2>"$T/mpi.err" &&
		cmp -s "$T/mpi.csv" "$T/j1.csv"; then ok
	else bad "mpirun -np 3: the output differs from the local run: $(head -n 2 "$T/mpi.err")"; fi
else
	echo "SKIP: MPI sweep (no $B/csfvm-mpi or mpirun: make deps-mpi)"
fi
# a wide model (120 columns: its rows written by the row thread in a run of its own, and into
# memory in a sweep's variant): each variant's rows are those of its -D run, x = A cos(w t)
{ echo "using mechanics/mass_point"; echo "global k = 16 N/m"
  echo "object b[0..19]: mass_point"; echo "object b[i]: m = 0.25 kg"; echo "object b[i]: pos = (0.1, 0, i) m"
  echo "rule F: S = (pos - (0, 0, pos.z)).mul(-k)"; echo "using mechanics/rules"
  echo "inc t till 2 s by 0.01 s watch pos, v"; } > "$T/wide.csf"
"$CSFC" "$T/wide.csf" -o "$T/wide.csfb"
if "$CSFVM" --sweep 'k=4:16:3 N/m' -j 2 "$T/wide.csfb" > "$T/wide_sweep.csv" 2> "$T/wide.err"; then
	good=1
	for kv in 4 10 16; do
		"$CSFVM" -D "k=$kv N/m" "$T/wide.csfb" | tail -n +2 > "$T/wide_d.csv"
		awk -F, -v k="$kv" 'NR > 1 && $1 == k { sub(/^[^,]*,/, ""); print }' "$T/wide_sweep.csv" | cmp -s - "$T/wide_d.csv" || good=0
		awk -F, -v k="$kv" 'function abs(x) { return x < 0 ? -x : x }
			{ w = sqrt(k / 0.25); if (NF != 121 || abs($2 - 0.1 * cos(w * $1)) > 1e-9) exit 1; n++ } END { exit n != 201 }' "$T/wide_d.csv" || good=0
	done
	if [ $good -eq 1 ]; then ok; else bad "a sweep of a wide model: a variant's rows are not its -D run's, or not A cos(w t)"; fi
else
	bad "a sweep of a wide model: exit $?, $(head -n 1 "$T/wide.err")"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
