/*
 * cone.c - the cone of influence: the objects that the watched variables,
 * the assertions and the stop conditions depend on (csfc leaves the others
 * out; csfc --keep-all keeps them).
 *
 * The walk is over (variable, member) and (instance, member) pairs: by
 * shape, one variable or rule instance stands for every member of its
 * shape, and each member is an object of its own here. From the roots (the
 * watched columns, every instance of an assertion or a stop condition) it
 * follows what an instance reads, what determines a variable (its rule, or
 * for a state variable its derivative), and the rules with attribute F
 * behind an RF that is read. A read of a shape named by $1..$k counts every
 * member of that shape.
 *
 * Contacts and constraints couple bodies without a rule reading one from the
 * other: a kept mass point keeps every body it can touch (a contact rule's
 * other side) and every body it shares a constraint with, with what the
 * contact routine or the constraint reads of them. An immovable body (a
 * plane, an anchor) passes nothing on: balls bouncing on one floor do not
 * depend on each other.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "cone.h"
#include "liveness.h"
#include "lint.h"

typedef struct Node { void *p; int mem, inst; } Node;

typedef struct Walk {
	const Model *M;
	Vec *Finsts;
	Map seen;       /* "%p" of a variable or an instance: its members' marks */
	char *kept;     /* by object index */
	int nkept;
	Node *stack;
	size_t n, cap;
} Walk;

static int nmembers(const Shape *S) { return S ? S->n : 1; }

/* An instance is per member when it is the loop over its shape's members; a rule among neighbours
   (Inst.iloop) is one, reading every member it binds, and so is a rule that applies once (Stmt.once: a
   sum over a million members, bound to the first object, read a million times by its million members
   took N^2 steps). */
static int inst_n(const Inst *I)
{
	return !I->iloop && !I->st->once && I->nbind > 0 && I->bind[0]->shape ? nmembers(I->bind[0]->shape) : 1;
}

/* Marks of p: n of them, one per member, then one more, set once every member has been pushed
   (so that a pair rule's N members, each reading every member of a shape, push its N members
   once, not N times N). */
static char *marks(Walk *W, void *p, int n)
{
	char key[32];
	snprintf(key, sizeof key, "%p", p);
	char *m = map_get(&W->seen, key);
	if (!m) {
		m = xalloc((size_t)n + 1);
		map_put(&W->seen, xprintf("%s", key), m);
	}
	return m;
}

static void keep(Walk *W, Object *o)
{
	if (o && !W->kept[o->index]) W->kept[o->index] = 1, W->nkept++;
}

static void push(Walk *W, void *p, int mem, int inst)
{
	if (W->n == W->cap) {
		W->cap = W->cap ? 2 * W->cap : 256;
		W->stack = xrealloc(W->stack, W->cap * sizeof *W->stack);
	}
	W->stack[W->n++] = (Node){ p, mem, inst };
}

/* Variable v of member mem (-1: of every member). */
static void need_var(Walk *W, Var *v, int mem)
{
	if (!v) return;
	v = sema_canon(v);
	if (!sema_per_member(v)) {
		push(W, v, 0, 0);
		return;
	}
	if (mem >= 0) {
		push(W, v, mem, 0);
		return;
	}
	char *m = marks(W, v, v->obj->shape->n);
	if (m[v->obj->shape->n]) return;
	m[v->obj->shape->n] = 1;
	for (int k = 0; k < v->obj->shape->n; k++)
		if (!m[k]) push(W, v, k, 0);
}

static void need_inst(Walk *W, Inst *I, int mem)
{
	int n = inst_n(I);
	if (n == 1) push(W, I, 0, 1);
	else if (mem >= 0) push(W, I, mem, 1);
	else {
		char *m = marks(W, I, n);
		if (m[n]) return;
		m[n] = 1;
		for (int k = 0; k < n; k++)
			if (!m[k]) push(W, I, k, 1);
	}
}

/* The member of an object's shape that instance I's member mem reads: mem for its own $0, every
   member (-1) for a shape that $1..$k range over, the object itself for another. */
static int member_read(const Inst *I, const Object *o, int mem)
{
	if (!o || !o->shape || o->shape->n == 1) return 0;
	if (I->iloop) return -1; /* a rule among neighbours: every member (at its offsets) */
	for (int b = 1; b < I->nbind; b++)
		if (I->bind[b]->shape == o->shape) return -1;
	if (I->nbind > 0 && I->bind[0]->shape == o->shape) return mem;
	return o->sidx;
}

static void visit_var(Walk *W, Var *v, int mem)
{
	if (v->obj) keep(W, sema_per_member(v) ? v->obj->shape->members[mem] : v->obj);
	if (v->det) need_inst(W, v->det, sema_per_member(v) && inst_n(v->det) > 1 ? mem : -1);
	if (v->state && v->deriv) need_inst(W, v->deriv, sema_per_member(v) && inst_n(v->deriv) > 1 ? mem : -1);
}

static void visit_inst(Walk *W, Inst *I, int mem)
{
	for (int k = 0; k < I->reads.n; k++) {
		Var *r = I->reads.v[k], *v = sema_canon(r);
		/* a member's own variable (in a sum): that member; one lean members share (Object.lean), in a
		   sum: every member */
		int all = r->obj && r->obj->lean && vec_has(&I->summed, r);
		need_var(W, v, !sema_per_member(v) ? 0 : all ? -1 : r != v ? r->obj->sidx : member_read(I, v->obj, mem));
	}
	for (int k = 0; k < I->rf_reads.n; k++) {
		Object *o = I->rf_reads.v[k];
		Object *rep = o->shape ? o->shape->members[0] : o;
		int m = member_read(I, o, mem);
		Vec *fs = &W->Finsts[rep->index];
		for (int j = 0; j < fs->n; j++) need_inst(W, fs->v[j], m);
	}
}

