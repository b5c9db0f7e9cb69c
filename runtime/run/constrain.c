/*
 * constrain.c - the state kept on the constraints (rules with attribute C):
 * checked at t = 0 (positions off a constraint are an error, velocities
 * off it are projected onto it, with a warning that says by how much),
 * projected back after every step that has drifted off, and on every row.
 *
 * The forces of the constraints (csf_constraint_apply) keep their second
 * derivatives zero, so an integrator's error makes the positions and
 * velocities drift off them as it makes any state drift, by about its
 * tolerance a step. After each step whose residual exceeds DRIFT times the
 * tolerance (relative to the sizes of the constraint's terms), the state is
 * moved back by the mass-weighted projection (SHAKE and RATTLE's: Newton
 * steps for the positions, then one for the velocities) and the integrator
 * restarts from it. A row is projected likewise before it is written, so
 * that every row satisfies every constraint to rounding.
 */
#include <math.h>
#include <string.h>

#include "run_int.h"
#include "constraint.h"

/* A residual (relative) that counts as drift after a step: this fraction of the tolerance. */
#define DRIFT 1e-3
/* A multistep method's: a restart costs it its order (it starts again from one), so it drifts further. */
#define DRIFT_HISTORY 1e3
/* What a projection aims at, and what t = 0 allows of the positions (relative). */
#define EXACT 1e-14
#define START_OFF 1e-9

/* RHS at (t, y) into r->m (the constraints' values with it); nonzero if it failed. */
static int eval_at(run *r, double t, const double *y) { return csf_run_rhs(t, y, r->cw, r); }

/*
 * Moves y at t onto the constraints until the residuals are within `within`
 * (relative): positions by Newton steps while they get smaller, then the
 * velocities. 1 if y changed, 0 if not, -1 if an evaluation failed. r->m
 * holds the evaluation at the y it returns.
 */
static int project(run *r, double t, double *y, double within)
{
	csf_cons *cs = r->cons;
	int changed = 0;
	double last = INFINITY;
	for (int it = 0;; it++) {
		if (eval_at(r, t, y)) return -1;
		double res = csf_cons_residual(cs, r->m, CSF_CONS_POS, NULL, NULL);
		if (res <= within || it == 10 || !(res < 0.5 * last)) break;
		last = res;
		csf_cons_correct(cs, r->m, y, CSF_CONS_POS);
		changed = 1;
	}
	for (int it = 0; it < 3; it++) {
		if (csf_cons_residual(cs, r->m, CSF_CONS_VEL, NULL, NULL) <= within) break;
		csf_cons_correct(cs, r->m, y, CSF_CONS_VEL);
		changed = 1;
		if (eval_at(r, t, y)) return -1;
	}
	return changed;
}

int csf_run_cons_start(run *r, double *y, FILE *err)
{
	const csf_prog *p = r->p;
	uint32_t k;
	double off;
	if (eval_at(r, 0, y)) return -1;
	if (csf_cons_residual(r->cons, r->m, CSF_CONS_POS, &k, &off) > START_OFF) {
		r->con_k = k, r->con_off = off;
		return 1;
	}
	double vres = csf_cons_residual(r->cons, r->m, CSF_CONS_VEL, &k, &off);
	if (project(r, 0, y, EXACT) < 0) return -1;
	if (vres > START_OFF) {
		const csf_con *c = &p->cons[k];
		const csf_src *s = &p->srcs[c->src];
		const char *u = csf_str(p, c->unit);
		char ob[32];
		csf_fmt_double(ob, off);
		fprintf(err, "%s:%lu: warning: the initial velocities break rule C at line %lu by %s%s%s/s (its rate): "
		        "projected onto it (%s)\n", csf_str(p, p->files[s->file]), (unsigned long)s->line,
		        (unsigned long)s->line, ob, *u ? " " : " ", *u ? u : "1", csf_str(p, s->text));
	}
	return 0;
}

int csf_run_cons_step(run *r, csf_ode *ode, double t, double *y)
{
	if (!r->cons) return 0;
	if (eval_at(r, t, y)) return 1;
	double within = (csf_ode_history(ode) ? DRIFT_HISTORY : DRIFT) * r->tol;
	if (csf_cons_residual(r->cons, r->m, CSF_CONS_POS, NULL, NULL) <= within &&
	    csf_cons_residual(r->cons, r->m, CSF_CONS_VEL, NULL, NULL) <= within)
		return 0;
	int st = project(r, t, y, EXACT);
	if (st < 0) return 1;
	csf_ode_restart(ode);
	if (r->ga && csf_run_guards_at(r, t, y, r->ga)) return 1;
	if (r->fa) memcpy(r->fa, r->fs, r->p->ny * sizeof *r->fa);
	return 0;
}

int csf_run_cons_row(run *r, double t, double *y)
{
	if (!r->cons) return 0;
	return project(r, t, y, EXACT) < 0;
}
