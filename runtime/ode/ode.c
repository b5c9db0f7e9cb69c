/*
 * ode.c - GSL odeiv2 behind a small checked API.
 *
 * This is the only file of the runtime that includes GSL. GSL's error
 * handler is switched off; every status is checked and turned into a CSF
 * error. The method table is the one list of steppers CSF offers.
 */
#include <complex.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "csf.h"
#include "dop853.h"
#include "dopri5.h"
#include "erk.h"
#include "ode.h"


/* The most coefficients of a stability polynomial: more than the most stages (rk8pd's 13) plus one. */
enum { NSTAB = 16 };

/*
 * One fixed step of h from (t, y), without error control: CSF_ODE_OK,
 * CSF_ODE_STOPPED when f failed, CSF_ODE_FAILED with a reason in err.
 */
typedef int fixed_fn(csf_ode *o, double t, double h, double *y, char *err, size_t errlen);

/* A continuous extension (erk.c's): its error norm's scale, and the state at tc within the last step. */
struct dense {
	void (*set_scale)(gsl_odeiv2_step *s, const double *scale);
	int (*eval)(csf_ode *o, double tc, double *out);
};

/*
 * How csf_ode_stable_step finds the method's stable steps: the stability
 * polynomial of adaptive and of fixed steps, put in o->stab (NULL: none
 * needed), and how much faster than the exact solution one step grows a
 * mode; without excess, the answer for every mode.
 */
struct stability {
	int (*poly)(csf_ode *o);
	int (*poly_fixed)(csf_ode *o);
	double (*excess)(const csf_ode *o, double complex z);
	double every;
};

/*
 * A method: what differs from one to the next, as entries (REBOUND's
 * reb_integrator is the model). The generic code dispatches through them.
 */
