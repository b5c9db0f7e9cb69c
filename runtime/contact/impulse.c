/*
 * impulse.c - impacts: the impulses of a pair that is hit and of the pairs
 * in contact with it, solved directly by active sets (a linear
 * complementarity problem) or by Gauss-Seidel sweeps.
 */
#include "contact_int.h"

/* Changes the relative velocity of the pair by dv (along any direction), conserving momentum. */
void csf_contact_add_impulse(cpair *c, double *m, const double dv[3])
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj;
	for (int k = 0; k < 3; k++) {
		double j = dv[k] / w; /* the impulse on i */
		m[I(c, V) + k] += j * wi;
		if (!c->plane) m[J(c, V) + k] -= j * wj;
	}
}

/* Does pair c take part in the impact of pair hit: the pairs in contact, or with cs->group set
   the pairs marked in cs->mark (csf_contact_settle: every pair that touches)? */
static int joins(const csf_contacts *cs, const cpair *c, const cpair *hit)
{
	return c == hit || (cs->group ? cs->mark[c - cs->pairs] != 0 : in_contact(c));
}

typedef struct impact { const csf_contacts *cs; const cpair *hit; } impact;

/* For csf_contact_clusters(): the pairs that take part in the impact (arg). */
static int picks_impact(const cpair *c, const void *arg)
{
	const impact *im = arg;
	return joins(im->cs, c, im->hit);
}

/* The factors L D L^T of the n x n symmetric positive definite matrix in L (row-major, lower
   half read), in place, D on the diagonal: no square roots, so that a system of small integers
   and halves (equal masses) is solved exactly; -1 if it is not positive definite to rounding
   (a pivot below 1e-15 of its diagonal element). */
static int ldl(double *L, uint32_t n)
{
	for (uint32_t j = 0; j < n; j++) {
		double d = L[j * n + j];
		for (uint32_t k = 0; k < j; k++) d -= L[j * n + k] * L[j * n + k] * L[k * n + k];
		if (!(d > 1e-15 * L[j * n + j])) return -1;
		L[j * n + j] = d;
		for (uint32_t i = j + 1; i < n; i++) {
			double v = L[i * n + j];
			for (uint32_t k = 0; k < j; k++) v -= L[i * n + k] * L[j * n + k] * L[k * n + k];
			L[i * n + j] = v / d;
		}
	}
	return 0;
}

/* Solves L D L^T x = b with ldl's factors (x may be b). */
static void ldl_solve(const double *L, uint32_t n, const double *b, double *x)
{
	for (uint32_t i = 0; i < n; i++) {
		double v = b[i];
		for (uint32_t k = 0; k < i; k++) v -= L[i * n + k] * x[k];
		x[i] = v;
	}
	for (uint32_t i = n; i-- > 0;) {
		double v = x[i] / L[i * n + i];
		for (uint32_t k = i + 1; k < n; k++) v -= L[k * n + i] * x[k];
		x[i] = v;
	}
}

/*
 * How much each pair of an impact yields, in units of its own impulse's
 * effect: a pair's velocity is taken to change by (1 + YIELD) G_aa P_a
 * under its own impulse P_a. Contacts that are redundant to within
 * rounding (a row of balls jammed between two walls, level to 1e-8 rad)
 * leave the impulses' system singular to rounding, its exact answer
 * (impulses of 1e12 N s) meaningless; with the yield, each such impulse is
 * bounded by its pair's velocity over 1e-14 of its effect, and the
 * velocities it leaves are off by 1e-14 of that effect, far below the
 * least velocity that counts. Where the set's system is not singular its
 * answer without the yield is taken (csf_contact_dual_rows).
 */
#define YIELD 1e-14

/*
 * The impact of pair hit, whose relative normal velocity is to become
 * target, on the cluster it forms with the pairs in contact, solved
 * directly: the normal impulses P make the hit's velocity target, and each
 * pair in contact either pushes (P >= 0) and is left with a relative normal
 * velocity of zero, or takes no impulse and does not close (v >= 0): a
 * linear complementarity problem, whose matrix (the coupling of the pairs'
 * normals) is symmetric and positive semidefinite (csf_contact_dual_rows,
 * a row a pair's normal, the hit's held at target). Each
 * pair is measured in its own least velocity that counts
 * (csf_contact_speed_resolution), so that a pair left closing within it is
 * not struck again. Fails (-1, nothing changed) for a cluster of more than
 * DIRECT_MAX pairs, where csf_contact_dual_rows fails, or where its answer leaves
 * a pair closing or a pair of its set off its target beyond that velocity;
 * size is the scale of the velocities (at least those of the cluster's
 * bodies).
 */
