#!/bin/sh
# tests/piles/statics.sh CSFC CSFVM DIR - balls at rest in exact contact,
# whose forces are known in closed form; each scene runs 1 s (rows every
# 0.01 s, watching pos, v, a, FN and Ff) and statics.awk checks every row:
# nothing moves (v and a 0, pos as placed, to 1e-9) and the forces are the
# exact ones to 1e-9 m g (the scenes whose balls are dropped, into a groove,
# onto pegs, into a box, run 3 s, and their rows from t = 2 s are checked).
# Balls: 1 kg, radius r = 0.05 m, unless a scene says; W = m g.
#
# FN of a ball is the sum of the normal forces of all its contacts, Ff of
# their friction forces, so at rest FN + Ff = (0, 0, W) for every ball
# whatever the contacts share; the single contact forces are not columns,
# and the checks below say what the columns determine.
#
#  box: two balls on the floor touching each other and both walls (the box
#    4 r = 0.2 m wide), a third on both, frictionless. The top ball's two
#    contacts push along the lines of centres, 60 deg from horizontal, each
#    W/sqrt(3) (2 F sin 60 = W); each gives its bottom ball W/(2 sqrt 3)
#    outwards and W/2 down, so the floor pushes each bottom ball 1.5 W and its
#    wall W/(2 sqrt 3) + P, with P >= 0 the push between the bottom balls,
#    which nothing determines (wall-ball-ball-wall is a chain between two
#    parallel planes; P = 0 in the least-norm sense). Each ball's FN is the
#    sum: (0, 0, W) for all three, whatever P is; Ff = 0.
#  groove: a ball in a V of two planes at +-30 deg from horizontal, touching
#    both, frictionless: each plane pushes W/(2 cos 30) = W/sqrt(3) along its
#    normal; the ball's FN = (0, 0, W), Ff = 0.
#  pyramid: three balls on the floor touching in an equilateral triangle
#    (centres R = 2 r/sqrt(3) from its centre, at angles 90, 210, 330 deg),
#    a fourth on them (centre 2 r sqrt(2/3) above theirs); the floor rough
#    (mu_s 0.5, mu_k 0.4), the balls frictionless (a pair's coefficient is
#    the larger of the two: the ball-ball pairs have none). The lines of
#    centres make alpha with the vertical, cos alpha = sqrt(2/3), tan alpha =
#    1/sqrt(2); the top ball's three pushes are W/(3 cos alpha), each giving
#    its bottom ball W/3 down and H = W tan(alpha)/3 = W/(3 sqrt 2)
#    outwards (along u, the unit vector from the triangle's centre). A
#    bottom ball: floor N = W + W/3 = 4/3 W up, floor friction inwards,
#    bottom-bottom pushes P >= 0 (not determined: the floor's friction can
#    hold any prestress up to mu_s N), which add sqrt(3) P outwards. So
#    determined: top FN = (0, 0, W), Ff = 0; bottom FN_z = W, FN across u
#    0, FN along u = H + sqrt(3) P >= H, FN + Ff = (0, 0, W), and friction
#    within the cone |Ff| <= mu_s (FN_z + W/3). In the least-norm sense
#    (P = 0, checked apart as "pyramid, least-norm"): FN along u = H and
#    Ff = -H u exactly.
#  stack: fifteen balls stacked 5-4-3-2-1 in a box exactly 10 r = 0.5 m
#    wide (each row's balls touching, the bottom row both walls, each ball
#    above resting on two below), everything rough (mu_s 0.3, mu_k 0.2):
#    statically indeterminate, so only FN + Ff = (0, 0, W) for each ball is
#    determined. Its cluster of 37 pairs is too large for the searches of
#    modes but the modes as they are and the complementarity problem, on
#    which Lemke's method ends on a ray (162 unknowns, no pair slipping);
#    solved again with its diagonal shifted, it gives the cluster's modes,
#    so --stats says that no search found none (before the shift, the one
#    search found none and the stack was left to its pairs' guards).
#
# Every process has a time limit (TERM, then KILL 10 s later, as in piles.sh).
#
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
HERE=$(dirname "$0")
pass=0 fail=0
HEAD='using mechanics/mass_point'
TAIL='using mechanics/rules
rule F: W = g.mul(m)
inc t till 1 s by 0.01 s watch pos, v, a, FN, Ff'
# ball NAME X Y Z: a 1 kg ball of radius 0.05 m at (X, Y, Z) m (CSF expressions)
ball() {
	printf 'object %s: mass_point\nobject %s: m = 1 kg\nobject %s: radius = 0.05 m\nobject %s: pos = (%s, %s, %s) m\n' "$1" "$1" "$1" "$1" "$2" "$3" "$4"
}
# at_rest NAME X Y Z: checks that ball NAME stays at (X, Y, Z) (numbers)
at_rest() {
	printf 'pos of %s;eq;%.17g;1;1 %s.pos.x\npos of %s;eq;%.17g;1;1 %s.pos.y\npos of %s;eq;%.17g;1;1 %s.pos.z\n' "$1" "$2" "$1" "$1" "$3" "$1" "$1" "$4" "$1"
}
# forces NAME FNX FNY FNZ FFX FFY FFZ: checks of ball NAME's FN and Ff (numbers, N)
forces() {
	awk -v b="$1" -v s="$2 $3 $4 $5 $6 $7" 'BEGIN {
		split(s, f, " "); split("x y z", ax, " ")
		for (k = 1; k <= 3; k++) printf "%s.FN.%s;eq;%.17g;9.80665;1 %s.FN.%s\n", b, ax[k], f[k], b, ax[k]
		for (k = 1; k <= 3; k++) printf "%s.Ff.%s;eq;%.17g;9.80665;1 %s.Ff.%s\n", b, ax[k], f[k + 3], b, ax[k]
	}'
}
# run SCENE CHECKNAME...: compiles and runs $T/SCENE.csf, then checks it with
# each $T/CHECKNAME.expect
run() {
	s=$1
	shift
	if ! timeout -k 10 60 "$CSFC" "$T/$s.csf" -o "$T/$s.csfb" 2>"$T/$s.err"; then
		for k in "$@"; do fail=$((fail + 1)); echo "FAIL: $k: csfc: $(head -n 1 "$T/$s.err")"; done
		return
	fi
	timeout -k 10 120 "$CSFVM" "$T/$s.csfb" >"$T/$s.csv" 2>"$T/$s.err"
	st=$?
	if [ $st -ne 0 ]; then
		for k in "$@"; do
			fail=$((fail + 1))
			echo "FAIL: $k: csfvm exit $st after $(($(wc -l <"$T/$s.csv") - 1)) rows: $(grep -v '^warning' "$T/$s.err" | head -n 1 | cut -c1-200)"
		done
		return
	fi
	# FROM: only the rows from t = FROM s on are at rest (ROWS of them)
	awk -F, -v from="${FROM:-}" 'NR == 1 || from == "" || $1 + 0 >= from + 0' "$T/$s.csv" >"$T/$s.rest.csv"
	for k in "$@"; do
		if timeout -k 10 60 awk -v name="$k" -v rows="${ROWS:-101}" -f "$HERE/statics.awk" "$T/$k.expect" "$T/$s.rest.csv" >"$T/$k.chk" 2>&1; then
			pass=$((pass + 1)); [ -n "${VERBOSE:-}" ] && cat "$T/$k.chk"
		else
			fail=$((fail + 1)); echo "FAIL: $(head -n 1 "$T/$k.chk")"
		fi
	done
}
W=9.80665

