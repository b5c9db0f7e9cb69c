/*
 * modes.c - the modes of a cluster with friction, chosen for the whole
 * cluster at once (csf_contact_choose_modes), at an instant.
 *
 * Each pair of the cluster (in contact, or touching at rest) takes a mode:
 *
 *   apart:  no force; its relative normal acceleration does not close;
 *   slide:  a normal force N >= 0 and friction -mu_k N u, u the way it
 *           slips or, where it does not slip, the way its slip begins:
 *           its relative tangential acceleration does not point back
 *           against u (the friction across u keeps it from slipping
 *           sideways: csf_contact_basis), and where the forces hold it at
 *           rest its friction is static friction's, within mu_s N; a pair
 *           turned back tries the other way;
 *   stick:  (a pair that does not slip) the force that cancels its
 *           relative acceleration, N >= 0 and |f| <= mu_s N.
 *
 * A set of modes is consistent when every pair's forces and
 * accelerations, the cluster's system solved as the force stage solves it
 * (force.c), agree with its mode, to the rounding of the accelerations
 * that meet in the pair (csf_contact_accel_resolution). The pairs decide
 * each other: a pair that sticks presses or pulls the next, whose
 * friction holds or slips the first, so no rule of one pair at a time
 * settles every cluster (a ball pressed against a wall by one sliding
 * down it flips between sticking and sliding on the floor, and between
 * touching the wall and parting, without end). So the sets are tried in
 * order of the number of pairs whose mode changes: first the modes as
 * they are (a pair that does not slip taken as sticking: at zero relative
 * velocity friction is static, and a pair sticks when it can), then every
 * set that changes one pair; among as many changes, those of the earliest
 * pairs in the order of pairs first, each pair trying sticking, then
 * sliding, then parting. Most sets are found so. A pile's cluster of 20
 * pairs can need many changes, which that order reaches only after
 * millions of sets: then the worst pair at a time is mended (guided_set, a
 * pivoting method); then the sets of two changes and more, as many as
 * MODES_WORK allows; last the cluster's complementarity problem with
 * Coulomb friction, by Lemke's method (lcp_sets: again with the pairs it
 * let slide held sliding at mu_k N). The first consistent set
 * found is the cluster's. Where none is, the searches are made again with
 * each set's forces kept within the
 * cones of its sticking pairs by the smallest self-stress that can
 * (spread.c: the least-norm forces of a pile at rest may leave a cone
 * where other forces of the same motion hold every pair), and a set found
 * so marks its pairs (W_SPREAD), whose forces the force stage then keeps
 * so. A cluster of more than MODES_MAX pairs tries
 * the modes as they are and then the complementarity problem alone (the
 * searches between cost some dim^3 a set tried: in a pile of 64 balls a
 * cluster of 33 pairs, left to its pairs' own guards, went round between
 * two of them with an event every 1e-8 s). One of more than MODES_LCP_MAX
 * pairs (or whose set has more than DIRECT_MAX unknowns), or for which none
 * of these finds a consistent set, or that has none (with sliding
 * friction, Painlevé's paradox), is left to the complementarity problem of
 * its normal forces and its pairs' own guards (force.c, settle.c).
 */
#include "contact_int.h"

/* The most pairs of a cluster whose sets are searched, the most whose modes are chosen at all
   (the complementarity problem's), the most sets tried, and the solves a set may take to turn
   its slides round. The sets tried are fewer for a large cluster: about MODES_WORK operations in
   all (a set costs some dim^3, dim its unknowns), 0.1 s, but at least every set that changes one
   pair. */
enum { MODES_MAX = 32, MODES_LCP_MAX = 256, MODES_TRIES = 4096, MODES_TURNS = 4 };
static const double MODES_WORK = 2e8;
/* The tangential accelerations, in lcp_set's shift (csf_lcp_shift) times the largest normal force,
   below which a pair of a shifted answer is taken to stick where the forces are kept within the
   cones (with 16, the sets so found left the Galton board of 60 balls stopping at t = 0.8268 s as
   before; with 64 it goes on) */
static const double SHIFT_SLIP = 64;

/* A pair's options: what it is tried in. */
enum { O_APART, O_SLIDE, O_STICK };

/* A pair of the cluster, as the search sees it. */
typedef struct mpair {
	cpair *c;
	double n[3], curv, ar[3]; /* its normal, centripetal term, relative acceleration without contact forces */
	double wn, res;           /* its inverse masses' sum; the rounding of its forces */
	double u0[3], u[3];       /* the direction it slides in: the first guess, and the one tried */
	int slips;                /* it slips beyond the speeds' rounding: it slides along u0 or parts */
	int fixed, lslide;        /* at rest: it slides along uf in the complementarity problem; the
	                             problem found it sliding (along uf) */
	double uf[3];
	int nopt;
	unsigned char opt[3]; /* its options, in the order tried: the first is its mode now */
	unsigned char mode;   /* in the set being tried */
} mpair;

