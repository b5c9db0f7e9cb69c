/*
 * contact.c - mechanics/rules 1 to 4: normal force, collision, static and
 * dynamic friction between a mass point and another mass point or a plane.
 *
 * A pair is apart (mode 0), hopping (3), or in contact, sliding (1) or
 * sticking (2). The mode changes only at events, which the driver locates
 * in time:
 *
 *   apart:    guard 0 is the gap; when it closes the bodies collide (an
 *             impulse along the normal with restitution min(cr_i, cr_j); a
 *             plane has infinite mass; the pairs in contact stay in
 *             contact), or come to rest in contact when the train of
 *             bounces that would follow ends within the Zeno time.
 *   hopping:  apart, on a hop too low for the positions to follow; guard 0
 *             is the time left until it lands, known from its flight time.
 *   contact:  the normal force N n is the constraint force that keeps the
 *             relative normal acceleration zero; guard 0 is N, and the
 *             bodies separate when it would pull (N < 0).
 *   sliding:  friction -mu_k |N| v_t/|v_t|; guard 1 is v_t . d, with d the
 *             direction of sliding at its start: sticking begins when the
 *             relative tangential velocity reaches zero.
 *   sticking: friction is the force that keeps the relative tangential
 *             acceleration zero; guard 1 is mu_s |N| - |f|, and sliding
 *             begins when static friction cannot hold.
 *
 * No threshold is a length or a time of its own: the gap's resolution
 * follows from the magnitudes of the positions, the Zeno time from the
 * output interval (csf(5), Rest).
 *
 * Materials combine as mu = max(mu_i, mu_j) (the rougher surface) and
 * restitution e = min(cr_i, cr_j) (the less elastic one), so the defaults
 * (cr 1, mu 0) leave the other body's coefficient as it is. Several
 * simultaneous contacts are solved together by Gauss-Seidel sweeps.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "csf.h"

enum { APART, SLIDING, STICKING, HOPPING }; /* the modes of a pair */

#define F(c, f) ((c)->s[CSF_CF_##f])
#define W(c, k) ((c)->s[CSF_CF_WORK] + CSF_CW_##k)

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double mag3(const double *a) { return csf_vmag3(a[0], a[1], a[2]); }

static double inv_mass_i(const csf_contact *c, const double *m) { return 1.0 / m[F(c, M)]; }
static double inv_mass_j(const csf_contact *c, const double *m) { return c->plane ? 0.0 : 1.0 / m[F(c, M2)]; }

/* Relative value of vector property field fi of i and fj of j (j a plane: 0). */
static void rel(const csf_contact *c, const double *m, uint32_t fi, uint32_t fj, double out[3])
{
	for (int k = 0; k < 3; k++) out[k] = m[fi + k] - (c->plane ? 0.0 : m[fj + k]);
}

/*
 * The pair's unit normal n (from j towards i), its gap (returned) and the
 * centripetal term of the gap's second derivative (spheres moving round
 * each other): gap'' = (a_i - a_j) . n + curv.
 */
static double geometry(const csf_contact *c, const double *m, double n[3], double *curv)
{
	const double *pi = m + F(c, POS);
	*curv = 0;
	if (c->plane) {
		const double *q = m + F(c, POS2), *nn = m + F(c, R2);
		double k = mag3(nn), d[3];
		for (int i = 0; i < 3; i++) n[i] = nn[i] / k, d[i] = pi[i] - q[i];
		return dot3(d, n) - m[F(c, R)];
	}
	const double *pj = m + F(c, POS2);
	double d[3] = { pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2] };
	double R = m[F(c, R)] + m[F(c, R2)], dist = mag3(d);
	if (R > 0 && dist > 0) {
		double vr[3];
		for (int i = 0; i < 3; i++) n[i] = d[i] / dist;
		rel(c, m, F(c, V), F(c, V2), vr);
		double vn = dot3(vr, n);
		*curv = (dot3(vr, vr) - vn * vn) / dist;
		return dist - R;
	}
	/* two points: the line they move on, fixed when the program was compiled */
	memcpy(n, m + W(c, DIR), 3 * sizeof *n);
	return dot3(d, n) - R;
}

