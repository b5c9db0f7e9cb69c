/*
 * jac.c - the JAC section: forward-mode differentiation of the RHS section
 * for the exact Jacobian, and the analysis of which slots depend on which
 * (depends, shared with pairs.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "gen_int.h"

/* ---- the Jacobian: forward-mode differentiation of the RHS section ----
 *
 * JAC repeats RHS's instructions and, before each one whose result depends
 * on the state or t ("active"), computes the tangent of that result from
 * the tangents of its operands: tangent(s) lives in slot s + P. The runtime
 * seeds the tangents of the state (one column of the identity) and of t,
 * runs JAC and reads the tangents of the derivatives: one column of the
 * exact Jacobian, the same arithmetic on both execution paths. Tangent code
 * runs before its instruction, so an operand the instruction overwrites is
 * still intact; a result it needs is recomputed into a work slot.
 */
typedef struct Jac {
	Gen *G;
	uint32_t P;          /* tangent offset */
	uint32_t W;          /* first work slot */
	uint32_t zero, one, two, ln10, zvec;
	unsigned char *act;  /* active primal slots */
	uint32_t cnt[CSF_LOOP_MAX + 1]; /* the counts of the loops around the instruction */
} Jac;

/*
 * The slots [lo, hi) an operand word of kind `kind` can name, given the
 * counts of the loops around it (cnt[level]): all of its array for a word
 * relative to a loop index. The analyses below are by array, not by element.
 */
static void operand_range(uint32_t w, int kind, const uint32_t *cnt, uint32_t *lo, uint32_t *hi)
{
	uint32_t r = csf_reg(w);
	*lo = w & CSF_SLOT_MASK;
	*hi = (uint32_t)csf_operand_end(w, csf_kind_width(kind), r ? cnt[csf_reg_level(r)] : 1);
}

static int any_marked(const unsigned char *act, uint32_t w, int kind, const uint32_t *cnt)
{
	uint32_t lo, hi;
	operand_range(w, kind, cnt, &lo, &hi);
	for (uint32_t s = lo; s < hi; s++)
		if (act[s]) return 1;
	return 0;
}

static int jact(Jac *J, int kind, uint32_t s) { return any_marked(J->act, s, kind, J->cnt); }

#define JE(op, a, b, c, d) emit_op(J->G, CSF_OP_##op, a, b, c, d)
#define T(x) ((x) + J->P)
#define WK(i) (J->W + (i))

/* Emits the tangent of vector instruction op (operands o[], inputs' activity in[]) as tangent
   does; returns 0 if op is not one of these. */
