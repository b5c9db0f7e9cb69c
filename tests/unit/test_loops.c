/*
 * Loops (LOOP ... NEXT, JEQ, operands relative to the loop registers): the
 * VM on hand-built programs, the verifier on every kind of malformed loop,
 * the listing, and the C translation against the VM.
 */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "suites.h"
#include "emit_c.h"
#include "gen_int.h"
#include "insn.h"

/* Slot word slot relative to register r (csf_rel, as a constant expression). */
#define R(slot, r) ((uint32_t)(slot) | (uint32_t)(r) << CSF_REG_SHIFT)

/* Appends an instruction with its operands (as many as the opcode takes) to code[*n]; returns its pc. */
static uint32_t put(uint32_t *code, uint32_t *n, int op, uint32_t a, uint32_t b, uint32_t c)
{
	uint32_t pc = *n, ops[3] = { a, b, c };
	code[(*n)++] = (uint32_t)op;
	for (int k = 0; k < csf_opinfo_table[op].nops; k++) code[(*n)++] = ops[k];
	return pc;
}

/*
 * The memory of the hand-built programs: four objects of one shape with a
 * flag, a scalar x and a vector v each, laid out as arrays (x of object i
 * at X + i, v at VEC + 3 i); VEC's last vector ends exactly at NMEM.
 */
enum { SUM = 0, TMP = 1, OUT2 = 2, COND = 3, VACC = 4, FLAG = 7, X = 11, ONES = 15, VEC = 20, NMEM = 32, NOBJ = 4 };
static const double xs[NOBJ] = { 1, 2, 4, 8 }, flags[NOBJ] = { 1, 0, 1, 1 };

static double mem[NMEM];

/* A verifiable program around OUT code code[0..n): the memory above, one assertion per object. */
static csf_prog bare(uint32_t *code, uint32_t n)
{
	memset(mem, 0, sizeof mem);
	mem[COND] = 1;
	for (int i = 0; i < NOBJ; i++) {
		mem[FLAG + i] = flags[i];
		mem[X + i] = xs[i];
		mem[ONES + i] = 1;
	}
	for (int k = 0; k < 3 * NOBJ; k++) mem[VEC + k] = k + 1;
	return bare_prog(code, n, mem, NMEM, NOBJ);
}

/*
 * A pair rule over the shape, as the compiler would write it: for every
 * object i whose flag is set (JZ skips the rest of its body), assert
 * ONES[i], then for every other object j (JEQ skips j == i) add x_i x_j to
 * SUM and v_j to VACC. Then a statement outside the loops. The pcs of the
 * instructions are kept for the tests that corrupt them.
 */
typedef struct master { uint32_t code[64], n, jz0, l1, jz1, as1, l2, jeq, mul, add, vadd, nx, n1, mov; } master;

static void build_master(master *M)
{
	uint32_t *c = M->code, *n = &M->n;
	*n = 0;
	M->jz0 = put(c, n, CSF_OP_JZ, COND, 0, 0);
	M->l1 = put(c, n, CSF_OP_LOOP, 1, NOBJ, 0);
	M->jz1 = put(c, n, CSF_OP_JZ, R(FLAG, 1), 0, 0);
	M->as1 = put(c, n, CSF_OP_ASSERT, R(ONES, 1), R(0, 1), 0);
	M->l2 = put(c, n, CSF_OP_LOOP, 2, NOBJ, 0);
	M->jeq = put(c, n, CSF_OP_JEQ, 1, 2, 0);
	M->mul = put(c, n, CSF_OP_MUL, TMP, R(X, 1), R(X, 3));
	M->add = put(c, n, CSF_OP_ADD, SUM, SUM, TMP);
	M->vadd = put(c, n, CSF_OP_VADD, VACC, VACC, R(VEC, 4));
	M->nx = put(c, n, CSF_OP_NEXT, 2, M->l2 + 4, 0);
	M->n1 = put(c, n, CSF_OP_NEXT, 1, M->l1 + 4, 0);
	M->mov = put(c, n, CSF_OP_MOV, OUT2, COND, 0);
	c[M->jz0 + 2] = *n;
	c[M->l1 + 3] = M->n1 + 3;
	c[M->jz1 + 2] = M->n1;
	c[M->l2 + 3] = M->nx + 3;
	c[M->jeq + 3] = M->nx;
}

/* Runs p's OUT section on a fresh copy of its memory, of exactly nmem doubles (the sanitizers see any overrun). */
static double *run(const csf_prog *p, int *ret)
{
	double *m = malloc(p->nmem * sizeof *m);
	memcpy(m, p->mem0, p->nmem * sizeof *m);
	*ret = vm_run(p, CSF_SEC_OUT, m);
	return m;
}

