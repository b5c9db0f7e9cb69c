/*
 * gen.c - from a resolved model to a csf_prog (bytecode).
 *
 * Only what the scene needs is compiled: the RHS section holds the rule
 * instances the state derivatives depend on, then the derivatives; the OUT
 * section holds the instances the watched variables and the assertions
 * depend on, then the assertions. Memory is laid out as
 *   t | state | derivatives | globals, properties, temporaries, constants | scratch
 * where variables and constants get slots as the code first refers to them
 * and scratch slots (expression temporaries, reused by every instance) are
 * placed last once their number is known.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "csf.h"
#include "gen.h"

/* Scratch operands carry this bit until scratch is placed; memory stays below it. */
#define SCRATCH (1u << 28)

typedef struct Gen {
	Model *M;
	csf_prog *p;
	double *mem;
	uint32_t nmem, capmem;
	uint32_t *code;
	uint32_t ncode, capcode;
	csf_line *lines;
	uint32_t nlines, caplines;
	csf_target *targets;
	uint32_t ntargets, captargets;
	uint32_t scratch, max_scratch;
	char *strs;
	uint32_t nstrs, capstrs;
	Vec *Finsts; /* per object index: its F instances */
	Map strmap;  /* string -> offset + 1 */
	Map pclass;  /* parameter class key -> index + 1 */
	csf_pclass *pclasses;
	uint32_t npclasses, cappclasses;
	struct { RExpr *e; uint32_t slot; } cse[64]; /* within one equation: values computed so far */
	int ncse;
	Map consts;  /* constant bits -> slot + 1 */
	int loop;     /* the levels of the loops the instance being emitted runs in (0: none) */
	Inst *evinst; /* emitting a condition of this conditional rule, located as events ... */
	int evsrc;    /* ... which name this statement */
	Map evmap;    /* comparison (by address) -> event index + 1 */
	csf_event *events;
	uint32_t nevents, capevents;
} Gen;

static void *grow(void *p, uint32_t *cap, uint32_t need, size_t elem)
{
	if (need <= *cap) return p;
	uint32_t c = *cap ? *cap : 64;
	while (c < need) c *= 2;
	void *q = realloc(p, (size_t)c * elem);
	if (!q) {
		fprintf(stderr, "csfc: out of memory\n");
		exit(2);
	}
	*cap = c;
	return q;
}

static uint32_t alloc_mem(Gen *G, uint32_t n, const double *init)
{
	if ((uint64_t)G->nmem + n >= SCRATCH / 2) { /* the Jacobian's tangents double it */
		error_plain("the scene needs more than %u memory slots (%u MiB of values): too big to compile", SCRATCH / 2,
		            SCRATCH / 2 / 131072);
		exit(1);
	}
	G->mem = grow(G->mem, &G->capmem, G->nmem + n, sizeof(double));
	for (uint32_t i = 0; i < n; i++) G->mem[G->nmem + i] = init ? init[i] : 0.0;
	G->nmem += n;
	return G->nmem - n;
}

static uint32_t str_intern(Gen *G, const char *s)
{
	uintptr_t known = (uintptr_t)map_get(&G->strmap, s);
	if (known) return (uint32_t)(known - 1);
	uint32_t n = (uint32_t)strlen(s) + 1;
	G->strs = grow(G->strs, &G->capstrs, G->nstrs + n, 1);
	memcpy(G->strs + G->nstrs, s, n);
	G->nstrs += n;
	map_put(&G->strmap, xstrdup(s), (void *)(uintptr_t)(G->nstrs - n + 1));
	return G->nstrs - n;
}

/*
 * The slot of v, allocated at its first use. A property of the objects of a
 * shape is an array, member i's value at slot + i (a vector: slot + 3 i),
 * allocated for all members at once; so is a temporary of one object of
 * such a shape (only the representative's exists).
 */
static uint32_t var_slot(Gen *G, Var *v)
{
	if (v->slot >= 0) return (uint32_t)v->slot;
	uint32_t w = v->isvec ? 3 : 1;
	if (!sema_per_member(v)) {
		v->slot = (int)alloc_mem(G, w, v->kind == V_TEMP ? NULL : v->init);
		return (uint32_t)v->slot;
	}
	Shape *S = v->obj->shape;
	uint32_t base = alloc_mem(G, (uint32_t)S->n * w, NULL);
	if (v->kind == V_TEMP) {
		v->slot = (int)base;
		return base;
	}
	for (int q = 0; q < S->n; q++) {
		Var *m = map_get(&S->members[q]->props_by_name, v->name);
		m->slot = (int)(base + (uint32_t)q * w);
		memcpy(G->mem + m->slot, m->init, w * sizeof(double));
	}
	return (uint32_t)v->slot;
}

/*
 * Why -D cannot set the initial value of global or property v, or "" if it
 * can: a value folded at compile time into another, or computed from
 * others, or one that decided which contacts exist, or a variable a rule
 * computes (its initial value is never read). The initial value of a state
 * variable is its value at t = 0, and can be set.
 */
static const char *param_why(Var *v)
{
	Var *r = sema_canon(v);
	const char *on = v->fix_obj ? v->fix_obj : "", *dot = v->fix_obj ? "." : "";
	switch (v->fix) {
	case FIX_FOLDED:
		return xprintf("its value is folded at compile time into the value of %s%s%s (line %d)", on, dot, v->fix_name,
		               v->fix_line);
	case FIX_DERIVED:
		return xprintf("its value is computed at compile time from %s%s%s (line %d)", on, dot,
		               v->fix_name, v->fix_line);
	case FIX_RUN: return xprintf("its value is folded at compile time into the run's '%s' (line %d)", v->fix_name, v->fix_line);
	case FIX_CONTACT: return "its value 0 decided at compile time that it never touches another point";
	}
	if (r->det && !r->state)
		return xprintf("a rule computes it (%s:%d); it is not an input",
		               ((Source *)sources.v[r->det->st->loc.file])->path, r->det->st->loc.line);
	return "";
}

/*
 * The parameter class (csf_pclass) of global or property v: its dimension,
 * unit, and param_why. The strings of a class already known are released:
 * a million objects' properties take no memory but their classes'.
 */
static uint32_t param_class(Gen *G, Var *v)
{
	Var *r = sema_canon(v);
	const Var *d = v->dimk == DK_KNOWN ? v : r;
	int known = d->dimk == DK_KNOWN;
	for (int pass = 0;; pass++) {
		ArenaMark mark = arena_mark();
		const char *unit = known ? dims_unit(d->dim) : "", *why = param_why(v);
		char *key = xprintf("%d %.17g %.17g %.17g %.17g %s\x01%s", known, known ? d->dim[0] : 0, known ? d->dim[1] : 0,
		                    known ? d->dim[2] : 0, known ? d->dim[3] : 0, unit, why);
		uintptr_t k = (uintptr_t)map_get(&G->pclass, key);
		if (k || pass == 0) {
			arena_release(mark);
			if (k) return (uint32_t)(k - 1);
			continue;
		}
		/* a new class (second pass, its strings kept) */
		G->pclasses = grow(G->pclasses, &G->cappclasses, G->npclasses + 1, sizeof *G->pclasses);
		csf_pclass *c = &G->pclasses[G->npclasses];
		*c = (csf_pclass){ str_intern(G, unit), str_intern(G, why), (uint32_t)known, { 0 } };
		if (known) memcpy(c->dim, d->dim, sizeof c->dim);
		map_put(&G->pclass, key, (void *)(uintptr_t)(++G->npclasses));
		return G->npclasses - 1;
	}
}

