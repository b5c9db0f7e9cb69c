#!/bin/sh
# tests/cone/check.sh CSFC CSFVM DIR - the cone of influence (csfc leaves out the objects that
# nothing watched, asserted or stopped on depends on) and --every, against exact answers:
#  - 200 projectiles with drag watching two (gen_projectiles.sh): the others are left out with a
#    warning and listed by --explain; with fixed steps (--fixed, with dop853 and with rk4) the
#    rows are byte for byte those of csfc --keep-all; with the default adaptive steps the
#    watched projectile follows the closed form of linear drag to 1e-9 m;
#  - a ball that rolls into an unwatched one keeps it (collide.csf): it stops dead at the
#    elastic impact, exactly as the closed form says, while an unrelated clock is left out;
#  - points on one floor (floor.csf): the floor is kept, the other points (which touch only
#    the floor) are not; the watched point's bounce to 1e-9 m;
#  - springs (spring_chain.csf): a chain of three is kept whole, byte for byte as with
#    --keep-all under --fixed; an unrelated point is left out;
#  - an assertion keeps what it reads (assert_kept.csf): it fails at t = 0.5 s, exit 1, after
#    the 5 rows before it;
#  - -D on a property of an object left out is an error naming it;
#  - a state variable nothing watched reads (odometer.csf) is not integrated: --explain says so,
#    the rows are byte for byte those of --keep-all under --fixed; watched, it is the arc length
#    of the parabola to 1e-9 m;
#  - --every 4 writes rows 0, 4, 8, ... and the last of the full output, byte for byte.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
D=$(dirname "$0")
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { if "$@"; then ok; else bad "$*"; fi; }
comp() { # comp NAME SCENE [CSFC OPTIONS]: $T/NAME.csfb, csfc's words in $T/NAME.err
	n=$1 f=$2
	shift 2
	"$CSFC" "$@" "$f" -o "$T/$n.csfb" 2>"$T/$n.err" && return 0
	bad "$n: does not compile: $(head -n 1 "$T/$n.err")"
	return 1
}

# 200 projectiles, two watched
sh "$D/gen_projectiles.sh" 200 "p0.pos, p123.v" >"$T/proj.csf"
if comp proj "$T/proj.csf" && comp projall "$T/proj.csf" --keep-all; then
	check grep -q "warning: object 'p1' affects nothing watched" "$T/proj.err"
	check grep -q "and 195 more objects from 'p4' on affect nothing watched" "$T/proj.err"
	check test ! -s "$T/projall.err"
	"$CSFC" --explain "$T/proj.csf" 2>/dev/null >"$T/proj.explain"
	check test "$(grep -c '^object p[0-9]*: left out: nothing watched' "$T/proj.explain")" = 198
	check test "$(grep -c '^object p\(0\|123\): m ' "$T/proj.explain")" = 2
	# the memory of two projectiles is a small part of that of 200 (the bytecode's tables of
	# properties are progressions, a few hundred bytes whatever the objects: not a measure)
	mem() { "$CSFC" --dump-bytecode "$@" "$T/proj.csf" -o /dev/null 2>/dev/null | sed -n '1s/^; memory \([0-9]*\) slots.*/\1/p'; }
	check test "$(mem)" -lt "$(($(mem --keep-all) / 10))"
	for m in "--fixed" "--fixed --method rk4" "--fixed --method rk2 --step 0.001"; do
		# shellcheck disable=SC2086 # m holds options
		"$CSFVM" $m "$T/proj.csfb" >"$T/a.csv" && "$CSFVM" $m "$T/projall.csfb" >"$T/b.csv" &&
			check cmp -s "$T/a.csv" "$T/b.csv"
	done
	# p0: m 0.5 kg, k 0.05 kg/s, v0 (3, 1, 10) m/s from the origin: x = v0 tau (1 - exp(-t/tau)),
	# z = tau (v0z + g tau) (1 - exp(-t/tau)) - g tau t, tau = m/k
	"$CSFVM" "$T/proj.csfb" >"$T/a.csv" && check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { tau = 10; g = 9.80665; e = 1 - exp(-$1 / tau)
			x = 3 * tau * e; y = tau * e; z = tau * (10 + g * tau) * e - g * tau * $1
			if (abs($2 - x) > 1e-9 || abs($3 - y) > 1e-9 || abs($4 - z) > 1e-9) {
				printf "FAIL: p0 at t=%s: (%.17g, %.17g, %.17g), not (%.17g, %.17g, %.17g)\n", $1, $2, $3, $4, x, y, z; exit 1 }
			n++ }
		END { exit n != 41 }' "$T/a.csv"
fi

# a ball into an unwatched ball
if comp collide "$D/collide.csf"; then
	check grep -q "object 'clock' affects nothing watched" "$T/collide.err"
	check test "$(grep -c "affects nothing" "$T/collide.err")" = 1
	"$CSFVM" "$T/collide.csfb" >"$T/c.csv" && check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { x = $1 <= 0.5 ? 2 * $1 : 1; v = $1 <= 0.5 ? 2 : 0
			if (abs($2 - x) > 1e-9 || abs($5 - v) > 1e-9) { printf "FAIL: a at t=%s: x %.17g v %.17g\n", $1, $2, $5; exit 1 }
			n++ }
		END { exit n != 9 }' "$T/c.csv"
