/*
 * slots.c - the memory of the program being generated: the growing tables,
 * the slots of variables (arrays over a shape's members), of constants
 * (shared by bits) and of scratch, the interned strings, and the parameter
 * classes that say what -D may set.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

void *grow(void *p, uint32_t *cap, uint32_t need, size_t elem)
{
	if (need <= *cap) return p;
	uint32_t c = *cap ? *cap : 64;
	while (c < need) c *= 2;
	void *q = xrealloc(p, (size_t)c * elem); /* out of memory: xoom, the compiler's one exit for it */
	*cap = c;
	return q;
}

uint32_t alloc_mem(Gen *G, uint32_t n, const double *init)
{
	if ((uint64_t)G->nmem + n >= SCRATCH / 2) { /* the Jacobian's tangents double it */
		error_plain("the scene needs more than %u memory slots (%u MiB of values): too big to compile", SCRATCH / 2,
		            SCRATCH / 2 / 131072);
		longjmp(*G->fail, 1); /* back to gen_program, which frees what it holds and returns 1 */
	}
	if (G->nmem + n > G->capmem) {
		/* a new block of zeros, of which only the slots in use are written: the rest, zeros, take no
		   memory until they are (the Jacobian's tangents, one for every slot, most never set) */
		uint32_t c = G->capmem ? G->capmem : 64;
		while (c < G->nmem + n) c *= 2;
		double *m = xcalloc(c, sizeof *m);
		if (G->nmem) memcpy(m, G->mem, G->nmem * sizeof *m);
		free(G->mem);
		G->mem = m;
		G->capmem = c;
	}
	if (init) memcpy(G->mem + G->nmem, init, n * sizeof *init);
	G->nmem += n;
	return G->nmem - n;
}

uint32_t obj_str(Gen *G, const Object *o)
{
	if (!G->objstr) G->objstr = xcalloc((size_t)G->M->objects.n + 1, sizeof *G->objstr);
	if (!G->objstr[o->index]) G->objstr[o->index] = str_intern(G, o->name) + 1;
	return G->objstr[o->index] - 1;
}

uint32_t str_intern(Gen *G, const char *s)
{
	uintptr_t known = (uintptr_t)map_get(&G->strmap, s);
	if (known) return (uint32_t)(known - 1);
	uint32_t n = (uint32_t)strlen(s) + 1;
	G->strs = grow(G->strs, &G->capstrs, G->nstrs + n, 1);
	memcpy(G->strs + G->nstrs, s, n);
	G->nstrs += n;
	map_put(&G->strmap, xstrdup(s), (void *)(uintptr_t)(G->nstrs - n + 1));
	return G->nstrs - n;
}

/*
 * The slot of v, allocated at its first use. A property of the objects of a
 * shape is an array, member i's value at slot + i (a vector: slot + 3 i),
 * allocated for all members at once; so is a temporary of one object of
 * such a shape (only the representative's exists).
 */
uint32_t var_slot(Gen *G, Var *v)
{
	if (v->slot >= 0) return (uint32_t)v->slot;
	uint32_t w = v->isvec ? 3 : 1;
	Var *r = sema_canon(v);
	if (r != v && v->obj->lean) { /* lean members' (Object.lean): the shape's array, at its start */
		var_slot(G, r);
		return (uint32_t)v->slot;
	}
	if (!sema_per_member(v)) {
		v->slot = (int)alloc_mem(G, w, v->kind == V_TEMP ? NULL : member_init(v, v->obj));
		return (uint32_t)v->slot;
	}
	Shape *S = v->obj->shape;
	uint32_t base = alloc_mem(G, (uint32_t)S->n * w, NULL);
	if (v->kind == V_TEMP) {
		v->slot = (int)base;
		return base;
	}
	for (int q = 0; q < S->n; q++) {
		Object *o = S->members[q];
		Var *m = prop_of_obj(o, v->name);
		m->slot = (int)(base + (o->lean ? 0 : (uint32_t)q * w)); /* (lean members share m: prop_slot) */
		memcpy(G->mem + base + (uint32_t)q * w, member_init(m, o), w * sizeof(double));
	}
	return (uint32_t)v->slot;
}

/*
 * Why -D cannot set the initial value of global or property v, or "" if it
 * can: a value folded at compile time into another, or computed from
 * others, or one that decided which contacts exist, or a variable a rule
 * computes (its initial value is never read). The initial value of a state
 * variable is its value at t = 0, and can be set.
 */
