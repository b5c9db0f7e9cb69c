/*
 * gen.c - from a resolved model to a csf_prog (bytecode).
 *
 * Only what the scene needs is compiled: the RHS section holds the rule
 * instances the state derivatives depend on, then the derivatives; the OUT
 * section holds the instances the watched variables and the assertions
 * depend on, then the assertions. Memory is laid out as
 *   t | state | derivatives | globals, properties, temporaries, constants | scratch
 * where variables and constants get slots as the code first refers to them
 * and scratch slots (expression temporaries, reused by every instance) are
 * placed last once their number is known.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "csf.h"
#include "gen.h"
#include "gen_int.h"

/* The magnitude of v's initial value. */
static double init_mag(const Var *v) { return v->isvec ? csf_vmag3(v->init[0], v->init[1], v->init[2]) : fabs(v->init[0]); }

static void mark(Gen *G, Inst *I, int sec)
{
	if (I->needed[sec]) return;
	I->needed[sec] = 1;
	for (int i = 0; i < I->reads.n; i++) {
		Var *v = I->reads.v[i];
		if (v->det && v->det != I) mark(G, v->det, sec);
	}
	for (int i = 0; i < I->rf_reads.n; i++) {
		Object *o = I->rf_reads.v[i];
		Vec *fs = &G->Finsts[o->index];
		for (int k = 0; k < fs->n; k++) mark(G, fs->v[k], sec);
	}
}

