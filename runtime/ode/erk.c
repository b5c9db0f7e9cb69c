/*
 * erk.c - explicit Runge-Kutta pairs with a continuous extension as GSL
 * odeiv2 step types, for the tables of dop853.c and dopri5.c (erk.h).
 *
 * A step evaluates k0..k(nstage-1) and the end stage k(nstage) =
 * f(t + h, y1), which is the exact dydt_out, a stage of the continuous
 * extension and the next step's k0 (first same as last: GSL's evolve, which
 * would evaluate a dydt_in for every step, is told the method takes none;
 * a step from where the last ended reuses it, and a step tried again from
 * the same start its k0). The extension's own stages are evaluated on
 * request only (csf_erk_dense_prepare), since most steps are never
 * interpolated.
 *
 * Every sum runs over its stages in ascending order, skipping zero
 * coefficients, so that results do not depend on the compiler (the project
 * builds with -ffp-contract=off).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "csf_int.h"
#include "erk.h"

/*
 * The sums run a block of BLOCK components at a time: the block's partial
 * sums stay in the first-level cache while each stage's block is added in,
 * and a loop of a known length (the block's) is one the compiler can turn
 * into vector instructions at -O2. Each component still sees the same
 * operations in the same order, so the bits do not depend on the blocking.
 */
enum { BLOCK = 256 };

/*
 * out[0..len) = sum of w[j] k[j][0..len) over the nk terms given; then, when
 * y0 is given, yout = y0 + h out (in out's place when yout is NULL).
 */
static inline __attribute__((always_inline)) void combine_block(size_t len, int nk, const double *w,
                                                               const double *const *k, const double *y0, double h,
                                                               double *restrict out, double *restrict yout)
{
	if (nk == 0)
		for (size_t i = 0; i < len; i++) out[i] = 0;
	else {
		const double w0 = w[0], *restrict k0 = k[0];
		for (size_t i = 0; i < len; i++) out[i] = w0 * k0[i];
	}
	for (int j = 1; j < nk; j++) {
		const double wj = w[j], *restrict kj = k[j];
		for (size_t i = 0; i < len; i++) out[i] += wj * kj[i];
	}
	if (y0 && !yout)
		for (size_t i = 0; i < len; i++) out[i] = y0[i] + h * out[i];
	else if (y0)
		for (size_t i = 0; i < len; i++) yout[i] = y0[i] + h * out[i];
}

/*
 * out = sum_j w_j k_j (the nonzero w_j, ascending j); then, when y0 is
 * given, yout = y0 + h out, in out's place when yout is NULL.
 */
static void combine(size_t dim, const double *w, int n, double *const *k, const double *y0, double h, double *out,
                    double *yout)
{
	double wz[CSF_ERK_MAX_K];
	const double *kz[CSF_ERK_MAX_K], *kb[CSF_ERK_MAX_K];
	int nz = 0;
	for (int j = 0; j < n; j++)
		if (w[j] != 0) wz[nz] = w[j], kz[nz++] = k[j];
	for (size_t b = 0; b < dim; b += BLOCK) {
		for (int j = 0; j < nz; j++) kb[j] = kz[j] + b;
		const double *y0b = y0 ? y0 + b : NULL;
		double *yb = yout ? yout + b : NULL;
		if (dim - b >= BLOCK)
			combine_block(BLOCK, nz, wz, kb, y0b, h, out + b, yb);
		else
			combine_block(dim - b, nz, wz, kb, y0b, h, out + b, yb);
	}
}

void csf_erk_combine(size_t dim, const double *w, int n, double *const *k, double *out)
{
	combine(dim, w, n, k, NULL, 0, out, NULL);
}

/* k[s] = f(t0 + c_s h, y0 + h sum_j a_sj k_j). */
static int stage(csf_erk_state *st, const gsl_odeiv2_system *sys, int s, double t0, double h)
{
	double *y = st->ysum;
	combine(st->dim, st->m->a + (size_t)s * (size_t)st->m->nk, s, st->k, st->y0, h, y, NULL);
	return GSL_ODEIV_FN_EVAL(sys, t0 + st->m->c[s] * h, y, st->k[s]);
}

/* Vectors of one state: the nk stages, the extension's 3 + nd, y0, y1 and ysum. */
static size_t nvectors(const csf_erk_method *m) { return (size_t)m->nk + 3 + (size_t)m->nd + 3; }