struct method {
	const char *name;
	const gsl_odeiv2_step_type *const *type; /* the adaptive stepper (NULL: fixed steps only) */
	/* what csf_ode_new sets up for it (a GSL driver and control, or verlet's pairs) */
	int (*setup)(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
	fixed_fn *step;                          /* one fixed step (NULL: none, a multistep method) */
	int (*substep)(csf_ode *o, double t, double h, double *out); /* csf_ode_substep's step, 0 or 1 */
	const gsl_odeiv2_step_type *const *sub;  /* the one-step stepper of gsl_substep */
	double (*fixed_h)(const csf_ode *o, double by); /* the fixed step without --step (NULL: by) */
	const struct dense *dense;               /* a continuous extension: steps past the output times (or NULL) */
	const struct stability *stab;
	int jacobian;  /* the stepper uses the Jacobian */
	double tol;    /* the default local error bound (the work-precision benchmark: the cheapest that keeps
	                  every problem with an exact answer within 1e-6) */
};

static int gsl_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
static int verlet_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
static fixed_fn gsl_fixed, rk4_fixed, verlet_fixed;
static int gsl_substep(csf_ode *o, double t, double h, double *out);
static int rk4_substep(csf_ode *o, double t, double h, double *out);
static int verlet_substep(csf_ode *o, double t, double h, double *out);
static double verlet_h(const csf_ode *o, double by);
static int erk_dense_eval(csf_ode *o, double tc, double *out);
static int measured_poly(csf_ode *o);
static int rk4_poly(csf_ode *o);
static double poly_excess(const csf_ode *o, double complex z);
static double verlet_excess(const csf_ode *o, double complex z);

static const struct dense erk_dense = { csf_erk_set_scale, erk_dense_eval };

static const struct stability
	stab_measured = { measured_poly, measured_poly, poly_excess, 0 }, /* explicit Runge-Kutta: the code's polynomial */
	stab_rk4 = { measured_poly, rk4_poly, poly_excess, 0 },           /* fixed steps: the classical rk4's */
	stab_verlet = { NULL, NULL, verlet_excess, 0 },                   /* on x'' = lambda^2 x */
	stab_implicit = { NULL, NULL, NULL, INFINITY },                   /* no step is unstable */
	stab_unknown = { NULL, NULL, NULL, NAN };                         /* msadams, whose order varies */

#define STEP(T) &gsl_odeiv2_step_##T
static const struct method methods[] = {
	/* Dormand-Prince 8(5,3) with dense output (dop853.c) */
	{ "dop853", &csf_step_dop853, gsl_setup, gsl_fixed, gsl_substep, &csf_step_dop853, NULL, &erk_dense, &stab_measured, 0, 1e-12 },
	/* Dormand-Prince 5(4), its free extension (dopri5.c) */
	{ "dopri5", &csf_step_dopri5, gsl_setup, gsl_fixed, gsl_substep, &csf_step_dopri5, NULL, &erk_dense, &stab_measured, 0, CSF_DEFAULT_TOL },
	{ "rk8pd", STEP(rk8pd), gsl_setup, gsl_fixed, gsl_substep, STEP(rk8pd), NULL, NULL, &stab_measured, 0, CSF_DEFAULT_TOL },
	{ "rk2", STEP(rk2), gsl_setup, gsl_fixed, gsl_substep, STEP(rk2), NULL, NULL, &stab_measured, 0, CSF_DEFAULT_TOL },
	/* fixed steps: the classical four-stage method, written here */
	{ "rk4", STEP(rk4), gsl_setup, rk4_fixed, rk4_substep, NULL, NULL, NULL, &stab_rk4, 0, CSF_DEFAULT_TOL },
	{ "rkf45", STEP(rkf45), gsl_setup, gsl_fixed, gsl_substep, STEP(rkf45), NULL, NULL, &stab_measured, 0, CSF_DEFAULT_TOL },
	{ "rkck", STEP(rkck), gsl_setup, gsl_fixed, gsl_substep, STEP(rkck), NULL, NULL, &stab_measured, 0, CSF_DEFAULT_TOL },
	{ "rk1imp", STEP(rk1imp), gsl_setup, gsl_fixed, gsl_substep, STEP(rk1imp), NULL, NULL, &stab_implicit, 1, CSF_DEFAULT_TOL },
	{ "rk2imp", STEP(rk2imp), gsl_setup, gsl_fixed, gsl_substep, STEP(rk2imp), NULL, NULL, &stab_implicit, 1, CSF_DEFAULT_TOL },
	{ "rk4imp", STEP(rk4imp), gsl_setup, gsl_fixed, gsl_substep, STEP(rk4imp), NULL, NULL, &stab_implicit, 1, CSF_DEFAULT_TOL },
	{ "bsimp", STEP(bsimp), gsl_setup, gsl_fixed, gsl_substep, STEP(bsimp), NULL, NULL, &stab_implicit, 1, CSF_DEFAULT_TOL },
	/* multistep: no fixed steps; a one-step method of high order takes the substeps (implicit where the
	   method is, for stiff problems), since they cannot start from anywhere */
	{ "msadams", STEP(msadams), gsl_setup, NULL, gsl_substep, STEP(rk8pd), NULL, NULL, &stab_unknown, 0, CSF_DEFAULT_TOL },
	{ "msbdf", STEP(msbdf), gsl_setup, NULL, gsl_substep, STEP(rk4imp), NULL, NULL, &stab_implicit, 1, CSF_DEFAULT_TOL },
	/* velocity Verlet, written here: symplectic, fixed steps */
	{ "verlet", NULL, verlet_setup, verlet_fixed, verlet_substep, NULL, verlet_h, NULL, &stab_verlet, 0, CSF_DEFAULT_TOL },
};
#undef STEP

const char *csf_method_name(size_t i) { return i < sizeof methods / sizeof methods[0] ? methods[i].name : NULL; }

static const struct method *find_method(const char *name)
{
	for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
		if (strcmp(methods[i].name, name) == 0) return &methods[i];
	return NULL;
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

int csf_method_dense(const char *method)
{
	const struct method *m = method ? find_method(method) : &methods[0];
	return m && m->dense;
}

struct csf_ode {
	gsl_odeiv2_system sys;
	gsl_odeiv2_driver *drv;
	const struct method *m;
	size_t n;
	double tol;
	double *k;                 /* fixed steps: 5 work vectors of n */
	gsl_odeiv2_step *sub;      /* events: a second stepper of the same method, for substeps */
	double *yerr;
	unsigned long fixed_steps;
	unsigned long past_steps, past_rejected; /* GSL's counts before the last restart */
	const double *scale;       /* each component's absolute tolerance, in units of tol (o->live) */
	const double *base;        /* the program's scale: one unit, or less (csf_ode_new's scale) */
	double *live;              /* the scale now: as the component has grown, within base (owned) */
	unsigned char *fixed_atol; /* the scene's atol or --atol holds this component's scale fixed (owned) */
	int live_set;              /* live has been set from a state (live_start) */
	const uint32_t *vpair;     /* verlet: 1 + velocity index of each position component */
	double *acc;               /* verlet: the derivative at the current point */
	double acc_t;
	int acc_ok;
	csf_rhs_fn f;
	csf_jac_fn jac;
	void *ctx;
	csf_watch_fn watch;        /* called after every step (csf_ode_watch) */
	void *watch_ctx;
	double hcap;               /* fixed steps: at most this long from now on (csf_ode_cap_step; 0: none) */
	double stab[NSTAB];        /* the stability polynomial's coefficients (stability_poly) */
	int nstab, stab_fixed;     /* how many (0: not yet computed), and for fixed steps or not */
	double complex last_u;     /* the last csf_ode_stable_step: its direction, allowance and answer */
	double last_allow, last_s;
};

/*
 * A state or derivative that is not finite (the model's f failed). Inside a
 * trial step it means the step was too long: GSL's evolve retries a step
 * shorter (halved) for any failure of the stepper but GSL_EBADFUNC and
 * GSL_EFAULT, and every stepper passes this code on, restoring its state
 * (the multistep methods' failure handlers). It comes out of evolve only
 * when it persists as the step shrinks to nothing, or at the step's start:
 * an accepted state whose derivative is not finite. GSL's odeiv2 never
 * returns GSL_ERANGE itself.
 */
enum { TOO_LONG = GSL_ERANGE };

static int gsl_rhs(double t, const double y[], double dydt[], void *params)
{
	csf_ode *o = params;
	for (size_t i = 0; i < o->n; i++)
		if (!isfinite(y[i])) return TOO_LONG; /* a trial state that overflowed (f may not look at it) */
	return o->f(t, y, dydt, o->ctx) ? TOO_LONG : GSL_SUCCESS;
}

static int gsl_jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
	csf_ode *o = params;
	return o->jac(t, y, dfdy, dfdt, o->ctx) ? TOO_LONG : GSL_SUCCESS;
}

/*
 * The error control. GSL's standard control, as its manual states it: each
 * component may err by D_i = tol (scale_i + |y_i|); the step shrinks when the
 * largest E_i / D_i is over 1.1, to S (E/D)^(-1/q) of itself (S = 0.9, q the
 * method's order, at most 5 times shorter), and grows when it is under 0.5, by
 * S (E/D)^(-1/(q+1)) (at least 1, at most 4.9 times). Unlike GSL's scaled
 * control, which copies its scales once, it reads scale_i where csf_ode keeps
 * it, so the scale can follow the component as it grows (live_scale).
 */
typedef struct control {
	double eps_abs, eps_rel, a_y, a_dydt;
	const double *scale;
} control;

static void *control_alloc(void) { return calloc(1, sizeof(control)); }

static int control_init(void *state, double eps_abs, double eps_rel, double a_y, double a_dydt)
{
	control *c = state;
	if (eps_abs < 0 || eps_rel < 0 || a_y < 0 || a_dydt < 0) return GSL_EINVAL;
	c->eps_abs = eps_abs, c->eps_rel = eps_rel, c->a_y = a_y, c->a_dydt = a_dydt;
	return GSL_SUCCESS;
}

static double control_level(const control *c, double y, double dydt, double h, size_t i)
{
	return c->eps_rel * (c->a_y * fabs(y) + c->a_dydt * fabs(h * dydt)) + c->eps_abs * c->scale[i];
}

static int control_hadjust(void *state, size_t dim, unsigned int ord, const double y[], const double yerr[],
                           const double yp[], double *h)
{
	const control *c = state;
	const double S = 0.9, h_old = *h;
	double rmax = DBL_MIN;
	for (size_t i = 0; i < dim; i++) {
		double r = fabs(yerr[i]) / fabs(control_level(c, y[i], yp ? yp[i] : 0, h_old, i));
		if (r > rmax) rmax = r;
	}
	if (rmax > 1.1) {
		double r = S / pow(rmax, 1.0 / ord);
		*h = (r < 0.2 ? 0.2 : r) * h_old;
		return GSL_ODEIV_HADJ_DEC;
	}
	if (rmax < 0.5) {
		double r = S / pow(rmax, 1.0 / (ord + 1.0));
		*h = (r > 4.9 ? 4.9 : r < 1.0 ? 1.0 : r) * h_old;
		return GSL_ODEIV_HADJ_INC;
	}
	return GSL_ODEIV_HADJ_NIL;
}

static int control_errlevel(void *state, const double y, const double dydt, const double h, const size_t i,
                            double *errlev)
{
	*errlev = control_level(state, y, dydt, h, i);
	return *errlev > 0 ? GSL_SUCCESS : GSL_ESANITY;
}

static int control_set_driver(void *state, const gsl_odeiv2_driver *d)
{
	(void)state, (void)d;
	return GSL_SUCCESS;
}

static const gsl_odeiv2_control_type control_type = { "csf", control_alloc, control_init, control_hadjust,
	                                                control_errlevel, control_set_driver, free };

/*
 * The scale of a component's absolute error follows its size. It starts at
 * the component's initial size and grows with the largest size the component
 * reaches, but stays within [LIVE_FLOOR, 1] times the program's scale (one
 * unit of the component, or less when the property starts smaller in every
 * object: gen.c). So a concentration that starts at 0 and never exceeds
 * 3.6e-5 mol/L is held to the tolerance relative to 3.6e-5, not to 1 mol/L
 * (where it would be free to go negative: Robertson's kinetics), while a
 * component that stays at rounding-error size, such as a normal mode's node,
 * is held absolutely, at LIVE_FLOOR of its unit. A component the scene gives
 * an atol (or --atol) keeps that.
 */
#define LIVE_FLOOR 1e-6

static void live_grow(csf_ode *o, const double *y)
{
	for (size_t i = 0; i < o->n; i++) {
		if (o->fixed_atol[i]) continue;
		double a = fabs(y[i]);
		if (a > o->live[i]) o->live[i] = a < o->base[i] ? a : o->base[i];
	}
}

/* The scales at their floor, before any state has been seen. */
static void live_init(csf_ode *o)
{
	o->live_set = 1;
	for (size_t i = 0; i < o->n; i++)
		if (!o->fixed_atol[i]) o->live[i] = LIVE_FLOOR * o->base[i];
}

static void live_start(csf_ode *o, const double *y)
{
	if (o->live_set) return;
	live_init(o);
	live_grow(o, y);
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

/* verlet: every component a position with a velocity, or that velocity */
static int verlet_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen)
{
	(void)h0, (void)hmax;
	size_t n = o->n;
	unsigned char *isvel = calloc(n ? n : 1, 1);
	int ok = isvel != NULL;
	for (size_t i = 0; ok && i < n; i++)
		if (vpair[i]) ok = !isvel[vpair[i] - 1]++ && !vpair[vpair[i] - 1];
	for (size_t i = 0; ok && i < n; i++) ok = vpair[i] || isvel[i];
	free(isvel);
	if (!ok) {
		snprintf(err, errlen,
		         "verlet needs every state variable in a position/velocity pair (x' = v, where v' does not "
		         "depend on v); this model's are not");
		return -1;
	}
	o->vpair = vpair;
	return 0;
}

/* GSL's driver, with the error control as driver_alloc_y_new (a_y = 1, a_dydt = 0), the absolute
   tolerance of each component scaled as o->scale is now (control_type) */
static int gsl_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen)
{
	(void)vpair;
	double tol = o->tol;
	o->drv = gsl_odeiv2_driver_alloc_y_new(&o->sys, *o->m->type, h0 < hmax ? h0 : hmax, tol, tol);
	if (o->drv) {
		gsl_odeiv2_control_free(o->drv->c);
		o->drv->c = gsl_odeiv2_control_alloc(&control_type);
		if (o->drv->c) ((control *)o->drv->c->state)->scale = o->scale;
	}
	if (!o->drv || !o->drv->c || gsl_odeiv2_control_init(o->drv->c, tol, tol, 1.0, 0.0) != GSL_SUCCESS ||
	    gsl_odeiv2_control_set_driver(o->drv->c, o->drv) != GSL_SUCCESS ||
	    gsl_odeiv2_driver_set_hmax(o->drv, hmax) != GSL_SUCCESS) {
		snprintf(err, errlen, "cannot set up the integrator");
		return -1;
	}
	/* the error norm of a method with a continuous extension (dop853's) weighs components as the control does */
	if (o->m->dense) o->m->dense->set_scale(o->drv->s, o->scale);
	return 0;
}

