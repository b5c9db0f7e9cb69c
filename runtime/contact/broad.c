/*
 * broad.c - the candidate pairs and the broad phase: which pairs the
 * contact routine watches (csf_contacts_find, csf_contacts_commit), found
 * by sort and sweep; the run-time state's creation (csf_contacts_new) and
 * release, and what the driver reads of it.
 */
#include "contact_int.h"

/*
 * Which pairs are candidates. Every pair that can matter during a step must
 * be one, so that its events are located exactly as if every pair of the
 * scene were watched: a pair matters when its gap is (nearly) closed at one
 * of the instants the driver looks at its guards (the step's start, the
 * three interpolated points and its end; a gap that dips below zero only
 * between two of them, a grazing approach the driver finds from the gap's
 * rate, belongs to a pair whose boxes, below, overlap: each box holds its
 * body's path between the instants, as far as their velocities bound it,
 * path_reach; the guards at the states that locate an event serve only
 * that event's pair),
 * and at an event, when it touches. The driver calls
 * csf_contacts_find after each step with those five states, and at each
 * event with the one state: so the candidates are fixed from a step's end
 * until the next step, while its events are located. A pair that is in
 * contact or hopping has a mode of its own and stays a candidate; one that
 * is apart has none (its guard is its gap), so it can leave and come back.
 *
 * The broad phase is sort and sweep along one axis (sweep and prune, as in
 * Box2D's first broad phase and Bullet's axis sweep; Chrono's multicore
 * solver uses a uniform grid instead): each mass point's box, over the positions
 * of the states and grown by how far its path may reach between them
 * (path_reach), its radius and a margin, is sorted by its
 * lower end along the axis on which the bodies are most spread out; a
 * sweep along the sorted list finds every pair of boxes that overlap, in
 * O(N + pairs found). Between two calls the bodies move little compared
 * with their spacing, so the list of the last call is nearly sorted and an
 * insertion sort puts it in order in about linear time (a sort from
 * scratch, O(N log N), when it is far off). A uniform grid would do the
 * same in linear time but needs a cell size: the radii range from 0 (a
 * point) to any size, and the positions from 1e-20 to 1e20 m, while the
 * sweep needs no parameter at all. A plane is not a box: each mass point
 * is tested against each plane (its box's nearest corner), a few planes.
 * An anchor is a box that does not move (its centre grown by its radius
 * and the margin), swept with the mass points; only the pairs of a mass
 * point ($0) and an anchor ($1) are kept, two anchors never touch.
 *
 * The margin is 1e-9 of the magnitudes of the positions and radius, far
 * above the rounding of any gap (1e-16 of them) and above the tolerance
 * within which a touching pair counts as touching (1e-12 of them).
 */

static const double MARGIN = 1e-9;

static int key_cmp(const void *x, const void *y)
{
	const pkey *a = x, *b = y;
	if (a->rule != b->rule) return a->rule < b->rule ? -1 : 1;
	if (a->k0 != b->k0) return a->k0 < b->k0 ? -1 : 1;
	return (a->k1 > b->k1) - (a->k1 < b->k1);
}

static int grow(void **arr, size_t *cap, size_t need, size_t elem)
{
	if (need <= *cap) return 0;
	size_t n = *cap ? *cap : 16;
	while (n < need) n *= 2;
	void *q = realloc(*arr, n * elem);
	if (!q) return -1;
	*arr = q;
	*cap = n;
	return 0;
}

/* Room in the clusters' work (csf_contact_clusters: cl, cstart; the force stage's direct) for n pairs. */
static int grow_cluster_work(csf_contacts *c, size_t n)
{
	return grow((void **)&c->cl, &c->capcl, n + 1, sizeof *c->cl) ||
	       grow((void **)&c->cstart, &c->capcstart, n + 2, sizeof *c->cstart) ||
	       grow((void **)&c->direct, &c->capdirect, n + 1, sizeof *c->direct);
}

static int push_key(csf_contacts *c, uint32_t rule, uint32_t k0, uint32_t k1)
{
	if (grow((void **)&c->keys, &c->capkeys, c->nkeys + 1, sizeof *c->keys)) return -1;
	c->keys[c->nkeys++] = (pkey){ rule, k0, k1 };
	return 0;
}

