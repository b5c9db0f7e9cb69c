/*
 * fields.c - the .csfb payload's fields (fields.h), in file order, with
 * what csf_verify checks in each: the one list of the format's payload,
 * which bytecode.c's encoder, decoder, csf_prog_free and csf_verify walk.
 * csf(5) ("Bytecode (.csfb)") describes the same fields in the same order.
 *
 * Every field but three is an array of elements of u32 words and doubles
 * (count-prefixed, or one per state component). The special cases:
 * strings is bytes; layout, run and units are not arrays but values in
 * csf_prog itself (a constant count, no count in the file); the code
 * field's elements are instructions, checked by the instruction verifier
 * (csf_verify_code, bytecode.c). In the file, the memory image, yscale and
 * yatol are runs, vpair and the tables of u32 structs progressions
 * (bytecode.h); in memory every field is a plain array but the targets and
 * vpair, which a decoded program keeps as progressions (csf_targets_copy,
 * csf_vpair_copy).
 */
#include <math.h>
#include <stdlib.h>

#include "csf_int.h"
#include "bytecode.h"
#include "fields.h"

_Static_assert(sizeof(csf_src) == 12 && sizeof(csf_col) == 8 && sizeof(csf_assert) == 8 && sizeof(csf_prop) == 20 &&
               sizeof(csf_global) == 16 && sizeof(csf_event) == 16 &&
               sizeof(csf_target) == 20 && sizeof(csf_line) == 8 && sizeof(csf_cbody) == 4 * (3 + CSF_CF_N) &&
               sizeof(csf_crule) == 24 && sizeof(csf_con) == 44 && sizeof(csf_conbody) == 28,
               "tables are arrays of u32");
_Static_assert(offsetof(csf_prog, jtan) == offsetof(csf_prog, tslot) + 16 &&
               offsetof(csf_prog, ystart) == offsetof(csf_prog, tslot) + 4 &&
               offsetof(csf_prog, dstart) == offsetof(csf_prog, tslot) + 8 &&
               offsetof(csf_prog, ny) == offsetof(csf_prog, tslot) + 12, "layout is five u32 in a row");
_Static_assert(offsetof(csf_prog, by) == offsetof(csf_prog, till) + 8, "run is two doubles in a row");
_Static_assert(sizeof(csf_target) / 4 <= CSFB_PROG_WORDS_MAX, "a kept table's element fits the verifier's");
_Static_assert(offsetof(csf_pclass, why) == 4 && offsetof(csf_pclass, known) == 8, "a class starts with three u32");

static int slot_ok(const csf_prog *p, uint32_t s, uint32_t width)
{
	return s < p->nmem && width <= p->nmem - s;
}

static int str_ok(const csf_prog *p, uint32_t off)
{
	return off < p->nstrs;
}

/* ---- whole-field checks ---- */

static int check_strings(const csf_prog *p, int sec, char *err, size_t errlen)
{
	(void)sec;
	if (p->nstrs == 0 || p->strs[p->nstrs - 1] != '\0') return csf_fail(err, errlen, "string table is not NUL-terminated");
	return 0;
}

static int check_layout(const csf_prog *p, int sec, char *err, size_t errlen)
{
	(void)sec;
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
	return 0;
}

static int check_run(const csf_prog *p, int sec, char *err, size_t errlen)
{
	(void)sec;
	if (!(p->by > 0) || !isfinite(p->by) || !(p->till >= 0) || !isfinite(p->till))
		return csf_fail(err, errlen, "invalid run range (till %g, by %g)", p->till, p->by);
	if (p->till / p->by > 4e15) return csf_fail(err, errlen, "too many output steps");
	return 0;
}

/*
 * The contact rules: the bodies and lists in range, a rule's $0 mass
 * points, a `for` rule's two lists as long and its pairs of two objects,
 * and no body twice in a list (the entries of cmembers are checked before).
 */
