/*
 * events.c - guards and events: the guards' values, the modes, the candidate
 * contacts, the Hermite interpolant of a step, the Illinois location of a
 * crossing, and the earliest event of a step (step_events).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"
#include "constraint.h"

/*
 * A guard is a continuous function of t and the state that is >= 0 while
 * the current mode holds: for a conditional rule's comparison, its value
 * on the side it was last found on; for a contact, see runtime/contact/. After
 * each step the guards are checked at its end and at three points of the
 * step's cubic Hermite interpolant (so that a guard which dips below zero
 * and back within one step is seen), and, with contacts, at the earliest
 * point where an apart pair's gap, positive at those five instants, dips
 * below zero between two of them (a grazing approach, found from the gap's
 * rate: graze_point). A guard that was >= 0 at the step's
 * start and is negative at one of them is an event: its crossing is
 * bracketed and narrowed by the Illinois method on states computed by one
 * step of the method from the step's start, to 1e-13 s. The earliest
 * crossing ends the step there; the modes are brought up to date (and
 * impacts applied), the integrator restarts, and integration goes on.
 */

/* The guards of the last RHS evaluation of r->m into g. */
static void read_guards(run *r, double *g)
{
	const csf_prog *p = r->p;
	const double *m = r->m;
	for (uint32_t i = 0; i < p->nevents; i++) {
		const csf_event *e = &p->events[i];
		g[i] = m[e->mode] > 0 ? m[e->value] : -m[e->value];
	}
	if (r->ncg) csf_cons_guards(r->cons, m, g + p->nevents);
	if (r->cs) csf_contacts_guards(r->cs, g + r->gcont);
}

/* Guards g at (t, y), and the derivative in r->fs. 0, or 1 if a derivative is not finite. */
int csf_run_guards_at(run *r, double t, const double *y, double *g)
{
	if (csf_run_rhs(t, y, r->fs, r)) return 1;
	read_guards(r, g);
	return 0;
}

/* Sets each comparison's side from its value at the state in r->m (after an RHS evaluation). */
void csf_run_free_modes(run *r, double t, const double *y)
{
	const csf_prog *p = r->p;
	for (uint32_t i = 0; i < p->nevents; i++) r->m[p->events[i].mode] = -1;
	(void)csf_run_rhs(t, y, r->fs, r);
	for (uint32_t i = 0; i < p->nevents; i++) {
		const csf_event *e = &p->events[i];
		double v = r->m[e->value];
		r->m[e->mode] = (e->kind & 1 ? v >= 0 : v > 0) ? 1 : 0;
	}
}

typedef struct settle_ctx { run *r; double t; double *y; } settle_ctx;

/* RHS on the state in r->m (which csf_contact_settle changes), keeping y in step with it. */
static int settle_eval(void *ctx)
{
	settle_ctx *s = ctx;
	const csf_prog *p = s->r->p;
	memcpy(s->y, s->r->m + p->ystart, p->ny * sizeof *s->y);
	return csf_run_rhs(s->t, s->y, s->r->fs, s->r);
}

/* Room for ng guards in each guard vector (keeping their values). 0, or -1 when memory runs out. */
int csf_run_room_for_guards(run *r, size_t ng)
{
	if (ng <= r->capg) return 0;
	size_t cap = r->capg ? r->capg : 16;
	while (cap < ng) cap *= 2;
	double **g[10] = { &r->ga, &r->gb, &r->gs, &r->gh, &r->gt, &r->gl, &r->gp, &r->gx, &r->gk, &r->est };
	for (int i = 0; i < 10; i++) {
		double *q = realloc(*g[i], cap * sizeof *q);
		if (!q) {
			r->nomem = 1;
			return -1;
		}
		*g[i] = q;
	}
	uint32_t *o = realloc(r->order, cap * sizeof *o);
	if (!o) {
		r->nomem = 1;
		return -1;
	}
	r->order = o;
	r->capg = cap;
	return 0;
}

/*
 * Chooses the candidate contacts for the ns states ys (runtime/contact/broad.c): the
 * instants at which their guards will be looked at. The guard vectors
 * g[0..ng) (ga, gb) become those of the new candidates, a new pair's
 * computed from state gy[q]. 0, or -1 when memory runs out.
 */
static int choose_contacts(run *r, const double *const *ys, int ns, double h, double **g[], const double *const *gy,
                           int ng)
{
	long k = csf_contacts_find(r->cs, r->m, ys, ns, h);
	if (k < 0 || csf_run_room_for_guards(r, r->gcont + 2 * (size_t)k)) {
		r->nomem = 1;
		return -1;
	}
	double *gc[2];
	for (int q = 0; q < ng; q++) gc[q] = *g[q] + r->gcont;
	csf_contacts_commit(r->cs, r->m, gc, gy, ng);
	r->ng = r->gcont + 2 * (uint32_t)k;
	r->nchoices++, r->ncand += (unsigned long)k;
	if ((unsigned long)k > r->maxcand) r->maxcand = (unsigned long)k;
	return 0;
}

