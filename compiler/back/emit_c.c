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
 * And for the time of one loop, a sum that its body adds into an outer
 * loop's element (the force on body i1 over every i2) is a local
 * accumulator, loaded before the loop and stored after it
 * (find_accumulators).
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
 *
 * This file writes the C text; emit_c_slots.c decides where each slot
 * lives (emit_c_int.h), cc.c runs the C compiler on the result.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "emit_c.h"
#include "emit_c_int.h"
#include "parloop.h"

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

/* ---- the C of one function ---- */

enum { ACC_MAX = 8 }; /* accumulators a loop may keep in locals */

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
	uint64_t *par;        /* par[pc] > 0: the level-1 loop at pc is the function NAME_parPC, its work + 1 */
	uint32_t par_pc;      /* the function being written is that of the loop at par_pc (UINT32_MAX: none) */
	struct { uint32_t w, pc; int vec; } acc[CSF_LOOP_MAX + 1][ACC_MAX]; /* the loops' accumulators (accumulators) */
	uint32_t nacc[CSF_LOOP_MAX + 1];                                       /* by the depth of their loop */
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
	if (E->nloc == E->caploc) E->loc = xrealloc(E->loc, (E->caploc = E->caploc ? 2 * E->caploc : 64) * sizeof *E->loc);
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
static void put_index(FILE *f, uint32_t r)
{
	fprintf(f, "%si%lu", csf_reg_stride(r) == 3 ? "3u * " : "", (unsigned long)csf_reg_level(r));
}

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

/* 1 + the instruction of the accumulator that operand word w is in a loop open now, else 0. */
static uint32_t is_acc(const Emit *E, uint32_t w)
{
	if (!csf_reg(w)) return 0;
	for (int d = 1; d <= E->L.depth; d++)
		for (uint32_t k = 0; k < E->nacc[d]; k++)
			if (E->acc[d][k].w == w) return E->acc[d][k].pc + 1;
	return 0;
}

/* Writes the local of the accumulator that operand word w is, if it is one. */
static int put_acc(Emit *E, uint32_t w)
{
	uint32_t a = is_acc(E, w);
	if (a) fprintf(E->f, "a%lu", (unsigned long)(a - 1));
	return a != 0;
}

