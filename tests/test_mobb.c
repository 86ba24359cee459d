/* MOBB suite: oriented-box primitives (covariance axes, separating axes, transform, enclose), leaf
 * boxes of every degenerate kind of segment, and the MOBBtree's invariant for both box methods on
 * smooth and rough shapes (SPEC 5, 7; thesis chapters 3-4). */
#include "core/internal.h"
#include "test_util.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static void* xmalloc(size_t n) {
    void* p = malloc(n);
    ck_assert_ptr_nonnull(p);
    return p;
}

static rugo_obb make_box(double cx, double cy, double angle, double h0, double h1) {
    rugo_obb b;
    b.center = rugo_v2(cx, cy);
    b.axis[0] = rugo_v2(cos(angle), sin(angle));
    b.axis[1] = rugo_v2_perp(b.axis[0]);
    b.half[0] = h0;
    b.half[1] = h1;
    return b;
}

static rugo_obb random_box(test_rng* r, double spread, double size) {
    double h0 = test_rng_uniform(r, 0.0, size), h1 = test_rng_uniform(r, 0.0, size);
    uint64_t kind = test_rng_next(r) % 10;
    if (kind == 0) h0 = 0.0; /* a segment */
    if (kind == 1) h1 = 0.0;
    if (kind == 2) h0 = h1 = 0.0; /* a point */
    return make_box(test_rng_uniform(r, -spread, spread), test_rng_uniform(r, -spread, spread),
                    test_rng_uniform(r, 0.0, 2.0 * PI), h0, h1);
}

static void check_frame(const rugo_vec2 axis[2]) {
    ck_assert_near(rugo__v2_length(axis[0]), 1.0, 1e-15);
    ck_assert(axis[1].x == -axis[0].y && axis[1].y == axis[0].x); /* axis[1] = perp(axis[0]) */
}

/* |sin| of the angle between two directions (0 when parallel or antiparallel). */
static double direction_error(rugo_vec2 a, rugo_vec2 b) {
    return fabs(rugo_v2_cross(a, b)) / (rugo__v2_length(a) * rugo__v2_length(b));
}

/* ---- covariance axes (SPEC 5.1) ------------------------------------------------------------------ */

START_TEST(test_covariance_axes_known) {
    rugo_vec2 axis[2];
    /* An elongated point set rotated by a known angle: the major axis follows it. */
    test_rng r = test_rng_seed(11);
    for (int trial = 0; trial < 200; ++trial) {
        double angle = test_rng_uniform(&r, 0.0, PI);
        rugo_vec2 u = rugo_v2(cos(angle), sin(angle)), w = rugo_v2_perp(u);
        rugo_vec2 o = rugo_v2(test_rng_uniform(&r, -1e3, 1e3), test_rng_uniform(&r, -1e3, 1e3));
        /* A symmetric cross of points: exact covariance diag(2 * 9 + ..., ...) in the (u, w) frame. */
        const double s[4][2] = {{3, 0}, {-3, 0}, {0, 1}, {0, -1}};
        rugo_vec2 p[4];
        for (int i = 0; i < 4; ++i)
            p[i] = rugo_v2_add(o, rugo_v2_add(rugo_v2_scale(s[i][0], u), rugo_v2_scale(s[i][1], w)));
        rugo_covariance_axes(p, 4, axis);
        check_frame(axis);
        ck_assert_msg(direction_error(axis[0], u) < 1e-12, "angle %g: axis (%g, %g)", angle, axis[0].x,
                      axis[0].y);
    }
    /* Points on a line, at any angle. */
    for (int trial = 0; trial < 100; ++trial) {
        double angle = test_rng_uniform(&r, 0.0, 2.0 * PI);
        rugo_vec2 u = rugo_v2(cos(angle), sin(angle));
        rugo_vec2 p[5];
        for (int i = 0; i < 5; ++i)
            p[i] = rugo_v2_add(rugo_v2(1e5, -2e5), rugo_v2_scale(test_rng_uniform(&r, -4.0, 4.0), u));
        rugo_covariance_axes(p, 5, axis);
        check_frame(axis);
        ck_assert(direction_error(axis[0], u) < 1e-9);
    }
}
END_TEST

START_TEST(test_covariance_axes_degenerate) {
    rugo_vec2 axis[2];
    /* b = 0 (axis-aligned data), whichever diagonal entry is larger: the coordinate axes. */
    const rugo_vec2 wide[4] = {{2, 0}, {-2, 0}, {0, 1}, {0, -1}};
    const rugo_vec2 tall[4] = {{1, 0}, {-1, 0}, {0, 2}, {0, -2}};
    const rugo_vec2 square[4] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    const rugo_vec2* sets[3] = {wide, tall, square};
    for (int s = 0; s < 3; ++s) {
        rugo_covariance_axes(sets[s], 4, axis);
        ck_assert(axis[0].x == 1.0 && axis[0].y == 0.0 && axis[1].x == 0.0 && axis[1].y == 1.0);
    }
    /* Isotropic with round-off (a rotated regular octagon): the coordinate axes. */
    rugo_vec2 oct[8];
    for (int i = 0; i < 8; ++i)
        oct[i] = rugo_v2(5.0 + cos(0.3 + i * PI / 4), -7.0 + sin(0.3 + i * PI / 4));
    rugo_covariance_axes(oct, 8, axis);
    ck_assert(axis[0].x == 1.0 && axis[0].y == 0.0);
    /* One point, coincident points: no spread at all. */
    const rugo_vec2 one[1] = {{3, 4}};
    rugo_covariance_axes(one, 1, axis);
    ck_assert(axis[0].x == 1.0 && axis[0].y == 0.0 && axis[1].y == 1.0);
    const rugo_vec2 same[3] = {{3, 4}, {3, 4}, {3, 4}};
    rugo_covariance_axes(same, 3, axis);
    ck_assert(axis[0].x == 1.0 && axis[0].y == 0.0);
    /* Bad input does not crash and still gives a frame. */
    rugo_covariance_axes(NULL, 3, axis);
    ck_assert(axis[0].x == 1.0);
    rugo_covariance_axes(one, 0, axis);
    ck_assert(axis[0].x == 1.0);
    rugo_covariance_axes(one, 1, NULL);
}
END_TEST

/* ---- separating axes against a brute-force polygon test --------------------------------------- */

static double orient(rugo_vec2 a, rugo_vec2 b, rugo_vec2 c) {
    return rugo_v2_cross(rugo_v2_sub(b, a), rugo_v2_sub(c, a));
}

static double point_segment_distance(rugo_vec2 p, rugo_vec2 a, rugo_vec2 b) {
    rugo_vec2 d = rugo_v2_sub(b, a);
    double dd = rugo_v2_dot(d, d);
    double t = dd > 0.0 ? rugo_v2_dot(rugo_v2_sub(p, a), d) / dd : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    return rugo__v2_length(rugo_v2_sub(p, rugo_v2_add(a, rugo_v2_scale(t, d))));
}

static double segment_distance(rugo_vec2 a, rugo_vec2 b, rugo_vec2 c, rugo_vec2 d) {
    double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 0.0;
    double m = point_segment_distance(a, c, d);
    m = fmin(m, point_segment_distance(b, c, d));
    m = fmin(m, point_segment_distance(c, a, b));
    return fmin(m, point_segment_distance(d, a, b));
}

/* p strictly inside the convex counter-clockwise quad q (a degenerate quad contains nothing). */
static int inside_quad(const rugo_vec2 q[4], rugo_vec2 p) {
    for (int i = 0; i < 4; ++i)
        if (!(orient(q[i], q[(i + 1) % 4], p) > 0.0)) return 0;
    return 1;
}

/* Distance between two boxes as closed polygons (0 if they intersect), by brute force. */
static double box_distance(const rugo_obb* a, const rugo_obb* b) {
    rugo_vec2 pa[4], pb[4];
    rugo_obb_corners(a, pa);
    rugo_obb_corners(b, pb);
    for (int i = 0; i < 4; ++i)
        if (inside_quad(pa, pb[i]) || inside_quad(pb, pa[i])) return 0.0;
    double m = INFINITY;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k)
            m = fmin(m, segment_distance(pa[i], pa[(i + 1) % 4], pb[k], pb[(k + 1) % 4]));
    return m;
}

