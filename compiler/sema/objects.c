/*
 * objects.c - objects, kinds and globals from their statements, and the
 * predefined constants; initial values are constant expressions (context.c)
 * folded with the runtime's arithmetic.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_const_mksa.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

int check_name(const char *n, Loc l, const char *what)
{
	if (is_predefined(n)) {
		error_at(l, "'%s' is predefined and cannot name %s", n, what);
		return 0;
	}
	return 1;
}

/* How -D's messages name object o: a member of the array a statement gives every member a value, while it
   does, as any member ("star[i]"). */
static const char *obj_label(const Object *o)
{
	const ObjArray *A = sema.arr_set;
	if (!o) return NULL;
	return A && o->index >= A->first && o->index - A->first <= A->hi - A->lo ? sema.fold_as : o->name;
}

static Var *new_global(const char *name, int isvec, const double *v, Loc l)
{
	Var *g = xalloc(sizeof *g);
	g->kind = V_GLOBAL;
	g->name = (char *)name;
	g->isvec = isvec;
	memcpy(g->init, v, sizeof g->init);
	g->loc = l;
	g->slot = -1;
	g->order = sema.def_counter++;
	vec_push(&sema.M->globals, g);
	map_put(&sema.globals_by_name, g->name, g);
	return g;
}

static void set_dim(Var *v, int k, const double *d)
{
	v->dimk = k;
	if (k == DK_KNOWN) memcpy(v->dim, d, sizeof v->dim);
}

/* A predefined constant: its SI value, converted to the unit system in use. */
static void predefine_const(const char *name, int isvec, const double *si, double dl, double dm, double dt)
{
	Loc none = { 0, 0, 0 };
	double d[CSF_NDIM] = { dl, dm, dt, 0 }, v[3];
	for (int i = 0; i < 3; i++) v[i] = dims_to_system(si[i], d);
	set_dim(new_global(name, isvec, v, none), DK_KNOWN, d);
}

void predefine(void)
{
	sema.M->time = xalloc(sizeof *sema.M->time);
	sema.M->time->kind = V_TIME;
	sema.M->time->name = "t";
	sema.M->time->slot = -1;
	set_dim(sema.M->time, DK_KNOWN, (double[CSF_NDIM]){ 0, 0, 1, 0 });
	predefine_const("g", 1, (double[3]){ 0, 0, -GSL_CONST_MKSA_GRAV_ACCEL }, 1, 0, -2);
	predefine_const("G", 0, (double[3]){ GSL_CONST_MKSA_GRAVITATIONAL_CONSTANT, 0, 0 }, 3, -1, -2);
	predefine_const("c", 0, (double[3]){ GSL_CONST_MKSA_SPEED_OF_LIGHT, 0, 0 }, 1, 0, -1);
	predefine_const("e", 0, (double[3]){ M_E, 0, 0 }, 0, 0, 0);
	predefine_const("pi", 0, (double[3]){ M_PI, 0, 0 }, 0, 0, 0);
}

/*
 * The constant value of x, the value of obj.name (obj NULL: the global
 * name; fold FIX_RUN: the run's name) defined on line. The values it reads
 * are folded into it, so -D cannot set them (Var.fix); *read, if not NULL,
 * gets the first one it read (NULL: none, it is a literal).
 */
RExpr *const_value(Expr *x, Object *obj, const char *name, int fold, int line, int *ok, Var **read)
{
	Ctx C = { 0 };
	C.init = 1;
	C.self = obj;
	C.fold = fold;
	C.fold_obj = obj_label(obj);
	C.fold_name = name;
	C.fold_line = line;
	C.ivar = sema.ivar;
	C.idx = sema.idx;
	RExpr *r = build(&C, x);
	if (read) *read = C.first_read;
	*ok = !C.failed;
	if (*ok && (r->k != R_CONST || r->isbool)) {
		error_at(x->loc, r->isbool ? "a value cannot be a condition" : "this value is not known at compile time");
		*ok = 0;
	}
	return r;
}

Var *prop_of_obj(const Object *o, const char *name)
{
	if (o->lean) o = &o->lean->proto;
	if (o->props.n > PROPS_SCANNED) return map_get(&o->props_by_name, name);
	for (int i = 0; i < o->props.n; i++) {
		Var *v = o->props.v[i];
		if (v->name == name || (v->name[0] == name[0] && !strcmp(v->name, name))) return v;
	}
	return NULL;
}

