/*
 * fmt - the cost of a CSV cell: runtime/run/fmt.c's csf_fmt_double beside
 * the loop it replaced (tests/fmt_ref.h: %.15g, %.16g, %.17g and strtod),
 * in ns per value on five kinds of values, then COUNT random doubles (bit
 * patterns, NaN aside, and a run's kinds of values in turn) compared one by
 * one; a mismatch prints the value's bits and the exit status is 1.
 *
 *   fmt [COUNT] [REPS]   (1e8, 5: the median of REPS timings of 1e6 values)
 *
 * Prints a Markdown table (fmt.sh puts it into README.md).
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "csf.h"
#include "../tests/fmt_ref.h"

enum { N = 1000000 };

static uint64_t seed = 0x9E3779B97F4A7C15;

static uint64_t rnd(void) /* splitmix64 */
{
	uint64_t z = (seed += 0x9E3779B97F4A7C15);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EB;
	return z ^ (z >> 31);
}

static double unif(void) { return (double)(rnd() >> 11) * 0x1p-53; }

static double bits_no_nan(void)
{
	uint64_t b;
	while (((b = rnd()) >> 52 & 0x7ff) == 0x7ff) {}
	double x;
	memcpy(&x, &b, sizeof x);
	return x;
}

/* the kinds of values timed, and compared in turn */
static double kind(int k, long i)
{
	switch (k) {
	case 0: return bits_no_nan();
	case 1: return 0.01 * (double)(i % 100000); /* output times k * by */
	case 2: return sin(1e-3 * (double)i) * exp(-1e-6 * (double)i); /* a state variable */
	case 3: return unif() * pow(10, (double)(rnd() % 41) - 20);
	default: return (double)(rnd() % 10000) / 64; /* short: 15 digits or fewer */
	}
}
static const char *kinds[] = { "random 64-bit patterns (no NaN)", "output times 0.01 k",
	                       "sin(t) exp(-t) (a state variable)", "uniform times 1e-20 .. 1e20",
	                       "short (integers / 64)" };
enum { NKINDS = 5 };

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmpd(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* the median over reps of ns per value of fmt on v[0..n) */
static double ns_per_value(void (*fmt)(char buf[32], double x), const double *v, long n, int reps)
{
	double t[32];
	char b[32];
	unsigned sum = 0;
	for (int r = 0; r < reps; r++) {
		double t0 = now();
		for (long i = 0; i < n; i++) {
			fmt(b, v[i]);
			sum += (unsigned char)b[1];
		}
		t[r] = 1e9 * (now() - t0) / (double)n;
	}
	if (sum == 1) puts("");
	qsort(t, (size_t)reps, sizeof t[0], cmpd);
	return t[reps / 2];
}

int main(int argc, char **argv)
{
	double count = argc > 1 ? atof(argv[1]) : 1e8;
	int reps = argc > 2 ? atoi(argv[2]) : 5;
	if (reps < 1 || reps > 31) reps = 5;
	double *v = malloc(N * sizeof *v);
	if (!v) return 2;
	printf("| values | new: ns per value | old loop: ns per value | old / new |\n|---|---|---|---|\n");
	for (int k = 0; k < NKINDS; k++) {
		for (long i = 0; i < N; i++) v[i] = kind(k, i);
		double a = ns_per_value(csf_fmt_double, v, N, reps);
		double b = ns_per_value(fmt_ref, v, N / 10, reps < 3 ? reps : 3);
		printf("| %s | %.1f | %.0f | %.0f |\n", kinds[k], a, b, b / a);
		fflush(stdout);
	}
	free(v);
	/* the comparison: COUNT values, bit patterns and the other kinds in turn */
	long n = (long)count, bad = 0;
	double t0 = now();
	for (long i = 0; i < n; i++) {
		char msg[200];
		double x = kind(i % 2 ? 0 : (int)(i / 2 % NKINDS), i);
		if (fmt_ref_mismatch(csf_fmt_double, x, msg, sizeof msg) && bad++ < 20) printf("MISMATCH: %s\n", msg);
	}
	printf("\n%ld values compared with the old loop (half random 64-bit patterns, half the other kinds): "
	       "%ld mismatches (%.0f s).\n", n, bad, now() - t0);
	return bad != 0;
}