typedef struct search {
	csf_contacts *cs;
	const double *m;
	const uint32_t *cl; /* the cluster's pairs */
	int spread;         /* its sets judged with the forces kept within the cones (csf_contact_spread) */
	uint32_t np;
	double wratio;
	double *F;      /* the forces of the set tried (on body i of each pair), 3 np */
	mpair *p;       /* np */
	uint32_t *at;   /* np: each pair's first unknown in the set's system */
	unsigned char *dc; /* np: its unknowns */
} search;

/* The unit vector of x into u; 0 if x is 0. */
static int unit(const double x[3], double u[3])
{
	double s = mag3(x);
	for (int k = 0; k < 3; k++) u[k] = s > 0 ? x[k] / s : 0;
	return s > 0;
}

/*
 * Solves the cluster's system in the modes of s->p[].mode, each sliding
 * pair along its u: its forces into s->F. Returns 0, or -1 when the system
 * has no solution.
 */
static int solve_set(search *s)
{
	csf_contacts *cs = s->cs;
	uint32_t np = s->np, dim = 0, *at = s->at;
	unsigned char *dc = s->dc;
	double *B = cs->B, *E = cs->E;
	for (uint32_t a = 0; a < np; a++) {
		mpair *p = &s->p[a];
		dc[a] = 0, at[a] = dim;
		if (p->mode == O_APART) continue;
		int mode = p->mode == O_STICK ? STICKING : SLIDING;
		dc[a] = (unsigned char)csf_contact_basis(p->c, s->m, p->n, 1, mode, p->u, B + 9 * a, E + 9 * a);
		if (dim + dc[a] > DIRECT_MAX) return -1;
		for (int r = 0; r < dc[a]; r++)
			cs->rhs[dim + r] = -(dot3(E + 9 * a + 3 * r, p->ar) + p->curv * dot3(E + 9 * a + 3 * r, p->n));
		dim += dc[a];
	}
	for (uint32_t a = 0; a < np; a++)
		for (uint32_t b = 0; b < np; b++)
			for (int r = 0; r < dc[a]; r++)
				for (int q = 0; q < dc[b]; q++) {
					size_t k = (size_t)(at[a] + r) * dim + at[b] + q;
					double w = cs->G[a * np + b], w1 = cs->G1[a * np + b];
					cs->K[k] = w == 0 ? 0 : w * dot3(E + 9 * a + 3 * r, B + 9 * b + 3 * q);
					cs->K1[k] = w1 == 0 ? 0 : w1 * dot3(E + 9 * a + 3 * r, E + 9 * b + 3 * q);
				}
	for (uint32_t a = 0; a < np; a++) memcpy(cs->nv + 3 * a, s->p[a].n, sizeof s->p[a].n);
	csf_contact_frames(np, dc, cs->nv, dim, cs->T, cs->fric);
	if (dim && csf_contact_solve(cs, dim, cs->K1, s->wratio, cs->T, cs->fric)) return -1;
	if (dim && s->spread) { /* the forces within the cones of the pairs that stick, where they can be */
		unsigned char cone[DIRECT_MAX];
		for (uint32_t a = 0; a < np; a++) cone[a] = s->p[a].mode == O_STICK && has_friction(s->p[a].c, s->m);
		csf_contact_spread(cs, s->m, s->cl, np, dim, dc, at, B, cs->nv, cone, cs->x);
	}
	for (uint32_t a = 0; a < np; a++) {
		double *F = s->F + 3 * a;
		F[0] = F[1] = F[2] = 0;
		for (int q = 0; q < dc[a]; q++)
			for (int k = 0; k < 3; k++) F[k] += B[9 * a + 3 * q + k] * cs->x[at[a] + q];
	}
	return 0;
}

/*
 * Is the set of modes in s->p[].mode consistent? A pair that slides
 * without slipping whose forces turn it back tries the other way, again
 * (MODES_TURNS solves at most). 1 consistent, 0 not.
 */
