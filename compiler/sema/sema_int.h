/*
 * sema_int.h - what the pieces of the semantic pass (the .c files of compiler/sema) share:
 * the state of the pass, the resolution context, and their functions. The rest
 * of the compiler sees only sema.h.
 */
#ifndef CSF_SEMA_INT_H
#define CSF_SEMA_INT_H

#include "csfc.h"
#include "ast.h"
#include "sema.h"

/* The size of Sema.prop_seen. */
#define PROP_SEEN 64

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
	Vec waiting;            /* rules that cannot be resolved alone, in the order reached (group.c) */
	Map waits_of;           /* "%p" of an unknown of theirs: a Vec of them */
	Map group_vars;         /* "%p" of a variable they determined (its rule waited) */
	Map arrays;             /* ObjArray* by name */
	Vec array_list;         /* the same, in the order declared */
	const void *arr_stmt;   /* the statement giving every member of an array a value, while it does (arrays.c) */
	const struct ObjArray *arr_set; /* meanwhile, its array, */
	const char *fold_as;    /* and how -D's messages name any member ("star[i]"): see Var.fix */
	int dims_off;           /* folding a value whose dimension is known: rop leaves it out, */
	int dims_set;           /* and set_prop gives the value this one (set by the last value it folded) */
	int dimk;
	double dim[CSF_NDIM];
	Map arrays_failed;      /* the arrays whose data files are wrong (reported once) */
	/* the index of the member being defined (`object star[i]: ...`) or bound (`for node[i], ...`):
	   its name stands for it in expressions */
	const char *ivar;
	long idx;
	long iloop;             /* binding a rule that is one loop over its bindings (Stmt.loop): how many */
	struct FoldMemo *memo;  /* set_prop's values that are the same for every object (objects.c) */
	const char *prop_seen[PROP_SEEN]; /* names put_prop has put in prop_names, direct-mapped by pointer */
} Sema;

/* A resolution context: what an expression is built for (context.c). */
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
	const char *ivar;  /* an index name and its value (Sema.ivar, Inst.ivar), or NULL */
	long idx;
	long iloop;        /* building a rule among neighbours compiled as one loop (Inst.iloop) */
	Object *sum_obj;   /* in sum(EXPR for NAME): the member whose properties the names of EXPR are */
	Vec *summed;       /* Var* read in a sum: the rule does not solve for them (NULL: not recorded) */
} Ctx;

/* A function of one expression (NULL for none) and a context; 0 stops a walk. */
typedef int (*ExprFn)(Expr *x, void *ctx);

/* ---- pass.c: the pass ---- */

extern Sema sema;

/* Gives up resolving by shape (the model is resolved again, object by object). */
void unshape(const char *why);

/* ---- expr.c: resolved expressions ---- */

RExpr *rnew(RKind k, Loc l);
RExpr *rconst(double x, Loc l);
RExpr *rvconst(const double *v, Loc l);

/* A constant standing for a variable's value (initial values): it has the variable's dimension. */
RExpr *rvarconst(Var *v, Loc l);

int is_const(RExpr *e, double x);

/* Builds op(a, b, c) of the given result type, folding constant operands. */
RExpr *rop(int op, int isvec, Loc l, RExpr *a, RExpr *b, RExpr *c);

int opcode_of_func(const char *name, int *nargs);

/* ---- context.c: the resolution context ---- */

void add_unique(Vec *v, void *x);
int is_predefined(const char *n);
char *temp_key(const char *name, Object **bind, int nbind);
RExpr *build(Ctx *C, Expr *x);

/* ---- objects.c: objects, kinds, globals ---- */

int check_name(const char *n, Loc l, const char *what);
void predefine(void);

/*
 * The constant value of x, the value of obj.name (obj NULL: the global
 * name; fold FIX_RUN: the run's name) defined on line. The values it reads
 * are folded into it, so -D cannot set them (Var.fix); *read, if not NULL,
 * gets the first one it read (NULL: none, it is a literal).
 */
RExpr *const_value(Expr *x, Object *obj, const char *name, int fold, int line, int *ok, Var **read);

void build_objects(Stmt *stmts);

/* Defines object o's property from statement s (from_kind: a kind's default). */
void set_prop(Object *o, Stmt *s, int from_kind);
/* Defines or overrides object o's property name, at l, to constant r (a vector if isvec); reports
 * a clash of type or dimension at at. */
