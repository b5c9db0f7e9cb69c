/* The bytecode writer, reader and verifier. */
#include <math.h>
#include <string.h>

#include "suites.h"
#include "bytecode.h"

static const char *model = "object b: x = 1\nobject b: v = 0\nrule: x' = v\nrule: v' = -x\n"
                           "rule: if x > 0:\n    s = 1\nelse:\n    s = -1\nassert x < 2\ninc t till 1 by 0.5 watch x, s\n";

START_TEST(test_roundtrip)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	unsigned char *buf;
	size_t len;
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	char err[256];
	ck_assert_msg(csf_decode(buf, len, &q, err, sizeof err) == 0, "%s", err);
	ck_assert_uint_eq(p.nmem, q.nmem);
	ck_assert(memcmp(p.mem0, q.mem0, p.nmem * sizeof(double)) == 0);
	for (int s = 0; s < CSF_NSEC; s++) {
		ck_assert_uint_eq(p.ncode[s], q.ncode[s]);
		ck_assert(memcmp(p.code[s], q.code[s], p.ncode[s] * 4) == 0);
		ck_assert_uint_eq(p.ntargets[s], q.ntargets[s]);
	}
	ck_assert_uint_eq(p.ncols, q.ncols);
	ck_assert_str_eq(csf_str(&q, q.cols[1].name), "b.s");
	ck_assert(q.till == 1 && q.by == 0.5);
	ck_assert_uint_eq(q.nasserts, 1);
	free(buf);
	csf_prog_free(&p);
	csf_prog_free(&q);
}
END_TEST

/* csf_load (csf.h): the embedders' loader gives a program that runs as the decoded one does, and
   refuses a truncated file with the reason and no program. */
START_TEST(test_load)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	unsigned char *buf;
	size_t len;
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	char err[256] = "";
	csf_prog *q = csf_load(buf, len, err, sizeof err);
	ck_assert_msg(q != NULL, "%s", err);
	ck_assert_uint_eq(q->nmem, p.nmem);
	ck_assert(memcmp(q->mem0, p.mem0, p.nmem * sizeof(double)) == 0);
	ck_assert_ptr_null(csf_load(buf, len - 1, err, sizeof err));
	ck_assert_msg(strstr(err, "does not match file size") != NULL, "%s", err);
	csf_unload(q);
	csf_unload(NULL);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

/* The format's checksum is the standard CRC-32: its check value, and lengths around the
   eight-byte steps against the byte-at-a-time definition. */
START_TEST(test_crc32)
{
	ck_assert_uint_eq(csf_crc32((const unsigned char *)"123456789", 9), 0xCBF43926ul);
	ck_assert_uint_eq(csf_crc32((const unsigned char *)"", 0), 0ul);
	unsigned char buf[41];
	for (int i = 0; i < 41; i++) buf[i] = (unsigned char)(i * 37 + 11);
	for (size_t n = 0; n <= 41; n++) {
		unsigned long c = 0xFFFFFFFFul;
		for (size_t i = 0; i < n; i++) {
			c ^= buf[i];
			for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xEDB88320ul & (0ul - (c & 1ul)));
		}
		ck_assert_uint_eq(csf_crc32(buf, n), c ^ 0xFFFFFFFFul);
	}
}
END_TEST

START_TEST(test_header_checks)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	unsigned char *buf;
	size_t len;
	csf_encode(&p, &buf, &len);
	char err[256];
	static const struct { size_t off; const char *why; } c[] = {
		{ 0, "bad magic" }, { 4, "version" }, { 8, "integer layout" }, { 12, "floating-point layout" },
		{ 20, "payload size" }, { 24, "checksum" }, { 40, "checksum" },
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		buf[c[i].off] ^= 0x5A;
		ck_assert_int_eq(csf_decode(buf, len, &q, err, sizeof err), -1);
		ck_assert_msg(strstr(err, c[i].why) != NULL, "offset %zu: %s", c[i].off, err);
		buf[c[i].off] ^= 0x5A;
	}
	ck_assert_int_eq(csf_decode(buf, 10, &q, err, sizeof err), -1);
	ck_assert_int_eq(csf_decode(buf, len - 1, &q, err, sizeof err), -1);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

/* The bytes of the memory image's runs in an encoded program (bytecode.h): from *at, *len of them. */
static void memory_runs(const unsigned char *buf, size_t size, size_t *at, size_t *len)
{
	uint32_t nstrs, nmem, h;
	memcpy(&nstrs, buf + CSFB_HEADER_SIZE, 4);
	size_t i = CSFB_HEADER_SIZE + 4 + nstrs;
	memcpy(&nmem, buf + i, 4);
	*at = i += 4;
	for (uint32_t done = 0; done < nmem; done += h & CSFB_RUN_MAX) {
		ck_assert(i + 4 <= size);
		memcpy(&h, buf + i, 4);
		i += 4 + ((h >> 30) == CSFB_RUN_LITERAL ? 8 * (size_t)(h & CSFB_RUN_MAX) : (h >> 30) == CSFB_RUN_REPEAT ? 8 : 0);
	}
	*len = i - *at;
}

/* The encoded program buf with nmem and its memory runs replaced by words (n of them), the file cut
   after them if cut; payload size and CRC-32 made right, so that only the runs are wrong. */
static unsigned char *with_runs(const unsigned char *buf, size_t size, uint32_t nmem, const uint32_t *words, size_t n,
                                int cut, size_t *out)
{
	size_t at, len;
	memory_runs(buf, size, &at, &len);
	size_t tail = cut ? 0 : size - at - len;
	unsigned char *b = malloc(at + 4 * n + tail);
	memcpy(b, buf, at);
	memcpy(b + at - 4, &nmem, 4);
	memcpy(b + at, words, 4 * n);
	memcpy(b + at + 4 * n, buf + at + len, tail);
	*out = at + 4 * n + tail;
	uint32_t plen = (uint32_t)(*out - CSFB_HEADER_SIZE), crc = (uint32_t)csf_crc32(b + CSFB_HEADER_SIZE, plen);
	memcpy(b + 20, &plen, 4);
	memcpy(b + 24, &crc, 4);
	return b;
}

#define RUN(kind, n) ((uint32_t)(kind) << 30 | (uint32_t)(n))

/* The memory image in runs (bytecode.h): every value back bit for bit (-0.0 is not a zero, a NaN keeps
   its payload), zeros and equal values in runs (all zeros: one word, 8 bytes a value fewer than all
   different), and malformed runs refused with the reason. */
