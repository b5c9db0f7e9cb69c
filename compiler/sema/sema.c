/*
 * sema.c - from statements to a resolved model.
 *
 * 1. Objects, kinds and globals are built; initial values are constant
 *    expressions folded with the runtime's own arithmetic (fold_op).
 * 2. Rules are instantiated: a rule applies to every object ($0) and every
 *    permitted tuple ($1..$k, spec 2.2.1) that has the properties it reads,
 *    or to the objects its `for` list names.
 * 3. Derivative rules (`v' = a`) are found first: their left sides become
 *    state variables, determined at the start of every evaluation.
 * 4. The other rules are resolved in source order, except that a rule
 *    reading RF waits until every rule with attribute F has been resolved
 *    (RF is their sum). For each instance the target is chosen by the
 *    precedence of spec 2.4.1 among the variables not yet determined
 *    (unwatched temporary, then property, then global; the later defined
 *    first); none left is "overdetermined", an undetermined temporary read
 *    is "unresolvable". The equation is then solved for the target
 *    symbolically: it must be linear in it.
 * 5. Assertions and the watch list are resolved, and the dimensions checked
 *    (dims.c) over every instance that resolved, also after errors; then
 *    gen.c keeps only the instances that the derivatives, the watches and
 *    the assertions need.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_const_mksa.h>

#include "csfc.h"
#include "sema.h"
#include "lint.h"
#include "csf.h"
#include "parse.h"

/* ---- state of the pass ---- */

/* The state of one resolution (sema_run resolves twice: by shape, then, if need be, by object);
 * sema_reset starts it anew. */
typedef struct Sema {
	Model *M;
	Map objects_by_name, globals_by_name, kinds, temps, prop_names, vector_decls;
	int def_counter;
	int shaped;             /* resolving once per shape (sema_run's first attempt) */
	const char *unshaped;   /* why the model cannot be: the attempt is given up */
	int cur_src;            /* source entry of the statement being instantiated */
	Map watched;            /* names in the watch list, and OBJECT\x01NAME */
	Vec *cur_insts;         /* where the instances of rules, assertions and stops go */
	Vec deriv_insts;        /* the derivative rules' instances, resolved after the others */
} Sema;

static Sema sema;

/* Starts a resolution: nothing defined yet, a new model; shaped: once per shape. */
static void sema_reset(int shaped)
{
	sema = (Sema){ 0 };
	sema.M = xalloc(sizeof *sema.M);
	sema.shaped = shaped;
}

/* Gives up resolving by shape (the model is resolved again, object by object). */
static void unshape(const char *why)
{
	if (!sema.unshaped) sema.unshaped = why;
}

static const char *const predefined_names[] = { "t", "RF", NULL };

/* ---- folding with the runtime's arithmetic ---- */

/* Operand k of an instruction being folded: a scalar, a vector, an immediate. */
#define FOLD_S(k) in[k][0]
#define FOLD_V(k) csf_v(in[k][0], in[k][1], in[k][2])
#define FOLD_N(k) (int)in[k][0]
#define FOLD_DS(e) out[0] = (e)
#define FOLD_DV(e) \
	do { \
		csf_vec r_ = (e); \
		out[0] = r_.x, out[1] = r_.y, out[2] = r_.z; \
	} while (0)
#define FOLD_ARGS1(b, c, d)
#define FOLD_ARGS2(b, c, d) FOLD_##b(0)
#define FOLD_ARGS3(b, c, d) FOLD_##b(0), FOLD_##c(1)
#define FOLD_ARGS4(b, c, d) FOLD_##b(0), FOLD_##c(1), FOLD_##d(2)

/* The result of instruction op on the operand values in[0..], as the VM computes it, in out[0..2]. */
void fold_op(int op, double in[3][3], double out[3])
{
	out[0] = out[1] = out[2] = 0;
	if (op == CSF_OP_POW) { /* a constant exponent: as POWI computes it, not as POW */
		out[0] = csf_pow(in[0][0], in[1][0]);
		return;
	}
	switch (op) {
#define OP(name, n, a, b, c, d, syn) \
	case CSF_OP_##name: \
		FOLD_##a(csf_op_##name(FOLD_ARGS##n(b, c, d))); \
		break;
#define CTRL(name, n, a, b, c, d, syn)
#include "opcodes.def"
#undef OP
#undef CTRL
	default: break;
	}
}

/* ---- expressions ---- */

static RExpr *rnew(RKind k, Loc l)
{
	RExpr *e = xalloc(sizeof *e);
	e->k = k;
	e->loc = l;
	return e;
}

static RExpr *rconst(double x, Loc l)
{
	RExpr *e = rnew(R_CONST, l);
	e->c[0] = x;
	e->dimk = DK_FREE;
	return e;
}

static RExpr *rvconst(const double *v, Loc l)
{
	RExpr *e = rnew(R_CONST, l);
	memcpy(e->c, v, sizeof e->c);
	e->isvec = 1;
	e->dimk = DK_FREE;
	return e;
}

/* A constant standing for a variable's value (initial values): it has the variable's dimension. */
static RExpr *rvarconst(Var *v, Loc l)
{
	RExpr *e = v->isvec ? rvconst(v->init, l) : rconst(v->init[0], l);
	if (v->dimk == DK_KNOWN) {
		e->dimk = DK_KNOWN;
		memcpy(e->dim, v->dim, sizeof e->dim);
	}
	return e;
}

static int is_const(RExpr *e, double x) { return e->k == R_CONST && !e->isvec && e->c[0] == x; }

/* Builds op(a, b, c) of the given result type, folding constant operands. */
static RExpr *rop(int op, int isvec, Loc l, RExpr *a, RExpr *b, RExpr *c)
{
	RExpr *e = rnew(R_OP, l);
	e->op = op;
	e->isvec = isvec;
	e->a[0] = a;
	e->a[1] = b;
	e->a[2] = c;
	e->n = c ? 3 : b ? 2 : 1;
	int allc = 1;
	for (int i = 0; i < e->n; i++) allc &= e->a[i]->k == R_CONST;
	if (allc) {
		double in[3][3] = { { 0 } }, out[3];
		for (int i = 0; i < e->n; i++) memcpy(in[i], e->a[i]->c, sizeof in[i]);
		/* Folding -0.0 and NaN is safe here: the constant pool (gen.c) tells
		 * constants apart by their bits, not by ==. */
		fold_op(op, in, out);
		RExpr *k = rnew(R_CONST, l);
		memcpy(k->c, out, sizeof out);
		k->isvec = isvec;
		dims_fold(op, e->a, e->n, k, l);
		return k;
	}
	return e;
}

static int opcode_of_func(const char *name, int *nargs)
{
	static const struct { const char *n; int op, args; } f[] = {
		{ "sin", CSF_OP_SIN, 1 }, { "cos", CSF_OP_COS, 1 }, { "tan", CSF_OP_TAN, 1 },
		{ "asin", CSF_OP_ASIN, 1 }, { "acos", CSF_OP_ACOS, 1 }, { "atan", CSF_OP_ATAN, 1 },
		{ "sinh", CSF_OP_SINH, 1 }, { "cosh", CSF_OP_COSH, 1 }, { "tanh", CSF_OP_TANH, 1 },
		{ "exp", CSF_OP_EXP, 1 }, { "log", CSF_OP_LOG, 1 }, { "log10", CSF_OP_LOG10, 1 },
		{ "sqrt", CSF_OP_SQRT, 1 }, { "abs", CSF_OP_ABS, 1 }, { "atan2", CSF_OP_ATAN2, 2 },
		{ "min", CSF_OP_MIN, 2 }, { "max", CSF_OP_MAX, 2 },
	};
	for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
		if (strcmp(f[i].n, name) == 0) {
			*nargs = f[i].args;
			return f[i].op;
		}
	return -1;
}

static int determined(struct Var *v);

/* ---- resolution context ---- */

typedef struct Ctx {
	int init;          /* building an initial value: only constants */
	Object *self;      /* init: the object being defined, if any */
	Object **bind;
	int nbind;
	Vec *reads;        /* Var* read */
	Vec *rf;           /* Object* whose RF is read */
	Vec *pending;      /* Var* temporaries read but not yet existing */
	int failed;
	int key_nbind;     /* how much of the binding keys a temporary: 1 for `for` rules, all for $n tuples */
	int fold;          /* init: the values it reads are folded into (FIX_FOLDED or FIX_RUN) ... */
	const char *fold_obj, *fold_name; /* ... this value, */
	int fold_line;     /* defined on this line (see Var.fix) */
	Var *first_read;   /* init: the first global or property it read */
} Ctx;

static void add_unique(Vec *v, void *x)
{
	if (v && !vec_has(v, x)) vec_push(v, x);
}

static int is_predefined(const char *n)
{
	for (int i = 0; predefined_names[i]; i++)
		if (strcmp(n, predefined_names[i]) == 0) return 1;
	return 0;
}

static Var *prop_of(Object *o, const char *name) { return map_get(&o->props_by_name, name); }

static char *temp_key(const char *name, Object **bind, int nbind)
{
	char *k = xstrdup(name);
	for (int i = 0; i < nbind; i++) k = xprintf("%s\x01%d", k, bind[i]->index);
	return k;
}

/* The temporary `name` of a binding: the tuple's own, else $0's. */
static Var *find_temp(const char *name, Object **bind, int nbind)
{
	Var *v = map_get(&sema.temps, temp_key(name, bind, nbind));
	if (!v && nbind > 1) v = map_get(&sema.temps, temp_key(name, bind, 1));
	return v;
}

static RExpr *var_ref(Ctx *C, Var *v, Loc l, int place)
{
	if (C->init) {
		if (v->kind == V_TIME) {
			error_at(l, "'t' is not known at compile time; an initial value must be a constant");
			C->failed = 1;
			return rconst(0, l);
		}
		if (C->fold && !v->fix) {
			v->fix = C->fold;
			v->fix_obj = C->fold_obj;
			v->fix_name = C->fold_name;
			v->fix_line = C->fold_line;
		}
		if (!C->first_read) C->first_read = v;
		return rvarconst(v, l);
	}
	RExpr *e = rnew(R_VAR, l);
	e->var = v;
	e->place = place;
	e->isvec = v->isvec;
	add_unique(C->reads, v);
	return e;
}

static RExpr *build(Ctx *C, Expr *x);

static RExpr *build_name(Ctx *C, Expr *x, const char *name, Object *o, int explicit_obj)
{
	Loc l = x->loc;
	int place = -1; /* which $n o is */
	for (int p = 0; !C->init && !explicit_obj && p < C->nbind; p++)
		if (C->bind[p] == o) {
			place = p;
			break;
		}
	/* by shape, a member stands for its shape: the representative's variables, at o's place */
	if (sema.shaped && o && !C->init && o->sidx) o = o->shape->members[0];
	if (!explicit_obj) {
		if (strcmp(name, "t") == 0) return var_ref(C, sema.M->time, l, -1);
		if (strcmp(name, "RF") == 0) {
			if (C->init || !o) {
				error_at(l, "RF is only defined in rules");
				C->failed = 1;
				return rvconst((double[3]){ 0, 0, 0 }, l);
			}
			if (place != 0 && o->shape->n > 1) unshape("a rule reads the RF of $1");
			RExpr *e = rnew(R_RF, l);
			e->obj = o;
			e->isvec = 1;
			add_unique(C->rf, o);
			return e;
		}
		Var *g = map_get(&sema.globals_by_name, name);
		if (g) return var_ref(C, g, l, -1);
	}
	if (o) {
		Var *p = prop_of(o, name);
		if (p) return var_ref(C, p, l, place);
	}
	if (C->init) {
		if (explicit_obj) error_at(l, "object '%s' has no property '%s' (yet)", o->name, name);
		else {
			Unit u;
			/* `4 /s^2` divides by a name: a unit cannot begin with '/' */
			error_at(l, "unknown name '%s' in an initial value%s", name,
			         unit_lookup(name, &u) ? xprintf(" ('%s' is a unit only directly after a number: 4 %s, 4 1/%s)", name, name, name) : "");
		}
		C->failed = 1;
		return rconst(0, l);
	}
	if (map_get(&sema.prop_names, name) || explicit_obj) {
		if (explicit_obj) {
			Var *t = map_get(&sema.temps, temp_key(name, &o, 1));
			if (t) return var_ref(C, t, l, -1);
			error_at(l, "object '%s' has no property '%s'", o->name, name);
		}
		C->failed = 2; /* not applicable to this binding */
		return rconst(0, l);
	}
	/* A temporary of this binding (or, for NAME$n, of object $n). */
	Object **bind = C->bind;
	int nbind = C->key_nbind ? C->key_nbind : C->nbind;
	if (place != 0) {
		bind = xalloc(sizeof *bind);
		bind[0] = o;
		nbind = 1;
	}
	Var *t = find_temp(name, bind, nbind);
	if (!t) {
		for (int i = 0; C->pending && i < C->pending->n; i++) {
			Var *p = C->pending->v[i];
			if (strcmp(p->name, name) == 0 && p->obj == o) t = p;
		}
	}
	if (!t) {
		t = xalloc(sizeof *t);
		t->kind = V_TEMP;
		t->name = (char *)name;
		t->obj = o;
		t->loc = l;
		t->slot = -1;
		t->isvec = map_get(&sema.vector_decls, name) != NULL;
		t->key = temp_key(name, bind, nbind);
		t->pair = nbind > 1;
		t->order = sema.def_counter++;
		vec_push(C->pending, t);
	}
	return var_ref(C, t, l, place);
}