static int cluster_impulses(csf_contacts *cs, double *m, const cpair *hit, double target, double size)
{
	impact im = { cs, hit };
	uint32_t nq = csf_contact_clusters(cs, picks_impact, &im), h = (uint32_t)(hit - cs->pairs), q = 0, np = 0, ih = 0;
	const uint32_t *cl = NULL;
	for (; q < nq && !cl; q++)
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++)
			if (cs->cl[a] == h) cl = cs->cl + cs->cstart[q], np = cs->cstart[q + 1] - cs->cstart[q], ih = a - cs->cstart[q];
	if (!cl || np == 0 || np > DIRECT_MAX) return -1;
	double *n = cs->nv, vr[DIRECT_MAX][3], x[DIRECT_MAX];
	csf_srow R[DIRECT_MAX]; /* a row each pair: its normal, the hit's held at target */
	unsigned char in[DIRECT_MAX];
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double curv;
		csf_contact_geometry(c, m, n + 3 * a, &curv);
		rel(c, m, I(c, V), J(c, V), vr[a]);
		R[a] = (csf_srow){ { n[3 * a], n[3 * a + 1], n[3 * a + 2] }, a, a == ih, a == ih ? target : 0 };
		/* the velocities' own size: a pair that closes within its rounding does not close */
		size = csf_max(size, csf_contact_speeds(c, m));
	}
	double vres[DIRECT_MAX]; /* the least relative velocity that counts, each pair's */
	for (uint32_t a = 0; a < np; a++) vres[a] = csf_contact_speed_resolution(&cs->pairs[cl[a]], m, 1e-14 * size);
	for (uint32_t a = 0; a < np; a++) /* the pairs' coupling, once each normal is known */
		for (uint32_t b = 0; b < np; b++) cs->G[a * np + b] = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
	if (csf_contact_dual_rows(cs, np, R, np, vr, vres, x, in)) return -1;
	for (uint32_t a = 0; a < np; a++) {
		cpair *c = &cs->pairs[cl[a]];
		double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), P = x[a];
		for (int k = 0; k < 3; k++) {
			m[I(c, V) + k] += P * n[3 * a + k] * wi;
			if (!c->plane) m[J(c, V) + k] -= P * n[3 * a + k] * wj;
		}
	}
	return 0;
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
int csf_contact_collide(csf_contacts *cs, double *m, cpair *hit, double target, double vn)
{
	double size = fabs(target) + fabs(vn);
	if (!cluster_impulses(cs, m, hit, target, size)) return 0;
	for (int sweep = 0; sweep < 1000; sweep++) {
		double change = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			if (!joins(cs, c, hit)) continue;
			double n[3], curv, vr[3], dv[3];
			csf_contact_geometry(c, m, n, &curv);
			rel(c, m, I(c, V), J(c, V), vr);
			double v = dot3(vr, n), d = c == hit ? target - v : csf_max(0, -v);
			size = csf_max(size, fabs(v)); /* converged: to the rounding of the fastest pair's velocity */
			if (d == 0) continue;
			for (int k = 0; k < 3; k++) dv[k] = d * n[k];
			csf_contact_add_impulse(c, m, dv);
			change = csf_max(change, fabs(d));
		}
		if (change <= 1e-15 * size) return 0;
	}
	uint32_t np = 0; /* the pairs of the impact, as cluster_impulses took them, into cs->cl */
	for (uint32_t i = 0; i < cs->n; i++)
		if (joins(cs, &cs->pairs[i], hit)) cs->cl[np++] = i;
	csf_contact_unsolvable(cs, cs->cl, np, m);
	cs->why_pair = (uint32_t)(hit - cs->pairs);
	return 1;
}

/* Before an impact: each pair in contact's relative velocity into W_VR, for after_impact. */
void csf_contact_before_impact(csf_contacts *cs, const double *m)
{
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		if (in_contact(c)) rel(c, m, I(c, V), J(c, V), WV(c, VR));
	}
}

