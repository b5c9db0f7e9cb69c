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
#include <strings.h>
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
	"usage: csfvm [--method NAME] [--tol EPS] [--atol A] [-o FILE] MODEL.csfb  (- reads standard input)\n"
	"       csfvm --dump RUN.h5\n"
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
	"  --rows-at-events  a row just before and one just after each located event,\n"
	"                 marked -1 and 1 in a last column 'event' (0 on the other rows)\n"
	"  --progress, --no-progress  a progress line on stderr (default: on a terminal)\n"
	"  --compare-methods  run the scene with every method and several tolerances;\n"
	"                 print time and the difference from the most accurate run\n"
	"  -D NAME=VALUE  set a global or OBJECT.PROP before the run, with units as in the\n"
	"                 source: -D 'ball.v=(3, 0, 4) m/s', -D k=2000 g/s^2\n"
	"  --sweep 'NAME=FROM:TO:COUNT [UNIT]'  run COUNT values from FROM to TO; several\n"
	"                 --sweep run their Cartesian product, in one CSV with the swept\n"
	"                 values as leading columns (or one HDF5 file: -o)\n"
	"  --sweep-file FILE.csv  one variant per row (a header names the parameters)\n"
	"  --sweep-summary 'max(COL) from T, mean(COL), ...'  one row per variant: final,\n"
	"                 max, min, mean or rms of columns, optionally over 'from T'/'to T'\n"
	"  --out-dir DIR  one CSV per variant, DIR/run-00001.csv..., and DIR/index.csv\n"
	"  --sweep-binary the rows (or summaries) as 8-byte doubles in the machine's byte\n"
	"                 order after the CSV header line (for programs: csf-python(7))\n"
	"  -j N           N worker processes for a sweep (default: every CPU)\n"
	"  --threads N    N threads share the loops of a shape with thousands of pairs or\n"
	"                 members (default 1); the output is the same, byte for byte\n"
	"  -o FILE        the output to FILE: the rows in HDF5 when it ends in .h5 or .hdf5\n"
	"                 (a dataset per watched value; a sweep's with a leading axis of\n"
	"                 variants, the swept values on it), else the CSV\n"
	"  --dump RUN.h5  print the rows of a file of -o RUN.h5 as the run's (or sweep's) CSV\n"
	"  --checkpoint FILE  the run's whole state to FILE every --checkpoint-every S\n"
	"                 seconds of wall time (default 60), and when a signal ends it\n"
	"  --resume FILE  go on from that checkpoint: csfvm --resume FILE M.csfb >> RUN.csv\n"
	"                 gives the uninterrupted run's bytes\n"
	"  --record RUN.json  the run record: version, bytecode hash, options, host,\n"
	"                 times, --stats's figures, exit status\n"
	"  --estimate-error  the largest difference of each column from a run 100 times\n"
	"                 tighter, on stderr: the run's global error\n"
	"  --accuracy A   tighten the tolerance until that estimate is at most A\n"
	"  --help, --version\n";

static const char exe_usage[] =
	"usage: %s [--method NAME] [--tol EPS] [--atol A]\n"
	"Runs the CSF model compiled into this program and writes its watched variables as CSV on stdout.\n"
	METHOD_TOL_HELP
	"  --atol A       absolute local error bound, in the model's units (as csfvm(1))\n"
	"  --hmax H, --fixed, --step H, --every K, --stats, --rows-at-events, --progress,\n"
	"  --no-progress,\n"
	"  --compare-methods, -D NAME=VALUE, --sweep 'NAME=FROM:TO:COUNT [UNIT]',\n"
	"  --sweep-file FILE, --sweep-summary EXPR, --out-dir DIR, --sweep-binary, -j N,\n"
	"  --threads N, -o FILE, --dump RUN.h5, --checkpoint FILE, --checkpoint-every S,\n"
	"  --resume FILE, --record RUN.json, --estimate-error, --accuracy A: as csfvm(1)\n"
	"  --help, --version\n";

