/*
 * api.c - libcsf's ABI (csf_api.h): models and runs behind opaque handles,
 * over the runtime's own csf_decode, csf_param_set, csf_parse_opts and
 * csf_run_sink, so that a run from another language is csfvm's run: the
 * same checks, messages, rows and statuses. The rows go to a sink that
 * copies them into the caller's array; the diagnostics to a memory stream.
 * A large array is made present by a helper thread on another CPU while
 * the run computes (prefault_pages), so that the run does not stop to have
 * fresh pages mapped and zeroed.
 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include "csf_int.h"
#include "bytecode.h"
#include "csf_api.h"

/* A parameter of the model: its name (a global's, or OBJECT.PROP), slot, width and class. */
typedef struct aparam {
	const char *name;
	uint32_t slot, width;
	const csf_pclass *cls;
} aparam;

struct csf_api_model {
	csf_prog p;
	size_t ncols;
	const char **name, **unit; /* per column, into text */
	int *comp;                 /* per column: its component in a vector, or -1 */
	size_t npar;
	aparam *par;
	char *text; /* the columns' names and units, the properties' OBJECT.PROP */
};

struct csf_api_run {
	const csf_api_model *m;
	csf_opts o;         /* the options (csf_api_run_options), their strings in args */
	char *args;
	csf_overlay init;   /* the parameters set */
	char error[1024];   /* the last failure's message */
	char *diag;         /* the last run's diagnostics */
	size_t diaglen, nrows;
	unsigned long steps, rhs;
	double seconds;
	csf_api_progress_fn progress;
	void *progress_ctx;
	double interval;
};

int csf_api_version(void) { return CSF_API_VERSION; }

const char *csf_api_runtime_version(void) { return CSF_VERSION_STRING; }

/* The CRC tables are filled on first use: once, before two threads can load at the same time. */
static pthread_once_t crc_once = PTHREAD_ONCE_INIT;
static void crc_init(void) { (void)csf_crc32((const unsigned char *)"", 0); }

/* The columns' names and units (the header's `NAME [UNIT]` split), and their vectors. */
static int model_columns(csf_api_model *m, size_t textlen)
{
	const csf_prog *p = &m->p;
	char *t = m->text + textlen;
	for (size_t i = 0; i < m->ncols; i++) {
		const char *h = csf_str(p, p->cols[i].name);
		size_t n = strlen(h);
		memcpy(t, h, n + 1);
		m->name[i] = t;
		m->unit[i] = t + n; /* "" */
		char *br = strstr(t, " [");
		if (br && n && t[n - 1] == ']') {
			*br = '\0';
			t[n - 1] = '\0';
			m->unit[i] = br + 2;
		}
		t += n + 1;
	}
	/* x, y and z of one vector: NAME.x, NAME.y, NAME.z in a row, in one unit */
	for (size_t i = 0; i < m->ncols; i++) m->comp[i] = -1;
	for (size_t i = 0; i + 2 < m->ncols; i++) {
		size_t n = strlen(m->name[i]);
		if (n < 3 || strcmp(m->name[i] + n - 2, ".x") != 0) continue;
		int vec = 1;
		for (size_t k = 1; k < 3; k++)
			vec &= strlen(m->name[i + k]) == n && strncmp(m->name[i + k], m->name[i], n - 1) == 0 &&
			       m->name[i + k][n - 1] == (char)('x' + k) && strcmp(m->unit[i + k], m->unit[i]) == 0;
		if (!vec) continue;
		for (int k = 0; k < 3; k++) m->comp[i + (size_t)k] = k;
		i += 2;
	}
	return 0;
}

