/*
 * watch.c - the watch list: the columns of the output.
 */
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

static void add_col(Var *v, const char *label, int member)
{
	for (int c = 0; c < (v->isvec ? 3 : 1); c++) {
		WatchCol *w = xalloc(sizeof *w);
		w->var = v;
		w->comp = c;
		w->member = member;
		w->name = v->isvec ? xprintf("%s.%c", label, 'x' + c) : xstrdup(label);
		vec_push(&sema.M->cols, w);
	}
}

/* Object o's property or temporary `name`, or NULL; a temporary of a shape's member is the
 * representative's, at *member. */
static Var *watch_var(Object *o, const char *name, int *member)
{
	Var *v = prop_of_obj(o, name);
	*member = o->lean ? o->sidx : 0; /* a property lean members share: o's place in it */
	if (v) return v;
	Object *r = sema.shaped ? o->shape->members[0] : o;
	v = map_get(&sema.temps, temp_key(name, &r, 1));
	if (v) *member = o->sidx;
	return v;
}

/* Column label.comp of vector v (the watch item w names a component), or an error. */
static void add_comp(WatchItem *w, Var *v, const char *label, int member)
{
	const char *c = w->comp;
	if (!v->isvec) {
		error_at(w->loc, "'%s' is a scalar: it has no component '%s'", label, c);
		return;
	}
	if (strlen(c) != 1 || c[0] < 'x' || c[0] > 'z') {
		error_at(w->loc, "'%s' is not a component of a vector: watch %s.x, %s.y or %s.z", c, label, label, label);
		return;
	}
	WatchCol *col = xalloc(sizeof *col);
	col->var = v;
	col->comp = c[0] - 'x';
	col->member = member;
	col->name = xprintf("%s.%s", label, c);
	vec_push(&sema.M->cols, col);
}

void build_watch(Stmt *st)
{
	int member;
	if (!st || !st->has_watch) {
		for (int i = 0; i < sema.M->objects.n; i++) {
			Object *o = sema.M->objects.v[i];
			const Vec *P = obj_props(o);
			for (int j = 0; j < P->n && !o->dropped; j++) {
				Var *v = P->v[j];
				add_col(v, o->lean ? xprintf("%s.%s", o->name, v->name) : var_label(v), o->lean ? o->sidx : 0);
			}
		}
		return;
	}
	for (int i = 0; i < st->watch.n; i++) {
		WatchItem *w = st->watch.v[i];
		/* (an object or an array of that name comes first: `watch a.pos`, a an array, is its members' pos) */
		if (w->obj && !w->comp && !object_named(w->obj) && !array_of(w->obj) &&
		    (map_get(&sema.prop_names, w->obj) || map_get(&sema.globals_by_name, w->obj))) {
			/* PROP.c: that component of every object's PROP (or of a global) */
			WatchItem c = *w;
			c.obj = NULL, c.prop = w->obj, c.comp = w->prop;
			Var *g = map_get(&sema.globals_by_name, c.prop);
			if (g) {
				add_comp(&c, g, g->name, 0);
				continue;
			}
			int before = diag_errors;
			for (int j = 0; j < sema.M->objects.n && diag_errors == before; j++) { /* one report, not one per object */
				Object *o = sema.M->objects.v[j];
				Var *v = o->dropped ? NULL : watch_var(o, c.prop, &member);
				if (v) add_comp(&c, v, xprintf("%s.%s", o->name, c.prop), member);
			}
			continue;
		}
		ObjArray *A = w->obj ? array_of(w->obj) : NULL;
		if (A) { /* ARRAY.PROP: every member's */
			for (long k = A->lo; k <= A->hi; k++) {
				Object *o = array_member(A, k);
				Var *v = o->dropped ? NULL : watch_var(o, w->prop, &member);
				if (!v && !o->dropped) {
					error_at(w->loc, "member '%s' of '%s' has no property or temporary '%s'", o->name, A->name, w->prop);
					break;
				}
				if (!v) continue;
				if (w->comp) add_comp(w, v, xprintf("%s.%s", o->name, w->prop), member);
				else add_col(v, xprintf("%s.%s", o->name, w->prop), member);
			}
			continue;
		}
		if (w->obj) {
			Object *o = object_named(w->obj);
			if (!o && (map_get(&sema.prop_names, w->obj) || map_get(&sema.globals_by_name, w->obj))) {
				error_at(w->loc, "'%s.%s': watch the whole variable ('watch %s' gives its x, y and z columns)", w->obj,
				         w->prop, w->obj);
				continue;
			}
			if (!o && map_get(&sema.arrays_failed, w->obj)) continue;
			if (!o) {
				const char *br = strchr(w->obj, '[');
				ObjArray *B = br ? array_of(xstrndup(w->obj, (size_t)(br - w->obj))) : NULL;
				if (!B && br && map_get(&sema.arrays_failed, xstrndup(w->obj, (size_t)(br - w->obj)))) continue;
				if (B) error_at(w->loc, "'%s' has the members %ld..%ld: there is no %s", B->name, B->lo, B->hi, w->obj);
				else error_at(w->loc, "unknown object '%s'", w->obj);
				continue;
			}
			Var *v = watch_var(o, w->prop, &member);
			if (!v) {
				error_at(w->loc, "object '%s' has no property or temporary '%s'", o->name, w->prop);
				continue;
			}
			if (w->comp) add_comp(w, v, xprintf("%s.%s", o->name, w->prop), member);
			else add_col(v, xprintf("%s.%s", o->name, w->prop), member);
			continue;
		}
		if (strcmp(w->prop, "t") == 0) continue; /* t is always the first column */
		Var *g = map_get(&sema.globals_by_name, w->prop);
		if (g) {
			add_col(g, g->name, 0);
			continue;
		}
		int found = 0;
		for (int j = 0; j < sema.M->objects.n; j++) {
			Object *o = sema.M->objects.v[j];
			Var *v = o->dropped ? NULL : watch_var(o, w->prop, &member);
			if (v) {
				add_col(v, xprintf("%s.%s", o->name, w->prop), member);
				found = 1;
			}
		}
		if (!found) error_at(w->loc, "nothing to watch: no object has '%s'", w->prop);
	}
}