static int work(csf_ode *o)
{
	if (!o->k && (!(o->k = malloc(5 * (o->n ? o->n : 1) * sizeof *o->k)) ||
	              !(o->acc = malloc((o->n ? o->n : 1) * sizeof *o->acc))))
		return -1;
	return 0;
}

/* One velocity Verlet step: x += h v + h^2/2 a(x); v += h/2 (a(x) + a(x')); one evaluation. */
static int verlet_step(csf_ode *o, double t, double h, double *y)
{
	size_t n = o->n;
	double *a1 = o->k;
	if (!o->acc_ok || o->acc_t != t) {
		if (o->f(t, y, o->acc, o->ctx)) return 1;
		o->acc_t = t;
	}
	for (size_t i = 0; i < n; i++)
		if (o->vpair[i]) {
			size_t v = o->vpair[i] - 1;
			y[i] += h * y[v] + h * h / 2 * o->acc[v];
		}
	o->acc_ok = 0;
	if (o->f(t + h, y, a1, o->ctx)) return 1;
	for (size_t i = 0; i < n; i++)
		if (o->vpair[i]) {
			size_t v = o->vpair[i] - 1;
			y[v] += h / 2 * (o->acc[v] + a1[v]);
		}
	memcpy(o->acc, a1, n * sizeof *a1);
	o->acc_t = t + h;
	o->acc_ok = 1;
	return 0;
}

