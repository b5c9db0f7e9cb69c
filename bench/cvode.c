/* cvode.c - the four stiff reference problems of stiff.sh (stiff/: the IVP Test
 * Set's VDPOL unscaled with mu = 1000 to t = 2000, ROBER to 1e11, OREGO to 360,
 * HIRES to 321.8122) under SUNDIALS CVODE: BDF, Newton iteration, the dense
 * direct linear solver and the analytic Jacobian, for cvode.sh. The equations
 * and parameters are those of the scenes in stiff/ (vdp.csf: x' = v,
 * v' = mu (1 - x^2) v - x, not the Test Set's eps-scaled form).
 *
 * Tolerances as csfvm applies its own: relative tol, absolute tol times the
 * component's scale, which is min(1 unit, largest initial magnitude of the
 * property), 1 for a property that starts at zero (compiler/gen.c, yscale;
 * runtime/ode.c, csf_ode_new). Here that is 1 for every component except
 * HIRES's y8 (0.0057).
 *
 *   cvode [REPS [TOL...]]   (REPS 3, TOLs 1e-10)
 *
 * Prints CSV on stdout, one row per problem and tolerance:
 *   problem,method,tol,exit,steps,rhs,jac,seconds,error
 * rhs is nfe + nfeLS (the latter 0 with the analytic Jacobian), jac the
 * Jacobian evaluations, seconds the best of REPS of the CVode call alone
 * (clock_gettime, CLOCK_MONOTONIC), error the largest over the components at
 * the end time of the smaller of absolute and relative error against the
 * reference (as stiff.sh measures). exit is CVode's return flag (0: success).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#define Y(i) NV_Ith_S(y, i)
#define F(i) NV_Ith_S(f, i)
#define J(i, j) SM_ELEMENT_D(Jm, i, j)

/* van der Pol, mu = 1000 s^-1, w2 = 1 s^-2, a = 1 m (vdp.csf) */
static const double mu = 1000;
static int vdp_f(sunrealtype t, N_Vector y, N_Vector f, void *u) {
	(void)t, (void)u;
	F(0) = Y(1);
	F(1) = mu * (1 - Y(0) * Y(0)) * Y(1) - Y(0);
	return 0;
}
static int vdp_j(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jm, void *u, N_Vector t1, N_Vector t2, N_Vector t3) {
	(void)t, (void)fy, (void)u, (void)t1, (void)t2, (void)t3;
	J(0, 0) = 0;
	J(0, 1) = 1;
	J(1, 0) = -2 * mu * Y(0) * Y(1) - 1;
	J(1, 1) = mu * (1 - Y(0) * Y(0));
	return 0;
}

/* Robertson (robertson.csf) */
static const double k1 = 0.04, k2 = 3e7, k3 = 1e4;
static int rob_f(sunrealtype t, N_Vector y, N_Vector f, void *u) {
	(void)t, (void)u;
	F(0) = -k1 * Y(0) + k3 * Y(1) * Y(2);
	F(1) = k1 * Y(0) - k3 * Y(1) * Y(2) - k2 * Y(1) * Y(1);
	F(2) = k2 * Y(1) * Y(1);
	return 0;
}
static int rob_j(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jm, void *u, N_Vector t1, N_Vector t2, N_Vector t3) {
	(void)t, (void)fy, (void)u, (void)t1, (void)t2, (void)t3;
	J(0, 0) = -k1, J(0, 1) = k3 * Y(2), J(0, 2) = k3 * Y(1);
	J(1, 0) = k1, J(1, 1) = -k3 * Y(2) - 2 * k2 * Y(1), J(1, 2) = -k3 * Y(1);
	J(2, 0) = 0, J(2, 1) = 2 * k2 * Y(1), J(2, 2) = 0;
	return 0;
}

