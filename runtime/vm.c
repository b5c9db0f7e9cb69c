/*
 * vm.c - the CSF bytecode interpreter.
 *
 * A code section is a sequence of instructions with forward jumps only
 * (conditional rules) and counted loops (LOOP ... NEXT, the rules over the
 * objects of a shape), so execution always terminates. Slot operands are
 * relative to the loop registers (csf_operand, csf.h). Every
 * instruction's semantics is the csf_op_NAME function of csf_ops.h, the
 * same function the generated C calls; this file only decodes operands.
 * The program must have passed csf_verify: operands are not checked here.
 */
#include <string.h>

#include "block.h"
#include "csf_int.h"
#include "insn.h"
#include "par.h"

/* The value of a read operand of kind K: a scalar or vector slot (through the registers), an immediate. */
#define LOAD_S(w) m[csf_operand(w, reg)]
#define LOAD_V(w) csf_vload(m + csf_operand(w, reg))
#define LOAD_N(w) csf_imm(w)
/* Stores value e into the destination operand of kind K. */
#define STORE_DS(w, e) m[csf_operand(w, reg)] = (e)
#define STORE_DV(w, e) csf_vstore(m + csf_operand(w, reg), (e))
#define ARGS1(b, c, d)
#define ARGS2(b, c, d) LOAD_##b(pc[2])
#define ARGS3(b, c, d) LOAD_##b(pc[2]), LOAD_##c(pc[3])
#define ARGS4(b, c, d) LOAD_##b(pc[2]), LOAD_##c(pc[3]), LOAD_##d(pc[4])

/*
 * Dispatch: where the compiler has labels as values (GCC, clang), each
 * instruction jumps straight to the next one's code through a table
 * (threaded code: one indirect jump per instruction, each predicted on its
 * own); elsewhere, or built with -DCSF_VM_SWITCH, a switch in a loop. The
 * two run the same code for every instruction.
 */
#if defined(__GNUC__) && !defined(CSF_VM_SWITCH)
#define CSF_VM_THREADED 1
#define CASE(name) op_##name
#define DISPATCH() \
	do { \
		if (pc >= end) return -1; \
		goto *label[pc[0]]; \
	} while (0)
#else
#define CASE(name) case CSF_OP_##name
#define DISPATCH() continue
#endif

/*
 * Block interpretation (block.h): instruction op over nk indices, operand
 * k's values at q[k], q[k] + s[k], ... (a stride of 0: the same slots for
 * every index; an immediate in imm[k]). Ascending, each index's operands
 * read before its result is written, as the serial loop does: a sum whose
 * slots are both the destination and a source (stride 0) adds its terms
 * in order.
 */
#define BLOAD_S(k) q##k[i * s##k]
#define BLOAD_V(k) csf_vload(q##k + i * s##k)
#define BLOAD_N(k) imm##k
#define BSTORE_DS(e) q0[i * s0] = (e)
#define BSTORE_DV(e) csf_vstore(q0 + i * s0, (e))
#define BARGS1(b, c, d)
#define BARGS2(b, c, d) BLOAD_##b(1)
#define BARGS3(b, c, d) BLOAD_##b(1), BLOAD_##c(2)
#define BARGS4(b, c, d) BLOAD_##b(1), BLOAD_##c(2), BLOAD_##d(3)

/* Do the 3 slots at d and the values of an operand at q, q + s, ... (nk of them, 3 slots each) meet? */
static int block_meets(const double *d, const double *q, size_t s, uint32_t nk)
{
	uintptr_t d0 = (uintptr_t)d, q0 = (uintptr_t)q, q1 = q0 + (s * (nk - 1) + 3) * sizeof *q;
	return d0 < q1 && q0 < d0 + 3 * sizeof *d;
}