/* One classical Runge-Kutta step of size h (four evaluations). */
static int rk4_step(csf_ode *o, double t, double h, double *y)
{
	size_t n = o->n;
	double *k1 = o->k, *k2 = k1 + n, *k3 = k2 + n, *k4 = k3 + n, *yt = k4 + n;
	if (o->f(t, y, k1, o->ctx)) return 1;
	for (size_t i = 0; i < n; i++) yt[i] = y[i] + h / 2 * k1[i];
	if (o->f(t + h / 2, yt, k2, o->ctx)) return 1;
	for (size_t i = 0; i < n; i++) yt[i] = y[i] + h / 2 * k2[i];
	if (o->f(t + h / 2, yt, k3, o->ctx)) return 1;
	for (size_t i = 0; i < n; i++) yt[i] = y[i] + h * k3[i];
	if (o->f(t + h, yt, k4, o->ctx)) return 1;
	for (size_t i = 0; i < n; i++) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
	return 0;
}

static int verlet_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	return verlet_step(o, t, h, y) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

static int rk4_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	return rk4_step(o, t, h, y) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/* GSL's step, its error estimate unused */
static int gsl_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	int st = gsl_odeiv2_step_apply(o->drv->s, t, h, y, o->k, NULL, NULL, &o->sys);
	if (st == GSL_SUCCESS) return CSF_ODE_OK;
	if (st == TOO_LONG) return CSF_ODE_STOPPED;
	snprintf(err, errlen, "%s", gsl_strerror(st));
	return CSF_ODE_FAILED;
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
	live_start(o, y);
	int st = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, &o->sys, t, t1, &d->h, y);
	if (st == GSL_SUCCESS) live_grow(o, y);
	if (st == GSL_SUCCESS) return o->watch && o->watch(o->watch_ctx, *t, y, *t - ta) ? CSF_ODE_HALTED : CSF_ODE_OK;
	if (st == TOO_LONG) return CSF_ODE_STOPPED;
	snprintf(err, errlen, "%s", gsl_strerror(st));
	return CSF_ODE_FAILED;
}

