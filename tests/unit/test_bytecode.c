/* The bytecode writer, reader and verifier. */
#include <math.h>
#include <string.h>

#include "suites.h"
#include "bytecode.h"

static const char *model = "object b: x = 1\nobject b: v = 0\nrule: x' = v\nrule: v' = -x\n"
                           "rule: if x > 0:\n    s = 1\nelse:\n    s = -1\nassert x < 2\ninc t till 1 by 0.5 watch x, s\n";

START_TEST(test_roundtrip)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	unsigned char *buf;
	size_t len;
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	char err[256];
	ck_assert_msg(csf_decode(buf, len, &q, err, sizeof err) == 0, "%s", err);
	ck_assert_uint_eq(p.nmem, q.nmem);
	ck_assert(memcmp(p.mem0, q.mem0, p.nmem * sizeof(double)) == 0);
	for (int s = 0; s < CSF_NSEC; s++) {
		ck_assert_uint_eq(p.ncode[s], q.ncode[s]);
		ck_assert(memcmp(p.code[s], q.code[s], p.ncode[s] * 4) == 0);
		ck_assert_uint_eq(p.ntargets[s], q.ntargets[s]);
	}
	ck_assert_uint_eq(p.ncols, q.ncols);
	ck_assert_str_eq(csf_str(&q, q.cols[1].name), "b.s");
	ck_assert(q.till == 1 && q.by == 0.5);
	ck_assert_uint_eq(q.nasserts, 1);
	free(buf);
	csf_prog_free(&p);
	csf_prog_free(&q);
}
END_TEST

START_TEST(test_header_checks)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	unsigned char *buf;
	size_t len;
	csf_encode(&p, &buf, &len);
	char err[256];
	static const struct { size_t off; const char *why; } c[] = {
		{ 0, "bad magic" }, { 4, "version" }, { 8, "integer layout" }, { 12, "floating-point layout" },
		{ 20, "payload size" }, { 24, "checksum" }, { 40, "checksum" },
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		buf[c[i].off] ^= 0x5A;
		ck_assert_int_eq(csf_decode(buf, len, &q, err, sizeof err), -1);
		ck_assert_msg(strstr(err, c[i].why) != NULL, "offset %zu: %s", c[i].off, err);
		buf[c[i].off] ^= 0x5A;
	}
	ck_assert_int_eq(csf_decode(buf, 10, &q, err, sizeof err), -1);
	ck_assert_int_eq(csf_decode(buf, len - 1, &q, err, sizeof err), -1);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

typedef struct defect { uint32_t *w; uint32_t bad; const char *why; } defect;

/* Plants each defect in turn in the valid program p: csf_verify must reject it, giving the reason. */
static void expect_defects(csf_prog *p, const defect *c, size_t n)
{
	char err[256];
	for (size_t i = 0; i < n; i++) {
		uint32_t keep = *c[i].w;
		*c[i].w = c[i].bad;
		ck_assert_msg(csf_verify(p, err, sizeof err) == -1, "defect %zu accepted", i);
		ck_assert_msg(strstr(err, c[i].why) != NULL, "defect %zu: %s", i, err);
		*c[i].w = keep;
	}
	ck_assert_int_eq(csf_verify(p, err, sizeof err), 0);
}

