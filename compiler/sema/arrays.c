/*
 * arrays.c - object arrays (DECISIONS §11): `object star[0..999]: KIND`
 * declares the members star[0] .. star[999], objects like any other, made
 * one after the other so that member k is object first + k - lo;
 * `object star[i]: PROP = EXPR` sets a property of every member, the index
 * name standing for the member's index; `object star[7]: ...` sets one;
 * `object grain[]: from "FILE.csv"` makes one member per data row of a file
 * whose header names the properties, with their units in brackets, as
 * CSF's own output does. A `for` list may name members by an index
 * expression (`for node[i], node[i+1]`): the rule applies for every value
 * of the index for which each member it names exists.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

ObjArray *array_of(const char *name) { return map_get(&sema.arrays, name); }

Object *object_named(const char *name)
{
	Object *o = map_get(&sema.objects_by_name, name);
	const char *br = o ? NULL : strchr(name, '[');
	if (!br || (!isdigit((unsigned char)br[1]) && br[1] != '-')) return o;
	char *end;
	long k = strtol(br + 1, &end, 10);
	ObjArray *A = strcmp(end, "]") ? NULL : array_of(xstrndup(name, (size_t)(br - name)));
	return A ? array_member(A, k) : NULL;
}

Object *array_member(const ObjArray *A, long k)
{
	if (k < A->lo || k > A->hi) return NULL;
	return sema.M->objects.v[A->first + (int)(k - A->lo)];
}

/* Declares the array name with the members lo..hi, made now (NULL after an error at l). */
static ObjArray *declare(const char *name, Loc l, long lo, long hi)
{
	ObjArray *A = array_of(name);
	if (A) {
		error_at(l, "object array '%s' is already declared", name);
		note_at(A->loc, "declared here");
		return NULL;
	}
	if (!check_name(name, l, "an object array")) return NULL;
	if (map_get(&sema.objects_by_name, name)) {
		error_at(l, "'%s' already names an object", name);
		return NULL;
	}
	if (map_get(&sema.globals_by_name, name)) {
		error_at(l, "'%s' is a global and cannot name an object array", name);
		return NULL;
	}
	A = xalloc(sizeof *A);
	A->name = (char *)name;
	A->loc = l;
	A->lo = lo;
	A->hi = hi;
	A->first = sema.M->objects.n;
	size_t len = strlen(name);
	for (long k = lo; k <= hi; k++) {
		/* NAME[K], written without printf: a million of them */
		char digits[24], *d = digits + sizeof digits;
		unsigned long u = k < 0 ? 0UL - (unsigned long)k : (unsigned long)k;
		*--d = '\0';
		*--d = ']';
		do *--d = (char)('0' + u % 10); while (u /= 10);
		if (k < 0) *--d = '-';
		size_t nd = (size_t)(digits + sizeof digits - d);
		char *n = xalloc(len + 1 + nd);
		memcpy(n, name, len);
		n[len] = '[';
		memcpy(n + len + 1, d, nd);
		new_object(n, l)->lean = sema.shaped ? A : NULL; /* by object, every object has its own properties */
	}
	A->owner = sema.shaped ? sema.M->objects.v[A->first] : NULL;
	map_put(&sema.arrays, A->name, A);
	vec_push(&sema.array_list, A);
	return A;
}

/* The array statement s names, declared before (NULL after an error). */
static ObjArray *declared(Stmt *s)
{
	ObjArray *A = array_of(s->name);
	if (!A && !map_get(&sema.arrays_failed, s->name)) error_at(s->name_loc, "'%s' is not an object array: declare its members first ('object %s[0..9]: KIND')",
	                 s->name, s->name);
	return A;
}

/* Applies object statement s (a kind, or a property) to member o; every: s sets every member
   (object NAME[i], NAME[A..B]), which a member's own value that follows (object NAME[K])
   overrides (put_prop). A member left out (mid/cone.c's resolution without the objects that
   nothing watched depends on) takes nothing: no rule, watch or contact reads it, and a million
   members' properties made only to be left out took a tenth of csfc's time. */
static void apply(Stmt *s, Object *o, int every)
{
	if (sema_dropping(o->index)) return;
	if (s->kind == S_OBJKIND) apply_kind(o, s);
	else set_prop(o, s, every ? 2 : 0);
}

