/*
 * emit_c.c - translates a compiled program (bytecode) to C.
 *
 * The C is a translation of the bytecode, instruction by instruction, not a
 * second compiler from the AST: every instruction becomes a call of the
 * function the VM's case calls (csf_op_NAME of csf_ops.h, a function of
 * plain values) on its operands, jumps become gotos, assertions returns, a
 * LOOP ... NEXT a for statement over its own index variable. What changes
 * is where the operands live. The VM keeps every value in the model's
 * memory m; here each slot is one of
 *
 *   state, derivative  GSL's arrays y and dydt, read and written directly
 *                      (unless a section needs them in m: see direct below);
 *   constant           a slot no code writes and the runtime never sees (nor
 *                      -D sets): a literal, printed so that it reads back
 *                      to the same double;
 *   local              a slot only code writes and reads, always written
 *                      before it is read within one C function, never
 *                      through a loop index, and never seen by the runtime:
 *                      a C local (double, or csf_vec for a vector), which
 *                      gcc keeps in a register;
 *   memory             everything else: m[slot], or m[base + i] for an array
 *                      read through a loop index.
 *
 * The runtime sees t, the columns, the events' values and modes, the
 * contact bodies' slots and the Jacobian's tangents of t, the state and
 * the derivatives: those stay in m. When a value must be named after a
 * non-finite result, the driver re-runs the section on the VM, which
 * stores every value (csf_exec_fn, csf.h).
 *
 * The program's tables travel as the bytecode image itself, embedded as a
 * byte array and loaded by the same loader csfvm uses; the integrator
 * driver, output and diagnostics are libcsfrt's. So the executable and
 * csfvm print the same bytes.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csfc.h"
#include "emit_c.h"

extern char **environ;

static void comment(FILE *f, const char *s)
{
	fputs("/* ", f);
	for (; *s; s++) {
		if (s[0] == '*' && s[1] == '/') {
			fputs("* /", f);
			s++;
			continue;
		}
		fputc(*s, f);
	}
	fputs(" */", f);
}

/* Instructions per generated function: C compilers slow down on huge functions. */
#define CHUNK 4000

static uint32_t insn_len(const uint32_t *code, uint32_t pc) { return 1u + csf_opinfo_table[code[pc]].nops; }

/* Operand kinds that name slots (and may be relative to a loop register: csf_operand). */
static int slot_kind(int kind) { return kind == CSF_K_DS || kind == CSF_K_DV || kind == CSF_K_S || kind == CSF_K_V; }
static int write_kind(int kind) { return kind == CSF_K_DS || kind == CSF_K_DV; }
static uint32_t kind_width(int kind) { return kind == CSF_K_DV || kind == CSF_K_V ? 3 : 1; }

/* ---- where each slot lives ---- */

enum { C_MEM, C_STATE, C_DERIV, C_CONST, C_LOCAL, C_VLOCAL };

typedef struct Slots {
	const csf_prog *p;
	uint32_t n;             /* slots described: nmem, or more for a program that names more */
	unsigned char *ext;     /* the runtime reads or writes it */
	unsigned char *written; /* some code writes it */
	unsigned char *rel;     /* some code reaches it through a loop index */
	unsigned char *bad;     /* some code may read it before its section wrote it */
	unsigned char *cross;   /* bit sec: section sec writes it in one function, reads it in a later one */
	uint32_t *vb;           /* 1 + the slot of the vector accesses covering it; UINT32_MAX: two differ */
	unsigned char *cls;     /* C_*, from the above */
	int direct;             /* state and derivatives in y and dydt: no code writes the state, none
	                           reads a derivative it did not write, no CONTACT, no array across regions */
} Slots;

static int region(const csf_prog *p, uint32_t s)
{
	if (s >= p->ystart && s < p->ystart + p->ny) return C_STATE;
	if (s >= p->dstart && s < p->dstart + p->ny) return C_DERIV;
	return C_MEM;
}

/* The loops open at an instruction: their counts by level, for the extent of relative operands. */
typedef struct Loops { uint32_t count[CSF_LOOP_MAX + 1], next[CSF_LOOP_MAX + 1]; int depth; } Loops;

