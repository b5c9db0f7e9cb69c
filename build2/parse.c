/* A Bison parser, made by GNU Bison 3.8.2.  */

/* Bison implementation for Yacc-like parsers in C

   Copyright (C) 1984, 1989-1990, 2000-2015, 2018-2021 Free Software Foundation,
   Inc.

   This program is free software: you can redistribute it and/or modify
   it under the terms of the GNU General Public License as published by
   the Free Software Foundation, either version 3 of the License, or
   (at your option) any later version.

   This program is distributed in the hope that it will be useful,
   but WITHOUT ANY WARRANTY; without even the implied warranty of
   MERCHANTABILITY or FITNESS FOR A PARTICULAR PURPOSE.  See the
   GNU General Public License for more details.

   You should have received a copy of the GNU General Public License
   along with this program.  If not, see <https://www.gnu.org/licenses/>.  */

/* As a special exception, you may create a larger work that contains
   part or all of the Bison parser skeleton and distribute that work
   under terms of your choice, so long as that work isn't itself a
   parser generator using the skeleton or a modified version thereof
   as a parser skeleton.  Alternatively, if you modify or redistribute
   the parser skeleton itself, you may (at your option) remove this
   special exception, which will cause the skeleton and the resulting
   Bison output files to be licensed under the GNU General Public
   License without this special exception.

   This special exception was added by the Free Software Foundation in
   version 2.2 of Bison.  */

/* C LALR(1) parser skeleton written by Richard Stallman, by
   simplifying the original so-called "semantic" parser.  */

/* DO NOT RELY ON FEATURES THAT ARE NOT DOCUMENTED in the manual,
   especially those whose name start with YY_ or yy_.  They are
   private implementation details that can be changed or removed.  */

/* All symbols defined below should begin with yy or YY, to avoid
   infringing on user name space.  This should be done even for local
   variables, as they might otherwise be expanded by user macros.
   There are some unavoidable exceptions within include files to
   define necessary library symbols; they are noted "INFRINGES ON
   USER NAME SPACE" below.  */

/* Identify Bison output, and Bison version.  */
#define YYBISON 30802

/* Bison version string.  */
#define YYBISON_VERSION "3.8.2"

/* Skeleton name.  */
#define YYSKELETON_NAME "yacc.c"

/* Pure parsers.  */
#define YYPURE 2

/* Push parsers.  */
#define YYPUSH 0

/* Pull parsers.  */
#define YYPULL 1





# ifndef YY_CAST
#  ifdef __cplusplus
#   define YY_CAST(Type, Val) static_cast<Type> (Val)
#   define YY_REINTERPRET_CAST(Type, Val) reinterpret_cast<Type> (Val)
#  else
#   define YY_CAST(Type, Val) ((Type) (Val))
#   define YY_REINTERPRET_CAST(Type, Val) ((Type) (Val))
#  endif
# endif
# ifndef YY_NULLPTR
#  if defined __cplusplus
#   if 201103L <= __cplusplus
#    define YY_NULLPTR nullptr
#   else
#    define YY_NULLPTR 0
#   endif
#  else
#   define YY_NULLPTR ((void*)0)
#  endif
# endif

#include "parse.h"
/* Symbol kind.  */
enum yysymbol_kind_t
{
  YYSYMBOL_YYEMPTY = -2,
  YYSYMBOL_YYEOF = 0,                      /* "end of file"  */
  YYSYMBOL_YYerror = 1,                    /* error  */
  YYSYMBOL_YYUNDEF = 2,                    /* "invalid token"  */
  YYSYMBOL_NUMBER = 3,                     /* "number"  */
  YYSYMBOL_IDENT = 4,                      /* "name"  */
  YYSYMBOL_DOLLAR = 5,                     /* "object number ($n)"  */
  YYSYMBOL_UNIT = 6,                       /* "unit"  */
  YYSYMBOL_NEWLINE = 7,                    /* "end of line"  */
  YYSYMBOL_INDENT = 8,                     /* "indented block"  */
  YYSYMBOL_DEDENT = 9,                     /* "end of indented block"  */
  YYSYMBOL_LEXERROR = 10,                  /* "invalid token"  */
  YYSYMBOL_PROTECTED = 11,                 /* "protected name"  */
  YYSYMBOL_USING = 12,                     /* "'using'"  */
  YYSYMBOL_OBJECT = 13,                    /* "'object'"  */
  YYSYMBOL_DEF = 14,                       /* "'def'"  */
  YYSYMBOL_GLOBAL = 15,                    /* "'global'"  */
  YYSYMBOL_RULE = 16,                      /* "'rule'"  */
  YYSYMBOL_FOR = 17,                       /* "'for'"  */
  YYSYMBOL_STOP = 18,                      /* "'stop'"  */
  YYSYMBOL_WHEN = 19,                      /* "'when'"  */
  YYSYMBOL_IF = 20,                        /* "'if'"  */
  YYSYMBOL_ELIF = 21,                      /* "'elif'"  */
  YYSYMBOL_ELSE = 22,                      /* "'else'"  */
  YYSYMBOL_ASSERT = 23,                    /* "'assert'"  */
  YYSYMBOL_VECTOR = 24,                    /* "'vector'"  */
  YYSYMBOL_INC = 25,                       /* "'inc'"  */
  YYSYMBOL_TILL = 26,                      /* "'till'"  */
  YYSYMBOL_BY = 27,                        /* "'by'"  */
  YYSYMBOL_WATCH = 28,                     /* "'watch'"  */
  YYSYMBOL_AND = 29,                       /* "'and'"  */
  YYSYMBOL_OR = 30,                        /* "'or'"  */
  YYSYMBOL_NOT = 31,                       /* "'not'"  */
  YYSYMBOL_ATOL = 32,                      /* "'atol'"  */
  YYSYMBOL_DOTDOT = 33,                    /* "'..'"  */
  YYSYMBOL_STRING = 34,                    /* "string"  */
  YYSYMBOL_EQEQ = 35,                      /* "'=='"  */
  YYSYMBOL_NE = 36,                        /* "'!='"  */
  YYSYMBOL_LE = 37,                        /* "'<='"  */
  YYSYMBOL_GE = 38,                        /* "'>='"  */
  YYSYMBOL_39_ = 39,                       /* '<'  */
  YYSYMBOL_40_ = 40,                       /* '>'  */
  YYSYMBOL_41_ = 41,                       /* '+'  */
  YYSYMBOL_42_ = 42,                       /* '-'  */
  YYSYMBOL_43_ = 43,                       /* '*'  */
  YYSYMBOL_44_ = 44,                       /* '/'  */
  YYSYMBOL_UMINUS = 45,                    /* UMINUS  */
  YYSYMBOL_46_ = 46,                       /* '^'  */
  YYSYMBOL_47_ = 47,                       /* '='  */
  YYSYMBOL_48_ = 48,                       /* ':'  */
  YYSYMBOL_49_ = 49,                       /* '['  */
  YYSYMBOL_50_ = 50,                       /* ']'  */
  YYSYMBOL_51_ = 51,                       /* '\''  */
  YYSYMBOL_52_ = 52,                       /* ','  */
  YYSYMBOL_53_ = 53,                       /* '.'  */
  YYSYMBOL_54_ = 54,                       /* '('  */
  YYSYMBOL_55_ = 55,                       /* ')'  */
  YYSYMBOL_YYACCEPT = 56,                  /* $accept  */
  YYSYMBOL_file = 57,                      /* file  */
  YYSYMBOL_line = 58,                      /* line  */
  YYSYMBOL_stmt = 59,                      /* stmt  */
  YYSYMBOL_objname = 60,                   /* objname  */
  YYSYMBOL_index = 61,                     /* index  */
  YYSYMBOL_till = 62,                      /* till  */
  YYSYMBOL_atol = 63,                      /* atol  */
  YYSYMBOL_by = 64,                        /* by  */
  YYSYMBOL_attr = 65,                      /* attr  */
  YYSYMBOL_block = 66,                     /* block  */
  YYSYMBOL_ifblock = 67,                   /* ifblock  */
  YYSYMBOL_elsepart = 68,                  /* elsepart  */
  YYSYMBOL_body = 69,                      /* body  */
  YYSYMBOL_defprops = 70,                  /* defprops  */
  YYSYMBOL_defprop = 71,                   /* defprop  */
  YYSYMBOL_steps = 72,                     /* steps  */
  YYSYMBOL_step = 73,                      /* step  */
  YYSYMBOL_eqn = 74,                       /* eqn  */
  YYSYMBOL_names = 75,                     /* names  */
  YYSYMBOL_objrefs = 76,                   /* objrefs  */
  YYSYMBOL_objref = 77,                    /* objref  */
  YYSYMBOL_watches = 78,                   /* watches  */
  YYSYMBOL_watch = 79,                     /* watch  */
  YYSYMBOL_expr = 80,                      /* expr  */
  YYSYMBOL_postfix = 81,                   /* postfix  */
  YYSYMBOL_primary = 82,                   /* primary  */
  YYSYMBOL_args = 83,                      /* args  */
  YYSYMBOL_args1 = 84                      /* args1  */
};
typedef enum yysymbol_kind_t yysymbol_kind_t;



/* Unqualified %code blocks.  */
#line 43 "compiler/front/parse.y"

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
static Expr *with_unit(Expr *a, Token *u)
{
	Expr *e = ast_expr(E_UNIT, u->loc);
	e->a = a;
	e->unit = u->unit;
	e->unit_text = u->text;
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

#line 350 "build2/parse.c"

#ifdef short
# undef short
#endif

/* On compilers that do not define __PTRDIFF_MAX__ etc., make sure
   <limits.h> and (if available) <stdint.h> are included
   so that the code can choose integer types of a good width.  */

#ifndef __PTRDIFF_MAX__
# include <limits.h> /* INFRINGES ON USER NAME SPACE */
# if defined __STDC_VERSION__ && 199901 <= __STDC_VERSION__
#  include <stdint.h> /* INFRINGES ON USER NAME SPACE */
#  define YY_STDINT_H
# endif
#endif

/* Narrow types that promote to a signed type and that can represent a
   signed or unsigned integer of at least N bits.  In tables they can
   save space and decrease cache pressure.  Promoting to a signed type
   helps avoid bugs in integer arithmetic.  */

#ifdef __INT_LEAST8_MAX__
typedef __INT_LEAST8_TYPE__ yytype_int8;
#elif defined YY_STDINT_H
typedef int_least8_t yytype_int8;
#else
typedef signed char yytype_int8;
#endif

#ifdef __INT_LEAST16_MAX__
typedef __INT_LEAST16_TYPE__ yytype_int16;
#elif defined YY_STDINT_H
typedef int_least16_t yytype_int16;
#else
typedef short yytype_int16;
#endif

/* Work around bug in HP-UX 11.23, which defines these macros
   incorrectly for preprocessor constants.  This workaround can likely
   be removed in 2023, as HPE has promised support for HP-UX 11.23
   (aka HP-UX 11i v2) only through the end of 2022; see Table 2 of
   <https://h20195.www2.hpe.com/V2/getpdf.aspx/4AA4-7673ENW.pdf>.  */
#ifdef __hpux
# undef UINT_LEAST8_MAX
# undef UINT_LEAST16_MAX
# define UINT_LEAST8_MAX 255
# define UINT_LEAST16_MAX 65535
#endif

#if defined __UINT_LEAST8_MAX__ && __UINT_LEAST8_MAX__ <= __INT_MAX__
typedef __UINT_LEAST8_TYPE__ yytype_uint8;
#elif (!defined __UINT_LEAST8_MAX__ && defined YY_STDINT_H \
       && UINT_LEAST8_MAX <= INT_MAX)
typedef uint_least8_t yytype_uint8;
#elif !defined __UINT_LEAST8_MAX__ && UCHAR_MAX <= INT_MAX
typedef unsigned char yytype_uint8;
#else
typedef short yytype_uint8;
#endif

#if defined __UINT_LEAST16_MAX__ && __UINT_LEAST16_MAX__ <= __INT_MAX__
typedef __UINT_LEAST16_TYPE__ yytype_uint16;
#elif (!defined __UINT_LEAST16_MAX__ && defined YY_STDINT_H \
       && UINT_LEAST16_MAX <= INT_MAX)
typedef uint_least16_t yytype_uint16;
#elif !defined __UINT_LEAST16_MAX__ && USHRT_MAX <= INT_MAX
typedef unsigned short yytype_uint16;
#else
typedef int yytype_uint16;
#endif

#ifndef YYPTRDIFF_T
# if defined __PTRDIFF_TYPE__ && defined __PTRDIFF_MAX__
#  define YYPTRDIFF_T __PTRDIFF_TYPE__
#  define YYPTRDIFF_MAXIMUM __PTRDIFF_MAX__
# elif defined PTRDIFF_MAX
#  ifndef ptrdiff_t
#   include <stddef.h> /* INFRINGES ON USER NAME SPACE */
#  endif
#  define YYPTRDIFF_T ptrdiff_t
#  define YYPTRDIFF_MAXIMUM PTRDIFF_MAX
# else
#  define YYPTRDIFF_T long
#  define YYPTRDIFF_MAXIMUM LONG_MAX
# endif
#endif

#ifndef YYSIZE_T
# ifdef __SIZE_TYPE__
#  define YYSIZE_T __SIZE_TYPE__
# elif defined size_t
#  define YYSIZE_T size_t
# elif defined __STDC_VERSION__ && 199901 <= __STDC_VERSION__
#  include <stddef.h> /* INFRINGES ON USER NAME SPACE */
#  define YYSIZE_T size_t
# else
#  define YYSIZE_T unsigned
# endif
#endif

