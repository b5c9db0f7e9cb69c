/*
 * constraints.c - rules with attribute C (DECISIONS 10, csf(5)
 * CONSTRAINTS): `rule C [for ...]: LHS = RHS` keeps LHS - RHS at zero at
 * all times, `<=` or `>=` in place of `=` at most or at least zero (a
 * string), by ideal forces on the mass points whose positions it reads.
 *
 * A constraint solves for nothing: it is not resolved like a rule. Each
 * binding is built (inst_constraint) while the rules are resolved, in
 * order; once every rule is, constraints_finish checks what it reads
 * (positions of mass points, constants and t: anything that a rule
 * computes or that is integrated but a position would make its force
 * depend on itself), finds its bodies, and differentiates g symbolically
 * (diff.c): its gradient with respect to each body's position, its rate
 * gd = sum_b grad_b . v_b + dg/dt, and the bias c, the rate of gd with the
 * velocities held, so that g'' = sum_b grad_b . a_b + c. The runtime
 * (runtime/constraint/) solves for the forces from these.
 */
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"
#include "parse.h"

/* The properties a constrained body must have (mechanics/mass_point's): all but pos are read by the runtime. */
static const char *const body_props[] = { "v", "a", "m", "FC" };

int is_constraint(Stmt *s)
{
	if (!s->attr || strcmp(s->attr, "C") != 0) return 0;
	if (s->call) {
		Expr *x = s->call;
		if (x->kind != E_BIN || (x->op != LE && x->op != GE)) {
			error_at(x->loc, "a constraint is an equation 'LHS = RHS', or 'LHS <= RHS' or 'LHS >= RHS' for one "
			         "that holds one way (a string)");
			return -1;
		}
		return 1;
	}
	Eqn *q = s->eqns;
	if (!q || q->nest || q->next || q->deriv) {
		error_at(q ? q->loc : s->loc, "a constraint is one equation among positions, constants and t: not %s",
		         q && q->deriv ? "a derivative" : "a conditional block");
		return -1;
	}
	return 1;
}

void inst_constraint(Stmt *s, Object **bind, int nbind)
{
	Constraint *K = xalloc(sizeof *K);
	Vec rf = { 0 }, pending = { 0 };
	Ctx C = { 0 };
	C.bind = bind;
	C.nbind = nbind;
	C.reads = &K->reads;
	C.rf = &rf;
	C.pending = &pending;
	C.key_nbind = s->has_for ? 1 : nbind;
	C.ivar = sema.ivar;
	C.idx = sema.idx;
	Expr *l = s->call ? s->call->a : s->eqns->lhs, *r = s->call ? s->call->b : s->eqns->rhs;
	K->st = s;
	K->src = sema.cur_src;
	K->kind = !s->call ? CSF_CON_EQ : s->call->op == LE ? CSF_CON_LE : CSF_CON_GE;
	K->bind = bind;
	K->nbind = nbind;
	K->lhs = build(&C, l);
	K->rhs = build(&C, r);
	if (C.failed) return;
	if (rf.n) {
		error_at(s->loc, "a constraint cannot read RF: it reads positions, constants and t");
		return;
	}
	if (pending.n) {
		Var *v = pending.v[0];
		error_at(s->loc, "a constraint reads positions, constants and t, not the temporary '%s'", v->name);
		return;
	}
	if (K->lhs->isvec || K->rhs->isvec || K->lhs->isbool || K->rhs->isbool) {
		error_at(l->loc, "a constraint is one scalar equation: write one for each component ('pos.z = 0 m'), or "
		         "one on a magnitude ('(pos - pos$1).mag = L')");
		return;
	}
	vec_push(&sema.M->cons, K);
}

/* The rates of a direction: each body's position, and t. */
typedef struct Rates {
	Constraint *K;
	int body, comp;   /* the gradient: body's position along comp (body -1: the motion) */
} Rates;

static int body_of(Constraint *K, Var *v)
{
	for (int i = 0; i < K->pos.n; i++)
		if (K->pos.v[i] == v) return i;
	return -1;
}

static RExpr *var_ref(Var *v, Loc l)
{
	RExpr *e = rnew(R_VAR, l);
	e->var = v;
	e->isvec = v->isvec;
	e->place = -1;
	return e;
}

/* Along one component of one body's position: its unit vector; zero for everything else. */
static RExpr *rate_grad(Dir *D, RExpr *x)
{
	Rates *R = D->ctx;
	if (body_of(R->K, x->var) != R->body) return NULL;
	double u[3] = { 0, 0, 0 };
	u[R->comp] = 1;
	return rvconst(u, x->loc);
}

/* Along the motion: a position at its velocity, t at 1; the velocities held. */
static RExpr *rate_motion(Dir *D, RExpr *x)
{
	Rates *R = D->ctx;
	if (x->var->kind == V_TIME) return rconst(1, x->loc);
	int b = body_of(R->K, x->var);
	return b < 0 ? NULL : var_ref(R->K->vel.v[b], x->loc);
}

