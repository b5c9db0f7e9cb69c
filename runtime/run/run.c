/*
 * run.c - csf_run, shared by csfvm and by every generated executable: it
 * owns the model's memory, integrates the state between output times
 * t_k = k*by, runs the OUT section at each t_k, checks assertions and
 * finiteness, and writes one CSV row per t_k as it goes. Rows are written
 * through stdio and flushed on every exit path; a write error is reported,
 * never ignored.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run_int.h"
#include "par.h"
#include "block.h"
#include "constraint.h"

/*
 * One run's state beside the run (run_int.h): the stability guard, --method
 * auto's pair, the rows' state y, the method, and what the set-up decided.
 * csf_run keeps it on its stack; r.g and r.au point into it.
 */
typedef struct session {
	run r;
	guard gd;
	autom au;
	watch_ctx wc, wc_stiff;
	const char *method; /* --method, NULL for auto */
	int autom_on;       /* --method auto: dop853 with AUTO_STIFF beside it */
	int events;         /* comparisons, or contacts (whose candidates come and go) */
	int fixed;          /* fixed steps */
	double *y, *work;   /* the rows' state; the events' work vectors */
	uint32_t *vec;      /* the state's vectors, for the error control (csf_ode_vectors) */
	uint32_t *vpair;    /* verlet's state pairs, expanded for it in a decoded program (csf_vpair_copy) */
	csf_ode *ode;
	double kmax;        /* the last output time is kmax * by */
	double every;       /* --every: the rows written are those of k a multiple of it, and the last */
	double fixed_h;     /* the fixed step */
	struct timespec t0; /* when the run started */
	FILE *out;          /* the CSV rows, or NULL */
	csf_rowthread *rows; /* the thread that writes them (wide rows), or NULL */
	const csf_sink *sink; /* the rows' values, or NULL */
	double *v;          /* with a sink: a row's values */
	const csf_overlay *init; /* initial values over p->mem0 (csf_opts.init) */
	int werr;           /* a row's write error (errno) */
	time_t flushed;     /* the second of the clock at which out was last flushed */
	char msg[256];      /* the integrator's words */
	/* --checkpoint, --resume (checkpoint below) */
	const char *ck;     /* the checkpoint's file, or NULL */
	double ck_every;    /* seconds of wall time between checkpoints */
	struct timespec ck_last; /* when the last was written */
	int ck_warned;      /* a checkpoint could not be written (said once) */
	char ck_opts[CSF_KEEP_OPTS]; /* the options a checkpoint holds the run to */
	unsigned long long hash; /* the bytecode's */
	csf_keeper *resume; /* the checkpoint read, until the run is set up from it */
	double k0, trow;    /* the first row to compute, and the time of the row before it */
	long long ck_off;   /* the output's length at the checkpoint resumed (-1: unknown) */
	char ck_err[1400];  /* why a resume failed */
} session;

static stop stop_kind_only(stop_kind kind)
{
	stop s = { .kind = kind, .hs = INFINITY };
	return s;
}

static stop stop_at(stop_kind kind, double t)
{
	stop s = stop_kind_only(kind);
	s.t = t;
	return s;
}

/* The model's memory, the rows' state, the events' work vectors and the contacts. */
static stop run_alloc(session *S)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	r->m = p->spans ? calloc(p->nmem ? p->nmem : 1, sizeof(double)) : malloc((p->nmem ? p->nmem : 1) * sizeof(double));
	S->y = malloc((p->ny ? p->ny : 1) * sizeof(double));
	for (uint32_t k = 0; k < p->ncons; k++) /* one-sided constraints switch: a guard for each constraint */
		if (p->cons[k].kind != CSF_CON_EQ) r->ncg = p->ncons;
	r->gcont = p->nevents + r->ncg;
	r->ng = r->gcont; /* and two per candidate contact, none yet */
	if (S->events || S->autom_on || p->ncons) { /* (auto, constraints: jw, for a Jacobian by differences) */
		size_t n = p->ny ? p->ny : 1;
		S->work = malloc(13 * n * sizeof *S->work);
		if (S->work) {
			r->ya = S->work, r->fa = r->ya + n, r->fb = r->fa + n, r->ys = r->fb + n, r->fs = r->ys + n,
			r->ye = r->fs + n;
			r->jw = r->ye + n;
			r->yh = r->jw + 3 * n;
			r->yk = r->yh + 3 * n;
		}
	}
	if (S->events) csf_run_room_for_guards(r, r->ng ? r->ng : 1);
	if (p->ncrules) {
		r->cs = csf_contacts_new(p);
		r->x.contacts = r->cs; /* the CONTACT instruction's state */
	}
	if (p->ncons) {
		r->cons = csf_cons_new(p);
		r->x.cons = r->cons; /* the CONSTRAIN instruction's state */
		r->cw = malloc(2 * (p->ny ? p->ny : 1) * sizeof *r->cw);
		r->cy = r->cw + (p->ny ? p->ny : 1);
	}
	if (S->sink && !S->sink->place) S->v = malloc((p->ncols + 1) * sizeof *S->v);
	S->vec = calloc(p->ny ? p->ny : 1, sizeof *S->vec);
	for (uint32_t i = 0; S->vec && i < p->nprops; i++) { /* a vector in the state: its components, together */
		const csf_prop *q = &p->props[i];
		if (q->width == 3 && q->slot >= p->ystart && (uint64_t)q->slot + 3 <= (uint64_t)p->ystart + p->ny)
			for (uint32_t k = 0; k < 3; k++) S->vec[q->slot - p->ystart + k] = q->slot - p->ystart + 1;
	}
	if (!r->m || !S->y || ((S->events || S->autom_on || p->ncons) && !S->work) || r->nomem || (p->ncrules && !r->cs) || (p->ncons && (!r->cons || !r->cw)) ||
	    (S->sink && !S->sink->place && !S->v) || !S->vec)
		return stop_kind_only(STOP_NOMEM);
	if (p->spans) /* what is not zeros: a million members' tangents and accelerations stay untouched pages */
		for (uint32_t i = 0; i < p->nspans; i++)
			memcpy(r->m + p->spans[2 * i], p->mem0 + p->spans[2 * i], p->spans[2 * i + 1] * sizeof(double));
	else
		memcpy(r->m, p->mem0, p->nmem * sizeof(double));
	if (p->ncons) r->m[p->cons[0].want] = r->ncg ? 1 : 0; /* one-sided constraints' guards read g */
	csf_overlay_apply(S->init, r->m); /* -D's values, a sweep variant's */
	memcpy(S->y, r->m + p->ystart, p->ny * sizeof(double));
	if (p->ncrules && !csf_method_contacts(S->method)) {
		stop s = stop_kind_only(STOP_NO_CONTACTS);
		s.method = S->method;
		return s;
	}
	return stop_kind_only(STOP_END);
}

