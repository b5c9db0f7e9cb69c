/*
 * The DOP853 stepper (runtime/ode/dop853.c): its coefficient table, read back
 * through the stepper itself and held against the order conditions; the
 * order of a step, of the global error and of the continuous extension,
 * measured against exact solutions; the stepper under GSL's own
 * evolve/control/driver, next to rk8pd; a failing evaluation.
 */
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "suites.h"
#include "dop853.h"
#include "erk.h"

/* ---- the table, read back ----
 *
 * With y0 = 0, h = 1 and a system whose n-th evaluation returns the unit
 * vector e_n whatever its arguments, stage n is evaluated at t = c_n and
 * y = sum_j a_nj e_j: the row a_n itself, exactly. The result y1 is b, yerr
 * is err5's weights times the error factor q (one unknown positive number),
 * and the continuous extension at theta is its weights b(theta). So the
 * tests see the table the stepper computes with, not a copy of it.
 */

enum { NK = 16, NSTAGE = 12 };

typedef struct {
	int calls;
	double t[NK], y[NK][NK];
} probe;

static int probe_f(double t, const double y[], double dydt[], void *params)
{
	probe *p = params;
	ck_assert_int_lt(p->calls, NK);
	p->t[p->calls] = t;
	memcpy(p->y[p->calls], y, NK * sizeof *y);
	for (int i = 0; i < NK; i++) dydt[i] = i == p->calls;
	p->calls++;
	return GSL_SUCCESS;
}

#define NTHETA 5
static const double thetas[NTHETA] = { 0.1, 0.25, 0.5, 0.8, 0.95 };

typedef struct {
	long double a[NK][NK], c[NK], b[NK], e5[NK];
	long double bt[NTHETA][NK]; /* the continuous extension's weights at thetas */
} tableau;

static void read_tableau(tableau *tb)
{
	probe p = { 0 };
	gsl_odeiv2_system sys = { probe_f, NULL, NK, &p };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, NK);
	double y[NK] = { 0 }, yerr[NK], dydt[NK];
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 1, y, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	ck_assert_int_eq(p.calls, NSTAGE + 1);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(p.calls, NK);
	for (int n = 0; n < NK; n++) {
		tb->c[n] = p.t[n];
		for (int j = 0; j < NK; j++) tb->a[n][j] = p.y[n][j];
	}
	for (int j = 0; j < NK; j++) {
		tb->b[j] = y[j];
		tb->e5[j] = yerr[j];
		ck_assert(p.y[NSTAGE][j] == y[j]); /* the end stage is evaluated at y1 */
	}
	for (int k = 0; k < NTHETA; k++) {
		double yt[NK];
		csf_erk_dense_eval(s, thetas[k], yt, 0);
		for (int j = 0; j < NK; j++) tb->bt[k][j] = yt[j];
	}
	gsl_odeiv2_step_free(s);
}

START_TEST(test_table_shape)
{
	tableau tb;
	read_tableau(&tb);
	for (int n = 0; n < NK; n++)
		for (int j = n; j < NK; j++) ck_assert_msg(tb.a[n][j] == 0, "a[%d][%d] not explicit", n, j);
	for (int j = NSTAGE; j < NK; j++) ck_assert(tb.b[j] == 0 && tb.e5[j] == 0);
	/* the published c: 1/3, 4/13, 6/7, 7/9 among them, and 1 for stages 11 and 12 */
	ck_assert(tb.c[0] == 0 && tb.c[11] == 1 && tb.c[12] == 1);
	ck_assert(tb.c[5] == 1.0 / 3 && tb.c[7] == 4.0 / 13 && tb.c[10] == 6.0 / 7 && tb.c[15] == 7.0 / 9);
	ck_assert(tb.c[13] == 0.1 && tb.c[14] == 0.2 && tb.c[9] == 0.6 && tb.c[6] == 0.25);
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 1);
	ck_assert_str_eq(gsl_odeiv2_step_name(s), "dop853");
	ck_assert_uint_eq(gsl_odeiv2_step_order(s), 8);
	gsl_odeiv2_step_free(s);
}
END_TEST

/*
 * Row sums: sum_j a_nj = c_n for every stage, the dense stages too. The
 * coefficients are doubles, rounded from the published 30 digits, so the
 * sum is exact only to the rounding of its terms: 1e-15 relative to
 * sum_j |a_nj| (rows 8 to 11 reach 100).
 */