void *csf_erk_alloc(const csf_erk_method *m, size_t dim)
{
	size_t n = dim ? dim : 1, nf = 3 + (size_t)m->nd;
	if (m->nk > CSF_ERK_MAX_K) return NULL;
	csf_erk_state *st = calloc(1, sizeof *st);
	double **v = calloc((size_t)m->nk + nf, sizeof *v);
	double *mem = calloc(nvectors(m) * n, sizeof *mem);
	if (!st || !v || !mem) {
		free(st);
		free(v);
		free(mem);
		return NULL;
	}
	st->m = m;
	st->dim = dim;
	st->k = v;
	st->f = v + m->nk;
	for (size_t j = 0; j < (size_t)m->nk + nf; j++) v[j] = mem + j * n;
	st->y0 = mem + ((size_t)m->nk + nf) * n;
	st->y1 = st->y0 + n;
	st->ysum = st->y1 + n;
	return st;
}

int csf_erk_apply(void *vstate, size_t dim, double t, double h, double y[], double yerr[], const double dydt_in[],
                  double dydt_out[], const gsl_odeiv2_system *sys)
{
	csf_erk_state *st = vstate;
	const csf_erk_method *m = st->m;
	int status, end = m->nstage;
	/* first same as last: a step from where the last one ended starts from its end stage */
	int fsal = !dydt_in && st->ok && st->have_end && t == st->t0 + st->h && memcmp(y, st->y1, dim * sizeof *y) == 0;
	/* and a step tried again from the same start (a shorter one, the last rejected) keeps its k0 */
	int again = !dydt_in && st->ok && t == st->t0 && memcmp(y, st->y0, dim * sizeof *y) == 0;
	if (fsal) memcpy(st->k[0], st->k[end], dim * sizeof *y);
	/* from here on, k, y0 and y1 are this step's: what they held is gone */
	st->ok = st->have_end = st->stages = st->dense = 0;
	memcpy(st->y0, y, dim * sizeof *y);
	if (dydt_in)
		memcpy(st->k[0], dydt_in, dim * sizeof *dydt_in);
	else if (!fsal && !again && (status = GSL_ODEIV_FN_EVAL(sys, t, st->y0, st->k[0])) != GSL_SUCCESS)
		return status;
	for (int s = 1; s < end; s++)
		if ((status = stage(st, sys, s, t, h)) != GSL_SUCCESS) return status;
	combine(dim, m->a + (size_t)end * (size_t)m->nk, end, st->k, st->y0, h, st->ysum, st->y1);
	if ((status = GSL_ODEIV_FN_EVAL(sys, t + h, st->y1, st->k[end])) != GSL_SUCCESS) return status;
	st->have_end = 1;
	/* y, yerr and dydt_out are written only now that nothing can fail */
	m->error(st, h, st->ysum, yerr);
	memcpy(y, st->y1, dim * sizeof *y);
	if (dydt_out) memcpy(dydt_out, st->k[end], dim * sizeof *dydt_out);
	st->t0 = t;
	st->h = h;
	st->ok = 1;
	return GSL_SUCCESS;
}

int csf_erk_set_driver(void *vstate, const gsl_odeiv2_driver *drv)
{
	(void)vstate;
	(void)drv;
	return GSL_SUCCESS;
}

int csf_erk_reset(void *vstate, size_t dim)
{
	csf_erk_state *st = vstate;
	memset(st->k[0], 0, nvectors(st->m) * (dim ? dim : 1) * sizeof *st->k[0]);
	st->ok = st->have_end = st->stages = st->dense = 0;
	st->t0 = st->h = 0;
	return GSL_SUCCESS;
}

unsigned int csf_erk_order(void *vstate) { return ((csf_erk_state *)vstate)->m->order; }

void csf_erk_free(void *vstate)
{
	csf_erk_state *st = vstate;
	if (!st) return;
	free(st->k[0]);
	free(st->k);
	free(st);
}

static csf_erk_state *state_of(const gsl_odeiv2_step *s)
{
	return s && s->type->apply == csf_erk_apply ? s->state : NULL;
}

void csf_erk_set_scale(gsl_odeiv2_step *s, const double *scale)
{
	csf_erk_state *st = state_of(s);
	if (st) st->scale = scale;
}

void csf_erk_set_rows(gsl_odeiv2_step *s, const uint32_t *rows, size_t n)
{
	csf_erk_state *st = state_of(s);
	if (!st) return;
	st->rows = rows;
	st->nrows = n;
	st->dense = DENSE_NONE;
}

/* F0..F(2+nd) of component i: F(3+r) as csf_erk_combine sums them, the same operations in the same order. */
static void extension(csf_erk_state *st, size_t i)
{
	const csf_erk_method *m = st->m;
	const double h = st->h;
	double *const *f = st->f;
	f[0][i] = st->y1[i] - st->y0[i];
	f[1][i] = h * st->k[0][i] - f[0][i];
	f[2][i] = f[0][i] - h * st->k[m->nstage][i] - f[1][i];
	for (int r = 0; r < m->nd; r++) {
		const double *w = m->d + (size_t)r * (size_t)m->nk;
		double acc = 0;
		int first = 1;
		for (int j = 0; j < m->nk; j++) {
			if (w[j] == 0) continue;
			if (first) acc = w[j] * st->k[j][i];
			else acc += w[j] * st->k[j][i];
			first = 0;
		}
		f[3 + r][i] = acc * h;
	}
}

