/*
 * block.c - the loops the VM runs a block at a time (block.h).
 *
 * One pass over each section keeps the loops open at each pc (their
 * levels and counts). At a LOOP whose body holds no other loop and no
 * control flow but a leading JEQ to its NEXT, the body's slot operands are
 * listed in the order they are reached (an instruction reads all its
 * operands before it writes), each with its footprint over the loops
 * around it: a fixed slot's its own slots, a slot through the loop's index
 * every slot it reaches over the count, a slot through an outer loop's
 * index every slot it reaches over that loop's count.
 *
 * A region of fixed slots is a temporary when the first operand to reach
 * it writes it, only fixed operands reach it, and every read of it is of
 * slots written earlier in the iteration (a slot reused for a scalar, then
 * for a vector, is one region of three slots: temporaries()). Then,
 * outside the temporaries, the block runs instruction b of iteration j
 * before instruction a < b of iteration j' > j, where the serial loop ran
 * them the other way round: every such pair of footprints must be apart,
 * or both through the index within one cell (the same stride, both within
 * one stride: they meet only within an iteration), or nothing is written.
 * Pairs within one instruction keep their order.
 */
#include <stdlib.h>
#include <string.h>

#include "block.h"
#include "insn.h"

/* A body longer than this stays an iteration at a time (the pairs of operands are quadratic in it). */
enum { BLOCK_MAX_INSNS = 128, BLOCK_MIN = 4 }; /* BLOCK_MIN: the fewest indices a block may take */

enum { A_FIX, A_OUTER, A_IDX }; /* a fixed slot; through an outer loop's index; through the loop's */
typedef struct acc {
	uint32_t insn, write, kind, base, width, stride, temp; /* temp: 1 + its index in the temporaries, or 0 */
	uint64_t lo, hi;                                        /* the footprint */
} acc;

/* Is op control flow (a CTRL row of opcodes.def)? */
static int is_ctrl(uint32_t op)
{
	switch (op) {
#define OP(name, n, a, b, c, d, syn)
#define CTRL(name, n, a, b, c, d, syn) case CSF_OP_##name:
#include "opcodes.def"
#undef CTRL
#undef OP
		return 1;
	default: return 0;
	}
}

static int overlap(uint64_t a0, uint64_t a1, uint64_t b0, uint64_t b1) { return a0 < b1 && b0 < a1; }

/* Do the footprints of x and y, run by different iterations, never meet? */
static int apart(const acc *x, const acc *y)
{
	if (!overlap(x->lo, x->hi, y->lo, y->hi)) return 1;
	if (x->kind != A_IDX || y->kind != A_IDX || x->stride != y->stride) return 0;
	uint32_t lo = x->base < y->base ? x->base : y->base;
	uint64_t hi = x->base + (uint64_t)x->width > y->base + (uint64_t)y->width ? x->base + (uint64_t)x->width
	                                                                          : y->base + (uint64_t)y->width;
	return hi - lo <= x->stride;
}

/* The slot operands of the body's instructions [from, to) in the order reached, into a (room for 4 per instruction). */
static uint32_t accesses(const uint32_t *code, uint32_t from, uint32_t to, uint32_t level, const uint32_t *cnt, acc *a,
                         int *ok)
{
	uint32_t n = 0, t = 0;
	for (uint32_t q = from; q < to; q += csf_insn_len(code[q]), t++) {
		const csf_opinfo *oi = &csf_opinfo_table[code[q]];
		for (uint32_t pass = 0; pass < 2; pass++)
			for (int k = 0; k < oi->nops; k++) {
				int kind = oi->kind[k];
				if (!csf_kind_slot(kind) || (uint32_t)csf_kind_write(kind) != pass) continue;
				uint32_t w = code[q + 1 + k], r = csf_reg(w), lv = csf_reg_level(r), width = csf_kind_width(kind);
				if (r >= CSF_NREGS || lv > level) { /* not a loop around it (the verifier lets none through) */
					*ok = 0;
					return n;
				}
				acc x = { t, pass, !r ? A_FIX : lv < level ? A_OUTER : A_IDX, w & CSF_SLOT_MASK, width,
				          csf_reg_stride(r), 0, w & CSF_SLOT_MASK, csf_operand_end(w, width, cnt[lv]) };
				a[n++] = x;
			}
	}
	return n;
}