/* Operand word w of kind kind, read, as a C expression. */
static void put_read(Emit *E, int kind, uint32_t w)
{
	if (kind != CSF_K_N && put_acc(E, w)) return;
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
	for (uint32_t k = 0; k < csf_kind_width(kind); k++) {
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
	if (put_acc(E, w)) {
		fputs(" = ", E->f);
		way = V_LOCAL;
	} else if (!vec) {
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

/*
 * The accumulators of the loop at pc, at depth d: operand words that one
 * instruction of the body writes (and may read) through the index of an
 * outer loop, which no other operand of the body reaches, such as the sum
 * of the forces on body i1 over the inner loop's i2. Each is kept in a local
 * of the function, loaded before the loop and stored after it, where the
 * bytecode loads and stores it at every iteration: the same operations in
 * the same order, so the same bits, without a store and a load through
 * memory that the C compiler cannot prove apart from the body's other
 * reads (and that a thread sharing m may have to fetch again). The body
 * may not jump out of itself, return (ASSERT) or call the runtime (CONTACT,
 * CONSTRAIN), which reads m. Sets E->nacc[d]; returns it.
 */
static uint32_t find_accumulators(Emit *E, const uint32_t *code, uint32_t pc, int d)
{
	uint32_t next = code[pc + 3] - csf_insn_len(CSF_OP_NEXT), n = 0;
	Loops L = E->L;
	E->nacc[d] = 0;
	for (uint32_t q = pc; q < next; q += csf_insn_len(code[q])) {
		uint32_t op = code[q], t = op == CSF_OP_JMP ? code[q + 1] : op == CSF_OP_JZ ? code[q + 2]
		                          : op == CSF_OP_JEQ ? code[q + 3] : pc;
		if (op == CSF_OP_ASSERT || op == CSF_OP_CONTACT || op == CSF_OP_CONSTRAIN || t < pc || t > next) return 0;
		const csf_opinfo *oi = &csf_opinfo_table[op];
		uint32_t w = code[q + 1], r = csf_reg(w);
		if (op == CSF_OP_LOOP || op == CSF_OP_NEXT || !oi->nops || !csf_kind_write(oi->kind[0]) || !r ||
		    csf_reg_level(r) >= (uint32_t)d || n == ACC_MAX || is_acc(E, w))
			continue;
		E->acc[d][n].w = w, E->acc[d][n].pc = q, E->acc[d][n].vec = oi->kind[0] == CSF_K_DV;
		n++;
	}
	/* each candidate: every other operand of the body (its own instruction's reads of the same word aside) apart from it */
	uint32_t keep = 0;
	for (uint32_t k = 0; k < n; k++) {
		uint32_t w = E->acc[d][k].w, wd = E->acc[d][k].vec ? 3 : 1, ok = 1;
		uint32_t lo = w & CSF_SLOT_MASK, lv = csf_reg_level(csf_reg(w));
		uint64_t hi = csf_operand_end(w, wd, L.count[lv]);
		Loops M = L;
		for (uint32_t q = pc; q <= next && ok; q += csf_insn_len(code[q])) {
			const csf_opinfo *oi = &csf_opinfo_table[code[q]];
			track_loops(&M, code, q);
			if (code[q] == CSF_OP_LOOP || code[q] == CSF_OP_NEXT) continue;
			for (int j = 0; j < oi->nops && ok; j++) {
				uint32_t v = code[q + 1 + j], rv = csf_reg(v), lvv = csf_reg_level(rv);
				if (!csf_kind_slot(oi->kind[j])) continue;
				if (q == E->acc[d][k].pc && v == w && csf_kind_width(oi->kind[j]) == wd) continue;
				uint64_t vlo = v & CSF_SLOT_MASK,
				         vhi = csf_operand_end(v, csf_kind_width(oi->kind[j]), rv && lvv <= (uint32_t)M.depth ? M.count[lvv] : 1);
				ok = vhi <= lo || vlo >= hi;
			}
		}
		if (ok) E->acc[d][keep++] = E->acc[d][k];
	}
	return E->nacc[d] = keep;
}

/* The instruction at pc as C. */
static void emit_insn(Emit *E, const uint32_t *code, uint32_t pc)
{
	const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
	const uint32_t *a = code + pc + 1; /* only the instruction's own operands: a CONTACT has none */
	if (code[pc] == CSF_OP_NEXT) {
		if (E->target[pc]) fprintf(E->f, "L%lu: ;\n", (unsigned long)pc); /* a label needs a statement */
		int d = E->L.depth;
		track_loops(&E->L, code, pc);
		indent(E);
		fputs("}\n", E->f);
		if (d > 0 && E->nacc[d]) {
			for (uint32_t k = 0; k < E->nacc[d]; k++) {
				indent(E);
				fputs(E->acc[d][k].vec ? "\tcsf_vstore(" : "\t", E->f);
				put_place(E, E->acc[d][k].w, !E->acc[d][k].vec);
				fprintf(E->f, E->acc[d][k].vec ? ", a%lu);\n" : " = a%lu;\n", (unsigned long)E->acc[d][k].pc);
			}
			E->nacc[d] = 0;
			indent(E);
			fputs("}\n", E->f);
		}
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
		fputs("csf_contact_apply(p, x, m);\n", E->f);
		return;
	case CSF_OP_CONSTRAIN:
		E->used_p = E->used_m = 1;
		fputs("csf_constraint_apply(p, x, m);\n", E->f);
		return;
	case CSF_OP_LOOP: { /* a count of 0 runs no iteration, as the VM's jump to the end */
		unsigned long l = a[0];
		int d = E->L.depth + 1;
		if (pc != E->par_pc && d <= CSF_LOOP_MAX && find_accumulators(E, code, pc, d)) {
			fputs("{\n", E->f);
			for (uint32_t k = 0; k < E->nacc[d]; k++) {
				indent(E);
				fprintf(E->f, E->acc[d][k].vec ? "\tcsf_vec a%lu = csf_vload(" : "\tdouble a%lu = ",
				        (unsigned long)E->acc[d][k].pc);
				put_place(E, E->acc[d][k].w, !E->acc[d][k].vec);
				fputs(E->acc[d][k].vec ? ");\n" : ";\n", E->f);
			}
			indent(E);
		}
		if (pc == E->par_pc)
			fputs("for (uint32_t i1 = lo; i1 < hi; i1++) {\n", E->f);
		else
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
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		uint32_t t = code[pc] == CSF_OP_JMP ? code[pc + 1] : code[pc] == CSF_OP_JZ ? code[pc + 2]
		           : code[pc] == CSF_OP_JEQ ? code[pc + 3] : UINT32_MAX;
		if (t != UINT32_MAX && !is_continue(&L, t)) target[t] = 1;
		track_loops(&L, code, pc);
	}
}

/* The parameters of a section's functions (a loop's for the threads: csf_par_fn). */
static const char *params(const Emit *E)
{
	return E->par_pc != UINT32_MAX ? "const csf_prog *p, const csf_exec_ctx *x, double *m, const double *y, double *dydt, "
	                                 "uint32_t lo, uint32_t hi"
	     : E->S->direct ? "const csf_prog *p, const csf_exec_ctx *x, double *m, const double *y, double *dydt"
	                    : "const csf_prog *p, const csf_exec_ctx *x, double *m";
}

/* The call of the function of the level-1 loop at pc of section fname, which the threads may share. */
static void emit_par_call(Emit *E, const char *fname, uint32_t pc)
{
	const uint32_t *code = E->p->code[E->sec];
	E->used_p = E->used_m = 1;
	E->used_y = E->used_d = E->S->direct;
	indent(E);
	fprintf(E->f, "csf_par_for(p, x, %lluu, %luu, %s_par%lu, m, %s);\n", (unsigned long long)(E->par[pc] - 1),
	        (unsigned long)code[pc + 2], fname, (unsigned long)pc, E->S->direct ? "y, dydt" : "0, 0");
}

/* Is fixed slot s read by section sec's code outside [from, to)? */
static int read_outside(const csf_prog *p, int sec, uint32_t from, uint32_t to, uint32_t s)
{
	const uint32_t *code = p->code[sec];
	uint32_t cnt[CSF_LOOP_MAX + 1] = { 0 }; /* the counts of the loops open, by level */
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(code[pc])) {
		if (code[pc] == CSF_OP_LOOP) cnt[code[pc + 1]] = code[pc + 2];
		if (pc >= from && pc < to) continue;
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = code[pc + 1 + k], r = csf_reg(w);
			uint64_t end = csf_operand_end(w, csf_kind_width(oi->kind[k]), r ? cnt[csf_reg_level(r)] : 1);
			if (csf_kind_slot(oi->kind[k]) && !csf_kind_write(oi->kind[k]) && s >= (w & CSF_SLOT_MASK) && s < end) return 1;
		}
	}
	return 0;
}

/*
 * The work of the level-1 loop at pc of the section being written when it
 * becomes a function of its own that threads may share (csf_par_for), or
 * 0: its iterations are independent (csf_parloop_analyse), the slots each
 * writes for itself are locals of that function, read nowhere else, and
 * the other locals of the section are not read in it. Its workers then
 * share m, y and dydt.
 */
static uint64_t par_loop(Emit *E, uint32_t pc)
{
	const csf_prog *p = E->p;
	const uint32_t *code = p->code[E->sec];
	csf_parloop L;
	if (code[pc] != CSF_OP_LOOP || !csf_parloop_analyse(p, E->sec, pc, &L)) return 0;
	int ok = 1;
	for (uint32_t i = 0; i < L.npriv && ok; i++) {
		int c = slot_class(E, L.priv[i]);
		ok = (c == C_LOCAL || c == C_VLOCAL) && !read_outside(p, E->sec, pc, L.end, L.priv[i]);
	}
	for (uint32_t q = pc; q < L.end && ok; q += csf_insn_len(code[q])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[q]];
		for (int k = 0; k < oi->nops && ok; k++) {
			uint32_t w = code[q + 1 + k];
			if (!csf_kind_slot(oi->kind[k]) || csf_reg(w)) continue;
			for (uint32_t j = 0; j < csf_kind_width(oi->kind[k]) && ok; j++) {
				int c = slot_class(E, w + j);
				if (c != C_LOCAL && c != C_VLOCAL) continue;
				ok = csf_parloop_own(&L, w + j); /* a local the loop writes, and the whole vector its local holds */
				for (uint32_t d = 0; d < 3 && ok && c == C_VLOCAL; d++) ok = csf_parloop_own(&L, E->S->vb[w + j] - 1 + d);
			}
		}
	}
	uint64_t work = ok ? (L.work ? L.work : 1) : 0;
	csf_parloop_free(&L);
	return work < UINT64_MAX ? work : UINT64_MAX - 1;
}

/*
 * Writes the function name of the code [from, to) of section sec: the
 * locals it uses declared first, a comment with each statement's source
 * line above its code.
 */
static void emit_function(Emit *E, int sec, uint32_t from, uint32_t to, const char *name, const char *qual,
                          const char *fname)
{
	const csf_prog *p = E->p;
	const uint32_t *code = p->code[sec];
	char *body;
	size_t blen;
	FILE *out = E->f;
	E->f = open_memstream(&body, &blen);
	if (!E->f) xoom(); /* open_memstream fails only for want of memory */
	E->sec = sec;
	E->fn++;
	E->nloc = 0;
	E->used_m = E->used_y = E->used_d = E->used_p = 0;
	memset(&E->L, 0, sizeof E->L);
	mark_targets(code, from, to, E->target);
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		const csf_opinfo *oi = &csf_opinfo_table[code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t w = code[pc + 1 + k];
			if (csf_kind_slot(oi->kind[k]) && !csf_kind_write(oi->kind[k]) && !csf_reg(w))
				for (uint32_t q = 0; q < csf_kind_width(oi->kind[k]) && w + q < E->S->n; q++) E->readin[w + q] = E->fn;
		}
	}
	uint32_t li = 0;
	while (li < p->nlines[sec] && p->lines[sec][li].pc < from) li++;
	for (uint32_t pc = from; pc < to; pc += csf_insn_len(code[pc])) {
		for (; li < p->nlines[sec] && p->lines[sec][li].pc == pc; li++) {
			const csf_src *s = &p->srcs[p->lines[sec][li].src];
			indent(E);
			comment(E->f, xprintf("%s:%lu: %s", csf_str(p, p->files[s->file]), (unsigned long)s->line, csf_str(p, s->text)));
			fputc('\n', E->f);
		}
		if (E->par[pc] && pc != E->par_pc) {
			if (E->target[pc]) fprintf(E->f, "L%lu:\n", (unsigned long)pc);
			emit_par_call(E, fname, pc);
			pc = code[pc + 3] - csf_insn_len(CSF_OP_NEXT);
			continue;
		}
		emit_insn(E, code, pc);
	}
	if (E->target[to]) fprintf(E->f, "L%lu:\n", (unsigned long)to);
	fclose(E->f);
	E->f = out;
	memset(E->target + from, 0, (size_t)(to - from) + 1);

	fprintf(out, "%s int %s(%s)\n{\n", qual, name, params(E));
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
	if (!E->used_p) fputs("\t(void)p;\n\t(void)x;\n", out);
	if (!E->used_m) fputs("\t(void)m;\n", out);
	int ydydt = E->S->direct || E->par_pc != UINT32_MAX;
	if (ydydt && !E->used_y) fputs("\t(void)y;\n", out);
	if (ydydt && !E->used_d) fputs("\t(void)dydt;\n", out);
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
	const char *sig = "const csf_prog *p, const csf_exec_ctx *x, double *m, const double *y, double *dydt";
	memset(E->par, 0, ((size_t)p->ncode[sec] + 1) * sizeof *E->par);
	E->sec = sec;
	for (uint32_t pc = 0; pc < p->ncode[sec]; pc += csf_insn_len(p->code[sec][pc])) {
		uint64_t work = par_loop(E, pc);
		if (!work) continue;
		E->par_pc = pc;
		E->par[pc] = work + 1;
		emit_function(E, sec, pc, p->code[sec][pc + 3], xprintf("%s_par%lu", fname, (unsigned long)pc), "CSF_FN", fname);
		E->par_pc = UINT32_MAX;
	}
	if (E->S->direct && nfn[sec] == 1) {
		emit_function(E, sec, 0, p->ncode[sec], fname, "static", fname);
		return;
	}
	for (uint32_t i = 0; i < nfn[sec]; i++)
		emit_function(E, sec, starts[sec][i], starts[sec][i + 1], xprintf("%s_%lu", fname, (unsigned long)i), "CSF_FN",
		              fname);
	fprintf(E->f, "static int %s(%s)\n{\n\tint r = -1;\n", fname, sig);
	if (!E->S->direct)
		fprintf(E->f, "\tif (y != m + %luu) memcpy(m + %luu, y, %luu * sizeof *y);\n", (unsigned long)p->ystart,
		        (unsigned long)p->ystart, (unsigned long)p->ny);
	for (uint32_t i = 0; i < nfn[sec]; i++)
		fprintf(E->f, "\tif (r < 0) r = %s_%lu(p, x, m%s);\n", fname, (unsigned long)i, E->S->direct ? ", y, dydt" : "");
	if (!E->S->direct)
		fprintf(E->f, "\tif (dydt != m + %luu) memcpy(dydt, m + %luu, %luu * sizeof *dydt);\n", (unsigned long)p->dstart,
		        (unsigned long)p->dstart, (unsigned long)p->ny);
	else
		fputs("\t(void)y;\n\t(void)dydt;\n", E->f);
	fputs("\treturn r;\n}\n\n", E->f);
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
	static const char *const names[CSF_NSEC] = { "csf_model_rhs", "csf_model_out", "csf_model_jac",
		                                              "csf_model_evt" };
	Slots S;
	uint32_t *starts[CSF_NSEC], nfn[CSF_NSEC];
	slots_analyse(&S, p, starts, nfn);

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
	E.decl = xcalloc(S.n + 1, sizeof *E.decl);
	E.readin = xcalloc(S.n + 1, sizeof *E.readin);
	uint32_t maxcode = 0;
	for (int sec = 0; sec < CSF_NSEC; sec++)
		if (p->ncode[sec] > maxcode) maxcode = p->ncode[sec];
	E.target = xcalloc((size_t)maxcode + 1, 1);
	E.par = xcalloc((size_t)maxcode + 1, sizeof *E.par);
	E.par_pc = UINT32_MAX;
	for (int sec = 0; sec < CSF_NSEC; sec++) emit_section(&E, sec, names[sec], starts, nfn);
	fputs("static int csf_model_exec(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, const double *y,\n"
	      "                          double *dydt)\n{\n"
	      "\treturn sec == CSF_SEC_RHS ? csf_model_rhs(p, x, m, y, dydt)\n"
	      "\t     : sec == CSF_SEC_OUT ? csf_model_out(p, x, m, y, dydt)\n"
	      "\t     : sec == CSF_SEC_JAC ? csf_model_jac(p, x, m, y, dydt)\n"
	      "\t                          : csf_model_evt(p, x, m, y, dydt);\n}\n\n"
	      "int main(int argc, char **argv)\n{\n"
	      "\treturn csf_main(argc, argv, csf_model_image, sizeof csf_model_image, csf_model_exec);\n}\n",
	      f);
	for (int sec = 0; sec < CSF_NSEC; sec++) free(starts[sec]);
	free(E.decl);
	free(E.readin);
	free(E.target);
	free(E.par);
	free(E.loc);
	slots_free(&S);
}
