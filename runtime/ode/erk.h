/*
 * erk.h - explicit Runge-Kutta pairs with a continuous extension, as GSL
 * odeiv2 step types (erk.c): the machinery dop853.c and dopri5.c share.
 */
#ifndef CSF_ERK_H
#define CSF_ERK_H

#include <stdint.h>
#include <gsl/gsl_odeiv2.h>

struct csf_erk_state;

/*
 * A method: the stages k0..k(nstage-1) of a step, y1 = y0 + h sum b_j k_j
 * with b = row nstage of a, the end stage k(nstage) = f(t + h, y1), and
 * the extension's own stages up to k(nk-1), each k_s = f(t0 + c_s h,
 * y0 + h sum_j a_sj k_j) (a: nk rows of nk). The continuous extension is
 * Hairer's y(t0 + s h) = y0 + s (F0 + s' (F1 + s (F2 + s' (F3 + ...)))),
 * s' = 1 - s, F0 = y1 - y0, F1 = h k0 - F0, F2 = F0 - h k(nstage) - F1 and
 * F(3+r) = h sum_j d_rj k_j for the nd rows of d (nk each). error writes the
 * step's error estimate into yerr, given bsum = sum b_j k_j (which it may
 * overwrite); it may use the extension's vectors f as work space, which
 * csf_erk_apply has marked as not ready.
 */
/* The most stages (nk) a method may have: dop853's 16. */
#define CSF_ERK_MAX_K 16

typedef struct csf_erk_method {
	const char *name;
	unsigned order;
	int nstage, nk, nd;
	const double *a, *c, *d;
	void (*error)(const struct csf_erk_state *st, double h, double *bsum, double *yerr);
} csf_erk_method;

/* A stepper's state; a method's error function reads k, y0, y1, dim and scale. */
typedef struct csf_erk_state {
	const csf_erk_method *m;
	size_t dim;
	double **k;         /* the nk stages */
	double **f;         /* F0..F(2+nd), the continuous extension */
	double *y0, *y1;    /* the last step's start and result */
	double *ysum;       /* work: a stage's argument, or sum b_j k_j */
	const double *scale; /* the error norm's absolute scale, or NULL */
	double t0, h;       /* the last successful step */
	int ok;             /* k, y0, y1 belong to (t0, h): the last apply succeeded */
	int have_end;       /* k(nstage) is f(t0 + h, y1) */
	int stages;         /* the extension's own stages are evaluated */
	int dense;          /* f[] is ready: DENSE_ROWS, for the components rows[] alone; DENSE_ALL, for all */
	const uint32_t *rows; /* the components the rows need (csf_erk_set_rows), or NULL: all */
	size_t nrows;
} csf_erk_state;

enum { DENSE_NONE, DENSE_ROWS, DENSE_ALL };

/* out[i] = sum over j < n of w[j] k[j][i], the nonzero w[j] only, j ascending. */
void csf_erk_combine(size_t dim, const double *w, int n, double *const *k, double *out);

/* The step type functions of a method m: alloc is the method's (it calls this). */
void *csf_erk_alloc(const csf_erk_method *m, size_t dim);
int csf_erk_apply(void *state, size_t dim, double t, double h, double y[], double yerr[], const double dydt_in[],
                  double dydt_out[], const gsl_odeiv2_system *sys);
int csf_erk_set_driver(void *state, const gsl_odeiv2_driver *d);
int csf_erk_reset(void *state, size_t dim);
unsigned int csf_erk_order(void *state);
void csf_erk_free(void *state);

/*
 * For a stepper of one of these types (dop853, dopri5; GSL_EINVAL or
 * nothing for another): the scale of the error norm (dop853's weighs
 * components as the control does; the array must outlive the stepper);
 * the continuous extension of the last successful apply, prepared with the
 * evaluations its stages need (none for dopri5, 3 for dop853; once a step;
 * GSL_EFAILED when the last apply failed; sys may be NULL when no stage is
 * needed) and evaluated at t0 + theta h
 * (theta = 0 and 1 give y0 and y1 exactly; NaN before a prepare); and that
 * step's t0 and h. With rows set (csf_erk_set_rows: the components the
 * output rows need, ascending; the array must outlive the stepper), a
 * prepare and an eval for the rows (some = 1) compute those components
 * alone, bit for bit as a whole one does; the others of y are left as
 * they were.
 */
void csf_erk_set_scale(gsl_odeiv2_step *s, const double *scale);
void csf_erk_set_rows(gsl_odeiv2_step *s, const uint32_t *rows, size_t n);
int csf_erk_dense_prepare(gsl_odeiv2_step *s, const gsl_odeiv2_system *sys, int some);
void csf_erk_dense_eval(const gsl_odeiv2_step *s, double theta, double *y, int some);
/* The components idx[0..n) alone of a whole extension's value (csf_erk_dense_eval's, bit for bit),
   into y[idx[q]]; NaN there when the extension prepared is not the whole one. */
void csf_erk_dense_at(const gsl_odeiv2_step *s, double theta, const uint32_t *idx, size_t n, double *y);
void csf_erk_last_step(const gsl_odeiv2_step *s, double *t0, double *h);

/* Saves or restores the last step's stages, extension and flags under tag (a checkpoint): 0 or -1. */
struct csf_keeper;
int csf_erk_keep(gsl_odeiv2_step *s, struct csf_keeper *k, const char *tag);

#endif