START_TEST(test_memory_runs)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	uint32_t n = p.nmem;
	ck_assert(n >= 12);
	double *keep = p.mem0, *x = calloc(n, sizeof *x);
	uint64_t nan = 0x7FF8000000000123ull;
	for (uint32_t i = 0; i < n; i++) x[i] = i % 7 < 3 ? 0.0 : i % 7 < 5 ? 2.5 : (double)i;
	x[1] = -0.0;
	memcpy(&x[n - 1], &nan, 8);
	p.mem0 = x;
	unsigned char *buf, *b0, *b1;
	size_t len, l0, l1, bad_len;
	char err[256];
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	ck_assert_msg(csf_decode(buf, len, &q, err, sizeof err) == 0, "%s", err);
	ck_assert_uint_eq(q.nmem, n);
	ck_assert(memcmp(q.mem0, x, n * sizeof *x) == 0);
	csf_prog_free(&q);
	/* all zeros against all different */
	memset(x, 0, n * sizeof *x);
	ck_assert_int_eq(csf_encode(&p, &b0, &l0), 0);
	for (uint32_t i = 0; i < n; i++) x[i] = i + 0.5;
	ck_assert_int_eq(csf_encode(&p, &b1, &l1), 0);
	ck_assert_uint_eq(l1 - l0, 8 * (size_t)n);
	size_t at, rl;
	memory_runs(b0, l0, &at, &rl);
	ck_assert_uint_eq(rl, 4);
	/* malformed: a kind 3, a run of length 0, a run past nmem, runs short of it, a literal run past the
	   end of the file, more elements than a field of runs may have */
	static const struct { uint32_t nmem, w[3]; size_t n; int cut; } bad[] = {
		{ 0, { RUN(3, 1) }, 1, 0 },
		{ 0, { RUN(CSFB_RUN_ZEROS, 0) }, 1, 0 },
		{ 1, { RUN(CSFB_RUN_ZEROS, 2) }, 1, 0 },
		{ 2, { RUN(CSFB_RUN_ZEROS, 1) }, 1, 1 },
		{ 0, { RUN(CSFB_RUN_LITERAL, 4), 0, 0 }, 3, 1 },
		{ CSFB_RUNS_MAX + 1, { RUN(CSFB_RUN_ZEROS, CSFB_RUNS_MAX + 1) }, 1, 0 },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		unsigned char *h = with_runs(buf, len, bad[i].nmem ? bad[i].nmem : n, bad[i].w, bad[i].n, bad[i].cut, &bad_len);
		ck_assert_msg(csf_decode(h, bad_len, &q, err, sizeof err) == -1, "malformed runs %zu accepted", i);
		ck_assert_msg(strstr(err, "malformed payload") != NULL, "malformed runs %zu: %s", i, err);
		free(h);
	}
	/* the same file with its runs written again as they were is accepted (the harness is right) */
	memory_runs(buf, len, &at, &rl);
	unsigned char *same = with_runs(buf, len, n, (const uint32_t *)(const void *)(buf + at), rl / 4, 0, &bad_len);
	ck_assert_uint_eq(bad_len, len);
	ck_assert(memcmp(same, buf, len) == 0);
	free(same);
	free(buf);
	free(b0);
	free(b1);
	free(x);
	p.mem0 = keep;
	csf_prog_free(&p);
}
END_TEST

/* The offset of the runs of n doubles from i on, past them. */
static size_t skip_runs(const unsigned char *buf, size_t size, size_t i, uint32_t n)
{
	uint32_t h;
	for (uint32_t done = 0; done < n; done += h & CSFB_RUN_MAX) {
		ck_assert(i + 4 <= size);
		memcpy(&h, buf + i, 4);
		i += 4 + ((h >> 30) == CSFB_RUN_LITERAL ? 8 * (size_t)(h & CSFB_RUN_MAX) : (h >> 30) == CSFB_RUN_REPEAT ? 8 : 0);
	}
	return i;
}

/* The encoded program buf with the words of vpair (after the memory, the layout, yscale and yatol,
   *len words) replaced by words (n of them), cut after them if cut; payload size and CRC-32 made
   right. NULL words: only *at and *len. */
static unsigned char *with_vpair(const unsigned char *buf, size_t size, const uint32_t *words, size_t n, int cut,
                                 size_t *at, size_t *len, size_t *out)
{
	uint32_t nstrs, nmem, ny, g, k, done = 0;
	memcpy(&nstrs, buf + CSFB_HEADER_SIZE, 4);
	size_t i = CSFB_HEADER_SIZE + 4 + nstrs;
	memcpy(&nmem, buf + i, 4);
	i = skip_runs(buf, size, i + 4, nmem);
	memcpy(&ny, buf + i + 12, 4);
	i = skip_runs(buf, size, skip_runs(buf, size, i + 20, ny), ny);
	for (*at = i; done < ny; done += g * k) {
		memcpy(&g, buf + i, 4);
		memcpy(&k, buf + i + 4, 4);
		i += 8 + 4 * (size_t)g * (k > 1 ? 2 : 1);
	}
	*len = i - *at;
	if (!words) return NULL;
	size_t tail = cut ? 0 : size - i;
	unsigned char *b = malloc(*at + 4 * n + tail);
	memcpy(b, buf, *at);
	memcpy(b + *at, words, 4 * n);
	memcpy(b + *at + 4 * n, buf + i, tail);
	*out = *at + 4 * n + tail;
	uint32_t plen = (uint32_t)(*out - CSFB_HEADER_SIZE), crc = (uint32_t)csf_crc32(b + CSFB_HEADER_SIZE, plen);
	memcpy(b + 20, &plen, 4);
	memcpy(b + 24, &crc, 4);
	return b;
}

/* Tables of u32 as progressions (bytecode.h): an array's per-member tables come back as they were,
   each a few progressions whatever the members (40 members' zero vpair: one progression of 4
   words); other covers of the same elements are read as well; malformed ones refused, and
   elements out of range that a progression makes refused by the verifier with the element. */
