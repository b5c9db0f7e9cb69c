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
	if (lo < hi) exec(p, x, sec, m, pc + csf_insn_len(CSF_OP_LOOP), end, lo, hi);
}
