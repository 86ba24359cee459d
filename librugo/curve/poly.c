/* Real roots of polynomials of degree <= 5 on an interval (see poly.h).
 *
 * Method: the roots of p' (found the same way, one degree down) cut [lo, hi] into pieces on which p
 * is monotone; each piece whose ends have opposite signs holds exactly one root, which safeguarded
 * Newton refines inside its bracket to full precision. A critical point where p comes within
 * round-off (plus the caller's tol) of zero without crossing it is a double root that round-off
 * lifted off the axis; it is reported too, so tangencies are not lost. Nothing depends on the
 * nominal degree being exact, so a leading coefficient that is round-off noise is harmless. */
#include "curve/poly.h"

#include "core/internal.h"

#include <float.h>

/* Breakpoints: lo, at most RUGO__POLY_MAX_ROOTS critical points, hi. */
#define POLY_MAX_BREAKS (RUGO__POLY_MAX_ROOTS + 2)

rugo_real rugo__poly_eval(const rugo_real* a, int degree, rugo_real t) {
    rugo_real p = a[degree];
    for (int k = degree - 1; k >= 0; --k)
        p = p * t + a[k];
    return p;
}

/* sum |a_k| |t|^k: scales the rounding error of Horner's rule at t. */
static rugo_real abs_eval(const rugo_real* a, int degree, rugo_real t) {
    rugo_real at = fabs(t), s = fabs(a[degree]);
    for (int k = degree - 1; k >= 0; --k)
        s = s * at + fabs(a[k]);
    return s;
}

/* Rounding error bound of Horner's rule (2 d u with u = eps/2, doubled for safety). */
static rugo_real horner_error(const rugo_real* a, int degree, rugo_real t) {
    return 2.0 * (rugo_real)degree * DBL_EPSILON * abs_eval(a, degree, t);
}

static int sign_of(rugo_real v) { return (v > 0.0) - (v < 0.0); }

/* The root of p in [x0, x1], where p is monotone and p(x0), p(x1) are non-zero with opposite signs.
 * Newton inside the bracket (rtsafe): a step that leaves the bracket, or that is not at least twice
 * as short as the step before last, becomes a bisection. Ends when a step no longer moves x (full
 * precision), the bracket is two adjacent doubles, or p hits zero exactly. */
static rugo_real refine_root(const rugo_real* a, const rugo_real* da, int degree, rugo_real x0, rugo_real x1,
                             rugo_real p0) {
    /* xl: the end where p < 0, xh: where p > 0 (either may be the larger). */
    rugo_real xl = p0 < 0.0 ? x0 : x1, xh = p0 < 0.0 ? x1 : x0;
    rugo_real x = x0 + 0.5 * (x1 - x0);
    rugo_real dx_old = fabs(x1 - x0), dx = dx_old;
    rugo_real px = rugo__poly_eval(a, degree, x);
    rugo_real dp = rugo__poly_eval(da, degree - 1, x);
    for (int iter = 0; iter < 200 && px != 0.0; ++iter) {
        if (px < 0.0)
            xl = x;
        else
            xh = x;
        rugo_real xn = dp != 0.0 ? x - px / dp : xl;
        int inside = (xn > xl && xn < xh) || (xn < xl && xn > xh);
        if (!inside || fabs(2.0 * px) > fabs(dx_old * dp)) {
            dx_old = dx;
            dx = 0.5 * (xh - xl);
            xn = xl + dx;
            if (xn == xl || xn == xh) break; /* bracket is two adjacent doubles */
        } else {
            dx_old = dx;
            dx = x - xn;
            if (xn == x) break;
        }
        x = xn;
        px = rugo__poly_eval(a, degree, x);
        dp = rugo__poly_eval(da, degree - 1, x);
    }
    return x;
}

/* touch: whether to report near-zero extrema (off for the derivative levels, which only need the
 * sign changes of p' to split p into monotone pieces). */
