/*
 * constraint.c - the constraints (rules with attribute C, csf(5)
 * CONSTRAINTS): their forces (the CONSTRAIN instruction), and the
 * corrections that put positions and velocities back on them.
 *
 * A constraint k is g_k(positions, t) = 0. The compiled code computes, at
 * the slots of its table (csf_con), g, its rate gd, the bias c and, per
 * body b, the gradient J_kb, so that g'' = sum_b J_kb . a_b + c_k. Ideal
 * constraint forces act along the gradients: body b gets
 * FC_b = sum_k mu_k J_kb, and a_b += FC_b / m_b. The multipliers mu make
 * every active constraint's second derivative zero:
 *
 *     A mu = -(J a + c),   A_kl = sum_b J_kb . J_lb / m_b,
 *
 * with a the accelerations of the other forces. A is symmetric and
 * positive semi-definite, sparse: A_kl is nonzero only when k and l share
 * a body. It is factored as L D L^T in envelope (skyline) storage, in the
 * order of the constraints: row k holds columns f_k .. k, where f_k is the
 * first constraint that shares a body with k. A chain or a tree written in
 * order has a narrow envelope, and the cost is linear in its length.
 *
 * Redundant constraints (a closed loop of rods) make A singular: a pivot
 * below 1e-10 of its row's diagonal marks the row redundant; it takes no
 * force of its own (mu_k = 0), the others' forces are the solution of the
 * rest (the documented choice: the earlier constraints carry the load), and
 * the redundant row's own equation is checked against that solution.
 * When it does not hold, the constraints contradict each other there: the
 * set is marked failed (csf_cons_failed), and the run stops, naming them.
 *
 * A one-sided constraint (g <= 0 or g >= 0, a string) is either taut,
 * a row like an equality, or slack, no row at all (csf_cons_set_mode).
 *
 * The same factorisation corrects a state that has drifted off the
 * constraints (csf_cons_correct): positions by Newton steps of the
 * mass-weighted projection, dq = -W J^T A^-1 g, velocities likewise with
 * gd (one step: gd is linear in the velocities).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "constraint.h"

struct csf_cons {
	const csf_prog *p;
	uint32_t n;
	uint32_t *f;          /* per constraint: the first column of its row */
	size_t *row;          /* per constraint: where its row starts in A and L */
	double *A, *L;        /* the matrix (envelope), its factor */
	double *d, *b, *mu;   /* the pivots, the right-hand side, the multipliers */
	double *mut;          /* with contacts: the multipliers' sum over the turns (csf_constraint_apply) */
	unsigned char *drop;  /* a redundant row (or a slack one): no force of its own */
	unsigned char *taut;  /* one-sided: taut (an equality: always 1) */
	uint32_t *order;      /* the conbodies entries sorted by body (pos slot), then constraint */
	uint32_t *aslot, na;  /* with contacts: the a of every body either moves, once each */
	double *a0;           /* their accelerations before contact and constraint forces */
	uint32_t *owner;      /* per conbodies entry: its constraint */
	int failed;           /* a redundant row whose equation does not hold */
	uint32_t fail_k;      /* its constraint */
	double fail_res;      /* its residual, relative */
};

/* A conbodies entry by its body (the slot of its pos), then by its place: for sorting. */
typedef struct bkey { uint32_t pos, e; } bkey;

static int by_body(const void *x, const void *y)
{
	const bkey *a = x, *b = y;
	if (a->pos != b->pos) return a->pos < b->pos ? -1 : 1;
	return a->e < b->e ? -1 : a->e > b->e;
}