/* Does x read only numbers and globals: is its value the same for every member? */
static int reads_constants(const Expr *x)
{
	if (!x) return 1;
	if (x->kind == E_NAME) return map_get(&sema.globals_by_name, x->name) != NULL;
	if (x->kind == E_DOLLAR || x->kind == E_INDEX || x->kind == E_SUM) return 0;
	if (!reads_constants(x->a) || !reads_constants(x->b)) return 0;
	for (int i = 0; x->kind != E_LIT && i < x->nargs; i++)
		if (!reads_constants(x->args[i])) return 0;
	return 1;
}

/* Does x raise to a power that reads the name n (a dimension that depends on the member)? */
static int power_reads(const Expr *x, const char *n)
{
	if (!x) return 0;
	if (x->kind == E_BIN && x->op == '^' && expr_reads_name(x->b, n)) return 1;
	if (power_reads(x->a, n) || power_reads(x->b, n)) return 1;
	for (int i = 0; x->kind != E_LIT && i < x->nargs; i++)
		if (power_reads(x->args[i], n)) return 1;
	return 0;
}

/* Having applied s to lean member o, the first: does every other lean member take the same, so that
   nothing is left to do for them? Its values read only constants, and no member has a value of its own
   of a property it sets (that would be an error to report). */
static int same_for_all(Stmt *s, Object *o)
{
	if (s->kind == S_PROP) {
		Var *p = prop_of_obj(o, s->prop);
		return p && !var_more_of(p)->own && reads_constants(s->value) && (!s->atol || reads_constants(s->atol));
	}
	Stmt *k = map_get(&sema.kinds, s->prop);
	for (Stmt *p = k ? k->body : NULL; p; p = p->next) {
		Var *v = prop_of_obj(o, p->prop);
		if (!v || var_more_of(v)->own || !reads_constants(p->value) || (p->atol && !reads_constants(p->atol))) return 0;
	}
	return k != NULL;
}

/* Applies s to every member of A, ivar (if not NULL) naming the member's index; as names every member
   in -D's messages (sema.fold_as). One report, not one per member. The lean members (Object.lean) after
   the first need nothing if they all take the same; and a value's dimension, which the first's
   folding found, is theirs too, unless a power reads the index. */
static void every_member(Stmt *s, ObjArray *A, const char *ivar, const char *as)
{
	sema.arr_stmt = s;
	sema.arr_set = A;
	sema.fold_as = as;
	int first = 1, alike = 0, dims = 0;
	for (long k = A->lo; k <= A->hi; k++) {
		Object *o = array_member(A, k);
		if (o->lean && alike) continue;
		int before = diag_errors;
		sema.ivar = ivar;
		sema.idx = k;
		sema.dims_off = o->lean && dims;
		apply(s, o, 1);
		sema.dims_off = 0;
		sema.ivar = NULL;
		if (diag_errors > before) break;
		if (o->lean && first && !sema_dropping(o->index)) {
			first = 0;
			alike = same_for_all(s, o);
			dims = s->kind == S_PROP && !(ivar && power_reads(s->value, ivar)) && sema.dims_set;
		}
	}
	sema.arr_stmt = NULL;
	sema.arr_set = NULL;
	sema.fold_as = NULL;
	sema.dims_set = 0;
}

static void from_file(Stmt *s);

void array_stmt(Stmt *s)
{
	ObjArray *A;
	switch (s->arr) {
	case ARR_RANGE:
		if (s->kind == S_OBJKIND && !map_get(&sema.kinds, s->prop)) {
			error_at(s->prop_loc, "unknown kind '%s'", s->prop);
			return;
		}
		if (!(A = declare(s->name, s->name_loc, s->lo, s->hi))) return;
		every_member(s, A, NULL, xprintf("%s[%ld..%ld]", A->name, A->lo, A->hi));
		return;
	case ARR_EACH:
		if (!(A = declared(s)) || !check_name(s->ivar, s->name_loc, "an index")) return;
		if (s->kind == S_OBJKIND && !map_get(&sema.kinds, s->prop)) {
			error_at(s->prop_loc, "unknown kind '%s'", s->prop);
			return;
		}
		every_member(s, A, s->ivar, xprintf("%s[%s]", A->name, s->ivar));
		return;
	case ARR_ONE: {
		if (!(A = declared(s))) return;
		Object *o = array_member(A, s->lo);
		if (!o) {
			error_at(s->name_loc, "'%s' has the members %ld..%ld: there is no %s[%ld]", A->name, A->lo, A->hi, A->name, s->lo);
			return;
		}
		apply(s, o, 0);
		return;
	}
	case ARR_FILE:
		if (!s->from) {
			error_at(s->name_loc, "'%s[]' reads its members from a data file: 'object %s[]: from \"FILE.csv\"'", s->name,
			         s->name);
			return;
		}
		from_file(s);
		return;
	}
}