/* p verified, then run: its memory after a run that ends without a failed assertion. */
static double *run_ok(const csf_prog *p)
{
	char err[256];
	ck_assert_msg(csf_verify(p, err, sizeof err) == 0, "%s", err);
	int ret;
	double *m = run(p, &ret);
	ck_assert_int_eq(ret, -1);
	return m;
}

/* A sum over an array and over an array of vectors, each in one loop. */
START_TEST(test_loop_sum)
{
	uint32_t code[32], n = 0;
	uint32_t l1 = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
	put(code, &n, CSF_OP_ADD, SUM, SUM, R(X, 1));
	uint32_t n1 = put(code, &n, CSF_OP_NEXT, 1, l1 + 4, 0);
	code[l1 + 3] = n;
	uint32_t l2 = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
	put(code, &n, CSF_OP_VADD, VACC, VACC, R(VEC, 2));
	put(code, &n, CSF_OP_NEXT, 1, l2 + 4, 0);
	code[l2 + 3] = n;
	ck_assert_uint_eq(n1 + 3, l2);
	csf_prog p = bare(code, n);
	char err[256];
	int ret;
	double *m = run_ok(&p);
	ck_assert(m[SUM] == 15);
	ck_assert(m[VACC] == 22 && m[VACC + 1] == 26 && m[VACC + 2] == 30);
	free(m);
	/* a count of 0: neither body runs */
	code[l1 + 2] = code[l2 + 2] = 0;
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	m = run(&p, &ret);
	ck_assert(m[SUM] == 0 && m[VACC] == 0);
	free(m);
}
END_TEST

/* The pair rule: 1*14 + 4*11 + 8*7 (object 1's flag is 0), each v_j added for every other i with its flag set. */
START_TEST(test_pair_loop)
{
	master M;
	build_master(&M);
	csf_prog p = bare(M.code, M.n);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	int ret;
	double *m = run(&p, &ret);
	ck_assert_int_eq(ret, -1);
	ck_assert_msg(m[SUM] == 114, "sum %.17g", m[SUM]);
	ck_assert_msg(m[VACC] == 48 && m[VACC + 1] == 57 && m[VACC + 2] == 66, "%g %g %g", m[VACC], m[VACC + 1], m[VACC + 2]);
	ck_assert(m[OUT2] == 1);
	free(m);
	/* a relative assertion fails with the index of its object, after object 0's pairs */
	mem[ONES + 2] = 0;
	m = run(&p, &ret);
	ck_assert_int_eq(ret, 2);
	ck_assert(m[SUM] == 14 && m[OUT2] == 0);
	free(m);
	/* no outer iterations: the statement after the loops still runs */
	p = bare(M.code, M.n);
	M.code[M.l1 + 2] = 0;
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	m = run(&p, &ret);
	ck_assert(ret == -1 && m[SUM] == 0 && m[VACC] == 0 && m[OUT2] == 1);
	free(m);
	/* valid variants: a jump to the inner LOOP, from the outer body; the largest bounds that fit */
	M.code[M.l1 + 2] = NOBJ;
	M.code[M.jz1 + 2] = M.l2;
	M.code[M.mul + 2] = R(NMEM - NOBJ, 1);
	M.code[M.as1 + 2] = R(0, 1);
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
}
END_TEST

typedef struct defect { uint32_t *w; uint32_t bad; const char *why; } defect;