csf_contacts *csf_contacts_new(const csf_prog *p)
{
	csf_contacts *c = calloc(1, sizeof *c);
	if (!c) return NULL;
	c->p = p;
	c->axis = -1;
	size_t nb = p->ncbodies, nm = 0;
	c->box = malloc((6 * nb + 1) * sizeof *c->box);
	c->mg = malloc((nb + 1) * sizeof *c->mg);
	c->pn = malloc((4 * nb + 1) * sizeof *c->pn);
	c->mstart = calloc(nb + 2, sizeof *c->mstart);
	c->sap = malloc((nb + 1) * sizeof *c->sap);
	c->uf = malloc(((size_t)p->ny + 1) * sizeof *c->uf);
	c->cid = malloc(((size_t)p->ny + 1) * sizeof *c->cid);
	c->K = malloc((size_t)DIRECT_MAX * DIRECT_MAX * sizeof *c->K);
	c->G = malloc((size_t)DIRECT_MAX * DIRECT_MAX * sizeof *c->G);
	c->K1 = malloc((size_t)DIRECT_MAX * DIRECT_MAX * sizeof *c->K1);
	c->G1 = malloc((size_t)DIRECT_MAX * DIRECT_MAX * sizeof *c->G1);
	c->T = malloc((size_t)DIRECT_MAX * DIRECT_MAX * sizeof *c->T);
	c->fric = malloc(DIRECT_MAX * sizeof *c->fric);
	c->lam = malloc(DIRECT_MAX * sizeof *c->lam);
	c->v0 = malloc(DIRECT_MAX * sizeof *c->v0);
	c->nv = malloc(3 * DIRECT_MAX * sizeof *c->nv);
	c->act = malloc(DIRECT_MAX * sizeof *c->act);
	c->rhs = malloc(DIRECT_MAX * sizeof *c->rhs);
	c->x = malloc(DIRECT_MAX * sizeof *c->x);
	c->at = malloc(DIRECT_MAX * sizeof *c->at);
	c->B = malloc(9 * DIRECT_MAX * sizeof *c->B);
	c->E = malloc(9 * DIRECT_MAX * sizeof *c->E);
	c->dc = malloc(DIRECT_MAX * sizeof *c->dc);
	if (!c->box || !c->mg || !c->pn || !c->mstart || !c->sap || !c->uf || !c->cid || !c->K || !c->G || !c->K1 || !c->G1 || !c->T || !c->fric || !c->lam || !c->v0 || !c->nv || !c->act || !c->rhs || !c->x ||
	    !c->at || !c->B || !c->E || !c->dc)
		goto oom;
	/* the memberships of mass points and anchors in rules without `for`, by body, each body's in rule order */
	for (uint32_t r = 0; r < p->ncrules; r++) {
		const csf_crule *cr = &p->crules[r];
		if (!cr->every) continue;
		for (int role = 0; role < 2; role++)
			for (uint32_t k = 0; k < (role ? cr->n1 : cr->n0); k++) {
				uint32_t b = p->cmembers[(role ? cr->first1 : cr->first0) + k];
				if (p->cbodies[b].plane != CSF_CB_PLANE) c->mstart[b + 2]++, nm++;
			}
	}
	for (size_t b = 2; b < nb + 2; b++) c->mstart[b] += c->mstart[b - 1];
	c->mem = malloc((nm + 1) * sizeof *c->mem);
	if (!c->mem) goto oom;
	for (uint32_t r = 0; r < p->ncrules; r++) { /* mstart[b + 1] is body b's cursor */
		const csf_crule *cr = &p->crules[r];
		if (!cr->every) continue;
		for (uint32_t role = 0; role < 2; role++)
			for (uint32_t k = 0; k < (role ? cr->n1 : cr->n0); k++) {
				uint32_t b = p->cmembers[(role ? cr->first1 : cr->first0) + k];
				if (p->cbodies[b].plane != CSF_CB_PLANE) c->mem[c->mstart[b + 1]++] = (memb){ r, role, k };
			}
	}
	/* the bodies of the sweep: mass points and anchors in rules without `for` that do not vary */
	for (uint32_t b = 0; b < nb; b++)
		if (c->mstart[b + 1] > c->mstart[b] && !p->cbodies[b].varies) c->sap[c->nsap++] = b;
	return c;
oom:
	csf_contacts_free(c);
	return NULL;
}

