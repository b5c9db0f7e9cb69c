/*
 * bytecode.h - the .csfb file format, defined once.
 *
 * All integers are unsigned 32-bit little-endian; doubles are IEEE 754
 * binary64 stored little-endian. A file is a 28-byte header and a payload:
 *
 *   offset  size  field
 *   0       4     magic "CSFB"
 *   4       4     format version (CSFB_VERSION)
 *   8       4     integer probe CSFB_INT_PROBE
 *   12      8     float probe CSFB_FLOAT_PROBE
 *   20      4     payload size in bytes (must equal file size - 28)
 *   24      4     CRC-32 (IEEE 802.3) of the payload
 *
 * The payload's fields, in order, are listed once, in the table csf_fields
 * of fields.c: how each one's element count is given (a u32 before its
 * elements, checked against the bytes that remain before anything is
 * allocated; ny; or constant), how an element is encoded (u32 words, then
 * doubles; the strings are bytes), and what the verifier checks in it.
 * The encoder, the decoder, csf_prog_free and csf_verify all walk that
 * table; csf(5) describes the same fields in the same order (checked by
 * tests/docs/check.sh).
 *
 * The loader (csf_decode) rejects any file whose fields or instructions are
 * out of range: csf_verify (bytecode.c) applies each field's checks of the
 * table, and the instruction verifier to the code.
 */
#ifndef CSF_BYTECODE_H
#define CSF_BYTECODE_H

#define CSFB_MAGIC "CSFB"
#define CSFB_VERSION 15u
#define CSFB_INT_PROBE 0x01020304u
#define CSFB_FLOAT_PROBE 370.5
#define CSFB_HEADER_SIZE 28u

/*
 * A field of doubles stored in runs (csf_field.runs: the memory image, yscale, yatol) is a sequence
 * of runs, each a u32 header h, its kind h >> 30 and its length h & CSFB_RUN_MAX (at least 1): kind 0,
 * that many doubles follow; 1, that many zeros (+0.0), nothing follows; 2, that many copies of the
 * one double that follows. The runs cover the field's element count exactly. A million objects'
 * masses, all equal, take 12 bytes; their zero accelerations 4.
 */
enum { CSFB_RUN_LITERAL, CSFB_RUN_ZEROS, CSFB_RUN_REPEAT };
#define CSFB_RUN_MAX 0x3FFFFFFFu
/* The most elements a field of runs may have (2^27 doubles, 1 GiB): a few bytes of runs cannot make
   the loader allocate more. csfc's scenes have fewer slots in all (compiler/back/slots.c); a million
   objects some 5e7. */
#define CSFB_RUNS_MAX (1u << 27)

/*
 * A table of u32 words (csf_field.progs: vpair and every table of structs of u32 but the code) is
 * a sequence of progressions, each two u32, g (at least 1) and k (at least 1), then g elements (a
 * group) and, when k > 1, g more: the difference, word by word, from each group to the next (u32
 * arithmetic, wrapping). It stands for the k groups group + j * difference, j = 0 .. k - 1 (g * k
 * elements); k = 1 is g elements as they are. The progressions cover the field's count exactly.
 * A million members' properties, each the same few with slots a stride apart, take one
 * progression of a group of their few: 8 + 2 * 20 * few bytes.
 */
#define CSFB_PROG_GROUP_MAX 16u /* the longest group the encoder looks for */
#define CSFB_PROG_WORDS_MAX 8u  /* the most words of an element of a table kept as progressions (fields.c) */
/* The most bytes a table of progressions may take in memory (as CSFB_RUNS_MAX: 1 GiB). */
#define CSFB_PROGS_BYTES_MAX (1u << 30)

/* CRC-32 of len bytes (the format's checksum). */
unsigned long csf_crc32(const unsigned char *buf, size_t len);

#endif