START_TEST(test_progressions)
{
	static const char *arr = "object p[0..39]: x = 0\nobject p[i]: v = i\nobject p[7]: x = 2\nobject q: x = 1\n"
	                         "rule for p[i]: x' = v\ninc t till 1 by 0.5 watch p[3].x, p.v\n";
	csf_prog p, q;
	ck_assert_int_eq(compile_string(arr, &p, NULL), 0);
	ck_assert_uint_eq(p.ny, 40);
	ck_assert_uint_ge(p.nprops, 80);
	unsigned char *buf, *b;
	size_t len, at, vl, blen;
	char err[256];
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	ck_assert_msg(csf_decode(buf, len, &q, err, sizeof err) == 0, "%s", err);
	ck_assert(q.nprops == p.nprops && memcmp(q.props, p.props, p.nprops * sizeof *p.props) == 0);
	ck_assert(q.nobjects == p.nobjects && memcmp(q.objects, p.objects, p.nobjects * 4) == 0);
	ck_assert(q.ncols == p.ncols && memcmp(q.cols, p.cols, p.ncols * sizeof *p.cols) == 0);
	/* vpair kept as progressions (only verlet reads it), and made from them */
	uint32_t *vq = csf_vpair_copy(&q);
	ck_assert(q.vpair == NULL && q.vpair_file != NULL && vq && memcmp(vq, p.vpair, p.ny * 4) == 0);
	free(vq);
	for (int s = 0; s < CSF_NSEC; s++) {
		ck_assert(q.ntargets[s] == p.ntargets[s] && q.nlines[s] == p.nlines[s]);
		/* the targets kept as progressions, and made from them */
		ck_assert(q.targets[s] == NULL && q.targets_file[s] != NULL);
		csf_target *tq = csf_targets_copy(&q, s), *tp = csf_targets_copy(&p, s);
		ck_assert(tq && tp && (!p.ntargets[s] || memcmp(tq, tp, p.ntargets[s] * sizeof(csf_target)) == 0));
		ck_assert(!p.ntargets[s] || memcmp(tp, p.targets[s], p.ntargets[s] * sizeof(csf_target)) == 0);
		free(tq);
		free(tp);
		ck_assert(!p.nlines[s] || memcmp(q.lines[s], p.lines[s], p.nlines[s] * sizeof(csf_line)) == 0);
	}
	ck_assert_uint_ge(p.ntargets[CSF_SEC_RHS], 40);
	ck_assert_uint_lt(q.targets_file_len[CSF_SEC_RHS], p.ntargets[CSF_SEC_RHS] * sizeof(csf_target));
	/* the decoded program encodes to the same bytes */
	unsigned char *again;
	size_t alen;
	ck_assert_int_eq(csf_encode(&q, &again, &alen), 0);
	ck_assert(alen == len && memcmp(again, buf, len) == 0);
	free(again);
	csf_prog_free(&q);
	/* a target out of range that a progression makes: slots 0, d, 2d, ... past the memory from one on,
	   refused by the verifier of the kept targets with that target's index */
	{
		csf_target *tg = p.targets[CSF_SEC_RHS];
		uint32_t nt = p.ntargets[CSF_SEC_RHS], d = p.nmem / (nt - 1) + 1, first = 0;
		csf_target *keep = malloc(nt * sizeof *keep);
		memcpy(keep, tg, nt * sizeof *keep);
		for (uint32_t i = 0; i < nt; i++) tg[i].slot = i * d;
		while ((uint64_t)tg[first].slot + tg[first].width <= p.nmem) first++;
		unsigned char *bad;
		size_t blen2;
		char want[64];
		ck_assert_int_eq(csf_encode(&p, &bad, &blen2), 0);
		ck_assert(csf_decode(bad, blen2, &q, err, sizeof err) == -1);
		snprintf(want, sizeof want, "target %lu of section 0 out of range", (unsigned long)first);
		ck_assert_msg(strstr(err, want) != NULL, "%s (want %s)", err, want);
		free(bad);
		memcpy(tg, keep, nt * sizeof *keep);
		free(keep);
	}
	with_vpair(buf, len, NULL, 0, 0, &at, &vl, &blen);
	static const uint32_t one[] = { 1, 40, 0, 0 };
	ck_assert_uint_eq(vl, sizeof one);
	ck_assert(memcmp(buf + at, one, sizeof one) == 0);
	/* other covers: 40 elements as they are, 2 x 20, 10 + 3 x 10 */
	static const struct { uint32_t w[44]; size_t n; } other[] = {
		{ { 40, 1 }, 42 },
		{ { 2, 20, 0, 0, 0, 0 }, 6 },
		{ { 10, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 3 }, 34 },
	};
	for (size_t i = 0; i < sizeof other / sizeof other[0]; i++) {
		b = with_vpair(buf, len, other[i].w, other[i].n, 0, &at, &vl, &blen);
		ck_assert_msg(csf_decode(b, blen, &q, err, sizeof err) == 0, "cover %zu: %s", i, err);
		vq = csf_vpair_copy(&q);
		ck_assert(vq && memcmp(vq, p.vpair, p.ny * 4) == 0);
		free(vq);
		csf_prog_free(&q);
		free(b);
	}
	/* malformed: a group of 0, a count of 0, past ny, short of it (the file cut), a group past the end */
	static const struct { uint32_t w[4]; size_t n; int cut; } bad[] = {
		{ { 0, 1 }, 2, 0 }, { { 1, 0, 0 }, 3, 0 }, { { 1, 41, 0, 0 }, 4, 0 }, { { 1, 39, 0, 0 }, 4, 1 }, { { 40, 1, 0 }, 3, 1 },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		b = with_vpair(buf, len, bad[i].w, bad[i].n, bad[i].cut, &at, &vl, &blen);
		ck_assert_msg(csf_decode(b, blen, &q, err, sizeof err) == -1, "malformed progression %zu accepted", i);
		ck_assert_msg(strstr(err, "malformed payload") != NULL, "malformed progression %zu: %s", i, err);
		free(b);
	}
	/* 0, 5, 10, ...: element 9 is 45, past ny */
	static const uint32_t five[] = { 1, 40, 0, 5 };
	b = with_vpair(buf, len, five, 4, 0, &at, &vl, &blen);
	ck_assert(csf_decode(b, blen, &q, err, sizeof err) == -1);
	ck_assert_msg(strstr(err, "position/velocity pair 9 out of range") != NULL, "%s", err);
	free(b);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

typedef struct defect { uint32_t *w; uint32_t bad; const char *why; } defect;

/* Plants each defect in turn in the valid program p: csf_verify must reject it, giving the reason. */
static void expect_defects(csf_prog *p, const defect *c, size_t n)
{
	char err[256];
	for (size_t i = 0; i < n; i++) {
		uint32_t keep = *c[i].w;
		*c[i].w = c[i].bad;
		ck_assert_msg(csf_verify(p, err, sizeof err) == -1, "defect %zu accepted", i);
		ck_assert_msg(strstr(err, c[i].why) != NULL, "defect %zu: %s", i, err);
		*c[i].w = keep;
	}
	ck_assert_int_eq(csf_verify(p, err, sizeof err), 0);
}

/* Each defect planted in a valid program must be caught by csf_verify. */
START_TEST(test_verifier)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	char err[256];
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	uint32_t *code = p.code[CSF_SEC_OUT];
	/* find the JZ of the conditional rule and the ASSERT */
	uint32_t jz = 0, as = 0;
	for (uint32_t i = 0; i < p.ncode[CSF_SEC_OUT]; i += 1u + csf_opinfo_table[code[i]].nops) {
		if (code[i] == CSF_OP_JZ) jz = i;
		if (code[i] == CSF_OP_ASSERT) as = i;
	}
	ck_assert(code[jz] == CSF_OP_JZ && code[as] == CSF_OP_ASSERT);
	defect c[] = {
		{ &code[0], CSF_NOPCODES, "invalid opcode" },
		{ &code[jz + 1], p.nmem, "out of range" },         /* read past memory */
		{ &code[jz + 2], jz, "out of range" },             /* backward jump (a loop) */
		{ &code[jz + 2], jz + 1, "out of range" },         /* into the middle of an instruction */
		{ &code[jz + 2], p.ncode[CSF_SEC_OUT] + 1, "out of range" },
		{ &code[as + 2], 7, "out of range" },              /* no such assertion */
		{ &p.tslot, p.nmem, "time slot" },
		{ &p.ny, p.nmem, "state layout" },
		{ &p.cols[0].slot, p.nmem + 5, "column" },
		{ &p.srcs[0].file, 99, "source entry" },
		{ &p.targets[CSF_SEC_RHS][0].width, 2, "target" },
		{ &p.props[0].slot, p.nmem, "property" },
		{ &p.props[0].object, 99, "property" },
		{ &p.objects[0], p.nstrs, "object" },
		{ &p.vpair[0], 1, "pair" },
		{ &p.jtan, p.nmem, "tangent" },
	};
	expect_defects(&p, c, sizeof c / sizeof c[0]);
	p.strs[p.nstrs - 1] = 'x';
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	p.strs[p.nstrs - 1] = '\0';
	p.by = 0;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	p.by = 0.5;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	/* a scene's absolute tolerance: 0 (none) or a positive number */
	static const double bad_atol[] = { -1e-9, NAN, INFINITY };
	for (size_t i = 0; i < sizeof bad_atol / sizeof bad_atol[0]; i++) {
		p.yatol[0] = bad_atol[i];
		ck_assert_msg(csf_verify(&p, err, sizeof err) == -1 && strstr(err, "absolute tolerance"), "atol %g: %s",
		              bad_atol[i], err);
	}
	p.yatol[0] = 1e-12;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	csf_prog_free(&p);
}
END_TEST

