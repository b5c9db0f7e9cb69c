/*
 * h5.c - a run's rows in an HDF5 file (-o RUN.h5), a sweep's (--sweep
 * ... -o RUN.h5), and such a file back to the CSV the run or the sweep
 * would have written (--dump).
 *
 * The file's root group holds, in creation order (csfvm(1), HDF5 OUTPUT):
 *   t        (rows,)             the output times, unit "s";
 *   xyz      (3,)                the strings "x", "y", "z", when a vector is watched;
 *   objects  (n,)                the names of the objects of a property watched for
 *                                several (objects_PROP for a second list of objects, ...);
 *   PROP     (rows, n) or (rows, n, 3)  a property watched for n > 1 objects, scalar or
 *                                vector: the CSV's columns OBJECT.PROP [UNIT] or OBJECT.PROP.x,
 *                                .y, .z [UNIT], object k at [:, k]; the attribute columns
 *                                holds each object's column in the CSV (its x's);
 *   NAME     (rows,)             any other watched scalar, the CSV's column NAME [UNIT];
 *   NAME     (rows, 3)           any other watched vector, the columns NAME.x, .y, .z [UNIT];
 * the watched datasets in the order of their first columns; each number an
 * IEEE double, each watched dataset with the attribute unit (the CSV
 * header's brackets, "" when none). One property is one dataset when it has
 * one width and one unit; a column of an object watched twice is, the
 * second time, a dataset NAME of its own. t, objects and xyz are dimension
 * scales attached to the watched datasets' axes, so that xarray (h5netcdf)
 * names the axes t, objects and xyz. A name taken before (a column watched
 * twice) is followed by " (2)", " (3)", ... The root's attributes say what
 * ran: model, method, tolerance, defines (-D), command_line, csf_version,
 * till, by, and columns, the CSV header's fields.
 *
 * The datasets are chunked and extendable, a chunk of B rows (as many as
 * fit BLOCK_BYTES, at most 1024) and of as many objects as fit CHUNK_BYTES:
 * the rows are gathered in a buffer of B rows, each dataset's apart, and
 * written a block at a time, the file flushed after each, so that memory
 * stays bounded and a run that ends early (or is killed) leaves a readable
 * file of the rows before.
 *
 * A sweep's file (csfvm(1), HDF5 OUTPUT OF A SWEEP) has a run's datasets
 * with a leading axis of variants, in their order, (variants, rows, ...),
 * t among them (a run that stops early has its own last time); a variant
 * of fewer rows than the longest is NaN past them. Before them:
 *   NAME     (variants,)         each swept parameter's values, in the order
 *                                of the sweep's CSV, attribute unit;
 *   variant  (variants,)         the run numbers 1, 2, ..., a dimension scale;
 *   rows     (variants,)         the rows each variant's run wrote;
 *   status   (variants,)         its exit status, -1 for one never run;
 *   row      (rows,)             0, 1, ..., a dimension scale;
 * then xyz and the objects as in a run's. Variant and row are the scales
 * of the two leading axes; the swept values are no scales (xarray would
 * take each for a dimension of its own) but datasets on variant that
 * every watched dataset names, with t, in its attribute coordinates, the
 * CF convention by which xarray makes them coordinates of variant. The
 * root's attributes are a run's, columns the sweep's CSV header, and
 * swept the parameters' datasets. The variants come one at a time, in
 * order (the writer takes them so: sweep.c), and are written in blocks of
 * as many as a chunk holds (and fit BLOCK_BYTES at the most rows a run
 * has), the file flushed after each; the row axis grows to the longest
 * variant's rows.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>

#include "run_int.h"

enum { BLOCK_BYTES = 32 << 20, BLOCK_ROWS = 1024, CHUNK_BYTES = 1 << 20 };
#define MAX_FIXED 1e9

/*
 * A dataset of rows: its name, unit and width (1, or 3 for a vector), its place in a block of
 * rows. A property's of n objects (col: each one's first column, t being column 0; scale: its
 * dimension scale of objects, an index in h5rows's), else n = 1 and col NULL.
 */
typedef struct h5var {
	char *name, *unit;
	uint32_t width, n;
	uint32_t *col;
	size_t scale;
	size_t off; /* its values in a block: buf[off + (r * n + j) * width + k], row r, object j, component k */
	hid_t ds;
} h5var;

/* A dimension scale of objects: its name and the objects'. */
typedef struct h5objs {
	char *name;
	char **obj;
	uint32_t n;
} h5objs;

/*
 * The datasets of rows (t first), the scales of objects and the buffer of a block of B rows (a
 * sweep's: of B = variants * rows, variant v's row r the block's row v * rows + r). In a sweep's
 * file (lead 1) every dataset has the leading axis of nvariants variants.
 */
typedef struct h5rows {
	h5var *var;
	size_t nvar, ncol;
	h5objs *scale;
	size_t nscale;
	size_t *coff; /* column c (t: 0) at buf[coff[c] + r * cw[c]] */
	uint32_t *cw;
	size_t B;
	hsize_t max;   /* the rows a dataset can hold */
	hsize_t chunk; /* the rows of a chunk */
	int lead;
	hsize_t nvariants, cv; /* a sweep's variants, and those of a chunk */
	double *buf;
} h5rows;

/* A sweep's block: cv variants' swept values (npar each), status, number of rows and rows (ncol each). */
typedef struct h5block {
	int npar;
	hid_t *par;                      /* the datasets of the swept values */
	hid_t variant, rows, status, row; /* and of the others before the rows' */
	double *val;
	long long *st, *nrows, *num;
	unsigned char *held; /* the variants' rows, one after the other, as given */
	size_t nheld, hcap;
	size_t cap;    /* the doubles of the rows' buffer */
	hsize_t first; /* the block's first variant */
} h5block;

struct csf_h5 {
	hid_t file;
	h5rows R;
	size_t nb;    /* rows (a sweep's: variants) in the buffer */
	hsize_t rows; /* rows in the file (a sweep's: its row axis) */
	int werr;     /* a failed write's errno (0: none) */
	h5block S;    /* a sweep's */
};

/*
 * The offsets of the datasets and the R->ncol columns in a block of R->B rows: a property's
 * columns where its col says, the other datasets' the columns left, in order. -2 when the
 * datasets are not ncol columns, each one once.
 */
static int rows_layout(h5rows *R)
{
	size_t w = R->ncol, next = 0;
	memset(R->cw, 0, w * sizeof *R->cw); /* 0: a column not placed yet */
	size_t off = 0;
	for (size_t d = 0; d < R->nvar; d++) {
		h5var *x = &R->var[d];
		x->off = off;
		off += R->B * x->n * x->width;
		for (uint32_t j = 0; x->col && j < x->n; j++)
			for (uint32_t k = 0; k < x->width; k++) {
				size_t c = (size_t)x->col[j] + k;
				if (!c || c >= w || R->cw[c]) return -2; /* t is no object's */
				R->coff[c] = x->off + (size_t)j * x->width + k, R->cw[c] = x->n * x->width;
			}
	}
	for (size_t d = 0; d < R->nvar; d++) {
		h5var *x = &R->var[d];
		for (uint32_t k = 0; !x->col && k < x->width; k++, next++) {
			while (next < w && R->cw[next]) next++;
			if (next == w) return -2;
			R->coff[next] = x->off + k, R->cw[next] = x->width;
		}
	}
	return 0;
}

/* The layout of the ncol columns in a block (rows_layout) and its buffer. -1 when memory runs out, -2 as rows_layout. */
static int rows_alloc(h5rows *R, size_t maxrows, size_t ncol)
{
	size_t w = 0;
	for (size_t d = 0; d < R->nvar; d++) w += (size_t)R->var[d].width * R->var[d].n;
	if (w != ncol || !w) return -2;
	R->B = BLOCK_BYTES / (w * sizeof(double));
	R->B = R->B < 1 ? 1 : R->B > maxrows ? maxrows : R->B;
	R->ncol = w;
	R->coff = malloc(w * sizeof *R->coff);
	R->cw = malloc(w * sizeof *R->cw);
	R->buf = malloc(R->B * w * sizeof *R->buf);
	if (!R->coff || !R->cw || !R->buf) return -1;
	return rows_layout(R);
}

