/*
 * contact_int.h - what the files of the contact routine share, and no more:
 * the modes of a pair, a candidate pair, the run-time state (struct
 * csf_contacts), the small helpers every stage uses, and the functions one
 * file calls in another. Private: csf.h declares the routine's entry points.
 *
 * The contact routine: mechanics/rules 1 to 4: normal force, collision,
 * static and dynamic friction between a mass point and another mass point,
 * a plane or an anchor (an immovable sphere, a peg: the geometry of two
 * spheres, the infinite mass of a plane; its centre does not move).
 *
 * A pair is apart (mode 0), hopping (3), or in contact, sliding (1) or
 * sticking (2). The mode changes only at events, which the driver locates
 * in time:
 *
 *   apart:    guard 0 is the gap; when it closes the bodies collide (an
 *             impulse along the normal with restitution min(cr_i, cr_j); a
 *             plane or an anchor has infinite mass; the pairs in contact do not close,
 *             and those whose velocity it changed take their mode afresh:
 *             apart, sliding or sticking), or come to rest in contact when
 *             the train of bounces that would follow ends within the Zeno
 *             time.
 *   hopping:  apart, on a hop too low for the positions to follow; guard 0
 *             is the time left until it lands, known from its flight time.
 *   contact:  the normal force N n is the constraint force that keeps the
 *             relative normal acceleration zero; guard 0 is N, and the
 *             bodies separate when it would pull (N < 0).
 *   sliding:  friction -mu_k |N| v_t/|v_t|; guard 1 is v_t . d, with d the
 *             direction of sliding at its start: sticking begins when the
 *             relative tangential velocity reaches zero.
 *   sticking: friction is the force that keeps the relative tangential
 *             acceleration zero; guard 1 is mu_s |N| - |f|, and sliding
 *             begins when static friction cannot hold.
 *
 * No threshold is a length or a time of its own: the gap's resolution
 * follows from the magnitudes of the positions, the Zeno time from the
 * output interval (csf(5), Rest).
 *
 * Materials combine as mu = max(mu_i, mu_j) (the rougher surface) and
 * restitution e = min(cr_i, cr_j) (the less elastic one), so the defaults
 * (cr 1, mu 0) leave the other body's coefficient as it is. Several
 * simultaneous contacts are solved together, exactly: the pairs that share
 * bodies form a cluster, whose forces (and impulses) are the solution of
 * one linear system (cluster.c).
 *
 * The program lists the bodies of each contact rule, not its pairs; the
 * routine works on the candidate pairs only, those near enough to matter,
 * found by a broad phase (broad.c) and kept in the
 * order of the pairs, so that what it computes is what it would compute
 * for every pair of the scene: an apart pair that is not a candidate has
 * a positive gap at every instant its guard would be looked at, and does
 * nothing. Two points (radius 0: mass points, or a mass point and an
 * anchor) never touch.
 *
 * The files, runtime/contact/, in the order of the work:
 *
 *   geometry.c  a pair's normal, gap (sphere and sphere or anchor, or
 *               plane), edge and length scale; its slip
 *   cluster.c   the clusters: the pairs in contact that share bodies, and
 *               the direct (LU) solve of their linear systems
 *   force.c     the force stage (csf_contact_apply): contact forces and
 *               friction, directly or by Gauss-Seidel sweeps; the guards
 *   modes.c     the modes of a cluster with friction (apart, sliding,
 *               sticking), chosen for the whole cluster at an instant
 *   lemke.c     Lemke's method for a linear complementarity problem
 *   impulse.c   impacts: impulses by active sets, or by sweeps
 *   settle.c    the settle state machine (csf_contact_settle): impacts,
 *               rest, hops, lift-off, sticking and sliding at an instant
 *   broad.c     the candidate pairs and the broad phase (sort and sweep);
 *               the run-time state's life and its accessors
 *   graze.c     an apart pair's gap and its rate at a state, for the
 *               driver's search for a grazing approach (runtime/run/events.c)
 */
#ifndef CSF_CONTACT_INT_H
#define CSF_CONTACT_INT_H

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csf_int.h"

