/*
 * guard.c - the stability guard: the dominant eigenvalues of the Jacobian,
 * the largest stable step, the halt of a fixed step past it, the stiffness
 * warning, and --method auto's switches; step_watch calls it after a step.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"

/*
 * The stability guard. A fixed step is stable for a scene only while h
 * lambda stays in the method's stability region for its fastest modes
 * (csf_ode_stable_step); an explicit adaptive method on a stiff scene is
 * held by that region to steps far shorter than its accuracy needs. The
 * guard estimates the dominant eigenvalues of df/dy (spectrum.c) from
 * Jacobian-vector products: the JAC section run with the tangent of the
 * state set to v, or with contacts (whose forces have no tangent code) a
 * difference of the RHS along v. It looks at the start, after every
 * event, and then again as often as keeps its cost near 2.5 % of the
 * run's evaluations, more often as a fixed step nears the limit. It
 * halts a fixed step past the limit (exit 1, before the step's rows),
 * shortens verlet's own step, warns of stiffness, and feeds --stats.
 * Its decisions depend on counts of evaluations, never on the clock, so
 * that csfvm and a generated program halt at the same step.
 */

/* J v in the coordinates y_i / yscale_i (J's eigenvalues are the same in any). */
static int jvp(void *ctx, const double *v, double *jv)
{
	run *r = ctx;
	guard *g = r->g;
	const csf_prog *p = r->p;
	uint32_t n = p->ny;
	if (g->exact) {
		double *m = r->m, *tan = m + p->jtan;
		m[p->tslot] = g->t;
		memcpy(m + p->ystart, g->y, n * sizeof *m);
		for (uint32_t i = 0; i < n; i++) tan[p->ystart + i] = v[i] * p->yscale[i];
		tan[p->tslot] = 0;
		r->exec(p, &r->x, CSF_SEC_JAC, m, m + p->ystart, m + p->dstart);
		for (uint32_t i = 0; i < n; i++) jv[i] = tan[p->dstart + i] / p->yscale[i];
		g->nexact++;
		return 0;
	}
	/* forward difference: v has unit length, the step sqrt(eps) of the state's size */
	double size = 0;
	for (uint32_t i = 0; i < n; i++) size += (g->y[i] / p->yscale[i]) * (g->y[i] / p->yscale[i]);
	double e = sqrt(DBL_EPSILON) * (1 + sqrt(size));
	for (uint32_t i = 0; i < n; i++) g->yd[i] = g->y[i] + e * v[i] * p->yscale[i];
	if (csf_run_rhs(g->t, g->yd, g->fd, r)) return 1;
	for (uint32_t i = 0; i < n; i++) jv[i] = (g->fd[i] - g->f0[i]) / (e * p->yscale[i]);
	return 0;
}

/* The run's evaluations so far, the guard's own included: an RHS counts 1, a product by the JAC section 2. */
static double guard_evals(const run *r) { return (double)r->nrhs + 2.0 * (double)r->g->nexact - r->g->aside; }

/*
 * The largest stable step for the dominant eigenvalues e. verlet's come
 * in pairs +-lambda; a real pair is a mode that grows by itself, which
 * limits no step, but a slower oscillation beside it does: the most
 * negative eigenvalue of J^2 gives it.
 */
double csf_run_stable_step(run *r, csf_ode *ode, const csf_eigs *e)
{
	guard *g = r->g;
	double h = INFINITY;
	for (int i = 0; i < e->n; i++)
		if (i == 0 || e->im[0] == 0 || e->im[i] != -e->im[0]) /* a complex pair's second: the first's conjugate */
			h = fmin(h, csf_ode_stable_step(ode, g->fixed, e->re[i], e->im[i], g->span));
	if (csf_ode_fixed_only(ode) && h == INFINITY && e->rho > 0) {
		double mu;
		if (csf_spectrum_lowest_square(g->sp, jvp, r, e->rho * e->rho, &mu) == 0 && mu < 0)
			h = csf_ode_stable_step(ode, g->fixed, 0, sqrt(-mu), g->span);
	}
	return h;
}

