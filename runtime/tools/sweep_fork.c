/*
 * sweep_fork.c - where a sweep's variants run (sweep.c): here, in order, or
 * in -j N worker processes that take batches of variant numbers from a pipe
 * and send each result back as one message.
 */
#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sweep_int.h"

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


/* Runs every variant here, in order. */
int csf_sweep_run_serial(csf_sweep *S)
{
	for (size_t i = S->first; i < S->nvar && !csf_signal; i++) {
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
int csf_sweep_run_forked(csf_sweep *S, int nw)
{
	worker *w = calloc((size_t)nw, sizeof *w);
	unsigned char **got = calloc(S->nvar, sizeof *got);
	size_t *glen = calloc(S->nvar, sizeof *glen);
	struct pollfd *pf = calloc((size_t)nw, sizeof *pf);
	if (!w || !got || !glen || !pf) {
		free(w), free(got), free(glen), free(pf);
		return csf_sweep_err(S, "out of memory");
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
	if (started == 0) bad = csf_sweep_err(S, "cannot start worker processes: %s", strerror(errno));
	size_t next = S->first, written = S->first, batch = S->nvar / ((size_t)(started ? started : 1) * 32);
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
				bad = csf_sweep_err(S, "a worker process ended unexpectedly");
				break;
			}
			size_t len = get64(l);
			unsigned char *m = len >= MSG_HEAD ? malloc(len) : NULL;
			if (m && read_all(w[k].res, m, len)) {
				free(m);
				bad = csf_sweep_err(S, "a worker process ended unexpectedly");
				break;
			}
			size_t i = m ? get64(m) : SIZE_MAX;
			if (i >= S->nvar || got[i]) {
				free(m);
				bad = csf_sweep_err(S, "a worker process sent a bad result");
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

