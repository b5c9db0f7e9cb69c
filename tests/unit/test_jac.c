/*
 * The Jacobian section (forward-mode differentiation of RHS): every
 * instruction's derivative rule, checked against central differences of the
 * RHS section itself, and exact where the answer is known.
 */
#include <math.h>
#include <string.h>

#include "suites.h"

static const char *model =
	"global r = 1 s^-1\n"
	"object b: x = 0.7\n"
	"object b: vector u = (0.3, -0.4, 0.5)\n"
	"object b: vector w = (0.2, 0.1, -0.3)\n"
	"rule: s = sin(x) * exp(u.x) + atan2(x, u.y) + sqrt(x + 2) + log(x + 3) + x^2.5 + tanh(u.z) + abs(u.y)"
	" + min(x, u.x) + cos(x)^2 + tan(x) / cosh(u.z) + asin(x / 2) - acos(u.x) + atan(x) + sinh(x) - log10(x + 1)"
	" + max(x, u.z) + 2^x\n"
	"rule: x' = r * (s + u.mag + u.dot(w) + u.angle(w))\n"
	"rule: if x > 0.5:\n"
	"    q = u.cross(w) + u.unit.mul(x) + u.proj(w)\n"
	"else:\n"
	"    q = -u\n"
	"rule: u' = r * (q + (x, u.x * u.y, 1 / (u.z + 2)) - w / (x + 1))\n"
	"inc t till 1 s by 1 s watch x\n";

static void rhs_at(const csf_prog *p, double *m, const double *y, double *f)
{
	memcpy(m + p->ystart, y, p->ny * sizeof *y);
	vm_run(p, CSF_SEC_RHS, m);
	memcpy(f, m + p->dstart, p->ny * sizeof *f);
}

START_TEST(test_against_differences)
{
	csf_prog p;
	char *d;
	ck_assert_msg(compile_string(model, &p, &d) == 0, "%s", d);
	free(d);
	ck_assert_uint_eq(p.ny, 4);
	ck_assert(p.jtan > 0);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	double y0[4], f1[4], f2[4], y[4];
	memcpy(y0, m + p.ystart, sizeof y0);
	for (uint32_t j = 0; j < p.ny; j++) {
		/* exact column j from JAC */
		memcpy(m + p.ystart, y0, sizeof y0);
		memset(m + p.jtan + p.ystart, 0, p.ny * sizeof *m);
		m[p.jtan + p.tslot] = 0;
		m[p.jtan + p.ystart + j] = 1;
		vm_run(&p, CSF_SEC_JAC, m);
		double col[4];
		memcpy(col, m + p.jtan + p.dstart, sizeof col);
		/* central difference */
		double h = 1e-6;
		memcpy(y, y0, sizeof y);
		y[j] += h;
		rhs_at(&p, m, y, f1);
		y[j] = y0[j] - h;
		rhs_at(&p, m, y, f2);
		for (uint32_t i = 0; i < p.ny; i++) {
			double fd = (f1[i] - f2[i]) / (2 * h);
			ck_assert_msg(fabs(col[i] - fd) <= 1e-6 * (1 + fabs(fd)), "df%u/dy%u: exact %.17g, difference %.17g", i, j,
			              col[i], fd);
		}
	}
	free(m);
	csf_prog_free(&p);
}
END_TEST

/* A linear system's Jacobian is its matrix, exactly. */
START_TEST(test_linear_exact)
{
	csf_prog p;
	ck_assert_int_eq(compile_string("object b: x = 1 m\nobject b: v = 2 m/s\nobject b: k = 9 s^-2\n"
	                                "object b: damp = 0.5 s^-1\nrule: x' = v\nrule: v' = -k * x - damp * v + 3 m/s^3 * t\n"
	                                "inc t till 1 s by 1 s watch x\n",
	                                &p, NULL),
	                 0);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	double want[3][2] = { { 0, -9 }, { 1, -0.5 }, { 0, 3 } }; /* columns x, v, t: (dx'/d., dv'/d.) */
	for (int j = 0; j < 3; j++) {
		memset(m + p.jtan + p.ystart, 0, 2 * sizeof *m);
		m[p.jtan + p.tslot] = j == 2;
		if (j < 2) m[p.jtan + p.ystart + j] = 1;
		vm_run(&p, CSF_SEC_JAC, m);
		for (int i = 0; i < 2; i++)
			ck_assert_msg(m[p.jtan + p.dstart + i] == want[j][i], "column %d row %d: %.17g", j, i, m[p.jtan + p.dstart + i]);
	}
	free(m);
	csf_prog_free(&p);
}
END_TEST

/*
 * The tangent of x^n (POWI) is n x^(n-1) dx with x^(n-1) as '^' computes it:
 * for x^3, exactly (x*x)*3; x^(n-1) for n = -8 is pow(x, -9).
 */
static const int powi_n[] = { -8, -3, -1, 0, 1, 2, 3, 8 };

START_TEST(test_powi_tangent)
{
	int n = powi_n[_i];
	csf_prog p;
	char *d;
	ck_assert_msg(compile_string(xprintf("global r = 1 s^-1\nobject b: x = 1.3\nrule: x' = r * x^(%d)\n"
	                                     "inc t till 1 s by 1 s watch x\n", n), &p, &d) == 0, "%s", d);
	free(d);
	double *m = malloc(p.nmem * sizeof *m);
	memcpy(m, p.mem0, p.nmem * sizeof *m);
	m[p.jtan + p.tslot] = 0;
	m[p.jtan + p.ystart] = 1;
	vm_run(&p, CSF_SEC_JAC, m);
	double x = 1.3, got = m[p.jtan + p.dstart];
	double want = n == 3 ? (x * x) * 3 : n == 0 ? 0 : csf_pow(x, n - 1) * n;
	ck_assert_msg(got == want, "d(x^%d)/dx = %.17g, expected %.17g", n, got, want);
	ck_assert(n != -8 || want == pow(x, -9) * -8);
	free(m);
	csf_prog_free(&p);
}
END_TEST

Suite *jac_suite(void)
{
	Suite *s = suite_create("jacobian");
	TCase *tc = tcase_create("jac");
	tcase_add_test(tc, test_against_differences);
	tcase_add_test(tc, test_linear_exact);
	tcase_add_loop_test(tc, test_powi_tangent, 0, sizeof powi_n / sizeof powi_n[0]);
	suite_add_tcase(s, tc);
	return s;
}