void csf_contacts_free(csf_contacts *c)
{
	if (!c) return;
	free(c->pairs);
	free(c->next);
	free(c->from);
	free(c->old);
	free(c->keys);
	free(c->box);
	free(c->mg);
	free(c->pn);
	free(c->sap);
	free(c->mstart);
	free(c->mem);
	free(c->uf);
	free(c->cid);
	free(c->cl);
	free(c->cstart);
	free(c->direct);
	free(c->K);
	free(c->kb);
	free(c->blk);
	csf_contact_forget(c);
	free(c->K1);
	free(c->G1);
	free(c->T);
	free(c->fric);
	free(c->mark);
	free(c->snap);
	free(c->dir);
	free(c->ls);
	free(c->G);
	free(c->lam);
	free(c->v0);
	free(c->nv);
	free(c->act);
	free(c->seen);
	free(c->seenh);
	free(c->rhs);
	free(c->x);
	free(c->at);
	free(c->B);
	free(c->E);
	free(c->dc);
	free(c);
}

uint32_t csf_contacts_count(const csf_contacts *c) { return c->n; }

void csf_contacts_solves(const csf_contacts *c, unsigned long *solved, unsigned long *recalled)
{
	*solved = (unsigned long)c->solved_clock, *recalled = (unsigned long)c->recalled;
}

void csf_contacts_searches(const csf_contacts *c, unsigned long *searches, unsigned long *unfound)
{
	*searches = (unsigned long)c->searches, *unfound = (unsigned long)c->unfound;
}

void csf_contacts_guards(const csf_contacts *c, double *g)
{
	for (uint32_t k = 0; k < c->n; k++) g[2 * k] = c->pairs[k].w[W_G0], g[2 * k + 1] = c->pairs[k].w[W_G1];
}

uint32_t csf_contacts_src(const csf_contacts *c, uint32_t k) { return c->p->crules[c->pairs[k].rule].src; }

void csf_contacts_objects(const csf_contacts *c, uint32_t k, uint32_t *oi, uint32_t *oj)
{
	const csf_prog *p = c->p;
	const cpair *q = &c->pairs[k];
	const csf_crule *cr = &p->crules[q->rule];
	*oi = p->cbodies[p->cmembers[cr->first0 + q->k0]].object;
	*oj = p->cbodies[p->cmembers[cr->first1 + q->k1]].object;
}

uint32_t csf_contacts_overlaps(const csf_contacts *c, const double *m, uint32_t *deepest, double *depth)
{
	uint32_t n = 0;
	*depth = 0;
	for (uint32_t k = 0; k < c->n; k++) {
		const cpair *q = &c->pairs[k];
		double nv[3], curv, gap = csf_contact_geometry(q, m, nv, &curv);
		if (!(gap < -1e-12 * csf_contact_scale(q, m)) || csf_contact_inside(q, m) < 0) continue;
		n++;
		if (-gap > *depth) *deepest = k, *depth = -gap;
	}
	return n;
}

/*
 * How far body b's path may reach beyond the box of its positions at the
 * states, along each axis (into out): between two states h apart, a cubic
 * through the positions with the velocities there (the interpolant the
 * guards are looked at on) strays beyond the two positions by at most
 * 4/27 h (|v0| + |v1|) (the largest value of the Hermite basis functions
 * of the velocities). Without it a path that turns back within a quarter
 * of the step was not in the box: a ball of a packing sent at 2.3 mm/s
 * towards a neighbour 5.6e-10 m away, its slide on the floor stopped by
 * friction and turned back within the first quarter of a step of 7.7 ms,
 * was no candidate, and struck it 2.4e-8 m deep, 1e-5 s late.
 */
static void path_reach(const csf_prog *p, const csf_cbody *cb, const double *const *ys, int ns, double h, double out[3])
{
	out[0] = out[1] = out[2] = 0;
	uint32_t v = cb->s[CSF_CF_V];
	if (!(h > 0) || v < p->ystart || v + 3 > p->ystart + p->ny) return;
	v -= p->ystart;
	for (int s = 0; s + 1 < ns; s++)
		for (int a = 0; a < 3; a++) {
			double d = 4.0 / 27.0 * h * (fabs(ys[s][v + a]) + fabs(ys[s + 1][v + a]));
			if (d > out[a]) out[a] = d;
		}
}

