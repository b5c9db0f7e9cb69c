/*
 * tables.c - the tables of the program beside its code: the state's scales
 * and tolerances, the contact bodies and rules, the watched columns, the
 * globals, objects and properties -D may set, and the source tables (files,
 * statements, assertions) its messages quote.
 */
#include <math.h>
#include <stdlib.h>

#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

/* The magnitude of the initial value of object o's property v. */
static double init_mag(const Var *v, const Object *o)
{
	const double *x = member_init(v, o);
	return v->isvec ? csf_vmag3(x[0], x[1], x[2]) : fabs(x[0]);
}

/* The largest magnitude of the initial values of v over the objects that have it (v's, or every
 * member's that shares it). */
static double most_mag(const Var *v)
{
	const Object *o = v->obj;
	if (!o->lean || !o->shape) return init_mag(v, o);
	double most = init_mag(v, o);
	for (int q = o->sidx + 1; q < o->shape->n; q++) {
		const Object *m = o->shape->members[q];
		if (m->lean == o->lean && init_mag(v, m) > most) most = init_mag(v, m);
	}
	return most;
}

/* Each state component's scale (one SI unit, or smaller: csf_prog.yscale) and absolute tolerance. */
void gen_state_scales(Model *M, csf_prog *p)
{
	p->yscale = xmalloc((p->ny ? p->ny : 1) * sizeof *p->yscale);
	p->yatol = xcalloc(p->ny ? p->ny : 1, sizeof *p->yatol);
	/* the largest magnitude each property name starts at, over all objects, of a state variable */
	Map largest = { 0 };
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		for (int j = 0; j < P->n && !obj_shares(o); j++) {
			Var *v = P->v[j];
			if (!var_integrated(v)) continue;
			double *w = map_get(&largest, v->name), m = most_mag(v);
			if (!w) map_put(&largest, v->name, w = xalloc(sizeof *w)), *w = m;
			else if (m > *w) *w = m;
		}
	}
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		for (int j = 0; j < P->n && !obj_shares(o); j++) {
			Var *v = P->v[j];
			if (!var_integrated(v)) continue;
			/* one SI unit of v, in the system's units; smaller when the property starts
			   smaller in every object (so that a 1e-20 m orbit keeps the relative accuracy
			   of a 1 m one), but not because it starts near zero in this one (a normal
			   mode's node: cos(pi/2) is 6e-17) */
			double one = v->dimk == DK_KNOWN ? dims_to_system(1.0, v->dim) : 1.0;
			if (!(one > 0) || !isfinite(one)) one = 1.0; /* a dimension such as m^100 kg^100 in cgs */
			double mag = *(double *)map_get(&largest, v->name);
			if (mag > 0 && mag < one && isfinite(mag)) one = mag;
			/* (every member's that shares v, at its place) */
			for (int q = o->lean ? o->sidx : 0; q < (o->lean ? o->shape->n : 1); q++) {
				const Object *m = o->lean ? o->shape->members[q] : o;
				if (m->lean != o->lean) continue;
				uint32_t at = (uint32_t)v->slot + member_offset(v, m) - p->ystart;
				for (uint32_t k = 0; k < (v->isvec ? 3u : 1u); k++) {
					p->yscale[at + k] = one;
					p->yatol[at + k] = var_more_of(v)->atol ? var_more_of(v)->atol->c[0] : 0;
				}
			}
		}
	}
}

