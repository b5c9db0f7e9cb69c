/*
 * param.c - parameters: the initial values -D NAME=VALUE sets, in an overlay
 * (csf_overlay) that the run applies over the program's (which stays as loaded).
 *
 * The compiler lists what can be set: every global (p->globals) and every
 * object property the run keeps in memory (p->props), each with a class
 * (p->pclasses) giving its dimension and unit in the model's unit system,
 * or why it cannot be set (its value was folded at compile time into
 * another value, it is computed by a rule, it decided which contacts
 * exist). A value is read as the source writes one, a number or a vector
 * with units, converted with the same arithmetic the compiler uses for a
 * literal (csf_units_to_system of the unit's SI factor, times the number),
 * so `-D 'ball.v=(3, 0, 4) m/s'` gives the bits `v = (3, 0, 4) m/s` gives.
 * A bare number is in the model's units and is taken as it is: the values
 * a sweep prints read back to the same doubles. NAME.x (.y, .z) sets one
 * component of a vector. An unknown name's error suggests the nearest
 * known one, as csfc's errors do (csf_suggest_name serves both).
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"

/* ---- names: the suggestions of csfc's errors and of -D ---- */

/* The edit distance of a and b (insertions, deletions, substitutions), at most cap + 1. */
static int edit_distance(const char *a, const char *b, int cap)
{
	size_t n = strlen(a), m = strlen(b);
	if ((n > m ? n - m : m - n) > (size_t)cap) return cap + 1;
	if (m > 64) return cap + 1;
	int row[65];
	for (size_t j = 0; j <= m; j++) row[j] = (int)j;
	for (size_t i = 1; i <= n; i++) {
		int diag = row[0], best;
		row[0] = (int)i;
		best = row[0];
		for (size_t j = 1; j <= m; j++) {
			int up = row[j], v = diag + (a[i - 1] != b[j - 1]);
			if (up + 1 < v) v = up + 1;
			if (row[j - 1] + 1 < v) v = row[j - 1] + 1;
			diag = up;
			row[j] = v;
			if (v < best) best = v;
		}
		if (best > cap) return cap + 1;
	}
	return row[m] > cap ? cap + 1 : row[m];
}

const char *csf_suggest_name(const char *name, const char *const *cands, int n)
{
	/* a near miss of a name of 3 letters or more (one or two letters are too many names' near
	   misses): at most 2 edits; a name that begins with a candidate counts as 1, as the symbol
	   of a word does (mass: m, velocity: v, position: pos) */
	if (strlen(name) < 3) return NULL;
	int cap = 2, best = cap + 1;
	const char *pick = NULL;
	for (int i = 0; i < n; i++) {
		if (!cands[i] || !*cands[i] || !strcmp(cands[i], name)) continue;
		int d = edit_distance(name, cands[i], cap);
		if (!strncmp(name, cands[i], strlen(cands[i])) && d > 1) d = 1;
		if (d < best || (d == best && pick && strlen(cands[i]) > strlen(pick))) best = d, pick = cands[i];
	}
	return best <= cap ? pick : NULL;
}

/* "; did you mean 'NAME'?" for the candidate nearest to name among those of cands[0..n) that
   are set (the rest NULL), or ""; into buf. Frees cands. */
static const char *suggestion(const char *name, const char **cands, uint32_t n, char *buf, size_t len)
{
	const char *s = cands ? csf_suggest_name(name, cands, (int)n) : NULL;
	if (s) snprintf(buf, len, "; did you mean '%s'?", s);
	else buf[0] = '\0';
	free(cands);
	return buf;
}

enum { GLOBALS, OBJECTS, PROPS };

/* The names of p's globals, objects, or the properties of object obj that the run keeps (the
   others NULL), *n of them; malloc'd (NULL if out of memory). */
