/*
 * lsp.c - csfc --lsp: a Language Server Protocol server over standard input
 * and output, for editors.
 *
 * Messages are JSON-RPC 2.0, each after a `Content-Length: N` header and a
 * blank line. The server keeps the text of every open document (full sync:
 * didOpen, didChange with the whole text) and compiles it as csfc does, short
 * of writing anything: parse, resolve, leave out what nothing watched needs,
 * generate, lint. Every error and warning csfc would print becomes a
 * diagnostic (publishDiagnostics), its range the token at the column csfc
 * names; a note is added to the diagnostic before it. Hover on a name says
 * what --explain knows of it (vector or scalar, its unit, state, computed by
 * which rule, constant); definition jumps to the line that defines an object
 * or a property (a kind's default: the `def` in its file).
 *
 * The compiler's memory is the arena csfc_reset releases before every
 * compilation; the last compiled model is kept for hover and definition
 * until the next. The server's own memory (documents, messages) is the
 * heap's, freed as it goes. A message that is not JSON gets a parse error
 * (-32700), one that is not a request an invalid request (-32600), an
 * unknown method -32601; a header without Content-Length, or a body longer
 * than LSP_MAX_BODY, is skipped with an error. Nothing in a message can
 * end the server but `exit` and the end of the input.
 */
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "ast.h"
#include "sema.h"
#include "gen.h"
#include "lint.h"
#include "cone.h"
#include "explain.h"
#include "json.h"
#include "lsp.h"

/* The longest message body read: a model may be CSF_MAX_SOURCE bytes, escaped in JSON. */
#define LSP_MAX_BODY (2 * CSF_MAX_SOURCE + (1 << 20))
/* The longest header line kept (longer ones are read and ignored). */
#define LSP_MAX_HEADER 1024

typedef struct Doc {
	char *uri, *path;    /* path: the file the uri names (what `using` and `from` are relative to) */
	char *text;
	size_t len;
	unsigned gen;        /* changes when the text does */
	struct Doc *next;
} Doc;

static struct {
	Doc *docs;
	unsigned gen;
	const char *stdlib;
	char **incdirs;
	int nincdirs, units;
	/* the last compilation: of doc at generation gen; its model (NULL: it had errors) */
	Doc *doc;
	unsigned doc_gen;
	Model *model;
	int file;            /* the document's index in the source table */
	int shutdown;
} S;

/* ---- reading and writing messages ---- */

static void send(const Buf *b)
{
	printf("Content-Length: %zu\r\n\r\n", b->n);
	fwrite(b->s, 1, b->n, stdout);
	fflush(stdout);
}

/* A response to request id: result (JSON text), or error code and message when msg is not NULL. */
static void respond(const Json *id, const char *result, int code, const char *msg)
{
	Buf b = { 0 };
	jbuf_puts(&b, "{\"jsonrpc\":\"2.0\",\"id\":");
	if (id) jbuf_value(&b, id);
	else jbuf_puts(&b, "null");
	if (msg) {
		jbuf_printf(&b, ",\"error\":{\"code\":%d,\"message\":", code);
		jbuf_string(&b, msg, strlen(msg));
		jbuf_puts(&b, "}}");
	} else {
		jbuf_printf(&b, ",\"result\":%s}", result);
	}
	send(&b);
	free(b.s);
}

/* Reads one header block; the body's length, -1 at the end of the input, -2 without a usable Content-Length. */
static long read_header(void)
{
	long len = -2;
	char line[LSP_MAX_HEADER];
	for (;;) {
		size_t n = 0;
		int c, any = 0;
		while ((c = getchar()) != EOF && c != '\n') {
			any = 1;
			if (n + 1 < sizeof line) line[n++] = (char)c;
		}
		if (c == EOF) return -1;
		if (n && line[n - 1] == '\r') n--;
		line[n] = '\0';
		if (!n) {
			if (any || len != -2) return len; /* the blank line ends the header */
			continue;                       /* blank lines between messages */
		}
		if (!strncasecmp(line, "Content-Length:", 15)) {
			char *end;
			long v = strtol(line + 15, &end, 10);
			while (*end == ' ' || *end == '\t') end++;
			len = *end || v < 0 ? -2 : v;
		}
	}
}

