/* Wavelet suite: CDF(4, m~) filters, periodic analysis/synthesis, refinement (SPEC 2.1-2.2). */
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

static const rugo_filter ALL_FILTERS[] = {RUGO_FILTER_CDF4_2, RUGO_FILTER_CDF4_4, RUGO_FILTER_CDF4_6,
                                          RUGO_FILTER_CDF4_8, RUGO_FILTER_CDF4_12};
#define NFILTERS ((int)(sizeof ALL_FILTERS / sizeof ALL_FILTERS[0]))

/* SPEC 2.1 written out again, independently of the library's tables. */
static const double SPEC_A2[] = {5. / 4, 5. / 32, -3. / 8, 3. / 32};
static const double SPEC_A4[] = {35. / 32, 35. / 128, -3. / 8, -1. / 256, 5. / 64, -5. / 256};
static const double SPEC_A6[] = {525. / 512,  2625. / 8192, -733. / 2048, -557. / 8192,
                                 115. / 1024, -55. / 8192,  -35. / 2048,  35. / 8192};
static const double SPEC_A8[] = {8085. / 8192, 11319. / 32768, -1403. / 4096, -1807. / 16384, 523. / 4096,
                                 205. / 16384, -133. / 4096,   217. / 65536,  63. / 16384,    -63. / 65536};
static const double SPEC_A12[] = {495495. / 524288,  778635. / 2097152, -5249. / 16384, -1354283. / 8388608,
                                  288995. / 2097152, 401465. / 8388608, -3415. / 65536, -32543. / 4194304,
                                  15153. / 1048576,  -1095. / 4194304,  -165. / 65536,  3135. / 8388608,
                                  429. / 2097152,    -429. / 8388608};
static const double* const SPEC_A[] = {SPEC_A2, SPEC_A4, SPEC_A6, SPEC_A8, SPEC_A12};
static const int SPEC_A_COUNT[] = {4, 6, 8, 10, 14};

static rugo_vec2* vec_alloc(int n) {
    rugo_vec2* v = (rugo_vec2*)calloc((size_t)n, sizeof(rugo_vec2));
    ck_assert_ptr_nonnull(v);
    return v;
}

static int log2_int(int n) {
    int k = 0;
    while ((1 << k) < n)
        ++k;
    return k;
}

/* ---- Filters -------------------------------------------------------------------------------- */