/* POWI's exponent must be within -8..8; the disassembler prints it signed. */
START_TEST(test_powi_verified)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 2\nobject b: y = 0\nrule: y = x^-2\ninc t till 1 by 1 watch y\n", &p, NULL), 0);
	uint32_t *code = p.code[CSF_SEC_OUT];
	ck_assert(code[0] == CSF_OP_POWI && code[3] == (uint32_t)-2);
	defect c[] = {
		{ &code[3], 9, "operand 3 of POWI" },
		{ &code[3], (uint32_t)-9, "operand 3 of POWI" },
		{ &code[3], 0x7FFFFFFFu, "operand 3 of POWI" },
		{ &code[3], 0x80000000u, "operand 3 of POWI" },
		{ &code[2], p.nmem, "operand 2 of POWI" },
	};
	expect_defects(&p, c, sizeof c / sizeof c[0]);
	char err[256];
	for (int n = -8; n <= 8; n += 16) {
		code[3] = (uint32_t)n;
		ck_assert_msg(csf_verify(&p, err, sizeof err) == 0, "POWI %d: %s", n, err);
	}
	code[3] = (uint32_t)-2;
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	csf_disassemble(&p, f);
	fclose(f);
	ck_assert_msg(strstr(buf, xprintf("POWI    %lu %lu -2 ", (unsigned long)code[1], (unsigned long)code[2])) != NULL, "%s", buf);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

/* A block on a 30 degree ramp, held by static friction; and a conditional force. */
static const char *contact_model =
	"object ramp: vector point = (0, 0, 0) m\n"
	"object ramp: vector normal = (-0.5, 0, 0.8660254037844386)\n"
	"object ramp: vector edge = (0, 0, 0) m\n"
	"object ramp: cr = 1\nobject ramp: mu_s = 0\nobject ramp: mu_k = 0\n"
	"object b: m = 2 kg\nobject b: vector v = (0, 0, 0) m/s\nobject b: vector a = (0, 0, 0) m/s^2\n"
	"object b: vector pos = (0, 0, 0) m\nobject b: radius = 0 m\nobject b: cr = 1\n"
	"object b: mu_s = 1\nobject b: mu_k = 0.5\n"
	"object b: vector FN = (0, 0, 0) N\nobject b: vector Ff = (0, 0, 0) N\n"
	"rule: contact(pos, radius, point$1, normal$1)\n"
	"rule: if t < 1 s:\n    a = g\nelse:\n    a = g.mul(2)\n"
	"rule: v' = a\nrule: pos' = v\n"
	"inc t till 1 s by 0.5 s watch b.a, b.FN, b.Ff\n";

typedef struct eval_ctx { const csf_prog *p; double *m; csf_exec_ctx x; } eval_ctx;
static int eval_rhs(void *ctx)
{
	eval_ctx *e = ctx;
	csf_vm_exec(e->p, &e->x, CSF_SEC_RHS, e->m, e->m + e->p->ystart, e->m + e->p->dstart);
	return 0;
}

/* The contact routine's state for p, its candidates chosen at the state in m. */
static csf_contacts *contacts_at(const csf_prog *p, const double *m)
{
	csf_contacts *cs = csf_contacts_new(p);
	ck_assert_ptr_nonnull(cs);
	const double *ys[1] = { m + p->ystart };
	ck_assert_int_ge(csf_contacts_find(cs, m, ys, 1, 0), 0);
	csf_contacts_commit(cs, m, NULL, NULL, 0);
	return cs;
}

/* The contact body of object `name`. */
static const csf_cbody *cbody_of(const csf_prog *p, const char *name)
{
	for (uint32_t i = 0; i < p->ncbodies; i++)
		if (strcmp(csf_str(p, p->objects[p->cbodies[i].object]), name) == 0) return &p->cbodies[i];
	ck_abort_msg("no contact body %s", name);
	return NULL;
}

/* The contact routine on a resting, sticking block: a = 0, FN = m g cos30 n, Ff = m g sin30 up the slope. */
START_TEST(test_contact_routine)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(contact_model, &p, NULL), 0);
	ck_assert_uint_eq(p.ncrules, 1);
	ck_assert_uint_eq(p.ncbodies, 2);
	ck_assert_uint_eq(p.nevents, 1);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	m[p.events[0].mode] = 1; /* t < 1 s */
	/* it touches the ramp at rest, pressed into it: it comes to rest in contact, sticking */
	csf_contacts *cs = contacts_at(&p, m);
	ck_assert_uint_eq(csf_contacts_count(cs), 1);
	eval_ctx e = { &p, m, { .contacts = cs } };
	ck_assert_int_eq(csf_contact_settle(&p, cs, m, 5e-7, 1e-10, eval_rhs, &e), 0);
	ck_assert_int_eq(csf_vm_exec(&p, &e.x, CSF_SEC_RHS, m, m + p.ystart, m + p.dstart), -1);
	double g = 9.80665, mg = 2 * g, s30 = 0.5, c30 = 0.8660254037844386;
	const csf_cbody *c = cbody_of(&p, "b");
	const double *a = m + c->s[CSF_CF_A], *fn = m + c->s[CSF_CF_FN], *ff = m + c->s[CSF_CF_FF];
	double want_fn[3] = { -mg * c30 * s30, 0, mg * c30 * c30 }, want_ff[3] = { mg * s30 * c30, 0, mg * s30 * s30 };
	for (int k = 0; k < 3; k++) {
		ck_assert_msg(fabs(a[k]) < 1e-14, "a[%d] = %g", k, a[k]);
		ck_assert_msg(fabs(fn[k] - want_fn[k]) < 1e-13, "FN[%d] = %.17g, want %.17g", k, fn[k], want_fn[k]);
		ck_assert_msg(fabs(ff[k] - want_ff[k]) < 1e-13, "Ff[%d] = %.17g, want %.17g", k, ff[k], want_ff[k]);
	}
	/* guards: the normal force pushes (m g cos30 > 0, with the slack of its rounding, 1e-12 of the
	   forces that meet: csf_contact_accel_resolution); static friction holds (mu_s N - |f| > 0) */
	double gd[2];
	csf_contacts_guards(cs, gd);
	ck_assert(gd[0] - mg * c30 > 0 && gd[0] - mg * c30 < 1e-11 * mg);
	ck_assert(fabs(gd[1] - mg * (c30 - s30)) < 1e-13);
	csf_contacts_free(cs);
	free(m);
	csf_prog_free(&p);
}
END_TEST