/* Body b's box over the states h apart (a mass point; an anchor's at its place in m), grown by how far its
   path may reach between them, its radius and the margin; empty if not a number. */
static void body_box(csf_contacts *c, const double *m, uint32_t b, const double *const *ys, int ns, double h)
{
	const csf_prog *p = c->p;
	const csf_cbody *cb = &p->cbodies[b];
	double *bx = c->box + 6 * (size_t)b, big = 0, reach[3] = { 0, 0, 0 };
	int anchor = cb->plane == CSF_CB_ANCHOR, bad = 0;
	uint32_t pos = cb->s[CSF_CF_POS] - (anchor ? 0 : p->ystart);
	for (int a = 0; a < 3; a++) bx[a] = HUGE_VAL, bx[3 + a] = -HUGE_VAL;
	for (int s = 0; s < (anchor ? 1 : ns); s++) {
		const double *x = (anchor ? m : ys[s]) + pos;
		for (int a = 0; a < 3; a++) {
			bad |= isnan(x[a]);
			if (x[a] < bx[a]) bx[a] = x[a];
			if (x[a] > bx[3 + a]) bx[3 + a] = x[a];
		}
		double l1 = fabs(x[0]) + fabs(x[1]) + fabs(x[2]);
		if (l1 > big) big = l1;
	}
	if (!anchor) path_reach(p, cb, ys, ns, h, reach);
	double r = fabs(m[cb->s[CSF_CF_R]]);
	c->mg[b] = MARGIN * (big + r);
	double d = r + c->mg[b];
	for (int a = 0; a < 3; a++) bx[a] -= d + reach[a], bx[3 + a] += d + reach[a];
	for (int a = 0; a < 6; a++) bad |= isnan(bx[a]);
	if (bad)
		for (int a = 0; a < 3; a++) bx[a] = HUGE_VAL, bx[3 + a] = -HUGE_VAL;
}

/* Plane b's unit normal and the size of its point, into pn. */
static void plane_normal(csf_contacts *c, const double *m, uint32_t b)
{
	const uint32_t *s = c->p->cbodies[b].s;
	const double *nn = m + s[CSF_CF_R], *q = m + s[CSF_CF_POS];
	double *pn = c->pn + 4 * (size_t)b, k = mag3(nn);
	for (int a = 0; a < 3; a++) pn[a] = nn[a] / k;
	pn[3] = fabs(q[0]) + fabs(q[1]) + fabs(q[2]);
}