static void type_error(Ctx *C, Loc l, const char *msg)
{
	error_at(l, "%s", msg);
	C->failed = 1;
}

/* A temporary no rule has determined yet takes the type its use asks for. */
static int infer_vector(RExpr *r)
{
	if (r->k != R_VAR || r->var->kind != V_TEMP || determined(r->var) || map_get(&sema.temps, r->var->key)) return 0;
	r->isvec = r->var->isvec = 1;
	return 1;
}

static RExpr *build_method(Ctx *C, Expr *x, RExpr *r, const char *name, Expr **args, int nargs)
{
	Loc l = x->loc;
	if (!r->isvec && !infer_vector(r)) {
		if (!r->isbool) error_at(l, "'.%s' needs a vector, but this is a scalar", name);
		else error_at(l, "'.%s' needs a vector, but this is a condition", name);
		C->failed = 1;
		return rconst(0, l);
	}
	static const struct { const char *n; int op, nargs, argvec, resvec; } m[] = {
		{ "mul", CSF_OP_VMUL, 1, 0, 1 }, { "dot", CSF_OP_VDOT, 1, 1, 0 }, { "cross", CSF_OP_VCROSS, 1, 1, 1 },
		{ "mag", CSF_OP_VMAG, 0, 0, 0 }, { "angle", CSF_OP_VANGLE, 1, 1, 0 }, { "unit", CSF_OP_VUNIT, 0, 0, 1 },
		{ "proj", CSF_OP_VPROJ, 1, 1, 1 },
	};
	for (size_t i = 0; i < sizeof m / sizeof m[0]; i++) {
		if (strcmp(m[i].n, name) != 0) continue;
		if (nargs != m[i].nargs) {
			error_at(l, "'.%s' takes %d argument%s, not %d", name, m[i].nargs, m[i].nargs == 1 ? "" : "s", nargs);
			C->failed = 1;
			return rconst(0, l);
		}
		RExpr *a = nargs ? build(C, args[0]) : NULL;
		if (a && (a->isvec != m[i].argvec || a->isbool)) {
			error_at(args[0]->loc, "the argument of '.%s' must be a %s", name, m[i].argvec ? "vector" : "scalar");
			C->failed = 1;
			return rconst(0, l);
		}
		return rop(m[i].op, m[i].resvec, l, r, a, NULL);
	}
	error_at(l, "unknown vector method '.%s' (known: .mul .dot .cross .mag .angle .unit .proj .x .y .z)", name);
	C->failed = 1;
	return rconst(0, l);
}

static RExpr *build_bin(Ctx *C, Expr *x)
{
	RExpr *a = build(C, x->a), *b = build(C, x->b);
	Loc l = x->loc;
	int op = x->op;
	if (op == AND || op == OR) {
		if (!a->isbool || !b->isbool) return type_error(C, l, "'and' and 'or' combine conditions"), a;
		RExpr *e = rop(op == AND ? CSF_OP_AND : CSF_OP_OR, 0, l, a, b, NULL);
		e->isbool = 1;
		return e;
	}
	if (a->isbool || b->isbool) return type_error(C, l, "a condition cannot be used as a number"), a;
	switch (op) {
	case '<': case '>': case LE: case GE: case EQEQ: case NE: {
		if (a->isvec || b->isvec) return type_error(C, l, "vectors cannot be compared; compare .mag or a component"), a;
		int o = op == '<' ? CSF_OP_LT : op == '>' ? CSF_OP_GT : op == LE ? CSF_OP_LE : op == GE ? CSF_OP_GE
		        : op == EQEQ ? CSF_OP_EQ : CSF_OP_NE;
		RExpr *e = rop(o, 0, l, a, b, NULL);
		e->isbool = 1;
		return e;
	}
	case '+': case '-':
		if (a->isvec && !b->isvec) infer_vector(b);
		if (b->isvec && !a->isvec) infer_vector(a);
		if (a->isvec != b->isvec)
			return type_error(C, l, op == '+' ? "cannot add a vector and a scalar" : "cannot subtract a vector and a scalar"), a;
		return rop(a->isvec ? (op == '+' ? CSF_OP_VADD : CSF_OP_VSUB) : (op == '+' ? CSF_OP_ADD : CSF_OP_SUB), a->isvec, l,
		           a, b, NULL);
	case '*':
		if (a->isvec && b->isvec) return type_error(C, l, "cannot multiply two vectors: use .dot or .cross"), a;
		if (a->isvec) return rop(CSF_OP_VMUL, 1, l, a, b, NULL);
		if (b->isvec) return rop(CSF_OP_VMUL, 1, l, b, a, NULL);
		return rop(CSF_OP_MUL, 0, l, a, b, NULL);
	case '/':
		if (b->isvec) return type_error(C, l, "cannot divide by a vector"), a;
		return rop(a->isvec ? CSF_OP_VDIV : CSF_OP_DIV, a->isvec, l, a, b, NULL);
	case '^':
		if (a->isvec || b->isvec) return type_error(C, l, "'^' needs scalars"), a;
		return rop(CSF_OP_POW, 0, l, a, b, NULL);
	}
	return type_error(C, l, "unknown operator"), a;
}

static RExpr *build_coords(Ctx *C, Expr *x)
{
	RExpr *r[3];
	for (int i = 0; i < 3; i++) {
		r[i] = build(C, x->args[i]);
		if (r[i]->isvec || r[i]->isbool || r[i]->k != R_CONST) {
			type_error(C, x->args[i]->loc, "coordinates must be constant scalars");
			return rvconst((double[3]){ 0, 0, 0 }, x->loc);
		}
	}
	double a = r[0]->c[0], b = r[1]->c[0], c = r[2]->c[0], v[3];
	if (strcmp(x->name, "sph") == 0) { /* r, theta from +z, phi from +x */
		v[0] = a * sin(b) * cos(c);
		v[1] = a * sin(b) * sin(c);
		v[2] = a * cos(b);
	} else if (strcmp(x->name, "cyl") == 0) { /* rho, phi, z */
		v[0] = a * cos(b);
		v[1] = a * sin(b);
		v[2] = c;
	} else {
		v[0] = a;
		v[1] = b;
		v[2] = c;
	}
	RExpr *e = rvconst(v, x->loc);
	dims_coords(x->name, r, e);
	return e;
}

static RExpr *build(Ctx *C, Expr *x)
{
	Loc l = x->loc;
	switch (x->kind) {
	case E_NUM: return rconst(x->num, l);
	case E_NAME: return build_name(C, x, x->name, C->init ? C->self : C->bind[0], 0);
	case E_DOLLAR:
		if (C->init) return type_error(C, l, "'$n' is only meaningful in rules"), rconst(0, l);
		if (x->n >= C->nbind) return type_error(C, l, "no such object in this rule"), rconst(0, l);
		return build_name(C, x, x->name, C->bind[x->n], 0);
	case E_FIELD: {
		if (x->a->kind == E_NAME) {
			Object *o = map_get(&sema.objects_by_name, x->a->name);
			if (o && !(C->bind && prop_of(C->bind[0], x->a->name)) && !map_get(&sema.globals_by_name, x->a->name))
				return build_name(C, x, x->name, o, 1);
		}
		RExpr *r = build(C, x->a);
		const char *n = x->name;
		if ((n[0] == 'x' || n[0] == 'y' || n[0] == 'z') && n[1] == '\0') {
			if (!r->isvec) return type_error(C, l, "a component (.x .y .z) needs a vector"), rconst(0, l);
			if (r->k == R_CONST) {
				RExpr *k = rconst(r->c[n[0] - 'x'], l);
				k->dimk = r->dimk;
				memcpy(k->dim, r->dim, sizeof k->dim);
				return k;
			}
			RExpr *e = rnew(R_COMP, l);
			e->a[0] = r;
			e->n = 1;
			e->comp = n[0] - 'x';
			return e;
		}
		return build_method(C, x, r, n, NULL, 0);
	}
	case E_METHOD: return build_method(C, x, build(C, x->a), x->name, x->args, x->nargs);
	case E_CALL: {
		if (!strcmp(x->name, "sph") || !strcmp(x->name, "cyl") || !strcmp(x->name, "cart")) {
			if (!C->init) return type_error(C, l, "local coordinates (sph, cyl, cart) are only for initial values"), rconst(0, l);
			if (x->nargs != 3) return type_error(C, l, "local coordinates take 3 values"), rconst(0, l);
			return build_coords(C, x);
		}
		int nargs, op = opcode_of_func(x->name, &nargs);
		if (op < 0) return type_error(C, l, xprintf("unknown function '%s'", x->name)), rconst(0, l);
		if (x->nargs != nargs)
			return type_error(C, l, xprintf("'%s' takes %d argument%s, not %d", x->name, nargs, nargs == 1 ? "" : "s", x->nargs)),
			       rconst(0, l);
		RExpr *a[2] = { NULL, NULL };
		for (int i = 0; i < nargs; i++) {
			a[i] = build(C, x->args[i]);
			if (a[i]->isvec || a[i]->isbool)
				return type_error(C, x->args[i]->loc, xprintf("'%s' needs a scalar argument", x->name)), rconst(0, l);
		}
		return rop(op, 0, l, a[0], a[1], NULL);
	}
	case E_VEC: {
		RExpr *c[3];
		for (int i = 0; i < 3; i++) {
			c[i] = build(C, x->args[i]);
			if (c[i]->isvec || c[i]->isbool)
				return type_error(C, x->args[i]->loc, "a vector's components must be scalars"), rconst(0, l);
		}
		return rop(CSF_OP_VPACK, 1, l, c[0], c[1], c[2]);
	}
	case E_UNIT: {
		RExpr *a = build(C, x->a);
		if (a->isbool) return type_error(C, l, "a unit cannot follow a condition"), a;
		double ud[CSF_NDIM];
		for (int i = 0; i < CSF_NDIM; i++) ud[i] = x->unit.dim[i];
		RExpr *f = rconst(dims_to_system(x->unit.factor, ud), l);
		f->dimk = DK_KNOWN;
		memcpy(f->dim, ud, sizeof ud);
		return rop(a->isvec ? CSF_OP_VMUL : CSF_OP_MUL, a->isvec, l, a, f, NULL);
	}
	case E_BIN: return build_bin(C, x);
	case E_NEG: {
		RExpr *a = build(C, x->a);
		if (a->isbool) return type_error(C, l, "cannot negate a condition: use 'not'"), a;
		return rop(a->isvec ? CSF_OP_VNEG : CSF_OP_NEG, a->isvec, l, a, NULL, NULL);
	}
	case E_NOT: {
		RExpr *a = build(C, x->a);
		if (!a->isbool) return type_error(C, l, "'not' needs a condition"), a;
		RExpr *e = rop(CSF_OP_NOT, 0, l, a, NULL, NULL);
		e->isbool = 1;
		return e;
	}
	}
	return rconst(0, l);
}

/* ---- objects, kinds, globals ---- */

static int check_name(const char *n, Loc l, const char *what)
{
	if (is_predefined(n)) {
		error_at(l, "'%s' is predefined and cannot name %s", n, what);
		return 0;
	}
	return 1;
}

static Var *new_global(const char *name, int isvec, const double *v, Loc l)
{
	Var *g = xalloc(sizeof *g);
	g->kind = V_GLOBAL;
	g->name = (char *)name;
	g->isvec = isvec;
	memcpy(g->init, v, sizeof g->init);
	g->loc = l;
	g->slot = -1;
	g->order = sema.def_counter++;
	vec_push(&sema.M->globals, g);
	map_put(&sema.globals_by_name, g->name, g);
	return g;
}

static void set_dim(Var *v, int k, const double *d)
{
	v->dimk = k;
	if (k == DK_KNOWN) memcpy(v->dim, d, sizeof v->dim);
}

/* A predefined constant: its SI value, converted to the unit system in use. */
static void predefine_const(const char *name, int isvec, const double *si, double dl, double dm, double dt)
{
	Loc none = { 0, 0, 0 };
	double d[CSF_NDIM] = { dl, dm, dt, 0 }, v[3];
	for (int i = 0; i < 3; i++) v[i] = dims_to_system(si[i], d);
	set_dim(new_global(name, isvec, v, none), DK_KNOWN, d);
}

