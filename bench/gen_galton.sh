#!/bin/sh
# gen_galton.sh NBALLS NROWS TILL BY OUT.csf [WATCH] - writes a CSF scene of a
# Galton board in the x-z plane (y = 0) under gravity (rule F: W = g.mul(m)):
# NBALLS equal balls fall from a column above the apex through NROWS rows of
# pegs into NROWS + 1 bins.
#
# The board (lengths in m; dx = 0.06, dz = dx sqrt(3)/2, so that the pegs
# form equilateral triangles):
#  - bins: NROWS + 1 of them, dx wide, between a floor plane at z = 0 and two
#    outer wall planes at x = 0 and x = W = (NROWS + 1) dx; divider i (i = 1
#    .. NROWS) stands at x = i dx: a column of touching anchors dI_J of radius
#    rho = 0.004 at z = rho (2 J + 1), J = 0 .. nd - 1, its top at h = rho
#    (2 nd - 1) (the top anchor's centre), nd the least with h >= r (NBALLS/2
#    + 4): a bin's inside is dx - 2 rho = 5.2 r wide, so it holds 2 balls a
#    layer, and h holds at least NBALLS/2 balls, more than the binomial share
#    of the fullest bin (C(n, n/2)/2^n: 0.375 for 4 rows, 0.246 for 10). A
#    divider is not two planes back to back with an edge at h: a plane is
#    one-sided, and a ball behind it (over it, not past its edge) is taken
#    as touching it and put on its face (a ball whose centre starts 0.18 m
#    behind a vertical plane bounded at z = 0.09 m starts on its face
#    instead; in a board of such dividers, balls jumped 0.17 m from one bin
#    onto the face of a divider across the board), so such a divider is two
#    half-spaces, not a thin wall;
#  - pegs: a triangle, row k (k = 0 at the top .. NROWS - 1) of k + 1 anchors
#    pK (radius rp = 0.004) at x = W/2 + (j - k/2) dx, j = 0 .. k, and z = zb
#    + (NROWS - 1 - k) dz, where zb = h + dz: the bottom row stands right
#    above the dividers. The gap between two pegs of a row is dx - 2 rp =
#    0.052 = 5.2 r, so a ball passes between them;
#  - balls bK: mass_point, m = 0.01 kg, r = 0.01, in a column above the apex:
#    ball i (from 0) at z = zt + rp + r + 0.02 + 0.03 i (zt: the apex's z),
#    0.01 apart so that they reach the pegs one after another, at x = W/2 +
#    1e-3 (2 u - 1) with u a Park-Miller pseudo-random number in (0, 1) (seed
#    4242), so that the balls do not strike the apex dead centre and the runs
#    are not perfectly symmetric.
# Every body: restitution cr = 0.5, mu_s = 0.05, mu_k = 0.04. The friction is
# small so that a ball cannot stick on top of a peg more than atan(0.05) = 2.9
# degrees from its summit (a mass point does not roll), and not 0 so that the
# balls come to rest in the bins (without friction, a ball with room to move
# never stops at cr > 0: tests/piles/piles.sh).
#
# A "# galton: ..." line gives the geometry (tests/piles/galton.awk's -v geom).
# Runs to TILL s, output every BY s, watching WATCH (default: each ball's pos
# and v, "b0.pos, b0.v, b1.pos, ...": the anchors' pos would add 3 constant
# columns each).
set -eu
[ $# -eq 5 ] || [ $# -eq 6 ] || { echo "usage: gen_galton.sh NBALLS NROWS TILL BY OUT.csf [WATCH]" >&2; exit 2; }
awk -v n="$1" -v rows="$2" -v till="$3" -v by="$4" -v watch="${6:-}" '
function rnd() { seed = (seed * 16807) % 2147483647; return seed / 2147483647 }
function props(o) {
	printf "object %s: cr = %s\nobject %s: mu_s = %s\nobject %s: mu_k = %s\n", o, cr, o, mus, o, muk
}
function plane(o, px, nx) {
	printf "object %s: plane\nobject %s: point = (%.15g, 0, 0) m\nobject %s: normal = (%s, 0, %s)\n", o, o, px, o, nx, nx == 0 ? 1 : 0
	props(o)
}
function anchor(o, x, z, rad) {
	printf "object %s: anchor\nobject %s: pos = (%.15g, 0, %.15g) m\nobject %s: radius = %s m\n", o, o, x, z, o, rad
	props(o)
}
BEGIN {
	seed = 4242
	r = 0.01; m = 0.01; rp = 0.004; rho = 0.004; dx = 0.06; dz = dx * sqrt(3) / 2
	cr = 0.5; mus = 0.05; muk = 0.04
	w = (rows + 1) * dx; xc = w / 2
	nd = int((r * (n / 2 + 4) / rho + 1) / 2); if (rho * (2 * nd - 1) < r * (n / 2 + 4)) nd++
	h = rho * (2 * nd - 1); zb = h + dz; zt = zb + (rows - 1) * dz
	print "# a Galton board: " n " balls, " rows " rows of pegs, " rows + 1 " bins (bench/gen_galton.sh " n " " rows " " till " " by ")"
	printf "# galton: n=%d rows=%d r=%s m=%s rp=%s rho=%s nd=%d dx=%s dz=%.15g h=%.15g zb=%.15g w=%.15g\n", n, rows, r, m, rp, rho, nd, dx, dz, h, zb, w
	print "using mechanics/mass_point"
	plane("floor", 0, 0)
	plane("wall0", 0, 1)
	plane("wall1", w, -1)
	for (i = 1; i <= rows; i++)
		for (j = 0; j < nd; j++) anchor("d" i "_" j, i * dx, rho * (2 * j + 1), rho)
	p = 0
	for (k = 0; k < rows; k++)
		for (j = 0; j <= k; j++) anchor("p" p++, xc + (j - k / 2) * dx, zb + (rows - 1 - k) * dz, rp)
	for (i = 0; i < n; i++) {
		printf "object b%d: mass_point\nobject b%d: m = %s kg\nobject b%d: radius = %s m\n", i, i, m, i, r
		printf "object b%d: pos = (%.15g, 0, %.15g) m\n", i, xc + 1e-3 * (2 * rnd() - 1), zt + rp + r + 0.02 + 0.03 * i
		props("b" i)
	}
	print "using mechanics/rules"
	print "rule F: W = g.mul(m)"
	if (watch == "") for (i = 0; i < n; i++) watch = watch (i ? ", " : "") "b" i ".pos, b" i ".v"
	printf "inc t till %s s by %s s watch %s\n", till, by, watch
}' > "$5"