enum { APART, SLIDING, STICKING, HOPPING }; /* the modes of a pair */

/* A pair's work values: mode, the two guards, the normal force's size, the friction force,
   the sliding direction, the time a hop lands, the relative velocity before an impact, the
   times it has begun to stick at the instant being settled (csf_contact_settle), whether
   sliding friction locks it (force.c), the margin its gap's guard takes after it lifted off
   (settle.c's lift_off), whether it lifted off at the instant being settled, whether it would turn
   back (settle.c's turns_back, on the accelerations of the pass's evaluation), whether its cluster's
   modes were found only with the forces kept within the cones (modes.c; force.c then keeps them so:
   spread.c), whether it slid with a slip beyond the rounding when the instant began (settle.c's
   stops_at_once). A pair that is not a candidate is apart. */
enum { W_MODE = 0, W_G0 = 1, W_G1 = 2, W_LAM = 3, W_F = 4, W_DS = 7, W_TL = 10, W_VR = 11, W_SS = 14, W_LOCK = 15, W_LIFT = 16, W_LO = 17, W_TB = 18, W_SPREAD = 19, W_SL = 20, W_N = 21 };

/* A candidate pair: body i (a mass point, $0) and body j (a mass point, a plane or an anchor, $1). */
typedef struct cpair {
	uint32_t rule, k0, k1;   /* its place in the order of pairs: its rule, $0's and $1's place in its lists */
	uint32_t plane;          /* j is immovable, of infinite mass, no velocity: a plane or an anchor */
	const uint32_t *si, *sj; /* the property slots of i and j (csf_cbody) */
	double w[W_N];
	uint32_t anchor;         /* j is an anchor: a sphere (plane is 1 too) */
} cpair;

/* A pair's key, for sorting: rule, k0, k1. */
typedef struct pkey { uint32_t rule, k0, k1; } pkey;

/* Where a mass point is in the lists of a rule without `for`: rule, role (0 $0, 1 $1), place. */
typedef struct memb { uint32_t rule, role, place; } memb;

struct csf_contacts {
	const csf_prog *p;
	cpair *pairs, *next;      /* the candidates; the next ones (csf_contacts_find) */
	uint32_t n, nnext;
	size_t cap, capnext;
	long *from;               /* next[k]'s place in pairs, or -1 (new) */
	double *old;              /* a copy of a guard vector while it is remapped */
	size_t capfrom, capold;
	pkey *keys;               /* the pairs found, before sorting */
	size_t nkeys, capkeys;
	double *box;              /* 6 per body (lo xyz, hi xyz), its reach over the states; planes: unused */
	double *mg;               /* per body, the rounding margin of its reach */
	double *pn;               /* 4 per plane: the unit normal, and |point|_1 */
	uint32_t *sap, nsap;      /* the mass points of rules without `for`, in sweep order */
	int axis;                 /* the sweep's axis, -1 before the first */
	uint32_t *mstart;         /* per body, its memberships: mem[mstart[b] .. mstart[b + 1]) */
	memb *mem;
	/* the clusters (cluster.c): per state slot of a position, its union-find parent and cluster;
	   per candidate, the candidates of the clusters in order, and whether its cluster was
	   solved directly; a cluster's matrix, right-hand side, solution and unknowns' places */
	uint32_t *uf, *cid, *cl, *cstart;
	unsigned char *direct;
	size_t capcl, capcstart, capdirect;
	double *K, *G, *rhs, *x, *lam, *v0, *nv;
	uint32_t *at;
	unsigned char *act;
	unsigned char *seen;       /* the sets force.c's lcp_sets has been through (np bytes each), */
	uint64_t *seenh;           /* their hashes, */
	size_t capseen, capseenh;  /* and the room for them */
	double *B, *E;             /* per pair of a cluster: its force directions and equations (3 x 3 each) */
	unsigned char *dc;        /* and its unknowns */
	double *kb, *ls;           /* a copy of a system while it is solved, and the least-norm solve's work */
	double *K1, *G1;           /* K and G with every mass 1 (DIRECT_MAX^2 each) */
	double *T;                 /* the frames of K's unknowns (DIRECT_MAX^2), and which are friction */
	unsigned char *fric;
	double *blk;               /* a system set aside while csf_contact_solve solves its blocks */
	size_t capkb, capls, capblk;
	struct csf_solved *solved; /* the systems solved last, and their answers (cluster.c, recall) */
	uint64_t solved_clock, recalled; /* the systems solved or recalled, and those recalled */
	unsigned char *mark;       /* per candidate: the pairs csf_contact_choose chooses among, and its choice */
	double *dir;               /* per candidate, 3: the direction a pair chosen to slide slides in */
	size_t capmark;
	double *snap;              /* settle.c's copy of the state and the pairs' work values (a cycle's start) */
	size_t capsnap;
	int group;                 /* an impact's impulses are shared by the pairs marked (impulse.c) */
	uint32_t why_pair, why_np; /* of a cluster that could not be solved: a pair of it, its pairs, */
	uint32_t why_big;          /* and DIRECT_MAX if its unknowns are more (else 0) */
	double tol;                /* the integrator's tolerance at the last instant settled (settle.c) */
	double zeno;               /* and its Zeno time (settle.c) */
	double vfloor;             /* the least speed that counts at the instant being settled (settle.c) */
	uint32_t vain;             /* the searches for modes that found none at that instant (modes.c) */
	uint64_t searches, unfound; /* the searches for modes of the run, and those that found none */
	/* the ranks held for the friction of indeterminate clusters (cluster.c, held_rank): per system's
	   shape (its hash), the rank taken last, and when; and apart, per shape, whether its least-norm
	   forces were taken as solving it (held_fit: rank 1 taken, 2 not); held_now: the last solve
	   held one or the other */
	struct csf_held { uint64_t sig, used; uint32_t rank; } held[16], fits[16];
	uint64_t held_clock;
	int held_now, hold; /* hold: the force stage's solves, which hold ranks (impacts and searches do not) */
	int unsolved; /* the sweeps left contact forces that do not hold (csf_contacts_unsolved) */
};

