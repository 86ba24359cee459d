/* Thesis Fig. 2.7: a 32-point object decomposed two levels down (32 -> 16 -> 8 control points) with
 * the default CDF(4,8) filter. Writes fig2_7.svg (the three curves) and fig2_7.json (per level: points,
 * area, distance to the original curve) and checks perfect reconstruction and the kept mean. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>

enum { N = 32, LEVELS = 2 };

/* Largest distance from the curve `from` (dense samples) to the curve `to`. */
static double curve_distance(rugo_contour from, rugo_contour to) {
    double worst = 0.0;
    for (int j = 0; j < from.count; ++j)
        for (int i = 0; i < 8; ++i) {
            rugo_curve_point cp = rugo_contour_closest_point(to, rugo_contour_point(from, j, i / 8.0));
            if (cp.distance > worst) worst = cp.distance;
        }
    return worst;
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/fig2_7_decompose";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    rugo_vec2 pts[N];
    sample_object(N, rugo_v2(300.0, 300.0), 200.0, pts);
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = pts;
    def.count = N;
    def.coarsest_level = 5 - LEVELS;
    rugo_pyramid* p = NULL;
    rugo_status st = rugo_pyramid_create(&def, &p, NULL);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_pyramid_create: %s\n", rugo_status_string(st));
        return 1;
    }

    /* Perfect reconstruction: synthesize the stored pyramid (coarsest points and the details of every
     * level) back up and compare with the input. */
    rugo_vec2 data[N], fine_buf[N];
    rugo_contour coarsest;
    rugo_pyramid_level(p, 5 - LEVELS, &coarsest);
    int m = coarsest.count;
    for (int i = 0; i < m; ++i)
        data[i] = coarsest.points[i];
    int synth_ok = 1;
    for (int j = 5 - LEVELS; j < 5; ++j, m *= 2) {
        const rugo_vec2 *dw = NULL, *dl = NULL;
        synth_ok &= rugo_pyramid_details(p, j, &dw, &dl) == RUGO_OK;
        synth_ok &= dw != NULL && rugo_wavelet_synthesize(def.filter, data, dw, m, fine_buf) == RUGO_OK;
        for (int i = 0; i < 2 * m; ++i)
            data[i] = fine_buf[i];
    }
    sample_expect("synthesis from the stored pyramid succeeded", synth_ok);
    double pr = 0.0, size = 0.0;
    for (int i = 0; i < N; ++i) {
        pr = sample_max(pr, sample_max(fabs(data[i].x - pts[i].x), fabs(data[i].y - pts[i].y)));
        size = sample_max(size, sample_max(fabs(pts[i].x), fabs(pts[i].y)));
    }
    sample_expect_le("perfect reconstruction, relative error", pr / size, 1e-12);

    char path[1100];
    snprintf(path, sizeof path, "%s/fig2_7.json", dir);
    FILE* f = fopen(path, "w");
    if (f == NULL) return 1;
    rugo_contour fine;
    rugo_pyramid_level(p, 5, &fine);
    rugo_vec2 mean_fine = rugo_v2(0, 0);
    for (int i = 0; i < N; ++i)
        mean_fine = rugo_v2_add(mean_fine, rugo_v2_scale(1.0 / N, fine.points[i]));
    fprintf(f, "{\"filter\": \"%s\", \"perfect_reconstruction_error\": %.3g, \"levels\": [",
            rugo_filter_name(def.filter), pr / size);
    for (int j = 5; j >= 5 - LEVELS; --j) {
        rugo_contour c;
        rugo_pyramid_level(p, j, &c);
        rugo_mass_properties mp = rugo_contour_mass_properties(c);
        rugo_vec2 mean = rugo_v2(0, 0);
        for (int i = 0; i < c.count; ++i)
            mean = rugo_v2_add(mean, rugo_v2_scale(1.0 / c.count, c.points[i]));
        double dist = curve_distance(fine, c);
        fprintf(f,
                "%s\n  {\"level\": %d, \"control_points\": %d, \"area\": %.10g, \"mean\": [%.12g, %.12g], "
                "\"max_distance_from_original\": %.6g}",
                j == 5 ? "" : ",", j, c.count, mp.area, mean.x, mean.y, dist);
        char name[96];
        snprintf(name, sizeof name, "level %d keeps the control points' mean (abs error)", j);
        sample_expect_le(name, sample_max(fabs(mean.x - mean_fine.x), fabs(mean.y - mean_fine.y)),
                         1e-12 * size);
        printf("level %d: %d points, area %.6g, max distance from the original curve %.4g\n", j, c.count,
               mp.area, dist);
    }
    fprintf(f, "\n]}\n");
    fclose(f);

    /* The picture: original (solid), first and second decomposition (dashed), as in Fig. 2.7. */
    rugo_vec2 lo, hi;
    svg_contour_extent(fine, &lo, &hi);
    for (int j = 5 - LEVELS; j < 5; ++j) { /* coarse control polygons reach further out */
        rugo_contour c;
        rugo_vec2 a, b;
        rugo_pyramid_level(p, j, &c);
        svg_contour_extent(c, &a, &b);
        lo = rugo_v2(fmin(lo.x, a.x), fmin(lo.y, a.y));
        hi = rugo_v2(fmax(hi.x, b.x), fmax(hi.y, b.y));
    }
    snprintf(path, sizeof path, "%s/fig2_7.svg", dir);
    svg_canvas svg;
    if (svg_open(&svg, path, lo, hi, 600.0) != 0) return 1;
    static const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3"};
    for (int j = 5; j >= 5 - LEVELS; --j) {
        rugo_contour c;
        rugo_pyramid_level(p, j, &c);
        svg_contour(&svg, c, 16, colours[5 - j], j == 5 ? 2.0 : 1.4, j == 5 ? NULL : "6,4");
        svg_control_polygon(&svg, c, colours[5 - j]);
    }
    svg_text(&svg, rugo_v2(lo.x, hi.y), "Fig. 2.7: 32 points (green), 16 (orange), 8 (purple)", 14.0);
    sample_expect("wrote fig2_7.svg", svg_close(&svg) == 0);
    rugo_pyramid_destroy(p);
    return sample_finish();
}
