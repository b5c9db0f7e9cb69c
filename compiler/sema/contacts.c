/*
 * contacts.c - contact rules (mechanics/rules 1-4): the bodies the runtime's
 * contact routine works on, checked for the properties it reads.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"

/* Is the rule's call the contact routine, with properties for arguments? Reports if not. */
int check_call(Stmt *s)
{
	Expr *x = s->call;
	if (x->kind != E_CALL || strcmp(x->name, "contact") != 0 || x->nargs != 4) {
		error_at(x->loc, "a rule is an equation, or the contact routine 'contact(pos, radius, pos$1, radius$1)'");
		return 0;
	}
	for (int i = 0; i < 4; i++) {
		Expr *a = x->args[i];
		int want = i < 2 ? 0 : 1;
		if (!((a->kind == E_NAME && want == 0) || (a->kind == E_DOLLAR && a->n == want))) {
			error_at(a->loc, "argument %d of contact() must be a property of %s", i + 1, want ? "$1" : "$0");
			return 0;
		}
	}
	return 1;
}

/*
 * contact(pos, radius, pos$1, radius$1) or contact(pos, radius, point$1,
 * normal$1): mass points, a mass point and an anchor, and a mass point and
 * a plane, for the runtime's contact routine, which reads the bodies'
 * other properties by their mechanics/mass_point names. The program lists
 * the bodies of each rule (Contact, ContactBody), not its pairs: the
 * routine finds at run time the pairs that come near. Two points (both of
 * radius 0) never touch.
 *
 * The kind of a body (enum csf_cbody_kind) follows from its properties: a
 * plane's second geometry property (normal) is a vector; an anchor has the
 * sphere's (pos, radius) but no velocity, acceleration or mass (v, a, m):
 * it is no $0, only a $1 that mass points meet.
 */

static const char *const body_props[CSF_CF_N] = { NULL, "v", "a", "m", NULL, "cr", "mu_s", "mu_k", "FN", "Ff" };
static const char *const plane_props[CSF_CF_N] = { NULL, "edge", NULL, NULL, NULL, "cr", "mu_s", "mu_k", NULL, NULL };
static const char *const anchor_props[CSF_CF_N] = { NULL, NULL, NULL, NULL, NULL, "cr", "mu_s", "mu_k", NULL, NULL };

/* A binding ($0, $1) of a contact rule, as it is checked: its objects and their properties. */
typedef struct CPair {
	Object *a, *b;
	int kind;             /* of b (enum csf_cbody_kind) */
	Var *f[2][CSF_CF_N];  /* of a and of b, in the order of enum csf_contact_field (csf.h) */
} CPair;

/* Is o, with geometry geo of contact(), an anchor: a sphere without v, a and m? */
static int is_anchor(Object *o, Var **geo)
{
	return !geo[1]->isvec && !prop_of_obj(o, "v") && !prop_of_obj(o, "a") && !prop_of_obj(o, "m");
}

/* The kind of body o, with geometry geo, as $1. */
static int body_kind(Object *o, Var **geo)
{
	return geo[1]->isvec ? CSF_CB_PLANE : is_anchor(o, geo) ? CSF_CB_ANCHOR : CSF_CB_POINT;
}

/* Body k's (0: $0, 1: $1) geometry in rule s on object o: the properties that arguments 2k and
 * 2k + 1 of contact() name, into geo[0..1]. Returns 0 if o lacks one: not this geometry. */
static int contact_geo(Stmt *s, Object *o, int k, Var **geo)
{
	for (int i = 0; i < 2; i++)
		if (!(geo[i] = prop_of_obj(o, s->call->args[2 * k + i]->name))) return 0;
	return 1;
}

/* Fills body k's fields of c (its a, b and kind set) from geo and the properties the contact
 * routine reads. Returns 0 if one is missing or of the wrong type, reporting it at s if report. */