static int consistent(search *s)
{
	uint32_t np = s->np;
	for (uint32_t a = 0; a < np; a++) memcpy(s->p[a].u, s->p[a].u0, sizeof s->p[a].u);
	for (int turn = 0; turn < MODES_TURNS; turn++) {
		if (solve_set(s)) return 0;
		int turned = 0;
		for (uint32_t a = 0; a < np; a++) {
			mpair *p = &s->p[a];
			double acc[3], *F = s->F + 3 * a;
			memcpy(acc, p->ar, sizeof acc);
			for (uint32_t b = 0; b < np; b++) {
				double w = s->cs->G[a * np + b];
				for (int k = 0; k < 3; k++) acc[k] += w * s->F[3 * b + k];
			}
			double an = (dot3(acc, p->n) + p->curv) / p->wn, N = dot3(F, p->n);
			if (p->mode == O_APART) { /* does not close */
				if (an < -p->res) return 0;
				continue;
			}
			if (N < -p->res) return 0; /* pushes */
			if (!has_friction(p->c, s->m)) continue;
			if (p->mode == O_STICK) { /* static friction holds (as the guard says) */
				double f[3];
				for (int k = 0; k < 3; k++) f[k] = F[k] - N * p->n[k];
				if (mu_s(p->c, s->m) * fabs(N) - mag3(f) < 0) return 0;
				continue;
			}
			if (p->slips) continue;
			/* it does not slip: it begins to slip along u (its friction across u keeps it from
			   slipping sideways), or, held by its neighbours, does not slip, its friction static
			   friction's (within mu_s |N|, or mu_k's if that is more); or, turned back, it tries
			   the other way (without a way, the way it is pulled) */
			double f[3], t[3];
			csf_contact_tangential(acc, p->n, t);
			if (!(mag3(p->u) > 0)) {
				if (!(mag3(t) / p->wn > p->res) || turn == MODES_TURNS - 1) return 0;
				unit(t, p->u), turned = 1;
				continue;
			}
			if (dot3(t, p->u) / p->wn < -p->res) {
				if (turn == MODES_TURNS - 1) return 0;
				for (int k = 0; k < 3; k++) p->u[k] = -p->u[k];
				turned = 1;
				continue;
			}
			for (int k = 0; k < 3; k++) f[k] = F[k] - N * p->n[k];
			if (csf_max(mu_s(p->c, s->m), mu_k(p->c, s->m)) * fabs(N) - mag3(f) < 0) return 0; /* as its guard */
		}
		if (!turned) return 1;
	}
	return 0;
}

/*
 * The sets of modes in order (the header): those that change d pairs,
 * for d = 0, 1, ..., np; the pairs changed, idx[0..d), in lexicographic
 * order, and each one's alternatives (its options after the first) in
 * theirs, up to depth changes; those of fewer than from changes (tried
 * before) are counted against the budget but not tried again. Returns 0
 * with the consistent set in
 * s->p[].mode and .u, 1 when there is none, -1 when the sets it may try
 * (MODES_WORK) are done.
 */
static int find_set(search *s, uint32_t from, uint32_t depth)
{
	uint32_t np = s->np, tries = 0, idx[MODES_MAX], alt[MODES_MAX];
	double dim = 3.0 * np, most = csf_max(csf_min(MODES_TRIES, MODES_WORK / (dim * dim * dim)), 1 + 3.0 * np);
	for (uint32_t d = 0; d <= np && d <= depth; d++) {
		for (uint32_t k = 0; k < d; k++) idx[k] = k;
		for (;;) {
			for (uint32_t k = 0; k < d; k++) alt[k] = 1;
			for (;;) {
				for (uint32_t a = 0; a < np; a++) s->p[a].mode = s->p[a].opt[0];
				for (uint32_t k = 0; k < d; k++) s->p[idx[k]].mode = s->p[idx[k]].opt[alt[k]];
				if (++tries > most) return -1;
				if (d >= from && consistent(s)) return 0;
				uint32_t k = d;
				while (k > 0 && ++alt[k - 1] >= (uint32_t)s->p[idx[k - 1]].nopt) alt[k - 1] = 1, k--;
				if (k == 0) break;
			}
			uint32_t k = d;
			while (k > 0 && idx[k - 1] == np - d + k - 1) k--;
			if (k == 0) break;
			idx[k - 1]++;
			for (uint32_t j = k; j < d; j++) idx[j] = idx[j - 1] + 1;
		}
	}
	return 1;
}

/*
 * The pair of the set in s->p[].mode (each slide along its u) whose mode
 * is furthest from consistent (as consistent() judges, measured in the
 * rounding of its forces), and the mode and way (u) that would mend it: a
 * pair apart that would close comes into contact (sticking, where it does
 * not slip and has friction); one in contact that would pull parts; one
 * that sticks beyond mu_s N slides against its friction; one that slides
 * from rest (it does not slip) and is pulled back sticks, or without a way
 * takes the way it is pulled. Returns the pair, or -1 when the set is
 * consistent, or -2 when its system has no solution.
 */
