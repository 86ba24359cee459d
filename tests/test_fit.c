/* Suite "fit": least-squares contour fitting and simultaneous multi-point manipulation (rugo/fit.h). */
#include "rugo/fit.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI 6.283185307179586

/* Samples of the curve of ctrl (n points) at the uniform parameters u_k = k n / m. */
static void sample_uniform(const rugo_vec2* ctrl, int n, int m, rugo_vec2* out) {
    rugo_contour c = {ctrl, n};
    for (int k = 0; k < m; ++k)
        out[k] = rugo_contour_point_at(c, (double)k * n / m);
}

static rugo_fit_def make_def(const rugo_vec2* samples, int m, int n, rugo_parameterization param) {
    rugo_fit_def d = rugo_default_fit_def();
    d.samples = samples;
    d.sample_count = m;
    d.control_count = n;
    d.parameterization = param;
    return d;
}

/* ---------------------------------------------------------------------------------------------- */

START_TEST(default_def) {
    rugo_fit_def d = rugo_default_fit_def();
    ck_assert_int_eq(d.parameterization, RUGO_PARAM_CHORD_LENGTH);
    ck_assert_ptr_null(d.samples);
    ck_assert(d.allocator.alloc == NULL && d.allocator.free == NULL);
    ck_assert_int_ne(d.cookie, 0);
    /* Two defaults are identical (the cookie is a constant, not an address or a counter). */
    rugo_fit_def e = rugo_default_fit_def();
    ck_assert_int_eq(memcmp(&d, &e, sizeof d), 0);
}
END_TEST

/* Acceptance: samples at the uniform parameters of a known 2^J-point contour give back its control
 * points with RUGO_PARAM_UNIFORM, for J = 2..8 and several sample densities (including sample counts
 * that are not multiples of n, so the samples fall at varying t). */
START_TEST(uniform_recovers_control_points) {
    static const int per_segment_num[] = {1, 2, 3, 5, 8, 7};
    static const int per_segment_den[] = {1, 1, 1, 2, 1, 3}; /* m = n * num / den + extra */
    double worst_ctrl = 0.0, worst_err = 0.0;
    test_rng rng = test_rng_seed(20240601u);
    for (int J = 2; J <= 8; ++J) {
        const int n = 1 << J;
        for (int v = 0; v < 6; ++v) {
            const int m = n * per_segment_num[v] / per_segment_den[v] + (per_segment_den[v] > 1 ? 1 : 0);
            if (m < n) continue;
            const double radius = test_rng_uniform(&rng, 0.5, 50.0);
            const rugo_vec2 centre =
                rugo_v2(test_rng_uniform(&rng, -1e3, 1e3), test_rng_uniform(&rng, -1e3, 1e3));
            rugo_vec2* truth = malloc((size_t)n * sizeof *truth);
            rugo_vec2* fitted = malloc((size_t)n * sizeof *fitted);
            rugo_vec2* samples = malloc((size_t)m * sizeof *samples);
            test_random_star(&rng, n, centre, radius, 0.35, truth);
            sample_uniform(truth, n, m, samples);
            rugo_fit_def d = make_def(samples, m, n, RUGO_PARAM_UNIFORM);
            rugo_fit_result res = {-1.0, -1.0};
            ck_assert_int_eq(rugo_fit_contour(&d, fitted, &res), RUGO_OK);
            const double ctrl_err = test_max_diff(truth, fitted, n) / radius;
            ck_assert_msg(ctrl_err <= 1e-9, "J=%d m=%d: control points off by %.3g of size", J, m, ctrl_err);
            ck_assert_msg(res.max_error / radius <= 1e-9, "J=%d m=%d: max_error %.3g", J, m, res.max_error);
            ck_assert(res.rms_error >= 0.0 && res.rms_error <= res.max_error);
            if (ctrl_err > worst_ctrl) worst_ctrl = ctrl_err;
            if (res.max_error / radius > worst_err) worst_err = res.max_error / radius;
            free(truth);
            free(fitted);
            free(samples);
        }
    }
    printf("fit: uniform recovery, J=2..8: worst control-point error %.3g, worst max_error %.3g (of size)\n",
           worst_ctrl, worst_err);
}
END_TEST

/* Chord-length parameters differ from the generating (uniform) ones, so the fit is approximate; for
 * dense samples (8 per segment) of a smooth star the error must be small, and shrink fast (the
 * cubic's h^4) as the same shape gets more control points. The measured numbers are printed. */