static void block_op(uint32_t op, uint32_t nk, double *const q[4], const size_t s[4], const int imm[4])
{
	double *q0 = q[0];
	const double *q1 = q[1], *q2 = q[2], *q3 = q[3];
	size_t s0 = s[0], s1 = s[1], s2 = s[2], s3 = s[3];
	int imm1 = imm[1], imm2 = imm[2], imm3 = imm[3];
	(void)imm1, (void)imm2, (void)imm3;
	if (s0 == 0 && s1 == 0 && q0 == q1 && !block_meets(q0, q2, s2, nk)) { /* a sum: kept in a register */
		if (op == CSF_OP_VADD) {
			csf_vec sum = csf_vload(q1);
			for (size_t i = 0; i < nk; i++) sum = csf_op_VADD(sum, BLOAD_V(2));
			csf_vstore(q0, sum);
			return;
		}
		if (op == CSF_OP_ADD) {
			double sum = q1[0];
			for (size_t i = 0; i < nk; i++) sum = csf_op_ADD(sum, BLOAD_S(2));
			q0[0] = sum;
			return;
		}
	}
	/* integer powers with their exponent known, so that csf_powi's loop unrolls */
	if (op == CSF_OP_DIVPOWI && imm3 == 3) {
		for (size_t i = 0; i < nk; i++) BSTORE_DS(csf_op_DIVPOWI(BLOAD_S(1), BLOAD_S(2), 3));
		return;
	}
	if (op == CSF_OP_POWI && imm2 == 2) {
		for (size_t i = 0; i < nk; i++) BSTORE_DS(csf_op_POWI(BLOAD_S(1), 2));
		return;
	}
	switch ((enum csf_opcode)op) {
#define OP(name, n, a, b, c, d, syn) \
	case CSF_OP_##name: \
		for (size_t i = 0; i < nk; i++) \
			BSTORE_##a(csf_op_##name(BARGS##n(b, c, d))); \
		return;
#define CTRL(name, n, a, b, c, d, syn) case CSF_OP_##name:
#include "opcodes.def"
#undef CTRL
#undef OP
	case CSF_NOPCODES:
		return; /* (control flow is never blocked) */
	}
}

/*
 * The iterations lo to hi - 1 of blocked loop B (its index's level runs
 * them; the loops around it at the indices in reg), a block of them at a
 * time: each instruction over the block, its temporaries in scratch; the
 * index of the loop B skips left out. Then the temporaries of the last
 * iteration into m, as the serial loop leaves them.
 */
static void run_blocked(const csf_bloop *B, double *m, const uint32_t *reg, uint32_t lo, uint32_t hi)
{
	double scratch[CSF_BLOCK_SCRATCH];
	uint32_t skip = B->skip ? reg[2 * B->skip - 1] : hi, last = 0;
	for (uint32_t j0 = lo, j1; j0 < hi; j0 = j1) {
		if (j0 == skip) {
			j1 = j0 + 1;
			continue;
		}
		j1 = hi - j0 > B->block ? j0 + B->block : hi;
		if (skip > j0 && skip < j1) j1 = skip;
		for (uint32_t t = 0; t < B->ninsn; t++) {
			const csf_binsn *in = &B->insn[t];
			double *q[4];
			size_t s[4];
			int imm[4];
			for (int k = 0; k < 4; k++) {
				const csf_bopnd *o = &in->o[k];
				q[k] = m;
				s[k] = 0;
				imm[k] = 0;
				switch ((enum csf_bmode)o->mode) {
				case CSF_BM_FIX: q[k] = m + csf_operand(o->w, reg); break;
				case CSF_BM_IDX: q[k] = m + o->w + (size_t)o->stride * j0, s[k] = o->stride; break;
				case CSF_BM_TMP: q[k] = scratch + o->w, s[k] = o->stride; break;
				case CSF_BM_IMM: imm[k] = csf_imm(o->w); break;
				}
			}
			block_op(in->op, j1 - j0, q, s, imm);
		}
		last = j1 - j0;
	}
	for (uint32_t i = 0; i < B->ntmp && last; i++) {
		const csf_btemp *tp = &B->tmp[i];
		memcpy(m + tp->slot, scratch + tp->off + (size_t)(last - 1) * tp->width, tp->width * sizeof *m);
	}
}

/*
 * Runs the code [from, to) of section sec on m. With hi > 0, [from, to) is
 * the body of a level-1 loop and its NEXT, run for the indices lo to
 * hi - 1 (a block of its iterations: csf_vm_loop_range).
 */
