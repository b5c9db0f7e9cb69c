/*
 * force.c - the force stage (csf_contact_apply): the contact forces of the
 * pairs in contact, normal force and friction, each cluster solved directly
 * (cluster.c) or by Gauss-Seidel sweeps; then every pair's guards.
 */
#include "contact_int.h"

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

/* For csf_contact_clusters(): the pairs in contact. */
static int picks_contact(const cpair *c, const void *arg)
{
	(void)arg;
	return in_contact(c);
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
		csf_contact_slip_velocity(c, m, n, vt);
		double s = mag3(vt);
		int ahead = dot3(vt, WV(c, DS)) > 0;
		for (int j = 0; j < 3; j++) u[j] = ahead ? vt[j] / s : WV(c, DS)[j];
		k = mu_k(c, m) * sign;
	}
	for (int j = 0; j < 3; j++) B[j] = n[j] - k * u[j], E[j] = n[j];
	return 1;
}

/*
 * The contact forces of cluster cl[0..np), solved directly (cluster.c); fails
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
			csf_contact_geometry(c, m, n + 3 * a, &curv);
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
				double w = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
				if (w == 0) continue;
				for (int r = 0; r < cs->dc[a]; r++)
					for (int q = 0; q < cs->dc[b]; q++)
						cs->K[(size_t)(cs->at[a] + r) * dim + cs->at[b] + q] =
							w * dot3(E + 9 * a + 3 * r, B + 9 * b + 3 * q);
			}
		if (csf_contact_solve(cs, dim)) return -1;
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
		csf_contact_geometry(c, m, n, &curv);
		rel(c, m, I(c, A), J(c, A), ar);
		r = csf_max(r, fabs(dot3(ar, n) + curv));
	}
	return r;
}

int csf_contacts_unsolved(const csf_contacts *c) { return c->unsolved; }

void csf_contact_apply(const csf_prog *p, const csf_exec_ctx *x, double *m)
{
	csf_contacts *cs = x ? x->contacts : NULL;
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
	/* each cluster directly; those it does not take (cluster.c) by Gauss-Seidel sweeps */
	uint32_t nq = csf_contact_clusters(cs, picks_contact, NULL), sweeps = 0; /* some cluster needs them */
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
			csf_contact_geometry(c, m, n, &curv);
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
				csf_contact_slip_velocity(c, m, n, vt);
				/* against the sliding; once it has turned back (past the guard's zero, before the
				   event is located) against its direction at the start, so that the force is smooth
				   up to the crossing and the integrator sees no switching */
				double s = mag3(vt), k = mu_k(c, m) * fabs(W(c, LAM));
				int ahead = dot3(vt, WV(c, DS)) > 0;
				for (int j = 0; j < 3; j++) f[j] = -k * (ahead ? vt[j] / s : WV(c, DS)[j]);
			} else { /* sticking: cancel the relative tangential acceleration */
				double at[3];
				rel(c, m, I(c, A), J(c, A), ar);
				csf_contact_tangential(ar, n, at);
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
		double gap = csf_contact_geometry(c, m, n, &curv);
		double *g = WV(c, G0);
		double in = csf_contact_inside(c, m);
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
			csf_contact_slip_velocity(c, m, n, vt);
			g[1] = dot3(vt, WV(c, DS));
		} else {
			g[1] = mu_s(c, m) * fabs(W(c, LAM)) - mag3(WV(c, F));
		}
	}
}