/*
 * A plane with an edge (V2 holds the vector from its point to the edge line,
 * perpendicular to it; zero: no edge) ends there: how far inside body i is
 * (negative past the edge). HUGE_VAL without an edge.
 */
static double inside(const csf_contact *c, const double *m)
{
	if (!c->plane) return HUGE_VAL;
	const double *e = m + F(c, V2), *pi = m + F(c, POS), *q = m + F(c, POS2);
	double len = mag3(e);
	if (!(len > 0)) return HUGE_VAL;
	double d[3] = { pi[0] - q[0], pi[1] - q[1], pi[2] - q[2] };
	return len - dot3(d, e) / len;
}

/* The pair's length scale: the magnitudes its gap is computed from. */
static double scale(const csf_contact *c, const double *m)
{
	return mag3(m + F(c, POS)) + mag3(m + F(c, POS2)) + m[F(c, R)] + (c->plane ? 0 : m[F(c, R2)]);
}

/*
 * The smallest gap the pair's positions resolve: a few units in the last
 * place of the magnitudes the gap is computed from. A gap within it of zero
 * is zero, and a hop no higher than it cannot be followed.
 */
static double resolution(const csf_contact *c, const double *m)
{
	return 2 * DBL_EPSILON * scale(c, m);
}

/* Sliding or sticking: pressed together by a normal force. */
static int in_contact(const csf_contact *c, const double *m)
{
	return m[W(c, MODE)] == SLIDING || m[W(c, MODE)] == STICKING;
}

static int has_friction(const csf_contact *c, const double *m)
{
	return m[F(c, MUS)] > 0 || m[F(c, MUK)] > 0 || (m[F(c, MUS2)] > 0 || m[F(c, MUK2)] > 0);
}
static double mu_s(const csf_contact *c, const double *m) { return csf_max(m[F(c, MUS)], m[F(c, MUS2)]); }
static double mu_k(const csf_contact *c, const double *m) { return csf_max(m[F(c, MUK)], m[F(c, MUK2)]); }
static double restitution(const csf_contact *c, const double *m) { return csf_min(m[F(c, CR)], m[F(c, CR2)]); }

