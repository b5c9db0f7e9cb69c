/*
 * group.c - rules solved together (DECISIONS 10): rules that determine
 * several unknowns only together, and are linear in them, are one linear
 * system.
 *
 * Rules are resolved in order (spec 2.4.1); a plain rule that reads two
 * temporaries or more that no rule has determined (its unknowns) cannot be
 * resolved alone, and waits instead of being an error at once. Its unknowns
 * are those of the point it was reached. Whenever a rule begins to wait, or
 * the unknowns of waiting rules are determined, the smallest set of k
 * waiting rules (2 <= k <= SOLVE_MAX) that together have exactly k unknowns
 * left is looked for among the rules connected to it through shared
 * unknowns; the set is solved at once (solve_system: each of its instances
 * gets one unknown, the value of the whole system), at the point of the rule
 * that completed it, so what it reads is whatever is determined there. A
 * waiting rule left with one unknown by such a system is then resolved
 * alone, and one left with none is overdetermined. Rule order still
 * counts: a waiting rule one of whose unknowns a later rule determines alone
 * (a rule that does not wait) is an error as before, since it read a
 * temporary that no earlier rule determined.
 *
 * After the last rule (group_finish), the rules still waiting are reported,
 * by the sets they make through shared unknowns: a set with at least as
 * many equations as unknowns, more than SOLVE_MAX, by one error that says
 * so; a set of two rules or more with fewer equations than unknowns by one
 * error that counts them; any other rule as the error it would have been
 * had it not waited (a misspelt name, with a suggestion, is the likelier
 * mistake than a missing equation, so a set with one is reported so), once
 * per statement. The unknowns of rules that fail are marked determined (by
 * an instance that is never compiled), so the rules that read them do not
 * repeat the error.
 *
 * Each rule of a system computes the value of one unknown (one whose
 * coefficient in it is not zero), from the whole system. The rules of a
 * system read each other's unknowns, as far as the sections are concerned
 * (liveness.c): a system is computed whole wherever one of its values is
 * needed, and none of its rules is "left out" while the others are used,
 * since none can be left out of the system.
 *
 * The search is small: the members of a set of at most three unknowns, each
 * with two unknowns or more, all share one with the rule it starts from;
 * the candidates are the waiting rules reached through shared unknowns, at
 * most MAX_CANDS of them.
 */
#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* The most waiting rules one search looks at. */
#define MAX_CANDS 64

typedef struct Wait {
	Inst *I;
	Eqn *q;
	RExpr *lhs, *rhs;
	Vec reads, rf;   /* what its equation reads: Var*, and Object* whose RF */
	Vec unknowns;    /* of Var*: its unknowns, when it was reached */
	Loc at;          /* the error it is if it is never solved */
	const char *msg;
	int suggests;    /* msg suggests a name for a misspelt one */
	int index;       /* in sema.waiting */
	int done;        /* solved, or reported */
} Wait;

static char *key_of(const void *p) { return xprintf("%p", p); }

/* Was v determined by a rule that waited (alone or in a system), or marked so after an error? */
static int group_var(const Var *v) { return map_get(&sema.group_vars, key_of(v)) != NULL; }

static void mark_group_var(Var *v) { map_put(&sema.group_vars, key_of(v), v); }

/* A rule one of whose unknowns a later rule determined alone: it read a temporary no earlier rule determined. */
static int dead(const Wait *w)
{
	for (int i = 0; i < w->unknowns.n; i++) {
		Var *v = w->unknowns.v[i];
		if (determined(v) && !group_var(v)) return 1;
	}
	return 0;
}

static int live(const Wait *w) { return !w->done && !dead(w); }

/* Its unknowns not yet determined, into out (cleared). */
static void left(const Wait *w, Vec *out)
{
	out->n = 0;
	for (int i = 0; i < w->unknowns.n; i++)
		if (!determined(w->unknowns.v[i])) vec_push(out, w->unknowns.v[i]);
}