START_TEST(test_sat_brute_force) {
    test_rng r = test_rng_seed(2024);
    int apart = 0, overlapping = 0, ambiguous = 0;
    for (int trial = 0; trial < 40000; ++trial) {
        rugo_obb a = random_box(&r, 2.0, 1.0), b = random_box(&r, 2.0, 1.0);
        double d = box_distance(&a, &b);
        int o = rugo_obb_overlap(&a, &b);
        ck_assert_int_eq(o, rugo_obb_overlap(&b, &a));
        if (d > 1e-9) {
            ck_assert_msg(o == 0, "trial %d: distance %g but overlap reported", trial, d);
            ++apart;
        } else if (d == 0.0) {
            ck_assert_msg(o == 1, "trial %d: intersecting boxes reported apart", trial);
            ++overlapping;
        } else {
            ++ambiguous;
        }
    }
    ck_assert_int_gt(apart, 5000);
    ck_assert_int_gt(overlapping, 5000);
    ck_assert_int_lt(ambiguous, 10);
}
END_TEST

START_TEST(test_sat_touching_nested_degenerate) {
    test_rng r = test_rng_seed(77);
    for (int trial = 0; trial < 2000; ++trial) {
        double angle = test_rng_uniform(&r, 0.0, 2.0 * PI);
        double cx = test_rng_uniform(&r, -1e3, 1e3), cy = test_rng_uniform(&r, -1e3, 1e3);
        double h0 = test_rng_uniform(&r, 0.1, 3.0), h1 = test_rng_uniform(&r, 0.1, 3.0);
        rugo_obb a = make_box(cx, cy, angle, h0, h1);
        /* Face to face, same axes: touching along a side. */
        double g0 = test_rng_uniform(&r, 0.1, 3.0), g1 = test_rng_uniform(&r, 0.1, 3.0);
        double slide = test_rng_uniform(&r, -0.9, 0.9) * (h1 + g1);
        rugo_vec2 c = rugo_v2_add(
            a.center, rugo_v2_add(rugo_v2_scale(h0 + g0, a.axis[0]), rugo_v2_scale(slide, a.axis[1])));
        rugo_obb b = make_box(c.x, c.y, angle, g0, g1);
        ck_assert_msg(rugo_obb_overlap(&a, &b) && rugo_obb_overlap(&b, &a), "face touching, trial %d", trial);
        /* Pulled apart by a visible gap: separated. */
        rugo_obb b2 = b;
        b2.center = rugo_v2_add(b.center, rugo_v2_scale(1e-9 * (1.0 + fabs(cx) + fabs(cy)), a.axis[0]));
        ck_assert(!rugo_obb_overlap(&a, &b2));
        /* Corner on a face: a box turned by 45 degrees whose corner touches a's side. */
        double diag = g0 * sqrt(2.0);
        c = rugo_v2_add(a.center,
                        rugo_v2_add(rugo_v2_scale(h1 + diag, a.axis[1]), rugo_v2_scale(0.5 * h0, a.axis[0])));
        rugo_obb corner = make_box(c.x, c.y, angle + PI / 4, g0, g0);
        ck_assert_msg(rugo_obb_overlap(&a, &corner), "corner touching, trial %d", trial);
        corner.center = rugo_v2_add(corner.center, rugo_v2_scale(1e-6, a.axis[1]));
        ck_assert(!rugo_obb_overlap(&a, &corner));
        /* Nested either way, any rotation; identical boxes. */
        rugo_obb inner = make_box(cx + 0.1 * h0 * a.axis[0].x, cy + 0.1 * h0 * a.axis[0].y,
                                  test_rng_uniform(&r, 0.0, PI), 0.3 * fmin(h0, h1), 0.2 * fmin(h0, h1));
        ck_assert(rugo_obb_overlap(&a, &inner) && rugo_obb_overlap(&inner, &a));
        ck_assert(rugo_obb_overlap(&a, &a));
    }
    /* Degenerate boxes: points and segments. */
    rugo_obb p1 = make_box(0.5, 0.5, 0.3, 0.0, 0.0), p2 = make_box(0.5, 0.5, 1.1, 0.0, 0.0);
    rugo_obb p3 = make_box(0.6, 0.5, 0.0, 0.0, 0.0);
    ck_assert(rugo_obb_overlap(&p1, &p2));
    ck_assert(!rugo_obb_overlap(&p1, &p3));
    rugo_obb unit = make_box(0, 0, 0, 1, 1);
    ck_assert(rugo_obb_overlap(&unit, &p1));
    rugo_obb on_side = make_box(1.0, 0.25, 0.0, 0.0, 0.0);
    ck_assert(rugo_obb_overlap(&unit, &on_side));
    rugo_obb outside = make_box(1.0 + 1e-9, 0.25, 0.0, 0.0, 0.0);
    ck_assert(!rugo_obb_overlap(&unit, &outside));
    rugo_obb sx = make_box(0, 0, 0.0, 2.0, 0.0), sy = make_box(0, 0, PI / 2, 2.0, 0.0); /* an X */
    ck_assert(rugo_obb_overlap(&sx, &sy));
    rugo_obb par = make_box(0, 1e-6, 0.0, 2.0, 0.0); /* parallel, offset */
    ck_assert(!rugo_obb_overlap(&sx, &par));
    rugo_obb collinear = make_box(4.0, 0.0, PI, 2.0, 0.0); /* end to end, the ends touch */
    ck_assert(rugo_obb_overlap(&sx, &collinear));
    rugo_obb tee = make_box(0.0, 2.5, PI / 2, 2.0, 0.0); /* a T whose stem stops short */
    ck_assert(!rugo_obb_overlap(&sx, &tee));
    tee.center.y = 2.0;
    ck_assert(rugo_obb_overlap(&sx, &tee));
    ck_assert(!rugo_obb_overlap(NULL, &sx));
}
END_TEST

START_TEST(test_transform_enclose_contains) {
    test_rng r = test_rng_seed(5);
    for (int trial = 0; trial < 2000; ++trial) {
        rugo_obb a = random_box(&r, 10.0, 3.0), b = random_box(&r, 10.0, 3.0);
        rugo_transform t = rugo_make_transform(
            test_rng_uniform(&r, -100, 100), test_rng_uniform(&r, -100, 100), test_rng_uniform(&r, -PI, PI));
        /* transform: corners of the moved box = moved corners; overlap and containment unchanged. */
        rugo_obb ta = rugo_obb_transform(t, &a), tb = rugo_obb_transform(t, &b);
        check_frame(ta.axis);
        rugo_vec2 ca[4], cta[4];
        rugo_obb_corners(&a, ca);
        rugo_obb_corners(&ta, cta);
        for (int i = 0; i < 4; ++i) {
            rugo_vec2 m = rugo_transform_point(t, ca[i]);
            ck_assert_near(m.x, cta[i].x, 1e-12);
            ck_assert_near(m.y, cta[i].y, 1e-12);
        }
        double d = box_distance(&a, &b);
        if (d > 1e-9 || d == 0.0) ck_assert_int_eq(rugo_obb_overlap(&a, &b), rugo_obb_overlap(&ta, &tb));
        ck_assert_near(rugo_obb_area(&ta), rugo_obb_area(&a), 1e-12);
        /* corners counter-clockwise, area 4 h0 h1 */
        double shoelace = 0.0;
        for (int i = 0; i < 4; ++i)
            shoelace += 0.5 * rugo_v2_cross(ca[i], ca[(i + 1) % 4]);
        ck_assert_near(shoelace, rugo_obb_area(&a), 1e-9);
        ck_assert_near(rugo_obb_area(&a), 4.0 * a.half[0] * a.half[1], 0.0);
        /* contains: the corners with a little slack, not points beyond a side */
        for (int i = 0; i < 4; ++i)
            ck_assert(rugo_obb_contains(&a, ca[i], 1e-12));
        rugo_vec2 out = rugo_v2_add(a.center, rugo_v2_scale(a.half[0] + 1e-6, a.axis[0]));
        ck_assert(!rugo_obb_contains(&a, out, 0.0));
        ck_assert(rugo_obb_contains(&a, out, 2e-6));
        ck_assert(!rugo_obb_contains(&a, a.center, -1.0 - fmax(a.half[0], a.half[1])));
        /* enclose: a's axes, b's corners inside, each side touched by a corner of b */
        rugo_obb e = rugo_obb_enclose(a, &b);
        ck_assert(memcmp(e.axis, a.axis, sizeof e.axis) == 0);
        rugo_vec2 cb[4];
        rugo_obb_corners(&b, cb);
        for (int i = 0; i < 4; ++i)
            ck_assert(rugo_obb_contains(&e, cb[i], 1e-12));
        for (int ax = 0; ax < 2; ++ax)
            for (int side = -1; side <= 1; side += 2) {
                double best = -INFINITY;
                for (int i = 0; i < 4; ++i)
                    best = fmax(best, side * rugo_v2_dot(rugo_v2_sub(cb[i], e.center), e.axis[ax]));
                ck_assert_near(best, e.half[ax], 1e-12);
            }
        /* enclosing a box in its own axes gives it back */
        rugo_obb same = rugo_obb_enclose(b, &b);
        ck_assert_near(same.center.x, b.center.x, 1e-12);
        ck_assert_near(same.center.y, b.center.y, 1e-12);
        ck_assert_near(same.half[0], b.half[0], 1e-12);
        ck_assert_near(same.half[1], b.half[1], 1e-12);
    }
}
END_TEST

