/*
 * fmt.c - numbers as the run writes them: a double in the fewest digits that
 * read back to it (every CSV cell), a step rounded down to suggest, and a
 * ratio or a count as a person writes it.
 *
 * csf_fmt_double writes, byte for byte, what the loop it replaced wrote
 * (issue 30): the first of printf's %.15g, %.16g and %.17g that strtod
 * reads back to x. It uses neither: it scales x by a power of ten with
 * Schubfach's exact scaling (R. Giulietti, "The Schubfach way to render
 * doubles", 2020; the table of powers of ten, fmt_pow10.h, is written at
 * build time by fmt_gen.c with exact integer arithmetic), then rounds the
 * scaled value itself to 15, 16 and 17 digits as printf does (to nearest,
 * ties to even) and tests each against the interval of the reals that
 * strtod rounds to x, as the old loop tested with strtod. Not Schubfach's
 * shortest digits, then, but printf's correctly rounded ones, which differ:
 *
 *  - at a power of two the interval reaches twice as far above x as below,
 *    so the nearest 16 digits (below x) may miss it where others (above)
 *    are in it; the old loop, and this, then print 17 digits;
 *  - a subnormal keeps 15 digits, all correct, where its shortest is fewer
 *    (5e-324 is 4.94065645841247e-324);
 *  - P, at which the loop stopped, decides the notation: exponent when the
 *    exponent of the rounded number is below -4 or at least P ("1e+15").
 *
 * The scaling multiplies c 2^q (x's integer significand c, c < 2^53) by
 * 10^k, k = -floor(q log10 2), so that F = x 10^k has 16 or 17 digits;
 * Schubfach's rop keeps two bits of its fraction and one sticky bit (the
 * paper proves the 126-bit table enough for this k), which decide every
 * comparison below exactly: with 17 digits (F >= 1e16), %.15g and %.16g
 * round F at its hundreds and tens; with 16 (F < 1e16, only where 10^k 2^q
 * < 2.3, so that the interval is at least 1 wide) the nearest integer to F
 * is always in the interval and %.17g never needed. Two cases leave the
 * paper's ground, and each is tested over all its members (tests/fmt_double.c):
 *
 *  - the 2045 powers of two from 2^-1021 up, whose lopsided interval may need
 *    %.17g where F has 16 digits: they are scaled once more, by 10^(k+1);
 *  - subnormals below 1e-309 (x 10^324 < 1e15): %.15g always reads back
 *    (its error, 5e-325 at most, is within the half ulp, 2.5e-324), and its
 *    digits are computed exactly: c 5^K in 32-bit limbs, shifted. Slower
 *    (some 300 ns), and such values do not occur in a run's rows.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"
#include "fmt_log.h"
#include "fmt_pow10.h" /* generated: csf_pow10[k - CSF_POW10_MIN], 10^k's 126 leading bits rounded up */

#define E15 UINT64_C(1000000000000000)
#define E16 UINT64_C(10000000000000000)