START_TEST(filter_names_round_trip) {
    const char* names[] = {"cdf4.2", "cdf4.4", "cdf4.6", "cdf4.8", "cdf4.12"};
    for (int i = 0; i < NFILTERS; ++i) {
        ck_assert_str_eq(rugo_filter_name(ALL_FILTERS[i]), names[i]);
        rugo_filter f = RUGO_FILTER_COUNT;
        ck_assert_int_eq(rugo_filter_from_name(names[i], &f), RUGO_OK);
        ck_assert_int_eq(f, ALL_FILTERS[i]);
    }
    ck_assert_ptr_null(rugo_filter_name(RUGO_FILTER_COUNT));
    ck_assert_ptr_null(rugo_filter_name((rugo_filter)-1));
    rugo_filter f = RUGO_FILTER_CDF4_2;
    ck_assert_int_eq(rugo_filter_from_name("cdf4.10", &f), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_filter_from_name("CDF4.8", &f), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_filter_from_name("", &f), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_filter_from_name("cdf4.8 ", &f), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(f, RUGO_FILTER_CDF4_2); /* untouched on failure */
    ck_assert_int_eq(rugo_filter_from_name(NULL, &f), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_filter_from_name("cdf4.8", NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(RUGO_FILTER_DEFAULT, RUGO_FILTER_CDF4_8);
}
END_TEST

START_TEST(filter_taps_equal_spec) {
    for (int k = 0; k < NFILTERS; ++k) {
        rugo_filter f = ALL_FILTERS[k];
        const rugo_real *a, *b, *p, *q;
        int na = 0, nb = 0, np = 0, nq = 0;
        ck_assert_int_eq(rugo_filter_taps(f, RUGO_FILTER_A, &a, &na), RUGO_OK);
        ck_assert_int_eq(rugo_filter_taps(f, RUGO_FILTER_B, &b, &nb), RUGO_OK);
        ck_assert_int_eq(rugo_filter_taps(f, RUGO_FILTER_P, &p, &np), RUGO_OK);
        ck_assert_int_eq(rugo_filter_taps(f, RUGO_FILTER_Q, &q, &nq), RUGO_OK);
        ck_assert_int_eq(na, SPEC_A_COUNT[k]);
        ck_assert_int_eq(nq, na);
        ck_assert_int_eq(nb, 3);
        ck_assert_int_eq(np, 3);
        /* Exact equality: every value is a dyadic rational, exactly representable. */
        for (int i = 0; i < na; ++i)
            ck_assert_double_eq(a[i], SPEC_A[k][i]);
        const double pq[3] = {3. / 8, 1. / 4, 1. / 16};
        for (int i = 0; i < 3; ++i) {
            ck_assert_double_eq(p[i], 2.0 * pq[i]);
            ck_assert_double_eq(b[i], (i % 2 ? -1.0 : 1.0) * pq[i]);
        }
        for (int i = 0; i < nq; ++i)
            ck_assert_double_eq(q[i], 2.0 * (i % 2 ? -1.0 : 1.0) * SPEC_A[k][i]);
        /* The lowpass filters sum to 1 exactly: the full a, and Pq = p / 2. */
        double sa = a[0], sp = p[0];
        for (int i = 1; i < na; ++i)
            sa += 2.0 * a[i];
        for (int i = 1; i < np; ++i)
            sp += 2.0 * p[i];
        ck_assert_double_eq(sa, 1.0);
        ck_assert_double_eq(sp, 2.0);
        /* Highpass filters annihilate constants. */
        double sb = b[0] + 2.0 * (b[1] + b[2]), sq = q[0];
        for (int i = 1; i < nq; ++i)
            sq += 2.0 * q[i];
        ck_assert_double_eq(sb, 0.0);
        ck_assert_double_eq(sq, 0.0);
        /* NULL outputs are allowed. */
        ck_assert_int_eq(rugo_filter_taps(f, RUGO_FILTER_A, NULL, NULL), RUGO_OK);
    }
    /* Spot check against the thesis' 6-digit table (Appendix A, m~ = 8): a_0 = 0.986938. */
    const rugo_real* a8;
    ck_assert_int_eq(rugo_filter_taps(RUGO_FILTER_CDF4_8, RUGO_FILTER_A, &a8, NULL), RUGO_OK);
    ck_assert_near(a8[0], 0.986938, 5e-7);
    const rugo_real* t;
    int c;
    ck_assert_int_eq(rugo_filter_taps(RUGO_FILTER_COUNT, RUGO_FILTER_A, &t, &c), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_filter_taps((rugo_filter)-3, RUGO_FILTER_P, &t, &c), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_filter_taps(RUGO_FILTER_CDF4_8, (rugo_filter_part)7, &t, &c),
                     RUGO_ERR_BAD_ARGUMENT);
}
END_TEST

/* Impulse responses pin the placement convention: c_s = sum_k a(k - 2s) x_k, d_s centred at 2s-1,
 * and synthesis of a unit detail d_s is q centred at fine index 2s - 1. */
START_TEST(impulse_responses) {
    enum { N = 64, H = N / 2 };
    for (int k = 0; k < NFILTERS; ++k) {
        rugo_filter f = ALL_FILTERS[k];
        const rugo_real *a, *b, *p, *q;
        int na, nb, np, nq;
        rugo_filter_taps(f, RUGO_FILTER_A, &a, &na);
        rugo_filter_taps(f, RUGO_FILTER_B, &b, &nb);
        rugo_filter_taps(f, RUGO_FILTER_P, &p, &np);
        rugo_filter_taps(f, RUGO_FILTER_Q, &q, &nq);
        rugo_vec2 x[N], c[H], d[H], zero[H];
        memset(zero, 0, sizeof zero);
        /* Analysis of a unit impulse at fine index 30. */
        memset(x, 0, sizeof x);
        x[30] = rugo_v2(1.0, -2.0);
        ck_assert_int_eq(rugo_wavelet_analyze(f, x, H, c, d), RUGO_OK);
        for (int s = 0; s < H; ++s) {
            int off = abs(30 - 2 * s), offd = abs(30 - (2 * s - 1));
            double ea = off < na ? a[off] : 0.0, eb = offd < nb ? b[offd] : 0.0;
            ck_assert_double_eq(c[s].x, ea);
            ck_assert_double_eq(c[s].y, -2.0 * ea);
            ck_assert_double_eq(d[s].x, eb);
        }
        /* Synthesis of a unit coarse point and of a unit detail at s = 10. */
        rugo_vec2 u[H];
        memset(u, 0, sizeof u);
        u[10] = rugo_v2(1.0, 0.0);
        ck_assert_int_eq(rugo_wavelet_synthesize(f, u, zero, H, x), RUGO_OK);
        for (int i = 0; i < N; ++i) {
            int off = abs(i - 20);
            ck_assert_double_eq(x[i].x, off < np ? p[off] : 0.0);
        }
        ck_assert_int_eq(rugo_wavelet_synthesize(f, zero, u, H, x), RUGO_OK);
        for (int i = 0; i < N; ++i) {
            int off = abs(i - 19);
            ck_assert_double_eq(x[i].x, off < nq ? q[off] : 0.0);
        }
    }
}
END_TEST

/* ---- Perfect reconstruction ---------------------------------------------------------------- */

/* ACCEPTANCE: every filter, n = 16 .. 4096, seeded random data, all the way down to 4 points:
 * relative error <= 1e-12. (Measured: about 1e-15.) */
START_TEST(perfect_reconstruction_multilevel) {
    test_rng r = test_rng_seed(0x5eed0001ull);
    for (int k = 0; k < NFILTERS; ++k) {
        for (int n = 16; n <= 4096; n *= 2) {
            for (int trial = 0; trial < 3; ++trial) {
                rugo_vec2* x = vec_alloc(n);
                rugo_vec2* y = vec_alloc(n);
                if (trial == 0)
                    test_random_points(&r, n, 100.0, x);
                else
                    test_random_star(&r, n, rugo_v2(500.0 * trial, -300.0), 250.0, 0.4, x);
                memcpy(y, x, (size_t)n * sizeof *x);
                int levels = log2_int(n) - 2;
                ck_assert_int_eq(rugo_wavelet_analyze_levels(ALL_FILTERS[k], y, n, levels, NULL, NULL),
                                 RUGO_OK);
                ck_assert_int_eq(rugo_wavelet_synthesize_levels(ALL_FILTERS[k], y, n, levels, NULL, NULL),
                                 RUGO_OK);
                double err = test_max_diff(x, y, n) / test_max_abs(x, n);
                ck_assert_msg(err <= 1e-12, "filter %d n %d trial %d: relative error %.3g", k, n, trial, err);
                free(x);
                free(y);
            }
        }
    }
}
END_TEST

/* Single steps at tiny sizes, where every filter is longer than the level and wraps around several
 * times (cdf4.12 has 27 taps): reconstruction still holds. half = 3, 5 are not powers of two; a
 * single step accepts any half >= 2. */
START_TEST(perfect_reconstruction_tiny_levels) {
    test_rng r = test_rng_seed(77);
    for (int k = 0; k < NFILTERS; ++k) {
        for (int half = 2; half <= 9; ++half) {
            rugo_vec2 x[18], y[18], c[9], d[9];
            test_random_points(&r, 2 * half, 3.0, x);
            ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, half, c, d), RUGO_OK);
            ck_assert_int_eq(rugo_wavelet_synthesize(ALL_FILTERS[k], c, d, half, y), RUGO_OK);
            double err = test_max_diff(x, y, 2 * half) / test_max_abs(x, 2 * half);
            ck_assert_msg(err <= 1e-13, "filter %d half %d: relative error %.3g", k, half, err);
        }
    }
}
END_TEST

/* The inverse direction: analysis after synthesis is also the identity (the transform is square). */
START_TEST(analysis_inverts_synthesis) {
    test_rng r = test_rng_seed(4242);
    for (int k = 0; k < NFILTERS; ++k) {
        enum { H = 32 };
        rugo_vec2 c[H], d[H], x[2 * H], c2[H], d2[H];
        test_random_points(&r, H, 10.0, c);
        test_random_points(&r, H, 1.0, d);
        ck_assert_int_eq(rugo_wavelet_synthesize(ALL_FILTERS[k], c, d, H, x), RUGO_OK);
        ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, H, c2, d2), RUGO_OK);
        ck_assert_double_le(test_max_diff(c, c2, H), 1e-13);
        ck_assert_double_le(test_max_diff(d, d2, H), 1e-13);
    }
}
END_TEST

