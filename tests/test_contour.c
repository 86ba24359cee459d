/* Contour suite: evaluation, polynomial roots, arc length, mass properties, bounds, closest point,
 * containment, ray cast and validation (SPEC 1). References are computed here independently:
 * de Casteljau on the Bezier form, finite differences, dense polygons, brute-force sampling, exact
 * rationals derived symbolically. */
#include "core/internal.h"
#include "curve/poly.h"
#include "test_util.h"

#include <float.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846

static rugo_vec2* vec_alloc(int n) {
    rugo_vec2* v = (rugo_vec2*)calloc((size_t)n, sizeof(rugo_vec2));
    ck_assert_ptr_nonnull(v);
    return v;
}

static rugo_contour contour_of(const rugo_vec2* p, int n) {
    rugo_contour c;
    c.points = p;
    c.count = n;
    return c;
}

static double v2_dist(rugo_vec2 a, rugo_vec2 b) { return hypot(a.x - b.x, a.y - b.y); }

/* A contour holding all four segment kinds (SPEC 1, Figure 3.3), counter-clockwise:
 * segment 1 (points 0..3) straight and evenly spaced, segment 4 (points 3..6) parabolic (v = 0),
 * segment 8 (points 7..10) a point, the rest cubic. Segment 0 ends tangent to the line y = -1. */
#define DEG_N 13
static const rugo_vec2 DEG_POINTS[DEG_N] = {{-2, -1},   {-1, -1}, {0, -1},    {1, -1}, {2, -0.5},
                                            {2.5, 0.5}, {2.5, 2}, {0, 3},     {0, 3},  {0, 3},
                                            {0, 3},     {-2, 2},  {-2.5, 0.5}};
enum { DEG_STRAIGHT = 1, DEG_PARABOLIC = 4, DEG_POINT = 8, DEG_CUBIC = 11 };

/* A seeded random star: n points, random centre and radius; bumpiness 0.3 keeps it simple. */
static void star(uint64_t seed, int n, rugo_vec2* out, rugo_vec2* centre, double* radius) {
    test_rng r = test_rng_seed(seed);
    rugo_vec2 ctr = rugo_v2(test_rng_uniform(&r, -3, 3), test_rng_uniform(&r, -3, 3));
    double rad = test_rng_uniform(&r, 0.5, 2.0);
    test_random_star(&r, n, ctr, rad, 0.3, out);
    if (centre) *centre = ctr;
    if (radius) *radius = rad;
}

/* Dense polygon: m samples per segment, count * m vertices. */
static rugo_vec2* dense_polygon(rugo_contour c, int m) {
    rugo_vec2* v = vec_alloc(c.count * m);
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < m; ++i)
            v[j * m + i] = rugo_contour_point(c, j, (double)i / m);
    return v;
}

/* Winding number of a polygon around p, half-open crossing rule. */
static int polygon_winding(const rugo_vec2* v, int n, rugo_vec2 p) {
    int w = 0;
    for (int i = 0; i < n; ++i) {
        rugo_vec2 a = v[i], b = v[(i + 1) % n];
        if (a.y <= p.y) {
            if (b.y > p.y && (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y) > 0) ++w;
        } else if (b.y <= p.y && (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y) < 0) {
            --w;
        }
    }
    return w;
}

/* ---------------------------------------------------------------------------------------------------
 * Polynomial roots. */

static void poly_from_roots(const double* r, int k, double lead, double* a) {
    /* a = lead * prod (t - r_i), ascending powers */
    for (int i = 0; i <= RUGO__POLY_MAX_DEGREE; ++i)
        a[i] = 0.0;
    a[0] = lead;
    for (int i = 0; i < k; ++i) {
        for (int d = i + 1; d >= 1; --d)
            a[d] = a[d - 1] - r[i] * a[d];
        a[0] = -r[i] * a[0];
    }
}

START_TEST(poly_simple_roots) {
    double r[5] = {0.1, 0.25, 0.5, 0.7, 0.95}, a[6], out[RUGO__POLY_MAX_ROOTS];
    for (int k = 1; k <= 5; ++k) {
        poly_from_roots(r, k, 1.0, a);
        int n = rugo__poly_roots(a, k, 0.0, 1.0, 0.0, out);
        ck_assert_int_eq(n, k);
        for (int i = 0; i < k; ++i)
            ck_assert_near(out[i], r[i], 1e-13);
    }
    /* Only the roots inside the interval, and roots exactly at its ends. */
    poly_from_roots(r, 5, -3.0, a);
    int n = rugo__poly_roots(a, 5, 0.2, 0.6, 0.0, out);
    ck_assert_int_eq(n, 2);
    ck_assert_near(out[0], 0.25, 1e-14);
    ck_assert_near(out[1], 0.5, 1e-14);
    double e[3] = {0.0, -1.0, 1.0}; /* t (t - 1) */
    n = rugo__poly_roots(e, 2, 0.0, 1.0, 0.0, out);
    ck_assert_int_eq(n, 2);
    ck_assert(out[0] == 0.0 && out[1] == 1.0);
    /* No root: constant, and a quadratic without real roots. */
    double k0[1] = {2.0}, q[3] = {1.0, 0.0, 1.0};
    ck_assert_int_eq(rugo__poly_roots(k0, 0, -1.0, 1.0, 0.0, out), 0);
    ck_assert_int_eq(rugo__poly_roots(q, 2, -5.0, 5.0, 0.0, out), 0);
    /* A degenerate interval. */
    double lin[2] = {-0.5, 1.0};
    ck_assert_int_eq(rugo__poly_roots(lin, 1, 0.5, 0.5, 0.0, out), 1);
    ck_assert_int_eq(rugo__poly_roots(lin, 1, 0.6, 0.6, 0.0, out), 0);
    ck_assert_int_eq(rugo__poly_roots(lin, 1, 0.6, 0.5, 0.0, out), 0);
}
END_TEST

START_TEST(poly_degenerate) {
    double out[RUGO__POLY_MAX_ROOTS];
    /* Identically zero, and zero within tol. */
    double z[6] = {0, 0, 0, 0, 0, 0};
    ck_assert_int_eq(rugo__poly_roots(z, 5, 0.0, 1.0, 0.0, out), RUGO__POLY_ALL);
    double tiny[4] = {1e-17, -2e-17, 1e-18, 3e-17};
    ck_assert_int_eq(rugo__poly_roots(tiny, 3, 0.0, 1.0, 1e-15, out), RUGO__POLY_ALL);
    /* Leading coefficients that are round-off noise: the degree effectively drops. */
    double lead[6] = {-0.5, 1.0, 0.0, 1e-300, -1e-290, 1e-280};
    int n = rugo__poly_roots(lead, 5, 0.0, 1.0, 0.0, out);
    ck_assert_int_eq(n, 1);
    ck_assert_near(out[0], 0.5, 1e-15);
    double lead2[4] = {0.3 * 0.6, -0.9, 1.0, 1e-17}; /* (t - 0.3)(t - 0.6) + noise t^3 */
    n = rugo__poly_roots(lead2, 3, 0.0, 1.0, 0.0, out);
    ck_assert_int_eq(n, 2);
    ck_assert_near(out[0], 0.3, 1e-14);
    ck_assert_near(out[1], 0.6, 1e-14);
    /* Double roots: exact, lifted by round-off (reported), lifted more (reported only with tol). */
    double r2[3] = {0.3, 0.3, 0.7}, a[6];
    poly_from_roots(r2, 3, 1.0, a);
    n = rugo__poly_roots(a, 3, 0.0, 1.0, 0.0, out);
    /* round-off may split the double root into two roots ~1e-8 apart */
    ck_assert(n == 2 || n == 3);
    for (int i = 0; i + 1 < n; ++i)
        ck_assert_near(out[i], 0.3, 1e-7);
    ck_assert_near(out[n - 1], 0.7, 1e-14);
    double sq[3] = {0.09 + 1e-18, -0.6, 1.0}; /* (t - 0.3)^2 + 1e-18 */
    n = rugo__poly_roots(sq, 2, 0.0, 1.0, 0.0, out);
    ck_assert_int_eq(n, 1);
    ck_assert_near(out[0], 0.3, 1e-15);
    double sq2[3] = {0.09 + 1e-10, -0.6, 1.0};
    ck_assert_int_eq(rugo__poly_roots(sq2, 2, 0.0, 1.0, 0.0, out), 0);
    ck_assert_int_eq(rugo__poly_roots(sq2, 2, 0.0, 1.0, 1e-9, out), 1);
    ck_assert_near(out[0], 0.3, 1e-15);
    /* A touching extremum at an end of the interval. */
    double sq3[3] = {1e-20, 0.0, 1.0}; /* t^2 + 1e-20 on [0, 1]: exact evaluation at 0, so only tol */
    ck_assert_int_eq(rugo__poly_roots(sq3, 2, 0.0, 1.0, 0.0, out), 0);
    ck_assert_int_eq(rugo__poly_roots(sq3, 2, 0.0, 1.0, 1e-15, out), 1);
    ck_assert(out[0] == 0.0);
    /* A triple root and a quintuple root. */
    double r3[5] = {0.4, 0.4, 0.4, 0.4, 0.4};
    poly_from_roots(r3, 3, 1.0, a);
    n = rugo__poly_roots(a, 3, 0.0, 1.0, 0.0, out);
    ck_assert_int_ge(n, 1);
    for (int i = 0; i < n; ++i)
        ck_assert_near(out[i], 0.4, 1e-5);
    poly_from_roots(r3, 5, 1.0, a);
    n = rugo__poly_roots(a, 5, 0.0, 1.0, 0.0, out);
    ck_assert_int_ge(n, 1);
    for (int i = 0; i < n; ++i)
        ck_assert_near(out[i], 0.4, 1e-2);
    /* Non-finite input gives nothing rather than garbage. */
    double bad[2] = {NAN, 1.0};
    ck_assert_int_eq(rugo__poly_roots(bad, 1, 0.0, 1.0, 0.0, out), 0);
}
END_TEST

