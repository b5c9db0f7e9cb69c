/*
 * advance.c - the advance loops: from one output time to the next, by plain
 * adaptive steps, by steps stopped at events, or (a method with a continuous
 * extension, and --method auto) by the integrator's own steps; the taking of
 * an event and of a 'stop when' condition.
 */
#include <math.h>
#include <string.h>

#include "run_int.h"

/* After the modes were set at t from scratch: a 'stop when' condition already true ends the run there. */
void csf_run_stop_now(run *r, double t)
{
	const csf_prog *p = r->p;
	for (uint32_t i = 0; i < p->nevents && !r->stopped; i++)
		if (p->events[i].kind & CSF_EVENT_TERMINAL && r->m[p->events[i].mode] > 0)
			r->stopped = 1, r->stop_t = t, r->stop_src = p->events[i].src;
}

/*
 * Takes the event r->last at (t, y): the `when` blocks, the modes brought
 * up to date, the integrator restarted (with --rows-at-events, a row before
 * and one after). A 'stop when' condition's ends the run instead:
 * ADV_TERMINAL, with its time in r->stop_t. 0, or CSF_ODE_STOPPED when a
 * derivative is not finite.
 */
int csf_run_take_event(run *r, csf_ode *ode, double t, double *y)
{
	r->nevents++;
	r->pending = 0;
	if (r->last >= 0 && r->last < (long)r->p->nevents && r->p->events[r->last].kind & CSF_EVENT_TERMINAL) {
		r->stop_src = r->last_src;
		r->stop_t = t;
		return ADV_TERMINAL;
	}
	if (r->event_row) r->event_row(r, t, y, -1);
	if (r->g) r->g->due = 1; /* the scene may have changed: with fixed steps, look after the next one */
	/* the `when` blocks on the values before the event, then the modes (and impacts); again while
	   the blocks fire on what the modes changed (a velocity an impact reversed) */
	r->wround = 0;
	for (int pass = 0, fired = 1; fired; pass++) {
		int st = csf_run_whens(r, t, y, &fired);
		if (st) return st;
		if (pass > 0 && !fired) break;
		if (csf_run_update_modes(r, t, y, NULL)) return CSF_ODE_STOPPED;
		if (csf_run_cons_row(r, t, y)) return CSF_ODE_STOPPED; /* impulses the constraints did not see */
		fired = r->p->nwhens != 0;
	}
	if (r->event_row) r->event_row(r, t, y, 1);
	csf_ode_restart(ode);
	if (csf_run_guards_at(r, t, y, r->ga)) return CSF_ODE_STOPPED;
	memcpy(r->fa, r->fs, r->p->ny * sizeof *r->fa);
	return 0;
}

/* Has the run spent more evaluations than its budget (csf_opts.max_rhs)? */
static int over_budget(const run *r) { return r->max_rhs && r->nrhs > r->max_rhs; }

/* Advances (*t, y) to t1 by adaptive steps, at most MAX_WORK of them. */
int csf_run_advance_plain(run *r, csf_ode *ode, double *t, double t1, double *y, char *msg, size_t msglen)
{
	for (unsigned long work = 0; *t < t1; work++) {
		double ta = *t;
		if (work == MAX_WORK) return ADV_TOO_MUCH;
		if (over_budget(r)) return ADV_BUDGET;
		int st = csf_ode_step(ode, t, t1, 0, 0, y, msg, msglen);
		if (st != CSF_ODE_OK) return st;
		r->last_h = *t - ta;
		if (csf_run_cons_step(r, ode, *t, y)) return CSF_ODE_STOPPED;
	}
	return CSF_ODE_OK;
}

/*
 * Events that crowd: CROWD_EVENTS in a row within a span of time so short
 * that, at their pace, the time left to the last output time would take
 * more than CROWD_MORE more (a pile of 64 balls whose contact stuck and
 * slid every 1e-8 s: the run went on for hours without a word). A warning,
 * once a run, naming the last event; the run goes on. It depends on the
 * events' times alone, so that csfvm and a generated program warn alike.
 */
enum { CROWD_EVENTS = 1000 };
static const double CROWD_MORE = 1e6;