/* The value of an index expression in context C: a whole number; 0 after an error (C->failed). */
static int index_value(Ctx *C, Expr *idx, long *out)
{
	Ctx K = { 0 };
	K.init = 1;
	K.ivar = C->ivar;
	K.idx = C->idx;
	K.fold = FIX_FOLDED; /* a global that chooses members: -D cannot set it */
	K.fold_name = "an object index";
	K.fold_line = idx->loc.line;
	RExpr *r = build(&K, idx);
	if (K.failed) {
		C->failed = 1;
		return 0;
	}
	if (r->k != R_CONST || r->isvec || r->isbool || (r->dimk == DK_KNOWN && !dims_none(r->dim)) ||
	    r->c[0] != floor(r->c[0]) || fabs(r->c[0]) >= 1e9) {
		error_at(idx->loc, "an object index must be a whole number known at compile time (the index name, numbers, globals)");
		C->failed = 1;
		return 0;
	}
	*out = (long)r->c[0];
	return 1;
}

Object *array_at(Ctx *C, const char *array, Expr *idx, Loc l)
{
	ObjArray *A = array_of(array);
	if (!A) {
		C->failed = 1;
		if (map_get(&sema.arrays_failed, array)) return NULL; /* its data file is wrong: reported */
		error_at(l, map_get(&sema.objects_by_name, array) ? "'%s' is an object, not an object array: it has no members"
		                                                   : "'%s' is not an object array",
		         array);
		C->failed = 1;
		return NULL;
	}
	long k;
	if (!index_value(C, idx, &k)) return NULL;
	Object *o = array_member(A, k);
	if (!o) {
		error_at(l, "'%s' has the members %ld..%ld: there is no %s[%ld]", A->name, A->lo, A->hi, A->name, k);
		C->failed = 1;
	}
	return o;
}

Object *objref_object(ObjRef *r)
{
	if (r->idx) {
		Ctx C = { 0 };
		C.ivar = sema.ivar;
		C.idx = sema.idx;
		return array_at(&C, r->name, r->idx, r->loc);
	}
	int nobj = sema.M->objects.n;
	Object *o = r->name ? map_get(&sema.objects_by_name, r->name) : (r->index < nobj ? sema.M->objects.v[r->index] : NULL);
	if (o) return o;
	if (r->name && map_get(&sema.arrays_failed, r->name)) return NULL; /* its data file is wrong: reported */
	if (r->name && array_of(r->name))
		error_at(r->loc, "'%s' is an object array: name one member ('%s[3]'), or each by an index ('%s[i]')", r->name, r->name,
		         r->name);
	else if (r->name) error_at(r->loc, "unknown object '%s'", r->name);
	else error_at(r->loc, "there is no object number %d (objects are numbered from 0)", r->index);
	return NULL;
}

/* Adds to *name the free name expression x reads (not a global, t or RF); reports a second one at *bad. */
static void free_names(Expr *x, const char **name, int *bad)
{
	if (!x || *bad) return;
	if (x->kind == E_NAME && !is_predefined(x->name) && !map_get(&sema.globals_by_name, x->name)) {
		if (*name && strcmp(*name, x->name) != 0) {
			error_at(x->loc, "the members of a 'for' list are indexed by one name: '%s' and '%s'", *name, x->name);
			*bad = 1;
		}
		*name = x->name;
	}
	free_names(x->a, name, bad);
	free_names(x->b, name, bad);
	for (int i = 0; i < x->nargs; i++) free_names(x->args[i], name, bad);
}

int for_indexed(Stmt *s)
{
	const char *name = NULL;
	int bad = 0;
	for (int i = 0; i < s->fors.n; i++) free_names(((ObjRef *)s->fors.v[i])->idx, &name, &bad);
	if (bad) return -1;
	s->ivar = (char *)name;
	return name != NULL;
}

