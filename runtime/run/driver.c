/*
 * driver.c - the simulation loop, output and run-time diagnostics.
 *
 * csf_run is shared by csfvm and by every generated executable: it owns the
 * model's memory, integrates the state between output times t_k = k*by with
 * ode.c, runs the OUT section at each t_k, checks assertions and finiteness,
 * and writes one CSV row per t_k as it goes. Rows are written through stdio
 * and flushed on every exit path; a write error is reported, never ignored.
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "csf.h"
#include "ode.h"
#include "spectrum.h"

void csf_fmt_double(char buf[32], double x)
{
	if (isnan(x)) {
		strcpy(buf, "nan");
		return;
	}
	if (isinf(x)) {
		strcpy(buf, x > 0 ? "inf" : "-inf");
		return;
	}
	for (int prec = 15; prec <= 17; prec++) {
		snprintf(buf, 32, "%.*g", prec, x);
		if (strtod(buf, NULL) == x) return;
	}
}

/* The value v of option name into *x: a positive finite number, or a usage error (-1). */
static int positive(const char *prog, const char *v, const char *name, const char *what, double *x)
{
	char *end;
	errno = 0;
	*x = strtod(v, &end);
	if (end == v || *end || errno || !(*x > 0) || !isfinite(*x)) {
		fprintf(stderr, "%s: %s needs a positive number%s, not '%s'\n", prog, name, what, v);
		return -1;
	}
	return 0;
}

/* Appends s to the array *v of *n strings (room for max); -1 when memory runs out. */
static int push_arg(const char ***v, int *n, const char *s, int max)
{
	if (!*v && !(*v = malloc((size_t)max * sizeof **v))) return -1;
	(*v)[(*n)++] = s;
	return 0;
}

void csf_opts_free(csf_opts *o)
{
	free(o->defs);
	free(o->sweeps);
	o->defs = o->sweeps = NULL;
}

int csf_opt_value(int argc, char **argv, int *i, const char *name, const char **val)
{
	const char *a = argv[*i];
	size_t n = strlen(name);
	if (strncmp(a, name, n) != 0) return 0;
	if (a[n] == '=') {
		*val = a + n + 1;
		return 1;
	}
	if (a[n] == '\0' && *i + 1 < argc) {
		*val = argv[++*i];
		return 1;
	}
	return 0;
}

