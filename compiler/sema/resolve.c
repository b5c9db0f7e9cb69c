/*
 * resolve.c - resolving one rule instance: the target of each equation chosen
 * by the precedence of spec 2.4.1 among the variables not yet determined,
 * then solved for (solve.c), or, for a rule with several unknowns, left to
 * wait for the rules that determine them together (group.c); conditional
 * blocks; derivative rules, assertions and stop conditions.
 */
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

static int var_class(Var *v)
{
	switch (v->kind) {
	case V_TEMP:
		if (map_get(&sema.watched, v->name) || (v->obj && map_get(&sema.watched, xprintf("%s\x01%s", v->obj->name, v->name))))
			return 2; /* a watched temporary ranks with the watched variables */
		return 1;
	case V_PROP: return 2;
	case V_GLOBAL: return 3;
	default: return 9;
	}
}

static const char *class_name(Var *v)
{
	switch (v->kind) {
	case V_TEMP: return var_class(v) == 1 ? "unwatched temporary" : "watched temporary";
	case V_PROP: return "watched variable";
	case V_GLOBAL: return "global";
	default: return "time";
	}
}

static void register_temp(Var *t)
{
	if (map_get(&sema.temps, var_more_of(t)->key)) return;
	if (!check_name(t->name, t->loc, "a temporary")) return;
	map_put(&sema.temps, var_more_of(t)->key, t);
	vec_push(&sema.M->temps, t);
}

/* What instance I may have meant by u, a temporary no rule determines: a property of its objects
 * or a global within a few edits of its name (a misspelling), or another object's temporary of that
 * name (OBJECT.NAME); NULL if nothing is close. */
static const char *near_name(Inst *I, Var *u)
{
	Vec c = { 0 };
	for (int b = 0; b < I->nbind; b++)
		for (int j = 0; j < obj_props(I->bind[b])->n; j++) vec_push(&c, ((Var *)obj_props(I->bind[b])->v[j])->name);
	for (int j = 0; j < sema.M->globals.n; j++) vec_push(&c, ((Var *)sema.M->globals.v[j])->name);
	const char *s = csf_suggest_name(u->name, (const char *const *)c.v, c.n);
	for (int j = 0; !s && j < sema.M->temps.n; j++) {
		Var *t = sema.M->temps.v[j];
		if (t != u && !t->pair && t->obj && t->obj != u->obj && !strcmp(t->name, u->name) && determined(t))
			s = xprintf("%s.%s", t->obj->name, t->name);
	}
	return s;
}

/* Where expression e first reads u, or NULL. */
static RExpr *find_read(RExpr *e, Var *u)
{
	if (!e) return NULL;
	if (e->k == R_VAR) return e->var == u ? e : NULL;
	for (int i = 0; i < e->n; i++) {
		RExpr *r = find_read(e->a[i], u);
		if (r) return r;
	}
	return NULL;
}

/* The place of u in an equation of sides lhs and rhs (at), as a diagnostic points at it. */
static Loc read_loc(RExpr *lhs, RExpr *rhs, Var *u, Loc at)
{
	RExpr *r = find_read(lhs, u);
	if (!r) r = find_read(rhs, u);
	return r ? r->loc : at;
}

/* The context that builds instance I's expressions, recording what they read into reads, rf and pending. */
static Ctx inst_ctx(Inst *I, Vec *reads, Vec *rf, Vec *pending)
{
	Ctx C = { 0 };
	C.summed = &I->summed;
	C.bind = I->bind;
	C.nbind = I->nbind;
	C.reads = reads;
	C.rf = rf;
	C.pending = pending;
	C.key_nbind = I->st->has_for ? 1 : I->nbind;
	C.ivar = I->ivar;
	C.idx = I->idx;
	C.iloop = I->iloop;
	return C;
}

/* A new temporary x that is a side of lhs = rhs alone takes its type from the other side. Returns 0
 * after an error (a declared vector made a scalar). */