static long worst_pair(search *s, unsigned char *mode, double u[3])
{
	uint32_t np = s->np;
	long worst = -1;
	double most = 1;
	if (solve_set(s)) return -2;
	for (uint32_t a = 0; a < np; a++) {
		mpair *p = &s->p[a];
		double acc[3], *F = s->F + 3 * a, f[3], t[3], bad = 0, w[3] = { 0, 0, 0 };
		unsigned char to = p->mode;
		memcpy(acc, p->ar, sizeof acc);
		for (uint32_t b = 0; b < np; b++)
			for (int k = 0; k < 3; k++) acc[k] += s->cs->G[a * np + b] * s->F[3 * b + k];
		double an = (dot3(acc, p->n) + p->curv) / p->wn, N = dot3(F, p->n);
		int fr = has_friction(p->c, s->m);
		csf_contact_tangential(acc, p->n, t);
		for (int k = 0; k < 3; k++) f[k] = F[k] - N * p->n[k];
		if (p->mode == O_APART) {
			bad = -an / p->res, to = fr && !p->slips ? O_STICK : O_SLIDE;
		} else if (N < -p->res) {
			bad = -N / p->res, to = O_APART;
		} else if (fr && p->mode == O_STICK) {
			bad = (mag3(f) - mu_s(p->c, s->m) * fabs(N)) / p->res, to = O_SLIDE;
			for (int k = 0; k < 3; k++) w[k] = -f[k];
		} else if (fr && !p->slips && !(mag3(p->u) > 0)) { /* no way to slide: pulled one way, or sticks */
			bad = csf_max(mag3(t) / p->wn / p->res, 2), to = mag3(t) / p->wn > p->res ? O_SLIDE : O_STICK;
			memcpy(w, t, sizeof w);
		} else if (fr && !p->slips) {
			bad = -dot3(t, p->u) / p->wn / p->res, to = O_STICK;
			if (csf_max(mu_s(p->c, s->m), mu_k(p->c, s->m)) * fabs(N) < mag3(f))
				bad = csf_max(bad, 1 + (mag3(f) - csf_max(mu_s(p->c, s->m), mu_k(p->c, s->m)) * fabs(N)) / p->res);
		}
		if (bad > most) {
			most = bad, worst = (long)a, *mode = to;
			if (!unit(w, u)) memcpy(u, p->u, 3 * sizeof *u);
		}
	}
	return worst;
}

/*
 * A consistent set found by mending the worst pair at a time (worst_pair),
 * from the modes as they are: a pivoting method, as Baraff's for contact
 * forces, which follows the pairs that disagree instead of trying every
 * set of few changes (find_set), and so reaches the sets of many changes
 * that a cluster of many pairs can need. At most 4 np + 8 mends; a set met
 * before (a cycle) ends it. Returns 0 with the set in s->p[].mode and .u,
 * or -1.
 */
static int guided_set(search *s)
{
	uint32_t np = s->np;
	enum { SEEN = 64 };
	uint64_t seen[SEEN];
	uint32_t nseen = 0;
	for (uint32_t a = 0; a < np; a++) s->p[a].mode = s->p[a].opt[0], memcpy(s->p[a].u, s->p[a].u0, sizeof s->p[a].u);
	for (uint32_t it = 0; it < 4 * np + 8; it++) {
		unsigned char to = 0;
		double u[3];
		long a = worst_pair(s, &to, u);
		if (a == -1) return 0;
		if (a < 0) return -1;
		uint64_t h = 1469598103934665603ull; /* FNV-1a of the modes */
		for (uint32_t b = 0; b < np; b++) h = (h ^ s->p[b].mode) * 1099511628211ull;
		for (uint32_t k = 0; k < nseen; k++)
			if (seen[k] == h) return -1;
		if (nseen < SEEN) seen[nseen++] = h;
		s->p[a].mode = to;
		memcpy(s->p[a].u, u, sizeof u);
	}
	return -1;
}

