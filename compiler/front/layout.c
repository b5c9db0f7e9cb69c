/*
 * layout.c - the token layer between the scanner and the parser.
 *
 * Three jobs, each small:
 *  - indentation: a stack of indentation widths (as CPython's tokenizer);
 *    a deeper line after a line ending in ':' opens a block (INDENT), a
 *    shallower line closes blocks (DEDENT). Blank lines never matter.
 *  - `using FILE`: textual inclusion. The named file is found next to the
 *    including file, then in each -I directory, then in the standard
 *    library; its tokens are spliced in. A file already being included is
 *    a cycle (an error); a file included before is not included again.
 *  - unit literals: a unit name, 1/ and one, or either in parentheses,
 *    directly after a number or a ')' , starts a unit expression (`m/s^2`,
 *    `kg*m/(s^2)`, `1/s`, `(1/s)`);
 *    it becomes one UNIT token carrying its SI factor and dimension.
 *    The name `atol` after the end of a value (a number, a unit, a name, a
 *    ')') is the word ATOL of a property line's `atol A`; anywhere else it
 *    is a name.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "csfc.h"
#include "ast.h"
#include "parse.h"

#define MAX_INCLUDE 64
#define QSIZE 16 /* the unit reader looks up to 6 tokens ahead */

struct Parser {
	Lexer lex[MAX_INCLUDE];
	char *real[MAX_INCLUDE];
	Loc using_loc[MAX_INCLUDE];
	int depth;
	Vec included; /* realpaths of files included (or being included) */
	int indents[1024];
	int nind;
	int dedents;       /* DEDENT tokens owed */
	Token q[QSIZE];    /* lookahead of raw tokens from the current lexer */
	int qn;
	int last;          /* kind of the last token given to the parser, -1 at start */
	int last_colon;    /* the last line given ended with ':' */
	Token pending;     /* the real token held back behind INDENT/DEDENT */
	int has_pending;
	int at_end;        /* the main file has ended: close blocks, then END */
	Token end;
	Stmt *head, *tail;
	const char *text;  /* spelling of the last token given */
	int skip;          /* drop the block after the line just ended (a syntax error) ... */
	int skip_indent;   /* ... the lines deeper than this, and the elif and else lines at it */
	Loc bad;           /* the last line whose indentation was reported */
};

static char *real_path(const char *p)
{
	char buf[PATH_MAX];
	return realpath(p, buf) ? xstrdup(buf) : xstrdup(p);
}

Parser *layout_new(int file)
{
	Parser *P = xalloc(sizeof *P);
	lex_init(&P->lex[0], file);
	P->real[0] = real_path(((Source *)sources.v[file])->path);
	vec_push(&P->included, P->real[0]);
	P->depth = 1;
	P->indents[0] = 0;
	P->nind = 1;
	P->last = NEWLINE;
	return P;
}

Stmt *layout_result(Parser *P) { return P->head; }

void layout_append(Parser *P, Stmt *s)
{
	if (P->tail) P->tail->next = s;
	else P->head = s;
	P->tail = s;
	while (P->tail->next) P->tail = P->tail->next;
}

const char *layout_token_text(Parser *P) { return P->text; }

/* The parser recovered from a syntax error at the end of a line: the block indented under it,
 * and the `elif` and `else` lines that continue it with their blocks, belong to the broken
 * line and are dropped unread (their errors would be the same mistake again). */
void layout_skip_block(Parser *P)
{
	P->skip = 1;
	P->skip_indent = P->indents[P->nind - 1];
}

/* Was an error on l's line reported already (its indentation)? */
int layout_reported(Parser *P, Loc l) { return P->bad.line && P->bad.file == l.file && P->bad.line == l.line; }

/* Reports a bad indentation at l, once for its line. */
static void indent_error(Parser *P, Loc l, const char *msg)
{
	error_at(l, "%s", msg);
	P->bad = l;
}

static Token *peek(Parser *P, int k)
{
	while (P->qn <= k) lex_next(&P->lex[P->depth - 1], &P->q[P->qn++]);
	return &P->q[k];
}

static Token take(Parser *P)
{
	Token t = *peek(P, 0);
	memmove(P->q, P->q + 1, (size_t)(P->qn - 1) * sizeof(Token));
	P->qn--;
	return t;
}