static int tangent_vec(Jac *J, int op, const uint32_t *o, const int *in)
{
	uint32_t a = o[0], b = o[1], c = o[2];
	uint32_t ta = T(a), tc = in[1] ? T(c) : J->zero;
	uint32_t vtb = in[0] ? T(b) : J->zvec, vtc = in[1] ? T(c) : J->zvec;
	switch (op) {
	case CSF_OP_VMUL: /* dv s + v ds */
		JE(VMUL, WK(0), vtb, c, 0);
		JE(VMUL, WK(3), b, tc, 0);
		JE(VADD, ta, WK(0), WK(3), 0);
		break;
	case CSF_OP_VDIV: /* (dv - z ds) / s */
		JE(VDIV, WK(0), b, c, 0);
		JE(VMUL, WK(3), WK(0), tc, 0);
		JE(VSUB, WK(6), vtb, WK(3), 0);
		JE(VDIV, ta, WK(6), c, 0);
		break;
	case CSF_OP_VDOT:
		JE(VDOT, WK(0), vtb, c, 0);
		JE(VDOT, WK(1), b, vtc, 0);
		JE(ADD, ta, WK(0), WK(1), 0);
		break;
	case CSF_OP_VCROSS:
		JE(VCROSS, WK(0), vtb, c, 0);
		JE(VCROSS, WK(3), b, vtc, 0);
		JE(VADD, ta, WK(0), WK(3), 0);
		break;
	case CSF_OP_VMAG: /* (v . dv) / |v| */
		JE(VMAG, WK(0), b, 0, 0);
		JE(VDOT, WK(1), b, vtb, 0);
		JE(DIV, ta, WK(1), WK(0), 0);
		break;
	case CSF_OP_VUNIT: /* (dv - u (u . dv)) / |v| */
		JE(VMAG, WK(0), b, 0, 0);
		JE(VDIV, WK(1), b, WK(0), 0);
		JE(VDOT, WK(4), WK(1), vtb, 0);
		JE(VMUL, WK(5), WK(1), WK(4), 0);
		JE(VSUB, WK(8), vtb, WK(5), 0);
		JE(VDIV, ta, WK(8), WK(0), 0);
		break;
	case CSF_OP_VPROJ: { /* p = k w, k = (u.w)/(w.w): dp = dk w + k dw */
		JE(VDOT, WK(0), b, c, 0);                    /* u.w */
		JE(VDOT, WK(1), c, c, 0);                    /* w.w */
		JE(DIV, WK(2), WK(0), WK(1), 0);             /* k */
		JE(VDOT, WK(3), vtb, c, 0);
		JE(VDOT, WK(4), b, vtc, 0);
		JE(ADD, WK(5), WK(3), WK(4), 0);             /* d(u.w) */
		JE(VDOT, WK(6), c, vtc, 0);
		JE(MUL, WK(7), WK(6), J->two, 0);            /* d(w.w) */
		JE(MUL, WK(8), WK(2), WK(7), 0);
		JE(SUB, WK(9), WK(5), WK(8), 0);
		JE(DIV, WK(10), WK(9), WK(1), 0);            /* dk */
		JE(VMUL, WK(11), c, WK(10), 0);
		JE(VMUL, WK(14), vtc, WK(2), 0);
		JE(VADD, ta, WK(11), WK(14), 0);
		break;
	}
	case CSF_OP_VANGLE: { /* theta = atan2(|u x w|, u.w) */
		JE(VCROSS, WK(0), b, c, 0);                  /* x = u x w */
		JE(VMAG, WK(3), WK(0), 0, 0);                /* s = |x| */
		JE(VDOT, WK(4), b, c, 0);                    /* q = u.w */
		JE(VCROSS, WK(5), vtb, c, 0);
		JE(VCROSS, WK(8), b, vtc, 0);
		JE(VADD, WK(11), WK(5), WK(8), 0);           /* dx */
		JE(VDOT, WK(14), WK(0), WK(11), 0);
		JE(DIV, WK(15), WK(14), WK(3), 0);           /* ds = x.dx / s */
		JE(VDOT, WK(16), vtb, c, 0);
		JE(VDOT, WK(17), b, vtc, 0);
		JE(ADD, WK(18), WK(16), WK(17), 0);          /* dq */
		JE(MUL, WK(19), WK(4), WK(15), 0);
		JE(MUL, WK(20), WK(3), WK(18), 0);
		JE(SUB, WK(21), WK(19), WK(20), 0);          /* q ds - s dq */
		JE(MUL, WK(22), WK(3), WK(3), 0);
		JE(MUL, WK(23), WK(4), WK(4), 0);
		JE(ADD, WK(24), WK(22), WK(23), 0);
		JE(DIV, ta, WK(21), WK(24), 0);
		break;
	}
	default: return 0;
	}
	return 1;
}

