/*
 * parse.y - the CSF grammar (bison). It builds the AST and nothing else:
 * names are resolved, rules solved and units checked by later passes.
 * Tokens come from layout.c (indentation, inclusion and unit literals on
 * top of the re2c scanner). Errors recover at the end of the line, so one
 * run reports several; a token the scanner already reported is not
 * reported again.
 */
%code requires {
#include "csfc.h"
#include "ast.h"
typedef struct YYLoc { int file, first_line, first_column, last_line, last_column; } YYLoc;
#define YYLLOC_DEFAULT(Cur, Rhs, N) \
	do { \
		if (N) { \
			(Cur).file = YYRHSLOC(Rhs, 1).file; \
			(Cur).first_line = YYRHSLOC(Rhs, 1).first_line; \
			(Cur).first_column = YYRHSLOC(Rhs, 1).first_column; \
			(Cur).last_line = YYRHSLOC(Rhs, N).last_line; \
			(Cur).last_column = YYRHSLOC(Rhs, N).last_column; \
		} else { \
			(Cur) = YYRHSLOC(Rhs, 0); \
			(Cur).first_line = (Cur).last_line; \
			(Cur).first_column = (Cur).last_column; \
		} \
	} while (0)
typedef struct Parser Parser;
/* How an object statement names its object (Stmt.arr). */
typedef struct ObjName { char *name; YYLoc loc; int arr; long lo, hi; char *ivar; } ObjName;
/* A unit literal (layout.c): its SI factor and dimension, its spelling and place. */
typedef struct UnitTok { Unit unit; char *text; Loc loc; } UnitTok;
}

%code provides {
int yylex(YYSTYPE *lval, YYLoc *lloc, Parser *P);
/* The layout layer's state (layout.c). */
Parser *layout_new(int file);
Stmt *layout_result(Parser *P);
void layout_append(Parser *P, Stmt *s);
const char *layout_token_text(Parser *P);
void layout_skip_block(Parser *P);
int layout_reported(Parser *P, Loc l);
}

