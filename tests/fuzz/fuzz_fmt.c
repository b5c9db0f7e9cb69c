/*
 * fuzz_fmt - the number formatter's fuzz target: bytes as doubles, each
 * formatted by csf_fmt_double (runtime/run/fmt.c) and by the loop it
 * replaced (tests/fmt_ref.h: %.15g, %.16g, %.17g and strtod); a difference
 * is a finding (abort, with the value's bits on stderr).
 *
 * The doubles: every 8 bytes of the input (the last ones padded with
 * zeros), and the input read as text by strtod (a seed can then be
 * written as "9.999999999999999e22").
 *
 * Built for libFuzzer by `make fuzz`; linked with replay.c it replays
 * tests/fuzz/regress/fmt under make check (see tests/fuzz/README.md).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf.h"
#include "../fmt_ref.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(double x)
{
	char msg[200];
	if (fmt_ref_mismatch(csf_fmt_double, x, msg, sizeof msg)) {
		fprintf(stderr, "fuzz_fmt: %s\n", msg);
		abort();
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	for (size_t i = 0; i < size; i += 8) {
		uint64_t b = 0;
		for (size_t j = 0; j < 8 && i + j < size; j++) b |= (uint64_t)data[i + j] << 8 * j;
		double x;
		memcpy(&x, &b, sizeof x);
		check(x);
	}
	char text[64];
	size_t n = size < sizeof text - 1 ? size : sizeof text - 1;
	memcpy(text, data, n);
	text[n] = 0;
	check(strtod(text, NULL));
	return 0;
}
