#!/bin/sh
# gen_pile.sh N CR MU TILL BY OUT.csf [WATCH] - writes a CSF scene of a pile of N
# equal balls (1 kg, radius 0.05 m) dropped in a 2-D box under gravity:
# they start on a lattice 0.12 m apart, W = ceil(sqrt(N)) balls a row along
# x (the first at x = 0.11 m), rows going up in z (the first at z = 0.1 m
# above the floor), each moved along x by 1e-3 m times a Park-Miller
# pseudo-random number in (-1, 1) (seed 4242) so that the lattice is not
# perfectly symmetric; all in y = 0. The box: a floor plane at z = 0 and
# two wall planes at x = 0 and x = W*0.12 + 0.1 m. Every body has
# restitution CR and, when MU is not 0, friction mu_s = MU, mu_k = 0.8*MU.
# Gravity: rule F: W = g.mul(m). Runs to TILL s, output every BY s,
# watching WATCH, a watch list (default: pos; tests/piles/piles.sh gives
# "pos, v, FN, Ff"). bench/box2d_pile.cpp builds the same scene in Box2D.
set -eu
[ $# -eq 6 ] || [ $# -eq 7 ] || { echo "usage: gen_pile.sh N CR MU TILL BY OUT.csf [WATCH]" >&2; exit 2; }
awk -v n="$1" -v cr="$2" -v mu="$3" -v till="$4" -v by="$5" -v watch="${7:-pos}" '
function rnd() { seed = (seed * 16807) % 2147483647; return seed / 2147483647 }
function props(o) {
	printf "object %s: cr = %s\n", o, cr
	if (mu + 0 != 0) printf "object %s: mu_s = %s\nobject %s: mu_k = %.15g\n", o, mu, o, 0.8 * mu
}
BEGIN {
	seed = 4242
	w = int(sqrt(n)); if (w * w < n) w++
	print "# a pile of " n " balls in a 2-D box (bench/gen_pile.sh " n " " cr " " mu " " till " " by ")"
	print "using mechanics/mass_point"
	for (i = 0; i < n; i++) {
		col = i % w; row = int(i / w)
		x = 0.11 + 0.12 * col + 1e-3 * (2 * rnd() - 1); z = 0.1 + 0.12 * row
		printf "object b%d: mass_point\nobject b%d: m = 1 kg\nobject b%d: radius = 0.05 m\n", i, i, i
		printf "object b%d: pos = (%.15g, 0, %.15g) m\n", i, x, z
		props("b" i)
	}
	print "object floor: plane"
	props("floor")
	print "object wall0: plane\nobject wall0: normal = (1, 0, 0)"
	props("wall0")
	printf "object wall1: plane\nobject wall1: point = (%.15g, 0, 0) m\nobject wall1: normal = (-1, 0, 0)\n", w * 0.12 + 0.1
	props("wall1")
	print "using mechanics/rules"
	print "rule F: W = g.mul(m)"
	printf "inc t till %s s by %s s watch %s\n", till, by, watch
}' > "$6"
