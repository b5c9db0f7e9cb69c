/*
 * constraint.h - the constraints' run-time state and what the run does
 * with it (runtime/constraint/constraint.c; the force stage, the
 * CONSTRAIN instruction, is csf_constraint_apply in csf.h).
 */
#ifndef CSF_CONSTRAINT_H
#define CSF_CONSTRAINT_H

#include "csf_int.h"

/* What a solve is for: the forces (CONSTRAIN), or a correction of the positions or of the velocities. */
enum { CSF_CONS_FORCE, CSF_CONS_POS, CSF_CONS_VEL };

/* The work arrays and modes for p's constraints (every one taut), or NULL when memory runs out. */
csf_cons *csf_cons_new(const csf_prog *p);
void csf_cons_free(csf_cons *cs);

/*
 * Moves the positions (what CSF_CONS_POS) or velocities (CSF_CONS_VEL) of
 * state y onto the constraints, by the mass-weighted projection of one
 * Newton step, from g (or gd) and J that the RHS section left in m at y.
 */
void csf_cons_correct(csf_cons *cs, const double *m, double *y, int what);

/*
 * The largest residual of the taut constraints in m (g, or gd), relative
 * to the sizes of its terms; *worst gets its constraint and *abs_res its
 * value (either may be NULL). 0 when every one holds exactly.
 */
double csf_cons_residual(const csf_cons *cs, const double *m, int what, uint32_t *worst, double *abs_res);

/* Did a solve find constraints that contradict each other? *k gets one of them, *res how much (relative). */
int csf_cons_failed(const csf_cons *cs, uint32_t *k, double *res);

/* A one-sided constraint's mode: taut (a row of the solve) or slack (no force). */
void csf_cons_set_mode(csf_cons *cs, uint32_t k, int taut);
int csf_cons_taut(const csf_cons *cs, uint32_t k);
/*
 * The guards of the constraints, one each, from the last evaluation in m
 * (>= 0 while its mode holds): an equality's is 1; a slack one-sided
 * constraint's is how far it is from breaking (-g for g <= 0), a taut one's
 * its force's size in the direction it may act (a string pulls: -mu).
 */
void csf_cons_guards(const csf_cons *cs, const double *m, double *g);
/* The distance from its bound within which one-sided constraint k is at it: 1e-13 of its terms' size. */
double csf_cons_resolution(const csf_cons *cs, const double *m, uint32_t k);
/*
 * Constraint k goes taut: the impulse that turns its rate gd into -e gd
 * (restitution e) and keeps the other taut constraints' rates, applied to
 * the velocities of state y (gd and J as the RHS section left them in m at y).
 */
void csf_cons_impulse(csf_cons *cs, const double *m, double *y, uint32_t k, double e);
/*
 * One-sided constraint k in m: *g and *gd, its value and rate relative to
 * the sizes of their terms (the rate's also to 1e-4 s times its
 * acceleration's), signed so that positive breaks it (0 for an equality,
 * which returns 0; else 1).
 */
int csf_cons_state(const csf_cons *cs, const double *m, uint32_t k, double *g, double *gd);
/*
 * How hard taut one-sided constraint k holds its bodies back, by the last
 * solve: the rate at which its force changes its second derivative, signed
 * so that positive is the way it can act (a string's pull); 0 for an equality.
 */
double csf_cons_pull(const csf_cons *cs, uint32_t k);
/* The multiplier of constraint k in the last solve. */
double csf_cons_force(const csf_cons *cs, uint32_t k);

#endif
