/*
 * dims.c - unit systems and the static dimension analysis.
 *
 * A dimension is a vector of exponents of length, mass, time and electric
 * current (CSF_NDIM; angles are dimensionless: rad and deg are plain
 * factors). Every value in a model
 * has one:
 *  - a unit literal has its unit's; a bare number is a coefficient whose
 *    unit is whatever its equation needs (`x + 1` adds metres to metres;
 *    in `v' = -4 * x` the 4 is 4 1/s^2): an expression with a bare factor is
 *    "soft" and never mismatches; only two dimensioned quantities can
 *    (csf(5), DIMENSIONS);
 *  - predefined constants and t have theirs; a property or global takes the
 *    dimension of its initial value, or of its kind's default; local
 *    coordinates (sph, cyl, cart) that of their lengths, like a vector literal;
 *  - the others (temporaries, and properties given bare numbers) are
 *    inferred from the rules: each equation, sum, comparison and function
 *    argument is a constraint, linear in the unknown exponents; constraints
 *    with one unknown left are solved, repeatedly, until nothing changes.
 * Then every constraint whose dimensions are all known is checked, and a
 * mismatch is a compile error naming both dimensions in the units of the
 * system the model is compiled for (csfc --units mks|cgs|fps). A unit is
 * printed by the name of a derived unit of that system when its dimension
 * is one (N, V, T in mks; dyn, erg in cgs; pdl in fps; C in all three),
 * else in the system's base units (kg*m/(s^3*A)): either reads back.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "csf_int.h"

/* ---- unit systems ---- */

/* A derived unit a system prints by its name: the dimension it names. */
typedef struct Named { const char *name; double d[CSF_NDIM]; } Named;

#define MAX_NAMED 12

static const struct system {
	const char *name;
	double base[CSF_NDIM];       /* the system's unit of length, mass, time, current in SI */
	const char *unit[CSF_NDIM];  /* their names */
	Named named[MAX_NAMED];      /* the derived units that are coherent in the system */
} systems[] = {
	[UNITS_MKS] = { "mks", { 1, 1, 1, 1 }, { "m", "kg", "s", "A" },
	                { { "N", { 1, 1, -2, 0 } }, { "J", { 2, 1, -2, 0 } }, { "W", { 2, 1, -3, 0 } },
	                  { "Pa", { -1, 1, -2, 0 } }, { "C", { 0, 0, 1, 1 } }, { "V", { 2, 1, -3, -1 } },
	                  { "ohm", { 2, 1, -3, -2 } }, { "S", { -2, -1, 3, 2 } }, { "F", { -2, -1, 4, 2 } },
	                  { "H", { 2, 1, -2, -2 } }, { "Wb", { 2, 1, -2, -1 } }, { "T", { 0, 1, -2, -1 } } } },
	[UNITS_CGS] = { "cgs", { 1e-2, 1e-3, 1, 1 }, { "cm", "g", "s", "A" },
	                { { "dyn", { 1, 1, -2, 0 } }, { "erg", { 2, 1, -2, 0 } }, { "C", { 0, 0, 1, 1 } } } },
	[UNITS_FPS] = { "fps", { 0.3048, 0.45359237, 1, 1 }, { "ft", "lb", "s", "A" },
	                { { "pdl", { 1, 1, -2, 0 } }, { "C", { 0, 0, 1, 1 } } } },
};

double dims_to_system(double si, const double d[CSF_NDIM])
{
	return csf_units_to_system(si, d, systems[opts.units].base);
}

void dims_system_base(double base[CSF_NDIM])
{
	memcpy(base, systems[opts.units].base, sizeof systems[opts.units].base);
}

int dims_none(const double d[CSF_NDIM])
{
	for (int i = 0; i < CSF_NDIM; i++)
		if (d[i] != 0) return 0;
	return 1;
}

/* The derived unit of the system in use that names dimension d, or NULL. */
static const char *named_unit(const double d[CSF_NDIM])
{
	const struct system *s = &systems[opts.units];
	for (int i = 0; i < MAX_NAMED && s->named[i].name; i++)
		if (memcmp(s->named[i].d, d, sizeof s->named[i].d) == 0) return s->named[i].name;
	return NULL;
}