int csf_erk_dense_prepare(gsl_odeiv2_step *s, const gsl_odeiv2_system *sys, int some)
{
	csf_erk_state *st = state_of(s);
	const csf_erk_method *m = st ? st->m : NULL;
	int status, end = m ? m->nstage : 0;
	/* sys may be NULL for a method whose extension has no stages of its own */
	if (!st || (sys ? sys->dimension != st->dim : m->nk > end + 1)) return GSL_EINVAL;
	if (!st->ok) return GSL_EFAILED;
	int want = some && st->rows ? DENSE_ROWS : DENSE_ALL;
	if (st->dense >= want) return GSL_SUCCESS;
	for (int j = end + 1; j < m->nk && !st->stages; j++)
		if ((status = stage(st, sys, j, st->t0, st->h)) != GSL_SUCCESS) return status;
	st->stages = 1;
	if (want == DENSE_ROWS)
		for (size_t q = 0; q < st->nrows; q++) extension(st, st->rows[q]);
	else
		for (size_t i = 0; i < st->dim; i++) extension(st, i);
	st->dense = want;
	return GSL_SUCCESS;
}

/*
 * Horner's scheme from the inside out, P = F1 + s (F2 + s' (F3 + ...)),
 * the factor of F_r being s for r even and s' for r odd; then
 * y0 + s (F0 + s' P) in the first half of the step and the same
 * polynomial written as y1 - s' (F0 - s P) in the second: each form is
 * exact at its own end (y0 + 0, y1 - 0), where the other would add the
 * rounding of F0 = y1 - y0.
 */
/* Component i of the extension at theta (s1 = 1 - theta). */
static double dense_at(const csf_erk_state *st, size_t i, double theta, double s1)
{
	const int last = 2 + st->m->nd;
	double *const *f = st->f;
	double p = f[last][i];
	for (int r = last; r > 1; r--) p = f[r - 1][i] + (r % 2 ? s1 : theta) * p;
	if (theta <= 0.5) return st->y0[i] + theta * (f[0][i] + s1 * p);
	return st->y1[i] - s1 * (f[0][i] - theta * p);
}

void csf_erk_dense_eval(const gsl_odeiv2_step *s, double theta, double *y, int some)
{
	const csf_erk_state *st = state_of(s);
	if (!st) return;
	int rows = some && st->rows && st->dense == DENSE_ROWS;
	if (!st->dense || (st->dense == DENSE_ROWS && !rows)) { /* misuse: no value rather than a stale one */
		for (size_t i = 0; i < st->dim; i++) y[i] = NAN;
		return;
	}
	const double s1 = 1.0 - theta;
	if (rows)
		for (size_t q = 0; q < st->nrows; q++) y[st->rows[q]] = dense_at(st, st->rows[q], theta, s1);
	else
		for (size_t i = 0; i < st->dim; i++) y[i] = dense_at(st, i, theta, s1);
}

void csf_erk_dense_at(const gsl_odeiv2_step *s, double theta, const uint32_t *idx, size_t n, double *y)
{
	const csf_erk_state *st = state_of(s);
	if (!st) return;
	for (size_t q = 0; q < n; q++) y[idx[q]] = st->dense == DENSE_ALL ? dense_at(st, idx[q], theta, 1.0 - theta) : NAN;
}

void csf_erk_last_step(const gsl_odeiv2_step *s, double *t0, double *h)
{
	const csf_erk_state *st = state_of(s);
	*t0 = st ? st->t0 : 0;
	*h = st ? st->h : 0;
}

int csf_erk_keep(gsl_odeiv2_step *s, struct csf_keeper *k, const char *tag)
{
	csf_erk_state *st = state_of(s);
	if (!st) return 0;
	size_t n = st->dim ? st->dim : 1, nf = 3 + (size_t)st->m->nd;
	char name[64];
	snprintf(name, sizeof name, "%s.erk", tag);
	/* the nk stages, the extension's vectors, y0 and y1: one block (ysum, after them, is work) */
	int bad = csf_keep(k, name, st->k[0], ((size_t)st->m->nk + nf + 2) * n * sizeof(double));
	double v[2] = { st->t0, st->h };
	int flags[4] = { st->ok, st->have_end, st->stages, st->dense };
	snprintf(name, sizeof name, "%s.erk.t0h", tag);
	bad |= csf_keep(k, name, v, sizeof v);
	snprintf(name, sizeof name, "%s.erk.flags", tag);
	bad |= csf_keep(k, name, flags, sizeof flags);
	st->t0 = v[0], st->h = v[1];
	st->ok = flags[0], st->have_end = flags[1], st->stages = flags[2], st->dense = flags[3];
	return bad;
}