START_TEST(poly_random) {
    /* Random polynomials from random roots (some outside the interval, some complex pairs): every
     * real root in the interval is found to near machine precision, results sorted and distinct,
     * and every sign change seen on a fine grid is accounted for. */
    test_rng rng = test_rng_seed(12345);
    double out[RUGO__POLY_MAX_ROOTS];
    for (int trial = 0; trial < 3000; ++trial) {
        int deg = 1 + (int)(test_rng_next(&rng) % 5);
        double a[6] = {0, 0, 0, 0, 0, 0}, real[5];
        int nreal = 0;
        a[0] = test_rng_uniform(&rng, 0.5, 2.0) * ((test_rng_next(&rng) & 1) ? 1 : -1);
        int d = 0;
        while (d < deg) {
            if (deg - d >= 2 && (test_rng_next(&rng) % 4) == 0) {
                /* (t - re)^2 + im^2 */
                double re = test_rng_uniform(&rng, -0.5, 1.5), im = test_rng_uniform(&rng, 0.01, 1.0);
                double f[3] = {re * re + im * im, -2 * re, 1.0}, b[6] = {0, 0, 0, 0, 0, 0};
                for (int i = 0; i <= d; ++i)
                    for (int k = 0; k < 3; ++k)
                        b[i + k] += a[i] * f[k];
                memcpy(a, b, sizeof a);
                d += 2;
            } else {
                double r = test_rng_uniform(&rng, -0.5, 1.5);
                real[nreal++] = r;
                for (int i = d + 1; i >= 1; --i)
                    a[i] = a[i - 1] - r * a[i];
                a[0] = -r * a[0];
                d += 1;
            }
        }
        int n = rugo__poly_roots(a, deg, 0.0, 1.0, 0.0, out);
        ck_assert_int_ge(n, 0);
        for (int i = 1; i < n; ++i)
            ck_assert(out[i] > out[i - 1]);
        for (int i = 0; i < n; ++i)
            ck_assert(out[i] >= 0.0 && out[i] <= 1.0);
        /* each in-range real root is found, unless it nearly coincides with another (then it may
         * merge with its neighbour, which is still within the cluster) */
        for (int i = 0; i < nreal; ++i) {
            if (real[i] < 0.0 || real[i] > 1.0) continue;
            double sep = HUGE_VAL;
            for (int k = 0; k < nreal; ++k)
                if (k != i) sep = fmin(sep, fabs(real[k] - real[i]));
            double best = HUGE_VAL;
            for (int k = 0; k < n; ++k)
                best = fmin(best, fabs(out[k] - real[i]));
            /* forward error of a simple root: round-off of p over |p'(r)| */
            double dp = 0.0, ap = 0.0;
            for (int k = deg; k >= 1; --k)
                dp = dp * real[i] + k * a[k];
            for (int k = deg; k >= 0; --k)
                ap = ap * fabs(real[i]) + fabs(a[k]);
            double cond = 64 * DBL_EPSILON * ap / fabs(dp);
            if (sep > 1e-3)
                ck_assert_msg(best <= 1e-13 + cond, "trial %d root %.17g missed (best %.3g)", trial, real[i],
                              best);
            else
                ck_assert_msg(best <= 1e-3, "trial %d clustered root %.17g missed", trial, real[i]);
        }
        /* every reported root is a root */
        for (int k = 0; k < n; ++k) {
            double best = HUGE_VAL;
            for (int i = 0; i < nreal; ++i)
                best = fmin(best, fabs(out[k] - real[i]));
            ck_assert_msg(best <= 1e-3, "trial %d spurious root %.17g", trial, out[k]);
        }
        /* grid sign changes */
        double prev = rugo__poly_eval(a, deg, 0.0);
        for (int g = 1; g <= 200; ++g) {
            double t = g / 200.0, v = rugo__poly_eval(a, deg, t);
            if ((prev < 0 && v > 0) || (prev > 0 && v < 0)) {
                int inside = 0;
                for (int k = 0; k < n; ++k)
                    inside |= out[k] >= (g - 1) / 200.0 && out[k] <= t;
                ck_assert_msg(inside, "trial %d: sign change in [%g, %g] without a root", trial,
                              (g - 1) / 200.0, t);
            }
            prev = v;
        }
    }
}
END_TEST

START_TEST(poly_scaled) {
    /* Roots on a wide interval and with large coefficients. */
    double r[3] = {-40.0, 3.5, 77.0}, a[6], out[RUGO__POLY_MAX_ROOTS];
    poly_from_roots(r, 3, 1e12, a);
    int n = rugo__poly_roots(a, 3, -100.0, 100.0, 0.0, out);
    ck_assert_int_eq(n, 3);
    for (int i = 0; i < 3; ++i)
        ck_assert_near(out[i], r[i], 1e-12 * 100);
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Evaluation. */

static rugo_vec2 lerp(rugo_vec2 a, rugo_vec2 b, double t) {
    return rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}

static rugo_vec2 de_casteljau(const rugo_vec2 b[4], double t) {
    rugo_vec2 p01 = lerp(b[0], b[1], t), p12 = lerp(b[1], b[2], t), p23 = lerp(b[2], b[3], t);
    return lerp(lerp(p01, p12, t), lerp(p12, p23, t), t);
}

START_TEST(basis_partition_of_unity) {
    for (int i = 0; i <= 1000; ++i) {
        double t = i / 1000.0, b[4];
        rugo_bspline_basis(t, b);
        ck_assert_near(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
        for (int k = 0; k < 4; ++k)
            ck_assert(b[k] >= 0.0);
    }
    double b[4];
    rugo_bspline_basis(0.0, b);
    ck_assert_near(b[0], 1.0 / 6, 1e-16);
    ck_assert_near(b[1], 4.0 / 6, 1e-16);
    ck_assert_near(b[2], 1.0 / 6, 1e-16);
    ck_assert(b[3] == 0.0);
}
END_TEST

START_TEST(evaluation_continuity_and_forms) {
    for (int s = 0; s < 6; ++s) {
        int n = 4 << (s % 3);
        rugo_vec2 pts[16];
        double rad;
        star(100 + s, n, pts, NULL, &rad);
        rugo_contour c = contour_of(pts, n);
        double scale = rad;
        for (int j = 0; j < n; ++j) {
            /* C0, C1, C2 at the joint with the next segment. */
            rugo_vec2 a = rugo_contour_point(c, j, 1.0), b = rugo_contour_point(c, j + 1, 0.0);
            ck_assert_near(v2_dist(a, b), 0.0, 1e-15 * scale);
            ck_assert_near(v2_dist(rugo_contour_d1(c, j, 1.0), rugo_contour_d1(c, j + 1, 0.0)), 0.0,
                           1e-14 * scale);
            ck_assert_near(v2_dist(rugo_contour_d2(c, j, 1.0), rugo_contour_d2(c, j + 1, 0.0)), 0.0,
                           1e-14 * scale);
            rugo_vec2 bz[4];
            rugo_contour_bezier(c, j, bz);
            for (int i = 0; i <= 50; ++i) {
                double t = i / 50.0;
                rugo_vec2 p = rugo_contour_point(c, j, t);
                /* Matrix form (2.4) equals the Bezier form. */
                ck_assert_near(v2_dist(p, de_casteljau(bz, t)), 0.0, 1e-13 * (scale + 3));
                /* Derivatives against central differences (h = 1e-4: error ~h^2 |f'''|, round-off
                 * ~eps/h). */
                double h = 1e-4;
                rugo_vec2 pp = rugo_contour_point(c, j, t + h), pm = rugo_contour_point(c, j, t - h);
                rugo_vec2 fd1 = rugo_v2((pp.x - pm.x) / (2 * h), (pp.y - pm.y) / (2 * h));
                rugo_vec2 fd2 = rugo_v2((pp.x - 2 * p.x + pm.x) / (h * h), (pp.y - 2 * p.y + pm.y) / (h * h));
                ck_assert_near(v2_dist(rugo_contour_d1(c, j, t), fd1), 0.0, 1e-7 * (scale + 3));
                ck_assert_near(v2_dist(rugo_contour_d2(c, j, t), fd2), 0.0, 1e-4 * (scale + 3));
                /* point_at: global parameter, wrapping both ways. */
                ck_assert_near(v2_dist(rugo_contour_point_at(c, j + t), p), 0.0, 1e-13 * (scale + 3));
                if (t < 1.0)
                    ck_assert_near(v2_dist(rugo_contour_point_at(c, j + t - 2.0 * n), p), 0.0,
                                   1e-12 * (scale + 3));
            }
            /* Derivative coefficients (3.8) agree with d1. */
            rugo_vec2 v, w, r;
            rugo_contour_derivative_coefficients(c, j, &v, &w, &r);
            rugo_vec2 d = rugo_contour_d1(c, j, 0.3);
            ck_assert_near(d.x, 0.5 * (v.x * 0.09 + w.x * 0.3 + r.x), 1e-14 * (scale + 3));
            ck_assert_near(d.y, 0.5 * (v.y * 0.09 + w.y * 0.3 + r.y), 1e-14 * (scale + 3));
            /* Joint of the Bezier form is bitwise shared. */
            rugo_vec2 bn[4];
            rugo_contour_bezier(c, j + 1, bn);
            ck_assert(bz[3].x == bn[0].x && bz[3].y == bn[0].y);
        }
    }
}
END_TEST

START_TEST(tangent_normal) {
    rugo_vec2 pts[16];
    star(7, 16, pts, NULL, NULL);
    rugo_contour c = contour_of(pts, 16);
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 10; ++i) {
            double t = i / 10.0;
            rugo_vec2 tg = rugo_contour_tangent(c, j, t), nm = rugo_contour_normal(c, j, t);
            rugo_vec2 d = rugo_contour_d1(c, j, t);
            ck_assert_near(hypot(tg.x, tg.y), 1.0, 1e-15);
            ck_assert_near(rugo_v2_cross(tg, d), 0.0, 1e-14 * hypot(d.x, d.y));
            ck_assert(rugo_v2_dot(tg, d) > 0);
            ck_assert_near(rugo_v2_dot(tg, nm), 0.0, 1e-15);
            /* outward for a counter-clockwise curve: a small step along the normal leaves the region */
            rugo_vec2 p = rugo_contour_point(c, j, t);
            ck_assert(!rugo_contour_contains(c, rugo_v2(p.x + 1e-6 * nm.x, p.y + 1e-6 * nm.y)));
            ck_assert(rugo_contour_contains(c, rugo_v2(p.x - 1e-6 * nm.x, p.y - 1e-6 * nm.y)));
        }
}
END_TEST

START_TEST(degenerate_segments_everywhere) {
    rugo_contour c = contour_of(DEG_POINTS, DEG_N);
    ck_assert_int_eq(rugo_contour_check(DEG_POINTS, DEG_N, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL),
                     RUGO_OK);
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, DEG_PARABOLIC, &v, &w, &r);
    ck_assert(v.x == 0.0 && v.y == 0.0);
    rugo_contour_derivative_coefficients(c, DEG_STRAIGHT, &v, &w, &r);
    ck_assert(rugo_v2_cross(v, r) == 0.0 && rugo_v2_cross(w, r) == 0.0);
    rugo_contour_derivative_coefficients(c, DEG_POINT, &v, &w, &r);
    ck_assert(v.x == 0 && v.y == 0 && w.x == 0 && w.y == 0 && r.x == 0 && r.y == 0);
    const int kinds[4] = {DEG_CUBIC, DEG_PARABOLIC, DEG_STRAIGHT, DEG_POINT};
    for (int k = 0; k < 4; ++k) {
        int j = kinds[k];
        for (int i = 0; i <= 8; ++i) {
            double t = i / 8.0;
            rugo_vec2 p = rugo_contour_point(c, j, t), tg = rugo_contour_tangent(c, j, t);
            rugo_vec2 nm = rugo_contour_normal(c, j, t);
            ck_assert(isfinite(p.x) && isfinite(p.y) && isfinite(tg.x) && isfinite(tg.y));
            ck_assert(isfinite(nm.x) && isfinite(nm.y));
            ck_assert_near(hypot(nm.x, nm.y), 1.0, 1e-15);
            /* the closest point to a point on the segment is itself */
            rugo_curve_point cp = rugo_contour_closest_point(c, p);
            ck_assert_near(cp.distance, 0.0, 1e-14);
            ck_assert(cp.t >= 0.0 && cp.t < 1.0);
        }
        double len = rugo_contour_segment_length(c, j), alen, err;
        ck_assert(isfinite(len));
        ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, j, 1e-12, &alen, &err), RUGO_OK);
        ck_assert(isfinite(alen) && isfinite(err) && err <= 1e-12);
    }
    ck_assert(rugo_contour_segment_length(c, DEG_POINT) == 0.0);
    /* Evenly spaced straight segment: length exactly the spacing. */
    ck_assert_near(rugo_contour_segment_length(c, DEG_STRAIGHT), 1.0, 1e-15);
    rugo_mass_properties m = rugo_contour_mass_properties(c);
    ck_assert(isfinite(m.area) && isfinite(m.centroid.x) && isfinite(m.centroid.y) && isfinite(m.inertia));
    ck_assert(m.area > 0 && m.inertia > 0);
    ck_assert(isfinite(rugo_contour_perimeter(c)));
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    ck_assert_near(lo.y, -1.0, 1e-15);
    ck_assert_near(hi.y, 3.0, 1e-15); /* the pointed corner */
    ck_assert(rugo_contour_contains(c, m.centroid));
    /* Containment on the line of the straight segment and through the corner. */
    ck_assert(!rugo_contour_contains(c, rugo_v2(-5, -1)));
    ck_assert(!rugo_contour_contains(c, rugo_v2(5, -1)));
    ck_assert(rugo_contour_contains(c, rugo_v2(-0.5, -1 + 1e-9)));
    ck_assert(!rugo_contour_contains(c, rugo_v2(-5, 3)));
    ck_assert(!rugo_contour_contains(c, rugo_v2(5, 3)));
    ck_assert(rugo_contour_contains(c, rugo_v2(0, 3 - 1e-6)));
    /* A ray along the straight segment's line first touches the curve at the start of that
     * segment (segment 0 arrives there tangentially). */
    double s;
    rugo_curve_point hit;
    rugo_vec2 nm;
    ck_assert(rugo_contour_ray_cast(c, rugo_v2(-5, -1), rugo_v2(1, 0), 100.0, &s, &hit, &nm));
    ck_assert_near(s, 4.0, 1e-6);
    ck_assert_near(hit.point.y, -1.0, 1e-12);
    /* Rays at the point-like corner. */
    ck_assert(rugo_contour_ray_cast(c, rugo_v2(0, 5), rugo_v2(0, -1), 100.0, &s, &hit, &nm));
    ck_assert_near(s, 2.0, 1e-12);
    ck_assert(isfinite(nm.x) && isfinite(nm.y));
    ck_assert(rugo_contour_ray_cast(c, m.centroid, rugo_v2(0, 1), 100.0, &s, &hit, &nm));
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Arc length. */

