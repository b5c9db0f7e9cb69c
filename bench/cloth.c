/*
 * cloth.c - the hand-written C reference for the cloth of gen_cloth.sh.
 *
 *   cloth [--stats] DATA_CSV TILL BY W WATCH...
 *
 * Integrates the W x H cloth that gen_cloth.sh writes (its data file, the
 * members' pos, home, m, link and hang; H from the number of rows) the way
 * csfvm does, with the integrator, output loop and number format of ref.h,
 * and prints pos and v of each WATCH index as ref.h does.
 *
 * The arithmetic is the VM's, operation for operation (`csfc --dump-bytecode`
 * of the scene: the neighbour rules are loops, each force an array). With
 * d the vector from a node to its neighbour, u = d / |d| (VUNIT), the
 * spring's force is (u * k) * (|d| - s) (VMUL, VMAG, SUB, VMUL), k being
 * link * K along a row (MUL) and K along a column; then for every node
 *
 *   RF = ((((R + L) + U) + D) + W) + Hold    VADD in the rules' order
 *   a  = (RF.x/m, RF.y/m, RF.z/m)            VDIV
 *   v' = a, pos' = v                         VMOV
 *
 * R from the next in its row, L from the previous, U from the one in the
 * next row, D from the previous row (+0.0 where there is none, as the
 * VM's arrays hold), W = g * m, Hold = (home - pos) * (hang * H): one
 * evaluation computes what the VM's does, the same operations in the same
 * order (its steps are ref.h's, not csfvm's, so the rows agree to the
 * tolerance, not bit for bit). What it leaves out is what a person writing C would not write: the VM
 * keeps each rule's forces in an array of its own before the sums, and
 * copies the state in and the derivatives out around each evaluation.
 * Compile with -O2 -ffp-contract=off, as the VM is.
 *
 * --stats prints, on stderr, the number of right-hand side evaluations.
 */
#include <gsl/gsl_const_mksa.h>

#include "ref.h"

static const double K = 200;  /* N/m, gen_cloth.sh's global K */
static const double S = 0.05; /* m, its rest length s */
static const double H = 1e4;  /* N/m, its holding springs' H */

static size_t n, w;            /* nodes, nodes in a row */
static double *m, *link_, *hang, *home; /* per node; home 3 a node */
static double *R, *L, *U, *D;  /* the forces of the four neighbour rules, 3 a node */
static unsigned long nevals;   /* right-hand side evaluations */

/* The force of the spring from p to q, scaled by k, as the VM computes it. */
static inline void spring(const double *p, const double *q, double k, double *f)
{
	csf_vec d = csf_v(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
	csf_vec a = csf_op_VMUL(csf_op_VUNIT(d), k);
	csf_vec r = csf_op_VMUL(a, csf_op_VMAG(d) - S);
	f[0] = r.x, f[1] = r.y, f[2] = r.z;
}

/* y = (pos_0, v_0, pos_1, v_1, ...), 6 doubles a node. */
static int rhs(double t, const double *y, double *dydt, void *ctx)
{
	(void)t;
	(void)ctx;
	nevals++;
	const double g[3] = { 0, 0, -GSL_CONST_MKSA_GRAV_ACCEL };
	for (size_t i = 0; i + 1 < n; i++) {
		spring(y + 6 * i, y + 6 * (i + 1), link_[i] * K, R + 3 * i);
		spring(y + 6 * (i + 1), y + 6 * i, link_[i] * K, L + 3 * (i + 1));
	}
	for (size_t i = 0; i + w < n; i++) {
		spring(y + 6 * i, y + 6 * (i + w), K, U + 3 * i);
		spring(y + 6 * (i + w), y + 6 * i, K, D + 3 * (i + w));
	}
	for (size_t i = 0; i < n; i++) {
		const double *p = y + 6 * i, *v = p + 3;
		double *dp = dydt + 6 * i, *dv = dp + 3, hk = hang[i] * H;
		for (int c = 0; c < 3; c++) {
			double rf = ((((R[3 * i + c] + L[3 * i + c]) + U[3 * i + c]) + D[3 * i + c]) + g[c] * m[i]) +
			            (home[3 * i + c] - p[c]) * hk;
			dv[c] = rf / m[i];
			dp[c] = v[c];
		}
	}
	return GSL_SUCCESS;
}

int main(int argc, char **argv)
{
	int check, first, nw;
	double till, by;
	ref_name = "cloth";
	FILE *f = ref_args(argc, argv, &check, &till, &by, &first);
	if (first >= argc) ref_die("usage: [--stats] DATA_CSV TILL BY W WATCH...");
	w = strtoul(argv[first++], NULL, 10);
	char line[1024];
	if (!fgets(line, sizeof line, f)) ref_die("bad data file: no header");
	size_t cap = 1024;
	double *y = malloc(6 * cap * sizeof *y);
	m = malloc(cap * sizeof *m), link_ = malloc(cap * sizeof *link_), hang = malloc(cap * sizeof *hang);
	home = malloc(3 * cap * sizeof *home);
	if (!y || !m || !link_ || !hang || !home) ref_die("out of memory");
	double c[9];
	/* strtod on the very strings csfc reads, so the doubles are the same */
	while (fgets(line, sizeof line, f)) {
		char *s = line;
		for (int k = 0; k < 9; k++) {
			c[k] = strtod(s, &s);
			if (*s == ',') s++;
		}
		if (n == cap) ref_die("more than 1024 nodes");
		for (int k = 0; k < 3; k++) y[6 * n + k] = c[k], y[6 * n + 3 + k] = 0, home[3 * n + k] = c[3 + k];
		m[n] = c[6], link_[n] = c[7], hang[n] = c[8];
		n++;
	}
	fclose(f);
	if (n < 2 || w < 1 || w >= n) ref_die("bad data file or W");
	R = calloc(3 * n, sizeof *R), L = calloc(3 * n, sizeof *L), U = calloc(3 * n, sizeof *U), D = calloc(3 * n, sizeof *D);
	if (!R || !L || !U || !D) ref_die("out of memory");
	size_t *wt = ref_watch(argc, argv, first, n, &nw);
	static const int off[] = { 0, 1, 2, 3, 4, 5 };
	double steps = ref_run(rhs, 6 * n, y, till, by, wt, nw, off, NULL);
	if (check) fprintf(stderr, "cloth: %lu right-hand side evaluations, %.0f output steps\n", nevals, steps);
	free(y), free(m), free(link_), free(hang), free(home), free(R), free(L), free(U), free(D), free(wt);
	return 0;
}
