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
int csf_contact_picks_contact(const cpair *c, const void *arg)
{
	(void)arg;
	return in_contact(c);
}

/* The sum of the speeds of the pair's bodies. */
double csf_contact_speeds(const cpair *c, const double *m)
{
	return mag3(m + I(c, V)) + (c->plane ? 0 : mag3(m + J(c, V)));
}

/*
 * The smallest relative speed (or slip) that counts: 1e-13 of the bodies'
 * speeds (no less than least), and of their accelerations times 1 s
 * (csf_contact_accel_resolution): the speeds change by their accelerations
 * times the time within which an event is located, 1e-13 s. A slip that
 * small is the rounding of the impulses and forces that stopped or started
 * it, whose direction is noise: below it a sliding pair's direction is the
 * one it began to slide in (W_DS), not its slip's, whose friction would
 * switch within a step; nor is a subnormal speed between bodies at rest
 * one (DBL_MIN).
 */
double csf_contact_speed_resolution(const cpair *c, const double *m, double least)
{
	double n[3], curv;
	csf_contact_geometry(c, m, n, &curv);
	return csf_max(1e-13 * csf_contact_speeds(c, m), least) + 0.1 * csf_contact_accel_resolution(c, m, curv) + DBL_MIN;
}

/*
 * The way sliding pair c's friction opposes (normal n, ds the direction it
 * began to slide in), into u; returns whether it slips ahead of ds beyond
 * its rounding (csf_contact_speed_resolution). Ahead, u is its slip's
 * direction; within the rounding (a slide that begins) or turned back (past
 * its guard's zero, before the stop is located), ds turned into the tangent
 * plane as it is now, so that the force is smooth up to the crossing and
 * the integrator sees no switching. Turned, not ds itself: the normal of two
 * balls turns as they slide, and ds's part along it changed the force where
 * the slip crossed its rounding, inside a step (a pile of 256 balls
 * rejected 7674 of 12084 steps to t = 0.2 s). ds itself where it is normal
 * to the plane.
 */
static int slide_way(const cpair *c, const double *m, const double n[3], const double ds[3], double u[3])
{
	double vt[3];
	csf_contact_slip_velocity(c, m, n, vt);
	double s = mag3(vt);
	int ahead = dot3(vt, ds) > csf_contact_speed_resolution(c, m, 0);
	if (ahead) {
		for (int k = 0; k < 3; k++) u[k] = vt[k] / s;
	} else {
		csf_contact_tangential(ds, n, u);
		double t = mag3(u);
		for (int k = 0; k < 3; k++) u[k] = t > 0 ? u[k] / t : ds[k];
	}
	return ahead;
}

/*
 * Pair c's force directions B (3 x d, column-major) and equations E likewise, in mode mode: d = 3
 * when it sticks (its whole force; every direction of its relative acceleration), else its
 * normal force with sliding friction -mu_k |N| along the way it slips or, where it does not slip
 * ahead of ds (a slide that begins, or stopped: the direction it began to slide in), along ds,
 * and then (d = 2) the friction across ds that keeps it from slipping sideways: it begins to slip
 * along ds, or, held by its neighbours, stays at rest with a static friction whose part along ds
 * is mu_k |N|. Returns d.
 */
int csf_contact_basis(const cpair *c, const double *m, const double n[3], double sign, int mode, const double ds[3],
                      double B[9], double E[9])
{
	if (has_friction(c, m) && mode == STICKING) {
		for (int k = 0; k < 9; k++) B[k] = E[k] = k % 4 == 0;
		return 3;
	}
	double u[3] = { 0, 0, 0 }, k = 0, w[3] = { 0, 0, 0 };
	int ahead = 0;
	if (has_friction(c, m)) { /* sliding: -mu_k |N| along the way it slides (as csf_contact_apply's sweeps) */
		ahead = slide_way(c, m, n, ds, u);
		k = mu_k(c, m) * sign;
		w[0] = n[1] * u[2] - n[2] * u[1], w[1] = n[2] * u[0] - n[0] * u[2], w[2] = n[0] * u[1] - n[1] * u[0];
	}
	for (int j = 0; j < 3; j++) B[j] = n[j] - k * u[j], E[j] = n[j];
	double sw = mag3(w);
	if (ahead || !(sw > 0)) return 1;
	for (int j = 0; j < 3; j++) B[3 + j] = E[3 + j] = w[j] / sw;
	return 2;
}