%code {
#include <ctype.h>
#include <math.h>
#include <string.h>
static Loc LOC(YYLoc l) { return (Loc){ l.file, l.first_line, l.first_column }; }
/* Sets e's depth from its children's; the first node past CSF_MAX_DEPTH is an error (the later
 * passes walk expressions recursively, so depth must be bounded). */
static Expr *nest(Expr *e)
{
	int d = 0;
	if (e->a && e->a->depth > d) d = e->a->depth;
	if (e->b && e->b->depth > d) d = e->b->depth;
	for (int i = 0; i < e->nargs; i++)
		if (e->args[i]->depth > d) d = e->args[i]->depth;
	e->depth = d > CSF_MAX_DEPTH ? d : d + 1;
	if (e->depth == CSF_MAX_DEPTH + 1 && d == CSF_MAX_DEPTH)
		error_at(e->loc, "expression nested more than %d levels deep: split it with temporaries", CSF_MAX_DEPTH);
	return e;
}
/* A list built backwards (each new item in front), in order. */
static Stmt *stmts_reversed(Stmt *s)
{
	Stmt *r = NULL;
	while (s) {
		Stmt *n = s->next;
		s->next = r;
		r = s;
		s = n;
	}
	return r;
}
static Eqn *eqns_reversed(Eqn *q)
{
	Eqn *r = NULL;
	while (q) {
		Eqn *n = q->next;
		q->next = r;
		r = q;
		q = n;
	}
	return r;
}
static Expr *bin(int op, Expr *a, Expr *b, YYLoc l)
{
	Expr *e = ast_expr(E_BIN, LOC(l));
	e->op = op;
	e->a = a;
	e->b = b;
	return nest(e);
}
static Expr *with_unit(Expr *a, UnitTok u)
{
	Expr *e = ast_expr(E_UNIT, u.loc);
	e->a = a;
	e->unit = u.unit;
	e->unit_text = u.text;
	return nest(e);
}
/* The rest of the line from l, without a comment or trailing blanks. */
static char *text_from(Loc l)
{
	char *s = src_line(l.file, l.line);
	char *p = s + (l.col - 1 <= (int)strlen(s) ? l.col - 1 : (int)strlen(s));
	char *h = strchr(p, '#');
	if (h) *h = '\0';
	size_t n = strlen(p);
	while (n && (p[n - 1] == ' ' || p[n - 1] == '\t' || p[n - 1] == '\r')) p[--n] = '\0';
	return p;
}
static Stmt *stmt(StmtKind k, YYLoc l)
{
	Stmt *s = xalloc(sizeof *s);
	s->kind = k;
	s->loc = LOC(l);
	if (k == S_RULE) s->text = text_from(s->loc); /* what diagnostics and --explain quote (assertions set theirs) */
	return s;
}
static Eqn *eqn(Expr *lhs, int deriv, Expr *rhs, YYLoc l)
{
	Eqn *q = xalloc(sizeof *q);
	q->loc = LOC(l);
	q->lhs = lhs;
	q->deriv = deriv;
	q->rhs = rhs;
	q->text = text_from(q->loc);
	return q;
}
/* The step holding the block `if cond:` at l with the steps then and the else part rest (NULL: none). */
static Eqn *cond_block(YYLoc l, Expr *cond, Eqn *then, If *rest)
{
	If *f = xalloc(sizeof *f);
	f->loc = LOC(l);
	f->text = text_from(f->loc);
	f->cond = cond;
	f->then = then;
	if (rest) {
		f->els = rest->els;
		f->else_loc = rest->else_loc;
	}
	Eqn *q = xalloc(sizeof *q);
	q->loc = f->loc;
	q->text = f->text;
	q->nest = f;
	return q;
}
/* A `when` statement at l: condition cond (its text up to the ':' at colon), the objects fors (NULL: none),
 * its assignments q. */
static Stmt *when_stmt(YYLoc l, Expr *cond, YYLoc colon, Vec *fors, Eqn *q)
{
	Stmt *s = xalloc(sizeof *s);
	s->kind = S_WHEN;
	s->loc = LOC(l);
	s->cond = cond;
	s->eqns = q;
	if (fors) {
		s->fors = *fors;
		s->has_for = 1;
	}
	char *line = src_line(s->loc.file, s->loc.line);
	size_t a = (size_t)(s->loc.col - 1), b = (size_t)(colon.first_column - 1), n = strlen(line);
	if (colon.first_line != s->loc.line || b > n) b = n;
	if (a > b) a = b;
	while (b > a && line[b - 1] == ' ') b--;
	s->text = xstrndup(line + a, b - a); /* "when COND" (with `for`: "when for OBJS: COND") */
	return s;
}
/* Is x a number, or a negated number, that an E_LIT can hold? */
static int lit_part(const Expr *x) { return x->kind == E_NUM || (x->kind == E_NEG && x->a->kind == E_NUM); }
/* (a, b, c) u, the '(' at l: one E_LIT if a, b and c are numbers (their nodes given back), else E_UNIT over E_VEC. */
static Expr *vec_unit(YYLoc l, Expr *a, Expr *b, Expr *c, UnitTok u)
{
	Expr *x[3] = { a, b, c };
	if (!lit_part(a) || !lit_part(b) || !lit_part(c)) {
		Expr *v = ast_expr(E_VEC, LOC(l));
		v->args = xalloc(3 * sizeof(Expr *));
		v->nargs = 3;
		for (int i = 0; i < 3; i++) v->args[i] = x[i];
		return with_unit(nest(v), u);
	}
	Lit *L = xalloc(sizeof *L);
	int depth = 1;
	for (int i = 0; i < 3; i++) {
		Expr *n = x[i];
		if (n->kind == E_NEG) {
			L->neg[i] = 1;
			L->neg_at[i] = n->loc;
			n = n->a;
			ast_free(x[i]);
			depth = 2;
		}
		L->v[i] = n->num;
		L->at[i] = n->loc;
		ast_free(n);
	}
	L->vec_at = LOC(l);
	Expr *e = ast_expr(E_LIT, u.loc);
	e->lit = L;
	e->unit = u.unit;
	e->unit_text = u.text;
	e->depth = depth + 2; /* as E_UNIT over E_VEC */
	return e;
}
static Expr *call(ExprKind k, Expr *recv, char *name, Vec *args, YYLoc l)
{
	Expr *e = ast_expr(k, LOC(l));
	e->a = recv;
	e->name = name;
	e->args = (Expr **)args->v;
	e->nargs = args->n;
	return nest(e);
}
static void yyerror(YYLoc *l, Parser *P, const char *msg);


/* An object statement of kind k naming n. */
static Stmt *obj_stmt(StmtKind k, YYLoc l, ObjName *n)
{
	Stmt *s = stmt(k, l);
	s->name = n->name;
	s->name_loc = LOC(n->loc);
	s->arr = n->arr;
	s->lo = n->lo;
	s->hi = n->hi;
	s->ivar = n->ivar;
	return s;
}

/* An index of an object array, written as a number: a whole number of at most 9 digits. */
static long array_index(double x, YYLoc l)
{
	if (x != floor(x) || fabs(x) >= 1e9) {
		error_at(LOC(l), "an object index must be a whole number of at most 9 digits");
		return 0;
	}
	return (long)x;
}
}

