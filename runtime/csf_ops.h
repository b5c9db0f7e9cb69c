/*
 * csf_ops.h - the semantics of every CSF instruction, as inline functions.
 *
 * This header is the single definition of CSF arithmetic: functions of
 * plain values, which know nothing of memory. The VM's dispatch loop calls
 * csf_op_NAME on the operands it loads from the model's memory and stores
 * the result; the C that `csfc --emit-c` generates calls the same functions
 * on C locals, literals and the state arrays; the compiler's constant folder
 * calls them on constants. All three therefore perform the same IEEE
 * operations in the same order, and with -ffp-contract=off on every path
 * their results are bit-identical.
 *
 * A vector is three doubles x, y, z (csf_vec; in memory, three consecutive
 * slots). An instruction's operands are all read before its result is
 * written, so a destination may overlap an operand.
 */
#ifndef CSF_OPS_H
#define CSF_OPS_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

typedef uint32_t csf_u32;

/* Scalar helpers, shared with the compiler's constant folder. */
static inline double csf_min(double a, double b) { return isnan(a) || isnan(b) ? NAN : (a < b ? a : b); }
static inline double csf_max(double a, double b) { return isnan(a) || isnan(b) ? NAN : (a > b ? a : b); }
/* C's fmax (a NaN gives the other argument), inline: gcc calls libm's fmax without -ffinite-math-only */
static inline double csf_fmax(double a, double b) { return a >= b || isnan(b) ? a : b; }
/*
 * Whether v[0..n) are all finite: x - x is 0 for a finite x and NaN for an
 * infinity or a NaN, and a sum holding a NaN is NaN. Four sums, over blocks
 * of a fixed length, which the compiler vectorises.
 */
static inline int csf_all_finite(const double *v, size_t n)
{
	enum { B = 64 };
	double acc[4] = { 0, 0, 0, 0 };
	size_t i = 0;
	for (; i + B <= n; i += B) {
		for (size_t j = 0; j < B; j += 4)
			for (int l = 0; l < 4; l++) acc[l] += v[i + j + l] - v[i + j + l];
		if (acc[0] + acc[1] + acc[2] + acc[3] != 0) return 0;
	}
	for (; i < n; i++) acc[0] += v[i] - v[i];
	return acc[0] + acc[1] + acc[2] + acc[3] == 0;
}

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

/* A vector: the three consecutive slots x, y, z of one in memory. */
typedef struct csf_vec { double x, y, z; } csf_vec;

static inline csf_vec csf_v(double x, double y, double z) { return (csf_vec){ x, y, z }; }
/* The vector in slots s[0..2], and a vector stored there. */
static inline csf_vec csf_vload(const double *s) { return (csf_vec){ s[0], s[1], s[2] }; }
static inline void csf_vstore(double *s, csf_vec v) { s[0] = v.x; s[1] = v.y; s[2] = v.z; }

/* The angle between a and b, as atan2(|a x b|, a . b): accurate near 0 and pi too. */
static inline double csf_vangle3(csf_vec a, csf_vec b)
{
	double x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x;
	return atan2(csf_vmag3(x, y, z), a.x * b.x + a.y * b.y + a.z * b.z);
}

/*
 * The instructions. csf_op_NAME takes the values of the instruction's
 * operands after the first (a scalar S as a double, a vector V as a
 * csf_vec, an immediate N as an int) and returns the value its first
 * operand, the destination (DS: a double, DV: a csf_vec), receives.
 */
#define CSF_OP1(name, expr) static inline double csf_op_##name(double x) { return (expr); }
#define CSF_OP2(name, expr) static inline double csf_op_##name(double x, double y) { return (expr); }

static inline double csf_op_MOV(double x) { return x; }
static inline csf_vec csf_op_VMOV(csf_vec p) { return p; }
static inline csf_vec csf_op_VPACK(double x, double y, double z) { return csf_v(x, y, z); }
CSF_OP2(ADD, x + y)
CSF_OP2(SUB, x - y)
CSF_OP2(MUL, x * y)
CSF_OP2(DIV, x / y)
CSF_OP2(POW, pow(x, y))
/* POW with an exponent known at compile time: the immediate n, |n| <= CSF_POWI_MAX. */
static inline double csf_op_POWI(double x, int n) { return csf_powi(x, n); }
/* DIV of POWI's result, fused (csfc writes it for a POWI whose result only that DIV reads): the same two operations. */
static inline double csf_op_DIVPOWI(double x, double y, int n) { return x / csf_powi(y, n); }
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
CSF_OP1(FLOOR, floor(x))
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
   integrates, the side is the mode it froze at the last event, y. */
CSF_OP2(EVGT, y >= 0.0 ? y : csf_bool(x > 0.0))
CSF_OP2(EVGE, y >= 0.0 ? y : csf_bool(x >= 0.0))

#define CSF_VOP2(name, ex, ey, ez) \
	static inline csf_vec csf_op_##name(csf_vec p, csf_vec q) { return csf_v((ex), (ey), (ez)); }
CSF_VOP2(VADD, p.x + q.x, p.y + q.y, p.z + q.z)
CSF_VOP2(VSUB, p.x - q.x, p.y - q.y, p.z - q.z)
CSF_VOP2(VCROSS, p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x)

static inline csf_vec csf_op_VMUL(csf_vec p, double k) { return csf_v(p.x * k, p.y * k, p.z * k); }
static inline csf_vec csf_op_VDIV(csf_vec p, double k) { return csf_v(p.x / k, p.y / k, p.z / k); }
static inline csf_vec csf_op_VNEG(csf_vec p) { return csf_v(-p.x, -p.y, -p.z); }
static inline double csf_op_VDOT(csf_vec p, csf_vec q) { return p.x * q.x + p.y * q.y + p.z * q.z; }
static inline double csf_op_VMAG(csf_vec p) { return csf_vmag3(p.x, p.y, p.z); }
static inline double csf_op_VANGLE(csf_vec p, csf_vec q) { return csf_vangle3(p, q); }
static inline csf_vec csf_op_VUNIT(csf_vec p)
{
	double n = csf_vmag3(p.x, p.y, p.z);
	return csf_v(p.x / n, p.y / n, p.z / n);
}
static inline csf_vec csf_op_VPROJ(csf_vec p, csf_vec q)
{
	double k = (p.x * q.x + p.y * q.y + p.z * q.z) / (q.x * q.x + q.y * q.y + q.z * q.z);
	return csf_v(q.x * k, q.y * k, q.z * k);
}

#undef CSF_OP1
#undef CSF_OP2
#undef CSF_VOP2
#endif