/* Dimension d in the system's base units, "kg*m/s^2"; "" if dimensionless. */
static const char *base_unit(const double d[CSF_NDIM])
{
	const struct system *s = &systems[opts.units];
	if (dims_none(d)) return "";
	char *num = xstrdup(""), *den = xstrdup("");
	int nden = 0;
	/* the order physicists write: mass, length, time, current */
	static const int order[CSF_NDIM] = { 1, 0, 2, 3 };
	for (int k = 0; k < CSF_NDIM; k++) {
		int i = order[k];
		double e = d[i];
		if (e == 0) continue;
		double a = fabs(e);
		char *part = a == 1 ? xstrdup(s->unit[i]) : xprintf("%s^%g", s->unit[i], a);
		if (e > 0) num = xprintf("%s%s%s", num, *num ? "*" : "", part);
		else den = xprintf("%s%s%s", den, *den ? "*" : "", part), nden++;
	}
	if (!*num) num = "1";
	if (!*den) return num;
	return nden > 1 ? xprintf("%s/(%s)", num, den) : xprintf("%s/%s", num, den);
}

const char *dims_unit(const double d[CSF_NDIM])
{
	const char *n = named_unit(d);
	return n ? n : base_unit(d);
}

const char *dims_describe(const double d[CSF_NDIM])
{
	if (dims_none(d)) return "dimensionless";
	const char *n = named_unit(d);
	return n ? xprintf("%s (%s)", n, base_unit(d)) : base_unit(d);
}

/* ---- affine dimensions: known part + sum of coefficient * unknown variable ---- */

#define MAXU 6

typedef struct Aff {
	int soft;        /* a bare number is a factor (or the whole): any dimension fits; c and u are
	                    the dimension it has when the bare numbers are pure numbers */
	int overflow;    /* too many unknowns to track */
	double c[CSF_NDIM];
	int nu;
	Var *u[MAXU];
	double k[MAXU];
	Var *bare;       /* a property or global among its leaves that an equation gave its dimension */
} Aff;

/* A known dimension: exponents of length, mass, time (and current: known_dim). */
static Aff known_dim(const double d[CSF_NDIM])
{
	Aff a = { 0 };
	memcpy(a.c, d, sizeof a.c);
	return a;
}

static Aff known(double l, double m, double t)
{
	return known_dim((double[CSF_NDIM]){ l, m, t, 0 });
}

static Aff lin(Aff a, double ka, Aff b, double kb)
{
	Aff r = { 0 };
	r.soft = a.soft || b.soft;
	r.bare = a.bare ? a.bare : b.bare;
	r.overflow = a.overflow || b.overflow;
	for (int i = 0; i < CSF_NDIM; i++) r.c[i] = ka * a.c[i] + kb * b.c[i];
	for (int s = 0; s < 2; s++) {
		Aff *x = s ? &b : &a;
		double kx = s ? kb : ka;
		for (int i = 0; i < x->nu; i++) {
			int j = 0;
			while (j < r.nu && r.u[j] != x->u[i]) j++;
			if (j == r.nu) {
				if (r.nu == MAXU) {
					r.overflow = 1;
					continue;
				}
				r.u[r.nu] = x->u[i];
				r.k[r.nu++] = 0;
			}
			r.k[j] += kx * x->k[i];
		}
	}
	/* drop cancelled unknowns */
	int n = 0;
	for (int i = 0; i < r.nu; i++)
		if (r.k[i] != 0) r.u[n] = r.u[i], r.k[n++] = r.k[i];
	r.nu = n;
	return r;
}

/* ---- the constraint walk ---- */

/* The largest exponent of a dimension (m^100): beyond it an expression's dimension is an error. */
#define DIM_MAX_EXP 100

typedef struct Walk {
	int report;      /* 0: infer, 1: report mismatches */
	int soft;        /* infer also from soft sides (after everything else has been inferred) */
	int progress;
	Map reported;    /* locations already reported */
} Walk;

