/* Thesis Fig. 2.8: a 32-point object refined to 64 points (synthesis with zero details). The shape
 * must not change: checks that every coarse segment equals its two fine halves, and that the refined
 * points are cubic B-spline subdivision. Writes fig2_8.svg and fig2_8.json. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>

enum { N = 32 };

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/fig2_8_refine";
    if (sample_mkdir(dir) != 0) return 1;
    rugo_vec2 coarse[N], fine[2 * N];
    sample_object(N, rugo_v2(300.0, 300.0), 200.0, coarse);
    if (rugo_wavelet_refine(coarse, N, fine) != RUGO_OK) return 1;
    rugo_contour c = {coarse, N}, f = {fine, 2 * N};

    /* Same curve: f^5_k(t) = f^6_{2k}(2t) on [0, 1/2] and f^6_{2k+1}(2t - 1) on [1/2, 1]. */
    double worst = 0.0;
    for (int k = 0; k < N; ++k)
        for (int i = 0; i <= 64; ++i) {
            double t = i / 64.0;
            rugo_vec2 a = rugo_contour_point(c, k, t);
            rugo_vec2 b = t <= 0.5 ? rugo_contour_point(f, 2 * k, 2.0 * t)
                                   : rugo_contour_point(f, 2 * k + 1, 2.0 * t - 1.0);
            worst = sample_max(worst, hypot(a.x - b.x, a.y - b.y));
        }
    double size = 400.0;
    sample_expect_le("refined curve equals the original, relative", worst / size, 1e-13);
    double sub = 0.0;
    for (int s = 0; s < N; ++s) {
        rugo_vec2 cm = coarse[(s + N - 1) % N], c0 = coarse[s], cp = coarse[(s + 1) % N];
        rugo_vec2 even = rugo_v2((cm.x + 6 * c0.x + cp.x) / 8, (cm.y + 6 * c0.y + cp.y) / 8);
        rugo_vec2 odd = rugo_v2((c0.x + cp.x) / 2, (c0.y + cp.y) / 2);
        sub = sample_max(sub, sample_max(hypot(fine[2 * s].x - even.x, fine[2 * s].y - even.y),
                                         hypot(fine[2 * s + 1].x - odd.x, fine[2 * s + 1].y - odd.y)));
    }
    sample_expect_le("refinement is cubic B-spline subdivision, relative", sub / size, 1e-13);
    rugo_mass_properties mc = rugo_contour_mass_properties(c), mf = rugo_contour_mass_properties(f);
    sample_expect_le("area unchanged, relative", fabs(mc.area - mf.area) / mc.area, 1e-12);

    char path[1100];
    snprintf(path, sizeof path, "%s/fig2_8.json", dir);
    FILE* out = fopen(path, "w");
    if (out == NULL) return 1;
    fprintf(out,
            "{\"control_points\": [%d, %d], \"max_curve_difference\": %.3g, \"subdivision_error\": %.3g, "
            "\"area\": [%.15g, %.15g]}\n",
            N, 2 * N, worst, sub, mc.area, mf.area);
    fclose(out);
    printf("refined %d -> %d points: curves differ by at most %.3g (shape size %.0f)\n", N, 2 * N, worst,
           size);

    rugo_vec2 lo, hi;
    svg_contour_extent(c, &lo, &hi);
    snprintf(path, sizeof path, "%s/fig2_8.svg", dir);
    svg_canvas svg;
    if (svg_open(&svg, path, lo, hi, 600.0) != 0) return 1;
    svg_control_polygon(&svg, c, "#d95f02");
    svg_control_polygon(&svg, f, "#7570b3");
    svg_contour(&svg, f, 16, "#1b9e77", 2.0, NULL);
    svg_text(&svg, rugo_v2(lo.x, hi.y),
             "Fig. 2.8: 32 control points (orange) refined to 64 (purple); one curve", 14.0);
    sample_expect("wrote fig2_8.svg", svg_close(&svg) == 0);
    return sample_finish();
}