static void predefine(void)
{
	sema.M->time = xalloc(sizeof *sema.M->time);
	sema.M->time->kind = V_TIME;
	sema.M->time->name = "t";
	sema.M->time->slot = -1;
	set_dim(sema.M->time, DK_KNOWN, (double[CSF_NDIM]){ 0, 0, 1, 0 });
	predefine_const("g", 1, (double[3]){ 0, 0, -GSL_CONST_MKSA_GRAV_ACCEL }, 1, 0, -2);
	predefine_const("G", 0, (double[3]){ GSL_CONST_MKSA_GRAVITATIONAL_CONSTANT, 0, 0 }, 3, -1, -2);
	predefine_const("c", 0, (double[3]){ GSL_CONST_MKSA_SPEED_OF_LIGHT, 0, 0 }, 1, 0, -1);
	predefine_const("e", 0, (double[3]){ M_E, 0, 0 }, 0, 0, 0);
	predefine_const("pi", 0, (double[3]){ M_PI, 0, 0 }, 0, 0, 0);
}

/*
 * The constant value of x, the value of obj.name (obj NULL: the global
 * name; fold FIX_RUN: the run's name) defined on line. The values it reads
 * are folded into it, so -D cannot set them (Var.fix); *read, if not NULL,
 * gets the first one it read (NULL: none, it is a literal).
 */
static RExpr *const_value(Expr *x, Object *obj, const char *name, int fold, int line, int *ok, Var **read)
{
	Ctx C = { 0 };
	C.init = 1;
	C.self = obj;
	C.fold = fold;
	C.fold_obj = obj ? obj->name : NULL;
	C.fold_name = name;
	C.fold_line = line;
	RExpr *r = build(&C, x);
	if (read) *read = C.first_read;
	*ok = !C.failed;
	if (*ok && (r->k != R_CONST || r->isbool)) {
		error_at(x->loc, r->isbool ? "a value cannot be a condition" : "this value is not known at compile time");
		*ok = 0;
	}
	return r;
}

static Object *get_object(const char *name, Loc l)
{
	Object *o = map_get(&sema.objects_by_name, name);
	if (o) return o;
	if (!check_name(name, l, "an object")) return NULL;
	if (map_get(&sema.globals_by_name, name)) {
		error_at(l, "'%s' is a global and cannot name an object", name);
		return NULL;
	}
	o = xalloc(sizeof *o);
	o->name = (char *)name;
	o->loc = l;
	o->index = sema.M->objects.n;
	vec_push(&sema.M->objects, o);
	map_put(&sema.objects_by_name, o->name, o);
	return o;
}

/* v's value, defined on line, is computed from read's (if not NULL): -D cannot set it. */
static void fix_derived(Var *v, Var *read, int line)
{
	if (!read || v->fix == FIX_FOLDED) {
		if (!read && v->fix == FIX_DERIVED) v->fix = FIX_NONE;
		return;
	}
	v->fix = FIX_DERIVED;
	v->fix_obj = read->obj ? read->obj->name : NULL;
	v->fix_name = read->name;
	v->fix_line = line;
}

/* May constant r replace the value of v (a kind's default, a predefined constant)? Same type, same dimension. */
static int override_ok(Loc l, const char *what, Var *v, RExpr *r)
{
	if (v->isvec != r->isvec) {
		error_at(l, "%s is a %s; it cannot take a %s", what, v->isvec ? "vector" : "scalar", r->isvec ? "vector" : "scalar");
		return 0;
	}
	if (r->dimk == DK_KNOWN && v->dimk == DK_KNOWN && memcmp(r->dim, v->dim, sizeof v->dim) != 0) {
		error_at(l, "%s is %s; this value is %s", what, dims_describe(v->dim), dims_operand(r, r->dim));
		return 0;
	}
	return 1;
}

/* Property p of o takes the absolute tolerance `atol A` of statement s, if it has one: a positive
 * scalar constant (its dimension is checked against p's by check_atols). */
static void set_atol(Object *o, Var *p, Stmt *s)
{
	if (!s->atol) return;
	int ok;
	RExpr *r = const_value(s->atol, o, s->prop, FIX_NONE, s->prop_loc.line, &ok, NULL);
	if (!ok) return;
	if (r->isvec || !(r->c[0] > 0) || !isfinite(r->c[0])) {
		error_at(s->atol->loc, "the atol of '%s' must be a positive number%s", s->prop,
		         r->isvec ? " (one for every component)" : "");
		return;
	}
	p->atol = r;
}

/* Defines or overrides property p of o from a property statement. */
static void set_prop(Object *o, Stmt *s, int from_kind)
{
	if (!check_name(s->prop, s->prop_loc, "a property")) return;
	if (map_get(&sema.globals_by_name, s->prop)) {
		error_at(s->prop_loc, "'%s' is a global constant; a property cannot have the same name", s->prop);
		return;
	}
	int ok;
	Var *read;
	/* the value's expression is folded to a constant and then not needed: one object's
	   values take no memory from the next's */
	ArenaMark mark = arena_mark();
	RExpr rv = *const_value(s->value, o, s->prop, FIX_FOLDED, s->prop_loc.line, &ok, &read), *r = &rv;
	arena_release(mark);
	if (!ok) return;
	if (s->isvec && !r->isvec) {
		error_at(s->value->loc, "property '%s' is declared a vector but its value is a scalar", s->prop);
		return;
	}
	Var *p = prop_of(o, s->prop);
	if (p) {
		if (!p->from_kind) {
			error_at(s->prop_loc, "property '%s' of object '%s' is already defined", s->prop, o->name);
			note_at(p->loc, "defined here");
			return;
		}
		if (!override_ok(s->value->loc, xprintf("property '%s'", s->prop), p, r)) return;
		memcpy(p->init, r->c, sizeof p->init);
		p->loc = s->prop_loc;
		p->from_kind = from_kind;
		fix_derived(p, read, s->prop_loc.line);
		if (r->dimk == DK_KNOWN) set_dim(p, DK_KNOWN, r->dim);
		set_atol(o, p, s);
		return;
	}
	p = xalloc(sizeof *p);
	p->kind = V_PROP;
	p->name = s->prop;
	p->obj = o;
	p->isvec = r->isvec;
	memcpy(p->init, r->c, sizeof p->init);
	p->loc = s->prop_loc;
	p->slot = -1;
	p->order = sema.def_counter++;
	p->from_kind = from_kind;
	fix_derived(p, read, s->prop_loc.line);
	if (r->dimk == DK_KNOWN) set_dim(p, DK_KNOWN, r->dim);
	set_atol(o, p, s);
	vec_push(&o->props, p);
	map_put(&o->props_by_name, p->name, p);
	map_put(&sema.prop_names, p->name, p);
}

static void build_objects(Stmt *stmts)
{
	for (Stmt *s = stmts; s; s = s->next) {
		switch (s->kind) {
		case S_GLOBAL: {
			if (!check_name(s->name, s->name_loc, "a global")) break;
			int ok;
			Var *read;
			RExpr *r = const_value(s->value, NULL, s->name, FIX_FOLDED, s->name_loc.line, &ok, &read);
			if (!ok) break;
			Var *g = map_get(&sema.globals_by_name, s->name);
			if (g) {
				if (!override_ok(s->value->loc, xprintf("'%s'", s->name), g, r)) break;
				memcpy(g->init, r->c, sizeof g->init);
				g->loc = s->name_loc;
				fix_derived(g, read, s->name_loc.line);
			} else if (map_get(&sema.objects_by_name, s->name) || map_get(&sema.prop_names, s->name)) {
				error_at(s->name_loc, "'%s' already names an object or a property", s->name);
			} else {
				Var *ng = new_global(s->name, r->isvec, r->c, s->name_loc);
				fix_derived(ng, read, s->name_loc.line);
				set_dim(ng, r->dimk == DK_KNOWN ? DK_KNOWN : DK_UNKNOWN, r->dim);
			}
			break;
		}
		case S_DEF:
			if (map_get(&sema.kinds, s->name)) {
				error_at(s->name_loc, "kind '%s' is already defined", s->name);
				break;
			}
			map_put(&sema.kinds, s->name, s);
			break;
		case S_OBJKIND: {
			Stmt *k = map_get(&sema.kinds, s->prop);
			if (!k) {
				error_at(s->prop_loc, "unknown kind '%s'", s->prop);
				break;
			}
			Object *o = get_object(s->name, s->name_loc);
			if (!o) break;
			for (Stmt *p = k->body; p; p = p->next)
				if (!prop_of(o, p->prop)) set_prop(o, p, 1);
			break;
		}
		case S_PROP: {
			Object *o = get_object(s->name, s->name_loc);
			if (o) set_prop(o, s, 0);
			break;
		}
		default:
			break;
		}
	}
}

/* ---- the expressions of a statement ---- */

/* A function of one expression (NULL for none) and a context; 0 stops a walk. */
typedef int (*ExprFn)(Expr *x, void *ctx);

/* Calls f on both sides of each equation of steps q and on the condition of each block, at every
 * depth. Returns 0 as soon as f does, else 1. */
static int eqns_each(Eqn *q, ExprFn f, void *ctx)
{
	for (; q; q = q->next) {
		if (q->nest) {
			if (!f(q->nest->cond, ctx) || !eqns_each(q->nest->then, f, ctx) || !eqns_each(q->nest->els, f, ctx)) return 0;
		} else if (!f(q->lhs, ctx) || !f(q->rhs, ctx)) {
			return 0;
		}
	}
	return 1;
}

/* Calls f on every expression of statement s: its condition, its call, its steps'. As eqns_each. */
static int stmt_each(Stmt *s, ExprFn f, void *ctx)
{
	return f(s->cond, ctx) && f(s->call, ctx) && eqns_each(s->eqns, f, ctx);
}

/* ---- shapes ---- */

/* Marks in named (a Map) the objects expression x names (NAME.PROP). Returns 1. */
static int mark_named(Expr *x, void *named)
{
	if (!x) return 1;
	if (x->kind == E_FIELD && x->a->kind == E_NAME) {
		Object *o = map_get(&sema.objects_by_name, x->a->name);
		if (o) map_put(named, o->name, o);
	}
	mark_named(x->a, named);
	mark_named(x->b, named);
	for (int i = 0; i < x->nargs; i++) mark_named(x->args[i], named);
	return 1;
}

/*
 * Groups the objects into shapes: by the names, types and dimensions of
 * their properties, in order (what decides which rules apply to an object
 * and how each resolves). By object (not shaped), or when a rule, a `for`
 * list or the watch list names the object and one of its temporaries, an
 * object is a shape of its own.
 */
static void build_shapes(Stmt *start)
{
	Map named = { 0 }, by_sig = { 0 };
	for (int i = 0; i < sema.M->stmts.n; i++) { /* the rules and assertions */
		Stmt *s = sema.M->stmts.v[i];
		stmt_each(s, mark_named, &named);
		for (int i = 0; i < s->fors.n; i++) {
			ObjRef *r = s->fors.v[i];
			Object *o = r->name ? map_get(&sema.objects_by_name, r->name)
			                    : (r->index < sema.M->objects.n ? sema.M->objects.v[r->index] : NULL);
			if (o) map_put(&named, o->name, o);
		}
	}
	for (int i = 0; start && i < start->watch.n; i++) {
		WatchItem *w = start->watch.v[i];
		Object *o = w->obj ? map_get(&sema.objects_by_name, w->obj) : NULL;
		if (o && !prop_of(o, w->prop)) map_put(&named, o->name, o);
	}
	for (int i = 0; i < sema.M->objects.n; i++) {
		Object *o = sema.M->objects.v[i];
		char *sig = NULL;
		ArenaMark mark = arena_mark();
		if (sema.shaped && !map_get(&named, o->name)) {
			/* each property: its name, then type, dimension kind and dimension as hex digits */
			size_t len = 0;
			for (int j = 0; j < o->props.n; j++) len += strlen(((Var *)o->props.v[j])->name) + 1 + 2 * (2 + CSF_NDIM * 8);
			char *at = sig = xalloc(len + 1);
			for (int j = 0; j < o->props.n; j++) {
				Var *v = o->props.v[j];
				unsigned char bits[2 + CSF_NDIM * 8] = { (unsigned char)v->isvec, (unsigned char)v->dimk };
				memcpy(bits + 2, v->dim, sizeof v->dim);
				size_t n = strlen(v->name);
				memcpy(at, v->name, n);
				at += n;
				*at++ = ':';
				for (size_t k = 0; k < sizeof bits; k++) {
					*at++ = "0123456789abcdef"[bits[k] >> 4];
					*at++ = "0123456789abcdef"[bits[k] & 15];
				}
			}
		}
		Shape *S = sig ? map_get(&by_sig, sig) : NULL;
		if (S) arena_release(mark); /* the signature of a known shape is not kept */
		if (!S) {
			S = xalloc(sizeof *S);
			S->index = sema.M->shapes.n;
			vec_push(&sema.M->shapes, S);
			if (sig) map_put(&by_sig, sig, S);
		}
		o->shape = S;
		o->sidx = S->n++;
	}
	for (int i = 0; i < sema.M->shapes.n; i++) ((Shape *)sema.M->shapes.v[i])->members = NULL;
	int *fill = xalloc((size_t)sema.M->shapes.n * sizeof *fill);
	for (int i = 0; i < sema.M->objects.n; i++) {
		Object *o = sema.M->objects.v[i];
		if (!o->shape->members) o->shape->members = xalloc((size_t)o->shape->n * sizeof(Object *));
		o->shape->members[fill[o->shape->index]++] = o;
	}
}

