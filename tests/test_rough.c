/* Rough suite: the tolerance library (presets, constructors, validation) and the perturbation
 * generators (rugo_roughen, wavelet and local methods) — SPEC 4; thesis 2.4, 5.2, Fig. 5.5.
 *
 * Statistical checks run on fixed seeds (deterministic); each states its tolerance, usually five
 * standard errors of the estimate. "Normal deviation" is the parametric one: at a parameter u of the
 * output, (f_rough(u) - f_refined(u)) · n_refined(u), with f_refined the input refined to the output's
 * level (the unperturbed curve at the same resolution). */
#include "core/internal.h"
#include "test_util.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* Figure 5.5 as printed in the thesis, segments 0..31 (the patterns repeat; the table's last row,
 * segment 127 of tipo_5, reads 0.04). */
static const double FIG55_TIPO_3[32] = {0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20,
                                        0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24,
                                        0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24};
static const double FIG55_TIPO_5[32] = {0.55, 0.55, 0.55, 0.55, 0.04, 0.04, 0.04, 0.04, 0.65, 0.65, 0.65,
                                        0.65, 0.04, 0.04, 0.04, 0.04, 0.55, 0.55, 0.55, 0.55, 0.04, 0.04,
                                        0.04, 0.04, 0.65, 0.65, 0.65, 0.65, 0.04, 0.04, 0.04, 0.04};

static const double SENTINEL = -12345.0;

static void fill(double* v, int n, double x) {
    for (int i = 0; i < n; ++i)
        v[i] = x;
}
static int all_equal(const double* v, int n, double x) {
    for (int i = 0; i < n; ++i)
        if (v[i] != x) return 0;
    return 1;
}

/* ---- presets ------------------------------------------------------------------------------------ */

START_TEST(preset_names) {
    static const char* names[] = {"tipo_1", "tipo_2", "tipo_3", "tipo_5"};
    for (int p = 0; p < (int)RUGO_PRESET_COUNT; ++p) {
        ck_assert_str_eq(rugo_preset_name((rugo_tolerance_preset)p), names[p]);
        rugo_tolerance_preset back = RUGO_PRESET_COUNT;
        ck_assert_int_eq(rugo_preset_from_name(names[p], &back), RUGO_OK);
        ck_assert_int_eq(back, p);
    }
    ck_assert_ptr_null(rugo_preset_name(RUGO_PRESET_COUNT));
    ck_assert_ptr_null(rugo_preset_name((rugo_tolerance_preset)-1));
    rugo_tolerance_preset p = RUGO_PRESET_TIPO_3;
    ck_assert_int_eq(rugo_preset_from_name("tipo_4", &p), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_preset_from_name("TIPO_1", &p), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_preset_from_name("", &p), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(p, RUGO_PRESET_TIPO_3); /* untouched on error */
    ck_assert_int_eq(rugo_preset_from_name(NULL, &p), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_preset_from_name("tipo_1", NULL), RUGO_ERR_NULL_ARGUMENT);
}
END_TEST

START_TEST(preset_tipo_1_constant) {
    static double v[1000];
    const int ns[] = {1, 32, 1000};
    for (int i = 0; i < 3; ++i) {
        fill(v, 1000, SENTINEL);
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_1, 99, ns[i], v), RUGO_OK);
        ck_assert(all_equal(v, ns[i], 0.25));
        ck_assert(all_equal(v + ns[i], 1000 - ns[i], SENTINEL)); /* exactly n written */
    }
}
END_TEST

/* ACCEPTANCE: tipo_3 and tipo_5 equal the thesis' Figure 5.5 on 32 and 128 segments, starting at
 * segment 0, whatever the seed. */
START_TEST(preset_tipo_3_tipo_5_fig55) {
    double v[128];
    for (uint64_t seed = 0; seed < 3; ++seed) {
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_3, seed, 32, v), RUGO_OK);
        for (int i = 0; i < 32; ++i)
            ck_assert_double_eq(v[i], FIG55_TIPO_3[i]);
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_5, seed, 32, v), RUGO_OK);
        for (int i = 0; i < 32; ++i)
            ck_assert_double_eq(v[i], FIG55_TIPO_5[i]);
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_3, seed, 128, v), RUGO_OK);
        for (int i = 0; i < 128; ++i)
            ck_assert_double_eq(v[i], FIG55_TIPO_3[i % 32]);
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_5, seed, 128, v), RUGO_OK);
        for (int i = 0; i < 128; ++i)
            ck_assert_double_eq(v[i], FIG55_TIPO_5[i % 32]);
        ck_assert_double_eq(v[127], 0.04); /* the table's last row */
    }
    /* Counts that are not multiples of the period keep the phase at segment 0. */
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, 7, v), RUGO_OK);
    for (int i = 0; i < 7; ++i)
        ck_assert_double_eq(v[i], FIG55_TIPO_5[i]);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, 1, v), RUGO_OK);
    ck_assert_double_eq(v[0], 0.32);
}
END_TEST

/* tipo_2: per block, first the length 1 + rugo_rng_below(4), then the value rugo_rng_range(0.04,
 * 0.65), from one rugo_rng seeded with the seed (the documented draw order, replayed here). */
START_TEST(preset_tipo_2_draw_order) {
    enum { N = 1000 };
    static double v[N], w[N];
    for (uint64_t seed = 0; seed < 20; ++seed) {
        ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, seed, N, v), RUGO_OK);
        rugo_rng rng;
        rugo_rng_seed(&rng, seed);
        int i = 0;
        while (i < N) {
            int len = 1 + (int)rugo_rng_below(&rng, 4);
            double x = rugo_rng_range(&rng, 0.04, 0.65);
            for (int k = 0; k < len && i < N; ++k)
                w[i++] = x;
        }
        ck_assert(memcmp(v, w, sizeof v) == 0);
    }
}
END_TEST

/* tipo_2: deterministic per seed, different across seeds, values in [0.04, 0.65], runs of 1..4
 * segments; over 10^5 segments the block lengths are uniform on 1..4 (chi-square, df 3, below the
 * 1e-6 quantile 30.66) and the block values have mean 0.345 within 5 SE (SE = 0.61/sqrt(12 B)). */
