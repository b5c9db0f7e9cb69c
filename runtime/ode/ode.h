/*
 * ode.h - the runtime's only window on GSL's odeiv2 (implemented in ode.c).
 */
#ifndef CSF_ODE_H
#define CSF_ODE_H

#include <stddef.h>
#include <stdint.h>

/*
 * Right-hand side: dydt = f(t, y). Returns 0, or non-zero when dydt is not
 * finite. Inside a trial step that means the step was too long: it is
 * tried again shorter. At an accepted state, or when it persists as the
 * step shrinks to nothing, the integration stops (CSF_ODE_STOPPED).
 */
typedef int (*csf_rhs_fn)(double t, const double *y, double *dydt, void *ctx);

/* Jacobian: dfdy[i*n + j] = df_i/dy_j, dfdt[i] = df_i/dt. Returns 0, or non-zero as f does. */
typedef int (*csf_jac_fn)(double t, const double *y, double *dfdy, double *dfdt, void *ctx);

typedef struct csf_ode csf_ode;

enum { CSF_ODE_OK = 0, CSF_ODE_STOPPED = 1, CSF_ODE_FAILED = 2, CSF_ODE_HALTED = 3 };

/*
 * Called after every step the integrator takes (fixed, or an accepted
 * adaptive step; not the substeps of csf_ode_substep), with the time and
 * state at its end and its length. Returns 0 to go on, non-zero to halt
 * (the step returns CSF_ODE_HALTED).
 */
typedef int (*csf_watch_fn)(void *ctx, double t, const double *y, double h);

/*
 * A new integrator for n state variables with the named method (NULL for the
 * default; with fixed, a method that can take fixed steps), a first step of
 * h0 (at most hmax) and internal steps never longer than hmax (but for a
 * step stretched by at most 1e-4 of its length to end at the time asked
 * for), local error bound tol (relative, and absolute times scale[i] for
 * component i; <= 0 for the default), but the absolute bound atol_each[i]
 * where that is > 0 (atol_each may be NULL), else atol where that is > 0.
 * Returns NULL and writes a reason to err for an unknown method or when
 * memory runs out.
 */
csf_ode *csf_ode_new(const char *method, int fixed, size_t n, double h0, double hmax, double tol, double atol,
                     const double *atol_each, const double *scale, const uint32_t *vpair, csf_rhs_fn f, csf_jac_fn jac, void *ctx, char *err,
                     size_t errlen);

/* Has the named method a row of its own in --compare-methods' table (compare.c)? */
int csf_method_compared(const char *method);

/* Can the named method run a model with contacts (a method with a step of its own: not verlet)? */
int csf_method_contacts(const char *method);

/*
 * Has the named method (NULL: the default) a continuous extension, so that
 * it steps past the output times and computes the rows from it (dop853)?
 */
int csf_method_dense(const char *method);
/* Does the named method (NULL: the default) read the state's position/velocity pairs, csf_ode_new's
   vpair (verlet)? Another may be given NULL. */
int csf_method_pairs(const char *method);
int csf_ode_dense(const csf_ode *o);

/*
 * Chooses the first adaptive step from (t, y), instead of the h0 given to
 * csf_ode_new: Hairer's estimate (Solving ODEs I, II.4) from f at y and at
 * a small Euler step, so that a smooth scene starts with a step of its own
 * size (two evaluations; an Euler step that overflows is halved until it
 * does not). Every adaptive method starts so. 0, or 1 if f failed at
 * (t, y) or on every Euler step down to nothing.
 */
int csf_ode_first_step(csf_ode *o, double t, const double *y);

/*
 * The state at time tc within the last adaptive step of a dense method
 * (clamped to the step), from its continuous extension: the first call for
 * a step costs the method's extra evaluations. 0, or 1 if one failed.
 */
int csf_ode_dense_eval(csf_ode *o, double tc, double *out);

/*
 * The same for the components the rows need (csf_ode_set_rows: ascending
 * indices, an array that outlives o; NULL: all), bit for bit as
 * csf_ode_dense_eval gives them; the other components of out are left as
 * they were. Only these are interpolated, and only these prepared.
 */
int csf_ode_dense_rows(csf_ode *o, double tc, double *out);
void csf_ode_set_rows(csf_ode *o, const uint32_t *rows, size_t n);
/* The components idx[0..n) alone, bit for bit as csf_ode_dense_eval gives them, into out[idx[q]];
   the others of out are left as they were. 0, or 1 if an evaluation failed. */
int csf_ode_dense_at(csf_ode *o, double tc, const uint32_t *idx, size_t n, double *out);

/*
 * Advances (*t, y) to exactly t1 in equal steps of at most h, without error
 * control (rk4 is the classical four-stage method; the other one-step
 * methods take GSL's step without using its error estimate). Returns as
 * csf_ode_step.
 */
int csf_ode_advance_fixed(csf_ode *o, double *t, double t1, double h, double *y, char *err, size_t errlen);

/*
 * One step from (*t, y) towards t1, never past it: an accepted adaptive step
 * (error control, steps no longer than hmax, a step that would end just
 * short of t1 stretched to end at it), or with fixed, one step of h.
 * A trial step on which f fails (a value not finite) is tried again
 * shorter, as one whose error is too large. Returns CSF_ODE_OK;
 * CSF_ODE_STOPPED when f failed at (*t, y), or on every trial down to a
 * step too short to change t (*t is then the step's start);
 * CSF_ODE_FAILED with a reason in err for any other GSL failure.
 */
