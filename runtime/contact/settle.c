/*
 * settle.c - the settle state machine (csf_contact_settle): at an instant,
 * the changes of mode a pair goes through (impact, rest, hop, lift-off,
 * sticking, sliding) until the modes stand, and the transitions
 * themselves.
 */
#include "contact_int.h"

/*
 * Moves the bodies along n so that the gap is zero (they move by the event's
 * location error): then, if rounding left it negative, body i outward by the
 * least amount that makes it non-negative, so that the gap's guard is armed.
 */
/* Moves the pair's bodies along n, each by its share of the inverse masses, so that gap closes. */
static void move_closed(cpair *c, double *m, const double n[3], double gap)
{
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), w = wi + wj;
	for (int k = 0; k < 3; k++) {
		m[I(c, POS) + k] -= gap * n[k] * (wi / w);
		if (!c->plane) m[J(c, POS) + k] += gap * n[k] * (wj / w);
	}
}

static void close_gap(cpair *c, double *m, const double n[3], double gap)
{
	double nn[3], curv;
	move_closed(c, m, n, gap);
	double push = DBL_EPSILON * csf_contact_scale(c, m) / 8;
	for (int i = 0; i < 64 && (gap = csf_contact_geometry(c, m, nn, &curv)) < 0; i++, push *= 2)
		for (int k = 0; k < 3; k++) m[I(c, POS) + k] += csf_max(push, -gap) * n[k];
}

/*
 * The smallest relative speed that counts at an instant being settled:
 * csf_contact_speed_resolution, at least 1e-13 of the fastest pair's speeds
 * at the instant (cs->vfloor). A pair that closes more slowly than that is
 * not struck: an impulse that small does not change the velocities it is
 * added to, or is the rounding of the impulses of an impact elsewhere (an
 * impact at 1 m/s leaves the pairs at rest around it closing at 1e-17 m/s,
 * and the impulses among touching bodies are solved to 1e-14 of their
 * speeds, csf_contact_collide), which would be passed from pair to pair
 * without end; and a slip that small leaves a pair that comes to rest
 * sticking.
 */
static double speed_resolution(const csf_contacts *cs, const cpair *c, const double *m)
{
	return csf_contact_speed_resolution(c, m, cs->vfloor);
}

/* Are the pair's bodies at rest: their speeds within vres, their accelerations within ares? */
static int bodies_at_rest(const cpair *c, const double *m, double vres, double ares)
{
	return mag3(m + I(c, V)) <= vres && mag3(m + I(c, A)) <= ares &&
	       (c->plane || (mag3(m + J(c, V)) <= vres && mag3(m + J(c, A)) <= ares));
}

/* The pair's relative tangential acceleration (into at; n its normal), and its size. */
static double tangential_accel_of(const cpair *c, const double *m, const double n[3], double at[3])
{
	double ar[3];
	rel(c, m, I(c, A), J(c, A), ar);
	csf_contact_tangential(ar, n, at);
	return mag3(at);
}

/* The pair's slip velocity (into vt, with its normal and curvature at n, curv), and its size. */
static double slip_of(const cpair *c, const double *m, double n[3], double *curv, double vt[3])
{
	csf_contact_geometry(c, m, n, curv);
	csf_contact_slip_velocity(c, m, n, vt);
	return mag3(vt);
}

/*
 * Enters contact: the relative normal velocity is zero; sticks if the
 * tangential one is too, or slips no faster than the speeds' rounding
 * (speed_resolution: the impulses that brought it to rest leave such a
 * slip, whose direction is noise), which an impulse as small takes away.
 */
static void enter_contact(const csf_contacts *cs, cpair *c, double *m, const double n[3])
{
	double vt[3];
	csf_contact_slip_velocity(c, m, n, vt);
	double s = mag3(vt);
	if (s > 0 && has_friction(c, m) && s <= speed_resolution(cs, c, m)) {
		for (int k = 0; k < 3; k++) vt[k] = -vt[k];
		csf_contact_add_impulse(c, m, vt);
		s = 0;
	}
	W(c, MODE) = s == 0 && has_friction(c, m) ? STICKING : SLIDING;
	W(c, LIFT) = 0;
	for (int k = 0; k < 3; k++) WV(c, DS)[k] = s > 0 ? vt[k] / s : 0;
}

/* Is the pair touching: the gap closed, up to the event's location error? */
static int touching(const cpair *c, const double *m, double gap)
{
	return gap <= 1e-12 * csf_contact_scale(c, m) && csf_contact_inside(c, m) >= 0;
}

/* Apart, exactly touching. */
static void separate(cpair *c, double *m)
{
	double n[3], curv, gap = csf_contact_geometry(c, m, n, &curv);
	W(c, MODE) = APART;
	close_gap(c, m, n, gap);
}

/*
 * Lift-off where the normal force fades to zero (it would pull): the
 * relative normal velocity and acceleration are zero there too, so the gap
 * opens as the cube of the time, and for a while stays within the
 * integrator's error of positions, tol times their size, which takes it
 * below zero and back again and again (some 2000 events as a ball slid off
 * another, each a restart). Until the gap is beyond ten times that error
 * (hold_contacts), its guard takes that as margin (W_LIFT, at least the
 * touching gap): the pair is struck when it closes beyond it, and placed
 * touching (close_gap). Not after an impulse: a pair pressed together that
 * an impact parted would gain speed falling back through the margin, and
 * rattle on.
 */
static double lift_margin(const csf_contacts *cs, const cpair *c, const double *m)
{
	return csf_max(1e-12, 10 * cs->tol) * csf_contact_scale(c, m);
}

static void lift_off(const csf_contacts *cs, cpair *c, double *m)
{
	separate(c, m);
	W(c, LO) = 1;
	W(c, LIFT) = lift_margin(cs, c, m);
}