static int verlet_substep(csf_ode *o, double t, double h, double *out)
{
	o->acc_ok = 0;
	int bad = verlet_step(o, t, h, out);
	o->acc_ok = 0;
	return bad;
}

static int rk4_substep(csf_ode *o, double t, double h, double *out) { return rk4_step(o, t, h, out); }

/* a second GSL stepper, of the method's one-step stand-in (struct method's sub) */
static int gsl_substep(csf_ode *o, double t, double h, double *out)
{
	if (!o->sub) {
		o->sub = gsl_odeiv2_step_alloc(*o->m->sub, o->n);
		o->yerr = malloc((o->n ? o->n : 1) * sizeof *o->yerr);
		if (!o->sub || !o->yerr) return 1;
		gsl_odeiv2_step_set_driver(o->sub, o->drv); /* the implicit methods read its tolerance */
	}
	gsl_odeiv2_step_reset(o->sub);
	return gsl_odeiv2_step_apply(o->sub, t, h, out, o->yerr, NULL, NULL, &o->sys) != GSL_SUCCESS;
}

int csf_ode_substep(csf_ode *o, double t, const double *y, double h, double *out)
{
	memcpy(out, y, o->n * sizeof *y);
	if (work(o)) return 1;
	return o->m->substep(o, t, h, out);
}