#define YYSIZE_MAXIMUM                                  \
  YY_CAST (YYPTRDIFF_T,                                 \
           (YYPTRDIFF_MAXIMUM < YY_CAST (YYSIZE_T, -1)  \
            ? YYPTRDIFF_MAXIMUM                         \
            : YY_CAST (YYSIZE_T, -1)))

#define YYSIZEOF(X) YY_CAST (YYPTRDIFF_T, sizeof (X))


/* Stored state numbers (used for stacks). */
typedef yytype_uint8 yy_state_t;

/* State numbers in computations.  */
typedef int yy_state_fast_t;

#ifndef YY_
# if defined YYENABLE_NLS && YYENABLE_NLS
#  if ENABLE_NLS
#   include <libintl.h> /* INFRINGES ON USER NAME SPACE */
#   define YY_(Msgid) dgettext ("bison-runtime", Msgid)
#  endif
# endif
# ifndef YY_
#  define YY_(Msgid) Msgid
# endif
#endif


#ifndef YY_ATTRIBUTE_PURE
# if defined __GNUC__ && 2 < __GNUC__ + (96 <= __GNUC_MINOR__)
#  define YY_ATTRIBUTE_PURE __attribute__ ((__pure__))
# else
#  define YY_ATTRIBUTE_PURE
# endif
#endif

#ifndef YY_ATTRIBUTE_UNUSED
# if defined __GNUC__ && 2 < __GNUC__ + (7 <= __GNUC_MINOR__)
#  define YY_ATTRIBUTE_UNUSED __attribute__ ((__unused__))
# else
#  define YY_ATTRIBUTE_UNUSED
# endif
#endif

/* Suppress unused-variable warnings by "using" E.  */
#if ! defined lint || defined __GNUC__
# define YY_USE(E) ((void) (E))
#else
# define YY_USE(E) /* empty */
#endif

/* Suppress an incorrect diagnostic about yylval being uninitialized.  */
#if defined __GNUC__ && ! defined __ICC && 406 <= __GNUC__ * 100 + __GNUC_MINOR__
# if __GNUC__ * 100 + __GNUC_MINOR__ < 407
#  define YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN                           \
    _Pragma ("GCC diagnostic push")                                     \
    _Pragma ("GCC diagnostic ignored \"-Wuninitialized\"")
# else
#  define YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN                           \
    _Pragma ("GCC diagnostic push")                                     \
    _Pragma ("GCC diagnostic ignored \"-Wuninitialized\"")              \
    _Pragma ("GCC diagnostic ignored \"-Wmaybe-uninitialized\"")
# endif
# define YY_IGNORE_MAYBE_UNINITIALIZED_END      \
    _Pragma ("GCC diagnostic pop")
#else
# define YY_INITIAL_VALUE(Value) Value
#endif
#ifndef YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
# define YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
# define YY_IGNORE_MAYBE_UNINITIALIZED_END
#endif
#ifndef YY_INITIAL_VALUE
# define YY_INITIAL_VALUE(Value) /* Nothing. */
#endif

#if defined __cplusplus && defined __GNUC__ && ! defined __ICC && 6 <= __GNUC__
# define YY_IGNORE_USELESS_CAST_BEGIN                          \
    _Pragma ("GCC diagnostic push")                            \
    _Pragma ("GCC diagnostic ignored \"-Wuseless-cast\"")
# define YY_IGNORE_USELESS_CAST_END            \
    _Pragma ("GCC diagnostic pop")
#endif
#ifndef YY_IGNORE_USELESS_CAST_BEGIN
# define YY_IGNORE_USELESS_CAST_BEGIN
# define YY_IGNORE_USELESS_CAST_END
#endif


#define YY_ASSERT(E) ((void) (0 && (E)))

#if 1

/* The parser invokes alloca or malloc; define the necessary symbols.  */

# ifdef YYSTACK_USE_ALLOCA
#  if YYSTACK_USE_ALLOCA
#   ifdef __GNUC__
#    define YYSTACK_ALLOC __builtin_alloca
#   elif defined __BUILTIN_VA_ARG_INCR
#    include <alloca.h> /* INFRINGES ON USER NAME SPACE */
#   elif defined _AIX
#    define YYSTACK_ALLOC __alloca
#   elif defined _MSC_VER
#    include <malloc.h> /* INFRINGES ON USER NAME SPACE */
#    define alloca _alloca
#   else
#    define YYSTACK_ALLOC alloca
#    if ! defined _ALLOCA_H && ! defined EXIT_SUCCESS
#     include <stdlib.h> /* INFRINGES ON USER NAME SPACE */
      /* Use EXIT_SUCCESS as a witness for stdlib.h.  */
#     ifndef EXIT_SUCCESS
#      define EXIT_SUCCESS 0
#     endif
#    endif
#   endif
#  endif
# endif

# ifdef YYSTACK_ALLOC
   /* Pacify GCC's 'empty if-body' warning.  */
#  define YYSTACK_FREE(Ptr) do { /* empty */; } while (0)
#  ifndef YYSTACK_ALLOC_MAXIMUM
    /* The OS might guarantee only one guard page at the bottom of the stack,
       and a page size can be as small as 4096 bytes.  So we cannot safely
       invoke alloca (N) if N exceeds 4096.  Use a slightly smaller number
       to allow for a few compiler-allocated temporary stack slots.  */
#   define YYSTACK_ALLOC_MAXIMUM 4032 /* reasonable circa 2006 */
#  endif
# else
#  define YYSTACK_ALLOC YYMALLOC
#  define YYSTACK_FREE YYFREE
#  ifndef YYSTACK_ALLOC_MAXIMUM
#   define YYSTACK_ALLOC_MAXIMUM YYSIZE_MAXIMUM
#  endif
#  if (defined __cplusplus && ! defined EXIT_SUCCESS \
       && ! ((defined YYMALLOC || defined malloc) \
             && (defined YYFREE || defined free)))
#   include <stdlib.h> /* INFRINGES ON USER NAME SPACE */
#   ifndef EXIT_SUCCESS
#    define EXIT_SUCCESS 0
#   endif
#  endif
#  ifndef YYMALLOC
#   define YYMALLOC malloc
#   if ! defined malloc && ! defined EXIT_SUCCESS
void *malloc (YYSIZE_T); /* INFRINGES ON USER NAME SPACE */
#   endif
#  endif
#  ifndef YYFREE
#   define YYFREE free
#   if ! defined free && ! defined EXIT_SUCCESS
void free (void *); /* INFRINGES ON USER NAME SPACE */
#   endif
#  endif
# endif
#endif /* 1 */

#if (! defined yyoverflow \
     && (! defined __cplusplus \
         || (defined YYLTYPE_IS_TRIVIAL && YYLTYPE_IS_TRIVIAL \
             && defined YYSTYPE_IS_TRIVIAL && YYSTYPE_IS_TRIVIAL)))

/* A type that is properly aligned for any stack member.  */
union yyalloc
{
  yy_state_t yyss_alloc;
  YYSTYPE yyvs_alloc;
  YYLTYPE yyls_alloc;
};

/* The size of the maximum gap between one aligned stack and the next.  */
# define YYSTACK_GAP_MAXIMUM (YYSIZEOF (union yyalloc) - 1)

/* The size of an array large to enough to hold all stacks, each with
   N elements.  */
# define YYSTACK_BYTES(N) \
     ((N) * (YYSIZEOF (yy_state_t) + YYSIZEOF (YYSTYPE) \
             + YYSIZEOF (YYLTYPE)) \
      + 2 * YYSTACK_GAP_MAXIMUM)

# define YYCOPY_NEEDED 1

/* Relocate STACK from its old location to the new one.  The
   local variables YYSIZE and YYSTACKSIZE give the old and new number of
   elements in the stack, and YYPTR gives the new location of the
   stack.  Advance YYPTR to a properly aligned location for the next
   stack.  */
# define YYSTACK_RELOCATE(Stack_alloc, Stack)                           \
    do                                                                  \
      {                                                                 \
        YYPTRDIFF_T yynewbytes;                                         \
        YYCOPY (&yyptr->Stack_alloc, Stack, yysize);                    \
        Stack = &yyptr->Stack_alloc;                                    \
        yynewbytes = yystacksize * YYSIZEOF (*Stack) + YYSTACK_GAP_MAXIMUM; \
        yyptr += yynewbytes / YYSIZEOF (*yyptr);                        \
      }                                                                 \
    while (0)

#endif

#if defined YYCOPY_NEEDED && YYCOPY_NEEDED
/* Copy COUNT objects from SRC to DST.  The source and destination do
   not overlap.  */
# ifndef YYCOPY
#  if defined __GNUC__ && 1 < __GNUC__
#   define YYCOPY(Dst, Src, Count) \
      __builtin_memcpy (Dst, Src, YY_CAST (YYSIZE_T, (Count)) * sizeof (*(Src)))
#  else
#   define YYCOPY(Dst, Src, Count)              \
      do                                        \
        {                                       \
          YYPTRDIFF_T yyi;                      \
          for (yyi = 0; yyi < (Count); yyi++)   \
            (Dst)[yyi] = (Src)[yyi];            \
        }                                       \
      while (0)
#  endif
# endif
#endif /* !YYCOPY_NEEDED */

/* YYFINAL -- State number of the termination state.  */
#define YYFINAL  2
/* YYLAST -- Last index in YYTABLE.  */
#define YYLAST   550

/* YYNTOKENS -- Number of terminals.  */
#define YYNTOKENS  56
/* YYNNTS -- Number of nonterminals.  */
#define YYNNTS  29
/* YYNRULES -- Number of rules.  */
#define YYNRULES  110
/* YYNSTATES -- Number of states.  */
#define YYNSTATES  228

/* YYMAXUTOK -- Last valid token kind.  */
#define YYMAXUTOK   294


/* YYTRANSLATE(TOKEN-NUM) -- Symbol number corresponding to TOKEN-NUM
   as returned by yylex, with out-of-bounds checking.  */
#define YYTRANSLATE(YYX)                                \
  (0 <= (YYX) && (YYX) <= YYMAXUTOK                     \
   ? YY_CAST (yysymbol_kind_t, yytranslate[YYX])        \
   : YYSYMBOL_YYUNDEF)

/* YYTRANSLATE[TOKEN-NUM] -- Symbol number corresponding to TOKEN-NUM
   as returned by yylex.  */
static const yytype_int8 yytranslate[] =
{
       0,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,    51,
      54,    55,    43,    41,    52,    42,    53,    44,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,    48,     2,
      39,    47,    40,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,    49,     2,    50,    46,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     2,     2,     2,     2,
       2,     2,     2,     2,     2,     2,     1,     2,     3,     4,
       5,     6,     7,     8,     9,    10,    11,    12,    13,    14,
      15,    16,    17,    18,    19,    20,    21,    22,    23,    24,
      25,    26,    27,    28,    29,    30,    31,    32,    33,    34,
      35,    36,    37,    38,    45
};

#if YYDEBUG
/* YYRLINE[YYN] -- Source line where rule number YYN was defined.  */
static const yytype_int16 yyrline[] =
{
       0,   273,   273,   274,   278,   279,   280,   281,   285,   288,
     291,   302,   306,   310,   313,   316,   319,   322,   325,   328,
     329,   330,   333,   336,   344,   345,   346,   351,   352,   356,
     357,   360,   360,   363,   363,   364,   364,   366,   366,   369,
     372,   375,   378,   379,   384,   389,   390,   391,   397,   401,
     402,   406,   409,   412,   416,   417,   421,   422,   423,   427,
     428,   441,   442,   446,   447,   451,   452,   454,   458,   459,
     463,   464,   465,   468,   471,   477,   478,   479,   480,   481,
     482,   483,   484,   485,   486,   487,   488,   489,   490,   491,
     492,   493,   497,   498,   499,   503,   504,   505,   506,   507,
     508,   513,   514,   515,   516,   517,   521,   529,   530,   534,
     535
};
#endif

/** Accessing symbol of state STATE.  */
#define YY_ACCESSING_SYMBOL(State) YY_CAST (yysymbol_kind_t, yystos[State])

#if 1
/* The user-facing name of the symbol whose (internal) number is
   YYSYMBOL.  No bounds checking.  */
static const char *yysymbol_name (yysymbol_kind_t yysymbol) YY_ATTRIBUTE_UNUSED;

static const char *
yysymbol_name (yysymbol_kind_t yysymbol)
{
  static const char *const yy_sname[] =
  {
  "end of file", "error", "invalid token", "number", "name",
  "object number ($n)", "unit", "end of line", "indented block",
  "end of indented block", "invalid token", "protected name", "'using'",
  "'object'", "'def'", "'global'", "'rule'", "'for'", "'stop'", "'when'",
  "'if'", "'elif'", "'else'", "'assert'", "'vector'", "'inc'", "'till'",
  "'by'", "'watch'", "'and'", "'or'", "'not'", "'atol'", "'..'", "string",
  "'=='", "'!='", "'<='", "'>='", "'<'", "'>'", "'+'", "'-'", "'*'", "'/'",
  "UMINUS", "'^'", "'='", "':'", "'['", "']'", "'\\''", "','", "'.'",
  "'('", "')'", "$accept", "file", "line", "stmt", "objname", "index",
  "till", "atol", "by", "attr", "block", "ifblock", "elsepart", "body",
  "defprops", "defprop", "steps", "step", "eqn", "names", "objrefs",
  "objref", "watches", "watch", "expr", "postfix", "primary", "args",
  "args1", YY_NULLPTR
  };
  return yy_sname[yysymbol];
}
#endif