/* "lines 12, 13" for rules S[0..n) (in order); when a statement is more than one of them, each says for
   which object ("line 12 for a, line 12 for b"); a file other than the first rule's is named ("x.csf:3"). */
static const char *rules_at(Wait **S, int n)
{
	int twice = 0;
	for (int i = 0; i < n; i++)
		for (int j = 0; j < i; j++) twice |= S[j]->I->st == S[i]->I->st;
	char *s = xstrdup(twice ? "" : n > 1 ? "lines " : "line ");
	for (int i = 0; i < n; i++) {
		Stmt *st = S[i]->I->st;
		const char *file = st->loc.file != S[0]->I->st->loc.file ? xprintf("%s:", ((Source *)sources.v[st->loc.file])->path) : "";
		s = xprintf("%s%s%s%s%d%s%s", s, i ? ", " : "", twice ? "line " : "", file, st->loc.line, twice ? " for " : "",
		            twice ? S[i]->I->bind[0]->name : "");
	}
	return s;
}

/* "a1, a2": the names of x[0..k), with their objects when they are not all one object's. */
static const char *names_of(Var *const *x, int k)
{
	int one = 1;
	for (int j = 1; j < k; j++) one &= x[j]->obj == x[0]->obj;
	char *s = xstrdup("");
	for (int j = 0; j < k; j++) s = xprintf("%s%s%s", s, j ? ", " : "", one ? x[j]->name : var_label(x[j]));
	return s;
}

/* Adds to reads and rf what e reads. */
static void collect(RExpr *e, Vec *reads, Vec *rf)
{
	if (e->k == R_VAR && e->var->kind != V_TIME) add_unique(reads, e->var);
	if (e->k == R_RF) add_unique(rf, e->obj);
	for (int i = 0; i < e->n; i++) collect(e->a[i], reads, rf);
}

/* The waiting rules that have one of vars[0..n) among their unknowns, into work. */
static void touch(Var *const *vars, int n, Vec *work)
{
	for (int j = 0; j < n; j++) {
		Vec *ws = map_get(&sema.waits_of, key_of(vars[j]));
		for (int i = 0; ws && i < ws->n; i++) add_unique(work, ws->v[i]);
	}
}

/* The rules of S[0..n) fail: none is reported again, nor any other waiting rule with one of their unknowns
   x[0..k) (a consequence), and those count as determined, so that no later rule is an error for them. */
static void fail(Wait **S, int n, Var *const *x, int k)
{
	Vec also = { 0 };
	touch(x, k, &also);
	for (int i = 0; i < also.n; i++) ((Wait *)also.v[i])->done = 1;
	for (int i = 0; i < n; i++) S[i]->done = 1;
	for (int j = 0; j < k; j++) {
		if (!x[j]->det) x[j]->det = S[0]->I;
		mark_group_var(x[j]);
	}
}

/* The unknowns left to S[0..n), in the order they were made (first use), into x; returns how many (at most max + 1). */
static int union_left(Wait **S, int n, Var **x, int max)
{
	int k = 0;
	Vec l = { 0 };
	for (int i = 0; i < n; i++) {
		left(S[i], &l);
		for (int j = 0; j < l.n; j++) {
			int seen = 0;
			for (int q = 0; q < k; q++) seen |= x[q] == l.v[j];
			if (!seen) {
				if (k > max) return k;
				x[k++] = l.v[j];
			}
		}
	}
	for (int a = 1; a < k; a++) /* insertion sort by order */
		for (int b = a; b > 0 && x[b]->order < x[b - 1]->order; b--) {
			Var *t = x[b];
			x[b] = x[b - 1];
			x[b - 1] = t;
		}
	return k;
}

/* Chooses size - 1 rules of cands[from..n) into S[1..), S[0] chosen: 1 when S[0..size) has exactly size
 * unknowns left. */
