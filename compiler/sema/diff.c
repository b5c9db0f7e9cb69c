/*
 * diff.c - the directional derivative of a resolved expression, as an
 * expression: d/ds e(x + s dx, t + s dt) at s = 0, where the direction
 * gives each variable's rate (Dir). Constraints use it for their gradient
 * (the direction of one position component), their rate (positions moving
 * at the velocities, t at 1) and the bias of their second derivative (the
 * rate of the rate, velocities held).
 *
 * Zero is NULL throughout, so that a derivative is only as large as the
 * variables it depends on make it; constants fold as rop folds them. What
 * is not differentiable (a comparison, min, max, an angle between vectors,
 * a projection, RF) is reported once, at the operation.
 */
#include <math.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

static RExpr *add(RExpr *a, RExpr *b, Loc l)
{
	if (!a) return b;
	if (!b) return a;
	return rop(a->isvec ? CSF_OP_VADD : CSF_OP_ADD, a->isvec, l, a, b, NULL);
}

static RExpr *sub(RExpr *a, RExpr *b, Loc l)
{
	if (!b) return a;
	if (!a) return rop(b->isvec ? CSF_OP_VNEG : CSF_OP_NEG, b->isvec, l, b, NULL, NULL);
	return rop(a->isvec ? CSF_OP_VSUB : CSF_OP_SUB, a->isvec, l, a, b, NULL);
}

/* a * k, a scalar or a vector times scalar k; zero if either is. */
static RExpr *mul(RExpr *a, RExpr *k, Loc l)
{
	if (!a || !k) return NULL;
	if (is_const(k, 1)) return a;
	if (!a->isvec && is_const(a, 1)) return k;
	if (a->isvec) return rop(CSF_OP_VMUL, 1, l, a, k, NULL);
	if (k->isvec) return rop(CSF_OP_VMUL, 1, l, k, a, NULL);
	return rop(CSF_OP_MUL, 0, l, a, k, NULL);
}

static RExpr *dvd(RExpr *a, RExpr *k, Loc l)
{
	if (!a) return NULL;
	return rop(a->isvec ? CSF_OP_VDIV : CSF_OP_DIV, a->isvec, l, a, k, NULL);
}

/* The axis (0, 1, 2) a constant vector is a unit vector along, times *sign; -1 if it is not one. */
static int axis_of(const RExpr *e, double *sign)
{
	if (e->k != R_CONST || !e->isvec) return -1;
	int ax = -1;
	for (int i = 0; i < 3; i++) {
		if (e->c[i] == 0) continue;
		if (ax >= 0 || fabs(e->c[i]) != 1) return -1;
		ax = i, *sign = e->c[i];
	}
	return ax;
}

static RExpr *dot(RExpr *a, RExpr *b, Loc l)
{
	if (!a || !b) return NULL;
	double sign;
	int ax = axis_of(b, &sign);
	if (ax < 0 && (ax = axis_of(a, &sign)) >= 0) a = b;
	if (ax >= 0) { /* along an axis (a gradient's direction): a component, not a dot product */
		RExpr *c = rnew(R_COMP, l);
		c->a[0] = a;
		c->n = 1;
		c->comp = ax;
		return sign > 0 ? c : rop(CSF_OP_NEG, 0, l, c, NULL, NULL);
	}
	return rop(CSF_OP_VDOT, 0, l, a, b, NULL);
}

static RExpr *fn(int op, RExpr *a, Loc l) { return rop(op, 0, l, a, NULL, NULL); }

static RExpr *k(double x, Loc l) { return rconst(x, l); }

/* An operation that has no derivative, in a model's words. */
static const char *op_words(int op)
{
	switch (op) {
	case CSF_OP_MIN: return "min()";
	case CSF_OP_MAX: return "max()";
	case CSF_OP_VANGLE: return "an angle between vectors";
	case CSF_OP_VPROJ: return "a projection";
	case CSF_OP_FLOOR: return "floor()";
	default: return "a comparison";
	}
}