/*
 * The set of modes that the cluster's complementarity problem gives, for a
 * cluster whose sets in order of changes (find_set) are not consistent as
 * far as they were tried. The problem (Baraff, "Fast contact force
 * computation for nonpenetrating rigid bodies", 1994; Stewart and Trinkle,
 * 1996, here at the level of accelerations): each pair's normal force N >=
 * 0 and its relative normal acceleration a_n >= 0, one of them 0; a pair
 * that slips has friction -mu_k N along its slip; one that does not has
 * friction f = D b, b >= 0, in the four directions +-t1, +-t2 of its
 * tangent plane (t1 along its relative tangential acceleration without
 * contact forces), within the pyramid mu_s N - sum b >= 0, whose
 * complement l >= 0 is the size of its tangential acceleration: D^T a_t +
 * l >= 0 with b. It sticks where l is 0 and otherwise slides against its
 * friction. In a scene in a plane the pyramid is the cone (t2 across the
 * plane, where nothing moves); elsewhere it is close to it. Solved by
 * Lemke's method (lemke.c, csf_lcp_solve: where the method ends on a ray,
 * again with the matrix's diagonal raised by 1e-9 of its largest entry;
 * that second solve once only in large clusters and in those where no pair
 * slides with mu_k N, since elsewhere it led the pile of 16 balls at
 * restitution 0.9 to a cluster whose friction's rank came and went, which
 * cluster.c's held_rank now holds), it names the pairs that part, stick and slide,
 * and the way each slide begins: a guess, taken where consistent() finds
 * it consistent with the cluster's exact system (mu_k's friction, the
 * cone). A pair at rest that is fixed (lcp_sets) is taken as one that
 * slips, along uf; each pair at rest that it found sliding is marked
 * (lslide, its way in uf). Returns 0 with the set in s->p[].mode and .u,
 * or -1.
 */