# box
{
	echo "$HEAD"
	ball b0 0.05 0 0.05
	ball b1 0.15 0 0.05
	ball b2 0.1 0 '0.05 + 0.1 * sin(60 deg)'
	printf 'object floor: plane\nobject wall0: plane\nobject wall0: normal = (1, 0, 0)\n'
	printf 'object wall1: plane\nobject wall1: point = (0.2, 0, 0) m\nobject wall1: normal = (-1, 0, 0)\n'
	echo "$TAIL"
} >"$T/box.csf"
{
	at_rest b0 0.05 0 0.05
	at_rest b1 0.15 0 0.05
	at_rest b2 0.1 0 "$(awk 'BEGIN { printf "%.17g", 0.05 + 0.1 * sin(atan2(0, -1) / 3) }')"
	for b in b0 b1 b2; do forces $b 0 0 $W 0 0 0; done
} >"$T/box.expect"
run box box

# groove
{
	echo "$HEAD"
	ball b0 0 0 '0.05 / cos(30 deg)'
	printf 'object left: plane\nobject left: normal = (sin(30 deg), 0, cos(30 deg))\n'
	printf 'object right: plane\nobject right: normal = (-sin(30 deg), 0, cos(30 deg))\n'
	echo "$TAIL"
} >"$T/groove.csf"
{
	at_rest b0 0 0 "$(awk 'BEGIN { printf "%.17g", 0.05 / cos(atan2(0, -1) / 6) }')"
	forces b0 0 0 $W 0 0 0
} >"$T/groove.expect"
run groove groove