#define YYPACT_NINF (-153)

#define yypact_value_is_default(Yyn) \
  ((Yyn) == YYPACT_NINF)

#define YYTABLE_NINF (-1)

#define yytable_value_is_error(Yyn) \
  ((Yyn) == YYTABLE_NINF)

/* YYPACT[STATE-NUM] -- Index in YYTABLE of the portion describing
   STATE-NUM.  */
static const yytype_int16 yypact[] =
{
    -153,   302,  -153,     9,  -153,     7,    19,    22,    25,    26,
      90,   142,    38,    44,  -153,    56,  -153,  -153,    24,    47,
      49,    45,  -153,   -12,   142,    94,    17,    66,   142,   142,
     142,   142,   366,    48,  -153,   464,  -153,    51,    78,  -153,
      40,     6,    98,   142,    66,   138,   464,  -153,  -153,   142,
     142,  -153,    57,   -14,  -153,   492,    63,    63,   234,   142,
     142,   142,   142,   142,   142,   142,   142,   142,   142,   142,
     142,   142,   144,   104,   107,   142,    87,  -153,    68,   113,
    -153,   -25,   -19,   115,   120,   464,   -11,   142,  -153,  -153,
     311,   330,   216,    74,    81,   142,   142,    66,   142,   117,
     492,   480,   504,   504,   504,   504,   504,   504,    35,    35,
      63,    63,    63,   122,  -153,  -153,   311,    84,  -153,   464,
     142,   112,  -153,  -153,     4,  -153,  -153,   142,    88,    23,
     138,   386,   142,    96,  -153,   148,   147,   142,   348,   406,
    -153,   293,  -153,    95,   142,   464,   150,   105,   446,   142,
     152,   110,   156,     8,  -153,  -153,  -153,   311,   154,   464,
     142,   108,  -153,   464,  -153,   144,   142,   155,  -153,    71,
    -153,   157,   464,   111,    15,   118,  -153,  -153,   142,  -153,
     446,  -153,   142,   124,  -153,  -153,    62,   464,  -153,  -153,
    -153,   255,  -153,  -153,  -153,  -153,  -153,     4,   161,   150,
     464,  -153,   170,   142,   142,   119,  -153,   168,   126,   125,
    -153,  -153,   188,   426,   154,  -153,   128,   178,  -153,   154,
    -153,   183,  -153,    62,   135,  -153,   185,  -153
};

/* YYDEFACT[STATE-NUM] -- Default reduction number in state STATE-NUM.
   Performed when YYTABLE does not specify something else to do.  Zero
   means the default is an error.  */
static const yytype_int8 yydefact[] =
{
       2,     0,     1,     0,     4,     0,     0,     0,    37,     0,
       0,     0,     0,     0,     3,     0,     6,     7,    24,     0,
       0,     0,    38,     0,     0,    95,    97,     0,     0,     0,
       0,     0,     0,    91,    92,    18,    61,    13,    31,     5,
       0,     0,     0,     0,     0,     0,    21,    96,    98,     0,
     107,    66,    65,     0,    63,    77,    90,    89,     0,     0,
       0,     0,     0,     0,     0,     0,     0,     0,     0,     0,
       0,     0,     0,     0,     0,     0,    35,    29,     0,     0,
      28,     0,     9,     0,     0,     8,     0,     0,    40,    14,
      16,     0,   109,     0,   108,     0,     0,     0,     0,   103,
      76,    75,    82,    83,    80,    81,    78,    79,    84,    85,
      86,    87,    88,     0,    42,    19,     0,    93,    62,    32,
       0,    22,    27,    30,     0,    25,    10,     0,     0,     0,
       0,     0,     0,     0,   101,     0,    99,     0,     0,     0,
      64,     0,   104,     0,   107,    36,     0,     0,    33,     0,
       0,     0,     0,     0,    49,    41,    15,    17,     0,    59,
       0,     0,   102,   110,    67,     0,     0,     0,    57,     0,
      54,     0,   109,     0,    70,    23,    68,    26,     0,    11,
      33,    53,     0,     0,    39,    50,    45,    60,   100,    43,
      20,     0,    58,    48,    55,    56,    94,     0,     0,     0,
      34,    12,     0,     0,     0,     0,    44,   105,     0,    71,
      69,    51,     0,     0,     0,   106,     0,     0,    52,     0,
      46,     0,    72,    45,    73,    47,     0,    74
};

/* YYPGOTO[NTERM-NUM].  */
static const yytype_int16 yypgoto[] =
{
    -153,  -153,  -153,  -153,  -153,  -121,  -153,    10,  -153,  -153,
    -153,   -43,   -32,  -152,  -153,    50,  -153,    28,   -41,  -153,
     158,   123,  -153,     2,   -10,  -153,  -153,    60,  -153
};

/* YYDEFGOTO[NTERM-NUM].  */
static const yytype_uint8 yydefgoto[] =
{
       0,     1,    14,    15,    19,    81,    76,   179,   121,    23,
      16,   168,   206,   114,   153,   154,   169,   170,   171,    37,
      53,    54,   175,   176,   116,    33,    34,    93,    94
};

/* YYTABLE[YYPACT[STATE-NUM]] -- What to do in state STATE-NUM.  If
   positive, shift that token.  If negative, reduce the rule whose
   number is the opposite.  If YYTABLE_NINF, syntax error.  */
static const yytype_int16 yytable[] =
{
      32,    35,    88,   147,    89,    44,   186,    77,   124,   150,
      82,    18,   151,   189,    46,   126,    17,   184,    55,    56,
      57,    58,    48,    20,   150,   125,    21,   151,   127,    22,
      83,   115,   152,    85,    96,    90,    45,   130,    97,    91,
      92,    97,    36,    77,    78,    24,    79,   152,    38,   100,
     101,   102,   103,   104,   105,   106,   107,   108,   109,   110,
     111,   112,   220,    39,   197,   119,    49,   223,   198,    51,
      52,    50,   167,    40,    25,    26,   208,   131,    69,    70,
     193,    71,    79,   204,   205,   138,   139,   155,   141,   156,
      80,    87,    43,    25,    26,    41,   167,    42,    25,    26,
      47,    73,    28,    74,    75,    84,    95,    27,   117,    71,
     145,   118,    29,    30,   120,    87,   123,   148,   122,   128,
     157,    28,   159,   142,   190,    31,    28,   163,   129,   136,
     143,    29,    30,   137,   172,   149,    29,    30,   144,   180,
     146,    25,    26,   160,    31,    25,    26,    25,    26,    31,
     187,   113,   161,   162,   174,   177,   191,   182,    87,   181,
     183,   113,   192,   188,   195,   209,   196,   214,   200,    28,
     199,   203,   202,    28,   215,    28,   216,   211,   217,    29,
      30,   221,   222,    29,    30,    29,    30,   224,   226,   227,
     201,   225,    31,   212,   213,   218,    31,   194,    31,    59,
      60,   210,    86,   185,   173,    61,    62,    63,    64,    65,
      66,    67,    68,    69,    70,     0,    71,    59,    60,     0,
     140,     0,     0,    61,    62,    63,    64,    65,    66,    67,
      68,    69,    70,   135,    71,     0,     0,     0,     0,     0,
       0,     0,     0,     0,     0,    59,    60,     0,     0,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,    59,    60,     0,     0,     0,     0,    61,
      62,    63,    64,    65,    66,    67,    68,    69,    70,     0,
      71,     0,     0,     0,    59,    60,    98,     0,     0,    99,
      61,    62,    63,    64,    65,    66,    67,    68,    69,    70,
       0,    71,     2,     3,     0,     0,     0,     0,     0,     4,
     207,     0,     0,     0,     0,     5,     6,     7,     8,     0,
       9,    10,    59,    60,     0,    11,    12,    13,    61,    62,
      63,    64,    65,    66,    67,    68,    69,    70,     0,    71,
      59,    60,     0,     0,     0,   166,    61,    62,    63,    64,
      65,    66,    67,    68,    69,    70,     0,    71,   132,    59,
      60,     0,   133,     0,     0,    61,    62,    63,    64,    65,
      66,    67,    68,    69,    70,     0,    71,    59,    60,     0,
     134,     0,     0,    61,    62,    63,    64,    65,    66,    67,
      68,    69,    70,     0,    71,    59,    60,     0,   164,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,     0,    72,    59,    60,     0,     0,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,     0,   158,    59,    60,     0,     0,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,     0,   165,    59,    60,     0,     0,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,     0,   219,    59,    60,     0,   178,     0,
       0,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,     0,    71,    59,    60,     0,     0,     0,     0,    61,
      62,    63,    64,    65,    66,    67,    68,    69,    70,    59,
      71,     0,     0,     0,     0,    61,    62,    63,    64,    65,
      66,    67,    68,    69,    70,     0,    71,    61,    62,    63,
      64,    65,    66,    67,    68,    69,    70,     0,    71,    -1,
      -1,    -1,    -1,    -1,    -1,    67,    68,    69,    70,     0,
      71
};

static const yytype_int16 yycheck[] =
{
      10,    11,    45,   124,    45,    17,   158,     3,    33,     1,
       4,     4,     4,   165,    24,    34,     7,     9,    28,    29,
      30,    31,     5,     4,     1,    50,     4,     4,    47,     4,
      24,    72,    24,    43,    48,    45,    48,    48,    52,    49,
      50,    52,     4,     3,     4,    19,    42,    24,     4,    59,
      60,    61,    62,    63,    64,    65,    66,    67,    68,    69,
      70,    71,   214,     7,    49,    75,    49,   219,    53,     3,
       4,    54,     1,    49,     3,     4,   197,    87,    43,    44,
       9,    46,    42,    21,    22,    95,    96,   130,    98,   130,
      50,    20,    47,     3,     4,    48,     1,    48,     3,     4,
       6,    53,    31,    52,    26,     7,    49,    17,     4,    46,
     120,     4,    41,    42,    27,    20,     3,   127,    50,     4,
     130,    31,   132,     6,   165,    54,    31,   137,     8,    55,
       8,    41,    42,    52,   144,    47,    41,    42,    54,   149,
      28,     3,     4,    47,    54,     3,     4,     3,     4,    54,
     160,     7,     4,     6,     4,    50,   166,    47,    20,     7,
       4,     7,     7,    55,     7,     4,    55,    48,   178,    31,
      52,    47,   182,    31,     6,    31,    50,     7,    53,    41,
      42,    53,     4,    41,    42,    41,    42,     4,    53,     4,
     180,   223,    54,   203,   204,     7,    54,   169,    54,    29,
      30,   199,    44,   153,   144,    35,    36,    37,    38,    39,
      40,    41,    42,    43,    44,    -1,    46,    29,    30,    -1,
      97,    -1,    -1,    35,    36,    37,    38,    39,    40,    41,
      42,    43,    44,    17,    46,    -1,    -1,    -1,    -1,    -1,
      -1,    -1,    -1,    -1,    -1,    29,    30,    -1,    -1,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    29,    30,    -1,    -1,    -1,    -1,    35,
      36,    37,    38,    39,    40,    41,    42,    43,    44,    -1,
      46,    -1,    -1,    -1,    29,    30,    52,    -1,    -1,    55,
      35,    36,    37,    38,    39,    40,    41,    42,    43,    44,
      -1,    46,     0,     1,    -1,    -1,    -1,    -1,    -1,     7,
      55,    -1,    -1,    -1,    -1,    13,    14,    15,    16,    -1,
      18,    19,    29,    30,    -1,    23,    24,    25,    35,    36,
      37,    38,    39,    40,    41,    42,    43,    44,    -1,    46,
      29,    30,    -1,    -1,    -1,    52,    35,    36,    37,    38,
      39,    40,    41,    42,    43,    44,    -1,    46,    47,    29,
      30,    -1,    51,    -1,    -1,    35,    36,    37,    38,    39,
      40,    41,    42,    43,    44,    -1,    46,    29,    30,    -1,
      50,    -1,    -1,    35,    36,    37,    38,    39,    40,    41,
      42,    43,    44,    -1,    46,    29,    30,    -1,    50,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    -1,    48,    29,    30,    -1,    -1,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    -1,    48,    29,    30,    -1,    -1,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    -1,    48,    29,    30,    -1,    -1,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    -1,    48,    29,    30,    -1,    32,    -1,
      -1,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    -1,    46,    29,    30,    -1,    -1,    -1,    -1,    35,
      36,    37,    38,    39,    40,    41,    42,    43,    44,    29,
      46,    -1,    -1,    -1,    -1,    35,    36,    37,    38,    39,
      40,    41,    42,    43,    44,    -1,    46,    35,    36,    37,
      38,    39,    40,    41,    42,    43,    44,    -1,    46,    35,
      36,    37,    38,    39,    40,    41,    42,    43,    44,    -1,
      46
};

/* YYSTOS[STATE-NUM] -- The symbol kind of the accessing symbol of
   state STATE-NUM.  */
