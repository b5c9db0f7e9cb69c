/*
 * ode.c - GSL odeiv2 behind a small checked API: the method table and
 * what dispatches through it.
 *
 * Only the files of runtime/ode/ include GSL. GSL's error handler is
 * switched off; every status is checked and turned into a CSF error. The
 * method table is the one list of steppers CSF offers; what differs from
 * one method to the next is in its entries (struct method, ode_int.h), the
 * fixed steppers in fixed.c, the error control in control.c, the
 * stability regions in stable.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "csf_ops.h"
#include "dop853.h"
#include "dopri5.h"
#include "erk.h"
#include "ode_int.h"

static int erk_dense_eval(csf_ode *o, double tc, double *out, int some);
static int erk_dense_eval_at(csf_ode *o, double tc, const uint32_t *idx, size_t n, double *out);
static const struct dense erk_dense = { csf_erk_set_scale, csf_erk_set_rows, erk_dense_eval, erk_dense_eval_at };

#define STEP(T) &gsl_odeiv2_step_##T
static const struct method methods[] = {
	/* Dormand-Prince 8(5,3) with dense output (dop853.c) */
	{ .name = "dop853", .type = &csf_step_dop853, .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = &csf_step_dop853, .dense = &erk_dense, .stab = &csf_ode_stab_measured,
	  .tol = 1e-12 },
	/* Dormand-Prince 5(4), its free extension (dopri5.c) */
	{ .name = "dopri5", .type = &csf_step_dopri5, .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = &csf_step_dopri5, .dense = &erk_dense, .stab = &csf_ode_stab_measured,
	  .tol = CSF_DEFAULT_TOL },
	{ .name = "rk8pd", .type = STEP(rk8pd), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rk8pd), .stab = &csf_ode_stab_measured, .tol = CSF_DEFAULT_TOL },
	{ .name = "rk2", .type = STEP(rk2), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rk2), .stab = &csf_ode_stab_measured, .tol = CSF_DEFAULT_TOL },
	/* fixed steps: the classical four-stage method, written here */
	{ .name = "rk4", .type = STEP(rk4), .setup = csf_ode_gsl_setup, .step = csf_ode_rk4_fixed,
	  .substep = csf_ode_rk4_substep, .stab = &csf_ode_stab_rk4, .tol = CSF_DEFAULT_TOL },
	{ .name = "rkf45", .type = STEP(rkf45), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rkf45), .stab = &csf_ode_stab_measured, .tol = CSF_DEFAULT_TOL },
	{ .name = "rkck", .type = STEP(rkck), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rkck), .stab = &csf_ode_stab_measured, .tol = CSF_DEFAULT_TOL },
	{ .name = "rk1imp", .type = STEP(rk1imp), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rk1imp), .stab = &csf_ode_stab_implicit, .jacobian = 1,
	  .skip_compare = 1, .tol = CSF_DEFAULT_TOL },
	{ .name = "rk2imp", .type = STEP(rk2imp), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rk2imp), .stab = &csf_ode_stab_implicit, .jacobian = 1,
	  .skip_compare = 1, .tol = CSF_DEFAULT_TOL },
	{ .name = "rk4imp", .type = STEP(rk4imp), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(rk4imp), .stab = &csf_ode_stab_implicit, .jacobian = 1,
	  .tol = CSF_DEFAULT_TOL },
	{ .name = "bsimp", .type = STEP(bsimp), .setup = csf_ode_gsl_setup, .step = csf_ode_gsl_fixed,
	  .substep = csf_ode_gsl_substep, .sub = STEP(bsimp), .stab = &csf_ode_stab_implicit, .jacobian = 1,
	  .tol = CSF_DEFAULT_TOL },
	/* multistep: no fixed steps; a one-step method of high order takes the substeps (implicit where the
	   method is, for stiff problems), since they cannot start from anywhere */
	{ .name = "msadams", .type = STEP(msadams), .setup = csf_ode_gsl_setup, .substep = csf_ode_gsl_substep,
	  .sub = STEP(rk8pd), .stab = &csf_ode_stab_unknown, .tol = CSF_DEFAULT_TOL, .history = 1 },
	{ .name = "msbdf", .type = STEP(msbdf), .setup = csf_ode_gsl_setup, .substep = csf_ode_gsl_substep,
	  .sub = STEP(rk4imp), .stab = &csf_ode_stab_implicit, .jacobian = 1, .tol = CSF_DEFAULT_TOL, .history = 1 },
	/* velocity Verlet, written here: symplectic, fixed steps */
	{ .name = "verlet", .skip_compare = 1, .setup = csf_ode_verlet_setup, .step = csf_ode_verlet_fixed, .substep = csf_ode_verlet_substep,
	  .fixed_h = csf_ode_verlet_h, .stab = &csf_ode_stab_verlet, .tol = CSF_DEFAULT_TOL, .pairs = 1 },
};
#undef STEP

