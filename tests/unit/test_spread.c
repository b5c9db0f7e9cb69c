/*
 * The forces of a statically indeterminate cluster brought within the
 * friction cones (runtime/contact/spread.c), against closed forms.
 *
 * A ball stuck in a corner, touching a floor (normal z) and a wall
 * (normal x), with mu_s = 1/2 at both; the contacts must carry R = (P, 0,
 * 2) (the ball's weight, 2, and a push P): F_floor + F_wall = R. With P =
 * 0 the least-norm forces are R/2 each, which leave the wall's friction 1
 * with no normal force, beyond its cone. The smallest self-stress s
 * (F_floor = R/2 + s, F_wall = R/2 - s) that brings both within: the
 * wall's cone is met, mu' (1 - s_z) = -s_x with mu' = mu (1 - 1e-9), and
 * |s|^2 = s_x^2 + s_z^2 least there: -s_x = mu' / (1 + mu'^2), s_z = 1 /
 * (1 + mu'^2). So F_floor = (-0.4, 0, 1.8), F_wall = (0.4, 0, 0.2) to
 * 1e-9 (the wall's friction 0.2 = mu N). Forces within their cones are
 * left as they are, to the bit; a push away from the wall of 1.5, more
 * than mu times the weight, has no forces that hold it: x as it was.
 */
#include <stdlib.h>
#include <string.h>

#include "suites.h"
#include "contact_int.h"

enum { BALL = 0, FLOOR = CSF_CF_N, WALL = 2 * CSF_CF_N };

/* The corner: two pairs of the ball with planes, each sticking with three unknowns (N, then the
   friction along the other axis in the plane, then across it). */
typedef struct corner {
	csf_contacts cs;
	cpair pairs[2];
	uint32_t s[3][CSF_CF_N];
	double m[3 * CSF_CF_N], B[18], nv[6];
	uint32_t at[2];
	unsigned char dc[2], cone[2];
} corner;

static void corner_init(corner *k)
{
	memset(k, 0, sizeof *k);
	for (int b = 0; b < 3; b++)
		for (int f = 0; f < CSF_CF_N; f++) k->s[b][f] = (uint32_t)(b * CSF_CF_N + f);
	k->m[BALL + CSF_CF_M] = k->m[FLOOR + CSF_CF_M] = k->m[WALL + CSF_CF_M] = 1;
	k->m[BALL + CSF_CF_MUS] = 0.5;
	k->cs.pairs = k->pairs, k->cs.n = 2;
	for (int a = 0; a < 2; a++) {
		k->pairs[a].si = k->s[0], k->pairs[a].sj = k->s[1 + a], k->pairs[a].plane = 1;
		k->at[a] = 3 * (uint32_t)a, k->dc[a] = 3, k->cone[a] = 1;
	}
	const double B[18] = { 0, 0, 1, 1, 0, 0, 0, 1, 0, /* floor: z, x, y */
		               1, 0, 0, 0, 0, 1, 0, 1, 0 /* wall: x, z, y */ };
	memcpy(k->B, B, sizeof B);
	const double nv[6] = { 0, 0, 1, 1, 0, 0 };
	memcpy(k->nv, nv, sizeof nv);
}

/* The forces of x on the ball, floor's and wall's. */
static void forces(const corner *k, const double *x, double F[2][3])
{
	for (int a = 0; a < 2; a++)
		for (int j = 0; j < 3; j++) {
			F[a][j] = 0;
			for (int q = 0; q < 3; q++) F[a][j] += k->B[9 * a + 3 * q + j] * x[3 * a + q];
		}
}

static int spread(corner *k, double *x)
{
	const uint32_t cl[2] = { 0, 1 };
	return csf_contact_spread(&k->cs, k->m, cl, 2, 6, k->dc, k->at, k->B, k->nv, k->cone, x);
}

START_TEST(corner_least_stress)
{
	corner k;
	corner_init(&k);
	double x[6] = { 1, 0, 0, 0, 1, 0 }, F[2][3]; /* R/2 each: the floor's N 1, the wall's friction 1 */
	ck_assert_int_eq(spread(&k, x), 1);
	forces(&k, x, F);
	ck_assert_double_eq_tol(F[0][0], -0.4, 1e-9);
	ck_assert_double_eq_tol(F[0][2], 1.8, 1e-9);
	ck_assert_double_eq_tol(F[1][0], 0.4, 1e-9);
	ck_assert_double_eq_tol(F[1][2], 0.2, 1e-9);
	for (int j = 0; j < 3; j++) ck_assert_double_eq_tol(F[0][j] + F[1][j], j == 2 ? 2 : 0, 1e-15);
	ck_assert_double_eq(F[0][1], 0); /* nothing across the plane */
	ck_assert_double_eq(F[1][1], 0);
	ck_assert(fabs(F[1][2]) <= 0.5 * F[1][0]); /* within the cones */
	ck_assert(fabs(F[0][0]) <= 0.5 * F[0][2]);
}
END_TEST

START_TEST(within_left_alone)
{
	corner k;
	corner_init(&k);
	double x[6] = { 1.5, 0.25, 0, 0.5, 0.2, 0 }, y[6]; /* F_floor (0.25, 0, 1.5), F_wall (0.5, 0, 0.2) */
	memcpy(y, x, sizeof x);
	ck_assert_int_eq(spread(&k, x), 0);
	ck_assert_mem_eq(x, y, sizeof x);
}
END_TEST

START_TEST(pull_too_strong)
{
	corner k;
	corner_init(&k);
	/* R = (-1.5, 0, 2): least norm R/2 each, the wall pulling; no forces within the cones give it */
	double x[6] = { 1, -0.75, 0, -0.75, 1, 0 }, y[6];
	memcpy(y, x, sizeof x);
	ck_assert_int_eq(spread(&k, x), -1);
	ck_assert_mem_eq(x, y, sizeof x);
	/* a pull of 0.8 (less than mu times the weight): the floor's friction holds it, the wall pushing
	   not at all or a little, every force within its cone and R carried */
	double z[6] = { 1, -0.4, 0, -0.4, 1, 0 }, F[2][3];
	ck_assert_int_eq(spread(&k, z), 1);
	forces(&k, z, F);
	ck_assert_double_eq_tol(F[0][0] + F[1][0], -0.8, 1e-15);
	ck_assert_double_eq_tol(F[0][2] + F[1][2], 2, 1e-15);
	ck_assert(F[1][0] >= 0 && F[0][2] >= 0);
	ck_assert(fabs(F[1][2]) <= 0.5 * F[1][0] + 1e-15);
	ck_assert(fabs(F[0][0]) <= 0.5 * F[0][2]);
}
END_TEST

Suite *spread_suite(void)
{
	Suite *s = suite_create("spread");
	TCase *tc = tcase_create("core");
	tcase_add_test(tc, corner_least_stress);
	tcase_add_test(tc, within_left_alone);
	tcase_add_test(tc, pull_too_strong);
	suite_add_tcase(s, tc);
	return s;
}