START_TEST(test_row_sums)
{
	tableau tb;
	read_tableau(&tb);
	for (int n = 1; n < NK; n++) {
		long double sum = 0, mag = 0;
		for (int j = 0; j < n; j++) {
			sum += tb.a[n][j];
			mag += fabsl(tb.a[n][j]);
		}
		ck_assert_msg(fabsl(sum - tb.c[n]) <= 1e-15 * mag, "row %d: sum %.20Lg, c %.20Lg", n, sum, tb.c[n]);
	}
}
END_TEST

/*
 * Order conditions. A tree's stage vector g approximates a monomial
 * coef t^deg at t = c_i: c^k is t^k, A g is the integral of g's monomial,
 * g o g' the product. Its condition is then sum_i w_i g_i = the integral of
 * the monomial from 0 to theta: coef theta^(deg+1) / (deg+1), for a tree
 * of order deg + 1 (b, theta = 1: the step; b(theta): the extension).
 * mag is the same sum in absolute values, the scale of its rounding.
 */
typedef struct {
	long double v[NK], mag[NK];
	int deg;
	long double coef;
} gvec;

static gvec g_c(const tableau *tb, int k)
{
	gvec g = { .deg = k, .coef = 1 };
	for (int i = 0; i < NK; i++) g.v[i] = g.mag[i] = powl(tb->c[i], k);
	return g;
}

static gvec g_a(const tableau *tb, gvec u)
{
	gvec g = { .deg = u.deg + 1, .coef = u.coef / (u.deg + 1) };
	for (int i = 0; i < NK; i++)
		for (int j = 0; j < i; j++) {
			g.v[i] += tb->a[i][j] * u.v[j];
			g.mag[i] += fabsl(tb->a[i][j]) * u.mag[j];
		}
	return g;
}

static gvec g_mul(gvec u, gvec w)
{
	gvec g = { .deg = u.deg + w.deg, .coef = u.coef * w.coef };
	for (int i = 0; i < NK; i++) {
		g.v[i] = u.v[i] * w.v[i];
		g.mag[i] = u.mag[i] * w.mag[i];
	}
	return g;
}

#define MAXTREES 64

/* The trees checked: every one of order <= 4, and a selection of orders 5 to 8. */
static int trees(const tableau *tb, gvec *g)
{
	int n = 0;
	gvec c1 = g_c(tb, 1), ac = g_a(tb, c1), ac2 = g_a(tb, g_c(tb, 2)), ac3 = g_a(tb, g_c(tb, 3));
	for (int k = 0; k <= 7; k++) g[n++] = g_c(tb, k);              /* bushy: sum b c^k = 1/(k+1) */
	for (int k = 0; k <= 6; k++) g[n++] = g_a(tb, g_c(tb, k));     /* sum b a c^k = 1/((k+1)(k+2)) */
	for (int k = 0; k <= 5; k++) g[n++] = g_a(tb, g_a(tb, g_c(tb, k)));
	for (int k = 0; k <= 4; k++) g[n++] = g_a(tb, g_a(tb, g_a(tb, g_c(tb, k))));
	for (int k = 1; k <= 5; k++) g[n++] = g_mul(g_c(tb, k), ac); /* sum b c^k a c: 1/8 for k = 1 */
	g[n++] = g_mul(c1, ac2);
	g[n++] = g_mul(g_c(tb, 2), ac3);
	g[n++] = g_mul(g_c(tb, 3), ac3);
	g[n++] = g_mul(ac, ac);                     /* sum b (a c)^2 = 1/20 */
	g[n++] = g_mul(c1, g_mul(ac, ac));
	g[n++] = g_mul(ac, ac2);
	g[n++] = g_mul(ac, g_mul(ac, ac));
	g[n++] = g_mul(ac, ac3);
	g[n++] = g_mul(c1, g_mul(ac2, ac2));
	g[n++] = g_mul(c1, g_mul(ac, ac2));
	g[n++] = g_a(tb, g_mul(c1, ac));
	g[n++] = g_a(tb, g_mul(c1, ac2));
	g[n++] = g_a(tb, g_mul(ac, ac));
	g[n++] = g_mul(c1, g_a(tb, g_mul(c1, ac)));
	g[n++] = g_a(tb, g_mul(c1, g_a(tb, g_mul(c1, ac))));
	g[n++] = g_mul(c1, g_a(tb, g_mul(c1, g_a(tb, g_mul(c1, ac)))));
	g[n++] = g_a(tb, g_a(tb, g_mul(c1, ac)));
	g[n++] = g_mul(g_a(tb, ac), ac);
	g[n++] = g_a(tb, g_mul(g_c(tb, 2), ac2));
	g[n++] = g_mul(g_a(tb, ac), g_a(tb, ac));
	g[n++] = g_a(tb, g_a(tb, g_mul(ac, ac2)));
	ck_assert_int_le(n, MAXTREES);
	return n;
}