/* The next message's body (NUL-terminated, *n bytes), NULL at the end of the input; a header
   without a usable length or a body too long is answered with an error and skipped. */
static char *read_message(size_t *n)
{
	for (;;) {
		long len = read_header();
		if (len == -1) return NULL;
		if (len == -2) {
			respond(NULL, NULL, -32600, "a message needs a header 'Content-Length: N'");
			continue;
		}
		if (len > LSP_MAX_BODY) {
			for (long i = 0; i < len; i++)
				if (getchar() == EOF) return NULL;
			respond(NULL, NULL, -32600, "a message longer than csfc --lsp reads");
			continue;
		}
		char *body = xmalloc((size_t)len + 1);
		if (fread(body, 1, (size_t)len, stdin) != (size_t)len) {
			free(body);
			return NULL;
		}
		body[len] = '\0';
		*n = (size_t)len;
		return body;
	}
}

/* ---- documents and positions ---- */

static Doc *find_doc(const char *uri)
{
	for (Doc *d = S.docs; d; d = d->next)
		if (!strcmp(d->uri, uri)) return d;
	return NULL;
}

static int hexval(char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; }

/* The path a file: URI names (percent-decoded), or the URI itself for any other scheme. */
static char *uri_path(const char *uri)
{
	const char *p = strncmp(uri, "file://", 7) ? uri : uri + 7;
	if (p == uri) {
		char *copy = xmalloc(strlen(uri) + 1);
		return strcpy(copy, uri);
	}
	if (*p != '/') p = strchr(p, '/') ? strchr(p, '/') : ""; /* file://host/path */
	char *out = xmalloc(strlen(p) + 1), *o = out;
	for (; *p; p++) {
		if (*p == '%' && hexval(p[1]) >= 0 && hexval(p[2]) >= 0 && (hexval(p[1]) | hexval(p[2]))) {
			*o++ = (char)(hexval(p[1]) << 4 | hexval(p[2]));
			p += 2;
		} else {
			*o++ = *p;
		}
	}
	*o = '\0';
	return out;
}

/* Appends the file: URI of path to b, as a JSON string. */
static void buf_uri(Buf *b, const char *path)
{
	Buf u = { 0 };
	jbuf_puts(&u, "file://");
	for (const unsigned char *p = (const unsigned char *)path; *p; p++) {
		if ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || strchr("/-._~", *p))
			jbuf_add(&u, (const char *)p, 1);
		else jbuf_printf(&u, "%%%02X", *p);
	}
	jbuf_string(b, u.s, u.n);
	free(u.s);
}

/* Line `line` (from 0) of text: its start and length (without the newline); 0 past the end. */
static int line_span(const char *text, size_t len, int line, size_t *start, size_t *n)
{
	size_t i = 0;
	for (int l = 0; l < line; l++) {
		const char *nl = i < len ? memchr(text + i, '\n', len - i) : NULL;
		if (!nl) return 0;
		i = (size_t)(nl - text) + 1;
	}
	size_t e = i;
	while (e < len && text[e] != '\n') e++;
	if (e > i && text[e - 1] == '\r') e--;
	*start = i, *n = e - i;
	return 1;
}

/* Walks line p (n bytes) from its start by characters until byte stop or UTF-16 column ch, whichever
   comes first; the byte and the column reached. */
