/*
 * emit_c_int.h - what the files of the C back end share (emit_c.c, the C
 * text; emit_c_slots.c, where each slot lives): the slot classes and the
 * analysis's results, the loops open at an instruction, operand kinds.
 */
#ifndef CSF_EMIT_C_INT_H
#define CSF_EMIT_C_INT_H

#include <stdint.h>

#include "csf_int.h"
#include "insn.h"

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
static inline int region(const csf_prog *p, uint32_t s)
{
	if (s >= p->ystart && s < p->ystart + p->ny) return C_STATE;
	if (s >= p->dstart && s < p->dstart + p->ny) return C_DERIV;
	return C_MEM;
}

/* The loops open at an instruction: their counts by level, for the extent of relative operands. */
typedef struct Loops { uint32_t count[CSF_LOOP_MAX + 1], next[CSF_LOOP_MAX + 1]; int depth; } Loops;

/* Keeps L up to date past the instruction at pc. */
void track_loops(Loops *L, const uint32_t *code, uint32_t pc);

/* Fills S for program p: which slots the runtime sees, code writes, reaches through loop indices, may
   read before writing, and so the class of each (S->cls); and splits each section sec into nfn[sec]
   functions at starts[sec] (malloc'd; starts[sec][nfn[sec]] = the section's end). */
void slots_analyse(Slots *S, const csf_prog *p, uint32_t **starts, uint32_t *nfn);

/* Frees what slots_analyse allocated in S. */
void slots_free(Slots *S);

#endif
