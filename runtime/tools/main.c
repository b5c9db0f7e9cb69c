/*
 * main.c - the command line shared by csfvm and every generated executable.
 *
 * csfvm passes no image: the bytecode comes from the file named on the
 * command line and runs on the VM. A generated executable passes the image
 * compiled into it and its own compiled code sections. Options, messages and
 * exit statuses are therefore the same for both.
 */
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "csf_int.h"

/* --method and --tol, as csfvm and a generated program both explain them */
#define METHOD_TOL_HELP \
	"  --method NAME  ODE stepper: auto (default: dop853, and bsimp while the scene is\n" \
	"                 stiff), dop853, dopri5, rk8pd, rk2, rk4, rkf45, rkck, msadams;\n" \
	"                 implicit, with the exact Jacobian: rk1imp, rk2imp, rk4imp, bsimp,\n" \
	"                 msbdf; symplectic, fixed steps (--step): verlet\n" \
	"  --tol EPS      relative local error bound per internal step, 1e-15 <= EPS < 1\n" \
	"                 (default 1e-12 for dop853, 1e-10 for the others)\n"

static const char vm_usage[] =
	"usage: csfvm [--method NAME] [--tol EPS] [--atol A] MODEL.csfb  (- reads standard input)\n"
	"Runs a compiled CSF model and writes its watched variables as CSV on stdout.\n"
	METHOD_TOL_HELP
	"  --atol A       absolute local error bound, in the model's units, for every state\n"
	"                 variable the scene gives no atol (default: EPS times the largest\n"
	"                 size the variable has reached, within 1e-6 and 1 of one unit)\n"
	"  --hmax H       internal steps of at most H seconds (dop853 and dopri5 step past the\n"
	"                 output times and compute the rows from their dense output)\n"
	"  --fixed        no error control: internal steps of 'by' (or --step H); a step\n"
	"                 past the method's stability limit for the scene is refused\n"
	"  --step H       fixed internal steps of at most H seconds\n"
	"  --every K      write every K-th row (t = 0, K by, 2K by, ...) and the last; the\n"
	"                 run and its assertions are those of every row\n"
	"  --stats        steps, evaluations, time, auto's switches and the fastest time\n"
	"                 scale on stderr\n"
	"  --progress, --no-progress  a progress line on stderr (default: on a terminal)\n"
	"  --compare-methods  run the scene with every method and several tolerances;\n"
	"                 print time and the difference from the most accurate run\n"
	"  -D NAME=VALUE  set a global or OBJECT.PROP before the run, with units as in the\n"
	"                 source: -D 'ball.v=(3, 0, 4) m/s', -D k=2000 g/s^2\n"
	"  --sweep 'NAME=FROM:TO:COUNT [UNIT]'  run COUNT values from FROM to TO; several\n"
	"                 --sweep run their Cartesian product, in one CSV with the swept\n"
	"                 values as leading columns\n"
	"  --sweep-file FILE.csv  one variant per row (a header names the parameters)\n"
	"  --sweep-summary 'max(COL) from T, mean(COL), ...'  one row per variant: final,\n"
	"                 max, min, mean or rms of columns, optionally over 'from T'/'to T'\n"
	"  --out-dir DIR  one CSV per variant, DIR/run-00001.csv..., and DIR/index.csv\n"
	"  --sweep-binary the rows (or summaries) as 8-byte doubles in the machine's byte\n"
	"                 order after the CSV header line (for programs: csf-python(7))\n"
	"  -j N           N worker processes for a sweep (default: every CPU)\n"
	"  --help, --version\n";

static const char exe_usage[] =
	"usage: %s [--method NAME] [--tol EPS] [--atol A]\n"
	"Runs the CSF model compiled into this program and writes its watched variables as CSV on stdout.\n"
	METHOD_TOL_HELP
	"  --atol A       absolute local error bound, in the model's units (as csfvm(1))\n"
	"  --hmax H, --fixed, --step H, --every K, --stats, --progress, --no-progress,\n"
	"  --compare-methods, -D NAME=VALUE, --sweep 'NAME=FROM:TO:COUNT [UNIT]',\n"
	"  --sweep-file FILE, --sweep-summary EXPR, --out-dir DIR, --sweep-binary, -j N:\n"
	"                 as csfvm(1)\n"
	"  --help, --version\n";