static int type_new_temp(Var *x, RExpr *lhs, RExpr *rhs, Eqn *q)
{
	if (x->kind != V_TEMP || map_get(&sema.temps, var_more_of(x)->key)) return 1;
	RExpr *side = lhs->k == R_VAR && lhs->var == x ? lhs : rhs->k == R_VAR && rhs->var == x ? rhs : NULL;
	if (!side) return 1;
	side->isvec = (side == lhs ? rhs : lhs)->isvec;
	if (map_get(&sema.vector_decls, x->name) && !side->isvec) {
		error_at(q->loc, "'%s' is declared a vector, but \"%s\" makes it a scalar", x->name, q->text);
		return 0;
	}
	x->isvec = side->isvec;
	return 1;
}

/* Do the two sides of q differ, a vector and a scalar? Reports it. */
static int sides_differ(RExpr *lhs, RExpr *rhs, Eqn *q)
{
	if (lhs->isvec == rhs->isvec) return 0;
	/* a side that is a global alone: a name meant for a new value that is already taken (G, c, g) */
	const RExpr *g = lhs->k == R_VAR && lhs->var->kind == V_GLOBAL ? lhs : rhs->k == R_VAR && rhs->var->kind == V_GLOBAL ? rhs : NULL;
	error_at(q->rhs->loc, "the two sides of \"%s\" differ: %s = %s%s%s%s", q->text, lhs->isvec ? "vector" : "scalar",
	         rhs->isvec ? "vector" : "scalar", g ? " ('" : "", g ? g->var->name : "",
	         g ? "' is a global, not a new name: give the value a name of its own)" : "");
	return 1;
}

void resolve_assign(Inst *I, Var *x, RExpr *sol, RExpr *lhs, RExpr *rhs, Eqn *q, int src, Vec *branch, Vec *reads, Vec *rf)
{
	if (sema.shaped && !I->st->has_for && I->nbind > 1 && !(x->kind == V_TEMP && x->pair))
		unshape("a rule over pairs ($1) determines a variable of one object");
	if (sema.shaped && sema_per_member(x) && (var_places(lhs, x) | var_places(rhs, x)) & ~2u)
		unshape("a rule determines a variable of $1");
	if (sema.shaped && I->iloop && x->kind != V_TEMP) /* the members without a binding would keep theirs */
		unshape("a rule among neighbours determines a property");
	Assign *a = xalloc(sizeof *a);
	a->var = x;
	a->e = sol;
	a->src = src;
	a->lhs = lhs;
	a->rhs = rhs;
	a->loc = q->loc;
	a->text = q->text;
	vec_push(branch, a);
	vec_add_new(&I->reads, reads, x);
	vec_add_new(&I->rf_reads, rf, NULL);
	x->det = I;
	for (int i = 0; i < I->targets.n; i++)
		if (I->targets.v[i] == x) return; /* the other branch of a conditional rule: already listed */
	vec_push(&I->targets, x);
	I->why = I->why ? xprintf("%s, %s (%s)", I->why, x->name, class_name(x)) : xprintf("%s (%s)", x->name, class_name(x));
}

/* What resolve_eqn did with an equation. */
enum { EQN_ERROR, EQN_SOLVED, EQN_WAITING };

/*
 * Equation q of instance I reads the temporaries unknowns (two or more) that no rule has
 * determined: it waits for the rules that determine them only together with it (group.c). msg,
 * at at, is the error it is if none does (suggests: it names a misspelling). New temporaries
 * that are a side alone take their type from the other side, and the unknowns are registered,
 * so that later rules read the same ones.
 */
static int wait_eqn(Inst *I, Eqn *q, RExpr *lhs, RExpr *rhs, Vec *reads, Vec *rf, Vec *unknowns, Loc at, const char *msg,
                    int suggests)
{
	for (int i = 0; i < unknowns->n; i++)
		if (!type_new_temp(unknowns->v[i], lhs, rhs, q)) return EQN_ERROR;
	if (sides_differ(lhs, rhs, q)) return EQN_ERROR;
	for (int i = 0; i < unknowns->n; i++) register_temp(unknowns->v[i]);
	group_wait(I, q, lhs, rhs, reads, rf, unknowns, at, msg, suggests);
	return EQN_WAITING;
}