/* ---- leaf boxes (SPEC 5.2) ---------------------------------------------------------------------- */

static double projection(rugo_contour c, int seg, double t, rugo_vec2 origin, rugo_vec2 e) {
    return rugo_v2_dot(rugo_v2_sub(rugo_contour_point(c, seg, t), origin), e);
}

/* max over t in [0, 1] of the projection: dense samples, then golden-section refinement around the
 * best sample (an independent check of the roots the library solves for). */
static double max_projection(rugo_contour c, int seg, rugo_vec2 origin, rugo_vec2 e) {
    enum { S = 2000 };
    int best = 0;
    double bv = -INFINITY;
    for (int i = 0; i <= S; ++i) {
        double v = projection(c, seg, (double)i / S, origin, e);
        if (v > bv) {
            bv = v;
            best = i;
        }
    }
    double lo = fmax(0.0, (best - 1.0) / S), hi = fmin(1.0, (best + 1.0) / S);
    const double g = 0.6180339887498949;
    for (int it = 0; it < 80; ++it) {
        double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        if (projection(c, seg, x1, origin, e) > projection(c, seg, x2, origin, e))
            hi = x2;
        else
            lo = x1;
    }
    double v = projection(c, seg, 0.5 * (lo + hi), origin, e);
    return fmax(v, bv);
}

/* Contains dense samples of the segment thickened by band (as discs), and every side is touched. */
static void check_leaf(rugo_contour c, int seg, double band, double min_length, double tol) {
    rugo_obb b = rugo_segment_box(c, seg, band, min_length);
    check_frame(b.axis);
    ck_assert(b.half[0] >= band && b.half[1] >= band);
    for (int i = 0; i <= 400; ++i) {
        rugo_vec2 p = rugo_contour_point(c, seg, i / 400.0);
        ck_assert_msg(rugo_obb_contains(&b, p, tol - band), "segment %d, t = %g outside its box", seg,
                      i / 400.0);
    }
    for (int ax = 0; ax < 2; ++ax)
        for (int side = -1; side <= 1; side += 2) {
            rugo_vec2 e = rugo_v2_scale((double)side, b.axis[ax]);
            double m = max_projection(c, seg, b.center, e);
            ck_assert_msg(fabs(m - (b.half[ax] - band)) <= tol,
                          "axis %d side %d: reach %.17g, half - band %.17g", ax, side, m, b.half[ax] - band);
        }
}

/* A 4-point contour whose segment 1 uses exactly q[0..3] (c_{j-1} .. c_{j+2}). */
static rugo_contour four(const rugo_vec2 q[4]) {
    rugo_contour c = {q, 4};
    return c;
}

START_TEST(test_leaf_box_kinds) {
    const double bands[3] = {0.0, 0.3, 2.5};
    for (int bi = 0; bi < 3; ++bi) {
        double band = bands[bi];
        /* cubic */
        const rugo_vec2 cubic[4] = {{0, 0}, {1, 2}, {3, -1}, {4, 1.5}};
        check_leaf(four(cubic), 1, band, 0.0, 1e-12);
        /* parabolic: v = 0 (control points on a quadratic sequence), so f'·e is linear for every axis */
        const rugo_vec2 para[4] = {{-1.5, 0.75}, {-0.5, -0.25}, {0.5, 0.75}, {1.5, 3.75}};
        rugo_vec2 v, w, r;
        rugo_contour_derivative_coefficients(four(para), 1, &v, &w, &r);
        ck_assert(v.x == 0.0 && v.y == 0.0);
        check_leaf(four(para), 1, band, 0.0, 1e-12);
        /* the linear case with v != 0: an odd x(t), even y(t) segment; its axes are the coordinate axes
         * and v·e_y = 0 exactly while w·e_y != 0 (the case the thesis' text gets wrong) */
        rugo_vec2 sym[4];
        for (int i = 0; i < 4; ++i) {
            double s = i - 1.5;
            sym[i] = rugo_v2(s + 0.3 * s * s * s, s * s);
        }
        rugo_contour_derivative_coefficients(four(sym), 1, &v, &w, &r);
        rugo_obb b = rugo_segment_box(four(sym), 1, band, 0.0);
        ck_assert(b.axis[1].x == 0.0 && b.axis[1].y == 1.0);
        ck_assert(v.x != 0.0 && rugo_v2_dot(v, b.axis[1]) == 0.0 && rugo_v2_dot(w, b.axis[1]) != 0.0);
        check_leaf(four(sym), 1, band, 0.0, 1e-12);
        /* its extreme in y is the interior root t = 1/2, not an end */
        ck_assert_near(b.center.y - b.half[1] + band, rugo_contour_point(four(sym), 1, 0.5).y, 1e-14);
        /* straight, tilted: zero thickness up to round-off */
        const rugo_vec2 line[4] = {{0, 0}, {1, 2}, {1.5, 3}, {4, 8}};
        b = rugo_segment_box(four(line), 1, band, 0.0);
        ck_assert(b.half[1] - band <= 1e-14 * 9.0);
        ck_assert(direction_error(b.axis[0], rugo_v2(1, 2)) < 1e-14);
        check_leaf(four(line), 1, band, 0.0, 1e-12);
        /* straight and axis-aligned: exactly zero thickness */
        const rugo_vec2 flat[4] = {{0, 1}, {1, 1}, {3, 1}, {4, 1}};
        b = rugo_segment_box(four(flat), 1, band, 0.0);
        ck_assert(b.half[1] == band && b.center.y == 1.0);
        check_leaf(four(flat), 1, band, 0.0, 1e-12);
        /* a straight segment that runs back on itself (f' changes sign along the line) */
        const rugo_vec2 back[4] = {{0, 0}, {3, 3}, {1, 1}, {4, 4}};
        check_leaf(four(back), 1, band, 0.0, 1e-12);
        /* point-like: four coincident control points */
        const rugo_vec2 pt[4] = {{2.5, -1.25}, {2.5, -1.25}, {2.5, -1.25}, {2.5, -1.25}};
        b = rugo_segment_box(four(pt), 1, band, 0.0);
        ck_assert(b.center.x == 2.5 && b.center.y == -1.25 && b.half[0] == band && b.half[1] == band);
        ck_assert(b.axis[0].x == 1.0 && b.axis[0].y == 0.0);
        check_leaf(four(pt), 1, band, 0.0, 1e-12);
        /* a cusp (zero speed inside the segment) */
        const rugo_vec2 cusp[4] = {{0, 0}, {2, 1}, {0, 1}, {2, 0}};
        check_leaf(four(cusp), 1, band, 0.0, 1e-12);
    }
}
END_TEST

START_TEST(test_leaf_box_random_and_far) {
    test_rng r = test_rng_seed(99);
    for (int trial = 0; trial < 300; ++trial) {
        rugo_vec2 q[4];
        test_random_points(&r, 4, 5.0, q);
        double band = trial % 3 == 0 ? 0.0 : test_rng_uniform(&r, 0.0, 1.0);
        check_leaf(four(q), 1, band, 0.0, 1e-11);
        /* Far from the origin: the box stays as tight as the curve's own evaluation allows. */
        rugo_vec2 far[4];
        for (int i = 0; i < 4; ++i)
            far[i] = rugo_v2_add(q[i], rugo_v2(1e6, -3e6));
        check_leaf(four(far), 1, band, 0.0, 1e-8);
        rugo_obb a = rugo_segment_box(four(q), 1, band, 0.0), b = rugo_segment_box(four(far), 1, band, 0.0);
        ck_assert(direction_error(a.axis[0], b.axis[0]) < 1e-8);
        ck_assert_near(a.half[0], b.half[0], 1e-8);
        ck_assert_near(a.half[1], b.half[1], 1e-8);
    }
}
END_TEST

