/* How much of a rough curve lies outside the tolerance bands of its coarser levels?
 *
 * λ = q σ is a statistical band (thesis 5.1-5.3): for a normal perturbation a fraction
 * P(|Z| > q) = erfc(q / sqrt 2) of it lies outside (0.342 for the thesis' q = 0.95), and the thesis'
 * accumulation (5.3) adds bands rather than variances, so coarser levels are expected to be wider
 * than that. β is the hard bound and must never be exceeded. This sample measures both.
 *
 * The shape: sample_object(32) with three levels of outward roughness synthesised here (N(0, σ²) in
 * the local frames, σ in blocks along the contour and shrinking by 0.6 per finer level): 256 segments.
 * Finest tolerances 0, so every band comes from geometry the pyramid can see.
 * For every level j < 8 and both estimators: dense samples of the finest curve (16 per finest
 * segment), their distance to the level's curve (closest point), and whether it exceeds λ^j(t) at
 * that closest point (total band; also the level's own band alone). β: the distance of each sample
 * to its own coarse segment (brute force) plus the finest band, against β^j_k; checked again with
 * non-zero finest tolerances. Writes band_coverage.json and prints a table. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { N0 = 32, ADDED = 3, N = N0 << ADDED, J = 8, JMIN = 3, S = 16 };

/* Distance from p to segment k of c: the best of 65 samples refined by golden section. It can only
 * overestimate the true distance, which makes the β check strict. */
static double dist_to_segment(rugo_contour c, int k, rugo_vec2 p) {
    double best = INFINITY, bt = 0.0;
    for (int i = 0; i <= 64; ++i) {
        double t = i / 64.0;
        double d = hypot(rugo_contour_point(c, k, t).x - p.x, rugo_contour_point(c, k, t).y - p.y);
        if (d < best) {
            best = d;
            bt = t;
        }
    }
    double a = fmax(0.0, bt - 1.0 / 64), b = fmin(1.0, bt + 1.0 / 64);
    const double g = 0.6180339887498949;
    for (int it = 0; it < 60; ++it) {
        double x1 = b - g * (b - a), x2 = a + g * (b - a);
        rugo_vec2 q1 = rugo_contour_point(c, k, x1), q2 = rugo_contour_point(c, k, x2);
        double d1 = hypot(q1.x - p.x, q1.y - p.y), d2 = hypot(q2.x - p.x, q2.y - p.y);
        if (d1 < best) best = d1;
        if (d2 < best) best = d2;
        if (d1 < d2)
            b = x2;
        else
            a = x1;
    }
    return best;
}

static void rough_object(rugo_vec2* out) {
    static const double pattern[8] = {1.0, 0.3, 1.5, 0.6, 0.2, 1.2, 0.5, 1.8};
    rugo_vec2 cur[N], d[N / 2];
    sample_object(N0, rugo_v2(300.0, 300.0), 200.0, cur);
    rugo_rng rng;
    rugo_rng_seed(&rng, 4242);
    int n = N0;
    double sigma0 = 4.0;
    for (int l = 0; l < ADDED; ++l, n *= 2, sigma0 *= 0.6) {
        rugo_contour c = {cur, n};
        for (int s = 0; s < n; ++s) {
            int seg = (s - 1 + n) % n;
            double sigma = sigma0 * pattern[(seg * 8) / n];
            d[s] = rugo_v2_scale(sigma * rugo_rng_gaussian(&rng), rugo_contour_normal(c, seg, 0.5));
        }
        rugo_wavelet_synthesize(RUGO_FILTER_DEFAULT, cur, d, n, out);
        for (int i = 0; i < 2 * n; ++i)
            cur[i] = out[i];
    }
}

typedef struct beta_result {
    long outside;
    double worst_excess;          /* max of (measured - β), negative when never exceeded */
    double tight_mean, tight_min; /* β / measured max per coarse segment */
} beta_result;