/* floor(a / b) and ceil(a / b) of whole numbers, b > 0 */
static long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
static long ceil_div(long a, long b) { return -floor_div(-a, b); }

int for_index_range(Stmt *s, long *from, long *to)
{
	long lo = -2000000000L, hi = 2000000000L;
	int chosen = 0;
	for (int i = 0; i < s->fors.n; i++) {
		ObjRef *r = s->fors.v[i];
		if (!r->idx) continue;
		ObjArray *A = array_of(r->name);
		if (!A) {
			Ctx C = { 0 };
			array_at(&C, r->name, r->idx, r->loc); /* reports it */
			return 0;
		}
		/* the index is a * i + b: its values at -1, 0, 1 and 2 say which a and b, and that it is */
		long v[4];
		for (int k = 0; k < 4; k++) {
			Ctx C = { 0 };
			C.ivar = s->ivar;
			C.idx = k - 1;
			if (!index_value(&C, r->idx, &v[k])) return 0;
		}
		long a = v[2] - v[1], b = v[1];
		if (v[0] != b - a || v[3] != b + 2 * a) {
			error_at(r->idx->loc, "a member's index in a 'for' list is the index name times a whole number plus a whole "
			                      "number ('%s+1', '2*%s')", s->ivar, s->ivar);
			return 0;
		}
		if (a == 0) {
			if (b < A->lo || b > A->hi) lo = 1, hi = 0; /* a member that is not there: no binding */
			continue;
		}
		chosen = 1;
		long l = a > 0 ? ceil_div(A->lo - b, a) : ceil_div(b - A->hi, -a);
		long h = a > 0 ? floor_div(A->hi - b, a) : floor_div(b - A->lo, -a);
		if (l > lo) lo = l;
		if (h < hi) hi = h;
	}
	if (!chosen) {
		error_at(s->loc, "the index name '%s' of this 'for' list does not choose the members", s->ivar);
		return 0;
	}
	*from = lo;
	*to = hi;
	return 1;
}

/* ---- members from a data file ---- */

/* A column of the header: property prop (component comp, or -1), its unit (has_unit). */
typedef struct DataCol {
	char *prop;
	int comp;
	int has_unit;
	csf_unit u;
	Loc loc;
} DataCol;

/* A property of the data: its columns (col[0] alone for a scalar). */
typedef struct DataProp {
	char *name;
	int isvec;
	int col[3];
	Loc loc;
} DataProp;

/* The path of the data file name, relative to the directory of the source file. */
static char *data_path(const char *name, int file)
{
	if (name[0] == '/' || file < 0 || file >= sources.n) return xstrdup(name);
	const char *src = ((Source *)sources.v[file])->path, *slash = strrchr(src, '/');
	return slash ? xprintf("%.*s/%s", (int)(slash - src), src, name) : xstrdup(name);
}

/* The source table's index of the data file at path, read once. */
static int data_load(const char *path)
{
	for (int i = 0; i < sources.n; i++)
		if (!strcmp(((Source *)sources.v[i])->path, path)) return i;
	return src_load(path);
}

/* The bounds of field k of a line [p, e): [*b, *f) trimmed of blanks. */
static const char *trim(const char *b, const char *e, const char **f)
{
	while (b < e && (*b == ' ' || *b == '\t')) b++;
	while (e > b && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) e--;
	*f = e;
	return b;
}