START_TEST(test_leaf_box_min_length) {
    /* Arc length <= l_min: axes from the two ends only, so axis[0] follows the chord. */
    const rugo_vec2 q[4] = {{0, 0}, {1, 2}, {3, -1}, {4, 1.5}};
    rugo_contour c = four(q);
    double len = rugo_contour_segment_length(c, 1);
    rugo_obb b = rugo_segment_box(c, 1, 0.0, len);
    rugo_vec2 chord = rugo_v2_sub(rugo_contour_point(c, 1, 1.0), rugo_contour_point(c, 1, 0.0));
    ck_assert(direction_error(b.axis[0], chord) < 1e-14);
    check_leaf(c, 1, 0.1, len, 1e-12);
    rugo_obb five = rugo_segment_box(c, 1, 0.0, 0.999 * len);
    ck_assert(direction_error(five.axis[0], chord) > 1e-3); /* 5 samples: another direction */
    /* bad inputs */
    rugo_contour none = {NULL, 0};
    rugo_obb z = rugo_segment_box(none, 0, 1.0, 0.0);
    ck_assert(z.half[0] == 0.0 && z.axis[0].x == 1.0);
    rugo_obb nb = rugo_segment_box(c, 1, NAN, 0.0);
    ck_assert(isfinite(nb.half[0]) && isfinite(nb.half[1]));
}
END_TEST

/* ---- the tree ------------------------------------------------------------------------------------ */

static rugo_pyramid* make_pyramid(const rugo_vec2* pts, int n, int coarsest) {
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = pts;
    def.count = n;
    def.coarsest_level = coarsest;
    rugo_pyramid* p = NULL;
    rugo_status st = rugo_pyramid_create(&def, &p, NULL);
    ck_assert_msg(st == RUGO_OK, "pyramid: %s", rugo_status_string(st));
    return p;
}

static rugo_tolerances* make_tolerances(const rugo_pyramid* p, double lo, double hi, uint64_t seed) {
    int n = 1 << rugo_pyramid_finest_level(p);
    double* lam = xmalloc((size_t)n * sizeof *lam);
    ck_assert_int_eq(rugo_tolerances_random(lo, hi, seed, n, lam), RUGO_OK);
    rugo_tolerance_def def = rugo_default_tolerance_def();
    def.pyramid = p;
    def.finest = lam;
    def.count = n;
    rugo_tolerances* t = NULL;
    rugo_status st = rugo_tolerances_create(&def, &t);
    ck_assert_msg(st == RUGO_OK, "tolerances: %s", rugo_status_string(st));
    free(lam);
    return t;
}

static rugo_mobb_tree* make_tree(const rugo_pyramid* p, const rugo_tolerances* t, rugo_box_method m,
                                 double min_length) {
    rugo_mobb_tree_def def = rugo_default_mobb_tree_def();
    def.pyramid = p;
    def.tolerances = t;
    def.method = m;
    def.min_length = min_length;
    rugo_mobb_tree* tree = NULL;
    rugo_status st = rugo_mobb_tree_create(&def, &tree);
    ck_assert_msg(st == RUGO_OK, "tree: %s", rugo_status_string(st));
    return tree;
}

static rugo_contour curve_of(const rugo_pyramid* p, int j) {
    rugo_contour c;
    ck_assert_int_eq(rugo_pyramid_level(p, j, &c), RUGO_OK);
    return c;
}

/* Invariant (mobb.h): node (j, k) contains (i) every descendant finest segment thickened by β^J and
 * (ii) its own coarse segment thickened by λ^j_k; parents contain their children; the root contains
 * every coarsest node. Thickening is checked as discs: each sample must lie in the box shrunk by the
 * radius. Returns the number of sample checks. */
static long check_tree_invariant(const rugo_mobb_tree* tree, const rugo_pyramid* p,
                                 const rugo_tolerances* t) {
    enum { S = 32 };
    int J = rugo_pyramid_finest_level(p), J0 = rugo_pyramid_coarsest_level(p);
    ck_assert_int_eq(rugo_mobb_tree_finest_level(tree), J);
    ck_assert_int_eq(rugo_mobb_tree_coarsest_level(tree), J0);
    rugo_contour fine = curve_of(p, J);
    /* The tree pads its boxes for round-off, so computed points need no slack at all. */
    const double slack = 0.0;
    rugo_tolerance_level fl;
    if (t) ck_assert_int_eq(rugo_tolerances_level(t, J, &fl), RUGO_OK);
    long checks = 0;
    for (int j = J0; j <= J; ++j) {
        rugo_contour cj = curve_of(p, j);
        rugo_tolerance_level tl;
        if (t) ck_assert_int_eq(rugo_tolerances_level(t, j, &tl), RUGO_OK);
        int r = J - j;
        for (int k = 0; k < (1 << j); ++k) {
            const rugo_obb* box = rugo_mobb_tree_node(tree, j, k);
            ck_assert_ptr_nonnull(box);
            check_frame(box->axis);
            for (int i = k << r; i < (k + 1) << r; ++i) {
                double beta = t ? fl.bound[i] : 0.0;
                for (int s = 0; s <= S; ++s) {
                    rugo_vec2 q = rugo_contour_point(fine, i, (double)s / S);
                    ck_assert_msg(rugo_obb_contains(box, q, slack - beta),
                                  "level %d node %d: finest segment %d, t = %g", j, k, i, (double)s / S);
                    ++checks;
                }
            }
            double lambda = t ? tl.total[k] : 0.0;
            for (int s = 0; s <= S; ++s) {
                rugo_vec2 q = rugo_contour_point(cj, k, (double)s / S);
                ck_assert_msg(rugo_obb_contains(box, q, slack - lambda),
                              "level %d node %d: own segment, t = %g", j, k, (double)s / S);
                ++checks;
            }
            if (j < J)
                for (int c = 0; c < 2; ++c) {
                    rugo_vec2 corner[4];
                    rugo_obb_corners(rugo_mobb_tree_node(tree, j + 1, 2 * k + c), corner);
                    for (int i = 0; i < 4; ++i)
                        ck_assert(rugo_obb_contains(box, corner[i], slack));
                }
            if (j == J0) {
                rugo_vec2 corner[4];
                rugo_obb_corners(box, corner);
                for (int i = 0; i < 4; ++i)
                    ck_assert(rugo_obb_contains(rugo_mobb_tree_root(tree), corner[i], slack));
            }
        }
    }
    return checks;
}

START_TEST(test_tree_invariant_smooth) {
    test_rng r = test_rng_seed(300);
    const int sizes[3] = {16, 64, 256};
    for (int si = 0; si < 3; ++si) {
        int n = sizes[si];
        rugo_vec2* pts = xmalloc((size_t)n * sizeof *pts);
        test_random_star(&r, n, rugo_v2(40.0, -25.0), 100.0, 0.45, pts);
        rugo_pyramid* p = make_pyramid(pts, n, 2);
        for (int m = 0; m < 2; ++m) {
            rugo_mobb_tree* tree = make_tree(p, NULL, (rugo_box_method)m, 0.0);
            ck_assert_int_eq(rugo_mobb_tree_method(tree), m);
            ck_assert_int_gt(check_tree_invariant(tree, p, NULL), 0);
            rugo_mobb_tree_destroy(tree);
        }
        /* A large l_min (every segment sampled at its ends only) keeps the invariant. */
        rugo_mobb_tree* tree = make_tree(p, NULL, RUGO_BOXES_MULTIRES, 1e9);
        check_tree_invariant(tree, p, NULL);
        rugo_mobb_tree_destroy(tree);
        rugo_pyramid_destroy(p);
        free(pts);
    }
}
END_TEST

