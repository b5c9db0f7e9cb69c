/*
 * json.c - a JSON reader and writer for csfc --lsp (json.h): RFC 8259,
 * recursive descent with a depth limit, strings decoded to UTF-8.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "json.h"

typedef struct Reader { const char *p, *end; int depth; } Reader;

static void skip_ws(Reader *r)
{
	while (r->p < r->end && (*r->p == ' ' || *r->p == '\t' || *r->p == '\n' || *r->p == '\r')) r->p++;
}

static Json *new_value(JsonKind k)
{
	Json *j = xcalloc(1, sizeof *j);
	j->k = k;
	return j;
}

/* Four hex digits at r->p into *u; 0 on success. */
static int hex4(Reader *r, unsigned *u)
{
	if (r->end - r->p < 4) return -1;
	*u = 0;
	for (int i = 0; i < 4; i++) {
		char c = *r->p++;
		int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
		if (d < 0) return -1;
		*u = *u << 4 | (unsigned)d;
	}
	return 0;
}

static void put_utf8(Buf *b, unsigned u)
{
	char c[4];
	size_t n;
	if (u < 0x80) c[0] = (char)u, n = 1;
	else if (u < 0x800) c[0] = (char)(0xC0 | u >> 6), c[1] = (char)(0x80 | (u & 63)), n = 2;
	else if (u < 0x10000)
		c[0] = (char)(0xE0 | u >> 12), c[1] = (char)(0x80 | (u >> 6 & 63)), c[2] = (char)(0x80 | (u & 63)), n = 3;
	else
		c[0] = (char)(0xF0 | u >> 18), c[1] = (char)(0x80 | (u >> 12 & 63)), c[2] = (char)(0x80 | (u >> 6 & 63)),
		c[3] = (char)(0x80 | (u & 63)), n = 4;
	jbuf_add(b, c, n);
}

/* A string at r->p (just past its opening quote) into j; 0 on success. */
static int read_string(Reader *r, Json *j)
{
	Buf b = { 0 };
	for (;;) {
		if (r->p >= r->end) goto bad;
		unsigned char c = (unsigned char)*r->p++;
		if (c == '"') break;
		if (c < 0x20) goto bad;
		if (c != '\\') {
			jbuf_add(&b, (const char *)&c, 1);
			continue;
		}
		if (r->p >= r->end) goto bad;
		char e = *r->p++;
		const char *plain = strchr("\"\\/bfnrt", e);
		if (e && plain) {
			char out = "\"\\/\b\f\n\r\t"[plain - "\"\\/bfnrt"];
			jbuf_add(&b, &out, 1);
		} else if (e == 'u') {
			unsigned u, lo;
			if (hex4(r, &u)) goto bad;
			if (u >= 0xD800 && u < 0xDC00) { /* a surrogate pair */
				if (r->end - r->p < 6 || r->p[0] != '\\' || r->p[1] != 'u') goto bad;
				r->p += 2;
				if (hex4(r, &lo) || lo < 0xDC00 || lo > 0xDFFF) goto bad;
				u = 0x10000 + ((u - 0xD800) << 10) + (lo - 0xDC00);
			} else if (u >= 0xDC00 && u < 0xE000) {
				goto bad;
			}
			put_utf8(&b, u);
		} else {
			goto bad;
		}
	}
	jbuf_add(&b, "", 1); /* the NUL, not counted */
	j->str = b.s;
	j->len = b.n - 1;
	return 0;
bad:
	free(b.s);
	return -1;
}

static Json *read_value(Reader *r);

/* The elements of an array or the members of an object, r->p just past its bracket. */
static int read_items(Reader *r, Json *j, int obj)
{
	Json **tail = &j->kids;
	skip_ws(r);
	if (r->p < r->end && *r->p == (obj ? '}' : ']')) {
		r->p++;
		return 0;
	}
	for (;;) {
		char *key = NULL;
		if (obj) {
			Json k = { 0 };
			skip_ws(r);
			if (r->p >= r->end || *r->p != '"') return -1;
			r->p++;
			if (read_string(r, &k)) return -1;
			key = k.str;
			skip_ws(r);
			if (r->p >= r->end || *r->p != ':') {
				free(key);
				return -1;
			}
			r->p++;
		}
		Json *v = read_value(r);
		if (!v) {
			free(key);
			return -1;
		}
		v->key = key;
		*tail = v;
		tail = &v->next;
		skip_ws(r);
		if (r->p >= r->end) return -1;
		char c = *r->p++;
		if (c == (obj ? '}' : ']')) return 0;
		if (c != ',') return -1;
	}
}

static Json *read_number(Reader *r)
{
	const char *s = r->p;
	if (r->p < r->end && *r->p == '-') r->p++;
	if (r->p >= r->end || !(*r->p >= '0' && *r->p <= '9')) return NULL;
	if (*r->p == '0') r->p++;
	else while (r->p < r->end && *r->p >= '0' && *r->p <= '9') r->p++;
	if (r->p < r->end && *r->p == '.') {
		r->p++;
		if (r->p >= r->end || !(*r->p >= '0' && *r->p <= '9')) return NULL;
		while (r->p < r->end && *r->p >= '0' && *r->p <= '9') r->p++;
	}
	if (r->p < r->end && (*r->p == 'e' || *r->p == 'E')) {
		r->p++;
		if (r->p < r->end && (*r->p == '+' || *r->p == '-')) r->p++;
		if (r->p >= r->end || !(*r->p >= '0' && *r->p <= '9')) return NULL;
		while (r->p < r->end && *r->p >= '0' && *r->p <= '9') r->p++;
	}
	if (r->p - s > 64) return NULL;
	char tmp[72];
	memcpy(tmp, s, (size_t)(r->p - s));
	tmp[r->p - s] = '\0';
	Json *j = new_value(J_NUM);
	j->num = strtod(tmp, NULL);
	return j;
}

