/*
 * stable.c - the largest stable step of a method for a mode of df/dy
 * (csf_ode_stable_step), from its stability polynomial or, for verlet,
 * its factor on x'' = lambda^2 x.
 */
#include <math.h>
#include <string.h>

#include "ode_int.h"

/* y' = N y with N the shift, N e_j = e_(j+1), for measured_poly. */
static int shift_rhs(double t, const double y[], double dydt[], void *params)
{
	(void)t, (void)params;
	dydt[0] = 0;
	for (int j = 1; j < NSTAB; j++) dydt[j] = y[j - 1];
	return GSL_SUCCESS;
}

/*
 * The method's stability polynomial R(z) = sum c_j z^j, the factor one
 * step multiplies y by on y' = lambda y, z = h lambda, in o->stab (struct
 * stability's poly and poly_fixed): for the classical rk4 of fixed steps
 * 1/j!, for a GSL stepper measured by one step of h = 1 on y' = N y (N the
 * shift) from e_0, which ends at R(N) e_0 = (c_0, c_1, ...): the polynomial
 * of the code that runs, not of a table that might not match it (GSL's rk2
 * takes the third-order solution; its rk4, two half steps). 0, or -1 when
 * memory runs out.
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

const struct stability
	csf_ode_stab_measured = { measured_poly, measured_poly, poly_excess, 0 }, /* explicit Runge-Kutta: the code's polynomial */
	csf_ode_stab_rk4 = { measured_poly, rk4_poly, poly_excess, 0 },           /* fixed steps: the classical rk4's */
	csf_ode_stab_verlet = { NULL, NULL, verlet_excess, 0 },                   /* on x'' = lambda^2 x */
	csf_ode_stab_implicit = { NULL, NULL, NULL, INFINITY },                   /* no step is unstable */
	csf_ode_stab_unknown = { NULL, NULL, NULL, NAN };                         /* msadams, whose order varies */

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
