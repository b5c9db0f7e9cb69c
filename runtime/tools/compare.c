/*
 * compare.c - csfvm --compare-methods: the speed/accuracy trade on the
 * user's own scene.
 *
 * The scene is run once with the most accurate setting (auto at 1e-13:
 * dop853, or bsimp where the scene is stiff), then with each method and
 * tolerance of a fixed list; every run's rows are kept in memory (a row
 * sink, csf_run_sink) and compared value by value with the reference run.
 * Each run may spend BUDGET times the reference's evaluations (at least
 * BUDGET_MIN): an explicit method on a stiff scene gives up instead of
 * taking millions of steps, and its row says so.
 * The difference printed is the largest over all rows and columns of
 * min(absolute, relative) difference, the measure the accuracy requirement
 * uses (1e-6 absolutely or relatively).
 */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "ode.h"

enum { BUDGET = 100 };
#define BUDGET_MIN 1e6

/* A run's rows: n values each (t and the columns), one after the other. */
typedef struct rows {
	double *v;
	size_t n, nrows, cap;
} rows;

/* The sink that keeps every row's values (csf_sink). */
static int keep_row(void *ctx, const double *v, size_t n)
{
	rows *R = ctx;
	if ((R->nrows + 1) * n > R->cap) {
		size_t cap = R->cap ? 2 * R->cap : 64 * n;
		while (cap < (R->nrows + 1) * n) cap *= 2;
		double *q = realloc(R->v, cap * sizeof *q);
		if (!q) return -1;
		R->v = q, R->cap = cap;
	}
	memcpy(R->v + R->nrows * n, v, n * sizeof *v);
	R->n = n;
	R->nrows++;
	return 0;
}

/* Runs p with method m and tolerance tol; returns its rows (free with free_rows) and exit status. */
static rows *capture(const csf_prog *p, csf_exec_fn exec, const csf_overlay *init, const char *m, double tol, int fixed,
                     unsigned long budget, csf_opts *o, int *st)
{
	char *ebuf = NULL;
	size_t elen = 0;
	rows *R = calloc(1, sizeof *R);
	FILE *e = open_memstream(&ebuf, &elen);
	if (!R || !e) {
		if (e) fclose(e);
		free(R);
		*st = 2;
		return NULL;
	}
	memset(o, 0, sizeof *o);
	o->method = m;
	o->tol = tol;
	o->fixed = fixed;
	o->max_rhs = budget;
	o->init = init;
	csf_sink sink = { keep_row, R, NULL };
	*st = csf_run_sink(p, exec, o, NULL, &sink, e);
	fclose(e);
	free(ebuf);
	return R;
}

static void free_rows(rows *R)
{
	if (R) free(R->v);
	free(R);
}

/* The largest min(absolute, relative) difference between two runs' rows; -1 if their shapes differ. */
static double difference(const rows *a, const rows *b)
{
	double worst = 0;
	if (a->nrows != b->nrows || (a->nrows && a->n != b->n)) return -1;
	for (size_t i = 0; i < a->nrows * a->n; i++) {
		double x = a->v[i], y = b->v[i];
		double d = fabs(x - y), r = y != 0 ? d / fabs(y) : d;
		double m = d < r ? d : r;
		if (isnan(m)) m = INFINITY;
		if (m > worst) worst = m;
	}
	return worst;
}

/* A line of the table on out, never cut by the interruption watchdog (csf_out_begin). */
static void say(FILE *out, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	csf_out_begin();
	vfprintf(out, fmt, ap);
	csf_out_end();
	va_end(ap);
}

/* The rows of method name at each tolerance: a run within budget evaluations compared with ref. */
static void method_rows(const csf_prog *p, csf_exec_fn exec, const csf_overlay *init, const char *name, const rows *ref,
                        unsigned long budget, FILE *out)
{
	static const double tols[] = { 1e-4, 1e-6, 1e-8, 1e-10, 1e-12 };
	csf_opts o;
	int st;
	for (size_t k = 0; k < sizeof tols / sizeof tols[0]; k++) {
		rows *run = capture(p, exec, init, name, tols[k], 0, budget, &o, &st);
		char diff[32];
		double d = run && st == 0 ? difference(run, ref) : -1;
		if (st != 0 && o.run_rhs > budget) snprintf(diff, sizeof diff, "over budget");
		else if (st != 0) snprintf(diff, sizeof diff, "failed (%d)", st);
		else if (d < 0) snprintf(diff, sizeof diff, "mismatch");
		else snprintf(diff, sizeof diff, "%.3g", d);
		say(out, "%-8s %-7g %10.4f %10lu %12lu %14s\n", name, tols[k], o.run_seconds, o.run_steps, o.run_rhs, diff);
		free_rows(run);
	}
}

int csf_compare_methods(const csf_prog *p, csf_exec_fn exec, const csf_overlay *init, FILE *out, FILE *err)
{
	csf_opts o;
	int st;
	rows *ref = capture(p, exec, init, "auto", 1e-13, 0, 0, &o, &st);
	if (st != 0 || !ref) {
		fprintf(err, "error: the reference run (auto, tol 1e-13) failed; run the scene alone to see why\n");
		free_rows(ref);
		return st ? st : 2;
	}
	say(out, "reference: auto at tol 1e-13, %.3f s, %lu steps\n", o.run_seconds, o.run_steps);
	double b = (double)BUDGET * (double)o.run_rhs;
	unsigned long budget = (unsigned long)(b > BUDGET_MIN ? b : BUDGET_MIN);
	say(out, "%-8s %-7s %10s %10s %12s %14s\n", "method", "tol", "seconds", "steps", "rhs_evals", "difference");
	/* auto, then the methods of the method table that have a row (csf_method_compared) */
	method_rows(p, exec, init, "auto", ref, budget, out);
	for (size_t i = 0; csf_method_name(i); i++)
		if (csf_method_compared(csf_method_name(i))) method_rows(p, exec, init, csf_method_name(i), ref, budget, out);
	/* Verlet, where the scene has position/velocity pairs: its own step at the default tolerance
	   (csfvm(1), verlet) */
	if (p->ny > 0) {
		rows *run = capture(p, exec, init, "verlet", 0, 1, budget, &o, &st);
		if (st == 0 && run) {
			say(out, "%-8s %-7g %10.4f %10lu %12lu %14.3g\n", "verlet", csf_method_tol("verlet"), o.run_seconds,
			        o.run_steps, o.run_rhs, difference(run, ref));
		}
		free_rows(run);
	}
	free_rows(ref);
	say(out, "difference: the largest min(absolute, relative) difference from the reference over every row and column;\n"
	         "over budget: the run took more than %d times the reference's evaluations (at least %g) and was stopped\n",
	    BUDGET, BUDGET_MIN);
	return ferror(out) ? 2 : 0;
}