/* Each defect planted in a valid program must be caught by csf_verify. */
START_TEST(test_verifier)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	char err[256];
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	uint32_t *code = p.code[CSF_SEC_OUT];
	/* find the JZ of the conditional rule and the ASSERT */
	uint32_t jz = 0, as = 0;
	for (uint32_t i = 0; i < p.ncode[CSF_SEC_OUT]; i += 1u + csf_opinfo_table[code[i]].nops) {
		if (code[i] == CSF_OP_JZ) jz = i;
		if (code[i] == CSF_OP_ASSERT) as = i;
	}
	ck_assert(code[jz] == CSF_OP_JZ && code[as] == CSF_OP_ASSERT);
	defect c[] = {
		{ &code[0], CSF_NOPCODES, "invalid opcode" },
		{ &code[jz + 1], p.nmem, "out of range" },         /* read past memory */
		{ &code[jz + 2], jz, "out of range" },             /* backward jump (a loop) */
		{ &code[jz + 2], jz + 1, "out of range" },         /* into the middle of an instruction */
		{ &code[jz + 2], p.ncode[CSF_SEC_OUT] + 1, "out of range" },
		{ &code[as + 2], 7, "out of range" },              /* no such assertion */
		{ &p.tslot, p.nmem, "time slot" },
		{ &p.ny, p.nmem, "state layout" },
		{ &p.cols[0].slot, p.nmem + 5, "column" },
		{ &p.srcs[0].file, 99, "source entry" },
		{ &p.targets[CSF_SEC_RHS][0].width, 2, "target" },
		{ &p.props[0].slot, p.nmem, "property" },
		{ &p.props[0].object, 99, "property" },
		{ &p.objects[0], p.nstrs, "object" },
		{ &p.vpair[0], 1, "pair" },
		{ &p.jtan, p.nmem, "tangent" },
	};
	expect_defects(&p, c, sizeof c / sizeof c[0]);
	p.strs[p.nstrs - 1] = 'x';
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	p.strs[p.nstrs - 1] = '\0';
	p.by = 0;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	p.by = 0.5;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	csf_prog_free(&p);
}
END_TEST

/* POWI's exponent must be within -8..8; the disassembler prints it signed. */
START_TEST(test_powi_verified)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 2\nobject b: y = 0\nrule: y = x^-2\ninc t till 1 by 1 watch y\n", &p, NULL), 0);
	uint32_t *code = p.code[CSF_SEC_OUT];
	ck_assert(code[0] == CSF_OP_POWI && code[3] == (uint32_t)-2);
	defect c[] = {
		{ &code[3], 9, "operand 3 of POWI" },
		{ &code[3], (uint32_t)-9, "operand 3 of POWI" },
		{ &code[3], 0x7FFFFFFFu, "operand 3 of POWI" },
		{ &code[3], 0x80000000u, "operand 3 of POWI" },
		{ &code[2], p.nmem, "operand 2 of POWI" },
	};
	expect_defects(&p, c, sizeof c / sizeof c[0]);
	char err[256];
	for (int n = -8; n <= 8; n += 16) {
		code[3] = (uint32_t)n;
		ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "POWI %d: %s", n, err);
	}
	code[3] = (uint32_t)-2;
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	csf_disassemble(&p, f);
	fclose(f);
	ck_assert_msg(strstr(buf, xprintf("POWI    %lu %lu -2 ", (unsigned long)code[1], (unsigned long)code[2])) != NULL, "%s", buf);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

/* A block on a 30 degree ramp, held by static friction; and a conditional force. */
static const char *contact_model =
	"object ramp: vector point = (0, 0, 0) m\n"
	"object ramp: vector normal = (-0.5, 0, 0.8660254037844386)\n"
	"object ramp: vector edge = (0, 0, 0) m\n"
	"object ramp: cr = 1\nobject ramp: mu_s = 0\nobject ramp: mu_k = 0\n"
	"object b: m = 2 kg\nobject b: vector v = (0, 0, 0) m/s\nobject b: vector a = (0, 0, 0) m/s^2\n"
	"object b: vector pos = (0, 0, 0) m\nobject b: radius = 0 m\nobject b: cr = 1\n"
	"object b: mu_s = 1\nobject b: mu_k = 0.5\n"
	"object b: vector FN = (0, 0, 0) N\nobject b: vector Ff = (0, 0, 0) N\n"
	"rule: contact(pos, radius, point$1, normal$1)\n"
	"rule: if t < 1 s:\n    a = g\nelse:\n    a = g.mul(2)\n"
	"rule: v' = a\nrule: pos' = v\n"
	"inc t till 1 s by 0.5 s watch b.a, b.FN, b.Ff\n";

