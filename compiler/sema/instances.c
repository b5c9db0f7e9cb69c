/*
 * instances.c - rule instances: which bindings ($0, $1..$k, or a `for` list)
 * a rule, an assertion or a stop condition applies to, and what an instance
 * is; whether a variable is determined yet.
 */
#include <limits.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

static int max_dollar(Expr *x)
{
	if (!x) return 0;
	int m = x->kind == E_DOLLAR ? x->n : 0;
	int a = max_dollar(x->a), b = max_dollar(x->b);
	if (a > m) m = a;
	if (b > m) m = b;
	for (int i = 0; i < x->nargs; i++) {
		int c = max_dollar(x->args[i]);
		if (c > m) m = c;
	}
	return m;
}

static int reads_rf(Expr *x)
{
	if (!x) return 0;
	if (x->kind == E_NAME && strcmp(x->name, "RF") == 0) return 1;
	if (reads_rf(x->a) || reads_rf(x->b)) return 1;
	for (int i = 0; i < x->nargs; i++)
		if (reads_rf(x->args[i])) return 1;
	return 0;
}

/* Raises *(int *)most to x's highest $n. Returns 1. */
static int raise_dollar(Expr *x, void *most)
{
	int k = max_dollar(x);
	if (k > *(int *)most) *(int *)most = k;
	return 1;
}

static int stmt_max_dollar(Stmt *s)
{
	int m = 0;
	stmt_each(s, raise_dollar, &m);
	return m;
}

static int no_rf(Expr *x, void *ctx)
{
	(void)ctx;
	return !reads_rf(x);
}

int stmt_reads_rf(Stmt *s) { return !stmt_each(s, no_rf, NULL); }

/* Does every name the statement reads exist for this binding? (Without reporting.) Each name is
 * checked on one object of the binding; a NULL in bind passes every name checked on it. */
static int names_apply(Expr *x, Object **bind, int nbind, const char **missing)
{
	if (!x) return 1;
	if (x->kind == E_SUM || x->kind == E_INDEX || (x->kind == E_FIELD && x->a->kind == E_INDEX)) return 1; /* members' */
	if (x->kind == E_NAME && sema.ivar && !strcmp(x->name, sema.ivar)) return 1;
	if (x->kind == E_NAME || x->kind == E_DOLLAR) {
		Object *o = x->kind == E_DOLLAR ? (x->n < nbind ? bind[x->n] : NULL) : bind[0];
		if (!o) return 1;
		if (x->kind == E_NAME && (is_predefined(x->name) || map_get(&sema.globals_by_name, x->name))) return 1;
		if (map_get(&sema.prop_names, x->name) && !prop_of_obj(o, x->name)) {
			*missing = x->name;
			return 0;
		}
		return 1;
	}
	if (x->kind == E_FIELD && x->a->kind == E_NAME && map_get(&sema.objects_by_name, x->a->name) &&
	    (!bind[0] || !prop_of_obj(bind[0], x->a->name)))
		return 1;
	if (!names_apply(x->a, bind, nbind, missing) || !names_apply(x->b, bind, nbind, missing)) return 0;
	for (int i = 0; i < x->nargs; i++)
		if (!names_apply(x->args[i], bind, nbind, missing)) return 0;
	return 1;
}

typedef struct Applies { Object **bind; int nbind; const char **missing; } Applies;

static int applies(Expr *x, void *ctx)
{
	Applies *a = ctx;
	return names_apply(x, a->bind, a->nbind, a->missing);
}

static int stmt_applies(Stmt *s, Object **bind, int nbind, const char **missing)
{
	Applies a = { bind, nbind, missing };
	return stmt_each(s, applies, &a);
}

/* The bindings of a rule: $0 any object, $1..$k other objects in ascending order (spec 2.2.1).
 * stmt_applies is a conjunction of conditions each on one place of the tuple, so only the
 * objects fit for each place are tried, and every tuple of them applies. */