/* How the dominant eigenvalues lie: on the imaginary axis, the real axis, or neither. */
const char *csf_run_eig_kind(const csf_eigs *e)
{
	int re = 1, im = 1;
	for (int i = 0; i < e->n; i++) {
		re &= fabs(e->im[i]) <= 1e-3 * e->rho;
		im &= fabs(e->re[i]) <= 1e-3 * e->rho;
	}
	return e->rho == 0 ? "zero" : im ? "imaginary" : re ? "real" : "complex";
}

/* The stiffness ratio at the state looked at, kept when the largest yet. 0, or 1 if it cannot be computed. */
static int guard_ratio(run *r, double rho)
{
	guard *g = r->g;
	double ratio;
	/* zero: below sqrt(eps) of the largest, 10 times over, for exact products; differences,
	   good to some sqrt(eps), leave the fourth root */
	int exact, st = csf_spectrum_ratio(g->sp, jvp, r, g->exact ? 1.5e-7 : 1e-3, &ratio, &exact);
	r->fail = 0;
	g->ratio_rho = rho;
	if (st) return 1;
	if (!g->have_ratio || ratio > g->ratio) g->ratio = ratio, g->ratio_exact = exact, g->have_ratio = 1;
	if (ratio > g->auto_ratio) g->auto_ratio = ratio;
	return 0;
}

/*
 * --method auto: is the stiffness ratio at least min? Measured at the
 * first look that asks (and kept, the largest, by later ones), never taken
 * from the looks --stats adds, so that --stats does not steer the run.
 */
static int auto_ratio_at_least(run *r, double rho, double min)
{
	guard *g = r->g;
	if (!(g->auto_ratio > 0)) guard_ratio(r, rho);
	return g->auto_ratio >= min;
}

/*
 * Error: a fixed step hc at or beyond the largest stable step hs for the
 * eigenvalues e, at t after a step of h (0: before the first); what to use.
 */
static void refuse_step(run *r, csf_ode *ode, double t, double h, double hc, double hs, const csf_eigs *e)
{
	guard *g = r->g;
	const csf_prog *p = r->p;
	csf_run_progress_off(r);
	char hb[32], tb[32], why[96] = "", tolb[64] = "";
	snprintf(hb, sizeof hb, "%.3g", hc);
	csf_fmt_double(tb, t);
	if (g->user_step > 0 && fabs(g->user_step - hc) > 1e-12 * hc)
		snprintf(why, sizeof why, " (from --step %g)", g->user_step);
	if (g->auto_step && h == 0) {
		double tau = e->rho > 0 ? fmin(p->by, 1 / e->rho) : p->by;
		snprintf(why, sizeof why, " (verlet's step for --tol %g)", g->vfrac * g->vfrac * 1e-4);
		snprintf(tolb, sizeof tolb, ", --tol %g", csf_run_round_down(0.81e-4 * (hs / tau) * (hs / tau)));
	}
	fprintf(g->err,
	        "error: %s%s%sstep %s s%s is %s the stability limit of %s for this scene (fastest time scale "
	        "%.3g s; largest stable step %.3g s): use --step %g%s or an adaptive method\n",
	        h > 0 ? "at t=" : "", h > 0 ? tb : "", h > 0 ? ", " : "", hb, why, hc < hs ? "at" : "beyond",
	        csf_ode_method(ode), 1 / e->rho,
	        hs, csf_run_round_down(0.9 * hs), tolb);
}

/* Warning: an explicit method's steps of h held by its stability at t, for the eigenvalues e. */
static void warn_stiff(run *r, csf_ode *ode, double t, double h, const csf_eigs *e)
{
	guard *g = r->g;
	char tb[32], rb[64] = "";
	csf_fmt_double(tb, t);
	if (g->have_ratio && g->ratio > 0) {
		char x[32];
		csf_run_fmt_ratio(x, g->ratio);
		snprintf(rb, sizeof rb, ", stiffness ratio %s%s", g->ratio_exact ? "" : "about ", x);
	}
	char more[32];
	csf_run_fmt_ratio(more, (r->tend - t) / h);
	csf_run_progress_off(r);
	fprintf(g->err,
	        "warning: at t=%s, after %lu steps, the problem looks stiff: the explicit method %s is held to steps "
	        "of %.3g s by its stability (fastest time scale %.3g s%s) and needs some %s more; an implicit method "
	        "is not: try --method msbdf or --method bsimp\n",
	        tb, g->steps, csf_ode_method(ode), h, 1 / e->rho, rb, more);
}