void put_prop(Object *o, const char *name, Loc l, Loc at, RExpr *r, int isvec, int from_kind, Var *read, Stmt *s);
/* The object name, made if new (NULL after an error at l). */
Object *get_object(const char *name, Loc l);
/* A new object, the last (not in Sema.objects_by_name). */
Object *new_object(const char *name, Loc l);
/* Applies kind statement s (`object NAME: KIND`) to object o. */
void apply_kind(Object *o, Stmt *s);
/* Gives lean member o (Object.lean) properties of its own, of its values. */
void array_own(Object *o);
/* Lean member o's property prop is read by an initial value, folded (Var.fix) into fold_obj.fold_name on
 * line: o gets properties of its own, and that one the fix, once the statement is done (own_pending);
 * not at once: the read is inside an arena mark that set_prop releases. */
void own_later(Object *o, const char *prop, int fold, const char *fold_obj, const char *fold_name, int line);
void own_pending(void);

/* ---- arrays.c: object arrays (DECISIONS §11) ---- */

ObjArray *array_of(const char *name);
/* The object named name (a member of an array: NAME[K], which Sema.objects_by_name does not hold), or NULL. */
Object *object_named(const char *name);
/* Member k of array A, or NULL. */
Object *array_member(const ObjArray *A, long k);
/* An object statement naming members of an array (s->arr): declares them, reads them from a data file,
 * or sets a property of them. */
void array_stmt(Stmt *s);
/* The member array[idx] in context C (idx built there: numbers, globals, the index name), or NULL after
 * an error at l (C->failed set). */
Object *array_at(Ctx *C, const char *array, Expr *idx, Loc l);
/* The object a `for` list names (reports and returns NULL if none): r->idx resolved with the index
 * binding of sema (Sema.ivar). */
Object *objref_object(ObjRef *r);
/* Is a `for` list's index name the free name of its member indices (`for node[i], node[i+1]`)? Sets
 * s->ivar; returns 1 (0: the list names no member by a name, -1 after an error). */
int for_indexed(Stmt *s);
/* The range of the index name of s (for_indexed) for which every member it names exists: [*from, *to],
 * empty if *from > *to. 0 after an error. */
int for_index_range(Stmt *s, long *from, long *to);
/* Can rule s be one loop over its bindings (Stmt.loop)? A plain equation, its `for` list every member
 * of one array at the index name plus a whole number, and its equation naming members only so (and
 * not the index name as a number). Returns the number of bindings (at least 2; their first index in
 * *from), else 0. */
long for_loopable(Stmt *s, long *from);
/* The array whose members s's `for` list names (for_loopable). */
ObjArray *for_array(Stmt *s);
/* Does expression x read the name n? */
int expr_reads_name(const Expr *x, const char *n);

/* ---- walk.c: the expressions of a statement ---- */

/* Calls f on every expression of statement s: its condition, its call, its steps'. As eqns_each. */
int stmt_each(Stmt *s, ExprFn f, void *ctx);

/* ---- shapes.c: shapes ---- */

/*
 * Groups the objects into shapes: by the names, types and dimensions of
 * their properties, in order (what decides which rules apply to an object
 * and how each resolves). By object (not shaped), or when a rule, a `for`
 * list or the watch list names the object and one of its temporaries, an
 * object is a shape of its own.
 */
void build_shapes(Stmt *start);

/* ---- instances.c: rule instances ---- */

int stmt_reads_rf(Stmt *s);

/* Calls f for every binding the statement applies to; returns how many, -1 after an error. */
int for_each_binding(Stmt *s, void (*f)(Stmt *, Object **, int));

int add_src(Loc l, char *text);
Inst *new_inst(Stmt *s, Object **bind, int nbind);
const char *var_label(Var *v);
int determined(Var *v);

/* The places ($n) at which e reads x, as bits 1 << (place + 1). */
unsigned var_places(const RExpr *e, const Var *x);

void explain_det(Var *v);

/* ---- solve.c: solving ---- */

/* Solves lhs = rhs for x. Returns NULL (after an error) when it cannot. */
RExpr *solve(RExpr *lhs, RExpr *rhs, Var *x, Loc l, const char *text);

/* The most rules solved together, as one linear system (csf(5), RULES). */
#define SOLVE_MAX 3