/* Each malformed loop, planted in the valid pair rule, is rejected with its reason. */
START_TEST(test_loop_verifier)
{
	master M;
	build_master(&M);
	csf_prog p = bare(M.code, M.n);
	uint32_t *c = M.code;
	const defect d[] = {
		{ &c[M.l1 + 3], M.n1, "is not just past its NEXT" },       /* LOOP's end on its NEXT */
		{ &c[M.l1 + 3], M.n, "is not just past its NEXT" },
		{ &c[M.l2 + 3], M.n1 + 3, "is not just past its NEXT" },
		{ &c[M.n1 + 2], M.l1, "is not the body of its LOOP" },     /* NEXT's start */
		{ &c[M.nx + 2], M.mul, "is not the body of its LOOP" },
		{ &c[M.n1 + 1], 2, "innermost loop is level 1" },          /* NEXT's level */
		{ &c[M.nx + 1], 1, "innermost loop is level 2" },
		{ &c[M.l1 + 1], 2, "loop level 2 where level 1 is expected" }, /* level 2 outside level 1 */
		{ &c[M.l2 + 1], 1, "loop level 1 where level 2 is expected" }, /* the same level nested */
		{ &c[M.l1 + 1], 0, "loop level 0 where level 1" },
		{ &c[M.l1 + 1], 4, "loop level 4 where level 1" },
		{ &c[M.l2 + 1], 3, "loop level 3 where level 2" },
		{ &c[M.jz0 + 2], M.mul, "into or out of a loop body" },    /* into a loop body */
		{ &c[M.jz0 + 2], M.jz1, "into or out of a loop body" },
		{ &c[M.jz0 + 2], M.nx, "into or out of a loop body" },     /* onto a NEXT: inside its loop */
		{ &c[M.jz1 + 2], M.mov, "into or out of a loop body" },    /* out of a loop body */
		{ &c[M.jz1 + 2], M.mul, "into or out of a loop body" },    /* from the outer body into the inner */
		{ &c[M.jz1 + 2], M.jeq, "into or out of a loop body" },
		{ &c[M.jz1 + 2], M.n1 + 3, "into or out of a loop body" }, /* past the outer loop's NEXT */
		{ &c[M.jeq + 3], M.n1, "into or out of a loop body" },
		{ &c[M.jeq + 3], M.jeq, "out of range" },                  /* not forward */
		{ &c[M.jeq + 3], M.mul + 1, "out of range" },              /* not an instruction boundary */
		{ &c[M.jeq + 1], 3, "is loop level 3, which is not open" },
		{ &c[M.jeq + 2], 0, "is loop level 0, which is not open" },
		{ &c[M.mov + 2], R(COND, 1), "register of loop level 1, which is not open" }, /* outside any loop */
		{ &c[M.mov + 1], R(OUT2, 2), "register of loop level 1, which is not open" },
		{ &c[M.jz0 + 1], R(COND, 1), "register of loop level 1, which is not open" },
		{ &c[M.as1 + 1], R(ONES, 3), "register of loop level 2, which is not open" }, /* outer body only */
		{ &c[M.as1 + 2], R(0, 4), "register of loop level 2, which is not open" },
		{ &c[M.mul + 2], R(X, 5), "register of loop level 3, which is not open" },
		{ &c[M.mul + 2], R(X, 6), "register of loop level 3, which is not open" },
		{ &c[M.mul + 2], R(X, 7), "invalid register 7" },
		{ &c[M.as1 + 2], R(0, 7), "invalid register 7" },
		{ &c[M.mul + 2], R(NMEM - NOBJ + 1, 1), "operand 2 of MUL" }, /* base + (count - 1) past memory */
		{ &c[M.mul + 3], R(NMEM - NOBJ + 1, 3), "operand 3 of MUL" },
		{ &c[M.mul + 3], R(NMEM - 9, 4), "operand 3 of MUL" },        /* stride 3: fits with stride 1 */
		{ &c[M.vadd + 3], R(VEC + 1, 4), "operand 3 of VADD" },      /* the last vector's last component past memory */
		{ &c[M.vadd + 1], R(VEC + 1, 2), "operand 1 of VADD" },
		{ &c[M.vadd + 2], R(NMEM - 5, 3), "operand 2 of VADD" },      /* stride 1: the last vector's end past memory */
		{ &c[M.as1 + 2], R(1, 1), "operand 2 of ASSERT" },           /* an assertion index past nasserts */
		{ &c[M.as1 + 2], R(0, 2), "operand 2 of ASSERT" },
		{ &c[M.l1 + 2], NOBJ + 1, "out of range" },                 /* a count larger than the arrays */
		{ &c[M.l2 + 2], NMEM, "out of range" },
		{ &c[M.l2 + 2], 0xFFFFFFFFu, "out of range" },               /* base + (count - 1) * stride wraps 32 bits */
		{ &c[M.l2 + 2], 0x55555556u, "out of range" },               /* 3 (count - 1) = 2^32 - 1: VEC - 1 in 32 bits */
		{ &c[M.l2 + 2], 0x80000000u, "out of range" },
		{ &c[M.mul + 2], R(CSF_SLOT_MASK, 1), "out of range" },
		{ &c[M.l1], CSF_OP_NEXT, "" },                               /* an opcode changed: the structure breaks */
		{ &c[M.n1], CSF_OP_LOOP, "" },
		{ &c[M.nx], CSF_OP_JEQ, "" },
	};
	char err[256];
	for (size_t i = 0; i < sizeof d / sizeof d[0]; i++) {
		uint32_t keep = *d[i].w;
		*d[i].w = d[i].bad;
		ck_assert_msg(csf_verify(&p, err, sizeof err) == -1, "defect %zu accepted", i);
		ck_assert_msg(strstr(err, d[i].why) != NULL && !strchr(err, '\n'), "defect %zu: %s", i, err);
		*d[i].w = keep;
	}
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
}
END_TEST

