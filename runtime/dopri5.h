/*
 * dopri5.h - the Dormand-Prince 5(4) Runge-Kutta method with its free
 * 4th-order continuous extension (Hairer's DOPRI5, SciPy's RK45) as a GSL
 * odeiv2 step type, so that GSL's evolve, control and driver run it
 * (implemented in dopri5.c).
 */
#ifndef CSF_DOPRI5_H
#define CSF_DOPRI5_H

#include <gsl/gsl_odeiv2.h>

/* The DOPRI5 stepper: order 5 (as GSL's rkf45 reports it), yerr the 5th- minus the embedded 4th-order solution (behaves like h^5 for small h); takes no dydt_in and gives the exact dydt_out (FSAL). */
extern const gsl_odeiv2_step_type *csf_step_dopri5;

/* After an apply of s that succeeded (for evolve: the accepted step, which is the last apply evolve made), from (t0, y0) over h: prepares the 4th-order continuous extension of that step. It is built from the step's own 7 stages, so it makes no evaluation of sys (sys may be NULL; if given, its dimension must be s's). Returns GSL_SUCCESS; GSL_EFAILED: the last apply failed (or there was none); GSL_EINVAL: s is not a DOPRI5 stepper, or sys does not fit it. */
int csf_dopri5_dense_prepare(gsl_odeiv2_step *s, const gsl_odeiv2_system *sys);

/* The continuous extension of the last step at t0 + theta h, 0 <= theta <= 1 (theta = 1 gives the step's result y1 exactly, theta = 0 gives y0 exactly), into y (dim values). Only after csf_dopri5_dense_prepare. */
void csf_dopri5_dense_eval(const gsl_odeiv2_step *s, double theta, double *y);

/* t0 and h of the last successful apply. */
void csf_dopri5_last_step(const gsl_odeiv2_step *s, double *t0, double *h);

#endif