/*
 * Sliding has stopped: the relative tangential velocity becomes exactly
 * zero, and the pair sticks. The impulse that stops it is its cluster's
 * (csf_contact_stick_cluster: its neighbours stay in contact, and those
 * that stick go on sticking); then, or where that cannot be had, the
 * pair's own impulse takes away what slip is left.
 */
static void stick(csf_contacts *cs, cpair *c, double *m)
{
	double n[3], curv, vt[3];
	csf_contact_stick_cluster(cs, m, c, cs->vfloor);
	csf_contact_geometry(c, m, n, &curv);
	csf_contact_slip_velocity(c, m, n, vt);
	for (int k = 0; k < 3; k++) vt[k] = -vt[k];
	csf_contact_add_impulse(c, m, vt);
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
 * Among bodies that touch others, what presses a pair back need not be its
 * own normal acceleration: two balls side by side in a pile, parted by the
 * rounding of an impact's impulses or a last, tiny collision, are pressed
 * back by their neighbours, whose collisions follow ever faster (a group's
 * inelastic collapse). So with e < 1 a parting no faster than the speed the
 * forces on its bodies give in the Zeno time (zeno (1 - e) a/2, a the
 * size of their accelerations: csf_contact_accel_resolution) is rest too:
 * the gap it would open by the next row is below what positions resolve
 * (at 1 m/s^2 and rows every 0.01 s, 5e-9 m/s for 5e-11 m).
 */
static int at_rest(const cpair *c, const double *m, double vn, double an, double zeno)
{
	double e = restitution(c, m), n[3], curv;
	if (an < 0 && 2 * vn / -an <= zeno * (e < 1 ? 1 - e : 1)) return 1;
	if (!(e < 1)) return 0;
	csf_contact_geometry(c, m, n, &curv);
	return 2 * vn <= zeno * (1 - e) * 1e12 * csf_contact_accel_resolution(c, m, curv);
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
	return csf_max(1024 * csf_contact_resolution(c, m), 100 * tol * csf_contact_scale(c, m));
}

static int hops(const cpair *c, const double *m, double vn, double an, double tol)
{
	return an < 0 && vn * vn / (-2 * an) <= too_low(c, m, tol);
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
		csf_contact_geometry(c, m, n, &curv);
		double vn = dot3(vr, n), an = -W(c, LAM) * (inv_mass_i(c, m) + inv_mass_j(c, m));
		if (vn < -speed_resolution(cs, c, m)) continue; /* closing: struck in turn (csf_contact_settle) */
		if (vn > 0 && !at_rest(c, m, vn, an, zeno)) separate(c, m);
		else enter_contact(cs, c, m, n);
	}
}

void csf_contacts_before_kick(csf_contacts *cs, const double *m) { csf_contact_before_impact(cs, m); }

void csf_contacts_after_kick(csf_contacts *cs, double *m, double zeno) { after_impact(cs, m, zeno); }

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
		if (share_body(c, d) && (in_contact(d) || touching(d, m, csf_contact_geometry(d, m, n, &curv)))) return 1;
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
	double n[3], curv;
	csf_contact_geometry(c, m, n, &curv);
	/* at rest, neither pressed nor pulled apart beyond the rounding: in contact, with no force */
	/* at rest: pressed together beyond the rounding, or apart (touching, with no force) */
	if (v == 0) return an < -csf_contact_accel_resolution(c, m, curv) ? RESTS : FLIES;
	if (at_rest(c, m, v, an, zeno)) return RESTS;
	if (!hops(c, m, v, an, tol)) return FLIES;
	return crowded(cs, m, c) ? RESTS : HOPS;
}

/* Room in cs->mark for a mark per candidate, and in cs->dir for a direction. 0, or -1: no memory. */
static int grow_marks(csf_contacts *cs)
{
	if (cs->n <= cs->capmark) return 0;
	unsigned char *mk = realloc(cs->mark, cs->n);
	if (!mk) return -1;
	cs->mark = mk;
	double *dir = realloc(cs->dir, 3 * (size_t)cs->n * sizeof *dir);
	if (!dir) return -1;
	cs->dir = dir, cs->capmark = cs->n;
	return 0;
}

/* Marks in cs->mark the pairs in contact and those touching (not hopping). 0, or -1: no memory. */
static int mark_touching(csf_contacts *cs, const double *m)
{
	if (grow_marks(cs)) return -1;
	for (uint32_t i = 0; i < cs->n; i++) {
		const cpair *c = &cs->pairs[i];
		double n[3], curv;
		cs->mark[i] = (unsigned char)(in_contact(c) ||
		                              (W(c, MODE) != HOPPING && touching(c, m, csf_contact_geometry(c, m, n, &curv))));
	}
	return 0;
}

/* A slip that friction stops within the Zeno time: a sticking pair's, within what its static friction
   so stops (as hold_velocity holds it); a sliding pair's, ahead and slowing (its relative tangential
   acceleration against its way), within what its sliding friction so stops. */
int csf_contact_slip_stops(const cpair *c, const double *m, double zeno)
{
	double n[3], curv, vt[3], at[3];
	if (!has_friction(c, m) || !in_contact(c)) return 0;
	csf_contact_geometry(c, m, n, &curv);
	csf_contact_slip_velocity(c, m, n, vt);
	if (W(c, MODE) == STICKING) return mag3(vt) <= stopped_within(c, m, mu_s(c, m), zeno);
	tangential_accel_of(c, m, n, at);
	return dot3(vt, WV(c, DS)) > 0 && dot3(at, WV(c, DS)) < 0 && mag3(vt) <= stopped_within(c, m, mu_k(c, m), zeno);
}