csf_api_model *csf_api_load(const void *bytes, size_t len, char *err, size_t errlen)
{
	pthread_once(&crc_once, crc_init);
	csf_api_model *m = calloc(1, sizeof *m);
	if (!m) {
		csf_fail(err, errlen, "out of memory");
		return NULL;
	}
	if (csf_decode(bytes, len, &m->p, err, errlen)) {
		free(m);
		return NULL;
	}
	const csf_prog *p = &m->p;
	m->ncols = p->ncols;
	m->npar = (size_t)p->nglobals + p->nprops;
	size_t textlen = 0, collen = 0;
	for (uint32_t i = 0; i < p->nprops; i++)
		textlen += strlen(csf_str(p, p->objects[p->props[i].object])) + strlen(csf_str(p, p->props[i].name)) + 2;
	for (uint32_t i = 0; i < p->ncols; i++) collen += strlen(csf_str(p, p->cols[i].name)) + 1;
	m->text = malloc(textlen + collen + 1);
	m->name = malloc((m->ncols + 1) * sizeof *m->name);
	m->unit = malloc((m->ncols + 1) * sizeof *m->unit);
	m->comp = malloc((m->ncols + 1) * sizeof *m->comp);
	m->par = malloc((m->npar + 1) * sizeof *m->par);
	if (!m->text || !m->name || !m->unit || !m->comp || !m->par) {
		csf_api_free(m);
		csf_fail(err, errlen, "out of memory");
		return NULL;
	}
	size_t k = 0;
	for (uint32_t i = 0; i < p->nglobals; i++, k++)
		m->par[k] = (aparam){ csf_str(p, p->globals[i].name), p->globals[i].slot, p->globals[i].width,
		                      &p->pclasses[p->globals[i].cls] };
	char *t = m->text;
	for (uint32_t i = 0; i < p->nprops; i++, k++) {
		const csf_prop *q = &p->props[i];
		int n = sprintf(t, "%s.%s", csf_str(p, p->objects[q->object]), csf_str(p, q->name));
		m->par[k] = (aparam){ t, q->slot, q->width, &p->pclasses[q->cls] };
		t += n + 1;
	}
	model_columns(m, textlen);
	return m;
}

void csf_api_free(csf_api_model *m)
{
	if (!m) return;
	csf_prog_free(&m->p);
	free(m->text);
	free(m->name);
	free(m->unit);
	free(m->comp);
	free(m->par);
	free(m);
}

double csf_api_till(const csf_api_model *m) { return m->p.till; }
double csf_api_by(const csf_api_model *m) { return m->p.by; }

size_t csf_api_ncols(const csf_api_model *m) { return m->ncols; }
const char *csf_api_col_name(const csf_api_model *m, size_t i) { return i < m->ncols ? m->name[i] : NULL; }
const char *csf_api_col_unit(const csf_api_model *m, size_t i) { return i < m->ncols ? m->unit[i] : NULL; }
int csf_api_col_component(const csf_api_model *m, size_t i) { return i < m->ncols ? m->comp[i] : -1; }

size_t csf_api_nparams(const csf_api_model *m) { return m->npar; }
const char *csf_api_param_name(const csf_api_model *m, size_t i) { return i < m->npar ? m->par[i].name : NULL; }

const char *csf_api_param_unit(const csf_api_model *m, size_t i)
{
	return i < m->npar ? csf_str(&m->p, m->par[i].cls->unit) : NULL;
}

const char *csf_api_param_why(const csf_api_model *m, size_t i)
{
	return i < m->npar ? csf_str(&m->p, m->par[i].cls->why) : NULL;
}

int csf_api_param_known(const csf_api_model *m, size_t i) { return i < m->npar ? m->par[i].cls->known != 0 : 0; }

int csf_api_param_value(const csf_api_model *m, size_t i, double v[3])
{
	if (i >= m->npar) return 0;
	for (uint32_t k = 0; k < m->par[i].width; k++) v[k] = m->p.mem0[m->par[i].slot + k];
	return (int)m->par[i].width;
}

int csf_api_param_parse(const csf_api_model *m, const char *assign, double v[3], char *err, size_t errlen)
{
	csf_overlay ov = { 0 };
	int n = -1;
	if (!csf_param_set(&m->p, &ov, assign, err, errlen)) {
		n = (int)ov.n;
		for (size_t k = 0; k < ov.n; k++) v[k] = ov.v[k].value;
	}
	csf_overlay_free(&ov);
	return n;
}

