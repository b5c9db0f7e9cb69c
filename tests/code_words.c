/*
 * tests/code_words.c - code_words FILE.csfb: the size of each code section of a
 * compiled program, as csfc --dump-bytecode heads them ("section rhs (60 words)"),
 * read with the runtime's own loader (csf_decode, which verifies the file).
 * For tests/many/code_size.sh: the listing of a scene of 100 000 objects takes a
 * minute (its object table is listed property by property), the sizes nothing.
 * Exit 0, or 2 on a file that cannot be read or loaded.
 */
#include <stdio.h>
#include <stdlib.h>

#include "csf_int.h"

int main(int argc, char **argv)
{
	static const char *const secname[CSF_NSEC] = { "rhs", "out", "jac" };
	if (argc != 2) {
		fprintf(stderr, "usage: code_words FILE.csfb\n");
		return 2;
	}
	FILE *f = fopen(argv[1], "rb");
	if (!f) {
		perror(argv[1]);
		return 2;
	}
	size_t cap = 1 << 20, len = 0, n;
	unsigned char *buf = malloc(cap);
	while (buf && (n = fread(buf + len, 1, cap - len, f)) > 0) {
		len += n;
		if (len == cap) {
			unsigned char *b = realloc(buf, cap *= 2);
			if (!b) free(buf);
			buf = b;
		}
	}
	fclose(f);
	if (!buf) {
		fprintf(stderr, "code_words: out of memory\n");
		return 2;
	}
	csf_prog p;
	char err[256];
	if (csf_decode(buf, len, &p, err, sizeof err)) {
		fprintf(stderr, "code_words: %s: %s\n", argv[1], err);
		free(buf);
		return 2;
	}
	for (int s = 0; s < CSF_NSEC; s++) printf("section %s (%lu words)\n", secname[s], (unsigned long)p.ncode[s]);
	csf_prog_free(&p);
	free(buf);
	return 0;
}