/* Adds force f (on i; -f on j) to both accelerations and to force property fi/fj. */
static void add_force(const csf_contact *c, double *m, const double f[3], uint32_t fi, uint32_t fj)
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m);
	for (int k = 0; k < 3; k++) {
		m[F(c, A) + k] += f[k] * wi;
		m[fi + k] += f[k];
		if (!c->plane) {
			m[F(c, A2) + k] -= f[k] * wj;
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
static void slip_velocity(const csf_contact *c, const double *m, const double n[3], double vt[3])
{
	double vr[3];
	rel(c, m, F(c, V), F(c, V2), vr);
	tangential(vr, n, vt);
}

void csf_contact_apply(const csf_prog *p, double *m)
{
	for (uint32_t i = 0; i < p->ncontacts; i++) {
		const csf_contact *c = &p->contacts[i];
		for (int k = 0; k < 3; k++) {
			m[F(c, FN) + k] = m[F(c, FF) + k] = m[W(c, F) + k] = 0;
			if (!c->plane) m[F(c, FN2) + k] = m[F(c, FF2) + k] = 0;
		}
		m[W(c, LAM)] = 0;
	}
	/* Gauss-Seidel sweeps: with one contact the second sweep changes nothing */
	for (int sweep = 0; sweep < 100; sweep++) {
		double change = 0, size = 0;
		for (uint32_t i = 0; i < p->ncontacts; i++) {
			const csf_contact *c = &p->contacts[i];
			if (!in_contact(c, m)) continue;
			double n[3], curv, ar[3], f[3];
			geometry(c, m, n, &curv);
			double w = inv_mass_i(c, m) + inv_mass_j(c, m);
			rel(c, m, F(c, A), F(c, A2), ar);
			double dl = -(dot3(ar, n) + curv) / w, dn[3] = { dl * n[0], dl * n[1], dl * n[2] };
			m[W(c, LAM)] += dl;
			add_force(c, m, dn, F(c, FN), F(c, FN2));
			change = csf_max(change, fabs(dl));
			size = csf_max(size, fabs(m[W(c, LAM)]));
			if (!has_friction(c, m)) continue;
			double *fc = m + W(c, F);
			if (m[W(c, MODE)] == SLIDING) {
				double vt[3];
				slip_velocity(c, m, n, vt);
				/* against the sliding; once it has turned back (past the guard's zero, before the
				   event is located) against its direction at the start, so that the force is smooth
				   up to the crossing and the integrator sees no switching */
				double s = mag3(vt), k = mu_k(c, m) * fabs(m[W(c, LAM)]);
				int ahead = dot3(vt, m + W(c, DS)) > 0;
				for (int j = 0; j < 3; j++) f[j] = -k * (ahead ? vt[j] / s : m[W(c, DS) + j]);
			} else { /* sticking: cancel the relative tangential acceleration */
				double at[3];
				rel(c, m, F(c, A), F(c, A2), ar);
				tangential(ar, n, at);
				for (int j = 0; j < 3; j++) f[j] = fc[j] - at[j] / w;
			}
			double df[3] = { f[0] - fc[0], f[1] - fc[1], f[2] - fc[2] };
			memcpy(fc, f, sizeof f);
			add_force(c, m, df, F(c, FF), F(c, FF2));
			change = csf_max(change, mag3(df));
			size = csf_max(size, mag3(f));
		}
		if (change <= 1e-15 * size) break;
	}
	for (uint32_t i = 0; i < p->ncontacts; i++) {
		const csf_contact *c = &p->contacts[i];
		double n[3], curv;
		double gap = geometry(c, m, n, &curv);
		double *g = m + W(c, G0);
		double in = inside(c, m);
		if (m[W(c, MODE)] == HOPPING) { /* the hop lands */
			g[0] = m[W(c, TL)] - m[p->tslot];
			g[1] = 1;
			continue;
		}
		if (!in_contact(c, m)) { /* the gap closes over the plane (not past its edge) */
			g[0] = csf_max(gap, -in);
			g[1] = 1;
			continue;
		}
		g[0] = csf_min(m[W(c, LAM)], in); /* the normal force would pull, or the body left the edge */
		if (!has_friction(c, m)) {
			g[1] = 1;
		} else if (m[W(c, MODE)] == SLIDING) {
			double vt[3];
			slip_velocity(c, m, n, vt);
			g[1] = dot3(vt, m + W(c, DS));
		} else {
			g[1] = mu_s(c, m) * fabs(m[W(c, LAM)]) - mag3(m + W(c, F));
		}
	}
}

/* Changes the relative velocity of the pair by dv (along any direction), conserving momentum. */
static void add_impulse(const csf_contact *c, double *m, const double dv[3])
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj;
	for (int k = 0; k < 3; k++) {
		double j = dv[k] / w; /* the impulse on i */
		m[F(c, V) + k] += j * wi;
		if (!c->plane) m[F(c, V2) + k] -= j * wj;
	}
}

/*
 * Moves the bodies along n so that the gap is zero (they move by the event's
 * location error): then, if rounding left it negative, body i outward by the
 * least amount that makes it non-negative, so that the gap's guard is armed.
 */
static void close_gap(const csf_contact *c, double *m, const double n[3], double gap)
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj, nn[3], curv;
	for (int k = 0; k < 3; k++) {
		m[F(c, POS) + k] -= gap * n[k] * (wi / w);
		if (!c->plane) m[F(c, POS2) + k] += gap * n[k] * (wj / w);
	}
	double push = DBL_EPSILON * scale(c, m) / 8;
	for (int i = 0; i < 64 && (gap = geometry(c, m, nn, &curv)) < 0; i++, push *= 2)
		for (int k = 0; k < 3; k++) m[F(c, POS) + k] += csf_max(push, -gap) * n[k];
}

/* Enters contact: the relative normal velocity is zero; sticks if the tangential one is too. */
static void enter_contact(const csf_contact *c, double *m, const double n[3])
{
	double vt[3];
	slip_velocity(c, m, n, vt);
	double s = mag3(vt);
	m[W(c, MODE)] = s == 0 && has_friction(c, m) ? STICKING : SLIDING;
	for (int k = 0; k < 3; k++) m[W(c, DS) + k] = s > 0 ? vt[k] / s : 0;
}

