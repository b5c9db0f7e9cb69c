#!/bin/sh
# tests/when/check.sh CSFC CSFVM DIR - discrete events (`when` blocks, latched values,
# --rows-at-events) against exact answers, on the scenes of examples/ and tests/e2e/ whose
# rows the exact suite checks (their closed forms are in their headers):
#  - the parachute (examples/parachute.csf) opens once: one event, at the instant the diver
#    passes 1000 m (t1 from the closed form, by Newton's method, to 1e-12 s; z to 1e-9 m),
#    open 0 just before and 1 just after; with -D diver.open=1 it is open from the start and
#    the descent is the closed form with the larger drag all along; with -D diver.b_open=0
#    the opening changes nothing: free fall with the small drag;
#  - the two-stage rocket (tests/e2e/when_staging.csf): one event, at t = 60 s, where the mass
#    drops by 3000 kg and the velocity does not change; each stage's velocity gain is the
#    rocket equation's, u ln(m_start/m_end);
#  - the bouncing ball's counter (tests/e2e/when_bounces.csf): --rows-at-events gives a row
#    before and after each of its N impacts (N from the closed form), counting 0..N; the first
#    at t1 = sqrt(2 h0/g) and each one at the previous one's time plus the flight its rebound
#    speed gives (2 w/g) to 1e-13 s, every one within k * 1e-13 s of the closed-form T_k;
#  - the kick (tests/e2e/when_kick.csf): the rows at t1 before and after differ by dv exactly;
#  - --rows-at-events leaves the other rows as they were (byte for byte, the event column
#    aside), and csfvm and the generated program write the same bytes with it;
#  - --rows-at-events is refused with -o FILE.h5 and with a sweep (exit 2);
#  - csfc --explain says what a when block does, and that the property is latched.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
TOP=$(cd "$(dirname "$0")/../.." && pwd)
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { if "$@"; then ok; else bad "$*"; fi; }
comp() { # comp NAME SCENE: $T/NAME.csfb
	"$CSFC" "$2" -o "$T/$1.csfb" 2>"$T/$1.err" && return 0
	bad "$1: does not compile: $(head -n 1 "$T/$1.err")"
	return 1
}
# events FILE: the rows of FILE whose last column (event) is not 0, header first
events() { awk -F, 'NR == 1 || $NF != 0' "$1"; }
# plain FILE: FILE without its last column and without the event rows
plain() { awk -F, 'NR == 1 || $NF == 0 { sub(/,[^,]*$/, ""); print }' "$1"; }

# the parachute
if comp chute "$TOP/examples/parachute.csf"; then
	"$CSFVM" --rows-at-events "$T/chute.csfb" >"$T/chute.csv" && "$CSFVM" "$T/chute.csfb" >"$T/chute0.csv"
	check test "$(head -n 1 "$T/chute.csv")" = "t,diver.pos.z [m],diver.v.z [m/s],diver.open,event"
	plain "$T/chute.csv" >"$T/chute1.csv"
	check cmp -s "$T/chute0.csv" "$T/chute1.csv"
	events "$T/chute.csv" >"$T/chute.ev"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		function z(t) { return 1500 + vi * t - vi * (1 - exp(-k * t)) / k }
		function v(t) { return vi * (1 - exp(-k * t)) }
		BEGIN { g = 9.80665; k = 0.2; vi = -g * 80 / 16; t1 = 10; for (i = 0; i < 60; i++) t1 -= (z(t1) - 1000) / v(t1) }
		NR == 1 { next }
		{ n++; if (abs($1 - t1) > 1e-12 || abs($2 - 1000) > 1e-9 || $4 != (n == 2) || $5 != (n == 1 ? -1 : 1)) {
			printf "FAIL: chute event row %d: %s (opens at t1 = %.17g s at 1000 m)\n", n, $0, t1; exit 1 } }
		END { if (n != 2) { print "FAIL: " n " event rows, not 2: it opens once"; exit 1 } }' "$T/chute.ev"
	# open from the start: the larger drag all along, k = 5.2 /s
	"$CSFVM" -D diver.open=1 "$T/chute.csfb" >"$T/open.csv"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { g = 9.80665; k = 5.2; vi = -g * 80 / 416; t = $1
			z = 1500 + vi * t - vi * (1 - exp(-k * t)) / k; v = vi * (1 - exp(-k * t))
			if (abs($2 - z) > 1e-6 || abs($3 - v) > 1e-6 || $4 != 1) { print "FAIL: -D diver.open=1: " $0; exit 1 } n++ }
		END { exit n != 121 }' "$T/open.csv"
	# an opening that changes nothing: free fall with the small drag, k = 0.2 /s, opened at 1000 m
	"$CSFVM" -D diver.b_open=0 "$T/chute.csfb" >"$T/none.csv"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { g = 9.80665; k = 0.2; vi = -g * 80 / 16; t = $1
			z = 1500 + vi * t - vi * (1 - exp(-k * t)) / k; v = vi * (1 - exp(-k * t))
			if (abs($2 - z) > 1e-6 * abs(z) || abs($3 - v) > 1e-6 * abs(v) || $4 != (z < 1000)) { print "FAIL: -D diver.b_open=0: " $0; exit 1 } n++ }
		END { exit n != 121 }' "$T/none.csv"
	"$CSFC" --explain "$TOP/examples/parachute.csf" >"$T/chute.explain" 2>/dev/null
	check grep -q "when pos.z < 1000 m$" "$T/chute.explain"
	check grep -q "sets diver.open (latched: it keeps its value between events)" "$T/chute.explain"
	check grep -q "open (latched, when block line" "$T/chute.explain"
	# the generated program writes the same bytes, with the rows at events too
	if "$CSFC" --emit-c "$TOP/examples/parachute.csf" -o "$T/chute" 2>"$T/ec.err"; then
		"$T/chute" --rows-at-events >"$T/chute_c.csv" && check cmp -s "$T/chute.csv" "$T/chute_c.csv"
	else
		bad "csfc --emit-c parachute.csf: $(head -n 1 "$T/ec.err")"
	fi
	"$CSFVM" --rows-at-events -o "$T/x.h5" "$T/chute.csfb" >/dev/null 2>"$T/h5.err"
	check test $? = 2
	check grep -q "rows-at-events adds rows to the CSV of one run" "$T/h5.err"
	"$CSFVM" --rows-at-events --sweep 'diver.m=70:90:3' "$T/chute.csfb" >/dev/null 2>"$T/sw.err"
	check test $? = 2
