/*
 * par.c - the threads of one run (par.h).
 *
 * The pool's n - 1 workers wait on a condition variable for a job: a
 * generation count goes up, each worker takes chunks of the iterations
 * from a shared counter until none is left, and the last to finish wakes
 * the caller, which took chunks meanwhile. Chunk c of count iterations is
 * [count c / k, count (c + 1) / k), k = min(count, PAR_CHUNKS n): small
 * enough that a thread slowed down by another program on its processor
 * holds up the others by one chunk at most. Each iteration runs whole on
 * one thread, its instructions in their order, so every value it computes
 * is the serial run's. The caller runs the last chunk, after every other
 * chunk it took, in m itself: the values a serial run leaves behind in the
 * iteration's own slots are the last iteration's, and they are there.
 *
 * A VM worker works in a memory of its own (the body's fixed scratch slots
 * are shared slots of m): before the job the caller copies into it the
 * slots the body reads (csf_parloop.in); after each chunk the worker copies
 * its cells back into m, which no other thread reads or writes then. A
 * generated program's body keeps its scratch values in C locals, so its
 * workers share m, y and dydt, each writing only its own cells.
 */
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "insn.h"
#include "par.h"
#include "parloop.h"

/* Reads of a flag before a thread sleeps on a condition variable (some microseconds); chunks of a job per thread. */
enum { PAR_SPIN = 1 << 10, PAR_CHUNKS = 16 };

typedef struct worker {
	csf_pool *pool;
	double *mem;   /* its memory for the VM (NULL until the first VM job) */
	pthread_t th;
} worker;

struct csf_pool {
	const csf_prog *p;
	int n;                            /* threads, the caller's included */
	uint64_t min_work;
	unsigned long jobs_left;          /* jobs the pool may still run (CSF_THREADS_MAX_JOBS; ULONG_MAX: no limit) */
	csf_parloop *loops[CSF_NSEC];     /* the independent loops of each section, by pc */
	uint32_t nloops[CSF_NSEC];
	worker *w;                        /* n - 1 of them */
	pthread_mutex_t mu;
	pthread_cond_t go, done;
	atomic_ulong gen;                 /* jobs posted (written under mu) */
	atomic_int busy;                  /* workers not done with the current job */
	int quit;                         /* (under mu) */
	/* the job */
	const csf_exec_ctx *x;
	uint32_t count, chunks;           /* iterations, and the chunks they are cut into */
	atomic_uint next;                 /* the next chunk to take (the last is the caller's) */
	double *m;
	int sec;                          /* the VM's: its section and loop */
	const csf_parloop *L;
	csf_par_fn *fn;                   /* a generated program's: its function (NULL: the VM's job) */
	const double *y;
	double *dydt;
};

/* Chunk c of the job, on mem (m for the caller). */
static void run_chunk(csf_pool *pool, uint32_t c, double *mem)
{
	uint32_t lo = (uint32_t)((uint64_t)pool->count * c / pool->chunks);
	uint32_t hi = (uint32_t)((uint64_t)pool->count * (c + 1) / pool->chunks);
	if (pool->fn) {
		pool->fn(pool->p, pool->x, pool->m, pool->y, pool->dydt, lo, hi);
		return;
	}
	const csf_parloop *L = pool->L;
	csf_vm_loop_range(pool->p, pool->x, pool->sec, L->pc, L->end, mem, lo, hi);
	if (mem == pool->m || lo == hi) return;
	for (uint32_t i = 0; i < L->nout; i++) {
		const csf_cell *cl = &L->out[i];
		size_t first = cl->base + (size_t)cl->stride * lo, past = cl->base + (size_t)cl->stride * (hi - 1) + cl->width;
		memcpy(pool->m + first, mem + first, (past - first) * sizeof *mem);
	}
}

