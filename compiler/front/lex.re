/*
 * lex.re - the raw CSF scanner (re2c).
 *
 * Produces one token at a time with its line and column. It knows nothing
 * of indentation blocks or includes: at the start of each non-blank line it
 * measures the indentation (spaces only: a tab there is an error token) and
 * marks the first token with bol/indent; blank and comment-only lines are
 * skipped entirely. layout.c turns indentation into INDENT/DEDENT.
 */
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "csfc.h"
#include "ast.h"
#include "parse.h"

static const struct { const char *s; int tok; } keywords[] = {
	{ "object", OBJECT }, { "def", DEF }, { "global", GLOBAL }, { "rule", RULE }, { "for", FOR },
	{ "if", IF }, { "elif", ELIF }, { "else", ELSE }, { "assert", ASSERT }, { "vector", VECTOR }, { "inc", INC },
	{ "till", TILL }, { "by", BY }, { "watch", WATCH }, { "and", AND }, { "or", OR }, { "not", NOT },
	{ "using", USING }, { "stop", STOP }, { "when", WHEN },
	/* protected names (spec 2.2.3) that no statement uses */
	{ "None", PROTECTED }, { "True", PROTECTED }, { "False", PROTECTED }, { "const", PROTECTED },
	{ "scalar", PROTECTED }, { "start", PROTECTED }, { "step", PROTECTED }, { "Pi", PROTECTED },
};

int lex_keyword(const char *s, size_t n)
{
	for (size_t i = 0; i < sizeof keywords / sizeof keywords[0]; i++)
		if (strlen(keywords[i].s) == n && memcmp(keywords[i].s, s, n) == 0) return keywords[i].tok;
	return 0;
}

void lex_init(Lexer *L, int file)
{
	Source *s = sources.v[file];
	L->file = file;
	L->start = L->cur = L->line_start = s->text;
	L->lim = s->text + s->len;
	L->line = 1;
	L->bol = 1;
}

/* The spellings of names and numbers, one copy per distinct spelling (a scene of 100 000 objects
   spells each object's name five times). */
static Map spellings;

void lex_reset(void) { spellings = (Map){ 0 }; }

static char *intern(const char *tok, size_t n)
{
	char buf[128];
	if (n >= sizeof buf) return xstrndup(tok, n);
	memcpy(buf, tok, n);
	buf[n] = '\0';
	char *s = map_get(&spellings, buf);
	if (!s) {
		s = xstrndup(tok, n);
		map_put(&spellings, s, s);
	}
	return s;
}

static void set_loc(Lexer *L, Token *t, const char *at)
{
	t->loc.file = L->file;
	t->loc.line = L->line;
	t->loc.col = (int)(at - L->line_start) + 1;
}

static void error_tok(Lexer *L, Token *t, const char *at, char *msg)
{
	set_loc(L, t, at);
	t->kind = LEXERROR;
	t->text = msg;
	error_at(t->loc, "%s", msg);
}

int lex_utf8_len(const unsigned char *p, const unsigned char *lim)
{
	int n = p[0] < 0x80 ? 1 : p[0] >= 0xC2 && p[0] <= 0xDF ? 2 : p[0] >= 0xE0 && p[0] <= 0xEF ? 3
	      : p[0] >= 0xF0 && p[0] <= 0xF4 ? 4 : 0;
	if (!n || lim - p < n) return 0;
	for (int i = 1; i < n; i++)
		if ((p[i] & 0xC0) != 0x80) return 0;
	if ((p[0] == 0xE0 && p[1] < 0xA0) || (p[0] == 0xED && p[1] > 0x9F) || (p[0] == 0xF0 && p[1] < 0x90) ||
	    (p[0] == 0xF4 && p[1] > 0x8F))
		return 0;
	return n;
}

/* A control character other than tab, CR and newline. */
static int is_control(unsigned char c) { return (c < 32 && c != '\t' && c != '\r' && c != '\n') || c == 127; }