/*
 * Solves the rules lhs[i] = rhs[i] (i < k, 2 <= k <= SOLVE_MAX; text[i] as written) together
 * for x[0..k): returns the values of x[0..k) (arena), expressions of what the rules read
 * besides; NULL after an error at l or in a rule, which begins with what (which rules
 * determine which unknowns together): a rule not linear in them, the vector and scalar
 * rules mixed, a system that is singular at compile time. nz[i*k + j]: x[j]'s coefficient in
 * rule i is not zero (a constant 0).
 */
RExpr **solve_system(RExpr **lhs, RExpr **rhs, char **text, Var *const *x, int k, Loc l, const char *what, int *nz);

/* ---- resolve.c: resolving one rule instance ---- */

int stmt_src(Stmt *s);
void inst_rule(Stmt *s, Object **bind, int nbind);
void inst_deriv(Stmt *s, Object **bind, int nbind);

/* Records that instance I solves equation q (its sides lhs, rhs) for x: x := sol, an assignment
 * into branch from source entry src; reads (all but x) and rf (objects whose RF it reads)
 * become I's. x is determined from here on. */
void resolve_assign(Inst *I, Var *x, RExpr *sol, RExpr *lhs, RExpr *rhs, Eqn *q, int src, Vec *branch, Vec *reads, Vec *rf);
void resolve_deriv(Inst *I);
void inst_assert(Stmt *s, Object **bind, int nbind);

/*
 * stop when COND: a terminal event. COND is one comparison, located in
 * time like a conditional rule's; its instance is computed in RHS (where
 * the runtime reads the guards), never in OUT.
 */
void inst_stop(Stmt *s, Object **bind, int nbind);
void inst_when(Stmt *s, Object **bind, int nbind);

/* ---- group.c: rules solved together ---- */

/*
 * Rule instance I (a plain rule), its equation q built as lhs = rhs reading reads and the RF of
 * rf, has two unknowns or more (temporaries no rule has determined, registered): it waits. When
 * it and other waiting rules determine their unknowns together, they are solved (pushed to
 * sema.cur_insts), here or at a later rule; msg is reported at at if that never happens
 * (suggests: it suggests a name for a misspelt one, the likelier mistake).
 */
void group_wait(Inst *I, Eqn *q, RExpr *lhs, RExpr *rhs, Vec *reads, Vec *rf, Vec *unknowns, Loc at, const char *msg,
                int suggests);

/* After the last rule: reports the rules that still wait (each as the error it would have been
 * had it not waited; too many unknowns to solve together). */
void group_finish(void);

/* ---- contacts.c: contact rules ---- */

/* Is the rule's call the contact routine, with properties for arguments? Reports if not. */
int check_call(Stmt *s);

/* Rule s with `for`: the pair (bind[0], bind[1]), unless it is two points (they never touch) or its $0 is
 * an anchor. */
void inst_contact(Stmt *s, Object **bind, int nbind);

/*
 * A contact rule without `for`: every mass point with its geometry as $0,
 * every object with its geometry as $1, in the order of definition; the
 * first binding that is an error is reported instead. Kept only if one of
 * its pairs can touch: a mass point and a plane (of another object), or
 * two mass points, or a mass point and an anchor, the sum of whose radii
 * is positive.
 */
void contact_pairs(Stmt *s);
/* Is object index left out in this resolution (the one mid/cone.c asks for without them)? */
int sema_dropping(int index);

/* Every mass point of a contact rule must have its a determined (by Newton's second law). */
void contact_accels(void);

/* ---- diff.c: derivatives ---- */

/* A direction: the rate of each variable (an R_VAR; NULL: zero), what is differentiated (for messages). */
typedef struct Dir Dir;
struct Dir {
	RExpr *(*rate)(Dir *D, RExpr *var);
	const char *what;
	int failed;      /* an error was reported */
	void *ctx;
};
/* The derivative of e along D (NULL: zero); reports, once, an operation that has none (D->failed). */
RExpr *diff(Dir *D, RExpr *e);

/* ---- constraints.c: rules with attribute C ---- */

/* Is s a constraint (attribute C)? Checks its form (one equation, or a one-sided comparison); reports if not. */
int is_constraint(Stmt *s);
/* The constraint of one binding of rule s. */
void inst_constraint(Stmt *s, Object **bind, int nbind);
/* After every rule is resolved: what each constraint reads, its bodies, its derivatives. */
void constraints_finish(void);

/* ---- watch.c: the watch list ---- */

void build_watch(Stmt *st);

#endif
