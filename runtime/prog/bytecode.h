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
 * The payload is these fields in this order (count-prefixed arrays; every
 * count is checked against the bytes that remain before anything is
 * allocated):
 *
 *   strings   u32 n, n bytes (NUL-terminated strings; last byte is NUL)
 *   memory    u32 nmem, nmem doubles (initial image)
 *   layout    u32 tslot, ystart, dstart, ny, jtan
 *   yscale    ny doubles (tolerance scale of each state component, > 0)
 *   yatol     ny doubles (absolute tolerance the scene sets for each state
 *             component, >= 0; 0: none)
 *   vpair     ny u32 (1 + velocity index of a position component, else 0)
 *   run       double till, by
 *   files     u32 n, n x {u32 name}
 *   sources   u32 n, n x {u32 file, line, text}
 *   columns   u32 n, n x {u32 name, slot}
 *   asserts   u32 n, n x {u32 src, object}
 *   objects   u32 n, n x {u32 name}
 *   props     u32 n, n x {u32 object, name, slot, width, cls}
 *   units     CSF_NDIM (4) doubles: the model's units of length, mass, time,
 *             current in SI (> 0)
 *   globals   u32 n, n x {u32 name, slot, width, cls}: the globals -D sets
 *   pclasses  u32 n, n x {u32 unit, why, known, CSF_NDIM doubles dim}: what -D
 *             needs to read a value of a property or global (its
 *             dimension and unit), or why it cannot be set (csf.h)
 *   events    u32 n, n x {u32 kind, value, mode, src}
 *   cbodies   u32 n, n x {u32 plane, object, varies, CSF_CF_N slots}: the
 *             bodies of the contact routine, mass points and planes (csf.h)
 *   cmembers  u32 n, n x u32: the contact rules' lists of bodies
 *   crules    u32 n, n x {u32 src, every, first0, n0, first1, n1}: the
 *             contact rules, each with its $0 and $1 lists in cmembers
 *   then for each code section (RHS, OUT, JAC):
 *   targets   u32 n, n x {u32 slot, width, src, name, object}
 *   code      u32 n, n words (opcode, operands...)
 *   lines     u32 n, n x {u32 pc, src}
 *
 * The loader (csf_decode) rejects any file whose fields or instructions are
 * out of range; see csf_verify in bytecode.c for the full list of checks.
 */
#ifndef CSF_BYTECODE_H
#define CSF_BYTECODE_H

#define CSFB_MAGIC "CSFB"
#define CSFB_VERSION 11u
#define CSFB_INT_PROBE 0x01020304u
#define CSFB_FLOAT_PROBE 370.5
#define CSFB_HEADER_SIZE 28u

/* CRC-32 of len bytes (the format's checksum). */
unsigned long csf_crc32(const unsigned char *buf, size_t len);

#endif