static void crowd(run *r, double te)
{
	if (r->crowd_n++ == 0) r->crowd_t = te;
	if (r->crowd_n <= CROWD_EVENTS || r->crowd_warned) return;
	double span = te - r->crowd_t, more = (r->tend - te) / span * CROWD_EVENTS;
	r->crowd_n = 0;
	if (!(span > 0) || !(more > CROWD_MORE)) return;
	const csf_prog *p = r->p;
	char tb[32], left[32], last[160] = "";
	csf_fmt_double(tb, te);
	csf_run_fmt_ratio(left, more);
	r->crowd_warned = 1;
	csf_run_progress_off(r);
	if (r->last >= (long)r->gcont)
		snprintf(last, sizeof last, "the contact of '%s' and '%s'", csf_str(p, p->objects[r->last_oi]),
		         csf_str(p, p->objects[r->last_oj]));
	else {
		const csf_src *sr = &p->srcs[r->last_src];
		snprintf(last, sizeof last, "the rule at %s:%lu", csf_str(p, p->files[sr->file]), (unsigned long)sr->line);
	}
	fprintf(r->err,
	        "warning: at t=%s the last %d events came within %.3g s (the last of them of %s): at that pace "
	        "the %.3g s left take some %s more\n",
	        tb, CROWD_EVENTS, span, last, r->tend - te, left);
}

/* One more event at time te after a step from ta: ADV_CHATTER after 1000 in a row that do not advance
   time; a warning where they crowd (crowd). */
static int chatter(run *r, unsigned long *same, double ta, double te, char *msg, size_t msglen)
{
	crowd(r, te);
	if (te - ta > 1e-12 * (1 + fabs(te))) {
		*same = 0;
		return 0;
	}
	if (++*same <= 1000) return 0;
	snprintf(msg, msglen, "%lu events without time advancing", *same);
	return ADV_CHATTER;
}

/*
 * Advances (*t, y) to t1 as csf_ode_step does, stopping at events. On entry
 * r->ga and r->fa hold the guards and derivative at (*t, y), unless an event
 * located at the last output time is pending: it happens first.
 */
int csf_run_advance_events(run *r, csf_ode *ode, double *t, double t1, int fixed, double h, double *y, char *msg,
                          size_t msglen)
{
	const csf_prog *p = r->p;
	size_t n = p->ny;
	unsigned long same = 0, work = 0;
	int st;
	if (r->pending && (st = csf_run_take_event(r, ode, *t, y))) return st;
	while (*t < t1) {
		double ta = *t, best;
		long which;
		if (++work > MAX_WORK) return ADV_TOO_MUCH;
		if (over_budget(r)) return ADV_BUDGET;
		memcpy(r->ya, y, n * sizeof *y);
		st = csf_ode_step(ode, t, t1, fixed, h, y, msg, msglen);
		if (st != CSF_ODE_OK) return st;
		r->last_h = *t - ta;
		if ((st = csf_run_step_events(r, ode, ta, *t, y, &best, &which, msg, msglen))) return st;
		if (which < 0) {
			same = 0;
			if (csf_run_cons_step(r, ode, *t, y)) return CSF_ODE_STOPPED;
			continue;
		}
		memcpy(y, r->ye, n * sizeof *y);
		*t = best;
		if (t1 - best <= csf_run_location_tol(p)) { /* at an output time: its row shows the state before the event */
			*t = t1;
			r->pending = 1;
			return CSF_ODE_OK;
		}
		if ((st = csf_run_take_event(r, ode, best, y))) return st;
		if ((st = chatter(r, &same, ta, best, msg, msglen))) return st;
	}
	return CSF_ODE_OK;
}

/*
 * --method auto: the other method takes the steps from (r->ti, r->yi) on,
 * restarted there (no history: the state is the one the last step ended
 * at), with the error scales the first one has reached (the sizes the
 * state has had so far) and a first step from its estimate. 0, or
 * CSF_ODE_STOPPED if f failed there.
 */
