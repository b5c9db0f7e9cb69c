/*
 * lint.h - warnings (lint.c, util.c): `file:line:col: warning: ...`, never
 * an error but under -Werror; and the near-miss suggestions that warnings
 * and errors share ("did you mean 'NAME'?").
 */
#ifndef CSF_LINT_H
#define CSF_LINT_H

#include "csfc.h"

/* Warnings written; -Werror makes each an error (counted in diag_errors); -w silences them. */
extern int diag_warnings, diag_werror, diag_nowarn;
void warn_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The edit distance of a and b (insertions, deletions, substitutions), or cap + 1 if more. */
int edit_distance(const char *a, const char *b, int cap);
/* The candidate nearest to name (of 3 letters or more), within 2 edits, or the symbol it begins with; NULL if none. */
const char *suggest_name(const char *name, const char *const *cands, int n);

/* A known unit, or a quotient of two ("mps": "m/s"), near the unknown unit name; NULL if none. */
const char *suggest_unit(const char *name);

struct Model;
/* Warns of what the compiled model does not do that its author meant (after gen_program). */
void lint_model(struct Model *M);

#endif