START_TEST(test_tree_invariant_rough) {
    test_rng r = test_rng_seed(301);
    const int sizes[2] = {64, 256};
    for (int si = 0; si < 2; ++si) {
        int n = sizes[si];
        rugo_vec2* pts = xmalloc((size_t)n * sizeof *pts);
        /* rough geometry too: a star with small random radial jitter at every control point */
        test_random_star(&r, n, rugo_v2(-500.0, 800.0), 100.0, 0.4, pts);
        for (int i = 0; i < n; ++i) {
            rugo_vec2 d = rugo_v2_sub(pts[i], rugo_v2(-500.0, 800.0));
            double s = 1.0 + test_rng_uniform(&r, -0.004, 0.004) * 256.0 / n;
            pts[i] = rugo_v2_add(rugo_v2(-500.0, 800.0), rugo_v2_scale(s, d));
        }
        for (int coarsest = 2; coarsest <= 4; coarsest += 2) {
            rugo_pyramid* p = make_pyramid(pts, n, coarsest);
            rugo_tolerances* t = make_tolerances(p, 0.2, 3.0, 77u + (uint64_t)n);
            for (int m = 0; m < 2; ++m) {
                rugo_mobb_tree* tree = make_tree(p, t, (rugo_box_method)m, 0.0);
                check_tree_invariant(tree, p, t);
                /* leaves are exactly the basic boxes thickened by β^J (β >= λ at the finest level) */
                rugo_tolerance_level fl;
                ck_assert_int_eq(rugo_tolerances_level(t, rugo_pyramid_finest_level(p), &fl), RUGO_OK);
                rugo_contour fine = curve_of(p, fl.level);
                for (int k = 0; k < n; ++k) {
                    rugo_obb b = rugo_segment_box(fine, k, fmax(fl.bound[k], fl.total[k]), 0.0);
                    const rugo_obb* leaf = rugo_mobb_tree_node(tree, fl.level, k);
                    ck_assert(memcmp(&b.center, &leaf->center, sizeof b.center) == 0);
                    ck_assert(memcmp(b.axis, leaf->axis, sizeof b.axis) == 0);
                    for (int a = 0; a < 2; ++a) /* plus a round-off pad */
                        ck_assert(leaf->half[a] >= b.half[a] && leaf->half[a] - b.half[a] <= 1e-12 * 1000.0);
                }
                rugo_mobb_tree_destroy(tree);
            }
            rugo_tolerances_destroy(t);
            rugo_pyramid_destroy(p);
        }
        free(pts);
    }
}
END_TEST

START_TEST(test_tree_nodes_and_areas) {
    test_rng r = test_rng_seed(302);
    enum { N = 256 };
    rugo_vec2 pts[N];
    test_random_star(&r, N, rugo_v2(0.0, 0.0), 50.0, 0.3, pts);
    rugo_pyramid* p = make_pyramid(pts, N, 3);
    rugo_mobb_tree* tree = make_tree(p, NULL, RUGO_BOXES_MULTIRES, 0.0);
    int count = 0;
    for (int j = 3; j <= 8; ++j) {
        double sum = 0.0;
        for (int k = 0; k < (1 << j); ++k) {
            const rugo_obb* b = rugo_mobb_tree_node(tree, j, k);
            ck_assert_ptr_nonnull(b);
            sum += rugo_obb_area(b);
            ++count;
        }
        ck_assert_near(rugo_mobb_tree_level_area(tree, j), sum, 1e-9 * sum);
        ck_assert_ptr_null(rugo_mobb_tree_node(tree, j, -1));
        ck_assert_ptr_null(rugo_mobb_tree_node(tree, j, 1 << j));
    }
    ck_assert_int_eq(count, 2 * N - 8);
    ck_assert_ptr_null(rugo_mobb_tree_node(tree, 2, 0));
    ck_assert_ptr_null(rugo_mobb_tree_node(tree, 9, 0));
    ck_assert(isnan(rugo_mobb_tree_level_area(tree, 2)));
    ck_assert(isnan(rugo_mobb_tree_level_area(tree, 9)));
    /* Coarser boxes are bigger in total (they hold their children). */
    for (int j = 3; j < 8; ++j)
        ck_assert(rugo_mobb_tree_level_area(tree, j) > rugo_mobb_tree_level_area(tree, j + 1));
    /* Accessors tolerate NULL. */
    ck_assert_ptr_null(rugo_mobb_tree_node(NULL, 3, 0));
    ck_assert_ptr_null(rugo_mobb_tree_root(NULL));
    ck_assert(isnan(rugo_mobb_tree_level_area(NULL, 3)));
    ck_assert_int_eq(rugo_mobb_tree_finest_level(NULL), -1);
    rugo_mobb_tree_destroy(NULL);
    rugo_mobb_tree_destroy(tree);
    rugo_pyramid_destroy(p);
}
END_TEST

START_TEST(test_tree_linear_size) {
    /* Node count 2n - 2^J_min for n up to 8192, and the root holds every leaf (no timing here). */
    test_rng r = test_rng_seed(303);
    for (int J = 5; J <= 13; J += 4) {
        int n = 1 << J;
        rugo_vec2* pts = xmalloc((size_t)n * sizeof *pts);
        test_random_star(&r, n, rugo_v2(3.0, 4.0), 1000.0, 0.3, pts);
        for (int coarsest = 2; coarsest <= 5; coarsest += 3) {
            rugo_pyramid* p = make_pyramid(pts, n, coarsest);
            rugo_tolerances* t = make_tolerances(p, 0.0, 1.0, 5);
            for (int m = 0; m < 2; ++m) {
                rugo_mobb_tree* tree = make_tree(p, t, (rugo_box_method)m, 0.0);
                long nodes = 0;
                for (int j = 0; j <= J + 1; ++j)
                    for (int k = 0; k < (1 << j); ++k)
                        nodes += rugo_mobb_tree_node(tree, j, k) != NULL;
                ck_assert_int_eq(nodes, 2L * n - (1L << coarsest));
                for (int k = 0; k < n; ++k) {
                    rugo_vec2 corner[4];
                    rugo_obb_corners(rugo_mobb_tree_node(tree, J, k), corner);
                    for (int i = 0; i < 4; ++i)
                        ck_assert(rugo_obb_contains(rugo_mobb_tree_root(tree), corner[i], 1e-9));
                }
                rugo_mobb_tree_destroy(tree);
            }
            rugo_tolerances_destroy(t);
            rugo_pyramid_destroy(p);
        }
        free(pts);
    }
}
END_TEST

static int same_tree(const rugo_mobb_tree* a, const rugo_mobb_tree* b) {
    for (int j = rugo_mobb_tree_coarsest_level(a); j <= rugo_mobb_tree_finest_level(a); ++j)
        for (int k = 0; k < (1 << j); ++k)
            if (memcmp(rugo_mobb_tree_node(a, j, k), rugo_mobb_tree_node(b, j, k), sizeof(rugo_obb)) != 0)
                return 0;
    return memcmp(rugo_mobb_tree_root(a), rugo_mobb_tree_root(b), sizeof(rugo_obb)) == 0;
}

START_TEST(test_tree_determinism) {
    test_rng r = test_rng_seed(304);
    enum { N = 128 };
    rugo_vec2 pts[N];
    test_random_star(&r, N, rugo_v2(1.0, 2.0), 30.0, 0.4, pts);
    rugo_pyramid* p = make_pyramid(pts, N, 2);
    rugo_tolerances* t = make_tolerances(p, 0.1, 0.5, 9);
    for (int m = 0; m < 2; ++m) {
        rugo_mobb_tree* a = make_tree(p, t, (rugo_box_method)m, 0.0);
        rugo_mobb_tree* b = make_tree(p, t, (rugo_box_method)m, 0.0);
        ck_assert(same_tree(a, b));
        rugo_mobb_tree_destroy(a);
        rugo_mobb_tree_destroy(b);
    }
    /* The methods differ only above the leaves. */
    rugo_mobb_tree* a = make_tree(p, t, RUGO_BOXES_MULTIRES, 0.0);
    rugo_mobb_tree* b = make_tree(p, t, RUGO_BOXES_OF_BOXES, 0.0);
    for (int k = 0; k < N; ++k)
        ck_assert(memcmp(rugo_mobb_tree_node(a, 7, k), rugo_mobb_tree_node(b, 7, k), sizeof(rugo_obb)) == 0);
    ck_assert(!same_tree(a, b));
    rugo_mobb_tree_destroy(a);
    rugo_mobb_tree_destroy(b);
    rugo_tolerances_destroy(t);
    rugo_pyramid_destroy(p);
}
END_TEST

/* ---- reference: the straightforward build ------------------------------------------------------- */

/* REFERENCE ONLY. The MOBBtree build as librugo/mobb.c computed it before issue 7's optimisation
 * (commit dbc0681): one segment at a time, 5 evaluated samples, hypot, the quadratic's roots tested
 * case by case, growth by one child at a time. Kept (same operations, the allocation and error
 * handling left out) so that test_leaf_box_matches_reference and test_tree_matches_reference can pin
 * that the fast build computes the same boxes up to round-off. Not used by the library. */

