/* Thesis Fig. 2.12 and 2.13: roughness generated on a 32-point object
 *   Fig. 2.12 — by wavelet coefficients: two levels added above f^5 with N(0, σ²) details in the
 *               local frames (f^5 -> f^6 -> f^7, 128 control points);
 *   Fig. 2.13 — by local deformation: two rounds of "refine, then push each original segment's
 *               midpoint along its normal by N(0, σ²)" (also 128 control points).
 * A constant tolerance λ = 4 (σ = λ / q = 4.21, q = 0.95) on an object of radius ~200, so that the
 * asperities are visible. Writes fig2_12.svg, fig2_13.svg (original dashed, one level / round
 * thin, final rough curve solid) and fig2_12.json (RMS / max normal deviation of each method from the
 * unperturbed curve, in units and in σ). Checks: the run is deterministic (two runs, same bytes),
 * every point is finite, and the deviation is of the order of σ: RMS within a factor 2 of σ
 * (expected, over many seeds: 1.3 σ wavelet, 1.0 σ local, see tests/test_rough.c) and the
 * largest deviation below 6 σ. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { N = 32, LEVELS = 2, M = N << LEVELS, SAMPLES = 8 };
static const double LAMBDA = 4.0;
static const uint64_t SEED = 2012;

typedef struct stats {
    double rms, max;
} stats;

/* Parametric normal deviation of `rough` from `ref` (same count m): at SAMPLES parameters per
 * segment, (rough(u) - ref(u)) · n_ref(u). */
static stats deviation(const rugo_vec2* rough, const rugo_vec2* ref, int m) {
    rugo_contour cr = {rough, m}, cf = {ref, m};
    stats s = {0.0, 0.0};
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < SAMPLES; ++i) {
            double t = (double)i / SAMPLES;
            rugo_vec2 d = rugo_v2_sub(rugo_contour_point(cr, j, t), rugo_contour_point(cf, j, t));
            double dn = rugo_v2_dot(d, rugo_contour_normal(cf, j, t));
            s.rms += dn * dn;
            s.max = fmax(s.max, fabs(dn));
        }
    s.rms = sqrt(s.rms / (double)(m * SAMPLES));
    return s;
}

static rugo_status run(const rugo_vec2* pts, const double* lam, rugo_roughen_method method, int levels,
                       rugo_vec2* out) {
    rugo_roughen_def d = rugo_default_roughen_def();
    d.points = pts;
    d.count = N;
    d.tolerances = lam;
    d.method = method;
    d.levels = levels;
    d.seed = SEED;
    return rugo_roughen(&d, out);
}

static int all_finite(const rugo_vec2* v, int n) {
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i].x) || !isfinite(v[i].y)) return 0;
    return 1;
}

