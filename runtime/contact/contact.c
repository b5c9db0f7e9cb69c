/*
 * contact.c - the contact routine (contact_int.h says what it does and how).
 */
#include "contact_int.h"

long csf_contacts_bad_mass(const csf_prog *p, const double *m)
{
	for (uint32_t b = 0; b < p->ncbodies; b++) {
		if (p->cbodies[b].plane) continue; /* a plane has no mass slot */
		double x = m[p->cbodies[b].s[CSF_CF_M]];
		if (!(x > 0 && isfinite(1 / x))) return (long)b;
	}
	return -1;
}

/*
 * The pair's unit normal n (from j towards i), its gap (returned) and the
 * centripetal term of the gap's second derivative (spheres moving round
 * each other): gap'' = (a_i - a_j) . n + curv. The positions of i and j
 * (a mass point) are at pi and pj, the rest in m. Two points (radius 0)
 * never touch: their gap is infinite; two spheres at one place have no
 * normal (n = 0), their gap is minus the sum of their radii.
 */
double csf_contact_geometry_at(const cpair *c, const double *m, const double *pi, const double *pj, double n[3],
                          double *curv)
{
	*curv = 0;
	if (c->plane) {
		const double *q = m + J(c, POS), *nn = m + J(c, R);
		double k = mag3(nn), d[3];
		for (int i = 0; i < 3; i++) n[i] = nn[i] / k, d[i] = pi[i] - q[i];
		return dot3(d, n) - m[I(c, R)];
	}
	double d[3] = { pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2] };
	double R = m[I(c, R)] + m[J(c, R)], dist = mag3(d);
	if (R > 0 && dist > 0) {
		double vr[3];
		for (int i = 0; i < 3; i++) n[i] = d[i] / dist;
		rel(c, m, I(c, V), J(c, V), vr);
		double vn = dot3(vr, n);
		*curv = (dot3(vr, vr) - vn * vn) / dist;
		return dist - R;
	}
	n[0] = n[1] = n[2] = 0;
	return R > 0 ? -R : HUGE_VAL;
}

static double geometry(const cpair *c, const double *m, double n[3], double *curv)
{
	return csf_contact_geometry_at(c, m, m + I(c, POS), c->plane ? NULL : m + J(c, POS), n, curv);
}

/*
 * A plane with an edge (its V slot holds the vector from its point to the edge line,
 * perpendicular to it; zero: no edge) ends there: how far inside body i,
 * at pi, is (negative past the edge). HUGE_VAL without an edge.
 */
double csf_contact_inside_at(const cpair *c, const double *m, const double *pi)
{
	if (!c->plane) return HUGE_VAL;
	const double *e = m + J(c, V), *q = m + J(c, POS);
	double len = mag3(e);
	if (!(len > 0)) return HUGE_VAL;
	double d[3] = { pi[0] - q[0], pi[1] - q[1], pi[2] - q[2] };
	return len - dot3(d, e) / len;
}

static double inside(const cpair *c, const double *m) { return csf_contact_inside_at(c, m, m + I(c, POS)); }

/* The pair's length scale: the magnitudes its gap is computed from. */
static double scale(const cpair *c, const double *m)
{
	return mag3(m + I(c, POS)) + mag3(m + J(c, POS)) + m[I(c, R)] + (c->plane ? 0 : m[J(c, R)]);
}

/*
 * The smallest gap the pair's positions resolve: a few units in the last
 * place of the magnitudes the gap is computed from. A gap within it of zero
 * is zero, and a hop no higher than it cannot be followed.
 */
static double resolution(const cpair *c, const double *m)
{
	return 2 * DBL_EPSILON * scale(c, m);
}

/* Adds force f (on i; -f on j) to both accelerations and to force property fi/fj. */
static void add_force(cpair *c, double *m, const double f[3], uint32_t fi, uint32_t fj)
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m);
	for (int k = 0; k < 3; k++) {
		m[I(c, A) + k] += f[k] * wi;
		m[fi + k] += f[k];
		if (!c->plane) {
			m[J(c, A) + k] -= f[k] * wj;
			m[fj + k] -= f[k];
		}
	}
}

