/*
 * ref.h - what the hand-written reference programs (nbody.c, chain.c) share:
 * their command line, the integrator set up as runtime/ode/ode.c sets it up
 * (GSL rk8pd, driver_alloc_scaled_new with h0 = by, epsabs = epsrel = 1e-10,
 * a_y = 1, a_dydt = 0 and the absolute tolerance of each property scaled as
 * csfc scales it: by its largest initial magnitude over the objects when
 * that is below one unit;
 * hmax = by, evolve_apply up to each t_k = k*by, a step that would end
 * just short of it stretched to end there, as csf_ode_step), and the output loop of
 * runtime/run/run.c, numbers formatted by the runtime's own csf_fmt_double.
 * Each program supplies its right-hand side, where a watched object's pos
 * and v sit in the state, and a check run at every row under --stats.
 */
#ifndef CSF_BENCH_REF_H
#define CSF_BENCH_REF_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "csf_int.h"

static const char *ref_name = "ref";

static void ref_die(const char *msg)
{
	fprintf(stderr, "%s: %s\n", ref_name, msg);
	exit(2);
}

/* PROG [--stats] IC_FILE TILL BY WATCH...: opens IC_FILE; *first_watch indexes the WATCH arguments. */
static FILE *ref_args(int argc, char **argv, int *check, double *till, double *by, int *first_watch)
{
	int a = 1;
	*check = a < argc && strcmp(argv[a], "--stats") == 0;
	a += *check;
	if (argc - a < 3) ref_die("usage: [--stats] IC_FILE TILL BY WATCH...");
	FILE *f = fopen(argv[a], "r");
	if (!f) ref_die("cannot open the initial conditions");
	*till = strtod(argv[a + 1], NULL);
	*by = strtod(argv[a + 2], NULL);
	if (!(*by > 0) || !(*till >= 0)) ref_die("TILL and BY must be positive numbers");
	*first_watch = a + 3;
	return f;
}

/* The WATCH arguments as object indices below n; their count in *nw. */
static size_t *ref_watch(int argc, char **argv, int first, size_t n, int *nw)
{
	*nw = argc - first;
	size_t *w = malloc((*nw ? (size_t)*nw : 1) * sizeof *w);
	if (!w) ref_die("out of memory");
	for (int k = 0; k < *nw; k++) {
		long v = strtol(argv[first + k], NULL, 10);
		if (v < 0 || (size_t)v >= n) ref_die("watch index out of range");
		w[k] = (size_t)v;
	}
	return w;
}

/*
 * Integrates y (dim doubles) with rhs and prints csfvm's CSV: pos and v of
 * every watched object i, found at y[6*i + off[c]] (c: pos.x..z, v.x..z).
 * Calls row(y) at every output row when given. Returns the number of output
 * steps, or exits on failure.
 */
static double ref_run(int (*rhs)(double, const double *, double *, void *), size_t dim, double *y, double till,
                      double by, const size_t *w, int nw, const int *off, void (*row)(const double *))
{
	gsl_set_error_handler_off();
	gsl_odeiv2_system sys = { rhs, NULL, dim, NULL };
	/* the state is made of objects of two 3-vectors (pos and v); each property's tolerance
	   scale is min(1, the largest |initial value| it has in any object) */
	double *scale = malloc(dim * sizeof *scale), big[2] = { 0, 0 };
	if (!scale) ref_die("out of memory");
	for (size_t i = 0; i + 2 < dim; i += 3) {
		double mag = sqrt(y[i] * y[i] + y[i + 1] * y[i + 1] + y[i + 2] * y[i + 2]);
		if (mag > big[i % 6 / 3]) big[i % 6 / 3] = mag;
	}
	for (size_t i = 0; i < dim; i++) scale[i] = big[i % 6 / 3] > 0 && big[i % 6 / 3] < 1 ? big[i % 6 / 3] : 1;
	gsl_odeiv2_driver *drv =
		gsl_odeiv2_driver_alloc_scaled_new(&sys, gsl_odeiv2_step_rk8pd, by, 1e-10, 1e-10, 1.0, 0.0, scale);
	if (!drv || gsl_odeiv2_driver_set_hmax(drv, by) != GSL_SUCCESS) ref_die("cannot set up the integrator");

	static const char *const comp[] = { "pos.x [m]", "pos.y [m]", "pos.z [m]", "v.x [m/s]", "v.y [m/s]", "v.z [m/s]" };
	fputs("t", stdout);
	for (int k = 0; k < nw; k++)
		for (int c = 0; c < 6; c++) printf(",p%zu.%s", w[k], comp[c]);
	putchar('\n');

	/* The last k with k*by <= till, allowing for till/by's rounding (as runtime/run/run.c). */
	double kmax = floor(till / by);
	if ((kmax + 1) * by <= till * (1 + 1e-12)) kmax += 1;

	double t = 0;
	char b[32];
	for (double k = 0; k <= kmax; k++) {
		double tk = k * by;
		while (t < tk) {
			if (drv->h > drv->hmax) drv->h = drv->hmax;
			double left = tk - t;
			if (drv->h <= left && left <= drv->h * (1 + 1e-4)) drv->h = nextafter(left, INFINITY);
			int st = gsl_odeiv2_evolve_apply(drv->e, drv->c, drv->s, &sys, &t, tk, &drv->h, y);
			if (st != GSL_SUCCESS) {
				fprintf(stderr, "%s: integration failed at t=%g: %s\n", ref_name, t, gsl_strerror(st));
				exit(1);
			}
		}
		t = tk;
		csf_fmt_double(b, tk);
		fputs(b, stdout);
		for (int q = 0; q < nw; q++)
			for (int c = 0; c < 6; c++) {
				csf_fmt_double(b, y[6 * w[q] + (size_t)off[c]]);
				putchar(',');
				fputs(b, stdout);
			}
		putchar('\n');
		if (row) row(y);
	}
	gsl_odeiv2_driver_free(drv);
	free(scale);
	if (fflush(stdout) != 0 || ferror(stdout)) ref_die("cannot write output");
	return kmax;
}

#endif