/* Length of segment j by a polyline of m chords, Richardson-extrapolated from m/2 (error O(m^-4)). */
static double polyline_length(rugo_contour c, int j, int m) {
    double l[2];
    for (int pass = 0; pass < 2; ++pass) {
        int k = pass == 0 ? m / 2 : m;
        double s = 0.0;
        rugo_vec2 prev = rugo_contour_point(c, j, 0.0);
        for (int i = 1; i <= k; ++i) {
            rugo_vec2 p = rugo_contour_point(c, j, (double)i / k);
            s += v2_dist(p, prev);
            prev = p;
        }
        l[pass] = s;
    }
    return (4.0 * l[1] - l[0]) / 3.0;
}

START_TEST(arc_length_quadrature) {
    for (int s = 0; s < 4; ++s) {
        int n = 4 + 4 * s; /* few points: curvy segments */
        rugo_vec2 pts[16];
        star(200 + s, n, pts, NULL, NULL);
        rugo_contour c = contour_of(pts, n);
        double total = 0.0;
        for (int j = 0; j < n; ++j) {
            double ref = polyline_length(c, j, 200000);
            double gl = rugo_contour_segment_length(c, j), ad, err;
            ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, j, 1e-13, &ad, &err), RUGO_OK);
            ck_assert_near(ad, ref, 1e-11 * ref);
            ck_assert(err <= 1e-13);
            ck_assert_near(gl, ref, 1e-11 * ref);
            /* Honest error bounds at looser tolerances. */
            const double tols[3] = {1e-4, 1e-7, 1e-10};
            for (int k = 0; k < 3; ++k) {
                double l2, e2;
                ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, j, tols[k], &l2, &e2), RUGO_OK);
                ck_assert(e2 <= tols[k]);
                ck_assert_msg(fabs(l2 - ad) <= e2 + 1e-13, "tol %g: actual %.3g > bound %.3g", tols[k],
                              fabs(l2 - ad), e2);
            }
            total += gl;
        }
        ck_assert_near(rugo_contour_perimeter(c), total, 1e-13 * total);
    }
}
END_TEST

START_TEST(arc_length_straight_and_cusp) {
    /* Collinear, unevenly spaced: the speed is a positive quadratic, GL4 is exact. */
    rugo_vec2 line[6] = {{0, 0}, {1, 0}, {3, 0}, {4, 0}, {2, 1}, {1, 1}};
    rugo_contour c = contour_of(line, 6);
    ck_assert_near(rugo_contour_segment_length(c, 1), 5.0 / 3.0, 1e-15);
    /* A cusp at a joint (c_j == c_{j+2}): zero speed, |f'| has a kink there. */
    rugo_vec2 cusp[6] = {{0, 0}, {2, -1}, {3, 1}, {2, 3}, {3, 1}, {-1, 2}};
    c = contour_of(cusp, 6);
    rugo_vec2 d = rugo_contour_d1(c, 2, 1.0);
    ck_assert(d.x == 0 && d.y == 0);
    for (int j = 1; j <= 3; ++j) {
        double ref = polyline_length(c, j, 400000), ad, err;
        ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, j, 1e-10, &ad, &err), RUGO_OK);
        ck_assert_near(ad, ref, 1e-9);
        ck_assert(fabs(ad - ref) <= err + 1e-10);
    }
}
END_TEST

/* An independent reference for the round-off test below: adaptive Simpson with Richardson's
 * correction in long double, on the speed from the Bezier points (not the library's power form). */
typedef struct bezier_speed {
    long double d[3][2]; /* 3 (b1 - b0), 3 (b2 - b1), 3 (b3 - b2) */
} bezier_speed;

static long double bezier_speed_at(const bezier_speed* b, long double t) {
    const long double u = 1.0L - t, w0 = u * u, w1 = 2.0L * u * t, w2 = t * t;
    const long double x = w0 * b->d[0][0] + w1 * b->d[1][0] + w2 * b->d[2][0];
    const long double y = w0 * b->d[0][1] + w1 * b->d[1][1] + w2 * b->d[2][1];
    return sqrtl(x * x + y * y);
}

static long double simpson_adapt(const bezier_speed* b, long double a, long double fa, long double m,
                                 long double fm, long double e, long double fe, long double whole,
                                 long double tol, int depth) {
    const long double lm = 0.5L * (a + m), rm = 0.5L * (m + e);
    const long double flm = bezier_speed_at(b, lm), frm = bezier_speed_at(b, rm);
    const long double left = (m - a) / 6.0L * (fa + 4.0L * flm + fm);
    const long double right = (e - m) / 6.0L * (fm + 4.0L * frm + fe);
    const long double delta = left + right - whole;
    if (depth >= 60 || fabsl(delta) <= 15.0L * tol) return left + right + delta / 15.0L;
    return simpson_adapt(b, a, fa, lm, flm, m, fm, left, 0.5L * tol, depth + 1) +
           simpson_adapt(b, m, fm, rm, frm, e, fe, right, 0.5L * tol, depth + 1);
}

/* Segment j's length to about rel_tol of its chord-polygon length. */
static double reference_length(rugo_contour c, int j, long double rel_tol) {
    rugo_vec2 q[4];
    rugo_contour_bezier(c, j, q);
    bezier_speed b;
    long double poly = 0.0L;
    for (int i = 0; i < 3; ++i) {
        b.d[i][0] = 3.0L * ((long double)q[i + 1].x - (long double)q[i].x);
        b.d[i][1] = 3.0L * ((long double)q[i + 1].y - (long double)q[i].y);
        poly += sqrtl(b.d[i][0] * b.d[i][0] + b.d[i][1] * b.d[i][1]) / 3.0L;
    }
    if (poly == 0.0L) return 0.0;
    /* Eight pieces to start, so that no first guess agrees by luck. */
    long double total = 0.0L;
    for (int p = 0; p < 8; ++p) {
        const long double a = p / 8.0L, e = (p + 1) / 8.0L, m = 0.5L * (a + e);
        const long double fa = bezier_speed_at(&b, a), fm = bezier_speed_at(&b, m);
        const long double fe = bezier_speed_at(&b, e);
        const long double whole = (e - a) / 6.0L * (fa + 4.0L * fm + fe);
        total += simpson_adapt(&b, a, fa, m, fm, e, fe, whole, rel_tol * poly / 8.0L, 0);
    }
    return (double)total;
}

/* Every segment length and the perimeter within 1e-12 relative of the reference (the library asks
 * its quadrature for 1e-13), on a rough outline (128 points, independent radial noise of ±30 %: near
 * cusps everywhere; the 4-point rule was 3.5e-5 off here), a smooth one (a 32-point circle) and a
 * degenerate one (a point tripled, so two segments have a cusp and one a zero-speed end). */
