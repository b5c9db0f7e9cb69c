/*
 * sweep.c - csfvm --sweep: many runs of one scene with different
 * parameters, written as one CSV in the order of the variants.
 *
 * The variants are the Cartesian product of axes: a --sweep-file is the
 * first axis, whose entries are its rows (one value per named parameter),
 * then each --sweep, in order, an axis of COUNT evenly spaced values of
 * one parameter; the last axis varies fastest. Variant i sets its values in
 * an overlay of the program's initial memory (every swept value is a
 * parameter, param.c; the program is not changed), runs csf_run_sink with
 * its output captured (a summary's values taken from its row sink, not read
 * back from the text), and turns that output into its text: each row with
 * the variant's values as leading columns (or, with --sweep-summary, one
 * row of final/max/min/mean/rms of columns, over a window of time). A variant's result is one message
 * (status, text, diagnostics), so it can be made anywhere: here, in a
 * worker process of -j N (a pipe carries it back), or on another MPI rank
 * (sweep_mpi.c); the one writer takes the messages in variant order, so
 * the bytes written do not depend on where or in what order variants ran.
 * With -o RUN.h5 a variant's text is its rows as doubles, and the writer
 * gives them, with its values and status, to one HDF5 file (h5.c), whose
 * data are the same for any -j; an interrupted sweep's file gets the
 * variants not run as such (status -1, no rows).
 *
 * The values are printed in the model's units with the shortest text that
 * reads back to the same double, and a bare number given to -D is taken
 * as it is: `-D NAME=PRINTED` for each swept column reproduces the
 * variant's rows byte for byte.
 *
 * This file reads the sweep's options (the axes, a --sweep-file, the
 * summaries) and runs the whole; a variant is made in sweep_variant.c, and
 * sweep_fork.c runs the variants here or in worker processes.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sweep_int.h"

int (*csf_sweep_distribute)(csf_sweep *s);


int csf_sweep_err(csf_sweep *S, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "%s: ", S->prog);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
	return -1;
}

static char *xstrndup0(const char *s, size_t n)
{
	char *d = malloc(n + 1);
	if (!d) return NULL;
	memcpy(d, s, n);
	d[n] = '\0';
	return d;
}

static char *trim(char *s)
{
	while (*s == ' ' || *s == '\t') s++;
	size_t n = strlen(s);
	while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n')) s[--n] = '\0';
	return s;
}

/* Adds parameter name (a scalar that can be set) for option what; returns its index or -1. */
static int add_param(csf_sweep *S, const char *name, const char *what)
{
	char why[400];
	csf_pref r;
	for (int k = 0; k < S->npar; k++)
		if (strcmp(S->par[k].name, name) == 0) return csf_sweep_err(S, "%s: %s is swept twice", what, name);
	if (csf_param_find(S->p, name, &r, why, sizeof why)) return csf_sweep_err(S, "%s: %s", what, why);
	if (*csf_str(S->p, r.cls->why))
		return csf_sweep_err(S, "%s: %s cannot be overridden: %s", what, name, csf_str(S->p, r.cls->why));
	if (r.width != 1)
		return csf_sweep_err(S, "%s: %s is a vector; a sweep varies a scalar (a global the vector is computed from)", what, name);
	sparam *q = realloc(S->par, (size_t)(S->npar + 1) * sizeof *q);
	if (!q) return csf_sweep_err(S, "out of memory");
	S->par = q;
	const char *unit = csf_str(S->p, r.cls->unit);
	size_t hn = strlen(name) + strlen(unit) + 4;
	char *head = malloc(hn);
	if (head) snprintf(head, hn, *unit ? "%s [%s]" : "%s", name, unit);
	S->par[S->npar] = (sparam){ xstrndup0(name, strlen(name)), head, r };
	if (!S->par[S->npar].name || !head) return csf_sweep_err(S, "out of memory");
	return S->npar++;
}