int csf_ode_dense(const csf_ode *o) { return o->m->dense != NULL; }

/* The root mean square of v_i / (tol (scale_i + |y_i|)): the error control's measure. */
static double wrms(const csf_ode *o, const double *v, const double *y)
{
	double s = 0;
	for (size_t i = 0; i < o->n; i++) {
		double r = v[i] / (o->tol * (o->scale[i] + fabs(y[i])));
		s += r * r;
	}
	return o->n ? sqrt(s / (double)o->n) : 0;
}

int csf_ode_first_step(csf_ode *o, double t, const double *y)
{
	size_t n = o->n;
	gsl_odeiv2_driver *d = o->drv;
	if (!d || work(o)) return 0;
	live_start(o, y);
	double *f0 = o->k, *y1 = f0 + n, *f1 = y1 + n;
	if (o->f(t, y, f0, o->ctx)) return 1;
	double d0 = wrms(o, y, y), d1 = wrms(o, f0, y);
	double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
	if (h0 > d->hmax) h0 = d->hmax;
	for (;;) { /* an Euler step that overflows is too long, as a trial step is: halved, down to nothing */
		for (size_t i = 0; i < n; i++) y1[i] = y[i] + h0 * f0[i];
		if (gsl_rhs(t + h0, y1, f1, o) == GSL_SUCCESS) break;
		h0 /= 2;
		if (t + h0 == t) return 1;
	}
	for (size_t i = 0; i < n; i++) f1[i] -= f0[i];
	double d2 = wrms(o, f1, y) / h0, dm = d1 > d2 ? d1 : d2;
	double h1 = dm <= 1e-15 ? fmax(1e-6, h0 * 1e-3) : pow(0.01 / dm, 1.0 / (gsl_odeiv2_step_order(d->s) + 1.0));
	double h = 100 * h0 < h1 ? 100 * h0 : h1;
	d->h = h < d->hmax ? h : d->hmax;
	return 0;
}