Object *get_object(const char *name, Loc l)
{
	Object *o = map_get(&sema.objects_by_name, name);
	if (o) return o;
	if (!check_name(name, l, "an object")) return NULL;
	if (map_get(&sema.arrays, name)) {
		ObjArray *A = map_get(&sema.arrays, name);
		error_at(l, "'%s' is an object array: name a member, '%s[%ld]', or every member, '%s[i]'", name, name, A->lo, name);
		return NULL;
	}
	if (map_get(&sema.globals_by_name, name)) {
		error_at(l, "'%s' is a global and cannot name an object", name);
		return NULL;
	}
	o = new_object(name, l);
	map_put(&sema.objects_by_name, o->name, o);
	return o;
}

Object *new_object(const char *name, Loc l)
{
	Object *o = xalloc(sizeof *o);
	o->name = (char *)name;
	o->loc = l;
	o->index = sema.M->objects.n;
	vec_push(&sema.M->objects, o);
	return o;
}

/* v's value, defined on line, is computed from read's (if not NULL): -D cannot set it. */
static void fix_derived(Var *v, Var *read, int line)
{
	if (!read || v->fix == FIX_FOLDED) {
		if (!read && v->fix == FIX_DERIVED) v->fix = FIX_NONE;
		return;
	}
	v->fix = FIX_DERIVED;
	v->fix_obj = obj_label(read->obj);
	v->fix_name = read->name;
	v->fix_line = line;
}

/* May constant r replace the value of v (a kind's default, a predefined constant)? Same type, same
 * dimension. kind: "property" or "" (a global), the word before v's name in the message. */
static int override_ok(Loc l, const char *kind, Var *v, RExpr *r)
{
	if (v->isvec != r->isvec) {
		error_at(l, "%s%s'%s' is a %s; it cannot take a %s", kind, *kind ? " " : "", v->name, v->isvec ? "vector" : "scalar",
		         r->isvec ? "vector" : "scalar");
		return 0;
	}
	if (r->dimk == DK_KNOWN && v->dimk == DK_KNOWN && memcmp(r->dim, v->dim, sizeof v->dim) != 0) {
		error_at(l, "%s%s'%s' is %s; this value is %s", kind, *kind ? " " : "", v->name, dims_describe(v->dim),
		         dims_operand(r, r->dim));
		return 0;
	}
	return 1;
}

/* Property p of o takes the absolute tolerance `atol A` of statement s, if it has one: a positive
 * scalar constant (its dimension is checked against p's by check_atols). */
static void set_atol(Object *o, Var *p, Stmt *s)
{
	if (!s->atol) return;
	int ok;
	RExpr *r = const_value(s->atol, o, s->prop, FIX_NONE, s->prop_loc.line, &ok, NULL);
	if (!ok) return;
	if (r->isvec || !(r->c[0] > 0) || !isfinite(r->c[0])) {
		error_at(s->atol->loc, "the atol of '%s' must be a positive number%s", s->prop,
		         r->isvec ? " (one for every component)" : "");
		return;
	}
	var_more(p)->atol = r;
}

/* Defines or overrides property p of o from a property statement. */
/* The values of property statements that read nothing (no property, global or index name): the
   same for every object, folded once for the million members of an array (a kind's defaults, a
   value every member is given), direct-mapped by the statement. */
#define MEMO_SIZE 256
typedef struct FoldMemo { const Stmt *s; RExpr v; } FoldMemo;

static FoldMemo *memo_of(const Stmt *s)
{
	if (!sema.memo) sema.memo = xalloc(MEMO_SIZE * sizeof *sema.memo);
	return &sema.memo[((uintptr_t)s / sizeof(Stmt)) % MEMO_SIZE];
}

void set_prop(Object *o, Stmt *s, int from_kind)
{
	int ok = 1;
	Var *read = NULL;
	FoldMemo *m = memo_of(s);
	RExpr rv;
	if (m->s == s) rv = m->v;
	else {
		/* the value's expression is folded to a constant and then not needed: one object's
		   values take no memory from the next's */
		ArenaMark mark = arena_mark();
		rv = *const_value(s->value, o, s->prop, FIX_FOLDED, s->prop_loc.line, &ok, &read);
		arena_release(mark);
		if (sema.dims_off) { /* the dimension another member's value had (arrays.c) */
			rv.dimk = sema.dimk;
			memcpy(rv.dim, sema.dim, sizeof rv.dim);
		} else if (sema.arr_stmt) {
			sema.dims_set = 1;
			sema.dimk = rv.dimk;
			memcpy(sema.dim, rv.dim, sizeof rv.dim);
		}
		if (ok && !read && !(sema.ivar && expr_reads_name(s->value, sema.ivar))) *m = (FoldMemo){ s, rv };
	}
	if (!ok) return;
	if (s->isvec && !rv.isvec) {
		error_at(s->value->loc, "property '%s' is declared a vector but its value is a scalar", s->prop);
		return;
	}
	put_prop(o, s->prop, s->prop_loc, s->value->loc, &rv, rv.isvec, from_kind, read, s);
}