/* Takes chunks of the job until none but the last is left. */
static void run_chunks(csf_pool *pool, double *mem)
{
	for (;;) {
		uint32_t c = atomic_fetch_add_explicit(&pool->next, 1, memory_order_relaxed);
		if (c >= pool->chunks - 1) return;
		run_chunk(pool, c, mem);
	}
}

/* Waits for the job after job seen: a short spin (jobs come in quick succession), then on the condition variable. */
static unsigned long next_job(csf_pool *pool, unsigned long seen)
{
	unsigned long g = seen;
	for (int k = 0; k < PAR_SPIN && g == seen; k++) g = atomic_load_explicit(&pool->gen, memory_order_acquire);
	if (g != seen) return g;
	pthread_mutex_lock(&pool->mu);
	while ((g = atomic_load_explicit(&pool->gen, memory_order_acquire)) == seen && !pool->quit)
		pthread_cond_wait(&pool->go, &pool->mu);
	if (pool->quit) g = seen;
	pthread_mutex_unlock(&pool->mu);
	return g;
}

static void *work(void *arg)
{
	worker *w = arg;
	csf_pool *pool = w->pool;
	unsigned long seen = 0;
	for (;;) {
		unsigned long g = next_job(pool, seen);
		if (g == seen) return NULL; /* quit */
		seen = g;
		run_chunks(pool, w->mem);
		if (atomic_fetch_sub_explicit(&pool->busy, 1, memory_order_acq_rel) == 1) {
			pthread_mutex_lock(&pool->mu);
			pthread_cond_signal(&pool->done);
			pthread_mutex_unlock(&pool->mu);
		}
	}
}

/* Posts the job set up in pool, takes chunks and runs the last, waits for the others (a short spin, then on done). */
static void run_job(csf_pool *pool)
{
	uint64_t k = (uint64_t)PAR_CHUNKS * (uint64_t)pool->n;
	pool->chunks = pool->count < k ? pool->count : (uint32_t)k;
	atomic_store_explicit(&pool->next, 0, memory_order_relaxed);
	atomic_store_explicit(&pool->busy, pool->n - 1, memory_order_relaxed);
	pthread_mutex_lock(&pool->mu);
	atomic_fetch_add_explicit(&pool->gen, 1, memory_order_release);
	pthread_cond_broadcast(&pool->go);
	pthread_mutex_unlock(&pool->mu);
	run_chunks(pool, pool->m);
	run_chunk(pool, pool->chunks - 1, pool->m);
	for (int k = 0; k < PAR_SPIN && atomic_load_explicit(&pool->busy, memory_order_acquire); k++) continue;
	if (!atomic_load_explicit(&pool->busy, memory_order_acquire)) return;
	pthread_mutex_lock(&pool->mu);
	while (atomic_load_explicit(&pool->busy, memory_order_acquire)) pthread_cond_wait(&pool->done, &pool->mu);
	pthread_mutex_unlock(&pool->mu);
}

/* The independent loops of section sec, ascending by pc. */
static void analyse(csf_pool *pool, int sec)
{
	const csf_prog *p = pool->p;
	const uint32_t *code = p->code[sec];
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		csf_parloop L;
		if (code[pc] != CSF_OP_LOOP || !csf_parloop_analyse(p, sec, pc, &L)) continue;
		csf_parloop *a = realloc(pool->loops[sec], (pool->nloops[sec] + 1) * sizeof *a);
		if (!a) {
			csf_parloop_free(&L);
			return;
		}
		pool->loops[sec] = a;
		a[pool->nloops[sec]++] = L;
	}
}

/* Environment variable name's whole number, else dflt. */
static unsigned long long env_count(const char *name, unsigned long long dflt)
{
	const char *e = getenv(name);
	char *end;
	if (!e || *e < '0' || *e > '9') return dflt;
	errno = 0;
	unsigned long long v = strtoull(e, &end, 10);
	return *end || errno ? dflt : v;
}