/* Reports msg at l (once per place); bare, if not NULL, is a property or global given a bare value
 * that an equation gave its dimension: a note at it says which, and how to write its unit. */
static void report(Walk *W, Loc l, const char *msg, const Var *bare)
{
	char *key = xprintf("%d:%d:%d", l.file, l.line, l.col);
	if (map_get(&W->reported, key)) return;
	map_put(&W->reported, key, key);
	error_at(l, "%s", msg);
	if (!bare) return;
	const char *value = bare->isvec ? xprintf("(%g, %g, %g)", bare->init[0], bare->init[1], bare->init[2])
	                                : xprintf("%g", bare->init[0]);
	note_at(bare->loc, "'%s' has no unit, and line %d makes it %s: write '%s = %s %s' if that is its unit",
	        bare->name, var_more_of(bare)->dim_from.line, dims_describe(bare->dim), bare->name, value, dims_unit(bare->dim));
}

const char *dims_operand(const RExpr *e, const double d[CSF_NDIM])
{
	const char *unit = dims_none(d) ? "dimensionless" : dims_unit(d);
	if (e && e->k == R_COMP && e->a[0]->k == R_VAR)
		return xprintf("%s.%c (%s)", e->a[0]->var->name, "xyz"[e->comp], unit);
	if (e && e->k == R_VAR) return xprintf("%s (%s)", e->var->name, unit);
	if (e && e->k == R_CONST && e->dimk == DK_KNOWN) {
		const char *u = dims_unit(d);
		if (!e->isvec) return xprintf("%.10g%s%s", e->c[0], *u ? " " : "", u);
		return xprintf("(%.10g, %.10g, %.10g)%s%s", e->c[0], e->c[1], e->c[2], *u ? " " : "", u);
	}
	return dims_describe(d);
}

/*
 * The constraint a == b (both free of booleans). In infer mode solves it when
 * one unknown is left; in report mode reports a mismatch of known dimensions
 * with the message made by msg(da, db). A soft side (one with a bare factor)
 * never mismatches: its bare number takes the dimension the other side needs.
 * It infers an unknown of the other side only when it has no unknown itself
 * and a dimension, its bare numbers taken as pure numbers (`w = 0.5 * m * v^2`
 * makes w a J; `u = 1` decides nothing), one at a time after all else.
 */
typedef const char *(*MsgFn)(const char *da, const char *db, void *ctx);

static void constrain(Walk *W, Aff a, RExpr *ea, Aff b, RExpr *eb, Loc l, MsgFn msg, void *ctx)
{
	if (a.overflow || b.overflow) return;
	if (a.soft || b.soft) {
		const Aff *s = a.soft ? &a : &b;
		if (W->report || !W->soft || W->progress || (a.soft && b.soft) || s->nu || dims_none(s->c)) return;
	}
	Aff d = lin(a, 1, b, -1);
	if (d.nu == 1 && !W->report) {
		Var *v = d.u[0];
		double k = d.k[0];
		for (int i = 0; i < CSF_NDIM; i++)
			if (!(fabs(d.c[i] / k) <= DIM_MAX_EXP)) return; /* left unknown; the expression reports it */
		v->dimk = DK_KNOWN;
		if (v->kind == V_PROP || v->kind == V_GLOBAL) var_more(v)->dim_from = l;
		for (int i = 0; i < CSF_NDIM; i++) {
			double x = -d.c[i] / k;
			x = fabs(x - round(x)) < 1e-9 ? round(x) : x;
			v->dim[i] = x == 0 ? 0.0 : x; /* never -0, which would print as "^-0" */
		}
		W->progress = 1;
		return;
	}
	int differ = 0;
	for (int i = 0; i < CSF_NDIM; i++) differ |= fabs(d.c[i]) > 1e-9;
	if (d.nu == 0 && W->report && differ)
		report(W, l, msg(dims_operand(ea, a.c), dims_operand(eb, b.c), ctx), a.bare ? a.bare : b.bare);
}

