/* Random suite: the library's seeded generator (random.h): xoshiro256** seeded by splitmix64, uniform
 * doubles, unbiased bounded integers, Marsaglia polar Gaussians.
 *
 * Golden values were computed once by an independent Python reimplementation of splitmix64 and
 * xoshiro256** written from Blackman & Vigna's reference code (not from random.c); the same script
 * reproduces the published first splitmix64 output for seed 0, 0xe220a8397b1dcdaf, which is pinned
 * below too. The statistical checks run on fixed seeds, so they are deterministic; their thresholds
 * are five standard errors (probability of a false alarm for a correct generator ~ 6e-7 each) or,
 * for chi-square, the upper 1e-6 quantile of the distribution. */
#include "test_util.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

enum { BIG = 1000000 };

/* ---- golden values --------------------------------------------------------------------------- */

/* First outputs of rugo_rng_next after rugo_rng_seed(seed). */
START_TEST(next_golden_values) {
    static const struct {
        uint64_t seed;
        uint64_t first[5];
    } golden[] = {
        {0u,
         {0x99ec5f36cb75f2b4ull, 0xbf6e1f784956452aull, 0x1a5f849d4933e6e0ull, 0x6aa594f1262d2d2cull,
          0xbba5ad4a1f842e59ull}},
        {42u,
         {0x15780b2e0c2ec716ull, 0x6104d9866d113a7eull, 0xae17533239e499a1ull, 0xecb8ad4703b360a1ull,
          0xfde6dc7fe2ec5e64ull}},
        {UINT64_MAX,
         {0x8f5520d52a7ead08ull, 0xc476a018caa1802dull, 0x81de31c0d260469eull, 0xbf658d7e065f3c2full,
          0x913593fda1bca32aull}},
    };
    for (size_t g = 0; g < sizeof golden / sizeof golden[0]; ++g) {
        rugo_rng rng;
        rugo_rng_seed(&rng, golden[g].seed);
        for (int i = 0; i < 5; ++i) {
            uint64_t v = rugo_rng_next(&rng);
            ck_assert_msg(v == golden[g].first[i], "seed %llu output %d: 0x%016llx, want 0x%016llx",
                          (unsigned long long)golden[g].seed, i, (unsigned long long)v,
                          (unsigned long long)golden[g].first[i]);
        }
    }
}
END_TEST

/* The seeding: the state is the first four splitmix64 outputs of the seed. */
START_TEST(seed_state_golden) {
    rugo_rng rng;
    rugo_rng_seed(&rng, 0);
    ck_assert(rng.state[0] == 0xe220a8397b1dcdafull); /* splitmix64's published first output for 0 */
    ck_assert(rng.state[1] == 0x6e789e6aa1b965f4ull);
    ck_assert(rng.state[2] == 0x06c45d188009454full);
    ck_assert(rng.state[3] == 0xf88bb8a8724c81ecull);
    ck_assert(!rng.has_spare);
    rugo_rng_seed(NULL, 1); /* tolerated */
}
END_TEST

/* Uniforms are the top 53 bits times 2^-53: exact values. */
START_TEST(uniform_golden_values) {
    static const uint64_t top53[3] = {755370490430936ull, 3413550631330343ull, 6125286505004179ull};
    rugo_rng rng;
    rugo_rng_seed(&rng, 42);
    for (int i = 0; i < 3; ++i)
        ck_assert(rugo_rng_uniform(&rng) == (double)top53[i] * 0x1.0p-53);
    /* range = lo + (hi - lo) u with the same draws */
    rugo_rng_seed(&rng, 42);
    ck_assert(rugo_rng_range(&rng, -3.0, 5.0) == -3.0 + 8.0 * ((double)top53[0] * 0x1.0p-53));
    /* bounds whose difference overflows: lo (1 - u) + hi u, inside [lo, hi] (was inf) */
    for (int i = 0; i < 100; ++i) {
        const double v = rugo_rng_range(&rng, -DBL_MAX, DBL_MAX);
        ck_assert(isfinite(v) && v >= -DBL_MAX && v <= DBL_MAX);
    }
    rugo_rng_seed(&rng, 42);
    ck_assert(rugo_rng_range(&rng, -DBL_MAX, DBL_MAX) ==
              -DBL_MAX * (1.0 - (double)top53[0] * 0x1.0p-53) + DBL_MAX * ((double)top53[0] * 0x1.0p-53));
}
END_TEST

