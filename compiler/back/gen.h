/*
 * gen.h - bytecode generation (gen.c and the files it names).
 */
#ifndef CSF_GEN_H
#define CSF_GEN_H

#include "csf_int.h"
#include "sema.h"

/* Fills p (malloc'd tables, free with csf_prog_free) from a resolved model. Returns 0, or 1
   after an error (a scene too big to compile): then p holds part of the tables, for csf_prog_free. */
int gen_program(Model *M, csf_prog *p);

#endif
