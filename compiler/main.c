/*
 * csfc - the CSF compiler driver.
 */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "csfc.h"
#include "lint.h"
#include "ast.h"
#include "sema.h"
#include "gen.h"
#include "csf_int.h"
#include "emit_c.h"
#include "explain.h"
#include "cone.h"
#include "lsp.h"

static const char usage[] =
	"usage: csfc [options] MODEL.csf   (- reads standard input)\n"
	"Compiles a CSF model to bytecode (MODEL.csfb).\n"
	"  -o FILE            write the bytecode to FILE (- for standard output)\n"
	"  -I DIR             add DIR to the search path of 'using'\n"
	"  --units SYSTEM     mks (default), cgs or fps: the units of bare numbers and of the output\n"
	"  --explain          print what every rule solves for, and what is left out\n"
	"  --keep-all         compile every object, also those nothing watched depends on\n"
	"  --dump-bytecode    print the compiled code as a listing\n"
	"  -Werror            make every warning an error; -w: no warnings\n"
	"  --max-rows N       allow 'till/by' to ask for up to N rows of output (default 1e7)\n"
	"  --lsp              serve the Language Server Protocol on standard input and output\n"
	"                     (diagnostics, hover, definition: for editors; no MODEL)\n"
	"  --emit-c           translate to C: with -o NAME.c write the source, otherwise\n"
	"                     build an executable (with $CC $CFLAGS, libcsfrt and GSL)\n"
	"  --help, --version\n";

/* The standard library: $CSF_STDLIB, else next to the installed or the built csfc. */
static const char *find_stdlib(void)
{
	const char *env = getenv("CSF_STDLIB");
	if (env && *env) return env;
	char exe[PATH_MAX];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n <= 0) return NULL;
	exe[n] = '\0';
	char *slash = strrchr(exe, '/');
	if (!slash) return NULL;
	*slash = '\0';
	const char *cands[] = { "%s/../share/csf/stdlib", "%s/../stdlib" };
	for (size_t i = 0; i < sizeof cands / sizeof cands[0]; i++) {
		char *d = xprintf(cands[i], exe);
		char *probe = xprintf("%s/mechanics/rules.csf", d);
		char real[PATH_MAX];
		if (access(probe, R_OK) == 0) return realpath(d, real) ? xstrdup(real) : d;
	}
	return NULL;
}

/*
 * Writes buf to path. A regular file (or a new one) is written to a temporary file beside it and
 * renamed over it only when complete, so a failed write (a full disk) leaves the previous file as
 * it was; the temporary file is the only one ever removed. Anything else (a device, a pipe) is
 * written in place and never removed. Returns 0, or -1 with errno set.
 */
static int write_file(const char *path, const unsigned char *buf, size_t len)
{
	struct stat st;
	char *dest = (char *)path;
	if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) { /* write what the link names, keep the link */
		char *real = realpath(path, NULL);
		if (real) {
			dest = xstrdup(real);
			free(real);
		}
	}
	int exists = stat(dest, &st) == 0;
	if (exists && !S_ISREG(st.st_mode)) {
		FILE *f = fopen(dest, "wb");
		if (!f) return -1;
		int bad = fwrite(buf, 1, len, f) != len || ferror(f);
		int e = errno;
		if (fclose(f) != 0 && !bad) bad = 1, e = errno;
		errno = e;
		return bad ? -1 : 0;
	}
	char *tmp = xprintf("%s.XXXXXX", dest);
	int fd = mkstemp(tmp);
	if (fd < 0) return -1;
	mode_t mask = umask(0);
	umask(mask);
	int bad = fchmod(fd, exists ? st.st_mode & 07777 : 0666 & ~mask) != 0;
	for (size_t done = 0; !bad && done < len;) {
		ssize_t w = write(fd, buf + done, len - done);
		if (w < 0 && errno == EINTR) continue;
		if (w <= 0) bad = 1;
		else done += (size_t)w;
	}
	int e = errno;
	if (close(fd) != 0 && !bad) bad = 1, e = errno;
	if (!bad && rename(tmp, dest) != 0) bad = 1, e = errno;
	if (bad) {
		unlink(tmp);
		errno = e;
		return -1;
	}
	return 0;
}

