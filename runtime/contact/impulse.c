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
 * until neither happens; each measured in its own least velocity that
 * counts (csf_contact_speed_resolution), so that a pair left closing within
 * it is not struck again, nor does one whose impulse's effect is that small
 * leave. Fails (-1, nothing changed) for a cluster of more than DIRECT_MAX
 * pairs, a singular system whose least-squares impulses leave a pair of the
 * set beyond that velocity, or one that does not settle in 4 np + 8
 * changes of the set; size is the scale of the velocities (at least those
 * of the cluster's bodies).
 */
static int cluster_impulses(csf_contacts *cs, double *m, const cpair *hit, double target, double size)
{
	impact im = { cs, hit };
	uint32_t nq = csf_contact_clusters(cs, picks_impact, &im), h = (uint32_t)(hit - cs->pairs), q = 0, np = 0, ih = 0;
	const uint32_t *cl = NULL;
	for (; q < nq && !cl; q++)
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++)
			if (cs->cl[a] == h) cl = cs->cl + cs->cstart[q], np = cs->cstart[q + 1] - cs->cstart[q], ih = a - cs->cstart[q];
	if (!cl || np > DIRECT_MAX) return -1;
	double *G = cs->G, *n = cs->nv;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double curv, vr[3];
		csf_contact_geometry(c, m, n + 3 * a, &curv);
		rel(c, m, I(c, V), J(c, V), vr);
		cs->v0[a] = dot3(vr, n + 3 * a);
		/* the velocities' own size: a pair that closes within its rounding does not close */
		size = csf_max(size, csf_contact_speeds(c, m));
		cs->act[a] = a == ih;
		cs->lam[a] = 0;
	}
	double vres[DIRECT_MAX]; /* the least relative velocity that counts, each pair's */
	for (uint32_t a = 0; a < np; a++) vres[a] = csf_contact_speed_resolution(&cs->pairs[cl[a]], m, 1e-14 * size);
	for (uint32_t a = 0; a < np; a++) /* G = the normals' coupling, once each normal is known */
		for (uint32_t b = 0; b < np; b++) {
			double w = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
			double w1 = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], NULL);
			G[a * np + b] = w == 0 ? 0 : w * dot3(n + 3 * a, n + 3 * b);
			cs->G1[a * np + b] = w1 == 0 ? 0 : w1 * dot3(n + 3 * a, n + 3 * b);
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
			for (uint32_t k = 0; k < dim; k++) {
				cs->K[r * dim + k] = G[cs->at[r] * np + cs->at[k]];
				cs->K1[r * dim + k] = cs->G1[cs->at[r] * np + cs->at[k]];
			}
		double wratio = csf_contact_mass_ratio(cs, cl, np, m);
		if (csf_contact_solve(cs, dim, cs->K1, wratio, NULL, NULL)) {
			/* contacts all but redundant (a row jammed between two walls, one of its contacts
			   tilted by the 1e-10 m a ball has risen), whose velocities agree only to their
			   rounding: the least-squares impulses, if they leave every pair of the set within
			   the least velocity that counts of what it is to be */
			if (!(wratio < 1e6) || csf_contact_least_squares(cs, dim, NULL, NULL)) return -1;
			for (uint32_t r = 0; r < dim; r++) {
				double e = (cs->at[r] == ih ? target : 0) - cs->v0[cs->at[r]];
				for (uint32_t k = 0; k < dim; k++) e -= G[cs->at[r] * np + cs->at[k]] * cs->x[k];
				if (!(fabs(e) <= vres[cs->at[r]])) return -1;
			}
		}
		for (uint32_t a = 0; a < np; a++) cs->lam[a] = 0;
		for (uint32_t r = 0; r < dim; r++) cs->lam[cs->at[r]] = cs->x[r];
		long out = -1, in = -1;
		double worst = 0; /* in units of each pair's vres */
		for (uint32_t a = 0; a < np; a++) { /* a contact that would pull: its impulse's effect */
			double pull = cs->lam[a] * G[a * np + a];
			if (cs->act[a] && a != ih && pull < -vres[a] && pull / vres[a] < worst) worst = pull / vres[a], out = a;
		}
		if (out < 0) {
			for (uint32_t a = 0; a < np; a++) { /* a contact that would close */
				if (cs->act[a]) continue;
				double v = cs->v0[a];
				for (uint32_t b = 0; b < np; b++) v += G[a * np + b] * cs->lam[b];
				if (v < -vres[a] && v / vres[a] < worst) worst = v / vres[a], in = a;
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

/*
 * Pair hit stops slipping (it sticks) together with the pairs in contact
 * in its cluster: the impulses that leave hit and every sticking pair at a
 * relative velocity of zero (normal and tangential), and every other pair
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
 * 3e-7 s, at 1e-10 m/s. Returns 0, or -1 with nothing changed: a pair
 * alone, more than DIRECT_MAX unknowns, a system whose impulses do not
 * make the velocities what they are to be (to 1e-9 of the cluster's
 * speeds: contacts so nearly redundant that only impulses without bound
 * would), impulses that turn back or speed up the slip of a pair left
 * sliding (which friction cannot), or sets that do not settle in 4 np + 8
 * changes.
 */
int csf_contact_stick_cluster(csf_contacts *cs, double *m, cpair *hit, double least)
{
	impact im = { cs, hit };
	uint32_t nq = csf_contact_clusters(cs, picks_impact, &im), h = (uint32_t)(hit - cs->pairs), np = 0, ih = 0;
	const uint32_t *cl = NULL;
	for (uint32_t q = 0; q < nq && !cl; q++)
		for (uint32_t a = cs->cstart[q]; a < cs->cstart[q + 1]; a++)
			if (cs->cl[a] == h) cl = cs->cl + cs->cstart[q], np = cs->cstart[q + 1] - cs->cstart[q], ih = a - cs->cstart[q];
	if (!cl || np < 2 || np > DIRECT_MAX) return -1;
	double *n = cs->nv, size = 0, vr[DIRECT_MAX][3], va[DIRECT_MAX][3], vres[DIRECT_MAX], P[DIRECT_MAX][3],
	       E[DIRECT_MAX][3];
	unsigned char whole[DIRECT_MAX], dc[DIRECT_MAX];
	uint32_t dim = 0, pa[DIRECT_MAX];
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		double curv;
		csf_contact_geometry(c, m, n + 3 * a, &curv);
		rel(c, m, I(c, V), J(c, V), vr[a]);
		whole[a] = a == ih || (W(c, MODE) == STICKING && has_friction(c, m));
		dim += whole[a] ? 3 : 1;
		size = csf_max(size, csf_contact_speeds(c, m));
		cs->act[a] = 1;
	}
	if (dim > DIRECT_MAX) return -1;
	for (uint32_t a = 0; a < np; a++) vres[a] = csf_contact_speed_resolution(&cs->pairs[cl[a]], m, csf_max(least, 1e-14 * size));
	for (uint32_t a = 0; a < np; a++) /* the pairs' coupling, with their masses and with every mass 1 */
		for (uint32_t b = 0; b < np; b++) {
			cs->G[a * np + b] = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], m);
			cs->G1[a * np + b] = csf_contact_coupling(cs, &cs->pairs[cl[a]], &cs->pairs[cl[b]], NULL);
		}
	double wratio = csf_contact_mass_ratio(cs, cl, np, m);
	for (uint32_t iter = 0; iter < 4 * np + 8; iter++) {
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
		if (csf_contact_solve(cs, sub, cs->K1, wratio, cs->T, cs->fric) &&
		    (!(wratio < 1e6) || csf_contact_least_squares(cs, sub, cs->T, cs->fric)))
			return -1;
		for (uint32_t a = 0; a < np; a++) P[a][0] = P[a][1] = P[a][2] = 0;
		for (uint32_t r = 0; r < sub; r++)
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
					if (pa[r] == a && !(fabs(dot3(E[r], v)) <= 1e-9 * size)) return -1;
				double pull = dot3(P[a], n + 3 * a) * (inv_mass_i(c, m) + inv_mass_j(c, m));
				if (a != ih && pull < -vres[a] && pull / vres[a] < worst) worst = pull / vres[a], out = a;
			} else {
				double vn = dot3(v, n + 3 * a);
				if (vn < -vres[a] && vn / vres[a] < worst && out < 0) worst = vn / vres[a], in = a;
			}
		}
		if (out >= 0) cs->act[out] = 0;
		else if (in >= 0) cs->act[in] = 1;
		else {
			/* a pair left sliding (its normal row only) keeps its slip or less, never turned back:
			   friction can stop a slide, not reverse it. Impulses that do are the rounding of a
			   system all but singular over a tiny pivot (in a pile of 1024 balls, a slip of 2.3e-11
			   m/s stopped so turned a neighbour's slide of 1.3e-3 m/s back) */
			for (uint32_t a = 0; a < np; a++) {
				if (!cs->act[a] || whole[a]) continue;
				double t0[3], t1[3], *na = n + 3 * a, s0 = dot3(vr[a], na), s1 = dot3(va[a], na);
				for (int k = 0; k < 3; k++) t0[k] = vr[a][k] - s0 * na[k], t1[k] = va[a][k] - s1 * na[k];
				double m0 = mag3(t0), d[3] = { t1[0] - t0[0], t1[1] - t0[1], t1[2] - t0[2] };
				if (m0 > vres[a] && !(dot3(t1, t0) >= -vres[a] * m0 && mag3(d) <= m0 + vres[a])) return -1;
			}
			for (uint32_t a = 0; a < np; a++) {
				cpair *c = &cs->pairs[cl[a]];
				double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m);
				for (int k = 0; k < 3; k++) {
					m[I(c, V) + k] += P[a][k] * wi;
					if (!c->plane) m[J(c, V) + k] -= P[a][k] * wj;
				}
			}
			return 0;
		}
	}
	return -1;
}
