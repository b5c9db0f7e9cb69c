# awk -F, -f err.awk -f harmonic.awk out.csv : exact answer of harmonic.csf.
#   pos = pos0 cos(wt) + (v0/w) sin(wt),  v = -pos0 w sin(wt) + v0 cos(wt),  w = 3 rad/s
function setup(   j) {
	pi = atan2(0, -1); w = 3; by = pi / 6; rows = 41
	split("1 0 -0.5", p0, " "); split("0 3 1.5", v0, " "); split("x y z", xyz, " ")
	for (j = 1; j <= 3; j++) { P[j] = col("bob.pos." xyz[j]); V[j] = col("bob.v." xyz[j]) }
}
function row(t,   j, cs, sn) {
	cs = cos(w * t); sn = sin(w * t)
	for (j = 1; j <= 3; j++) {
		cmp($P[j], p0[j] * cs + v0[j] / w * sn)
		cmp($V[j], -p0[j] * w * sn + v0[j] * cs)
	}
}
