/*
 * ode.c - GSL odeiv2 behind a small checked API.
 *
 * This is the only file of the runtime that includes GSL. GSL's error
 * handler is switched off; every status is checked and turned into a CSF
 * error. The method table is the one list of steppers CSF offers.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "csf.h"
#include "ode.h"

#define CSF_DEFAULT_TOL 1e-10

static const struct method {
	const char *name;
	const gsl_odeiv2_step_type *const *type;
	int jacobian; /* the stepper uses the Jacobian */
} methods[] = {
	{ "rk8pd", &gsl_odeiv2_step_rk8pd, 0 },
	{ "rk2", &gsl_odeiv2_step_rk2, 0 },
	{ "rk4", &gsl_odeiv2_step_rk4, 0 },
	{ "rkf45", &gsl_odeiv2_step_rkf45, 0 },
	{ "rkck", &gsl_odeiv2_step_rkck, 0 },
	{ "rk1imp", &gsl_odeiv2_step_rk1imp, 1 },
	{ "rk2imp", &gsl_odeiv2_step_rk2imp, 1 },
	{ "rk4imp", &gsl_odeiv2_step_rk4imp, 1 },
	{ "bsimp", &gsl_odeiv2_step_bsimp, 1 },
	{ "msadams", &gsl_odeiv2_step_msadams, 0 },
	{ "msbdf", &gsl_odeiv2_step_msbdf, 1 },
};

const char *const csf_method_names[] = { "rk8pd", "rk2", "rk4", "rkf45", "rkck", "rk1imp", "rk2imp",
	                                     "rk4imp", "bsimp", "msadams", "msbdf", NULL };

struct csf_ode {
	gsl_odeiv2_system sys;
	gsl_odeiv2_driver *drv;
	csf_rhs_fn f;
	csf_jac_fn jac;
	void *ctx;
};

static int gsl_rhs(double t, const double y[], double dydt[], void *params)
{
	csf_ode *o = params;
	return o->f(t, y, dydt, o->ctx) ? GSL_EBADFUNC : GSL_SUCCESS;
}

static int gsl_jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
	csf_ode *o = params;
	return o->jac(t, y, dfdy, dfdt, o->ctx) ? GSL_EBADFUNC : GSL_SUCCESS;
}

csf_ode *csf_ode_new(const char *method, size_t n, double hmax, double tol, const double *scale, csf_rhs_fn f,
                     csf_jac_fn jac, void *ctx, char *err, size_t errlen)
{
	gsl_set_error_handler_off();
	const struct method *m = &methods[0];
	if (method) {
		m = NULL;
		for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
			if (strcmp(methods[i].name, method) == 0) m = &methods[i];
		if (!m) {
			snprintf(err, errlen, "unknown method '%s'", method);
			return NULL;
		}
	}
	if (m->jacobian && !jac) {
		snprintf(err, errlen, "method '%s' needs a Jacobian, and this program has none", m->name);
		return NULL;
	}
	if (tol <= 0) tol = CSF_DEFAULT_TOL;
	csf_ode *o = calloc(1, sizeof *o);
	if (!o) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	o->sys = (gsl_odeiv2_system){ gsl_rhs, jac ? gsl_jac : NULL, n, o };
	o->f = f;
	o->jac = jac;
	o->ctx = ctx;
	/* error control as driver_alloc_y_new (a_y = 1, a_dydt = 0), with the absolute
	   tolerance of each component scaled to its unit */
	o->drv = gsl_odeiv2_driver_alloc_scaled_new(&o->sys, *m->type, hmax, tol, tol, 1.0, 0.0, scale);
	if (!o->drv || gsl_odeiv2_driver_set_hmax(o->drv, hmax) != GSL_SUCCESS) {
		snprintf(err, errlen, "cannot set up the integrator");
		csf_ode_free(o);
		return NULL;
	}
	return o;
}

int csf_ode_advance(csf_ode *o, double *t, double t1, double *y, char *err, size_t errlen)
{
	int st = gsl_odeiv2_driver_apply(o->drv, t, t1, y);
	if (st == GSL_SUCCESS) return CSF_ODE_OK;
	if (st == GSL_EBADFUNC) return CSF_ODE_STOPPED;
	snprintf(err, errlen, "%s", gsl_strerror(st));
	return CSF_ODE_FAILED;
}

void csf_ode_free(csf_ode *o)
{
	if (!o) return;
	if (o->drv) gsl_odeiv2_driver_free(o->drv);
	free(o);
}