/* ---- rule instances ---- */

static int max_dollar(Expr *x)
{
	if (!x) return 0;
	int m = x->kind == E_DOLLAR ? x->n : 0;
	int a = max_dollar(x->a), b = max_dollar(x->b);
	if (a > m) m = a;
	if (b > m) m = b;
	for (int i = 0; i < x->nargs; i++) {
		int c = max_dollar(x->args[i]);
		if (c > m) m = c;
	}
	return m;
}

static int reads_rf(Expr *x)
{
	if (!x) return 0;
	if (x->kind == E_NAME && strcmp(x->name, "RF") == 0) return 1;
	if (reads_rf(x->a) || reads_rf(x->b)) return 1;
	for (int i = 0; i < x->nargs; i++)
		if (reads_rf(x->args[i])) return 1;
	return 0;
}

/* Raises *(int *)most to x's highest $n. Returns 1. */
static int raise_dollar(Expr *x, void *most)
{
	int k = max_dollar(x);
	if (k > *(int *)most) *(int *)most = k;
	return 1;
}

static int stmt_max_dollar(Stmt *s)
{
	int m = 0;
	stmt_each(s, raise_dollar, &m);
	return m;
}

static int no_rf(Expr *x, void *ctx)
{
	(void)ctx;
	return !reads_rf(x);
}

static int stmt_reads_rf(Stmt *s) { return !stmt_each(s, no_rf, NULL); }

/* Does every name the statement reads exist for this binding? (Without reporting.) Each name is
 * checked on one object of the binding; a NULL in bind passes every name checked on it. */
static int names_apply(Expr *x, Object **bind, int nbind, const char **missing)
{
	if (!x) return 1;
	if (x->kind == E_NAME || x->kind == E_DOLLAR) {
		Object *o = x->kind == E_DOLLAR ? (x->n < nbind ? bind[x->n] : NULL) : bind[0];
		if (!o) return 1;
		if (x->kind == E_NAME && (is_predefined(x->name) || map_get(&sema.globals_by_name, x->name))) return 1;
		if (map_get(&sema.prop_names, x->name) && !prop_of(o, x->name)) {
			*missing = x->name;
			return 0;
		}
		return 1;
	}
	if (x->kind == E_FIELD && x->a->kind == E_NAME && map_get(&sema.objects_by_name, x->a->name) &&
	    (!bind[0] || !prop_of(bind[0], x->a->name)))
		return 1;
	if (!names_apply(x->a, bind, nbind, missing) || !names_apply(x->b, bind, nbind, missing)) return 0;
	for (int i = 0; i < x->nargs; i++)
		if (!names_apply(x->args[i], bind, nbind, missing)) return 0;
	return 1;
}

typedef struct Applies { Object **bind; int nbind; const char **missing; } Applies;

static int applies(Expr *x, void *ctx)
{
	Applies *a = ctx;
	return names_apply(x, a->bind, a->nbind, a->missing);
}

static int stmt_applies(Stmt *s, Object **bind, int nbind, const char **missing)
{
	Applies a = { bind, nbind, missing };
	return stmt_each(s, applies, &a);
}

/* The bindings of a rule: $0 any object, $1..$k other objects in ascending order (spec 2.2.1).
 * stmt_applies is a conjunction of conditions each on one place of the tuple, so only the
 * objects fit for each place are tried, and every tuple of them applies. */
typedef struct Tuples {
	Stmt *s;
	void (*f)(Stmt *, Object **, int);
	int k;
	int **fit;     /* [0..k]: the indices of the objects fit for $j, ascending */
	int *nfit;     /* [0..k]: how many */
	Object **cur;  /* the tuple being built */
	int count;     /* how many tuples f was called for */
	int failed;    /* f reported an error */
} Tuples;

/* The position of the first value greater than x in the ascending array v[0..n). */
static int first_greater(const int *v, int n, int x)
{
	int lo = 0, hi = n;
	while (lo < hi) {
		int mid = lo + (hi - lo) / 2;
		if (v[mid] > x) hi = mid;
		else lo = mid + 1;
	}
	return lo;
}

/* Binds $j..$k in ascending order to objects of index greater than `after`, then calls f. */
static void bind_from(Tuples *T, int j, int after)
{
	if (j > T->k) {
		Object **bind = xalloc((size_t)(T->k + 1) * sizeof *bind);
		memcpy(bind, T->cur, (size_t)(T->k + 1) * sizeof *bind);
		int before = diag_errors;
		T->f(T->s, bind, T->k + 1);
		T->count++;
		T->failed = diag_errors > before; /* one report per statement, not per object */
		return;
	}
	for (int i = first_greater(T->fit[j], T->nfit[j], after); i < T->nfit[j] && !T->failed; i++) {
		if (T->fit[j][i] == T->cur[0]->index) continue;
		T->cur[j] = sema.M->objects.v[T->fit[j][i]];
		/* by shape: $1 is another shape's representative, or the second member of $0's */
		if (sema.shaped && T->cur[j]->sidx == 1 && T->cur[j]->shape != T->cur[0]->shape) continue;
		bind_from(T, j + 1, T->fit[j][i]);
	}
}

/* An upper bound of the tuples bind_from makes (exact but for $0's exclusion from $1..$k): the objects
 * fit for $0 times the ascending chains through the lists fit for $1..$k, counted from the last list
 * back with suffix sums, in O(k n log n). */
static double count_tuples(const Tuples *T)
{
	if (T->k == 0) return T->nfit[0];
	int nobj = sema.M->objects.n;
	double *next = xalloc(((size_t)nobj + 1) * sizeof *next), *cur = xalloc(((size_t)nobj + 1) * sizeof *cur);
	for (int i = T->nfit[T->k]; i >= 0; i--) next[i] = T->nfit[T->k] - i; /* suffix sums of ones */
	for (int j = T->k - 1; j >= 1; j--) {
		cur[T->nfit[j]] = 0;
		for (int i = T->nfit[j] - 1; i >= 0; i--)
			cur[i] = cur[i + 1] + next[first_greater(T->fit[j + 1], T->nfit[j + 1], T->fit[j][i])];
		double *x = next;
		next = cur;
		cur = x;
	}
	return (double)T->nfit[0] * next[0];
}

/* Calls f for every binding the statement applies to; returns how many, -1 after an error. */
static int for_each_binding(Stmt *s, void (*f)(Stmt *, Object **, int))
{
	int k = stmt_max_dollar(s);
	int nobj = sema.M->objects.n;
	const char *missing = NULL;
	if (s->has_for) {
		int n = s->fors.n;
		Object **bind = xalloc((size_t)n * sizeof *bind);
		for (int i = 0; i < n; i++) {
			ObjRef *r = s->fors.v[i];
			Object *o = r->name ? map_get(&sema.objects_by_name, r->name)
			                    : (r->index < nobj ? sema.M->objects.v[r->index] : NULL);
			if (!o) {
				if (r->name) error_at(r->loc, "unknown object '%s'", r->name);
				else error_at(r->loc, "there is no object number %d (objects are numbered from 0)", r->index);
				return -1;
			}
			for (int j = 0; j < i; j++)
				if (bind[j] == o) {
					error_at(r->loc, "object '%s' is named twice in 'for'", o->name);
					return -1;
				}
			bind[i] = o;
		}
		if (k >= n) {
			error_at(s->loc, "the rule reads $%d but 'for' names only %d object%s", k, n, n == 1 ? "" : "s");
			return -1;
		}
		if (!stmt_applies(s, bind, n, &missing)) {
			error_at(s->loc, "this rule reads '%s', which object '%s' does not have", missing, bind[0]->name);
			return -1;
		}
		f(s, bind, n);
		return 1;
	}
	Tuples T = { s, f, k, xalloc((size_t)(k + 1) * sizeof(int *)), xalloc((size_t)(k + 1) * sizeof(int)),
		     xalloc((size_t)(k + 1) * sizeof(Object *)), 0, 0 };
	if (sema.shaped && k > 1) unshape("a rule over $1..$k, k > 1");
	for (int j = 0; j <= k && k < nobj; j++) { /* a tuple has k + 1 different objects */
		T.fit[j] = xalloc((size_t)nobj * sizeof(int));
		for (int i = 0; i < nobj; i++) {
			/* by shape: the representatives, and for $1 the second members */
			if (sema.shaped && ((Object *)sema.M->objects.v[i])->sidx > (j ? 1 : 0)) continue;
			T.cur[j] = sema.M->objects.v[i];
			if (stmt_applies(s, T.cur, k + 1, &missing)) T.fit[j][T.nfit[j]++] = i;
			T.cur[j] = NULL;
		}
	}
	double n = count_tuples(&T);
	long most = opts.max_tuples > 0 ? opts.max_tuples : CSF_MAX_TUPLES;
	if (n > (double)most) {
		error_at(s->loc, "this %s applies to %.3g tuples of objects ($0..$%d), more than the %ld that one rule may "
		         "have: name the objects with 'for', or write fewer objects", s->kind == S_ASSERT ? "assertion" : "rule",
		         n, k, most);
		return -1;
	}
	for (int i = 0; i < T.nfit[0] && !T.failed; i++) {
		T.cur[0] = sema.M->objects.v[T.fit[0][i]];
		bind_from(&T, 1, -1);
	}
	if (T.failed) return -1;
	if (T.count == 0 && !s->call) { /* contact rules: a scene may have no pair that can touch */
		/* the name to report is the one the last tuple lacks: ($0, $1, ..., $k) = (last, last - k, ..., last - 1) */
		missing = NULL;
		if (k < nobj) {
			T.cur[0] = sema.M->objects.v[nobj - 1];
			for (int j = 1; j <= k; j++) T.cur[j] = sema.M->objects.v[nobj - 1 - k + j - 1];
			stmt_applies(s, T.cur, k + 1, &missing);
		}
		const char *what = s->kind == S_ASSERT ? "assertion" : s->kind == S_STOP ? "stop condition" : "rule";
		if (missing) error_at(s->loc, "this %s applies to no object: none has '%s'", what, missing);
		else error_at(s->loc, "this %s applies to no object", what);
		return -1;
	}
	return T.count;
}

static int add_src(Loc l, char *text)
{
	SrcEntry *e = xalloc(sizeof *e);
	e->loc = l;
	e->text = text;
	vec_push(&sema.M->srcs, e);
	return sema.M->srcs.n - 1;
}

static Inst *new_inst(Stmt *s, Object **bind, int nbind)
{
	Inst *I = xalloc(sizeof *I);
	I->st = s;
	I->bind = bind;
	I->nbind = nbind;
	I->assert_index = -1;
	I->isF = s->attr && strcmp(s->attr, "F") == 0;
	return I;
}

static const char *var_label(Var *v)
{
	if (!v->obj) return v->name;
	return xprintf("%s.%s", v->obj->name, v->name);
}

static int determined(Var *v)
{
	v = sema_canon(v);
	return v->kind == V_TIME || v->state || v->det != NULL;
}

Var *sema_canon(Var *v)
{
	if (!v || v->kind != V_PROP || !v->obj->shape || v->obj->sidx == 0) return v;
	Var *r = prop_of(v->obj->shape->members[0], v->name);
	return r ? r : v;
}

int sema_per_member(const Var *v)
{
	return v->obj && v->obj->shape && v->obj->shape->n > 1 && (v->kind == V_PROP || (v->kind == V_TEMP && !v->pair));
}

/* The places ($n) at which e reads x, as bits 1 << (place + 1). */
static unsigned var_places(const RExpr *e, const Var *x)
{
	if (!e) return 0;
	if (e->k == R_VAR) return e->var == x ? 1u << (e->place + 1) : 0;
	unsigned m = 0;
	for (int i = 0; i < 3; i++) m |= var_places(e->a[i], x);
	return m;
}

static void explain_det(Var *v)
{
	if (v->kind == V_TIME) return;
	if (v->state) {
		Inst *d = v->deriv;
		note_at(d->st->loc, "%s is a state variable, integrated by this rule", var_label(v));
	} else if (v->det) {
		note_at(v->det->st->loc, "%s is determined by this rule", var_label(v));
	}
}

/* ---- solving ---- */