const char *csf_method_name(size_t i) { return i < sizeof methods / sizeof methods[0] ? methods[i].name : NULL; }

static const struct method *find_method(const char *name)
{
	for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
		if (strcmp(methods[i].name, name) == 0) return &methods[i];
	return NULL;
}

int csf_method_compared(const char *method)
{
	const struct method *m = find_method(method);
	return m && !m->skip_compare;
}

int csf_method_contacts(const char *method)
{
	const struct method *m = method ? find_method(method) : &methods[0];
	return m && m->type;
}

double csf_method_tol(const char *method)
{
	const struct method *m = method ? find_method(method) : &methods[0];
	return m ? m->tol : CSF_DEFAULT_TOL;
}

int csf_method_pairs(const char *method)
{
	const struct method *m = method ? find_method(method) : &methods[0];
	return m && m->pairs;
}

int csf_method_dense(const char *method)
{
	const struct method *m = method ? find_method(method) : &methods[0];
	return m && m->dense;
}

static int gsl_rhs(double t, const double y[], double dydt[], void *params)
{
	csf_ode *o = params;
	if (!csf_all_finite(y, o->n)) return TOO_LONG; /* a trial state that overflowed (f may not look at it) */
	return o->f(t, y, dydt, o->ctx) ? TOO_LONG : GSL_SUCCESS;
}

static int gsl_jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
	csf_ode *o = params;
	return o->jac(t, y, dfdy, dfdt, o->ctx) ? TOO_LONG : GSL_SUCCESS;
}

csf_ode *csf_ode_new(const char *method, int fixed, size_t n, double h0, double hmax, double tol, double atol,
                     const double *atol_each, const double *scale, const uint32_t *vpair, csf_rhs_fn f, csf_jac_fn jac, void *ctx, char *err,
                     size_t errlen)
{
	gsl_set_error_handler_off();
	const struct method *m = method ? find_method(method) : &methods[0];
	if (!m) {
		snprintf(err, errlen, "unknown method '%s'", method);
		return NULL;
	}
	if (fixed && !m->step) {
		snprintf(err, errlen, "--fixed needs a one-step method, not the multistep %s", m->name);
		return NULL;
	}
	if (m->jacobian && !jac) {
		snprintf(err, errlen, "method '%s' needs a Jacobian, and this program has none", m->name);
		return NULL;
	}
	if (tol <= 0) tol = m->tol;
	csf_ode *o = calloc(1, sizeof *o);
	if (!o) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	o->tol = tol;
	o->base = scale;
	o->live = malloc((n ? n : 1) * sizeof *o->live);
	o->fixed_atol = calloc(n ? n : 1, 1);
	if (!o->live || !o->fixed_atol) {
		snprintf(err, errlen, "out of memory");
		csf_ode_free(o);
		return NULL;
	}
	for (size_t i = 0; i < n; i++) { /* the control's absolute bound is tol * scale[i]: atol_each[i], else atol */
		double a = atol_each && atol_each[i] > 0 ? atol_each[i] : atol;
		o->fixed_atol[i] = a > 0;
		o->live[i] = a > 0 ? a / tol : scale[i];
	}
	o->scale = o->live;
	o->limit = n;
	o->m = m;
	o->n = n;
	o->sys = (gsl_odeiv2_system){ gsl_rhs, jac ? gsl_jac : NULL, n, o };
	o->f = f;
	o->jac = jac;
	o->ctx = ctx;
	if (m->setup(o, h0, hmax, vpair, err, errlen)) {
		csf_ode_free(o);
		return NULL;
	}
	return o;
}

