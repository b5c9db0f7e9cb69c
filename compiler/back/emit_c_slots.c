/*
 * emit_c_slots.c - where each slot of the program lives in its C
 * translation (state, derivative, constant, local or memory: emit_c.c's
 * opening comment): what the runtime sees, what code writes, what it may
 * read before writing; and where each section splits into functions.
 */
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "emit_c_int.h"

/* Instructions per generated function: C compilers slow down on huge functions. */
#define CHUNK 4000

/* Keeps L up to date past the instruction at pc. */
void track_loops(Loops *L, const uint32_t *code, uint32_t pc)
{
	if (code[pc] == CSF_OP_LOOP && L->depth < CSF_LOOP_MAX) {
		L->depth++;
		L->count[L->depth] = code[pc + 2];
		L->next[L->depth] = code[pc + 3] - csf_insn_len(CSF_OP_NEXT); /* the pc of its NEXT */
	} else if (code[pc] == CSF_OP_NEXT && L->depth > 0)
		L->depth--;
}

/* The slots [*lo, *hi) operand word w of width wd reaches under the loops L. */
static void extent(const Loops *L, uint32_t w, uint32_t wd, uint32_t *lo, uint32_t *hi)
{
	uint32_t r = csf_reg(w), level = csf_reg_level(r);
	*lo = w & CSF_SLOT_MASK;
	*hi = (uint32_t)csf_operand_end(w, wd, r && level <= (uint32_t)L->depth ? L->count[level] : 1);
}

static void mark_ext(Slots *S, uint32_t s, uint32_t w)
{
	for (uint32_t k = 0; k < w && s + k < S->n; k++) S->ext[s + k] = 1;
}

/* Pass 1: what the runtime sees, what code writes and reaches through loop indices, how vectors lie. */
static void scan_slots(Slots *S)
{
	const csf_prog *p = S->p;
	mark_ext(S, p->tslot, 1);
	if (p->jtan) {
		mark_ext(S, p->tslot + p->jtan, 1);
		mark_ext(S, p->ystart + p->jtan, p->ny);
		mark_ext(S, p->dstart + p->jtan, p->ny);
	}
	for (uint32_t i = 0; i < p->ncols; i++) mark_ext(S, p->cols[i].slot, 1);
	for (uint32_t i = 0; i < p->nevents; i++) {
		mark_ext(S, p->events[i].value, 1);
		mark_ext(S, p->events[i].mode, 1);
	}
	for (uint32_t i = 0; i < p->nwhens; i++) mark_ext(S, p->whens[i].fire, 1), mark_ext(S, p->whens[i].prev, 1);
	for (uint32_t i = 0; i < p->ncbodies; i++)
		for (int k = 0; k < CSF_CF_N; k++) mark_ext(S, p->cbodies[i].s[k], 3);
	for (uint32_t i = 0; i < p->ncons; i++) {
		const csf_con *c = &p->cons[i];
		mark_ext(S, c->g, 1), mark_ext(S, c->gd, 1), mark_ext(S, c->c, 1), mark_ext(S, c->scale, 1), mark_ext(S, c->cr, 1), mark_ext(S, c->want, 1);
	}
	for (uint32_t i = 0; i < p->nconbodies; i++) {
		const csf_conbody *b = &p->conbodies[i];
		mark_ext(S, b->J, 3), mark_ext(S, b->pos, 3), mark_ext(S, b->v, 3), mark_ext(S, b->a, 3);
		mark_ext(S, b->m, 1), mark_ext(S, b->fc, 3);
	}
	/* what -D can set is read from m, not compiled in as a literal */
	for (uint32_t i = 0; i < p->nprops; i++)
		if (!*csf_str(p, p->pclasses[p->props[i].cls].why)) mark_ext(S, p->props[i].slot, p->props[i].width);
	for (uint32_t i = 0; i < p->nglobals; i++)
		if (!*csf_str(p, p->pclasses[p->globals[i].cls].why)) mark_ext(S, p->globals[i].slot, p->globals[i].width);
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		const uint32_t *code = p->code[sec];
		Loops L = { .depth = 0 };
		for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			if (code[pc] == CSF_OP_CONTACT || code[pc] == CSF_OP_CONSTRAIN) S->direct = 0;
			for (int k = 0; k < oi->nops; k++) {
				if (!csf_kind_slot(oi->kind[k])) continue;
				uint32_t w = code[pc + 1 + k], wd = csf_kind_width(oi->kind[k]), lo, hi;
				extent(&L, w, wd, &lo, &hi);
				if (region(p, lo) != region(p, hi - 1) || (csf_kind_write(oi->kind[k]) && region(p, lo) == C_STATE))
					S->direct = 0;
				for (uint32_t s = lo; s < hi && s < S->n; s++) {
					if (csf_kind_write(oi->kind[k])) S->written[s] = 1;
					if (csf_reg(w)) S->rel[s] = 1;
				}
				if (wd == 3 && !csf_reg(w))
					for (uint32_t s = lo; s < hi && s < S->n; s++)
						S->vb[s] = S->vb[s] == 0 || S->vb[s] == lo + 1 ? lo + 1 : UINT32_MAX;
			}
			track_loops(&L, code, pc);
		}
	}
}

