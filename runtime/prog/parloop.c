/*
 * parloop.c - the loops whose iterations are independent (parloop.h).
 *
 * One pass over the body collects every slot operand: writes through the
 * loop's own index (the cells), writes of fixed slots, reads. A fixed slot
 * the body writes must be written before every read of it, on every path
 * through the body: the pass keeps the set of those written so far (a
 * bitset over them), intersected where forward jumps meet, and after an
 * inner loop the set from before it (the loop may run no iteration). Then
 * the footprints, each over its loop's whole count, are compared: cells
 * overlap only within one iteration (csf_cell: the same stride, within one
 * stride of each other), a read through the loop's index of a cell's slots
 * only within its own iteration, and no other read reaches a cell or an
 * iteration's own slot.
 */
#include <stdlib.h>
#include <string.h>

#include "insn.h"
#include "parloop.h"

/* A loop body longer than this, or with more fixed slots written, stays serial (the analysis is quadratic in them). */
enum { PAR_MAX_WORDS = 1 << 16, PAR_MAX_PRIV = 4096 };

/* A slot operand through a loop register: slots base + stride k + [0, width) for k < count. */
typedef struct rel { uint32_t base, stride, width, level, count; } rel;

typedef struct ana {
	const uint32_t *code;
	uint32_t *priv, npriv;          /* the fixed slots the body writes, ascending */
	uint64_t *d;                    /* those written on every path so far (a bitset over priv) */
	size_t words;                   /* 64-bit words of a bitset */
	struct pend { uint32_t to; uint64_t *d; } *pend; /* forward jumps not yet reached, with their sets */
	uint32_t npend;
	rel *rd, *wr;                   /* reads and writes through a register */
	uint32_t nrd, nwr;
	csf_span *fix;                  /* fixed slots read that the body does not write */
	uint32_t nfix;
	int ok;                         /* 0: serial (or out of memory) */
} ana;

static void *grow(void *a, uint32_t n, size_t size)
{
	return (n & (n - 1)) == 0 ? realloc(a, (n ? 2 * (size_t)n : 1) * size) : a;
}

static uint64_t rel_end(const rel *x) { return x->base + (uint64_t)(x->count ? x->count - 1 : 0) * x->stride + x->width; }

static int overlap(uint64_t a0, uint64_t a1, uint64_t b0, uint64_t b1) { return a0 < b1 && b0 < a1; }

/* Do x and y, both through the loop's index, meet only within one iteration? */
static int same_cell(const rel *x, const rel *y)
{
	uint32_t lo = x->base < y->base ? x->base : y->base;
	uint64_t hi = x->base + x->width > y->base + y->width ? (uint64_t)x->base + x->width : (uint64_t)y->base + y->width;
	return x->stride == y->stride && hi - lo <= x->stride;
}

/* The index of s in the ascending a[0..n - 1], or -1. */
static long find(const uint32_t *a, uint32_t n, uint32_t s)
{
	uint32_t lo = 0, hi = n;
	while (lo < hi) {
		uint32_t mid = lo + (hi - lo) / 2;
		if (a[mid] < s) lo = mid + 1;
		else hi = mid;
	}
	return lo < n && a[lo] == s ? (long)lo : -1;
}

int csf_parloop_own(const csf_parloop *L, uint32_t s) { return find(L->priv, L->npriv, s) >= 0; }

static int cmp_u32(const void *a, const void *b)
{
	uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
	return (x > y) - (x < y);
}

/* The fixed slots the body [from, to) writes, sorted and unique, into A->priv. */
static void collect_priv(ana *A, uint32_t from, uint32_t to)
{
	for (uint32_t q = from; q < to && A->ok; q += csf_insn_len(A->code[q])) {
		const csf_opinfo *oi = &csf_opinfo_table[A->code[q]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = A->code[q + 1 + k];
			if (!csf_kind_write(oi->kind[k]) || csf_reg(w)) continue;
			for (uint32_t j = 0; j < csf_kind_width(oi->kind[k]); j++) {
				if (A->npriv >= PAR_MAX_PRIV || !(A->priv = grow(A->priv, A->npriv, sizeof *A->priv))) {
					A->ok = 0;
					return;
				}
				A->priv[A->npriv++] = w + j;
			}
		}
	}
	if (!A->ok || !A->npriv) return;
	qsort(A->priv, A->npriv, sizeof *A->priv, cmp_u32);
	uint32_t n = 1;
	for (uint32_t i = 1; i < A->npriv; i++)
		if (A->priv[i] != A->priv[n - 1]) A->priv[n++] = A->priv[i];
	A->npriv = n;
}

