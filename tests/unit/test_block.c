/*
 * Block interpretation (runtime/prog/block.h): which innermost loops the
 * analysis lets the VM run a block of iterations at a time, on hand-built
 * loops (each kind of dependence that the order of a block would change
 * refused), and the VM with the blocks, alone and with 2 threads, leaving
 * the memory of the VM run an iteration at a time, bit for bit. The loops
 * run N iterations: several blocks, the last one short.
 */
#include <string.h>

#include "suites.h"
#include "block.h"
#include "insn.h"
#include "par.h"

#define R(slot, r) ((uint32_t)(slot) | (uint32_t)(r) << CSF_REG_SHIFT)

/* Memory: scratch T (6 slots), a running sum, a constant, a vector, then per member (N of them) x, a vector v,
   and the cells the loops write: OUT (scalars) and OV (vectors). */
enum { T = 1 /* (slot 0 is t) */, SUM = T + 6, G = SUM + 1, V0 = G + 1, N = 2 * CSF_BLOCK + 22, X = V0 + 3,
       V = X + N, OUT = V + 3 * N, OV = OUT + N, NMEM = OV + 3 * N + 2 };

static uint32_t put(uint32_t *code, uint32_t *n, int op, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
	uint32_t pc = *n, ops[4] = { a, b, c, d };
	code[(*n)++] = (uint32_t)op;
	for (int k = 0; k < csf_opinfo_table[op].nops; k++) code[(*n)++] = ops[k];
	return pc;
}

/* Opens a loop of level l over the N members; next() closes it. */
static uint32_t loop(uint32_t *code, uint32_t *n, uint32_t l) { return put(code, n, CSF_OP_LOOP, l, N, 0, 0); }
static void next(uint32_t *code, uint32_t *n, uint32_t l, uint32_t at)
{
	put(code, n, CSF_OP_NEXT, l, at + 4, 0, 0);
	code[at + 3] = *n;
}

/* A case builds code whose first loop (or the loop inside it) is blocked or not, as it says. */
typedef struct bcase { const char *what; int blocked; void (*build)(uint32_t *c, uint32_t *n); } bcase;

static void pair_sum(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VMOV, R(OV, 2), V0, 0, 0);
	put(c, n, CSF_OP_MUL, SUM, G, R(X, 1), 0);
	uint32_t l2 = loop(c, n, 2), jeq = put(c, n, CSF_OP_JEQ, 1, 2, 0, 0);
	put(c, n, CSF_OP_VSUB, T, R(V, 4), R(V, 2), 0);
	put(c, n, CSF_OP_MUL, T + 3, SUM, R(X, 3), 0);
	put(c, n, CSF_OP_VMAG, T + 4, T, 0, 0);
	put(c, n, CSF_OP_DIVPOWI, T + 5, T + 3, T + 4, 3);
	put(c, n, CSF_OP_VMUL, T, T, T + 5, 0);
	put(c, n, CSF_OP_VADD, R(OV, 2), R(OV, 2), T, 0);
	c[jeq + 3] = *n;
	next(c, n, 2, l2);
	next(c, n, 1, l);
}

static void running_sum(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MUL, T, R(X, 1), R(X, 1), 0);
	put(c, n, CSF_OP_ADD, SUM, SUM, T, 0);
	next(c, n, 1, l);
}

static void doubling_sum(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VADD, V0, V0, V0, 0);
	put(c, n, CSF_OP_ADD, SUM, SUM, X + 5, 0);
	next(c, n, 1, l);
}

static void sum_in_its_terms(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, X + 70, X + 70, R(X, 1), 0); /* at index 70 the term is the sum so far */
	next(c, n, 1, l);
}

static void powers(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_POWI, T, R(X, 1), 2, 0);
	put(c, n, CSF_OP_POWI, T + 1, R(X, 1), (uint32_t)-3, 0);
	put(c, n, CSF_OP_DIVPOWI, R(OUT, 1), T, T + 1, 3);
	put(c, n, CSF_OP_DIVPOWI, T, T + 1, R(X, 1), (uint32_t)-2);
	put(c, n, CSF_OP_ADD, R(OV, 2), T, G, 0);
	next(c, n, 1, l);
}

