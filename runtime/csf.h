/*
 * csf.h - the public interface of libcsfrt, the CSF runtime: what a
 * program that csfc --emit-c generated, and a program that embeds CSF,
 * may use. Everything else of the runtime is internal (csf_int.h).
 *
 * A compiled model is a csf_prog, opaque here: an initial memory image, the
 * code sections, and the tables that name memory slots and source
 * positions for output and diagnostics. csf_load reads one from the bytes
 * of a .csfb file (csf(5)) and verifies it; a program that fails the
 * verifier is never returned, so every function below may trust it.
 *
 * A model is run by csf_run (or csf_run_sink), which integrates it and
 * calls back into an execution function for its code sections:
 * csf_vm_exec interprets them; a generated executable passes its own
 * compiled function instead. Both see the same program and the same
 * driver, so they write the same bytes on stdout and stderr. csf_main is
 * the whole command line of csfvm and of a generated executable.
 *
 * Promises: no function here exits the process or writes outside the
 * FILEs it is given; each returns an exit status (0 done, 1 the model
 * failed: an assertion, a non-finite value, an integrator that gave up;
 * 2 bad options, out of memory or an output error) or says how it fails.
 * The library has no global state but the signal flag csf_main installs.
 */
#ifndef CSF_H
#define CSF_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "csf_ops.h"

#define CSF_VERSION_STRING "0.1.0"

/* A loaded, verified program (csf_load; the runtime's own layout: csf_int.h). */
typedef struct csf_prog csf_prog;
/* The run's state the code reaches (csf_exec_fn). */
typedef struct csf_exec_ctx csf_exec_ctx;
/* Initial values set over a program's (-D, a sweep's variant: csf_opts.init). */
typedef struct csf_overlay csf_overlay;

/*
 * Code sections: RHS computes the state derivatives; OUT what the watch list
 * and the assertions need; JAC the derivatives' tangents (forward-mode
 * differentiation of RHS, for the exact Jacobian; empty when the model has
 * no state).
 */
enum { CSF_SEC_RHS = 0, CSF_SEC_OUT = 1, CSF_SEC_JAC = 2, CSF_SEC_EVT = 3, CSF_NSEC = 4 };

/*
 * Runs code section sec of p on memory m, with the state read from y and
 * the derivatives written to dydt (ny values each) rather than m's slots
 * [ystart, ystart + ny) and [dstart, dstart + ny); y and dydt may be those
 * slots themselves. Every slot the runtime reads after a section (t, the
 * columns, the events' values, the contact bodies', the tangents of the
 * state and of the derivatives) is in m; the values only a section uses
 * need not be: csf_vm_exec stores every value it computes, a generated
 * program keeps the rest in registers (re-run a section on csf_vm_exec to
 * see them all, as the driver does to name a non-finite value). x is the
 * run's state that the code reaches (csf_exec_ctx; NULL: none). Returns
 * -1, or the index of the first assertion that failed (execution stops
 * there).
 */
typedef struct csf_exec_ctx csf_exec_ctx;
typedef int (*csf_exec_fn)(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, const double *y, double *dydt);

/* The interpreter: a csf_exec_fn for verified programs (it copies y into m and the derivatives out). */
int csf_vm_exec(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, const double *y, double *dydt);

/*
 * Threads (--threads N): a loop of level 1 whose iterations are
 * independent (runtime/prog/parloop.h) as a function of its own, which
 * runs the iterations lo to hi - 1 in ascending order; csf_par_for runs
 * iterations 0 to count - 1 of it, split over x's threads when it has
 * them and the loop has at least as much work (instructions) as pays for
 * them, else at once. Every iteration computes what it would alone: the
 * result is the same, bit for bit, for every number of threads.
 */
typedef struct csf_pool csf_pool;
typedef int csf_par_fn(const csf_prog *p, const csf_exec_ctx *x, double *m, const double *y, double *dydt, uint32_t lo,
                       uint32_t hi);