/* The impulses P[a] (on body i of cluster pair cl[a], -P[a] on j) applied to the velocities. */
static void apply_impulses(const csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, double (*P)[3])
{
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m);
		for (int k = 0; k < 3; k++) {
			m[I(c, V) + k] += P[a][k] * wi;
			if (!c->plane) m[J(c, V) + k] -= P[a][k] * wj;
		}
	}
}

/* The coupling of rows r and k: the change of r's velocity per unit impulse along k. */
static double row_g(const csf_contacts *cs, uint32_t np, const csf_srow *R, uint32_t r, uint32_t k)
{
	double w = cs->G[R[r].a * np + R[k].a];
	return w == 0 ? 0 : w * dot3(R[r].e, R[k].e);
}

/* Row r's velocity after the impulses x (per row), each row yielding by yield (YIELD), less its
   target; into *round the rounding of that sum (8 DBL_EPSILON its terms' sizes). */
static double row_after(const csf_contacts *cs, uint32_t np, const csf_srow *R, uint32_t nr, double (*vr)[3],
                        const double *x, uint32_t r, double yield, double *round)
{
	double v = dot3(R[r].e, vr[R[r].a]) - R[r].target + yield * row_g(cs, np, R, r, r) * x[r], size = fabs(v);
	for (uint32_t k = 0; k < nr; k++)
		if (x[k] != 0) {
			double t = row_g(cs, np, R, r, k) * x[k];
			v += t, size += fabs(t);
		}
	*round = 8 * DBL_EPSILON * size;
	return v;
}

/* G of the rows in the set A[0..na) (+ yield on its diagonal) into cs->K, factored; 0, or -1. */
static int factor_rows(csf_contacts *cs, uint32_t np, const csf_srow *R, const uint32_t *A, uint32_t na, double yield)
{
	double *L = cs->K;
	for (uint32_t i = 0; i < na; i++)
		for (uint32_t k = 0; k <= i; k++) L[i * na + k] = row_g(cs, np, R, A[i], A[k]) * (k == i ? 1 + yield : 1);
	return ldl(L, na);
}

/* Whether the impulses x hold every row: those of the set in[] at their targets, the others not
   closing, within each pair's vres and the rounding. */
static int rows_hold(const csf_contacts *cs, uint32_t np, const csf_srow *R, uint32_t nr, double (*vr)[3],
                     const double *x, const unsigned char *in, const double *vres, double yield)
{
	for (uint32_t r = 0; r < nr; r++) {
		double round, v = row_after(cs, np, R, nr, vr, x, r, yield, &round), tol = vres[R[r].a] + round;
		if (!(in[r] ? fabs(v) <= tol : v >= -tol)) return 0;
	}
	return 1;
}

/*
 * The impulses of a cluster's rows (an impact's normals, a stop's normals
 * and tangents) by the dual active-set method of Goldfarb and Idnani ("A
 * numerically stable dual method for solving strictly convex quadratic
 * programs", 1983): the velocities after the impulses are those nearest
 * to the velocities before them, in the metric of the masses, among those
 * that hold the rows eq at their targets and leave no other row closing: a
 * strictly convex problem, whose answer is unique even where the impulses
 * are not. From no impulses, the rows eq join first (their impulses of
 * either sign), then the row that closes fastest (in its pair's least
 * velocity that counts, vres); each join raises its impulse until its
 * velocity is its target, the set's changing as that takes (-G_AA^-1 G_Ap
 * of it); where one of theirs (not eq) would fall below zero first, that
 * row leaves the set (at zero) and the join goes on. The distance grows at
 * every join, and no set comes back: the sets cannot go round, as the
 * primal active sets did on a jam whose contacts were redundant to 1e-7
 * rad, and on a pile's slip at t = 0.7511 s. Each row yields by YIELD.
 * Then the set is solved again without the yield, where its system is not
 * singular to rounding and its impulses push (but the rows eq), and taken
 * where it holds; otherwise the yield's answer, where it holds. Impulses
 * per row into x, the set into in[]. 0, or -1: no pushing impulses leave
 * none closing, or rounding defeats it (4 nr + 8 changes).
 */