static void scratch_read_first(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, R(OUT, 1), T, R(X, 1), 0); /* the last iteration's T */
	put(c, n, CSF_OP_MUL, T, R(X, 1), G, 0);
	next(c, n, 1, l);
}

static void sum_read_by_another(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, SUM, SUM, R(X, 1), 0);
	put(c, n, CSF_OP_MOV, R(OUT, 1), SUM, 0, 0); /* the sums so far */
	next(c, n, 1, l);
}

static void next_cell(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MOV, R(OUT, 1), R(X, 1), 0, 0);
	put(c, n, CSF_OP_ADD, R(OV, 1), R(OUT + 1, 1), G, 0); /* OUT[i + 1]: the next iteration's, before it writes it */
	next(c, n, 1, l);
}

static void previous_cell(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_ADD, R(OV, 1), R(OUT, 1), G, 0);         /* OUT[i]: the last iteration wrote it */
	put(c, n, CSF_OP_MUL, R(OUT + 1, 1), R(OV, 1), R(X, 1), 0); /* OUT[i + 1] */
	next(c, n, 1, l);
}

static void part_of_scratch(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VSUB, T, R(V, 2), V0, 0);
	put(c, n, CSF_OP_MUL, R(OUT, 1), T + 1, G, 0); /* one component of a vector temporary */
	next(c, n, 1, l);
}

static void reused_slot(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_NEG, T, R(X, 1), 0, 0);           /* T a scalar, */
	put(c, n, CSF_OP_VMUL, R(OV, 2), R(V, 2), T, 0);
	put(c, n, CSF_OP_VADD, T, R(OV, 2), V0, 0);         /* then T..T+2 a vector (csfc reuses the slot) */
	put(c, n, CSF_OP_VDIV, R(OV, 2), T, R(X, 1), 0);
	next(c, n, 1, l);
}

static void scalar_read_as_vector(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_MUL, T, R(X, 1), G, 0);
	put(c, n, CSF_OP_VADD, R(OV, 2), T, V0, 0); /* T+1 and T+2: the values before the loop */
	next(c, n, 1, l);
}

static void conditional(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), jz = put(c, n, CSF_OP_JZ, R(X, 1), 0, 0, 0);
	put(c, n, CSF_OP_MUL, R(OUT, 1), R(X, 1), G, 0);
	c[jz + 2] = *n;
	next(c, n, 1, l);
}

static void overlapping_writes(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1);
	put(c, n, CSF_OP_VMUL, R(OUT, 1), R(V, 2), G, 0); /* 3 slots a stride of 1 apart: the later iteration's last */
	next(c, n, 1, l);
}

static void outer_cell_read(uint32_t *c, uint32_t *n)
{
	uint32_t l = loop(c, n, 1), l2 = loop(c, n, 2);
	put(c, n, CSF_OP_ADD, R(OUT, 1), R(OUT, 1), R(X, 3), 0);
	put(c, n, CSF_OP_MUL, R(OV, 4), R(OUT, 1), G, 0); /* reads the sum another instruction adds to */
	next(c, n, 2, l2);
	next(c, n, 1, l);
}

static const bcase cases[] = {
	{ "a pair sum (JEQ, scratch, a sum through the outer index)", 1, pair_sum },
	{ "a running sum of scratch", 1, running_sum },
	{ "sums that double themselves", 1, doubling_sum },
	{ "a sum that is one of its terms", 1, sum_in_its_terms },
	{ "integer powers and their quotients", 1, powers },
	{ "scratch read before it is written", 0, scratch_read_first },
	{ "a sum another instruction reads", 0, sum_read_by_another },
	{ "a read of the next iteration's cell", 0, next_cell },
	{ "a read of the previous iteration's cell", 0, previous_cell },
	{ "one component of a vector temporary", 1, part_of_scratch },
	{ "a slot a scalar, then a vector", 1, reused_slot },
	{ "a scalar read as a vector's first component", 0, scalar_read_as_vector },
	{ "a conditional rule", 0, conditional },
	{ "writes of one instruction that overlap", 1, overlapping_writes },
	{ "a sum through the outer index read in the loop", 0, outer_cell_read },
};