static axis *add_axis(csf_sweep *S, int first, int n, size_t count)
{
	axis *a = realloc(S->ax, (size_t)(S->nax + 1) * sizeof *a);
	if (!a) return NULL;
	S->ax = a;
	a = &S->ax[S->nax++];
	*a = (axis){ first, n, count, calloc(count * (size_t)n + 1, sizeof(double)) };
	return a->vals ? a : NULL;
}

/* --sweep 'NAME=FROM:TO:COUNT [UNIT]': COUNT values from FROM to TO, both included, evenly spaced. */
static int parse_grid(csf_sweep *S, const char *spec)
{
	const char *eq = strchr(spec, '='), *c1 = eq ? strchr(eq + 1, ':') : NULL, *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
	if (!c2) return csf_sweep_err(S, "--sweep '%s': expected NAME=FROM:TO:COUNT [UNIT]", spec);
	char *name = xstrndup0(spec, (size_t)(eq - spec)), *from = xstrndup0(eq + 1, (size_t)(c1 - eq - 1)),
	     *to = xstrndup0(c1 + 1, (size_t)(c2 - c1 - 1));
	int st = -1;
	if (!name || !from || !to) goto done;
	char *end;
	errno = 0;
	long count = strtol(c2 + 1, &end, 10);
	if (end == c2 + 1 || errno || count < 1 || count > 100000000) {
		csf_sweep_err(S, "--sweep '%s': COUNT must be a whole number from 1 to 1e8", spec);
		goto done;
	}
	int k = add_param(S, trim(name), "--sweep");
	if (k < 0) goto done;
	const char *unit = end;
	double a[3], b[3];
	char why[400];
	size_t fn = strlen(from) + strlen(unit) + 2, tn = strlen(to) + strlen(unit) + 2;
	char *ft = malloc(fn), *tt = malloc(tn);
	if (ft && tt) {
		snprintf(ft, fn, "%s %s", from, unit);
		snprintf(tt, tn, "%s %s", to, unit);
		if (csf_param_value(S->p, S->par[k].name, &S->par[k].ref, ft, a, why, sizeof why) ||
		    csf_param_value(S->p, S->par[k].name, &S->par[k].ref, tt, b, why, sizeof why)) {
			csf_sweep_err(S, "--sweep '%s': %s", spec, why);
		} else {
			axis *ax = add_axis(S, k, 1, (size_t)count);
			if (!ax) csf_sweep_err(S, "out of memory");
			for (long i = 0; ax && i < count; i++)
				ax->vals[i] = i == count - 1 && count > 1 ? b[0] : a[0] + (b[0] - a[0]) * ((double)i / (double)(count - 1 ? count - 1 : 1));
			st = ax ? 0 : -1;
		}
	}
	free(ft);
	free(tt);
done:
	free(name);
	free(from);
	free(to);
	return st;
}

/* Splits line at commas into at most max trimmed fields; returns how many. */
static int split(char *line, char **f, int max)
{
	int n = 0;
	for (char *s = line;;) {
		char *c = strchr(s, ',');
		if (c) *c = '\0';
		if (n < max) f[n] = trim(s);
		n++;
		if (!c) return n;
		s = c + 1;
	}
}

/*
 * A cell of a sweep file's header: NAME, or NAME [UNIT] as a sweep's output
 * names its leading columns; the unit (NULL if none) into *unit, malloc'd.
 * Returns the name, or NULL when the brackets are not closed at the end.
 */
static char *header_cell(char *cell, char **unit)
{
	*unit = NULL;
	char *br = strchr(cell, '[');
	if (!br) return cell;
	size_t n = strlen(br);
	if (br[n - 1] != ']') return NULL;
	br[n - 1] = '\0';
	*br = '\0';
	const char *u = trim(br + 1);
	*unit = xstrndup0(u, strlen(u));
	return trim(cell);
}

/*
 * The text of value cell of a column whose header gave unit (NULL if none)
 * for parameter q, into buf: a bare number is in the header's unit (and so
 * as it is when that is the parameter's own, what a sweep prints).
 */