/* The derivative of e along D; reports what it cannot differentiate (D->failed). */
static RExpr *d(Dir *D, RExpr *e)
{
	Loc l = e->loc;
	if (D->failed) return NULL;
	switch (e->k) {
	case R_CONST: return NULL;
	case R_VAR: return D->rate(D, e);
	case R_COMP: {
		RExpr *x = d(D, e->a[0]);
		if (!x) return NULL;
		if (x->k == R_CONST) return k(x->c[e->comp], l);
		RExpr *c = rnew(R_COMP, l);
		c->a[0] = x;
		c->n = 1;
		c->comp = e->comp;
		return c;
	}
	case R_RF:
		D->failed = 1;
		error_at(l, "%s cannot read RF", D->what);
		return NULL;
	case R_OP: break;
	}
	RExpr *a = e->a[0], *b = e->n > 1 ? e->a[1] : NULL;
	RExpr *da = d(D, a), *db = b ? d(D, b) : NULL;
	if (D->failed) return NULL;
	switch (e->op) {
	case CSF_OP_MOV:
	case CSF_OP_VMOV: return da;
	case CSF_OP_VPACK: {
		RExpr *dc = d(D, e->a[2]);
		if (!da && !db && !dc) return NULL;
		return rop(CSF_OP_VPACK, 1, l, da ? da : k(0, l), db ? db : k(0, l), dc ? dc : k(0, l));
	}
	case CSF_OP_ADD:
	case CSF_OP_VADD: return add(da, db, l);
	case CSF_OP_SUB:
	case CSF_OP_VSUB: return sub(da, db, l);
	case CSF_OP_NEG:
	case CSF_OP_VNEG: return sub(NULL, da, l);
	case CSF_OP_MUL: return add(mul(da, b, l), mul(a, db, l), l);
	case CSF_OP_VMUL: return add(mul(da, b, l), mul(a, db, l), l);
	case CSF_OP_DIV:
	case CSF_OP_VDIV: /* da / b - (a / b) db / b */
		return sub(dvd(da, b, l), db ? dvd(mul(dvd(a, b, l), db, l), b, l) : NULL, l);
	case CSF_OP_VDOT: return add(dot(da, b, l), dot(a, db, l), l);
	case CSF_OP_VCROSS:
		return add(da ? rop(CSF_OP_VCROSS, 1, l, da, b, NULL) : NULL, db ? rop(CSF_OP_VCROSS, 1, l, a, db, NULL) : NULL, l);
	case CSF_OP_VMAG: /* a . da / |a| */
		return da ? dvd(dot(a, da, l), e, l) : NULL;
	case CSF_OP_VUNIT: /* da / |a| - a (a . da) / |a|^3 */
		if (!da) return NULL;
		{
			RExpr *m = fn(CSF_OP_VMAG, a, l);
			return sub(dvd(da, m, l), mul(a, dvd(dot(a, da, l), rop(CSF_OP_POW, 0, l, m, k(3, l), NULL), l), l), l);
		}
	case CSF_OP_POW:
		if (b->k == R_CONST) { /* b a^(b-1) da */
			if (!da) return NULL;
			return mul(da, mul(k(b->c[0], l), rop(CSF_OP_POW, 0, l, a, k(b->c[0] - 1, l), NULL), l), l);
		}
		/* a^b (db ln a + b da / a) */
		return mul(e, add(mul(db, fn(CSF_OP_LOG, a, l), l), dvd(mul(da, b, l), a, l), l), l);
	case CSF_OP_SIN: return mul(da, fn(CSF_OP_COS, a, l), l);
	case CSF_OP_COS: return sub(NULL, mul(da, fn(CSF_OP_SIN, a, l), l), l);
	case CSF_OP_TAN: return da ? dvd(da, rop(CSF_OP_POW, 0, l, fn(CSF_OP_COS, a, l), k(2, l), NULL), l) : NULL;
	case CSF_OP_SQRT: return da ? dvd(da, mul(k(2, l), e, l), l) : NULL;
	case CSF_OP_EXP: return mul(da, e, l);
	case CSF_OP_LOG: return da ? dvd(da, a, l) : NULL;
	case CSF_OP_LOG10: return da ? dvd(da, mul(a, k(log(10.0), l), l), l) : NULL;
	case CSF_OP_ASIN:
	case CSF_OP_ACOS: {
		if (!da) return NULL;
		RExpr *r = dvd(da, fn(CSF_OP_SQRT, sub(k(1, l), mul(a, a, l), l), l), l);
		return e->op == CSF_OP_ASIN ? r : sub(NULL, r, l);
	}
	case CSF_OP_ATAN: return da ? dvd(da, add(k(1, l), mul(a, a, l), l), l) : NULL;
	case CSF_OP_ATAN2: /* atan2(a, b): (b da - a db) / (a^2 + b^2) */
		if (!da && !db) return NULL;
		return dvd(sub(mul(b, da, l), mul(a, db, l), l), add(mul(a, a, l), mul(b, b, l), l), l);
	case CSF_OP_SINH: return mul(da, fn(CSF_OP_COSH, a, l), l);
	case CSF_OP_COSH: return mul(da, fn(CSF_OP_SINH, a, l), l);
	case CSF_OP_TANH: return da ? mul(da, sub(k(1, l), mul(e, e, l), l), l) : NULL;
	case CSF_OP_ABS: return da ? mul(da, dvd(a, e, l), l) : NULL;
	default:
		if (!da && !db) return NULL; /* a step function of what does not move */
		D->failed = 1;
		error_at(l, "%s must be differentiable in the positions and t, and %s is not", D->what, op_words(e->op));
		return NULL;
	}
}

RExpr *diff(Dir *D, RExpr *e) { return d(D, e); }