/* the Oregonator (oregonator.csf) */
static const double os = 77.27, oq = 8.375e-6, ow = 0.161;
static int ore_f(sunrealtype t, N_Vector y, N_Vector f, void *u) {
	(void)t, (void)u;
	F(0) = os * (Y(1) + Y(0) * (1 - oq * Y(0) - Y(1)));
	F(1) = (Y(2) - (1 + Y(0)) * Y(1)) / os;
	F(2) = ow * (Y(0) - Y(2));
	return 0;
}
static int ore_j(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jm, void *u, N_Vector t1, N_Vector t2, N_Vector t3) {
	(void)t, (void)fy, (void)u, (void)t1, (void)t2, (void)t3;
	J(0, 0) = os * (1 - 2 * oq * Y(0) - Y(1)), J(0, 1) = os * (1 - Y(0)), J(0, 2) = 0;
	J(1, 0) = -Y(1) / os, J(1, 1) = -(1 + Y(0)) / os, J(1, 2) = 1 / os;
	J(2, 0) = ow, J(2, 1) = 0, J(2, 2) = -ow;
	return 0;
}

/* HIRES (hires.csf) */
static const double ha = 1.71, hb = 0.43, c8 = 8.32, src = 0.0007, d2 = 8.75, d3 = 10.03, f5 = 0.035,
                    d4 = 1.12, d5 = 1.745, hk = 280, hp = 0.69, d7 = 1.81;
static int hir_f(sunrealtype t, N_Vector y, N_Vector f, void *u) {
	(void)t, (void)u;
	F(0) = -ha * Y(0) + hb * Y(1) + c8 * Y(2) + src;
	F(1) = ha * Y(0) - d2 * Y(1);
	F(2) = -d3 * Y(2) + hb * Y(3) + f5 * Y(4);
	F(3) = c8 * Y(1) + ha * Y(2) - d4 * Y(3);
	F(4) = -d5 * Y(4) + hb * Y(5) + hb * Y(6);
	F(5) = -hk * Y(5) * Y(7) + hp * Y(3) + ha * Y(4) - hb * Y(5) + hp * Y(6);
	F(6) = hk * Y(5) * Y(7) - d7 * Y(6);
	F(7) = -hk * Y(5) * Y(7) + d7 * Y(6);
	return 0;
}
static int hir_j(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jm, void *u, N_Vector t1, N_Vector t2, N_Vector t3) {
	(void)t, (void)fy, (void)u, (void)t1, (void)t2, (void)t3;
	SUNMatZero(Jm);
	J(0, 0) = -ha, J(0, 1) = hb, J(0, 2) = c8;
	J(1, 0) = ha, J(1, 1) = -d2;
	J(2, 2) = -d3, J(2, 3) = hb, J(2, 4) = f5;
	J(3, 1) = c8, J(3, 2) = ha, J(3, 3) = -d4;
	J(4, 4) = -d5, J(4, 5) = hb, J(4, 6) = hb;
	J(5, 3) = hp, J(5, 4) = ha, J(5, 5) = -hk * Y(7) - hb, J(5, 6) = hp, J(5, 7) = -hk * Y(5);
	J(6, 5) = hk * Y(7), J(6, 6) = -d7, J(6, 7) = hk * Y(5);
	J(7, 5) = -hk * Y(7), J(7, 6) = d7, J(7, 7) = -hk * Y(5);
	return 0;
}

typedef struct {
	const char *name;
	int n;
	double tend;
	CVRhsFn f;
	CVLsJacFn jac;
	double y0[8], scale[8], ref[8];
} problem;

static const problem problems[] = {
	{ "vdp", 2, 2000, vdp_f, vdp_j, { 2, 0 }, { 1, 1 }, { 1.706167732170483, -8.928097010247975e-4 } },
	{ "robertson", 3, 1e11, rob_f, rob_j, { 1, 0, 0 }, { 1, 1, 1 },
	  { 2.083340149701255e-8, 8.333360770334713e-14, 0.9999999791665050 } },
	{ "oregonator", 3, 360, ore_f, ore_j, { 1, 2, 3 }, { 1, 1, 1 },
	  { 1.000814870318523, 1228.178521549917, 132.0554942846706 } },
	{ "hires", 8, 321.8122, hir_f, hir_j, { 1, 0, 0, 0, 0, 0, 0, 0.0057 }, { 1, 1, 1, 1, 1, 1, 1, 0.0057 },
	  { 0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4, 0.1175651343283149e-2,
	    0.2386356198831331e-2, 0.6238968252742796e-2, 0.2849998395185769e-2, 0.2850001604814231e-2 } },
};