/* Checks sum_i w_i g_i against its exact value at theta for the trees up to maxorder; returns the largest error. */
static long double check_conditions(const tableau *tb, const long double *w, long double theta, int maxorder,
                                    double tol, const char *what)
{
	gvec g[MAXTREES];
	int n = trees(tb, g), checked = 0;
	long double worst = 0;
	for (int k = 0; k < n; k++) {
		if (g[k].deg + 1 > maxorder) continue;
		long double phi = 0, exact = g[k].coef * powl(theta, g[k].deg + 1) / (g[k].deg + 1);
		for (int i = 0; i < NK; i++) phi += w[i] * g[k].v[i];
		ck_assert_msg(fabsl(phi - exact) <= tol, "%s, tree %d (order %d): %.17Lg, exact %.17Lg", what, k,
		              g[k].deg + 1, phi, exact);
		worst = fmaxl(worst, fabsl(phi - exact));
		checked++;
	}
	ck_assert_int_ge(checked, 20);
	return worst;
}

START_TEST(test_order_conditions)
{
	tableau tb;
	read_tableau(&tb);
	check_conditions(&tb, tb.b, 1, 8, 1e-13, "b");
	/* and no more: the order-9 quadrature condition fails */
	long double q9 = 0;
	for (int i = 0; i < NK; i++) q9 += tb.b[i] * powl(tb.c[i], 8);
	ck_assert(fabsl(q9 - 1.0L / 9) > 1e-6);
}
END_TEST

/*
 * err5 is the 8th- minus the 5th-order solution, b - b5 times a positive
 * factor: b5 satisfies the conditions to order 5 if and only if err5's
 * weights give 0 on every tree of order <= 5, whatever the factor. On the
 * order-6 quadrature tree they do not: the estimate is of order 5, not more.
 */
START_TEST(test_embedded_order5)
{
	tableau tb;
	read_tableau(&tb);
	gvec g[MAXTREES];
	int n = trees(&tb, g), checked = 0;
	long double scale = 0;
	for (int i = 0; i < NK; i++) scale += fabsl(tb.e5[i]);
	ck_assert(scale > 0);
	for (int k = 0; k < n; k++) {
		if (g[k].deg + 1 > 5) continue;
		long double phi = 0, mag = 0;
		for (int i = 0; i < NK; i++) {
			phi += tb.e5[i] * g[k].v[i];
			mag += fabsl(tb.e5[i]) * g[k].mag[i];
		}
		ck_assert_msg(fabsl(phi) <= 1e-14 * mag, "tree %d (order %d): %Lg of %Lg", k, g[k].deg + 1, phi, mag);
		checked++;
	}
	ck_assert_int_ge(checked, 15);
	long double q6 = 0;
	for (int i = 0; i < NK; i++) q6 += tb.e5[i] * powl(tb.c[i], 5);
	ck_assert(fabsl(q6) > 1e-5 * scale);
}
END_TEST

/* The continuous extension's weights b(theta) satisfy the conditions of order <= 7 at every theta. */
START_TEST(test_dense_conditions)
{
	tableau tb;
	read_tableau(&tb);
	for (int k = 0; k < NTHETA; k++) check_conditions(&tb, tb.bt[k], thetas[k], 7, 1e-12, "b(theta)");
}
END_TEST

/* ---- convergence on problems with known solutions ---- */

typedef struct {
	double lambda;
	int calls, fail_at; /* fail_at >= 0: that evaluation returns GSL_EBADFUNC */
} counter;

static int count_call(counter *n)
{
	return n->calls++ == n->fail_at ? GSL_EBADFUNC : GSL_SUCCESS;
}

/* y' = lambda y */
static int growth_f(double t, const double y[], double dydt[], void *params)
{
	(void)t;
	counter *n = params;
	dydt[0] = n->lambda * y[0];
	return count_call(n);
}

/* the harmonic oscillator x'' = -lambda^2 x as (x, v) */
static int osc_f(double t, const double y[], double dydt[], void *params)
{
	(void)t;
	counter *n = params;
	dydt[0] = n->lambda * y[1];
	dydt[1] = -n->lambda * y[0];
	return count_call(n);
}

/* x = cos(lambda t), v = -sin(lambda t) */
static void osc_exact(double lambda, double t, double *y)
{
	y[0] = cos(lambda * t);
	y[1] = -sin(lambda * t);
}

