/*
 * units.c - the unit table, defined once for the compiler and the runtime:
 * every unit name CSF knows, its factor to SI and its dimension (exponents
 * of length, mass, time, angle). Factors come from GSL's constant tables
 * wherever GSL has the unit; the rest are exact by definition (SI
 * prefixes, minute, hour, degree).
 *
 * The compiler reads unit expressions from its tokens (compiler/layout.c);
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

#include "csf.h"

/* Dimensions: L M T A */
#define LEN { 1, 0, 0, 0 }
#define MASS { 0, 1, 0, 0 }
#define TIME { 0, 0, 1, 0 }
#define ANGLE { 0, 0, 0, 1 }
#define FORCE { 1, 1, -2, 0 }
#define ENERGY { 2, 1, -2, 0 }
#define POWER { 2, 1, -3, 0 }
#define PRESSURE { -1, 1, -2, 0 }
#define FREQ { 0, 0, -1, 0 }
#define SPEED { 1, 0, -1, 0 }
#define ACCEL { 1, 0, -2, 0 }

const csf_unit csf_unit_table[] = {
	{ "m", 1, LEN, "SI base unit" },
	{ "km", 1e3, LEN, "SI prefix" },
	{ "cm", 1e-2, LEN, "SI prefix" },
	{ "mm", 1e-3, LEN, "SI prefix" },
	{ "um", 1e-6, LEN, "SI prefix" },
	{ "nm", 1e-9, LEN, "SI prefix" },
	{ "kg", 1, MASS, "SI base unit" },
	{ "g", 1e-3, MASS, "SI prefix" },
	{ "mg", 1e-6, MASS, "SI prefix" },
	{ "s", 1, TIME, "SI base unit" },
	{ "ms", 1e-3, TIME, "SI prefix" },
	{ "us", 1e-6, TIME, "SI prefix" },
	{ "min", 60, TIME, "definition" },
	{ "h", 3600, TIME, "definition" },
	{ "N", 1, FORCE, "SI derived unit" },
	{ "J", 1, ENERGY, "SI derived unit" },
	{ "W", 1, POWER, "SI derived unit" },
	{ "Pa", 1, PRESSURE, "SI derived unit" },
	{ "Hz", 1, FREQ, "SI derived unit" },
	{ "rad", 1, ANGLE, "SI derived unit" },
	{ "deg", M_PI / 180, ANGLE, "definition (pi/180)" },
	{ "dyn", GSL_CONST_MKSA_DYNE, FORCE, "GSL_CONST_MKSA_DYNE" },
	{ "erg", GSL_CONST_MKSA_ERG, ENERGY, "GSL_CONST_MKSA_ERG" },
	{ "gal", 1e-2, ACCEL, "definition (1 cm/s^2)" },
	{ "ft", GSL_CONST_MKSA_FOOT, LEN, "GSL_CONST_MKSA_FOOT" },
	{ "in", GSL_CONST_MKSA_INCH, LEN, "GSL_CONST_MKSA_INCH" },
	{ "yd", GSL_CONST_MKSA_YARD, LEN, "GSL_CONST_MKSA_YARD" },
	{ "mi", GSL_CONST_MKSA_MILE, LEN, "GSL_CONST_MKSA_MILE" },
	{ "lb", GSL_CONST_MKSA_POUND_MASS, MASS, "GSL_CONST_MKSA_POUND_MASS" },
	{ "oz", GSL_CONST_MKSA_OUNCE_MASS, MASS, "GSL_CONST_MKSA_OUNCE_MASS" },
	{ "slug", GSL_CONST_MKSA_POUND_FORCE / GSL_CONST_MKSA_FOOT, MASS,
	  "GSL_CONST_MKSA_POUND_FORCE / GSL_CONST_MKSA_FOOT (1 lbf s^2/ft)" },
	{ "lbf", GSL_CONST_MKSA_POUND_FORCE, FORCE, "GSL_CONST_MKSA_POUND_FORCE" },
	{ "pdl", GSL_CONST_MKSA_POUNDAL, FORCE, "GSL_CONST_MKSA_POUNDAL" },
	{ "mph", GSL_CONST_MKSA_MILES_PER_HOUR, SPEED, "GSL_CONST_MKSA_MILES_PER_HOUR" },
	{ NULL, 0, { 0, 0, 0, 0 }, NULL },
};

const csf_unit *csf_unit_find(const char *name, size_t len)
{
	for (const csf_unit *u = csf_unit_table; u->name; u++)
		if (strlen(u->name) == len && memcmp(u->name, name, len) == 0) return u;
	return NULL;
}

double csf_units_to_system(double si, const double d[3], const double base[3])
{
	double v = si;
	for (int i = 0; i < 3; i++) {
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

/* ---- unit expressions from text: unit := factor (('*' | '/') factor)*; factor := name | '(' unit ')' [^ [-]n] ---- */

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
	} else {
		const char *b = P->s;
		while (isalpha((unsigned char)*P->s)) P->s++;
		const csf_unit *k = csf_unit_find(b, (size_t)(P->s - b));
		if (!k) return P->err = P->s == b ? "expected a unit" : "unknown unit", -1;
		*u = *k;
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
		for (int d = 0; d < 4; d++) u->dim[d] = (signed char)(u->dim[d] * (int)x);
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
		for (int d = 0; d < 4; d++) u->dim[d] = (signed char)(op == '*' ? u->dim[d] + v.dim[d] : u->dim[d] - v.dim[d]);
	}
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