static int switch_method(run *r)
{
	autom *au = r->au;
	csf_ode *to = au->m[!au->cur];
	au->want = 0, au->soft = 0;
	csf_ode_restart(to);
	csf_ode_take_scale(to, au->m[au->cur]);
	if (csf_ode_first_step(to, r->ti, r->yi)) return CSF_ODE_STOPPED;
	r->fail = 0; /* an Euler step of the estimate that failed was tried again shorter */
	au->cur = !au->cur;
	if (au->n < AUTO_SHOWN) au->at[au->n] = r->ti;
	au->n++;
	r->ode = to;
	r->dense = csf_ode_dense(to);
	return 0;
}

/*
 * A method with a continuous extension (csf_ode_dense): the integrator, at
 * (r->ti, r->yi), steps as far as its error control allows towards the
 * last output time, past tk, and the state y at tk is computed from the
 * last step's extension (or is its end), never by shortening a step to end
 * at tk. With --method auto, also the implicit method, which has none: its
 * steps end at tk. Each row comes from the method that took the step it is
 * in: a switch takes effect at the next step, when the rows before the
 * integrator's time have been computed. With events, a step is cut at its earliest event: the integrator
 * stops there, the rows before it come from the step's extension, and the
 * event is taken (modes, impacts, a restart) before the next step
 * (r->pending). An event within location_tol before an output time is moved
 * to it: the row shows the state before the event. On entry with events,
 * r->ga and r->fa hold the guards and derivative at (r->ti, r->yi) unless
 * an event is pending there.
 */
int csf_run_advance_dense(run *r, double tk, double *y, char *msg, size_t msglen)
{
	csf_ode *ode = r->ode;
	const csf_prog *p = r->p;
	size_t n = p->ny;
	unsigned long same = 0, work = 0;
	int events = p->nevents || p->ncrules || r->ncg;
	while (r->ti < tk) {
		double ta = r->ti, te;
		long which;
		if (++work > MAX_WORK) return ADV_TOO_MUCH;
		if (over_budget(r)) return ADV_BUDGET;
		int st;
		if (r->pending && (st = csf_run_take_event(r, ode, r->ti, r->yi))) {
			if (st == ADV_TERMINAL) memcpy(y, r->yi, n * sizeof *y);
			return st;
		}
		if (r->au && r->au->want) {
			if ((st = switch_method(r))) return st;
			ode = r->ode;
		}
		/* off the constraints after the last step: back on them, now that its rows are written */
		if (csf_run_cons_step(r, ode, r->ti, r->yi)) return CSF_ODE_STOPPED;
		if (events) memcpy(r->ya, r->yi, n * sizeof *y);
		st = csf_ode_step(ode, &r->ti, r->dense ? r->tend : tk, 0, 0, r->yi, msg, msglen);
		if (st == CSF_ODE_FAILED && events && r->au && r->au->cur && !r->fail) {
			/* the implicit method's step collapsed in a scene with events: its Jacobian, by
			   differences, spans the switching of contacts' modes (a Galton board whose spectrum
			   looked stiff at an event, then every step refused): dop853 takes the step again
			   from its start, and keeps the steps from there on */
			r->ti = ta;
			memcpy(r->yi, r->ya, n * sizeof *y);
			r->au->want = 1, r->au->failed = 1;
			continue;
		}
		if (st != CSF_ODE_OK) return st;
		r->last_h = r->ti - ta;
		if (!events) continue;
		if ((st = csf_run_step_events(r, ode, ta, r->ti, r->yi, &te, &which, msg, msglen))) return st;
		if (which < 0) {
			same = 0;
			continue;
		}
		double row = ceil(te / p->by) * p->by; /* the first output time at or after the event */
		if (row < te) row += p->by;
		if (row - te <= csf_run_location_tol(p) && row <= r->ti) te = row;
		r->ti = te;
		memcpy(r->yi, r->ye, n * sizeof *y);
		r->pending = 1;
		if ((st = chatter(r, &same, ta, te, msg, msglen))) return st;
	}
	if (tk == r->ti) memcpy(y, r->yi, n * sizeof *y);
	else if (csf_ode_dense_rows(ode, tk, y)) return CSF_ODE_STOPPED;
	return CSF_ODE_OK;
}