/*
 * y' = y is scale-free in time: y' = 10 y at h = 0.1, 0.05, 0.025 is y' = y
 * at h = 1, 0.5, 0.25. At h = 0.1 itself the error of a step of y' = y is
 * ~6e-17 (the constant of its h^9 term is ~6.4e-8), below the rounding of
 * y1, and its ratios would be noise; at lambda h = 1 it is ~1e-7, and at
 * 0.25 still ~3e-13, far above it.
 */
#define LAMBDA 10.0

static double step_error(double h, double *yerr_out)
{
	counter n = { LAMBDA, 0, -1 };
	gsl_odeiv2_system sys = { growth_f, NULL, 1, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 1);
	double y = 1, yerr, dydt;
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, h, &y, &yerr, NULL, &dydt, &sys), GSL_SUCCESS);
	ck_assert(dydt == LAMBDA * y); /* FSAL: f at the result */
	gsl_odeiv2_step_free(s);
	*yerr_out = fabs(yerr);
	return fabs(y - exp(LAMBDA * h));
}

START_TEST(test_step_order)
{
	double e[3], ye[3];
	for (int k = 0; k < 3; k++) e[k] = step_error(0.1 / (1 << k), &ye[k]);
	for (int k = 0; k < 2; k++) {
		/* h^9: 512 per halving; 2^8 leaves room for the next terms */
		ck_assert_msg(e[k] / e[k + 1] >= 256, "step error ratio %g (%g, %g)", e[k] / e[k + 1], e[k], e[k + 1]);
		/* the estimate behaves like h^8 */
		ck_assert_msg(ye[k] / ye[k + 1] >= 128, "yerr ratio %g (%g, %g)", ye[k] / ye[k + 1], ye[k], ye[k + 1]);
	}
	/* the estimate is an estimate: not below the true error, not far above */
	ck_assert(ye[0] >= e[0] && ye[0] <= 1e4 * e[0]);
}
END_TEST

/* The relative error at t = 1 of y' = 10 y, y(0) = 1, in n fixed steps. */
static double global_error(int n)
{
	counter c = { LAMBDA, 0, -1 };
	gsl_odeiv2_system sys = { growth_f, NULL, 1, &c };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 1);
	double y = 1, yerr, dydt_in = LAMBDA, dydt_out;
	for (int k = 0; k < n; k++) {
		ck_assert_int_eq(gsl_odeiv2_step_apply(s, (double)k / n, 1.0 / n, &y, &yerr, &dydt_in, &dydt_out, &sys),
		                 GSL_SUCCESS);
		dydt_in = dydt_out;
	}
	gsl_odeiv2_step_free(s);
	ck_assert_int_eq(c.calls, 12 * n); /* 11 stages and the end per step: the first stage is dydt_in */
	return fabs(y / exp(LAMBDA) - 1);
}

START_TEST(test_global_order)
{
	double e[3];
	for (int k = 0; k < 3; k++) e[k] = global_error(10 << k);
	for (int k = 0; k < 2; k++)
		ck_assert_msg(e[k] / e[k + 1] >= pow(2, 7.5), "global error ratio %g (%g, %g)", e[k] / e[k + 1], e[k],
		              e[k + 1]);
}
END_TEST

/*
 * The largest error of the continuous extension at 100 points inside one
 * step of h from t0, against the exact solution; checks that theta = 0 and
 * 1 give y0 and y1 exactly, and that it costs 3 evaluations, once.
 */
static double dense_error(int osc, double lambda, double t0, double h)
{
	counter n = { lambda, 0, -1 };
	gsl_odeiv2_system sys = { osc ? osc_f : growth_f, NULL, osc ? 2 : 1, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, sys.dimension);
	double y0[2], y[2], yerr[2], dydt[2], yt[2], ex[2] = { 0, 0 };
	if (osc)
		osc_exact(lambda, t0, y0);
	else
		y0[0] = exp(lambda * t0);
	memcpy(y, y0, sizeof y);
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, t0, h, y, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	double tl, hl;
	csf_erk_last_step(s, &tl, &hl);
	ck_assert(tl == t0 && hl == h);
	int calls = n.calls;
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, calls + 3);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, calls + 3);
	double err = 0;
	for (int k = 1; k <= 100; k++) {
		double theta = k / 101.0, t = t0 + theta * h;
		csf_erk_dense_eval(s, theta, yt, 0);
		if (osc)
			osc_exact(lambda, t, ex);
		else
			ex[0] = exp(lambda * t);
		for (size_t i = 0; i < sys.dimension; i++) err = fmax(err, fabs(yt[i] - ex[i]) / fabs(y0[0]));
	}
	csf_erk_dense_eval(s, 0, yt, 0);
	for (size_t i = 0; i < sys.dimension; i++) ck_assert(yt[i] == y0[i]);
	csf_erk_dense_eval(s, 1, yt, 0);
	for (size_t i = 0; i < sys.dimension; i++) ck_assert(yt[i] == y[i]);
	gsl_odeiv2_step_free(s);
	return err;
}

