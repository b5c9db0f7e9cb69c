/*
 * csf_ops.h - the semantics of every CSF instruction, as inline functions.
 *
 * This header is the single definition of CSF arithmetic. The VM's dispatch
 * loop calls csf_op_NAME with operands decoded from the bytecode; the C that
 * `csfc --emit-c` generates calls the same functions with the operands as
 * constants; the compiler's constant folder calls the scalar helpers. All
 * three therefore perform the same IEEE operations in the same order, and
 * with -ffp-contract=off on both paths their results are bit-identical.
 *
 * m is the model's memory (see bytecode.h); a vector occupies three
 * consecutive slots x, y, z. Vector results are computed into locals before
 * they are stored, so a destination may overlap an operand.
 */
#ifndef CSF_OPS_H
#define CSF_OPS_H

#include <math.h>
#include <stdint.h>

typedef uint32_t csf_u32;

/* Scalar helpers, shared with the compiler's constant folder. */
static inline double csf_min(double a, double b) { return isnan(a) || isnan(b) ? NAN : (a < b ? a : b); }
static inline double csf_max(double a, double b) { return isnan(a) || isnan(b) ? NAN : (a > b ? a : b); }
static inline double csf_bool(int c) { return c ? 1.0 : 0.0; }

static inline double csf_vmag3(double x, double y, double z) { return sqrt(x * x + y * y + z * z); }

/* The largest |n| for which x^n is repeated multiplication (csf_powi). */
#define CSF_POWI_MAX 8

/*
 * x^n for an integer n, |n| <= CSF_POWI_MAX, by multiplication from the left:
 * x^0 = 1 (for every x, as pow gives), x^1 = x, x^2 = x*x, x^3 = (x*x)*x,
 * x^4 = ((x*x)*x)*x, ..., and x^-n = 1/(x^n): x^-2 = 1/(x*x), 0^-2 = inf.
 */
static inline double csf_powi(double x, int n)
{
	int k = n < 0 ? -n : n;
	double r = k ? x : 1.0;
	for (int i = 1; i < k; i++) r = r * x;
	return n < 0 ? 1.0 / r : r;
}

/* Is y an exponent csf_powi takes: a whole number with |y| <= CSF_POWI_MAX? */
static inline int csf_is_powi(double y) { return fabs(y) <= CSF_POWI_MAX && y == (double)(int)y; }

/*
 * x^y for an exponent y known at compile time, the language's '^' with a
 * constant exponent: csf_powi for a whole number |y| <= CSF_POWI_MAX, else
 * pow. The constant folder and the POWI instruction compute it; an exponent
 * known only at run time (POW) is always pow.
 */
static inline double csf_pow(double x, double y) { return csf_is_powi(y) ? csf_powi(x, (int)y) : pow(x, y); }

/* The signed integer an immediate operand word holds (two's complement, as gen.c writes it). */
static inline int csf_imm(csf_u32 w) { return w < 0x80000000u ? (int)w : -(int)~w - 1; }

