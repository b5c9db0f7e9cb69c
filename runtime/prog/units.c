/*
 * units.c - the unit table, defined once for the compiler and the runtime:
 * every unit name CSF knows, its factor to SI and its dimension (exponents
 * of length, mass, time, current; angles are dimensionless), and the SI
 * prefixes every SI unit takes (`kV`, `uC`, `ns`, `mT`). Factors come from
 * GSL's constant tables wherever GSL has the unit; the rest are exact by
 * definition (SI prefixes, minute, hour, degree).
 *
 * The compiler reads unit expressions from its tokens (compiler/front/layout.c);
 * the runtime reads them from text (csf_unit_parse: the values of -D and
 * --sweep) with the same arithmetic, left to right, `^` by pow(), so a
 * value given on the command line is the same double as the same literal
 * in the source.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_const_mksa.h>

#include "csf_int.h"

/* Dimensions: length, mass, time, current (CSF_NDIM) */
#define LEN { 1, 0, 0, 0 }
#define MASS { 0, 1, 0, 0 }
#define TIME { 0, 0, 1, 0 }
#define CURRENT { 0, 0, 0, 1 }
#define NONE { 0, 0, 0, 0 }
#define FORCE { 1, 1, -2, 0 }
#define ENERGY { 2, 1, -2, 0 }
#define POWER { 2, 1, -3, 0 }
#define PRESSURE { -1, 1, -2, 0 }
#define FREQ { 0, 0, -1, 0 }
#define SPEED { 1, 0, -1, 0 }
#define ACCEL { 1, 0, -2, 0 }
#define CHARGE { 0, 0, 1, 1 }
#define VOLTAGE { 2, 1, -3, -1 }
#define RESISTANCE { 2, 1, -3, -2 }
#define CONDUCTANCE { -2, -1, 3, 2 }
#define CAPACITANCE { -2, -1, 4, 2 }
#define INDUCTANCE { 2, 1, -2, -2 }
#define FLUX { 2, 1, -2, -1 }
#define FLUX_DENSITY { 0, 1, -2, -1 }

/* a unit that takes the SI prefixes, 10^decade of the coherent SI unit */
#define SI(decade) 1, decade

const csf_unit csf_unit_table[] = {
	{ "m", 1, LEN, SI(0), "SI base unit" },
	{ "kg", 1, MASS, 0, 0, "SI base unit" },
	{ "g", 1e-3, MASS, SI(-3), "SI prefix" },
	{ "s", 1, TIME, SI(0), "SI base unit" },
	{ "A", 1, CURRENT, SI(0), "SI base unit" },
	{ "min", 60, TIME, 0, 0, "definition" },
	{ "h", 3600, TIME, 0, 0, "definition" },
	{ "N", 1, FORCE, SI(0), "SI derived unit" },
	{ "J", 1, ENERGY, SI(0), "SI derived unit" },
	{ "W", 1, POWER, SI(0), "SI derived unit" },
	{ "Pa", 1, PRESSURE, SI(0), "SI derived unit" },
	{ "Hz", 1, FREQ, SI(0), "SI derived unit" },
	{ "C", 1, CHARGE, SI(0), "SI derived unit (A*s)" },
	{ "V", 1, VOLTAGE, SI(0), "SI derived unit (W/A)" },
	{ "ohm", 1, RESISTANCE, SI(0), "SI derived unit (V/A)" },
	{ "S", 1, CONDUCTANCE, SI(0), "SI derived unit (A/V)" },
	{ "F", 1, CAPACITANCE, SI(0), "SI derived unit (C/V)" },
	{ "H", 1, INDUCTANCE, SI(0), "SI derived unit (Wb/A)" },
	{ "Wb", 1, FLUX, SI(0), "SI derived unit (V*s)" },
	{ "T", 1, FLUX_DENSITY, SI(0), "SI derived unit (Wb/m^2)" },
	{ "rad", 1, NONE, SI(0), "SI derived unit" },
	{ "deg", M_PI / 180, NONE, 0, 0, "definition (pi/180)" },
	{ "dyn", GSL_CONST_MKSA_DYNE, FORCE, 0, 0, "GSL_CONST_MKSA_DYNE" },
	{ "erg", GSL_CONST_MKSA_ERG, ENERGY, 0, 0, "GSL_CONST_MKSA_ERG" },
	{ "gal", 1e-2, ACCEL, 0, 0, "definition (1 cm/s^2)" },
	{ "ft", GSL_CONST_MKSA_FOOT, LEN, 0, 0, "GSL_CONST_MKSA_FOOT" },
	{ "in", GSL_CONST_MKSA_INCH, LEN, 0, 0, "GSL_CONST_MKSA_INCH" },
	{ "yd", GSL_CONST_MKSA_YARD, LEN, 0, 0, "GSL_CONST_MKSA_YARD" },
	{ "mi", GSL_CONST_MKSA_MILE, LEN, 0, 0, "GSL_CONST_MKSA_MILE" },
	{ "lb", GSL_CONST_MKSA_POUND_MASS, MASS, 0, 0, "GSL_CONST_MKSA_POUND_MASS" },
	{ "oz", GSL_CONST_MKSA_OUNCE_MASS, MASS, 0, 0, "GSL_CONST_MKSA_OUNCE_MASS" },
	{ "slug", GSL_CONST_MKSA_POUND_FORCE / GSL_CONST_MKSA_FOOT, MASS, 0, 0,
	  "GSL_CONST_MKSA_POUND_FORCE / GSL_CONST_MKSA_FOOT (1 lbf s^2/ft)" },
	{ "lbf", GSL_CONST_MKSA_POUND_FORCE, FORCE, 0, 0, "GSL_CONST_MKSA_POUND_FORCE" },
	{ "pdl", GSL_CONST_MKSA_POUND_MASS * GSL_CONST_MKSA_FOOT, FORCE, 0, 0,
	  "definition (1 lb*ft/s^2, the FPS unit of force; GSL_CONST_MKSA_POUNDAL is rounded to 0.138255)" },
	{ "mph", GSL_CONST_MKSA_MILES_PER_HOUR, SPEED, 0, 0, "GSL_CONST_MKSA_MILES_PER_HOUR" },
	{ NULL, 0, NONE, 0, 0, NULL },
};

