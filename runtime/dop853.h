/*
 * dop853.h - the Dormand-Prince 8(5,3) Runge-Kutta method with its 7th-order
 * continuous extension (Hairer's DOP853) as a GSL odeiv2 step type, so that
 * GSL's evolve, control and driver run it (implemented in dop853.c).
 */
#ifndef CSF_DOP853_H
#define CSF_DOP853_H

#include <gsl/gsl_odeiv2.h>

/* The DOP853 stepper: order 8, embedded 5th- and 3rd-order error estimates combined as in Hairer's DOP853 (yerr behaves like h^8 for small h); uses dydt_in and gives the exact dydt_out (FSAL). */
extern const gsl_odeiv2_step_type *csf_step_dop853;

/* Weights of the error norm: component i of the error is measured against scale[i] + |y_i| (the driver's tolerance scale, as gsl_odeiv2_control_scaled_new's absolute scale with a_y = 1); NULL: 1 + |y_i|. The array must outlive the stepper. Only for a stepper of type csf_step_dop853. */
void csf_dop853_set_scale(gsl_odeiv2_step *s, const double *scale);

/* After an apply of s that succeeded (for evolve: the accepted step, which is the last apply evolve made), from (t0, y0) over h: prepares the 7th-order continuous extension of that step, with the 3 extra evaluations of sys it needs (done once per step; calling it again for the same step costs nothing). Returns GSL_SUCCESS, or the status of a failing evaluation (GSL_EBADFUNC from sys's function).
   (An apply given no dydt_out has not evaluated f at the step's end; the first call then makes that evaluation too. GSL_EFAILED: the last apply failed; GSL_EINVAL: s is not a DOP853 stepper, or sys does not fit it.) */
int csf_dop853_dense_prepare(gsl_odeiv2_step *s, const gsl_odeiv2_system *sys);

/* The continuous extension of the last step at t0 + theta h, 0 <= theta <= 1 (theta = 1 gives the step's result y1 exactly, theta = 0 gives y0 exactly), into y (dim values). Only after csf_dop853_dense_prepare. */
void csf_dop853_dense_eval(const gsl_odeiv2_step *s, double theta, double *y);

/* t0 and h of the last successful apply. */
void csf_dop853_last_step(const gsl_odeiv2_step *s, double *t0, double *h);

#endif
