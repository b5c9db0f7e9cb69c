/*
 * expr.c - the resolved expressions (RExpr): constants, and operations whose
 * constant operands are folded (fold.c) with their dimension (dims.c); the
 * functions a model may call.
 */
#include <math.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

RExpr *rnew(RKind k, Loc l)
{
	RExpr *e = xalloc(sizeof *e);
	e->k = k;
	e->loc = l;
	return e;
}

RExpr *rconst(double x, Loc l)
{
	RExpr *e = rnew(R_CONST, l);
	e->c[0] = x;
	e->dimk = DK_FREE;
	return e;
}

RExpr *rvconst(const double *v, Loc l)
{
	RExpr *e = rnew(R_CONST, l);
	memcpy(e->c, v, sizeof e->c);
	e->isvec = 1;
	e->dimk = DK_FREE;
	return e;
}

/* A constant standing for a variable's value (initial values): it has the variable's dimension. */
RExpr *rvarconst(Var *v, Loc l)
{
	RExpr *e = v->isvec ? rvconst(v->init, l) : rconst(v->init[0], l);
	if (v->dimk == DK_KNOWN) {
		e->dimk = DK_KNOWN;
		memcpy(e->dim, v->dim, sizeof e->dim);
	}
	return e;
}

int is_const(RExpr *e, double x) { return e->k == R_CONST && !e->isvec && e->c[0] == x; }

/* Builds op(a, b, c) of the given result type, folding constant operands. */
RExpr *rop(int op, int isvec, Loc l, RExpr *a, RExpr *b, RExpr *c)
{
	RExpr *e = rnew(R_OP, l);
	e->op = op;
	e->isvec = isvec;
	e->a[0] = a;
	e->a[1] = b;
	e->a[2] = c;
	e->n = c ? 3 : b ? 2 : 1;
	int allc = 1;
	for (int i = 0; i < e->n; i++) allc &= e->a[i]->k == R_CONST;
	if (allc) {
		double in[3][3] = { { 0 } }, out[3];
		for (int i = 0; i < e->n; i++) memcpy(in[i], e->a[i]->c, sizeof in[i]);
		/* Folding -0.0 and NaN is safe here: the constant pool (gen.c) tells
		 * constants apart by their bits, not by ==. */
		fold_op(op, in, out);
		RExpr *k = rnew(R_CONST, l);
		memcpy(k->c, out, sizeof out);
		k->isvec = isvec;
		if (!sema.dims_off) dims_fold(op, e->a, e->n, k, l);
		return k;
	}
	return e;
}

int opcode_of_func(const char *name, int *nargs)
{
	static const struct { const char *n; int op, args; } f[] = {
		{ "sin", CSF_OP_SIN, 1 }, { "cos", CSF_OP_COS, 1 }, { "tan", CSF_OP_TAN, 1 },
		{ "asin", CSF_OP_ASIN, 1 }, { "acos", CSF_OP_ACOS, 1 }, { "atan", CSF_OP_ATAN, 1 },
		{ "sinh", CSF_OP_SINH, 1 }, { "cosh", CSF_OP_COSH, 1 }, { "tanh", CSF_OP_TANH, 1 },
		{ "exp", CSF_OP_EXP, 1 }, { "log", CSF_OP_LOG, 1 }, { "log10", CSF_OP_LOG10, 1 },
		{ "sqrt", CSF_OP_SQRT, 1 }, { "abs", CSF_OP_ABS, 1 }, { "atan2", CSF_OP_ATAN2, 2 },
		{ "min", CSF_OP_MIN, 2 }, { "max", CSF_OP_MAX, 2 }, { "floor", CSF_OP_FLOOR, 1 }, { "mod", CSF_OP_FLOOR, 2 },
	};
	for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
		if (strcmp(f[i].n, name) == 0) {
			*nargs = f[i].args;
			return f[i].op;
		}
	return -1;
}