static uint64_t *set_copy(ana *A, const uint64_t *d)
{
	uint64_t *c = malloc(A->words * sizeof *c);
	if (!c) A->ok = 0;
	else memcpy(c, d, A->words * sizeof *c);
	return c;
}

/* A jump to t: the set here goes with it. */
static void jump(ana *A, uint32_t t)
{
	uint64_t *c = set_copy(A, A->d);
	if (!c || !(A->pend = grow(A->pend, A->npend, sizeof *A->pend))) {
		free(c);
		A->ok = 0;
		return;
	}
	A->pend[A->npend++] = (struct pend){ t, c };
}

/* At pc q: the sets of the jumps that land here met with the one that falls through (none after a JMP: dead). */
static void land(ana *A, uint32_t q, int *dead)
{
	for (uint32_t i = 0; i < A->npend;) {
		if (A->pend[i].to != q) {
			i++;
			continue;
		}
		for (size_t k = 0; k < A->words; k++) A->d[k] = *dead ? A->pend[i].d[k] : A->d[k] & A->pend[i].d[k];
		*dead = 0;
		free(A->pend[i].d);
		A->pend[i] = A->pend[--A->npend];
	}
}

static void add_rel(ana *A, rel **a, uint32_t *n, rel x)
{
	if (!(*a = grow(*a, *n, sizeof **a))) {
		A->ok = 0;
		return;
	}
	(*a)[(*n)++] = x;
}

static void add_span(ana *A, csf_span **a, uint32_t *n, uint64_t lo, uint64_t hi)
{
	if (!(*a = grow(*a, *n, sizeof **a))) {
		A->ok = 0;
		return;
	}
	(*a)[(*n)++] = (csf_span){ (uint32_t)lo, (uint32_t)hi };
}

/* The slot operands of the instruction at q: its reads, then its writes (an instruction reads all before it writes). */
static void operands(ana *A, uint32_t q, const uint32_t *cnt)
{
	const csf_opinfo *oi = &csf_opinfo_table[A->code[q]];
	for (int pass = 0; pass < 2; pass++)
		for (int k = 0; k < oi->nops && A->ok; k++) {
			int kind = oi->kind[k];
			uint32_t w = A->code[q + 1 + k], r = csf_reg(w), base = w & CSF_SLOT_MASK, width = csf_kind_width(kind);
			if (!csf_kind_slot(kind) || csf_kind_write(kind) != pass) continue;
			if (r) {
				uint32_t level = csf_reg_level(r);
				rel x = { base, csf_reg_stride(r), width, level, cnt[level] };
				if (pass && (level != 1 || width > x.stride)) A->ok = 0; /* another iteration's slots */
				else add_rel(A, pass ? &A->wr : &A->rd, pass ? &A->nwr : &A->nrd, x);
				continue;
			}
			for (uint32_t j = 0; j < width; j++) {
				long i = find(A->priv, A->npriv, base + j);
				if (pass) A->d[i / 64] |= 1ull << (i % 64);
				else if (i < 0) add_span(A, &A->fix, &A->nfix, base + j, base + j + 1);
				else if (!(A->d[i / 64] >> (i % 64) & 1)) A->ok = 0; /* read before this iteration wrote it */
			}
		}
}

/* The walk over the body [from, to): its operands, the written sets, the work. */
static void walk(ana *A, uint32_t from, uint32_t to, uint32_t count, uint64_t *work)
{
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0, count }, depth = 1;
	uint64_t mult[CSF_LOOP_MAX + 1] = { 1, count }, *before[CSF_LOOP_MAX + 1] = { NULL };
	int dead = 0;
	for (uint32_t q = from; q < to && A->ok; q += csf_insn_len(A->code[q])) {
		const uint32_t *a = A->code + q + 1;
		land(A, q, &dead);
		*work = *work + mult[depth] < *work ? UINT64_MAX : *work + mult[depth];
		switch (A->code[q]) {
		case CSF_OP_CONTACT:
		case CSF_OP_CONSTRAIN:
		case CSF_OP_ASSERT:
			A->ok = 0;
			break;
		case CSF_OP_JMP:
			jump(A, a[0]);
			dead = 1;
			break;
		case CSF_OP_JZ:
			operands(A, q, cnt);
			jump(A, a[1]);
			break;
		case CSF_OP_JEQ:
			jump(A, a[2]);
			break;
		case CSF_OP_LOOP:
			depth = a[0];
			cnt[depth] = a[1];
			mult[depth] = a[1] && mult[depth - 1] > UINT64_MAX / a[1] ? UINT64_MAX : mult[depth - 1] * a[1];
			before[depth] = set_copy(A, A->d);
			break;
		case CSF_OP_NEXT: /* (the body's own NEXT is past to) */
			memcpy(A->d, before[depth], A->words * sizeof *A->d);
			free(before[depth]);
			before[depth--] = NULL;
			break;
		default:
			operands(A, q, cnt);
		}
	}
	for (uint32_t l = 0; l <= CSF_LOOP_MAX; l++) free(before[l]);
}

