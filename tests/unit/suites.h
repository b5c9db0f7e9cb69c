/*
 * suites.h - the Check suites of the unit tests, one per module, and the
 * helpers they share (compiling a model held in a string).
 */
#ifndef CSF_SUITES_H
#define CSF_SUITES_H

#include <check.h>
#include <stdlib.h>

#include "csfc.h"
#include "ast.h"
#include "sema.h"
#include "csf_int.h"

Suite *units_suite(void);
Suite *lex_suite(void);
Suite *parse_suite(void);
Suite *sema_suite(void);
Suite *bytecode_suite(void);
Suite *vm_suite(void);
Suite *emit_c_suite(void);
Suite *jac_suite(void);
Suite *loops_suite(void);
Suite *par_suite(void);
Suite *block_suite(void);
Suite *dop853_suite(void);
Suite *dopri5_suite(void);
Suite *stability_suite(void);
Suite *signals_suite(void);
Suite *lcp_suite(void);
Suite *recall_suite(void);
Suite *spread_suite(void);
Suite *dualrows_suite(void);

/*
 * Compiles source text (file name "t.csf") to a verified program in *p.
 * Diagnostics are captured into a string returned in *diag (may be NULL).
 * Returns the number of errors.
 */
int compile_string(const char *text, csf_prog *p, char **diag);

/* Runs section sec of p on the VM with the state and derivatives in m's own slots. */
static inline int vm_run(const csf_prog *p, int sec, double *m)
{
	return csf_vm_exec(p, NULL, sec, m, m + p->ystart, m + p->dstart);
}

/* Runs the OUT section of p at t = 0 on a fresh copy of its memory; returns the memory (free it). */
double *run_out(const csf_prog *p);

/* The C emit_c writes for p (with a dummy image), malloc'd. */
char *emit_string(const csf_prog *p);

/* A verifiable program around OUT code code[0..n) and memory mem0[0..nmem), with nasserts
 * (at most BARE_MAX_ASSERTS) assertions of one source statement; the tables are shared statics. */
#define BARE_MAX_ASSERTS 16
csf_prog bare_prog(uint32_t *code, uint32_t n, double *mem0, uint32_t nmem, uint32_t nasserts);

/* Slot of output column `name` in p, or -1. */
int col_slot(const csf_prog *p, const char *name);

#endif
