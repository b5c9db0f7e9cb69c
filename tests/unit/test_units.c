/* Units table: factors against their definitions, dimensions. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_const_mksa.h>

#include "suites.h"

/* Dimensions: length, mass, time, current. */
static const struct { const char *name; double factor; signed char dim[CSF_NDIM]; } cases[] = {
	{ "m", 1, { 1, 0, 0, 0 } },     { "km", 1000, { 1, 0, 0, 0 } },  { "cm", 0.01, { 1, 0, 0, 0 } },
	{ "um", 1e-6, { 1, 0, 0, 0 } }, { "g", 1e-3, { 0, 1, 0, 0 } },   { "min", 60, { 0, 0, 1, 0 } },
	{ "h", 3600, { 0, 0, 1, 0 } },  { "N", 1, { 1, 1, -2, 0 } },     { "J", 1, { 2, 1, -2, 0 } },
	{ "Pa", 1, { -1, 1, -2, 0 } },  { "Hz", 1, { 0, 0, -1, 0 } },    { "deg", M_PI / 180, { 0, 0, 0, 0 } },
	{ "ft", 0.3048, { 1, 0, 0, 0 } }, { "in", 0.0254, { 1, 0, 0, 0 } }, { "mi", 1609.344, { 1, 0, 0, 0 } },
	{ "lb", 0.45359237, { 0, 1, 0, 0 } }, { "lbf", GSL_CONST_MKSA_POUND_FORCE, { 1, 1, -2, 0 } },
	{ "dyn", 1e-5, { 1, 1, -2, 0 } }, { "erg", 1e-7, { 2, 1, -2, 0 } }, { "mph", 0.44704, { 1, 0, -1, 0 } },
	{ "slug", GSL_CONST_MKSA_POUND_FORCE / 0.3048, { 0, 1, 0, 0 } },
	{ "pdl", 0.45359237 * 0.3048, { 1, 1, -2, 0 } },
	/* electromagnetism: the ampere and the SI derived units */
	{ "A", 1, { 0, 0, 0, 1 } },     { "C", 1, { 0, 0, 1, 1 } },      { "V", 1, { 2, 1, -3, -1 } },
	{ "ohm", 1, { 2, 1, -3, -2 } }, { "S", 1, { -2, -1, 3, 2 } },    { "F", 1, { -2, -1, 4, 2 } },
	{ "H", 1, { 2, 1, -2, -2 } },   { "Wb", 1, { 2, 1, -2, -1 } },   { "T", 1, { 0, 1, -2, -1 } },
	/* SI prefixes, f to T, on every SI unit; u is micro */
	{ "uC", 1e-6, { 0, 0, 1, 1 } }, { "nC", 1e-9, { 0, 0, 1, 1 } },  { "pC", 1e-12, { 0, 0, 1, 1 } },
	{ "kV", 1e3, { 2, 1, -3, -1 } }, { "MV", 1e6, { 2, 1, -3, -1 } }, { "mV", 1e-3, { 2, 1, -3, -1 } },
	{ "mT", 1e-3, { 0, 1, -2, -1 } }, { "uT", 1e-6, { 0, 1, -2, -1 } }, { "nT", 1e-9, { 0, 1, -2, -1 } },
	{ "ns", 1e-9, { 0, 0, 1, 0 } }, { "ps", 1e-12, { 0, 0, 1, 0 } }, { "fs", 1e-15, { 0, 0, 1, 0 } },
	{ "ms", 1e-3, { 0, 0, 1, 0 } }, { "us", 1e-6, { 0, 0, 1, 0 } },  { "ks", 1e3, { 0, 0, 1, 0 } },
	{ "mA", 1e-3, { 0, 0, 0, 1 } }, { "uA", 1e-6, { 0, 0, 0, 1 } },  { "kA", 1e3, { 0, 0, 0, 1 } },
	{ "kohm", 1e3, { 2, 1, -3, -2 } }, { "Mohm", 1e6, { 2, 1, -3, -2 } }, { "mohm", 1e-3, { 2, 1, -3, -2 } },
	{ "uF", 1e-6, { -2, -1, 4, 2 } }, { "nF", 1e-9, { -2, -1, 4, 2 } }, { "pF", 1e-12, { -2, -1, 4, 2 } },
	{ "mH", 1e-3, { 2, 1, -2, -2 } }, { "uH", 1e-6, { 2, 1, -2, -2 } }, { "mS", 1e-3, { -2, -1, 3, 2 } },
	{ "mWb", 1e-3, { 2, 1, -2, -1 } }, { "kN", 1e3, { 1, 1, -2, 0 } }, { "MJ", 1e6, { 2, 1, -2, 0 } },
	{ "GW", 1e9, { 2, 1, -3, 0 } }, { "kPa", 1e3, { -1, 1, -2, 0 } }, { "TPa", 1e12, { -1, 1, -2, 0 } },
	{ "MHz", 1e6, { 0, 0, -1, 0 } }, { "GHz", 1e9, { 0, 0, -1, 0 } }, { "mrad", 1e-3, { 0, 0, 0, 0 } },
	{ "mm", 1e-3, { 1, 0, 0, 0 } }, { "nm", 1e-9, { 1, 0, 0, 0 } },  { "pm", 1e-12, { 1, 0, 0, 0 } },
	{ "Mm", 1e6, { 1, 0, 0, 0 } },  { "mg", 1e-6, { 0, 1, 0, 0 } },  { "ug", 1e-9, { 0, 1, 0, 0 } },
	{ "ng", 1e-12, { 0, 1, 0, 0 } }, { "Mg", 1e3, { 0, 1, 0, 0 } },  { "kg", 1, { 0, 1, 0, 0 } },
};

