/*
 * lemke.c - Lemke's complementary pivoting method for a linear
 * complementarity problem: given M (n x n) and q, find z with
 *
 *   w = M z + q >= 0,   z >= 0,   w . z = 0.
 *
 * The method (Lemke 1965; Cottle, Pang and Stone, "The Linear
 * Complementarity Problem", 1992, section 4.4) adds an artificial variable
 * z0 with covering vector 1, w = M z + q + z0 1, which makes z = 0, z0 =
 * -min q a solution of the enlarged problem, and follows the path of
 * almost complementary basic solutions from there: each pivot brings in
 * the complement of the variable that left, until z0 leaves (a solution)
 * or no row limits the entering variable (a secondary ray: the method
 * finds no solution, which for the contact problems means none may exist,
 * or the matrix is not of a class it is sure to solve). The tableau is
 * dense, n rows of 2n + 2 columns: w, z, z0 and the right-hand side.
 * Among rows that tie in the ratio test (a degenerate step, common where
 * contacts are redundant), z0's row leaves first, and otherwise the
 * lexicographic rule decides (prefer); the pivots are bounded too.
 *
 * csf_lcp_solve takes the method's answer, and where it ends on a ray,
 * that of M + e I, e = csf_lcp_shift times M's largest entry: a copositive M
 * (as the contact problems' pyramid of pairs at rest, z . M z >= 0 for z
 * >= 0) is then strictly copositive, for which the method ends in a
 * solution for every q (Cottle, Pang and Stone, 3.8 and 4.4). An unknown
 * on which no row depends (a force that moves nothing) is brought in with
 * nothing to limit it and ends the method on a ray, though the problem
 * may have a solution, which the shift finds (tests/unit/test_lcp.c); the
 * clusters of about 50 pairs of a Galton board's bins (balls on dividers,
 * pegs and each other, 160 to 226 unknowns) ended on rays after some 300
 * pivots, double or long double alike, and no longer do. The shifted
 * answer solves a problem within e of the one asked, so it is a guess,
 * which its caller checks (modes.c: the modes it gives are taken only
 * where the cluster's exact system agrees).
 */
#include "contact_int.h"

/* Divides row r of the tableau T (rows of width wd) by its entry in column c and clears column c elsewhere. */
static void pivot(double *T, uint32_t n, uint32_t wd, uint32_t r, uint32_t c)
{
	double *tr = T + (size_t)r * wd, p = tr[c];
	for (uint32_t k = 0; k < wd; k++) tr[k] /= p;
	tr[c] = 1;
	for (uint32_t i = 0; i < n; i++) {
		double *ti = T + (size_t)i * wd, f = ti[c];
		if (i == r || f == 0) continue;
		for (uint32_t k = 0; k < wd; k++) ti[k] -= f * tr[k];
		ti[c] = 0;
	}
}

/*
 * Of rows i and j, tied in the ratio test for column c: is i the one to
 * leave? z0's row first (a solution); otherwise the lexicographic rule:
 * the rows of the basis's inverse (the tableau's w columns) over their
 * pivots, compared entry by entry, the smaller first, which never returns
 * to a basis and so ends every degenerate cycle (Cottle, Pang and Stone,
 * 4.9).
 */
static int prefer(const double *T, uint32_t n, uint32_t wd, uint32_t c, const uint32_t *basis, uint32_t i, uint32_t j)
{
	if (basis[j] == 2 * n) return 0;
	if (basis[i] == 2 * n) return 1;
	const double *ti = T + (size_t)i * wd, *tj = T + (size_t)j * wd;
	for (uint32_t k = 0; k < n; k++) {
		double x = ti[k] / ti[c], y = tj[k] / tj[c];
		if (fabs(x - y) > 1e-12 * csf_max(fabs(x), fabs(y))) return x < y;
	}
	return 0;
}

size_t csf_lcp_work(uint32_t n) { return (size_t)n * (2 * (size_t)n + 2); }

/* The shift of csf_lcp_solve's second try, relative to M's largest entry (1e-12 left a
   third of the Galton board's rays; 1e-9 and 1e-6 none). */
const double csf_lcp_shift = 1e-9;

/* Lemke's method on M + shift I. */
static int lemke(uint32_t n, const double *M, double shift, const double *q, double *z, double *T, uint32_t *basis)
{
	const uint32_t wd = 2 * n + 2, z0 = 2 * n, rhs = 2 * n + 1;
	uint32_t r = 0;
	for (uint32_t i = 0; i < n; i++) z[i] = 0;
	for (uint32_t i = 1; i < n; i++)
		if (q[i] < q[r]) r = i;
	if (!n || q[r] >= 0) return 0; /* z = 0 */
	memset(T, 0, csf_lcp_work(n) * sizeof *T);
	for (uint32_t i = 0; i < n; i++) {
		double *ti = T + (size_t)i * wd;
		ti[i] = 1;
		for (uint32_t j = 0; j < n; j++) ti[n + j] = -M[(size_t)i * n + j];
		ti[n + i] -= shift;
		ti[z0] = -1;
		ti[rhs] = q[i];
		basis[i] = i;
	}
	/* w = M z + q + z0: z0 enters at -min q, and the w that it makes zero leaves */
	pivot(T, n, wd, r, z0);
	uint32_t leaving = basis[r];
	basis[r] = z0;
	for (uint32_t step = 0; step < 50 * n + 50; step++) {
		uint32_t col = leaving < n ? leaving + n : leaving - n; /* the complement of the one that left */
		double big = 0;
		for (uint32_t i = 0; i < n; i++) big = csf_max(big, fabs(T[(size_t)i * wd + col]));
		long row = -1;
		double best = 0;
		for (uint32_t i = 0; i < n; i++) {
			double a = T[(size_t)i * wd + col];
			if (!(a > 1e-11 * big)) continue;
			double ratio = csf_max(T[(size_t)i * wd + rhs] / a, 0); /* (rounding below zero: degenerate) */
			int tie = row >= 0 && fabs(ratio - best) <= 1e-12 * csf_max(fabs(best), 1e-300);
			if (row >= 0 && !tie && ratio > best) continue;
			if (tie && !prefer(T, n, wd, col, basis, i, (uint32_t)row)) continue;
			row = i, best = ratio;
		}
		if (row < 0) return -1; /* a secondary ray */
		pivot(T, n, wd, (uint32_t)row, col);
		leaving = basis[row];
		basis[row] = col;
		if (leaving == z0) {
			for (uint32_t i = 0; i < n; i++)
				if (basis[i] >= n && basis[i] < 2 * n) z[basis[i] - n] = csf_max(T[(size_t)i * wd + rhs], 0);
			return 0;
		}
	}
	return -1;
}

int csf_lcp_lemke(uint32_t n, const double *M, const double *q, double *z, double *T, uint32_t *basis)
{
	return lemke(n, M, 0, q, z, T, basis);
}

int csf_lcp_solve(uint32_t n, const double *M, const double *q, double *z, double *T, uint32_t *basis)
{
	if (!lemke(n, M, 0, q, z, T, basis)) return 0;
	double big = 0;
	for (size_t k = 0; k < (size_t)n * n; k++) big = csf_max(big, fabs(M[k]));
	return big > 0 && !lemke(n, M, csf_lcp_shift * big, q, z, T, basis) ? 1 : -1;
}
