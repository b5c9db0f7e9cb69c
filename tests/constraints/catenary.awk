# awk -F, -v n=N -v span=S -v L=L -v m=M -v tol=TOL -f catenary.awk out.csv - the last row of a
# chain of n rigid links (tests/constraints/gen_chain.sh) against the discrete catenary: with
# equal masses m at the joints, the horizontal tension H is the same in every link, and link j
# (from joint j-1 to joint j) descends at angle phi_j with tan phi_j = ((n - 1)/2 - (j - 1)) m g/H
# (by symmetry, the first link carries half the weight); H is the root of
# sum_j L cos(phi_j) = span, found by bisection. Every joint within tol (m). Also every row: every
# link of length L to 1e-10 relative (unless -v springs=1: a chain of springs, whose links
# stretch). Prints the largest error.
function abs(x) { return x < 0 ? -x : x }
function spanof(H,   j, s, tp) {
	s = 0
	for (j = 1; j <= n; j++) { tp = ((n - 1) / 2 - (j - 1)) * m * g / H; s += L / sqrt(1 + tp * tp) }
	return s
}
BEGIN {
	g = 9.80665; lo = 1e-9; hi = 1e9
	for (it = 0; it < 300; it++) { mid = sqrt(lo * hi); if (spanof(mid) < span) lo = mid; else hi = mid }
	H = sqrt(lo * hi); x = 0; z = 0
	for (j = 1; j < n; j++) {
		tp = ((n - 1) / 2 - (j - 1)) * m * g / H; c = 1 / sqrt(1 + tp * tp)
		x += L * c; z -= L * tp * c; X[j] = x; Z[j] = z
	}
}
NR == 1 { for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); col[h] = i } next }
{
	px = 0; pz = 0
	for (j = 1; j <= n; j++) {
		if (j < n) { qx = $col["b" j ".pos.x"]; qz = $col["b" j ".pos.z"] } else { qx = span; qz = 0 }
		d = sqrt((qx - px) ^ 2 + (qz - pz) ^ 2 + (j < n ? $col["b" j ".pos.y"] ^ 2 : 0))
		if (!springs && abs(d - L) > 1e-10 * L) { printf "FAIL: t=%s: link %d of length %.17g, not %.17g\n", $1, j, d, L; bad = 1; exit 1 }
		px = qx; pz = qz
	}
	last = $0
}
END {
	if (bad) exit 1
	nf = split(last, f, ",")
	for (j = 1; j < n; j++) {
		e = abs(f[col["b" j ".pos.x"]] - X[j]); if (abs(f[col["b" j ".pos.z"]] - Z[j]) > e) e = abs(f[col["b" j ".pos.z"]] - Z[j])
		if (e > worst) worst = e
		if (e > tol) { printf "FAIL: joint %d at (%.17g, %.17g), the catenary's (%.17g, %.17g)\n", j, f[col["b" j ".pos.x"]], f[col["b" j ".pos.z"]], X[j], Z[j]; exit 1 }
	}
	printf "catenary of %d links: H = %.15g N, worst joint %.3g m\n", n, H, worst
}