/*
 * Pair c takes the mode csf_contact_choose chose for it (to, TO_*; a
 * slide along dir). Entering contact, it is placed exactly in contact and
 * its relative normal velocity (within the rounding of zero) is taken
 * away; to stick, its slip (as small) too. Returns 1 if its mode changed.
 */
static int take_mode(csf_contacts *cs, cpair *c, double *m, int to, const double dir[3])
{
	int was = in_contact(c);
	if (to == TO_APART) {
		if (was) lift_off(cs, c, m);
		return was;
	}
	if (!has_friction(c, m)) to = TO_CONTACT;
	if (!was) {
		double n[3], curv, vr[3];
		double gap = csf_contact_geometry(c, m, n, &curv);
		close_gap(c, m, n, gap);
		rel(c, m, I(c, V), J(c, V), vr);
		double vn = dot3(vr, n);
		for (int k = 0; k < 3; k++) vr[k] = -vn * n[k];
		csf_contact_add_impulse(c, m, vr);
		if (to == TO_CONTACT) enter_contact(cs, c, m, n);
	} else if (to == TO_CONTACT || (to == TO_STICK && W(c, MODE) == STICKING) ||
	           (to == TO_SLIDE && W(c, MODE) == SLIDING && memcmp(WV(c, DS), dir, 3 * sizeof *dir) == 0))
		return 0;
	if (to == TO_STICK) stick(cs, c, m);
	if (to == TO_SLIDE) { /* a slip within the rounding, whose way is noise, is taken away, and a slide
		                         that its friction stops within the Zeno time (csf_contact_slip_stops, as
		                         csf_contact_choose_modes counts it) stops, as one that stops at once: it
		                         begins along dir */
		double n[3], curv, vt[3], s = slip_of(c, m, n, &curv, vt);
		if (s <= speed_resolution(cs, c, m)) {
			for (int k = 0; k < 3; k++) vt[k] = -vt[k];
			csf_contact_add_impulse(c, m, vt);
		} else if (csf_contact_slip_stops(c, m, cs->zeno))
			stick(cs, c, m); /* by its cluster's impulses (its pair's own drove a ball 3e-9 m into a wall) */
		W(c, MODE) = SLIDING;
		memcpy(WV(c, DS), dir, 3 * sizeof *dir);
	}
	return 1;
}

/*
 * The modes chosen afresh (csf_contact_choose; fresh: m holds the
 * accelerations of the modes as they are) among the pairs in contact and
 * those that touch at rest (a relative normal velocity within the
 * rounding of zero), and taken. Returns 1 if a mode changed, 0 if none
 * did, -1 when memory runs out.
 */
static int choose(csf_contacts *cs, double *m, int fresh)
{
	if (grow_marks(cs)) return -1;
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		double n[3], curv, vr[3];
		cs->mark[i] = (unsigned char)in_contact(c);
		if (cs->mark[i] || W(c, MODE) == HOPPING || !touching(c, m, csf_contact_geometry(c, m, n, &curv))) continue;
		rel(c, m, I(c, V), J(c, V), vr);
		cs->mark[i] = fabs(dot3(vr, n)) <= speed_resolution(cs, c, m);
	}
	csf_contact_choose(cs, m, fresh);
	int changed = 0;
	for (uint32_t i = 0; i < cs->n; i++)
		if (cs->mark[i]) changed |= take_mode(cs, &cs->pairs[i], m, cs->mark[i] & ~MODES_CHOSEN, cs->dir + 3 * (size_t)i);
	return changed;
}

/*
 * A pair in contact whose normal force pulls again at an instant at which
 * it has lifted off already: lifted off, it closed and was pressed back
 * (settle's passes would go round, lift-off and contact, until their
 * bound, and the step would start with the pull, whose guard, negative
 * from the start, no event reports). Its cluster's forces push only
 * where slides stop: sliding friction wedges it (a ball rising between a
 * wall and a neighbour, each contact's friction pressing it down into the
 * wedge harder than any squeeze can hold it up: the least-norm forces
 * took a squeeze of -32.7 N, whose friction, -mu_k N along the slip,
 * drove the slip and gained energy). That is Painlevé's inconsistent case,
 * whose motion is an impulse of friction (a tangential impact): each
 * sliding pair that shares a body with it stops and sticks, at most twice
 * an instant, as a slide that stops. Returns 1 if one did.
 */
static int lock_slides(csf_contacts *cs, const cpair *c, double *m)
{
	int any = 0;
	for (uint32_t j = 0; j < cs->n; j++) {
		cpair *d = &cs->pairs[j];
		if (W(d, MODE) == SLIDING && share_body(c, d) && W(d, SS) < 2) stick(cs, d, m), W(d, SS)++, any = 1;
	}
	return any;
}

/*
 * A sliding pair that does not slip ahead (beyond the speeds' rounding, as
 * csf_contact_choose_modes sees it) whose relative tangential acceleration
 * points against the way it slides, beyond its rounding: its friction
 * would turn it back at once (it sticks, or slides the other way).
 */
static int turns_back(const csf_contacts *cs, const cpair *c, const double *m)
{
	double n[3], curv, vt[3], at[3];
	if (W(c, MODE) != SLIDING || !has_friction(c, m)) return 0;
	csf_contact_geometry(c, m, n, &curv);
	csf_contact_slip_velocity(c, m, n, vt);
	if (dot3(vt, WV(c, DS)) > speed_resolution(cs, c, m)) return 0;
	tangential_accel_of(c, m, n, at);
	return dot3(at, WV(c, DS)) < -csf_contact_accel_resolution(c, m, curv);
}

