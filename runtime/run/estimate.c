/*
 * estimate.c - --estimate-error and --accuracy A: the run's global error,
 * estimated by running the scene again at a tolerance 100 times tighter
 * (fixed steps: steps 10 times shorter) and taking, for each watched
 * column, the largest difference between the two runs' rows and the time
 * it occurred. The error of a method of order q at tolerance tol grows
 * like tol^(q/(q+1)) or faster, so the reference run's own error is 40 to
 * 100 times smaller for the methods of order 4 to 8, and the difference is
 * the run's error to within a few per cent (a second method, the other
 * choice, would estimate the error of the worse of the two). The rows of
 * the run are kept in memory (a double per value) while the reference run
 * streams past them.
 *
 * --accuracy A: the run at the tolerance given (or the default), its
 * estimate, and while the largest difference is above A, the tolerance
 * 100 times tighter: each reference run is the next try, so that each
 * step costs one run. Then the run at the tolerance found writes the rows
 * as a plain run does. Below the least tolerance (CSF_MIN_TOL), or with
 * fixed steps after six tightenings, it says why A cannot be met.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"

typedef struct rowbuf {
	double *v;
	size_t n, cap, w; /* rows, room, values a row */
} rowbuf;

typedef struct cmp {
	rowbuf *keep;       /* the rows, kept (or NULL) */
	const rowbuf *base; /* the rows compared with (or NULL) */
	const csf_sink *fwd; /* passed on to (or NULL) */
	size_t at;          /* the next row of base */
	double *dmax, *tmax; /* per column: the largest difference and its t */
	int nomem;
} cmp;

static int cmp_row(void *ctx, const double *v, size_t n)
{
	cmp *c = ctx;
	if (c->keep) {
		rowbuf *b = c->keep;
		if (b->n == b->cap) {
			size_t cap = b->cap ? 2 * b->cap : 1024;
			double *nv = realloc(b->v, cap * b->w * sizeof *nv);
			if (!nv) {
				c->nomem = 1;
				errno = ENOMEM;
				return -1;
			}
			b->v = nv, b->cap = cap;
		}
		memcpy(b->v + b->n++ * b->w, v, n * sizeof *v);
	}
	if (c->base && c->at < c->base->n) {
		const double *u = c->base->v + c->at++ * c->base->w;
		for (size_t i = 1; i < n; i++) {
			double d = fabs(v[i] - u[i]);
			if (d > c->dmax[i] || (isnan(d) && !isnan(c->dmax[i]))) c->dmax[i] = d, c->tmax[i] = v[0];
		}
	}
	return c->fwd ? c->fwd->row(c->fwd->ctx, v, n) : 0;
}

/* The tolerance a run of o takes. */
static double tol_of(const csf_opts *o)
{
	return o->tol > 0 ? o->tol : csf_method_tol(o->method && strcmp(o->method, "auto") ? o->method : NULL);
}

/* Fixed steps: the step a run of o takes (--step, else the output interval). */
static double step_of(const csf_prog *p, const csf_opts *o) { return o->step > 0 && o->step < p->by ? o->step : p->by; }

/* o's run tightened once: the tolerance 100 times, or with --fixed the step 10 times. 0, or -1 when it cannot be. */
static int tighten(const csf_prog *p, csf_opts *o)
{
	if (o->fixed) {
		o->step = step_of(p, o) / 10;
		return 0;
	}
	double t = tol_of(o);
	if (t <= CSF_MIN_TOL) return -1;
	char b[32]; /* t / 100 to 12 digits: 1e-11, not 1.0000000000000001e-11, from 1e-9 */
	snprintf(b, sizeof b, "%.12g", t / 100);
	o->tol = strtod(b, NULL) < CSF_MIN_TOL ? CSF_MIN_TOL : strtod(b, NULL);
	/* steps capped at the output interval (a method without dense output, or events), or at --hmax, are
	   the same steps at any tolerance, and so is their error: the reference's are half as long */
	double cap = o->hmax > 0 ? o->hmax : INFINITY;
	if (!csf_method_dense(o->method && strcmp(o->method, "auto") ? o->method : NULL) || p->nevents || p->ncrules)
		cap = cap < p->by ? cap : p->by;
	if (isfinite(cap)) o->hmax = cap / 2;
	return 0;
}