/* A NUL byte, another control character or invalid UTF-8 at p: the input is not text; one error,
   and the compiler stops. */
static void not_text(Lexer *L, Token *t, const char *p)
{
	unsigned char c = (unsigned char)*p;
	set_loc(L, t, p);
	t->kind = LEXERROR;
	t->text = "not text";
	L->cur = L->lim;
	fatal_at(t->loc, "%s at byte offset %ld: this is not a CSF source (a binary file?)",
	         !c ? "NUL byte" : is_control(c) ? xprintf("control character 0x%02x", c) : "invalid UTF-8",
	         (long)(p - L->start));
}

/* The first control character or invalid UTF-8 in [p, e), or NULL. */
static const char *find_binary(const char *p, const char *e)
{
	while (p < e) {
		int n = is_control((unsigned char)*p) ? 0 : lex_utf8_len((const unsigned char *)p, (const unsigned char *)e);
		if (!n) return p;
		p += n;
	}
	return NULL;
}

/* At the start of a line: skips blank and comment lines, measures indentation. */
static int line_start(Lexer *L, Token *t)
{
	for (;;) {
		const char *p = L->cur;
		int col = 0;
		while (p < L->lim && *p == ' ') p++, col++;
		if (p < L->lim && *p == '\t') {
			/* one error, and the line is left out as if blank: the blocks around it go on, and
			   the parser sees no token it could stumble on (no cascade of errors) */
			set_loc(L, t, p);
			error_at(t->loc, "tabs are not allowed in indentation; indent with spaces");
			while (p < L->lim && *p != '\n') p++;
			if (p >= L->lim) {
				L->cur = p;
				return 0;
			}
			L->cur = p + 1;
			L->line++;
			L->line_start = L->cur;
			continue;
		}
		const char *q = p;
		while (q < L->lim && (*q == ' ' || *q == '\t' || *q == '\r')) q++;
		if (q < L->lim && *q == '#')
			while (q < L->lim && *q != '\n') q++;
		if (q >= L->lim) {
			L->cur = q;
			return 0;
		}
		if (*q == '\n') {
			L->cur = q + 1;
			L->line++;
			L->line_start = L->cur;
			continue;
		}
		L->cur = p;
		t->indent = col;
		return 1;
	}
}