START_TEST(preset_tipo_2_properties) {
    enum { N = 100000 };
    static double a[N], b[N];
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 5, N, a), RUGO_OK);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 5, N, b), RUGO_OK);
    ck_assert(memcmp(a, b, sizeof a) == 0);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 6, N, b), RUGO_OK);
    ck_assert(memcmp(a, b, sizeof a) != 0);
    /* A shorter call gives a prefix of a longer one. */
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 5, 37, b), RUGO_OK);
    ck_assert(memcmp(a, b, 37 * sizeof(double)) == 0);

    long lengths[5] = {0}, blocks = 0, bad = 0;
    double sum = 0.0;
    int i = 0;
    while (i < N) {
        int j = i;
        while (j < N && a[j] == a[i])
            ++j;
        const int len = j - i;
        if (!(a[i] >= 0.04 && a[i] <= 0.65)) ++bad;
        if (len < 1 || len > 4) ++bad;
        if (j < N) { /* the last run may be cut short */
            ++lengths[len <= 4 ? len : 0];
            ++blocks;
            sum += a[i];
        }
        i = j;
    }
    ck_assert_int_eq(bad, 0);
    double chi2 = 0.0, e = (double)blocks / 4.0;
    for (int k = 1; k <= 4; ++k)
        chi2 += (lengths[k] - e) * (lengths[k] - e) / e;
    ck_assert_msg(chi2 < 30.66, "block lengths chi-square %.3f", chi2);
    ck_assert_near(sum / blocks, 0.345, 5.0 * 0.61 / sqrt(12.0 * blocks));
}
END_TEST

START_TEST(preset_errors) {
    double v[8];
    fill(v, 8, SENTINEL);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_1, 0, 8, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_COUNT, 0, 8, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_preset((rugo_tolerance_preset)-1, 0, 8, v), RUGO_ERR_BAD_ARGUMENT);
    for (int p = 0; p < (int)RUGO_PRESET_COUNT; ++p) {
        ck_assert_int_eq(rugo_tolerances_preset((rugo_tolerance_preset)p, 0, 0, v), RUGO_ERR_TOO_FEW_POINTS);
        ck_assert_int_eq(rugo_tolerances_preset((rugo_tolerance_preset)p, 0, -5, v), RUGO_ERR_TOO_FEW_POINTS);
        ck_assert_int_eq(rugo_tolerances_preset((rugo_tolerance_preset)p, 0, RUGO_MAX_CONTROL_POINTS + 1, v),
                         RUGO_ERR_TOO_MANY_POINTS);
    }
    ck_assert(all_equal(v, 8, SENTINEL));
}
END_TEST

/* ---- constructors ------------------------------------------------------------------------------- */

START_TEST(constant_values_and_errors) {
    double v[16];
    ck_assert_int_eq(rugo_tolerances_constant(0.7, 16, v), RUGO_OK);
    ck_assert(all_equal(v, 16, 0.7));
    ck_assert_int_eq(rugo_tolerances_constant(0.0, 16, v), RUGO_OK);
    ck_assert(all_equal(v, 16, 0.0));
    ck_assert_int_eq(rugo_tolerances_constant(-0.0, 16, v), RUGO_OK); /* a zero tolerance */
    fill(v, 16, SENTINEL);
    ck_assert_int_eq(rugo_tolerances_constant(0.5, 16, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_constant(0.5, 0, v), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_tolerances_constant(0.5, RUGO_MAX_CONTROL_POINTS + 1, v), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_tolerances_constant(NAN, 16, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_constant(INFINITY, 16, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_constant(-INFINITY, 16, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_constant(-0.1, 16, v), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_int_eq(rugo_tolerances_constant(-DBL_MIN, 16, v), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert(all_equal(v, 16, SENTINEL)); /* nothing written on error */
}
END_TEST

START_TEST(pattern_values_and_errors) {
    const double pat[3] = {0.1, 0.2, 0.3};
    double v[10];
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 3, 10, v), RUGO_OK);
    for (int i = 0; i < 10; ++i)
        ck_assert_double_eq(v[i], pat[i % 3]);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 3, 2, v), RUGO_OK); /* period longer than n */
    ck_assert_double_eq(v[1], 0.2);
    fill(v, 10, SENTINEL);
    ck_assert_int_eq(rugo_tolerances_pattern(NULL, 3, 10, v), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 3, 10, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 3, 0, v), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 3, RUGO_MAX_CONTROL_POINTS + 1, v),
                     RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, 0, 10, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, -1, 10, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_pattern(pat, RUGO_MAX_CONTROL_POINTS + 1, 10, v), RUGO_ERR_BAD_ARGUMENT);
    const double nan_pat[3] = {0.1, NAN, 0.3}, inf_pat[2] = {INFINITY, 0.1}, neg_pat[3] = {0.1, 0.2, -0.3};
    ck_assert_int_eq(rugo_tolerances_pattern(nan_pat, 3, 10, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_pattern(inf_pat, 2, 10, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_pattern(neg_pat, 3, 10, v), RUGO_ERR_NEGATIVE_TOLERANCE);
    /* Every value of the pattern is checked, also those a short n would not use. */
    ck_assert_int_eq(rugo_tolerances_pattern(neg_pat, 3, 1, v), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert(all_equal(v, 10, SENTINEL));
}
END_TEST

START_TEST(blocks_values_and_errors) {
    /* tipo_5 rebuilt from blocks. */
    const double vals[4] = {0.55, 0.04, 0.65, 0.04};
    double v[128];
    ck_assert_int_eq(rugo_tolerances_blocks(vals, 4, 4, 128, v), RUGO_OK);
    for (int i = 0; i < 128; ++i)
        ck_assert_double_eq(v[i], FIG55_TIPO_5[i % 32]);
    const double two[2] = {1.0, 2.0};
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 3, 10, v), RUGO_OK);
    const double want[10] = {1, 1, 1, 2, 2, 2, 1, 1, 1, 2};
    for (int i = 0; i < 10; ++i)
        ck_assert_double_eq(v[i], want[i]);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 1000, 10, v), RUGO_OK); /* one long block */
    ck_assert(all_equal(v, 10, 1.0));
    fill(v, 128, SENTINEL);
    ck_assert_int_eq(rugo_tolerances_blocks(NULL, 2, 3, 10, v), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 3, 10, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 3, 0, v), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 3, RUGO_MAX_CONTROL_POINTS + 1, v),
                     RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 0, 3, 10, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_blocks(two, -2, 3, 10, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, 0, 10, v), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_blocks(two, 2, -1, 10, v), RUGO_ERR_BAD_ARGUMENT);
    const double bad_nan[2] = {1.0, NAN}, bad_neg[2] = {-1.0, 1.0};
    ck_assert_int_eq(rugo_tolerances_blocks(bad_nan, 2, 3, 10, v), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_blocks(bad_neg, 2, 3, 10, v), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert(all_equal(v, 128, SENTINEL));
}
END_TEST

/* Random: one rugo_rng_range(lo, hi) per segment from segment 0 (replayed), values in [lo, hi];
 * 10^5 values have mean (lo+hi)/2 within 5 SE (SE = (hi-lo)/sqrt(12 N)). */
