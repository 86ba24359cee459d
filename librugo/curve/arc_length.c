/* Arc length with an error bound (curve/internal.h, rugo__arc_length): globally adaptive 7-15 point
 * Gauss-Kronrod on the pieces of [0, 1] between the speed's interior minima, always bisecting the
 * piece with the largest error estimate, until the summed estimates meet the tolerance.
 *
 * Why this and not a fixed rule: |c'| is the square root of a polynomial; where c' nearly vanishes (a
 * cusp of a rough outline, a tripled control point) the root has a kink, or a pair of complex zeros
 * close to the real axis, and a fixed 4-point rule was 3.5e-5 relative off on a rough 128-point
 * outline. Splitting at the speed's minima puts such a kink at the end of a piece, where the rule
 * converges again, and bisection resolves what is left. */
#include "curve/internal.h"
#include "curve/poly.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* 15-point Kronrod nodes on [-1, 1] (±x_i and 0) and weights; the odd-indexed nodes with wg are the
 * 7-point Gauss rule inside it. */
static const double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                               0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                               0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                               0.207784955007898467600689403773245, 0.0};
static const double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                               0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                               0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                               0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                              0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

double rugo__arc_gk15(rugo__speed_fn speed, const void* ctx, double a, double b, double* error) {
    const double h = 0.5 * (b - a), c = a + h;
    const double f0 = speed(ctx, c);
    double k = kWgk[7] * f0, g = kWg[3] * f0;
    for (int i = 0; i < 7; ++i) {
        const double fs = speed(ctx, c - h * kXgk[i]) + speed(ctx, c + h * kXgk[i]);
        k += kWgk[i] * fs;
        if (i & 1) g += kWg[i >> 1] * fs;
    }
    k *= h;
    g *= h;
    /* |K15 - G7| bounds the error of K15 from above for any integrand smooth on the piece (K15 is exact
     * to degree 22, G7 to 13, and the estimate is G7's error); the speed is >= 0, so K15 is also the
     * integral of |speed|, and 50 ulps of it cover the round-off of the 15 evaluations and the sum. */
    if (error != NULL) *error = fabs(k - g) + 50.0 * DBL_EPSILON * fabs(k);
    return k;
}

/* Neumaier's compensated sum. */
static void add(double* s, double* c, double x) {
    const double t = *s + x;
    if (fabs(*s) >= fabs(x))
        *c += (*s - t) + x;
    else
        *c += (x - t) + *s;
    *s = t;
}

static void totals(rugo__arc* out) {
    double s = 0.0, sc = 0.0, e = 0.0, ec = 0.0;
    for (int i = 0; i < out->count; ++i) {
        add(&s, &sc, out->piece[i].length);
        add(&e, &ec, out->piece[i].error);
    }
    out->length = s + sc;
    out->error = e + ec;
}

static int cmp_double(const void* a, const void* b) {
    const double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

void rugo__arc_length(rugo__speed_fn speed, const void* ctx, const double* breaks, int break_count,
                      double rel_tol, double abs_tol, rugo__arc* out) {
    double cut[RUGO__ARC_MAX_BREAKS + 2];
    int n = 0;
    cut[n++] = 0.0;
    for (int i = 0; i < break_count && i < RUGO__ARC_MAX_BREAKS; ++i)
        if (breaks[i] > 0.0 && breaks[i] < 1.0) cut[n++] = breaks[i];
    qsort(cut + 1, (size_t)(n - 1), sizeof *cut, cmp_double);
    cut[n++] = 1.0;
    out->count = 0;
    out->converged = 0;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(cut[i + 1] > cut[i])) continue; /* a repeated break */
        rugo__arc_piece* p = &out->piece[out->count++];
        p->a = cut[i];
        p->b = cut[i + 1];
        p->length = rugo__arc_gk15(speed, ctx, p->a, p->b, &p->error);
    }
    for (;;) {
        totals(out);
        /* A non-finite length (a speed beyond doubles) never improves by splitting: stop at once. */
        if (!isfinite(out->length) || !isfinite(out->error)) return;
        if (out->error <= abs_tol || out->error <= rel_tol * out->length) {
            out->converged = 1;
            return;
        }
        if (out->count >= RUGO__ARC_MAX_PIECES) return;
        int worst = 0;
        for (int i = 1; i < out->count; ++i)
            if (out->piece[i].error > out->piece[worst].error) worst = i;
        rugo__arc_piece* p = &out->piece[worst];
        const double mid = p->a + 0.5 * (p->b - p->a);
        if (!(mid > p->a && mid < p->b)) return; /* the piece is as narrow as doubles allow */
        memmove(&out->piece[worst + 2], &out->piece[worst + 1],
                (size_t)(out->count - worst - 1) * sizeof out->piece[0]);
        ++out->count;
        rugo__arc_piece* q = &out->piece[worst + 1];
        q->a = mid;
        q->b = p->b;
        q->length = rugo__arc_gk15(speed, ctx, mid, q->b, &q->error);
        p->b = mid;
        p->length = rugo__arc_gk15(speed, ctx, p->a, mid, &p->error);
    }
}

int rugo__arc_speed_breaks(rugo_vec2 a, rugo_vec2 b, rugo_vec2 c, double* breaks) {
    /* d/dt |d|^2 / 2 = d · d' = (a + b t + c t^2) · (b + 2 c t): a cubic whose interior roots are the
     * speed's extrema. Only the minima well below the speed's largest value matter (a cusp or a near
     * one); the others are left to bisection. */
    const double p[4] = {a.x * b.x + a.y * b.y, b.x * b.x + b.y * b.y + 2.0 * (a.x * c.x + a.y * c.y),
                         3.0 * (b.x * c.x + b.y * c.y), 2.0 * (c.x * c.x + c.y * c.y)};
    double roots[RUGO__POLY_MAX_ROOTS];
    const int nr = rugo__poly_roots(p, 3, 0.0, 1.0, 0.0, roots);
    if (nr <= 0) return 0;
    double top = 0.0;
    const double ends[2] = {0.0, 1.0};
    for (int i = 0; i < 2 + nr; ++i) {
        const double t = i < 2 ? ends[i] : roots[i - 2];
        top = fmax(top, hypot(a.x + (b.x + c.x * t) * t, a.y + (b.y + c.y * t) * t));
    }
    int n = 0;
    for (int i = 0; i < nr && n < RUGO__ARC_MAX_BREAKS; ++i) {
        const double t = roots[i];
        if (!(t > 0.0 && t < 1.0)) continue;
        const double s = hypot(a.x + (b.x + c.x * t) * t, a.y + (b.y + c.y * t) * t);
        if (s <= 0.25 * top) breaks[n++] = t;
    }
    return n;
}
