/*
 * load.c - csf_load and csf_unload (csf.h): a program in memory of its own,
 * for embedders, who see csf_prog as opaque.
 */
#include <stdlib.h>

#include "csf_int.h"

csf_prog *csf_load(const unsigned char *buf, size_t len, char *err, size_t errlen)
{
	csf_prog *p = calloc(1, sizeof *p);
	if (!p) {
		csf_fail(err, errlen, "out of memory");
		return NULL;
	}
	if (csf_decode(buf, len, p, err, errlen)) { /* decodes and verifies; frees what it made on failure */
		free(p);
		return NULL;
	}
	return p;
}

void csf_unload(csf_prog *p)
{
	if (!p) return;
	csf_prog_free(p);
	free(p);
}