/* The operand word for v read at place ($n) of the instance being emitted: relative to
   that place's loop index when v is an array over a shape. */
static uint32_t var_operand(Gen *G, Var *v, int place)
{
	uint32_t s = var_slot(G, v), level = (uint32_t)place + 1;
	if (place < 0 || (int)level > G->loop || !sema_per_member(v)) return s;
	return csf_rel(s, v->isvec ? 2 * level : 2 * level - 1);
}

/* How many levels of loops instance I runs in: one per place when a shape of more than one
   object is bound (0: compiled for its objects alone). */
static int inst_loops(const Model *M, const Inst *I)
{
	if (!M->shaped || I->st->has_for) return 0;
	for (int b = 0; b < I->nbind; b++)
		if (I->bind[b]->shape->n > 1) return I->nbind;
	return 0;
}

/* A $1 rule with attribute F in loops: its forces summed over $1 into an array (acc). */
static int sums_pairs(const Model *M, const Inst *I) { return I->isF && I->nbind > 1 && inst_loops(M, I); }

static uint64_t dbits(double d)
{
	uint64_t u;
	memcpy(&u, &d, 8);
	return u;
}

/* The slot of a constant, shared by every use of the same bits. */
static uint32_t const_slot(Gen *G, const double *c, int isvec)
{
	char key[64];
	snprintf(key, sizeof key, "%d:%016llx:%016llx:%016llx", isvec, (unsigned long long)dbits(c[0]),
	         isvec ? (unsigned long long)dbits(c[1]) : 0ull, isvec ? (unsigned long long)dbits(c[2]) : 0ull);
	uintptr_t known = (uintptr_t)map_get(&G->consts, key);
	if (known) return (uint32_t)(known - 1);
	uint32_t s = alloc_mem(G, isvec ? 3 : 1, c);
	map_put(&G->consts, xstrdup(key), (void *)(uintptr_t)(s + 1));
	return s;
}

static uint32_t new_scratch(Gen *G, int width)
{
	uint32_t s = G->scratch;
	G->scratch += (uint32_t)width;
	if (G->scratch > G->max_scratch) G->max_scratch = G->scratch;
	return SCRATCH | s;
}

static uint32_t pc(Gen *G) { return G->ncode; }

static void emit_words(Gen *G, int op, const uint32_t *ops)
{
	int n = csf_opinfo_table[op].nops;
	G->code = grow(G->code, &G->capcode, G->ncode + 1 + (uint32_t)n, sizeof(uint32_t));
	G->code[G->ncode++] = (uint32_t)op;
	for (int i = 0; i < n; i++) G->code[G->ncode++] = ops[i];
}

static void emit_op(Gen *G, int op, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
	uint32_t ops[4] = { a, b, c, d };
	emit_words(G, op, ops);
}

/* Does an operand of this kind (enum csf_operand_kind) name memory slots? */
static int slot_kind(int kind)
{
	return kind == CSF_K_S || kind == CSF_K_V || kind == CSF_K_DS || kind == CSF_K_DV;
}

/* Emits R[dest] := R[x] ^ k for a constant k: POWI when csf_powi computes it, else POW. */
static void emit_pow_const(Gen *G, uint32_t dest, uint32_t x, double k)
{
	if (csf_is_powi(k)) emit_op(G, CSF_OP_POWI, dest, x, (uint32_t)(int)k, 0);
	else emit_op(G, CSF_OP_POW, dest, x, const_slot(G, (double[3]){ k, 0, 0 }, 0), 0);
}

static uint32_t emit(Gen *G, RExpr *e);

/* The slot of I's sums over $1 (sums_pairs), one vector per member of $0's shape. */
static uint32_t acc_slot(Gen *G, Inst *I)
{
	if (!I->acc) I->acc = 1 + (int)alloc_mem(G, 3u * (uint32_t)I->bind[0]->shape->n, NULL);
	return (uint32_t)I->acc - 1;
}

/* The terms of object o's RF, the forces of its F rules in their order (of a $1 rule in loops,
   its sum over $1), as operand words into t[0..max); returns how many there are. */
static int rf_terms(Gen *G, Object *o, uint32_t *t, int max)
{
	Vec *fs = &G->Finsts[o->index];
	int n = 0;
	for (int i = 0; i < fs->n; i++) {
		Inst *I = fs->v[i];
		if (sums_pairs(G->M, I)) {
			if (n < max) t[n] = G->loop ? csf_rel(acc_slot(G, I), 2) : acc_slot(G, I);
			n++;
			continue;
		}
		for (int k = 0; k < I->targets.n; k++, n++)
			if (n < max) t[n] = var_operand(G, I->targets.v[k], 0);
	}
	return n;
}

/* Structural equality of two expressions (same operations on the same operands). */
static int expr_same(const RExpr *a, const RExpr *b)
{
	if (a == b) return 1;
	if (a->k != b->k || a->isvec != b->isvec) return 0;
	switch (a->k) {
	case R_CONST: return memcmp(a->c, b->c, sizeof a->c) == 0;
	case R_VAR: return a->var == b->var && a->place == b->place;
	case R_RF: return a->obj == b->obj;
	case R_COMP: return a->comp == b->comp && expr_same(a->a[0], b->a[0]);
	case R_OP:
		if (a->op != b->op || a->n != b->n) return 0;
		for (int i = 0; i < a->n; i++)
			if (!expr_same(a->a[i], b->a[i])) return 0;
		return 1;
	}
	return 0;
}

static void cse_reset(Gen *G) { G->ncse = 0; }

/*
 * A comparison in the condition of a conditional rule that the RHS needs is
 * an event: its value (the difference of its sides, positive when true)
 * goes to a slot of its own, and EVGT/EVGE give the side the runtime froze
 * at the last located crossing. Both sections share the event.
 */