static int work(csf_ode *o)
{
	if (!o->k && (!(o->k = malloc(5 * (o->n ? o->n : 1) * sizeof *o->k)) ||
	              !(o->acc = malloc((o->n ? o->n : 1) * sizeof *o->acc))))
		return -1;
	return 0;
}

int csf_ode_advance_fixed(csf_ode *o, double *t, double t1, double h, double *y, char *err, size_t errlen)
{
	if (!o->m->step) {
		snprintf(err, errlen, "%s takes no fixed steps", o->m->name);
		return CSF_ODE_FAILED;
	}
	if (work(o)) {
		snprintf(err, errlen, "out of memory");
		return CSF_ODE_FAILED;
	}
again:
	if (o->hcap > 0 && o->hcap < h) h = o->hcap;
	double t0 = *t, span = t1 - t0;
	double steps = ceil(span / h * (1 - 1e-12));
	if (steps < 1) steps = 1;
	for (double i = 0; i < steps; i++) {
		double ta = t0 + span * (i / steps), tb = i + 1 == steps ? t1 : t0 + span * ((i + 1) / steps);
		int st = o->m->step(o, ta, tb - ta, y, err, errlen);
		if (st != CSF_ODE_OK) {
			*t = ta;
			return st;
		}
		o->fixed_steps++;
		*t = tb;
		if (o->watch && o->watch(o->watch_ctx, tb, y, tb - ta)) return CSF_ODE_HALTED;
		if (tb < t1 && o->hcap > 0 && o->hcap < (tb - ta) * (1 - 1e-12)) goto again; /* the rest in shorter steps */
	}
	return CSF_ODE_OK;
}

int csf_ode_step(csf_ode *o, double *t, double t1, int fixed, double h, double *y, char *err, size_t errlen)
{
	if (fixed || !o->m->type) {
		double tb = *t + h < t1 ? *t + h : t1;
		return csf_ode_advance_fixed(o, t, tb, h, y, err, errlen);
	}
	gsl_odeiv2_driver *d = o->drv;
	if (d->h > d->hmax) d->h = d->hmax;
	/* A step that would end just short of t1 (by at most 1e-4 of its length, as
	   in RADAU5) is stretched to end there. Otherwise what is left can be a
	   sliver, as when t + hmax rounds to one ulp below t1 = t + by: a step too
	   small to change y, on which the Newton iteration of the implicit
	   Runge-Kutta methods (GSL's modnewton1) sees its correction repeat, takes
	   that for divergence, and fails however often the step is halved. A step
	   longer than what is left ends exactly at t1 (evolve_apply's last step). */
	double left = t1 - *t;
	if (d->h <= left && left <= d->h * (1 + 1e-4)) d->h = nextafter(left, INFINITY);
	double ta = *t;
	csf_ode_live_start(o, y);
	int st = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, &o->sys, t, t1, &d->h, y);
	if (st == GSL_SUCCESS) csf_ode_live_grow(o, y);
	if (st == GSL_SUCCESS) return o->watch && o->watch(o->watch_ctx, *t, y, *t - ta) ? CSF_ODE_HALTED : CSF_ODE_OK;
	if (st == TOO_LONG) return CSF_ODE_STOPPED;
	snprintf(err, errlen, "%s", gsl_strerror(st));
	return CSF_ODE_FAILED;
}

int csf_ode_substep(csf_ode *o, double t, const double *y, double h, double *out)
{
	memcpy(out, y, o->n * sizeof *y);
	if (work(o)) return 1;
	return o->m->substep(o, t, h, out);
}

int csf_ode_dense(const csf_ode *o) { return o->m->dense != NULL; }

/*
 * The root mean square of u_i / (tol (scale_i + |y_i|)), the error control's measure, into *du;
 * the same of v into *dv in the same pass when v is given.
 */