/*
 * The linear system of the contact forces of the pairs cl[0..np), each as
 * if in contact in its mode (sign as in cluster_forces): pair a's unknowns
 * from row at[a], dc[a] of them, its normal in nv; the matrix, dim x dim
 * row-major, into K, with every mass 1 and the equations' directions for the
 * forces' into K1 (csf_contact_solve), and the right-hand side into rhs (the
 * accelerations in m are those of the other forces). Returns dim, or 0 past
 * DIRECT_MAX.
 */
static uint32_t cluster_system(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, const double *sign,
                               double *K, double *K1, double *rhs)
{
	double *n = cs->nv, *B = cs->B, *E = cs->E;
	uint32_t dim = 0;
	if (np > DIRECT_MAX) return 0;
	for (uint32_t a = 0; a < np; a++) { /* each pair's normal, force directions and equations */
		const cpair *c = &cs->pairs[cl[a]];
		double curv, ar[3];
		csf_contact_geometry(c, m, n + 3 * a, &curv);
		cs->dc[a] = (unsigned char)csf_contact_basis(c, m, n + 3 * a, sign ? sign[a] : 1, (int)W(c, MODE), WV(c, DS),
		                                             B + 9 * a, E + 9 * a);
		cs->at[a] = dim;
		dim += cs->dc[a];
		if (dim > DIRECT_MAX) return 0;
		rel(c, m, I(c, A), J(c, A), ar);
		for (int r = 0; r < cs->dc[a]; r++)
			rhs[cs->at[a] + r] = -(dot3(E + 9 * a + 3 * r, ar) + curv * dot3(E + 9 * a + 3 * r, n + 3 * a));
	}
	memset(K, 0, (size_t)dim * dim * sizeof *K);
	memset(K1, 0, (size_t)dim * dim * sizeof *K1);
	/* only pairs that share a body are coupled: their bodies' slots compared first (a cluster of
	   np pairs has np^2 pairs of pairs, a few per row coupled) */
	uint32_t bi[DIRECT_MAX], bj[DIRECT_MAX];
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		bi[a] = I(c, POS), bj[a] = c->plane ? UINT32_MAX : J(c, POS);
	}
	for (uint32_t a = 0; a < np; a++)
		for (uint32_t b = 0; b < np; b++) {
			if (bi[a] != bi[b] && bi[a] != bj[b] && (bj[a] == UINT32_MAX || (bj[a] != bi[b] && bj[a] != bj[b])))
				continue;
			double w = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
			double w1 = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], NULL);
			if (w == 0 && w1 == 0) continue;
			for (int r = 0; r < cs->dc[a]; r++)
				for (int q = 0; q < cs->dc[b]; q++) {
					size_t at = (size_t)(cs->at[a] + r) * dim + cs->at[b] + q;
					K[at] = w * dot3(E + 9 * a + 3 * r, B + 9 * b + 3 * q);
					K1[at] = w1 * dot3(E + 9 * a + 3 * r, E + 9 * b + 3 * q);
				}
		}
	return dim;
}

static int lcp_cluster(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, const double *res, const double *sign,
                       uint32_t *dimp);
static int cluster_parts(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, const double *sign);
static void force_resolutions(const csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, double *res);

/*
 * The contact forces of cluster cl[0..np) whose pairs cannot all stay in
 * contact (their system has no solution; not masses that differ too much):
 * those of the pairs that press (lcp_cluster); a pair that does not has no
 * force, and its normal force's place (W_LAM, its guard) holds minus its
 * relative normal acceleration (per unit of inverse mass), so that its
 * guard says it parts and the event that follows separates it; sign as in
 * cluster_system (NULL: every pair's friction as its mode says). 0, or -1.
 */