double csf_run_kmax(const csf_prog *p)
{
	/* the last k with k*by <= till, allowing for till/by's rounding */
	double kmax = floor(p->till / p->by);
	if ((kmax + 1) * p->by <= p->till * (1 + 1e-12)) kmax += 1;
	return kmax;
}

/* The output times, and the method (with --method auto, the pair). */
static stop run_method(session *S, csf_opts *o)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	S->kmax = csf_run_kmax(p);
	r->tend = S->kmax * p->by;
	if (!p->ny) return stop_kind_only(STOP_END);
	/* a dense method steps as far as its error control allows (--hmax caps it), the others
	   to each output time; with events, steps of at most by, so that a guard that dips below
	   zero and back is not missed between the points each step looks at (events, below) */
	int unbounded = !o->fixed && csf_method_dense(S->method) && !S->events;
	double hmax = unbounded ? (r->tend > p->by ? r->tend : p->by) : p->by;
	if (o->hmax > 0 && o->hmax < hmax) hmax = o->hmax;
	const uint32_t *vpair = p->vpair;
	if (!vpair && csf_method_pairs(S->method)) { /* expanded only for a method that reads them */
		if (!S->vpair && !(S->vpair = csf_vpair_copy(p))) {
			snprintf(S->msg, sizeof S->msg, "out of memory");
			stop s = stop_kind_only(STOP_SETUP);
			s.msg = S->msg;
			return s;
		}
		vpair = S->vpair;
	}
	S->ode = csf_ode_new(S->method, o->fixed, p->ny, p->by, hmax, o->tol, o->atol, p->yatol, p->yscale, vpair, csf_run_rhs_trial,
	                     p->jtan ? csf_run_jac : NULL, r, S->msg, sizeof S->msg);
	if (S->ode) csf_ode_vectors(S->ode, S->vec);
	if (S->ode && (r->row_y = csf_run_row_state(p, &r->nrow_y))) csf_ode_set_rows(S->ode, r->row_y, r->nrow_y);
	if (S->ode && S->autom_on) { /* the implicit method ends its steps on the rows: at most by */
		S->au.m[0] = S->ode;
		S->au.m[1] = csf_ode_new(AUTO_STIFF, 0, p->ny, p->by, o->hmax > 0 && o->hmax < p->by ? o->hmax : p->by,
		                         o->tol, o->atol, p->yatol, p->yscale, vpair, csf_run_rhs_trial, csf_run_jac, r, S->msg, sizeof S->msg);
		r->au = &S->au;
		if (S->au.m[1]) csf_ode_vectors(S->au.m[1], S->vec);
		if (!S->au.m[1]) {
			csf_ode_free(S->ode);
			S->ode = NULL;
		}
	}
	if (!S->ode) {
		stop s = stop_kind_only(STOP_SETUP);
		s.msg = S->msg;
		return s;
	}
	return stop_kind_only(STOP_END);
}

/* The fixed step, the stability guard (when it has work), and the watch after every step. */
static stop run_guard(session *S, csf_opts *o)
{
	run *r = &S->r;
	guard *gd = &S->gd;
	const csf_prog *p = r->p;
	csf_ode *ode = S->ode;
	S->fixed = ode && (o->fixed || csf_ode_fixed_only(ode));
	S->fixed_h = ode ? csf_ode_fixed_step(ode, p->by, o->step) : p->by;
	int verlet = ode && csf_ode_fixed_only(ode);
	if (ode) {
		gd->fixed = S->fixed;
		gd->check_step = S->fixed && csf_ode_explicit(ode);
		gd->auto_step = verlet && o->step <= 0;
		gd->user_step = o->step;
		gd->vfrac = sqrt((o->tol > 0 ? o->tol : csf_method_tol("verlet")) / 1e-4);
		gd->detect_stiff = !S->fixed && csf_ode_explicit(ode);
		gd->hcap = o->hmax > 0 && o->hmax < p->by ? o->hmax : p->by;
		gd->stats = o->stats;
	}
	if (gd->check_step || gd->auto_step || gd->detect_stiff || gd->stats) {
		size_t n = p->ny;
		gd->sp = csf_spectrum_new(n);
		gd->y = malloc(4 * n * sizeof *gd->y);
		if (!gd->sp || !gd->y) return stop_kind_only(STOP_NOMEM);
		gd->f0 = gd->y + n, gd->yd = gd->f0 + n, gd->fd = gd->yd + n;
		gd->exact = p->jtan && !p->ncrules && !p->ncons;
		gd->err = r->err;
		gd->span = r->tend;
		gd->h = p->by / ceil(p->by / S->fixed_h * (1 - 1e-12)); /* the step a row's interval is cut into */
		r->g = gd;
	}
	if (ode) {
		S->wc.ode = ode;
		csf_ode_watch(ode, csf_run_step_watch, &S->wc);
		if (r->au) {
			S->wc_stiff.ode = S->au.m[1];
			csf_ode_watch(S->au.m[1], csf_run_step_watch, &S->wc_stiff);
		}
	}
	/* a train of bounces that would end within zeno is at rest; the integrator's accuracy (runtime/contact/) */
	r->zeno = 1e-6 * p->by;
	r->tol = o->tol > 0 ? o->tol : csf_method_tol(S->method);
	return stop_kind_only(STOP_END);
}

