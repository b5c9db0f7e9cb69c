/*
 * explain.c - csfc --explain: what each rule solves for, for which objects,
 * which rules were left out, and what each property is.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "explain.h"
#include "csf_int.h"

/*
 * For --explain: which bodies the contact rules of statement s apply to.
 * Returns how many lines it wrote.
 */
static int explain_contacts(Model *Mo, Stmt *s, FILE *f)
{
	static const char *const pair_of[] = { "two mass points", "a mass point and a plane", "a mass point and an anchor" };
	static const char *const kind_of[] = { "", "plane", "anchor" };
	int lines = 0;
	for (int k = 0; k < Mo->contacts.n; k++) {
		Contact *r = Mo->contacts.v[k];
		if (r->st != s) continue;
		lines++;
		if (!r->every) {
			fprintf(f, "  for %s with %s: the contact routine (%s); computed in rhs and out\n",
			        ((ContactBody *)r->b0.v[0])->o->name, ((ContactBody *)r->b1.v[0])->o->name,
			        pair_of[((ContactBody *)r->b1.v[0])->kind]);
			continue;
		}
		/* the mass points ($0, and $1 that are not planes or anchors), the planes and the anchors, each once */
		char *seen = xalloc((size_t)Mo->cbodies.n + 1);
		Vec names = { 0 };
		int npts = 0, nk[3] = { 0, r->nplanes, r->nanchors };
		for (int q = 0; q < 2; q++)
			for (int j = 0; j < (q ? r->b1.n : r->b0.n); j++) {
				ContactBody *b = (q ? r->b1.v : r->b0.v)[j];
				if (b->kind || seen[b->index]) continue;
				seen[b->index] = 1, npts++;
				vec_push(&names, b->o->name);
			}
		for (int kind = CSF_CB_PLANE; kind <= CSF_CB_ANCHOR; kind++)
			for (int j = 0; j < r->b1.n; j++)
				if (((ContactBody *)r->b1.v[j])->kind == kind) vec_push(&names, ((ContactBody *)r->b1.v[j])->o->name);
		fprintf(f, "  for %d mass point%s", npts, npts == 1 ? "" : "s");
		for (int kind = CSF_CB_PLANE; kind <= CSF_CB_ANCHOR; kind++)
			if (nk[kind]) fprintf(f, " and %d %s%s", nk[kind], kind_of[kind], nk[kind] == 1 ? "" : "s");
		if (names.n <= 6)
			for (int j = 0; j < names.n; j++) fprintf(f, "%s%s", j ? ", " : " (", (char *)names.v[j]);
		/* which pairs: of two mass points, a mass point and a plane, a mass point and an anchor */
		int has[3] = { npts > 1 && r->nplanes + r->nanchors < r->b1.n, r->nplanes > 0, r->nanchors > 0 }, nh = 0;
		fprintf(f, "%s: the contact routine (", names.n <= 6 ? ")" : "");
		for (int kind = 0; kind < 3; kind++)
			if (has[kind]) fprintf(f, "%s%s", nh++ ? ", " : "", pair_of[kind]);
		fprintf(f, "), on the pairs it finds near at run time%s; computed in rhs and out\n",
		        has[0] || has[2] ? " (two points never touch)" : "");
	}
	return lines;
}

/* For --explain: the constraints of statement s (rule C), one line each. Returns how many lines it wrote. */
static int explain_constraints(Model *Mo, Stmt *s, FILE *f)
{
	static const char *const kind_of[] = { "holds LHS = RHS", "holds LHS <= RHS (slack or taut: events)",
		                               "holds LHS >= RHS (slack or taut: events)" };
	int lines = 0;
	for (int k = 0; k < Mo->cons.n; k++) {
		Constraint *K = Mo->cons.v[k];
		if (K->st != s) continue;
		lines++;
		fprintf(f, "  for %s", K->bind[0]->name);
		for (int b = 1; b < K->nbind; b++) fprintf(f, "%s%s", b == 1 ? " with " : ", ", K->bind[b]->name);
		fprintf(f, ": a constraint, %s by forces along its gradient on ", kind_of[K->kind]);
		for (int b = 0; b < K->bodies.n; b++)
			fprintf(f, "%s%s", b ? (b + 1 == K->bodies.n ? " and " : ", ") : "", ((Object *)K->bodies.v[b])->name);
		fprintf(f, " (their FC), solved with every constraint and contact; computed in rhs and out\n");
	}
	return lines;
}