/* e = a*x + b, where x is the target; a is a scalar (NULL: 0), b of e's type (NULL: 0). */
typedef struct Lin { RExpr *a, *b; int ok; } Lin;

static int contains(RExpr *e, Var *x)
{
	if (e->k == R_VAR) return e->var == x;
	for (int i = 0; i < e->n; i++)
		if (contains(e->a[i], x)) return 1;
	return 0;
}

static RExpr *sadd(RExpr *p, RExpr *q, int sub, Loc l)
{
	if (!q) return p;
	if (!p) return sub ? rop(q->isvec ? CSF_OP_VNEG : CSF_OP_NEG, q->isvec, l, q, NULL, NULL) : q;
	return rop(p->isvec ? (sub ? CSF_OP_VSUB : CSF_OP_VADD) : (sub ? CSF_OP_SUB : CSF_OP_ADD), p->isvec, l, p, q, NULL);
}

static RExpr *smul(RExpr *p, RExpr *s, Loc l) /* p * scalar s */
{
	if (!p) return NULL;
	if (is_const(s, 1)) return p;
	if (!p->isvec && is_const(p, 1)) return s;
	return rop(p->isvec ? CSF_OP_VMUL : CSF_OP_MUL, p->isvec, l, p, s, NULL);
}

static RExpr *sdiv(RExpr *p, RExpr *s, Loc l)
{
	if (!p) return NULL;
	if (is_const(s, 1)) return p;
	return rop(p->isvec ? CSF_OP_VDIV : CSF_OP_DIV, p->isvec, l, p, s, NULL);
}

static Lin lin(RExpr *e, Var *x)
{
	Lin r = { NULL, NULL, 1 };
	if (!contains(e, x)) {
		r.b = e;
		return r;
	}
	if (e->k == R_VAR) {
		r.a = rconst(1, e->loc);
		return r;
	}
	if (e->k != R_OP) {
		r.ok = 0;
		return r;
	}
	Lin p = lin(e->a[0], x), q = e->n > 1 ? lin(e->a[1], x) : (Lin){ NULL, NULL, 1 };
	if (!p.ok || !q.ok) return (Lin){ NULL, NULL, 0 };
	Loc l = e->loc;
	switch (e->op) {
	case CSF_OP_ADD: case CSF_OP_VADD: case CSF_OP_SUB: case CSF_OP_VSUB: {
		int sub = e->op == CSF_OP_SUB || e->op == CSF_OP_VSUB;
		r.a = p.a && q.a ? sadd(p.a, q.a, sub, l) : p.a ? p.a : q.a ? sadd(NULL, q.a, sub, l) : NULL;
		r.b = sadd(p.b, q.b, sub, l);
		return r;
	}
	case CSF_OP_NEG: case CSF_OP_VNEG:
		r.a = p.a ? sadd(NULL, p.a, 1, l) : NULL;
		r.b = p.b ? sadd(NULL, p.b, 1, l) : NULL;
		return r;
	case CSF_OP_MUL: case CSF_OP_VMUL:
		if (p.a && !q.a) {
			r.a = smul(p.a, e->a[1], l);
			r.b = smul(p.b, e->a[1], l);
			return r;
		}
		if (q.a && !p.a && e->op == CSF_OP_MUL) {
			r.a = smul(q.a, e->a[0], l);
			r.b = smul(q.b, e->a[0], l);
			return r;
		}
		break;
	case CSF_OP_DIV: case CSF_OP_VDIV:
		if (p.a && !q.a) {
			r.a = sdiv(p.a, e->a[1], l);
			r.b = sdiv(p.b, e->a[1], l);
			return r;
		}
		break;
	}
	return (Lin){ NULL, NULL, 0 };
}

/* Solves lhs = rhs for x. Returns NULL (after an error) when it cannot. */
static RExpr *solve(RExpr *lhs, RExpr *rhs, Var *x, Loc l, const char *text)
{
	int inl = contains(lhs, x), inr = contains(rhs, x);
	if (lhs->k == R_VAR && lhs->var == x && !inr) return rhs;
	if (rhs->k == R_VAR && rhs->var == x && !inl) return lhs;
	Lin p = lin(lhs, x), q = lin(rhs, x);
	if (!p.ok || !q.ok) {
		error_at(l, "cannot solve \"%s\" for %s: it is not linear in %s", text, var_label(x), x->name);
		return NULL;
	}
	/* p.a x + p.b = q.a x + q.b  =>  x = (q.b - p.b) / (p.a - q.a); one side without x keeps its form */
	RExpr *num, *den;
	if (!inl) {
		num = q.b ? sadd(lhs, q.b, 1, l) : lhs;
		den = q.a;
	} else if (!inr) {
		num = p.b ? sadd(rhs, p.b, 1, l) : rhs;
		den = p.a;
	} else {
		den = sadd(p.a, q.a, 1, l);
		num = q.b && p.b ? sadd(q.b, p.b, 1, l) : q.b ? q.b : p.b ? sadd(NULL, p.b, 1, l) : NULL;
	}
	if (!den || is_const(den, 0)) {
		error_at(l, "cannot solve \"%s\" for %s: %s cancels out", text, var_label(x), x->name);
		return NULL;
	}
	if (!num) num = x->isvec ? rvconst((double[3]){ 0, 0, 0 }, l) : rconst(0, l);
	if (is_const(den, -1)) return sadd(NULL, num, 1, l);
	return sdiv(num, den, l);
}

/* ---- resolving one rule instance ---- */

static int var_class(Var *v)
{
	switch (v->kind) {
	case V_TEMP:
		if (map_get(&sema.watched, v->name) || (v->obj && map_get(&sema.watched, xprintf("%s\x01%s", v->obj->name, v->name))))
			return 2; /* a watched temporary ranks with the watched variables */
		return 1;
	case V_PROP: return 2;
	case V_GLOBAL: return 3;
	default: return 9;
	}
}

static const char *class_name(Var *v)
{
	switch (v->kind) {
	case V_TEMP: return var_class(v) == 1 ? "unwatched temporary" : "watched temporary";
	case V_PROP: return "watched variable";
	case V_GLOBAL: return "global";
	default: return "time";
	}
}

static void register_temp(Var *t)
{
	if (map_get(&sema.temps, t->key)) return;
	if (!check_name(t->name, t->loc, "a temporary")) return;
	map_put(&sema.temps, t->key, t);
	vec_push(&sema.M->temps, t);
}

/* What instance I may have meant by u, a temporary no rule determines: a property of its objects
 * or a global within a few edits of its name (a misspelling), or another object's temporary of that
 * name (OBJECT.NAME); NULL if nothing is close. */
static const char *near_name(Inst *I, Var *u)
{
	Vec c = { 0 };
	for (int b = 0; b < I->nbind; b++)
		for (int j = 0; j < I->bind[b]->props.n; j++) vec_push(&c, ((Var *)I->bind[b]->props.v[j])->name);
	for (int j = 0; j < sema.M->globals.n; j++) vec_push(&c, ((Var *)sema.M->globals.v[j])->name);
	const char *s = csf_suggest_name(u->name, (const char *const *)c.v, c.n);
	for (int j = 0; !s && j < sema.M->temps.n; j++) {
		Var *t = sema.M->temps.v[j];
		if (t != u && !t->pair && t->obj && t->obj != u->obj && !strcmp(t->name, u->name) && determined(t))
			s = xprintf("%s.%s", t->obj->name, t->name);
	}
	return s;
}

/* Where expression e first reads u, or NULL. */
static RExpr *find_read(RExpr *e, Var *u)
{
	if (!e) return NULL;
	if (e->k == R_VAR) return e->var == u ? e : NULL;
	for (int i = 0; i < e->n; i++) {
		RExpr *r = find_read(e->a[i], u);
		if (r) return r;
	}
	return NULL;
}

/* The place of u in an equation of sides lhs and rhs (at), as a diagnostic points at it. */
static Loc read_loc(RExpr *lhs, RExpr *rhs, Var *u, Loc at)
{
	RExpr *r = find_read(lhs, u);
	if (!r) r = find_read(rhs, u);
	return r ? r->loc : at;
}

/*
 * Resolves one equation of instance I: chooses the target among the
 * undetermined variables, solves for it, records the assignment. Returns
 * the target, or NULL after reporting an error.
 */
static Var *resolve_eqn(Inst *I, Eqn *q, Vec *branch, int src)
{
	Vec reads = { 0 }, pending = { 0 }, rf = { 0 };
	Ctx C = { 0 };
	C.bind = I->bind;
	C.nbind = I->nbind;
	C.reads = &reads;
	C.rf = &rf;
	C.pending = &pending;
	C.key_nbind = I->st->has_for ? 1 : I->nbind;
	RExpr *lhs = build(&C, q->lhs), *rhs = build(&C, q->rhs);
	if (C.failed) return NULL;
	if (lhs->isbool || rhs->isbool) {
		error_at(q->loc, "an equation relates values, not conditions");
		return NULL;
	}
	Var *x = NULL;
	for (int i = 0; i < reads.n; i++) {
		Var *v = reads.v[i];
		if (determined(v)) continue;
		if (!x || var_class(v) < var_class(x) || (var_class(v) == var_class(x) && v->order > x->order)) x = v;
	}
	if (!x) {
		error_at(q->loc, "rule \"%s\" is overdetermined%s%s: every variable in it is already determined", q->text,
		         I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "");
		for (int i = 0; i < reads.n; i++) explain_det(reads.v[i]);
		return NULL;
	}
	Var *other = NULL; /* a temporary besides the target that nothing determines: two unknowns */
	for (int i = 0; i < reads.n && !other; i++) {
		Var *v = reads.v[i];
		if (v != x && v->kind == V_TEMP && !determined(v)) other = v;
	}
	if (other) {
		/* the one the equation defines is a bare name on its left side (else the target chosen); the
		   other is unknown, most often a misspelling or another object's temporary */
		Var *want = lhs->k == R_VAR && lhs->var == other ? other : x, *u = want == other ? x : other;
		const char *s = near_name(I, u);
		Loc at = read_loc(lhs, rhs, u, q->loc);
		if (s)
			error_at(at, "unknown name '%s' in rule \"%s\"%s%s; did you mean '%s'?", u->name, q->text,
			         I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "", s);
		else
			error_at(at, "rule \"%s\" is unresolvable%s%s: it solves for %s but also reads %s, which no earlier rule determines",
			         q->text, I->nbind > 0 ? " for object " : "", I->nbind > 0 ? I->bind[0]->name : "", want->name, u->name);
		return NULL;
	}
	/* A new temporary takes its type from the other side of its equation. */
	if (x->kind == V_TEMP && !map_get(&sema.temps, x->key)) {
		RExpr *side = lhs->k == R_VAR && lhs->var == x ? lhs : rhs->k == R_VAR && rhs->var == x ? rhs : NULL;
		if (side) {
			side->isvec = (side == lhs ? rhs : lhs)->isvec;
			if (map_get(&sema.vector_decls, x->name) && !side->isvec) {
				error_at(q->loc, "'%s' is declared a vector, but \"%s\" makes it a scalar", x->name, q->text);
				return NULL;
			}
			x->isvec = side->isvec;
		}
	}
	if (lhs->isvec != rhs->isvec) {
		error_at(q->rhs->loc, "the two sides of \"%s\" differ: %s = %s", q->text, lhs->isvec ? "vector" : "scalar",
		         rhs->isvec ? "vector" : "scalar");
		return NULL;
	}
	if (x->kind == V_TEMP && !map_get(&sema.temps, x->key)) register_temp(x);
	RExpr *sol = solve(lhs, rhs, x, q->loc, q->text);
	if (!sol) return NULL;
	if (sol->isvec != x->isvec) {
		error_at(q->loc, "\"%s\" would make %s a %s, but it is a %s", q->text, var_label(x), sol->isvec ? "vector" : "scalar",
		         x->isvec ? "vector" : "scalar");
		return NULL;
	}
	if (sema.shaped && !I->st->has_for && I->nbind > 1 && !(x->kind == V_TEMP && x->pair))
		unshape("a rule over pairs ($1) determines a variable of one object");
	if (sema.shaped && sema_per_member(x) && (var_places(lhs, x) | var_places(rhs, x)) & ~2u)
		unshape("a rule determines a variable of $1");
	Assign *a = xalloc(sizeof *a);
	a->var = x;
	a->e = sol;
	a->src = src;
	a->lhs = lhs;
	a->rhs = rhs;
	a->loc = q->loc;
	a->text = q->text;
	vec_push(branch, a);
	for (int i = 0; i < reads.n; i++)
		if (reads.v[i] != x) add_unique(&I->reads, reads.v[i]);
	for (int i = 0; i < rf.n; i++) add_unique(&I->rf_reads, rf.v[i]);
	x->det = I;
	for (int i = 0; i < I->targets.n; i++)
		if (I->targets.v[i] == x) return x; /* the other branch of a conditional rule: already listed */
	vec_push(&I->targets, x);
	I->why = I->why ? xprintf("%s, %s (%s)", I->why, x->name, class_name(x)) : xprintf("%s (%s)", x->name, class_name(x));
	return x;
}