static const yytype_int8 yystos[] =
{
       0,    57,     0,     1,     7,    13,    14,    15,    16,    18,
      19,    23,    24,    25,    58,    59,    66,     7,     4,    60,
       4,     4,     4,    65,    19,     3,     4,    17,    31,    41,
      42,    54,    80,    81,    82,    80,     4,    75,     4,     7,
      49,    48,    48,    47,    17,    48,    80,     6,     5,    49,
      54,     3,     4,    76,    77,    80,    80,    80,    80,    29,
      30,    35,    36,    37,    38,    39,    40,    41,    42,    43,
      44,    46,    48,    53,    52,    26,    62,     3,     4,    42,
      50,    61,     4,    24,     7,    80,    76,    20,    67,    74,
      80,    80,    80,    83,    84,    49,    48,    52,    52,    55,
      80,    80,    80,    80,    80,    80,    80,    80,    80,    80,
      80,    80,    80,     7,    69,    74,    80,     4,     4,    80,
      27,    64,    50,     3,    33,    50,    34,    47,     4,     8,
      48,    80,    47,    51,    50,    17,    55,    52,    80,    80,
      77,    80,     6,     8,    54,    80,    28,    61,    80,    47,
       1,     4,    24,    70,    71,    67,    74,    80,    48,    80,
      47,     4,     6,    80,    50,    48,    52,     1,    67,    72,
      73,    74,    80,    83,     4,    78,    79,    50,    32,    63,
      80,     7,    47,     4,     9,    71,    69,    80,    55,    69,
      74,    80,     7,     9,    73,     7,    55,    49,    53,    52,
      80,    63,    80,    47,    21,    22,    68,    55,    61,     4,
      79,     7,    80,    80,    48,     6,    50,    53,     7,    48,
      69,    53,     4,    69,     4,    68,    53,     4
};

/* YYR1[RULE-NUM] -- Symbol kind of the left-hand side of rule RULE-NUM.  */
static const yytype_int8 yyr1[] =
{
       0,    56,    57,    57,    58,    58,    58,    58,    59,    59,
      59,    59,    59,    59,    59,    59,    59,    59,    59,    59,
      59,    59,    59,    59,    60,    60,    60,    60,    60,    61,
      61,    62,    62,    63,    63,    64,    64,    65,    65,    66,
      66,    66,    66,    66,    67,    68,    68,    68,    69,    70,
      70,    71,    71,    71,    72,    72,    73,    73,    73,    74,
      74,    75,    75,    76,    76,    77,    77,    77,    78,    78,
      79,    79,    79,    79,    79,    80,    80,    80,    80,    80,
      80,    80,    80,    80,    80,    80,    80,    80,    80,    80,
      80,    80,    81,    81,    81,    82,    82,    82,    82,    82,
      82,    82,    82,    82,    82,    82,    82,    83,    83,    84,
      84
};

/* YYR2[RULE-NUM] -- Number of symbols on the right-hand side of rule RULE-NUM.  */
static const yytype_int8 yyr2[] =
{
       0,     2,     0,     2,     1,     2,     1,     2,     4,     4,
       5,     7,     8,     2,     4,     6,     4,     6,     2,     4,
       7,     3,     4,     6,     1,     4,     6,     4,     3,     1,
       2,     0,     2,     0,     2,     0,     2,     0,     1,     7,
       4,     6,     4,     7,     5,     0,     3,     5,     4,     1,
       2,     4,     5,     2,     1,     2,     2,     1,     2,     3,
       4,     1,     3,     1,     3,     1,     1,     4,     1,     3,
       1,     3,     5,     6,     8,     3,     3,     2,     3,     3,
       3,     3,     3,     3,     3,     3,     3,     3,     3,     2,
       2,     1,     1,     3,     6,     1,     2,     1,     2,     4,
       6,     4,     5,     3,     4,     7,     8,     0,     1,     1,
       3
};


enum { YYENOMEM = -2 };

#define yyerrok         (yyerrstatus = 0)
#define yyclearin       (yychar = YYEMPTY)

#define YYACCEPT        goto yyacceptlab
#define YYABORT         goto yyabortlab
#define YYERROR         goto yyerrorlab
#define YYNOMEM         goto yyexhaustedlab


#define YYRECOVERING()  (!!yyerrstatus)

#define YYBACKUP(Token, Value)                                    \
  do                                                              \
    if (yychar == YYEMPTY)                                        \
      {                                                           \
        yychar = (Token);                                         \
        yylval = (Value);                                         \
        YYPOPSTACK (yylen);                                       \
        yystate = *yyssp;                                         \
        goto yybackup;                                            \
      }                                                           \
    else                                                          \
      {                                                           \
        yyerror (&yylloc, P, YY_("syntax error: cannot back up")); \
        YYERROR;                                                  \
      }                                                           \
  while (0)

/* Backward compatibility with an undocumented macro.
   Use YYerror or YYUNDEF. */
#define YYERRCODE YYUNDEF

/* YYLLOC_DEFAULT -- Set CURRENT to span from RHS[1] to RHS[N].
   If N is 0, then set CURRENT to the empty location which ends
   the previous symbol: RHS[0] (always defined).  */

#ifndef YYLLOC_DEFAULT
# define YYLLOC_DEFAULT(Current, Rhs, N)                                \
    do                                                                  \
      if (N)                                                            \
        {                                                               \
          (Current).first_line   = YYRHSLOC (Rhs, 1).first_line;        \
          (Current).first_column = YYRHSLOC (Rhs, 1).first_column;      \
          (Current).last_line    = YYRHSLOC (Rhs, N).last_line;         \
          (Current).last_column  = YYRHSLOC (Rhs, N).last_column;       \
        }                                                               \
      else                                                              \
        {                                                               \
          (Current).first_line   = (Current).last_line   =              \
            YYRHSLOC (Rhs, 0).last_line;                                \
          (Current).first_column = (Current).last_column =              \
            YYRHSLOC (Rhs, 0).last_column;                              \
        }                                                               \
    while (0)
#endif

#define YYRHSLOC(Rhs, K) ((Rhs)[K])


/* Enable debugging if requested.  */
#if YYDEBUG

# ifndef YYFPRINTF
#  include <stdio.h> /* INFRINGES ON USER NAME SPACE */
#  define YYFPRINTF fprintf
# endif

# define YYDPRINTF(Args)                        \
do {                                            \
  if (yydebug)                                  \
    YYFPRINTF Args;                             \
} while (0)


/* YYLOCATION_PRINT -- Print the location on the stream.
   This macro was not mandated originally: define only if we know
   we won't break user code: when these are the locations we know.  */

# ifndef YYLOCATION_PRINT

#  if defined YY_LOCATION_PRINT

   /* Temporary convenience wrapper in case some people defined the
      undocumented and private YY_LOCATION_PRINT macros.  */
#   define YYLOCATION_PRINT(File, Loc)  YY_LOCATION_PRINT(File, *(Loc))

#  elif defined YYLTYPE_IS_TRIVIAL && YYLTYPE_IS_TRIVIAL

/* Print *YYLOCP on YYO.  Private, do not rely on its existence. */

YY_ATTRIBUTE_UNUSED
static int
yy_location_print_ (FILE *yyo, YYLTYPE const * const yylocp)
{
  int res = 0;
  int end_col = 0 != yylocp->last_column ? yylocp->last_column - 1 : 0;
  if (0 <= yylocp->first_line)
    {
      res += YYFPRINTF (yyo, "%d", yylocp->first_line);
      if (0 <= yylocp->first_column)
        res += YYFPRINTF (yyo, ".%d", yylocp->first_column);
    }
  if (0 <= yylocp->last_line)
    {
      if (yylocp->first_line < yylocp->last_line)
        {
          res += YYFPRINTF (yyo, "-%d", yylocp->last_line);
          if (0 <= end_col)
            res += YYFPRINTF (yyo, ".%d", end_col);
        }
      else if (0 <= end_col && yylocp->first_column < end_col)
        res += YYFPRINTF (yyo, "-%d", end_col);
    }
  return res;
}

#   define YYLOCATION_PRINT  yy_location_print_

    /* Temporary convenience wrapper in case some people defined the
       undocumented and private YY_LOCATION_PRINT macros.  */
#   define YY_LOCATION_PRINT(File, Loc)  YYLOCATION_PRINT(File, &(Loc))

#  else

#   define YYLOCATION_PRINT(File, Loc) ((void) 0)
    /* Temporary convenience wrapper in case some people defined the
       undocumented and private YY_LOCATION_PRINT macros.  */
#   define YY_LOCATION_PRINT  YYLOCATION_PRINT

#  endif
# endif /* !defined YYLOCATION_PRINT */


# define YY_SYMBOL_PRINT(Title, Kind, Value, Location)                    \
do {                                                                      \
  if (yydebug)                                                            \
    {                                                                     \
      YYFPRINTF (stderr, "%s ", Title);                                   \
      yy_symbol_print (stderr,                                            \
                  Kind, Value, Location, P); \
      YYFPRINTF (stderr, "\n");                                           \
    }                                                                     \
} while (0)


/*-----------------------------------.
| Print this symbol's value on YYO.  |
`-----------------------------------*/

static void
yy_symbol_value_print (FILE *yyo,
                       yysymbol_kind_t yykind, YYSTYPE const * const yyvaluep, YYLTYPE const * const yylocationp, Parser *P)
{
  FILE *yyoutput = yyo;
  YY_USE (yyoutput);
  YY_USE (yylocationp);
  YY_USE (P);
  if (!yyvaluep)
    return;
  YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
  YY_USE (yykind);
  YY_IGNORE_MAYBE_UNINITIALIZED_END
}


/*---------------------------.
| Print this symbol on YYO.  |
`---------------------------*/

static void
yy_symbol_print (FILE *yyo,
                 yysymbol_kind_t yykind, YYSTYPE const * const yyvaluep, YYLTYPE const * const yylocationp, Parser *P)
{
  YYFPRINTF (yyo, "%s %s (",
             yykind < YYNTOKENS ? "token" : "nterm", yysymbol_name (yykind));

  YYLOCATION_PRINT (yyo, yylocationp);
  YYFPRINTF (yyo, ": ");
  yy_symbol_value_print (yyo, yykind, yyvaluep, yylocationp, P);
  YYFPRINTF (yyo, ")");
}

/*------------------------------------------------------------------.
| yy_stack_print -- Print the state stack from its BOTTOM up to its |
| TOP (included).                                                   |
`------------------------------------------------------------------*/

static void
yy_stack_print (yy_state_t *yybottom, yy_state_t *yytop)
{
  YYFPRINTF (stderr, "Stack now");
  for (; yybottom <= yytop; yybottom++)
    {
      int yybot = *yybottom;
      YYFPRINTF (stderr, " %d", yybot);
    }
  YYFPRINTF (stderr, "\n");
}

# define YY_STACK_PRINT(Bottom, Top)                            \
do {                                                            \
  if (yydebug)                                                  \
    yy_stack_print ((Bottom), (Top));                           \
} while (0)


/*------------------------------------------------.
| Report that the YYRULE is going to be reduced.  |
`------------------------------------------------*/

static void
yy_reduce_print (yy_state_t *yyssp, YYSTYPE *yyvsp, YYLTYPE *yylsp,
                 int yyrule, Parser *P)
{
  int yylno = yyrline[yyrule];
  int yynrhs = yyr2[yyrule];
  int yyi;
  YYFPRINTF (stderr, "Reducing stack by rule %d (line %d):\n",
             yyrule - 1, yylno);
  /* The symbols being reduced.  */
  for (yyi = 0; yyi < yynrhs; yyi++)
    {
      YYFPRINTF (stderr, "   $%d = ", yyi + 1);
      yy_symbol_print (stderr,
                       YY_ACCESSING_SYMBOL (+yyssp[yyi + 1 - yynrhs]),
                       &yyvsp[(yyi + 1) - (yynrhs)],
                       &(yylsp[(yyi + 1) - (yynrhs)]), P);
      YYFPRINTF (stderr, "\n");
    }
}

# define YY_REDUCE_PRINT(Rule)          \
do {                                    \
  if (yydebug)                          \
    yy_reduce_print (yyssp, yyvsp, yylsp, Rule, P); \
} while (0)

/* Nonzero means print parse trace.  It is left uninitialized so that
   multiple parsers can coexist.  */
int yydebug;
#else /* !YYDEBUG */
# define YYDPRINTF(Args) ((void) 0)
# define YY_SYMBOL_PRINT(Title, Kind, Value, Location)
# define YY_STACK_PRINT(Bottom, Top)
# define YY_REDUCE_PRINT(Rule)
#endif /* !YYDEBUG */


/* YYINITDEPTH -- initial size of the parser's stacks.  */
#ifndef YYINITDEPTH
# define YYINITDEPTH 200
#endif

/* YYMAXDEPTH -- maximum size the stacks can grow to (effective only
   if the built-in stack extension method is used).

   Do not make this value too large; the results are undefined if
   YYSTACK_ALLOC_MAXIMUM < YYSTACK_BYTES (YYMAXDEPTH)
   evaluated with infinite-precision integer arithmetic.  */

#ifndef YYMAXDEPTH
# define YYMAXDEPTH 10000
#endif


/* Context of a parse error.  */
typedef struct
{
  yy_state_t *yyssp;
  yysymbol_kind_t yytoken;
  YYLTYPE *yylloc;
} yypcontext_t;

/* Put in YYARG at most YYARGN of the expected tokens given the
   current YYCTX, and return the number of tokens stored in YYARG.  If
   YYARG is null, return the number of expected tokens (guaranteed to
   be less than YYNTOKENS).  Return YYENOMEM on memory exhaustion.
   Return 0 if there are more than YYARGN expected tokens, yet fill
   YYARG up to YYARGN. */