START_TEST(chord_length_dense_star) {
    static const uint64_t seeds[] = {77u, 78u, 79u};
    for (int v = 0; v < 3; ++v) {
        double previous = 0.0;
        for (int J = 4; J <= 8; ++J) {
            const int n = 1 << J, m = 8 * n;
            const double radius = 10.0;
            rugo_vec2* truth = malloc((size_t)n * sizeof *truth);
            rugo_vec2* fitted = malloc((size_t)n * sizeof *fitted);
            rugo_vec2* samples = malloc((size_t)m * sizeof *samples);
            /* Same seed: the same smooth shape (harmonics 2..5) at every J. */
            test_rng rng = test_rng_seed(seeds[v]);
            test_random_star(&rng, n, rugo_v2(3.0, -2.0), radius, 0.2, truth);
            sample_uniform(truth, n, m, samples);
            rugo_fit_def d = make_def(samples, m, n, RUGO_PARAM_CHORD_LENGTH);
            rugo_fit_result res;
            ck_assert_int_eq(rugo_fit_contour(&d, fitted, &res), RUGO_OK);
            const double rel = res.max_error / radius;
            printf(
                "fit: chord-length, star %d, J=%d, 8 samples/segment: max_error %.3g, rms %.3g (of size)\n",
                v, J, rel, res.rms_error / radius);
            /* J = 4, 5: the star's fifth harmonic has only 3 to 6 control points per wave. */
            ck_assert_msg(rel < (J >= 6 ? 1e-3 : 1e-2), "J=%d: chord-length max_error %.3g of size", J, rel);
            if (J >= 6)
                ck_assert_msg(rel < previous / 4.0, "J=%d: error %.3g did not drop from %.3g", J, rel,
                              previous);
            previous = rel;
            ck_assert(res.rms_error > 0.0 && res.rms_error <= res.max_error);
            /* The reported error is what it says: recompute it from the fitted curve. */
            rugo_contour c = {fitted, n};
            double total = 0.0, maxe = 0.0, sumsq = 0.0;
            double* cum = malloc((size_t)m * sizeof *cum);
            for (int k = 0; k < m; ++k) {
                cum[k] = total;
                rugo_vec2 a = samples[k], b = samples[(k + 1) % m];
                total += hypot(b.x - a.x, b.y - a.y);
            }
            for (int k = 0; k < m; ++k) {
                rugo_vec2 f = rugo_contour_point_at(c, cum[k] / total * n);
                double e = hypot(f.x - samples[k].x, f.y - samples[k].y);
                if (e > maxe) maxe = e;
                sumsq += e * e;
            }
            ck_assert_near(res.max_error, maxe, 1e-6 * res.max_error + 1e-12);
            ck_assert_near(res.rms_error, sqrt(sumsq / m), 1e-6 * res.rms_error + 1e-12);
            free(cum);
            free(truth);
            free(fitted);
            free(samples);
        }
    }
}
END_TEST

/* A circle sampled densely: by its symmetry the least-squares control points form a regular n-gon of
 * some radius R (the problem is invariant under rotation by 2 pi / n with an index shift, and under
 * reflection), so an independent one-unknown least squares gives R and the exact fit error. */
START_TEST(circle_known_error) {
    static const int ns[] = {8, 16, 32, 64};
    for (int v = 0; v < 4; ++v) {
        const int n = ns[v], m = 16 * n;
        const double r0 = 2.5;
        rugo_vec2* samples = malloc((size_t)m * sizeof *samples);
        rugo_vec2* unit = malloc((size_t)n * sizeof *unit);
        rugo_vec2* fitted = malloc((size_t)n * sizeof *fitted);
        for (int k = 0; k < m; ++k)
            samples[k] = rugo_v2(r0 * cos(TWO_PI * k / m), r0 * sin(TWO_PI * k / m));
        for (int j = 0; j < n; ++j)
            unit[j] = rugo_v2(cos(TWO_PI * j / n), sin(TWO_PI * j / n));
        rugo_contour uc = {unit, n};
        double num = 0.0, den = 0.0;
        for (int k = 0; k < m; ++k) {
            rugo_vec2 g = rugo_contour_point_at(uc, (double)k * n / m);
            num += rugo_v2_dot(g, samples[k]);
            den += rugo_v2_dot(g, g);
        }
        const double R = num / den;
        double expect_max = 0.0;
        for (int k = 0; k < m; ++k) {
            rugo_vec2 g = rugo_contour_point_at(uc, (double)k * n / m);
            double e = hypot(R * g.x - samples[k].x, R * g.y - samples[k].y);
            if (e > expect_max) expect_max = e;
        }
        rugo_fit_def d = make_def(samples, m, n, RUGO_PARAM_CHORD_LENGTH);
        rugo_fit_result res;
        ck_assert_int_eq(rugo_fit_contour(&d, fitted, &res), RUGO_OK);
        for (int j = 0; j < n; ++j) {
            ck_assert_near(fitted[j].x, R * unit[j].x, 1e-12 * r0);
            ck_assert_near(fitted[j].y, R * unit[j].y, 1e-12 * r0);
        }
        ck_assert_near(res.max_error, expect_max, 1e-12 * r0);
        printf("fit: circle, n=%d, %d samples: R/r = %.12f, max_error %.3g, rms %.3g (of radius)\n", n, m,
               R / r0, res.max_error / r0, res.rms_error / r0);
        /* The cubic B-spline's error on a circle falls like (2 pi / n)^4. */
        const double h = TWO_PI / n;
        ck_assert(res.max_error / r0 < 0.01 * h * h * h * h);
        free(samples);
        free(unit);
        free(fitted);
    }
}
END_TEST

