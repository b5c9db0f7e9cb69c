/*
 * emit_c.h - the C back end (emit_c.c, emit_c_slots.c, cc.c).
 */
#ifndef CSF_EMIT_C_H
#define CSF_EMIT_C_H

#include <stdio.h>

#include "csf_int.h"

/* Writes the C translation of p, whose encoded bytecode is image[0..len), to f. */
void emit_c(const csf_prog *p, const unsigned char *image, size_t len, const char *model, FILE *f);

/* Builds executable out from C source csource with $CC $CFLAGS, libcsfrt and GSL. Returns 0 or 2. */
int emit_c_executable(const char *csource, const char *out);

#endif