int csf_contact_dual_rows(csf_contacts *cs, uint32_t np, const csf_srow *R, uint32_t nr, double (*vr)[3],
                          const double *vres, double *x, unsigned char *in)
{
	double *r = cs->x, *b = cs->rhs, keep[DIRECT_MAX];
	uint32_t *A = cs->at, na = 0;
	long p = -1;
	for (uint32_t k = 0; k < nr; k++) x[k] = 0, in[k] = 0;
	for (uint32_t iter = 0;; iter++) {
		if (iter == 4 * nr + 8) return -1;
		if (p < 0) { /* the first row eq not in the set, then the row that closes fastest */
			double worst = -1, round;
			for (uint32_t k = 0; k < nr && p < 0; k++)
				if (R[k].eq && !in[k]) p = k;
			for (uint32_t k = 0; k < nr && !(p >= 0 && R[p].eq); k++) {
				if (in[k] || R[k].eq) continue;
				double v = row_after(cs, np, R, nr, vr, x, k, YIELD, &round), res = vres[R[k].a];
				if (v < -res && v / res < worst) worst = v / res, p = k;
			}
			if (p < 0) break;
		}
		if (factor_rows(cs, np, R, A, na, YIELD)) return -1;
		for (uint32_t i = 0; i < na; i++) r[i] = row_g(cs, np, R, A[i], (uint32_t)p);
		ldl_solve(cs->K, na, r, r);
		double sigma = row_g(cs, np, R, (uint32_t)p, (uint32_t)p) * (1 + YIELD), round;
		for (uint32_t i = 0; i < na; i++) sigma -= row_g(cs, np, R, (uint32_t)p, A[i]) * r[i];
		double s = row_after(cs, np, R, nr, vr, x, (uint32_t)p, YIELD, &round);
		double full = sigma > 0 ? -s / sigma : INFINITY, sign = full < 0 ? -1 : 1, part = INFINITY;
		uint32_t out = 0;
		for (uint32_t i = 0; i < na; i++)
			if (!R[A[i]].eq && sign * r[i] > 0 && x[A[i]] / (sign * r[i]) < part) part = x[A[i]] / (sign * r[i]), out = i;
		if (isinf(full) && isinf(part)) return -1;
		double t = fabs(full) <= part ? full : sign * part;
		for (uint32_t i = 0; i < na; i++) x[A[i]] -= t * r[i];
		x[p] += t;
		if (fabs(full) <= part) {
			A[na++] = (uint32_t)p, in[p] = 1, p = -1;
		} else {
			x[A[out]] = 0, in[A[out]] = 0;
			A[out] = A[--na];
		}
	}
	memcpy(keep, x, nr * sizeof *keep); /* the set solved again without the yield */
	if (!factor_rows(cs, np, R, A, na, 0)) {
		for (uint32_t i = 0; i < na; i++) b[i] = R[A[i]].target - dot3(R[A[i]].e, vr[R[A[i]].a]);
		ldl_solve(cs->K, na, b, b);
		int push = 1;
		for (uint32_t i = 0; i < na; i++) push &= R[A[i]].eq || b[i] >= 0;
		if (push) {
			for (uint32_t k = 0; k < nr; k++) x[k] = 0;
			for (uint32_t i = 0; i < na; i++) x[A[i]] = b[i];
			if (rows_hold(cs, np, R, nr, vr, x, in, vres, 0)) return 0;
			memcpy(x, keep, nr * sizeof *x);
		}
	}
	return rows_hold(cs, np, R, nr, vr, x, in, vres, YIELD) ? 0 : -1;
}

/*
 * csf_contact_stick_cluster's impulses where its active sets fail, by
 * csf_contact_dual_rows: the rows are each pair's normal, and for the hit and each
 * pair held (wh) its two tangents. The hit's normal is held at zero too
 * (it does not part: it is the pair that stops). In a scene in a plane
 * (every normal and relative velocity without a part along one axis) the
 * tangent across it is left out: nothing moves along it, and its rows would
 * leave the system singular. A pair left sliding, with friction, whose
 * slip the impulses turn back, or change by more than its size (beyond
 * vres), is held too: friction stops a slip before it turns it. A slip
 * that the impulses on its bodies speed up by less than its size slides
 * on, as csf_contact_stick_cluster's sets let it: held for that, a slide
 * of 0.16 m/s was stopped to stop a neighbour's slip of 2.6e-10 m/s, and
 * the stops went on from pair to pair through a pile of 64 balls, taking
 * 0.094 J (the pairs it parted left in contact, their forces could not be
 * solved an instant later). A pair held whose normal the impulses part
 * (beyond vres) is let go: parted, it has no friction. Then the rows are solved again, at most 2 np times
 * (a pair let go is never held again). Every change takes a constraint
 * away from the velocities or adds one, each a projection in the metric of
 * the masses: no set gains energy. Fails (-1, nothing changed) where
 * csf_contact_dual_rows does, or where the changes do not end.
 */