static int overlap(const double *a, const double *b)
{
	return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

/* Can mass point u and mass point or anchor v touch within the states (their boxes)? Two points never do. */
static int near_bodies(const csf_contacts *c, const double *m, uint32_t u, uint32_t v)
{
	const csf_cbody *bu = &c->p->cbodies[u], *bv = &c->p->cbodies[v];
	if (bu->varies || bv->varies) return 1;
	if (!(m[bu->s[CSF_CF_R]] + m[bv->s[CSF_CF_R]] > 0)) return 0;
	return overlap(c->box + 6 * (size_t)u, c->box + 6 * (size_t)v);
}

/* Can mass point u touch plane v within the states: does its box reach the plane? */
static int near_plane(const csf_contacts *c, const double *m, uint32_t u, uint32_t v)
{
	const csf_cbody *bu = &c->p->cbodies[u], *bv = &c->p->cbodies[v];
	if (bu->varies || bv->varies) return 1;
	const double *bx = c->box + 6 * (size_t)u, *n = c->pn + 4 * (size_t)v, *q = m + bv->s[CSF_CF_POS];
	double d = 0; /* the least distance over the box from the plane, along its normal */
	for (int a = 0; a < 3; a++) d += ((n[a] > 0 ? bx[a] : bx[3 + a]) - q[a]) * n[a];
	return d <= MARGIN * n[3];
}

/* The pairs of bodies u and v, whose boxes overlap: in every rule without `for` that has one as $0 and
   the other as $1, of another object: an anchor, or a mass point defined after it. */
static int sweep_pair(csf_contacts *c, uint32_t u, uint32_t v)
{
	const csf_prog *p = c->p;
	uint32_t ou = p->cbodies[u].object, ov = p->cbodies[v].object;
	int au = p->cbodies[u].plane == CSF_CB_ANCHOR, av = p->cbodies[v].plane == CSF_CB_ANCHOR;
	for (uint32_t i = c->mstart[u]; i < c->mstart[u + 1]; i++)
		for (uint32_t j = c->mstart[v]; j < c->mstart[v + 1]; j++) {
			const memb *a = &c->mem[i], *b = &c->mem[j];
			if (a->rule != b->rule || a->role == b->role) continue;
			if (a->role == 0 && (av ? ou != ov : ou < ov) && push_key(c, a->rule, a->place, b->place)) return -1;
			if (b->role == 0 && (au ? ov != ou : ov < ou) && push_key(c, b->rule, b->place, a->place)) return -1;
		}
	return 0;
}

/* A box's lower end along the axis, and its body (to sort afresh). */
typedef struct sapent { double lo; uint32_t b; } sapent;

static int sap_cmp(const void *x, const void *y)
{
	const sapent *a = x, *b = y;
	if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
	return (a->b > b->b) - (a->b < b->b);
}

/* Sort and sweep over the mass points of the rules without `for`. */
static int sweep(csf_contacts *c, const double *m)
{
	const csf_prog *p = c->p;
	uint32_t n = c->nsap, *s = c->sap;
	/* the axis along which the centres spread most (kept unless another spreads 20 % more) */
	double sum[3] = { 0 }, sq[3] = { 0 }, var[3];
	uint32_t cnt = 0;
	for (uint32_t i = 0; i < n; i++) {
		const double *bx = c->box + 6 * (size_t)s[i];
		if (!(bx[0] <= bx[3])) continue;
		cnt++;
		for (int a = 0; a < 3; a++) {
			double x = (bx[a] + bx[3 + a]) / 2;
			sum[a] += x, sq[a] += x * x;
		}
	}
	int axis = c->axis < 0 ? 0 : c->axis;
	for (int a = 0; a < 3; a++) var[a] = cnt ? sq[a] - sum[a] * sum[a] / cnt : 0;
	for (int a = 0; a < 3; a++)
		if (var[a] > 1.2 * var[axis] || (c->axis < 0 && var[a] > var[axis])) axis = a;
	if (!isfinite(var[0] + var[1] + var[2])) axis = c->axis < 0 ? 0 : c->axis;
	c->axis = axis;
	/* insertion sort by the boxes' lower ends (then by body), from scratch if it is far off */
	const double *box = c->box;
#define SAP_LESS(x, y) (box[6 * (size_t)(x) + axis] < box[6 * (size_t)(y) + axis] || \
                        (box[6 * (size_t)(x) + axis] == box[6 * (size_t)(y) + axis] && (x) < (y)))
	size_t moves = 0, limit = 8 * (size_t)n + 64;
	for (uint32_t i = 1; i < n && moves <= limit; i++) {
		uint32_t x = s[i], j = i;
		while (j > 0 && SAP_LESS(x, s[j - 1]) && moves++ <= limit) s[j] = s[j - 1], j--;
		s[j] = x;
	}
	if (moves > limit) {
		/* lower ends with their bodies, sorted afresh (an empty box's is +inf) */
		sapent *e = malloc((n + 1) * sizeof *e);
		if (!e) return -1;
		for (uint32_t i = 0; i < n; i++) e[i].lo = box[6 * (size_t)s[i] + axis], e[i].b = s[i];
		qsort(e, n, sizeof *e, sap_cmp);
		for (uint32_t i = 0; i < n; i++) s[i] = e[i].b;
		free(e);
	}
#undef SAP_LESS
	for (uint32_t i = 0; i < n; i++) {
		uint32_t u = s[i];
		const double *bu = box + 6 * (size_t)u;
		double hi = bu[3 + axis];
		if (!(bu[axis] <= hi)) continue;
		for (uint32_t j = i + 1; j < n; j++) {
			uint32_t v = s[j];
			const double *bv = box + 6 * (size_t)v;
			if (bv[axis] > hi) break;
			if (!overlap(bu, bv) || !(m[p->cbodies[u].s[CSF_CF_R]] + m[p->cbodies[v].s[CSF_CF_R]] > 0)) continue;
			if (sweep_pair(c, u, v)) return -1;
		}
	}
	return 0;
}