START_TEST(bad_input_statuses) {
    enum { N = 16, M = 64 };
    rugo_vec2 truth[N], samples[M], out[N];
    test_rng rng = test_rng_seed(5u);
    test_random_star(&rng, N, rugo_v2(0.0, 0.0), 1.0, 0.3, truth);
    sample_uniform(truth, N, M, samples);
    rugo_fit_def good = make_def(samples, M, N, RUGO_PARAM_CHORD_LENGTH);
    rugo_fit_result res;
    ck_assert_int_eq(rugo_fit_contour(&good, out, &res), RUGO_OK);

    ck_assert_int_eq(rugo_fit_contour(NULL, out, &res), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_fit_contour(&good, NULL, &res), RUGO_ERR_NULL_ARGUMENT);
    rugo_fit_def d = good;
    d.samples = NULL;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_NULL_ARGUMENT);

    /* A def not made by rugo_default_fit_def. */
    memset(&d, 0, sizeof d);
    d.samples = samples;
    d.sample_count = M;
    d.control_count = N;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);

    d = good;
    d.control_count = 2;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_TOO_FEW_POINTS);
    d.control_count = -8;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_TOO_FEW_POINTS);
    d.control_count = 12;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_NOT_POWER_OF_TWO);
    d.control_count = 2 * RUGO_MAX_CONTROL_POINTS;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_TOO_MANY_POINTS);

    d = good;
    d.sample_count = RUGO_MAX_CONTROL_POINTS + 1;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_TOO_MANY_POINTS);
    d.sample_count = N - 1; /* fewer samples than control points */
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);
    d.sample_count = -1;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);

    d = good;
    d.parameterization = (rugo_parameterization)7;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);
    d.parameterization = (rugo_parameterization)-1;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);

    rugo_vec2 bad[M];
    memcpy(bad, samples, sizeof bad);
    bad[17].y = NAN;
    d = good;
    d.samples = bad;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_NOT_FINITE);
    bad[17].y = samples[17].y;
    bad[M - 1].x = -INFINITY;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_NOT_FINITE);

    /* Repeated consecutive samples make a zero chord: refused for chord-length parameters... */
    memcpy(bad, samples, sizeof bad);
    bad[30] = bad[29];
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);
    /* ...including the closing edge (the last sample repeating the first)... */
    memcpy(bad, samples, sizeof bad);
    bad[M - 1] = bad[0];
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_BAD_ARGUMENT);
    /* ...but harmless with uniform parameters. */
    d.parameterization = RUGO_PARAM_UNIFORM;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
    memcpy(bad, samples, sizeof bad);
    bad[30] = bad[29];
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
}
END_TEST

/* Coordinates near the top of the double range: the fit works in normalised coordinates, so the
 * answer stays finite, or the status says the control points cannot be represented. */
START_TEST(extreme_coordinates) {
    enum { N = 8, M = 32 };
    rugo_vec2 truth[N], samples[M], out[N];
    test_rng rng = test_rng_seed(9u);
    test_random_star(&rng, N, rugo_v2(0.0, 0.0), 1.0, 0.3, truth);
    sample_uniform(truth, N, M, samples);
    static const double scales[] = {1e-300, 1e-150, 1e150, 1e300};
    for (int v = 0; v < 4; ++v) {
        rugo_vec2 big[M], big_truth[N];
        for (int k = 0; k < M; ++k)
            big[k] = rugo_v2_scale(scales[v], samples[k]);
        for (int j = 0; j < N; ++j)
            big_truth[j] = rugo_v2_scale(scales[v], truth[j]);
        rugo_fit_def d = make_def(big, M, N, RUGO_PARAM_UNIFORM);
        rugo_fit_result res;
        ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
        ck_assert(test_max_diff(out, big_truth, N) <= 1e-12 * scales[v]);
        ck_assert(res.max_error <= 1e-12 * scales[v]);
        d.parameterization = RUGO_PARAM_CHORD_LENGTH;
        ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
        ck_assert(isfinite(res.max_error) && isfinite(res.rms_error));
    }
    /* Samples spanning almost the whole double range: control points overshoot the samples' hull
     * (a cubic B-spline's control polygon encloses its curve) and cannot be represented. */
    rugo_vec2 huge[M];
    for (int k = 0; k < M; ++k)
        huge[k] = rugo_v2_scale(1.7e308 / 1.5, samples[k]);
    rugo_fit_def d = make_def(huge, M, N, RUGO_PARAM_UNIFORM);
    rugo_fit_result res = {-1.0, -1.0};
    rugo_vec2 before[N];
    for (int j = 0; j < N; ++j)
        out[j] = before[j] = rugo_v2(1.0, 2.0);
    rugo_status st = rugo_fit_contour(&d, out, &res);
    ck_assert(st == RUGO_OK || st == RUGO_ERR_NOT_FINITE);
    if (st != RUGO_OK) {
        ck_assert_int_eq(memcmp(out, before, sizeof out), 0);
        ck_assert(res.max_error == -1.0);
    }
}
END_TEST

