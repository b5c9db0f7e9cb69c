/* The parser and the layout layer: statements, blocks, precedence, units. */
#include <string.h>

#include "suites.h"
#include "parse.h"

static Stmt *parse_string(const char *text, char **diag)
{
	char *buf = NULL;
	size_t len = 0;
	diag_out = open_memstream(&buf, &len);
	diag_errors = 0;
	Stmt *s = parse_file(src_add("p.csf", text));
	fclose(diag_out);
	diag_out = NULL;
	if (diag) *diag = buf;
	else free(buf);
	return s;
}

START_TEST(test_statements)
{
	Stmt *s = parse_string("global k = 2\nobject b: m = 1 kg\nobject b: vector v = (1, 2, 3) m/s\n"
	                       "object c: b\nvector W\nrule F for b, c: W = g.mul(m)\nassert m > 0\n"
	                       "inc t till 2 s by 1 ms watch pos, b.v\n",
	                       NULL);
	ck_assert_int_eq(diag_errors, 0);
	StmtKind k[] = { S_GLOBAL, S_PROP, S_PROP, S_OBJKIND, S_VECDECL, S_RULE, S_ASSERT, S_START };
	for (int i = 0; i < 8; i++, s = s->next) {
		ck_assert_ptr_nonnull(s);
		ck_assert_msg(s->kind == k[i], "statement %d", i);
		if (i == 2) ck_assert(s->isvec && s->value->kind == E_LIT && s->value->lit && s->value->lit->v[2] == 3);
		if (i == 5) {
			ck_assert_str_eq(s->attr, "F");
			ck_assert_int_eq(s->fors.n, 2);
			ck_assert_str_eq(s->text, "rule F for b, c: W = g.mul(m)");
		}
		if (i == 6) ck_assert_str_eq(s->text, "m > 0");
		if (i == 7) {
			ck_assert_int_eq(s->watch.n, 2);
			ck_assert_str_eq(((WatchItem *)s->watch.v[1])->obj, "b");
		}
	}
}
END_TEST

START_TEST(test_blocks)
{
	Stmt *s = parse_string("def k:\n    m = 1\n    vector p = (0, 0, 0)\n"
	                       "object b: k\nrule: if m > 0:\n    x = 1\n    y = 2\nelse:\n    x = 3\n"
	                       "inc t\n",
	                       NULL);
	ck_assert_int_eq(diag_errors, 0);
	ck_assert_int_eq(s->kind, S_DEF);
	ck_assert_ptr_nonnull(s->body);
	ck_assert_ptr_nonnull(s->body->next);
	ck_assert(s->body->next->isvec);
	Stmt *r = s->next->next;
	ck_assert_int_eq(r->kind, S_RULE);
	If *f = r->eqns->nest;
	ck_assert_ptr_nonnull(f);
	ck_assert_ptr_nonnull(f->cond);
	ck_assert_ptr_nonnull(f->then->next);
	ck_assert_ptr_nonnull(f->els);
	ck_assert_ptr_null(f->els->next);
	ck_assert_int_eq(f->else_loc.line, 8);
}
END_TEST

/* elif chains, nested blocks with their own elif and else, and what each block holds */
START_TEST(test_elif_and_nesting)
{
	char *d;
	Stmt *s = parse_string("rule: if t < 2:\n    u = 1\nelif t < 5:\n    if x > 1:\n        u = 2\n"
	                       "    elif x > 0:\n        u = 3\n    else:\n        u = 4\n    w = 5\nelse:\n    u = 0\n"
	                       "inc t\n",
	                       &d);
	ck_assert_msg(diag_errors == 0, "%s", d);
	free(d);
	If *f = s->eqns->nest;
	ck_assert_ptr_nonnull(f);
	ck_assert_str_eq(f->text, "if t < 2:");
	ck_assert(!f->elif && !f->then->nest && !f->then->next);
	/* the elif: the whole else part, a block of its own */
	ck_assert_ptr_nonnull(f->els);
	ck_assert_ptr_null(f->els->next);
	If *e = f->els->nest;
	ck_assert_ptr_nonnull(e);
	ck_assert(e->elif);
	ck_assert_int_eq(e->loc.line, 3);
	ck_assert_int_eq(e->else_loc.line, 11);
	ck_assert_str_eq(e->els->text, "u = 0");
	/* its branch: a nested block (with an elif and an else of its own), then an equation */
	If *n = e->then->nest;
	ck_assert_ptr_nonnull(n);
	ck_assert_int_eq(n->loc.col, 5);
	ck_assert_str_eq(n->then->text, "u = 2");
	ck_assert(n->els->nest && n->els->nest->elif);
	ck_assert_str_eq(n->els->nest->els->text, "u = 4");
	ck_assert_str_eq(e->then->next->text, "w = 5");
	ck_assert_ptr_null(e->then->next->next);
}
END_TEST