/* The multi-level layout is that of repeated single steps: [C^{J-K} | D^{J-K} | ... | D^{J-1}]. */
START_TEST(multilevel_layout) {
    enum { N = 64 };
    test_rng r = test_rng_seed(99);
    rugo_vec2 x[N], y[N], scratch[N], c1[32], d1[32], c2[16], d2[16], c3[8], d3[8];
    test_random_points(&r, N, 5.0, x);
    memcpy(y, x, sizeof x);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(RUGO_FILTER_CDF4_6, y, N, 3, scratch, NULL), RUGO_OK);
    rugo_wavelet_analyze(RUGO_FILTER_CDF4_6, x, 32, c1, d1);
    rugo_wavelet_analyze(RUGO_FILTER_CDF4_6, c1, 16, c2, d2);
    rugo_wavelet_analyze(RUGO_FILTER_CDF4_6, c2, 8, c3, d3);
    ck_assert_double_eq(test_max_diff(y, c3, 8), 0.0);
    ck_assert_double_eq(test_max_diff(y + 8, d3, 8), 0.0);
    ck_assert_double_eq(test_max_diff(y + 16, d2, 16), 0.0);
    ck_assert_double_eq(test_max_diff(y + 32, d1, 32), 0.0);
    /* levels = 0 is the identity. */
    memcpy(y, x, sizeof x);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(RUGO_FILTER_CDF4_6, y, N, 0, NULL, NULL), RUGO_OK);
    ck_assert_int_eq(memcmp(x, y, sizeof x), 0);
    ck_assert_int_eq(rugo_wavelet_synthesize_levels(RUGO_FILTER_CDF4_6, y, N, 0, NULL, NULL), RUGO_OK);
    ck_assert_int_eq(memcmp(x, y, sizeof x), 0);
}
END_TEST