/*
 * Warning: an adaptive method's steps of h at t, more than SHORT_STEPS times
 * shorter than the fastest time scale of the scene's dynamics (1/rho) and
 * than the caps on a step (the output interval by, --hmax), with
 * more than SHORT_LEFT of them to go (and SHORT_LEFT / 100 taken, so that
 * the first steps' growth is over): the error control, not stability,
 * holds them. Either the scene changes faster than its own dynamics (a fast
 * forcing), or the tolerance asks for more than rounding allows: a value
 * held near 0, relative to its size, while large forces cancel on it (the
 * masses of a chain started at rest).
 */
enum { SHORT_STEPS = 1000, SHORT_LEFT = 100000 };

/* The name of state component i (a property's, or a global's, with its component) into buf, or "". */
void csf_run_state_name(const csf_prog *p, long i, char *buf, size_t len)
{
	buf[0] = '\0';
	if (i < 0) return;
	uint64_t slot = (uint64_t)p->ystart + (uint64_t)i;
	const char *obj = NULL, *name = NULL;
	uint32_t at = 0, width = 0;
	for (uint32_t k = 0; k < p->nprops && !name; k++)
		if (slot >= p->props[k].slot && slot < (uint64_t)p->props[k].slot + p->props[k].width)
			obj = csf_str(p, p->objects[p->props[k].object]), name = csf_str(p, p->props[k].name),
			at = p->props[k].slot, width = p->props[k].width;
	for (uint32_t k = 0; k < p->nglobals && !name; k++)
		if (slot >= p->globals[k].slot && slot < (uint64_t)p->globals[k].slot + p->globals[k].width)
			name = csf_str(p, p->globals[k].name), at = p->globals[k].slot, width = p->globals[k].width;
	if (!name) return;
	const char *comp = width == 3 ? (const char *[]){ ".x", ".y", ".z" }[slot - at] : "";
	snprintf(buf, len, "%s%s%s%s", obj ? obj : "", obj ? "." : "", name, comp);
}

/* " (the error of NAME holds them)", NAME the state variable whose error limited the last step the
   control sized (csf_ode_limit), else "". */
static void limit_words(const csf_prog *p, const csf_ode *ode, char *buf, size_t len)
{
	char name[200];
	csf_run_state_name(p, csf_ode_limit(ode), name, sizeof name);
	if (name[0]) snprintf(buf, len, " (the error of %s holds them)", name);
	else buf[0] = '\0';
}

/*
 * Before the short-step warning: is it rounding that holds the steps? A
 * value near 0 on which large forces cancel (a velocity in a chain at rest
 * far from the origin) has a derivative whose rounding no step can make
 * smaller: its error over a step of h is some h times that rounding,
 * against a bound of tol (scale + |y|) that its small size makes tiny, so
 * the control shortens the steps without end. The rounding of each
 * derivative is measured as how far it moves when every component of the
 * state moves by one unit in the last place (f at y, and at y so moved).
 * Each component whose error bound that rounding, over the step h now
 * taken, fills to 1 % or more gets the absolute tolerance ROUND_MARGIN
 * times the rounding over the step the scene's own dynamics allow (the
 * least of its fastest time scale and the caps on a step): the bound the
 * rounding itself sets, which steps of that length can meet. At most
 * ROUND_LOOKS looks do it; when none raises anything (a true fast forcing,
 * whose derivative does not move with the state), the warning comes.
 * --stats says how many were raised, and which held the steps.
 */
enum { ROUND_LOOKS = 2 };
#define ROUND_MARGIN 10.0

/* A state property by its name, for sorting (ties by its index, for a stable order). */
typedef struct named { const char *name; uint32_t k; } named;
static int by_name(const void *a, const void *b)
{
	const named *x = a, *y = b;
	int c = strcmp(x->name, y->name);
	return c ? c : (x->k > y->k) - (x->k < y->k);
}