static void walk_line(const char *p, size_t n, size_t stop, int ch, size_t *byte, int *col)
{
	size_t i = 0;
	int c = 0;
	while (i < stop && i < n && c < ch) {
		int k = lex_utf8_len((const unsigned char *)p + i, (const unsigned char *)p + n);
		if (k < 1) k = 1;
		c += k == 4 ? 2 : 1; /* beyond the BMP: two UTF-16 units */
		i += (size_t)k;
	}
	*byte = i, *col = c;
}

/* The UTF-16 column (LSP's character) of byte b of a line p (n bytes), and the reverse. */
static int utf16_col(const char *p, size_t n, size_t b)
{
	size_t i;
	int c;
	walk_line(p, n, b, INT_MAX, &i, &c);
	return c;
}

static size_t byte_col(const char *p, size_t n, int ch)
{
	size_t i;
	int c;
	walk_line(p, n, SIZE_MAX, ch, &i, &c);
	return i;
}

static int is_word(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

/* Appends the LSP range of the token at line, byte col (from 1) of text: a word, a number, or one character. */
static void buf_range(Buf *b, const char *text, size_t len, int line, int col)
{
	size_t s = 0, n = 0;
	if (line < 1 || !line_span(text, len, line - 1, &s, &n)) s = n = 0, line = line < 1 ? 1 : line;
	const char *p = text + s;
	size_t from = col > 1 ? (size_t)col - 1 : 0, to;
	if (from > n) from = n;
	to = from;
	if (to < n && is_word(p[to])) {
		while (to < n && (is_word(p[to]) || (p[to] == '.' && to + 1 < n && p[to + 1] >= '0' && p[to + 1] <= '9' &&
		                                    p[from] >= '0' && p[from] <= '9'))) to++;
	} else if (to < n) {
		int k = lex_utf8_len((const unsigned char *)p + to, (const unsigned char *)p + n);
		to += k > 0 ? (size_t)k : 1;
	}
	jbuf_printf(b, "{\"start\":{\"line\":%d,\"character\":%d},\"end\":{\"line\":%d,\"character\":%d}}", line - 1,
	           utf16_col(p, n, from), line - 1, utf16_col(p, n, to));
}

/* ---- compiling ---- */

/* Compiles d as csfc would, into S.model (NULL if it has errors); its diagnostics, csfc's text, in *out. */
static void compile(Doc *d, char **out, size_t *outlen)
{
	csfc_reset();
	opts = (Options){ .units = S.units, .stdlib = S.stdlib };
	for (int i = 0; i < S.nincdirs; i++) vec_push(&opts.incdirs, S.incdirs[i]);
	FILE *f = open_memstream(out, outlen);
	if (!f) xoom();
	diag_out = f;
	S.file = src_add_n(d->path, d->text, d->len);
	Stmt *stmts = parse_file(S.file);
	ArenaMark mark = arena_mark();
	Model *M = diag_errors ? NULL : sema_run(stmts, NULL);
	if (M && !diag_errors) {
		M = cone_leave_out(stmts, M, mark);
		cone_idle_states(M);
		csf_prog p;
		if (!gen_program(M, &p)) lint_model(M);
		csf_prog_free(&p);
	}
	if (diag_errors) M = NULL;
	fclose(f);
	diag_out = NULL;
	S.doc = d, S.doc_gen = d->gen, S.model = M;
}

/* The model of d, compiling it again if it changed since (NULL if it has errors). */
static Model *model_of(Doc *d)
{
	if (S.doc != d || S.doc_gen != d->gen) {
		char *out = NULL;
		size_t n = 0;
		compile(d, &out, &n);
		free(out);
	}
	return S.model;
}

/* One diagnostic line of csfc's text ("PATH:L:C: KIND: MSG"): its parts, or 0 if it is none. */
static int parse_diag(char *s, char **path, int *line, int *col, const char **kind, char **msg)
{
	static const char *const kinds[] = { "error", "warning", "note" };
	for (char *p = strstr(s, ": "); p; p = strstr(p + 1, ": ")) {
		for (int k = 0; k < 3; k++) {
			size_t kl = strlen(kinds[k]);
			if (strncmp(p + 2, kinds[k], kl) || strncmp(p + 2 + kl, ": ", 2)) continue;
			*kind = kinds[k];
			*msg = p + 4 + kl;
			/* back over ":C" and ":L" */
			char *q = p;
			int nums[2];
			for (int j = 1; j >= 0; j--) {
				char *e = q;
				while (q > s && q[-1] >= '0' && q[-1] <= '9') q--;
				if (q == e || q == s || q[-1] != ':') goto plain;
				nums[j] = atoi(q);
				q--;
			}
			*q = '\0';
			*path = s, *line = nums[0], *col = nums[1];
			return 1;
		plain:
			*path = s, *line = 0, *col = 0;
			*p = '\0'; /* "csfc: error: ..." */
			return 1;
		}
	}
	return 0;
}

/* A diagnostic being collected: where, how severe, its message (with the notes after it). */
typedef struct Diag { int line, col, severity; Buf msg; } Diag;

/* The start of d's publishDiagnostics notification, up to the opening of its list. */
static void diagnostics_head(Buf *b, const Doc *d)
{
	jbuf_puts(b, "{\"jsonrpc\":\"2.0\",\"method\":\"textDocument/publishDiagnostics\",\"params\":{\"uri\":");
	jbuf_string(b, d->uri, strlen(d->uri));
	jbuf_puts(b, ",\"diagnostics\":[");
}

/* Compiles d and publishes its diagnostics. */
static void publish(Doc *d)
{
	char *out = NULL;
	size_t n = 0;
	compile(d, &out, &n);
	Diag *v = NULL;
	size_t nd = 0;
	for (char *line = out, *next; line && *line; line = next) {
		next = strchr(line, '\n');
		if (next) *next++ = '\0';
		char *path, *msg;
		const char *kind;
		int l, c;
		if (line[0] == ' ' || !parse_diag(line, &path, &l, &c, &kind, &msg)) continue;
		int here = !strcmp(path, d->path) && l > 0;
		if (!strcmp(kind, "note")) {
			if (!nd) continue;
			jbuf_puts(&v[nd - 1].msg, "\nnote: ");
			if (!here && l > 0) jbuf_printf(&v[nd - 1].msg, "%s:%d:%d: ", path, l, c);
			else if (here && l != v[nd - 1].line) jbuf_printf(&v[nd - 1].msg, "line %d: ", l);
			jbuf_puts(&v[nd - 1].msg, msg);
			continue;
		}
		v = xrealloc(v, (nd + 1) * sizeof *v);
		Diag *g = &v[nd++];
		*g = (Diag){ here ? l : 1, here ? c : 1, strcmp(kind, "error") ? 2 : 1, { 0 } };
		if (!here && l > 0) jbuf_printf(&g->msg, "%s:%d:%d: ", path, l, c);
		jbuf_puts(&g->msg, msg);
	}
	free(out);
	Buf b = { 0 };
	diagnostics_head(&b, d);
	for (size_t i = 0; i < nd; i++) {
		jbuf_puts(&b, i ? ",{\"range\":" : "{\"range\":");
		buf_range(&b, d->text, d->len, v[i].line, v[i].col);
		jbuf_printf(&b, ",\"severity\":%d,\"source\":\"csfc\",\"message\":", v[i].severity);
		jbuf_string(&b, v[i].msg.s ? v[i].msg.s : "", v[i].msg.n);
		jbuf_puts(&b, "}");
		free(v[i].msg.s);
	}
	free(v);
	jbuf_puts(&b, "]}}");
	send(&b);
	free(b.s);
}

/* ---- hover and definition ---- */

/* The object the name ending at p[to] of a line (n bytes) belongs to: on an object's line, that object;
   in a rule or when with a `for` list, the list's first name, or with `$k` after the name its k-th
   (from 0); a fresh string, or NULL. */
static char *bound_object(const char *p, size_t n, size_t to)
{
	int place = 0;
	if (to < n && p[to] == '$') place = atoi(p + to + 1);
	size_t i = 0;
	while (i < n && p[i] == ' ') i++;
	if (n - i > 7 && !strncmp(p + i, "object ", 7)) { /* a property line: its object */
		size_t b = i + 7, e;
		while (b < n && p[b] == ' ') b++;
		for (e = b; e < n && is_word(p[e]); e++) {}
		char *name = xmalloc(e - b + 1);
		memcpy(name, p + b, e - b);
		name[e - b] = '\0';
		return name;
	}
	if (!((n - i > 5 && !strncmp(p + i, "rule ", 5)) || (n - i > 5 && !strncmp(p + i, "when ", 5)))) return NULL;
	const char *colon = memchr(p, ':', n), *f = NULL;
	for (const char *q = p + i; colon && q + 4 < colon; q++)
		if (!strncmp(q, " for ", 5)) f = q + 5;
	if (!f) return NULL;
	for (int k = 0; f < colon; k++) { /* the k-th item, up to a ',' outside brackets */
		while (f < colon && *f == ' ') f++;
		const char *e = f;
		int depth = 0;
		while (e < colon && (depth || *e != ',')) depth += (*e == '[') - (*e == ']'), e++;
		if (k == place) {
			while (e > f && e[-1] == ' ') e--;
			char *name = xmalloc((size_t)(e - f) + 1);
			memcpy(name, f, (size_t)(e - f));
			name[e - f] = '\0';
			return name;
		}
		f = e + 1;
	}
	return NULL;
}

/* The name under position pos ({line, character}) of d, the object name before a '.' in front of it
   (NULL if none), and the object its statement's `for` list binds it to (NULL if none): fresh strings,
   freed by the caller; 0 if there is no name there. */
static int word_at(Doc *d, const Json *pos, char **name, char **qual, char **bound, int *line)
{
	*bound = NULL;
	*line = json_int(json_get(pos, "line"), -1);
	int ch = json_int(json_get(pos, "character"), -1);
	size_t s, n;
	if (*line < 0 || ch < 0 || !line_span(d->text, d->len, *line, &s, &n)) return 0;
	const char *p = d->text + s;
	size_t at = byte_col(p, n, ch), from = at, to = at;
	if ((at >= n || !is_word(p[at])) && at > 0 && is_word(p[at - 1])) from = to = at - 1; /* just after a name */
	if (to >= n || !is_word(p[to])) return 0;
	while (from > 0 && is_word(p[from - 1])) from--;
	while (to < n && is_word(p[to])) to++;
	if (p[from] >= '0' && p[from] <= '9') return 0;
	int quoted = 0; /* in a comment or a string: no name */
	for (size_t i = 0; i < from; i++) {
		if (p[i] == '"') quoted = !quoted;
		else if (p[i] == '#' && !quoted) return 0;
	}
	if (quoted) return 0;
	*name = xmalloc(to - from + 1);
	memcpy(*name, p + from, to - from);
	(*name)[to - from] = '\0';
	*qual = NULL;
	if (from >= 2 && p[from - 1] == '.') { /* obj.prop, or member[3].prop */
		size_t e = from - 1, b = e;
		if (p[b - 1] == ']') {
			while (b > 0 && p[b - 1] != '[') b--;
			if (b > 0) b--;
		}
		while (b > 0 && is_word(p[b - 1])) b--;
		if (b < e) {
			*qual = xmalloc(e - b + 1);
			memcpy(*qual, p + b, e - b);
			(*qual)[e - b] = '\0';
		}
	}
	if (!*qual) *bound = bound_object(p, n, to);
	return 1;
}

static Object *object_named(Model *M, const char *name)
{
	for (int i = 0; name && i < M->objects.n; i++)
		if (!strcmp(((Object *)M->objects.v[i])->name, name)) return M->objects.v[i];
	return NULL;
}

/* The variable a name stands for: qual's property (obj.prop), else that of the object its `for` list
   binds (bound), else an object's property (the first that has it), a temporary, a global. */
static Var *var_named(Model *M, const char *name, const char *qual, const char *bound)
{
	Object *q = object_named(M, qual), *b = object_named(M, bound);
	if (q) return prop_of_obj(q, name);
	if (b && prop_of_obj(b, name)) return prop_of_obj(b, name);
	for (int i = 0; b && i < M->temps.n; i++)
		if (((Var *)M->temps.v[i])->obj == b && !strcmp(((Var *)M->temps.v[i])->name, name)) return M->temps.v[i];
	for (int i = 0; i < M->objects.n; i++) {
		Var *v = prop_of_obj(M->objects.v[i], name);
		if (v) return v;
	}
	for (int i = 0; i < M->temps.n; i++)
		if (!strcmp(((Var *)M->temps.v[i])->name, name)) return M->temps.v[i];
	for (int i = 0; i < M->globals.n; i++)
		if (!strcmp(((Var *)M->globals.v[i])->name, name)) return M->globals.v[i];
	if (!strcmp(name, "t")) return M->time;
	return NULL;
}

/* What --explain says of line `line` (from 1) of the document: its lines, or those of object o. */
static void explain_part(Model *M, Buf *b, int line, const Object *o)
{
	char *out = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&out, &n);
	if (!f) xoom();
	explain_model(M, f);
	fclose(f);
	char *head = o ? xprintf("object %s:", o->name) : xprintf("%s:%d: ", ((Source *)sources.v[S.file])->path, line);
	int in = 0;
	for (char *l = out, *next; l && *l; l = next) {
		next = strchr(l, '\n');
		if (next) *next++ = '\0';
		if (!strncmp(l, head, strlen(head))) in = 1, l += o ? 0 : strlen(head);
		else if (l[0] != ' ') in = 0;
		if (in) jbuf_printf(b, "%s%s\n", b->n ? "\n" : "", l);
	}
	free(out);
}