/* With events: the masses of contacts, and the modes at t = 0. */
static stop run_modes(session *S)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	double *y = S->y;
	/* the masses first, as the rules make them: the impulses and forces of contacts divide
	   by them (a derivative that is not finite is reported by update_modes below) */
	long b = r->cs && !csf_run_rhs(0, y, r->fs, r) ? csf_contacts_bad_mass(p, r->m) : -1;
	r->fail = 0;
	if (b >= 0) {
		stop s = stop_kind_only(STOP_BAD_MASS);
		s.which = b;
		return s;
	}
	/* the modes at t = 0: each comparison's side, contacts at rest or colliding; then the conditions
	   of the `when` blocks (none fires at the start) */
	int fired;
	if (csf_run_update_modes(r, 0, y, r->err) || csf_run_whens(r, 0, y, &fired) ||
	    (p->ny && csf_run_guards_at(r, 0, y, r->ga))) {
		if (r->unsettled) return stop_kind_only(STOP_UNSETTLED);
		if (r->nomem) return stop_kind_only(STOP_NOMEM);
		return stop_at(STOP_NONFINITE, 0);
	}
	memcpy(r->fa, r->fs, p->ny * sizeof *r->fa);
	csf_run_stop_now(r, 0); /* a 'stop when' condition true at the start: the row at t = 0 is the last */
	return stop_kind_only(STOP_END);
}

/* Before the first step: the modes, the integrator's own state, the first step, the guard's first look. */
static stop run_start(session *S)
{
	run *r = &S->r;
	guard *gd = &S->gd;
	const csf_prog *p = r->p;
	csf_ode *ode = S->ode;
	double *y = S->y;
	if (r->cons) { /* the state on the constraints: positions checked, velocities projected */
		int st = csf_run_cons_start(r, y, r->err);
		if (st > 0) return stop_kind_only(STOP_CON_START);
		if (st < 0) return stop_at(r->conflict ? STOP_CON_CONFLICT : STOP_NONFINITE, 0);
	}
	if (S->events) {
		stop s = run_modes(S);
		if (s.kind != STOP_END) return s;
	}
	r->dense = ode && !S->fixed && csf_ode_dense(ode);
	r->own = r->dense; /* (auto: dop853, dense) */
	r->ode = ode;
	if (r->own) { /* the integrator's own state, apart from the rows' */
		if (!(r->yi = malloc(p->ny * sizeof *r->yi))) return stop_kind_only(STOP_NOMEM);
		memcpy(r->yi, y, p->ny * sizeof *y);
	}
	/* adaptive steps start at the scene's own size, not at by (a run till 0 takes no step) */
	if (ode && !S->fixed && p->till > 0) {
		if (csf_ode_first_step(ode, 0, y)) return stop_at(STOP_NONFINITE, r->fail_t);
		r->fail = 0; /* an Euler step of the estimate that failed was tried again shorter */
	}
	if (r->g && !gd->fixed) /* the first look when the run has spent LOOK_EVERY times what one may cost */
		gd->next = LOOK_EVERY * 2.0 * (p->ny < 12 ? p->ny + 1 : 12);
	if (r->g && gd->fixed) { /* the first look, before any step */
		if (csf_run_guard_check(r, ode, 0, y, 0)) return stop_kind_only(STOP_HALTED);
		if (gd->auto_step) S->fixed_h = gd->h;
	}
	return stop_kind_only(STOP_END);
}

/*
 * An advance that did not end at its output time tk (status st, from *t):
 * why, as a stop. The side flags tell a CSF_ODE_STOPPED's cause: contacts
 * not settled, memory, or else a derivative that is not finite.
 */
static stop advance_stop(session *S, int st, double t, double tk)
{
	run *r = &S->r;
	double now = r->own ? r->ti : t;
	stop s = stop_at(STOP_END, now);
	switch (st) {
	case CSF_ODE_HALTED: /* the guard said why */
		s.kind = STOP_HALTED;
		break;
	case CSF_ODE_STOPPED:
		if (!r->unsettled && !r->fail && !r->nomem && !r->conflict && r->trial_unsolved)
			r->unsettled = CSF_SETTLE_FORCES, r->unsettled_t = r->trial_unsolved_t; /* no step was short enough */
		s.kind = r->unsettled ? STOP_UNSETTLED : r->nomem ? STOP_NOMEM : r->conflict ? STOP_CON_CONFLICT : STOP_NONFINITE;
		s.t = r->fail_t;
		break;
	case ADV_TOO_MUCH:
		s.kind = STOP_TOO_MUCH;
		s.t_row = tk - r->p->by;
		s.events = S->events;
		/* stiff only when measured so: the step at the stability limit of the guard's last look */
		s.hs = r->g && S->gd.checks && !S->fixed && !S->au.cur ? csf_run_stable_step(r, S->ode, &S->gd.last) : INFINITY;
		break;
	case ADV_BUDGET:
		s.kind = STOP_BUDGET;
		break;
	case ADV_WHEN_CYCLE:
		s.kind = STOP_WHEN_CYCLE;
		break;
	case ADV_CHATTER:
		s.kind = STOP_CHATTER;
		s.msg = S->msg;
		break;
	case CSF_ODE_FAILED:
		s.kind = STOP_FAILED;
		s.msg = S->msg;
		break;
	}
	return s;
}