/* Writes buf to standard output (-o -). */
static int write_stdout(const unsigned char *buf, size_t len)
{
	return fwrite(buf, 1, len, stdout) != len || fflush(stdout) != 0 ? -1 : 0;
}

/* csfc's command line. */
typedef struct cli {
	const char *in, *out;
	int explain, dump, emit, keep_all, lsp;
} cli;

/* Reads the options into c (and opts); -1 to go on, else csfc's exit status. */
static int parse_args(int argc, char **argv, cli *c)
{
	const char *v;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(usage, stdout);
			return 0;
		} else if (!strcmp(a, "--version")) {
			printf("csfc %s\n", CSF_VERSION_STRING);
			return 0;
		} else if (csf_opt_value(argc, argv, &i, "-o", &v)) {
			c->out = v;
		} else if (!strcmp(a, "-Werror")) {
			diag_werror = 1;
		} else if (!strcmp(a, "-w")) {
			diag_nowarn = 1;
		} else if (!strcmp(a, "-I") && i + 1 < argc) {
			vec_push(&opts.incdirs, argv[++i]);
		} else if (!strncmp(a, "-I", 2) && a[2]) {
			vec_push(&opts.incdirs, (void *)(a + 2));
		} else if (csf_opt_value(argc, argv, &i, "--units", &v)) {
			const char *u = v;
			if (!strcmp(u, "mks")) opts.units = UNITS_MKS;
			else if (!strcmp(u, "cgs")) opts.units = UNITS_CGS;
			else if (!strcmp(u, "fps")) opts.units = UNITS_FPS;
			else {
				fprintf(stderr, "csfc: unknown unit system '%s' (mks, cgs or fps)\n", u);
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--max-rows", &v)) {
			char *end;
			const char *n = v;
			errno = 0;
			opts.max_rows = strtod(n, &end);
			if (end == n || *end || errno || !(opts.max_rows >= 1) || !(opts.max_rows <= CSF_FORMAT_MAX_ROWS)) {
				fprintf(stderr, "csfc: --max-rows needs a number of rows from 1 to %g, not '%s'\n",
				        CSF_FORMAT_MAX_ROWS, n);
				return 2;
			}
		} else if (!strcmp(a, "--keep-all")) {
			c->keep_all = 1;
		} else if (!strcmp(a, "--explain")) {
			c->explain = 1;
		} else if (!strcmp(a, "--dump-bytecode")) {
			c->dump = 1;
		} else if (!strcmp(a, "--emit-c")) {
			c->emit = 1;
		} else if (!strcmp(a, "--lsp")) {
			c->lsp = 1;
		} else if (a[0] == '-' && a[1]) {
			fprintf(stderr, "csfc: unknown or incomplete option '%s'\n%s", a, usage);
			return 2;
		} else if (c->in) {
			fprintf(stderr, "csfc: more than one input file\n%s", usage);
			return 2;
		} else {
			c->in = a;
		}
	}
	if (c->lsp && c->in) {
		fprintf(stderr, "csfc: --lsp reads its documents from the protocol, not '%s'\n", c->in);
		return 2;
	}
	if (!c->in && !c->lsp) {
		fputs(usage, stderr);
		return 2;
	}
	if (c->in && !strcmp(c->in, "-") && !c->out && !c->explain && !c->dump) {
		fprintf(stderr, "csfc: the model comes from standard input: name the output with -o FILE (-o - for "
		                "standard output)\n");
		return 2;
	}
	return -1;
}