# groove, dropped: a rough ball (cr 0.4, mu_s 0.3, mu_k 0.2, the planes' too)
# dropped off centre into a V of two planes at 45 deg through (100, 0, 2) m;
# from t = 2 s it is at rest at (100, 0, 2 + r sqrt 2), each plane pushing
# W/sqrt(2) along its normal (FN = (0, 0, W)) and no friction (Ff = 0, the
# least there is: csf(5), Rest). Dropped at x = 100.013 or 99.98 m, its last
# impact left one plane's slip at 5e-20 m/s, and that pair slid on, with
# mu_k N up its plane (Ff = (-W/10, 0, -W/10), FN = (W/10, 0, 1.1 W)).
for x in 100.013 99.98; do
	{
		echo "$HEAD"
		ball b0 $x 0 2.4
		for o in b0 left right; do printf 'object %s: cr = 0.4\nobject %s: mu_s = 0.3\nobject %s: mu_k = 0.2\n' $o $o $o; done
		printf 'object left: plane\nobject left: point = (100, 0, 2) m\nobject left: normal = (1, 0, 1)\n'
		printf 'object right: plane\nobject right: point = (100, 0, 2) m\nobject right: normal = (-1, 0, 1)\n'
		echo "$TAIL" | sed 's/till 1 s/till 3 s/'
	} >"$T/drop$x.csf"
	{
		at_rest b0 100 0 "$(awk 'BEGIN { printf "%.17g", 2 + 0.05 * sqrt(2) }')"
		forces b0 0 0 $W 0 0 0
	} >"$T/groove, dropped at x = $x.expect"
	FROM=2 ROWS=101 run drop$x "groove, dropped at x = $x"
done

# pegs: a ball set down at rest on three pegs (anchors of radius 0.01 m at
# (0, 0, 0), (0.06, 0, 0) and (0.03, 0.05, 0) m), over their circumcentre
# (0.03, 0.016), its centre 0.06 m from each, at z = sqrt(0.06^2 - 0.034^2)
# (0.034 m the circumradius): the three normal forces, along the lines
# from the pegs' centres, are the only forces of a frictionless ball and
# are determined (three unknowns, three equations), their sum (0, 0, W);
# rough (mu_s 0.4, mu_k 0.3), the least friction is none. Both: nothing
# moves, FN = (0, 0, W), Ff = 0 from the first row.
for rough in 0 1; do
	{
		echo "$HEAD"
		ball b0 0.03 0.016 'sqrt(0.06 * 0.06 - 0.034 * 0.034)'
		[ $rough = 1 ] && printf 'object b0: mu_s = 0.4\nobject b0: mu_k = 0.3\n'
		k=1
		for at in '0, 0, 0' '0.06, 0, 0' '0.03, 0.05, 0'; do
			printf 'object p%d: anchor\nobject p%d: pos = (%s) m\nobject p%d: radius = 0.01 m\n' $k $k "$at" $k
			k=$((k + 1))
		done
		echo "$TAIL"
	} >"$T/pegs$rough.csf"
	name="pegs"
	[ $rough = 1 ] && name="pegs, rough"
	{
		at_rest b0 0.03 0.016 "$(awk 'BEGIN { printf "%.17g", sqrt(0.06 * 0.06 - 0.034 * 0.034) }')"
		forces b0 0 0 $W 0 0 0
	} >"$T/$name.expect"
	run pegs$rough "$name"
done