static int contact_body(CPair *c, int k, Var **geo, Stmt *s, int report)
{
	Object *o = k ? c->b : c->a;
	int kind = k ? c->kind : CSF_CB_POINT;
	const char *const *names = kind == CSF_CB_PLANE ? plane_props : kind == CSF_CB_ANCHOR ? anchor_props : body_props;
	Var **f = c->f[k];
	f[CSF_CF_POS] = geo[0];
	f[CSF_CF_R] = geo[1];
	for (int i = 0; i < CSF_CF_N; i++) {
		if (!names[i]) continue;
		Var *v = prop_of_obj(o, names[i]);
		if (!v || v->isvec != (i == CSF_CF_V || i == CSF_CF_A || i == CSF_CF_FN || i == CSF_CF_FF)) {
			if (report)
				error_at(s->loc, "contact of %s and %s: object '%s' needs %s property '%s' (mechanics/mass_point's "
				                 "kinds have it)",
				         c->a->name, c->b->name, o->name, v && v->isvec ? "a scalar" : v ? "a vector" : "the", names[i]);
			return 0;
		}
		f[i] = v;
	}
	return 1;
}

/* Are the position and velocity of c's body k integrated? A plane's or an anchor's need not be. */
static int contact_integrated(CPair *c, int k)
{
	return (k && c->kind) || (c->f[k][CSF_CF_POS]->state && c->f[k][CSF_CF_V]->state);
}

/* Checks the binding (a, b) of contact rule s into c, reporting what is wrong. 0 if it is wrong. */
static int contact_binding(Stmt *s, Object *a, Object *b, CPair *c)
{
	Var *geo[4];
	memset(c, 0, sizeof *c);
	c->a = a, c->b = b;
	if (!contact_geo(s, a, 0, geo) || !contact_geo(s, b, 1, geo + 2)) return 0;
	c->kind = body_kind(b, geo + 2);
	if (!contact_body(c, 0, geo, s, 1) || !contact_body(c, 1, geo + 2, s, 1)) return 0;
	if (!contact_integrated(c, 0) || !contact_integrated(c, 1)) {
		error_at(s->loc, "contact of %s and %s: positions and velocities must be integrated (pos' = v, v' = a)",
		         a->name, b->name);
		return 0;
	}
	return 1;
}

/* The contact body of object o of kind kind with properties f: one per object and geometry. */
static ContactBody *contact_cbody(Object *o, int kind, Var **f)
{
	char *key = xprintf("%d %p %p %d", o->index, (void *)f[CSF_CF_POS], (void *)f[CSF_CF_R], kind);
	ContactBody *b = map_get(&sema.M->cbody_keys, key);
	if (b) return b;
	b = xalloc(sizeof *b);
	b->o = o, b->kind = kind, b->index = sema.M->cbodies.n;
	memcpy(b->f, f, sizeof b->f);
	vec_push(&sema.M->cbodies, b);
	map_put(&sema.M->cbody_keys, key, b);
	return b;
}

static Contact *new_contact(Stmt *s, int every)
{
	Contact *r = xalloc(sizeof *r);
	r->st = s, r->src = sema.cur_src, r->every = every;
	return r;
}

/* A radius of 0 decided at compile time that two points never touch: -D cannot change it. (A radius lean
   members share: if every member's is 0.) */
static void contact_radius_fixed(Var *r)
{
	if (!r || r->isvec || r->init[0] != 0 || r->fix) return;
	const double *vals = var_more_of(r)->vals;
	if (vals) {
		const ObjArray *A = r->obj->lean;
		for (long k = 0; A && k <= A->hi - A->lo; k++)
			if (vals[k] != 0) return;
	}
	r->fix = FIX_CONTACT;
}

/* Rule s with `for`: the pair (bind[0], bind[1]), unless it is two points (they never touch) or
 * its $0 is an anchor (an anchor meets mass points only as $1). */
void inst_contact(Stmt *s, Object **bind, int nbind)
{
	CPair c;
	Var *geo[2];
	if (nbind < 2 || (contact_geo(s, bind[0], 0, geo) && is_anchor(bind[0], geo))) return;
	if (!contact_binding(s, bind[0], bind[1], &c)) return;
	for (int k = 0; k < 2 && c.kind != CSF_CB_PLANE; k++) contact_radius_fixed(c.f[k][CSF_CF_R]);
	if (c.kind != CSF_CB_PLANE && !(c.f[0][CSF_CF_R]->init[0] + c.f[1][CSF_CF_R]->init[0] > 0)) return;
	Contact *r = new_contact(s, 0);
	vec_push(&r->b0, contact_cbody(c.a, CSF_CB_POINT, c.f[0]));
	vec_push(&r->b1, contact_cbody(c.b, c.kind, c.f[1]));
	r->nplanes = c.kind == CSF_CB_PLANE;
	r->nanchors = c.kind == CSF_CB_ANCHOR;
	vec_push(&sema.M->contacts, r);
}

