/*
 * The impulses that stop a slip in a cluster, by the dual active-set
 * method over rows (runtime/contact/impulse.c, csf_contact_dual_rows),
 * against answers worked by hand. Ball A (1 kg) slides on the floor and
 * touches ball B (1 kg) beside it, B on the floor too: pair 0 is A and the
 * floor (normal z; its normal and its tangent x held at zero: A's slip
 * stops), pair 1 is B and A (normal x, from A to B), pair 2 is B and the
 * floor (normal z). The couplings G (the change of a pair's relative
 * velocity per unit impulse on another's): G00 = 1, G01 = -1, G11 = 2,
 * G12 = 1, G22 = 1, G02 = 0.
 */
#include <stdlib.h>
#include <string.h>

#include "suites.h"
#include "contact_int.h"

static csf_contacts *three_pairs(void)
{
	csf_contacts *cs = calloc(1, sizeof *cs);
	ck_assert_ptr_nonnull(cs);
	cs->K = calloc(DIRECT_MAX * DIRECT_MAX, sizeof *cs->K);
	cs->G = calloc(DIRECT_MAX * DIRECT_MAX, sizeof *cs->G);
	cs->rhs = calloc(DIRECT_MAX, sizeof *cs->rhs);
	cs->x = calloc(DIRECT_MAX, sizeof *cs->x);
	cs->at = calloc(DIRECT_MAX, sizeof *cs->at);
	ck_assert(cs->K && cs->G && cs->rhs && cs->x && cs->at);
	const double G[9] = { 1, -1, 0, -1, 2, 1, 0, 1, 1 };
	memcpy(cs->G, G, sizeof G);
	return cs;
}

static void three_free(csf_contacts *cs)
{
	free(cs->K), free(cs->G), free(cs->rhs), free(cs->x), free(cs->at), free(cs);
}

/* the rows: A on the floor (normal and tangent, held), B against A, B on the floor */
static const csf_srow rows[4] = {
	{ { 0, 0, 1 }, 0, 1, 0 }, { { 1, 0, 0 }, 0, 1, 0 }, { { 1, 0, 0 }, 1, 0, 0 }, { { 0, 0, 1 }, 2, 0, 0 }
};
static const double vres[3] = { 1e-12, 1e-12, 1e-12 };

/* Both balls slide at u towards A's side (-x): A stops, and stops B, which presses on it: every
   velocity 0; the floor takes both momenta (2 u along x at A), A pushes B with u. */
START_TEST(pushed_along)
{
	csf_contacts *cs = three_pairs();
	double u = 0.375, vr[3][3] = { { -u, 0, 0 }, { 0, 0, 0 }, { -u, 0, 0 } }, x[4];
	unsigned char in[4];
	ck_assert_int_eq(csf_contact_dual_rows(cs, 3, rows, 4, vr, vres, x, in), 0);
	ck_assert_double_eq(x[0], 0);
	ck_assert_double_eq(x[1], 2 * u);
	ck_assert_double_eq(x[2], u);
	ck_assert_double_eq(x[3], 0);
	ck_assert(in[0] && in[1] && in[2]);
	three_free(cs);
}
END_TEST

/* Both slide at u away from A's side (+x): A stops, B goes on, the pair between them parting. */
START_TEST(left_behind)
{
	csf_contacts *cs = three_pairs();
	double u = 0.375, vr[3][3] = { { u, 0, 0 }, { 0, 0, 0 }, { u, 0, 0 } }, x[4];
	unsigned char in[4];
	ck_assert_int_eq(csf_contact_dual_rows(cs, 3, rows, 4, vr, vres, x, in), 0);
	ck_assert_double_eq(x[1], -u);
	ck_assert_double_eq(x[2], 0);
	ck_assert_double_eq(x[3], 0);
	ck_assert(in[0] && in[1] && !in[2] && !in[3]);
	three_free(cs);
}
END_TEST

/* B falls onto the floor at w while A slides at u towards it: A's stop takes A's slip (u), B is
   at rest along x and A no longer closes on it, the floor stops B's fall (w); with A sliding
   away and B rising at w instead, neither normal takes anything. */