static void drain(Walk *W)
{
	while (W->n) {
		Node x = W->stack[--W->n];
		int n = x.inst ? inst_n(x.p) : sema_per_member(x.p) ? ((Var *)x.p)->obj->shape->n : 1;
		char *m = marks(W, x.p, n);
		if (m[x.mem]) continue;
		m[x.mem] = 1;
		if (x.inst) visit_inst(W, x.p, x.mem);
		else visit_var(W, x.p, x.mem);
	}
}

/* Every field the contact routine reads of body b. */
static void need_body(Walk *W, ContactBody *b)
{
	keep(W, b->o);
	for (int f = 0; f < CSF_CF_N; f++)
		if (b->f[f]) need_var(W, b->f[f], b->o->sidx);
}

/* The contacts and constraints of kept bodies; returns whether it kept more. */
static int couple(Walk *W)
{
	int before = W->nkept;
	const Model *M = W->M;
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		int k0 = 0, k1 = 0; /* a kept movable body on each side */
		for (int j = 0; j < c->b0.n; j++) k0 |= W->kept[((ContactBody *)c->b0.v[j])->o->index];
		for (int j = 0; j < c->b1.n; j++) {
			ContactBody *b = c->b1.v[j];
			k1 |= !b->kind && W->kept[b->o->index];
		}
		for (int j = 0; j < c->b0.n; j++) {
			ContactBody *b = c->b0.v[j];
			if (k1 || W->kept[b->o->index]) need_body(W, b);
		}
		for (int j = 0; j < c->b1.n && (k0 || k1); j++) {
			ContactBody *b = c->b1.v[j];
			if (k0 || W->kept[b->o->index]) need_body(W, b);
		}
	}
	for (int i = 0; i < M->cons.n; i++) {
		Constraint *K = M->cons.v[i];
		int any = 0;
		for (int b = 0; b < K->bodies.n; b++) any |= W->kept[((Object *)K->bodies.v[b])->index];
		if (!any) continue;
		static const char *const props[] = { "pos", "v", "a", "m", "cr", "FC" };
		for (int k = 0; k < K->reads.n; k++) {
			Var *v = K->reads.v[k];
			need_var(W, v, v->obj ? v->obj->sidx : 0);
		}
		for (int b = 0; b < K->nbind; b++) {
			keep(W, K->bind[b]);
			for (size_t k = 0; k < sizeof props / sizeof props[0]; k++)
				need_var(W, prop_of_obj(K->bind[b], props[k]), K->bind[b]->sidx);
		}
	}
	drain(W);
	return W->nkept > before;
}

/* The walk from the roots (the watched columns, the assertions and stop conditions) to its end. */
static void walk(Walk *W, const Model *M)
{
	*W = (Walk){ .M = M, .Finsts = live_forces(M) };
	W->kept = xalloc((size_t)M->objects.n + 1);
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		Var *v = sema_canon(w->var);
		need_var(W, v, !sema_per_member(v) ? 0 : v->kind == V_TEMP || w->var->obj->lean ? w->member : w->var->obj->sidx);
	}
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isassert || I->isstop || I->iswhen) need_inst(W, I, -1);
	}
	drain(W);
	while (couple(W))
		;
	free(W->stack);
}

char *cone_dropped(const Model *M)
{
	Walk W;
	walk(&W, M);
	/* nothing kept (only t and globals watched): left as it is, so that every assertion stays */
	if (W.nkept == M->objects.n || W.nkept == 0) return NULL;
	char *drop = xalloc((size_t)M->objects.n + 1);
	for (int i = 0; i < M->objects.n; i++) drop[i] = !W.kept[i];
	return drop;
}

void cone_idle_states(Model *M)
{
	Walk W;
	walk(&W, M);
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (!I->isderiv || !I->targets.n) continue;
		Var *v = sema_canon(I->targets.v[0]);
		const char *m = map_get(&W.seen, xprintf("%p", (void *)v));
		int n = sema_per_member(v) ? v->obj->shape->n : 1, any = 0;
		for (int k = 0; m && k < n; k++) any |= m[k];
		I->idle = !any;
	}
}

/*
 * The model without the objects that nothing watched, asserted or stopped on
 * depends on (cone_dropped), resolved again, with a warning for each (the
 * first three; then how many more); M itself if every object is needed.
 */
Model *cone_leave_out(Stmt *stmts, Model *M, ArenaMark mark)
{
	const char *left = cone_dropped(M);
	if (!left) return M;
	size_t n = (size_t)M->objects.n + 1;
	char *drop = memcpy(xmalloc(n), left, n);
	arena_release(mark);
	Model *P = sema_run(stmts, drop);
	free(drop);
	/* left out, they make an error: M again (it resolved without a diagnostic: silently again) */
	if (!P) return sema_run(stmts, NULL);
	int shown = 0;
	for (int i = 0; i < P->objects.n; i++) {
		Object *o = P->objects.v[i];
		if (!o->dropped) continue;
		if (shown++ < 3) warn_at(o->loc, "object '%s' affects nothing watched: it is left out (csfc --keep-all keeps it)", o->name);
		else {
			warn_at(o->loc, "and %d more objects from '%s' on affect nothing watched: they are left out (csfc --explain "
			                "lists them)", P->ndropped - 3, o->name);
			break;
		}
	}
	return P;
}
