/*
 * cluster.c - the clusters: the pairs in contact that share bodies, solved
 * together. Their coupling, their sorting into clusters (union-find), and
 * the direct solve of a cluster's linear system (Gaussian elimination with
 * partial pivoting, an LU factorisation in place). The force stage
 * (force.c) and the impacts (impulse.c) build the systems.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include "contact_int.h"

/*
 * Pairs in contact that share a body (a plane is no body: its mass is
 * infinite) act on each other; those that are connected so form a cluster,
 * and the clusters are independent. A cluster's contact forces are the
 * solution of one linear system: each pair's force is F = B x (x its
 * unknowns: the normal force, or with sticking friction the whole force),
 * and its equations say that the relative acceleration vanishes along E
 * (the normal, or every direction when it sticks), given the forces of the
 * others. With the bodies' inverse masses w, the coefficient of pair d's
 * unknowns in pair c's equations is E_c^T B_d times the sum, over their
 * common bodies b, of w_b s_cb s_db (s = +1 for a pair's body i, -1 for
 * j). The system is solved by Gaussian elimination with partial
 * pivoting, so that its answer does not depend on how the masses compare:
 * Gauss-Seidel sweeps, which each pair corrects in turn, converge at a rate
 * of about one part in the mass ratio per sweep (a 1e-5 kg ball between 1
 * kg ones takes 1e5 sweeps). Those sweeps remain for what the direct solve
 * does not take: a cluster of more than DIRECT_MAX unknowns (its dense
 * matrix would cost DIRECT_MAX^3/3 operations per evaluation, some 5e6 at
 * 256: a column of 100 balls stands, one of 300 does not), or one whose
 * system has no solution that neither csf_contact_solve's least-norm nor
 * force.c's complementarity problem takes. Sweeps that leave the contacts'
 * accelerations above 1e-6 of where they began mark the run's contacts
 * unsolved, and the driver stops it with a message that names the cluster
 * (csf_contacts_why).
 */

/* The bodies of pair c as state slots of their positions (j a plane: none, UINT32_MAX). */
static uint32_t body_i(const csf_contacts *cs, const cpair *c) { return I(c, POS) - cs->p->ystart; }
static uint32_t body_j(const csf_contacts *cs, const cpair *c) { return c->plane ? UINT32_MAX : J(c, POS) - cs->p->ystart; }

static uint32_t uf_root(uint32_t *uf, uint32_t x)
{
	while (uf[x] != x) x = uf[x] = uf[uf[x]];
	return x;
}

/* Sum over the common bodies of c and d of w_b s_cb s_db (above); with m NULL, w_b = 1. */
double csf_contact_coupling(const csf_contacts *cs, const cpair *c, const cpair *d, const double *m)
{
	uint32_t ci = body_i(cs, c), cj = body_j(cs, c), di = body_i(cs, d), dj = body_j(cs, d);
	double k = 0, wi = m ? inv_mass_i(c, m) : 1, wj = m ? inv_mass_j(c, m) : 1;
	if (ci == di) k += wi;
	if (ci == dj) k -= wi;
	if (cj != UINT32_MAX && cj == di) k -= wj;
	if (cj != UINT32_MAX && cj == dj) k += wj;
	return k;
}

/* The ratio of the largest mass of the bodies of pairs cl[0..np) to the smallest. */
double csf_contact_mass_ratio(const csf_contacts *cs, const uint32_t *cl, uint32_t np, const double *m)
{
	double lo = HUGE_VAL, hi = 0;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m);
		lo = csf_min(lo, wi), hi = csf_max(hi, wi);
		if (!c->plane) lo = csf_min(lo, wj), hi = csf_max(hi, wj);
	}
	return hi > 0 ? hi / lo : 1;
}

/* Records cluster cl[0..np) as the one that could not be solved (csf_contacts_why). */
void csf_contact_unsolvable(csf_contacts *cs, const uint32_t *cl, uint32_t np, const double *m)
{
	uint32_t dim = 0;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		dim += has_friction(c, m) && W(c, MODE) == STICKING ? 3 : 1;
	}
	cs->why_pair = np ? cl[0] : 0, cs->why_np = np, cs->why_big = dim > DIRECT_MAX ? DIRECT_MAX : 0;
}

void csf_contacts_why(const csf_contacts *cs, uint32_t *pair, uint32_t *np, uint32_t *big)
{
	*pair = cs->why_pair, *np = cs->why_np, *big = cs->why_big;
}

/*
 * Sorts the candidates k for which pick(k) holds into clusters: cl lists
 * them cluster by cluster, each in the order of pairs, the clusters in the
 * order of their first pair; cluster q is cl[cstart[q] .. cstart[q + 1]).
 * Returns the number of clusters. Linear in the pairs picked.
 */
