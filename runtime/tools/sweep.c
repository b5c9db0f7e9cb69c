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
 *
 * The values are printed in the model's units with the shortest text that
 * reads back to the same double, and a bare number given to -D is taken
 * as it is: `-D NAME=PRINTED` for each swept column reproduces the
 * variant's rows byte for byte.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csf.h"

int (*csf_sweep_distribute)(csf_sweep *s);

enum { SUM_FINAL, SUM_MAX, SUM_MIN, SUM_MEAN, SUM_RMS };

typedef struct sparam { char *name, *head; csf_pref ref; } sparam;
/* An axis: params [first, first + n), count entries of n values each (vals[entry * n + k]). */
typedef struct axis { int first, n; size_t count; double *vals; } axis;
/* A summary: func of column col over the rows with from <= t <= to. */
typedef struct sumcol { int func; uint32_t col; double from, to; char *head; } sumcol;

struct csf_sweep {
	const csf_prog *p;
	csf_exec_fn exec;
	csf_opts o;
	const char *prog;
	int npar, nax, nsum;
	sparam *par;
	axis *ax;
	sumcol *sum;
	size_t nvar;
	const char *out_dir;
	FILE *index;
	FILE *out, *err;
	int status, header_done;
	csf_overlay init; /* o->init (-D's values), then the variant's: the run's initial values over p's */
	size_t ninit;     /* how many of them are -D's */
};

