/*
 * The recall of solved contact systems (runtime/contact/cluster.c): a
 * system the same to the last bit as one solved lately is answered from
 * the record, with exactly the answer a solve gives, and what a failed
 * solve leaves for the least-squares solve after it. Known answers: a
 * system of two blocks ((2 1; 1 2) x = (5, 6), x = (4/3, 7/3), and 4 x =
 * 8), one of its blocks changed, two contacts that say the same (singular;
 * least norm (1, 1)), a system of zeros (least norm 0), and more systems
 * than are kept.
 */
#include <stdlib.h>
#include <string.h>

#include "suites.h"
#include "contact_int.h"

static csf_contacts *system_new(void)
{
	csf_contacts *cs = calloc(1, sizeof *cs);
	ck_assert_ptr_nonnull(cs);
	cs->K = calloc(DIRECT_MAX * DIRECT_MAX, sizeof *cs->K);
	cs->rhs = calloc(DIRECT_MAX, sizeof *cs->rhs);
	cs->x = calloc(DIRECT_MAX, sizeof *cs->x);
	ck_assert(cs->K && cs->rhs && cs->x);
	return cs;
}

static void set(csf_contacts *cs, uint32_t dim, const double *K, const double *b)
{
	memcpy(cs->K, K, (size_t)dim * dim * sizeof *K);
	memcpy(cs->rhs, b, dim * sizeof *b);
}

START_TEST(same_answer)
{
	csf_contacts *cs = system_new();
	const double K[9] = { 2, 1, 0, 1, 2, 0, 0, 0, 4 }, b[3] = { 5, 6, 8 };
	double x[3];
	set(cs, 3, K, b);
	ck_assert_int_eq(csf_contact_solve(cs, 3, NULL, 1, NULL, NULL), 0);
	ck_assert_uint_eq(cs->recalled, 0);
	memcpy(x, cs->x, sizeof x);
	ck_assert_double_eq_tol(x[0], 4.0 / 3, 1e-15);
	ck_assert_double_eq_tol(x[1], 7.0 / 3, 1e-15);
	ck_assert_double_eq(x[2], 2);
	/* the same bits again: both blocks recalled, the answer the same bits */
	memset(cs->x, 0, 3 * sizeof *cs->x);
	set(cs, 3, K, b);
	ck_assert_int_eq(csf_contact_solve(cs, 3, NULL, 1, NULL, NULL), 0);
	ck_assert_uint_eq(cs->recalled, 2);
	ck_assert_mem_eq(cs->x, x, sizeof x);
	/* one block changed (8 -> 12): it is solved, the other recalled */
	const double b2[3] = { 5, 6, 12 };
	set(cs, 3, K, b2);
	ck_assert_int_eq(csf_contact_solve(cs, 3, NULL, 1, NULL, NULL), 0);
	ck_assert_uint_eq(cs->recalled, 3);
	ck_assert_mem_eq(cs->x, x, 2 * sizeof *x);
	ck_assert_double_eq(cs->x[2], 3);
	/* a change in the last bit of one coefficient is a new system */
	double K3[9];
	memcpy(K3, K, sizeof K3);
	K3[0] = nextafter(2, 3);
	set(cs, 3, K3, b);
	ck_assert_int_eq(csf_contact_solve(cs, 3, NULL, 1, NULL, NULL), 0);
	ck_assert_uint_eq(cs->recalled, 4); /* only the block 4 x = 8 */
	ck_assert_double_lt(cs->x[0], x[0]);
	csf_contacts_free(cs);
}
END_TEST

START_TEST(failure_recalled)
{
	/* two contacts along the same normal: singular, the direct solve fails (no K1 given), and
	   the least-squares solve after it gives the least-norm forces (1, 1), from what the failed
	   solve left; recalled, the failure leaves the same */
	csf_contacts *cs = system_new();
	const double K[4] = { 1, 1, 1, 1 }, b[2] = { 2, 2 };
	for (int round = 0; round < 2; round++) {
		set(cs, 2, K, b);
		ck_assert_int_eq(csf_contact_solve(cs, 2, NULL, 1, NULL, NULL), -1);
		ck_assert_uint_eq(cs->recalled, (uint64_t)round);
		ck_assert_int_eq(csf_contact_least_squares(cs, 2, NULL, NULL), 0);
		ck_assert_double_eq_tol(cs->x[0], 1, 1e-15);
		ck_assert_double_eq_tol(cs->x[1], 1, 1e-15);
		memset(cs->kb, 0, 6 * sizeof *cs->kb); /* not what the recall reads */
	}
	/* a system of zeros (no coupling at all): the solve fails at once, and leaves this system
	   aside, not the one before, so that the least-squares answer is its own, x = 0; recalled
	   the same (before, the singular system's (1, 1) came back) */
	const double Z[4] = { 0, 0, 0, 0 };
	for (int round = 0; round < 2; round++) {
		set(cs, 2, K, b); /* the singular system first (recalled): it is what cs->kb holds */
		ck_assert_int_eq(csf_contact_solve(cs, 2, NULL, 1, NULL, NULL), -1);
		set(cs, 2, Z, b);
		ck_assert_int_eq(csf_contact_solve(cs, 2, NULL, 1, NULL, NULL), -1);
		ck_assert_uint_eq(cs->recalled, (uint64_t)(2 + 2 * round));
		ck_assert_int_eq(csf_contact_least_squares(cs, 2, NULL, NULL), 0);
		ck_assert_double_eq(cs->x[0], 0);
		ck_assert_double_eq(cs->x[1], 0);
	}
	csf_contacts_free(cs);
}
END_TEST