/*
 * want[i] (an absolute tolerance, 0: none) raised to the largest of its
 * group: the same component of the same property in every object, as the
 * program's scales are set per property (a mass whose neighbours' rounding
 * happened to cancel in the measurement is as near 0 as they are).
 */
static void group_wants(const csf_prog *p, double *want)
{
	named *v = malloc((p->nprops ? p->nprops : 1) * sizeof *v);
	uint32_t n = 0;
	if (!v) return; /* each keeps its own */
	for (uint32_t k = 0; k < p->nprops; k++)
		if (p->props[k].slot >= p->ystart && p->props[k].slot < p->ystart + p->ny)
			v[n++] = (named){ csf_str(p, p->props[k].name), k };
	qsort(v, n, sizeof *v, by_name);
	for (uint32_t a = 0, b; a < n; a = b) {
		for (b = a + 1; b < n && strcmp(v[b].name, v[a].name) == 0; b++) continue;
		for (uint32_t c = 0; c < p->props[v[a].k].width; c++) {
			double m = 0;
			for (uint32_t k = a; k < b; k++)
				if (c < p->props[v[k].k].width) m = fmax(m, want[p->props[v[k].k].slot - p->ystart + c]);
			for (uint32_t k = a; k < b && m > 0; k++)
				if (c < p->props[v[k].k].width) want[p->props[v[k].k].slot - p->ystart + c] = m;
		}
	}
	free(v);
}

static int rounding_floors(run *r, csf_ode *ode, double t, const double *y, double h, const csf_eigs *e)
{
	guard *g = r->g;
	const csf_prog *p = r->p;
	uint32_t n = p->ny;
	if (g->floor_looks >= ROUND_LOOKS) return 0;
	g->floor_looks++;
	long lim = csf_ode_limit(ode);
	double *want = calloc(n ? n : 1, sizeof *want);
	if (!want || csf_run_rhs(t, y, g->f0, r)) {
		free(want);
		return r->fail = 0;
	}
	/* the rounding of each derivative: the most it moves over two patterns of signs (one may cancel
	   on a component, as equal moves of two neighbours do on the spring between them) */
	for (uint32_t pat = 0; pat < 2; pat++) {
		for (uint32_t i = 0; i < n; i++) {
			double a = fabs(y[i]), ulp = nextafter(a, INFINITY) - a;
			uint32_t bit = pat ? (i * 2654435761u) >> 16 & 1 : i & 1;
			g->yd[i] = y[i] + (bit ? ulp : -ulp);
		}
		if (csf_run_rhs(t, g->yd, g->fd, r)) {
			free(want);
			return r->fail = 0;
		}
		for (uint32_t i = 0; i < n; i++) want[i] = fmax(want[i], fabs(g->fd[i] - g->f0[i]));
	}
	double tol = csf_ode_tol(ode), hr = fmin(g->hcap, 1 / e->rho);
	for (uint32_t i = 0; i < n; i++) {
		double noise = want[i], bound = csf_ode_abs_tol(ode, i) + tol * fabs(y[i]);
		want[i] = h * noise >= 0.01 * bound ? ROUND_MARGIN * hr * noise : 0;
	}
	group_wants(p, want);
	unsigned long raised = 0;
	for (uint32_t i = 0; i < n; i++) raised += (unsigned long)csf_ode_raise_abs_tol(ode, i, want[i]);
	free(want);
	if (raised && !g->floor_n)
		g->floor_t = t, g->floor_i = lim, g->floor_atol = lim >= 0 ? csf_ode_abs_tol(ode, (size_t)lim) : 0;
	g->floor_n += raised;
	return raised > 0;
}