static const char *cell_value(const csf_sweep *S, const sparam *q, const char *unit, const char *cell, char *buf,
                              size_t len)
{
	char *end;
	strtod(cell, &end);
	if (!unit || end == cell || *trim(end) || strcmp(unit, csf_str(S->p, q->ref.cls->unit)) == 0) return cell;
	snprintf(buf, len, "%s %s", cell, unit);
	return buf;
}

/* --sweep-file FILE.csv: a header of parameter names (with optional units), then one variant per row (values with
   optional units). */
static int parse_file(csf_sweep *S, const char *path)
{
	size_t len;
	char *text = (char *)csf_read_file(path, &len);
	if (!text) return csf_sweep_err(S, "--sweep-file: cannot read %s: %s", path, strerror(errno));
	text[len] = '\0';
	int st = -1, first = S->npar, n = 0;
	enum { MAXF = 256 };
	char *f[MAXF], *units[MAXF] = { NULL };
	size_t rows = 0;
	axis *ax = NULL;
	/* two passes: count the rows, then read them */
	for (int pass = 0; pass < 2; pass++) {
		char *copy = pass ? text : xstrndup0(text, len), *line = copy, *next;
		if (!copy) goto out;
		size_t row = 0;
		int lineno = 0, header = 1;
		for (; line && *line; line = next) {
			next = strchr(line, '\n');
			if (next) *next++ = '\0';
			lineno++;
			char *t = trim(line);
			if (!*t || *t == '#') continue;
			int nf = split(t, f, MAXF);
			if (header) {
				header = 0;
				if (pass) continue;
				if (nf > MAXF) {
					free(copy);
					csf_sweep_err(S, "--sweep-file %s: more than %d columns", path, MAXF);
					goto out;
				}
				for (int k = 0; k < nf; k++) {
					char *name = header_cell(f[k], &units[k]);
					if (!name) {
						csf_sweep_err(S, "--sweep-file %s: header '%s': expected NAME or NAME [UNIT]", path, f[k]);
						free(copy);
						goto out;
					}
					if (add_param(S, name, "--sweep-file") < 0) {
						free(copy);
						goto out;
					}
				}
				n = nf;
				continue;
			}
			if (nf != n) {
				if (!pass) free(copy);
				csf_sweep_err(S, "--sweep-file %s:%d: %d values, the header names %d", path, lineno, nf, n);
				goto out;
			}
			if (pass)
				for (int k = 0; k < n; k++) {
					char why[400], buf[512];
					sparam *q = &S->par[first + k];
					double v[3];
					const char *cell = cell_value(S, q, units[k], f[k], buf, sizeof buf);
					if (csf_param_value(S->p, q->name, &q->ref, cell, v, why, sizeof why)) {
						csf_sweep_err(S, "--sweep-file %s:%d: %s", path, lineno, why);
						goto out;
					}
					ax->vals[row * (size_t)n + (size_t)k] = v[0];
				}
			row++;
		}
		if (!pass) {
			free(copy);
			rows = row;
			if (n == 0 || rows == 0) {
				csf_sweep_err(S, "--sweep-file %s: no header or no rows", path);
				goto out;
			}
			ax = add_axis(S, first, n, rows);
			if (!ax) {
				csf_sweep_err(S, "out of memory");
				goto out;
			}
		}
	}
	st = 0;
out:
	for (int k = 0; k < MAXF; k++) free(units[k]);
	free(text);
	return st;
}

/* The header cell of column c of a run's output: "t", or the column's name with its unit. */
const char *csf_sweep_col_head(const csf_prog *p, uint32_t c) { return c == 0 ? "t" : csf_str(p, p->cols[c - 1].name); }

/* The length of column k's header without its unit. */
size_t csf_sweep_head_len(const csf_prog *p, uint32_t k)
{
	const char *h = csf_sweep_col_head(p, k), *u = strstr(h, " [");
	return u ? (size_t)(u - h) : strlen(h);
}

