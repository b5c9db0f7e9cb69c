/*
 * context.c - an expression of the source built into a resolved one (RExpr)
 * in a resolution context (Ctx): an initial value (constants only) or a rule
 * instance's binding ($0, $1, ...). Names resolve to t, RF, globals,
 * properties and temporaries, which a rule creates by reading them; types
 * (scalar, vector, condition) are checked.
 */
#include <math.h>
#include <string.h>

#include "csfc.h"
#include "sema.h"
#include "sema_int.h"
#include "csf_int.h"
#include "parse.h"

static const char *const predefined_names[] = { "t", "RF", NULL };

void add_unique(Vec *v, void *x)
{
	if (v && !vec_has(v, x)) vec_push(v, x);
}

int is_predefined(const char *n)
{
	for (int i = 0; predefined_names[i]; i++)
		if (strcmp(n, predefined_names[i]) == 0) return 1;
	return 0;
}


char *temp_key(const char *name, Object **bind, int nbind)
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

static RExpr *var_ref(Ctx *C, Var *v, Loc l, int place, Object *o)
{
	/* a term of a sum at a lean member: every member's value is read (folded into this one, or at its
	   place), none gets properties of its own */
	int term = C->sum_obj && o == C->sum_obj && o->lean;
	if (C->init) {
		if (v->kind == V_TIME) {
			error_at(l, "'t' is not known at compile time; an initial value must be a constant");
			C->failed = 1;
			return rconst(0, l);
		}
		if (C->fold && o && o->lean && o != C->self && !term) /* another member's: it gets its own properties */
			own_later(o, v->name, C->fold, C->fold_obj, C->fold_name, C->fold_line);
		else if (C->fold && !v->fix) {
			v->fix = C->fold;
			v->fix_obj = C->fold_obj;
			v->fix_name = C->fold_name;
			v->fix_line = C->fold_line;
		}
		if (!C->first_read) C->first_read = v;
		RExpr *e = rvarconst(v, l);
		memcpy(e->c, member_init(v, o), (v->isvec ? 3 : 1) * sizeof *e->c); /* o's own, if it shares v */
		return e;
	}
	RExpr *e = rnew(R_VAR, l);
	e->var = v;
	e->place = place;
	if (term) e->obj = o;
	e->isvec = v->isvec;
	add_unique(C->reads, v);
	return e;
}

static RExpr *build_name(Ctx *C, Expr *x, const char *name, Object *o, int explicit_obj)
{
	Loc l = x->loc;
	int place = -1; /* which $n o is */
	/* explicit_obj 2: a member named by the index of a rule that is one loop, at its place */
	for (int p = 0; !C->init && (!explicit_obj || explicit_obj == 2) && p < C->nbind; p++)
		if (C->bind[p] == o) {
			place = p;
			break;
		}
	/* by shape, a member stands for its shape: the representative's variables, at o's place */
	/* (explicit_obj 3: a member in a sum, read as itself: its own slot of its shape's arrays) */
	if (sema.shaped && o && !C->init && o->sidx && explicit_obj != 3) o = o->shape->members[0];
	if (!explicit_obj) {
		if (strcmp(name, "t") == 0) return var_ref(C, sema.M->time, l, -1, NULL);
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
		if (g) return var_ref(C, g, l, -1, NULL);
	}
	if (o) {
		Var *p = prop_of_obj(o, name);
		if (p) return var_ref(C, p, l, place, o);
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
			if (t && explicit_obj == 2) unshape("a rule among neighbours reads a temporary of a member");
			if (t) return var_ref(C, t, l, -1, NULL);
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
		var_more(t)->key = temp_key(name, bind, nbind);
		t->pair = nbind > 1;
		t->order = sema.def_counter++;
		vec_push(C->pending, t);
	}
	return var_ref(C, t, l, place, NULL);
}

static void type_error(Ctx *C, Loc l, const char *msg)
{
	error_at(l, "%s", msg);
	C->failed = 1;
}

