#!/bin/sh
# tests/many/ring.sh CSFC CSFVM DIR - a ring of 200 masses (M = 0.25 kg)
# joined by springs (K = 400 N/m), each a `for` rule naming the mass and its
# two neighbours; started from rest in normal mode q = 3:
#   u_j(0) = A cos(2 pi q j / N),  A = 0.01 m,
# the exact motion is u_j(t) = u_j(0) cos(w t) with
#   w = 2 sqrt(K/M) sin(pi q / N) = 3.7684... rad/s.
# Every row of every mass within 1e-9 m. Prints "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
n=200 q=3
awk -v n=$n -v q=$q 'BEGIN {
	pi = atan2(0, -1)
	print "global K = 400 N/m"
	print "global M = 0.25 kg"
	for (j = 0; j < n; j++) {
		printf "object p%d: u = %.17g m\n", j, 0.01 * cos(2 * pi * q * j / n)
		printf "object p%d: w = 0 m/s\n", j
	}
	print "rule: u'"'"' = w"
	for (j = 0; j < n; j++)
		printf "rule for p%d, p%d, p%d: w'"'"' = K / M * ((u$1 - u) + (u$2 - u))\n", j, (j + n - 1) % n, (j + 1) % n
	print "inc t till 2 s by 0.05 s watch u"
}' >"$T/ring.csf"
if ! "$CSFC" "$T/ring.csf" -o "$T/ring.csfb" 2>"$T/ring.err" || ! "$CSFVM" "$T/ring.csfb" >"$T/ring.csv" 2>>"$T/ring.err"; then
	echo "FAIL: ring of $n masses: $(head -n 1 "$T/ring.err")"; echo "0 passed, 1 failed"; exit 1
fi
if awk -F, -v n=$n -v q=$q 'function abs(x) { return x < 0 ? -x : x }
	BEGIN { pi = atan2(0, -1); w = 2 * sqrt(400 / 0.25) * sin(pi * q / n) }
	NR == 1 { if (NF != n + 1) { print "FAIL: " NF " columns"; bad = 1; exit 1 } next }
	{ t = $1; rows++
	  for (c = 2; c <= NF; c++) {
		j = c - 2; want = 0.01 * cos(2 * pi * q * j / n) * cos(w * t)
		if (abs($c - want) > 1e-9) { printf "FAIL: p%d.u at t=%s: %.17g, exact %.17g\n", j, t, $c, want; bad = 1; exit 1 }
	  } }
	END { if (!bad && rows != 41) { print "FAIL: " rows " rows, not 41"; exit 1 } exit bad }' "$T/ring.csv"; then
	echo "1 passed, 0 failed"
else
	echo "0 passed, 1 failed"; exit 1
fi