csf_cons *csf_cons_new(const csf_prog *p)
{
	csf_cons *cs = calloc(1, sizeof *cs);
	if (!cs) return NULL;
	uint32_t n = p->ncons, nb = p->nconbodies;
	cs->p = p;
	cs->n = n;
	cs->f = malloc((n + 1) * sizeof *cs->f);
	cs->row = malloc((n + 1) * sizeof *cs->row);
	cs->d = malloc((n + 1) * sizeof *cs->d);
	cs->b = malloc((n + 1) * sizeof *cs->b);
	cs->mu = malloc((n + 1) * sizeof *cs->mu);
	cs->mut = malloc((n + 1) * sizeof *cs->mut);
	cs->drop = malloc(n + 1);
	cs->taut = malloc(n + 1);
	cs->order = malloc((nb + 1) * sizeof *cs->order);
	cs->owner = malloc((nb + 1) * sizeof *cs->owner);
	if (!cs->f || !cs->row || !cs->d || !cs->b || !cs->mu || !cs->mut || !cs->drop || !cs->taut || !cs->order || !cs->owner) {
		csf_cons_free(cs);
		return NULL;
	}
	for (uint32_t k = 0; k < n; k++) {
		cs->f[k] = k;
		cs->taut[k] = 1;
		for (uint32_t e = p->cons[k].first; e < p->cons[k].first + p->cons[k].n; e++) cs->owner[e] = k;
	}
	bkey *keys = malloc((nb + 1) * sizeof *keys);
	if (!keys) {
		csf_cons_free(cs);
		return NULL;
	}
	for (uint32_t e = 0; e < nb; e++) keys[e] = (bkey){ p->conbodies[e].pos, e };
	qsort(keys, nb, sizeof *keys, by_body);
	for (uint32_t e = 0; e < nb; e++) cs->order[e] = keys[e].e;
	free(keys);
	/* the envelope: a row reaches back to the first constraint that shares a body with it */
	for (uint32_t i = 0; i < nb;) {
		uint32_t j = i, first = cs->owner[cs->order[i]];
		while (j < nb && p->conbodies[cs->order[j]].pos == p->conbodies[cs->order[i]].pos) j++;
		for (uint32_t e = i; e < j; e++)
			if (cs->f[cs->owner[cs->order[e]]] > first) cs->f[cs->owner[cs->order[e]]] = first;
		i = j;
	}
	size_t at = 0;
	for (uint32_t k = 0; k < n; k++) {
		cs->row[k] = at;
		at += k - cs->f[k] + 1;
	}
	cs->row[n] = at;
	cs->A = malloc((at + 1) * sizeof *cs->A);
	cs->L = malloc((at + 1) * sizeof *cs->L);
	/* the accelerations the contact routine and the constraints both change, for their iteration */
	cs->aslot = malloc(((size_t)p->ncbodies + nb + 1) * sizeof *cs->aslot);
	cs->a0 = malloc(3 * ((size_t)p->ncbodies + nb + 1) * sizeof *cs->a0);
	if (!cs->A || !cs->L || !cs->aslot || !cs->a0) {
		csf_cons_free(cs);
		return NULL;
	}
	for (uint32_t b = 0; b < p->ncbodies + nb; b++) {
		uint32_t s = b < p->ncbodies ? p->cbodies[b].s[CSF_CF_A] : p->conbodies[b - p->ncbodies].a;
		if (b < p->ncbodies && p->cbodies[b].plane) continue;
		uint32_t j = 0;
		while (j < cs->na && cs->aslot[j] != s) j++;
		if (j == cs->na) cs->aslot[cs->na++] = s;
	}
	return cs;
}