int csf_contact_slide_turned(const double n[3], const double v0[3], const double v1[3], double vres)
{
	double t0[3], t1[3];
	csf_contact_tangential(v0, n, t0);
	csf_contact_tangential(v1, n, t1);
	double m0 = mag3(t0), d[3] = { t1[0] - t0[0], t1[1] - t0[1], t1[2] - t0[2] };
	return !(dot3(t1, t0) >= -vres * m0 && mag3(d) <= m0 + vres);
}

static int stick_dual(csf_contacts *cs, double *m, const uint32_t *cl, uint32_t np, uint32_t ih, const double *n,
                      double (*vr)[3], const unsigned char *whole, const double *vres)
{
	csf_srow R[DIRECT_MAX];
	double x[DIRECT_MAX], P[DIRECT_MAX][3];
	unsigned char in[DIRECT_MAX], wh[DIRECT_MAX], gone[DIRECT_MAX];
	uint32_t rn[DIRECT_MAX]; /* each pair's normal row */
	int flat = -1;           /* the axis nothing has a part along, if any */
	for (int k = 0; k < 3 && flat < 0; k++) {
		int off = 0;
		for (uint32_t a = 0; a < np && !off; a++) off = n[3 * a + k] != 0 || vr[a][k] != 0;
		if (!off) flat = k;
	}
	memcpy(wh, whole, np);
	memset(gone, 0, np);
	for (uint32_t round = 0; round < 2 * np; round++) {
		uint32_t nr = 0;
		for (uint32_t a = 0; a < np; a++) {
			const double *na = n + 3 * a;
			if (nr + (wh[a] ? 3 : 1) > DIRECT_MAX) return -1;
			rn[a] = nr;
			R[nr++] = (csf_srow){ { na[0], na[1], na[2] }, a, a == ih, 0 };
			if (!wh[a]) continue;
			double e[3] = { 0, 0, 0 }, t1[3], t2[3];
			int k0 = flat;
			if (k0 < 0) /* the axis the normal is least along */
				k0 = fabs(na[0]) <= fabs(na[1]) && fabs(na[0]) <= fabs(na[2]) ? 0 : fabs(na[1]) <= fabs(na[2]) ? 1 : 2;
			e[k0] = 1;
			t1[0] = na[1] * e[2] - na[2] * e[1], t1[1] = na[2] * e[0] - na[0] * e[2];
			t1[2] = na[0] * e[1] - na[1] * e[0];
			double s = mag3(t1);
			for (int k = 0; k < 3; k++) t1[k] /= s;
			t2[0] = na[1] * t1[2] - na[2] * t1[1], t2[1] = na[2] * t1[0] - na[0] * t1[2];
			t2[2] = na[0] * t1[1] - na[1] * t1[0];
			R[nr++] = (csf_srow){ { t1[0], t1[1], t1[2] }, a, 1, 0 };
			if (flat < 0) R[nr++] = (csf_srow){ { t2[0], t2[1], t2[2] }, a, 1, 0 };
		}
		if (csf_contact_dual_rows(cs, np, R, nr, vr, vres, x, in)) return -1;
		for (uint32_t a = 0; a < np; a++) P[a][0] = P[a][1] = P[a][2] = 0;
		for (uint32_t r = 0; r < nr; r++)
			for (int k = 0; k < 3; k++) P[R[r].a][k] += R[r].e[k] * x[r];
		int changed = 0;
		for (uint32_t a = 0; a < np; a++) { /* each pair's relative velocity after the impulses */
			const cpair *c = &cs->pairs[cl[a]];
			const double *na = n + 3 * a;
			if (wh[a]) { /* a pair held stays in contact */
				double rnd;
				if (a != ih && !in[rn[a]] && !(row_after(cs, np, R, nr, vr, x, rn[a], 0, &rnd) <= vres[a] + rnd))
					wh[a] = 0, gone[a] = 1, changed = 1;
				continue;
			}
			if (!has_friction(c, m) || gone[a]) continue;
			double va[3];
			memcpy(va, vr[a], sizeof va);
			for (uint32_t b = 0; b < np; b++)
				for (int k = 0; k < 3; k++) va[k] += cs->G[a * np + b] * P[b][k];
			if (csf_contact_slide_turned(na, vr[a], va, vres[a])) wh[a] = 1, changed = 1;
		}
		if (changed) continue;
		apply_impulses(cs, m, cl, np, P);
		return 0;
	}
	return -1;
}

