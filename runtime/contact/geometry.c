/*
 * geometry.c - a pair's geometry: its normal, gap and the gap's
 * centripetal term (two spheres, a sphere and an anchor, or a sphere and a
 * plane), a plane's edge, the pair's length scale and the
 * smallest gap its positions resolve, and the relative tangential velocity;
 * and the check that every mass point's mass is positive (csf_contacts_bad_mass).
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
 * (a mass point) are at pi and pj, the rest in m; an anchor's position is
 * in m (pj unused), and its velocity and acceleration are zero, so that
 * curv is that of i going round a fixed centre. Two points (radius 0)
 * never touch: their gap is infinite; two spheres at one place have no
 * normal (n = 0), their gap is minus the sum of their radii.
 */
double csf_contact_geometry_at(const cpair *c, const double *m, const double *pi, const double *pj, double n[3],
                               double *curv)
{
	*curv = 0;
	if (c->anchor) pj = m + J(c, POS);
	else if (c->plane) {
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

double csf_contact_geometry(const cpair *c, const double *m, double n[3], double *curv)
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
	if (!c->plane || c->anchor) return HUGE_VAL;
	const double *e = m + J(c, V), *q = m + J(c, POS);
	double len = mag3(e);
	if (!(len > 0)) return HUGE_VAL;
	double d[3] = { pi[0] - q[0], pi[1] - q[1], pi[2] - q[2] };
	return len - dot3(d, e) / len;
}

double csf_contact_inside(const cpair *c, const double *m) { return csf_contact_inside_at(c, m, m + I(c, POS)); }

/* The pair's length scale: the magnitudes its gap is computed from. */
double csf_contact_scale_at(const cpair *c, const double *m, const double *pi, const double *pj)
{
	return mag3(pi) + mag3(pj ? pj : m + J(c, POS)) + m[I(c, R)] + (c->plane && !c->anchor ? 0 : m[J(c, R)]);
}

double csf_contact_scale(const cpair *c, const double *m) { return csf_contact_scale_at(c, m, m + I(c, POS), NULL); }

/*
 * The smallest gap the pair's positions resolve: a few units in the last
 * place of the magnitudes the gap is computed from. A gap within it of zero
 * is zero, and a hop no higher than it cannot be followed.
 */
double csf_contact_resolution(const cpair *c, const double *m)
{
	return 2 * DBL_EPSILON * csf_contact_scale(c, m);
}

/* Tangential part of x: x - (x . n) n. */
void csf_contact_tangential(const double x[3], const double n[3], double out[3])
{
	double xn = dot3(x, n);
	for (int k = 0; k < 3; k++) out[k] = x[k] - xn * n[k];
}

/* The relative tangential velocity of the pair (normal n). */
void csf_contact_slip_velocity(const cpair *c, const double *m, const double n[3], double vt[3])
{
	double vr[3];
	rel(c, m, I(c, V), J(c, V), vr);
	csf_contact_tangential(vr, n, vt);
}
