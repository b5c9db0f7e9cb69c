/*
 * solve.c - an equation solved symbolically for its target: it must be linear
 * in it; and rules solved together (group.c), a linear system solved
 * symbolically for its unknowns.
 *
 * A system of k <= SOLVE_MAX rules in k unknowns is solved by Cramer's rule:
 * x_j = N_j / D, where D is the determinant of the coefficients and N_j the
 * sum over the rules of each right-hand side times its cofactor in column j
 * (a vector right-hand side gives a vector unknown: CSF's coefficients are
 * scalars, so a vector system is the same scalar system for each
 * component). The values are ordinary expressions, computed in each
 * evaluation in the order the expressions say, so csfvm and the C that
 * `csfc --emit-c` writes compute the same bits.
 *
 * Why Cramer's rule, and no more than three unknowns. Pivoting chooses rows
 * by the values at run time, and an expression cannot choose; elimination in
 * a fixed order divides by whatever comes first, which may be zero or tiny
 * for a system that is well conditioned. Let P be the permanent of |A| (D
 * with every product taken positive) and P_j that of |A| with column j
 * replaced by |b|, u = 2^-53. D and N_j are sums of products of k factors,
 * so their rounding errors are at most about (2k - 1) u P and (2k - 1) u P_j,
 * and the error of x_j at most about (2k - 1) u (P_j + |x_j| P)/|D|. The
 * ratio P/|D| does not change with the units of the equations or of the
 * unknowns (both scale alike). For k = 2 it is at most the condition number
 * (Skeel's, || |A^-1| |A| ||: P is a diagonal entry of |adj A| |A|), and
 * Cramer's rule is as accurate as Gaussian elimination with partial pivoting
 * (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., ch. 1).
 * For k = 3 no such bound is known, and P/|D| can be the square of the
 * condition number, when two of A's singular values are small in a basis
 * that mixes the unknowns (a system of such a condition loses twice the
 * digits it would need to); the physical systems of the tests (a wedge's
 * equations, a triple pendulum's mass matrix) are nowhere near. Beyond three
 * unknowns the cost and the rounding of the cofactors grow too fast, so the
 * limit is an error that says so.
 *
 * The guard. A singular system may not give a determinant of exactly zero
 * in floating point, and then a finite, wrong answer. D is compared with its
 * own rounding error: where |D| <= 64u P (2^-47 P, above the bound of 5u P
 * with margin for the rounding of the coefficients, some 4u each, which
 * moves D by up to 3 * 4u P), every x_j is NaN, through the factor
 * sqrt(y)/sqrt(y) with y = |D| - 2^-47 P, which is exactly 1 where y > 0 and
 * NaN elsewhere; the run then stops at that evaluation with the message
 * that names the value and the rules (csfvm's check of non-finite values).
 * The comparison does not depend on units: both sides scale by the same
 * product of row and column factors.
 */
#include <math.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* e = a*x + b, where x is the target; a is a scalar (NULL: 0), b of e's type (NULL: 0). */
typedef struct Lin { RExpr *a, *b; int ok; } Lin;

static int contains(RExpr *e, Var *x)
{
	if (e->k == R_VAR) return e->var == x;
	for (int i = 0; i < e->n; i++)
		if (contains(e->a[i], x)) return 1;
	return 0;
}

static RExpr *sadd(RExpr *p, RExpr *q, int sub, Loc l)
{
	if (!q) return p;
	if (!p) return sub ? rop(q->isvec ? CSF_OP_VNEG : CSF_OP_NEG, q->isvec, l, q, NULL, NULL) : q;
	return rop(p->isvec ? (sub ? CSF_OP_VSUB : CSF_OP_VADD) : (sub ? CSF_OP_SUB : CSF_OP_ADD), p->isvec, l, p, q, NULL);
}

