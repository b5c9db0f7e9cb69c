/*
 * when.c - the EVT section: the code of the `when` blocks, which the
 * runtime runs at each event, on the values of an RHS evaluation at the
 * event's instant with the modes before it (csf_when, csf_int.h).
 *
 * Each block's comparisons are events of the RHS section (loops.c), where
 * the runtime reads the guards that locate them; here its condition is
 * computed again from the same values, as plain comparisons: the located
 * instant is the first one found on its new side. The section is two
 * passes over the blocks, so that every new value is computed from the
 * values before the event, whichever block sets what:
 *   1. per block: c := COND; fire := c and prev == 0; prev := c; if fire,
 *      each new value into a slot of its own (stage);
 *   2. per block that fired: each variable := its stage.
 * The model is resolved object by object when it has a `when` block, so
 * no block runs in a loop.
 */
#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

/* Where one block's flags and new values are. */
typedef struct WhenSlots { uint32_t fire, prev, *stage; } WhenSlots;

/* Pass 1 for block I: its condition, its flags, and (if it fires) its new values into W's stages. */
static void emit_fire(Gen *G, Inst *I, const WhenSlots *W)
{
	G->scratch = 0;
	cse_reset(G);
	add_line(G, (uint32_t)I->src);
	uint32_t c = emit(G, I->cond), zero = const_slot(G, (double[3]){ 0, 0, 0 }, 0), was = new_scratch(G, 1);
	cse_reset(G);
	emit_op(G, CSF_OP_EQ, was, W->prev, zero, 0);
	emit_op(G, CSF_OP_AND, W->fire, c, was, 0);
	emit_op(G, CSF_OP_MOV, W->prev, c, 0, 0);
	uint32_t jz = pc(G);
	emit_op(G, CSF_OP_JZ, W->fire, 0, 0, 0);
	for (int k = 0; k < I->then.n; k++) {
		cse_reset(G);
		emit_into(G, ((Assign *)I->then.v[k])->e, W->stage[k]);
	}
	cse_reset(G);
	G->code[jz + 2] = pc(G);
}

/* Pass 2 for block I: if it fired, each of its variables takes its new value; the targets of the section. */
static void emit_set(Gen *G, Inst *I, const WhenSlots *W)
{
	add_line(G, (uint32_t)I->src);
	uint32_t jz = pc(G);
	emit_op(G, CSF_OP_JZ, W->fire, 0, 0, 0);
	for (int k = 0; k < I->then.n; k++) {
		Var *v = ((Assign *)I->then.v[k])->var;
		uint32_t to = var_operand(G, v, -1);
		emit_op(G, v->isvec ? CSF_OP_VMOV : CSF_OP_MOV, to, W->stage[k], 0, 0);
		add_target(G, to, v, (uint32_t)I->src, v->name, v->obj);
	}
	G->code[jz + 2] = pc(G);
}

void gen_when_section(Gen *G, Model *M, csf_prog *p)
{
	section_begin(G);
	G->loop = 0;
	Vec whens = { 0 };
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->iswhen && I->needed[CSF_SEC_RHS]) vec_push(&whens, I);
	}
	WhenSlots *W = xalloc(((size_t)whens.n + 1) * sizeof *W);
	p->whens = xcalloc((size_t)whens.n + 1, sizeof *p->whens);
	for (int i = 0; i < whens.n; i++) {
		Inst *I = whens.v[i];
		W[i].fire = alloc_mem(G, 1, NULL);
		W[i].prev = alloc_mem(G, 1, (double[1]){ -1 });
		W[i].stage = xalloc(((size_t)I->then.n + 1) * sizeof *W[i].stage);
		for (int k = 0; k < I->then.n; k++)
			W[i].stage[k] = alloc_mem(G, ((Assign *)I->then.v[k])->var->isvec ? 3 : 1, NULL);
		p->whens[i] = (csf_when){ (uint32_t)I->src, W[i].fire, W[i].prev };
	}
	p->nwhens = (uint32_t)whens.n;
	for (int i = 0; i < whens.n; i++) emit_fire(G, whens.v[i], &W[i]);
	for (int i = 0; i < whens.n; i++) emit_set(G, whens.v[i], &W[i]);
	section_end(G, p, CSF_SEC_EVT);
}
