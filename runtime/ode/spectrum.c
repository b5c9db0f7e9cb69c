/*
 * spectrum.c - eigenvalue estimates from Jacobian-vector products.
 *
 * The runtime needs to know how fast a scene's fastest modes are, to
 * check a fixed step against the method's stability region and to see
 * that an explicit method is held back by stiffness. The Jacobian is
 * available only as products J v (one tangent evaluation each), so the
 * estimates are Krylov methods: power iteration with a two-dimensional
 * Rayleigh-Ritz step for the dominant eigenvalues (which finds a
 * complex or a +- pair as readily as a single real one), and a short
 * Arnoldi process for the spread of the spectrum (GSL's nonsymmetric
 * eigensolver on its small Hessenberg matrix).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>

#include "csf_int.h"
#include "spectrum.h"

enum { ARNOLDI = 16, MAXIT = 40 };

struct csf_spectrum {
	size_t n;
	double *v, *w, *z, *q; /* the power iteration's direction (unit length), J v, J^2 v, work */
	int warm;              /* v is the last call's direction */
	unsigned long nprod;
};

static double dot(size_t n, const double *a, const double *b)
{
	double s = 0;
	for (size_t i = 0; i < n; i++) s += a[i] * b[i];
	return s;
}

static double norm(size_t n, const double *a) { return sqrt(dot(n, a, a)); }

/* A fixed pseudo-random unit vector: no direction of a scene is special to it, and runs repeat exactly. */
static void start_vector(size_t n, double *v)
{
	uint32_t x = 2463534242u;
	for (size_t i = 0; i < n; i++) {
		x ^= x << 13, x ^= x >> 17, x ^= x << 5;
		v[i] = x / 2147483648.0 - 1;
	}
	double s = norm(n, v);
	for (size_t i = 0; i < n; i++) v[i] /= s;
}

/* out = J in, every entry finite. */
static int product(csf_spectrum *s, csf_jvp_fn f, void *ctx, const double *in, double *out)
{
	s->nprod++;
	if (f(ctx, in, out)) return -1;
	for (size_t i = 0; i < s->n; i++)
		if (!isfinite(out[i])) return -1;
	return 0;
}

csf_spectrum *csf_spectrum_new(size_t n)
{
	csf_spectrum *s = calloc(1, sizeof *s);
	if (!s) return NULL;
	s->n = n;
	s->v = malloc(4 * (n ? n : 1) * sizeof *s->v);
	if (!s->v) {
		free(s);
		return NULL;
	}
	s->w = s->v + n, s->z = s->w + n, s->q = s->z + n;
	return s;
}

void csf_spectrum_free(csf_spectrum *s)
{
	if (!s) return;
	free(s->v);
	free(s);
}

unsigned long csf_spectrum_products(const csf_spectrum *s) { return s->nprod; }

/* The eigenvalues of [[a, b], [c, d]] into e. */
static void eig2(double a, double b, double c, double d, csf_eigs *e)
{
	double half = (a + d) / 2, disc = (a - d) * (a - d) / 4 + b * c;
	e->n = 2;
	if (disc >= 0) {
		double r = sqrt(disc);
		/* the root of larger modulus first, the other from the determinant (no cancellation) */
		double l1 = half >= 0 ? half + r : half - r;
		double l2 = l1 != 0 ? (a * d - b * c) / l1 : 0;
		e->re[0] = l1, e->re[1] = l2, e->im[0] = e->im[1] = 0;
		e->rho = fmax(fabs(l1), fabs(l2));
	} else {
		double r = sqrt(-disc);
		e->re[0] = e->re[1] = half, e->im[0] = r, e->im[1] = -r;
		e->rho = hypot(half, r);
	}
}

int csf_spectrum_dominant(csf_spectrum *s, csf_jvp_fn f, void *ctx, int maxprod, csf_eigs *e)
{
	size_t n = s->n;
	double *v = s->v, *w = s->w, *z = s->z, *q = s->q;
	if (!s->warm) start_vector(n, v);
	s->warm = 0;
	if (product(s, f, ctx, v, w)) return -1;
	double wn = norm(n, w);
	if (!(wn > 0)) { /* J v = 0: from a fresh start, unless this was one */
		start_vector(n, v);
		if (product(s, f, ctx, v, w)) return -1;
		wn = norm(n, w);
	}
	double prev = -1;
	int maxit = maxprod - 1 < 2 ? 2 : maxprod - 1 > MAXIT ? MAXIT : maxprod - 1;
	for (int it = 0;; it++) {
		if (!(wn > 0)) { /* J is zero on the Krylov space of v */
			*e = (csf_eigs){ .n = 1 };
			break;
		}
		if (product(s, f, ctx, w, z)) return -1;
		/* v, and q the unit part of J v orthogonal to it: J v = a v + b q, and J q = h12 v + h22 q + r */
		double a = dot(n, w, v), res;
		for (size_t i = 0; i < n; i++) q[i] = w[i] - a * v[i];
		double b = norm(n, q);
		if (!(b > 1e-10 * wn)) { /* v is an eigenvector */
			*e = (csf_eigs){ .n = 1, .re = { a }, .rho = fabs(a) };
			res = b;
		} else {
			for (size_t i = 0; i < n; i++) q[i] /= b;
			double h12 = (dot(n, v, z) - a * a) / b, h22 = (dot(n, q, z) - a * b) / b, r2 = 0;
			for (size_t i = 0; i < n; i++) {
				double r = (z[i] - a * w[i]) / b - h12 * v[i] - h22 * q[i];
				r2 += r * r;
			}
			eig2(a, h12, b, h22, e);
			res = sqrt(r2);
		}
		/* converged: the plane of v and J v nearly invariant, or rho no longer changing */
		if (res <= 1e-3 * fmax(e->rho, 1e-300) || (prev >= 0 && fabs(e->rho - prev) <= 1e-6 * e->rho) ||
		    it + 1 >= maxit)
			break;
		prev = e->rho;
		for (size_t i = 0; i < n; i++) v[i] = w[i] / wn, w[i] = z[i] / wn;
		wn = norm(n, w);
	}
	s->warm = 1;
	return 0;
}