static int
yypcontext_expected_tokens (const yypcontext_t *yyctx,
                            yysymbol_kind_t yyarg[], int yyargn)
{
  /* Actual size of YYARG. */
  int yycount = 0;
  int yyn = yypact[+*yyctx->yyssp];
  if (!yypact_value_is_default (yyn))
    {
      /* Start YYX at -YYN if negative to avoid negative indexes in
         YYCHECK.  In other words, skip the first -YYN actions for
         this state because they are default actions.  */
      int yyxbegin = yyn < 0 ? -yyn : 0;
      /* Stay within bounds of both yycheck and yytname.  */
      int yychecklim = YYLAST - yyn + 1;
      int yyxend = yychecklim < YYNTOKENS ? yychecklim : YYNTOKENS;
      int yyx;
      for (yyx = yyxbegin; yyx < yyxend; ++yyx)
        if (yycheck[yyx + yyn] == yyx && yyx != YYSYMBOL_YYerror
            && !yytable_value_is_error (yytable[yyx + yyn]))
          {
            if (!yyarg)
              ++yycount;
            else if (yycount == yyargn)
              return 0;
            else
              yyarg[yycount++] = YY_CAST (yysymbol_kind_t, yyx);
          }
    }
  if (yyarg && yycount == 0 && 0 < yyargn)
    yyarg[0] = YYSYMBOL_YYEMPTY;
  return yycount;
}




/* The kind of the lookahead of this context.  */
static yysymbol_kind_t
yypcontext_token (const yypcontext_t *yyctx) YY_ATTRIBUTE_UNUSED;

static yysymbol_kind_t
yypcontext_token (const yypcontext_t *yyctx)
{
  return yyctx->yytoken;
}

/* The location of the lookahead of this context.  */
static YYLTYPE *
yypcontext_location (const yypcontext_t *yyctx) YY_ATTRIBUTE_UNUSED;

static YYLTYPE *
yypcontext_location (const yypcontext_t *yyctx)
{
  return yyctx->yylloc;
}

/* User defined function to report a syntax error.  */
static int
yyreport_syntax_error (const yypcontext_t *yyctx, Parser *P);

/*-----------------------------------------------.
| Release the memory associated to this symbol.  |
`-----------------------------------------------*/

static void
yydestruct (const char *yymsg,
            yysymbol_kind_t yykind, YYSTYPE *yyvaluep, YYLTYPE *yylocationp, Parser *P)
{
  YY_USE (yyvaluep);
  YY_USE (yylocationp);
  YY_USE (P);
  if (!yymsg)
    yymsg = "Deleting";
  YY_SYMBOL_PRINT (yymsg, yykind, yyvaluep, yylocationp);

  YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
  YY_USE (yykind);
  YY_IGNORE_MAYBE_UNINITIALIZED_END
}






/*----------.
| yyparse.  |
`----------*/

int
yyparse (Parser *P)
{
/* Lookahead token kind.  */
int yychar;


/* The semantic value of the lookahead symbol.  */
/* Default value used for initialization, for pacifying older GCCs
   or non-GCC compilers.  */
YY_INITIAL_VALUE (static YYSTYPE yyval_default;)
YYSTYPE yylval YY_INITIAL_VALUE (= yyval_default);

/* Location data for the lookahead symbol.  */
static YYLTYPE yyloc_default
# if defined YYLTYPE_IS_TRIVIAL && YYLTYPE_IS_TRIVIAL
  = { 1, 1, 1, 1 }
# endif
;
YYLTYPE yylloc = yyloc_default;

    /* Number of syntax errors so far.  */
    int yynerrs = 0;

    yy_state_fast_t yystate = 0;
    /* Number of tokens to shift before error messages enabled.  */
    int yyerrstatus = 0;

    /* Refer to the stacks through separate pointers, to allow yyoverflow
       to reallocate them elsewhere.  */

    /* Their size.  */
    YYPTRDIFF_T yystacksize = YYINITDEPTH;

    /* The state stack: array, bottom, top.  */
    yy_state_t yyssa[YYINITDEPTH];
    yy_state_t *yyss = yyssa;
    yy_state_t *yyssp = yyss;

    /* The semantic value stack: array, bottom, top.  */
    YYSTYPE yyvsa[YYINITDEPTH];
    YYSTYPE *yyvs = yyvsa;
    YYSTYPE *yyvsp = yyvs;

    /* The location stack: array, bottom, top.  */
    YYLTYPE yylsa[YYINITDEPTH];
    YYLTYPE *yyls = yylsa;
    YYLTYPE *yylsp = yyls;

  int yyn;
  /* The return value of yyparse.  */
  int yyresult;
  /* Lookahead symbol kind.  */
  yysymbol_kind_t yytoken = YYSYMBOL_YYEMPTY;
  /* The variables used to return semantic value and location from the
     action routines.  */
  YYSTYPE yyval;
  YYLTYPE yyloc;

  /* The locations where the error started and ended.  */
  YYLTYPE yyerror_range[3];



#define YYPOPSTACK(N)   (yyvsp -= (N), yyssp -= (N), yylsp -= (N))

  /* The number of symbols on the RHS of the reduced rule.
     Keep to zero when no symbol should be popped.  */
  int yylen = 0;

  YYDPRINTF ((stderr, "Starting parse\n"));

  yychar = YYEMPTY; /* Cause a token to be read.  */

  yylsp[0] = yylloc;
  goto yysetstate;


/*------------------------------------------------------------.
| yynewstate -- push a new state, which is found in yystate.  |
`------------------------------------------------------------*/
yynewstate:
  /* In all cases, when you get here, the value and location stacks
     have just been pushed.  So pushing a state here evens the stacks.  */
  yyssp++;


/*--------------------------------------------------------------------.
| yysetstate -- set current state (the top of the stack) to yystate.  |
`--------------------------------------------------------------------*/
yysetstate:
  YYDPRINTF ((stderr, "Entering state %d\n", yystate));
  YY_ASSERT (0 <= yystate && yystate < YYNSTATES);
  YY_IGNORE_USELESS_CAST_BEGIN
  *yyssp = YY_CAST (yy_state_t, yystate);
  YY_IGNORE_USELESS_CAST_END
  YY_STACK_PRINT (yyss, yyssp);

  if (yyss + yystacksize - 1 <= yyssp)
#if !defined yyoverflow && !defined YYSTACK_RELOCATE
    YYNOMEM;
#else
    {
      /* Get the current used size of the three stacks, in elements.  */
      YYPTRDIFF_T yysize = yyssp - yyss + 1;

# if defined yyoverflow
      {
        /* Give user a chance to reallocate the stack.  Use copies of
           these so that the &'s don't force the real ones into
           memory.  */
        yy_state_t *yyss1 = yyss;
        YYSTYPE *yyvs1 = yyvs;
        YYLTYPE *yyls1 = yyls;

        /* Each stack pointer address is followed by the size of the
           data in use in that stack, in bytes.  This used to be a
           conditional around just the two extra args, but that might
           be undefined if yyoverflow is a macro.  */
        yyoverflow (YY_("memory exhausted"),
                    &yyss1, yysize * YYSIZEOF (*yyssp),
                    &yyvs1, yysize * YYSIZEOF (*yyvsp),
                    &yyls1, yysize * YYSIZEOF (*yylsp),
                    &yystacksize);
        yyss = yyss1;
        yyvs = yyvs1;
        yyls = yyls1;
      }
# else /* defined YYSTACK_RELOCATE */
      /* Extend the stack our own way.  */
      if (YYMAXDEPTH <= yystacksize)
        YYNOMEM;
      yystacksize *= 2;
      if (YYMAXDEPTH < yystacksize)
        yystacksize = YYMAXDEPTH;

      {
        yy_state_t *yyss1 = yyss;
        union yyalloc *yyptr =
          YY_CAST (union yyalloc *,
                   YYSTACK_ALLOC (YY_CAST (YYSIZE_T, YYSTACK_BYTES (yystacksize))));
        if (! yyptr)
          YYNOMEM;
        YYSTACK_RELOCATE (yyss_alloc, yyss);
        YYSTACK_RELOCATE (yyvs_alloc, yyvs);
        YYSTACK_RELOCATE (yyls_alloc, yyls);
#  undef YYSTACK_RELOCATE
        if (yyss1 != yyssa)
          YYSTACK_FREE (yyss1);
      }
# endif

      yyssp = yyss + yysize - 1;
      yyvsp = yyvs + yysize - 1;
      yylsp = yyls + yysize - 1;

      YY_IGNORE_USELESS_CAST_BEGIN
      YYDPRINTF ((stderr, "Stack size increased to %ld\n",
                  YY_CAST (long, yystacksize)));
      YY_IGNORE_USELESS_CAST_END

      if (yyss + yystacksize - 1 <= yyssp)
        YYABORT;
    }
#endif /* !defined yyoverflow && !defined YYSTACK_RELOCATE */


  if (yystate == YYFINAL)
    YYACCEPT;

  goto yybackup;


/*-----------.
| yybackup.  |
`-----------*/
yybackup:
  /* Do appropriate processing given the current state.  Read a
     lookahead token if we need one and don't already have one.  */

  /* First try to decide what to do without reference to lookahead token.  */
  yyn = yypact[yystate];
  if (yypact_value_is_default (yyn))
    goto yydefault;

  /* Not known => get a lookahead token if don't already have one.  */

  /* YYCHAR is either empty, or end-of-input, or a valid lookahead.  */
  if (yychar == YYEMPTY)
    {
      YYDPRINTF ((stderr, "Reading a token\n"));
      yychar = yylex (&yylval, &yylloc, P);
    }

  if (yychar <= END)
    {
      yychar = END;
      yytoken = YYSYMBOL_YYEOF;
      YYDPRINTF ((stderr, "Now at end of input.\n"));
    }
  else if (yychar == YYerror)
    {
      /* The scanner already issued an error message, process directly
         to error recovery.  But do not keep the error token as
         lookahead, it is too special and may lead us to an endless
         loop in error recovery. */
      yychar = YYUNDEF;
      yytoken = YYSYMBOL_YYerror;
      yyerror_range[1] = yylloc;
      goto yyerrlab1;
    }
  else
    {
      yytoken = YYTRANSLATE (yychar);
      YY_SYMBOL_PRINT ("Next token is", yytoken, &yylval, &yylloc);
    }

  /* If the proper action on seeing token YYTOKEN is to reduce or to
     detect an error, take that action.  */
  yyn += yytoken;
  if (yyn < 0 || YYLAST < yyn || yycheck[yyn] != yytoken)
    goto yydefault;
  yyn = yytable[yyn];
  if (yyn <= 0)
    {
      if (yytable_value_is_error (yyn))
        goto yyerrlab;
      yyn = -yyn;
      goto yyreduce;
    }

  /* Count tokens shifted since error; after three, turn off error
     status.  */
  if (yyerrstatus)
    yyerrstatus--;

  /* Shift the lookahead token.  */
  YY_SYMBOL_PRINT ("Shifting", yytoken, &yylval, &yylloc);
  yystate = yyn;
  YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
  *++yyvsp = yylval;
  YY_IGNORE_MAYBE_UNINITIALIZED_END
  *++yylsp = yylloc;

  /* Discard the shifted token.  */
  yychar = YYEMPTY;
  goto yynewstate;


/*-----------------------------------------------------------.
| yydefault -- do the default action for the current state.  |
`-----------------------------------------------------------*/
yydefault:
  yyn = yydefact[yystate];
  if (yyn == 0)
    goto yyerrlab;
  goto yyreduce;


/*-----------------------------.
| yyreduce -- do a reduction.  |
`-----------------------------*/
yyreduce:
  /* yyn is the number of a rule to reduce with.  */
  yylen = yyr2[yyn];

  /* If YYLEN is nonzero, implement the default value of the action:
     '$$ = $1'.

     Otherwise, the following line sets YYVAL to garbage.
     This behavior is undocumented and Bison
     users should not rely upon it.  Assigning to YYVAL
     unconditionally makes the parser a bit smaller, and it avoids a
     GCC warning that YYVAL may be used uninitialized.  */
  yyval = yyvsp[1-yylen];

  /* Default location. */
  YYLLOC_DEFAULT (yyloc, (yylsp - yylen), yylen);
  yyerror_range[1] = yyloc;
  YY_REDUCE_PRINT (yyn);
  switch (yyn)
    {
  case 5: /* line: stmt "end of line"  */
#line 279 "compiler/front/parse.y"
                             { if ((yyvsp[-1].stmt)) layout_append(P, (yyvsp[-1].stmt)); }
#line 1712 "build2/parse.c"
    break;

  case 6: /* line: block  */
#line 280 "compiler/front/parse.y"
                             { if ((yyvsp[0].stmt)) layout_append(P, (yyvsp[0].stmt)); }
#line 1718 "build2/parse.c"
    break;

  case 7: /* line: error "end of line"  */
#line 281 "compiler/front/parse.y"
                             { yyerrok; layout_skip_block(P); }
#line 1724 "build2/parse.c"
    break;

  case 8: /* stmt: "'global'" "name" '=' expr  */
#line 285 "compiler/front/parse.y"
                                {
		(yyval.stmt) = stmt(S_GLOBAL, (yyloc)); (yyval.stmt)->name = (yyvsp[-2].str); (yyval.stmt)->name_loc = LOC((yylsp[-2])); (yyval.stmt)->value = (yyvsp[0].expr);
	}
#line 1732 "build2/parse.c"
    break;

  case 9: /* stmt: "'object'" objname ':' "name"  */
#line 288 "compiler/front/parse.y"
                                   {
		(yyval.stmt) = obj_stmt(S_OBJKIND, (yyloc), (yyvsp[-2].oname)); (yyval.stmt)->prop = (yyvsp[0].str); (yyval.stmt)->prop_loc = LOC((yylsp[0]));
	}
#line 1740 "build2/parse.c"
    break;

  case 10: /* stmt: "'object'" objname ':' "name" "string"  */
#line 291 "compiler/front/parse.y"
                                          {
		(yyval.stmt) = obj_stmt(S_OBJKIND, (yyloc), (yyvsp[-3].oname)); (yyval.stmt)->prop = (yyvsp[-1].str); (yyval.stmt)->prop_loc = LOC((yylsp[-1])); (yyval.stmt)->from = (yyvsp[0].str);
		if (strcmp((yyvsp[-1].str), "from") != 0) {
			error_at(LOC((yylsp[-1])), "a string after ':' reads a data file: 'object %s[]: from \"%s\"'", (yyvsp[-3].oname)->name, (yyvsp[0].str));
			(yyval.stmt) = NULL;
		} else if ((yyvsp[-3].oname)->arr != ARR_FILE) {
			error_at(LOC((yylsp[-3])), "the members read from a data file are numbered by its rows: 'object %s[]: from \"%s\"'",
			         (yyvsp[-3].oname)->name, (yyvsp[0].str));
			(yyval.stmt) = NULL;
		} /* else the members, one per data row: objects.c */
	}
#line 1756 "build2/parse.c"
    break;

  case 11: /* stmt: "'object'" objname ':' "name" '=' expr atol  */
#line 302 "compiler/front/parse.y"
                                                 {
		(yyval.stmt) = obj_stmt(S_PROP, (yyloc), (yyvsp[-5].oname)); (yyval.stmt)->prop = (yyvsp[-3].str); (yyval.stmt)->prop_loc = LOC((yylsp[-3]));
		(yyval.stmt)->value = (yyvsp[-1].expr); (yyval.stmt)->atol = (yyvsp[0].expr);
	}
#line 1765 "build2/parse.c"
    break;

  case 12: /* stmt: "'object'" objname ':' "'vector'" "name" '=' expr atol  */
#line 306 "compiler/front/parse.y"
                                                        {
		(yyval.stmt) = obj_stmt(S_PROP, (yyloc), (yyvsp[-6].oname)); (yyval.stmt)->prop = (yyvsp[-3].str); (yyval.stmt)->prop_loc = LOC((yylsp[-3]));
		(yyval.stmt)->value = (yyvsp[-1].expr); (yyval.stmt)->isvec = 1; (yyval.stmt)->atol = (yyvsp[0].expr);
	}
#line 1774 "build2/parse.c"
    break;

  case 13: /* stmt: "'vector'" names  */
#line 310 "compiler/front/parse.y"
                       {
		(yyval.stmt) = stmt(S_VECDECL, (yyloc)); (yyval.stmt)->names = (yyvsp[0].vec);
	}
#line 1782 "build2/parse.c"
    break;

  case 14: /* stmt: "'rule'" attr ':' eqn  */
#line 313 "compiler/front/parse.y"
                            {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-2].str); (yyval.stmt)->eqns = (yyvsp[0].eqn);
	}
