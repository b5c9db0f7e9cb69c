/*
 * fuzz_csfc - the compiler's fuzz target: bytes as a model source.
 *
 * Runs everything csfc does short of writing a file: scanner, layout
 * (indentation, `using` from the standard library, unit literals), parser,
 * resolver, dimension check, code generator, verifier, encoder, and the
 * three listings (--explain, --dump-bytecode, --emit-c), all written to
 * /dev/null. A program the generator makes that does not verify is a
 * finding (abort). Every input starts from a fresh compiler (csfc_reset),
 * so nothing carries over from one input to the next.
 *
 * Built for libFuzzer by `make fuzz` (clang -fsanitize=fuzzer); the same
 * file, linked with replay.c, replays tests/fuzz/regress/csfc under make
 * check, and runs under AFL++ (see tests/fuzz/README.md).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "csfc.h"
#include "ast.h"
#include "sema.h"
#include "explain.h"
#include "gen.h"
#include "emit_c.h"
#include "csf_int.h"

#ifndef CSF_FUZZ_STDLIB
#define CSF_FUZZ_STDLIB "stdlib"
#endif

/* Fewer tuples per rule than csfc allows: a fuzz input must compile in well under a second. */
#define FUZZ_MAX_TUPLES 20000

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static FILE *null_out;
	if (!null_out && !(null_out = fopen("/dev/null", "w"))) abort();
	diag_out = null_out;
	opts = (Options){ 0 };
	opts.stdlib = CSF_FUZZ_STDLIB;
	opts.max_tuples = FUZZ_MAX_TUPLES;
	int f = src_add_n("fuzz.csf", (const char *)data, size);
	Stmt *s = parse_file(f);
	if (!diag_errors) {
		Model *M = sema_run(s, NULL);
		if (!diag_errors) {
			csf_prog p;
			gen_program(M, &p);
			explain_model(M, null_out);
			char err[256];
			if (csf_verify(&p, err, sizeof err)) {
				fprintf(stderr, "fuzz_csfc: the generated code does not verify: %s\n", err);
				abort();
			}
			csf_disassemble(&p, null_out);
			unsigned char *buf;
			size_t len;
			if (csf_encode(&p, &buf, &len) == 0) {
				emit_c(&p, buf, len, "fuzz.csf", null_out);
				free(buf);
			}
			csf_prog_free(&p);
		}
	}
	csfc_reset();
	return 0;
}
