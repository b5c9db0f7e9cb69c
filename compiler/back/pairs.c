/*
 * pairs.c - the position/velocity pairs of the state for velocity Verlet
 * (csf_prog.vpair).
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "gen_int.h"

/*
 * Position/velocity pairs for velocity Verlet: a state variable x whose
 * derivative rule is x' = v, with v a state variable whose own derivative
 * does not depend on v. vpair[i] = 1 + the index of i's velocity component.
 * One dependency pass from all the candidate velocities at once settles
 * every candidate whose derivative none of them reaches (gravity: all); only
 * the others get a pass of their own.
 */
static Var *pair_velocity(Inst *I)
{
	if (!I->isderiv || I->idle) return NULL;
	Assign *a = I->then.v[0];
	Var *x = a->var, *v = a->e->k == R_VAR && !a->e->obj ? a->e->var : NULL;
	return v && var_integrated(v) && v != x && v->isvec == x->isvec ? v : NULL;
}

/* Does v's derivative depend on the slots marked in act (after depends from them)? */
static int reaches(const csf_prog *p, const unsigned char *act, int branch, const Var *v)
{
	uint32_t vd = p->dstart + ((uint32_t)v->slot - p->ystart);
	int dep = branch;
	for (int k = 0; k < (v->isvec ? 3 : 1); k++) dep |= act[vd + k];
	return dep;
}

static void mark_var(unsigned char *act, const Var *v)
{
	for (int k = 0; k < (v->isvec ? 3 : 1); k++) act[v->slot + k] = 1;
}

void gen_pairs(Gen *G, Model *M, csf_prog *p)
{
	p->vpair = xcalloc(p->ny ? p->ny : 1, sizeof *p->vpair);
	unsigned char *all = xcalloc(G->nmem, 1), *act = xmalloc(G->nmem);
	for (int i = 0; i < M->insts.n; i++) {
		Var *v = pair_velocity(M->insts.v[i]);
		if (v) mark_var(all, v);
	}
	int branch = depends(p->code[CSF_SEC_RHS], p->ncode[CSF_SEC_RHS], all, 0);
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		Var *v = pair_velocity(I), *x = v ? ((Assign *)I->then.v[0])->var : NULL;
		if (!v) continue;
		if (reaches(p, all, branch, v)) {
			memset(act, 0, G->nmem);
			mark_var(act, v);
			if (reaches(p, act, depends(p->code[CSF_SEC_RHS], p->ncode[CSF_SEC_RHS], act, 0), v)) continue;
		}
		Shape *S = x->obj->shape; /* by shape, x and v are arrays over its members */
		int nm = M->shaped ? S->n : 1;
		for (int k = 0; k < (v->isvec ? 3 : 1) * nm; k++)
			p->vpair[(uint32_t)x->slot - p->ystart + k] = (uint32_t)v->slot - p->ystart + k + 1;
	}
	free(all);
	free(act);
}