static int cluster_parts(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, const double *sign)
{
	double res[DIRECT_MAX];
	uint32_t dim = 0;
	force_resolutions(cs, m, cl, np, res);
	for (uint32_t a = 0; a < np; a++) cs->act[a] = 1;
	if (lcp_cluster(cs, m, cl, np, res, sign, &dim)) return -1;
	for (uint32_t a = 0; a < np; a++) {
		cpair *c = &cs->pairs[cl[a]];
		double F[3] = { 0, 0, 0 }, *na = cs->nv + 3 * a, fn[3], *f = WV(c, F), an = 0;
		for (int q = 0; q < cs->dc[a]; q++) {
			uint32_t row = cs->at[a] + (uint32_t)q;
			double acc = -cs->v0[row];
			for (uint32_t k = 0; k < dim; k++) acc += cs->G[(size_t)row * dim + k] * cs->lam[k];
			an += acc * dot3(cs->E + 9 * a + 3 * q, na);
			for (int k = 0; k < 3; k++) F[k] += cs->B[9 * a + 3 * q + k] * cs->lam[row];
		}
		double lam = cs->act[a] ? dot3(F, na) : -an / (inv_mass_i(c, m) + inv_mass_j(c, m));
		for (int k = 0; k < 3; k++) fn[k] = cs->act[a] ? lam * na[k] : 0, f[k] = cs->act[a] && has_friction(c, m) ? F[k] - fn[k] : 0;
		W(c, LAM) = lam;
		add_force(c, m, fn, I(c, FN), J(c, FN));
		add_force(c, m, f, I(c, FF), J(c, FF));
	}
	return 0;
}

/* The forces of the solution cs->x of cluster_system's system for cl[0..np) added to the bodies. */
static void cluster_apply(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np)
{
	const double *n = cs->nv, *B = cs->B;
	for (uint32_t a = 0; a < np; a++) {
		cpair *c = &cs->pairs[cl[a]];
		double F[3] = { 0, 0, 0 };
		const double *na = n + 3 * a;
		for (int q = 0; q < cs->dc[a]; q++)
			for (int k = 0; k < 3; k++) F[k] += B[9 * a + 3 * q + k] * cs->x[cs->at[a] + q];
		/* F = N n + the friction force */
		double lam = cs->dc[a] < 3 ? cs->x[cs->at[a]] : dot3(F, na), fn[3], *f = WV(c, F);
		for (int k = 0; k < 3; k++) fn[k] = lam * na[k], f[k] = has_friction(c, m) ? F[k] - fn[k] : 0;
		W(c, LAM) = lam;
		add_force(c, m, fn, I(c, FN), J(c, FN));
		add_force(c, m, f, I(c, FF), J(c, FF));
	}
}

/* Sets sign 0 for the sliding pairs with friction of cl[0..np); 1 if there is one. */
static int drop_sliding(const csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, double *sign)
{
	int sliding = 0;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		if (has_friction(c, m) && W(c, MODE) == SLIDING) sign[a] = 0, sliding = 1;
	}
	return sliding;
}

/*
 * The contact forces of cluster cl[0..np) whose system has no solution
 * (its direct solve failed, sign as there): if it has one without the
 * sliding pairs' friction, sliding friction locks the contacts (Painlevé:
 * a column of balls sliding against each other, each contact's friction
 * pressing the next harder, whose forces grow without bound as the column
 * leans into it). The forces are those without that friction, and each
 * sliding pair's guard 1 says it stops (W_LOCK): the event that follows
 * stops its slip by an impulse of friction, and it sticks if static
 * friction can hold. Otherwise the pairs that cannot all hold
 * (cluster_parts). lock_solve is the first part: the system without the
 * sliding pairs' friction (sign 0 for them) solved into cs->x and their
 * locks set, 0; or -1 (no sliding pair, masses that differ by 1e6 or
 * more, or no solution).
 */
static int lock_solve(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, double *sign)
{
	int sliding = drop_sliding(cs, m, cl, np, sign);
	double wratio = csf_contact_mass_ratio(cs, cl, np, m);
	if (!sliding || !(wratio < 1e6)) return -1;
	uint32_t dim = cluster_system(cs, m, cl, np, sign, cs->K, cs->K1, cs->rhs);
	if (!dim) return -1;
	csf_contact_frames(np, cs->dc, cs->nv, dim, cs->T, cs->fric);
	if (csf_contact_solve(cs, dim, cs->K1, wratio, cs->T, cs->fric)) return -1;
	for (uint32_t a = 0; a < np; a++) {
		cpair *c = &cs->pairs[cl[a]];
		if (sign[a] == 0) W(c, LOCK) = 1;
	}
	return 0;
}