static int is_unit_name(Token *t)
{
	Unit u;
	return t->kind == IDENT && !t->bol && unit_lookup(t->text, &u);
}

/* The 1 of a unit such as 1/s (as CSF prints one): a NUMBER token spelt "1". */
static int is_one(Token *t)
{
	return t->kind == NUMBER && !t->bol && t->text && strcmp(t->text, "1") == 0;
}

/* A unit name at token k, or '(' and one. */
static int starts_name(Parser *P, int k)
{
	return is_unit_name(peek(P, k)) || (peek(P, k)->kind == '(' && is_unit_name(peek(P, k + 1)));
}

/* Is token k the first of 1/UNIT? */
static int starts_one_per(Parser *P, int k)
{
	return is_one(peek(P, k)) && peek(P, k + 1)->kind == '/' && starts_name(P, k + 2);
}

/* Does a unit factor start at token k: a name, 1/UNIT, or either in parentheses? */
static int starts_factor(Parser *P, int k)
{
	return starts_name(P, k) || starts_one_per(P, k) || (peek(P, k)->kind == '(' && starts_one_per(P, k + 1));
}

/* The spelling of a unit being read, grown by doubling (a unit of many factors is read in linear time). */
typedef struct UnitText { char *s; size_t n, cap; } UnitText;

static void ut_add(UnitText *t, const char *x)
{
	size_t k = strlen(x);
	if (t->n + k + 1 > t->cap) {
		size_t cap = t->cap ? t->cap : 32;
		while (cap < t->n + k + 1) cap *= 2;
		char *s = xalloc(cap);
		if (t->n) memcpy(s, t->s, t->n);
		t->s = s;
		t->cap = cap;
	}
	memcpy(t->s + t->n, x, k + 1);
	t->n += k;
}

/* The largest dimension exponent a unit may have (m^64), and the deepest nesting of its parentheses. */
#define UNIT_MAX_EXP 64
#define UNIT_MAX_NEST 32

/* The dimension of u := u * v^k, with the exponents checked for overflow, and u's factor (which the
 * caller has set) checked for range; reports at l, once per unit. */
static void unit_combine(Unit *u, const Unit *v, int k, Loc l, int *bad)
{
	int big = 0;
	for (int d = 0; d < CSF_NDIM; d++) {
		int e = u->dim[d] + k * v->dim[d];
		if (e > UNIT_MAX_EXP || e < -UNIT_MAX_EXP) big = 1;
		else u->dim[d] = (signed char)e;
	}
	if (*bad) return;
	if (big) error_at(l, "the unit's dimension has an exponent beyond %d: too large to be a unit", UNIT_MAX_EXP);
	else if (!isfinite(u->factor) || u->factor == 0)
		error_at(l, "the unit's factor is beyond the range of a double: too large or too small to be a unit");
	else return;
	*bad = 1;
}

static void unit_expr(Parser *P, Unit *u, UnitText *text, int nest, int *bad);

/* factor := name | 1 | '(' unit ')' , then an optional ^ [-] integer */
static void unit_factor(Parser *P, Unit *u, UnitText *text, int nest, int *bad)
{
	Token t = take(P);
	Unit base = { 1, { 0 } };
	if (t.kind == '(') {
		ut_add(text, "(");
		if (nest == UNIT_MAX_NEST) {
			if (!*bad) error_at(t.loc, "parentheses in a unit nested more than %d deep", UNIT_MAX_NEST);
			*bad = 1;
		} else {
			unit_expr(P, &base, text, nest + 1, bad);
		}
		if (peek(P, 0)->kind == ')') {
			take(P);
			ut_add(text, ")");
		} else if (!*bad) {
			error_at(peek(P, 0)->loc, "expected ')' in unit");
			*bad = 1;
		}
	} else {
		if (t.kind != NUMBER) unit_lookup(t.text, &base); /* else the 1 of 1/s */
		ut_add(text, t.text);
	}
	int neg = peek(P, 1)->kind == '-';
	Token *n = peek(P, neg ? 2 : 1);
	int x = 1;
	if (peek(P, 0)->kind == '^' && n->kind == NUMBER) {
		take(P);
		if (neg) take(P);
		Token e = take(P);
		double k = neg ? -e.num : e.num;
		if (k != floor(k) || fabs(k) > 16) {
			error_at(e.loc, "a unit exponent must be a whole number between -16 and 16");
			k = 1;
		}
		x = (int)k;
		ut_add(text, "^");
		if (neg) ut_add(text, "-");
		ut_add(text, e.text);
	}
	*u = (Unit){ x == 1 ? base.factor : pow(base.factor, x), { 0 } };
	unit_combine(u, &base, x, t.loc, bad);
}