/* ---- runs ---- */

csf_api_run *csf_api_run_new(const csf_api_model *m)
{
	csf_api_run *r = calloc(1, sizeof *r);
	if (r) r->m = m;
	return r;
}

void csf_api_run_free(csf_api_run *r)
{
	if (!r) return;
	csf_opts_free(&r->o);
	csf_overlay_free(&r->init);
	free(r->args);
	free(r->diag);
	free(r);
}

const char *csf_api_run_error(const csf_api_run *r) { return r->error; }

/* A message into r->error, without csfvm's "csfvm: " and the line's end. Returns -1. */
static int run_fail(csf_api_run *r, const char *msg)
{
	if (strncmp(msg, "csfvm: ", 7) == 0) msg += 7;
	size_t n = strcspn(msg, "\n");
	snprintf(r->error, sizeof r->error, "%.*s", (int)n, msg);
	return -1;
}

int csf_api_run_set(csf_api_run *r, const char *assign)
{
	char err[1024];
	if (csf_param_set(&r->m->p, &r->init, assign, err, sizeof err)) return run_fail(r, err);
	r->error[0] = '\0';
	return 0;
}

/* The options of a run from the API: none of sweeps, --compare-methods, files. */
static const char *not_for_a_run(const csf_opts *o)
{
	if (o->nsweeps) return "--sweep";
	if (o->sweep_file) return "--sweep-file";
	if (o->summary) return "--sweep-summary";
	if (o->out_dir) return "--out-dir";
	if (o->sweep_binary) return "--sweep-binary";
	if (o->output) return "-o"; /* (the rows are the caller's arrays) */
	if (o->dump) return "--dump";
	if (o->jobs) return "-j";
	if (o->compare) return "--compare-methods";
	if (o->progress == CSF_PROGRESS_ON) return "--progress";
	return NULL;
}

int csf_api_run_options(csf_api_run *r, int argc, const char *const *argv)
{
	csf_opts_free(&r->o);
	free(r->args);
	memset(&r->o, 0, sizeof r->o);
	r->args = NULL;
	if (argc < 0) argc = 0;
	/* the strings copied (the options keep pointers into them), after csfvm's name */
	size_t len = 6;
	for (int i = 0; i < argc; i++) len += strlen(argv[i]) + 1;
	char **av = malloc(((size_t)argc + 2) * sizeof *av);
	r->args = malloc(len);
	if (!av || !r->args) {
		free(av);
		return run_fail(r, "out of memory");
	}
	char *s = r->args;
	memcpy(s, "csfvm", 6);
	av[0] = s;
	s += 6;
	for (int i = 0; i < argc; i++) {
		size_t n = strlen(argv[i]) + 1;
		memcpy(s, argv[i], n);
		av[i + 1] = s;
		s += n;
	}
	av[argc + 1] = NULL;
	char *msg = NULL;
	size_t msglen = 0;
	FILE *err = open_memstream(&msg, &msglen);
	int pos[1], npos = 0, st = 2;
	if (err) {
		st = csf_parse_opts_to(argc + 1, av, 1, &r->o, pos, 1, &npos, "", err, err);
		fclose(err);
	}
	const char *bad = st ? NULL : not_for_a_run(&r->o);
	int ret = 0;
	if (!err || !msg) ret = run_fail(r, "out of memory");
	else if (st == 1) ret = run_fail(r, "--help and --version are not options of a run");
	else if (st) ret = run_fail(r, msg);
	else if (npos) {
		snprintf(r->error, sizeof r->error, "'%s': a run takes options, not a file name", av[pos[0]]);
		ret = -1;
	} else if (bad) {
		snprintf(r->error, sizeof r->error, "%s is not an option of one run (sweeps: csfvm --sweep)", bad);
		ret = -1;
	}
	for (int i = 0; !ret && i < r->o.ndefs; i++) ret = csf_api_run_set(r, r->o.defs[i]);
	free(msg);
	free(av);
	if (ret) {
		csf_opts_free(&r->o);
		memset(&r->o, 0, sizeof r->o);
	} else {
		r->error[0] = '\0';
	}
	return ret;
}

