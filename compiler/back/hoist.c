/*
 * hoist.c - loop-invariant code motion: an instruction of an innermost
 * loop of level 2 or deeper whose operands the loop does not change (no
 * operand through its index, nothing it reads written in the loop) moves to
 * just before the loop, where it runs once instead of once an iteration.
 *
 * Only what changes nothing else moves: an instruction with a result (a
 * pure function of its operands, csf_ops.h), into scratch slots [lo, hi)
 * (the compiler's temporaries) that no other instruction of the loop writes,
 * that nothing in the loop reads before it, and that no code of the section
 * outside the loop reads at all. The value it computes is the one every
 * iteration computed, by the same operation on the same operands, so the
 * section computes the same bits; an iteration the loop skips (JEQ, JZ)
 * merely had not needed it. The VM and the generated C run the moved code
 * alike: both run the bytecode.
 *
 * Loop fusion: two loops one after the other at the same level over the
 * same count (two rules over one array: W = g.mul(m), then D = v.mul(-k))
 * become one, when running them member by member computes what running the
 * first to its end and then the second did: their bodies straight-line
 * arithmetic, and every slot one writes that the other touches either the
 * same member's (the same operand: the same base through the same index)
 * or a temporary each body writes before it reads it. A million members
 * are then walked once, not once a rule.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "gen_int.h"
#include "insn.h"

/* Slots [a0, a1) and [b0, b1) meet. */
static int meet(uint64_t a0, uint64_t a1, uint64_t b0, uint64_t b1) { return a0 < b1 && b0 < a1; }

/* The slots operand k of the instruction at pc reaches over the loop counts cnt. */
static void reach(const uint32_t *code, uint32_t pc, int k, const uint32_t *cnt, uint64_t *lo, uint64_t *hi)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
	uint32_t w = code[pc + 1 + k], r = csf_reg(w);
	*lo = w & CSF_SLOT_MASK;
	*hi = csf_operand_end(w, csf_kind_width(oi->kind[k]), r ? cnt[csf_reg_level(r)] : 1);
}

/* Does an instruction of [from, to) read (write: writes) slots [lo, hi)? cnt: the counts of the loops open at from. */
static int touches(const uint32_t *code, uint32_t from, uint32_t to, const uint32_t *cnt0, uint64_t lo, uint64_t hi,
                   int writes)
{
	uint32_t cnt[CSF_LOOP_MAX + 1];
	memcpy(cnt, cnt0, sizeof cnt);
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
		for (int k = 0; k < oi->nops; k++) {
			uint64_t a, b;
			if (!csf_kind_slot(oi->kind[k]) || csf_kind_write(oi->kind[k]) != writes) continue;
			reach(code, pc, k, cnt, &a, &b);
			if (meet(a, b, lo, hi)) return 1;
		}
	}
	return 0;
}

/*
 * May the instruction at q of the innermost loop whose body is [b, e)
 * (level, counts cnt) move before the loop? code[0..n) is the section.
 */
static int invariant(const uint32_t *code, uint32_t n, uint32_t b, uint32_t e, uint32_t q, uint32_t level,
                     const uint32_t *cnt, uint32_t lo, uint32_t hi)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[q]];
	if (code[q] == CSF_OP_JMP || code[q] == CSF_OP_JZ || code[q] == CSF_OP_ASSERT || code[q] == CSF_OP_LOOP ||
	    code[q] == CSF_OP_NEXT || code[q] == CSF_OP_JEQ || code[q] == CSF_OP_CONTACT || code[q] == CSF_OP_CONSTRAIN)
		return 0;
	uint64_t d0, d1;
	reach(code, q, 0, cnt, &d0, &d1);
	if (csf_reg(code[q + 1]) || d0 < lo || d1 > hi) return 0;
	for (int k = 1; k < oi->nops; k++) {
		uint64_t a, z;
		if (!csf_kind_slot(oi->kind[k])) continue;
		uint32_t r = csf_reg(code[q + 1 + k]);
		if (r && csf_reg_level(r) >= level) return 0;
		reach(code, q, k, cnt, &a, &z);
		if (meet(a, z, d0, d1) || touches(code, b, e, cnt, a, z, 1)) return 0;
	}
	/* the result: written only here in the loop, read in it only after, read nowhere outside it */
	for (uint32_t pc = b; pc < e; pc += csf_insn_len(code[pc]))
		if (pc != q && touches(code, pc, pc + csf_insn_len(code[pc]), cnt, d0, d1, 1)) return 0;
	if (touches(code, b, q, cnt, d0, d1, 0)) return 0;
	static const uint32_t none[CSF_LOOP_MAX + 1] = { 1, 1, 1, 1 };
	return !touches(code, 0, b - csf_insn_len(CSF_OP_LOOP), none, d0, d1, 0) && !touches(code, e, n, cnt, d0, d1, 0);
}