# pegs, dropped: the same ball (mu_s 0.4, mu_k 0.3, cr 0.3) set down 2.7 mm
# above its rest on three pegs (anchors of radius 0.01 m at (0, 0, 0),
# (0.06, 0, 0) and (0.03, 0.05, 0) m): from t = 2 s at rest over the
# circumcentre (0.03, 0.016) of the pegs, its centre 0.06 m from each, at
# z = sqrt(0.06^2 - 0.03^2 - 0.016^2); the three normal forces alone hold
# it, so FN = (0, 0, W) and Ff = 0, the least friction (csf(5), Rest).
# Before, FN = (0.68, -0.46, 10.37) N and Ff = -(0.68, -0.46, 0.56) N: a
# pair left sliding at rest (no slip, no tangential acceleration).
{
	echo "$HEAD"
	ball b0 0.0305 0.0163 0.052
	printf 'object b0: cr = 0.3\nobject b0: mu_s = 0.4\nobject b0: mu_k = 0.3\n'
	k=1
	for at in '0, 0, 0' '0.06, 0, 0' '0.03, 0.05, 0'; do
		printf 'object p%d: anchor\nobject p%d: pos = (%s) m\nobject p%d: radius = 0.01 m\n' $k $k "$at" $k
		k=$((k + 1))
	done
	echo "$TAIL" | sed 's/till 1 s/till 3 s/'
} >"$T/pegs.csf"
{
	at_rest b0 0.03 0.016 "$(awk 'BEGIN { printf "%.17g", sqrt(0.06 * 0.06 - 0.03 * 0.03 - 0.016 * 0.016) }')"
	forces b0 0 0 $W 0 0 0
} >"$T/pegs, dropped.expect"
FROM=2 ROWS=101 run pegs "pegs, dropped"

# two in a groove: a (1 kg, radius 0.05 m) and then b (0.25 kg, radius 0.03
# m) dropped into a V of planes at 50 and 40 deg from horizontal, all
# rough (mu_s 0.5, mu_k 0.4, cr 0.3): from t = 2 s a rests on both planes
# (its centre r/sin 90 deg from the corner along the bisector: x and z from
# the two planes' equations) and b on a and the 50-deg plane. The normal
# forces alone hold both (b's two pushes are positive), so each ball's FN
# is its weight and Ff = 0 (csf(5), Rest). Before, both balls were held
# with friction: a pair sliding at rest.
{
	echo "$HEAD"
	ball a 0.011 0 0.3
	printf 'object b: mass_point\nobject b: m = 0.25 kg\nobject b: radius = 0.03 m\nobject b: pos = (-0.017, 0, 0.6) m\n'
	for o in a b p q; do printf 'object %s: cr = 0.3\nobject %s: mu_s = 0.5\nobject %s: mu_k = 0.4\n' $o $o $o; done
	printf 'object p: plane\nobject p: normal = (sin(50 deg), 0, cos(50 deg))\n'
	printf 'object q: plane\nobject q: normal = (-sin(40 deg), 0, cos(40 deg))\n'
	echo "$TAIL" | sed 's/till 1 s/till 3 s/'
} >"$T/two.csf"
{
	# a's centre: sin50 x + cos50 z = r and -sin40 x + cos40 z = r
	awk -v r=0.05 'BEGIN { d = atan2(0, -1) / 180; s5 = sin(50 * d); c5 = cos(50 * d); s4 = sin(40 * d); c4 = cos(40 * d)
		det = s5 * c4 + c5 * s4; x = r * (c4 - c5) / det; z = r * (s5 + s4) / det
		printf "pos of a;eq;%.17g;1;1 a.pos.x\npos of a;eq;0;1;1 a.pos.y\npos of a;eq;%.17g;1;1 a.pos.z\n", x, z }'
	forces a 0 0 $W 0 0 0
	forces b 0 0 "$(awk -v W=$W 'BEGIN { printf "%.17g", W / 4 }')" 0 0 0
} >"$T/two in a groove.expect"
FROM=2 ROWS=101 run two "two in a groove"