static const char **names_of(const csf_prog *p, int which, uint32_t obj, uint32_t *n)
{
	*n = which == GLOBALS ? p->nglobals : which == OBJECTS ? p->nobjects : p->nprops;
	const char **c = calloc(*n + 1, sizeof *c);
	for (uint32_t i = 0; c && i < *n; i++)
		if (which == GLOBALS) c[i] = csf_str(p, p->globals[i].name);
		else if (which == OBJECTS) c[i] = csf_str(p, p->objects[i]);
		else if (p->props[i].object == obj) c[i] = csf_str(p, p->props[i].name);
	return c;
}

/* ---- -D NAME=VALUE ---- */

/* csf_param_find of a whole global or property (no component). */
static int find_whole(const csf_prog *p, const char *name, csf_pref *r, char *err, size_t errlen)
{
	char hint[300];
	uint32_t n;
	const char *dot = strchr(name, '.');
	if (!dot) {
		for (uint32_t i = 0; i < p->nglobals; i++)
			if (strcmp(csf_str(p, p->globals[i].name), name) == 0) {
				*r = (csf_pref){ p->globals[i].slot, p->globals[i].width, &p->pclasses[p->globals[i].cls] };
				return 0;
			}
		for (uint32_t i = 0; i < p->nobjects; i++)
			if (strcmp(csf_str(p, p->objects[i]), name) == 0)
				return csf_fail(err, errlen, "'%s' is an object: name one of its properties, %s.PROP", name, name);
		const char **c = names_of(p, GLOBALS, 0, &n);
		return csf_fail(err, errlen, "unknown name '%s': the scene has no global of that name%s", name,
		                suggestion(name, c, n, hint, sizeof hint));
	}
	size_t on = (size_t)(dot - name);
	uint32_t obj = UINT32_MAX;
	for (uint32_t i = 0; i < p->nobjects && obj == UINT32_MAX; i++)
		if (strlen(csf_str(p, p->objects[i])) == on && memcmp(csf_str(p, p->objects[i]), name, on) == 0) obj = i;
	if (obj == UINT32_MAX) {
		char oname[256];
		snprintf(oname, sizeof oname, "%.*s", (int)on, name);
		const char **c = names_of(p, OBJECTS, 0, &n);
		return csf_fail(err, errlen, "unknown name '%s': the scene has no object '%s'%s", name, oname,
		                suggestion(oname, c, n, hint, sizeof hint));
	}
	for (uint32_t i = 0; i < p->nprops; i++)
		if (p->props[i].object == obj && strcmp(csf_str(p, p->props[i].name), dot + 1) == 0) {
			*r = (csf_pref){ p->props[i].slot, p->props[i].width, &p->pclasses[p->props[i].cls] };
			return 0;
		}
	const char **c = names_of(p, PROPS, obj, &n);
	return csf_fail(err, errlen, "unknown name '%s': object '%.*s' has no property '%s' that the run uses%s", name,
	                (int)on, name, dot + 1, suggestion(dot + 1, c, n, hint, sizeof hint));
}

int csf_param_find(const csf_prog *p, const char *name, csf_pref *r, char *err, size_t errlen)
{
	if (!find_whole(p, name, r, err, errlen)) return 0;
	/* NAME.x, .y or .z: one component of a vector */
	size_t n = strlen(name);
	if (n < 3 || name[n - 2] != '.' || name[n - 1] < 'x' || name[n - 1] > 'z') return -1;
	char *whole = malloc(n - 1);
	if (!whole) return -1;
	memcpy(whole, name, n - 2);
	whole[n - 2] = '\0';
	char why[8];
	int bad = find_whole(p, whole, r, why, sizeof why);
	free(whole);
	if (bad || r->width != 3) return -1; /* err says why name is unknown */
	r->slot += (uint32_t)(name[n - 1] - 'x');
	r->width = 1;
	return 0;
}

/* A value being read: where in the text, whether the last opt_unit found a unit, the model's unit system. */
typedef struct vread {
	const char *s;
	int has_unit;
	const double *base;
} vread;

