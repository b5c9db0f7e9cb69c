/*
 * driver.c - the simulation loop, output and run-time diagnostics.
 *
 * csf_run is shared by csfvm and by every generated executable: it owns the
 * model's memory, integrates the state between output times t_k = k*by with
 * ode.c, runs the OUT section at each t_k, checks assertions and finiteness,
 * and writes one CSV row per t_k as it goes. Rows are written through stdio
 * and flushed on every exit path; a write error is reported, never ignored.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "csf.h"
#include "ode.h"

void csf_fmt_double(char buf[32], double x)
{
	if (isnan(x)) {
		strcpy(buf, "nan");
		return;
	}
	if (isinf(x)) {
		strcpy(buf, x > 0 ? "inf" : "-inf");
		return;
	}
	for (int prec = 15; prec <= 17; prec++) {
		snprintf(buf, 32, "%.*g", prec, x);
		if (strtod(buf, NULL) == x) return;
	}
}

int csf_parse_opts(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                   const char *usage)
{
	memset(o, 0, sizeof *o);
	*npos_out = 0;
	for (int i = first; i < argc; i++) {
		const char *a = argv[i];
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			fputs(usage, stdout);
			return 1;
		} else if (strcmp(a, "--version") == 0) {
			const char *slash = strrchr(argv[0], '/');
			printf("%s %s\n", slash ? slash + 1 : argv[0], CSF_VERSION_STRING);
			return 1;
		} else if (strcmp(a, "--method") == 0 && i + 1 < argc) {
			o->method = argv[++i];
			int known = 0;
			for (size_t k = 0; csf_method_name(k); k++) known |= strcmp(csf_method_name(k), o->method) == 0;
			if (!known) {
				fprintf(stderr, "%s: unknown method '%s' (one of:", argv[0], o->method);
				for (size_t k = 0; csf_method_name(k); k++) fprintf(stderr, " %s", csf_method_name(k));
				fprintf(stderr, ")\n");
				return 2;
			}
		} else if (strcmp(a, "--tol") == 0 && i + 1 < argc) {
			char *end;
			errno = 0;
			o->tol = strtod(argv[++i], &end);
			if (*end || errno || !(o->tol > 0) || !isfinite(o->tol)) {
				fprintf(stderr, "%s: --tol needs a positive number, not '%s'\n", argv[0], argv[i]);
				return 2;
			}
		} else if (strcmp(a, "--step") == 0 && i + 1 < argc) {
			char *end;
			errno = 0;
			o->step = strtod(argv[++i], &end);
			o->fixed = 1;
			if (*end || errno || !(o->step > 0) || !isfinite(o->step)) {
				fprintf(stderr, "%s: --step needs a positive number of seconds, not '%s'\n", argv[0], argv[i]);
				return 2;
			}
		} else if (strcmp(a, "--fixed") == 0) {
			o->fixed = 1;
		} else if (strcmp(a, "--stats") == 0) {
			o->stats = 1;
		} else if (strcmp(a, "--compare-methods") == 0) {
			o->compare = 1;
		} else if (a[0] == '-' && a[1] != '\0') {
			fprintf(stderr, "%s: unknown or incomplete option '%s'\n%s", argv[0], a, usage);
			return 2;
		} else {
			if (*npos_out >= npos) {
				fprintf(stderr, "%s: too many arguments\n%s", argv[0], usage);
				return 2;
			}
			pos[(*npos_out)++] = i;
		}
	}
	return 0;
}

typedef struct run {
	const csf_prog *p;
	csf_exec_fn exec;
	double *m;
	double fail_t; /* time of a non-finite derivative */
	int fail;
	unsigned long nrhs, njac; /* evaluations, for --stats */
} run;

static int rhs(double t, const double *y, double *dydt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m;
	m[p->tslot] = t;
	memcpy(m + p->ystart, y, p->ny * sizeof *y);
	r->exec(p, CSF_SEC_RHS, m);
	r->nrhs++;
	memcpy(dydt, m + p->dstart, p->ny * sizeof *y);
	for (uint32_t i = 0; i < p->ny; i++)
		if (!isfinite(dydt[i])) {
			r->fail = 1;
			r->fail_t = t;
			return 1;
		}
	return 0;
}

/*
 * The exact Jacobian: JAC run once per state component with that
 * component's tangent set to 1 (a column), then once with t's (dfdt).
 */
