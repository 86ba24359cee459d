/* The ray cast through a shape's MOBBtree (rugo_shape_ray_cast, shape/point_query.c) against the pass
 * over all segments (rugo_contour_ray_cast): the same answers, bit for bit, on every ray; the work it
 * saves; its statuses. */
#include "rugo/rugo.h"

#include "shape/internal.h" /* rugo__level_ray_cast: the segments the walk evaluates */
#include "test_util.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI 6.283185307179586

static void* xmalloc(size_t n) {
    void* p = malloc(n);
    ck_assert_ptr_nonnull(p);
    return p;
}

static rugo_shape* make_shape(const rugo_vec2* pts, int n, const double* tol) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts;
    d.count = n;
    d.tolerances = tol;
    rugo_shape* s = NULL;
    rugo_status st = rugo_shape_create(&d, &s, NULL);
    ck_assert_msg(st == RUGO_OK, "rugo_shape_create: %s", rugo_status_string(st));
    return s;
}

static uint64_t bits(double x) {
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

typedef struct ray_tally {
    long cases, hits, mismatches, visited, segments;
} ray_tally;

/* One ray on one level: the tree's answer and the contour's, every output compared bit for bit
 * (outputs start from a sentinel, so "left untouched" is compared too). */
static void ray_check(const rugo_shape* s, int level, rugo_contour c, rugo_vec2 o, rugo_vec2 d,
                      double max_fraction, ray_tally* T) {
    rugo_curve_point h1, h2;
    rugo_vec2 n1 = rugo_v2(7.0, 7.0), n2 = n1;
    double f1 = -7.0, f2 = -7.0;
    memset(&h1, 0x5a, sizeof h1);
    memset(&h2, 0x5a, sizeof h2);
    bool found = false;
    const rugo_status st = rugo_shape_ray_cast(s, level, o, d, max_fraction, &f1, &h1, &n1, &found);
    const bool ref = rugo_contour_ray_cast(c, o, d, max_fraction, &f2, &h2, &n2);
    if (!(rugo_v2_dot(d, d) > 0.0)) { /* between repeated control points: refused, and no hit there */
        ck_assert_int_eq(st, RUGO_ERR_BAD_ARGUMENT);
        ck_assert(!found && !ref);
        return;
    }
    ck_assert_msg(st == RUGO_OK, "ray cast: %s", rugo_status_string(st));
    T->cases++;
    T->hits += ref;
    const bool same = found == ref && bits(f1) == bits(f2) && h1.segment == h2.segment &&
                      bits(h1.t) == bits(h2.t) && bits(h1.point.x) == bits(h2.point.x) &&
                      bits(h1.point.y) == bits(h2.point.y) && bits(h1.distance) == bits(h2.distance) &&
                      bits(n1.x) == bits(n2.x) && bits(n1.y) == bits(n2.y);
    if (!same) {
        if (T->mismatches < 5)
            printf("ray cast mismatch: level %d, origin (%.17g, %.17g), direction (%.17g, %.17g), max %.17g: "
                   "tree %d s %.17g seg %d t %.17g, all segments %d s %.17g seg %d t %.17g\n",
                   level, o.x, o.y, d.x, d.y, max_fraction, (int)found, f1, h1.segment, h1.t, (int)ref, f2,
                   h2.segment, h2.t);
        T->mismatches++;
    }
    rugo__ray r;
    if (rugo__ray_begin(&r, o, d, max_fraction)) {
        int visited = 0;
        rugo__level_ray_cast(s, level, &r, &visited);
        T->visited += visited;
        T->segments += c.count;
    }
}

/* A random direction of length `scale`. */
static rugo_vec2 random_direction(test_rng* r, double scale) {
    const double a = test_rng_uniform(r, 0.0, TWO_PI);
    return rugo_v2(scale * cos(a), scale * sin(a));
}

/* Rays that stress the walk, on every level: random ones around and across the shape (directions of
 * length 1e-3 .. 1e3, short and long max_fraction, and of length 1e-150 .. 1e140); towards every joint
 * (through it, and stopping on it); from inside, from the curve itself (s = 0) and from just off it;
 * along the tangent at a point of every segment (touching the curve there, and one ulp or 1e-12 of the
 * size beside it); along the horizontal tangents; along straight pieces (from a joint towards the
 * next); from far away (1e4 times the size) towards the shape; max_fraction 0. */
static void ray_stress(const rugo_shape* s, test_rng* r, ray_tally* T) {
    const rugo_vec2 centroid = rugo_shape_mass(s).centroid;
    for (int L = rugo_shape_coarsest_level(s); L <= rugo_shape_finest_level(s); ++L) {
        rugo_contour c;
        rugo_shape_level(s, L, &c);
        rugo_vec2 lo, hi;
        rugo_contour_bounds(c, &lo, &hi);
        const double w = hi.x - lo.x, h = hi.y - lo.y, size = hypot(w, h);
        for (int i = 0; i < 120; ++i) {
            const rugo_vec2 o = rugo_v2(test_rng_uniform(r, lo.x - 0.5 * w, hi.x + 0.5 * w),
                                        test_rng_uniform(r, lo.y - 0.5 * h, hi.y + 0.5 * h));
            const double scale = pow(10.0, (double)(i % 7) - 3.0);
            const double maxf = (i % 3 == 0 ? 1e3 : test_rng_uniform(r, 0.0, 2.0)) * size / scale;
            ray_check(s, L, c, o, random_direction(r, scale), maxf, T);
        }
        static const double extreme[4] = {1e-150, 1e-60, 1e60, 1e140}; /* |d|^2 subnormal .. near overflow */
        for (int i = 0; i < 16; ++i) {
            const rugo_vec2 o = rugo_v2(test_rng_uniform(r, lo.x - 0.5 * w, hi.x + 0.5 * w),
                                        test_rng_uniform(r, lo.y - 0.5 * h, hi.y + 0.5 * h));
            const double scale = extreme[i % 4];
            ray_check(s, L, c, o, random_direction(r, scale), test_rng_uniform(r, 0.0, 2.0) * size / scale,
                      T);
        }
        for (int k = 0; k < c.count; ++k) {
            const rugo_vec2 joint = rugo_contour_point(c, k, 0.0);
            const rugo_vec2 o = rugo_v2(test_rng_uniform(r, lo.x - 0.5 * w, hi.x + 0.5 * w),
                                        test_rng_uniform(r, lo.y - 0.5 * h, hi.y + 0.5 * h));
            const rugo_vec2 toj = rugo_v2_sub(joint, o);
            ray_check(s, L, c, o, toj, 1.0, T);
            ray_check(s, L, c, o, toj, 3.0, T);
            ray_check(s, L, c, centroid, rugo_v2_sub(joint, centroid), 2.0, T);
            const double t = test_rng_uniform(r, 0.0, 1.0);
            const rugo_vec2 q = rugo_contour_point(c, k, t), n = rugo_contour_normal(c, k, t),
                            tau = rugo_contour_tangent(c, k, t);
            ray_check(s, L, c, q, random_direction(r, 1.0), 2.0 * size, T);
            ray_check(s, L, c, q, random_direction(r, 1.0), 0.0, T);
            const double e = pow(10.0, -test_rng_uniform(r, 3.0, 15.0)) * size;
            ray_check(s, L, c, rugo_v2(q.x - e * n.x, q.y - e * n.y), random_direction(r, 1.0), 2.0 * size,
                      T);
            ray_check(s, L, c, rugo_v2(q.x + e * n.x, q.y + e * n.y), rugo_v2(-n.x, -n.y), 2.0 * size, T);
            /* tangent rays: touching at q, and just beside it */
            const double back = test_rng_uniform(r, 0.01, 0.5) * size;
            for (int side = -1; side <= 1; ++side) {
                const double off = side == 0 ? 0.0 : side * 1e-12 * size;
                const rugo_vec2 o2 = rugo_v2(q.x - back * tau.x + off * n.x, q.y - back * tau.y + off * n.y);
                ray_check(s, L, c, o2, tau, 2.0 * back, T);
            }
            const rugo_vec2 o3 = rugo_v2(q.x - back * tau.x, q.y - back * tau.y);
            ray_check(s, L, c, rugo_v2(o3.x, nextafter(o3.y, HUGE_VAL)), tau, 2.0 * back, T);
            /* along the piece from this joint to the next (straight pieces lie on the ray) */
            const rugo_vec2 next = rugo_contour_point(c, k + 1, 0.0);
            ray_check(s, L, c, joint, rugo_v2_sub(next, joint), 1.0, T);
            ray_check(s, L, c, rugo_v2(2.0 * joint.x - next.x, 2.0 * joint.y - next.y),
                      rugo_v2_sub(next, joint), 3.0, T);
            /* horizontal tangents: y'(t) = 0, rays along y = y(t) from the left */
            rugo_vec2 cv, cw, cr;
            rugo_contour_derivative_coefficients(c, k, &cv, &cw, &cr);
            const double A = cv.y, B = cw.y, C = cr.y, disc = B * B - 4.0 * A * C;
            if (A != 0.0 && disc >= 0.0)
                for (int sg = -1; sg <= 1; sg += 2) {
                    const double tt = (-B + sg * sqrt(disc)) / (2.0 * A);
                    if (!(tt >= 0.0 && tt < 1.0)) continue;
                    const rugo_vec2 qq = rugo_contour_point(c, k, tt);
                    ray_check(s, L, c, rugo_v2(lo.x - 0.25 * w, qq.y), rugo_v2(1.0, 0.0), 2.0 * w, T);
                    ray_check(s, L, c, rugo_v2(lo.x - 0.25 * w, nextafter(qq.y, -HUGE_VAL)),
                              rugo_v2(1.0, 0.0), 2.0 * w, T);
                }
        }
        for (int i = 0; i < 16; ++i) {
            const rugo_vec2 u = random_direction(r, 1.0);
            const rugo_vec2 far = rugo_v2(centroid.x + 1e4 * size * u.x, centroid.y + 1e4 * size * u.y);
            ray_check(s, L, c, far, rugo_v2_sub(centroid, far), 1.0, T);
            ray_check(s, L, c, far, rugo_v2(-u.x, -u.y), 2e4 * size, T);
        }
    }
}

START_TEST(test_tree_ray_cast_matches_contour) {
    test_rng r = test_rng_seed(0x72617973);
    ray_tally T;
    memset(&T, 0, sizeof T);
    rugo_vec2* p = (rugo_vec2*)xmalloc(1024 * sizeof *p);
    double* tol = (double*)xmalloc(1024 * sizeof *tol);
    /* an ellipse with a band */
    for (int i = 0; i < 16; ++i) {
        const double th = TWO_PI * i / 16;
        p[i] = rugo_v2(1.2 * cos(th), 0.7 * sin(th));
        tol[i] = 0.01;
    }
    rugo_shape* s = make_shape(p, 16, tol);
    ray_stress(s, &r, &T);
    rugo_shape_destroy(s);
    /* wavy stars of 16 .. 1024 points, very rough and smooth */
    for (int n = 16; n <= 1024; n *= 4)
        for (int rep = 0; rep < 2; ++rep) {
            test_random_star(&r, n, rugo_v2(0.3, -0.1), 1.0, 0.45, p);
            for (int i = 0; i < n; ++i)
                tol[i] = test_rng_uniform(&r, 0.0, rep ? 0.2 : 0.0);
            s = make_shape(p, n, tol);
            ray_stress(s, &r, &T);
            rugo_shape_destroy(s);
        }
    /* straight sides: four collinear control points per side */
    for (int side = 0; side < 4; ++side)
        for (int i = 0; i < 4; ++i) {
            const double a = -1.0 + 0.5 * i;
            const rugo_vec2 q[4] = {{a, -0.8}, {1.0, -0.8 + 0.4 * i}, {-a, 0.8}, {-1.0, 0.8 - 0.4 * i}};
            p[4 * side + i] = q[side];
        }
    s = make_shape(p, 16, NULL);
    ray_stress(s, &r, &T);
    rugo_shape_destroy(s);
    /* a staircase: horizontal pieces on the rays of their own joints */
    for (int i = 0; i < 64; ++i) {
        const int step = i / 8, j = i % 8;
        const double x = step < 4 ? -1.0 + 0.5 * step + 0.0625 * j : 1.0 - 0.5 * (step - 4) - 0.0625 * j;
        const double y = (step < 4 ? 0.25 * step : 1.5 - 0.25 * (step - 4)) + (j < 4 ? 0.0 : 0.1);
        p[i] = rugo_v2(x, y);
    }
    s = make_shape(p, 64, NULL);
    ray_stress(s, &r, &T);
    rugo_shape_destroy(s);
    /* repeated corners (point-like segments, sharp corners), at the origin and far from it; a star far
     * from the origin */
    const rugo_vec2 corners[4] = {{-0.9, -0.6}, {0.9, -0.6}, {0.9, 0.6}, {-0.9, 0.6}};
    for (int far = 0; far < 2; ++far) {
        for (int i = 0; i < 16; ++i)
            p[i] = rugo_v2(corners[i / 4].x + (far ? 1e6 : 0.0), corners[i / 4].y - (far ? 3e5 : 0.0));
        s = make_shape(p, 16, NULL);
        ray_stress(s, &r, &T);
        rugo_shape_destroy(s);
    }
    test_random_star(&r, 64, rugo_v2(-2e7, 5e6), 1.0, 0.4, p);
    s = make_shape(p, 64, NULL);
    ray_stress(s, &r, &T);
    rugo_shape_destroy(s);
    free(p);
    free(tol);
    printf("tree ray cast: %ld rays (%ld hit), %ld answers differ from the pass over all segments; %.1f%% of "
           "the segments evaluated\n",
           T.cases, T.hits, T.mismatches, 100.0 * (double)T.visited / (double)T.segments);
    ck_assert_int_ge(T.cases, 50000);
    ck_assert(T.hits > T.cases / 4 && T.hits < T.cases - T.cases / 10);
    ck_assert_int_eq(T.mismatches, 0);
    ck_assert(T.visited < T.segments / 4);
}
END_TEST

/* The work: rays across an ellipse of 64 .. 4096 segments evaluate a few segments around each
 * crossing, not all of them. */
START_TEST(test_tree_ray_cast_work) {
    rugo_vec2* p = (rugo_vec2*)xmalloc(4096 * sizeof *p);
    test_rng r = test_rng_seed(0x776f726b);
    for (int n = 64; n <= 4096; n *= 4) {
        for (int k = 0; k < n; ++k) {
            const double th = TWO_PI * k / n;
            p[k] = rugo_v2(0.5 * cos(th), 0.35 * sin(th));
        }
        rugo_shape* s = make_shape(p, n, NULL);
        rugo_contour c;
        rugo_shape_level(s, rugo_shape_finest_level(s), &c);
        int max_visited = 0;
        for (int i = 0; i < 200; ++i) {
            const rugo_vec2 o = random_direction(&r, 2.0);
            const rugo_vec2 d =
                rugo_v2_sub(rugo_v2(test_rng_uniform(&r, -0.3, 0.3), test_rng_uniform(&r, -0.2, 0.2)), o);
            rugo__ray ray;
            ck_assert(rugo__ray_begin(&ray, o, d, 2.0));
            int visited = 0;
            rugo__level_ray_cast(s, rugo_shape_finest_level(s), &ray, &visited);
            max_visited = visited > max_visited ? visited : max_visited;
            double f = 0.0;
            ck_assert(rugo_contour_ray_cast(c, o, d, 2.0, &f, NULL, NULL));
            ck_assert(ray.found && ray.best_s == f);
        }
        printf("ray cast through the tree, %d segments: at most %d segments evaluated per ray\n", n,
               max_visited);
        ck_assert_int_le(max_visited, 16);
        rugo_shape_destroy(s);
    }
    free(p);
}
END_TEST

/* Statuses and outputs on bad input. */
START_TEST(test_shape_ray_cast_bad_input) {
    rugo_vec2 p[16];
    for (int i = 0; i < 16; ++i)
        p[i] = rugo_v2(cos(TWO_PI * i / 16), 0.5 * sin(TWO_PI * i / 16));
    rugo_shape* s = make_shape(p, 16, NULL);
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    const rugo_vec2 o = rugo_v2(-3.0, 0.0), d = rugo_v2(1.0, 0.0);
    double f = -1.0;
    rugo_curve_point cp;
    cp.segment = -5;
    rugo_vec2 n = rugo_v2(9.0, 9.0);
    bool found = true;
    ck_assert_int_eq(rugo_shape_ray_cast(NULL, J, o, d, 10.0, &f, &cp, &n, &found), RUGO_ERR_NULL_ARGUMENT);
    ck_assert(!found);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, 10.0, &f, &cp, &n, NULL), RUGO_ERR_NULL_ARGUMENT);
    const int bad_levels[4] = {J + 1, Jmin - 1, 0, -1};
    for (int i = 0; i < 4; ++i) {
        found = true;
        ck_assert_int_eq(rugo_shape_ray_cast(s, bad_levels[i], o, d, 10.0, &f, &cp, &n, &found),
                         RUGO_ERR_BAD_LEVEL);
        ck_assert(!found);
    }
    const rugo_vec2 bad[4] = {{NAN, 0.0}, {0.0, INFINITY}, {-INFINITY, NAN}, {2e150, 0.0}};
    for (int i = 0; i < 4; ++i) {
        found = true;
        ck_assert_int_eq(rugo_shape_ray_cast(s, J, bad[i], d, 10.0, &f, &cp, &n, &found),
                         RUGO_ERR_NOT_FINITE);
        ck_assert(!found);
        found = true;
        ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, bad[i], 10.0, &f, &cp, &n, &found),
                         RUGO_ERR_NOT_FINITE);
        ck_assert(!found);
    }
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, NAN, &f, &cp, &n, &found), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, INFINITY, &f, &cp, &n, &found), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, -1.0, &f, &cp, &n, &found), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, rugo_v2(0.0, 0.0), 10.0, &f, &cp, &n, &found),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, rugo_v2(1e-170, 0.0), 10.0, &f, &cp, &n, &found),
                     RUGO_ERR_BAD_ARGUMENT); /* |d|^2 underflows */
    ck_assert(!found);
    /* nothing written on errors or without a hit */
    ck_assert(f == -1.0 && cp.segment == -5 && n.x == 9.0 && n.y == 9.0);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, 1.0, &f, &cp, &n, &found), RUGO_OK); /* stops short */
    ck_assert(!found);
    ck_assert(f == -1.0 && cp.segment == -5 && n.x == 9.0 && n.y == 9.0);
    /* valid input answers, with or without the optional outputs; up to 1e150 the ray is fine */
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, d, 10.0, &f, &cp, &n, &found), RUGO_OK);
    ck_assert(found && f > 1.9 && f < 2.1 && n.x < -0.99 && cp.distance == f);
    ck_assert_int_eq(rugo_shape_ray_cast(s, Jmin, o, d, 10.0, NULL, NULL, NULL, &found), RUGO_OK);
    ck_assert(found);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, rugo_v2(-1e150, 0.0), d, 2e150, &f, &cp, &n, &found), RUGO_OK);
    ck_assert(found && f > 0.99e150);
    ck_assert_int_eq(rugo_shape_ray_cast(s, J, o, rugo_v2(1e150, 0.0), 1.0, &f, &cp, &n, &found), RUGO_OK);
    ck_assert(found && f > 1.9e-150 && f < 2.1e-150);
    rugo_shape_destroy(s);
}
END_TEST

static Suite* point_query_suite(void) {
    Suite* s = suite_create("point_query");
    TCase* t = tcase_create("ray_cast");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, test_tree_ray_cast_matches_contour);
    tcase_add_test(t, test_tree_ray_cast_work);
    tcase_add_test(t, test_shape_ray_cast_bad_input);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return test_run_suite(point_query_suite()); }