void csf_par_for(const csf_prog *p, const csf_exec_ctx *x, uint64_t work, uint32_t count, csf_par_fn *fn, double *m,
                 const double *y, double *dydt);

/*
 * The contact routine (the CONTACT instruction; runtime/contact/force.c), on the
 * candidate pairs of x->contacts (nothing when x or they are NULL): for every pair in
 * contact, the normal force that keeps the relative normal acceleration
 * zero and the friction force of its mode, added to both bodies' a, FN and
 * Ff; and each candidate's two guards (an event when one becomes negative).
 */
void csf_contact_apply(const csf_prog *p, const csf_exec_ctx *x, double *m);

/*
 * The constraints (the CONSTRAIN instruction; runtime/constraint/): the
 * forces that keep the second derivative of every active constraint zero
 * (ideal: along its gradient), solved together, added to each body's a and
 * written to its FC (nothing when x or x->cons is NULL).
 */
void csf_constraint_apply(const csf_prog *p, const csf_exec_ctx *x, double *m);

/*
 * The program in the len bytes of a .csfb file (buf), decoded and verified,
 * in memory of its own (buf may be freed); NULL with the reason in err when
 * the bytes are not a valid program or memory runs out. csf_unload frees it.
 */
csf_prog *csf_load(const unsigned char *buf, size_t len, char *err, size_t errlen);
void csf_unload(csf_prog *p);

enum { CSF_PROGRESS_AUTO = 0, CSF_PROGRESS_ON = 1, CSF_PROGRESS_OFF = 2 };

/* Run-time options, parsed identically by csfvm and generated executables. */
typedef struct csf_opts {
	const char *method; /* ODE stepper name, NULL for the default */
	double tol;         /* local error bound, relative, <= 0 for the default (else CSF_MIN_TOL <= tol < 1) */
	double atol;        /* --atol A: the absolute error bound of every state component the scene gives
	                       none (csf_prog.yatol), in the model's units (<= 0: tol times each
	                       component's scale, csf_prog.yscale) */
	int fixed;          /* --fixed: no error control, constant internal steps */
	double step;        /* --step H: the fixed step (<= 0: by) */
	double hmax;        /* --hmax H: the longest internal step (<= 0: no cap but the run's length; by for
	                       the methods that step to each output time) */
	int stats;          /* --stats: a summary on stderr at the end */
	int rows_at_events; /* --rows-at-events: a row before and after each located event, and the column event */
	int progress;       /* CSF_PROGRESS_AUTO (on a terminal), _ON (--progress), _OFF (--no-progress) */
	int compare;        /* --compare-methods */
	unsigned long every; /* --every K: write the rows k = 0, K, 2K, ... and the last (0 or 1: every row) */
	unsigned long max_rhs; /* stop (exit 1) past this many right-hand side evaluations (0: no limit;
	                          --compare-methods' budget for each of its runs) */
	/* parameters and sweeps (param.c, sweep.c); the strings are argv's, the arrays malloc'd (csf_opts_free) */
	const char **defs;  /* -D NAME=VALUE, in order */
	int ndefs;
	const char **sweeps; /* --sweep NAME=FROM:TO:COUNT [UNIT], in order (the last varies fastest) */
	int nsweeps;
	const char *sweep_file; /* --sweep-file FILE.csv */
	const char *summary;    /* --sweep-summary EXPR */
	const char *out_dir;    /* --out-dir DIR */
	int sweep_binary;       /* --sweep-binary: a sweep's rows as doubles after the header line */
	const char *output;     /* -o FILE: the rows as HDF5 (FILE.h5, FILE.hdf5) or CSV (any other name; -: stdout) */
	const char *dump;       /* --dump FILE.h5: that file's rows as CSV, and no run */
	long jobs;              /* -j N: worker processes of a sweep (0: the number of online CPUs) */
	int threads;            /* --threads N: threads that share a shape's loops (0 or 1: one) */
	const csf_overlay *init; /* initial values over p->mem0 (-D; a sweep's variant), NULL: none; not
	                            csf_parse_opts', and not freed by csf_opts_free */
	/* long runs (run.c, record.c, main.c) */
	const char *checkpoint; /* --checkpoint FILE: the run's state every checkpoint_every seconds */
	double checkpoint_every; /* --checkpoint-every S (wall time; 0: at every row), when checkpoint_every_set */
	int checkpoint_every_set;
	const char *resume;     /* --resume FILE: go on from that checkpoint */
	const char *record;     /* --record FILE.json: the run record */
	int estimate;           /* --estimate-error: a second run at a tolerance 100 times tighter */
	double accuracy;        /* --accuracy A: tighten the tolerance until the estimate is below A (0: none) */
	unsigned long long hash; /* the bytecode's FNV-1a hash (csf_main; 0: unknown) */
	/* filled in by csf_run: */
	unsigned long run_steps, run_rhs;
	double run_seconds;
	unsigned long run_rejected, run_jac, run_events, run_rows;
	/* filled in by --estimate-error (main.c): the largest difference, its column and time, the tolerance */
	double err_estimate, err_t, err_tol;
	const char *err_column;
} csf_opts;

