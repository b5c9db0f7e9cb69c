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
 * semaphores (sem_post is what a signal handler may call). The work of a
 * row is shared: the run formats t and the columns before `split` into the
 * slot's text, the thread the others, and the split moves towards the one
 * that waits less (the run that finds the ring full takes more columns, a
 * thread that finds it empty leaves more to the run), so that both
 * processors are busy whatever a row costs to compute. The thread writes
 * the text with write(2) from its own buffer of 1 MiB, flushed at least
 * once a second.
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
/* The ring: about this many bytes of values and text, and between 4 and 1024 rows. */
enum { RING_BYTES = 16 << 20 };
/* A cell's text at most (csf_fmt_put's 32 bytes and a comma), the thread's buffer of text. */
enum { CELL = 1 + 32, WBUF = 1 << 20 };

struct csf_rowthread {
	const csf_prog *p;
	FILE *out;
	pthread_t th;
	sem_t full, free_;   /* published rows not yet written; free slots */
	size_t nslots, width; /* slots; doubles in a slot (t and the columns) */
	double *ring;
	char *text;          /* each slot's text from the run: t and the columns before its split */
	size_t textcap;      /* bytes of text a slot holds */
	size_t *textlen;     /* per slot: its text's length */
	uint32_t *cut;       /* per slot: the columns the run formatted */
	uint32_t split;      /* the run's: the columns it formats (0 .. ncols) */
	atomic_int starved;  /* the thread found no row to write since the run last looked */
	int fd;              /* out's descriptor */
	char *wbuf;          /* the thread's text, not yet written */
	size_t wlen;
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

/* Formats columns [from, to) of row values v (t, then the columns) at dst, each after a comma: the length. */
static size_t cells(const double *v, uint32_t from, uint32_t to, char *dst)
{
	size_t n = 0;
	for (uint32_t i = from; i < to; i++) {
		dst[n++] = ',';
		n += (size_t)csf_fmt_put(dst + n, v[i + 1]);
	}
	return n;
}

/* Writes the thread's buffer to out's descriptor (after a signal, again; a partial write, the rest). */
static void drain(csf_rowthread *q)
{
	size_t at = 0;
	while (at < q->wlen && !atomic_load(&q->werr)) {
		ssize_t k = write(q->fd, q->wbuf + at, q->wlen - at);
		if (k < 0 && errno == EINTR) continue;
		if (k <= 0) atomic_store(&q->werr, k < 0 ? errno : EIO);
		else at += (size_t)k;
	}
	q->wlen = 0;
}

static void *writer(void *arg)
{
	csf_rowthread *q = arg;
	time_t flushed = 0;
	for (;;) {
		if (sem_trywait(&q->full) != 0) { /* nothing to write: leave more of each row to the run */
			atomic_store(&q->starved, 1);
			wait_sem(&q->full);
		}
		size_t w = atomic_load(&q->w);
		while (q->r < w) {
			size_t k = q->r % q->nslots;
			const double *v = q->ring + k * q->width;
			if (q->wlen >= WBUF) drain(q); /* then a row's text fits: wlen + rowcap < WBUF + rowcap */
			if (!atomic_load(&q->werr)) {
				memcpy(q->wbuf + q->wlen, q->text + k * q->textcap, q->textlen[k]);
				q->wlen += q->textlen[k];
				q->wlen += cells(v, q->cut[k], q->p->ncols, q->wbuf + q->wlen);
				q->wbuf[q->wlen++] = '\n';
			}
			q->r++;
			sem_post(&q->free_);
		}
		/* the rows reach out within a second, as emit_row's do (a slow run watched with tail -f) */
		struct timespec now;
		clock_gettime(CLOCK_MONOTONIC_COARSE, &now);
		if (now.tv_sec != flushed) {
			flushed = now.tv_sec;
			drain(q);
		}
		if (atomic_load(&q->done) && q->r == atomic_load(&q->w)) {
			drain(q);
			return NULL;
		}
		if (csf_watchdog_overdue() && q->r == atomic_load(&q->w)) { /* every row published written */
			drain(q);
			csf_watchdog_exit();
		}
	}
}

/* For the watchdog's handler: wakes the thread (async-signal-safe). */
static void wake(void)
{
	if (active) sem_post(&active->full);
}

/* Frees q and its buffers. */
static void release(csf_rowthread *q)
{
	free(q->ring);
	free(q->text);
	free(q->textlen);
	free(q->cut);
	free(q->wbuf);
	free(q);
}

csf_rowthread *csf_rowthread_start(const csf_prog *p, FILE *out)
{
	const char *env = getenv("CSF_ROW_THREAD");
	if (p->ncols < ROWTHREAD_MIN_COLS || (env && strcmp(env, "0") == 0) || sysconf(_SC_NPROCESSORS_ONLN) < 2 ||
	    fileno(out) < 0 || isatty(fileno(out)))
		return NULL;
	csf_rowthread *q = calloc(1, sizeof *q);
	if (!q) return NULL;
	q->p = p;
	q->out = out;
	q->width = (size_t)p->ncols + 1;
	q->textcap = q->width * CELL + 1;
	q->nslots = RING_BYTES / (q->width * sizeof(double) + q->textcap);
	if (q->nslots < 4) q->nslots = 4;
	if (q->nslots > 1024) q->nslots = 1024;
	q->split = p->ncols / 4;
	q->ring = malloc(q->nslots * q->width * sizeof(double));
	q->text = malloc(q->nslots * q->textcap);
	q->textlen = malloc(q->nslots * sizeof *q->textlen);
	q->cut = malloc(q->nslots * sizeof *q->cut);
	q->wbuf = malloc(WBUF + q->textcap);
	if (!q->ring || !q->text || !q->textlen || !q->cut || !q->wbuf || sem_init(&q->full, 0, 0) != 0) goto fail;
	if (sem_init(&q->free_, 0, (unsigned)q->nslots) != 0) {
		sem_destroy(&q->full);
		goto fail;
	}
	q->fd = fileno(out);
	if (fflush(out) != 0 || pthread_create(&q->th, NULL, writer, q) != 0) { /* (the header first) */
		sem_destroy(&q->full);
		sem_destroy(&q->free_);
		goto fail;
	}
	active = q;
	csf_watchdog_wakes(wake);
	return q;
fail:
	release(q);
	return NULL;
}

int csf_rowthread_put(csf_rowthread *q, const double *m, double t)
{
	int e = atomic_load(&q->werr);
	if (e) {
		errno = e;
		return -1;
	}
	/* the ring full: the thread is behind, the run takes more of each row; it was empty: less */
	uint32_t step = q->p->ncols / 64 + 1, n = q->p->ncols;
	if (sem_trywait(&q->free_) != 0) {
		q->split = q->split + step < n ? q->split + step : n;
		wait_sem(&q->free_);
	} else if (atomic_exchange(&q->starved, 0)) {
		q->split = q->split > step ? q->split - step : 0;
	}
	size_t w = atomic_load(&q->w), k = w % q->nslots;
	double *v = q->ring + k * q->width;
	v[0] = t;
	for (uint32_t i = 0; i < n; i++) v[i + 1] = m[q->p->cols[i].slot];
	char *text = q->text + k * q->textcap;
	size_t len = (size_t)csf_fmt_put(text, t);
	q->textlen[k] = len + cells(v, 0, q->split, text + len);
	q->cut[k] = q->split;
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
	release(q);
	return e;
}
