/*
 * fixed.c - the steps without error control: velocity Verlet and the
 * classical rk4, written here, and GSL's steppers taken without their error
 * estimate (csf_ode_advance_fixed); the single steps of csf_ode_substep.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ode_int.h"

/* verlet: every component a position with a velocity, or that velocity */
int csf_ode_verlet_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen)
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

int csf_ode_verlet_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	return verlet_step(o, t, h, y) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

int csf_ode_rk4_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	(void)err, (void)errlen;
	return rk4_step(o, t, h, y) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/* GSL's step, its error estimate unused */
int csf_ode_gsl_fixed(csf_ode *o, double t, double h, double *y, char *err, size_t errlen)
{
	int st = gsl_odeiv2_step_apply(o->drv->s, t, h, y, o->k, NULL, NULL, &o->sys);
	if (st == GSL_SUCCESS) return CSF_ODE_OK;
	if (st == TOO_LONG) return CSF_ODE_STOPPED;
	snprintf(err, errlen, "%s", gsl_strerror(st));
	return CSF_ODE_FAILED;
}

int csf_ode_verlet_substep(csf_ode *o, double t, double h, double *out)
{
	o->acc_ok = 0;
	int bad = verlet_step(o, t, h, out);
	o->acc_ok = 0;
	return bad;
}

int csf_ode_rk4_substep(csf_ode *o, double t, double h, double *out) { return rk4_step(o, t, h, out); }

/* a second GSL stepper, of the method's one-step stand-in (struct method's sub) */
int csf_ode_gsl_substep(csf_ode *o, double t, double h, double *out)
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

/* verlet has no error estimate: its global error goes as h^2, so the step comes
   from the tolerance, h = by sqrt(tol / 1e-4) (by / 1000 at the default 1e-10) */
double csf_ode_verlet_h(const csf_ode *o, double by)
{
	double f = sqrt(o->tol / 1e-4);
	return f < 1 ? by * f : by;
}