/* A temporary no rule has determined yet takes the type its use asks for. */
static int infer_vector(RExpr *r)
{
	if (r->k != R_VAR || r->var->kind != V_TEMP || determined(r->var) || map_get(&sema.temps, var_more_of(r->var)->key)) return 0;
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

/* sum(EXPR for NAME): EXPR of each member of the array NAME, added pairwise (a tree of depth log2 of the members). */
static RExpr *build_sum(Ctx *C, Expr *x)
{
	ObjArray *A = array_of(x->name);
	if (!A) {
		type_error(C, x->loc, xprintf("'sum(... for %s)': '%s' is not an object array", x->name, x->name));
		return rconst(0, x->loc);
	}
	long n = A->hi - A->lo + 1;
	RExpr **t = xalloc((size_t)n * sizeof *t);
	Vec all = { 0 }; /* every member's reads, added to C's once (vec_add_new: linear in them) */
	for (long k = 0; k < n; k++) {
		Ctx D = *C;
		Vec reads = { 0 };
		D.sum_obj = array_member(A, A->lo + k);
		D.reads = C->reads ? &reads : NULL;
		t[k] = build(&D, x->a);
		for (int i = 0; i < reads.n; i++) vec_push(&all, reads.v[i]);
		if (!C->first_read) C->first_read = D.first_read;
		if (D.failed) {
			C->failed = D.failed;
			return rconst(0, x->loc);
		}
		if (t[k]->isbool) {
			type_error(C, x->a->loc, "'sum' adds numbers or vectors, not conditions");
			return rconst(0, x->loc);
		}
	}
	if (C->reads) vec_add_new(C->reads, &all, NULL);
	if (C->summed) vec_add_new(C->summed, &all, NULL);
	while (n > 1) {
		long m = 0;
		for (long k = 0; k + 1 < n; k += 2)
			t[m++] = rop(t[k]->isvec ? CSF_OP_VADD : CSF_OP_ADD, t[k]->isvec, x->loc, t[k], t[k + 1], NULL);
		if (n & 1) t[m++] = t[n - 1];
		n = m;
	}
	return t[0];
}

/* a times the unit of x (E_UNIT, E_LIT), at x's place. */
static RExpr *times_unit(const Expr *x, RExpr *a)
{
	double ud[CSF_NDIM];
	for (int i = 0; i < CSF_NDIM; i++) ud[i] = x->unit.dim[i];
	RExpr *f = rconst(dims_to_system(x->unit.factor, ud), x->loc);
	f->dimk = DK_KNOWN;
	memcpy(f->dim, ud, sizeof ud);
	return rop(a->isvec ? CSF_OP_VMUL : CSF_OP_MUL, a->isvec, x->loc, a, f, NULL);
}

RExpr *build(Ctx *C, Expr *x)
{
	Loc l = x->loc;
	switch (x->kind) {
	case E_NUM: return rconst(x->num, l);
	case E_NAME:
		if (C->ivar && !strcmp(x->name, C->ivar)) return rconst((double)C->idx, l); /* an index: a bare number */
		if (C->sum_obj && strcmp(x->name, "t") != 0 && !map_get(&sema.globals_by_name, x->name))
			return build_name(C, x, x->name, C->sum_obj, 3);
		return build_name(C, x, x->name, C->init ? C->self : C->bind[0], 0);
	case E_INDEX:
		array_at(C, x->name, x->a, l);
		if (!C->failed) type_error(C, l, xprintf("'%s[...]' is an object: name one of its properties ('%s[3].pos')", x->name, x->name));
		return rconst(0, l);
	case E_SUM: return build_sum(C, x);
	case E_DOLLAR:
		if (C->init) return type_error(C, l, "'$n' is only meaningful in rules"), rconst(0, l);
		if (x->n >= C->nbind) return type_error(C, l, "no such object in this rule"), rconst(0, l);
		return build_name(C, x, x->name, C->bind[x->n], 0);
	case E_FIELD: {
		if (x->a->kind == E_INDEX) {
			Object *o = array_at(C, x->a->name, x->a->a, x->a->loc);
			int by_index = C->iloop && C->ivar && expr_reads_name(x->a->a, C->ivar);
			return o ? build_name(C, x, x->name, o, by_index ? 2 : 1) : rconst(0, l);
		}
		if (x->a->kind == E_NAME) {
			Object *o = map_get(&sema.objects_by_name, x->a->name);
			if (o && !(C->bind && prop_of_obj(C->bind[0], x->a->name)) && !map_get(&sema.globals_by_name, x->a->name))
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
		if (op == CSF_OP_FLOOR && !C->init)
			return type_error(C, l, xprintf("'%s' is only for initial values (in a rule it would jump where no event "
			                                "is looked for)", x->name)),
			       rconst(0, l);
		RExpr *a[2] = { NULL, NULL };
		for (int i = 0; i < nargs; i++) {
			a[i] = build(C, x->args[i]);
			if (a[i]->isvec || a[i]->isbool)
				return type_error(C, x->args[i]->loc, xprintf("'%s' needs a scalar argument", x->name)), rconst(0, l);
		}
		if (op == CSF_OP_FLOOR && nargs == 2) /* mod(a, b) = a - b floor(a / b): the sign of b, as a floor */
			return rop(CSF_OP_SUB, 0, l, a[0],
			           rop(CSF_OP_MUL, 0, l, a[1], rop(CSF_OP_FLOOR, 0, l, rop(CSF_OP_DIV, 0, l, a[0], a[1], NULL), NULL, NULL),
			               NULL),
			           NULL);
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
		return times_unit(x, a);
	}
	case E_LIT: { /* as E_UNIT over E_NUM (whose place the product, folded, does not keep), or over E_VEC of
	                 E_NUM and E_NEG of E_NUM at their places */
		const Lit *L = x->lit;
		if (!L) return times_unit(x, rconst(x->num, l));
		RExpr *c[3];
		for (int i = 0; i < 3; i++) {
			c[i] = rconst(L->v[i], L->at[i]);
			if (L->neg[i]) c[i] = rop(CSF_OP_NEG, 0, L->neg_at[i], c[i], NULL, NULL);
		}
		return times_unit(x, rop(CSF_OP_VPACK, 1, L->vec_at, c[0], c[1], c[2]));
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
