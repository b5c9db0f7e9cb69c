/*
 * fmt_double - runtime/run/fmt.c's csf_fmt_double against the loop it
 * replaced (tests/fmt_ref.h: %.15g, %.16g, %.17g, the first that strtod
 * reads back), value by value, on:
 *
 *  - zeros, infinities, NaN; the smallest and largest subnormals, DBL_MIN,
 *    DBL_MAX; every power of two from 2^-1074 to 2^1023 (the lopsided
 *    intervals, all of them) and every power of ten from 1e-323 to 1e308,
 *    with their neighbours both ways;
 *  - decimals that fall halfway between two of 15 or 16 digits; integers to
 *    2^53, and around 1e15, 1e16, 1e17 (where %g turns to an exponent);
 *    0.1, 1/3, 5e-5, 1e-4, 9.999999999999999e22 and the like;
 *  - N random 64-bit patterns (NaN aside), N values of the kinds a run
 *    writes (fractions, multiples of 0.01, short decimals, magnitudes from
 *    1e-30 to 1e30), N / 4 subnormals of every length, from a fixed seed.
 *
 * Each value with either sign. A mismatch prints "FAIL: " and the value's
 * bits (the first 20); the harness shows first that a deliberate one is
 * caught. Also prints the time per value of both (informational).
 *
 *   fmt-test [N]   (N = 500000 by default: 1.1e6 random values in all)
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "csf.h"
#include "fmt_ref.h"

static unsigned long nchecked, nfailed;

static void check1(double x)
{
	char msg[200];
	nchecked++;
	if (fmt_ref_mismatch(csf_fmt_double, x, msg, sizeof msg) && nfailed++ < 20) printf("FAIL: %s\n", msg);
}

/* x and -x */
static void check(double x)
{
	check1(x);
	check1(-x);
}

/* x, its neighbours both ways, each with either sign */
static void around(double x)
{
	check(x);
	check(nextafter(x, INFINITY));
	check(nextafter(x, -INFINITY));
}

static double parse(const char *s) { return strtod(s, NULL); }

static uint64_t seed = 0x2545F4914F6CDD1D;

/* splitmix64 */
static uint64_t rnd(void)
{
	uint64_t z = (seed += 0x9E3779B97F4A7C15);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EB;
	return z ^ (z >> 31);
}

static double from_bits(uint64_t b)
{
	double x;
	memcpy(&x, &b, sizeof x);
	return x;
}

/* a uniform double in [0, 1) */
static double unif(void) { return (double)(rnd() >> 11) * 0x1p-53; }

/* a formatter wrong on one value: the harness must report it */
static void wrong_on_tenth(char buf[32], double x)
{
	csf_fmt_double(buf, x);
	if (x == 0.1) buf[strlen(buf) - 1]++;
}