/* Rank-deficient problems: samples clustered so that some control points are undetermined. */
START_TEST(singular_fits) {
    enum { N = 8, M = 12 };
    rugo_vec2 samples[M], out[N];
    /* Eleven samples within a tiny arc, one far away: chord-length parameters put eleven samples in
     * segment 0 and one near u = n/2, leaving control points free. */
    for (int k = 0; k < M - 1; ++k)
        samples[k] = rugo_v2(1e-6 * k, 1e-6 * k * k);
    samples[M - 1] = rugo_v2(5.0, 3.0);
    rugo_fit_def d = make_def(samples, M, N, RUGO_PARAM_CHORD_LENGTH);
    rugo_fit_result res = {-1.0, -1.0};
    for (int j = 0; j < N; ++j)
        out[j] = rugo_v2(42.0, 42.0);
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_ERR_SINGULAR);
    /* Outputs untouched on error. */
    for (int j = 0; j < N; ++j)
        ck_assert(out[j].x == 42.0 && out[j].y == 42.0);
    ck_assert(res.max_error == -1.0 && res.rms_error == -1.0);

    /* The same points with uniform parameters are well posed (every segment gets a sample). */
    d.parameterization = RUGO_PARAM_UNIFORM;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);

    /* Two clusters: segments between them are empty. */
    rugo_vec2 two[16];
    for (int k = 0; k < 8; ++k)
        two[k] = rugo_v2(1e-5 * k, 1e-5 * k * k);
    for (int k = 0; k < 8; ++k)
        two[8 + k] = rugo_v2(10.0 - 1e-5 * k, 10.0 + 2e-5 * k * k);
    d = make_def(two, 16, 16, RUGO_PARAM_CHORD_LENGTH);
    rugo_vec2 out16[16];
    ck_assert_int_eq(rugo_fit_contour(&d, out16, &res), RUGO_ERR_SINGULAR);

    /* Four clusters of four points on the unit circle: every control point has samples in its
     * support, but each cluster pins down only about two of them, so the problem is (numerically)
     * rank deficient until the clusters spread out; the pivot test decides. */
    static const double spreads[] = {1e-12, 1e-9, 1e-6, 1e-4, 1e-2};
    for (int v = 0; v < 5; ++v) {
        rugo_vec2 pts[16];
        for (int c = 0; c < 4; ++c)
            for (int i = 0; i < 4; ++i) {
                const double a = TWO_PI * c / 4 + spreads[v] * i;
                pts[4 * c + i] = rugo_v2(cos(a), sin(a));
            }
        d = make_def(pts, 16, 8, RUGO_PARAM_CHORD_LENGTH);
        rugo_vec2 out8[8];
        ck_assert_int_eq(rugo_fit_contour(&d, out8, &res), spreads[v] < 1e-3 ? RUGO_ERR_SINGULAR : RUGO_OK);
    }
}
END_TEST

/* m == n with uniform parameters is interpolation at the knots (the cyclic (1, 4, 1)/6 system), which
 * is always well posed: the fit interpolates. */
START_TEST(interpolation_when_m_equals_n) {
    enum { N = 32 };
    rugo_vec2 samples[N], out[N];
    test_rng rng = test_rng_seed(31u);
    test_random_points(&rng, N, 3.0, samples); /* not even an outline: still a linear problem */
    rugo_fit_def d = make_def(samples, N, N, RUGO_PARAM_UNIFORM);
    rugo_fit_result res;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
    ck_assert(res.max_error <= 1e-13 * 3.0);
    rugo_contour c = {out, N};
    for (int k = 0; k < N; ++k) {
        rugo_vec2 f = rugo_contour_point(c, k, 0.0);
        ck_assert_near(f.x, samples[k].x, 1e-13 * 3.0);
        ck_assert_near(f.y, samples[k].y, 1e-13 * 3.0);
    }
    /* All samples equal: the fit is that point. */
    for (int k = 0; k < N; ++k)
        samples[k] = rugo_v2(-7.5, 1e9);
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
    for (int k = 0; k < N; ++k)
        ck_assert(out[k].x == -7.5 && out[k].y == 1e9);
    ck_assert(res.max_error <= 1e-15 * 1e9);
}
END_TEST

START_TEST(properties) {
    enum { N = 32, M = 200 };
    rugo_vec2 truth[N], samples[M], a[N], b[N];
    test_rng rng = test_rng_seed(123u);
    test_random_star(&rng, N, rugo_v2(1.0, 2.0), 4.0, 0.4, truth);
    for (int k = 0; k < M; ++k) {
        /* Irregular parameters plus noise: a genuine approximation problem. */
        double u = (k + 0.4 * sin(3.0 * k)) * N / M;
        rugo_contour c = {truth, N};
        samples[k] = rugo_v2_add(rugo_contour_point_at(c, u), rugo_v2(test_rng_uniform(&rng, -0.01, 0.01),
                                                                      test_rng_uniform(&rng, -0.01, 0.01)));
    }
    rugo_fit_def d = make_def(samples, M, N, RUGO_PARAM_CHORD_LENGTH);
    rugo_fit_result ra, rb;
    /* Deterministic: bit-identical run after run. */
    ck_assert_int_eq(rugo_fit_contour(&d, a, &ra), RUGO_OK);
    ck_assert_int_eq(rugo_fit_contour(&d, b, &rb), RUGO_OK);
    ck_assert_int_eq(memcmp(a, b, sizeof a), 0);
    ck_assert_int_eq(memcmp(&ra, &rb, sizeof ra), 0);
    ck_assert(ra.max_error < 0.1 && ra.rms_error < ra.max_error);
    /* result may be NULL. */
    ck_assert_int_eq(rugo_fit_contour(&d, b, NULL), RUGO_OK);
    ck_assert_int_eq(memcmp(a, b, sizeof a), 0);

    /* Equivariant under similarity transforms (rotation, scale, translation). */
    rugo_vec2 moved[M];
    const double cs = cos(0.7) * 1e3, sn = sin(0.7) * 1e3;
    for (int k = 0; k < M; ++k)
        moved[k] =
            rugo_v2(cs * samples[k].x - sn * samples[k].y + 5e5, sn * samples[k].x + cs * samples[k].y - 2e5);
    d.samples = moved;
    ck_assert_int_eq(rugo_fit_contour(&d, b, &rb), RUGO_OK);
    for (int j = 0; j < N; ++j) {
        ck_assert_near(b[j].x, cs * a[j].x - sn * a[j].y + 5e5, 1e-9 * 4e3);
        ck_assert_near(b[j].y, sn * a[j].x + cs * a[j].y - 2e5, 1e-9 * 4e3);
    }
    ck_assert_near(rb.max_error, 1e3 * ra.max_error, 1e-9 * rb.max_error + 1e-9);

    /* Orientation kept: clockwise samples give a clockwise contour. */
    rugo_vec2 rev[M];
    for (int k = 0; k < M; ++k)
        rev[k] = samples[M - 1 - k];
    d.samples = rev;
    ck_assert_int_eq(rugo_fit_contour(&d, b, &rb), RUGO_OK);
    rugo_contour cb = {b, N}, ca = {a, N};
    ck_assert(rugo_contour_signed_area(cb) < 0.0);
    ck_assert(rugo_contour_signed_area(ca) > 0.0);
    ck_assert_near(-rugo_contour_signed_area(cb), rugo_contour_signed_area(ca),
                   1e-3 * rugo_contour_signed_area(ca));
}
END_TEST