/* Whole programs with a malformed loop structure. */
START_TEST(test_loop_structure)
{
	enum { L = CSF_OP_LOOP, N = CSF_OP_NEXT, MOV = CSF_OP_MOV, JMP = CSF_OP_JMP, JEQ = CSF_OP_JEQ };
	static const struct { uint32_t code[40]; uint32_t n; const char *why; } c[] = {
		{ { N, 1, 0 }, 3, "NEXT at 0: no LOOP is open" },
		{ { MOV, 0, 1, N, 1, 3 }, 6, "NEXT at 3: no LOOP is open" },
		{ { L, 1, 2, 7, MOV, 0, R(X, 1) }, 7, "LOOP at 0: loop has no NEXT" },
		{ { L, 1, 2, 14, L, 2, 2, 11, MOV, 0, R(X, 1), N, 1, 4 }, 14, "innermost loop is level 2" },
		{ { L, 1, 2, 14, L, 2, 2, 14, MOV, 0, R(X, 1), N, 2, 8 }, 14, "LOOP at 0: loop has no NEXT" },
		{ { L, 1, 1, 24, L, 2, 1, 21, L, 3, 1, 18, L, 4, 1, 15, N, 4, 16, N, 3, 12, N, 2, 8, N, 1, 4 }, 28,
		  "LOOP at 12: loops nested deeper than 3" },
		{ { JMP, 6, L, 1, 2, 12, MOV, 0, R(X, 1), N, 1, 6 }, 12, "operand 1 of JMP at 0 jumps to 6 into or out of a loop body" },
		{ { L, 1, 2, 12, JMP, 12, MOV, 0, R(X, 1), N, 1, 4 }, 12, "operand 1 of JMP at 4 jumps to 12 into or out of a loop body" },
		{ { JEQ, 1, 1, 4 }, 4, "operand 1 of JEQ at 0 is loop level 1, which is not open" },
		{ { L, 1, 2, 11, JEQ, 1, 2, 8, N, 1, 4 }, 11, "operand 2 of JEQ at 4 is loop level 2, which is not open" },
		{ { L, 1, 2, 7, N, 1, 4, N, 1, 4 }, 10, "NEXT at 7: no LOOP is open" },
		{ { L, 1, 2, 7, N, 1, 4, L, 2, 2, 14, N, 2, 11 }, 14, "loop level 2 where level 1 is expected" },
	};
	char err[256];
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		uint32_t code[40];
		memcpy(code, c[i].code, sizeof code);
		csf_prog p = bare(code, c[i].n);
		ck_assert_msg(csf_verify(&p, err, sizeof err) == -1, "program %zu accepted", i);
		ck_assert_msg(strstr(err, c[i].why) != NULL, "program %zu: %s", i, err);
	}
}
END_TEST

/*
 * Loop fusion (gen_fuse_loops): two loops of four iterations, the second after the first, become
 * one exactly when running them member by member computes what they computed one after the other.
 * Each case runs before and after; the memory must be the same, and fused as the case says. A = X's
 * array of squares (VEC + i), B the second loop's array (VEC + 4 + i); TMP a scratch slot.
 */