static void ref_axes_from_covariance(double a, double b, double c, rugo_vec2 axis[2]) {
    double trace = a + c, d = hypot(a - c, 2.0 * b);
    rugo_vec2 e = rugo_v2(1.0, 0.0);
    if (isfinite(d) && trace > 0.0 && fabs(b) > 1e-12 * trace && d > 1e-12 * trace) {
        rugo_vec2 x = a >= c ? rugo_v2(0.5 * (a - c + d), b) : rugo_v2(b, 0.5 * (c - a + d));
        double len = rugo__v2_length(x);
        if (len > 0.0 && isfinite(len)) {
            e = rugo_v2(x.x / len, x.y / len);
            if (e.x < 0.0 || (e.x == 0.0 && e.y < 0.0)) e = rugo_v2(-e.x, -e.y);
        }
    }
    axis[0] = e;
    axis[1] = rugo_v2_perp(e);
}

static void ref_covariance_axes(const rugo_vec2* points, int n, rugo_vec2 axis[2]) {
    rugo_vec2 o = points[0], mean = rugo_v2(0.0, 0.0);
    for (int i = 0; i < n; ++i)
        mean = rugo_v2_add(mean, rugo_v2_sub(points[i], o));
    mean = rugo_v2_scale(1.0 / n, mean);
    double a = 0.0, b = 0.0, c = 0.0;
    for (int i = 0; i < n; ++i) {
        rugo_vec2 q = rugo_v2_sub(rugo_v2_sub(points[i], o), mean);
        a += q.x * q.x;
        b += q.x * q.y;
        c += q.y * q.y;
    }
    ref_axes_from_covariance(a, b, c, axis);
}

static void ref_box_interval(const rugo_obb* b, rugo_vec2 o, rugo_vec2 e, double* lo, double* hi) {
    double m = rugo_v2_dot(rugo_v2_sub(b->center, o), e);
    double r = b->half[0] * fabs(rugo_v2_dot(b->axis[0], e)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], e));
    *lo = m - r;
    *hi = m + r;
}

static rugo_obb ref_box_from_intervals(const rugo_vec2 axis[2], rugo_vec2 o, const double lo[2],
                                       const double hi[2]) {
    rugo_obb r;
    r.axis[0] = axis[0];
    r.axis[1] = axis[1];
    r.center = o;
    for (int i = 0; i < 2; ++i) {
        r.center = rugo_v2_add(r.center, rugo_v2_scale(0.5 * (lo[i] + hi[i]), axis[i]));
        r.half[i] = 0.5 * (hi[i] - lo[i]);
        if (!(r.half[i] >= 0.0)) r.half[i] = 0.0;
    }
    return r;
}

static void ref_grow_to_contain(rugo_obb* box, const rugo_obb* b) {
    double lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        double blo, bhi;
        ref_box_interval(b, box->center, box->axis[i], &blo, &bhi);
        lo[i] = fmin(-box->half[i], blo);
        hi[i] = fmax(box->half[i], bhi);
    }
    if (lo[0] < -box->half[0] || hi[0] > box->half[0] || lo[1] < -box->half[1] || hi[1] > box->half[1])
        *box = ref_box_from_intervals(box->axis, box->center, lo, hi);
}

static rugo_vec2 ref_offset_at(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r, double t) {
    double a = t * t * t / 6.0, b = t * t / 4.0, c = 0.5 * t;
    return rugo_v2(a * v.x + b * w.x + c * r.x, a * v.y + b * w.y + c * r.y);
}

static void ref_projection_extremes(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r, rugo_vec2 e, double* lo,
                                    double* hi) {
    double alpha = rugo_v2_dot(v, e), beta = rugo_v2_dot(w, e), gamma = rugo_v2_dot(r, e);
    double cand[4];
    int nc = 0;
    cand[nc++] = 0.0;
    cand[nc++] = 1.0;
    double disc = beta * beta - 4.0 * alpha * gamma;
    double disc_err = 8.0 * DBL_EPSILON * (beta * beta + fabs(4.0 * alpha * gamma));
    if (disc < 0.0 && disc >= -disc_err) disc = 0.0;
    if (disc >= 0.0 && (alpha != 0.0 || beta != 0.0)) {
        double s = sqrt(disc);
        double q = -0.5 * (beta + (beta >= 0.0 ? s : -s));
        if (q != 0.0) {
            if (alpha != 0.0) cand[nc++] = q / alpha;
            cand[nc++] = gamma / q;
        } else if (alpha != 0.0) {
            cand[nc++] = 0.0;
        }
    }
    double mn = 0.0, mx = 0.0;
    for (int i = 1; i < nc; ++i) {
        double t = cand[i];
        if (!(t >= 0.0 && t <= 1.0)) continue;
        double h = rugo_v2_dot(ref_offset_at(v, w, r, t), e);
        mn = fmin(mn, h);
        mx = fmax(mx, h);
    }
    *lo = mn;
    *hi = mx;
}

/* Method (a)'s weight of a segment: its arc length by the 4-point Gauss-Legendre rule (3.6)-(3.7), as
 * mobb.c weighs (a weight needs no more; rugo_contour_segment_length is the certified length). */
static double ref_weight_length(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r) {
    static const double x[4] = {0.06943184420297371238802676, 0.3300094782075718675986671,
                                0.6699905217924281324013329, 0.9305681557970262876119732};
    static const double wt[4] = {0.173927422568726928686532, 0.326072577431273071313468,
                                 0.326072577431273071313468, 0.173927422568726928686532};
    double sum = 0.0;
    for (int g = 0; g < 4; ++g) {
        double t = x[g], dx = (v.x * t + w.x) * t + r.x, dy = (v.y * t + w.y) * t + r.y;
        sum += wt[g] * sqrt(dx * dx + dy * dy);
    }
    return 0.5 * sum;
}

static rugo_obb ref_segment_box(rugo_contour c, int segment, double band, double min_length,
                                double* length_out) {
    rugo_vec2 v, w, r, b[4];
    rugo_contour_derivative_coefficients(c, segment, &v, &w, &r);
    rugo_contour_bezier(c, segment, b);
    double length = rugo_contour_segment_length(c, segment);
    if (length_out) *length_out = ref_weight_length(v, w, r);
    rugo_vec2 samples[5];
    int ns = 0;
    if (length > min_length) {
        for (int i = 0; i < 5; ++i)
            samples[ns++] = ref_offset_at(v, w, r, 0.25 * i);
    } else {
        samples[ns++] = rugo_v2(0.0, 0.0);
        samples[ns++] = ref_offset_at(v, w, r, 1.0);
    }
    rugo_vec2 axis[2];
    ref_covariance_axes(samples, ns, axis);
    double lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        ref_projection_extremes(v, w, r, axis[i], &lo[i], &hi[i]);
        lo[i] -= band;
        hi[i] += band;
    }
    return ref_box_from_intervals(axis, b[0], lo, hi);
}

typedef struct ref_moments {
    double weight;
    rugo_vec2 mean;
    double sxx, sxy, syy;
} ref_moments;

static ref_moments ref_merge_moments(const ref_moments* a, const ref_moments* b) {
    ref_moments m;
    double wsum = a->weight + b->weight;
    rugo_vec2 d = rugo_v2_sub(b->mean, a->mean);
    double fb = wsum > 0.0 ? b->weight / wsum : 0.5;
    double cross = wsum > 0.0 ? a->weight * b->weight / wsum : 0.0;
    m.weight = wsum;
    m.mean = rugo_v2_add(a->mean, rugo_v2_scale(fb, d));
    m.sxx = a->sxx + b->sxx + cross * d.x * d.x;
    m.sxy = a->sxy + b->sxy + cross * d.x * d.y;
    m.syy = a->syy + b->syy + cross * d.y * d.y;
    return m;
}

static rugo_obb ref_padded(rugo_obb b) {
    double pad = 64.0 * DBL_EPSILON * (fmax(fabs(b.center.x), fabs(b.center.y)) + b.half[0] + b.half[1]);
    b.half[0] += pad;
    b.half[1] += pad;
    return b;
}

