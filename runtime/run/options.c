/*
 * options.c - the command line shared by csfvm and generated programs:
 * csf_parse_opts reads the run's options (--method, --tol, --step, -D,
 * --sweep, ...) into a csf_opts.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_int.h"

/* The value v of option name into *x: a positive finite number, or a usage error (-1) on err. */
static int positive(FILE *err, const char *prog, const char *v, const char *name, const char *what, double *x)
{
	char *end;
	errno = 0;
	*x = strtod(v, &end);
	if (end == v || *end || errno || !(*x > 0) || !isfinite(*x)) {
		fprintf(err, "%s: %s needs a positive number%s, not '%s'\n", prog, name, what, v);
		return -1;
	}
	return 0;
}

/* Appends s to the array *v of *n strings (room for max); -1 when memory runs out. */
static int push_arg(const char ***v, int *n, const char *s, int max)
{
	if (!*v && !(*v = malloc((size_t)max * sizeof **v))) return -1;
	(*v)[(*n)++] = s;
	return 0;
}

void csf_opts_free(csf_opts *o)
{
	free(o->defs);
	free(o->sweeps);
	o->defs = o->sweeps = NULL;
}

int csf_opt_value(int argc, char **argv, int *i, const char *name, const char **val)
{
	const char *a = argv[*i];
	size_t n = strlen(name);
	if (strncmp(a, name, n) != 0) return 0;
	if (a[n] == '=') {
		*val = a + n + 1;
		return 1;
	}
	if (a[n] == '\0' && *i + 1 < argc) {
		*val = argv[++*i];
		return 1;
	}
	return 0;
}

int csf_parse_opts(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                   const char *usage)
{
	return csf_parse_opts_to(argc, argv, first, o, pos, npos, npos_out, usage, stdout, stderr);
}

