/*
 * csf_api.h - libcsf's ABI: CSF for other languages (Python's csf package
 * loads it with ctypes; csf-python(7)). A small, stable C interface of opaque
 * handles and plain types only (ints, size_t, doubles, strings, arrays the
 * caller allocates), so that a binding mirrors no struct. Every exported
 * symbol carries the version node CSF_1 (runtime/api/csf_api.map); a
 * change that breaks a caller gets a new node and a new CSF_API_VERSION,
 * additions keep both.
 *
 * A model (csf_api_model) is a verified program: csf_api_load decodes
 * the bytes of a .csfb file and checks them as csfvm does (hostile bytes
 * are refused with a reason, never run). It lists its output columns and
 * its parameters as csfvm's CSV header and `csfc --explain` name them.
 * A run (csf_api_run) holds one run's settings: parameters set as
 * `csfvm -D NAME=VALUE` sets them (the same checks and messages), and
 * csfvm's options (--method, --tol, ...). csf_api_run_exec runs it: the
 * rows go into an array the caller allocates (csf_api_run_rows tells how
 * many rows at most), each row t and then the columns, the doubles the CSV
 * prints; the diagnostics csfvm would write on stderr are kept as text.
 *
 * Messages are csfvm's without its "csfvm: " prefix. Statuses are csfvm's
 * exit statuses: 0 done, 1 the model failed (an assertion, a non-finite
 * value, an integrator that gave up), 2 bad options or out of memory, 130
 * interrupted (csf_api_interrupt, or SIGINT with CSF_API_CATCH_SIGINT).
 *
 * Threads: models are read-only once loaded; one run handle belongs to
 * one thread at a time, and runs of different handles may go on at once.
 * The interrupt is process-wide: it ends every run in progress. Nothing is
 * kept between calls but what the handles own; everything is freed with
 * them. A run into an array of 4 MiB or more, on a machine of two CPUs or
 * more, has a helper thread of its own (every signal blocked) for as long
 * as csf_api_run_exec lasts (see there).
 */
#ifndef CSF_API_H
#define CSF_API_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CSF_API_VERSION 1

#if defined(__GNUC__)
#define CSF_API __attribute__((visibility("default")))
#else
#define CSF_API
#endif

typedef struct csf_api_model csf_api_model;
typedef struct csf_api_run csf_api_run;

/* CSF_API_VERSION of the library (a binding checks it before anything else). */
CSF_API int csf_api_version(void);
/* The runtime's version, "0.1.0" (csfvm --version). */
CSF_API const char *csf_api_runtime_version(void);

/* ---- models ---- */

/*
 * The program in the len bytes at bytes (a .csfb file), decoded and
 * verified into memory of its own (bytes may be freed). NULL with the
 * reason in err (errlen bytes, NUL-terminated) when they are not a valid
 * program or memory runs out.
 */
CSF_API csf_api_model *csf_api_load(const void *bytes, size_t len, char *err, size_t errlen);
/* Frees a model (NULL: nothing). Its runs must be freed first. */
CSF_API void csf_api_free(csf_api_model *m);

/* The run's end time (till) and output interval (by), in seconds. */
CSF_API double csf_api_till(const csf_api_model *m);
CSF_API double csf_api_by(const csf_api_model *m);

/*
 * The output columns (t not counted), i = 0 .. ncols - 1, in the order of
 * the CSV header: the name (`ball.pos.x`), the unit the header gives in
 * brackets (`m`; "" when it gives none), and the vector grouping: 0, 1 or
 * 2 when columns i - c .. i - c + 2 are the x, y and z of one vector
 * (`ball.pos.x`, `.y`, `.z` in a row, one unit), else -1. The strings live
 * as long as the model.
 */
CSF_API size_t csf_api_ncols(const csf_api_model *m);
CSF_API const char *csf_api_col_name(const csf_api_model *m, size_t i);
CSF_API const char *csf_api_col_unit(const csf_api_model *m, size_t i);
CSF_API int csf_api_col_component(const csf_api_model *m, size_t i);

/*
 * The parameters, i = 0 .. nparams - 1, as `csfc --explain` lists them: the
 * globals, then every object property the run keeps. The name (`g`,
 * `ball.v`), the unit in the model's unit system ("" when dimensionless),
 * why -D cannot set it ("" when it can), whether its dimension is known (0:
 * a bare number whose dimension nothing fixed), and its initial value:
 * csf_api_param_value writes 1 or 3 values (a vector) into v and returns
 * how many.
 */