/*
 * The column a summary names: as in the header without the unit
 * (`ball.pos.z`), or as the watch list may (`pos.z` for the one object
 * whose column it is). UINT32_MAX, with a message in S, if none or several.
 */
static uint32_t find_column(csf_sweep *S, const char *c)
{
	const csf_prog *p = S->p;
	size_t n = strlen(c);
	uint32_t found = UINT32_MAX, nsuffix = 0, ends = UINT32_MAX;
	for (uint32_t k = 0; k <= p->ncols; k++) {
		const char *h = csf_sweep_col_head(p, k);
		size_t hn = csf_sweep_head_len(p, k);
		if (hn == n && strncmp(h, c, n) == 0) return k;
		if (hn > n && h[hn - n - 1] == '.' && strncmp(h + hn - n, c, n) == 0) {
			if (!nsuffix++) ends = k;
			else if (nsuffix == 2)
				csf_sweep_err(S, "--sweep-summary: '%s' names several columns ('%.*s', '%.*s'...): name one as in the header",
				     c, (int)csf_sweep_head_len(p, ends), csf_sweep_col_head(p, ends), (int)hn, h);
		}
	}
	if (nsuffix == 1) return ends;
	if (nsuffix > 1) return found;
	const char **names = malloc((p->ncols + 1) * sizeof *names);
	char **cut = calloc(p->ncols + 1, sizeof *cut);
	for (uint32_t k = 0; names && cut && k <= p->ncols; k++) names[k] = cut[k] = xstrndup0(csf_sweep_col_head(p, k), csf_sweep_head_len(p, k));
	const char *near = names && cut ? csf_suggest_name(c, names, (int)p->ncols + 1) : NULL;
	if (near) csf_sweep_err(S, "--sweep-summary: '%s' is not a watched column; did you mean '%s'?", c, near);
	else csf_sweep_err(S, "--sweep-summary: '%s' is not a watched column (the header of a run names them)", c);
	for (uint32_t k = 0; cut && k <= p->ncols; k++) free(cut[k]);
	free(cut);
	free(names);
	return found;
}

/*
 * A time at *s for a summary's window, `50`, `50 s` or `2 min` (a time unit), into *t in the model's
 * units; *s past it. 0, or -1 (a message in S).
 */
static int window_time(csf_sweep *S, const char *spec, const char **s, double *t)
{
	char *end;
	errno = 0;
	*t = strtod(*s, &end);
	if (end == *s || errno == ERANGE || !isfinite(*t))
		return csf_sweep_err(S, "--sweep-summary '%s': expected a time after 'from' or 'to' ('from 50 s')", spec);
	*s = end;
	while (**s == ' ') ++*s;
	if (!isalpha((unsigned char)**s)) return 0;
	csf_unit u;
	const char *why, *uend;
	if (csf_unit_parse(*s, &uend, &u, &why))
		return csf_sweep_err(S, "--sweep-summary '%s': the time's unit: %s", spec, why);
	for (size_t k = 0; k < sizeof u.dim; k++)
		if (u.dim[k] != (k == 2))
			return csf_sweep_err(S, "--sweep-summary '%s': '%.*s' is not a unit of time", spec, (int)(uend - *s), *s);
	const double d[CSF_NDIM] = { 0, 0, 1, 0 };
	*t *= csf_units_to_system(u.factor, d, S->p->ubase);
	*s = uend;
	return 0;
}

