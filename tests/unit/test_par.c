/*
 * Threads (--threads N): which loops the analysis lets threads share
 * (csf_parloop_analyse) on hand-built loops, each kind of dependence
 * between iterations refused, and the VM with a pool of 2 and 3 threads
 * leaving the memory of a serial run, bit for bit; the superinstruction
 * DIVPOWI against the two instructions it fuses.
 */
#include <math.h>
#include <string.h>

#include "suites.h"
#include "emit_c.h"
#include "insn.h"
#include "par.h"
#include "parloop.h"

#define R(slot, r) ((uint32_t)(slot) | (uint32_t)(r) << CSF_REG_SHIFT)

/* Memory: scratch T (6 slots), a running sum, a constant, the zero vector, then per member (N of them)
   a flag, x, a vector v, and the cells the loops write: OUT (scalars) and OV (vectors). */
enum { T = 1 /* (slot 0 is t) */, SUM = T + 6, G = SUM + 1, ZERO = G + 1, N = 8, FLAG = ZERO + 3, X = FLAG + N, V = X + N, OUT = V + 3 * N, OV = OUT + N,
       NMEM = OV + 3 * N };

static uint32_t put(uint32_t *code, uint32_t *n, int op, uint32_t a, uint32_t b, uint32_t c)
{
	uint32_t pc = *n, ops[3] = { a, b, c };
	code[(*n)++] = (uint32_t)op;
	for (int k = 0; k < csf_opinfo_table[op].nops; k++) code[(*n)++] = ops[k];
	return pc;
}

/* Opens a loop of level l over the N members; next() closes it. */
static uint32_t loop(uint32_t *code, uint32_t *n, uint32_t l) { return put(code, n, CSF_OP_LOOP, l, N, 0); }
static void next(uint32_t *code, uint32_t *n, uint32_t l, uint32_t at)
{
	put(code, n, CSF_OP_NEXT, l, at + 4, 0);
	code[at + 3] = *n;
}

/* The loops: each builds code and says whether its iterations are independent. */
typedef struct pcase { const char *what; int par; void (*build)(uint32_t *c, uint32_t *n); } pcase;

static void own_cells(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MUL, T, R(X, 1), G);
	put(c, n, CSF_OP_ADD, R(OUT, 1), T, R(X, 1));
	next(c, n, 1, l);
}

static void pair_sum(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VMOV, R(OV, 2), ZERO, 0);
	uint32_t l2 = loop(c, n, 2), jeq = put(c, n, CSF_OP_JEQ, 1, 2, 0);
	put(c, n, CSF_OP_VSUB, T, R(V, 4), R(V, 2));
	put(c, n, CSF_OP_VMAG, T + 3, T, 0);
	put(c, n, CSF_OP_POWI, T + 4, T + 3, 3);
	put(c, n, CSF_OP_DIV, T + 5, R(X, 3), T + 4);
	put(c, n, CSF_OP_VMUL, T, T, T + 5);
	put(c, n, CSF_OP_VADD, R(OV, 2), R(OV, 2), T);
	c[jeq + 3] = *n;
	next(c, n, 2, l2);
	next(c, n, 1, l);
}

static void running_sum(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, SUM, SUM, R(X, 1));
	next(c, n, 1, l);
}

static void neighbour(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MOV, R(OUT, 1), R(X, 1), 0);
	put(c, n, CSF_OP_ADD, R(OV, 1), R(OUT + 1, 1), G); /* OUT[i + 1]: the next iteration's */
	next(c, n, 1, l);
}

static void inner_write(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), l2 = loop(c, n, 2);
	put(c, n, CSF_OP_ADD, R(OUT, 3), R(X, 1), R(X, 3));
	next(c, n, 2, l2);
	next(c, n, 1, l);
}

static void skipped_scratch(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), jz = put(c, n, CSF_OP_JZ, R(FLAG, 1), 0, 0);
	put(c, n, CSF_OP_MOV, T, R(X, 1), 0);
	c[jz + 2] = *n;
	put(c, n, CSF_OP_ADD, R(OUT, 1), T, G); /* T from an earlier iteration where the flag is 0 */
	next(c, n, 1, l);
}

static void skipped_cell(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), jz = put(c, n, CSF_OP_JZ, R(FLAG, 1), 0, 0);
	put(c, n, CSF_OP_MUL, R(OUT, 1), R(X, 1), G);
	c[jz + 2] = *n;
	next(c, n, 1, l);
}