/*
 * The cluster of pair hit's impact (the pairs in contact, or with cs->group
 * the pairs marked), of 2 to DIRECT_MAX pairs, into *cl (np pairs, hit the
 * ih-th), with each pair's normal (cs->nv), relative velocity vr, slip's
 * size (slip) and least velocity that counts (vres, at least least); 0,
 * or -1 (no such cluster). Their coupling is couple's.
 */
static int stop_cluster(csf_contacts *cs, double *m, const cpair *hit, double least, const uint32_t **cl,
                        uint32_t *np, uint32_t *ih, double (*vr)[3], double *slip, double *vres)
{
	impact im = { cs, hit };
	uint32_t nq = csf_contact_clusters(cs, picks_impact, &im), h = (uint32_t)(hit - cs->pairs);
	*cl = NULL;
	for (uint32_t q = 0; q < nq && !*cl; q++)
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++)
			if (cs->cl[a] == h) *cl = cs->cl + cs->cstart[q], *np = cs->cstart[q + 1] - cs->cstart[q], *ih = a - cs->cstart[q];
	if (!*cl || *np < 2 || *np > DIRECT_MAX) return -1;
	double *n = cs->nv, size = 0;
	for (uint32_t a = 0; a < *np; a++) {
		const cpair *c = &cs->pairs[(*cl)[a]];
		double curv;
		csf_contact_geometry(c, m, n + 3 * a, &curv);
		rel(c, m, I(c, V), J(c, V), vr[a]);
		size = csf_max(size, csf_contact_speeds(c, m));
	}
	for (uint32_t a = 0; a < *np; a++) {
		const cpair *c = &cs->pairs[(*cl)[a]];
		double vt[3];
		vres[a] = csf_contact_speed_resolution(c, m, csf_max(least, 1e-14 * size));
		csf_contact_slip_velocity(c, m, n + 3 * a, vt);
		slip[a] = mag3(vt);
	}
	return 0;
}

/* The coupling of the pairs cl[0..np) with their masses into cs->G, and, with unit, with every mass 1
   into cs->G1 (only the primal active sets read it). */
static void couple(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, int unit)
{
	for (uint32_t a = 0; a < np; a++)
		for (uint32_t b = 0; b < np; b++) {
			cs->G[a * np + b] = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
			if (unit) cs->G1[a * np + b] = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], NULL);
		}
}

/*
 * Pair hit stops slipping (it sticks) together with the pairs in contact
 * in its cluster: the impulses that leave hit and every sticking pair at a
 * relative velocity of zero (normal and tangential), and so every pair
 * that slides without slipping (its slip within the rounding of speeds: it
 * has stopped, and friction holds it as a sticking pair's does; left free,
 * the impulses of a pile of 64 balls that stopped one slip set its
 * neighbour slipping at 2.6e-8 m/s, whose stop set the first going again,
 * an event every 6e-9 s), and every other pair
 * in contact either pushing (its normal impulse >= 0) at a relative normal
 * velocity of zero, or taking no impulse and not closing: a linear
 * complementarity problem, solved by active sets as an impact's
 * (cluster_impulses; a sticking pair's unknown is its whole impulse, and
 * only the pairs other than hit may leave), each pair measured in its own
 * least speed that counts (csf_contact_speed_resolution, at least least).
 * Where the pairs are statically indeterminate (a ball on a peg leaning on
 * a divider) the impulses with the least friction (csf_contact_solve). A
 * slip stopped by its own pair's impulse alone drives its neighbours into
 * each other; their impact starts the slip again, a little slower, and
 * the slip stops again at the next event: a ball in a Galton board's bin,
 * leaning on one that rests on a peg, stopped and slipped 3400 times in
 * 3e-7 s, at 1e-10 m/s. A set whose impulses do not make the velocities
 * what they are to be (to 1e-9 of the cluster's speeds) or that turn back
 * the slip of a pair left sliding, or change it by more than its size
 * (csf_contact_slide_turned: friction stops a slip before it turns it), is
 * one that only impulses without bound would hold: contacts all but
 * redundant (two balls stuck together resting on two others stuck
 * together, along normals 8e-7 apart, one pair sliding on the other: the
 * impulses along the two normals that stop it grow without bound as the
 * normals align). Then one pair of the set held by its normal alone
 * parts, on trial, the first in the order of pairs whose parting leaves a
 * set that is solved (a pile of 64 balls whose slip failed so to stop,
 * stopped by its pair's own impulse instead, crawled at t = 0.7229 s, an
 * event every 5e-10 s). Where no trial gives a set, or the sets do not
 * settle in 5 np + 8 changes (they go round: pairs leave with impulses of
 * -2.7e4 times their least speed and come back, in a pile of 64 balls at
 * t = 0.7511 s), stick_dual's sets, which cannot. Returns 0, or -1 with
 * nothing changed: a pair alone, more than DIRECT_MAX unknowns, or
 * stick_dual fails.
 */