/* Tangential part of x: x - (x . n) n. */
static void tangential(const double x[3], const double n[3], double out[3])
{
	double xn = dot3(x, n);
	for (int k = 0; k < 3; k++) out[k] = x[k] - xn * n[k];
}

/* The relative tangential velocity of the pair (normal n). */
static void slip_velocity(const cpair *c, const double *m, const double n[3], double vt[3])
{
	double vr[3];
	rel(c, m, I(c, V), J(c, V), vr);
	tangential(vr, n, vt);
}

/* ---- the clusters: the pairs in contact that share bodies, solved together ---- */

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
static double coupling(const csf_contacts *cs, const cpair *c, const cpair *d, const double *m)
{
	uint32_t ci = body_i(cs, c), cj = body_j(cs, c), di = body_i(cs, d), dj = body_j(cs, d);
	double k = 0;
	if (ci == di) k += inv_mass_i(c, m);
	if (ci == dj) k -= inv_mass_i(c, m);
	if (cj != UINT32_MAX && cj == di) k -= inv_mass_j(c, m);
	if (cj != UINT32_MAX && cj == dj) k += inv_mass_j(c, m);
	return k;
}

/* For clusters(): the pairs in contact. */
static int picks_contact(const cpair *c, const void *arg)
{
	(void)arg;
	return in_contact(c);
}

/*
 * Sorts the candidates k for which pick(k) holds into clusters: cl lists
 * them cluster by cluster, each in the order of pairs, the clusters in the
 * order of their first pair; cluster q is cl[cstart[q] .. cstart[q + 1]).
 * Returns the number of clusters. Linear in the pairs picked.
 */
static uint32_t clusters(csf_contacts *cs, int (*pick)(const cpair *, const void *), const void *arg)
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
static int solve(csf_contacts *cs, uint32_t dim)
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

/* Pair c's force directions B (3 x d, column-major: d = 3 when it sticks), and E likewise. */
static int force_basis(const cpair *c, const double *m, const double n[3], double sign, double B[9], double E[9])
{
	if (has_friction(c, m) && W(c, MODE) == STICKING) {
		for (int k = 0; k < 9; k++) B[k] = E[k] = k % 4 == 0;
		return 3;
	}
	double u[3] = { 0, 0, 0 }, k = 0;
	if (has_friction(c, m)) { /* sliding: -mu_k |N| along the way it slides (as csf_contact_apply's sweeps) */
		double vt[3];
		slip_velocity(c, m, n, vt);
		double s = mag3(vt);
		int ahead = dot3(vt, WV(c, DS)) > 0;
		for (int j = 0; j < 3; j++) u[j] = ahead ? vt[j] / s : WV(c, DS)[j];
		k = mu_k(c, m) * sign;
	}
	for (int j = 0; j < 3; j++) B[j] = n[j] - k * u[j], E[j] = n[j];
	return 1;
}

/*
 * The contact forces of cluster cl[0..np), solved directly (above); fails
 * (-1, nothing changed) when it has more than DIRECT_MAX unknowns or its
 * system is singular. The accelerations in m are those of the other forces.
 */
