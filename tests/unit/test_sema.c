/*
 * Resolution and solving (spec 2.4, DECISIONS 5): which variable each rule
 * solves for, the solved values (run through the VM), tuples, RF, pruning.
 */
#include <math.h>
#include <string.h>

#include "suites.h"

static const struct { const char *src; const char *col; double want[3]; int vec; } cases[] = {
	/* linear solving for a temporary: x = (y - 3) / 2 */
	{ "object b: y = 7\nrule: 2*x + 3 = y\ninc t till 1 by 1 watch x\n", "b.x", { 2 }, 0 },
	/* the target on the right, several occurrences: x = (9 - 1)/(3 + 1) */
	{ "object b: y = 9\nrule: 1 + x = y - 3*x\ninc t till 1 by 1 watch x\n", "b.x", { 2 }, 0 },
	/* a temporary outranks properties */
	{ "object b: p = 2\nrule: w = p * 3\ninc t till 1 by 1 watch w\n", "b.w", { 6 }, 0 },
	/* between properties, the one defined last is solved for (q = p - 1) */
	{ "object b: p = 1\nobject b: q = 5\nrule: p = q + 1\ninc t till 1 by 1 watch q\n", "b.q", { 0 }, 0 },
	/* vector solving: f = a.mul(m) with a defined last: a = f / m */
	{ "object b: vector f = (2, 4, 6)\nobject b: m = 2\nobject b: vector a = (0, 0, 0)\nrule: f = a.mul(m)\n"
	  "inc t till 1 by 1 watch a\n", "b.a.y", { 2 }, 0 },
	/* conditional, the if branch */
	{ "object b: x = 3\nrule: if x > 2:\n    y = 1\n    z = 5\nelse:\n    y = 2\ninc t till 1 by 1 watch y, z\n", "b.z", { 5 }, 0 },
	/* conditional, the else branch: z is zero where not stated */
	{ "object b: x = 1\nrule: if x > 2:\n    y = 1\n    z = 5\nelse:\n    y = 2\ninc t till 1 by 1 watch y, z\n", "b.y", { 2 }, 0 },
	{ "object b: x = 1\nrule: if x > 2:\n    y = 1\n    z = 5\nelse:\n    y = 2\ninc t till 1 by 1 watch y, z\n", "b.z", { 0 }, 0 },
	/* elif chains: the first condition that holds chooses */
	{ "object b: x = 7\nrule: if x > 5:\n    y = 1\nelif x > 2:\n    y = 2\nelse:\n    y = 3\ninc t till 1 by 1 watch y\n", "b.y", { 1 }, 0 },
	{ "object b: x = 3\nrule: if x > 5:\n    y = 1\nelif x > 2:\n    y = 2\nelse:\n    y = 3\ninc t till 1 by 1 watch y\n", "b.y", { 2 }, 0 },
	{ "object b: x = 1\nrule: if x > 5:\n    y = 1\nelif x > 2:\n    y = 2\nelse:\n    y = 3\ninc t till 1 by 1 watch y\n", "b.y", { 3 }, 0 },
	/* an elif without else: zero when no condition holds */
	{ "object b: x = 1\nrule: if x > 5:\n    y = 1\nelif x > 2:\n    y = 2\ninc t till 1 by 1 watch y\n", "b.y", { 0 }, 0 },
	/* nested blocks: every path defines y, z and w, zero where it does not state them */
#define NEST(x) "object b: x = " #x "\nrule: if x > 2:\n    if x > 5:\n        y = 1\n    else:\n        y = 2\n        z = 4\n" \
	        "    w = 6\nelse:\n    y = 3\ninc t till 1 by 1 watch y, z, w\n"
	{ NEST(7), "b.y", { 1 }, 0 }, { NEST(7), "b.z", { 0 }, 0 }, { NEST(7), "b.w", { 6 }, 0 },
	{ NEST(3), "b.y", { 2 }, 0 }, { NEST(3), "b.z", { 4 }, 0 }, { NEST(3), "b.w", { 6 }, 0 },
	{ NEST(1), "b.y", { 3 }, 0 }, { NEST(1), "b.z", { 0 }, 0 }, { NEST(1), "b.w", { 0 }, 0 },
#undef NEST
	/* a nested condition reads what its branch determined before it */
	{ "object b: x = 3\nrule: if x > 2:\n    k = x * 2\n    if k > 5:\n        y = 1\n    else:\n        y = 2\n"
	  "inc t till 1 by 1 watch y\n", "b.y", { 1 }, 0 },
	/* a rule reading RF is resolved after the F rules, wherever it stands */
	{ "object b: m = 2\nrule: RF = a.mul(m)\nrule F: W = (0, 0, -4)\nrule F: D = (1, 0, 0)\ninc t till 1 by 1 watch a\n", "b.a.z", { -2 }, 0 },
	{ "object b: m = 2\nrule: RF = a.mul(m)\nrule F: W = (0, 0, -4)\nrule F: D = (1, 0, 0)\ninc t till 1 by 1 watch a\n", "b.a.x", { 0.5 }, 0 },
	/* $1 with k = 1: every other object; RF sums them: for b0, q1 + q2 = 5 */
	{ "object b0: q = 1\nobject b1: q = 2\nobject b2: q = 3\nrule F: P = (q$1, 0, 0)\nrule: RF = a.mul(1)\n"
	  "inc t till 1 by 1 watch b0.a, b2.a\n", "b0.a.x", { 5 }, 0 },
	{ "object b0: q = 1\nobject b1: q = 2\nobject b2: q = 3\nrule F: P = (q$1, 0, 0)\nrule: RF = a.mul(1)\n"
	  "inc t till 1 by 1 watch b0.a, b2.a\n", "b2.a.x", { 3 }, 0 },
	/* $1 $2 with k = 2: combinations of the others: for b0, 2*3 + 2*4 + 3*4 = 26 */
	{ "object b0: q = 1\nobject b1: q = 2\nobject b2: q = 3\nobject b3: q = 4\nrule F: P = (q$1 * q$2, 0, 0)\n"
	  "rule: RF = a.mul(1)\ninc t till 1 by 1 watch b0.a\n", "b0.a.x", { 26 }, 0 },
	/* `for` binds named objects */
	{ "object s: k = 10\nobject p: x = 3\nrule for p, s: y = k$1 * x\ninc t till 1 by 1 watch p.y\n", "p.y", { 30 }, 0 },
	/* a global override and a component */
	{ "global g = (0, -9.81, 0) m/s^2\nobject b: m = 2\nrule: w = g.y * m\ninc t till 1 by 1 watch w\n", "b.w", { -19.62 }, 0 },
	/* methods */
	{ "object b: vector u = (3, 4, 0)\nrule: n = u.mag\ninc t till 1 by 1 watch n\n", "b.n", { 5 }, 0 },
	{ "object b: vector u = (1, 0, 0)\nobject b: vector w = (0, 1, 0)\nrule: c3 = u.cross(w)\ninc t till 1 by 1 watch c3\n", "b.c3.z", { 1 }, 0 },
	{ "object b: vector u = (2, 2, 0)\nobject b: vector w = (1, 0, 0)\nrule: pr = u.proj(w)\ninc t till 1 by 1 watch pr\n", "b.pr.x", { 2 }, 0 },
	/* local coordinates in initial values: sph(r, theta, phi) */
	{ "object b: vector p = sph(2, 90 deg, 0)\ninc t till 1 by 1 watch p\n", "b.p.x", { 2 }, 0 },
	{ "object b: vector p = cyl(1, 0, 5) m\ninc t till 1 by 1 watch p\n", "b.p.z", { 5 }, 0 },
	/* kinds and overrides */
	{ "def k:\n    m = 1\n    s = 2\nobject b: k\nobject b: m = 4\nrule: y = m * s\ninc t till 1 by 1 watch y\n", "b.y", { 8 }, 0 },
};