typedef struct Tuples {
	Stmt *s;
	void (*f)(Stmt *, Object **, int);
	int k;
	int **fit;     /* [0..k]: the indices of the objects fit for $j, ascending */
	int *nfit;     /* [0..k]: how many */
	Object **cur;  /* the tuple being built */
	int count;     /* how many tuples f was called for */
	int failed;    /* f reported an error */
} Tuples;

/* The position of the first value greater than x in the ascending array v[0..n). */
static int first_greater(const int *v, int n, int x)
{
	int lo = 0, hi = n;
	while (lo < hi) {
		int mid = lo + (hi - lo) / 2;
		if (v[mid] > x) hi = mid;
		else lo = mid + 1;
	}
	return lo;
}

/* Binds $j..$k in ascending order to objects of index greater than `after`, then calls f. */
static void bind_from(Tuples *T, int j, int after)
{
	if (j > T->k) {
		Object **bind = xalloc((size_t)(T->k + 1) * sizeof *bind);
		memcpy(bind, T->cur, (size_t)(T->k + 1) * sizeof *bind);
		int before = diag_errors;
		T->f(T->s, bind, T->k + 1);
		T->count++;
		T->failed = diag_errors > before; /* one report per statement, not per object */
		return;
	}
	for (int i = first_greater(T->fit[j], T->nfit[j], after); i < T->nfit[j] && !T->failed; i++) {
		if (T->fit[j][i] == T->cur[0]->index) continue;
		T->cur[j] = sema.M->objects.v[T->fit[j][i]];
		/* by shape: $1 is another shape's representative, or the second member of $0's */
		if (sema.shaped && T->cur[j]->sidx == 1 && T->cur[j]->shape != T->cur[0]->shape) continue;
		bind_from(T, j + 1, T->fit[j][i]);
	}
}

/* An upper bound of the tuples bind_from makes (exact but for $0's exclusion from $1..$k): the objects
 * fit for $0 times the ascending chains through the lists fit for $1..$k, counted from the last list
 * back with suffix sums, in O(k n log n). */
static double count_tuples(const Tuples *T)
{
	if (T->k == 0) return T->nfit[0];
	int nobj = sema.M->objects.n;
	double *next = xalloc(((size_t)nobj + 1) * sizeof *next), *cur = xalloc(((size_t)nobj + 1) * sizeof *cur);
	for (int i = T->nfit[T->k]; i >= 0; i--) next[i] = T->nfit[T->k] - i; /* suffix sums of ones */
	for (int j = T->k - 1; j >= 1; j--) {
		cur[T->nfit[j]] = 0;
		for (int i = T->nfit[j] - 1; i >= 0; i--)
			cur[i] = cur[i + 1] + next[first_greater(T->fit[j + 1], T->nfit[j + 1], T->fit[j][i])];
		double *x = next;
		next = cur;
		cur = x;
	}
	return (double)T->nfit[0] * next[0];
}

/* Does x read nothing of a binding: only numbers, globals, t, the index name, NAME.PROP, NAME[K].PROP and sums? */
static int binding_free(Expr *x, void *ctx)
{
	(void)ctx;
	if (!x || x->kind == E_SUM || (x->kind == E_FIELD && x->a->kind == E_INDEX)) return 1;
	if (x->kind == E_DOLLAR) return 0;
	if (x->kind == E_NAME)
		return !strcmp(x->name, "t") || map_get(&sema.globals_by_name, x->name) || (sema.ivar && !strcmp(x->name, sema.ivar));
	if (x->kind == E_FIELD && x->a->kind == E_NAME && map_get(&sema.objects_by_name, x->a->name) &&
	    !map_get(&sema.globals_by_name, x->a->name))
		return 1;
	if (!binding_free(x->a, NULL) || !binding_free(x->b, NULL)) return 0;
	for (int i = 0; i < x->nargs; i++)
		if (!binding_free(x->args[i], NULL)) return 0;
	return 1;
}