START_TEST(test_loop_fusion)
{
	enum { A = VEC, B = VEC + 4, MUL = CSF_OP_MUL, ADD = CSF_OP_ADD, NEG = CSF_OP_NEG, JZ = CSF_OP_JZ };
	static const struct { int op[2][2]; uint32_t a[2][2], b[2][2], c[2][2]; uint32_t count2; int fused; const char *what; } c[] = {
		{ { { MUL, 0 }, { ADD, 0 } }, { { R(A, 1) }, { R(B, 1) } }, { { R(X, 1) }, { R(A, 1) } }, { { R(X, 1) }, { R(X, 1) } },
		  NOBJ, 1, "the second reads the first's result of the same member" },
		{ { { MUL, 0 }, { ADD, 0 } }, { { R(A + 1, 1) }, { R(B, 1) } }, { { R(X, 1) }, { R(A, 1) } }, { { R(X, 1) }, { R(X, 1) } },
		  NOBJ, 0, "the second reads what the first writes for the member before" },
		{ { { MUL, 0 }, { NEG, 0 } }, { { R(A, 1) }, { R(X, 1) } }, { { R(X + 1, 1) }, { R(B, 1) } }, { { R(X, 1) }, { 0 } },
		  NOBJ - 1, 0, "a different count" },
		{ { { MUL, 0 }, { NEG, 0 } }, { { R(A, 1) }, { R(X, 1) } }, { { R(X, 1) }, { R(B, 1) } }, { { R(X, 1) }, { 0 } }, NOBJ,
		  1, "the second writes what the first reads, of the same member" },
		{ { { ADD, 0 }, { ADD, 0 } }, { { SUM }, { R(B, 1) } }, { { SUM }, { SUM } }, { { R(X, 1) }, { R(X, 1) } }, NOBJ, 0,
		  "the second reads a sum the first makes" },
		{ { { MUL, ADD }, { MUL, ADD } }, { { TMP, R(A, 1) }, { TMP, R(B, 1) } }, { { R(X, 1), TMP }, { R(X, 1), TMP } },
		  { { R(X, 1), TMP }, { R(X, 1), R(X, 1) } }, NOBJ, 1, "both write the scratch slot before they read it" },
		{ { { MUL, 0 }, { ADD, 0 } }, { { TMP }, { R(B, 1) } }, { { R(X, 1) }, { TMP } }, { { R(X, 1) }, { R(X, 1) } }, NOBJ, 0,
		  "the second reads the scratch slot the first wrote" },
		{ { { MUL, 0 }, { JZ, 0 } }, { { R(A, 1) }, { R(FLAG, 1) } }, { { R(X, 1) }, { 0 } }, { { R(X, 1) }, { 0 } }, NOBJ, 0,
		  "a jump in a body" },
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		uint32_t code[64], n = 0, l[2];
		for (int k = 0; k < 2; k++) {
			l[k] = put(code, &n, CSF_OP_LOOP, 1, k ? c[i].count2 : NOBJ, 0);
			for (int q = 0; q < 2 && c[i].op[k][q]; q++) {
				uint32_t pc = put(code, &n, c[i].op[k][q], c[i].a[k][q], c[i].b[k][q], c[i].c[k][q]);
				if (c[i].op[k][q] == JZ) code[pc + 2] = pc + 3; /* to the NEXT */
			}
			put(code, &n, CSF_OP_NEXT, 1, l[k] + 4, 0);
			code[l[k] + 3] = n;
		}
		csf_prog p = bare(code, n);
		char err[256];
		ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "case %zu (%s): %s", i, c[i].what, err);
		int ret;
		double *before = run(&p, &ret);
		gen_fuse_loops(&p, TMP, TMP + 1);
		ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "case %zu (%s) fused: %s", i, c[i].what, err);
		int loops = 0;
		for (uint32_t pc = 0; pc < p.ncode[CSF_SEC_OUT]; pc += csf_insn_len(code[pc])) loops += code[pc] == CSF_OP_LOOP;
		ck_assert_msg(loops == 2 - c[i].fused, "case %zu (%s): %d loops", i, c[i].what, loops);
		double *after = run(&p, &ret);
		ck_assert_msg(memcmp(before, after, NMEM * sizeof *before) == 0, "case %zu (%s): another result", i, c[i].what);
		free(before);
		free(after);
	}
}
END_TEST

/*
 * Every word of the pair rule replaced by values likely to break it: the
 * verifier rejects the result with a reason, or accepts it and the VM runs
 * it to the end inside the memory (the sanitizer build checks that).
 */
START_TEST(test_loop_mutations)
{
	master M;
	build_master(&M);
	csf_prog p = bare(M.code, M.n);
	char err[256];
	long accepted = 0, rejected = 0;
	for (uint32_t i = 0; i < M.n; i++) {
		uint32_t keep = M.code[i];
		const uint32_t v[] = { 0, 1, 2, 3, 4, 5, 7, 8, M.n - 1, M.n, M.n + 1, NMEM, 0xFFFFFFFFu, keep + 1, keep - 1,
		                       keep + 4, keep ^ 1u << 29, keep ^ 2u << 29, keep ^ 7u << 29, keep | 6u << 29,
		                       CSF_OP_LOOP, CSF_OP_NEXT, CSF_OP_JEQ, CSF_NOPCODES };
		for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
			M.code[i] = v[k];
			err[0] = '\0';
			if (csf_verify(&p, err, sizeof err) == 0) {
				int ret;
				free(run(&p, &ret));
				ck_assert(ret >= -1 && ret < NOBJ);
				accepted++;
			} else {
				ck_assert_msg(err[0] && !strchr(err, '\n'), "word %u = %u: no one-line reason", i, v[k]);
				rejected++;
			}
		}
		M.code[i] = keep;
	}
	ck_assert(rejected > accepted && accepted > 0);
}
END_TEST

/* The listing: loop levels as i, j, k, relative operands as base+i or base+3j, bodies indented. */
START_TEST(test_loop_listing)
{
	master M;
	build_master(&M);
	csf_prog p = bare(M.code, M.n);
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	csf_disassemble(&p, f);
	fclose(f);
	const char *want[] = {
		xprintf("  %5u  LOOP    i 4 %u ", M.l1, M.n1 + 3),
		xprintf("  %5u    JZ      7+i %u ", M.jz1, M.n1),
		xprintf("  %5u    ASSERT  15+i 0+i ", M.as1),
		xprintf("  %5u    LOOP    j 4 %u ", M.l2, M.nx + 3),
		xprintf("  %5u      JEQ     i j %u ", M.jeq, M.nx),
		xprintf("  %5u      MUL     1 11+i 11+j ", M.mul),
		xprintf("  %5u      VADD    4 4 20+3j ", M.vadd),
		xprintf("  %5u    NEXT    j %u ", M.nx, M.l2 + 4),
		xprintf("  %5u  NEXT    i %u ", M.n1, M.l1 + 4),
		xprintf("  %5u  MOV     2 3 ", M.mov),
	};
	for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
		ck_assert_msg(strstr(buf, want[i]) != NULL, "no '%s' in\n%s", want[i], buf);
	free(buf);
}
END_TEST

