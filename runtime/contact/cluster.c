/*
 * cluster.c - the clusters: the pairs in contact that share bodies, solved
 * together. Their coupling, their sorting into clusters (union-find), and
 * the direct solve of a cluster's linear system (Gaussian elimination with
 * partial pivoting, an LU factorisation in place). The force stage
 * (force.c) and the impacts (impulse.c) build the systems.
 */
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
 * does not take: a cluster of more than DIRECT_MAX unknowns (its matrix
 * would cost DIRECT_MAX^3 operations per evaluation), or a singular one (a
 * body held by more contacts than it has directions, whose forces are not
 * determined: the sweeps find one of the answers). Sweeps that leave the
 * contacts' accelerations above 1e-6 of where they began (masses that
 * differ by more than the direct solve takes) mark the run's contacts
 * unsolved, and the driver stops it with a message.
 */

/* The bodies of pair c as state slots of their positions (j a plane: none, UINT32_MAX). */
static uint32_t body_i(const csf_contacts *cs, const cpair *c) { return I(c, POS) - cs->p->ystart; }
static uint32_t body_j(const csf_contacts *cs, const cpair *c) { return c->plane ? UINT32_MAX : J(c, POS) - cs->p->ystart; }

static uint32_t uf_root(uint32_t *uf, uint32_t x)
{
	while (uf[x] != x) x = uf[x] = uf[uf[x]];
	return x;
}

/* Sum over the common bodies of c and d of w_b s_cb s_db (above). */
double csf_contact_coupling(const csf_contacts *cs, const cpair *c, const cpair *d, const double *m)
{
	uint32_t ci = body_i(cs, c), cj = body_j(cs, c), di = body_i(cs, d), dj = body_j(cs, d);
	double k = 0;
	if (ci == di) k += inv_mass_i(c, m);
	if (ci == dj) k -= inv_mass_i(c, m);
	if (cj != UINT32_MAX && cj == di) k -= inv_mass_j(c, m);
	if (cj != UINT32_MAX && cj == dj) k += inv_mass_j(c, m);
	return k;
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
 * Solves the system of cs->K (dim x dim, row-major) with right-hand side
 * cs->rhs into cs->x. Fails (-1) when it is singular: a pivot below 1e-10
 * of the largest coefficient. Past that the cluster's masses differ by more
 * than about 1e10, and the net force on its lightest body is the difference
 * of forces 1e10 times larger: rounding would take more than 1e-6 of it.
 */
int csf_contact_solve(csf_contacts *cs, uint32_t dim)
{
	double *K = cs->K, *b = cs->rhs, *x = cs->x, big = 0;
	for (uint32_t k = 0; k < dim * dim; k++) big = csf_max(big, fabs(K[k]));
	if (!(big > 0) || !isfinite(big)) return -1;
	/* Gaussian elimination with partial pivoting, in place (the systems are small: GSL's
	   LU costs more in its calls than in its arithmetic at these sizes) */
	for (uint32_t k = 0; k < dim; k++) {
		uint32_t pr = k;
		for (uint32_t i = k + 1; i < dim; i++)
			if (fabs(K[i * dim + k]) > fabs(K[pr * dim + k])) pr = i;
		if (!(fabs(K[pr * dim + k]) > 1e-10 * big)) return -1;
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