/* Fraction of dense finest samples (plus their band) beyond β of their coarse segment, level j. */
static beta_result check_beta(const rugo_pyramid* p, const rugo_tolerances* t, const double* lam, int j) {
    rugo_contour fin, c;
    rugo_pyramid_level(p, J, &fin);
    rugo_pyramid_level(p, j, &c);
    rugo_tolerance_level l;
    rugo_tolerances_level(t, j, &l);
    beta_result r = {0, -INFINITY, 0.0, INFINITY};
    const int per = 1 << (J - j);
    for (int k = 0; k < l.count; ++k) {
        double worst = 0.0;
        for (int i = k * per; i < (k + 1) * per; ++i)
            for (int s = 0; s < S; ++s) {
                double tt = (double)s / S;
                double d = dist_to_segment(c, k, rugo_contour_point(fin, i, tt)) +
                           rugo_tolerance_at(lam, N, i, tt, 0.0);
                if (d > l.bound[k]) ++r.outside;
                worst = fmax(worst, d);
                r.worst_excess = fmax(r.worst_excess, d - l.bound[k]);
            }
        double tight = l.bound[k] / worst;
        r.tight_mean += tight / l.count;
        r.tight_min = fmin(r.tight_min, tight);
    }
    return r;
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/band_coverage";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    rugo_vec2 pts[N];
    rough_object(pts);
    rugo_pyramid_def pdef = rugo_default_pyramid_def();
    pdef.points = pts;
    pdef.count = N;
    pdef.coarsest_level = JMIN;
    rugo_pyramid* p = NULL;
    rugo_status st = rugo_pyramid_create(&pdef, &p, NULL);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_pyramid_create: %s\n", rugo_status_string(st));
        return 1;
    }
    static double zero[N], rough[N];
    for (int i = 0; i < N; ++i) {
        zero[i] = 0.0;
        rough[i] = 0.5 + (double)((i * 7) % 11) / 10.0; /* 0.5 .. 1.5, irregular */
    }
    const double q = RUGO_DEFAULT_Q;
    const double predicted = erfc(q / sqrt(2.0));
    rugo_tolerances* tol[2] = {NULL, NULL};
    rugo_tolerances* banded = NULL;
    for (int e = 0; e < 3; ++e) {
        rugo_tolerance_def d = rugo_default_tolerance_def();
        d.pyramid = p;
        d.finest = e < 2 ? zero : rough;
        d.count = N;
        d.q = q;
        d.estimator = e == 0 ? RUGO_ESTIMATOR_COEFFICIENTS : RUGO_ESTIMATOR_DETAIL;
        st = rugo_tolerances_create(&d, e < 2 ? &tol[e] : &banded);
        if (st != RUGO_OK) {
            fprintf(stderr, "rugo_tolerances_create: %s\n", rugo_status_string(st));
            return 1;
        }
    }

    rugo_contour fin;
    rugo_pyramid_level(p, J, &fin);
    char path[1100];
    snprintf(path, sizeof path, "%s/band_coverage.json", dir);
    FILE* js = fopen(path, "w");
    if (js == NULL) return 1;
    fprintf(js,
            "{\"shape\": \"sample_object(32) + 3 synthesised levels of outward roughness, %d segments\",\n"
            " \"q\": %.3g, \"predicted_fraction_outside\": %.6g,\n"
            " \"prediction_note\": \"P(|Z| > q) for a normal perturbation and a band q sigma\",\n"
            " \"samples\": %d,\n \"levels\": [",
            N, q, predicted, N * S);
    printf("q = %.2f: a normal perturbation lies outside q sigma with probability %.3f\n", q, predicted);
    printf("level segs | outside total band: coef  detail | outside own band: coef  detail | outside beta "
           "(lambda=0, lambda>0) | beta/measured mean (min)\n");
    int all_in_range = 1;
    long beta_outside_total = 0;
    double worst_excess = -INFINITY;
    for (int j = J - 1; j >= JMIN; --j) {
        rugo_contour c;
        rugo_pyramid_level(p, j, &c);
        double frac_total[2], frac_own[2];
        for (int e = 0; e < 2; ++e) {
            rugo_tolerance_level l;
            rugo_tolerances_level(tol[e], j, &l);
            long out_total = 0, out_own = 0;
            for (int i = 0; i < N; ++i)
                for (int s = 0; s < S; ++s) {
                    rugo_curve_point cp =
                        rugo_contour_closest_point(c, rugo_contour_point(fin, i, (double)s / S));
                    if (cp.distance > rugo_tolerance_at(l.total, l.count, cp.segment, cp.t, 0.0)) ++out_total;
                    if (cp.distance > rugo_tolerance_at(l.own, l.count, cp.segment, cp.t, 0.0)) ++out_own;
                }
            frac_total[e] = (double)out_total / (N * S);
            frac_own[e] = (double)out_own / (N * S);
            all_in_range &=
                frac_total[e] >= 0.0 && frac_total[e] <= 1.0 && frac_own[e] >= 0.0 && frac_own[e] <= 1.0;
        }
        beta_result b0 = check_beta(p, tol[1], zero, j);
        beta_result b1 = check_beta(p, banded, rough, j);
        beta_outside_total += b0.outside + b1.outside;
        worst_excess = fmax(worst_excess, fmax(b0.worst_excess, b1.worst_excess));
        printf("%5d %4d |                     %.3f   %.3f |                   %.3f   %.3f |        %ld, %ld"
               "            | %.3f (%.3f), %.3f (%.3f)\n",
               j, 1 << j, frac_total[0], frac_total[1], frac_own[0], frac_own[1], b0.outside, b1.outside,
               b0.tight_mean, b0.tight_min, b1.tight_mean, b1.tight_min);
        fprintf(js,
                "%s\n  {\"level\": %d, \"segments\": %d,\n"
                "   \"outside_total_band\": {\"coefficients\": %.6g, \"detail\": %.6g},\n"
                "   \"outside_own_band\": {\"coefficients\": %.6g, \"detail\": %.6g},\n"
                "   \"outside_total_vs_predicted\": {\"coefficients\": %.4g, \"detail\": %.4g},\n"
                "   \"outside_beta\": {\"finest_lambda_zero\": %ld, \"finest_lambda_positive\": %ld},\n"
                "   \"beta_over_measured\": {\"finest_lambda_zero\": {\"mean\": %.4g, \"min\": %.4g}, "
                "\"finest_lambda_positive\": {\"mean\": %.4g, \"min\": %.4g}}}",
                j == J - 1 ? "" : ",", j, 1 << j, frac_total[0], frac_total[1], frac_own[0], frac_own[1],
                frac_total[0] / predicted, frac_total[1] / predicted, b0.outside, b1.outside, b0.tight_mean,
                b0.tight_min, b1.tight_mean, b1.tight_min);
    }
    fprintf(
        js,
        "\n ],\n \"beta_worst_excess\": %.6g,\n"
        " \"reading\": \"outside_total_vs_predicted is the measured fraction over P(|Z| > q); 1 would mean "
        "the band behaves like q sigma of a normal perturbation. Coarser totals add the finer bands (5.3), "
        "so they are expected to be wider.\"\n}\n",
        worst_excess);
    fclose(js);
    printf("worst (measured - beta) over every check: %.3g (negative: never exceeded)\n", worst_excess);
    sample_expect("no finest sample (plus its band) outside beta, any level, lambda = 0 and lambda > 0",
                  beta_outside_total == 0);
    sample_expect("statistical fractions are in [0, 1]", all_in_range);
    rugo_tolerances_destroy(tol[0]);
    rugo_tolerances_destroy(tol[1]);
    rugo_tolerances_destroy(banded);
    rugo_pyramid_destroy(p);
    return sample_finish();
}
