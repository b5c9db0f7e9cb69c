/* Every instruction of the VM against its exact result. */
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

static csf_prog one_instruction(uint32_t *code, uint32_t n, double *mem0, uint32_t nmem)
{
	csf_prog p;
	memset(&p, 0, sizeof p);
	p.code[CSF_SEC_OUT] = code;
	p.ncode[CSF_SEC_OUT] = n;
	p.mem0 = mem0;
	p.nmem = nmem;
	p.strs = "";
	p.nstrs = 1;
	p.by = 1;
	p.nasserts = 1;
	static csf_assert a;
	static csf_src s;
	static uint32_t f;
	p.asserts = &a;
	p.srcs = &s;
	p.nsrcs = 1;
	p.files = &f;
	p.nfiles = 1;
	return p;
}

START_TEST(test_instruction)
{
	double m[12] = { 0 };
	memcpy(m + 3, cases[_i].in, sizeof cases[_i].in);
	m[9] = cases[_i].in[6];
	uint32_t code[5] = { (uint32_t)cases[_i].op, 0, 3, 6, 9 };
	int op = cases[_i].op;
	csf_prog p = one_instruction(code, 1u + csf_opinfo_table[op].nops, m, 12);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s: %s", csf_opinfo_table[op].name, err);
	ck_assert_int_eq(csf_vm_exec(&p, CSF_SEC_OUT, m), -1);
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
	csf_prog p = one_instruction(code, 5, m, 12);
	csf_vm_exec(&p, CSF_SEC_OUT, m);
	ck_assert(m[0] == 7 && m[1] == 8 && m[2] == 9);
}
END_TEST

START_TEST(test_overlapping_vectors)
{
	/* V[0] := V[0] x V[1]: the destination overlaps an operand */
	double m[6] = { 1, 2, 3, 4, 5, 6 };
	uint32_t code[] = { CSF_OP_VCROSS, 0, 0, 3 };
	csf_prog p = one_instruction(code, 4, m, 6);
	csf_vm_exec(&p, CSF_SEC_OUT, m);
	ck_assert(m[0] == -3 && m[1] == 6 && m[2] == -3);
}
END_TEST

START_TEST(test_control_flow)
{
	/* if R[1] == 0 skip the MOV; then assert R[2] */
	double m[4] = { 0, 0, 1, 5 };
	uint32_t code[] = { CSF_OP_JZ, 1, 6, CSF_OP_MOV, 0, 3, CSF_OP_ASSERT, 2, 0 };
	csf_prog p = one_instruction(code, 9, m, 4);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	ck_assert_int_eq(csf_vm_exec(&p, CSF_SEC_OUT, m), -1);
	ck_assert(m[0] == 0);
	m[1] = 1;
	m[2] = 0;
	ck_assert_int_eq(csf_vm_exec(&p, CSF_SEC_OUT, m), 0); /* the assertion fails */
	ck_assert(m[0] == 5);
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
	suite_add_tcase(s, tc);
	return s;
}
