/*
 * util.c - the compiler's arena, source table and diagnostics.
 *
 * Diagnostics follow gcc: `file:line:col: error: message`, then the source
 * line, then a caret under the column. They go to diag_out (stderr unless
 * a test redirects it), so tests can compare the exact text. Hostile input
 * cannot make them costly: at most CSF_MAX_ERRORS are written, each quotes
 * at most DIAG_WIDTH bytes of its line (read in place, never copied), and a
 * fatal error (a binary file) is the last.
 */
#include <errno.h>
#include <stdint.h>
#include <sys/stat.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "lint.h"
#include "ast.h"
#include "csf_int.h"

/* The arena: zeroed chunks of CHUNK bytes, handed out by bumping a pointer;
 * a large request gets a block of its own. */
#define CHUNK (256 * 1024)
typedef struct Block { struct Block *next; max_align_t data[]; } Block;
static Block *blocks;
static char *bump, *bump_end;
/* The syntax tree's nodes given back by ast_free, linked by their a; forgotten when the arena
 * releases memory (they may be in what it releases). */
static Expr *expr_free;

void xoom(void)
{
	fprintf(stderr, "csfc: out of memory\n");
	exit(2);
}

void *xmalloc(size_t n)
{
	void *p = malloc(n ? n : 1);
	if (!p) xoom();
	return p;
}

void *xcalloc(size_t n, size_t size)
{
	void *p = calloc(n ? n : 1, size ? size : 1);
	if (!p) xoom();
	return p;
}

void *xrealloc(void *p, size_t n)
{
	void *q = realloc(p, n ? n : 1);
	if (!q) xoom();
	return q;
}

static void *new_block(size_t n)
{
	Block *b = calloc(1, sizeof(Block) + n);
	if (!b) xoom();
	b->next = blocks;
	blocks = b;
	return b->data;
}