size_t csf_api_run_rows(const csf_api_run *r)
{
	double kmax = csf_run_kmax(&r->m->p);
	double every = r->o.every > 1 ? (double)r->o.every : 1;
	/* every K-th row, k = 0, K, 2K, ..., and the last (or a 'stop when' row) */
	return (size_t)(floor(kmax / every) + 1 + (fmod(kmax, every) != 0));
}

void csf_api_run_progress(csf_api_run *r, csf_api_progress_fn fn, void *ctx, double interval)
{
	r->progress = fn;
	r->progress_ctx = ctx;
	r->interval = interval > 0 ? interval : 0;
}

void csf_api_interrupt(void) { csf_signal = SIGINT; }

/*
 * The caller's array, made present ahead of the rows. Memory fresh from the kernel (numpy's
 * arrays, malloc's large blocks) is mapped on first touch: a page fault and the page zeroed, some
 * 25 ms for 240 MB (more where a virtual machine's host has to back the page too), which the run
 * would spend on its own thread, row after row. A helper thread faults the pages in beforehand on
 * another CPU with madvise(MADV_POPULATE_WRITE) (Linux 5.14): the pages made present and writable,
 * their contents left as they are, so the run may write beside it. It starts at the first row,
 * after the run's own allocations (brk and mmap wait while madvise holds the address space), and
 * asks for PREFAULT_CHUNK bytes (a huge page) a call, so that an allocation of the run's never
 * waits long. It stops when the run ends (done), and at madvise's first refusal (EINVAL before
 * Linux 5.14): the run faults the rest in itself, as without it. Only for PREFAULT_MIN bytes or
 * more, and where there are two CPUs or more.
 */
enum { PREFAULT_MIN = 4 << 20, PREFAULT_CHUNK = 2 << 20 };

typedef struct prefault {
	char *from, *to; /* the pages that hold the array (from == to: none to fault in) */
	atomic_int done; /* the run has ended: stop */
	int started;
	pthread_t thread;
} prefault;

static void *prefault_pages(void *ctx)
{
	prefault *pf = ctx;
#ifdef MADV_POPULATE_WRITE
	for (char *a = pf->from; a < pf->to && !atomic_load_explicit(&pf->done, memory_order_relaxed);) {
		char *b = (char *)(((uintptr_t)a + PREFAULT_CHUNK) & ~(uintptr_t)(PREFAULT_CHUNK - 1));
		if (b > pf->to) b = pf->to;
		if (madvise(a, (size_t)(b - a), MADV_POPULATE_WRITE)) break;
		a = b;
	}
#endif
	return NULL;
}

/* The pages of n rows of width doubles at out for the helper, where it is worth it; none else. */
static void prefault_plan(prefault *pf, double *out, size_t n, size_t width)
{
	long page = sysconf(_SC_PAGESIZE);
	pf->from = pf->to = NULL;
	pf->started = 0;
	atomic_init(&pf->done, 0);
#ifdef MADV_POPULATE_WRITE
	if (!out || n > SIZE_MAX / sizeof *out / width) return;
	size_t bytes = n * width * sizeof *out;
	if (bytes < PREFAULT_MIN || page <= 0 || sysconf(_SC_NPROCESSORS_ONLN) < 2) return;
	uintptr_t mask = (uintptr_t)page - 1;
	pf->from = (char *)((uintptr_t)out & ~mask);
	pf->to = (char *)(((uintptr_t)out + bytes + mask) & ~mask);
#else
	(void)out, (void)n, (void)width, (void)page;
#endif
}