/*
 * Resolves one equation of instance I: chooses the target among the
 * undetermined variables, solves for it, records the assignment. An
 * equation with two unknown temporaries or more waits, if may_wait, for the
 * rules that determine them together with it (group.c). Returns EQN_SOLVED,
 * EQN_WAITING, or EQN_ERROR after reporting an error.
 */
static int resolve_eqn(Inst *I, Eqn *q, Vec *branch, int src, int may_wait)
{
	Vec reads = { 0 }, pending = { 0 }, rf = { 0 }, summed = { 0 };
	Ctx C = inst_ctx(I, &reads, &rf, &pending);
	C.summed = &summed;
	RExpr *lhs = build(&C, q->lhs), *rhs = build(&C, q->rhs);
	if (C.failed) return EQN_ERROR;
	vec_add_new(&I->summed, &summed, NULL);
	if (lhs->isbool || rhs->isbool) {
		error_at(q->loc, "an equation relates values, not conditions");
		return EQN_ERROR;
	}
	Var *x = NULL;
	PSet sums = { 0 };
	for (int i = 0; i < summed.n; i++) pset_add(&sums, summed.v[i]);
	for (int i = 0; i < reads.n; i++) {
		Var *v = reads.v[i];
		if (determined(v) || pset_has(&sums, v)) continue; /* a sum's terms are read, never solved for */
		if (!x || var_class(v) < var_class(x) || (var_class(v) == var_class(x) && v->order > x->order)) x = v;
	}
	pset_free(&sums);
	if (!x) {
		error_at(q->loc, "rule \"%s\" is overdetermined%s%s: every variable in it is already determined", q->text,
		         I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "");
		for (int i = 0; i < reads.n; i++) explain_det(reads.v[i]);
		return EQN_ERROR;
	}
	Var *other = NULL; /* a temporary besides the target that nothing determines: two unknowns */
	for (int i = 0; i < reads.n && !other; i++) {
		Var *v = reads.v[i];
		if (v != x && v->kind == V_TEMP && !determined(v)) other = v;
	}
	if (other) {
		/* the one the equation defines is a bare name on its left side (else the target chosen); the
		   other is unknown, most often a misspelling or another object's temporary */
		Var *want = lhs->k == R_VAR && lhs->var == other ? other : x, *u = want == other ? x : other;
		const char *s = near_name(I, u), *msg;
		Loc at = read_loc(lhs, rhs, u, q->loc);
		if (s)
			msg = xprintf("unknown name '%s' in rule \"%s\"%s%s; did you mean '%s'?", u->name, q->text,
			              I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "", s);
		else
			msg = xprintf("rule \"%s\" is unresolvable%s%s: it solves for %s but also reads %s, which no earlier rule determines",
			              q->text, I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "", want->name, u->name);
		Vec unknowns = { 0 };
		for (int i = 0; i < reads.n; i++) {
			Var *v = reads.v[i];
			if (v->kind == V_TEMP && !determined(v)) vec_push(&unknowns, v);
		}
		if (may_wait && unknowns.n >= 2) return wait_eqn(I, q, lhs, rhs, &reads, &rf, &unknowns, at, msg, s != NULL);
		error_at(at, "%s", msg);
		return EQN_ERROR;
	}
	if (!type_new_temp(x, lhs, rhs, q) || sides_differ(lhs, rhs, q)) return EQN_ERROR;
	if (x->kind == V_TEMP && !map_get(&sema.temps, var_more_of(x)->key)) register_temp(x);
	RExpr *sol = solve(lhs, rhs, x, q->loc, q->text);
	if (!sol) return EQN_ERROR;
	if (sol->isvec != x->isvec) {
		error_at(q->loc, "\"%s\" would make %s a %s, but it is a %s", q->text, var_label(x), sol->isvec ? "vector" : "scalar",
		         x->isvec ? "vector" : "scalar");
		return EQN_ERROR;
	}
	resolve_assign(I, x, sol, lhs, rhs, q, src, branch, &reads, &rf);
	return EQN_SOLVED;
}

