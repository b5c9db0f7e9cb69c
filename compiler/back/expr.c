/*
 * expr.c - the code of expressions: instructions appended to the section
 * being generated, operands evaluated into scratch, common subexpressions
 * computed once per equation, comparisons of conditional rules located as
 * events, and the sum of a body's forces (RF).
 */
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

void emit_words(Gen *G, int op, const uint32_t *ops)
{
	int n = csf_opinfo_table[op].nops;
	G->code = grow(G->code, &G->capcode, G->ncode + 1 + (uint32_t)n, sizeof(uint32_t));
	G->code[G->ncode++] = (uint32_t)op;
	for (int i = 0; i < n; i++) G->code[G->ncode++] = ops[i];
}

void emit_op(Gen *G, int op, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
	uint32_t ops[4] = { a, b, c, d };
	emit_words(G, op, ops);
}

/* Emits R[dest] := R[x] ^ k for a constant k: POWI when csf_powi computes it, else POW. */
void emit_pow_const(Gen *G, uint32_t dest, uint32_t x, double k)
{
	if (csf_is_powi(k)) emit_op(G, CSF_OP_POWI, dest, x, (uint32_t)(int)k, 0);
	else emit_op(G, CSF_OP_POW, dest, x, const_slot(G, (double[3]){ k, 0, 0 }, 0), 0);
}

/* The slot of I's sums over $1 (sums_pairs), one vector per member of $0's shape. */
uint32_t acc_slot(Gen *G, Inst *I)
{
	if (!I->acc) I->acc = 1 + (int)alloc_mem(G, 3u * (uint32_t)I->bind[0]->shape->n, NULL);
	return (uint32_t)I->acc - 1;
}

/* The terms of object o's RF, the forces of its F rules in their order (of a $1 rule in loops,
   its sum over $1), as operand words into t[0..max); returns how many there are. */
static int rf_terms(Gen *G, Object *o, uint32_t *t, int max)
{
	Vec *fs = &G->Finsts[o->index];
	int n = 0;
	for (int i = 0; i < fs->n; i++) {
		Inst *I = fs->v[i];
		if (sums_pairs(G->M, I)) {
			if (n < max) t[n] = G->loop ? csf_rel(acc_slot(G, I), 2) : acc_slot(G, I);
			n++;
			continue;
		}
		for (int k = 0; k < I->targets.n; k++, n++)
			if (n < max) t[n] = var_operand(G, I->targets.v[k], 0);
	}
	return n;
}

/* Structural equality of two expressions (same operations on the same operands). */
static int expr_same(const RExpr *a, const RExpr *b)
{
	if (a == b) return 1;
	if (a->k != b->k || a->isvec != b->isvec) return 0;
	switch (a->k) {
	case R_CONST: return memcmp(a->c, b->c, sizeof a->c) == 0;
	case R_VAR: return a->var == b->var && a->place == b->place && a->obj == b->obj;
	case R_RF: return a->obj == b->obj;
	case R_COMP: return a->comp == b->comp && expr_same(a->a[0], b->a[0]);
	case R_OP:
		if (a->op != b->op || a->n != b->n) return 0;
		for (int i = 0; i < a->n; i++)
			if (!expr_same(a->a[i], b->a[i])) return 0;
		return 1;
	}
	return 0;
}


/*
 * A comparison in the condition of a conditional rule that the RHS needs is
 * an event: its value (the difference of its sides, positive when true)
 * goes to a slot of its own, and EVGT/EVGE give the side the runtime froze
 * at the last located crossing. Both sections share the event.
 */
