/*
 * units.c - the unit table: every unit name CSF knows, its factor to SI and
 * its dimension (exponents of length, mass, time, angle). Factors come from
 * GSL's constant tables wherever GSL has the unit; the rest are exact by
 * definition (SI prefixes, minute, hour, degree).
 */
#include <math.h>
#include <string.h>

#include <gsl/gsl_const_mksa.h>

#include "csfc.h"

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

const UnitInfo unit_table[] = {
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

int unit_lookup(const char *name, Unit *u)
{
	for (const UnitInfo *p = unit_table; p->name; p++)
		if (strcmp(p->name, name) == 0) {
			u->factor = p->factor;
			memcpy(u->dim, p->dim, sizeof u->dim);
			return 1;
		}
	return 0;
}