int csf_parse_opts_to(int argc, char **argv, int first, csf_opts *o, int *pos, int npos, int *npos_out,
                      const char *usage, FILE *out, FILE *err)
{
	memset(o, 0, sizeof *o);
	*npos_out = 0;
	for (int i = first; i < argc; i++) {
		const char *a = argv[i], *v;
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			fputs(usage, out);
			return 1;
		} else if (strcmp(a, "--version") == 0) {
			const char *slash = strrchr(argv[0], '/');
			fprintf(out, "%s %s\n", slash ? slash + 1 : argv[0], CSF_VERSION_STRING);
			return 1;
		} else if (csf_opt_value(argc, argv, &i, "--method", &v)) {
			o->method = v;
			int known = strcmp(v, "auto") == 0;
			for (size_t k = 0; csf_method_name(k); k++) known |= strcmp(csf_method_name(k), o->method) == 0;
			if (!known) {
				fprintf(err, "%s: unknown method '%s' (one of: auto", argv[0], o->method);
				for (size_t k = 0; csf_method_name(k); k++) fprintf(err, " %s", csf_method_name(k));
				fprintf(err, ")\n");
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--tol", &v)) {
			if (positive(err, argv[0], v, "--tol", "", &o->tol)) return 2;
			if (o->tol < CSF_MIN_TOL || o->tol >= 1) {
				fprintf(err,
				        o->tol >= 1 ? "%s: --tol %s: a relative error of 1 or more allows any answer; the tolerance "
				                      "must be below 1\n"
				                    : "%s: --tol %s is below 1e-15, what doubles can deliver: a step's result is "
				                      "rounded by 1.1e-16 of its size, and below 1e-15 the methods' error "
				                      "estimates measure that rounding, not their error (they take ever more "
				                      "steps for no gain, or fail)\n",
				        argv[0], v);
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--atol", &v)) {
			if (positive(err, argv[0], v, "--atol", " (in the model's units)", &o->atol)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--step", &v)) {
			if (positive(err, argv[0], v, "--step", " of seconds", &o->step)) return 2;
			o->fixed = 1;
		} else if (csf_opt_value(argc, argv, &i, "--hmax", &v)) {
			if (positive(err, argv[0], v, "--hmax", " of seconds", &o->hmax)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--every", &v)) {
			char *end;
			errno = 0;
			long k = strtol(v, &end, 10);
			if (end == v || *end || errno || k < 1) {
				fprintf(err, "%s: --every needs a whole number of rows, 1 or more, not '%s'\n", argv[0], v);
				return 2;
			}
			o->every = (unsigned long)k;
		} else if (csf_opt_value(argc, argv, &i, "--checkpoint-every", &v)) {
			char *end;
			errno = 0;
			o->checkpoint_every = strtod(v, &end);
			if (end == v || *end || errno || !(o->checkpoint_every >= 0) || !isfinite(o->checkpoint_every)) {
				fprintf(err, "%s: --checkpoint-every needs a number of seconds, 0 or more, not '%s'\n", argv[0], v);
				return 2;
			}
			o->checkpoint_every_set = 1;
		} else if (csf_opt_value(argc, argv, &i, "--checkpoint", &v)) {
			o->checkpoint = v;
		} else if (csf_opt_value(argc, argv, &i, "--resume", &v)) {
			o->resume = v;
		} else if (csf_opt_value(argc, argv, &i, "--record", &v)) {
			o->record = v;
		} else if (strcmp(a, "--estimate-error") == 0) {
			o->estimate = 1;
		} else if (csf_opt_value(argc, argv, &i, "--accuracy", &v)) {
			if (positive(err, argv[0], v, "--accuracy", " (the largest error allowed, in the columns' units)", &o->accuracy))
				return 2;
			o->estimate = 1;
		} else if (strcmp(a, "--fixed") == 0) {
			o->fixed = 1;
		} else if (strcmp(a, "--stats") == 0) {
			o->stats = 1;
		} else if (strcmp(a, "--rows-at-events") == 0) {
			o->rows_at_events = 1;
		} else if (strcmp(a, "--progress") == 0) {
			o->progress = CSF_PROGRESS_ON;
		} else if (strcmp(a, "--no-progress") == 0) {
			o->progress = CSF_PROGRESS_OFF;
		} else if (strcmp(a, "--compare-methods") == 0) {
			o->compare = 1;
		} else if (strncmp(a, "-D", 2) == 0 && (a[2] || i + 1 < argc)) {
			if (push_arg(&o->defs, &o->ndefs, a[2] ? a + 2 : argv[++i], argc)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--sweep", &v)) {
			if (push_arg(&o->sweeps, &o->nsweeps, v, argc)) return 2;
		} else if (csf_opt_value(argc, argv, &i, "--sweep-file", &v)) {
			o->sweep_file = v;
		} else if (csf_opt_value(argc, argv, &i, "--sweep-summary", &v)) {
			o->summary = v;
		} else if (csf_opt_value(argc, argv, &i, "--out-dir", &v)) {
			o->out_dir = v;
		} else if (strcmp(a, "--sweep-binary") == 0) {
			o->sweep_binary = 1;
		} else if (csf_opt_value(argc, argv, &i, "-o", &v) || csf_opt_value(argc, argv, &i, "--output", &v)) {
			o->output = v;
		} else if (csf_opt_value(argc, argv, &i, "--dump", &v)) {
			o->dump = v;
		} else if ((strncmp(a, "-j", 2) == 0 && (a[2] || i + 1 < argc)) || csf_opt_value(argc, argv, &i, "--jobs", &v)) {
			if (strncmp(a, "-j", 2) == 0) v = a[2] ? a + 2 : argv[++i];
			char *end;
			errno = 0;
			o->jobs = strtol(v, &end, 10);
			if (end == v || *end || errno || o->jobs < 1 || o->jobs > 4096) {
				fprintf(err, "%s: -j needs a number of processes from 1 to 4096, not '%s'\n", argv[0], v);
				return 2;
			}
		} else if (csf_opt_value(argc, argv, &i, "--threads", &v)) {
			char *end;
			errno = 0;
			long k = strtol(v, &end, 10);
			if (end == v || *end || errno || k < 1 || k > 1024) {
				fprintf(err, "%s: --threads needs a number of threads from 1 to 1024, not '%s'\n", argv[0], v);
				return 2;
			}
			o->threads = (int)k;
		} else if (a[0] == '-' && a[1] != '\0') {
			fprintf(err, "%s: unknown or incomplete option '%s'\n%s", argv[0], a, usage);
			return 2;
		} else {
			if (*npos_out >= npos) {
				fprintf(err, "%s: too many arguments\n%s", argv[0], usage);
				return 2;
			}
			pos[(*npos_out)++] = i;
		}
	}
	return 0;
}
