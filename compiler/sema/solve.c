/*
 * solve.c - an equation solved symbolically for its target: it must be linear
 * in it.
 */
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