/* A property, temporary or global for hover: what it is, its unit, what determines it. */
static void describe_var(Buf *b, Var *v)
{
	Var *r = sema_canon(v);
	if (v->kind == V_PROP) jbuf_printf(b, "**%s.%s**: ", v->obj->name, v->name);
	else if (v->kind == V_TEMP) jbuf_printf(b, "**%s** (of %s): ", v->name, v->obj ? v->obj->name : "a rule");
	else jbuf_printf(b, "**%s** (%s): ", v->name, v->kind == V_TIME ? "time" : "global");
	jbuf_puts(b, v->isvec ? "vector" : "scalar");
	if (r->dimk == DK_KNOWN) {
		if (dims_none(r->dim)) jbuf_puts(b, ", dimensionless");
		else jbuf_printf(b, ", unit `%s`", dims_unit(r->dim));
	}
	if (v->kind == V_TIME) return;
	if (v->kind == V_PROP && v->obj->dropped) jbuf_puts(b, "\n\nleft out: nothing watched depends on its object");
	else if (r->state) jbuf_printf(b, "\n\nstate variable, integrated (its derivative: line %d)", r->deriv ? r->deriv->st->loc.line : 0);
	else if (r->det) jbuf_printf(b, "\n\ncomputed by the rule on line %d: solves for %s", r->det->st->loc.line, r->det->why ? r->det->why : v->name);
	else jbuf_puts(b, "\n\nconstant");
}