%define api.pure full
%define api.location.type {YYLoc}
%locations
%define parse.error custom
%expect 0
%parse-param {Parser *P}
%lex-param {Parser *P}

%union {
	double num;
	char *str;
	int n;
	UnitTok unit; /* (by value, as the object name: nothing allocated for each) */
	Expr *expr;
	Eqn *eqn;
	If *cond;
	Stmt *stmt;
	ObjRef *ref;
	WatchItem *watch;
	ObjName oname;
	long idx;
	Vec vec;
}

%token END 0 "end of file"
%token <num> NUMBER "number"
%token <str> IDENT "name"
%token <n> DOLLAR "object number ($n)"
%token <unit> UNIT "unit"
%token NEWLINE "end of line"
%token INDENT "indented block"
%token DEDENT "end of indented block"
%token LEXERROR "invalid token"
%token <str> PROTECTED "protected name"
%token USING "'using'"
%token OBJECT "'object'" DEF "'def'" GLOBAL "'global'" RULE "'rule'" FOR "'for'"
%token STOP "'stop'" WHEN "'when'"
%token IF "'if'" ELIF "'elif'" ELSE "'else'" ASSERT "'assert'" VECTOR "'vector'" INC "'inc'"
%token TILL "'till'" BY "'by'" WATCH "'watch'" AND "'and'" OR "'or'" NOT "'not'"
%token ATOL "'atol'"
%token DOTDOT "'..'"
%token <str> STRING "string"
%token EQEQ "'=='" NE "'!='" LE "'<='" GE "'>='"

%left OR
%left AND
%precedence NOT
%nonassoc '<' '>' LE GE EQEQ NE
%left '+' '-'
%left '*' '/'
%precedence UMINUS
%right '^'

%type <expr> expr postfix primary
%type <eqn> eqn steps step body ifblock
%type <cond> elsepart
%type <stmt> stmt block defprop defprops
%type <vec> args args1 names objrefs watches
%type <ref> objref
%type <watch> watch
%type <oname> objname
%type <idx> index
%type <str> attr
%type <expr> till by atol

%%

file:
	  %empty
	| file line
	;

line:
	  NEWLINE
	| stmt NEWLINE       { if ($1) layout_append(P, $1); }
	| block              { if ($1) layout_append(P, $1); }
	| error NEWLINE      { yyerrok; layout_skip_block(P); }
	;