static int emit_event(Gen *G, RExpr *e, uint32_t dest)
{
	int op = e->op;
	if (!G->evinst || !(op == CSF_OP_LT || op == CSF_OP_LE || op == CSF_OP_GT || op == CSF_OP_GE)) return 0;
	char *key = xprintf("%p", (void *)e);
	uintptr_t known = (uintptr_t)map_get(&G->evmap, key);
	/* in a loop (one level: by shape, conditional rules of pairs are not), one event per member */
	uint32_t n = G->loop ? (uint32_t)G->evinst->bind[0]->shape->n : 1;
	if (!known) {
		G->events = grow(G->events, &G->capevents, G->nevents + n, sizeof *G->events);
		uint32_t value = alloc_mem(G, n, NULL), mode = alloc_mem(G, n, NULL);
		int strict = op == CSF_OP_LT || op == CSF_OP_GT;
		known = G->nevents + 1;
		for (uint32_t q = 0; q < n; q++) {
			G->mem[mode + q] = -1;
			G->events[G->nevents++] = (csf_event){ strict ? 0u : 1u, value + q, mode + q, (uint32_t)G->evsrc };
		}
		map_put(&G->evmap, key, (void *)known);
	}
	const csf_event *ev = &G->events[known - 1];
	uint32_t r = G->loop ? 1 : 0, value = csf_rel(ev->value, r), mode = csf_rel(ev->mode, r);
	uint32_t x = emit(G, e->a[0]), y = emit(G, e->a[1]);
	if (op == CSF_OP_LT || op == CSF_OP_LE) emit_op(G, CSF_OP_SUB, value, y, x, 0);
	else emit_op(G, CSF_OP_SUB, value, x, y, 0);
	emit_op(G, ev->kind ? CSF_OP_EVGE : CSF_OP_EVGT, dest, value, mode, 0);
	return 1;
}

static void emit_into(Gen *G, RExpr *e, uint32_t dest)
{
	if (e->k == R_OP && emit_event(G, e, dest)) return;
	if (e->k == R_OP && e->op == CSF_OP_POW && e->a[1]->k == R_CONST) {
		emit_pow_const(G, dest, emit(G, e->a[0]), e->a[1]->c[0]);
		return;
	}
	if (e->k == R_OP) {
		uint32_t o[3] = { 0, 0, 0 };
		for (int i = 0; i < e->n; i++) o[i] = emit(G, e->a[i]);
		emit_op(G, e->op, dest, o[0], o[1], o[2]);
		return;
	}
	if (e->k == R_RF) {
		int n = rf_terms(G, e->obj, NULL, 0);
		if (n >= 2) {
			uint32_t *t = xalloc((size_t)n * sizeof *t);
			rf_terms(G, e->obj, t, n);
			emit_op(G, CSF_OP_VADD, dest, t[0], t[1], 0);
			for (int i = 2; i < n; i++) emit_op(G, CSF_OP_VADD, dest, dest, t[i], 0);
			return;
		}
	}
	uint32_t s = emit(G, e);
	emit_op(G, e->isvec ? CSF_OP_VMOV : CSF_OP_MOV, dest, s, 0, 0);
}

static uint32_t emit(Gen *G, RExpr *e)
{
	switch (e->k) {
	case R_CONST: return const_slot(G, e->c, e->isvec);
	case R_VAR: return e->var->kind == V_TIME ? G->p->tslot : var_operand(G, e->var, e->place);
	case R_COMP: return emit(G, e->a[0]) + (uint32_t)e->comp;
	case R_RF: {
		uint32_t t[1];
		int n = rf_terms(G, e->obj, t, 1);
		if (n == 0) return const_slot(G, (double[3]){ 0, 0, 0 }, 1);
		if (n == 1) return t[0];
		uint32_t d = new_scratch(G, 3);
		emit_into(G, e, d);
		return d;
	}
	case R_OP: {
		/* the same operation on the same operands within one equation is computed once:
		   the value is the same bits, so this never changes a result */
		for (int i = 0; i < G->ncse; i++)
			if (expr_same(G->cse[i].e, e)) return G->cse[i].slot;
		uint32_t d = new_scratch(G, e->isvec ? 3 : 1);
		emit_into(G, e, d);
		if (G->ncse < (int)(sizeof G->cse / sizeof G->cse[0])) {
			G->cse[G->ncse].e = e;
			G->cse[G->ncse++].slot = d;
		}
		return d;
	}
	}
	return 0;
}

static void add_line(Gen *G, uint32_t src)
{
	G->lines = grow(G->lines, &G->caplines, G->nlines + 1, sizeof(csf_line));
	G->lines[G->nlines++] = (csf_line){ pc(G), src };
}

static void add_target(Gen *G, uint32_t slot, Var *v, uint32_t src, const char *name, Object *o)
{
	G->targets = grow(G->targets, &G->captargets, G->ntargets + 1, sizeof(csf_target));
	G->targets[G->ntargets++] = (csf_target){ slot, v->isvec ? 3u : 1u, src, str_intern(G, name),
		                                      str_intern(G, o ? o->name : "global") };
}

/* Targets of v, computed at slot by I (a derivative: at its derivative's slot): one per member in loops. */
static void add_targets(Gen *G, Inst *I, Var *v, uint32_t slot, uint32_t src, const char *name)
{
	Shape *S = I->bind[0]->shape;
	if (!inst_loops(G->M, I) || !(sema_per_member(v) || sums_pairs(G->M, I))) {
		add_target(G, slot, v, src, name, v->obj);
		return;
	}
	for (int q = 0; q < S->n; q++) add_target(G, slot + (uint32_t)q * (v->isvec ? 3u : 1u), v, src, name, S->members[q]);
}

static void emit_block(Gen *G, Inst *I, Branch *B);

/* The steps of one branch (a plain rule: its one assignment), then zero for each variable of
 * need that none of them determines (another path does). */
static void emit_steps(Gen *G, Inst *I, Vec *steps, Vec *need)
{
	Vec set = { 0 };
	for (int i = 0; i < steps->n; i++) {
		Assign *a = steps->v[i];
		cse_reset(G);
		if (a->nest) emit_block(G, I, a->nest);
		else emit_into(G, a->e, var_operand(G, a->var, 0));
	}
	cse_reset(G);
	sema_steps_targets(steps, &set);
	for (int i = 0; i < need->n; i++) {
		Var *v = need->v[i];
		if (!vec_has(&set, v))
			emit_op(G, v->isvec ? CSF_OP_VMOV : CSF_OP_MOV, var_operand(G, v, 0), const_slot(G, (double[3]){ 0, 0, 0 }, v->isvec), 0, 0);
	}
}

/* A conditional block: its condition (comparisons located as events when the RHS needs the rule),
 * then either branch. */
static void emit_block(Gen *G, Inst *I, Branch *B)
{
	G->evinst = I->needed[CSF_SEC_RHS] ? I : NULL;
	G->evsrc = B->src;
	uint32_t c = emit(G, B->cond);
	G->evinst = NULL;
	cse_reset(G); /* what the condition computed is not there on the other path */
	uint32_t jz = pc(G);
	emit_op(G, CSF_OP_JZ, c, 0, 0, 0);
	emit_steps(G, I, &B->steps[0], &B->targets);
	uint32_t jmp = pc(G);
	emit_op(G, CSF_OP_JMP, 0, 0, 0, 0);
	G->code[jz + 2] = pc(G);
	emit_steps(G, I, &B->steps[1], &B->targets);
	G->code[jmp + 1] = pc(G);
}

static Vec assert_tab, assert_obj; /* of Inst* and Object*, in assertion index order */