/* Keeps L up to date past the instruction at pc. */
static void track_loops(Loops *L, const uint32_t *code, uint32_t pc)
{
	if (code[pc] == CSF_OP_LOOP && L->depth < CSF_LOOP_MAX) {
		L->depth++;
		L->count[L->depth] = code[pc + 2];
		L->next[L->depth] = code[pc + 3] - 3; /* the pc of its NEXT (3 words) */
	} else if (code[pc] == CSF_OP_NEXT && L->depth > 0)
		L->depth--;
}

/* The slots [*lo, *hi) operand word w of width wd reaches under the loops L. */
static void extent(const Loops *L, uint32_t w, uint32_t wd, uint32_t *lo, uint32_t *hi)
{
	uint32_t r = csf_reg(w), base = w & CSF_SLOT_MASK, level = (r + 1) / 2;
	uint32_t n = r && level <= (uint32_t)L->depth ? L->count[level] : 1, stride = r % 2 ? 1 : 3;
	*lo = base;
	*hi = base + (n ? (n - 1) * (r ? stride : 0) : 0) + wd;
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
	for (uint32_t i = 0; i < p->ncbodies; i++)
		for (int k = 0; k < CSF_CF_N; k++) mark_ext(S, p->cbodies[i].s[k], 3);
	/* what -D can set is read from m, not compiled in as a literal */
	for (uint32_t i = 0; i < p->nprops; i++)
		if (!*csf_str(p, p->pclasses[p->props[i].cls].why)) mark_ext(S, p->props[i].slot, p->props[i].width);
	for (uint32_t i = 0; i < p->nglobals; i++)
		if (!*csf_str(p, p->pclasses[p->globals[i].cls].why)) mark_ext(S, p->globals[i].slot, p->globals[i].width);
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		const uint32_t *code = p->code[sec];
		Loops L = { .depth = 0 };
		for (uint32_t pc = 0; pc < p->ncode[sec]; pc += insn_len(code, pc)) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			if (code[pc] == CSF_OP_CONTACT) S->direct = 0;
			for (int k = 0; k < oi->nops; k++) {
				if (!slot_kind(oi->kind[k])) continue;
				uint32_t w = code[pc + 1 + k], wd = kind_width(oi->kind[k]), lo, hi;
				extent(&L, w, wd, &lo, &hi);
				if (region(p, lo) != region(p, hi - 1) || (write_kind(oi->kind[k]) && region(p, lo) == C_STATE))
					S->direct = 0;
				for (uint32_t s = lo; s < hi && s < S->n; s++) {
					if (write_kind(oi->kind[k])) S->written[s] = 1;
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
	long *span = calloc((size_t)n + 2, sizeof *span); /* +1 where a span starts, -1 past its end */
	uint32_t *st = malloc(((size_t)p->nlines[sec] + 2) * sizeof *st), ns = 0;
	if (!span || !st) exit(2);
	for (uint32_t pc = 0; pc < n; pc += insn_len(code, pc)) {
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
	for (uint32_t pc = 0; pc < n; pc += insn_len(code, pc), count++) {
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
		*q = malloc((2 * nw + 1) * sizeof **q);
		if (!*q) exit(2);
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
	uint32_t nc = 0, cap = 64, *cand = malloc(cap * sizeof *cand);
	if (!cand) exit(2);
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = code[pc + 1 + k];
			if (!slot_kind(oi->kind[k]) || csf_reg(w)) continue;
			for (uint32_t s = w; s < w + kind_width(oi->kind[k]) && s < S->n; s++) {
				if (idx[s] != UINT32_MAX || S->ext[s] || region(p, s) == C_STATE) continue;
				if (nc == cap && !(cand = realloc(cand, (cap *= 2) * sizeof *cand))) exit(2);
				idx[s] = nc;
				cand[nc++] = s;
			}
		}
	}
	/* cur[0, nw): written in the section; cur[nw, 2 nw): written in this function */
	uint32_t nw = (nc + 63) / 64;
	uint64_t *cur = calloc(2 * nw + 1, sizeof *cur), **pend = calloc((size_t)(to - from) + 1, sizeof *pend);
	if (!cur || !pend) exit(2);
	for (uint32_t i = 0; i < nc; i++)
		if (sofar[cand[i]]) cur[i / 64] |= 1ull << (i % 64);
	int live = 1;
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) {
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
				if (!slot_kind(oi->kind[k]) || csf_reg(w) || write_kind(oi->kind[k]) != pass) continue;
				for (uint32_t s = w; s < w + kind_width(oi->kind[k]) && s < S->n; s++) {
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

/* ---- the C of one function ---- */

typedef struct Emit {
	Slots *S;
	const csf_prog *p;
	FILE *f;              /* the function's body */
	int sec;              /* the section being written */
	uint32_t fn;          /* 1 + the function's number, for decl */
	uint32_t *decl;       /* decl[s] == fn: slot s's local is declared in this function */
	uint32_t *loc, nloc, caploc; /* those locals (a vector's by its first slot) */
	uint32_t *readin;     /* readin[s] == fn: this function reads slot s (named without a loop index) */
	int used_m, used_y, used_d, used_p;
	Loops L;
	unsigned char *target; /* a goto jumps there */
} Emit;

/* Slot s's class in the section being written: a local that goes from function to function there is in memory. */
static int slot_class(const Emit *E, uint32_t s)
{
	const Slots *S = E->S;
	int c = s < S->n ? S->cls[s] : C_MEM;
	return (c == C_LOCAL || c == C_VLOCAL) && S->cross[s] >> E->sec & 1 ? C_MEM : c;
}

static void indent(Emit *E) { fprintf(E->f, "%.*s", E->L.depth + 1, "\t\t\t\t\t"); }

static void use_local(Emit *E, uint32_t s)
{
	if (E->decl[s] == E->fn) return;
	E->decl[s] = E->fn;
	if (E->nloc == E->caploc && !(E->loc = realloc(E->loc, (E->caploc = E->caploc ? 2 * E->caploc : 64) * sizeof *E->loc)))
		exit(2);
	E->loc[E->nloc++] = s;
}

/* A double as a C literal that reads back to it (finite x only). */
static void put_literal(FILE *f, double x)
{
	char b[40];
	csf_fmt_double(b, x);
	if (!strpbrk(b, ".e")) strcat(b, ".0");
	fprintf(f, signbit(x) ? "(%s)" : "%s", b);
}

/* The array that holds region r's slots, and the slot its element 0 is. */
static const char *array_of(Emit *E, int r, uint32_t *first)
{
	const csf_prog *p = E->p;
	if (r == C_STATE && E->S->direct) {
		E->used_y = 1;
		*first = p->ystart;
		return "y";
	}
	if (r == C_DERIV && E->S->direct) {
		E->used_d = 1;
		*first = p->dstart;
		return "dydt";
	}
	E->used_m = 1;
	*first = 0;
	return "m";
}

/* A loop index term: "i1", or "3u * i1" for the register of three times it. */
static void put_index(FILE *f, uint32_t r) { fprintf(f, "%si%lu", r % 2 ? "" : "3u * ", (unsigned long)(r + 1) / 2); }

/* "ARRAY + OFFSET" or "ARRAY[OFFSET" of a slot operand word (absolute or relative), the index included. */
static void put_place(Emit *E, uint32_t w, int element)
{
	uint32_t base = w & CSF_SLOT_MASK, first, r = csf_reg(w);
	const char *a = array_of(E, region(E->p, base), &first);
	fprintf(E->f, element ? "%s[%luu" : "%s + %luu", a, (unsigned long)(base - first));
	if (r) {
		fputs(" + ", E->f);
		put_index(E->f, r);
	}
	if (element) fputc(']', E->f);
}

/* Scalar slot s, named without a loop index, as a C expression (an lvalue unless a constant). */
static void put_slot(Emit *E, uint32_t s)
{
	const Slots *S = E->S;
	int c = slot_class(E, s);
	if (c == C_CONST) {
		put_literal(E->f, E->p->mem0[s]);
	} else if (c == C_LOCAL) {
		use_local(E, s);
		fprintf(E->f, "r%lu", (unsigned long)s);
	} else if (c == C_VLOCAL) {
		uint32_t b = S->vb[s] - 1;
		use_local(E, b);
		fprintf(E->f, "v%lu.%c", (unsigned long)b, "xyz"[s - b]);
	} else
		put_place(E, s, 1);
}

/* How the vector at slot b (no loop index) is reached: as a vector local, as three slots of one array, or slot by slot. */
enum { V_LOCAL, V_ARRAY, V_SLOTS };
static int vector_way(const Emit *E, uint32_t b)
{
	const Slots *S = E->S;
	if (b + 2 >= S->n) return V_ARRAY;
	int c = slot_class(E, b);
	if (c == C_VLOCAL && S->vb[b] == b + 1) return V_LOCAL;
	if ((c == C_MEM || c == C_STATE || c == C_DERIV) && slot_class(E, b + 1) == c && slot_class(E, b + 2) == c &&
	    region(E->p, b) == region(E->p, b + 2))
		return V_ARRAY;
	return V_SLOTS;
}

/* Operand word w of kind kind, read, as a C expression. */
static void put_read(Emit *E, int kind, uint32_t w)
{
	if (kind == CSF_K_N) {
		fprintf(E->f, "%d", csf_imm(w));
		return;
	}
	if (kind == CSF_K_S) {
		if (csf_reg(w)) put_place(E, w, 1);
		else put_slot(E, w);
		return;
	}
	int way = csf_reg(w) ? V_ARRAY : vector_way(E, w);
	if (way == V_LOCAL) {
		use_local(E, w);
		fprintf(E->f, "v%lu", (unsigned long)w);
	} else if (way == V_ARRAY) {
		fputs("csf_vload(", E->f);
		put_place(E, w, 0);
		fputc(')', E->f);
	} else {
		fputs("csf_v(", E->f);
		for (uint32_t k = 0; k < 3; k++) {
			if (k) fputs(", ", E->f);
			put_slot(E, w + k);
		}
		fputc(')', E->f);
	}
}

/* Is the result of an instruction writing operand w of kind kind a local this function never reads? */
static int dead_local(const Emit *E, int kind, uint32_t w)
{
	if (csf_reg(w)) return 0;
	for (uint32_t k = 0; k < kind_width(kind); k++) {
		int c = slot_class(E, w + k);
		if ((c != C_LOCAL && c != C_VLOCAL) || E->readin[w + k] == E->fn) return 0;
	}
	return 1;
}

/* An instruction with a result: DEST = csf_op_NAME(operands); */
static void emit_op(Emit *E, const uint32_t *a, const csf_opinfo *oi)
{
	uint32_t w = a[0];
	int vec = oi->kind[0] == CSF_K_DV, way = !vec ? -1 : csf_reg(w) ? V_ARRAY : vector_way(E, w);
	if (!vec) {
		if (csf_reg(w)) put_place(E, w, 1);
		else put_slot(E, w);
		fputs(" = ", E->f);
	} else if (way == V_LOCAL) {
		use_local(E, w);
		fprintf(E->f, "v%lu = ", (unsigned long)w);
	} else if (way == V_ARRAY) {
		fputs("csf_vstore(", E->f);
		put_place(E, w, 0);
		fputs(", ", E->f);
	} else {
		fputs("{\n", E->f);
		indent(E);
		fputs("\tcsf_vec w = ", E->f);
	}
	fprintf(E->f, "csf_op_%s(", oi->name);
	for (int k = 1; k < oi->nops; k++) {
		if (k > 1) fputs(", ", E->f);
		put_read(E, oi->kind[k], a[k]);
	}
	fputs(way == V_ARRAY ? "));\n" : ");\n", E->f);
	if (way == V_SLOTS) {
		for (uint32_t k = 0; k < 3; k++) {
			indent(E);
			fputc('\t', E->f);
			put_slot(E, w + k);
			fprintf(E->f, " = w.%c;\n", "xyz"[k]);
		}
		indent(E);
		fputs("}\n", E->f);
	}
}

/* A jump to target t: continue when t is the innermost loop's NEXT, else goto. */
static int is_continue(const Loops *L, uint32_t t) { return L->depth > 0 && t == L->next[L->depth]; }

static void put_jump(Emit *E, uint32_t t)
{
	if (is_continue(&E->L, t)) fputs("continue;\n", E->f);
	else fprintf(E->f, "goto L%lu;\n", (unsigned long)t);
}

/* The instruction at pc as C. */
static void emit_insn(Emit *E, const uint32_t *code, uint32_t pc)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
	const uint32_t *a = code + pc + 1; /* only the instruction's own operands: a CONTACT has none */
	if (code[pc] == CSF_OP_NEXT) {
		if (E->target[pc]) fprintf(E->f, "L%lu: ;\n", (unsigned long)pc); /* a label needs a statement */
		track_loops(&E->L, code, pc);
		indent(E);
		fputs("}\n", E->f);
		return;
	}
	if (E->target[pc]) fprintf(E->f, "L%lu:\n", (unsigned long)pc);
	indent(E);
	switch (code[pc]) {
	case CSF_OP_JMP:
		put_jump(E, a[0]);
		return;
	case CSF_OP_JZ:
		fputs("if (", E->f);
		put_read(E, CSF_K_S, a[0]);
		fputs(" == 0.0) ", E->f);
		put_jump(E, a[1]);
		return;
	case CSF_OP_JEQ:
		fprintf(E->f, "if (i%lu == i%lu) ", (unsigned long)a[0], (unsigned long)a[1]);
		put_jump(E, a[2]);
		return;
	case CSF_OP_ASSERT:
		fputs("if (", E->f);
		put_read(E, CSF_K_S, a[0]);
		if (csf_reg(a[1])) {
			fprintf(E->f, " == 0.0) return (int)(%luu + ", (unsigned long)(a[1] & CSF_SLOT_MASK));
			put_index(E->f, csf_reg(a[1]));
			fputs(");\n", E->f);
		} else
			fprintf(E->f, " == 0.0) return %lu;\n", (unsigned long)a[1]);
		return;
	case CSF_OP_CONTACT:
		E->used_p = E->used_m = 1;
		fputs("csf_contact_apply(p, m);\n", E->f);
		return;
	case CSF_OP_LOOP: { /* a count of 0 runs no iteration, as the VM's jump to the end */
		unsigned long l = a[0];
		fprintf(E->f, "for (uint32_t i%lu = 0; i%lu < %luu; i%lu++) {\n", l, l, (unsigned long)a[1], l);
		track_loops(&E->L, code, pc);
		return;
	}
	}
	if (dead_local(E, oi->kind[0], a[0])) fputs("/* a value no one reads */;\n", E->f);
	else emit_op(E, a, oi);
}

/* Marks the targets of the function [from, to) that need a label (every jump but a continue). */
static void mark_targets(const uint32_t *code, uint32_t from, uint32_t to, unsigned char *target)
{
	Loops L = { .depth = 0 };
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) {
		uint32_t t = code[pc] == CSF_OP_JMP ? code[pc + 1] : code[pc] == CSF_OP_JZ ? code[pc + 2]
		           : code[pc] == CSF_OP_JEQ ? code[pc + 3] : UINT32_MAX;
		if (t != UINT32_MAX && !is_continue(&L, t)) target[t] = 1;
		track_loops(&L, code, pc);
	}
}

/* The parameters of a section's functions. */
static const char *params(const Slots *S)
{
	return S->direct ? "const csf_prog *p, double *m, const double *y, double *dydt" : "const csf_prog *p, double *m";
}

/*
 * Writes the function name of the code [from, to) of section sec: the
 * locals it uses declared first, a comment with each statement's source
 * line above its code.
 */
static void emit_function(Emit *E, int sec, uint32_t from, uint32_t to, const char *name, const char *qual)
{
	const csf_prog *p = E->p;
	const uint32_t *code = p->code[sec];
	char *body;
	size_t blen;
	FILE *out = E->f;
	E->f = open_memstream(&body, &blen);
	if (!E->f) exit(2);
	E->sec = sec;
	E->fn++;
	E->nloc = 0;
	E->used_m = E->used_y = E->used_d = E->used_p = 0;
	memset(&E->L, 0, sizeof E->L);
	mark_targets(code, from, to, E->target);
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = code[pc + 1 + k];
			if (slot_kind(oi->kind[k]) && !write_kind(oi->kind[k]) && !csf_reg(w))
				for (uint32_t q = 0; q < kind_width(oi->kind[k]) && w + q < E->S->n; q++) E->readin[w + q] = E->fn;
		}
	}
	uint32_t li = 0;
	while (li < p->nlines[sec] && p->lines[sec][li].pc < from) li++;
	for (uint32_t pc = from; pc < to; pc += insn_len(code, pc)) {
		for (; li < p->nlines[sec] && p->lines[sec][li].pc == pc; li++) {
			const csf_src *s = &p->srcs[p->lines[sec][li].src];
			indent(E);
			comment(E->f, xprintf("%s:%lu: %s", csf_str(p, p->files[s->file]), (unsigned long)s->line, csf_str(p, s->text)));
			fputc('\n', E->f);
		}
		emit_insn(E, code, pc);
	}
	if (E->target[to]) fprintf(E->f, "L%lu:\n", (unsigned long)to);
	fclose(E->f);
	E->f = out;
	memset(E->target + from, 0, (size_t)(to - from) + 1);

	fprintf(out, "%s int %s(%s)\n{\n", qual, name, params(E->S));
	for (int vec = 0; vec < 2; vec++) {
		int first = 1;
		for (uint32_t i = 0; i < E->nloc; i++) {
			uint32_t s = E->loc[i];
			if ((E->S->cls[s] == C_VLOCAL) != vec) continue;
			fprintf(out, "%s%c%lu", first ? vec ? "\tcsf_vec " : "\tdouble " : ", ", vec ? 'v' : 'r', (unsigned long)s);
			first = 0;
		}
		if (!first) fputs(";\n", out);
	}
	if (!E->used_p) fputs("\t(void)p;\n", out);
	if (!E->used_m) fputs("\t(void)m;\n", out);
	if (E->S->direct && !E->used_y) fputs("\t(void)y;\n", out);
	if (E->S->direct && !E->used_d) fputs("\t(void)dydt;\n", out);
	fwrite(body, 1, blen, out);
	fputs("\treturn -1;\n}\n\n", out);
	free(body);
}

