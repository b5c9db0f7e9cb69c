/*
 * bytecode.c - encoding, decoding, verification and listing of .csfb files.
 *
 * The format is described in bytecode.h. Decoding reads through a bounded
 * cursor: every read checks the bytes left, every array count is checked
 * against the bytes left before it is allocated, so a truncated or hostile
 * file costs at most its own size in memory. The encoder, the decoder,
 * csf_prog_free and csf_verify walk one table of the payload's fields
 * (fields.c). After decoding, csf_verify checks every cross-reference
 * (string offsets, memory slots, sources) and every instruction (opcode
 * in range, operands in bounds for every value of the loop registers they
 * use, jumps forward to an instruction boundary inside the section and
 * inside the same loop body, loops properly nested and matched, POWI's
 * exponent within CSF_POWI_MAX). A verified program
 * cannot make the VM read or write outside its memory or loop forever.
 */
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>

#include "csf_int.h"
#include "bytecode.h"
#include "fields.h"
#include "insn.h"

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

/* The bits of double d (runs compare bits: -0.0 is not a zero, a NaN's payload is kept). */
static uint64_t bits(double d)
{
	uint64_t u;
	memcpy(&u, &d, 8);
	return u;
}

/* How many of the n doubles from x[0] on have x[0]'s bits (at most CSFB_RUN_MAX). */
static uint32_t run_length(const double *x, uint32_t n)
{
	uint32_t k = 1;
	while (k < n && k < CSFB_RUN_MAX && bits(x[k]) == bits(x[0])) k++;
	return k;
}

/* Is the run at x (of length k) worth its header: zeros from 2 on, another value from 3 on. */
static int worth_a_run(const double *x, uint32_t k) { return k >= (bits(x[0]) == 0 ? 2u : 3u); }

/* Writes the n doubles x as runs (bytecode.h): runs of zeros and of equal values, the rest literal. */
static void put_runs(wbuf *w, const double *x, uint32_t n)
{
	uint32_t i = 0;
	while (i < n) {
		uint32_t k = run_length(x + i, n - i);
		if (worth_a_run(x + i, k)) {
			int zero = bits(x[i]) == 0;
			put_u32(w, (uint32_t)(zero ? CSFB_RUN_ZEROS : CSFB_RUN_REPEAT) << 30 | k);
			if (!zero) put_f64(w, x[i]);
			i += k;
			continue;
		}
		uint32_t j = i + k; /* the literals: up to the next run worth its header */
		while (j < n && j - i < CSFB_RUN_MAX) {
			uint32_t l = run_length(x + j, n - j);
			if (worth_a_run(x + j, l)) break;
			j += l < CSFB_RUN_MAX - (j - i) ? l : CSFB_RUN_MAX - (j - i);
		}
		put_u32(w, (uint32_t)CSFB_RUN_LITERAL << 30 | (j - i));
		for (; i < j; i++) put_f64(w, x[i]);
	}
}

/*
 * How many groups of g elements (of w words) from e on, m elements left, go on as the first two
 * do: each the one before plus the same difference, word by word (at least 1 when g <= m).
 */
static uint64_t prog_groups(const uint32_t *e, uint32_t w, uint64_t m, uint32_t g)
{
	size_t gw = (size_t)g * w;
	uint64_t k = m >= 2 * (uint64_t)g ? 2 : m >= g;
	for (; k >= 2 && (k + 1) * g <= m; k++) {
		const uint32_t *a = e + (k - 1) * gw, *b = a + gw;
		size_t t = 0;
		while (t < gw && b[t] - a[t] == e[gw + t] - e[t]) t++;
		if (t < gw) break;
	}
	return k;
}

/* Writes g elements of w words from e as they are (a progression of one group), none if g is 0. */
static void put_group(wbuf *w, const uint32_t *e, uint32_t words, uint32_t g)
{
	if (!g) return;
	put_u32(w, g);
	put_u32(w, 1);
	for (size_t t = 0; t < (size_t)g * words; t++) put_u32(w, e[t]);
}

/*
 * Writes the n elements of w words from e as progressions (bytecode.h): at each element, the
 * group of up to CSFB_PROG_GROUP_MAX elements that repeats with a constant difference over the
 * most elements, if three groups or more; the elements between such progressions as they are.
 */