static void wrms(const csf_ode *o, const double *y, const double *u, double *du, const double *v, double *dv)
{
	double su = 0, sv = 0;
	for (size_t i = 0; i < o->n; i++) {
		double w = o->tol * (o->scale[i] + fabs(y[i])), ru = u[i] / w;
		su += ru * ru;
		if (v) {
			double rv = v[i] / w;
			sv += rv * rv;
		}
	}
	*du = o->n ? sqrt(su / (double)o->n) : 0;
	if (v) *dv = o->n ? sqrt(sv / (double)o->n) : 0;
}

int csf_ode_first_step(csf_ode *o, double t, const double *y)
{
	size_t n = o->n;
	gsl_odeiv2_driver *d = o->drv;
	if (!d || work(o)) return 0;
	csf_ode_live_start(o, y);
	double *f0 = o->k, *y1 = f0 + n, *f1 = y1 + n;
	if (o->f(t, y, f0, o->ctx)) return 1;
	double d0, d1, d2;
	wrms(o, y, y, &d0, f0, &d1);
	double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
	if (h0 > d->hmax) h0 = d->hmax;
	for (;;) { /* an Euler step that overflows is too long, as a trial step is: halved, down to nothing */
		for (size_t i = 0; i < n; i++) y1[i] = y[i] + h0 * f0[i];
		if (gsl_rhs(t + h0, y1, f1, o) == GSL_SUCCESS) break;
		h0 /= 2;
		if (t + h0 == t) return 1;
	}
	for (size_t i = 0; i < n; i++) f1[i] -= f0[i];
	wrms(o, y, f1, &d2, NULL, NULL);
	d2 /= h0;
	double dm = d1 > d2 ? d1 : d2;
	double h1 = dm <= 1e-15 ? fmax(1e-6, h0 * 1e-3) : pow(0.01 / dm, 1.0 / (gsl_odeiv2_step_order(d->s) + 1.0));
	double h = 100 * h0 < h1 ? 100 * h0 : h1;
	d->h = h < d->hmax ? h : d->hmax;
	return 0;
}

int csf_ode_dense_eval(csf_ode *o, double tc, double *out) { return o->m->dense->eval(o, tc, out, 0); }

int csf_ode_dense_rows(csf_ode *o, double tc, double *out) { return o->m->dense->eval(o, tc, out, 1); }

int csf_ode_dense_at(csf_ode *o, double tc, const uint32_t *idx, size_t n, double *out)
{
	return o->m->dense->eval_at(o, tc, idx, n, out);
}

void csf_ode_set_rows(csf_ode *o, const uint32_t *rows, size_t n)
{
	if (o->m->dense && o->drv) o->m->dense->set_rows(o->drv->s, rows, n);
}

static int erk_dense_eval(csf_ode *o, double tc, double *out, int some)
{
	double t0, h;
	gsl_odeiv2_step *s = o->drv->s;
	csf_erk_last_step(s, &t0, &h);
	if (csf_erk_dense_prepare(s, &o->sys, some) != GSL_SUCCESS) return 1;
	double theta = h != 0 ? (tc - t0) / h : 1;
	csf_erk_dense_eval(s, theta < 0 ? 0 : theta > 1 ? 1 : theta, out, some);
	return 0;
}

static int erk_dense_eval_at(csf_ode *o, double tc, const uint32_t *idx, size_t n, double *out)
{
	double t0, h;
	gsl_odeiv2_step *s = o->drv->s;
	csf_erk_last_step(s, &t0, &h);
	if (csf_erk_dense_prepare(s, &o->sys, 0) != GSL_SUCCESS) return 1;
	double theta = h != 0 ? (tc - t0) / h : 1;
	csf_erk_dense_at(s, theta < 0 ? 0 : theta > 1 ? 1 : theta, idx, n, out);
	return 0;
}

void csf_ode_restart(csf_ode *o)
{
	o->acc_ok = 0;
	if (o->drv) {
		o->past_steps += o->drv->e->count;
		o->past_rejected += o->drv->e->failed_steps;
		gsl_odeiv2_evolve_reset(o->drv->e);
		gsl_odeiv2_step_reset(o->drv->s);
	}
}

void csf_ode_take_scale(csf_ode *o, const csf_ode *from)
{
	if (!from->live_set || o->n != from->n) return;
	if (!o->live_set) csf_ode_live_init(o);
	for (size_t i = 0; i < o->n; i++)
		if (!o->fixed_atol[i] && from->live[i] > o->live[i]) o->live[i] = from->live[i];
}

