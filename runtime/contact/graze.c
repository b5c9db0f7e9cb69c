/*
 * graze.c - an apart pair's gap and its rate at a state vector, for the
 * driver's search for a grazing approach (runtime/run/events.c): a gap that
 * closes and opens again between two of the instants at which the guards
 * are looked at, positive at both.
 */
#include "contact_int.h"

/* Slot s at the state y (a slot of the state) or in m (another: a parameter, an anchor's position). */
static const double *slot_at(const csf_prog *p, const double *m, const double *y, uint32_t s)
{
	return s >= p->ystart && s - p->ystart < p->ny ? y + (s - p->ystart) : m + s;
}

uint32_t csf_contacts_gap_slots(const csf_contacts *cs, uint32_t k, uint32_t idx[12])
{
	const csf_prog *p = cs->p;
	const cpair *c = &cs->pairs[k];
	if (W(c, MODE) != APART) return 0;
	uint32_t n = 0, s[4] = { I(c, POS), I(c, V), c->plane ? UINT32_MAX : J(c, POS), c->plane ? UINT32_MAX : J(c, V) };
	for (int q = 0; q < 4; q++)
		if (s[q] >= p->ystart && s[q] - p->ystart < p->ny) /* (a plane's, an anchor's are in m) */
			for (uint32_t a = 0; a < 3; a++) idx[n++] = s[q] - p->ystart + a;
	return n;
}

int csf_contacts_gap_rate(const csf_contacts *cs, uint32_t k, const double *m, const double *y, double *gap,
                          double *rate)
{
	const csf_prog *p = cs->p;
	const cpair *c = &cs->pairs[k];
	if (W(c, MODE) != APART) return 0;
	const double *pi = slot_at(p, m, y, I(c, POS)), *pj = c->plane ? NULL : slot_at(p, m, y, J(c, POS));
	const double *vi = slot_at(p, m, y, I(c, V)), *vj = c->plane ? NULL : slot_at(p, m, y, J(c, V));
	double n[3], curv, vr[3];
	csf_contact_geometry_at(c, m, pi, pj, n, &curv);
	for (int a = 0; a < 3; a++) vr[a] = vi[a] - (vj ? vj[a] : 0.0);
	*gap = csf_contact_gap_guard(c, m, pi, pj);
	*rate = dot3(vr, n);
	return 1;
}