long csf_contacts_find(csf_contacts *c, const double *m, const double *const *ys, int ns, double h)
{
	const csf_prog *p = c->p;
	c->nkeys = 0;
	for (uint32_t k = 0; k < c->n; k++) /* the pairs with a mode of their own */
		if (c->pairs[k].w[W_MODE] != APART && push_key(c, c->pairs[k].rule, c->pairs[k].k0, c->pairs[k].k1))
			return -1;
	for (uint32_t b = 0; b < p->ncbodies; b++) {
		if (p->cbodies[b].plane == CSF_CB_PLANE) plane_normal(c, m, b);
		else body_box(c, m, b, ys, ns, h);
	}
	for (uint32_t r = 0; r < p->ncrules; r++) {
		const csf_crule *cr = &p->crules[r];
		const uint32_t *L0 = p->cmembers + cr->first0, *L1 = p->cmembers + cr->first1;
		if (!cr->every) { /* `for`: its one pair */
			for (uint32_t k = 0; k < cr->n0; k++) {
				uint32_t i = L0[k], j = L1[k];
				if ((p->cbodies[j].plane == CSF_CB_PLANE ? near_plane(c, m, i, j) : near_bodies(c, m, i, j)) &&
				    push_key(c, r, k, k))
					return -1;
			}
			continue;
		}
		for (uint32_t k1 = 0; k1 < cr->n1; k1++) { /* every $0 with each plane, and with a $1 that varies */
			uint32_t j = L1[k1];
			const csf_cbody *bj = &p->cbodies[j];
			if (bj->plane != CSF_CB_PLANE && !bj->varies) continue;
			for (uint32_t k0 = 0; k0 < cr->n0; k0++) {
				uint32_t i = L0[k0];
				const csf_cbody *bi = &p->cbodies[i];
				if (bj->plane ? bi->object != bj->object && (bj->plane == CSF_CB_ANCHOR || near_plane(c, m, i, j))
				              : bi->object < bj->object)
					if (push_key(c, r, k0, k1)) return -1;
			}
		}
		for (uint32_t k0 = 0; k0 < cr->n0; k0++) { /* a $0 that varies, with every mass point and anchor */
			const csf_cbody *bi = &p->cbodies[L0[k0]];
			if (!bi->varies) continue;
			for (uint32_t k1 = 0; k1 < cr->n1; k1++) {
				const csf_cbody *bj = &p->cbodies[L1[k1]];
				int pair = bj->plane == CSF_CB_ANCHOR ? bi->object != bj->object : !bj->plane && bi->object < bj->object;
				if (pair && push_key(c, r, k0, k1)) return -1;
			}
		}
	}
	if (sweep(c, m)) return -1;
	/* in the order of pairs, each once; a pair that was a candidate keeps its mode */
	if (c->nkeys) qsort(c->keys, c->nkeys, sizeof *c->keys, key_cmp);
	if (grow((void **)&c->next, &c->capnext, c->nkeys + 1, sizeof *c->next) ||
	    grow((void **)&c->from, &c->capfrom, c->nkeys + 1, sizeof *c->from) ||
	    grow((void **)&c->old, &c->capold, 2 * (size_t)c->n + 1, sizeof *c->old) || grow_cluster_work(c, c->nkeys))
		return -1;
	uint32_t o = 0, n = 0;
	for (size_t k = 0; k < c->nkeys; k++) {
		const pkey *key = &c->keys[k];
		if (k && key_cmp(key, &c->keys[k - 1]) == 0) continue;
		while (o < c->n && key_cmp(&(pkey){ c->pairs[o].rule, c->pairs[o].k0, c->pairs[o].k1 }, key) < 0) o++;
		cpair *q = &c->next[n];
		if (o < c->n && c->pairs[o].rule == key->rule && c->pairs[o].k0 == key->k0 && c->pairs[o].k1 == key->k1) {
			*q = c->pairs[o];
			c->from[n] = o;
		} else {
			const csf_crule *cr = &p->crules[key->rule];
			const csf_cbody *bi = &p->cbodies[p->cmembers[cr->first0 + key->k0]];
			const csf_cbody *bj = &p->cbodies[p->cmembers[cr->first1 + key->k1]];
			memset(q, 0, sizeof *q);
			q->rule = key->rule, q->k0 = key->k0, q->k1 = key->k1;
			q->plane = bj->plane != CSF_CB_POINT;
			q->anchor = bj->plane == CSF_CB_ANCHOR;
			q->si = bi->s, q->sj = bj->s;
			c->from[n] = -1;
		}
		n++;
	}
	c->nnext = n;
	return n;
}