static int serr(csf_sweep *S, const char *fmt, ...)
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
		if (strcmp(S->par[k].name, name) == 0) return serr(S, "%s: %s is swept twice", what, name);
	if (csf_param_find(S->p, name, &r, why, sizeof why)) return serr(S, "%s: %s", what, why);
	if (*csf_str(S->p, r.cls->why))
		return serr(S, "%s: %s cannot be overridden: %s", what, name, csf_str(S->p, r.cls->why));
	if (r.width != 1)
		return serr(S, "%s: %s is a vector; a sweep varies a scalar (a global the vector is computed from)", what, name);
	sparam *q = realloc(S->par, (size_t)(S->npar + 1) * sizeof *q);
	if (!q) return serr(S, "out of memory");
	S->par = q;
	const char *unit = csf_str(S->p, r.cls->unit);
	size_t hn = strlen(name) + strlen(unit) + 4;
	char *head = malloc(hn);
	if (head) snprintf(head, hn, *unit ? "%s [%s]" : "%s", name, unit);
	S->par[S->npar] = (sparam){ xstrndup0(name, strlen(name)), head, r };
	if (!S->par[S->npar].name || !head) return serr(S, "out of memory");
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
	if (!c2) return serr(S, "--sweep '%s': expected NAME=FROM:TO:COUNT [UNIT]", spec);
	char *name = xstrndup0(spec, (size_t)(eq - spec)), *from = xstrndup0(eq + 1, (size_t)(c1 - eq - 1)),
	     *to = xstrndup0(c1 + 1, (size_t)(c2 - c1 - 1));
	int st = -1;
	if (!name || !from || !to) goto done;
	char *end;
	errno = 0;
	long count = strtol(c2 + 1, &end, 10);
	if (end == c2 + 1 || errno || count < 1 || count > 100000000) {
		serr(S, "--sweep '%s': COUNT must be a whole number from 1 to 1e8", spec);
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
			serr(S, "--sweep '%s': %s", spec, why);
		} else {
			axis *ax = add_axis(S, k, 1, (size_t)count);
			if (!ax) serr(S, "out of memory");
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
	if (!text) return serr(S, "--sweep-file: cannot read %s: %s", path, strerror(errno));
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
					serr(S, "--sweep-file %s: more than %d columns", path, MAXF);
					goto out;
				}
				for (int k = 0; k < nf; k++) {
					char *name = header_cell(f[k], &units[k]);
					if (!name) {
						serr(S, "--sweep-file %s: header '%s': expected NAME or NAME [UNIT]", path, f[k]);
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
				serr(S, "--sweep-file %s:%d: %d values, the header names %d", path, lineno, nf, n);
				goto out;
			}
			if (pass)
				for (int k = 0; k < n; k++) {
					char why[400], buf[512];
					sparam *q = &S->par[first + k];
					double v[3];
					const char *cell = cell_value(S, q, units[k], f[k], buf, sizeof buf);
					if (csf_param_value(S->p, q->name, &q->ref, cell, v, why, sizeof why)) {
						serr(S, "--sweep-file %s:%d: %s", path, lineno, why);
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
				serr(S, "--sweep-file %s: no header or no rows", path);
				goto out;
			}
			ax = add_axis(S, first, n, rows);
			if (!ax) {
				serr(S, "out of memory");
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
static const char *col_head(const csf_prog *p, uint32_t c) { return c == 0 ? "t" : csf_str(p, p->cols[c - 1].name); }

/* The length of column k's header without its unit. */
static size_t head_len(const csf_prog *p, uint32_t k)
{
	const char *h = col_head(p, k), *u = strstr(h, " [");
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
		const char *h = col_head(p, k);
		size_t hn = head_len(p, k);
		if (hn == n && strncmp(h, c, n) == 0) return k;
		if (hn > n && h[hn - n - 1] == '.' && strncmp(h + hn - n, c, n) == 0) {
			if (!nsuffix++) ends = k;
			else if (nsuffix == 2)
				serr(S, "--sweep-summary: '%s' names several columns ('%.*s', '%.*s'...): name one as in the header",
				     c, (int)head_len(p, ends), col_head(p, ends), (int)hn, h);
		}
	}
	if (nsuffix == 1) return ends;
	if (nsuffix > 1) return found;
	const char **names = malloc((p->ncols + 1) * sizeof *names);
	char **cut = calloc(p->ncols + 1, sizeof *cut);
	for (uint32_t k = 0; names && cut && k <= p->ncols; k++) names[k] = cut[k] = xstrndup0(col_head(p, k), head_len(p, k));
	const char *near = names && cut ? csf_suggest_name(c, names, (int)p->ncols + 1) : NULL;
	if (near) serr(S, "--sweep-summary: '%s' is not a watched column; did you mean '%s'?", c, near);
	else serr(S, "--sweep-summary: '%s' is not a watched column (the header of a run names them)", c);
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
		return serr(S, "--sweep-summary '%s': expected a time after 'from' or 'to' ('from 50 s')", spec);
	*s = end;
	while (**s == ' ') ++*s;
	if (!isalpha((unsigned char)**s)) return 0;
	csf_unit u;
	const char *why, *uend;
	if (csf_unit_parse(*s, &uend, &u, &why))
		return serr(S, "--sweep-summary '%s': the time's unit: %s", spec, why);
	for (size_t k = 0; k < sizeof u.dim; k++)
		if (u.dim[k] != (k == 2))
			return serr(S, "--sweep-summary '%s': '%.*s' is not a unit of time", spec, (int)(uend - *s), *s);
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
			return serr(S, "--sweep-summary '%s': expected final(COLUMN), max(COLUMN), min(COLUMN), mean(COLUMN) "
			            "or rms(COLUMN), each optionally followed by 'from TIME' and 'to TIME', separated by commas",
			            spec);
		char *col = xstrndup0(open + 1, (size_t)(close - open - 1));
		if (!col) return serr(S, "out of memory");
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
			st = serr(S, "--sweep-summary '%s': unexpected '%s' after %s(%s): expected 'from TIME', 'to TIME' or a comma",
			          spec, w, fn[func], c);
		else if (!(from <= to)) st = serr(S, "--sweep-summary '%s': the window ends before it starts", spec);
		else if (from > S->p->till)
			st = serr(S, "--sweep-summary '%s': the window starts after the run ends (t = %g)", spec, S->p->till);
		if (st) return free(col), st;
		sumcol *q = realloc(S->sum, (size_t)(S->nsum + 1) * sizeof *q);
		if (!q) return free(col), serr(S, "out of memory");
		S->sum = q;
		const char *h = col_head(S->p, found), *unit = strstr(h, " [");
		size_t wn = (size_t)(wend - wstart);
		size_t cn = head_len(S->p, found), hn = strlen(fn[func]) + cn + wn + (unit ? strlen(unit) : 0) + 4;
		char *head = malloc(hn);
		if (head)
			snprintf(head, hn, "%s(%.*s)%s%.*s%s", fn[func], (int)cn, h, wn ? " " : "", (int)wn, wstart, unit ? unit : "");
		S->sum[S->nsum++] = (sumcol){ func, found, from, to, head };
		free(col);
		if (!head) return serr(S, "out of memory");
		s = w;
		if (*s == ',') s++;
	}
	return S->nsum ? 0 : serr(S, "--sweep-summary: no column named");
}

size_t csf_sweep_count(const csf_sweep *s) { return s->nvar; }

/* The entry of each axis in variant i (the last axis fastest). */
static void entries(const csf_sweep *S, size_t i, size_t *e)
{
	for (int a = S->nax - 1; a >= 0; a--) {
		e[a] = i % S->ax[a].count;
		i /= S->ax[a].count;
	}
}

/* Variant i's values: VALS_ROW "v1,v2," (the leading cells of its rows), VALS_INDEX ",v1,v2", VALS_NAMED "a=v1, b=v2". */
enum { VALS_ROW, VALS_INDEX, VALS_NAMED };
static void put_values(const csf_sweep *S, size_t i, FILE *f, int how)
{
	size_t e[64];
	entries(S, i, e);
	int first = 1;
	for (int a = 0; a < S->nax; a++)
		for (int k = 0; k < S->ax[a].n; k++) {
			char b[32];
			csf_fmt_double(b, S->ax[a].vals[e[a] * (size_t)S->ax[a].n + (size_t)k]);
			if (how == VALS_ROW) fprintf(f, "%s,", b);
			else if (how == VALS_INDEX) fprintf(f, ",%s", b);
			else fprintf(f, "%s%s=%s", first ? "" : ", ", S->par[S->ax[a].first + k].name, b);
			first = 0;
		}
}

/*
 * One summary value over a run's rows whose time is in the window: the last
 * value, the largest, the smallest, or the time average of the value (mean)
 * or of its square (rms, then its root) by the trapezoid rule over those
 * rows (a window of one row: its value). NaN when no row is in the window.
 * It is made as the rows come (sum_row, from the run's row sink), and
 * summary gives it at the end.
 */
typedef struct sumacc { double acc, t0, tp, xp, area; } sumacc;

static void sum_start(sumacc *a) { *a = (sumacc){ NAN, NAN, NAN, NAN, 0 }; }

/* The row at t whose value in c's column is x. */
static void sum_row(sumacc *a, const sumcol *c, double t, double x)
{
	if (!(t >= c->from && t <= c->to)) return;
	if (c->func == SUM_RMS) x *= x;
	if (c->func == SUM_MEAN || c->func == SUM_RMS) {
		if (isnan(a->t0)) a->t0 = t, a->acc = x;
		else a->area += (t - a->tp) * (a->xp + x) / 2;
		a->tp = t, a->xp = x;
	} else if (c->func == SUM_FINAL || isnan(a->acc)) a->acc = x;
	else if (c->func == SUM_MAX ? x > a->acc : x < a->acc) a->acc = x;
}

static double summary(const sumacc *a, const sumcol *c)
{
	double acc = a->acc;
	if ((c->func == SUM_MEAN || c->func == SUM_RMS) && a->tp > a->t0) acc = a->area / (a->tp - a->t0);
	return c->func == SUM_RMS ? sqrt(acc) : acc;
}

/* A run's summaries, made by its row sink. */
typedef struct summaries { const csf_sweep *S; sumacc *acc; } summaries;

static int summary_row(void *ctx, const double *v, size_t n)
{
	summaries *u = ctx;
	(void)n;
	for (int k = 0; k < u->S->nsum; k++) sum_row(&u->acc[k], &u->S->sum[k], v[0], v[u->S->sum[k].col]);
	return 0;
}

/* The text of variant i from its run's output: rows prefixed by its values, or its summary row. */
static void variant_text(const csf_sweep *S, size_t i, const char *out, const sumacc *acc, FILE *f)
{
	if (S->out_dir) {
		fputs(out, f);
		return;
	}
	const char *nl = strchr(out, '\n');
	if (!nl) return; /* no header: the run failed before its first row */
	fputs(S->par[0].head, f);
	for (int k = 1; k < S->npar; k++) fprintf(f, ",%s", S->par[k].head);
	if (S->nsum) {
		for (int k = 0; k < S->nsum; k++) fprintf(f, ",%s", S->sum[k].head);
		fputc('\n', f);
		put_values(S, i, f, VALS_ROW);
		for (int k = 0; k < S->nsum; k++) {
			char b[32];
			csf_fmt_double(b, summary(&acc[k], &S->sum[k]));
			fprintf(f, k ? ",%s" : "%s", b);
		}
		fputc('\n', f);
		return;
	}
	fputc(',', f);
	fwrite(out, 1, (size_t)(nl + 1 - out), f);
	for (const char *s = nl + 1; *s;) {
		const char *eol = strchr(s, '\n');
		size_t n = eol ? (size_t)(eol + 1 - s) : strlen(s);
		put_values(S, i, f, VALS_ROW);
		fwrite(s, 1, n, f);
		s += n;
	}
}

/* message: u64 index, u32 status, u64 text length, u64 diagnostics length, the text, the diagnostics */
enum { MSG_HEAD = 28 };

static void put64(unsigned char *b, uint64_t v)
{
	for (int k = 0; k < 8; k++) b[k] = (unsigned char)(v >> (8 * k));
}
static uint64_t get64(const unsigned char *b)
{
	uint64_t v = 0;
	for (int k = 0; k < 8; k++) v |= (uint64_t)b[k] << (8 * k);
	return v;
}

unsigned char *csf_sweep_run(csf_sweep *S, size_t i, size_t *len)
{
	size_t e[64];
	entries(S, i, e);
	S->init.n = S->ninit; /* room for every swept value: csf_sweep_main */
	for (int a = 0; a < S->nax; a++)
		for (int k = 0; k < S->ax[a].n; k++)
			S->init.v[S->init.n++] = (csf_setting){ S->par[S->ax[a].first + k].ref.slot,
			                                        S->ax[a].vals[e[a] * (size_t)S->ax[a].n + (size_t)k] };
	char *out = NULL, *err = NULL, *text = NULL;
	size_t olen = 0, elen = 0, tlen = 0;
	FILE *fo = open_memstream(&out, &olen), *fe = open_memstream(&err, &elen);
	int st = 2;
	summaries u = { S, S->nsum ? malloc((size_t)S->nsum * sizeof *u.acc) : NULL };
	for (int k = 0; u.acc && k < S->nsum; k++) sum_start(&u.acc[k]);
	if (fo && fe && (u.acc || !S->nsum)) {
		csf_opts o = S->o;
		o.init = &S->init;
		csf_sink sink = { summary_row, &u };
		st = csf_run_sink(S->p, S->exec, &o, fo, S->nsum ? &sink : NULL, fe);
	}
	if (fo) fclose(fo);
	if (fe) fclose(fe);
	FILE *ft = out ? open_memstream(&text, &tlen) : NULL;
	if (ft) {
		variant_text(S, i, out, u.acc, ft);
		fclose(ft);
	}
	unsigned char *m = text && err ? malloc(MSG_HEAD + tlen + elen) : NULL;
	if (m) {
		put64(m, i);
		for (int k = 0; k < 4; k++) m[8 + k] = (unsigned char)((uint32_t)st >> (8 * k));
		put64(m + 12, tlen);
		put64(m + 20, elen);
		memcpy(m + MSG_HEAD, text, tlen);
		memcpy(m + MSG_HEAD + tlen, err, elen);
		*len = MSG_HEAD + tlen + elen;
	}
	free(out);
	free(err);
	free(text);
	free(u.acc);
	return m;
}

/* Writes all of buf to fd; 0 or -1. */
static int write_all(int fd, const void *buf, size_t n)
{
	const char *b = buf;
	while (n) {
		ssize_t w = write(fd, b, n);
		if (w < 0 && errno == EINTR) continue;
		if (w <= 0) return -1;
		b += w;
		n -= (size_t)w;
	}
	return 0;
}

static int read_all(int fd, void *buf, size_t n)
{
	char *b = buf;
	while (n) {
		ssize_t r = read(fd, b, n);
		if (r < 0 && errno == EINTR) continue;
		if (r <= 0) return -1;
		b += r;
		n -= (size_t)r;
	}
	return 0;
}

int csf_sweep_take(csf_sweep *S, size_t i, const unsigned char *m, size_t len)
{
	if (!m || len < MSG_HEAD || get64(m) != i) {
		fprintf(S->err, "%s: run %zu: its result was lost (out of memory or a worker died)\n", S->prog, i + 1);
		S->status = 2;
		return -1;
	}
	int st = (int)((uint32_t)m[8] | (uint32_t)m[9] << 8 | (uint32_t)m[10] << 16 | (uint32_t)m[11] << 24);
	uint64_t tlen = get64(m + 12), elen = get64(m + 20);
	if (tlen > len - MSG_HEAD || elen != len - MSG_HEAD - tlen) {
		fprintf(S->err, "%s: run %zu: malformed result\n", S->prog, i + 1);
		S->status = 2;
		return -1;
	}
	const char *text = (const char *)m + MSG_HEAD, *diag = text + tlen;
	if (S->out_dir) {
		char path[4096];
		snprintf(path, sizeof path, "%s/run-%05zu.csv", S->out_dir, i + 1);
		FILE *f = fopen(path, "w");
		if (!f || fwrite(text, 1, tlen, f) != tlen || fclose(f)) {
			fprintf(S->err, "%s: cannot write %s: %s\n", S->prog, path, strerror(errno));
			S->status = 2;
			return -1;
		}
		fprintf(S->index, "%zu,run-%05zu.csv,%d", i + 1, i + 1, st);
		put_values(S, i, S->index, VALS_INDEX);
		fputc('\n', S->index);
	} else {
		const char *body = text;
		if (S->header_done) {
			const char *nl = memchr(text, '\n', tlen);
			body = nl ? nl + 1 : text + tlen;
		}
		if (tlen) S->header_done = 1;
		csf_out_begin();
		fwrite(body, 1, tlen - (size_t)(body - text), S->out);
		csf_out_end();
	}
	for (const char *s = diag; s < diag + elen;) {
		const char *eol = memchr(s, '\n', (size_t)(diag + elen - s));
		size_t n = eol ? (size_t)(eol - s) : (size_t)(diag + elen - s);
		fprintf(S->err, "%s: run %zu (", S->prog, i + 1);
		put_values(S, i, S->err, VALS_NAMED);
		fprintf(S->err, "): %.*s\n", (int)n, s);
		s += n + 1;
	}
	if (st > S->status) S->status = st;
	if (ferror(S->out)) {
		S->status = 2;
		return -1;
	}
	return 0;
}

/* Runs every variant here, in order. */
static int run_serial(csf_sweep *S)
{
	for (size_t i = 0; i < S->nvar && !csf_signal; i++) {
		size_t len = 0;
		unsigned char *m = csf_sweep_run(S, i, &len);
		int r = csf_sweep_take(S, i, m, len);
		free(m);
		if (r) return -1;
	}
	return 0;
}

typedef struct worker { pid_t pid; int task, res; size_t inflight; } worker;

/* A worker process: runs the batches of variants the parent sends (u64 first, u64 count) and sends back each message. */
static void worker_loop(csf_sweep *S, int task, int res)
{
	unsigned char b[16];
	while (read_all(task, b, 16) == 0)
		for (size_t i = get64(b), n = get64(b + 8); n--; i++) {
			size_t len = 0;
			unsigned char *m = csf_sweep_run(S, i, &len), l[8];
			put64(l, m ? len : 0);
			if (write_all(res, l, 8) || (m && write_all(res, m, len))) _exit(2);
			free(m);
		}
	_exit(0);
}

/* Sends worker w the next batch of (up to) batch variants. */
static int send_task(csf_sweep *S, worker *w, size_t *next, size_t batch)
{
	if (*next >= S->nvar || csf_signal) return 0;
	size_t n = S->nvar - *next < batch ? S->nvar - *next : batch;
	unsigned char b[16];
	put64(b, *next);
	put64(b + 8, n);
	if (write_all(w->task, b, 16)) return -1;
	*next += n;
	w->inflight += n;
	return 0;
}

/*
 * -j N: N worker processes, each given batches of consecutive variants
 * (about 1/32 of its share, at most 64, so that a pipe's round trip costs
 * little beside a short run and the last batches still balance the load);
 * each has two batches in hand, the next sent when one is done. Results
 * that arrive before their turn wait in got[] until the writer reaches
 * them.
 */
static int run_forked(csf_sweep *S, int nw)
{
	worker *w = calloc((size_t)nw, sizeof *w);
	unsigned char **got = calloc(S->nvar, sizeof *got);
	size_t *glen = calloc(S->nvar, sizeof *glen);
	struct pollfd *pf = calloc((size_t)nw, sizeof *pf);
	if (!w || !got || !glen || !pf) {
		free(w), free(got), free(glen), free(pf);
		return serr(S, "out of memory");
	}
	fflush(NULL);
	int started = 0, bad = 0;
	for (; started < nw; started++) {
		int t[2], r[2];
		if (pipe(t)) break;
		if (pipe(r)) {
			close(t[0]), close(t[1]);
			break;
		}
		pid_t pid = fork();
		if (pid < 0) {
			close(t[0]), close(t[1]), close(r[0]), close(r[1]);
			break;
		}
		if (pid == 0) {
			for (int k = 0; k < started; k++) close(w[k].task), close(w[k].res);
			close(t[1]), close(r[0]);
			worker_loop(S, t[0], r[1]);
		}
		close(t[0]), close(r[1]);
		w[started] = (worker){ pid, t[1], r[0], 0 };
	}
	if (started == 0) bad = serr(S, "cannot start worker processes: %s", strerror(errno));
	size_t next = 0, written = 0, batch = S->nvar / ((size_t)(started ? started : 1) * 32);
	batch = batch < 1 ? 1 : batch > 64 ? 64 : batch;
	for (int k = 0; k < started && !bad; k++)
		for (int q = 0; q < 2; q++) bad = send_task(S, &w[k], &next, batch);
	while (!bad && written < next) {
		int n = 0;
		for (int k = 0; k < started; k++)
			if (w[k].inflight) pf[n++] = (struct pollfd){ .fd = w[k].res, .events = POLLIN };
		if (poll(pf, (nfds_t)n, -1) < 0) {
			if (errno == EINTR) continue;
			bad = -1;
			break;
		}
		for (int k = 0; k < started && !bad; k++) {
			int ready = 0;
			for (int q = 0; q < n; q++) ready |= pf[q].fd == w[k].res && pf[q].revents;
			if (!ready) continue;
			unsigned char l[8];
			if (read_all(w[k].res, l, 8)) {
				bad = serr(S, "a worker process ended unexpectedly");
				break;
			}
			size_t len = get64(l);
			unsigned char *m = len >= MSG_HEAD ? malloc(len) : NULL;
			if (m && read_all(w[k].res, m, len)) {
				free(m);
				bad = serr(S, "a worker process ended unexpectedly");
				break;
			}
			size_t i = m ? get64(m) : SIZE_MAX;
			if (i >= S->nvar || got[i]) {
				free(m);
				bad = serr(S, "a worker process sent a bad result");
				break;
			}
			got[i] = m;
			glen[i] = len;
			/* a batch done: the next (two stay in hand) */
			if (--w[k].inflight <= batch) bad = send_task(S, &w[k], &next, batch);
		}
		while (!bad && written < next && got[written]) {
			if (csf_sweep_take(S, written, got[written], glen[written])) bad = -1;
			free(got[written]);
			got[written++] = NULL;
		}
	}
	for (int k = 0; k < started; k++) {
		close(w[k].task);
		close(w[k].res);
		if (bad) kill(w[k].pid, SIGTERM);
	}
	for (int k = 0; k < started; k++) waitpid(w[k].pid, NULL, 0);
	for (size_t i = 0; i < S->nvar; i++) free(got[i]);
	free(w), free(got), free(glen), free(pf);
	return bad ? -1 : 0;
}

static void sweep_free(csf_sweep *S)
{
	for (int k = 0; k < S->npar; k++) free(S->par[k].name), free(S->par[k].head);
	for (int a = 0; a < S->nax; a++) free(S->ax[a].vals);
	for (int k = 0; k < S->nsum; k++) free(S->sum[k].head);
	free(S->par), free(S->ax), free(S->sum);
	csf_overlay_free(&S->init);
}

int csf_sweep_main(const csf_prog *p, csf_exec_fn exec, const csf_opts *o, const char *prog, FILE *out, FILE *err)
{
	csf_sweep S = { .p = p, .exec = exec, .o = *o, .prog = prog, .out = out, .err = err, .out_dir = o->out_dir };
	S.o.progress = CSF_PROGRESS_OFF;
	S.o.stats = 0;
	int st = 2;
	if (o->sweep_file && parse_file(&S, o->sweep_file)) goto out;
	for (int k = 0; k < o->nsweeps; k++)
		if (parse_grid(&S, o->sweeps[k])) goto out;
	if (o->summary && parse_summary(&S, o->summary)) goto out;
	if (S.nax > 64) {
		serr(&S, "more than 64 sweeps");
		goto out;
	}
	S.nvar = 1;
	for (int a = 0; a < S.nax; a++) {
		if (S.nvar > (size_t)1e12 / S.ax[a].count) {
			serr(&S, "more than 1e12 variants");
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
			serr(&S, "--out-dir: cannot create %s: %s", S.out_dir, strerror(errno));
			goto out;
		}
		char path[4096];
		snprintf(path, sizeof path, "%s/index.csv", S.out_dir);
		if (!(S.index = fopen(path, "w"))) {
			serr(&S, "--out-dir: cannot write %s: %s", path, strerror(errno));
			goto out;
		}
		fputs("run,file,status", S.index);
		for (int k = 0; k < S.npar; k++) fprintf(S.index, ",%s", S.par[k].head);
		fputc('\n', S.index);
	}
	long jobs = o->jobs > 0 ? o->jobs : sysconf(_SC_NPROCESSORS_ONLN);
	if (jobs < 1) jobs = 1;
	if ((size_t)jobs > S.nvar) jobs = (long)S.nvar;
	S.status = 0;
	int r = csf_sweep_distribute ? csf_sweep_distribute(&S) : 1;
	if (r > 0) r = jobs > 1 ? run_forked(&S, (int)jobs) : run_serial(&S);
	if (r < 0 && S.status < 2) S.status = 2;
	if (fflush(out) || ferror(out)) S.status = errno == EPIPE ? 128 + SIGPIPE : 2;
	if (S.index && fclose(S.index)) S.status = 2;
	S.index = NULL;
	st = csf_signal ? 128 + csf_signal : S.status;
	goto out;
nomem:
	serr(&S, "out of memory");
out:
	if (S.index) fclose(S.index);
	sweep_free(&S);
	return st;
}
