/*
 * pass.c - the semantic pass: from statements to a resolved model.
 *
 * 1. Objects, kinds and globals are built; initial values are constant
 *    expressions folded with the runtime's own arithmetic (fold_op).
 * 2. Rules are instantiated: a rule applies to every object ($0) and every
 *    permitted tuple ($1..$k, spec 2.2.1) that has the properties it reads,
 *    or to the objects its `for` list names.
 * 3. Derivative rules (`v' = a`) are found first: their left sides become
 *    state variables, determined at the start of every evaluation.
 * 4. The other rules are resolved in source order, except that a rule
 *    reading RF waits until every rule with attribute F has been resolved
 *    (RF is their sum). For each instance the target is chosen by the
 *    precedence of spec 2.4.1 among the variables not yet determined
 *    (unwatched temporary, then property, then global; the later defined
 *    first); none left is "overdetermined", an undetermined temporary read
 *    is "unresolvable". The equation is then solved for the target
 *    symbolically: it must be linear in it. A rule with two unknown
 *    temporaries or more waits for the rules that determine them only
 *    together with it, and is solved with them as one linear system
 *    (group.c); the rules still waiting after the last are reported.
 * 5. Assertions and the watch list are resolved, and the dimensions checked
 *    (dims.c) over every instance that resolved, also after errors; then
 *    gen.c keeps only the instances that the derivatives, the watches and
 *    the assertions need.
 *
 * The pieces: state of the pass (sema_int.h, Sema); fold.c, expr.c: the
 * resolved expressions; context.c: names and types in a resolution context;
 * objects.c: step 1; walk.c, shapes.c, instances.c: step 2; resolve.c,
 * solve.c, group.c: steps 3 and 4; contacts.c: contact rules; constraints.c
 * and diff.c: constraints (rules with attribute C); watch.c: the watch
 * list; this file: the order of it all (resolve, sema_run). --explain is
 * compiler/mid/explain.c.
 */
#include <math.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* The state of the pass: one resolution at a time (sema_reset). */
Sema sema;
/* sema_run's drop: the objects left out, by index (NULL: none) */
static const char *drop_objects;

int sema_dropping(int index) { return drop_objects && drop_objects[index]; }

/* Starts a resolution: nothing defined yet, a new model; shaped: once per shape. */
static void sema_reset(int shaped)
{
	sema = (Sema){ 0 };
	sema.M = xalloc(sizeof *sema.M);
	sema.shaped = shaped;
}

/* Gives up resolving by shape (the model is resolved again, object by object). */
void unshape(const char *why)
{
	if (!sema.unshaped) sema.unshaped = why;
}

static double const_time(Expr *x, double dflt, const char *what)
{
	if (!x) return dflt;
	int ok;
	RExpr *r = const_value(x, NULL, what, FIX_RUN, x->loc.line, &ok, NULL);
	if (!ok) return dflt;
	if (r->isvec || !isfinite(r->c[0]) || r->c[0] < 0) {
		if (!strcmp(what, "by")) error_at(x->loc, "'by' must be a positive time");
		else error_at(x->loc, "'%s' needs a finite, non-negative time", what);
		return dflt;
	}
	/* a pure number is a time in the unit system's seconds (till 2*pi, till pi) */
	if (r->dimk == DK_KNOWN && !dims_none(r->dim) && (r->dim[0] != 0 || r->dim[1] != 0 || r->dim[2] != 1 || r->dim[3] != 0)) {
		error_at(x->loc, "'%s' needs a time, not %s", what, dims_operand(r, r->dim));
		return dflt;
	}
	return r->c[0];
}

/*
 * One walk over the statements (a scene written out object by object has a million): checks their
 * order (objects, then rules, then the start directive), and collects the rules, assertions, stops
 * and `when` blocks (sema.M->stmts; the rules also in rules) and the vector declarations. Returns
 * the last start directive (NULL: none).
 */