/* Are the footprints independent across iterations (see the top of the file)? */
static int independent(const ana *A)
{
	for (uint32_t i = 0; i < A->nwr; i++) {
		const rel *c = &A->wr[i];
		for (uint32_t j = 0; j < i; j++)
			if (overlap(c->base, rel_end(c), A->wr[j].base, rel_end(&A->wr[j])) && !same_cell(c, &A->wr[j])) return 0;
		for (uint32_t j = 0; j < A->nrd; j++) {
			const rel *x = &A->rd[j];
			if (overlap(c->base, rel_end(c), x->base, rel_end(x)) && (x->level != 1 || !same_cell(c, x))) return 0;
		}
		for (uint32_t j = 0; j < A->nfix; j++)
			if (overlap(c->base, rel_end(c), A->fix[j].lo, A->fix[j].hi)) return 0;
		for (uint32_t j = 0; j < A->npriv; j++)
			if (overlap(c->base, rel_end(c), A->priv[j], A->priv[j] + 1ull)) return 0;
	}
	for (uint32_t i = 0; i < A->nrd; i++)
		for (uint32_t j = 0; j < A->npriv; j++)
			if (overlap(A->rd[i].base, rel_end(&A->rd[i]), A->priv[j], A->priv[j] + 1ull)) return 0;
	return 1;
}

static int cmp_span(const void *a, const void *b)
{
	const csf_span *x = a, *y = b;
	return (x->lo > y->lo) - (x->lo < y->lo);
}

/* L's in: every read footprint and every cell, merged (a cell the body may skip keeps its value through the copy). */
static void spans_in(ana *A, csf_parloop *L)
{
	for (uint32_t i = 0; i < A->nrd + A->nwr && A->ok; i++) {
		const rel *x = i < A->nrd ? &A->rd[i] : &A->wr[i - A->nrd];
		add_span(A, &A->fix, &A->nfix, x->base, rel_end(x));
	}
	if (!A->ok || !A->nfix) return;
	qsort(A->fix, A->nfix, sizeof *A->fix, cmp_span);
	uint32_t n = 1;
	for (uint32_t i = 1; i < A->nfix; i++) {
		if (A->fix[i].lo <= A->fix[n - 1].hi) {
			if (A->fix[i].hi > A->fix[n - 1].hi) A->fix[n - 1].hi = A->fix[i].hi;
		} else
			A->fix[n++] = A->fix[i];
	}
	L->in = A->fix;
	L->nin = n;
	A->fix = NULL;
}

int csf_parloop_analyse(const csf_prog *p, int sec, uint32_t pc, csf_parloop *L)
{
	const uint32_t *code = p->code[sec];
	memset(L, 0, sizeof *L);
	if (code[pc] != CSF_OP_LOOP || code[pc + 1] != 1) return 0;
	uint32_t from = pc + csf_insn_len(CSF_OP_LOOP), end = code[pc + 3], to = end - csf_insn_len(CSF_OP_NEXT);
	if (end - pc > PAR_MAX_WORDS) return 0;
	ana A = { .code = code, .ok = 1 };
	collect_priv(&A, from, to);
	A.words = A.npriv / 64 + 1;
	if (A.ok && !(A.d = calloc(A.words, sizeof *A.d))) A.ok = 0;
	uint64_t work = 0;
	if (A.ok) walk(&A, from, to, code[pc + 2], &work);
	if (A.ok && !independent(&A)) A.ok = 0;
	if (A.ok) spans_in(&A, L);
	if (A.ok && A.nwr && !(L->out = malloc(A.nwr * sizeof *L->out))) A.ok = 0;
	if (A.ok) {
		L->pc = pc;
		L->end = end;
		L->count = code[pc + 2];
		L->work = work;
		for (uint32_t i = 0; i < A.nwr; i++) L->out[i] = (csf_cell){ A.wr[i].base, A.wr[i].stride, A.wr[i].width };
		L->nout = A.nwr;
		L->priv = A.priv;
		L->npriv = A.npriv;
		A.priv = NULL;
	}
	for (uint32_t i = 0; i < A.npend; i++) free(A.pend[i].d);
	free(A.pend);
	free(A.d);
	free(A.rd);
	free(A.wr);
	free(A.fix);
	free(A.priv);
	if (!A.ok) csf_parloop_free(L);
	return A.ok;
}

void csf_parloop_free(csf_parloop *L)
{
	free(L->in);
	free(L->out);
	free(L->priv);
	memset(L, 0, sizeof *L);
}