/* Reads, resolves and generates the model in c->in into p, with --explain's text; 0 or an exit status. */
static int compile(const cli *c, csf_prog *p)
{
	const char *in = c->in;
	opts.stdlib = find_stdlib();
	if (src_load(in) < 0) {
		if (errno == EFBIG) {
			fprintf(stderr, "csfc: error: %s is larger than the %ld MiB a model may have (about a million "
			                "objects): too big to compile\n", in, CSF_MAX_SOURCE >> 20);
			return 1;
		}
		fprintf(stderr, "csfc: cannot read %s: %s\n", in, strerror(errno));
		return 2;
	}
	if (!strcmp(in, "-")) ((Source *)sources.v[0])->path = "<stdin>";
	Stmt *stmts = parse_file(0);
	if (diag_errors) return 1;
	ArenaMark mark = arena_mark();
	Model *M = sema_run(stmts, NULL);
	if (diag_errors) return 1;
	if (!c->keep_all) {
		M = cone_leave_out(stmts, M, mark);
		cone_idle_states(M);
	}
	if (gen_program(M, p)) {
		csf_prog_free(p);
		return 1;
	}
	lint_model(M);
	if (diag_errors) { /* -Werror */
		csf_prog_free(p);
		return 1;
	}
	if (c->explain) {
		explain_model(M, stdout);
		csf_params_list(p, stdout);
	}
	char err[256];
	if (csf_verify(p, err, sizeof err)) {
		fprintf(stderr, "csfc: internal error: generated code does not verify: %s\n", err);
		csf_prog_free(p);
		return 2;
	}
	return 0;
}

/* Writes the bytecode buf (len bytes) of p where c says: a .csfb, or with --emit-c a C source or an executable. */
static int write_output(const cli *c, const csf_prog *p, const unsigned char *buf, size_t len)
{
	int st = 0;
	const char *in = c->in, *out = c->out;
	size_t n = strlen(in);
	char *stem = n > 4 && !strcmp(in + n - 4, ".csf") ? xstrndup(in, n - 4) : xstrdup(in);
	if (c->emit) {
		if (!out) out = stem;
		size_t on = strlen(out);
		int source_only = on > 2 && !strcmp(out + on - 2, ".c");
		char *cpath = source_only ? (char *)out : xprintf("%s.csfc-tmp.c", out);
		FILE *f = fopen(cpath, "w");
		if (!f) {
			fprintf(stderr, "csfc: cannot write %s: %s\n", cpath, strerror(errno));
			st = 2;
		} else {
			emit_c(p, buf, len, in, f);
			if (ferror(f) | fclose(f)) {
				fprintf(stderr, "csfc: cannot write %s\n", cpath);
				st = 2;
			} else if (!source_only) {
				st = emit_c_executable(cpath, out);
			}
			if (!source_only) remove(cpath);
		}
	} else {
		if (!out) out = xprintf("%s.csfb", stem);
		if (!strcmp(out, "-") ? write_stdout(buf, len) : write_file(out, buf, len)) {
			fprintf(stderr, "csfc: cannot write %s: %s\n", out, strerror(errno));
			st = 2;
		}
	}
	return st;
}

static int run(int argc, char **argv)
{
	cli c = { 0 };
	csf_prog p;
	int st = parse_args(argc, argv, &c);
	if (st >= 0) return st;
	if (c.lsp) return lsp_main(find_stdlib(), (char **)opts.incdirs.v, opts.incdirs.n, opts.units);
	if ((st = compile(&c, &p))) return st;
	if (c.dump) csf_disassemble(&p, stdout);
	unsigned char *buf;
	size_t len;
	if (csf_encode(&p, &buf, &len)) {
		fprintf(stderr, "csfc: out of memory\n");
		csf_prog_free(&p);
		return 2;
	}
	st = write_output(&c, &p, buf, len);
	csf_prog_free(&p);
	free(buf);
	return st;
}

int main(int argc, char **argv)
{
	int st = run(argc, argv);
	arena_free();
	/* --help, --explain, --dump-bytecode: their output must have been written */
	if (fflush(stdout) != 0 || ferror(stdout)) {
		fprintf(stderr, "csfc: cannot write the output: %s\n", strerror(errno));
		return 2;
	}
	return st;
}