static int cluster_locks(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, double *sign)
{
	if (lock_solve(cs, m, cl, np, sign)) return cluster_parts(cs, m, cl, np, NULL);
	cluster_apply(cs, m, cl, np);
	return 0;
}

/*
 * The contact forces of cluster cl[0..np), solved directly (cluster.c); fails
 * (-1, nothing changed) when it has more than DIRECT_MAX unknowns or its
 * system is singular and has no solution. The accelerations in m are those
 * of the other forces. Where a pair's normal force would pull beyond its
 * rounding (a pair lifting off within a step, before the event is located;
 * or the least-norm forces of a statically indeterminate cluster, which
 * take no account of N >= 0: two balls jammed between two walls, squeezed
 * by a third, whose sliding friction turns the squeeze into a vertical
 * force, may take a squeeze of -39 N), the pairs that press are chosen as a
 * complementarity problem (cluster_parts), whose forces push only: a
 * sliding pair's friction is -mu_k N along its slip, with N >= 0, and so
 * never drives it (before, a sliding pair whose N came out negative was
 * solved again with its friction turned, and where that gave N > 0 its
 * friction pushed along its slip: a jammed ball rose, gaining energy).
 */
static int cluster_forces(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np)
{
	if (np > DIRECT_MAX) return -1;
	double sign[DIRECT_MAX], res[DIRECT_MAX]; /* sign: 1, or 0 for a pair whose friction locks it */
	double *n = cs->nv, *B = cs->B;
	for (uint32_t a = 0; a < np; a++) sign[a] = 1;
	uint32_t dim = cluster_system(cs, m, cl, np, sign, cs->K, cs->K1, cs->rhs);
	if (!dim) return -1;
	csf_contact_frames(np, cs->dc, cs->nv, dim, cs->T, cs->fric);
	if (csf_contact_solve(cs, dim, cs->K1, csf_contact_mass_ratio(cs, cl, np, m), cs->T, cs->fric))
		return cluster_locks(cs, m, cl, np, sign);
	force_resolutions(cs, m, cl, np, res);
	/* a cluster whose modes were found only with forces within the cones (modes.c): its sticking
	   pairs' friction kept within them, and no normal force pulling, where other forces of the same
	   motion can (spread.c) */
	int spread = 0;
	for (uint32_t a = 0; a < np; a++) spread |= W(&cs->pairs[cl[a]], SPREAD) != 0;
	if (spread) {
		unsigned char cone[DIRECT_MAX];
		for (uint32_t a = 0; a < np; a++) {
			const cpair *c = &cs->pairs[cl[a]];
			cone[a] = has_friction(c, m) && W(c, MODE) == STICKING;
		}
		csf_contact_spread(cs, m, cl, np, dim, cs->dc, cs->at, cs->B, cs->nv, cone, cs->x);
	}
	for (uint32_t a = 0; a < np; a++) { /* a pair that pulls: the pairs that press (cluster_parts) */
		double F[3] = { 0, 0, 0 };
		for (int q = 0; q < cs->dc[a]; q++)
			for (int k = 0; k < 3; k++) F[k] += B[9 * a + 3 * q + k] * cs->x[cs->at[a] + q];
		if (!((cs->dc[a] < 3 ? cs->x[cs->at[a]] : dot3(F, n + 3 * a)) < -res[a])) continue;
		double keep[DIRECT_MAX];
		memcpy(keep, cs->x, dim * sizeof *keep);
		if (!cluster_parts(cs, m, cl, np, NULL)) return 0;
		/* none: its sliding pairs' friction locks them (a ball jammed between a wall and another,
		   whose squeeze its sliding friction turns into a force along its slip, is wedged): the pairs
		   that press without that friction, or its system's solution without it (lock_solve); else
		   the least-norm forces, whose pull its guard reports */
		if (drop_sliding(cs, m, cl, np, sign) && !cluster_parts(cs, m, cl, np, sign)) {
			for (uint32_t b = 0; b < np; b++)
				if (sign[b] == 0) W(&cs->pairs[cl[b]], LOCK) = 1;
			return 0;
		}
		for (uint32_t b = 0; b < np; b++) sign[b] = 1;
		if (!lock_solve(cs, m, cl, np, sign)) break;
		for (uint32_t b = 0; b < np; b++) sign[b] = 1;
		dim = cluster_system(cs, m, cl, np, sign, cs->K, cs->K1, cs->rhs); /* B, at and dc as they were */
		memcpy(cs->x, keep, dim * sizeof *keep);
		break;
	}
	cluster_apply(cs, m, cl, np);
	return 0;
}