int csf_parse_opts(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                   const char *usage)
{
	memset(o, 0, sizeof *o);
	*npos_out = 0;
	for (int i = first; i < argc; i++) {
		const char *a = argv[i], *v;
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			fputs(usage, stdout);
			return 1;
		} else if (strcmp(a, "--version") == 0) {
			const char *slash = strrchr(argv[0], '/');
			printf("%s %s\n", slash ? slash + 1 : argv[0], CSF_VERSION_STRING);
			return 1;
		} else if (csf_opt_value(argc, argv, &i, "--method", &v)) {
			o->method = v;
			int known = strcmp(v, "auto") == 0;
			for (size_t k = 0; csf_method_name(k); k++) known |= strcmp(csf_method_name(k), o->method) == 0;
			if (!known) {
				fprintf(stderr, "%s: unknown method '%s' (one of: auto", argv[0], o->method);
				for (size_t k = 0; csf_method_name(k); k++) fprintf(stderr, " %s", csf_method_name(k));
				fprintf(stderr, ")\n");
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--tol", &v)) {
			if (positive(argv[0], v, "--tol", "", &o->tol)) return 2;
			if (o->tol < CSF_MIN_TOL || o->tol >= 1) {
				fprintf(stderr,
				        o->tol >= 1 ? "%s: --tol %s: a relative error of 1 or more allows any answer; the tolerance "
				                      "must be below 1\n"
				                    : "%s: --tol %s is below 1e-15, what doubles can deliver: a step's result is "
				                      "rounded by 1.1e-16 of its size, and below 1e-15 the methods' error "
				                      "estimates measure that rounding, not their error (they take ever more "
				                      "steps for no gain, or fail)\n",
				        argv[0], v);
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--atol", &v)) {
			if (positive(argv[0], v, "--atol", " (in the model's units)", &o->atol)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--step", &v)) {
			if (positive(argv[0], v, "--step", " of seconds", &o->step)) return 2;
			o->fixed = 1;
		} else if (csf_opt_value(argc, argv, &i, "--hmax", &v)) {
			if (positive(argv[0], v, "--hmax", " of seconds", &o->hmax)) return 2;
		} else if (strcmp(a, "--fixed") == 0) {
			o->fixed = 1;
		} else if (strcmp(a, "--stats") == 0) {
			o->stats = 1;
		} else if (strcmp(a, "--progress") == 0) {
			o->progress = CSF_PROGRESS_ON;
		} else if (strcmp(a, "--no-progress") == 0) {
			o->progress = CSF_PROGRESS_OFF;
		} else if (strcmp(a, "--compare-methods") == 0) {
			o->compare = 1;
		} else if (strncmp(a, "-D", 2) == 0 && (a[2] || i + 1 < argc)) {
			if (push_arg(&o->defs, &o->ndefs, a[2] ? a + 2 : argv[++i], argc)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--sweep", &v)) {
			if (push_arg(&o->sweeps, &o->nsweeps, v, argc)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--sweep-file", &v)) {
			o->sweep_file = v;
		} else if (csf_opt_value(argc, argv, &i, "--sweep-summary", &v)) {
			o->summary = v;
		} else if (csf_opt_value(argc, argv, &i, "--out-dir", &v)) {
			o->out_dir = v;
		} else if ((strncmp(a, "-j", 2) == 0 && (a[2] || i + 1 < argc)) || csf_opt_value(argc, argv, &i, "--jobs", &v)) {
			if (strncmp(a, "-j", 2) == 0) v = a[2] ? a + 2 : argv[++i];
			char *end;
			errno = 0;
			o->jobs = strtol(v, &end, 10);
			if (end == v || *end || errno || o->jobs < 1 || o->jobs > 4096) {
				fprintf(stderr, "%s: -j needs a number of processes from 1 to 4096, not '%s'\n", argv[0], v);
				return 2;
			}
		} else if (a[0] == '-' && a[1] != '\0') {
			fprintf(stderr, "%s: unknown or incomplete option '%s'\n%s", argv[0], a, usage);
			return 2;
		} else {
			if (*npos_out >= npos) {
				fprintf(stderr, "%s: too many arguments\n%s", argv[0], usage);
				return 2;
			}
			pos[(*npos_out)++] = i;
		}
	}
	return 0;
}

typedef struct run {
	const csf_prog *p;
	csf_exec_fn exec;
	double *m;
	double fail_t; /* time of a non-finite derivative */
	int fail;
	unsigned long nrhs, njac; /* evaluations, for --stats */
	unsigned long nevents;
	long last; /* the guard of the last event */
	uint32_t last_src; /* its rule's statement */
	int pending; /* it was located at an output time and happens after that row */
	double last_h; /* the last step's length */
	double zeno, tol; /* for csf_contact_settle */
	int dense;        /* the method's continuous extension gives the rows (advance_dense) */
	double ti, tend;  /* dense: the integrator's time (at or past the last row), the last output time */
	double *yi;       /* dense: the integrator's state at ti */
	/* events: guards (conditional rules' comparisons, then two per candidate contact), ng of them
	   (room for capg), and work vectors */
	uint32_t ng;
	size_t capg;
	double *ga, *gb, *gs, *gh, *gt, *gl, *ya, *fa, *fb, *ys, *fs, *ye;
	double *jw; /* with contacts: 3 work vectors for the Jacobian by differences */
	double *yh; /* with contacts: the 3 interpolated states of a step, one after the other */
	csf_contacts *cs; /* with contacts: the candidate pairs (contact.c) */
	unsigned long nchoices, ncand, maxcand; /* for --stats: the choices of candidates, their sum and largest */
	int nomem; /* memory ran out */
	int unsettled;     /* why the contacts stopped the run: CSF_SETTLE_ENDLESS, _IMPULSES, _FORCES (csf.h) */
	double unsettled_t;
	double stop_t; /* a 'stop when' condition ended the run at stop_t: the statement stop_src's */
	uint32_t stop_src;
	int stopped;
	struct guard *g; /* the stability guard, or NULL */
	csf_ode *ode;     /* the method taking the steps (with --method auto, one of au->m) */
	int own;          /* the integrator has its own time and state (ti, yi), apart from the rows' */
	struct autom *au; /* --method auto, or NULL */
	FILE *err;
	int prog, shown;  /* the progress line: drawn, and on the screen now */
	struct timespec start, drawn; /* when the run started, and the line was last drawn */
	unsigned long rows; /* rows written */
} run;

volatile sig_atomic_t csf_signal;

/*
 * Interruption. SIGINT and SIGTERM set csf_signal; every loop of a run that
 * can last looks at it, and the run ends after its last whole row with the
 * --stats line. A computation that does not look (a defect, or a library's
 * long loop) must not make a run deaf: the first signal also arms a
 * watchdog, and if the process is still running CSF_WATCHDOG_MS later the
 * watchdog flushes the rows already written and ends the process with the
 * same status. It never cuts a row: while one is being written
 * (csf_out_begin .. csf_out_end), it waits for the row's end.
 */
enum { CSF_WATCHDOG_MS = 500 };
static volatile sig_atomic_t writing, overdue;
static FILE *guarded_out;
static char watchdog_msg[160];

/* Flushes the rows written (no row is half written) and ends the process: 128 + the signal. */
static void watchdog_exit(void)
{
	if (guarded_out) fflush(guarded_out);
	ssize_t w = write(STDERR_FILENO, watchdog_msg, strlen(watchdog_msg));
	(void)w;
	_exit(128 + csf_signal);
}

static void on_watchdog(int sig)
{
	(void)sig;
	if (writing) overdue = 1; /* csf_out_end ends the process after the row */
	else watchdog_exit();
}

static void on_signal(int sig)
{
	if (csf_signal) return;
	csf_signal = sig;
	struct itimerval it = {{0, 0}, {0, CSF_WATCHDOG_MS * 1000}};
	setitimer(ITIMER_REAL, &it, NULL);
}

void csf_signals_install(FILE *out, const char *prog)
{
	guarded_out = out;
	snprintf(watchdog_msg, sizeof watchdog_msg,
	         "%s: interrupted: the run did not reach the end of a row within %d ms; the rows before it are "
	         "written\n",
	         prog, (int)CSF_WATCHDOG_MS);
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sigemptyset(&sa.sa_mask);
	sa.sa_flags = SA_RESTART;
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	sa.sa_handler = on_watchdog;
	sigaction(SIGALRM, &sa, NULL);
}

void csf_out_begin(void) { writing = 1; }

void csf_out_end(void)
{
	writing = 0;
	if (overdue) watchdog_exit();
}

/* Seconds from a to b. */
static double seconds(struct timespec a, struct timespec b)
{
	return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

/*
 * The progress line (a terminal's stderr, or --progress): "t = T of TILL s
 * (P %), R rows/s, ETA E s", redrawn in place at most 10 times a second,
 * the first time after 0.1 s (a short run shows none).
 */
static void progress(run *r, double t)
{
	struct timespec now;
	clock_gettime(CLOCK_MONOTONIC, &now);
	if (seconds(r->drawn, now) < 0.1) return;
	r->drawn = now;
	double el = seconds(r->start, now);
	double frac = r->tend > 0 ? fmin(1, t / r->tend) : 1;
	char eta[48] = "";
	if (frac > 0 && frac < 1) snprintf(eta, sizeof eta, ", ETA %.0f s", el * (1 - frac) / frac);
	fprintf(r->err, "\r\033[Kt = %.4g of %g s (%.0f %%), %.0f rows/s%s", t, r->tend, 100 * frac,
	        (double)r->rows / el, eta);
	fflush(r->err);
	r->shown = 1;
}

/* Erases the progress line, before a message or at the end. */
static void progress_off(run *r)
{
	if (!r->shown) return;
	fputs("\r\033[K", r->err);
	fflush(r->err);
	r->shown = 0;
}

static int rhs(double t, const double *y, double *dydt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m;
	m[p->tslot] = t;
	r->exec(p, CSF_SEC_RHS, m, y, dydt);
	r->nrhs++;
	for (uint32_t i = 0; i < p->ny; i++)
		if (!isfinite(dydt[i])) {
			r->fail = 1;
			r->fail_t = t;
			/* every value the section computed, in m for report_nonfinite: the VM's, bit for bit the same */
			csf_vm_exec(p, CSF_SEC_RHS, m, y, m + p->dstart);
			return 1;
		}
	return 0;
}

/*
 * With contacts, the Jacobian by central differences of the RHS: the
 * contact routine's forces have no tangent code, and they are smooth while
 * the modes are frozen, as they are between events. Also for --method
 * auto's implicit method in a program without a JAC section. The step for component
 * j is cbrt(eps) times its size (at least its unit), which balances the
 * truncation and rounding errors of the difference.
 */
static int jac_differences(run *r, double t, const double *y, double *dfdy, double *dfdt)
{
	const csf_prog *p = r->p;
	uint32_t n = p->ny;
	double *yd = r->jw, *fp = yd + n, *fm = fp + n, c = cbrt(DBL_EPSILON);
	memcpy(yd, y, n * sizeof *y);
	for (uint32_t j = 0; j <= n; j++) {
		double x = j < n ? y[j] : t;
		double h = c * csf_max(fabs(x), j < n ? p->yscale[j] : p->by);
		double xp = x + h, xm = x - h; /* divided by the steps actually taken */
		if (j < n) yd[j] = xp;
		if (rhs(j < n ? t : xp, yd, fp, r)) return 1;
		if (j < n) yd[j] = xm;
		if (rhs(j < n ? t : xm, yd, fm, r)) return 1;
		if (j < n) yd[j] = y[j];
		for (uint32_t i = 0; i < n; i++) {
			double d = (fp[i] - fm[i]) / (xp - xm);
			if (j < n) dfdy[(size_t)i * n + j] = d;
			else dfdt[i] = d;
		}
	}
	return 0;
}

/*
 * The exact Jacobian: JAC run once per state component with that
 * component's tangent set to 1 (a column), then once with t's (dfdt).
 */
static int jac(double t, const double *y, double *dfdy, double *dfdt, void *ctx)
{
	run *r = ctx;
	const csf_prog *p = r->p;
	double *m = r->m, *tan = r->m + p->jtan;
	uint32_t n = p->ny;
	r->njac++;
	if (p->ncrules || !p->jtan) return jac_differences(r, t, y, dfdy, dfdt); /* (no JAC: --method auto) */
	m[p->tslot] = t;
	memcpy(m + p->ystart, y, n * sizeof *y);
	for (uint32_t j = 0; j <= n; j++) {
		memset(tan + p->ystart, 0, n * sizeof *tan);
		tan[p->tslot] = j == n ? 1.0 : 0.0;
		if (j < n) tan[p->ystart + j] = 1.0;
		r->exec(p, CSF_SEC_JAC, m, m + p->ystart, m + p->dstart);
		for (uint32_t i = 0; i < n; i++) {
			double d = tan[p->dstart + i];
			if (j < n) dfdy[(size_t)i * n + j] = d;
			else dfdt[i] = d;
		}
	}
	return 0;
}

/* Index of the first non-finite target computed by section sec, or -1. */
static long first_nonfinite(const csf_prog *p, int sec, const double *m)
{
	for (uint32_t i = 0; i < p->ntargets[sec]; i++) {
		const csf_target *tg = &p->targets[sec][i];
		for (uint32_t k = 0; k < tg->width; k++)
			if (!isfinite(m[tg->slot + k])) return (long)i;
	}
	return -1;
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err);

/* Reports a non-finite value; with fixed steps, adds that the step is the likely cause. */
static void report_nonfinite(const csf_prog *p, int sec, const double *m, double t, const char *what, int fixed,
                             FILE *err)
{
	report_nonfinite_value(p, sec, m, t, what, err);
	if (fixed)
		fprintf(err, "note: with --fixed, the step is probably too large for the method to be stable: "
		             "try a smaller --step, or leave out --fixed\n");
}

static void report_nonfinite_value(const csf_prog *p, int sec, const double *m, double t, const char *what, FILE *err)
{
	char tb[32], vb[32];
	csf_fmt_double(tb, t);
	long i = first_nonfinite(p, sec, m);
	if (i < 0) {
		/* no rule computed it: an initial value or a constant; name the column */
		for (uint32_t c = 0; c < p->ncols; c++)
			if (!isfinite(m[p->cols[c].slot])) {
				csf_fmt_double(vb, m[p->cols[c].slot]);
				fprintf(err, "error: non-finite value at t=%s: %s = %s, set by no rule (an initial value or a constant)\n",
				        tb, csf_str(p, p->cols[c].name), vb);
				return;
			}
		fprintf(err, "error: non-finite value at t=%s: %s\n", tb, what);
		return;
	}
	const csf_target *tg = &p->targets[sec][i];
	const csf_src *s = &p->srcs[tg->src];
	uint32_t k = 0;
	while (k + 1 < tg->width && isfinite(m[tg->slot + k])) k++;
	csf_fmt_double(vb, m[tg->slot + k]);
	fprintf(err, "%s:%lu: error: non-finite value at t=%s: %s%s%s (object %s) = %s, computed by: %s\n",
	        csf_str(p, p->files[s->file]), (unsigned long)s->line, tb, csf_str(p, tg->name),
	        tg->width == 3 ? "." : "", tg->width == 3 ? (const char *[]){ "x", "y", "z" }[k] : "",
	        csf_str(p, tg->object), vb, csf_str(p, s->text));
}

/* "file:line: " of statement src, the rule whose guard had the last event (a comparison, or a contact's). */
static void report_event_src(const csf_prog *p, uint32_t src, FILE *err)
{
	const csf_src *sr = &p->srcs[src];
	fprintf(err, "%s:%lu: ", csf_str(p, p->files[sr->file]), (unsigned long)sr->line);
}

/* The impacts at r->unsettled_t did not come to an end or could not be solved (csf_contact_settle): why, and what to do. */
static void report_unsettled(const run *r, FILE *err)
{
	char tb[32];
	csf_fmt_double(tb, r->unsettled_t);
	if (r->unsettled != CSF_SETTLE_ENDLESS) {
		/* the lightest and the heaviest mass point that can touch: blame the masses only if they differ */
		const csf_prog *p = r->p;
		uint32_t lo = 0, hi = 0; /* objects */
		double mlo = INFINITY, mhi = 0;
		for (uint32_t b = 0; b < p->ncbodies; b++) {
			if (p->cbodies[b].plane) continue;
			double mb = r->m[p->cbodies[b].s[CSF_CF_M]];
			if (mb < mlo) mlo = mb, lo = p->cbodies[b].object;
			if (mb > mhi) mhi = mb, hi = p->cbodies[b].object;
		}
		const char *what = r->unsettled == CSF_SETTLE_IMPULSES ? "impulses of an impact" : "contact forces";
		if (mhi > 1e9 * mlo) {
			fprintf(err,
			        "error: at t=%s, the %s among bodies in contact could not be solved: their masses differ by more "
			        "than about 1e10 ('%s' %g and '%s' %g, in the model's units); make them less different\n",
			        tb, what, csf_str(p, p->objects[lo]), mlo, csf_str(p, p->objects[hi]), mhi);
			return;
		}
		fprintf(err,
		        "error: at t=%s, the %s among bodies in contact could not be solved: the equations of the contacts "
		        "there are singular (more contacts than the bodies' motions can tell apart), though the masses "
		        "differ by a factor of %.3g at most\n",
		        tb, what, mhi / mlo);
		return;
	}
	fprintf(err,
	        "error: at t=%s, the impacts among touching bodies did not come to an end after %llu collisions "
	        "(%lu pairs near contact): a light body squeezed between heavy ones collides about "
	        "pi sqrt(M/m) times; make the masses less different\n",
	        tb, (unsigned long long)csf_contact_passes(csf_contacts_count(r->cs)),
	        (unsigned long)csf_contacts_count(r->cs));
}

static int write_row(const csf_prog *p, const double *m, double t, FILE *out)
{
	char b[32];
	csf_out_begin();
	csf_fmt_double(b, t);
	fputs(b, out);
	for (uint32_t i = 0; i < p->ncols; i++) {
		csf_fmt_double(b, m[p->cols[i].slot]);
		putc(',', out);
		fputs(b, out);
	}
	putc('\n', out);
	csf_out_end();
	return ferror(out) ? -1 : 0;
}

/*
 * Flushes out: its error (werr, from a row, or fflush's) is reported with
 * status 2, but for a reader that went away (EPIPE: `csfvm ... | head`),
 * which ends the run quietly as it ends cat, with the status of SIGPIPE.
 */
static int finish(FILE *out, FILE *err, int status, int werr)
{
	csf_out_begin();
	int bad = fflush(out) != 0 || ferror(out);
	csf_out_end();
	if (bad) {
		int e = werr ? werr : errno;
		if (e == EPIPE) return 128 + SIGPIPE;
		fprintf(err, "error: cannot write output: %s\n", strerror(e));
		return 2;
	}
	return status;
}


/* ---- events ---- */

/*
 * advance_events: modes switch back and forth at one instant (CHATTER);
 * both advances: more than MAX_WORK steps (and events) in one output
 * interval (TOO_MUCH), a run that cannot get on, halted instead of hanging.
 */
enum { CHATTER = 10, TOO_MUCH = 11, TERMINAL = 12, MAX_WORK = 1000000 };

/*
 * A guard is a continuous function of t and the state that is >= 0 while
 * the current mode holds: for a conditional rule's comparison, its value
 * on the side it was last found on; for a contact, see contact.c. After
 * each step the guards are checked at its end and at three points of the
 * step's cubic Hermite interpolant (so that a guard which dips below zero
 * and back within one step is seen). A guard that was >= 0 at the step's
 * start and is negative at one of them is an event: its crossing is
 * bracketed and narrowed by the Illinois method on states computed by one
 * step of the method from the step's start, to 1e-13 s. The earliest
 * crossing ends the step there; the modes are brought up to date (and
 * impacts applied), the integrator restarts, and integration goes on.
 */

/* The guards of the last RHS evaluation of r->m into g. */
static void read_guards(run *r, double *g)
{
	const csf_prog *p = r->p;
	const double *m = r->m;
	for (uint32_t i = 0; i < p->nevents; i++) {
		const csf_event *e = &p->events[i];
		g[i] = m[e->mode] > 0 ? m[e->value] : -m[e->value];
	}
	if (r->cs) csf_contacts_guards(r->cs, g + p->nevents);
}

/* Guards g at (t, y), and the derivative in r->fs. 0, or 1 if a derivative is not finite. */
static int guards_at(run *r, double t, const double *y, double *g)
{
	if (rhs(t, y, r->fs, r)) return 1;
	read_guards(r, g);
	return 0;
}

/* Sets each comparison's side from its value at the state in r->m (after an RHS evaluation). */
static void free_modes(run *r, double t, const double *y)
{
	const csf_prog *p = r->p;
	for (uint32_t i = 0; i < p->nevents; i++) r->m[p->events[i].mode] = -1;
	(void)rhs(t, y, r->fs, r);
	for (uint32_t i = 0; i < p->nevents; i++) {
		const csf_event *e = &p->events[i];
		double v = r->m[e->value];
		r->m[e->mode] = (e->kind & 1 ? v >= 0 : v > 0) ? 1 : 0;
	}
}

typedef struct settle_ctx { run *r; double t; double *y; } settle_ctx;

/* RHS on the state in r->m (which csf_contact_settle changes), keeping y in step with it. */
static int settle_eval(void *ctx)
{
	settle_ctx *s = ctx;
	const csf_prog *p = s->r->p;
	memcpy(s->y, s->r->m + p->ystart, p->ny * sizeof *s->y);
	return rhs(s->t, s->y, s->r->fs, s->r);
}

/* Room for ng guards in each guard vector (keeping their values). 0, or -1 when memory runs out. */
static int room_for_guards(run *r, size_t ng)
{
	if (ng <= r->capg) return 0;
	size_t cap = r->capg ? r->capg : 16;
	while (cap < ng) cap *= 2;
	double **g[6] = { &r->ga, &r->gb, &r->gs, &r->gh, &r->gt, &r->gl };
	for (int i = 0; i < 6; i++) {
		double *q = realloc(*g[i], cap * sizeof *q);
		if (!q) {
			r->nomem = 1;
			return -1;
		}
		*g[i] = q;
	}
	r->capg = cap;
	return 0;
}

/*
 * Chooses the candidate contacts for the ns states ys (contact.c): the
 * instants at which their guards will be looked at. The guard vectors
 * g[0..ng) (ga, gb) become those of the new candidates, a new pair's
 * computed from state gy[q]. 0, or -1 when memory runs out.
 */
static int choose_contacts(run *r, const double *const *ys, int ns, double **g[], const double *const *gy, int ng)
{
	const csf_prog *p = r->p;
	long k = csf_contacts_find(r->cs, r->m, ys, ns);
	if (k < 0 || room_for_guards(r, p->nevents + 2 * (size_t)k)) {
		r->nomem = 1;
		return -1;
	}
	double *gc[2];
	for (int q = 0; q < ng; q++) gc[q] = *g[q] + p->nevents;
	csf_contacts_commit(r->cs, r->m, gc, gy, ng);
	r->ng = p->nevents + 2 * (uint32_t)k;
	r->nchoices++, r->ncand += (unsigned long)k;
	if ((unsigned long)k > r->maxcand) r->maxcand = (unsigned long)k;
	return 0;
}

/* Brings every mode up to date at (t, y): at the start, and after an event. */
static int update_modes(run *r, double t, double *y)
{
	const csf_prog *p = r->p;
	free_modes(r, t, y);
	if (r->cs) {
		const double *ys[1] = { y };
		if (choose_contacts(r, ys, 1, NULL, NULL, 0)) return 1;
		settle_ctx s = { r, t, y };
		memcpy(r->m + p->ystart, y, p->ny * sizeof *y);
		int st = csf_contact_settle(p, r->m, r->zeno, r->tol, settle_eval, &s);
		if (st > 0) r->unsettled = st, r->unsettled_t = t;
		if (!st && csf_contacts_unsolved(r->cs)) r->unsettled = CSF_SETTLE_FORCES, r->unsettled_t = t, st = 1;
		if (st) return 1;
		memcpy(y, r->m + p->ystart, p->ny * sizeof *y);
		free_modes(r, t, y);
	}
	return r->fail;
}

/* How closely events are located in time: 1e-13 s, finer for scenes on tiny time scales. */
static double location_tol(const csf_prog *p) { return csf_min(1e-13, 1e-10 * p->by); }

/*
 * The cubic Hermite interpolant of the step from (ta, r->ya), derivative
 * r->fa, to (ta + dt, yb), derivative r->fb, at ta + s dt, into out.
 */
static void hermite(const run *r, double dt, const double *yb, double s, double *out)
{
	double s2 = s * s, s3 = s2 * s;
	double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
	for (size_t i = 0; i < r->p->ny; i++)
		out[i] = h00 * r->ya[i] + h10 * dt * r->fa[i] + h01 * yb[i] + h11 * dt * r->fb[i];
}

/*
 * The state at ta + s (tb - ta) within the step just taken from (ta, r->ya)
 * to (tb, yb): the method's continuous extension, or the cubic Hermite
 * interpolant of the values and derivatives (r->fa, r->fb) at its ends.
 * 0, or 1 if an evaluation failed.
 */
static int interp(run *r, csf_ode *ode, double ta, double tb, const double *yb, double s, double *out)
{
	if (r->dense) return csf_ode_dense_eval(ode, ta + s * (tb - ta), out);
	hermite(r, tb - ta, yb, s, out);
	return 0;
}

/*
 * The guards at time tc on the state stepped exactly from the step's start
 * (ta, r->ya) of the step that ended at (tb, yb), into r->gs, the state left
 * in r->ys. Within 1e-6 of the step from its start, the state is the step's
 * interpolant (exact there to far below rounding), not a substep: a method's
 * step that short can be off by many units in the last place (bsimp's
 * extrapolation), enough to put a gap that has just opened below zero.
 * CSF_ODE_OK, STOPPED if a derivative was not finite, FAILED (with msg) if
 * the step failed.
 */
static int substep_guards(run *r, csf_ode *ode, double ta, double tb, const double *yb, double tc, char *msg,
                          size_t msglen)
{
	if (tc - ta < 1e-6 * (tb - ta)) {
		if (interp(r, ode, ta, tb, yb, (tc - ta) / (tb - ta), r->ys)) return CSF_ODE_STOPPED;
	} else if (csf_ode_substep(ode, ta, r->ya, tc - ta, r->ys)) {
		if (r->fail) return CSF_ODE_STOPPED;
		snprintf(msg, msglen, "the %s step from t=%.17g to locate an event at t=%.17g failed", csf_ode_method(ode),
		         ta, tc);
		return CSF_ODE_FAILED;
	}
	return guards_at(r, tc, r->ys, r->gs) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/*
 * Guard k at time tc of the step from (ta, r->ya) to (tb, yb), into r->gs (the
 * state in r->ys): on the state stepped exactly from the step's start, or
 * (dense) on the step's continuous extension, which costs no step.
 */
static int guard_at(run *r, csf_ode *ode, int dense, double ta, double tb, const double *yb, double tc, char *msg,
                    size_t msglen)
{
	if (!dense) return substep_guards(r, ode, ta, tb, yb, tc, msg, msglen);
	if (csf_ode_dense_eval(ode, tc, r->ys)) return CSF_ODE_STOPPED;
	return guards_at(r, tc, r->ys, r->gs) ? CSF_ODE_STOPPED : CSF_ODE_OK;
}

/*
 * Narrows [*lo, *hi], where guard k is >= 0 at *lo (value *glo) and < 0 at
 * *hi (*ghi), to at most tol by the Illinois method, on exact states or on
 * the continuous extension (guard_at).
 */
static int illinois(run *r, csf_ode *ode, int dense, uint32_t k, double ta, double tb, const double *yb, double *lo,
                    double *glo, double *hi, double *ghi, double tol, char *msg, size_t msglen)
{
	int side = 0, st;
	/* Each pass moves an end of the bracket inwards by at least one double, so the loop ends:
	   it stops when the bracket is tol wide or its ends are adjacent doubles (the spacing of
	   doubles at the event's time can exceed tol: 1.1e-13 s past 512 s). */
	while (*hi - *lo > tol && nextafter(*lo, *hi) < *hi) {
		if (csf_signal) return CSF_ODE_HALTED;
		double c = *hi - *ghi * (*hi - *lo) / (*ghi - *glo);
		/* the secant's point rounds to an end when the guard there is tiny (a crossing found
		   exactly): it then moves in by tol / 4 below, which ends the search; only a point
		   that is not a number, or outside the bracket, is a bisection */
		if (!(c >= *lo && c <= *hi)) c = *lo + (*hi - *lo) / 2;
		if (c - *lo < tol / 4) c = *lo + tol / 4; /* shrink the bracket from both ends */
		if (*hi - c < tol / 4) c = *hi - tol / 4;
		/* tol / 4 can be under half the spacing of doubles at c: the nudge rounds back onto the end */
		if (c <= *lo) c = nextafter(*lo, *hi);
		if (c >= *hi) c = nextafter(*hi, *lo);
		if ((st = guard_at(r, ode, dense, ta, tb, yb, c, msg, msglen))) return st;
		double gc = r->gs[k];
		if (gc < 0) {
			*hi = c, *ghi = gc;
			if (side < 0) *glo /= 2;
			side = -1;
		} else {
			*lo = c, *glo = gc;
			if (side > 0) *ghi /= 2;
			side = 1;
		}
	}
	return CSF_ODE_OK;
}

/*
 * The time *tk of guard k's crossing in (lo, hi], where g(lo) >= 0 > g(hi),
 * on states stepped from the step's start (ta, r->ya) that ended at
 * (tb, yb); leaves the state at that time in r->ys. With a continuous
 * extension, the crossing is found on it first, without steps; then a
 * bracket around it, 1000 times the location tolerance wide (wider, by
 * factors of 1000, when the exact guards do not change sign across it), is
 * narrowed on exact states, a few steps instead of some forty. *tl is the
 * bracket's other end: the guard is >= 0 there. Returns as substep_guards.
 */
static int locate(run *r, csf_ode *ode, uint32_t k, double ta, double tb, const double *yb, double lo, double glo,
                  double hi, double ghi, double *tk, double *tl, char *msg, size_t msglen)
{
	const double tol = location_tol(r->p);
	int st;
	if (r->dense) {
		double l = lo, gl = glo, u = hi, gu = ghi;
		if ((st = illinois(r, ode, 1, k, ta, tb, yb, &l, &gl, &u, &gu, tol, msg, msglen))) return st;
		for (double w = 1e3 * tol; w < hi - lo; w *= 1e3) {
			double a = u - w > lo ? u - w : lo, b = u + w < hi ? u + w : hi, gla = glo, ghb = ghi;
			if (a > lo) {
				if ((st = substep_guards(r, ode, ta, tb, yb, a, msg, msglen))) return st;
				gla = r->gs[k];
			}
			if (b < hi) {
				if ((st = substep_guards(r, ode, ta, tb, yb, b, msg, msglen))) return st;
				ghb = r->gs[k];
			}
			if (gla >= 0 && ghb < 0) {
				lo = a, glo = gla, hi = b, ghi = ghb;
				break;
			}
		}
	}
	if ((st = illinois(r, ode, 0, k, ta, tb, yb, &lo, &glo, &hi, &ghi, tol, msg, msglen))) return st;
	*tk = hi, *tl = lo;
	if (hi == tb) {
		memcpy(r->ys, yb, r->p->ny * sizeof *yb);
		return CSF_ODE_OK;
	}
	return substep_guards(r, ode, ta, tb, yb, hi, msg, msglen);
}

/*
 * The event r->last happened at (t, y): the modes are brought up to date
 * (impacts change y), the integrator restarts, and r->ga and r->fa hold the
 * guards and derivative there. 0, or 1 if a derivative was not finite.
 */
/*
 * The stability guard. A fixed step is stable for a scene only while h
 * lambda stays in the method's stability region for its fastest modes
 * (csf_ode_stable_step); an explicit adaptive method on a stiff scene is
 * held by that region to steps far shorter than its accuracy needs. The
 * guard estimates the dominant eigenvalues of df/dy (spectrum.c) from
 * Jacobian-vector products: the JAC section run with the tangent of the
 * state set to v, or with contacts (whose forces have no tangent code) a
 * difference of the RHS along v. It looks at the start, after every
 * event, and then again as often as keeps its cost near 2.5 % of the
 * run's evaluations, more often as a fixed step nears the limit. It
 * halts a fixed step past the limit (exit 1, before the step's rows),
 * shortens verlet's own step, warns of stiffness, and feeds --stats.
 * Its decisions depend on counts of evaluations, never on the clock, so
 * that csfvm and a generated program halt at the same step.
 */
/* A look costs at most 1 / LOOK_EVERY of the evaluations before it (but for those a fixed step needs). */
enum { LOOK_EVERY = 100 };

/*
 * --method auto (the default): dop853 while its steps are held by its
 * accuracy. When a look of the guard, with a thousand steps or more to go,
 * finds them held by its stability, as the stiffness warning would (steps
 * at 0.8 of the largest stable step or more, a stiffness ratio of 100 or
 * more, or a second look that agrees), or about to be (steps at AUTO_NEAR
 * of it or more, the dominant eigenvalue nearer the negative real axis
 * than the imaginary one, a decaying mode, and a stiffness ratio of 1000
 * or more: the accuracy-held steps of Oregonator's and HIRES's starts,
 * which cost dop853 4 and 1.3 times what the whole run costs bsimp), the
 * next step is taken by AUTO_STIFF, implicit. Back to dop853 when two looks
 * in a row find the implicit method's own step (the one its error control
 * proposes) shorter than dop853's largest stable step, as in a fast
 * transient or once the fast modes are gone. The gap between the
 * thresholds and the second look are the hysteresis that keeps switches
 * few, as LSODA's. bsimp, not msbdf: on the four reference problems
 * (bench/stiff.sh) it takes 1.5 to 2.1 times msbdf's evaluations, but
 * restarts without a history to rebuild (every switch and every event
 * restarts) and reaches Robertson's kinetics at 1e11 s within 1e-10
 * relatively, where msbdf at its default tolerance is 7 % off.
 */
#define AUTO_STIFF "bsimp"
#define AUTO_NEAR 0.05
/*
 * bsimp works on the dense n-by-n Jacobian: n^2 memory and some n^3/3
 * operations a step for its LU decompositions. Past AUTO_MAX_N state
 * variables auto is dop853 alone, which warns of stiffness as when named.
 */
enum { AUTO_MAX_N = 200 };
enum { AUTO_SHOWN = 8 }; /* the switches --stats lists */

typedef struct autom {
	csf_ode *m[2];              /* dop853 and AUTO_STIFF */
	int cur;                    /* the one that takes the steps */
	int want;                   /* the guard asks for the other from the next step on */
	int soft;                   /* looks in a row (implicit) that found the stiffness passed */
	unsigned long n;            /* switches */
	double at[AUTO_SHOWN];      /* the first ones' times (to m[1], m[0], m[1], ...: they alternate) */
} autom;

typedef struct guard {
	csf_spectrum *sp;
	FILE *err;
	double *y, *f0, *yd, *fd; /* the state looked at, f there; with differences, a state along v and f there */
	double t;
	int exact;                 /* J v from the JAC section, not by differences */
	int check_step;            /* a fixed step of an explicit method: halt past the limit */
	int auto_step;             /* verlet's own step (no --step), from the tolerance and the time scale */
	double vfrac;              /* verlet: sqrt(tol / 1e-4) */
	double user_step;          /* --step */
	int detect_stiff;          /* an explicit adaptive method: warn when stability holds its steps */
	int fixed;                 /* fixed steps */
	int stats;
	int due;                   /* look after the next step (an event happened) */
	int stiff_hits;
	double h;                  /* the fixed step (the longest a row's interval is cut into) */
	double span;               /* the run's length */
	double smin;               /* fixed steps: the method's least limit of h |lambda| on the two axes */
	unsigned long nexact;      /* J v products by the JAC section */
	double next;               /* look when guard_evals reaches this */
	unsigned long next_step;   /* fixed steps: look after this many */
	unsigned long steps, checks;
	double seconds;
	/* what it saw */
	csf_eigs last, at_max; /* the last look's eigenvalues, and those of the largest rho */
	double rho_max, ratio, ratio_rho, hrho, hlim_rho; /* fixed: the largest h / largest stable step, at rho */
	int ratio_exact, have_ratio;
	double auto_ratio;         /* auto: the largest ratio of the looks that decide (not --stats's) */
	double aside;              /* auto: the evaluations of --stats's own ratios, left out of the schedule */
	int warned; /* of stiffness */
} guard;

/* J v in the coordinates y_i / yscale_i (J's eigenvalues are the same in any). */
static int jvp(void *ctx, const double *v, double *jv)
{
	run *r = ctx;
	guard *g = r->g;
	const csf_prog *p = r->p;
	uint32_t n = p->ny;
	if (g->exact) {
		double *m = r->m, *tan = m + p->jtan;
		m[p->tslot] = g->t;
		memcpy(m + p->ystart, g->y, n * sizeof *m);
		for (uint32_t i = 0; i < n; i++) tan[p->ystart + i] = v[i] * p->yscale[i];
		tan[p->tslot] = 0;
		r->exec(p, CSF_SEC_JAC, m, m + p->ystart, m + p->dstart);
		for (uint32_t i = 0; i < n; i++) jv[i] = tan[p->dstart + i] / p->yscale[i];
		g->nexact++;
		return 0;
	}
	/* forward difference: v has unit length, the step sqrt(eps) of the state's size */
	double size = 0;
	for (uint32_t i = 0; i < n; i++) size += (g->y[i] / p->yscale[i]) * (g->y[i] / p->yscale[i]);
	double e = sqrt(DBL_EPSILON) * (1 + sqrt(size));
	for (uint32_t i = 0; i < n; i++) g->yd[i] = g->y[i] + e * v[i] * p->yscale[i];
	if (rhs(g->t, g->yd, g->fd, r)) return 1;
	for (uint32_t i = 0; i < n; i++) jv[i] = (g->fd[i] - g->f0[i]) / (e * p->yscale[i]);
	return 0;
}

/* The run's evaluations so far, the guard's own included: an RHS counts 1, a product by the JAC section 2. */
static double guard_evals(const run *r) { return (double)r->nrhs + 2.0 * (double)r->g->nexact - r->g->aside; }

/* x rounded down to one significant digit: a step to suggest. */
static double round_down(double x)
{
	double e = pow(10, floor(log10(x))), d = floor(x / e * (1 + 1e-12));
	return d * e;
}

/* A ratio or a count as a person writes it: 350, 1e6, 2.5e6. */
static void fmt_ratio(char buf[32], double x)
{
	if (x < 1e4) {
		snprintf(buf, 32, "%.0f", x);
		return;
	}
	char m[16];
	int ex = (int)floor(log10(x));
	double mant = x / pow(10, ex);
	if (mant >= 9.95) mant /= 10, ex++;
	snprintf(m, sizeof m, "%.2g", mant);
	snprintf(buf, 32, "%se%d", m, ex);
}

/*
 * The largest stable step for the dominant eigenvalues e. verlet's come
 * in pairs +-lambda; a real pair is a mode that grows by itself, which
 * limits no step, but a slower oscillation beside it does: the most
 * negative eigenvalue of J^2 gives it.
 */
static double stable_step(run *r, csf_ode *ode, const csf_eigs *e)
{
	guard *g = r->g;
	double h = INFINITY;
	for (int i = 0; i < e->n; i++)
		if (i == 0 || e->im[0] == 0 || e->im[i] != -e->im[0]) /* a complex pair's second: the first's conjugate */
			h = fmin(h, csf_ode_stable_step(ode, g->fixed, e->re[i], e->im[i], g->span));
	if (csf_ode_fixed_only(ode) && h == INFINITY && e->rho > 0) {
		double mu;
		if (csf_spectrum_lowest_square(g->sp, jvp, r, e->rho * e->rho, &mu) == 0 && mu < 0)
			h = csf_ode_stable_step(ode, g->fixed, 0, sqrt(-mu), g->span);
	}
	return h;
}

/* How the dominant eigenvalues lie: on the imaginary axis, the real axis, or neither. */
static const char *eig_kind(const csf_eigs *e)
{
	int re = 1, im = 1;
	for (int i = 0; i < e->n; i++) {
		re &= fabs(e->im[i]) <= 1e-3 * e->rho;
		im &= fabs(e->re[i]) <= 1e-3 * e->rho;
	}
	return e->rho == 0 ? "zero" : im ? "imaginary" : re ? "real" : "complex";
}

/* The stiffness ratio at the state looked at, kept when the largest yet. 0, or 1 if it cannot be computed. */
static int guard_ratio(run *r, double rho)
{
	guard *g = r->g;
	double ratio;
	/* zero: below sqrt(eps) of the largest, 10 times over, for exact products; differences,
	   good to some sqrt(eps), leave the fourth root */
	int exact, st = csf_spectrum_ratio(g->sp, jvp, r, g->exact ? 1.5e-7 : 1e-3, &ratio, &exact);
	r->fail = 0;
	g->ratio_rho = rho;
	if (st) return 1;
	if (!g->have_ratio || ratio > g->ratio) g->ratio = ratio, g->ratio_exact = exact, g->have_ratio = 1;
	if (ratio > g->auto_ratio) g->auto_ratio = ratio;
	return 0;
}

/*
 * --method auto: is the stiffness ratio at least min? Measured at the
 * first look that asks (and kept, the largest, by later ones), never taken
 * from the looks --stats adds, so that --stats does not steer the run.
 */
static int auto_ratio_at_least(run *r, double rho, double min)
{
	guard *g = r->g;
	if (!(g->auto_ratio > 0)) guard_ratio(r, rho);
	return g->auto_ratio >= min;
}

/*
 * Looks at the scene at (t, y) after a step of h (0 at the start).
 * Returns 1 after writing why the run must halt, else 0. A state where an
 * estimate cannot be made (a derivative not finite nearby) is passed
 * over: the integration reports what is wrong there.
 */
static int guard_check(run *r, csf_ode *ode, double t, const double *y, double h)
{
	guard *g = r->g;
	const csf_prog *p = r->p;
	struct timespec c0, c1;
	clock_gettime(CLOCK_MONOTONIC, &c0);
	double before = guard_evals(r);
	/* a look for a fixed step is as long as it needs; another spends at most its share of the run */
	int maxprod = g->fixed ? 1000 : (int)fmin(1000, fmax(3, before / LOOK_EVERY / 2));
	int halt = 0;
	g->due = 0;
	g->checks++;
	g->t = t;
	memcpy(g->y, y, p->ny * sizeof *y);
	csf_eigs e;
	if ((!g->exact && rhs(t, y, g->f0, r)) || csf_spectrum_dominant(g->sp, jvp, r, maxprod, &e)) {
		r->fail = 0;
		goto out;
	}
	g->last = e;
	if (e.rho > g->rho_max) g->rho_max = e.rho, g->at_max = e;
	if (g->stats && (!g->have_ratio || e.rho > 1.5 * g->ratio_rho)) {
		double b = guard_evals(r), keep = g->auto_ratio;
		guard_ratio(r, e.rho);
		if (r->au) g->aside += guard_evals(r) - b, g->auto_ratio = keep;
	}
	if (!g->fixed && !g->detect_stiff) goto out;
	autom *au = r->au;
	if (au && au->cur) {
		/* implicit: back to dop853 when its own step is within dop853's stable step (not when h rho
		   is 40 or more, past the region of every explicit method, without the search for it) */
		double hn = csf_ode_next_step(ode);
		au->soft = hn * e.rho < 40 && hn < stable_step(r, au->m[0], &e) ? au->soft + 1 : 0;
		r->fail = 0;
		if (au->soft >= 2) au->want = 1;
		goto out;
	}
	double hs = stable_step(r, au ? au->m[0] : ode, &e); /* auto: dop853's */
	r->fail = 0;
	if (g->fixed) {
		double hc = g->h; /* the step to judge */
		if (g->auto_step && h == 0) {
			/* verlet's own step: the fraction sqrt(tol / 1e-4) of the smaller of by and the fastest
			   time scale (a step the tolerance asks for, judged as asked, before a row's interval
			   is cut into equal steps) */
			double tau = e.rho > 0 ? fmin(p->by, 1 / e.rho) : p->by;
			hc = g->vfrac * tau;
			g->h = p->by / ceil(p->by / fmin(hc, p->by) * (1 - 1e-12));
		}
		if (hs < INFINITY && g->h / hs > g->hrho) g->hrho = g->h / hs, g->hlim_rho = hs * e.rho;
		if (!(g->smin > 0) && e.rho > 0) { /* the least h |lambda| limit on the two axes, once */
			double sr = csf_ode_stable_step(ode, 1, -e.rho, 0, g->span), si = csf_ode_stable_step(ode, 1, 0, e.rho, g->span);
			g->smin = fmin(sr, si) * e.rho;
		}
		if (g->check_step && hc >= hs * (1 - 1e-6)) { /* at the limit nothing decays: refused too */
			progress_off(r);
			char hb[32], tb[32], why[96] = "", tolb[64] = "";
			snprintf(hb, sizeof hb, "%.3g", hc);
			csf_fmt_double(tb, t);
			if (g->user_step > 0 && fabs(g->user_step - hc) > 1e-12 * hc)
				snprintf(why, sizeof why, " (from --step %g)", g->user_step);
			if (g->auto_step && h == 0) {
				double tau = e.rho > 0 ? fmin(p->by, 1 / e.rho) : p->by;
				snprintf(why, sizeof why, " (verlet's step for --tol %g)", g->vfrac * g->vfrac * 1e-4);
				snprintf(tolb, sizeof tolb, ", --tol %g", round_down(0.81e-4 * (hs / tau) * (hs / tau)));
			}
			fprintf(g->err,
			        "error: %s%s%sstep %s s%s is %s the stability limit of %s for this scene (fastest time scale "
			        "%.3g s; largest stable step %.3g s): use --step %g%s or an adaptive method\n",
			        h > 0 ? "at t=" : "", h > 0 ? tb : "", h > 0 ? ", " : "", hb, why, hc < hs ? "at" : "beyond",
			        csf_ode_method(ode), 1 / e.rho,
			        hs, round_down(0.9 * hs), tolb);
			halt = 1;
		}
	} else if (au) { /* dop853: the implicit method from the next step on when stability holds it */
		if (h > 0 && hs < INFINITY && (r->tend - t) / h > 1000 &&
		    ((h >= AUTO_NEAR * hs && e.re[0] < 0 && fabs(e.im[0]) < -e.re[0] && auto_ratio_at_least(r, e.rho, 1000)) ||
		     (h >= 0.8 * hs && (auto_ratio_at_least(r, e.rho, 100) || ++g->stiff_hits >= 2))))
			au->want = 1;
	} else if (h > 0 && hs < INFINITY && h >= 0.8 * hs && (r->tend - t) / h > 1000 &&
	           ((!g->have_ratio && guard_ratio(r, e.rho)) || g->ratio >= 100 || ++g->stiff_hits >= 2)) {
		/* steps held near the stability limit, with many steps to go: stiff if the spectrum spans
		   100 times or more, or (a spread that cannot be measured) when a second look agrees */
		char tb[32], rb[64] = "";
		csf_fmt_double(tb, t);
		if (g->have_ratio && g->ratio > 0) {
			char x[32];
			fmt_ratio(x, g->ratio);
			snprintf(rb, sizeof rb, ", stiffness ratio %s%s", g->ratio_exact ? "" : "about ", x);
		}
		char more[32];
		fmt_ratio(more, (r->tend - t) / h);
		progress_off(r);
		fprintf(g->err,
		        "warning: at t=%s, after %lu steps, the problem looks stiff: the explicit method %s is held to steps "
		        "of %.3g s by its stability (fastest time scale %.3g s%s) and needs some %s more; an implicit method "
		        "is not: try --method msbdf or --method bsimp\n",
		        tb, g->steps, csf_ode_method(ode), h, 1 / e.rho, rb, more);
		g->detect_stiff = 0;
		g->warned = 1;
	}
out:; /* a label before a declaration: C11 needs a statement */
	/* the next look: after LOOK_EVERY times this one's cost in evaluations; with fixed steps,
	   sooner as h rho nears the method's least limit on either axis (the direction of the
	   eigenvalues may turn, as a pendulum's do), every step past half of it */
	double now = guard_evals(r);
	g->next = now + LOOK_EVERY * (now - before);
	if (g->fixed) {
		double per_step = g->steps ? (double)r->nrhs / (double)g->steps : 1;
		double every = LOOK_EVERY * (now - before) / fmax(per_step, 1);
		if (g->smin > 0 && g->h * g->rho_max > 0.5 * g->smin)
			every *= fmax(0, 1 - g->h * g->rho_max / g->smin) / 0.5;
		g->next_step = g->steps + (unsigned long)fmax(1, floor(every));
	}
	clock_gettime(CLOCK_MONOTONIC, &c1);
	g->seconds += seconds(c0, c1);
	return halt;
}

typedef struct watch_ctx { run *r; csf_ode *ode; } watch_ctx;

/* After every step (csf_watch_fn): a signal halts the run; the progress line; a look when one is due. */
static int step_watch(void *ctx, double t, const double *y, double h)
{
	watch_ctx *w = ctx;
	w->r->fail = 0; /* an evaluation that failed was in a trial step, tried again shorter */
	if (csf_signal) return 1;
	if (w->r->prog) progress(w->r, t);
	guard *g = w->r->g;
	if (!g) return 0;
	g->steps++;
	if (g->fixed ? g->steps < g->next_step && !g->due : guard_evals(w->r) < g->next) return 0;
	return guard_check(w->r, w->ode, t, y, h);
}

/* After the modes were set at t from scratch: a 'stop when' condition already true ends the run there. */
static void stop_now(run *r, double t)
{
	const csf_prog *p = r->p;
	for (uint32_t i = 0; i < p->nevents && !r->stopped; i++)
		if (p->events[i].kind & CSF_EVENT_TERMINAL && r->m[p->events[i].mode] > 0)
			r->stopped = 1, r->stop_t = t, r->stop_src = p->events[i].src;
}

/*
 * Takes the event r->last at (t, y): the modes brought up to date, the
 * integrator restarted. A 'stop when' condition's ends the run instead:
 * TERMINAL, with its time in r->stop_t. 0, or CSF_ODE_STOPPED when a
 * derivative is not finite.
 */
static int take_event(run *r, csf_ode *ode, double t, double *y)
{
	r->nevents++;
	r->pending = 0;
	if (r->last >= 0 && r->last < (long)r->p->nevents && r->p->events[r->last].kind & CSF_EVENT_TERMINAL) {
		r->stop_src = r->last_src;
		r->stop_t = t;
		return TERMINAL;
	}
	if (r->g) r->g->due = 1; /* the scene may have changed: with fixed steps, look after the next one */
	if (update_modes(r, t, y)) return CSF_ODE_STOPPED;
	csf_ode_restart(ode);
	if (guards_at(r, t, y, r->ga)) return CSF_ODE_STOPPED;
	memcpy(r->fa, r->fs, r->p->ny * sizeof *r->fa);
	return 0;
}

/* Advances (*t, y) to t1 by adaptive steps, at most MAX_WORK of them. */
static int advance_plain(run *r, csf_ode *ode, double *t, double t1, double *y, char *msg, size_t msglen)
{
	for (unsigned long work = 0; *t < t1; work++) {
		double ta = *t;
		if (work == MAX_WORK) return TOO_MUCH;
		int st = csf_ode_step(ode, t, t1, 0, 0, y, msg, msglen);
		if (st != CSF_ODE_OK) return st;
		r->last_h = *t - ta;
	}
	return CSF_ODE_OK;
}

/*
 * After a step from (ta, r->ya), with guards r->ga and derivative r->fa
 * there, to (tb, y): the earliest event in (ta, tb]. *which is its guard, or
 * -1 when there is none (r->ga and r->fa then move on to tb); *te is its
 * time, r->ye the state there, r->last and r->last_src name it.
 */
static int step_events(run *r, csf_ode *ode, double ta, double tb, const double *y, double *te, long *which, char *msg,
                       size_t msglen)
{
	const csf_prog *p = r->p;
	size_t n = p->ny;
	int st;
	*which = -1;
	if (r->cs && csf_contacts_unsolved(r->cs)) { /* the forces of the step did not hold the contacts */
		r->unsettled = CSF_SETTLE_FORCES, r->unsettled_t = ta;
		return CSF_ODE_STOPPED;
	}
	if (guards_at(r, tb, y, r->gb)) return CSF_ODE_STOPPED;
	memcpy(r->fb, r->fs, n * sizeof *y);
	double lo = ta, hi = tb, dt = tb - ta;
	if (r->cs) {
		/* the candidate contacts of this step: every pair that can touch at the instants
		   its guards are looked at (the start, 3 interpolated points, the end) */
		for (int j = 1; j < 4; j++)
			if (interp(r, ode, ta, tb, y, j / 4.0, r->yh + (size_t)(j - 1) * n)) return CSF_ODE_STOPPED;
		const double *ys[5] = { r->ya, r->yh, r->yh + n, r->yh + 2 * n, y }, *gy[2] = { r->ya, y };
		double **g[2] = { &r->ga, &r->gb };
		if (choose_contacts(r, ys, 5, g, gy, 2)) return CSF_ODE_STOPPED;
	}
	size_t ng = r->ng;
	/* the first of the sample points (3 interpolated, then the step's end) where an armed
	   guard is negative: [lo, hi], with hi's guards in r->gh */
	int found = 0;
	for (int j = 1; j <= 4 && !found; j++) {
		if (j < 4) {
			const double *yj = r->yh + (size_t)(j - 1) * n; /* with contacts, computed above */
			if (!r->cs) {
				if (interp(r, ode, ta, tb, y, j / 4.0, r->ys)) return CSF_ODE_STOPPED;
				yj = r->ys;
			}
			hi = ta + j / 4.0 * dt;
			if (guards_at(r, hi, yj, r->gh)) return CSF_ODE_STOPPED;
		} else {
			hi = tb;
			memcpy(r->gh, r->gb, ng * sizeof *r->gh);
		}
		for (size_t k = 0; k < ng; k++) found |= r->ga[k] >= 0 && r->gh[k] < 0;
		if (!found) lo = hi;
	}
	/* the earliest crossing among the guards negative at hi, each bracketed on exact states;
	   once one is located in (bl, best], a guard that is not yet negative at best crosses later,
	   and one negative at best but not at bl crosses at the same instant (to the location's
	   tolerance): neither is located, so that many pairs that switch at once (a row of blocks
	   that stop together) cost one location, not one each */
	double best = tb, bl = ta;
	int known = 0; /* the guards at best and at bl are in r->gt and r->gl */
	for (size_t k = 0; found && k < ng; k++) {
		if (!(r->ga[k] >= 0 && r->gh[k] < 0)) continue;
		if (*which >= 0 && !known) {
			if (guards_at(r, best, r->ye, r->gt)) return CSF_ODE_STOPPED;
			if ((st = substep_guards(r, ode, ta, tb, y, bl, msg, msglen))) return st;
			memcpy(r->gl, r->gs, ng * sizeof *r->gl);
			known = 1;
		}
		if (*which >= 0 && (r->gt[k] >= 0 || r->gl[k] >= 0)) continue;
		/* the exact state's guards at lo and hi (the interpolant only pointed here) */
		double l = lo, gl = r->ga[k], u = hi, gu = r->gh[k];
		if (lo > ta) {
			if ((st = substep_guards(r, ode, ta, tb, y, lo, msg, msglen))) return st;
			if (r->gs[k] < 0) l = ta; /* already below at lo: the crossing is earlier */
			else gl = r->gs[k];
		}
		if (*which >= 0) { /* below at bl: the crossing is before it */
			if (bl <= l) continue; /* (it cannot be: bl is past a state where the guard is >= 0) */
			u = bl, gu = r->gl[k];
		} else if (hi < tb) {
			if ((st = substep_guards(r, ode, ta, tb, y, hi, msg, msglen))) return st;
			gu = r->gs[k];
			if (gu >= 0) { /* not below on the exact state: try the step's end */
				u = tb, gu = r->gb[k];
				if (gu >= 0) continue;
			}
		}
		double tk, tl;
		if ((st = locate(r, ode, (uint32_t)k, ta, tb, y, l, gl, u, gu, &tk, &tl, msg, msglen))) return st;
		if (tk < best || *which < 0) {
			best = tk, bl = tl, *which = (long)k, known = 0;
			memcpy(r->ye, r->ys, n * sizeof *r->ye);
		}
	}
	if (*which < 0) { /* none, or the interpolant's alarm was false */
		memcpy(r->ga, r->gb, ng * sizeof *r->ga);
		memcpy(r->fa, r->fb, n * sizeof *r->fa);
		return CSF_ODE_OK;
	}
	*te = best;
	r->last = *which;
	r->last_src = *which < (long)p->nevents ? p->events[*which].src
	                                        : csf_contacts_src(r->cs, (uint32_t)(*which - (long)p->nevents) / 2);
	return CSF_ODE_OK;
}

/* One more event at time te after a step from ta: CHATTER after 1000 in a row that do not advance time. */
static int chatter(unsigned long *same, double ta, double te, char *msg, size_t msglen)
{
	if (te - ta > 1e-12 * (1 + fabs(te))) {
		*same = 0;
		return 0;
	}
	if (++*same <= 1000) return 0;
	snprintf(msg, msglen, "%lu events without time advancing", *same);
	return CHATTER;
}

/*
 * Advances (*t, y) to t1 as csf_ode_step does, stopping at events. On entry
 * r->ga and r->fa hold the guards and derivative at (*t, y), unless an event
 * located at the last output time is pending: it happens first.
 */
static int advance_events(run *r, csf_ode *ode, double *t, double t1, int fixed, double h, double *y, char *msg,
                          size_t msglen)
{
	const csf_prog *p = r->p;
	size_t n = p->ny;
	unsigned long same = 0, work = 0;
	int st;
	if (r->pending && (st = take_event(r, ode, *t, y))) return st;
	while (*t < t1) {
		double ta = *t, best;
		long which;
		if (++work > MAX_WORK) return TOO_MUCH;
		memcpy(r->ya, y, n * sizeof *y);
		st = csf_ode_step(ode, t, t1, fixed, h, y, msg, msglen);
		if (st != CSF_ODE_OK) return st;
		r->last_h = *t - ta;
		if ((st = step_events(r, ode, ta, *t, y, &best, &which, msg, msglen))) return st;
		if (which < 0) {
			same = 0;
			continue;
		}
		memcpy(y, r->ye, n * sizeof *y);
		*t = best;
		if (t1 - best <= location_tol(p)) { /* at an output time: its row shows the state before the event */
			*t = t1;
			r->pending = 1;
			return CSF_ODE_OK;
		}
		if ((st = take_event(r, ode, best, y))) return st;
		if ((st = chatter(&same, ta, best, msg, msglen))) return st;
	}
	return CSF_ODE_OK;
}

/*
 * --method auto: the other method takes the steps from (r->ti, r->yi) on,
 * restarted there (no history: the state is the one the last step ended
 * at), with a first step from its estimate. 0, or CSF_ODE_STOPPED if f
 * failed there.
 */
static int switch_method(run *r)
{
	autom *au = r->au;
	csf_ode *to = au->m[!au->cur];
	au->want = 0, au->soft = 0;
	csf_ode_restart(to);
	if (csf_ode_first_step(to, r->ti, r->yi)) return CSF_ODE_STOPPED;
	r->fail = 0; /* an Euler step of the estimate that failed was tried again shorter */
	au->cur = !au->cur;
	if (au->n < AUTO_SHOWN) au->at[au->n] = r->ti;
	au->n++;
	r->ode = to;
	r->dense = csf_ode_dense(to);
	return 0;
}

/*
 * A method with a continuous extension (csf_ode_dense): the integrator, at
 * (r->ti, r->yi), steps as far as its error control allows towards the
 * last output time, past tk, and the state y at tk is computed from the
 * last step's extension (or is its end), never by shortening a step to end
 * at tk. With --method auto, also the implicit method, which has none: its
 * steps end at tk. Each row comes from the method that took the step it is
 * in: a switch takes effect at the next step, when the rows before the
 * integrator's time have been computed. With events, a step is cut at its earliest event: the integrator
 * stops there, the rows before it come from the step's extension, and the
 * event is taken (modes, impacts, a restart) before the next step
 * (r->pending). An event within location_tol before an output time is moved
 * to it: the row shows the state before the event. On entry with events,
 * r->ga and r->fa hold the guards and derivative at (r->ti, r->yi) unless
 * an event is pending there.
 */
static int advance_dense(run *r, double tk, double *y, char *msg, size_t msglen)
{
	csf_ode *ode = r->ode;
	const csf_prog *p = r->p;
	size_t n = p->ny;
	unsigned long same = 0, work = 0;
	int events = p->nevents || p->ncrules;
	while (r->ti < tk) {
		double ta = r->ti, te;
		long which;
		if (++work > MAX_WORK) return TOO_MUCH;
		int st;
		if (r->pending && (st = take_event(r, ode, r->ti, r->yi))) {
			if (st == TERMINAL) memcpy(y, r->yi, n * sizeof *y);
			return st;
		}
		if (r->au && r->au->want) {
			if ((st = switch_method(r))) return st;
			ode = r->ode;
		}
		if (events) memcpy(r->ya, r->yi, n * sizeof *y);
		st = csf_ode_step(ode, &r->ti, r->dense ? r->tend : tk, 0, 0, r->yi, msg, msglen);
		if (st != CSF_ODE_OK) return st;
		r->last_h = r->ti - ta;
		if (!events) continue;
		if ((st = step_events(r, ode, ta, r->ti, r->yi, &te, &which, msg, msglen))) return st;
		if (which < 0) {
			same = 0;
			continue;
		}
		double row = ceil(te / p->by) * p->by; /* the first output time at or after the event */
		if (row < te) row += p->by;
		if (row - te <= location_tol(p) && row <= r->ti) te = row;
		r->ti = te;
		memcpy(r->yi, r->ye, n * sizeof *y);
		r->pending = 1;
		if ((st = chatter(&same, ta, te, msg, msglen))) return st;
	}
	if (tk == r->ti) memcpy(y, r->yi, n * sizeof *y);
	else if (csf_ode_dense_eval(ode, tk, y)) return CSF_ODE_STOPPED;
	return CSF_ODE_OK;
}

int csf_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, FILE *err)
{
	run r = { .p = p, .exec = exec };
	guard gd = { 0 };
	autom au = { 0 };
	watch_ctx wc = { &r, NULL }, wc_stiff = { &r, NULL };
	/* --method auto (the default, but for fixed steps and large scenes: dop853) is dop853 with
	   AUTO_STIFF beside it */
	const char *method = o->method && strcmp(o->method, "auto") != 0 ? o->method : NULL;
	int autom_on = !method && !o->fixed && p->ny <= AUTO_MAX_N;
	double *y = NULL;
	int fixed = 0;
	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	csf_ode *ode = NULL;
	int status = 0, werr = 0;
	char msg[256];
	r.err = err;
	r.start = r.drawn = t0;
	r.prog = o->progress == CSF_PROGRESS_ON || (o->progress == CSF_PROGRESS_AUTO && isatty(fileno(err)));

	r.m = malloc((p->nmem ? p->nmem : 1) * sizeof(double));
	y = malloc((p->ny ? p->ny : 1) * sizeof(double));
	r.ng = p->nevents; /* and two per candidate contact, none yet */
	/* events: comparisons, or contacts (whose candidates come and go) */
	int events = p->nevents || p->ncrules;
	double *work = NULL;
	if (events || autom_on) { /* (auto: jw, for a Jacobian by differences) */
		size_t n = p->ny ? p->ny : 1;
		work = malloc(12 * n * sizeof *work);
		if (work) {
			r.ya = work, r.fa = r.ya + n, r.fb = r.fa + n, r.ys = r.fb + n, r.fs = r.ys + n, r.ye = r.fs + n;
			r.jw = r.ye + n;
			r.yh = r.jw + 3 * n;
		}
	}
	if (events) room_for_guards(&r, r.ng ? r.ng : 1);
	if (p->ncrules) {
		r.cs = csf_contacts_new(p);
		((csf_prog *)p)->crun = r.cs; /* the CONTACT instruction's state (p is the caller's, not const data) */
	}
	if (!r.m || !y || ((events || autom_on) && !work) || r.nomem || (p->ncrules && !r.cs)) {
		fprintf(err, "error: out of memory\n");
		status = 2;
		goto done;
	}
	memcpy(r.m, p->mem0, p->nmem * sizeof(double));
	memcpy(y, p->mem0 + p->ystart, p->ny * sizeof(double));
	if (p->ncrules && !csf_method_contacts(method)) {
		fprintf(err, "error: method '%s' cannot run a model with contacts (mechanics/rules: their friction "
		        "depends on v); one of:", method);
		for (size_t k = 0; csf_method_name(k); k++)
			if (csf_method_contacts(csf_method_name(k))) fprintf(err, " %s", csf_method_name(k));
		fprintf(err, "\n");
		status = 2;
		goto done;
	}
	/* The last k with k*by <= till, allowing for till/by's rounding. */
	double kmax = floor(p->till / p->by);
	if ((kmax + 1) * p->by <= p->till * (1 + 1e-12)) kmax += 1;
	r.tend = kmax * p->by;
	if (p->ny) {
		/* a dense method steps as far as its error control allows (--hmax caps it), the others
		   to each output time; with events, steps of at most by, so that a guard that dips below
		   zero and back is not missed between the points each step looks at (events, below) */
		int unbounded = !o->fixed && csf_method_dense(method) && !events;
		double hmax = unbounded ? (r.tend > p->by ? r.tend : p->by) : p->by;
		if (o->hmax > 0 && o->hmax < hmax) hmax = o->hmax;
		ode = csf_ode_new(method, o->fixed, p->ny, p->by, hmax, o->tol, o->atol, p->yatol, p->yscale, p->vpair, rhs,
		                  p->jtan ? jac : NULL, &r, msg, sizeof msg);
		if (ode && autom_on) { /* the implicit method ends its steps on the rows: at most by */
			au.m[0] = ode;
			au.m[1] = csf_ode_new(AUTO_STIFF, 0, p->ny, p->by, o->hmax > 0 && o->hmax < p->by ? o->hmax : p->by,
			                      o->tol, o->atol, p->yatol, p->yscale, p->vpair, rhs, jac, &r, msg, sizeof msg);
			r.au = &au;
			if (!au.m[1]) {
				csf_ode_free(ode);
				ode = NULL;
			}
		}
		if (!ode) {
			fprintf(err, "error: %s\n", msg);
			status = 2;
			goto done;
		}
	}

	csf_out_begin();
	fputs("t", out);
	for (uint32_t i = 0; i < p->ncols; i++) fprintf(out, ",%s", csf_str(p, p->cols[i].name));
	putc('\n', out);
	csf_out_end();

	fixed = ode && (o->fixed || csf_ode_fixed_only(ode));
	double fixed_h = ode ? csf_ode_fixed_step(ode, p->by, o->step) : p->by;
	int verlet = ode && csf_ode_fixed_only(ode);
	if (ode) {
		gd.fixed = fixed;
		gd.check_step = fixed && csf_ode_explicit(ode);
		gd.auto_step = verlet && o->step <= 0;
		gd.user_step = o->step;
		gd.vfrac = sqrt((o->tol > 0 ? o->tol : csf_method_tol("verlet")) / 1e-4);
		gd.detect_stiff = !fixed && csf_ode_explicit(ode);
		gd.stats = o->stats;
	}
	if (gd.check_step || gd.auto_step || gd.detect_stiff || gd.stats) {
		size_t n = p->ny;
		gd.sp = csf_spectrum_new(n);
		gd.y = malloc(4 * n * sizeof *gd.y);
		if (!gd.sp || !gd.y) {
			fprintf(err, "error: out of memory\n");
			status = 2;
			goto done;
		}
		gd.f0 = gd.y + n, gd.yd = gd.f0 + n, gd.fd = gd.yd + n;
		gd.exact = p->jtan && !p->ncrules;
		gd.err = err;
		gd.span = r.tend;
		gd.h = p->by / ceil(p->by / fixed_h * (1 - 1e-12)); /* the step a row's interval is cut into */
		r.g = &gd;
	}
	if (ode) {
		wc.ode = ode;
		csf_ode_watch(ode, step_watch, &wc);
		if (r.au) {
			wc_stiff.ode = au.m[1];
			csf_ode_watch(au.m[1], step_watch, &wc_stiff);
		}
	}
	/* a train of bounces that would end within zeno is at rest; the integrator's accuracy (contact.c) */
	r.zeno = 1e-6 * p->by;
	r.tol = o->tol > 0 ? o->tol : csf_method_tol(method);
	if (events) {
		/* the masses first, as the rules make them: the impulses and forces of contacts divide
		   by them (a derivative that is not finite is reported by update_modes below) */
		long b = r.cs && !rhs(0, y, r.fs, &r) ? csf_contacts_bad_mass(p, r.m) : -1;
		r.fail = 0;
		if (b >= 0) {
			fprintf(err, "error: the mass of %s is %g: a body in contact needs a positive mass\n",
			        csf_str(p, p->objects[p->cbodies[b].object]), r.m[p->cbodies[b].s[CSF_CF_M]]);
			status = 1;
			goto done;
		}
		/* the modes at t = 0: each comparison's side, contacts at rest or colliding */
		if (update_modes(&r, 0, y) || (p->ny && guards_at(&r, 0, y, r.ga))) {
			if (r.unsettled) {
				report_unsettled(&r, err);
				status = 1;
				goto done;
			}
			if (r.nomem) {
				fprintf(err, "error: out of memory\n");
				status = 2;
				goto done;
			}
			report_nonfinite(p, CSF_SEC_RHS, r.m, 0, "a state derivative", o->fixed, err);
			status = 1;
			goto done;
		}
		memcpy(r.fa, r.fs, p->ny * sizeof *r.fa);
		stop_now(&r, 0); /* a 'stop when' condition true at the start: the row at t = 0 is the last */
	}
	r.dense = ode && !fixed && csf_ode_dense(ode);
	r.own = r.dense; /* (auto: dop853, dense) */
	r.ode = ode;
	if (r.own) { /* the integrator's own state, apart from the rows' */
		if (!(r.yi = malloc(p->ny * sizeof *r.yi))) {
			fprintf(err, "error: out of memory\n");
			status = 2;
			goto done;
		}
		memcpy(r.yi, y, p->ny * sizeof *y);
	}
	/* adaptive steps start at the scene's own size, not at by */
	if (ode && !fixed) {
		if (csf_ode_first_step(ode, 0, y)) {
			report_nonfinite(p, CSF_SEC_RHS, r.m, r.fail_t, "a state derivative", o->fixed, err);
			status = 1;
			goto done;
		}
		r.fail = 0; /* an Euler step of the estimate that failed was tried again shorter */
	}

	if (r.g && !gd.fixed) /* the first look when the run has spent LOOK_EVERY times what one may cost */
		gd.next = LOOK_EVERY * 2.0 * (p->ny < 12 ? p->ny + 1 : 12);
	if (r.g && gd.fixed) { /* the first look, before any step */
		if (guard_check(&r, ode, 0, y, 0)) {
			status = 1;
			goto done;
		}
		if (gd.auto_step) fixed_h = gd.h;
	}

	double t = 0;
	for (double k = 0; k <= kmax; k++) {
		double tk = k * p->by;
		if (csf_signal) break; /* after the last whole row */
		if (r.prog) progress(&r, t);
		if (ode && tk > t) {
			double trow = t; /* the last row's time */
			int st = r.own    ? advance_dense(&r, tk, y, msg, sizeof msg)
			         : events ? advance_events(&r, ode, &t, tk, fixed, fixed_h, y, msg, sizeof msg)
			         : fixed  ? csf_ode_advance_fixed(ode, &t, tk, fixed_h, y, msg, sizeof msg)
			                  : advance_plain(&r, ode, &t, tk, y, msg, sizeof msg);
			if (st == CSF_ODE_HALTED && csf_signal) break;
			if (st == TERMINAL) { /* a 'stop when' condition: the last row at its instant */
				r.stopped = 1;
				if (r.stop_t <= trow) break; /* at the last row's time: that row was the last */
				tk = r.stop_t;
				st = CSF_ODE_OK;
			}
			if (st != CSF_ODE_OK) progress_off(&r);
			if (st == CSF_ODE_HALTED) { /* the guard said why */
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_STOPPED && r.unsettled) {
				report_unsettled(&r, err);
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_STOPPED && r.nomem) {
				fprintf(err, "error: out of memory\n");
				status = 2;
				goto done;
			}
			if (st == CSF_ODE_STOPPED) {
				report_nonfinite(p, CSF_SEC_RHS, r.m, r.fail_t, "a state derivative", o->fixed, err);
				status = 1;
				goto done;
			}
			if (st == TOO_MUCH) {
				char tb[32], ta[32], hb[32], why[160];
				csf_fmt_double(tb, r.own ? r.ti : t);
				csf_fmt_double(ta, tk - p->by);
				csf_fmt_double(hb, r.last_h);
				/* stiff only when measured so: the step at the stability limit of the guard's last look */
				double hs = r.g && gd.checks && !fixed && !au.cur ? stable_step(&r, ode, &gd.last) : INFINITY;
				if (hs < INFINITY && r.last_h >= 0.8 * hs)
					snprintf(why, sizeof why,
					         "the problem is stiff: the explicit method's largest stable step is %.3g s here; try "
					         "--method msbdf or --method bsimp",
					         hs);
				else
					snprintf(why, sizeof why, "the steps are held by the error control, not by stability: the "
					                          "solution may be singular there");
				if (r.nevents) report_event_src(p, r.last_src, err);
				fprintf(err,
				        "error: at t=%s, %d steps%s since the row at t=%s, the last of %s s: the run cannot get "
				        "on (%s)\n",
				        tb, MAX_WORK, events ? " and events" : "", ta, hb,
				        r.nevents ? "the last event was of the rule on this line: events that follow each other "
				                    "ever faster, or a force that switches within each step"
				                  : why);
				status = 1;
				goto done;
			}
			if (st == CHATTER) {
				char tb[32];
				csf_fmt_double(tb, r.own ? r.ti : t);
				if (r.last >= (long)p->nevents) { /* a contact: the bodies are the user's, the rule the library's */
					uint32_t oi, oj;
					csf_contacts_objects(r.cs, (uint32_t)(r.last - (long)p->nevents) / 2, &oi, &oj);
					fprintf(err,
					        "error: at t=%s the contact of '%s' and '%s' switches between touching and parting, "
					        "or sticking and sliding, again and again (%s): no set of contacts among the "
					        "bodies touching there is consistent, and the run cannot go on\n",
					        tb, csf_str(p, p->objects[oi]), csf_str(p, p->objects[oj]), msg);
					status = 1;
					goto done;
				}
				report_event_src(p, r.last_src, err);
				fprintf(err,
				        "error: at t=%s the conditions switch back and forth without time advancing (%s): "
				        "the model has no solution past this point (a sliding mode; make the switching "
				        "condition depend on the mode, or smooth the force)\n",
				        tb, msg);
				status = 1;
				goto done;
			}
			if (st == CSF_ODE_FAILED) {
				char tb[32];
				csf_fmt_double(tb, r.own ? r.ti : t);
				fprintf(err,
				        "error: integration failed at t=%s: %s (the step size collapsed: the solution may be "
				        "singular there, or the problem stiff; try another --method or a smaller 'by')\n",
				        tb, msg);
				status = 1;
				goto done;
			}
		}
		t = tk;
		if (events && !ode) { /* no state: the conditions depend on t alone, and are looked at on the rows */
			free_modes(&r, tk, y);
			stop_now(&r, tk);
		}
		r.m[p->tslot] = tk;
		memcpy(r.m + p->ystart, y, p->ny * sizeof(double));
		int a = exec(p, CSF_SEC_OUT, r.m, r.m + p->ystart, r.m + p->dstart);
		if (a >= 0) {
			progress_off(&r);
			const csf_src *s = &p->srcs[p->asserts[a].src];
			char tb[32];
			csf_fmt_double(tb, tk);
			fprintf(err, "%s:%lu: assertion failed at t=%s: %s (object %s)\n", csf_str(p, p->files[s->file]),
			        (unsigned long)s->line, tb, csf_str(p, s->text), csf_str(p, p->asserts[a].object));
			status = 1;
			goto done;
		}
		int bad = 0;
		for (uint32_t i = 0; i < p->ny; i++) bad |= !isfinite(r.m[p->ystart + i]);
		for (uint32_t i = 0; i < p->ncols; i++) bad |= !isfinite(r.m[p->cols[i].slot]);
		if (bad) {
			progress_off(&r);
			csf_vm_exec(p, CSF_SEC_OUT, r.m, r.m + p->ystart, r.m + p->dstart); /* every value, for the report */
			report_nonfinite(p, CSF_SEC_OUT, r.m, tk, "a watched or state value", o->fixed, err);
			status = 1;
			goto done;
		}
		if (write_row(p, r.m, tk, out)) {
			werr = errno;
			break;
		}
		r.rows++;
		if (r.stopped) break;
	}
	if (csf_signal && !status) status = 128 + csf_signal;
done:
	progress_off(&r);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	unsigned long steps = 0, rejected = 0;
	if (ode) csf_ode_stats(ode, &steps, &rejected);
	if (au.m[1]) {
		unsigned long s1, r1;
		csf_ode_stats(au.m[1], &s1, &r1);
		steps += s1, rejected += r1;
	}
	o->run_steps = steps;
	o->run_rhs = r.nrhs;
	o->run_seconds = seconds(t0, t1);
	if (o->stats) {
		char cand[96] = "";
		if (r.cs)
			snprintf(cand, sizeof cand, ", %.1f contact pairs watched (candidates) on average, at most %lu",
			         r.nchoices ? (double)r.ncand / (double)r.nchoices : 0.0, r.maxcand);
		char name[64];
		snprintf(name, sizeof name, "%s%s%s%s", r.au ? "auto (" : "", ode ? csf_ode_method(ode) : "none",
		         r.au && au.n ? " and " AUTO_STIFF : "", r.au ? ")" : "");
		fprintf(err,
		        "stats: method %s%s, %lu steps (%lu rejected), %lu right-hand side and %lu Jacobian evaluations, "
		        "%lu events%s, %.6f s\n",
		        name, fixed ? " (fixed steps)" : "", steps, rejected, r.nrhs, r.njac, r.nevents, cand,
		        o->run_seconds);
	}
	if (o->stats && au.n) { /* the switches, alternately to the implicit method and back */
		fprintf(err, "stats: auto: %lu switch%s:", au.n, au.n > 1 ? "es" : "");
		for (unsigned long i = 0; i < au.n && i < AUTO_SHOWN; i++)
			fprintf(err, "%s at t=%.6g to %s", i ? "," : "", au.at[i], i % 2 ? csf_ode_method(ode) : AUTO_STIFF);
		fprintf(err, "%s\n", au.n > AUTO_SHOWN ? ", ..." : "");
	}
	if (o->stats && r.g && gd.checks) {
		char rb[64] = "", hb[160] = "";
		if (gd.have_ratio && gd.ratio > 0) {
			char x[32];
			fmt_ratio(x, gd.ratio);
			snprintf(rb, sizeof rb, ", stiffness ratio %s%s", gd.ratio_exact ? "" : "about ", x);
		}
		if (fixed && gd.hrho > 0)
			snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g against %s's limit %.3g there (largest stable step %.3g s)",
			         gd.h, gd.h * gd.rho_max, csf_ode_method(ode), gd.hlim_rho, gd.h / gd.hrho);
		else if (fixed)
			snprintf(hb, sizeof hb, "; step %g s: h*rho %.3g, %s not limited there", gd.h, gd.h * gd.rho_max,
			         csf_ode_method(ode));
		fprintf(err,
		        "stats: stability: rho %.3g 1/s (fastest time scale %.3g s, dominant eigenvalues %s)%s%s; %lu looks, "
		        "%lu Jacobian-vector products, %.6f s\n",
		        gd.rho_max, gd.rho_max > 0 ? 1 / gd.rho_max : INFINITY, eig_kind(&gd.at_max), rb, hb, gd.checks,
		        csf_spectrum_products(gd.sp), gd.seconds);
	}
	if (o->stats && r.stopped) {
		char tb[32];
		csf_fmt_double(tb, r.stop_t);
		const csf_src *s = &p->srcs[r.stop_src];
		fprintf(err, "stats: stopped at t=%s by %s:%lu: stop when %s\n", tb, csf_str(p, p->files[s->file]),
		        (unsigned long)s->line, csf_str(p, s->text));
	}
	if (o->stats && r.g && !gd.checks)
		fprintf(err,
		        "stats: stability: not looked at (the run ended after %lu evaluations, before its first look, due "
		        "after %.0f)\n",
		        r.nrhs, gd.next);
	csf_spectrum_free(gd.sp);
	free(gd.y);
	csf_ode_free(ode);
	csf_ode_free(au.m[1]);
	if (r.cs) ((csf_prog *)p)->crun = NULL;
	csf_contacts_free(r.cs);
	free(r.ga);
	free(r.gb);
	free(r.gs);
	free(r.gh);
	free(r.gt);
	free(r.gl);
	free(work);
	free(y);
	free(r.yi);
	free(r.m);
	return finish(out, err, status, werr);
}
