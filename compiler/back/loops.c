/*
 * loops.c - the code of one rule instance: the loops over the members of
 * its shapes, its conditional blocks and steps, its assertion or stop
 * condition, and the targets (the values it computes, by name) and source
 * lines that go with the code.
 */
#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

/* How many levels of loops instance I runs in: one per place when a shape of more than one
   object is bound (0: compiled for its objects alone). */
int inst_loops(const Model *M, const Inst *I)
{
	if (M->shaped && I->iloop) return 1; /* one loop over the bindings */
	if (!M->shaped || I->st->has_for || I->st->once) return 0;
	for (int b = 0; b < I->nbind; b++)
		if (I->bind[b]->shape->n > 1) return I->nbind;
	return 0;
}

/* A $1 rule with attribute F in loops: its forces summed over $1 into an array (acc). */
int sums_pairs(const Model *M, const Inst *I) { return I->isF && I->nbind > 1 && !I->iloop && inst_loops(M, I); }
void add_line(Gen *G, uint32_t src)
{
	G->lines = grow(G->lines, &G->caplines, G->nlines + 1, sizeof(csf_line));
	G->lines[G->nlines++] = (csf_line){ pc(G), src };
}

/* A target whose name is interned (name). */
static void add_target_str(Gen *G, uint32_t slot, Var *v, uint32_t src, uint32_t name, Object *o)
{
	G->targets = grow(G->targets, &G->captargets, G->ntargets + 1, sizeof(csf_target));
	G->targets[G->ntargets++] = (csf_target){ slot, v->isvec ? 3u : 1u, src, name, o ? obj_str(G, o) : str_intern(G, "global") };
}

void add_target(Gen *G, uint32_t slot, Var *v, uint32_t src, const char *name, Object *o)
{
	add_target_str(G, slot, v, src, str_intern(G, name), o);
}

/* Targets of v, computed at slot by I (a derivative: at its derivative's slot): one per member in loops. */
static void add_targets(Gen *G, Inst *I, Var *v, uint32_t slot, uint32_t src, const char *name)
{
	Shape *S = I->bind[0]->shape;
	if (!inst_loops(G->M, I) || !(sema_per_member(v) || sums_pairs(G->M, I))) {
		add_target(G, slot, v, src, name, v->obj);
		return;
	}
	uint32_t n = str_intern(G, name);
	for (int q = 0; q < S->n; q++)
		add_target_str(G, slot + (uint32_t)q * (v->isvec ? 3u : 1u), v, src, n, S->members[q]);
}

static void emit_block(Gen *G, Inst *I, Branch *B);

/* The steps of one branch (a plain rule: its one assignment), then zero for each variable of
 * need that none of them determines (another path does). */
static void emit_steps(Gen *G, Inst *I, Vec *steps, Vec *need)
{
	Vec set = { 0 };
	for (int i = 0; i < steps->n; i++) {
		Assign *a = steps->v[i];
		cse_reset(G);
		if (a->nest) emit_block(G, I, a->nest);
		else emit_into(G, a->e, var_operand(G, a->var, 0));
	}
	cse_reset(G);
	sema_steps_targets(steps, &set);
	for (int i = 0; i < need->n; i++) {
		Var *v = need->v[i];
		if (!vec_has(&set, v))
			emit_op(G, v->isvec ? CSF_OP_VMOV : CSF_OP_MOV, var_operand(G, v, 0), const_slot(G, (double[3]){ 0, 0, 0 }, v->isvec), 0, 0);
	}
}

/* A conditional block: its condition (comparisons located as events when the RHS needs the rule),
 * then either branch. */
static void emit_block(Gen *G, Inst *I, Branch *B)
{
	G->evinst = I->needed[CSF_SEC_RHS] ? I : NULL;
	G->evsrc = B->src;
	uint32_t c = emit(G, B->cond);
	G->evinst = NULL;
	cse_reset(G); /* what the condition computed is not there on the other path */
	uint32_t jz = pc(G);
	emit_op(G, CSF_OP_JZ, c, 0, 0, 0);
	emit_steps(G, I, &B->steps[0], &B->targets);
	uint32_t jmp = pc(G);
	emit_op(G, CSF_OP_JMP, 0, 0, 0, 0);
	G->code[jz + 2] = pc(G);
	emit_steps(G, I, &B->steps[1], &B->targets);
	G->code[jmp + 1] = pc(G);
}