/*
 * Section sec as the function fname, a csf_exec_fn's section: its code
 * whole, or (a long section) split into functions fname_0, fname_1, ...
 * called in order, with the state and derivatives copied into and out of
 * m when the program is not direct.
 */
static void emit_section(Emit *E, int sec, const char *fname, uint32_t *const *starts, const uint32_t *nfn)
{
	const csf_prog *p = E->p;
	const char *sig = "const csf_prog *p, double *m, const double *y, double *dydt";
	if (E->S->direct && nfn[sec] == 1) {
		emit_function(E, sec, 0, p->ncode[sec], fname, "static");
		return;
	}
	for (uint32_t i = 0; i < nfn[sec]; i++)
		emit_function(E, sec, starts[sec][i], starts[sec][i + 1], xprintf("%s_%lu", fname, (unsigned long)i), "CSF_FN");
	fprintf(E->f, "static int %s(%s)\n{\n\tint r = -1;\n", fname, sig);
	if (!E->S->direct)
		fprintf(E->f, "\tif (y != m + %luu) memcpy(m + %luu, y, %luu * sizeof *y);\n", (unsigned long)p->ystart,
		        (unsigned long)p->ystart, (unsigned long)p->ny);
	for (uint32_t i = 0; i < nfn[sec]; i++)
		fprintf(E->f, "\tif (r < 0) r = %s_%lu(p, m%s);\n", fname, (unsigned long)i, E->S->direct ? ", y, dydt" : "");
	if (!E->S->direct)
		fprintf(E->f, "\tif (dydt != m + %luu) memcpy(dydt, m + %luu, %luu * sizeof *dydt);\n", (unsigned long)p->dstart,
		        (unsigned long)p->dstart, (unsigned long)p->ny);
	else
		fputs("\t(void)y;\n\t(void)dydt;\n", E->f);
	fputs("\treturn r;\n}\n\n", E->f);
}