/* Hostile contact tables: every slot, body and list checked (csf_verify). */
START_TEST(test_contact_tables_verified)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(contact_model, &p, NULL), 0);
	uint32_t b = (uint32_t)(cbody_of(&p, "b") - p.cbodies), r = (uint32_t)(cbody_of(&p, "ramp") - p.cbodies);
	csf_cbody *cb = &p.cbodies[b], *cr = &p.cbodies[r];
	csf_crule *ru = &p.crules[0];
	ck_assert_uint_eq(p.ncmembers, 2);
	ck_assert(p.cmembers[ru->first0] == b && p.cmembers[ru->first1] == r && ru->every == 1);
	defect d[] = {
		{ &cb->s[CSF_CF_V], p.nmem - 1, "contact body" },   /* a vector past the end of memory */
		{ &cb->s[CSF_CF_M], p.nmem, "contact body" },
		{ &cb->s[CSF_CF_POS], p.dstart, "contact body" },   /* a position not in the state */
		{ &cb->s[CSF_CF_POS], p.ystart + p.ny - 2, "contact body" },
		{ &cb->plane, CSF_CB_ANCHOR + 1, "contact body" }, /* no such kind */
		{ &cb->varies, 2, "contact body" },
		{ &cb->object, p.nobjects, "contact body" },
		{ &cr->s[CSF_CF_R], p.nmem - 2, "contact body" },   /* a plane's normal is a vector */
		{ &cr->s[CSF_CF_POS], p.nmem, "contact body" },
		{ &p.cmembers[0], p.ncbodies, "contact list entry" },
		{ &p.cmembers[ru->first0], r, "contact rule" },     /* a plane as $0 */
		{ &cb->plane, CSF_CB_ANCHOR, "contact rule" },     /* an anchor as $0 */
		{ &ru->src, p.nsrcs, "contact rule" },
		{ &ru->every, 2, "contact rule" },
		{ &ru->first1, p.ncmembers, "contact rule" },
		{ &ru->n1, 2, "contact rule" },                     /* a list past the end */
		{ &ru->first0, 0xFFFFFFFFu, "contact rule" },       /* and one that wraps */
		{ &ru->n0, 0, "contact rule" },                     /* `for`: not one $0 for each $1 */
		{ &p.events[0].mode, p.nmem, "event" },
		{ &p.events[0].kind, 4, "event" }, /* 0 to 3: strict or not, terminal or not */
	};
	/* n0 = 0 is fine for a rule without `for`: the n0 defect is checked with every = 0 */
	expect_defects(&p, d, sizeof d / sizeof d[0] - 3);
	char err[256];
	ru->every = 0;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0);
	expect_defects(&p, d + sizeof d / sizeof d[0] - 3, 3);
	/* `for`: a pair of one object; a body twice in a list */
	p.cmembers[ru->first1] = b;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	ck_assert_msg(strstr(err, "contact rule") != NULL, "%s", err);
	ru->every = 1;
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), 0); /* every: the pair of one object is left out */
	ru->first1 = ru->first0, ru->n1 = 2;                   /* [b, ramp] ... */
	p.cmembers[1] = b;                                      /* ... [b, b] */
	ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
	ck_assert_msg(strstr(err, "contact rule") != NULL, "%s", err);
	csf_prog_free(&p);
}
END_TEST

/* A spring whose constant and mass -D can set; k2 is folded from k, so neither can be. */
static const char *param_model = "global k = 20 N/m\nglobal k2 = 2 * k\nobject b: m = 1 kg\nobject b: x = 1 m\n"
                                 "object b: v = 0 m/s\nrule: x' = v\nrule: v' = -k2 * x / m\n"
                                 "inc t till 1 s by 0.5 s watch b.x\n";

/* The parameter tables: every name, slot, class and the unit system checked (csf_verify); they survive a round trip. */
START_TEST(test_param_tables_verified)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(param_model, &p, NULL), 0);
	ck_assert_uint_ge(p.nglobals, 2);
	ck_assert_uint_ge(p.npclasses, 2);
	defect d[] = {
		{ &p.props[0].cls, p.npclasses, "property" },
		{ &p.globals[0].cls, p.npclasses, "global" },
		{ &p.globals[0].slot, p.nmem, "global" },
		{ &p.globals[0].slot, p.nmem - 1, "global" }, /* g is a vector */
		{ &p.globals[0].width, 2, "global" },
		{ &p.globals[0].name, p.nstrs, "global" },
		{ &p.pclasses[0].unit, p.nstrs, "parameter class" },
		{ &p.pclasses[0].why, p.nstrs, "parameter class" },
		{ &p.pclasses[0].known, 2, "parameter class" },
	};
	expect_defects(&p, d, sizeof d / sizeof d[0]);
	char err[256];
	/* every unit of the system, the ampere's too, and every exponent of a class, current's too */
	for (int k = 0; k < CSF_NDIM; k++) {
		double keep = p.ubase[k];
		p.ubase[k] = k % 2 ? 0 : -INFINITY;
		ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
		ck_assert_msg(strstr(err, "unit system") != NULL, "%s", err);
		p.ubase[k] = keep;
		keep = p.pclasses[0].dim[k];
		p.pclasses[0].dim[k] = k % 2 ? NAN : 65;
		ck_assert_int_eq(csf_verify(&p, err, sizeof err), -1);
		ck_assert_msg(strstr(err, "parameter class") != NULL, "%s", err);
		p.pclasses[0].dim[k] = keep;
	}
	unsigned char *buf;
	size_t len;
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	ck_assert_int_eq(csf_decode(buf, len, &q, err, sizeof err), 0);
	ck_assert_uint_eq(q.nglobals, p.nglobals);
	ck_assert_uint_eq(q.npclasses, p.npclasses);
	ck_assert(memcmp(q.globals, p.globals, p.nglobals * sizeof *p.globals) == 0);
	for (uint32_t i = 0; i < p.npclasses; i++)
		ck_assert(q.pclasses[i].unit == p.pclasses[i].unit && q.pclasses[i].why == p.pclasses[i].why &&
		          q.pclasses[i].known == p.pclasses[i].known &&
		          memcmp(q.pclasses[i].dim, p.pclasses[i].dim, sizeof q.pclasses[i].dim) == 0);
	ck_assert(memcmp(q.ubase, p.ubase, sizeof p.ubase) == 0);
	free(buf);
	csf_prog_free(&q);
	csf_prog_free(&p);
}
END_TEST