/* A misplaced elif or else is one error: its block and the branches after it go with it. */
START_TEST(test_misplaced_branches)
{
	static const struct { const char *src, *want; } cases[] = {
		{ "rule: u = 1\nelif t < 5:\n    u = 3\nelse:\n    u = 0\ninc t\n", "p.csf:2:1: error: 'elif' without" },
		{ "rule: if t < 2:\n    u = 1\n    elif t < 5:\n        u = 3\n    else:\n        u = 0\ninc t\n",
		  "p.csf:3:5: error: 'elif' without" },
		{ "rule: if t < 2:\n    u = 1\n        elif t < 5:\n            u = 3\ninc t\n",
		  "p.csf:3:9: error: unexpected indentation" },
		{ "rule: if t < 2:\n    u = 1\nelse:\n    u = 2\nelse:\n    u = 3\ninc t\n", "p.csf:5:1: error: 'else' without" },
		{ "rule: if t < :\n    u = 1\nelif t < 5:\n    u = 3\nelse:\n    u = 0\ninc t\n", "p.csf:1:14: error: syntax error" },
		{ "def k:\n    m = 1\n    if m > 0:\n        q = 2\n    else:\n        q = 3\nobject b: k\ninc t\n",
		  "p.csf:3:5: error: an 'if' block belongs to a conditional rule" },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		char *d;
		parse_string(cases[i].src, &d);
		ck_assert_msg(diag_errors == 1 && strstr(d, cases[i].want), "case %zu: %s", i, d);
		free(d);
	}
}
END_TEST

START_TEST(test_precedence)
{
	Stmt *s = parse_string("rule: y = -x^2 + 3 * z / w\ninc t\n", NULL);
	ck_assert_int_eq(diag_errors, 0);
	Expr *e = s->eqns->rhs; /* (-(x^2)) + ((3*z)/w) */
	ck_assert(e->kind == E_BIN && e->op == '+');
	ck_assert(e->a->kind == E_NEG && e->a->a->kind == E_BIN && e->a->a->op == '^');
	ck_assert(e->b->kind == E_BIN && e->b->op == '/' && e->b->a->op == '*');
}
END_TEST

START_TEST(test_derivative_and_dollar)
{
	Stmt *s = parse_string("rule: v' = a$1.mul(2)\ninc t\n", NULL);
	ck_assert_int_eq(diag_errors, 0);
	ck_assert(s->eqns->deriv);
	ck_assert_str_eq(s->eqns->lhs->name, "v");
	Expr *e = s->eqns->rhs;
	ck_assert(e->kind == E_METHOD && e->a->kind == E_DOLLAR && e->a->n == 1);
}
END_TEST

START_TEST(test_unit_only_after_literal)
{
	/* `2 m` is two metres; `2 * m` is twice the variable m */
	Stmt *s = parse_string("rule: y = 2 m\nrule: z = 2 * m\ninc t\n", NULL);
	ck_assert_int_eq(diag_errors, 0);
	ck_assert(s->eqns->rhs->kind == E_LIT && !s->eqns->rhs->lit && s->eqns->rhs->num == 2);
	ck_assert(s->next->eqns->rhs->kind == E_BIN);
	ck_assert(s->next->eqns->rhs->b->kind == E_NAME);
}
END_TEST

START_TEST(test_literal_vectors)
{
	/* numbers, negated or not, in a vector with a unit: one E_LIT, each component's place kept; a vector
	   with anything else in it: E_UNIT over E_VEC */
	Stmt *s = parse_string("object b: vector v = (-1.5, 2,  - 3) m/s\nobject b: vector w = (1, k, 3) m\n"
	                       "object b: vector u = (1, 2, 3)\ninc t\n", NULL);
	ck_assert_int_eq(diag_errors, 0);
	Expr *e = s->value;
	ck_assert(e->kind == E_LIT && e->lit && e->nargs == 0);
	ck_assert_int_eq(e->loc.col, 38); /* the unit's, as E_UNIT's */
	const Lit *L = e->lit;
	ck_assert(L->v[0] == 1.5 && L->v[1] == 2 && L->v[2] == 3);
	ck_assert(L->neg[0] && !L->neg[1] && L->neg[2]);
	ck_assert_int_eq(L->vec_at.col, 22);
	ck_assert_int_eq(L->neg_at[0].col, 23);
	ck_assert_int_eq(L->at[0].col, 24);
	ck_assert_int_eq(L->at[1].col, 29);
	ck_assert_int_eq(L->neg_at[2].col, 33);
	ck_assert_int_eq(L->at[2].col, 35);
	e = s->next->value;
	ck_assert(e->kind == E_UNIT && e->a->kind == E_VEC && e->a->nargs == 3 && e->a->args[1]->kind == E_NAME);
	ck_assert(s->next->next->value->kind == E_VEC);
}
END_TEST

START_TEST(test_recovery)
{
	char *d;
	parse_string("object b: x = 1 +\nobject c: y = )\nobject d: z = 1\nrule: = 2\ninc t\n", &d);
	ck_assert_int_eq(diag_errors, 3);
	ck_assert_msg(strstr(d, "p.csf:1:18: error:") && strstr(d, "p.csf:2:15: error:") && strstr(d, "p.csf:4:7: error:"), "%s", d);
	free(d);
}
END_TEST

Suite *parse_suite(void)
{
	Suite *s = suite_create("parse");
	TCase *tc = tcase_create("grammar");
	tcase_add_test(tc, test_statements);
	tcase_add_test(tc, test_blocks);
	tcase_add_test(tc, test_elif_and_nesting);
	tcase_add_test(tc, test_misplaced_branches);
	tcase_add_test(tc, test_precedence);
	tcase_add_test(tc, test_derivative_and_dollar);
	tcase_add_test(tc, test_unit_only_after_literal);
	tcase_add_test(tc, test_literal_vectors);
	tcase_add_test(tc, test_recovery);
	suite_add_tcase(s, tc);
	return s;
}
