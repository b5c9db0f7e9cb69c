/*
 * control.c - the error control of the adaptive methods, over GSL's driver,
 * and the live absolute scale it reads.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "csf_ops.h"
#include "ode_int.h"

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
	size_t *limit; /* where the component of the largest E_i / D_i goes (csf_ode_limit) */
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
	size_t imax = dim;
	for (size_t i = 0; i < dim; i++) {
		double r = fabs(yerr[i]) / fabs(control_level(c, y[i], yp ? yp[i] : 0, h_old, i));
		if (r > rmax) rmax = r, imax = i;
	}
	if (c->limit) *c->limit = imax;
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
 * is held absolutely, at LIVE_FLOOR of its unit. A component of a vector
 * follows the vector's size (csf_ode_vectors): the x velocity of a bead at
 * the bottom of a swinging chain is 0 by symmetry, and what it has is the
 * rounding of forces of the size of its z velocity's, which no step can
 * make smaller. A component the scene gives an atol (or --atol) keeps that.
 */
#define LIVE_FLOOR 1e-6

/* The scales of the components not fixed grown to y's sizes; from their floor first when init. */
static void live_update(csf_ode *o, const double *y, int init)
{
	for (size_t i = 0; i < o->n; i++) {
		if (o->fixed_atol[i]) continue;
		if (init) o->live[i] = LIVE_FLOOR * o->base[i];
		double a = fabs(y[i]);
		if (o->vec && o->vec[i]) { /* a vector's component: the vector's size (its largest component) */
			const double *v = y + o->vec[i] - 1;
			a = csf_fmax(fabs(v[0]), csf_fmax(fabs(v[1]), fabs(v[2])));
		}
		if (a > o->live[i]) o->live[i] = a < o->base[i] ? a : o->base[i];
	}
}

void csf_ode_live_grow(csf_ode *o, const double *y) { live_update(o, y, 0); }

double csf_ode_abs_tol(const csf_ode *o, size_t i) { return i < o->n ? o->tol * o->live[i] : 0; }

int csf_ode_raise_abs_tol(csf_ode *o, size_t i, double atol)
{
	if (i >= o->n || o->fixed_atol[i] || !(atol > 0)) return 0;
	double s = fmin(atol / o->tol, o->base[i]);
	if (!o->live_set) csf_ode_live_init(o);
	if (!(s > o->live[i])) return 0;
	o->live[i] = s;
	return 1;
}

/* The scales at their floor, before any state has been seen. */
void csf_ode_live_init(csf_ode *o)
{
	o->live_set = 1;
	for (size_t i = 0; i < o->n; i++)
		if (!o->fixed_atol[i]) o->live[i] = LIVE_FLOOR * o->base[i];
}

void csf_ode_live_start(csf_ode *o, const double *y)
{
	if (o->live_set) return;
	o->live_set = 1;
	live_update(o, y, 1); /* csf_ode_live_init, then csf_ode_live_grow, in one pass */
}

/* GSL's driver, with the error control as driver_alloc_y_new (a_y = 1, a_dydt = 0), the absolute
   tolerance of each component scaled as o->scale is now (control_type) */
int csf_ode_gsl_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen)
{
	(void)vpair;
	double tol = o->tol;
	o->drv = gsl_odeiv2_driver_alloc_y_new(&o->sys, *o->m->type, h0 < hmax ? h0 : hmax, tol, tol);
	if (o->drv) {
		gsl_odeiv2_control_free(o->drv->c);
		o->drv->c = gsl_odeiv2_control_alloc(&control_type);
		if (o->drv->c) ((control *)o->drv->c->state)->scale = o->scale, ((control *)o->drv->c->state)->limit = &o->limit;
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