static int jac(double t, const double *y, double *dfdy, double *dfdt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m, *tan = r->m + p->jtan;
	uint32_t n = p->ny;
	m[p->tslot] = t;
	memcpy(m + p->ystart, y, n * sizeof *y);
	r->njac++;
	for (uint32_t j = 0; j <= n; j++) {
		memset(tan + p->ystart, 0, n * sizeof *tan);
		tan[p->tslot] = j == n ? 1.0 : 0.0;
		if (j < n) tan[p->ystart + j] = 1.0;
		r->exec(p, CSF_SEC_JAC, m);
		for (uint32_t i = 0; i < n; i++) {
			double d = tan[p->dstart + i];
			if (j < n) dfdy[(size_t)i * n + j] = d;
			else dfdt[i] = d;
		}
	}
	return 0;
}

/* Index of the first non-finite target computed by section sec, or -1. */
static long first_nonfinite(const csf_prog *p, int sec, const double *m)
{
	for (uint32_t i = 0; i < p->ntargets[sec]; i++) {
		const csf_target *tg = &p->targets[sec][i];
		for (uint32_t k = 0; k < tg->width; k++)
			if (!isfinite(m[tg->slot + k])) return (long)i;
	}
	return -1;
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err);

/* Reports a non-finite value; with fixed steps, adds that the step is the likely cause. */
static void report_nonfinite(const csf_prog *p, int sec, const double *m, double t, const char *what, int fixed,
                             FILE *err)
{
	report_nonfinite_value(p, sec, m, t, what, err);
	if (fixed)
		fprintf(err, "note: with --fixed, the step is probably too large for the method to be stable: "
		             "try a smaller --step, or leave out --fixed\n");
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err)
{
	char tb[32], vb[32];
	csf_fmt_double(tb, t);
	long i = first_nonfinite(p, sec, m);
	if (i < 0) {
		/* no rule computed it: an initial value or a constant; name the column */
		for (uint32_t c = 0; c < p->ncols; c++)
			if (!isfinite(m[p->cols[c].slot])) {
				csf_fmt_double(vb, m[p->cols[c].slot]);
				fprintf(err, "error: non-finite value at t=%s: %s = %s, set by no rule (an initial value or a constant)\n",
				        tb, csf_str(p, p->cols[c].name), vb);
				return;
			}
		fprintf(err, "error: non-finite value at t=%s: %s\n", tb, what);
		return;
	}
	const csf_target *tg = &p->targets[sec][i];
	const csf_src *s = &p->srcs[tg->src];
	uint32_t k = 0;
	while (k + 1 < tg->width && isfinite(m[tg->slot + k])) k++;
	csf_fmt_double(vb, m[tg->slot + k]);
	fprintf(err, "%s:%lu: error: non-finite value at t=%s: %s%s%s (object %s) = %s, computed by: %s\n",
	        csf_str(p, p->files[s->file]), (unsigned long)s->line, tb, csf_str(p, tg->name),
	        tg->width == 3 ? "." : "", tg->width == 3 ? (const char *[]){ "x", "y", "z" }[k] : "",
	        csf_str(p, tg->object), vb, csf_str(p, s->text));
}

static int write_row(const csf_prog *p, const double *m, double t, FILE *out)
{
	char b[32];
	csf_fmt_double(b, t);
	fputs(b, out);
	for (uint32_t i = 0; i < p->ncols; i++) {
		csf_fmt_double(b, m[p->cols[i].slot]);
		putc(',', out);
		fputs(b, out);
	}
	putc('\n', out);
	return ferror(out) ? -1 : 0;
}

static int finish(FILE *out, FILE *err, int status)
{
	if (fflush(out) != 0 || ferror(out)) {
		fprintf(err, "error: cannot write output: %s\n", strerror(errno));
		return 2;
	}
	return status;
}