START_TEST(arc_length_to_round_off) {
    enum { N_ROUGH = 128, N_SMOOTH = 32, N_DEG = 10 };
    rugo_vec2 rough[N_ROUGH], smooth[N_SMOOTH], deg[N_DEG];
    test_rng r = test_rng_seed(25);
    const double two_pi = 2.0 * acos(-1.0);
    for (int i = 0; i < N_ROUGH; ++i) {
        const double th = two_pi * i / N_ROUGH, rad = 1.0 + test_rng_uniform(&r, -0.3, 0.3);
        rough[i] = rugo_v2(rad * cos(th), rad * sin(th));
    }
    for (int i = 0; i < N_SMOOTH; ++i)
        smooth[i] = rugo_v2(cos(two_pi * i / N_SMOOTH), sin(two_pi * i / N_SMOOTH));
    const rugo_vec2 deg_pts[N_DEG] = {{0, 0}, {2, 0}, {3, 0}, {3, 0},  {3, 0},
                                      {3, 1}, {3, 2}, {1, 3}, {-1, 2}, {-1, 1}};
    memcpy(deg, deg_pts, sizeof deg);
    const struct {
        const rugo_vec2* p;
        int n;
    } cases[3] = {{rough, N_ROUGH}, {smooth, N_SMOOTH}, {deg, N_DEG}};
    for (int k = 0; k < 3; ++k) {
        rugo_contour c = contour_of(cases[k].p, cases[k].n);
        long double total = 0.0L;
        for (int j = 0; j < cases[k].n; ++j) {
            const double ref = reference_length(c, j, 1e-16L);
            /* The reference against itself at a looser tolerance: it resolves these segments. */
            ck_assert_near(reference_length(c, j, 1e-14L), ref, 1e-13 * ref + 1e-300);
            const double len = rugo_contour_segment_length(c, j);
            ck_assert_msg(fabs(len - ref) <= 1e-12 * ref,
                          "case %d segment %d: %.17g vs %.17g (%.3g relative)", k, j, len, ref,
                          fabs(len - ref) / ref);
            double ad, err;
            const double tol = 1e-13 * ref + 1e-300;
            ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, j, tol, &ad, &err), RUGO_OK);
            ck_assert(fabs(ad - ref) <= err + 1e-15 * ref); /* the bound is honest */
            total += ref;
        }
        const double per = rugo_contour_perimeter(c);
        ck_assert_msg(fabsl(per - total) <= 1e-12L * total, "case %d: perimeter %.17g vs %.17Lg", k, per,
                      total);
    }
    /* The tripled point: the speed vanishes at a joint. */
    rugo_contour c = contour_of(deg, N_DEG);
    rugo_vec2 d = rugo_contour_d1(c, 3, 0.0);
    ck_assert(d.x == 0.0 && d.y == 0.0);
}
END_TEST

START_TEST(arc_length_arguments) {
    rugo_vec2 pts[8];
    star(3, 8, pts, NULL, NULL);
    rugo_contour c = contour_of(pts, 8);
    double l = 1, e = 1;
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, 1e-9, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, 0.0, &l, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, -1.0, &l, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, NAN, &l, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, INFINITY, &l, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, 1e-9, &l, NULL), RUGO_OK);
    rugo_contour none = contour_of(NULL, 8);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(none, 0, 1e-9, &l, &e), RUGO_ERR_NULL_ARGUMENT);
    /* More than double precision can give: not converged, but the best estimate comes back. */
    double ref;
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, 1e-12, &ref, NULL), RUGO_OK);
    ck_assert_int_eq(rugo_contour_segment_length_adaptive(c, 0, 1e-300, &l, &e), RUGO_ERR_NOT_CONVERGED);
    ck_assert(fabs(l - ref) <= e + 1e-12);
    ck_assert(e < 1e-9);
    ck_assert(isfinite(e));
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Mass properties. */

typedef struct poly_props {
    double area, cx, cy, inertia;
} poly_props;

static void kadd(double* s, double* comp, double x) {
    double t = *s + x;
    if (fabs(*s) >= fabs(x))
        *comp += (*s - t) + x;
    else
        *comp += (x - t) + *s;
    *s = t;
}

/* Shoelace area, polygon centroid and polar moment of a polygon with m samples of the curve per
 * segment, about reference point o (compensated sums). */
static poly_props polygon_props(rugo_contour c, int m, rugo_vec2 o) {
    double a = 0, ac = 0, x = 0, xc = 0, y = 0, yc = 0, j = 0, jc = 0;
    int total = c.count * m;
    rugo_vec2 first = rugo_v2_sub(rugo_contour_point(c, 0, 0.0), o), p0 = first;
    for (int i = 1; i <= total; ++i) {
        rugo_vec2 p1 = i == total ? first : rugo_v2_sub(rugo_contour_point(c, i / m, (double)(i % m) / m), o);
        double cr = p0.x * p1.y - p1.x * p0.y;
        kadd(&a, &ac, cr);
        kadd(&x, &xc, (p0.x + p1.x) * cr);
        kadd(&y, &yc, (p0.y + p1.y) * cr);
        kadd(&j, &jc,
             cr * (p0.x * p0.x + p0.x * p1.x + p1.x * p1.x + p0.y * p0.y + p0.y * p1.y + p1.y * p1.y));
        p0 = p1;
    }
    poly_props r;
    r.area = 0.5 * (a + ac);
    double mx = (x + xc) / 6.0, my = (y + yc) / 6.0, jo = (j + jc) / 12.0;
    r.cx = mx / r.area;
    r.cy = my / r.area;
    r.inertia = jo - r.area * (r.cx * r.cx + r.cy * r.cy);
    r.cx += o.x;
    r.cy += o.y;
    return r;
}

/* The 10^6-vertex polygon reference, Richardson-extrapolated from 5e5 vertices (polygon errors are
 * O(h^2) with an h^4 next term). */
static poly_props polygon_reference(rugo_contour c, rugo_vec2 o) {
    int m = 1000000 / c.count;
    poly_props a = polygon_props(c, m / 2, o), b = polygon_props(c, m, o), r;
    r.area = (4 * b.area - a.area) / 3;
    r.cx = (4 * b.cx - a.cx) / 3;
    r.cy = (4 * b.cy - a.cy) / 3;
    r.inertia = (4 * b.inertia - a.inertia) / 3;
    return r;
}

START_TEST(mass_properties_vs_polygon) {
    /* ACCEPTANCE: 1e-9 relative against the independent 10^6-vertex polygon. */
    const int counts[5] = {8, 16, 32, 64, 4};
    for (int s = 0; s < 5; ++s) {
        int n = counts[s];
        rugo_vec2 pts[64], ctr;
        double rad;
        star(300 + s, n, pts, &ctr, &rad);
        rugo_contour c = contour_of(pts, n);
        rugo_mass_properties m = rugo_contour_mass_properties(c);
        poly_props r = polygon_reference(c, ctr);
        ck_assert_near(m.area, r.area, 1e-9 * fabs(r.area));
        ck_assert_near(m.centroid.x, r.cx, 1e-9 * rad);
        ck_assert_near(m.centroid.y, r.cy, 1e-9 * rad);
        ck_assert_near(m.inertia, r.inertia, 1e-9 * fabs(r.inertia));
        ck_assert_near(m.area, rugo_contour_signed_area(c), 1e-14 * m.area);
    }
}
END_TEST

START_TEST(mass_properties_exact) {
    /* Closed forms derived symbolically (exact rational integrals of the segments). */
    rugo_vec2 sq[4] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    rugo_mass_properties m = rugo_contour_mass_properties(contour_of(sq, 4));
    ck_assert_near(m.area, 122.0 / 45.0, 1e-15);
    ck_assert_near(m.centroid.x, 0.0, 1e-15);
    ck_assert_near(m.centroid.y, 0.0, 1e-15);
    ck_assert_near(m.inertia, 109484.0 / 93555.0, 1e-15);
    rugo_vec2 hex[6] = {{0, 0}, {4, 0}, {5, 2}, {3, 5}, {1, 4}, {-1, 2}};
    m = rugo_contour_mass_properties(contour_of(hex, 6));
    ck_assert_near(m.area, 84.0 / 5.0, 1e-14);
    ck_assert_near(m.centroid.x, 703651.0 / 338688.0, 1e-14);
    ck_assert_near(m.centroid.y, 1064053.0 / 508032.0, 1e-14);
    ck_assert_near(m.inertia, 6236160408677.0 / 135193411584.0, 1e-13);
    /* Clockwise: the same region, area and inertia negative (inertia has the sign of the area). */
    rugo_vec2 rev[6];
    for (int i = 0; i < 6; ++i)
        rev[i] = hex[5 - i];
    rugo_mass_properties w = rugo_contour_mass_properties(contour_of(rev, 6));
    ck_assert_near(w.area, -m.area, 1e-14);
    ck_assert_near(w.centroid.x, m.centroid.x, 1e-14);
    ck_assert_near(w.centroid.y, m.centroid.y, 1e-14);
    ck_assert_near(w.inertia, -m.inertia, 1e-13);
}
END_TEST

START_TEST(mass_properties_triangle) {
    /* Corners repeated four times: the curve is exactly the triangle (straight sides, point-like
     * segments at the corners), so the polygon formulas are exact references. */
    rugo_vec2 a = {0.5, -1}, b = {4, 0.25}, c3 = {1, 3}, pts[12];
    for (int i = 0; i < 4; ++i)
        pts[i] = a, pts[4 + i] = b, pts[8 + i] = c3;
    rugo_contour c = contour_of(pts, 12);
    ck_assert_int_eq(rugo_contour_check(pts, 12, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL), RUGO_OK);
    double area = 0.5 * rugo_v2_cross(rugo_v2_sub(b, a), rugo_v2_sub(c3, a));
    double l2 = rugo_v2_dot(rugo_v2_sub(b, a), rugo_v2_sub(b, a)) +
                rugo_v2_dot(rugo_v2_sub(c3, b), rugo_v2_sub(c3, b)) +
                rugo_v2_dot(rugo_v2_sub(a, c3), rugo_v2_sub(a, c3));
    rugo_mass_properties m = rugo_contour_mass_properties(c);
    ck_assert_near(m.area, area, 1e-14 * area);
    ck_assert_near(m.centroid.x, (a.x + b.x + c3.x) / 3, 1e-14);
    ck_assert_near(m.centroid.y, (a.y + b.y + c3.y) / 3, 1e-14);
    ck_assert_near(m.inertia, area * l2 / 36, 1e-13 * area * l2 / 36); /* triangle: A (a^2 + b^2 + c^2)/36 */
    double per = sqrt(rugo_v2_dot(rugo_v2_sub(b, a), rugo_v2_sub(b, a))) +
                 sqrt(rugo_v2_dot(rugo_v2_sub(c3, b), rugo_v2_sub(c3, b))) +
                 sqrt(rugo_v2_dot(rugo_v2_sub(a, c3), rugo_v2_sub(a, c3)));
    ck_assert_near(rugo_contour_perimeter(c), per, 1e-13 * per);
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    ck_assert_near(lo.x, 0.5, 1e-15);
    ck_assert_near(lo.y, -1.0, 1e-15);
    ck_assert_near(hi.x, 4.0, 1e-15);
    ck_assert_near(hi.y, 3.0, 1e-15);
    ck_assert_near(rugo_contour_closest_point(c, rugo_v2(1, 4)).distance, 1.0, 1e-14);
    ck_assert(rugo_contour_contains(c, m.centroid));
    ck_assert(!rugo_contour_contains(c, rugo_v2(1, 3.0000001)));
    ck_assert(rugo_contour_contains(c, rugo_v2(1, 2.9999)));
}
END_TEST