static RExpr *build_cond(Inst *I, Expr *cond, const char *what)
{
	Vec reads = { 0 }, pending = { 0 }, rf = { 0 };
	Ctx C = inst_ctx(I, &reads, &rf, &pending);
	RExpr *r = build(&C, cond);
	if (C.failed) return NULL;
	if (!r->isbool) {
		error_at(cond->loc, "%s must be a condition (a comparison)", what);
		return NULL;
	}
	for (int i = 0; i < reads.n; i++) {
		Var *v = reads.v[i];
		if (v->kind == V_TEMP && !determined(v)) {
			error_at(read_loc(r, NULL, v, cond->loc), "%s reads '%s', which no rule determines", what, v->name);
			return NULL;
		}
	}
	vec_add_new(&I->reads, &reads, NULL);
	vec_add_new(&I->rf_reads, &rf, NULL);
	return r;
}

int stmt_src(Stmt *s) { return add_src(s->loc, s->text); }

static Branch *resolve_block(Inst *I, If *f, Vec *flat0, Vec *flat1);

/* Resolves the steps q of a conditional block of I into out, each assignment also into flat.
 * Returns 0 after an error. */
static int resolve_steps(Inst *I, Eqn *q, Vec *out, Vec *flat)
{
	for (; q; q = q->next) {
		if (q->nest) {
			Assign *a = xalloc(sizeof *a);
			a->nest = resolve_block(I, q->nest, flat, flat);
			if (!a->nest) return 0;
			a->loc = q->loc;
			a->text = q->text;
			vec_push(out, a);
			continue;
		}
		if (q->deriv) {
			error_at(q->loc, "a derivative rule cannot be conditional");
			return 0;
		}
		if (resolve_eqn(I, q, out, add_src(q->loc, q->text), 0) != EQN_SOLVED) return 0;
		vec_push(flat, out->v[out->n - 1]);
	}
	return 1;
}

/* Adds to v (once each) the variables steps determine: their assignments' and their blocks'. */
void sema_steps_targets(const Vec *steps, Vec *v)
{
	for (int i = 0; i < steps->n; i++) {
		Assign *a = steps->v[i];
		if (!a->nest) add_unique(v, a->var);
		for (int k = 0; a->nest && k < a->nest->targets.n; k++) add_unique(v, a->nest->targets.v[k]);
	}
}

/* Resolves conditional block f of I; its assignments, at every depth, go also to flat0 (under
 * its condition) and flat1 (not). Returns NULL after an error. */
static Branch *resolve_block(Inst *I, If *f, Vec *flat0, Vec *flat1)
{
	Branch *B = xalloc(sizeof *B);
	B->ast = f;
	B->cond = build_cond(I, f->cond, "the condition of a rule");
	if (!B->cond) return NULL;
	B->src = add_src(f->loc, f->text);
	I->cond = I->cond ? rop(CSF_OP_AND, 0, f->loc, I->cond, B->cond, NULL) : B->cond;
	I->cond->isbool = 1;
	for (int b = 0; b < 2; b++) {
		if (!resolve_steps(I, b ? f->els : f->then, &B->steps[b], b ? flat1 : flat0)) return NULL;
		sema_steps_targets(&B->steps[b], &B->targets);
		/* the other branch must not see this branch's targets as determined */
		for (int i = 0; i < B->targets.n; i++) ((Var *)B->targets.v[i])->det = NULL;
	}
	/* after the block every variable it determines is defined: zero on the paths that do not state it */
	for (int i = 0; i < B->targets.n; i++) ((Var *)B->targets.v[i])->det = I;
	return B;
}