/* Reads header field [b, f) at l into c. */
static int header_col(const char *b, const char *f, Loc l, DataCol *c)
{
	const char *n = b;
	if (n == f || !(isalpha((unsigned char)*n) || *n == '_')) {
		error_at(l, "a column of the header is a property, with its unit in brackets: 'm [kg]', 'pos.x [m]'");
		return 0;
	}
	while (n < f && (isalnum((unsigned char)*n) || *n == '_')) n++;
	c->prop = xstrndup(b, (size_t)(n - b));
	c->comp = -1;
	c->loc = l;
	if (n < f && *n == '.') {
		if (n + 2 > f || !strchr("xyz", n[1]) || (n + 2 < f && n[2] != ' ' && n[2] != '[')) {
			error_at(l, "'%.*s': a vector's column names its component x, y or z ('pos.x [m]')", (int)(f - b), b);
			return 0;
		}
		c->comp = n[1] - 'x';
		n += 2;
	}
	while (n < f && *n == ' ') n++;
	if (n == f) return 1;
	if (*n != '[' || f[-1] != ']') {
		error_at(l, "'%.*s': a column's unit is written in brackets after its name ('v.x [m/s]')", (int)(f - b), b);
		return 0;
	}
	const char *u = n + 1, *ue = f - 1, *end, *why = NULL;
	while (u < ue && *u == ' ') u++;
	while (ue > u && ue[-1] == ' ') ue--;
	c->has_unit = 1;
	if (u == ue || (ue - u == 1 && *u == '1')) { /* [] or [1]: dimensionless */
		c->u = (csf_unit){ 0 };
		c->u.factor = 1;
		return 1;
	}
	char *text = xstrndup(u, (size_t)(ue - u));
	if (csf_unit_parse(text, &end, &c->u, &why) != 0 || *end) {
		error_at(l, "unknown unit '%s'%s%s", text, why && strcmp(why, "unknown unit") ? ": " : "",
		         why && strcmp(why, "unknown unit") ? why : "");
		return 0;
	}
	return 1;
}

/* The properties of the header's columns, checked (0 after an error). */
static int header_props(DataCol *cols, int ncols, Vec *props)
{
	Map by_name = { 0 };
	for (int i = 0; i < ncols; i++) {
		DataCol *c = &cols[i];
		if (!check_name(c->prop, c->loc, "a property")) return 0;
		DataProp *p = map_get(&by_name, c->prop);
		if (!p) {
			p = xalloc(sizeof *p);
			p->name = c->prop;
			p->isvec = c->comp >= 0;
			p->col[0] = p->col[1] = p->col[2] = -1;
			p->loc = c->loc;
			map_put(&by_name, p->name, p);
			vec_push(props, p);
		}
		if (p->isvec != (c->comp >= 0)) {
			error_at(c->loc, "'%s' is a column and a vector's component: a vector has the columns %s.x, %s.y and %s.z",
			         c->prop, c->prop, c->prop, c->prop);
			return 0;
		}
		int k = c->comp >= 0 ? c->comp : 0;
		if (p->col[k] >= 0) {
			error_at(c->loc, "the column '%s' appears twice", c->comp >= 0 ? xprintf("%s.%c", c->prop, 'x' + c->comp) : c->prop);
			return 0;
		}
		p->col[k] = i;
		if (p->isvec && k > 0) {
			DataCol *f = &cols[p->col[0] >= 0 ? p->col[0] : p->col[1]];
			if (f != c && (f->has_unit != c->has_unit || memcmp(f->u.dim, c->u.dim, sizeof c->u.dim) != 0)) {
				error_at(c->loc, "the components of '%s' have units of different dimensions", c->prop);
				return 0;
			}
		}
	}
	for (int i = 0; i < props->n; i++) {
		DataProp *p = props->v[i];
		for (int k = 0; p->isvec && k < 3; k++)
			if (p->col[k] < 0) {
				error_at(p->loc, "the vector '%s' has no column %s.%c: a vector has the columns %s.x, %s.y and %s.z", p->name,
				         p->name, 'x' + k, p->name, p->name, p->name);
				return 0;
			}
	}
	return 1;
}

/* The next line of file f from *at (its number *line): [b, e), skipping blank lines. 0 at the end. */
static int next_line(Source *f, size_t *at, int *line, const char **b, const char **e)
{
	while (*at < f->len) {
		const char *p = f->text + *at, *q = memchr(p, '\n', f->len - *at);
		if (!q) q = f->text + f->len;
		*at = (size_t)(q - f->text) + 1;
		(*line)++;
		const char *t, *s = trim(p, q, &t);
		if (s < t) {
			*b = p;
			*e = q;
			return 1;
		}
	}
	return 0;
}

static void read_file(Stmt *s);

/* Reads the members of s from its data file; after an error, the array's name is known to have failed
 * (its uses are not reported again). */
static void from_file(Stmt *s)
{
	int before = diag_errors;
	sema.arr_stmt = s;
	read_file(s);
	sema.arr_stmt = NULL;
	if (diag_errors > before) map_put(&sema.arrays_failed, s->name, s);
}

