/* Units table: factors against their definitions, dimensions. */
#include <float.h>
#include <math.h>

#include <gsl/gsl_const_mksa.h>

#include "suites.h"

static const struct { const char *name; double factor; signed char dim[NDIM]; } cases[] = {
	{ "m", 1, { 1, 0, 0, 0 } },     { "km", 1000, { 1, 0, 0, 0 } },  { "cm", 0.01, { 1, 0, 0, 0 } },
	{ "um", 1e-6, { 1, 0, 0, 0 } }, { "g", 1e-3, { 0, 1, 0, 0 } },   { "min", 60, { 0, 0, 1, 0 } },
	{ "h", 3600, { 0, 0, 1, 0 } },  { "N", 1, { 1, 1, -2, 0 } },     { "J", 1, { 2, 1, -2, 0 } },
	{ "Pa", 1, { -1, 1, -2, 0 } },  { "Hz", 1, { 0, 0, -1, 0 } },    { "deg", M_PI / 180, { 0, 0, 0, 1 } },
	{ "ft", 0.3048, { 1, 0, 0, 0 } }, { "in", 0.0254, { 1, 0, 0, 0 } }, { "mi", 1609.344, { 1, 0, 0, 0 } },
	{ "lb", 0.45359237, { 0, 1, 0, 0 } }, { "lbf", GSL_CONST_MKSA_POUND_FORCE, { 1, 1, -2, 0 } },
	{ "dyn", 1e-5, { 1, 1, -2, 0 } }, { "erg", 1e-7, { 2, 1, -2, 0 } }, { "mph", 0.44704, { 1, 0, -1, 0 } },
	{ "slug", GSL_CONST_MKSA_POUND_FORCE / 0.3048, { 0, 1, 0, 0 } },
};

START_TEST(test_unit_table)
{
	Unit u;
	ck_assert_msg(unit_lookup(cases[_i].name, &u), "%s is not a unit", cases[_i].name);
	ck_assert_msg(u.factor == cases[_i].factor, "%s: factor %.17g, expected %.17g", cases[_i].name, u.factor,
	              cases[_i].factor);
	for (int d = 0; d < NDIM; d++)
		ck_assert_msg(u.dim[d] == cases[_i].dim[d], "%s: dimension %d is %d", cases[_i].name, d, u.dim[d]);
}
END_TEST

START_TEST(test_not_units)
{
	Unit u;
	ck_assert(!unit_lookup("meter", &u));
	ck_assert(!unit_lookup("x", &u));
	ck_assert(!unit_lookup("", &u));
}
END_TEST

/* Unit expressions in literals: the factor of the compound, through the compiler. */
static const struct { const char *src; double value; } literals[] = {
	{ "36 km/h", 10 },
	{ "1 m/s^2", 1 },
	{ "2 g/cm^3", 2000 },
	{ "1 km^2", 1e6 },
	{ "3 s^-1", 3 },
	{ "1 N*s/m", 1 },
	{ "1 m^3/(kg*s^2)", 1 },
	{ "180 deg", M_PI },
	{ "5 ft", 1.524 },
};

START_TEST(test_unit_literals)
{
	csf_prog p;
	char *src = xprintf("object b: x = %s\ninc t till 1 by 1 watch x\n", literals[_i].src);
	ck_assert_int_eq(compile_string(src, &p, NULL), 0);
	int s = col_slot(&p, "b.x");
	ck_assert_int_ge(s, 0);
	ck_assert_msg(fabs(p.mem0[s] - literals[_i].value) <= 1e-15 * fabs(literals[_i].value), "%s = %.17g",
	              literals[_i].src, p.mem0[s]);
	csf_prog_free(&p);
}
END_TEST

/*
 * Conversions at the extremes: a value from 1e-30 to 1e30 in every unit,
 * converted to each unit system and back, keeps its relative accuracy to a
 * few ulps.
 */
START_TEST(test_extremes)
{
	static const double base[3][3] = { { 1, 1, 1 }, { 1e-2, 1e-3, 1 }, { 0.3048, 0.45359237, 1 } };
	for (const csf_unit *u = csf_unit_table; u->name; u++) {
		double d[3] = { u->dim[DIM_L], u->dim[DIM_M], u->dim[DIM_T] };
		for (int e = -30; e <= 30; e += 3) {
			double x = 1.2345678901234567 * pow(10, e), si = x * u->factor;
			opts.units = _i;
			double sys = dims_to_system(si, d), back = sys;
			for (int k = 0; k < 3; k++) back *= pow(base[_i][k], d[k]);
			ck_assert_msg(fabs(back - si) <= 4 * DBL_EPSILON * fabs(si), "%s, %g, system %d: %.17g -> %.17g", u->name, x, _i,
			              si, back);
		}
	}
	opts.units = 0;
}
END_TEST

/* Under CGS and FPS, bare numbers and constants are in that system's units. */
START_TEST(test_systems)
{
	static const struct { int sys; const char *src; const char *col; double want; } c[] = {
		{ UNITS_CGS, "object b: x = 100\ninc t till 1 by 1 watch x\n", "b.x", 100 },
		{ UNITS_CGS, "object b: x = 2 m\ninc t till 1 by 1 watch x\n", "b.x", 200 },
		{ UNITS_CGS, "object b: x = 1\nrule: y = g.z * x\ninc t till 1 by 1 watch y\n", "b.y", -980.665 },
		{ UNITS_FPS, "object b: x = 3 ft\ninc t till 1 by 1 watch x\n", "b.x", 3 },
		{ UNITS_FPS, "object b: x = 1 lbf\ninc t till 1 by 1 watch x\n", "b.x", 4.44822161526 / 0.45359237 / 0.3048 },
		{ UNITS_MKS, "object b: x = 36 km/h\ninc t till 1 by 1 watch x\n", "b.x", 10 },
	};
	opts.units = c[_i].sys;
	csf_prog p;
	char *d;
	ck_assert_msg(compile_string(c[_i].src, &p, &d) == 0, "%s", d);
	free(d);
	int s = col_slot(&p, c[_i].col);
	ck_assert_int_ge(s, 0);
	double *m = run_out(&p);
	ck_assert_msg(fabs(m[s] - c[_i].want) <= 1e-14 * fabs(c[_i].want), "case %d: %.17g", _i, m[s]);
	free(m);
	csf_prog_free(&p);
	opts.units = 0;
}
END_TEST

Suite *units_suite(void)
{
	Suite *s = suite_create("units");
	TCase *tc = tcase_create("table");
	tcase_add_loop_test(tc, test_unit_table, 0, sizeof cases / sizeof cases[0]);
	tcase_add_test(tc, test_not_units);
	tcase_add_loop_test(tc, test_unit_literals, 0, sizeof literals / sizeof literals[0]);
	tcase_add_loop_test(tc, test_extremes, 0, 3);
	tcase_add_loop_test(tc, test_systems, 0, 6);
	suite_add_tcase(s, tc);
	return s;
}