/* ---- Refinement ----------------------------------------------------------------------------- */

/* ACCEPTANCE: zero-detail synthesis is cubic B-spline subdivision, for every filter. */
START_TEST(refinement_is_bspline_subdivision) {
    test_rng r = test_rng_seed(12345);
    for (int half = 4; half <= 256; half *= 2) {
        rugo_vec2* c = vec_alloc(half);
        rugo_vec2* zero = vec_alloc(half);
        rugo_vec2* x = vec_alloc(2 * half);
        rugo_vec2* e = vec_alloc(2 * half);
        test_random_points(&r, half, 50.0, c);
        for (int s = 0; s < half; ++s) {
            rugo_vec2 cm = c[(s + half - 1) % half], c0 = c[s], cp = c[(s + 1) % half];
            e[2 * s] = rugo_v2((cm.x + 6.0 * c0.x + cp.x) / 8.0, (cm.y + 6.0 * c0.y + cp.y) / 8.0);
            e[2 * s + 1] = rugo_v2((c0.x + cp.x) / 2.0, (c0.y + cp.y) / 2.0);
        }
        double scale = test_max_abs(c, half);
        ck_assert_int_eq(rugo_wavelet_refine(c, half, x), RUGO_OK);
        ck_assert_double_le(test_max_diff(x, e, 2 * half) / scale, 1e-13);
        for (int k = 0; k < NFILTERS; ++k) {
            ck_assert_int_eq(rugo_wavelet_synthesize(ALL_FILTERS[k], c, NULL, half, x), RUGO_OK);
            ck_assert_double_le(test_max_diff(x, e, 2 * half) / scale, 1e-13);
            ck_assert_int_eq(rugo_wavelet_synthesize(ALL_FILTERS[k], c, zero, half, x), RUGO_OK);
            ck_assert_double_le(test_max_diff(x, e, 2 * half) / scale, 1e-13);
        }
        free(c);
        free(zero);
        free(x);
        free(e);
    }
}
END_TEST

