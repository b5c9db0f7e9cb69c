#!/bin/sh
# tests/many/box.sh CSFC CSFVM DIR - 100 elastic balls (radius 0.05 m, 1 kg,
# cr = 1, no friction, no gravity) in a box of six planes, the unit cube
# [0, 1 m]^3; they start on a 5 x 5 x 4 lattice, 0.1 m apart, each with its
# own velocity (components in (-1, 1) m/s, from a Park-Miller generator),
# and collide with each other and the walls for 3 s: some 1300 collisions,
# each located as an event (mechanics/rules, with no list of pairs: the
# contact routine finds the pairs that come near).
# Checked:
#  - an assertion in the model: every coordinate of every ball stays
#    between the walls less its radius, radius <= x <= 1 m - radius,
#    exactly, at every output row (an impact is located to 1e-13 s, and
#    the ball placed exactly touching the wall, never past it; between
#    impacts every gap is open);
#  - the run exits 0 with every row (61);
#  - the total kinetic energy, sum m |v|^2 / 2 over the 300 velocity
#    columns, stays that of t = 0 to 1e-9 relative at every row: elastic
#    collisions conserve it (each impulse to rounding), and no force acts.
# Prints "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
n=100
awk -v n=$n 'function rnd() { seed = (seed * 16807) % 2147483647; return seed / 2147483647 }
BEGIN {
	seed = 4242
	print "using mechanics/mass_point"
	for (i = 0; i < n; i++) {
		x = i % 5; y = int(i / 5) % 5; z = int(i / 25)
		printf "object b%d: mass_point\nobject b%d: radius = 0.05 m\n", i, i
		printf "object b%d: pos = (%.2f, %.2f, %.3f) m\n", i, 0.1 + 0.2 * x, 0.1 + 0.2 * y, 0.125 + 0.25 * z
		printf "object b%d: v = (%.3f, %.3f, %.3f) m/s\n", i, 2 * rnd() - 1, 2 * rnd() - 1, 2 * rnd() - 1
	}
	print "object x0: plane\nobject x0: normal = (1, 0, 0)\nobject x1: plane\nobject x1: point = (1, 0, 0) m\nobject x1: normal = (-1, 0, 0)"
	print "object y0: plane\nobject y0: normal = (0, 1, 0)\nobject y1: plane\nobject y1: point = (0, 1, 0) m\nobject y1: normal = (0, -1, 0)"
	print "object z0: plane\nobject z1: plane\nobject z1: point = (0, 0, 1) m\nobject z1: normal = (0, 0, -1)"
	print "using mechanics/rules"
	print "assert pos.x >= radius and pos.x <= 1 m - radius"
	print "assert pos.y >= radius and pos.y <= 1 m - radius"
	print "assert pos.z >= radius and pos.z <= 1 m - radius"
	print "inc t till 3 s by 0.05 s watch v"
}' >"$T/box.csf"
if ! "$CSFC" "$T/box.csf" -o "$T/box.csfb" 2>"$T/box.err" || ! "$CSFVM" "$T/box.csfb" >"$T/box.csv" 2>>"$T/box.err"; then
	echo "FAIL: 100 balls in a box: $(head -n 1 "$T/box.err")"; echo "0 passed, 1 failed"; exit 1
fi
if awk -F, -v n=$n 'function abs(x) { return x < 0 ? -x : x }
	NR == 1 { if (NF != 1 + 3 * n) { print "FAIL: " NF " columns, not " 1 + 3 * n; bad = 1; exit 1 } next }
	{ rows++; e = 0
	  for (c = 2; c <= NF; c++) e += $c * $c / 2
	  if (rows == 1) e0 = e
	  if (abs(e - e0) > 1e-9 * e0) { printf "FAIL: kinetic energy at t=%s: %.17g J, at t=0 %.17g J\n", $1, e, e0; bad = 1; exit 1 }
	  if (abs(e - e0) > worst) worst = abs(e - e0) }
	END { if (!bad && rows != 61) { print "FAIL: " rows " rows, not 61"; exit 1 }
	      if (!bad) printf "kinetic energy %.17g J, conserved to %.3g relative\n", e0, worst / e0
	      exit bad }' "$T/box.csv" >"$T/box.chk"; then
	cat "$T/box.chk"
	echo "1 passed, 0 failed"
else
	cat "$T/box.chk"
	echo "0 passed, 1 failed"; exit 1
fi