static int choose(Wait **S, int m, int size, Wait **cands, int from, int n)
{
	Var *x[SOLVE_MAX + 1];
	if (union_left(S, m, x, SOLVE_MAX) > size) return 0;
	if (m == size) return union_left(S, m, x, SOLVE_MAX) == size;
	for (int i = from; i < n; i++) {
		S[m] = cands[i];
		if (choose(S, m + 1, size, cands, i + 1, n)) return 1;
	}
	return 0;
}

/* The smallest set of waiting rules with w that have as many unknowns left as rules, into S (w first, then in
 * the order reached); returns its size, 0 if none within SOLVE_MAX. */
static int find_set(Wait *w, Wait **S)
{
	Wait *cands[MAX_CANDS];
	int n = 0;
	Vec l = { 0 }, seen = { 0 };
	vec_push(&seen, w);
	/* breadth first through shared unknowns; a rule with more than SOLVE_MAX unknowns left is in no set */
	for (int h = 0; h < seen.n && n < MAX_CANDS; h++) {
		left(seen.v[h], &l);
		for (int j = 0; j < l.n; j++) {
			Vec *ws = map_get(&sema.waits_of, key_of(l.v[j]));
			for (int i = 0; ws && i < ws->n && n < MAX_CANDS; i++) {
				Wait *c = ws->v[i];
				if (vec_has(&seen, c) || !live(c)) continue;
				vec_push(&seen, c);
				Vec lc = { 0 };
				left(c, &lc);
				if (lc.n <= SOLVE_MAX) cands[n++] = c;
			}
		}
	}
	for (int a = 1; a < n; a++) /* in the order reached */
		for (int b = a; b > 0 && cands[b]->index < cands[b - 1]->index; b--) {
			Wait *t = cands[b];
			cands[b] = cands[b - 1];
			cands[b - 1] = t;
		}
	S[0] = w;
	for (int size = 2; size <= SOLVE_MAX; size++)
		if (choose(S, 1, size, cands, 0, n)) return size;
	return 0;
}

/* Is instance I compiled as a loop over the members of a shape (by shape: gen's inst_loops)? */
static int in_loop(const Inst *I)
{
	if (sema.shaped && I->iloop) return 1;
	if (!sema.shaped || I->st->has_for || I->st->once) return 0;
	for (int b = 0; b < I->nbind; b++)
		if (I->bind[b]->shape->n > 1) return 1;
	return 0;
}

/* w, left with one unknown x by the rules it waited with, is resolved alone; work gets the rules x concerns. */
static void solve_one(Wait *w, Var *x, Vec *work)
{
	w->done = 1;
	RExpr *sol = solve(w->lhs, w->rhs, x, w->q->loc, w->q->text);
	if (sol && sol->isvec != x->isvec) {
		error_at(w->q->loc, "\"%s\" would make %s a %s, but it is a %s", w->q->text, var_label(x),
		         sol->isvec ? "vector" : "scalar", x->isvec ? "vector" : "scalar");
		sol = NULL;
	}
	if (!sol) {
		fail(&w, 1, &x, 1);
		return;
	}
	resolve_assign(w->I, x, sol, w->lhs, w->rhs, w->q, w->I->src, &w->I->then, &w->reads, &w->rf);
	mark_group_var(x);
	vec_push(sema.cur_insts, w->I);
	touch(&x, 1, work);
}