/* The caller's allocator carries every buffer the fit sizes itself; a failing allocator gives
 * OUT_OF_MEMORY at every point of failure, without leaks. */
typedef struct counting {
    int allocs, frees, live, fail_at;
} counting;
static void* count_alloc(size_t size, void* ctx) {
    counting* c = ctx;
    if (c->fail_at >= 0 && c->allocs == c->fail_at) return NULL;
    ++c->allocs;
    ++c->live;
    return malloc(size);
}
static void count_free(void* p, void* ctx) {
    counting* c = ctx;
    if (p != NULL) {
        ++c->frees;
        --c->live;
    }
    free(p);
}

START_TEST(allocator_used_and_failures_reported) {
    enum { N = 16, M = 64 };
    rugo_vec2 truth[N], samples[M], out[N], ref[N];
    test_rng rng = test_rng_seed(8u);
    test_random_star(&rng, N, rugo_v2(0.0, 0.0), 1.0, 0.3, truth);
    sample_uniform(truth, N, M, samples);
    rugo_fit_def d = make_def(samples, M, N, RUGO_PARAM_CHORD_LENGTH);
    ck_assert_int_eq(rugo_fit_contour(&d, ref, NULL), RUGO_OK);
    counting cnt = {0, 0, 0, -1};
    d.allocator.alloc = count_alloc;
    d.allocator.free = count_free;
    d.allocator.ctx = &cnt;
    ck_assert_int_eq(rugo_fit_contour(&d, out, NULL), RUGO_OK);
    ck_assert_int_eq(memcmp(out, ref, sizeof out), 0);
    ck_assert_int_gt(cnt.allocs, 0);
    ck_assert_int_eq(cnt.live, 0);
    const int total = cnt.allocs;
    for (int f = 0; f < total; ++f) {
        counting c2 = {0, 0, 0, f};
        d.allocator.ctx = &c2;
        ck_assert_int_eq(rugo_fit_contour(&d, out, NULL), RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_int_eq(c2.live, 0);
    }
}
END_TEST

/* A big problem (n = 2^14, four samples per segment) to show the sparse path's O(n) behaviour. */
START_TEST(large_fit) {
    const int n = 1 << 14, m = 4 * n;
    rugo_vec2* truth = malloc((size_t)n * sizeof *truth);
    rugo_vec2* out = malloc((size_t)n * sizeof *out);
    rugo_vec2* samples = malloc((size_t)m * sizeof *samples);
    test_rng rng = test_rng_seed(4u);
    test_random_star(&rng, n, rugo_v2(0.0, 0.0), 100.0, 0.3, truth);
    sample_uniform(truth, n, m, samples);
    rugo_fit_def d = make_def(samples, m, n, RUGO_PARAM_UNIFORM);
    rugo_fit_result res;
    ck_assert_int_eq(rugo_fit_contour(&d, out, &res), RUGO_OK);
    ck_assert(test_max_diff(out, truth, n) <= 1e-9 * 100.0);
    ck_assert(res.max_error <= 1e-9 * 100.0);
    free(truth);
    free(out);
    free(samples);
}
END_TEST

/* ---------------------------------------------------------------------------------------------- */
/* rugo_pyramid_move_points */

enum { PJ = 6, PN = 1 << PJ };

static rugo_pyramid* make_pyramid(uint64_t seed, rugo_vec2* finest_out) {
    rugo_vec2 pts[PN];
    test_rng rng = test_rng_seed(seed);
    test_random_star(&rng, PN, rugo_v2(2.0, -1.0), 10.0, 0.3, pts);
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = pts;
    def.count = PN;
    rugo_pyramid* p = NULL;
    ck_assert_int_eq(rugo_pyramid_create(&def, &p, NULL), RUGO_OK);
    ck_assert_ptr_nonnull(p);
    if (finest_out != NULL) memcpy(finest_out, pts, sizeof pts);
    return p;
}

static void level_points(const rugo_pyramid* p, int level, rugo_vec2* out) {
    rugo_contour c;
    ck_assert_int_eq(rugo_pyramid_level(p, level, &c), RUGO_OK);
    memcpy(out, c.points, (size_t)c.count * sizeof *out);
}

static rugo_vec2 level_point(const rugo_pyramid* p, int level, int segment, double t) {
    rugo_contour c;
    ck_assert_int_eq(rugo_pyramid_level(p, level, &c), RUGO_OK);
    return rugo_contour_point(c, segment, t);
}

/* Every constrained point lands at old + delta on its level; in FIXED mode the corresponding finest
 * points move by the same deltas (synthesis is linear and refinement keeps the curve). */
static void check_landing(rugo_detail_mode mode, int level, int count, const int* segs, const double* ts,
                          const rugo_vec2* deltas) {
    rugo_pyramid* p = make_pyramid(1000u + (uint64_t)level, NULL);
    const int J = rugo_pyramid_finest_level(p);
    rugo_vec2 before[64], fine_before[64];
    for (int i = 0; i < count; ++i) {
        before[i] = level_point(p, level, segs[i], ts[i]);
        int fs;
        double ft;
        rugo_level_parameter(level, segs[i], ts[i], J, &fs, &ft);
        fine_before[i] = level_point(p, J, fs, ft);
    }
    ck_assert_int_eq(rugo_pyramid_move_points(p, level, count, segs, ts, deltas, mode), RUGO_OK);
    for (int i = 0; i < count; ++i) {
        rugo_vec2 after = level_point(p, level, segs[i], ts[i]);
        ck_assert_near(after.x, before[i].x + deltas[i].x, 1e-9 * 10.0);
        ck_assert_near(after.y, before[i].y + deltas[i].y, 1e-9 * 10.0);
        if (mode == RUGO_DETAILS_FIXED) {
            int fs;
            double ft;
            rugo_level_parameter(level, segs[i], ts[i], J, &fs, &ft);
            rugo_vec2 fa = level_point(p, J, fs, ft);
            ck_assert_near(fa.x, fine_before[i].x + deltas[i].x, 1e-9 * 10.0);
            ck_assert_near(fa.y, fine_before[i].y + deltas[i].y, 1e-9 * 10.0);
        }
    }
    rugo_pyramid_destroy(p);
}

START_TEST(move_two_points_land) {
    const int segs[2] = {3, 9};
    const double ts[2] = {0.3, 0.75};
    const rugo_vec2 deltas[2] = {{0.5, -0.25}, {-0.3, 0.8}};
    for (int mode = 0; mode < 2; ++mode) {
        for (int level = 4; level <= PJ; ++level)
            check_landing((rugo_detail_mode)mode, level, 2, segs, ts, deltas);
        /* Overlapping supports (adjacent segments) and a wrap-around pair. */
        const int segs2[2] = {4, 5}, segs3[2] = {15, 0};
        check_landing((rugo_detail_mode)mode, 4, 2, segs2, ts, deltas);
        check_landing((rugo_detail_mode)mode, 4, 2, segs3, ts, deltas);
    }
}
END_TEST

START_TEST(move_many_points_land) {
    /* Eight points in clusters on a 16-point level, including two on one segment and the ends. */
    const int segs[8] = {0, 0, 1, 5, 6, 10, 15, 15};
    const double ts[8] = {0.0, 0.6, 0.5, 1.0, 0.25, 0.5, 0.1, 0.9};
    rugo_vec2 deltas[8];
    test_rng rng = test_rng_seed(66u);
    for (int i = 0; i < 8; ++i)
        deltas[i] = rugo_v2(test_rng_uniform(&rng, -1, 1), test_rng_uniform(&rng, -1, 1));
    check_landing(RUGO_DETAILS_FIXED, 4, 8, segs, ts, deltas);
    check_landing(RUGO_DETAILS_LOCAL, 4, 8, segs, ts, deltas);
    /* Four generic points on the coarsest 4-point level determine all four control points. */
    const int s4[4] = {0, 1, 2, 3};
    const double t4[4] = {0.1, 0.4, 0.7, 0.95};
    check_landing(RUGO_DETAILS_FIXED, 2, 4, s4, t4, deltas);
    check_landing(RUGO_DETAILS_FIXED, PJ, 8, segs, ts, deltas);
}
END_TEST

/* The displacement is the least-norm one: compare with ΔC = N^T (N N^T)^{-1} ΔF computed here by
 * hand for two overlapping constraints, and check that nothing outside their supports moved. */
START_TEST(move_points_least_norm) {
    const int level = 4, n = 16;
    const int segs[2] = {6, 7};
    const double ts[2] = {0.2, 0.65};
    const rugo_vec2 deltas[2] = {{0.4, 0.1}, {-0.2, 0.3}};
    double rows[2][16];
    memset(rows, 0, sizeof rows);
    for (int i = 0; i < 2; ++i) {
        double b[4];
        rugo_bspline_basis(ts[i], b);
        for (int a = 0; a < 4; ++a)
            rows[i][(segs[i] - 1 + a + n) % n] += b[a];
    }
    double g[2][2] = {{0, 0}, {0, 0}};
    for (int i = 0; i < 2; ++i)
        for (int k = 0; k < 2; ++k)
            for (int j = 0; j < n; ++j)
                g[i][k] += rows[i][j] * rows[k][j];
    const double det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    rugo_vec2 y[2];
    y[0] = rugo_v2((g[1][1] * deltas[0].x - g[0][1] * deltas[1].x) / det,
                   (g[1][1] * deltas[0].y - g[0][1] * deltas[1].y) / det);
    y[1] = rugo_v2((-g[1][0] * deltas[0].x + g[0][0] * deltas[1].x) / det,
                   (-g[1][0] * deltas[0].y + g[0][0] * deltas[1].y) / det);

    rugo_pyramid* p = make_pyramid(7u, NULL);
    rugo_vec2 before[16], after[16];
    level_points(p, level, before);
    ck_assert_int_eq(rugo_pyramid_move_points(p, level, 2, segs, ts, deltas, RUGO_DETAILS_FIXED), RUGO_OK);
    level_points(p, level, after);
    for (int j = 0; j < n; ++j) {
        const double ex = rows[0][j] * y[0].x + rows[1][j] * y[1].x;
        const double ey = rows[0][j] * y[0].y + rows[1][j] * y[1].y;
        ck_assert_near(after[j].x - before[j].x, ex, 1e-12 * 10.0);
        ck_assert_near(after[j].y - before[j].y, ey, 1e-12 * 10.0);
    }
    rugo_pyramid_destroy(p);
}
END_TEST

/* One point: identical (to round-off) to rugo_pyramid_move_point, in both detail modes and on every
 * level, including the segment ends t = 0 and t = 1. */
START_TEST(single_point_equals_move_point) {
    static const double ts[] = {0.0, 0.37, 0.5, 1.0};
    for (int mode = 0; mode < 2; ++mode) {
        for (int level = 2; level <= PJ; ++level) {
            for (int v = 0; v < 4; ++v) {
                rugo_pyramid* a = make_pyramid(55u, NULL);
                rugo_pyramid* b = make_pyramid(55u, NULL);
                const int seg = (5 * level + v) % (1 << level);
                const rugo_vec2 delta = rugo_v2(0.7, -0.45);
                ck_assert_int_eq(rugo_pyramid_move_point(a, level, seg, ts[v], delta, (rugo_detail_mode)mode),
                                 RUGO_OK);
                ck_assert_int_eq(
                    rugo_pyramid_move_points(b, level, 1, &seg, &ts[v], &delta, (rugo_detail_mode)mode),
                    RUGO_OK);
                for (int l = 2; l <= PJ; ++l) {
                    rugo_vec2 pa[PN], pb[PN];
                    level_points(a, l, pa);
                    level_points(b, l, pb);
                    ck_assert_msg(test_max_diff(pa, pb, 1 << l) <= 1e-12 * 10.0,
                                  "mode %d level %d t %g: level %d differs by %g", mode, level, ts[v], l,
                                  test_max_diff(pa, pb, 1 << l));
                }
                rugo_pyramid_destroy(a);
                rugo_pyramid_destroy(b);
            }
        }
    }
}
END_TEST

static void expect_singular_unchanged(int level, int count, const int* segs, const double* ts,
                                      const rugo_vec2* deltas) {
    rugo_pyramid* p = make_pyramid(3u, NULL);
    rugo_vec2 before[PN], after[PN];
    level_points(p, PJ, before);
    ck_assert_int_eq(rugo_pyramid_move_points(p, level, count, segs, ts, deltas, RUGO_DETAILS_FIXED),
                     RUGO_ERR_SINGULAR);
    level_points(p, PJ, after);
    ck_assert_int_eq(memcmp(before, after, sizeof before), 0);
    rugo_pyramid_destroy(p);
}

START_TEST(conflicting_constraints_singular) {
    /* The same point twice with different deltas. */
    {
        const int segs[3] = {2, 5, 5};
        const double ts[3] = {0.5, 0.3, 0.3};
        const rugo_vec2 deltas[3] = {{0.1, 0.1}, {1.0, 0.0}, {0.0, 1.0}};
        expect_singular_unchanged(4, 3, segs, ts, deltas);
    }
    /* The same point named two ways: end of segment 5 = start of segment 6. */
    {
        const int segs[2] = {5, 6};
        const double ts[2] = {1.0, 0.0};
        const rugo_vec2 deltas[2] = {{1.0, 0.0}, {1.0, 0.5}};
        expect_singular_unchanged(4, 2, segs, ts, deltas);
        /* Wrapping: end of the last segment = start of segment 0. */
        const int segs_w[2] = {15, 0};
        expect_singular_unchanged(4, 2, segs_w, ts, deltas);
    }
    /* Two points 1e-12 apart in parameter with different deltas: numerically the same point. */
    {
        const int segs[2] = {5, 5};
        const double ts[2] = {0.4, 0.4 + 1e-12};
        const rugo_vec2 deltas[2] = {{1.0, 0.0}, {0.0, 1.0}};
        expect_singular_unchanged(4, 2, segs, ts, deltas);
    }
    /* A conflict in a tiny component is not hidden by a large move elsewhere. */
    {
        const int segs[3] = {1, 9, 9};
        const double ts[3] = {0.5, 0.3, 0.3};
        const rugo_vec2 deltas[3] = {{1e6, 0.0}, {1e-3, 0.0}, {0.0, 1e-3}};
        expect_singular_unchanged(4, 3, segs, ts, deltas);
    }
    /* Five points on one segment with unrelated deltas: only four control points to move. */
    {
        const int segs[5] = {7, 7, 7, 7, 7};
        const double ts[5] = {0.0, 0.2, 0.4, 0.6, 0.8};
        rugo_vec2 deltas[5];
        test_rng rng = test_rng_seed(2u);
        for (int i = 0; i < 5; ++i)
            deltas[i] = rugo_v2(test_rng_uniform(&rng, -1, 1), test_rng_uniform(&rng, -1, 1));
        expect_singular_unchanged(4, 5, segs, ts, deltas);
        expect_singular_unchanged(PJ, 5, segs, ts, deltas);
    }
}
END_TEST

START_TEST(consistent_dependent_constraints_accepted) {
    /* The same point twice with the same delta. */
    const int segs[3] = {2, 5, 5};
    const double ts[3] = {0.5, 0.3, 0.3};
    const rugo_vec2 deltas[3] = {{0.1, 0.1}, {1.0, -0.5}, {1.0, -0.5}};
    check_landing(RUGO_DETAILS_FIXED, 4, 3, segs, ts, deltas);
    /* ...and it moves exactly as the point given once. */
    rugo_pyramid* a = make_pyramid(1004u, NULL);
    rugo_pyramid* b = make_pyramid(1004u, NULL);
    ck_assert_int_eq(rugo_pyramid_move_points(a, 4, 3, segs, ts, deltas, RUGO_DETAILS_FIXED), RUGO_OK);
    ck_assert_int_eq(rugo_pyramid_move_points(b, 4, 2, segs, ts, deltas, RUGO_DETAILS_FIXED), RUGO_OK);
    rugo_vec2 pa[PN], pb[PN];
    level_points(a, PJ, pa);
    level_points(b, PJ, pb);
    ck_assert(test_max_diff(pa, pb, PN) <= 1e-12 * 10.0);
    rugo_pyramid_destroy(a);
    rugo_pyramid_destroy(b);
    /* Five points on one segment all moved by the same delta: a translation of that piece. */
    const int s5[5] = {7, 7, 7, 7, 7};
    const double t5[5] = {0.0, 0.2, 0.4, 0.6, 0.8};
    const rugo_vec2 d5[5] = {{0.3, 0.2}, {0.3, 0.2}, {0.3, 0.2}, {0.3, 0.2}, {0.3, 0.2}};
    check_landing(RUGO_DETAILS_FIXED, 4, 5, s5, t5, d5);
    /* Two close but distinct points (1e-3 apart in t) with different deltas: a steep but exact edit. */
    {
        const int sc[2] = {5, 5};
        const double tc[2] = {0.4, 0.401};
        const rugo_vec2 dc[2] = {{0.01, 0.0}, {0.0, 0.01}};
        check_landing(RUGO_DETAILS_FIXED, 4, 2, sc, tc, dc);
    }
    /* Zero deltas: nothing moves. */
    const rugo_vec2 z[2] = {{0.0, 0.0}, {0.0, 0.0}};
    const int s2[2] = {1, 1};
    const double t2[2] = {0.5, 0.5};
    rugo_pyramid* p = make_pyramid(3u, NULL);
    rugo_vec2 before[PN], after[PN];
    level_points(p, PJ, before);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, s2, t2, z, RUGO_DETAILS_FIXED), RUGO_OK);
    level_points(p, PJ, after);
    ck_assert(test_max_diff(before, after, PN) <= 1e-12 * 10.0);
    rugo_pyramid_destroy(p);
}
END_TEST