void lex_next(Lexer *L, Token *t)
{
	memset(t, 0, sizeof *t);
	if (diag_stop) { /* a fatal error, or too many: the input ends here */
		L->cur = L->lim;
		set_loc(L, t, L->cur);
		t->kind = END;
		return;
	}
	if (L->bol) {
		int r = line_start(L, t);
		if (r < 0) return;
		if (r == 1) {
			t->bol = 1;
			L->bol = 0;
		}
	}
	const char *tok, *YYCURSOR, *YYMARKER = NULL;
	for (;;) {
		tok = YYCURSOR = L->cur;
		if (YYCURSOR >= L->lim) {
			set_loc(L, t, YYCURSOR);
			t->kind = END;
			return;
		}
		/*!re2c
		re2c:define:YYCTYPE = "unsigned char";
		re2c:yyfill:enable = 0;
		re2c:eof = 0;
		re2c:define:YYLIMIT = "L->lim";

		digits = [0-9]+;
		exp = [eE] [+-]? digits;
		number = (digits ("." [0-9]*)? | "." digits) exp?;
		ident = [a-zA-Z_] [a-zA-Z_0-9]*;

		$ { set_loc(L, t, tok); t->kind = END; return; }
		[ \t\r]+ { L->cur = YYCURSOR; continue; }
		"#" [^\n]* { L->cur = YYCURSOR; continue; }
		"\n" {
			set_loc(L, t, tok);
			t->kind = NEWLINE;
			L->cur = YYCURSOR;
			L->line++;
			L->line_start = L->cur;
			L->bol = 1;
			return;
		}
		digits / ".." { /* the A of A..B: an integer, not "A." */
			set_loc(L, t, tok);
			t->kind = NUMBER;
			t->num = strtod(tok, NULL);
			t->text = intern(tok, (size_t)(YYCURSOR - tok));
			goto done;
		}
		number {
			set_loc(L, t, tok);
			t->kind = NUMBER;
			t->num = strtod(tok, NULL);
			t->text = intern(tok, (size_t)(YYCURSOR - tok));
			goto done;
		}
		ident {
			set_loc(L, t, tok);
			size_t n = (size_t)(YYCURSOR - tok);
			t->text = intern(tok, n);
			if (n == 3 && memcmp(tok, "Inf", 3) == 0) { t->kind = NUMBER; t->num = HUGE_VAL; goto done; }
			if (n == 3 && memcmp(tok, "NaN", 3) == 0) { t->kind = NUMBER; t->num = NAN; goto done; }
			int kw = lex_keyword(tok, n);
			t->kind = kw ? kw : IDENT;
			if (kw == USING) {
				const char *p = YYCURSOR, *e;
				while (p < L->lim && (*p == ' ' || *p == '\t')) p++;
				e = p;
				while (e < L->lim && *e != '\n' && *e != '#') e++;
				L->cur = e;
				while (e > p && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r')) e--;
				const char *bad = find_binary(p, e);
				if (bad) { not_text(L, t, bad); return; }
				if (e - p >= 2 && *p == '"' && e[-1] == '"') p++, e--;
				t->text = xstrndup(p, (size_t)(e - p));
				t->end_col = t->loc.col + (int)(L->cur - tok);
				return;
			}
			goto done;
		}
		"\xCF\x80" { /* U+03C0, the spec's spelling of the constant pi (spec 1.1) */
			set_loc(L, t, tok);
			t->kind = IDENT;
			t->text = xstrdup("pi");
			goto done;
		}
		"$" digits {
			set_loc(L, t, tok);
			t->kind = DOLLAR;
			t->n = (int)strtol(tok + 1, NULL, 10);
			t->text = xstrndup(tok, (size_t)(YYCURSOR - tok));
			if (YYCURSOR - tok > 6) { L->cur = YYCURSOR; error_tok(L, t, tok, xstrdup("object number too large")); return; }
			goto done;
		}
		".." { set_loc(L, t, tok); t->kind = DOTDOT; goto done; }
		["] [^"\n]* ["] { /* a string: a data file's name (`from "grains.csv"`) */
			set_loc(L, t, tok);
			t->kind = STRING;
			t->text = xstrndup(tok + 1, (size_t)(YYCURSOR - tok - 2));
			goto done;
		}
		["] [^"\n]* {
			set_loc(L, t, tok);
			L->cur = YYCURSOR;
			error_tok(L, t, tok, xstrdup("a string without its closing '\"'"));
			return;
		}
		"==" { set_loc(L, t, tok); t->kind = EQEQ; goto done; }
		"!=" { set_loc(L, t, tok); t->kind = NE; goto done; }
		"<=" { set_loc(L, t, tok); t->kind = LE; goto done; }
		">=" { set_loc(L, t, tok); t->kind = GE; goto done; }
		[-+*/^()=,.:<>'[\]] { set_loc(L, t, tok); t->kind = (unsigned char)*tok; goto done; }
		* {
			unsigned char c = (unsigned char)*tok;
			int n = is_control(c) ? 0 : lex_utf8_len((const unsigned char *)tok, (const unsigned char *)L->lim);
			if (!n) { not_text(L, t, tok); return; }
			L->cur = tok + n;
			error_tok(L, t, tok, n == 1 ? xprintf("unexpected character '%c'", c)
			                            : xprintf("unexpected character '%.*s'", n, tok));
			return;
		}
		*/
	}
done:
	(void)YYMARKER;
	L->cur = YYCURSOR;
	t->end_col = t->loc.col + (int)(YYCURSOR - tok);
}