/* Appends property p to the properties of o (an object, or an array's proto). */
static void add_prop(Object *o, Var *p)
{
	vec_push(&o->props, p);
	if (o->props.n == PROPS_SCANNED + 1)
		for (int i = 0; i < o->props.n; i++) map_put(&o->props_by_name, ((Var *)o->props.v[i])->name, o->props.v[i]);
	else if (o->props.n > PROPS_SCANNED) map_put(&o->props_by_name, p->name, p);
}

/* A new property name of object o, at l, of value r, in the properties of to (o's, or its array's that
   its members share, o->lean->proto); norders: how many definition orders it takes (Var.order, one per
   member that shares it). */
static Var *new_prop(Object *o, Object *to, const char *name, Loc l, RExpr *r, int isvec, int from_kind, Var *read, Stmt *s,
                     int norders)
{
	Var *p = xalloc(sizeof *p);
	p->kind = V_PROP;
	p->name = (char *)name;
	p->obj = o->lean ? o->lean->owner : o;
	p->isvec = isvec;
	memcpy(p->init, r->c, sizeof p->init);
	p->loc = l;
	p->slot = -1;
	p->order = sema.def_counter;
	sema.def_counter += norders;
	p->from_kind = from_kind;
	fix_derived(p, read, l.line);
	if (r->dimk == DK_KNOWN) set_dim(p, DK_KNOWN, r->dim);
	if (s) set_atol(o, p, s);
	add_prop(to, p);
	/* (by the name's pointer, interned: a million objects' dozen names are a dozen strings) */
	const char **seen = &sema.prop_seen[((uintptr_t)p->name / 16) % PROP_SEEN];
	if (*seen != p->name) map_put(&sema.prop_names, p->name, p);
	*seen = p->name;
	return p;
}

/* Property p of object o takes the value r anew, defined at l (from_kind: as put_prop). */
static void override_prop(Object *o, Var *p, Loc l, RExpr *r, int from_kind, Var *read, Stmt *s)
{
	memcpy(p->init, r->c, sizeof p->init);
	p->loc = l;
	p->from_kind = from_kind;
	fix_derived(p, read, l.line);
	if (r->dimk == DK_KNOWN) set_dim(p, DK_KNOWN, r->dim);
	if (s) set_atol(o, p, s);
}

/* The error of a property defined twice: at l, the first time at first (own_first: the first was
 * one member's own value, the second every member's). */
static void defined_twice(const char *name, const Object *o, Loc l, Loc first, int own_first)
{
	error_at(l, "property '%s' of object '%s' is already defined", name, o->name);
	note_at(first, own_first ? "defined here: one member's own value comes after the value every member takes"
	                         : "defined here");
}

/* Member o's index in its array (Object.lean). */
static size_t member_k(const Object *o) { return (size_t)(o->index - o->lean->first); }

/* Lean member o's value of the property p its array's members share: c. */
static void set_member_value(Var *p, Object *o, const double *c)
{
	size_t w = p->isvec ? 3 : 1, k = member_k(o);
	VarMore *m = var_more(p);
	if (!m->vals) {
		if (!memcmp(c, p->init, w * sizeof *c)) return;
		size_t n = (size_t)(o->lean->hi - o->lean->lo + 1);
		m->vals = xalloc(n * w * sizeof *m->vals);
		for (size_t q = 0; q < n; q++) memcpy(m->vals + q * w, p->init, w * sizeof *c);
	}
	memcpy(m->vals + k * w, c, w * sizeof *c);
}