static RExpr *smul(RExpr *p, RExpr *s, Loc l) /* p * scalar s */
{
	if (!p) return NULL;
	if (is_const(s, 1)) return p;
	if (!p->isvec && is_const(p, 1)) return s;
	return rop(p->isvec ? CSF_OP_VMUL : CSF_OP_MUL, p->isvec, l, p, s, NULL);
}

static RExpr *sdiv(RExpr *p, RExpr *s, Loc l)
{
	if (!p) return NULL;
	if (is_const(s, 1)) return p;
	return rop(p->isvec ? CSF_OP_VDIV : CSF_OP_DIV, p->isvec, l, p, s, NULL);
}

static Lin lin(RExpr *e, Var *x)
{
	Lin r = { NULL, NULL, 1 };
	if (!contains(e, x)) {
		r.b = e;
		return r;
	}
	if (e->k == R_VAR) {
		r.a = rconst(1, e->loc);
		return r;
	}
	if (e->k != R_OP) {
		r.ok = 0;
		return r;
	}
	Lin p = lin(e->a[0], x), q = e->n > 1 ? lin(e->a[1], x) : (Lin){ NULL, NULL, 1 };
	if (!p.ok || !q.ok) return (Lin){ NULL, NULL, 0 };
	Loc l = e->loc;
	switch (e->op) {
	case CSF_OP_ADD: case CSF_OP_VADD: case CSF_OP_SUB: case CSF_OP_VSUB: {
		int sub = e->op == CSF_OP_SUB || e->op == CSF_OP_VSUB;
		r.a = p.a && q.a ? sadd(p.a, q.a, sub, l) : p.a ? p.a : q.a ? sadd(NULL, q.a, sub, l) : NULL;
		r.b = sadd(p.b, q.b, sub, l);
		return r;
	}
	case CSF_OP_NEG: case CSF_OP_VNEG:
		r.a = p.a ? sadd(NULL, p.a, 1, l) : NULL;
		r.b = p.b ? sadd(NULL, p.b, 1, l) : NULL;
		return r;
	case CSF_OP_MUL: case CSF_OP_VMUL:
		if (p.a && !q.a) {
			r.a = smul(p.a, e->a[1], l);
			r.b = smul(p.b, e->a[1], l);
			return r;
		}
		if (q.a && !p.a && e->op == CSF_OP_MUL) {
			r.a = smul(q.a, e->a[0], l);
			r.b = smul(q.b, e->a[0], l);
			return r;
		}
		break;
	case CSF_OP_DIV: case CSF_OP_VDIV:
		if (p.a && !q.a) {
			r.a = sdiv(p.a, e->a[1], l);
			r.b = sdiv(p.b, e->a[1], l);
			return r;
		}
		break;
	}
	return (Lin){ NULL, NULL, 0 };
}

/* Solves lhs = rhs for x. Returns NULL (after an error) when it cannot. */
RExpr *solve(RExpr *lhs, RExpr *rhs, Var *x, Loc l, const char *text)
{
	int inl = contains(lhs, x), inr = contains(rhs, x);
	if (lhs->k == R_VAR && lhs->var == x && !inr) return rhs;
	if (rhs->k == R_VAR && rhs->var == x && !inl) return lhs;
	Lin p = lin(lhs, x), q = lin(rhs, x);
	if (!p.ok || !q.ok) {
		error_at(l, "cannot solve \"%s\" for %s: it is not linear in %s", text, var_label(x), x->name);
		return NULL;
	}
	/* p.a x + p.b = q.a x + q.b  =>  x = (q.b - p.b) / (p.a - q.a); one side without x keeps its form */
	RExpr *num, *den;
	if (!inl) {
		num = q.b ? sadd(lhs, q.b, 1, l) : lhs;
		den = q.a;
	} else if (!inr) {
		num = p.b ? sadd(rhs, p.b, 1, l) : rhs;
		den = p.a;
	} else {
		den = sadd(p.a, q.a, 1, l);
		num = q.b && p.b ? sadd(q.b, p.b, 1, l) : q.b ? q.b : p.b ? sadd(NULL, p.b, 1, l) : NULL;
	}
	if (!den || is_const(den, 0)) {
		error_at(l, "cannot solve \"%s\" for %s: %s cancels out", text, var_label(x), x->name);
		return NULL;
	}
	if (!num) num = x->isvec ? rvconst((double[3]){ 0, 0, 0 }, l) : rconst(0, l);
	if (is_const(den, -1)) return sadd(NULL, num, 1, l);
	return sdiv(num, den, l);
}

