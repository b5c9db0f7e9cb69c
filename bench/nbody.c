/*
 * nbody.c - the hand-written C reference for the pairwise-gravity benchmark.
 *
 *   nbody [--stats] IC_FILE TILL BY WATCH...
 *
 * Integrates the model that gen_nbody.sh writes as CSF, the way csfvm does:
 * the integrator, output loop and number format of ref.h (as runtime/ode/ode.c
 * and runtime/run/run.c set them up). It prints the same
 * CSV as csfvm for the watched bodies (pos and v of each WATCH index, in the
 * order given), formatted as csfvm formats numbers, so the two outputs can
 * be compared value by value.
 *
 * The arithmetic is the VM's, operation for operation (see the listing of
 * `csfc --dump-bytecode` in bench/README.md). For body i and every other
 * body j in ascending order:
 *
 *   d   = pos_j - pos_i                      VSUB  (per component)
 *   gm  = G * m_i                            MUL
 *   gmm = gm * m_j                           MUL
 *   r   = sqrt((dx*dx + dy*dy) + dz*dz)      VMAG  (csf_vmag3)
 *   r3  = (r*r)*r                            POWI  (csf_powi(r, 3): the
 *                                                  language's r^3)
 *   s   = gmm / r3                           DIV
 *   F   = (dx*s, dy*s, dz*s)                 VMUL
 *   RF  = ((F_j0 + F_j1) + F_j2) + ...       VADD chain, j ascending
 *   a   = (RF.x/m_i, RF.y/m_i, RF.z/m_i)     VDIV
 *   pos' = v, v' = a                         VMOV
 *
 * so its results are bit-identical to csfvm's. What it leaves out is what a
 * person writing C would not write: the VM computes G*m_i once per pair,
 * stores every pair force in memory before summing, and copies the state in
 * and the derivatives out around each evaluation; here G*m_i is computed
 * once per body (the same IEEE result) and the sum is accumulated in
 * registers. Compile with -O2 -ffp-contract=off (no FMA contraction, never
 * -ffast-math), as the VM is.
 *
 * Built with -DNBODY_POW (bin/nbody_pow), it computes r^3 as pow(r, 3.0),
 * as the VM did before integer powers: no longer the VM's arithmetic
 * (results differ in the last bits). The benchmark runs it as a third,
 * informational program, to show what pow would cost.
 *
 * --stats prints, on stderr, the number of right-hand side evaluations and
 * the smallest distance between two bodies seen at the output times (a
 * check that the run has no close encounter).
 */
#include <gsl/gsl_const_mksa.h>

#include "ref.h"

static size_t n;  /* bodies */
static double *m; /* masses */
static unsigned long nevals; /* right-hand side evaluations */

/* y = (pos_0, v_0, pos_1, v_1, ...), 6 doubles a body, as the VM's state. */
static int rhs(double t, const double *y, double *dydt, void *ctx)
{
	(void)t;
	(void)ctx;
	nevals++;
	const double G = GSL_CONST_MKSA_GRAVITATIONAL_CONSTANT;
	for (size_t i = 0; i < n; i++) {
		const double *pi = y + 6 * i;
		const double gm = G * m[i];
		double ax = 0, ay = 0, az = 0;
		int first = 1;
		for (size_t j = 0; j < n; j++) {
			if (j == i) continue;
			const double *pj = y + 6 * j;
			double dx = pj[0] - pi[0], dy = pj[1] - pi[1], dz = pj[2] - pi[2];
			double gmm = gm * m[j];
			double r = sqrt(dx * dx + dy * dy + dz * dz);
#ifdef NBODY_POW
			double s = gmm / pow(r, 3.0); /* not the VM's arithmetic: see the top */
#else
			double s = gmm / ((r * r) * r); /* POWI: csf_powi(r, 3) */
#endif
			double fx = dx * s, fy = dy * s, fz = dz * s;
			if (first) {
				ax = fx, ay = fy, az = fz;
				first = 0;
			} else {
				ax = ax + fx, ay = ay + fy, az = az + fz;
			}
		}
		double *d = dydt + 6 * i;
		d[0] = y[6 * i + 3];
		d[1] = y[6 * i + 4];
		d[2] = y[6 * i + 5];
		d[3] = ax / m[i];
		d[4] = ay / m[i];
		d[5] = az / m[i];
	}
	return GSL_SUCCESS;
}

static double min_dist(const double *y)
{
	double best = INFINITY;
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++) {
			double dx = y[6 * j] - y[6 * i], dy = y[6 * j + 1] - y[6 * i + 1], dz = y[6 * j + 2] - y[6 * i + 2];
			double r = sqrt(dx * dx + dy * dy + dz * dz);
			if (r < best) best = r;
		}
	return best;
}

static double dmin = INFINITY;

static void closest(const double *y)
{
	double d = min_dist(y);
	if (d < dmin) dmin = d;
}

int main(int argc, char **argv)
{
	int check, first, nw;
	double till, by;
	ref_name = "nbody";
	FILE *f = ref_args(argc, argv, &check, &till, &by, &first);
	if (fscanf(f, "%zu", &n) != 1 || n < 2) ref_die("bad initial conditions: body count");
	m = malloc(n * sizeof *m);
	double *y = malloc(6 * n * sizeof *y);
	if (!m || !y) ref_die("out of memory");
	for (size_t i = 0; i < n; i++) {
		/* strtod on the very strings csfc reads, so the doubles are the same */
		char s[7][64];
		if (fscanf(f, "%63s %63s %63s %63s %63s %63s %63s", s[0], s[1], s[2], s[3], s[4], s[5], s[6]) != 7)
			ref_die("bad initial conditions: short file");
		m[i] = strtod(s[0], NULL);
		for (int k = 0; k < 6; k++) y[6 * i + k] = strtod(s[k + 1], NULL);
	}
	fclose(f);
	size_t *w = ref_watch(argc, argv, first, n, &nw);
	static const int off[] = { 0, 1, 2, 3, 4, 5 }; /* pos then v for each body */
	double steps = ref_run(rhs, 6 * n, y, till, by, w, nw, off, check ? closest : NULL);
	if (check)
		fprintf(stderr, "nbody: %lu right-hand side evaluations, %.0f output steps, closest approach %.6g m\n",
		        nevals, steps, dmin);
	free(y);
	free(m);
	free(w);
	return 0;
}