/* The highest slot any operand names, plus one (at least nmem). */
static uint32_t slots_named(const csf_prog *p)
{
	uint32_t n = p->nmem;
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		const uint32_t *code = p->code[sec];
		Loops L = { .depth = 0 };
		for (uint32_t pc = 0; pc < p->ncode[sec]; pc += insn_len(code, pc)) {
			const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
			for (int k = 0; k < oi->nops; k++) {
				uint32_t lo, hi;
				if (!slot_kind(oi->kind[k])) continue;
				extent(&L, code[pc + 1 + k], kind_width(oi->kind[k]), &lo, &hi);
				if (hi > n) n = hi;
			}
			track_loops(&L, code, pc);
		}
	}
	return n;
}

/*
 * The bytecode image as a string literal of exactly len bytes (C drops the
 * terminating NUL that does not fit), which a C compiler reads several
 * times faster than a list of numbers: printable bytes as themselves,
 * the others as three-digit octal escapes (never followed by a digit that
 * would join them).
 */
static void put_image(FILE *f, const unsigned char *image, size_t len)
{
	fprintf(f, "static const unsigned char csf_model_image[%zu] =\n\t\"", len);
	for (size_t i = 0, col = 0; i < len; i++) {
		int c = image[i];
		if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\' && c != '?') {
			fputc(c, f);
			col++;
		} else {
			fprintf(f, "\\%03o", (unsigned)c);
			col += 4;
		}
		if (col >= 76 && i + 1 < len) {
			fputs("\"\n\t\"", f);
			col = 0;
		}
	}
	fputs("\";\n\n", f);
}

