/*
 * spectrum.h - a scene's fastest time scales from Jacobian-vector products
 * (spectrum.c): never the n-by-n Jacobian, only J v for vectors v.
 */
#ifndef CSF_SPECTRUM_H
#define CSF_SPECTRUM_H

#include <stddef.h>

/* jv = J v for the caller's J (n by n). 0, or non-zero when it cannot be computed (the estimate is dropped). */
typedef int (*csf_jvp_fn)(void *ctx, const double *v, double *jv);

typedef struct csf_spectrum csf_spectrum;

/* One or two eigenvalues of J, re[i] + i im[i] (a complex pair has both), and rho = max |lambda|. */
typedef struct csf_eigs {
	int n;
	double re[2], im[2];
	double rho;
} csf_eigs;

/* A new estimator for n-by-n matrices (n >= 1), NULL when memory runs out. */
csf_spectrum *csf_spectrum_new(size_t n);
void csf_spectrum_free(csf_spectrum *s);

/*
 * The dominant eigenvalues of J (largest modulus: one real one, a real
 * pair +-a, or a complex pair) by power iteration, each iterate's span
 * with the next (two-dimensional Arnoldi) giving the pair. Starts from
 * the last call's direction, so that tracking a slowly changing J costs a
 * few products; at most maxprod of them (at least 3, at most 41), fewer
 * once the estimate has converged. 0, or -1 when a product failed.
 */
int csf_spectrum_dominant(csf_spectrum *s, csf_jvp_fn f, void *ctx, int maxprod, csf_eigs *e);

/*
 * The smallest (most negative) eigenvalue mu of J^2 when J^2's spectrum
 * is real and its largest is sigma > 0 (x'' = A x, J = [0 I; A 0], J^2 =
 * A twice): power iteration on J^2 - sigma I. 0, or -1 when a product
 * failed.
 */
int csf_spectrum_lowest_square(csf_spectrum *s, csf_jvp_fn f, void *ctx, double sigma, double *mu);

/*
 * The stiffness ratio: largest over smallest nonzero |eigenvalue|, from
 * the Ritz values of an Arnoldi process of min(n, 16) steps; *exact is
 * set when that spans the whole space (n <= 16: the ratio of J's
 * eigenvalues themselves), else the ratio is an estimate. An eigenvalue
 * below zero times the largest counts as zero: rounding moves a zero
 * eigenvalue of a Jordan block (free motion: x' = v, v' = 0) by about the
 * square root of the products' relative error. 0 with *ratio = 0 when
 * every eigenvalue is zero; -1 when a product or memory failed.
 */
int csf_spectrum_ratio(csf_spectrum *s, csf_jvp_fn f, void *ctx, double zero, double *ratio, int *exact);

/* The products computed so far. */
unsigned long csf_spectrum_products(const csf_spectrum *s);

/* Saves or restores the power iteration's direction and counts (a checkpoint): 0, or nonzero. */
struct csf_keeper;
int csf_spectrum_keep(csf_spectrum *s, struct csf_keeper *k);

#endif