static void both_branches(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), jz = put(c, n, CSF_OP_JZ, R(FLAG, 1), 0, 0);
	put(c, n, CSF_OP_MOV, T, R(X, 1), 0);
	uint32_t jmp = put(c, n, CSF_OP_JMP, 0, 0, 0);
	c[jz + 2] = *n;
	put(c, n, CSF_OP_NEG, T, G, 0);
	c[jmp + 1] = *n;
	put(c, n, CSF_OP_MUL, R(OUT, 1), T, R(X, 1));
	next(c, n, 1, l);
}

static void assertion(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ASSERT, R(X, 1), R(0, 1), 0);
	put(c, n, CSF_OP_MOV, R(OUT, 1), R(X, 1), 0);
	next(c, n, 1, l);
}

static void fixed_read_of_cell(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, R(OUT, 1), R(X, 1), OUT + 2); /* iteration 2's cell */
	next(c, n, 1, l);
}

static void after_inner_loop(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), l2 = loop(c, n, 2);
	put(c, n, CSF_OP_MOV, T, R(X, 3), 0);
	next(c, n, 2, l2);
	put(c, n, CSF_OP_MOV, R(OUT, 1), T, 0); /* the inner loop might have run no iteration */
	next(c, n, 1, l);
}

static void strides(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MOV, R(OUT, 1), R(X, 1), 0);
	put(c, n, CSF_OP_VMOV, R(OUT, 2), R(V, 2), 0); /* OUT as vectors: other iterations' scalars */
	next(c, n, 1, l);
}

static void own_vector_parts(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VMOV, R(OV, 2), R(V, 2), 0);
	put(c, n, CSF_OP_MUL, R(OV + 1, 2), R(OV + 2, 2), R(X, 1)); /* y := z x: within the iteration's vector */
	next(c, n, 1, l);
}

static const pcase cases[] = {
	{ "each iteration its own cell, scratch written first", 1, own_cells },
	{ "a pair sum into the iteration's vector (JEQ, an inner loop)", 1, pair_sum },
	{ "a running sum over the iterations", 0, running_sum },
	{ "a read of the next iteration's cell", 0, neighbour },
	{ "a write through the inner loop's index", 0, inner_write },
	{ "scratch that a jump may leave unwritten", 0, skipped_scratch },
	{ "a cell that a jump may leave unwritten", 1, skipped_cell },
	{ "scratch written on both branches", 1, both_branches },
	{ "an assertion", 0, assertion },
	{ "a fixed read of a cell", 0, fixed_read_of_cell },
	{ "scratch read after the inner loop that wrote it", 0, after_inner_loop },
	{ "cells of two strides over one array", 0, strides },
	{ "the parts of the iteration's own vector", 1, own_vector_parts },
};

static double mem0[NMEM];

static void init_mem(void)
{
	for (int k = 0; k < NMEM; k++) mem0[k] = 0.25 * k + 1;
	for (int k = 0; k < 3; k++) mem0[ZERO + k] = 0;
	for (int i = 0; i < N; i++) mem0[FLAG + i] = i % 3 == 1 ? 0 : 1;
}

/* Each loop: the analysis's answer; then the VM alone and with 2 and 3 threads, the same memory, bit for bit. */
START_TEST(test_par_loops)
{
	const pcase *k = &cases[_i];
	uint32_t code[128], n = 0;
	k->build(code, &n);
	init_mem();
	csf_prog p = bare_prog(code, n, mem0, NMEM, N);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s: %s", k->what, err);
	csf_parloop L;
	int par = csf_parloop_analyse(&p, CSF_SEC_OUT, 0, &L);
	ck_assert_msg(par == k->par, "%s: analysed as %s", k->what, par ? "independent" : "serial");
	if (par) ck_assert_msg(L.count == N && L.end == n && L.work > N, "%s: count %u, end %u, work %llu", k->what,
	                       L.count, L.end, (unsigned long long)L.work);
	csf_parloop_free(&L);
	double serial[NMEM], m[NMEM];
	memcpy(serial, mem0, sizeof serial);
	ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, serial), -1);
	setenv("CSF_THREADS_MIN_WORK", "0", 1);
	for (int threads = 2; threads <= 3; threads++)
		for (int rep = 0; rep < 3; rep++) { /* again with the workers' memories as the last job left them */
			csf_exec_ctx x = { .pool = csf_pool_new(&p, threads) };
			ck_assert_msg(x.pool != NULL, "%s: no pool", k->what);
			memcpy(m, mem0, sizeof m);
			for (int r = 0; r <= rep; r++) {
				if (r) memcpy(m, mem0, sizeof m);
				ck_assert_int_eq(csf_vm_exec(&p, &x, CSF_SEC_OUT, m, m + p.ystart, m + p.dstart), -1);
			}
			ck_assert_msg(memcmp(m, serial, sizeof m) == 0, "%s: %d threads: the memory differs from the serial run's",
			              k->what, threads);
			csf_pool_free(x.pool);
		}
	unsetenv("CSF_THREADS_MIN_WORK");
}
END_TEST

