/*
 * units.c - unit names for the compiler's unit literals, from the one unit
 * table the compiler and the runtime share (runtime/prog/units.c), and the
 * unit suggested for an unknown one (the parser's "did you mean 'm/s'?").
 */
#include <string.h>

#include "csfc.h"
#include "csf_int.h"

int unit_lookup(const char *name, Unit *u)
{
	csf_unit k;
	if (!csf_unit_find(name, strlen(name), &k)) return 0;
	u->factor = k.factor;
	memcpy(u->dim, k.dim, sizeof u->dim);
	return 1;
}

const char *suggest_unit(const char *name)
{
	/* "mps", "kmph", "mps2": X per Y */
	size_t n = strlen(name);
	Unit u;
	for (size_t i = 1; i + 1 < n && n < 32; i++) {
		if (name[i] != 'p') continue;
		char x[32], y[32];
		memcpy(x, name, i);
		x[i] = 0;
		strcpy(y, name + i + 1);
		size_t ny = strlen(y);
		int sq = ny > 1 && (y[ny - 1] == '2' || y[ny - 1] == '3');
		char pw = sq ? y[ny - 1] : 0;
		if (sq) y[ny - 1] = 0;
		if (unit_lookup(x, &u) && unit_lookup(y, &u))
			return pw ? xprintf("%s/%s^%c", x, y, pw) : xprintf("%s/%s", x, y);
	}
	const char *c[64];
	int nc = 0;
	for (const csf_unit *p = csf_unit_table; p->name && nc < 64; p++) c[nc++] = p->name;
	return csf_suggest_name(name, c, nc);
}