/*
 * Advances the state from *t to the output time *tk. A 'stop when'
 * condition between them moves *tk to its instant (r->stopped); *last is
 * set when the last row was the run's last (a signal, or the condition at
 * that row's time).
 */
static stop run_advance(session *S, double *t, double *tk, int *last)
{
	run *r = &S->r;
	csf_ode *ode = S->ode;
	double trow = *t; /* the last row's time */
	int st = r->own      ? csf_run_advance_dense(r, *tk, S->y, S->msg, sizeof S->msg)
	         : S->events ? csf_run_advance_events(r, ode, t, *tk, S->fixed, S->fixed_h, S->y, S->msg, sizeof S->msg)
	         : S->fixed  ? csf_ode_advance_fixed(ode, t, *tk, S->fixed_h, S->y, S->msg, sizeof S->msg)
	                     : csf_run_advance_plain(r, ode, t, *tk, S->y, S->msg, sizeof S->msg);
	/* fixed steps: back on the constraints at each row (the steps between have no error control) */
	if (st == CSF_ODE_OK && S->fixed && !S->events && csf_run_cons_step(r, ode, *t, S->y)) st = CSF_ODE_STOPPED;
	if (st == CSF_ODE_HALTED && csf_signal) {
		*last = 1;
		return stop_kind_only(STOP_SIGNAL);
	}
	if (st == ADV_TERMINAL) { /* a 'stop when' condition: the last row at its instant */
		r->stopped = 1;
		if (r->stop_t <= trow) { /* at the last row's time: that row was the last */
			*last = 1;
			return stop_kind_only(STOP_END);
		}
		*tk = r->stop_t;
		st = CSF_ODE_OK;
	}
	if (st == CSF_ODE_OK) return stop_kind_only(STOP_END);
	csf_run_progress_off(r);
	return advance_stop(S, st, *t, *tk);
}

/* CLOCK_MONOTONIC to the tick of the kernel (a few ms), where there is one: read at every row */
#ifdef CLOCK_MONOTONIC_COARSE
#define ROW_CLOCK CLOCK_MONOTONIC_COARSE
#else
#define ROW_CLOCK CLOCK_MONOTONIC
#endif

/*
 * The row at tk to the CSV output and to the sink. 0, or -1 (errno set) when
 * either failed. The rows reach out within a second (whose buffer may hold
 * 1 MiB: csf_main), so that a slow run can be watched with tail(1).
 */
static int emit_row(session *S, double tk)
{
	const csf_prog *p = S->r.p;
	if (S->rows) {
		if (csf_rowthread_put(S->rows, S->r.m, tk)) return -1;
	} else if (S->out) {
		struct timespec now;
		if (csf_run_write_row(p, S->r.m, tk, S->out)) return -1;
		clock_gettime(ROW_CLOCK, &now);
		if (now.tv_sec != S->flushed) {
			S->flushed = now.tv_sec;
			csf_out_begin();
			int bad = fflush(S->out) != 0;
			csf_out_end();
			if (bad) return -1;
		}
	}
	if (!S->sink) return 0;
	double *v = S->sink->place ? S->sink->place(S->sink->ctx) : S->v;
	if (!v) {
		errno = ENOBUFS;
		return -1;
	}
	v[0] = tk;
	for (uint32_t i = 0; i < p->ncols; i++) v[i + 1] = S->r.m[p->cols[i].slot];
	return S->sink->row(S->sink->ctx, v, (size_t)p->ncols + 1);
}

/* Row k, at tk: the OUT section, its assertions, finiteness, and the CSV row (with --every, only
   that of every K-th and of the last row). */
static stop run_row(session *S, double k, double tk, int *last)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	if (S->events && !S->ode) { /* no state: the conditions depend on t alone, and are looked at on the rows */
		int fired, st = (r->wround = 0, csf_run_whens(r, tk, S->y, &fired));
		if (st) return stop_at(st == ADV_WHEN_CYCLE ? STOP_WHEN_CYCLE : STOP_NONFINITE, tk);
		csf_run_free_modes(r, tk, S->y);
		csf_run_stop_now(r, tk);
	}
	const double *y = S->y;
	if (r->cons) { /* the row on the constraints, to rounding (the integrator's state stays as it is) */
		memcpy(r->cy, S->y, p->ny * sizeof *r->cy);
		if (csf_run_cons_row(r, tk, r->cy)) return stop_at(r->conflict ? STOP_CON_CONFLICT : STOP_NONFINITE, tk);
		y = r->cy;
	}
	r->m[p->tslot] = tk;
	memcpy(r->m + p->ystart, y, p->ny * sizeof(double));
	int a = r->exec(p, &r->x, CSF_SEC_OUT, r->m, r->m + p->ystart, r->m + p->dstart);
	if (a >= 0) {
		stop s = stop_at(STOP_ASSERT, tk);
		s.which = a;
		return s;
	}
	int bad = 0;
	for (uint32_t i = 0; i < p->ny; i++) bad |= !isfinite(r->m[p->ystart + i]);
	for (uint32_t i = 0; i < p->ncols; i++) bad |= !isfinite(r->m[p->cols[i].slot]);
	if (bad) {
		csf_run_progress_off(r);
		csf_vm_exec(p, &r->x, CSF_SEC_OUT, r->m, r->m + p->ystart, r->m + p->dstart); /* every value, for the report */
		return stop_at(STOP_NONFINITE_ROW, tk);
	}
	if ((fmod(k, S->every) == 0 || k == S->kmax || r->stopped) && emit_row(S, tk)) {
		S->werr = errno;
		*last = 1;
		return stop_kind_only(STOP_END);
	}
	r->rows++;
	if (r->stopped) *last = 1;
	return stop_kind_only(STOP_END);
}