/* The contact routine on a resting, sticking block: a = 0, FN = m g cos30 n, Ff = m g sin30 up the slope. */
START_TEST(test_contact_routine)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(contact_model, &p, NULL), 0);
	ck_assert_uint_eq(p.ncontacts, 1);
	ck_assert_uint_eq(p.nevents, 1);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	const csf_contact *c = &p.contacts[0];
	m[c->s[CSF_CF_WORK] + CSF_CW_MODE] = 2; /* in contact, sticking */
	m[p.events[0].mode] = 1;                 /* t < 1 s */
	ck_assert_int_eq(csf_vm_exec(&p, CSF_SEC_RHS, m), -1);
	double g = 9.80665, mg = 2 * g, s30 = 0.5, c30 = 0.8660254037844386;
	const double *a = m + c->s[CSF_CF_A], *fn = m + c->s[CSF_CF_FN], *ff = m + c->s[CSF_CF_FF];
	double want_fn[3] = { -mg * c30 * s30, 0, mg * c30 * c30 }, want_ff[3] = { mg * s30 * c30, 0, mg * s30 * s30 };
	for (int k = 0; k < 3; k++) {
		ck_assert_msg(fabs(a[k]) < 1e-14, "a[%d] = %g", k, a[k]);
		ck_assert_msg(fabs(fn[k] - want_fn[k]) < 1e-13, "FN[%d] = %.17g, want %.17g", k, fn[k], want_fn[k]);
		ck_assert_msg(fabs(ff[k] - want_ff[k]) < 1e-13, "Ff[%d] = %.17g, want %.17g", k, ff[k], want_ff[k]);
	}
	/* guards: the normal force pushes (m g cos30 > 0); static friction holds (mu_s N - |f| > 0) */
	ck_assert(fabs(m[c->s[CSF_CF_WORK] + CSF_CW_G0] - mg * c30) < 1e-13);
	ck_assert(fabs(m[c->s[CSF_CF_WORK] + CSF_CW_G1] - mg * (c30 - s30)) < 1e-13);
	/* the verifier checks both tables */
	defect d[] = {
		{ &p.contacts[0].s[CSF_CF_V], p.nmem - 1, "contact" }, /* a vector past the end of memory */
		{ &p.contacts[0].s[CSF_CF_WORK], p.nmem - 2, "contact" },
		{ &p.contacts[0].plane, 2, "contact" },
		{ &p.contacts[0].src, p.nsrcs, "contact" },
		{ &p.events[0].mode, p.nmem, "event" },
		{ &p.events[0].kind, 2, "event" },
	};
	expect_defects(&p, d, sizeof d / sizeof d[0]);
	free(m);
	csf_prog_free(&p);
}
END_TEST

/* A sphere (radius 0.1 m, restitution 0.5) on a floor 1000 km up, under gravity. */
static const char *floor_model =
	"object floor: vector point = (0, 0, 1e6) m\n"
	"object floor: vector normal = (0, 0, 1)\n"
	"object floor: vector edge = (0, 0, 0) m\n"
	"object floor: cr = 1\nobject floor: mu_s = 0\nobject floor: mu_k = 0\n"
	"object b: m = 1 kg\nobject b: vector v = (0, 0, 0) m/s\nobject b: vector a = (0, 0, 0) m/s^2\n"
	"object b: vector pos = (0, 0, 1000000.1) m\nobject b: radius = 0.1 m\nobject b: cr = 0.5\n"
	"object b: mu_s = 0\nobject b: mu_k = 0\n"
	"object b: vector FN = (0, 0, 0) N\nobject b: vector Ff = (0, 0, 0) N\n"
	"rule: contact(pos, radius, point$1, normal$1)\n"
	"rule: a = g\nrule: v' = a\nrule: pos' = v\n"
	"inc t till 1 s by 0.5 s watch b.pos\n";

