/* The C emitter: each instruction's translation, control flow, comments. */
#include <math.h>
#include <string.h>

#include "suites.h"
#include "emit_c.h"

static char *emit_one(uint32_t *code, uint32_t n)
{
	csf_prog p;
	memset(&p, 0, sizeof p);
	p.code[CSF_SEC_OUT] = code;
	p.ncode[CSF_SEC_OUT] = n;
	return emit_string(&p);
}

/*
 * Every non-control instruction becomes DEST = csf_op_NAME(operands): here
 * a local written (and read after), memory read; a local no one reads is
 * not computed.
 */
START_TEST(test_each_instruction)
{
	int op = _i;
	const csf_opinfo *oi = &csf_opinfo_table[op];
	if (op == CSF_OP_JMP || op == CSF_OP_JZ || op == CSF_OP_ASSERT || op == CSF_OP_LOOP || op == CSF_OP_NEXT ||
	    op == CSF_OP_JEQ)
		return; /* control flow: test_control_flow, and the loops suite */
	if (op == CSF_OP_CONTACT || op == CSF_OP_CONSTRAIN) { /* the runtime's routines, which read the program's tables */
		uint32_t one = (uint32_t)op;
		char *c = emit_one(&one, 1);
		const char *want = op == CSF_OP_CONTACT ? "\tcsf_contact_apply(p, x, m);\n" : "\tcsf_constraint_apply(p, x, m);\n";
		ck_assert_msg(strstr(c, want) != NULL, "%s", c);
		free(c);
		return;
	}
	uint32_t code[8] = { (uint32_t)op, 10, 13, 16, 19 }, n = 1u + oi->nops; /* then the result read */
	code[n++] = oi->kind[0] == CSF_K_DV ? CSF_OP_VMOV : CSF_OP_MOV;
	code[n++] = 40;
	code[n++] = 10;
	char *c = emit_one(code, n);
	char *want = xprintf("\t%s10 = csf_op_%s(", oi->kind[0] == CSF_K_DV ? "v" : "r", oi->name);
	for (int k = 1; k < oi->nops; k++)
		want = xprintf("%s%s%s", want, k > 1 ? ", " : "",
		               oi->kind[k] == CSF_K_V   ? xprintf("csf_vload(m + %du)", 10 + 3 * k)
		               : oi->kind[k] == CSF_K_N ? xprintf("%d", 10 + 3 * k)
		                                        : xprintf("m[%du]", 10 + 3 * k));
	want = xprintf("%s);\n", want);
	ck_assert_msg(strstr(c, want) != NULL, "%s: no '%s' in\n%s", oi->name, want, c);
	free(c);
}
END_TEST

/* POWI's exponent, an immediate, is written as the signed number it is. */
START_TEST(test_powi_exponent)
{
	uint32_t code[] = { CSF_OP_POWI, 10, 13, (uint32_t)-2, CSF_OP_POWI, 11, 13, 8, CSF_OP_ADD, 12, 10, 11 };
	char *c = emit_one(code, sizeof code / sizeof code[0]);
	ck_assert_msg(strstr(c, "\tr10 = csf_op_POWI(m[13u], -2);\n") && strstr(c, "\tr11 = csf_op_POWI(m[13u], 8);\n"), "%s", c);
	free(c);
}
END_TEST

START_TEST(test_control_flow)
{
	uint32_t code[] = { CSF_OP_JZ, 1, 6, CSF_OP_MOV, 0, 3, CSF_OP_ASSERT, 2, 0, CSF_OP_JMP, 14, CSF_OP_NOT, 4, 5 };
	char *c = emit_one(code, sizeof code / sizeof code[0]);
	ck_assert_msg(strstr(c, "\tif (m[1u] == 0.0) goto L6;\n\tm[0u] = csf_op_MOV(m[3u]);\n") &&
	              strstr(c, "L6:\n\tif (m[2u] == 0.0) return 0;\n") && strstr(c, "\tgoto L14;\n") &&
	              strstr(c, "L14:\n\treturn -1;\n"),
	              "%s", c);
	free(c);
}
END_TEST

/*
 * Where each slot lives. Memory: t 0, the state (a vector) 1..3, its
 * derivative 4..6, constants 7..11, a column 13, the rest work slots.
 */
enum { YS = 1, DS = 4, K25 = 7, NZ = 8, K01 = 9, BIG = 10, NANK = 11, T12 = 12, COL = 13, V14 = 14, T18 = 18, T19 = 19, T20 = 20, NM = 21 };