static void rows_free(h5rows *R)
{
	for (size_t d = 0; d < R->nvar; d++) {
		if (R->var[d].ds > 0) H5Dclose(R->var[d].ds);
		free(R->var[d].name);
		free(R->var[d].unit);
		free(R->var[d].col);
	}
	for (size_t s = 0; s < R->nscale; s++) {
		for (uint32_t j = 0; j < R->scale[s].n; j++) free(R->scale[s].obj[j]);
		free(R->scale[s].obj);
		free(R->scale[s].name);
	}
	free(R->var);
	free(R->scale);
	free(R->coff);
	free(R->cw);
	free(R->buf);
}

/*
 * Dataset x's rank and the shape of n of its rows: (n,), (n, 3), (n, objects) or (n, objects, 3);
 * in a sweep's file, of nv variants: (nv, n, ...).
 */
static int shape(const h5rows *R, const h5var *x, hsize_t nv, hsize_t n, hsize_t *dims)
{
	int rank = 0;
	if (R->lead) dims[rank++] = nv;
	dims[rank++] = n;
	if (x->col) dims[rank++] = x->n;
	if (x->width > 1) dims[rank++] = x->width;
	return rank;
}

/*
 * The hyperslab of rows [r0, r0 + n) of dataset x (in a sweep's file, of variants [v0, v0 + nv)):
 * its file space (*fs) and a memory space of its shape; -1 on failure.
 */
static int slab(const h5rows *R, const h5var *x, hsize_t v0, hsize_t nv, hsize_t r0, hsize_t n, hid_t *fs, hid_t *ms)
{
	hsize_t start[4] = { R->lead ? v0 : r0, R->lead ? r0 : 0, 0, 0 }, count[4];
	int rank = shape(R, x, nv, n, count);
	*ms = -1;
	*fs = H5Dget_space(x->ds);
	if (*fs < 0 || H5Sselect_hyperslab(*fs, H5S_SELECT_SET, start, NULL, count, NULL) < 0) return -1;
	*ms = H5Screate_simple(rank, count, NULL);
	return *ms < 0 ? -1 : 0;
}

static void close_spaces(hid_t fs, hid_t ms)
{
	if (fs >= 0) H5Sclose(fs);
	if (ms >= 0) H5Sclose(ms);
}

/*
 * HDF5's words for its last failure: the innermost entry of its error stack
 * (where the failure was found), kept by the library's automatic error
 * report (H5Eset_auto2), which runs as the failed call returns, before
 * the next call clears the stack. The only state of this file outside a
 * csf_h5; one process writes or reads one file at a time.
 */
static char h5_failure[128];

static herr_t innermost(unsigned n, const H5E_error2_t *e, void *data)
{
	(void)data;
	if (n == 0 && e->desc && *e->desc) snprintf(h5_failure, sizeof h5_failure, "HDF5: %s", e->desc);
	return 0;
}

static herr_t keep_failure(hid_t stack, void *data)
{
	(void)data;
	H5Ewalk2(stack, H5E_WALK_UPWARD, innermost, NULL);
	return 0;
}

/*
 * Reports HDF5's failures to keep_failure alone, from none yet. And no
 * clean-up of the library at exit: after a file's close failed (a write
 * error), HDF5 1.10's would close it again and crash; the file is closed
 * here on every path, and the system frees the rest.
 */
static void h5_quiet(void)
{
	H5dont_atexit();
	H5Eset_auto2(H5E_DEFAULT, keep_failure, NULL);
	snprintf(h5_failure, sizeof h5_failure, "HDF5 failed");
}

/* Why the last call failed: the system's error e, or else HDF5's words. */
static const char *h5_why(int e) { return e ? strerror(e) : h5_failure; }

/* ---- writing ---- */

/* A column's name and unit: "NAME [UNIT]", or NAME alone (unit ""). */
static void split_col(const char *col, size_t *namelen, const char **unit, size_t *unitlen)
{
	size_t n = strlen(col);
	const char *b = n && col[n - 1] == ']' ? strstr(col, " [") : NULL;
	*namelen = b ? (size_t)(b - col) : n;
	*unit = b ? b + 2 : "";
	*unitlen = b ? (size_t)(col + n - 1 - *unit) : 0;
}

/*
 * Is column i NAME.c [UNIT] with c = 'x' + k, a vector's component? NAME is OBJECT.PROP (a dot
 * in it), or a vector global: OBJECT.x is the object's scalar property x. Its unit into *u.
 */
static int component(const csf_prog *p, uint32_t i, int k, size_t *nl, const char **u, size_t *ul)
{
	const char *c = csf_str(p, p->cols[i].name);
	split_col(c, nl, u, ul);
	if (*nl < 3 || c[*nl - 2] != '.' || c[*nl - 1] != 'x' + k) return 0;
	if (memchr(c, '.', *nl - 2)) return 1;
	for (uint32_t g = 0; g < p->nglobals; g++)
		if (p->globals[g].width == 3 && strlen(csf_str(p, p->globals[g].name)) == *nl - 2 &&
		    !strncmp(csf_str(p, p->globals[g].name), c, *nl - 2))
			return 1;
	return 0;
}

/* The width of the dataset whose first column is column i: 3 when columns i..i+2 are one vector's x, y, z. */
static uint32_t width_at(const csf_prog *p, uint32_t i)
{
	size_t nl[3], ul[3];
	const char *u[3];
	if (i + 3 > p->ncols) return 1;
	for (int k = 0; k < 3; k++)
		if (!component(p, i + (uint32_t)k, k, &nl[k], &u[k], &ul[k])) return 1;
	const char *a = csf_str(p, p->cols[i].name);
	for (int k = 1; k < 3; k++) {
		const char *b = csf_str(p, p->cols[i + (uint32_t)k].name);
		if (nl[k] != nl[0] || strncmp(a, b, nl[0] - 1) || ul[k] != ul[0] || strncmp(u[0], u[k], ul[0])) return 1;
	}
	return 3;
}

static char *strndup_or_null(const char *s, size_t n)
{
	char *d = malloc(n + 1);
	if (d) memcpy(d, s, n), d[n] = '\0';
	return d;
}

/*
 * A watched value as plan() finds it: NAME [UNIT] at column col (t: 0), width 1 or 3; NAME is
 * OBJECT.PROP with the dot at obj, or a global (obj 0); def: OBJECT's place in the definition
 * order. A property's dataset's first object (lead), or another of its objects (in: 1), or a
 * dataset of its own (neither).
 */
typedef struct pval {
	const char *name, *unit;
	size_t nl, ul, obj;
	uint32_t col, width, def;
	struct pval *lead;
	int in;
} pval;

static int cmp_str(const char *a, size_t na, const char *b, size_t nb)
{
	int c = memcmp(a, b, na < nb ? na : nb);
	return c ? c : (na > nb) - (na < nb);
}

/* The property, width and unit of a and b: which is first (0: the same). */
static int cmp_prop(const pval *a, const pval *b)
{
	int c = cmp_str(a->name + a->obj + 1, a->nl - a->obj - 1, b->name + b->obj + 1, b->nl - b->obj - 1);
	if (!c) c = (a->width > b->width) - (a->width < b->width);
	return c ? c : cmp_str(a->unit, a->ul, b->unit, b->ul);
}

static int cmp_obj(const pval *a, const pval *b) { return cmp_str(a->name, a->obj, b->name, b->obj); }

/* By property, width, unit, object, column. */
static int by_prop(const void *pa, const void *pb)
{
	const pval *a = *(pval *const *)pa, *b = *(pval *const *)pb;
	int c = cmp_prop(a, b);
	if (!c) c = cmp_obj(a, b);
	return c ? c : (a->col > b->col) - (a->col < b->col);
}

/* By the objects' definition order, then column. */
static int by_def(const void *pa, const void *pb)
{
	const pval *a = *(pval *const *)pa, *b = *(pval *const *)pb;
	return a->def != b->def ? (a->def > b->def) - (a->def < b->def) : (a->col > b->col) - (a->col < b->col);
}

/* An object's name and its place in the definition order. */
typedef struct defobj {
	const char *name;
	uint32_t def;
} defobj;

static int by_name(const void *pa, const void *pb) { return strcmp(((const defobj *)pa)->name, ((const defobj *)pb)->name); }