int csf_spectrum_lowest_square(csf_spectrum *s, csf_jvp_fn f, void *ctx, double sigma, double *mu)
{
	size_t n = s->n;
	double *x = s->q, *y = s->z, *t = s->w, prev = 0;
	double *keep = malloc((n ? n : 1) * sizeof *keep); /* the dominant direction, for the next call */
	if (!keep) return -1;
	memcpy(keep, s->v, n * sizeof *keep);
	start_vector(n, x);
	int st = 0;
	for (int it = 0; it < MAXIT; it++) {
		if (product(s, f, ctx, x, t) || product(s, f, ctx, t, y)) {
			st = -1;
			break;
		}
		for (size_t i = 0; i < n; i++) y[i] -= sigma * x[i]; /* (J^2 - sigma) x */
		double nu = dot(n, x, y), yn = norm(n, y);
		*mu = nu + sigma;
		if (!(yn > 0) || (it > 0 && fabs(nu - prev) <= 1e-6 * fabs(nu))) break;
		prev = nu;
		for (size_t i = 0; i < n; i++) x[i] = y[i] / yn;
	}
	memcpy(s->v, keep, n * sizeof *keep);
	free(keep);
	return st;
}

int csf_spectrum_ratio(csf_spectrum *s, csf_jvp_fn f, void *ctx, double zero, double *ratio, int *exact)
{
	size_t n = s->n, m = n < ARNOLDI ? n : ARNOLDI, k;
	double *Q = malloc((m + 1) * n * sizeof *Q), H[(ARNOLDI + 1) * ARNOLDI] = { 0 };
	if (!Q) return -1;
	start_vector(n, Q);
	int invariant = 0;
	for (k = 0; k < m && !invariant; k++) {
		double *qk = Q + k * n, *qn = qk + n;
		if (product(s, f, ctx, qk, qn)) {
			free(Q);
			return -1;
		}
		double before = norm(n, qn);
		for (int pass = 0; pass < 2; pass++) /* Gram-Schmidt twice: orthogonal to rounding */
			for (size_t j = 0; j <= k; j++) {
				double h = dot(n, Q + j * n, qn);
				H[j * m + k] += h;
				for (size_t i = 0; i < n; i++) qn[i] -= h * Q[j * n + i];
			}
		double hk = norm(n, qn);
		if (k + 1 < m) H[(k + 1) * m + k] = hk;
		if (!(hk > 1e-10 * before)) invariant = 1; /* the Krylov space is invariant: its Ritz values are exact */
		else
			for (size_t i = 0; i < n; i++) qn[i] /= hk;
	}
	free(Q);
	*exact = invariant || k == n;
	/* the eigenvalues of the leading k by k block of H (row stride m) */
	gsl_matrix *A = gsl_matrix_alloc(k, k);
	gsl_vector_complex *ev = gsl_vector_complex_alloc(k);
	gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(k);
	int st = -1;
	if (A && ev && ws) {
		for (size_t i = 0; i < k; i++)
			for (size_t j = 0; j < k; j++) gsl_matrix_set(A, i, j, H[i * m + j]);
		if (gsl_eigen_nonsymm(A, ev, ws) == GSL_SUCCESS) {
			double big = 0, small = INFINITY;
			for (size_t i = 0; i < k; i++) big = fmax(big, gsl_complex_abs(gsl_vector_complex_get(ev, i)));
			for (size_t i = 0; i < k; i++) {
				double a = gsl_complex_abs(gsl_vector_complex_get(ev, i));
				if (a > zero * big) small = fmin(small, a);
			}
			*ratio = big > 0 ? big / small : 0;
			st = 0;
		}
	}
	if (ws) gsl_eigen_nonsymm_free(ws);
	if (ev) gsl_vector_complex_free(ev);
	if (A) gsl_matrix_free(A);
	return st;
}

int csf_spectrum_keep(csf_spectrum *s, struct csf_keeper *k)
{
	if (!s) return 0;
	return csf_keep(k, "spectrum.v", s->v, (s->n ? s->n : 1) * sizeof *s->v) | CSF_KEEP(k, s->warm) |
	       CSF_KEEP(k, s->nprod);
}