/* The most unknowns of a cluster solved directly (cluster.c). */
enum { DIRECT_MAX = 256 };

#define I(c, f) ((c)->si[CSF_CF_##f])
#define J(c, f) ((c)->sj[CSF_CF_##f])
#define W(c, k) ((c)->w[W_##k])
#define WV(c, k) ((c)->w + W_##k)

/* Union-find: the root of x in up, halving the paths (clusters, a system's blocks, spread.c's parts). */
static inline uint32_t csf_uf_root(uint32_t *up, uint32_t x)
{
	while (up[x] != x) x = up[x] = up[up[x]];
	return x;
}
static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline double mag3(const double *a) { return csf_vmag3(a[0], a[1], a[2]); }

static inline double inv_mass_i(const cpair *c, const double *m) { return 1.0 / m[I(c, M)]; }
static inline double inv_mass_j(const cpair *c, const double *m) { return c->plane ? 0.0 : 1.0 / m[J(c, M)]; }

/* Relative value of vector property field fi of i and fj of j (j a plane: 0). */
static inline void rel(const cpair *c, const double *m, uint32_t fi, uint32_t fj, double out[3])
{
	for (int k = 0; k < 3; k++) out[k] = m[fi + k] - (c->plane ? 0.0 : m[fj + k]);
}

/* Sliding or sticking: pressed together by a normal force. */
static inline int in_contact(const cpair *c)
{
	return W(c, MODE) == SLIDING || W(c, MODE) == STICKING;
}

static inline int has_friction(const cpair *c, const double *m)
{
	return m[I(c, MUS)] > 0 || m[I(c, MUK)] > 0 || (m[J(c, MUS)] > 0 || m[J(c, MUK)] > 0);
}
static inline double mu_s(const cpair *c, const double *m) { return csf_max(m[I(c, MUS)], m[J(c, MUS)]); }
static inline double mu_k(const cpair *c, const double *m) { return csf_max(m[I(c, MUK)], m[J(c, MUK)]); }
static inline double restitution(const cpair *c, const double *m) { return csf_min(m[I(c, CR)], m[J(c, CR)]); }
/* The slip (speed) that friction of coefficient mu at pair c's normal force stops within time
   zeno: mu |N| (1/m_i + 1/m_j) zeno. */