void emit_c(const csf_prog *p, const unsigned char *image, size_t len, const char *model, FILE *f)
{
	static const char *const names[CSF_NSEC] = { "csf_model_rhs", "csf_model_out", "csf_model_jac" };
	Slots S = { .p = p, .n = slots_named(p), .direct = 1 };
	S.ext = calloc(S.n + 1, 1);
	S.written = calloc(S.n + 1, 1);
	S.rel = calloc(S.n + 1, 1);
	S.bad = calloc(S.n + 1, 1);
	S.cross = calloc(S.n + 1, 1);
	unsigned char *sofar = calloc(S.n + 1, 1);
	S.cls = calloc(S.n + 1, 1);
	S.vb = calloc(S.n + 1, sizeof *S.vb);
	uint32_t *idx = malloc(((size_t)S.n + 1) * sizeof *idx), *starts[CSF_NSEC], nfn[CSF_NSEC];
	if (!S.ext || !S.written || !S.rel || !S.bad || !S.cross || !sofar || !S.cls || !S.vb || !idx) exit(2);
	memset(idx, 0xff, ((size_t)S.n + 1) * sizeof *idx);
	scan_slots(&S);
	for (int sec = 0; sec < CSF_NSEC; sec++) {
		nfn[sec] = split_section(p, sec, &starts[sec]);
		memset(sofar, 0, S.n + 1);
		for (uint32_t i = 0; i < nfn[sec]; i++) check_reads(&S, sec, starts[sec][i], starts[sec][i + 1], idx, sofar);
	}
	classify(&S);

	fputs("/*\n * Generated by csfc --emit-c from ", f);
	fputs(model, f);
	fputs(".\n * Each function is one code section of the model's bytecode, translated\n"
	      " * instruction by instruction into calls of csf_ops.h; the embedded image\n"
	      " * carries its tables.\n"
	      " * Build: cc -O2 -ffp-contract=off model.c $(pkg-config --cflags --libs csfrt)\n */\n",
	      f);
	fputs("#include <string.h>\n\n#include \"csf.h\"\n\n"
	      "#if defined(__GNUC__)\n#define CSF_FN static __attribute__((noinline))\n#else\n#define CSF_FN static\n#endif\n\n",
	      f);
	put_image(f, image, len);
	Emit E = { .S = &S, .p = p, .f = f };
	E.decl = calloc(S.n + 1, sizeof *E.decl);
	E.readin = calloc(S.n + 1, sizeof *E.readin);
	uint32_t maxcode = 0;
	for (int sec = 0; sec < CSF_NSEC; sec++)
		if (p->ncode[sec] > maxcode) maxcode = p->ncode[sec];
	E.target = calloc((size_t)maxcode + 1, 1);
	if (!E.decl || !E.readin || !E.target) exit(2);
	for (int sec = 0; sec < CSF_NSEC; sec++) emit_section(&E, sec, names[sec], starts, nfn);
	fputs("static int csf_model_exec(const csf_prog *p, int sec, double *m, const double *y, double *dydt)\n{\n"
	      "\treturn sec == CSF_SEC_RHS ? csf_model_rhs(p, m, y, dydt)\n"
	      "\t     : sec == CSF_SEC_OUT ? csf_model_out(p, m, y, dydt)\n"
	      "\t                          : csf_model_jac(p, m, y, dydt);\n}\n\n"
	      "int main(int argc, char **argv)\n{\n"
	      "\treturn csf_main(argc, argv, csf_model_image, sizeof csf_model_image, csf_model_exec);\n}\n",
	      f);
	for (int sec = 0; sec < CSF_NSEC; sec++) free(starts[sec]);
	free(E.decl);
	free(E.readin);
	free(E.target);
	free(E.loc);
	free(idx);
	free(S.ext);
	free(S.written);
	free(S.rel);
	free(S.bad);
	free(S.cross);
	free(sofar);
	free(S.cls);
	free(S.vb);
}