void inst_rule(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->src = sema.cur_src;
	if (!s->eqns->nest) {
		/* a rule with attribute F does not wait: RF, the sum of their forces, is read in their order */
		if (resolve_eqn(I, s->eqns, &I->then, I->src, !I->isF) != EQN_SOLVED) return; /* waiting: group.c goes on */
	} else {
		if (sema.shaped && !s->has_for && nbind > 1) unshape("a conditional rule over pairs ($1)");
		I->top = resolve_block(I, s->eqns->nest, &I->then, &I->els);
		if (!I->top) return;
	}
	if (I->isF)
		for (int i = 0; i < I->targets.n; i++) {
			Var *v = I->targets.v[i];
			if (!v->isvec) {
				error_at(s->loc, "a rule with attribute F must determine a force (a vector); %s is a scalar", v->name);
				return;
			}
		}
	vec_push(sema.cur_insts, I);
}

void inst_deriv(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isderiv = 1;
	if (sema.shaped && !s->has_for && nbind > 1) unshape("a derivative rule over pairs ($1)");
	I->src = sema.cur_src;
	Var *v = prop_of_obj(bind[0], s->eqns->lhs->name);
	if (!v) {
		error_at(s->eqns->lhs->loc, "'%s' is not a property of object '%s': only properties can be integrated",
		         s->eqns->lhs->name, bind[0]->name);
		return;
	}
	if (v->state) {
		error_at(s->loc, "%s already has a derivative rule", var_label(v));
		note_at(v->deriv->st->loc, "the first derivative rule for %s", var_label(v));
		return;
	}
	v->state = 1;
	v->deriv = I;
	for (int q = 1; sema.shaped && q < bind[0]->shape->n; q++) { /* every member's is state (lean ones' again) */
		Var *w = prop_of_obj(bind[0]->shape->members[q], v->name);
		w->state = 1;
		w->deriv = I;
	}
	add_unique(&I->targets, v);
	I->why = xprintf("integrates %s (state variable)", v->name);
	vec_push(&sema.deriv_insts, I);
}

void resolve_deriv(Inst *I)
{
	Eqn *q = I->st->eqns;
	Vec pending = { 0 }, rf = { 0 };
	Ctx C = inst_ctx(I, &I->reads, &rf, &pending);
	RExpr *r = build(&C, q->rhs);
	if (C.failed) return;
	Var *v = I->targets.v[0];
	if (r->isbool || r->isvec != v->isvec) {
		error_at(q->rhs->loc, "the derivative of %s must be a %s", var_label(v), v->isvec ? "vector" : "scalar");
		return;
	}
	for (int i = 0; i < I->reads.n; i++) {
		Var *w = I->reads.v[i];
		if (w->kind == V_TEMP && !determined(w)) {
			const char *s = near_name(I, w);
			Loc at = read_loc(r, NULL, w, q->loc);
			if (s) error_at(at, "unknown name '%s' in rule \"%s\"; did you mean '%s'?", w->name, q->text, s);
			else error_at(at, "rule \"%s\" is unresolvable: it reads '%s', which no rule determines", q->text, w->name);
			return;
		}
	}
	for (int i = 0; i < rf.n; i++) add_unique(&I->rf_reads, rf.v[i]);
	Assign *a = xalloc(sizeof *a);
	a->var = v;
	a->e = r;
	a->src = I->src;
	a->rhs = r;
	a->loc = q->loc;
	a->text = q->text;
	vec_push(&I->then, a);
}

void inst_assert(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isassert = 1;
	I->src = sema.cur_src;
	I->cond = build_cond(I, s->cond, "an assertion");
	if (!I->cond) return;
	vec_push(sema.cur_insts, I);
}

/*
 * stop when COND: a terminal event. COND is one comparison, located in
 * time like a conditional rule's; its instance is computed in RHS (where
 * the runtime reads the guards), never in OUT.
 */