/*
 * Checkpoints (--checkpoint, --resume). A checkpoint is taken at a row
 * boundary, after row k at time tk has been written: everything the run
 * keeps from one row to the next (keep_state), which is every array and
 * value that the next rows depend on, so that a run set up as usual and
 * then given that state continues exactly as the run that wrote it did.
 * What the set-up computes again the same way (the program, the method's
 * tables, work vectors) is not saved.
 */
static int keep_state(session *S, csf_keeper *k)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	guard *gd = &S->gd;
	size_t ny = p->ny ? p->ny : 1;
	int bad = csf_keep(k, "m", r->m, (p->nmem ? p->nmem : 1) * sizeof *r->m) |
	          csf_keep(k, "y", S->y, ny * sizeof *S->y);
	/* the run's counts, the last event, the integrator's own time */
	bad |= CSF_KEEP(k, r->fail_t) | CSF_KEEP(k, r->fail) | CSF_KEEP(k, r->nrhs) | CSF_KEEP(k, r->njac) |
	       CSF_KEEP(k, r->nevents) | CSF_KEEP(k, r->last) | CSF_KEEP(k, r->last_src) | CSF_KEEP(k, r->last_oi) |
	       CSF_KEEP(k, r->last_oj) | CSF_KEEP(k, r->crowd_t) | CSF_KEEP(k, r->crowd_n) |
	       CSF_KEEP(k, r->crowd_warned) | CSF_KEEP(k, r->pending) |
	       CSF_KEEP(k, r->last_h) | CSF_KEEP(k, r->dense) | CSF_KEEP(k, r->ti) | CSF_KEEP(k, r->nchoices) |
	       CSF_KEEP(k, r->ncand) | CSF_KEEP(k, r->maxcand) | CSF_KEEP(k, r->stop_t) | CSF_KEEP(k, r->stop_src) |
	       CSF_KEEP(k, r->stopped) | CSF_KEEP(k, r->own) | CSF_KEEP(k, r->rows) | CSF_KEEP(k, r->ng) |
	       CSF_KEEP(k, S->fixed_h);
	if (bad) return -1;
	if (r->own && r->yi) bad |= csf_keep(k, "yi", r->yi, ny * sizeof *r->yi);
	/* the events' guards and derivative at the integrator's point; the contacts and constraints */
	if (S->events && csf_keep_reading(k) && csf_run_room_for_guards(r, r->ng ? r->ng : 1)) return -1;
	if (S->events && r->ga) bad |= csf_keep(k, "ga", r->ga, (r->ng ? r->ng : 1) * sizeof *r->ga);
	if (r->fa) bad |= csf_keep(k, "fa", r->fa, ny * sizeof *r->fa);
	bad |= csf_contacts_keep(r->cs, k) | csf_cons_keep(r->cons, k);
	/* the stability guard */
	bad |= CSF_KEEP(k, gd->t) | CSF_KEEP(k, gd->due) | CSF_KEEP(k, gd->stiff_hits) | CSF_KEEP(k, gd->h) |
	       CSF_KEEP(k, gd->next) | CSF_KEEP(k, gd->next_step) | CSF_KEEP(k, gd->steps) | CSF_KEEP(k, gd->checks) |
	       CSF_KEEP(k, gd->seconds) | CSF_KEEP(k, gd->last) | CSF_KEEP(k, gd->at_max) | CSF_KEEP(k, gd->rho_max) |
	       CSF_KEEP(k, gd->ratio) | CSF_KEEP(k, gd->ratio_rho) | CSF_KEEP(k, gd->hrho) | CSF_KEEP(k, gd->hlim_rho) |
	       CSF_KEEP(k, gd->ratio_exact) | CSF_KEEP(k, gd->have_ratio) | CSF_KEEP(k, gd->auto_ratio) |
	       CSF_KEEP(k, gd->aside) | CSF_KEEP(k, gd->warned) | CSF_KEEP(k, gd->warned_short) | CSF_KEEP(k, gd->nexact) | CSF_KEEP(k, gd->smin) |
	       csf_spectrum_keep(gd->sp, k);
	if (gd->y) bad |= csf_keep(k, "guard.y", gd->y, 4 * ny * sizeof *gd->y);
	/* --method auto's pair, and the integrators */
	bad |= CSF_KEEP(k, S->au.cur) | CSF_KEEP(k, S->au.want) | CSF_KEEP(k, S->au.soft) | CSF_KEEP(k, S->au.n) |
	       CSF_KEEP(k, S->au.at) | csf_ode_keep(S->ode, k, "ode") | csf_ode_keep(S->au.m[1], k, "stiff");
	if (S->au.cur < 0 || S->au.cur > 1 || (S->au.cur && !S->au.m[1])) return -1;
	r->ode = r->au ? S->au.m[S->au.cur] : S->ode;
	return bad ? -1 : 0;
}

/* Writes the checkpoint after row k at tk (a failure is said once, and the run goes on). */
static void checkpoint(session *S, double k, double tk)
{
	char err[600];
	if (S->rows) { /* the row thread's rows written (it starts again after the checkpoint) */
		int e = csf_rowthread_stop(S->rows);
		S->rows = NULL;
		if (e && !S->werr) S->werr = e;
	}
	long long off = csf_keep_offset(S->out); /* where the next row begins */
	csf_keeper *w = csf_keep_write(S->ck, err, sizeof err);
	if (w) {
		double row[2] = { k, tk };
		csf_keep_header(w, &S->hash, S->ck_opts, sizeof S->ck_opts, &off);
		csf_keep(w, "row", row, sizeof row);
		keep_state(S, w);
		if (csf_keep_commit(w, S->ck, err, sizeof err)) w = NULL;
	}
	if (!w && !S->ck_warned) {
		csf_run_progress_off(&S->r);
		fprintf(S->r.err, "warning: %s (the run goes on; the last checkpoint written stays as it was)\n", err);
		S->ck_warned = 1;
	}
	if (S->out && !S->werr) S->rows = csf_rowthread_start(S->r.p, S->out);
	clock_gettime(ROW_CLOCK, &S->ck_last);
}