/* rugo_rng_below(10) for seed 3 (rejection included). */
START_TEST(below_golden_values) {
    static const uint32_t want[8] = {0, 4, 5, 3, 5, 8, 3, 5};
    rugo_rng rng;
    rugo_rng_seed(&rng, 3);
    for (int i = 0; i < 8; ++i)
        ck_assert_uint_eq(rugo_rng_below(&rng, 10), want[i]);
}
END_TEST

/* The first polar pair for seed 7. The reference values used the platform's log through Python, so
 * they are compared to 4 ulps rather than bit for bit (log is the one libm-dependent step). */
START_TEST(gaussian_golden_values) {
    rugo_rng rng;
    rugo_rng_seed(&rng, 7);
    double a = rugo_rng_gaussian(&rng), b = rugo_rng_gaussian(&rng);
    ck_assert_near(a, 0.9643618527255184, 4 * 2.2e-16);
    ck_assert_near(b, -1.0637531974798475, 4 * 2.2e-16);
}
END_TEST

/* ---- determinism ------------------------------------------------------------------------------ */

START_TEST(same_seed_same_sequence) {
    rugo_rng a, b;
    rugo_rng_seed(&a, 123456789);
    rugo_rng_seed(&b, 123456789);
    int differ = 0;
    for (int i = 0; i < 10000; ++i) {
        if (rugo_rng_next(&a) != rugo_rng_next(&b)) ++differ;
        double ga = rugo_rng_gaussian(&a), gb = rugo_rng_gaussian(&b);
        if (memcmp(&ga, &gb, sizeof ga) != 0) ++differ;
        double ua = rugo_rng_uniform(&a), ub = rugo_rng_uniform(&b);
        if (memcmp(&ua, &ub, sizeof ua) != 0) ++differ;
        if (rugo_rng_below(&a, 1000003) != rugo_rng_below(&b, 1000003)) ++differ;
    }
    ck_assert_int_eq(differ, 0);
    ck_assert(memcmp(a.state, b.state, sizeof a.state) == 0);
    /* Reseeding restarts the sequence. */
    rugo_rng_seed(&a, 5);
    uint64_t first = rugo_rng_next(&a);
    rugo_rng_seed(&a, 5);
    ck_assert(rugo_rng_next(&a) == first);
}
END_TEST

START_TEST(different_seeds_differ) {
    /* The first outputs of 1000 consecutive seeds are all distinct, and two neighbouring seeds give
     * sequences that agree nowhere in their first 1000 words. */
    enum { S = 1000 };
    static uint64_t first[S];
    for (int s = 0; s < S; ++s) {
        rugo_rng rng;
        rugo_rng_seed(&rng, (uint64_t)s);
        first[s] = rugo_rng_next(&rng);
    }
    int same = 0;
    for (int i = 0; i < S; ++i)
        for (int j = i + 1; j < S; ++j)
            same += first[i] == first[j];
    rugo_rng a, b;
    rugo_rng_seed(&a, 1);
    rugo_rng_seed(&b, 2);
    for (int i = 0; i < S; ++i)
        same += rugo_rng_next(&a) == rugo_rng_next(&b);
    ck_assert_int_eq(same, 0);
}
END_TEST

/* The polar method keeps the second sample of each pair: the spare is reset by seeding, copied with
 * the struct, and served without consuming uniforms. */
START_TEST(gaussian_spare_handling) {
    rugo_rng a;
    rugo_rng_seed(&a, 99);
    double g1 = rugo_rng_gaussian(&a);
    ck_assert(a.has_spare);
    rugo_rng copy = a; /* mid-pair */
    double g2 = rugo_rng_gaussian(&a);
    ck_assert(!a.has_spare);
    ck_assert(rugo_rng_gaussian(&copy) == g2);
    ck_assert(memcmp(a.state, copy.state, sizeof a.state) == 0);

    /* Interleaving: gaussian, uniform, gaussian. The second gaussian is the spare, and the uniform is
     * the first word after the pair's uniforms. */
    rugo_rng b, ref;
    rugo_rng_seed(&b, 99);
    rugo_rng_seed(&ref, 99);
    double h1 = rugo_rng_gaussian(&b);
    double u = rugo_rng_uniform(&b);
    double h2 = rugo_rng_gaussian(&b);
    ck_assert(h1 == g1 && h2 == g2);
    (void)rugo_rng_gaussian(&ref);
    (void)rugo_rng_gaussian(&ref);
    ck_assert(rugo_rng_uniform(&ref) == u);

    /* Reseeding drops a pending spare. */
    rugo_rng_seed(&b, 99);
    (void)rugo_rng_gaussian(&b);
    rugo_rng_seed(&b, 99);
    ck_assert(!b.has_spare);
    ck_assert(rugo_rng_gaussian(&b) == g1);
}
END_TEST