static void skip_ws(vread *V) { while (isspace((unsigned char)*V->s)) V->s++; }

/* An optional unit at V->s: its factor in the model's units into *f (1 if none), its dimension checked. */
static int opt_unit(vread *V, double *f, double dim[CSF_NDIM], const char **why)
{
	skip_ws(V);
	*f = 1;
	memset(dim, 0, CSF_NDIM * sizeof *dim);
	if (!csf_unit_starts(V->s)) return 0;
	csf_unit u;
	const char *end;
	if (csf_unit_parse(V->s, &end, &u, why)) return -1;
	V->s = end;
	for (int k = 0; k < CSF_NDIM; k++) dim[k] = u.dim[k];
	*f = csf_units_to_system(u.factor, dim, V->base);
	V->has_unit = 1;
	return 0;
}

static int number(vread *V, double *x)
{
	skip_ws(V);
	char *end;
	errno = 0;
	*x = strtod(V->s, &end);
	if (end == V->s || errno == ERANGE || !isfinite(*x)) return -1;
	V->s = end;
	return 0;
}

int csf_param_value(const csf_prog *p, const char *name, const csf_pref *r, const char *text, double v[3], char *err,
                    size_t errlen)
{
	vread V = { .s = text, .base = p->ubase };
	const char *why = "expected a number";
	int n = 1, has[3] = { 0, 0, 0 };
	double f[3] = { 1, 1, 1 }, d[3][CSF_NDIM] = { { 0 } }, of, od[CSF_NDIM];
	skip_ws(&V);
	if (*V.s == '(') {
		n = 3;
		V.s++;
		for (int k = 0; k < 3; k++) {
			V.has_unit = 0;
			if (number(&V, &v[k]) || opt_unit(&V, &f[k], d[k], &why)) goto bad;
			has[k] = V.has_unit;
			skip_ws(&V);
			if (*V.s != (k < 2 ? ',' : ')')) {
				why = k < 2 ? "expected ',' between a vector's components" : "expected ')' after a vector's third component";
				goto bad;
			}
			V.s++;
		}
	} else if (number(&V, &v[0])) {
		goto bad;
	}
	V.has_unit = 0;
	if (opt_unit(&V, &of, od, &why)) goto bad;
	skip_ws(&V);
	if (*V.s) {
		why = "unexpected text after the value";
		goto bad;
	}
	/* as the compiler folds it: each component times its unit's factor, then the whole times the outer one's */
	int dim_set = 0;
	double dim[CSF_NDIM] = { 0 }, t[CSF_NDIM];
	for (int k = 0; k < n; k++) {
		v[k] = v[k] * f[k] * of;
		if (!has[k] && !V.has_unit) continue;
		for (int i = 0; i < CSF_NDIM; i++) t[i] = d[k][i] + od[i];
		if (dim_set && memcmp(t, dim, sizeof t) != 0)
			return csf_fail(err, errlen, "'%s': the components of a vector must have one dimension", text);
		memcpy(dim, t, sizeof t);
		dim_set = 1;
	}
	if ((uint32_t)n != r->width)
		return csf_fail(err, errlen, "%s is a %s: give %s, not '%s'", name, r->width == 3 ? "vector" : "scalar",
		            r->width == 3 ? "(x, y, z) and a unit" : "a number and a unit", text);
	const csf_pclass *c = r->cls;
	const char *unit = csf_str(p, c->unit);
	if (dim_set && !c->known && memcmp(dim, (double[CSF_NDIM]){ 0 }, sizeof dim) != 0)
		return csf_fail(err, errlen, "the dimension of %s is not known to the model: give a bare number, not '%s'", name, text);
	if (dim_set && c->known && memcmp(c->dim, dim, sizeof dim) != 0) {
		if (!*unit) return csf_fail(err, errlen, "wrong dimension: %s is dimensionless, '%s' is not (expected a bare number)", name, text);
		return csf_fail(err, errlen, "wrong dimension: %s is in %s, '%s' is not (expected unit %s)", name, unit, text, unit);
	}
	for (int k = 0; k < n; k++)
		if (!isfinite(v[k])) return csf_fail(err, errlen, "'%s' is not a finite value", text);
	return 0;
bad:
	return csf_fail(err, errlen, "cannot read '%s' as a value: %s at '%s'", text, why, V.s);
}

