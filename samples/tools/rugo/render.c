/* `rugo render`: an SVG picture of a shape, its coarser levels, its tolerance band and its stored
 * perturbation. */
#include "cli.h"
#include "svg.h"

#include <math.h>
#include <stdlib.h>

/* One side of the tolerance band: the curve offset by sign * λ(t) along its outward normal, as a thin
 * closed line (the contour is counter-clockwise, tol in its numbering). */
static void svg_band(svg_canvas* svg, rugo_contour c, const rugo_real* tol, int per_segment, double sign,
                     double exaggerate) {
    fprintf(svg->file,
            "<polygon class=\"band\" fill=\"none\" stroke=\"#1b9e77\" stroke-width=\"0.6\" points=\"");
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            rugo_real t = (rugo_real)i / per_segment;
            rugo_vec2 q =
                rugo_v2_add(rugo_contour_point(c, j, t),
                            rugo_v2_scale(sign * exaggerate * rugo_tolerance_at(tol, c.count, j, t, 0.0),
                                          rugo_contour_normal(c, j, t)));
            fprintf(svg->file, "%.2f,%.2f ", (q.x - svg->ox) * svg->scale,
                    svg->height - (q.y - svg->oy) * svg->scale);
        }
    fprintf(svg->file, "\"/>\n");
}

/* The curve coloured by the friction μ(λ(t)) of its surface, from blue (the smallest μ drawn) to red
 * (the largest), as short lines each coloured by μ at its middle, with a legend giving both values. */
static void svg_friction(svg_canvas* svg, rugo_contour c, const rugo_real* tol, const rugo_friction_map* fm,
                         int per_segment) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            const double mu =
                rugo_friction(fm, rugo_tolerance_at(tol, c.count, j, (i + 0.5) / per_segment, 0.0));
            lo = fmin(lo, mu);
            hi = fmax(hi, mu);
        }
    fprintf(svg->file, "<g class=\"friction\" stroke-width=\"4\" stroke-linecap=\"round\">\n");
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            const double t0 = (double)i / per_segment, t1 = (double)(i + 1) / per_segment;
            const double mu = rugo_friction(fm, rugo_tolerance_at(tol, c.count, j, 0.5 * (t0 + t1), 0.0));
            const double x = hi > lo ? (mu - lo) / (hi - lo) : 0.0;
            const int r = (int)(44 + x * (215 - 44)), g = (int)(123 + x * (25 - 123)),
                      b = (int)(182 + x * (28 - 182));
            const rugo_vec2 p = rugo_contour_point(c, j, t0), q = rugo_contour_point(c, j, t1);
            fprintf(svg->file,
                    "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#%02x%02x%02x\"/>\n",
                    (p.x - svg->ox) * svg->scale, svg->height - (p.y - svg->oy) * svg->scale,
                    (q.x - svg->ox) * svg->scale, svg->height - (q.y - svg->oy) * svg->scale, r, g, b);
        }
    fprintf(svg->file,
            "</g>\n<text class=\"friction-legend\" x=\"8\" y=\"20\" font-size=\"14\">"
            "friction: %.3g (blue) to %.3g (red)</text>\n",
            lo, hi);
}

int cmd_render(int argc, char** argv) {
    static const char* const vals[] = {"-o", "--levels", "--samples", "--exaggerate", NULL};
    static const char* const flags[] = {"--no-control-polygon", "--band", "--perturbation", "--friction",
                                        NULL};
    args a;
    int rc = parse_args(argc, argv, vals, flags, &a);
    if (rc) return rc;
    const char* out = opt(&a, "-o", NULL);
    if (a.positional_count != 1 || out == NULL) return usage_error("expects SHAPE.json -o OUT.svg%s", "");
    int levels = 0, samples = 16, no_polygon = 0, band = 0, perturbation = 0, friction = 0;
    double exaggerate = 1.0;
    const char *lv = opt(&a, "--levels", NULL), *sv = opt(&a, "--samples", NULL),
               *xv = opt(&a, "--exaggerate", NULL);
    opt(&a, "--friction", &friction);
    if (xv && (parse_real(xv, &exaggerate) != 0 || !(exaggerate >= 1.0) || exaggerate > 1e6))
        return usage_error("--exaggerate must be a factor from 1 to 1e6 (e.g. 20 to see a 2 mm band on a 1 m "
                           "rock), got '%s'",
                           xv);
    opt(&a, "--no-control-polygon", &no_polygon);
    opt(&a, "--band", &band);
    opt(&a, "--perturbation", &perturbation);
    if (lv && parse_int(lv, 0, 30, &levels) != 0) return usage_error("--levels must be >= 0, got '%s'", lv);
    if (sv && parse_int(sv, 1, 256, &samples) != 0)
        return usage_error("--samples must be 1..256, got '%s'", sv);
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    if ((rc = check_outline(a.positional[0], &desc, RUGO_CHECK_SELF_INTERSECTION))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    int reversed = rugo_contour_orient_ccw(desc.control_points, desc.count);
    rugo_real* tol = NULL;
    if ((band || friction) &&
        (rc = finest_tolerances(a.positional[0], desc.has_roughness ? &desc.roughness : NULL,
                                desc.control_points, desc.count, reversed, &tol))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    rugo_pyramid* p = NULL;
    int J = log2_exact(desc.count);
    if (levels > 0) {
        if (J < 2 || levels > J - 2) {
            fprintf(
                stderr,
                "rugo render: --levels needs a power-of-two count with %d coarser levels of >= 4 points\n",
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
            widest = fmax(widest, exaggerate * tol[k]);
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
        svg_band(&svg, c, tol, samples, 1.0, exaggerate);
        svg_band(&svg, c, tol, samples, -1.0, exaggerate);
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
    if (friction) {
        const rugo_roughness_desc r = roughness_of(&desc);
        svg_friction(&svg, c, tol, &r.friction, samples);
    } else {
        svg_contour(&svg, c, samples, "#1b9e77", 2.0, NULL);
    }
    rc = svg_close(&svg) == 0 ? 0 : EXIT_INPUT;
    if (rc) fprintf(stderr, "rugo render: %s: write failed\n", out);
    rugo_pyramid_destroy(p);
    free(tol);
    rugo_shape_desc_free(&desc);
    return rc;
}