/*
 * A sliding pair whose slip its own friction would stop within the Zeno
 * time (the slip over the deceleration mu_k |N| (1/m_i + 1/m_j)): a slip of
 * a few 1e-12 m/s, the integrator's error of velocities at rest, left a
 * pair sliding in a direction that is noise, whose friction turned it this
 * way and that in steps of 1e-11 s (a ball wedged on a peg in a Galton
 * board). It sticks, as a slide that stops does (its slip taken away); at
 * most twice at an instant (W_SS), since static friction that cannot hold
 * sends it sliding again at once, from no slip. So does a sliding pair
 * whose slip the instant's impulses took away (W_SL), left at rest.
 */
static int stops_at_once(const csf_contacts *cs, const cpair *c, const double *m, double zeno)
{
	double n[3], curv, vt[3];
	if (W(c, MODE) != SLIDING || !has_friction(c, m) || W(c, SS) >= 2) return 0;
	double s = slip_of(c, m, n, &curv, vt), at[3];
	if (s > speed_resolution(cs, c, m)) return s <= stopped_within(c, m, mu_k(c, m), zeno);
	/* a slip that the instant's impulses took away, leaving no tangential acceleration beyond
	   its rounding: at rest (an impact left a slip of 5e-20 m/s, and a ball in a V-groove slid
	   on with mu_k N for good); a slide that would turn back is left to turns_back (sticking
	   it, a pile of 16 balls at 0.9 crawled in steps of 7e-12 s), and one that slid without
	   slipping before the instant to the modes as they were chosen (sticking those as well
	   put two balls of a packing 1.1e-9 m into each other, and a column of nine balls thrown
	   at 0.8 m/s collided 50 290 times at one instant) */
	return W(c, SL) && tangential_accel_of(c, m, n, at) <= csf_contact_accel_resolution(c, m, curv);
}

/*
 * A pair in contact with friction that the instant's impulses set slipping
 * (sticking), or whose slip they turned back (sliding, not ahead of the way
 * it slides, W_DS), beyond the slip its friction stops within the Zeno time
 * (stopped_within, at mu_s sticking, mu_k sliding): an impact is
 * frictionless, and what it leaves is a slide, along its slip. Left
 * sticking, its forces kept that slip for good, and a sliding pair turned
 * back was stopped at once by impulses, as a slide that stops (a slip of
 * 0.15 m/s, in a pile of 64 balls); a cluster of pairs so left had contact
 * forces that contradict each other an instant later. A smaller slip
 * sticks at once (stops_at_once, hold_velocity). Returns 1 if it changed.
 */