/* For csf_contact_clusters(): the pairs marked in the array arg. */
static int picks_marked(const cpair *c, const void *arg)
{
	const csf_contacts *cs = *(const csf_contacts *const *)arg;
	return cs->mark[c - cs->pairs] != 0;
}

/*
 * lcp_cluster's set cs->act solved: every pair's unknowns into cs->lam (0
 * for those apart), its normal force into lam[a] and its relative normal
 * acceleration (per unit of inverse mass) into an[a]. Returns 1 when the
 * set's forces keep its accelerations zero, 0 when they cannot (the
 * least-squares forces), -1 when neither solves.
 */
static int lcp_solve(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, uint32_t dim, double wratio,
                     double *lam, double *an)
{
	uint32_t sub = 0, rows[DIRECT_MAX];
	unsigned char dc[DIRECT_MAX];
	double *x = cs->lam;
	for (uint32_t a = 0; a < np; a++) {
		dc[a] = cs->act[a] ? cs->dc[a] : 0;
		for (int r = 0; r < dc[a]; r++) rows[sub++] = cs->at[a] + (uint32_t)r;
	}
	for (uint32_t r = 0; r < sub; r++) {
		cs->rhs[r] = cs->v0[rows[r]];
		for (uint32_t k = 0; k < sub; k++) {
			cs->K[r * sub + k] = cs->G[(size_t)rows[r] * dim + rows[k]];
			cs->K1[r * sub + k] = cs->G1[(size_t)rows[r] * dim + rows[k]];
		}
	}
	csf_contact_frames(np, dc, cs->nv, sub, cs->T, cs->fric);
	int solved = !sub || !csf_contact_solve(cs, sub, cs->K1, wratio, cs->T, cs->fric);
	if (!solved && (!(wratio < 1e6) || csf_contact_least_squares(cs, sub, cs->T, cs->fric))) return -1;
	memset(x, 0, dim * sizeof *x);
	for (uint32_t r = 0; r < sub; r++) x[rows[r]] = cs->x[r];
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double *na = cs->nv + 3 * a;
		an[a] = lam[a] = 0;
		for (int r = 0; r < cs->dc[a]; r++) {
			uint32_t row = cs->at[a] + (uint32_t)r;
			double acc = -cs->v0[row];
			for (uint32_t k = 0; k < dim; k++) acc += cs->G[(size_t)row * dim + k] * x[k];
			an[a] += acc * dot3(cs->E + 9 * a + 3 * r, na);
			lam[a] += dot3(cs->B + 9 * a + 3 * r, na) * x[row];
		}
		an[a] /= inv_mass_i(c, m) + inv_mass_j(c, m);
	}
	return solved;
}

/* Room for lcp_sets to remember sets sets of np pairs: 1, or 0 (no memory: none remembered). */
static int seen_room(csf_contacts *cs, uint32_t sets, uint32_t np)
{
	size_t n = (size_t)sets * np;
	if (n > cs->capseen) {
		unsigned char *s = realloc(cs->seen, n);
		if (!s) return 0;
		cs->seen = s, cs->capseen = n;
	}
	if (sets > cs->capseenh) {
		uint64_t *h = realloc(cs->seenh, sets * sizeof *h);
		if (!h) return 0;
		cs->seenh = h, cs->capseenh = sets;
	}
	return 1;
}

/* Whether the set cs->act[0..np) is one of lcp_sets' sets 0..iter-1; if not, it is kept as set iter. */
static int been_here(csf_contacts *cs, uint32_t np, uint32_t iter)
{
	uint64_t h = csf_hash_bytes(cs->act, np);
	for (uint32_t k = 0; k < iter; k++)
		if (cs->seenh[k] == h && !memcmp(cs->seen + (size_t)k * np, cs->act, np)) return 1;
	cs->seenh[iter] = h;
	memcpy(cs->seen + (size_t)iter * np, cs->act, np);
	return 0;
}

