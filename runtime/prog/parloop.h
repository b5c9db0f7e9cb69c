/*
 * parloop.h - which loops of a program may run their iterations on several
 * threads and give the same bytes (csfvm --threads N, a generated
 * program's): the analysis both execution paths share (parloop.c).
 */
#ifndef CSF_PARLOOP_H
#define CSF_PARLOOP_H

#include <stdint.h>

#include "csf_int.h"

/* Slots [lo, hi). */
typedef struct csf_span { uint32_t lo, hi; } csf_span;
/* What iteration k of a loop writes: slots base + stride k + [0, width), width <= stride. */
typedef struct csf_cell { uint32_t base, stride, width; } csf_cell;

/*
 * A loop of level 1 whose iterations are independent: each one writes only
 * its own cells (slots through the loop's index, disjoint from every other
 * iteration's) and slots of its own (priv: fixed slots it writes before it
 * reads them, in every iteration), and reads nothing another iteration
 * writes. Its iterations may then run in any order, on any thread, each
 * on a memory holding the slots it reads (in), and the cells copied back
 * are those of a serial run, bit for bit. Contacts, constraints and
 * assertions make a loop serial.
 */
typedef struct csf_parloop {
	uint32_t pc, end, count; /* the LOOP (first: csf_find_pc), the pc just past its NEXT, its iterations */
	uint64_t work;           /* instructions one run of the loop executes, at most (saturated) */
	csf_span *in;            /* what a worker's memory needs: the slots the body reads and its cells */
	uint32_t nin;
	csf_cell *out;           /* the cells */
	uint32_t nout;
	uint32_t *priv;          /* the iteration's own fixed slots, ascending */
	uint32_t npriv;
} csf_parloop;

/*
 * Analyses the level-1 LOOP at pc of section sec of verified program p.
 * Returns 1 and fills *L (its arrays malloc'd: csf_parloop_free) when its
 * iterations are independent as above; 0 (and *L empty) when they are not,
 * the loop is not of level 1, or memory ran out.
 */
int csf_parloop_analyse(const csf_prog *p, int sec, uint32_t pc, csf_parloop *L);
void csf_parloop_free(csf_parloop *L);
/* Is fixed slot s one of L's iteration's own (L->priv)? */
int csf_parloop_own(const csf_parloop *L, uint32_t s);

#endif