START_TEST(random_values_and_errors) {
    enum { N = 100000 };
    static double v[N];
    ck_assert_int_eq(rugo_tolerances_random(0.1, 0.9, 17, N, v), RUGO_OK);
    rugo_rng rng;
    rugo_rng_seed(&rng, 17);
    int mismatch = 0, outside = 0;
    double sum = 0.0;
    for (int i = 0; i < N; ++i) {
        if (v[i] != rugo_rng_range(&rng, 0.1, 0.9)) ++mismatch;
        if (!(v[i] >= 0.1 && v[i] <= 0.9)) ++outside;
        sum += v[i];
    }
    ck_assert_int_eq(mismatch, 0);
    ck_assert_int_eq(outside, 0);
    ck_assert_near(sum / N, 0.5, 5.0 * 0.8 / sqrt(12.0 * N));
    static double w[N];
    ck_assert_int_eq(rugo_tolerances_random(0.1, 0.9, 18, N, w), RUGO_OK);
    ck_assert(memcmp(v, w, sizeof v) != 0);
    ck_assert_int_eq(rugo_tolerances_random(0.3, 0.3, 18, 100, w), RUGO_OK); /* lo == hi */
    ck_assert(all_equal(w, 100, 0.3));
    ck_assert_int_eq(rugo_tolerances_random(0.0, 0.0, 18, 100, w), RUGO_OK);
    ck_assert(all_equal(w, 100, 0.0));

    double u[8];
    fill(u, 8, SENTINEL);
    ck_assert_int_eq(rugo_tolerances_random(0.1, 0.9, 1, 8, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tolerances_random(0.1, 0.9, 1, 0, u), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_tolerances_random(0.1, 0.9, 1, RUGO_MAX_CONTROL_POINTS + 1, u),
                     RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(rugo_tolerances_random(NAN, 0.9, 1, 8, u), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_random(0.1, INFINITY, 1, 8, u), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_random(0.9, 0.1, 1, 8, u), RUGO_ERR_EMPTY_RANGE);
    ck_assert_int_eq(rugo_tolerances_random(-0.1, 0.9, 1, 8, u), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_int_eq(rugo_tolerances_random(-0.5, -0.1, 1, 8, u), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_int_eq(rugo_tolerances_random(-0.1, -0.5, 1, 8, u), RUGO_ERR_EMPTY_RANGE); /* range first */
    ck_assert(all_equal(u, 8, SENTINEL));
}
END_TEST

START_TEST(check_values) {
    double v[6] = {0.1, 0.0, -0.0, 2.0, 0.5, 1e300};
    int bad = 77;
    ck_assert_int_eq(rugo_tolerances_check(v, 6, &bad), RUGO_OK);
    ck_assert_int_eq(bad, -1);
    ck_assert_int_eq(rugo_tolerances_check(v, 6, NULL), RUGO_OK);
    v[3] = NAN;
    v[4] = -1.0;
    ck_assert_int_eq(rugo_tolerances_check(v, 6, &bad), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(bad, 3);
    v[3] = 1.0;
    ck_assert_int_eq(rugo_tolerances_check(v, 6, &bad), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_int_eq(bad, 4);
    ck_assert_int_eq(rugo_tolerances_check(v, 4, &bad), RUGO_OK); /* only n values are read */
    v[0] = -INFINITY;
    ck_assert_int_eq(rugo_tolerances_check(v, 6, &bad), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(bad, 0);
    ck_assert_int_eq(rugo_tolerances_check(v, 6, NULL), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tolerances_check(NULL, 6, &bad), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(bad, -1);
    ck_assert_int_eq(rugo_tolerances_check(v, 0, &bad), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(bad, -1);
}
END_TEST

/* ---- roughen: helpers --------------------------------------------------------------------------- */

enum { MAXN = 128, MAXOUT = 128 << 3 };

static void ball(int n, double radius, rugo_vec2* out) {
    for (int k = 0; k < n; ++k) {
        double th = 6.283185307179586 * k / n;
        out[k] = rugo_v2(radius * cos(th), radius * sin(th));
    }
}

static void object(int n, rugo_vec2* out) {
    test_rng r = test_rng_seed(555);
    test_random_star(&r, n, rugo_v2(40.0, -25.0), 200.0, 0.35, out);
}

static rugo_status roughen(const rugo_vec2* pts, int n, const double* lam, rugo_roughen_method method,
                           int levels, uint64_t seed, rugo_vec2* out) {
    rugo_roughen_def d = rugo_default_roughen_def();
    d.points = pts;
    d.count = n;
    d.tolerances = lam;
    d.method = method;
    d.levels = levels;
    d.seed = seed;
    return rugo_roughen(&d, out);
}

/* The input refined `levels` times (zero details). */
static void refine(const rugo_vec2* pts, int n, int levels, rugo_vec2* out) {
    static rugo_vec2 tmp[MAXOUT];
    memcpy(out, pts, (size_t)n * sizeof(rugo_vec2));
    for (int r = 0; r < levels; ++r) {
        ck_assert_int_eq(rugo_wavelet_refine(out, n << r, tmp), RUGO_OK);
        memcpy(out, tmp, (size_t)(n << (r + 1)) * sizeof(rugo_vec2));
    }
}

/* Normal deviations at T parameters per segment of an m-point output: dev[j*T + i] at (j, i/T). */
enum { T = 4 };
static void deviations(const rugo_vec2* rough, const rugo_vec2* ref, int m, double* dev) {
    rugo_contour cr = {rough, m}, cf = {ref, m};
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < T; ++i) {
            double t = (double)i / T;
            rugo_vec2 d = rugo_v2_sub(rugo_contour_point(cr, j, t), rugo_contour_point(cf, j, t));
            dev[j * T + i] = rugo_v2_dot(d, rugo_contour_normal(cf, j, t));
        }
}

static const rugo_roughen_method METHODS[2] = {RUGO_ROUGHEN_WAVELET, RUGO_ROUGHEN_LOCAL};

/* ---- roughen: basic contract ---------------------------------------------------------------------- */

START_TEST(default_def) {
    rugo_roughen_def d = rugo_default_roughen_def();
    ck_assert_ptr_null(d.points);
    ck_assert_ptr_null(d.tolerances);
    ck_assert_int_eq(d.count, 0);
    ck_assert_double_eq(d.q, RUGO_DEFAULT_Q);
    ck_assert_double_eq(d.q, 0.95);
    ck_assert_int_eq(d.method, RUGO_ROUGHEN_WAVELET);
    ck_assert_int_eq(d.levels, 2);
    ck_assert_int_eq(d.filter, RUGO_FILTER_DEFAULT);
    ck_assert(d.seed == 0);
    ck_assert(d.allocator.alloc == NULL && d.allocator.free == NULL);
    ck_assert_int_ne(d.cookie, 0);
}
END_TEST

/* Output: exactly count << levels points written, all finite, near the input curve. */
START_TEST(output_count) {
    rugo_vec2 pts[32];
    double lam[32];
    object(32, pts);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, 32, lam), RUGO_OK);
    static rugo_vec2 out[MAXOUT + 8];
    for (int mth = 0; mth < 2; ++mth)
        for (int levels = 1; levels <= 3; ++levels) {
            const int m = 32 << levels;
            for (int i = 0; i < MAXOUT + 8; ++i)
                out[i] = rugo_v2(SENTINEL, SENTINEL);
            ck_assert_int_eq(roughen(pts, 32, lam, METHODS[mth], levels, 1, out), RUGO_OK);
            for (int i = 0; i < m; ++i) {
                ck_assert(rugo__v2_finite(out[i]) && out[i].x != SENTINEL);
            }
            for (int i = m; i < MAXOUT + 8; ++i)
                ck_assert_double_eq(out[i].x, SENTINEL);
            static rugo_vec2 ref[MAXOUT];
            refine(pts, 32, levels, ref);
            /* λ <= 0.32, σ <= 0.34: no control point moves by more than ~20 σ */
            ck_assert_double_lt(test_max_diff(out, ref, m), 7.0);
        }
}
END_TEST

/* ACCEPTANCE: same seed -> identical bytes; different seed -> different output; both methods, every
 * filter, several levels; out may alias the input points. */
START_TEST(determinism) {
    rugo_vec2 pts[64];
    double lam[64];
    object(64, pts);
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 3, 64, lam), RUGO_OK);
    static rugo_vec2 a[MAXOUT], b[MAXOUT], c[MAXOUT];
    for (int mth = 0; mth < 2; ++mth)
        for (int levels = 1; levels <= 3; ++levels)
            for (int f = 0; f < (int)RUGO_FILTER_COUNT; ++f) {
                const int m = 64 << levels;
                rugo_roughen_def d = rugo_default_roughen_def();
                d.points = pts;
                d.count = 64;
                d.tolerances = lam;
                d.method = METHODS[mth];
                d.levels = levels;
                d.filter = (rugo_filter)f;
                d.seed = 2000;
                ck_assert_int_eq(rugo_roughen(&d, a), RUGO_OK);
                ck_assert_int_eq(rugo_roughen(&d, b), RUGO_OK);
                ck_assert(memcmp(a, b, (size_t)m * sizeof(rugo_vec2)) == 0);
                d.seed = 2001;
                ck_assert_int_eq(rugo_roughen(&d, b), RUGO_OK);
                ck_assert(memcmp(a, b, (size_t)m * sizeof(rugo_vec2)) != 0);
                /* out aliasing the input */
                memcpy(c, pts, sizeof pts);
                d.points = c;
                d.seed = 2000;
                ck_assert_int_eq(rugo_roughen(&d, c), RUGO_OK);
                ck_assert(memcmp(a, c, (size_t)m * sizeof(rugo_vec2)) == 0);
            }
    /* The local method does not use the filter. */
    for (int f = 0; f < (int)RUGO_FILTER_COUNT; ++f) {
        rugo_roughen_def d = rugo_default_roughen_def();
        d.points = pts;
        d.count = 64;
        d.tolerances = lam;
        d.method = RUGO_ROUGHEN_LOCAL;
        d.filter = (rugo_filter)f;
        ck_assert_int_eq(rugo_roughen(&d, b), RUGO_OK);
        if (f == 0) memcpy(a, b, 256 * sizeof(rugo_vec2));
        ck_assert(memcmp(a, b, 256 * sizeof(rugo_vec2)) == 0);
    }
}
END_TEST

/* ACCEPTANCE: zero tolerances give the plain refinement: the wavelet method to round-off (synthesis
 * with zero details vs subdivision), the local method exactly. */
START_TEST(zero_tolerances_give_refinement) {
    rugo_vec2 pts[64];
    double lam[64];
    object(64, pts);
    ck_assert_int_eq(rugo_tolerances_constant(0.0, 64, lam), RUGO_OK);
    static rugo_vec2 out[MAXOUT], ref[MAXOUT];
    for (int levels = 1; levels <= 3; ++levels) {
        const int m = 64 << levels;
        refine(pts, 64, levels, ref);
        const double size = test_max_abs(ref, m);
        for (int f = 0; f < (int)RUGO_FILTER_COUNT; ++f) {
            rugo_roughen_def d = rugo_default_roughen_def();
            d.points = pts;
            d.count = 64;
            d.tolerances = lam;
            d.levels = levels;
            d.filter = (rugo_filter)f;
            d.seed = 9;
            ck_assert_int_eq(rugo_roughen(&d, out), RUGO_OK);
            ck_assert_double_le(test_max_diff(out, ref, m), 1e-13 * size);
        }
        ck_assert_int_eq(roughen(pts, 64, lam, RUGO_ROUGHEN_LOCAL, levels, 9, out), RUGO_OK);
        ck_assert(memcmp(out, ref, (size_t)m * sizeof(rugo_vec2)) == 0);
    }
}
END_TEST

/* ACCEPTANCE (draw order and geometry, wavelet): with one level and a tolerance on segment k only,
 * the output is the synthesis of the input with the single detail d_{k+1} = g σ n, n the outward
 * normal of the input curve at segment k, t = 1/2 (multires.h's frame), σ = λ_k / q, and g the
 * Gaussian number (k+1) mod N (from 0) of rugo_rng seeded with the seed (draw s is detail s). Clockwise
 * input: the same with the true outward normal. */
START_TEST(wavelet_single_segment_draw_order) {
    enum { N = 32 };
    rugo_vec2 pts[N];
    object(N, pts);
    for (int cw = 0; cw < 2; ++cw) {
        if (cw)
            for (int i = 0; i < N / 2; ++i) {
                rugo_vec2 t = pts[i];
                pts[i] = pts[N - 1 - i];
                pts[N - 1 - i] = t;
            }
        rugo_contour c = {pts, N};
        const double sign = cw ? -1.0 : 1.0; /* rugo_contour_normal is outward for CCW only */
        const int ks[] = {0, 5, N - 1};
        for (int ik = 0; ik < 3; ++ik) {
            const int k = ks[ik];
            double lam[N];
            fill(lam, N, 0.0);
            lam[k] = 0.4;
            rugo_vec2 out[2 * N], want[2 * N], det[N];
            for (uint64_t seed = 0; seed < 5; ++seed) {
                ck_assert_int_eq(roughen(pts, N, lam, RUGO_ROUGHEN_WAVELET, 1, seed, out), RUGO_OK);
                rugo_rng rng;
                rugo_rng_seed(&rng, seed);
                double g = 0.0;
                for (int s = 0; s <= (k + 1) % N; ++s)
                    g = rugo_rng_gaussian(&rng);
                for (int s = 0; s < N; ++s)
                    det[s] = rugo_v2(0.0, 0.0);
                det[(k + 1) % N] = rugo_v2_scale(sign * g * 0.4 / 0.95, rugo_contour_normal(c, k, 0.5));
                ck_assert_int_eq(rugo_wavelet_synthesize(RUGO_FILTER_DEFAULT, pts, det, N, want), RUGO_OK);
                ck_assert_double_le(test_max_diff(out, want, 2 * N), 1e-12);
            }
        }
    }
}
END_TEST

/* ACCEPTANCE (draw order and geometry, local): one round, tolerance on segment k only: the refined
 * curve's control points 2k, 2k+1, 2k+2 move by (1/3, 4/3, 1/3) Δ (the least-norm change for the
 * knot at segment 2k+1, t = 0, which is the midpoint of original segment k) and nothing else moves;
 * Δ = g σ n with n the outward normal there and g the (k+1)-th Gaussian; the curve point moves by
 * exactly Δ. Clockwise input: the same with the true outward normal. */
START_TEST(local_single_segment_draw_order) {
    enum { N = 32 };
    rugo_vec2 pts[N];
    object(N, pts);
    for (int cw = 0; cw < 2; ++cw) {
        if (cw)
            for (int i = 0; i < N / 2; ++i) {
                rugo_vec2 t = pts[i];
                pts[i] = pts[N - 1 - i];
                pts[N - 1 - i] = t;
            }
        const double sign = cw ? -1.0 : 1.0;
        rugo_vec2 ref[2 * N], out[2 * N];
        refine(pts, N, 1, ref);
        rugo_contour cref = {ref, 2 * N}, cout = {out, 2 * N};
        const int ks[] = {0, 9, N - 1};
        for (int ik = 0; ik < 3; ++ik) {
            const int k = ks[ik];
            double lam[N];
            fill(lam, N, 0.0);
            lam[k] = 0.3;
            for (uint64_t seed = 10; seed < 15; ++seed) {
                ck_assert_int_eq(roughen(pts, N, lam, RUGO_ROUGHEN_LOCAL, 1, seed, out), RUGO_OK);
                rugo_rng rng;
                rugo_rng_seed(&rng, seed);
                double g = 0.0;
                for (int s = 0; s <= k; ++s)
                    g = rugo_rng_gaussian(&rng);
                const int seg = 2 * k + 1;
                rugo_vec2 delta = rugo_v2_scale(sign * g * 0.3 / 0.95, rugo_contour_normal(cref, seg, 0.0));
                for (int i = 0; i < 2 * N; ++i) {
                    const int rel = rugo__wrap(i - 2 * k, 2 * N);
                    const double w = rel == 0 || rel == 2 ? 1.0 / 3.0 : rel == 1 ? 4.0 / 3.0 : 0.0;
                    rugo_vec2 want = rugo_v2_add(ref[i], rugo_v2_scale(w, delta));
                    ck_assert_near(out[i].x, want.x, 1e-12);
                    ck_assert_near(out[i].y, want.y, 1e-12);
                    if (w == 0.0) ck_assert(out[i].x == ref[i].x && out[i].y == ref[i].y);
                }
                rugo_vec2 moved =
                    rugo_v2_sub(rugo_contour_point(cout, seg, 0.0), rugo_contour_point(cref, seg, 0.0));
                ck_assert_near(moved.x, delta.x, 1e-12);
                ck_assert_near(moved.y, delta.y, 1e-12);
            }
        }
    }
}
END_TEST

/* With one level the perturbation is linear in σ: doubling every tolerance doubles out - refined
 * (same seed) to round-off. With two levels the second level's frames follow the first level's
 * noise, so it is linear only to first order: the departure from linearity, relative to the size of
 * the perturbation, shrinks in proportion to σ (measured about 4.5% for tipo_3 on a 64-point object
 * of radius ~200 with the wavelet method, 0.045% for tipo_3 / 100). */
static double nonlinearity(const rugo_vec2* pts, int n, const double* lam, double scale,
                           rugo_roughen_method method, int levels) {
    static rugo_vec2 a[MAXOUT], b[MAXOUT], ref[MAXOUT];
    double l1[MAXN], l2[MAXN];
    for (int i = 0; i < n; ++i) {
        l1[i] = scale * lam[i];
        l2[i] = 2.0 * scale * lam[i];
    }
    const int m = n << levels;
    refine(pts, n, levels, ref);
    ck_assert_int_eq(roughen(pts, n, l1, method, levels, 4, a), RUGO_OK);
    ck_assert_int_eq(roughen(pts, n, l2, method, levels, 4, b), RUGO_OK);
    double worst = 0.0, size = 0.0;
    for (int i = 0; i < m; ++i) {
        rugo_vec2 da = rugo_v2_sub(a[i], ref[i]), db = rugo_v2_sub(b[i], ref[i]);
        worst = fmax(worst, rugo__v2_length(rugo_v2_sub(db, rugo_v2_scale(2.0, da))));
        size = fmax(size, rugo__v2_length(db));
    }
    ck_assert_double_gt(size, 0.0);
    return worst / size;
}

START_TEST(same_seed_linear_in_sigma) {
    enum { N = 64 };
    rugo_vec2 pts[N];
    object(N, pts);
    double lam[N];
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, N, lam), RUGO_OK);
    for (int mth = 0; mth < 2; ++mth) {
        ck_assert_double_le(nonlinearity(pts, N, lam, 1.0, METHODS[mth], 1), 1e-12);
        ck_assert_double_le(nonlinearity(pts, N, lam, 100.0, METHODS[mth], 1), 1e-12);
        const double r2 = nonlinearity(pts, N, lam, 1e-2, METHODS[mth], 2);
        const double r3 = nonlinearity(pts, N, lam, 1e-3, METHODS[mth], 2);
        ck_assert_msg(r2 <= 1e-3, "method %d: relative nonlinearity %.3g", mth, r2);
        ck_assert_msg(r3 <= 0.2 * r2, "method %d: nonlinearity %.3g at σ/10 vs %.3g", mth, r3, r2);
    }
}
END_TEST

/* ---- roughen: statistics ----------------------------------------------------------------------- */

/* The exact law of the one-level perturbation. With one level the normal deviation at sample u is
 * δ(u) = σ Σ_k a_k(u) g_k, linear in independent N(0,1) draws g_k, with a_k(u) the response to a unit
 * perturbation k (wavelet: detail d_{k+1} = outward normal at segment k, t = 1/2, synthesised;
 * local: the least-norm unit push at original segment k's midpoint on the refined curve), computed
 * here from the public wavelet and contour functions. The mean square over U samples of one draw is
 * then Q = σ² g^T A g with A = (1/U) Σ_u a(u) a(u)^T: E[Q] = σ² tr A, Var[Q] = 2 σ⁴ tr(A²). The
 * average of S seeds must lie within 5 of its exact standard errors of σ² tr A. This also yields the
 * factor between σ and the curve's RMS deviation for one level: 0.950 for the wavelet method (CDF(4,8))
 * and 0.832 for the local one, on a 64-point ball (measured mean squares within 1 SE of the law). */
static void one_level_law(rugo_roughen_method method, const rugo_vec2* pts, int n, double lambda, int seeds,
                          double* expected_ms, double* se, double* measured_ms) {
    const int m = 2 * n, U = m * T;
    const double sigma = lambda / RUGO_DEFAULT_Q;
    double* a = (double*)malloc(sizeof(double) * (size_t)n * (size_t)U); /* a[k * U + u] */
    rugo_vec2* ref = (rugo_vec2*)malloc(sizeof(rugo_vec2) * (size_t)m);
    rugo_vec2* resp = (rugo_vec2*)malloc(sizeof(rugo_vec2) * (size_t)m);
    rugo_vec2* det = (rugo_vec2*)malloc(sizeof(rugo_vec2) * (size_t)n);
    double* dev = (double*)malloc(sizeof(double) * (size_t)U);
    ck_assert(a && ref && resp && det && dev);
    refine(pts, n, 1, ref);
    rugo_contour c = {pts, n}, cref = {ref, m};
    for (int k = 0; k < n; ++k) {
        if (method == RUGO_ROUGHEN_WAVELET) {
            for (int s = 0; s < n; ++s)
                det[s] = rugo_v2(0.0, 0.0);
            det[(k + 1) % n] = rugo_contour_normal(c, k, 0.5);
            ck_assert_int_eq(rugo_wavelet_synthesize(RUGO_FILTER_DEFAULT, pts, det, n, resp), RUGO_OK);
        } else {
            memcpy(resp, ref, sizeof(rugo_vec2) * (size_t)m);
            rugo_vec2 nm = rugo_contour_normal(cref, 2 * k + 1, 0.0);
            double w[4];
            rugo_bspline_basis(0.0, w);
            double nn = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + w[3] * w[3];
            for (int i = 0; i < 4; ++i) {
                int idx = rugo__wrap(2 * k + i, m);
                resp[idx] = rugo_v2_add(resp[idx], rugo_v2_scale(w[i] / nn, nm));
            }
        }
        deviations(resp, ref, m, a + (size_t)k * U);
    }
    double trA = 0.0, trA2 = 0.0;
    for (int k = 0; k < n; ++k)
        for (int l = 0; l < n; ++l) {
            double s = 0.0;
            for (int u = 0; u < U; ++u)
                s += a[(size_t)k * U + u] * a[(size_t)l * U + u];
            s /= U;
            if (k == l) trA += s;
            trA2 += s * s;
        }
    double lam[MAXN];
    fill(lam, n, lambda);
    double total = 0.0;
    for (int seed = 0; seed < seeds; ++seed) {
        ck_assert_int_eq(roughen(pts, n, lam, method, 1, (uint64_t)seed, resp), RUGO_OK);
        deviations(resp, ref, m, dev);
        double ms = 0.0;
        for (int u = 0; u < U; ++u)
            ms += dev[u] * dev[u];
        total += ms / U;
    }
    *expected_ms = sigma * sigma * trA;
    *se = sigma * sigma * sqrt(2.0 * trA2 / seeds);
    *measured_ms = total / seeds;
    free(a);
    free(ref);
    free(resp);
    free(det);
    free(dev);
}

START_TEST(one_level_variance_exact_law) {
    enum { N = 64 };
    rugo_vec2 pts[N];
    ball(N, 200.0, pts);
    for (int mth = 0; mth < 2; ++mth) {
        double e, se, got;
        one_level_law(METHODS[mth], pts, N, 0.5, 300, &e, &se, &got);
        ck_assert_msg(fabs(got - e) <= 5.0 * se, "method %d: mean square %.6g, expected %.6g +- %.3g", mth,
                      got, e, se);
        /* the factor RMS / σ */
        const double sigma = 0.5 / RUGO_DEFAULT_Q, f = sqrt(e) / sigma;
        if (mth == 0)
            ck_assert_msg(f > 0.9 && f < 1.05, "wavelet factor %.4f", f);
        else
            ck_assert_msg(f > 0.78 && f < 0.88, "local factor %.4f", f);
    }
}
END_TEST

/* RMS normal deviation over S seeds of a constant-λ profile, and its mean. */
static void rms_deviation(const rugo_vec2* pts, int n, double lambda, rugo_roughen_method method, int levels,
                          int seeds, uint64_t seed0, double* rms, double* mean) {
    const int m = n << levels, U = m * T;
    static rugo_vec2 out[MAXOUT], ref[MAXOUT];
    static double dev[MAXOUT * T];
    double lam[MAXN];
    fill(lam, n, lambda);
    refine(pts, n, levels, ref);
    double s2 = 0.0, s1 = 0.0;
    for (int s = 0; s < seeds; ++s) {
        ck_assert_int_eq(roughen(pts, n, lam, method, levels, seed0 + (uint64_t)s, out), RUGO_OK);
        deviations(out, ref, m, dev);
        for (int u = 0; u < U; ++u) {
            s2 += dev[u] * dev[u];
            s1 += dev[u];
        }
    }
    *rms = sqrt(s2 / ((double)U * seeds));
    *mean = s1 / ((double)U * seeds);
}

/* ACCEPTANCE: the deviation scales with σ. Two levels, 100 seeds each (independent seeds per σ),
 * λ = 0.01, 0.1, 1 on an object of radius ~200 (segments ~5 long at the output level, so σ stays
 * small against them; at σ ~ segment length the wavelet method's second-level frames tilt and RMS/σ
 * drops, measured -9% at λ = 5): RMS / σ agrees across σ within 5% (each estimate's relative SE is
 * about 0.7%, as the first level's 64 draws per seed dominate, so 5% is about 5 SE of a ratio) and
 * lies in the measured band (wavelet 1.32-1.36, local 1.18 for two levels; the band allows
 * ±10%); the mean deviation is 0 within 5% of σ (about 5 SE for the local method; the wavelet
 * method's is ~1e-6 σ, its synthesis wavelets having vanishing moments). */
START_TEST(deviation_scales_with_sigma) {
    enum { N = 64 };
    rugo_vec2 pts[N];
    object(N, pts);
    const double lambdas[3] = {0.01, 0.1, 1.0};
    const double centre[2] = {1.35, 1.18};
    for (int mth = 0; mth < 2; ++mth) {
        double f[3];
        for (int i = 0; i < 3; ++i) {
            double rms, mean;
            const double sigma = lambdas[i] / RUGO_DEFAULT_Q;
            rms_deviation(pts, N, lambdas[i], METHODS[mth], 2, 100, 1000u * (uint64_t)(i + 1), &rms, &mean);
            f[i] = rms / sigma;
            ck_assert_msg(fabs(f[i] - centre[mth]) <= 0.1 * centre[mth], "method %d λ %g: RMS/σ %.4f", mth,
                          lambdas[i], f[i]);
            ck_assert_msg(fabs(mean) <= 0.05 * sigma, "method %d: mean deviation %.3g σ", mth, mean / sigma);
        }
        ck_assert_double_le(fabs(f[1] / f[0] - 1.0), 0.05);
        ck_assert_double_le(fabs(f[2] / f[0] - 1.0), 0.05);
    }
}
END_TEST

/* ACCEPTANCE: a constant λ gives statistically uniform roughness: on a 64-point ball, two levels,
 * 200 seeds, the RMS normal deviation over each quarter of the contour (16 original segments) is
 * within 5% of the whole contour's (per-quarter relative SE about 1%, the first level's 16 draws per
 * quarter and seed dominating; measured deviations at most 2.1%). */
START_TEST(constant_lambda_uniform) {
    enum { N = 64, LEVELS = 2, M = N << LEVELS, S = 200 };
    rugo_vec2 pts[N];
    ball(N, 200.0, pts);
    double lam[N];
    fill(lam, N, 0.25);
    static rugo_vec2 out[M], ref[M];
    static double dev[M * T];
    refine(pts, N, LEVELS, ref);
    for (int mth = 0; mth < 2; ++mth) {
        double q[4] = {0, 0, 0, 0};
        for (int s = 0; s < S; ++s) {
            ck_assert_int_eq(roughen(pts, N, lam, METHODS[mth], LEVELS, 50000u + (uint64_t)s, out), RUGO_OK);
            deviations(out, ref, M, dev);
            for (int u = 0; u < M * T; ++u)
                q[u / (M * T / 4)] += dev[u] * dev[u];
        }
        const double all = sqrt((q[0] + q[1] + q[2] + q[3]) / (M * T * S));
        for (int i = 0; i < 4; ++i) {
            const double qi = sqrt(q[i] / (M * T / 4 * S));
            ck_assert_msg(fabs(qi / all - 1.0) <= 0.05, "method %d quarter %d: %.4f vs %.4f", mth, i, qi,
                          all);
        }
    }
}
END_TEST

/* ACCEPTANCE: tipo_5 shapes are visibly rougher on the 0.55 / 0.65 blocks than on the 0.04 blocks.
 * 128-point object, two levels, 50 seeds; RMS normal deviation over the output samples lying on
 * each block's original segments, grouped by the block's λ, over whole blocks and over their two
 * central segments. The λ ratios are 14 and 16, but perturbations spread over neighbouring segments
 * (CDF(4,8)'s synthesis wavelet reaches about 2 original segments each side; the local method's
 * pushes 1), so the quiet 0.04 blocks pick up roughness at their edges. Measured RMS ratios
 * (0.55 : 0.04, 0.65 : 0.04): wavelet 2.7, 3.1 whole blocks, 6.4, 7.5 central; the local method's
 * are larger (6.7, 7.8 whole and 13, 15 central with one push per original segment per round; the
 * thesis' rule used now pushes every current segment and still passes the thresholds). Asserted:
 * whole-block ratios > 2, central > 4, 0.65 blocks rougher than 0.55. */
START_TEST(tipo_5_blocks_differ) {
    enum { N = 128, LEVELS = 2, M = N << LEVELS, S = 50 };
    rugo_vec2 pts[N];
    object(N, pts);
    double lam[N];
    ck_assert_int_eq(rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, N, lam), RUGO_OK);
    static rugo_vec2 out[M], ref[M];
    static double dev[M * T];
    refine(pts, N, LEVELS, ref);
    for (int mth = 0; mth < 2; ++mth) {
        double ss[2][3] = {{0, 0, 0}, {0, 0, 0}};
        long cnt[2][3] = {{0, 0, 0}, {0, 0, 0}};
        for (int s = 0; s < S; ++s) {
            ck_assert_int_eq(roughen(pts, N, lam, METHODS[mth], LEVELS, 7000u + (uint64_t)s, out), RUGO_OK);
            deviations(out, ref, M, dev);
            for (int u = 0; u < M * T; ++u) {
                const int k = (u / T) >> LEVELS; /* original segment of the output segment */
                const int g = lam[k] == 0.04 ? 0 : lam[k] == 0.55 ? 1 : 2;
                const int central = k % 4 == 1 || k % 4 == 2;
                for (int w = 0; w <= central; ++w) {
                    ss[w][g] += dev[u] * dev[u];
                    ++cnt[w][g];
                }
            }
        }
        double r[2][3];
        for (int w = 0; w < 2; ++w)
            for (int g = 0; g < 3; ++g)
                r[w][g] = sqrt(ss[w][g] / cnt[w][g]);
        ck_assert_msg(
            r[0][1] / r[0][0] > 2.0 && r[0][2] / r[0][0] > 2.0 && r[1][1] / r[1][0] > 4.0 &&
                r[1][2] / r[1][0] > 4.0 && r[0][2] > r[0][1] && r[1][2] > r[1][1],
            "method %d: RMS on 0.04 / 0.55 / 0.65 blocks: whole %.4f %.4f %.4f, central %.4f %.4f %.4f", mth,
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2]);
    }
}
END_TEST