/*
 * The pairs of cluster cl[0..np) that press, and their forces: a linear
 * complementarity problem. Each pair either pushes (N >= 0) and keeps its
 * relative normal acceleration zero, or takes no force and is left with a
 * relative normal acceleration that does not close (>= 0); beyond rounding
 * (res, per pair: csf_contact_accel_resolution, in force per unit of
 * inverse mass). By active sets, from the pairs marked in cs->act: a pair
 * that would pull leaves, or else the apart pair that would close fastest
 * joins, until neither happens. Of the pairs that would pull, the one that
 * leaves is the one that pulls most among those whose leaving does not
 * close them (the one that pulls most if every one would close): in a
 * statically indeterminate cluster the least-norm forces may pull at
 * several pairs of which one is redundant, and it leaves, the others
 * holding it at zero acceleration with no force; were another to leave, it
 * would close, join again, and the sets would go round (a ball jammed
 * between a wall and another whose squeeze, turned by the friction of its
 * slides into a vertical force, came out as a pull at both); where the sets
 * so chosen go round (a set comes again: what followed it follows again,
 * but for a rank or a fit a solve holds, cluster.c; or 4 np + 8 changes),
 * they are chosen again from the
 * start with the pair that pulls most leaving, as before. Where a set's
 * forces cannot keep all of its accelerations zero (contacts all but
 * redundant that the motion pulls apart: a ball sliding past another
 * between two walls), the pair that the least-squares forces leave parting
 * fastest leaves. Each solve as cluster_forces does, the friction of each
 * pair as its mode says (sign as in cluster_system: lcp_cluster's, NULL
 * for every pair's). The accelerations in m are those of the other
 * forces. Returns 0 with the set in cs->act, every pair's unknowns in
 * cs->lam (0 for those apart) and the system in cs->G, cs->v0; -1 when the
 * sets go round.
 */
static int lcp_sets(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, const double *res, uint32_t dim,
                    int open_first)
{
	double wratio = csf_contact_mass_ratio(cs, cl, np, m), lam[DIRECT_MAX], an[DIRECT_MAX];
	uint32_t most = 4 * np + 8;
	int track = seen_room(cs, most, np);
	for (uint32_t iter = 0; iter < most; iter++) {
		if (track && been_here(cs, np, iter)) return -1; /* round: it would go on so to the end */
		int solved = lcp_solve(cs, m, cl, np, dim, wratio, lam, an);
		if (solved < 0) return -1;
		long out = -1, in = -1, pulls = 0;
		double worst = 0;
		for (uint32_t a = 0; a < np; a++) {
			if (!solved) { /* a set that cannot hold: the pair parting fastest leaves */
				if (cs->act[a] && an[a] > res[a] && -an[a] / res[a] < worst) worst = -an[a] / res[a], out = a;
			} else if (cs->act[a]) { /* a pair that would pull: its normal force */
				if (lam[a] < -res[a] && lam[a] / res[a] < worst) worst = lam[a] / res[a], out = a;
				pulls += lam[a] < -res[a];
			} else if (an[a] < -res[a] && an[a] / res[a] < worst) /* an apart pair that would close */
				worst = an[a] / res[a], in = a;
		}
		if (!solved && out < 0) return -1;
		if (open_first && pulls > 1) { /* the pair that pulls most of those whose leaving leaves them open */
			double pull[DIRECT_MAX], an2[DIRECT_MAX], lam2[DIRECT_MAX];
			memcpy(pull, lam, np * sizeof *pull);
			for (long tries = 0; tries < pulls; tries++) {
				long b = -1;
				for (uint32_t a = 0; a < np; a++)
					if (cs->act[a] && pull[a] < -res[a] && (b < 0 || pull[a] / res[a] < pull[b] / res[b])) b = a;
				if (b < 0) break;
				pull[b] = 0, cs->act[b] = 0;
				int open = lcp_solve(cs, m, cl, np, dim, wratio, lam2, an2) > 0 && !(an2[b] < -res[b]);
				cs->act[b] = 1;
				if (open) {
					out = b;
					break;
				}
			}
		}
		if (out >= 0) cs->act[out] = 0;
		else if (in >= 0) cs->act[in] = 1;
		else return 0;
	}
	return -1;
}