void csf_contacts_commit(csf_contacts *c, const double *m, double *const *g, const double *const *gy, int ng)
{
	const csf_prog *p = c->p;
	for (int q = 0; q < ng; q++) {
		memcpy(c->old, g[q], 2 * (size_t)c->n * sizeof *c->old);
		for (uint32_t k = 0; k < c->nnext; k++) {
			long o = c->from[k];
			if (o >= 0) {
				g[q][2 * k] = c->old[2 * o], g[q][2 * k + 1] = c->old[2 * o + 1];
				continue;
			}
			/* a new pair is apart: its guard is its gap, as csf_contact_apply computes it (an anchor's
			   position is in m) */
			const cpair *cp = &c->next[k];
			const double *pi = gy[q] + (I(cp, POS) - p->ystart), *pj = cp->plane ? NULL : gy[q] + (J(cp, POS) - p->ystart);
			g[q][2 * k] = csf_contact_gap_guard(cp, m, pi, pj);
			g[q][2 * k + 1] = 1;
		}
	}
	cpair *t = c->pairs;
	c->pairs = c->next, c->next = t;
	size_t cap = c->cap;
	c->cap = c->capnext, c->capnext = cap;
	c->n = c->nnext;
}

/*
 * The candidates (each one's place in the order of pairs and its work
 * values; the slots follow from the place) and the sweep's order and axis,
 * which the next search starts from.
 */
int csf_contacts_keep(csf_contacts *c, csf_keeper *k)
{
	if (!c) return 0;
	const csf_prog *p = c->p;
	int bad = CSF_KEEP(k, c->n) | CSF_KEEP(k, c->axis) | CSF_KEEP(k, c->nsap) | CSF_KEEP(k, c->held) | CSF_KEEP(k, c->fits) |
	          CSF_KEEP(k, c->held_clock);
	/* the pairs, and the clusters' work sized by them (csf_contacts_find's, which a resumed run's
	   first evaluation comes before) */
	if (bad || grow((void **)&c->pairs, &c->cap, (size_t)c->n + 1, sizeof *c->pairs) || grow_cluster_work(c, c->n))
		return -1;
	if (c->nsap) bad |= csf_keep(k, "contacts.sap", c->sap, c->nsap * sizeof *c->sap);
	for (uint32_t i = 0; i < c->n && !bad; i++) {
		cpair *q = &c->pairs[i];
		char name[48];
		uint32_t at[3] = { q->rule, q->k0, q->k1 };
		snprintf(name, sizeof name, "contacts.pair.%u", i);
		bad |= csf_keep(k, name, at, sizeof at);
		snprintf(name, sizeof name, "contacts.w.%u", i);
		bad |= csf_keep(k, name, q->w, sizeof q->w);
		if (bad || at[0] >= p->ncrules || at[1] >= p->crules[at[0]].n0 || at[2] >= p->crules[at[0]].n1) return -1;
		const csf_crule *cr = &p->crules[at[0]];
		const csf_cbody *bi = &p->cbodies[p->cmembers[cr->first0 + at[1]]];
		const csf_cbody *bj = &p->cbodies[p->cmembers[cr->first1 + at[2]]];
		q->rule = at[0], q->k0 = at[1], q->k1 = at[2];
		q->plane = bj->plane != CSF_CB_POINT;
		q->anchor = bj->plane == CSF_CB_ANCHOR;
		q->si = bi->s, q->sj = bj->s;
	}
	return bad ? -1 : 0;
}