static int slips_anew(const csf_contacts *cs, cpair *c, const double *m, double zeno)
{
	double n[3], curv, vt[3];
	if (!in_contact(c) || !has_friction(c, m)) return 0;
	double s = slip_of(c, m, n, &curv, vt), res = speed_resolution(cs, c, m);
	int sticks = W(c, MODE) == STICKING;
	if (!sticks && dot3(vt, WV(c, DS)) > res) return 0; /* sliding ahead */
	if (!(s > res && s > stopped_within(c, m, sticks ? mu_s(c, m) : mu_k(c, m), zeno))) return 0;
	for (int k = 0; k < 3; k++) WV(c, DS)[k] = vt[k] / s;
	W(c, MODE) = SLIDING;
	return 1;
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
/*
 * Impacts at one instant among bodies that touch are struck pair by pair,
 * as through infinitesimal gaps (so a Newton's cradle sends one ball out
 * whether its balls touch or not). A plastic impact (restitution 0, or a
 * pair that comes to rest: at_rest) is the limit of such impacts passed
 * back and forth among the pairs that touch, each stopping its pair's
 * approach (Gauss-Seidel sweeps of their impulses): its limit, the
 * impulses that leave no touching pair closing, is found at once, for the
 * pair struck and every pair that touches in its cluster (the impulses of
 * csf_contact_collide). With restitution below 1 a group of
 * touching bodies (a ball landing on a pile) exchanges ever smaller impacts
 * without end, each pair's speed falling by e at each (inelastic collapse,
 * as the bounces of one ball end): past 64 (n + 1) impacts at one instant,
 * or half the impacts an instant may take (csf_contact_passes), whichever
 * is fewer, an impact whose restitution is below 1 ends the group's at
 * once, the pair struck and every pair in contact with it at rest together
 * (the impulses of the cluster, csf_contact_collide). Elastic impacts are
 * followed to the end (a light ball between heavy ones, csf_contact_passes).
 * (With 64 (n + 1) alone, past some 100 candidate pairs the instant's bound
 * came first: a pile of 256 balls stopped with impacts that did not end
 * after 6711 collisions, its group's collapse never reached.)
 */
uint64_t csf_contact_passes(uint32_t n)
{
	return 100 + 10 * (uint64_t)n + 1000000 / ((uint64_t)n + 1);
}

static uint64_t group_after(uint32_t n)
{
	uint64_t after = 64 * ((uint64_t)n + 1), half = csf_contact_passes(n) / 2;
	return after < half ? after : half;
}

/*
 * Cycles. Where the modes of one pair at a time go round (a pair whose
 * normal force would pull lifts off; apart, it is pressed back at rest),
 * the passes repeat until their bound, at an evaluation each: hundreds to
 * thousands at one instant of a pile. A pass is a function of the state,
 * the pairs' work values and the counts of passes (which only their bounds
 * read): so when both are what they were some passes before, bit for bit,
 * every period that follows is the same, up to the period in which a count
 * would reach a bound. Those periods are skipped, their counts added: the
 * instant ends as it would have, in the same state, without their
 * evaluations. The state is compared at the evaluations' passes, with the
 * one of the pass 1, 2, 4, 8, ... (Brent's cycle finding).
 */
typedef struct cycle {
	uint64_t pass, at, hits, others; /* passes evaluated; the copy's pass and counts */
	int have;
} cycle;

/* Room in cs->snap for the state and the pairs' work values. 0, or -1: no memory. */
static int snap_room(const csf_prog *p, csf_contacts *cs)
{
	size_t need = p->ny + (size_t)cs->n * W_N;
	if (need <= cs->capsnap) return 0;
	double *q = realloc(cs->snap, need * sizeof *q);
	if (!q) return -1;
	cs->snap = q, cs->capsnap = need;
	return 0;
}

/* Copies (put) or compares (!put; 1: the same, bit for bit) the state and the pairs' work values. */
static int snap(const csf_prog *p, csf_contacts *cs, const double *m, int put)
{
	double *q = cs->snap;
	if (put) memcpy(q, m + p->ystart, p->ny * sizeof *q);
	else if (memcmp(q, m + p->ystart, p->ny * sizeof *q)) return 0;
	q += p->ny;
	for (uint32_t i = 0; i < cs->n; i++, q += W_N)
		if (put) memcpy(q, cs->pairs[i].w, sizeof cs->pairs[i].w);
		else if (memcmp(q, cs->pairs[i].w, sizeof cs->pairs[i].w)) return 0;
	return 1;
}

/* The whole periods of d passes a count c may skip, staying below bound b for a period after them. */
static uint64_t periods(uint64_t c, uint64_t d, uint64_t b)
{
	if (!d) return UINT64_MAX;
	return c + 2 * d < b ? (b - c) / d - 2 : 0;
}

/*
 * At a pass about to evaluate, with the counts of impacts and of other
 * passes: a cycle found skips its periods (the counts added). 0, or -1
 * when memory runs out.
 */
static int skip_cycle(const csf_prog *p, csf_contacts *cs, const double *m, cycle *y, uint64_t *hits,
                      uint64_t *others)
{
	y->pass++;
	if (y->have && snap(p, cs, m, 0)) {
		uint64_t dh = *hits - y->hits, dothers = *others - y->others;
		uint64_t hb = group_after(cs->n);
		uint64_t k = periods(*hits, dh, hb), ko = periods(*others, dothers, 100 + 10 * (uint64_t)cs->n);
		if (ko < k) k = ko;
		if (k != UINT64_MAX) *hits += k * dh, *others += k * dothers; /* (a period without counts never ends) */
		y->have = 0;
		y->at = UINT64_MAX; /* found: no more copies at this instant */
		return 0;
	}
	if (y->pass == y->at) {
		if (snap_room(p, cs)) return -1;
		snap(p, cs, m, 1);
		y->have = 1, y->hits = *hits, y->others = *others;
		y->at *= 2;
	}
	return 0;
}

static int settle(const csf_prog *p, csf_contacts *cs, double *m, double zeno, double tol, csf_eval_fn eval,
                  void *ctx)
{
	/* each pass evaluates the forces and guards of the current modes, then acts on what they say */
	/* impacts, up to csf_contact_passes; other changes of mode (rest, lift-off, stick, slip),
	   up to 100 + 10 n passes in all, after which the modes stand as they are (if they are
	   not consistent, the events that follow at this instant say so: csfvm(1)) */
	uint64_t hits = 0, others = 0;
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		/* a pair that static friction cannot hold and that, sliding, would stick again at once
		   (the slip its neighbours' sticking leaves, a rounding's worth, against its way) stops
		   no more than twice at an instant, and slides on: its slip grows the way it slides */
		W(c, SS) = 0;
		W(c, LO) = 0;
		W(c, SL) = 0;
		if (W(c, MODE) == SLIDING && has_friction(c, m)) {
			double n[3], curv, vt[3];
			W(c, SL) = slip_of(c, m, n, &curv, vt) > speed_resolution(cs, c, m);
		}
		cs->vfloor = csf_max(cs->vfloor, 1e-13 * csf_contact_speeds(c, m));
	}
	int fresh = 0; /* the forces and guards of the last evaluation are those of the modes */
	cycle cy = { 0, 1, 0, 0, 0 };
	for (;;) {
		/* between impacts the evaluation is skipped: an impact changes velocities, which the next
		   impact's choice reads; the accelerations it reads (whether a pair rests) from the
		   evaluation before are evaluated afresh before anything else changes a mode */
		if (!fresh) {
			if (skip_cycle(p, cs, m, &cy, &hits, &others)) return -1;
			cs->unsolved = 0; /* of the modes of this pass (the driver stops a run on it) */
			if (eval(ctx)) return -1;
		}
		int evaluated = !fresh;
		fresh = 0;
		/* the most violent impact first; each changes velocities, so look again */
		long hit = -1;
		double worst = 0;
		int changed = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			double n[3], curv, vr[3], ar[3];
			if (in_contact(c)) { /* closing, struck by an impact on a body it holds */
				csf_contact_geometry(c, m, n, &curv);
				rel(c, m, I(c, V), J(c, V), vr);
				double vn = dot3(vr, n), res = speed_resolution(cs, c, m);
				if (vn < -res && vn < worst) worst = vn, hit = (long)i;
				if (hit < 0 && evaluated && stops_at_once(cs, c, m, zeno)) stick(cs, c, m), W(c, SS)++, changed = 1;
				else if (slips_anew(cs, c, m, zeno)) changed = 1;
				continue;
			}
			double gap = csf_contact_geometry(c, m, n, &curv);
			int landing = 0;
			if (W(c, MODE) == HOPPING) { /* nothing until it lands (it may have been knocked away) */
				if (W(c, G0) >= 0) continue;
				W(c, MODE) = APART;
				changed = 1;
				/* its positions are no closer than that; past the plane's edge it falls */
				landing = gap <= too_low(c, m, tol) && csf_contact_inside(c, m) > 0;
			}
			if (!landing && !touching(c, m, gap)) continue;
			rel(c, m, I(c, V), J(c, V), vr);
			rel(c, m, I(c, A), J(c, A), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv;
			if (vn < -speed_resolution(cs, c, m)) {
				if (vn < worst) worst = vn, hit = (long)i;
				continue;
			}
			double v0 = vn; /* within the rounding of zero, perhaps closing: a rest takes it away */
			vn = csf_max(vn, 0);
			if (gap < 0) close_gap(c, m, n, gap), gap = 0; /* apart by rounding: arm its guard */
			if (hit >= 0) continue;
			int how = departure(cs, m, c, vn, an, zeno, tol);
			/* lifted off at this instant (its normal force would pull) and not pressed back beyond the
			   rounding: it parts, if at all, no faster than the rounding of speeds, and stays apart (as
			   at rest, a group's collapse, it would take contact and lift off again, pass after pass) */
			if (how == RESTS && W(c, LO) && !(an < -csf_contact_accel_resolution(c, m, curv))) how = FLIES;
			if (how == RESTS) { /* pressed together, at rest: contact */
				close_gap(c, m, n, gap);
				/* its normal velocity taken away: beyond the rounding of speeds (a hop shorter than
				   Zeno's time, or a separation its neighbours' impulses left) by the impulses of its
				   cluster, which keep the pairs in contact from closing (csf_contact_collide); the
				   pair's own impulse drove a neighbour into a third body (in a pile of 64 balls, a
				   separation of 3e-8 m/s so taken away set a ball closing on its neighbour, whose
				   impact started a slip that stopped 3e-8 s later, again and again) */
				int alone = !(v0 > speed_resolution(cs, c, m));
				if (!alone && csf_contact_collide(cs, m, c, 0, v0)) { /* what its sweeps left */
					rel(c, m, I(c, V), J(c, V), vr);
					v0 = dot3(vr, n), alone = 1;
				}
				if (alone) {
					for (int k = 0; k < 3; k++) vr[k] = -v0 * n[k];
					csf_contact_add_impulse(c, m, vr);
				}
				enter_contact(cs, c, m, n);
				changed = 1;
			} else if (how == HOPS) { /* alone, parting a little (at the start) */
				hop(c, m[p->tslot], vn, an);
				changed = 1;
			} else if (v0 < 0) {
				/* apart, closing within the rounding of speeds, and not pressed: struck when it closes
				   beyond the integrator's error of positions, as after a lift-off (struck at every
				   crossing of the touching gap, two balls of a pile of 16 at rest closing at
				   1.15e-12 m/s were settled every 3e-4 s, each time for nothing) */
				W(c, LIFT) = lift_margin(cs, c, m);
			}
		}
		if (hit < 0 && !evaluated) continue; /* evaluate before the other changes */
		if (hit >= 0) {
			if (++hits > csf_contact_passes(cs->n)) return CSF_SETTLE_ENDLESS;
			cpair *c = &cs->pairs[hit];
			double n[3], curv, vr[3], ar[3];
			double gap = csf_contact_geometry(c, m, n, &curv);
			rel(c, m, I(c, V), J(c, V), vr);
			rel(c, m, I(c, A), J(c, A), ar);
			double vn = dot3(vr, n), an = dot3(ar, n) + curv, sep = -restitution(c, m) * vn;
			int was = in_contact(c);
			if (was) an -= W(c, LAM) * (inv_mass_i(c, m) + inv_mass_j(c, m)); /* without its own force */
			int how = sep == 0 ? RESTS : departure(cs, m, c, sep, an, zeno, tol);
			csf_contact_before_impact(cs, m);
			if (how == RESTS || (hits > group_after(cs->n) && restitution(c, m) < 1)) {
				/* plastic, or a group's collapse: at rest together with every pair that touches */
				how = RESTS;
				if (mark_touching(cs, m)) return -1;
				cs->group = 1;
				int st = csf_contact_collide(cs, m, c, 0, vn);
				if (!st) csf_contact_hold_group(cs, m, c); /* its slips within the rounding, together */
				cs->group = 0;
				if (st) return CSF_SETTLE_IMPULSES;
			} else { /* the pair alone, as through an infinitesimal gap */
				for (int k = 0; k < 3; k++) vr[k] = (sep - vn) * n[k];
				csf_contact_add_impulse(c, m, vr);
			}
			after_impact(cs, m, zeno);
			close_gap(c, m, n, gap);
			if (how == RESTS) enter_contact(cs, c, m, n);
			else if (how == HOPS) hop(c, m[p->tslot], sep, an);
			else if (was) W(c, MODE) = APART;
			if (how != RESTS) W(c, LIFT) = 0; /* struck apart: its gap's guard is the gap */
			for (uint32_t i = 0; i < cs->n; i++) /* flights whose velocities just changed */
				if (share_body(c, &cs->pairs[i]) && W(&cs->pairs[i], MODE) == HOPPING)
					W(&cs->pairs[i], MODE) = APART;
			fresh = !changed; /* no other pair changed its mode in this pass */
			continue;
		}
		/* a normal force that would pull (or forces that do not hold), static friction that
		   cannot hold, a slide that stops or would turn back: the modes chosen afresh, each
		   cluster's all at once (those with friction only on the accelerations of their modes) */
		int pulls = cs->unsolved, slips = 0, chose = 0;
		for (uint32_t i = 0; i < cs->n; i++) {
			cpair *c = &cs->pairs[i];
			W(c, TB) = turns_back(cs, c, m); /* (as the evaluation has it: choose writes its own accelerations) */
			if (!in_contact(c)) continue;
			pulls |= W(c, G0) < 0;
			slips |= W(c, G1) < 0 || W(c, TB);
		}
		if (pulls || (slips && !changed)) {
			int st = choose(cs, m, !changed);
			if (st < 0) return -1;
			if (st > 0) {
				if (++others >= 100 + 10 * (uint64_t)cs->n) return 0;
				continue;
			}
			chose = 1;
		}
		/* a guard of a pair in contact that is negative, or a slide that would turn back (W_TB: a
		   cluster too large for modes.c left a pair sliding within its slip's rounding against its
		   acceleration, and its stop was found again 8.6e-13 s later, 1001 times), of a cluster
		   whose modes were not chosen together: its transition (contact_int.h's header); one a
		   pass, the first in the order of pairs (changing every one at once can go round in a
		   circle, changing the first each time settles, as Murty's least-index rule does for a
		   complementarity problem) */
		for (uint32_t i = 0; i < cs->n && !changed; i++) {
			cpair *c = &cs->pairs[i];
			if (!in_contact(c) || (chose && cs->mark[i] & MODES_CHOSEN)) continue;
			if (W(c, G0) < 0) {
				if (W(c, LO)) changed = lock_slides(cs, c, m);
				if (!changed) lift_off(cs, c, m), changed = 1;
			} else if ((W(c, G1) < 0 || W(c, TB)) && W(c, MODE) == SLIDING && W(c, SS) < 2)
				stick(cs, c, m), W(c, SS)++, changed = 1;
			else if (W(c, G1) < 0 && W(c, MODE) == STICKING) slide(c, m), changed = 1;
		}
		if (!changed || ++others >= 100 + 10 * (uint64_t)cs->n) return 0;
	}
}