/* The angle between a and b, as atan2(|a x b|, a . b): accurate near 0 and pi too. */
static inline double csf_vangle3(const double *a, const double *b)
{
	double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
	return atan2(csf_vmag3(x, y, z), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

#define CSF_OP1(name, expr) \
	static inline void csf_op_##name(double *m, csf_u32 a, csf_u32 b) { double x = m[b]; m[a] = (expr); }
#define CSF_OP2(name, expr) \
	static inline void csf_op_##name(double *m, csf_u32 a, csf_u32 b, csf_u32 c) { double x = m[b], y = m[c]; m[a] = (expr); }

static inline void csf_op_MOV(double *m, csf_u32 a, csf_u32 b) { m[a] = m[b]; }
static inline void csf_op_VMOV(double *m, csf_u32 a, csf_u32 b)
{
	double x = m[b], y = m[b + 1], z = m[b + 2];
	m[a] = x; m[a + 1] = y; m[a + 2] = z;
}
static inline void csf_op_VPACK(double *m, csf_u32 a, csf_u32 b, csf_u32 c, csf_u32 d)
{
	double x = m[b], y = m[c], z = m[d];
	m[a] = x; m[a + 1] = y; m[a + 2] = z;
}
CSF_OP2(ADD, x + y)
CSF_OP2(SUB, x - y)
CSF_OP2(MUL, x * y)
CSF_OP2(DIV, x / y)
CSF_OP2(POW, pow(x, y))
/* POW with an exponent known at compile time: the immediate c, |c| <= CSF_POWI_MAX. */
static inline void csf_op_POWI(double *m, csf_u32 a, csf_u32 b, csf_u32 c) { m[a] = csf_powi(m[b], csf_imm(c)); }
CSF_OP1(NEG, -x)
CSF_OP2(ATAN2, atan2(x, y))
CSF_OP2(MIN, csf_min(x, y))
CSF_OP2(MAX, csf_max(x, y))
CSF_OP1(SIN, sin(x))
CSF_OP1(COS, cos(x))
CSF_OP1(TAN, tan(x))
CSF_OP1(ASIN, asin(x))
CSF_OP1(ACOS, acos(x))
CSF_OP1(ATAN, atan(x))
CSF_OP1(SINH, sinh(x))
CSF_OP1(COSH, cosh(x))
CSF_OP1(TANH, tanh(x))
CSF_OP1(EXP, exp(x))
CSF_OP1(LOG, log(x))
CSF_OP1(LOG10, log10(x))
CSF_OP1(SQRT, sqrt(x))
CSF_OP1(ABS, fabs(x))
CSF_OP2(LT, csf_bool(x < y))
CSF_OP2(LE, csf_bool(x <= y))
CSF_OP2(GT, csf_bool(x > y))
CSF_OP2(GE, csf_bool(x >= y))
CSF_OP2(EQ, csf_bool(x == y))
CSF_OP2(NE, csf_bool(x != y))
CSF_OP2(AND, csf_bool(x != 0.0 && y != 0.0))
CSF_OP2(OR, csf_bool(x != 0.0 || y != 0.0))
CSF_OP1(NOT, csf_bool(x == 0.0))
/* A located comparison (an event of a conditional rule): while the runtime
   integrates, the side is the mode it froze at the last event, R[c]. */
CSF_OP2(EVGT, y >= 0.0 ? y : csf_bool(x > 0.0))
CSF_OP2(EVGE, y >= 0.0 ? y : csf_bool(x >= 0.0))

#define CSF_VOP2(name, ex, ey, ez) \
	static inline void csf_op_##name(double *m, csf_u32 a, csf_u32 b, csf_u32 c) \
	{ \
		const double *p = m + b, *q = m + c; \
		double x = (ex), y = (ey), z = (ez); \
		m[a] = x; m[a + 1] = y; m[a + 2] = z; \
	}
CSF_VOP2(VADD, p[0] + q[0], p[1] + q[1], p[2] + q[2])
CSF_VOP2(VSUB, p[0] - q[0], p[1] - q[1], p[2] - q[2])
CSF_VOP2(VMUL, p[0] * q[0], p[1] * q[0], p[2] * q[0])
CSF_VOP2(VDIV, p[0] / q[0], p[1] / q[0], p[2] / q[0])
CSF_VOP2(VCROSS, p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])

static inline void csf_op_VNEG(double *m, csf_u32 a, csf_u32 b)
{
	double x = -m[b], y = -m[b + 1], z = -m[b + 2];
	m[a] = x; m[a + 1] = y; m[a + 2] = z;
}
static inline void csf_op_VDOT(double *m, csf_u32 a, csf_u32 b, csf_u32 c)
{
	m[a] = m[b] * m[c] + m[b + 1] * m[c + 1] + m[b + 2] * m[c + 2];
}
static inline void csf_op_VMAG(double *m, csf_u32 a, csf_u32 b)
{
	m[a] = csf_vmag3(m[b], m[b + 1], m[b + 2]);
}
static inline void csf_op_VANGLE(double *m, csf_u32 a, csf_u32 b, csf_u32 c)
{
	m[a] = csf_vangle3(m + b, m + c);
}
static inline void csf_op_VUNIT(double *m, csf_u32 a, csf_u32 b)
{
	double n = csf_vmag3(m[b], m[b + 1], m[b + 2]);
	double x = m[b] / n, y = m[b + 1] / n, z = m[b + 2] / n;
	m[a] = x; m[a + 1] = y; m[a + 2] = z;
}
static inline void csf_op_VPROJ(double *m, csf_u32 a, csf_u32 b, csf_u32 c)
{
	const double *p = m + b, *q = m + c;
	double k = (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
	double x = q[0] * k, y = q[1] * k, z = q[2] * k;
	m[a] = x; m[a + 1] = y; m[a + 2] = z;
}

#undef CSF_OP1
#undef CSF_OP2
#undef CSF_VOP2
#endif