int csf_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, FILE *err)
{
	run r = { p, exec, NULL, 0, 0, 0, 0 };
	double *y = NULL;
	int warned = 0, fixed = 0;
	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	csf_ode *ode = NULL;
	int status = 0;
	char msg[256];

	r.m = malloc((p->nmem ? p->nmem : 1) * sizeof(double));
	y = malloc((p->ny ? p->ny : 1) * sizeof(double));
	if (!r.m || !y) {
		fprintf(err, "error: out of memory\n");
		status = 2;
		goto done;
	}
	memcpy(r.m, p->mem0, p->nmem * sizeof(double));
	memcpy(y, p->mem0 + p->ystart, p->ny * sizeof(double));
	if (p->ny) {
		ode = csf_ode_new(o->method, o->fixed, p->ny, p->by, o->tol, p->yscale, p->vpair, rhs, p->jtan ? jac : NULL, &r, msg,
		                  sizeof msg);
		if (!ode) {
			fprintf(err, "error: %s\n", msg);
			status = 2;
			goto done;
		}
	}

	fputs("t", out);
	for (uint32_t i = 0; i < p->ncols; i++) fprintf(out, ",%s", csf_str(p, p->cols[i].name));
	putc('\n', out);

	fixed = ode && (o->fixed || csf_ode_fixed_only(ode));
	double fixed_h = ode ? csf_ode_fixed_step(ode, p->by, o->step) : p->by;

	/* The last k with k*by <= till, allowing for till/by's rounding. */
	double kmax = floor(p->till / p->by);
	if ((kmax + 1) * p->by <= p->till * (1 + 1e-12)) kmax += 1;

	double t = 0;
	for (double k = 0; k <= kmax; k++) {
		double tk = k * p->by;
		if (ode && tk > t) {
			unsigned long before, rej;
			csf_ode_stats(ode, &before, &rej);
			int st = fixed ? csf_ode_advance_fixed(ode, &t, tk, fixed_h, y, msg, sizeof msg)
			               : csf_ode_advance(ode, &t, tk, y, msg, sizeof msg);
			unsigned long after;
			csf_ode_stats(ode, &after, &rej);
			if (!fixed && !warned && csf_ode_explicit(ode) && after - before > 10000) {
				char tb[32];
				csf_fmt_double(tb, tk);
				fprintf(err,
				        "warning: %lu steps of the explicit method %s to reach t=%s: the problem looks stiff; "
				        "try --method msbdf or --method bsimp\n",
				        after - before, csf_ode_method(ode), tb);
				warned = 1;
			}
			if (st == CSF_ODE_STOPPED) {
				report_nonfinite(p, CSF_SEC_RHS, r.m, r.fail_t, "a state derivative", o->fixed, err);
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_FAILED) {
				char tb[32];
				csf_fmt_double(tb, t);
				fprintf(err,
				        "error: integration failed at t=%s: %s (the step size collapsed: the solution may be "
				        "singular there, or the problem stiff; try another --method or a smaller 'by')\n",
				        tb, msg);
				status = 1;
				goto done;
			}
		}
		t = tk;
		r.m[p->tslot] = tk;
		memcpy(r.m + p->ystart, y, p->ny * sizeof(double));
		int a = exec(p, CSF_SEC_OUT, r.m);
		if (a >= 0) {
			const csf_src *s = &p->srcs[p->asserts[a].src];
			char tb[32];
			csf_fmt_double(tb, tk);
			fprintf(err, "%s:%lu: assertion failed at t=%s: %s (object %s)\n", csf_str(p, p->files[s->file]),
			        (unsigned long)s->line, tb, csf_str(p, s->text), csf_str(p, p->asserts[a].object));
			status = 1;
			goto done;
		}
		int bad = 0;
		for (uint32_t i = 0; i < p->ny; i++) bad |= !isfinite(r.m[p->ystart + i]);
		for (uint32_t i = 0; i < p->ncols; i++) bad |= !isfinite(r.m[p->cols[i].slot]);
		if (bad) {
			report_nonfinite(p, CSF_SEC_OUT, r.m, tk, "a watched or state value", o->fixed, err);
			status = 1;
			goto done;
		}
		if (write_row(p, r.m, tk, out)) break;
	}
done:
	clock_gettime(CLOCK_MONOTONIC, &t1);
	{
		unsigned long steps = 0, rejected = 0;
		if (ode) csf_ode_stats(ode, &steps, &rejected);
		o->run_steps = steps;
		o->run_rhs = r.nrhs;
		o->run_seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	}
	if (o->stats) {
		unsigned long steps = 0, rejected = 0;
		if (ode) csf_ode_stats(ode, &steps, &rejected);
		fprintf(err,
		        "stats: method %s%s, %lu steps (%lu rejected), %lu right-hand side and %lu Jacobian evaluations, "
		        "0 events, %.6f s\n",
		        ode ? csf_ode_method(ode) : "none", fixed ? " (fixed steps)" : "", steps, rejected, r.nrhs, r.njac,
		        (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
	}
	csf_ode_free(ode);
	free(y);
	free(r.m);
	return finish(out, err, status);
}