/*
 * Sweeps (Gauss-Seidel) of one correction over the pairs, pair by pair,
 * until a sweep corrects none, at most most (the holds: SWEEPS_MAX). one()
 * corrects a pair and returns 1, or returns 0 when it is within its
 * rounding or not one it corrects.
 * Returns 1 if any pair was corrected. In a pile the corrections of pairs
 * that share bodies undo each other in part, and a sweep takes away only
 * some of what is left (a sixth, in a pile of 16): 64 sweeps left a ball
 * on the floor rising at 4e-7 m/s, held there by the floor's force, which
 * did work on it (1e-7 J in a hundredth of a second). They cost no
 * evaluation, and stop as soon as every pair is within its rounding.
 */
enum { SWEEPS_MAX = 4096 };

static int sweep_contacts(csf_contacts *cs, double *m, int (*one)(const csf_contacts *, cpair *, double *), int most)
{
	int any = 0;
	for (int sweep = 0; sweep < most; sweep++) {
		int moved = 0;
		for (uint32_t i = 0; i < cs->n; i++)
			if (one(cs, &cs->pairs[i], m)) moved = any = 1;
		if (!moved) break;
	}
	return any;
}

/*
 * A pair in contact held at a relative normal velocity of zero: the
 * integrator's error, and the impulses of the instant, leave pairs in
 * contact parting or closing within what counts as rest (after_impact);
 * their normal forces would then do work (a ball on a floor that the floor
 * holds up while it rises at 3e-6 m/s gains energy). Beyond the rounding of
 * zero (speed_resolution), the pair takes the impulse along its normal (of
 * either sign) that makes its velocity zero: each such impulse takes away
 * the kinetic energy of the velocity it removes, so this never adds energy.
 * A pair that sticks is held at a relative velocity of zero, its slip too
 * (a slip its static friction would stop within the Zeno time, as a slide
 * that stops at once: stops_at_once): its forces keep its relative
 * acceleration zero, so a slip left to it (these normal impulses move the
 * bodies of its neighbours' sticking pairs) is kept for ever (five balls
 * settled in a box crept apart at 7.6e-10 m/s for good, a ball on top
 * rising between two on the floor, gaining energy).
 */