static int lcp_set(search *s)
{
	csf_contacts *cs = s->cs;
	const double *m = s->m;
	uint32_t np = s->np, nv = 0;
	/* per pair: N's unknown, b's (or UINT32_MAX), the number of b; its directions D, its force
	   f0 along N, its first guess u0 kept */
	uint32_t *iN = malloc(3 * (size_t)np * sizeof *iN), *iB = iN + np, *nd = iB + np;
	double (*D)[4][3] = malloc(np * sizeof *D), (*f0)[3] = malloc(2 * np * sizeof *f0), (*u0)[3] = f0 + np;
	double *M = NULL;
	uint32_t *basis = NULL;
	int ok = -1;
	for (uint32_t a = 0; a < np; a++) s->p[a].lslide = 0;
	if (!iN || !D || !f0) goto out;
	for (uint32_t a = 0; a < np; a++) { /* each pair's force directions: N's, and at rest with friction D's */
		mpair *p = &s->p[a];
		iB[a] = UINT32_MAX;
		double *f = f0[a];
		for (int k = 0; k < 3; k++) f[k] = p->n[k];
		if (!has_friction(p->c, m)) continue;
		if (p->slips || p->fixed) { /* -mu_k N along the way it slips (csf_contact_basis), or slides */
			double vt[3], u[3];
			csf_contact_slip_velocity(p->c, m, p->n, vt);
			if (p->fixed) memcpy(u, p->uf, sizeof u);
			else if (!unit(vt, u)) memcpy(u, p->u0, sizeof u);
			for (int k = 0; k < 3; k++) f[k] -= mu_k(p->c, m) * u[k];
			continue;
		}
		double t1[3], t2[3];
		csf_contact_tangential(p->ar, p->n, t1);
		if (!unit(t1, t1)) { /* any direction across the normal */
			double e[3] = { fabs(p->n[0]) < 0.6, fabs(p->n[0]) < 0.6 ? 0 : 1, 0 };
			csf_contact_tangential(e, p->n, t1);
			unit(t1, t1);
		}
		t2[0] = p->n[1] * t1[2] - p->n[2] * t1[1], t2[1] = p->n[2] * t1[0] - p->n[0] * t1[2];
		t2[2] = p->n[0] * t1[1] - p->n[1] * t1[0];
		for (int k = 0; k < 3; k++)
			D[a][0][k] = t1[k], D[a][1][k] = -t1[k], D[a][2][k] = t2[k], D[a][3][k] = -t2[k];
		iB[a] = 0; /* (its place comes below, once its directions are known) */
	}
	/* a pair whose t2 no force of the cluster and no acceleration has a part along (a scene in a
	   plane: t2 across it) takes no friction along it: its +-t2 are dropped, which the problem,
	   degenerate in them, would otherwise carry along */
	for (uint32_t a = 0; a < np; a++) {
		nd[a] = 4;
		if (iB[a] == UINT32_MAX) continue;
		const double *t2 = D[a][2];
		int off = fabs(dot3(t2, s->p[a].ar)) > 0;
		for (uint32_t b = 0; b < np && !off; b++) {
			if (cs->G[a * np + b] == 0) continue;
			off = fabs(dot3(t2, f0[b])) > 0;
			for (int j = 0; iB[b] != UINT32_MAX && j < 2 && !off; j++) off = fabs(dot3(t2, D[b][j])) > 0;
		}
		if (!off) nd[a] = 2;
	}
	for (uint32_t a = 0; a < np; a++) { /* the unknowns: N, and for a pair at rest with friction b and l */
		iN[a] = nv++;
		if (iB[a] != UINT32_MAX) iB[a] = nv, nv += nd[a] + 1;
	}
	size_t nw = (size_t)nv * nv + csf_lcp_work(nv) + 2 * (size_t)nv;
	M = calloc(nw, sizeof *M), basis = malloc(nv * sizeof *basis);
	if (!M || !basis) goto out;
	double *T = M + (size_t)nv * nv, *q = T + csf_lcp_work(nv), *z = q + nv;
	for (uint32_t a = 0; a < np; a++) {
		const mpair *p = &s->p[a];
		/* the rows of pair a: its normal acceleration, and (at rest, with friction) its tangential
		   acceleration along each direction, and its pyramid */
		uint32_t rows = iB[a] == UINT32_MAX ? 1 : 1 + nd[a], row[5] = { iN[a], iB[a], iB[a] + 1, iB[a] + 2, iB[a] + 3 };
		const double *dir[5] = { p->n, D[a][0], D[a][1], D[a][2], D[a][3] };
		for (uint32_t r = 0; r < rows; r++) {
			double *Mr = M + (size_t)row[r] * nv;
			q[row[r]] = dot3(dir[r], p->ar) + (r == 0 ? p->curv : 0);
			for (uint32_t b = 0; b < np; b++) {
				double g = cs->G[a * np + b];
				if (g == 0) continue;
				Mr[iN[b]] += g * dot3(dir[r], f0[b]);
				for (uint32_t j = 0; iB[b] != UINT32_MAX && j < nd[b]; j++) Mr[iB[b] + j] += g * dot3(dir[r], D[b][j]);
			}
			if (r > 0) Mr[iB[a] + nd[a]] += 1;
		}
		if (iB[a] != UINT32_MAX) {
			double *Ml = M + (size_t)(iB[a] + nd[a]) * nv;
			Ml[iN[a]] = mu_s(p->c, m);
			for (uint32_t j = 0; j < nd[a]; j++) Ml[iB[a] + j] = -1;
			q[iB[a] + nd[a]] = 0;
		}
	}
	int shifted = csf_lcp_solve(nv, M, q, z, T, basis);
	if (shifted < 0) goto out; /* where Lemke's method ends on a ray, shifted */
	/* shifted, the answer's tangential accelerations of pairs at rest are of the order of the shift
	   times the forces (e = csf_lcp_shift max|M|: up to 3 e N_max measured in a Galton board's bin at rest),
	   which the pairs' own rounding takes for slides; with the forces kept within the cones
	   (s->spread) below SHIFT_SLIP e N_max a pair is taken to stick */
	double lres = 0;
	if (shifted && s->spread) {
		double big = 0, nmax = 0;
		for (size_t k = 0; k < (size_t)nv * nv; k++) big = csf_max(big, fabs(M[k]));
		for (uint32_t a = 0; a < np; a++) nmax = csf_max(nmax, z[iN[a]]);
		lres = SHIFT_SLIP * csf_lcp_shift * big * nmax;
	}
	for (uint32_t a = 0; a < np; a++) {
		mpair *p = &s->p[a];
		memcpy(u0[a], p->u0, sizeof u0[a]);
		if (!(z[iN[a]] > p->res)) { /* no force: it parts (a_n >= 0) */
			p->mode = O_APART;
			continue;
		}
		p->mode = O_SLIDE;
		if (p->fixed) memcpy(p->u0, p->uf, sizeof p->u0);
		if (iB[a] == UINT32_MAX) continue; /* frictionless, slipping, or fixed: as it slides */
		if (!(z[iB[a] + nd[a]] > csf_max(p->res * p->wn, lres))) { /* no tangential acceleration: it sticks */
			p->mode = O_STICK;
			continue;
		}
		double f[3] = { 0, 0, 0 }, t[3];
		for (uint32_t j = 0; j < nd[a]; j++)
			for (int k = 0; k < 3; k++) f[k] -= z[iB[a] + j] * D[a][j][k];
		if (!unit(f, p->u0)) { /* against its friction; or along its tangential acceleration */
			csf_contact_tangential(p->ar, p->n, t);
			unit(t, p->u0);
		}
	}
	for (uint32_t a = 0; a < np; a++) {
		mpair *p = &s->p[a];
		p->lslide = iB[a] != UINT32_MAX && p->mode == O_SLIDE;
		if (p->lslide) memcpy(p->uf, p->u0, sizeof p->uf);
	}
	ok = consistent(s) ? 0 : -1;
	for (uint32_t a = 0; a < np; a++) memcpy(s->p[a].u0, u0[a], sizeof u0[a]);
out:
	free(M);
	free(basis);
	free(iN);
	free(D);
	free(f0);
	return ok;
}

