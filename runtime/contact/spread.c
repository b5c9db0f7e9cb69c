/*
 * spread.c - the forces of a statically indeterminate cluster kept within
 * its friction cones (csf_contact_spread).
 *
 * Where a cluster's contacts are redundant (a ball sticking to two others
 * and to a wall: more unknown forces than equations) its forces are not
 * unique: a self-stress, forces that add up to zero on every body, can be
 * added to them without changing any acceleration. cluster.c takes the
 * least-norm forces (csf_contact_solve), which know nothing of the cones:
 * they may put a sticking pair's friction beyond mu_s N where other forces
 * of the same motion hold every pair. The pile is then at rest, but a
 * search for its modes found no consistent set, and the force stage then
 * failed (a Galton board's first bin, 32 contacts of balls at rest, at
 * t = 0.8268 s: one pair's least-norm friction 0.084 N for each newton of
 * its normal force, mu_s 0.05, where the complementarity problem held
 * them all).
 *
 * csf_contact_spread adds to the forces x0 the smallest self-stress (in
 * the norm of the unknowns) for which every sticking pair's friction is
 * within (1 - SPREAD_MARGIN) mu_s N and no normal force pulls: a
 * least-distance problem, min |y| with G y >= h over the self-stresses
 * Z y (Z an orthonormal basis of the null space of the map from the
 * unknowns to the forces on the bodies, from a QR factorization), solved
 * as a nonnegative least-squares problem (Lawson and Hanson, "Solving
 * Least Squares Problems", 1974, chapters 23: LDP and NNLS). A cone is met
 * by cuts: its tangent plane where the friction leaves it, added until no
 * friction does (in a scene in a plane, one cut is the cone's side).
 * Where x0 is within every cone nothing changes; the stress added grows
 * from zero as x0 leaves one, so the forces stay continuous in time.
 * Only the unknowns that share a body's coordinate with a pair outside its
 * cone (transitively) move: in a scene in a plane, the friction across it
 * is of its own and stays 0. Used where a cluster's modes are found only
 * so (modes.c), and then by the force stage for that cluster (force.c):
 * taken in every cluster, the stress added (1e-7 to 1e-6 N) changed the
 * course of make check's column of nine balls thrown at 0.35 m/s, which
 * then crawled at t = 1.18 s.
 */
#include "contact_int.h"

#include <gsl/gsl_linalg.h>

/* The cone's margin (relative to mu_s N), the rounds of cuts, and the rank threshold (relative). */
static const double SPREAD_MARGIN = 1e-9, SPREAD_RANK = 1e-10;
enum { SPREAD_ROUNDS = 16 };

/* A constraint g . x >= 0: pair a's normal force (cone 0), or its friction along d within its cone. */
typedef struct scut {
	uint32_t a;
	int cone;
	double d[3];
} scut;

typedef struct spread {
	uint32_t np, dim;
	const unsigned char *dc, *cone;
	const uint32_t *at;
	const double *B, *nv, *mu;
} spread;

static void cut_row(const spread *s, const scut *k, double *g)
{
	const double *n = s->nv + 3 * k->a;
	memset(g, 0, s->dim * sizeof *g);
	for (int q = 0; q < s->dc[k->a]; q++) {
		const double *b = s->B + 9 * k->a + 3 * q;
		double bn = dot3(n, b);
		g[s->at[k->a] + q] = k->cone ? (1 - SPREAD_MARGIN) * s->mu[k->a] * bn - dot3(k->d, b) : bn;
	}
}

/* Pair a's force at x: its normal part N and its friction f. */
static void pair_force(const spread *s, uint32_t a, const double *x, double *N, double f[3])
{
	double F[3] = { 0, 0, 0 };
	const double *n = s->nv + 3 * a;
	for (int q = 0; q < s->dc[a]; q++)
		for (int k = 0; k < 3; k++) F[k] += s->B[9 * a + 3 * q + k] * x[s->at[a] + q];
	*N = dot3(F, n);
	for (int k = 0; k < 3; k++) f[k] = F[k] - *N * n[k];
}