/* ---- roughen: allocator and bad input ---------------------------------------------------------- */

typedef struct counter {
    int allocs, frees, fail;
} counter;
static void* counting_alloc(size_t size, void* ctx) {
    counter* c = (counter*)ctx;
    if (c->fail) return NULL;
    ++c->allocs;
    return malloc(size);
}
static void counting_free(void* p, void* ctx) {
    ++((counter*)ctx)->frees;
    free(p);
}

START_TEST(allocator_used) {
    rugo_vec2 pts[32];
    double lam[32];
    object(32, pts);
    fill(lam, 32, 0.2);
    static rugo_vec2 a[128], b[128];
    for (int mth = 0; mth < 2; ++mth) {
        ck_assert_int_eq(roughen(pts, 32, lam, METHODS[mth], 2, 3, a), RUGO_OK);
        counter cnt = {0, 0, 0};
        rugo_roughen_def d = rugo_default_roughen_def();
        d.points = pts;
        d.count = 32;
        d.tolerances = lam;
        d.method = METHODS[mth];
        d.seed = 3;
        d.allocator.alloc = counting_alloc;
        d.allocator.free = counting_free;
        d.allocator.ctx = &cnt;
        ck_assert_int_eq(rugo_roughen(&d, b), RUGO_OK);
        ck_assert_int_ge(cnt.allocs, 1);
        ck_assert_int_eq(cnt.allocs, cnt.frees);
        ck_assert(memcmp(a, b, sizeof a) == 0);
        cnt.fail = 1;
        for (int i = 0; i < 128; ++i)
            b[i] = rugo_v2(SENTINEL, SENTINEL);
        ck_assert_int_eq(rugo_roughen(&d, b), RUGO_ERR_OUT_OF_MEMORY);
        for (int i = 0; i < 128; ++i)
            ck_assert_double_eq(b[i].x, SENTINEL);
    }
}
END_TEST