/* A quiet run of o (no CSV, no --stats, no checkpoint, no record) into c: its exit status; its messages in *msg. */
static int quiet_run(const csf_prog *p, csf_exec_fn exec, const csf_opts *o, cmp *c, char **msg, unsigned long *rhs)
{
	csf_opts q = *o;
	q.stats = 0, q.progress = CSF_PROGRESS_OFF, q.checkpoint = q.resume = q.record = NULL, q.estimate = 0;
	size_t len;
	*msg = NULL;
	FILE *e = open_memstream(msg, &len);
	if (!e) return 2;
	csf_sink s = { cmp_row, c, NULL };
	int st = csf_run_sink(p, exec, &q, NULL, &s, e);
	fclose(e);
	*rhs += q.run_rhs;
	return c->nomem ? 2 : st;
}

/* The settings of a run of o, as its command line gives them: "--tol 1e-12" or "--step 0.001". */
static void setting(const csf_prog *p, const csf_opts *o, char *buf, size_t n)
{
	char v[32];
	csf_fmt_double(v, o->fixed ? step_of(p, o) : tol_of(o));
	snprintf(buf, n, "%s %s", o->fixed ? "--step" : "--tol", v);
}

/* The estimate of c's differences into o and on err: a line per column, and --stats's. */
static void report(const csf_prog *p, csf_opts *o, const cmp *c, const char *ref, double cost, FILE *err)
{
	size_t worst = 0;
	for (uint32_t i = 0; i < p->ncols; i++) {
		char d[32], t[32];
		csf_fmt_double(d, c->dmax[i + 1]);
		csf_fmt_double(t, c->tmax[i + 1]);
		fprintf(err, "error estimate: %s: %s at t=%s\n", csf_str(p, p->cols[i].name), d, t);
		if (!worst || c->dmax[i + 1] > c->dmax[worst] || isnan(c->dmax[i + 1])) worst = i + 1;
	}
	o->err_estimate = worst ? c->dmax[worst] : 0;
	o->err_t = worst ? c->tmax[worst] : 0;
	o->err_column = worst ? csf_str(p, p->cols[worst - 1].name) : "";
	if (o->stats) {
		char d[32], t[32];
		csf_fmt_double(d, o->err_estimate);
		csf_fmt_double(t, o->err_t);
		fprintf(err, "stats: error estimate: %s (%s at t=%s) against a run at %s; the estimate cost %.2f times the run\n",
		        d, worst ? o->err_column : "no column", t, ref, cost);
	}
}

/* The reference run of o (tightened) against the rows of base: 0, or the run's status with why on err. */
static int reference(const csf_prog *p, csf_exec_fn exec, csf_opts *o, cmp *c, rowbuf *keep, char *ref, size_t reflen,
                     unsigned long *rhs, FILE *err)
{
	csf_opts r = *o;
	if (tighten(p, &r)) {
		fprintf(err, "error estimate: none: the run is at the least tolerance, %g, and no run can be tighter\n",
		        CSF_MIN_TOL);
		return 1;
	}
	setting(p, &r, ref, reflen);
	for (size_t i = 0; i <= p->ncols; i++) c->dmax[i] = 0, c->tmax[i] = 0;
	c->at = 0, c->keep = keep, c->fwd = NULL;
	char *msg;
	int st = quiet_run(p, exec, &r, c, &msg, rhs);
	if (st) fprintf(err, "error estimate: none: the reference run at %s failed (exit %d): %s", ref, st, msg ? msg : "\n");
	else if (c->at != c->base->n)
		fprintf(err, "error estimate: the reference run at %s wrote %zu rows, the run %zu: compared over %zu\n", ref, c->at,
		        c->base->n, c->at);
	free(msg);
	if (!st) *o = r;
	return st;
}

