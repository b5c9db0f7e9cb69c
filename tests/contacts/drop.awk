# The exact motion of a ball dropped onto a plane, row by row (drop.sh).
#
# Parameters (-v): theta, the plane's slope in degrees; zf, the height of its
# point (0, 0, zf); r, the ball's radius; h0, the initial gap; e, the
# restitution; mus, muk, the friction coefficients; by, the output interval.
# The plane's normal is n = (-sin theta, 0, cos theta), its slope points
# down along d = (-cos theta, 0, -sin theta); the ball (1 kg) starts at rest
# at (0, 0, zf) + (r + h0) n. With gn = g cos theta and gt = g sin theta:
#   normal: free fall to t1 = sqrt(2 h0/gn) at speed w0 = gn t1; rebound k
#     leaves at e^k w0 and lands 2 e^k w0/gn later; the bounces accumulate
#     at tinf = t1 (1 + e)/(1 - e); after it the gap is 0 and FN = gn n.
#   along the slope: impacts are frictionless, so u = gt t up to tinf; then
#     it slides with u' = gt - muk gn, stops if that is negative (at
#     u = 0; static friction holds it when mus >= tan theta), Ff = -muk gn d
#     while sliding and -gt d once stuck.
# Every position (relative to the plane's point), velocity and force within
# tol = 1e-6 absolutely; the rows must be t = k by exactly.
function abs(x) { return x < 0 ? -x : x }
function fail(name, got, want) {
	printf "theta=%s zf=%s r=%s by=%s: row t=%s: %s = %.17g, exact %.17g\n", theta, zf, r, by, $1, name, got, want
	failed = 1; exit 1
}
function cmp(name, got, want,   d) {
	d = abs(got - want); if (d > maxerr) maxerr = d
	if (d > tol) fail(name, got, want)
}
BEGIN {
	FS = ","; tol = 1e-6; g = 9.80665; pi = atan2(0, -1); th = theta * pi / 180
	n[1] = -sin(th); n[2] = 0; n[3] = cos(th); d[1] = -cos(th); d[2] = 0; d[3] = -sin(th)
	gn = g * cos(th); gt = g * sin(th)
	t1 = sqrt(2 * h0 / gn); w[0] = gn * t1; T[0] = t1
	for (k = 1; k < 200; k++) { w[k] = w[k - 1] * e; T[k] = T[k - 1] + 2 * w[k] / gn }
	tinf = t1 * (1 + e) / (1 - e)
	u0 = gt * tinf; s0 = gt * tinf * tinf / 2; as = gt - muk * gn
	ts = as < 0 ? u0 / -as : -1 # how long it slides before it sticks
	if (ts >= 0 && mus * gn < gt) { print "drop.awk: the ball stops but cannot stick"; exit 2 }
}
NR == 1 { for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i }; next }
{
	rows++; t = $1
	if ($1 != (NR - 2) * by) fail("t", $1, (NR - 2) * by)
	fn = 0; ff = 0
	if (t < t1) { gap = h0 - gn * t * t / 2; vn = -gn * t }
	else if (t >= tinf) { gap = 0; vn = 0; fn = gn }
	else {
		for (k = 0; T[k + 1] <= t; k++);
		dt = t - T[k]; gap = w[k + 1] * dt - gn * dt * dt / 2; vn = w[k + 1] - gn * dt
	}
	if (t <= tinf) { u = gt * t; s = gt * t * t / 2 }
	else {
		tau = t - tinf
		if (ts >= 0 && tau >= ts) { u = 0; s = s0 + u0 * ts + as * ts * ts / 2; ff = -gt }
		else { u = u0 + as * tau; s = s0 + u0 * tau + as * tau * tau / 2; ff = muk > 0 || mus > 0 ? -muk * gn : 0 }
	}
	# the bounces that would end within 1e-6 by of tinf are a rest (csf(5)): the forces there
	zeno = t < tinf && t > tinf - 2e-6 * by
	split("x y z", ax, " ")
	for (i = 1; i <= 3; i++) {
		p0 = i == 3 ? zf : 0
		cmp("ball.pos." ax[i] " - point", $c["ball.pos." ax[i]] - p0, (r + gap) * n[i] + s * d[i])
		cmp("ball.v." ax[i], $c["ball.v." ax[i]], vn * n[i] + u * d[i])
		if (!zeno) {
			cmp("ball.FN." ax[i], $c["ball.FN." ax[i]], fn * n[i])
			cmp("ball.Ff." ax[i], $c["ball.Ff." ax[i]], ff * d[i])
		}
	}
}
END {
	if (failed) exit 1
	if (rows != rows_expected) { printf "theta=%s zf=%s r=%s by=%s: %d rows, expected %d\n", theta, zf, r, by, rows, rows_expected; exit 1 }
	printf "theta=%s zf=%s r=%s by=%s: max_err=%.3g\n", theta, zf, r, by, maxerr
}