/* Writes conditional block B, indented by depth levels: each branch's line with its equations and
 * the variables it leaves zero, then its nested blocks, deeper; an elif at the depth of its if. */
static void explain_block(FILE *f, Branch *B, int depth)
{
	for (int b = 0; b < 2; b++) {
		Vec *st = &B->steps[b], set = { 0 };
		Assign *one = st->n == 1 ? st->v[0] : NULL;
		if (b && one && one->nest && one->nest->ast->elif) {
			explain_block(f, one->nest, depth);
			continue;
		}
		if (!b) fprintf(f, "%*sline %d: %s", 2 * depth, "", B->ast->loc.line, B->ast->text);
		else if (B->ast->els) fprintf(f, "%*sline %d: else:", 2 * depth, "", B->ast->else_loc.line);
		else fprintf(f, "%*sotherwise:", 2 * depth, "");
		const char *sep = " ";
		for (int i = 0; i < st->n; i++) {
			Assign *a = st->v[i];
			if (!a->nest) fprintf(f, "%s%s", sep, a->text), sep = "; ";
		}
		sema_steps_targets(st, &set);
		for (int i = 0; i < B->targets.n; i++)
			if (!vec_has(&set, B->targets.v[i])) fprintf(f, "%s%s = 0 (not stated)", sep, ((Var *)B->targets.v[i])->name), sep = "; ";
		fputc('\n', f);
		for (int i = 0; i < st->n; i++)
			if (((Assign *)st->v[i])->nest) explain_block(f, ((Assign *)st->v[i])->nest, depth + 1);
	}
}

/* What --explain says of object o after its name: left out, or each property and what it is. */
static const char *object_line(Object *o)
{
	if (o->dropped) return " left out: nothing watched, asserted or stopped on depends on it (csfc --keep-all keeps it)";
	char *line = "";
	for (int j = 0; j < obj_props(o)->n; j++) {
		Var *v = obj_props(o)->v[j], *r = sema_canon(v);
		line = xprintf("%s%s %s (%s)", line, j ? "," : "", v->name,
		               r->state ? (var_integrated(r) ? "state" : "state, left out: nothing needs it")
		               : r->det   ? xprintf("computed, line %d", r->det->st->loc.line)
		               : var_more_of(r)->latch ? xprintf("latched, when block line %d", var_more_of(r)->latch->st->loc.line)
		                          : "constant");
	}
	return line;
}

/* Is b the member of an object array after a (NAME[k] and NAME[k + 1])? */
static int next_member(const Object *a, const Object *b)
{
	const char *pa = strrchr(a->name, '['), *pb = strrchr(b->name, '[');
	if (!pa || !pb || pa - a->name != pb - b->name || strncmp(a->name, b->name, (size_t)(pa - a->name)) != 0) return 0;
	return strtol(pa + 1, NULL, 10) + 1 == strtol(pb + 1, NULL, 10);
}

/* What a `when` block does at its events: the variables it assigns, each a state variable or latched. */
static void explain_when(FILE *f, const Inst *I)
{
	fprintf(f, ": at each instant its condition becomes true (its comparisons are events, located in time; not at "
	           "t = 0), computes every new value from the values just before, then sets");
	for (int k = 0; k < I->then.n; k++) {
		const Assign *a = I->then.v[k];
		const Var *v = a->var;
		fprintf(f, "%s %s%s%s (%s)", k ? "," : "", v->obj ? v->obj->name : "", v->obj ? "." : "", v->name,
		        v->state ? "a state variable: integration restarts from its new value"
		                 : "latched: it keeps its value between events");
	}
}