/* Directory of the running csfc. */
static char *exe_dir(void)
{
	char exe[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n <= 0) return xstrdup(".");
	exe[n] = '\0';
	char *slash = strrchr(exe, '/');
	if (slash) *slash = '\0';
	return xstrdup(exe);
}

/* Finds the runtime's header and library: installed (../include/csf, ../lib) or in the build tree. */
static int find_runtime(char **inc, char **lib)
{
	char *d = exe_dir();
	const char *incs[] = { "%s/../include/csf", "%s/../runtime" };
	const char *libs[] = { "%s/../lib", "%s" };
	for (int i = 0; i < 2; i++) {
		char *ic = xprintf(incs[i], d), *lc = xprintf(libs[i], d);
		if (access(xprintf("%s/csf.h", ic), R_OK) == 0 && access(xprintf("%s/libcsfrt.a", lc), R_OK) == 0) {
			*inc = ic;
			*lib = lc;
			return 0;
		}
	}
	return -1;
}

/* Splits s at blanks into argv entries appended to a. */
static void split_words(Vec *a, const char *s)
{
	while (s && *s) {
		while (*s == ' ' || *s == '\t') s++;
		const char *e = s;
		while (*e && *e != ' ' && *e != '\t') e++;
		if (e > s) vec_push(a, xstrndup(s, (size_t)(e - s)));
		s = e;
	}
}

