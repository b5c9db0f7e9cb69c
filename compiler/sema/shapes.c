/*
 * shapes.c - the objects grouped into shapes (sema.h): a rule is resolved once
 * per shape, for its representative.
 */
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* Set while the statement walked is one loop over its bindings (Stmt.loop): the members it names by
   the index name stay in their shape. */
static int in_loop_stmt;

/* Marks in named the members of array name: member idx if it is a number, else every member. */
static void mark_members(const char *name, Expr *idx, Map *named)
{
	ObjArray *A = array_of(name);
	if (!A || (idx && idx->kind != E_NUM && in_loop_stmt)) return;
	for (long k = A->lo; k <= A->hi; k++) {
		if (idx && idx->kind == E_NUM && idx->num != (double)k) continue;
		Object *o = array_member(A, k);
		map_put(named, o->name, o);
	}
}

/* Marks in named (a Map) the objects expression x names (NAME.PROP, NAME[K].PROP; not the members of a
   sum, which reads each member's own slot of its shape's arrays). Returns 1. */
static int mark_named(Expr *x, void *named)
{
	if (!x) return 1;
	if (x->kind == E_INDEX) mark_members(x->name, x->a, named);
	if (x->kind == E_FIELD && x->a->kind == E_NAME) {
		Object *o = map_get(&sema.objects_by_name, x->a->name);
		if (o) map_put(named, o->name, o);
	}
	mark_named(x->a, named);
	mark_named(x->b, named);
	for (int i = 0; i < x->nargs; i++) mark_named(x->args[i], named);
	return 1;
}

/* Do a and b have the same signature (group): the same properties' names, types, dimension kinds and
 * dimensions (their bits), in the same order? */
static int same_signature(const Object *a, const Object *b)
{
	const Vec *P = obj_props(a), *Q = obj_props(b);
	if (P == Q) return 1; /* lean members of one array */
	if (P->n != Q->n) return 0;
	for (int j = 0; j < P->n; j++) {
		const Var *v = P->v[j], *w = Q->v[j];
		if ((v->name != w->name && strcmp(v->name, w->name)) || v->isvec != w->isvec || v->dimk != w->dimk ||
		    memcmp(v->dim, w->dim, sizeof v->dim))
			return 0;
	}
	return 1;
}

/* Groups the objects not in named into shapes by their signatures (build_shapes). */
static void group(Map *named)
{
	Map by_sig = { 0 };
	Object *prev = NULL; /* the last object grouped by its signature: the next often has the same */
	sema.M->shapes.n = 0;
	for (int i = 0; i < sema.M->objects.n; i++) {
		Object *o = sema.M->objects.v[i];
		char *sig = NULL;
		ArenaMark mark = arena_mark();
		int by_sig_ok = sema.shaped && !map_get(named, o->name) && !o->dropped;
		if (by_sig_ok && prev && same_signature(prev, o)) {
			o->shape = prev->shape;
			o->sidx = o->shape->n++;
			continue;
		}
		if (by_sig_ok) {
			prev = o;
			/* each property: its name, then type, dimension kind and dimension as hex digits */
			const Vec *P = obj_props(o);
			size_t len = 0;
			for (int j = 0; j < P->n; j++) len += strlen(((Var *)P->v[j])->name) + 1 + 2 * (2 + CSF_NDIM * 8);
			char *at = sig = xalloc(len + 1);
			for (int j = 0; j < P->n; j++) {
				Var *v = P->v[j];
				unsigned char bits[2 + CSF_NDIM * 8] = { (unsigned char)v->isvec, (unsigned char)v->dimk };
				memcpy(bits + 2, v->dim, sizeof v->dim);
				size_t n = strlen(v->name);
				memcpy(at, v->name, n);
				at += n;
				*at++ = ':';
				for (size_t k = 0; k < sizeof bits; k++) {
					*at++ = "0123456789abcdef"[bits[k] >> 4];
					*at++ = "0123456789abcdef"[bits[k] & 15];
				}
			}
		}
		Shape *S = sig ? map_get(&by_sig, sig) : NULL;
		if (S) arena_release(mark); /* the signature of a known shape is not kept */
		if (!S) {
			S = xalloc(sizeof *S);
			S->index = sema.M->shapes.n;
			vec_push(&sema.M->shapes, S);
			if (sig) map_put(&by_sig, sig, S);
		}
		o->shape = S;
		o->sidx = S->n++;
	}
	for (int i = 0; i < sema.M->shapes.n; i++) ((Shape *)sema.M->shapes.v[i])->members = NULL;
	int *fill = xalloc((size_t)sema.M->shapes.n * sizeof *fill);
	for (int i = 0; i < sema.M->objects.n; i++) {
		Object *o = sema.M->objects.v[i];
		if (!o->shape->members) o->shape->members = xalloc((size_t)o->shape->n * sizeof(Object *));
		o->shape->members[fill[o->shape->index]++] = o;
	}
	/* the properties lean members share belong to the first of them that is not left out (in their shape,
	   the representative's stand for them, sema_canon) */
	for (int i = 0; i < sema.array_list.n; i++) {
		ObjArray *A = sema.array_list.v[i];
		for (long k = 0; A->owner && k <= A->hi - A->lo; k++) {
			Object *o = array_member(A, A->lo + k);
			if (o->lean && !o->dropped) {
				A->owner = o;
				break;
			}
		}
		for (int j = 0; A->owner && j < A->proto.props.n; j++) ((Var *)A->proto.props.v[j])->obj = A->owner;
	}
}

