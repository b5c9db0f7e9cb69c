/*
 * api_test.c - libcsf's API (runtime/api/csf_api.h) driven from C, linked with libcsfrt.a so that
 * it runs under the sanitizers too (make check's second pass; the Python tests need the shared
 * library, which that build has not). Usage: api-test MODEL.csfb [LARGE.csfb], MODEL a compiled
 * examples/projectile.csf. Checks: the columns and parameters; runs with -D and options against
 * csf_run's CSV of the same settings, every value formatted as the CSV formats it; the messages of
 * bad parameters and options; every truncation and every byte inverted refused; a progress
 * callback, csf_api_interrupt and SIGINT ending a run after a row; 2000 runs (LeakSanitizer
 * checks that nothing is left at exit). With LARGE.csfb, a model whose rows fill 4 MiB or more
 * (tests/arrays/gen_projectiles.sh: 1000 projectiles watching pos, 1001 rows), the array libcsf
 * faults in on a helper thread: its rows against the CSV, and stopped runs. Prints "FAIL: ..."
 * and exits 1 on the first miss.
 */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "csf_api.h"

static int failed;

#define CHECK(cond, ...)                                                                                               \
	do {                                                                                                           \
		if (!(cond)) {                                                                                         \
			printf("FAIL: %s:%d: %s: ", __FILE__, __LINE__, #cond);                                        \
			printf(__VA_ARGS__);                                                                           \
			putchar('\n');                                                                                 \
			failed = 1;                                                                                    \
			return;                                                                                        \
		}                                                                                                      \
	} while (0)

static unsigned char *bytes;
static size_t nbytes;

/* The CSV csfvm writes for the program in the n bytes at b with the options argv (and -D in them),
   into a malloc'd string. */
static char *csv_of(const unsigned char *b, size_t n, const char *const *argv, int argc)
{
	char *args[32] = { "csfvm" };
	for (int i = 0; i < argc; i++) args[i + 1] = (char *)argv[i];
	csf_opts o;
	int pos[1], npos;
	if (csf_parse_opts(argc + 1, args, 1, &o, pos, 0, &npos, "")) return NULL;
	csf_prog p;
	char err[256];
	if (csf_decode(b, n, &p, err, sizeof err)) return NULL;
	csf_overlay init = { 0 };
	for (int i = 0; i < o.ndefs; i++) csf_param_set(&p, &init, o.defs[i], err, sizeof err);
	o.init = &init;
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	FILE *e = fopen("/dev/null", "w");
	csf_run(&p, csf_vm_exec, &o, f, e);
	fclose(f);
	fclose(e);
	csf_overlay_free(&init);
	csf_prog_free(&p);
	csf_opts_free(&o);
	return text;
}

/* The rows (n of them, w values each) as the CSV's lines after its header. */
static char *rows_text(const double *v, size_t n, size_t w)
{
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	char b[32];
	for (size_t r = 0; r < n; r++)
		for (size_t c = 0; c < w; c++) {
			csf_fmt_double(b, v[r * w + c]);
			fprintf(f, "%s%c", b, c + 1 < w ? ',' : '\n');
		}
	fclose(f);
	return text;
}

/* The test's model, or NULL after saying why. */
static csf_api_model *load(void)
{
	char err[512];
	csf_api_model *m = csf_api_load(bytes, nbytes, err, sizeof err);
	if (!m) printf("FAIL: the model does not load: %s\n", err);
	return m;
}

static void test_model(void)
{
	char err[512];
	CHECK(csf_api_version() == CSF_API_VERSION, "%d", csf_api_version());
	csf_api_model *m = csf_api_load(bytes, nbytes, err, sizeof err);
	CHECK(m, "%s", err);
	static const char *const names[] = { "ball.pos.x", "ball.pos.y", "ball.pos.z", "ball.v.x", "ball.v.y", "ball.v.z" };
	CHECK(csf_api_ncols(m) == 6, "%zu", csf_api_ncols(m));
	for (size_t i = 0; i < 6; i++) {
		CHECK(strcmp(csf_api_col_name(m, i), names[i]) == 0, "%s", csf_api_col_name(m, i));
		CHECK(strcmp(csf_api_col_unit(m, i), i < 3 ? "m" : "m/s") == 0, "%s", csf_api_col_unit(m, i));
		CHECK(csf_api_col_component(m, i) == (int)(i % 3), "%d", csf_api_col_component(m, i));
	}
	CHECK(!csf_api_col_name(m, 6) && csf_api_col_component(m, 6) == -1, "past the last column");
	CHECK(csf_api_till(m) == 2 && csf_api_by(m) == 0.1, "till %g by %g", csf_api_till(m), csf_api_by(m));
	int found = 0;
	for (size_t i = 0; i < csf_api_nparams(m); i++) {
		double v[3];
		int n = csf_api_param_value(m, i, v);
		if (strcmp(csf_api_param_name(m, i), "ball.v") == 0) {
			CHECK(n == 3 && v[0] == 3 && v[1] == 0 && v[2] == 4, "ball.v");
			CHECK(strcmp(csf_api_param_unit(m, i), "m/s") == 0 && !*csf_api_param_why(m, i), "ball.v's unit");
			found++;
		}
		if (strcmp(csf_api_param_name(m, i), "ball.a") == 0) {
			CHECK(strstr(csf_api_param_why(m, i), "a rule computes it"), "%s", csf_api_param_why(m, i));
			found++;
		}
	}
	CHECK(found == 2, "ball.v and ball.a listed");
	double v[3];
	CHECK(csf_api_param_parse(m, "ball.b=200 g/s", v, err, sizeof err) == 1 && v[0] == 0.2, "%s", err);
	CHECK(csf_api_param_parse(m, "ball.b=3 m", v, err, sizeof err) == -1 &&
	          strcmp(err, "-D ball.b=3 m: wrong dimension: ball.b is in kg/s, '3 m' is not (expected unit kg/s)") == 0,
	      "%s", err);
	csf_api_free(m);
}

/* A run with options argv (-D among them) into an array, against csf_run's CSV of the same. */
static void one_run(csf_api_model *m, const char *const *argv, int argc)
{
	csf_api_run *r = csf_api_run_new(m);
	CHECK(r, "run_new");
	CHECK(csf_api_run_options(r, argc, argv) == 0, "%s", csf_api_run_error(r));
	size_t rows = csf_api_run_rows(r), w = csf_api_ncols(m) + 1;
	double *out = malloc(rows * w * sizeof *out);
	int st = csf_api_run_exec(r, out, rows, 0);
	char *want = csv_of(bytes, nbytes, argv, argc), *got = rows_text(out, csf_api_run_nrows(r), w);
	CHECK(st == 0 && want && strcmp(strchr(want, '\n') + 1, got) == 0, "status %d, rows differ from the CSV", st);
	CHECK(csf_api_run_steps(r) > 0 && csf_api_run_rhs(r) > csf_api_run_steps(r), "stats");
	free(want);
	free(got);
	free(out);
	csf_api_run_free(r);
}

static void test_runs(void)
{
	csf_api_model *m = load();
	CHECK(m, "the model does not load");
	const char *a0[] = { "--method", "dop853" };
	const char *a1[] = { "-D", "ball.v=(3, 0, 4) m/s", "-Dball.b=200 g/s", "--tol=1e-10" };
	const char *a2[] = { "--method", "rk4", "--fixed", "--every", "3" };
	const char *a3[] = { "--method", "msbdf", "--atol", "1e-9", "--hmax", "0.05" };
	for (int k = 0; k < 2000 && !failed; k++) {
		one_run(m, a0, 0);
		if (k % 100) continue;
		one_run(m, a0, 2);
		one_run(m, a1, 4);
		one_run(m, a2, 5);
		one_run(m, a3, 6);
	}
	/* --every 3 over 21 rows: k = 0, 3, ..., 18 and the last, 20 */
	csf_api_run *r = csf_api_run_new(m);
	CHECK(csf_api_run_options(r, 5, a2) == 0 && csf_api_run_rows(r) == 8, "%zu rows", csf_api_run_rows(r));
	/* the counting run (no array) and a run into too small an array */
	CHECK(csf_api_run_exec(r, NULL, 0, 0) == 0 && csf_api_run_nrows(r) == 8, "counted");
	double few[7 * 2];
	CHECK(csf_api_run_exec(r, few, 2, 0) == 2 && strstr(csf_api_run_diagnostics(r), "cannot write output"), "%s",
	      csf_api_run_diagnostics(r));
	csf_api_run_free(r);
	csf_api_free(m);
}

static void test_errors(void)
{
	char err[512];
	csf_api_model *m = load();
	CHECK(m, "the model does not load");
	csf_api_run *r = csf_api_run_new(m);
	static const struct { const char *set, *msg; } bad[] = {
		{ "ball.k=3", "-D ball.k=3: unknown name 'ball.k': object 'ball' has no property 'k' that the run uses" },
		{ "ball.v=3 m/s", "-D ball.v=3 m/s: ball.v is a vector: give (x, y, z) and a unit, not '3 m/s'" },
		{ "nothing", "-D nothing: expected NAME=VALUE" },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
		CHECK(csf_api_run_set(r, bad[i].set) == -1 && strcmp(csf_api_run_error(r), bad[i].msg) == 0, "%s",
		      csf_api_run_error(r));
	static const struct { const char *a, *b, *msg; } opts[] = {
		{ "--tol", "1e-30", "--tol 1e-30 is below 1e-15" },
		{ "--method", "nosuch", "unknown method 'nosuch' (one of: auto dop853" },
		{ "--every", "0", "--every needs a whole number of rows, 1 or more, not '0'" },
		{ "--sweep", "ball.m=1:2:3", "--sweep is not an option of one run" },
		{ "--compare-methods", NULL, "--compare-methods is not an option of one run" },
		{ "-o", "run.h5", "-o is not an option of one run" },
		{ "--help", NULL, "--help and --version are not options of a run" },
		{ "--no-such", NULL, "unknown or incomplete option '--no-such'" },
		{ "x.csfb", NULL, "'x.csfb': a run takes options, not a file name" },
		{ "-D", "ball.b=1 m", "-D ball.b=1 m: wrong dimension" },
	};
	for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++) {
		const char *argv[] = { opts[i].a, opts[i].b };
		CHECK(csf_api_run_options(r, opts[i].b ? 2 : 1, argv) == -1 &&
		          strncmp(csf_api_run_error(r), opts[i].msg, strlen(opts[i].msg)) == 0,
		      "%s %s: %s", opts[i].a, opts[i].b ? opts[i].b : "", csf_api_run_error(r));
	}
	/* after the errors, the run is the model's own */
	size_t rows = csf_api_run_rows(r);
	double *out = malloc(rows * 7 * sizeof *out);
	CHECK(csf_api_run_exec(r, out, rows, 0) == 0 && csf_api_run_nrows(r) == 21 && out[7 * 20] == 2, "a plain run");
	free(out);
	csf_api_run_free(r);
	csf_api_free(m);
	/* every truncation, every byte inverted: refused with a reason */
	unsigned char *b = malloc(nbytes + 1);
	for (size_t n = 0; n < nbytes; n++) {
		csf_api_model *t = csf_api_load(bytes, n, err, sizeof err);
		CHECK(!t && *err, "truncated to %zu bytes: loaded", n);
	}
	for (size_t i = 0; i < nbytes; i++) {
		memcpy(b, bytes, nbytes);
		b[i] ^= 0xFF;
		csf_api_model *t = csf_api_load(b, nbytes, err, sizeof err);
		CHECK(!t && *err, "byte %zu inverted: loaded", i);
	}
	free(b);
}

static int stop_at(void *ctx, double t, size_t rows)
{
	(void)rows;
	return t >= *(double *)ctx;
}

static int interrupt_at(void *ctx, double t, size_t rows)
{
	(void)rows;
	if (t >= *(double *)ctx) csf_api_interrupt();
	return 0;
}

static int sigint_at(void *ctx, double t, size_t rows)
{
	(void)rows;
	if (t >= *(double *)ctx) raise(SIGINT);
	return 0;
}

static void test_stops(void)
{
	csf_api_model *m = load();
	CHECK(m, "the model does not load");
	csf_api_run *r = csf_api_run_new(m);
	size_t rows = csf_api_run_rows(r);
	double *out = malloc(rows * 7 * sizeof *out), at = 1.0;
	csf_api_progress_fn fn[] = { stop_at, interrupt_at, sigint_at };
	for (int k = 0; k < 3; k++) {
		csf_api_run_progress(r, fn[k], &at, 0);
		struct sigaction before, after;
		sigaction(SIGINT, NULL, &before);
		int st = csf_api_run_exec(r, out, rows, k == 2 ? CSF_API_CATCH_SIGINT : 0);
		sigaction(SIGINT, NULL, &after);
		/* the row at t = 1 is the last, whichever way the run was asked to end */
		CHECK(st == 130 && csf_api_run_nrows(r) == 11 && out[7 * 10] == 1, "way %d: status %d, %zu rows", k, st,
		      csf_api_run_nrows(r));
		CHECK(before.sa_handler == after.sa_handler, "way %d: SIGINT's handler not put back", k);
	}
	/* and a run after them is whole */
	csf_api_run_progress(r, NULL, NULL, 0);
	CHECK(csf_api_run_exec(r, out, rows, 0) == 0 && csf_api_run_nrows(r) == 21, "after the stops");
	free(out);
	csf_api_run_free(r);
	csf_api_free(m);
}

/*
 * A model whose array is large enough for the helper thread that faults it in while the run writes
 * (runtime/api/api.c, prefault_pages: 4 MiB or more; malloc's memory here, not page-aligned): its
 * rows against the CSV, and runs stopped after the first row and halfway, the helper still at work.
 */
static void test_large(const unsigned char *b, size_t n)
{
	char err[512];
	csf_api_model *m = csf_api_load(b, n, err, sizeof err);
	CHECK(m, "the large model does not load: %s", err);
	csf_api_run *r = csf_api_run_new(m);
	size_t rows = csf_api_run_rows(r), w = csf_api_ncols(m) + 1;
	CHECK(rows * w * sizeof(double) >= 4 << 20, "%zu rows of %zu values: too few for the helper", rows, w);
	double *out = malloc(rows * w * sizeof *out), half = csf_api_till(m) / 2;
	CHECK(out && csf_api_run_exec(r, out, rows, 0) == 0 && csf_api_run_nrows(r) == rows, "%s",
	      csf_api_run_diagnostics(r));
	char *want = csv_of(b, n, NULL, 0), *got = rows_text(out, rows, w);
	const char *body = want ? strchr(want, '\n') + 1 : "";
	CHECK(strcmp(body, got) == 0, "the large run's rows differ from the CSV");
	free(got);
	double at[] = { 0, half };
	for (int k = 0; k < 2; k++) {
		csf_api_run_progress(r, k ? sigint_at : stop_at, &at[k], 0);
		int st = csf_api_run_exec(r, out, rows, k ? CSF_API_CATCH_SIGINT : 0);
		size_t kept = csf_api_run_nrows(r), len = 0;
		for (size_t i = 0; i < kept; i++) len += strcspn(body + len, "\n") + 1;
		got = rows_text(out, kept, w);
		/* the first row alone, or the rows to t = half: the CSV's first rows */
		CHECK(st == 130 && (k ? kept > 1 && kept < rows : kept == 1) && strlen(got) == len &&
		          memcmp(body, got, len) == 0,
		      "stopped at t = %g: status %d, %zu rows", at[k], st, kept);
		free(got);
	}
	free(want);
	free(out);
	csf_api_run_free(r);
	csf_api_free(m);
}

int main(int argc, char **argv)
{
	if (argc < 2 || argc > 3 || !(bytes = csf_read_file(argv[1], &nbytes))) {
		fprintf(stderr, "usage: api-test PROJECTILE.csfb [LARGE.csfb]\n");
		return 2;
	}
	test_model();
	if (!failed) test_runs();
	if (!failed) test_errors();
	if (!failed) test_stops();
	free(bytes);
	size_t n;
	unsigned char *large = argc > 2 ? csf_read_file(argv[2], &n) : NULL;
	if (argc > 2 && !large) {
		printf("FAIL: cannot read %s\n", argv[2]);
		failed = 1;
	}
	if (large && !failed) test_large(large, n);
	free(large);
	if (!failed) printf("api-test: all passed\n");
	return failed;
}