/* The code of one instance, for one binding of its loops' indices. */
static void emit_body(Gen *G, Inst *I)
{
	if (I->isassert) {
		uint32_t c = emit(G, I->cond);
		I->assert_index = G->assert_tab.n;
		Shape *S = I->bind[0]->shape;
		for (int q = 0; q < (G->loop ? S->n : 1); q++) {
			vec_push(&G->assert_tab, I);
			vec_push(&G->assert_obj, G->loop ? S->members[q] : I->bind[0]);
		}
		emit_op(G, CSF_OP_ASSERT, c, csf_rel((uint32_t)I->assert_index, G->loop ? 1 : 0), 0, 0);
		return;
	}
	if (I->isstop || I->iswhen) { /* its comparisons as events of the RHS (a stop's marked terminal) */
		uint32_t first = G->nevents;
		G->evinst = I;
		G->evsrc = I->src;
		emit(G, I->cond);
		G->evinst = NULL;
		for (uint32_t k = first; k < G->nevents && I->isstop; k++) G->events[k].kind |= CSF_EVENT_TERMINAL;
		return;
	}
	if (I->isderiv) {
		Assign *a = I->then.v[0];
		emit_into(G, a->e, var_operand(G, a->var, 0) + (G->p->dstart - G->p->ystart));
		return;
	}
	if (I->top) emit_block(G, I, I->top);
	else emit_steps(G, I, &I->then, &I->targets);
}

/*
 * One instance. By shape, its code runs in a loop over the members of $0's
 * shape (level 1), and for $1 over those of $1's (level 2, skipping $0
 * itself); a $1 rule with attribute F adds its force to the sum of $0's,
 * over $1 in ascending object index, from 0. A rule among neighbours
 * (`for node[i], node[i+1]`, Inst.iloop) is one loop over its bindings,
 * each place reading its member at the index plus its own offset.
 */
void emit_inst(Gen *G, Inst *I)
{
	G->scratch = 0;
	cse_reset(G);
	add_line(G, (uint32_t)I->src);
	G->loop = inst_loops(G->M, I);
	G->iloop = G->loop && I->iloop ? I : NULL;
	int sums = sums_pairs(G->M, I);
	uint32_t top[CSF_LOOP_MAX + 1] = { 0 }, jeq = 0;
	for (int l = 1; l <= G->loop; l++) {
		if (l == 2 && sums) emit_op(G, CSF_OP_VMOV, csf_rel(acc_slot(G, I), 2), const_slot(G, (double[3]){ 0, 0, 0 }, 1), 0, 0);
		top[l] = pc(G);
		emit_op(G, CSF_OP_LOOP, (uint32_t)l, G->iloop ? (uint32_t)I->iloop : (uint32_t)I->bind[l - 1]->shape->n, 0, 0);
	}
	if (G->loop == 2 && I->bind[0]->shape == I->bind[1]->shape) {
		jeq = pc(G);
		emit_op(G, CSF_OP_JEQ, 1, 2, 0, 0);
	}
	emit_body(G, I);
	for (int i = 0; sums && i < I->targets.n; i++) {
		uint32_t acc = csf_rel(acc_slot(G, I), 2);
		emit_op(G, CSF_OP_VADD, acc, acc, var_operand(G, I->targets.v[i], 0), 0);
	}
	if (jeq) G->code[jeq + 3] = pc(G);
	for (int l = G->loop; l >= 1; l--) {
		emit_op(G, CSF_OP_NEXT, (uint32_t)l, top[l] + csf_insn_len(CSF_OP_LOOP), 0, 0);
		G->code[top[l] + 3] = pc(G);
	}
	G->loop = 0;
	G->iloop = NULL;
	if (I->isassert || I->isstop || I->iswhen) return;
	if (I->isderiv) {
		Var *v = ((Assign *)I->then.v[0])->var;
		add_targets(G, I, v, G->p->dstart + (var_slot(G, v) - G->p->ystart), (uint32_t)I->src, xprintf("%s'", v->name));
		return;
	}
	for (int i = 0; i < I->targets.n; i++) {
		Var *v = I->targets.v[i];
		uint32_t src = (uint32_t)I->src;
		for (int b = 0; b < 2; b++) {
			Vec *br = b ? &I->els : &I->then;
			for (int k = 0; k < br->n; k++)
				if (((Assign *)br->v[k])->var == v) src = (uint32_t)((Assign *)br->v[k])->src;
		}
		add_targets(G, I, v, sums ? acc_slot(G, I) : var_slot(G, v), src, v->name);
	}
}