/* Text (no NUL or other control bytes but white space in the first 4 KiB), as a .csf file is. */
static int looks_like_source(const unsigned char *b, size_t len)
{
	if (!b || len == 0) return 0;
	for (size_t i = 0; i < len && i < 4096; i++)
		if (b[i] < 0x20 && b[i] != '\n' && b[i] != '\t' && b[i] != '\r') return 0;
	return 1;
}

int csf_quiet;

/* The process's exit status st; 128 + SIGPIPE: as cat, killed by the signal the closed pipe sent. */
static int exit_status(int st)
{
	if (st == 128 + SIGPIPE) {
		signal(SIGPIPE, SIG_DFL);
		raise(SIGPIPE);
	}
	return st;
}

/* Does path name an HDF5 file (-o): does it end in .h5 or .hdf5? */
static int h5_name(const char *path)
{
	size_t n = strlen(path);
	return (n > 3 && strcasecmp(path + n - 3, ".h5") == 0) || (n > 5 && strcasecmp(path + n - 5, ".hdf5") == 0);
}

/* Rows go out in writes of 1 MiB to a file or a pipe (to a terminal, line by line, as they come). */
static void out_buffer(FILE *out)
{
	static char buf[1 << 20];
	if (!isatty(fileno(out))) setvbuf(out, buf, _IOFBF, sizeof buf);
}

/* --dump FILE.h5: its rows as CSV on stdout or -o FILE. */
static int dump(const csf_opts *o, const char *prog)
{
	if (o->output && h5_name(o->output)) {
		fprintf(stderr, "%s: --dump writes CSV: -o FILE.csv, or standard output\n", prog);
		return 2;
	}
	FILE *out = o->output && strcmp(o->output, "-") ? fopen(o->output, "w") : stdout;
	if (!out) {
		fprintf(stderr, "%s: cannot write %s: %s\n", prog, o->output, strerror(errno));
		return 2;
	}
	out_buffer(out);
	signal(SIGPIPE, SIG_IGN);
	int st = csf_h5_dump(o->dump, out, stderr, prog);
	if (out != stdout && fclose(out) && st != 2) {
		fprintf(stderr, "error: cannot write output: %s\n", strerror(errno));
		st = 2;
	}
	return st;
}