static int cluster_forces(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np)
{
	if (np > DIRECT_MAX) return -1;
	double sign[DIRECT_MAX]; /* a sliding pair's friction is against its way for N > 0: |N| = sign N */
	double *n = cs->nv, *B = cs->B, *E = cs->E;
	for (uint32_t a = 0; a < np; a++) sign[a] = 1;
	for (int attempt = 0; attempt < 2; attempt++) {
		uint32_t dim = 0;
		for (uint32_t a = 0; a < np; a++) { /* each pair's normal, force directions and equations */
			const cpair *c = &cs->pairs[cl[a]];
			double curv, ar[3];
			geometry(c, m, n + 3 * a, &curv);
			cs->dc[a] = (unsigned char)force_basis(c, m, n + 3 * a, sign[a], B + 9 * a, E + 9 * a);
			cs->at[a] = dim;
			dim += cs->dc[a];
			if (dim > DIRECT_MAX) return -1;
			rel(c, m, I(c, A), J(c, A), ar);
			for (int r = 0; r < cs->dc[a]; r++)
				cs->rhs[cs->at[a] + r] = -(dot3(E + 9 * a + 3 * r, ar) + curv * dot3(E + 9 * a + 3 * r, n + 3 * a));
		}
		memset(cs->K, 0, (size_t)dim * dim * sizeof *cs->K);
		for (uint32_t a = 0; a < np; a++)
			for (uint32_t b = 0; b < np; b++) {
				double w = coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
				if (w == 0) continue;
				for (int r = 0; r < cs->dc[a]; r++)
					for (int q = 0; q < cs->dc[b]; q++)
						cs->K[(size_t)(cs->at[a] + r) * dim + cs->at[b] + q] =
							w * dot3(E + 9 * a + 3 * r, B + 9 * b + 3 * q);
			}
		if (solve(cs, dim)) return -1;
		int flip = 0;
		for (uint32_t a = 0; a < np; a++) {
			const cpair *c = &cs->pairs[cl[a]];
			if (has_friction(c, m) && W(c, MODE) == SLIDING && cs->x[cs->at[a]] * sign[a] < 0) sign[a] = -sign[a], flip = 1;
		}
		if (!flip || attempt == 1) break;
	}
	for (uint32_t a = 0; a < np; a++) {
		cpair *c = &cs->pairs[cl[a]];
		double F[3] = { 0, 0, 0 }, *na = n + 3 * a;
		for (int q = 0; q < cs->dc[a]; q++)
			for (int k = 0; k < 3; k++) F[k] += B[9 * a + 3 * q + k] * cs->x[cs->at[a] + q];
		/* F = N n + the friction force */
		double lam = cs->dc[a] == 1 ? cs->x[cs->at[a]] : dot3(F, na), fn[3], *f = WV(c, F);
		for (int k = 0; k < 3; k++) fn[k] = lam * na[k], f[k] = has_friction(c, m) ? F[k] - fn[k] : 0;
		W(c, LAM) = lam;
		add_force(c, m, fn, I(c, FN), J(c, FN));
		add_force(c, m, f, I(c, FF), J(c, FF));
	}
	return 0;
}

/* The largest relative normal acceleration of a pair in contact that the sweeps solve. */
static double residual(const csf_contacts *cs, const double *m)
{
	double r = 0;
	for (uint32_t i = 0; i < cs->n; i++) {
		const cpair *c = &cs->pairs[i];
		if (!in_contact(c) || cs->direct[i]) continue;
		double n[3], curv, ar[3];
		geometry(c, m, n, &curv);
		rel(c, m, I(c, A), J(c, A), ar);
		r = csf_max(r, fabs(dot3(ar, n) + curv));
	}
	return r;
}

int csf_contacts_unsolved(const csf_contacts *c) { return c->unsolved; }