static void warn_short(run *r, csf_ode *ode, double t, double h, const csf_eigs *e)
{
	char tb[32], more[32], times[32], held[256];
	csf_fmt_double(tb, t);
	limit_words(r->p, ode, held, sizeof held);
	csf_run_fmt_ratio(more, (r->tend - t) / h);
	/* a spectral radius whose time scale is longer than the whole run is no time scale of the scene
	   (rounding in a scene that J leaves all but still, 3e-19 1/s in a pile of balls in flight):
	   the steps are compared with the run */
	int none = !(e->rho * r->p->till > 1);
	double scale = none ? r->p->till : 1 / e->rho;
	csf_run_fmt_ratio(times, scale / h);
	csf_run_progress_off(r);
	fprintf(r->g->err,
	        "warning: at t=%s, after %lu steps, the error control holds %s to steps of %.3g s%s, %s times shorter "
	        "than %s (%.3g s), and some %s more are to go: either the scene "
	        "changes faster than that (a fast forcing), or the tolerance asks for more than the rounding of the "
	        "values allows (a velocity near 0 while large forces cancel on it: the masses of a chain started at "
	        "rest); --atol bounds the error of such values absolutely (--atol 1e-9), a larger --tol loosens "
	        "every value\n",
	        tb, r->g->steps, csf_ode_method(ode), h, held, times,
	        none ? "the run, as the scene's dynamics have no shorter time scale" : "the fastest time scale of the scene",
	        scale, more);
	r->g->warned_short = 1;
}

/*
 * Looks at the scene at (t, y) after a step of h (0 at the start).
 * Returns 1 after writing why the run must halt, else 0. A state where an
 * estimate cannot be made (a derivative not finite nearby) is passed
 * over: the integration reports what is wrong there.
 */
