# elliptic.awk - Jacobi's elliptic functions and the complete elliptic integral K,
# for the checkers of pendulums (loaded with "# uses: ../../examples/elliptic.awk" or
# "# uses: elliptic.awk" on a checker's first line).
# sn and cn come from the descending Landen (AGM) method, Abramowitz & Stegun 16.4.
function abs(x) { return x < 0 ? -x : x }
function asin(x) { return atan2(x, sqrt(1 - x * x)) }
# Jacobi sn and cn of u, modulus k: sets SN, CN
function sncn(u, k,   a, b, cc, n, i, phi, an, bn) {
	a[0] = 1; b = sqrt(1 - k * k); cc[0] = k; n = 0
	while (abs(cc[n]) > 1e-16 && n < 40) {
		an = (a[n] + b) / 2; bn = sqrt(a[n] * b); cc[n + 1] = (a[n] - b) / 2
		n++; a[n] = an; b = bn
	}
	phi = 2 ^ n * a[n] * u
	for (i = n; i > 0; i--) phi = (phi + asin(cc[i] / a[i] * sin(phi))) / 2
	SN = sin(phi); CN = cos(phi)
}
function agm(x, y,   t) { while (abs(x - y) > 1e-16 * x) { t = (x + y) / 2; y = sqrt(x * y); x = t } return x }
# K(k), the complete elliptic integral of the first kind of modulus k
function ellK(k) { return 3.14159265358979324 / (2 * agm(1, sqrt(1 - k * k))) }