# box, dropped: two rough balls b and d (2 kg, radius 0.15 m) on the floor
# of a box whose walls stand at x = -1 and -0.3 m, each against a wall, at
# x = -0.85 and -0.45 m, and a third, a (0.8 kg, radius 0.12 m), dropped
# from (-0.652, 0, 0.9) m into the gap between them; all rough (mu_s 0.5,
# mu_k 0.3) and a little elastic (cr 0.2). From t = 2 s all three are at
# rest, a at x = -0.65 m touching both (its centre sqrt(0.27^2 - 0.2^2)
# above theirs); a's two pushes hold it, the floor and the walls hold b and
# d, so each FN is its ball's weight and Ff = 0 (csf(5), Rest). Before, a
# went on moving at 3e-12 m/s, away from both, its two pairs sliding at
# that slip with mu_k N of friction (a.Ff.z = -3.88 N, a.FN.z = 11.72 N,
# b.FN.x = 1.76 N).
{
	echo "$HEAD"
	for o in b d; do printf 'object %s: mass_point\nobject %s: m = 2 kg\nobject %s: radius = 0.15 m\n' $o $o $o; done
	printf 'object b: pos = (-0.85, 0, 0.15) m\nobject d: pos = (-0.45, 0, 0.15) m\n'
	printf 'object a: mass_point\nobject a: m = 0.8 kg\nobject a: radius = 0.12 m\nobject a: pos = (-0.652, 0, 0.9) m\n'
	for o in a b d; do printf 'object %s: cr = 0.2\nobject %s: mu_s = 0.5\nobject %s: mu_k = 0.3\n' $o $o $o; done
	printf 'object floor: plane\nobject floor: cr = 0.2\nobject w0: plane\nobject w0: point = (-1, 0, 0) m\nobject w0: normal = (1, 0, 0)\n'
	printf 'object w1: plane\nobject w1: point = (-0.3, 0, 0) m\nobject w1: normal = (-1, 0, 0)\n'
	echo "$TAIL" | sed 's/till 1 s/till 3 s/'
} >"$T/boxdrop.csf"
{
	at_rest b -0.85 0 0.15
	at_rest d -0.45 0 0.15
	at_rest a -0.65 0 "$(awk 'BEGIN { printf "%.17g", 0.15 + sqrt(0.27 * 0.27 - 0.2 * 0.2) }')"
	forces b 0 0 "$(awk -v W=$W 'BEGIN { printf "%.17g", 2 * W }')" 0 0 0
	forces d 0 0 "$(awk -v W=$W 'BEGIN { printf "%.17g", 2 * W }')" 0 0 0
	forces a 0 0 "$(awk -v W=$W 'BEGIN { printf "%.17g", 0.8 * W }')" 0 0 0
} >"$T/box, dropped.expect"
FROM=2 ROWS=101 run boxdrop "box, dropped"

# pyramid
{
	echo "$HEAD"
	ball b0 0 '0.1 / sqrt(3)' 0.05
	ball b1 '-0.1 / sqrt(3) * cos(30 deg)' '-0.1 / sqrt(3) * sin(30 deg)' 0.05
	ball b2 '0.1 / sqrt(3) * cos(30 deg)' '-0.1 / sqrt(3) * sin(30 deg)' 0.05
	ball top 0 0 '0.05 + 0.1 * sqrt(2 / 3)'
	printf 'object floor: plane\nobject floor: mu_s = 0.5\nobject floor: mu_k = 0.4\n'
	echo "$TAIL"
} >"$T/pyramid.csf"
LN="$T/pyramid, least-norm.expect" awk -v W=$W 'BEGIN {
	pi = atan2(0, -1); R = 0.1 / sqrt(3); H = W / (3 * sqrt(2)); mus = 0.5
	split("b0 b1 b2", b, " "); th[1] = pi / 2; th[2] = 7 * pi / 6; th[3] = 11 * pi / 6
	for (i = 1; i <= 3; i++) {
		ux = cos(th[i]); uy = sin(th[i])
		printf "pos of %s;eq;%.17g;1;1 %s.pos.x\npos of %s;eq;%.17g;1;1 %s.pos.y\npos of %s;eq;0.05;1;1 %s.pos.z\n", b[i], R * ux, b[i], b[i], R * uy, b[i], b[i], b[i]
		printf "%s.FN.z;eq;%.17g;%.17g;1 %s.FN.z\n", b[i], W, W, b[i]
		printf "%s.FN across u;eq;0;%.17g;%.17g %s.FN.x %.17g %s.FN.y\n", b[i], W, -uy, b[i], ux, b[i]
		printf "%s.FN along u (H + sqrt(3) P, P >= 0);ge;%.17g;%.17g;%.17g %s.FN.x %.17g %s.FN.y\n", b[i], H, W, ux, b[i], uy, b[i]
		printf "%s.FN.x + Ff.x;eq;0;%.17g;1 %s.FN.x 1 %s.Ff.x\n", b[i], W, b[i], b[i]
		printf "%s.FN.y + Ff.y;eq;0;%.17g;1 %s.FN.y 1 %s.Ff.y\n", b[i], W, b[i], b[i]
		printf "%s.FN.z + Ff.z;eq;%.17g;%.17g;1 %s.FN.z 1 %s.Ff.z\n", b[i], W, W, b[i], b[i]
		# |Ff| = -u.Ff once Ff is along u; the floor normal is FN_z + W/3
		printf "%s |Ff| - mu_s (FN.z + W/3);le;%.17g;%.17g;%.17g %s.Ff.x %.17g %s.Ff.y %.17g %s.FN.z\n", b[i], mus * W / 3, W, -ux, b[i], -uy, b[i], -mus, b[i]
		printf "%s.FN along u;eq;%.17g;%.17g;%.17g %s.FN.x %.17g %s.FN.y\n", b[i], H, W, ux, b[i], uy, b[i] > ENVIRON["LN"]
		printf "%s.Ff along u;eq;%.17g;%.17g;%.17g %s.Ff.x %.17g %s.Ff.y\n", b[i], -H, W, ux, b[i], uy, b[i] > ENVIRON["LN"]
	}
	printf "pos of top;eq;0;1;1 top.pos.x\npos of top;eq;0;1;1 top.pos.y\npos of top;eq;%.17g;1;1 top.pos.z\n", 0.05 + 0.1 * sqrt(2 / 3)
}' >"$T/pyramid.expect"
forces top 0 0 $W 0 0 0 >>"$T/pyramid.expect"
run pyramid pyramid "pyramid, least-norm"