stmt:
	  GLOBAL IDENT '=' expr {
		$$ = stmt(S_GLOBAL, @$); $$->name = $2; $$->name_loc = LOC(@2); $$->value = $4;
	}
	| OBJECT objname ':' IDENT {
		$$ = obj_stmt(S_OBJKIND, @$, &$2); $$->prop = $4; $$->prop_loc = LOC(@4);
	}
	| OBJECT objname ':' IDENT STRING {
		$$ = obj_stmt(S_OBJKIND, @$, &$2); $$->prop = $4; $$->prop_loc = LOC(@4); $$->from = $5;
		if (strcmp($4, "from") != 0) {
			error_at(LOC(@4), "a string after ':' reads a data file: 'object %s[]: from \"%s\"'", $2.name, $5);
			$$ = NULL;
		} else if ($2.arr != ARR_FILE) {
			error_at(LOC(@2), "the members read from a data file are numbered by its rows: 'object %s[]: from \"%s\"'",
			         $2.name, $5);
			$$ = NULL;
		} /* else the members, one per data row: objects.c */
	}
	| OBJECT objname ':' IDENT '=' expr atol {
		$$ = obj_stmt(S_PROP, @$, &$2); $$->prop = $4; $$->prop_loc = LOC(@4);
		$$->value = $6; $$->atol = $7;
	}
	| OBJECT objname ':' VECTOR IDENT '=' expr atol {
		$$ = obj_stmt(S_PROP, @$, &$2); $$->prop = $5; $$->prop_loc = LOC(@5);
		$$->value = $7; $$->isvec = 1; $$->atol = $8;
	}
	| VECTOR names {
		$$ = stmt(S_VECDECL, @$); $$->names = $2;
	}
	| RULE attr ':' eqn {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->eqns = $4;
	}
	| RULE attr FOR objrefs ':' eqn {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->fors = $4; $$->has_for = 1; $$->eqns = $6;
	}
	| RULE attr ':' expr {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->call = $4;
	}
	| RULE attr FOR objrefs ':' expr {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->fors = $4; $$->has_for = 1; $$->call = $6;
	}
	| ASSERT expr {
		$$ = stmt(S_ASSERT, @$); $$->cond = $2; $$->text = text_from(LOC(@2));
	}
	| WHEN expr ':' eqn                   { $$ = when_stmt(@1, $2, @3, NULL, $4); }
	| WHEN FOR objrefs ':' expr ':' eqn   { $$ = when_stmt(@1, $5, @6, &$3, $7); }
	| STOP WHEN expr {
		$$ = stmt(S_STOP, @$); $$->cond = $3; $$->text = text_from(LOC(@3));
	}
	| INC IDENT till by {
		$$ = stmt(S_START, @$); $$->var = $2; $$->name_loc = LOC(@2); $$->till = $3; $$->by = $4;
	}
	| INC IDENT till by WATCH watches {
		$$ = stmt(S_START, @$); $$->var = $2; $$->name_loc = LOC(@2); $$->till = $3; $$->by = $4;
		$$->watch = $6; $$->has_watch = 1;
	}
	;

/* An object, or members of an object array (DECISIONS §11). */
objname:
	  IDENT                { $$ = (ObjName){ .name = $1, .loc = @1 }; }
	| IDENT '[' index ']'  { $$ = (ObjName){ .name = $1, .loc = @1, .arr = ARR_ONE, .lo = $3 }; }
	| IDENT '[' index DOTDOT index ']' {
		$$ = (ObjName){ .name = $1, .loc = @1, .arr = ARR_RANGE, .lo = $3, .hi = $5 };
		if ($5 < $3) error_at(LOC(@5), "an object array 'NAME[A..B]' needs A <= B, not %ld..%ld", $3, $5);
		else if ($5 - $3 >= 100000000) error_at(LOC(@5), "an object array has at most 100000000 members");
	}
	| IDENT '[' IDENT ']'  { $$ = (ObjName){ .name = $1, .loc = @1, .arr = ARR_EACH, .ivar = $3 }; }
	| IDENT '[' ']'        { $$ = (ObjName){ .name = $1, .loc = @1, .arr = ARR_FILE }; }
	;

index:
	  NUMBER               { $$ = array_index($1, @1); }
	| '-' NUMBER           { $$ = -array_index($2, @2); }
	;

till: %empty { $$ = NULL; } | TILL expr { $$ = $2; } ;

/* `atol A` after a property's value: its absolute tolerance (ATOL: layout.c). */
atol: %empty { $$ = NULL; } | ATOL expr { $$ = $2; } ;
by:   %empty { $$ = NULL; } | BY expr   { $$ = $2; } ;

attr: %empty { $$ = NULL; } | IDENT { $$ = $1; } ;

block:
	  DEF IDENT ':' NEWLINE INDENT defprops DEDENT {
		$$ = stmt(S_DEF, @$); $$->name = $2; $$->name_loc = LOC(@2); $$->body = stmts_reversed($6);
	}
	| RULE attr ':' ifblock {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->eqns = $4;
	}
	| RULE attr FOR objrefs ':' ifblock {
		$$ = stmt(S_RULE, @$); $$->attr = $2; $$->fors = $4; $$->has_for = 1; $$->eqns = $6;
	}
	| WHEN expr ':' body                  { $$ = when_stmt(@1, $2, @3, NULL, $4); }
	| WHEN FOR objrefs ':' expr ':' body  { $$ = when_stmt(@1, $5, @6, &$3, $7); }
	;