/* --sweep-summary 'max(ball.pos.z) from 50 s, final(t), mean(x) from 10 s to 20 s, ...' */
static int parse_summary(csf_sweep *S, const char *spec)
{
	static const char *const fn[] = { "final", "max", "min", "mean", "rms" };
	enum { NFN = sizeof fn / sizeof fn[0] };
	const char *s = spec;
	while (*s) {
		const char *open = strchr(s, '('), *close = open ? strchr(open, ')') : NULL;
		int func = -1;
		while (*s == ' ') s++;
		for (int k = 0; open && k < NFN; k++)
			if ((size_t)(open - s) == strlen(fn[k]) && memcmp(s, fn[k], (size_t)(open - s)) == 0) func = k;
		if (func < 0 || !close)
			return csf_sweep_err(S, "--sweep-summary '%s': expected final(COLUMN), max(COLUMN), min(COLUMN), mean(COLUMN) "
			            "or rms(COLUMN), each optionally followed by 'from TIME' and 'to TIME', separated by commas",
			            spec);
		char *col = xstrndup0(open + 1, (size_t)(close - open - 1));
		if (!col) return csf_sweep_err(S, "out of memory");
		char *c = trim(col);
		uint32_t found = find_column(S, c);
		if (found == UINT32_MAX) {
			free(col);
			return -1;
		}
		double from = -INFINITY, to = INFINITY;
		const char *w = close + 1, *wstart;
		while (*w == ' ') w++;
		wstart = w;
		for (int k = 0; k < 2; k++) {
			size_t n = strspn(w, "abcdefghijklmnopqrstuvwxyz");
			double *bound = n == 4 && strncmp(w, "from", 4) == 0 ? &from : n == 2 && strncmp(w, "to", 2) == 0 ? &to : NULL;
			if (!bound) break;
			w += n;
			while (*w == ' ') w++;
			if (window_time(S, spec, &w, bound)) return free(col), -1;
			while (*w == ' ') w++;
		}
		const char *wend = w;
		while (wend > wstart && wend[-1] == ' ') wend--;
		int st = 0;
		if (*w && *w != ',')
			st = csf_sweep_err(S, "--sweep-summary '%s': unexpected '%s' after %s(%s): expected 'from TIME', 'to TIME' or a comma",
			          spec, w, fn[func], c);
		else if (!(from <= to)) st = csf_sweep_err(S, "--sweep-summary '%s': the window ends before it starts", spec);
		else if (from > S->p->till)
			st = csf_sweep_err(S, "--sweep-summary '%s': the window starts after the run ends (t = %g)", spec, S->p->till);
		if (st) return free(col), st;
		sumcol *q = realloc(S->sum, (size_t)(S->nsum + 1) * sizeof *q);
		if (!q) return free(col), csf_sweep_err(S, "out of memory");
		S->sum = q;
		const char *h = csf_sweep_col_head(S->p, found), *unit = strstr(h, " [");
		size_t wn = (size_t)(wend - wstart);
		size_t cn = csf_sweep_head_len(S->p, found), hn = strlen(fn[func]) + cn + wn + (unit ? strlen(unit) : 0) + 4;
		char *head = malloc(hn);
		if (head)
			snprintf(head, hn, "%s(%.*s)%s%.*s%s", fn[func], (int)cn, h, wn ? " " : "", (int)wn, wstart, unit ? unit : "");
		S->sum[S->nsum++] = (sumcol){ func, found, from, to, head };
		free(col);
		if (!head) return csf_sweep_err(S, "out of memory");
		s = w;
		if (*s == ',') s++;
	}
	return S->nsum ? 0 : csf_sweep_err(S, "--sweep-summary: no column named");
}

/* The HDF5 file of -o RUN.h5, for S's variants (NULL after a message). */
static csf_h5 *h5_create(csf_sweep *S, const csf_h5_origin *h5)
{
	char err[1024];
	const char **heads = malloc((size_t)S->npar * sizeof *heads);
	if (!heads) return csf_sweep_err(S, "out of memory"), NULL;
	for (int k = 0; k < S->npar; k++) heads[k] = S->par[k].head;
	csf_h5 *h = csf_h5_sweep_create(S->o.output, S->p, &S->o, h5->model, h5->argc, h5->argv, S->nvar, S->npar, heads, err,
	                                sizeof err);
	free(heads);
	if (!h) csf_sweep_err(S, "%s", err);
	return h;
}

static void sweep_free(csf_sweep *S)
{
	for (int k = 0; k < S->npar; k++) free(S->par[k].name), free(S->par[k].head);
	for (int a = 0; a < S->nax; a++) free(S->ax[a].vals);
	for (int k = 0; k < S->nsum; k++) free(S->sum[k].head);
	free(S->par), free(S->ax), free(S->sum);
	csf_overlay_free(&S->init);
}

