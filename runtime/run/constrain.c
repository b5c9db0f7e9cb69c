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
/* What a projection aims at; what t = 0 allows of the positions, and what a projection must
   reach (beyond it, the constraints contradict each other): relative to the sizes of the terms. */
#define EXACT 1e-14
#define START_OFF 1e-9
/* A one-sided constraint this near its bound (relative), or moving this slowly, is at it. */
#define EDGE 1e-9

/*
 * RHS at (t, y) into r->m, with the constraints' values (g, its rate, the
 * sizes: what the forces alone do not need, csf_con.want); nonzero if it
 * failed.
 */
static int eval_at(run *r, double t, const double *y)
{
	double *want = r->m + r->p->cons[0].want, was = *want;
	*want = 1;
	int st = csf_run_rhs(t, y, r->cw, r);
	*want = was;
	return st;
}

/* After a projection: a residual it could not remove (what, at t) is constraints that contradict each other. */
static int contradicts(run *r, double t, int what)
{
	uint32_t k;
	double res = csf_cons_residual(r->cons, r->m, what, &k, NULL);
	if (!(res > START_OFF)) return 0;
	r->conflict = 1, r->con_k = k, r->con_off = res;
	r->fail = 1, r->fail_t = t;
	return 1;
}

/*
 * Moves y at t onto the constraints until the residuals are within `within`
 * (relative): positions by Newton steps while they get smaller, then the
 * velocities. 1 if y changed, 0 if not, -1 if an evaluation failed. r->m
 * holds the evaluation at the y it returns.
 */
static int project_pos(run *r, double t, double *y, double within)
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
	return changed;
}

static int project(run *r, double t, double *y, double within)
{
	csf_cons *cs = r->cons;
	int changed = project_pos(r, t, y, within);
	if (changed < 0 || contradicts(r, t, CSF_CONS_POS)) return -1;
	for (int it = 0; it < 3; it++) {
		if (csf_cons_residual(cs, r->m, CSF_CONS_VEL, NULL, NULL) <= within) break;
		csf_cons_correct(cs, r->m, y, CSF_CONS_VEL);
		changed = 1;
		if (eval_at(r, t, y)) return -1;
	}
	return contradicts(r, t, CSF_CONS_VEL) ? -1 : changed;
}

int csf_run_cons_start(run *r, double *y, FILE *err)
{
	const csf_prog *p = r->p;
	uint32_t k;
	double off, g, gd;
	if (eval_at(r, 0, y)) return -1;
	for (k = 0; k < p->ncons; k++) /* a one-sided constraint away from its bound is slack */
		if (csf_cons_state(r->cons, r->m, k, &g, &gd) && g < -EDGE) csf_cons_set_mode(r->cons, k, 0);
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
		        (unsigned long)s->line, ob, " ", *u ? u : "1", csf_str(p, s->text));
	}
	return 0;
}

/*
 * The contacts' impulses are not solved together with the constraints: a
 * bob that strikes a peg across its rod (a cradle's balls, hung by strings)
 * is exact, the rod's rate untouched; one that strikes it at a slant would
 * have the part of its rebound along the rod taken away by the projection.
 * That answer would be wrong, so it is an error, not a result.
 */
int csf_run_cons_impact(run *r, double t, double *y)
{
	uint32_t k;
	if (!r->cons) return 0;
	if (eval_at(r, t, y)) return 1;
	double res = csf_cons_residual(r->cons, r->m, CSF_CONS_VEL, &k, NULL);
	if (!(res > 1e-6)) return 0;
	r->conflict = r->con_impact = 1, r->con_k = k, r->con_off = res;
	r->fail = 1, r->fail_t = t;
	return 1;
}

/*
 * The modes of the one-sided constraints, one change at a time until none
 * is called for: a slack one at its bound goes taut, with an impulse of its
 * restitution when it is moving to break (a string jerked taut), or without
 * one when it is at rest there and the force it needs is one it can give (a
 * string pulls); a taut one goes slack when its force would act the other
 * way or it is moving away from its bound (after a bounce).
 */
int csf_run_cons_modes(run *r, double t, double *y)
{
	const csf_prog *p = r->p;
	csf_cons *cs = r->cons;
	if (!r->ncg) return 0;
	uint32_t last = 0;
	for (uint32_t pass = 0; pass < 4 * p->ncons + 4; pass++) {
		int changed = 0;
		if (eval_at(r, t, y)) return 1;
		for (uint32_t k = 0; k < p->ncons && !changed; k++) {
			double g, gd, s = p->cons[k].kind == CSF_CON_LE ? 1 : -1;
			if (!csf_cons_state(cs, r->m, k, &g, &gd)) continue;
			if (csf_cons_taut(cs, k)) {
				if (gd < -EDGE || s * csf_cons_force(cs, k) > 0) csf_cons_set_mode(cs, k, 0), changed = 1, last = k;
				continue;
			}
			if (g < -EDGE || gd < -EDGE) continue; /* away from its bound, or leaving it */
			csf_cons_set_mode(cs, k, 1);
			if (gd > EDGE) { /* jerked taut: an impact, on its bound (where its guard has put it, to 1e-13 s) */
				if (project_pos(r, t, y, EXACT) < 0) return 1;
				double e = r->m[p->cons[k].cr], v = s * r->m[p->cons[k].gd], a;
				/* the train of bounces that would follow (rates e^n v, each turned back by the pull a
				   the taut string gives) ends within the Zeno time, or its first bounce is too low
				   for positions to follow (1000 times the bound's resolution): at rest on the
				   bound, taut */
				if (e > 0 && e < 1) {
					if (eval_at(r, t, y)) return 1;
					a = csf_cons_pull(cs, k);
					if (a > 0 && (2 * e * v / (a * (1 - e)) <= r->zeno ||
					              e * v * e * v / (2 * a) <= 1e3 * csf_cons_resolution(cs, r->m, k)))
						e = 0;
				}
				csf_cons_impulse(cs, r->m, y, k, e);
				changed = 1, last = k;
				continue;
			}
			if (eval_at(r, t, y)) return 1; /* at rest on its bound: taut if its force acts the way it can */
			if (s * csf_cons_force(cs, k) > 0) csf_cons_set_mode(cs, k, 0);
			else changed = 1, last = k;
		}
		if (!changed) return 0;
	}
	r->conflict = 1; /* taut and slack in turn without end */
	r->con_k = last, r->con_off = -1;
	r->fail = 1, r->fail_t = t;
	return 1;
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