/* A conditional block, as one step (an Eqn holding it); `elif` is a block nested as the else part. */
ifblock:
	  IF expr ':' body elsepart { $$ = cond_block(@1, $2, $4, $5); }
	;

/* The else part of a block: els and else_loc of an If (NULL: none). */
elsepart:
	  %empty             { $$ = NULL; }
	| ELSE ':' body      { $$ = xalloc(sizeof *$$); $$->els = $3; $$->else_loc = LOC(@1); }
	| ELIF expr ':' body elsepart {
		$$ = xalloc(sizeof *$$); $$->els = cond_block(@1, $2, $4, $5); $$->els->nest->elif = 1;
	}
	;

body:
	  NEWLINE INDENT steps DEDENT { $$ = eqns_reversed($3); }
	;

defprops:
	  defprop            { $$ = $1; }
	| defprops defprop   { $$ = $1; if ($2) { $2->next = $$; $$ = $2; } } /* backwards: reversed by block */
	;

defprop:
	  IDENT '=' expr NEWLINE {
		$$ = stmt(S_PROP, @$); $$->prop = $1; $$->prop_loc = LOC(@1); $$->value = $3;
	}
	| VECTOR IDENT '=' expr NEWLINE {
		$$ = stmt(S_PROP, @$); $$->prop = $2; $$->prop_loc = LOC(@2); $$->value = $4; $$->isvec = 1;
	}
	| error NEWLINE { $$ = NULL; yyerrok; layout_skip_block(P); }
	;

steps:
	  step               { $$ = $1; }
	| steps step         { $$ = $1; if ($2) { $2->next = $$; $$ = $2; } } /* backwards: reversed by body */
	;

step:
	  eqn NEWLINE        { $$ = $1; }
	| ifblock            { $$ = $1; }
	| error NEWLINE      { $$ = NULL; yyerrok; layout_skip_block(P); }
	;

eqn:
	  expr '=' expr      { $$ = eqn($1, 0, $3, @$); }
	| expr '\'' '=' expr {
		/* the derivative of a name of the rule's own objects; of anything else, one clear error */
		$$ = NULL;
		if ($1->kind == E_NAME) $$ = eqn($1, 1, $4, @$);
		else if ($1->kind == E_FIELD && $1->a->kind == E_NAME)
			error_at(LOC(@2), "a derivative is written for the rule's own objects: 'rule for %s: %s' = ...', not "
			         "'%s.%s' = ...'", $1->a->name, $1->name, $1->a->name, $1->name);
		else
			error_at(LOC(@2), "only a name can have a derivative ('v' = a')");
	}
	;

names:
	  IDENT              { $$ = (Vec){ 0 }; vec_push(&$$, $1); }
	| names ',' IDENT    { $$ = $1; vec_push(&$$, $3); }
	;

objrefs:
	  objref             { $$ = (Vec){ 0 }; vec_push(&$$, $1); }
	| objrefs ',' objref { $$ = $1; vec_push(&$$, $3); }
	;

objref:
	  IDENT  { $$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->name = $1; $$->index = -1; }
	| NUMBER { $$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->index = $1 >= 0 && $1 < 1e9 ? (int)$1 : 1000000000;
	           if ($$->index != $1) error_at($$->loc, "object number must be a whole number"); }
	| IDENT '[' expr ']' { $$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->name = $1; $$->index = -1; $$->idx = $3; }
	;

watches:
	  watch              { $$ = (Vec){ 0 }; vec_push(&$$, $1); }
	| watches ',' watch  { $$ = $1; vec_push(&$$, $3); }
	;