#line 1790 "build2/parse.c"
    break;

  case 15: /* stmt: "'rule'" attr "'for'" objrefs ':' eqn  */
#line 316 "compiler/front/parse.y"
                                        {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-4].str); (yyval.stmt)->fors = (yyvsp[-2].vec); (yyval.stmt)->has_for = 1; (yyval.stmt)->eqns = (yyvsp[0].eqn);
	}
#line 1798 "build2/parse.c"
    break;

  case 16: /* stmt: "'rule'" attr ':' expr  */
#line 319 "compiler/front/parse.y"
                             {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-2].str); (yyval.stmt)->call = (yyvsp[0].expr);
	}
#line 1806 "build2/parse.c"
    break;

  case 17: /* stmt: "'rule'" attr "'for'" objrefs ':' expr  */
#line 322 "compiler/front/parse.y"
                                         {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-4].str); (yyval.stmt)->fors = (yyvsp[-2].vec); (yyval.stmt)->has_for = 1; (yyval.stmt)->call = (yyvsp[0].expr);
	}
#line 1814 "build2/parse.c"
    break;

  case 18: /* stmt: "'assert'" expr  */
#line 325 "compiler/front/parse.y"
                      {
		(yyval.stmt) = stmt(S_ASSERT, (yyloc)); (yyval.stmt)->cond = (yyvsp[0].expr); (yyval.stmt)->text = text_from(LOC((yylsp[0])));
	}
#line 1822 "build2/parse.c"
    break;

  case 19: /* stmt: "'when'" expr ':' eqn  */
#line 328 "compiler/front/parse.y"
                                              { (yyval.stmt) = when_stmt((yylsp[-3]), (yyvsp[-2].expr), (yylsp[-1]), NULL, (yyvsp[0].eqn)); }
#line 1828 "build2/parse.c"
    break;

  case 20: /* stmt: "'when'" "'for'" objrefs ':' expr ':' eqn  */
#line 329 "compiler/front/parse.y"
                                              { (yyval.stmt) = when_stmt((yylsp[-6]), (yyvsp[-2].expr), (yylsp[-1]), &(yyvsp[-4].vec), (yyvsp[0].eqn)); }
#line 1834 "build2/parse.c"
    break;

  case 21: /* stmt: "'stop'" "'when'" expr  */
#line 330 "compiler/front/parse.y"
                         {
		(yyval.stmt) = stmt(S_STOP, (yyloc)); (yyval.stmt)->cond = (yyvsp[0].expr); (yyval.stmt)->text = text_from(LOC((yylsp[0])));
	}
#line 1842 "build2/parse.c"
    break;

  case 22: /* stmt: "'inc'" "name" till by  */
#line 333 "compiler/front/parse.y"
                            {
		(yyval.stmt) = stmt(S_START, (yyloc)); (yyval.stmt)->var = (yyvsp[-2].str); (yyval.stmt)->name_loc = LOC((yylsp[-2])); (yyval.stmt)->till = (yyvsp[-1].expr); (yyval.stmt)->by = (yyvsp[0].expr);
	}
#line 1850 "build2/parse.c"
    break;

  case 23: /* stmt: "'inc'" "name" till by "'watch'" watches  */
#line 336 "compiler/front/parse.y"
                                          {
		(yyval.stmt) = stmt(S_START, (yyloc)); (yyval.stmt)->var = (yyvsp[-4].str); (yyval.stmt)->name_loc = LOC((yylsp[-4])); (yyval.stmt)->till = (yyvsp[-3].expr); (yyval.stmt)->by = (yyvsp[-2].expr);
		(yyval.stmt)->watch = (yyvsp[0].vec); (yyval.stmt)->has_watch = 1;
	}
#line 1859 "build2/parse.c"
    break;

  case 24: /* objname: "name"  */
#line 344 "compiler/front/parse.y"
                               { (yyval.oname) = xalloc(sizeof *(yyval.oname)); (yyval.oname)->name = (yyvsp[0].str); (yyval.oname)->loc = (yylsp[0]); }
#line 1865 "build2/parse.c"
    break;

  case 25: /* objname: "name" '[' index ']'  */
#line 345 "compiler/front/parse.y"
                               { (yyval.oname) = xalloc(sizeof *(yyval.oname)); (yyval.oname)->name = (yyvsp[-3].str); (yyval.oname)->loc = (yylsp[-3]); (yyval.oname)->arr = ARR_ONE; (yyval.oname)->lo = (yyvsp[-1].idx); }
#line 1871 "build2/parse.c"
    break;

  case 26: /* objname: "name" '[' index "'..'" index ']'  */
#line 346 "compiler/front/parse.y"
                                           {
		(yyval.oname) = xalloc(sizeof *(yyval.oname)); (yyval.oname)->name = (yyvsp[-5].str); (yyval.oname)->loc = (yylsp[-5]); (yyval.oname)->arr = ARR_RANGE; (yyval.oname)->lo = (yyvsp[-3].idx); (yyval.oname)->hi = (yyvsp[-1].idx);
		if ((yyvsp[-1].idx) < (yyvsp[-3].idx)) error_at(LOC((yylsp[-1])), "an object array 'NAME[A..B]' needs A <= B, not %ld..%ld", (yyvsp[-3].idx), (yyvsp[-1].idx));
		else if ((yyvsp[-1].idx) - (yyvsp[-3].idx) >= 100000000) error_at(LOC((yylsp[-1])), "an object array has at most 100000000 members");
	}
#line 1881 "build2/parse.c"
    break;

  case 27: /* objname: "name" '[' "name" ']'  */
#line 351 "compiler/front/parse.y"
                               { (yyval.oname) = xalloc(sizeof *(yyval.oname)); (yyval.oname)->name = (yyvsp[-3].str); (yyval.oname)->loc = (yylsp[-3]); (yyval.oname)->arr = ARR_EACH; (yyval.oname)->ivar = (yyvsp[-1].str); }
#line 1887 "build2/parse.c"
    break;

  case 28: /* objname: "name" '[' ']'  */
#line 352 "compiler/front/parse.y"
                               { (yyval.oname) = xalloc(sizeof *(yyval.oname)); (yyval.oname)->name = (yyvsp[-2].str); (yyval.oname)->loc = (yylsp[-2]); (yyval.oname)->arr = ARR_FILE; }
#line 1893 "build2/parse.c"
    break;

  case 29: /* index: "number"  */
#line 356 "compiler/front/parse.y"
                               { (yyval.idx) = array_index((yyvsp[0].num), (yylsp[0])); }
#line 1899 "build2/parse.c"
    break;

  case 30: /* index: '-' "number"  */
#line 357 "compiler/front/parse.y"
                               { (yyval.idx) = -array_index((yyvsp[0].num), (yylsp[0])); }
#line 1905 "build2/parse.c"
    break;

  case 31: /* till: %empty  */
#line 360 "compiler/front/parse.y"
             { (yyval.expr) = NULL; }
#line 1911 "build2/parse.c"
    break;

  case 32: /* till: "'till'" expr  */
#line 360 "compiler/front/parse.y"
                                        { (yyval.expr) = (yyvsp[0].expr); }
#line 1917 "build2/parse.c"
    break;

  case 33: /* atol: %empty  */
#line 363 "compiler/front/parse.y"
             { (yyval.expr) = NULL; }
#line 1923 "build2/parse.c"
    break;

  case 34: /* atol: "'atol'" expr  */
#line 363 "compiler/front/parse.y"
                                        { (yyval.expr) = (yyvsp[0].expr); }
#line 1929 "build2/parse.c"
    break;

  case 35: /* by: %empty  */
#line 364 "compiler/front/parse.y"
             { (yyval.expr) = NULL; }
#line 1935 "build2/parse.c"
    break;

  case 36: /* by: "'by'" expr  */
#line 364 "compiler/front/parse.y"
                                        { (yyval.expr) = (yyvsp[0].expr); }
#line 1941 "build2/parse.c"
    break;

  case 37: /* attr: %empty  */
#line 366 "compiler/front/parse.y"
             { (yyval.str) = NULL; }
#line 1947 "build2/parse.c"
    break;

  case 38: /* attr: "name"  */
#line 366 "compiler/front/parse.y"
                                    { (yyval.str) = (yyvsp[0].str); }
#line 1953 "build2/parse.c"
    break;

  case 39: /* block: "'def'" "name" ':' "end of line" "indented block" defprops "end of indented block"  */
#line 369 "compiler/front/parse.y"
                                                       {
		(yyval.stmt) = stmt(S_DEF, (yyloc)); (yyval.stmt)->name = (yyvsp[-5].str); (yyval.stmt)->name_loc = LOC((yylsp[-5])); (yyval.stmt)->body = stmts_reversed((yyvsp[-1].stmt));
	}
#line 1961 "build2/parse.c"
    break;

  case 40: /* block: "'rule'" attr ':' ifblock  */
#line 372 "compiler/front/parse.y"
                                {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-2].str); (yyval.stmt)->eqns = (yyvsp[0].eqn);
	}
#line 1969 "build2/parse.c"
    break;

  case 41: /* block: "'rule'" attr "'for'" objrefs ':' ifblock  */
#line 375 "compiler/front/parse.y"
                                            {
		(yyval.stmt) = stmt(S_RULE, (yyloc)); (yyval.stmt)->attr = (yyvsp[-4].str); (yyval.stmt)->fors = (yyvsp[-2].vec); (yyval.stmt)->has_for = 1; (yyval.stmt)->eqns = (yyvsp[0].eqn);
	}
#line 1977 "build2/parse.c"
    break;

  case 42: /* block: "'when'" expr ':' body  */
#line 378 "compiler/front/parse.y"
                                              { (yyval.stmt) = when_stmt((yylsp[-3]), (yyvsp[-2].expr), (yylsp[-1]), NULL, (yyvsp[0].eqn)); }
#line 1983 "build2/parse.c"
    break;

  case 43: /* block: "'when'" "'for'" objrefs ':' expr ':' body  */
#line 379 "compiler/front/parse.y"
                                              { (yyval.stmt) = when_stmt((yylsp[-6]), (yyvsp[-2].expr), (yylsp[-1]), &(yyvsp[-4].vec), (yyvsp[0].eqn)); }
#line 1989 "build2/parse.c"
    break;

  case 44: /* ifblock: "'if'" expr ':' body elsepart  */
#line 384 "compiler/front/parse.y"
                                    { (yyval.eqn) = cond_block((yylsp[-4]), (yyvsp[-3].expr), (yyvsp[-1].eqn), (yyvsp[0].cond)); }
