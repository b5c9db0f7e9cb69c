/*
 * rowthread.c - wide rows formatted and written by a second thread. A row
 * of many columns costs more to print (some 30 ns a cell, csf_fmt_put) than
 * to compute; where the machine has a second processor, csfvm hands each
 * row's values to a thread that formats and writes them while the run goes
 * on to the next row. The text is the same, byte for byte (the same
 * formatter, the rows in order); nothing is lost on any way out:
 *
 *  - a row is handed over whole (its values copied into a ring of slots,
 *    then published), and the thread writes only whole rows;
 *  - the end of a run, a failed assertion or a non-finite value: the run
 *    stops the thread (csf_rowthread_stop), which writes every row published
 *    before it, then the caller flushes;
 *  - a write error (a full disk, a closed pipe): the thread notes it and
 *    writes no more, the run sees it at its next row, as it would have seen
 *    fwrite's;
 *  - the watchdog (signals.c), whose run no longer looks: the thread writes
 *    the rows published and ends the process itself, as the watchdog would.
 *
 * The ring is a single producer and a single consumer, counted by two
 * semaphores (sem_post is what a signal handler may call).
 */
#include <errno.h>
#include <pthread.h>
#include <semaphore.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "run_int.h"

/* The fewest columns for which a second thread pays (below it, rows are written as they come). */
enum { ROWTHREAD_MIN_COLS = 64 };
/* The ring: about this many bytes of values, and between 4 and 1024 rows. */
enum { RING_BYTES = 4 << 20 };

struct csf_rowthread {
	const csf_prog *p;
	FILE *out;
	pthread_t th;
	sem_t full, free_;   /* published rows not yet written; free slots */
	size_t nslots, width; /* slots; doubles in a slot (t and the columns) */
	double *ring;
	size_t w;            /* rows published (the producer's) */
	size_t r;            /* rows written (the thread's) */
	atomic_int done;     /* no more rows will come */
	atomic_int werr;     /* the first write error (errno), or 0 */
};

static csf_rowthread *volatile active; /* the one the watchdog wakes */

/* sem_wait, again after a signal */
static void wait_sem(sem_t *s)
{
	while (sem_wait(s) != 0 && errno == EINTR) {
	}
}

/* Writes one row of values (t, then the columns) to out, as csf_run_write_row does. */
static int write_values(const csf_prog *p, const double *v, FILE *out)
{
	enum { ROW_BUF = 8192, CELL = 1 + 32 };
	char row[ROW_BUF];
	size_t n = (size_t)csf_fmt_put(row, v[0]);
	for (uint32_t i = 0; i < p->ncols; i++) {
		if (n + CELL > sizeof row) {
			fwrite(row, 1, n, out);
			n = 0;
		}
		row[n++] = ',';
		n += (size_t)csf_fmt_put(row + n, v[i + 1]);
	}
	row[n++] = '\n';
	fwrite(row, 1, n, out);
	return ferror(out) ? -1 : 0;
}

static void *writer(void *arg)
{
	csf_rowthread *q = arg;
	time_t flushed = 0;
	for (;;) {
		wait_sem(&q->full);
		size_t w = atomic_load(&q->w);
		while (q->r < w) {
			const double *v = q->ring + (q->r % q->nslots) * q->width;
			if (!atomic_load(&q->werr) && write_values(q->p, v, q->out)) atomic_store(&q->werr, errno ? errno : EIO);
			q->r++;
			sem_post(&q->free_);
		}
		/* the rows reach out within a second, as emit_row's do (a slow run watched with tail -f) */
		struct timespec now;
		clock_gettime(CLOCK_MONOTONIC_COARSE, &now);
		if (now.tv_sec != flushed && !atomic_load(&q->werr)) {
			flushed = now.tv_sec;
			if (fflush(q->out) != 0) atomic_store(&q->werr, errno ? errno : EIO);
		}
		if (atomic_load(&q->done) && q->r == atomic_load(&q->w)) return NULL;
		if (csf_watchdog_overdue() && q->r == atomic_load(&q->w)) csf_watchdog_exit(); /* every row published written */
	}
}

/* For the watchdog's handler: wakes the thread (async-signal-safe). */
static void wake(void)
{
	if (active) sem_post(&active->full);
}

csf_rowthread *csf_rowthread_start(const csf_prog *p, FILE *out)
{
	const char *env = getenv("CSF_ROW_THREAD");
	if (p->ncols < ROWTHREAD_MIN_COLS || (env && strcmp(env, "0") == 0) || sysconf(_SC_NPROCESSORS_ONLN) < 2 ||
	    isatty(fileno(out)))
		return NULL;
	csf_rowthread *q = calloc(1, sizeof *q);
	if (!q) return NULL;
	q->p = p;
	q->out = out;
	q->width = (size_t)p->ncols + 1;
	q->nslots = RING_BYTES / (q->width * sizeof(double));
	if (q->nslots < 4) q->nslots = 4;
	if (q->nslots > 1024) q->nslots = 1024;
	q->ring = malloc(q->nslots * q->width * sizeof(double));
	if (!q->ring || sem_init(&q->full, 0, 0) != 0) goto fail;
	if (sem_init(&q->free_, 0, (unsigned)q->nslots) != 0) {
		sem_destroy(&q->full);
		goto fail;
	}
	if (fflush(out) != 0 || pthread_create(&q->th, NULL, writer, q) != 0) { /* (the header first) */
		sem_destroy(&q->full);
		sem_destroy(&q->free_);
		goto fail;
	}
	active = q;
	csf_watchdog_wakes(wake);
	return q;
fail:
	free(q->ring);
	free(q);
	return NULL;
}

int csf_rowthread_put(csf_rowthread *q, const double *m, double t)
{
	int e = atomic_load(&q->werr);
	if (e) {
		errno = e;
		return -1;
	}
	wait_sem(&q->free_);
	size_t w = atomic_load(&q->w);
	double *v = q->ring + (w % q->nslots) * q->width;
	v[0] = t;
	for (uint32_t i = 0; i < q->p->ncols; i++) v[i + 1] = m[q->p->cols[i].slot];
	atomic_store(&q->w, w + 1);
	sem_post(&q->full);
	return 0;
}

int csf_rowthread_stop(csf_rowthread *q)
{
	atomic_store(&q->done, 1);
	sem_post(&q->full);
	pthread_join(q->th, NULL);
	csf_watchdog_wakes(NULL);
	active = NULL;
	int e = atomic_load(&q->werr);
	sem_destroy(&q->full);
	sem_destroy(&q->free_);
	free(q->ring);
	free(q);
	return e;
}