watch:
	  IDENT              { $$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->prop = $1; }
	| IDENT '.' IDENT    { $$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->obj = $1; $$->prop = $3; }
	| IDENT '.' IDENT '.' IDENT {
		$$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->obj = $1; $$->prop = $3; $$->comp = $5;
	}
	| IDENT '[' index ']' '.' IDENT {
		$$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->obj = xprintf("%s[%ld]", $1, $3); $$->prop = $6;
	}
	| IDENT '[' index ']' '.' IDENT '.' IDENT {
		$$ = xalloc(sizeof *$$); $$->loc = LOC(@1); $$->obj = xprintf("%s[%ld]", $1, $3); $$->prop = $6; $$->comp = $8;
	}
	;

expr:
	  expr OR expr       { $$ = bin(OR, $1, $3, @2); }
	| expr AND expr      { $$ = bin(AND, $1, $3, @2); }
	| NOT expr           { $$ = ast_expr(E_NOT, LOC(@1)); $$->a = $2; $$ = nest($$); }
	| expr '<' expr      { $$ = bin('<', $1, $3, @2); }
	| expr '>' expr      { $$ = bin('>', $1, $3, @2); }
	| expr LE expr       { $$ = bin(LE, $1, $3, @2); }
	| expr GE expr       { $$ = bin(GE, $1, $3, @2); }
	| expr EQEQ expr     { $$ = bin(EQEQ, $1, $3, @2); }
	| expr NE expr       { $$ = bin(NE, $1, $3, @2); }
	| expr '+' expr      { $$ = bin('+', $1, $3, @2); }
	| expr '-' expr      { $$ = bin('-', $1, $3, @2); }
	| expr '*' expr      { $$ = bin('*', $1, $3, @2); }
	| expr '/' expr      { $$ = bin('/', $1, $3, @2); }
	| expr '^' expr      { $$ = bin('^', $1, $3, @2); }
	| '-' expr %prec UMINUS { $$ = ast_expr(E_NEG, LOC(@1)); $$->a = $2; $$ = nest($$); }
	| '+' expr %prec UMINUS { $$ = $2; }
	| postfix
	;

postfix:
	  primary
	| postfix '.' IDENT  { $$ = ast_expr(E_FIELD, LOC(@3)); $$->a = $1; $$->name = $3; $$ = nest($$); }
	| postfix '.' IDENT '(' args ')' { $$ = call(E_METHOD, $1, $3, &$5, @3); }
	;

primary:
	  NUMBER             { $$ = ast_expr(E_NUM, LOC(@1)); $$->num = $1; $$->depth = 1; }
	| NUMBER UNIT {
		$$ = ast_expr(E_LIT, $2.loc); $$->num = $1; $$->unit = $2.unit; $$->unit_text = $2.text; $$->depth = 2;
	}
	| IDENT              { $$ = ast_expr(E_NAME, LOC(@1)); $$->name = $1; $$->depth = 1; }
	| IDENT DOLLAR       { $$ = ast_expr(E_DOLLAR, LOC(@1)); $$->name = $1; $$->n = $2; $$->depth = 1; }
	| IDENT '(' args ')' { $$ = call(E_CALL, NULL, $1, &$3, @1); }
	| IDENT '(' expr FOR IDENT ')' {
		/* sum(EXPR for NAME): over the members of an object array */
		$$ = ast_expr(E_SUM, LOC(@1)); $$->name = $5; $$->a = $3; $$ = nest($$);
		if (strcmp($1, "sum") != 0) error_at(LOC(@1), "'%s(... for %s)': only 'sum' runs over the members of an object array", $1, $5);
	}
	| IDENT '[' expr ']' { $$ = ast_expr(E_INDEX, LOC(@1)); $$->name = $1; $$->a = $3; $$ = nest($$); }
	| IDENT '(' args ')' UNIT { $$ = with_unit(call(E_CALL, NULL, $1, &$3, @1), $5); }
	| '(' expr ')'       { $$ = $2; }
	| '(' expr ')' UNIT  { $$ = with_unit($2, $4); }
	| '(' expr ',' expr ',' expr ')' {
		$$ = ast_expr(E_VEC, LOC(@1)); $$->args = xalloc(3 * sizeof(Expr *)); $$->nargs = 3;
		$$->args[0] = $2; $$->args[1] = $4; $$->args[2] = $6; $$ = nest($$);
	}
	| '(' expr ',' expr ',' expr ')' UNIT { $$ = vec_unit(@1, $2, $4, $6, $8); }
	;