/* What the search for contact bodies knows of an object, as $0 (k = 0) and as $1 (k = 1). */
typedef struct Body {
	int geo[2];       /* has the geometry (an anchor has none as $0) */
	int bad[2];       /* lacks a field the contact routine reads, or is not integrated: an error */
	int kind;         /* as $1: enum csf_cbody_kind (nonzero: immovable, meets every $0 of another object) */
	int own;          /* f is its own (malloc'd), not the one the lean members of its array share */
	double r[2];      /* radius */
	Var *(*f)[CSF_CF_N]; /* [2]: as $0 and as $1 */
} Body;

/* What contact rule s needs of every object, in an array indexed like M->objects (malloc'd: the
   caller frees it with free_bodies). The lean members of an array (Object.lean) share their array's
   properties: their array is looked at once, and each takes its own radius. */
static Body *contact_bodies(Stmt *s)
{
	int n = sema.M->objects.n;
	Body *B = xcalloc((size_t)n + 1, sizeof *B), *seen = NULL; /* seen: the last lean member's */
	for (int i = 0; i < n; i++) {
		Object *o = sema.M->objects.v[i];
		if (o->dropped) continue;
		if (o->lean && seen && ((Object *)sema.M->objects.v[seen - B])->lean == o->lean) {
			B[i] = *seen;
			B[i].own = 0;
			for (int k = 0; k < 2; k++)
				if (B[i].geo[k]) B[i].r[k] = member_init(B[i].f[k][CSF_CF_R], o)[0];
			continue;
		}
		B[i].f = xcalloc(2, sizeof *B[i].f);
		B[i].own = 1;
		if (o->lean) seen = &B[i];
		for (int k = 0; k < 2; k++) {
			Var *geo[2];
			if (!contact_geo(s, o, k, geo) || (!k && is_anchor(o, geo))) continue;
			CPair c = { 0 };
			c.a = c.b = o;
			c.kind = k ? body_kind(o, geo) : CSF_CB_POINT;
			B[i].geo[k] = 1;
			B[i].bad[k] = !contact_body(&c, k, geo, s, 0) || !contact_integrated(&c, k);
			if (k) B[i].kind = c.kind;
			B[i].r[k] = member_init(geo[1], o)[0];
			if (B[i].kind != CSF_CB_PLANE || !k) contact_radius_fixed(geo[1]);
			memcpy(B[i].f[k], c.f[k], sizeof B[i].f[k]);
		}
	}
	return B;
}

static void free_bodies(Body *B)
{
	for (int i = 0; i < sema.M->objects.n; i++)
		if (B[i].own) free(B[i].f);
	free(B);
}

/* The first binding (*ea, *eb) of n bodies B that is an error, in binding order: $0 in order,
 * each with its $1 in order (a plane or an anchor before it, or any body after it). (n, n) if none. */
static void first_bad_pair(Body *B, int n, int *ea, int *eb)
{
	/* next_*[i]: the first $1 from i on, any or bad; plane_*: the first plane or anchor */
	int *next_any = xcalloc((size_t)n + 1, sizeof *next_any), *next_bad = xcalloc((size_t)n + 1, sizeof *next_bad);
	int plane_any = n, plane_bad = n;
	next_any[n] = next_bad[n] = n;
	for (int i = n - 1; i >= 0; i--) {
		next_any[i] = B[i].geo[1] ? i : next_any[i + 1];
		next_bad[i] = B[i].geo[1] && B[i].bad[1] ? i : next_bad[i + 1];
		if (B[i].geo[1] && B[i].kind) plane_any = i;
		if (B[i].geo[1] && B[i].kind && B[i].bad[1]) plane_bad = i;
	}
	*ea = *eb = n;
	for (int a = 0; a < n; a++) {
		if (!B[a].geo[0]) continue;
		/* a bad $0 fails with its first $1, a good one with its first bad $1 */
		int plane = B[a].bad[0] ? plane_any : plane_bad, b = plane < a ? plane : (B[a].bad[0] ? next_any : next_bad)[a + 1];
		if (b < n) {
			*ea = a, *eb = b;
			break;
		}
	}
	free(next_any);
	free(next_bad);
}