void csf_contact_apply(const csf_prog *p, double *m)
{
	csf_contacts *cs = p->crun;
	if (!cs) return;
	for (uint32_t b = 0; b < p->ncbodies; b++) {
		const csf_cbody *cb = &p->cbodies[b];
		if (cb->plane) continue;
		for (int k = 0; k < 3; k++) m[cb->s[CSF_CF_FN] + k] = m[cb->s[CSF_CF_FF] + k] = 0;
	}
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		for (int k = 0; k < 3; k++) WV(c, F)[k] = 0;
		W(c, LAM) = 0;
	}
	/* each cluster directly; those it does not take (above) by Gauss-Seidel sweeps */
	uint32_t nq = clusters(cs, picks_contact, NULL), sweeps = 0; /* some cluster needs them */
	for (uint32_t q = 0; q < nq; q++) {
		int ok = !cluster_forces(cs, m, cs->cl + cs->cstart[q], cs->cstart[q + 1] - cs->cstart[q]);
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++) cs->direct[cs->cl[a]] = (unsigned char)ok;
		sweeps |= !ok;
	}
	double before = sweeps ? residual(cs, m) : 0;
	for (uint32_t sweep = 0; sweeps && sweep < 100; sweep++) {
		double change = 0, size = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			if (!in_contact(c) || cs->direct[i]) continue;
			double n[3], curv, ar[3], f[3];
			geometry(c, m, n, &curv);
			double w = inv_mass_i(c, m) + inv_mass_j(c, m);
			rel(c, m, I(c, A), J(c, A), ar);
			double dl = -(dot3(ar, n) + curv) / w, dn[3] = { dl * n[0], dl * n[1], dl * n[2] };
			W(c, LAM) += dl;
			add_force(c, m, dn, I(c, FN), J(c, FN));
			change = csf_max(change, fabs(dl));
			size = csf_max(size, fabs(W(c, LAM)));
			if (!has_friction(c, m)) continue;
			double *fc = WV(c, F);
			if (W(c, MODE) == SLIDING) {
				double vt[3];
				slip_velocity(c, m, n, vt);
				/* against the sliding; once it has turned back (past the guard's zero, before the
				   event is located) against its direction at the start, so that the force is smooth
				   up to the crossing and the integrator sees no switching */
				double s = mag3(vt), k = mu_k(c, m) * fabs(W(c, LAM));
				int ahead = dot3(vt, WV(c, DS)) > 0;
				for (int j = 0; j < 3; j++) f[j] = -k * (ahead ? vt[j] / s : WV(c, DS)[j]);
			} else { /* sticking: cancel the relative tangential acceleration */
				double at[3];
				rel(c, m, I(c, A), J(c, A), ar);
				tangential(ar, n, at);
				for (int j = 0; j < 3; j++) f[j] = fc[j] - at[j] / w;
			}
			double df[3] = { f[0] - fc[0], f[1] - fc[1], f[2] - fc[2] };
			memcpy(fc, f, sizeof f);
			add_force(c, m, df, I(c, FF), J(c, FF));
			change = csf_max(change, mag3(df));
			size = csf_max(size, mag3(f));
		}
		if (change <= 1e-15 * size) break;
	}
	/* the sweeps converge slowly on masses that differ greatly: a relative acceleration that
	   they left above 1e-6 of what they began with means forces that do not hold the contacts */
	if (sweeps && residual(cs, m) > 1e-6 * before) cs->unsolved = 1;
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		double n[3], curv;
		double gap = geometry(c, m, n, &curv);
		double *g = WV(c, G0);
		double in = inside(c, m);
		if (W(c, MODE) == HOPPING) { /* the hop lands, or passes the plane's edge */
			g[0] = csf_min(W(c, TL) - m[p->tslot], in);
			g[1] = 1;
			continue;
		}
		if (!in_contact(c)) { /* the gap closes over the plane (not past its edge) */
			g[0] = csf_max(gap, -in);
			g[1] = 1;
			continue;
		}
		g[0] = csf_min(W(c, LAM), in); /* the normal force would pull, or the body left the edge */
		if (!has_friction(c, m)) {
			g[1] = 1;
		} else if (W(c, MODE) == SLIDING) {
			double vt[3];
			slip_velocity(c, m, n, vt);
			g[1] = dot3(vt, WV(c, DS));
		} else {
			g[1] = mu_s(c, m) * fabs(W(c, LAM)) - mag3(WV(c, F));
		}
	}
}

/* Changes the relative velocity of the pair by dv (along any direction), conserving momentum. */
static void add_impulse(cpair *c, double *m, const double dv[3])
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj;
	for (int k = 0; k < 3; k++) {
		double j = dv[k] / w; /* the impulse on i */
		m[I(c, V) + k] += j * wi;
		if (!c->plane) m[J(c, V) + k] -= j * wj;
	}
}

/*
 * Moves the bodies along n so that the gap is zero (they move by the event's
 * location error): then, if rounding left it negative, body i outward by the
 * least amount that makes it non-negative, so that the gap's guard is armed.
 */
static void close_gap(cpair *c, double *m, const double n[3], double gap)
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj, nn[3], curv;
	for (int k = 0; k < 3; k++) {
		m[I(c, POS) + k] -= gap * n[k] * (wi / w);
		if (!c->plane) m[J(c, POS) + k] += gap * n[k] * (wj / w);
	}
	double push = DBL_EPSILON * scale(c, m) / 8;
	for (int i = 0; i < 64 && (gap = geometry(c, m, nn, &curv)) < 0; i++, push *= 2)
		for (int k = 0; k < 3; k++) m[I(c, POS) + k] += csf_max(push, -gap) * n[k];
}

