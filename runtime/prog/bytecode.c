/*
 * bytecode.c - encoding, decoding, verification and listing of .csfb files.
 *
 * The format is described in bytecode.h. Decoding reads through a bounded
 * cursor: every read checks the bytes left, every array count is checked
 * against the bytes left before it is allocated, so a truncated or hostile
 * file costs at most its own size in memory. After decoding, csf_verify
 * checks every cross-reference (string offsets, memory slots, sources) and
 * every instruction (opcode in range, operands in bounds for every value of
 * the loop registers they use, jumps forward to an instruction boundary
 * inside the section and inside the same loop body, loops properly nested
 * and matched, POWI's exponent within CSF_POWI_MAX). A verified program
 * cannot make the VM read or write outside its memory or loop forever.
 */
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <stdarg.h>

#include "csf_int.h"
#include "bytecode.h"
#include "insn.h"

_Static_assert(sizeof(csf_src) == 12 && sizeof(csf_col) == 8 && sizeof(csf_assert) == 8 && sizeof(csf_prop) == 20 &&
               sizeof(csf_global) == 16 &&
               sizeof(csf_target) == 20 && sizeof(csf_line) == 8 && sizeof(csf_cbody) == 4 * (3 + CSF_CF_N) &&
               sizeof(csf_crule) == 24, "tables are arrays of u32");

