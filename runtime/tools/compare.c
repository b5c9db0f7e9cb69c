/*
 * compare.c - csfvm --compare-methods: the speed/accuracy trade on the
 * user's own scene.
 *
 * The scene is run once with the most accurate setting (rk8pd at 1e-13),
 * then with each method and tolerance of a fixed list; every run's CSV is
 * captured in memory and compared value by value with the reference run.
 * The difference printed is the largest over all rows and columns of
 * min(absolute, relative) difference, the measure the accuracy requirement
 * uses (1e-6 absolutely or relatively).
 */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "csf.h"
#include "ode.h"

/* Runs p with method m and tolerance tol; returns its output (malloc'd text) and exit status. */
static char *capture(const csf_prog *p, csf_exec_fn exec, const char *m, double tol, int fixed, csf_opts *o, int *st)
{
	char *buf = NULL, *ebuf = NULL;
	size_t len = 0, elen = 0;
	FILE *f = open_memstream(&buf, &len), *e = open_memstream(&ebuf, &elen);
	if (!f || !e) {
		if (f) fclose(f);
		if (e) fclose(e);
		*st = 2;
		return NULL;
	}
	memset(o, 0, sizeof *o);
	o->method = m;
	o->tol = tol;
	o->fixed = fixed;
	*st = csf_run(p, exec, o, f, e);
	fclose(f);
	fclose(e);
	free(ebuf);
	return buf;
}

/* The largest min(absolute, relative) difference between two CSV texts; -1 if their shapes differ. */
static double difference(const char *a, const char *b)
{
	const char *pa = strchr(a, '\n'), *pb = strchr(b, '\n');
	double worst = 0;
	if (!pa || !pb) return -1;
	pa++, pb++;
	while (*pa && *pb) {
		char *ea, *eb;
		double x = strtod(pa, &ea), y = strtod(pb, &eb);
		double d = fabs(x - y), r = y != 0 ? d / fabs(y) : d;
		double m = d < r ? d : r;
		if (isnan(m)) m = INFINITY;
		if (m > worst) worst = m;
		if (*ea != *eb) return -1;
		pa = *ea ? ea + 1 : ea;
		pb = *eb ? eb + 1 : eb;
	}
	return *pa || *pb ? -1 : worst;
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

int csf_compare_methods(const csf_prog *p, csf_exec_fn exec, FILE *out, FILE *err)
{
	static const char *const methods[] = { "dop853", "dopri5", "rk8pd", "rkck", "rkf45", "rk4", "rk2", "msadams", "bsimp", "rk4imp", "msbdf" };
	static const double tols[] = { 1e-4, 1e-6, 1e-8, 1e-10, 1e-12 };
	csf_opts o;
	int st;
	char *ref = capture(p, exec, "rk8pd", 1e-13, 0, &o, &st);
	if (st != 0 || !ref) {
		fprintf(err, "error: the reference run (rk8pd, tol 1e-13) failed; run the scene alone to see why\n");
		free(ref);
		return st ? st : 2;
	}
	say(out, "reference: rk8pd at tol 1e-13, %.3f s, %lu steps\n", o.run_seconds, o.run_steps);
	say(out, "%-8s %-7s %10s %10s %12s %14s\n", "method", "tol", "seconds", "steps", "rhs_evals", "difference");
	for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
		for (size_t k = 0; k < sizeof tols / sizeof tols[0]; k++) {
			char *run = capture(p, exec, methods[i], tols[k], 0, &o, &st);
			char diff[32];
			double d = run && st == 0 ? difference(run, ref) : -1;
			if (st != 0) snprintf(diff, sizeof diff, "failed (%d)", st);
			else if (d < 0) snprintf(diff, sizeof diff, "mismatch");
			else snprintf(diff, sizeof diff, "%.3g", d);
			say(out, "%-8s %-7g %10.4f %10lu %12lu %14s\n", methods[i], tols[k], o.run_seconds, o.run_steps, o.run_rhs,
			        diff);
			free(run);
		}
	/* Verlet, where the scene has position/velocity pairs: its own step at the default tolerance
	   (csfvm(1), verlet) */
	if (p->ny > 0) {
		char *run = capture(p, exec, "verlet", 0, 1, &o, &st);
		if (st == 0 && run) {
			say(out, "%-8s %-7g %10.4f %10lu %12lu %14.3g\n", "verlet", csf_method_tol("verlet"), o.run_seconds,
			        o.run_steps, o.run_rhs, difference(run, ref));
		}
		free(run);
	}
	free(ref);
	say(out, "difference: the largest min(absolute, relative) difference from the reference over every row and column\n");
	return ferror(out) ? 2 : 0;
}