/* Enters contact: the relative normal velocity is zero; sticks if the tangential one is too. */
static void enter_contact(cpair *c, double *m, const double n[3])
{
	double vt[3];
	slip_velocity(c, m, n, vt);
	double s = mag3(vt);
	W(c, MODE) = s == 0 && has_friction(c, m) ? STICKING : SLIDING;
	for (int k = 0; k < 3; k++) WV(c, DS)[k] = s > 0 ? vt[k] / s : 0;
}

/* Is the pair touching: the gap closed, up to the event's location error? */
static int touching(const cpair *c, const double *m, double gap)
{
	return gap <= 1e-12 * scale(c, m) && inside(c, m) >= 0;
}

/* Lift-off: apart, exactly touching. */
static void separate(cpair *c, double *m)
{
	double n[3], curv, gap = geometry(c, m, n, &curv);
	W(c, MODE) = APART;
	close_gap(c, m, n, gap);
}

/* Sliding has stopped: the relative tangential velocity becomes exactly zero, and the pair sticks. */
static void stick(cpair *c, double *m)
{
	double n[3], curv, vt[3];
	geometry(c, m, n, &curv);
	slip_velocity(c, m, n, vt);
	for (int k = 0; k < 3; k++) vt[k] = -vt[k];
	add_impulse(c, m, vt);
	W(c, MODE) = STICKING;
}

/* Static friction cannot hold: the pair slides, the way the friction force held it back from. */
static void slide(cpair *c, double *m)
{
	(void)m; /* as stick */
	double *f = WV(c, F), s = mag3(f);
	for (int k = 0; k < 3; k++) WV(c, DS)[k] = s > 0 ? -f[k] / s : 0;
	W(c, MODE) = SLIDING;
}

/*
 * A touching pair pressed together (relative normal acceleration an < 0)
 * that separates at normal speed vn >= 0 hops for 2 vn/|an|, to the height
 * vn^2/(2|an|); with restitution e < 1 the hops that follow shrink by e and
 * end (Zeno's accumulation of bounces) after 2 vn/(|an| (1 - e)).
 *
 * At rest: that train ends within zeno seconds (a single hop, with e = 1).
 */
static int at_rest(const cpair *c, const double *m, double vn, double an, double zeno)
{
	double e = restitution(c, m);
	return an < 0 && 2 * vn / -an <= zeno * (e < 1 ? 1 - e : 1);
}

/*
 * Hopping: the hop is too low for the positions to follow: within 1024
 * times the gap's resolution (where the rounding of positions far from the
 * origin would misplace its landing), or 100 times the integrator's
 * accuracy, tol times the pair's length scale (an implicit method's
 * iteration leaves errors of that size). It lands at the time its flight
 * takes, 2 vn/|an|, found from the velocity alone.
 */
/* The height below which a hop is too low (as hops() says). */
static double too_low(const cpair *c, const double *m, double tol)
{
	return csf_max(1024 * resolution(c, m), 100 * tol * scale(c, m));
}

static int hops(const cpair *c, const double *m, double vn, double an, double tol)
{
	return an < 0 && vn * vn / (-2 * an) <= too_low(c, m, tol);
}

/* For clusters(): the pairs in contact, and the pair hit (arg). */
static int picks_impact(const cpair *c, const void *hit)
{
	return c == hit || in_contact(c);
}

/*
 * The impact of pair hit, whose relative normal velocity is to become
 * target, on the cluster it forms with the pairs in contact, solved
 * directly: the normal impulses P make the hit's velocity target, and each
 * pair in contact either pushes (P >= 0) and is left with a relative normal
 * velocity of zero, or takes no impulse and does not close (v >= 0): a
 * linear complementarity problem, whose matrix (the coupling of the pairs'
 * normals) is symmetric and positive definite when it is not singular. It
 * is solved by active sets: starting with the hit alone, the pair in
 * contact that closes fastest joins, or the one that would pull most leaves,
 * until neither happens. Fails (-1, nothing changed) for a cluster of more
 * than DIRECT_MAX pairs, a singular system or one that does not settle in
 * 4 np + 8 changes of the set; size is the scale of the velocities.
 */