static const char *msg_add(const char *a, const char *b, void *ctx)
{
	return xprintf("cannot %s %s and %s", (const char *)ctx, a, b);
}
static const char *msg_vector(const char *a, const char *b, void *ctx)
{
	(void)ctx;
	return xprintf("the components of a vector must have one dimension, not %s and %s", a, b);
}
static const char *msg_eq(const char *a, const char *b, void *ctx)
{
	return xprintf("the two sides of \"%s\" differ in dimension: %s and %s", (const char *)ctx, a, b);
}
static const char *msg_deriv(const char *a, const char *b, void *ctx)
{
	return xprintf("the derivative rule \"%s\" sets a rate of %s to %s", (const char *)ctx, a, b);
}
static const char *msg_dimless(const char *a, const char *b, void *ctx)
{
	(void)b;
	return xprintf("%s must be dimensionless, not %s", (const char *)ctx, a);
}
static const char *msg_force(const char *a, const char *b, void *ctx)
{
	(void)b;
	return xprintf("a rule with attribute F determines a force, but %s is %s", (const char *)ctx, a);
}

static Aff walk(Walk *W, RExpr *e);

/* A variable's dimension: known, or itself as the one unknown. */
static Aff var_aff(Var *v)
{
	if (v->dimk == DK_KNOWN) {
		Aff a = known_dim(v->dim);
		if (var_more_of(v)->dim_from.line) a.bare = v;
		return a;
	}
	Aff a = { 0 };
	a.nu = 1;
	a.u[0] = v;
	a.k[0] = 1;
	return a;
}

static Aff dimless(Walk *W, RExpr *arg, Aff a, const char *what)
{
	constrain(W, a, arg, known(0, 0, 0), NULL, arg->loc, msg_dimless, (void *)what);
	return known(0, 0, 0);
}

/* Values that must share one dimension (a vector's components): the first that is not soft sets it. */
static Aff one_dim(Walk *W, const Aff *x, RExpr *const *args, int n)
{
	Aff d = x[0];
	RExpr *de = args[0];
	for (int i = 1; i < n; i++) {
		constrain(W, d, de, x[i], args[i], args[i]->loc, msg_vector, NULL);
		if (d.soft) d = x[i], de = args[i];
	}
	return d;
}

/* r, the dimension of e; one whose exponents (or the coefficients of its unknowns) pass
 * DIM_MAX_EXP is reported, and not tracked further. */
static Aff bounded(Walk *W, RExpr *e, Aff r)
{
	int big = 0;
	for (int i = 0; i < CSF_NDIM; i++) big |= !(fabs(r.c[i]) <= DIM_MAX_EXP);
	for (int i = 0; i < r.nu; i++) big |= !(fabs(r.k[i]) <= DIM_MAX_EXP);
	if (!big) return r;
	if (W->report) report(W, e->loc, xprintf("the dimension of this expression has an exponent beyond %d", DIM_MAX_EXP), NULL);
	r.overflow = 1;
	r.nu = 0;
	memset(r.c, 0, sizeof r.c);
	return r;
}