/*
 * Is every slot that read a[r] reaches written, in this iteration, by a
 * write among a[0..r) of the region [lo, hi)? (Accesses are listed in the
 * order reached: an instruction's reads before its writes.)
 */
static int covered(const acc *a, uint32_t r, uint64_t lo, uint64_t hi)
{
	for (uint64_t s = a[r].lo; s < a[r].hi; s++) {
		int w = 0;
		for (uint32_t j = 0; j < r && !w; j++)
			w = a[j].write && a[j].kind == A_FIX && a[j].lo >= lo && a[j].hi <= hi && a[j].lo <= s && s < a[j].hi;
		if (!w) return 0;
	}
	return 1;
}

/*
 * Marks the temporaries among a[0..n) (temp = 1 + their index), into tmp;
 * returns their number. A temporary is a region of fixed slots that only
 * fixed operands reach and that each iteration writes before it reads: the
 * union of the footprints that overlap, begun by a write (the compiler
 * reuses a slot for a scalar, then for a vector: one region of three
 * slots), in which every read is of slots written earlier in the
 * iteration.
 */
static uint32_t temporaries(acc *a, uint32_t n, csf_btemp *tmp)
{
	uint32_t nt = 0;
	for (uint32_t i = 0; i < n; i++) {
		acc *x = &a[i];
		if (x->temp || x->kind != A_FIX || !x->write) continue;
		uint64_t lo = x->lo, hi = x->hi;
		int ok = 1, grew = 1;
		while (grew && ok) { /* the region: every footprint that meets it, until none is added */
			grew = 0;
			for (uint32_t j = 0; j < n && ok; j++) {
				const acc *y = &a[j];
				if (!overlap(lo, hi, y->lo, y->hi)) continue;
				if (y->kind != A_FIX || y->temp) ok = 0;
				if (y->lo < lo) lo = y->lo, grew = 1;
				if (y->hi > hi) hi = y->hi, grew = 1;
			}
		}
		/* none reaches it before this write, and every read is of slots written before it */
		for (uint32_t j = 0; j < n && ok; j++)
			if (overlap(lo, hi, a[j].lo, a[j].hi) && (j < i || (!a[j].write && !covered(a, j, lo, hi)))) ok = 0;
		if (!ok) continue;
		tmp[nt] = (csf_btemp){ (uint32_t)lo, (uint32_t)(hi - lo), 0 };
		nt++;
		for (uint32_t j = i; j < n; j++)
			if (overlap(lo, hi, a[j].lo, a[j].hi)) a[j].temp = nt;
	}
	return nt;
}