static char *emit_rhs(uint32_t *code, uint32_t n, double *mem, csf_col *col)
{
	memset(mem, 0, NM * sizeof *mem);
	mem[K25] = 2.5, mem[NZ] = -0.0, mem[K01] = 0.1, mem[BIG] = 1e300, mem[NANK] = NAN;
	csf_prog p = bare_prog(NULL, 0, mem, NM, 0);
	p.code[CSF_SEC_RHS] = code;
	p.ncode[CSF_SEC_RHS] = n;
	static double yscale[3] = { 1, 1, 1 }, yatol[3];
	static uint32_t vpair[3];
	p.ystart = YS, p.dstart = DS, p.ny = 3;
	p.yscale = yscale, p.yatol = yatol, p.vpair = vpair;
	*col = (csf_col){ 0, COL };
	p.cols = col;
	p.ncols = 1;
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	return emit_string(&p);
}

/*
 * The state and derivatives are GSL's arrays; a constant is a literal that
 * reads back to its double; a value written before it is read is a local
 * (a vector's a csf_vec); a column, a value read before it is written (on
 * some path), and a NaN stay in memory.
 */
START_TEST(test_slot_classes)
{
	uint32_t code[] = {
		CSF_OP_VMUL, V14, YS, K25,  /* 0: a local vector from the state and a constant */
		CSF_OP_VMOV, DS, V14,       /* 4: the derivative */
		CSF_OP_ADD, T12, NZ, K01,   /* 7: -0.0 + 0.1 */
		CSF_OP_MUL, COL, T12, BIG,  /* 11: a column */
		CSF_OP_ADD, COL, NANK, T12, /* 15: NaN is no literal */
		CSF_OP_ADD, T18, T18, K25,  /* 19: read before it is written */
		CSF_OP_JZ, COL, 29,         /* 23: written on one path only */
		CSF_OP_MOV, T19, K25,       /* 26 */
		CSF_OP_MOV, COL, T19,       /* 29 */
		CSF_OP_JZ, COL, 40,         /* 32: written on both paths */
		CSF_OP_MOV, T20, K25,       /* 35 */
		CSF_OP_JMP, 43,             /* 38 */
		CSF_OP_MOV, T20, K01,       /* 40 */
		CSF_OP_ADD, COL, T20, T20,  /* 43 */
	};
	double mem[NM];
	csf_col col;
	char *c = emit_rhs(code, sizeof code / sizeof code[0], mem, &col);
	const char *want[] = {
		"static int csf_model_rhs(const csf_prog *p, const csf_exec_ctx *x, double *m, const double *y, double *dydt)\n",
		"\tv14 = csf_op_VMUL(csf_vload(y + 0u), 2.5);\n",
		"\tcsf_vstore(dydt + 0u, csf_op_VMOV(v14));\n",
		"\tr12 = csf_op_ADD((-0.0), 0.1);\n",
		"\tm[13u] = csf_op_MUL(r12, 1e+300);\n",
		"\tm[13u] = csf_op_ADD(m[11u], r12);\n",
		"\tm[18u] = csf_op_ADD(m[18u], 2.5);\n",
		"\tm[19u] = csf_op_MOV(2.5);\n",
		"\tm[13u] = csf_op_MOV(m[19u]);\n",
		"\tm[13u] = csf_op_ADD(r20, r20);\n",
		"\tcsf_vec v14;\n",
	};
	for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
		ck_assert_msg(strstr(c, want[i]) != NULL, "no\n%s\nin\n%s", want[i], c);
	ck_assert_msg(strstr(c, "memcpy") == NULL, "%s", c);
	free(c);

	/* with a CONTACT, the state and derivatives are m's, copied in and out */
	uint32_t contact[] = { CSF_OP_VMOV, DS, YS, CSF_OP_CONTACT };
	c = emit_rhs(contact, sizeof contact / sizeof contact[0], mem, &col);
	ck_assert_msg(strstr(c, "\tcsf_vstore(m + 4u, csf_op_VMOV(csf_vload(m + 1u)));\n") &&
	              strstr(c, "\tif (y != m + 1u) memcpy(m + 1u, y, 3u * sizeof *y);\n") &&
	              strstr(c, "\tif (dydt != m + 4u) memcpy(dydt, m + 4u, 3u * sizeof *dydt);\n"),
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
	ck_assert_msg(strstr(buf, "#include \"csf.h\"") &&
	              strstr(buf, "static int csf_model_rhs(const csf_prog *p, const csf_exec_ctx *x, double *m, "
	                          "const double *y, double *dydt)") &&
	              strstr(buf, "static int csf_model_out(const csf_prog *p, const csf_exec_ctx *x, double *m, "
	                          "const double *y, double *dydt)") &&
	              strstr(buf, "/* t.csf:3: rule: x' = v */") &&
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
	tcase_add_test(tc, test_slot_classes);
	tcase_add_test(tc, test_program_shape);
	suite_add_tcase(s, tc);
	return s;
}