/* No pool for one thread: the run is serial. */
START_TEST(test_par_one_thread)
{
	uint32_t code[64], n = 0;
	own_cells(code, &n);
	init_mem();
	csf_prog p = bare_prog(code, n, mem0, NMEM, N);
	ck_assert(csf_pool_new(&p, 1) == NULL);
	ck_assert(csf_pool_new(&p, 0) == NULL);
	csf_pool_free(NULL);
}
END_TEST

/* The C of a loop whose iterations are independent: a function of its own, called through csf_par_for,
   the label of a jump that lands on the loop before the call. */
START_TEST(test_par_c)
{
	uint32_t code[64], n = 0;
	uint32_t jz = put(code, &n, CSF_OP_JZ, G, 0, 0);
	put(code, &n, CSF_OP_MOV, SUM, G, 0);
	code[jz + 2] = n;
	uint32_t l = n;
	own_cells(code, &n);
	init_mem();
	csf_prog p = bare_prog(code, n, mem0, NMEM, N);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
	char *c = emit_string(&p), want[128];
	snprintf(want, sizeof want, "L%lu:\n\tcsf_par_for(p, x, ", (unsigned long)l);
	ck_assert_msg(strstr(c, want) && strstr(c, "for (uint32_t i1 = lo; i1 < hi; i1++) {"), "%s", c);
	free(c);
}
END_TEST

/* DIVPOWI, the superinstruction of POWI then DIV: the same bits as the two, on the VM too; hostile operands refused. */
START_TEST(test_divpowi)
{
	static const double xs[] = { 1.5, -3e10, 7, 0.1, 0 }, ys[] = { 0.7, 2, -1e-3, 3e100, 0 };
	for (int n = -CSF_POWI_MAX; n <= CSF_POWI_MAX; n++)
		for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
			double two = csf_op_DIV(xs[i], csf_op_POWI(ys[i], n)), one = csf_op_DIVPOWI(xs[i], ys[i], n);
			ck_assert_msg(memcmp(&one, &two, sizeof one) == 0 || (isnan(one) && isnan(two)), "%g / %g^%d: %.17g, not %.17g",
			              xs[i], ys[i], n, one, two);
			double m[4] = { 0, xs[i], ys[i], 0 };
			uint32_t code[] = { CSF_OP_DIVPOWI, 0, 1, 2, (uint32_t)n };
			csf_prog p = bare_prog(code, 5, m, 4, 1);
			char err[256];
			ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s", err);
			ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, m), -1);
			ck_assert(memcmp(&m[0], &one, sizeof one) == 0 || (isnan(m[0]) && isnan(one)));
		}
	/* an exponent past CSF_POWI_MAX, a slot past memory, a register of no open loop */
	uint32_t bad[][5] = { { CSF_OP_DIVPOWI, 0, 1, 2, 9 }, { CSF_OP_DIVPOWI, 0, 1, 2, (uint32_t)-9 },
		                  { CSF_OP_DIVPOWI, 0, 1, 4, 3 }, { CSF_OP_DIVPOWI, 0, R(1, 1), 2, 3 } };
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		double m[4] = { 0 };
		csf_prog p = bare_prog(bad[i], 5, m, 4, 1);
		char err[256];
		ck_assert_msg(csf_verify(&p, err, sizeof err) != 0, "hostile DIVPOWI %zu verified", i);
	}
}
END_TEST

Suite *par_suite(void)
{
	Suite *s = suite_create("par");
	TCase *tc = tcase_create("core");
	tcase_add_loop_test(tc, test_par_loops, 0, (int)(sizeof cases / sizeof cases[0]));
	tcase_add_test(tc, test_par_one_thread);
	tcase_add_test(tc, test_divpowi);
	tcase_add_test(tc, test_par_c);
	suite_add_tcase(s, tc);
	return s;
}