/* The constraint tables: each constraint's slots (g, gd, c, scale) and bodies (csf_con, csf_conbody). */
void gen_constraint_tables(Gen *G, Model *M, csf_prog *p)
{
	p->ncons = (uint32_t)M->cons.n;
	for (int i = 0; i < M->cons.n; i++) p->nconbodies += (uint32_t)((Constraint *)M->cons.v[i])->bodies.n;
	p->cons = xcalloc(p->ncons + 1, sizeof *p->cons);
	p->conbodies = xcalloc(p->nconbodies + 1, sizeof *p->conbodies);
	uint32_t nb = 0, want = p->ncons ? alloc_mem(G, 1, (double[1]){ 1 }) : 0;
	for (uint32_t k = 0; k < p->ncons; k++) {
		Constraint *K = M->cons.v[k];
		csf_con *c = &p->cons[k];
		c->src = (uint32_t)K->src;
		c->kind = (uint32_t)K->kind;
		c->g = alloc_mem(G, 1, NULL);
		c->gd = alloc_mem(G, 1, NULL);
		c->c = alloc_mem(G, 1, NULL);
		c->scale = alloc_mem(G, 1, NULL);
		c->cr = alloc_mem(G, 1, NULL);
		c->want = want;
		c->first = nb;
		c->n = (uint32_t)K->bodies.n;
		c->unit = str_intern(G, K->dimk == DK_KNOWN ? dims_unit(K->dim) : "");
		for (int b = 0; b < K->bodies.n; b++) {
			Object *o = K->bodies.v[b];
			csf_conbody *e = &p->conbodies[nb++];
			e->object = (uint32_t)o->index;
			e->J = alloc_mem(G, 3, NULL);
			e->pos = var_slot(G, K->pos.v[b]);
			e->v = var_slot(G, K->vel.v[b]);
			e->a = var_slot(G, prop_of_obj(o, "a"));
			e->m = var_slot(G, prop_of_obj(o, "m"));
			e->fc = var_slot(G, prop_of_obj(o, "FC"));
		}
	}
}

/* The code of the constraints' values, before the CONSTRAIN instruction (gen.c). */
void gen_constraint_code(Gen *G, Model *M, csf_prog *p)
{
	for (uint32_t k = 0; k < p->ncons; k++) {
		Constraint *K = M->cons.v[k];
		const csf_con *c = &p->cons[k];
		RExpr *e[5] = { K->g, K->gd, K->c, K->scale, K->cr };
		uint32_t at[5] = { c->g, c->gd, c->c, c->scale, c->cr };
		add_line(G, c->src);
		G->scratch = 0; /* one constraint's values share their common parts (scratch is not reused within it) */
		cse_reset(G);
		/* what the forces need (the gradients, c), then, while want is set, the rest */
		for (uint32_t b = 0; b < c->n; b++) emit_into(G, K->grad[b], p->conbodies[c->first + b].J);
		emit_into(G, e[2], at[2]);
		uint32_t jz = pc(G);
		emit_op(G, CSF_OP_JZ, c->want, 0, 0, 0);
		for (int i = 0; i < 5; i++)
			if (i != 2) emit_into(G, e[i], at[i]);
		G->code[jz + 2] = pc(G);
	}
	emit_op(G, CSF_OP_CONSTRAIN, 0, 0, 0, 0);
}

/* The contact tables: the bodies' property slots, and each rule's lists of bodies (csf.h). */
void gen_contact_tables(Gen *G, Model *M, csf_prog *p)
{
	p->ncbodies = M->contacts.n ? (uint32_t)M->cbodies.n : 0;
	p->ncrules = (uint32_t)M->contacts.n;
	p->cbodies = xcalloc(p->ncbodies + 1, sizeof *p->cbodies);
	p->crules = xcalloc(p->ncrules + 1, sizeof *p->crules);
	for (uint32_t i = 0; i < p->ncbodies; i++) {
		ContactBody *b = M->cbodies.v[i];
		csf_cbody *pb = &p->cbodies[i];
		pb->plane = (uint32_t)b->kind;
		pb->object = (uint32_t)b->o->index;
		for (int f = 0; f < CSF_CF_N; f++) {
			Var *v = b->f[f];
			pb->s[f] = v ? prop_slot(G, v, b->o) : p->tslot;
			/* the radius, or a plane's or an anchor's geometry, computed or integrated: not known from positions */
			if (v && (f == CSF_CF_R || (b->kind && (f == CSF_CF_POS || f == CSF_CF_V))) && (var_integrated(v) || v->det))
				pb->varies = 1;
		}
	}
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		p->ncmembers += (uint32_t)(c->b0.n + c->b1.n);
	}
	p->cmembers = xcalloc(p->ncmembers + 1, sizeof *p->cmembers);
	uint32_t nm = 0;
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		csf_crule *pr = &p->crules[i];
		pr->src = (uint32_t)c->src;
		pr->every = (uint32_t)c->every;
		for (int k = 0; k < 2; k++) {
			Vec *L = k ? &c->b1 : &c->b0;
			*(k ? &pr->first1 : &pr->first0) = nm;
			*(k ? &pr->n1 : &pr->n0) = (uint32_t)L->n;
			for (int j = 0; j < L->n; j++) p->cmembers[nm++] = (uint32_t)((ContactBody *)L->v[j])->index;
		}
	}
}

