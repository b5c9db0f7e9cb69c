/*
 * dopri5.c - the Dormand-Prince 5(4) pair (Hairer's DOPRI5, SciPy's RK45,
 * with its free 4th-order continuous extension) as a GSL odeiv2 step type.
 *
 * A step takes 6 stages k0..k5 (k0 = f(t, y0) may come in as dydt_in),
 * y1 = y0 + h sum b_j k_j with b = row 6 of a, and k6 = f(t + h, y1),
 * which is the exact dydt_out, a stage of the error estimate and of the
 * continuous extension, and the next step's k0 (first same as last: GSL's
 * evolve, which would evaluate a dydt_in for every step, is told the
 * method takes none; a step from where the last ended reuses k6, and a
 * step tried again from the same start its k0). So a step costs 6
 * evaluations, 7 for the first, 6 after a rejected one.
 * The error estimate is the embedded one of dopri5.f: yerr = h sum e_j k_j
 * over the 7 stages, e = b - b4, the 5th- minus the embedded 4th-order
 * solution (which behaves like h^5); GSL's control weighs it itself.
 *
 * The continuous extension needs no more stages: it is Hairer's CONTD5,
 *   y(t0 + s h) = y0 + s (F0 + s' (F1 + s (F2 + s' F3)))
 * with s' = 1 - s, F0 = y1 - y0, F1 = h k0 - F0, F2 = F0 - h k6 - F1 and
 * F3 = h sum_j d_j k_j, of order 4 (Shampine's choice of the free
 * parameter, as in dopri5.f and SciPy's RK45.P, whose last column is d).
 *
 * Coefficients: the published Dormand-Prince (1980) tableau as given in
 * Hairer, Norsett and Wanner, Solving ODEs I (Sec. II.5) and in
 * dopri5.f / SciPy's scipy/integrate/_ivp/rk.py (class RK45: C, A, B, E,
 * P). They are written as the published fractions, which the compiler
 * rounds once each. SciPy's E is b4 - b; here it is b - b4, as in
 * dopri5.f.
 *
 * The stepping, first same as last and the extension are erk.c's, shared
 * with dop853.c; this file has the tables and the error estimate.
 */

#include <gsl/gsl_odeiv2.h>

#include "dopri5.h"
#include "erk.h"

enum {
	NSTAGE = 6, /* stages of a step: k0..k5 */
	NK = 7,     /* all the stages, k6 = f(t + h, y1) the last */
};

static const double a[NK][NK] = {
	[1] = {
		[0] = 1.0 / 5,
	},
	[2] = {
		[0] = 3.0 / 40, [1] = 9.0 / 40,
	},
	[3] = {
		[0] = 44.0 / 45, [1] = -56.0 / 15, [2] = 32.0 / 9,
	},
	[4] = {
		[0] = 19372.0 / 6561, [1] = -25360.0 / 2187, [2] = 64448.0 / 6561, [3] = -212.0 / 729,
	},
	[5] = {
		[0] = 9017.0 / 3168, [1] = -355.0 / 33, [2] = 46732.0 / 5247, [3] = 49.0 / 176,
		[4] = -5103.0 / 18656,
	},
	[6] = {
		[0] = 35.0 / 384, [2] = 500.0 / 1113, [3] = 125.0 / 192, [4] = -2187.0 / 6784,
		[5] = 11.0 / 84,
	},
};

static const double c[NK] = {
	[0] = 0.0, [1] = 1.0 / 5, [2] = 3.0 / 10, [3] = 4.0 / 5, [4] = 8.0 / 9, [5] = 1.0, [6] = 1.0,
};

/* the error's weights: b minus the embedded 4th-order weights */
static const double e[NK] = {
	[0] = 71.0 / 57600, [2] = -71.0 / 16695, [3] = 71.0 / 1920, [4] = -17253.0 / 339200,
	[5] = 22.0 / 525, [6] = -1.0 / 40,
};

/* the continuous extension's F3 = h sum d_j k_j */
static const double d[NK] = {
	[0] = -12715105075.0 / 11282082432.0, [2] = 87487479700.0 / 32700410799.0,
	[3] = -10690763975.0 / 1880347072.0, [4] = 701980252875.0 / 199316789632.0,
	[5] = -1453857185.0 / 822651844.0, [6] = 69997945.0 / 29380423.0,
};

/* yerr = h sum e_j k_j: the embedded estimate, which GSL's control weighs itself. */
static void error_estimate(const csf_erk_state *st, double h, double *bsum, double *yerr)
{
	(void)bsum;
	csf_erk_combine(st->dim, e, NK, st->k, yerr);
	for (size_t i = 0; i < st->dim; i++) yerr[i] *= h;
}

/* 5, the order of the solution, as GSL's rkf45 reports it: the control's exponents are 1/order and 1/(order + 1). */
static const csf_erk_method dopri5 = {
	"dopri5", 5, NSTAGE, NK, 1, &a[0][0], c, d, error_estimate,
};

static void *dopri5_alloc(size_t dim) { return csf_erk_alloc(&dopri5, dim); }

static const gsl_odeiv2_step_type dopri5_type = {
	"dopri5",
	0, /* no dydt_in: GSL's evolve would evaluate it for every step, where k6 of the step before serves */
	1, /* gives exact dydt_out */
	dopri5_alloc,
	csf_erk_apply,
	csf_erk_set_driver,
	csf_erk_reset,
	csf_erk_order,
	csf_erk_free,
};

const gsl_odeiv2_step_type *csf_step_dopri5 = &dopri5_type;
