/*
 * gen_int.h - what the files of the bytecode generator share (gen.c, slots.c,
 * expr.c, loops.c, jac.c, pairs.c, tables.c): the generator's state and the
 * functions each file offers the others, in the order the pass uses them.
 */
#ifndef CSF_GEN_INT_H
#define CSF_GEN_INT_H

#include <setjmp.h>

#include "csfc.h"
#include "sema.h"
#include "csf_int.h"
#include "insn.h"

/* Scratch operands carry this bit until scratch is placed; memory stays below it. */
#define SCRATCH (1u << 28)

typedef struct Gen {
	Model *M;
	csf_prog *p;
	double *mem;
	uint32_t nmem, capmem;
	uint32_t *code;
	uint32_t ncode, capcode;
	csf_line *lines;
	uint32_t nlines, caplines;
	csf_target *targets;
	uint32_t ntargets, captargets;
	uint32_t scratch, max_scratch;
	char *strs;
	uint32_t nstrs, capstrs;
	Vec *Finsts; /* per object index: its F instances */
	Map strmap;  /* string -> offset + 1 */
	uint32_t *objstr; /* per object index: its interned name + 1 (0: not yet; obj_str) */
	Map pclass;  /* parameter class key -> index + 1 */
	csf_pclass *pclasses;
	uint32_t npclasses, cappclasses;
	struct { RExpr *e; uint32_t slot; } cse[64]; /* within one equation: values computed so far */
	int ncse;
	Map consts;  /* constant bits -> slot + 1 */
	int loop;     /* the levels of the loops the instance being emitted runs in (0: none) */
	Inst *iloop;        /* the instance being emitted when it is one loop over neighbours (Inst.iloop) */
	Inst *evinst; /* emitting a condition of this conditional rule, located as events ... */
	int evsrc;    /* ... which name this statement */
	Map evmap;    /* comparison (by address) -> event index + 1 */
	csf_event *events;
	uint32_t nevents, capevents;
	Vec assert_tab, assert_obj; /* of Inst* and Object*, in assertion index order */
	jmp_buf *fail; /* alloc_mem's way out of a scene too big to compile, back to gen_program */
	void *work[3]; /* gen_jacobian's heap arrays while it runs, for gen_program to free after that */
} Gen;

/* gen.c: a code section's code, lines and targets, from empty (begin) into p's section sec (end) */
void section_begin(Gen *G);
void section_end(Gen *G, csf_prog *p, int sec);

/* slots.c: memory, strings and parameter classes */
void *grow(void *p, uint32_t *cap, uint32_t need, size_t elem);
uint32_t alloc_mem(Gen *G, uint32_t n, const double *init);
uint32_t str_intern(Gen *G, const char *s);
/* Object o's name, interned (once per object: a million members are a million names). */
uint32_t obj_str(Gen *G, const Object *o);
uint32_t var_slot(Gen *G, Var *v);
/* The slot of object o's property v: var_slot, at o's place if o shares v (a lean member, Object.lean). */
uint32_t prop_slot(Gen *G, Var *v, const Object *o);
/* o's place in the array of property v that lean members share, from its start (0 if o has its own). */
static inline uint32_t member_offset(const Var *v, const Object *o)
{
	return o && o->lean ? (uint32_t)o->sidx * (v->isvec ? 3u : 1u) : 0u;
}
uint32_t param_class(Gen *G, Var *v);
uint32_t var_operand(Gen *G, Var *v, int place);
uint32_t const_slot(Gen *G, const double *c, int isvec);
uint32_t new_scratch(Gen *G, int width);

/* expr.c: instructions and expressions */
static inline uint32_t pc(Gen *G) { return G->ncode; }
void emit_words(Gen *G, int op, const uint32_t *ops);
void emit_op(Gen *G, int op, uint32_t a, uint32_t b, uint32_t c, uint32_t d);
void emit_pow_const(Gen *G, uint32_t dest, uint32_t x, double k);
uint32_t acc_slot(Gen *G, Inst *I);
static inline void cse_reset(Gen *G) { G->ncse = 0; }
void emit_into(Gen *G, RExpr *e, uint32_t dest);
uint32_t emit(Gen *G, RExpr *e);

/* loops.c: one rule instance */
int inst_loops(const Model *M, const Inst *I);
int sums_pairs(const Model *M, const Inst *I);
void add_line(Gen *G, uint32_t src);
void add_target(Gen *G, uint32_t slot, Var *v, uint32_t src, const char *name, Object *o);
void emit_inst(Gen *G, Inst *I);

/* when.c: the EVT section */
void gen_when_section(Gen *G, Model *M, csf_prog *p);

/* jac.c: the Jacobian */
int depends(const uint32_t *code, uint32_t n, unsigned char *act, int smooth);
void gen_jacobian(Gen *G, csf_prog *p);
/* Moves what does not change in an innermost loop before it (hoist.c): instructions with a
   result in scratch slots [lo, hi) that nothing outside the loop reads. */
void gen_hoist(csf_prog *p, uint32_t lo, uint32_t hi);
/* Fuses loops one after the other at one level over one count (hoist.c) when running them member by
   member computes the same; [lo, hi): the scratch slots. */
void gen_fuse_loops(csf_prog *p, uint32_t lo, uint32_t hi);
/* Superinstructions (hoist.c): POWI then the DIV that alone reads its scratch result, as DIVPOWI. */
void gen_fuse(csf_prog *p, uint32_t lo, uint32_t hi);

/* pairs.c: velocity Verlet's pairs */
void gen_pairs(Gen *G, Model *M, csf_prog *p);

/* tables.c: the tables beside the code, in the order gen_program fills them */
void gen_state_scales(Model *M, csf_prog *p);
void gen_contact_tables(Gen *G, Model *M, csf_prog *p);
void gen_constraint_tables(Gen *G, Model *M, csf_prog *p);
void gen_constraint_code(Gen *G, Model *M, csf_prog *p);
void gen_columns(Gen *G, Model *M, csf_prog *p);
void gen_globals(Gen *G, Model *M, csf_prog *p);
void gen_objects(Gen *G, Model *M, csf_prog *p);
void gen_source_tables(Gen *G, Model *M, csf_prog *p);

#endif