/* The sweep's place: the variants written, the header, the worst status so far. */
static int keep_sweep(csf_sweep *S, csf_keeper *k)
{
	unsigned long long taken = S->taken;
	int bad = csf_keep(k, "sweep.taken", &taken, sizeof taken) | CSF_KEEP(k, S->header_done) | CSF_KEEP(k, S->status);
	S->taken = S->first = (size_t)taken;
	return bad || taken > S->nvar ? -1 : 0;
}

void csf_sweep_checkpoint(csf_sweep *S)
{
	struct timespec now;
	clock_gettime(CLOCK_MONOTONIC, &now);
	double dt = (double)(now.tv_sec - S->ck_last.tv_sec) + 1e-9 * (double)(now.tv_nsec - S->ck_last.tv_nsec);
	/* (a signal: the variant just written may be cut short, and the last checkpoint stands) */
	if (csf_signal || dt < S->ck_every) return;
	char err[600];
	long long off = csf_keep_offset(S->out);
	unsigned long long hash = S->o.hash;
	csf_keeper *w = csf_keep_write(S->ck, err, sizeof err);
	if (w) {
		csf_keep_header(w, &hash, S->ck_opts, sizeof S->ck_opts, &off);
		keep_sweep(S, w);
		if (csf_keep_commit(w, S->ck, err, sizeof err)) w = NULL;
	}
	if (!w && !S->ck_warned) {
		fprintf(S->err, "warning: %s (the sweep goes on; the last checkpoint written stays as it was)\n", err);
		S->ck_warned = 1;
	}
	clock_gettime(CLOCK_MONOTONIC, &S->ck_last);
}

/*
 * --checkpoint, --resume of a sweep written as one stream (CSV, summaries,
 * --sweep-binary): a checkpoint after each variant written, when due, holds
 * how many are; a resumed sweep cuts the output back to their end and runs
 * the rest. 0, or -1 (reported).
 */
static int sweep_resume(csf_sweep *S, const csf_opts *o)
{
	char err[1400];
	S->ck = o->checkpoint ? o->checkpoint : o->resume;
	S->ck_every = o->checkpoint_every_set ? o->checkpoint_every : 60;
	clock_gettime(CLOCK_MONOTONIC, &S->ck_last);
	csf_keep_options(o, S->ck_opts, sizeof S->ck_opts);
	if (S->out_dir || S->h5rows || csf_sweep_distribute)
		return csf_sweep_err(S, "--checkpoint and --resume continue a sweep written as one stream, not %s",
		                     S->out_dir ? "--out-dir's files" : S->h5rows ? "-o FILE.h5" : "under MPI");
	if (!o->resume) return 0;
	long long off = -1;
	csf_keeper *k = csf_keep_read(o->resume, err, sizeof err);
	int bad = !k || csf_keep_check(k, o->resume, o->hash, S->ck_opts, sizeof S->ck_opts, &off, err, sizeof err);
	if (k && !bad && keep_sweep(S, k))
		bad = 1, snprintf(err, sizeof err, "--resume: %s does not fit this sweep: %s", o->resume, csf_keep_why(k));
	if (!bad && csf_keep_output(S->out, off, o->resume, err, sizeof err)) bad = 1;
	csf_keep_free(k);
	if (bad) fprintf(S->err, "error: %s%s\n", k ? "" : "--resume: ", err);
	return bad ? -1 : 0;
}

