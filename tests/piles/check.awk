# tests/piles/check.awk - every row of a pile's CSV (bench/gen_pile.sh with
# watch "pos, v, FN, Ff") against what holds for any correct answer.
#
# The pile: equal balls (columns NAME.pos.x ... NAME.Ff.z, any names) of mass
# m and radius r on a floor z = 0 between walls x = 0 and x = xw, in the
# plane y = 0, under gravity g along -z. At every row, in this order, the
# first miss stops the check with exit 1 and one line naming the row, the
# bodies and the numbers:
#  (t) the rows are t = k by (to 1e-9 by), and, at the end, there are `rows`
#      of them when rows is given;
#  (a) nothing overlaps by more than tol metres: ball to ball |p_i - p_j| >=
#      2 r - tol; ball to floor z >= r - tol; to the walls r - tol <= x <=
#      xw - r + tol; and every ball stays in the plane: |y|, |v_y| <= tol;
#  (b) the energy E = sum (m |v|^2 / 2 + m g z) never grows from one row to
#      the next by more than tol |E_0|; with conserve=1 it stays within
#      tol |E_0| of E_0;
#  (c) with rest=T, at every row with t >= T: every speed <= tol m/s, and
#      the pile is in equilibrium: sum (FN + Ff) = (0, 0, N m g) to tol N m g
#      and each ball's FN + Ff = (0, 0, m g) to tol m g (its acceleration is
#      zero). FN is the sum of a ball's normal forces, so ball-ball forces
#      cancel in the sums and what is left is the floor's and the walls':
#      with mu = 0 this is sum FN_z = N m g (the walls push horizontally) and
#      sum FN_x = 0 (the walls balance), checked as such; with friction the
#      walls' friction is vertical (it can carry weight, as in a silo) and
#      the floor's is horizontal (it can balance a wall), so only FN + Ff is
#      determined;
#  (d) a ball is classified by the bodies within near metres of touching it
#      (near, default 1e-6, far above the positions' error, so that a pair
#      the runtime holds in contact is never taken as apart): one touching
#      nothing has FN = Ff = 0 (to tol m g); one touching only the floor has
#      a vertical FN with FN_z >= -tol m g and Ff_z = 0, and, with mu=MU
#      (its pairs' static coefficient), |Ff| <= MU |FN| + tol m g. A ball with
#      several contacts has no check of its own: its FN and Ff are sums.
#
# -v: xw (required), r (0.05), m (1), g (9.80665), tol (1e-9), near (1e-6),
# by (0.01), rows, conserve, rest, mu, name (printed before a failure), and
# balls: "NAME:M:R ..." for balls of other masses M (kg) and radii R (m)
# than m and r (then each ball's own m g, and the pile's weight their sum).
# Each row costs O(N^2) (fine for N <= 256 at 0.01 s).
function abs(x) { return x < 0 ? -x : x }
function fail(msg) {
	printf "%srow %d, t = %s: %s\n", name == "" ? "" : name ": ", NR - 1, $1, msg
	failed = 1
	exit 1
}
function col(h) {
	if (!(h in c)) { printf "%scheck.awk: no column %s in the header\n", name == "" ? "" : name ": ", h; failed = 2; exit 2 }
	return c[h]
}
BEGIN {
	FS = ","
	if (xw == "") { print "check.awk: -v xw=... (the right wall's x) is required"; failed = 2; exit 2 }
	if (r == "") r = 0.05
	if (m == "") m = 1
	if (g == "") g = 9.80665
	if (tol == "") tol = 1e-9
	if (near == "") near = 1e-6
	if (by == "") by = 0.01
	split("x y z", ax, " ")
	split("pos v FN Ff", qs, " ")
}
NR == 1 {
	for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i }
	nb = 0
	for (i = 1; i <= NF; i++) {
		h = $i; sub(/ *\[.*$/, "", h)
		if (h ~ /\.pos\.x$/) { sub(/\.pos\.x$/, "", h); nb++; ball[nb] = h }
	}
	if (nb == 0) { print "check.awk: no NAME.pos.x column"; failed = 2; exit 2 }
	for (b = 1; b <= nb; b++)
		for (q = 1; q <= 4; q++)
			for (k = 1; k <= 3; k++) ci[b, q, k] = col(ball[b] "." qs[q] "." ax[k])
	nown = split(balls, own, " ")
	for (i = 1; i <= nown; i++) { split(own[i], f, ":"); om[f[1]] = f[2]; orr[f[1]] = f[3] }
	sumW = 0
	for (b = 1; b <= nb; b++) {
		mb[b] = ball[b] in om ? om[ball[b]] + 0 : m; rb[b] = ball[b] in orr ? orr[ball[b]] + 0 : r
		Wb[b] = mb[b] * g; sumW += Wb[b]
	}
	next
}
{
	t = $1
	if (abs(t - (NR - 2) * by) > 1e-9 * by) fail(sprintf("t = %.17g, expected %.17g (rows every %s s)", t, (NR - 2) * by, by))
	for (b = 1; b <= nb; b++) {
		x[b] = $ci[b, 1, 1]; y[b] = $ci[b, 1, 2]; z[b] = $ci[b, 1, 3]
		vx[b] = $ci[b, 2, 1]; vy[b] = $ci[b, 2, 2]; vz[b] = $ci[b, 2, 3]
		nx[b] = $ci[b, 3, 1]; ny[b] = $ci[b, 3, 2]; nz[b] = $ci[b, 3, 3]
		fx[b] = $ci[b, 4, 1]; fy[b] = $ci[b, 4, 2]; fz[b] = $ci[b, 4, 3]
		nnb[b] = 0
	}
	# (a) overlaps, and (d)'s neighbours
	for (b = 1; b <= nb; b++) {
		if (abs(y[b]) > tol || abs(vy[b]) > tol)
			fail(sprintf("%s leaves the plane y = 0: y = %.17g m, v_y = %.17g m/s", ball[b], y[b], vy[b]))
		R = rb[b]
		if (z[b] < R - tol) fail(sprintf("%s overlaps the floor: z = %.17g m < r = %s m by %.3g m", ball[b], z[b], R, R - z[b]))
		if (x[b] < R - tol) fail(sprintf("%s overlaps the wall x = 0: x = %.17g m < r = %s m by %.3g m", ball[b], x[b], R, R - x[b]))
		if (x[b] > xw - R + tol)
			fail(sprintf("%s overlaps the wall x = %s: x = %.17g m > %.17g m by %.3g m", ball[b], xw, x[b], xw - R, x[b] - xw + R))
		for (j = b + 1; j <= nb; j++) {
			dx = x[j] - x[b]; dz = z[j] - z[b]; D = R + rb[j]
			if (abs(dx) > D + near || abs(dz) > D + near) continue
			dy = y[j] - y[b]
			d = sqrt(dx * dx + dy * dy + dz * dz)
			if (d < D - tol)
				fail(sprintf("%s and %s overlap: distance %.17g m < r_i + r_j = %.17g m by %.3g m", ball[b], ball[j], d, D, D - d))
			if (d <= D + near) { nnb[b]++; nnb[j]++ }
		}
	}
	# (b) energy
	E = 0
	for (b = 1; b <= nb; b++) E += mb[b] * (vx[b] * vx[b] + vy[b] * vy[b] + vz[b] * vz[b]) / 2 + mb[b] * g * z[b]
	if (NR == 2) { E0 = E; Es = abs(E0) > 0 ? abs(E0) : 1 }
	else {
		if (E - Eprev > tol * Es)
			fail(sprintf("the energy grows: %.17g J at the row before, %.17g J now (+%.3g of |E_0| = %.17g J)", Eprev, E, (E - Eprev) / Es, Es))
		if (conserve && abs(E - E0) > tol * Es)
			fail(sprintf("the energy is not conserved: %.17g J, E_0 = %.17g J (%.3g of |E_0|)", E, E0, (E - E0) / Es))
	}
	Eprev = E
	# (c) rest
	if (rest != "" && t >= rest - 1e-9 * by) {
		for (b = 1; b <= nb; b++) {
			s = sqrt(vx[b] * vx[b] + vy[b] * vy[b] + vz[b] * vz[b])
			if (s > tol) fail(sprintf("%s is not at rest (from t = %s s): speed %.17g m/s, v = (%.17g, %.17g, %.17g)", ball[b], rest, s, vx[b], vy[b], vz[b]))
		}
		sx = sy = sz = snx = snz = 0
		for (b = 1; b <= nb; b++) { sx += nx[b] + fx[b]; sy += ny[b] + fy[b]; sz += nz[b] + fz[b]; snx += nx[b]; snz += nz[b] }
		if (mu != "" && mu + 0 == 0) {
			if (abs(snz - sumW) > tol * sumW)
				fail(sprintf("at rest the floor does not carry the pile: sum FN_z = %.17g N, N m g = %.17g N (%.3g relative)", snz, sumW, (snz - sumW) / sumW))
			if (abs(snx) > tol * sumW)
				fail(sprintf("at rest the walls do not balance: sum FN_x = %.17g N (%.3g of N m g)", snx, snx / sumW))
		}
		if (abs(sx) > tol * sumW || abs(sy) > tol * sumW || abs(sz - sumW) > tol * sumW)
			fail(sprintf("at rest the box does not carry the pile: sum (FN + Ff) = (%.17g, %.17g, %.17g) N, expected (0, 0, %.17g) N", sx, sy, sz, sumW))
		for (b = 1; b <= nb; b++)
			if (abs(nx[b] + fx[b]) > tol * Wb[b] || abs(ny[b] + fy[b]) > tol * Wb[b] || abs(nz[b] + fz[b] - Wb[b]) > tol * Wb[b])
				fail(sprintf("%s at rest is not in equilibrium: FN + Ff = (%.17g, %.17g, %.17g) N, expected (0, 0, %.17g) N; FN = (%.17g, %.17g, %.17g) N, Ff = (%.17g, %.17g, %.17g) N",
					ball[b], nx[b] + fx[b], ny[b] + fy[b], nz[b] + fz[b], Wb[b], nx[b], ny[b], nz[b], fx[b], fy[b], fz[b]))
	}
	# (d) balls whose contacts are known
	for (b = 1; b <= nb; b++) {
		R = rb[b]; W = Wb[b]
		if (nnb[b] > 0 || x[b] - R <= near || xw - x[b] - R <= near) continue
		fn = sqrt(nx[b] * nx[b] + ny[b] * ny[b] + nz[b] * nz[b]); ff = sqrt(fx[b] * fx[b] + fy[b] * fy[b] + fz[b] * fz[b])
		if (z[b] - R > near) {
			if (fn > tol * W || ff > tol * W)
				fail(sprintf("%s touches nothing (gap to the floor %.3g m) but FN = (%.17g, %.17g, %.17g) N, Ff = (%.17g, %.17g, %.17g) N",
					ball[b], z[b] - R, nx[b], ny[b], nz[b], fx[b], fy[b], fz[b]))
			continue
		}
		if (abs(nx[b]) > tol * W || abs(ny[b]) > tol * W || nz[b] < -tol * W || abs(fz[b]) > tol * W)
			fail(sprintf("%s touches only the floor but FN = (%.17g, %.17g, %.17g) N is not vertical up or Ff_z = %.17g N is not 0",
				ball[b], nx[b], ny[b], nz[b], fz[b]))
		if (mu != "" && ff > mu * fn + tol * W)
			fail(sprintf("%s touches only the floor and |Ff| = %.17g N > mu_s |FN| = %s * %.17g N = %.17g N", ball[b], ff, mu, fn, mu * fn))
	}
}
END {
	if (failed) exit failed
	if (NR < 2) { printf "%sno data rows\n", name == "" ? "" : name ": "; exit 1 }
	if (rows != "" && NR - 1 != rows) { printf "%s%d data rows, expected %d\n", name == "" ? "" : name ": ", NR - 1, rows; exit 1 }
	printf "%s%d rows of %d balls checked\n", name == "" ? "" : name ": ", NR - 1, nb
}