typedef struct eval_ctx { const csf_prog *p; double *m; } eval_ctx;
static int eval_rhs(void *ctx)
{
	eval_ctx *e = ctx;
	csf_vm_exec(e->p, CSF_SEC_RHS, e->m);
	return 0;
}

/*
 * Impacts of the sphere landing at speed w at t = 2 s, settled by
 * csf_contact_settle (Zeno time 5e-7 s, tolerance 1e-10): it rebounds at
 * w/2 and is apart; on a hop lower than 100 tol times the scale (2e6 m, so
 * 0.02 m) it is hopping, landing after the flight time 2 (w/2)/g; when the
 * train of bounces would end within the Zeno time it rests, with FN = m g.
 * The floor's distance from the origin changes none of this.
 */
START_TEST(test_contact_settle)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(floor_model, &p, NULL), 0);
	ck_assert_uint_eq(p.ncontacts, 1);
	double *m = malloc(p.nmem * sizeof *m), g = 9.80665;
	const csf_contact *c = &p.contacts[0];
	uint32_t w0 = c->s[CSF_CF_WORK];
	eval_ctx e = { &p, m };
	static const struct { double w, mode, v; } cases[] = {
		{ 2, 0, 1 },         /* a hop of 0.051 m: apart */
		{ 1, 3, 0.5 },       /* 0.0127 m: hopping */
		{ 1e-6, 1, 0 },      /* bounces that end within 2e-7 s: at rest, sliding freely */
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		memcpy(m, p.mem0, p.nmem * sizeof *m);
		m[p.tslot] = 2;
		m[c->s[CSF_CF_V] + 2] = -cases[i].w;
		ck_assert_int_eq(csf_contact_settle(&p, m, 5e-7, 1e-10, eval_rhs, &e), 0);
		ck_assert_msg(m[w0 + CSF_CW_MODE] == cases[i].mode, "w=%g: mode %g", cases[i].w, m[w0 + CSF_CW_MODE]);
		ck_assert_msg(m[c->s[CSF_CF_V] + 2] == cases[i].v, "w=%g: v %.17g", cases[i].w, m[c->s[CSF_CF_V] + 2]);
		ck_assert(m[c->s[CSF_CF_POS] + 2] >= 1000000.1); /* not below the floor */
		if (cases[i].mode == 3)
			ck_assert_msg(fabs(m[w0 + CSF_CW_TL] - (2 + 2 * 0.5 / g)) < 1e-15, "landing %.17g", m[w0 + CSF_CW_TL]);
		if (cases[i].mode == 1)
			ck_assert_msg(fabs(m[c->s[CSF_CF_FN] + 2] - g) < 1e-12 && fabs(m[c->s[CSF_CF_A] + 2]) < 1e-12,
			              "FN %.17g, a %.17g", m[c->s[CSF_CF_FN] + 2], m[c->s[CSF_CF_A] + 2]);
	}
	free(m);
	csf_prog_free(&p);
}
END_TEST

START_TEST(test_disassembler)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	csf_disassemble(&p, f);
	fclose(f);
	ck_assert_msg(strstr(buf, "section rhs") && strstr(buf, "section out") && strstr(buf, "JZ") &&
	              strstr(buf, "ASSERT") && strstr(buf, "t.csf:3: rule: x' = v"), "%s", buf);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

Suite *bytecode_suite(void)
{
	Suite *s = suite_create("bytecode");
	TCase *tc = tcase_create("format");
	tcase_add_test(tc, test_roundtrip);
	tcase_add_test(tc, test_header_checks);
	tcase_add_test(tc, test_verifier);
	tcase_add_test(tc, test_powi_verified);
	tcase_add_test(tc, test_contact_routine);
	tcase_add_test(tc, test_contact_settle);
	tcase_add_test(tc, test_disassembler);
	suite_add_tcase(s, tc);
	return s;
}
