/*
 * vm.c - the CSF bytecode interpreter.
 *
 * A code section is a straight sequence of instructions with forward jumps
 * only (conditional rules), so execution always terminates. Every
 * instruction's semantics is the csf_op_NAME function of csf_ops.h, the
 * same function the generated C calls; this file only decodes operands.
 * The program must have passed csf_verify: operands are not checked here.
 */
#include "csf.h"

#define CSF_ARGS1 , pc[1]
#define CSF_ARGS2 , pc[1], pc[2]
#define CSF_ARGS3 , pc[1], pc[2], pc[3]
#define CSF_ARGS4 , pc[1], pc[2], pc[3], pc[4]

int csf_vm_exec(const csf_prog *p, int sec, double *m)
{
	const uint32_t *code = p->code[sec];
	const uint32_t *pc = code, *end = code + p->ncode[sec];

	while (pc < end) {
		switch ((enum csf_opcode)pc[0]) {
		case CSF_OP_JMP:
			pc = code + pc[1];
			continue;
		case CSF_OP_JZ:
			if (m[pc[1]] == 0.0) {
				pc = code + pc[2];
				continue;
			}
			pc += 3;
			continue;
		case CSF_OP_CONTACT:
			csf_contact_apply(p, m);
			pc += 1;
			continue;
		case CSF_OP_ASSERT:
			if (m[pc[1]] == 0.0) return (int)pc[2];
			pc += 3;
			continue;
#define OP(name, n, a, b, c, d, syn) \
	case CSF_OP_##name: \
		csf_op_##name(m CSF_ARGS##n); \
		pc += 1 + n; \
		continue;
#define CTRL(name, n, a, b, c, d, syn)
#include "opcodes.def"
#undef CTRL
#undef OP
		case CSF_NOPCODES:
			break;
		}
		break; /* unreachable for verified code */
	}
	return -1;
}
