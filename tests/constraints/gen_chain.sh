#!/bin/sh
# tests/constraints/gen_chain.sh N SPAN L DAMP TILL BY - a chain of N rigid links of length L
# (rods, rule C) with N - 1 beads of 0.1 kg at the joints, hung between two anchors SPAN
# apart at the same height, started as a V (two straight halves, N even) and damped (each bead
# -DAMP v): it settles into the discrete catenary. Watches every bead's pos and v.
N=$1 SPAN=$2 L=$3 DAMP=$4 TILL=$5 BY=$6
awk -v n="$N" -v span="$SPAN" -v L="$L" -v damp="$DAMP" -v till="$TILL" -v by="$BY" 'BEGIN {
	print "using mechanics/mass_point"
	print "object left: anchor"
	printf "object right: anchor\nobject right: pos = (%.17g, 0, 0) m\n", span
	h = n / 2; ca = span / (n * L); sa = sqrt(1 - ca * ca)
	for (i = 1; i < n; i++) {
		k = i <= h ? i : n - i
		x = i <= h ? i * L * ca : span - k * L * ca
		printf "object b%d: mass_point\nobject b%d: m = 0.1 kg\nobject b%d: pos = (%.17g, 0, %.17g) m\n", i, i, i, x, -k * L * sa
	}
	printf "global L = %.17g m\nglobal damp = %.17g kg/s\n", L, damp
	print "using mechanics/rules"
	print "rule F: W = g.mul(m)"
	print "rule F: D = v.mul(-damp)"
	print "rule C for b1, left: (pos - pos$1).mag = L"
	for (i = 2; i < n; i++) printf "rule C for b%d, b%d: (pos - pos$1).mag = L\n", i, i - 1
	printf "rule C for b%d, right: (pos - pos$1).mag = L\n", n - 1
	printf "inc t till %s s by %s s watch pos, v\n", till, by
}'
