/*
 * csfc.h - shared declarations of the CSF compiler.
 *
 * Pipeline: lex.re (re2c scanner) -> layout.c (indentation, `using`
 * inclusion, unit literals) -> parse.y (bison, builds the AST) -> sema/
 * (pass.c: objects, rule instances, resolution, solving) -> mid/liveness.c
 * (what each section needs) -> back/gen.c and the files it names (bytecode)
 * -> back/emit_c.c (C, with --emit-c).
 * Memory: everything the compiler allocates comes from one arena (xalloc)
 * and is released at exit by arena_free(), but the program's tables and the
 * back end's work arrays (xmalloc, xcalloc, xrealloc: heap memory).
 */
#ifndef CSFC_H
#define CSFC_H

#include <stddef.h>
#include <stdio.h>

#include "csf_int.h"

/* ---- memory ---- */
void *xalloc(size_t n);                 /* zeroed; never returns NULL (xoom on OOM) */
void *xrealloc_arr(void *p, size_t n);  /* grows an xalloc'd array to n bytes (copies) */
char *xstrdup(const char *s);
char *xstrndup(const char *s, size_t n);
char *xprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void arena_free(void);
/* Heap memory for what outlives the arena (csf_prog's tables, freed with csf_prog_free, and
   work arrays freed at once). Never NULL: running out of memory, here or in xalloc, ends in
   xoom, the one place that writes "csfc: out of memory" and exits with status 2. */
void *xmalloc(size_t n);
void *xcalloc(size_t n, size_t size);
void *xrealloc(void *p, size_t n);
void xoom(void) __attribute__((noreturn));
/* Everything allocated after a mark is released by arena_release (temporary work, or a model
   resolved again), with the sources loaded since (data files: they live in the arena). */
typedef struct ArenaMark { void *blocks; char *bump, *bump_end; void **src_v; int src_n, src_cap; } ArenaMark;
ArenaMark arena_mark(void);
void arena_release(ArenaMark m);

/* A growable array of pointers. */
typedef struct Vec { void **v; int n, cap; } Vec;
void vec_push(Vec *a, void *x);
/* Does a hold x? */
int vec_has(const Vec *a, const void *x);
/* Appends to a each element of b that a does not hold yet, other than skip, once, in b's order: in time
 * linear in both (the reads of a sum over a million members). */
void vec_add_new(Vec *a, const Vec *b, const void *skip);

/* A set of pointers (heap memory: pset_free). */
typedef struct PSet { const void **slot; size_t cap, n; } PSet;
/* Adds p; returns whether it was new. */
int pset_add(PSet *s, const void *p);
int pset_has(const PSet *s, const void *p);
void pset_free(PSet *s);

/* A string-keyed hash map (keys are not copied). */
typedef struct Map { char **keys; void **vals; size_t cap, n; } Map;
void *map_get(const Map *m, const char *k);
void map_put(Map *m, char *k, void *v);

/* ---- sources and diagnostics ---- */
typedef struct Loc { int file, line, col; } Loc; /* file indexes the source table; line, col from 1 */

typedef struct Source { char *path; char *text; size_t len; int nlines; size_t *line_start; } Source;
extern Vec sources; /* of Source*, index = Loc.file */

/* The largest model file csfc reads: 128 MiB, about a million objects. */
#define CSF_MAX_SOURCE (128L << 20)
/* Reads a file into the source table; returns its index or -1 (errno set; EFBIG: larger than
 * CSF_MAX_SOURCE). */
int src_load(const char *path);
/* Adds an in-memory source (tests); returns its index. */
int src_add(const char *name, const char *text);
/* The same for len bytes of text, which may hold NUL bytes (the fuzz target). */
int src_add_n(const char *name, const char *text, size_t len);
/* The text of line `line` of file `file` (without newline), in a fresh string. */
char *src_line(int file, int line);

/* At most this many errors are reported; then "too many errors" and the compiler stops. */
#define CSF_MAX_ERRORS 20
extern int diag_errors;
/* Set by a fatal error (binary input) or past CSF_MAX_ERRORS: nothing more is reported, and the
 * scanner ends the input. */
extern int diag_stop;
/* Reports `file:line:col: error: ...` with the source line (at most 160 bytes of it, around the
 * column) and a caret. */
void error_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* An error after which the compiler stops: the only one reported from here on. */
void fatal_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void note_at(Loc l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* An error with no source position: `csfc: error: ...`. */
void error_plain(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
extern FILE *diag_out;
/* Releases all the compiler's memory and forgets every source, diagnostic and interned name:
 * the state of a fresh process (for compiling many inputs in one, as the fuzz target does). */
void csfc_reset(void);

/* Expressions nest at most this deep (every pass walks them recursively). */
#define CSF_MAX_DEPTH 1000

/* ---- units (units.c) ---- */
/* A unit's factor to SI and dimension: exponents of length, mass, time, current (CSF_NDIM). */
typedef struct Unit { double factor; signed char dim[CSF_NDIM]; } Unit;
/* Looks up a unit name in the runtime's unit table (csf_unit_table); returns 1 and fills *u if known. */
int unit_lookup(const char *name, Unit *u);
/* A known unit, or a quotient of two ("mps": "m/s"), near the unknown unit name; NULL if none
 * (names: csf_suggest_name, which -D shares). */
const char *suggest_unit(const char *name);

/* ---- tokens (lex.re, layout.c) ---- */
typedef struct Token {
	int kind;      /* a parser token code (parse.h) or a punctuation character */
	double num;    /* NUMBER */
	int n;         /* DOLLAR */
	char *text;    /* spelling; USING: the path; LEXERROR: the message */
	Loc loc;
	int bol;       /* first token of a line */
	int indent;    /* with bol: the line's indentation in columns */
	Unit unit;     /* unit tokens made by layout.c */
	int end_col;   /* column just past the token */
} Token;

typedef struct Lexer {
	int file;
	const char *start, *cur, *lim, *line_start;
	int line;
	int bol;
} Lexer;

void lex_init(Lexer *L, int file);
/* The next raw token (keywords as their parser token codes). */
void lex_next(Lexer *L, Token *t);
/* Parser token code of a keyword, or 0. */
int lex_keyword(const char *s, size_t n);
/* The length of the UTF-8 sequence at p (before lim): 1 to 4, or 0 if it is not valid UTF-8
 * (a stray continuation byte, a truncated or overlong sequence, a surrogate, past U+10FFFF). */
int lex_utf8_len(const unsigned char *p, const unsigned char *lim);
/* Forgets the interned spellings (their memory is the arena's). */
void lex_reset(void);

/* ---- options ---- */
enum { UNITS_MKS, UNITS_CGS, UNITS_FPS };
typedef struct Options {
	int units;          /* the unit system: UNITS_MKS, UNITS_CGS, UNITS_FPS */
	Vec incdirs;        /* of char*, from -I */
	const char *stdlib; /* the standard library directory */
	double max_rows;    /* the most output rows (till/by) a model may ask for: --max-rows */
	long max_tuples;    /* the most tuples of objects one rule may apply to */
} Options;
/* The defaults of max_rows and max_tuples; the bytecode format's own limit of rows. */
#define CSF_MAX_ROWS 1e7
#define CSF_MAX_TUPLES 1000000L
#define CSF_FORMAT_MAX_ROWS 4e15
extern Options opts;

#endif