/* ---- distributions ----------------------------------------------------------------------------- */

/* 10^6 uniforms: all in [0, 1) on the 2^-53 grid; mean 1/2 within 5 standard errors
 * (SE = sqrt(1/12 / N) = 2.9e-4), variance 1/12 within 5 SE (SE = sqrt((1/80 - 1/144) / N) = 7.5e-5);
 * the 10 equal bins pass chi-square at the 1e-6 level (df 9: 44.81). */
START_TEST(uniform_moments_and_bins) {
    rugo_rng rng;
    rugo_rng_seed(&rng, 2024);
    double sum = 0.0, sum2 = 0.0;
    long bins[10] = {0}, bad = 0;
    for (int i = 0; i < BIG; ++i) {
        double u = rugo_rng_uniform(&rng);
        double scaled = u * 0x1.0p53;
        /* (Per-sample ck_asserts would cost a system call each: count, then assert once.) */
        if (!(u >= 0.0 && u < 1.0) || scaled != floor(scaled)) {
            ++bad;
            continue;
        }
        sum += u;
        sum2 += (u - 0.5) * (u - 0.5);
        ++bins[(int)(u * 10.0)];
    }
    ck_assert_int_eq(bad, 0);
    const double mean = sum / BIG, var = sum2 / BIG;
    ck_assert_near(mean, 0.5, 5.0 * sqrt(1.0 / 12.0 / BIG));
    ck_assert_near(var, 1.0 / 12.0, 5.0 * sqrt((1.0 / 80.0 - 1.0 / 144.0) / BIG));
    double chi2 = 0.0, e = BIG / 10.0;
    for (int k = 0; k < 10; ++k)
        chi2 += (bins[k] - e) * (bins[k] - e) / e;
    ck_assert_msg(chi2 < 44.81, "chi-square %.3f", chi2);

    for (int i = 0; i < 1000; ++i) {
        double v = rugo_rng_range(&rng, -2.5, 7.0);
        if (!(v >= -2.5 && v <= 7.0)) ++bad;
    }
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* rugo_rng_below: edge counts, powers of two, chi-square on small n, and a large n where plain
 * modulo would be badly biased. */
START_TEST(below_unbiased) {
    rugo_rng rng;
    rugo_rng_seed(&rng, 77);
    int bad = 0;
    for (int i = 0; i < 100; ++i) {
        bad += rugo_rng_below(&rng, 0) != 0;
        bad += rugo_rng_below(&rng, 1) != 0;
        bad += rugo_rng_below(&rng, 8) >= 8;
        bad += rugo_rng_below(&rng, UINT32_MAX) >= UINT32_MAX;
    }
    ck_assert_int_eq(bad, 0);
    /* Chi-square for n = 4 (a power of two: no rejection), 7 and 10, 10^6 draws each; thresholds are
     * the upper 1e-6 quantiles for df = n - 1 (30.66, 38.26, 44.81). */
    static const uint32_t ns[3] = {4, 7, 10};
    static const double limits[3] = {30.66, 38.26, 44.81};
    for (int c = 0; c < 3; ++c) {
        long counts[10] = {0}, out_of_range = 0;
        for (int i = 0; i < BIG; ++i) {
            uint32_t v = rugo_rng_below(&rng, ns[c]);
            if (v < ns[c])
                ++counts[v];
            else
                ++out_of_range;
        }
        ck_assert_int_eq(out_of_range, 0);
        double chi2 = 0.0, e = (double)BIG / ns[c];
        for (uint32_t k = 0; k < ns[c]; ++k)
            chi2 += (counts[k] - e) * (counts[k] - e) / e;
        ck_assert_msg(chi2 < limits[c], "n = %u: chi-square %.3f", ns[c], chi2);
    }
    /* n = 3 * 2^30: 2^32 mod n = 2^30, so r mod n without rejection would give values below 2^30
     * with probability 1/2 instead of 1/3. Unbiased: fraction 1/3 within 5 SE (SE = 4.7e-4). */
    const uint32_t n = 3u << 30;
    long low = 0;
    for (int i = 0; i < BIG; ++i)
        if (rugo_rng_below(&rng, n) < (1u << 30)) ++low;
    ck_assert_near((double)low / BIG, 1.0 / 3.0, 5.0 * sqrt((1.0 / 3.0) * (2.0 / 3.0) / BIG));
}
END_TEST

/* 10^6 Gaussians: mean 0 (SE 1e-3), variance 1 (SE sqrt(2/N) = 1.4e-3), fourth moment 3 (kurtosis;
 * SE sqrt((105 - 9)/N) = 9.8e-3), skewness (third moment, SE sqrt(15/N) = 3.9e-3), all within 5 SE;
 * P(|Z| <= 0.95) = 0.6579 (the thesis' q) and P(|Z| <= 1.96) = 0.9500 within 5 SE. */
START_TEST(gaussian_moments) {
    rugo_rng rng;
    rugo_rng_seed(&rng, 31337);
    double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
    long in095 = 0, in196 = 0, not_finite = 0;
    for (int i = 0; i < BIG; ++i) {
        double z = rugo_rng_gaussian(&rng);
        if (!isfinite(z)) {
            ++not_finite;
            continue;
        }
        double z2 = z * z;
        s1 += z;
        s2 += z2;
        s3 += z2 * z;
        s4 += z2 * z2;
        if (fabs(z) <= 0.95) ++in095;
        if (fabs(z) <= 1.96) ++in196;
    }
    ck_assert_int_eq(not_finite, 0);
    ck_assert_near(s1 / BIG, 0.0, 5.0 * sqrt(1.0 / BIG));
    ck_assert_near(s2 / BIG, 1.0, 5.0 * sqrt(2.0 / BIG));
    ck_assert_near(s3 / BIG, 0.0, 5.0 * sqrt(15.0 / BIG));
    ck_assert_near(s4 / BIG, 3.0, 5.0 * sqrt(96.0 / BIG));
    const double p095 = 0.6578877473830363, p196 = 0.9500042097035591;
    ck_assert_near((double)in095 / BIG, p095, 5.0 * sqrt(p095 * (1.0 - p095) / BIG));
    ck_assert_near((double)in196 / BIG, p196, 5.0 * sqrt(p196 * (1.0 - p196) / BIG));
}
END_TEST

/* Gaussian pairs are independent draws: the correlation of the two members of each pair, and of
 * consecutive pairs, is 0 within 5 SE (SE = 1/sqrt(pairs)). */
START_TEST(gaussian_pairs_uncorrelated) {
    enum { PAIRS = 200000 };
    rugo_rng rng;
    rugo_rng_seed(&rng, 8);
    double within = 0.0, across = 0.0, prev = 0.0;
    for (int i = 0; i < PAIRS; ++i) {
        double a = rugo_rng_gaussian(&rng), b = rugo_rng_gaussian(&rng);
        within += a * b;
        across += prev * a;
        prev = b;
    }
    ck_assert_near(within / PAIRS, 0.0, 5.0 / sqrt((double)PAIRS));
    ck_assert_near(across / PAIRS, 0.0, 5.0 / sqrt((double)PAIRS));
}
END_TEST

static Suite* random_suite(void) {
    Suite* s = suite_create("random");
    TCase* tg = tcase_create("golden");
    tcase_add_test(tg, next_golden_values);
    tcase_add_test(tg, seed_state_golden);
    tcase_add_test(tg, uniform_golden_values);
    tcase_add_test(tg, below_golden_values);
    tcase_add_test(tg, gaussian_golden_values);
    suite_add_tcase(s, tg);
    TCase* td = tcase_create("determinism");
    tcase_add_test(td, same_seed_same_sequence);
    tcase_add_test(td, different_seeds_differ);
    tcase_add_test(td, gaussian_spare_handling);
    suite_add_tcase(s, td);
    TCase* ts = tcase_create("statistics");
    tcase_set_timeout(ts, 60);
    tcase_add_test(ts, uniform_moments_and_bins);
    tcase_add_test(ts, below_unbiased);
    tcase_add_test(ts, gaussian_moments);
    tcase_add_test(ts, gaussian_pairs_uncorrelated);
    suite_add_tcase(s, ts);
    return s;
}

int main(void) { return test_run_suite(random_suite()); }
