/*
 * cone.h - the cone of influence of the watched variables (cone.c).
 */
#ifndef CSF_CONE_H
#define CSF_CONE_H

#include "sema.h"

/* By object index, 1 for each object that nothing watched, asserted or stopped on depends on;
   NULL when every object is needed (or none is). */
char *cone_dropped(const Model *M);

#endif