static void check_dense_order(int osc, double lambda, double t0, double h)
{
	double e[3];
	for (int k = 0; k < 3; k++) e[k] = dense_error(osc, lambda, t0, h / (1 << k));
	for (int k = 0; k < 2; k++)
		ck_assert_msg(e[k] / e[k + 1] >= 64, "%s: dense error ratio %g (%g, %g)", osc ? "oscillator" : "growth",
		              e[k] / e[k + 1], e[k], e[k + 1]);
}

START_TEST(test_dense_order)
{
	check_dense_order(0, LAMBDA, 0.0, 0.1);
	check_dense_order(1, 1.0, 0.3, 1.0);
}
END_TEST

/*
 * The error's weights: scale {1, 1} is the default's 1 + |y|; a scale that
 * makes component 1 count for nothing changes the factor q, which is
 * common to the components, so yerr changes by one factor.
 */
static void scaled_yerr(const double *scale, double *yerr)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	csf_erk_set_scale(s, scale);
	double y[2] = { 0.6, -0.8 }, dydt[2];
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	gsl_odeiv2_step_free(s);
}

START_TEST(test_scale)
{
	static const double ones[2] = { 1, 1 }, skew[2] = { 1, 1e6 };
	double e0[2], e1[2], e2[2];
	scaled_yerr(NULL, e0);
	scaled_yerr(ones, e1);
	scaled_yerr(skew, e2);
	ck_assert(e0[0] != 0 && e0[1] != 0);
	ck_assert(e0[0] == e1[0] && e0[1] == e1[1]);
	double r = e2[0] / e0[0];
	ck_assert(r > 0 && fabs(r - 1) > 1e-6);
	ck_assert(fabs(e2[1] / e0[1] - r) <= 1e-14 * r);
}
END_TEST

/*
 * The sums over stages run in blocks of components (erk.c): a step of 1000
 * independent equations y_i' = r_i y_i cos t (so across block ends and a
 * short last block) gives each component the bits that a step of that
 * equation alone gives, and its end derivative too; and each is the exact
 * y_i(t0) exp(r_i (sin(t0 + h) - sin t0)) to 1e-12 relative (an 8th-order
 * step of 0.001 with r_i up to 144: r h up to 0.144).
 */
typedef struct {
	size_t first; /* the index of y[0] among the 1000 */
} rates;

static int rates_f(double t, const double y[], double dydt[], void *params)
{
	const rates *r = params;
	size_t n = r->first == (size_t)-1 ? 1000 : 1;
	for (size_t i = 0; i < n; i++) {
		size_t k = r->first == (size_t)-1 ? i : r->first;
		dydt[i] = (1 + (double)k / 7) * y[i] * cos(t);
	}
	return GSL_SUCCESS;
}

START_TEST(test_blocks)
{
	enum { N = 1000 };
	static double y[N], yerr[N], dydt[N];
	rates all = { (size_t)-1 };
	gsl_odeiv2_system sys = { rates_f, NULL, N, &all };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, N);
	for (size_t i = 0; i < N; i++) y[i] = 1 + (double)i / 1000;
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0.25, 0.001, y, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	gsl_odeiv2_step_free(s);
	for (size_t i = 0; i < N; i++) {
		rates one = { i };
		gsl_odeiv2_system sys1 = { rates_f, NULL, 1, &one };
		gsl_odeiv2_step *s1 = gsl_odeiv2_step_alloc(csf_step_dop853, 1);
		double y1 = 1 + (double)i / 1000, e1, d1;
		ck_assert_int_eq(gsl_odeiv2_step_apply(s1, 0.25, 0.001, &y1, &e1, NULL, &d1, &sys1), GSL_SUCCESS);
		gsl_odeiv2_step_free(s1);
		ck_assert_msg(memcmp(&y1, &y[i], sizeof y1) == 0 && memcmp(&d1, &dydt[i], sizeof d1) == 0,
		              "component %zu: %.17g against %.17g alone", i, y[i], y1);
		double r = 1 + (double)i / 7, exact = (1 + (double)i / 1000) * exp(r * (sin(0.251) - sin(0.25)));
		ck_assert_msg(fabs(y[i] - exact) <= 1e-12 * exact, "component %zu: %.17g, exact %.17g", i, y[i], exact);
	}
}
END_TEST