START_TEST(move_points_bad_input) {
    rugo_pyramid* p = make_pyramid(3u, NULL);
    rugo_vec2 before[PN], after[PN];
    level_points(p, PJ, before);
    int segs[2] = {1, 2};
    double ts[2] = {0.5, 0.5};
    rugo_vec2 deltas[2] = {{0.1, 0.0}, {0.0, 0.1}};
    const rugo_detail_mode F = RUGO_DETAILS_FIXED;
    ck_assert_int_eq(rugo_pyramid_move_points(NULL, 4, 2, segs, ts, deltas, F), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, NULL, ts, deltas, F), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, NULL, deltas, F), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, NULL, F), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, (rugo_detail_mode)5),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, (rugo_detail_mode)-1),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 1, 2, segs, ts, deltas, F), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_pyramid_move_points(p, PJ + 1, 2, segs, ts, deltas, F), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_pyramid_move_points(p, -3, 2, segs, ts, deltas, F), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 0, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, -2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    segs[1] = 16;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    segs[1] = -1;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    segs[1] = 2;
    ts[1] = 1.0000001;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    ts[1] = -1e-300;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    ts[1] = NAN; /* out of range, as for rugo_pyramid_move_point */
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_BAD_ARGUMENT);
    ts[1] = 0.5;
    deltas[0].y = INFINITY;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_NOT_FINITE);
    deltas[0].y = NAN;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_ERR_NOT_FINITE);
    /* None of that touched the pyramid. */
    level_points(p, PJ, after);
    ck_assert_int_eq(memcmp(before, after, sizeof before), 0);
    deltas[0].y = 0.0;
    ck_assert_int_eq(rugo_pyramid_move_points(p, 4, 2, segs, ts, deltas, F), RUGO_OK);
    rugo_pyramid_destroy(p);
}
END_TEST

