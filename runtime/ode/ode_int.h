/*
 * ode_int.h - what the files of runtime/ode/ share behind ode.h: the method
 * table's entries (ode.c), the integrator's state, the fixed steppers
 * (fixed.c), the error control and live scale (control.c) and the stability
 * regions (stable.c).
 */
#ifndef CSF_ODE_INT_H
#define CSF_ODE_INT_H

#include <complex.h>
#include <stdint.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "ode.h"

/* The most coefficients of a stability polynomial: more than the most stages (rk8pd's 13) plus one. */
enum { NSTAB = 16 };

/*
 * One fixed step of h from (t, y), without error control: CSF_ODE_OK,
 * CSF_ODE_STOPPED when f failed, CSF_ODE_FAILED with a reason in err.
 */
typedef int fixed_fn(csf_ode *o, double t, double h, double *y, char *err, size_t errlen);

/* A continuous extension (erk.c's): its error norm's scale, and the state at tc within the last step. */
struct dense {
	void (*set_scale)(gsl_odeiv2_step *s, const double *scale);
	void (*set_rows)(gsl_odeiv2_step *s, const uint32_t *rows, size_t n);
	int (*eval)(csf_ode *o, double tc, double *out, int some);
	int (*eval_at)(csf_ode *o, double tc, const uint32_t *idx, size_t n, double *out);
};

/*
 * How csf_ode_stable_step finds the method's stable steps: the stability
 * polynomial of adaptive and of fixed steps, put in o->stab (NULL: none
 * needed), and how much faster than the exact solution one step grows a
 * mode; without excess, the answer for every mode.
 */
struct stability {
	int (*poly)(csf_ode *o);
	int (*poly_fixed)(csf_ode *o);
	double (*excess)(const csf_ode *o, double complex z);
	double every;
};

/*
 * A method: what differs from one to the next, as entries (REBOUND's
 * reb_integrator is the model). The generic code dispatches through them.
 */
struct method {
	const char *name;
	const gsl_odeiv2_step_type *const *type; /* the adaptive stepper (NULL: fixed steps only) */
	/* what csf_ode_new sets up for it (a GSL driver and control, or verlet's pairs) */
	int (*setup)(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
	fixed_fn *step;                          /* one fixed step (NULL: none, a multistep method) */
	int (*substep)(csf_ode *o, double t, double h, double *out); /* csf_ode_substep's step, 0 or 1 */
	const gsl_odeiv2_step_type *const *sub;  /* the one-step stepper of ode_gsl_substep */
	double (*fixed_h)(const csf_ode *o, double by); /* the fixed step without --step (NULL: by) */
	const struct dense *dense;               /* a continuous extension: steps past the output times (or NULL) */
	const struct stability *stab;
	int jacobian;  /* the stepper uses the Jacobian */
	int history;   /* a multistep method: a restart loses the history its order rests on */
	int pairs;     /* setup reads the state's position/velocity pairs (vpair: verlet) */
	int skip_compare; /* left out of --compare-methods' table (rk1imp, rk2imp: the low-order implicit
	                     methods, which only spend its budget; verlet, fixed steps, has its own row) */
	double tol;    /* the default local error bound (the work-precision benchmark: the cheapest that keeps
	                  every problem with an exact answer within 1e-6) */
};

struct csf_ode {
	gsl_odeiv2_system sys;
	gsl_odeiv2_driver *drv;
	const struct method *m;
	size_t n;
	double tol;
	double *k;                 /* fixed steps: 5 work vectors of n */
	gsl_odeiv2_step *sub;      /* events: a second stepper of the same method, for substeps */
	double *yerr;
	unsigned long fixed_steps;
	unsigned long past_steps, past_rejected; /* GSL's counts before the last restart */
	const double *scale;       /* each component's absolute tolerance, in units of tol (o->live) */
	const double *base;        /* the program's scale: one unit, or less (csf_ode_new's scale) */
	double *live;              /* the scale now: as the component has grown, within base (owned) */
	unsigned char *fixed_atol; /* the scene's atol or --atol holds this component's scale fixed (owned) */
	int live_set;              /* live has been set from a state (ode_live_start) */
	size_t limit;              /* the component whose error limited the last step the control sized (n: none yet) */
	const uint32_t *vec;       /* per component: 1 + the first component of its vector, or 0 (csf_ode_vectors) */
	const uint32_t *vpair;     /* verlet: 1 + velocity index of each position component */
	double *acc;               /* verlet: the derivative at the current point */
	double acc_t;
	int acc_ok;
	csf_rhs_fn f;
	csf_jac_fn jac;
	void *ctx;
	csf_watch_fn watch;        /* called after every step (csf_ode_watch) */
	void *watch_ctx;
	double hcap;               /* fixed steps: at most this long from now on (csf_ode_cap_step; 0: none) */
	double stab[NSTAB];        /* the stability polynomial's coefficients (stability_poly) */
	int nstab, stab_fixed;     /* how many (0: not yet computed), and for fixed steps or not */
	double complex last_u;     /* the last csf_ode_stable_step: its direction, allowance and answer */
	double last_allow, last_s;
};

/*
 * A state or derivative that is not finite (the model's f failed). Inside a
 * trial step it means the step was too long: GSL's evolve retries a step
 * shorter (halved) for any failure of the stepper but GSL_EBADFUNC and
 * GSL_EFAULT, and every stepper passes this code on, restoring its state
 * (the multistep methods' failure handlers). It comes out of evolve only
 * when it persists as the step shrinks to nothing, or at the step's start:
 * an accepted state whose derivative is not finite. GSL's odeiv2 never
 * returns GSL_ERANGE itself.
 */
enum { TOO_LONG = GSL_ERANGE };

/* fixed.c: the fixed steppers, the steppers of csf_ode_substep, verlet's setup and step size */
int csf_ode_verlet_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
fixed_fn csf_ode_gsl_fixed, csf_ode_rk4_fixed, csf_ode_verlet_fixed;
int csf_ode_gsl_substep(csf_ode *o, double t, double h, double *out);
int csf_ode_rk4_substep(csf_ode *o, double t, double h, double *out);
int csf_ode_verlet_substep(csf_ode *o, double t, double h, double *out);
double csf_ode_verlet_h(const csf_ode *o, double by);

/* control.c: GSL's driver with CSF's error control; the live scale */
int csf_ode_gsl_setup(csf_ode *o, double h0, double hmax, const uint32_t *vpair, char *err, size_t errlen);
void csf_ode_live_init(csf_ode *o);
void csf_ode_live_start(csf_ode *o, const double *y);
void csf_ode_live_grow(csf_ode *o, const double *y);

/* stable.c: how each kind of method finds its stable steps (struct stability) */
extern const struct stability csf_ode_stab_measured, csf_ode_stab_rk4, csf_ode_stab_verlet, csf_ode_stab_implicit, csf_ode_stab_unknown;

#endif
