/*
 * The stability guard's two halves against known answers: each method's
 * largest stable step on the real and the imaginary axis (ode.c, from the
 * stability polynomial it measures on its own stepper) against the roots
 * of the published polynomials, and the eigenvalue estimates (spectrum.c)
 * on matrices whose spectra are known.
 */
#include <math.h>

#include "suites.h"
#include "ode.h"
#include "spectrum.h"

static int unused_rhs(double t, const double *y, double *dydt, void *ctx)
{
	(void)t, (void)ctx;
	dydt[0] = y[1], dydt[1] = -y[0];
	return 0;
}

static int unused_jac(double t, const double *y, double *dfdy, double *dfdt, void *ctx)
{
	(void)t, (void)y, (void)ctx;
	dfdy[0] = 0, dfdy[1] = 1, dfdy[2] = -1, dfdy[3] = 0, dfdt[0] = dfdt[1] = 0;
	return 0;
}

/* The largest stable h |lambda| of method (fixed steps or not) along re + i im, in a run of 1e9 time scales. */
static double limit(const char *method, int fixed, double re, double im)
{
	static const uint32_t vpair[2] = { 2, 0 };
	static const double scale[2] = { 1, 1 };
	char err[128];
	csf_ode *o = csf_ode_new(method, fixed, 2, 0.1, 0.1, 0, 0, NULL, scale, vpair, unused_rhs, unused_jac, NULL, err, sizeof err);
	ck_assert_msg(o != NULL, "%s: %s", method, err);
	double s = csf_ode_stable_step(o, fixed, re, im, 1e9);
	csf_ode_free(o);
	return s;
}

START_TEST(test_limits_analytic)
{
	/* classical RK4, R = 1 + z + z^2/2 + z^3/6 + z^4/24: |R(-2.785294)| = 1, |R(i 2 sqrt 2)| = 1 */
	ck_assert_double_eq_tol(limit("rk4", 1, -1, 0), 2.7852935634, 1e-6);
	ck_assert_double_eq_tol(limit("rk4", 1, 0, 1), 2 * sqrt(2), 1e-6);
	/* a step of rk4 is 10 times as long for lambda 10 times smaller */
	ck_assert_double_eq_tol(limit("rk4", 1, 0, 0.1), 20 * sqrt(2), 1e-5);
	/* GSL's rk4 with error control takes two half steps: R(z/2)^2, twice the range */
	ck_assert_double_eq_tol(limit("rk4", 0, -1, 0), 2 * 2.7852935634, 2e-6);
	/* GSL's rk2 advances the third-order solution: R = 1 + z + z^2/2 + z^3/6, real root of R = -1
	   at -2.5127453266, and |R(iy)|^2 = 1 - y^4/12 + y^6/36 = 1 at y = sqrt 3 */
	ck_assert_double_eq_tol(limit("rk2", 1, -1, 0), 2.5127453266, 1e-6);
	ck_assert_double_eq_tol(limit("rk2", 1, 0, 1), sqrt(3), 1e-6);
	/* dopri5: R = sum_0^5 z^j/j! + z^6/600, the real root of R = -1 at -3.3066 */
	ck_assert_double_eq_tol(limit("dopri5", 0, -1, 0), 3.3066, 1e-3);
	/* verlet on x'' = -w^2 x: stable for h w < 2; a real pair +-a grows by itself, limits nothing */
	ck_assert_double_eq_tol(limit("verlet", 1, 0, 1), 2, 1e-6);
	ck_assert(isinf(limit("verlet", 1, -1, 0)));
	/* a mode that grows is not a stability limit for a Runge-Kutta method either */
	ck_assert(isinf(limit("rk4", 1, 1, 0)));
	/* implicit methods are not limited; msadams's changing order is not known */
	ck_assert(isinf(limit("rk4imp", 1, -1, 0)));
	ck_assert(isinf(limit("bsimp", 0, 0, 1)));
	ck_assert(isnan(limit("msadams", 0, -1, 0)));
}
END_TEST

/* J v for a dense matrix (row-major, n by n) held in ctx. */
typedef struct dense { size_t n; const double *a; } dense;
static int dense_jvp(void *ctx, const double *v, double *jv)
{
	const dense *d = ctx;
	for (size_t i = 0; i < d->n; i++) {
		jv[i] = 0;
		for (size_t j = 0; j < d->n; j++) jv[i] += d->a[i * d->n + j] * v[j];
	}
	return 0;
}

