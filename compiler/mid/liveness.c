/*
 * liveness.c - which rule instances each section needs: the RHS the state
 * derivatives and stop conditions and what they depend on, the OUT section
 * the watched variables, the assertions and the contact bodies'
 * accelerations and what they depend on (Inst.needed, read by the bytecode
 * generator and by lint.c).
 */
#include "csfc.h"
#include "sema.h"
#include "csf_int.h"
#include "liveness.h"

Vec *live_forces(const Model *M)
{
	Vec *Finsts = xalloc((size_t)(M->objects.n + 1) * sizeof(Vec));
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isF) vec_push(&Finsts[(I->iloop ? I->bind[0]->shape->members[0] : I->bind[0])->index], I);
	}
	return Finsts;
}

static void mark(Vec *Finsts, Inst *I, int sec)
{
	if (I->needed[sec]) return;
	I->needed[sec] = 1;
	for (int i = 0; i < I->reads.n; i++) {
		Var *v = sema_canon(I->reads.v[i]); /* a sum reads the members' own */
		if (v->det && v->det != I) mark(Finsts, v->det, sec);
	}
	for (int i = 0; i < I->rf_reads.n; i++) {
		Object *o = I->rf_reads.v[i];
		Vec *fs = &Finsts[o->index];
		for (int k = 0; k < fs->n; k++) mark(Finsts, fs->v[k], sec);
	}
}

int live_mark(Model *M, Vec *Finsts)
{
	/* What is needed: derivatives for RHS; watches and assertions for OUT. */
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if ((I->isderiv && !I->idle) || I->isstop || I->iswhen) mark(Finsts, I, CSF_SEC_RHS);
		if (I->isassert) mark(Finsts, I, CSF_SEC_OUT);
	}
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		Var *v = sema_canon(w->var);
		if (v->det) mark(Finsts, v->det, CSF_SEC_OUT);
	}

	/* Contacts need every body's acceleration, in OUT too (a, FN and Ff are watchable). */
	/* The contact routine runs after the last of them: last_a, an index into M->insts. */
	int last_a = -1;
	Map dets = { 0 }; /* the instances that determine a body's a, by address */
	for (int i = 0; i < M->cbodies.n && M->contacts.n; i++) {
		ContactBody *b = M->cbodies.v[i];
		Var *a = sema_canon(b->f[CSF_CF_A]);
		if (b->kind || !a || !a->det) continue;
		mark(Finsts, a->det, CSF_SEC_OUT);
		map_put(&dets, xprintf("%p", (void *)a->det), a->det);
	}
	/* the constraints likewise: CONSTRAIN runs after CONTACT */
	for (int i = 0; i < M->cons.n; i++) {
		Constraint *K = M->cons.v[i];
		for (int b = 0; b < K->bodies.n; b++) {
			Var *a = sema_canon(prop_of_obj(K->bodies.v[b], "a"));
			if (!a || !a->det) continue;
			mark(Finsts, a->det, CSF_SEC_OUT);
			mark(Finsts, a->det, CSF_SEC_RHS);
			map_put(&dets, xprintf("%p", (void *)a->det), a->det);
		}
	}
	for (int j = 0; j < M->insts.n && (M->contacts.n || M->cons.n); j++)
		if (map_get(&dets, xprintf("%p", M->insts.v[j]))) last_a = j;
	return last_a;
}