START_TEST(roughen_bad_input) {
    rugo_vec2 pts[64];
    double lam[64];
    object(64, pts);
    fill(lam, 64, 0.2);
    static rugo_vec2 out[256];
    for (int i = 0; i < 256; ++i)
        out[i] = rugo_v2(SENTINEL, SENTINEL);
    rugo_roughen_def good = rugo_default_roughen_def();
    good.points = pts;
    good.count = 64;
    good.tolerances = lam;
    rugo_roughen_def d;

    ck_assert_int_eq(rugo_roughen(NULL, out), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughen(&good, NULL), RUGO_ERR_NULL_ARGUMENT);
    d = good;
    d.cookie = 0;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_ARGUMENT);
    d = good;
    d.points = NULL;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NULL_ARGUMENT);
    d = good;
    d.tolerances = NULL;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NULL_ARGUMENT);
    d = good;
    d.method = (rugo_roughen_method)2;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_ARGUMENT);
    d.method = (rugo_roughen_method)-1;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_ARGUMENT);
    const int bad_levels[] = {0, -1, 15, 31, 1000, -2147483647 - 1};
    for (int i = 0; i < 6; ++i) {
        d = good;
        d.levels = bad_levels[i]; /* 64 << 15 = 2^21 points: beyond RUGO_MAX_CONTROL_POINTS */
        ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_ARGUMENT);
    }
    d = good;
    d.filter = RUGO_FILTER_COUNT;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_FILTER);
    d.filter = (rugo_filter)-1;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_FILTER);
    d = good;
    d.count = 2;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_TOO_FEW_POINTS);
    d.count = 0;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_TOO_FEW_POINTS);
    d.count = -64;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_TOO_FEW_POINTS);
    d.count = 2 * RUGO_MAX_CONTROL_POINTS; /* refused before anything is read */
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_TOO_MANY_POINTS);
    d.count = 48;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_POWER_OF_TWO);
    d.count = 6;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_POWER_OF_TWO);
    const double bad_q[] = {0.0, -0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 6; ++i) {
        d = good;
        d.q = bad_q[i];
        ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_BAD_QUANTILE);
    }
    rugo_vec2 bad_pts[64];
    memcpy(bad_pts, pts, sizeof pts);
    bad_pts[17].y = NAN;
    d = good;
    d.points = bad_pts;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_FINITE);
    bad_pts[17].y = 0.0;
    bad_pts[63].x = -INFINITY;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_FINITE);
    double bad_lam[64];
    memcpy(bad_lam, lam, sizeof lam);
    bad_lam[40] = NAN;
    d = good;
    d.tolerances = bad_lam;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_FINITE);
    bad_lam[40] = -0.01;
    ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NEGATIVE_TOLERANCE);
    /* Finite input whose perturbation overflows: σ = DBL_MAX / q is infinite. */
    bad_lam[40] = DBL_MAX;
    for (int mth = 0; mth < 2; ++mth) {
        d.method = METHODS[mth];
        ck_assert_int_eq(rugo_roughen(&d, out), RUGO_ERR_NOT_FINITE);
    }
    for (int i = 0; i < 256; ++i)
        ck_assert_double_eq(out[i].x, SENTINEL); /* nothing written */

    /* The smallest valid input, 4 points, works for both methods and any filter. */
    rugo_vec2 four[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    double lam4[4] = {0.01, 0.02, 0.0, 0.05};
    for (int mth = 0; mth < 2; ++mth)
        for (int f = 0; f < (int)RUGO_FILTER_COUNT; ++f) {
            d = rugo_default_roughen_def();
            d.points = four;
            d.count = 4;
            d.tolerances = lam4;
            d.method = METHODS[mth];
            d.filter = (rugo_filter)f;
            d.levels = 3;
            ck_assert_int_eq(rugo_roughen(&d, out), RUGO_OK);
            for (int i = 0; i < 32; ++i)
                ck_assert(rugo__v2_finite(out[i]));
        }
}
END_TEST

