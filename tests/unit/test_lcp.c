/*
 * Lemke's method (runtime/contact/lemke.c) on linear complementarity
 * problems with known answers: w = M z + q >= 0, z >= 0, w . z = 0. A
 * positive definite pair solved by hand, one where q >= 0 (z = 0), two
 * contacts that say the same (a degenerate, singular M: every split of
 * the force is an answer), a contact with Coulomb friction in the four
 * directions of its tangent plane that sticks and one that slides (the
 * forces from the friction law by hand), a problem without a solution
 * (a secondary ray), and one with a solution on which the method ends on
 * a ray, which csf_lcp_solve's shifted diagonal finds.
 */
#include <math.h>

#include "suites.h"
#include "contact_int.h"

enum { MAXN = 8 };

/* Solves the n x n problem; returns Lemke's status, the answer in z and w = M z + q in w. */
static int solve(uint32_t n, const double *M, const double *q, double *z, double *w)
{
	double T[MAXN * (2 * MAXN + 2)];
	uint32_t basis[MAXN];
	ck_assert_uint_le(csf_lcp_work(n), sizeof T / sizeof T[0]);
	int st = csf_lcp_lemke(n, M, q, z, T, basis);
	for (uint32_t i = 0; i < n; i++) {
		w[i] = q[i];
		for (uint32_t k = 0; k < n; k++) w[i] += M[i * n + k] * z[k];
	}
	return st;
}

/* z >= 0, w >= 0 and z . w = 0, each to 1e-12 of the problem's size. */
static void complementary(uint32_t n, const double *z, const double *w, double size)
{
	for (uint32_t i = 0; i < n; i++) {
		ck_assert_double_ge(z[i], 0);
		ck_assert_double_ge(w[i], -1e-12 * size);
		ck_assert_double_le(fabs(z[i] * w[i]), 1e-12 * size * size);
	}
}

START_TEST(positive_definite)
{
	/* 2 z1 + z2 = 5, z1 + 2 z2 = 6: z = (4/3, 7/3), w = 0 */
	double M[4] = { 2, 1, 1, 2 }, q[2] = { -5, -6 }, z[2], w[2];
	ck_assert_int_eq(solve(2, M, q, z, w), 0);
	ck_assert_double_eq_tol(z[0], 4.0 / 3, 1e-14);
	ck_assert_double_eq_tol(z[1], 7.0 / 3, 1e-14);
	complementary(2, z, w, 6);
	/* the second constraint inactive: z = (5/2, 0), w = (0, 10 + 5/2) */
	double q2[2] = { -5, 10 };
	ck_assert_int_eq(solve(2, M, q2, z, w), 0);
	ck_assert_double_eq_tol(z[0], 2.5, 1e-14);
	ck_assert_double_eq(z[1], 0);
	ck_assert_double_eq_tol(w[1], 12.5, 1e-13);
}
END_TEST

START_TEST(nothing_to_do)
{
	double M[4] = { 1, -3, 2, 1 }, q[2] = { 0, 4 }, z[2] = { 7, 7 }, w[2];
	ck_assert_int_eq(solve(2, M, q, z, w), 0);
	ck_assert_double_eq(z[0], 0);
	ck_assert_double_eq(z[1], 0);
}
END_TEST

START_TEST(redundant_contacts)
{
	/* a body held by two contacts along the same normal: only z1 + z2 = 1 is determined */
	double M[4] = { 1, 1, 1, 1 }, q[2] = { -1, -1 }, z[2], w[2];
	ck_assert_int_eq(solve(2, M, q, z, w), 0);
	ck_assert_double_eq_tol(z[0] + z[1], 1, 1e-14);
	complementary(2, z, w, 1);
}
END_TEST

/*
 * One contact of a unit mass point with a floor: unknowns N, the friction
 * b1..b4 along +t1, -t1, +t2, -t2 and l; the free acceleration has a
 * normal part -an (into the floor) and a tangential part at along t1. The
 * rows: N (the normal acceleration), each direction's tangential
 * acceleration plus l, and the pyramid mu N - sum b.
 */