static inline double stopped_within(const cpair *c, const double *m, double mu, double zeno)
{
	return mu * fabs(W(c, LAM)) * (inv_mass_i(c, m) + inv_mass_j(c, m)) * zeno;
}

/* ---- the functions one file calls in another ---- */

/* geometry.c: a pair's normal, gap and edge (at the positions pi, pj or those in m), its length
   scale and the smallest gap it resolves, tangential parts and the slip velocity */
double csf_contact_geometry_at(const cpair *c, const double *m, const double *pi, const double *pj, double n[3],
                               double *curv);
double csf_contact_geometry(const cpair *c, const double *m, double n[3], double *curv);
double csf_contact_inside_at(const cpair *c, const double *m, const double *pi);
double csf_contact_inside(const cpair *c, const double *m);
double csf_contact_scale(const cpair *c, const double *m);
double csf_contact_scale_at(const cpair *c, const double *m, const double *pi, const double *pj);
double csf_contact_resolution(const cpair *c, const double *m);
void csf_contact_tangential(const double x[3], const double n[3], double out[3]);
void csf_contact_slip_velocity(const cpair *c, const double *m, const double n[3], double vt[3]);

/* cluster.c: the coupling of two pairs (m NULL: every mass 1), the clusters of the pairs pick()
   takes (in cs->cl, cs->cstart; returns their number), and the direct solve of cs->K x = cs->rhs,
   K1 the system with every mass 1, wratio the masses' ratio (-1: not solved) */
double csf_contact_coupling(const csf_contacts *cs, const cpair *c, const cpair *d, const double *m);
uint32_t csf_contact_clusters(csf_contacts *cs, int (*pick)(const cpair *, const void *), const void *arg);
int csf_contact_picks_contact(const cpair *c, const void *arg); /* (force.c) for it: the pairs in contact */
int csf_contact_solve(csf_contacts *cs, uint32_t dim, double *K1, double wratio, const double *T,
                      const unsigned char *fric);
double csf_contact_mass_ratio(const csf_contacts *cs, const uint32_t *cl, uint32_t np, const double *m);
void csf_contact_unsolvable(csf_contacts *cs, const uint32_t *cl, uint32_t np, const double *m);
/* Frees the systems kept for recall (cluster.c). */
void csf_contact_forget(csf_contacts *cs);
int csf_contact_least_squares(csf_contacts *cs, uint32_t dim, const double *T, const unsigned char *fric);
/* cluster.c: the frames of a system's unknowns (pair a's dc[a] of them, normal n + 3a): T turns them
   into normal forces and friction, which fric marks (csf_contact_solve takes the least friction) */
void csf_contact_frames(uint32_t np, const unsigned char *dc, const double *n, uint32_t dim, double *T,
                        unsigned char *fric);

/* force.c: the rounding of a pair's relative acceleration (curv its centripetal term); an apart
   pair's guard at positions pi, pj (NULL: j's in m) */
double csf_contact_accel_resolution(const cpair *c, const double *m, double curv);
/* force.c: the sum of the pair's bodies' speeds; the least relative speed or slip that counts, no
   less than least */
double csf_contact_speeds(const cpair *c, const double *m);
double csf_contact_speed_resolution(const cpair *c, const double *m, double least);
double csf_contact_gap_guard(const cpair *c, const double *m, const double *pi, const double *pj);
/* The choice of csf_contact_choose for a pair: apart, in contact (in the mode it has, or entering
   contact takes), sliding (along cs->dir), sticking; or'ed with MODES_CHOSEN when modes.c chose
   it for its whole cluster. */
enum { TO_APART = 1, TO_CONTACT, TO_SLIDE, TO_STICK, MODES_CHOSEN = 8 };
/* force.c: pair c's force directions B and equations E in mode mode, sliding along ds where it
   does not slip ahead (returns its unknowns: 3 sticking, 1 sliding, 2 sliding without slipping
   ahead, with the friction across ds) */