/* The code of one instance, for one binding of its loops' indices. */
static void emit_body(Gen *G, Inst *I)
{
	if (I->isassert) {
		uint32_t c = emit(G, I->cond);
		I->assert_index = assert_tab.n;
		Shape *S = I->bind[0]->shape;
		for (int q = 0; q < (G->loop ? S->n : 1); q++) {
			vec_push(&assert_tab, I);
			vec_push(&assert_obj, G->loop ? S->members[q] : I->bind[0]);
		}
		emit_op(G, CSF_OP_ASSERT, c, csf_rel((uint32_t)I->assert_index, G->loop ? 1 : 0), 0, 0);
		return;
	}
	if (I->isstop) { /* its comparison as an event of the RHS, marked terminal */
		uint32_t first = G->nevents;
		G->evinst = I;
		G->evsrc = I->src;
		emit(G, I->cond);
		G->evinst = NULL;
		for (uint32_t k = first; k < G->nevents; k++) G->events[k].kind |= CSF_EVENT_TERMINAL;
		return;
	}
	if (I->isderiv) {
		Assign *a = I->then.v[0];
		emit_into(G, a->e, var_operand(G, a->var, 0) + (G->p->dstart - G->p->ystart));
		return;
	}
	if (I->top) emit_block(G, I, I->top);
	else emit_steps(G, I, &I->then, &I->targets);
}

/*
 * One instance. By shape, its code runs in a loop over the members of $0's
 * shape (level 1), and for $1 over those of $1's (level 2, skipping $0
 * itself); a $1 rule with attribute F adds its force to the sum of $0's,
 * over $1 in ascending object index, from 0.
 */
static void emit_inst(Gen *G, Inst *I)
{
	G->scratch = 0;
	cse_reset(G);
	add_line(G, (uint32_t)I->src);
	G->loop = inst_loops(G->M, I);
	int sums = sums_pairs(G->M, I);
	uint32_t top[CSF_LOOP_MAX + 1] = { 0 }, jeq = 0;
	for (int l = 1; l <= G->loop; l++) {
		if (l == 2 && sums) emit_op(G, CSF_OP_VMOV, csf_rel(acc_slot(G, I), 2), const_slot(G, (double[3]){ 0, 0, 0 }, 1), 0, 0);
		top[l] = pc(G);
		emit_op(G, CSF_OP_LOOP, (uint32_t)l, (uint32_t)I->bind[l - 1]->shape->n, 0, 0);
	}
	if (G->loop == 2 && I->bind[0]->shape == I->bind[1]->shape) {
		jeq = pc(G);
		emit_op(G, CSF_OP_JEQ, 1, 2, 0, 0);
	}
	emit_body(G, I);
	for (int i = 0; sums && i < I->targets.n; i++) {
		uint32_t acc = csf_rel(acc_slot(G, I), 2);
		emit_op(G, CSF_OP_VADD, acc, acc, var_operand(G, I->targets.v[i], 0), 0);
	}
	if (jeq) G->code[jeq + 3] = pc(G);
	for (int l = G->loop; l >= 1; l--) {
		emit_op(G, CSF_OP_NEXT, (uint32_t)l, top[l] + 4, 0, 0);
		G->code[top[l] + 3] = pc(G);
	}
	G->loop = 0;
	if (I->isassert || I->isstop) return;
	if (I->isderiv) {
		Var *v = ((Assign *)I->then.v[0])->var;
		add_targets(G, I, v, G->p->dstart + (var_slot(G, v) - G->p->ystart), (uint32_t)I->src, xprintf("%s'", v->name));
		return;
	}
	for (int i = 0; i < I->targets.n; i++) {
		Var *v = I->targets.v[i];
		uint32_t src = (uint32_t)I->src;
		for (int b = 0; b < 2; b++) {
			Vec *br = b ? &I->els : &I->then;
			for (int k = 0; k < br->n; k++)
				if (((Assign *)br->v[k])->var == v) src = (uint32_t)((Assign *)br->v[k])->src;
		}
		add_targets(G, I, v, sums ? acc_slot(G, I) : var_slot(G, v), src, v->name);
	}
}

/* ---- the Jacobian: forward-mode differentiation of the RHS section ----
 *
 * JAC repeats RHS's instructions and, before each one whose result depends
 * on the state or t ("active"), computes the tangent of that result from
 * the tangents of its operands: tangent(s) lives in slot s + P. The runtime
 * seeds the tangents of the state (one column of the identity) and of t,
 * runs JAC and reads the tangents of the derivatives: one column of the
 * exact Jacobian, the same arithmetic on both execution paths. Tangent code
 * runs before its instruction, so an operand the instruction overwrites is
 * still intact; a result it needs is recomputed into a work slot.
 */
typedef struct Jac {
	Gen *G;
	uint32_t P;          /* tangent offset */
	uint32_t W;          /* first work slot */
	uint32_t zero, one, two, ln10, zvec;
	unsigned char *act;  /* active primal slots */
	uint32_t cnt[CSF_LOOP_MAX + 1]; /* the counts of the loops around the instruction */
} Jac;

/*
 * The slots [lo, hi) an operand word of kind `kind` can name, given the
 * counts of the loops around it (cnt[level]): all of its array for a word
 * relative to a loop index. The analyses below are by array, not by element.
 */
static void operand_range(uint32_t w, int kind, const uint32_t *cnt, uint32_t *lo, uint32_t *hi)
{
	uint32_t r = csf_reg(w), n = r ? cnt[(r + 1) / 2] : 1;
	*lo = w & CSF_SLOT_MASK;
	*hi = *lo + (n ? n - 1 : 0) * (r && r % 2 == 0 ? 3u : 1u) + (kind == CSF_K_V || kind == CSF_K_DV ? 3u : 1u);
}

static int any_marked(const unsigned char *act, uint32_t w, int kind, const uint32_t *cnt)
{
	uint32_t lo, hi;
	operand_range(w, kind, cnt, &lo, &hi);
	for (uint32_t s = lo; s < hi; s++)
		if (act[s]) return 1;
	return 0;
}

static int jact(Jac *J, int kind, uint32_t s) { return any_marked(J->act, s, kind, J->cnt); }

#define JE(op, a, b, c, d) emit_op(J->G, CSF_OP_##op, a, b, c, d)
#define T(x) ((x) + J->P)
#define WK(i) (J->W + (i))