/* Rules S[0..k) (w first), with k unknowns left, are solved together; work gets the rules their unknowns concern. */
static void solve_set(Wait **S, int k, Vec *work)
{
	for (int a = 1; a < k; a++) /* in the order reached */
		for (int b = a; b > 0 && S[b]->index < S[b - 1]->index; b--) {
			Wait *t = S[b];
			S[b] = S[b - 1];
			S[b - 1] = t;
		}
	Var *x[SOLVE_MAX + 1];
	union_left(S, k, x, SOLVE_MAX);
	RExpr *lhs[SOLVE_MAX], *rhs[SOLVE_MAX];
	char *text[SOLVE_MAX];
	for (int i = 0; i < k; i++) lhs[i] = S[i]->lhs, rhs[i] = S[i]->rhs, text[i] = S[i]->q->text;
	const char *at = rules_at(S, k), *names = names_of(x, k);
	int nz[SOLVE_MAX * SOLVE_MAX];
	RExpr **sol = solve_system(lhs, rhs, text, x, k, S[0]->q->loc,
	                           xprintf("the rules at %s determine %s only together", at, names), nz);
	if (!sol) {
		fail(S, k, x, k);
		return;
	}
	/* each rule gets an unknown whose coefficient in it is not zero, the first such permutation: there is one,
	   as the determinant (a sum over permutations of such products) is not zero */
	int p[SOLVE_MAX], used[SOLVE_MAX] = { 0 }, i = 0;
	p[0] = -1;
	while (i < k) {
		if (p[i] >= 0) used[p[i]] = 0;
		do p[i]++;
		while (p[i] < k && (used[p[i]] || !nz[i * k + p[i]]));
		if (p[i] == k) {
			i--;
			continue;
		}
		used[p[i]] = 1;
		if (++i < k) p[i] = -1;
	}
	int src = add_src(S[0]->q->loc, xprintf("rules at %s solved together for %s (not finite where their linear system "
	                                        "is singular)", at, names));
	for (i = 0; i < k; i++) {
		Wait *w = S[i];
		Vec reads = { 0 }, rf = { 0 };
		collect(sol[p[i]], &reads, &rf);
		for (int j = 0; j < k; j++) add_unique(&reads, x[j]); /* one system: needed where any of it is */
		resolve_assign(w->I, x[p[i]], sol[p[i]], w->lhs, w->rhs, w->q, src, &w->I->then, &reads, &rf);
		w->I->why = xprintf("%s; rules at %s solved together for %s (a linear system)", w->I->why, at, names);
		w->done = 1;
		vec_push(sema.cur_insts, w->I);
		/* by shape, an instance computes a value from the others' equations, which name their objects by
		   place: in a loop over a shape, it must have the same objects in the same places */
		Inst *I0 = S[0]->I;
		int same = w->I->nbind == I0->nbind && w->I->st->has_for == I0->st->has_for;
		for (int b = 0; same && b < I0->nbind; b++) same = w->I->bind[b] == I0->bind[b];
		if (!same && (in_loop(w->I) || in_loop(I0))) unshape("rules solved together for different objects");
	}
	for (int j = 0; j < k; j++) mark_group_var(x[j]);
	touch(x, k, work);
}

/* Resolves what the waiting rules in work (and those it leads to) can: each, in the order reached, alone if one
   unknown is left, overdetermined if none, else in the smallest set that has as many unknowns as rules. */
static void settle(Vec *work)
{
	while (work->n) {
		int m = 0;
		for (int i = 1; i < work->n; i++)
			if (((Wait *)work->v[i])->index < ((Wait *)work->v[m])->index) m = i;
		Wait *w = work->v[m];
		work->v[m] = work->v[--work->n];
		if (!live(w)) continue;
		Vec l = { 0 };
		left(w, &l);
		if (l.n == 0) {
			w->done = 1;
			error_at(w->q->loc, "rule \"%s\" is overdetermined%s%s: every variable in it is already determined", w->q->text,
			         w->I->nbind > 0 ? " for object " : "", w->I->nbind > 0 ? w->I->bind[0]->name : "");
			for (int i = 0; i < w->unknowns.n; i++) explain_det(w->unknowns.v[i]);
			continue;
		}
		if (l.n == 1) {
			solve_one(w, l.v[0], work);
			continue;
		}
		Wait *S[SOLVE_MAX];
		int k = find_set(w, S);
		if (k) solve_set(S, k, work);
	}
}

