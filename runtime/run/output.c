/*
 * output.c - the CSV rows on out, and the flush that reports a write error
 * (or ends quietly for a reader that went away).
 */
#include <errno.h>
#include <signal.h>
#include <string.h>

#include "run_int.h"

/*
 * A row: built in a buffer (each cell by csf_fmt_put, which needs room for 32
 * bytes) and written with one fwrite, or one per ROW_BUF bytes of a very
 * wide row.
 */
int csf_run_write_row(const csf_prog *p, const double *m, double t, FILE *out)
{
	enum { ROW_BUF = 8192, CELL = 1 + 32 };
	char row[ROW_BUF];
	csf_out_begin();
	size_t n = (size_t)csf_fmt_put(row, t);
	for (uint32_t i = 0; i < p->ncols; i++) {
		if (n + CELL > sizeof row) {
			fwrite(row, 1, n, out);
			n = 0;
		}
		row[n++] = ',';
		n += (size_t)csf_fmt_put(row + n, m[p->cols[i].slot]);
	}
	row[n++] = '\n';
	fwrite(row, 1, n, out);
	csf_out_end();
	return ferror(out) ? -1 : 0;
}

/*
 * Flushes out: its error (werr, from a row, or fflush's) is reported with
 * status 2, but for a reader that went away (EPIPE: `csfvm ... | head`),
 * which ends the run quietly as it ends cat, with the status of SIGPIPE.
 */
int csf_run_finish(FILE *out, FILE *err, int status, int werr)
{
	csf_out_begin();
	/* (no out: rows to a sink alone; werr without ferror: the row thread's write(2)) */
	int bad = out ? fflush(out) != 0 || ferror(out) || werr != 0 : werr != 0;
	csf_out_end();
	if (bad) {
		int e = werr ? werr : errno;
		if (e == EPIPE) return 128 + SIGPIPE;
		fprintf(err, "error: cannot write output: %s\n", strerror(e));
		return 2;
	}
	return status;
}


/* The CSV header: t and the columns' names. */
void csf_run_write_header(const csf_prog *p, FILE *out)
{
	csf_out_begin();
	fputs("t", out);
	for (uint32_t i = 0; i < p->ncols; i++) fprintf(out, ",%s", csf_str(p, p->cols[i].name));
	putc('\n', out);
	csf_out_end();
}