/* Is the pair touching: the gap closed, up to the event's location error? */
static int touching(const csf_contact *c, const double *m, double gap)
{
	return gap <= 1e-12 * scale(c, m) && inside(c, m) >= 0;
}

/* Lift-off: apart, exactly touching. */
static void separate(const csf_contact *c, double *m)
{
	double n[3], curv, gap = geometry(c, m, n, &curv);
	m[W(c, MODE)] = APART;
	close_gap(c, m, n, gap);
}

/* Sliding has stopped: the relative tangential velocity becomes exactly zero, and the pair sticks. */
static void stick(const csf_contact *c, double *m)
{
	double n[3], curv, vt[3];
	geometry(c, m, n, &curv);
	slip_velocity(c, m, n, vt);
	for (int k = 0; k < 3; k++) vt[k] = -vt[k];
	add_impulse(c, m, vt);
	m[W(c, MODE)] = STICKING;
}

/* Static friction cannot hold: the pair slides, the way the friction force held it back from. */
static void slide(const csf_contact *c, double *m)
{
	double *f = m + W(c, F), s = mag3(f);
	for (int k = 0; k < 3; k++) m[W(c, DS) + k] = s > 0 ? -f[k] / s : 0;
	m[W(c, MODE)] = SLIDING;
}

/*
 * A touching pair pressed together (relative normal acceleration an < 0)
 * that separates at normal speed vn >= 0 hops for 2 vn/|an|, to the height
 * vn^2/(2|an|); with restitution e < 1 the hops that follow shrink by e and
 * end (Zeno's accumulation of bounces) after 2 vn/(|an| (1 - e)).
 *
 * At rest: that train ends within zeno seconds (a single hop, with e = 1).
 */
static int at_rest(const csf_contact *c, const double *m, double vn, double an, double zeno)
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
static double too_low(const csf_contact *c, const double *m, double tol)
{
	return csf_max(1024 * resolution(c, m), 100 * tol * scale(c, m));
}

static int hops(const csf_contact *c, const double *m, double vn, double an, double tol)
{
	return an < 0 && vn * vn / (-2 * an) <= too_low(c, m, tol);
}

/*
 * The impact of pair hit, whose relative normal velocity vn becomes target,
 * together with the pairs in contact, which stay in contact (their normal
 * velocities do not close): a ball landing on one that rests on the floor
 * rebounds as from the floor. Their impulses are found by Gauss-Seidel
 * sweeps, each pair's correcting its velocity in turn (the contacts' only
 * pushing).
 */
static void collide(const csf_prog *p, double *m, const csf_contact *hit, double target, double vn)
{
	double size = fabs(target) + fabs(vn);
	for (int sweep = 0; sweep < 1000; sweep++) {
		double change = 0;
		for (uint32_t i = 0; i < p->ncontacts; i++) {
			const csf_contact *c = &p->contacts[i];
			if (c != hit && !in_contact(c, m)) continue;
			double n[3], curv, vr[3], dv[3];
			geometry(c, m, n, &curv);
			rel(c, m, F(c, V), F(c, V2), vr);
			double v = dot3(vr, n), d = c == hit ? target - v : csf_max(0, -v);
			if (d == 0) continue;
			for (int k = 0; k < 3; k++) dv[k] = d * n[k];
			add_impulse(c, m, dv);
			change = csf_max(change, fabs(d));
		}
		if (change <= 1e-15 * size) break;
	}
}

/* Do pairs c and d share a body (a plane is no body: it does not move)? */
static int share_body(const csf_contact *c, const csf_contact *d)
{
	uint32_t ci = F(c, POS), cj = c->plane ? 0 : F(c, POS2), di = F(d, POS), dj = d->plane ? 0 : F(d, POS2);
	return c != d && (ci == di || ci == dj || (cj && (cj == di || cj == dj)));
}