/* A pc t of the section after the instruction at q (len words) moved to l, the loop's LOOP. */
static uint32_t moved(uint32_t t, uint32_t l, uint32_t q, uint32_t len)
{
	return t > l && t < q ? t + len : t == q ? q + len : t;
}

/* Moves the instruction at q to l, ahead of the LOOP there: every pc the section and its lines name follows. */
static void move(csf_prog *p, int sec, uint32_t l, uint32_t q)
{
	uint32_t *code = p->code[sec], len = csf_insn_len(code[q]), ins[1 + 4];
	memcpy(ins, code + q, len * sizeof *ins);
	memmove(code + l + len, code + l, (size_t)(q - l) * sizeof *code);
	memcpy(code + l, ins, len * sizeof *ins);
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++)
			if (oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) code[pc + 1 + k] = moved(code[pc + 1 + k], l, q, len);
	}
	for (uint32_t i = 0; i < p->nlines[sec]; i++) p->lines[sec][i].pc = moved(p->lines[sec][i].pc, l, q, len);
}

/* One instruction of section sec moved out of its loop; 0 when none can. */
static int hoist_one(csf_prog *p, int sec, uint32_t lo, uint32_t hi)
{
	const uint32_t *code = p->code[sec];
	uint32_t n = p->ncode[sec], cnt[CSF_LOOP_MAX + 1] = { 1, 1, 1, 1 };
	for (uint32_t l = 0; l < n; l += csf_insn_len(code[l])) {
		if (code[l] != CSF_OP_LOOP) continue;
		cnt[code[l + 1]] = code[l + 2];
		uint32_t level = code[l + 1], b = l + csf_insn_len(CSF_OP_LOOP), e = code[l + 3] - csf_insn_len(CSF_OP_NEXT);
		if (level < 2 || code[l + 2] == 0) continue;
		int inner = 1;
		for (uint32_t q = b; q < e && inner; q += csf_insn_len(code[q])) inner = code[q] != CSF_OP_LOOP;
		for (uint32_t q = b; q < e && inner; q += csf_insn_len(code[q]))
			if (code[q] == CSF_OP_CONTACT || code[q] == CSF_OP_CONSTRAIN) inner = 0;
		for (uint32_t q = b; q < e && inner; q += csf_insn_len(code[q]))
			if (invariant(code, n, b, e, q, level, cnt, lo, hi)) {
				move(p, sec, l, q);
				return 1;
			}
	}
	return 0;
}

void gen_hoist(csf_prog *p, uint32_t lo, uint32_t hi)
{
	for (int sec = 0; sec < CSF_NSEC; sec++)
		for (uint32_t k = 0; k < p->ncode[sec] && hoist_one(p, sec, lo, hi); k++) continue;
}

/* May the instruction op be in a loop that is fused: arithmetic, no control flow and no event? */
static int fusable(uint32_t op)
{
	switch (op) {
#define OP(name, n, a, b, c, d, syn)
#define CTRL(name, n, a, b, c, d, syn) case CSF_OP_##name:
#define STEP OP
#include "opcodes.def"
#undef STEP
#undef CTRL
#undef OP
	case CSF_OP_EVGT:
	case CSF_OP_EVGE: return 0;
	default: return 1;
	}
}

/* A slot operand of a loop body: its word, its instruction, whether it writes, the slots it reaches. */
typedef struct Opnd { uint32_t w, pc, write; uint64_t lo, hi; } Opnd;