void *xalloc(size_t n)
{
	size_t a = _Alignof(max_align_t); /* 16, where sizeof(max_align_t) is 32 */
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

ArenaMark arena_mark(void) { return (ArenaMark){ blocks, bump, bump_end, sources.v, sources.n, sources.cap }; }

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
	expr_free = NULL;
	sources.v = m.src_v; /* vec_push copies on growth: the table as it was is intact */
	sources.n = m.src_n;
	sources.cap = m.src_cap;
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
	expr_free = NULL;
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

int vec_has(const Vec *a, const void *x)
{
	for (int i = 0; i < a->n; i++)
		if (a->v[i] == x) return 1;
	return 0;
}

static size_t pset_at(const PSet *s, const void *p)
{
	uint64_t h = (uint64_t)(uintptr_t)p * 0x9E3779B97F4A7C15ull;
	size_t i = (size_t)(h >> 20) & (s->cap - 1);
	while (s->slot[i] && s->slot[i] != p) i = (i + 1) & (s->cap - 1);
	return i;
}

int pset_has(const PSet *s, const void *p) { return s->cap && s->slot[pset_at(s, p)] == p; }

int pset_add(PSet *s, const void *p)
{
	if (2 * (s->n + 1) > s->cap) {
		PSet g = { xcalloc(s->cap ? 2 * s->cap : 64, sizeof *g.slot), s->cap ? 2 * s->cap : 64, 0 };
		for (size_t i = 0; i < s->cap; i++)
			if (s->slot[i]) g.slot[pset_at(&g, s->slot[i])] = s->slot[i], g.n++;
		free(s->slot);
		*s = g;
	}
	size_t i = pset_at(s, p);
	if (s->slot[i]) return 0;
	s->slot[i] = p;
	s->n++;
	return 1;
}

void pset_free(PSet *s)
{
	free(s->slot);
	*s = (PSet){ 0 };
}

void vec_add_new(Vec *a, const Vec *b, const void *skip)
{
	if (a->n + b->n <= 32) { /* small: scanning is quicker */
		for (int i = 0; i < b->n; i++)
			if (b->v[i] != skip && !vec_has(a, b->v[i])) vec_push(a, b->v[i]);
		return;
	}
	PSet s = { 0 };
	for (int i = 0; i < a->n; i++) pset_add(&s, a->v[i]);
	for (int i = 0; i < b->n; i++)
		if (b->v[i] != skip && pset_add(&s, b->v[i])) vec_push(a, b->v[i]);
	pset_free(&s);
}

Expr *ast_expr(ExprKind k, Loc l)
{
	Expr *e = expr_free;
	if (e) {
		expr_free = e->a;
		memset(e, 0, sizeof *e);
	} else {
		e = xalloc(sizeof *e);
	}
	e->kind = k;
	e->loc = l;
	return e;
}

void ast_free(Expr *e)
{
	e->a = expr_free;
	expr_free = e;
}

Vec sources;
Options opts;
int diag_errors;
FILE *diag_out;

/* Indexes the starts of s's lines, when it is added, so that src_line is O(1) (added later,
   inside an arena mark a pass releases, the index would be lost). */
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

int src_load(const char *path)
{
	/* a model takes some 26 times its size to compile (4.9 KB for an object of 190 bytes written out
	   line by line, bench/gen_scene.sh): a larger file is refused before it is read, not left to
	   exhaust memory */
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
	index_lines(s);
	vec_push(&sources, s);
	return sources.n - 1;
}

int src_add_n(const char *name, const char *text, size_t len)
{
	Source *s = xalloc(sizeof *s);
	s->path = xstrdup(name);
	s->text = xstrndup(text, len);
	s->len = len;
	index_lines(s);
	vec_push(&sources, s);
	return sources.n - 1;
}

int src_add(const char *name, const char *text) { return src_add_n(name, text, strlen(text)); }

char *src_line(int file, int line)
{
	Source *s = sources.v[file];
	if (line < 1 || line > s->nlines) return xstrdup("");
	const char *p = s->text + s->line_start[line - 1], *end = s->text + s->len;
	const char *e = p;
	while (e < end && *e != '\n') e++;
	if (e > p && e[-1] == '\r') e--;
	return xstrndup(p, (size_t)(e - p));
}

/* The part of a source line a diagnostic quotes: at most DIAG_WIDTH bytes around the column. */
#define DIAG_WIDTH 160

/* Writes the quoted line and the caret under column col (from 1) as one block, with control
 * characters and invalid UTF-8 as '?' (a binary file cannot write raw bytes to the terminal). */
static void quote_line(FILE *out, Loc l)
{
	Source *s = sources.v[l.file];
	if (l.line < 1 || l.line > s->nlines) return;
	const char *p = s->text + s->line_start[l.line - 1], *end = s->text + s->len;
	size_t n = 0;
	while (p + n < end && p[n] != '\n') n++;
	if (n && p[n - 1] == '\r') n--;
	size_t col = l.col > 0 ? (size_t)l.col - 1 : 0, from = 0;
	if (col > n) col = n;
	if (n > DIAG_WIDTH && col > DIAG_WIDTH / 2) from = col - DIAG_WIDTH / 2;
	size_t to = n - from > DIAG_WIDTH ? from + DIAG_WIDTH : n;
	char buf[2 * DIAG_WIDTH + 32], *b = buf;
	b += sprintf(b, "  %s", from ? "..." : "");
	for (size_t i = from; i < to; i++) {
		unsigned char c = (unsigned char)p[i];
		int k = c < 0x80 ? 1 : lex_utf8_len((const unsigned char *)p + i, (const unsigned char *)p + to);
		if (k > 1) {
			memcpy(b, p + i, (size_t)k);
			b += k;
			i += (size_t)k - 1;
		} else {
			*b++ = c == '\t' || (c >= 32 && c < 127) ? (char)c : '?';
		}
	}
	b += sprintf(b, "%s\n  %s", to < n ? "..." : "", from ? "   " : "");
	for (size_t i = from; i < col; i++)
		if (((unsigned char)p[i] & 0xC0) != 0x80) *b++ = p[i] == '\t' ? '\t' : ' ';
	strcpy(b, "^\n");
	fputs(buf, out);
}

static void vdiag(Loc l, const char *kind, const char *fmt, va_list ap)
{
	FILE *out = diag_out ? diag_out : stderr;
	Source *s = sources.v[l.file];
	fprintf(out, "%s:%d:%d: %s: ", s->path, l.line, l.col, kind);
	vfprintf(out, fmt, ap);
	fputc('\n', out);
	quote_line(out, l);
}

int diag_stop;

/* Counts an error; returns 0 if it is not to be printed (past CSF_MAX_ERRORS, or after a fatal one). */
static int count_error(void)
{
	if (diag_stop) return 0;
	if (++diag_errors <= CSF_MAX_ERRORS) return 1;
	FILE *out = diag_out ? diag_out : stderr;
	fprintf(out, "csfc: error: too many errors (more than %d); stopping\n", CSF_MAX_ERRORS);
	diag_stop = 1;
	return 0;
}

void error_at(Loc l, const char *fmt, ...)
{
	if (!count_error()) return;
	va_list ap;
	va_start(ap, fmt);
	vdiag(l, "error", fmt, ap);
	va_end(ap);
}

void fatal_at(Loc l, const char *fmt, ...)
{
	if (!count_error()) return;
	va_list ap;
	va_start(ap, fmt);
	vdiag(l, "error", fmt, ap);
	va_end(ap);
	diag_stop = 1;
}

void note_at(Loc l, const char *fmt, ...)
{
	if (diag_stop || diag_errors > CSF_MAX_ERRORS) return;
	va_list ap;
	va_start(ap, fmt);
	vdiag(l, "note", fmt, ap);
	va_end(ap);
}

void error_plain(const char *fmt, ...)
{
	if (!count_error()) return;
	FILE *out = diag_out ? diag_out : stderr;
	va_list ap;
	va_start(ap, fmt);
	fputs("csfc: error: ", out);
	vfprintf(out, fmt, ap);
	fputc('\n', out);
	va_end(ap);
}

void csfc_reset(void)
{
	arena_free();
	sources = (Vec){ 0 };
	diag_errors = 0;
	diag_stop = 0;
	lex_reset();
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

void *map_get(const Map *m, const char *k)
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