START_TEST(test_resolve_and_solve)
{
	csf_prog p;
	char *d;
	int errs = compile_string(cases[_i].src, &p, &d);
	ck_assert_msg(errs == 0, "case %d: %s", _i, d);
	free(d);
	int s = col_slot(&p, cases[_i].col);
	ck_assert_msg(s >= 0, "case %d: no column %s", _i, cases[_i].col);
	double *m = run_out(&p);
	ck_assert_msg(fabs(m[s] - cases[_i].want[0]) <= 1e-15 * (1 + fabs(cases[_i].want[0])), "case %d: %s = %.17g, want %.17g",
	              _i, cases[_i].col, m[s], cases[_i].want[0]);
	free(m);
	csf_prog_free(&p);
}
END_TEST

START_TEST(test_prunes_unneeded_rules)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 1\nrule: y = x * 2\nrule: z = x * 3\ninc t till 1 by 1 watch x, z\n", &p, NULL), 0);
	/* only z's rule is compiled: one MUL in OUT, nothing in RHS */
	ck_assert_uint_eq(p.ncode[CSF_SEC_RHS], 0);
	ck_assert_uint_eq(p.ncode[CSF_SEC_OUT], 4);
	ck_assert_uint_eq(p.code[CSF_SEC_OUT][0], CSF_OP_MUL);
	csf_prog_free(&p);
}
END_TEST

