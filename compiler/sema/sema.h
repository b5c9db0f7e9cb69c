/*
 * sema.h - the resolved model: objects, variables, rule instances.
 */
#ifndef CSF_SEMA_H
#define CSF_SEMA_H

#include "csfc.h"
#include "ast.h"
#include "csf_int.h"

typedef struct Object Object;
typedef struct Inst Inst;
typedef struct RExpr RExpr;

/*
 * A shape: the objects that have the same properties (names, types and
 * dimensions, in the same order), and so the same rule instances. A rule is
 * resolved once per shape, for its first member (the representative), and
 * compiled as a loop over the members; their properties are arrays (gen.c).
 * An object named in a rule, a `for` list or a watched temporary is a shape
 * of its own.
 */
typedef struct Shape {
	int index;
	int n;             /* members */
	Object **members;  /* in ascending object index; members[0] represents the shape */
} Shape;

typedef enum VarKind { V_TIME, V_GLOBAL, V_PROP, V_TEMP } VarKind;

/* What few variables have (Var.more), made by var_more when first set; never set inside an arena
 * mark that a pass releases (set_prop's): the Var would outlive it. */
typedef struct VarMore {
	char *key;       /* temps: lookup key */
	Inst *latch;     /* props, globals: the first `when` block that assigns it (a state variable, or latched:
	                    piecewise constant between the events at which the blocks assign it) */
	Loc dim_from;    /* props and globals given a bare value: the equation that gave it its dimension
	                    (line 0: none did) */
	RExpr *atol;     /* props: the absolute tolerance `atol A` set on its line (a constant), or NULL */
	/* a property the members of an array share (ObjArray): member k's value at vals + k (a vector's at
	   vals + 3 k; NULL: every member's is init); own[k]: where member k was given a value of its own (line
	   0, or own NULL: it was not); by: the statement that last gave every member a value, and checked:
	   the last kind statement that checked it (objects.c) */
	double *vals;
	Loc *own;
	const void *by, *checked;
} VarMore;

/* A variable: 144 bytes (a million objects have a dozen each), its small fields chars, what few
 * variables have in more. */
typedef struct Var {
	char *name;
	Object *obj;     /* owner (props, temps), NULL for globals and t */
	double init[3];
	double dim[CSF_NDIM]; /* exponents of length, mass, time, current */
	Inst *det;       /* the instance that determines it, if any */
	Inst *deriv;     /* its derivative rule instance (state variables) */
	VarMore *more;   /* NULL: none of its fields set (var_more_of reads them as zeros) */
	/* globals, props: why -D cannot set the initial value (gen.c words it): FIX_FOLDED, its value is
	   folded into that of fix_obj.fix_name (fix_obj NULL: the global fix_name) on line fix_line;
	   FIX_DERIVED, it is computed from fix_obj.fix_name's; FIX_RUN, folded into the run's fix_name
	   (till, by); FIX_CONTACT, its value 0 left contacts out (fix) */
	const char *fix_obj, *fix_name;
	int fix_line;
	Loc loc;
	int order;       /* definition order, for the precedence of spec 2.4.1 */
	int slot;        /* memory slot, -1 until allocated */
	unsigned char kind; /* VarKind */
	unsigned char isvec;
	unsigned char state; /* integrated: has a derivative rule */
	unsigned char from_kind; /* props: the value is a kind's default, not yet set */
	unsigned char dimk;  /* DK_UNKNOWN until known (dims.c) */
	unsigned char pair;  /* temps: of a tuple of objects ($1), not of one object */
	unsigned char fix;
} Var;

/* v's rarely set fields, to set (made if need be). */
static inline VarMore *var_more(Var *v)
{
	if (!v->more) v->more = xalloc(sizeof *v->more);
	return v->more;
}

/* v's rarely set fields, to read (zeros if none is set). */
static inline const VarMore *var_more_of(const Var *v)
{
	static const VarMore none;
	return v->more ? v->more : &none;
}