/* Is a checkpoint due (the interval past since the last)? */
static int checkpoint_due(const session *S)
{
	struct timespec now;
	if (!S->ck) return 0;
	if (S->ck_every <= 0) return 1;
	clock_gettime(ROW_CLOCK, &now);
	return csf_run_seconds(S->ck_last, now) >= S->ck_every;
}

/*
 * --resume: the checkpoint read and checked against this run (the
 * bytecode, the options); its row and output position. 0, or -1 with the
 * reason in S->ck_err.
 */
static int resume_open(session *S, const char *path)
{
	char err[400];
	double row[2];
	if (!(S->resume = csf_keep_read(path, err, sizeof err))) {
		snprintf(S->ck_err, sizeof S->ck_err, "--resume: %s", err);
		return -1;
	}
	if (csf_keep_check(S->resume, path, S->hash, S->ck_opts, sizeof S->ck_opts, &S->ck_off, S->ck_err,
	                   sizeof S->ck_err))
		return -1;
	if (csf_keep(S->resume, "row", row, sizeof row)) {
		snprintf(S->ck_err, sizeof S->ck_err, "--resume: %s does not fit this run: %s", path, csf_keep_why(S->resume));
		return -1;
	}
	S->k0 = row[0] + 1;
	S->trow = row[1];
	return 0;
}

/* --resume: the run, set up as usual, takes the checkpoint's state. */
static stop resume_state(session *S, const char *path)
{
	stop s = stop_kind_only(STOP_END);
	/* the output goes on where the checkpoint's rows ended: a file is cut back to that length,
	   dropping the rows the killed run wrote after it; into a pipe, the rows after it are written */
	if (keep_state(S, S->resume) || csf_keep_output(S->out, S->ck_off, path, S->ck_err, sizeof S->ck_err)) {
		if (!S->ck_err[0])
			snprintf(S->ck_err, sizeof S->ck_err, "--resume: %s does not fit this run: %s", path,
			         csf_keep_why(S->resume)[0] ? csf_keep_why(S->resume) : "its state is damaged");
		s = stop_kind_only(STOP_SETUP);
		s.msg = S->ck_err;
	}
	csf_keep_free(S->resume);
	S->resume = NULL;
	return s;
}

/* The rows t_k = k*by, k = 0 .. kmax, each after the advance to it. */
static stop run_rows(session *S)
{
	run *r = &S->r;
	const csf_prog *p = r->p;
	double t = S->trow;
	int last = 0;
	for (double k = S->k0; k <= S->kmax; k++) {
		double tk = k * p->by;
		/* a checkpoint after the last row: when due, and when a signal ends the run (the signal read
		   once: one that came between two reads ended the run with no checkpoint, 1 kill in 60 on a
		   busy machine, tests/longrun/check.sh) */
		int sig = csf_signal != 0;
		if (k > S->k0 && S->ck && (sig || checkpoint_due(S))) checkpoint(S, k - 1, t);
		if (sig) return stop_kind_only(STOP_SIGNAL); /* after the last whole row */
		if (r->prog) csf_run_progress(r, t);
		if (S->ode && tk > t) {
			stop s = run_advance(S, &t, &tk, &last);
			if (s.kind != STOP_END || last) return s;
		}
		t = tk;
		stop s = run_row(S, k, tk, &last);
		if (s.kind != STOP_END || last) return s;
	}
	return stop_kind_only(STOP_END);
}

/* --stats: the method, its steps and evaluations, the events and contacts. */
static void stats_run(const session *S, const csf_opts *o, unsigned long steps, unsigned long rejected, FILE *err)
{
	const run *r = &S->r;
	char cand[320] = "";
	if (r->cs) {
		unsigned long solved, recalled, searches, unfound;
		csf_contacts_solves(r->cs, &solved, &recalled);
		csf_contacts_searches(r->cs, &searches, &unfound);
		int n = snprintf(cand, sizeof cand,
		                 ", %.1f contact pairs watched (candidates) on average, at most %lu, %lu contact systems solved "
		                 "(%lu of them recalled)",
		                 r->nchoices ? (double)r->ncand / (double)r->nchoices : 0.0, r->maxcand, solved, recalled);
		if (searches && n > 0 && (size_t)n < sizeof cand)
			snprintf(cand + n, sizeof cand - (size_t)n, ", %lu search%s for the modes of a cluster with friction (%lu found none)",
			         searches, searches > 1 ? "es" : "", unfound);
	}
	char fired[48] = "";
	if (r->p->nwhens) snprintf(fired, sizeof fired, " (%lu when blocks fired)", r->nfired);
	char name[64];
	snprintf(name, sizeof name, "%s%s%s%s", r->au ? "auto (" : "", S->ode ? csf_ode_method(S->ode) : "none",
	         r->au && S->au.n ? " and " AUTO_STIFF : "", r->au ? ")" : "");
	fprintf(err,
	        "stats: method %s%s, %lu steps (%lu rejected), %lu right-hand side and %lu Jacobian evaluations, "
	        "%lu events%s%s, %.6f s\n",
	        name, S->fixed ? " (fixed steps)" : "", steps, rejected, r->nrhs, r->njac, r->nevents, fired, cand,
	        o->run_seconds);
}