uint32_t csf_contact_clusters(csf_contacts *cs, int (*pick)(const cpair *, const void *), const void *arg)
{
	uint32_t *uf = cs->uf, *cid = cs->cid, nq = 0;
	if (!cs->n) return 0;
	for (int pass = 0; pass < 2; pass++)
		for (uint32_t k = 0; k < cs->n; k++) {
			const cpair *c = &cs->pairs[k];
			if (!pick(c, arg)) continue;
			uint32_t bi = body_i(cs, c), bj = body_j(cs, c);
			if (pass == 0) {
				uf[bi] = bi, cid[bi] = UINT32_MAX;
				if (bj != UINT32_MAX) uf[bj] = bj, cid[bj] = UINT32_MAX;
			} else if (bj != UINT32_MAX) {
				uint32_t a = uf_root(uf, bi), b = uf_root(uf, bj);
				if (a != b) uf[a < b ? b : a] = a < b ? a : b;
			}
		}
	for (uint32_t k = 0; k < cs->n; k++) { /* count each cluster's pairs; the clusters numbered as met */
		const cpair *c = &cs->pairs[k];
		if (!pick(c, arg)) continue;
		uint32_t r = uf_root(uf, body_i(cs, c));
		if (cid[r] == UINT32_MAX) cid[r] = nq, cs->cstart[++nq] = 0;
		cs->cstart[cid[r] + 1]++;
	}
	cs->cstart[0] = 0;
	for (uint32_t q = 0; q < nq; q++) cs->cstart[q + 1] += cs->cstart[q];
	for (uint32_t k = 0; k < cs->n; k++) { /* cstart[q] is cluster q's cursor, then its end */
		const cpair *c = &cs->pairs[k];
		if (pick(c, arg)) cs->cl[cs->cstart[cid[uf_root(uf, body_i(cs, c))]]++] = k;
	}
	for (uint32_t q = nq; q > 0; q--) cs->cstart[q] = cs->cstart[q - 1];
	cs->cstart[0] = 0;
	return nq;
}

/*
 * The system of a statically indeterminate cluster is singular: a ball
 * resting on two others that stick, or a row of balls jammed between two
 * walls, is held by more contacts than it has directions to move in, and
 * the forces are not determined by the motion (which is). Of the forces
 * that hold it, the routine takes the least-norm solution: the smallest
 * forces that keep every contact's acceleration (or velocity) zero. It is
 * the least-squares solution of least norm, from GSL's complete orthogonal
 * decomposition (rank revealed by the pivots of a QR with column pivoting,
 * those below 1e-10 of the largest taken as zero), accepted when it solves
 * the system to 1e-9 of its sizes: a singular system that has no solution
 * (contacts that contradict each other) fails (-1).
 */
static int solve_least_norm(csf_contacts *cs, uint32_t dim, const double *K, const double *b, int check)
{
	size_t need = (size_t)dim * dim + 6 * (size_t)dim;
	if (need > cs->capls) {
		double *ls = realloc(cs->ls, need * sizeof *ls);
		if (!ls) return -1;
		cs->ls = ls, cs->capls = need;
	}
	double *A = cs->ls, *w = A + (size_t)dim * dim, colmax = 0;
	memcpy(A, K, (size_t)dim * dim * sizeof *A);
	for (uint32_t j = 0; j < dim; j++) {
		double c = 0;
		for (uint32_t i = 0; i < dim; i++) c = hypot(c, K[i * dim + j]);
		colmax = csf_max(colmax, c);
	}
	size_t perm[DIRECT_MAX], rank = 0;
	gsl_matrix_view Av = gsl_matrix_view_array(A, dim, dim);
	gsl_vector_view tq = gsl_vector_view_array(w, dim), tz = gsl_vector_view_array(w + dim, dim),
	                work = gsl_vector_view_array(w + 2 * dim, dim), res = gsl_vector_view_array(w + 3 * dim, dim),
	                bv = gsl_vector_view_array(w + 4 * dim, dim), xv = gsl_vector_view_array(cs->x, dim);
	gsl_permutation pv = { dim, perm };
	memcpy(w + 4 * dim, b, dim * sizeof *b);
	gsl_set_error_handler_off();
	if (gsl_linalg_COD_decomp_e(&Av.matrix, &tq.vector, &tz.vector, &pv, 1e-10 * colmax, &rank, &work.vector) ||
	    gsl_linalg_COD_lssolve(&Av.matrix, &tq.vector, &tz.vector, &pv, rank, &bv.vector, &xv.vector, &res.vector))
		return -1;
	double rn = 0, bn = 0, xn = 0;
	for (uint32_t i = 0; i < dim; i++) rn = hypot(rn, w[3 * dim + i]), bn = hypot(bn, b[i]), xn = hypot(xn, cs->x[i]);
	for (uint32_t i = 0; i < dim; i++)
		if (!isfinite(cs->x[i])) return -1;
	return !check || rn <= 1e-9 * csf_max(bn, colmax * xn) ? 0 : -1;
}