int csf_sweep_main(const csf_prog *p, csf_exec_fn exec, const csf_opts *o, const char *prog, const csf_h5_origin *h5,
                   FILE *out, FILE *err)
{
	csf_sweep S = { .p = p, .exec = exec, .o = *o, .prog = prog, .out = out, .err = err, .out_dir = o->out_dir,
	                .binary = o->sweep_binary, .h5rows = h5 != NULL };
	S.o.progress = CSF_PROGRESS_OFF;
	S.o.stats = 0;
	S.o.checkpoint = S.o.resume = NULL; /* the sweep's, not each variant's */
	int st = 2;
	if (o->sweep_file && parse_file(&S, o->sweep_file)) goto out;
	for (int k = 0; k < o->nsweeps; k++)
		if (parse_grid(&S, o->sweeps[k])) goto out;
	if (o->summary && parse_summary(&S, o->summary)) goto out;
	if (S.binary && S.out_dir) {
		csf_sweep_err(&S, "--sweep-binary writes one stream, not --out-dir's files");
		goto out;
	}
	if (S.nax > 64) {
		csf_sweep_err(&S, "more than 64 sweeps");
		goto out;
	}
	S.nvar = 1;
	for (int a = 0; a < S.nax; a++) {
		if (S.nvar > (size_t)1e12 / S.ax[a].count) {
			csf_sweep_err(&S, "more than 1e12 variants");
			goto out;
		}
		S.nvar *= S.ax[a].count;
	}
	/* each variant's initial values: -D's, then its swept values (after them, so that they win) */
	for (size_t k = 0; o->init && k < o->init->n; k++)
		if (csf_overlay_add(&S.init, o->init->v[k].slot, o->init->v[k].value)) goto nomem;
	S.ninit = S.init.n;
	for (int a = 0; a < S.nax; a++)
		for (int k = 0; k < S.ax[a].n; k++)
			if (csf_overlay_add(&S.init, 0, 0)) goto nomem; /* room for the variant's values */
	if (S.out_dir) {
		if (mkdir(S.out_dir, 0777) && errno != EEXIST) {
			csf_sweep_err(&S, "--out-dir: cannot create %s: %s", S.out_dir, strerror(errno));
			goto out;
		}
		char path[4096];
		snprintf(path, sizeof path, "%s/index.csv", S.out_dir);
		if (!(S.index = fopen(path, "w"))) {
			csf_sweep_err(&S, "--out-dir: cannot write %s: %s", path, strerror(errno));
			goto out;
		}
		fputs("run,file,status", S.index);
		for (int k = 0; k < S.npar; k++) fprintf(S.index, ",%s", S.par[k].head);
		fputc('\n', S.index);
	}
	if (h5 && !csf_quiet && !(S.h5 = h5_create(&S, h5))) goto out;
	if ((o->checkpoint || o->resume) && sweep_resume(&S, o)) goto out;
	long jobs = o->jobs > 0 ? o->jobs : sysconf(_SC_NPROCESSORS_ONLN);
	if (jobs < 1) jobs = 1;
	if ((size_t)jobs > S.nvar) jobs = (long)S.nvar;
	S.status = 0;
	int r = csf_sweep_distribute ? csf_sweep_distribute(&S) : 1;
	if (r > 0) r = jobs > 1 ? csf_sweep_run_forked(&S, (int)jobs) : csf_sweep_run_serial(&S);
	if (r < 0 && S.status < 2) S.status = 2;
	/* an HDF5 file: the variants not run (the sweep was interrupted) too, and closed */
	if (S.h5 && !S.h5err && csf_sweep_h5_rest(&S)) {
		fprintf(err, "error: cannot write output: %s\n", strerror(errno));
		S.status = 2;
	}
	if (S.h5 && csf_h5_close(S.h5)) {
		fprintf(err, "error: cannot write output: %s\n", strerror(errno));
		S.status = 2;
	}
	S.h5 = NULL;
	if (fflush(out) || ferror(out)) S.status = errno == EPIPE ? 128 + SIGPIPE : 2;
	if (S.index && fclose(S.index)) S.status = 2;
	S.index = NULL;
	st = csf_signal ? 128 + csf_signal : S.status;
	goto out;
nomem:
	csf_sweep_err(&S, "out of memory");
out:
	if (S.index) fclose(S.index);
	if (S.h5) csf_h5_close(S.h5);
	sweep_free(&S);
	return st;
}