static void put_progs(wbuf *w, const uint32_t *e, uint32_t words, uint32_t n)
{
	uint32_t i = 0, lit = 0; /* lit: the elements before i not yet written */
	while (i < n) {
		uint32_t g = 0;
		uint64_t k = 0;
		for (uint32_t h = 1; h <= CSFB_PROG_GROUP_MAX && 3 * (uint64_t)h <= n - i; h++) {
			uint64_t l = prog_groups(e + (size_t)i * words, words, n - i, h);
			if (l >= 3 && h * l > g * k) g = h, k = l;
		}
		if (!g) {
			i++;
			lit++;
			continue;
		}
		put_group(w, e + (size_t)(i - lit) * words, words, lit);
		lit = 0;
		put_u32(w, g);
		put_u32(w, (uint32_t)k);
		const uint32_t *a = e + (size_t)i * words, *b = a + (size_t)g * words;
		for (size_t t = 0; t < (size_t)g * words; t++) put_u32(w, a[t]);
		for (size_t t = 0; t < (size_t)g * words; t++) put_u32(w, b[t] - a[t]);
		i += (uint32_t)(g * k);
	}
	put_group(w, e + (size_t)(i - lit) * words, words, lit);
}

/* Field f of p: its elements (in memory) and their count. */
static const unsigned char *field_elems(const csf_prog *p, const csf_field *f, uint32_t *n)
{
	const unsigned char *at = (const unsigned char *)p + f->at, *e = at;
	*n = (uint32_t)f->count;
	if (f->how == CSF_FC_INLINE) return at;
	memcpy(&e, at, sizeof e);
	if (f->how == CSF_FC_NY) *n = p->ny;
	else memcpy(n, (const unsigned char *)p + f->count, sizeof *n);
	return e;
}