/* What the name at params' position of d stands for in its model: an object (*o), or a variable (*v),
   or neither (a keyword: *kw set); 0 if the text has errors or there is no name there. *line: the
   position's line (from 0). */
static int lookup(Doc *d, const Json *params, Model **M, Object **o, Var **v, int *kw, int *line)
{
	char *name = NULL, *qual = NULL, *bound = NULL;
	*M = model_of(d), *o = NULL, *v = NULL, *kw = 0;
	if (!*M || !word_at(d, json_get(params, "position"), &name, &qual, &bound, line)) return 0;
	*o = qual ? NULL : object_named(*M, name);
	*v = *o ? NULL : var_named(*M, name, qual, bound);
	*kw = lex_keyword(name, strlen(name)) != 0;
	free(name);
	free(qual);
	free(bound);
	return 1;
}

/* The location of loc as LSP JSON: in the document, or in another file (a kind's default, in its `using` file). */
static void buf_location(Buf *b, Doc *d, Loc l)
{
	jbuf_puts(b, "{\"uri\":");
	Source *src = sources.v[l.file];
	if (l.file == S.file) {
		jbuf_string(b, d->uri, strlen(d->uri));
	} else {
		char *real = realpath(src->path, NULL);
		buf_uri(b, real ? real : src->path);
		free(real);
	}
	jbuf_puts(b, ",\"range\":");
	buf_range(b, src->text, src->len, l.line, l.col);
	jbuf_puts(b, "}");
}