/* Beyond its cone less the margin (and the rounding of a friction set on it: 1e-12 of it)? */
static int beyond(const double f[3], double N, double mu) { return mag3(f) > (1 - SPREAD_MARGIN + 1e-12) * mu * N; }

/* Is pair a (a sticking pair with friction) beyond its cone, less the margin, at x? */
static int outside(const spread *s, uint32_t a, const double *x, double *N, double f[3])
{
	pair_force(s, a, x, N, f);
	return beyond(f, *N, s->mu[a]);
}

/*
 * Nonnegative least squares (Lawson and Hanson's NNLS): u >= 0 minimizing
 * |E u - f|, E rows x n (row-major). 0, or -1 (no progress: rounding).
 */
static int nnls(uint32_t rows, uint32_t n, const double *E, const double *f, double *u)
{
	unsigned char *pas = calloc(n, 1);
	uint32_t *idx = malloc(n * sizeof *idx);
	double *r = malloc(rows * sizeof *r), *z = malloc(n * sizeof *z);
	gsl_matrix *A = gsl_matrix_alloc(rows, n);
	gsl_vector *tau = gsl_vector_alloc(csf_min(rows, n) ? (size_t)csf_min(rows, n) : 1), *b = gsl_vector_alloc(rows);
	gsl_vector *sol = gsl_vector_alloc(n), *res = gsl_vector_alloc(rows);
	int rc = -1;
	if (!pas || !idx || !r || !z || !A || !tau || !b || !sol || !res) goto out;
	double fn = 0, en = 0;
	for (uint32_t i = 0; i < rows; i++) fn = csf_max(fn, fabs(f[i]));
	for (size_t k = 0; k < (size_t)rows * n; k++) en = csf_max(en, fabs(E[k]));
	for (uint32_t j = 0; j < n; j++) u[j] = 0;
	for (uint32_t outer = 0; outer < 3 * n + 3; outer++) {
		for (uint32_t i = 0; i < rows; i++) {
			r[i] = f[i];
			for (uint32_t j = 0; j < n; j++) r[i] -= E[(size_t)i * n + j] * u[j];
		}
		long t = -1;
		double wmax = 1e-13 * en * csf_max(fn, 1e-300);
		for (uint32_t j = 0; j < n; j++) {
			if (pas[j]) continue;
			double w = 0;
			for (uint32_t i = 0; i < rows; i++) w += E[(size_t)i * n + j] * r[i];
			if (w > wmax) wmax = w, t = j;
		}
		if (t < 0) {
			rc = 0;
			goto out;
		}
		pas[t] = 1;
		for (uint32_t inner = 0; inner < 3 * n + 3; inner++) {
			uint32_t p = 0;
			for (uint32_t j = 0; j < n; j++)
				if (pas[j]) idx[p++] = j;
			if (p > rows) goto out;
			if (!p) { /* every variable left the passive set: u = 0 solves it (no columns to factor) */
				for (uint32_t j = 0; j < n; j++) u[j] = 0;
				break;
			}
			gsl_matrix_view Av = gsl_matrix_submatrix(A, 0, 0, rows, p);
			for (uint32_t i = 0; i < rows; i++) {
				gsl_vector_set(b, i, f[i]);
				for (uint32_t c = 0; c < p; c++) gsl_matrix_set(&Av.matrix, i, c, E[(size_t)i * n + idx[c]]);
			}
			gsl_vector_view tv = gsl_vector_subvector(tau, 0, p), sv = gsl_vector_subvector(sol, 0, p);
			if (gsl_linalg_QR_decomp(&Av.matrix, &tv.vector) ||
			    gsl_linalg_QR_lssolve(&Av.matrix, &tv.vector, b, &sv.vector, res))
				goto out;
			for (uint32_t j = 0; j < n; j++) z[j] = 0;
			int positive = 1;
			for (uint32_t c = 0; c < p; c++) {
				z[idx[c]] = gsl_vector_get(&sv.vector, c);
				if (!isfinite(z[idx[c]])) goto out;
				positive &= z[idx[c]] > 0;
			}
			if (positive) {
				memcpy(u, z, n * sizeof *u);
				break;
			}
			double alpha = 1;
			for (uint32_t c = 0; c < p; c++) {
				uint32_t j = idx[c];
				if (z[j] <= 0) alpha = csf_min(alpha, u[j] / (u[j] - z[j]));
			}
			for (uint32_t j = 0; j < n; j++) {
				u[j] += alpha * (z[j] - u[j]);
				if (pas[j] && !(u[j] > 0)) pas[j] = 0, u[j] = 0;
			}
			if (inner == 3 * n + 2) goto out;
		}
	}
out:
	free(pas);
	free(idx);
	free(r);
	free(z);
	if (A) gsl_matrix_free(A);
	if (tau) gsl_vector_free(tau);
	if (b) gsl_vector_free(b);
	if (sol) gsl_vector_free(sol);
	if (res) gsl_vector_free(res);
	return rc;
}