int csf_overlay_add(csf_overlay *ov, uint32_t slot, double value)
{
	if (ov->n == ov->cap) {
		size_t cap = ov->cap ? 2 * ov->cap : 8;
		csf_setting *v = realloc(ov->v, cap * sizeof *v);
		if (!v) return -1;
		ov->v = v, ov->cap = cap;
	}
	ov->v[ov->n++] = (csf_setting){ slot, value };
	return 0;
}

void csf_overlay_apply(const csf_overlay *ov, double *m)
{
	for (size_t i = 0; ov && i < ov->n; i++) m[ov->v[i].slot] = ov->v[i].value;
}

void csf_overlay_free(csf_overlay *ov)
{
	free(ov->v);
	*ov = (csf_overlay){ 0 };
}

int csf_param_set(const csf_prog *p, csf_overlay *ov, const char *assign, char *err, size_t errlen)
{
	const char *eq = strchr(assign, '=');
	if (!eq || eq == assign) return csf_fail(err, errlen, "-D %s: expected NAME=VALUE", assign);
	char name[256];
	size_t n = (size_t)(eq - assign);
	while (n && isspace((unsigned char)assign[n - 1])) n--;
	if (n >= sizeof name) return csf_fail(err, errlen, "-D %s: name too long", assign);
	memcpy(name, assign, n);
	name[n] = '\0';
	csf_pref r;
	char why[400];
	double v[3];
	if (csf_param_find(p, name, &r, why, sizeof why)) return csf_fail(err, errlen, "-D %s: %s", assign, why);
	if (*csf_str(p, r.cls->why))
		return csf_fail(err, errlen, "-D %s: %s cannot be overridden: %s", assign, name, csf_str(p, r.cls->why));
	if (csf_param_value(p, name, &r, eq + 1, v, why, sizeof why)) return csf_fail(err, errlen, "-D %s: %s", assign, why);
	for (uint32_t k = 0; k < r.width; k++)
		if (csf_overlay_add(ov, r.slot + k, v[k])) return csf_fail(err, errlen, "-D %s: out of memory", assign);
	return 0;
}

/* A value of a parameter as csf_params_list writes it: "3" or "(1, 2, 3)". */
static void put_value(FILE *f, const double *v, uint32_t width)
{
	char b[32];
	for (uint32_t k = 0; k < width; k++) {
		csf_fmt_double(b, v[k]);
		fprintf(f, "%s%s", width == 3 ? (k ? ", " : "(") : "", b);
	}
	if (width == 3) fputc(')', f);
}

/* What follows a parameter's value on its line: its unit, a note, and why -D cannot set it. */
static void put_tail(const csf_prog *p, FILE *f, const csf_pclass *c, const char *note)
{
	const char *why = csf_str(p, c->why), *unit = csf_str(p, c->unit);
	fprintf(f, "%s%s%s", *unit ? " " : "", unit, note);
	if (*why) fprintf(f, ": cannot be set: %s", why);
	else if (!c->known) fputs(" (dimension not known: a bare number)", f);
}

/* One parameter's line of csf_params_list. */
static void list_one(const csf_prog *p, FILE *f, const char *obj, const char *name, uint32_t slot, uint32_t width,
                     const csf_pclass *c)
{
	fprintf(f, "  %s%s%s = ", obj ? obj : "", obj ? "." : "", name);
	put_value(f, p->mem0 + slot, width);
	put_tail(p, f, c, "");
	fputc('\n', f);
}