/* Answers textDocument/hover (def 0: what the name is, as Markdown) or textDocument/definition (def 1:
   where it is defined); null where there is nothing to say. */
static void hover_or_definition(Doc *d, const Json *id, const Json *params, int def)
{
	Model *M;
	Object *o;
	Var *v;
	int kw, line;
	Buf b = { 0 };
	if (lookup(d, params, &M, &o, &v, &kw, &line)) {
		if (def && o) buf_location(&b, d, o->loc);
		else if (def && v && v->kind != V_TIME && v->loc.line > 0) buf_location(&b, d, v->loc);
		else if (!def && o) explain_part(M, &b, 0, o);
		else if (!def && v) describe_var(&b, v);
		else if (!def && kw) explain_part(M, &b, line + 1, NULL);
	}
	if (b.n && !def) {
		Buf r = { 0 };
		jbuf_puts(&r, "{\"contents\":{\"kind\":\"markdown\",\"value\":");
		jbuf_string(&r, b.s, b.n);
		jbuf_puts(&r, "}}");
		free(b.s);
		b = r;
	}
	respond(id, b.n ? b.s : "null", 0, NULL);
	free(b.s);
}

/* ---- the protocol ---- */

/* Gives d the text of string j and publishes its diagnostics. */
static void set_text(Doc *d, const Json *j)
{
	free(d->text);
	d->text = xmalloc(j->len + 1);
	memcpy(d->text, j->str, j->len + 1);
	d->len = j->len;
	d->gen = ++S.gen;
	publish(d);
}