static int lcp_cluster(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, const double *res, const double *sign,
                       uint32_t *dimp)
{
	uint32_t dim = cluster_system(cs, m, cl, np, sign, cs->G, cs->G1, cs->v0);
	if (!dim) return -1;
	*dimp = dim;
	unsigned char act[DIRECT_MAX];
	memcpy(act, cs->act, np);
	if (!lcp_sets(cs, m, cl, np, res, dim, 1)) return 0;
	memcpy(cs->act, act, np);
	return lcp_sets(cs, m, cl, np, res, dim, 0);
}

/* The rounding of each pair's normal force (lcp_cluster's res). */
static void force_resolutions(const csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, double *res)
{
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double n[3], curv;
		csf_contact_geometry(c, m, n, &curv);
		res[a] = csf_contact_accel_resolution(c, m, curv) / (inv_mass_i(c, m) + inv_mass_j(c, m));
	}
}

/*
 * Which of the pairs that could press (cl[0..np): those in contact, and
 * those that touch at zero relative normal velocity) are in contact
 * (lcp_cluster, from the pairs in contact), at an instant: m holds the
 * accelerations of every force with the pairs' modes as they are. The
 * result, in cs->act: 1 in contact. Returns 0, or -1 (the modes stay).
 */
static int choose_cluster(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np)
{
	if (np > DIRECT_MAX) return -1;
	double res[DIRECT_MAX];
	uint32_t dim = 0;
	force_resolutions(cs, m, cl, np, res);
	for (uint32_t a = 0; a < np; a++) cs->act[a] = (unsigned char)in_contact(&cs->pairs[cl[a]]);
	for (uint32_t a = 0; a < np; a++) { /* the accelerations without the forces of these pairs */
		cpair *c = &cs->pairs[cl[a]];
		double n[3], curv, fn[3], f[3];
		if (!in_contact(c)) continue;
		csf_contact_geometry(c, m, n, &curv);
		for (int k = 0; k < 3; k++) fn[k] = -W(c, LAM) * n[k], f[k] = -WV(c, F)[k];
		add_force(c, m, fn, I(c, FN), J(c, FN));
		add_force(c, m, f, I(c, FF), J(c, FF));
	}
	return lcp_cluster(cs, m, cl, np, res, NULL, &dim);
}

/*
 * Chooses the modes of the pairs marked in cs->mark (the pairs in contact,
 * and those touching at rest), cluster by cluster: with fresh
 * accelerations (m holds those of the forces of the modes as they are), a
 * cluster with friction chooses them all at once (modes.c); the others,
 * and those it leaves, which pairs are in contact (choose_cluster). The
 * marks become TO_APART, TO_CONTACT, TO_SLIDE or TO_STICK; a cluster whose
 * sets do not settle keeps its modes.
 */