fi

# points on one floor
if comp floor "$D/floor.csf"; then
	check grep -q "object 'b' affects nothing watched" "$T/floor.err"
	check grep -q "object 'ball3' affects nothing watched" "$T/floor.err"
	check test "$(grep -c "affects nothing" "$T/floor.err")" = 2
	"$CSFVM" "$T/floor.csfb" >"$T/f.csv" && check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { g = 9.80665; t0 = sqrt(3.6 / g); s = $1 - t0
			z = $1 <= t0 ? 1.8 - g * $1 * $1 / 2 : g * t0 * s - g * s * s / 2
			if (abs($4 - z) > 1e-9) { printf "FAIL: a at t=%s: z %.17g, not %.17g\n", $1, $4, z; exit 1 }
			n++ }
		END { exit n != 21 }' "$T/f.csv"
fi

# a chain of springs
if comp spring "$D/spring_chain.csf" && comp springall "$D/spring_chain.csf" --keep-all; then
	check grep -q "object 'm4' affects nothing watched" "$T/spring.err"
	check test "$(grep -c "affects nothing" "$T/spring.err")" = 1
	"$CSFVM" --fixed "$T/spring.csfb" >"$T/a.csv" && "$CSFVM" --fixed "$T/springall.csfb" >"$T/b.csv" &&
		check cmp -s "$T/a.csv" "$T/b.csv"
fi

# an assertion keeps what it reads
if comp assert "$D/assert_kept.csf"; then
	check test ! -s "$T/assert.err"
	"$CSFVM" "$T/assert.csfb" >"$T/a.csv" 2>"$T/a.err"
	check test $? = 1
	check test "$(wc -l <"$T/a.csv")" = 6
	check grep -q "assertion failed at t=0.5: b.pos.z > 0 m" "$T/a.err"
fi

# -D on what was left out
if [ -f "$T/proj.csfb" ]; then
	"$CSFVM" -D p7.k=1 "$T/proj.csfb" >/dev/null 2>"$T/d.err"
	check test $? = 2
	check grep -q "object 'p7' has no property 'k' that the run uses" "$T/d.err"
fi

# an odometer nobody reads
if comp odo "$D/odometer.csf" && comp odoall "$D/odometer.csf" --keep-all; then
	check test ! -s "$T/odo.err"
	"$CSFC" --explain "$D/odometer.csf" 2>/dev/null | grep -q "path (state, left out: nothing needs it)"
	check test $? = 0
	"$CSFVM" --fixed "$T/odo.csfb" >"$T/a.csv" && "$CSFVM" --fixed "$T/odoall.csfb" >"$T/b.csv" && check cmp -s "$T/a.csv" "$T/b.csv"
	sed 's/watch ball.pos$/watch ball.pos, ball.path/' "$D/odometer.csf" >"$T/odo2.csf"
	comp odo2 "$T/odo2.csf" && "$CSFVM" "$T/odo2.csfb" >"$T/a.csv" && check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		function asinh(x) { return log(x + sqrt(x * x + 1)) }
		function F(u) { return (u * sqrt(9 + u * u) + 9 * asinh(u / 3)) / 2 }
		NR > 1 { g = 9.80665; s = (F(4) - F(4 - g * $1)) / g
			if (abs($5 - s) > 1e-9) { printf "FAIL: path at t=%s: %.17g, not %.17g\n", $1, $5, s; exit 1 }
			n++ }
		END { exit n != 9 }' "$T/a.csv"
fi

# --every 4: rows 0, 4, 8, ... and the last (40 rows after t = 0: the last is row 40, a multiple)
if [ -f "$T/proj.csfb" ]; then
	"$CSFVM" "$T/proj.csfb" >"$T/a.csv" && "$CSFVM" --every 4 "$T/proj.csfb" >"$T/e.csv" &&
		awk 'NR == 1 || (NR - 2) % 4 == 0' "$T/a.csv" >"$T/b.csv" && check cmp -s "$T/e.csv" "$T/b.csv"
	"$CSFVM" --every 7 "$T/proj.csfb" >"$T/e.csv" &&
		awk -v n="$(wc -l <"$T/a.csv")" 'NR == 1 || (NR - 2) % 7 == 0 || NR == n' "$T/a.csv" >"$T/b.csv" &&
		check cmp -s "$T/e.csv" "$T/b.csv"
	"$CSFVM" --every 0 "$T/proj.csfb" >/dev/null 2>"$T/e.err"
	check test $? = 2
	check grep -q "every needs a whole number of rows, 1 or more, not '0'" "$T/e.err"
fi
echo "$pass passed, $fail failed"
[ "$fail" = 0 ]
