/*
 * cone.h - the cone of influence of the watched variables (cone.c).
 */
#ifndef CSF_CONE_H
#define CSF_CONE_H

#include "sema.h"

/* By object index, 1 for each object that nothing watched, asserted or stopped on depends on;
   NULL when every object is needed (or none is). */
char *cone_dropped(const Model *M);

/* Marks idle the derivatives of the state variables that nothing watched, asserted or stopped on
   depends on (Inst.idle): they are not integrated. */
void cone_idle_states(Model *M);

#endif