/* ---- rules solved together ---- */

/* Does e read any of x[0..k)? */
static int contains_any(RExpr *e, Var *const *x, int k)
{
	for (int j = 0; j < k; j++)
		if (contains(e, x[j])) return 1;
	return 0;
}

/* The first of x[0..k) that e reads, or NULL. */
static Var *first_unknown(RExpr *e, Var *const *x, int k)
{
	if (e->k == R_VAR) {
		for (int j = 0; j < k; j++)
			if (e->var == x[j]) return x[j];
		return NULL;
	}
	for (int i = 0; i < e->n; i++) {
		Var *v = first_unknown(e->a[i], x, k);
		if (v) return v;
	}
	return NULL;
}

/* The smallest part of e that is not linear in x[0..k) (what lin refuses), or NULL. */
static RExpr *nonlinear_part(RExpr *e, Var *const *x, int k)
{
	if (e->k == R_VAR || !contains_any(e, x, k)) return NULL;
	if (e->k != R_OP) return e;
	int in0 = contains_any(e->a[0], x, k), in1 = e->n > 1 && contains_any(e->a[1], x, k);
	switch (e->op) {
	case CSF_OP_ADD: case CSF_OP_VADD: case CSF_OP_SUB: case CSF_OP_VSUB: case CSF_OP_NEG: case CSF_OP_VNEG: {
		RExpr *r = in0 ? nonlinear_part(e->a[0], x, k) : NULL;
		return r ? r : in1 ? nonlinear_part(e->a[1], x, k) : NULL;
	}
	case CSF_OP_MUL:
		if (in0 && in1) return e;
		return nonlinear_part(e->a[in0 ? 0 : 1], x, k);
	case CSF_OP_VMUL: case CSF_OP_DIV: case CSF_OP_VDIV:
		return in1 ? e : nonlinear_part(e->a[0], x, k);
	}
	return e;
}

/* Why e, a part of an equation that nonlinear_part found, is not linear in x[0..k): "multiplies a1 by a2". */
static const char *nonlinear_why(RExpr *e, Var *const *x, int k)
{
	static const char *const fn[] = {
		[CSF_OP_SIN] = "sin()", [CSF_OP_COS] = "cos()", [CSF_OP_TAN] = "tan()", [CSF_OP_ASIN] = "asin()",
		[CSF_OP_ACOS] = "acos()", [CSF_OP_ATAN] = "atan()", [CSF_OP_SINH] = "sinh()", [CSF_OP_COSH] = "cosh()",
		[CSF_OP_TANH] = "tanh()", [CSF_OP_EXP] = "exp()", [CSF_OP_LOG] = "log()", [CSF_OP_LOG10] = "log10()",
		[CSF_OP_SQRT] = "sqrt()", [CSF_OP_ABS] = "abs()", [CSF_OP_ATAN2] = "atan2()", [CSF_OP_MIN] = "min()",
		[CSF_OP_MAX] = "max()", [CSF_OP_VMAG] = ".mag", [CSF_OP_VDOT] = ".dot()", [CSF_OP_VCROSS] = ".cross()",
		[CSF_OP_VUNIT] = ".unit", [CSF_OP_VANGLE] = ".angle()", [CSF_OP_VPROJ] = ".proj()",
		[CSF_OP_VPACK] = "a vector (x, y, z)", [CSF_OP_FLOOR] = "floor()",
	};
	const char *v = first_unknown(e, x, k)->name;
	if (e->k == R_COMP) return xprintf("takes a component of %s", v);
	if (e->k != R_OP) return xprintf("is not linear in %s", v);
	int in0 = contains_any(e->a[0], x, k);
	switch (e->op) {
	case CSF_OP_MUL: case CSF_OP_VMUL:
		if (in0 && contains_any(e->a[1], x, k))
			return xprintf("multiplies %s by %s", v, first_unknown(e->a[1], x, k)->name);
		return xprintf("multiplies a vector by %s, a scalar unknown", v);
	case CSF_OP_DIV: case CSF_OP_VDIV:
		return e->a[1]->k == R_VAR ? xprintf("divides by %s", v) : xprintf("divides by an expression of %s", v);
	case CSF_OP_POW: case CSF_OP_POWI:
		return in0 ? xprintf("raises %s to a power", v) : xprintf("has %s in an exponent", v);
	}
	if ((size_t)e->op < sizeof fn / sizeof fn[0] && fn[e->op]) return xprintf("has %s inside %s", v, fn[e->op]);
	return xprintf("is not linear in %s", v);
}

