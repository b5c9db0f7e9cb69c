/* Every instruction of the VM against its exact result. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "suites.h"

/* Operands: slot 0..2 destination, 3..5 first input, 6..8 second, 9 third. */
static const struct { int op; double in[7]; double out[3]; } cases[] = {
	{ CSF_OP_MOV, { 2.5 }, { 2.5 } },
	{ CSF_OP_VMOV, { 1, 2, 3 }, { 1, 2, 3 } },
	{ CSF_OP_ADD, { 1.5, 0, 0, 2.25 }, { 3.75 } },
	{ CSF_OP_SUB, { 1.5, 0, 0, 2.25 }, { -0.75 } },
	{ CSF_OP_MUL, { 1.5, 0, 0, 2.25 }, { 3.375 } },
	{ CSF_OP_DIV, { 3, 0, 0, 4 }, { 0.75 } },
	{ CSF_OP_POW, { 2, 0, 0, 10 }, { 1024 } },
	{ CSF_OP_POWI, { 1.5 }, { 11.390625 } }, /* the immediate is 6 */
	{ CSF_OP_NEG, { 2 }, { -2 } },
	{ CSF_OP_ATAN2, { 1, 0, 0, 1 }, { M_PI / 4 } },
	{ CSF_OP_MIN, { 1, 0, 0, -1 }, { -1 } },
	{ CSF_OP_MAX, { 1, 0, 0, -1 }, { 1 } },
	{ CSF_OP_SIN, { M_PI / 2 }, { 1 } },
	{ CSF_OP_COS, { 0 }, { 1 } },
	{ CSF_OP_TAN, { 0 }, { 0 } },
	{ CSF_OP_ASIN, { 1 }, { M_PI / 2 } },
	{ CSF_OP_ACOS, { 1 }, { 0 } },
	{ CSF_OP_ATAN, { 1 }, { M_PI / 4 } },
	{ CSF_OP_SINH, { 0 }, { 0 } },
	{ CSF_OP_COSH, { 0 }, { 1 } },
	{ CSF_OP_TANH, { 0 }, { 0 } },
	{ CSF_OP_EXP, { 0 }, { 1 } },
	{ CSF_OP_LOG, { 1 }, { 0 } },
	{ CSF_OP_LOG10, { 1000 }, { 3 } },
	{ CSF_OP_SQRT, { 2.25 }, { 1.5 } },
	{ CSF_OP_ABS, { -3 }, { 3 } },
	{ CSF_OP_VADD, { 1, 2, 3, 10, 20, 30 }, { 11, 22, 33 } },
	{ CSF_OP_VSUB, { 1, 2, 3, 10, 20, 30 }, { -9, -18, -27 } },
	{ CSF_OP_VNEG, { 1, -2, 3 }, { -1, 2, -3 } },
	{ CSF_OP_VMUL, { 1, 2, 3, 2 }, { 2, 4, 6 } },
	{ CSF_OP_VDIV, { 1, 2, 3, 2 }, { 0.5, 1, 1.5 } },
	{ CSF_OP_VDOT, { 1, 2, 3, 4, 5, 6 }, { 32 } },
	{ CSF_OP_VCROSS, { 1, 0, 0, 0, 1, 0 }, { 0, 0, 1 } },
	{ CSF_OP_VCROSS, { 1, 2, 3, 4, 5, 6 }, { -3, 6, -3 } },
	{ CSF_OP_VMAG, { 3, 4, 12 }, { 13 } },
	{ CSF_OP_VANGLE, { 1, 0, 0, 0, 0, 5 }, { M_PI / 2 } },
	{ CSF_OP_VANGLE, { 1, 1, 0, 2, 2, 0 }, { 0 } },
	{ CSF_OP_VUNIT, { 0, 3, 4 }, { 0, 0.6, 0.8 } },
	{ CSF_OP_VPROJ, { 2, 3, 0, 0, 5, 0 }, { 0, 3, 0 } },
	{ CSF_OP_LT, { 1, 0, 0, 2 }, { 1 } },
	{ CSF_OP_LE, { 2, 0, 0, 2 }, { 1 } },
	{ CSF_OP_GT, { 1, 0, 0, 2 }, { 0 } },
	{ CSF_OP_GE, { 1, 0, 0, 2 }, { 0 } },
	{ CSF_OP_EQ, { 2, 0, 0, 2 }, { 1 } },
	{ CSF_OP_NE, { 2, 0, 0, 2 }, { 0 } },
	{ CSF_OP_AND, { 1, 0, 0, 0 }, { 0 } },
	{ CSF_OP_OR, { 1, 0, 0, 0 }, { 1 } },
	{ CSF_OP_NOT, { 0 }, { 1 } },
};

