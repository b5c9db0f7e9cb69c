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
 *
 * This file is the driver of the pass; the work is in
 *   mid/liveness.c  which instances each section needs (Inst.needed)
 *   slots.c         memory: slots of variables, constants, scratch; strings
 *   loops.c         the code of one instance (its loops, blocks, targets)
 *   expr.c          the code of expressions (instructions, CSE, events)
 *   tables.c        the tables beside the code (contacts, columns, -D, sources)
 *   pairs.c         velocity Verlet's position/velocity pairs
 *   jac.c           the JAC section, by forward-mode differentiation of RHS
 *   when.c          the EVT section: the `when` blocks
 *   hoist.c         loop-invariant code motion, last
 * sharing the generator's state through gen_int.h.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "csf_int.h"
#include "gen.h"
#include "gen_int.h"
#include "liveness.h"

void section_begin(Gen *G)
{
	G->code = NULL;
	G->ncode = G->capcode = 0;
	G->lines = NULL;
	G->nlines = G->caplines = 0;
	G->targets = NULL;
	G->ntargets = G->captargets = 0;
}

void section_end(Gen *G, csf_prog *p, int sec)
{
	p->code[sec] = G->code ? G->code : xcalloc(1, sizeof *G->code); /* an empty section is an array too */
	p->ncode[sec] = G->ncode;
	p->lines[sec] = G->lines;
	p->nlines[sec] = G->nlines;
	p->targets[sec] = G->targets;
	p->ntargets[sec] = G->ntargets;
}

/* The RHS and OUT sections: the code of each instance the section needs, in order, the
   contact routine (and the constraints) after the instance last_a (live_mark). */
static void sections(Gen *G, Model *M, csf_prog *p, int last_a)
{
	for (int sec = CSF_SEC_RHS; sec <= CSF_SEC_OUT; sec++) {
		section_begin(G);
		for (int i = 0; i < M->insts.n; i++) {
			Inst *I = M->insts.v[i];
			if (!I->needed[sec]) continue;
			if (sec == CSF_SEC_RHS && I->isassert) continue;
			if (sec == CSF_SEC_OUT && I->isderiv) continue;
			emit_inst(G, I);
			/* with constraints, CONSTRAIN runs the contact routine too (their forces depend on each other) */
			if (i == last_a && p->ncrules && !p->ncons) {
				add_line(G, p->crules[0].src);
				emit_op(G, CSF_OP_CONTACT, 0, 0, 0, 0);
			}
			if (i == last_a && p->ncons) gen_constraint_code(G, M, p);
		}
		section_end(G, p, sec);
	}
}

/* Scratch goes last; relocate scratch operands. Returns the first scratch slot. */
static uint32_t place_scratch(Gen *G, csf_prog *p)
{
	uint32_t base = alloc_mem(G, G->max_scratch, NULL);
	for (int sec = 0; sec < CSF_NSEC; sec++)
		for (uint32_t i = 0; i < p->ncode[sec];) {
			const csf_opinfo *oi = &csf_opinfo_table[p->code[sec][i]];
			for (int k = 0; k < oi->nops; k++) {
				uint32_t *w = &p->code[sec][i + 1 + k];
				if (csf_kind_slot(oi->kind[k]) && (*w & SCRATCH)) *w = base + (*w & ~SCRATCH);
			}
			i += csf_insn_len(p->code[sec][i]);
		}
	return base;
}

/* The pass, on G (zeroed) after gen_program has cleared p and set where a scene too big to compile goes. */
static void gen_run(Gen *G, Model *M, csf_prog *p)
{
	G->M = M;
	G->p = p;
	G->Finsts = live_forces(M);
	int last_a = live_mark(M, G->Finsts);

	/* Layout: t, state, derivatives. */
	p->tslot = alloc_mem(G, 1, NULL);
	p->ystart = G->nmem;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const Vec *P = obj_props(o);
		for (int j = 0; j < P->n && !obj_shares(o); j++) {
			Var *v = P->v[j];
			if (var_integrated(v)) var_slot(G, v);
		}
	}
	p->ny = G->nmem - p->ystart;
	p->dstart = alloc_mem(G, p->ny ? p->ny : 1, NULL); /* a slot even without state: the layout is inside memory */
	gen_state_scales(M, p);
	M->time->slot = (int)p->tslot;
	gen_contact_tables(G, M, p);
	gen_constraint_tables(G, M, p);

	sections(G, M, p, last_a);
	gen_when_section(G, M, p);
	gen_columns(G, M, p);
	gen_globals(G, M, p);
	gen_objects(G, M, p);
	uint32_t scratch = place_scratch(G, p);
	if (!p->ncrules && !p->ncons) gen_pairs(G, M, p); /* contact and constraint forces depend on v */
	else p->vpair = xcalloc(p->ny ? p->ny : 1, sizeof *p->vpair);
	gen_jacobian(G, p);
	gen_source_tables(G, M, p);
	str_intern(G, "");
	p->strs = G->strs;
	p->nstrs = G->nstrs;
	p->mem0 = G->mem;
	p->nmem = G->nmem;
	p->till = M->till;
	p->by = M->by;
	p->nevents = G->nevents;
	p->events = G->events ? G->events : xcalloc(1, sizeof *p->events);
	gen_fuse_loops(p, scratch, scratch + G->max_scratch);
	gen_hoist(p, scratch, scratch + G->max_scratch);
	gen_fuse(p, scratch, scratch + G->max_scratch);
}

/* After a failure: frees what G holds that p does not (p's tables are csf_prog_free's). */
static void gen_drop(Gen *G, csf_prog *p)
{
	int code = 0, lines = 0, targets = 0;
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		code |= G->code == p->code[sec];
		lines |= G->lines == p->lines[sec];
		targets |= G->targets == p->targets[sec];
	}
	if (!code) free(G->code);
	if (!lines) free(G->lines);
	if (!targets) free(G->targets);
	if (G->pclasses != p->pclasses) free(G->pclasses);
	free(G->mem); /* these go to p only at the end */
	free(G->strs);
	free(G->events);
	free(G->objstr);
	for (int i = 0; i < 3; i++) free(G->work[i]);
}

int gen_program(Model *M, csf_prog *p)
{
	Gen *G = xalloc(sizeof *G); /* zeroed; not a local, so that it is intact after longjmp */
	jmp_buf fail;
	memset(p, 0, sizeof *p);
	G->fail = &fail;
	if (setjmp(fail)) { /* too big to compile: alloc_mem wrote the error */
		gen_drop(G, p);
		return 1;
	}
	gen_run(G, M, p);
	free(G->objstr);
	return 0;
}
