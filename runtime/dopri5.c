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
 * Every sum runs over its stages in ascending order, skipping zero
 * coefficients, so that results do not depend on the compiler (the project
 * builds with -ffp-contract=off).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "dopri5.h"

enum {
	NSTAGE = 6, /* stages of a step: k0..k5 */
	KEND = 6,   /* k6 = f(t + h, y1) */
	NK = 7,     /* all the stages */
	NF = 4,     /* coefficient vectors F0..F3 of the continuous extension */
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

#define B (a[KEND]) /* the 5th-order weights: k6's row, since y1 is its argument */

typedef struct {
	size_t dim;
	double *k[NK];
	double *f[NF];      /* the continuous extension */
	double *y0, *y1;    /* the last step's start and result */
	double *ysum;       /* work: a stage's argument, or sum b_j k_j */
	double t0, h;       /* the last successful step */
	int ok;             /* k, y0, y1 belong to (t0, h): the last apply succeeded */
	int have_end;       /* k6 is f(t0 + h, y1) */
	int dense;          /* f[] is ready */
} dopri5_state;

/* out[i] = sum over j < n of w[j] k[j][i], the nonzero w[j] only, j ascending. */
static void combine(size_t dim, const double *w, int n, double *const *k, double *out)
{
	int first = 1;
	for (int j = 0; j < n; j++) {
		if (w[j] == 0) continue;
		const double wj = w[j], *kj = k[j];
		if (first)
			for (size_t i = 0; i < dim; i++) out[i] = wj * kj[i];
		else
			for (size_t i = 0; i < dim; i++) out[i] += wj * kj[i];
		first = 0;
	}
	if (first) memset(out, 0, dim * sizeof *out);
}

/* k[s] = f(t0 + c_s h, y0 + h sum_j a_sj k_j). */
static int stage(dopri5_state *st, const gsl_odeiv2_system *sys, int s, double t0, double h)
{
	double *y = st->ysum;
	combine(st->dim, a[s], s, st->k, y);
	for (size_t i = 0; i < st->dim; i++) y[i] = st->y0[i] + h * y[i];
	return GSL_ODEIV_FN_EVAL(sys, t0 + c[s] * h, y, st->k[s]);
}

static void *dopri5_alloc(size_t dim)
{
	dopri5_state *st = calloc(1, sizeof *st);
	size_t n = dim ? dim : 1;
	double *mem = calloc((NK + NF + 3) * n, sizeof *mem);
	if (!st || !mem) {
		free(st);
		free(mem);
		return NULL;
	}
	st->dim = dim;
	for (int j = 0; j < NK; j++) st->k[j] = mem + (size_t)j * n;
	for (int r = 0; r < NF; r++) st->f[r] = mem + (size_t)(NK + r) * n;
	st->y0 = mem + (size_t)(NK + NF) * n;
	st->y1 = st->y0 + n;
	st->ysum = st->y1 + n;
	return st;
}

static int dopri5_apply(void *vstate, size_t dim, double t, double h, double y[], double yerr[],
                        const double dydt_in[], double dydt_out[], const gsl_odeiv2_system *sys)
{
	dopri5_state *st = vstate;
	int status;
	/* first same as last: a step from where the last one ended starts from its k6 */
	int fsal = !dydt_in && st->ok && st->have_end && t == st->t0 + st->h && memcmp(y, st->y1, dim * sizeof *y) == 0;
	/* and a step tried again from the same start (a shorter one, the last rejected) keeps its k0 */
	int again = !dydt_in && st->ok && t == st->t0 && memcmp(y, st->y0, dim * sizeof *y) == 0;
	if (fsal) memcpy(st->k[0], st->k[KEND], dim * sizeof *y);
	/* from here on, k, y0 and y1 are this step's: what they held is gone */
	st->ok = st->have_end = st->dense = 0;
	memcpy(st->y0, y, dim * sizeof *y);
	if (dydt_in)
		memcpy(st->k[0], dydt_in, dim * sizeof *dydt_in);
	else if (!fsal && !again && (status = GSL_ODEIV_FN_EVAL(sys, t, st->y0, st->k[0])) != GSL_SUCCESS)
		return status;
	for (int s = 1; s < NSTAGE; s++)
		if ((status = stage(st, sys, s, t, h)) != GSL_SUCCESS) return status;
	combine(dim, B, NSTAGE, st->k, st->ysum);
	for (size_t i = 0; i < dim; i++) st->y1[i] = st->y0[i] + h * st->ysum[i];
	/* k6: the next step's k0, dydt_out, and a stage of the error estimate and the continuous extension */
	if ((status = GSL_ODEIV_FN_EVAL(sys, t + h, st->y1, st->k[KEND])) != GSL_SUCCESS) return status;
	st->have_end = 1;
	/* y, yerr and dydt_out are written only now that nothing can fail */
	combine(dim, e, NK, st->k, yerr);
	for (size_t i = 0; i < dim; i++) yerr[i] *= h;
	memcpy(y, st->y1, dim * sizeof *y);
	if (dydt_out) memcpy(dydt_out, st->k[KEND], dim * sizeof *dydt_out);
	st->t0 = t;
	st->h = h;
	st->ok = 1;
	return GSL_SUCCESS;
}

static int dopri5_set_driver(void *vstate, const gsl_odeiv2_driver *drv)
{
	(void)vstate;
	(void)drv;
	return GSL_SUCCESS;
}

static int dopri5_reset(void *vstate, size_t dim)
{
	dopri5_state *st = vstate;
	size_t n = dim ? dim : 1;
	memset(st->k[0], 0, (NK + NF + 3) * n * sizeof *st->k[0]);
	st->ok = st->have_end = st->dense = 0;
	st->t0 = st->h = 0;
	return GSL_SUCCESS;
}

/* 5, the order of the solution, as GSL's rkf45 reports it: the control's exponents are 1/order and 1/(order + 1). */
static unsigned int dopri5_order(void *vstate)
{
	(void)vstate;
	return 5;
}

static void dopri5_free(void *vstate)
{
	dopri5_state *st = vstate;
	if (!st) return;
	free(st->k[0]);
	free(st);
}

static const gsl_odeiv2_step_type dopri5_type = {
	"dopri5",
	0, /* no dydt_in: GSL's evolve would evaluate it for every step, where k6 of the step before serves */
	1, /* gives exact dydt_out */
	dopri5_alloc,
	dopri5_apply,
	dopri5_set_driver,
	dopri5_reset,
	dopri5_order,
	dopri5_free,
};

const gsl_odeiv2_step_type *csf_step_dopri5 = &dopri5_type;

static dopri5_state *state_of(const gsl_odeiv2_step *s)
{
	return s && s->type == &dopri5_type ? s->state : NULL;
}

/* F0..F3 of the continuous extension from the 7 stages. */
static void dense_coefficients(dopri5_state *st)
{
	const double h = st->h;
	double *const *f = st->f;
	for (size_t i = 0; i < st->dim; i++) {
		f[0][i] = st->y1[i] - st->y0[i];
		f[1][i] = h * st->k[0][i] - f[0][i];
		f[2][i] = f[0][i] - h * st->k[KEND][i] - f[1][i];
	}
	combine(st->dim, d, NK, st->k, f[3]);
	for (size_t i = 0; i < st->dim; i++) f[3][i] *= h;
}

int csf_dopri5_dense_prepare(gsl_odeiv2_step *s, const gsl_odeiv2_system *sys)
{
	dopri5_state *st = state_of(s);
	if (!st || (sys && sys->dimension != st->dim)) return GSL_EINVAL;
	if (!st->ok) return GSL_EFAILED;
	if (st->dense) return GSL_SUCCESS;
	/* every successful apply has evaluated k6 (its error estimate needs it) */
	dense_coefficients(st);
	st->dense = 1;
	return GSL_SUCCESS;
}

/*
 * Horner's scheme from the inside out, P = F1 + s (F2 + s' F3), then
 * y0 + s (F0 + s' P) in the first half of the step and the same
 * polynomial written as y1 - s' (F0 - s P) in the second: each form is
 * exact at its own end (y0 + 0, y1 - 0), where the other would add
 * the rounding of F0 = y1 - y0.
 */
void csf_dopri5_dense_eval(const gsl_odeiv2_step *s, double theta, double *y)
{
	const dopri5_state *st = state_of(s);
	if (!st) return;
	if (!st->dense) { /* misuse: no value rather than a stale one */
		for (size_t i = 0; i < st->dim; i++) y[i] = NAN;
		return;
	}
	const double s1 = 1.0 - theta;
	double *const *f = st->f;
	for (size_t i = 0; i < st->dim; i++) {
		double p = f[2][i] + s1 * f[3][i];
		p = f[1][i] + theta * p;
		if (theta <= 0.5)
			y[i] = st->y0[i] + theta * (f[0][i] + s1 * p);
		else
			y[i] = st->y1[i] - s1 * (f[0][i] - theta * p);
	}
}

void csf_dopri5_last_step(const gsl_odeiv2_step *s, double *t0, double *h)
{
	const dopri5_state *st = state_of(s);
	*t0 = st ? st->t0 : 0;
	*h = st ? st->h : 0;
}