/*
 * The split points of section sec into functions: starts[0] = 0, then
 * line-table entries (a statement's code) after about CHUNK instructions
 * where no loop or jump spans (a goto cannot leave its function).
 * Returns the number of functions; starts[that] = the section's end.
 */
static uint32_t split_section(const csf_prog *p, int sec, uint32_t **starts)
{
	uint32_t n = p->ncode[sec];
	const uint32_t *code = p->code[sec];
	long *span = xcalloc((size_t)n + 2, sizeof *span); /* +1 where a span starts, -1 past its end */
	uint32_t *st = xmalloc(((size_t)p->nlines[sec] + 2) * sizeof *st), ns = 0;
	for (uint32_t pc = 0; pc < n; pc += csf_insn_len(code[pc])) {
		uint32_t op = code[pc], to;
		if (op == CSF_OP_LOOP) to = code[pc + 3] - 1;
		else if (op == CSF_OP_JMP) to = code[pc + 1];
		else if (op == CSF_OP_JZ) to = code[pc + 2];
		else if (op == CSF_OP_JEQ) to = code[pc + 3];
		else continue;
		span[pc + 1]++;
		span[to + 1]--;
	}
	long open = 0;
	for (uint32_t pc = 0; pc <= n; pc++) span[pc] = (open += span[pc]) > 0; /* now: no split at pc */
	st[ns++] = 0;
	uint32_t count = 0, li = 0;
	for (uint32_t pc = 0; pc < n; pc += csf_insn_len(code[pc]), count++) {
		while (li < p->nlines[sec] && p->lines[sec][li].pc < pc) li++;
		if (count >= CHUNK && !span[pc] && li < p->nlines[sec] && p->lines[sec][li].pc == pc) {
			st[ns++] = pc;
			count = 0;
		}
	}
	st[ns] = n;
	free(span);
	*starts = st;
	return ns;
}

/*
 * The incoming state at a jump target, two sets of nw words: the candidates
 * every jump there surely wrote, in the section and in the function.
 */
static void meet(uint64_t **pend, uint32_t from, uint32_t to, uint32_t t, const uint64_t *cur, uint32_t nw, int live)
{
	if (!live || t < from || t > to) return;
	uint64_t **q = &pend[t - from];
	if (!*q) {
		*q = xmalloc((2 * nw + 1) * sizeof **q);
		memcpy(*q, cur, 2 * nw * sizeof **q);
	} else
		for (uint32_t i = 0; i < 2 * nw; i++) (*q)[i] &= cur[i];
}