/*
 * lcp_set, and where its set is not consistent, again with the pairs it
 * let slide from rest fixed as sliding the way it found, with mu_k's
 * friction (a slide that begins has mu_k N, which the problem's pyramid
 * took as mu_s N: in a Galton board of 40 balls a pair it left apart then
 * closed at 1e-3 m/s^2, and no set was found), and so on while it lets
 * more slide, at most MODES_TURNS problems. Returns 0 with the set in
 * s->p[].mode and .u, or -1.
 */
static int lcp_sets(search *s)
{
	int ok = -1;
	for (uint32_t a = 0; a < s->np; a++) s->p[a].fixed = 0;
	for (int round = 0; round < MODES_TURNS && ok; round++) {
		ok = lcp_set(s);
		int more = 0;
		for (uint32_t a = 0; a < s->np; a++)
			if (s->p[a].lslide) s->p[a].fixed = 1, more = 1;
		if (!more) break;
	}
	for (uint32_t a = 0; a < s->np; a++) s->p[a].fixed = 0;
	return ok;
}

static void take_pair(search *s, mpair *p, cpair *c);

/* The searches in order (the header), each pair's options taken afresh: 0 with a set found, else 1. */
static int search_sets(search *s)
{
	uint32_t np = s->np;
	for (uint32_t a = 0; a < np; a++) take_pair(s, &s->p[a], &s->cs->pairs[s->cl[a]]);
	return np <= MODES_MAX ? find_set(s, 0, 1) && guided_set(s) && find_set(s, 2, np) && lcp_sets(s)
	                       : find_set(s, 0, 0) && lcp_sets(s);
}

/*
 * Pair a of the search, for cluster pair c at the instant m (whose
 * accelerations are those of the modes as they are): its geometry, its
 * relative acceleration without contact forces (each body's acceleration
 * less its contact forces over its mass: every contact force on a body of
 * the cluster is one of the cluster's), the rounding of its forces, its
 * options and its first guess of a direction to slide in.
 */
static void take_pair(search *s, mpair *p, cpair *c)
{
	const double *m = s->m;
	double wi = inv_mass_i(c, m), wj = inv_mass_j(c, m), vt[3];
	p->c = c;
	csf_contact_geometry(c, m, p->n, &p->curv);
	p->wn = wi + wj;
	p->res = csf_contact_accel_resolution(c, m, p->curv) / p->wn;
	for (int k = 0; k < 3; k++) {
		double ai = m[I(c, A) + k] - (m[I(c, FN) + k] + m[I(c, FF) + k]) * wi;
		double aj = c->plane ? 0 : m[J(c, A) + k] - (m[J(c, FN) + k] + m[J(c, FF) + k]) * wj;
		p->ar[k] = ai - aj;
	}
	/* it slips: beyond the speeds' rounding, or, sliding, ahead (its guard: past the event at which
	   its slip turns back, a slip within the rounding behind it, it has stopped) */
	csf_contact_slip_velocity(c, m, p->n, vt);
	int touch = in_contact(c), fr = has_friction(c, m);
	double vres = csf_contact_speed_resolution(c, m, s->cs->vfloor);
	/* in contact, a slip that its friction stops within the Zeno time (sliding: ahead, and slowing) is
	   none (settle.c stops such a slide at once, and holds such a pair that sticks): left slipping,
	   a pair whose slip a neighbour's stop had set going was chosen to slide on against its
	   acceleration, stopped 1.3e-9 s later, and its stop set the neighbour going again (a Galton
	   board of 40 balls, an event every 1.3e-9 s at t = 1.1873 s); every slip so small taken as
	   none, slowing or not, a column of nine balls at 0.65 m/s solved 40 times as many contact
	   systems and took 14 times as long */
	if (csf_contact_slip_stops(c, m, s->cs->zeno)) vres = HUGE_VAL;
	p->slips = fr && (W(c, MODE) == SLIDING ? dot3(vt, WV(c, DS)) > vres : mag3(vt) > vres);
	p->nopt = 0;
	if (fr && !p->slips) { /* sticks if it can; or slides, or parts */
		if (!touch) p->opt[p->nopt++] = O_APART;
		p->opt[p->nopt++] = O_STICK;
		p->opt[p->nopt++] = O_SLIDE;
		if (touch) p->opt[p->nopt++] = O_APART;
	} else {
		p->opt[p->nopt++] = touch ? O_SLIDE : O_APART;
		p->opt[p->nopt++] = touch ? O_APART : O_SLIDE;
	}
	/* the way it slides: as it slides (csf_contact_basis turns that to its slip where it slips
	   ahead); its slip, entering contact; against its static friction; as it is pulled */
	double t[3];
	if (W(c, MODE) == SLIDING && unit(WV(c, DS), p->u0)) return;
	if (p->slips && unit(vt, p->u0)) return;
	for (int k = 0; k < 3; k++) t[k] = -WV(c, F)[k];
	if (W(c, MODE) == STICKING && unit(t, p->u0)) return;
	csf_contact_tangential(p->ar, p->n, t);
	unit(t, p->u0);
}