/*
 * The C of the pair rule: nested for statements over i1 and i2, relative
 * operands as index expressions, a jump to the end of the body a continue,
 * a constant a literal, a work value written before it is read a local,
 * and what is read before it is written in memory.
 */
START_TEST(test_loop_c)
{
	master M;
	build_master(&M);
	csf_prog p = bare(M.code, M.n);
	char *c = emit_string(&p);
	const char *want = xprintf("\tif (1.0 == 0.0) goto L%u;\n\tfor (uint32_t i1 = 0; i1 < 4u; i1++) {\n"
	                           "\t\tif (m[7u + i1] == 0.0) continue;\n"
	                           "\t\tif (m[15u + i1] == 0.0) return (int)(0u + i1);\n"
	                           "\t\tfor (uint32_t i2 = 0; i2 < 4u; i2++) {\n"
	                           "\t\t\tif (i1 == i2) continue;\n"
	                           "\t\t\tr1 = csf_op_MUL(m[11u + i1], m[11u + i2]);\n"
	                           "\t\t\tm[0u] = csf_op_ADD(m[0u], r1);\n"
	                           "\t\t\tcsf_vstore(m + 4u, csf_op_VADD(csf_vload(m + 4u), csf_vload(m + 20u + 3u * i2)));\n"
	                           "\t\t}\n\t}\n\t/* a value no one reads */;\nL%u:\n\treturn -1;\n",
	                           M.n, M.n);
	ck_assert_msg(strstr(c, want) != NULL, "no\n%s\nin\n%s", want, c);
	ck_assert_msg(strstr(c, "\tdouble r1;\n") != NULL, "%s", c);
	free(c);
}
END_TEST

/* A sum into a local across a loop: written before the loop, it stays a local inside it. */
START_TEST(test_loop_c_local_sum)
{
	uint32_t code[64], n = 0;
	put(code, &n, CSF_OP_MOV, TMP, ONES, 0);
	uint32_t l1 = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
	put(code, &n, CSF_OP_ADD, TMP, TMP, R(X, 1));
	put(code, &n, CSF_OP_NEXT, 1, l1 + 4, 0);
	code[l1 + 3] = n;
	put(code, &n, CSF_OP_MOV, OUT2, TMP, 0);
	/* a loop of count 0 may not run: what it writes is not written after it */
	uint32_t l2 = put(code, &n, CSF_OP_LOOP, 1, 0, 0);
	put(code, &n, CSF_OP_MOV, COND, ONES, 0);
	put(code, &n, CSF_OP_NEXT, 1, l2 + 4, 0);
	code[l2 + 3] = n;
	put(code, &n, CSF_OP_MOV, OUT2, COND, 0);
	put(code, &n, CSF_OP_ASSERT, OUT2, 0, 0);
	csf_prog p = bare(code, n);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	char *c = emit_string(&p);
	ck_assert_msg(strstr(c, "\tr1 = csf_op_MOV(1.0);\n\tfor (uint32_t i1 = 0; i1 < 4u; i1++) {\n"
	                        "\t\tr1 = csf_op_ADD(r1, m[11u + i1]);\n\t}\n\tr2 = csf_op_MOV(r1);\n") &&
	              strstr(c, "\t\tm[3u] = csf_op_MOV(1.0);\n\t}\n\tr2 = csf_op_MOV(m[3u]);\n"),
	              "%s", c);
	free(c);
}
END_TEST

/*
 * A sum over the inner loop into a cell of the outer loop's object (the
 * forces on body i1 from every i2) is kept in a local across the inner loop,
 * loaded before it and stored after it; not when the body reads the array
 * elsewhere, or may return (an assertion).
 */
static char *accumulator_c(int variant)
{
	uint32_t code[64], n = 0;
	uint32_t l1 = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
	uint32_t l2 = put(code, &n, CSF_OP_LOOP, 2, NOBJ, 0);
	put(code, &n, CSF_OP_ADD, R(X, 1), R(X, 1), R(FLAG, 3));
	if (variant == 1) put(code, &n, CSF_OP_MOV, R(VEC, 4), R(X, 3), 0); /* x of another object */
	if (variant == 2) put(code, &n, CSF_OP_ASSERT, R(ONES, 3), R(0, 3), 0);
	put(code, &n, CSF_OP_NEXT, 2, l2 + 4, 0);
	code[l2 + 3] = n;
	put(code, &n, CSF_OP_NEXT, 1, l1 + 4, 0);
	code[l1 + 3] = n;
	csf_prog p = bare(code, n);
	double *m = run_ok(&p);
	for (int i = 0; i < NOBJ; i++) ck_assert(m[X + i] == xs[i] + 3); /* the flags add up to 3 */
	free(m);
	return emit_string(&p);
}