static RExpr *build_cond(Inst *I, Expr *cond, const char *what)
{
	Vec reads = { 0 }, pending = { 0 }, rf = { 0 };
	Ctx C = { 0 };
	C.bind = I->bind;
	C.nbind = I->nbind;
	C.reads = &reads;
	C.rf = &rf;
	C.pending = &pending;
	C.key_nbind = I->st->has_for ? 1 : I->nbind;
	RExpr *r = build(&C, cond);
	if (C.failed) return NULL;
	if (!r->isbool) {
		error_at(cond->loc, "%s must be a condition (a comparison)", what);
		return NULL;
	}
	for (int i = 0; i < reads.n; i++) {
		Var *v = reads.v[i];
		if (v->kind == V_TEMP && !determined(v)) {
			error_at(read_loc(r, NULL, v, cond->loc), "%s reads '%s', which no rule determines", what, v->name);
			return NULL;
		}
		add_unique(&I->reads, v);
	}
	for (int i = 0; i < rf.n; i++) add_unique(&I->rf_reads, rf.v[i]);
	return r;
}

static int stmt_src(Stmt *s) { return add_src(s->loc, s->text); }

static Branch *resolve_block(Inst *I, If *f, Vec *flat0, Vec *flat1);

/* Resolves the steps q of a conditional block of I into out, each assignment also into flat.
 * Returns 0 after an error. */
static int resolve_steps(Inst *I, Eqn *q, Vec *out, Vec *flat)
{
	for (; q; q = q->next) {
		if (q->nest) {
			Assign *a = xalloc(sizeof *a);
			a->nest = resolve_block(I, q->nest, flat, flat);
			if (!a->nest) return 0;
			a->loc = q->loc;
			a->text = q->text;
			vec_push(out, a);
			continue;
		}
		if (q->deriv) {
			error_at(q->loc, "a derivative rule cannot be conditional");
			return 0;
		}
		if (!resolve_eqn(I, q, out, add_src(q->loc, q->text))) return 0;
		vec_push(flat, out->v[out->n - 1]);
	}
	return 1;
}

/* Adds to v (once each) the variables steps determine: their assignments' and their blocks'. */
void sema_steps_targets(const Vec *steps, Vec *v)
{
	for (int i = 0; i < steps->n; i++) {
		Assign *a = steps->v[i];
		if (!a->nest) add_unique(v, a->var);
		for (int k = 0; a->nest && k < a->nest->targets.n; k++) add_unique(v, a->nest->targets.v[k]);
	}
}

/* Resolves conditional block f of I; its assignments, at every depth, go also to flat0 (under
 * its condition) and flat1 (not). Returns NULL after an error. */
static Branch *resolve_block(Inst *I, If *f, Vec *flat0, Vec *flat1)
{
	Branch *B = xalloc(sizeof *B);
	B->ast = f;
	B->cond = build_cond(I, f->cond, "the condition of a rule");
	if (!B->cond) return NULL;
	B->src = add_src(f->loc, f->text);
	I->cond = I->cond ? rop(CSF_OP_AND, 0, f->loc, I->cond, B->cond, NULL) : B->cond;
	I->cond->isbool = 1;
	for (int b = 0; b < 2; b++) {
		if (!resolve_steps(I, b ? f->els : f->then, &B->steps[b], b ? flat1 : flat0)) return NULL;
		sema_steps_targets(&B->steps[b], &B->targets);
		/* the other branch must not see this branch's targets as determined */
		for (int i = 0; i < B->targets.n; i++) ((Var *)B->targets.v[i])->det = NULL;
	}
	/* after the block every variable it determines is defined: zero on the paths that do not state it */
	for (int i = 0; i < B->targets.n; i++) ((Var *)B->targets.v[i])->det = I;
	return B;
}

static void inst_rule(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->src = sema.cur_src;
	if (!s->eqns->nest) {
		if (!resolve_eqn(I, s->eqns, &I->then, I->src)) return;
	} else {
		if (sema.shaped && !s->has_for && nbind > 1) unshape("a conditional rule over pairs ($1)");
		I->top = resolve_block(I, s->eqns->nest, &I->then, &I->els);
		if (!I->top) return;
	}
	if (I->isF)
		for (int i = 0; i < I->targets.n; i++) {
			Var *v = I->targets.v[i];
			if (!v->isvec) {
				error_at(s->loc, "a rule with attribute F must determine a force (a vector); %s is a scalar", v->name);
				return;
			}
		}
	vec_push(sema.cur_insts, I);
}

/* Is the rule's call the contact routine, with properties for arguments? Reports if not. */
static int check_call(Stmt *s)
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
 * normal$1): mass points, and a mass point and a plane, for the runtime's
 * contact routine, which reads the bodies' other properties by their
 * mechanics/mass_point names. The program lists the bodies of each rule
 * (Contact, ContactBody), not its pairs: the routine finds at run time the
 * pairs that come near. Two points (both of radius 0) never touch.
 */

static const char *const body_props[CSF_CF_N] = { NULL, "v", "a", "m", NULL, "cr", "mu_s", "mu_k", "FN", "Ff" };
static const char *const plane_props[CSF_CF_N] = { NULL, "edge", NULL, NULL, NULL, "cr", "mu_s", "mu_k", NULL, NULL };

/* A binding ($0, $1) of a contact rule, as it is checked: its objects and their properties. */
typedef struct CPair {
	Object *a, *b;
	int plane;            /* b is a plane */
	Var *f[2][CSF_CF_N];  /* of a and of b, in the order of enum csf_contact_field (csf.h) */
} CPair;

/* Body k's (0: $0, 1: $1) geometry in rule s on object o: the properties that arguments 2k and
 * 2k + 1 of contact() name, into geo[0..1]. Returns 0 if o lacks one: not this geometry. */
static int contact_geo(Stmt *s, Object *o, int k, Var **geo)
{
	for (int i = 0; i < 2; i++)
		if (!(geo[i] = prop_of(o, s->call->args[2 * k + i]->name))) return 0;
	return 1;
}

/* Fills body k's fields of c (its a, b and plane set) from geo and the properties the contact
 * routine reads. Returns 0 if one is missing or of the wrong type, reporting it at s if report. */