static void read_file(Stmt *s)
{
	char *path = data_path(s->from, s->loc.file);
	int file = data_load(path);
	if (file < 0) {
		error_at(s->prop_loc, "cannot read the data file '%s': %s", path, strerror(errno));
		return;
	}
	Source *f = sources.v[file];
	if (memchr(f->text, '\0', f->len)) {
		error_at((Loc){ file, 1, 1 }, "this is not a text file of data (it holds a NUL byte)");
		return;
	}
	size_t at = 0;
	int line = 0;
	const char *b, *e;
	if (!next_line(f, &at, &line, &b, &e)) {
		error_at(s->prop_loc, "the data file '%s' is empty: its first line names the columns ('pos.x [m],pos.y [m],...')", path);
		return;
	}
	Vec cols = { 0 };
	for (const char *p = b;;) {
		const char *c = memchr(p, ',', (size_t)(e - p));
		if (!c) c = e;
		const char *fe, *fb = trim(p, c, &fe);
		DataCol *col = xalloc(sizeof *col);
		if (!header_col(fb, fe, (Loc){ file, line, (int)(fb - b) + 1 }, col)) return;
		vec_push(&cols, col);
		if (c == e) break;
		p = c + 1;
	}
	int ncols = cols.n;
	DataCol *cv = xalloc((size_t)ncols * sizeof *cv);
	for (int i = 0; i < ncols; i++) cv[i] = *(DataCol *)cols.v[i];
	Vec props = { 0 };
	if (!header_props(cv, ncols, &props)) return;
	/* the rows: their values, checked, before any member is made */
	int header_line = line;
	size_t rows_at = at;
	long nrows = 0;
	double *val = xalloc((size_t)ncols * sizeof *val);
	while (next_line(f, &at, &line, &b, &e)) {
		const char *p = b;
		for (int k = 0; k < ncols; k++) {
			const char *c = k + 1 < ncols ? memchr(p, ',', (size_t)(e - p)) : e;
			if (!c) {
				error_at((Loc){ file, line, (int)(e - b) + 1 }, "this row has %d value%s; the header names %d columns", k + 1,
				         k ? "s" : "", ncols);
				return;
			}
			if (k + 1 == ncols && memchr(p, ',', (size_t)(e - p))) {
				error_at((Loc){ file, line, (int)((const char *)memchr(p, ',', (size_t)(e - p)) - b) + 1 },
				         "this row has more values than the %d columns the header names", ncols);
				return;
			}
			const char *fe, *fb = trim(p, c, &fe), *end;
			Loc l = { file, line, (int)(fb - b) + 1 };
			DataCol *col = &cv[k];
			char *text = xstrndup(fb, (size_t)(fe - fb));
			errno = 0;
			double x = fb == fe ? 0 : strtod(text, (char **)&end);
			const char *cn = col->comp < 0 ? col->prop : xprintf("%s.%c", col->prop, 'x' + col->comp);
			if (fb == fe) {
				error_at(l, "a value is missing (column %d, '%s')", k + 1, cn);
				return;
			}
			if (*end || !isfinite(x)) {
				error_at(l, "'%s' is not a finite number (column %d, '%s')", text, k + 1, cn);
				return;
			}
			p = c + 1;
		}
		nrows++;
	}
	if (nrows == 0) {
		error_at((Loc){ file, header_line, 1 }, "the data file '%s' has a header but no rows: one member per row", path);
		return;
	}
	ObjArray *A = declare(s->name, s->name_loc, 0, nrows - 1);
	if (!A) return;
	at = rows_at;
	line = header_line;
	for (long k = 0; next_line(f, &at, &line, &b, &e); k++) {
		const char *p = b;
		for (int j = 0; j < ncols; j++) {
			const char *c = j + 1 < ncols ? memchr(p, ',', (size_t)(e - p)) : e;
			const char *fe, *fb = trim(p, c, &fe);
			char *text = xstrndup(fb, (size_t)(fe - fb));
			double si = strtod(text, NULL) * (cv[j].has_unit ? cv[j].u.factor : 1);
			double d[CSF_NDIM];
			for (int q = 0; q < CSF_NDIM; q++) d[q] = cv[j].u.dim[q];
			val[j] = cv[j].has_unit ? dims_to_system(si, d) : si;
			p = c + 1;
		}
		Object *o = array_member(A, k);
		for (int i = 0; i < props.n; i++) {
			DataProp *dp = props.v[i];
			DataCol *c0 = &cv[dp->col[0]];
			RExpr r = { 0 };
			r.k = R_CONST;
			r.isvec = dp->isvec;
			for (int q = 0; q < (dp->isvec ? 3 : 1); q++) r.c[q] = val[dp->col[q]];
			r.dimk = c0->has_unit ? DK_KNOWN : DK_FREE;
			for (int q = 0; q < CSF_NDIM; q++) r.dim[q] = c0->u.dim[q];
			int before = diag_errors;
			put_prop(o, dp->name, dp->loc, (Loc){ file, line, 1 }, &r, dp->isvec, 0, NULL, NULL);
			if (diag_errors > before) return;
		}
	}
}