static double now(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ns per value of fmt over v[0..n) */
static double time_per_value(void (*fmt)(char buf[32], double x), const double *v, size_t n)
{
	char b[32];
	unsigned sum = 0;
	double t0 = now();
	for (size_t i = 0; i < n; i++) {
		fmt(b, v[i]);
		sum += (unsigned char)b[0];
	}
	double t = now() - t0;
	if (sum == 1) puts(""); /* keeps the calls */
	return 1e9 * t / (double)n;
}

int main(int argc, char **argv)
{
	long n = argc > 1 ? atol(argv[1]) : 500000;
	char msg[200], s[64];

	/* the harness: a deliberate mismatch is caught, with the bits */
	if (!fmt_ref_mismatch(wrong_on_tenth, 0.1, msg, sizeof msg) || !strstr(msg, "0x3fb999999999999a")) {
		printf("FAIL: a deliberate mismatch on 0.1 was not reported\n");
		return 1;
	}
	printf("a deliberate mismatch is reported as: %s\n", msg);

	/* zeros, infinities, NaN, the ends of the subnormals and normals */
	check(0);
	check(INFINITY);
	check1(NAN);
	check1(-NAN);
	around(from_bits(1));                     /* 4.9e-324 */
	around(from_bits(0x000fffffffffffff));    /* the largest subnormal */
	around(DBL_MIN);
	around(DBL_MAX);
	/* every power of two, every power of ten, and 5 and 9.99.. times the powers of ten */
	for (int e = -1074; e <= 1023; e++) around(ldexp(1, e));
	for (int e = -323; e <= 308; e++) {
		snprintf(s, sizeof s, "1e%d", e);
		around(parse(s));
		snprintf(s, sizeof s, "5e%d", e);
		around(parse(s));
		snprintf(s, sizeof s, "9.999999999999999e%d", e);
		around(parse(s));
		snprintf(s, sizeof s, "9.99999999999999e%d", e);
		around(parse(s));
	}
	/* halfway between two decimals of 15 and of 16 digits, at every exponent */
	for (int i = 0; i < 20000; i++) {
		int e = (int)(rnd() % 630) - 320, d = 15 + i % 2;
		snprintf(s, sizeof s, "%.*" PRIu64 "5e%d", d, rnd() % (uint64_t)(d == 15 ? 900000000000000 : 9000000000000000) +
		         (uint64_t)(d == 15 ? 100000000000000 : 1000000000000000), e);
		around(parse(s));
	}
	/* integers: all to 1e5, random ones to 2^53, and those around 2^53, 1e14 .. 1e18 */
	for (int i = 0; i <= 100000; i++) check(i);
	for (int i = 0; i < 20000; i++) check((double)(rnd() >> 11));
	for (int i = -2000; i <= 2000; i++) {
		check(0x1p53 + 2 * i);
		check(1e14 + i);
		check(1e15 + i);
		check(1e16 + 2 * i);
		check(1e17 + 16 * i);
		check(1e18 + 128 * i);
	}
	/* the steps just below and above 1e15, 1e16, 1e17 (the exponent switch of %g) */
	for (int e = 14; e <= 18; e++) {
		double a = pow(10, e), b = a;
		for (int i = 0; i < 200; i++) {
			check(a = nextafter(a, 0));
			check(b = nextafter(b, INFINITY));
		}
	}
	const double named[] = { 0.1, 0.2, 0.3, 0.1 * 3, 1.0 / 3, 2.0 / 3, 5e-5, 1e-4, 1e-5, 9.999999999999999e22, 1e23,
		                 0.5, 1.5, 123.456, 3.141592653589793, 2.718281828459045, 6.02214076e23, 1.602176634e-19,
		                 299792458, 9.81, 1e21, 1e22, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308 };
	for (size_t i = 0; i < sizeof named / sizeof named[0]; i++) around(named[i]);
	unsigned long nspecial = nchecked;

	/* random: bit patterns (no NaN), values of the kinds a run writes, subnormals of every length */
	for (long i = 0; i < n; i++) {
		uint64_t b = rnd();
		if ((b >> 52 & 0x7ff) == 0x7ff && (b & 0xfffffffffffff)) continue;
		check1(from_bits(b));
	}
	for (long i = 0; i < n; i++) {
		switch (i % 6) {
		case 0: check(unif()); break;
		case 1: check(0.01 * (double)(rnd() % 1000000)); break;
		case 2: check(sin(10 * unif())); break;
		case 3: check(unif() * pow(10, (double)(rnd() % 61) - 30)); break;
		case 4:
			snprintf(s, sizeof s, "%" PRIu64 "e%d", rnd() % 1000000, (int)(rnd() % 40) - 20);
			check(parse(s));
			break;
		default: check((double)(rnd() % 100000) / (double)(1 + rnd() % 1000)); break;
		}
	}
	for (long i = 0; i < n / 4; i++) check(from_bits(rnd() >> (12 + rnd() % 52)));

	/* the time per value, on random bit patterns and on a run's kind of values */
	enum { T = 200000 };
	double *v = malloc(2 * T * sizeof *v);
	if (!v) return 2;
	for (int i = 0; i < T; i++) {
		uint64_t b;
		while (((b = rnd()) >> 52 & 0x7ff) == 0x7ff) {}
		v[i] = from_bits(b);
		v[T + i] = i % 2 ? 0.01 * i : sin(0.001 * i);
	}
	printf("ns per value, new / old: random bit patterns %.1f / %.1f; a run's kind of values %.1f / %.1f\n",
	       time_per_value(csf_fmt_double, v, T), time_per_value(fmt_ref, v, T),
	       time_per_value(csf_fmt_double, v + T, T), time_per_value(fmt_ref, v + T, T));
	free(v);
	printf("%lu values (%lu special, %lu random), %lu mismatches\n", nchecked, nspecial, nchecked - nspecial, nfailed);
	return nfailed != 0;
}