void explain_model(Model *Mo, FILE *f)
{
	for (int i = 0; i < Mo->stmts.n; i++) {
		Stmt *s = Mo->stmts.v[i];
		Source *src = sources.v[s->loc.file];
		fprintf(f, "%s:%d: %s%s\n", src->path, s->loc.line,
		        s->kind == S_ASSERT ? "assert " : s->kind == S_STOP ? "stop when " : "", s->text);
		if (s->kind == S_WHEN)
			for (Eqn *q = s->eqns; q; q = q->next) fprintf(f, "  %s\n", q->text);
		int n = 0;
		Inst *cond = NULL; /* an instance of a conditional rule: its branches are every instance's */
		for (int k = 0; k < Mo->insts.n; k++) {
			Inst *I = Mo->insts.v[k];
			if (I->st != s) continue;
			n++;
			if (I->top && !cond) cond = I;
			Shape *S = Mo->shaped && !s->has_for && !s->once ? I->bind[0]->shape : NULL;
			if (s->once) fprintf(f, "  once (it reads no property of an object of its own)");
			else fprintf(f, "  for %s", I->bind[0]->name);
			if (S && S->n > 1) fprintf(f, " and the %d other object%s of its shape", S->n - 1, S->n > 2 ? "s" : "");
			for (int b = 1; b < I->nbind; b++) {
				Object *o = I->bind[b];
				if (S && o->shape == S) fprintf(f, ", each with every other one");
				else if (S && o->shape->n > 1)
					fprintf(f, ", each with %s and the %d other object%s of its shape", o->name, o->shape->n - 1,
					        o->shape->n > 2 ? "s" : "");
				else fprintf(f, "%s%s", b == 1 ? " with " : ", ", o->name);
			}
			if (Mo->shaped && I->iloop)
				fprintf(f, ", and so on: one loop over the %ld bindings, %s = %ld .. %ld", I->iloop, I->ivar, I->idx,
				        I->idx + I->iloop - 1);
			if (I->isassert) fprintf(f, ": checked at every output step");
			else if (I->isstop) fprintf(f, ": ends the run at the instant it becomes true (a terminal event)");
			else if (I->iswhen) explain_when(f, I);
			else fprintf(f, ": %s%s", I->isderiv ? "" : "solves for ", I->why ? I->why : "?");
			if (!I->isassert && !I->isstop && !I->iswhen && !I->needed[0] && !I->needed[1])
				fprintf(f, "; left out: nothing needs it");
			else if (!I->isassert && !I->isstop && !I->iswhen)
				fprintf(f, "; computed in %s", I->needed[0] && I->needed[1] ? "rhs and out" : I->needed[0] ? "rhs" : "out");
			fputc('\n', f);
		}
		if (cond) {
			fprintf(f, "  branches%s:\n", cond->needed[CSF_SEC_RHS] ? " (their comparisons <, <=, >, >= are events, located in time)" : "");
			explain_block(f, cond->top, 2);
		}
		n += explain_contacts(Mo, s, f);
		n += explain_constraints(Mo, s, f);
		if (!n && Mo->ndropped) fprintf(f, "  left out: it applies only to objects left out\n");
		else if (!n) fprintf(f, "  applies to no %s\n", s->call ? "pair that can touch" : "object");
	}
	if (!Mo->shaped && *Mo->unshaped_why) fprintf(f, "rules compiled once per object, not per shape: %s\n", Mo->unshaped_why);
	/* each object's line; the consecutive members of an object array with the same line, as one */
	for (int i = 0; i < Mo->objects.n;) {
		const char *what = object_line(Mo->objects.v[i]);
		int j = i + 1;
		while (j < Mo->objects.n && next_member(Mo->objects.v[j - 1], Mo->objects.v[j]) &&
		       !strcmp(object_line(Mo->objects.v[j]), what))
			j++;
		Object *o = Mo->objects.v[i];
		if (j - i > 1) fprintf(f, "objects %s .. %s (%d members):%s\n", o->name, ((Object *)Mo->objects.v[j - 1])->name, j - i, what);
		else fprintf(f, "object %s:%s\n", o->name, what);
		i = j;
	}
}