int csf_contact_basis(const cpair *c, const double *m, const double n[3], double sign, int mode, const double ds[3],
                      double B[9], double E[9]);
/* force.c: the modes of the pairs marked in cs->mark (those in contact, and those touching at
   rest), cluster by cluster: with fresh accelerations (of the modes as they are) a cluster with
   friction by csf_contact_choose_modes, the others (and those it leaves) by the complementarity
   problem of their normal forces; the marks become TO_* (a cluster not settled keeps its modes) */
void csf_contact_choose(csf_contacts *cs, double *m, int fresh);
/* modes.c: the modes of cluster cl[0..np) with friction, chosen together (0), or -1 (not chosen) */
int csf_contact_choose_modes(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np);

/* settle.c: a pair in contact whose slip (sliding: ahead, slowing) its friction stops within time zeno */
int csf_contact_slip_stops(const cpair *c, const double *m, double zeno);

/* lemke.c: the linear complementarity problem w = M z + q >= 0, z >= 0, w . z = 0 (M n x n,
   row-major) by Lemke's method, into z, with T (csf_lcp_work(n) doubles) and basis (n) to work in:
   0, or -1 when it finds no solution; csf_lcp_solve: that, or where it ends on a ray, the
   solution of the problem with M's diagonal raised by 1e-9 of its largest entry, 1 */
size_t csf_lcp_work(uint32_t n);
int csf_lcp_lemke(uint32_t n, const double *M, const double *q, double *z, double *T, uint32_t *basis);
int csf_lcp_solve(uint32_t n, const double *M, const double *q, double *z, double *T, uint32_t *basis);
extern const double csf_lcp_shift; /* csf_lcp_solve's shift, relative to M's largest entry */
/* spread.c: the forces x of a cluster whose pairs with cone[a] stick, where one's friction is beyond
   mu_s N, plus the smallest self-stress that brings each within its cone and leaves no normal force
   pulling: 0 nothing to do, 1 x changed, -1 none does (x as it was). */
int csf_contact_spread(csf_contacts *cs, const double *m, const uint32_t *cl, uint32_t np, uint32_t dim,
                       const unsigned char *dc, const uint32_t *at, const double *B, const double *nv,
                       const unsigned char *cone, double *x);

/* impulse.c: a change dv of a pair's relative velocity; the impact of pair hit, whose relative
   normal velocity vn becomes target (1: not solved); the velocities before an impact, into W_VR */
void csf_contact_add_impulse(cpair *c, double *m, const double dv[3]);
int csf_contact_collide(csf_contacts *cs, double *m, cpair *hit, double target, double vn);
void csf_contact_before_impact(csf_contacts *cs, const double *m);
/* impulse.c: pair hit sticks together with its cluster (0), or -1 (nothing changed); least as in
   csf_contact_speed_resolution */
int csf_contact_stick_cluster(csf_contacts *cs, double *m, cpair *hit, double least);
/* impulse.c: after a plastic impact or a group's collapse at hit (cs->group), the slips within the
   rounding it leaves stopped together (0), or -1 (nothing changed) */
int csf_contact_hold_group(csf_contacts *cs, double *m, const cpair *hit);
/* A row of a cluster's impulses (csf_contact_dual_rows: an impact's, a slip's stop): a direction e
   of pair a's relative velocity, held at target always (eq: an impact's hit, a stop's hit and its
   tangents, a held pair's tangents) or pushing (a normal, target 0: its impulse >= 0 at velocity
   target, or no impulse and not closing). */
typedef struct csf_srow {
	double e[3];
	uint32_t a;
	unsigned char eq;
	double target;
} csf_srow;
/* impulse.c: does a slide whose relative velocity the impulses of a stop take from v0 to v1 (normal
   n) turn back, or change by more than its slip (beyond vres)? Friction stops a slip before it
   turns it; a slip that the impulses on its bodies change by less than its size slides on. */
int csf_contact_slide_turned(const double n[3], const double v0[3], const double v1[3], double vres);
int csf_contact_dual_rows(csf_contacts *cs, uint32_t np, const csf_srow *R, uint32_t nr, double (*vr)[3],
                          const double *vres, double *x, unsigned char *in);

#endif
