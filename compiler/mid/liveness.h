/*
 * liveness.h - which rule instances each section needs (liveness.c).
 */
#ifndef CSF_LIVENESS_H
#define CSF_LIVENESS_H

#include "sema.h"

/* Per object index: the instances of its rules with attribute F (the terms of its RF), in order. */
Vec *live_forces(const Model *M);

/* Sets I->needed[sec] of every instance section sec needs (Finsts: live_forces). Returns the
   index into M->insts of the last instance that determines a contact body's acceleration,
   after which the contact routine runs, or -1. */
int live_mark(Model *M, Vec *Finsts);

#endif