START_TEST(test_state_variables)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 1\nobject b: v = 0\nrule: x' = v\nrule: v' = -x\ninc t till 1 by 1 watch x\n", &p, NULL), 0);
	ck_assert_uint_eq(p.ny, 2);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	vm_run(&p, CSF_SEC_RHS, m);
	ck_assert(m[p.dstart] == 0 && m[p.dstart + 1] == -1); /* x' = v = 0, v' = -x = -1 */
	free(m);
	csf_prog_free(&p);
}
END_TEST

START_TEST(test_errors_still_reported_when_unneeded)
{
	char *d;
	csf_prog p;
	/* nothing needs y, but the overdetermined rule is still an error */
	int errs = compile_string("object b: x = 1\nrule: y = 2\nrule: y = 3\ninc t till 1 by 1 watch x\n", &p, &d);
	ck_assert_int_eq(errs, 1);
	ck_assert_msg(strstr(d, "overdetermined") != NULL, "%s", d);
	free(d);
}
END_TEST

/* Every comparison of every block, nested or chained, is an event that names its own line. */
START_TEST(test_block_conditions_are_events)
{
	csf_prog p;
	char *d;
	int errs = compile_string("object b: x = 0\nrule: x' = u\nrule: if t < 2:\n    u = 1\nelif t < 5:\n"
	                          "    if x > 3:\n        u = 2\n    else:\n        u = 3\nelse:\n    u = 0\n"
	                          "inc t till 8 by 1 watch x\n",
	                          &p, &d);
	ck_assert_msg(errs == 0, "%s", d);
	free(d);
	ck_assert_uint_eq(p.nevents, 3);
	static const uint32_t lines[] = { 3, 5, 6 }; /* if, elif, the nested if */
	for (uint32_t i = 0; i < 3; i++)
		ck_assert_msg(p.srcs[p.events[i].src].line == lines[i], "event %u names line %u", i, p.srcs[p.events[i].src].line);
	csf_prog_free(&p);
}
END_TEST

/* The unknown name of two is the one the equation does not define, at its own column. */
START_TEST(test_unknown_name)
{
	static const struct { const char *src, *want; } errs[] = {
		/* another object's temporary */
		{ "object a: x = 1\nobject b: y = 2\nrule for b: r2 = y * 2\nrule for a: S2r = r2 * 3\ninc t till 1 by 1 watch x\n",
		  "t.csf:4:19: error: unknown name 'r2' in rule \"S2r = r2 * 3\" for object a; did you mean 'b.r2'?" },
		/* a misspelt property */
		{ "object a: mass = 1\nrule: w2 = 2 * mas\ninc t till 1 by 1 watch mass\n",
		  "t.csf:2:16: error: unknown name 'mas' in rule \"w2 = 2 * mas\" for object a; did you mean 'mass'?" },
		/* nothing close: no suggestion */
		{ "object a: x = 1\nrule: w2 = 2 * zork\ninc t till 1 by 1 watch x\n",
		  "t.csf:2:16: error: rule \"w2 = 2 * zork\" is unresolvable for object a: it solves for w2 but also reads zork" },
	};
	for (size_t i = 0; i < sizeof errs / sizeof errs[0]; i++) {
		csf_prog p;
		char *d;
		int n = compile_string(errs[i].src, &p, &d);
		ck_assert_msg(n == 1 && strstr(d, errs[i].want) != NULL, "case %zu: %s", i, d);
		free(d);
	}
}
END_TEST

Suite *sema_suite(void)
{
	Suite *s = suite_create("sema");
	TCase *tc = tcase_create("resolve");
	tcase_add_loop_test(tc, test_resolve_and_solve, 0, sizeof cases / sizeof cases[0]);
	tcase_add_test(tc, test_prunes_unneeded_rules);
	tcase_add_test(tc, test_state_variables);
	tcase_add_test(tc, test_errors_still_reported_when_unneeded);
	tcase_add_test(tc, test_block_conditions_are_events);
	tcase_add_test(tc, test_unknown_name);
	suite_add_tcase(s, tc);
	return s;
}
