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

/* Its continuous extension and last step are those of erk.h; the extension needs no evaluation. */

#endif