static Json *read_value(Reader *r)
{
	skip_ws(r);
	if (r->p >= r->end) return NULL;
	static const struct { const char *word; JsonKind k; } words[] = { { "null", J_NULL }, { "false", J_FALSE }, { "true", J_TRUE } };
	for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
		size_t n = strlen(words[i].word);
		if ((size_t)(r->end - r->p) >= n && !memcmp(r->p, words[i].word, n)) {
			r->p += n;
			return new_value(words[i].k);
		}
	}
	char c = *r->p;
	if (c == '"') {
		r->p++;
		Json *j = new_value(J_STR);
		if (read_string(r, j)) {
			free(j);
			return NULL;
		}
		return j;
	}
	if (c == '[' || c == '{') {
		if (++r->depth > JSON_MAX_DEPTH) return NULL;
		r->p++;
		Json *j = new_value(c == '[' ? J_ARR : J_OBJ);
		if (read_items(r, j, c == '{')) {
			json_free(j);
			return NULL;
		}
		r->depth--;
		return j;
	}
	return read_number(r);
}

Json *json_parse(const char *text, size_t len)
{
	Reader r = { text, text + len, 0 };
	Json *j = read_value(&r);
	skip_ws(&r);
	if (j && r.p != r.end) {
		json_free(j);
		return NULL;
	}
	return j;
}

void json_free(Json *j)
{
	while (j) {
		Json *next = j->next;
		json_free(j->kids);
		free(j->str);
		free(j->key);
		free(j);
		j = next;
	}
}

Json *json_get(const Json *j, const char *key)
{
	if (!j || j->k != J_OBJ) return NULL;
	for (Json *m = j->kids; m; m = m->next)
		if (!strcmp(m->key, key)) return m;
	return NULL;
}

Json *json_path(const Json *j, ...)
{
	va_list ap;
	va_start(ap, j);
	const char *k;
	while (j && (k = va_arg(ap, const char *))) j = json_get(j, k);
	va_end(ap);
	return (Json *)j;
}

const char *json_str(const Json *j) { return j && j->k == J_STR ? j->str : NULL; }

int json_int(const Json *j, int def)
{
	if (!j || j->k != J_NUM || !(j->num >= -2147483648.0 && j->num <= 2147483647.0) || j->num != floor(j->num)) return def;
	return (int)j->num;
}

/* ---- writing ---- */

void jbuf_add(Buf *b, const char *s, size_t n)
{
	if (b->n + n + 1 > b->cap) {
		size_t cap = b->cap ? b->cap : 256;
		while (cap < b->n + n + 1) cap *= 2;
		b->s = xrealloc(b->s, cap);
		b->cap = cap;
	}
	memcpy(b->s + b->n, s, n);
	b->n += n;
	b->s[b->n] = '\0';
}

void jbuf_puts(Buf *b, const char *s) { jbuf_add(b, s, strlen(s)); }

void jbuf_printf(Buf *b, const char *fmt, ...)
{
	va_list ap, aq;
	va_start(ap, fmt);
	va_copy(aq, ap);
	int n = vsnprintf(NULL, 0, fmt, aq);
	va_end(aq);
	if (n > 0) {
		char *tmp = xmalloc((size_t)n + 1);
		vsnprintf(tmp, (size_t)n + 1, fmt, ap);
		jbuf_add(b, tmp, (size_t)n);
		free(tmp);
	}
	va_end(ap);
}

void jbuf_string(Buf *b, const char *s, size_t n)
{
	jbuf_add(b, "\"", 1);
	for (size_t i = 0; i < n;) {
		unsigned char c = (unsigned char)s[i];
		if (c == '"' || c == '\\') {
			char e[2] = { '\\', (char)c };
			jbuf_add(b, e, 2);
			i++;
		} else if (c < 0x20) {
			const char *esc = c == '\n' ? "\\n" : c == '\t' ? "\\t" : c == '\r' ? "\\r" : NULL;
			if (esc) jbuf_puts(b, esc);
			else jbuf_printf(b, "\\u%04x", c);
			i++;
		} else if (c < 0x80) {
			jbuf_add(b, (const char *)&c, 1);
			i++;
		} else {
			int k = lex_utf8_len((const unsigned char *)s + i, (const unsigned char *)s + n);
			if (k > 0) jbuf_add(b, s + i, (size_t)k), i += (size_t)k;
			else jbuf_puts(b, "\xEF\xBF\xBD"), i++;
		}
	}
	jbuf_add(b, "\"", 1);
}

void jbuf_value(Buf *b, const Json *j)
{
	switch (j->k) {
	case J_NULL: jbuf_puts(b, "null"); break;
	case J_FALSE: jbuf_puts(b, "false"); break;
	case J_TRUE: jbuf_puts(b, "true"); break;
	case J_NUM: jbuf_printf(b, "%.17g", j->num); break;
	case J_STR: jbuf_string(b, j->str, j->len); break;
	case J_ARR:
	case J_OBJ:
		jbuf_add(b, j->k == J_ARR ? "[" : "{", 1);
		for (Json *m = j->kids; m; m = m->next) {
			if (m != j->kids) jbuf_add(b, ",", 1);
			if (j->k == J_OBJ) {
				jbuf_string(b, m->key, strlen(m->key));
				jbuf_add(b, ":", 1);
			}
			jbuf_value(b, m);
		}
		jbuf_add(b, j->k == J_ARR ? "]" : "}", 1);
		break;
	}
}
