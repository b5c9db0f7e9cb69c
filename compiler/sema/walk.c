/*
 * walk.c - the expressions of a statement: its condition, its call, both sides
 * of its equations, at every depth of its conditional blocks.
 */
#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* Calls f on both sides of each equation of steps q and on the condition of each block, at every
 * depth. Returns 0 as soon as f does, else 1. */
static int eqns_each(Eqn *q, ExprFn f, void *ctx)
{
	for (; q; q = q->next) {
		if (q->nest) {
			if (!f(q->nest->cond, ctx) || !eqns_each(q->nest->then, f, ctx) || !eqns_each(q->nest->els, f, ctx)) return 0;
		} else if (!f(q->lhs, ctx) || !f(q->rhs, ctx)) {
			return 0;
		}
	}
	return 1;
}

/* Calls f on every expression of statement s: its condition, its call, its steps'. As eqns_each. */
int stmt_each(Stmt *s, ExprFn f, void *ctx)
{
	return f(s->cond, ctx) && f(s->call, ctx) && eqns_each(s->eqns, f, ctx);
}
