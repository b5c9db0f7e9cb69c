/*
 * lint.h - warnings (lint.c, util.c): `file:line:col: warning: ...`, never
 * an error but under -Werror; and the unit suggestions of errors ("did you
 * mean 'm/s'?"; names: csf_suggest_name, which -D shares).
 */
#ifndef CSF_LINT_H
#define CSF_LINT_H

#include "csfc.h"

/* Warnings written; -Werror makes each an error (counted in diag_errors); -w silences them. */
extern int diag_warnings, diag_werror, diag_nowarn;
void warn_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A known unit, or a quotient of two ("mps": "m/s"), near the unknown unit name; NULL if none. */
const char *suggest_unit(const char *name);

struct Model;
/* Warns of what the compiled model does not do that its author meant (after gen_program). */
void lint_model(struct Model *M);

#endif