static int hold_velocity(const csf_contacts *cs, cpair *c, double *m)
{
	double n[3], curv, vr[3], dv[3], vt[3];
	if (!in_contact(c)) return 0;
	csf_contact_geometry(c, m, n, &curv);
	rel(c, m, I(c, V), J(c, V), vr);
	csf_contact_slip_velocity(c, m, n, vt);
	double vn = dot3(vr, n), res = speed_resolution(cs, c, m), s = mag3(vt);
	int sticks = W(c, MODE) == STICKING && has_friction(c, m) && s <= stopped_within(c, m, mu_s(c, m), cs->zeno);
	if (fabs(vn) <= res && !(sticks && s > res)) return 0;
	for (int k = 0; k < 3; k++) dv[k] = -(sticks ? vr[k] : vn * n[k]);
	csf_contact_add_impulse(c, m, dv);
	return 1;
}

/*
 * A pair in contact placed exactly in contact: the integrator's error, and
 * a gap closed between two bodies that moved one of them along that pair's
 * normal into a third (close_gap on a ball resting on a floor and leaning
 * on another), leave pairs in contact apart or overlapping, which their
 * accelerations keep so: a ball that sinks into a floor a little more at
 * every event. A gap beyond the touching one (touching) is closed by moving
 * the bodies along the normal (move_closed, without close_gap's outward
 * push).
 */
static int hold_gap(const csf_contacts *cs, cpair *c, double *m)
{
	double n[3], curv, gap;
	(void)cs;
	if (!in_contact(c) || fabs(gap = csf_contact_geometry(c, m, n, &curv)) <= 1e-12 * csf_contact_scale(c, m)) return 0;
	move_closed(c, m, n, gap);
	return 1;
}

/* An apart pair left overlapping placed touching (arm_apart); 1 if it moved. */
static int arm_one(const csf_contacts *cs, cpair *c, double *m)
{
	double n[3], curv, gap;
	(void)cs;
	if (W(c, MODE) != APART || (gap = csf_contact_geometry(c, m, n, &curv)) >= 0 || csf_contact_inside(c, m) < 0) return 0;
	close_gap(c, m, n, gap);
	return 1;
}