static void free_doc(Doc *d)
{
	free(d->uri);
	free(d->path);
	free(d->text);
	free(d);
}

static void open_doc(const Json *params)
{
	const char *uri = json_str(json_path(params, "textDocument", "uri", NULL));
	const Json *text = json_path(params, "textDocument", "text", NULL);
	if (!uri || !text || text->k != J_STR) return;
	Doc *d = find_doc(uri);
	if (!d) {
		d = xcalloc(1, sizeof *d);
		d->uri = xmalloc(strlen(uri) + 1);
		strcpy(d->uri, uri);
		d->path = uri_path(uri);
		d->next = S.docs;
		S.docs = d;
	}
	set_text(d, text);
}

static void change_doc(const Json *params)
{
	const char *uri = json_str(json_path(params, "textDocument", "uri", NULL));
	Json *ch = json_get(params, "contentChanges");
	Doc *d = uri ? find_doc(uri) : NULL;
	if (!d || !ch || ch->k != J_ARR) return;
	const Json *last = NULL;
	for (Json *c = ch->kids; c; c = c->next)
		if (json_get(c, "text") && json_get(c, "text")->k == J_STR && !json_get(c, "range")) last = json_get(c, "text");
	if (last) set_text(d, last);
}

static void close_doc(const Json *params)
{
	const char *uri = json_str(json_path(params, "textDocument", "uri", NULL));
	for (Doc **p = &S.docs; uri && *p; p = &(*p)->next) {
		Doc *d = *p;
		if (strcmp(d->uri, uri)) continue;
		Buf b = { 0 };
		diagnostics_head(&b, d);
		jbuf_puts(&b, "]}}");
		send(&b);
		free(b.s);
		if (S.doc == d) S.doc = NULL, S.model = NULL;
		*p = d->next;
		free_doc(d);
		return;
	}
}

