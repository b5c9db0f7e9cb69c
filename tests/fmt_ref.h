/*
 * fmt_ref.h - the reference for runtime/run/fmt.c's csf_fmt_double: the
 * loop it replaced (issue 30), printf's %.15g, %.16g and %.17g in turn, the
 * first that strtod reads back to x. Used by the test (tests/fmt_double.c),
 * the fuzz target (tests/fuzz/fuzz_fmt.c) and the benchmark (bench/fmt.c);
 * not part of the runtime. fmt_ref_mismatch compares the two on one value.
 */
#ifndef CSF_FMT_REF_H
#define CSF_FMT_REF_H

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void fmt_ref(char buf[32], double x)
{
	if (isnan(x)) {
		strcpy(buf, "nan");
		return;
	}
	if (isinf(x)) {
		strcpy(buf, x > 0 ? "inf" : "-inf");
		return;
	}
	for (int prec = 15; prec <= 17; prec++) {
		snprintf(buf, 32, "%.*g", prec, x);
		if (strtod(buf, NULL) == x) return;
	}
}

/*
 * 0 when fmt writes for x what the reference writes; else 1, and msg (of
 * msize bytes) names x by its bits: "0x... (%a): got "...", want "..."".
 */
static int fmt_ref_mismatch(void (*fmt)(char buf[32], double x), double x, char *msg, size_t msize)
{
	char got[32], want[32];
	memset(got, 'X', sizeof got); /* a formatter that writes no terminator shows */
	got[31] = 0;
	fmt(got, x);
	fmt_ref(want, x);
	if (strcmp(got, want) == 0) return 0;
	uint64_t b;
	memcpy(&b, &x, sizeof b);
	snprintf(msg, msize, "0x%016" PRIx64 " (%a): got \"%s\", want \"%s\"", b, x, got, want);
	return 1;
}

#endif