enum { FIX_NONE, FIX_FOLDED, FIX_DERIVED, FIX_RUN, FIX_CONTACT };

struct Object {
	char *name;
	Loc loc;
	int index;
	Vec props;       /* of Var* (V_PROP), in definition order */
	Map props_by_name; /* the same, by name, once there are more than PROPS_SCANNED */
	Shape *shape;
	int sidx;        /* its index among the shape's members */
	int dropped;     /* left out: nothing watched depends on it (mid/cone.c); no rule applies to it */
	struct ObjArray *lean; /* a member of this array without properties of its own: it shares the array's
	                          (ObjArray.proto), its values in theirs (VarMore.vals); NULL: its own */
};

/*
 * An object array (DECISIONS §11): its members NAME[lo] .. NAME[hi] are the
 * objects first .. first + hi - lo, in order (arrays.c). Resolved by shape,
 * its members are lean: they have no variables of their own, but share
 * proto's properties, whose values are arrays over the members (member k's
 * in VarMore.vals). They are in one shape (with other objects of their
 * signature, if any), proto's properties belong (Var.obj) to the first of
 * them, and a member's slot of a property is the shape's array at its
 * place (prop_slot; a sum reads each member there). A member that a rule
 * names, that is given a property the others lack, or whose value another
 * initial value reads, gets properties of its own (objects.c, array_own).
 */
typedef struct ObjArray {
	char *name;
	Loc loc;
	long lo, hi;
	int first;
	Object proto;     /* props, props_by_name: the properties the lean members share */
	Object *owner;    /* the lean member they belong to (Var.obj): the first (not left out, shapes.c) */
} ObjArray;

/* The properties of object o: its own, or those it shares with the lean members of its array. */
static inline const Vec *obj_props(const Object *o) { return o->lean ? &o->lean->proto.props : &o->props; }

/* Does o share its properties with another member that stands for it (its shape's representative,
 * whose properties they are)? Walks over every object's properties visit them once, at that member. */
static inline int obj_shares(const Object *o) { return o->lean && o->lean->owner != o; }

/* The initial value of property v of object o: o's own (vals) if v is shared by an array's members. */
static inline const double *member_init(const Var *v, const Object *o)
{
	if (o && o->lean && v->more && v->more->vals)
		return v->more->vals + (v->isvec ? 3 : 1) * (size_t)(o->index - o->lean->first);
	return v->init;
}

typedef enum RKind { R_CONST, R_VAR, R_RF, R_OP, R_COMP } RKind;

struct RExpr {
	RKind k;
	int isvec, isbool;
	int op;          /* csf opcode for R_OP */
	double c[3];     /* R_CONST */
	Var *var;        /* R_VAR */
	int place;       /* R_VAR: the place of the binding ($n) whose object it belongs to; -1: a global,
	                    t, or a property of a named object */
	Object *obj;     /* R_RF; R_VAR: the lean member (Object.lean) whose place of a property it reads, a term
	                    of a sum (prop_slot); NULL: none */
	int comp;        /* R_COMP: 0..2 of a[0] */
	RExpr *a[3];
	int n;
	Loc loc;
	int dimk;        /* R_CONST: DK_FREE (a bare number) or DK_KNOWN */
	double dim[CSF_NDIM];
};

enum { DK_UNKNOWN = 0, DK_FREE, DK_KNOWN };

typedef struct Branch Branch;

/* An assignment a rule instance performs: var := e; or (nest set, var NULL) a conditional block. */
typedef struct Assign {
	Var *var;
	RExpr *e;
	int src;
	RExpr *lhs, *rhs; /* the equation as written (for the dimension check) */
	Loc loc;
	char *text;
	Branch *nest;
} Assign;

/* A conditional block of a rule instance, resolved: its steps when cond holds (steps[0]) and
 * when not (steps[1]); a variable one path determines is zero on the paths that do not. */
struct Branch {
	If *ast;
	RExpr *cond;
	Vec steps[2];    /* of Assign* */
	Vec targets;     /* of Var*: what it determines, on one path or more */
	int src;         /* its `if` or `elif` line (what its events name) */
};