/* Is a body of pair c in contact with, or touching, a third one? */
static int crowded(const csf_prog *p, const double *m, const csf_contact *c)
{
	for (uint32_t i = 0; i < p->ncontacts; i++) {
		const csf_contact *d = &p->contacts[i];
		double n[3], curv;
		if (share_body(c, d) && (in_contact(d, m) || touching(d, m, geometry(d, m, n, &curv)))) return 1;
	}
	return 0;
}

int csf_contact_settle(const csf_prog *p, double *m, double zeno, double tol, csf_eval_fn eval, void *ctx)
{
	/* each pass evaluates the forces and guards of the current modes, then acts on what they say */
	for (uint32_t iter = 0; iter < 100 + 10 * p->ncontacts; iter++) {
		if (eval(ctx)) return -1;
		/* the most violent impact first; each changes velocities, so look again */
		long hit = -1;
		double worst = 0;
		int changed = 0;
		for (uint32_t i = 0; i < p->ncontacts; i++) {
			const csf_contact *c = &p->contacts[i];
			if (in_contact(c, m)) continue;
			double n[3], curv, vr[3], ar[3];
			double gap = geometry(c, m, n, &curv);
			int landing = 0;
			if (m[W(c, MODE)] == HOPPING) { /* nothing until it lands (it may have been knocked away) */
				if (m[W(c, G0)] >= 0) continue;
				m[W(c, MODE)] = APART;
				changed = 1;
				landing = gap <= too_low(c, m, tol); /* its positions are no closer than that */
			}
			if (!landing && !touching(c, m, gap)) continue;
			rel(c, m, F(c, V), F(c, V2), vr);
			rel(c, m, F(c, A), F(c, A2), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv;
			if (vn < 0) {
				if (vn < worst) worst = vn, hit = (long)i;
				continue;
			}
			if (gap < 0) close_gap(c, m, n, gap), gap = 0; /* apart by rounding: arm its guard */
			if (hit < 0 && at_rest(c, m, vn, an, zeno)) { /* pressed together, at rest: contact */
				close_gap(c, m, n, gap);
				for (int k = 0; k < 3; k++) vr[k] = -vn * n[k];
				add_impulse(c, m, vr);
				enter_contact(c, m, n);
				changed = 1;
			}
		}
		if (hit >= 0) {
			const csf_contact *c = &p->contacts[hit];
			double n[3], curv, vr[3], ar[3];
			double gap = geometry(c, m, n, &curv);
			rel(c, m, F(c, V), F(c, V2), vr);
			rel(c, m, F(c, A), F(c, A2), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv, sep = -restitution(c, m) * vn;
			/* a hop too low to follow by positions is followed by its flight time only when
			   nothing else touches the bodies; among several (a ball on a ball on the floor)
			   it is a rest: the impulses that follow are passed on within this instant */
			int rest = sep == 0 || at_rest(c, m, sep, an, zeno), low = !rest && hops(c, m, sep, an, tol);
			if (low && crowded(p, m, c)) rest = 1, low = 0;
			collide(p, m, c, rest ? 0 : sep, vn);
			close_gap(c, m, n, gap);
			if (rest) {
				enter_contact(c, m, n);
			} else if (low) {
				m[W(c, MODE)] = HOPPING;
				m[W(c, TL)] = m[p->tslot] + 2 * sep / -an;
			}
			for (uint32_t i = 0; i < p->ncontacts; i++) /* flights whose velocities just changed */
				if (share_body(c, &p->contacts[i]) && m[W(&p->contacts[i], MODE)] == HOPPING)
					m[W(&p->contacts[i], MODE)] = APART;
			continue;
		}
		/* a guard of a pair in contact that is negative: its transition (contact.c's header) */
		for (uint32_t i = 0; i < p->ncontacts; i++) {
			const csf_contact *c = &p->contacts[i];
			if (!in_contact(c, m)) continue;
			if (m[W(c, G0)] < 0) separate(c, m), changed = 1;
			else if (m[W(c, G1)] < 0) (m[W(c, MODE)] == SLIDING ? stick : slide)(c, m), changed = 1;
		}
		if (!changed) return 0;
	}
	return 0;
}
