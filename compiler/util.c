/*
 * util.c - the compiler's arena, source table and diagnostics.
 *
 * Diagnostics follow gcc: `file:line:col: error: message`, then the source
 * line, then a caret under the column. They go to diag_out (stderr unless
 * a test redirects it), so tests can compare the exact text.
 */
#include <errno.h>
#include <sys/stat.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "lint.h"
#include "ast.h"
#include "csf.h"

/* The arena: zeroed chunks of CHUNK bytes, handed out by bumping a pointer;
 * a large request gets a block of its own. */
#define CHUNK (256 * 1024)
typedef struct Block { struct Block *next; max_align_t data[]; } Block;
static Block *blocks;
static char *bump, *bump_end;

static void *new_block(size_t n)
{
	Block *b = calloc(1, sizeof(Block) + n);
	if (!b) {
		fprintf(stderr, "csfc: out of memory\n");
		exit(2);
	}
	b->next = blocks;
	blocks = b;
	return b->data;
}

void *xalloc(size_t n)
{
	size_t a = sizeof(max_align_t);
	n = (n + a - 1) / a * a;
	if (n > CHUNK / 8) return new_block(n);
	if ((size_t)(bump_end - bump) < n) {
		bump = new_block(CHUNK);
		bump_end = bump + CHUNK;
	}
	void *p = bump;
	bump += n;
	return p;
}

ArenaMark arena_mark(void) { return (ArenaMark){ blocks, bump, bump_end }; }

void arena_release(ArenaMark m)
{
	/* what was handed out from m's chunk since: up to bump, or (a new chunk was begun) all of it */
	char *end = bump_end == m.bump_end ? bump : m.bump_end;
	while (blocks != m.blocks) {
		Block *b = blocks->next;
		free(blocks);
		blocks = b;
	}
	bump = m.bump;
	bump_end = m.bump_end;
	if (bump) memset(bump, 0, (size_t)(end - bump)); /* xalloc hands out zeroed memory */
}

void *xrealloc_arr(void *p, size_t n)
{
	void *q = xalloc(n);
	if (p) memcpy(q, p, n); /* callers only grow, and the old block is at least as large as its use */
	return q;
}

void arena_free(void)
{
	while (blocks) {
		Block *b = blocks->next;
		free(blocks);
		blocks = b;
	}
	bump = bump_end = NULL;
}

char *xstrndup(const char *s, size_t n)
{
	char *p = xalloc(n + 1);
	memcpy(p, s, n);
	return p;
}

char *xstrdup(const char *s) { return xstrndup(s, strlen(s)); }

char *xprintf(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(NULL, 0, fmt, ap);
	va_end(ap);
	char *p = xalloc((size_t)n + 1);
	va_start(ap, fmt);
	vsnprintf(p, (size_t)n + 1, fmt, ap);
	va_end(ap);
	return p;
}

void vec_push(Vec *a, void *x)
{
	if (a->n == a->cap) {
		int cap = a->cap ? 2 * a->cap : 8;
		void **v = xalloc((size_t)cap * sizeof *v);
		if (a->n) memcpy(v, a->v, (size_t)a->n * sizeof *v);
		a->v = v;
		a->cap = cap;
	}
	a->v[a->n++] = x;
}

Expr *ast_expr(ExprKind k, Loc l)
{
	Expr *e = xalloc(sizeof *e);
	e->kind = k;
	e->loc = l;
	return e;
}

Vec sources;
Options opts;
int diag_errors;
FILE *diag_out;

int src_load(const char *path)
{
	/* a model takes some 80 times its size to compile (10 KB for an object of 130 bytes):
	   a larger file is refused before it is read, not left to exhaust memory */
	struct stat st;
	if (stat(path, &st) == 0 && st.st_size > CSF_MAX_SOURCE) {
		errno = EFBIG;
		return -1;
	}
	size_t n;
	unsigned char *buf = csf_read_file(path, &n);
	if (!buf) return -1;
	Source *s = xalloc(sizeof *s);
	s->path = xstrdup(path);
	s->text = xstrndup((char *)buf, n); /* NUL-terminated copy in the arena */
	s->len = n;
	free(buf);
	vec_push(&sources, s);
	return sources.n - 1;
}

int src_add(const char *name, const char *text)
{
	Source *s = xalloc(sizeof *s);
	s->path = xstrdup(name);
	s->text = xstrdup(text);
	s->len = strlen(text);
	vec_push(&sources, s);
	return sources.n - 1;
}

