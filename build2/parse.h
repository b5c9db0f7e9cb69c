/* A Bison parser, made by GNU Bison 3.8.2.  */

/* Bison interface for Yacc-like parsers in C

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

/* DO NOT RELY ON FEATURES THAT ARE NOT DOCUMENTED in the manual,
   especially those whose name start with YY_ or yy_.  They are
   private implementation details that can be changed or removed.  */

#ifndef YY_YY_BUILD2_PARSE_H_INCLUDED
# define YY_YY_BUILD2_PARSE_H_INCLUDED
/* Debug traces.  */
#ifndef YYDEBUG
# define YYDEBUG 0
#endif
#if YYDEBUG
extern int yydebug;
#endif
/* "%code requires" blocks.  */
#line 9 "compiler/front/parse.y"

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

#line 72 "build2/parse.h"

/* Token kinds.  */
#ifndef YYTOKENTYPE
# define YYTOKENTYPE
  enum yytokentype
  {
    YYEMPTY = -2,
    END = 0,                       /* "end of file"  */
    YYerror = 256,                 /* error  */
    YYUNDEF = 257,                 /* "invalid token"  */
    NUMBER = 258,                  /* "number"  */
    IDENT = 259,                   /* "name"  */
    DOLLAR = 260,                  /* "object number ($n)"  */
    UNIT = 261,                    /* "unit"  */
    NEWLINE = 262,                 /* "end of line"  */
    INDENT = 263,                  /* "indented block"  */
    DEDENT = 264,                  /* "end of indented block"  */
    LEXERROR = 265,                /* "invalid token"  */
    PROTECTED = 266,               /* "protected name"  */
    USING = 267,                   /* "'using'"  */
    OBJECT = 268,                  /* "'object'"  */
    DEF = 269,                     /* "'def'"  */
    GLOBAL = 270,                  /* "'global'"  */
    RULE = 271,                    /* "'rule'"  */
    FOR = 272,                     /* "'for'"  */
    STOP = 273,                    /* "'stop'"  */
    WHEN = 274,                    /* "'when'"  */
    IF = 275,                      /* "'if'"  */
    ELIF = 276,                    /* "'elif'"  */
    ELSE = 277,                    /* "'else'"  */
    ASSERT = 278,                  /* "'assert'"  */
    VECTOR = 279,                  /* "'vector'"  */
    INC = 280,                     /* "'inc'"  */
    TILL = 281,                    /* "'till'"  */
    BY = 282,                      /* "'by'"  */
    WATCH = 283,                   /* "'watch'"  */
    AND = 284,                     /* "'and'"  */
    OR = 285,                      /* "'or'"  */
    NOT = 286,                     /* "'not'"  */
    ATOL = 287,                    /* "'atol'"  */
    DOTDOT = 288,                  /* "'..'"  */
    STRING = 289,                  /* "string"  */
    EQEQ = 290,                    /* "'=='"  */
    NE = 291,                      /* "'!='"  */
    LE = 292,                      /* "'<='"  */
    GE = 293,                      /* "'>='"  */
    UMINUS = 294                   /* UMINUS  */
  };
  typedef enum yytokentype yytoken_kind_t;
#endif

/* Value type.  */
#if ! defined YYSTYPE && ! defined YYSTYPE_IS_DECLARED
union YYSTYPE
{
#line 213 "compiler/front/parse.y"

	double num;
	char *str;
	int n;
	Token *tok;
	Expr *expr;
	Eqn *eqn;
	If *cond;
	Stmt *stmt;
	ObjRef *ref;
	WatchItem *watch;
	ObjName *oname;
	long idx;
	Vec vec;

#line 144 "build2/parse.h"

};
typedef union YYSTYPE YYSTYPE;
# define YYSTYPE_IS_TRIVIAL 1
# define YYSTYPE_IS_DECLARED 1
#endif

/* Location type.  */
typedef YYLoc YYLTYPE;




int yyparse (Parser *P);

/* "%code provides" blocks.  */
#line 32 "compiler/front/parse.y"

int yylex(YYSTYPE *lval, YYLoc *lloc, Parser *P);
/* The layout layer's state (layout.c). */
Parser *layout_new(int file);
Stmt *layout_result(Parser *P);
void layout_append(Parser *P, Stmt *s);
const char *layout_token_text(Parser *P);
void layout_skip_block(Parser *P);
int layout_reported(Parser *P, Loc l);

#line 172 "build2/parse.h"

#endif /* !YY_YY_BUILD2_PARSE_H_INCLUDED  */