/* ---- under GSL's evolve, control and driver ---- */

typedef struct {
	unsigned long steps, rejected;
	int calls;
	double err;
} run_stats;

/* The oscillator over 10 periods with GSL's driver at 1e-10 (absolute and relative). */
static run_stats drive(const gsl_odeiv2_step_type *type)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, type, 1e-3, 1e-10, 1e-10);
	ck_assert_ptr_nonnull(d);
	double t = 0, t1 = 20 * M_PI, y[2] = { 1, 0 }, ex[2];
	ck_assert_int_eq(gsl_odeiv2_driver_apply(d, &t, t1, y), GSL_SUCCESS);
	ck_assert(t == t1);
	osc_exact(1.0, t1, ex);
	run_stats r = { d->n, d->e->failed_steps, n.calls, fmax(fabs(y[0] - ex[0]), fabs(y[1] - ex[1])) };
	gsl_odeiv2_driver_free(d);
	return r;
}

START_TEST(test_driver)
{
	run_stats dop = drive(csf_step_dop853), rk8 = drive(gsl_odeiv2_step_rk8pd);
	ck_assert_msg(dop.err < 1e-8, "dop853: error %g", dop.err);
	ck_assert_msg(rk8.err < 1e-8, "rk8pd: error %g", rk8.err);
	/*
	 * Comparable to rk8pd, not better: at this tolerance DOP853 takes a few
	 * more steps (its error estimate is the more cautious one: 187 against
	 * 174, with GSL 2.7), but each costs 12 evaluations, not 13, so about
	 * as many evaluations in all (2245 against 2263).
	 */
	ck_assert_msg(dop.steps <= rk8.steps + rk8.steps / 5 && dop.calls <= rk8.calls + rk8.calls / 20,
	              "dop853 %lu steps (%d calls), rk8pd %lu (%d)", dop.steps, dop.calls, rk8.steps, rk8.calls);
	ck_assert(dop.rejected <= 2 && rk8.rejected <= 2);
}
END_TEST

/*
 * Step by step with evolve: after each accepted step the continuous
 * extension is that step's (last_step), its ends are the step's, and its
 * midpoint is as accurate as the steps.
 */
START_TEST(test_evolve_dense)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	gsl_odeiv2_control *c = gsl_odeiv2_control_y_new(1e-10, 1e-10);
	gsl_odeiv2_evolve *e = gsl_odeiv2_evolve_alloc(2);
	static const double scale[2] = { 1, 1 };
	csf_erk_set_scale(s, scale);
	double t = 0, t1 = 20 * M_PI, h = 1e-3, y[2] = { 1, 0 }, ym[2], ex[2], worst = 0;
	int steps = 0;
	while (t < t1) {
		double tb = t, yb[2] = { y[0], y[1] };
		ck_assert_int_eq(gsl_odeiv2_evolve_apply(e, c, s, &sys, &t, t1, &h, y), GSL_SUCCESS);
		double t0, hs;
		csf_erk_last_step(s, &t0, &hs);
		ck_assert(t0 == tb && tb + hs == t);
		ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
		csf_erk_dense_eval(s, 0, ym, 0);
		ck_assert(ym[0] == yb[0] && ym[1] == yb[1]);
		csf_erk_dense_eval(s, 1, ym, 0);
		ck_assert(ym[0] == y[0] && ym[1] == y[1]);
		csf_erk_dense_eval(s, 0.5, ym, 0);
		osc_exact(1.0, t0 + 0.5 * hs, ex);
		worst = fmax(worst, fmax(fabs(ym[0] - ex[0]), fabs(ym[1] - ex[1])));
		steps++;
	}
	ck_assert_msg(worst < 1e-8, "dense error %g", worst);
	ck_assert_int_gt(steps, 20);
	gsl_odeiv2_evolve_free(e);
	gsl_odeiv2_control_free(c);
	gsl_odeiv2_step_free(s);
}
END_TEST

/* ---- a failing evaluation ---- */