/* Starts the helper on the planned pages (once). */
static void prefault_start(prefault *pf)
{
	if (pf->from == pf->to || pf->started) return;
	/* no signal for it: SIGINT stays the run's thread's (CSF_API_CATCH_SIGINT) */
	sigset_t all, old;
	sigfillset(&all);
	if (pthread_sigmask(SIG_SETMASK, &all, &old)) return;
	pf->started = pthread_create(&pf->thread, NULL, prefault_pages, pf) == 0;
	pthread_sigmask(SIG_SETMASK, &old, NULL);
}

/* Stops the helper (after its current chunk) and waits for it. */
static void prefault_end(prefault *pf)
{
	if (!pf->started) return;
	atomic_store_explicit(&pf->done, 1, memory_order_relaxed);
	pthread_join(pf->thread, NULL);
	pf->started = 0;
}

/* The rows' sink: each written by the run straight into the caller's array (row_place; the helper
   started at the first), counted, and the progress callback. */
typedef struct rows {
	csf_api_run *r;
	double *out;
	size_t max, n, width;
	struct timespec last;
	prefault pf;
} rows;

static double *row_place(void *ctx)
{
	rows *w = ctx;
	if (w->n == 0) prefault_start(&w->pf);
	return w->n < w->max ? w->out + w->n * w->width : NULL;
}

static int row_in(void *ctx, const double *v, size_t n)
{
	rows *w = ctx;
	(void)n;
	w->n++;
	csf_api_run *r = w->r;
	if (r->progress) {
		struct timespec now;
		clock_gettime(CLOCK_MONOTONIC, &now);
		double dt = (double)(now.tv_sec - w->last.tv_sec) + 1e-9 * (double)(now.tv_nsec - w->last.tv_nsec);
		if (dt >= r->interval) {
			w->last = now;
			if (r->progress(r->progress_ctx, v[0], w->n)) csf_signal = SIGINT;
		}
	}
	return 0;
}

static void on_sigint(int sig) { csf_signal = sig; }

int csf_api_run_exec(csf_api_run *r, double *out, size_t maxrows, unsigned flags)
{
	const csf_api_model *m = r->m;
	free(r->diag);
	r->diag = NULL;
	r->diaglen = r->nrows = 0;
	r->steps = r->rhs = 0;
	r->seconds = 0;
	FILE *err = open_memstream(&r->diag, &r->diaglen);
	if (!err) return 2;
	rows w = { .r = r, .out = out, .max = maxrows, .width = m->ncols + 1 };
	clock_gettime(CLOCK_MONOTONIC, &w.last);
	/* the rows the run can write, of those the caller has room for */
	size_t most = csf_api_run_rows(r);
	prefault_plan(&w.pf, out, maxrows < most ? maxrows : most, w.width);
	csf_sink sink = { row_in, &w, out ? row_place : NULL };
	csf_opts o = r->o;
	o.init = &r->init;
	o.progress = CSF_PROGRESS_OFF;
	struct sigaction sa, old;
	int caught = (flags & CSF_API_CATCH_SIGINT) != 0;
	csf_signal = 0;
	if (caught) {
		memset(&sa, 0, sizeof sa);
		sigemptyset(&sa.sa_mask);
		sa.sa_flags = SA_RESTART;
		sa.sa_handler = on_sigint;
		if (sigaction(SIGINT, &sa, &old)) caught = 0;
	}
	int st = csf_run_sink(&m->p, csf_vm_exec, &o, NULL, &sink, err);
	prefault_end(&w.pf);
	if (caught) sigaction(SIGINT, &old, NULL);
	csf_signal = 0;
	if (fclose(err) && st == 0) st = 2;
	r->nrows = w.n;
	r->steps = o.run_steps;
	r->rhs = o.run_rhs;
	r->seconds = o.run_seconds;
	return st;
}

size_t csf_api_run_nrows(const csf_api_run *r) { return r->nrows; }
const char *csf_api_run_diagnostics(const csf_api_run *r) { return r->diag ? r->diag : ""; }
unsigned long csf_api_run_steps(const csf_api_run *r) { return r->steps; }
unsigned long csf_api_run_rhs(const csf_api_run *r) { return r->rhs; }
double csf_api_run_seconds(const csf_api_run *r) { return r->seconds; }