/*
 * A contact rule without `for`: every mass point with its geometry as $0,
 * every object with its geometry as $1, in the order of definition; the
 * first binding that is an error is reported instead. Kept only if one of
 * its pairs can touch: a mass point and a plane (of another object), or
 * two mass points, or a mass point and an anchor, the sum of whose radii
 * is positive.
 */
void contact_pairs(Stmt *s)
{
	int n = sema.M->objects.n, ea, eb;
	Body *B = contact_bodies(s);
	first_bad_pair(B, n, &ea, &eb);
	if (ea < n) {
		CPair c;
		contact_binding(s, sema.M->objects.v[ea], sema.M->objects.v[eb], &c);
		free_bodies(B);
		return;
	}
	/* the bodies it applies to (a bad one here has no binding) */
	for (int i = 0; i < n; i++)
		for (int k = 0; k < 2; k++) B[i].geo[k] = B[i].geo[k] && !B[i].bad[k];
	int n0 = 0, touch = 0;
	double maxr0 = -HUGE_VAL, maxr0all = -HUGE_VAL; /* the largest radius of a $0 defined before, of any */
	for (int i = 0; i < n; i++) {
		n0 += B[i].geo[0];
		if (B[i].geo[0] && B[i].r[0] > maxr0all) maxr0all = B[i].r[0];
	}
	for (int i = 0; i < n && !touch; i++) {
		if (B[i].geo[1] && B[i].kind == CSF_CB_PLANE) touch = n0 > B[i].geo[0];
		else if (B[i].geo[1] && B[i].kind == CSF_CB_ANCHOR) touch = maxr0all + B[i].r[1] > 0;
		else if (B[i].geo[1] && maxr0 + B[i].r[1] > 0) touch = 1;
		if (B[i].geo[0] && B[i].r[0] > maxr0) maxr0 = B[i].r[0];
	}
	if (!touch) {
		free_bodies(B);
		return;
	}
	Contact *r = new_contact(s, 1);
	for (int i = 0; i < n; i++) {
		if (B[i].geo[0]) vec_push(&r->b0, contact_cbody(sema.M->objects.v[i], CSF_CB_POINT, B[i].f[0]));
		if (B[i].geo[1]) vec_push(&r->b1, contact_cbody(sema.M->objects.v[i], B[i].kind, B[i].f[1]));
		r->nplanes += B[i].geo[1] && B[i].kind == CSF_CB_PLANE;
		r->nanchors += B[i].geo[1] && B[i].kind == CSF_CB_ANCHOR;
	}
	vec_push(&sema.M->contacts, r);
	free_bodies(B);
}

/* Every mass point of a contact rule must have its a determined (by Newton's second law). */
void contact_accels(void)
{
	char *done = xalloc((size_t)sema.M->cbodies.n + 1);
	for (int i = 0; i < sema.M->contacts.n; i++) {
		Contact *r = sema.M->contacts.v[i];
		for (int k = 0; k < 2; k++) {
			Vec *L = k ? &r->b1 : &r->b0, *O = k ? &r->b0 : &r->b1;
			for (int j = 0; j < L->n; j++) {
				ContactBody *b = L->v[j];
				Var *a = b->f[CSF_CF_A];
				if (b->kind || !a || sema_canon(a)->det || done[b->index]) continue;
				done[b->index] = 1;
				Object *other = NULL; /* the first body it can meet, to name the pair */
				for (int q = 0; q < O->n && !other; q++)
					if (((ContactBody *)O->v[q])->o != b->o) other = ((ContactBody *)O->v[q])->o;
				error_at(r->st->loc, "contact of %s and %s: no rule determines %s.a (Newton's second law, "
				                     "'rule: RF = a.mul(m)' of mechanics/rules, does)",
				         k ? (other ? other->name : "?") : b->o->name, k ? b->o->name : (other ? other->name : "?"),
				         b->o->name);
			}
		}
	}
}