/* Each value's object's place in p's definition order (past the objects when p has not its name). -1 when memory runs out. */
static int definition_order(const csf_prog *p, pval *v, size_t nv)
{
	defobj *o = malloc(((size_t)p->nobjects + 1) * sizeof *o);
	if (!o) return -1;
	for (uint32_t i = 0; i < p->nobjects; i++) o[i] = (defobj){ csf_str(p, p->objects[i]), i };
	qsort(o, p->nobjects, sizeof *o, by_name);
	for (size_t i = 0; i < nv; i++) {
		size_t lo = 0, hi = p->nobjects;
		while (lo < hi) { /* the first name not before v[i]'s object */
			size_t mid = lo + (hi - lo) / 2;
			if (cmp_str(o[mid].name, strlen(o[mid].name), v[i].name, v[i].obj) < 0) lo = mid + 1;
			else hi = mid;
		}
		int found = v[i].obj && lo < p->nobjects && !cmp_str(o[lo].name, strlen(o[lo].name), v[i].name, v[i].obj);
		v[i].def = found ? o[lo].def : p->nobjects;
	}
	free(o);
	return 0;
}

/*
 * The properties watched for more than one object: each object's first value of the property
 * (one width, one unit) in the property's dataset, lead the first in the CSV; the others keep a
 * dataset of their own. 0, or -1 when memory runs out.
 */
static int group(pval *v, size_t nv)
{
	pval **s = malloc((nv ? nv : 1) * sizeof *s), **e = malloc((nv ? nv : 1) * sizeof *e);
	size_t ns = 0;
	if (!s || !e) return free(s), free(e), -1;
	for (size_t i = 0; i < nv; i++)
		if (v[i].obj) s[ns++] = &v[i];
	qsort(s, ns, sizeof *s, by_prop);
	for (size_t i = 0, j; i < ns; i = j) {
		size_t ne = 0;
		for (j = i; j < ns && !cmp_prop(s[i], s[j]); j++)
			if (j == i || cmp_obj(s[j - 1], s[j])) e[ne++] = s[j]; /* an object's first column */
		if (ne < 2) continue;
		pval *lead = e[0];
		for (size_t k = 1; k < ne; k++)
			if (e[k]->col < lead->col) lead = e[k];
		for (size_t k = 0; k < ne; k++) e[k]->lead = lead, e[k]->in = e[k] != lead;
	}
	free(s);
	free(e);
	return 0;
}

/* The dimension scale of x's objects: one of R's with their names, else a new one; -1 when memory runs out. */
static int objects_scale(h5rows *R, h5var *x, pval *const *e)
{
	size_t s = 0;
	for (; s < R->nscale; s++) {
		uint32_t j = 0;
		if (R->scale[s].n != x->n) continue;
		while (j < x->n && !cmp_str(R->scale[s].obj[j], strlen(R->scale[s].obj[j]), e[j]->name, e[j]->obj)) j++;
		if (j == x->n) break;
	}
	x->scale = s;
	if (s < R->nscale) return 0;
	h5objs *o = &R->scale[R->nscale++];
	size_t nn = strlen(x->name) + 9;
	if (!(o->name = malloc(nn)) || !(o->obj = calloc(x->n, sizeof *o->obj))) return -1;
	snprintf(o->name, nn, s ? "objects_%s" : "objects", x->name);
	for (; o->n < x->n; o->n++)
		if (!(o->obj[o->n] = strndup_or_null(e[o->n]->name, e[o->n]->obj))) return -1;
	return 0;
}

/* The datasets of p's columns: t, then one per property watched for several objects, scalar or vector. -1 when memory runs out. */
static int plan(const csf_prog *p, h5rows *R)
{
	pval *v = calloc((size_t)p->ncols + 1, sizeof *v), **e = malloc(((size_t)p->ncols + 1) * sizeof *e);
	size_t nv = 0;
	R->var = calloc((size_t)p->ncols + 1, sizeof *R->var);
	R->scale = calloc((size_t)p->ncols + 1, sizeof *R->scale);
	if (!v || !e || !R->var || !R->scale) return free(v), free(e), -1;
	for (uint32_t i = 0; i < p->ncols; i += v[nv++].width) {
		pval *x = &v[nv];
		const char *dot;
		x->col = i + 1;
		x->width = width_at(p, i);
		x->name = csf_str(p, p->cols[i].name);
		split_col(x->name, &x->nl, &x->unit, &x->ul);
		if (x->width > 1) x->nl -= 2; /* NAME of NAME.x */
		dot = memchr(x->name, '.', x->nl);
		x->obj = dot ? (size_t)(dot - x->name) : 0;
	}
	int bad = definition_order(p, v, nv) || group(v, nv) || !(R->var[R->nvar++] = (h5var){ .name = strndup_or_null("t", 1),
	                                                          .unit = strndup_or_null("s", 1), .width = 1, .n = 1 }).name;
	for (size_t i = 0; i < nv && !bad; i++) {
		h5var *x = &R->var[R->nvar];
		if (v[i].in) continue;
		R->nvar++;
		x->width = v[i].width;
		x->unit = strndup_or_null(v[i].unit, v[i].ul);
		if (!v[i].lead) {
			x->n = 1;
			x->name = strndup_or_null(v[i].name, v[i].nl);
			bad = !x->name || !x->unit;
			continue;
		}
		x->name = strndup_or_null(v[i].name + v[i].obj + 1, v[i].nl - v[i].obj - 1); /* PROP */
		for (size_t k = i; k < nv; k++)
			if (v[k].lead == &v[i]) e[x->n++] = &v[k];
		qsort(e, x->n, sizeof *e, by_def); /* the objects in their definition order */
		bad = !x->name || !x->unit || !(x->col = malloc(x->n * sizeof *x->col)) || objects_scale(R, x, e);
		for (uint32_t j = 0; !bad && j < x->n; j++) x->col[j] = e[j]->col;
	}
	free(v);
	free(e);
	if (bad) return -1;
	/*
	 * At most till/by + 2 rows (k*by <= till, and one for till/by's rounding): the datasets'
	 * limit, a fixed one, that readers see as a dimension of fixed size (h5netcdf sizes an
	 * unlimited one from every dataset attached to its scale, for each dataset: time quadratic
	 * in the datasets); past MAX_FIXED rows, none. A short run's rows in one chunk.
	 */
	double rows = floor(p->till / p->by) + 2;
	R->max = rows <= MAX_FIXED ? (hsize_t)rows : H5S_UNLIMITED;
	if (rows_alloc(R, rows < BLOCK_ROWS ? (size_t)rows : BLOCK_ROWS, (size_t)p->ncols + 1)) return -1;
	R->chunk = R->B;
	return 0;
}