static int emit_event(Gen *G, RExpr *e, uint32_t dest)
{
	int op = e->op;
	if (!G->evinst || !(op == CSF_OP_LT || op == CSF_OP_LE || op == CSF_OP_GT || op == CSF_OP_GE)) return 0;
	char *key = xprintf("%p", (void *)e);
	uintptr_t known = (uintptr_t)map_get(&G->evmap, key);
	/* in a loop (one level: by shape, conditional rules of pairs are not), one event per member */
	uint32_t n = G->loop ? (uint32_t)G->evinst->bind[0]->shape->n : 1;
	if (!known) {
		G->events = grow(G->events, &G->capevents, G->nevents + n, sizeof *G->events);
		uint32_t value = alloc_mem(G, n, NULL), mode = alloc_mem(G, n, NULL);
		int strict = op == CSF_OP_LT || op == CSF_OP_GT;
		known = G->nevents + 1;
		for (uint32_t q = 0; q < n; q++) {
			G->mem[mode + q] = -1;
			G->events[G->nevents++] = (csf_event){ strict ? 0u : 1u, value + q, mode + q, (uint32_t)G->evsrc };
		}
		map_put(&G->evmap, key, (void *)known);
	}
	const csf_event *ev = &G->events[known - 1];
	uint32_t r = G->loop ? 1 : 0, value = csf_rel(ev->value, r), mode = csf_rel(ev->mode, r);
	uint32_t x = emit(G, e->a[0]), y = emit(G, e->a[1]);
	if (op == CSF_OP_LT || op == CSF_OP_LE) emit_op(G, CSF_OP_SUB, value, y, x, 0);
	else emit_op(G, CSF_OP_SUB, value, x, y, 0);
	emit_op(G, ev->kind ? CSF_OP_EVGE : CSF_OP_EVGT, dest, value, mode, 0);
	return 1;
}

void emit_into(Gen *G, RExpr *e, uint32_t dest)
{
	if (e->k == R_OP && emit_event(G, e, dest)) return;
	if (e->k == R_OP && e->op == CSF_OP_POW && e->a[1]->k == R_CONST) {
		emit_pow_const(G, dest, emit(G, e->a[0]), e->a[1]->c[0]);
		return;
	}
	if (e->k == R_OP) {
		uint32_t o[3] = { 0, 0, 0 };
		for (int i = 0; i < e->n; i++) o[i] = emit(G, e->a[i]);
		emit_op(G, e->op, dest, o[0], o[1], o[2]);
		return;
	}
	if (e->k == R_RF) {
		int n = rf_terms(G, e->obj, NULL, 0);
		if (n >= 2) {
			uint32_t *t = xalloc((size_t)n * sizeof *t);
			rf_terms(G, e->obj, t, n);
			emit_op(G, CSF_OP_VADD, dest, t[0], t[1], 0);
			for (int i = 2; i < n; i++) emit_op(G, CSF_OP_VADD, dest, dest, t[i], 0);
			return;
		}
	}
	uint32_t s = emit(G, e);
	emit_op(G, e->isvec ? CSF_OP_VMOV : CSF_OP_MOV, dest, s, 0, 0);
}

uint32_t emit(Gen *G, RExpr *e)
{
	switch (e->k) {
	case R_CONST: return const_slot(G, e->c, e->isvec);
	case R_VAR: /* (a term of a sum at a lean member: its place of the shape's array) */
		if (e->obj) return prop_slot(G, e->var, e->obj);
		return e->var->kind == V_TIME ? G->p->tslot : var_operand(G, e->var, e->place);
	case R_COMP: return emit(G, e->a[0]) + (uint32_t)e->comp;
	case R_RF: {
		uint32_t t[1];
		int n = rf_terms(G, e->obj, t, 1);
		if (n == 0) return const_slot(G, (double[3]){ 0, 0, 0 }, 1);
		if (n == 1) return t[0];
		uint32_t d = new_scratch(G, 3);
		emit_into(G, e, d);
		return d;
	}
	case R_OP: {
		/* the same operation on the same operands within one equation is computed once:
		   the value is the same bits, so this never changes a result */
		for (int i = 0; i < G->ncse; i++)
			if (expr_same(G->cse[i].e, e)) return G->cse[i].slot;
		uint32_t d = new_scratch(G, e->isvec ? 3 : 1);
		emit_into(G, e, d);
		if (G->ncse < (int)(sizeof G->cse / sizeof G->cse[0])) {
			G->cse[G->ncse].e = e;
			G->cse[G->ncse++].slot = d;
		}
		return d;
	}
	}
	return 0;
}