/* The binding of rule s's `for` list (with the index binding of sema, if any): calls f; returns 1, 0 if
 * the rule is left out with an object (mid/cone.c), -1 after an error. */
static int bind_for(Stmt *s, void (*f)(Stmt *, Object **, int), int k)
{
	int n = s->fors.n;
	const char *missing = NULL;
	Object **bind = xalloc((size_t)n * sizeof *bind);
	for (int i = 0; i < n; i++) {
		ObjRef *r = s->fors.v[i];
		Object *o = objref_object(r);
		if (!o) return -1;
		if (o->dropped) return 0; /* left out (mid/cone.c), and so is the rule for it */
		for (int j = 0; j < i; j++)
			if (bind[j] == o) {
				error_at(r->loc, "object '%s' is named twice in 'for'", o->name);
				return -1;
			}
		bind[i] = o;
	}
	if (k >= n) {
		error_at(s->loc, "the rule reads $%d but 'for' names only %d object%s", k, n, n == 1 ? "" : "s");
		return -1;
	}
	if (!stmt_applies(s, bind, n, &missing)) {
		error_at(s->loc, "this rule reads '%s', which object '%s' does not have", missing, bind[0]->name);
		return -1;
	}
	f(s, bind, n);
	return 1;
}

/* Calls f for every binding the statement applies to; returns how many, -1 after an error. */
int for_each_binding(Stmt *s, void (*f)(Stmt *, Object **, int))
{
	int k = stmt_max_dollar(s);
	int nobj = sema.M->objects.n;
	const char *missing = NULL;
	if (s->has_for && s->loop) { /* one loop: one instance, bound to the members of the first binding */
		sema.ivar = s->ivar;
		sema.idx = s->loop_from;
		sema.iloop = s->loop;
		int r = bind_for(s, f, k);
		sema.ivar = NULL;
		sema.iloop = 0;
		return r < 0 ? -1 : r > 0 ? (s->loop > INT_MAX ? INT_MAX : (int)s->loop) : 0;
	}
	if (s->has_for) {
		int ix = for_indexed(s);
		long from = 0, to = 0, count = 0;
		if (ix < 0 || (ix && !for_index_range(s, &from, &to))) return -1;
		for (long i = from; i <= to; i++) {
			sema.ivar = ix ? s->ivar : NULL;
			sema.idx = i;
			int before = diag_errors, r = bind_for(s, f, k);
			sema.ivar = NULL;
			if (r < 0 || diag_errors > before) return -1; /* one report, not one per member */
			count += r;
		}
		return count > INT_MAX ? INT_MAX : (int)count;
	}
	if (s->kind != S_RULE || !s->call) {
		s->once = k == 0 && stmt_each(s, binding_free, NULL);
		for (int i = 0; s->once && i < nobj; i++) {
			Object *o = sema.M->objects.v[i];
			if (o->dropped) continue;
			Object **bind = xalloc(sizeof *bind);
			bind[0] = o;
			f(s, bind, 1);
			return 1;
		}
	}
	Tuples T = { s, f, k, xalloc((size_t)(k + 1) * sizeof(int *)), xalloc((size_t)(k + 1) * sizeof(int)),
		     xalloc((size_t)(k + 1) * sizeof(Object *)), 0, 0 };
	if (sema.shaped && k > 1) unshape("a rule over $1..$k, k > 1");
	for (int j = 0; j <= k && k < nobj; j++) { /* a tuple has k + 1 different objects */
		T.fit[j] = xalloc((size_t)nobj * sizeof(int));
		for (int i = 0; i < nobj; i++) {
			/* by shape: the representatives, and for $1 the second members */
			if (sema.shaped && ((Object *)sema.M->objects.v[i])->sidx > (j ? 1 : 0)) continue;
			if (((Object *)sema.M->objects.v[i])->dropped) continue;
			T.cur[j] = sema.M->objects.v[i];
			if (stmt_applies(s, T.cur, k + 1, &missing)) T.fit[j][T.nfit[j]++] = i;
			T.cur[j] = NULL;
		}
	}
	double n = count_tuples(&T);
	long most = opts.max_tuples > 0 ? opts.max_tuples : CSF_MAX_TUPLES;
	if (n > (double)most) {
		error_at(s->loc, "this %s applies to %.3g tuples of objects ($0..$%d), more than the %ld that one rule may "
		         "have: name the objects with 'for', or write fewer objects", s->kind == S_ASSERT ? "assertion" : "rule",
		         n, k, most);
		return -1;
	}
	for (int i = 0; i < T.nfit[0] && !T.failed; i++) {
		T.cur[0] = sema.M->objects.v[T.fit[0][i]];
		bind_from(&T, 1, -1);
	}
	if (T.failed) return -1;
	if (T.count == 0 && sema.M->ndropped) return 0; /* it applied to objects left out (mid/cone.c) */
	if (T.count == 0 && !s->call) { /* contact rules: a scene may have no pair that can touch */
		/* the name to report is the one the last tuple lacks: ($0, $1, ..., $k) = (last, last - k, ..., last - 1) */
		missing = NULL;
		if (k < nobj) {
			T.cur[0] = sema.M->objects.v[nobj - 1];
			for (int j = 1; j <= k; j++) T.cur[j] = sema.M->objects.v[nobj - 1 - k + j - 1];
			stmt_applies(s, T.cur, k + 1, &missing);
		}
		const char *what = s->kind == S_ASSERT ? "assertion" : s->kind == S_STOP ? "stop condition"
		                   : s->kind == S_WHEN ? "when block" : "rule";
		if (missing) error_at(s->loc, "this %s applies to no object: none has '%s'", what, missing);
		else error_at(s->loc, "this %s applies to no object", what);
		return -1;
	}
	return T.count;
}

