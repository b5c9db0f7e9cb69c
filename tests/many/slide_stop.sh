#!/bin/sh
# tests/many/slide_stop.sh CSFC CSFVM DIR - 1000 balls (radius 0.1 m, 1 kg,
# mu_s 0.5, mu_k 0.4) on a floor under gravity, on a 40 x 25 lattice 0.3 m
# apart, each sliding with one of six velocities v = (0.01 (k mod 3),
# 0.005 (k mod 2), 0) m/s: kinetic friction mu_k g slows each along its
# own direction, and the balls of a class stop together at t = |v|/(mu_k g)
# (at most 6.4 ms), some 330 pairs switching from sliding to sticking at
# one instant. Exact: p = p0 + v (t - mu_k g t^2/(2 |v|)) until then, and
# p0 + v |v|/(2 mu_k g) after. Every coordinate of every ball at every row
# (0 to 0.5 s every 10 ms) is checked to 1e-9 m. The pairs that switch at
# once are located as one event: one location each made this scene take
# 15 s instead of 0.2 s.
# Prints "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
awk 'BEGIN {
	print "using mechanics/mass_point"
	for (k = 0; k < 1000; k++) {
		printf "object b%d: mass_point\nobject b%d: radius = 0.1 m\nobject b%d: mu_s = 0.5\nobject b%d: mu_k = 0.4\n", k, k, k, k
		printf "object b%d: pos = (%.1f, %.1f, 0.1) m\n", k, 0.3 * int(k / 25), 0.3 * (k % 25)
		printf "object b%d: v = (%.2f, %.3f, 0) m/s\n", k, 0.01 * (k % 3), 0.005 * (k % 2)
	}
	print "object floor: plane\nusing mechanics/rules\nrule F: W = g.mul(m)\ninc t till 0.5 s by 10 ms watch pos"
}' >"$T/slide.csf"
if ! "$CSFC" "$T/slide.csf" -o "$T/slide.csfb" 2>"$T/slide.err" || ! "$CSFVM" "$T/slide.csfb" >"$T/slide.csv" 2>>"$T/slide.err"; then
	echo "FAIL: 1000 sliding balls: $(head -n 1 "$T/slide.err")"; echo "0 passed, 1 failed"; exit 1
fi
if awk -F, 'function abs(x) { return x < 0 ? -x : x }
	function want(p0, vc, s, t,   a, ts) { # one coordinate: start p0, velocity component vc, speed s
		if (s == 0) return p0
		a = 0.4 * 9.80665; ts = s / a
		if (t > ts) t = ts
		return p0 + vc / s * (s * t - a * t * t / 2)
	}
	NR == 1 { if (NF != 3001) { print "FAIL: " NF " columns, not 3001"; bad = 1; exit 1 } next }
	{ rows++; t = $1
	  for (k = 0; k < 1000; k++) {
		vx = 0.01 * (k % 3); vy = 0.005 * (k % 2); s = sqrt(vx * vx + vy * vy)
		x = want(0.3 * int(k / 25), vx, s, t); y = want(0.3 * (k % 25), vy, s, t)
		c = 2 + 3 * k
		if (abs($c - x) > 1e-9 || abs($(c + 1) - y) > 1e-9 || abs($(c + 2) - 0.1) > 1e-9) {
			printf "FAIL: t=%s: b%d at (%.17g, %.17g, %.17g), exact (%.17g, %.17g, 0.1)\n", t, k, $c, $(c + 1), $(c + 2), x, y
			bad = 1; exit 1
		}
		e = abs($c - x) + abs($(c + 1) - y); if (e > worst) worst = e
	  } }
	END { if (!bad && rows != 51) { print "FAIL: " rows " rows, not 51"; exit 1 }
	      if (!bad) printf "every ball within %.3g m of the exact motion\n", worst
	      exit bad }' "$T/slide.csv" >"$T/slide.chk"; then
	cat "$T/slide.chk"
	echo "1 passed, 0 failed"
else
	cat "$T/slide.chk"
	echo "0 passed, 1 failed"; exit 1
fi
