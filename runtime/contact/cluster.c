/*
 * cluster.c - the clusters: the pairs in contact that share bodies, solved
 * together. Their coupling, their sorting into clusters (union-find), and
 * the direct solve of a cluster's linear system (Gaussian elimination with
 * partial pivoting, an LU factorisation in place). The force stage
 * (force.c) and the impacts (impulse.c) build the systems.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include <float.h>

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
		double n[3], curv, B[9], E[9];
		csf_contact_geometry(c, m, n, &curv);
		dim += (uint32_t)csf_contact_basis(c, m, n, 1, (int)W(c, MODE), WV(c, DS), B, E);
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
				uint32_t a = csf_uf_root(uf, bi), b = csf_uf_root(uf, bj);
				if (a != b) uf[a < b ? b : a] = a < b ? a : b;
			}
		}
	for (uint32_t k = 0; k < cs->n; k++) { /* count each cluster's pairs; the clusters numbered as met */
		const cpair *c = &cs->pairs[k];
		if (!pick(c, arg)) continue;
		uint32_t r = csf_uf_root(uf, body_i(cs, c));
		if (cid[r] == UINT32_MAX) cid[r] = nq, cs->cstart[++nq] = 0;
		cs->cstart[cid[r] + 1]++;
	}
	cs->cstart[0] = 0;
	for (uint32_t q = 0; q < nq; q++) cs->cstart[q + 1] += cs->cstart[q];
	for (uint32_t k = 0; k < cs->n; k++) { /* cstart[q] is cluster q's cursor, then its end */
		const cpair *c = &cs->pairs[k];
		if (pick(c, arg)) cs->cl[cs->cstart[cid[csf_uf_root(uf, body_i(cs, c))]]++] = k;
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
 * that hold it, the routine takes those with the least friction (in the
 * sum of the squares of the friction forces), and of those the least
 * normal forces: friction takes only what the normal forces cannot. A
 * ball on the floor pressed against a wall stands on the floor, the
 * wall's friction carrying none of its weight (the least forces overall
 * would share it half and half); a ball's prestress against its
 * neighbours, which only the floor's friction could hold, is none. In the
 * frames of the pairs (csf_contact_frames: each sticking pair's force as
 * its normal force and two components of friction), with A = K T split
 * into the columns of normal forces A_N and of friction A_F: the friction
 * is the least-norm solution of P A_F y_F = P b, P the projection on what
 * A_N cannot reach (the residual of A_N's least squares), and the normal
 * forces the least-norm solution of A_N y_N = b - A_F y_F. Each least
 * squares is the least-norm one, from GSL's complete orthogonal
 * decomposition (rank revealed by the pivots of a QR with column
 * pivoting, those below 1e-10 of the largest column taken as zero). The
 * answer is accepted when it solves the system to 1e-9 of its sizes: a
 * singular system that has no solution (contacts that contradict each
 * other) fails (-1).
 */

/*
 * The frames of a system of pairs 0..np, pair a's dc[a] unknowns (0: not
 * in the system) in order, its normal at n + 3a (csf_contact_basis): T
 * (dim x dim, block-diagonal, orthogonal) turns a sticking pair's force
 * into its normal force and two components of friction, and leaves the
 * other unknowns as they are; fric marks the unknowns (after T) that are
 * friction: a sticking pair's two, and the friction across the way a pair
 * slides.
 */
void csf_contact_frames(uint32_t np, const unsigned char *dc, const double *n, uint32_t dim, double *T,
                        unsigned char *fric)
{
	memset(T, 0, (size_t)dim * dim * sizeof *T);
	for (uint32_t a = 0, at = 0; a < np; at += dc[a], a++) {
		const double *na = n + 3 * a;
		double t1[3] = { 0, 0, 0 }, t2[3];
		if (dc[a] == 3) { /* t1 across n from its least component's axis, t2 = n x t1 */
			int k = fabs(na[0]) <= fabs(na[1]) && fabs(na[0]) <= fabs(na[2]) ? 0 : fabs(na[1]) <= fabs(na[2]) ? 1 : 2;
			t1[k] = 1;
			double d = dot3(t1, na), s;
			for (int j = 0; j < 3; j++) t1[j] -= d * na[j];
			s = mag3(t1);
			for (int j = 0; j < 3; j++) t1[j] /= s;
			t2[0] = na[1] * t1[2] - na[2] * t1[1], t2[1] = na[2] * t1[0] - na[0] * t1[2], t2[2] = na[0] * t1[1] - na[1] * t1[0];
		}
		for (int r = 0; r < dc[a]; r++) {
			fric[at + r] = r > 0;
			for (int q = 0; q < dc[a]; q++) {
				const double *col = q == 0 ? na : q == 1 ? t1 : t2;
				T[(size_t)(at + r) * dim + at + q] = dc[a] < 3 ? r == q : col[r];
			}
		}
	}
}

/* The largest column norm of the rows x cols matrix A (row-major, leading dimension ld). */
static double max_column(const double *A, uint32_t rows, uint32_t cols, uint32_t ld)
{
	double big = 0;
	for (uint32_t j = 0; j < cols; j++) {
		double c = 0; /* the sum of squares (hypot's care for overflow only where it overflows: it is slow) */
		for (uint32_t i = 0; i < rows; i++) c += A[(size_t)i * ld + j] * A[(size_t)i * ld + j];
		if (!(c <= DBL_MAX)) {
			c = 0;
			for (uint32_t i = 0; i < rows; i++) c = hypot(c, A[(size_t)i * ld + j]);
		} else {
			c = sqrt(c);
		}
		big = csf_max(big, c);
	}
	return big;
}

/* A least-squares problem: the rows x cols matrix (rows >= cols) and its COD (GSL's) in place. */
typedef struct lsq {
	gsl_matrix_view A;
	gsl_vector_view tq, tz, work, res;
	gsl_permutation p;
	size_t perm[DIRECT_MAX], rank;
} lsq;

/* Factors A (rows x cols, row-major, destroyed), with w 4 rows doubles of work. 0, or -1. */
static int lsq_factor(lsq *q, double *A, uint32_t rows, uint32_t cols, double tol, double *w)
{
	q->A = gsl_matrix_view_array(A, rows, cols);
	q->tq = gsl_vector_view_array(w, cols), q->tz = gsl_vector_view_array(w + rows, cols);
	q->work = gsl_vector_view_array(w + 2 * (size_t)rows, cols), q->res = gsl_vector_view_array(w + 3 * (size_t)rows, rows);
	q->p = (gsl_permutation){ cols, q->perm };
	return gsl_linalg_COD_decomp_e(&q->A.matrix, &q->tq.vector, &q->tz.vector, &q->p, tol, &q->rank, &q->work.vector)
	               ? -1
	               : 0;
}

/* The least-squares solution of least norm of the factored system with right-hand side b (rows) into
   y (cols), and, if r is not NULL, its residual b - A y into r. 0, or -1. */
static int lsq_solve(lsq *q, const double *b, double *y, double *r)
{
	gsl_vector_const_view bv = gsl_vector_const_view_array(b, q->A.matrix.size1);
	gsl_vector_view yv = gsl_vector_view_array(y, q->A.matrix.size2);
	if (gsl_linalg_COD_lssolve(&q->A.matrix, &q->tq.vector, &q->tz.vector, &q->p, q->rank, &bv.vector, &yv.vector,
	                           &q->res.vector))
		return -1;
	if (r) memcpy(r, q->res.vector.data, q->A.matrix.size1 * sizeof *r);
	return 0;
}

/* The 2-norm of v[0..n): the root of the sum of squares, or hypot's where that overflows. */
static double norm2(const double *v, uint32_t n)
{
	double s = 0;
	for (uint32_t i = 0; i < n; i++) s += v[i] * v[i];
	if (s <= DBL_MAX) return sqrt(s);
	s = 0;
	for (uint32_t i = 0; i < n; i++) s = hypot(s, v[i]);
	return s;
}

/* b - K x (K dim x dim, row-major) into r. */
static void residual_of(const double *K, const double *b, const double *x, uint32_t dim, double *r)
{
	for (uint32_t i = 0; i < dim; i++) {
		double e = b[i];
		for (uint32_t j = 0; j < dim; j++) e -= K[(size_t)i * dim + j] * x[j];
		r[i] = e;
	}
}

/*
 * The friction of a system whose normal forces leave some of it (M, the
 * friction's columns projected off the normal forces' span, and c, the
 * part of the right-hand side they leave) has the rank the factoring's
 * threshold tol gives M: M's largest column (the first pivot) below tol,
 * the friction is redundant with the normal forces and none is taken, c
 * is left unsolved; above it, M's solution for c. At tol the forces
 * jumped: in a hexagonal packing of balls wedged between two walls, a
 * friction of 0 or 58 N and a normal force of 14.9 N or 218.6 N took turns
 * at the stages of a step (M's largest column equal to tol to six digits:
 * each answer moved the packing toward the other's side), and the error
 * control held the steps to 2.7e-8 s. So below tol, down to tol /
 * RANK_BAND, M's solution with that lower threshold is taken in part, its
 * share rising from 0 at tol / RANK_BAND to 1 at tol, a smooth step in
 * log(column / tol): the forces go continuously from the one answer to
 * the other, and leave less of c unsolved than none taken did. (A share
 * above tol instead, across a factor of 8, left part of c unsolved where
 * the whole answer solved it: a ball of a packing went 1.8e-9 m into
 * another.) Elsewhere the answer is as before, the same bits.
 */
enum { RANK_BAND = 8 };

static double rank_share(double column, double tol)
{
	double u = log(column / tol) / log((double)RANK_BAND) + 1;
	if (!(u > 0)) return 0;
	if (u >= 1) return 1;
	return u * u * (3 - 2 * u);
}

/*
 * The friction's rank is the number of pivots of M's QR with column
 * pivoting above the threshold; a pivot within a factor of HOLD_BAND of it
 * may as well be taken or not. Decided afresh at each evaluation, a pivot at the
 * threshold was taken at one and not at the next, at states 1e-19 m/s
 * apart: in a pile of 16 balls (restitution 0.9, friction 0.3) a 22-pair
 * cluster's fifth friction direction came and went, a sticking ball's
 * normal force 12.66 and 17.97 N in turn, and the error control held the
 * steps to 3e-13 s. So a pivot below the threshold but within the band is
 * taken where the last solve of a system of the same shape (its size, its
 * friction unknowns, which of its coefficients are not zero: the same
 * cluster, most often) took it: the rank is the one taken last where that
 * lies above the threshold's and within the band's, else the threshold's.
 * It is never less than the threshold's: holding the rank down instead
 * left a friction direction above the threshold out where the whole
 * friction part lay near it (rank_share's case), and the column of nine
 * balls thrown at 0.35 m/s rejected 514 000 of its 679 000 steps. The rank
 * is kept (csf_contacts.held, saved in checkpoints) for the shape's next
 * solve, and an answer of a rank held is not recalled later (it depends on
 * the rank held, not only on the system). Elsewhere the rank and the
 * answer are the threshold's, as before, to the bit. Returns 0 with qf
 * factored at the rank taken (M restored from Mc first if it must be
 * factored again), or -1. Only the force stage's solves hold ranks
 * (cs->hold, which force.c sets): an impact's and a search's are an
 * instant's own, and keep the threshold's.
 */
enum { HOLD_BAND = 4, HOLD_N = (int)(sizeof ((csf_contacts *)0)->held / sizeof ((csf_contacts *)0)->held[0]) };

/* The bytes of a system's shape, dim, nf, which unknowns are friction and which of K's coefficients
   are not zero (SHAPE_BYTES(dim) of them), into pat; returns their number. */
#define SHAPE_BYTES(dim) (2 * sizeof(uint32_t) + (size_t)(dim) + (size_t)(dim) * (dim))
static size_t shape_of(uint32_t dim, uint32_t nf, const double *K, const unsigned char *fric, unsigned char *pat)
{
	memcpy(pat, &dim, sizeof dim), memcpy(pat + sizeof dim, &nf, sizeof nf);
	unsigned char *at = pat + 2 * sizeof(uint32_t);
	for (uint32_t i = 0; i < dim; i++) *at++ = fric && fric[i] != 0;
	for (size_t k = 0; k < (size_t)dim * dim; k++) *at++ = K[k] != 0;
	return (size_t)(at - pat);
}

/* The entry of table t (HOLD_N of them) for the shape sig, or NULL; *old, the one used least recently
   before it (the one to take for sig). */
static struct csf_held *held_entry(struct csf_held *t, uint64_t sig, struct csf_held **old)
{
	*old = &t[0];
	for (int k = 0; k < HOLD_N; k++) {
		if (t[k].used && t[k].sig == sig) return &t[k];
		if (t[k].used < (*old)->used) *old = &t[k];
	}
	return NULL;
}

/* M kept in Mc and factored for the system K, fric (its shape hashed in pat: SHAPE_BYTES(dim) bytes). */
static int held_rank(csf_contacts *cs, lsq *qf, double *M, double *Mc, uint32_t dim, uint32_t nf, double thr,
                     const double *K, const unsigned char *fric, unsigned char *pat, double *wf)
{
	memcpy(Mc, M, (size_t)dim * nf * sizeof *Mc);
	uint64_t sig = csf_hash_bytes(pat, shape_of(dim, nf, K, fric, pat));
	if (lsq_factor(qf, M, dim, nf, thr * HOLD_BAND, wf)) return -1;
	size_t lo = qf->rank, hi = lo, r0 = lo, r;
	double d[DIRECT_MAX]; /* the pivots past the rank: the RZ step leaves those rows as the QR's */
	for (size_t k = lo; k < nf && k < dim; k++) {
		d[k] = fabs(M[k * nf + k]);
		if (d[k] > thr / HOLD_BAND) hi = k + 1;
		if (d[k] > thr) r0 = k + 1;
	}
	struct csf_held *old, *e = held_entry(cs->held, sig, &old);
	if (hi == lo) { /* no pivot near the threshold: the threshold's rank, noted */
		if (e) e->rank = (uint32_t)lo;
		r = lo;
	} else {
		r = e && e->rank > r0 && e->rank <= hi ? e->rank : r0;
		if (!e) e = old, e->sig = sig;
		e->rank = (uint32_t)r, e->used = ++cs->held_clock;
		cs->held_now = 1;
	}
	if (r == lo) return 0;
	memcpy(M, Mc, (size_t)dim * nf * sizeof *M);
	return lsq_factor(qf, M, dim, nf, r < nf ? d[r] : d[nf - 1] / 2, wf);
}

/*
 * Whether least-norm forces solve their system: whether the residual they
 * leave is within 1e-9 of the larger of the right-hand side and the
 * system's largest column times the forces (fit, that residual in units of
 * this threshold, at most 1).
 * Where they do not, the system is nearly singular and its elimination
 * gives its forces (solve_direct), large as they may be. Decided afresh at
 * each evaluation, a residual at the threshold was taken at one state and
 * not at the next: in a frictionless pile of 16 balls, a cluster of 27
 * pairs (three balls in a triangle against a wall) left residuals of
 * 2.37e-7 at the threshold's 2.37e-7, and its forces took turns between
 * the least-norm ones (0.88 N at a pair) and the elimination's (a pull of
 * 3e5 N there, which parted it); at each event the pair was found
 * pressing again, and after 1001 events at one instant the run stopped.
 * So in the force stage (cs->hold), a residual within a factor of
 * HOLD_BAND of the threshold is taken as it was taken last for a system of
 * the same shape (a table like held_rank's, cs->fits), and a decision
 * within the band is not recalled. Elsewhere, and away from the
 * threshold, it is decided as before.
 */
static int held_fit(csf_contacts *cs, double fit, uint32_t dim, uint32_t nf, const double *K,
                    const unsigned char *fric, unsigned char *pat)
{
	int ok = fit <= 1;
	if (!cs->hold) return ok;
	uint64_t sig = csf_hash_bytes(pat, shape_of(dim, nf, K, fric, pat));
	struct csf_held *old, *e = held_entry(cs->fits, sig, &old);
	if (fit > 1.0 / HOLD_BAND && fit <= HOLD_BAND) { /* within the band: as last time */
		if (e) ok = e->rank == 1;
		else e = old, e->sig = sig;
		e->used = ++cs->held_clock;
		cs->held_now = 1;
	}
	if (e) e->rank = ok ? 1 : 2;
	return ok;
}

static int solve_least_norm(csf_contacts *cs, uint32_t dim, const double *K, const double *b, const double *T,
                            const unsigned char *fric, int check)
{
	uint32_t nf = 0, nn, cn[DIRECT_MAX], cf[DIRECT_MAX];
	for (uint32_t j = 0; T && j < dim; j++) nf += fric[j] != 0;
	nn = dim - nf;
	if (!nn) nf = 0; /* friction alone (a block of it: csf_contact_solve): T is orthogonal, the least-norm forces */
	size_t need = 2 * (size_t)dim * dim + 3 * (size_t)dim * nf + 16 * (size_t)dim + SHAPE_BYTES(dim) / sizeof(double) + 1;
	if (need > cs->capls) {
		double *ls = realloc(cs->ls, need * sizeof *ls);
		if (!ls) return -1;
		cs->ls = ls, cs->capls = need;
	}
	double *A = cs->ls, *AN = A + (size_t)dim * dim, *AF = AN + (size_t)dim * nn, *M = AF + (size_t)dim * nf;
	double *w = M + (size_t)dim * nf, *y = w + 4 * dim, *v = y + dim, *c = v + dim, *yf = c + dim, *yn = yf + dim;
	double colmax = max_column(K, dim, dim, dim);
	if (!nf) memcpy(A, K, (size_t)dim * dim * sizeof *A);
	else { /* A = K T, T block-diagonal: at most 3 terms a column */
		memset(A, 0, (size_t)dim * dim * sizeof *A);
		for (uint32_t k = 0; k < dim; k++)
			for (uint32_t j = 0; j < dim; j++) {
				double t = T[(size_t)k * dim + j];
				if (t == 0) continue;
				for (uint32_t i = 0; i < dim; i++) A[(size_t)i * dim + j] += K[(size_t)i * dim + k] * t;
			}
	}
	double tol = 1e-10 * max_column(A, dim, dim, dim);
	lsq qn, qf;
	gsl_set_error_handler_off();
	double *wf = yn + dim, *r = wf + 4 * dim, *x0 = r + dim; /* the friction's own work, past qn's */
	double *Mc = x0 + dim; /* M kept, should it be factored again, and the system's shape (held_rank) */
	unsigned char *pat = (unsigned char *)(Mc + (size_t)dim * nf);
	double share = 1; /* of the friction M leaves (rank_share) */
	if (!nf) { /* the least-norm forces */
		if (lsq_factor(&qn, A, dim, dim, tol, w)) return -1;
	} else {
		nn = nf = 0;
		for (uint32_t j = 0; j < dim; j++) {
			if (fric[j]) cf[nf++] = j;
			else cn[nn++] = j;
		}
		for (uint32_t i = 0; i < dim; i++) {
			for (uint32_t j = 0; j < nn; j++) AN[(size_t)i * nn + j] = A[(size_t)i * dim + cn[j]];
			for (uint32_t j = 0; j < nf; j++) AF[(size_t)i * nf + j] = A[(size_t)i * dim + cf[j]];
		}
		if (lsq_factor(&qn, AN, dim, nn, tol, w)) return -1;
		for (uint32_t j = 0; j < nf; j++) { /* M = P A_F, column by column */
			for (uint32_t i = 0; i < dim; i++) v[i] = AF[(size_t)i * nf + j];
			if (lsq_solve(&qn, v, yn, c)) return -1;
			for (uint32_t i = 0; i < dim; i++) M[(size_t)i * nf + j] = c[i];
		}
		double colm = max_column(M, dim, nf, nf);
		share = rank_share(colm, tol);
		double thr = colm <= tol ? tol / RANK_BAND : tol;
		if (cs->hold ? held_rank(cs, &qf, M, Mc, dim, nf, thr, K, fric, pat, wf) : lsq_factor(&qf, M, dim, nf, thr, wf))
			return -1;
	}
	/* the forces for b, then once more for what they leave of it (its residual r, computed from K
	   itself), kept if that leaves less: the second pass takes the rounding of the first (a
	   ball at rest in a corner pressing the floor with its weight to the last bit, not 4 ulp less) */
	double rn = 0, bn, xn, rn0 = 0;
	for (int pass = 0; pass < 2; pass++) {
		const double *rhs = pass ? r : b;
		double *dx = pass ? x0 : cs->x;
		if (!nf) {
			if (lsq_solve(&qn, rhs, dx, NULL)) return -1;
		} else {
			if (lsq_solve(&qn, rhs, yn, c) || lsq_solve(&qf, c, yf, NULL)) return -1; /* c = P rhs */
			for (uint32_t j = 0; share < 1 && j < nf; j++) yf[j] *= share;
			for (uint32_t i = 0; i < dim; i++) { /* the normal forces for what friction leaves */
				v[i] = rhs[i];
				for (uint32_t j = 0; j < nf; j++) v[i] -= AF[(size_t)i * nf + j] * yf[j];
			}
			if (lsq_solve(&qn, v, yn, NULL)) return -1;
			for (uint32_t j = 0; j < nn; j++) y[cn[j]] = yn[j];
			for (uint32_t j = 0; j < nf; j++) y[cf[j]] = yf[j];
			for (uint32_t i = 0; i < dim; i++) { /* x = T y */
				double sum = 0;
				for (uint32_t j = 0; j < dim; j++) sum += T[(size_t)i * dim + j] * y[j];
				dx[i] = sum;
			}
		}
		if (pass) { /* x0: the first pass's forces plus the correction; kept if their residual is less */
			for (uint32_t i = 0; i < dim; i++) x0[i] += cs->x[i];
			residual_of(K, b, x0, dim, v);
			double rn1 = norm2(v, dim);
			if (rn1 < rn0) memcpy(cs->x, x0, dim * sizeof *x0), rn = rn1;
			break;
		}
		residual_of(K, b, cs->x, dim, r);
		rn = rn0 = norm2(r, dim);
		if (rn0 == 0) break;
	}
	bn = norm2(b, dim), xn = norm2(cs->x, dim);
	for (uint32_t i = 0; i < dim; i++)
		if (!isfinite(cs->x[i])) return -1;
	if (!check) return 0;
	double scale = 1e-9 * csf_max(bn, colmax * xn);
	return held_fit(cs, rn == 0 ? 0 : scale > 0 ? rn / scale : INFINITY, dim, nf, K, fric, pat) ? 0 : -1;
}

static uint32_t blocks(uint32_t dim, const double *K, const double *K1, const double *T, uint32_t *eq, uint32_t *xs,
                       uint32_t *ys, uint32_t *start);

/*
 * Block q of the blocks of a system (eq, xs, ys, start as blocks gives
 * them) of dim unknowns, K and b (K1, T, fric where not NULL), copied into
 * the n x n system Kq, bq (K1q, Tq, fq); returns n.
 */
static uint32_t take_block(uint32_t dim, const double *K, const double *K1, const double *T, const unsigned char *fric,
                           const double *b, const uint32_t *eq, const uint32_t *xs, const uint32_t *ys,
                           const uint32_t *start, uint32_t q, double *Kq, double *K1q, double *Tq, unsigned char *fq,
                           double *bq)
{
	const uint32_t *e = eq + start[q], *xq = xs + start[q], *yq = ys + start[q];
	uint32_t n = start[q + 1] - start[q];
	for (uint32_t r = 0; r < n; r++) {
		bq[r] = b[e[r]];
		if (fric) fq[r] = fric[yq[r]];
		for (uint32_t c = 0; c < n; c++) {
			Kq[r * n + c] = K[(size_t)e[r] * dim + xq[c]];
			if (K1) K1q[r * n + c] = K1[(size_t)e[r] * dim + xq[c]];
			if (T) Tq[r * n + c] = T[(size_t)xq[r] * dim + yq[c]];
		}
	}
	return n;
}

/*
 * After csf_contact_solve failed: the least-squares solution of least norm
 * of its system (T, fric as there) into cs->x, block by block as
 * csf_contact_solve solves (blocks: the least norm of the whole is each
 * block's), so that a block whose right-hand side is 0 has the answer 0
 * exactly: solved as one, the friction across the plane of a scene in a
 * plane took 1e-29 of rounding, which the motion across the plane then
 * grew (a Galton board whose steps fell to 8e-11 s, held by a velocity
 * across the board of 1e-12 m/s).
 */
int csf_contact_least_squares(csf_contacts *cs, uint32_t dim, const double *T, const unsigned char *fric)
{
	const double *K = cs->kb, *b = cs->kb + (size_t)dim * dim;
	uint32_t eq[DIRECT_MAX], xs[DIRECT_MAX], ys[DIRECT_MAX], start[DIRECT_MAX + 1];
	uint32_t nb = dim <= DIRECT_MAX ? blocks(dim, K, NULL, T, eq, xs, ys, start) : 1;
	if (nb <= 1) return solve_least_norm(cs, dim, K, b, T, fric, 0);
	size_t d2 = (size_t)dim * dim, need = 2 * d2 + 2 * (size_t)dim;
	if (need > cs->capblk) {
		double *w = realloc(cs->blk, need * sizeof *w);
		if (!w) return -1;
		cs->blk = w, cs->capblk = need;
	}
	double *Kq = cs->blk, *Tq = Kq + d2, *bq = Tq + d2, *x0 = bq + dim;
	unsigned char fq[DIRECT_MAX];
	for (uint32_t q = 0; q < nb; q++) {
		uint32_t n = take_block(dim, K, NULL, T, fric, b, eq, xs, ys, start, q, Kq, NULL, Tq, fq, bq);
		if (solve_least_norm(cs, n, Kq, bq, T ? Tq : NULL, fric ? fq : NULL, 0)) return -1;
		for (uint32_t r = 0; r < n; r++) x0[xs[start[q] + r]] = cs->x[r];
	}
	memcpy(cs->x, x0, dim * sizeof *x0);
	return 0;
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
 * masses): the solution with the least friction above (in the frames T and
 * fric of csf_contact_frames; NULL: the least-norm solution). If not, the masses differ by more
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
/* The system cs->K, cs->rhs (dim unknowns) set aside in cs->kb, K then rhs (csf_contact_least_squares
   reads it after a failed solve). 0, or -1. */
static int set_aside(csf_contacts *cs, uint32_t dim)
{
	size_t d2 = (size_t)dim * dim;
	if (d2 + dim > cs->capkb) {
		double *kb = realloc(cs->kb, (d2 + dim) * sizeof *kb);
		if (!kb) return -1;
		cs->kb = kb, cs->capkb = d2 + dim;
	}
	memcpy(cs->kb, cs->K, d2 * sizeof *cs->kb);
	memcpy(cs->kb + d2, cs->rhs, dim * sizeof *cs->kb);
	return 0;
}

static int solve_direct(csf_contacts *cs, uint32_t dim, double *K1, double wratio, const double *T,
                       const unsigned char *fric)
{
	double *K = cs->K, *b = cs->rhs, big = 0, big1 = 0;
	if (set_aside(cs, dim)) return -1; /* first: a failure below leaves this system there, not another */
	for (uint32_t k = 0; k < dim * dim; k++) big = csf_max(big, fabs(K[k]));
	if (!(big > 0) || !isfinite(big)) return -1;
	if (!solve_lu(K, b, cs->x, dim, 1e-10 * big)) return 0;
	if (!K1) return -1;
	for (uint32_t k = 0; k < dim * dim; k++) big1 = csf_max(big1, fabs(K1[k]));
	double *b1 = cs->rhs; /* a right-hand side for K1's elimination, whose answer is not used */
	for (uint32_t k = 0; k < dim; k++) b1[k] = 1;
	int redundant = solve_lu(K1, b1, cs->x, dim, 1e-10 * big1) != 0;
	if (redundant && !solve_least_norm(cs, dim, cs->kb, cs->kb + (size_t)dim * dim, T, fric, 1)) return 0;
	if (!redundant && !(wratio < 1e6)) return -1; /* the masses differ too much */
	/* nearly redundant contacts, whose forces are large (a row of balls all but jammed), or
	   sliding friction that all but cancels a normal force: the elimination's own answer */
	memcpy(K, cs->kb, (size_t)dim * dim * sizeof *K);
	memcpy(b, cs->kb + (size_t)dim * dim, dim * sizeof *b);
	return solve_lu(K, b, cs->x, dim, 1e-14 * big);
}

/*
 * The systems solve_direct solved last, with their answers: a system the
 * same to the last bit as one of them (a pile's balls at rest, whose
 * blocks are the same at every evaluation while others fall) is not solved
 * again. Its answer is the one solve_direct would give, bit for bit: the
 * same function of the same bits. Kept: RECALL_N systems, the one used
 * least recently replaced (a system solved once, by a moving body, does
 * not push out those that come back); each holds K, rhs, K1 and T (as
 * given) and the answer x and its rc; a recall sets the system aside as
 * solve_direct does (set_aside).
 */
enum { RECALL_N = 32 };
typedef struct csf_solved {
	uint32_t dim;
	unsigned char has; /* 1: K1 given, 2: T given, 4: fric given */
	int rc;
	double wratio;
	uint64_t used; /* the clock at its last use (0: empty) */
	double *buf;   /* K, rhs, K1, T (those given), x */
	size_t cap;
	unsigned char fric[DIRECT_MAX];
} csf_solved;

void csf_contact_forget(csf_contacts *cs)
{
	if (!cs->solved) return;
	for (int e = 0; e < RECALL_N; e++) free(cs->solved[e].buf);
	free(cs->solved);
	cs->solved = NULL;
}

/* Does entry e hold this system? */
static int same_system(const csf_solved *e, uint32_t dim, unsigned char has, double wratio, const double *K,
                       const double *b, const double *K1, const double *T, const unsigned char *fric)
{
	size_t d2 = (size_t)dim * dim;
	const double *at = e->buf;
	if (!e->used || e->dim != dim || e->has != has || memcmp(&e->wratio, &wratio, sizeof wratio)) return 0;
	if (memcmp(at + d2, b, dim * sizeof *b) || memcmp(at, K, d2 * sizeof *K)) return 0;
	at += d2 + dim;
	if (K1 && memcmp(at, K1, d2 * sizeof *K1)) return 0;
	at += K1 ? d2 : 0;
	if (T && memcmp(at, T, d2 * sizeof *T)) return 0;
	return !fric || !memcmp(e->fric, fric, dim);
}

/* solve_direct, or its answer recalled (above). */
static int solve_whole(csf_contacts *cs, uint32_t dim, double *K1, double wratio, const double *T,
                       const unsigned char *fric)
{
	if (!cs->solved && !(cs->solved = calloc(RECALL_N, sizeof *cs->solved)))
		return solve_direct(cs, dim, K1, wratio, T, fric);
	unsigned char has = (unsigned char)((K1 ? 1 : 0) | (T ? 2 : 0) | (fric ? 4 : 0));
	size_t d2 = (size_t)dim * dim, nx = d2 * (1 + !!K1 + !!T) + dim; /* the system's doubles, then x's */
	csf_solved *e = NULL, *old = cs->solved;
	for (int k = 0; k < RECALL_N && !e; k++) {
		csf_solved *c = &cs->solved[k];
		if (same_system(c, dim, has, wratio, cs->K, cs->rhs, K1, T, fric)) e = c;
		else if (c->used < old->used) old = c;
	}
	if (e) { /* what solve_direct leaves: x, and the system set aside */
		if (set_aside(cs, dim)) return -1;
		memcpy(cs->x, e->buf + nx, dim * sizeof *cs->x);
		e->used = ++cs->solved_clock;
		cs->recalled++;
		return e->rc;
	}
	e = old; /* the one used least recently takes this system, before solve_direct destroys it */
	e->used = 0;
	if (nx + dim > e->cap) {
		double *w = realloc(e->buf, (nx + dim) * sizeof *w);
		if (!w) return solve_direct(cs, dim, K1, wratio, T, fric);
		e->buf = w, e->cap = nx + dim;
	}
	double *at = e->buf;
	memcpy(at, cs->K, d2 * sizeof *at);
	memcpy(at + d2, cs->rhs, dim * sizeof *at);
	at += d2 + dim;
	if (K1) memcpy(at, K1, d2 * sizeof *at), at += d2;
	if (T) memcpy(at, T, d2 * sizeof *at);
	if (fric) memcpy(e->fric, fric, dim);
	e->dim = dim, e->has = has, e->wratio = wratio;
	cs->held_now = 0;
	e->rc = solve_direct(cs, dim, K1, wratio, T, fric);
	memcpy(e->buf + nx, cs->x, dim * sizeof *cs->x);
	e->used = cs->held_now ? 0 : ++cs->solved_clock; /* an answer of a held rank is not recalled */
	return e->rc;
}

/*
 * The blocks of a system K x = b whose unknowns x = T y are solved in the
 * frames y (T NULL: x itself): its equations, unknowns x and unknowns y
 * are the nodes of a graph, an equation joined to the x that K or K1
 * gives it, an x to the y that T makes it of. Each part of the graph is a
 * block: a system of its own, square (as many equations as unknowns of
 * each sort) where the whole is solvable. Into eq, xs and ys (3 dim
 * entries each: each block's, one after the other) and start (nb + 1
 * entries: block q is from start[q] to start[q + 1] in each) the blocks,
 * each in the order of the whole; returns their number, or 1 when one is
 * not square.
 */
static uint32_t blocks(uint32_t dim, const double *K, const double *K1, const double *T, uint32_t *eq, uint32_t *xs,
                       uint32_t *ys, uint32_t *start)
{
	uint32_t up[3 * DIRECT_MAX], id[3 * DIRECT_MAX], blk[3 * DIRECT_MAX], nb = 0;
	for (uint32_t v = 0; v < 3 * dim; v++) up[v] = v, id[v] = UINT32_MAX;
	/* each row's (each x's) root found once: a node joined to it goes under it, which stays the root */
	for (uint32_t i = 0; i < dim; i++) {
		const double *Ki = K + (size_t)i * dim, *K1i = K1 ? K1 + (size_t)i * dim : NULL;
		uint32_t ri = csf_uf_root(up, i);
		for (uint32_t k = 0; k < dim; k++)
			if (Ki[k] != 0 || (K1i && K1i[k] != 0)) {
				uint32_t rk = csf_uf_root(up, dim + k);
				if (rk != ri) up[rk] = ri;
			}
	}
	for (uint32_t k = 0; k < dim; k++) {
		uint32_t rk = csf_uf_root(up, dim + k);
		for (uint32_t j = 0; j < dim; j++)
			if (T ? T[(size_t)k * dim + j] != 0 : k == j) {
				uint32_t rj = csf_uf_root(up, 2 * dim + j);
				if (rj != rk) up[rj] = rk;
			}
	}
	for (uint32_t v = 0; v < 3 * dim; v++) { /* node v's block: its root's number */
		uint32_t r = csf_uf_root(up, v);
		if (id[r] == UINT32_MAX) id[r] = nb++;
		blk[v] = id[r];
	}
	if (nb <= 1) return 1;
	/* each block's equations, x and y counted by sort (rows, x, y: 0, 1, 2), each sort's must agree */
	uint32_t n[3][3 * DIRECT_MAX], *out[3] = { eq, xs, ys }, at[3 * DIRECT_MAX];
	for (uint32_t q = 0; q < nb; q++) n[0][q] = n[1][q] = n[2][q] = 0;
	for (uint32_t v = 0; v < 3 * dim; v++) n[v / dim][blk[v]]++;
	for (uint32_t q = 0; q < nb; q++)
		if (n[0][q] != n[1][q] || n[1][q] != n[2][q] || !n[0][q]) return 1;
	start[0] = 0;
	for (uint32_t q = 0; q < nb; q++) start[q + 1] = start[q] + n[0][q];
	for (int sort = 0; sort < 3; sort++) { /* each sort's nodes, block by block, in their order */
		for (uint32_t q = 0; q < nb; q++) at[q] = start[q];
		for (uint32_t i = 0; i < dim; i++) out[sort][at[blk[sort * dim + i]]++] = i;
	}
	return nb;
}

/*
 * The system of cs->K, cs->rhs (dim unknowns), as solve_whole solves it,
 * but block by block (blocks): the unknowns that nothing couples are
 * solved apart, each block as a system of its own. The answer is the
 * same, and exact where it should be: in a scene in a plane, the friction
 * across the plane is a block of its own whose right-hand side is 0, and
 * so is its answer, where a solve of the whole would leave rounding there
 * (1e-16 of the forces), which the motion then takes out of the plane.
 * Where a block alone fails (its residual, measured against its own sizes,
 * is more than those of the whole allow), the whole is solved as one, and
 * its answer taken for that block's unknowns only: the others keep their
 * blocks' own (the blocks do not couple, so together they solve the
 * whole). Taken whole, the impulses that stopped a slip in a pile of 40
 * balls in a plane moved a ball across it at 8.6e-36 m/s, which grew to
 * 1e-6 m/s and held the steps to 3e-11 s.
 */
int csf_contact_solve(csf_contacts *cs, uint32_t dim, double *K1, double wratio, const double *T,
                      const unsigned char *fric)
{
	uint32_t eq[DIRECT_MAX], xs[DIRECT_MAX], ys[DIRECT_MAX], start[DIRECT_MAX + 1];
	uint32_t nb = dim <= DIRECT_MAX ? blocks(dim, cs->K, K1, T, eq, xs, ys, start) : 1;
	if (nb <= 1) return solve_whole(cs, dim, K1, wratio, T, fric);
	/* the whole system aside: K, K1, rhs, T (dim^2 each but rhs), and the answer */
	size_t d2 = (size_t)dim * dim, need = 3 * d2 + 2 * (size_t)dim;
	if (need > cs->capblk) {
		double *w = realloc(cs->blk, need * sizeof *w);
		if (!w) return -1;
		cs->blk = w, cs->capblk = need;
	}
	double *K0 = cs->blk, *K10 = K0 + d2, *T0 = K10 + d2, *b0 = T0 + d2, *x0 = b0 + dim;
	unsigned char fric0[DIRECT_MAX];
	memcpy(K0, cs->K, d2 * sizeof *K0);
	if (K1) memcpy(K10, K1, d2 * sizeof *K10);
	if (T) memcpy(T0, T, d2 * sizeof *T0);
	if (fric) memcpy(fric0, fric, dim);
	memcpy(b0, cs->rhs, dim * sizeof *b0);
	double *Tb = T ? cs->T : NULL; /* T is cs->T where given: the blocks' frames go there once it is aside */
	unsigned char own[DIRECT_MAX]; /* an unknown whose block was solved alone */
	int failed = 0;
	for (uint32_t q = 0; q < nb; q++) {
		const uint32_t *xq = xs + start[q];
		uint32_t n = take_block(dim, K0, K1 ? K10 : NULL, Tb ? T0 : NULL, fric ? fric0 : NULL, b0, eq, xs, ys, start, q,
		                        cs->K, K1, Tb, cs->fric, cs->rhs);
		int bad = solve_whole(cs, n, K1, wratio, Tb, fric ? cs->fric : NULL);
		failed |= bad;
		for (uint32_t r = 0; r < n; r++) x0[xq[r]] = cs->x[r], own[xq[r]] = !bad;
	}
	memcpy(cs->x, x0, dim * sizeof *x0);
	if (failed) { /* the whole, as if not split; but each block solved alone keeps its own answer */
		memcpy(cs->K, K0, d2 * sizeof *K0);
		if (K1) memcpy(K1, K10, d2 * sizeof *K10);
		if (Tb) memcpy(Tb, T0, d2 * sizeof *T0);
		if (fric) memcpy(cs->fric, fric0, dim);
		memcpy(cs->rhs, b0, dim * sizeof *b0);
		if (solve_whole(cs, dim, K1, wratio, T, fric)) return -1;
		for (uint32_t k = 0; k < dim; k++)
			if (own[k]) cs->x[k] = x0[k];
		return 0;
	}
	if (Tb) memcpy(Tb, T0, d2 * sizeof *T0);
	if (fric) memcpy(cs->fric, fric0, dim);
	return 0;
}