/*
 * Bodies that overlap at the start are placed touching by the modes' first
 * settling (the bodies moved apart along the normal), so the first row is
 * not the scene as written: a ball placed a quarter of its radius into a
 * slope started at the slope's surface without a word. Says so, naming the
 * deepest pair and its depth in metres.
 */
static void report_overlaps(const run *r, FILE *warn)
{
	const csf_prog *p = r->p;
	uint32_t k, oi, oj;
	double depth;
	uint32_t n = csf_contacts_overlaps(r->cs, r->m, &k, &depth);
	if (!n) return;
	csf_contacts_objects(r->cs, k, &oi, &oj);
	char db[32];
	csf_fmt_double(db, depth * p->ubase[0]);
	fprintf(warn, "warning: at the start, '%s' and '%s' overlap by %s m", csf_str(p, p->objects[oi]),
	        csf_str(p, p->objects[oj]), db);
	if (n > 1) fprintf(warn, " (the deepest of %lu overlapping pairs)", (unsigned long)n);
	fprintf(warn, ": the run starts with them moved apart to touching, along the line of their centres "
	              "(a plane's normal), not where the model places them\n");
}

/* Brings every mode up to date at (t, y): at the start (warn: where the overlaps there are reported), and after
   an event (warn NULL). */
int csf_run_update_modes(run *r, double t, double *y, FILE *warn)
{
	const csf_prog *p = r->p;
	csf_run_free_modes(r, t, y);
	if (r->cs) {
		const double *ys[1] = { y };
		if (choose_contacts(r, ys, 1, 0, NULL, NULL, 0)) return 1;
		settle_ctx s = { r, t, y };
		memcpy(r->m + p->ystart, y, p->ny * sizeof *y);
		if (warn) report_overlaps(r, warn);
		int st = csf_contact_settle(p, r->cs, r->m, r->zeno, r->tol, settle_eval, &s);
		if (st > 0) r->unsettled = st, r->unsettled_t = t;
		if (!st && csf_contacts_unsolved(r->cs)) r->unsettled = CSF_SETTLE_FORCES, r->unsettled_t = t, st = 1;
		if (st) return 1;
		memcpy(y, r->m + p->ystart, p->ny * sizeof *y);
		if (csf_run_cons_impact(r, t, y)) return 1;
		csf_run_free_modes(r, t, y);
	}
	if (csf_run_cons_modes(r, t, y)) return 1;
	return r->fail;
}

int csf_run_whens(run *r, double t, double *y, int *fired_any)
{
	const csf_prog *p = r->p;
	double *m = r->m;
	*fired_any = 0;
	for (; p->nwhens; r->wround++) {
		if (csf_run_rhs(t, y, r->fs, r)) return CSF_ODE_STOPPED;
		memcpy(m + p->ystart, y, p->ny * sizeof *y); /* (a generated RHS may have read y alone) */
		if (r->cs) csf_contacts_before_kick(r->cs, m);
		r->exec(p, &r->x, CSF_SEC_EVT, m, m + p->ystart, m + p->dstart);
		memcpy(y, m + p->ystart, p->ny * sizeof *y);
		unsigned long fired = 0;
		for (uint32_t i = 0; i < p->nwhens; i++) {
			if (m[p->whens[i].fire] == 0) continue;
			fired++;
			if (r->wround >= WHEN_ROUNDS - 2 && r->ncycle < 2 && (!r->ncycle || r->cycle[0] != i))
				r->cycle[r->ncycle++] = i;
		}
		if (!fired) return 0;
		if (r->cs) csf_contacts_after_kick(r->cs, m, r->zeno); /* a body kicked off a floor leaves it */
		r->nfired += fired;
		*fired_any = 1;
		if (r->wround >= WHEN_ROUNDS - 1) return ADV_WHEN_CYCLE;
	}
	return 0;
}

/* How closely events are located in time: 1e-13 s, finer for scenes on tiny time scales. */
double csf_run_location_tol(const csf_prog *p) { return csf_min(1e-13, 1e-10 * p->by); }

/*
 * The cubic Hermite interpolant of the step from (ta, r->ya), derivative
 * r->fa, to (ta + dt, yb), derivative r->fb, at ta + s dt, into out.
 */
static void hermite(const run *r, double dt, const double *yb, double s, double *out)
{
	double s2 = s * s, s3 = s2 * s;
	double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
	for (size_t i = 0; i < r->p->ny; i++)
		out[i] = h00 * r->ya[i] + h10 * dt * r->fa[i] + h01 * yb[i] + h11 * dt * r->fb[i];
}