/* -D: values with units, converted as the compiler converts a literal; the refusals name the reason. */
static const struct { const char *assign; double want; const char *err; } param_cases[] = {
	{ "b.m=500 g", 0.5, NULL },
	{ "b.m = 2", 2, NULL },
	{ "b.x=(3 ft)", 0, "cannot read" },
	{ "b.x=3 ft", 0.9144, NULL },
	{ "b.x=36 km/h", 0, "expected unit m" },
	{ "b.v=36 km/h", 10, NULL },
	{ "b.v=1 mph", 0.44704, NULL },
	{ "k=20", 0, "k cannot be overridden: its value is folded" },
	{ "k2=20", 0, "k2 cannot be overridden: its value is computed at compile time from k" },
	{ "g=(0, 0, -1.62) m/s^2", 0, NULL },
	{ "g=(0, 0, -1.62 m/s^2)", 0, NULL },
	{ "g=(0, 0, -1.62 kg)", 0, "expected unit m/s^2" },
	{ "g=(1 m/s^2, 0, 2 kg)", 0, "one dimension" },
	{ "g=1 m/s^2", 0, "g is a vector" },
	{ "pi=3 m", 0, "pi is dimensionless" },
	{ "nope=1", 0, "unknown name 'nope'" },
	{ "b.nope=1", 0, "no property 'nope'" },
	{ "c.x=1", 0, "no object 'c'" },
	{ "b=1", 0, "is an object" },
	{ "b.m", 0, "expected NAME=VALUE" },
	{ "b.m=1 kg kg", 0, "cannot read" },
	{ "b.m=1e999", 0, "cannot read" },
	/* one component of a vector, as csfc reads g.z */
	{ "g.z=-1.62 m/s^2", -1.62, NULL },
	{ "g.z = -162 cm/s^2", -1.62, NULL },
	{ "g.z=1 kg", 0, "wrong dimension: g.z is in m/s^2" },
	{ "g.z=(0, 0, 1) m/s^2", 0, "g.z is a scalar" },
	{ "g.w=1", 0, "unknown name 'g.w'" },
	{ "b.m.x=1", 0, "no property 'm.x'" },
	/* a unit as CSF prints one: 1/s */
	{ "b.v=4 m*(1/s)", 4, NULL },
	{ "b.v=4 m*1/s", 4, NULL },
	{ "b.v=4 1/s", 0, "expected unit m/s" },
	/* a near miss is suggested */
	{ "pii=3", 0, "unknown name 'pii': the scene has no global of that name; did you mean 'pi'?" },
};

START_TEST(test_param_set)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(param_model, &p, NULL), 0);
	char err[512];
	csf_overlay ov = { 0 };
	int r = csf_param_set(&p, &ov, param_cases[_i].assign, err, sizeof err);
	if (param_cases[_i].err) {
		ck_assert_msg(r == -1, "%s accepted", param_cases[_i].assign);
		ck_assert_msg(strstr(err, param_cases[_i].err) != NULL, "%s: %s", param_cases[_i].assign, err);
	} else {
		ck_assert_msg(r == 0, "%s: %s", param_cases[_i].assign, err);
		char name[32];
		sscanf(param_cases[_i].assign, "%31[^= ]", name);
		csf_pref ref;
		ck_assert_int_eq(csf_param_find(&p, name, &ref, err, sizeof err), 0);
		/* the program is not changed: the value is in the overlay, which the run applies */
		double *m = malloc(p.nmem * sizeof *m);
		memcpy(m, p.mem0, p.nmem * sizeof *m);
		csf_overlay_apply(&ov, m);
		double got = ref.width == 3 ? m[ref.slot + 2] : m[ref.slot];
		free(m);
		double want = ref.width == 3 ? -1.62 : param_cases[_i].want;
		ck_assert_msg(fabs(got - want) <= 1e-15 * fabs(want), "%s: %.17g, want %.17g", param_cases[_i].assign, got, want);
	}
	csf_overlay_free(&ov);
	csf_prog_free(&p);
}
END_TEST

/* A sphere (radius 0.1 m, restitution 0.5) on a floor 1000 km up, under gravity. */
static const char *floor_model =
	"object floor: vector point = (0, 0, 1e6) m\n"
	"object floor: vector normal = (0, 0, 1)\n"
	"object floor: vector edge = (0, 0, 0) m\n"
	"object floor: cr = 1\nobject floor: mu_s = 0\nobject floor: mu_k = 0\n"
	"object b: m = 1 kg\nobject b: vector v = (0, 0, 0) m/s\nobject b: vector a = (0, 0, 0) m/s^2\n"
	"object b: vector pos = (0, 0, 1000000.1) m\nobject b: radius = 0.1 m\nobject b: cr = 0.5\n"
	"object b: mu_s = 0\nobject b: mu_k = 0\n"
	"object b: vector FN = (0, 0, 0) N\nobject b: vector Ff = (0, 0, 0) N\n"
	"rule: contact(pos, radius, point$1, normal$1)\n"
	"rule: a = g\nrule: v' = a\nrule: pos' = v\n"
	"inc t till 1 s by 0.5 s watch b.pos\n";

/*
 * Impacts of the sphere landing at speed w at t = 2 s, settled by
 * csf_contact_settle (Zeno time 5e-7 s, tolerance 1e-10): it rebounds at
 * w/2 and is apart (guard 0, the gap, zero); on a hop lower than 100 tol
 * times the scale (2e6 m, so 0.02 m) it is hopping (guard 0, the time
 * left until it lands after the flight time 2 (w/2)/g); when the train of
 * bounces would end within the Zeno time it rests (guard 0, the normal
 * force, FN = m g). The floor's distance from the origin changes none of
 * this.
 */
START_TEST(test_contact_settle)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(floor_model, &p, NULL), 0);
	ck_assert_uint_eq(p.ncrules, 1);
	double *m = malloc(p.nmem * sizeof *m), g = 9.80665;
	const csf_cbody *c = cbody_of(&p, "b");
	eval_ctx e = { &p, m, { NULL } };
	enum { APART, REST, HOPPING };
	static const struct { double w; int mode; double v; } cases[] = {
		{ 2, APART, 1 },          /* a hop of 0.051 m: apart */
		{ 1, HOPPING, 0.5 },      /* 0.0127 m: hopping */
		{ 1e-6, REST, 0 },        /* bounces that end within 2e-7 s: at rest, sliding freely */
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		memcpy(m, p.mem0, p.nmem * sizeof *m);
		m[p.tslot] = 2;
		m[c->s[CSF_CF_V] + 2] = -cases[i].w;
		csf_contacts *cs = contacts_at(&p, m);
		ck_assert_uint_eq(csf_contacts_count(cs), 1);
		e.x.contacts = cs;
		ck_assert_int_eq(csf_contact_settle(&p, cs, m, 5e-7, 1e-10, eval_rhs, &e), 0);
		double gd[2];
		csf_contacts_guards(cs, gd);
		ck_assert_msg(m[c->s[CSF_CF_V] + 2] == cases[i].v, "w=%g: v %.17g", cases[i].w, m[c->s[CSF_CF_V] + 2]);
		ck_assert(m[c->s[CSF_CF_POS] + 2] >= 1000000.1); /* not below the floor */
		if (cases[i].mode == APART) ck_assert_msg(gd[0] >= 0 && gd[0] < 1e-9, "w=%g: gap %g", cases[i].w, gd[0]);
		if (cases[i].mode == HOPPING)
			ck_assert_msg(fabs(gd[0] - 2 * 0.5 / g) < 1e-15, "landing in %.17g", gd[0]);
		if (cases[i].mode == REST)
			ck_assert_msg(fabs(gd[0] - g) < 1e-11 * g && fabs(m[c->s[CSF_CF_FN] + 2] - g) < 1e-12 &&
			                      fabs(m[c->s[CSF_CF_A] + 2]) < 1e-12,
			              "N %.17g, FN %.17g, a %.17g", gd[0], m[c->s[CSF_CF_FN] + 2], m[c->s[CSF_CF_A] + 2]);
		csf_contacts_free(cs);
	}
	free(m);
	csf_prog_free(&p);
}
END_TEST