static int cluster_impulses(csf_contacts *cs, double *m, const cpair *hit, double target, double size)
{
	uint32_t nq = clusters(cs, picks_impact, hit), h = (uint32_t)(hit - cs->pairs), q = 0, np = 0, ih = 0;
	const uint32_t *cl = NULL;
	for (; q < nq && !cl; q++)
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++)
			if (cs->cl[a] == h) cl = cs->cl + cs->cstart[q], np = cs->cstart[q + 1] - cs->cstart[q], ih = a - cs->cstart[q];
	if (!cl || np > DIRECT_MAX) return -1;
	double *G = cs->G, *n = cs->nv;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double curv, vr[3];
		geometry(c, m, n + 3 * a, &curv);
		rel(c, m, I(c, V), J(c, V), vr);
		cs->v0[a] = dot3(vr, n + 3 * a);
		cs->act[a] = a == ih;
		cs->lam[a] = 0;
	}
	for (uint32_t a = 0; a < np; a++) /* G = the normals' coupling, once each normal is known */
		for (uint32_t b = 0; b < np; b++) {
			double w = coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
			G[a * np + b] = w == 0 ? 0 : w * dot3(n + 3 * a, n + 3 * b);
		}
	for (uint32_t iter = 0; iter < 4 * np + 8; iter++) {
		uint32_t dim = 0;
		for (uint32_t a = 0; a < np; a++) {
			if (!cs->act[a]) continue;
			cs->at[dim] = a;
			cs->rhs[dim] = (a == ih ? target : 0) - cs->v0[a];
			dim++;
		}
		for (uint32_t r = 0; r < dim; r++)
			for (uint32_t k = 0; k < dim; k++) cs->K[r * dim + k] = G[cs->at[r] * np + cs->at[k]];
		if (solve(cs, dim)) return -1;
		for (uint32_t a = 0; a < np; a++) cs->lam[a] = 0;
		for (uint32_t r = 0; r < dim; r++) cs->lam[cs->at[r]] = cs->x[r];
		long out = -1, in = -1;
		double worst = -1e-14 * size;
		for (uint32_t a = 0; a < np; a++) /* a contact that would pull: its impulse's effect */
			if (cs->act[a] && a != ih && cs->lam[a] * G[a * np + a] < worst) worst = cs->lam[a] * G[a * np + a], out = a;
		if (out < 0) {
			worst = -1e-14 * size;
			for (uint32_t a = 0; a < np; a++) { /* a contact that would close */
				if (cs->act[a]) continue;
				double v = cs->v0[a];
				for (uint32_t b = 0; b < np; b++) v += G[a * np + b] * cs->lam[b];
				if (v < worst) worst = v, in = a;
			}
		}
		if (out >= 0) cs->act[out] = 0;
		else if (in >= 0) cs->act[in] = 1;
		else {
			for (uint32_t a = 0; a < np; a++) {
				cpair *c = &cs->pairs[cl[a]];
				double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), P = cs->lam[a];
				for (int k = 0; k < 3; k++) {
					m[I(c, V) + k] += P * n[3 * a + k] * wi;
					if (!c->plane) m[J(c, V) + k] -= P * n[3 * a + k] * wj;
				}
			}
			return 0;
		}
	}
	return -1;
}

/*
 * The impact of pair hit, whose relative normal velocity vn becomes target,
 * together with the pairs in contact, which stay in contact (their normal
 * velocities do not close): a ball landing on one that rests on the floor
 * rebounds as from the floor. Their impulses are solved directly
 * (cluster_impulses), or where that fails by Gauss-Seidel sweeps, each
 * pair's correcting its velocity in turn (the contacts' only pushing).
 * Returns 0, or 1 when the sweeps did not converge either (masses that
 * differ by more than the direct solve's 1e10 in a cluster).
 */
static int collide(csf_contacts *cs, double *m, cpair *hit, double target, double vn)
{
	double size = fabs(target) + fabs(vn);
	if (!cluster_impulses(cs, m, hit, target, size)) return 0;
	for (int sweep = 0; sweep < 1000; sweep++) {
		double change = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			if (c != hit && !in_contact(c)) continue;
			double n[3], curv, vr[3], dv[3];
			geometry(c, m, n, &curv);
			rel(c, m, I(c, V), J(c, V), vr);
			double v = dot3(vr, n), d = c == hit ? target - v : csf_max(0, -v);
			size = csf_max(size, fabs(v)); /* converged: to the rounding of the fastest pair's velocity */
			if (d == 0) continue;
			for (int k = 0; k < 3; k++) dv[k] = d * n[k];
			add_impulse(c, m, dv);
			change = csf_max(change, fabs(d));
		}
		if (change <= 1e-15 * size) return 0;
	}
	return 1;
}