int csf_contact_stick_cluster(csf_contacts *cs, double *m, cpair *hit, double least)
{
	const uint32_t *cl;
	uint32_t np, ih;
	double vr[DIRECT_MAX][3], slip[DIRECT_MAX], vres[DIRECT_MAX];
	if (stop_cluster(cs, m, hit, least, &cl, &np, &ih, vr, slip, vres)) return -1;
	couple(cs, m, cl, np, 1);
	double *n = cs->nv, size = 0, va[DIRECT_MAX][3], P[DIRECT_MAX][3], E[DIRECT_MAX][3];
	unsigned char whole[DIRECT_MAX], dc[DIRECT_MAX];
	uint32_t dim = 0, pa[DIRECT_MAX];
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		size = csf_max(size, csf_contact_speeds(c, m));
		cs->act[a] = 1;
		whole[a] = a == ih || (has_friction(c, m) && (W(c, MODE) == STICKING || (W(c, MODE) == SLIDING && !(slip[a] > vres[a]))));
		dim += whole[a] ? 3 : 1;
	}
	if (dim > DIRECT_MAX) return -1;
	double wratio = csf_contact_mass_ratio(cs, cl, np, m);
	uint32_t trial = UINT32_MAX, next = 0; /* the pair let part on trial, and the next to try (above) */
	for (uint32_t iter = 0; iter < 5 * np + 8; iter++) {
		uint32_t sub = 0; /* the rows of the active pairs: a whole pair's three axes, another's normal */
		for (uint32_t a = 0; a < np; a++) {
			dc[a] = cs->act[a] ? (whole[a] ? 3 : 1) : 0;
			for (int r = 0; r < dc[a]; r++, sub++) {
				for (int k = 0; k < 3; k++) E[sub][k] = dc[a] == 3 ? (k == r) : n[3 * a + k];
				pa[sub] = a;
				cs->rhs[sub] = -dot3(E[sub], vr[a]);
			}
		}
		for (uint32_t r = 0; r < sub; r++)
			for (uint32_t k = 0; k < sub; k++) {
				double w = cs->G[pa[r] * np + pa[k]], w1 = cs->G1[pa[r] * np + pa[k]], d = dot3(E[r], E[k]);
				cs->K[r * sub + k] = w == 0 ? 0 : w * d;
				cs->K1[r * sub + k] = w1 == 0 ? 0 : w1 * d;
			}
		csf_contact_frames(np, dc, n, sub, cs->T, cs->fric);
		int unmet = csf_contact_solve(cs, sub, cs->K1, wratio, cs->T, cs->fric) &&
		            (!(wratio < 1e6) || csf_contact_least_squares(cs, sub, cs->T, cs->fric));
		for (uint32_t a = 0; a < np; a++) P[a][0] = P[a][1] = P[a][2] = 0;
		for (uint32_t r = 0; r < sub && !unmet; r++)
			for (int k = 0; k < 3; k++) P[pa[r]][k] += E[r][k] * cs->x[r];
		long out = -1, in = -1;
		double worst = 0; /* in units of each pair's vres */
		for (uint32_t a = 0; a < np; a++) { /* each pair's relative velocity after the impulses, va[a] */
			const cpair *c = &cs->pairs[cl[a]];
			double *v = va[a];
			memcpy(v, vr[a], sizeof va[a]);
			for (uint32_t b = 0; b < np; b++)
				for (int k = 0; k < 3; k++) v[k] += cs->G[a * np + b] * P[b][k];
			if (cs->act[a]) {
				for (uint32_t r = 0; r < sub; r++) /* a row the impulses do not satisfy */
					if (pa[r] == a && !(fabs(dot3(E[r], v)) <= 1e-9 * size)) unmet = 1;
				double pull = dot3(P[a], n + 3 * a) * (inv_mass_i(c, m) + inv_mass_j(c, m));
				if (a != ih && pull < -vres[a] && pull / vres[a] < worst) worst = pull / vres[a], out = a;
			} else {
				double vn = dot3(v, n + 3 * a);
				if (vn < -vres[a] && vn / vres[a] < worst && out < 0) worst = vn / vres[a], in = a;
			}
		}
		/* a pair left sliding (its normal row only) keeps its slip or less, never turned back:
		   friction can stop a slide, not reverse it. Impulses that do are the rounding of a
		   system all but singular over a tiny pivot (in a pile of 1024 balls, a slip of 2.3e-11
		   m/s stopped so turned a neighbour's slide of 1.3e-3 m/s back) */
		for (uint32_t a = 0; a < np && !unmet && out < 0 && in < 0; a++) {
			if (!cs->act[a] || whole[a]) continue;
			unmet = slip[a] > vres[a] && csf_contact_slide_turned(n + 3 * a, vr[a], va[a], vres[a]);
		}
		if (unmet) { /* no impulses hold the pairs as they are: one held by its normal alone parts, on trial */
			if (trial != UINT32_MAX) cs->act[trial] = 1;
			while (next < np && (!cs->act[next] || whole[next])) next++;
			if (next == np) break;
			cs->act[trial = next++] = 0;
			continue;
		}
		trial = UINT32_MAX; /* the impulses of a set, solved: a pair parted on trial stays so (or closes again) */
		if (out >= 0) cs->act[out] = 0;
		else if (in >= 0) cs->act[in] = 1;
		else {
			apply_impulses(cs, m, cl, np, P);
			return 0;
		}
	}
	return stick_dual(cs, m, cl, np, ih, n, vr, whole, vres);
}

