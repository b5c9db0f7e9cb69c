/*
 * galaxy.c - one evaluation of gen_galaxy.sh's galaxy: the code csfc --emit-c writes beside
 * hand-written C.
 *
 *   cc -O2 -ffp-contract=off -I../runtime -DGALAXY_C='"GAL.c"' galaxy.c libcsfrt.a -lgsl ...
 *   galaxy STARS.csv REPS ROWS
 *
 * GAL.c is `csfc --emit-c` of the galaxy scene (gen_galaxy.sh), included here with its main
 * renamed and its loops over the stars (csf_par_for) cut to the first ROWS stars (0: all): star i's
 * work is the same for every i (its N - 1 pairs), so ROWS of N stars take ROWS/N of an
 * evaluation, and 1e5 stars (1e10 pairs an evaluation) are measured in a second or two. It times
 * REPS evaluations of the generated right-hand side (csf_model_rhs, on the memory of the
 * program's embedded image, as the generated program evaluates, one thread) and REPS of the loop
 * a physicist would write over arrays of the stars' masses and positions read from STARS.csv
 * (strtod), both over the first ROWS stars, and prints one line:
 *
 *   N emitc_seconds hand_seconds identical
 *
 * the medians of one evaluation (the time of ROWS stars times N/ROWS), and whether the two gave
 * the same accelerations and velocity derivatives for those stars, bit for bit (1 or 0). The
 * hand-written loop does the scene's operations in their order: for star i, gm = G m_i once,
 * then for every other star j ascending
 *
 *   d = pos_j - pos_i; gmm = gm m_j; r2 = (dx dx + dy dy) + dz dz + eps^2;
 *   F += d (gmm / (r2 sqrt(r2)))
 *
 * and a_i = F / m_i; pos' = v. Compile with -O2 -ffp-contract=off, as the generated program is.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"
#include "timing.h"

static uint32_t rows; /* the stars each loop of the generated code runs over (the first) */

/* The generated code's loops, one thread, over the first rows of their count iterations. */
static void galaxy_par_for(const csf_prog *p, const csf_exec_ctx *x, uint64_t work, uint32_t count, csf_par_fn *fn,
                           double *m, const double *y, double *dydt)
{
	(void)work;
	fn(p, x, m, y, dydt, 0, count < rows ? count : rows);
}

#define main csf_generated_main
#define csf_par_for galaxy_par_for
#include GALAXY_C
#undef csf_par_for
#undef main

static void die(const char *msg)
{
	fprintf(stderr, "galaxy: %s\n", msg);
	exit(2);
}

/* The slot of name (a global or STAR.PROP) in p; dies if p has none. */
static uint32_t slot(const csf_prog *p, const char *name)
{
	csf_pref r;
	char err[256];
	if (csf_param_find(p, name, &r, err, sizeof err)) die(err);
	return r.slot;
}

int main(int argc, char **argv)
{
	int reps = argc == 4 ? atoi(argv[2]) : 0;
	FILE *f = reps > 0 ? fopen(argv[1], "r") : NULL;
	csf_prog p;
	char err[256], line[512], name[64];
	if (!f || csf_decode(csf_model_image, sizeof csf_model_image, &p, err, sizeof err))
		die("usage: galaxy STARS.csv REPS ROWS (and the program's image valid)");
	size_t n = p.nobjects;
	rows = (uint32_t)strtoul(argv[3], NULL, 10);
	if (rows == 0 || rows > n) rows = (uint32_t)n;
	snprintf(name, sizeof name, "star[%zu].pos", n - 1);
	uint32_t sp = slot(&p, "star[0].pos"), sv = slot(&p, "star[0].v");
	if (slot(&p, name) != sp + 3 * (n - 1) || sp < p.ystart || sv < p.ystart) die("not gen_galaxy.sh's array of stars");
	double G = p.mem0[slot(&p, "G")], eps = p.mem0[slot(&p, "eps")];
	double *mem = malloc(p.nmem * sizeof *mem), *m = malloc(n * sizeof *m), *pos = malloc(3 * n * sizeof *pos);
	double *v = malloc(3 * n * sizeof *v), *dv = malloc(3 * n * sizeof *dv), *dp = malloc(3 * n * sizeof *dp);
	double *te = malloc((size_t)reps * sizeof *te), *th = malloc((size_t)reps * sizeof *th);
	if (!mem || !m || !pos || !v || !dv || !dp || !te || !th) die("out of memory");
	/* the stars as the file gives them: m, pos.x .. pos.z, v.x .. v.z */
	size_t k = 0;
	if (!fgets(line, sizeof line, f)) die("no header");
	for (; k < n && fgets(line, sizeof line, f); k++) {
		char *s = line;
		m[k] = strtod(s, &s);
		for (int c = 0; c < 3; c++) pos[3 * k + c] = strtod(s + 1, &s);
		for (int c = 0; c < 3; c++) v[3 * k + c] = strtod(s + 1, &s);
	}
	fclose(f);
	if (k != n) die("the file has fewer stars than the program");
	memcpy(mem, p.mem0, p.nmem * sizeof *mem);
	csf_exec_ctx x = { 0 };
	const double eps2 = eps * eps;
	for (int r = 0; r < reps; r++) {
		double t0 = now();
		csf_model_rhs(&p, &x, mem, mem + p.ystart, mem + p.dstart);
		double t1 = now();
		for (size_t i = 0; i < rows; i++) {
			const double gm = G * m[i], xi = pos[3 * i], yi = pos[3 * i + 1], zi = pos[3 * i + 2];
			double fx = 0, fy = 0, fz = 0;
			for (size_t j = 0; j < n; j++) {
				if (j == i) continue;
				double dx = pos[3 * j] - xi, dy = pos[3 * j + 1] - yi, dz = pos[3 * j + 2] - zi;
				double gmm = gm * m[j], r2 = (dx * dx + dy * dy) + dz * dz + eps2;
				double s = gmm / (r2 * sqrt(r2));
				fx = fx + dx * s, fy = fy + dy * s, fz = fz + dz * s;
			}
			dv[3 * i] = fx / m[i], dv[3 * i + 1] = fy / m[i], dv[3 * i + 2] = fz / m[i];
			for (int c = 0; c < 3; c++) dp[3 * i + c] = v[3 * i + c];
		}
		double t2 = now();
		te[r] = (t1 - t0) * ((double)n / rows);
		th[r] = (t2 - t1) * ((double)n / rows);
	}
	/* the derivative of slot s is at dstart + (s - ystart) */
	const double *vd = mem + p.dstart + (sv - p.ystart), *pd = mem + p.dstart + (sp - p.ystart);
	int same = !memcmp(vd, dv, 3 * (size_t)rows * sizeof *dv) && !memcmp(pd, dp, 3 * (size_t)rows * sizeof *dp);
	printf("%zu %.6e %.6e %d\n", n, median(te, reps), median(th, reps), same);
	free(mem), free(m), free(pos), free(v), free(dv), free(dp), free(te), free(th);
	csf_prog_free(&p);
	return 0;
}