/* Before an impact: each pair in contact's relative velocity into W_VR, for after_impact. */
static void before_impact(csf_contacts *cs, const double *m)
{
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		if (in_contact(c)) rel(c, m, I(c, V), J(c, V), WV(c, VR));
	}
}

/*
 * After an impact (whose impulses are normal: impacts are frictionless),
 * each pair in contact whose relative velocity it changed (from W_VR) takes
 * its mode afresh from the velocity it is left with. It separates if its
 * bodies move apart (a pair in contact takes no impulse that would pull,
 * and may be left separating: a ball struck from below its centre leaves
 * the table), unless they part so slowly that the hop that follows would
 * end within the Zeno time (at_rest, with the relative normal acceleration
 * that the pair's normal force alone would leave: an overestimate among
 * several contacts): such a parting is the rounding of the impulses (some
 * 1e-9 of the impact's speed among masses 1e7 apart), and the pair stays
 * in contact. In contact, it slides the way it now slips or,
 * if it no longer slips, sticks (until static friction cannot hold). Its
 * mode from before the impact would keep it in contact as it moves away,
 * hold it at the new velocity (sticking), or stop it by an impulse of
 * friction (sliding, the slip turned back).
 */
static void after_impact(csf_contacts *cs, double *m, double zeno)
{
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		double n[3], curv, vr[3];
		if (!in_contact(c)) continue;
		rel(c, m, I(c, V), J(c, V), vr);
		if (memcmp(vr, WV(c, VR), sizeof vr) == 0) continue;
		geometry(c, m, n, &curv);
		double vn = dot3(vr, n), an = -W(c, LAM) * (inv_mass_i(c, m) + inv_mass_j(c, m));
		if (vn > 0 && !at_rest(c, m, vn, an, zeno)) separate(c, m);
		else enter_contact(c, m, n);
	}
}

/* Do pairs c and d share a body (a plane is no body: it does not move)? */
static int share_body(const cpair *c, const cpair *d)
{
	uint32_t ci = I(c, POS), cj = c->plane ? 0 : J(c, POS), di = I(d, POS), dj = d->plane ? 0 : J(d, POS);
	return c != d && (ci == di || ci == dj || (cj && (cj == di || cj == dj)));
}

/* Is a body of pair c in contact with, or touching, a third one? */
static int crowded(csf_contacts *cs, const double *m, const cpair *c)
{
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *d = &cs->pairs[i];
		double n[3], curv;
		if (share_body(c, d) && (in_contact(d) || touching(d, m, geometry(d, m, n, &curv)))) return 1;
	}
	return 0;
}

/*
 * How a touching pair goes on that separates at normal speed v >= 0 with
 * relative normal acceleration an (after its impact, lifted off by
 * another's, or at the start): at rest in contact (at_rest), on a hop too
 * low for the positions to follow (hops), followed by its flight time, or
 * apart. A low hop among several touching bodies (a ball on a ball on the
 * floor; a ball lifted off by an impact, which touches the body that hit
 * it) is a rest: the impulses that follow are passed on within this
 * instant.
 */
enum { FLIES, HOPS, RESTS };

static int departure(csf_contacts *cs, const double *m, const cpair *c, double v, double an, double zeno, double tol)
{
	if (at_rest(c, m, v, an, zeno)) return RESTS;
	if (!hops(c, m, v, an, tol)) return FLIES;
	return crowded(cs, m, c) ? RESTS : HOPS;
}

/* Hops from time t at normal speed v >= 0 (an < 0): it lands after 2 v/|an|. */
static void hop(cpair *c, double t, double v, double an)
{
	W(c, MODE) = HOPPING;
	W(c, TL) = t + 2 * v / -an;
}

/*
 * The impacts csf_contact_settle follows at one instant before it gives
 * up: each is one pass (an evaluation and a look at the n pairs), and
 * impacts propagate pair by pair. A light ball between heavy ones goes back
 * and forth between them some pi sqrt(M/m) times (as the block on a wall
 * counts pi's digits), so a bound of 1e6/(n + 1) beyond 100 + 10 n admits
 * mass ratios up to about 1e9 in a small scene, in well under a second.
 */