struct Inst {
	Stmt *st;
	Object **bind;   /* $0, $1, ... */
	int nbind;
	int isassert, isstop, isderiv, isF;
	int iswhen;      /* a `when` block: its condition in cond, its assignments in then (var := e, every e read
	                    before any var is set) */
	RExpr *cond;     /* assertion, stop; conditional rule: all its conditions joined by 'and' (dims.c) */
	Branch *top;     /* conditional rule: its block */
	Vec then, els;   /* of Assign*: a plain rule's one (then); a conditional rule's, at every depth,
	                    under its first condition (then) and not (els) */
	Vec targets;     /* of Var*: every variable it determines (union of branches) */
	Vec reads;       /* of Var*: every variable it reads */
	Vec rf_reads;    /* of Object*: whose RF it reads */
	Vec summed;      /* of Var*: the variables it reads in a sum (at every member, when lean members share them) */
	int needed[2];   /* by the RHS section, by the OUT section */
	int src;         /* its statement in the source table */
	int assert_index;
	char *why;       /* for --explain: what it solves for and why */
	int acc;         /* gen.c: a $1 F rule's sums over $1, an array of vectors (slot, -1 before) */
	int idle;        /* a derivative whose state variable nothing watched depends on: not integrated
	                    (mid/cone.c) */
	const char *ivar; /* a rule whose `for` list indexes members (`for node[i], node[i+1]`): its index name
	                     and value for this binding; NULL: none */
	long idx;
	long iloop;      /* a rule among neighbours compiled as one loop (Stmt.loop): how many bindings, the
	                    first bound (idx the index's value there); binding b of the k-th is the member
	                    k places after bind[b] in their shape. 0: none */
};

/* A body of the contact routine: a mass point, a plane or an anchor, with the properties the routine reads. */
typedef struct ContactBody {
	Object *o;
	int kind;         /* enum csf_cbody_kind: nonzero, immovable (a plane or an anchor) */
	Var *f[CSF_CF_N]; /* in the order of enum csf_contact_field (csf.h); NULL: not read */
	int index;        /* in Model.cbodies */
} ContactBody;

/*
 * A contact rule (mechanics/rules 1-4) and the bodies it applies to; the
 * runtime's contact routine finds which of its pairs touch (csf_crule).
 */
typedef struct Contact {
	Stmt *st;
	int src;
	int every;       /* 1: every pair of the lists; 0: a rule with `for`, its one pair */
	Vec b0, b1;      /* of ContactBody*: the $0 mass points, the $1 mass points, planes or anchors */
	int nplanes, nanchors; /* of b1 */
} Contact;

/*
 * A constraint: one binding of a rule with attribute C, g = lhs - rhs kept
 * at 0 (kind CSF_CON_EQ), or at most or at least 0 (CSF_CON_LE, _GE: a
 * string), by ideal forces on its bodies, the mass points whose positions
 * it reads (constraints.c). Its code: g, its rate gd (positions moving at
 * their velocities, t at 1), the bias c (g'' = sum of grad . a, plus c),
 * the size of its terms (scale), the restitution of going taut (cr, the
 * least of its objects'), and per body the gradient of g.
 */
typedef struct Constraint {
	Stmt *st;
	int src;
	int kind;
	Object **bind;
	int nbind;
	RExpr *lhs, *rhs, *g, *gd, *c, *scale, *cr;
	Vec reads;        /* of Var* */
	Vec bodies;       /* of Object* */
	Vec pos, vel;     /* of Var*: each body's pos and v */
	RExpr **grad;     /* per body */
	int dimk;         /* the dimension of g (dims.c) */
	double dim[CSF_NDIM];
} Constraint;

/* A column: component comp of var, of its shape's member member (a temporary, or a property the members of
 * an array share: Object.lean); otherwise of var's object. */
typedef struct WatchCol { char *name; Var *var; int comp; int member; } WatchCol;