START_TEST(test_instruction)
{
	double m[12] = { 0 };
	memcpy(m + 3, cases[_i].in, sizeof cases[_i].in);
	m[9] = cases[_i].in[6];
	uint32_t code[5] = { (uint32_t)cases[_i].op, 0, 3, 6, 9 };
	int op = cases[_i].op;
	csf_prog p = bare_prog(code, 1u + csf_opinfo_table[op].nops, m, 12, 1);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s: %s", csf_opinfo_table[op].name, err);
	ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, m), -1);
	int vec = csf_opinfo_table[op].kind[0] == CSF_K_DV;
	for (int k = 0; k < (vec ? 3 : 1); k++)
		ck_assert_msg(fabs(m[k] - cases[_i].out[k]) <= 1e-15, "%s: result %d is %.17g, expected %.17g",
		              csf_opinfo_table[op].name, k, m[k], cases[_i].out[k]);
}
END_TEST

START_TEST(test_vpack)
{
	double m[12] = { 0, 0, 0, 7, 0, 0, 8, 0, 0, 9 };
	uint32_t code[] = { CSF_OP_VPACK, 0, 3, 6, 9 };
	csf_prog p = bare_prog(code, 5, m, 12, 1);
	vm_run(&p, CSF_SEC_OUT, m);
	ck_assert(m[0] == 7 && m[1] == 8 && m[2] == 9);
}
END_TEST

START_TEST(test_overlapping_vectors)
{
	/* V[0] := V[0] x V[1]: the destination overlaps an operand */
	double m[6] = { 1, 2, 3, 4, 5, 6 };
	uint32_t code[] = { CSF_OP_VCROSS, 0, 0, 3 };
	csf_prog p = bare_prog(code, 4, m, 6, 1);
	vm_run(&p, CSF_SEC_OUT, m);
	ck_assert(m[0] == -3 && m[1] == 6 && m[2] == -3);
}
END_TEST

START_TEST(test_control_flow)
{
	/* if R[1] == 0 skip the MOV; then assert R[2] */
	double m[4] = { 0, 0, 1, 5 };
	uint32_t code[] = { CSF_OP_JZ, 1, 6, CSF_OP_MOV, 0, 3, CSF_OP_ASSERT, 2, 0 };
	csf_prog p = bare_prog(code, 9, m, 4, 1);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, m), -1);
	ck_assert(m[0] == 0);
	m[1] = 1;
	m[2] = 0;
	ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, m), 0); /* the assertion fails */
	ck_assert(m[0] == 5);
}
END_TEST

/* x^k for k = 0..8, written out in the order DECISIONS 8 gives: from the left. */
static double product(double x, int k)
{
	switch (k) {
	case 0: return 1;
	case 1: return x;
	case 2: return x * x;
	case 3: return (x * x) * x;
	case 4: return ((x * x) * x) * x;
	case 5: return (((x * x) * x) * x) * x;
	case 6: return ((((x * x) * x) * x) * x) * x;
	case 7: return (((((x * x) * x) * x) * x) * x) * x;
	default: return ((((((x * x) * x) * x) * x) * x) * x) * x;
	}
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b)); }

/* x values: ordinary, negative, zeros, ones, overflowing, non-finite */
static const double powi_x[] = { 1.3, -1.3, 2.3, 0.7, -0.5, 0.0, -0.0, 1.0, -1.0, 1e40, -1e300, 1e-200, INFINITY, -INFINITY, NAN };

/* csf_powi(x, n) is the product from the left, bit for bit, and 1/(that) for n < 0. */
START_TEST(test_powi_products)
{
	for (size_t i = 0; i < sizeof powi_x / sizeof powi_x[0]; i++)
		for (int n = -CSF_POWI_MAX; n <= CSF_POWI_MAX; n++) {
			double x = powi_x[i], want = n < 0 ? 1 / product(x, -n) : product(x, n);
			ck_assert_msg(same_bits(csf_powi(x, n), want), "%g^%d = %.17g, expected %.17g", x, n, csf_powi(x, n), want);
			ck_assert_msg(same_bits(csf_pow(x, n), want), "csf_pow(%g, %d) = %.17g", x, n, csf_pow(x, n));
		}
	/* where it differs from pow: 1.3^3 in the last bit; 0^-n is 1/0; x^n overflows, so x^-n is 0 */
	ck_assert(csf_powi(1.3, 3) == (1.3 * 1.3) * 1.3 && csf_powi(1.3, 3) != pow(1.3, 3));
	ck_assert(csf_powi(0.0, -2) == INFINITY && csf_powi(-0.0, -1) == -INFINITY && csf_powi(-0.0, -2) == INFINITY);
	ck_assert(csf_powi(1e40, 8) == INFINITY && csf_powi(-1e103, 3) == -INFINITY);
	ck_assert(csf_powi(1e40, -8) == 0 && pow(1e40, -8) > 0);
	ck_assert(csf_powi(NAN, 0) == 1 && pow(NAN, 0) == 1);
	/* any other exponent calls pow */
	static const double other[] = { 2.5, -0.5, 9, -9, 1e300, INFINITY, NAN, 0.1 };
	for (size_t i = 0; i < sizeof other / sizeof other[0]; i++) {
		ck_assert(!csf_is_powi(other[i]));
		ck_assert_msg(same_bits(csf_pow(1.3, other[i]), pow(1.3, other[i])), "csf_pow(1.3, %g)", other[i]);
	}
	ck_assert(csf_is_powi(-0.0) && csf_is_powi(8) && csf_is_powi(-8) && csf_is_powi(2.0));
}
END_TEST