/* Writes field f: its count (if in the file), then each element's u32 words and doubles (strings: bytes). */
static void put_field(wbuf *w, const csf_prog *p, const csf_field *f)
{
	uint32_t n, v;
	double d;
	const unsigned char *e = field_elems(p, f, &n), *kept = NULL;
	if (f->how == CSF_FC_PREFIX) put_u32(w, n);
	if (f->kept) memcpy(&kept, (const unsigned char *)p + f->kept_at, sizeof kept);
	if (kept && !e) { /* as decoded: the progressions read */
		memcpy(&v, (const unsigned char *)p + f->kept_len, sizeof v);
		put(w, kept, v);
		return;
	}
	if (f->runs) {
		put_runs(w, (const double *)(const void *)e, n);
		return;
	}
	if (f->progs) {
		put_progs(w, (const uint32_t *)(const void *)e, f->words, n);
		return;
	}
	if (!f->words && !f->dbls) {
		if (n) put(w, e, n);
		return;
	}
	for (uint32_t i = 0; i < n; i++, e += f->size) {
		for (unsigned k = 0; k < f->words; k++) {
			memcpy(&v, e + 4 * k, 4);
			put_u32(w, v);
		}
		for (unsigned k = 0; k < f->dbls; k++) {
			memcpy(&d, e + f->dbl_at + 8 * k, 8);
			put_f64(w, d);
		}
	}
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

	for (size_t k = 0; k < csf_nfields; k++) put_field(&w, p, &csf_fields[k]);
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

/* Adds the stretch of k slots from slot at to p's spans (joined to the last when they meet). -1: no memory. */
static int add_span(csf_prog *p, uint32_t at, uint32_t k)
{
	uint32_t *last = p->nspans ? p->spans + 2 * (p->nspans - 1) : NULL;
	if (last && (uint64_t)last[0] + last[1] == at) {
		last[1] += k;
		return 0;
	}
	if (!(p->nspans & (p->nspans - 1))) { /* 0, 1, 2, 4, ...: room for twice as many */
		uint32_t *q = realloc(p->spans, 2 * sizeof *q * (p->nspans ? 2 * (size_t)p->nspans : 1));
		if (!q) return -1;
		p->spans = q;
	}
	p->spans[2 * p->nspans] = at;
	p->spans[2 * p->nspans++ + 1] = k;
	return 0;
}

/*
 * Reads n doubles stored as runs into x (zeroed memory: the runs of zeros leave it as it is, and
 * sp, if not NULL, gets the stretches the other runs write as its spans), or (x NULL) only checks
 * that the runs cover exactly n within the bytes left (r is not advanced then). -1 on a malformed
 * run (kind 3, length 0, past n or past the end), or when memory for the spans runs out.
 */
static int get_runs(rbuf *r, double *x, uint32_t n, csf_prog *sp)
{
	rbuf s = *r;
	uint32_t done = 0, h;
	while (done < n) {
		if (get_u32(&s, &h)) return -1;
		uint32_t kind = h >> 30, k = h & CSFB_RUN_MAX;
		if (kind > CSFB_RUN_REPEAT || k == 0 || k > n - done) return -1;
		if (x && sp && kind != CSFB_RUN_ZEROS && add_span(sp, done, k)) return -1;
		if (kind == CSFB_RUN_LITERAL) {
			if (k > s.left / 8) return -1;
			if (!x) s.p += 8 * (size_t)k, s.left -= 8 * (size_t)k, done += k;
			else
				for (uint32_t j = 0; j < k; j++) get_f64(&s, &x[done++]);
			continue;
		}
		double d = 0;
		if (kind == CSFB_RUN_REPEAT && get_f64(&s, &d)) return -1;
		for (uint32_t j = 0; x && kind == CSFB_RUN_REPEAT && j < k; j++) x[done + j] = d;
		done += k;
	}
	if (x) *r = s;
	return 0;
}

/*
 * Reads n elements of w words stored as progressions into x, or (x NULL) only checks that they
 * cover exactly n within the bytes left (r is not advanced then); *used (if not NULL): the bytes
 * they take. -1 on a malformed progression: a group or count of 0, past n or past the end.
 */
static int get_progs(rbuf *r, uint32_t *x, uint32_t w, uint32_t n, size_t *used)
{
	rbuf s = *r;
	uint32_t done = 0, g, k;
	while (done < n) {
		if (get_u32(&s, &g) || get_u32(&s, &k)) return -1;
		if (g == 0 || k == 0 || (uint64_t)g * k > n - done) return -1;
		size_t gw = (size_t)g * w, words = k > 1 ? 2 * gw : gw;
		if (words > s.left / 4) return -1;
		if (x) {
			uint32_t *out = x + (size_t)done * w;
			for (size_t t = 0; t < gw; t++) out[t] = le32(s.p + 4 * t);
			for (uint32_t j = 1; j < k; j++, out += gw)
				for (size_t t = 0; t < gw; t++) out[gw + t] = out[t] + le32(s.p + 4 * (gw + t));
		}
		s.p += 4 * words;
		s.left -= 4 * words;
		done += g * k;
	}
	if (used) *used = r->left - s.left;
	if (x) *r = s;
	return 0;
}

/*
 * Applies f's element check to each of the n elements of the progressions at b (checked by
 * get_progs), made one at a time: the index of the first that fails, or n.
 */
static uint32_t progs_check(const csf_prog *p, const csf_field *f, const unsigned char *b, uint32_t n)
{
	uint32_t e[CSFB_PROG_WORDS_MAX], i = 0;
	while (i < n) {
		uint32_t g = le32(b), k = le32(b + 4);
		const unsigned char *base = b + 8, *diff = base + 4 * (size_t)g * f->words;
		for (uint32_t j = 0; j < k; j++)
			for (uint32_t q = 0; q < g; q++, i++) {
				for (uint32_t t = 0; t < f->words; t++) {
					size_t at = 4 * ((size_t)q * f->words + t);
					e[t] = le32(base + at) + (j ? j * le32(diff + at) : 0);
				}
				if (!f->ok(p, f->sec, e, i)) return i;
			}
		b = k > 1 ? diff + 4 * (size_t)g * f->words : diff;
	}
	return n;
}

/* A kept field's n elements of w words in a malloc'd array: a copy of plain, or made from the
   progressions at file (len bytes) when plain is NULL (a decoded program). NULL: no memory. */
static uint32_t *kept_copy(const uint32_t *plain, const unsigned char *file, uint32_t len, uint32_t n, uint32_t w)
{
	uint32_t *v = malloc(n ? (size_t)n * w * sizeof *v : 1);
	if (!v || !n) return v;
	if (plain) {
		memcpy(v, plain, (size_t)n * w * sizeof *v);
		return v;
	}
	rbuf r = { file, len, "" };
	if (get_progs(&r, v, w, n, NULL)) { /* (not after csf_decode) */
		free(v);
		return NULL;
	}
	return v;
}

csf_target *csf_targets_copy(const csf_prog *p, int sec)
{
	return (csf_target *)(void *)kept_copy((const uint32_t *)(const void *)p->targets[sec], p->targets_file[sec],
	                                       p->targets_file_len[sec], p->ntargets[sec], sizeof(csf_target) / 4);
}

uint32_t *csf_vpair_copy(const csf_prog *p) { return kept_copy(p->vpair, p->vpair_file, p->vpair_file_len, p->ny, 1); }

/*
 * Reads field f into p: its count (checked against the bytes left before
 * anything is allocated; a field of runs or progressions, checked by reading them), the array,
 * its elements.
 */
static int get_field(rbuf *r, csf_prog *p, const csf_field *f)
{
	unsigned char *at = (unsigned char *)p + f->at, *e = at;
	uint32_t n = (uint32_t)f->count, v = 0;
	double d = 0;
	size_t fsize = f->words || f->dbls ? 4u * f->words + 8u * f->dbls : 1; /* an element's bytes in the file */
	if (f->how == CSF_FC_PREFIX) {
		if (get_u32(r, &n)) return -1;
		memcpy((unsigned char *)p + f->count, &n, sizeof n);
	} else if (f->how == CSF_FC_NY) {
		n = p->ny;
	}
	size_t used = 0;
	if (f->runs ? n > CSFB_RUNS_MAX || get_runs(r, NULL, n, NULL)
	    : f->progs ? (size_t)n > CSFB_PROGS_BYTES_MAX / f->size || get_progs(r, NULL, f->words, n, &used)
	    : (size_t)n > r->left / fsize)
		return -1;
	if (f->kept) { /* the progressions as they are (a u32 count of bytes: they fit in the file's payload) */
		unsigned char *k = malloc(used ? used : 1);
		if (!k) return -1;
		memcpy(k, r->p, used);
		memcpy((unsigned char *)p + f->kept_at, &k, sizeof k);
		memcpy((unsigned char *)p + f->kept_len, &(uint32_t){ (uint32_t)used }, sizeof(uint32_t));
		r->p += used;
		r->left -= used;
		return 0;
	}
	if (f->how != CSF_FC_INLINE) {
		if (!(e = f->runs ? calloc(n ? n : 1, f->size) : malloc(n ? (size_t)n * f->size : 1))) return -1;
		memcpy(at, &e, sizeof e);
	}
	if (f->runs) /* the memory image's spans with it */
		return get_runs(r, (double *)(void *)e, n, f->at == offsetof(csf_prog, mem0) ? p : NULL);
	if (f->progs) return get_progs(r, (uint32_t *)(void *)e, f->words, n, NULL);
	if (fsize == 1) {
		memcpy(e, r->p, n);
		r->p += n;
		r->left -= n;
		return 0;
	}
	for (uint32_t i = 0; i < n; i++, e += f->size) {
		for (unsigned k = 0; k < f->words; k++) {
			get_u32(r, &v);
			memcpy(e + 4 * k, &v, 4);
		}
		for (unsigned k = 0; k < f->dbls; k++) {
			get_f64(r, &d);
			memcpy(e + f->dbl_at + 8 * k, &d, 8);
		}
	}
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
	for (size_t k = 0; k < csf_nfields && !bad; k++) bad = get_field(&r, p, &csf_fields[k]);
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

/* The code field of section sec (fields.c): check_code. */
int csf_verify_code(const csf_prog *p, int sec, char *err, size_t errlen)
{
	return check_code(p, sec, err, errlen);
}

/* Checks every field of the table (fields.c) in file order: each element, then the whole field. */
int csf_verify(const csf_prog *p, char *err, size_t errlen)
{
	for (size_t k = 0; k < csf_nfields; k++) {
		const csf_field *f = &csf_fields[k];
		uint32_t n;
		const unsigned char *e = field_elems(p, f, &n), *kept = NULL;
		if (f->kept) memcpy(&kept, (const unsigned char *)p + f->kept_at, sizeof kept);
		if (kept && !e) { /* as decoded: each element made from its progression */
			uint32_t i = progs_check(p, f, kept, n);
			if (i < n) return csf_fail(err, errlen, f->bad, (unsigned long)i, (int)f->sec);
		}
		for (uint32_t i = 0; f->ok && e && i < n; i++, e += f->size)
			if (!f->ok(p, f->sec, e, i)) return csf_fail(err, errlen, f->bad, (unsigned long)i, (int)f->sec);
		if (f->check && f->check(p, f->sec, err, errlen)) return -1;
	}
	return 0;
}

void csf_prog_free(csf_prog *p)
{
	for (size_t k = 0; k < csf_nfields; k++) {
		void *e;
		if (csf_fields[k].how == CSF_FC_INLINE) continue;
		memcpy(&e, (unsigned char *)p + csf_fields[k].at, sizeof e);
		free(e);
		if (!csf_fields[k].kept) continue;
		memcpy(&e, (unsigned char *)p + csf_fields[k].kept_at, sizeof e);
		free(e);
	}
	free(p->spans);
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
	static const char *const secname[CSF_NSEC] = { "rhs", "out", "jac", "evt" };
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
