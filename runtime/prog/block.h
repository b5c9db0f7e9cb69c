/*
 * block.h - the innermost loops the VM may run a block of iterations at a
 * time (block.c): each instruction of the body over up to CSF_BLOCK
 * indices before the next instruction, so that one dispatch and one decode
 * of its operands serve them all.
 *
 * That order gives the serial run's values, bit for bit, when no
 * instruction of an iteration depends on a later instruction of an earlier
 * one, through memory: the analysis proves it from the footprints of the
 * operands. A fixed slot the body writes before it reads it in every
 * iteration (a temporary: the body's scratch values) gets one copy per
 * index of the block, in a scratch array, and the last iteration's value
 * goes back into memory at the end. A fixed slot one instruction alone
 * reads and writes (a sum over the loop, such as a force added up over the
 * other bodies) is its own dependence, which the block keeps: that
 * instruction runs over the indices in ascending order, as the serial
 * loop does, so each sum adds its terms in the same order.
 */
#ifndef CSF_BLOCK_H
#define CSF_BLOCK_H

#include <stdint.h>

#include "csf_int.h"

/*
 * Indices of a block, at most; doubles of scratch a block's temporaries may
 * take; the fewest iterations for which a loop is run a block at a time.
 */
enum { CSF_BLOCK = 64, CSF_BLOCK_SCRATCH = 2048, CSF_BLOCK_MIN_COUNT = 4 };

/* How an operand of a blocked instruction reaches its values. */
enum csf_bmode {
	CSF_BM_FIX, /* a slot the loop's index does not move: m + csf_operand(w, registers) */
	CSF_BM_IDX, /* through the loop's index: slot w + stride index */
	CSF_BM_TMP, /* a temporary: scratch + w, one value of stride (its width) slots per index */
	CSF_BM_IMM  /* an immediate (w), or no operand */
};
typedef struct csf_bopnd { uint32_t mode, w, stride; } csf_bopnd;
typedef struct csf_binsn { uint32_t op; csf_bopnd o[4]; } csf_binsn;
/* A temporary: its slots [slot, slot + width) of memory, at scratch + off (width per index). */
typedef struct csf_btemp { uint32_t slot, width, off; } csf_btemp;

/*
 * A blocked loop: the LOOP at pc of level `level`, end the pc just past its
 * NEXT. skip: the level of the loop around it whose index this one's skips
 * (a leading `JEQ` to the NEXT, the other bodies of a pair), or 0; block:
 * indices a block takes (the scratch holds that many of every temporary).
 */
typedef struct csf_bloop {
	uint32_t pc, end, level, skip, block; /* pc first: csf_find_pc */
	csf_binsn *insn; /* the body's instructions after the JEQ, in order */
	uint32_t ninsn;
	csf_btemp *tmp;
	uint32_t ntmp;
} csf_bloop;

/* The blocked loops of a program, per section, ascending by pc. */
struct csf_blocks {
	csf_bloop *loops[CSF_NSEC];
	uint32_t nloops[CSF_NSEC];
};

/*
 * The blocked loops of verified program p (malloc'd: csf_blocks_free).
 * NULL when none can be, or memory ran out: the VM then runs every loop
 * an iteration at a time, with the same results. csf_blocks_free(NULL)
 * does nothing.
 */
csf_blocks *csf_blocks_new(const csf_prog *p);
void csf_blocks_free(csf_blocks *b);
/* The blocked loop at pc of section sec, or NULL (b NULL: none). */
const csf_bloop *csf_blocks_find(const csf_blocks *b, int sec, uint32_t pc);

#endif