int csf_main(int argc, char **argv, const unsigned char *image, size_t image_len, csf_exec_fn exec)
{
	csf_opts o;
	int pos[1], npos;
	time_t start = time(NULL);
	char usage[4096];
	if (image) snprintf(usage, sizeof usage, exe_usage, argv[0]);
	else snprintf(usage, sizeof usage, "%s", vm_usage);
	int st = csf_parse_opts(argc, argv, 1, &o, pos, image ? 0 : 1, &npos, usage);
	if (st) {
		csf_opts_free(&o);
		return st == 1 ? 0 : 2;
	}
	const char *prog = image ? argv[0] : "csfvm";
	if (o.dump) {
		st = npos ? (fputs(usage, stderr), 2) : dump(&o, prog);
		csf_opts_free(&o);
		return exit_status(st);
	}
	int sweep = o.nsweeps || o.sweep_file;
	int sweep_only = o.summary || o.out_dir || o.sweep_binary;
	/* -o FILE.h5: a run's rows, or a sweep's (on csfvm-mpi's quiet ranks, no file) */
	int h5 = o.output && h5_name(o.output);
	if (h5 && (o.compare || (sweep && sweep_only))) {
		fprintf(stderr, o.compare   ? "%s: --compare-methods writes a table; -o FILE.h5 is for a run's or a sweep's rows\n"
		                : o.summary ? "%s: --sweep-summary writes CSV; -o FILE.h5 is for a sweep's rows\n"
		                : o.out_dir ? "%s: --out-dir writes a CSV per variant; -o FILE.h5 writes one file of them all\n"
		                            : "%s: --sweep-binary writes doubles after a CSV header; -o FILE.h5 writes HDF5\n",
		        prog);
		csf_opts_free(&o);
		return 2;
	}
	if (o.estimate && (sweep || o.compare || o.checkpoint || o.resume)) {
		fprintf(stderr, "%s: --estimate-error and --accuracy run one scene twice or more; not %s\n", prog,
		        sweep ? "a sweep" : o.compare ? "with --compare-methods" : "with --checkpoint or --resume");
		csf_opts_free(&o);
		return 2;
	}
	if ((o.checkpoint || o.resume) && (o.compare || h5)) {
		fprintf(stderr, "%s: --checkpoint and --resume continue a run's or a sweep's CSV; %s\n", prog,
		        o.compare ? "--compare-methods runs a table of short runs"
		                  : "-o FILE.h5 is written whole at the end (write CSV, and convert it)");
		csf_opts_free(&o);
		return 2;
	}
	if (o.rows_at_events && (h5 || sweep || o.compare)) {
		fprintf(stderr, "%s: --rows-at-events adds rows to the CSV of one run, not to %s\n", prog,
		        sweep ? "a sweep" : o.compare ? "--compare-methods' table" : "an HDF5 file (-o FILE.h5)");
		csf_opts_free(&o);
		return 2;
	}
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
	/* the bytecode's name in a checkpoint and a run record: a pass over every byte, only for them */
	if (o.record || h5 || o.checkpoint || o.resume || sweep) o.hash = csf_hash_bytes(image ? image : buf, len);
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
	/* -o: a run's rows to an HDF5 file (a sweep's: csf_sweep_main), or the CSV to a file (not on csfvm-mpi's quiet ranks) */
	FILE *out = stdout;
	csf_h5 *h = NULL;
	csf_h5_origin origin = { p.nfiles ? csf_str(&p, p.files[0]) : path, argc, argv };
	int h5run = h5 && !sweep && !csf_quiet;
	if (h5run && !(h = csf_h5_create(o.output, &p, &o, origin.model, argc, argv, err, sizeof err)))
		fprintf(stderr, "%s: %s\n", prog, err);
	else if (!h5 && o.output && strcmp(o.output, "-") && !csf_quiet && !(out = fopen(o.output, o.resume ? "r+" : "w")))
		fprintf(stderr, "%s: cannot write %s: %s\n", prog, o.output, strerror(errno));
	if ((h5run && !h) || !out) {
		csf_overlay_free(&init);
		csf_prog_free(&p);
		csf_opts_free(&o);
		return 2;
	}
	out_buffer(out);
	/* a write to a closed pipe is an error csf_run sees (EPIPE), and ends quietly */
	signal(SIGPIPE, SIG_IGN);
	/* SIGINT, SIGTERM: csf_run ends after the current row (csf_signal), or the watchdog ends it */
	csf_signals_install(out, prog);
	csf_sink sink = { csf_h5_row, h, NULL };
	if (sweep) st = csf_sweep_main(&p, exec, &o, prog, h5 ? &origin : NULL, out, stderr);
	else if (o.compare) st = csf_compare_methods(&p, exec, &init, out, stderr);
	else if (o.estimate) st = csf_estimate_run(&p, exec, &o, h ? NULL : out, h ? &sink : NULL, stderr);
	else st = h ? csf_run_sink(&p, exec, &o, NULL, &sink, stderr) : csf_run(&p, exec, &o, out, stderr);
	/* the run record: --record FILE.json, and -o FILE.h5's attributes */
	if (o.record || h) {
		csf_record rec;
		csf_record_make(&rec, &p, &o, origin.model, argc, argv, start, time(NULL), st);
		if (h && csf_h5_record(h, &rec)) fprintf(stderr, "%s: cannot write the run record into %s\n", prog, o.output);
		if (o.record && csf_record_json(&rec, o.record, err, sizeof err)) {
			fprintf(stderr, "%s: --record: %s\n", prog, err);
			if (!st) st = 2;
		}
		csf_record_free(&rec);
	}
	/* the rows kept and the file closed: every row written survives a run that failed */
	if ((h && csf_h5_close(h)) || (out != stdout && fclose(out) && st != 2)) {
		fprintf(stderr, "error: cannot write output: %s\n", strerror(errno));
		st = 2;
	}
	csf_overlay_free(&init);
	csf_prog_free(&p);
	csf_opts_free(&o);
	return exit_status(st);
}