START_TEST(test_unit_table)
{
	Unit u;
	ck_assert_msg(unit_lookup(cases[_i].name, &u), "%s is not a unit", cases[_i].name);
	ck_assert_msg(u.factor == cases[_i].factor, "%s: factor %.17g, expected %.17g", cases[_i].name, u.factor,
	              cases[_i].factor);
	for (int d = 0; d < CSF_NDIM; d++)
		ck_assert_msg(u.dim[d] == cases[_i].dim[d], "%s: dimension %d is %d", cases[_i].name, d, u.dim[d]);
}
END_TEST

START_TEST(test_not_units)
{
	Unit u;
	/* no prefix on a unit that is not SI, on kg, twice, or that SI does not have (d, h, da, E) */
	static const char *const no[] = { "meter", "x", "", "mkg", "kmin", "kh", "kft", "klb", "mdeg", "kerg", "mmm",
	                                  "dm", "hPa", "EJ", "Ohm", "volt", "uu", "k" };
	for (size_t i = 0; i < sizeof no / sizeof no[0]; i++) ck_assert_msg(!unit_lookup(no[i], &u), "'%s' is a unit", no[i]);
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
	{ "4 1/s^2", 4 },
	{ "3 (1/s)", 3 },
	{ "2 1/(s*A)", 2 },
	{ "230 kV", 230e3 },
	{ "5 uC", 5e-6 },
	{ "2 mT", 2e-3 },
	{ "7 ns", 7e-9 },
	{ "2 F", 2 },
	{ "3 C", 3 },
	{ "50 ohm", 50 },
	{ "1.602176634e-19 C", 1.602176634e-19 },
};

/* The SI derived units of electromagnetism are what their definitions say: x - y is 0 (dimensions agree). */
static const struct { const char *x, *y; } same[] = {
	{ "C", "A*s" },      { "V", "W/A" },    { "ohm", "V/A" },   { "S", "A/V" },      { "S", "1/ohm" },
	{ "F", "C/V" },      { "Wb", "V*s" },   { "T", "Wb/m^2" },  { "H", "Wb/A" },     { "T", "N/(A*m)" },
	{ "J", "C*V" },      { "W", "V*A" },    { "H", "ohm*s" },   { "F", "s/ohm" },    { "mT", "mWb/m^2" },
	{ "kV", "kW/A" },    { "uC", "uA*s" },  { "ns", "us/1000" }, { "N", "C*V/m" },   { "kohm", "kV/A" },
};

START_TEST(test_em_identities)
{
	csf_prog p;
	char *d;
	char *src = xprintf("object b: x = 1 %s\nobject b: y = 1 %s\nrule: z = x - y\ninc t till 1 s by 1 s watch z\n",
	                    same[_i].x, same[_i].y);
	ck_assert_msg(compile_string(src, &p, &d) == 0, "%s - %s: %s", same[_i].x, same[_i].y, d);
	free(d);
	int s = col_slot(&p, "b.z");
	ck_assert_int_ge(s, 0);
	double *m = run_out(&p);
	ck_assert_msg(fabs(m[s]) <= 1e-15, "1 %s - 1 %s = %.17g", same[_i].x, same[_i].y, m[s]);
	free(m);
	csf_prog_free(&p);
}
END_TEST

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