/* ACCEPTANCE: segment alignment (4.5). With D = 0, f^j_k(t) = f^{j+1}_{2k}(2t) = f^{j+1}_{2k+1}(2t-1). */
START_TEST(refinement_segment_alignment) {
    test_rng r = test_rng_seed(2718);
    for (int half = 4; half <= 64; half *= 2) {
        rugo_vec2 c[64], x[128];
        test_random_star(&r, half, rugo_v2(1000.0, 2000.0), 300.0, 0.3, c);
        ck_assert_int_eq(rugo_wavelet_refine(c, half, x), RUGO_OK);
        rugo_contour coarse = {c, half}, fine = {x, 2 * half};
        for (int k = 0; k < half; ++k) {
            for (int i = 0; i <= 16; ++i) {
                double t = i / 16.0;
                rugo_vec2 pc = rugo_contour_point(coarse, k, t);
                rugo_vec2 pf = t <= 0.5 ? rugo_contour_point(fine, 2 * k, 2.0 * t)
                                        : rugo_contour_point(fine, 2 * k + 1, 2.0 * t - 1.0);
                ck_assert_near(pc.x, pf.x, 1e-12 * 2000.0);
                ck_assert_near(pc.y, pf.y, 1e-12 * 2000.0);
                /* At t = 1/2 both fine segments meet. */
                if (i == 8) {
                    rugo_vec2 pg = rugo_contour_point(fine, 2 * k + 1, 0.0);
                    ck_assert_near(pc.x, pg.x, 1e-12 * 2000.0);
                    ck_assert_near(pc.y, pg.y, 1e-12 * 2000.0);
                }
            }
        }
    }
}
END_TEST

/* ---- Properties of the analysis ------------------------------------------------------------ */

/* ACCEPTANCE: details of control points sampled from a cubic polynomial vanish.
 * Periodic data cannot be a global cubic, so x_k = P(k / n) for k = 0..n-1 is a cubic on the
 * interior and jumps at the wrap (x_{n-1} -> x_0). b has support 2s-1-2 .. 2s-1+2, so d_s only sees
 * samples of the cubic when 2s-3 >= 0 and 2s+1 <= n-1, i.e. s = 2 .. n/2-1: those must vanish to
 * round-off; the two that straddle the wrap (s = 0, 1) must not (they see the jump). */
