# awk -F, -f err.awk -f linear_drag.awk out.csv : exact answer of linear_drag.csf.
#   v = v_inf + (v0 - v_inf) e^{-kt},  pos = pos0 + v_inf t + (v0 - v_inf)(1 - e^{-kt})/k
function setup(   j) {
	by = 1; rows = 21; m = 2; b = 0.5; k = b / m
	split("0 50 0", p0, " "); split("10 0 0", v0, " "); split("0 -9.81 0", g, " "); split("x y z", xyz, " ")
	for (j = 1; j <= 3; j++) { P[j] = col("ball.pos." xyz[j]); V[j] = col("ball.v." xyz[j]) }
}
function row(t,   j, vi, ek) {
	ek = exp(-k * t)
	for (j = 1; j <= 3; j++) {
		vi = m * g[j] / b
		cmp($P[j], p0[j] + vi * t + (v0[j] - vi) * (1 - ek) / k)
		cmp($V[j], vi + (v0[j] - vi) * ek)
	}
}
