/*
 * fmt_log.h - the two logarithms fmt.c's conversion of a double needs, in
 * integer arithmetic: floor(q log10 2) and floor(k log2 10). The table
 * generator fmt_gen.c includes this header too and checks both, exactly, over
 * every q and k that fmt.c passes (the build fails if one is wrong).
 */
#ifndef CSF_FMT_LOG_H
#define CSF_FMT_LOG_H

#include <stdint.h>

/* floor(v / 2^32) for v > -2^48 (>> on a negative number is the compiler's choice in C: shifted
   when made positive) */
static inline int csf_floor_shift32(int64_t v)
{
	return (int)((uint64_t)(v + ((int64_t)1 << 48)) >> 32) - 65536;
}

/* floor(q log10(2)), for -1100 <= q <= 1100 (1292913986 = floor(log10(2) 2^32)) */
static inline int csf_flog10pow2(int q)
{
	return csf_floor_shift32((int64_t)q * 1292913986);
}

/* floor(k log2(10)), for -400 <= k <= 400 (14267572527 = floor(log2(10) 2^32)) */
static inline int csf_flog2pow10(int k)
{
	return csf_floor_shift32((int64_t)k * 14267572527);
}

#endif