void array_own(Object *o)
{
	ObjArray *A = o->lean;
	if (!A) return;
	const Vec *P = &A->proto.props;
	size_t k = member_k(o);
	for (int i = 0; i < P->n; i++) {
		Var *p = P->v[i], *q = xalloc(sizeof *q);
		*q = *p;
		q->obj = o;
		q->order = p->order + (int)k;
		q->more = NULL;
		memcpy(q->init, member_init(p, o), (p->isvec ? 3 : 1) * sizeof *q->init);
		if (var_more_of(p)->atol) var_more(q)->atol = var_more_of(p)->atol;
		if (var_more_of(p)->own && var_more_of(p)->own[k].line) q->from_kind = 0, q->loc = var_more_of(p)->own[k];
		add_prop(o, q);
	}
	o->lean = NULL;
	if (A->owner != o) return;
	/* the shared properties belong to the next lean member, if any is left */
	A->owner = NULL;
	long n = A->hi - A->lo + 1;
	for (long j = 1; j < n && !A->owner; j++) {
		Object *m = sema.M->objects.v[A->first + (int)(((long)k + j) % n)];
		if (m->lean) A->owner = m;
	}
	for (int i = 0; A->owner && i < P->n; i++) ((Var *)P->v[i])->obj = A->owner;
}

/* The reads own_later records (malloc'd: they outlive the arena marks they are made in). */
typedef struct OwnRead { Object *o; const char *prop, *fold_obj, *fold_name; int fold, line; } OwnRead;
static OwnRead *own_reads;
static size_t nown, capown;

void own_later(Object *o, const char *prop, int fold, const char *fold_obj, const char *fold_name, int line)
{
	if (nown == capown) {
		capown = capown ? 2 * capown : 16;
		own_reads = xrealloc(own_reads, capown * sizeof *own_reads);
	}
	own_reads[nown++] = (OwnRead){ o, prop, fold_obj, fold_name, fold, line };
}

void own_pending(void)
{
	for (size_t i = 0; i < nown; i++) {
		OwnRead *r = &own_reads[i];
		array_own(r->o);
		Var *v = prop_of_obj(r->o, r->prop);
		if (v && !v->fix) v->fix = r->fold, v->fix_obj = r->fold_obj, v->fix_name = r->fold_name, v->fix_line = r->line;
	}
	nown = 0;
}

/* put_prop for lean member o: 1 if done (or reported), 0 if o needs properties of its own (made, then
   put_prop goes on as for any object). A statement that gives every member a value (sema.arr_stmt)
   sets the shared property's value anew at the first member it reaches, each member's after. */
static int put_lean(Object *o, const char *name, Loc l, Loc at, RExpr *r, int isvec, int from_kind, Var *read, Stmt *s)
{
	Var *p = prop_of_obj(o, name);
	const void *by = sema.arr_stmt;
	size_t k = member_k(o);
	if (!p) {
		if (!by) return 0; /* a property of one member alone */
		/* (each member's is defined after the member before's: orders apart, array_own) */
		p = new_prop(o, &o->lean->proto, name, l, r, isvec, from_kind, read, s, (int)(o->lean->hi - o->lean->lo + 1));
		var_more(p)->by = by;
		return 1;
	}
	const VarMore *m = var_more_of(p);
	int own = m->own && m->own[k].line, fk = own ? 0 : p->from_kind;
	if (by && m->by == by && !own) { /* the statement that set it at another member */
		if (override_ok(at, "property", p, r)) set_member_value(p, o, r->c);
		return 1;
	}
	if (!fk || (fk == 2 && from_kind == 2)) {
		defined_twice(name, o, l, own ? m->own[k] : p->loc, from_kind == 2 && !fk);
		return 1;
	}
	if (!override_ok(at, "property", p, r)) return 1;
	if (by) { /* every member's value anew */
		VarMore *w = var_more(p);
		w->vals = NULL;
		w->by = by;
		override_prop(o, p, l, r, from_kind, read, s);
		return 1;
	}
	/* this member's own value: its own properties if it differs from the others' in more than the value */
	if (read || (s && s->atol) || (r->dimk == DK_KNOWN && p->dimk != DK_KNOWN)) return 0;
	set_member_value(p, o, r->c);
	VarMore *w = var_more(p);
	if (!w->own) w->own = xalloc((size_t)(o->lean->hi - o->lean->lo + 1) * sizeof *w->own);
	w->own[k] = l;
	return 1;
}

void put_prop(Object *o, const char *name, Loc l, Loc at, RExpr *r, int isvec, int from_kind, Var *read, Stmt *s)
{
	if (!check_name(name, l, "a property")) return;
	if (map_get(&sema.globals_by_name, name)) {
		error_at(l, "'%s' is a global constant; a property cannot have the same name", name);
		return;
	}
	if (o->lean) {
		if (put_lean(o, name, l, at, r, isvec, from_kind, read, s)) return;
		array_own(o);
	}
	Var *p = prop_of_obj(o, name);
	if (p) {
		/* the value every member of an array takes (object NAME[i], from_kind 2) gives way to a
		   member's own that follows it (object NAME[K]), as a kind's default does */
		if (!p->from_kind || (p->from_kind == 2 && from_kind == 2)) {
			defined_twice(name, o, l, p->loc, from_kind == 2 && !p->from_kind);
			return;
		}
		if (override_ok(at, "property", p, r)) override_prop(o, p, l, r, from_kind, read, s);
		return;
	}
	new_prop(o, o, name, l, r, isvec, from_kind, read, s, 1);
}