/* The slot operands of the straight-line body [b, e) (counts cnt) into o (n so far); -1: not straight-line. */
static int operands(const uint32_t *code, uint32_t b, uint32_t e, const uint32_t *cnt, Opnd **o, size_t *n, size_t *cap)
{
	for (uint32_t pc = b; pc < e; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		if (!fusable(code[pc])) return -1;
		for (int k = 0; k < oi->nops; k++) {
			if (!csf_kind_slot(oi->kind[k])) continue;
			if (*n == *cap) *o = xrealloc(*o, (*cap = *cap ? 2 * *cap : 64) * sizeof **o);
			Opnd *x = &(*o)[(*n)++];
			x->w = code[pc + 1 + k], x->pc = pc, x->write = (uint32_t)csf_kind_write(oi->kind[k]);
			reach(code, pc, k, cnt, &x->lo, &x->hi);
		}
	}
	return 0;
}

/* Does the body from b write every slot of [lo, hi) before the instruction at pc? */
static int written_before(const uint32_t *code, uint32_t b, uint32_t pc, const uint32_t *cnt, uint64_t lo, uint64_t hi)
{
	for (uint64_t s = lo; s < hi; s++)
		if (!touches(code, b, pc, cnt, s, s + 1, 1)) return 0;
	return 1;
}

/* Operand x of one body and y of the other (at least one a write) allow running them member by member. */
static int independent(const uint32_t *code, const Opnd *x, uint32_t bx, const Opnd *y, uint32_t by, uint32_t level,
                       const uint32_t *cnt, uint32_t lo, uint32_t hi)
{
	if (!meet(x->lo, x->hi, y->lo, y->hi)) return 1;
	uint32_t rx = csf_reg(x->w), ry = csf_reg(y->w);
	if (rx && x->w == y->w && csf_reg_level(rx) == level && x->hi - x->lo == y->hi - y->lo) return 1; /* the same member's */
	if (rx || ry || x->lo < lo || x->hi > hi || y->lo < lo || y->hi > hi) return 0;
	/* a temporary: each body's reads of it come after its own writes */
	return (x->write || written_before(code, bx, x->pc, cnt, x->lo, x->hi)) &&
	       (y->write || written_before(code, by, y->pc, cnt, y->lo, y->hi));
}

/* Does a jump of the section other than those of the loops at l1 and l2 name a pc in (l1, a2)? */
static int jumped_into(const csf_prog *p, int sec, uint32_t l1, uint32_t l2, uint32_t a2)
{
	const uint32_t *code = p->code[sec];
	uint32_t e1 = l2 - csf_insn_len(CSF_OP_NEXT), e2 = a2 - csf_insn_len(CSF_OP_NEXT);
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		if (pc == l1 || pc == e1 || pc == l2 || pc == e2) continue;
		for (int k = 0; k < oi->nops; k++)
			if ((oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) && code[pc + 1 + k] > l1 && code[pc + 1 + k] < a2) return 1;
	}
	return 0;
}

/* One pair of loops of section sec fused; 0 when none can be. */
static int fuse_loops_one(csf_prog *p, int sec, uint32_t lo, uint32_t hi)
{
	uint32_t *code = p->code[sec], n = p->ncode[sec], cnt[CSF_LOOP_MAX + 1] = { 1, 1, 1, 1 };
	uint32_t ll = csf_insn_len(CSF_OP_LOOP), nl = csf_insn_len(CSF_OP_NEXT);
	Opnd *o = NULL;
	size_t cap = 0;
	int done = 0;
	for (uint32_t l1 = 0; l1 < n && !done; l1 += csf_insn_len(code[l1])) {
		if (code[l1] != CSF_OP_LOOP) continue;
		cnt[code[l1 + 1]] = code[l1 + 2];
		uint32_t level = code[l1 + 1], l2 = code[l1 + 3];
		if (l2 + ll > n || code[l2] != CSF_OP_LOOP || code[l2 + 1] != level || code[l2 + 2] != code[l1 + 2]) continue;
		uint32_t b1 = l1 + ll, e1 = l2 - nl, b2 = l2 + ll, a2 = code[l2 + 3], e2 = a2 - nl;
		size_t na = 0, nb = 0;
		if (operands(code, b1, e1, cnt, &o, &na, &cap) || (nb = na, operands(code, b2, e2, cnt, &o, &nb, &cap)) ||
		    jumped_into(p, sec, l1, l2, a2))
			continue;
		int ok = 1;
		for (size_t i = 0; i < na && ok; i++)
			for (size_t j = na; j < nb && ok; j++)
				if (o[i].write || o[j].write) ok = independent(code, &o[i], b1, &o[j], b2, level, cnt, lo, hi);
		if (!ok) continue;
		/* drop the first NEXT and the second LOOP: [e1, b2) */
		uint32_t gone = b2 - e1;
		memmove(code + e1, code + b2, (size_t)(n - b2) * sizeof *code);
		p->ncode[sec] = n -= gone;
		for (uint32_t pc = 0; pc < n; pc += csf_insn_len(code[pc])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			for (int k = 0; k < oi->nops; k++)
				if ((oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) && code[pc + 1 + k] >= b2) code[pc + 1 + k] -= gone;
		}
		code[l1 + 3] = a2 - gone;     /* the first LOOP ends past the second NEXT, */
		code[e2 - gone + 2] = b1;     /* which goes back to the first body */
		for (uint32_t i = 0; i < p->nlines[sec]; i++) {
			csf_line *l = &p->lines[sec][i];
			l->pc = l->pc >= b2 ? l->pc - gone : l->pc >= e1 ? e1 : l->pc;
		}
		done = 1;
	}
	free(o);
	return done;
}