static Aff walk_op(Walk *W, RExpr *e, Aff *x)
{
	switch (e->op) {
	case CSF_OP_MOV: case CSF_OP_VMOV: case CSF_OP_NEG: case CSF_OP_VNEG: case CSF_OP_ABS: case CSF_OP_VMAG:
		return x[0];
	case CSF_OP_ADD: case CSF_OP_VADD: case CSF_OP_SUB: case CSF_OP_VSUB: case CSF_OP_MIN: case CSF_OP_MAX: {
		int sub = e->op == CSF_OP_SUB || e->op == CSF_OP_VSUB;
		constrain(W, x[0], e->a[0], x[1], e->a[1], e->a[1]->loc, msg_add,
		          (void *)(sub ? "subtract" : e->op == CSF_OP_MIN || e->op == CSF_OP_MAX ? "take min/max of" : "add"));
		return x[0].soft ? x[1] : x[0];
	}
	case CSF_OP_VPACK:
		return one_dim(W, x, e->a, 3);
	case CSF_OP_MUL: case CSF_OP_VMUL: case CSF_OP_VDOT: case CSF_OP_VCROSS:
		return lin(x[0], 1, x[1], 1);
	case CSF_OP_DIV: case CSF_OP_VDIV:
		return lin(x[0], 1, x[1], -1);
	case CSF_OP_SQRT:
		return lin(x[0], 0.5, known(0, 0, 0), 0);
	case CSF_OP_POW:
		dimless(W, e->a[1], x[1], "an exponent");
		if (e->a[1]->k == R_CONST) return lin(x[0], e->a[1]->c[0], known(0, 0, 0), 0);
		return dimless(W, e->a[0], x[0], "a base raised to a variable power");
	case CSF_OP_SIN: case CSF_OP_COS: case CSF_OP_TAN: case CSF_OP_ASIN: case CSF_OP_ACOS: case CSF_OP_ATAN:
	case CSF_OP_SINH: case CSF_OP_COSH: case CSF_OP_TANH: case CSF_OP_EXP: case CSF_OP_LOG: case CSF_OP_LOG10: {
		static const char *const names[] = {
			[CSF_OP_SIN] = "sin", [CSF_OP_COS] = "cos", [CSF_OP_TAN] = "tan", [CSF_OP_ASIN] = "asin",
			[CSF_OP_ACOS] = "acos", [CSF_OP_ATAN] = "atan", [CSF_OP_SINH] = "sinh", [CSF_OP_COSH] = "cosh",
			[CSF_OP_TANH] = "tanh", [CSF_OP_EXP] = "exp", [CSF_OP_LOG] = "log", [CSF_OP_LOG10] = "log10",
		};
		return dimless(W, e->a[0], x[0], xprintf("the argument of %s", names[e->op]));
	}
	case CSF_OP_FLOOR:
		return dimless(W, e->a[0], x[0], "the argument of floor (of mod: its first argument over its second)");
	case CSF_OP_ATAN2:
		constrain(W, x[0], e->a[0], x[1], e->a[1], e->a[1]->loc, msg_add, "compare (atan2)");
		return known(0, 0, 0);
	case CSF_OP_LT: case CSF_OP_LE: case CSF_OP_GT: case CSF_OP_GE: case CSF_OP_EQ: case CSF_OP_NE:
		constrain(W, x[0], e->a[0], x[1], e->a[1], e->a[1]->loc, msg_add, "compare");
		return known(0, 0, 0);
	case CSF_OP_VPROJ:
		return x[0];
	default: /* VUNIT, VANGLE, AND, OR, NOT */
		return known(0, 0, 0);
	}
}

static Aff walk(Walk *W, RExpr *e)
{
	switch (e->k) {
	case R_CONST: {
		Aff a = { 0 };
		if (e->dimk != DK_KNOWN) a.soft = 1;
		else memcpy(a.c, e->dim, sizeof a.c);
		return a;
	}
	case R_VAR: return var_aff(e->var);
	case R_RF: return known(1, 1, -2);
	case R_COMP: return walk(W, e->a[0]);
	case R_OP: {
		Aff x[3];
		for (int i = 0; i < e->n; i++) x[i] = walk(W, e->a[i]);
		return bounded(W, e, walk_op(W, e, x));
	}
	}
	return known(0, 0, 0);
}

static void walk_inst(Walk *W, Inst *I)
{
	if (I->cond) walk(W, I->cond);
	for (int b = 0; b < 2; b++) {
		Vec *br = b ? &I->els : &I->then;
		for (int i = 0; i < br->n; i++) {
			Assign *a = br->v[i];
			if (I->isderiv) {
				Aff rate = lin(var_aff(a->var), 1, known(0, 0, 1), -1);
				constrain(W, rate, NULL, walk(W, a->rhs), a->rhs, a->loc, msg_deriv, a->text);
				continue;
			}
			Aff l = walk(W, a->lhs), r = walk(W, a->rhs);
			constrain(W, l, a->lhs, r, a->rhs, a->rhs->loc, msg_eq, a->text);
		}
	}
	if (I->isF)
		for (int i = 0; i < I->targets.n; i++) {
			Var *v = I->targets.v[i];
			constrain(W, var_aff(v), NULL, known(1, 1, -2), NULL, I->st->loc, msg_force, v->name);
		}
}