/* --stats: --method auto's switches, alternately to the implicit method and back. */
static void stats_auto(const session *S, FILE *err)
{
	const autom *au = &S->au;
	fprintf(err, "stats: auto: %lu switch%s:", au->n, au->n > 1 ? "es" : "");
	for (unsigned long i = 0; i < au->n && i < AUTO_SHOWN; i++)
		fprintf(err, "%s at t=%.6g to %s", i ? "," : "", au->at[i], i % 2 ? csf_ode_method(S->ode) : AUTO_STIFF);
	fprintf(err, "%s%s\n", au->n > AUTO_SHOWN ? ", ..." : "",
	        au->failed ? " (" AUTO_STIFF "'s step collapsed: dop853 from there on)" : "");
}

/* --stats: what the stability guard saw. */
static void stats_guard(const session *S, FILE *err)
{
	const guard *gd = &S->gd;
	char rb[64] = "", hb[160] = "";
	if (gd->have_ratio && gd->ratio > 0) {
		char x[32];
		csf_run_fmt_ratio(x, gd->ratio);
		snprintf(rb, sizeof rb, ", stiffness ratio %s%s", gd->ratio_exact ? "" : "about ", x);
	}
	if (S->fixed && gd->hrho > 0)
		snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g against %s's limit %.3g there (largest stable step %.3g s)",
		         gd->h, gd->h * gd->rho_max, csf_ode_method(S->ode), gd->hlim_rho, gd->h / gd->hrho);
	else if (S->fixed)
		snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g, %s not limited there", gd->h, gd->h * gd->rho_max,
		         csf_ode_method(S->ode));
	fprintf(err,
	        "stats: stability: rho %.3g 1/s (fastest time scale %.3g s, dominant eigenvalues %s)%s%s; %lu looks, "
	        "%lu Jacobian-vector products, %.6f s\n",
	        gd->rho_max, gd->rho_max > 0 ? 1 / gd->rho_max : INFINITY, csf_run_eig_kind(&gd->at_max), rb, hb, gd->checks,
	        csf_spectrum_products(gd->sp), gd->seconds);
	if (gd->floor_n) {
		char tb[32], name[200];
		csf_fmt_double(tb, gd->floor_t);
		csf_run_state_name(S->r.p, gd->floor_i, name, sizeof name);
		fprintf(err,
		        "stats: rounding: at t=%s the absolute tolerance of %lu values raised to the rounding of their "
		        "derivatives over the scene's time scale (%s, whose error held the steps: %.3g)\n",
		        tb, gd->floor_n, name[0] ? name : "?", gd->floor_atol);
	}
}

/* The run's counts into o (run_steps, run_rhs, run_seconds), and --stats's lines. */
static void run_stats(const session *S, csf_opts *o, FILE *err)
{
	const run *r = &S->r;
	const csf_prog *p = r->p;
	struct timespec t1;
	clock_gettime(CLOCK_MONOTONIC, &t1);
	unsigned long steps = 0, rejected = 0;
	if (S->ode) csf_ode_stats(S->ode, &steps, &rejected);
	if (S->au.m[1]) {
		unsigned long s1, r1;
		csf_ode_stats(S->au.m[1], &s1, &r1);
		steps += s1, rejected += r1;
	}
	o->run_steps = steps;
	o->run_rhs = r->nrhs;
	o->run_seconds = csf_run_seconds(S->t0, t1);
	o->run_rejected = rejected, o->run_jac = r->njac, o->run_events = r->nevents, o->run_rows = r->rows;
	if (o->stats) stats_run(S, o, steps, rejected, err);
	if (o->stats && S->au.n) stats_auto(S, err);
	if (o->stats && r->g && S->gd.checks) stats_guard(S, err);
	if (o->stats && r->stopped) {
		char tb[32];
		csf_fmt_double(tb, r->stop_t);
		const csf_src *s = &p->srcs[r->stop_src];
		fprintf(err, "stats: stopped at t=%s by %s:%lu: stop when %s\n", tb, csf_str(p, p->files[s->file]),
		        (unsigned long)s->line, csf_str(p, s->text));
	}
	if (o->stats && r->g && !S->gd.checks)
		fprintf(err,
		        "stats: stability: not looked at (the run ended after %lu evaluations, before its first look, due "
		        "after %.0f)\n",
		        r->nrhs, S->gd.next);
}

/*
 * --rows-at-events: p seen with one more column, "event", at a slot past
 * p's memory (q's last, 0 at the start): *q shares p's tables but the
 * memory image, the strings and the columns, its own (event_view_free).
 * 0, or -1 when memory runs out.
 */
static int event_view(const csf_prog *p, csf_prog *q)
{
	static const char name[] = "event";
	*q = *p;
	q->mem0 = malloc(((size_t)p->nmem + 1) * sizeof *q->mem0);
	q->strs = malloc((size_t)p->nstrs + sizeof name);
	q->cols = malloc(((size_t)p->ncols + 1) * sizeof *q->cols);
	if (!q->mem0 || !q->strs || !q->cols) return -1;
	memcpy(q->mem0, p->mem0, p->nmem * sizeof *q->mem0);
	q->mem0[q->nmem++] = 0;
	memcpy(q->strs, p->strs, p->nstrs);
	memcpy(q->strs + p->nstrs, name, sizeof name);
	q->nstrs += sizeof name;
	memcpy(q->cols, p->cols, p->ncols * sizeof *q->cols);
	q->cols[q->ncols++] = (csf_col){ p->nstrs, p->nmem };
	return 0;
}

static void event_view_free(csf_prog *q)
{
	free(q->mem0);
	free(q->strs);
	free(q->cols);
}

