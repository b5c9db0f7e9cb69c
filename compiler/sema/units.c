/*
 * units.c - unit names for the compiler's unit literals, from the one unit
 * table the compiler and the runtime share (runtime/prog/units.c).
 */
#include <string.h>

#include "csfc.h"
#include "csf.h"

int unit_lookup(const char *name, Unit *u)
{
	csf_unit k;
	if (!csf_unit_find(name, strlen(name), &k)) return 0;
	u->factor = k.factor;
	memcpy(u->dim, k.dim, sizeof u->dim);
	return 1;
}