/*
 * Warns of the C compiler flags in a->v[first..] that let it compute other
 * floating-point results than csf_ops.h's IEEE operations in their order.
 */
static void warn_inexact(const Vec *a, int first)
{
	static const char *const inexact[] = { "-ffast-math", "-Ofast", "-funsafe-math-optimizations", "-fassociative-math",
		                               "-freciprocal-math", "-ffinite-math-only", "-fno-signed-zeros", "-mfpmath=387",
		                               NULL };
	for (int i = first; i < a->n; i++)
		for (int k = 0; inexact[k]; k++)
			if (strcmp(a->v[i], inexact[k]) == 0)
				fprintf(stderr,
				        "csfc: warning: CFLAGS %s lets the C compiler change floating-point results: the "
				        "executable's output may differ from csfvm's\n",
				        inexact[k]);
}

int emit_c_executable(const char *csource, const char *out)
{
	char *inc, *lib;
	if (find_runtime(&inc, &lib)) {
		fprintf(stderr, "csfc: cannot find the CSF runtime (csf.h and libcsfrt.a) next to csfc\n");
		return 2;
	}
	const char *cc = getenv("CC");
	const char *cflags = getenv("CFLAGS");
	Vec a = { 0 };
	split_words(&a, cc && *cc ? cc : "cc");
	int first = a.n;
	split_words(&a, cflags);
	if (a.n == first) split_words(&a, "-O2"); /* CFLAGS unset or blank */
	warn_inexact(&a, first);
	vec_push(&a, "-ffp-contract=off"); /* last: it overrides a -ffp-contract of CFLAGS */
	vec_push(&a, xprintf("-I%s", inc));
	vec_push(&a, (void *)csource);
	vec_push(&a, "-o");
	vec_push(&a, (void *)out);
	vec_push(&a, xprintf("-L%s", lib));
	vec_push(&a, "-lcsfrt");
	vec_push(&a, "-lgsl");
	vec_push(&a, "-lgslcblas");
	vec_push(&a, "-lm");
	vec_push(&a, NULL);
	pid_t pid;
	int st = posix_spawnp(&pid, a.v[0], NULL, NULL, (char **)a.v, environ);
	if (st) {
		fprintf(stderr, "csfc: cannot run %s: %s\n", (char *)a.v[0], strerror(st));
		return 2;
	}
	int ws;
	while (waitpid(pid, &ws, 0) < 0)
		if (errno != EINTR) return 2;
	if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
		fprintf(stderr, "csfc: the C compiler failed to build %s\n", out);
		return 2;
	}
	return 0;
}