/* Text (no NUL or other control bytes but white space in the first 4 KiB), as a .csf file is. */
static int looks_like_source(const unsigned char *b, size_t len)
{
	if (!b || len == 0) return 0;
	for (size_t i = 0; i < len && i < 4096; i++)
		if (b[i] < 0x20 && b[i] != '\n' && b[i] != '\t' && b[i] != '\r') return 0;
	return 1;
}

int csf_main(int argc, char **argv, const unsigned char *image, size_t image_len, csf_exec_fn exec)
{
	csf_opts o;
	int pos[1], npos;
	char usage[4096];
	if (image) snprintf(usage, sizeof usage, exe_usage, argv[0]);
	else snprintf(usage, sizeof usage, "%s", vm_usage);
	int st = csf_parse_opts(argc, argv, 1, &o, pos, image ? 0 : 1, &npos, usage);
	if (st) {
		csf_opts_free(&o);
		return st == 1 ? 0 : 2;
	}
	const char *prog = image ? argv[0] : "csfvm";
	int sweep = o.nsweeps || o.sweep_file;
	int sweep_only = o.summary || o.out_dir || o.sweep_binary;
	if ((!image && npos != 1) || (!sweep && sweep_only) || (sweep && o.compare)) {
		if (!sweep && sweep_only)
			fprintf(stderr, "%s: --sweep-summary, --sweep-binary and --out-dir need --sweep or --sweep-file\n", prog);
		else if (sweep && o.compare) fprintf(stderr, "%s: --compare-methods runs one scene, not a sweep\n", prog);
		else fputs(usage, stderr);
		csf_opts_free(&o);
		return 2;
	}
	const char *path = image ? argv[0] : argv[pos[0]];
	size_t len = image_len;
	unsigned char *buf = NULL;
	if (!image) {
		buf = csf_read_file(path, &len);
		if (!buf) {
			fprintf(stderr, "csfvm: cannot read %s: %s\n", path, strerror(errno));
			csf_opts_free(&o);
			return 2;
		}
	}
	csf_prog p;
	char err[1024];
	if (csf_decode(image ? image : buf, len, &p, err, sizeof err)) {
		const char *name = strcmp(path, "-") == 0 ? "standard input" : path;
		fprintf(stderr, "%s: %s: invalid bytecode: %s\n", image ? argv[0] : "csfvm", name, err);
		if (!image && looks_like_source(buf, len))
			fprintf(stderr, "csfvm: hint: %s looks like CSF source; compile it with csfc first: csfc %s -o MODEL.csfb\n",
			        name, strcmp(path, "-") == 0 ? "-" : path);
		free(buf);
		csf_opts_free(&o);
		return 2;
	}
	free(buf);
	/* -D's values: an overlay over the program's initial memory, which stays as loaded */
	csf_overlay init = { 0 };
	o.init = &init;
	for (int i = 0; i < o.ndefs; i++)
		if (csf_param_set(&p, &init, o.defs[i], err, sizeof err)) {
			fprintf(stderr, "%s: %s\n", prog, err);
			csf_overlay_free(&init);
			csf_prog_free(&p);
			csf_opts_free(&o);
			return 2;
		}
	/* rows go out in writes of 1 MiB to a file or a pipe (to a terminal, line by line, as they come) */
	static char out_buf[1 << 20];
	if (!isatty(fileno(stdout))) setvbuf(stdout, out_buf, _IOFBF, sizeof out_buf);
	/* a write to a closed pipe is an error csf_run sees (EPIPE), and ends quietly */
	signal(SIGPIPE, SIG_IGN);
	/* SIGINT, SIGTERM: csf_run ends after the current row (csf_signal), or the watchdog ends it */
	csf_signals_install(stdout, prog);
	if (sweep) st = csf_sweep_main(&p, exec, &o, prog, stdout, stderr);
	else st = o.compare ? csf_compare_methods(&p, exec, &init, stdout, stderr) : csf_run(&p, exec, &o, stdout, stderr);
	csf_overlay_free(&init);
	csf_prog_free(&p);
	csf_opts_free(&o);
	if (st == 128 + SIGPIPE) { /* as cat: killed by the signal the closed pipe sent */
		signal(SIGPIPE, SIG_DFL);
		raise(SIGPIPE);
	}
	return st;
}
