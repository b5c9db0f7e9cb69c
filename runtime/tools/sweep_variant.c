/*
 * sweep_variant.c - one variant of a sweep (sweep.c): its values set over
 * the program's initial memory, its run, its text (rows with the values as
 * leading columns, or its summary row), and the message that carries its
 * result to the one writer, which takes the messages in variant order. With
 * --sweep-binary the text is the header line and then each row's values as
 * doubles (the run's rows taken from its sink, never formatted); for an
 * HDF5 file (-o RUN.h5) the rows' doubles alone, which the writer gives
 * csf_h5_sweep_variant with the variant's values and status.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_int.h"

size_t csf_sweep_count(const csf_sweep *s) { return s->nvar; }

/* The entry of each axis in variant i (the last axis fastest). */
static void entries(const csf_sweep *S, size_t i, size_t *e)
{
	for (int a = S->nax - 1; a >= 0; a--) {
		e[a] = i % S->ax[a].count;
		i /= S->ax[a].count;
	}
}

/* Variant i's swept values into v[0 .. S->npar). */
static void values_of(const csf_sweep *S, size_t i, double *v)
{
	size_t e[64];
	entries(S, i, e);
	for (int a = 0, j = 0; a < S->nax; a++)
		for (int k = 0; k < S->ax[a].n; k++) v[j++] = S->ax[a].vals[e[a] * (size_t)S->ax[a].n + (size_t)k];
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

/* A run's summaries, made by its row sink; with --sweep-binary and no summaries, its rows (n values each). */
typedef struct summaries {
	const csf_sweep *S;
	sumacc *acc;
	double *rows;
	size_t nrows, cap;
} summaries;

static int summary_row(void *ctx, const double *v, size_t n)
{
	summaries *u = ctx;
	for (int k = 0; k < u->S->nsum; k++) sum_row(&u->acc[k], &u->S->sum[k], v[0], v[u->S->sum[k].col]);
	if (!(u->S->binary || u->S->h5rows) || u->S->nsum) return 0;
	if (u->nrows == u->cap) {
		size_t cap = u->cap ? 2 * u->cap : 64;
		double *r = realloc(u->rows, cap * n * sizeof *r);
		if (!r) return -1; /* (errno ENOMEM: the run reports it) */
		u->rows = r, u->cap = cap;
	}
	memcpy(u->rows + u->nrows++ * n, v, n * sizeof *v);
	return 0;
}

/*
 * --sweep-binary: variant i's text, the header line of the CSV (always, also when the run failed
 * before its first row), then each row as doubles: its swept values, then t and the columns (or
 * the summaries: one row).
 */
static void variant_binary(const csf_sweep *S, size_t i, const summaries *u, FILE *f)
{
	const csf_prog *p = S->p;
	for (int k = 0; k < S->npar; k++) fprintf(f, "%s%s", k ? "," : "", S->par[k].head);
	if (S->nsum)
		for (int k = 0; k < S->nsum; k++) fprintf(f, ",%s", S->sum[k].head);
	else
		for (uint32_t c = 0; c <= p->ncols; c++) fprintf(f, ",%s", csf_sweep_col_head(p, c));
	fputc('\n', f);
	double *v = malloc(((size_t)S->npar + 1) * sizeof *v);
	if (!v) return; /* (the message's length tells the writer) */
	values_of(S, i, v);
	if (S->nsum) {
		fwrite(v, sizeof *v, (size_t)S->npar, f);
		for (int k = 0; k < S->nsum; k++) {
			double x = summary(&u->acc[k], &S->sum[k]);
			fwrite(&x, sizeof x, 1, f);
		}
	}
	size_t n = (size_t)p->ncols + 1;
	for (size_t r = 0; !S->nsum && r < u->nrows; r++) {
		fwrite(v, sizeof *v, (size_t)S->npar, f);
		fwrite(u->rows + r * n, sizeof *u->rows, n, f);
	}
	free(v);
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
	/* the run's CSV, but with --sweep-binary and -o RUN.h5 (whose rows come from the sink alone) */
	int rows = S->binary || S->h5rows;
	FILE *fo = rows ? NULL : open_memstream(&out, &olen), *fe = open_memstream(&err, &elen);
	int st = 2;
	summaries u = { S, S->nsum ? malloc((size_t)S->nsum * sizeof *u.acc) : NULL, NULL, 0, 0 };
	for (int k = 0; u.acc && k < S->nsum; k++) sum_start(&u.acc[k]);
	if ((fo || rows) && fe && (u.acc || !S->nsum)) {
		csf_opts o = S->o;
		o.init = &S->init;
		csf_sink sink = { summary_row, &u, NULL };
		st = csf_run_sink(S->p, S->exec, &o, fo, S->nsum || rows ? &sink : NULL, fe);
	}
	if (fo) fclose(fo);
	if (fe) fclose(fe);
	FILE *ft = out || rows ? open_memstream(&text, &tlen) : NULL;
	if (ft) {
		if (S->h5rows) fwrite(u.rows, sizeof *u.rows, u.nrows * ((size_t)S->p->ncols + 1), ft);
		else if (S->binary) variant_binary(S, i, &u, ft);
		else variant_text(S, i, out, u.acc, ft);
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
	free(u.rows);
	return m;
}

/* Writes all of buf to fd; 0 or -1. */
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
	size_t rowlen = ((size_t)S->p->ncols + 1) * sizeof(double);
	if (S->h5rows && tlen % rowlen) {
		fprintf(S->err, "%s: run %zu: malformed result\n", S->prog, i + 1);
		S->status = 2;
		return -1;
	}
	S->taken = i + 1;
	int werr = 0;
	if (S->h5rows) {
		double *v = malloc((size_t)S->npar * sizeof *v);
		if (v) values_of(S, i, v);
		if (S->h5 && (!v || csf_h5_sweep_variant(S->h5, i, v, st, text, tlen / rowlen))) werr = v ? errno : ENOMEM;
		free(v);
	} else if (S->out_dir) {
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
	if (werr) fprintf(S->err, "error: cannot write output: %s\n", strerror(werr)), S->h5err = 1;
	if (werr || ferror(S->out)) {
		S->status = 2;
		return -1;
	}
	if (S->ck) csf_sweep_checkpoint(S);
	return 0;
}

int csf_sweep_h5_rest(csf_sweep *S)
{
	double *v = malloc((size_t)S->npar * sizeof *v);
	int bad = !v;
	for (size_t i = S->taken; S->h5 && i < S->nvar && !bad; i++) {
		values_of(S, i, v);
		bad = csf_h5_sweep_variant(S->h5, i, v, -1, NULL, 0);
	}
	free(v);
	return bad ? -1 : 0;
}