csf_pool *csf_pool_new(const csf_prog *p, int n)
{
	if (n < 2) return NULL;
	csf_pool *pool = calloc(1, sizeof *pool);
	if (!pool || !(pool->w = calloc((size_t)n - 1, sizeof *pool->w))) {
		free(pool);
		return NULL;
	}
	pool->p = p;
	pool->min_work = env_count("CSF_THREADS_MIN_WORK", CSF_PAR_MIN_WORK);
	unsigned long long jobs = env_count("CSF_THREADS_MAX_JOBS", ULONG_MAX);
	pool->jobs_left = jobs < ULONG_MAX ? (unsigned long)jobs : ULONG_MAX;
	for (int sec = 0; sec < CSF_NSEC; sec++) analyse(pool, sec);
	pthread_mutex_init(&pool->mu, NULL);
	pthread_cond_init(&pool->go, NULL);
	pthread_cond_init(&pool->done, NULL);
	pool->n = 1;
	for (int t = 0; t < n - 1; t++) {
		worker *w = &pool->w[t];
		w->pool = pool;
		if (pthread_create(&w->th, NULL, work, w)) break;
		pool->n++;
	}
	if (pool->n < 2) {
		csf_pool_free(pool);
		return NULL;
	}
	return pool;
}

void csf_pool_free(csf_pool *pool)
{
	if (!pool) return;
	pthread_mutex_lock(&pool->mu);
	pool->quit = 1;
	pthread_cond_broadcast(&pool->go);
	pthread_mutex_unlock(&pool->mu);
	for (int t = 0; t < pool->n - 1; t++) {
		pthread_join(pool->w[t].th, NULL);
		free(pool->w[t].mem);
	}
	pthread_cond_destroy(&pool->done);
	pthread_cond_destroy(&pool->go);
	pthread_mutex_destroy(&pool->mu);
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		for (uint32_t i = 0; i < pool->nloops[sec]; i++) csf_parloop_free(&pool->loops[sec][i]);
		free(pool->loops[sec]);
	}
	free(pool->w);
	free(pool);
}

/* Does a loop of count iterations and this much work go to the threads? */
static int worth(csf_pool *pool, uint64_t work, uint32_t count)
{
	if (count < 2 || work < pool->min_work || !pool->jobs_left) return 0; /* (a thread may have no iteration) */
	if (pool->jobs_left != ULONG_MAX) pool->jobs_left--;
	return 1;
}

int csf_pool_vm(csf_pool *pool, const csf_exec_ctx *x, int sec, uint32_t pc, double *m)
{
	const csf_parloop *a = pool->loops[sec];
	uint32_t i = csf_find_pc(a, pool->nloops[sec], sizeof *a, pc);
	if (i == pool->nloops[sec] || !worth(pool, a[i].work, a[i].count)) return 0;
	const csf_parloop *L = &a[i];
	for (int t = 0; t < pool->n - 1; t++) {
		worker *w = &pool->w[t];
		if (!w->mem && !(w->mem = malloc((pool->p->nmem ? pool->p->nmem : 1) * sizeof *w->mem))) return 0;
		for (uint32_t i = 0; i < L->nin; i++)
			memcpy(w->mem + L->in[i].lo, m + L->in[i].lo, (L->in[i].hi - L->in[i].lo) * sizeof *m);
	}
	pool->x = x;
	pool->count = L->count;
	pool->m = m;
	pool->sec = sec;
	pool->L = L;
	pool->fn = NULL;
	run_job(pool);
	return 1;
}

void csf_par_for(const csf_prog *p, const csf_exec_ctx *x, uint64_t work, uint32_t count, csf_par_fn *fn, double *m,
                 const double *y, double *dydt)
{
	csf_pool *pool = x ? x->pool : NULL;
	if (!pool || !worth(pool, work, count)) {
		fn(p, x, m, y, dydt, 0, count);
		return;
	}
	pool->x = x;
	pool->count = count;
	pool->m = m;
	pool->fn = fn;
	pool->y = y;
	pool->dydt = dydt;
	run_job(pool);
}