typedef struct Model {
	Vec objects;     /* of Object* */
	Vec globals;     /* of Var* */
	Var *time;
	Vec insts;       /* of Inst*: algebraic rules in resolution order, then derivatives, then assertions */
	Vec temps;       /* of Var* */
	Vec contacts;    /* of Contact*: the contact rules that have a pair that can touch */
	Vec cons;        /* of Constraint*, in rule order */
	Vec cbodies;     /* of ContactBody*: their bodies */
	Map cbody_keys;  /* ContactBody* by object and geometry */
	Vec cols;        /* of WatchCol* */
	Vec stmts;       /* of Stmt*: rules and assertions in source order (for --explain) */
	Vec srcs;        /* of Stmt* or Eqn* text: see gen.c */
	double till, by;
	Stmt *start;
	Vec shapes;      /* of Shape* */
	int shaped;      /* rules compiled once per shape; 0: once per object */
	const char *unshaped_why; /* why not, for --explain */
	int ndropped;    /* objects left out (Object.dropped) */
} Model;

/* A statement in the source table (what runtime errors name). */
typedef struct SrcEntry { Loc loc; char *text; } SrcEntry;

/* Builds and resolves the model from the statement list. Errors are reported; check diag_errors.
 * drop (NULL: none): by object index, the objects to leave out (no rule, contact or watch of all
 * objects applies to them; mid/cone.c), resolved silently. */
Model *sema_run(Stmt *stmts, const char *drop);

/* The variable standing for v in the code: the representative's property of v's name. */
Var *sema_canon(Var *v);
/* Object o's property name, or NULL. */
Var *prop_of_obj(const Object *o, const char *name);
/* The most properties prop_of_obj finds by a scan of Object.props, not by Object.props_by_name. */
#define PROPS_SCANNED 16

/* Is v integrated: a state variable whose derivative is not idle (mid/cone.c)? */
static inline int var_integrated(const Var *v) { return v->state && !(v->deriv && v->deriv->idle); }

/* Is v an array over its shape's members (a property, or a temporary of one object)? */
int sema_per_member(const Var *v);

/* Adds to v (once each) the variables the steps of a branch determine: their assignments' and
 * their blocks' (gen.c gives the others zero). */
void sema_steps_targets(const Vec *steps, Vec *v);

/* Checks and infers the dimensions of the whole model (dims.c). Errors are reported. */
void dims_check(Model *M);
/* The dimension of constant op(args) (for the folder); reports a mismatch at l. */
void dims_fold(int op, RExpr **args, int n, RExpr *out, Loc l);
/* The dimension of local coordinates sys(args) (sys: "sph", "cyl" or "cart"), into constant out:
 * that of the lengths (r; rho and z; x, y and z), which must agree; reports a mismatch, or an
 * angle that is not dimensionless, at the argument. */
void dims_coords(const char *sys, RExpr **args, RExpr *out);
/* The unit of dimension d in the unit system in use, e.g. "kg*m/s^2"; "" if dimensionless. */
const char *dims_unit(const double d[CSF_NDIM]);
/* A side of a dimension mismatch for a message: the name or literal e is with its unit d ("x (m)",
 * "10 m"), else the dimension d alone (e may be NULL). */
const char *dims_operand(const RExpr *e, const double d[CSF_NDIM]);
/* Is d dimensionless? */
int dims_none(const double d[CSF_NDIM]);
/* "a length (m)", "dimensionless": a dimension for messages. */
const char *dims_describe(const double d[CSF_NDIM]);
/* Converts an SI factor of dimension d to the unit system in use. */
double dims_to_system(double si, const double d[CSF_NDIM]);
/* The unit system in use: its units of length, mass, time and current in SI (csf_prog.ubase). */
void dims_system_base(double base[CSF_NDIM]);

/* Evaluates an instruction on constant operands with the runtime's own functions.
 * in: operand values (3 doubles each); out: result (3 doubles). */
void fold_op(int op, double in[3][3], double out[3]);

#endif
