/*
 * json.h - the little JSON that csfc --lsp reads and writes (json.c).
 *
 * A message is parsed into a tree of Json values in heap memory (not the
 * compiler's arena, which every compilation releases), freed with
 * json_free. Hostile input is refused, never trusted: nesting deeper than
 * JSON_MAX_DEPTH, invalid UTF-8 escapes, trailing bytes, a truncated text.
 */
#ifndef CSF_JSON_H
#define CSF_JSON_H

#include <stddef.h>

typedef enum JsonKind { J_NULL, J_FALSE, J_TRUE, J_NUM, J_STR, J_ARR, J_OBJ } JsonKind;

typedef struct Json Json;
struct Json {
	JsonKind k;
	double num;      /* J_NUM */
	char *str;       /* J_STR: the decoded text (NUL-terminated; len bytes, which may hold NUL) */
	size_t len;
	char *key;       /* a member of a J_OBJ: its name */
	Json *kids;      /* J_ARR, J_OBJ: the first element or member */
	Json *next;      /* the next element or member of the parent */
};

#define JSON_MAX_DEPTH 64

/* Parses the len bytes of text; NULL if they are not one JSON value. */
Json *json_parse(const char *text, size_t len);
void json_free(Json *j);
/* The member key of object j, or NULL (also when j is not an object). */
Json *json_get(const Json *j, const char *key);
/* json_get along a path of keys, ended by NULL. */
Json *json_path(const Json *j, ...);
/* The string j or NULL; the number j as an int (def if j is not an integral number in int's range). */
const char *json_str(const Json *j);
int json_int(const Json *j, int def);

/* A growable string of bytes, for the messages written. */
typedef struct Buf { char *s; size_t n, cap; } Buf;
void jbuf_add(Buf *b, const char *s, size_t n);
void jbuf_puts(Buf *b, const char *s);
void jbuf_printf(Buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Appends s (n bytes) as a JSON string, quoted and escaped; invalid UTF-8 becomes U+FFFD. */
void jbuf_string(Buf *b, const char *s, size_t n);
/* Appends JSON value j as it was read (an id echoed back). */
void jbuf_value(Buf *b, const Json *j);

#endif