/* Original (dashed grey), first level / round (thin), final rough curve (solid). */
static int picture(const char* path, const char* title, rugo_contour orig, rugo_contour mid,
                   rugo_contour rough) {
    rugo_vec2 lo, hi, a, b;
    svg_contour_extent(orig, &lo, &hi);
    svg_contour_extent(rough, &a, &b);
    lo = rugo_v2(fmin(lo.x, a.x), fmin(lo.y, a.y));
    hi = rugo_v2(fmax(hi.x, b.x), fmax(hi.y, b.y));
    svg_canvas svg;
    if (svg_open(&svg, path, lo, hi, 700.0) != 0) return -1;
    svg_contour(&svg, orig, 16, "#888888", 1.2, "6,4");
    svg_contour(&svg, mid, 8, "#7570b3", 0.8, NULL);
    svg_contour(&svg, rough, 8, "#d95f02", 1.6, NULL);
    svg_text(&svg, rugo_v2(lo.x, hi.y), title, 14.0);
    return svg_close(&svg);
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/fig2_12_roughen";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    rugo_vec2 pts[N];
    sample_object(N, rugo_v2(300.0, 300.0), 200.0, pts);
    double lam[N];
    if (rugo_tolerances_constant(LAMBDA, N, lam) != RUGO_OK) return 1;
    const double sigma = LAMBDA / RUGO_DEFAULT_Q;

    /* The unperturbed curve at the output's resolution. */
    rugo_vec2 ref[M], tmp[M];
    memcpy(ref, pts, sizeof pts);
    for (int r = 0; r < LEVELS; ++r) {
        if (rugo_wavelet_refine(ref, N << r, tmp) != RUGO_OK) return 1;
        memcpy(ref, tmp, sizeof(rugo_vec2) * (size_t)(N << (r + 1)));
    }

    static const rugo_roughen_method methods[2] = {RUGO_ROUGHEN_WAVELET, RUGO_ROUGHEN_LOCAL};
    static const char* names[2] = {"wavelet", "local"};
    static const char* figures[2] = {"2.12", "2.13"};
    stats st[2];
    char path[1100], name[160];
    for (int k = 0; k < 2; ++k) {
        rugo_vec2 out[M], again[M], mid[2 * N];
        rugo_status s1 = run(pts, lam, methods[k], LEVELS, out);
        rugo_status s2 = run(pts, lam, methods[k], LEVELS, again);
        /* One level / round with the same seed draws the same first Gaussians: it is the first step
         * of the two-level run (shown thin). */
        rugo_status s3 = run(pts, lam, methods[k], 1, mid);
        if (s1 != RUGO_OK || s2 != RUGO_OK || s3 != RUGO_OK) {
            fprintf(stderr, "rugo_roughen (%s): %s\n", names[k],
                    rugo_status_string(s1 != RUGO_OK   ? s1
                                       : s2 != RUGO_OK ? s2
                                                       : s3));
            return 1;
        }
        snprintf(name, sizeof name, "%s: two runs with the same seed give the same bytes", names[k]);
        sample_expect(name, memcmp(out, again, sizeof out) == 0);
        snprintf(name, sizeof name, "%s: all %d output points finite", names[k], M);
        sample_expect(name, all_finite(out, M));
        st[k] = deviation(out, ref, M);
        printf("%s (Fig. %s): RMS normal deviation %.4f = %.3f sigma, max %.4f = %.3f sigma\n", names[k],
               figures[k], st[k].rms, st[k].rms / sigma, st[k].max, st[k].max / sigma);
        snprintf(name, sizeof name, "%s: RMS deviation / sigma >= 1/2", names[k]);
        sample_expect_le(name, 0.5, st[k].rms / sigma);
        snprintf(name, sizeof name, "%s: RMS deviation / sigma <= 2", names[k]);
        sample_expect_le(name, st[k].rms / sigma, 2.0);
        snprintf(name, sizeof name, "%s: max deviation / sigma <= 6", names[k]);
        sample_expect_le(name, st[k].max / sigma, 6.0);

        rugo_contour co = {pts, N}, cm = {mid, 2 * N}, cr = {out, M};
        char title[200];
        snprintf(title, sizeof title,
                 "Fig. %s (%s): 32 points (dashed), %s (thin), %s (solid); lambda = %.0f", figures[k],
                 names[k], k == 0 ? "+1 level" : "1 round", k == 0 ? "+2 levels" : "2 rounds", LAMBDA);
        snprintf(path, sizeof path, "%s/fig%s.svg", dir, k == 0 ? "2_12" : "2_13");
        sample_expect(k == 0 ? "wrote fig2_12.svg" : "wrote fig2_13.svg",
                      picture(path, title, co, cm, cr) == 0);
    }

    snprintf(path, sizeof path, "%s/fig2_12.json", dir);
    FILE* f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(
        f,
        "{\"control_points\": %d, \"profile\": \"constant\", \"lambda\": %.6g, \"q\": %.6g, \"sigma\": %.6g, "
        "\"seed\": %llu, \"filter\": \"%s\", \"methods\": [",
        N, LAMBDA, RUGO_DEFAULT_Q, sigma, (unsigned long long)SEED, rugo_filter_name(RUGO_FILTER_DEFAULT));
    for (int k = 0; k < 2; ++k)
        fprintf(f,
                "%s\n  {\"method\": \"%s\", \"figure\": \"%s\", \"levels\": %d, \"output_points\": %d, "
                "\"rms_normal_deviation\": %.6g, \"max_normal_deviation\": %.6g, \"rms_over_sigma\": %.6g, "
                "\"max_over_sigma\": %.6g}",
                k ? "," : "", names[k], figures[k], LEVELS, M, st[k].rms, st[k].max, st[k].rms / sigma,
                st[k].max / sigma);
    fprintf(f, "\n]}\n");
    sample_expect("wrote fig2_12.json", fclose(f) == 0);
    return sample_finish();
}