/*
 * The broad phase: 60 mass points (radii 0 to 0.3 m, a third of them
 * points) and two planes, placed at random in a 3 m box over five states
 * (the instants of a step). For each state, the candidates' guards are
 * their gaps (computed there, all pairs new): every pair whose gap is
 * negative at one of the states (found by trying all of them) must be a
 * candidate, two points never are, and the candidates are few (not all
 * the 1770 + 120 pairs).
 */
START_TEST(test_contact_broad_phase)
{
	enum { N = 60, NS = 5 };
	/* mechanics/mass_point and mechanics/rules, without the standard library */
	char *text = xprintf("def mass_point:\n    m = 1 kg\n    vector v = (0, 0, 0) m/s\n    vector a = (0, 0, 0) m/s^2\n"
	                     "    vector pos = (0, 0, 0) m\n    radius = 0 m\n    cr = 1\n    mu_s = 0\n    mu_k = 0\n"
	                     "    vector FN = (0, 0, 0) N\n    vector Ff = (0, 0, 0) N\n"
	                     "def plane:\n    vector point = (0, 0, 0) m\n    vector normal = (0, 0, 1)\n"
	                     "    vector edge = (0, 0, 0) m\n    cr = 1\n    mu_s = 0\n    mu_k = 0\n");
	for (int i = 0; i < N; i++)
		text = xprintf("%sobject b%d: mass_point\nobject b%d: radius = %g m\n", text, i, i, i % 3 ? 0.05 * (i % 7) : 0.0);
	text = xprintf("%sobject f: plane\nobject w: plane\nobject w: point = (3, 0, 0) m\nobject w: normal = (-1, 0, 0)\n"
	               "rule: contact(pos, radius, pos$1, radius$1)\nrule: contact(pos, radius, point$1, normal$1)\n"
	               "rule: RF = a.mul(m)\nrule: v' = a\nrule: pos' = v\ninc t till 1 by 1 watch b0.pos\n", text);
	csf_prog p;
	ck_assert_int_eq(compile_string(text, &p, NULL), 0);
	ck_assert_uint_eq(p.ncrules, 2);
	double *m = malloc(p.nmem * sizeof *m), *ys[NS];
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	uint32_t pos[N];
	double rad[N];
	for (int i = 0; i < N; i++) {
		const csf_cbody *b = cbody_of(&p, xprintf("b%d", i));
		pos[i] = b->s[CSF_CF_POS] - p.ystart, rad[i] = m[b->s[CSF_CF_R]];
	}
	unsigned long seed = 12345;
	long total = 0; /* pairs with a negative gap, over the trials */
	for (int trial = 0; trial < 20; trial++) {
		for (int s = 0; s < NS; s++) {
			ys[s] = malloc(p.ny * sizeof *ys[s]);
			memcpy(ys[s], p.mem0 + p.ystart, p.ny * sizeof *ys[s]);
			for (int i = 0; i < N; i++)
				for (int k = 0; k < 3; k++) {
					seed = (seed * 16807) % 2147483647;
					/* a drift from state to state; some points exactly on others */
					double x = (double)seed / 2147483647 * 3 - (k == 2 ? 0.2 : 0);
					ys[s][pos[i] + k] = s ? ys[s - 1][pos[i] + k] + (x - 1.5) * 0.02 : (i % 10 == 9 ? ys[0][pos[i - 1] + k] : x);
				}
		}
		csf_contacts *cs = csf_contacts_new(&p);
		ck_assert_ptr_nonnull(cs);
		long nc = csf_contacts_find(cs, m, (const double *const *)ys, NS, 0);
		ck_assert_int_ge(nc, 0);
		double *g[NS];
		for (int s = 0; s < NS; s++) g[s] = malloc((2 * (size_t)nc + 1) * sizeof *g[s]);
		csf_contacts_commit(cs, m, g, (const double *const *)ys, NS);
		ck_assert_uint_eq(csf_contacts_count(cs), (uint32_t)nc);
		long want = 0, near = 0;
		for (int s = 0; s < NS; s++) {
			long neg = 0, all = 0;
			for (long k = 0; k < nc; k++) neg += g[s][2 * k] < 0;
			for (int i = 0; i < N; i++) {
				const double *x = ys[s] + pos[i];
				all += x[2] - rad[i] < 0;        /* the floor, z = 0 */
				all += 3 - x[0] - rad[i] < 0;    /* the wall, x = 3 */
				for (int j = i + 1; j < N; j++) {
					const double *q = ys[s] + pos[j];
					double d = csf_vmag3(x[0] - q[0], x[1] - q[1], x[2] - q[2]);
					if (rad[i] + rad[j] > 0) {
						all += d - rad[i] - rad[j] < 0;
						near += s == 0 && d - rad[i] - rad[j] < 0.2;
					}
				}
			}
			ck_assert_msg(neg == all, "trial %d, state %d: %ld candidates with a negative gap, %ld pairs", trial, s, neg,
			              all);
			want += all;
		}
		ck_assert_msg(nc < 2 * near + 4 * N, "trial %d: %ld candidates, %ld pairs near", trial, nc, near);
		for (long k = 0; k < nc; k++) ck_assert(isfinite(g[0][2 * k])); /* no two points: their gap is infinite */
		for (int s = 0; s < NS; s++) free(g[s]), free(ys[s]);
		csf_contacts_free(cs);
		total += want;
	}
	ck_assert_msg(total > 100, "%ld pairs touching: the test does not test", total);
	/* a body whose radius varies, and a plane whose geometry does, are candidates with every body */
	csf_cbody *b1 = (csf_cbody *)cbody_of(&p, "b1"), *w = (csf_cbody *)cbody_of(&p, "w");
	b1->varies = w->varies = 1;
	for (int s = 0; s < NS; s++) {
		ys[s] = calloc(p.ny, sizeof *ys[s]);
		for (int i = 0; i < N; i++) /* every body far from every other, above the floor, before the wall */
			ys[s][pos[i]] = -100.0 * i, ys[s][pos[i] + 2] = 1000 + 100.0 * i;
	}
	csf_contacts *cs = csf_contacts_new(&p);
	long nc = csf_contacts_find(cs, m, (const double *const *)ys, NS, 0);
	ck_assert_int_eq(nc, (N - 1) + 1 + N); /* b1 with each mass point and with f, w with each */
	csf_contacts_free(cs);
	for (int s = 0; s < NS; s++) free(ys[s]);
	free(m);
	csf_prog_free(&p);
}
END_TEST

/*
 * A path that turns back between two states: ball a (radius 0.05 m) at x =
 * 0 at both, its velocity +1 m/s at the first and -1 m/s at the second, h =
 * 0.01 s apart. The cubic through them, x(u) = h u (1 - u) on [0, 1],
 * reaches 0.0025 m at u = 1/2, so ball b (radius 0.05 m, at x = 0.102 m,
 * 0.002 m beyond a's reach at the states) touches it in between: a
 * candidate with h = 0.01 s, and not with h = 0 (the states alone), nor
 * with h = 0.01 s once b is beyond the bound 4/27 h (|v0| + |v1|) =
 * 0.00296 m.
 */