static Suite* fit_suite(void) {
    Suite* s = suite_create("fit");
    TCase* tc = tcase_create("fit_contour");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, default_def);
    tcase_add_test(tc, uniform_recovers_control_points);
    tcase_add_test(tc, chord_length_dense_star);
    tcase_add_test(tc, circle_known_error);
    tcase_add_test(tc, bad_input_statuses);
    tcase_add_test(tc, extreme_coordinates);
    tcase_add_test(tc, singular_fits);
    tcase_add_test(tc, interpolation_when_m_equals_n);
    tcase_add_test(tc, properties);
    tcase_add_test(tc, allocator_used_and_failures_reported);
    tcase_add_test(tc, large_fit);
    suite_add_tcase(s, tc);

    TCase* tm = tcase_create("move_points");
    tcase_set_timeout(tm, 120);
    tcase_add_test(tm, move_two_points_land);
    tcase_add_test(tm, move_many_points_land);
    tcase_add_test(tm, move_points_least_norm);
    tcase_add_test(tm, single_point_equals_move_point);
    tcase_add_test(tm, conflicting_constraints_singular);
    tcase_add_test(tm, consistent_dependent_constraints_accepted);
    tcase_add_test(tm, move_points_bad_input);
    suite_add_tcase(s, tm);
    return s;
}

int main(void) { return test_run_suite(fit_suite()); }