/* The objects in named have properties of their own, not their array's. */
static void own_named(Map *named)
{
	for (size_t i = 0; i < named->cap; i++)
		if (named->keys[i]) array_own(named->vals[i]);
}

/*
 * Groups the objects into shapes: by the names, types and dimensions of
 * their properties, in order (what decides which rules apply to an object
 * and how each resolves). By object (not shaped), or when a rule, a `for`
 * list or the watch list names the object and one of its temporaries, an
 * object is a shape of its own.
 */
void build_shapes(Stmt *start)
{
	Map named = { 0 };
	for (int i = 0; i < sema.M->stmts.n; i++) { /* the rules and assertions */
		Stmt *s = sema.M->stmts.v[i];
		s->loop = sema.shaped ? for_loopable(s, &s->loop_from) : 0;
		in_loop_stmt = s->loop > 0;
		stmt_each(s, mark_named, &named);
		for (int i = 0; i < s->fors.n; i++) {
			ObjRef *r = s->fors.v[i];
			if (r->idx) {
				mark_members(r->name, r->idx, &named);
				continue;
			}
			Object *o = r->name ? map_get(&sema.objects_by_name, r->name)
			                    : (r->index < sema.M->objects.n ? sema.M->objects.v[r->index] : NULL);
			if (o) map_put(&named, o->name, o);
		}
		in_loop_stmt = 0;
	}
	for (int i = 0; start && i < start->watch.n; i++) {
		WatchItem *w = start->watch.v[i];
		Object *o = w->obj ? object_named(w->obj) : NULL;
		if (o && !prop_of_obj(o, w->prop)) map_put(&named, o->name, o);
	}
	/* a loop over neighbours needs its array's members in one shape, in index order: where they are
	   not (some named, left out, or of other properties), its rule is one instance per binding, and
	   its members shapes of their own */
	for (int again = 1; again;) {
		own_named(&named);
		group(&named);
		again = 0;
		for (int i = 0; i < sema.M->stmts.n; i++) {
			Stmt *s = sema.M->stmts.v[i];
			if (!s->loop) continue;
			ObjArray *A = for_array(s);
			Object *o0 = array_member(A, A->lo);
			int ok = 1;
			for (long k = A->lo; ok && k <= A->hi; k++) {
				Object *o = array_member(A, k);
				ok = o->shape == o0->shape && o->sidx == o0->sidx + (int)(k - A->lo);
			}
			if (ok) continue;
			s->loop = 0;
			mark_members(A->name, NULL, &named);
			again = 1;
		}
	}
}
