# awk -F, -v ecc=E -f err.awk -f kepler.awk out.csv : exact answer of
# kepler_e05.csf (ecc=0.5) and kepler_e09.csf (ecc=0.9).
# Mean anomaly M = n t (reduced to [0, 2 pi)), n = sqrt(mu/a^3); Kepler's equation
# E - e sin E = M solved by Newton iteration (to |dE| < 1e-15, from E = M + 0.85 e
# for M < pi, M - 0.85 e above); then
#   r = (a (cos E - e), a sqrt(1-e^2) sin E, 0),  r' = (-a sin E, a sqrt(1-e^2) cos E, 0) n/(1 - e cos E)
#   body A = -m_B/(m_A+m_B) r,  body B = m_A/(m_A+m_B) r (positions and velocities).
function kepler(M, e,   E, dE, i) {
	M -= 2 * pi * int(M / (2 * pi))
	E = M < pi ? M + 0.85 * e : M - 0.85 * e
	for (i = 0; i < 50; i++) {
		dE = (E - e * sin(E) - M) / (1 - e * cos(E)); E -= dE
		if (abs(dE) < 1e-15) break
	}
	return E
}
function setup(   j) {
	if (ecc == "") { print "kepler.awk: needs -v ecc=..." > "/dev/stderr"; bad = 1; exit 1 }
	pi = atan2(0, -1); by = pi / 10; rows = 101
	m1 = 3; m2 = 1; mu = m1 + m2; a = 1; nm = sqrt(mu / a ^ 3)
	split("x y z", xyz, " ")
	for (j = 1; j <= 3; j++) {
		P1[j] = col("A.pos." xyz[j]); V1[j] = col("A.v." xyz[j])
		P2[j] = col("B.pos." xyz[j]); V2[j] = col("B.v." xyz[j])
	}
}
function row(t,   E, Ed, q, r, w, j) {
	E = kepler(nm * t, ecc); Ed = nm / (1 - ecc * cos(E)); q = sqrt(1 - ecc * ecc)
	r[1] = a * (cos(E) - ecc); r[2] = a * q * sin(E); r[3] = 0
	w[1] = -a * sin(E) * Ed; w[2] = a * q * cos(E) * Ed; w[3] = 0
	for (j = 1; j <= 3; j++) {
		cmp($P1[j], -m2 / mu * r[j]); cmp($V1[j], -m2 / mu * w[j])
		cmp($P2[j], m1 / mu * r[j]); cmp($V2[j], m1 / mu * w[j])
	}
}
