# kepler.awk - the checker shared by the two-body Kepler tests. A test's own
# X.check names it on its first line ("# uses: kepler.awk") and sets, in its
# BEGIN, the output step `by`, the number of data rows `rows`, the
# eccentricity `ecc`, and optionally the length scale `S` (default 1).
# Two-body Kepler orbit started at periapsis on +x, moving towards +y, centre of
# mass at rest at the origin. Mean anomaly M = n t, n = sqrt(mu/a^3); Kepler's
# equation E - e sin E = M is solved by Newton iteration; then
#   r = (a (cos E - e), a sqrt(1-e^2) sin E, 0),  r' = (-a sin E, a sqrt(1-e^2) cos E, 0) n/(1 - e cos E)
#   body 1 = -m2/(m1+m2) r,  body 2 = m1/(m1+m2) r (positions and velocities).
# Every value must be within 1e-6 absolutely or relatively (DECISIONS 6).
function abs(x) { return x < 0 ? -x : x }
function cmp(name, got, want,   d, r) {
	d = abs(got - want); r = want != 0 ? d / abs(want) : d
	if ((d < r ? d : r) > maxerr) maxerr = d < r ? d : r
	if (d > tol && d > tol * abs(want)) {
		printf "row %d (t=%s): %s = %.17g, exact %.17g, error %.3g\n%s\n", NR, $1, name, got, want, d, $0
		failed = 1; exit 1
	}
}
function col(name) { if (!(name in c)) { print "missing column " name; failed = 1; exit 1 } return c[name] }
function kepler(M, e,   E, dE, i) {
	E = M
	for (i = 0; i < 50; i++) {
		dE = (E - e * sin(E) - M) / (1 - e * cos(E)); E -= dE
		if (abs(dE) < 1e-15) break
	}
	return E
}
BEGIN {
	tol = 1e-6
	if (S == "") S = 1
	# G m1 = 3, G m2 = 1 (only the ratios and mu matter)
	m1 = 3; m2 = 1; mu = m1 + m2; a = 1; n1 = "A"; n2 = "B"
	nm = sqrt(mu / a ^ 3); split("x y z", xyz, " ")
}
NR == 1 {
	for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i }
	for (j = 1; j <= 3; j++) {
		P1[j] = col(n1 ".pos." xyz[j]); V1[j] = col(n1 ".v." xyz[j])
		P2[j] = col(n2 ".pos." xyz[j]); V2[j] = col(n2 ".v." xyz[j])
	}
	next
}
{
	n++; t = $1
	cmp("t", t, (NR - 2) * by)
	E = kepler(nm * t, ecc); Ed = nm / (1 - ecc * cos(E)); q = sqrt(1 - ecc * ecc)
	r[1] = a * (cos(E) - ecc); r[2] = a * q * sin(E); r[3] = 0
	w[1] = -a * sin(E) * Ed; w[2] = a * q * cos(E) * Ed; w[3] = 0
	for (j = 1; j <= 3; j++) {
		cmp(n1 ".pos." xyz[j], $P1[j] / S, -m2 / mu * r[j]); cmp(n1 ".v." xyz[j], $V1[j] / S, -m2 / mu * w[j])
		cmp(n2 ".pos." xyz[j], $P2[j] / S, m1 / mu * r[j]); cmp(n2 ".v." xyz[j], $V2[j] / S, m1 / mu * w[j])
	}
}
END {
	if (failed) exit 1
	if (n != rows) { printf "expected %d data rows, got %d\n", rows, n; exit 1 }
	printf "max_err=%.3g\n", maxerr > "/dev/stderr"
}