/* The length of the array name of a member named NAME[K] (K into *k), or 0. */
static size_t member_name(const char *obj, long *k)
{
	size_t n = strlen(obj);
	if (n < 4 || obj[n - 1] != ']') return 0;
	const char *open = strrchr(obj, '[');
	if (!open || open == obj) return 0;
	char *end;
	*k = strtol(open + 1, &end, 10);
	return end == obj + n - 1 && end != open + 1 ? (size_t)(open - obj) : 0;
}

/* The properties of object props[i].object: props[i .. *end). */
static uint32_t props_end(const csf_prog *p, uint32_t i)
{
	uint32_t j = i;
	while (j < p->nprops && p->props[j].object == p->props[i].object) j++;
	return j;
}

/* Do the properties at a and b (n each) have the same names, widths and classes? */
static int same_props(const csf_prog *p, uint32_t a, uint32_t b, uint32_t n)
{
	for (uint32_t q = 0; q < n; q++) {
		const csf_prop *x = &p->props[a + q], *y = &p->props[b + q];
		if (x->name != y->name || x->width != y->width || x->cls != y->cls) return 0;
	}
	return 1;
}

/*
 * The members of an array that follow each other in index order with the
 * same properties (at least ARRAY_RUN of them) are summarised, a line per
 * property: "star[0..999].m = 1 kg: 1000 members, the same", or the first
 * and last values, "each its own"; -D sets one member as NAME[K].PROP.
 */
enum { ARRAY_RUN = 3 };

void csf_params_list(const csf_prog *p, FILE *f)
{
	fputs("parameters (csfvm -D NAME=VALUE, --sweep), with their values and units:\n", f);
	for (uint32_t i = 0; i < p->nglobals; i++)
		list_one(p, f, NULL, csf_str(p, p->globals[i].name), p->globals[i].slot, p->globals[i].width,
		         &p->pclasses[p->globals[i].cls]);
	for (uint32_t i = 0; i < p->nprops;) {
		const char *obj = csf_str(p, p->objects[p->props[i].object]);
		uint32_t end = props_end(p, i), n = end - i, members = 1, last = i;
		long k0, k;
		size_t len = member_name(obj, &k0);
		for (uint32_t j = end; len && j < p->nprops; members++) { /* the run of members after obj */
			const char *o = csf_str(p, p->objects[p->props[j].object]);
			uint32_t e = props_end(p, j);
			if (member_name(o, &k) != len || strncmp(o, obj, len) != 0 || k != k0 + (long)members || e - j != n ||
			    !same_props(p, i, j, n))
				break;
			last = j;
			j = e;
		}
		if (members < ARRAY_RUN) {
			for (uint32_t q = i; q < end; q++)
				list_one(p, f, obj, csf_str(p, p->props[q].name), p->props[q].slot, p->props[q].width,
				         &p->pclasses[p->props[q].cls]);
			i = end;
			continue;
		}
		for (uint32_t q = 0; q < n; q++) {
			const csf_prop *a = &p->props[i + q];
			int same = 1;
			for (uint32_t j = i + n + q; same && j <= last + q; j += n)
				same = memcmp(p->mem0 + p->props[j].slot, p->mem0 + a->slot, a->width * sizeof(double)) == 0;
			fprintf(f, "  %.*s[%ld..%ld].%s = ", (int)len, obj, k0, k0 + (long)members - 1, csf_str(p, a->name));
			put_value(f, p->mem0 + a->slot, a->width);
			if (!same) {
				fputs(" .. ", f);
				put_value(f, p->mem0 + p->props[last + q].slot, a->width);
			}
			char note[64];
			snprintf(note, sizeof note, " (%u members, %s)", members, same ? "the same" : "each its own");
			put_tail(p, f, &p->pclasses[a->cls], note);
			fputc('\n', f);
		}
		i = last + n;
	}
}