#define CHECK(x) do { if (!(x)) { fprintf(stderr, "cvode: %s failed (%s:%d)\n", #x, __FILE__, __LINE__); exit(2); } } while (0)

static void run(SUNContext ctx, const problem *p, const char *tols, int reps) {
	double tol = atof(tols);
	double best = INFINITY, err = 0;
	long nst = 0, nfe = 0, nfels = 0, nje = 0;
	int flag = 0;
	for (int r = 0; r < reps; r++) {
		N_Vector y = N_VNew_Serial(p->n, ctx), atol = N_VNew_Serial(p->n, ctx);
		CHECK(y && atol);
		for (int i = 0; i < p->n; i++) NV_Ith_S(y, i) = p->y0[i], NV_Ith_S(atol, i) = tol * p->scale[i];
		void *mem = CVodeCreate(CV_BDF, ctx);
		CHECK(mem);
		CHECK(CVodeInit(mem, p->f, 0.0, y) == CV_SUCCESS);
		CHECK(CVodeSVtolerances(mem, tol, atol) == CV_SUCCESS);
		SUNMatrix A = SUNDenseMatrix(p->n, p->n, ctx);
		SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
		CHECK(A && LS);
		CHECK(CVodeSetLinearSolver(mem, LS, A) == CV_SUCCESS);
		CHECK(CVodeSetJacFn(mem, p->jac) == CV_SUCCESS);
		CHECK(CVodeSetMaxNumSteps(mem, 100000000L) == CV_SUCCESS);
		CHECK(CVodeSetStopTime(mem, p->tend) == CV_SUCCESS); /* end exactly at tend, as csfvm's rows */
		struct timespec a, b;
		double t = 0;
		clock_gettime(CLOCK_MONOTONIC, &a);
		flag = CVode(mem, p->tend, y, &t, CV_NORMAL);
		clock_gettime(CLOCK_MONOTONIC, &b);
		double s = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
		if (s < best) best = s;
		if (flag == CV_TSTOP_RETURN) flag = CV_SUCCESS;
		CVodeGetNumSteps(mem, &nst);
		CVodeGetNumRhsEvals(mem, &nfe);
		CVodeGetNumLinRhsEvals(mem, &nfels);
		CVodeGetNumJacEvals(mem, &nje);
		err = 0;
		for (int i = 0; i < p->n; i++) {
			double d = fabs(NV_Ith_S(y, i) - p->ref[i]);
			if (p->ref[i] != 0 && d / fabs(p->ref[i]) < d) d /= fabs(p->ref[i]);
			if (!(d <= err)) err = d; /* NaN propagates */
		}
		CVodeFree(&mem);
		SUNLinSolFree(LS);
		SUNMatDestroy(A);
		N_VDestroy(y);
		N_VDestroy(atol);
	}
	printf("%s,cvode,%s,%d,%ld,%ld,%ld,%.6g,%.3g\n", p->name, tols, flag, nst, nfe + nfels, nje, best, err);
}

int main(int argc, char **argv) {
	int reps = argc > 1 ? atoi(argv[1]) : 3;
	if (reps < 1) reps = 1;
	SUNContext ctx;
	CHECK(SUNContext_Create(NULL, &ctx) == 0);
	printf("problem,method,tol,exit,steps,rhs,jac,seconds,error\n");
	for (size_t k = 0; k < sizeof problems / sizeof problems[0]; k++) {
		if (argc > 2)
			for (int a = 2; a < argc; a++) run(ctx, &problems[k], argv[a], reps);
		else
			run(ctx, &problems[k], "1e-10", reps);
	}
	SUNContext_Free(&ctx);
	return 0;
}