/* The VM's POWI (exponent immediate) gives csf_powi's bits; POW (exponent in memory, known only at run time) pow's. */
START_TEST(test_powi_instruction)
{
	for (size_t i = 0; i < sizeof powi_x / sizeof powi_x[0]; i++)
		for (int n = -CSF_POWI_MAX; n <= CSF_POWI_MAX; n++) {
			double m[12] = { 0 };
			m[3] = powi_x[i];
			m[6] = n;
			uint32_t code[] = { CSF_OP_POWI, 0, 3, (uint32_t)n, CSF_OP_POW, 1, 3, 6 };
			csf_prog p = bare_prog(code, 8, m, 12, 1);
			char err[256];
			ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "POWI %d: %s", n, err);
			ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, m), -1);
			double want = csf_powi(powi_x[i], n), want_pow = pow(powi_x[i], n);
			ck_assert_msg(same_bits(m[0], want) && same_bits(m[1], want_pow),
			              "%g^%d: POWI %.17g, POW %.17g, expected %.17g and %.17g", powi_x[i], n, m[0], m[1], want,
			              want_pow);
		}
}
END_TEST

/*
 * The constant folder (a power of constants, folded at compile time) and the
 * VM (the same power of a variable, by POWI) agree bit for bit, for every
 * exponent written as an integer literal, a negative one, in parentheses,
 * as 2.0 or as a constant expression; other exponents stay POW.
 */
static const struct { const char *k; double n; int powi; } folder_cases[] = {
	{ "-8", -8, 1 }, { "-5", -5, 1 }, { "(-2)", -2, 1 }, { "-1", -1, 1 }, { "0", 0, 1 }, { "1", 1, 1 },
	{ "(2)", 2, 1 }, { "2.0", 2, 1 }, { "3", 3, 1 }, { "(1 + 3)", 4, 1 }, { "7", 7, 1 }, { "8", 8, 1 },
	{ "9", 9, 0 }, { "-9", -9, 0 }, { "2.5", 2.5, 0 }, { "0.5", 0.5, 0 },
};

START_TEST(test_powi_folder)
{
	const char *k = folder_cases[_i].k;
	char *src = xprintf("global q = 1.3^%s\nobject b: x = 1.3\nobject b: y = 0\nrule: y = x^%s\n"
	                    "inc t till 1 by 1 watch y, q\n", k, k);
	csf_prog p;
	char *d;
	ck_assert_msg(compile_string(src, &p, &d) == 0, "x^%s: %s", k, d);
	free(d);
	const uint32_t *code = p.code[CSF_SEC_OUT];
	ck_assert_msg(code[0] == (uint32_t)(folder_cases[_i].powi ? CSF_OP_POWI : CSF_OP_POW), "x^%s: %s", k,
	              csf_opinfo_table[code[0]].name);
	double *m = run_out(&p);
	double y = m[col_slot(&p, "b.y")], q = m[col_slot(&p, "q")];
	ck_assert_msg(same_bits(y, q) && same_bits(y, csf_pow(1.3, folder_cases[_i].n)), "x^%s: VM %.17g, folded %.17g", k,
	              y, q);
	free(m);
	csf_prog_free(&p);
}
END_TEST

/* csf_all_finite against isfinite: each special value at every place of every length to 200 */
START_TEST(test_all_finite)
{
	static const double special[] = { INFINITY, -INFINITY, NAN, -NAN, DBL_MAX, -DBL_MAX, 0x1p-1074, -0.0 };
	double v[200];
	for (size_t n = 0; n <= 200; n++) {
		for (size_t i = 0; i < n; i++) v[i] = (i % 2 ? -1.0 : 1.0) * (double)i * 1e300;
		ck_assert(csf_all_finite(v, n));
		for (size_t k = 0; k < n; k++)
			for (size_t q = 0; q < sizeof special / sizeof special[0]; q++) {
				double keep = v[k];
				v[k] = special[q];
				ck_assert_msg(csf_all_finite(v, n) == (isfinite(special[q]) != 0), "n %zu, v[%zu] = %g", n, k,
				              special[q]);
				v[k] = keep;
			}
	}
}
END_TEST

Suite *vm_suite(void)
{
	Suite *s = suite_create("vm");
	TCase *tc = tcase_create("instructions");
	tcase_add_loop_test(tc, test_instruction, 0, sizeof cases / sizeof cases[0]);
	tcase_add_test(tc, test_vpack);
	tcase_add_test(tc, test_overlapping_vectors);
	tcase_add_test(tc, test_control_flow);
	tcase_add_test(tc, test_powi_products);
	tcase_add_test(tc, test_powi_instruction);
	tcase_add_test(tc, test_all_finite);
	tcase_add_loop_test(tc, test_powi_folder, 0, sizeof folder_cases / sizeof folder_cases[0]);
	suite_add_tcase(s, tc);
	return s;
}