START_TEST(test_loop_c_accumulator)
{
	char *c = accumulator_c(0);
	ck_assert_msg(strstr(c, "\t\t{\n\t\t\tdouble a8 = m[11u + i1];\n\t\tfor (uint32_t i2 = 0; i2 < 4u; i2++) {\n"
	                        "\t\t\ta8 = csf_op_ADD(a8, m[7u + i2]);\n\t\t}\n\t\t\tm[11u + i1] = a8;\n\t\t}\n"),
	              "%s", c);
	free(c);
	for (int v = 1; v <= 2; v++) {
		c = accumulator_c(v);
		ck_assert_msg(strstr(c, "m[11u + i1] = csf_op_ADD(m[11u + i1], m[7u + i2]);") && !strstr(c, " a8"), "%s", c);
		free(c);
	}
}
END_TEST

/*
 * A whole model whose OUT section is replaced by loops: long enough to be
 * split into several C functions, with the split point falling inside a
 * loop and values going from one function to the next in memory; repeated
 * instances of one statement, each a loop; the pair rule. The generated executable must print exactly what
 * the VM prints.
 */
static void build_big(csf_prog *p, uint32_t base)
{
	uint32_t cap = 32768, n = 0, nl = 0, *code = malloc(cap * sizeof *code);
	csf_line *lines = malloc(8192 * sizeof *lines);
	uint32_t acc = base + SUM, tmp = base + TMP, x = base + X, one = base + COND, vacc = base + VACC;
#define LINE(src) (lines[nl++] = (csf_line){ n, (src) })
	LINE(0);
	put(code, &n, CSF_OP_SUB, acc, acc, acc);
	put(code, &n, CSF_OP_MOV, base + OUT2, one, 0); /* read in the last function: through memory */
	put(code, &n, CSF_OP_VSUB, vacc, vacc, vacc);
	for (int k = 0; k < 3600; k++) { /* statements, so that the loop below crosses 4000 instructions */
		LINE(k % 2);
		put(code, &n, CSF_OP_MOV, tmp, one, 0);
	}
	uint32_t l1 = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
	for (int k = 0; k < 800; k++) { /* a loop body of many statements, across the CHUNK boundary */
		LINE(k % 2);
		put(code, &n, k % 2 ? CSF_OP_SUB : CSF_OP_ADD, acc, acc, R(x, 1));
	}
	LINE(1);
	put(code, &n, CSF_OP_ADD, acc, acc, R(x, 1));
	put(code, &n, CSF_OP_NEXT, 1, l1 + 4, 0);
	code[l1 + 3] = n;
	for (int k = 0; k < 6; k++) { /* six instances of one statement, each a loop */
		LINE(0);
		uint32_t l = put(code, &n, CSF_OP_LOOP, 1, NOBJ, 0);
		put(code, &n, CSF_OP_ADD, acc, acc, R(x, 1));
		put(code, &n, CSF_OP_NEXT, 1, l + 4, 0);
		code[l + 3] = n;
	}
	LINE(1);
	put(code, &n, CSF_OP_MUL, acc, acc, base + OUT2);
	master M;
	build_master(&M);
	for (uint32_t pc = 0; pc < M.n; pc += 1u + csf_opinfo_table[M.code[pc]].nops) { /* the pair rule, moved */
		const csf_opinfo *oi = &csf_opinfo_table[M.code[pc]];
		uint32_t moved = n - pc;
		code[n++] = M.code[pc];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = M.code[pc + 1 + k];
			int kind = oi->kind[k];
			if (kind == CSF_K_J || kind == CSF_K_B) w += moved;
			else if (kind == CSF_K_DS || kind == CSF_K_DV || kind == CSF_K_S || kind == CSF_K_V) w += base;
			code[n++] = w;
		}
	}
	p->code[CSF_SEC_OUT] = code;
	p->ncode[CSF_SEC_OUT] = n;
	p->lines[CSF_SEC_OUT] = lines;
	p->nlines[CSF_SEC_OUT] = nl;
	p->ntargets[CSF_SEC_OUT] = 0;
#undef LINE
}

/* Runs command cmd (a shell command line) and returns its standard output, or NULL. */
static char *capture(const char *cmd)
{
	FILE *f = popen(cmd, "r");
	if (!f) return NULL;
	char *buf;
	size_t len;
	FILE *out = open_memstream(&buf, &len);
	int ch;
	while ((ch = fgetc(f)) != EOF) fputc(ch, out);
	fclose(out);
	return pclose(f) == 0 ? buf : (free(buf), NULL);
}