static int cmp_u32(const void *a, const void *b)
{
	uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
	return (x > y) - (x < y);
}

/*
 * The forces x (dim unknowns: pair a's from at[a], dc[a] of them, along
 * B's columns; its normal nv) of cluster cl[0..np), in which the pairs
 * with cone[a] stick: where one's friction is beyond mu_s N, the smallest
 * self-stress that brings every one within and leaves no normal force
 * pulling, added to x (the header). Returns 0 (nothing to do), 1 (x
 * changed), or -1 (no self-stress does it: x as it was).
 */
int csf_contact_spread(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, uint32_t dim,
                       const unsigned char *dc, const uint32_t *at, const double *B, const double *nv,
                       const unsigned char *cone, double *x)
{
	double N, f[3];
	int any = 0;
	spread s0 = { np, dim, dc, cone, at, B, nv, NULL };
	double Nbig = 0; /* the largest normal force: one below -1e-9 of it pulls */
	for (uint32_t a = 0; a < np; a++)
		if (dc[a]) pair_force(&s0, a, x, &N, f), Nbig = csf_max(Nbig, fabs(N));
	for (uint32_t a = 0; a < np && !any; a++) {
		if (!dc[a]) continue;
		pair_force(&s0, a, x, &N, f);
		any = N < -1e-9 * Nbig || (cone[a] && dc[a] > 1 && beyond(f, N, mu_s(&cs->pairs[cl[a]], m)));
	}
	if (!any) return 0;
	int rc = -1, copied = 0;
	uint32_t ncut = 0, nrows = 0;
	/* the body coordinates the unknowns act on: their slots, sorted (the rows of the map) */
	uint32_t *slot = malloc(6 * (size_t)np * sizeof *slot), *up = malloc(((size_t)dim + 6 * (size_t)np) * sizeof *up);
	uint32_t *col = malloc(dim * sizeof *col), *cidx = malloc(dim * sizeof *cidx), *row = malloc(6 * (size_t)np * sizeof *row);
	double *mu = malloc(np * sizeof *mu), *x0 = malloc(dim * sizeof *x0), *g = malloc(dim * sizeof *g);
	scut *cut = malloc((size_t)(SPREAD_ROUNDS * np + 1) * sizeof *cut);
	unsigned char *mark = malloc((size_t)dim + 6 * (size_t)np);
	double *Z = NULL, *E = NULL, *fv = NULL, *u = NULL, *rr = NULL;
	gsl_matrix *Jt = NULL, *Q = NULL, *R = NULL;
	gsl_vector *tau = NULL, *norm = NULL;
	gsl_permutation *perm = NULL;
	if (!slot || !up || !col || !cidx || !row || !mu || !x0 || !g || !cut || !mark) goto out;
	spread s = { np, dim, dc, cone, at, B, nv, mu };
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		mu[a] = mu_s(c, m);
		for (int k = 0; k < 3; k++) {
			slot[nrows++] = I(c, A) + (uint32_t)k;
			if (!c->plane) slot[nrows++] = J(c, A) + (uint32_t)k;
		}
	}
	qsort(slot, nrows, sizeof *slot, cmp_u32);
	uint32_t nr = 0;
	for (uint32_t k = 0; k < nrows; k++)
		if (!nr || slot[k] != slot[nr - 1]) slot[nr++] = slot[k];
	/* the unknowns joined through the coordinates they act on (a non-zero coefficient) */
	for (uint32_t k = 0; k < dim + nr; k++) up[k] = k;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		for (int side = 0; side < 2 - (int)(c->plane != 0); side++)
			for (int k = 0; k < 3; k++) {
				uint32_t sl = (side ? J(c, A) : I(c, A)) + (uint32_t)k;
				uint32_t *hit = bsearch(&sl, slot, nr, sizeof *slot, cmp_u32), ri = (uint32_t)(hit - slot);
				for (int q = 0; q < dc[a]; q++) {
					if (B[9 * a + 3 * q + k] == 0) continue;
					uint32_t x1 = csf_uf_root(up, at[a] + (uint32_t)q), x2 = csf_uf_root(up, dim + ri);
					if (x1 != x2) up[x1] = x2;
				}
			}
	}
	/* the parts with a pair beyond its cone or pulling: of its unknowns, those along its normal or its
	   friction (in a scene in a plane, not the friction across it, which is a part of its own) */
	memset(mark, 0, (size_t)dim + 6 * (size_t)np);
	for (uint32_t a = 0; a < np; a++) {
		if (!dc[a]) continue;
		pair_force(&s, a, x, &N, f);
		int pulls = N < -1e-9 * Nbig;
		if (pulls || (cone[a] && dc[a] > 1 && outside(&s, a, x, &N, f)))
			for (int q = 0; q < dc[a]; q++) {
				const double *b = B + 9 * a + 3 * q;
				if (dot3(b, nv + 3 * a) != 0 || dot3(b, f) != 0) mark[csf_uf_root(up, at[a] + (uint32_t)q)] = 1;
			}
	}
	uint32_t nc = 0, nrc = 0;
	for (uint32_t k = 0; k < dim; k++)
		if (mark[csf_uf_root(up, k)]) cidx[k] = nc, col[nc++] = k;
		else cidx[k] = UINT32_MAX;
	for (uint32_t k = 0; k < nr; k++) row[k] = UINT32_MAX;
	for (uint32_t k = 0; k < nr; k++)
		if (mark[csf_uf_root(up, dim + k)]) row[k] = nrc++;
	if (!nc || !nrc) goto out;
	/* J^T (the unknowns' forces on the coordinates), its QR factorization: Q's last columns beyond
	   its rank are the self-stresses */
	Jt = gsl_matrix_calloc(nc, nrc), Q = gsl_matrix_alloc(nc, nc), R = gsl_matrix_alloc(nc, nrc);
	tau = gsl_vector_alloc(csf_min(nc, nrc)), norm = gsl_vector_alloc(nrc), perm = gsl_permutation_alloc(nrc);
	if (!Jt || !Q || !R || !tau || !norm || !perm) goto out;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		for (int side = 0; side < 2 - (int)(c->plane != 0); side++)
			for (int k = 0; k < 3; k++) {
				uint32_t sl = (side ? J(c, A) : I(c, A)) + (uint32_t)k;
				uint32_t *hit = bsearch(&sl, slot, nr, sizeof *slot, cmp_u32), ri = row[hit - slot];
				for (int q = 0; q < dc[a]; q++) {
					uint32_t ck = cidx[at[a] + q];
					if (ck == UINT32_MAX || ri == UINT32_MAX) continue;
					double v = B[9 * a + 3 * q + k];
					*gsl_matrix_ptr(Jt, ck, ri) += side ? -v : v;
				}
			}
	}
	int signum;
	if (gsl_linalg_QRPT_decomp(Jt, tau, perm, &signum, norm) || gsl_linalg_QR_unpack(Jt, tau, Q, R)) goto out;
	uint32_t rank = 0, dmin = csf_min(nc, nrc);
	double r0 = dmin ? fabs(gsl_matrix_get(R, 0, 0)) : 0;
	while (rank < dmin && fabs(gsl_matrix_get(R, rank, rank)) > SPREAD_RANK * r0) rank++;
	uint32_t nz = nc - rank;
	if (!nz) goto out;
	Z = malloc((size_t)nc * nz * sizeof *Z);
	uint32_t maxcuts = SPREAD_ROUNDS * np + 1;
	E = malloc((size_t)(nz + 1) * maxcuts * sizeof *E), fv = malloc((nz + 1) * sizeof *fv);
	u = malloc(maxcuts * sizeof *u), rr = malloc((nz + 1) * sizeof *rr);
	if (!Z || !E || !fv || !u || !rr) goto out;
	for (uint32_t i = 0; i < nc; i++)
		for (uint32_t j = 0; j < nz; j++) Z[(size_t)i * nz + j] = gsl_matrix_get(Q, i, rank + j);
	memcpy(x0, x, dim * sizeof *x0);
	copied = 1;
	for (int round = 0; round < SPREAD_ROUNDS; round++) {
		/* the cuts the forces now break: a cone left (its tangent at the friction), a normal force
		   that pulls (beyond the rounding of the largest) */
		double Nnow = 0;
		for (uint32_t a = 0; a < np; a++)
			if (dc[a]) pair_force(&s, a, x, &N, f), Nnow = csf_max(Nnow, fabs(N));
		uint32_t added = 0;
		for (uint32_t a = 0; a < np && ncut < maxcuts; a++) {
			int moves = 0; /* a pair none of whose unknowns move keeps its forces */
			for (int q = 0; q < dc[a]; q++) moves |= cidx[at[a] + q] != UINT32_MAX;
			if (!moves) continue;
			if (cone[a] && dc[a] > 1 && outside(&s, a, x, &N, f) && mag3(f) > 0) {
				cut[ncut].a = a, cut[ncut].cone = 1;
				double fm = mag3(f);
				for (int k = 0; k < 3; k++) cut[ncut].d[k] = f[k] / fm;
				ncut++, added++;
			}
			pair_force(&s, a, x, &N, f);
			if (N < -1e-12 * Nnow && ncut < maxcuts) cut[ncut].a = a, cut[ncut].cone = 0, ncut++, added++;
		}
		if (!added) {
			rc = round > 0;
			goto out;
		}
		/* the least-distance problem: min |y|, G y >= h with G = g Z, h = -g . x0; as NNLS, E =
		   (G^T; h^T), f = (0 .. 0, 1) */
		for (uint32_t k = 0; k < ncut; k++) {
			cut_row(&s, &cut[k], g);
			double h = 0;
			for (uint32_t i = 0; i < dim; i++) h -= g[i] * x0[i];
			for (uint32_t j = 0; j < nz; j++) {
				double v = 0;
				for (uint32_t i = 0; i < nc; i++) v += g[col[i]] * Z[(size_t)i * nz + j];
				E[(size_t)j * ncut + k] = v;
			}
			E[(size_t)nz * ncut + k] = h;
		}
		for (uint32_t j = 0; j < nz; j++) fv[j] = 0;
		fv[nz] = 1;
		if (nnls(nz + 1, ncut, E, fv, u)) goto out;
		for (uint32_t j = 0; j <= nz; j++) {
			rr[j] = -fv[j];
			for (uint32_t k = 0; k < ncut; k++) rr[j] += E[(size_t)j * ncut + k] * u[k];
		}
		if (!(-rr[nz] > 1e-12)) goto out; /* infeasible: no self-stress holds them */
		memcpy(x, x0, dim * sizeof *x);
		for (uint32_t i = 0; i < nc; i++) {
			double v = 0;
			for (uint32_t j = 0; j < nz; j++) v += Z[(size_t)i * nz + j] * (rr[j] / -rr[nz]);
			x[col[i]] += v;
		}
	}
out:
	if (rc < 0 && copied) memcpy(x, x0, dim * sizeof *x);
	free(slot);
	free(up);
	free(mark);
	free(rr);
	free(col);
	free(cidx);
	free(row);
	free(mu);
	free(g);
	free(cut);
	free(Z);
	free(E);
	free(fv);
	free(u);
	if (Jt) gsl_matrix_free(Jt);
	if (Q) gsl_matrix_free(Q);
	if (R) gsl_matrix_free(R);
	if (tau) gsl_vector_free(tau);
	if (norm) gsl_vector_free(norm);
	if (perm) gsl_permutation_free(perm);
	free(x0);
	return rc;
}