/* Emits the tangent of instruction ins (operands o[]); its inputs' activity in in[]. */
static void tangent(Jac *J, int op, const uint32_t *o, const int *in)
{
	uint32_t a = o[0], b = o[1], c = o[2], d = o[3];
	uint32_t ta = T(a);
	/* tb, tc: operand tangents, or zero where the operand is inactive */
	uint32_t tb = in[0] ? T(b) : J->zero, tc = in[1] ? T(c) : J->zero;
	uint32_t vtb = in[0] ? T(b) : J->zvec, vtc = in[1] ? T(c) : J->zvec;
	switch (op) {
	case CSF_OP_MOV: JE(MOV, ta, tb, 0, 0); break;
	case CSF_OP_VMOV: JE(VMOV, ta, vtb, 0, 0); break;
	case CSF_OP_VPACK: JE(VPACK, ta, tb, tc, in[2] ? T(d) : J->zero); break;
	case CSF_OP_ADD: JE(ADD, ta, tb, tc, 0); break;
	case CSF_OP_SUB: JE(SUB, ta, tb, tc, 0); break;
	case CSF_OP_NEG: JE(NEG, ta, tb, 0, 0); break;
	case CSF_OP_VADD: JE(VADD, ta, vtb, vtc, 0); break;
	case CSF_OP_VSUB: JE(VSUB, ta, vtb, vtc, 0); break;
	case CSF_OP_VNEG: JE(VNEG, ta, vtb, 0, 0); break;
	case CSF_OP_MUL: /* db c + b dc */
		JE(MUL, WK(0), tb, c, 0);
		JE(MUL, WK(1), b, tc, 0);
		JE(ADD, ta, WK(0), WK(1), 0);
		break;
	case CSF_OP_DIV: /* (db - z dc) / c */
		JE(DIV, WK(0), b, c, 0);
		JE(MUL, WK(1), WK(0), tc, 0);
		JE(SUB, WK(2), tb, WK(1), 0);
		JE(DIV, ta, WK(2), c, 0);
		break;
	case CSF_OP_POW: /* c b^(c-1) db + ln(b) b^c dc */
		JE(SUB, WK(0), c, J->one, 0);
		JE(POW, WK(1), b, WK(0), 0);
		JE(MUL, WK(2), WK(1), c, 0);
		JE(MUL, WK(3), WK(2), tb, 0);
		if (in[1]) {
			JE(POW, WK(4), b, c, 0);
			JE(LOG, WK(5), b, 0, 0);
			JE(MUL, WK(6), WK(5), WK(4), 0);
			JE(MUL, WK(7), WK(6), tc, 0);
			JE(ADD, ta, WK(3), WK(7), 0);
		} else {
			JE(MOV, ta, WK(3), 0, 0);
		}
		break;
	case CSF_OP_POWI: { /* n b^(n-1) db, with b^(n-1) computed as '^' computes it */
		int n = csf_imm(c);
		if (n == 0) {
			JE(MOV, ta, J->zero, 0, 0);
			break;
		}
		emit_pow_const(J->G, WK(0), b, n - 1);
		JE(MUL, WK(1), WK(0), const_slot(J->G, (double[3]){ n, 0, 0 }, 0), 0);
		JE(MUL, ta, WK(1), tb, 0);
		break;
	}
	case CSF_OP_ATAN2: /* (c db - b dc) / (b^2 + c^2) */
		JE(MUL, WK(0), b, b, 0);
		JE(MUL, WK(1), c, c, 0);
		JE(ADD, WK(2), WK(0), WK(1), 0);
		JE(MUL, WK(3), c, tb, 0);
		JE(MUL, WK(4), b, tc, 0);
		JE(SUB, WK(5), WK(3), WK(4), 0);
		JE(DIV, ta, WK(5), WK(2), 0);
		break;
	case CSF_OP_MIN: case CSF_OP_MAX: /* the tangent of the operand chosen */
		if (op == CSF_OP_MIN) JE(LE, WK(0), b, c, 0);
		else JE(GE, WK(0), b, c, 0);
		JE(MUL, WK(1), WK(0), tb, 0);
		JE(SUB, WK(2), J->one, WK(0), 0);
		JE(MUL, WK(3), WK(2), tc, 0);
		JE(ADD, ta, WK(1), WK(3), 0);
		break;
	case CSF_OP_SIN: JE(COS, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_COS: JE(SIN, WK(0), b, 0, 0); JE(NEG, WK(1), WK(0), 0, 0); JE(MUL, ta, WK(1), tb, 0); break;
	case CSF_OP_TAN: JE(COS, WK(0), b, 0, 0); JE(MUL, WK(1), WK(0), WK(0), 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_ASIN: case CSF_OP_ACOS:
		JE(MUL, WK(0), b, b, 0);
		JE(SUB, WK(1), J->one, WK(0), 0);
		JE(SQRT, WK(2), WK(1), 0, 0);
		JE(DIV, WK(3), tb, WK(2), 0);
		if (op == CSF_OP_ASIN) JE(MOV, ta, WK(3), 0, 0);
		else JE(NEG, ta, WK(3), 0, 0);
		break;
	case CSF_OP_ATAN: JE(MUL, WK(0), b, b, 0); JE(ADD, WK(1), J->one, WK(0), 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_SINH: JE(COSH, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_COSH: JE(SINH, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_TANH:
		JE(TANH, WK(0), b, 0, 0);
		JE(MUL, WK(1), WK(0), WK(0), 0);
		JE(SUB, WK(2), J->one, WK(1), 0);
		JE(MUL, ta, WK(2), tb, 0);
		break;
	case CSF_OP_EXP: JE(EXP, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_LOG: JE(DIV, ta, tb, b, 0); break;
	case CSF_OP_LOG10: JE(MUL, WK(0), b, J->ln10, 0); JE(DIV, ta, tb, WK(0), 0); break;
	case CSF_OP_SQRT: JE(SQRT, WK(0), b, 0, 0); JE(MUL, WK(1), WK(0), J->two, 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_ABS: /* sign(b) db */
		JE(LT, WK(0), b, J->zero, 0);
		JE(MUL, WK(1), WK(0), J->two, 0);
		JE(SUB, WK(2), J->one, WK(1), 0);
		JE(MUL, ta, WK(2), tb, 0);
		break;
	default: /* the vector operations; comparisons and logic: not differentiable, zero */
		if (!tangent_vec(J, op, o, in)) JE(MOV, ta, J->zero, 0, 0);
		break;
	}
}
#define JAC_WORK 26

/*
 * Marks in act every slot whose value code computes from a marked slot, to a
 * fixed point (slots are reused). smooth: only through differentiable
 * operations. Returns 1 if a branch condition depends on a marked slot.
 */
int depends(const uint32_t *code, uint32_t n, unsigned char *act, int smooth)
{
	int branch = 0;
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0 };
	for (int changed = 1; changed;) {
		changed = 0;
		for (uint32_t pc = 0; pc < n; pc += csf_insn_len(code[pc])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
			if (code[pc] == CSF_OP_JZ && any_marked(act, code[pc + 1], CSF_K_S, cnt)) branch = 1;
			if (!csf_kind_write(oi->kind[0])) continue;
			if (smooth && !csf_op_differentiable(code[pc])) continue;
			int any = 0;
			for (int k = 1; k < oi->nops; k++)
				if (csf_kind_slot(oi->kind[k])) any |= any_marked(act, code[pc + 1 + k], oi->kind[k], cnt);
			uint32_t lo, hi;
			operand_range(code[pc + 1], oi->kind[0], cnt, &lo, &hi);
			for (uint32_t d = lo; any && d < hi; d++)
				if (!act[d]) act[d] = 1, changed = 1;
		}
	}
	return branch;
}
void gen_jacobian(Gen *G, csf_prog *p)
{
	const uint32_t *rc = p->code[CSF_SEC_RHS];
	uint32_t rn = p->ncode[CSF_SEC_RHS];
	if (!p->ny) return;
	Jac J0 = { 0 }, *J = &J0;
	J->G = G;
	J->zero = const_slot(G, (double[3]){ 0, 0, 0 }, 0);
	J->zvec = const_slot(G, (double[3]){ 0, 0, 0 }, 1);
	J->one = const_slot(G, (double[3]){ 1, 0, 0 }, 0);
	J->two = const_slot(G, (double[3]){ 2, 0, 0 }, 0);
	J->ln10 = const_slot(G, (double[3]){ M_LN10, 0, 0 }, 0);
	uint32_t nprimal = G->nmem;
	J->act = G->work[0] = xcalloc(nprimal, 1);
	J->act[p->tslot] = 1;
	for (uint32_t i = 0; i < p->ny; i++) J->act[p->ystart + i] = 1;
	depends(rc, rn, J->act, 1);
	J->P = nprimal;
	alloc_mem(G, nprimal, NULL); /* the tangents */
	J->W = alloc_mem(G, JAC_WORK, NULL);
	p->jtan = J->P;

	G->code = NULL;
	G->ncode = G->capcode = 0;
	G->lines = NULL;
	G->nlines = G->caplines = 0;
	uint32_t *map = G->work[1] = xcalloc((size_t)rn + 1, sizeof *map); /* RHS pc -> JAC pc, for jumps */
	uint32_t *fix = NULL, nfix = 0, capfix = 0;            /* JAC word positions of jump targets */
	uint32_t li = 0;
	for (uint32_t pc = 0; pc < rn;) {
		map[pc] = G->ncode;
		while (li < p->nlines[CSF_SEC_RHS] && p->lines[CSF_SEC_RHS][li].pc <= pc) {
			if (p->lines[CSF_SEC_RHS][li].pc == pc) add_line(G, p->lines[CSF_SEC_RHS][li].src);
			li++;
		}
		int op = (int)rc[pc];
		const csf_opinfo *oi = &csf_opinfo_table[op];
		uint32_t o[4] = { 0, 0, 0, 0 };
		for (int k = 0; k < oi->nops; k++) o[k] = rc[pc + 1 + k];
		if (op == CSF_OP_LOOP) J->cnt[o[0]] = o[1];
		if (csf_kind_write(oi->kind[0]) && jact(J, oi->kind[0], o[0])) {
			int in[3] = { 0, 0, 0 }, smooth = csf_op_differentiable((uint32_t)op);
			for (int k = 1; k < oi->nops; k++) in[k - 1] = smooth && csf_kind_slot(oi->kind[k]) && jact(J, oi->kind[k], o[k]);
			tangent(J, smooth ? op : -1, o, in);
		}
		emit_words(G, op, o);
		for (int k = 0; k < oi->nops; k++)
			if (oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) {
				if (nfix == capfix) {
					capfix = capfix ? 2 * capfix : 16;
					fix = G->work[2] = xrealloc(fix, capfix * sizeof *fix);
				}
				fix[nfix++] = G->ncode - (uint32_t)oi->nops + (uint32_t)k;
			}
		pc += csf_insn_len((uint32_t)op);
	}
	map[rn] = G->ncode;
	for (uint32_t i = 0; i < nfix; i++) G->code[fix[i]] = map[G->code[fix[i]]];
	p->code[CSF_SEC_JAC] = G->code;
	p->ncode[CSF_SEC_JAC] = G->ncode;
	p->lines[CSF_SEC_JAC] = G->lines;
	p->nlines[CSF_SEC_JAC] = G->nlines;
	free(map);
	free(fix);
	free(J->act);
	G->work[0] = G->work[1] = G->work[2] = NULL;
}
#undef JE
#undef T
#undef WK