static int check_crules(const csf_prog *p, int sec, char *err, size_t errlen)
{
	(void)sec;
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

/* ---- element checks: element e (index i) of its field is valid ---- */

#define ELEM(fn) static int fn(const csf_prog *p, int sec, const void *e_, uint32_t i)
#define UNUSED (void)p, (void)sec, (void)i

ELEM(positive_ok)
{
	const double *e = e_;
	UNUSED;
	return *e > 0 && isfinite(*e);
}

ELEM(nonnegative_ok)
{
	const double *e = e_;
	UNUSED;
	return *e >= 0 && isfinite(*e);
}

ELEM(vpair_ok)
{
	const uint32_t *e = e_;
	(void)sec;
	return !(*e > p->ny || *e == i + 1);
}

ELEM(str_elem_ok)
{
	const uint32_t *e = e_;
	UNUSED;
	return str_ok(p, *e);
}

ELEM(src_ok)
{
	const csf_src *e = e_;
	UNUSED;
	return e->file < p->nfiles && str_ok(p, e->text);
}

ELEM(col_ok)
{
	const csf_col *e = e_;
	UNUSED;
	return str_ok(p, e->name) && slot_ok(p, e->slot, 1);
}

ELEM(assert_ok)
{
	const csf_assert *e = e_;
	UNUSED;
	return e->src < p->nsrcs && str_ok(p, e->object);
}

ELEM(prop_ok)
{
	const csf_prop *q = e_;
	UNUSED;
	return q->object < p->nobjects && str_ok(p, q->name) && (q->width == 1 || q->width == 3) &&
	       slot_ok(p, q->slot, q->width) && q->cls < p->npclasses;
}

ELEM(global_ok)
{
	const csf_global *g = e_;
	UNUSED;
	return str_ok(p, g->name) && (g->width == 1 || g->width == 3) && slot_ok(p, g->slot, g->width) &&
	       g->cls < p->npclasses;
}

ELEM(pclass_ok)
{
	const csf_pclass *c = e_;
	UNUSED;
	int ok = str_ok(p, c->unit) && str_ok(p, c->why) && c->known <= 1;
	for (int k = 0; k < CSF_NDIM; k++) ok = ok && isfinite(c->dim[k]) && fabs(c->dim[k]) <= 64;
	return ok;
}

ELEM(when_ok)
{
	const csf_when *w = e_;
	UNUSED;
	return w->src < p->nsrcs && slot_ok(p, w->fire, 1) && slot_ok(p, w->prev, 1);
}

ELEM(event_ok)
{
	const csf_event *e = e_;
	UNUSED;
	return e->kind <= (1 | CSF_EVENT_TERMINAL) && slot_ok(p, e->value, 1) && slot_ok(p, e->mode, 1) &&
	       e->src < p->nsrcs;
}

/*
 * A contact body: a kind it can be, every slot it has in memory (a mass
 * point's position in the state, where the broad phase reads it from state
 * vectors), its object in range.
 */
ELEM(cbody_ok)
{
	const csf_cbody *b = e_;
	UNUSED;
	static const unsigned char width[CSF_CF_N] = { 3, 3, 3, 1, 1, 1, 1, 1, 3, 3 };
	int ok = b->plane <= CSF_CB_ANCHOR && b->varies <= 1 && b->object < p->nobjects;
	for (int f = 0; ok && f < CSF_CF_N; f++) {
		uint32_t w = width[f];
		if (b->plane == CSF_CB_PLANE && f == CSF_CF_R) w = 3; /* a plane's normal */
		if (b->plane && (f == CSF_CF_A || f == CSF_CF_M || f == CSF_CF_FN || f == CSF_CF_FF)) continue;
		if (b->plane == CSF_CB_ANCHOR && f == CSF_CF_V) continue; /* no velocity: a plane's edge */
		ok = slot_ok(p, b->s[f], w);
	}
	if (ok && !b->plane)
		ok = b->s[CSF_CF_POS] >= p->ystart && (uint64_t)b->s[CSF_CF_POS] + 3 <= (uint64_t)p->ystart + p->ny;
	return ok;
}

ELEM(cmember_ok)
{
	const uint32_t *e = e_;
	UNUSED;
	return *e < p->ncbodies;
}

/* A constraint: its kind, slots, unit and rule in range, its bodies a range of conbodies. */
ELEM(con_ok)
{
	const csf_con *c = e_;
	UNUSED;
	return c->kind <= CSF_CON_GE && c->src < p->nsrcs && str_ok(p, c->unit) && slot_ok(p, c->g, 1) &&
	       slot_ok(p, c->gd, 1) && slot_ok(p, c->c, 1) && slot_ok(p, c->scale, 1) && slot_ok(p, c->cr, 1) && slot_ok(p, c->want, 1) &&
	       (!i || c->want == p->cons[0].want) &&
	       (uint64_t)c->first + c->n <= p->nconbodies;
}

/* A constrained body: a mass point, its position and velocity in the state, its other slots in memory. */
ELEM(conbody_ok)
{
	const csf_conbody *b = e_;
	UNUSED;
	int instate = (uint64_t)b->pos >= p->ystart && (uint64_t)b->pos + 3 <= (uint64_t)p->ystart + p->ny &&
	              (uint64_t)b->v >= p->ystart && (uint64_t)b->v + 3 <= (uint64_t)p->ystart + p->ny;
	return instate && b->object < p->nobjects && slot_ok(p, b->J, 3) && slot_ok(p, b->a, 3) && slot_ok(p, b->m, 1) &&
	       slot_ok(p, b->fc, 3);
}

ELEM(target_ok)
{
	const csf_target *t = e_;
	UNUSED;
	return (t->width == 1 || t->width == 3) && slot_ok(p, t->slot, t->width) && t->src < p->nsrcs &&
	       str_ok(p, t->name) && str_ok(p, t->object);
}

ELEM(line_ok)
{
	const csf_line *l = e_;
	(void)i;
	return l->pc <= p->ncode[sec] && l->src < p->nsrcs;
}

/* ---- the table ---- */

/* An array of u32 or of structs of u32 behind pointer ptr, its count n before it in the file. */
#define U32S(nm, ptr, n, T, ok_, bad_)                                                                            \
	{ .name = nm, .how = CSF_FC_PREFIX, .sec = -1, .words = sizeof(T) / 4, .progs = 1,                         \
	  .at = offsetof(csf_prog, ptr), .count = offsetof(csf_prog, n), .size = sizeof(T), .ok = ok_, .bad = bad_ }
/* One element of type T (one u32 in progressions, or one double in runs) per state component. */
#define PER_Y(nm, ptr, T, ok_, bad_)                                                                              \
	{ .name = nm, .how = CSF_FC_NY, .sec = -1, .words = sizeof(T) == 4, .dbls = sizeof(T) == 8,                \
	  .runs = sizeof(T) == 8, .progs = sizeof(T) == 4, .at = offsetof(csf_prog, ptr), .size = sizeof(T), .ok = ok_, .bad = bad_ }
/* A field of code section s (the array ptr[s] of n[s] elements, in progressions if progs_);
   SECTION(s): the section's three. */
#define SEC_U32S(nm, ptr, n, T, s, progs_, ok_, bad_, check_)                                                      \
	{ .name = nm, .how = CSF_FC_PREFIX, .sec = s, .words = sizeof(T) / 4, .progs = progs_,                     \
	  .at = offsetof(csf_prog, ptr) + (s) * sizeof(T *), .count = offsetof(csf_prog, n) + (s) * sizeof(uint32_t), \
	  .size = sizeof(T), .ok = ok_, .bad = bad_, .check = check_ }
/* A field of code section s kept as its progressions (ptr[s] NULL; ptr##_file[s], ptr##_file_len[s]) */
#define SEC_KEPT(nm, ptr, n, T, s, ok_, bad_)                                                                      \
	{ .name = nm, .how = CSF_FC_PREFIX, .sec = s, .words = sizeof(T) / 4, .progs = 1, .kept = 1,                \
	  .at = offsetof(csf_prog, ptr) + (s) * sizeof(T *), .count = offsetof(csf_prog, n) + (s) * sizeof(uint32_t), \
	  .size = sizeof(T), .kept_at = offsetof(csf_prog, ptr##_file) + (s) * sizeof(unsigned char *),              \
	  .kept_len = offsetof(csf_prog, ptr##_file_len) + (s) * sizeof(uint32_t), .ok = ok_, .bad = bad_ }
#define SECTION(s)                                                                                                 \
	SEC_KEPT("targets", targets, ntargets, csf_target, s, target_ok, "target %lu of section %d out of range"),        \
	SEC_U32S("code", code, ncode, uint32_t, s, 0, NULL, NULL, csf_verify_code),                                        \
	SEC_U32S("lines", lines, nlines, csf_line, s, 1, line_ok, "line table entry %lu of section %d out of range", NULL)

const csf_field csf_fields[] = {
	/* special: bytes */
	{ .name = "strings", .how = CSF_FC_PREFIX, .sec = -1, .at = offsetof(csf_prog, strs),
	  .count = offsetof(csf_prog, nstrs), .size = 1, .check = check_strings },
	{ .name = "memory", .how = CSF_FC_PREFIX, .sec = -1, .dbls = 1, .runs = 1, .at = offsetof(csf_prog, mem0),
	  .count = offsetof(csf_prog, nmem), .size = sizeof(double) },
	/* special: u32 tslot, ystart, dstart, ny, jtan in csf_prog */
	{ .name = "layout", .how = CSF_FC_INLINE, .sec = -1, .words = 5, .at = offsetof(csf_prog, tslot), .count = 1,
	  .size = 5 * sizeof(uint32_t), .check = check_layout },
	PER_Y("yscale", yscale, double, positive_ok, "tolerance scale %lu is not a positive number"),
	PER_Y("yatol", yatol, double, nonnegative_ok, "absolute tolerance %lu is not a number >= 0"),
	/* kept as progressions in a decoded program (csf_vpair_copy): only verlet reads it */
	{ .name = "vpair", .how = CSF_FC_NY, .sec = -1, .words = 1, .progs = 1, .kept = 1, .at = offsetof(csf_prog, vpair),
	  .size = sizeof(uint32_t), .kept_at = offsetof(csf_prog, vpair_file), .kept_len = offsetof(csf_prog, vpair_file_len),
	  .ok = vpair_ok, .bad = "position/velocity pair %lu out of range" },
	/* special: double till, by in csf_prog */
	{ .name = "run", .how = CSF_FC_INLINE, .sec = -1, .dbls = 2, .at = offsetof(csf_prog, till), .count = 1,
	  .size = 2 * sizeof(double), .check = check_run },
	U32S("files", files, nfiles, uint32_t, str_elem_ok, "file name %lu out of range"),
	U32S("sources", srcs, nsrcs, csf_src, src_ok, "source entry %lu out of range"),
	U32S("columns", cols, ncols, csf_col, col_ok, "output column %lu out of range"),
	U32S("asserts", asserts, nasserts, csf_assert, assert_ok, "assertion %lu out of range"),
	U32S("objects", objects, nobjects, uint32_t, str_elem_ok, "object %lu out of range"),
	U32S("props", props, nprops, csf_prop, prop_ok, "property %lu out of range"),
	/* special: CSF_NDIM doubles ubase in csf_prog */
	{ .name = "units", .how = CSF_FC_INLINE, .sec = -1, .dbls = 1, .at = offsetof(csf_prog, ubase),
	  .count = CSF_NDIM, .size = sizeof(double), .ok = positive_ok, .bad = "unit system out of range" },
	U32S("globals", globals, nglobals, csf_global, global_ok, "global %lu out of range"),
	{ .name = "pclasses", .how = CSF_FC_PREFIX, .sec = -1, .words = 3, .dbls = CSF_NDIM,
	  .at = offsetof(csf_prog, pclasses), .count = offsetof(csf_prog, npclasses), .size = sizeof(csf_pclass),
	  .dbl_at = offsetof(csf_pclass, dim), .ok = pclass_ok, .bad = "parameter class %lu out of range" },
	U32S("events", events, nevents, csf_event, event_ok, "event %lu out of range"),
	U32S("whens", whens, nwhens, csf_when, when_ok, "when block %lu out of range"),
	U32S("cbodies", cbodies, ncbodies, csf_cbody, cbody_ok, "contact body %lu out of range"),
	U32S("cmembers", cmembers, ncmembers, uint32_t, cmember_ok, "contact list entry %lu out of range"),
	{ .name = "crules", .how = CSF_FC_PREFIX, .sec = -1, .words = sizeof(csf_crule) / 4, .progs = 1,
	  .at = offsetof(csf_prog, crules), .count = offsetof(csf_prog, ncrules), .size = sizeof(csf_crule),
	  .check = check_crules },
	U32S("conbodies", conbodies, nconbodies, csf_conbody, conbody_ok, "constrained body %lu out of range"),
	U32S("cons", cons, ncons, csf_con, con_ok, "constraint %lu out of range"),
	SECTION(CSF_SEC_RHS),
	SECTION(CSF_SEC_OUT),
	SECTION(CSF_SEC_JAC),
	SECTION(CSF_SEC_EVT),
};
_Static_assert(CSF_NSEC == 4, "a SECTION for each code section");

const size_t csf_nfields = sizeof csf_fields / sizeof csf_fields[0];