START_TEST(cubic_details_vanish) {
    test_rng r = test_rng_seed(31337);
    for (int k = 0; k < NFILTERS; ++k) {
        for (int n = 8; n <= 256; n *= 2) {
            double cx[4], cy[4];
            for (int i = 0; i < 4; ++i) {
                cx[i] = test_rng_uniform(&r, -100.0, 100.0);
                cy[i] = test_rng_uniform(&r, -100.0, 100.0);
            }
            rugo_vec2* x = vec_alloc(n);
            rugo_vec2* c = vec_alloc(n / 2);
            rugo_vec2* d = vec_alloc(n / 2);
            for (int i = 0; i < n; ++i) {
                double u = (double)i / n;
                x[i] = rugo_v2(((cx[3] * u + cx[2]) * u + cx[1]) * u + cx[0],
                               ((cy[3] * u + cy[2]) * u + cy[1]) * u + cy[0]);
            }
            double scale = test_max_abs(x, n);
            ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, n / 2, c, d), RUGO_OK);
            for (int s = 2; s < n / 2; ++s) {
                ck_assert_msg(fabs(d[s].x) <= 1e-13 * scale && fabs(d[s].y) <= 1e-13 * scale,
                              "filter %d n %d s %d: d = (%g, %g)", k, n, s, d[s].x, d[s].y);
            }
            ck_assert(fabs(d[0].x) + fabs(d[0].y) + fabs(d[1].x) + fabs(d[1].y) > 1e-6 * scale);
            free(x);
            free(c);
            free(d);
        }
    }
}
END_TEST

/* ACCEPTANCE: mean(C^{j-1}) = mean(C^j); the details' mean is in general NOT zero (SPEC 2.2). */
START_TEST(mean_preserved) {
    test_rng r = test_rng_seed(5);
    for (int k = 0; k < NFILTERS; ++k) {
        for (int half = 2; half <= 512; half *= 2) {
            rugo_vec2* x = vec_alloc(2 * half);
            rugo_vec2* c = vec_alloc(half);
            rugo_vec2* d = vec_alloc(half);
            test_random_points(&r, 2 * half, 10.0, x);
            for (int i = 0; i < 2 * half; ++i)
                x[i] = rugo_v2_add(x[i], rugo_v2(1000.0, -500.0));
            ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, half, c, d), RUGO_OK);
            double mfx = 0, mfy = 0, mcx = 0, mcy = 0, mdx = 0, mdy = 0;
            for (int i = 0; i < 2 * half; ++i) {
                mfx += x[i].x;
                mfy += x[i].y;
            }
            for (int s = 0; s < half; ++s) {
                mcx += c[s].x;
                mcy += c[s].y;
                mdx += d[s].x;
                mdy += d[s].y;
            }
            mfx /= 2 * half;
            mfy /= 2 * half;
            mcx /= half;
            mcy /= half;
            ck_assert_near(mcx, mfx, 1e-12 * 1000.0);
            ck_assert_near(mcy, mfy, 1e-12 * 1000.0);
            ck_assert(fabs(mdx) + fabs(mdy) > 1e-9);
            free(x);
            free(c);
            free(d);
        }
    }
}
END_TEST

/* SPEC's warning: a has negative taps, so coarse points are NOT convex averages of the fine ones.
 * A circle of 16 points with one spike at index 0 and its second neighbours (weighted by the
 * negative a_2) pulled in: the coarse point under the spike lies beyond every fine point in x, so
 * outside the fine points' convex hull, for every filter. */
START_TEST(coarse_points_not_convex_average) {
    enum { N = 16 };
    for (int k = 0; k < NFILTERS; ++k) {
        rugo_vec2 x[N], c[N / 2], d[N / 2];
        for (int i = 0; i < N; ++i) {
            double th = 6.283185307179586 * i / N, rad = i == 0 ? 3.0 : (i == 2 || i == N - 2) ? 0.2 : 1.0;
            x[i] = rugo_v2(rad * cos(th), rad * sin(th));
        }
        double maxx = -1e300;
        for (int i = 0; i < N; ++i)
            maxx = fmax(maxx, x[i].x);
        ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, N / 2, c, d), RUGO_OK);
        double maxc = -1e300;
        for (int s = 0; s < N / 2; ++s)
            maxc = fmax(maxc, c[s].x);
        ck_assert_msg(maxc > maxx + 1e-3, "filter %d: max coarse x %g, max fine x %g", k, maxc, maxx);
    }
}
END_TEST