START_TEST(test_spectrum_known)
{
	csf_eigs e;
	double ratio;
	int exact;
	/* an oscillator (+-3i) beside two decays (-1, -0.5): the dominant pair is imaginary */
	static const double a1[16] = { 0, 1, 0, 0, -9, 0, 0, 0, 0, 0, -1, 0.3, 0, 0, 0, -0.5 };
	dense d1 = { 4, a1 };
	csf_spectrum *s = csf_spectrum_new(4);
	ck_assert_int_eq(csf_spectrum_dominant(s, dense_jvp, &d1, 100, &e), 0);
	ck_assert_double_eq_tol(e.rho, 3, 1e-6);
	ck_assert_int_eq(e.n, 2);
	ck_assert_double_eq_tol(fabs(e.im[0]), 3, 1e-6);
	ck_assert_double_eq_tol(e.re[0], 0, 1e-6);
	ck_assert_int_eq(csf_spectrum_ratio(s, dense_jvp, &d1, 1e-7, &ratio, &exact), 0);
	ck_assert(exact);
	ck_assert_double_eq_tol(ratio, 6, 1e-6);
	csf_spectrum_free(s);

	/* stiff: -1 and -1e6, coupled */
	static const double a2[4] = { -1, 0, 5, -1e6 };
	dense d2 = { 2, a2 };
	s = csf_spectrum_new(2);
	ck_assert_int_eq(csf_spectrum_dominant(s, dense_jvp, &d2, 100, &e), 0);
	ck_assert_double_eq_tol(e.rho, 1e6, 1e-3);
	ck_assert_int_eq(csf_spectrum_ratio(s, dense_jvp, &d2, 1e-7, &ratio, &exact), 0);
	ck_assert(exact);
	ck_assert_double_eq_tol(ratio, 1e6, 1e-2);
	/* warm: the same matrix again costs two products */
	unsigned long before = csf_spectrum_products(s);
	ck_assert_int_eq(csf_spectrum_dominant(s, dense_jvp, &d2, 100, &e), 0);
	ck_assert_uint_eq(csf_spectrum_products(s) - before, 2);
	csf_spectrum_free(s);

	/* a real pair +-2 (x'' = 4 x) dominates an oscillation +-i (y'' = -y): J^2's lowest is -1 */
	static const double a3[16] = { 0, 0, 1, 0, 0, 0, 0, 1, 4, 0, 0, 0, 0, -1, 0, 0 };
	dense d3 = { 4, a3 };
	s = csf_spectrum_new(4);
	ck_assert_int_eq(csf_spectrum_dominant(s, dense_jvp, &d3, 100, &e), 0);
	ck_assert_double_eq_tol(e.rho, 2, 2e-3); /* power iteration: the plane invariant to 1e-3 */
	ck_assert_double_eq_tol(fabs(e.re[0]), 2, 2e-3);
	ck_assert_double_eq_tol(e.re[0] + e.re[1], 0, 2e-3);
	double mu;
	ck_assert_int_eq(csf_spectrum_lowest_square(s, dense_jvp, &d3, e.rho * e.rho, &mu), 0);
	ck_assert_double_eq_tol(mu, -1, 1e-5);
	csf_spectrum_free(s);

	/* free motion: J nilpotent, every eigenvalue 0 */
	static const double a4[4] = { 0, 1, 0, 0 };
	dense d4 = { 2, a4 };
	s = csf_spectrum_new(2);
	ck_assert_int_eq(csf_spectrum_dominant(s, dense_jvp, &d4, 100, &e), 0);
	ck_assert_double_eq_tol(e.rho, 0, 1e-12);
	ck_assert_int_eq(csf_spectrum_ratio(s, dense_jvp, &d4, 1e-7, &ratio, &exact), 0);
	ck_assert_double_eq(ratio, 0);
	csf_spectrum_free(s);
}
END_TEST

Suite *stability_suite(void)
{
	Suite *s = suite_create("stability");
	TCase *tc = tcase_create("core");
	tcase_add_test(tc, test_limits_analytic);
	tcase_add_test(tc, test_spectrum_known);
	suite_add_tcase(s, tc);
	return s;
}