int gen_program(Model *M, csf_prog *p)
{
	Gen G0 = { 0 }, *G = &G0;
	memset(p, 0, sizeof *p);
	G->M = M;
	G->p = p;
	G->Finsts = xalloc((size_t)(M->objects.n + 1) * sizeof(Vec));
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isF) vec_push(&G->Finsts[I->bind[0]->index], I);
	}
	/* What is needed: derivatives for RHS; watches and assertions for OUT. */
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isderiv || I->isstop) mark(G, I, CSF_SEC_RHS);
		if (I->isassert) mark(G, I, CSF_SEC_OUT);
	}
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		Var *v = sema_canon(w->var);
		if (v->det) mark(G, v->det, CSF_SEC_OUT);
	}

	/* Contacts need every body's acceleration, in OUT too (a, FN and Ff are watchable). */
	/* The contact routine runs after the last of them: last_a, an index into M->insts. */
	int last_a = -1;
	Map dets = { 0 }; /* the instances that determine a body's a, by address */
	for (int i = 0; i < M->cbodies.n && M->contacts.n; i++) {
		ContactBody *b = M->cbodies.v[i];
		Var *a = sema_canon(b->f[CSF_CF_A]);
		if (b->plane || !a || !a->det) continue;
		mark(G, a->det, CSF_SEC_OUT);
		map_put(&dets, xprintf("%p", (void *)a->det), a->det);
	}
	for (int j = 0; j < M->insts.n && M->contacts.n; j++)
		if (map_get(&dets, xprintf("%p", M->insts.v[j]))) last_a = j;

	/* Layout: t, state, derivatives. */
	p->tslot = alloc_mem(G, 1, NULL);
	p->ystart = G->nmem;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j];
			if (v->state) var_slot(G, v);
		}
	}
	p->ny = G->nmem - p->ystart;
	p->dstart = alloc_mem(G, p->ny ? p->ny : 1, NULL); /* a slot even without state: the layout is inside memory */
	p->yscale = malloc((p->ny ? p->ny : 1) * sizeof *p->yscale);
	p->yatol = calloc(p->ny ? p->ny : 1, sizeof *p->yatol);
	if (!p->yscale || !p->yatol) exit(2);
	/* the state variable of each property name that starts largest, over all objects */
	Map largest = { 0 };
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j], *w = v->state ? map_get(&largest, v->name) : NULL;
			if (v->state && (!w || init_mag(v) > init_mag(w))) map_put(&largest, v->name, v);
		}
	}
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j];
			if (!v->state) continue;
			/* one SI unit of v, in the system's units; smaller when the property starts
			   smaller in every object (so that a 1e-20 m orbit keeps the relative accuracy
			   of a 1 m one), but not because it starts near zero in this one (a normal
			   mode's node: cos(pi/2) is 6e-17) */
			double one = v->dimk == DK_KNOWN ? dims_to_system(1.0, v->dim) : 1.0;
			if (!(one > 0) || !isfinite(one)) one = 1.0; /* a dimension such as m^100 kg^100 in cgs */
			double mag = init_mag(map_get(&largest, v->name));
			if (mag > 0 && mag < one && isfinite(mag)) one = mag;
			for (int k = 0; k < (v->isvec ? 3 : 1); k++) {
				p->yscale[(uint32_t)v->slot - p->ystart + (uint32_t)k] = one;
				p->yatol[(uint32_t)v->slot - p->ystart + (uint32_t)k] = v->atol ? v->atol->c[0] : 0;
			}
		}
	}
	M->time->slot = (int)p->tslot;

	/* The contact tables: the bodies' property slots, and each rule's lists of bodies (csf.h). */
	p->ncbodies = M->contacts.n ? (uint32_t)M->cbodies.n : 0;
	p->ncrules = (uint32_t)M->contacts.n;
	p->cbodies = calloc(p->ncbodies + 1, sizeof *p->cbodies);
	p->crules = calloc(p->ncrules + 1, sizeof *p->crules);
	if (!p->cbodies || !p->crules) exit(2);
	for (uint32_t i = 0; i < p->ncbodies; i++) {
		ContactBody *b = M->cbodies.v[i];
		csf_cbody *pb = &p->cbodies[i];
		pb->plane = (uint32_t)b->plane;
		pb->object = (uint32_t)b->o->index;
		for (int f = 0; f < CSF_CF_N; f++) {
			Var *v = b->f[f];
			pb->s[f] = v ? var_slot(G, v) : p->tslot;
			/* the radius, or a plane's geometry, computed or integrated: not known from positions */
			if (v && (f == CSF_CF_R || (b->plane && (f == CSF_CF_POS || f == CSF_CF_V))) && (v->state || v->det))
				pb->varies = 1;
		}
	}
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		p->ncmembers += (uint32_t)(c->b0.n + c->b1.n);
	}
	p->cmembers = calloc(p->ncmembers + 1, sizeof *p->cmembers);
	if (!p->cmembers) exit(2);
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

	for (int sec = CSF_SEC_RHS; sec <= CSF_SEC_OUT; sec++) {
		G->code = NULL;
		G->ncode = G->capcode = 0;
		G->lines = NULL;
		G->nlines = G->caplines = 0;
		G->targets = NULL;
		G->ntargets = G->captargets = 0;
		for (int i = 0; i < M->insts.n; i++) {
			Inst *I = M->insts.v[i];
			if (!I->needed[sec]) continue;
			if (sec == CSF_SEC_RHS && I->isassert) continue;
			if (sec == CSF_SEC_OUT && I->isderiv) continue;
			emit_inst(G, I);
			if (i == last_a) {
				add_line(G, p->crules[0].src);
				emit_op(G, CSF_OP_CONTACT, 0, 0, 0, 0);
			}
		}
		p->code[sec] = G->code;
		p->ncode[sec] = G->ncode;
		p->lines[sec] = G->lines;
		p->nlines[sec] = G->nlines;
		p->targets[sec] = G->targets;
		p->ntargets[sec] = G->ntargets;
	}

	/* Columns. */
	p->ncols = (uint32_t)M->cols.n;
	p->cols = calloc(p->ncols + 1, sizeof *p->cols);
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		const char *unit = w->var->dimk == DK_KNOWN ? dims_unit(w->var->dim) : "";
		p->cols[i].name = str_intern(G, *unit ? xprintf("%s [%s]", w->name, unit) : w->name);
		p->cols[i].slot = (w->var->kind == V_TIME ? p->tslot : var_slot(G, w->var)) +
		                  (uint32_t)(w->member * (w->var->isvec ? 3 : 1) + w->comp);
	}

	/* The globals, every one in memory so that -D can set it. */
	p->nglobals = (uint32_t)M->globals.n;
	p->globals = calloc(p->nglobals + 1, sizeof *p->globals);
	if (!p->globals) exit(2);
	for (int i = 0; i < M->globals.n; i++) {
		Var *g = M->globals.v[i];
		p->globals[i] = (csf_global){ str_intern(G, g->name), var_slot(G, g), g->isvec ? 3u : 1u, param_class(G, g) };
	}
	dims_system_base(p->ubase);

	/* The object table: every object and the properties the program keeps in memory. */
	p->nobjects = (uint32_t)M->objects.n;
	p->objects = calloc(p->nobjects + 1, sizeof *p->objects);
	if (!p->objects) exit(2);
	Vec props = { 0 };
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		p->objects[i] = str_intern(G, o->name);
		for (int j = 0; j < o->props.n; j++)
			if (((Var *)o->props.v[j])->slot >= 0) vec_push(&props, o->props.v[j]);
	}
	p->nprops = (uint32_t)props.n;
	p->props = calloc(p->nprops + 1, sizeof *p->props);
	if (!p->props) exit(2);
	for (int i = 0; i < props.n; i++) {
		Var *v = props.v[i];
		p->props[i] = (csf_prop){ (uint32_t)v->obj->index, str_intern(G, v->name), (uint32_t)v->slot, v->isvec ? 3u : 1u,
		                          param_class(G, v) };
	}
	p->npclasses = G->npclasses;
	p->pclasses = G->pclasses ? G->pclasses : calloc(1, sizeof *p->pclasses);

	/* Scratch goes last; relocate scratch operands. */
	uint32_t base = alloc_mem(G, G->max_scratch, NULL);
	for (int sec = 0; sec < CSF_NSEC; sec++)
		for (uint32_t i = 0; i < p->ncode[sec];) {
			const csf_opinfo *oi = &csf_opinfo_table[p->code[sec][i]];
			for (int k = 0; k < oi->nops; k++) {
				uint32_t *w = &p->code[sec][i + 1 + k];
				if (slot_kind(oi->kind[k]) && (*w & SCRATCH)) *w = base + (*w & ~SCRATCH);
			}
			i += 1u + oi->nops;
		}

	if (!p->ncrules) gen_pairs(G, M, p); /* the contact routine's forces depend on v */
	else if (!(p->vpair = calloc(p->ny ? p->ny : 1, sizeof *p->vpair))) exit(2);
	gen_jacobian(G, p);

	/* Source tables. */
	p->nfiles = (uint32_t)sources.n;
	p->files = calloc(p->nfiles + 1, sizeof *p->files);
	for (int i = 0; i < sources.n; i++) p->files[i] = str_intern(G, ((Source *)sources.v[i])->path);
	p->nsrcs = (uint32_t)M->srcs.n;
	p->srcs = calloc(p->nsrcs + 1, sizeof *p->srcs);
	for (int i = 0; i < M->srcs.n; i++) {
		SrcEntry *e = M->srcs.v[i];
		p->srcs[i] = (csf_src){ (uint32_t)e->loc.file, (uint32_t)e->loc.line, str_intern(G, e->text) };
	}
	p->nasserts = (uint32_t)G->assert_tab.n;
	p->asserts = calloc(p->nasserts + 1, sizeof *p->asserts);
	for (int i = 0; i < G->assert_tab.n; i++) {
		Inst *I = G->assert_tab.v[i];
		p->asserts[i] = (csf_assert){ (uint32_t)I->src, str_intern(G, ((Object *)G->assert_obj.v[i])->name) };
	}
	str_intern(G, "");
	p->strs = G->strs;
	p->nstrs = G->nstrs;
	p->mem0 = G->mem;
	p->nmem = G->nmem;
	p->till = M->till;
	p->by = M->by;
	p->nevents = G->nevents;
	p->events = G->events ? G->events : calloc(1, sizeof *p->events);
	return 0;
}