static Suite* rough_suite(void) {
    Suite* s = suite_create("rough");
    TCase* tl = tcase_create("library");
    tcase_add_test(tl, preset_names);
    tcase_add_test(tl, preset_tipo_1_constant);
    tcase_add_test(tl, preset_tipo_3_tipo_5_fig55);
    tcase_add_test(tl, preset_tipo_2_draw_order);
    tcase_add_test(tl, preset_tipo_2_properties);
    tcase_add_test(tl, preset_errors);
    tcase_add_test(tl, constant_values_and_errors);
    tcase_add_test(tl, pattern_values_and_errors);
    tcase_add_test(tl, blocks_values_and_errors);
    tcase_add_test(tl, random_values_and_errors);
    tcase_add_test(tl, check_values);
    suite_add_tcase(s, tl);
    TCase* tr = tcase_create("roughen");
    tcase_add_test(tr, default_def);
    tcase_add_test(tr, output_count);
    tcase_add_test(tr, determinism);
    tcase_add_test(tr, zero_tolerances_give_refinement);
    tcase_add_test(tr, wavelet_single_segment_draw_order);
    tcase_add_test(tr, local_single_segment_draw_order);
    tcase_add_test(tr, same_seed_linear_in_sigma);
    suite_add_tcase(s, tr);
    TCase* ts = tcase_create("statistics");
    tcase_set_timeout(ts, 120);
    tcase_add_test(ts, one_level_variance_exact_law);
    tcase_add_test(ts, deviation_scales_with_sigma);
    tcase_add_test(ts, constant_lambda_uniform);
    tcase_add_test(ts, tipo_5_blocks_differ);
    suite_add_tcase(s, ts);
    TCase* tb = tcase_create("bad_input");
    tcase_add_test(tb, allocator_used);
    tcase_add_test(tb, roughen_bad_input);
    suite_add_tcase(s, tb);
    return s;
}

int main(void) { return test_run_suite(rough_suite()); }
