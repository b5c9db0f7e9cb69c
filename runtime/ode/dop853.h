/*
 * dop853.h - the Dormand-Prince 8(5,3) Runge-Kutta method with its 7th-order
 * continuous extension (Hairer's DOP853) as a GSL odeiv2 step type, so that
 * GSL's evolve, control and driver run it (implemented in dop853.c).
 */
#ifndef CSF_DOP853_H
#define CSF_DOP853_H

#include <gsl/gsl_odeiv2.h>

/* The DOP853 stepper: order 8, embedded 5th- and 3rd-order error estimates combined as in Hairer's DOP853 (yerr behaves like h^8 for small h); takes no dydt_in and gives the exact dydt_out (first same as last). */
extern const gsl_odeiv2_step_type *csf_step_dop853;

/*
 * Its error norm's scale (csf_erk_set_scale), continuous extension and last
 * step are those of erk.h: csf_erk_dense_prepare makes the 3 evaluations of
 * its extra stages once a step.
 */

#endif