# stack
{
	echo "$HEAD"
	k=0
	for row in 0 1 2 3 4; do
		j=0
		while [ $j -lt $((5 - row)) ]; do
			ball s$k "0.05 + 0.05 * $row + 0.1 * $j" 0 "0.05 + 0.1 * $row * sin(60 deg)"
			printf 'object s%d: mu_s = 0.3\nobject s%d: mu_k = 0.2\n' $k $k
			j=$((j + 1)) k=$((k + 1))
		done
	done
	printf 'object floor: plane\nobject wall0: plane\nobject wall0: normal = (1, 0, 0)\n'
	printf 'object wall1: plane\nobject wall1: point = (0.5, 0, 0) m\nobject wall1: normal = (-1, 0, 0)\n'
	for o in floor wall0 wall1; do printf 'object %s: mu_s = 0.3\nobject %s: mu_k = 0.2\n' $o $o; done
	echo "$TAIL"
} >"$T/stack.csf"
awk -v W=$W 'BEGIN {
	k = 0
	for (row = 0; row < 5; row++)
		for (j = 0; j < 5 - row; j++) {
			b = "s" k++
			printf "pos of %s;eq;%.17g;1;1 %s.pos.x\npos of %s;eq;0;1;1 %s.pos.y\n", b, 0.05 + 0.05 * row + 0.1 * j, b, b, b
			printf "pos of %s;eq;%.17g;1;1 %s.pos.z\n", b, 0.05 + 0.1 * row * sin(atan2(0, -1) / 3), b
			printf "%s.FN.x + Ff.x;eq;0;%.17g;1 %s.FN.x 1 %s.Ff.x\n", b, W, b, b
			printf "%s.FN.y + Ff.y;eq;0;%.17g;1 %s.FN.y 1 %s.Ff.y\n", b, W, b, b
			printf "%s.FN.z + Ff.z;eq;%.17g;%.17g;1 %s.FN.z 1 %s.Ff.z\n", b, W, W, b, b
		}
}' >"$T/stack.expect"
run stack stack
if timeout -k 10 120 "$CSFVM" --stats "$T/stack.csfb" >/dev/null 2>"$T/stack.st" &&
	grep -q ' search.* for the modes of a cluster with friction (0 found none)' "$T/stack.st"; then
	pass=$((pass + 1))
else
	fail=$((fail + 1)); echo "FAIL: stack: a search for the cluster's modes found none: $(grep -o '[0-9]* search.*none)' "$T/stack.st")"
fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
