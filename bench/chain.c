/*
 * chain.c - the hand-written C reference for the spring-chain benchmark.
 *
 *   chain [--stats] IC_FILE TILL BY WATCH...
 *
 * Integrates the model that gen_chain.sh writes as CSF (N masses p0..p(N-1)
 * between two fixed anchors, neighbours linked by Hooke springs of stiffness
 * k and rest length L, under gravity) the way csfvm does, with the
 * integrator, output loop and number format of ref.h. It prints the same CSV as csfvm for the watched masses (pos and v of each
 * WATCH index, in the order given), formatted as csfvm formats numbers.
 *
 * The arithmetic is the VM's, operation for operation (`csfc --dump-bytecode`
 * of the model). The state holds, for every mass in order, v then pos, as
 * the VM's state does. For mass i:
 *
 *   W   = (g.x*m, g.y*m, g.z*m)               VMUL, g = (0, 0, -9.80665)
 *   for the left neighbour j (a0 for p0), then the right one (a1 for p(N-1)):
 *     d = pos_j - pos_i                       VSUB  (per component)
 *     r = sqrt((dx*dx + dy*dy) + dz*dz)       VMAG  (csf_vmag3)
 *     s = (k * (r - L)) / r                   SUB, MUL, DIV
 *     S = (dx*s, dy*s, dz*s)                  VMUL
 *   RF  = (W + Sl) + Sr                       VADD, VADD
 *   a   = (RF.x/m, RF.y/m, RF.z/m)            VDIV
 *   v' = a, pos' = v                          VMOV
 *
 * (the VM computes all the forces first, then the sums; the values are the
 * same). So its results are bit-identical to csfvm's. Compile with -O2
 * -ffp-contract=off (no FMA contraction, never -ffast-math), as the VM is.
 *
 * --stats prints, on stderr, the number of right-hand side evaluations and
 * the shortest and longest link seen at the output times.
 */
#include <gsl/gsl_const_mksa.h>

#include "ref.h"

static const double K = 100;  /* N/m, gen_chain.sh's global k */
static const double L = 0.08; /* m, its global L */

static size_t n;       /* masses */
static double *m;      /* their masses */
static double anc[6];  /* the anchors' positions: a0, a1 */
static unsigned long nevals; /* right-hand side evaluations */

/* The force on the mass at p from the end at q, as the VM computes it. */
static inline void spring(const double *p, const double *q, double f[3])
{
	double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
	double r = sqrt(dx * dx + dy * dy + dz * dz);
	double s = (K * (r - L)) / r;
	f[0] = dx * s, f[1] = dy * s, f[2] = dz * s;
}

/* y = (v_0, pos_0, v_1, pos_1, ...), 6 doubles a mass, as the VM's state. */
static int rhs(double t, const double *y, double *dydt, void *ctx)
{
	(void)t;
	(void)ctx;
	nevals++;
	const double gx = 0, gy = 0, gz = -GSL_CONST_MKSA_GRAV_ACCEL;
	for (size_t i = 0; i < n; i++) {
		const double *v = y + 6 * i, *p = v + 3;
		const double *pl = i == 0 ? anc : y + 6 * (i - 1) + 3;
		const double *pr = i == n - 1 ? anc + 3 : y + 6 * (i + 1) + 3;
		double sl[3], sr[3];
		spring(p, pl, sl);
		spring(p, pr, sr);
		double wx = gx * m[i], wy = gy * m[i], wz = gz * m[i];
		double *d = dydt + 6 * i;
		d[0] = ((wx + sl[0]) + sr[0]) / m[i];
		d[1] = ((wy + sl[1]) + sr[1]) / m[i];
		d[2] = ((wz + sl[2]) + sr[2]) / m[i];
		d[3] = v[0];
		d[4] = v[1];
		d[5] = v[2];
	}
	return GSL_SUCCESS;
}

static double dist(const double *a, const double *b)
{
	double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
	return sqrt(dx * dx + dy * dy + dz * dz);
}

/* The shortest and longest link. */
static void links(const double *y, double *lo, double *hi)
{
	for (size_t i = 0; i <= n; i++) {
		double r = dist(i == 0 ? anc : y + 6 * (i - 1) + 3, i == n ? anc + 3 : y + 6 * i + 3);
		if (r < *lo) *lo = r;
		if (r > *hi) *hi = r;
	}
}

static double lo = INFINITY, hi = 0;

static void check_links(const double *y) { links(y, &lo, &hi); }

int main(int argc, char **argv)
{
	int check, first, nw;
	double till, by;
	ref_name = "chain";
	FILE *f = ref_args(argc, argv, &check, &till, &by, &first);
	if (fscanf(f, "%zu", &n) != 1 || n < 2) ref_die("bad initial conditions: mass count");
	m = malloc(n * sizeof *m);
	double *y = malloc(6 * n * sizeof *y);
	if (!m || !y) ref_die("out of memory");
	char s[7][64];
	for (int q = 0; q < 2; q++) {
		if (fscanf(f, "%63s %63s %63s", s[0], s[1], s[2]) != 3) ref_die("bad initial conditions: anchors");
		for (int c = 0; c < 3; c++) anc[3 * q + c] = strtod(s[c], NULL);
	}
	for (size_t i = 0; i < n; i++) {
		/* strtod on the very strings csfc reads, so the doubles are the same */
		if (fscanf(f, "%63s %63s %63s %63s %63s %63s %63s", s[0], s[1], s[2], s[3], s[4], s[5], s[6]) != 7)
			ref_die("bad initial conditions: short file");
		m[i] = strtod(s[0], NULL);
		for (int c = 0; c < 3; c++) {
			y[6 * i + 3 + c] = strtod(s[1 + c], NULL); /* pos */
			y[6 * i + c] = strtod(s[4 + c], NULL);     /* v */
		}
	}
	fclose(f);
	size_t *w = ref_watch(argc, argv, first, n, &nw);
	static const int off[] = { 3, 4, 5, 0, 1, 2 }; /* the VM keeps v then pos for each mass */
	double steps = ref_run(rhs, 6 * n, y, till, by, w, nw, off, check ? check_links : NULL);
	if (check)
		fprintf(stderr, "chain: %lu right-hand side evaluations, %.0f output steps, links %.6g to %.6g m\n", nevals,
		        steps, lo, hi);
	free(y);
	free(m);
	free(w);
	return 0;
}