#line 1995 "build2/parse.c"
    break;

  case 45: /* elsepart: %empty  */
#line 389 "compiler/front/parse.y"
                             { (yyval.cond) = NULL; }
#line 2001 "build2/parse.c"
    break;

  case 46: /* elsepart: "'else'" ':' body  */
#line 390 "compiler/front/parse.y"
                             { (yyval.cond) = xalloc(sizeof *(yyval.cond)); (yyval.cond)->els = (yyvsp[0].eqn); (yyval.cond)->else_loc = LOC((yylsp[-2])); }
#line 2007 "build2/parse.c"
    break;

  case 47: /* elsepart: "'elif'" expr ':' body elsepart  */
#line 391 "compiler/front/parse.y"
                                      {
		(yyval.cond) = xalloc(sizeof *(yyval.cond)); (yyval.cond)->els = cond_block((yylsp[-4]), (yyvsp[-3].expr), (yyvsp[-1].eqn), (yyvsp[0].cond)); (yyval.cond)->els->nest->elif = 1;
	}
#line 2015 "build2/parse.c"
    break;

  case 48: /* body: "end of line" "indented block" steps "end of indented block"  */
#line 397 "compiler/front/parse.y"
                                      { (yyval.eqn) = eqns_reversed((yyvsp[-1].eqn)); }
#line 2021 "build2/parse.c"
    break;

  case 49: /* defprops: defprop  */
#line 401 "compiler/front/parse.y"
                             { (yyval.stmt) = (yyvsp[0].stmt); }
#line 2027 "build2/parse.c"
    break;

  case 50: /* defprops: defprops defprop  */
#line 402 "compiler/front/parse.y"
                             { (yyval.stmt) = (yyvsp[-1].stmt); if ((yyvsp[0].stmt)) { (yyvsp[0].stmt)->next = (yyval.stmt); (yyval.stmt) = (yyvsp[0].stmt); } }
#line 2033 "build2/parse.c"
    break;

  case 51: /* defprop: "name" '=' expr "end of line"  */
#line 406 "compiler/front/parse.y"
                                 {
		(yyval.stmt) = stmt(S_PROP, (yyloc)); (yyval.stmt)->prop = (yyvsp[-3].str); (yyval.stmt)->prop_loc = LOC((yylsp[-3])); (yyval.stmt)->value = (yyvsp[-1].expr);
	}
#line 2041 "build2/parse.c"
    break;

  case 52: /* defprop: "'vector'" "name" '=' expr "end of line"  */
#line 409 "compiler/front/parse.y"
                                        {
		(yyval.stmt) = stmt(S_PROP, (yyloc)); (yyval.stmt)->prop = (yyvsp[-3].str); (yyval.stmt)->prop_loc = LOC((yylsp[-3])); (yyval.stmt)->value = (yyvsp[-1].expr); (yyval.stmt)->isvec = 1;
	}
#line 2049 "build2/parse.c"
    break;

  case 53: /* defprop: error "end of line"  */
#line 412 "compiler/front/parse.y"
                        { (yyval.stmt) = NULL; yyerrok; layout_skip_block(P); }
#line 2055 "build2/parse.c"
    break;

  case 54: /* steps: step  */
#line 416 "compiler/front/parse.y"
                             { (yyval.eqn) = (yyvsp[0].eqn); }
#line 2061 "build2/parse.c"
    break;

  case 55: /* steps: steps step  */
#line 417 "compiler/front/parse.y"
                             { (yyval.eqn) = (yyvsp[-1].eqn); if ((yyvsp[0].eqn)) { (yyvsp[0].eqn)->next = (yyval.eqn); (yyval.eqn) = (yyvsp[0].eqn); } }
#line 2067 "build2/parse.c"
    break;

  case 56: /* step: eqn "end of line"  */
#line 421 "compiler/front/parse.y"
                             { (yyval.eqn) = (yyvsp[-1].eqn); }
#line 2073 "build2/parse.c"
    break;

  case 57: /* step: ifblock  */
#line 422 "compiler/front/parse.y"
                             { (yyval.eqn) = (yyvsp[0].eqn); }
#line 2079 "build2/parse.c"
    break;

  case 58: /* step: error "end of line"  */
#line 423 "compiler/front/parse.y"
                             { (yyval.eqn) = NULL; yyerrok; layout_skip_block(P); }
#line 2085 "build2/parse.c"
    break;

  case 59: /* eqn: expr '=' expr  */
#line 427 "compiler/front/parse.y"
                             { (yyval.eqn) = eqn((yyvsp[-2].expr), 0, (yyvsp[0].expr), (yyloc)); }
#line 2091 "build2/parse.c"
    break;

  case 60: /* eqn: expr '\'' '=' expr  */
#line 428 "compiler/front/parse.y"
                             {
		/* the derivative of a name of the rule's own objects; of anything else, one clear error */
		(yyval.eqn) = NULL;
		if ((yyvsp[-3].expr)->kind == E_NAME) (yyval.eqn) = eqn((yyvsp[-3].expr), 1, (yyvsp[0].expr), (yyloc));
		else if ((yyvsp[-3].expr)->kind == E_FIELD && (yyvsp[-3].expr)->a->kind == E_NAME)
			error_at(LOC((yylsp[-2])), "a derivative is written for the rule's own objects: 'rule for %s: %s' = ...', not "
			         "'%s.%s' = ...'", (yyvsp[-3].expr)->a->name, (yyvsp[-3].expr)->name, (yyvsp[-3].expr)->a->name, (yyvsp[-3].expr)->name);
		else
			error_at(LOC((yylsp[-2])), "only a name can have a derivative ('v' = a')");
	}
#line 2106 "build2/parse.c"
    break;

  case 61: /* names: "name"  */
#line 441 "compiler/front/parse.y"
                             { (yyval.vec) = (Vec){ 0 }; vec_push(&(yyval.vec), (yyvsp[0].str)); }
#line 2112 "build2/parse.c"
    break;

  case 62: /* names: names ',' "name"  */
#line 442 "compiler/front/parse.y"
                             { (yyval.vec) = (yyvsp[-2].vec); vec_push(&(yyval.vec), (yyvsp[0].str)); }
#line 2118 "build2/parse.c"
    break;

  case 63: /* objrefs: objref  */
#line 446 "compiler/front/parse.y"
                             { (yyval.vec) = (Vec){ 0 }; vec_push(&(yyval.vec), (yyvsp[0].ref)); }
#line 2124 "build2/parse.c"
    break;

  case 64: /* objrefs: objrefs ',' objref  */
#line 447 "compiler/front/parse.y"
                             { (yyval.vec) = (yyvsp[-2].vec); vec_push(&(yyval.vec), (yyvsp[0].ref)); }
#line 2130 "build2/parse.c"
    break;

  case 65: /* objref: "name"  */
#line 451 "compiler/front/parse.y"
                 { (yyval.ref) = xalloc(sizeof *(yyval.ref)); (yyval.ref)->loc = LOC((yylsp[0])); (yyval.ref)->name = (yyvsp[0].str); (yyval.ref)->index = -1; }
#line 2136 "build2/parse.c"
    break;

  case 66: /* objref: "number"  */
#line 452 "compiler/front/parse.y"
                 { (yyval.ref) = xalloc(sizeof *(yyval.ref)); (yyval.ref)->loc = LOC((yylsp[0])); (yyval.ref)->index = (yyvsp[0].num) >= 0 && (yyvsp[0].num) < 1e9 ? (int)(yyvsp[0].num) : 1000000000;
	           if ((yyval.ref)->index != (yyvsp[0].num)) error_at((yyval.ref)->loc, "object number must be a whole number"); }
#line 2143 "build2/parse.c"
    break;

  case 67: /* objref: "name" '[' expr ']'  */
#line 454 "compiler/front/parse.y"
                             { (yyval.ref) = xalloc(sizeof *(yyval.ref)); (yyval.ref)->loc = LOC((yylsp[-3])); (yyval.ref)->name = (yyvsp[-3].str); (yyval.ref)->index = -1; (yyval.ref)->idx = (yyvsp[-1].expr); }
#line 2149 "build2/parse.c"
    break;

  case 68: /* watches: watch  */
#line 458 "compiler/front/parse.y"
                             { (yyval.vec) = (Vec){ 0 }; vec_push(&(yyval.vec), (yyvsp[0].watch)); }
#line 2155 "build2/parse.c"
    break;

  case 69: /* watches: watches ',' watch  */
#line 459 "compiler/front/parse.y"
                             { (yyval.vec) = (yyvsp[-2].vec); vec_push(&(yyval.vec), (yyvsp[0].watch)); }
#line 2161 "build2/parse.c"
    break;

  case 70: /* watch: "name"  */
#line 463 "compiler/front/parse.y"
                             { (yyval.watch) = xalloc(sizeof *(yyval.watch)); (yyval.watch)->loc = LOC((yylsp[0])); (yyval.watch)->prop = (yyvsp[0].str); }
#line 2167 "build2/parse.c"
    break;

  case 71: /* watch: "name" '.' "name"  */
#line 464 "compiler/front/parse.y"
                             { (yyval.watch) = xalloc(sizeof *(yyval.watch)); (yyval.watch)->loc = LOC((yylsp[-2])); (yyval.watch)->obj = (yyvsp[-2].str); (yyval.watch)->prop = (yyvsp[0].str); }
#line 2173 "build2/parse.c"
    break;

  case 72: /* watch: "name" '.' "name" '.' "name"  */
#line 465 "compiler/front/parse.y"
                                    {
		(yyval.watch) = xalloc(sizeof *(yyval.watch)); (yyval.watch)->loc = LOC((yylsp[-4])); (yyval.watch)->obj = (yyvsp[-4].str); (yyval.watch)->prop = (yyvsp[-2].str); (yyval.watch)->comp = (yyvsp[0].str);
	}
#line 2181 "build2/parse.c"
    break;

  case 73: /* watch: "name" '[' index ']' '.' "name"  */
#line 468 "compiler/front/parse.y"
                                        {
		(yyval.watch) = xalloc(sizeof *(yyval.watch)); (yyval.watch)->loc = LOC((yylsp[-5])); (yyval.watch)->obj = xprintf("%s[%ld]", (yyvsp[-5].str), (yyvsp[-3].idx)); (yyval.watch)->prop = (yyvsp[0].str);
	}
#line 2189 "build2/parse.c"
    break;

  case 74: /* watch: "name" '[' index ']' '.' "name" '.' "name"  */
#line 471 "compiler/front/parse.y"
                                                  {
		(yyval.watch) = xalloc(sizeof *(yyval.watch)); (yyval.watch)->loc = LOC((yylsp[-7])); (yyval.watch)->obj = xprintf("%s[%ld]", (yyvsp[-7].str), (yyvsp[-5].idx)); (yyval.watch)->prop = (yyvsp[-2].str); (yyval.watch)->comp = (yyvsp[0].str);
	}
#line 2197 "build2/parse.c"
    break;

  case 75: /* expr: expr "'or'" expr  */