int csf_run_guard_check(run *r, csf_ode *ode, double t, const double *y, double h)
{
	guard *g = r->g;
	const csf_prog *p = r->p;
	struct timespec c0, c1;
	clock_gettime(CLOCK_MONOTONIC, &c0);
	double before = guard_evals(r);
	/* its evaluations at states near y (its products) are not the run's: contact forces that do
	   not hold there (a ball wedged between two others, moved off their plane by 1e-8 m) do not
	   stop the run, which evaluates its own states afresh */
	int unsolved = r->cs ? csf_contacts_unsolved(r->cs) : 0;
	/* a look for a fixed step is as long as it needs; another spends at most its share of the run */
	int maxprod = g->fixed ? 1000 : (int)fmin(1000, fmax(3, before / LOOK_EVERY / 2));
	int halt = 0, looked = 0;
	g->due = 0;
	g->checks++;
	g->t = t;
	memcpy(g->y, y, p->ny * sizeof *y);
	csf_eigs e;
	memset(&e, 0, sizeof e); /* its padding and unused lanes too: g->last goes into a checkpoint's bytes */
	if ((!g->exact && csf_run_rhs(t, y, g->f0, r)) || csf_spectrum_dominant(g->sp, jvp, r, maxprod, &e)) {
		r->fail = 0;
		goto out;
	}
	g->last = e;
	looked = 1;
	if (e.rho > g->rho_max) g->rho_max = e.rho, g->at_max = e;
	if (g->stats && (!g->have_ratio || e.rho > 1.5 * g->ratio_rho)) {
		double b = guard_evals(r), keep = g->auto_ratio;
		guard_ratio(r, e.rho);
		g->aside += guard_evals(r) - b, g->auto_ratio = keep; /* the schedule of looks as without --stats */
	}
	if (!g->fixed && !g->detect_stiff) goto out;
	autom *au = r->au;
	if (au && au->cur) {
		/* implicit: back to dop853 when its own step is within dop853's stable step (not when h rho
		   is 40 or more, past the region of every explicit method, without the search for it) */
		double hn = csf_ode_next_step(ode);
		au->soft = hn * e.rho < 40 && hn < csf_run_stable_step(r, au->m[0], &e) ? au->soft + 1 : 0;
		r->fail = 0;
		if (au->soft >= 2) au->want = 1;
		goto out;
	}
	double hs = csf_run_stable_step(r, au ? au->m[0] : ode, &e); /* auto: dop853's */
	r->fail = 0;
	if (g->fixed) {
		double hc = g->h; /* the step to judge */
		if (g->auto_step && h == 0) {
			/* verlet's own step: the fraction sqrt(tol / 1e-4) of the smaller of by and the fastest
			   time scale (a step the tolerance asks for, judged as asked, before a row's interval
			   is cut into equal steps) */
			double tau = e.rho > 0 ? fmin(p->by, 1 / e.rho) : p->by;
			hc = g->vfrac * tau;
			g->h = p->by / ceil(p->by / fmin(hc, p->by) * (1 - 1e-12));
		}
		if (hs < INFINITY && g->h / hs > g->hrho) g->hrho = g->h / hs, g->hlim_rho = hs * e.rho;
		if (!(g->smin > 0) && e.rho > 0) { /* the least h |lambda| limit on the two axes, once */
			double sr = csf_ode_stable_step(ode, 1, -e.rho, 0, g->span), si = csf_ode_stable_step(ode, 1, 0, e.rho, g->span);
			g->smin = fmin(sr, si) * e.rho;
		}
		if (g->check_step && hc >= hs * (1 - 1e-6)) { /* at the limit nothing decays: refused too */
			refuse_step(r, ode, t, h, hc, hs, &e);
			halt = 1;
		}
	} else if (au) { /* dop853: the implicit method from the next step on when stability holds it */
		if (!au->failed && h > 0 && hs < INFINITY && (r->tend - t) / h > 1000 &&
		    ((h >= AUTO_NEAR * hs && e.re[0] < 0 && fabs(e.im[0]) < -e.re[0] && auto_ratio_at_least(r, e.rho, 1000)) ||
		     (h >= 0.8 * hs && (auto_ratio_at_least(r, e.rho, 100) || ++g->stiff_hits >= 2))))
			au->want = 1;
	} else if (h > 0 && hs < INFINITY && h >= 0.8 * hs && (r->tend - t) / h > 1000 &&
	           ((!g->have_ratio && guard_ratio(r, e.rho)) || g->ratio >= 100 || ++g->stiff_hits >= 2)) {
		/* steps held near the stability limit, with many steps to go: stiff if the spectrum spans
		   100 times or more, or (a spread that cannot be measured) when a second look agrees */
		warn_stiff(r, ode, t, h, &e);
		g->detect_stiff = 0;
		g->warned = 1;
	}
out:; /* a label before a declaration: C11 needs a statement */
	if (looked && !g->fixed && !g->warned_short && g->steps >= SHORT_LEFT / 100 && h > 0 &&
	    h * e.rho * SHORT_STEPS < 1 && h * SHORT_STEPS < g->hcap && (r->tend - t) / h > SHORT_LEFT &&
	    !rounding_floors(r, ode, t, y, h, &e))
		warn_short(r, ode, t, h, &e);
	/* the next look: after LOOK_EVERY times this one's cost in evaluations; with fixed steps,
	   sooner as h rho nears the method's least limit on either axis (the direction of the
	   eigenvalues may turn, as a pendulum's do), every step past half of it */
	double now = guard_evals(r);
	g->next = now + LOOK_EVERY * (now - before);
	if (g->fixed) {
		double per_step = g->steps ? (double)r->nrhs / (double)g->steps : 1;
		double every = LOOK_EVERY * (now - before) / fmax(per_step, 1);
		if (g->smin > 0 && g->h * g->rho_max > 0.5 * g->smin)
			every *= fmax(0, 1 - g->h * g->rho_max / g->smin) / 0.5;
		g->next_step = g->steps + (unsigned long)fmax(1, floor(every));
	}
	if (r->cs) csf_contacts_set_unsolved(r->cs, unsolved);
	clock_gettime(CLOCK_MONOTONIC, &c1);
	g->seconds += csf_run_seconds(c0, c1);
	return halt;
}

/* After every step (csf_watch_fn): a signal halts the run; the progress line; a look when one is due. */
int csf_run_step_watch(void *ctx, double t, const double *y, double h)
{
	watch_ctx *w = ctx;
	w->r->fail = 0; /* an evaluation that failed was in a trial step, tried again shorter */
	w->r->trial_unsolved = 0;
	if (csf_signal && !w->r->row_end) return 1;
	if (w->r->prog) csf_run_progress(w->r, t);
	guard *g = w->r->g;
	if (!g) return 0;
	g->steps++;
	if (g->fixed ? g->steps < g->next_step && !g->due : guard_evals(w->r) < g->next) return 0;
	return csf_run_guard_check(w->r, w->ode, t, y, h);
}
