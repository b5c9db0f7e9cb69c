#!/bin/sh
# tests/many/projectiles.sh CSFC CSFVM DIR - 1000 projectiles, each with
# its own initial position and velocity, under gravity (mechanics/rules):
# every row of every object against the closed form
#   pos = pos0 + v0 t + g t^2/2,  v = v0 + g t,  g = (0, 0, -9.80665),
# within 1e-9 (rk8pd is exact on a quadratic up to rounding). Two points
# (radius 0) never touch, and there is no plane, so the scene has no
# contacts. Prints "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
n=1000
awk -v n=$n 'BEGIN {
	print "using mechanics/mass_point"
	for (i = 0; i < n; i++) {
		printf "object p%d: mass_point\n", i
		printf "object p%d: pos = (%d, %d, %d) m\n", i, i % 10, int(i / 10) % 10, int(i / 100)
		printf "object p%d: v = (%.2f, %.2f, %.2f) m/s\n", i, (i % 7) * 0.5 - 1.5, (i % 11) * 0.3 - 1.2, 3 + (i % 13) * 0.7
	}
	print "using mechanics/rules"
	print "rule F: W = g.mul(m)"
	print "inc t till 1 s by 0.1 s watch pos, v"
}' >"$T/proj.csf"
if ! "$CSFC" "$T/proj.csf" -o "$T/proj.csfb" 2>"$T/proj.err" || ! "$CSFVM" "$T/proj.csfb" >"$T/proj.csv" 2>>"$T/proj.err"; then
	echo "FAIL: 1000 projectiles: $(head -n 1 "$T/proj.err")"; echo "0 passed, 1 failed"; exit 1
fi
if awk -F, -v n=$n 'function abs(x) { return x < 0 ? -x : x }
	NR == 1 {
		if (NF != 1 + 6 * n) { print "FAIL: " NF " columns, not " 1 + 6 * n; bad = 1; exit 1 }
		for (c = 2; c <= NF; c++) { h = $c; sub(/ *\[.*$/, "", h); split(h, q, "."); obj[c] = substr(q[1], 2) + 0; what[c] = q[2]; ax[c] = q[3] }
		next }
	{ t = $1; rows++
	  if (t != (NR - 2) * 0.1) { print "FAIL: row time " t; bad = 1; exit 1 }
	  for (c = 2; c <= NF; c++) {
		i = obj[c]; a = ax[c] == "x" ? 0 : ax[c] == "y" ? 1 : 2
		p0 = a == 0 ? i % 10 : a == 1 ? int(i / 10) % 10 : int(i / 100)
		v0 = a == 0 ? (i % 7) * 0.5 - 1.5 : a == 1 ? (i % 11) * 0.3 - 1.2 : 3 + (i % 13) * 0.7
		g = a == 2 ? -9.80665 : 0
		want = what[c] == "pos" ? p0 + v0 * t + g * t * t / 2 : v0 + g * t
		if (abs($c - want) > 1e-9) { printf "FAIL: p%d.%s.%s at t=%s: %.17g, exact %.17g\n", i, what[c], ax[c], t, $c, want; bad = 1; exit 1 }
	  } }
	END { if (!bad && rows != 11) { print "FAIL: " rows " rows, not 11"; exit 1 } exit bad }' "$T/proj.csv"; then
	echo "1 passed, 0 failed"
else
	echo "0 passed, 1 failed"; exit 1
fi