static void unit_expr(Parser *P, Unit *u, UnitText *text, int nest, int *bad)
{
	unit_factor(P, u, text, nest, bad);
	while ((peek(P, 0)->kind == '*' || peek(P, 0)->kind == '/') && starts_factor(P, 1)) {
		Token op = take(P);
		Unit v;
		ut_add(text, op.kind == '*' ? "*" : "/");
		unit_factor(P, &v, text, nest, bad);
		u->factor = op.kind == '*' ? u->factor * v.factor : u->factor / v.factor;
		unit_combine(u, &v, op.kind == '*' ? 1 : -1, op.loc, bad);
	}
}

/* Finds the file a `using` names. Returns a path or NULL. */
static char *find_include(Parser *P, const char *name)
{
	size_t n = strlen(name);
	const char *ext = n >= 4 && strcmp(name + n - 4, ".csf") == 0 ? "" : ".csf";
	if (name[0] == '/') {
		char *p = xprintf("%s%s", name, ext);
		return access(p, R_OK) == 0 ? p : NULL;
	}
	Vec dirs = { 0 };
	char *cur = xstrdup(((Source *)sources.v[P->lex[P->depth - 1].file])->path);
	char *slash = strrchr(cur, '/');
	vec_push(&dirs, slash ? (slash[1] = '\0', cur) : "");
	for (int i = 0; i < opts.incdirs.n; i++) vec_push(&dirs, opts.incdirs.v[i]);
	if (opts.stdlib) vec_push(&dirs, (void *)opts.stdlib);
	for (int i = 0; i < dirs.n; i++) {
		const char *d = dirs.v[i];
		size_t dl = strlen(d);
		char *p = xprintf("%s%s%s%s", d, !dl || d[dl - 1] == '/' ? "" : "/", name, ext);
		if (access(p, R_OK) == 0) return p;
	}
	return NULL;
}

static void do_using(Parser *P, Token *u)
{
	if (!u->text[0]) {
		error_at(u->loc, "'using' needs a file name");
		return;
	}
	char *path = find_include(P, u->text);
	if (!path) {
		error_at(u->loc, "cannot find '%s' for 'using' (searched next to this file, in the -I directories and %s)",
		         u->text, opts.stdlib ? "in the standard library" : "found no standard library");
		return;
	}
	char *rp = real_path(path);
	for (int i = 0; i < P->depth; i++)
		if (strcmp(P->real[i], rp) == 0) {
			error_at(u->loc, "include cycle: '%s' is already being included", path);
			for (int k = P->depth - 1; k > 0; k--) note_at(P->using_loc[k], "included from here");
			return;
		}
	for (int i = 0; i < P->included.n; i++)
		if (strcmp(P->included.v[i], rp) == 0) return; /* included before: once is enough */
	if (P->depth == MAX_INCLUDE) {
		error_at(u->loc, "'using' nested more than %d deep", MAX_INCLUDE);
		return;
	}
	int f = src_load(path);
	if (f < 0) {
		error_at(u->loc, "cannot read '%s': %s", path, strerror(errno));
		return;
	}
	vec_push(&P->included, rp);
	Lexer *L = &P->lex[P->depth];
	lex_init(L, f);
	P->real[P->depth] = rp;
	P->using_loc[P->depth] = u->loc;
	P->depth++;
}

/* Next raw token, with `using` and the ends of included files handled. */
static Token next_raw(Parser *P)
{
	for (;;) {
		Token t = take(P);
		if (t.kind == USING) {
			Token nl = take(P); /* the NEWLINE (or END) after the path */
			if (nl.kind != NEWLINE && nl.kind != END) error_at(nl.loc, "unexpected text after 'using'");
			do_using(P, &t);
			continue;
		}
		if (t.kind == END && P->depth > 1) {
			P->depth--;
			t.kind = NEWLINE; /* an included file ends its last line */
			t.bol = 0;
		}
		return t;
	}
}