/* Columns. */
void gen_columns(Gen *G, Model *M, csf_prog *p)
{
	p->ncols = (uint32_t)M->cols.n;
	p->cols = xcalloc(p->ncols + 1, sizeof *p->cols);
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		const char *unit = w->var->dimk == DK_KNOWN ? dims_unit(w->var->dim) : "";
		p->cols[i].name = str_intern(G, *unit ? xprintf("%s [%s]", w->name, unit) : w->name);
		p->cols[i].slot = (w->var->kind == V_TIME ? p->tslot : var_slot(G, w->var)) +
		                  (uint32_t)(w->member * (w->var->isvec ? 3 : 1) + w->comp);
	}
}

/* The globals, every one in memory so that -D can set it. */
void gen_globals(Gen *G, Model *M, csf_prog *p)
{
	p->nglobals = (uint32_t)M->globals.n;
	p->globals = xcalloc(p->nglobals + 1, sizeof *p->globals);
	for (int i = 0; i < M->globals.n; i++) {
		Var *g = M->globals.v[i];
		p->globals[i] = (csf_global){ str_intern(G, g->name), var_slot(G, g), g->isvec ? 3u : 1u, param_class(G, g) };
	}
	dims_system_base(p->ubase);
}

/* The object table: every object and the properties the program keeps in memory. */
void gen_objects(Gen *G, Model *M, csf_prog *p)
{
	p->nobjects = (uint32_t)M->objects.n;
	p->objects = xcalloc(p->nobjects + 1, sizeof *p->objects);
	uint32_t n = 0;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		p->objects[i] = obj_str(G, o);
		for (int j = 0; j < P->n && !o->dropped; j++) n += ((Var *)P->v[j])->slot >= 0;
	}
	p->nprops = n;
	p->props = xcalloc(p->nprops + 1, sizeof *p->props);
	n = 0;
	const ObjArray *known = NULL; /* the array whose shared properties' names and classes are in name, cls */
	uint32_t *name = NULL, *cls = NULL;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		if (o->lean && !o->dropped && o->lean != known) {
			known = o->lean;
			name = xrealloc(name, (size_t)P->n * sizeof *name + 1);
			cls = xrealloc(cls, (size_t)P->n * sizeof *cls + 1);
			for (int j = 0; j < P->n; j++) {
				Var *v = P->v[j];
				if (v->slot >= 0) name[j] = str_intern(G, v->name), cls[j] = param_class(G, v);
			}
		}
		for (int j = 0; j < P->n && !o->dropped; j++) {
			Var *v = P->v[j];
			if (v->slot >= 0)
				p->props[n++] = (csf_prop){ (uint32_t)o->index, o->lean ? name[j] : str_intern(G, v->name),
				                            prop_slot(G, v, o), v->isvec ? 3u : 1u, o->lean ? cls[j] : param_class(G, v) };
		}
	}
	free(name);
	free(cls);
	p->npclasses = G->npclasses;
	p->pclasses = G->pclasses ? G->pclasses : xcalloc(1, sizeof *p->pclasses);
}

/* Source tables. */
void gen_source_tables(Gen *G, Model *M, csf_prog *p)
{
	p->nfiles = (uint32_t)sources.n;
	p->files = xcalloc(p->nfiles + 1, sizeof *p->files);
	for (int i = 0; i < sources.n; i++) p->files[i] = str_intern(G, ((Source *)sources.v[i])->path);
	p->nsrcs = (uint32_t)M->srcs.n;
	p->srcs = xcalloc(p->nsrcs + 1, sizeof *p->srcs);
	for (int i = 0; i < M->srcs.n; i++) {
		SrcEntry *e = M->srcs.v[i];
		p->srcs[i] = (csf_src){ (uint32_t)e->loc.file, (uint32_t)e->loc.line, str_intern(G, e->text) };
	}
	p->nasserts = (uint32_t)G->assert_tab.n;
	p->asserts = xcalloc(p->nasserts + 1, sizeof *p->asserts);
	for (int i = 0; i < G->assert_tab.n; i++) {
		Inst *I = G->assert_tab.v[i];
		p->asserts[i] = (csf_assert){ (uint32_t)I->src, str_intern(G, ((Object *)G->assert_obj.v[i])->name) };
	}
}