int add_src(Loc l, char *text)
{
	SrcEntry *e = xalloc(sizeof *e);
	e->loc = l;
	e->text = text;
	vec_push(&sema.M->srcs, e);
	return sema.M->srcs.n - 1;
}

Inst *new_inst(Stmt *s, Object **bind, int nbind)
{
	Inst *I = xalloc(sizeof *I);
	I->st = s;
	I->bind = bind;
	I->nbind = nbind;
	I->assert_index = -1;
	I->isF = s->attr && strcmp(s->attr, "F") == 0;
	I->ivar = sema.ivar;
	I->idx = sema.idx;
	I->iloop = sema.iloop;
	return I;
}

const char *var_label(Var *v)
{
	if (!v->obj) return v->name;
	return xprintf("%s.%s", v->obj->name, v->name);
}

int determined(Var *v)
{
	v = sema_canon(v);
	return v->kind == V_TIME || v->state || v->det != NULL;
}

Var *sema_canon(Var *v)
{
	if (!v || v->kind != V_PROP || !v->obj->shape || v->obj->sidx == 0) return v;
	Var *r = prop_of_obj(v->obj->shape->members[0], v->name);
	return r ? r : v;
}

int sema_per_member(const Var *v)
{
	return v->obj && v->obj->shape && v->obj->shape->n > 1 && (v->kind == V_PROP || (v->kind == V_TEMP && !v->pair));
}

/* The places ($n) at which e reads x, as bits 1 << (place + 1). */
unsigned var_places(const RExpr *e, const Var *x)
{
	if (!e) return 0;
	if (e->k == R_VAR) return e->var == x ? 1u << (e->place + 1) : 0;
	unsigned m = 0;
	for (int i = 0; i < 3; i++) m |= var_places(e->a[i], x);
	return m;
}

void explain_det(Var *v)
{
	if (v->kind == V_TIME) return;
	if (v->state) {
		Inst *d = v->deriv;
		note_at(d->st->loc, "%s is a state variable, integrated by this rule", var_label(v));
	} else if (v->det) {
		note_at(v->det->st->loc, "%s is determined by this rule", var_label(v));
	}
}
