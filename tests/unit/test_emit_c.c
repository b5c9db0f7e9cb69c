/* The C emitter: each instruction's translation, control flow, comments. */
#include <string.h>

#include "suites.h"
#include "emit_c.h"

static char *emit_one(uint32_t *code, uint32_t n)
{
	csf_prog p;
	memset(&p, 0, sizeof p);
	p.code[CSF_SEC_OUT] = code;
	p.ncode[CSF_SEC_OUT] = n;
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	unsigned char image[2] = { 1, 2 };
	emit_c(&p, image, 2, "m.csf", f);
	fclose(f);
	return buf;
}

/* Every non-control instruction becomes a call of its runtime function with constant operands. */
START_TEST(test_each_instruction)
{
	int op = _i;
	const csf_opinfo *oi = &csf_opinfo_table[op];
	if (op == CSF_OP_JMP || op == CSF_OP_JZ || op == CSF_OP_ASSERT || op == CSF_OP_LOOP || op == CSF_OP_NEXT ||
	    op == CSF_OP_JEQ)
		return; /* control flow: test_control_flow, and the loops suite */
	if (op == CSF_OP_CONTACT) { /* the runtime's contact routine, which reads the program's tables */
		uint32_t one = (uint32_t)op;
		char *c = emit_one(&one, 1);
		ck_assert_msg(strstr(c, "\tcsf_contact_apply(p, m);\n") != NULL, "%s", c);
		free(c);
		return;
	}
	uint32_t code[5] = { (uint32_t)op, 10, 13, 16, 19 };
	char *c = emit_one(code, 1u + oi->nops);
	static const char *rest[] = { "", ", 13", ", 13, 16", ", 13, 16, 19" };
	char *want = xprintf("\tcsf_op_%s(m, 10%s);\n", oi->name, rest[oi->nops - 1]);
	ck_assert_msg(strstr(c, want) != NULL, "%s: no '%s' in\n%s", oi->name, want, c);
	free(c);
}
END_TEST

/* POWI's exponent, an immediate, is written as the signed number it is. */
START_TEST(test_powi_exponent)
{
	uint32_t code[] = { CSF_OP_POWI, 10, 13, (uint32_t)-2, CSF_OP_POWI, 11, 13, 8 };
	char *c = emit_one(code, sizeof code / sizeof code[0]);
	ck_assert_msg(strstr(c, "\tcsf_op_POWI(m, 10, 13, -2);\n") && strstr(c, "\tcsf_op_POWI(m, 11, 13, 8);\n"), "%s", c);
	free(c);
}
END_TEST

START_TEST(test_control_flow)
{
	uint32_t code[] = { CSF_OP_JZ, 1, 6, CSF_OP_MOV, 0, 3, CSF_OP_ASSERT, 2, 0, CSF_OP_JMP, 14, CSF_OP_NOT, 4, 5 };
	char *c = emit_one(code, sizeof code / sizeof code[0]);
	ck_assert_msg(strstr(c, "\tif (m[1] == 0.0) goto L6;\n") && strstr(c, "L6:\n\tif (m[2] == 0.0) return 0;\n") &&
	              strstr(c, "\tgoto L14;\n") && strstr(c, "L14:\n\treturn -1;\n"),
	              "%s", c);
	free(c);
}
END_TEST

START_TEST(test_program_shape)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 1 m\nobject b: v = 2 m/s\nrule: x' = v\ninc t till 1 by 1 watch x\n", &p, NULL), 0);
	unsigned char *img;
	size_t len;
	csf_encode(&p, &img, &len);
	char *buf;
	size_t blen;
	FILE *f = open_memstream(&buf, &blen);
	emit_c(&p, img, len, "t.csf", f);
	fclose(f);
	ck_assert_msg(strstr(buf, "#include \"csf.h\"") && strstr(buf, "CSF_CHUNK int csf_model_rhs_0(const csf_prog *p, double *m)") &&
	              strstr(buf, "static int csf_model_rhs(const csf_prog *p, double *m)") &&
	              strstr(buf, "static int csf_model_out(const csf_prog *p, double *m)") && strstr(buf, "/* t.csf:3: rule: x' = v */") &&
	              strstr(buf, xprintf("csf_model_image[%zu]", len)) && strstr(buf, "return csf_main(argc, argv"),
	              "%s", buf);
	free(buf);
	free(img);
	csf_prog_free(&p);
}
END_TEST

Suite *emit_c_suite(void)
{
	Suite *s = suite_create("emit_c");
	TCase *tc = tcase_create("translation");
	tcase_add_loop_test(tc, test_each_instruction, 0, CSF_NOPCODES);
	tcase_add_test(tc, test_powi_exponent);
	tcase_add_test(tc, test_control_flow);
	tcase_add_test(tc, test_program_shape);
	suite_add_tcase(s, tc);
	return s;
}