/* Every evaluation of a step in turn fails (the first is f(t, y) when there is no dydt_in, else the second stage). */
START_TEST(test_failing_evaluation)
{
	int with_in = _i >= NSTAGE + 1, fail_at = with_in ? _i - (NSTAGE + 1) : _i;
	counter n = { 1.0, 0, fail_at };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	const double y0[2] = { 0.6, -0.8 }, dydt_in[2] = { -0.8, -0.6 };
	double y[2] = { 0.6, -0.8 }, yerr[2] = { 7, 7 }, dydt[2] = { 7, 7 };
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, with_in ? dydt_in : NULL, dydt, &sys), GSL_EBADFUNC);
	ck_assert_int_eq(n.calls, fail_at + 1);
	ck_assert(memcmp(y, y0, sizeof y) == 0);
	ck_assert(yerr[0] == 7 && yerr[1] == 7 && dydt[0] == 7 && dydt[1] == 7);
	/* no continuous extension of a step that failed */
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_EFAILED);
	gsl_odeiv2_step_free(s);
}
END_TEST

/* A failing dense stage: its status, and a later prepare with a working function gives the same extension. */
START_TEST(test_failing_dense_stage)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2), *r = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	double y[2] = { 0.6, -0.8 }, yr[2] = { 0.6, -0.8 }, yerr[2], dydt[2], a[2], b[2];
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	ck_assert_int_eq(gsl_odeiv2_step_apply(r, 0, 0.5, yr, yerr, NULL, dydt, &sys), GSL_SUCCESS);
	n.fail_at = n.calls + _i; /* one of the 3 dense stages */
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_EBADFUNC);
	n.fail_at = -1;
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(csf_erk_dense_prepare(r, &sys, 0), GSL_SUCCESS);
	csf_erk_dense_eval(s, 0.3, a, 0);
	csf_erk_dense_eval(r, 0.3, b, 0);
	ck_assert(a[0] == b[0] && a[1] == b[1]);
	gsl_odeiv2_step_free(s);
	gsl_odeiv2_step_free(r);
}
END_TEST

/*
 * The extension of the rows' components alone (csf_erk_set_rows): each is bit for bit the whole
 * extension's, the others are left as they were, the dense stages are evaluated once a step
 * (a whole prepare after it costs no evaluation), and a whole evaluation after a prepare of the
 * rows alone is NaN, not a stale value.
 */
START_TEST(test_dense_rows)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2), *r = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	static const uint32_t rows[1] = { 1 };
	double y[2] = { 0.6, -0.8 }, yr[2] = { 0.6, -0.8 }, yerr[2], a[2], b[2];
	csf_erk_set_rows(s, rows, 1);
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(gsl_odeiv2_step_apply(r, 0, 0.5, yr, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	int calls = n.calls;
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 1), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, calls + 3); /* the rows' prepare still makes the 3 dense stages */
	ck_assert_int_eq(csf_erk_dense_prepare(r, &sys, 0), GSL_SUCCESS);
	for (double theta = 0; theta <= 1; theta += 0.125) {
		a[0] = 7, a[1] = 7;
		csf_erk_dense_eval(s, theta, a, 1);
		csf_erk_dense_eval(r, theta, b, 0);
		ck_assert(a[0] == 7 && memcmp(&a[1], &b[1], sizeof b[1]) == 0);
	}
	csf_erk_dense_eval(s, 0.5, a, 0);
	ck_assert(isnan(a[0]) && isnan(a[1]));
	calls = n.calls;
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, calls);
	csf_erk_dense_eval(s, 0.3, a, 0);
	csf_erk_dense_eval(r, 0.3, b, 0);
	ck_assert(memcmp(a, b, sizeof a) == 0);
	gsl_odeiv2_step_free(s);
	gsl_odeiv2_step_free(r);
}
END_TEST

/*
 * Chosen components alone (csf_erk_dense_at): each bit for bit the whole extension's, the others
 * left as they were; NaN where only the rows' extension is prepared.
 */
START_TEST(test_dense_at)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	static const uint32_t rows[1] = { 1 }, one[1] = { 0 };
	double y[2] = { 0.6, -0.8 }, yerr[2], a[2], b[2];
	csf_erk_set_rows(s, rows, 1);
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 1), GSL_SUCCESS);
	a[0] = 7, a[1] = 7;
	csf_erk_dense_at(s, 0.3, one, 1, a);
	ck_assert(isnan(a[0]) && a[1] == 7);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	for (double theta = 0; theta <= 1; theta += 0.125) {
		a[0] = 7, a[1] = 7;
		csf_erk_dense_at(s, theta, one, 1, a);
		csf_erk_dense_eval(s, theta, b, 0);
		ck_assert(memcmp(&a[0], &b[0], sizeof b[0]) == 0 && a[1] == 7);
	}
	gsl_odeiv2_step_free(s);
}
END_TEST