/* Emits the tangent of instruction ins (operands o[]); its inputs' activity in in[]. */
static void tangent(Jac *J, int op, const uint32_t *o, const int *in)
{
	uint32_t a = o[0], b = o[1], c = o[2], d = o[3];
	uint32_t ta = T(a);
	/* tb, tc: operand tangents, or zero where the operand is inactive */
	uint32_t tb = in[0] ? T(b) : J->zero, tc = in[1] ? T(c) : J->zero;
	uint32_t vtb = in[0] ? T(b) : J->zvec, vtc = in[1] ? T(c) : J->zvec;
	switch (op) {
	case CSF_OP_MOV: JE(MOV, ta, tb, 0, 0); break;
	case CSF_OP_VMOV: JE(VMOV, ta, vtb, 0, 0); break;
	case CSF_OP_VPACK: JE(VPACK, ta, tb, tc, in[2] ? T(d) : J->zero); break;
	case CSF_OP_ADD: JE(ADD, ta, tb, tc, 0); break;
	case CSF_OP_SUB: JE(SUB, ta, tb, tc, 0); break;
	case CSF_OP_NEG: JE(NEG, ta, tb, 0, 0); break;
	case CSF_OP_VADD: JE(VADD, ta, vtb, vtc, 0); break;
	case CSF_OP_VSUB: JE(VSUB, ta, vtb, vtc, 0); break;
	case CSF_OP_VNEG: JE(VNEG, ta, vtb, 0, 0); break;
	case CSF_OP_MUL: /* db c + b dc */
		JE(MUL, WK(0), tb, c, 0);
		JE(MUL, WK(1), b, tc, 0);
		JE(ADD, ta, WK(0), WK(1), 0);
		break;
	case CSF_OP_DIV: /* (db - z dc) / c */
		JE(DIV, WK(0), b, c, 0);
		JE(MUL, WK(1), WK(0), tc, 0);
		JE(SUB, WK(2), tb, WK(1), 0);
		JE(DIV, ta, WK(2), c, 0);
		break;
	case CSF_OP_POW: /* c b^(c-1) db + ln(b) b^c dc */
		JE(SUB, WK(0), c, J->one, 0);
		JE(POW, WK(1), b, WK(0), 0);
		JE(MUL, WK(2), WK(1), c, 0);
		JE(MUL, WK(3), WK(2), tb, 0);
		if (in[1]) {
			JE(POW, WK(4), b, c, 0);
			JE(LOG, WK(5), b, 0, 0);
			JE(MUL, WK(6), WK(5), WK(4), 0);
			JE(MUL, WK(7), WK(6), tc, 0);
			JE(ADD, ta, WK(3), WK(7), 0);
		} else {
			JE(MOV, ta, WK(3), 0, 0);
		}
		break;
	case CSF_OP_POWI: { /* n b^(n-1) db, with b^(n-1) computed as '^' computes it */
		int n = csf_imm(c);
		if (n == 0) {
			JE(MOV, ta, J->zero, 0, 0);
			break;
		}
		emit_pow_const(J->G, WK(0), b, n - 1);
		JE(MUL, WK(1), WK(0), const_slot(J->G, (double[3]){ n, 0, 0 }, 0), 0);
		JE(MUL, ta, WK(1), tb, 0);
		break;
	}
	case CSF_OP_ATAN2: /* (c db - b dc) / (b^2 + c^2) */
		JE(MUL, WK(0), b, b, 0);
		JE(MUL, WK(1), c, c, 0);
		JE(ADD, WK(2), WK(0), WK(1), 0);
		JE(MUL, WK(3), c, tb, 0);
		JE(MUL, WK(4), b, tc, 0);
		JE(SUB, WK(5), WK(3), WK(4), 0);
		JE(DIV, ta, WK(5), WK(2), 0);
		break;
	case CSF_OP_MIN: case CSF_OP_MAX: /* the tangent of the operand chosen */
		if (op == CSF_OP_MIN) JE(LE, WK(0), b, c, 0);
		else JE(GE, WK(0), b, c, 0);
		JE(MUL, WK(1), WK(0), tb, 0);
		JE(SUB, WK(2), J->one, WK(0), 0);
		JE(MUL, WK(3), WK(2), tc, 0);
		JE(ADD, ta, WK(1), WK(3), 0);
		break;
	case CSF_OP_SIN: JE(COS, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_COS: JE(SIN, WK(0), b, 0, 0); JE(NEG, WK(1), WK(0), 0, 0); JE(MUL, ta, WK(1), tb, 0); break;
	case CSF_OP_TAN: JE(COS, WK(0), b, 0, 0); JE(MUL, WK(1), WK(0), WK(0), 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_ASIN: case CSF_OP_ACOS:
		JE(MUL, WK(0), b, b, 0);
		JE(SUB, WK(1), J->one, WK(0), 0);
		JE(SQRT, WK(2), WK(1), 0, 0);
		JE(DIV, WK(3), tb, WK(2), 0);
		if (op == CSF_OP_ASIN) JE(MOV, ta, WK(3), 0, 0);
		else JE(NEG, ta, WK(3), 0, 0);
		break;
	case CSF_OP_ATAN: JE(MUL, WK(0), b, b, 0); JE(ADD, WK(1), J->one, WK(0), 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_SINH: JE(COSH, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_COSH: JE(SINH, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_TANH:
		JE(TANH, WK(0), b, 0, 0);
		JE(MUL, WK(1), WK(0), WK(0), 0);
		JE(SUB, WK(2), J->one, WK(1), 0);
		JE(MUL, ta, WK(2), tb, 0);
		break;
	case CSF_OP_EXP: JE(EXP, WK(0), b, 0, 0); JE(MUL, ta, WK(0), tb, 0); break;
	case CSF_OP_LOG: JE(DIV, ta, tb, b, 0); break;
	case CSF_OP_LOG10: JE(MUL, WK(0), b, J->ln10, 0); JE(DIV, ta, tb, WK(0), 0); break;
	case CSF_OP_SQRT: JE(SQRT, WK(0), b, 0, 0); JE(MUL, WK(1), WK(0), J->two, 0); JE(DIV, ta, tb, WK(1), 0); break;
	case CSF_OP_ABS: /* sign(b) db */
		JE(LT, WK(0), b, J->zero, 0);
		JE(MUL, WK(1), WK(0), J->two, 0);
		JE(SUB, WK(2), J->one, WK(1), 0);
		JE(MUL, ta, WK(2), tb, 0);
		break;
	case CSF_OP_VMUL: /* dv s + v ds */
		JE(VMUL, WK(0), vtb, c, 0);
		JE(VMUL, WK(3), b, tc, 0);
		JE(VADD, ta, WK(0), WK(3), 0);
		break;
	case CSF_OP_VDIV: /* (dv - z ds) / s */
		JE(VDIV, WK(0), b, c, 0);
		JE(VMUL, WK(3), WK(0), tc, 0);
		JE(VSUB, WK(6), vtb, WK(3), 0);
		JE(VDIV, ta, WK(6), c, 0);
		break;
	case CSF_OP_VDOT:
		JE(VDOT, WK(0), vtb, c, 0);
		JE(VDOT, WK(1), b, vtc, 0);
		JE(ADD, ta, WK(0), WK(1), 0);
		break;
	case CSF_OP_VCROSS:
		JE(VCROSS, WK(0), vtb, c, 0);
		JE(VCROSS, WK(3), b, vtc, 0);
		JE(VADD, ta, WK(0), WK(3), 0);
		break;
	case CSF_OP_VMAG: /* (v . dv) / |v| */
		JE(VMAG, WK(0), b, 0, 0);
		JE(VDOT, WK(1), b, vtb, 0);
		JE(DIV, ta, WK(1), WK(0), 0);
		break;
	case CSF_OP_VUNIT: /* (dv - u (u . dv)) / |v| */
		JE(VMAG, WK(0), b, 0, 0);
		JE(VDIV, WK(1), b, WK(0), 0);
		JE(VDOT, WK(4), WK(1), vtb, 0);
		JE(VMUL, WK(5), WK(1), WK(4), 0);
		JE(VSUB, WK(8), vtb, WK(5), 0);
		JE(VDIV, ta, WK(8), WK(0), 0);
		break;
	case CSF_OP_VPROJ: { /* p = k w, k = (u.w)/(w.w): dp = dk w + k dw */
		JE(VDOT, WK(0), b, c, 0);                    /* u.w */
		JE(VDOT, WK(1), c, c, 0);                    /* w.w */
		JE(DIV, WK(2), WK(0), WK(1), 0);             /* k */
		JE(VDOT, WK(3), vtb, c, 0);
		JE(VDOT, WK(4), b, vtc, 0);
		JE(ADD, WK(5), WK(3), WK(4), 0);             /* d(u.w) */
		JE(VDOT, WK(6), c, vtc, 0);
		JE(MUL, WK(7), WK(6), J->two, 0);            /* d(w.w) */
		JE(MUL, WK(8), WK(2), WK(7), 0);
		JE(SUB, WK(9), WK(5), WK(8), 0);
		JE(DIV, WK(10), WK(9), WK(1), 0);            /* dk */
		JE(VMUL, WK(11), c, WK(10), 0);
		JE(VMUL, WK(14), vtc, WK(2), 0);
		JE(VADD, ta, WK(11), WK(14), 0);
		break;
	}
	case CSF_OP_VANGLE: { /* theta = atan2(|u x w|, u.w) */
		JE(VCROSS, WK(0), b, c, 0);                  /* x = u x w */
		JE(VMAG, WK(3), WK(0), 0, 0);                /* s = |x| */
		JE(VDOT, WK(4), b, c, 0);                    /* q = u.w */
		JE(VCROSS, WK(5), vtb, c, 0);
		JE(VCROSS, WK(8), b, vtc, 0);
		JE(VADD, WK(11), WK(5), WK(8), 0);           /* dx */
		JE(VDOT, WK(14), WK(0), WK(11), 0);
		JE(DIV, WK(15), WK(14), WK(3), 0);           /* ds = x.dx / s */
		JE(VDOT, WK(16), vtb, c, 0);
		JE(VDOT, WK(17), b, vtc, 0);
		JE(ADD, WK(18), WK(16), WK(17), 0);          /* dq */
		JE(MUL, WK(19), WK(4), WK(15), 0);
		JE(MUL, WK(20), WK(3), WK(18), 0);
		JE(SUB, WK(21), WK(19), WK(20), 0);          /* q ds - s dq */
		JE(MUL, WK(22), WK(3), WK(3), 0);
		JE(MUL, WK(23), WK(4), WK(4), 0);
		JE(ADD, WK(24), WK(22), WK(23), 0);
		JE(DIV, ta, WK(21), WK(24), 0);
		break;
	}
	default: /* comparisons and logic: not differentiable, zero */
		JE(MOV, ta, J->zero, 0, 0);
		break;
	}
}
#define JAC_WORK 26

/* Is op's result a smooth function of its operands (comparisons and logic are not)? */
static int differentiable(int op)
{
	return !(op >= CSF_OP_LT && op <= CSF_OP_EVGE);
}

/*
 * Marks in act every slot whose value code computes from a marked slot, to a
 * fixed point (slots are reused). smooth: only through differentiable
 * operations. Returns 1 if a branch condition depends on a marked slot.
 */
static int depends(const uint32_t *code, uint32_t n, unsigned char *act, int smooth)
{
	int branch = 0;
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0 };
	for (int changed = 1; changed;) {
		changed = 0;
		for (uint32_t pc = 0; pc < n; pc += 1u + csf_opinfo_table[code[pc]].nops) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
			if (code[pc] == CSF_OP_JZ && any_marked(act, code[pc + 1], CSF_K_S, cnt)) branch = 1;
			if (oi->kind[0] != CSF_K_DS && oi->kind[0] != CSF_K_DV) continue;
			if (smooth && !differentiable((int)code[pc])) continue;
			int any = 0;
			for (int k = 1; k < oi->nops; k++)
				if (slot_kind(oi->kind[k])) any |= any_marked(act, code[pc + 1 + k], oi->kind[k], cnt);
			uint32_t lo, hi;
			operand_range(code[pc + 1], oi->kind[0], cnt, &lo, &hi);
			for (uint32_t d = lo; any && d < hi; d++)
				if (!act[d]) act[d] = 1, changed = 1;
		}
	}
	return branch;
}

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
	if (!I->isderiv) return NULL;
	Assign *a = I->then.v[0];
	Var *x = a->var, *v = a->e->k == R_VAR ? a->e->var : NULL;
	return v && v->state && v != x && v->isvec == x->isvec ? v : NULL;
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

static void gen_pairs(Gen *G, Model *M, csf_prog *p)
{
	p->vpair = calloc(p->ny ? p->ny : 1, sizeof *p->vpair);
	unsigned char *all = calloc(G->nmem, 1), *act = malloc(G->nmem);
	if (!p->vpair || !all || !act) exit(2);
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

/* The magnitude of v's initial value. */
static double init_mag(const Var *v) { return v->isvec ? csf_vmag3(v->init[0], v->init[1], v->init[2]) : fabs(v->init[0]); }

static void gen_jacobian(Gen *G, csf_prog *p)
{
	const uint32_t *rc = p->code[CSF_SEC_RHS];
	uint32_t rn = p->ncode[CSF_SEC_RHS];
	if (!p->ny) return;
	Jac J0 = { 0 }, *J = &J0;
	J->G = G;
	J->zero = const_slot(G, (double[3]){ 0, 0, 0 }, 0);
	J->zvec = const_slot(G, (double[3]){ 0, 0, 0 }, 1);
	J->one = const_slot(G, (double[3]){ 1, 0, 0 }, 0);
	J->two = const_slot(G, (double[3]){ 2, 0, 0 }, 0);
	J->ln10 = const_slot(G, (double[3]){ M_LN10, 0, 0 }, 0);
	uint32_t nprimal = G->nmem;
	J->act = calloc(nprimal, 1);
	if (!J->act) exit(2);
	J->act[p->tslot] = 1;
	for (uint32_t i = 0; i < p->ny; i++) J->act[p->ystart + i] = 1;
	depends(rc, rn, J->act, 1);
	J->P = nprimal;
	alloc_mem(G, nprimal, NULL); /* the tangents */
	J->W = alloc_mem(G, JAC_WORK, NULL);
	p->jtan = J->P;

	G->code = NULL;
	G->ncode = G->capcode = 0;
	G->lines = NULL;
	G->nlines = G->caplines = 0;
	uint32_t *map = calloc((size_t)rn + 1, sizeof *map); /* RHS pc -> JAC pc, for jumps */
	uint32_t *fix = NULL, nfix = 0, capfix = 0;            /* JAC word positions of jump targets */
	if (!map) exit(2);
	uint32_t li = 0;
	for (uint32_t pc = 0; pc < rn;) {
		map[pc] = G->ncode;
		while (li < p->nlines[CSF_SEC_RHS] && p->lines[CSF_SEC_RHS][li].pc <= pc) {
			if (p->lines[CSF_SEC_RHS][li].pc == pc) add_line(G, p->lines[CSF_SEC_RHS][li].src);
			li++;
		}
		int op = (int)rc[pc];
		const csf_opinfo *oi = &csf_opinfo_table[op];
		uint32_t o[4] = { 0, 0, 0, 0 };
		for (int k = 0; k < oi->nops; k++) o[k] = rc[pc + 1 + k];
		if (op == CSF_OP_LOOP) J->cnt[o[0]] = o[1];
		if ((oi->kind[0] == CSF_K_DS || oi->kind[0] == CSF_K_DV) && jact(J, oi->kind[0], o[0])) {
			int in[3] = { 0, 0, 0 };
			for (int k = 1; k < oi->nops; k++)
				in[k - 1] = differentiable(op) && slot_kind(oi->kind[k]) && jact(J, oi->kind[k], o[k]);
			tangent(J, differentiable(op) ? op : -1, o, in);
		}
		emit_words(G, op, o);
		for (int k = 0; k < oi->nops; k++)
			if (oi->kind[k] == CSF_K_J || oi->kind[k] == CSF_K_B) {
				if (nfix == capfix) {
					capfix = capfix ? 2 * capfix : 16;
					fix = realloc(fix, capfix * sizeof *fix);
					if (!fix) exit(2);
				}
				fix[nfix++] = G->ncode - (uint32_t)oi->nops + (uint32_t)k;
			}
		pc += 1u + oi->nops;
	}
	map[rn] = G->ncode;
	for (uint32_t i = 0; i < nfix; i++) G->code[fix[i]] = map[G->code[fix[i]]];
	p->code[CSF_SEC_JAC] = G->code;
	p->ncode[CSF_SEC_JAC] = G->ncode;
	p->lines[CSF_SEC_JAC] = G->lines;
	p->nlines[CSF_SEC_JAC] = G->nlines;
	free(map);
	free(fix);
	free(J->act);
}
#undef JE
#undef T
#undef WK

static void mark(Gen *G, Inst *I, int sec)
{
	if (I->needed[sec]) return;
	I->needed[sec] = 1;
	for (int i = 0; i < I->reads.n; i++) {
		Var *v = I->reads.v[i];
		if (v->det && v->det != I) mark(G, v->det, sec);
	}
	for (int i = 0; i < I->rf_reads.n; i++) {
		Object *o = I->rf_reads.v[i];
		Vec *fs = &G->Finsts[o->index];
		for (int k = 0; k < fs->n; k++) mark(G, fs->v[k], sec);
	}
}

int gen_program(Model *M, csf_prog *p)
{
	Gen G0 = { 0 }, *G = &G0;
	memset(p, 0, sizeof *p);
	G->M = M;
	G->p = p;
	assert_tab = assert_obj = (Vec){ 0 };
	G->Finsts = xalloc((size_t)(M->objects.n + 1) * sizeof(Vec));
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isF) vec_push(&G->Finsts[I->bind[0]->index], I);
	}
	/* What is needed: derivatives for RHS; watches and assertions for OUT. */
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isderiv || I->isstop) mark(G, I, CSF_SEC_RHS);
		if (I->isassert) mark(G, I, CSF_SEC_OUT);
	}
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		Var *v = sema_canon(w->var);
		if (v->det) mark(G, v->det, CSF_SEC_OUT);
	}

	/* Contacts need every body's acceleration, in OUT too (a, FN and Ff are watchable). */
	/* The contact routine runs after the last of them: last_a, an index into M->insts. */
	int last_a = -1;
	Map dets = { 0 }; /* the instances that determine a body's a, by address */
	for (int i = 0; i < M->cbodies.n && M->contacts.n; i++) {
		ContactBody *b = M->cbodies.v[i];
		Var *a = sema_canon(b->f[CSF_CF_A]);
		if (b->plane || !a || !a->det) continue;
		mark(G, a->det, CSF_SEC_OUT);
		map_put(&dets, xprintf("%p", (void *)a->det), a->det);
	}
	for (int j = 0; j < M->insts.n && M->contacts.n; j++)
		if (map_get(&dets, xprintf("%p", M->insts.v[j]))) last_a = j;

	/* Layout: t, state, derivatives. */
	p->tslot = alloc_mem(G, 1, NULL);
	p->ystart = G->nmem;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j];
			if (v->state) var_slot(G, v);
		}
	}
	p->ny = G->nmem - p->ystart;
	p->dstart = alloc_mem(G, p->ny ? p->ny : 1, NULL); /* a slot even without state: the layout is inside memory */
	p->yscale = malloc((p->ny ? p->ny : 1) * sizeof *p->yscale);
	p->yatol = calloc(p->ny ? p->ny : 1, sizeof *p->yatol);
	if (!p->yscale || !p->yatol) exit(2);
	/* the state variable of each property name that starts largest, over all objects */
	Map largest = { 0 };
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j], *w = v->state ? map_get(&largest, v->name) : NULL;
			if (v->state && (!w || init_mag(v) > init_mag(w))) map_put(&largest, v->name, v);
		}
	}
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j];
			if (!v->state) continue;
			/* one SI unit of v, in the system's units; smaller when the property starts
			   smaller in every object (so that a 1e-20 m orbit keeps the relative accuracy
			   of a 1 m one), but not because it starts near zero in this one (a normal
			   mode's node: cos(pi/2) is 6e-17) */
			double one = v->dimk == DK_KNOWN ? dims_to_system(1.0, v->dim) : 1.0;
			if (!(one > 0) || !isfinite(one)) one = 1.0; /* a dimension such as m^100 kg^100 in cgs */
			double mag = init_mag(map_get(&largest, v->name));
			if (mag > 0 && mag < one && isfinite(mag)) one = mag;
			for (int k = 0; k < (v->isvec ? 3 : 1); k++) {
				p->yscale[(uint32_t)v->slot - p->ystart + (uint32_t)k] = one;
				p->yatol[(uint32_t)v->slot - p->ystart + (uint32_t)k] = v->atol ? v->atol->c[0] : 0;
			}
		}
	}
	M->time->slot = (int)p->tslot;

	/* The contact tables: the bodies' property slots, and each rule's lists of bodies (csf.h). */
	p->ncbodies = M->contacts.n ? (uint32_t)M->cbodies.n : 0;
	p->ncrules = (uint32_t)M->contacts.n;
	p->cbodies = calloc(p->ncbodies + 1, sizeof *p->cbodies);
	p->crules = calloc(p->ncrules + 1, sizeof *p->crules);
	if (!p->cbodies || !p->crules) exit(2);
	for (uint32_t i = 0; i < p->ncbodies; i++) {
		ContactBody *b = M->cbodies.v[i];
		csf_cbody *pb = &p->cbodies[i];
		pb->plane = (uint32_t)b->plane;
		pb->object = (uint32_t)b->o->index;
		for (int f = 0; f < CSF_CF_N; f++) {
			Var *v = b->f[f];
			pb->s[f] = v ? var_slot(G, v) : p->tslot;
			/* the radius, or a plane's geometry, computed or integrated: not known from positions */
			if (v && (f == CSF_CF_R || (b->plane && (f == CSF_CF_POS || f == CSF_CF_V))) && (v->state || v->det))
				pb->varies = 1;
		}
	}
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		p->ncmembers += (uint32_t)(c->b0.n + c->b1.n);
	}
	p->cmembers = calloc(p->ncmembers + 1, sizeof *p->cmembers);
	if (!p->cmembers) exit(2);
	uint32_t nm = 0;
	for (int i = 0; i < M->contacts.n; i++) {
		Contact *c = M->contacts.v[i];
		csf_crule *pr = &p->crules[i];
		pr->src = (uint32_t)c->src;
		pr->every = (uint32_t)c->every;
		for (int k = 0; k < 2; k++) {
			Vec *L = k ? &c->b1 : &c->b0;
			*(k ? &pr->first1 : &pr->first0) = nm;
			*(k ? &pr->n1 : &pr->n0) = (uint32_t)L->n;
			for (int j = 0; j < L->n; j++) p->cmembers[nm++] = (uint32_t)((ContactBody *)L->v[j])->index;
		}
	}

	for (int sec = CSF_SEC_RHS; sec <= CSF_SEC_OUT; sec++) {
		G->code = NULL;
		G->ncode = G->capcode = 0;
		G->lines = NULL;
		G->nlines = G->caplines = 0;
		G->targets = NULL;
		G->ntargets = G->captargets = 0;
		for (int i = 0; i < M->insts.n; i++) {
			Inst *I = M->insts.v[i];
			if (!I->needed[sec]) continue;
			if (sec == CSF_SEC_RHS && I->isassert) continue;
			if (sec == CSF_SEC_OUT && I->isderiv) continue;
			emit_inst(G, I);
			if (i == last_a) {
				add_line(G, p->crules[0].src);
				emit_op(G, CSF_OP_CONTACT, 0, 0, 0, 0);
			}
		}
		p->code[sec] = G->code;
		p->ncode[sec] = G->ncode;
		p->lines[sec] = G->lines;
		p->nlines[sec] = G->nlines;
		p->targets[sec] = G->targets;
		p->ntargets[sec] = G->ntargets;
	}

	/* Columns. */
	p->ncols = (uint32_t)M->cols.n;
	p->cols = calloc(p->ncols + 1, sizeof *p->cols);
	for (int i = 0; i < M->cols.n; i++) {
		WatchCol *w = M->cols.v[i];
		const char *unit = w->var->dimk == DK_KNOWN ? dims_unit(w->var->dim) : "";
		p->cols[i].name = str_intern(G, *unit ? xprintf("%s [%s]", w->name, unit) : w->name);
		p->cols[i].slot = (w->var->kind == V_TIME ? p->tslot : var_slot(G, w->var)) +
		                  (uint32_t)(w->member * (w->var->isvec ? 3 : 1) + w->comp);
	}

	/* The globals, every one in memory so that -D can set it. */
	p->nglobals = (uint32_t)M->globals.n;
	p->globals = calloc(p->nglobals + 1, sizeof *p->globals);
	if (!p->globals) exit(2);
	for (int i = 0; i < M->globals.n; i++) {
		Var *g = M->globals.v[i];
		p->globals[i] = (csf_global){ str_intern(G, g->name), var_slot(G, g), g->isvec ? 3u : 1u, param_class(G, g) };
	}
	dims_system_base(p->ubase);

	/* The object table: every object and the properties the program keeps in memory. */
	p->nobjects = (uint32_t)M->objects.n;
	p->objects = calloc(p->nobjects + 1, sizeof *p->objects);
	if (!p->objects) exit(2);
	Vec props = { 0 };
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		p->objects[i] = str_intern(G, o->name);
		for (int j = 0; j < o->props.n; j++)
			if (((Var *)o->props.v[j])->slot >= 0) vec_push(&props, o->props.v[j]);
	}
	p->nprops = (uint32_t)props.n;
	p->props = calloc(p->nprops + 1, sizeof *p->props);
	if (!p->props) exit(2);
	for (int i = 0; i < props.n; i++) {
		Var *v = props.v[i];
		p->props[i] = (csf_prop){ (uint32_t)v->obj->index, str_intern(G, v->name), (uint32_t)v->slot, v->isvec ? 3u : 1u,
		                          param_class(G, v) };
	}
	p->npclasses = G->npclasses;
	p->pclasses = G->pclasses ? G->pclasses : calloc(1, sizeof *p->pclasses);

	/* Scratch goes last; relocate scratch operands. */
	uint32_t base = alloc_mem(G, G->max_scratch, NULL);
	for (int sec = 0; sec < CSF_NSEC; sec++)
		for (uint32_t i = 0; i < p->ncode[sec];) {
			const csf_opinfo *oi = &csf_opinfo_table[p->code[sec][i]];
			for (int k = 0; k < oi->nops; k++) {
				uint32_t *w = &p->code[sec][i + 1 + k];
				if (slot_kind(oi->kind[k]) && (*w & SCRATCH)) *w = base + (*w & ~SCRATCH);
			}
			i += 1u + oi->nops;
		}

	if (!p->ncrules) gen_pairs(G, M, p); /* the contact routine's forces depend on v */
	else if (!(p->vpair = calloc(p->ny ? p->ny : 1, sizeof *p->vpair))) exit(2);
	gen_jacobian(G, p);

	/* Source tables. */
	p->nfiles = (uint32_t)sources.n;
	p->files = calloc(p->nfiles + 1, sizeof *p->files);
	for (int i = 0; i < sources.n; i++) p->files[i] = str_intern(G, ((Source *)sources.v[i])->path);
	p->nsrcs = (uint32_t)M->srcs.n;
	p->srcs = calloc(p->nsrcs + 1, sizeof *p->srcs);
	for (int i = 0; i < M->srcs.n; i++) {
		SrcEntry *e = M->srcs.v[i];
		p->srcs[i] = (csf_src){ (uint32_t)e->loc.file, (uint32_t)e->loc.line, str_intern(G, e->text) };
	}
	p->nasserts = (uint32_t)assert_tab.n;
	p->asserts = calloc(p->nasserts + 1, sizeof *p->asserts);
	for (int i = 0; i < assert_tab.n; i++) {
		Inst *I = assert_tab.v[i];
		p->asserts[i] = (csf_assert){ (uint32_t)I->src, str_intern(G, ((Object *)assert_obj.v[i])->name) };
	}
	str_intern(G, "");
	p->strs = G->strs;
	p->nstrs = G->nstrs;
	p->mem0 = G->mem;
	p->nmem = G->nmem;
	p->till = M->till;
	p->by = M->by;
	p->nevents = G->nevents;
	p->events = G->events ? G->events : calloc(1, sizeof *p->events);
	return 0;
}