static int contact_body(CPair *c, int k, Var **geo, Stmt *s, int report)
{
	Object *o = k ? c->b : c->a;
	const char *const *names = k && c->plane ? plane_props : body_props;
	Var **f = c->f[k];
	f[CSF_CF_POS] = geo[0];
	f[CSF_CF_R] = geo[1];
	for (int i = 0; i < CSF_CF_N; i++) {
		if (!names[i]) continue;
		Var *v = prop_of(o, names[i]);
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

/* Are the position and velocity of c's body k integrated? A plane's need not be. */
static int contact_integrated(CPair *c, int k)
{
	return (k && c->plane) || (c->f[k][CSF_CF_POS]->state && c->f[k][CSF_CF_V]->state);
}

/* Checks the binding (a, b) of contact rule s into c, reporting what is wrong. 0 if it is wrong. */
static int contact_binding(Stmt *s, Object *a, Object *b, CPair *c)
{
	Var *geo[4];
	memset(c, 0, sizeof *c);
	c->a = a, c->b = b;
	if (!contact_geo(s, a, 0, geo) || !contact_geo(s, b, 1, geo + 2)) return 0;
	c->plane = geo[3]->isvec;
	if (!contact_body(c, 0, geo, s, 1) || !contact_body(c, 1, geo + 2, s, 1)) return 0;
	if (!contact_integrated(c, 0) || !contact_integrated(c, 1)) {
		error_at(s->loc, "contact of %s and %s: positions and velocities must be integrated (pos' = v, v' = a)",
		         a->name, b->name);
		return 0;
	}
	return 1;
}

/* The contact body of object o with properties f: one per object and geometry. */
static ContactBody *contact_cbody(Object *o, int plane, Var **f)
{
	char *key = xprintf("%d %p %p %d", o->index, (void *)f[CSF_CF_POS], (void *)f[CSF_CF_R], plane);
	ContactBody *b = map_get(&sema.M->cbody_keys, key);
	if (b) return b;
	b = xalloc(sizeof *b);
	b->o = o, b->plane = plane, b->index = sema.M->cbodies.n;
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

/* A radius of 0 decided at compile time that two points never touch: -D cannot change it. */
static void contact_radius_fixed(Var *r)
{
	if (r && !r->isvec && r->init[0] == 0 && !r->fix) r->fix = FIX_CONTACT;
}

/* Rule s with `for`: the pair (bind[0], bind[1]), unless it is two points (they never touch). */
static void inst_contact(Stmt *s, Object **bind, int nbind)
{
	CPair c;
	if (nbind < 2 || !contact_binding(s, bind[0], bind[1], &c)) return;
	for (int k = 0; k < 2 && !c.plane; k++) contact_radius_fixed(c.f[k][CSF_CF_R]);
	if (!c.plane && !(c.f[0][CSF_CF_R]->init[0] + c.f[1][CSF_CF_R]->init[0] > 0)) return;
	Contact *r = new_contact(s, 0);
	vec_push(&r->b0, contact_cbody(c.a, 0, c.f[0]));
	vec_push(&r->b1, contact_cbody(c.b, c.plane, c.f[1]));
	r->nplanes = c.plane;
	vec_push(&sema.M->contacts, r);
}

/* What the search for contact bodies knows of an object, as $0 (k = 0) and as $1 (k = 1). */
typedef struct Body {
	int geo[2];       /* has the geometry */
	int bad[2];       /* lacks a field the contact routine reads, or is not integrated: an error */
	int plane;        /* as $1: a plane */
	double r[2];      /* radius */
	Var *f[2][CSF_CF_N];
} Body;

/* What contact rule s needs of every object, in an array indexed like M->objects. */
static Body *contact_bodies(Stmt *s)
{
	Body *B = xalloc((size_t)sema.M->objects.n * sizeof *B);
	for (int i = 0; i < sema.M->objects.n; i++) {
		for (int k = 0; k < 2; k++) {
			Var *geo[2];
			if (!contact_geo(s, sema.M->objects.v[i], k, geo)) continue;
			CPair c = { 0 };
			c.a = c.b = sema.M->objects.v[i];
			c.plane = k && geo[1]->isvec;
			B[i].geo[k] = 1;
			B[i].bad[k] = !contact_body(&c, k, geo, s, 0) || !contact_integrated(&c, k);
			if (k) B[i].plane = c.plane;
			B[i].r[k] = geo[1]->init[0];
			if (!B[i].plane || !k) contact_radius_fixed(geo[1]);
			memcpy(B[i].f[k], c.f[k], sizeof B[i].f[k]);
		}
	}
	return B;
}

/* The first binding (*ea, *eb) of n bodies B that is an error, in binding order: $0 in order,
 * each with its $1 in order (a plane before it, or any body or plane after it). (n, n) if none. */
static void first_bad_pair(Body *B, int n, int *ea, int *eb)
{
	/* next_*[i]: the first $1 from i on, any or bad; plane_*: the first plane */
	int *next_any = xalloc((size_t)(n + 1) * sizeof *next_any), *next_bad = xalloc((size_t)(n + 1) * sizeof *next_bad);
	int plane_any = n, plane_bad = n;
	next_any[n] = next_bad[n] = n;
	for (int i = n - 1; i >= 0; i--) {
		next_any[i] = B[i].geo[1] ? i : next_any[i + 1];
		next_bad[i] = B[i].geo[1] && B[i].bad[1] ? i : next_bad[i + 1];
		if (B[i].geo[1] && B[i].plane) plane_any = i;
		if (B[i].geo[1] && B[i].plane && B[i].bad[1]) plane_bad = i;
	}
	*ea = *eb = n;
	for (int a = 0; a < n; a++) {
		if (!B[a].geo[0]) continue;
		/* a bad $0 fails with its first $1, a good one with its first bad $1 */
		int plane = B[a].bad[0] ? plane_any : plane_bad, b = plane < a ? plane : (B[a].bad[0] ? next_any : next_bad)[a + 1];
		if (b < n) {
			*ea = a, *eb = b;
			return;
		}
	}
}

/*
 * A contact rule without `for`: every mass point with its geometry as $0,
 * every object with its geometry as $1, in the order of definition; the
 * first binding that is an error is reported instead. Kept only if one of
 * its pairs can touch: a mass point and a plane (of another object), or
 * two mass points the sum of whose radii is positive.
 */
static void contact_pairs(Stmt *s)
{
	int n = sema.M->objects.n, ea, eb;
	Body *B = contact_bodies(s);
	first_bad_pair(B, n, &ea, &eb);
	if (ea < n) {
		CPair c;
		contact_binding(s, sema.M->objects.v[ea], sema.M->objects.v[eb], &c);
		return;
	}
	/* the bodies it applies to (a bad one here has no binding) */
	for (int i = 0; i < n; i++)
		for (int k = 0; k < 2; k++) B[i].geo[k] = B[i].geo[k] && !B[i].bad[k];
	int n0 = 0, touch = 0;
	for (int i = 0; i < n; i++) n0 += B[i].geo[0];
	double maxr0 = -HUGE_VAL; /* the largest radius of a $0 defined before */
	for (int i = 0; i < n && !touch; i++) {
		if (B[i].geo[1] && B[i].plane) touch = n0 > B[i].geo[0];
		else if (B[i].geo[1] && maxr0 + B[i].r[1] > 0) touch = 1;
		if (B[i].geo[0] && B[i].r[0] > maxr0) maxr0 = B[i].r[0];
	}
	if (!touch) return;
	Contact *r = new_contact(s, 1);
	for (int i = 0; i < n; i++) {
		if (B[i].geo[0]) vec_push(&r->b0, contact_cbody(sema.M->objects.v[i], 0, B[i].f[0]));
		if (B[i].geo[1]) vec_push(&r->b1, contact_cbody(sema.M->objects.v[i], B[i].plane, B[i].f[1]));
		if (B[i].geo[1] && B[i].plane) r->nplanes++;
	}
	vec_push(&sema.M->contacts, r);
}

/*
 * For --explain: which bodies the contact rules of statement s apply to.
 * Returns how many lines it wrote.
 */
static int explain_contacts(Model *Mo, Stmt *s, FILE *f)
{
	int lines = 0;
	for (int k = 0; k < Mo->contacts.n; k++) {
		Contact *r = Mo->contacts.v[k];
		if (r->st != s) continue;
		lines++;
		if (!r->every) {
			fprintf(f, "  for %s with %s: the contact routine (%s); computed in rhs and out\n",
			        ((ContactBody *)r->b0.v[0])->o->name, ((ContactBody *)r->b1.v[0])->o->name,
			        r->nplanes ? "a mass point and a plane" : "two mass points");
			continue;
		}
		/* the mass points ($0, and $1 that are not planes) and the planes, each once */
		char *seen = xalloc((size_t)Mo->cbodies.n + 1);
		Vec names = { 0 };
		int npts = 0;
		for (int q = 0; q < 2; q++)
			for (int j = 0; j < (q ? r->b1.n : r->b0.n); j++) {
				ContactBody *b = (q ? r->b1.v : r->b0.v)[j];
				if (b->plane || seen[b->index]) continue;
				seen[b->index] = 1, npts++;
				vec_push(&names, b->o->name);
			}
		for (int j = 0; j < r->b1.n; j++)
			if (((ContactBody *)r->b1.v[j])->plane) vec_push(&names, ((ContactBody *)r->b1.v[j])->o->name);
		fprintf(f, "  for %d mass point%s", npts, npts == 1 ? "" : "s");
		if (r->nplanes) fprintf(f, " and %d plane%s", r->nplanes, r->nplanes == 1 ? "" : "s");
		if (names.n <= 6)
			for (int j = 0; j < names.n; j++) fprintf(f, "%s%s", j ? ", " : " (", (char *)names.v[j]);
		fprintf(f, "%s: the contact routine (%s), on the pairs it finds near at run time%s; computed in rhs and out\n",
		        names.n <= 6 ? ")" : "", r->nplanes == r->b1.n ? "a mass point and a plane" : r->nplanes ? "two mass points, a mass point and a plane" : "two mass points",
		        r->nplanes == r->b1.n ? "" : " (two points never touch)");
	}
	return lines;
}

/* Every mass point of a contact rule must have its a determined (by Newton's second law). */
static void contact_accels(void)
{
	char *done = xalloc((size_t)sema.M->cbodies.n + 1);
	for (int i = 0; i < sema.M->contacts.n; i++) {
		Contact *r = sema.M->contacts.v[i];
		for (int k = 0; k < 2; k++) {
			Vec *L = k ? &r->b1 : &r->b0, *O = k ? &r->b0 : &r->b1;
			for (int j = 0; j < L->n; j++) {
				ContactBody *b = L->v[j];
				Var *a = b->f[CSF_CF_A];
				if (b->plane || !a || sema_canon(a)->det || done[b->index]) continue;
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

static void inst_deriv(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isderiv = 1;
	if (sema.shaped && !s->has_for && nbind > 1) unshape("a derivative rule over pairs ($1)");
	I->src = sema.cur_src;
	Var *v = prop_of(bind[0], s->eqns->lhs->name);
	if (!v) {
		error_at(s->eqns->lhs->loc, "'%s' is not a property of object '%s': only properties can be integrated",
		         s->eqns->lhs->name, bind[0]->name);
		return;
	}
	if (v->state) {
		error_at(s->loc, "%s already has a derivative rule", var_label(v));
		note_at(v->deriv->st->loc, "the first derivative rule for %s", var_label(v));
		return;
	}
	v->state = 1;
	v->deriv = I;
	for (int q = 1; sema.shaped && q < bind[0]->shape->n; q++) { /* every member's is state */
		Var *w = prop_of(bind[0]->shape->members[q], v->name);
		w->state = 1;
		w->deriv = I;
	}
	add_unique(&I->targets, v);
	I->why = xprintf("integrates %s (state variable)", v->name);
	vec_push(&sema.deriv_insts, I);
}

static void resolve_deriv(Inst *I)
{
	Eqn *q = I->st->eqns;
	Vec pending = { 0 }, rf = { 0 };
	Ctx C = { 0 };
	C.bind = I->bind;
	C.nbind = I->nbind;
	C.reads = &I->reads;
	C.rf = &rf;
	C.pending = &pending;
	C.key_nbind = I->st->has_for ? 1 : I->nbind;
	RExpr *r = build(&C, q->rhs);
	if (C.failed) return;
	Var *v = I->targets.v[0];
	if (r->isbool || r->isvec != v->isvec) {
		error_at(q->rhs->loc, "the derivative of %s must be a %s", var_label(v), v->isvec ? "vector" : "scalar");
		return;
	}
	for (int i = 0; i < I->reads.n; i++) {
		Var *w = I->reads.v[i];
		if (w->kind == V_TEMP && !determined(w)) {
			const char *s = near_name(I, w);
			Loc at = read_loc(r, NULL, w, q->loc);
			if (s) error_at(at, "unknown name '%s' in rule \"%s\"; did you mean '%s'?", w->name, q->text, s);
			else error_at(at, "rule \"%s\" is unresolvable: it reads '%s', which no rule determines", q->text, w->name);
			return;
		}
	}
	for (int i = 0; i < rf.n; i++) add_unique(&I->rf_reads, rf.v[i]);
	Assign *a = xalloc(sizeof *a);
	a->var = v;
	a->e = r;
	a->src = I->src;
	a->rhs = r;
	a->loc = q->loc;
	a->text = q->text;
	vec_push(&I->then, a);
}

static void inst_assert(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isassert = 1;
	I->src = sema.cur_src;
	I->cond = build_cond(I, s->cond, "an assertion");
	if (!I->cond) return;
	vec_push(sema.cur_insts, I);
}

/*
 * stop when COND: a terminal event. COND is one comparison, located in
 * time like a conditional rule's; its instance is computed in RHS (where
 * the runtime reads the guards), never in OUT.
 */
static void inst_stop(Stmt *s, Object **bind, int nbind)
{
	Inst *I = new_inst(s, bind, nbind);
	I->isstop = 1;
	I->src = sema.cur_src;
	I->cond = build_cond(I, s->cond, "a stop condition");
	if (!I->cond) return;
	int op = I->cond->k == R_OP ? I->cond->op : -1;
	if (op != CSF_OP_LT && op != CSF_OP_LE && op != CSF_OP_GT && op != CSF_OP_GE) {
		error_at(s->cond->loc, "a stop condition must be one comparison (<, <=, > or >=), located in time as it "
		                       "becomes true (for 'A or B', write 'stop when A' and 'stop when B')");
		return;
	}
	vec_push(sema.cur_insts, I);
}

/* ---- the watch list ---- */

static void add_col(Var *v, const char *label, int member)
{
	for (int c = 0; c < (v->isvec ? 3 : 1); c++) {
		WatchCol *w = xalloc(sizeof *w);
		w->var = v;
		w->comp = c;
		w->member = member;
		w->name = v->isvec ? xprintf("%s.%c", label, 'x' + c) : xstrdup(label);
		vec_push(&sema.M->cols, w);
	}
}

/* Object o's property or temporary `name`, or NULL; a temporary of a shape's member is the
 * representative's, at *member. */
static Var *watch_var(Object *o, const char *name, int *member)
{
	Var *v = prop_of(o, name);
	*member = 0;
	if (v) return v;
	Object *r = sema.shaped ? o->shape->members[0] : o;
	v = map_get(&sema.temps, temp_key(name, &r, 1));
	if (v) *member = o->sidx;
	return v;
}

/* Column label.comp of vector v (the watch item w names a component), or an error. */
static void add_comp(WatchItem *w, Var *v, const char *label, int member)
{
	const char *c = w->comp;
	if (!v->isvec) {
		error_at(w->loc, "'%s' is a scalar: it has no component '%s'", label, c);
		return;
	}
	if (strlen(c) != 1 || c[0] < 'x' || c[0] > 'z') {
		error_at(w->loc, "'%s' is not a component of a vector: watch %s.x, %s.y or %s.z", c, label, label, label);
		return;
	}
	WatchCol *col = xalloc(sizeof *col);
	col->var = v;
	col->comp = c[0] - 'x';
	col->member = member;
	col->name = xprintf("%s.%s", label, c);
	vec_push(&sema.M->cols, col);
}

static void build_watch(Stmt *st)
{
	int member;
	if (!st || !st->has_watch) {
		for (int i = 0; i < sema.M->objects.n; i++) {
			Object *o = sema.M->objects.v[i];
			for (int j = 0; j < o->props.n; j++) add_col(o->props.v[j], var_label(o->props.v[j]), 0);
		}
		return;
	}
	for (int i = 0; i < st->watch.n; i++) {
		WatchItem *w = st->watch.v[i];
		if (w->obj && !w->comp && !map_get(&sema.objects_by_name, w->obj) &&
		    (map_get(&sema.prop_names, w->obj) || map_get(&sema.globals_by_name, w->obj))) {
			/* PROP.c: that component of every object's PROP (or of a global) */
			WatchItem c = *w;
			c.obj = NULL, c.prop = w->obj, c.comp = w->prop;
			Var *g = map_get(&sema.globals_by_name, c.prop);
			if (g) {
				add_comp(&c, g, g->name, 0);
				continue;
			}
			for (int j = 0; j < sema.M->objects.n; j++) {
				Object *o = sema.M->objects.v[j];
				Var *v = watch_var(o, c.prop, &member);
				if (v) add_comp(&c, v, xprintf("%s.%s", o->name, c.prop), member);
			}
			continue;
		}
		if (w->obj) {
			Object *o = map_get(&sema.objects_by_name, w->obj);
			if (!o && (map_get(&sema.prop_names, w->obj) || map_get(&sema.globals_by_name, w->obj))) {
				error_at(w->loc, "'%s.%s': watch the whole variable ('watch %s' gives its x, y and z columns)", w->obj,
				         w->prop, w->obj);
				continue;
			}
			if (!o) {
				error_at(w->loc, "unknown object '%s'", w->obj);
				continue;
			}
			Var *v = watch_var(o, w->prop, &member);
			if (!v) {
				error_at(w->loc, "object '%s' has no property or temporary '%s'", o->name, w->prop);
				continue;
			}
			if (w->comp) add_comp(w, v, xprintf("%s.%s", o->name, w->prop), member);
			else add_col(v, xprintf("%s.%s", o->name, w->prop), member);
			continue;
		}
		if (strcmp(w->prop, "t") == 0) continue; /* t is always the first column */
		Var *g = map_get(&sema.globals_by_name, w->prop);
		if (g) {
			add_col(g, g->name, 0);
			continue;
		}
		int found = 0;
		for (int j = 0; j < sema.M->objects.n; j++) {
			Object *o = sema.M->objects.v[j];
			Var *v = watch_var(o, w->prop, &member);
			if (v) {
				add_col(v, xprintf("%s.%s", o->name, w->prop), member);
				found = 1;
			}
		}
		if (!found) error_at(w->loc, "nothing to watch: no object has '%s'", w->prop);
	}
}

static double const_time(Expr *x, double dflt, const char *what)
{
	if (!x) return dflt;
	int ok;
	RExpr *r = const_value(x, NULL, what, FIX_RUN, x->loc.line, &ok, NULL);
	if (!ok) return dflt;
	if (r->isvec || !isfinite(r->c[0]) || r->c[0] < 0) {
		if (!strcmp(what, "by")) error_at(x->loc, "'by' must be a positive time");
		else error_at(x->loc, "'%s' needs a finite, non-negative time", what);
		return dflt;
	}
	/* a pure number is a time in the unit system's seconds (till 2*pi, till pi) */
	if (r->dimk == DK_KNOWN && !dims_none(r->dim) && (r->dim[0] != 0 || r->dim[1] != 0 || r->dim[2] != 1 || r->dim[3] != 0)) {
		error_at(x->loc, "'%s' needs a time, not %s", what, dims_operand(r, r->dim));
		return dflt;
	}
	return r->c[0];
}

/* ---- the pass ---- */

static void check_sections(Stmt *stmts)
{
	int section = 0; /* 0 objects, 1 rules, 2 start */
	Stmt *start = NULL;
	for (Stmt *s = stmts; s; s = s->next) {
		int sec = s->kind == S_START ? 2
		          : (s->kind == S_RULE || s->kind == S_ASSERT || s->kind == S_STOP || s->kind == S_VECDECL) ? 1 : 0;
		if (start) {
			error_at(s->loc, "the start directive ('inc ...') must be the last statement");
			note_at(start->loc, "start directive here");
			return;
		}
		if (sec < section) {
			error_at(s->loc, "%s must come before the rules (objects, then rules, then the start directive)",
			         s->kind == S_DEF ? "a kind definition" : s->kind == S_GLOBAL ? "a global" : "an object definition");
		}
		if (sec > section) section = sec;
		if (s->kind == S_START) start = s;
	}
}

/* Every `atol A` is on a state variable's line, with the variable's dimension (a bare A takes it). */
static void check_atols(Model *M)
{
	for (int i = 0; i < M->objects.n; i++) {
		Object *o = M->objects.v[i];
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j];
			RExpr *a = v->atol;
			if (!a) continue;
			if (!v->state)
				error_at(a->loc, "'atol' is the absolute tolerance of a state variable, and '%s' of '%s' has no "
				         "derivative rule", v->name, o->name);
			else if (a->dimk == DK_KNOWN && v->dimk == DK_KNOWN && memcmp(a->dim, v->dim, sizeof v->dim) != 0)
				error_at(a->loc, "the atol of '%s' must be %s, as '%s' is, not %s", v->name, dims_describe(v->dim),
				         v->name, dims_operand(a, a->dim));
		}
	}
}

static Model *resolve(Stmt *stmts, int shaped)
{
	sema_reset(shaped);
	predefine();
	check_sections(stmts);
	build_objects(stmts);

	Stmt *start = NULL;
	Vec rules = { 0 };
	for (Stmt *s = stmts; s; s = s->next) {
		if (s->kind == S_START) start = s;
		if (s->kind == S_VECDECL)
			for (int i = 0; i < s->names.n; i++) map_put(&sema.vector_decls, s->names.v[i], s);
		if (s->kind == S_RULE || s->kind == S_ASSERT || s->kind == S_STOP) vec_push(&sema.M->stmts, s);
		if (s->kind == S_RULE) vec_push(&rules, s);
	}
	if (!start) {
		Loc end = { 0, 1, 1 };
		for (Stmt *s = stmts; s; s = s->next) end = s->loc;
		if (stmts) error_at(end, "no start directive: the model must end with 'inc t till TIME by STEP watch ...'");
		else error_plain("%s: empty model: there is nothing to simulate", ((Source *)sources.v[0])->path);
	} else {
		if (strcmp(start->var, "t") != 0) error_at(start->name_loc, "only time can be incremented: write 'inc t ...'");
		sema.M->till = const_time(start->till, 10, "till");
		sema.M->by = const_time(start->by, sema.M->till > 0 ? sema.M->till / 1000 : 0.01, "by");
		double most = opts.max_rows > 0 ? opts.max_rows : CSF_MAX_ROWS;
		if (!(sema.M->by > 0)) error_at(start->by ? start->by->loc : start->loc, "'by' must be a positive time");
		else if (sema.M->till / sema.M->by > most)
			error_at(start->till ? start->till->loc : start->loc,
			         "'till %g' by '%g' asks for %.3g rows of output, more than the limit of %.3g "
			         "(csfc --max-rows N raises it)", sema.M->till, sema.M->by, sema.M->till / sema.M->by, most);
		sema.M->start = start;
	}
	if (diag_errors) return sema.M;
	build_shapes(start);
	for (int i = 0; start && i < start->watch.n; i++) {
		WatchItem *w = start->watch.v[i];
		map_put(&sema.watched, w->obj ? xprintf("%s\x01%s", w->obj, w->prop) : w->prop, w);
	}

	/* Derivative rules first: their targets are state, determined from the start. */
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->eqns && s->eqns->deriv) {
			sema.cur_src = stmt_src(s);
			for_each_binding(s, inst_deriv);
		}
	}
	/* Algebraic rules in order; those reading RF after the last F rule. */
	int lastF = -1;
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->attr && strcmp(s->attr, "F") == 0) lastF = i;
	}
	Vec order = { 0 }, deferred = { 0 };
	for (int i = 0; i < rules.n; i++) {
		Stmt *s = rules.v[i];
		if (s->eqns && s->eqns->deriv) continue;
		if (i < lastF && stmt_reads_rf(s) && !(s->attr && strcmp(s->attr, "F") == 0)) vec_push(&deferred, s);
		else vec_push(&order, s);
		if (i == lastF)
			for (int k = 0; k < deferred.n; k++) vec_push(&order, deferred.v[k]);
	}
	sema.cur_insts = &sema.M->insts;
	for (int i = 0; i < order.n; i++) {
		Stmt *s = order.v[i];
		if (s->attr && strcmp(s->attr, "F") == 0 && stmt_reads_rf(s)) {
			error_at(s->loc, "a rule with attribute F cannot read RF: RF is the sum of the F rules");
			continue;
		}
		sema.cur_src = stmt_src(s);
		if (!s->call) for_each_binding(s, inst_rule);
		else if (check_call(s)) {
			if (s->has_for) for_each_binding(s, inst_contact);
			else contact_pairs(s);
		}
	}
	contact_accels();
	for (int i = 0; i < sema.deriv_insts.n; i++) {
		resolve_deriv(sema.deriv_insts.v[i]);
		vec_push(&sema.M->insts, sema.deriv_insts.v[i]);
	}
	for (int i = 0; i < sema.M->stmts.n; i++) {
		Stmt *s = sema.M->stmts.v[i];
		if (s->kind != S_ASSERT && s->kind != S_STOP) continue;
		sema.cur_src = add_src(s->loc, s->text);
		for_each_binding(s, s->kind == S_STOP ? inst_stop : inst_assert);
	}
	build_watch(start);
	/* by shape, a temporary of a pair lives for one iteration of its rule's loop */
	for (int i = 0; sema.shaped && i < sema.M->insts.n; i++) {
		Inst *I = sema.M->insts.v[i];
		for (int k = 0; k < I->reads.n; k++) {
			Var *v = I->reads.v[k];
			if (v->kind == V_TEMP && v->pair && v->det != I) unshape("a temporary of a pair ($1) read by another rule");
		}
	}
	/* Also after errors: the instances that failed are left out, and the dimensions of the
	 * others are checked all the same, so one run reports both kinds of error. */
	dims_check(sema.M);
	check_atols(sema.M);
	return sema.M;
}

/*
 * Resolves by shape first, silently; a model that cannot be resolved that way
 * (unshape), or that has an error, is resolved again object by object, which
 * reports the errors as they have always been reported.
 */
Model *sema_run(Stmt *stmts)
{
	FILE *saved = diag_out, *null = fopen("/dev/null", "w");
	int errors = diag_errors, stop = diag_stop;
	const char *why = "";
	if (null) {
		diag_out = null;
		Model *m = resolve(stmts, 1);
		diag_out = saved;
		fclose(null);
		if (!sema.unshaped && diag_errors == errors) {
			m->shaped = 1;
			return m;
		}
		why = sema.unshaped ? sema.unshaped : "";
		diag_errors = errors;
		diag_stop = stop;
	}
	Model *m = resolve(stmts, 0);
	m->unshaped_why = why;
	return m;
}

/* ---- --explain ---- */

/* Writes conditional block B, indented by depth levels: each branch's line with its equations and
 * the variables it leaves zero, then its nested blocks, deeper; an elif at the depth of its if. */
static void explain_block(FILE *f, Branch *B, int depth)
{
	for (int b = 0; b < 2; b++) {
		Vec *st = &B->steps[b], set = { 0 };
		Assign *one = st->n == 1 ? st->v[0] : NULL;
		if (b && one && one->nest && one->nest->ast->elif) {
			explain_block(f, one->nest, depth);
			continue;
		}
		if (!b) fprintf(f, "%*sline %d: %s", 2 * depth, "", B->ast->loc.line, B->ast->text);
		else if (B->ast->els) fprintf(f, "%*sline %d: else:", 2 * depth, "", B->ast->else_loc.line);
		else fprintf(f, "%*sotherwise:", 2 * depth, "");
		const char *sep = " ";
		for (int i = 0; i < st->n; i++) {
			Assign *a = st->v[i];
			if (!a->nest) fprintf(f, "%s%s", sep, a->text), sep = "; ";
		}
		sema_steps_targets(st, &set);
		for (int i = 0; i < B->targets.n; i++)
			if (!vec_has(&set, B->targets.v[i])) fprintf(f, "%s%s = 0 (not stated)", sep, ((Var *)B->targets.v[i])->name), sep = "; ";
		fputc('\n', f);
		for (int i = 0; i < st->n; i++)
			if (((Assign *)st->v[i])->nest) explain_block(f, ((Assign *)st->v[i])->nest, depth + 1);
	}
}

void sema_explain(Model *Mo, FILE *f)
{
	for (int i = 0; i < Mo->stmts.n; i++) {
		Stmt *s = Mo->stmts.v[i];
		Source *src = sources.v[s->loc.file];
		fprintf(f, "%s:%d: %s%s\n", src->path, s->loc.line,
		        s->kind == S_ASSERT ? "assert " : s->kind == S_STOP ? "stop when " : "", s->text);
		int n = 0;
		Inst *cond = NULL; /* an instance of a conditional rule: its branches are every instance's */
		for (int k = 0; k < Mo->insts.n; k++) {
			Inst *I = Mo->insts.v[k];
			if (I->st != s) continue;
			n++;
			if (I->top && !cond) cond = I;
			Shape *S = Mo->shaped && !s->has_for ? I->bind[0]->shape : NULL;
			fprintf(f, "  for %s", I->bind[0]->name);
			if (S && S->n > 1) fprintf(f, " and the %d other object%s of its shape", S->n - 1, S->n > 2 ? "s" : "");
			for (int b = 1; b < I->nbind; b++) {
				Object *o = I->bind[b];
				if (S && o->shape == S) fprintf(f, ", each with every other one");
				else if (S && o->shape->n > 1)
					fprintf(f, ", each with %s and the %d other object%s of its shape", o->name, o->shape->n - 1,
					        o->shape->n > 2 ? "s" : "");
				else fprintf(f, "%s%s", b == 1 ? " with " : ", ", o->name);
			}
			if (I->isassert) fprintf(f, ": checked at every output step");
			else if (I->isstop) fprintf(f, ": ends the run at the instant it becomes true (a terminal event)");
			else fprintf(f, ": %s%s", I->isderiv ? "" : "solves for ", I->why ? I->why : "?");
			if (!I->isassert && !I->isstop && !I->needed[0] && !I->needed[1]) fprintf(f, "; left out: nothing needs it");
			else if (!I->isassert && !I->isstop)
				fprintf(f, "; computed in %s", I->needed[0] && I->needed[1] ? "rhs and out" : I->needed[0] ? "rhs" : "out");
			fputc('\n', f);
		}
		if (cond) {
			fprintf(f, "  branches%s:\n", cond->needed[CSF_SEC_RHS] ? " (their comparisons <, <=, >, >= are events, located in time)" : "");
			explain_block(f, cond->top, 2);
		}
		n += explain_contacts(Mo, s, f);
		if (!n) fprintf(f, "  applies to no %s\n", s->call ? "pair that can touch" : "object");
	}
	if (!Mo->shaped && *Mo->unshaped_why) fprintf(f, "rules compiled once per object, not per shape: %s\n", Mo->unshaped_why);
	for (int i = 0; i < Mo->objects.n; i++) {
		Object *o = Mo->objects.v[i];
		fprintf(f, "object %s:", o->name);
		for (int j = 0; j < o->props.n; j++) {
			Var *v = o->props.v[j], *r = sema_canon(v);
			fprintf(f, "%s %s (%s)", j ? "," : "", v->name,
			        r->state ? "state" : r->det ? xprintf("computed, line %d", r->det->st->loc.line) : "constant");
		}
		fputc('\n', f);
	}
}