START_TEST(more_than_kept)
{
	/* 1 x 1 systems k x = k^2 (x = k): 100 of them, each new, then the first again (long
	   replaced: solved again, right); one used between every two new ones stays */
	csf_contacts *cs = system_new();
	const double K7[1] = { 7 }, b7[1] = { 49 };
	for (int k = 1; k <= 100; k++) {
		double K[1] = { k }, b[1] = { (double)k * k };
		set(cs, 1, K, b);
		ck_assert_int_eq(csf_contact_solve(cs, 1, NULL, 1, NULL, NULL), 0);
		ck_assert_double_eq(cs->x[0], k);
		set(cs, 1, K7, b7);
		ck_assert_int_eq(csf_contact_solve(cs, 1, NULL, 1, NULL, NULL), 0);
		ck_assert_double_eq(cs->x[0], 7);
	}
	ck_assert_uint_eq(cs->recalled, 100 - 1 + 1); /* every use of 7 x = 49 but its first, and k = 7 */
	uint64_t before = cs->recalled;
	const double K1[1] = { 1 }, b1[1] = { 1 };
	set(cs, 1, K1, b1);
	ck_assert_int_eq(csf_contact_solve(cs, 1, NULL, 1, NULL, NULL), 0);
	ck_assert_double_eq(cs->x[0], 1);
	ck_assert_uint_eq(cs->recalled, before);
	csf_contacts_free(cs);
}
END_TEST

/*
 * The friction's rank held near its threshold (cluster.c, held_rank). A
 * normal force x0 and two friction unknowns x1, x2 (T = I, fric 0 1 1) in
 * K = (1 1 0; 0 1 1; 0 0 e), b = (2, 1, e): the exact answer is (2, 0, 1)
 * for every e. The friction's columns off the normal force's, (0, 1, 0)
 * and (0, 1, e), have the pivots 1 and about e; the threshold is 1e-10 of
 * A's largest column (sqrt 2), 1.414e-10. Its rank 2 gives the exact
 * answer; rank 1 leaves the direction of e out and takes the least-norm
 * friction of the other, x1 = x2 = 1/2 to 1e-9 (and x0 = 3/2). A pivot
 * below the threshold by less than a factor of 4 is kept if the last solve
 * of the same system's shape kept it; above the threshold, or below the
 * band, the threshold decides. Only the force stage holds (cs->hold): an
 * impact's solve takes the threshold's rank.
 */
static void solve_e(csf_contacts *cs, double e, double x2)
{
	const double K[9] = { 1, 1, 0, 0, 1, 1, 0, 0, e }, b[3] = { 2, 1, e }, T[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
	const unsigned char fric[3] = { 0, 1, 1 };
	memcpy(cs->kb, K, sizeof K);
	memcpy(cs->kb + 9, b, sizeof b);
	ck_assert_int_eq(csf_contact_least_squares(cs, 3, T, fric), 0);
	ck_assert_double_eq_tol(cs->x[2], x2, 1e-9);
	ck_assert_double_eq_tol(cs->x[1], 1 - x2, 1e-9);
	ck_assert_double_eq_tol(cs->x[0], 1 + x2, 1e-9);
}

START_TEST(rank_held)
{
	csf_contacts *cs = system_new();
	cs->kb = calloc(12, sizeof *cs->kb);
	ck_assert_ptr_nonnull(cs->kb);
	cs->hold = 1;
	solve_e(cs, 4e-10, 1);     /* above the threshold, in the band: the threshold's rank, 2 */
	solve_e(cs, 1e-10, 1);     /* below it, in the band: 2 held (the threshold alone: 1, x2 = 1/2) */
	solve_e(cs, 1e-11, 0.5);   /* below the band: 1 */
	solve_e(cs, 1e-10, 0.5);   /* in the band again, below the threshold: 1, as last */
	solve_e(cs, 4e-10, 1);     /* above the threshold: 2 */
	solve_e(cs, 1e-10, 1);     /* below it, in the band: 2 held */
	ck_assert_int_eq(cs->held_now, 1);
	cs->hold = 0;
	solve_e(cs, 1e-10, 0.5);   /* not the force stage: the threshold's rank */
	cs->hold = 1;
	solve_e(cs, 1e-6, 1);      /* far from the threshold: not held */
	csf_contacts_free(cs);
}
END_TEST

Suite *recall_suite(void)
{
	Suite *s = suite_create("recall");
	TCase *tc = tcase_create("core");
	tcase_add_test(tc, same_answer);
	tcase_add_test(tc, failure_recalled);
	tcase_add_test(tc, more_than_kept);
	tcase_add_test(tc, rank_held);
	suite_add_tcase(s, tc);
	return s;
}