/* Analyses the LOOP at pc (level, count cnt[level]; the loops around it in cnt). 1: *L filled (free its arrays). */
static int analyse(const uint32_t *code, uint32_t pc, const uint32_t *cnt, csf_bloop *L)
{
	uint32_t level = code[pc + 1], from = pc + csf_insn_len(CSF_OP_LOOP), end = code[pc + 3];
	uint32_t to = end - csf_insn_len(CSF_OP_NEXT), skip = 0, ninsn = 0;
	if (code[to] != CSF_OP_NEXT || code[to + 1] != level || code[to + 2] != from) return 0;
	if (code[from] == CSF_OP_JEQ && code[from + 3] == to) {
		uint32_t l1 = code[from + 1], l2 = code[from + 2];
		skip = l1 == level ? l2 : l2 == level ? l1 : 0;
		if (!skip || skip >= level) return 0;
		from += csf_insn_len(CSF_OP_JEQ);
	}
	for (uint32_t q = from; q < to; q += csf_insn_len(code[q]), ninsn++)
		if (is_ctrl(code[q]) || ninsn >= BLOCK_MAX_INSNS) return 0;
	acc *a = malloc((4 * (size_t)ninsn + 1) * sizeof *a);
	csf_btemp *tmp = malloc((4 * (size_t)ninsn + 1) * sizeof *tmp);
	csf_binsn *insn = malloc(((size_t)ninsn + 1) * sizeof *insn);
	int ok = a && tmp && insn;
	uint32_t n = ok ? accesses(code, from, to, level, cnt, a, &ok) : 0, nt = ok ? temporaries(a, n, tmp) : 0, width = 0;
	for (uint32_t i = 0; i < n && ok; i++)
		for (uint32_t j = i + 1; j < n && ok; j++)
			if (a[i].insn != a[j].insn && !a[i].temp && !a[j].temp && (a[i].write || a[j].write) && !apart(&a[i], &a[j]))
				ok = 0;
	for (uint32_t i = 0; i < nt; i++) width += tmp[i].width;
	uint32_t block = width ? CSF_BLOCK_SCRATCH / width : CSF_BLOCK;
	if (block > CSF_BLOCK) block = CSF_BLOCK;
	if (block < BLOCK_MIN) ok = 0;
	for (uint32_t i = 0, off = 0; i < nt && ok; i++) {
		tmp[i].off = off;
		off += block * tmp[i].width;
	}
	/* The instructions with their operands' modes: the accesses were listed reads first, then writes. */
	uint32_t ai = 0, t = 0;
	for (uint32_t q = from; q < to && ok; q += csf_insn_len(code[q]), t++) {
		const csf_opinfo *oi = &csf_opinfo_table[code[q]];
		csf_binsn *b = &insn[t];
		b->op = code[q];
		for (int k = 0; k < 4; k++) b->o[k] = (csf_bopnd){ CSF_BM_IMM, k < oi->nops ? code[q + 1 + k] : 0, 0 };
		for (uint32_t pass = 0; pass < 2; pass++)
			for (int k = 0; k < oi->nops; k++) {
				if (!csf_kind_slot(oi->kind[k]) || (uint32_t)csf_kind_write(oi->kind[k]) != pass) continue;
				const acc *x = &a[ai++];
				if (x->temp) { /* at its place in its region's copy for the index */
					const csf_btemp *tp = &tmp[x->temp - 1];
					b->o[k] = (csf_bopnd){ CSF_BM_TMP, tp->off + (x->base - tp->slot), tp->width };
				} else if (x->kind == A_IDX) b->o[k] = (csf_bopnd){ CSF_BM_IDX, x->base, x->stride };
				else b->o[k] = (csf_bopnd){ CSF_BM_FIX, code[q + 1 + k], 0 };
			}
	}
	free(a);
	if (!ok) {
		free(tmp);
		free(insn);
		return 0;
	}
	*L = (csf_bloop){ pc, end, level, skip, block, insn, ninsn, tmp, nt };
	return 1;
}

/* The blocked loops of section sec into b. 0, or -1 when memory ran out. */
static int section(const csf_prog *p, int sec, csf_blocks *b)
{
	const uint32_t *code = p->code[sec];
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0 }, ends[CSF_LOOP_MAX + 1] = { 0 }, depth = 0;
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		while (depth && pc >= ends[depth]) depth--;
		if (code[pc] != CSF_OP_LOOP) continue;
		uint32_t level = code[pc + 1], inner = 0;
		if (level != depth + 1) return 0; /* (verified code nests its loops in order) */
		depth = level;
		cnt[level] = code[pc + 2];
		ends[level] = code[pc + 3];
		for (uint32_t q = pc + csf_insn_len(CSF_OP_LOOP); q < ends[level] && !inner; q += csf_insn_len(code[q]))
			inner = code[q] == CSF_OP_LOOP;
		csf_bloop L;
		if (inner || !analyse(code, pc, cnt, &L)) continue;
		csf_bloop *a = realloc(b->loops[sec], (b->nloops[sec] + 1) * sizeof *a);
		if (!a) {
			free(L.insn);
			free(L.tmp);
			return -1;
		}
		b->loops[sec] = a;
		a[b->nloops[sec]++] = L;
	}
	return 0;
}

csf_blocks *csf_blocks_new(const csf_prog *p)
{
	csf_blocks *b = calloc(1, sizeof *b);
	if (!b) return NULL;
	uint32_t n = 0;
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		if (section(p, sec, b)) {
			csf_blocks_free(b);
			return NULL;
		}
		n += b->nloops[sec];
	}
	if (!n) {
		csf_blocks_free(b);
		return NULL;
	}
	return b;
}

void csf_blocks_free(csf_blocks *b)
{
	if (!b) return;
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		for (uint32_t i = 0; i < b->nloops[sec]; i++) {
			free(b->loops[sec][i].insn);
			free(b->loops[sec][i].tmp);
		}
		free(b->loops[sec]);
	}
	free(b);
}

const csf_bloop *csf_blocks_find(const csf_blocks *b, int sec, uint32_t pc)
{
	if (!b) return NULL;
	uint32_t i = csf_find_pc(b->loops[sec], b->nloops[sec], sizeof *b->loops[sec], pc);
	return i < b->nloops[sec] ? &b->loops[sec][i] : NULL;
}
