/*
 * fold.c - folding constant operands with the runtime's own arithmetic: the
 * instruction's function from opcodes.def, as the VM computes it.
 */
#include "csfc.h"
#include "sema.h"
#include "csf_int.h"

/* Operand k of an instruction being folded: a scalar, a vector, an immediate. */
#define FOLD_S(k) in[k][0]
#define FOLD_V(k) csf_v(in[k][0], in[k][1], in[k][2])
#define FOLD_N(k) (int)in[k][0]
#define FOLD_DS(e) out[0] = (e)
#define FOLD_DV(e) \
	do { \
		csf_vec r_ = (e); \
		out[0] = r_.x, out[1] = r_.y, out[2] = r_.z; \
	} while (0)
#define FOLD_ARGS1(b, c, d)
#define FOLD_ARGS2(b, c, d) FOLD_##b(0)
#define FOLD_ARGS3(b, c, d) FOLD_##b(0), FOLD_##c(1)
#define FOLD_ARGS4(b, c, d) FOLD_##b(0), FOLD_##c(1), FOLD_##d(2)

/* The result of instruction op on the operand values in[0..], as the VM computes it, in out[0..2]. */
void fold_op(int op, double in[3][3], double out[3])
{
	out[0] = out[1] = out[2] = 0;
	if (op == CSF_OP_POW) { /* a constant exponent: as POWI computes it, not as POW */
		out[0] = csf_pow(in[0][0], in[1][0]);
		return;
	}
	switch (op) {
#define OP(name, n, a, b, c, d, syn) \
	case CSF_OP_##name: \
		FOLD_##a(csf_op_##name(FOLD_ARGS##n(b, c, d))); \
		break;
#define CTRL(name, n, a, b, c, d, syn)
#include "opcodes.def"
#undef OP
#undef CTRL
	default: break;
	}
}