static void contact(double mu, double an, double at, double *M, double *q)
{
	const double d[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
	for (int i = 0; i < 36; i++) M[i] = 0;
	M[0] = 1, q[0] = -an;
	for (int j = 0; j < 4; j++) {
		for (int k = 0; k < 4; k++) M[(1 + j) * 6 + 1 + k] = d[j][0] * d[k][0] + d[j][1] * d[k][1];
		M[(1 + j) * 6 + 5] = 1;
		q[1 + j] = d[j][0] * at;
	}
	M[5 * 6] = mu;
	for (int k = 0; k < 4; k++) M[5 * 6 + 1 + k] = -1;
	q[5] = 0;
}

START_TEST(friction_sticks)
{
	/* pulled along the floor by 1 m/s^2, pressed by 10: static friction 1 N < 0.3 * 10 holds it */
	double M[36], q[6], z[6], w[6];
	contact(0.3, 10, 1, M, q);
	ck_assert_int_eq(solve(6, M, q, z, w), 0);
	ck_assert_double_eq_tol(z[0], 10, 1e-13);
	ck_assert_double_eq_tol(z[2] - z[1], 1, 1e-13); /* friction against the pull */
	ck_assert_double_eq_tol(z[5], 0, 1e-13);       /* no tangential acceleration: it sticks */
	complementary(6, z, w, 10);
}
END_TEST

START_TEST(friction_slides)
{
	/* pulled by 5 m/s^2: friction is mu N = 3 against it, and it slides at 5 - 3 = 2 m/s^2 */
	double M[36], q[6], z[6], w[6];
	contact(0.3, 10, 5, M, q);
	ck_assert_int_eq(solve(6, M, q, z, w), 0);
	ck_assert_double_eq_tol(z[0], 10, 1e-13);
	ck_assert_double_eq_tol(z[2] - z[1], 3, 1e-13);
	ck_assert_double_eq_tol(z[5], 2, 1e-13);
	complementary(6, z, w, 10);
}
END_TEST

START_TEST(no_solution)
{
	/* w = -z - 1 >= 0 has no z >= 0 */
	double M[1] = { -1 }, q[1] = { -1 }, z[1], w[1];
	ck_assert_int_eq(solve(1, M, q, z, w), -1);
}
END_TEST

START_TEST(ray_with_a_solution)
{
	/* w1 = 2 z2 - 3, w2 = z2 - 2: z = (0, 2), w = (1, 0). No row depends on z1 (a force that
	   moves nothing): the method brings it in first (the complement of w1, which z0 sent out)
	   and nothing limits it, a ray; the shifted diagonal, e = 2e-9, limits it, and the answer
	   solves the problem asked to within e. Without a solution it still says so. */
	double M[4] = { 0, 2, 0, 1 }, q[2] = { -3, -2 }, z[2], w[2];
	double T[2 * 6];
	uint32_t basis[2];
	ck_assert_int_eq(solve(2, M, q, z, w), -1);
	ck_assert_int_eq(csf_lcp_solve(2, M, q, z, T, basis), 1);
	for (uint32_t i = 0; i < 2; i++) w[i] = q[i] + M[i * 2] * z[0] + M[i * 2 + 1] * z[1];
	ck_assert_double_eq_tol(z[0], 0, 1e-8);
	ck_assert_double_eq_tol(z[1], 2, 1e-8);
	ck_assert_double_eq_tol(w[0], 1, 1e-8);
	ck_assert_double_eq_tol(w[1], 0, 1e-8);
	double Mn[1] = { -1 }, qn[1] = { -1 };
	ck_assert_int_eq(csf_lcp_solve(1, Mn, qn, z, T, basis), -1);
	/* where the method finds the answer, it is the method's, unshifted */
	double Mp[4] = { 2, 1, 1, 2 }, qp[2] = { -5, -6 };
	ck_assert_int_eq(csf_lcp_solve(2, Mp, qp, z, T, basis), 0);
	ck_assert_double_eq_tol(z[0], 4.0 / 3, 1e-14);
	ck_assert_double_eq_tol(z[1], 7.0 / 3, 1e-14);
}
END_TEST

Suite *lcp_suite(void)
{
	Suite *s = suite_create("lcp");
	TCase *tc = tcase_create("lemke");
	tcase_add_test(tc, positive_definite);
	tcase_add_test(tc, nothing_to_do);
	tcase_add_test(tc, redundant_contacts);
	tcase_add_test(tc, friction_sticks);
	tcase_add_test(tc, friction_slides);
	tcase_add_test(tc, no_solution);
	tcase_add_test(tc, ray_with_a_solution);
	suite_add_tcase(s, tc);
	return s;
}