uint64_t csf_contact_passes(uint32_t n)
{
	return 100 + 10 * (uint64_t)n + 1000000 / ((uint64_t)n + 1);
}

int csf_contact_settle(const csf_prog *p, double *m, double zeno, double tol, csf_eval_fn eval, void *ctx)
{
	csf_contacts *cs = p->crun;
	if (!cs) return 0;
	/* each pass evaluates the forces and guards of the current modes, then acts on what they say */
	/* impacts, up to csf_contact_passes; other changes of mode (rest, lift-off, stick, slip),
	   up to 100 + 10 n passes in all, after which the modes stand as they are (if they are
	   not consistent, the events that follow at this instant say so: csfvm(1)) */
	uint64_t hits = 0, others = 0;
	for (;;) {
		if (eval(ctx)) return -1;
		/* the most violent impact first; each changes velocities, so look again */
		long hit = -1;
		double worst = 0;
		int changed = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			if (in_contact(c)) continue;
			double n[3], curv, vr[3], ar[3];
			double gap = geometry(c, m, n, &curv);
			int landing = 0;
			if (W(c, MODE) == HOPPING) { /* nothing until it lands (it may have been knocked away) */
				if (W(c, G0) >= 0) continue;
				W(c, MODE) = APART;
				changed = 1;
				/* its positions are no closer than that; past the plane's edge it falls */
				landing = gap <= too_low(c, m, tol) && inside(c, m) > 0;
			}
			if (!landing && !touching(c, m, gap)) continue;
			rel(c, m, I(c, V), J(c, V), vr);
			rel(c, m, I(c, A), J(c, A), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv;
			if (vn < 0) {
				if (vn < worst) worst = vn, hit = (long)i;
				continue;
			}
			if (gap < 0) close_gap(c, m, n, gap), gap = 0; /* apart by rounding: arm its guard */
			if (hit >= 0) continue;
			int how = departure(cs, m, c, vn, an, zeno, tol);
			if (how == RESTS) { /* pressed together, at rest: contact */
				close_gap(c, m, n, gap);
				for (int k = 0; k < 3; k++) vr[k] = -vn * n[k];
				add_impulse(c, m, vr);
				enter_contact(c, m, n);
				changed = 1;
			} else if (how == HOPS) { /* alone, parting a little (at the start) */
				hop(c, m[p->tslot], vn, an);
				changed = 1;
			}
		}
		if (hit >= 0) {
			if (++hits > csf_contact_passes(cs->n)) return CSF_SETTLE_ENDLESS;
			cpair *c = &cs->pairs[hit];
			double n[3], curv, vr[3], ar[3];
			double gap = geometry(c, m, n, &curv);
			rel(c, m, I(c, V), J(c, V), vr);
			rel(c, m, I(c, A), J(c, A), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv, sep = -restitution(c, m) * vn;
			int how = sep == 0 ? RESTS : departure(cs, m, c, sep, an, zeno, tol);
			before_impact(cs, m);
			if (collide(cs, m, c, how == RESTS ? 0 : sep, vn)) return CSF_SETTLE_IMPULSES;
			after_impact(cs, m, zeno);
			close_gap(c, m, n, gap);
			if (how == RESTS) enter_contact(c, m, n);
			else if (how == HOPS) hop(c, m[p->tslot], sep, an);
			for (uint32_t i = 0; i < cs->n; i++) /* flights whose velocities just changed */
				if (share_body(c, &cs->pairs[i]) && W(&cs->pairs[i], MODE) == HOPPING)
					W(&cs->pairs[i], MODE) = APART;
			continue;
		}
		/* a guard of a pair in contact that is negative: its transition (contact.c's header) */
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			if (!in_contact(c)) continue;
			if (W(c, G0) < 0) separate(c, m), changed = 1;
			else if (W(c, G1) < 0) (W(c, MODE) == SLIDING ? stick : slide)(c, m), changed = 1;
		}
		if (!changed || ++others >= 100 + 10 * (uint64_t)cs->n) return 0;
	}
}