/* The lifting form of SPEC 2.2 gives the same numbers (m~ = 2..8, where SPEC lists g). */
START_TEST(lifting_form_matches) {
    static const double g2[] = {3. / 16}, g4[] = {29. / 128, -5. / 128},
                        g6[] = {499. / 2048, -265. / 4096, 35. / 4096},
                        g8[] = {8299. / 32768, -2687. / 32768, 595. / 32768, -63. / 32768};
    static const double* const gs[] = {g2, g4, g6, g8};
    enum { N = 64, H = N / 2 };
    test_rng r = test_rng_seed(8);
    for (int k = 0; k < 4; ++k) {
        int ng = k + 1;
        rugo_vec2 x[N], c[H], d[H];
        double ex[H], ey[H], ox[H], oy[H];
        test_random_points(&r, N, 10.0, x);
        ck_assert_int_eq(rugo_wavelet_analyze(ALL_FILTERS[k], x, H, c, d), RUGO_OK);
        for (int s = 0; s < H; ++s) {
            rugo_vec2 m = x[(2 * s + N - 1) % N], p = x[2 * s + 1];
            ex[s] = x[2 * s].x - 0.25 * (m.x + p.x);
            ey[s] = x[2 * s].y - 0.25 * (m.y + p.y);
        }
        for (int s = 0; s < H; ++s) {
            ox[s] = x[2 * s + 1].x - (ex[s] + ex[(s + 1) % H]);
            oy[s] = x[2 * s + 1].y - (ey[s] + ey[(s + 1) % H]);
        }
        for (int s = 0; s < H; ++s) {
            for (int j = 1; j <= ng; ++j) {
                int a = ((s - j) % H + H) % H, b = (s + j - 1) % H;
                ex[s] += gs[k][j - 1] * (ox[a] + ox[b]);
                ey[s] += gs[k][j - 1] * (oy[a] + oy[b]);
            }
        }
        for (int s = 0; s < H; ++s) {
            ck_assert_near(c[s].x, 2.0 * ex[s], 1e-12);
            ck_assert_near(c[s].y, 2.0 * ey[s], 1e-12);
            int sm = (s + H - 1) % H; /* o_{s-1} is centred at 2s - 1 */
            ck_assert_near(d[s].x, ox[sm] / 4.0, 1e-12);
            ck_assert_near(d[s].y, oy[sm] / 4.0, 1e-12);
        }
    }
}
END_TEST

/* Bit-identical results run after run (no hidden state). */
START_TEST(deterministic) {
    enum { N = 256 };
    test_rng r = test_rng_seed(1);
    rugo_vec2 x[N], y[N], z[N];
    test_random_points(&r, N, 1.0, x);
    memcpy(y, x, sizeof x);
    memcpy(z, x, sizeof x);
    rugo_wavelet_analyze_levels(RUGO_FILTER_CDF4_12, y, N, 6, NULL, NULL);
    rugo_wavelet_analyze_levels(RUGO_FILTER_CDF4_12, z, N, 6, NULL, NULL);
    ck_assert_int_eq(memcmp(y, z, sizeof y), 0);
}
END_TEST

/* ---- Bad input ------------------------------------------------------------------------------ */

static void* failing_alloc(size_t n, void* ctx) {
    (void)n;
    (void)ctx;
    return NULL;
}
static void failing_free(void* p, void* ctx) {
    (void)p;
    (void)ctx;
}