fi

# the two-stage rocket: the rocket equation for each stage
if comp stage "$TOP/tests/e2e/when_staging.csf"; then
	"$CSFVM" --rows-at-events "$T/stage.csfb" >"$T/stage.csv"
	events "$T/stage.csv" >"$T/stage.ev"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR == 1 { next }
		{ n++; t[n] = $1; v[n] = $2; m[n] = $3 }
		END { u = 2000
			if (n != 2 || abs(t[1] - 60) > 1e-12 || t[2] != t[1] || v[2] != v[1] || abs(m[1] - m[2] - 3000) > 1e-9) {
				print "FAIL: staging: " n " event rows, t " t[1] ", m " m[1] " -> " m[2] ", v " v[1] " -> " v[2]; exit 1 }
			if (abs(v[1] - u * log(10000 / 7000)) > 1e-6 * v[1]) { printf "FAIL: first stage: %.17g\n", v[1]; exit 1 } }' "$T/stage.ev"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		$NF == 1 { v1 = $2 } NR > 1 { last = $2 }
		END { dv = last - v1; if (abs(dv - 2000 * log(4000 / 2000)) > 1e-6 * dv) { printf "FAIL: second stage gains %.17g\n", dv; exit 1 } }' "$T/stage.csv"
fi

# the bounce counter: a row before and after each impact, at the impact times
if comp bounce "$TOP/tests/e2e/when_bounces.csf"; then
	"$CSFVM" --rows-at-events "$T/bounce.csfb" >"$T/bounce.csv"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		BEGIN { g = 9.80665; h0 = 1; e = 0.5; by = 0.02; t1 = sqrt(2 * h0 / g); T[1] = t1; w[1] = g * t1 * e
			for (j = 2; j < 100; j++) { T[j] = T[j - 1] + 2 * w[j - 1] / g; w[j] = w[j - 1] * e }
			for (N = 1; 2 * w[N] / (g * (1 - e)) > 1e-6 * by; N++); }
		NR == 1 { next }
		$NF == -1 { bt = $1; bn = $4; before = 1; next }
		$NF == 1 { k++
			if (!before || $1 != bt || bn != k - 1 || $4 != k) { print "FAIL: impact " k ": " $0 " after " bt "," bn; exit 1 }
			want = k == 1 ? t1 : tp + 2 * wp / g
			if (abs($1 - want) > 1e-13 || abs($1 - T[k]) > k * 1e-13) {
				printf "FAIL: impact %d at t=%.17g: %.3g s from the flight before it, %.3g s from T_k\n", k, $1, $1 - want, $1 - T[k]; exit 1 }
			tp = $1; wp = $3; before = 0 }
		END { if (k != N) { print "FAIL: " k " impacts, the closed form has " N; exit 1 } }' "$T/bounce.csv"
	"$CSFVM" "$T/bounce.csfb" >"$T/bounce0.csv"
	plain "$T/bounce.csv" >"$T/bounce1.csv"
	check cmp -s "$T/bounce0.csv" "$T/bounce1.csv"
	if "$CSFC" --emit-c "$TOP/tests/e2e/when_bounces.csf" -o "$T/bounce" 2>"$T/ec.err"; then
		"$T/bounce" --rows-at-events >"$T/bounce_c.csv" && check cmp -s "$T/bounce.csv" "$T/bounce_c.csv"
	else
		bad "csfc --emit-c when_bounces.csf: $(head -n 1 "$T/ec.err")"
	fi
fi

# the kick: v jumps by dv at t1, the position does not
if comp kick "$TOP/tests/e2e/when_kick.csf"; then
	"$CSFVM" --rows-at-events "$T/kick.csfb" >"$T/kick.csv"
	events "$T/kick.csv" >"$T/kick.ev"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR == 1 { next }
		{ n++; for (i = 1; i <= NF; i++) r[n, i] = $i }
		END { if (n != 2 || abs(r[1, 1] - 0.35) > 1e-13 || r[2, 1] != r[1, 1]) { print "FAIL: kick: " n " event rows"; exit 1 }
			for (i = 2; i <= 4; i++) if (r[2, i] != r[1, i]) { print "FAIL: kick moved the position"; exit 1 }
			if (r[2, 5] - r[1, 5] != 0 || r[2, 6] - r[1, 6] != 2 || abs(r[2, 7] - r[1, 7] - 5) > 1e-12) {
				print "FAIL: kick: v " r[1, 5] "," r[1, 6] "," r[1, 7] " -> " r[2, 5] "," r[2, 6] "," r[2, 7]; exit 1 } }' "$T/kick.ev"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
