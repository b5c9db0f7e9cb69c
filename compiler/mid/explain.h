/*
 * explain.h - csfc --explain (explain.c).
 */
#ifndef CSF_EXPLAIN_H
#define CSF_EXPLAIN_H

#include <stdio.h>

#include "sema.h"

/* Writes what each rule solves for and which rules were left out (csfc --explain). */
void explain_model(Model *M, FILE *f);

#endif