START_TEST(bad_arguments) {
    rugo_vec2 x[16], c[8], d[8], s[16];
    memset(x, 0, sizeof x);
    const rugo_filter F = RUGO_FILTER_CDF4_8;
    /* Single steps. */
    ck_assert_int_eq(rugo_wavelet_analyze(F, NULL, 8, c, d), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 8, NULL, d), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 8, c, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_analyze(RUGO_FILTER_COUNT, x, 8, c, d), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_wavelet_analyze((rugo_filter)-1, x, 8, c, d), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 1, c, d), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 0, c, d), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, -4, c, d), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, RUGO_MAX_CONTROL_POINTS, c, d), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 8, x, d), RUGO_ERR_BAD_ARGUMENT); /* overlap */
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 4, x + 8, x + 12), RUGO_OK);      /* disjoint parts */
    ck_assert_int_eq(rugo_wavelet_analyze(F, x, 4, c, c + 2), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_synthesize(F, NULL, d, 8, x), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_synthesize(F, c, d, 8, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_synthesize(RUGO_FILTER_COUNT, c, d, 8, x), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_wavelet_synthesize(F, c, d, 1, x), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_wavelet_synthesize(F, x + 2, d, 4, x + 4), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_synthesize(F, c, x + 2, 4, x), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_refine(NULL, 8, x), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_refine(c, 8, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_refine(c, 1, x), RUGO_ERR_TOO_FEW_POINTS);
    /* Multi-level. */
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, NULL, 16, 1, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(RUGO_FILTER_COUNT, x, 16, 1, NULL, NULL),
                     RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 2, 0, NULL, NULL), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 12, 1, NULL, NULL), RUGO_ERR_NOT_POWER_OF_TWO);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 2 * RUGO_MAX_CONTROL_POINTS, 1, NULL, NULL),
                     RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 3, NULL, NULL), RUGO_ERR_BAD_LEVEL); /* 2 points */
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, -1, NULL, NULL), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 40, NULL, NULL), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_wavelet_synthesize_levels(F, x, 16, 3, NULL, NULL), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_wavelet_synthesize_levels(F, x, 12, 1, NULL, NULL), RUGO_ERR_NOT_POWER_OF_TWO);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 2, x, NULL),
                     RUGO_ERR_BAD_ARGUMENT); /* scratch = data */
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 2, s, NULL), RUGO_OK);
    rugo_allocator bad = {failing_alloc, failing_free, NULL};
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 2, NULL, &bad), RUGO_ERR_OUT_OF_MEMORY);
    ck_assert_int_eq(rugo_wavelet_synthesize_levels(F, x, 16, 2, NULL, &bad), RUGO_ERR_OUT_OF_MEMORY);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 2, s, &bad), RUGO_OK); /* no allocation needed */
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 16, 0, NULL, &bad), RUGO_OK);
    ck_assert_int_eq(rugo_wavelet_analyze_levels(F, x, 4, 0, NULL, NULL), RUGO_OK);
}
END_TEST

int main(void) {
    Suite* s = suite_create("wavelet");
    TCase* tf = tcase_create("filters");
    tcase_add_test(tf, filter_names_round_trip);
    tcase_add_test(tf, filter_taps_equal_spec);
    tcase_add_test(tf, impulse_responses);
    suite_add_tcase(s, tf);
    TCase* tr = tcase_create("reconstruction");
    tcase_set_timeout(tr, 120);
    tcase_add_test(tr, perfect_reconstruction_multilevel);
    tcase_add_test(tr, perfect_reconstruction_tiny_levels);
    tcase_add_test(tr, analysis_inverts_synthesis);
    tcase_add_test(tr, multilevel_layout);
    suite_add_tcase(s, tr);
    TCase* tp = tcase_create("properties");
    tcase_set_timeout(tp, 60);
    tcase_add_test(tp, refinement_is_bspline_subdivision);
    tcase_add_test(tp, refinement_segment_alignment);
    tcase_add_test(tp, cubic_details_vanish);
    tcase_add_test(tp, mean_preserved);
    tcase_add_test(tp, coarse_points_not_convex_average);
    tcase_add_test(tp, lifting_form_matches);
    tcase_add_test(tp, deterministic);
    suite_add_tcase(s, tp);
    TCase* tb = tcase_create("bad_input");
    tcase_add_test(tb, bad_arguments);
    suite_add_tcase(s, tb);
    return test_run_suite(s);
}