/*
 * One rule of a system: lhs = rhs as sum_j a[j] x[j] = *b, a[j] a scalar free of x[0..k)
 * (NULL: 0), *b of the equation's type (NULL: 0). Returns NULL, or the part of a side that is
 * not linear in the unknowns.
 */
static RExpr *linear_row(RExpr *lhs, RExpr *rhs, Var *const *x, int k, RExpr **a, RExpr **b)
{
	RExpr *side[2] = { lhs, rhs }, *coef[2][SOLVE_MAX], *rest[2];
	for (int s = 0; s < 2; s++) {
		RExpr *r = side[s];
		for (int j = 0; j < k; j++) {
			Lin p = r ? lin(r, x[j]) : (Lin){ NULL, NULL, 1 };
			if (!p.ok || (p.a && contains_any(p.a, x, k))) {
				RExpr *bad = nonlinear_part(side[s], x, k);
				return bad ? bad : side[s];
			}
			coef[s][j] = p.a;
			r = p.b;
		}
		rest[s] = r && !(r->k == R_CONST && r->c[0] == 0 && (!r->isvec || (r->c[1] == 0 && r->c[2] == 0))) ? r : NULL;
	}
	Loc l = lhs->loc;
	for (int j = 0; j < k; j++) {
		a[j] = coef[0][j] && coef[1][j] ? sadd(coef[0][j], coef[1][j], 1, l) : coef[0][j] ? coef[0][j]
		       : coef[1][j] ? sadd(NULL, coef[1][j], 1, l) : NULL;
		if (a[j] && is_const(a[j], 0)) a[j] = NULL;
	}
	*b = rest[0] && rest[1] ? sadd(rest[1], rest[0], 1, l) : rest[1] ? rest[1] : rest[0] ? sadd(NULL, rest[0], 1, l) : NULL;
	return NULL;
}

/* p * q for scalars (NULL: 0); abs: |p * q|. */
static RExpr *prod(RExpr *p, RExpr *q, int abs, Loc l)
{
	if (!p || !q) return NULL;
	RExpr *r = is_const(p, 1) ? q : is_const(q, 1) ? p : rop(CSF_OP_MUL, 0, l, p, q, NULL);
	return abs ? rop(CSF_OP_ABS, 0, l, r, NULL, NULL) : r;
}

/* The minor of a (k x k, k <= 3) without row i and column j, as a scalar (NULL: 0); abs: its permanent of
 * absolute values (every product positive). */