/* The reference tree: node (j, k) at nodes[(1 << j) - (1 << J0) + k], as the library stores them. */
static rugo_obb* ref_tree(const rugo_pyramid* p, const rugo_tolerances* t, rugo_box_method method,
                          double min_length) {
    int J = rugo_pyramid_finest_level(p), J0 = rugo_pyramid_coarsest_level(p), n = 1 << J;
    rugo_obb* nodes = xmalloc(((size_t)2 * n - ((size_t)1 << J0)) * sizeof *nodes);
    ref_moments* mom = xmalloc((size_t)n * sizeof *mom);
    rugo_tolerance_level tl;
    memset(&tl, 0, sizeof tl);
    if (t) ck_assert_int_eq(rugo_tolerances_level(t, J, &tl), RUGO_OK);
    rugo_contour c = curve_of(p, J);
    rugo_obb* leaves = nodes + (n - (1 << J0));
    for (int k = 0; k < n; ++k) {
        double band = t ? fmax(fmax(tl.bound[k], 0.0), fmax(tl.total[k], 0.0)) : 0.0, length;
        leaves[k] = ref_padded(ref_segment_box(c, k, band, min_length, &length));
        mom[k].weight = length > 0.0 ? length : 0.0;
        mom[k].mean = leaves[k].center;
        mom[k].sxx = mom[k].sxy = mom[k].syy = 0.0;
    }
    for (int j = J - 1; j >= J0; --j) {
        if (t) ck_assert_int_eq(rugo_tolerances_level(t, j, &tl), RUGO_OK);
        c = curve_of(p, j);
        rugo_obb* level = nodes + ((1 << j) - (1 << J0));
        const rugo_obb* below = nodes + ((2 << j) - (1 << J0));
        for (int k = 0; k < (1 << j); ++k) {
            rugo_obb own =
                ref_padded(ref_segment_box(c, k, t ? fmax(tl.total[k], 0.0) : 0.0, min_length, NULL));
            rugo_obb box;
            if (method == RUGO_BOXES_MULTIRES) {
                box = own;
                ref_grow_to_contain(&box, &below[2 * k]);
                ref_grow_to_contain(&box, &below[2 * k + 1]);
            } else {
                mom[k] = ref_merge_moments(&mom[2 * k], &mom[2 * k + 1]);
                rugo_vec2 axis[2];
                ref_axes_from_covariance(mom[k].sxx, mom[k].sxy, mom[k].syy, axis);
                double lo[2], hi[2];
                for (int i = 0; i < 2; ++i) {
                    double alo, ahi, blo, bhi;
                    ref_box_interval(&below[2 * k], below[2 * k].center, axis[i], &alo, &ahi);
                    ref_box_interval(&below[2 * k + 1], below[2 * k].center, axis[i], &blo, &bhi);
                    lo[i] = fmin(alo, blo);
                    hi[i] = fmax(ahi, bhi);
                }
                box = ref_box_from_intervals(axis, below[2 * k].center, lo, hi);
                ref_grow_to_contain(&box, &own);
            }
            level[k] = ref_padded(box);
        }
    }
    free(mom);
    return nodes;
}

/* Compares box a with the reference box b: the axis' turn (times the box's size, i.e. how far it
 * moves the corners), the centre and the extents, each relative to the box's scale (size plus distance
 * from the origin: its coordinates' round-off); the worst values seen go to worst[0..2]. */
static void compare_boxes(const rugo_obb* a, const rugo_obb* b, double worst[3]) {
    double size = b->half[0] + b->half[1];
    double scale = size + fmax(fabs(b->center.x), fabs(b->center.y));
    check_frame(a->axis);
    ck_assert(rugo_v2_dot(a->axis[0], b->axis[0]) > 0.0); /* the same canonical sign */
    worst[0] = fmax(worst[0], direction_error(a->axis[0], b->axis[0]) * size / scale);
    worst[1] = fmax(worst[1], fmax(fabs(a->center.x - b->center.x), fabs(a->center.y - b->center.y)) / scale);
    worst[2] = fmax(worst[2], fmax(fabs(a->half[0] - b->half[0]), fabs(a->half[1] - b->half[1])) / scale);
}

START_TEST(test_leaf_box_matches_reference) {
    /* rugo_segment_box against the straightforward leaf box: every degenerate kind of segment of
     * test_leaf_box_kinds, random segments near and far from the origin, with and without band, at
     * l_min = 0, at l_min = the segment's own length (2 samples) and just below it (5). Measured worst
     * (gcc 12, x86-64): axis turn 1.3e-15 (a nearly round random segment, whose covariance axis is
     * ill-conditioned), centre 4.7e-16, extents 3.1e-16 of the scale; the bounds leave a factor of 15
     * or more. */
    const rugo_vec2 kinds[7][4] = {
        {{0, 0}, {1, 2}, {3, -1}, {4, 1.5}},                      /* cubic */
        {{-1.5, 0.75}, {-0.5, -0.25}, {0.5, 0.75}, {1.5, 3.75}},  /* parabolic, v = 0 */
        {{-1.5, 2.25}, {-0.5, 0.25}, {0.5, 0.25}, {1.5, 2.25}},   /* parabolic, axis-aligned */
        {{0, 0}, {1, 2}, {1.5, 3}, {4, 8}},                       /* straight, tilted */
        {{0, 1}, {1, 1}, {3, 1}, {4, 1}},                         /* straight, axis-aligned */
        {{2.5, -1.25}, {2.5, -1.25}, {2.5, -1.25}, {2.5, -1.25}}, /* a point */
        {{0, 0}, {2, 1}, {0, 1}, {2, 0}},                         /* a cusp */
    };
    test_rng r = test_rng_seed(307);
    double worst[3] = {0.0, 0.0, 0.0};
    for (int trial = 0; trial < 607; ++trial) {
        rugo_vec2 q[4];
        if (trial < 7)
            memcpy(q, kinds[trial], sizeof q);
        else
            test_random_points(&r, 4, 5.0, q);
        if (trial % 2 == 1)
            for (int i = 0; i < 4; ++i)
                q[i] = rugo_v2_add(q[i], rugo_v2(1e6, -3e6));
        double band = trial % 3 == 0 ? 0.0 : test_rng_uniform(&r, 0.0, 1.0);
        double len = rugo_contour_segment_length(four(q), 1);
        const double min_lengths[3] = {0.0, len, 0.999 * len};
        for (int l = 0; l < 3; ++l) {
            rugo_obb a = rugo_segment_box(four(q), 1, band, min_lengths[l]);
            rugo_obb b = ref_segment_box(four(q), 1, band, min_lengths[l], NULL);
            compare_boxes(&a, &b, worst);
            if (trial == 4 || trial == 5)
                ck_assert(memcmp(&a, &b, sizeof a) == 0); /* degenerate: the same bits */
        }
    }
    ck_assert_msg(worst[0] < 2e-14, "axis turn %g", worst[0]);
    ck_assert_msg(worst[1] < 1e-14, "centre %g", worst[1]);
    ck_assert_msg(worst[2] < 1e-14, "extents %g", worst[2]);
}
END_TEST