/* The SI prefixes csf_unit_find knows, with their powers of ten; `u` is micro. */
static const struct { char c; int exp; } prefixes[] = {
	{ 'f', -15 }, { 'p', -12 }, { 'n', -9 }, { 'u', -6 }, { 'm', -3 },
	{ 'c', -2 },  { 'k', 3 },   { 'M', 6 },  { 'G', 9 },  { 'T', 12 },
};

static const csf_unit *table_find(const char *name, size_t len)
{
	for (const csf_unit *u = csf_unit_table; u->name; u++)
		if (strlen(u->name) == len && memcmp(u->name, name, len) == 0) return u;
	return NULL;
}

int csf_unit_find(const char *name, size_t len, csf_unit *u)
{
	const csf_unit *k = table_find(name, len);
	if (k) {
		*u = *k;
		return 1;
	}
	if (len < 2) return 0;
	k = table_find(name + 1, len - 1);
	if (!k || !k->prefixes) return 0;
	for (size_t i = 0; i < sizeof prefixes / sizeof prefixes[0]; i++)
		if (prefixes[i].c == name[0]) {
			char ten[16];
			snprintf(ten, sizeof ten, "1e%d", prefixes[i].exp + k->decade);
			*u = *k;
			u->name = NULL;
			u->source = NULL;
			u->factor = strtod(ten, NULL); /* the double nearest 10^n, as the literal 1eN */
			u->prefixes = 0;
			return 1;
		}
	return 0;
}

double csf_units_to_system(double si, const double d[CSF_NDIM], const double base[CSF_NDIM])
{
	double v = si;
	for (int i = 0; i < CSF_NDIM; i++) {
		/* divide by base^d one factor at a time: exact for the common small exponents */
		int n = fabs(d[i]) <= 8 ? (int)d[i] : 0; /* (int) of a huge exponent is undefined */
		if (n == d[i]) {
			for (int k = 0; k < abs(n); k++) v = n > 0 ? v / base[i] : v * base[i];
		} else {
			v /= pow(base[i], d[i]);
		}
	}
	return v;
}

/* ---- unit expressions from text: unit := factor (('*' | '/') factor)*; factor := (name | 1 | '(' unit ')') [^ [-]n] ---- */

typedef struct uparse { const char *s; const char *err; } uparse;

static void skip_space(uparse *P) { while (*P->s == ' ' || *P->s == '\t') P->s++; }

static int unit_expr(uparse *P, csf_unit *u);

static int unit_factor(uparse *P, csf_unit *u)
{
	skip_space(P);
	if (*P->s == '(') {
		P->s++;
		if (unit_expr(P, u)) return -1;
		skip_space(P);
		if (*P->s != ')') return P->err = "expected ')' in the unit", -1;
		P->s++;
	} else if (*P->s == '1' && !isdigit((unsigned char)P->s[1]) && P->s[1] != '.') {
		P->s++; /* the 1 of 1/s */
		*u = (csf_unit){ NULL, 1, { 0 }, 0, 0, NULL };
	} else {
		const char *b = P->s;
		while (isalpha((unsigned char)*P->s)) P->s++;
		if (!csf_unit_find(b, (size_t)(P->s - b), u)) return P->err = P->s == b ? "expected a unit" : "unknown unit", -1;
	}
	skip_space(P);
	if (*P->s == '^') {
		P->s++;
		skip_space(P);
		char *end;
		long x = strtol(P->s, &end, 10);
		if (end == P->s || x < -16 || x > 16) return P->err = "a unit exponent must be a whole number between -16 and 16", -1;
		P->s = end;
		u->factor = pow(u->factor, (double)x);
		for (int d = 0; d < CSF_NDIM; d++) u->dim[d] = (signed char)(u->dim[d] * (int)x);
	}
	return 0;
}

static int unit_expr(uparse *P, csf_unit *u)
{
	if (unit_factor(P, u)) return -1;
	for (;;) {
		skip_space(P);
		char op = *P->s;
		if (op != '*' && op != '/') return 0;
		P->s++;
		csf_unit v;
		if (unit_factor(P, &v)) return -1;
		u->factor = op == '*' ? u->factor * v.factor : u->factor / v.factor;
		for (int d = 0; d < CSF_NDIM; d++) u->dim[d] = (signed char)(op == '*' ? u->dim[d] + v.dim[d] : u->dim[d] - v.dim[d]);
	}
}

int csf_unit_starts(const char *s)
{
	if (*s == '(') s++;
	if (isalpha((unsigned char)*s)) return 1;
	if (*s++ != '1') return 0;
	while (*s == ' ' || *s == '\t') s++;
	return *s == '/';
}

int csf_unit_parse(const char *s, const char **end, csf_unit *u, const char **why)
{
	uparse P = { s, NULL };
	memset(u, 0, sizeof *u);
	int r = unit_expr(&P, u);
	u->name = NULL;
	u->source = NULL;
	*end = P.s;
	if (r && why) *why = P.err;
	return r;
}