/* What K reads: its bodies (mass points whose positions are integrated), or an error. */
static int find_bodies(Constraint *K)
{
	for (int i = 0; i < K->reads.n; i++) {
		Var *v = K->reads.v[i];
		if (v->kind == V_TIME) continue;
		if (v->kind == V_TEMP) {
			error_at(K->st->loc, "a constraint reads positions, constants and t, not the temporary '%s'", v->name);
			return 0;
		}
		int pos = v->kind == V_PROP && !strcmp(v->name, "pos") && v->isvec;
		if (pos && v->state) {
			for (size_t k = 0; k < sizeof body_props / sizeof body_props[0]; k++) {
				Var *p = prop_of_obj(v->obj, body_props[k]);
				if (!p || !p->isvec != (k == 2)) {
					error_at(K->st->loc, "constrained object '%s' is not a mass point: it has no %s '%s' "
					         "(object %s: mass_point)", v->obj->name, k == 2 ? "scalar" : "vector",
					         body_props[k], v->obj->name);
					return 0;
				}
			}
			if (!prop_of_obj(v->obj, "v")->state) {
				error_at(K->st->loc, "constrained object '%s' has no velocity integrated ('rule: pos' = v' "
				         "and 'rule: v' = a', from mechanics/rules)", v->obj->name);
				return 0;
			}
			vec_push(&K->bodies, v->obj);
			vec_push(&K->pos, v);
			vec_push(&K->vel, prop_of_obj(v->obj, "v"));
			continue;
		}
		if (v->state || v->det) {
			error_at(K->st->loc, "a constraint reads positions, constants and t, not '%s'%s%s%s, which %s", v->name,
			         v->obj ? " of '" : "", v->obj ? v->obj->name : "", v->obj ? "'" : "",
			         v->state ? "is integrated (a derivative rule's)" : "a rule computes");
			return 0;
		}
	}
	return 1;
}

/* Its derivatives: g, the gradients, gd, c and the scale of its terms. */
static int derive(Constraint *K)
{
	Loc l = K->st->loc;
	Rates R = { K, -1, 0 };
	Dir D = { .what = "a constraint", .ctx = &R };
	K->g = rop(CSF_OP_SUB, 0, l, K->lhs, K->rhs, NULL);
	K->grad = xalloc((size_t)(K->bodies.n + 1) * sizeof *K->grad);
	D.rate = rate_grad;
	for (int b = 0; b < K->bodies.n; b++) {
		RExpr *c[3];
		for (int i = 0; i < 3; i++) {
			R.body = b, R.comp = i;
			c[i] = diff(&D, K->g);
			if (!c[i]) c[i] = rconst(0, l);
		}
		if (D.failed) return 0;
		K->grad[b] = rop(CSF_OP_VPACK, 1, l, c[0], c[1], c[2]);
	}
	D.rate = rate_motion;
	R.body = -1;
	K->gd = diff(&D, K->g);
	if (!K->gd) K->gd = rconst(0, l);
	K->c = diff(&D, K->gd);
	if (!K->c) K->c = rconst(0, l);
	if (D.failed) return 0;
	K->cr = NULL; /* the least cr of its objects', 1 if none has one */
	for (int i = 0; i < K->nbind; i++) {
		Var *cr = prop_of_obj(K->bind[i], "cr");
		if (!cr || cr->isvec) continue;
		RExpr *v = var_ref(cr, l);
		K->cr = K->cr ? rop(CSF_OP_MIN, 0, l, K->cr, v, NULL) : v;
	}
	if (!K->cr) K->cr = rconst(1, l);
	K->scale = rop(CSF_OP_ADD, 0, l, rop(CSF_OP_ABS, 0, l, K->lhs, NULL, NULL), rop(CSF_OP_ABS, 0, l, K->rhs, NULL, NULL),
	               NULL);
	return 1;
}

void constraints_finish(void)
{
	Model *M = sema.M;
	int kept = 0;
	for (int i = 0; i < M->cons.n; i++) {
		Constraint *K = M->cons.v[i];
		if (!find_bodies(K) || !derive(K)) continue;
		if (!K->bodies.n) { /* it moves nothing: an anchor's position, a constant (csf(5)) */
			if (K->st->has_for)
				error_at(K->st->loc, "this constraint reads no position of a mass point: it moves nothing");
			continue;
		}
		for (int b = 0; b < K->bodies.n; b++) {
			Var *a = prop_of_obj(K->bodies.v[b], "a");
			if (!a->det)
				error_at(K->st->loc, "constrained object '%s' has no acceleration: use mechanics/rules (a from RF = "
				         "a.mul(m))", ((Object *)K->bodies.v[b])->name);
		}
		M->cons.v[kept++] = K;
	}
	M->cons.n = kept;
}