void group_wait(Inst *I, Eqn *q, RExpr *lhs, RExpr *rhs, Vec *reads, Vec *rf, Vec *unknowns, Loc at, const char *msg,
                int suggests)
{
	Wait *w = xalloc(sizeof *w);
	w->I = I;
	w->q = q;
	w->lhs = lhs;
	w->rhs = rhs;
	w->reads = *reads;
	w->rf = *rf;
	w->unknowns = *unknowns;
	w->at = at;
	w->msg = msg;
	w->suggests = suggests;
	w->index = sema.waiting.n;
	vec_push(&sema.waiting, w);
	for (int j = 0; j < unknowns->n; j++) {
		char *k = key_of(unknowns->v[j]);
		Vec *ws = map_get(&sema.waits_of, k);
		if (!ws) {
			ws = xalloc(sizeof *ws);
			map_put(&sema.waits_of, k, ws);
		}
		vec_push(ws, w);
	}
	Vec work = { 0 };
	vec_push(&work, w);
	settle(&work);
}

/* The live waiting rules that share unknowns left with w (through others), in the order reached, into comp;
   their unknowns left into vars. */
static void component(Wait *w, Vec *comp, Vec *vars)
{
	vec_push(comp, w);
	Vec l = { 0 };
	for (int h = 0; h < comp->n; h++) {
		left(comp->v[h], &l);
		for (int j = 0; j < l.n; j++) {
			if (vec_has(vars, l.v[j])) continue;
			vec_push(vars, l.v[j]);
			Vec *ws = map_get(&sema.waits_of, key_of(l.v[j]));
			for (int i = 0; ws && i < ws->n; i++)
				if (live(ws->v[i]) && !vec_has(comp, ws->v[i])) vec_push(comp, ws->v[i]);
		}
	}
	for (int a = 1; a < comp->n; a++)
		for (int b = a; b > 0 && ((Wait *)comp->v[b])->index < ((Wait *)comp->v[b - 1])->index; b--) {
			void *t = comp->v[b];
			comp->v[b] = comp->v[b - 1];
			comp->v[b - 1] = t;
		}
}

void group_finish(void)
{
	Vec reported = { 0 }; /* of Stmt*: one error a statement */
	for (int i = 0; i < sema.waiting.n; i++) {
		Wait *w = sema.waiting.v[i];
		if (!live(w)) continue;
		Vec comp = { 0 }, vars = { 0 };
		component(w, &comp, &vars);
		int suggests = 0;
		for (int c = 0; c < comp.n; c++) suggests |= ((Wait *)comp.v[c])->suggests;
		Var **x = (Var **)vars.v;
		for (int a = 1; a < vars.n; a++)
			for (int b = a; b > 0 && x[b]->order < x[b - 1]->order; b--) {
				Var *t = x[b];
				x[b] = x[b - 1];
				x[b - 1] = t;
			}
		const char *at = rules_at((Wait **)comp.v, comp.n), *names = names_of(x, vars.n);
		if (comp.n >= vars.n && vars.n > SOLVE_MAX) /* as many equations as unknowns, or more, but too many */
			error_at(w->q->loc, "the rules at %s determine %s only together: %d unknowns, more than the %d that rules "
			         "solved together may have (give some of them a rule of their own)", at, names, vars.n, SOLVE_MAX);
		else if (comp.n >= 2 && comp.n < vars.n && !suggests) /* else a misspelt name is the likelier mistake */
			error_at(w->q->loc, "the rules at %s cannot determine %s: %d equations for %d unknowns", at, names, comp.n, vars.n);
		else
			continue;
		for (int c = 0; c < comp.n; c++) add_unique(&reported, ((Wait *)comp.v[c])->I->st);
		fail((Wait **)comp.v, comp.n, x, vars.n);
	}
	for (int i = 0; i < sema.waiting.n; i++) {
		Wait *w = sema.waiting.v[i];
		if (w->done) continue;
		w->done = 1;
		if (vec_has(&reported, w->I->st)) continue;
		vec_push(&reported, w->I->st);
		error_at(w->at, "%s", w->msg);
	}
}
