/*
 * file.c - reading a whole file: csfvm's bytecode (tools/main.c), a
 * --sweep-file (tools/sweep.c), csfc's source (compiler/util.c). A neutral
 * place, so that no two of them depend on one another for it.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <sys/stat.h>

#include "csf_int.h"

unsigned char *csf_read_file(const char *path, size_t *len)
{
	int in = strcmp(path, "-") == 0;
	FILE *f = in ? stdin : fopen(path, "rb");
	if (!f) return NULL;
	/* a regular file's size: read at once, with the spare byte (a pipe's: in blocks that double) */
	struct stat st;
	size_t cap = 1 << 16, n = 0;
	if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 && (uintmax_t)st.st_size < SIZE_MAX / 2)
		cap = (size_t)st.st_size + 1;
	unsigned char *buf = malloc(cap);
	while (buf) {
		n += fread(buf + n, 1, cap - n, f);
		if (n < cap) break;
		unsigned char *b = realloc(buf, cap *= 2);
		if (!b) free(buf);
		buf = b;
	}
	int bad = !buf || ferror(f);
	int e = errno;
	if (!in) fclose(f);
	if (bad) {
		free(buf);
		errno = e ? e : EIO;
		return NULL;
	}
	*len = n;
	return buf;
}