/* Indexes the starts of s's lines, once, so that src_line is O(1). */
static void index_lines(Source *s)
{
	int n = 1;
	for (size_t i = 0; i < s->len; i++) n += s->text[i] == '\n';
	s->line_start = xalloc((size_t)(n + 1) * sizeof *s->line_start);
	s->line_start[0] = 0;
	int k = 1;
	for (size_t i = 0; i < s->len; i++)
		if (s->text[i] == '\n') s->line_start[k++] = i + 1;
	s->line_start[n] = s->len + 1;
	s->nlines = n;
}

char *src_line(int file, int line)
{
	Source *s = sources.v[file];
	if (!s->line_start) index_lines(s);
	if (line < 1 || line > s->nlines) return xstrdup("");
	const char *p = s->text + s->line_start[line - 1], *end = s->text + s->len;
	const char *e = p;
	while (e < end && *e != '\n') e++;
	if (e > p && e[-1] == '\r') e--;
	return xstrndup(p, (size_t)(e - p));
}

static void vdiag(Loc l, const char *kind, const char *fmt, va_list ap)
{
	FILE *out = diag_out ? diag_out : stderr;
	Source *s = sources.v[l.file];
	fprintf(out, "%s:%d:%d: %s: ", s->path, l.line, l.col, kind);
	vfprintf(out, fmt, ap);
	fputc('\n', out);
	char *line = src_line(l.file, l.line);
	fprintf(out, "  %s\n  ", line);
	/* the caret under the column: one space per character (l.col counts bytes; skip UTF-8 continuation bytes) */
	for (int i = 1; i < l.col && line[i - 1]; i++)
		if (((unsigned char)line[i - 1] & 0xC0) != 0x80) fputc(line[i - 1] == '\t' ? '\t' : ' ', out);
	fputs("^\n", out);
}

void error_at(Loc l, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vdiag(l, "error", fmt, ap);
	va_end(ap);
	diag_errors++;
}

void note_at(Loc l, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vdiag(l, "note", fmt, ap);
	va_end(ap);
}

void error_plain(const char *fmt, ...)
{
	FILE *out = diag_out ? diag_out : stderr;
	va_list ap;
	va_start(ap, fmt);
	fputs("csfc: error: ", out);
	vfprintf(out, fmt, ap);
	fputc('\n', out);
	va_end(ap);
	diag_errors++;
}

int diag_warnings, diag_werror, diag_nowarn;

void warn_at(Loc l, const char *fmt, ...)
{
	if (diag_nowarn) return;
	va_list ap;
	va_start(ap, fmt);
	if (diag_werror) { /* -Werror: an error, which says why */
		va_list aq;
		va_copy(aq, ap);
		int n = vsnprintf(NULL, 0, fmt, aq);
		va_end(aq);
		char *msg = xalloc((size_t)n + 1);
		vsnprintf(msg, (size_t)n + 1, fmt, ap);
		error_at(l, "%s [-Werror]", msg);
	} else {
		vdiag(l, "warning", fmt, ap);
		diag_warnings++;
	}
	va_end(ap);
}

/* ---- a string map ---- */

static size_t str_hash(const char *s)
{
	size_t h = 1469598103934665603ull;
	while (*s) h = (h ^ (unsigned char)*s++) * 1099511628211ull;
	return h;
}

void *map_get(Map *m, const char *k)
{
	if (!m->cap) return NULL;
	for (size_t i = str_hash(k) & (m->cap - 1);; i = (i + 1) & (m->cap - 1)) {
		if (!m->keys[i]) return NULL;
		if (strcmp(m->keys[i], k) == 0) return m->vals[i];
	}
}

void map_put(Map *m, char *k, void *v)
{
	if (2 * (m->n + 1) > m->cap) {
		Map g = { 0 };
		g.cap = m->cap ? 2 * m->cap : 8; /* most maps are small: an object's properties */
		g.keys = xalloc(g.cap * sizeof *g.keys);
		g.vals = xalloc(g.cap * sizeof *g.vals);
		for (size_t i = 0; i < m->cap; i++)
			if (m->keys[i]) map_put(&g, m->keys[i], m->vals[i]);
		*m = g;
	}
	size_t i = str_hash(k) & (m->cap - 1);
	while (m->keys[i] && strcmp(m->keys[i], k) != 0) i = (i + 1) & (m->cap - 1);
	if (!m->keys[i]) m->n++;
	m->keys[i] = k;
	m->vals[i] = v;
}