/* After csf_contact_solve failed: the least-squares solution of least norm of its system into cs->x. */
int csf_contact_least_squares(csf_contacts *cs, uint32_t dim)
{
	return solve_least_norm(cs, dim, cs->kb, cs->kb + (size_t)dim * dim, 0);
}

/*
 * Gaussian elimination with partial pivoting of the dim x dim system K x = b,
 * in place (the systems are small: GSL's LU costs more in its calls than in
 * its arithmetic at these sizes). Fails (-1) at a pivot not above tiny.
 */
static int solve_lu(double *K, double *b, double *x, uint32_t dim, double tiny)
{
	for (uint32_t k = 0; k < dim; k++) {
		uint32_t pr = k;
		for (uint32_t i = k + 1; i < dim; i++)
			if (fabs(K[i * dim + k]) > fabs(K[pr * dim + k])) pr = i;
		if (!(fabs(K[pr * dim + k]) > tiny)) return -1;
		if (pr != k) {
			for (uint32_t j = k; j < dim; j++) {
				double t = K[k * dim + j];
				K[k * dim + j] = K[pr * dim + j], K[pr * dim + j] = t;
			}
			double t = b[k];
			b[k] = b[pr], b[pr] = t;
		}
		for (uint32_t i = k + 1; i < dim; i++) {
			double l = K[i * dim + k] / K[k * dim + k];
			if (l == 0) continue;
			for (uint32_t j = k + 1; j < dim; j++) K[i * dim + j] -= l * K[k * dim + j];
			b[i] -= l * b[k];
		}
	}
	for (uint32_t k = dim; k-- > 0;) {
		double v = b[k];
		for (uint32_t j = k + 1; j < dim; j++) v -= K[k * dim + j] * x[j];
		x[k] = v / K[k * dim + k];
		if (!isfinite(x[k])) return -1;
	}
	return 0;
}

/*
 * Solves the system of cs->K (dim x dim, row-major) with right-hand side
 * cs->rhs into cs->x, by Gaussian elimination with partial pivoting. A
 * pivot below 1e-10 of the largest coefficient means one of two things,
 * told apart by K1, the same system with every body's mass 1 (or NULL: the
 * first). If K1 is singular too, the contacts are more than the bodies'
 * motions can tell apart (a statically indeterminate cluster, whatever the
 * masses): the least-norm solution above. If not, the masses differ by more
 * than about 1e10, and the net force on the lightest body would be the
 * difference of forces 1e10 times larger, of which rounding would take more
 * than 1e-6: it fails (-1). wratio is the ratio of the largest inverse mass
 * of the cluster's bodies to the smallest: the masses differ when it is
 * 1e6 or more. A system singular with masses that do not differ so, whose
 * least-norm solution (if any) does not solve it, is nearly singular
 * (contacts all but redundant, or sliding friction that all but cancels a
 * normal force): its elimination, pivots down to 1e-14 of the largest
 * coefficient, gives its forces, large as they may be. K, rhs and K1 are
 * destroyed.
 */
int csf_contact_solve(csf_contacts *cs, uint32_t dim, double *K1, double wratio)
{
	double *K = cs->K, *b = cs->rhs, big = 0, big1 = 0;
	for (uint32_t k = 0; k < dim * dim; k++) big = csf_max(big, fabs(K[k]));
	if (!(big > 0) || !isfinite(big)) return -1;
	size_t keep = (size_t)dim * dim + dim;
	if (keep > cs->capkb) {
		double *kb = realloc(cs->kb, keep * sizeof *kb);
		if (!kb) return -1;
		cs->kb = kb, cs->capkb = keep;
	}
	memcpy(cs->kb, K, (size_t)dim * dim * sizeof *K);
	memcpy(cs->kb + (size_t)dim * dim, b, dim * sizeof *b);
	if (!solve_lu(K, b, cs->x, dim, 1e-10 * big)) return 0;
	if (!K1) return -1;
	for (uint32_t k = 0; k < dim * dim; k++) big1 = csf_max(big1, fabs(K1[k]));
	double *b1 = cs->rhs; /* a right-hand side for K1's elimination, whose answer is not used */
	for (uint32_t k = 0; k < dim; k++) b1[k] = 1;
	int redundant = solve_lu(K1, b1, cs->x, dim, 1e-10 * big1) != 0;
	if (redundant && !solve_least_norm(cs, dim, cs->kb, cs->kb + (size_t)dim * dim, 1)) return 0;
	if (!redundant && !(wratio < 1e6)) return -1; /* the masses differ too much */
	/* nearly redundant contacts, whose forces are large (a row of balls all but jammed), or
	   sliding friction that all but cancels a normal force: the elimination's own answer */
	memcpy(K, cs->kb, (size_t)dim * dim * sizeof *K);
	memcpy(b, cs->kb + (size_t)dim * dim, dim * sizeof *b);
	return solve_lu(K, b, cs->x, dim, 1e-14 * big);
}