START_TEST(test_tree_matches_reference) {
    /* Smooth and rough shapes, near and far from the origin, with and without tolerances, both
     * methods, l_min = 0 and a positive l_min: every node agrees with the straightforward build's
     * (compare_boxes), and, near the origin, its area too (relative); far from it a thin box's area
     * is only known to the round-off of its coordinates. Every finest segment's dense samples lie in
     * its leaf (no slack: the pad) and in rugo_segment_box's box (1e-12 of the scale), as discs of
     * radius β^J. Measured worst (gcc 12, x86-64): axis 4.1e-16, centre 5.8e-16, extents 4.9e-16 of
     * the scale, area 2.8e-13; the bounds leave a factor of 17 to 36. */
    test_rng r = test_rng_seed(306);
    double worst[3] = {0.0, 0.0, 0.0}, worst_area = 0.0;
    long nodes_compared = 0, samples = 0;
    const int sizes[3] = {64, 256, 1024};
    for (int si = 0; si < 3; ++si)
        for (int far = 0; far < 2; ++far) {
            int n = sizes[si];
            rugo_vec2 centre = far ? rugo_v2(-3.0e5, 7.0e4) : rugo_v2(5.0, -3.0);
            rugo_vec2* pts = xmalloc((size_t)n * sizeof *pts);
            test_random_star(&r, n, centre, 100.0, 0.4, pts);
            if (si > 0) /* rough: radial jitter at every control point */
                for (int i = 0; i < n; ++i) {
                    double s = 1.0 + test_rng_uniform(&r, -0.01, 0.01);
                    pts[i] = rugo_v2_add(centre, rugo_v2_scale(s, rugo_v2_sub(pts[i], centre)));
                }
            rugo_pyramid* p = make_pyramid(pts, n, 2);
            rugo_tolerances* t = si == 1 ? NULL : make_tolerances(p, 0.05, 0.5, 40u + (uint64_t)si);
            int J = rugo_pyramid_finest_level(p);
            rugo_contour fine = curve_of(p, J);
            rugo_tolerance_level fl;
            memset(&fl, 0, sizeof fl);
            if (t) ck_assert_int_eq(rugo_tolerances_level(t, J, &fl), RUGO_OK);
            for (int m = 0; m < 2; ++m)
                for (int ml = 0; ml < 2; ++ml) {
                    /* a positive l_min among the segments' lengths, so that both sample counts occur */
                    double min_length = ml ? 0.6 * 2.0 * PI * 100.0 / n : 0.0;
                    rugo_mobb_tree* tree = make_tree(p, t, (rugo_box_method)m, min_length);
                    rugo_obb* ref = ref_tree(p, t, (rugo_box_method)m, min_length);
                    for (int j = 2; j <= J; ++j)
                        for (int k = 0; k < (1 << j); ++k) {
                            const rugo_obb* a = rugo_mobb_tree_node(tree, j, k);
                            const rugo_obb* b = &ref[(1 << j) - 4 + k];
                            compare_boxes(a, b, worst);
                            if (!far)
                                worst_area = fmax(worst_area, fabs(rugo_obb_area(a) - rugo_obb_area(b)) /
                                                                  rugo_obb_area(b));
                            ++nodes_compared;
                        }
                    for (int k = 0; k < n && m == 0; ++k) {
                        double beta = t ? fmax(fl.bound[k], fl.total[k]) : 0.0;
                        const rugo_obb* leaf = rugo_mobb_tree_node(tree, J, k);
                        rugo_obb box = rugo_segment_box(fine, k, beta, min_length);
                        double scale =
                            box.half[0] + box.half[1] + fmax(fabs(box.center.x), fabs(box.center.y));
                        for (int i = 0; i <= 64; ++i) {
                            rugo_vec2 s = rugo_contour_point(fine, k, i / 64.0);
                            ck_assert(rugo_obb_contains(leaf, s, -beta));
                            ck_assert(rugo_obb_contains(&box, s, 1e-12 * scale - beta));
                            ++samples;
                        }
                    }
                    free(ref);
                    rugo_mobb_tree_destroy(tree);
                }
            rugo_tolerances_destroy(t);
            rugo_pyramid_destroy(p);
            free(pts);
        }
    ck_assert_int_eq(nodes_compared, 2L * 2 * 2 * ((2 * 64 - 4) + (2 * 256 - 4) + (2 * 1024 - 4)));
    ck_assert_int_eq(samples, 2L * 2 * 65 * (64 + 256 + 1024));
    ck_assert_msg(worst[0] < 1e-14, "axis turn %g of the scale", worst[0]);
    ck_assert_msg(worst[1] < 1e-14, "centre %g of the scale", worst[1]);
    ck_assert_msg(worst[2] < 1e-14, "extents %g of the scale", worst[2]);
    ck_assert_msg(worst_area < 1e-11, "area %g (relative)", worst_area);
}
END_TEST

/* An allocator that fails on the fail_at-th call (0 = never) and counts live blocks. */
typedef struct counting_heap {
    int calls, fail_at, live;
} counting_heap;

static void* heap_alloc(size_t size, void* ctx) {
    counting_heap* h = ctx;
    if (++h->calls == h->fail_at) return NULL;
    void* p = malloc(size);
    if (p) ++h->live;
    return p;
}

static void heap_free(void* p, void* ctx) {
    counting_heap* h = ctx;
    if (p) --h->live;
    free(p);
}

START_TEST(test_tree_errors) {
    test_rng r = test_rng_seed(305);
    rugo_vec2 pts[64];
    test_random_star(&r, 64, rugo_v2(0.0, 0.0), 10.0, 0.3, pts);
    rugo_pyramid* p = make_pyramid(pts, 64, 2);
    rugo_pyramid* p3 = make_pyramid(pts, 64, 3);
    rugo_pyramid* p32 = make_pyramid(pts, 32, 2);
    rugo_tolerances* t3 = make_tolerances(p3, 0.1, 0.2, 1);
    rugo_tolerances* t32 = make_tolerances(p32, 0.1, 0.2, 1);

    rugo_mobb_tree* tree = (rugo_mobb_tree*)&r; /* must be reset to NULL on failure */
    rugo_mobb_tree_def def = rugo_default_mobb_tree_def();
    ck_assert_int_eq(def.method, RUGO_BOXES_MULTIRES);
    ck_assert(def.min_length == 0.0 && def.tolerances == NULL);
    ck_assert_int_eq(rugo_mobb_tree_create(&def, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_mobb_tree_create(NULL, &tree), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_ptr_null(tree);
    ck_assert_int_eq(rugo_mobb_tree_create(&def, &tree), RUGO_ERR_NULL_ARGUMENT); /* no pyramid */
    def.pyramid = p;
    rugo_mobb_tree_def bad = def;
    bad.cookie = 0;
    ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_ARGUMENT);
    bad = def;
    bad.method = (rugo_box_method)2;
    ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_ARGUMENT);
    bad.method = (rugo_box_method)-1;
    ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_ARGUMENT);
    const double lens[3] = {-1.0, NAN, INFINITY};
    for (int i = 0; i < 3; ++i) {
        bad = def;
        bad.min_length = lens[i];
        ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_ARGUMENT);
    }
    /* tolerances of another pyramid: other finest level, other coarsest level */
    bad = def;
    bad.tolerances = t32;
    ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_LEVEL);
    bad.tolerances = t3;
    ck_assert_int_eq(rugo_mobb_tree_create(&bad, &tree), RUGO_ERR_BAD_LEVEL);
    ck_assert_ptr_null(tree);

    /* Out of memory at every allocation the build makes, for both methods; nothing leaks. */
    for (int m = 0; m < 2; ++m) {
        counting_heap h = {0, 0, 0};
        def.method = (rugo_box_method)m;
        def.allocator.alloc = heap_alloc;
        def.allocator.free = heap_free;
        def.allocator.ctx = &h;
        ck_assert_int_eq(rugo_mobb_tree_create(&def, &tree), RUGO_OK);
        int calls = h.calls;
        ck_assert_int_gt(calls, 0);
        rugo_mobb_tree_destroy(tree);
        ck_assert_int_eq(h.live, 0);
        for (int f = 1; f <= calls; ++f) {
            h.calls = 0;
            h.fail_at = f;
            tree = (rugo_mobb_tree*)&r;
            ck_assert_int_eq(rugo_mobb_tree_create(&def, &tree), RUGO_ERR_OUT_OF_MEMORY);
            ck_assert_ptr_null(tree);
            ck_assert_int_eq(h.live, 0);
        }
    }
    rugo_tolerances_destroy(t3);
    rugo_tolerances_destroy(t32);
    rugo_pyramid_destroy(p);
    rugo_pyramid_destroy(p3);
    rugo_pyramid_destroy(p32);
}
END_TEST

static Suite* mobb_suite(void) {
    Suite* s = suite_create("mobb");
    TCase* prim = tcase_create("primitives");
    tcase_set_timeout(prim, 60);
    tcase_add_test(prim, test_covariance_axes_known);
    tcase_add_test(prim, test_covariance_axes_degenerate);
    tcase_add_test(prim, test_sat_brute_force);
    tcase_add_test(prim, test_sat_touching_nested_degenerate);
    tcase_add_test(prim, test_transform_enclose_contains);
    suite_add_tcase(s, prim);
    TCase* leaf = tcase_create("leaf");
    tcase_set_timeout(leaf, 60);
    tcase_add_test(leaf, test_leaf_box_kinds);
    tcase_add_test(leaf, test_leaf_box_random_and_far);
    tcase_add_test(leaf, test_leaf_box_min_length);
    suite_add_tcase(s, leaf);
    TCase* tree = tcase_create("tree");
    tcase_set_timeout(tree, 120);
    tcase_add_test(tree, test_tree_invariant_smooth);
    tcase_add_test(tree, test_tree_invariant_rough);
    tcase_add_test(tree, test_tree_nodes_and_areas);
    tcase_add_test(tree, test_tree_linear_size);
    tcase_add_test(tree, test_tree_determinism);
    tcase_add_test(tree, test_tree_matches_reference);
    tcase_add_test(tree, test_leaf_box_matches_reference);
    tcase_add_test(tree, test_tree_errors);
    suite_add_tcase(s, tree);
    return s;
}

int main(void) { return test_run_suite(mobb_suite()); }
