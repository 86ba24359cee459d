/* `rugo render`: an SVG picture of a shape, its coarser levels, its tolerance band and its stored
 * perturbation. */
#include "cli.h"
#include "svg.h"

#include <math.h>
#include <stdlib.h>

/* One side of the tolerance band: the curve offset by sign * λ(t) along its outward normal, as a thin
 * closed line (the contour is counter-clockwise, tol in its numbering). */
static void svg_band(svg_canvas* svg, rugo_contour c, const rugo_real* tol, int per_segment, double sign) {
    fprintf(svg->file,
            "<polygon class=\"band\" fill=\"none\" stroke=\"#1b9e77\" stroke-width=\"0.6\" points=\"");
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            rugo_real t = (rugo_real)i / per_segment;
            rugo_vec2 q = rugo_v2_add(rugo_contour_point(c, j, t),
                                      rugo_v2_scale(sign * rugo_tolerance_at(tol, c.count, j, t, 0.0),
                                                    rugo_contour_normal(c, j, t)));
            fprintf(svg->file, "%.2f,%.2f ", (q.x - svg->ox) * svg->scale,
                    svg->height - (q.y - svg->oy) * svg->scale);
        }
    fprintf(svg->file, "\"/>\n");
}

int cmd_render(int argc, char** argv) {
    static const char* const vals[] = {"-o", "--levels", "--samples", NULL};
    static const char* const flags[] = {"--no-control-polygon", "--band", "--perturbation", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, flags, &a);
    if (rc) return rc;
    const char* out = opt(&a, "-o", NULL);
    if (a.positional_count != 1 || out == NULL) return usage_error("expects SHAPE.json -o OUT.svg%s", "");
    int levels = 0, samples = 16, no_polygon = 0, band = 0, perturbation = 0;
    const char *lv = opt(&a, "--levels", NULL), *sv = opt(&a, "--samples", NULL);
    opt(&a, "--no-control-polygon", &no_polygon);
    opt(&a, "--band", &band);
    opt(&a, "--perturbation", &perturbation);
    if (lv && parse_int(lv, 0, 30, &levels) != 0) return usage_error("--levels must be >= 0, got '%s'", lv);
    if (sv && parse_int(sv, 1, 256, &samples) != 0) return usage_error("--samples must be 1..256, got '%s'", sv);
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    if ((rc = check_outline(a.positional[0], &desc, RUGO_CHECK_SELF_INTERSECTION))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    int reversed = rugo_contour_orient_ccw(desc.control_points, desc.count);
    rugo_real* tol = NULL;
    if (band && (rc = finest_tolerances(a.positional[0], desc.has_roughness ? &desc.roughness : NULL,
                                        desc.control_points, desc.count, reversed, &tol))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    rugo_pyramid* p = NULL;
    int J = log2_exact(desc.count);
    if (levels > 0) {
        if (J < 2 || levels > J - 2) {
            fprintf(stderr, "rugo render: --levels needs a power-of-two count with %d coarser levels of >= 4 points\n",
                    levels);
            free(tol);
            rugo_shape_desc_free(&desc);
            return EXIT_USAGE;
        }
        if ((rc = build_pyramid(a.positional[0], &desc, desc.filter, J - levels, &p))) {
            free(tol);
            rugo_shape_desc_free(&desc);
            return rc;
        }
    }
    rugo_contour c = {desc.control_points, desc.count};
    rugo_vec2 lo, hi;
    svg_contour_extent(c, &lo, &hi);
    if (band) { /* the band reaches at most the largest tolerance away from the curve */
        rugo_real widest = 0.0;
        for (int k = 0; k < desc.count; ++k)
            widest = fmax(widest, tol[k]);
        lo = rugo_v2(lo.x - widest, lo.y - widest);
        hi = rugo_v2(hi.x + widest, hi.y + widest);
    }
    const rugo_roughness_desc* rd = &desc.roughness;
    int draw_perturbation = perturbation && desc.has_roughness && rd->has_perturbation;
    rugo_contour pc = {rd->perturbation_points, rd->perturbation_count};
    if (draw_perturbation) {
        rugo_vec2 plo, phi;
        svg_contour_extent(pc, &plo, &phi);
        lo = rugo_v2(fmin(lo.x, plo.x), fmin(lo.y, plo.y));
        hi = rugo_v2(fmax(hi.x, phi.x), fmax(hi.y, phi.y));
    }
    svg_canvas svg;
    if (svg_open(&svg, out, lo, hi, 800.0) != 0) {
        fprintf(stderr, "rugo render: %s: cannot open for writing\n", out);
        rugo_pyramid_destroy(p);
        free(tol);
        rugo_shape_desc_free(&desc);
        return EXIT_INPUT;
    }
    static const char* const level_colours[] = {"#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"};
    for (int k = 1; k <= levels; ++k) {
        rugo_contour ck;
        rugo_pyramid_level(p, J - k, &ck);
        svg_contour(&svg, ck, samples, level_colours[(k - 1) % 5], 1.2, "6,4");
    }
    if (!no_polygon) svg_control_polygon(&svg, c, "#999999");
    if (band) {
        svg_band(&svg, c, tol, samples, 1.0);
        svg_band(&svg, c, tol, samples, -1.0);
    }
    if (draw_perturbation) {
        /* Each perturbation segment is 2^-levels of a shape segment: fewer samples keep the file small. */
        int per = samples >> rd->perturbation_levels;
        fprintf(svg.file, "<g class=\"perturbation\">\n");
        svg_contour(&svg, pc, per < 2 ? 2 : per, "#a6761d", 0.8, NULL);
        fprintf(svg.file, "</g>\n");
    } else if (perturbation) {
        fprintf(svg.file, "<!-- no perturbation stored in the shape -->\n");
    }
    svg_contour(&svg, c, samples, "#1b9e77", 2.0, NULL);
    rc = svg_close(&svg) == 0 ? 0 : EXIT_INPUT;
    if (rc) fprintf(stderr, "rugo render: %s: write failed\n", out);
    rugo_pyramid_destroy(p);
    free(tol);
    rugo_shape_desc_free(&desc);
    return rc;
}