START_TEST(fall_and_rise)
{
	csf_contacts *cs = three_pairs();
	double u = 0.25, w = 1.5, vr[3][3] = { { u, 0, 0 }, { -u, 0, -w }, { 0, 0, -w } }, x[4];
	unsigned char in[4];
	/* pair 1 is B less A: B at rest along x, A at u towards it; B falls at w */
	ck_assert_int_eq(csf_contact_dual_rows(cs, 3, rows, 4, vr, vres, x, in), 0);
	ck_assert_double_eq(x[1], -u);
	ck_assert_double_eq(x[2], 0);
	ck_assert_double_eq(x[3], w);
	ck_assert(in[3] && !in[2]);
	double vr2[3][3] = { { -u, 0, 0 }, { u, 0, w }, { 0, 0, w } };
	ck_assert_int_eq(csf_contact_dual_rows(cs, 3, rows, 4, vr2, vres, x, in), 0);
	ck_assert_double_eq(x[1], u);
	ck_assert_double_eq(x[2], 0);
	ck_assert_double_eq(x[3], 0);
	ck_assert(!in[2] && !in[3]);
	three_free(cs);
}
END_TEST

/* An impact (the rows of cluster_impulses: one normal a pair, the hit's held at its target): A
   lands on the floor at 2 m/s and leaves at its target, 1.5 m/s, while sliding into B at 0.5 m/s:
   the floor's impulse 3.5, and A's push on B 0.25, which leaves A and B both at 0.25 m/s along x
   (B's floor, its normal across that, takes nothing). */
START_TEST(impact_target)
{
	csf_contacts *cs = three_pairs();
	const csf_srow hit[3] = { { { 0, 0, 1 }, 0, 1, 1.5 }, { { 1, 0, 0 }, 1, 0, 0 }, { { 0, 0, 1 }, 2, 0, 0 } };
	double vr[3][3] = { { 0.5, 0, -2 }, { -0.5, 0, 2 }, { 0, 0, 0 } }, x[3];
	unsigned char in[3];
	ck_assert_int_eq(csf_contact_dual_rows(cs, 3, hit, 3, vr, vres, x, in), 0);
	ck_assert_double_eq(x[0], 3.5);
	ck_assert_double_eq(x[1], 0.25);
	ck_assert_double_eq(x[2], 0);
	ck_assert(in[0] && in[1] && !in[2]);
	three_free(cs);
}
END_TEST

/* A slide a stop's impulses leave sliding (csf_contact_slide_turned; normal z, vres 1e-12): one
   whose slip they change by less than its size slides on, grown or slowed, its normal part
   aside; one turned back, or changed by more than its size, is held (friction stops it). A
   slide of 0.16 m/s sped up by 1e-10 m/s by a neighbour's stop of 2.6e-10 m/s was held, and
   stopped, in a pile of 64 balls (impulse.c, stick_dual). */
START_TEST(slide_turned)
{
	const double z[3] = { 0, 0, 1 }, u = 0.16;
	const double v0[3] = { u, 0, 0 }, grown[3] = { u + 1e-10, 0, 0 }, slowed[3] = { u / 4, 0, 0 }, none[3] = { 0, 0, 0 };
	const double back[3] = { -0.01, 0, 0 }, doubled[3] = { 2 * u + 1e-9, 0, 0 }, lifted[3] = { u, 0, 3 };
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, grown, 1e-12), 0);
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, slowed, 1e-12), 0);
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, none, 1e-12), 0);
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, lifted, 1e-12), 0);
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, back, 1e-12), 1);
	ck_assert_int_eq(csf_contact_slide_turned(z, v0, doubled, 1e-12), 1);
	/* a slip of 1e-11 m/s turned sideways to 5e-9 m/s; and one within vres, changed within vres */
	const double tiny[3] = { 1e-11, 0, 2 }, sideways[3] = { 1e-11, 5e-9, 0 }, within[3] = { 1.5e-12, 0, 0 };
	ck_assert_int_eq(csf_contact_slide_turned(z, tiny, sideways, 1e-12), 1);
	ck_assert_int_eq(csf_contact_slide_turned(z, (const double[3]){ 1e-12, 0, 0 }, within, 1e-12), 0);
}
END_TEST

Suite *dualrows_suite(void)
{
	Suite *s = suite_create("dualrows");
	TCase *tc = tcase_create("core");
	tcase_add_test(tc, pushed_along);
	tcase_add_test(tc, left_behind);
	tcase_add_test(tc, fall_and_rise);
	tcase_add_test(tc, impact_target);
	tcase_add_test(tc, slide_turned);
	suite_add_tcase(s, tc);
	return s;
}