int csf_ode_dense_eval(csf_ode *o, double tc, double *out) { return o->m->dense->eval(o, tc, out); }

static int erk_dense_eval(csf_ode *o, double tc, double *out)
{
	double t0, h;
	gsl_odeiv2_step *s = o->drv->s;
	csf_erk_last_step(s, &t0, &h);
	if (csf_erk_dense_prepare(s, &o->sys) != GSL_SUCCESS) return 1;
	double theta = h != 0 ? (tc - t0) / h : 1;
	csf_erk_dense_eval(s, theta < 0 ? 0 : theta > 1 ? 1 : theta, out);
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
	if (!o->live_set) live_init(o);
	for (size_t i = 0; i < o->n; i++)
		if (!o->fixed_atol[i] && from->live[i] > o->live[i]) o->live[i] = from->live[i];
}

void csf_ode_stats(const csf_ode *o, unsigned long *steps, unsigned long *rejected)
{
	*steps = o->fixed_steps + o->past_steps + (o->drv ? o->drv->e->count : 0);
	*rejected = o->past_rejected + (o->drv ? o->drv->e->failed_steps : 0);
}

int csf_ode_explicit(const csf_ode *o) { return !o->m->jacobian; }

int csf_ode_fixed_only(const csf_ode *o) { return !o->m->type; }

double csf_ode_fixed_step(const csf_ode *o, double by, double step)
{
	if (step > 0) return step < by ? step : by;
	return o->m->fixed_h ? o->m->fixed_h(o, by) : by;
}

/* verlet has no error estimate: its global error goes as h^2, so the step comes
   from the tolerance, h = by sqrt(tol / 1e-4) (by / 1000 at the default 1e-10) */
static double verlet_h(const csf_ode *o, double by)
{
	double f = sqrt(o->tol / 1e-4);
	return f < 1 ? by * f : by;
}

const char *csf_ode_method(const csf_ode *o) { return o->m->name; }

double csf_ode_next_step(const csf_ode *o) { return o->drv ? o->drv->h : 0; }

void csf_ode_watch(csf_ode *o, csf_watch_fn fn, void *ctx)
{
	o->watch = fn;
	o->watch_ctx = ctx;
}

void csf_ode_cap_step(csf_ode *o, double h) { o->hcap = h; }

/* y' = N y with N the shift, N e_j = e_(j+1), for stability_poly. */
static int shift_rhs(double t, const double y[], double dydt[], void *params)
{
	(void)t, (void)params;
	dydt[0] = 0;
	for (int j = 1; j < NSTAB; j++) dydt[j] = y[j - 1];
	return GSL_SUCCESS;
}

/*
 * The method's stability polynomial R(z) = sum c_j z^j, the factor one
 * step multiplies y by on y' = lambda y, z = h lambda, in o->stab: for
 * the classical rk4 of fixed steps 1/j!, for a GSL stepper measured by
 * one step of h = 1 on y' = N y (N the shift) from e_0, which ends at
 * R(N) e_0 = (c_0, c_1, ...): the polynomial of the code that runs, not
 * of a table that might not match it (GSL's rk2 takes the third-order
 * solution; its rk4, two half steps). 0, or -1 when memory runs out.
 */
static int rk4_poly(csf_ode *o)
{
	memset(o->stab, 0, sizeof o->stab);
	for (int j = 0, f = 1; j <= 4; j++, f *= j ? j : 1) o->stab[j] = 1.0 / f;
	o->nstab = 5;
	return 0;
}