/*
 * Every apart pair armed: one left overlapping by the instant's moves (a
 * gap closed, or a body pushed out of another by close_gap, moves it into
 * a third by a few units in the last place) is placed touching, in sweeps
 * until none moves (at most 64). An apart pair's guard is its gap, and only
 * a guard that is not negative at a step's start is watched for a
 * crossing: a ball left 1e-14 m into another at the end of an instant in a
 * pile sank 1 um into it, and the energy the instant after that took to
 * part them was gained. Returns 1 if a body moved.
 */
static int arm_apart(csf_contacts *cs, double *m) { return sweep_contacts(cs, m, arm_one, 64); }

/*
 * Once the modes stand, a sliding pair at rest sticks: no slip and no
 * relative tangential acceleration beyond their rounding, its bodies at
 * rest (each speed within sqrt 2 times the rounding of speeds, a normal
 * and a tangential part within it; each acceleration within its rounding;
 * within what the pair's friction stops in the Zeno time instead, some
 * 1e-8 m/s, a column of nine balls thrown at 0.65 m/s crawled in steps
 * of 1.1e-8 s, 220 s against 16). Such a slide holds its bodies
 * with mu_k |N| where static friction holds them with the least friction
 * there is (csf(5), Rest): a ball dropped onto three pegs, two balls
 * dropped into a groove, each left a pair sliding at rest, with no slip
 * when their last instant began (so not stops_at_once's); a ball dropped
 * between two in a box went on at 3e-12 m/s, its two pairs sliding at that
 * slip. Done within the instant's passes (stops_at_once), it stuck pairs
 * that a group's collapse then struck again: a column of nine balls thrown
 * at 0.8 m/s collided 50 290 times at one instant. Returns 1 if a pair
 * stuck (the modes are then settled again).
 */
static int stick_at_rest(csf_contacts *cs, double *m)
{
	int any = 0;
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		double n[3], curv, vt[3], at[3];
		if (W(c, MODE) != SLIDING || !has_friction(c, m)) continue;
		double s = slip_of(c, m, n, &curv, vt), res = speed_resolution(cs, c, m);
		double ares = csf_contact_accel_resolution(c, m, curv);
		if (s > res || !bodies_at_rest(c, m, sqrt(2) * res, ares)) continue;
		if (tangential_accel_of(c, m, n, at) > ares) continue;
		stick(cs, c, m);
		any = 1;
	}
	return any;
}

/*
 * The modes stand and the forces of the cluster that cs->why_pair names
 * do not hold its contacts (no set of modes holds: sticking and sliding,
 * or pressing and parting, decide each other). That is Painleve's
 * inconsistent case, whose motion is an impulse of friction, a tangential
 * impact (as lock_slides): every pair of the cluster that slides stops
 * and sticks, by its cluster's impulses. Returns 1 if one did.
 */
static int jam(csf_contacts *cs, double *m)
{
	uint32_t k, np, big;
	csf_contacts_why(cs, &k, &np, &big);
	if (big || np == 0) return 0;
	uint32_t nq = csf_contact_clusters(cs, csf_contact_picks_contact, NULL), q = 0;
	for (; q < nq; q++) {
		uint32_t a = cs->cstart[q];
		while (a < cs->cstart[q + 1] && cs->cl[a] != k) a++;
		if (a < cs->cstart[q + 1]) break;
	}
	if (q == nq) return 0;
	uint32_t lo = cs->cstart[q], hi = cs->cstart[q + 1], list[DIRECT_MAX], n = 0;
	for (uint32_t a = lo; a < hi && n < DIRECT_MAX; a++) /* (sticking changes cs->cl) */
		if (W(&cs->pairs[cs->cl[a]], MODE) == SLIDING) list[n++] = cs->cl[a];
	for (uint32_t a = 0; a < n; a++) stick(cs, &cs->pairs[list[a]], m);
	return n > 0;
}

/*
 * The pairs in contact held, once the modes stand: their velocities, then
 * their gaps, in sweeps; then the apart pairs these moves left overlapping
 * armed (arm_apart), and a lift-off's margin dropped once the gap is clear
 * of it. Returns 1 if a body moved.
 */
static int hold_contacts(csf_contacts *cs, double *m)
{
	int moved = sweep_contacts(cs, m, hold_velocity, SWEEPS_MAX) | sweep_contacts(cs, m, hold_gap, SWEEPS_MAX);
	moved |= arm_apart(cs, m);
	for (uint32_t i = 0; i < cs->n; i++) {
		cpair *c = &cs->pairs[i];
		double n[3], curv;
		if (W(c, MODE) != APART || csf_contact_geometry(c, m, n, &curv) > W(c, LIFT)) W(c, LIFT) = 0;
	}
	return moved;
}

/* The instant's modes (settle), with the speed that counts at the instant (speed_resolution). */
int csf_contact_settle(const csf_prog *p, csf_contacts *cs, double *m, double zeno, double tol, csf_eval_fn eval,
                       void *ctx)
{
	if (!cs) return 0;
	cs->vfloor = 0, cs->vain = 0;
	cs->tol = tol, cs->zeno = zeno;
	/* the modes chosen again (at most 3 times) when holding the pairs in contact moved a body:
	   velocities changed, and a normal force could pull from the start of the next step; or
	   when a slide at rest stuck; and then (at most twice) when a cluster's forces still do not
	   hold and its slides stopped (jam: before the holds, a row of three balls between two walls
	   struck from above jammed at a state the hold would have made consistent, and stopped) */
	int st, jams = 0;
	for (int round = 0;; round++) {
		if ((st = settle(p, cs, m, zeno, tol, eval, ctx))) break;
		if (round < 3 && (hold_contacts(cs, m) | stick_at_rest(cs, m))) continue;
		if (!cs->unsolved || jams == 2 || !jam(cs, m)) break;
		jams++, cs->unsolved = 0; /* after the holds: forces that did not hold before one may after it */
	}
	if (!st) arm_apart(cs, m);
	cs->vfloor = 0;
	return st;
}