static double mem0[NMEM];

static void init_mem(void)
{
	for (int k = 0; k < NMEM; k++) mem0[k] = 1.0 + 0.37 * (k % 17) - 0.01 * k;
	mem0[X + 3] = 0; /* a conditional rule's skip */
}

/* The first innermost loop of section OUT of p: its pc. */
static uint32_t innermost(const csf_prog *p)
{
	const uint32_t *c = p->code[CSF_SEC_OUT];
	uint32_t at = 0;
	for (uint32_t pc = 0; pc < p->ncode[CSF_SEC_OUT]; pc += csf_insn_len(c[pc]))
		if (c[pc] == CSF_OP_LOOP) at = pc;
		else if (c[pc] == CSF_OP_NEXT) break;
	return at;
}

/* Each loop: the analysis's answer; then the VM with the blocks, alone and with 2 threads, the serial memory. */
START_TEST(test_block_loops)
{
	const bcase *k = &cases[_i];
	uint32_t code[256], n = 0;
	k->build(code, &n);
	init_mem();
	csf_prog p = bare_prog(code, n, mem0, NMEM, 0);
	char err[256];
	ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "%s: %s", k->what, err);
	csf_blocks *b = csf_blocks_new(&p);
	const csf_bloop *B = csf_blocks_find(b, CSF_SEC_OUT, innermost(&p));
	ck_assert_msg(!B == !k->blocked, "%s: %s", k->what, B ? "blocked" : "not blocked");
	double serial[NMEM], m[NMEM];
	memcpy(serial, mem0, sizeof serial);
	ck_assert_int_eq(vm_run(&p, CSF_SEC_OUT, serial), -1);
	setenv("CSF_THREADS_MIN_WORK", "0", 1);
	for (int threads = 1; threads <= 2; threads++) {
		csf_exec_ctx x = { .pool = csf_pool_new(&p, threads), .blocks = b };
		memcpy(m, mem0, sizeof m);
		ck_assert_int_eq(csf_vm_exec(&p, &x, CSF_SEC_OUT, m, m + p.ystart, m + p.dstart), -1);
		for (int s = 0; s < NMEM; s++)
			ck_assert_msg(memcmp(&m[s], &serial[s], sizeof *m) == 0, "%s, %d thread(s): slot %d is %.17g, not %.17g",
			              k->what, threads, s, m[s], serial[s]);
		csf_pool_free(x.pool);
	}
	unsetenv("CSF_THREADS_MIN_WORK");
	csf_blocks_free(b);
}
END_TEST

/* A program without loops has no blocks; csf_blocks_free(NULL) and csf_blocks_find(NULL, ...) are harmless. */
START_TEST(test_block_none)
{
	uint32_t code[8], n = 0;
	put(code, &n, CSF_OP_ADD, SUM, G, G, 0);
	init_mem();
	csf_prog p = bare_prog(code, n, mem0, NMEM, 0);
	ck_assert(csf_blocks_new(&p) == NULL);
	ck_assert(csf_blocks_find(NULL, CSF_SEC_OUT, 0) == NULL);
	csf_blocks_free(NULL);
}
END_TEST

Suite *block_suite(void)
{
	Suite *s = suite_create("block");
	TCase *tc = tcase_create("core");
	tcase_add_loop_test(tc, test_block_loops, 0, (int)(sizeof cases / sizeof cases[0]));
	tcase_add_test(tc, test_block_none);
	suite_add_tcase(s, tc);
	return s;
}