void csf_ode_stats(const csf_ode *o, unsigned long *steps, unsigned long *rejected)
{
	*steps = o->fixed_steps + o->past_steps + (o->drv ? o->drv->e->count : 0);
	*rejected = o->past_rejected + (o->drv ? o->drv->e->failed_steps : 0);
}

int csf_ode_explicit(const csf_ode *o) { return !o->m->jacobian; }

int csf_ode_history(const csf_ode *o) { return o->m->history; }

void csf_ode_vectors(csf_ode *o, const uint32_t *vec) { o->vec = vec; }

int csf_ode_fixed_only(const csf_ode *o) { return !o->m->type; }

double csf_ode_fixed_step(const csf_ode *o, double by, double step)
{
	if (step > 0) return step < by ? step : by;
	return o->m->fixed_h ? o->m->fixed_h(o, by) : by;
}

const char *csf_ode_method(const csf_ode *o) { return o->m->name; }

double csf_ode_tol(const csf_ode *o) { return o->tol; }

long csf_ode_limit(const csf_ode *o) { return o->limit < o->n ? (long)o->limit : -1; }

double csf_ode_next_step(const csf_ode *o) { return o->drv ? o->drv->h : 0; }

void csf_ode_watch(csf_ode *o, csf_watch_fn fn, void *ctx)
{
	o->watch = fn;
	o->watch_ctx = ctx;
}

void csf_ode_cap_step(csf_ode *o, double h) { o->hcap = h; }

void csf_ode_free(csf_ode *o)
{
	if (!o) return;
	free(o->k);
	free(o->acc);
	free(o->yerr);
	free(o->live);
	free(o->fixed_atol);
	if (o->sub) gsl_odeiv2_step_free(o->sub);
	if (o->drv) gsl_odeiv2_driver_free(o->drv);
	free(o);
}

/* Saves or restores one value of o under "tag.name". */
static int keep_in(struct csf_keeper *k, const char *tag, const char *name, void *p, size_t n)
{
	char full[96];
	snprintf(full, sizeof full, "%s.%s", tag, name);
	return csf_keep(k, full, p, n);
}
#define KEEP_IN(k, tag, x) keep_in((k), (tag), #x, &(x), sizeof(x))

int csf_ode_keep(csf_ode *o, struct csf_keeper *k, const char *tag)
{
	if (!o) return 0;
	size_t n = o->n ? o->n : 1;
	int bad = KEEP_IN(k, tag, o->fixed_steps) | KEEP_IN(k, tag, o->past_steps) | KEEP_IN(k, tag, o->past_rejected) |
	          keep_in(k, tag, "live", o->live, n * sizeof *o->live) | KEEP_IN(k, tag, o->live_set) |
	          KEEP_IN(k, tag, o->acc_t) | KEEP_IN(k, tag, o->acc_ok) | KEEP_IN(k, tag, o->hcap);
	/* verlet's derivative at the current point, when it has one */
	int has_acc = o->acc != NULL;
	bad |= KEEP_IN(k, tag, has_acc);
	if (has_acc && work(o)) return -1;
	if (has_acc) bad |= keep_in(k, tag, "acc", o->acc, n * sizeof *o->acc);
	if (o->drv) {
		gsl_odeiv2_driver *d = o->drv;
		bad |= KEEP_IN(k, tag, d->h) | KEEP_IN(k, tag, d->n) | KEEP_IN(k, tag, d->e->count) |
		       KEEP_IN(k, tag, d->e->failed_steps) | KEEP_IN(k, tag, d->e->last_step) |
		       keep_in(k, tag, "e.y0", d->e->y0, o->n * sizeof(double)) |
		       keep_in(k, tag, "e.yerr", d->e->yerr, o->n * sizeof(double)) |
		       keep_in(k, tag, "e.dydt_in", d->e->dydt_in, o->n * sizeof(double)) |
		       keep_in(k, tag, "e.dydt_out", d->e->dydt_out, o->n * sizeof(double));
		if (o->m->dense) bad |= csf_erk_keep(d->s, k, tag);
	}
	return bad ? -1 : 0;
}
