/*
 * lint.h - warnings (lint.c, util.c): `file:line:col: warning: ...`, never
 * an error but under -Werror.
 */
#ifndef CSF_LINT_H
#define CSF_LINT_H

#include "csfc.h"

/* Warnings written; -Werror makes each an error (counted in diag_errors); -w silences them. */
extern int diag_warnings, diag_werror, diag_nowarn;
void warn_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

struct Model;
/* Warns of what the compiled model does not do that its author meant (after gen_program). */
void lint_model(struct Model *M);

#endif