static Stmt *sections(Stmt *stmts, Vec *rules)
{
	int section = 0; /* 0 objects, 1 rules, 2 start */
	Stmt *first_start = NULL, *start = NULL;
	int check = 1;
	for (Stmt *s = stmts; s; s = s->next) {
		int rule_sec = s->kind == S_RULE || s->kind == S_ASSERT || s->kind == S_STOP || s->kind == S_WHEN ||
		               s->kind == S_VECDECL;
		int sec = s->kind == S_START ? 2 : rule_sec ? 1 : 0;
		if (check && first_start) {
			error_at(s->loc, "the start directive ('inc ...') must be the last statement");
			note_at(first_start->loc, "start directive here");
			check = 0;
		}
		if (check && sec < section) {
			error_at(s->loc, "%s must come before the rules (objects, then rules, then the start directive)",
			         s->kind == S_DEF ? "a kind definition" : s->kind == S_GLOBAL ? "a global" : "an object definition");
		}
		if (sec > section) section = sec;
		if (s->kind == S_START && !first_start) first_start = s;
		if (s->kind == S_START) start = s;
		if (s->kind == S_VECDECL)
			for (int i = 0; i < s->names.n; i++) map_put(&sema.vector_decls, s->names.v[i], s);
		if (s->kind == S_RULE || s->kind == S_ASSERT || s->kind == S_STOP || s->kind == S_WHEN) vec_push(&sema.M->stmts, s);
		if (s->kind == S_RULE) vec_push(rules, s);
	}
	return start;
}

/* Every `atol A` is on a state variable's line, with the variable's dimension (a bare A takes it). */
static void check_atols(Model *M)
{
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		for (int j = 0; j < P->n && !obj_shares(o); j++) {
			Var *v = P->v[j];
			RExpr *a = var_more_of(v)->atol;
			if (!a) continue;
			if (!v->state)
				error_at(a->loc, "'atol' is the absolute tolerance of a state variable, and '%s' of '%s' has no "
				         "derivative rule", v->name, o->name);
			else if (a->dimk == DK_KNOWN && v->dimk == DK_KNOWN && memcmp(a->dim, v->dim, sizeof v->dim) != 0)
				error_at(a->loc, "the atol of '%s' must be %s, as '%s' is, not %s", v->name, dims_describe(v->dim),
				         v->name, dims_operand(a, a->dim));
		}
	}
}

/* Does I read temporary v of D, a rule that is one loop (Inst.iloop), in the same loop and only at
   the member that D determines it for? (By shape, the members past D's bindings have none.) */
static int same_loop(const Inst *I, const Inst *D, const Var *v)
{
	if (I->iloop != D->iloop || I->idx != D->idx || !I->iloop) return 0;
	unsigned places = 0;
	for (int k = 0; k < I->then.n; k++) places |= var_places(((Assign *)I->then.v[k])->e, v);
	for (int p = 0; p < I->nbind; p++)
		if (places & 1u << (p + 1) && I->bind[p] != D->bind[0]) return 0;
	return !(places & 1u); /* not as a named object's */
}

