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

/* The model without the objects that nothing watched, asserted or stopped on depends on, resolved
   again from stmts, with a warning for each (the first three; then how many more); M itself if
   every object is needed (csfc, and csfc --lsp for its warnings). M was resolved from stmts after
   mark: what it holds is released before the second resolution (a model of many objects takes
   most of the memory csfc needs: it is not held twice). */
Model *cone_leave_out(Stmt *stmts, Model *M, ArenaMark mark);

#endif
