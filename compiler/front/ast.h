/*
 * ast.h - the syntax tree the parser builds. Nothing here is resolved:
 * names are strings, units are already converted to SI factors.
 */
#ifndef CSF_AST_H
#define CSF_AST_H

#include "csfc.h"

typedef enum ExprKind {
	E_NUM,    /* num */
	E_NAME,   /* name */
	E_DOLLAR, /* name$n */
	E_FIELD,  /* a.name: object property, vector component, or method without () */
	E_METHOD, /* a.name(args) */
	E_CALL,   /* name(args) */
	E_VEC,    /* (args[0], args[1], args[2]) */
	E_UNIT,   /* a with unit */
	E_BIN,    /* a op b; op is a token code */
	E_NEG,    /* -a */
	E_NOT,    /* not a */
	E_INDEX,  /* name[a]: a member of the object array name */
	E_SUM,    /* sum(a for name): a summed over the members of the object array name */
	E_LIT     /* a number with a unit, `num unit`, or (lit not NULL) a vector of numbers with one,
	             `(n1, n2, n3) unit`, each ni a number or a negated one: the value E_UNIT over E_NUM or
	             E_VEC would be, built the same way (one node, not two, or six to nine: the masses,
	             positions and velocities of a scene written out object by object) */
} ExprKind;

/* An E_LIT's numbers, as written: the components' values and places, whether each is negated and
 * where its '-' is, the place of the '('. */
typedef struct Lit {
	double v[3];
	Loc at[3], neg_at[3];
	Loc vec_at;
	unsigned char neg[3];
} Lit;

typedef struct Expr Expr;
struct Expr { /* (the fields in an order without holes) */
	ExprKind kind;
	int op;
	Loc loc;
	int n;
	int nargs;
	int depth;   /* levels of the tree below and including this node (at most CSF_MAX_DEPTH + 1) */
	double num;
	char *name;
	Unit unit;
	char *unit_text;
	Expr *a, *b;
	union {
		Expr **args; /* nargs of them */
		Lit *lit;    /* E_LIT of a vector */
	};
};

typedef struct If If;

/* One step of a rule: an equation, or (nest set; lhs and rhs NULL) a conditional block. */
typedef struct Eqn Eqn;
struct Eqn {
	Loc loc;
	Expr *lhs; /* for a derivative: the E_NAME whose derivative is set */
	int deriv;
	Expr *rhs;
	char *text;
	If *nest;
	Eqn *next;
};

/* A conditional block: `if COND:` (or `elif COND:`) with its indented steps, then its else part:
 * `else:` with its steps, or an `elif` (a block nested as the whole else part), or nothing. */
struct If {
	Loc loc;       /* of 'if' or 'elif' */
	char *text;    /* "if COND:" as written */
	Expr *cond;
	Eqn *then, *els;
	Loc else_loc;  /* of 'else' (els neither empty nor an elif) */
	int elif;      /* this block is an `elif` */
};

/* name, or index >= 0; idx not NULL: the member name[idx] of an object array (idx may read the
 * rule's index name: `for node[i], node[i+1]`) */
typedef struct ObjRef { Loc loc; char *name; int index; Expr *idx; } ObjRef;
/* obj may be NULL, an object, a member ("star[3]") or an object array (every member); comp: a vector's component (x, y or z), or NULL for the whole variable */
typedef struct WatchItem { Loc loc; char *obj; char *prop; char *comp; } WatchItem;

/* How an object statement names its object: one object, or members of an object array (DECISIONS §11):
 * NAME[A..B] declares them, NAME[I] (I the index name) sets every member, NAME[K] one, NAME[] reads
 * them from a data file. */
enum { ARR_NONE, ARR_RANGE, ARR_EACH, ARR_ONE, ARR_FILE };

typedef enum StmtKind {
	S_GLOBAL, S_PROP, S_OBJKIND, S_DEF, S_VECDECL, S_RULE, S_ASSERT, S_STOP, S_WHEN, S_START
} StmtKind;

typedef struct Stmt Stmt;
struct Stmt {
	StmtKind kind;
	Loc loc;
	char *text;   /* the statement's source text, for diagnostics */
	char *name;   /* global, object, kind; S_VECDECL: first of names */
	Loc name_loc;
	int arr;      /* S_OBJKIND, S_PROP: ARR_NONE, or how it names members of the array `name` */
	char *prop;   /* S_PROP; S_OBJKIND: the kind */
	Loc prop_loc;
	int isvec;
	Expr *value;
	Expr *atol;   /* S_PROP of an object: `atol A` after the value, or NULL */
	long lo, hi;  /* ARR_RANGE: the indices A..B; ARR_ONE: the index K (lo) */
	char *ivar;   /* ARR_EACH: the index name; a rule whose `for` list indexes members: its index name
	                 (sema sets it) */
	char *from;   /* ARR_FILE: the data file, as written */
	Stmt *body;   /* S_DEF: its property lines (S_PROP with name NULL) */
	Vec names;    /* S_VECDECL: char*; */
	char *attr;
	Vec fors;     /* of ObjRef* */
	int has_for;
	int once;     /* a rule, assertion or stop without `for` that reads nothing of an object it would bind
	                 (globals, t, NAME.PROP, sums): it applies once, bound to the first object (sema) */
	long loop;    /* a rule whose `for` list names neighbours of one array (`for node[i], node[i+1]`) whose
	                 members are one shape in index order: how many bindings, compiled as one loop over
	                 them (sema sets it; 0: one instance per binding) */
	long loop_from; /* its first binding's index value */
	Expr *cond;   /* assertion, stop condition, `when` condition */
	Eqn *eqns;    /* rule: its one step (an equation, or a conditional block); `when`: its assignments */
	Expr *call;   /* a rule that calls a runtime routine: contact(...) */
	/* S_START */
	char *var;
	Expr *till, *by;
	Vec watch;    /* of WatchItem* */
	int has_watch;
	Stmt *next;
};

Expr *ast_expr(ExprKind k, Loc l);
/* Gives back node e, which nothing points to any more (the parser folded it into an E_LIT): the next
 * ast_expr reuses it. */
void ast_free(Expr *e);

/* Parses a whole file (with its `using` inclusions) into a statement list. */
Stmt *parse_file(int file);

#endif