static int measured_poly(csf_ode *o)
{
	memset(o->stab, 0, sizeof o->stab);
	gsl_odeiv2_system sys = { shift_rhs, NULL, NSTAB, NULL };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(*o->m->type, NSTAB);
	double yerr[NSTAB];
	if (!s) return -1;
	o->stab[0] = 1;
	int st = gsl_odeiv2_step_apply(s, 0, 1, o->stab, yerr, NULL, NULL, &sys);
	gsl_odeiv2_step_free(s);
	if (st != GSL_SUCCESS) return -1;
	o->nstab = NSTAB;
	return 0;
}

/*
 * How much faster than the exact solution one step grows the mode of
 * eigenvalue lambda, z = h lambda, as a logarithm: log |R(z)| against
 * the growth e^max(0, Re z) of a mode that grows by itself. verlet
 * advances x'' = mu x (mu = lambda^2, eigenvalues +-lambda) by a factor
 * r with r^2 - (2 + z^2) r + 1 = 0, against e^|Re z|.
 */
static double verlet_excess(const csf_ode *o, double complex z)
{
	(void)o;
	double complex b = 2 + z * z, d = csqrt(b * b - 4);
	return log(fmax(cabs((b + d) / 2), cabs((b - d) / 2))) - fabs(creal(z));
}

static double poly_excess(const csf_ode *o, double complex z)
{
	if (cimag(z) == 0) { /* the real axis (stiff decays) in real arithmetic: the same value, 4 times sooner */
		double x = creal(z), r = 0;
		for (int j = o->nstab - 1; j >= 0; j--) r = r * x + o->stab[j];
		return log(fabs(r)) - fmax(0, x);
	}
	double complex r = 0;
	for (int j = o->nstab - 1; j >= 0; j--) r = r * z + o->stab[j];
	return log(cabs(r)) - fmax(0, creal(z));
}

double csf_ode_stable_step(csf_ode *o, int fixed, double re, double im, double span)
{
	double mag = hypot(re, im);
	const struct stability *sb = o->m->stab;
	if (!sb->excess) return sb->every;
	if (!(mag > 0) || !(span > 0)) return INFINITY;
	int (*poly)(csf_ode *) = fixed ? sb->poly_fixed : sb->poly;
	if (poly && (!o->nstab || o->stab_fixed != fixed)) {
		if (poly(o)) return NAN;
		o->stab_fixed = fixed;
		o->last_s = 0;
	}
	/* R has real coefficients: |R(conj z)| = |R(z)|; set as the two doubles a complex is (C11
	   6.2.5), not with CMPLX, which not every C library defines */
	double complex u;
	((double *)&u)[0] = re / mag, ((double *)&u)[1] = fabs(im) / mag;
	/* s = h |lambda| is stable while the mode grows by at most 1 % more than it should over the
	   span/h steps of the run: a method that is weakly unstable near the axis (rk8pd's factor on
	   the imaginary axis at s = 0.5 is 1 + 2.5e-11) is held to what that costs the run */
	double allow = log(1.01) / (mag * span);
	if (o->last_s > 0 && cabs(u - o->last_u) <= 1e-9 && fabs(allow - o->last_allow) <= 0.1 * allow)
		return o->last_s / mag; /* the same direction as last time (a scene that keeps its spectrum) */
#define UNSTABLE(s) (sb->excess(o, (s) * u) > allow * (s) + 1e-12)
	const double ds = 0.02, smax = 40; /* the regions of explicit methods end before 10 */
	double lo = 0;
	while (lo < smax && !UNSTABLE(lo + ds)) lo += ds;
	if (lo >= smax) {
		lo = INFINITY;
	} else {
		double hi = lo + ds;
		for (int i = 0; i < 60 && hi - lo > 1e-12 * hi; i++) {
			double mid = (lo + hi) / 2;
			if (UNSTABLE(mid)) hi = mid;
			else lo = mid;
		}
	}
	o->last_u = u, o->last_allow = allow, o->last_s = lo;
#undef UNSTABLE
	return lo / mag;
}

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
