/*
 * The unit-test runner: every module's Check suite, in fork mode so a
 * crash fails one test, not the run.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "suites.h"
#include "emit_c.h"
#include "gen.h"

int compile_string(const char *text, csf_prog *p, char **diag)
{
	char *buf = NULL;
	size_t len = 0;
	FILE *mem = open_memstream(&buf, &len);
	diag_out = mem;
	diag_errors = 0;
	opts.stdlib = getenv("CSF_STDLIB");
	int f = src_add("t.csf", text);
	Stmt *s = parse_file(f);
	int errs = diag_errors;
	if (!errs) {
		Model *M = sema_run(s, NULL);
		errs = diag_errors;
		if (!errs) {
			gen_program(M, p);
			char err[256];
			ck_assert_msg(csf_verify(p, err, sizeof err) == 0, "generated code does not verify: %s", err);
		}
	}
	fclose(mem);
	diag_out = NULL;
	if (diag) *diag = buf;
	else free(buf);
	return errs;
}

csf_prog bare_prog(uint32_t *code, uint32_t n, double *mem0, uint32_t nmem, uint32_t nasserts)
{
	static csf_assert a[BARE_MAX_ASSERTS];
	static csf_src s;
	static uint32_t f;
	csf_prog p;
	memset(&p, 0, sizeof p);
	p.code[CSF_SEC_OUT] = code;
	p.ncode[CSF_SEC_OUT] = n;
	p.mem0 = mem0;
	p.nmem = nmem;
	p.strs = "";
	p.nstrs = 1;
	p.by = 1;
	for (int k = 0; k < CSF_NDIM; k++) p.ubase[k] = 1; /* mks */
	p.asserts = a;
	p.nasserts = nasserts;
	p.srcs = &s;
	p.nsrcs = 1;
	p.files = &f;
	p.nfiles = 1;
	return p;
}

char *emit_string(const csf_prog *p)
{
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	unsigned char image[2] = { 1, 2 };
	emit_c(p, image, 2, "m.csf", f);
	fclose(f);
	return buf;
}

double *run_out(const csf_prog *p)
{
	double *m = malloc(p->nmem * sizeof *m + 1);
	memcpy(m, p->mem0, p->nmem * sizeof *m);
	vm_run(p, CSF_SEC_OUT, m);
	return m;
}

int col_slot(const csf_prog *p, const char *name)
{
	size_t n = strlen(name);
	for (uint32_t i = 0; i < p->ncols; i++) {
		const char *c = csf_str(p, p->cols[i].name); /* "b.x" or "b.x [m]" */
		if (strncmp(c, name, n) == 0 && (c[n] == '\0' || c[n] == ' ')) return (int)p->cols[i].slot;
	}
	return -1;
}

int main(void)
{
	SRunner *sr = srunner_create(units_suite());
	srunner_add_suite(sr, lex_suite());
	srunner_add_suite(sr, parse_suite());
	srunner_add_suite(sr, sema_suite());
	srunner_add_suite(sr, bytecode_suite());
	srunner_add_suite(sr, vm_suite());
	srunner_add_suite(sr, emit_c_suite());
	srunner_add_suite(sr, jac_suite());
	srunner_add_suite(sr, loops_suite());
	srunner_add_suite(sr, par_suite());
	srunner_add_suite(sr, block_suite());
	srunner_add_suite(sr, dop853_suite());
	srunner_add_suite(sr, dopri5_suite());
	srunner_add_suite(sr, stability_suite());
	srunner_add_suite(sr, signals_suite());
	srunner_add_suite(sr, lcp_suite());
	srunner_add_suite(sr, recall_suite());
	srunner_add_suite(sr, spread_suite());
	srunner_add_suite(sr, dualrows_suite());
	srunner_set_fork_status(sr, CK_FORK);
	srunner_run_all(sr, CK_NORMAL);
	int failed = srunner_ntests_failed(sr);
	srunner_free(sr);
	return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