int csf_estimate_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, const csf_sink *fwd, FILE *err)
{
	size_t w = (size_t)p->ncols + 1;
	rowbuf a = { .w = w }, b = { .w = w };
	double *d = calloc(2 * w, sizeof *d);
	cmp c = { .dmax = d, .tmax = d + w, .base = &a };
	char ref[64];
	unsigned long rhs = 0;
	int st;
	if (!d) {
		fprintf(err, "error: out of memory\n");
		return 2;
	}
	if (!o->accuracy) { /* the run as asked, its rows kept; then the reference */
		c.keep = &a, c.fwd = fwd;
		csf_sink s = { cmp_row, &c, NULL };
		st = csf_run_sink(p, exec, o, out, &s, err);
		if (c.nomem) st = 2, fprintf(err, "error estimate: out of memory for the rows\n");
		csf_opts r = *o;
		if (!st && !(st = reference(p, exec, &r, &c, NULL, ref, sizeof ref, &rhs, err)))
			report(p, o, &c, ref, o->run_rhs ? (double)(o->run_rhs + rhs) / (double)o->run_rhs : 0, err);
		o->err_tol = tol_of(o);
		free(a.v), free(d);
		return st;
	}
	/* --accuracy: tries, each reference run the next try */
	csf_opts t = *o;
	char *msg;
	c.keep = &a;
	st = quiet_run(p, exec, &t, &c, &msg, &rhs);
	if (st) fprintf(err, "%s", msg ? msg : "");
	free(msg);
	for (int tries = 0; !st; tries++) {
		csf_opts r = t;
		b.n = 0;
		c.base = &a;
		if ((st = reference(p, exec, &r, &c, &b, ref, sizeof ref, &rhs, err))) break;
		double e = 0;
		for (size_t i = 1; i < w; i++) e = c.dmax[i] > e || isnan(c.dmax[i]) ? c.dmax[i] : e;
		if (e <= o->accuracy) break;
		if (!isfinite(e) || (t.fixed && tries == 5) || (!t.fixed && tol_of(&r) <= CSF_MIN_TOL)) {
			char have[64], es[32], as[32];
			setting(p, &t, have, sizeof have);
			csf_fmt_double(es, e);
			csf_fmt_double(as, o->accuracy);
			fprintf(err, "error: --accuracy %s cannot be met: the estimate at %s is %s, and %s\n", as, have, es,
			        !isfinite(e) ? "not finite"
			        : t.fixed    ? "six steps, each 10 times shorter, did not reach it (an adaptive method may)"
			                     : "the next tolerance would be at or below 1e-15, where rounding, not the method, "
			                       "makes the error");
			st = 1;
			break;
		}
		t = r; /* the reference run is the next try */
		rowbuf x = a;
		a = b, b = x;
	}
	if (!st) { /* the run at the tolerance found, as a plain run */
		double acc = o->accuracy;
		cmp found = c;
		o->tol = t.tol, o->step = t.step, o->accuracy = 0;
		st = csf_run_sink(p, exec, o, out, fwd, err);
		o->accuracy = acc;
		report(p, o, &found, ref, o->run_rhs ? (double)(o->run_rhs + rhs) / (double)o->run_rhs : 0, err);
		char have[64], es[32], as[32];
		setting(p, o, have, sizeof have);
		csf_fmt_double(es, o->err_estimate);
		csf_fmt_double(as, acc);
		fprintf(err, "accuracy: %s met at %s (error estimate %s)\n", as, have, es);
	}
	o->err_tol = tol_of(o);
	free(a.v), free(b.v), free(d);
	return st;
}
