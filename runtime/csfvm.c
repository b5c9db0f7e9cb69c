/*
 * csfvm - runs a compiled CSF model (.csfb) and prints its watch output.
 */
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "csf.h"

static const char usage[] =
	"usage: csfvm [--method NAME] [--tol EPS] MODEL.csfb\n"
	"Runs a compiled CSF model and writes its watched variables as CSV on stdout.\n"
	"  --method NAME  ODE stepper (default rk8pd)\n"
	"  --tol EPS      local error bound per internal step (default 1e-10)\n"
	"  --help, --version\n";

/* Reads all of path into a malloc'd buffer. Returns NULL with errno set on failure. */
static unsigned char *slurp(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	if (!f) return NULL;
	size_t cap = 1 << 16, n = 0;
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
	fclose(f);
	if (bad) {
		free(buf);
		errno = e ? e : EIO;
		return NULL;
	}
	*len = n;
	return buf;
}

int main(int argc, char **argv)
{
	csf_opts o;
	int pos[1], npos;
	int st = csf_parse_opts(argc, argv, 1, &o, pos, 1, &npos, usage);
	if (st) return st == 1 ? 0 : 2;
	if (npos != 1) {
		fprintf(stderr, "%s", usage);
		return 2;
	}
	const char *path = argv[pos[0]];
	size_t len;
	unsigned char *buf = slurp(path, &len);
	if (!buf) {
		fprintf(stderr, "csfvm: cannot read %s: %s\n", path, strerror(errno));
		return 2;
	}
	csf_prog p;
	char err[256];
	if (csf_decode(buf, len, &p, err, sizeof err)) {
		fprintf(stderr, "csfvm: %s: invalid bytecode: %s\n", path, err);
		free(buf);
		return 2;
	}
	free(buf);
	signal(SIGPIPE, SIG_IGN);
	st = csf_run(&p, csf_vm_exec, &o, stdout, stderr);
	csf_prog_free(&p);
	return st;
}