START_TEST(test_contact_path_reach)
{
	const char *text = "def mass_point:\n    m = 1 kg\n    vector v = (0, 0, 0) m/s\n    vector a = (0, 0, 0) m/s^2\n"
	                   "    vector pos = (0, 0, 0) m\n    radius = 0.05 m\n    cr = 1\n    mu_s = 0\n    mu_k = 0\n"
	                   "    vector FN = (0, 0, 0) N\n    vector Ff = (0, 0, 0) N\n"
	                   "object a: mass_point\nobject b: mass_point\n"
	                   "rule: contact(pos, radius, pos$1, radius$1)\n"
	                   "rule: RF = a.mul(m)\nrule: v' = a\nrule: pos' = v\ninc t till 1 by 1 watch a.pos\n";
	csf_prog p;
	ck_assert_int_eq(compile_string(text, &p, NULL), 0);
	double *m = malloc(p.nmem * sizeof *m), *ys[2];
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	const csf_cbody *a = cbody_of(&p, "a"), *b = cbody_of(&p, "b");
	uint32_t av = a->s[CSF_CF_V] - p.ystart, bp = b->s[CSF_CF_POS] - p.ystart;
	struct { double h, bx; long want; } c[] = { { 0.01, 0.102, 1 }, { 0, 0.102, 0 }, { 0.01, 0.1035, 0 } };
	for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
		for (int s = 0; s < 2; s++) {
			ys[s] = malloc(p.ny * sizeof *ys[s]);
			memcpy(ys[s], p.mem0 + p.ystart, p.ny * sizeof *ys[s]);
			ys[s][av] = s ? -1 : 1;
			ys[s][bp] = c[k].bx;
		}
		csf_contacts *cs = csf_contacts_new(&p);
		ck_assert_ptr_nonnull(cs);
		long nc = csf_contacts_find(cs, m, (const double *const *)ys, 2, c[k].h);
		ck_assert_msg(nc == c[k].want, "h %g, b at x = %g: %ld candidates, expected %ld", c[k].h, c[k].bx, nc, c[k].want);
		csf_contacts_free(cs);
		for (int s = 0; s < 2; s++) free(ys[s]);
	}
	free(m);
	csf_prog_free(&p);
}
END_TEST

START_TEST(test_disassembler)
{
	csf_prog p;
	ck_assert_int_eq(compile_string(model, &p, NULL), 0);
	char *buf;
	size_t len;
	FILE *f = open_memstream(&buf, &len);
	csf_disassemble(&p, f);
	fclose(f);
	ck_assert_msg(strstr(buf, "section rhs") && strstr(buf, "section out") && strstr(buf, "JZ") &&
	              strstr(buf, "ASSERT") && strstr(buf, "t.csf:3: rule: x' = v"), "%s", buf);
	free(buf);
	csf_prog_free(&p);
}
END_TEST

/* A when block that swaps through its two assignments: both read the values before the event. */
static const char *when_model = "object b: x = 0\nobject b: y = 5\nobject b: n = 0\nrule: x' = 1\n"
                                "when x > 1:\n    n = n + y\n    y = n\ninc t till 2 s by 1 s watch n, y\n";

/* The slot of property name of p's first object. */
static uint32_t first_prop(const csf_prog *p, const char *name)
{
	for (uint32_t k = 0; k < p->nprops; k++)
		if (!strcmp(csf_str(p, p->props[k].name), name)) return p->props[k].slot;
	ck_abort_msg("no property %s", name);
	return 0;
}

/* The EVT section: no firing at the first look (prev -1), a firing only when the condition
   turns true, every new value from the values before; the table verified and kept by a round trip. */
START_TEST(test_when_section)
{
	csf_prog p, q;
	ck_assert_int_eq(compile_string(when_model, &p, NULL), 0);
	ck_assert_uint_eq(p.nwhens, 1);
	ck_assert_uint_gt(p.ncode[CSF_SEC_EVT], 0);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	uint32_t x = p.ystart, n = first_prop(&p, "n"), y = first_prop(&p, "y");
	const csf_when *w = &p.whens[0];
	ck_assert(m[w->prev] == -1 && m[w->fire] == 0);
	/* x' = 1 from x = 2: its condition holds at the first look, which does not fire */
	double look[][4] = { /* x, then fire, n, y after */ { 2, 0, 0, 5 }, { 0, 0, 0, 5 }, { 2, 1, 5, 0 }, { 3, 0, 5, 0 } };
	for (size_t i = 0; i < sizeof look / sizeof look[0]; i++) {
		m[x] = look[i][0];
		vm_run(&p, CSF_SEC_RHS, m);
		vm_run(&p, CSF_SEC_EVT, m);
		ck_assert_msg(m[w->fire] == look[i][1] && m[n] == look[i][2] && m[y] == look[i][3],
		              "look %zu at x=%g: fire %g, n %g, y %g", i, look[i][0], m[w->fire], m[n], m[y]);
		ck_assert(m[w->prev] == (look[i][0] > 1));
	}
	free(m);
	unsigned char *buf;
	size_t len;
	char err[256];
	ck_assert_int_eq(csf_encode(&p, &buf, &len), 0);
	ck_assert_msg(csf_decode(buf, len, &q, err, sizeof err) == 0, "%s", err);
	ck_assert(q.nwhens == 1 && q.whens[0].fire == w->fire && q.whens[0].prev == w->prev && q.whens[0].src == w->src);
	ck_assert(q.ncode[CSF_SEC_EVT] == p.ncode[CSF_SEC_EVT] &&
	          !memcmp(q.code[CSF_SEC_EVT], p.code[CSF_SEC_EVT], p.ncode[CSF_SEC_EVT] * sizeof(uint32_t)));
	free(buf);
	csf_prog_free(&q);
	defect d[] = {
		{ &p.whens[0].src, p.nsrcs, "when block" },
		{ &p.whens[0].fire, p.nmem, "when block" },
		{ &p.whens[0].prev, p.nmem, "when block" },
	};
	expect_defects(&p, d, sizeof d / sizeof d[0]);
	csf_prog_free(&p);
}
END_TEST

Suite *bytecode_suite(void)
{
	Suite *s = suite_create("bytecode");
	TCase *tc = tcase_create("format");
	tcase_add_test(tc, test_roundtrip);
	tcase_add_test(tc, test_load);
	tcase_add_test(tc, test_crc32);
	tcase_add_test(tc, test_header_checks);
	tcase_add_test(tc, test_memory_runs);
	tcase_add_test(tc, test_progressions);
	tcase_add_test(tc, test_verifier);
	tcase_add_test(tc, test_powi_verified);
	tcase_add_test(tc, test_contact_routine);
	tcase_add_test(tc, test_contact_tables_verified);
	tcase_add_test(tc, test_contact_settle);
	tcase_add_test(tc, test_contact_broad_phase);
	tcase_add_test(tc, test_contact_path_reach);
	tcase_add_test(tc, test_disassembler);
	tcase_add_test(tc, test_param_tables_verified);
	tcase_add_test(tc, test_when_section);
	tcase_add_loop_test(tc, test_param_set, 0, sizeof param_cases / sizeof param_cases[0]);
	suite_add_tcase(s, tc);
	return s;
}