START_TEST(mass_properties_invariance) {
    for (int s = 0; s < 4; ++s) {
        int n = 16 << (s % 2);
        rugo_vec2 pts[32], moved[32];
        double rad;
        star(400 + s, n, pts, NULL, &rad);
        rugo_mass_properties m = rugo_contour_mass_properties(contour_of(pts, n));
        const double shifts[3][2] = {{0.0, 0.0}, {1e6, -1e6}, {-3.5e6, 2.25e6}};
        const double angles[3] = {0.7, 0.0, -2.1};
        for (int k = 0; k < 3; ++k) {
            double ca = cos(angles[k]), sa = sin(angles[k]);
            for (int i = 0; i < n; ++i)
                moved[i] = rugo_v2(ca * pts[i].x - sa * pts[i].y + shifts[k][0],
                                   sa * pts[i].x + ca * pts[i].y + shifts[k][1]);
            rugo_mass_properties r = rugo_contour_mass_properties(contour_of(moved, n));
            rugo_vec2 ec = rugo_v2(ca * m.centroid.x - sa * m.centroid.y + shifts[k][0],
                                   sa * m.centroid.x + ca * m.centroid.y + shifts[k][1]);
            ck_assert_near(r.area, m.area, 1e-9 * m.area);
            ck_assert_near(r.inertia, m.inertia, 1e-9 * m.inertia);
            /* The centroid far away can only be as exact as the coordinates: 1e6 * eps. */
            ck_assert_near(r.centroid.x, ec.x, 1e-9 * rad + 4e-10 * fabs(ec.x));
            ck_assert_near(r.centroid.y, ec.y, 1e-9 * rad + 4e-10 * fabs(ec.y));
            ck_assert_near(rugo_contour_signed_area(contour_of(moved, n)), m.area, 1e-9 * m.area);
        }
    }
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Orientation. */

START_TEST(orientation_reversal_mapping) {
    rugo_vec2 ccw[16], cw[16], fixed[16];
    star(500, 16, ccw, NULL, NULL);
    ck_assert(!rugo_contour_orient_ccw(ccw, 16)); /* already counter-clockwise: untouched */
    for (int i = 0; i < 16; ++i)
        cw[i] = ccw[(5 * 16 - 3 * i) % 16]; /* clockwise, another start */
    memcpy(fixed, cw, sizeof cw);
    ck_assert(rugo_contour_signed_area(contour_of(cw, 16)) < 0);
    ck_assert(rugo_contour_orient_ccw(fixed, 16));
    ck_assert(rugo_contour_signed_area(contour_of(fixed, 16)) > 0);
    ck_assert(!rugo_contour_orient_ccw(fixed, 16));
    /* Segment j of the clockwise input at t is segment n-2-j of the reversed one at 1-t. */
    rugo_contour a = contour_of(cw, 16), b = contour_of(fixed, 16);
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i <= 20; ++i) {
            double t = i / 20.0;
            ck_assert_near(v2_dist(rugo_contour_point(a, j, t), rugo_contour_point(b, 16 - 2 - j, 1.0 - t)),
                           0.0, 1e-14);
        }
    /* Odd count too. */
    rugo_vec2 odd[7];
    for (int i = 0; i < 7; ++i)
        odd[i] = rugo_v2(cos(-2 * PI * i / 7), sin(-2 * PI * i / 7));
    rugo_vec2 odd_r[7];
    memcpy(odd_r, odd, sizeof odd);
    ck_assert(rugo_contour_orient_ccw(odd_r, 7));
    for (int j = 0; j < 7; ++j)
        ck_assert_near(v2_dist(rugo_contour_point(contour_of(odd, 7), j, 0.25),
                               rugo_contour_point(contour_of(odd_r, 7), rugo__wrap(7 - 2 - j, 7), 0.75)),
                       0.0, 1e-15);
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Bounds. */

/* Largest value of dot(f, e) near the best of dense samples, refined by golden section. */
static double extreme_along(rugo_contour c, rugo_vec2 e) {
    double best = -HUGE_VAL;
    double best_u = 0.0;
    int m = 400;
    for (int k = 0; k < c.count * m; ++k) {
        double u = (double)k / m;
        double v = rugo_v2_dot(rugo_contour_point_at(c, u), e);
        if (v > best) best = v, best_u = u;
    }
    double lo = best_u - 1.0 / m, hi = best_u + 1.0 / m;
    for (int it = 0; it < 100; ++it) {
        double a = lo + (hi - lo) * 0.381966011250105, b = hi - (hi - lo) * 0.381966011250105;
        if (rugo_v2_dot(rugo_contour_point_at(c, a), e) > rugo_v2_dot(rugo_contour_point_at(c, b), e))
            hi = b;
        else
            lo = a;
    }
    return fmax(best, rugo_v2_dot(rugo_contour_point_at(c, 0.5 * (lo + hi)), e));
}

static void check_bounds(rugo_contour c) {
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    double scale =
        fmax(hi.x - lo.x, hi.y - lo.y) + fmax(fabs(lo.x), fabs(hi.x)) + fmax(fabs(lo.y), fabs(hi.y));
    double tol = 1e-12 * scale;
    for (int k = 0; k < c.count * 200; ++k) {
        rugo_vec2 p = rugo_contour_point_at(c, k / 200.0);
        ck_assert(p.x >= lo.x - tol && p.x <= hi.x + tol && p.y >= lo.y - tol && p.y <= hi.y + tol);
    }
    ck_assert_near(extreme_along(c, rugo_v2(1, 0)), hi.x, tol);
    ck_assert_near(extreme_along(c, rugo_v2(0, 1)), hi.y, tol);
    ck_assert_near(-extreme_along(c, rugo_v2(-1, 0)), lo.x, tol);
    ck_assert_near(-extreme_along(c, rugo_v2(0, -1)), lo.y, tol);
}

START_TEST(bounds_tight) {
    for (int s = 0; s < 8; ++s) {
        rugo_vec2 pts[32];
        int n = 4 + 4 * s;
        star(600 + s, n, pts, NULL, NULL);
        check_bounds(contour_of(pts, n));
    }
    check_bounds(contour_of(DEG_POINTS, DEG_N));
    rugo_vec2 sq[4] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    rugo_vec2 lo, hi;
    rugo_contour_bounds(contour_of(sq, 4), &lo, &hi);
    /* the sides' middles: x = (-1 + 23 + 23 - 1)/48 at t = 1/2 (basis 1/48, 23/48, 23/48, 1/48) */
    ck_assert_near(hi.x, 11.0 / 12.0, 1e-15);
    ck_assert_near(lo.y, -11.0 / 12.0, 1e-15);
    rugo_contour_bounds(contour_of(sq, 4), NULL, NULL);
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Closest point. */

/* Brute force: dense samples, then golden section around the best. */
static double brute_distance(rugo_contour c, rugo_vec2 p) {
    int m = 256;
    double best = HUGE_VAL, bu = 0;
    for (int k = 0; k < c.count * m; ++k) {
        double u = (double)k / m, d = v2_dist(rugo_contour_point_at(c, u), p);
        if (d < best) best = d, bu = u;
    }
    double lo = bu - 1.0 / m, hi = bu + 1.0 / m;
    for (int it = 0; it < 100; ++it) {
        double a = lo + (hi - lo) * 0.381966011250105, b = hi - (hi - lo) * 0.381966011250105;
        if (v2_dist(rugo_contour_point_at(c, a), p) < v2_dist(rugo_contour_point_at(c, b), p))
            hi = b;
        else
            lo = a;
    }
    return fmin(best, v2_dist(rugo_contour_point_at(c, 0.5 * (lo + hi)), p));
}

static void check_closest(rugo_contour c, rugo_vec2 p) {
    rugo_curve_point cp = rugo_contour_closest_point(c, p);
    ck_assert(cp.segment >= 0 && cp.segment < c.count);
    ck_assert(cp.t >= 0.0 && cp.t < 1.0);
    rugo_vec2 f = rugo_contour_point(c, cp.segment, cp.t);
    ck_assert(f.x == cp.point.x && f.y == cp.point.y);
    ck_assert_near(cp.distance, v2_dist(f, p), 1e-14 * (1 + cp.distance));
    double bf = brute_distance(c, p);
    /* never worse than brute force, and brute force cannot beat it by more than its own slack */
    ck_assert_msg(cp.distance <= bf + 1e-13 * (1 + bf), "closest %.17g > brute %.17g", cp.distance, bf);
    ck_assert_near(cp.distance, bf, 1e-9 * (1 + bf));
}

START_TEST(closest_point_vs_brute_force) {
    test_rng rng = test_rng_seed(77);
    for (int s = 0; s < 6; ++s) {
        int n = 4 << (s % 4);
        rugo_vec2 pts[32], ctr;
        double rad;
        star(700 + s, n, pts, &ctr, &rad);
        rugo_contour c = contour_of(pts, n);
        for (int k = 0; k < 60; ++k) {
            double sc = k < 40 ? 1.6 : 10.0;
            check_closest(c, rugo_v2(ctr.x + test_rng_uniform(&rng, -sc, sc) * rad,
                                     ctr.y + test_rng_uniform(&rng, -sc, sc) * rad));
        }
        /* the centroid-ish centre, joints and points on the curve */
        check_closest(c, ctr);
        for (int j = 0; j < n; ++j) {
            rugo_curve_point cp = rugo_contour_closest_point(c, rugo_contour_point(c, j, 0.0));
            ck_assert_near(cp.distance, 0.0, 1e-14 * rad);
            cp = rugo_contour_closest_point(c, rugo_contour_point(c, j, 0.37));
            ck_assert_near(cp.distance, 0.0, 1e-14 * rad);
            ck_assert_int_eq(cp.segment, j);
            ck_assert_near(cp.t, 0.37, 1e-7);
        }
    }
    rugo_contour d = contour_of(DEG_POINTS, DEG_N);
    for (int k = 0; k < 200; ++k)
        check_closest(d, rugo_v2(test_rng_uniform(&rng, -4, 4), test_rng_uniform(&rng, -3, 5)));
    /* The pointed corner is closest for points straight above it. */
    rugo_curve_point cp = rugo_contour_closest_point(d, rugo_v2(0, 4));
    ck_assert_near(cp.distance, 1.0, 1e-14);
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Containment. */

static void check_contains_random(rugo_contour c, uint64_t seed, int count) {
    rugo_vec2* poly = dense_polygon(c, 1000);
    int np = c.count * 1000;
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    double w = hi.x - lo.x, h = hi.y - lo.y;
    test_rng rng = test_rng_seed(seed);
    int tested = 0, inside = 0;
    for (int k = 0; k < count; ++k) {
        rugo_vec2 p = rugo_v2(test_rng_uniform(&rng, lo.x - 0.2 * w, hi.x + 0.2 * w),
                              test_rng_uniform(&rng, lo.y - 0.2 * h, hi.y + 0.2 * h));
        /* every 8th point sits exactly on the level of a joint: rays through joints */
        if (k % 8 == 0) p.y = rugo_contour_point(c, (int)(test_rng_next(&rng) % (uint64_t)c.count), 0.0).y;
        if (rugo_contour_closest_point(c, p).distance < 1e-6) continue;
        int expect = polygon_winding(poly, np, p) != 0;
        ck_assert_msg(rugo_contour_contains(c, p) == expect, "point (%.17g, %.17g)", p.x, p.y);
        ++tested;
        inside += expect;
    }
    ck_assert_int_gt(tested, count * 8 / 10);
    ck_assert_int_gt(inside, 0);
    free(poly);
}

START_TEST(contains_vs_polygon) {
    for (int s = 0; s < 6; ++s) {
        int n = 4 << (s % 4);
        rugo_vec2 pts[32], rev[32];
        star(800 + s, n, pts, NULL, NULL);
        check_contains_random(contour_of(pts, n), 900 + (uint64_t)s, 2000);
        /* Non-zero winding: the clockwise copy contains the same points. */
        for (int i = 0; i < n; ++i)
            rev[i] = pts[n - 1 - i];
        check_contains_random(contour_of(rev, n), 900 + (uint64_t)s, 500);
    }
    check_contains_random(contour_of(DEG_POINTS, DEG_N), 999, 3000);
}
END_TEST

START_TEST(contains_tangent_and_joint_rays) {
    for (int s = 0; s < 6; ++s) {
        int n = 8 << (s % 2);
        rugo_vec2 pts[16];
        star(1000 + s, n, pts, NULL, NULL);
        rugo_contour c = contour_of(pts, n);
        rugo_vec2 lo, hi;
        rugo_contour_bounds(c, &lo, &hi);
        double w = hi.x - lo.x;
        /* The horizontal lines of the top and bottom tangents: the ray touches the curve. */
        for (int k = 0; k <= 20; ++k) {
            double x = lo.x - 0.5 * w + 2.0 * w * k / 20.0;
            rugo_vec2 top = rugo_v2(x, hi.y), bot = rugo_v2(x, lo.y);
            if (rugo_contour_closest_point(c, top).distance > 1e-6) ck_assert(!rugo_contour_contains(c, top));
            if (rugo_contour_closest_point(c, bot).distance > 1e-6) ck_assert(!rugo_contour_contains(c, bot));
        }
        /* Horizontal tangents inside the bounds: local extrema of y along the curve. */
        rugo_vec2* poly = dense_polygon(c, 1000);
        for (int j = 0; j < n; ++j) {
            rugo_vec2 v, ww, r;
            rugo_contour_derivative_coefficients(c, j, &v, &ww, &r);
            double a[3] = {r.y, ww.y, v.y}, roots[RUGO__POLY_MAX_ROOTS];
            int nr = rugo__poly_roots(a, 2, 0.0, 1.0, 0.0, roots);
            for (int i = 0; i < nr; ++i) {
                double y = rugo_contour_point(c, j, roots[i]).y;
                for (int k = 0; k <= 40; ++k) {
                    rugo_vec2 p = rugo_v2(lo.x - 0.1 * w + 1.2 * w * k / 40.0, y);
                    if (rugo_contour_closest_point(c, p).distance < 1e-6) continue;
                    ck_assert_int_eq(rugo_contour_contains(c, p), polygon_winding(poly, n * 1000, p) != 0);
                }
            }
        }
        free(poly);
    }
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Ray cast. */

/* First hit of the ray with a dense polygon (parameter s), or HUGE_VAL. */
static double polygon_ray(const rugo_vec2* v, int n, rugo_vec2 o, rugo_vec2 d) {
    double best = HUGE_VAL;
    for (int i = 0; i < n; ++i) {
        rugo_vec2 a = v[i], b = v[(i + 1) % n], e = rugo_v2_sub(b, a), ao = rugo_v2_sub(a, o);
        double den = rugo_v2_cross(d, e);
        if (den == 0.0) continue;
        double s = rugo_v2_cross(ao, e) / den, u = rugo_v2_cross(ao, d) / den;
        if (s >= 0 && u >= 0 && u <= 1 && s < best) best = s;
    }
    return best;
}

START_TEST(ray_cast_vs_brute_force) {
    test_rng rng = test_rng_seed(4242);
    for (int s = 0; s < 6; ++s) {
        int n = 4 << (s % 4);
        rugo_vec2 pts[32], ctr;
        double rad;
        star(1100 + s, n, pts, &ctr, &rad);
        rugo_contour c = contour_of(pts, n);
        rugo_vec2* poly = dense_polygon(c, 2000);
        int np = n * 2000, hits = 0;
        for (int k = 0; k < 300; ++k) {
            rugo_vec2 o = rugo_v2(ctr.x + test_rng_uniform(&rng, -2.5, 2.5) * rad,
                                  ctr.y + test_rng_uniform(&rng, -2.5, 2.5) * rad);
            double ang = test_rng_uniform(&rng, 0, 2 * PI), len = test_rng_uniform(&rng, 0.1, 3.0);
            rugo_vec2 d = rugo_v2(len * cos(ang), len * sin(ang));
            if (k % 3 == 0) d = rugo_v2_sub(ctr, o); /* aimed at the body */
            double sf;
            rugo_curve_point hit;
            rugo_vec2 nm;
            int got = rugo_contour_ray_cast(c, o, d, 1e9, &sf, &hit, &nm);
            double sp = polygon_ray(poly, np, o, d);
            double dl = hypot(d.x, d.y);
            if (!got) {
                /* a miss is a miss for the polygon too, unless the ray grazes within its error */
                if (sp < HUGE_VAL) {
                    rugo_vec2 q = rugo_v2(o.x + sp * d.x, o.y + sp * d.y);
                    double dist = rugo_contour_closest_point(c, q).distance;
                    ck_assert_msg(dist < 1e-6 * rad, "missed a hit at s = %g", sp);
                }
                continue;
            }
            ++hits;
            ck_assert(sf >= 0.0);
            rugo_vec2 q = rugo_v2(o.x + sf * d.x, o.y + sf * d.y);
            /* the hit is on the ray, on the curve, and the reported point is that point */
            ck_assert_near(v2_dist(q, hit.point), 0.0, 1e-10 * rad);
            ck_assert_near(rugo_contour_closest_point(c, q).distance, 0.0, 1e-10 * rad);
            ck_assert(hit.t >= 0.0 && hit.t < 1.0);
            ck_assert_near(hit.distance, sf * dl, 1e-12 * (1 + hit.distance));
            /* no earlier crossing: the polygon's first hit is not before it (within the polygon's
             * error along the ray) */
            ck_assert_msg(sf <= sp + 1e-6 * rad / dl, "s = %.17g, polygon %.17g", sf, sp);
            /* outward unit normal: against the ray when coming from outside */
            ck_assert_near(hypot(nm.x, nm.y), 1.0, 1e-14);
            int from_inside = rugo_contour_contains(c, o);
            double dn = rugo_v2_dot(nm, d) / dl;
            if (fabs(dn) > 1e-3) ck_assert_int_eq(dn > 0, from_inside);
            /* a little shorter: no hit */
            if (sf > 1e-6) ck_assert(!rugo_contour_ray_cast(c, o, d, sf * (1 - 1e-9), NULL, NULL, NULL));
            double s2;
            ck_assert(rugo_contour_ray_cast(c, o, d, sf, &s2, NULL, NULL));
            ck_assert(s2 == sf);
        }
        ck_assert_int_gt(hits, 50);
        free(poly);
    }
}
END_TEST

START_TEST(ray_cast_special) {
    rugo_vec2 pts[16], ctr;
    double rad;
    star(1200, 16, pts, &ctr, &rad);
    rugo_contour c = contour_of(pts, 16);
    rugo_mass_properties m = rugo_contour_mass_properties(c);
    double s;
    rugo_curve_point hit;
    rugo_vec2 nm;
    /* From inside: always a hit, normal along the ray. */
    for (int k = 0; k < 64; ++k) {
        double a = 2 * PI * k / 64;
        rugo_vec2 d = rugo_v2(cos(a), sin(a));
        ck_assert(rugo_contour_ray_cast(c, m.centroid, d, 100.0, &s, &hit, &nm));
        ck_assert(rugo_v2_dot(nm, d) > 0);
        ck_assert_near(rugo_contour_closest_point(c, hit.point).distance, 0.0, 1e-12);
    }
    /* Through every joint from far outside along the outward normal. */
    for (int j = 0; j < 16; ++j) {
        rugo_vec2 p = rugo_contour_point(c, j, 0.0), n0 = rugo_contour_normal(c, j, 0.0);
        rugo_vec2 o = rugo_v2(p.x + 3 * rad * n0.x, p.y + 3 * rad * n0.y);
        ck_assert(rugo_contour_ray_cast(c, o, rugo_v2(-n0.x, -n0.y), 10 * rad, &s, &hit, &nm));
        ck_assert_near(s, 3 * rad, 1e-12 * rad);
        ck_assert_near(v2_dist(hit.point, p), 0.0, 1e-12 * rad);
        ck_assert_near(v2_dist(nm, n0), 0.0, 1e-9);
        /* the joint: start of segment j or the very end of segment j-1 (never t = 1) */
        ck_assert((hit.segment == j && hit.t < 1e-9) ||
                  (hit.segment == rugo__wrap(j - 1, 16) && hit.t > 1.0 - 1e-9));
    }
    /* Tangent rays: along the top and bottom tangent lines, hitting the tangent points. */
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    ck_assert(rugo_contour_ray_cast(c, rugo_v2(lo.x - 1, hi.y), rugo_v2(1, 0), 100.0, &s, &hit, &nm));
    ck_assert_near(hit.point.y, hi.y, 1e-12);
    ck_assert_near(nm.y, 1.0, 1e-6);
    ck_assert(rugo_contour_ray_cast(c, rugo_v2(hi.x + 1, lo.y), rugo_v2(-1, 0), 100.0, &s, &hit, &nm));
    ck_assert_near(hit.point.y, lo.y, 1e-12);
    /* Just outside the tangent: no hit. */
    ck_assert(!rugo_contour_ray_cast(c, rugo_v2(lo.x - 1, hi.y + 1e-9), rugo_v2(1, 0), 100.0, &s, &hit, &nm));
    /* Away from the body, zero direction, negative or NaN max fraction: no hit. */
    ck_assert(!rugo_contour_ray_cast(c, rugo_v2(hi.x + 1, 0), rugo_v2(1, 0), 100.0, &s, &hit, &nm));
    ck_assert(!rugo_contour_ray_cast(c, m.centroid, rugo_v2(0, 0), 100.0, &s, &hit, &nm));
    ck_assert(!rugo_contour_ray_cast(c, m.centroid, rugo_v2(1, 0), -1.0, &s, &hit, &nm));
    ck_assert(!rugo_contour_ray_cast(c, m.centroid, rugo_v2(1, 0), NAN, &s, &hit, &nm));
    /* Origin on the curve: s = 0. */
    rugo_vec2 on = rugo_contour_point(c, 3, 0.5);
    ck_assert(rugo_contour_ray_cast(c, on, rugo_contour_normal(c, 3, 0.5), 1.0, &s, &hit, &nm));
    ck_assert_near(s, 0.0, 1e-12);
    /* Translated far away: same answers. */
    rugo_vec2 far[16];
    for (int i = 0; i < 16; ++i)
        far[i] = rugo_v2(pts[i].x + 1e6, pts[i].y - 1e6);
    double s0, s1;
    ck_assert(rugo_contour_ray_cast(c, m.centroid, rugo_v2(0.3, 1), 100.0, &s0, NULL, NULL));
    ck_assert_int_eq(rugo_contour_ray_cast(contour_of(far, 16),
                                           rugo_v2(m.centroid.x + 1e6, m.centroid.y - 1e6), rugo_v2(0.3, 1),
                                           100.0, &s1, NULL, NULL),
                     1);
    ck_assert_near(s0, s1, 1e-8);
}
END_TEST

/* ---------------------------------------------------------------------------------------------------
 * Validation. */

START_TEST(check_null_and_counts) {
    rugo_vec2 pts[8];
    star(1, 8, pts, NULL, NULL);
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_contour_check(NULL, 8, 0, &pr, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_contour_check(pts, 3, 0, &pr, NULL), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_contour_check(pts, -1, 0, &pr, NULL), RUGO_ERR_TOO_FEW_POINTS);
    /* counts are checked before any point is read */
    ck_assert_int_eq(rugo_contour_check(pts, RUGO_MAX_CONTROL_POINTS + 1, 0, &pr, NULL),
                     RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(pr.index, -1);
    ck_assert_int_eq(pr.segment_a, -1);
}
END_TEST

START_TEST(check_power_of_two) {
    rugo_vec2 pts[12];
    star(2, 12, pts, NULL, NULL);
    ck_assert_int_eq(rugo_contour_check(pts, 12, RUGO_CHECK_POWER_OF_TWO, NULL, NULL),
                     RUGO_ERR_NOT_POWER_OF_TWO);
    ck_assert_int_eq(rugo_contour_check(pts, 12, 0, NULL, NULL), RUGO_OK);
    ck_assert_int_eq(rugo_contour_check(pts, 12, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL), RUGO_OK);
    star(2, 8, pts, NULL, NULL);
    ck_assert_int_eq(rugo_contour_check(pts, 8, RUGO_CHECK_ALL, NULL, NULL), RUGO_OK);
    /* the power-of-two rule comes before finiteness */
    pts[0].x = NAN;
    ck_assert_int_eq(rugo_contour_check(pts, 7, RUGO_CHECK_POWER_OF_TWO, NULL, NULL),
                     RUGO_ERR_NOT_POWER_OF_TWO);
}
END_TEST

START_TEST(check_not_finite) {
    rugo_vec2 pts[8];
    star(3, 8, pts, NULL, NULL);
    rugo_contour_problem pr;
    pts[5].y = NAN;
    pts[6].x = INFINITY;
    ck_assert_int_eq(rugo_contour_check(pts, 8, RUGO_CHECK_ALL, &pr, NULL), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(pr.index, 5);
    pts[5].y = 0.0;
    ck_assert_int_eq(rugo_contour_check(pts, 8, 0, &pr, NULL), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(pr.index, 6);
    pts[0].x = -INFINITY;
    ck_assert_int_eq(rugo_contour_check(pts, 8, 0, &pr, NULL), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(pr.index, 0);
}
END_TEST

START_TEST(check_zero_area) {
    rugo_vec2 col[6] = {{0, 0}, {1, 1}, {2, 2}, {5, 5}, {3, 3}, {1, 1}};
    ck_assert_int_eq(rugo_contour_check(col, 6, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL),
                     RUGO_ERR_ZERO_AREA);
    rugo_vec2 same[4] = {{2, 3}, {2, 3}, {2, 3}, {2, 3}};
    ck_assert_int_eq(rugo_contour_check(same, 4, 0, NULL, NULL), RUGO_ERR_ZERO_AREA);
    /* Nearly collinear below the threshold, then clearly above it. */
    rugo_vec2 thin[4] = {{0, 0}, {1, 1e-14}, {2, 0}, {1, -1e-14}};
    ck_assert_int_eq(rugo_contour_check(thin, 4, 0, NULL, NULL), RUGO_ERR_ZERO_AREA);
    thin[1].y = 1e-3;
    thin[3].y = -1e-3;
    ck_assert_int_eq(rugo_contour_check(thin, 4, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL), RUGO_OK);
}
END_TEST

/* Whether segment j passes within tol of p: dense samples, then golden section at the best. */
static int segment_near(rugo_contour c, int j, rugo_vec2 p, double tol) {
    int m = 2000, bi = 0;
    double best = HUGE_VAL;
    for (int i = 0; i <= m; ++i) {
        double d = v2_dist(rugo_contour_point(c, j, (double)i / m), p);
        if (d < best) best = d, bi = i;
    }
    double lo = fmax(0.0, (bi - 1.0) / m), hi = fmin(1.0, (bi + 1.0) / m);
    for (int it = 0; it < 100; ++it) {
        double a = lo + (hi - lo) * 0.381966011250105, b = hi - (hi - lo) * 0.381966011250105;
        if (v2_dist(rugo_contour_point(c, j, a), p) < v2_dist(rugo_contour_point(c, j, b), p))
            hi = b;
        else
            lo = a;
    }
    best = fmin(best, v2_dist(rugo_contour_point(c, j, 0.5 * (lo + hi)), p));
    return best <= tol;
}

START_TEST(check_figure_eight) {
    rugo_vec2 pts[16];
    for (int k = 0; k < 16; ++k) {
        double th = 2 * PI * k / 16;
        /* a lemniscate, one lobe enlarged so that the signed area is not zero; crosses itself at the
         * origin */
        double sc = sin(th) > 0 ? 1.5 : 1.0;
        pts[k] = rugo_v2(2 * sc * sin(th), sc * sin(2 * th));
    }
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_contour_check(pts, 16, RUGO_CHECK_ALL, &pr, NULL), RUGO_ERR_SELF_INTERSECTING);
    ck_assert(pr.segment_a >= 0 && pr.segment_a < pr.segment_b && pr.segment_b < 16);
    ck_assert_near(v2_dist(pr.where, rugo_v2(0, 0)), 0.0, 1e-3); /* near the origin, not exactly */
    rugo_contour c = contour_of(pts, 16);
    ck_assert(segment_near(c, pr.segment_a, pr.where, 1e-8));
    ck_assert(segment_near(c, pr.segment_b, pr.where, 1e-8));
    /* Without the flag the check does not look for crossings. */
    ck_assert_int_eq(rugo_contour_check(pts, 16, 0, &pr, NULL), RUGO_OK);
}
END_TEST

START_TEST(check_loop_inside_segment) {
    /* Segment 1's Bezier points (0,0), (4,3), (-4,3), (1,0) make a loop; the B-spline points
     * follow from b1 = (2q1 + q2)/3, b2 = (q1 + 2q2)/3, b0 = (q0 + 4q1 + q2)/6, b3 = (q1 + 4q2 + q3)/6. */
    rugo_vec2 pts[6] = {{-36, -15}, {12, 3}, {-12, 3}, {42, -15}, {42, -40}, {-36, -40}};
    rugo_vec2 bz[4];
    rugo_contour_bezier(contour_of(pts, 6), 1, bz);
    ck_assert_near(bz[1].x, 4.0, 1e-14);
    ck_assert_near(bz[3].x, 1.0, 1e-14);
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_contour_check(pts, 6, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL),
                     RUGO_ERR_SELF_INTERSECTING);
    ck_assert_int_eq(pr.segment_a, 1);
    ck_assert_int_eq(pr.segment_b, 1);
    ck_assert(segment_near(contour_of(pts, 6), 1, pr.where, 1e-8));
}
END_TEST

START_TEST(check_touching_and_near) {
    /* An hourglass whose waist closes to a point: the two sides touch tangentially at (0, 0)
     * ((-1,1) + 4 (0,-1/2) + (1,1))/6 = 0, and symmetrically below. */
    rugo_vec2 hg[6] = {{1, 1}, {0, -0.5}, {-1, 1}, {-1, -1}, {0, 0.5}, {1, -1}};
    rugo_contour_problem pr;
    if (rugo_contour_signed_area(contour_of(hg, 6)) < 0) rugo_contour_orient_ccw(hg, 6);
    ck_assert_int_eq(rugo_contour_check(hg, 6, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL),
                     RUGO_ERR_SELF_INTERSECTING);
    ck_assert_near(v2_dist(pr.where, rugo_v2(0, 0)), 0.0, 1e-4); /* a tangency: located to ~sqrt(tol) */
    ck_assert(pr.segment_a != pr.segment_b);
    /* Open the waist a little (gap 4 * 0.01 / 6 ~ 6.7e-3 between the sides): valid. */
    rugo_vec2 ok[6] = {{1, 1}, {0, -0.49}, {-1, 1}, {-1, -1}, {0, 0.49}, {1, -1}};
    ck_assert_int_eq(rugo_contour_check(ok, 6, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL), RUGO_OK);
    /* Gap of 1e-7 of the size: still valid (far above the 5e-10 touching tolerance). */
    double d = 0.5 - 1.5e-7 / 4;
    rugo_vec2 ok2[6] = {{1, 1}, {0, -d}, {-1, 1}, {-1, -1}, {0, d}, {1, -1}};
    ck_assert_int_eq(rugo_contour_check(ok2, 6, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL), RUGO_OK);
    /* Crossing past the waist: self-intersecting. */
    rugo_vec2 bad[6] = {{1, 1}, {0, -0.6}, {-1, 1}, {-1, -1}, {0, 0.6}, {1, -1}};
    ck_assert_int_eq(rugo_contour_check(bad, 6, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL),
                     RUGO_ERR_SELF_INTERSECTING);
    /* The degenerate-segment contour (with a segment shrunk to a point) is valid. */
    ck_assert_int_eq(rugo_contour_check(DEG_POINTS, DEG_N, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL), RUGO_OK);
    /* A spike: the curve goes out and retraces the same line (c_{j-1}, c_j, c_{j+1} collinear
     * with c_j at the tip and three-fold): overlapping, hence self-intersecting. */
    rugo_vec2 spike[9] = {{-3, -2}, {0, 0}, {2, 0}, {4, 0}, {4, 0}, {4, 0}, {2, 0}, {0, 0}, {-3, 2}};
    ck_assert_int_eq(rugo_contour_check(spike, 9, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL),
                     RUGO_ERR_SELF_INTERSECTING);
    ck_assert(segment_near(contour_of(spike, 9), pr.segment_a, pr.where, 1e-6));
    ck_assert(segment_near(contour_of(spike, 9), pr.segment_b, pr.where, 1e-6));
    /* A sharp but open corner (three-fold point) is fine. */
    rugo_vec2 corner[7] = {{0, 0}, {4, 0}, {4, 0}, {4, 0}, {2, 2}, {0, 3}, {-1, 1}};
    ck_assert_int_eq(rugo_contour_check(corner, 7, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL), RUGO_OK);
}
END_TEST

START_TEST(check_random_stars_fast) {
    rugo_vec2* pts = vec_alloc(65536);
    for (int s = 0; s < 20; ++s) {
        int n = 4 << (s % 11); /* 4 .. 4096 */
        star(1300 + s, n, pts, NULL, NULL);
        rugo_contour_problem pr;
        ck_assert_int_eq(rugo_contour_check(pts, n, RUGO_CHECK_ALL, &pr, NULL), RUGO_OK);
        ck_assert_int_eq(pr.segment_a, -1);
    }
    /* n = 4096 well under 50 ms in an optimised build (generous bound here for sanitizers) and a
     * large count still fast. */
    star(1400, 4096, pts, NULL, NULL);
    clock_t t0 = clock();
    ck_assert_int_eq(rugo_contour_check(pts, 4096, RUGO_CHECK_ALL, NULL, NULL), RUGO_OK);
    double ms = 1000.0 * (double)(clock() - t0) / CLOCKS_PER_SEC;
    ck_assert_msg(ms < 1000.0, "check of 4096 points took %.1f ms", ms);
    star(1401, 65536, pts, NULL, NULL);
    ck_assert_int_eq(rugo_contour_check(pts, 65536, RUGO_CHECK_ALL, NULL, NULL), RUGO_OK);
    /* Crossings among many points: swap two far apart control points. */
    star(1402, 1024, pts, NULL, NULL);
    rugo_vec2 tmp = pts[100];
    pts[100] = pts[600];
    pts[600] = tmp;
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_contour_check(pts, 1024, RUGO_CHECK_ALL, &pr, NULL), RUGO_ERR_SELF_INTERSECTING);
    ck_assert(pr.segment_a <= pr.segment_b);
    free(pts);
}
END_TEST

/* Brute force: proper crossings between non-consecutive chords of a dense polyline. */
static int polyline_crosses(rugo_contour c, int m) {
    int e = c.count * m, found = 0;
    rugo_vec2* v = dense_polygon(c, m);
    for (int i = 0; i < e && !found; ++i)
        for (int k = i + 2; k < e && !found; ++k) {
            if (i == 0 && k == e - 1) continue;
            rugo_vec2 a0 = v[i], a1 = v[(i + 1) % e], b0 = v[k], b1 = v[(k + 1) % e];
            rugo_vec2 ea = rugo_v2_sub(a1, a0), eb = rugo_v2_sub(b1, b0);
            double d0 = rugo_v2_cross(ea, rugo_v2_sub(b0, a0)), d1 = rugo_v2_cross(ea, rugo_v2_sub(b1, a0));
            double d2 = rugo_v2_cross(eb, rugo_v2_sub(a0, b0)), d3 = rugo_v2_cross(eb, rugo_v2_sub(a1, b0));
            found = ((d0 > 0 && d1 < 0) || (d0 < 0 && d1 > 0)) && ((d2 > 0 && d3 < 0) || (d2 < 0 && d3 > 0));
        }
    free(v);
    return found;
}

START_TEST(check_self_intersection_vs_polyline) {
    /* Random control polygons (mostly crossing) and very bumpy stars (some with loops): the check
     * agrees with a brute-force test of a 150-chords-per-segment polyline. */
    test_rng rng = test_rng_seed(2024);
    int crossing = 0, simple = 0;
    for (int trial = 0; trial < 160; ++trial) {
        int n = 4 + (int)(test_rng_next(&rng) % 9);
        rugo_vec2 p[16];
        if (trial % 2 == 0)
            test_random_points(&rng, n, 1.0, p);
        else
            test_random_star(&rng, n, rugo_v2(0, 0), 1.0, test_rng_uniform(&rng, 0.8, 3.0), p);
        rugo_contour_problem pr;
        rugo_status st = rugo_contour_check(p, n, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL);
        if (st == RUGO_ERR_ZERO_AREA) continue;
        int brute = polyline_crosses(contour_of(p, n), 150);
        ck_assert_msg((st == RUGO_ERR_SELF_INTERSECTING) == brute, "trial %d: status %d, polyline %d", trial,
                      st, brute);
        if (brute) {
            ++crossing;
            ck_assert(segment_near(contour_of(p, n), pr.segment_a, pr.where, 1e-8));
            ck_assert(segment_near(contour_of(p, n), pr.segment_b, pr.where, 1e-8));
        } else {
            ++simple;
        }
    }
    ck_assert_int_gt(crossing, 30);
    ck_assert_int_gt(simple, 30);
}
END_TEST

START_TEST(deterministic_outputs) {
    rugo_vec2 pts[32];
    star(1500, 32, pts, NULL, NULL);
    rugo_contour c = contour_of(pts, 32);
    rugo_mass_properties a = rugo_contour_mass_properties(c), b = rugo_contour_mass_properties(c);
    ck_assert(memcmp(&a, &b, sizeof a) == 0);
    rugo_curve_point p = rugo_contour_closest_point(c, rugo_v2(0.1, 0.2)),
                     q = rugo_contour_closest_point(c, rugo_v2(0.1, 0.2));
    ck_assert(p.segment == q.segment && p.t == q.t && p.distance == q.distance);
}
END_TEST

/* Review findings: an equal-lobe figure eight has zero net area but is a crossing outline; huge
 * coordinates overflow the area (NOT_FINITE, not "zero area"); NaN parameters and empty contours
 * never reach an int cast or a division by zero; huge segment indices wrap without overflow. */
START_TEST(check_review_cases) {
    const rugo_vec2 eight[4] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_contour_check(eight, 4, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL),
                     RUGO_ERR_SELF_INTERSECTING);
    ck_assert_int_ge(pr.segment_a, 0);
    ck_assert_int_eq(rugo_contour_check(eight, 4, 0, NULL, NULL),
                     RUGO_ERR_ZERO_AREA); /* no crossing test asked */
    const rugo_vec2 flat[4] = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
    ck_assert_int_eq(rugo_contour_check(flat, 4, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL),
                     RUGO_ERR_ZERO_AREA);
    const rugo_vec2 huge[4] = {{1e200, 0}, {0, 1e200}, {-1e200, 0}, {0, -1e200}};
    ck_assert_int_eq(rugo_contour_check(huge, 4, RUGO_CHECK_ALL, NULL, NULL), RUGO_ERR_NOT_FINITE);
    const rugo_vec2 sq[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_contour c = contour_of((rugo_vec2*)sq, 4);
    rugo_vec2 p = rugo_contour_point_at(c, NAN);
    ck_assert(isnan(p.x) && isnan(p.y));
    p = rugo_contour_point_at(c, INFINITY);
    ck_assert(isnan(p.x));
    rugo_vec2 a = rugo_contour_point(c, INT_MAX, 0.25), b = rugo_contour_point(c, INT_MAX % 4, 0.25);
    ck_assert(a.x == b.x && a.y == b.y);
    a = rugo_contour_point(c, INT_MIN, 0.5);
    b = rugo_contour_point(c, rugo__wrap(INT_MIN, 4), 0.5);
    ck_assert(a.x == b.x && a.y == b.y);
    rugo_contour empty = {NULL, 0};
    p = rugo_contour_point(empty, 3, 0.5);
    ck_assert(p.x == 0.0 && p.y == 0.0);
    ck_assert(rugo_contour_d1(empty, 0, 0.5).x == 0.0);
}
END_TEST

int main(void) {
    Suite* s = suite_create("contour");
    struct {
        const char* name;
        const TTest* tests[12];
    } groups[] = {
        {"poly", {poly_simple_roots, poly_degenerate, poly_random, poly_scaled}},
        {"evaluation",
         {basis_partition_of_unity, evaluation_continuity_and_forms, tangent_normal,
          degenerate_segments_everywhere, orientation_reversal_mapping, deterministic_outputs}},
        {"arc_length",
         {arc_length_quadrature, arc_length_straight_and_cusp, arc_length_arguments,
          arc_length_to_round_off}},
        {"mass",
         {mass_properties_vs_polygon, mass_properties_exact, mass_properties_triangle,
          mass_properties_invariance}},
        {"queries",
         {bounds_tight, closest_point_vs_brute_force, contains_vs_polygon, contains_tangent_and_joint_rays,
          ray_cast_vs_brute_force, ray_cast_special}},
        {"check",
         {check_null_and_counts, check_power_of_two, check_not_finite, check_zero_area, check_figure_eight,
          check_loop_inside_segment, check_touching_and_near, check_random_stars_fast,
          check_self_intersection_vs_polyline, check_review_cases}},
    };
    for (size_t g = 0; g < sizeof groups / sizeof groups[0]; ++g) {
        TCase* tc = tcase_create(groups[g].name);
        tcase_set_timeout(tc, 120);
        for (int i = 0; i < 12 && groups[g].tests[i]; ++i)
            tcase_add_test(tc, groups[g].tests[i]);
        suite_add_tcase(s, tc);
    }
    return test_run_suite(s);
}