static RExpr *minor(RExpr *a[SOLVE_MAX][SOLVE_MAX], int k, int i, int j, int abs, Loc l)
{
	int r[2], c[2], nr = 0, nc = 0;
	for (int q = 0; q < k; q++) {
		if (q != i) r[nr++] = q;
		if (q != j) c[nc++] = q;
	}
	if (k == 2) return abs && a[r[0]][c[0]] ? rop(CSF_OP_ABS, 0, l, a[r[0]][c[0]], NULL, NULL) : a[r[0]][c[0]];
	return sadd(prod(a[r[0]][c[0]], a[r[1]][c[1]], abs, l), prod(a[r[0]][c[1]], a[r[1]][c[0]], abs, l), !abs, l);
}

/* sum_i sign_i t_i, where t_i = f(i) * minor(i, j) (f a column of scalars or of values of the equations'
 * type, NULL: 0), sign_i = (-1)^(i + j); abs: |f(i)| times the permanents, all positive. */
static RExpr *expand(RExpr *a[SOLVE_MAX][SOLVE_MAX], int k, RExpr **f, int j, int abs, Loc l)
{
	RExpr *sum = NULL;
	for (int i = 0; i < k; i++) {
		RExpr *m = minor(a, k, i, j, abs, l), *t;
		if (!m || !f[i]) continue;
		RExpr *fi = abs ? rop(CSF_OP_ABS, 0, l, f[i], NULL, NULL) : f[i];
		t = fi->isvec ? smul(fi, m, l) : prod(fi, m, 0, l);
		sum = sadd(sum, t, !abs && (i + j) % 2, l);
	}
	return sum;
}

RExpr **solve_system(RExpr **lhs, RExpr **rhs, char **text, Var *const *x, int k, Loc l, const char *what, int *nz)
{
	RExpr *a[SOLVE_MAX][SOLVE_MAX], *b[SOLVE_MAX], *col[SOLVE_MAX];
	int isvec = lhs[0]->isvec;
	for (int i = 0; i < k; i++) {
		RExpr *bad = linear_row(lhs[i], rhs[i], x, k, a[i], &b[i]);
		if (bad) {
			error_at(bad->loc, "%s, and they are not linear in them: \"%s\" %s", what, text[i], nonlinear_why(bad, x, k));
			return NULL;
		}
		if (lhs[i]->isvec != isvec) {
			error_at(lhs[i]->loc, "%s, but \"%s\" is a %s equation and \"%s\" a %s one: they cannot be one linear system",
			         what, text[0], isvec ? "vector" : "scalar", text[i], isvec ? "scalar" : "vector");
			return NULL;
		}
		for (int j = 0; j < k; j++) nz[i * k + j] = a[i][j] != NULL;
	}
	for (int i = 0; i < k; i++) col[i] = a[i][0];
	RExpr *det = expand(a, k, col, 0, 0, l), *perm = expand(a, k, col, 0, 1, l);
	/* the guard (see the top of this file): sqrt(y)/sqrt(y), 1 or NaN, y = |D| - 2^-47 P */
	RExpr *den = NULL;
	if (det) {
		RExpr *y = rop(CSF_OP_SUB, 0, l, rop(CSF_OP_ABS, 0, l, det, NULL, NULL), prod(rconst(ldexp(1, -47), l), perm, 0, l), NULL);
		RExpr *g = rop(CSF_OP_SQRT, 0, l, y, NULL, NULL);
		den = rop(CSF_OP_MUL, 0, l, det, rop(CSF_OP_DIV, 0, l, g, g, NULL), NULL);
	}
	if (!den || (den->k == R_CONST && !(den->c[0] != 0 && isfinite(den->c[0])))) {
		error_at(l, "%s, but their equations are not independent: the linear system is singular", what);
		return NULL;
	}
	RExpr **sol = xalloc((size_t)k * sizeof *sol);
	for (int j = 0; j < k; j++) {
		RExpr *num = expand(a, k, b, j, 0, l);
		if (!num) num = isvec ? rvconst((double[3]){ 0, 0, 0 }, l) : rconst(0, l);
		sol[j] = sdiv(num, den, l);
	}
	return sol;
}