void inst_stop(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isstop = 1;
	I->src = sema.cur_src;
	I->cond = build_cond(I, s->cond, "a stop condition");
	if (!I->cond) return;
	int op = I->cond->k == R_OP ? I->cond->op : -1;
	if (op != CSF_OP_LT && op != CSF_OP_LE && op != CSF_OP_GT && op != CSF_OP_GE) {
		error_at(s->cond->loc, "a stop condition must be one comparison (<, <=, > or >=), located in time as it "
		                       "becomes true (for 'A or B', write 'stop when A' and 'stop when B')");
		return;
	}
	vec_push(sema.cur_insts, I);
}

/*
 * when COND: NAME = EXPR ...: a discrete event. COND is located in time as a
 * conditional rule's is (its comparisons are events); at each instant it
 * becomes true, every EXPR is computed from the values just before, and
 * then each NAME takes its value. NAME is a property or a global that no
 * rule determines: a state variable (its integration restarts from the new
 * value), or latched, piecewise constant. Each binding is an instance of
 * its own (the model is not resolved by shape): its flags and new values
 * have slots of their own.
 */
void inst_when(Stmt *s, Object **bind, int nbind)
{
	unshape("a when block");
	Inst *I = new_inst(s, bind, nbind);
	I->iswhen = 1;
	I->src = sema.cur_src;
	I->cond = build_cond(I, s->cond, "a when condition");
	if (!I->cond) return;
	for (Eqn *q = s->eqns; q; q = q->next) {
		if (q->nest || q->deriv) {
			error_at(q->loc, "a when block holds assignments 'NAME = EXPR', not %s",
			         q->nest ? "an 'if' block (write a second when block)" : "a derivative (that is a rule's: 'rule: v' = a')");
			return;
		}
		Vec lreads = { 0 }, reads = { 0 }, pending = { 0 }, rf = { 0 };
		Ctx L = inst_ctx(I, &lreads, &rf, &pending), C = inst_ctx(I, &reads, &rf, &pending);
		RExpr *lhs = build(&L, q->lhs);
		if (L.failed) return;
		Var *x = lhs->k == R_VAR ? sema_canon(lhs->var) : NULL;
		if (x && x->det) {
			error_at(q->loc, "when block \"%s\" assigns %s, which a rule also determines: a variable is either "
			                 "computed by rules or changed at events", s->text, var_label(x));
			note_at(x->det->st->loc, "%s is determined by this rule", var_label(x));
			return;
		}
		if (!x || x->kind == V_TEMP || x->kind == V_TIME || (x->kind == V_GLOBAL && is_predefined(x->name))) {
			error_at(q->lhs->loc, "a when block assigns a property of an object or a global (it keeps its value "
			                      "between events), not %s",
			         !x                   ? "an expression"
			         : x->kind == V_TEMP ? xprintf("'%s', which is neither a property of %s nor a global", x->name,
			                                       I->bind[0]->name)
			                             : xprintf("the predefined '%s'", x->name));
			return;
		}
		RExpr *rhs = build(&C, q->rhs);
		if (C.failed) return;
		if (rhs->isbool || rhs->isvec != x->isvec) {
			error_at(q->rhs->loc, "'%s' is a %s, and \"%s\" gives it %s", var_label(x), x->isvec ? "vector" : "scalar",
			         q->text, rhs->isbool ? "a condition" : rhs->isvec ? "a vector" : "a scalar");
			return;
		}
		for (int i = 0; i < reads.n; i++) {
			Var *v = reads.v[i];
			if (v->kind == V_TEMP && !determined(v)) {
				error_at(read_loc(rhs, NULL, v, q->loc), "when block \"%s\" reads '%s', which no rule determines",
				         s->text, v->name);
				return;
			}
		}
		vec_add_new(&I->reads, &reads, NULL);
		vec_add_new(&I->rf_reads, &rf, NULL);
		if (!var_more_of(x)->latch) var_more(x)->latch = I;
		Assign *a = xalloc(sizeof *a);
		a->var = x;
		a->e = rhs;
		a->src = I->src;
		a->lhs = lhs;
		a->rhs = rhs;
		a->loc = q->loc;
		a->text = q->text;
		vec_push(&I->then, a);
		add_unique(&I->targets, x);
	}
	vec_push(sema.cur_insts, I);
}