int csf_ode_step(csf_ode *o, double *t, double t1, int fixed, double h, double *y, char *err, size_t errlen);

/*
 * The state at t + h (0 < h <= the last step) from (t, y), by one step of
 * the method without error control (to locate an event inside a step just
 * taken). The multistep methods, which cannot start a step from anywhere,
 * take one step of rk8pd (msadams) or rk4imp (msbdf) instead.
 * 0, or 1 if f stopped.
 */
int csf_ode_substep(csf_ode *o, double t, const double *y, double h, double *out);

/* Forgets the history of the integration: the state jumped (an event). */
void csf_ode_restart(csf_ode *o);

/*
 * o's error scales become at least those from has reached (each component's
 * largest size so far, within its bounds: ode.c): for a method that takes
 * over from another over the same state (--method auto).
 */
void csf_ode_take_scale(csf_ode *o, const csf_ode *from);

/* Steps taken and rejected so far. */
void csf_ode_stats(const csf_ode *o, unsigned long *steps, unsigned long *rejected);

/* The default local error bound of every method but dop853, and dop853's (csf_method_tol). */
#define CSF_DEFAULT_TOL 1e-10
/*
 * The smallest relative tolerance accepted (--tol), about 4.5 DBL_EPSILON:
 * on the harmonic oscillator of tests/methods_tol.csf no method gets closer
 * to the exact answer below 1e-14 (rounding leaves 1e-13), and below 1e-15
 * the error estimates measure rounding: rk4 rejects 833 steps at 1e-16 and
 * runs into the step limit at 1e-17, rk8pd rejects 7752 at 1e-18 and
 * 848972 at 1e-20, bsimp does not end at 1e-18.
 */
#define CSF_MIN_TOL 1e-15
double csf_method_tol(const char *method);

/*
 * The fixed step to take for outputs every by: --step (step > 0, at most by),
 * else by, except for verlet, whose step is derived from the tolerance.
 */
double csf_ode_fixed_step(const csf_ode *o, double by, double step);

/* Does the method take only fixed steps (verlet)? */
int csf_ode_fixed_only(const csf_ode *o);

/* Is the method explicit (no Jacobian)? */
int csf_ode_explicit(const csf_ode *o);
/*
 * The state's vectors: vec[i] is 1 + the first component of the vector
 * component i belongs to, or 0 for a scalar (NULL: every component is a
 * scalar). A component's absolute error scale then follows the size of its
 * vector, not its own. The array must outlive o.
 */
void csf_ode_vectors(csf_ode *o, const uint32_t *vec);
/* Does it keep a history of past steps (a multistep method), which a restart throws away? */
int csf_ode_history(const csf_ode *o);

/* Calls fn after every step from now on (NULL: none). */
void csf_ode_watch(csf_ode *o, csf_watch_fn fn, void *ctx);

/*
 * Fixed steps are at most h from now on, the rest of an interval that
 * csf_ode_advance_fixed is stepping included (0: no cap).
 */
void csf_ode_cap_step(csf_ode *o, double h);

/*
 * The largest stable step of the method (fixed: as csf_ode_advance_fixed
 * takes it) for a mode of eigenvalue re + i im of df/dy in a run of span
 * seconds: the largest h such that, for every step up to h, the method
 * grows the mode by at most 1 % more over the run's span/h steps than
 * the exact solution does (one step's factor: the stability polynomial
 * R(h lambda) against e^max(0, Re h lambda); verlet's, on x'' = lambda^2 x).
 * INFINITY when no step is unstable (implicit methods, a mode that only
 * grows), NaN when unknown (msadams, whose order varies).
 */
double csf_ode_stable_step(csf_ode *o, int fixed, double re, double im, double span);

/*
 * The step the error control proposes for the next adaptive step (after a
 * step cut short to end at an output time, the one it would have taken).
 */
double csf_ode_next_step(const csf_ode *o);

/* The method's name. */
const char *csf_ode_method(const csf_ode *o);

/* The state component whose error, against its bound, was the largest in the last step the error
   control sized (what holds the steps short), or -1 before any (or with fixed steps or a method
   whose steps this control does not size). */
long csf_ode_limit(const csf_ode *o);

/* The relative tolerance (--tol). */
double csf_ode_tol(const csf_ode *o);

/* The absolute tolerance of component i now (tol times its scale; --atol's or the scene's atol when set). */
double csf_ode_abs_tol(const csf_ode *o, size_t i);

/*
 * Raises the absolute tolerance of component i to at least atol (at most
 * tol times its unit scale; never one the scene or --atol fixed). Returns
 * 1 when it raised it, else 0.
 */
int csf_ode_raise_abs_tol(csf_ode *o, size_t i, double atol);

/*
 * Saves or restores under tag what o keeps from one step to the next (a
 * checkpoint, csf_keep: its step counts, error scales, next step, and a
 * dense method's last step): 0, or -1. The multistep methods' history and
 * bsimp's own state are GSL's and are not kept (csf_ode_keeps).
 */
struct csf_keeper;
int csf_ode_keep(csf_ode *o, struct csf_keeper *k, const char *tag);

void csf_ode_free(csf_ode *o);

#endif