void apply_kind(Object *o, Stmt *s)
{
	Stmt *k = map_get(&sema.kinds, s->prop);
	if (!k) {
		error_at(s->prop_loc, "unknown kind '%s'", s->prop);
		return;
	}
	for (Stmt *p = k->body; p; p = p->next) {
		Var *v = prop_of_obj(o, p->prop);
		/* (a property of lean members that this statement made at another member: this one's value) */
		if (!v || (o->lean && sema.arr_stmt && var_more_of(v)->by == sema.arr_stmt)) {
			set_prop(o, p, 1);
			continue;
		}
		if (v->from_kind || v->dimk != DK_KNOWN) continue;
		if (o->lean && var_more_of(v)->checked == s) continue; /* checked at another member */
		if (o->lean) var_more(v)->checked = s;
		/* set before the kind (a data file's column, say): of the kind's type and dimension */
		int ok;
		ArenaMark mark = arena_mark();
		RExpr r = *const_value(p->value, o, p->prop, FIX_NONE, p->prop_loc.line, &ok, NULL);
		arena_release(mark);
		if (ok && (r.isvec != v->isvec || (r.dimk == DK_KNOWN && memcmp(r.dim, v->dim, sizeof v->dim) != 0))) {
			error_at(v->loc, "property '%s' of '%s': %s here, but kind '%s' makes it %s", p->prop, o->name,
			         v->isvec != r.isvec ? (v->isvec ? "a vector" : "a scalar") : dims_describe(v->dim), s->prop,
			         v->isvec != r.isvec ? (r.isvec ? "a vector" : "a scalar") : dims_describe(r.dim));
			note_at(s->loc, "the kind is given here");
			return;
		}
	}
}

void build_objects(Stmt *stmts)
{
	/* the object of the statement before: a scene written out object by object names one object on
	   several lines in a row (the same name, interned by the scanner), found once */
	Object *last = NULL;
	nown = 0; /* (what another resolution left: its objects are gone) */
	for (Stmt *s = stmts; s; s = s->next, own_pending()) {
		switch (s->kind) {
		case S_GLOBAL: {
			if (!check_name(s->name, s->name_loc, "a global")) break;
			int ok;
			Var *read;
			RExpr *r = const_value(s->value, NULL, s->name, FIX_FOLDED, s->name_loc.line, &ok, &read);
			if (!ok) break;
			Var *g = map_get(&sema.globals_by_name, s->name);
			if (g) {
				if (!override_ok(s->value->loc, "", g, r)) break;
				memcpy(g->init, r->c, sizeof g->init);
				g->loc = s->name_loc;
				fix_derived(g, read, s->name_loc.line);
			} else if (map_get(&sema.objects_by_name, s->name) || map_get(&sema.prop_names, s->name)) {
				error_at(s->name_loc, "'%s' already names an object or a property", s->name);
			} else {
				Var *ng = new_global(s->name, r->isvec, r->c, s->name_loc);
				fix_derived(ng, read, s->name_loc.line);
				set_dim(ng, r->dimk == DK_KNOWN ? DK_KNOWN : DK_UNKNOWN, r->dim);
			}
			break;
		}
		case S_DEF:
			if (map_get(&sema.kinds, s->name)) {
				error_at(s->name_loc, "kind '%s' is already defined", s->name);
				break;
			}
			map_put(&sema.kinds, s->name, s);
			break;
		case S_OBJKIND: {
			if (s->arr) {
				array_stmt(s);
				break;
			}
			if (!map_get(&sema.kinds, s->prop)) {
				error_at(s->prop_loc, "unknown kind '%s'", s->prop);
				break;
			}
			Object *o = last && last->name == s->name ? last : get_object(s->name, s->name_loc);
			if (o) apply_kind(last = o, s);
			break;
		}
		case S_PROP: {
			if (s->arr) {
				array_stmt(s);
				break;
			}
			Object *o = last && last->name == s->name ? last : get_object(s->name, s->name_loc);
			if (o) set_prop(last = o, s, 0);
			break;
		}
		default:
			break;
		}
	}
}