/* The SI prefixes, written independently of the runtime's table. */
static const struct { const char *p; double f; } prefixes[] = {
	{ "f", 1e-15 }, { "p", 1e-12 }, { "n", 1e-9 }, { "u", 1e-6 }, { "m", 1e-3 },
	{ "c", 1e-2 },  { "k", 1e3 },   { "M", 1e6 },  { "G", 1e9 },  { "T", 1e12 },
};

/*
 * Every prefix on every unit that takes one: the unit's dimension, and the
 * prefix's factor exactly (times 1e-3 for the gram, to the nearest double);
 * a unit that takes none refuses every prefix.
 */
START_TEST(test_prefixes)
{
	for (const csf_unit *k = csf_unit_table; k->name; k++)
		for (size_t i = 0; i < sizeof prefixes / sizeof prefixes[0]; i++) {
			char name[32];
			snprintf(name, sizeof name, "%s%s", prefixes[i].p, k->name);
			Unit u, b;
			if (!k->prefixes) {
				/* no prefix, unless the name is one of the table's, read whole (min is not m in) */
				int whole = 0;
				for (const csf_unit *w = csf_unit_table; w->name; w++) whole |= strcmp(w->name, name) == 0;
				ck_assert_msg(whole || !unit_lookup(name, &u), "%s takes a prefix: %s", k->name, name);
				continue;
			}
			ck_assert_msg(unit_lookup(name, &u) && unit_lookup(k->name, &b), "%s is not a unit", name);
			ck_assert_msg(memcmp(u.dim, b.dim, sizeof u.dim) == 0, "%s: dimension", name);
			double want = prefixes[i].f * b.factor;
			ck_assert_msg(b.factor == 1 ? u.factor == want : fabs(u.factor - want) <= DBL_EPSILON * want,
			              "%s: %.17g, expected %.17g", name, u.factor, want);
		}
}
END_TEST

/* The round trip of SI value si of unit name's dimension to system sys and back, to a few ulps. */
static void round_trip(const char *name, int sys)
{
	static const double base[3][CSF_NDIM] = { { 1, 1, 1, 1 }, { 1e-2, 1e-3, 1, 1 }, { 0.3048, 0.45359237, 1, 1 } };
	Unit u;
	ck_assert_msg(unit_lookup(name, &u), "%s", name);
	double d[CSF_NDIM];
	for (int k = 0; k < CSF_NDIM; k++) d[k] = u.dim[k];
	for (int e = -30; e <= 30; e += 3) {
		double x = 1.2345678901234567 * pow(10, e), si = x * u.factor;
		opts.units = sys;
		double v = dims_to_system(si, d), back = v;
		for (int k = 0; k < CSF_NDIM; k++) back *= pow(base[sys][k], d[k]);
		ck_assert_msg(fabs(back - si) <= 4 * DBL_EPSILON * fabs(si), "%s, %g, system %d: %.17g -> %.17g", name, x, sys,
		              si, back);
	}
	opts.units = 0;
}

/*
 * Conversions at the extremes: a value from 1e-30 to 1e30 in every unit of
 * the table and every prefixed one, converted to each unit system and
 * back, keeps its relative accuracy to a few ulps.
 */
START_TEST(test_extremes)
{
	for (const csf_unit *k = csf_unit_table; k->name; k++) {
		round_trip(k->name, _i);
		for (size_t i = 0; k->prefixes && i < sizeof prefixes / sizeof prefixes[0]; i++) {
			char name[32];
			snprintf(name, sizeof name, "%s%s", prefixes[i].p, k->name);
			round_trip(name, _i);
		}
	}
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
		/* the electromagnetic units: the ampere is the same, the mechanical part converted */
		{ UNITS_CGS, "object b: x = 230 V\ninc t till 1 by 1 watch x\n", "b.x", 230e7 },
		{ UNITS_CGS, "object b: x = 2 uC\ninc t till 1 by 1 watch x\n", "b.x", 2e-6 },
		{ UNITS_CGS, "object b: x = 1 T\ninc t till 1 by 1 watch x\n", "b.x", 1e3 },
		{ UNITS_FPS, "object b: x = 1 T\ninc t till 1 by 1 watch x\n", "b.x", 1 / 0.45359237 },
		{ UNITS_FPS, "object b: x = 50 ohm\ninc t till 1 by 1 watch x\n", "b.x", 50 / 0.45359237 / 0.3048 / 0.3048 },
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
	tcase_add_test(tc, test_prefixes);
	tcase_add_loop_test(tc, test_extremes, 0, 3);
	tcase_add_loop_test(tc, test_systems, 0, 11);
	tcase_add_loop_test(tc, test_em_identities, 0, sizeof same / sizeof same[0]);
	suite_add_tcase(s, tc);
	return s;
}