void gen_fuse_loops(csf_prog *p, uint32_t lo, uint32_t hi)
{
	for (int sec = 0; sec < CSF_NSEC; sec++)
		while (fuse_loops_one(p, sec, lo, hi)) continue;
}

/* Does some jump of the section, or a line of its table, name pc? */
static int named(const csf_prog *p, int sec, uint32_t at)
{
	const uint32_t *code = p->code[sec];
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++)
			if ((oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) && code[pc + 1 + k] == at) return 1;
	}
	for (uint32_t i = 0; i < p->nlines[sec]; i++)
		if (p->lines[sec][i].pc == at) return 1;
	return 0;
}

/*
 * POWI t, y, n then DIV a, x, t, with t a scratch slot [lo, hi) that only
 * that DIV reads: DIVPOWI a, x, y, n (csf_op_DIVPOWI: the same two
 * operations), 3 words shorter. One fusion of section sec; 0 when none.
 */
static int fuse_one(csf_prog *p, int sec, uint32_t lo, uint32_t hi)
{
	uint32_t *code = p->code[sec], n = p->ncode[sec];
	static const uint32_t none[CSF_LOOP_MAX + 1] = { 1, 1, 1, 1 };
	for (uint32_t q = 0; q < n; q += csf_insn_len(code[q])) {
		uint32_t d = q + csf_insn_len(CSF_OP_POWI), t = code[q + 1];
		if (code[q] != CSF_OP_POWI || d >= n || code[d] != CSF_OP_DIV || code[d + 3] != t || code[d + 2] == t ||
		    t < lo || t >= hi || named(p, sec, d))
			continue;
		uint32_t cnt[CSF_LOOP_MAX + 1] = { 1, 1, 1, 1 }; /* the counts of the loops open at the DIV */
		for (uint32_t pc = 0; pc < d; pc += csf_insn_len(code[pc]))
			if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
		if (touches(code, 0, d, none, t, t + 1ull, 0) || touches(code, d + csf_insn_len(CSF_OP_DIV), n, cnt, t, t + 1ull, 0))
			continue;
		uint32_t a = code[d + 1], x = code[d + 2], y = code[q + 2], e = code[q + 3];
		code[q] = CSF_OP_DIVPOWI, code[q + 1] = a, code[q + 2] = x, code[q + 3] = y, code[q + 4] = e;
		uint32_t cut = q + csf_insn_len(CSF_OP_DIVPOWI), gone = d + csf_insn_len(CSF_OP_DIV) - cut;
		memmove(code + cut, code + cut + gone, (size_t)(n - cut - gone) * sizeof *code);
		p->ncode[sec] = n - gone;
		for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			for (int k = 0; k < oi->nops; k++)
				if ((oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) && code[pc + 1 + k] > q) code[pc + 1 + k] -= gone;
		}
		for (uint32_t i = 0; i < p->nlines[sec]; i++)
			if (p->lines[sec][i].pc > q) p->lines[sec][i].pc -= gone;
		return 1;
	}
	return 0;
}

void gen_fuse(csf_prog *p, uint32_t lo, uint32_t hi)
{
	for (int sec = 0; sec < CSF_NSEC; sec++)
		while (fuse_one(p, sec, lo, hi)) continue;
}