/*
 * The modes of cluster cl[0..np) (pairs in contact, or touching at rest)
 * if it has friction: the first consistent set (the header), written into
 * cs->mark (TO_APART, TO_SLIDE or TO_STICK, with MODES_CHOSEN) and, for
 * each pair that slides, its direction into cs->dir. A slip counts beyond
 * the speeds' rounding at the instant (cs->vfloor). m holds the accelerations of the modes as they are.
 * Returns 0, or -1 with nothing written: the cluster has no friction, a
 * pair locked by its sliding friction (force.c: its impulse settles it),
 * more than MODES_LCP_MAX pairs, or no consistent set among those it tries
 * (or memory runs out). Past two searches that found none at one instant
 * (cs->vain, csf_contact_settle), none at that instant: each tries up to
 * MODES_TRIES sets, and the passes that follow one that failed, each
 * changing a pair's mode, fail as well (a column of nine balls wedged in
 * a narrow box: 32 searches at an instant, 70 ms each, at instants 2e-6 s
 * apart); the cluster's modes are then chosen as without friction
 * (force.c's choose_cluster), and its pairs' guards take it from there.
 */
int csf_contact_choose_modes(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np)
{
	int friction = 0;
	if (np > MODES_LCP_MAX) return -1;
	for (uint32_t a = 0; a < np; a++) {
		const cpair *c = &cs->pairs[cl[a]];
		friction |= has_friction(c, m);
		if (W(c, LOCK)) return -1;
	}
	if (!friction || cs->vain >= 2) return -1;
	search s;
	s.cs = cs, s.m = m, s.cl = cl, s.spread = 0, s.np = np, s.wratio = csf_contact_mass_ratio(cs, cl, np, m);
	s.p = malloc(np * sizeof *s.p), s.F = malloc(3 * (size_t)np * sizeof *s.F);
	s.at = malloc(np * sizeof *s.at), s.dc = malloc(np);
	int found = -1;
	if (!s.p || !s.F || !s.at || !s.dc) goto out;
	for (uint32_t a = 0; a < np; a++) take_pair(&s, &s.p[a], &cs->pairs[cl[a]]);
	for (uint32_t a = 0; a < np; a++) /* the pairs' coupling, with their masses and with every mass 1 */
		for (uint32_t b = 0; b < np; b++) {
			cs->G[a * np + b] = csf_contact_coupling(cs, s.p[a].c, s.p[b].c, m);
			cs->G1[a * np + b] = csf_contact_coupling(cs, s.p[a].c, s.p[b].c, NULL);
		}
	cs->searches++;
	/* the searches; where they find none, again with the forces of a set kept within the cones where
	   a self-stress can (the least-norm forces of a pile at rest may leave one, where others hold it:
	   spread.c) */
	if (search_sets(&s) && (s.spread = 1, search_sets(&s))) {
		cs->vain++, cs->unfound++; /* none found */
		goto out;
	}
	found = 0;
	for (uint32_t a = 0; a < np; a++) {
		const mpair *p = &s.p[a];
		const cpair *c = p->c;
		double *dir = cs->dir + 3 * (size_t)cl[a];
		int to = p->mode == O_APART ? TO_APART : p->mode == O_STICK ? TO_STICK : TO_SLIDE;
		W(&cs->pairs[cl[a]], SPREAD) = s.spread;
		cs->mark[cl[a]] = (unsigned char)(to | MODES_CHOSEN);
		/* a pair that slides on keeps the direction it began in; one that begins takes its own */
		if (W(c, MODE) == SLIDING && p->slips) memcpy(dir, WV(c, DS), 3 * sizeof *dir);
		else memcpy(dir, p->u, 3 * sizeof *dir);
	}
out:
	free(s.p);
	free(s.F);
	free(s.at);
	free(s.dc);
	return found;
}