/*
 * A first step costs 13 evaluations (k0..k11 and k12 = f at its end), its
 * extension 3 more; the next step, from where it ended, starts from k12
 * (first same as last): 12; a step tried again from the same start keeps
 * its k0: 12; and the results are those of steps from scratch.
 */
START_TEST(test_fsal)
{
	counter n = { 1.0, 0, -1 };
	gsl_odeiv2_system sys = { osc_f, NULL, 2, &n };
	gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(csf_step_dop853, 2), *r = gsl_odeiv2_step_alloc(csf_step_dop853, 2);
	double y[2] = { 0.6, -0.8 }, yr[2] = { 0.6, -0.8 }, yerr[2], a[2], b[2];
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, y, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, NSTAGE + 1);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, NSTAGE + 4);
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0.5, 0.5, y, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, 2 * NSTAGE + 4);
	double y2[2] = { y[0], y[1] };
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 1.0, 0.5, y2, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, 3 * NSTAGE + 4);
	double y3[2] = { y[0], y[1] }; /* tried again from 1.0, shorter */
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 1.0, 0.25, y3, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(n.calls, 4 * NSTAGE + 4);
	/* the same two first steps, each on a fresh stepper: the same values */
	ck_assert_int_eq(gsl_odeiv2_step_apply(r, 0, 0.5, yr, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	gsl_odeiv2_step_reset(r);
	ck_assert_int_eq(gsl_odeiv2_step_apply(r, 0.5, 0.5, yr, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert(y[0] == yr[0] && y[1] == yr[1]);
	ck_assert_int_eq(csf_erk_dense_prepare(r, &sys, 0), GSL_SUCCESS);
	gsl_odeiv2_step_reset(s);
	double ys[2] = { 0.6, -0.8 };
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0, 0.5, ys, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(gsl_odeiv2_step_apply(s, 0.5, 0.5, ys, yerr, NULL, NULL, &sys), GSL_SUCCESS);
	ck_assert_int_eq(csf_erk_dense_prepare(s, &sys, 0), GSL_SUCCESS);
	csf_erk_dense_eval(s, 0.7, a, 0);
	csf_erk_dense_eval(r, 0.7, b, 0);
	ck_assert(a[0] == b[0] && a[1] == b[1]);
	gsl_odeiv2_step_free(s);
	gsl_odeiv2_step_free(r);
}
END_TEST

/* The driver passes the failure on. */
static int fails_late_f(double t, const double y[], double dydt[], void *params)
{
	dydt[0] = y[1];
	dydt[1] = -y[0];
	(void)params;
	return t > 2 ? GSL_EBADFUNC : GSL_SUCCESS;
}

START_TEST(test_failing_driver)
{
	gsl_odeiv2_system sys = { fails_late_f, NULL, 2, NULL };
	gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, csf_step_dop853, 1e-3, 1e-10, 1e-10);
	double t = 0, y[2] = { 1, 0 };
	ck_assert_int_eq(gsl_odeiv2_driver_apply(d, &t, 5, y), GSL_EBADFUNC);
	ck_assert(t <= 2);
	ck_assert(fabs(y[0] - cos(t)) < 1e-9 && fabs(y[1] + sin(t)) < 1e-9); /* the last accepted state */
	gsl_odeiv2_driver_free(d);
}
END_TEST

Suite *dop853_suite(void)
{
	gsl_set_error_handler_off();
	Suite *s = suite_create("dop853");
	TCase *tc = tcase_create("dop853");
	tcase_add_test(tc, test_table_shape);
	tcase_add_test(tc, test_row_sums);
	tcase_add_test(tc, test_order_conditions);
	tcase_add_test(tc, test_embedded_order5);
	tcase_add_test(tc, test_dense_conditions);
	tcase_add_test(tc, test_step_order);
	tcase_add_test(tc, test_global_order);
	tcase_add_test(tc, test_dense_order);
	tcase_add_test(tc, test_scale);
	tcase_add_test(tc, test_blocks);
	tcase_add_test(tc, test_driver);
	tcase_add_test(tc, test_evolve_dense);
	tcase_add_loop_test(tc, test_failing_evaluation, 0, 2 * NSTAGE + 1);
	tcase_add_loop_test(tc, test_failing_dense_stage, 0, 3);
	tcase_add_test(tc, test_dense_rows);
	tcase_add_test(tc, test_dense_at);
	tcase_add_test(tc, test_fsal);
	tcase_add_test(tc, test_failing_driver);
	suite_add_tcase(s, tc);
	return s;
}