static Model *resolve(Stmt *stmts, int shaped)
{
	sema_reset(shaped);
	predefine();
	Vec rules = { 0 };
	Stmt *start = sections(stmts, &rules);
	build_objects(stmts);
	for (int i = 0; drop_objects && i < sema.M->objects.n; i++)
		if (drop_objects[i]) ((Object *)sema.M->objects.v[i])->dropped = 1, sema.M->ndropped++;

	if (!start) {
		Loc end = { 0, 1, 1 };
		for (Stmt *s = stmts; s; s = s->next) end = s->loc;
		if (stmts) error_at(end, "no start directive: the model must end with 'inc t till TIME by STEP watch ...'");
		else error_plain("%s: empty model: there is nothing to simulate", ((Source *)sources.v[0])->path);
	} else {
		if (strcmp(start->var, "t") != 0) error_at(start->name_loc, "only time can be incremented: write 'inc t ...'");
		sema.M->till = const_time(start->till, 10, "till");
		sema.M->by = const_time(start->by, sema.M->till > 0 ? sema.M->till / 1000 : 0.01, "by");
		double most = opts.max_rows > 0 ? opts.max_rows : CSF_MAX_ROWS;
		if (!(sema.M->by > 0)) error_at(start->by ? start->by->loc : start->loc, "'by' must be a positive time");
		else if (sema.M->till / sema.M->by > most)
			error_at(start->till ? start->till->loc : start->loc,
			         "'till %g' by '%g' asks for %.3g rows of output, more than the limit of %.3g "
			         "(csfc --max-rows N raises it)", sema.M->till, sema.M->by, sema.M->till / sema.M->by, most);
		sema.M->start = start;
	}
	if (diag_errors) return sema.M;
	build_shapes(start);
	for (int i = 0; start && i < start->watch.n; i++) {
		WatchItem *w = start->watch.v[i];
		map_put(&sema.watched, w->obj ? xprintf("%s\x01%s", w->obj, w->prop) : w->prop, w);
	}

	/* Derivative rules first: their targets are state, determined from the start. */
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->eqns && s->eqns->deriv && !(s->attr && !strcmp(s->attr, "C"))) {
			sema.cur_src = stmt_src(s);
			for_each_binding(s, inst_deriv);
		}
	}
	/* Algebraic rules in order; those reading RF after the last F rule. */
	int lastF = -1;
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->attr && strcmp(s->attr, "F") == 0) lastF = i;
	}
	Vec order = { 0 }, deferred = { 0 };
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->eqns && s->eqns->deriv && !(s->attr && !strcmp(s->attr, "C"))) continue;
		if (i < lastF && stmt_reads_rf(s) && !(s->attr && strcmp(s->attr, "F") == 0)) vec_push(&deferred, s);
		else vec_push(&order, s);
		if (i == lastF)
			for (int k = 0; k < deferred.n; k++) vec_push(&order, deferred.v[k]);
	}
	sema.cur_insts = &sema.M->insts;
	for (int i = 0; i < order.n; i++) {
		Stmt *s = order.v[i];
		if (s->attr && strcmp(s->attr, "F") == 0 && stmt_reads_rf(s)) {
			error_at(s->loc, "a rule with attribute F cannot read RF: RF is the sum of the F rules");
			continue;
		}
		sema.cur_src = stmt_src(s);
		int con = is_constraint(s);
		if (con) {
			if (con > 0) {
				unshape("a constraint (rule C)");
				for_each_binding(s, inst_constraint);
			}
			continue;
		}
		if (!s->call) for_each_binding(s, inst_rule);
		else if (check_call(s)) {
			if (s->has_for) for_each_binding(s, inst_contact);
			else contact_pairs(s);
		}
	}
	group_finish();
	contact_accels();
	constraints_finish();
	for (int i = 0; i < sema.deriv_insts.n; i++) {
		resolve_deriv(sema.deriv_insts.v[i]);
		vec_push(&sema.M->insts, sema.deriv_insts.v[i]);
	}
	for (int i = 0; i < sema.M->stmts.n; i++) {
		Stmt *s = sema.M->stmts.v[i];
		if (s->kind != S_ASSERT && s->kind != S_STOP && s->kind != S_WHEN) continue;
		sema.cur_src = add_src(s->loc, s->text);
		for_each_binding(s, s->kind == S_STOP ? inst_stop : s->kind == S_WHEN ? inst_when : inst_assert);
	}
	build_watch(start);
	/* by shape, a temporary of a pair lives for one iteration of its rule's loop */
	for (int i = 0; sema.shaped && i < sema.M->insts.n; i++) {
		Inst *I = sema.M->insts.v[i];
		for (int k = 0; k < I->reads.n; k++) {
			Var *v = I->reads.v[k];
			if (v->kind == V_TEMP && v->pair && v->det != I) unshape("a temporary of a pair ($1) read by another rule");
			if (v->kind == V_TEMP && v->det && v->det->iloop && v->det != I && !same_loop(I, v->det, v))
				unshape("a temporary of a rule among neighbours read by another rule");
		}
	}
	/* Also after errors: the instances that failed are left out, and the dimensions of the
	 * others are checked all the same, so one run reports both kinds of error. */
	dims_check(sema.M);
	check_atols(sema.M);
	return sema.M;
}

/*
 * Resolves by shape first, silently; a model that cannot be resolved that way
 * (unshape), or that has an error, is resolved again object by object, which
 * reports the errors as they have always been reported. With drop (a model
 * already resolved whole, now without the objects mid/cone.c leaves out),
 * both are silent, and an error returns NULL: the whole model stands.
 */
Model *sema_run(Stmt *stmts, const char *drop)
{
	FILE *saved = diag_out, *null = fopen("/dev/null", "w");
	int errors = diag_errors, stop = diag_stop;
	const char *why = "";
	Model *m = NULL;
	if (drop && !null) return NULL;
	drop_objects = drop;
	if (null) {
		diag_out = null;
		ArenaMark mark = arena_mark();
		m = resolve(stmts, 1);
		if (!sema.unshaped && diag_errors == errors) m->shaped = 1;
		else {
			why = sema.unshaped ? sema.unshaped : ""; /* a literal */
			arena_release(mark);
			diag_errors = errors;
			diag_stop = stop;
			m = NULL;
		}
		diag_out = drop ? null : saved;
	}
	if (!m) {
		m = resolve(stmts, 0);
		m->unshaped_why = why;
		if (drop && diag_errors != errors) {
			diag_errors = errors;
			diag_stop = stop;
			m = NULL;
		}
	}
	diag_out = saved;
	if (null) fclose(null);
	drop_objects = NULL;
	return m;
}