const csf_opinfo csf_opinfo_table[CSF_NOPCODES] = {
#define OP(name, n, a, b, c, d, syn) \
	[CSF_OP_##name] = { #name, syn, n, { CSF_K_##a, CSF_K_##b, CSF_K_##c, CSF_K_##d } },
#define CTRL OP
#include "opcodes.def"
#undef CTRL
#undef OP
};

/*
 * CRC-32 (reflected polynomial 0xEDB88320), eight bytes a step ("slicing by
 * 8"): t[0][b] is the CRC of byte b, t[k][b] that of b followed by k zero
 * bytes, so the CRC of eight bytes is the exclusive or of eight lookups
 * (tables computed once). The bitwise loop took 8 steps per byte of a 60 MB
 * image, a byte-wise table most of csfvm's start-up.
 */
unsigned long csf_crc32(const unsigned char *buf, size_t len)
{
	static uint32_t t[8][256];
	static int ready;
	if (!ready) {
		for (uint32_t n = 0; n < 256; n++) {
			uint32_t c = n;
			for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
			t[0][n] = c;
		}
		for (int k = 1; k < 8; k++)
			for (uint32_t n = 0; n < 256; n++) t[k][n] = (t[k - 1][n] >> 8) ^ t[0][t[k - 1][n] & 0xFFu];
		ready = 1;
	}
	uint32_t crc = 0xFFFFFFFFu;
	size_t i = 0;
	for (; i + 8 <= len; i += 8) {
		const unsigned char *b = buf + i;
		crc ^= (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
		crc = t[7][crc & 0xFFu] ^ t[6][(crc >> 8) & 0xFFu] ^ t[5][(crc >> 16) & 0xFFu] ^ t[4][crc >> 24] ^
		      t[3][b[4]] ^ t[2][b[5]] ^ t[1][b[6]] ^ t[0][b[7]];
	}
	for (; i < len; i++) crc = (crc >> 8) ^ t[0][(crc ^ buf[i]) & 0xFFu];
	return (unsigned long)(crc ^ 0xFFFFFFFFu);
}

/* ---- encoding ---- */

typedef struct wbuf { unsigned char *p; size_t len, cap; int oom; } wbuf;

static void put(wbuf *w, const void *src, size_t n)
{
	if (w->oom) return;
	if (w->len + n > w->cap) {
		size_t cap = w->cap ? w->cap : 4096;
		while (cap < w->len + n) cap *= 2;
		unsigned char *q = realloc(w->p, cap);
		if (!q) { w->oom = 1; return; }
		w->p = q;
		w->cap = cap;
	}
	memcpy(w->p + w->len, src, n);
	w->len += n;
}

static void put_u32(wbuf *w, uint32_t v)
{
	unsigned char b[4] = { v & 0xFF, (v >> 8) & 0xFF, (v >> 16) & 0xFF, (v >> 24) & 0xFF };
	put(w, b, 4);
}

static void put_f64(wbuf *w, double d)
{
	uint64_t u;
	memcpy(&u, &d, 8);
	put_u32(w, (uint32_t)u);
	put_u32(w, (uint32_t)(u >> 32));
}

static void put_u32s(wbuf *w, const uint32_t *v, size_t n)
{
	for (size_t i = 0; i < n; i++) put_u32(w, v[i]);
}

int csf_encode(const csf_prog *p, unsigned char **out, size_t *len)
{
	wbuf w = { 0 };
	put(&w, CSFB_MAGIC, 4);
	put_u32(&w, CSFB_VERSION);
	put_u32(&w, CSFB_INT_PROBE);
	put_f64(&w, CSFB_FLOAT_PROBE);
	put_u32(&w, 0); /* payload size, patched below */
	put_u32(&w, 0); /* crc, patched below */

	put_u32(&w, p->nstrs);
	put(&w, p->strs, p->nstrs);
	put_u32(&w, p->nmem);
	for (uint32_t i = 0; i < p->nmem; i++) put_f64(&w, p->mem0[i]);
	put_u32(&w, p->tslot);
	put_u32(&w, p->ystart);
	put_u32(&w, p->dstart);
	put_u32(&w, p->ny);
	put_u32(&w, p->jtan);
	for (uint32_t i = 0; i < p->ny; i++) put_f64(&w, p->yscale[i]);
	for (uint32_t i = 0; i < p->ny; i++) put_f64(&w, p->yatol[i]);
	put_u32s(&w, p->vpair, p->ny);
	put_f64(&w, p->till);
	put_f64(&w, p->by);
	put_u32(&w, p->nfiles);
	put_u32s(&w, p->files, p->nfiles);
	put_u32(&w, p->nsrcs);
	put_u32s(&w, (const uint32_t *)p->srcs, 3 * (size_t)p->nsrcs);
	put_u32(&w, p->ncols);
	put_u32s(&w, (const uint32_t *)p->cols, 2 * (size_t)p->ncols);
	put_u32(&w, p->nasserts);
	put_u32s(&w, (const uint32_t *)p->asserts, 2 * (size_t)p->nasserts);
	put_u32(&w, p->nobjects);
	put_u32s(&w, p->objects, p->nobjects);
	put_u32(&w, p->nprops);
	put_u32s(&w, (const uint32_t *)p->props, 5 * (size_t)p->nprops);
	for (int i = 0; i < CSF_NDIM; i++) put_f64(&w, p->ubase[i]);
	put_u32(&w, p->nglobals);
	put_u32s(&w, (const uint32_t *)p->globals, 4 * (size_t)p->nglobals);
	put_u32(&w, p->npclasses);
	for (uint32_t i = 0; i < p->npclasses; i++) {
		const csf_pclass *c = &p->pclasses[i];
		put_u32(&w, c->unit);
		put_u32(&w, c->why);
		put_u32(&w, c->known);
		for (int k = 0; k < CSF_NDIM; k++) put_f64(&w, c->dim[k]);
	}
	put_u32(&w, p->nevents);
	put_u32s(&w, (const uint32_t *)p->events, 4 * (size_t)p->nevents);
	put_u32(&w, p->ncbodies);
	put_u32s(&w, (const uint32_t *)p->cbodies, (3 + CSF_CF_N) * (size_t)p->ncbodies);
	put_u32(&w, p->ncmembers);
	put_u32s(&w, p->cmembers, p->ncmembers);
	put_u32(&w, p->ncrules);
	put_u32s(&w, (const uint32_t *)p->crules, 6 * (size_t)p->ncrules);
	for (int s = 0; s < CSF_NSEC; s++) {
		put_u32(&w, p->ntargets[s]);
		put_u32s(&w, (const uint32_t *)p->targets[s], 5 * (size_t)p->ntargets[s]);
		put_u32(&w, p->ncode[s]);
		put_u32s(&w, p->code[s], p->ncode[s]);
		put_u32(&w, p->nlines[s]);
		put_u32s(&w, (const uint32_t *)p->lines[s], 2 * (size_t)p->nlines[s]);
	}
	if (w.oom || w.len - CSFB_HEADER_SIZE > 0xFFFFFFFFu) {
		free(w.p);
		return -1;
	}
	size_t plen = w.len - CSFB_HEADER_SIZE;
	unsigned long crc = csf_crc32(w.p + CSFB_HEADER_SIZE, plen);
	for (int i = 0; i < 4; i++) {
		w.p[20 + i] = (unsigned char)(plen >> (8 * i));
		w.p[24 + i] = (unsigned char)(crc >> (8 * i));
	}
	*out = w.p;
	*len = w.len;
	return 0;
}

/* ---- decoding ---- */

typedef struct rbuf { const unsigned char *p; size_t left; const char *what; } rbuf;

static uint32_t le32(const unsigned char *b)
{
	return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static int get_u32(rbuf *r, uint32_t *v)
{
	if (r->left < 4) return -1;
	*v = le32(r->p);
	r->p += 4;
	r->left -= 4;
	return 0;
}

static int get_f64(rbuf *r, double *d)
{
	uint32_t lo, hi;
	if (get_u32(r, &lo) || get_u32(r, &hi)) return -1;
	uint64_t u = (uint64_t)hi << 32 | lo;
	memcpy(d, &u, 8);
	return 0;
}

/* Reads a count of elements of size elem bytes and allocates the array. */
static int get_array(rbuf *r, uint32_t *n, void **arr, size_t elem)
{
	if (get_u32(r, n)) return -1;
	if ((size_t)*n > r->left / elem) return -1;
	*arr = malloc(*n ? (size_t)*n * elem : 1);
	if (!*arr) return -1;
	if (elem == 1) {
		memcpy(*arr, r->p, *n);
		r->p += *n;
		r->left -= *n;
		return 0;
	}
	if (elem == 8) {
		for (uint32_t i = 0; i < *n; i++) get_f64(r, (double *)*arr + i);
		return 0;
	}
	for (size_t i = 0; i < (size_t)*n * (elem / 4); i++) get_u32(r, (uint32_t *)*arr + i);
	return 0;
}

int csf_fail(char *err, size_t errlen, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(err, errlen, fmt, ap);
	va_end(ap);
	return -1;
}

int csf_decode(const unsigned char *buf, size_t len, csf_prog *p, char *err, size_t errlen)
{
	memset(p, 0, sizeof *p);
	if (len < CSFB_HEADER_SIZE) return csf_fail(err, errlen, "file too short for a CSF bytecode header (%zu bytes)", len);
	if (memcmp(buf, CSFB_MAGIC, 4) != 0) return csf_fail(err, errlen, "not a CSF bytecode file (bad magic)");
	if (le32(buf + 4) != CSFB_VERSION)
		return csf_fail(err, errlen, "bytecode format version %lu, this runtime reads version %u",
		            (unsigned long)le32(buf + 4), CSFB_VERSION);
	if (le32(buf + 8) != CSFB_INT_PROBE) return csf_fail(err, errlen, "integer layout probe mismatch");
	{
		rbuf r = { buf + 12, 8, "" };
		double probe;
		get_f64(&r, &probe);
		if (probe != CSFB_FLOAT_PROBE) return csf_fail(err, errlen, "floating-point layout probe mismatch");
	}
	if ((size_t)le32(buf + 20) != len - CSFB_HEADER_SIZE)
		return csf_fail(err, errlen, "payload size %lu does not match file size %zu (truncated or padded file)",
		            (unsigned long)le32(buf + 20), len);
	if (csf_crc32(buf + CSFB_HEADER_SIZE, len - CSFB_HEADER_SIZE) != le32(buf + 24))
		return csf_fail(err, errlen, "checksum mismatch (corrupted file)");

	rbuf r = { buf + CSFB_HEADER_SIZE, len - CSFB_HEADER_SIZE, "" };
	int bad = 0;
	void *a;
#define ARR(n, field, elem) (bad = bad || get_array(&r, &(n), &a, (elem)), (field) = bad ? (field) : a)
	ARR(p->nstrs, p->strs, 1);
	ARR(p->nmem, p->mem0, 8);
	bad = bad || get_u32(&r, &p->tslot) || get_u32(&r, &p->ystart) || get_u32(&r, &p->dstart) || get_u32(&r, &p->ny) ||
	      get_u32(&r, &p->jtan);
	if (!bad && (size_t)p->ny > r.left / 8) bad = 1;
	if (!bad) {
		p->yscale = malloc(p->ny ? p->ny * sizeof(double) : 1);
		bad = !p->yscale;
		for (uint32_t i = 0; !bad && i < p->ny; i++) get_f64(&r, &p->yscale[i]);
	}
	if (!bad && (size_t)p->ny > r.left / 8) bad = 1;
	if (!bad) {
		p->yatol = malloc(p->ny ? p->ny * sizeof(double) : 1);
		bad = !p->yatol;
		for (uint32_t i = 0; !bad && i < p->ny; i++) get_f64(&r, &p->yatol[i]);
	}
	if (!bad && (size_t)p->ny > r.left / 4) bad = 1;
	if (!bad) {
		p->vpair = malloc(p->ny ? p->ny * sizeof(uint32_t) : 1);
		bad = !p->vpair;
		for (uint32_t i = 0; !bad && i < p->ny; i++) get_u32(&r, &p->vpair[i]);
	}
	bad = bad || get_f64(&r, &p->till) || get_f64(&r, &p->by);
	ARR(p->nfiles, p->files, 4);
	ARR(p->nsrcs, p->srcs, sizeof(csf_src));
	ARR(p->ncols, p->cols, sizeof(csf_col));
	ARR(p->nasserts, p->asserts, sizeof(csf_assert));
	ARR(p->nobjects, p->objects, 4);
	ARR(p->nprops, p->props, sizeof(csf_prop));
	for (int i = 0; i < CSF_NDIM; i++) bad = bad || get_f64(&r, &p->ubase[i]);
	ARR(p->nglobals, p->globals, sizeof(csf_global));
	/* a class is 3 u32 and CSF_NDIM doubles in the file */
	bad = bad || get_u32(&r, &p->npclasses) || (size_t)p->npclasses > r.left / (12 + 8 * CSF_NDIM) ||
	      !(p->pclasses = malloc(p->npclasses ? p->npclasses * sizeof *p->pclasses : 1));
	for (uint32_t i = 0; !bad && i < p->npclasses; i++) {
		csf_pclass *c = &p->pclasses[i];
		get_u32(&r, &c->unit);
		get_u32(&r, &c->why);
		get_u32(&r, &c->known);
		for (int k = 0; k < CSF_NDIM; k++) get_f64(&r, &c->dim[k]);
	}
	ARR(p->nevents, p->events, sizeof(csf_event));
	ARR(p->ncbodies, p->cbodies, sizeof(csf_cbody));
	ARR(p->ncmembers, p->cmembers, 4);
	ARR(p->ncrules, p->crules, sizeof(csf_crule));
	for (int s = 0; s < CSF_NSEC; s++) {
		ARR(p->ntargets[s], p->targets[s], sizeof(csf_target));
		ARR(p->ncode[s], p->code[s], 4);
		ARR(p->nlines[s], p->lines[s], sizeof(csf_line));
	}
#undef ARR
	if (bad) {
		csf_prog_free(p);
		return csf_fail(err, errlen, "truncated or malformed payload");
	}
	if (r.left != 0) {
		csf_prog_free(p);
		return csf_fail(err, errlen, "%zu bytes of trailing garbage after the payload", r.left);
	}
	if (csf_verify(p, err, errlen)) {
		csf_prog_free(p);
		return -1;
	}
	return 0;
}

static int slot_ok(const csf_prog *p, uint32_t s, uint32_t width)
{
	return s < p->nmem && width <= p->nmem - s;
}

/*
 * The state of the code check of one section: the instruction boundaries,
 * the loop context of every pc, and the loops open at the pc being checked.
 */
typedef struct code_check {
	const csf_prog *p;
	int sec;
	const uint32_t *code;
	uint32_t n;
	unsigned char *start; /* start[pc]: an instruction starts at pc (or pc == n) */
	uint32_t *ctx;        /* ctx[pc]: 1 + the pc of the innermost loop around pc, 0 outside loops */
	uint32_t open[CSF_LOOP_MAX]; /* the pcs of the LOOPs open, outermost first */
	int depth;            /* how many are open */
	char *err;
	size_t errlen;
} code_check;

/* Fails the check of the instruction at pc (of its operand k + 1 when k >= 0) with a reason. */
static int bad_insn(code_check *c, uint32_t pc, int k, const char *fmt, ...)
{
	char why[160];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(why, sizeof why, fmt, ap);
	va_end(ap);
	const char *name = csf_opinfo_table[c->code[pc]].name;
	if (k >= 0)
		return csf_fail(c->err, c->errlen, "section %d: operand %d of %s at %lu %s", c->sec, k + 1, name,
		            (unsigned long)pc, why);
	return csf_fail(c->err, c->errlen, "section %d: %s at %lu: %s", c->sec, name, (unsigned long)pc, why);
}

/* Finds the instruction boundaries; rejects unknown opcodes and instructions cut off by the end. */
static int check_boundaries(code_check *c)
{
	for (uint32_t pc = 0; pc < c->n;) {
		uint32_t op = c->code[pc];
		if (op >= CSF_NOPCODES)
			return csf_fail(c->err, c->errlen, "section %d: invalid opcode %lu at %lu", c->sec, (unsigned long)op,
			            (unsigned long)pc);
		if (csf_insn_len(op) > c->n - pc)
			return csf_fail(c->err, c->errlen, "section %d: instruction at %lu runs past the end of the code", c->sec,
			            (unsigned long)pc);
		c->start[pc] = 1;
		pc += csf_insn_len(op);
	}
	c->start[c->n] = 1;
	return 0;
}

/*
 * Checks a slot operand word w naming width slots (width 0: an assertion
 * index) for every value its register takes. A relative operand's register
 * must be an open loop's: index (odd register) or 3 times the index (even).
 * Its largest value is base + (count - 1) * stride; a count of 0 is checked
 * as 1, so a body is valid even if it never runs and the bound does not
 * depend on the count's being non-zero. 64-bit arithmetic: no count can
 * wrap the bound around.
 */
static int check_slot(code_check *c, uint32_t pc, int k, uint32_t w, uint32_t width)
{
	uint32_t r = csf_reg(w);
	uint64_t count = 1;
	if (r >= CSF_NREGS) return bad_insn(c, pc, k, "uses invalid register %lu", (unsigned long)r);
	if (r) {
		uint32_t level = csf_reg_level(r);
		if ((int)level > c->depth)
			return bad_insn(c, pc, k, "uses the register of loop level %lu, which is not open",
			                (unsigned long)level);
		count = c->code[c->open[level - 1] + 2];
	}
	uint64_t end = csf_operand_end(w, width, count);
	if (width ? end > c->p->nmem : end >= c->p->nasserts)
		return bad_insn(c, pc, k, "out of range");
	return 0;
}

/* LOOP L, n, end: opens level L, which must be the next level down. Its end is checked at its NEXT. */
static int check_loop(code_check *c, uint32_t pc)
{
	uint32_t level = c->code[pc + 1];
	if (c->depth == CSF_LOOP_MAX) return bad_insn(c, pc, -1, "loops nested deeper than %d", CSF_LOOP_MAX);
	if (level != (uint32_t)c->depth + 1)
		return bad_insn(c, pc, -1, "loop level %lu where level %d is expected", (unsigned long)level, c->depth + 1);
	c->open[c->depth++] = pc;
	return 0;
}

/*
 * NEXT L, start closes the innermost loop: L must be its level, start the
 * pc just past its LOOP, and the LOOP's end the pc just past this NEXT.
 */
static int check_next(code_check *c, uint32_t pc)
{
	if (c->depth == 0) return bad_insn(c, pc, -1, "no LOOP is open");
	uint32_t loop = c->open[c->depth - 1];
	if (c->code[pc + 1] != (uint32_t)c->depth)
		return bad_insn(c, pc, -1, "loop level %lu where the innermost loop is level %d", (unsigned long)c->code[pc + 1],
		                c->depth);
	if (c->code[pc + 2] != loop + csf_insn_len(CSF_OP_LOOP))
		return bad_insn(c, pc, -1, "start %lu is not the body of its LOOP at %lu", (unsigned long)c->code[pc + 2],
		                (unsigned long)loop);
	if (c->code[loop + 3] != pc + csf_insn_len(CSF_OP_NEXT))
		return bad_insn(c, loop, -1, "end %lu is not just past its NEXT at %lu", (unsigned long)c->code[loop + 3],
		                (unsigned long)pc);
	c->depth--;
	return 0;
}

/*
 * One instruction in order, with the loops open before it: the loop
 * structure, every operand but the forward jumps (they need the context of
 * their target, known after the scan), and the instruction's context. A
 * LOOP is outside its own loop, a NEXT inside.
 */
static int check_insn(code_check *c, uint32_t pc)
{
	const csf_opinfo *oi = &csf_opinfo_table[c->code[pc]];
	c->ctx[pc] = c->depth ? c->open[c->depth - 1] + 1 : 0;
	for (int k = 0; k < oi->nops; k++) {
		uint32_t v = c->code[pc + 1 + k];
		int r = 0;
		switch (oi->kind[k]) {
		case CSF_K_DS: case CSF_K_S: case CSF_K_DV: case CSF_K_V:
			r = check_slot(c, pc, k, v, csf_kind_width(oi->kind[k]));
			break;
		case CSF_K_AS: r = check_slot(c, pc, k, v, 0); break;
		case CSF_K_N:
			if (csf_imm(v) < -CSF_POWI_MAX || csf_imm(v) > CSF_POWI_MAX) r = bad_insn(c, pc, k, "out of range");
			break;
		case CSF_K_L: /* LOOP's and NEXT's levels: check_loop, check_next; JEQ's: open loops */
			if (c->code[pc] == CSF_OP_JEQ && (v < 1 || v > (uint32_t)c->depth))
				r = bad_insn(c, pc, k, "is loop level %lu, which is not open", (unsigned long)v);
			break;
		case CSF_K_C: case CSF_K_B: case CSF_K_J: break; /* the count bounds operands; B: check_next; J: later */
		default: r = bad_insn(c, pc, k, "of an invalid kind"); break;
		}
		if (r) return r;
	}
	if (c->code[pc] == CSF_OP_LOOP) return check_loop(c, pc);
	if (c->code[pc] == CSF_OP_NEXT) return check_next(c, pc);
	return 0;
}

/* Forward jumps land on an instruction boundary in their own loop context: none enters or leaves a loop body. */
static int check_jumps(code_check *c)
{
	for (uint32_t pc = 0; pc < c->n;) {
		const csf_opinfo *oi = &csf_opinfo_table[c->code[pc]];
		for (int k = 0; k < oi->nops; k++) {
			uint32_t v = c->code[pc + 1 + k];
			if (oi->kind[k] != CSF_K_J) continue;
			if (!(v > pc && v <= c->n && c->start[v])) return bad_insn(c, pc, k, "out of range");
			if (c->ctx[v] != c->ctx[pc])
				return bad_insn(c, pc, k, "jumps to %lu into or out of a loop body", (unsigned long)v);
		}
		pc += csf_insn_len(c->code[pc]);
	}
	return 0;
}

/* Checks the code of section s: boundaries, loop structure, operands, jumps. */
static int check_code(const csf_prog *p, int s, char *err, size_t errlen)
{
	code_check c = { .p = p, .sec = s, .code = p->code[s], .n = p->ncode[s], .err = err, .errlen = errlen };
	c.start = calloc((size_t)c.n + 1, 1);
	c.ctx = calloc((size_t)c.n + 1, sizeof *c.ctx);
	int r = !c.start || !c.ctx ? csf_fail(err, errlen, "out of memory") : check_boundaries(&c);
	for (uint32_t pc = 0; !r && pc < c.n; pc += csf_insn_len(c.code[pc])) r = check_insn(&c, pc);
	if (!r && c.depth) r = bad_insn(&c, c.open[c.depth - 1], -1, "loop has no NEXT");
	if (!r) r = check_jumps(&c);
	free(c.start);
	free(c.ctx);
	return r;
}

/*
 * The contact tables: every slot in memory (a mass point's position in the
 * state, where the broad phase reads it from state vectors), every body and
 * list in range, a rule's $0 mass points, a `for` rule's two lists as long
 * and its pairs of two objects, and no body twice in a list.
 */
static int verify_contacts(const csf_prog *p, char *err, size_t errlen)
{
	for (uint32_t i = 0; i < p->ncbodies; i++) {
		const csf_cbody *b = &p->cbodies[i];
		static const unsigned char width[CSF_CF_N] = { 3, 3, 3, 1, 1, 1, 1, 1, 3, 3 };
		int ok = b->plane <= 1 && b->varies <= 1 && b->object < p->nobjects;
		for (int f = 0; ok && f < CSF_CF_N; f++) {
			uint32_t w = width[f];
			if (b->plane && f == CSF_CF_R) w = 3; /* a plane's normal */
			if (b->plane && (f == CSF_CF_A || f == CSF_CF_M || f == CSF_CF_FN || f == CSF_CF_FF)) continue;
			ok = slot_ok(p, b->s[f], w);
		}
		if (ok && !b->plane)
			ok = b->s[CSF_CF_POS] >= p->ystart && (uint64_t)b->s[CSF_CF_POS] + 3 <= (uint64_t)p->ystart + p->ny;
		if (!ok) return csf_fail(err, errlen, "contact body %lu out of range", (unsigned long)i);
	}
	for (uint32_t i = 0; i < p->ncmembers; i++)
		if (p->cmembers[i] >= p->ncbodies) return csf_fail(err, errlen, "contact list entry %lu out of range", (unsigned long)i);
	uint64_t *seen = calloc((size_t)p->ncbodies + 1, sizeof *seen); /* the last list each body was in, + 1 */
	if (!seen) return csf_fail(err, errlen, "out of memory");
	int bad = 0;
	uint32_t i = 0;
	for (; i < p->ncrules && !bad; i++) {
		const csf_crule *r = &p->crules[i];
		bad = r->src >= p->nsrcs || r->every > 1 || (uint64_t)r->first0 + r->n0 > p->ncmembers ||
		      (uint64_t)r->first1 + r->n1 > p->ncmembers || (!r->every && r->n0 != r->n1);
		for (uint32_t role = 0; role < 2 && !bad; role++)
			for (uint32_t k = 0; k < (role ? r->n1 : r->n0) && !bad; k++) {
				uint32_t b = p->cmembers[(role ? r->first1 : r->first0) + k];
				uint64_t list = 2 * (uint64_t)i + role + 1;
				bad = (role == 0 && p->cbodies[b].plane) || seen[b] == list;
				seen[b] = list;
				if (!r->every && role == 1)
					bad = bad || p->cbodies[b].object == p->cbodies[p->cmembers[r->first0 + k]].object;
			}
	}
	free(seen);
	if (bad) return csf_fail(err, errlen, "contact rule %lu out of range", (unsigned long)(i - 1));
	return 0;
}

int csf_verify(const csf_prog *p, char *err, size_t errlen)
{
	if (p->nstrs == 0 || p->strs[p->nstrs - 1] != '\0') return csf_fail(err, errlen, "string table is not NUL-terminated");
#define STR_OK(off) ((off) < p->nstrs)
	if (!slot_ok(p, p->tslot, 1)) return csf_fail(err, errlen, "time slot %lu out of range", (unsigned long)p->tslot);
	if (!slot_ok(p, p->ystart, p->ny) || !slot_ok(p, p->dstart, p->ny))
		return csf_fail(err, errlen, "state layout out of range");
	if (p->ny && p->ystart < p->dstart + p->ny && p->dstart < p->ystart + p->ny)
		return csf_fail(err, errlen, "state and derivative regions overlap");
	if (p->jtan) {
		uint64_t jt = p->jtan, n = p->nmem;
		if (p->tslot + jt >= n || p->ystart + jt + p->ny > n || p->dstart + jt + p->ny > n)
			return csf_fail(err, errlen, "tangent layout out of range");
	}
	for (uint32_t i = 0; i < p->ny; i++)
		if (p->vpair[i] > p->ny || p->vpair[i] == i + 1)
			return csf_fail(err, errlen, "position/velocity pair %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->ny; i++)
		if (!(p->yscale[i] > 0) || !isfinite(p->yscale[i]))
			return csf_fail(err, errlen, "tolerance scale %lu is not a positive number", (unsigned long)i);
	for (uint32_t i = 0; i < p->ny; i++)
		if (!(p->yatol[i] >= 0) || !isfinite(p->yatol[i]))
			return csf_fail(err, errlen, "absolute tolerance %lu is not a number >= 0", (unsigned long)i);
	if (!(p->by > 0) || !isfinite(p->by) || !(p->till >= 0) || !isfinite(p->till))
		return csf_fail(err, errlen, "invalid run range (till %g, by %g)", p->till, p->by);
	if (p->till / p->by > 4e15) return csf_fail(err, errlen, "too many output steps");
	for (uint32_t i = 0; i < p->nfiles; i++)
		if (!STR_OK(p->files[i])) return csf_fail(err, errlen, "file name %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->nsrcs; i++)
		if (p->srcs[i].file >= p->nfiles || !STR_OK(p->srcs[i].text))
			return csf_fail(err, errlen, "source entry %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->ncols; i++)
		if (!STR_OK(p->cols[i].name) || !slot_ok(p, p->cols[i].slot, 1))
			return csf_fail(err, errlen, "output column %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->nasserts; i++)
		if (p->asserts[i].src >= p->nsrcs || !STR_OK(p->asserts[i].object))
			return csf_fail(err, errlen, "assertion %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->nobjects; i++)
		if (!STR_OK(p->objects[i])) return csf_fail(err, errlen, "object %lu out of range", (unsigned long)i);
	for (uint32_t i = 0; i < p->nprops; i++) {
		const csf_prop *q = &p->props[i];
		if (q->object >= p->nobjects || !STR_OK(q->name) || (q->width != 1 && q->width != 3) ||
		    !slot_ok(p, q->slot, q->width) || q->cls >= p->npclasses)
			return csf_fail(err, errlen, "property %lu out of range", (unsigned long)i);
	}
	for (int k = 0; k < CSF_NDIM; k++)
		if (!(p->ubase[k] > 0) || !isfinite(p->ubase[k])) return csf_fail(err, errlen, "unit system out of range");
	for (uint32_t i = 0; i < p->npclasses; i++) {
		const csf_pclass *c = &p->pclasses[i];
		int ok = STR_OK(c->unit) && STR_OK(c->why) && c->known <= 1;
		for (int k = 0; k < CSF_NDIM; k++) ok = ok && isfinite(c->dim[k]) && fabs(c->dim[k]) <= 64;
		if (!ok) return csf_fail(err, errlen, "parameter class %lu out of range", (unsigned long)i);
	}
	for (uint32_t i = 0; i < p->nglobals; i++) {
		const csf_global *g = &p->globals[i];
		if (!STR_OK(g->name) || (g->width != 1 && g->width != 3) || !slot_ok(p, g->slot, g->width) || g->cls >= p->npclasses)
			return csf_fail(err, errlen, "global %lu out of range", (unsigned long)i);
	}
	for (uint32_t i = 0; i < p->nevents; i++) {
		const csf_event *e = &p->events[i];
		if (e->kind > (1 | CSF_EVENT_TERMINAL) || !slot_ok(p, e->value, 1) || !slot_ok(p, e->mode, 1) || e->src >= p->nsrcs)
			return csf_fail(err, errlen, "event %lu out of range", (unsigned long)i);
	}
	if (verify_contacts(p, err, errlen)) return -1;
	for (int s = 0; s < CSF_NSEC; s++) {
		for (uint32_t i = 0; i < p->ntargets[s]; i++) {
			const csf_target *t = &p->targets[s][i];
			if ((t->width != 1 && t->width != 3) || !slot_ok(p, t->slot, t->width) || t->src >= p->nsrcs ||
			    !STR_OK(t->name) || !STR_OK(t->object))
				return csf_fail(err, errlen, "target %lu of section %d out of range", (unsigned long)i, s);
		}
		if (check_code(p, s, err, errlen)) return -1;
		for (uint32_t i = 0; i < p->nlines[s]; i++)
			if (p->lines[s][i].pc > p->ncode[s] || p->lines[s][i].src >= p->nsrcs)
				return csf_fail(err, errlen, "line table entry %lu of section %d out of range", (unsigned long)i, s);
	}
#undef STR_OK
	return 0;
}

void csf_prog_free(csf_prog *p)
{
	free(p->strs);
	free(p->mem0);
	free(p->yscale);
	free(p->yatol);
	free(p->vpair);
	free(p->files);
	free(p->srcs);
	free(p->cols);
	free(p->asserts);
	free(p->objects);
	free(p->props);
	free(p->globals);
	free(p->pclasses);
	free(p->events);
	free(p->cbodies);
	free(p->cmembers);
	free(p->crules);
	for (int s = 0; s < CSF_NSEC; s++) {
		free(p->targets[s]);
		free(p->code[s]);
		free(p->lines[s]);
	}
	memset(p, 0, sizeof *p);
}

/* Operand word v of kind kind as listed: loop levels as i, j, k; relative slots as 120+i or 300+3i. */
static void dis_operand(FILE *f, int kind, uint32_t v)
{
	static const char level[] = "?ijk";
	switch (kind) {
	case CSF_K_N:
		fprintf(f, " %d", csf_imm(v));
		return;
	case CSF_K_L:
		if (v >= 1 && v <= CSF_LOOP_MAX) fprintf(f, " %c", level[v]);
		else fprintf(f, " %lu", (unsigned long)v);
		return;
	case CSF_K_DS: case CSF_K_DV: case CSF_K_S: case CSF_K_V: case CSF_K_AS: {
		uint32_t r = csf_reg(v);
		if (r == 0) break;
		fprintf(f, " %lu+", (unsigned long)(v & CSF_SLOT_MASK));
		if (r < CSF_NREGS) fprintf(f, "%s%c", r % 2 ? "" : "3", level[(r + 1) / 2]);
		else fprintf(f, "r%lu", (unsigned long)r); /* invalid: only an unverified program has it */
		return;
	}
	}
	fprintf(f, " %lu", (unsigned long)v);
}

/* Section s's instructions under their source lines, loop bodies indented one step per level. */
static void dis_section(const csf_prog *p, int s, FILE *f)
{
	uint32_t li = 0;
	int depth = 0;
	for (uint32_t pc = 0; pc < p->ncode[s];) {
		uint32_t op = p->code[s][pc];
		if (op == CSF_OP_NEXT && depth > 0) depth--; /* a NEXT lines up with its LOOP */
		while (li < p->nlines[s] && p->lines[s][li].pc <= pc) {
			const csf_src *src = &p->srcs[p->lines[s][li].src];
			if (p->lines[s][li].pc == pc)
				fprintf(f, "  %*s; %s:%lu: %s\n", 2 * depth, "", csf_str(p, p->files[src->file]),
				        (unsigned long)src->line, csf_str(p, src->text));
			li++;
		}
		const csf_opinfo *oi = &csf_opinfo_table[op];
		fprintf(f, "  %5lu  %*s%-7s", (unsigned long)pc, 2 * depth, "", oi->name);
		for (int k = 0; k < oi->nops; k++) dis_operand(f, oi->kind[k], p->code[s][pc + 1 + k]);
		fprintf(f, "%*s; %s\n", 4 * (4 - oi->nops), "", oi->synopsis);
		if (op == CSF_OP_LOOP && depth < CSF_LOOP_MAX) depth++;
		pc += 1u + oi->nops;
	}
}

void csf_disassemble(const csf_prog *p, FILE *f)
{
	static const char *const secname[CSF_NSEC] = { "rhs", "out", "jac" };
	fprintf(f, "; memory %lu slots, t at %lu, state %lu..%lu, derivatives %lu..%lu\n", (unsigned long)p->nmem,
	        (unsigned long)p->tslot, (unsigned long)p->ystart, (unsigned long)(p->ystart + p->ny),
	        (unsigned long)p->dstart, (unsigned long)(p->dstart + p->ny));
	for (uint32_t i = 0; i < p->nobjects; i++) {
		fprintf(f, "; object %lu %s:", (unsigned long)i, csf_str(p, p->objects[i]));
		for (uint32_t k = 0; k < p->nprops; k++)
			if (p->props[k].object == i)
				fprintf(f, " %s@%lu", csf_str(p, p->props[k].name), (unsigned long)p->props[k].slot);
		fputc('\n', f);
	}
	for (int s = 0; s < CSF_NSEC; s++) {
		fprintf(f, "section %s (%lu words)\n", secname[s], (unsigned long)p->ncode[s]);
		dis_section(p, s, f);
	}
}