/* Attribute name of loc: n strings (scalar: n < 0, one string), UTF-8. */
static int attr_strs(hid_t loc, const char *name, const char *const *s, long n)
{
	hsize_t dim = n < 0 ? 1 : (hsize_t)n;
	hid_t t = H5Tcopy(H5T_C_S1), sp = n < 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL), a = -1;
	int bad = t < 0 || sp < 0 || H5Tset_size(t, H5T_VARIABLE) < 0 || H5Tset_cset(t, H5T_CSET_UTF8) < 0 ||
	          (a = H5Acreate2(loc, name, t, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 || (dim && H5Awrite(a, t, s) < 0);
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	if (t >= 0) H5Tclose(t);
	return bad ? -1 : 0;
}

static int attr_str(hid_t loc, const char *name, const char *s) { return attr_strs(loc, name, &s, -1); }

static int attr_double(hid_t loc, const char *name, double x)
{
	hid_t sp = H5Screate(H5S_SCALAR), a = -1;
	int bad = sp < 0 || (a = H5Acreate2(loc, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
	          H5Awrite(a, H5T_NATIVE_DOUBLE, &x) < 0;
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	return bad ? -1 : 0;
}

/*
 * The root's attributes: what ran, and the CSV header's fields; a sweep's (npar > 0) header
 * begins with its swept parameters' heads, and the attribute swept names their datasets.
 */
static int root_attrs(hid_t f, const csf_prog *p, const csf_opts *o, const char *model, int argc, char **argv, int npar,
                      const char *const *heads, const char *const *names)
{
	size_t np = (size_t)npar;
	const char **cols = malloc((np + p->ncols + 1) * sizeof *cols);
	char *cl = csf_command_line(argc, argv);
	int bad = !cols || !cl;
	if (!bad) {
		for (size_t k = 0; k < np; k++) cols[k] = heads[k];
		cols[np] = "t";
		for (uint32_t i = 0; i < p->ncols; i++) cols[np + i + 1] = csf_str(p, p->cols[i].name);
		const char *m = o->method ? o->method : "auto";
		bad = attr_str(f, "model", model) || attr_str(f, "method", m) ||
		      attr_double(f, "tolerance", o->tol > 0 ? o->tol : csf_method_tol(strcmp(m, "auto") ? m : NULL)) ||
		      attr_strs(f, "defines", o->defs, o->ndefs) || attr_str(f, "command_line", cl) ||
		      attr_str(f, "csf_version", CSF_VERSION_STRING) || attr_double(f, "till", p->till) ||
		      attr_double(f, "by", p->by) || attr_strs(f, "columns", cols, (long)(np + p->ncols + 1)) ||
		      (npar && attr_strs(f, "swept", names, npar));
	}
	free(cols);
	free(cl);
	return bad ? -1 : 0;
}

/* A fixed-length, NUL-terminated ASCII string attribute, as a dimension scale's CLASS and NAME are. */
static int attr_fixed(hid_t loc, const char *name, const char *s)
{
	hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR), a = -1;
	int bad = t < 0 || sp < 0 || H5Tset_size(t, strlen(s) + 1) < 0 ||
	          (a = H5Acreate2(loc, name, t, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 || H5Awrite(a, t, s) < 0;
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	if (t >= 0) H5Tclose(t);
	return bad ? -1 : 0;
}

/* Makes dataset ds the dimension scale name (as H5DSset_scale does). */
static int set_scale(hid_t ds, const char *name)
{
	return attr_fixed(ds, "CLASS", "DIMENSION_SCALE") || attr_fixed(ds, "NAME", name) ? -1 : 0;
}

/*
 * The datasets each scale is attached to, and the axis (the dimension
 * scales' REFERENCE_LIST: the compound H5DSattach_scale writes). Written once
 * for all: H5DSattach_scale rewrites the whole list at each attachment,
 * which takes time quadratic in the datasets.
 */
typedef struct dsref { hobj_ref_t ds; int dim; } dsref;

static int reference_list(hid_t scale, const dsref *r, size_t n)
{
	hsize_t dim = n;
	hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(dsref)), sp = H5Screate_simple(1, &dim, NULL), a = -1;
	int bad = t < 0 || sp < 0 || H5Tinsert(t, "dataset", HOFFSET(dsref, ds), H5T_STD_REF_OBJ) < 0 ||
	          H5Tinsert(t, "dimension", HOFFSET(dsref, dim), H5T_NATIVE_INT) < 0 ||
	          (a = H5Acreate2(scale, "REFERENCE_LIST", t, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 || H5Awrite(a, t, r) < 0;
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	if (t >= 0) H5Tclose(t);
	return bad ? -1 : 0;
}

/* The scales of dataset ds's axes, one each (its DIMENSION_LIST, as H5DSattach_scale makes it). */
static int dimension_list(hid_t ds, hid_t vlen, hobj_ref_t *scales, int rank)
{
	hsize_t dim = (hsize_t)rank;
	hvl_t l[4] = { { 1, &scales[0] }, { 1, &scales[1] }, { 1, &scales[2] }, { 1, &scales[3] } };
	hid_t sp = H5Screate_simple(1, &dim, NULL), a = -1;
	int bad = sp < 0 || (a = H5Acreate2(ds, "DIMENSION_LIST", vlen, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
	          H5Awrite(a, vlen, l) < 0;
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	return bad ? -1 : 0;
}

/* *name, or if taken, *name followed by " (2)", " (3)", ... (*name becomes the one not taken). */
static int name_not_taken(hid_t f, char **name)
{
	char *base = *name;
	for (int k = 2; H5Lexists(f, *name, H5P_DEFAULT) > 0; k++) {
		size_t n = strlen(base) + 24;
		char *alt = malloc(n);
		if (!alt) return -1;
		snprintf(alt, n, "%s (%d)", base, k);
		if (*name != base) free(*name);
		*name = alt;
	}
	if (*name != base) free(base);
	return 0;
}

/* The dimension scale name: n strings (open; -1 on failure). */
static hid_t string_scale(hid_t f, const char *name, const char *const *s, hsize_t n)
{
	hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate_simple(1, &n, NULL), dcpl = H5Pcreate(H5P_DATASET_CREATE), ds = -1;
	int bad = t < 0 || sp < 0 || dcpl < 0 || H5Pset_obj_track_times(dcpl, 0) < 0 || H5Tset_size(t, H5T_VARIABLE) < 0 ||
	          H5Tset_cset(t, H5T_CSET_UTF8) < 0 ||
	          (ds = H5Dcreate2(f, name, t, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT)) < 0 ||
	          H5Dwrite(ds, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, s) < 0 || set_scale(ds, name);
	if (dcpl >= 0) H5Pclose(dcpl);
	if (sp >= 0) H5Sclose(sp);
	if (t >= 0) H5Tclose(t);
	if (bad && ds >= 0) H5Dclose(ds), ds = -1;
	return ds;
}

/* The dimension scale xyz: the strings "x", "y", "z" (open; -1 on failure). */
static hid_t xyz_scale(hid_t f)
{
	static const char *const xyz[3] = { "x", "y", "z" };
	return string_scale(f, "xyz", xyz, 3);
}

/* The attribute columns of a property's dataset x: each object's first column in the CSV. */
static int attr_cols(const h5var *x)
{
	hsize_t n = x->n;
	hid_t sp = H5Screate_simple(1, &n, NULL), a = -1;
	int bad = sp < 0 || (a = H5Acreate2(x->ds, "columns", H5T_STD_U32LE, sp, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
	          H5Awrite(a, H5T_NATIVE_UINT32, x->col) < 0;
	if (a >= 0) H5Aclose(a);
	if (sp >= 0) H5Sclose(sp);
	return bad ? -1 : 0;
}

/*
 * Creates dataset x (rows,), (rows, 3), (rows, n) or (rows, n, 3) (a sweep's: (variants, rows,
 * ...)), chunks of R->chunk rows (and R->cv variants) and of as many objects as fit CHUNK_BYTES,
 * under a name not taken (x->name becomes it).
 */
static int create_var(hid_t f, h5var *x, const h5rows *R, hid_t dcpl, hid_t dapl)
{
	hsize_t dims[4], maxd[4], chunk[4];
	int rank = shape(R, x, R->nvariants, 0, dims);
	shape(R, x, R->nvariants, R->max, maxd);
	shape(R, x, R->cv, R->chunk, chunk);
	if (x->col) {
		hsize_t per = CHUNK_BYTES / ((R->lead ? R->cv : 1) * R->chunk * x->width * sizeof(double));
		chunk[1 + R->lead] = per < 1 ? 1 : per < x->n ? per : x->n;
	}
	if (name_not_taken(f, &x->name)) return -1;
	hid_t sp = H5Screate_simple(rank, dims, maxd);
	if (sp < 0 || H5Pset_chunk(dcpl, rank, chunk) < 0) return -1;
	x->ds = H5Dcreate2(f, x->name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, dcpl, dapl);
	H5Sclose(sp);
	return x->ds < 0 ? -1 : 0;
}

/*
 * The scales of a file's leading axes (n of them) and what else is attached to them: a run's is
 * t, its dataset var[0], made a scale by create_vars; a sweep's are variant and row, made
 * before, with datasets on variant beside the watched ones (extra: the swept values, rows and
 * status), and coords, the attribute coordinates of every watched dataset ("t NAME ...", t's
 * own without "t ").
 */
typedef struct h5lead {
	int n;
	hid_t scale[2];
	hobj_ref_t ref[2];
	const dsref *extra;
	size_t nextra;
	const char *coords;
} h5lead;

/* The datasets, their units, and the dimension scales of L, objects and xyz attached to their axes. */
static int create_vars(hid_t f, h5rows *R, h5lead *L)
{
	static const double nan = NAN;
	hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE), dapl = H5Pcreate(H5P_DATASET_ACCESS), xyz = -1;
	hid_t vlen = H5Tvlen_create(H5T_STD_REF_OBJ), *os = calloc(R->nscale + 1, sizeof *os);
	size_t first = R->lead ? 0 : 1, nt = L->nextra, nx = 0, nr = 0; /* the watched datasets: var[first ...] */
	dsref *rt = malloc((nt + R->nvar) * sizeof *rt), *rx = malloc(R->nvar * sizeof *rx), *ro = malloc(R->nvar * sizeof *ro);
	hobj_ref_t sx = 0, *so = calloc(R->nscale + 1, sizeof *so); /* the scales xyz, objects */
	int vectors = 0;
	for (size_t d = 0; d < R->nvar; d++) vectors |= R->var[d].width > 1;
	/*
	 * no times in the objects (a file is the same bytes every time); whole chunks are written,
	 * uncached; a sweep's are NaN where no variant's rows are
	 */
	int bad = !os || !rt || !rx || !ro || !so || dcpl < 0 || dapl < 0 || vlen < 0 ||
	          H5Pset_obj_track_times(dcpl, 0) < 0 ||
	          (R->lead ? H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &nan) < 0
	                   : H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER) < 0) ||
	          H5Pset_chunk_cache(dapl, 0, 0, 1) < 0;
	if (!bad && !R->lead) {
		bad = create_var(f, &R->var[0], R, dcpl, dapl) || set_scale(R->var[0].ds, "t") ||
		      attr_str(R->var[0].ds, "unit", R->var[0].unit) || H5Rcreate(&L->ref[0], f, "t", H5R_OBJECT, -1) < 0;
		L->scale[0] = R->var[0].ds;
	}
	bad = bad || (vectors && ((xyz = xyz_scale(f)) < 0 || H5Rcreate(&sx, f, "xyz", H5R_OBJECT, -1) < 0));
	for (size_t s = 0; s < R->nscale && !bad; s++) {
		h5objs *o = &R->scale[s];
		bad = name_not_taken(f, &o->name) || (os[s] = string_scale(f, o->name, (const char *const *)o->obj, o->n)) < 0 ||
		      H5Rcreate(&so[s], f, o->name, H5R_OBJECT, -1) < 0;
	}
	if (!bad && nt) memcpy(rt, L->extra, nt * sizeof *rt);
	for (size_t d = first; d < R->nvar && !bad; d++) {
		h5var *x = &R->var[d];
		hobj_ref_t sc[4];
		int rank = 0;
		for (int a = 0; a < L->n; a++) sc[rank++] = L->ref[a];
		if (x->col) sc[rank++] = so[x->scale];
		if (x->width > 1) sc[rank++] = sx;
		bad = create_var(f, x, R, dcpl, dapl) || attr_str(x->ds, "unit", x->unit) || (x->col && attr_cols(x)) ||
		      (L->coords && attr_str(x->ds, "coordinates", d ? L->coords : L->coords + 2)) ||
		      dimension_list(x->ds, vlen, sc, rank) || H5Rcreate(&rt[nt].ds, f, x->name, H5R_OBJECT, -1) < 0;
		rt[nt++].dim = 0;
		if (x->width > 1) rx[nx++] = (dsref){ rt[nt - 1].ds, rank - 1 };
	}
	bad = bad || (nt && reference_list(L->scale[0], rt, nt)) || (nx && reference_list(xyz, rx, nx));
	/* a sweep's row: the watched datasets' axis 1 */
	for (size_t d = first; L->n > 1 && d < R->nvar; d++) ro[nr++] = (dsref){ rt[L->nextra + d - first].ds, 1 };
	bad = bad || (nr && reference_list(L->scale[1], ro, nr));
	/* each scale of objects: the datasets of its objects, their axis after the leading ones */
	for (size_t s = 0; s < R->nscale && !bad; s++) {
		size_t no = 0;
		for (size_t d = first; d < R->nvar; d++)
			if (R->var[d].col && R->var[d].scale == s) ro[no++] = (dsref){ rt[L->nextra + d - first].ds, L->n };
		bad = reference_list(os[s], ro, no);
	}
	for (size_t s = 0; os && s < R->nscale; s++)
		if (os[s] > 0) H5Dclose(os[s]);
	free(os);
	free(so);
	free(rt);
	free(rx);
	free(ro);
	if (xyz >= 0) H5Dclose(xyz);
	if (vlen >= 0) H5Tclose(vlen);
	if (dapl >= 0) H5Pclose(dapl);
	if (dcpl >= 0) H5Pclose(dcpl);
	return bad ? -1 : 0;
}

/* Closes h's datasets and frees what it holds (but h and its file). */
static void h5_release(csf_h5 *h)
{
	h5block *S = &h->S;
	rows_free(&h->R);
	for (int k = 0; S->par && k < S->npar; k++)
		if (S->par[k] > 0) H5Dclose(S->par[k]);
	hid_t ds[4] = { S->variant, S->rows, S->status, S->row };
	for (int k = 0; k < 4; k++)
		if (ds[k] > 0) H5Dclose(ds[k]);
	free(S->par);
	free(S->val);
	free(S->st);
	free(S->nrows);
	free(S->num);
	free(S->held);
}

/* A new HDF5 file at path, for h (NULL with the reason in err when it cannot be made). */
static csf_h5 *file_new(const char *path, char *err, size_t errlen)
{
	h5_quiet(); /* the failures are ours to report */
	csf_h5 *h = calloc(1, sizeof *h);
	hid_t fcpl = H5Pcreate(H5P_FILE_CREATE), fapl = H5Pcreate(H5P_FILE_ACCESS);
	if (!h || fcpl < 0 || fapl < 0) {
		snprintf(err, errlen, "out of memory");
		free(h);
		return NULL;
	}
	/* the datasets in creation order: the columns' (--dump), as netCDF-4 keeps them */
	H5Pset_link_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
	/* no times in the root group either: a file is the same bytes whenever it is written */
	H5Pset_obj_track_times(fcpl, 0);
	/*
	 * HDF5 1.8's format: attributes of any size (columns, t's list of the datasets it scales).
	 * Not 1.10's: its files stay marked open after a process that was killed writing them, and
	 * no reader opens them then (but after h5clear -s); its index of chunks takes 3/4 of the
	 * memory and time for 10000 datasets.
	 */
	H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V18);
	errno = 0;
	h->file = H5Fcreate(path, H5F_ACC_TRUNC, fcpl, fapl);
	int e = errno;
	H5Pclose(fcpl);
	H5Pclose(fapl);
	if (h->file < 0) {
		snprintf(err, errlen, "cannot create %s: %s", path, h5_why(e));
		free(h);
		return NULL;
	}
	return h;
}

/* h, or NULL after closing it, with why its file at path cannot be written in err (errno's, or HDF5's). */
static csf_h5 *written(csf_h5 *h, int bad, const char *path, char *err, size_t errlen)
{
	if (!bad) return h;
	int e = errno;
	snprintf(err, errlen, "cannot write %s: %s", path, h5_why(e));
	h5_release(h);
	H5Fclose(h->file);
	free(h);
	return NULL;
}

csf_h5 *csf_h5_create(const char *path, const csf_prog *p, const csf_opts *o, const char *model, int argc, char **argv,
                      char *err, size_t errlen)
{
	csf_h5 *h = file_new(path, err, errlen);
	if (!h) return NULL;
	h5lead L = { .n = 1 };
	errno = 0;
	return written(h,
	               plan(p, &h->R) || root_attrs(h->file, p, o, model, argc, argv, 0, NULL, NULL) ||
	                       create_vars(h->file, &h->R, &L) || H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0,
	               path, err, errlen);
}

/* Writes the rows in the buffer to the end of every dataset and flushes the file. 0, or -1 (errno set). */
static int flush_rows(csf_h5 *h)
{
	if (h->werr) return errno = h->werr, -1;
	if (!h->nb) return 0;
	int bad = 0;
	errno = 0;
	csf_out_begin(); /* the watchdog of a signal waits for a whole block */
	for (size_t d = 0; d < h->R.nvar && !bad; d++) {
		h5var *x = &h->R.var[d];
		hsize_t dims[4];
		hid_t fs = -1, ms = -1;
		shape(&h->R, x, 0, h->rows + h->nb, dims);
		bad = H5Dset_extent(x->ds, dims) < 0 || slab(&h->R, x, 0, 0, h->rows, h->nb, &fs, &ms) ||
		      H5Dwrite(x->ds, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, h->R.buf + x->off) < 0;
		close_spaces(fs, ms);
	}
	bad = bad || H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0;
	csf_out_end();
	if (bad) {
		h->werr = errno ? errno : EIO;
		errno = h->werr;
		return -1;
	}
	h->rows += h->nb;
	h->nb = 0;
	return 0;
}

int csf_h5_row(void *ctx, const double *v, size_t n)
{
	csf_h5 *h = ctx;
	h5rows *R = &h->R;
	for (size_t c = 0; c < n && c < R->ncol; c++) R->buf[R->coff[c] + h->nb * R->cw[c]] = v[c];
	return ++h->nb == R->B ? flush_rows(h) : 0;
}

/* ---- a sweep's ---- */

/*
 * The variants of a chunk and of a block (and their buffers): as many as fit BLOCK_BYTES at the
 * most rows a run has (one when that has no bound), and a vector's chunk CHUNK_BYTES; at most
 * every variant. -1 when memory runs out.
 */
static int sweep_plan(h5rows *R, h5block *S)
{
	hsize_t most = R->max == H5S_UNLIMITED ? 0 : R->max;
	hsize_t cv = most ? BLOCK_BYTES / (most * R->ncol * sizeof(double)) : 1, chunk = CHUNK_BYTES / (R->chunk * 3 * sizeof(double));
	cv = cv < chunk ? cv : chunk;
	cv = cv < R->nvariants ? cv : R->nvariants;
	R->cv = cv < 1 ? 1 : cv;
	S->par = calloc((size_t)S->npar + 1, sizeof *S->par);
	S->val = malloc(((size_t)S->npar + 1) * R->cv * sizeof *S->val);
	S->st = malloc(R->cv * sizeof *S->st);
	S->nrows = malloc(R->cv * sizeof *S->nrows);
	S->num = malloc(R->cv * sizeof *S->num);
	S->cap = R->B * R->ncol;
	return S->par && S->val && S->st && S->nrows && S->num ? 0 : -1;
}

/*
 * The 1-D dataset *name of n values of type t (at most max, in chunks of chunk; a name not taken:
 * *name becomes it), *fill (of memory type mt) where none is written; open, or -1.
 */
static hid_t create_1d(hid_t f, char **name, hid_t t, hsize_t n, hsize_t max, hsize_t chunk, hid_t mt, const void *fill)
{
	hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE), sp = H5Screate_simple(1, &n, &max), ds = -1;
	if (dcpl >= 0 && sp >= 0 && !name_not_taken(f, name) && H5Pset_obj_track_times(dcpl, 0) >= 0 &&
	    H5Pset_chunk(dcpl, 1, &chunk) >= 0 && H5Pset_fill_value(dcpl, mt, fill) >= 0)
		ds = H5Dcreate2(f, *name, t, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
	if (sp >= 0) H5Sclose(sp);
	if (dcpl >= 0) H5Pclose(dcpl);
	return ds;
}

/*
 * A sweep's datasets, in creation order: the swept values (named as names), variant, rows,
 * status, row, then a run's (create_vars), on the axes variant and row.
 */
static int create_sweep(hid_t f, csf_h5 *h, char *const *names)
{
	static const double nan = NAN;
	static const long long zero = 0, none = -1;
	h5rows *R = &h->R;
	h5block *S = &h->S;
	size_t np = (size_t)S->npar, cn = 2;
	char *dn[4] = { strndup_or_null("variant", 7), strndup_or_null("rows", 4), strndup_or_null("status", 6),
	                strndup_or_null("row", 3) };
	dsref *ex = malloc((np + 2) * sizeof *ex);
	hid_t vlen = H5Tvlen_create(H5T_STD_REF_OBJ);
	int bad = !ex || vlen < 0;
	for (size_t k = 0; k < np; k++) cn += strlen(names[k]) + 1;
	char *coords = malloc(cn);
	bad = bad || !coords;
	for (size_t k = 0; k < np && !bad; k++) {
		char *name = names[k];
		bad = (S->par[k] = create_1d(f, &name, H5T_IEEE_F64LE, R->nvariants, R->nvariants, R->cv, H5T_NATIVE_DOUBLE, &nan)) < 0;
		if (name != names[k]) free(name); /* (a name of a parameter is never taken) */
	}
	for (int k = 0; k < 4 && !bad; k++) bad = !dn[k];
	bad = bad || (S->variant = create_1d(f, &dn[0], H5T_STD_I64LE, R->nvariants, R->nvariants, R->cv, H5T_NATIVE_LLONG, &zero)) < 0 ||
	      (S->rows = create_1d(f, &dn[1], H5T_STD_I64LE, R->nvariants, R->nvariants, R->cv, H5T_NATIVE_LLONG, &zero)) < 0 ||
	      (S->status = create_1d(f, &dn[2], H5T_STD_I64LE, R->nvariants, R->nvariants, R->cv, H5T_NATIVE_LLONG, &none)) < 0 ||
	      (S->row = create_1d(f, &dn[3], H5T_STD_I64LE, 0, R->max, R->chunk, H5T_NATIVE_LLONG, &zero)) < 0 ||
	      set_scale(S->variant, dn[0]) || set_scale(S->row, dn[3]);
	h5lead L = { .n = 2, .scale = { S->variant, S->row }, .extra = ex, .nextra = np + 2, .coords = coords };
	bad = bad || H5Rcreate(&L.ref[0], f, dn[0], H5R_OBJECT, -1) < 0 || H5Rcreate(&L.ref[1], f, dn[3], H5R_OBJECT, -1) < 0;
	if (!bad) {
		char *c = coords + snprintf(coords, cn, "t");
		for (size_t k = 0; k < np; k++) c += sprintf(c, " %s", names[k]);
	}
	/* the swept values, rows and status: on variant */
	for (size_t k = 0; k < np + 2 && !bad; k++) {
		hid_t ds = k < np ? S->par[k] : k == np ? S->rows : S->status;
		ex[k].dim = 0;
		bad = H5Rcreate(&ex[k].ds, f, k < np ? names[k] : dn[k == np ? 1 : 2], H5R_OBJECT, -1) < 0 ||
		      dimension_list(ds, vlen, L.ref, 1) ||
		      (k < np ? attr_str(ds, "unit", names[np + k]) : attr_str(ds, "coordinates", coords + 2));
	}
	bad = bad || create_vars(f, R, &L);
	for (int k = 0; k < 4; k++) free(dn[k]);
	free(coords);
	free(ex);
	if (vlen >= 0) H5Tclose(vlen);
	return bad ? -1 : 0;
}

csf_h5 *csf_h5_sweep_create(const char *path, const csf_prog *p, const csf_opts *o, const char *model, int argc,
                            char **argv, size_t nvariants, int npar, const char *const *heads, char *err, size_t errlen)
{
	csf_h5 *h = file_new(path, err, errlen);
	if (!h) return NULL;
	size_t np = (size_t)npar;
	char **names = calloc(2 * np + 1, sizeof *names); /* each parameter's name, then its unit */
	int bad = !names;
	for (size_t k = 0; k < np && !bad; k++) {
		size_t nl, ul;
		const char *u;
		split_col(heads[k], &nl, &u, &ul);
		bad = !(names[k] = strndup_or_null(heads[k], nl)) || !(names[np + k] = strndup_or_null(u, ul));
	}
	h->R.lead = 1;
	h->R.nvariants = nvariants;
	h->S.npar = npar;
	errno = 0;
	bad = bad || plan(p, &h->R) || sweep_plan(&h->R, &h->S) ||
	      root_attrs(h->file, p, o, model, argc, argv, npar, heads, (const char *const *)names) ||
	      create_sweep(h->file, h, names) || H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0;
	for (size_t k = 0; names && k < 2 * np; k++) free(names[k]);
	free(names);
	return written(h, bad, path, err, errlen);
}

/* Values [v0, v0 + n) of the 1-D dataset ds, of memory type mt. */
static int write_1d(hid_t ds, hid_t mt, hsize_t v0, hsize_t n, const void *v)
{
	hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(1, &n, NULL);
	int bad = fs < 0 || ms < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, &v0, NULL, &n, NULL) < 0 ||
	          H5Dwrite(ds, mt, ms, fs, H5P_DEFAULT, v) < 0;
	close_spaces(fs, ms);
	return bad ? -1 : 0;
}

/* The row axis of every dataset grown to n rows, and row's numbers. */
static int grow_rows(csf_h5 *h, hsize_t n)
{
	h5rows *R = &h->R;
	long long *num = malloc((size_t)(n - h->rows) * sizeof *num);
	int bad = !num || H5Dset_extent(h->S.row, &n) < 0;
	for (hsize_t r = h->rows; !bad && r < n; r++) num[r - h->rows] = (long long)r;
	bad = bad || write_1d(h->S.row, H5T_NATIVE_LLONG, h->rows, n - h->rows, num);
	for (size_t d = 0; d < R->nvar && !bad; d++) {
		hsize_t dims[4];
		shape(R, &R->var[d], R->nvariants, n, dims);
		bad = H5Dset_extent(R->var[d].ds, dims) < 0;
	}
	free(num);
	if (!bad) h->rows = n;
	return bad ? -1 : 0;
}

/*
 * The block's rows into every dataset, NaN past a variant's rows (variant k's row r is the
 * buffer's row k * most + r, most the block's most rows), and its swept values, numbers, rows
 * and status.
 */
static int write_variants(csf_h5 *h)
{
	h5rows *R = &h->R;
	h5block *S = &h->S;
	hsize_t nv = h->nb, most = 0;
	for (hsize_t k = 0; k < nv; k++) most = (hsize_t)S->nrows[k] > most ? (hsize_t)S->nrows[k] : most;
	if (most > h->rows && grow_rows(h, most)) return -1;
	if (most) {
		size_t n = (size_t)(nv * most) * R->ncol;
		if (n > S->cap) {
			double *b = realloc(R->buf, n * sizeof *b);
			if (!b) return -1;
			R->buf = b, S->cap = n;
		}
		R->B = (size_t)(nv * most);
		if (rows_layout(R)) return -1;
		for (size_t k = 0; k < n; k++) R->buf[k] = NAN;
		const unsigned char *at = S->held;
		for (hsize_t k = 0; k < nv; k++)
			for (size_t r = 0; r < (size_t)S->nrows[k]; r++)
				for (size_t c = 0; c < R->ncol; c++, at += sizeof(double))
					memcpy(&R->buf[R->coff[c] + (k * most + r) * R->cw[c]], at, sizeof(double));
	}
	int bad = 0;
	for (size_t d = 0; d < R->nvar && most && !bad; d++) {
		h5var *x = &R->var[d];
		hid_t fs = -1, ms = -1;
		bad = slab(R, x, S->first, nv, 0, most, &fs, &ms) || H5Dwrite(x->ds, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, R->buf + x->off) < 0;
		close_spaces(fs, ms);
	}
	/* the swept values, each parameter's together (in val, past the block's) */
	for (int j = 0; j < S->npar && !bad; j++) {
		double *v = S->val + (size_t)S->npar * nv;
		for (hsize_t k = 0; k < nv; k++) v[k] = S->val[k * (size_t)S->npar + (size_t)j];
		bad = write_1d(S->par[j], H5T_NATIVE_DOUBLE, S->first, nv, v);
	}
	return bad || write_1d(S->variant, H5T_NATIVE_LLONG, S->first, nv, S->num) ||
	               write_1d(S->rows, H5T_NATIVE_LLONG, S->first, nv, S->nrows) ||
	               write_1d(S->status, H5T_NATIVE_LLONG, S->first, nv, S->st)
	           ? -1
	           : 0;
}

/* Writes the block of variants and flushes the file. 0, or -1 (errno set). */
static int flush_variants(csf_h5 *h)
{
	if (h->werr) return errno = h->werr, -1;
	if (!h->nb) return 0;
	errno = 0;
	csf_out_begin(); /* the watchdog of a signal waits for a whole block */
	int bad = write_variants(h) || H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0;
	csf_out_end();
	if (bad) {
		h->werr = errno ? errno : EIO;
		errno = h->werr;
		return -1;
	}
	h->S.first += h->nb;
	h->S.nheld = 0;
	h->nb = 0;
	return 0;
}

int csf_h5_sweep_variant(csf_h5 *h, size_t i, const double *par, int status, const void *rows, size_t nrows)
{
	h5rows *R = &h->R;
	h5block *S = &h->S;
	if (h->werr) return errno = h->werr, -1;
	if (i != S->first + h->nb || i >= R->nvariants) return errno = EINVAL, -1;
	size_t bytes = nrows * R->ncol * sizeof(double);
	if (S->nheld + bytes > S->hcap) {
		size_t cap = 2 * (S->nheld + bytes);
		unsigned char *b = realloc(S->held, cap);
		if (!b) return errno = ENOMEM, -1;
		S->held = b, S->hcap = cap;
	}
	if (bytes) memcpy(S->held + S->nheld, rows, bytes);
	S->nheld += bytes;
	memcpy(S->val + h->nb * (size_t)S->npar, par, (size_t)S->npar * sizeof *par);
	S->st[h->nb] = status;
	S->nrows[h->nb] = (long long)nrows;
	S->num[h->nb] = (long long)i + 1;
	return ++h->nb == R->cv || i + 1 == R->nvariants ? flush_variants(h) : 0;
}

int csf_h5_record(csf_h5 *h, const csf_record *rec)
{
	int bad = 0;
	for (int i = 0; i < rec->n && !bad; i++) {
		const csf_rfield *x = &rec->f[i];
		if (H5Aexists(h->file, x->name) > 0 && H5Adelete(h->file, x->name) < 0) return -1;
		bad = x->kind == CSF_RF_STR   ? attr_str(h->file, x->name, x->s)
		      : x->kind == CSF_RF_NUM ? attr_double(h->file, x->name, x->x)
		                              : attr_strs(h->file, x->name, x->v, x->nv);
	}
	return bad;
}

int csf_h5_close(csf_h5 *h)
{
	int seen = h->werr; /* the run saw that error (the row that failed) */
	int bad = (h->R.lead ? flush_variants(h) : flush_rows(h)) != 0;
	h5_release(h);
	errno = 0;
	bad |= H5Fclose(h->file) < 0;
	int e = h->werr ? h->werr : errno ? errno : EIO;
	free(h);
	if (!bad || seen) return 0;
	errno = e;
	return -1;
}

/* ---- reading (--dump) ---- */

/* The strings of attribute name of loc (a 1-D array of variable-length strings): *n of them, or NULL. */
static char **read_strs(hid_t loc, const char *name, size_t *n)
{
	hid_t a = H5Aopen(loc, name, H5P_DEFAULT), sp = a < 0 ? -1 : H5Aget_space(a), t = a < 0 ? -1 : H5Aget_type(a);
	char **s = NULL;
	hssize_t np = sp < 0 ? -1 : H5Sget_simple_extent_npoints(sp);
	if (np > 0 && t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0 &&
	    (s = calloc((size_t)np, sizeof *s)) && H5Aread(a, t, s) < 0) {
		free(s);
		s = NULL;
	}
	*n = s ? (size_t)np : 0;
	if (t >= 0) H5Tclose(t);
	if (sp >= 0) H5Sclose(sp);
	if (a >= 0) H5Aclose(a);
	return s;
}

/*
 * The datasets of numbers in f, in creation order, into R (t first); each one's rows into *rows
 * (in a sweep's file, R->lead 1: (variants, rows, ...), the variants into R->nvariants). A
 * property's of n objects, (rows, n) or (rows, n, 3), has the attribute columns. -1 when not.
 */
static int find_vars(hid_t f, h5rows *R, hsize_t *rows, const char **why)
{
	H5G_info_t gi;
	int L = R->lead;
	*why = "not a file of csfvm -o FILE.h5";
	if (H5Gget_info(f, &gi) < 0 || !(R->var = calloc(gi.nlinks + 1, sizeof *R->var))) return -1;
	for (hsize_t i = 0; i < gi.nlinks; i++) {
		char name[1024];
		ssize_t n = H5Lget_name_by_idx(f, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
		hid_t ds = n > 0 && (size_t)n < sizeof name ? H5Dopen2(f, name, H5P_DEFAULT) : -1;
		if (ds < 0) continue;
		hid_t t = H5Dget_type(ds), sp = H5Dget_space(ds);
		hsize_t dims[4] = { 0, 0, 0, 0 };
		int rank = sp < 0 ? -1 : H5Sget_simple_extent_ndims(sp), objs = H5Aexists(ds, "columns") > 0;
		int num = t >= 0 && H5Tget_class(t) == H5T_FLOAT && rank >= 1 + L && rank <= 2 + objs + L &&
		          H5Sget_simple_extent_dims(sp, dims, NULL) == rank && (rank == 1 + objs + L || dims[rank - 1] == 3) &&
		          (!objs || (rank > 1 + L && dims[1 + L] > 0 && dims[1 + L] <= UINT32_MAX));
		if (t >= 0) H5Tclose(t);
		if (sp >= 0) H5Sclose(sp);
		if (!num) {
			H5Dclose(ds);
			continue;
		}
		h5var *x = &R->var[R->nvar++];
		x->ds = ds;
		x->width = rank > 1 + objs + L ? 3 : 1;
		x->n = objs ? (uint32_t)dims[1 + L] : 1;
		if (objs) {
			hid_t a = H5Aopen(ds, "columns", H5P_DEFAULT), as = a < 0 ? -1 : H5Aget_space(a);
			int ok = as >= 0 && H5Sget_simple_extent_npoints(as) == (hssize_t)x->n &&
			         (x->col = malloc(x->n * sizeof *x->col)) && H5Aread(a, H5T_NATIVE_UINT32, x->col) >= 0;
			if (as >= 0) H5Sclose(as);
			if (a >= 0) H5Aclose(a);
			if (!ok) return -1;
		}
		if (R->nvar == 1) *rows = dims[L], R->nvariants = L ? dims[0] : 0;
		if (dims[L] != *rows || (L && dims[0] != R->nvariants)) {
			*why = "its datasets have different numbers of rows";
			return -1;
		}
	}
	if (!R->nvar || R->var[0].width != 1 || R->var[0].col) return -1;
	return 0;
}

/* Rows [0, n) of R's datasets (a sweep's: of variant v), each after pre, as CSV on out. 0, or -1 when they cannot be read. */
static int dump_rows(h5rows *R, hsize_t v, hsize_t n, const char *pre, FILE *out)
{
	int bad = 0;
	for (hsize_t r0 = 0; r0 < n && !bad && !ferror(out); r0 += R->B) {
		hsize_t nb = n - r0 < R->B ? n - r0 : R->B;
		for (size_t d = 0; d < R->nvar && !bad; d++) {
			hid_t fs, ms;
			bad = slab(R, &R->var[d], v, 1, r0, nb, &fs, &ms) ||
			      H5Dread(R->var[d].ds, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, R->buf + R->var[d].off) < 0;
			close_spaces(fs, ms);
		}
		for (hsize_t r = 0; r < nb && !bad; r++) {
			fputs(pre, out);
			for (size_t c = 0; c < R->ncol; c++) {
				char b[32];
				csf_fmt_double(b, R->buf[R->coff[c] + r * R->cw[c]]);
				if (c) putc(',', out);
				fputs(b, out);
				if (c + 1 == R->ncol) putc('\n', out);
			}
		}
	}
	return bad ? -1 : 0;
}

/* Values [v0, v0 + n) of the 1-D dataset ds as memory type mt into v. */
static int read_1d(hid_t ds, hid_t mt, hsize_t v0, hsize_t n, void *v)
{
	hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(1, &n, NULL);
	int bad = fs < 0 || ms < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, &v0, NULL, &n, NULL) < 0 ||
	          H5Dread(ds, mt, ms, fs, H5P_DEFAULT, v) < 0;
	close_spaces(fs, ms);
	return bad ? -1 : 0;
}

/* Dataset name of a sweep's file, which the swept values' datasets (swept[0 .. np)), made before it, may have pushed to "name (2)". */
static hid_t open_after(hid_t f, const char *name, char **swept, size_t np)
{
	char alt[32];
	for (size_t k = 0; k < np; k++)
		if (!strcmp(swept[k], name)) snprintf(alt, sizeof alt, "%.16s (2)", name), name = alt;
	return H5Dopen2(f, name, H5P_DEFAULT);
}

/*
 * A sweep's file as the sweep's CSV: the header (when a variant ran, status not -1), then each
 * variant's rows, each after its swept values. 0, or -1 when it cannot be read.
 */
static int dump_variants(hid_t f, h5rows *R, hsize_t rows, char **head, size_t nh, char **swept, size_t np, FILE *out)
{
	enum { K = 4096 };
	hid_t rd = open_after(f, "rows", swept, np), sd = open_after(f, "status", swept, np), *pd = calloc(np + 1, sizeof *pd);
	long long *nr = malloc(K * sizeof *nr), *st = malloc(K * sizeof *st);
	double *val = malloc((np + 1) * K * sizeof *val);
	char *pre = malloc(np * 33 + 32); /* (csf_fmt_put may write 32 bytes) */
	int bad = rd < 0 || sd < 0 || !pd || !nr || !st || !val || !pre, ran = 0;
	for (size_t k = 0; k < np && !bad; k++) bad = (pd[k] = H5Dopen2(f, swept[k], H5P_DEFAULT)) < 0;
	for (hsize_t v0 = 0; v0 < R->nvariants && !bad && !ran; v0 += K) {
		hsize_t n = R->nvariants - v0 < K ? R->nvariants - v0 : K;
		bad = read_1d(sd, H5T_NATIVE_LLONG, v0, n, st);
		for (hsize_t v = 0; v < n && !bad; v++) ran |= st[v] != -1;
	}
	for (size_t c = 0; c < nh && ran; c++) fprintf(out, "%s%s", c ? "," : "", head[c]);
	if (ran) putc('\n', out);
	for (hsize_t v0 = 0; v0 < R->nvariants && !bad && ran; v0 += K) {
		hsize_t n = R->nvariants - v0 < K ? R->nvariants - v0 : K;
		bad = read_1d(rd, H5T_NATIVE_LLONG, v0, n, nr);
		for (size_t k = 0; k < np && !bad; k++) bad = read_1d(pd[k], H5T_NATIVE_DOUBLE, v0, n, val + k * K);
		for (hsize_t v = 0; v < n && !bad; v++) {
			if (nr[v] < 0 || (hsize_t)nr[v] > rows) {
				bad = -1;
				break;
			}
			char *p = pre;
			for (size_t k = 0; k < np; k++) {
				p += csf_fmt_put(p, val[k * K + v]);
				*p++ = ',';
			}
			*p = '\0';
			bad = dump_rows(R, v0 + v, (hsize_t)nr[v], pre, out);
		}
	}
	for (size_t k = 0; pd && k < np; k++)
		if (pd[k] > 0) H5Dclose(pd[k]);
	if (rd >= 0) H5Dclose(rd);
	if (sd >= 0) H5Dclose(sd);
	free(pd);
	free(nr);
	free(st);
	free(val);
	free(pre);
	return bad ? -1 : 0;
}

int csf_h5_dump(const char *path, FILE *out, FILE *err, const char *prog)
{
	h5_quiet();
	errno = 0;
	hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	if (f < 0) {
		fprintf(err, "%s: cannot read %s: %s\n", prog, path, h5_why(errno));
		return 2;
	}
	h5rows R = { 0 };
	hsize_t rows = 0;
	size_t nh = 0, np = 0;
	const char *why = "out of memory";
	char **head = read_strs(f, "columns", &nh), **swept = H5Aexists(f, "swept") > 0 ? read_strs(f, "swept", &np) : NULL;
	int st = 2, bad = 0;
	int al = 0;
	R.lead = np > 0; /* a sweep's */
	if (!head || np >= nh || find_vars(f, &R, &rows, &why) < 0 || (al = rows_alloc(&R, BLOCK_ROWS, nh - np)) < 0) {
		if (al == -1) why = "out of memory";
		else if (!head || np >= nh || al == -2) why = "not a file of csfvm -o FILE.h5 (no attribute columns naming its columns)";
		fprintf(err, "%s: %s: %s\n", prog, path, why);
		goto out;
	}
	if (R.lead) bad = dump_variants(f, &R, rows, head, nh, swept, np, out);
	else {
		for (size_t c = 0; c < nh; c++) fprintf(out, "%s%s", c ? "," : "", head[c]);
		putc('\n', out);
		bad = dump_rows(&R, 0, rows, "", out);
	}
	if (bad) fprintf(err, "%s: %s: cannot read its rows\n", prog, path);
	st = csf_run_finish(out, err, bad ? 2 : 0, 0);
out:
	for (size_t c = 0; c < nh; c++) H5free_memory(head[c]);
	for (size_t c = 0; c < np; c++) H5free_memory(swept[c]);
	free(head);
	free(swept);
	rows_free(&R);
	H5Fclose(f);
	return st;
}