void csf_cons_free(csf_cons *cs)
{
	if (!cs) return;
	free(cs->f);
	free(cs->row);
	free(cs->A);
	free(cs->L);
	free(cs->d);
	free(cs->b);
	free(cs->mu);
	free(cs->mut);
	free(cs->drop);
	free(cs->taut);
	free(cs->order);
	free(cs->owner);
	free(cs->aslot);
	free(cs->a0);
	free(cs);
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The inverse mass of body e, 0 when its mass is not a positive finite number (the run names that elsewhere). */
static double inv_mass(const csf_conbody *e, const double *m)
{
	double w = 1 / m[e->m];
	return isfinite(w) && w > 0 ? w : 0;
}

/* A = J W J^T over the taut constraints, into the envelope. */
static void assemble(csf_cons *cs, const double *m)
{
	const csf_prog *p = cs->p;
	uint32_t nb = p->nconbodies;
	memset(cs->A, 0, cs->row[cs->n] * sizeof *cs->A);
	for (uint32_t i = 0; i < nb;) {
		uint32_t j = i;
		while (j < nb && p->conbodies[cs->order[j]].pos == p->conbodies[cs->order[i]].pos) j++;
		for (uint32_t x = i; x < j; x++) {
			const csf_conbody *ex = &p->conbodies[cs->order[x]];
			uint32_t kx = cs->owner[cs->order[x]];
			if (!cs->taut[kx]) continue;
			double w = inv_mass(ex, m);
			for (uint32_t y = i; y <= x; y++) { /* in constraint order: ky <= kx */
				const csf_conbody *ey = &p->conbodies[cs->order[y]];
				uint32_t ky = cs->owner[cs->order[y]];
				if (!cs->taut[ky]) continue;
				cs->A[cs->row[kx] + (ky - cs->f[kx])] += w * dot3(m + ex->J, m + ey->J);
			}
		}
		i = j;
	}
}

/* L D L^T of the envelope; rows whose pivot vanishes (redundant) or that are slack are dropped. */
static void factor(csf_cons *cs)
{
	for (uint32_t i = 0; i < cs->n; i++) {
		double *Li = cs->L + cs->row[i] - cs->f[i]; /* Li[j]: column j of row i */
		const double *Ai = cs->A + cs->row[i] - cs->f[i];
		for (uint32_t j = cs->f[i]; j < i; j++) {
			double *Lj = cs->L + cs->row[j] - cs->f[j];
			double s = Ai[j];
			uint32_t k0 = cs->f[i] > cs->f[j] ? cs->f[i] : cs->f[j];
			for (uint32_t k = k0; k < j; k++) s -= Li[k] * cs->d[k] * Lj[k];
			Li[j] = cs->drop[j] ? 0 : s / cs->d[j];
		}
		double s = Ai[i];
		for (uint32_t k = cs->f[i]; k < i; k++) s -= Li[k] * Li[k] * cs->d[k];
		Li[i] = 1;
		cs->drop[i] = !cs->taut[i] || !(s > 1e-10 * Ai[i]);
		cs->d[i] = cs->drop[i] ? 0 : s;
	}
}

/*
 * Solves A mu = b with the factor (the dropped rows' mu zero); with check,
 * checks the redundant rows' equations (forces and impulses: a correction's
 * residuals drift apart, and the others' correction mends them).
 */
static void solve(csf_cons *cs, int check)
{
	uint32_t n = cs->n;
	double *z = cs->mu;
	for (uint32_t i = 0; i < n; i++) {
		const double *Li = cs->L + cs->row[i] - cs->f[i];
		double s = cs->b[i];
		for (uint32_t k = cs->f[i]; k < i; k++) s -= Li[k] * z[k];
		z[i] = cs->drop[i] ? 0 : s;
	}
	for (uint32_t i = 0; i < n; i++) z[i] = cs->drop[i] ? 0 : z[i] / cs->d[i];
	for (uint32_t i = n; i-- > 0;) {
		const double *Li = cs->L + cs->row[i] - cs->f[i];
		for (uint32_t k = cs->f[i]; k < i; k++) z[k] -= Li[k] * z[i];
	}
	/* A redundant taut row: its equation must hold (residual against the sizes of its terms) */
	for (uint32_t i = 0; i < n && check; i++) {
		if (!cs->drop[i] || !cs->taut[i]) continue;
		double r = cs->b[i], size = fabs(cs->b[i]);
		const double *Ai = cs->A + cs->row[i] - cs->f[i];
		for (uint32_t k = cs->f[i]; k <= i; k++) r -= Ai[k] * z[k], size += fabs(Ai[k] * z[k]);
		for (uint32_t k = i + 1; k < n; k++)
			if (cs->f[k] <= i) {
				double a = cs->A[cs->row[k] + (i - cs->f[k])];
				r -= a * z[k], size += fabs(a * z[k]);
			}
		if (fabs(r) > 1e-6 * size + DBL_MIN && !cs->failed) {
			cs->failed = 1;
			cs->fail_k = i;
			cs->fail_res = size > 0 ? fabs(r) / size : INFINITY;
		}
	}
}

/* The multipliers mu for right-hand side rhs(k) of every taut constraint, at the state in m. */
static void multipliers(csf_cons *cs, const double *m, int what)
{
	const csf_prog *p = cs->p;
	assemble(cs, m);
	factor(cs);
	for (uint32_t k = 0; k < cs->n; k++) {
		const csf_con *c = &p->cons[k];
		double s;
		if (what == CSF_CONS_FORCE) {
			s = m[c->c];
			for (uint32_t e = c->first; e < c->first + c->n; e++)
				s += dot3(m + p->conbodies[e].J, m + p->conbodies[e].a);
			s = -s;
		} else
			s = what == CSF_CONS_POS ? m[c->g] : m[c->gd];
		cs->b[k] = cs->taut[k] ? s : 0;
	}
	solve(cs, what == CSF_CONS_FORCE);
}

/*
 * The forces of the constraints, given the other forces' accelerations in
 * m: added to each body's FC (with its multiplier, mu), and to its a. The
 * largest force added, into *most (of the largest FC, into *size).
 */
static void add_forces(csf_cons *cs, double *m, double *most, double *size)
{
	const csf_prog *p = cs->p;
	multipliers(cs, m, CSF_CONS_FORCE);
	*most = *size = 0;
	for (uint32_t i = 0; i < p->nconbodies;) { /* once per body: FC, as it was, to the change */
		uint32_t j = i;
		const csf_conbody *b = &p->conbodies[cs->order[i]];
		while (j < p->nconbodies && p->conbodies[cs->order[j]].pos == b->pos) j++;
		double was[3] = { m[b->fc], m[b->fc + 1], m[b->fc + 2] };
		for (uint32_t e = i; e < j; e++) {
			uint32_t k = cs->owner[cs->order[e]];
			if (!cs->taut[k]) continue; /* a slack string's gradient need not even be finite (at its pivot) */
			for (int d = 0; d < 3; d++) m[b->fc + d] += cs->mu[k] * m[p->conbodies[cs->order[e]].J + d];
		}
		double w = inv_mass(b, m), dd = 0, ff = 0;
		for (int k = 0; k < 3; k++) {
			double df = m[b->fc + k] - was[k];
			m[b->a + k] += df * w;
			dd += df * df, ff += m[b->fc + k] * m[b->fc + k];
		}
		if (sqrt(dd) > *most) *most = sqrt(dd);
		if (sqrt(ff) > *size) *size = sqrt(ff);
		i = j;
	}
}

/*
 * With contacts, the contact forces and the constraints' depend on each
 * other (a pendulum's bob resting against a wall): the contact routine and
 * the constraints' solve take turns (block Gauss-Seidel), each with the
 * other's last forces, from the accelerations of the other forces, until
 * the constraints' forces change by no more than 1e-14 of their size (at
 * most 200 turns; a scene where no constrained body touches anything needs
 * two).
 */
void csf_constraint_apply(const csf_prog *p, const csf_exec_ctx *x, double *m)
{
	csf_cons *cs = x ? x->cons : NULL;
	double most, size;
	if (!cs) return;
	for (uint32_t e = 0; e < p->nconbodies; e++) memset(m + p->conbodies[e].fc, 0, 3 * sizeof *m);
	if (!x->contacts) {
		add_forces(cs, m, &most, &size);
		return;
	}
	for (uint32_t j = 0; j < cs->na; j++) memcpy(cs->a0 + 3 * j, m + cs->aslot[j], 3 * sizeof *m);
	memset(cs->mut, 0, cs->n * sizeof *cs->mut);
	for (int turn = 0; turn < 200; turn++) {
		for (uint32_t j = 0; j < cs->na; j++) memcpy(m + cs->aslot[j], cs->a0 + 3 * j, 3 * sizeof *m);
		for (uint32_t i = 0; i < p->nconbodies;) { /* the constraints' forces so far */
			uint32_t j = i;
			const csf_conbody *b = &p->conbodies[cs->order[i]];
			while (j < p->nconbodies && p->conbodies[cs->order[j]].pos == b->pos) j++;
			double w = inv_mass(b, m);
			for (int k = 0; k < 3; k++) m[b->a + k] += m[b->fc + k] * w;
			i = j;
		}
		csf_contact_apply(p, x, m);
		add_forces(cs, m, &most, &size);
		for (uint32_t k = 0; k < cs->n; k++) cs->mut[k] += cs->mu[k];
		if (most <= 1e-14 * size) break;
	}
	memcpy(cs->mu, cs->mut, cs->n * sizeof *cs->mu); /* each turn's were the change: the whole for the guards */
}

/* Moves the positions (what CSF_CONS_POS) or velocities of state y by -W J^T mu, the last solve's. */
static void move_by(csf_cons *cs, const double *m, double *y, int what)
{
	const csf_prog *p = cs->p;
	for (uint32_t k = 0; k < cs->n; k++) {
		if (!cs->taut[k] || cs->mu[k] == 0) continue;
		const csf_con *c = &p->cons[k];
		for (uint32_t e = c->first; e < c->first + c->n; e++) {
			const csf_conbody *b = &p->conbodies[e];
			double w = inv_mass(b, m);
			uint32_t s = (what == CSF_CONS_POS ? b->pos : b->v) - p->ystart;
			for (int i = 0; i < 3; i++) y[s + i] -= w * cs->mu[k] * m[b->J + i];
		}
	}
}

void csf_cons_correct(csf_cons *cs, const double *m, double *y, int what)
{
	multipliers(cs, m, what);
	move_by(cs, m, y, what);
}

/* The size of the terms of constraint k's g: |LHS| + |RHS| and each body's |J| |pos|. */
static double size_of(const csf_prog *p, const double *m, uint32_t k)
{
	const csf_con *c = &p->cons[k];
	double size = m[c->scale];
	for (uint32_t e = c->first; e < c->first + c->n; e++) {
		const csf_conbody *b = &p->conbodies[e];
		size += sqrt(dot3(m + b->J, m + b->J) * dot3(m + b->pos, m + b->pos));
	}
	return size;
}

/*
 * The size of the terms of constraint k's rate gd = sum_b J_b . v_b + g_t:
 * each body's |J_b| |v_b| and |g_t|, and what the accelerations change it by
 * in 1e-4 s (a billionth of that, 1e-13 s, the time events are located to,
 * is rounding): at rest after an impact, what is left of a velocity along a
 * constraint is noise, not a direction. The acceleration's size is taken
 * with and without the constraints' forces, the same taut or slack.
 */
static double rate_size(const csf_cons *cs, const double *m, uint32_t k)
{
	const csf_prog *p = cs->p;
	const csf_con *c = &p->cons[k];
	double vsize = 0, asize = fabs(m[c->c]), jv = 0;
	for (uint32_t e = c->first; e < c->first + c->n; e++) {
		const csf_conbody *b = &p->conbodies[e];
		double jj = dot3(m + b->J, m + b->J);
		vsize += sqrt(jj * dot3(m + b->v, m + b->v));
		asize += sqrt(jj * dot3(m + b->a, m + b->a)) + sqrt(jj * dot3(m + b->fc, m + b->fc)) * inv_mass(b, m);
		jv += dot3(m + b->J, m + b->v);
	}
	return vsize + fabs(m[c->gd] - jv) + 1e-4 * asize;
}

double csf_cons_residual(const csf_cons *cs, const double *m, int what, uint32_t *worst, double *abs_res)
{
	const csf_prog *p = cs->p;
	double most = 0;
	if (worst) *worst = 0;
	if (abs_res) *abs_res = 0;
	for (uint32_t k = 0; k < cs->n; k++) {
		const csf_con *c = &p->cons[k];
		if (!cs->taut[k]) continue;
		double r, size;
		if (what == CSF_CONS_POS) {
			r = m[c->g];
			size = size_of(p, m, k);
		} else {
			r = m[c->gd];
			size = rate_size(cs, m, k);
		}
		double rel = r == 0 ? 0 : size > 0 ? fabs(r) / size : INFINITY;
		if (rel > most) {
			most = rel;
			if (worst) *worst = k;
			if (abs_res) *abs_res = fabs(r);
		}
	}
	return most;
}

int csf_cons_failed(const csf_cons *cs, uint32_t *k, double *res)
{
	if (cs->failed) {
		if (k) *k = cs->fail_k;
		if (res) *res = cs->fail_res;
	}
	return cs->failed;
}

void csf_cons_set_mode(csf_cons *cs, uint32_t k, int taut) { cs->taut[k] = (unsigned char)(taut != 0); }

int csf_cons_taut(const csf_cons *cs, uint32_t k) { return cs->taut[k]; }

double csf_cons_force(const csf_cons *cs, uint32_t k) { return cs->mu[k]; }

/* The side a one-sided constraint breaks on: +1 for g <= 0 (breaks when g > 0), -1 for g >= 0, 0 for an equality. */
static double side(const csf_con *c) { return c->kind == CSF_CON_LE ? 1 : c->kind == CSF_CON_GE ? -1 : 0; }

double csf_cons_resolution(const csf_cons *cs, const double *m, uint32_t k) { return 1e-13 * size_of(cs->p, m, k); }

void csf_cons_guards(const csf_cons *cs, const double *m, double *g)
{
	const csf_prog *p = cs->p;
	for (uint32_t k = 0; k < cs->n; k++) {
		const csf_con *c = &p->cons[k];
		double s = side(c);
		if (s == 0) g[k] = 1;
		else if (cs->taut[k]) g[k] = -s * cs->mu[k];
		else /* within its resolution of its bound is at it (a string that has just bounced, put back on
		        its bound to 1e-14: csf_run_cons_modes) */
			g[k] = -s * m[c->g] + csf_cons_resolution(cs, m, k);
	}
}

void csf_cons_impulse(csf_cons *cs, const double *m, double *y, uint32_t k, double e)
{
	const csf_prog *p = cs->p;
	assemble(cs, m);
	factor(cs);
	for (uint32_t j = 0; j < cs->n; j++)
		cs->b[j] = !cs->taut[j] ? 0 : j == k ? (1 + e) * m[p->cons[j].gd] : m[p->cons[j].gd];
	solve(cs, 1);
	move_by(cs, m, y, CSF_CONS_VEL);
}

double csf_cons_pull(const csf_cons *cs, uint32_t k)
{
	const csf_con *c = &cs->p->cons[k];
	return -side(c) * cs->mu[k] * cs->A[cs->row[k] + (k - cs->f[k])];
}

int csf_cons_state(const csf_cons *cs, const double *m, uint32_t k, double *g, double *gd)
{
	const csf_prog *p = cs->p;
	const csf_con *c = &p->cons[k];
	double s = side(c), size = size_of(p, m, k), vsize = rate_size(cs, m, k);
	*g = size > 0 ? s * m[c->g] / size : 0;
	*gd = vsize > 0 ? s * m[c->gd] / vsize : 0;
	return s != 0;
}

/* The modes of the one-sided constraints, the rows dropped and the last multipliers. */
int csf_cons_keep(csf_cons *cs, csf_keeper *k)
{
	if (!cs) return 0;
	size_t n = (size_t)cs->n + 1;
	return csf_keep(k, "cons.taut", cs->taut, n) | csf_keep(k, "cons.drop", cs->drop, n) |
	       csf_keep(k, "cons.mu", cs->mu, n * sizeof *cs->mu) | csf_keep(k, "cons.mut", cs->mut, n * sizeof *cs->mut) |
	       CSF_KEEP(k, cs->failed);
}
