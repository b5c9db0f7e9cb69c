/*
 * fuzz_csfb - the runtime's fuzz target: bytes as a .csfb file.
 *
 * The header's payload size and CRC-32 are rewritten first, so that a
 * mutation reaches the loader's checks instead of stopping at the
 * checksum, as a hostile file would. A file the loader accepts is
 * disassembled and then run by csf_run (the whole integrator driver, the
 * events and the contact routine) with a method chosen by the file's
 * length, for at most FUZZ_ROWS rows and FUZZ_EVALS evaluations of the
 * right-hand side: past those the derivatives are made NaN, which ends the
 * run as a non-finite value would. A rejection without a reason is a
 * finding (abort); so is any crash, sanitizer report or leak.
 *
 * Built for libFuzzer by `make fuzz`; linked with replay.c it replays
 * tests/fuzz/regress/csfb under make check (see tests/fuzz/README.md).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "bytecode.h"

#define FUZZ_ROWS 50
#define FUZZ_EVALS 5000

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static unsigned long evals;

static int exec_bounded(const csf_prog *p, const csf_exec_ctx *x, int sec, double *m, const double *y, double *dydt)
{
	int r = csf_vm_exec(p, x, sec, m, y, dydt);
	if (sec == CSF_SEC_RHS && ++evals > FUZZ_EVALS)
		for (uint32_t i = 0; i < p->ny; i++) dydt[i] = NAN;
	return r;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static FILE *null_out;
	if (!null_out && !(null_out = fopen("/dev/null", "w"))) abort();
	unsigned char *b = malloc(size ? size : 1);
	if (!b) return 0;
	memcpy(b, data, size);
	if (size >= CSFB_HEADER_SIZE) {
		size_t plen = size - CSFB_HEADER_SIZE;
		unsigned long crc = csf_crc32(b + CSFB_HEADER_SIZE, plen);
		for (int i = 0; i < 4; i++) {
			b[20 + i] = (unsigned char)(plen >> (8 * i));
			b[24 + i] = (unsigned char)(crc >> (8 * i));
		}
	}
	csf_prog p;
	char err[256] = "";
	if (csf_decode(b, size, &p, err, sizeof err)) {
		if (!err[0]) {
			fprintf(stderr, "fuzz_csfb: rejected without a reason\n");
			abort();
		}
		free(b);
		return 0;
	}
	free(b);
	csf_disassemble(&p, null_out);
	if (p.till / p.by > FUZZ_ROWS) p.till = FUZZ_ROWS * p.by;
	size_t nmethods = 0;
	while (csf_method_name(nmethods)) nmethods++;
	csf_opts o;
	memset(&o, 0, sizeof o);
	o.method = csf_method_name(size % nmethods);
	evals = 0;
	csf_run(&p, exec_bounded, &o, null_out, null_out);
	csf_prog_free(&p);
	return 0;
}