args:
	  %empty             { $$ = (Vec){ 0 }; }
	| args1
	;

args1:
	  expr               { $$ = (Vec){ 0 }; vec_push(&$$, $1); }
	| args1 ',' expr     { $$ = $1; vec_push(&$$, $3); }
	;

%%

/* Is l the first token of its line? */
static int starts_line(Loc l)
{
	const char *line = src_line(l.file, l.line);
	for (int c = 0; c < l.col - 1 && line[c]; c++)
		if (line[c] != ' ') return 0;
	return 1;
}

static void yyerror(YYLoc *l, Parser *P, const char *msg)
{
	(void)P;
	if (!strcmp(msg, "memory exhausted")) /* the parser's stack: YYMAXDEPTH */
		error_at(LOC(*l), "expression nested more than %d levels deep: split it with temporaries", YYMAXDEPTH / 2);
	else
		error_at(LOC(*l), "%s", msg);
}

static int yyreport_syntax_error(const yypcontext_t *ctx, Parser *P)
{
	yysymbol_kind_t got = yypcontext_token(ctx);
	Loc l = LOC(*yypcontext_location(ctx));
	if (got == YYSYMBOL_LEXERROR || layout_reported(P, l)) return 0; /* the scanner or the layout reported it */
	if ((got == YYSYMBOL_ELIF || got == YYSYMBOL_ELSE) && starts_line(l)) {
		error_at(l, "'%s' without an 'if' block before it at this indentation ('elif' and 'else' line up with "
		            "their 'if', or with 'rule' for the rule's own)", got == YYSYMBOL_ELIF ? "elif" : "else");
		return 0;
	}
	if (got == YYSYMBOL_IF && starts_line(l)) {
		error_at(l, "an 'if' block belongs to a conditional rule ('rule: if CONDITION:', or nested in one of its branches)");
		return 0;
	}
	yysymbol_kind_t exp[6];
	int n = yypcontext_expected_tokens(ctx, exp, 6);
	int wants_name = 0;
	for (int i = 0; i < n && i < 6; i++) wants_name |= exp[i] == YYSYMBOL_IDENT;
	const char *text = layout_token_text(P);
	int inf_nan = got == YYSYMBOL_NUMBER && text && (!strcmp(text, "Inf") || !strcmp(text, "NaN"));
	if (wants_name && (inf_nan || got == YYSYMBOL_PROTECTED || (got >= YYSYMBOL_USING && got <= YYSYMBOL_NOT))) {
		error_at(l, "'%s' is a protected name and cannot be used as a name", text);
		return 0;
	}
	if (got == YYSYMBOL_INDENT) {
		error_at(l, "unexpected indentation");
		return 0;
	}
	if (got == YYSYMBOL_IDENT && text && l.col > 1) {
		/* a name right after a number or a ')': a unit CSF does not know */
		char *line = src_line(l.file, l.line);
		int c = l.col - 2;
		while (c > 0 && (line[c] == ' ' || line[c] == '\t')) c--;
		if (c >= 0 && (isdigit((unsigned char)line[c]) || line[c] == ')' || line[c] == '.')) {
			const char *s = suggest_unit(text);
			if (s) error_at(l, "unknown unit '%s'; did you mean '%s'?", text, s);
			else error_at(l, "unknown unit '%s' (csf(5), UNITS, lists them)", text);
			return 0;
		}
	}
	char buf[512];
	size_t k = (size_t)snprintf(buf, sizeof buf, "syntax error: unexpected %s", yysymbol_name(got));
	if (text && (got == YYSYMBOL_IDENT || got == YYSYMBOL_NUMBER || got == YYSYMBOL_UNIT || got == YYSYMBOL_DOLLAR))
		k += (size_t)snprintf(buf + k, sizeof buf - k, " '%s'", text);
	if (n > 0 && n <= 5)
		for (int i = 0; i < n && k < sizeof buf; i++)
			k += (size_t)snprintf(buf + k, sizeof buf - k, "%s%s", i == 0 ? ", expecting " : " or ",
			                      yysymbol_name(exp[i]));
	error_at(l, "%s", buf);
	return 0;
}

Stmt *parse_file(int file)
{
	Parser *P = layout_new(file);
	yyparse(P);
	return layout_result(P);
}