START_TEST(test_loop_c_matches_vm)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 0\nobject b: y = 0\nobject b: z = 0\nrule: x' = 1\n"
	                                 "inc t till 1 by 0.5 watch x, y, z\n", &p, NULL), 0);
	/* the loop programs' memory after the model's, their assertions in place of its */
	uint32_t base = p.nmem;
	bare(NULL, 0);
	p.mem0 = realloc(p.mem0, (base + NMEM) * sizeof *p.mem0);
	memcpy(p.mem0 + base, mem, sizeof mem);
	p.nmem = base + NMEM;
	p.asserts = realloc(p.asserts, NOBJ * sizeof *p.asserts);
	for (int i = 0; i < NOBJ; i++) p.asserts[i] = (csf_assert){ 0, 0 };
	p.nasserts = NOBJ;
	if (p.nsrcs < 2) { /* two statements for the line table */
		p.srcs = realloc(p.srcs, 2 * sizeof *p.srcs);
		p.srcs[1] = p.srcs[0];
		p.nsrcs = 2;
	}
	ck_assert_uint_eq(p.ncols, 3);
	p.cols[0].slot = base + SUM;
	p.cols[1].slot = base + VACC;
	p.cols[2].slot = base + VACC + 2;
	free(p.code[CSF_SEC_OUT]);
	free(p.lines[CSF_SEC_OUT]);
	build_big(&p, base);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	int ret;
	double *m = run(&p, &ret);
	ck_assert_int_eq(ret, -1);
	ck_assert_msg(m[base + SUM] == 6 * 15 + 15 + 114, "%.17g", m[base + SUM]);
	free(m);

	/* the VM's output */
	char *vm;
	size_t vmlen;
	FILE *out = open_memstream(&vm, &vmlen), *errf = fopen("/dev/null", "w");
	csf_opts o;
	int pos[1], npos;
	char *argv[] = { "t", NULL };
	ck_assert_int_eq(csf_parse_opts(1, argv, 1, &o, pos, 0, &npos, "usage"), 0);
	ck_assert_int_eq(csf_run(&p, csf_vm_exec, &o, out, errf), 0);
	fclose(out);
	fclose(errf);

	/* the generated executable's */
	char dir[] = "/tmp/csf-loops-XXXXXX";
	ck_assert(mkdtemp(dir) != NULL);
	char *csrc = xprintf("%s/m.c", dir), *exe = xprintf("%s/m", dir);
	unsigned char *img;
	size_t len;
	ck_assert_int_eq(csf_encode(&p, &img, &len), 0);
	FILE *f = fopen(csrc, "w");
	emit_c(&p, img, len, "t.csf", f);
	fclose(f);
	char *c = capture(xprintf("grep -c '^CSF_FN int csf_model_out_' %s", csrc));
	ck_assert_msg(c && atoi(c) >= 2, "the OUT section is not split: %s", c ? c : "?");
	free(c);
	c = capture(xprintf("grep -c 'm\\[%uu\\] = csf_op_MOV(1.0);' %s", base + OUT2, csrc));
	ck_assert_msg(c && atoi(c) >= 1, "the value that goes from function to function is not in memory: %s", c ? c : "?");
	free(c);
#ifdef __SANITIZE_ADDRESS__
	setenv("CFLAGS", "-O1 -fsanitize=address,undefined", 1); /* libcsfrt.a is instrumented; -g takes a minute */
#endif
	ck_assert_int_eq(emit_c_executable(csrc, exe), 0);
	char *ex = capture(exe);
	ck_assert_msg(ex != NULL, "%s failed", exe);
	ck_assert_msg(strcmp(vm, ex) == 0, "the VM printed\n%s\nthe executable\n%s", vm, ex);
	ck_assert(strstr(vm, "\n0,219,") != NULL);
	free(ex);
	free(vm);
	free(img);
	free(capture(xprintf("rm -rf %s", dir)));
	csf_prog_free(&p);
}
END_TEST

Suite *loops_suite(void)
{
	Suite *s = suite_create("loops");
	TCase *tc = tcase_create("loops");
	tcase_set_timeout(tc, 60);
	tcase_add_test(tc, test_loop_sum);
	tcase_add_test(tc, test_loop_fusion);
	tcase_add_test(tc, test_loop_c_accumulator);
	tcase_add_test(tc, test_pair_loop);
	tcase_add_test(tc, test_loop_verifier);
	tcase_add_test(tc, test_loop_structure);
	tcase_add_test(tc, test_loop_mutations);
	tcase_add_test(tc, test_loop_listing);
	tcase_add_test(tc, test_loop_c);
	tcase_add_test(tc, test_loop_c_local_sum);
	tcase_add_test(tc, test_loop_c_matches_vm);
	suite_add_tcase(s, tc);
	return s;
}