static const char *param_why(Var *v)
{
	Var *r = sema_canon(v);
	const char *on = v->fix_obj ? v->fix_obj : "", *dot = v->fix_obj ? "." : "";
	switch (v->fix) {
	case FIX_FOLDED:
		return xprintf("its value is folded at compile time into the value of %s%s%s (line %d)", on, dot, v->fix_name,
		               v->fix_line);
	case FIX_DERIVED:
		return xprintf("its value is computed at compile time from %s%s%s (line %d)", on, dot,
		               v->fix_name, v->fix_line);
	case FIX_RUN: return xprintf("its value is folded at compile time into the run's '%s' (line %d)", v->fix_name, v->fix_line);
	case FIX_CONTACT: return "its value 0 decided at compile time that it never touches another point";
	}
	if (r->det && !r->state)
		return xprintf("a rule computes it (%s:%d); it is not an input",
		               ((Source *)sources.v[r->det->st->loc.file])->path, r->det->st->loc.line);
	return "";
}

/*
 * The parameter class (csf_pclass) of global or property v: its dimension,
 * unit, and param_why. The strings of a class already known are released:
 * a million objects' properties take no memory but their classes'.
 */
uint32_t param_class(Gen *G, Var *v)
{
	Var *r = sema_canon(v);
	const Var *d = v->dimk == DK_KNOWN ? v : r;
	int known = d->dimk == DK_KNOWN;
	for (int pass = 0;; pass++) {
		ArenaMark mark = arena_mark();
		const char *unit = known ? dims_unit(d->dim) : "", *why = param_why(v);
		char *key = xprintf("%d %.17g %.17g %.17g %.17g %s\x01%s", known, known ? d->dim[0] : 0, known ? d->dim[1] : 0,
		                    known ? d->dim[2] : 0, known ? d->dim[3] : 0, unit, why);
		uintptr_t k = (uintptr_t)map_get(&G->pclass, key);
		if (k || pass == 0) {
			arena_release(mark);
			if (k) return (uint32_t)(k - 1);
			continue;
		}
		/* a new class (second pass, its strings kept) */
		G->pclasses = grow(G->pclasses, &G->cappclasses, G->npclasses + 1, sizeof *G->pclasses);
		csf_pclass *c = &G->pclasses[G->npclasses];
		*c = (csf_pclass){ str_intern(G, unit), str_intern(G, why), (uint32_t)known, { 0 } };
		if (known) memcpy(c->dim, d->dim, sizeof c->dim);
		map_put(&G->pclass, key, (void *)(uintptr_t)(++G->npclasses));
		return G->npclasses - 1;
	}
}

uint32_t prop_slot(Gen *G, Var *v, const Object *o)
{
	return var_slot(G, v) + member_offset(v, o);
}

/* The operand word for v read at place ($n) of the instance being emitted: relative to
   that place's loop index when v is an array over a shape. */
uint32_t var_operand(Gen *G, Var *v, int place)
{
	uint32_t s = var_slot(G, v), level = (uint32_t)place + 1;
	if (G->iloop && place >= 0 && sema_per_member(v)) /* every place in the one loop: its member's offset */
		return csf_rel(s + (uint32_t)G->iloop->bind[place]->sidx * (v->isvec ? 3u : 1u), v->isvec ? 2 : 1);
	if (place < 0 || (int)level > G->loop || !sema_per_member(v)) return s;
	return csf_rel(s, v->isvec ? 2 * level : 2 * level - 1);
}

static uint64_t dbits(double d)
{
	uint64_t u;
	memcpy(&u, &d, 8);
	return u;
}

/* The slot of a constant, shared by every use of the same bits. */
uint32_t const_slot(Gen *G, const double *c, int isvec)
{
	char key[64];
	snprintf(key, sizeof key, "%d:%016llx:%016llx:%016llx", isvec, (unsigned long long)dbits(c[0]),
	         isvec ? (unsigned long long)dbits(c[1]) : 0ull, isvec ? (unsigned long long)dbits(c[2]) : 0ull);
	uintptr_t known = (uintptr_t)map_get(&G->consts, key);
	if (known) return (uint32_t)(known - 1);
	uint32_t s = alloc_mem(G, isvec ? 3 : 1, c);
	map_put(&G->consts, xstrdup(key), (void *)(uintptr_t)(s + 1));
	return s;
}

uint32_t new_scratch(Gen *G, int width)
{
	uint32_t s = G->scratch;
	G->scratch += (uint32_t)width;
	if (G->scratch > G->max_scratch) G->max_scratch = G->scratch;
	return SCRATCH | s;
}