void csf_contact_choose(csf_contacts *cs, double *m, int fresh)
{
	const csf_contacts *self = cs;
	uint32_t nq = csf_contact_clusters(cs, picks_marked, &self);
	for (uint32_t q = 0; q < nq; q++) {
		const uint32_t *cl = cs->cl + cs->cstart[q];
		uint32_t np = cs->cstart[q + 1] - cs->cstart[q];
		if (fresh && !csf_contact_choose_modes(cs, m, cl, np)) continue;
		int settled = !choose_cluster(cs, m, cl, np);
		for (uint32_t a = 0; a < np; a++) {
			int now = settled ? cs->act[a] : in_contact(&cs->pairs[cl[a]]);
			cs->mark[cl[a]] = (unsigned char)(now ? TO_CONTACT : TO_APART);
		}
	}
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
void csf_contacts_set_unsolved(csf_contacts *c, int unsolved) { c->unsolved = unsolved; }

/*
 * An apart pair's guard at positions pi, pj: the gap, beyond the smallest
 * gap those positions resolve (csf_contact_resolution), over the plane (not
 * past its edge). Two bodies that touch and part slowly stay touching
 * within rounding for a while; the gap's rounding is not an impact.
 */
double csf_contact_gap_guard(const cpair *c, const double *m, const double *pi, const double *pj)
{
	double n[3], curv, gap = csf_contact_geometry_at(c, m, pi, pj, n, &curv);
	return csf_max(gap + csf_max(2 * DBL_EPSILON * csf_contact_scale_at(c, m, pi, pj), W(c, LIFT)),
	               -csf_contact_inside_at(c, m, pi));
}

/*
 * The size of the accelerations that meet in a pair: each body's, and the
 * contact forces on it over its mass (a body at rest in a pile has a = 0
 * from forces that are not), and the centripetal term curv. A relative
 * acceleration within 1e-12 of it is zero: the rounding of the forces that
 * cancel is far below that, and a pair that neither presses nor parts (two
 * balls side by side on a floor) is not sent back and forth between
 * touching and parting by the sign of its rounding.
 */
double csf_contact_accel_resolution(const cpair *c, const double *m, double curv)
{
	double s = mag3(m + I(c, A)) + (mag3(m + I(c, FN)) + mag3(m + I(c, FF))) * inv_mass_i(c, m) + fabs(curv);
	if (!c->plane) s += mag3(m + J(c, A)) + (mag3(m + J(c, FN)) + mag3(m + J(c, FF))) * inv_mass_j(c, m);
	return 1e-12 * s;
}

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
		W(c, LAM) = W(c, LOCK) = 0;
	}
	/* each cluster directly; those it does not take (cluster.c) by Gauss-Seidel sweeps */
	uint32_t nq = csf_contact_clusters(cs, csf_contact_picks_contact, NULL), sweeps = 0; /* some cluster needs them */
	cs->hold = 1; /* the forces, continuous in time, hold the friction's rank (cluster.c, held_rank) */
	for (uint32_t q = 0; q < nq; q++) {
		int ok = !cluster_forces(cs, m, cs->cl + cs->cstart[q], cs->cstart[q + 1] - cs->cstart[q]);
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++) cs->direct[cs->cl[a]] = (unsigned char)ok;
		sweeps |= !ok;
	}
	cs->hold = 0;
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
				double u[3], k = mu_k(c, m) * fabs(W(c, LAM)); /* against the way it slides (slide_way) */
				slide_way(c, m, n, WV(c, DS), u);
				for (int j = 0; j < 3; j++) f[j] = -k * u[j];
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
	if (sweeps && residual(cs, m) > 1e-6 * before) {
		cs->unsolved = 1;
		for (uint32_t q = 0; q < nq; q++) /* the first cluster the direct solve did not take */
			if (!cs->direct[cs->cl[cs->cstart[q]]]) {
				csf_contact_unsolvable(cs, cs->cl + cs->cstart[q], cs->cstart[q + 1] - cs->cstart[q], m);
				break;
			}
	}
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
			g[0] = csf_max(gap + csf_max(csf_contact_resolution(c, m), W(c, LIFT)), -in); /* csf_contact_gap_guard */
			g[1] = 1;
			continue;
		}
		/* the normal force would pull (beyond its rounding: csf_contact_accel_resolution), or the
		   body left the edge */
		double wn = inv_mass_i(c, m) + inv_mass_j(c, m);
		g[0] = csf_min(W(c, LAM) + csf_contact_accel_resolution(c, m, curv) / wn, in);
		if (!has_friction(c, m)) {
			g[1] = 1;
		} else if (W(c, MODE) == SLIDING) {
			double vt[3];
			csf_contact_slip_velocity(c, m, n, vt);
			/* it stops, beyond the slip's rounding (csf_contact_speed_resolution: a slide that has just begun has
			   none); locked, at once (cluster_locks); not slipping ahead, its friction (its part across the
			   way it slides is static friction's) grows past what it can hold */
			double ahead = dot3(vt, WV(c, DS)), vres = csf_contact_speed_resolution(c, m, 0);
			g[1] = W(c, LOCK) ? -1 : ahead + vres;
			if (!(ahead > vres)) g[1] = csf_min(g[1], csf_max(mu_s(c, m), mu_k(c, m)) * fabs(W(c, LAM)) - mag3(WV(c, F)));
		} else {
			g[1] = mu_s(c, m) * fabs(W(c, LAM)) - mag3(WV(c, F));
		}
	}
}
