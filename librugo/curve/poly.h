/* Real roots of small polynomials (degree <= 5) on an interval. Internal, not installed.
 *
 * Used wherever a geometric query reduces to a polynomial in a segment parameter: curve bounds
 * (f' = 0), closest points ((f - p)·f' = 0), containment and ray casts (cubics), and later the
 * MOBBtree (f'·e = 0) and contact points. No allocation, no recursion deeper than the degree,
 * deterministic. */
#ifndef RUGO_POLY_H
#define RUGO_POLY_H

#include "rugo/base.h"

#define RUGO__POLY_MAX_DEGREE 5
/* Upper bound on the roots one call can report: at most one per monotone piece (degree) plus one
 * touching root per interior critical point (degree - 1). */
#define RUGO__POLY_MAX_ROOTS (2 * RUGO__POLY_MAX_DEGREE - 1)
/* Returned instead of a count when the polynomial is zero (within tol) on the whole interval. */
#define RUGO__POLY_ALL (-1)

/* p(t) = a[0] + a[1] t + ... + a[degree] t^degree, by Horner. */
rugo_real rugo__poly_eval(const rugo_real* a, int degree, rugo_real t);

/* Real roots of p in [lo, hi], sorted ascending and distinct, written to roots (room for
 * RUGO__POLY_MAX_ROOTS). Returns their count, or RUGO__POLY_ALL if |p| <= tol everywhere on
 * [lo, hi] (e.g. the zero polynomial; then roots is untouched). 0 <= degree <= 5.
 *
 * Reported: every sign change of p (bracketed, refined to full double precision), every exact zero,
 * and every interior or end critical point where p touches zero without changing sign, i.e. a local
 * extremum c with |p(c)| <= tol + Horner round-off (a double root perturbed by round-off).
 * tol is the caller's absolute uncertainty in the values of p (0 = only round-off of the evaluation
 * itself); it is how degenerate geometry (tangency, collinear pieces) is recognised.
 * Leading coefficients that are tiny relative to the others need no special care: the method works
 * on sign changes between critical points, not on the nominal degree. */
int rugo__poly_roots(const rugo_real* a, int degree, rugo_real lo, rugo_real hi, rugo_real tol,
                     rugo_real* roots);

#endif