/* ---- a rule among neighbours as one loop ---- */

int expr_reads_name(const Expr *x, const char *n)
{
	if (!x) return 0;
	if (x->kind == E_NAME && !strcmp(x->name, n)) return 1;
	if (expr_reads_name(x->a, n) || expr_reads_name(x->b, n)) return 1;
	for (int i = 0; i < x->nargs; i++)
		if (expr_reads_name(x->args[i], n)) return 1;
	return 0;
}

/* Is idx the index name of s plus a whole number (into *off)? Checked at -1, 0, 1 and 2, as
   for_index_range checks a * i + b. */
static int unit_offset(Stmt *s, Expr *idx, long *off)
{
	long v[4];
	for (int k = 0; k < 4; k++) {
		Ctx C = { 0 };
		C.ivar = s->ivar;
		C.idx = k - 1;
		if (!index_value(&C, idx, &v[k])) return 0;
	}
	*off = v[1];
	return v[0] == v[1] - 1 && v[2] == v[1] + 1 && v[3] == v[1] + 2;
}

/* for_loopable's walk of the equation: the members it names by the index name are among the `for`
   list's (its offsets off[0..n)), and the index name is read only in an index. */
typedef struct LoopWalk {
	Stmt *s;
	const char *array;
	long *off;
	int n, ok;
} LoopWalk;

static int loop_walk(Expr *x, void *ctx)
{
	LoopWalk *L = ctx;
	if (!x || !L->ok) return L->ok;
	if (x->kind == E_INDEX) {
		if (expr_reads_name(x->a, L->s->ivar)) {
			long b;
			int known = 0;
			if (!strcmp(x->name, L->array) && unit_offset(L->s, x->a, &b))
				for (int k = 0; k < L->n; k++) known |= L->off[k] == b;
			L->ok = known;
		}
		return L->ok;
	}
	if (x->kind == E_NAME && !strcmp(x->name, L->s->ivar)) return L->ok = 0;
	loop_walk(x->a, L);
	loop_walk(x->b, L);
	for (int i = 0; i < x->nargs; i++) loop_walk(x->args[i], L);
	return L->ok;
}

ObjArray *for_array(Stmt *s) { return array_of(((ObjRef *)s->fors.v[0])->name); }

long for_loopable(Stmt *s, long *from)
{
	Eqn *q = s->eqns;
	if (s->kind != S_RULE || s->call || !q || q->next || q->nest || q->deriv || (s->attr && strcmp(s->attr, "F") != 0))
		return 0;
	if (for_indexed(s) != 1) return 0;
	int n = s->fors.n;
	long *off = xalloc((size_t)n * sizeof *off), lo = 0, hi = 0;
	ObjArray *A = for_array(s);
	for (int k = 0; k < n; k++) {
		ObjRef *r = s->fors.v[k];
		if (!A || !r->idx || strcmp(r->name, A->name) != 0 || !unit_offset(s, r->idx, &off[k])) return 0;
		for (int j = 0; j < k; j++)
			if (off[j] == off[k]) return 0; /* a member named twice: reported per binding */
		if (k == 0 || off[k] < lo) lo = off[k];
		if (k == 0 || off[k] > hi) hi = off[k];
	}
	/* the index values for which every member named exists: A->lo - lo .. A->hi - hi */
	long count = (A->hi - hi) - (A->lo - lo) + 1;
	LoopWalk L = { s, A->name, off, n, 1 };
	if (count < 2 || !stmt_each(s, loop_walk, &L)) return 0;
	*from = A->lo - lo;
	return count;
}