/*
 * After a plastic impact or a group's collapse (csf_contact_settle;
 * cs->group set, the group's pairs marked, every pair that touches): its
 * impulses, normal only, leave pairs with friction
 * slipping within the rounding of speeds, slips that after_impact would
 * take away pair by pair, each by its own impulse, which sets a neighbour
 * closing beyond its least velocity: in a column of nine balls wedged in
 * a narrow box, two pairs were struck in turn at -3.9e-12 and -2.0e-12
 * m/s (their least velocities 3.5e-12 and 1.5e-12), each group's collapse
 * leaving the other closing, 55 000 collisions at one instant. Those
 * slips are stopped together, with every pair of the group in contact
 * that sticks (its slip zero) held too (a pair touching, not in contact,
 * has no friction): stick_dual's rows with no pair hit (the
 * velocities nearest to those the collapse left, in the metric of the
 * masses, that hold those pairs' tangents at zero and close no normal).
 * 0 (stopped, or no such slip), or -1 with nothing changed.
 */
int csf_contact_hold_group(csf_contacts *cs, double *m, const cpair *hit)
{
	const uint32_t *cl;
	uint32_t np, ih;
	double vr[DIRECT_MAX][3], slip[DIRECT_MAX], vres[DIRECT_MAX];
	if (stop_cluster(cs, m, hit, cs->vfloor, &cl, &np, &ih, vr, slip, vres)) return -1;
	unsigned char whole[DIRECT_MAX];
	int any = 0;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]]; /* (a pair touching, not in contact, has no friction) */
		whole[a] = in_contact(c) && has_friction(c, m) && slip[a] <= vres[a];
		any |= whole[a] && slip[a] > 0;
	}
	if (!any) return 0;
	couple(cs, m, cl, np, 0);
	return stick_dual(cs, m, cl, np, UINT32_MAX, cs->nv, vr, whole, vres);
}
