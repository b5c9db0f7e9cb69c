# tests/piles/galton.awk - every row of a Galton board's CSV (bench/gen_galton.sh,
# watching at least pos and v of its balls bK) against what holds for any
# correct answer.
#
# geom (required) is the scene's "# galton: ..." line without its prefix:
# n, rows, r, m, rp, rho, nd, dx, dz, h, zb, w as gen_galton.sh writes them.
# From it: the floor z = 0, the walls x = 0 and x = w, divider i = 1 .. rows
# (nd disks of radius rho at x = i dx, z = rho (2 J + 1), J = 0 .. nd - 1;
# its top h is the last one's centre), and peg j of row k (k = 0 .. rows - 1,
# j = 0 .. k), a disk of radius rp at (w/2 + (j - k/2) dx, zb + (rows - 1 -
# k) dz).
# At every row, in this order, the first miss stops the check with exit 1 and
# one line naming the row, the bodies and the numbers:
#  (t) the rows are t = k by (to 1e-9 by); at the end there are `rows_out`
#      of them when rows_out is given, and every ball bK (K = 0 .. n - 1) has
#      its columns;
#  (a) nothing overlaps by more than tol metres: ball to ball |p_i - p_j| >=
#      2 r - tol; ball to peg >= r + rp - tol; ball to a divider's disk >=
#      r + rho - tol; ball to floor z >= r - tol; to the walls
#      r - tol <= x <= w - r + tol; every ball stays in the plane: |y|, |v_y|
#      <= tol;
#  (b) the energy E = sum m (|v|^2/2 + g z) never grows from one row to the
#      next by more than tol |E_0|;
#  (c) at the last row: every ball is at rest (speed <= tol m/s), inside a
#      bin (its centre between the lines of the bin's two walls, and no
#      higher than the dividers' top h: not on a divider), and held up: on
#      the floor (z - r <= near), on a ball below it (centres within 2 r +
#      near, the other's lower) or against a divider's disk (within near; a
#      ball can rest in the notch between two of them). The count of balls in
#      each bin is printed; their sum is n.
#
# -v: geom (required), g (9.80665), tol (1e-9), near (1e-6), by (0.01),
# rows_out, name (printed before a failure). Each row costs O(n^2 + n rows^2).
function abs(x) { return x < 0 ? -x : x }
function fail(msg) {
	printf "%srow %d, t = %s: %s\n", name == "" ? "" : name ": ", NR - 1, $1, msg
	failed = 1
	exit 1
}
function bad(msg) { printf "%sgalton.awk: %s\n", name == "" ? "" : name ": ", msg; failed = 2; exit 2 }
function col(h) {
	if (!(h in c)) bad("no column " h " in the header")
	return c[h]
}
# the gap between ball b and the nearest disk of the divider nearest it (only
# that divider can be within r: they are dx > 2 (r + rho) apart), or 1 when
# it is not near one; sets di, dj (which)
function divgap(b,   i, j, j0, ddx, ddz, d, best) {
	i = int(x[b] / dx + 0.5); best = 1
	if (i < 1 || i > nrow) return best
	j0 = int((z[b] / rho - 1) / 2 + 0.5)
	for (j = j0 - 1; j <= j0 + 1; j++) {
		if (j < 0 || j >= nd) continue
		ddx = x[b] - i * dx; ddz = z[b] - rho * (2 * j + 1)
		d = sqrt(ddx * ddx + ddz * ddz) - r - rho
		if (d < best) { best = d; di = i; dj = j }
	}
	return best
}
BEGIN {
	FS = ","
	if (geom == "") bad("-v geom=... (the scene's \"# galton:\" line) is required")
	ng = split(geom, gw, " ")
	for (i = 1; i <= ng; i++) { split(gw[i], kv, "="); G[kv[1]] = kv[2] + 0 }
	split("n rows r m rp rho nd dx dz h zb w", need, " ")
	for (i in need) if (!(need[i] in G)) bad("geom has no " need[i])
	n = G["n"]; nrow = G["rows"]; r = G["r"]; m = G["m"]; rp = G["rp"]; rho = G["rho"]; nd = G["nd"]
	dx = G["dx"]; dz = G["dz"]; h = G["h"]; zb = G["zb"]; w = G["w"]
	if (g == "") g = 9.80665
	if (tol == "") tol = 1e-9
	if (near == "") near = 1e-6
	if (by == "") by = 0.01
	np = 0
	for (k = 0; k < nrow; k++)
		for (j = 0; j <= k; j++) { np++; pegx[np] = w / 2 + (j - k / 2) * dx; pegz[np] = zb + (nrow - 1 - k) * dz; pegn[np] = "p" (np - 1) }
}
NR == 1 {
	for (i = 1; i <= NF; i++) { hd = $i; sub(/ *\[.*$/, "", hd); c[hd] = i }
	split("x y z", ax, " ")
	for (b = 1; b <= n; b++)
		for (k = 1; k <= 3; k++) { cp[b, k] = col("b" (b - 1) ".pos." ax[k]); cv[b, k] = col("b" (b - 1) ".v." ax[k]) }
	next
}
{
	t = $1
	if (abs(t - (NR - 2) * by) > 1e-9 * by) fail(sprintf("t = %.17g, expected %.17g (rows every %s s)", t, (NR - 2) * by, by))
	for (b = 1; b <= n; b++) {
		x[b] = $cp[b, 1]; y[b] = $cp[b, 2]; z[b] = $cp[b, 3]
		vx[b] = $cv[b, 1]; vy[b] = $cv[b, 2]; vz[b] = $cv[b, 3]
	}
	# (a) overlaps
	for (b = 1; b <= n; b++) {
		bn = "b" (b - 1)
		if (abs(y[b]) > tol || abs(vy[b]) > tol)
			fail(sprintf("%s leaves the plane y = 0: y = %.17g m, v_y = %.17g m/s", bn, y[b], vy[b]))
		if (z[b] < r - tol) fail(sprintf("%s overlaps the floor: z = %.17g m < r = %s m by %.3g m", bn, z[b], r, r - z[b]))
		if (x[b] < r - tol) fail(sprintf("%s overlaps the wall x = 0: x = %.17g m < r by %.3g m", bn, x[b], r - x[b]))
		if (x[b] > w - r + tol) fail(sprintf("%s overlaps the wall x = %s: x = %.17g m by %.3g m", bn, w, x[b], x[b] - w + r))
		d = divgap(b)
		if (d < -tol)
			fail(sprintf("%s overlaps divider %d's disk d%d_%d at (%.17g, %.17g) m: at (%.17g, %.17g) m, gap %.3g m", bn, di, di, dj, di * dx, rho * (2 * dj + 1), x[b], z[b], d))
		for (p = 1; p <= np; p++) {
			ddx = x[b] - pegx[p]; ddz = z[b] - pegz[p]
			if (abs(ddx) > r + rp || abs(ddz) > r + rp) continue
			d = sqrt(ddx * ddx + ddz * ddz)
			if (d < r + rp - tol)
				fail(sprintf("%s overlaps peg %s at (%.17g, %.17g) m: distance %.17g m < r + rp = %.17g m by %.3g m", bn, pegn[p], pegx[p], pegz[p], d, r + rp, r + rp - d))
		}
		for (j = b + 1; j <= n; j++) {
			ddx = x[j] - x[b]; ddz = z[j] - z[b]
			if (abs(ddx) > 2 * r || abs(ddz) > 2 * r) continue
			ddy = y[j] - y[b]
			d = sqrt(ddx * ddx + ddy * ddy + ddz * ddz)
			if (d < 2 * r - tol)
				fail(sprintf("%s and b%d overlap: distance %.17g m < 2 r = %.17g m by %.3g m", bn, j - 1, d, 2 * r, 2 * r - d))
		}
	}
	# (b) energy
	E = 0
	for (b = 1; b <= n; b++) E += m * ((vx[b] * vx[b] + vy[b] * vy[b] + vz[b] * vz[b]) / 2 + g * z[b])
	if (NR == 2) { E0 = E; Es = abs(E0) > 0 ? abs(E0) : 1 }
	else if (E - Eprev > tol * Es)
		fail(sprintf("the energy grows: %.17g J at the row before, %.17g J now (+%.3g of |E_0| = %.17g J)", Eprev, E, (E - Eprev) / Es, Es))
	Eprev = E
}
END {
	if (failed) exit failed
	if (NR < 2) { printf "%sno data rows\n", name == "" ? "" : name ": "; exit 1 }
	if (rows_out != "" && NR - 1 != rows_out) { printf "%s%d data rows, expected %d\n", name == "" ? "" : name ": ", NR - 1, rows_out; exit 1 }
	# (c) the last row: at rest, in a bin, held up
	for (i = 0; i <= nrow; i++) inbin[i] = 0
	for (b = 1; b <= n; b++) {
		bn = "b" (b - 1)
		s = sqrt(vx[b] * vx[b] + vy[b] * vy[b] + vz[b] * vz[b])
		if (s > tol) { fail(sprintf("%s is not at rest at the end: speed %.17g m/s, v = (%.17g, %.17g, %.17g), at (%.17g, %.17g) m", bn, s, vx[b], vy[b], vz[b], x[b], z[b])); exit 1 }
		i = int(x[b] / dx)
		if (i < 0 || i > nrow || z[b] > h) {
			fail(sprintf("%s is not inside a bin at the end: at (%.17g, %.17g) m (the dividers stand at x = k %s m and end at z = %.17g m)", bn, x[b], z[b], dx, h))
			exit 1
		}
		held = z[b] - r <= near || divgap(b) <= near
		for (j = 1; j <= n && !held; j++) {
			if (j == b || z[j] >= z[b]) continue
			ddx = x[j] - x[b]; ddz = z[j] - z[b]
			if (sqrt(ddx * ddx + ddz * ddz) <= 2 * r + near) held = 1
		}
		if (!held) { fail(sprintf("%s is at rest but neither on the floor nor on a ball: at (%.17g, %.17g) m", bn, x[b], z[b])); exit 1 }
		inbin[i]++
	}
	line = ""; tot = 0
	for (i = 0; i <= nrow; i++) { line = line " " inbin[i]; tot += inbin[i] }
	printf "%s%d rows of %d balls checked; at rest in the bins:%s (%d)\n", name == "" ? "" : name ": ", NR - 1, n, line, tot
}