/*
 * --rows-at-events (run.event_row): the row of state y at the event at t,
 * its column event set to mark (-1: just before the event, 1: just after),
 * whatever --every says. A write error is the run's, as a row's.
 */
static void event_row(run *r, double t, const double *y, double mark)
{
	session *S = r->event_ctx;
	const csf_prog *p = r->p;
	double *m = r->m;
	m[p->tslot] = t;
	memcpy(m + p->ystart, y, p->ny * sizeof *y);
	(void)r->exec(p, &r->x, CSF_SEC_OUT, m, m + p->ystart, m + p->dstart); /* assertions: at the output times */
	m[p->cols[p->ncols - 1].slot] = mark;
	if (emit_row(S, t) && !S->werr) S->werr = errno;
	m[p->cols[p->ncols - 1].slot] = 0;
}

/* Frees what the run allocated. */
static void run_free(session *S)
{
	run *r = &S->r;
	csf_spectrum_free(S->gd.sp);
	free(S->gd.y);
	csf_ode_free(S->ode);
	csf_ode_free(S->au.m[1]);
	free(S->vpair);
	csf_contacts_free(r->cs);
	csf_cons_free(r->cons);
	csf_pool_free(r->x.pool);
	csf_blocks_free(r->x.blocks);
	free(r->cw);
	free(r->ga);
	free(r->gb);
	free(r->gs);
	free(r->gh);
	free(r->gt);
	free(r->gl);
	free(r->gp);
	free(r->gx);
	free(r->gk);
	free(r->est);
	free(r->order);
	free(S->work);
	free(S->y);
	free(S->r.row_y);
	free(S->v);
	free(S->vec);
	free(r->yi);
	free(r->m);
}

int csf_run_sink(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, const csf_sink *sink, FILE *err)
{
	csf_prog view;
	int ev_rows = o->rows_at_events && !sink; /* (a sink's rows are as wide as the program's columns) */
	if (ev_rows && event_view(p, &view)) {
		event_view_free(&view);
		fprintf(err, "error: out of memory\n");
		return 2;
	}
	if (ev_rows) p = &view;
	session S = { .r = { .p = p, .exec = exec, .max_rhs = o->max_rhs }, .out = out, .sink = sink, .init = o->init,
	              .every = o->every > 1 ? (double)o->every : 1 };
	S.wc.r = S.wc_stiff.r = &S.r;
	if (ev_rows) S.r.event_row = event_row, S.r.event_ctx = &S;
	/* --method auto (the default, but for fixed steps and large scenes: dop853) is dop853 with
	   AUTO_STIFF beside it */
	S.method = o->method && strcmp(o->method, "auto") != 0 ? o->method : NULL;
	S.autom_on = !S.method && !o->fixed && p->ny <= AUTO_MAX_N;
	S.events = p->nevents || p->ncrules;
	for (uint32_t k = 0; k < p->ncons; k++) S.events |= p->cons[k].kind != CSF_CON_EQ;
	clock_gettime(CLOCK_MONOTONIC, &S.t0);
	S.r.err = err;
	S.r.start = S.r.drawn = S.t0;
	S.r.prog = o->progress == CSF_PROGRESS_ON || (o->progress == CSF_PROGRESS_AUTO && isatty(fileno(err)));

	/* --checkpoint (--resume alone goes on writing to its file), --resume */
	S.ck = o->checkpoint ? o->checkpoint : o->resume;
	S.ck_every = o->checkpoint_every_set ? o->checkpoint_every : CSF_CHECKPOINT_EVERY;
	S.ck_last = S.t0;
	S.r.row_end = S.ck != NULL;
	S.hash = o->hash;
	csf_keep_options(o, S.ck_opts, sizeof S.ck_opts);
	stop s = stop_kind_only(STOP_END);
	if (o->resume && resume_open(&S, o->resume)) {
		s = stop_kind_only(STOP_SETUP);
		s.msg = S.ck_err;
	}
	if (s.kind == STOP_END) s = run_alloc(&S);
	S.r.x.pool = csf_pool_new(p, o->threads); /* NULL: one thread (the same result) */
	S.r.x.blocks = csf_blocks_new(p);         /* NULL: no loop run a block at a time (the same result) */
	if (s.kind == STOP_END) s = run_method(&S, o);
	if (s.kind == STOP_END && S.ck && S.ode && csf_ode_history(S.ode)) {
		snprintf(S.ck_err, sizeof S.ck_err,
		         "--checkpoint: %s keeps a history of past steps inside GSL that a checkpoint cannot hold, and a "
		         "resumed run would not repeat the rows; use a one-step method (auto, dop853, rk8pd, bsimp, ...)",
		         csf_ode_method(S.ode));
		s = stop_kind_only(STOP_SETUP);
		s.msg = S.ck_err;
	}
	if (s.kind == STOP_END) {
		if (out && !o->resume) csf_run_write_header(p, out);
		if (out) S.rows = csf_rowthread_start(p, out);
		s = run_guard(&S, o);
	}
	if (s.kind == STOP_END) s = run_start(&S);
	if (s.kind == STOP_END && S.resume) s = resume_state(&S, o->resume);
	if (s.kind == STOP_END) s = run_rows(&S);
	csf_keep_free(S.resume);
	if (S.rows) { /* every row handed over written, before the run's last words */
		int e = csf_rowthread_stop(S.rows);
		if (e && !S.werr) S.werr = e;
	}
	int status = csf_run_report_stop(&S.r, &s, o->fixed, err);
	run_stats(&S, o, err);
	run_free(&S);
	if (ev_rows) event_view_free(&view);
	return csf_run_finish(out, err, status, S.werr);
}

int csf_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, FILE *err)
{
	return csf_run_sink(p, exec, o, out, NULL, err);
}