static int exec(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, uint32_t from, uint32_t to, uint32_t lo,
                uint32_t hi)
{
	const uint32_t *code = p->code[sec];
	const uint32_t *pc = code + from, *end = code + to;
	uint32_t reg[CSF_NREGS + 1] = { 0, lo, 3 * lo }, count[CSF_LOOP_MAX + 1] = { 0, hi };

#ifdef CSF_VM_THREADED
	static const void *const label[CSF_NOPCODES] = {
#define OP(name, n, a, b, c, d, syn) [CSF_OP_##name] = &&op_##name,
#define CTRL(name, n, a, b, c, d, syn) [CSF_OP_##name] = &&op_##name,
#include "opcodes.def"
#undef CTRL
#undef OP
	};
	DISPATCH();
#else
	while (pc < end) {
		switch ((enum csf_opcode)pc[0]) {
#endif
		CASE(JMP):
			pc = code + pc[1];
			DISPATCH();
		CASE(JZ):
			if (m[csf_operand(pc[1], reg)] == 0.0) {
				pc = code + pc[2];
				DISPATCH();
			}
			pc += csf_insn_len(CSF_OP_JZ);
			DISPATCH();
		CASE(CONTACT):
			csf_contact_apply(p, x, m);
			pc += csf_insn_len(CSF_OP_CONTACT);
			DISPATCH();
		CASE(CONSTRAIN):
			csf_constraint_apply(p, x, m);
			pc += csf_insn_len(CSF_OP_CONSTRAIN);
			DISPATCH();
		CASE(ASSERT):
			if (m[csf_operand(pc[1], reg)] == 0.0) return (int)csf_operand(pc[2], reg);
			pc += csf_insn_len(CSF_OP_ASSERT);
			DISPATCH();
		CASE(LOOP):
			if (pc[1] == 1 && x && x->pool && csf_pool_vm(x->pool, x, sec, (uint32_t)(pc - code), m)) {
				pc = code + pc[3];
				DISPATCH();
			}
			reg[2 * pc[1] - 1] = reg[2 * pc[1]] = 0;
			count[pc[1]] = pc[2];
			if (pc[2] == 0) {
				pc = code + pc[3];
				DISPATCH();
			}
			if (x && x->blocks && pc[2] >= CSF_BLOCK_MIN_COUNT) {
				const csf_bloop *B = csf_blocks_find(x->blocks, sec, (uint32_t)(pc - code));
				if (B) {
					run_blocked(B, m, reg, 0, pc[2]);
					pc = code + pc[3];
					DISPATCH();
				}
			}
			pc += csf_insn_len(CSF_OP_LOOP);
			DISPATCH();
		CASE(NEXT):
			reg[2 * pc[1]] += 3;
			if (++reg[2 * pc[1] - 1] < count[pc[1]]) {
				pc = code + pc[2];
				DISPATCH();
			}
			pc += csf_insn_len(CSF_OP_NEXT);
			DISPATCH();
		CASE(JEQ):
			if (reg[2 * pc[1] - 1] == reg[2 * pc[2] - 1]) {
				pc = code + pc[3];
				DISPATCH();
			}
			pc += csf_insn_len(CSF_OP_JEQ);
			DISPATCH();
#define OP(name, n, a, b, c, d, syn) \
	CASE(name): \
		STORE_##a(pc[1], csf_op_##name(ARGS##n(b, c, d))); \
		pc += 1 + n; \
		DISPATCH();
#define CTRL(name, n, a, b, c, d, syn)
#include "opcodes.def"
#undef CTRL
#undef OP
#ifndef CSF_VM_THREADED
		case CSF_NOPCODES:
			break;
		}
		break; /* unreachable for verified code */
	}
#endif
	return -1;
}

/*
 * The state is y and the derivatives go to dydt: copied into and out of
 * m's own slots unless they are those slots.
 */
int csf_vm_exec(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, const double *y, double *dydt)
{
	if (y != m + p->ystart) memcpy(m + p->ystart, y, p->ny * sizeof *y);
	int r = exec(p, x, sec, m, 0, p->ncode[sec], 0, 0);
	if (dydt != m + p->dstart) memcpy(dydt, m + p->dstart, p->ny * sizeof *dydt);
	return r;
}

void csf_vm_loop_range(const csf_prog *p, const csf_exec_ctx *x, int sec, uint32_t pc, uint32_t end, double *m,
                       uint32_t lo, uint32_t hi)
{
	if (lo >= hi) return;
	const csf_bloop *B = x ? csf_blocks_find(x->blocks, sec, pc) : NULL;
	static const uint32_t reg[CSF_NREGS + 1];
	if (B) run_blocked(B, m, reg, lo, hi);
	else exec(p, x, sec, m, pc + csf_insn_len(CSF_OP_LOOP), end, lo, hi);
}