/* A constraint's two sides have one dimension, which is g's. */
static void walk_constraint(Walk *W, Constraint *K)
{
	Aff l = walk(W, K->lhs), r = walk(W, K->rhs);
	constrain(W, l, K->lhs, r, K->rhs, K->rhs->loc, msg_eq, K->st->text);
	if (!W->report) return;
	Aff g = !l.soft && !l.nu && !l.overflow ? l : r;
	K->dimk = !g.nu && !g.overflow ? DK_KNOWN : DK_UNKNOWN;
	memcpy(K->dim, g.c, sizeof K->dim);
}

void dims_check(Model *M)
{
	Walk W = { 0 };
	for (int iter = 0; iter < 64; iter++) {
		W.progress = 0;
		for (int i = 0; i < M->insts.n; i++) walk_inst(&W, M->insts.v[i]);
		for (int i = 0; i < M->cons.n; i++) walk_constraint(&W, M->cons.v[i]);
		if (W.progress) continue;
		W.soft = 1; /* one unknown at a time from a soft side, then the others again */
		for (int i = 0; i < M->insts.n && !W.progress; i++) walk_inst(&W, M->insts.v[i]);
		W.soft = 0;
		if (!W.progress) break;
	}
	W.report = 1;
	for (int i = 0; i < M->insts.n; i++) walk_inst(&W, M->insts.v[i]);
	for (int i = 0; i < M->cons.n; i++) walk_constraint(&W, M->cons.v[i]);
}

/* Gives constant out dimension a: known, or free when a is not fully known or is a bare
 * number (its bare factors pure numbers, it is dimensionless): `2 * pi` is bare, `2 * 3 m` 6 m. */
static void set_const_dim(RExpr *out, Aff a)
{
	if ((a.soft && dims_none(a.c)) || a.nu || a.overflow) {
		out->dimk = DK_FREE;
		return;
	}
	out->dimk = DK_KNOWN;
	for (int i = 0; i < CSF_NDIM; i++) out->dim[i] = a.c[i] == 0 ? 0 : a.c[i];
}

void dims_fold(int op, RExpr **args, int n, RExpr *out, Loc l)
{
	Walk W = { 0 };
	W.report = 1;
	RExpr e = { 0 };
	e.k = R_OP;
	e.op = op;
	e.n = n;
	for (int i = 0; i < n; i++) e.a[i] = args[i];
	e.loc = l;
	set_const_dim(out, walk(&W, &e));
}

void dims_coords(const char *sys, RExpr **args, RExpr *out)
{
	/* the names of the angles among the arguments; cart(x, y, z) has none */
	static const struct { const char *sys, *angle[3]; } coords[] = {
		{ "sph", { NULL, "theta", "phi" } }, /* sph(r, theta, phi) */
		{ "cyl", { NULL, "phi", NULL } },    /* cyl(rho, phi, z) */
	};
	static const char *const none[3] = { NULL, NULL, NULL };
	const char *const *angle = none;
	for (size_t i = 0; i < sizeof coords / sizeof coords[0]; i++)
		if (strcmp(sys, coords[i].sys) == 0) angle = coords[i].angle;
	Walk W = { 0 };
	W.report = 1;
	Aff len[3];
	RExpr *len_args[3];
	int n = 0;
	for (int i = 0; i < 3; i++) {
		Aff a = walk(&W, args[i]);
		if (angle[i]) {
			dimless(&W, args[i], a, xprintf("the angle %s of %s", angle[i], sys));
		} else {
			len[n] = a;
			len_args[n++] = args[i];
		}
	}
	set_const_dim(out, one_dim(&W, len, len_args, n));
}