/*
 * Pass 2, for the function [from, to) of section sec, run on the section's
 * functions in order: marks bad every slot that may be read before the
 * section wrote it, following the code's paths (forward jumps meet at
 * their targets; a loop body runs at least once when its count is not 0),
 * and cross in sec a slot read in this function but written in an earlier
 * one (memory carries it from one to the next). Only slots named without
 * a loop index, in memory or derivatives and not seen by the runtime, are
 * followed (the candidates for locals); a derivative read before it is
 * written is read from memory, and the program is not direct. sofar[s]:
 * the section surely wrote s before this function (the state where the
 * previous function ended: no jump crosses from one to the next); idx is
 * all UINT32_MAX on entry and exit.
 */
static void check_reads(Slots *S, int sec, uint32_t from, uint32_t to, uint32_t *idx, unsigned char *sofar)
{
	const csf_prog *p = S->p;
	const uint32_t *code = p->code[sec];
	uint32_t nc = 0, cap = 64, *cand = xmalloc(cap * sizeof *cand);
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = code[pc + 1 + k];
			if (!csf_kind_slot(oi->kind[k]) || csf_reg(w)) continue;
			for (uint32_t s = w; s < w + csf_kind_width(oi->kind[k]) && s < S->n; s++) {
				if (idx[s] != UINT32_MAX || S->ext[s] || region(p, s) == C_STATE) continue;
				if (nc == cap) cand = xrealloc(cand, (cap *= 2) * sizeof *cand);
				idx[s] = nc;
				cand[nc++] = s;
			}
		}
	}
	/* cur[0, nw): written in the section; cur[nw, 2 nw): written in this function */
	uint32_t nw = (nc + 63) / 64;
	uint64_t *cur = xcalloc(2 * nw + 1, sizeof *cur), **pend = xcalloc((size_t)(to - from) + 1, sizeof *pend);
	for (uint32_t i = 0; i < nc; i++)
		if (sofar[cand[i]]) cur[i / 64] |= 1ull << (i % 64);
	int live = 1;
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		uint64_t *in = pend[pc - from];
		if (in) {
			for (uint32_t i = 0; i < 2 * nw; i++) cur[i] = live ? cur[i] & in[i] : in[i];
			live = 1;
			free(in);
		}
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int pass = 0; pass < 2; pass++) /* the reads, then the writes */
			for (int k = 0; k < oi->nops; k++) {
				uint32_t w = code[pc + 1 + k];
				if (!csf_kind_slot(oi->kind[k]) || csf_reg(w) || csf_kind_write(oi->kind[k]) != pass) continue;
				for (uint32_t s = w; s < w + csf_kind_width(oi->kind[k]) && s < S->n; s++) {
					uint32_t i = idx[s];
					if (i == UINT32_MAX) continue;
					uint64_t bit = 1ull << (i % 64);
					if (pass) {
						cur[i / 64] |= bit;
						cur[nw + i / 64] |= bit;
					} else if (live && !(cur[i / 64] & bit)) {
						S->bad[s] = 1;
						if (region(p, s) == C_DERIV) S->direct = 0;
					} else if (live && !(cur[nw + i / 64] & bit))
						S->cross[s] |= (unsigned char)(1u << sec);
				}
			}
		switch (code[pc]) {
		case CSF_OP_JMP:
			meet(pend, from, to, code[pc + 1], cur, nw, live);
			live = 0;
			break;
		case CSF_OP_JZ: meet(pend, from, to, code[pc + 2], cur, nw, live); break;
		case CSF_OP_JEQ: meet(pend, from, to, code[pc + 3], cur, nw, live); break;
		case CSF_OP_LOOP:
			if (code[pc + 2] == 0) meet(pend, from, to, code[pc + 3], cur, nw, live);
			break;
		}
	}
	if (pend[to - from]) { /* the function's end: where the next one starts */
		for (uint32_t i = 0; i < nw; i++) cur[i] = live ? cur[i] & pend[to - from][i] : pend[to - from][i];
		free(pend[to - from]);
	}
	for (uint32_t i = 0; i < nc; i++) {
		if (cur[i / 64] >> (i % 64) & 1) sofar[cand[i]] = 1;
		idx[cand[i]] = UINT32_MAX;
	}
	free(pend);
	free(cur);
	free(cand);
}