static int roots_rec(const rugo_real* a, int degree, rugo_real lo, rugo_real hi, rugo_real tol, int touch,
                     rugo_real* out) {
    int d = degree;
    while (d > 0 && a[d] == 0.0)
        --d;
    rugo_real m = fmax(fabs(lo), fabs(hi));
    /* |p| <= sum |a_k| m^k on [lo, hi]: below tol it is indistinguishable from zero everywhere. */
    rugo_real bound = abs_eval(a, d, m);
    if (bound == 0.0 || bound <= tol) return RUGO__POLY_ALL;
    if (d == 0) return 0;
    if (lo == hi) {
        rugo_real p = rugo__poly_eval(a, d, lo);
        if (p == 0.0 || (touch && fabs(p) <= tol + horner_error(a, d, lo))) {
            out[0] = lo;
            return 1;
        }
        return 0;
    }

    rugo_real da[RUGO__POLY_MAX_DEGREE];
    for (int k = 0; k < d; ++k)
        da[k] = (rugo_real)(k + 1) * a[k + 1];

    rugo_real brk[POLY_MAX_BREAKS];
    int crit_flag[POLY_MAX_BREAKS];
    int nb = 0;
    brk[nb] = lo;
    crit_flag[nb++] = 0;
    if (d >= 2) {
        rugo_real crit[RUGO__POLY_MAX_ROOTS];
        int nc = roots_rec(da, d - 1, lo, hi, 0.0, 0, crit);
        for (int i = 0; i < nc; ++i) {
            if (crit[i] <= lo) {
                crit_flag[0] = 1;
            } else if (crit[i] >= hi) {
                /* marked below, once hi is appended */
            } else if (nb < POLY_MAX_BREAKS - 1) {
                brk[nb] = crit[i];
                crit_flag[nb++] = 1;
            }
        }
        brk[nb] = hi;
        crit_flag[nb] = nc > 0 && crit[nc - 1] >= hi;
        ++nb;
    } else {
        brk[nb] = hi;
        crit_flag[nb++] = 0;
    }

    rugo_real val[POLY_MAX_BREAKS];
    for (int i = 0; i < nb; ++i)
        val[i] = rugo__poly_eval(a, d, brk[i]);

    int count = 0;
    for (int i = 0; i < nb; ++i) {
        int hit = val[i] == 0.0;
        if (!hit && touch && crit_flag[i] && fabs(val[i]) <= tol + horner_error(a, d, brk[i])) {
            /* A near-zero extremum that turns back from the axis (both neighbours on its side). */
            int s = sign_of(val[i]);
            int left_ok = i == 0 || sign_of(val[i - 1]) == s;
            int right_ok = i == nb - 1 || sign_of(val[i + 1]) == s;
            hit = left_ok && right_ok;
        }
        if (hit && (count == 0 || out[count - 1] < brk[i]) && count < RUGO__POLY_MAX_ROOTS)
            out[count++] = brk[i];
        if (i + 1 < nb && val[i] != 0.0 && val[i + 1] != 0.0 && sign_of(val[i]) != sign_of(val[i + 1])) {
            rugo_real r = refine_root(a, da, d, brk[i], brk[i + 1], val[i]);
            if ((count == 0 || out[count - 1] < r) && count < RUGO__POLY_MAX_ROOTS) out[count++] = r;
        }
    }
    return count;
}

int rugo__poly_roots(const rugo_real* a, int degree, rugo_real lo, rugo_real hi, rugo_real tol,
                     rugo_real* roots) {
    RUGO_ASSERT(degree >= 0 && degree <= RUGO__POLY_MAX_DEGREE);
    if (degree < 0 || degree > RUGO__POLY_MAX_DEGREE) return 0;
    if (!(lo <= hi) || !isfinite(lo) || !isfinite(hi)) return 0;
    for (int k = 0; k <= degree; ++k)
        if (!isfinite(a[k])) return 0;
    if (!(tol >= 0.0)) tol = 0.0;
    return roots_rec(a, degree, lo, hi, tol, 1, roots);
}