/* a b: its high 64 bits, the low ones in *lo */
static inline uint64_t mul64(uint64_t a, uint64_t b, uint64_t *lo)
{
#ifdef __SIZEOF_INT128__
	unsigned __int128 p = (unsigned __int128)a * b;
	*lo = (uint64_t)p;
	return (uint64_t)(p >> 64);
#else
	uint64_t a0 = (uint32_t)a, a1 = a >> 32, b0 = (uint32_t)b, b1 = b >> 32;
	uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0;
	uint64_t mid = (p00 >> 32) + (uint32_t)p01 + (uint32_t)p10;
	*lo = mid << 32 | (uint32_t)p00;
	return a1 * b1 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/*
 * g cp / 2^128 rounded to odd: its integer part, with the last bit set when
 * it is not an integer (Schubfach's rop). g is above the exact power by less
 * than one unit, so a fraction below cp / 2^128 is that excess alone: the
 * exact product is then an integer.
 */
static inline uint64_t scale_odd(const uint64_t g[2], uint64_t cp)
{
	uint64_t l0, l1 = mul64(g[1], cp, &l0);
	uint64_t h0, h1 = mul64(g[0], cp, &h0);
	uint64_t mid = h0 + l1, top = h1 + (mid < l1);
	return top | (uint64_t)(mid != 0 || l0 >= cp);
}

/*
 * x 10^k and the ends of the interval strtod rounds to x, each times 4 and
 * rounded to odd: 4 x 10^k rounded to odd compares with every even integer
 * exactly, which is all the comparisons below need.
 */
typedef struct {
	uint64_t v, lo, hi;
	int k;
} scaled;

static inline void scale(scaled *s, uint64_t c, int q, int k, int lopsided)
{
	const uint64_t *g = csf_pow10[k - CSF_POW10_MIN];
	int h = q + csf_flog2pow10(k) + 3; /* 3..9: cb 2^h below 2^64 */
	uint64_t cb = c << 2;
	s->k = k;
	s->v = scale_odd(g, cb << h);
	s->lo = scale_odd(g, (cb - 2 + (uint64_t)lopsided) << h); /* x less half an ulp (a quarter: lopsided) */
	s->hi = scale_odd(g, (cb + 2) << h);
}

/* F (v = 4F rounded to odd) to the nearest multiple of unit, ties to even, as printf rounds
   (inline, unit a constant at each call: no division; no branch either, here and below,
   where the way would depend on the digits) */
static inline uint64_t round_to(uint64_t v, uint64_t unit)
{
	uint64_t n = (v >> 2) / unit, rem = v - 4 * unit * n;
	return (n + ((rem > 2 * unit) | ((rem == 2 * unit) & n))) * unit;
}

/* does n 10^-k read back to x: in the interval, its ends too when x's c is even (ties to even) */
static inline uint64_t reads_back(const scaled *s, uint64_t n, uint64_t odd)
{
	uint64_t lo = s->lo + odd, hi = s->hi - odd;
	return 4 * n - lo <= hi - lo;
}

/* v's 8 bytes at p, the lowest first */
static inline void store8(char *p, uint64_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
	memcpy(p, &v, 8);
#else
	for (int i = 0; i < 8; i++) p[i] = (char)(v >> 8 * i);
#endif
}

/* the 8 decimal digits of v < 1e8 in ASCII, the first in the lowest byte: 4 + 4, 2 + 2 in each, 1 + 1 */
static inline uint64_t ascii8(uint32_t v)
{
	uint64_t x = (uint64_t)(v / 10000) | (uint64_t)(v % 10000) << 32;
	uint64_t h = (x * 10486 >> 20) & 0x0000007f0000007f; /* / 100 in each half (below 10000) */
	x = h | (x - h * 100) << 16;
	h = (x * 103 >> 10) & 0x000f000f000f000f; /* / 10 in each quarter (below 100) */
	x = h | (x - h * 10) << 8;
	return x + 0x3030303030303030;
}

#define ZEROS UINT64_C(0x3030303030303030) /* "00000000" */

/* the '0's at the end of w (ascii8, not all '0') */
static inline int zeros_after(uint64_t w)
{
#ifdef __GNUC__
	return __builtin_clzll(w ^ ZEROS) / 8;
#else
	int n = 0;
	while ((w >> (56 - 8 * n) & 0xff) == '0') n++;
	return n;
#endif
}

/*
 * (-)n 10^e10, 10^16 <= n <= 10^17, as %.Pg writes it (trailing zeros
 * dropped), at dst (32 bytes): its length. n's 17 digits are one digit and
 * two words of eight (ascii8), stored where they go, the point put in
 * between by storing the tail again, shifted; every store stays within
 * dst's 32 bytes (the text is 24 at most). Nothing is read back.
 */
static int put(char *dst, int neg, uint64_t n, int e10, int P)
{
	if (n == 10 * E16) n = E16, e10++;
	uint64_t m = n % E16;
	char d0 = (char)('0' + n / E16);
	uint64_t a = ascii8((uint32_t)(m / 100000000)), b = ascii8((uint32_t)(m % 100000000));
	int len = 17 - (b != ZEROS ? zeros_after(b) : a != ZEROS ? 8 + zeros_after(a) : 16);
	int x = e10 + 16; /* the exponent of %e */
	char *p = dst + neg;
	dst[0] = '-';
	if ((unsigned)(x + 4) >= (unsigned)(P + 4)) { /* d.ddde+xx: x < -4 or x >= P */
		p[0] = d0;
		p[1] = '.';
		store8(p + 2, a);
		store8(p + 10, b);
		p += len > 1 ? len + 1 : 1;
		p[0] = 'e';
		p[1] = (char)('+' + 2 * (x < 0)); /* '-' */
		if (x < 0) x = -x;
		p[2] = (char)('0' + x / 100);
		p += 2 + (x >= 100);
		x %= 100;
		p[0] = (char)('0' + x / 10);
		p[1] = (char)('0' + x % 10);
		p += 2;
	} else if (x < 0) { /* 0.000ddd */
		memcpy(p, "0.0000", 6);
		p += 1 - x;
		p[0] = d0;
		store8(p + 1, a);
		store8(p + 9, b);
		p += len;
	} else if (len <= x + 1) { /* ddd000: n's own trailing '0's */
		p[0] = d0;
		store8(p + 1, a);
		store8(p + 9, b);
		p += x + 1;
	} else { /* ddd.ddd: after x + 1 digits (x < 16) the point, then the digits from a's byte x on */
		p[0] = d0;
		store8(p + 1, a);
		store8(p + 9, b);
		p[x + 1] = '.';
		if (x < 8) {
			store8(p + x + 2, a >> 8 * x | (b << 1) << (63 - 8 * x));
			store8(p + x + 10, b >> 8 * x);
		} else {
			store8(p + x + 2, b >> 8 * (x - 8));
		}
		p += len + 1;
	}
	*p = 0;
	return (int)(p - dst);
}

/*
 * x = c 2^-1074 below 1e-309, whose x 10^324 has nd digits (below 16): its
 * %.15g, exactly. F = x 10^K has 15 digits for K = 339 - nd; 4F rounded to
 * odd is c 5^K shifted right by 1072 - K, the sticky bit any bit shifted out.
 */
static int tiny(char *dst, int neg, uint64_t c, int nd)
{
	enum { LIMBS = 28 }; /* c 5^338 < 2^48 2^785 */
	uint32_t w[LIMBS] = { (uint32_t)c, (uint32_t)(c >> 32) };
	int K = 339 - nd, n = 2;
	for (int r = K; r > 0; r -= 13) {
		uint32_t m = 1; /* 5^13 at most: below 2^32 */
		for (int j = 0; j < r && j < 13; j++) m *= 5;
		uint64_t carry = 0;
		for (int i = 0; i < n; i++) {
			uint64_t t = (uint64_t)w[i] * m + carry;
			w[i] = (uint32_t)t;
			carry = t >> 32;
		}
		if (carry && n < LIMBS) w[n++] = (uint32_t)carry;
	}
	int sh = 1072 - K, i = sh / 32, b = sh % 32;
	uint64_t lo = w[i] | (uint64_t)w[i + 1] << 32, v = lo >> b;
	if (b) v |= (uint64_t)w[i + 2] << (64 - b);
	int sticky = (w[i] & ((UINT32_C(1) << b) - 1)) != 0;
	for (int j = 0; j < i; j++) sticky |= w[j] != 0;
	return put(dst, neg, 100 * round_to(v | (uint64_t)sticky, 1), -K - 2, 15);
}

int csf_fmt_put(char *dst, double x)
{
	uint64_t b;
	memcpy(&b, &x, sizeof b);
	uint64_t c = b & ((UINT64_C(1) << 52) - 1);
	int be = (int)(b >> 52 & 0x7ff), neg = (int)(b >> 63);
	if (be == 0x7ff || (be == 0 && c == 0)) {
		const char *w = be ? c ? "nan" : neg ? "-inf" : "inf" : neg ? "-0" : "0";
		strcpy(dst, w);
		return (int)strlen(w);
	}
	/* x = c 2^q; a power of two (but the smallest normal) has half the room below it */
	int lopsided = c == 0 && be > 1, q = be ? be - 1075 : -1074;
	if (be) c |= UINT64_C(1) << 52;
	scaled s;
	scale(&s, c, q, -csf_flog10pow2(q), lopsided);
	uint64_t a = s.v >> 2; /* floor(F), F = x 10^k: 16 or 17 digits (fewer for a subnormal) */
	if (lopsided & (a < E16)) {
		scale(&s, c, q, s.k + 1, lopsided);
		a = s.v >> 2;
	}
	if (a < E15) {
		int nd = 1;
		for (uint64_t t = a; t >= 10; t /= 10) nd++;
		return tiny(dst, neg, c, nd);
	}
	/* %.15g, %.16g, %.17g: with 17 digits (big), F rounded at its hundreds, tens and units; with
	   16, at its tens and units, and the units always read back */
	uint64_t odd = c & 1, big = a >= E16, v = s.v;
	uint64_t u1 = round_to(v, 1), u10 = round_to(v, 10), u100 = round_to(v, 100);
	uint64_t n15 = big ? u100 : u10, n16 = big ? u10 : u1;
	uint64_t ok15 = reads_back(&s, n15, odd), ok16 = (big ^ 1) | reads_back(&s, n16, odd);
	uint64_t n = ok15 ? n15 : ok16 ? n16 : u1;
	int P = ok15 ? 15 : ok16 ? 16 : 17;
	return put(dst, neg, big ? n : 10 * n, -s.k - !big, P);
}

void csf_fmt_double(char buf[32], double x) { csf_fmt_put(buf, x); }

/* x rounded down to one significant digit: a step to suggest. */
double csf_run_round_down(double x)
{
	double e = pow(10, floor(log10(x))), d = floor(x / e * (1 + 1e-12));
	return d * e;
}

/* A ratio or a count as a person writes it: 350, 1e6, 2.5e6. */
void csf_run_fmt_ratio(char buf[32], double x)
{
	if (x < 1e4) {
		snprintf(buf, 32, "%.0f", x);
		return;
	}
	char m[16];
	int ex = (int)floor(log10(x));
	double mant = x / pow(10, ex);
	if (mant >= 9.95) mant /= 10, ex++;
	snprintf(m, sizeof m, "%.2g", mant);
	snprintf(buf, 32, "%se%d", m, ex);
}