/* Pass 3: each slot's class (see the top of the file). */
static void classify(Slots *S)
{
	const csf_prog *p = S->p;
	for (uint32_t s = 0; s < S->n; s++) {
		int r = region(p, s);
		if (r != C_MEM) S->cls[s] = S->direct ? (unsigned char)r : C_MEM;
		else if (S->ext[s]) S->cls[s] = C_MEM;
		else if (!S->written[s]) S->cls[s] = s < p->nmem && isfinite(p->mem0[s]) ? C_CONST : C_MEM;
		else if (S->rel[s] || S->bad[s] || S->vb[s] == UINT32_MAX) S->cls[s] = C_MEM;
		else S->cls[s] = S->vb[s] ? C_VLOCAL : C_LOCAL;
	}
	/* a vector local is all three slots, or none */
	for (uint32_t s = 0; s < S->n; s++) {
		if (S->cls[s] != C_VLOCAL) continue;
		uint32_t b = S->vb[s] - 1;
		for (uint32_t k = 0; k < 3; k++)
			if (b + k >= S->n || S->cls[b + k] != C_VLOCAL || S->vb[b + k] != b + 1) S->cls[s] = C_MEM;
	}
	/* and in memory in a section when one of its slots goes from function to function there */
	for (uint32_t s = 0; s < S->n; s++)
		if (S->cls[s] == C_VLOCAL && S->vb[s] == s + 1) {
			unsigned char c = S->cross[s] | S->cross[s + 1] | S->cross[s + 2];
			S->cross[s] = S->cross[s + 1] = S->cross[s + 2] = c;
		}
}

/* The highest slot any operand names, plus one (at least nmem). */
static uint32_t slots_named(const csf_prog *p)
{
	uint32_t n = p->nmem;
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		const uint32_t *code = p->code[sec];
		Loops L = { .depth = 0 };
		for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			for (int k = 0; k < oi->nops; k++) {
				uint32_t lo, hi;
				if (!csf_kind_slot(oi->kind[k])) continue;
				extent(&L, code[pc + 1 + k], csf_kind_width(oi->kind[k]), &lo, &hi);
				if (hi > n) n = hi;
			}
			track_loops(&L, code, pc);
		}
	}
	return n;
}

void slots_analyse(Slots *S, const csf_prog *p, uint32_t **starts, uint32_t *nfn)
{
	*S = (Slots){ .p = p, .n = slots_named(p), .direct = 1 };
	S->ext = xcalloc(S->n + 1, 1);
	S->written = xcalloc(S->n + 1, 1);
	S->rel = xcalloc(S->n + 1, 1);
	S->bad = xcalloc(S->n + 1, 1);
	S->cross = xcalloc(S->n + 1, 1);
	unsigned char *sofar = xcalloc(S->n + 1, 1);
	S->cls = xcalloc(S->n + 1, 1);
	S->vb = xcalloc(S->n + 1, sizeof *S->vb);
	uint32_t *idx = xmalloc(((size_t)S->n + 1) * sizeof *idx);
	memset(idx, 0xff, ((size_t)S->n + 1) * sizeof *idx);
	scan_slots(S);
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		nfn[sec] = split_section(p, sec, &starts[sec]);
		memset(sofar, 0, S->n + 1);
		for (uint32_t i = 0; i < nfn[sec]; i++) check_reads(S, sec, starts[sec][i], starts[sec][i + 1], idx, sofar);
	}
	classify(S);
	free(idx);
	free(sofar);
}

void slots_free(Slots *S)
{
	free(S->ext);
	free(S->written);
	free(S->rel);
	free(S->bad);
	free(S->cross);
	free(S->cls);
	free(S->vb);
}
