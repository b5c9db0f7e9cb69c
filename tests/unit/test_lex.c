/* The re2c scanner and the layout layer. */
#include <math.h>
#include <string.h>

#include "suites.h"
#include "parse.h"

static int lex_all(const char *text, Token *out, int max)
{
	Lexer L;
	lex_init(&L, src_add("l.csf", text));
	int n = 0;
	do lex_next(&L, &out[n]);
	while (out[n].kind != END && ++n < max);
	return n;
}

/* What scanning text prints on the diagnostics stream (the caller frees it). */
static char *lex_diagnostics(const char *text)
{
	char *buf;
	size_t len;
	Token t[8];
	diag_out = open_memstream(&buf, &len);
	lex_all(text, t, 8);
	fclose(diag_out);
	diag_out = NULL;
	return buf;
}

START_TEST(test_tokens)
{
	Token t[32];
	int n = lex_all("rule F: x$2 = 6.5e-1 * (y) # comment\n", t, 32);
	int kinds[] = { RULE, IDENT, ':', IDENT, DOLLAR, '=', NUMBER, '*', '(', IDENT, ')', NEWLINE };
	ck_assert_int_eq(n, 12);
	for (int i = 0; i < 12; i++) ck_assert_msg(t[i].kind == kinds[i], "token %d is %d", i, t[i].kind);
	ck_assert_int_eq(t[4].n, 2);
	ck_assert(t[6].num == 0.65);
	ck_assert_int_eq(t[6].loc.col, 15);
	ck_assert(t[0].bol && t[0].indent == 0);
}
END_TEST

START_TEST(test_numbers)
{
	static const struct { const char *s; double v; } c[] = {
		{ "12", 12 }, { "0.5", 0.5 }, { ".25", 0.25 }, { "6.674e-11", 6.674e-11 }, { "1E3", 1000 },
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		Token t[4];
		lex_all(c[i].s, t, 4);
		ck_assert_msg(t[0].kind == NUMBER && t[0].num == c[i].v, "%s", c[i].s);
	}
	Token t[4];
	lex_all("Inf NaN", t, 4);
	ck_assert(t[0].kind == NUMBER && isinf(t[0].num));
	ck_assert(t[1].kind == NUMBER && isnan(t[1].num));
}
END_TEST

/* π (U+03C0 in UTF-8, spec 1.1) is the name pi; columns count bytes, the caret characters */
START_TEST(test_pi)
{
	Token t[8];
	int n = lex_all("x = 2 * \xCF\x80\n", t, 8);
	ck_assert_int_eq(n, 6);
	ck_assert_int_eq(t[4].kind, IDENT);
	ck_assert_str_eq(t[4].text, "pi");
	ck_assert_int_eq(t[4].loc.col, 9);
	ck_assert_int_eq(t[4].end_col, 11);
	char *buf = lex_diagnostics("\xCF\x80 @\n");
	ck_assert_msg(strstr(buf, "l.csf:1:4: error: unexpected character '@'\n  \xCF\x80 @\n    ^\n") != NULL, "%s", buf);
	free(buf);
}
END_TEST

START_TEST(test_operators)
{
	Token t[16];
	int n = lex_all("== != <= >= < > ^ '", t, 16);
	int kinds[] = { EQEQ, NE, LE, GE, '<', '>', '^', '\'' };
	ck_assert_int_eq(n, 8);
	for (int i = 0; i < 8; i++) ck_assert_int_eq(t[i].kind, kinds[i]);
}
END_TEST

START_TEST(test_indent_and_blank_lines)
{
	Token t[32];
	int n = lex_all("def k:\n\n   # only a comment\n    m = 1\n", t, 32);
	/* def k : NL  m = 1 NL */
	ck_assert_int_eq(n, 8);
	ck_assert(t[4].bol);
	ck_assert_int_eq(t[4].indent, 4);
	ck_assert_int_eq(t[4].loc.line, 4);
}
END_TEST

START_TEST(test_tab_rejected)
{
	char *buf = lex_diagnostics("x = 1\n\ty = 2\n");
	ck_assert_msg(strstr(buf, "l.csf:2:1: error: tabs are not allowed in indentation") != NULL, "%s", buf);
	free(buf);
}
END_TEST

START_TEST(test_protected_and_keywords)
{
	ck_assert_int_eq(lex_keyword("start", 5), PROTECTED);
	ck_assert_int_eq(lex_keyword("Pi", 2), PROTECTED);
	ck_assert_int_eq(lex_keyword("object", 6), OBJECT);
	ck_assert_int_eq(lex_keyword("watch", 5), WATCH);
	ck_assert_int_eq(lex_keyword("pos", 3), 0);
}
END_TEST

START_TEST(test_using_path)
{
	Token t[4];
	lex_all("using \"mechanics/rules\"  # c\n", t, 4);
	ck_assert_int_eq(t[0].kind, USING);
	ck_assert_str_eq(t[0].text, "mechanics/rules");
	lex_all("using mechanics/mass_point\n", t, 4);
	ck_assert_str_eq(t[0].text, "mechanics/mass_point");
}
END_TEST

Suite *lex_suite(void)
{
	Suite *s = suite_create("lex");
	TCase *tc = tcase_create("scanner");
	tcase_add_test(tc, test_tokens);
	tcase_add_test(tc, test_numbers);
	tcase_add_test(tc, test_pi);
	tcase_add_test(tc, test_operators);
	tcase_add_test(tc, test_indent_and_blank_lines);
	tcase_add_test(tc, test_tab_rejected);
	tcase_add_test(tc, test_protected_and_keywords);
	tcase_add_test(tc, test_using_path);
	suite_add_tcase(s, tc);
	return s;
}