CSF_API size_t csf_api_nparams(const csf_api_model *m);
CSF_API const char *csf_api_param_name(const csf_api_model *m, size_t i);
CSF_API const char *csf_api_param_unit(const csf_api_model *m, size_t i);
CSF_API const char *csf_api_param_why(const csf_api_model *m, size_t i);
CSF_API int csf_api_param_known(const csf_api_model *m, size_t i);
CSF_API int csf_api_param_value(const csf_api_model *m, size_t i, double v[3]);

/*
 * Reads assign, `NAME=VALUE` as -D takes it, without setting anything: the
 * value in the model's units into v. Returns how many values (1 or 3), or
 * -1 with -D's message in err.
 */
CSF_API int csf_api_param_parse(const csf_api_model *m, const char *assign, double v[3], char *err, size_t errlen);

/* ---- runs ---- */

/* A run of m with the model's own values and csfvm's default options; NULL when memory runs out. */
CSF_API csf_api_run *csf_api_run_new(const csf_api_model *m);
CSF_API void csf_api_run_free(csf_api_run *r);

/*
 * Sets a parameter for the run's start, as `-D NAME=VALUE` (assign):
 * `ball.v=(3, 0, 4) m/s`, `theta=30 deg`, `ball.pos.z=2`. Returns 0, or
 * -1 with -D's message (csf_api_run_error). Later settings of a value win.
 */
CSF_API int csf_api_run_set(csf_api_run *r, const char *assign);

/*
 * csfvm's options for the run, argc strings as on its command line:
 * --method NAME, --tol EPS, --atol A, --hmax H, --fixed, --step H,
 * --every K, --stats (its lines in the diagnostics), -D NAME=VALUE. Each
 * call replaces the options of the one before (not the parameters). The
 * options of sweeps, --compare-methods, -o and --dump (the rows are the
 * caller's array), --help, --version, file names and options this csfvm
 * does not know are errors. Returns 0, or -1 with the
 * message (csf_api_run_error).
 */
CSF_API int csf_api_run_options(csf_api_run *r, int argc, const char *const *argv);

/* The message of the last csf_api_run_set or csf_api_run_options that failed ("" if none). */
CSF_API const char *csf_api_run_error(const csf_api_run *r);

/* The most rows a run writes: kmax + 1 for t = k*by up to till, fewer with --every. */
CSF_API size_t csf_api_run_rows(const csf_api_run *r);

/* csf_api_run_exec's flags: while it runs, SIGINT ends the run after its current row (status 130) and
   is not passed on; the handler that was there is put back afterwards. For the process's main thread. */
#define CSF_API_CATCH_SIGINT 1u

/*
 * Runs the model: row k's values into out[k * (ncols + 1) ...], t first
 * and then the columns, for at most maxrows rows (out NULL: the rows are
 * counted, not kept; more rows than maxrows: status 2). Returns the
 * status (above). After it, csf_api_run_nrows is the number of rows
 * written (those before a failure, or an interruption), the diagnostics
 * are csfvm's stderr of the same run, and the --stats figures are set.
 * A run handle may be run again (the same settings, a new run).
 *
 * When the rows the run can write fill 4 MiB or more of out, a helper
 * thread makes the pages that hold them present while the run computes
 * (madvise MADV_POPULATE_WRITE, Linux 5.14 or later; nothing where the
 * kernel refuses it, or with one CPU): memory fresh from the kernel is
 * then not faulted in and zeroed by the run's own thread, row after row.
 * It leaves their contents as they are, and is stopped and joined before
 * the call returns; those pages count in the process's memory even when
 * the run ends early.
 */
CSF_API int csf_api_run_exec(csf_api_run *r, double *out, size_t maxrows, unsigned flags);
CSF_API size_t csf_api_run_nrows(const csf_api_run *r);
CSF_API const char *csf_api_run_diagnostics(const csf_api_run *r);
/* --stats: integrator steps, right-hand side evaluations, the run's wall time in seconds. */
CSF_API unsigned long csf_api_run_steps(const csf_api_run *r);
CSF_API unsigned long csf_api_run_rhs(const csf_api_run *r);
CSF_API double csf_api_run_seconds(const csf_api_run *r);

/*
 * A progress callback: fn(ctx, t, rows) after a row when interval seconds
 * (of wall time) have passed since the run started or fn was last called
 * (interval 0: after every row); a nonzero return ends the run after that row,
 * as an interrupt does (status 130). fn NULL: none.
 */
typedef int (*csf_api_progress_fn)(void *ctx, double t, size_t rows);
CSF_API void csf_api_run_progress(csf_api_run *r, csf_api_progress_fn fn, void *ctx, double interval);

/*
 * Ends every run in progress after its current row (status 130), as SIGINT
 * ends csfvm's; async-signal-safe (a signal handler or another thread may
 * call it). A run that starts later is not affected.
 */
CSF_API void csf_api_interrupt(void);

#ifdef __cplusplus
}
#endif

#endif