/* The next token for the parser, before unit literals are recognised. */
static Token next_token(Parser *P)
{
	Token t;
	if (P->dedents) {
		P->dedents--;
		t = P->pending;
		t.kind = DEDENT;
		t.text = NULL;
		t.end_col = t.loc.col;
		return t;
	}
	if (P->has_pending) {
		P->has_pending = 0;
		return P->pending;
	}
	for (;;) {
		t = P->at_end ? P->end : next_raw(P);
		if (t.kind == NEWLINE && P->last == NEWLINE) continue; /* no empty lines */
		if (t.kind == END) {
			P->at_end = 1;
			P->end = t;
			if (P->last != NEWLINE && P->last != DEDENT) t.kind = NEWLINE;
			else if (P->nind > 1) P->nind--, t.kind = DEDENT;
			return t;
		}
		if (!t.bol) return t;
		if (P->skip && (t.indent > P->skip_indent || (t.indent == P->skip_indent && (t.kind == ELIF || t.kind == ELSE)))) {
			while (t.kind != NEWLINE && t.kind != END) t = next_raw(P);
			if (t.kind == END) P->end = t, P->at_end = 1;
			continue;
		}
		P->skip = 0;
		int top = P->indents[P->nind - 1];
		if (t.indent > top) {
			if (!P->last_colon || P->nind == (int)(sizeof P->indents / sizeof P->indents[0])) {
				indent_error(P, t.loc, "unexpected indentation");
				return t;
			}
			P->indents[P->nind++] = t.indent;
		} else if (t.indent < top) {
			int n = 0;
			while (P->nind > 1 && t.indent < P->indents[P->nind - 1]) P->nind--, n++;
			if (t.indent != P->indents[P->nind - 1]) indent_error(P, t.loc, "indentation does not match any enclosing block");
			P->dedents = n - 1;
		} else {
			return t;
		}
		P->pending = t;
		P->pending.bol = 0;
		P->has_pending = 1;
		t.kind = t.indent > top ? INDENT : DEDENT;
		t.text = NULL;
		t.end_col = t.loc.col;
		return t;
	}
}

/* The spelling of a one-character token (the text of a syntax error), without a string per token. */
static const char *punct_text(int c)
{
	static char text[256][2];
	text[c][0] = (char)c;
	return text[c];
}

int yylex(YYSTYPE *lval, YYLoc *lloc, Parser *P)
{
	Token t = next_token(P);
	if ((P->last == NUMBER || P->last == ')') && !t.bol && (t.kind == IDENT || t.kind == NUMBER || t.kind == '(')) {
		/* put t back: does it start a unit expression? */
		memmove(P->q + 1, P->q, (size_t)P->qn * sizeof(Token));
		P->q[0] = t;
		P->qn++;
		if (!starts_factor(P, 0)) {
			t = take(P);
		} else {
			Unit un;
			UnitText text = { 0 };
			int bad = 0;
			unit_expr(P, &un, &text, 0, &bad);
			t.kind = UNIT;
			t.unit = un;
			t.text = text.s;
			lval->unit = (UnitTok){ un, text.s, t.loc };
		}
	}
	if (t.kind == IDENT && !t.bol && !strcmp(t.text, "atol") &&
	    (P->last == NUMBER || P->last == UNIT || P->last == IDENT || P->last == DOLLAR || P->last == ')'))
		t.kind = ATOL;
	if (t.kind == NEWLINE) P->last_colon = P->last == ':';
	P->last = t.kind;
	P->text = t.text ? t.text : t.kind > 0 && t.kind < 256 ? punct_text(t.kind) : NULL;
	lloc->file = t.loc.file;
	lloc->first_line = lloc->last_line = t.loc.line;
	lloc->first_column = t.loc.col;
	lloc->last_column = t.end_col > t.loc.col ? t.end_col : t.loc.col + 1;
	switch (t.kind) {
	case NUMBER: lval->num = t.num; break;
	case IDENT: case PROTECTED: case STRING: lval->str = t.text; break;
	case DOLLAR: lval->n = t.n; break;
	default: break;
	}
	return t.kind;
}
