/*
 * cc.c - builds an executable from the C that emit_c wrote: finds the
 * runtime (csf.h and libcsfrt.a) next to csfc, installed or in the build
 * tree, and runs $CC $CFLAGS on it with libcsfrt, HDF5 and GSL.
 */
#include <errno.h>
#include <limits.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csfc.h"
#include "emit_c.h"

extern char **environ;

#ifndef CSF_LDLIBS_H5 /* the Makefile's: the serial HDF5 libraries */
#define CSF_LDLIBS_H5 "-lhdf5"
#endif

/* Directory of the running csfc. */
static char *exe_dir(void)
{
	char exe[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n <= 0) return xstrdup(".");
	exe[n] = '\0';
	char *slash = strrchr(exe, '/');
	if (slash) *slash = '\0';
	return xstrdup(exe);
}

/* Finds the runtime's header and library: installed (../include/csf, ../lib) or in the build tree. */
static int find_runtime(char **inc, char **lib)
{
	char *d = exe_dir();
	const char *incs[] = { "%s/../include/csf", "%s/../runtime" };
	const char *libs[] = { "%s/../lib", "%s" };
	for (int i = 0; i < 2; i++) {
		char *ic = xprintf(incs[i], d), *lc = xprintf(libs[i], d);
		if (access(xprintf("%s/csf.h", ic), R_OK) == 0 && access(xprintf("%s/libcsfrt.a", lc), R_OK) == 0) {
			*inc = ic;
			*lib = lc;
			return 0;
		}
	}
	return -1;
}

/* Splits s at blanks into argv entries appended to a. */
static void split_words(Vec *a, const char *s)
{
	while (s && *s) {
		while (*s == ' ' || *s == '\t') s++;
		const char *e = s;
		while (*e && *e != ' ' && *e != '\t') e++;
		if (e > s) vec_push(a, xstrndup(s, (size_t)(e - s)));
		s = e;
	}
}

/*
 * Warns of the C compiler flags in a->v[first..] that let it compute other
 * floating-point results than csf_ops.h's IEEE operations in their order.
 */
static void warn_inexact(const Vec *a, int first)
{
	static const char *const inexact[] = { "-ffast-math", "-Ofast", "-funsafe-math-optimizations", "-fassociative-math",
		                               "-freciprocal-math", "-ffinite-math-only", "-fno-signed-zeros", "-mfpmath=387",
		                               NULL };
	for (int i = first; i < a->n; i++)
		for (int k = 0; inexact[k]; k++)
			if (strcmp(a->v[i], inexact[k]) == 0)
				fprintf(stderr,
				        "csfc: warning: CFLAGS %s lets the C compiler change floating-point results: the "
				        "executable's output may differ from csfvm's\n",
				        inexact[k]);
}

int emit_c_executable(const char *csource, const char *out)
{
	char *inc, *lib;
	if (find_runtime(&inc, &lib)) {
		fprintf(stderr, "csfc: cannot find the CSF runtime (csf.h and libcsfrt.a) next to csfc\n");
		return 2;
	}
	const char *cc = getenv("CC");
	const char *cflags = getenv("CFLAGS");
	Vec a = { 0 };
	split_words(&a, cc && *cc ? cc : "cc");
	int first = a.n;
	split_words(&a, cflags);
	if (a.n == first) split_words(&a, "-O2"); /* CFLAGS unset or blank */
	warn_inexact(&a, first);
	vec_push(&a, "-ffp-contract=off"); /* last: it overrides a -ffp-contract of CFLAGS */
	vec_push(&a, xprintf("-I%s", inc));
	vec_push(&a, (void *)csource);
	vec_push(&a, "-o");
	vec_push(&a, (void *)out);
	vec_push(&a, xprintf("-L%s", lib));
	vec_push(&a, "-lcsfrt");
	split_words(&a, CSF_LDLIBS_H5); /* -o RUN.h5: HDF5, as the Makefile found it */
	vec_push(&a, "-lgsl");
	vec_push(&a, "-lgslcblas");
	vec_push(&a, "-lm");
	vec_push(&a, NULL);
	pid_t pid;
	int st = posix_spawnp(&pid, a.v[0], NULL, NULL, (char **)a.v, environ);
	if (st) {
		fprintf(stderr, "csfc: cannot run %s: %s\n", (char *)a.v[0], strerror(st));
		return 2;
	}
	int ws;
	while (waitpid(pid, &ws, 0) < 0)
		if (errno != EINTR) return 2;
	if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0) {
		fprintf(stderr, "csfc: the C compiler failed to build %s\n", out);
		return 2;
	}
	return 0;
}
