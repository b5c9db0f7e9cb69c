/*
 * fields.h - the .csfb payload's fields, listed once: the table csf_fields
 * (fields.c), in file order. csf_encode writes the fields in its order,
 * csf_decode reads them, csf_prog_free frees them and csf_verify checks
 * them (bytecode.c); csf(5) describes the same fields in the same order.
 */
#ifndef CSF_FIELDS_H
#define CSF_FIELDS_H

#include <stddef.h>

#include "csf_int.h"

/* Where a field's element count is. */
enum csf_field_count {
	CSF_FC_PREFIX, /* a u32 in the file before the elements; in csf_prog at offset count */
	CSF_FC_NY,     /* p->ny (read before, with layout): one element per state component; not in the file */
	CSF_FC_INLINE, /* the constant count; the elements are in csf_prog itself at offset at, not behind a pointer */
};

/*
 * One field. An element is, in the file, words u32 (taken from the first
 * words u32 of the element in memory) then dbls doubles (from offset dbl_at
 * of the element); words = dbls = 0: one byte (the strings). csf_verify
 * applies ok to each element (failing with the message bad, a printf format
 * given the element's index as unsigned long and the section as int), then
 * check to the whole field.
 */
typedef struct csf_field {
	const char *name;    /* as csf(5) names it */
	unsigned char how;   /* enum csf_field_count */
	signed char sec;     /* a code section's field: the section (CSF_SEC_*); else -1 */
	unsigned char words, dbls;
	unsigned char runs;  /* doubles (dbls 1, words 0) stored as runs of equal values and zeros (csf_put_runs) */
	unsigned char progs; /* elements of u32 words only (size 4 * words) stored as progressions (bytecode.h) */
	unsigned char kept;  /* progs, and decoded as they are in the file (the bytes at kept_at, their count at
	                        kept_len), the elements' pointer left NULL; a program csfc builds has the elements */
	size_t at;           /* offsetof(csf_prog, the pointer to the elements), or (INLINE) of the elements */
	size_t count;        /* PREFIX: offsetof(csf_prog, the uint32_t count); INLINE: the count */
	size_t size;         /* sizeof an element in memory */
	size_t dbl_at;       /* offset of the doubles in an element */
	size_t kept_at, kept_len; /* kept: offsetof(csf_prog, the unsigned char *), (the uint32_t byte count) */
	int (*ok)(const csf_prog *p, int sec, const void *e, uint32_t i);
	const char *bad;
	int (*check)(const csf_prog *p, int sec, char *err, size_t errlen); /* 0, or -1 with the reason */
} csf_field;

extern const csf_field csf_fields[];
extern const size_t csf_nfields;

/* The instruction verifier (bytecode.c): the check of the code field of section sec. */
int csf_verify_code(const csf_prog *p, int sec, char *err, size_t errlen);

#endif
