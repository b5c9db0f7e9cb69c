/*
 * progress.c - the progress line on stderr while a run lasts, and the clock
 * it and --stats read.
 */
#include <math.h>

#include "run_int.h"

/* Seconds from a to b. */
double csf_run_seconds(struct timespec a, struct timespec b)
{
	return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

/*
 * The progress line (a terminal's stderr, or --progress): "t = T of TILL s
 * (P %), R rows/s, ETA E s", redrawn in place at most 10 times a second,
 * the first time after 0.1 s (a short run shows none).
 */
void csf_run_progress(run *r, double t)
{
	struct timespec now;
	clock_gettime(CLOCK_MONOTONIC, &now);
	if (csf_run_seconds(r->drawn, now) < 0.1) return;
	r->drawn = now;
	double el = csf_run_seconds(r->start, now);
	double frac = r->tend > 0 ? fmin(1, t / r->tend) : 1;
	char eta[48] = "";
	if (frac > 0 && frac < 1) snprintf(eta, sizeof eta, ", ETA %.0f s", el * (1 - frac) / frac);
	fprintf(r->err, "\r\033[Kt = %.4g of %g s (%.0f %%), %.0f rows/s%s", t, r->tend, 100 * frac,
	        (double)r->rows / el, eta);
	fflush(r->err);
	r->shown = 1;
}

/* Erases the progress line, before a message or at the end. */
void csf_run_progress_off(run *r)
{
	if (!r->shown) return;
	fputs("\r\033[K", r->err);
	fflush(r->err);
	r->shown = 0;
}
