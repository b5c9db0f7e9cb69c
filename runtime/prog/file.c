/*
 * file.c - reading a whole file: csfvm's bytecode (tools/main.c), a
 * --sweep-file (tools/sweep.c), csfc's source (compiler/util.c). A neutral
 * place, so that no two of them depend on one another for it; and the advice
 * on large blocks of memory (csf_advise_large) that the loader and the run
 * give the kernel.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "csf_int.h"

/*
 * A block of 4 MiB or more (a million members' memory image, its tables, the state) in transparent
 * huge pages where the kernel offers them for the asking (MADV_HUGEPAGE, Linux): one page fault
 * per 2 MiB instead of 512, the run's start-up with 1e6 members mostly faults. Advice only: the
 * contents are the same, and the call fails harmlessly elsewhere.
 */
void csf_advise_large(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
	long page = sysconf(_SC_PAGESIZE);
	if (!p || n < ((size_t)4 << 20) || page <= 0) return;
	uintptr_t mask = (uintptr_t)page - 1, a = ((uintptr_t)p + mask) & ~mask, b = ((uintptr_t)p + n) & ~mask;
	if (b > a) madvise((void *)a, (size_t)(b - a), MADV_HUGEPAGE);
#else
	(void)p, (void)n;
#endif
}

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
	csf_advise_large(buf, cap);
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
