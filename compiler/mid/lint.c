/*
 * lint.c - warnings: models that compile but do not say what their author
 * meant (a misspelt property, a force that nothing sums, a rule whose result
 * nothing reads, a rule that overrides a value the user gave).
 *
 * They look at the compiled model (after gen_program: which rules each
 * section needs is known then), once, so that the resolver's silent first
 * pass (sema_run) cannot lose or repeat them. Only statements of the user's
 * own files are warned about, never the standard library's. Warnings never
 * change the exit status, unless -Werror makes them errors (util.c).
 */
#include <string.h>

#include "csfc.h"
#include "lint.h"
#include "sema.h"

/* Is the statement or definition at l in one of the user's files (not the standard library)? */
static int users(Loc l)
{
	if (l.file < 0 || l.file >= sources.n) return 0;
	const char *path = ((Source *)sources.v[l.file])->path, *lib = opts.stdlib;
	return !(lib && *lib && !strncmp(path, lib, strlen(lib)));
}

/* Once per place: several objects, or a shape's members, share a statement or a kind's line. */
static int first_at(Vec *seen, Loc l)
{
	for (int i = 0; i < seen->n; i++) {
		Loc *s = seen->v[i];
		if (s->file == l.file && s->line == l.line && s->col == l.col) return 0;
	}
	Loc *c = xalloc(sizeof *c);
	*c = l;
	vec_push(seen, c);
	return 1;
}

static int is_force(const Var *v)
{
	return v->dimk == DK_KNOWN && v->dim[0] == 1 && v->dim[1] == 1 && v->dim[2] == -2;
}

void lint_model(Model *M)
{
	Vec read = { 0 }, seen = { 0 };
	int rf_read = 0;
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		for (int k = 0; k < I->reads.n; k++) vec_push(&read, sema_canon(I->reads.v[k]));
		rf_read |= I->rf_reads.n > 0;
	}
	for (int i = 0; i < M->cols.n; i++) vec_push(&read, sema_canon(((WatchCol *)M->cols.v[i])->var));
	for (int i = 0; i < M->cons.n; i++) { /* a constraint reads what it names, and its objects' cr, m, a, v */
		Constraint *K = M->cons.v[i];
		static const char *const props[] = { "cr", "m", "a", "v", "FC" };
		for (int k = 0; k < K->reads.n; k++) vec_push(&read, sema_canon(K->reads.v[k]));
		for (int b = 0; b < K->nbind; b++)
			for (size_t k = 0; k < sizeof props / sizeof props[0]; k++)
				if (prop_of_obj(K->bind[b], props[k])) vec_push(&read, sema_canon(prop_of_obj(K->bind[b], props[k])));
	}
	for (int i = 0; i < M->cbodies.n; i++) {
		ContactBody *b = M->cbodies.v[i];
		for (int f = 0; f < CSF_CF_N; f++)
			if (b->f[f]) vec_push(&read, sema_canon(b->f[f]));
	}

	/* a property the user set that nothing reads: a misspelling, most often; a radius, where
	   nothing collides: the contacts of mechanics/rules not used (said once) */
	int contact_hint = M->cbodies.n > 0;
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		const char **c = NULL; /* the names a misspelt one may stand for: made once for the object */
		const Vec *P = obj_props(o);
		for (int j = 0; j < P->n && !obj_shares(o); j++) {
			Var *p = P->v[j];
			if (p->from_kind || p->state || vec_has(&read, sema_canon(p)) || !users(p->loc)) continue;
			if (!o->dropped && !first_at(&seen, p->loc)) continue;
			if (!c) c = xalloc(((size_t)P->n + 1) * sizeof *c);
			int nc = 0;
			for (int k = 0; k < P->n; k++) {
				Var *q = P->v[k];
				if (q != p && (q->from_kind || vec_has(&read, sema_canon(q)) || q->state)) c[nc++] = q->name;
			}
			const char *s = csf_suggest_name(p->name, c, nc);
			/* of an object left out, nothing is read: only a misspelling is worth a word */
			if (o->dropped && (!s || !first_at(&seen, p->loc))) continue;
			if (!s && !contact_hint && !strcmp(p->name, "radius")) {
				warn_at(p->loc, "property 'radius' of object '%s' is never read: no contacts are made, so bodies "
				                "pass through each other and through planes; hint: using mechanics/rules",
				        o->name);
				contact_hint = 1;
			} else if (s)
				warn_at(p->loc, "property '%s' of object '%s' is never read; did you mean '%s'?", p->name, o->name, s);
			else warn_at(p->loc, "property '%s' of object '%s' is never read", p->name, o->name);
		}
	}

	/* forces that no rule sums */
	if (!rf_read)
		for (int i = 0; i < M->insts.n; i++) {
			Inst *I = M->insts.v[i];
			if (!I->isF || !users(I->st->loc)) continue;
			warn_at(I->st->loc, "rules with attribute F are summed by no rule ('RF' is never read), so no force "
			                    "moves anything; hint: using mechanics/rules");
			break;
		}

	/* the statements some instance of which is needed: a rule without 'for' applies to every object
	   that has what it reads, and is needed if it is for one of them (a force on the ball, not the floor) */
	Vec used = { 0 };
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->needed[0] || I->needed[1]) first_at(&used, I->st->loc);
	}
	for (int i = 0; i < M->insts.n; i++) {
		Inst *I = M->insts.v[i];
		if (I->isassert || I->isstop || I->iswhen || I->isderiv || !users(I->st->loc)) continue;
		/* a rule whose result nothing reads (what --explain calls left out) */
		if (!I->needed[0] && !I->needed[1] && I->targets.n && !(I->isF && !rf_read) && first_at(&used, I->st->loc) &&
		    first_at(&seen, I->st->loc)) {
			Var *v = I->targets.v[0];
			int temps = 1;
			for (int k = 0; k < I->targets.n; k++) temps &= ((Var *)I->targets.v[k])->kind == V_TEMP;
			if (temps)
				warn_at(I->st->loc, "rule determines '%s', which nothing reads%s", v->name,
				        !I->st->attr && is_force(v) ? " (a force? write 'rule F: ...' to add it to RF)" : "");
		}
		/* a rule that overrides a value the user gave */
		for (int k = 0; k < I->targets.n; k++) {
			Var *v = sema_canon(I->targets.v[k]);
			if ((v->kind != V_PROP && v->kind != V_GLOBAL) || v->from_kind || v->state || !users(v->loc)) continue;
			/* a global given 0 is declared for the rule to determine (a sum: `global E = 0 J`) */
			if (v->kind == V_GLOBAL && v->init[0] == 0 && v->init[1] == 0 && v->init[2] == 0) continue;
			/* once per statement and variable: the statement's line, the variable's place as the column */
			Loc key = { I->st->loc.file, -I->st->loc.line, v->loc.line * 1000 + v->loc.col };
			if (!first_at(&seen, key)) continue;
			warn_at(I->st->loc, "this rule solves for %s '%s', which has the initial value given at line %d: the "
			                    "rule overrides it", v->kind == V_GLOBAL ? "the global" : "property", v->name, v->loc.line);
		}
	}
}