#line 477 "compiler/front/parse.y"
                             { (yyval.expr) = bin(OR, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2203 "build2/parse.c"
    break;

  case 76: /* expr: expr "'and'" expr  */
#line 478 "compiler/front/parse.y"
                             { (yyval.expr) = bin(AND, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2209 "build2/parse.c"
    break;

  case 77: /* expr: "'not'" expr  */
#line 479 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_NOT, LOC((yylsp[-1]))); (yyval.expr)->a = (yyvsp[0].expr); (yyval.expr) = nest((yyval.expr)); }
#line 2215 "build2/parse.c"
    break;

  case 78: /* expr: expr '<' expr  */
#line 480 "compiler/front/parse.y"
                             { (yyval.expr) = bin('<', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2221 "build2/parse.c"
    break;

  case 79: /* expr: expr '>' expr  */
#line 481 "compiler/front/parse.y"
                             { (yyval.expr) = bin('>', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2227 "build2/parse.c"
    break;

  case 80: /* expr: expr "'<='" expr  */
#line 482 "compiler/front/parse.y"
                             { (yyval.expr) = bin(LE, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2233 "build2/parse.c"
    break;

  case 81: /* expr: expr "'>='" expr  */
#line 483 "compiler/front/parse.y"
                             { (yyval.expr) = bin(GE, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2239 "build2/parse.c"
    break;

  case 82: /* expr: expr "'=='" expr  */
#line 484 "compiler/front/parse.y"
                             { (yyval.expr) = bin(EQEQ, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2245 "build2/parse.c"
    break;

  case 83: /* expr: expr "'!='" expr  */
#line 485 "compiler/front/parse.y"
                             { (yyval.expr) = bin(NE, (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2251 "build2/parse.c"
    break;

  case 84: /* expr: expr '+' expr  */
#line 486 "compiler/front/parse.y"
                             { (yyval.expr) = bin('+', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2257 "build2/parse.c"
    break;

  case 85: /* expr: expr '-' expr  */
#line 487 "compiler/front/parse.y"
                             { (yyval.expr) = bin('-', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2263 "build2/parse.c"
    break;

  case 86: /* expr: expr '*' expr  */
#line 488 "compiler/front/parse.y"
                             { (yyval.expr) = bin('*', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2269 "build2/parse.c"
    break;

  case 87: /* expr: expr '/' expr  */
#line 489 "compiler/front/parse.y"
                             { (yyval.expr) = bin('/', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2275 "build2/parse.c"
    break;

  case 88: /* expr: expr '^' expr  */
#line 490 "compiler/front/parse.y"
                             { (yyval.expr) = bin('^', (yyvsp[-2].expr), (yyvsp[0].expr), (yylsp[-1])); }
#line 2281 "build2/parse.c"
    break;

  case 89: /* expr: '-' expr  */
#line 491 "compiler/front/parse.y"
                                { (yyval.expr) = ast_expr(E_NEG, LOC((yylsp[-1]))); (yyval.expr)->a = (yyvsp[0].expr); (yyval.expr) = nest((yyval.expr)); }
#line 2287 "build2/parse.c"
    break;

  case 90: /* expr: '+' expr  */
#line 492 "compiler/front/parse.y"
                                { (yyval.expr) = (yyvsp[0].expr); }
#line 2293 "build2/parse.c"
    break;

  case 93: /* postfix: postfix '.' "name"  */
#line 498 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_FIELD, LOC((yylsp[0]))); (yyval.expr)->a = (yyvsp[-2].expr); (yyval.expr)->name = (yyvsp[0].str); (yyval.expr) = nest((yyval.expr)); }
#line 2299 "build2/parse.c"
    break;

  case 94: /* postfix: postfix '.' "name" '(' args ')'  */
#line 499 "compiler/front/parse.y"
                                         { (yyval.expr) = call(E_METHOD, (yyvsp[-5].expr), (yyvsp[-3].str), &(yyvsp[-1].vec), (yylsp[-3])); }
#line 2305 "build2/parse.c"
    break;

  case 95: /* primary: "number"  */
#line 503 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_NUM, LOC((yylsp[0]))); (yyval.expr)->num = (yyvsp[0].num); (yyval.expr)->depth = 1; }
#line 2311 "build2/parse.c"
    break;

  case 96: /* primary: "number" "unit"  */
#line 504 "compiler/front/parse.y"
                             { Expr *n = ast_expr(E_NUM, LOC((yylsp[-1]))); n->num = (yyvsp[-1].num); n->depth = 1; (yyval.expr) = with_unit(n, (yyvsp[0].tok)); }
#line 2317 "build2/parse.c"
    break;

  case 97: /* primary: "name"  */
#line 505 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_NAME, LOC((yylsp[0]))); (yyval.expr)->name = (yyvsp[0].str); (yyval.expr)->depth = 1; }
#line 2323 "build2/parse.c"
    break;

  case 98: /* primary: "name" "object number ($n)"  */
#line 506 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_DOLLAR, LOC((yylsp[-1]))); (yyval.expr)->name = (yyvsp[-1].str); (yyval.expr)->n = (yyvsp[0].n); (yyval.expr)->depth = 1; }
#line 2329 "build2/parse.c"
    break;

  case 99: /* primary: "name" '(' args ')'  */
#line 507 "compiler/front/parse.y"
                             { (yyval.expr) = call(E_CALL, NULL, (yyvsp[-3].str), &(yyvsp[-1].vec), (yylsp[-3])); }
#line 2335 "build2/parse.c"
    break;

  case 100: /* primary: "name" '(' expr "'for'" "name" ')'  */
#line 508 "compiler/front/parse.y"
                                       {
		/* sum(EXPR for NAME): over the members of an object array */
		(yyval.expr) = ast_expr(E_SUM, LOC((yylsp[-5]))); (yyval.expr)->name = (yyvsp[-1].str); (yyval.expr)->a = (yyvsp[-3].expr); (yyval.expr) = nest((yyval.expr));
		if (strcmp((yyvsp[-5].str), "sum") != 0) error_at(LOC((yylsp[-5])), "'%s(... for %s)': only 'sum' runs over the members of an object array", (yyvsp[-5].str), (yyvsp[-1].str));
	}
#line 2345 "build2/parse.c"
    break;

  case 101: /* primary: "name" '[' expr ']'  */
#line 513 "compiler/front/parse.y"
                             { (yyval.expr) = ast_expr(E_INDEX, LOC((yylsp[-3]))); (yyval.expr)->name = (yyvsp[-3].str); (yyval.expr)->a = (yyvsp[-1].expr); (yyval.expr) = nest((yyval.expr)); }
#line 2351 "build2/parse.c"
    break;

  case 102: /* primary: "name" '(' args ')' "unit"  */
#line 514 "compiler/front/parse.y"
                                  { (yyval.expr) = with_unit(call(E_CALL, NULL, (yyvsp[-4].str), &(yyvsp[-2].vec), (yylsp[-4])), (yyvsp[0].tok)); }
#line 2357 "build2/parse.c"
    break;

  case 103: /* primary: '(' expr ')'  */
#line 515 "compiler/front/parse.y"
                             { (yyval.expr) = (yyvsp[-1].expr); }
#line 2363 "build2/parse.c"
    break;

  case 104: /* primary: '(' expr ')' "unit"  */
#line 516 "compiler/front/parse.y"
                             { (yyval.expr) = with_unit((yyvsp[-2].expr), (yyvsp[0].tok)); }
#line 2369 "build2/parse.c"
    break;

  case 105: /* primary: '(' expr ',' expr ',' expr ')'  */
#line 517 "compiler/front/parse.y"
                                         {
		(yyval.expr) = ast_expr(E_VEC, LOC((yylsp[-6]))); (yyval.expr)->args = xalloc(3 * sizeof(Expr *)); (yyval.expr)->nargs = 3;
		(yyval.expr)->args[0] = (yyvsp[-5].expr); (yyval.expr)->args[1] = (yyvsp[-3].expr); (yyval.expr)->args[2] = (yyvsp[-1].expr); (yyval.expr) = nest((yyval.expr));
	}
#line 2378 "build2/parse.c"
    break;

  case 106: /* primary: '(' expr ',' expr ',' expr ')' "unit"  */
#line 521 "compiler/front/parse.y"
                                              {
		Expr *v = ast_expr(E_VEC, LOC((yylsp[-7]))); v->args = xalloc(3 * sizeof(Expr *)); v->nargs = 3;
		v->args[0] = (yyvsp[-6].expr); v->args[1] = (yyvsp[-4].expr); v->args[2] = (yyvsp[-2].expr);
		(yyval.expr) = with_unit(nest(v), (yyvsp[0].tok));
	}
#line 2388 "build2/parse.c"
    break;

  case 107: /* args: %empty  */
#line 529 "compiler/front/parse.y"
                             { (yyval.vec) = (Vec){ 0 }; }
#line 2394 "build2/parse.c"
    break;

  case 109: /* args1: expr  */
#line 534 "compiler/front/parse.y"
                             { (yyval.vec) = (Vec){ 0 }; vec_push(&(yyval.vec), (yyvsp[0].expr)); }
#line 2400 "build2/parse.c"
    break;

  case 110: /* args1: args1 ',' expr  */
#line 535 "compiler/front/parse.y"
                             { (yyval.vec) = (yyvsp[-2].vec); vec_push(&(yyval.vec), (yyvsp[0].expr)); }
#line 2406 "build2/parse.c"
    break;


#line 2410 "build2/parse.c"

      default: break;
    }
  /* User semantic actions sometimes alter yychar, and that requires
     that yytoken be updated with the new translation.  We take the
     approach of translating immediately before every use of yytoken.
     One alternative is translating here after every semantic action,
     but that translation would be missed if the semantic action invokes
     YYABORT, YYACCEPT, or YYERROR immediately after altering yychar or
     if it invokes YYBACKUP.  In the case of YYABORT or YYACCEPT, an
     incorrect destructor might then be invoked immediately.  In the
     case of YYERROR or YYBACKUP, subsequent parser actions might lead
     to an incorrect destructor call or verbose syntax error message
     before the lookahead is translated.  */
  YY_SYMBOL_PRINT ("-> $$ =", YY_CAST (yysymbol_kind_t, yyr1[yyn]), &yyval, &yyloc);

  YYPOPSTACK (yylen);
  yylen = 0;

  *++yyvsp = yyval;
  *++yylsp = yyloc;

  /* Now 'shift' the result of the reduction.  Determine what state
     that goes to, based on the state we popped back to and the rule
     number reduced by.  */
  {
    const int yylhs = yyr1[yyn] - YYNTOKENS;
    const int yyi = yypgoto[yylhs] + *yyssp;
    yystate = (0 <= yyi && yyi <= YYLAST && yycheck[yyi] == *yyssp
               ? yytable[yyi]
               : yydefgoto[yylhs]);
  }

  goto yynewstate;


/*--------------------------------------.
| yyerrlab -- here on detecting error.  |
`--------------------------------------*/
yyerrlab:
  /* Make sure we have latest lookahead translation.  See comments at
     user semantic actions for why this is necessary.  */
  yytoken = yychar == YYEMPTY ? YYSYMBOL_YYEMPTY : YYTRANSLATE (yychar);
  /* If not already recovering from an error, report this error.  */
  if (!yyerrstatus)
    {
      ++yynerrs;
      {
        yypcontext_t yyctx
          = {yyssp, yytoken, &yylloc};
        if (yyreport_syntax_error (&yyctx, P) == 2)
          YYNOMEM;
      }
    }

  yyerror_range[1] = yylloc;
  if (yyerrstatus == 3)
    {
      /* If just tried and failed to reuse lookahead token after an
         error, discard it.  */

      if (yychar <= END)
        {
          /* Return failure if at end of input.  */
          if (yychar == END)
            YYABORT;
        }
      else
        {
          yydestruct ("Error: discarding",
                      yytoken, &yylval, &yylloc, P);
          yychar = YYEMPTY;
        }
    }

  /* Else will try to reuse lookahead token after shifting the error
     token.  */
  goto yyerrlab1;


/*---------------------------------------------------.
| yyerrorlab -- error raised explicitly by YYERROR.  |
`---------------------------------------------------*/
yyerrorlab:
  /* Pacify compilers when the user code never invokes YYERROR and the
     label yyerrorlab therefore never appears in user code.  */
  if (0)
    YYERROR;
  ++yynerrs;

  /* Do not reclaim the symbols of the rule whose action triggered
     this YYERROR.  */
  YYPOPSTACK (yylen);
  yylen = 0;
  YY_STACK_PRINT (yyss, yyssp);
  yystate = *yyssp;
  goto yyerrlab1;


/*-------------------------------------------------------------.
| yyerrlab1 -- common code for both syntax error and YYERROR.  |
`-------------------------------------------------------------*/
yyerrlab1:
  yyerrstatus = 3;      /* Each real token shifted decrements this.  */

  /* Pop stack until we find a state that shifts the error token.  */
  for (;;)
    {
      yyn = yypact[yystate];
      if (!yypact_value_is_default (yyn))
        {
          yyn += YYSYMBOL_YYerror;
          if (0 <= yyn && yyn <= YYLAST && yycheck[yyn] == YYSYMBOL_YYerror)
            {
              yyn = yytable[yyn];
              if (0 < yyn)
                break;
            }
        }

      /* Pop the current state because it cannot handle the error token.  */
      if (yyssp == yyss)
        YYABORT;

      yyerror_range[1] = *yylsp;
      yydestruct ("Error: popping",
                  YY_ACCESSING_SYMBOL (yystate), yyvsp, yylsp, P);
      YYPOPSTACK (1);
      yystate = *yyssp;
      YY_STACK_PRINT (yyss, yyssp);
    }

  YY_IGNORE_MAYBE_UNINITIALIZED_BEGIN
  *++yyvsp = yylval;
  YY_IGNORE_MAYBE_UNINITIALIZED_END

  yyerror_range[2] = yylloc;
  ++yylsp;
  YYLLOC_DEFAULT (*yylsp, yyerror_range, 2);

  /* Shift the error token.  */
  YY_SYMBOL_PRINT ("Shifting", YY_ACCESSING_SYMBOL (yyn), yyvsp, yylsp);

  yystate = yyn;
  goto yynewstate;


/*-------------------------------------.
| yyacceptlab -- YYACCEPT comes here.  |
`-------------------------------------*/
yyacceptlab:
  yyresult = 0;
  goto yyreturnlab;


/*-----------------------------------.
| yyabortlab -- YYABORT comes here.  |
`-----------------------------------*/
yyabortlab:
  yyresult = 1;
  goto yyreturnlab;


/*-----------------------------------------------------------.
| yyexhaustedlab -- YYNOMEM (memory exhaustion) comes here.  |
`-----------------------------------------------------------*/
yyexhaustedlab:
  yyerror (&yylloc, P, YY_("memory exhausted"));
  yyresult = 2;
  goto yyreturnlab;


/*----------------------------------------------------------.
| yyreturnlab -- parsing is finished, clean up and return.  |
`----------------------------------------------------------*/
yyreturnlab:
  if (yychar != YYEMPTY)
    {
      /* Make sure we have latest lookahead translation.  See comments at
         user semantic actions for why this is necessary.  */
      yytoken = YYTRANSLATE (yychar);
      yydestruct ("Cleanup: discarding lookahead",
                  yytoken, &yylval, &yylloc, P);
    }
  /* Do not reclaim the symbols of the rule whose action triggered
     this YYABORT or YYACCEPT.  */
  YYPOPSTACK (yylen);
  YY_STACK_PRINT (yyss, yyssp);
  while (yyssp != yyss)
    {
      yydestruct ("Cleanup: popping",
                  YY_ACCESSING_SYMBOL (+*yyssp), yyvsp, yylsp, P);
      YYPOPSTACK (1);
    }
#ifndef yyoverflow
  if (yyss != yyssa)
    YYSTACK_FREE (yyss);
#endif

  return yyresult;
}

#line 538 "compiler/front/parse.y"


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