/* Handles one message; 1 when it was `exit`. */
static int handle(const Json *m)
{
	const Json *id = json_get(m, "id");
	const char *method = json_str(json_get(m, "method"));
	const Json *params = json_get(m, "params");
	if (id && id->k != J_NUM && id->k != J_STR) id = NULL;
	if (!method) {
		if (!json_get(m, "result") && !json_get(m, "error")) respond(id, NULL, -32600, "not a request: no method");
		return 0; /* a response to a request of ours: none are sent */
	}
	if (!strcmp(method, "exit")) return 1;
	if (!strcmp(method, "initialize")) {
		respond(id, "{\"capabilities\":{\"textDocumentSync\":{\"openClose\":true,\"change\":1},\"hoverProvider\":true,"
		            "\"definitionProvider\":true},\"serverInfo\":{\"name\":\"csfc\",\"version\":\"" CSF_VERSION_STRING "\"}}",
		        0, NULL);
	} else if (!strcmp(method, "shutdown")) {
		S.shutdown = 1;
		respond(id, "null", 0, NULL);
	} else if (!strcmp(method, "textDocument/didOpen")) {
		open_doc(params);
	} else if (!strcmp(method, "textDocument/didChange")) {
		change_doc(params);
	} else if (!strcmp(method, "textDocument/didClose")) {
		close_doc(params);
	} else if (!strcmp(method, "textDocument/hover") || !strcmp(method, "textDocument/definition")) {
		const char *uri = json_str(json_path(params, "textDocument", "uri", NULL));
		Doc *d = uri ? find_doc(uri) : NULL;
		if (!d) respond(id, NULL, -32602, "no open document with that uri");
		else hover_or_definition(d, id, params, method[13] == 'd');
	} else if (id) {
		Buf msg = { 0 };
		jbuf_printf(&msg, "csfc --lsp does not know the method '%s'", method);
		respond(id, NULL, -32601, msg.s);
		free(msg.s);
	}
	return 0;
}

int lsp_main(const char *stdlib, char **incdirs, int nincdirs, int units)
{
	S.nincdirs = nincdirs, S.units = units;
	/* the standard library's path and the -I directories outlive the arena, which every compilation
	   releases (find_stdlib's path is the arena's) */
	char *lib = stdlib ? strcpy(xmalloc(strlen(stdlib) + 1), stdlib) : NULL;
	S.stdlib = lib;
	S.incdirs = xcalloc((size_t)nincdirs + 1, sizeof *S.incdirs);
	if (nincdirs) memcpy(S.incdirs, incdirs, (size_t)nincdirs * sizeof *incdirs);
	size_t n;
	char *body;
	while ((body = read_message(&n))) {
		Json *m = json_parse(body, n);
		free(body);
		int done = 0;
		if (!m) respond(NULL, NULL, -32700, "the message is not JSON");
		else if (m->k != J_OBJ) respond(NULL, NULL, -32600, "a message is a JSON object");
		else done = handle(m);
		json_free(m);
		if (done) break;
	}
	while (S.docs) {
		Doc *d = S.docs;
		S.docs = d->next;
		free_doc(d);
	}
	free(S.incdirs);
	free(lib);
	return S.shutdown ? 0 : 1;
}