/*
 * Is argv[*i] option name with a value, as "name VALUE" (the next
 * argument; *i moves past it) or "name=VALUE"? The value into *val.
 * (csfvm's options and csfc's alike.)
 */
int csf_opt_value(int argc, char **argv, int *i, const char *name, const char **val);

/*
 * Parses run-time options from argv[first..argc); stores the remaining
 * positional arguments' indices in pos[] (at most npos) and their count in
 * *npos_out. Returns 0, 1 if --help was printed, or 2 after printing a
 * usage error to stderr.
 */
int csf_parse_opts(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                   const char *usage);

/* Frees the arrays csf_parse_opts allocated in o. */
void csf_opts_free(csf_opts *o);

/*
 * Simulates p: integrates the state from t = 0 to till, evaluating OUT at
 * t_k = k*by and writing one CSV row each to out (diagnostics to err).
 * Fills o->run_steps, run_rhs and run_seconds.
 * Returns the process exit status: 0 done, 1 the model failed (assertion,
 * non-finite value, integrator failure), 2 bad options or an output error.
 */
int csf_run(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, FILE *err);

/*
 * A row sink (csf_run_sink): row receives each row's values as its CSV row
 * shows them, v[0] = t and then the p->ncols columns (n = ncols + 1). It
 * returns 0, or -1 to end the run after that row as a failed write does
 * (errno set). place, when not NULL, says where the row's n values are to
 * be written (the run writes them there, then calls row with that
 * pointer), so that they go straight into the embedder's array; NULL from
 * it ends the run as a failed write (ENOBUFS).
 */
typedef struct csf_sink {
	int (*row)(void *ctx, const double *v, size_t n);
	void *ctx;
	double *(*place)(void *ctx);
} csf_sink;

/*
 * csf_run that also gives each row's values to sink (when not NULL); with
 * out NULL, no CSV is written and the rows go to the sink alone. The same
 * run, messages and exit statuses as csf_run.
 */
int csf_run_sink(const csf_prog *p, csf_exec_fn exec, csf_opts *o, FILE *out, const csf_sink *sink, FILE *err);

/*
 * The whole command line of csfvm (image NULL: the bytecode file is the
 * argument) and of a generated executable (image: its embedded bytecode,
 * exec: its compiled code). Returns the process exit status.
 */
int csf_main(int argc, char **argv, const unsigned char *image, size_t image_len, csf_exec_fn exec);

/* Formats x so that it reads back to the same double (shortest of %.15g..%.17g). */
void csf_fmt_double(char buf[32], double x);

#endif