/*
 * The state at ta + s (tb - ta) within the step just taken from (ta, r->ya)
 * to (tb, yb): the method's continuous extension, or the cubic Hermite
 * interpolant of the values and derivatives (r->fa, r->fb) at its ends.
 * 0, or 1 if an evaluation failed.
 */
int csf_run_interp(run *r, csf_ode *ode, double ta, double tb, const double *yb, double s, double *out)
{
	if (r->dense) return csf_ode_dense_eval(ode, ta + s * (tb - ta), out);
	hermite(r, tb - ta, yb, s, out);
	return 0;
}

/*
 * The guards at time tc on the state stepped exactly from the step's start
 * (ta, r->ya) of the step that ended at (tb, yb), into r->gs, the state left
 * in r->ys. Within 1e-6 of the step from its start, the state is the step's
 * interpolant (exact there to far below rounding), not a substep: a method's
 * step that short can be off by many units in the last place (bsimp's
 * extrapolation), enough to put a gap that has just opened below zero.
 * CSF_ODE_OK, STOPPED if a derivative was not finite, FAILED (with msg) if
 * the step failed.
 */
static int substep_guards(run *r, csf_ode *ode, double ta, double tb, const double *yb, double tc, char *msg,
                          size_t msglen)
{
	if (tc - ta < 1e-6 * (tb - ta)) {
		if (csf_run_interp(r, ode, ta, tb, yb, (tc - ta) / (tb - ta), r->ys)) return CSF_ODE_STOPPED;
	} else if (csf_ode_substep(ode, ta, r->ya, tc - ta, r->ys)) {
		if (r->fail) return CSF_ODE_STOPPED;
		snprintf(msg, msglen, "the %s step from t=%.17g to locate an event at t=%.17g failed", csf_ode_method(ode),
		         ta, tc);
		return CSF_ODE_FAILED;
	}
	return csf_run_guards_at(r, tc, r->ys, r->gs) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/*
 * Guard k at time tc of the step from (ta, r->ya) to (tb, yb), into r->gs (the
 * state in r->ys): on the state stepped exactly from the step's start, or
 * (dense) on the step's continuous extension, which costs no step. On the
 * extension, an apart pair's gap (its first guard) is the geometry of the
 * positions alone (csf_contacts_gap_rate, the value its guard takes in an
 * evaluation), with no evaluation of the right-hand side: most events of a
 * pile are impacts, and this was some five of the 77 evaluations of each.
 * Only its bodies' slots of r->ys are interpolated then (csf_ode_dense_at,
 * the same values): the rest of r->ys is not that state.
 */
/* Whether guard k is a contact pair's first guard (an apart pair's gap: csf_contacts_gap_slots), that pair
   (k - r->gcont) / 2. */
static int pair_gap_guard(const run *r, size_t k) { return r->cs && k >= r->gcont && (k - r->gcont) % 2 == 0; }

static int guard_at(run *r, csf_ode *ode, int dense, uint32_t k, double ta, double tb, const double *yb, double tc,
                    char *msg, size_t msglen)
{
	if (!dense) return substep_guards(r, ode, ta, tb, yb, tc, msg, msglen);
	uint32_t idx[12], ni;
	double rate;
	if (pair_gap_guard(r, k) && (ni = csf_contacts_gap_slots(r->cs, (uint32_t)(k - r->gcont) / 2, idx)) > 0) {
		if (csf_ode_dense_at(ode, tc, idx, ni, r->ys)) return CSF_ODE_STOPPED;
		csf_contacts_gap_rate(r->cs, (uint32_t)(k - r->gcont) / 2, r->m, r->ys, &r->gs[k], &rate);
		return CSF_ODE_OK;
	}
	if (csf_ode_dense_eval(ode, tc, r->ys)) return CSF_ODE_STOPPED;
	return csf_run_guards_at(r, tc, r->ys, r->gs) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/* The state and guards in r->ys and r->gs, at time t, the upper end of a bracket: into r->yk and r->gk, *kept = t. */
static void keep_high(run *r, double *kept, double t)
{
	memcpy(r->yk, r->ys, r->p->ny * sizeof *r->yk);
	memcpy(r->gk, r->gs, r->ng * sizeof *r->gk);
	*kept = t;
}

/*
 * Narrows [*lo, *hi], where guard k is >= 0 at *lo (value *glo) and < 0 at
 * *hi (*ghi), to at most tol by the Illinois method, on exact states or on
 * the continuous extension (guard_at).
 */
static int illinois(run *r, csf_ode *ode, int dense, uint32_t k, double ta, double tb, const double *yb, double *lo,
                    double *glo, double *hi, double *ghi, double tol, int *at_hi, int *lx, double *kept, char *msg,
                    size_t msglen)
{
	int side = 0, st;
	*at_hi = 0;
	/* Each pass moves an end of the bracket inwards by at least one double, so the loop ends:
	   it stops when the bracket is tol wide or its ends are adjacent doubles (the spacing of
	   doubles at the event's time can exceed tol: 1.1e-13 s past 512 s). */
	while (*hi - *lo > tol && nextafter(*lo, *hi) < *hi) {
		if (csf_signal && !r->row_end) return CSF_ODE_HALTED;
		double c = *hi - *ghi * (*hi - *lo) / (*ghi - *glo);
		/* the secant's point rounds to an end when the guard there is tiny (a crossing found
		   exactly): it then moves in by tol / 4 below, which ends the search; only a point
		   that is not a number, or outside the bracket, is a bisection */
		if (!(c >= *lo && c <= *hi)) c = *lo + (*hi - *lo) / 2;
		if (c - *lo < tol / 4) c = *lo + tol / 4; /* shrink the bracket from both ends */
		if (*hi - c < tol / 4) c = *hi - tol / 4;
		/* tol / 4 can be under half the spacing of doubles at c: the nudge rounds back onto the end */
		if (c <= *lo) c = nextafter(*lo, *hi);
		if (c >= *hi) c = nextafter(*hi, *lo);
		if ((st = guard_at(r, ode, dense, k, ta, tb, yb, c, msg, msglen))) return st;
		double gc = r->gs[k];
		*at_hi = gc < 0;
		if (gc < 0) {
			*hi = c, *ghi = gc;
			if (kept) keep_high(r, kept, c);
			if (side < 0) *glo /= 2;
			side = -1;
		} else {
			*lo = c, *glo = gc;
			if (lx) memcpy(r->gx, r->gs, r->ng * sizeof *r->gx), *lx = 1;
			if (side > 0) *ghi /= 2;
			side = 1;
		}
	}
	return CSF_ODE_OK;
}

/*
 * The state at tc on the trajectory through the exact state in r->ys at ty
 * (a substep's; derivative r->fs), moved there in place, with its
 * derivative and guards (r->fs, r->gs): that state plus (tc - ty) times
 * the derivative, off the trajectory by (tc - ty)^2 / 2 times the second
 * derivative. Within NEAR_STEPS location tolerances of ty (1e-10 s at
 * most) that is some 1e-17 of a velocity whose second derivative is
 * 1e3 m/s^3, where a substep of its own from the step's start is off by
 * the substep's error, some 1e-12 of the values, either way: the two ends
 * of a crossing's bracket, 2.5e-14 s apart, were looked at on two substeps
 * whose errors decided which side the crossing was on as often as the
 * crossing did (a pile of 256 balls widened the bracket at 1403 of 2125
 * events, each widening two substeps more). CSF_ODE_OK, or STOPPED if a
 * derivative was not finite.
 */
enum { NEAR_STEPS = 1024 };

static int moved_to(run *r, double ty, double tc)
{
	double d = tc - ty;
	for (size_t i = 0; i < r->p->ny; i++) r->ys[i] += d * r->fs[i];
	return csf_run_guards_at(r, tc, r->ys, r->gs) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/* Whether the state at tc is moved_to from the state at ty, exact: within NEAR_STEPS tolerances of it. */
static int near_exact(const run *r, int exact, double ty, double tc)
{
	double near = NEAR_STEPS * csf_run_location_tol(r->p);
	return exact && tc - ty <= near && ty - tc <= near;
}

/*
 * The time *tk of guard k's crossing in (lo, hi], where g(lo) >= 0 > g(hi),
 * on states stepped from the step's start (ta, r->ya) that ended at
 * (tb, yb); leaves the state at that time in r->ys. *tl is the bracket's
 * other end: the guard is >= 0 there. With a continuous extension, the
 * crossing is found on it first, without steps; then the exact guards are
 * looked at on either side of it, tol / 8 away (a bracket a quarter of
 * the location's width: the event's time is the bracket's far end, and a
 * narrow one keeps it near the crossing, which a sliding mode's events,
 * each from the last, would otherwise drift from), and, where they do not
 * change sign across it, ever wider (by factors of 8), each end looked at
 * narrowing the bracket: the first on a substep, those after it moved_to
 * from it while they are near it (two substeps an event, and two more at
 * each widening, were half of a pile's evaluations); then the bracket is
 * narrowed on exact states (the Illinois method), some forty steps from a
 * whole step's bracket (a pile of 256 balls to 0.2 s: 132 460
 * evaluations for its 2125 events, 87 795 since). The state left at *tk
 * is the one on which the guard was found below zero there, kept (r->yk,
 * r->gk), not one computed again: a state moved_to differs from a
 * substep's by the substep's error, and a cluster's forces can jump
 * between two such states (its elimination's pivot on either side of its
 * threshold), so that the event was taken on a state with no pull and was
 * found again 3.4e-13 s later, 1001 times (the column of nine at 0.55 m/s);
 * and a bsimp step taken again need not be the same bits. Where ghi is the interpolant's
 * (sure = 0: hi is a sample inside the step), the exact guard at hi is
 * computed only when the brackets around the crossing reach hi (at once
 * without a continuous extension); where it is not negative there,
 * the bracket runs to the step's end (its guard r->gb), and *none is set,
 * with nothing located, when that is not negative either (the
 * interpolant's alarm was false). Returns as substep_guards.
 */
static int locate(run *r, csf_ode *ode, uint32_t k, double ta, double tb, const double *yb, double lo, double glo,
                  double hi, double ghi, int sure, double *tk, double *tl, int *lx, int *none, char *msg, size_t msglen)
{
	const double tol = csf_run_location_tol(r->p);
	int st, at_hi = 0;
	*none = *lx = 0;
	int exact = 0; /* r->ys and r->fs hold the state at ty, a substep's or moved_to from one */
	double ty = 0, kept = NAN; /* r->yk and r->gk: the state and guards at time kept, an upper end */
	if (r->dense) {
		double l = lo, gl = glo, u = hi, gu = ghi;
		if ((st = illinois(r, ode, 1, k, ta, tb, yb, &l, &gl, &u, &gu, tol, &at_hi, NULL, NULL, msg, msglen))) return st;
		at_hi = 0; /* the state in r->ys is hi's only when an exact step to hi was the last */
		for (double w = tol / 8;; w *= 8) {
			double x[2] = { u - w, u + w };
			for (int e = 0; e < 2; e++) {
				if (!(x[e] > lo && x[e] < hi)) continue;
				if ((st = near_exact(r, exact, ty, x[e]) ? moved_to(r, ty, x[e])
				                                         : substep_guards(r, ode, ta, tb, yb, x[e], msg, msglen)))
					return st;
				ty = x[e], exact = 1;
				if (r->gs[k] >= 0) {
					lo = x[e], glo = r->gs[k], at_hi = 0, *lx = 1;
					memcpy(r->gx, r->gs, r->ng * sizeof *r->gx);
				} else {
					hi = x[e], ghi = r->gs[k], sure = at_hi = 1;
					keep_high(r, &kept, hi);
				}
			}
			if ((sure && hi - lo <= 2 * w) || (x[0] <= lo && x[1] >= hi)) break;
		}
	}
	if (!sure) { /* the exact guard at hi; not below there: the step's end */
		if ((st = substep_guards(r, ode, ta, tb, yb, hi, msg, msglen))) return st;
		ghi = r->gs[k], at_hi = 1;
		if (ghi < 0) keep_high(r, &kept, hi);
		if (ghi >= 0) {
			hi = tb, ghi = r->gb[k], at_hi = 0;
			if (ghi >= 0) return *none = 1, CSF_ODE_OK;
		}
	}
	if (hi - lo > tol && nextafter(lo, hi) < hi &&
	    (st = illinois(r, ode, 0, k, ta, tb, yb, &lo, &glo, &hi, &ghi, tol, &at_hi, lx, &kept, msg, msglen)))
		return st;
	*tk = hi, *tl = lo;
	if (lo == ta) memcpy(r->gx, r->ga, r->ng * sizeof *r->gx), *lx = 1;
	if (hi == tb) {
		memcpy(r->ys, yb, r->p->ny * sizeof *yb);
		return CSF_ODE_OK;
	}
	/* the last evaluation was at hi: its state and guards are in r->ys and r->gs already */
	if (at_hi) return CSF_ODE_OK;
	if (kept == hi) { /* the state its guard was found below at */
		memcpy(r->ys, r->yk, r->p->ny * sizeof *r->ys);
		memcpy(r->gs, r->gk, r->ng * sizeof *r->gs);
		return CSF_ODE_OK;
	}
	return substep_guards(r, ode, ta, tb, yb, hi, msg, msglen);
}

/*
 * A grazing approach. An apart pair's guard is its gap, and the gap's rate
 * is known from the state: the relative velocity along the normal. A gap
 * that is positive at two of the instants a step's guards are looked at
 * and negative between them must close (its rate negative) and then open
 * (positive): its minimum is where the rate turns from one to the other.
 * So between two such instants, a pair's rate that turns is a bracket of
 * that minimum; the interior extrema of the cubic Hermite of the gap (its
 * values and rates at the two instants) are looked at too, so that a rate
 * that turns and turns back between them is seen as the sampled guards
 * are. Each bracket is narrowed by the Illinois method on the rate, over
 * the step's interpolant (no evaluation of the right-hand side), to the
 * location tolerance or to the first point where the gap is negative; a
 * minimum that is not negative is no event. The earliest negative point is
 * one more instant at which every guard is looked at, and the crossing is
 * then located between the instant before it and it, as any other.
 */

/* Candidate q's gap and rate at fraction s of the step (on its interpolant, in r->ys). 0, or 1 if it failed. */
static int gap_at(run *r, csf_ode *ode, double ta, double tb, const double *y, uint32_t q, double s, double *g,
                  double *v)
{
	if (csf_run_interp(r, ode, ta, tb, y, s, r->ys)) return 1;
	csf_contacts_gap_rate(r->cs, q, r->m, r->ys, g, v);
	return 0;
}

/*
 * The minimum of candidate q's gap in (a, b), fractions of the step, where
 * its rate turns from va < 0 to vb > 0: *s becomes the first point found
 * where the gap is negative (left alone if there is none). 0, or 1 if an
 * evaluation failed.
 */
static int graze_min(run *r, csf_ode *ode, double ta, double tb, const double *y, uint32_t q, double a, double va,
                     double b, double vb, double *s)
{
	const double tol = csf_run_location_tol(r->p) / (tb - ta);
	int side = 0;
	while (b - a > tol && nextafter(a, b) < b) {
		double c = b - vb * (b - a) / (vb - va), g, v;
		if (!(c >= a && c <= b)) c = a + (b - a) / 2;
		if (c - a < tol / 4) c = a + tol / 4;
		if (b - c < tol / 4) c = b - tol / 4;
		if (c <= a) c = nextafter(a, b);
		if (c >= b) c = nextafter(b, a);
		if (gap_at(r, ode, ta, tb, y, q, c, &g, &v)) return 1;
		if (g < 0) {
			*s = c;
			return 0;
		}
		if (v < 0) {
			a = c, va = v;
			if (side < 0) vb /= 2;
			side = -1;
		} else {
			b = c, vb = v;
			if (side > 0) va /= 2;
			side = 1;
		}
	}
	return 0;
}

/*
 * The interior extrema, in increasing order, of the cubic Hermite on [0, 1]
 * with values g0, g1 and derivatives d0, d1 (the rates times the interval's
 * length), into u; returns how many (0 to 2).
 */
static int cubic_extrema(double g0, double d0, double g1, double d1, double u[2])
{
	/* its derivative: A u^2 + B u + C */
	double A = 6 * (g0 - g1) + 3 * (d0 + d1), B = -6 * (g0 - g1) - 4 * d0 - 2 * d1, C = d0, x[2];
	int n = 0, k = 0;
	if (A == 0) {
		if (B != 0) x[n++] = -C / B;
	} else {
		double disc = B * B - 4 * A * C;
		if (disc > 0) {
			double r = sqrt(disc), q = -(B + (B < 0 ? -r : r)) / 2; /* without cancellation; not 0 */
			x[n++] = q / A;
			x[n++] = C / q;
		}
	}
	if (n == 2 && x[1] < x[0]) {
		double t = x[0];
		x[0] = x[1], x[1] = t;
	}
	for (int i = 0; i < n; i++)
		if (x[i] > 0 && x[i] < 1) u[k++] = x[i];
	return k;
}

/*
 * The earliest point of the step from (ta, r->ya) to (tb, y), as a
 * fraction of it, where an armed apart candidate's gap is negative though
 * positive at the instants sampled before and after it (the step's start,
 * the 3 interpolated states in r->yh, its end): into *sg, left alone when
 * there is none. 0, or 1 if an evaluation failed.
 */
static int graze_point(run *r, csf_ode *ode, double ta, double tb, const double *y, double *sg)
{
	const csf_prog *p = r->p;
	size_t n = p->ny;
	const double *ys[5] = { r->ya, r->yh, r->yh + n, r->yh + 2 * n, y };
	double dt = tb - ta;
	for (uint32_t q = 0; q < csf_contacts_count(r->cs); q++) {
		double g[5], v[5];
		if (!(r->ga[r->gcont + 2 * (size_t)q] >= 0)) continue;
		if (!csf_contacts_gap_rate(r->cs, q, r->m, ys[0], &g[0], &v[0])) continue;
		for (int j = 1; j < 5; j++) csf_contacts_gap_rate(r->cs, q, r->m, ys[j], &g[j], &v[j]);
		for (int j = 0; j < 4 && j / 4.0 < *sg; j++) {
			if (!(g[j] >= 0 && g[j + 1] >= 0)) break; /* the samples see the crossing */
			/* the points of the interval whose rates are looked at: its ends, and the cubic's extrema */
			double s0 = j / 4.0, h = 0.25, u[2], sp[4], vp[4], gm = 0;
			int k = cubic_extrema(g[j], h * dt * v[j], g[j + 1], h * dt * v[j + 1], u), np = 0;
			sp[np] = s0, vp[np++] = v[j];
			for (int i = 0; i < k && gm >= 0; i++) {
				sp[np] = s0 + h * u[i];
				if (gap_at(r, ode, ta, tb, y, q, sp[np], &gm, &vp[np])) return 1;
				np++;
			}
			if (gm < 0) { /* negative at an extremum */
				*sg = csf_min(*sg, sp[np - 1]);
				break;
			}
			sp[np] = s0 + h, vp[np++] = v[j + 1];
			double s = 2;
			for (int i = 0; i + 1 < np && s > 1; i++)
				if (vp[i] < 0 && vp[i + 1] > 0 && graze_min(r, ode, ta, tb, y, q, sp[i], vp[i], sp[i + 1], vp[i + 1], &s))
					return 1;
			if (s <= 1) {
				*sg = csf_min(*sg, s);
				break;
			}
		}
	}
	return 0;
}

/*
 * After a step from (ta, r->ya), with guards r->ga and derivative r->fa
 * there, to (tb, y): the earliest event in (ta, tb]. *which is its guard, or
 * -1 when there is none (r->ga and r->fa then move on to tb); *te is its
 * time, r->ye the state there, r->last and r->last_src name it.
 */
int csf_run_step_events(run *r, csf_ode *ode, double ta, double tb, const double *y, double *te, long *which, char *msg,
                       size_t msglen)
{
	const csf_prog *p = r->p;
	size_t n = p->ny;
	int st;
	*which = -1;
	if (r->cs && csf_contacts_unsolved(r->cs)) { /* the forces of the step did not hold the contacts */
		r->unsettled = CSF_SETTLE_FORCES, r->unsettled_t = ta;
		return CSF_ODE_STOPPED;
	}
	if (csf_run_guards_at(r, tb, y, r->gb)) return CSF_ODE_STOPPED;
	memcpy(r->fb, r->fs, n * sizeof *y);
	double lo = ta, hi = tb, dt = tb - ta;
	if (r->cs) {
		/* the candidate contacts of this step: every pair that can touch at the instants
		   its guards are looked at (the start, 3 interpolated points, the end) */
		for (int j = 1; j < 4; j++)
			if (csf_run_interp(r, ode, ta, tb, y, j / 4.0, r->yh + (size_t)(j - 1) * n)) return CSF_ODE_STOPPED;
		const double *ys[5] = { r->ya, r->yh, r->yh + n, r->yh + 2 * n, y }, *gy[2] = { r->ya, y };
		double **g[2] = { &r->ga, &r->gb };
		if (choose_contacts(r, ys, 5, (tb - ta) / 4, g, gy, 2)) return CSF_ODE_STOPPED;
	}
	size_t ng = r->ng;
	/* the sample points, as fractions of the step: 3 interpolated (with contacts, computed above),
	   a grazing approach's (before the first of them after it), then the step's end */
	double sg = 2, sv[5];
	const double *yv[5];
	int ns = 0;
	if (r->cs && graze_point(r, ode, ta, tb, y, &sg)) return CSF_ODE_STOPPED;
	for (int j = 1; j <= 4; j++) {
		if (sg < j / 4.0) sv[ns] = sg, yv[ns++] = NULL, sg = 2;
		sv[ns] = j / 4.0, yv[ns++] = j == 4 ? y : r->cs ? r->yh + (size_t)(j - 1) * n : NULL;
	}
	/* the first of them where an armed guard is negative: [lo, hi], with hi's guards in r->gh;
	   where every alarm there is false (no guard below on the exact states at hi or at the
	   step's end), the samples after hi are looked at in the same way: a guard that crosses
	   after hi, not yet negative there, was passed over, and an impact went unseen (a ball
	   1.1e-5 m inside another, tests/piles/jam.sh X = 0.21 with rows every 2 ms) */
	double best = tb, bl = ta;
	memcpy(r->gp, r->ga, ng * sizeof *r->gp);
	for (int j0 = 0; *which < 0 && j0 < ns;) {
		int found = 0;
		for (int j = j0; j < ns && !found; j++) {
			if (j > 0) memcpy(r->gp, r->gh, ng * sizeof *r->gp);
			j0 = j + 1;
			if (yv[j] != y) {
				const double *yj = yv[j];
				if (!yj) {
					if (csf_run_interp(r, ode, ta, tb, y, sv[j], r->ys)) return CSF_ODE_STOPPED;
					yj = r->ys;
				}
				hi = ta + sv[j] * dt;
				if (csf_run_guards_at(r, hi, yj, r->gh)) return CSF_ODE_STOPPED;
			} else {
				hi = tb;
				memcpy(r->gh, r->gb, ng * sizeof *r->gh);
			}
			for (size_t k = 0; k < ng; k++) found |= r->ga[k] >= 0 && r->gh[k] < 0;
			if (!found) lo = hi;
		}
		if (!found) break;
		/* the earliest crossing among the guards negative at hi, each bracketed on exact states;
		   once one is located in (bl, best], a guard that is not yet negative at best crosses
		   later, and one negative at best but not at bl crosses at the same instant (to the
		   location's tolerance): neither is located, so that many pairs that switch at once (a
		   row of blocks that stop together) cost one location, not one each */
		/* taken in the order of their crossings' estimates (each guard's line between its
		   values at lo and hi, on the interpolant): the earliest is most often located first,
		   and the others are then passed over (a pile's step crosses several guards; in their
		   own order some 2.4 were located an event) */
		/* an apart pair's gap, whose line misleads where it closes at a rate that changes (in a
		   pile's rattle the first located was not the earliest at 8044 of 9642 events, each
		   costing two exact steps more), by its crossing on the continuous extension, which
		   costs no evaluation (guard_at) */
		size_t nc = 0;
		for (size_t k = 0; k < ng; k++) {
			if (!(r->ga[k] >= 0 && r->gh[k] < 0)) continue;
			double sk = r->gp[k] >= 0 ? r->gp[k] / (r->gp[k] - r->gh[k]) : 0, g, rate;
			if (r->dense && r->gp[k] >= 0 && pair_gap_guard(r, k) &&
			    csf_contacts_gap_rate(r->cs, (uint32_t)(k - r->gcont) / 2, r->m, y, &g, &rate)) {
				double l = lo, gl = r->gp[k], u = hi, gu = r->gh[k];
				int at_hi;
				if ((st = illinois(r, ode, 1, (uint32_t)k, ta, tb, y, &l, &gl, &u, &gu, csf_run_location_tol(p),
				                   &at_hi, NULL, NULL, msg, msglen)))
					return st;
				sk = (u - lo) / (hi - lo);
			}
			r->est[k] = sk;
			size_t at = nc++; /* insertion by sk; ties in the guards' order */
			for (; at > 0; at--) {
				uint32_t q = r->order[at - 1];
				if (!(r->est[q] > sk)) break;
				r->order[at] = q;
			}
			r->order[at] = (uint32_t)k;
		}
		int known = 0; /* the guards at bl are in r->gl (those at best, in r->gt, always are) */
		for (size_t c = 0; c < nc; c++) {
			size_t k = r->order[c];
			if (*which >= 0 && !known) {
				if ((st = substep_guards(r, ode, ta, tb, y, bl, msg, msglen))) return st;
				memcpy(r->gl, r->gs, ng * sizeof *r->gl);
				known = 1;
			}
			if (*which >= 0 && (r->gt[k] >= 0 || r->gl[k] >= 0)) continue;
			/* the exact state's guards at lo and hi (the interpolant only pointed here) */
			double l = lo, gl = r->ga[k], u = hi, gu = r->gh[k];
			int sure = hi == tb, none, lx;
			if (lo > ta) {
				if ((st = substep_guards(r, ode, ta, tb, y, lo, msg, msglen))) return st;
				if (r->gs[k] < 0) l = ta; /* already below at lo: the crossing is earlier */
				else gl = r->gs[k];
			}
			if (*which >= 0) { /* below at bl: the crossing is before it */
				if (bl <= l) continue; /* (it cannot be: bl is past a state where the guard is >= 0) */
				u = bl, gu = r->gl[k], sure = 1;
			} /* else hi's exact guard is locate's to look at, when it needs it */
			double tk, tl;
			if ((st = locate(r, ode, (uint32_t)k, ta, tb, y, l, gl, u, gu, sure, &tk, &tl, &lx, &none, msg, msglen)))
				return st;
			if (none) continue;
			if (tk < best || *which < 0) { /* its guards at tk (locate's last), and at tl where it knows them */
				best = tk, bl = tl, *which = (long)k, known = lx;
				memcpy(r->ye, r->ys, n * sizeof *r->ye);
				memcpy(r->gt, tk < tb ? r->gs : r->gb, ng * sizeof *r->gt);
				if (lx) memcpy(r->gl, r->gx, ng * sizeof *r->gl);
			}
		}
		lo = hi; /* every alarm at hi was false: the samples after it */
	}
	if (*which < 0) { /* none, or the interpolant's alarm was false */
		memcpy(r->ga, r->gb, ng * sizeof *r->ga);
		memcpy(r->fa, r->fb, n * sizeof *r->fa);
		return CSF_ODE_OK;
	}
	*te = best;
	r->last = *which;
	if (*which >= (long)r->gcont) { /* a contact: its objects now, as the candidates are chosen again */
		uint32_t pair = (uint32_t)(*which - (long)r->gcont) / 2;
		csf_contacts_objects(r->cs, pair, &r->last_oi, &r->last_oj);
		r->last_src = csf_contacts_src(r->cs, pair);
	} else
		r->last_src = *which < (long)p->nevents ? p->events[*which].src : p->cons[*which - (long)p->nevents].src;
	return CSF_ODE_OK;
}
