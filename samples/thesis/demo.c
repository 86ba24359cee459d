/* A tour of the core library in one program (the README's main demo is the Box2D one, b2_demo): take
 * an outline, decompose it into levels of detail, deform it in multiresolution, fit a contour to a
 * sprite-like outline, and find the contacts of two rough shapes. Writes pictures and numbers into
 * OUTDIR (default out/demo): object.json, levels.svg, deform.svg, fit.svg, contacts.svg, results.json. */
#include "rugo/rugo.h"
#ifdef RUGO_HAVE_FIT
#include "rugo/fit.h"
#endif
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { J = 6, N = 1 << J };

static int write_text(const char* dir, const char* name, const char* text) {
    char path[1100];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE* f = fopen(path, "w");
    if (f == NULL) return -1;
    fputs(text, f);
    return fclose(f);
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/demo";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "rugo_demo: cannot create %s\n", dir);
        return 1;
    }
    char path[1100];
    rugo_vec2 pts[N];
    sample_object(N, rugo_v2(0.0, 0.0), 1.0, pts);

    /* 1. The shape file a pipeline would store. */
    rugo_shape_desc desc;
    memset(&desc, 0, sizeof desc); /* no roughness, default allocator */
    desc.control_points = pts;
    desc.count = N;
    desc.filter = RUGO_FILTER_DEFAULT;
    rugo_text text;
    if (rugo_shape_desc_write(&desc, NULL, &text) != RUGO_OK) return 1;
    sample_expect("wrote object.json", write_text(dir, "object.json", text.data) == 0);
    rugo_text_free(&text);

    /* 2. Levels of detail. */
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = pts;
    def.count = N;
    def.coarsest_level = 3;
    rugo_pyramid* p = NULL;
    rugo_status st = rugo_pyramid_create(&def, &p, NULL);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_demo: %s\n", rugo_status_string(st));
        return 1;
    }
    rugo_contour fine;
    rugo_pyramid_level(p, J, &fine);
    rugo_mass_properties mp = rugo_contour_mass_properties(fine);
    double perimeter = rugo_contour_perimeter(fine);
    rugo_vec2 lo, hi;
    svg_contour_extent(fine, &lo, &hi);
    snprintf(path, sizeof path, "%s/levels.svg", dir);
    svg_canvas svg;
    if (svg_open(&svg, path, lo, hi, 600.0) != 0) return 1;
    static const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a"};
    double level_area[4];
    for (int j = J; j >= 3; --j) {
        rugo_contour c;
        rugo_pyramid_level(p, j, &c);
        level_area[J - j] = rugo_contour_mass_properties(c).area;
        svg_contour(&svg, c, 16, colours[J - j], j == J ? 2.0 : 1.2, j == J ? NULL : "6,4");
    }
    svg_text(&svg, rugo_v2(lo.x, hi.y), "levels 6 (64 points) to 3 (8 points)", 13.0);
    sample_expect("wrote levels.svg", svg_close(&svg) == 0);

    /* 3. Multiresolution deformation: pull the rightmost point outward, spread over 4 levels. */
    rugo_curve_point cp = rugo_contour_closest_point(fine, rugo_v2(2.0, 0.0));
    rugo_vec2 before = cp.point, delta = rugo_v2(0.35, 0.1);
    static rugo_vec2 original[N];
    for (int i = 0; i < N; ++i)
        original[i] = fine.points[i];
    st = rugo_pyramid_deform(p, cp.segment, cp.t, delta, 4, 1.0, RUGO_DETAILS_LOCAL, NULL);
    if (st != RUGO_OK) return 1;
    rugo_pyramid_level(p, J, &fine);
    rugo_vec2 after = rugo_contour_point(fine, cp.segment, cp.t);
    double deviation = hypot(after.x - before.x - delta.x, after.y - before.y - delta.y);
    rugo_contour orig = {original, N};
    svg_contour_extent(fine, &lo, &hi);
    snprintf(path, sizeof path, "%s/deform.svg", dir);
    if (svg_open(&svg, path, lo, hi, 600.0) != 0) return 1;
    svg_contour(&svg, orig, 16, "#999999", 1.2, "6,4");
    svg_contour(&svg, fine, 16, "#1b9e77", 2.0, NULL);
    svg_arrow(&svg, before, rugo_v2_add(before, delta), "#e7298a");
    svg_text(&svg, rugo_v2(lo.x, hi.y),
             "multiresolution deformation over levels 6..3 (details in local frames)", 13.0);
    sample_expect("wrote deform.svg", svg_close(&svg) == 0);
    sample_expect_le("deformed point lands near its target (local frames), |error| / delta",
                     deviation / hypot(delta.x, delta.y), 0.25);
    rugo_pyramid_destroy(p);

    /* 4. Fitting a sprite outline: a dense, slightly noisy polygon as an image tracer would give. */
    double fit_max = -1.0, fit_rms = -1.0;
#ifdef RUGO_HAVE_FIT
    enum { M = 400, K = 32 };
    static rugo_vec2 outline[M], ctrl[K];
    for (int i = 0; i < M; ++i) {
        double th = 6.283185307179586 * i / M;
        double r = 1.0 + 0.15 * cos(4.0 * th) + 0.004 * sin(97.0 * th);
        outline[i] = rugo_v2(r * cos(th), 0.7 * r * sin(th));
    }
    rugo_fit_def fd = rugo_default_fit_def();
    fd.samples = outline;
    fd.sample_count = M;
    fd.control_count = K;
    rugo_fit_result fr = {-1.0, -1.0};
    if (sample_expect("fit succeeded", rugo_fit_contour(&fd, ctrl, &fr) == RUGO_OK)) {
        fit_max = fr.max_error;
        fit_rms = fr.rms_error;
    }
    sample_expect_le("fit max error on a 400-point outline with 32 control points", fit_max, 0.02);
    rugo_contour fitted = {ctrl, K};
    svg_contour_extent(fitted, &lo, &hi);
    snprintf(path, sizeof path, "%s/fit.svg", dir);
    if (svg_open(&svg, path, lo, hi, 600.0) != 0) return 1;
    for (int i = 0; i < M; ++i)
        svg_point(&svg, outline[i], 1.0, "#999999");
    svg_contour(&svg, fitted, 16, "#1b9e77", 1.5, NULL);
    svg_control_polygon(&svg, fitted, "#d95f02");
    svg_text(&svg, rugo_v2(lo.x, hi.y), "32-point contour fitted to a 400-point outline", 13.0);
    sample_expect("wrote fit.svg", svg_close(&svg) == 0);
#endif

    /* 5. Rough contact: the object (tipo_3 roughness, scaled to its size) resting against a rough ball
     * (tipo_5), found at the finest level and one level coarser; contact points and normals drawn. */
    int contacts_fine = -1, contacts_coarse = -1;
    double min_sep = 0.0, max_mu = 0.0;
    {
        enum { NB = 64 };
        static rugo_vec2 ball[NB];
        double lam_a[N], lam_b[NB];
        for (int i = 0; i < NB; ++i) {
            double th = 6.283185307179586 * i / NB;
            ball[i] = rugo_v2(0.5 * cos(th), 0.5 * sin(th));
        }
        rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, N, lam_a);
        rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, NB, lam_b);
        for (int i = 0; i < N; ++i)
            lam_a[i] *= 0.05; /* the presets are sized for objects ~10 across */
        for (int i = 0; i < NB; ++i)
            lam_b[i] *= 0.05;
        rugo_shape_def sd = rugo_default_shape_def();
        sd.points = pts;
        sd.count = N;
        sd.tolerances = lam_a;
        sd.friction = rugo_thesis_friction_map();
        sd.friction.alpha = 1.0 / 0.05; /* μ = (λ - λ_min) / 0.05: the scaled library spans μ ~ 0..0.6 */
        sd.friction.lambda_min = 0.04 * 0.05;
        rugo_shape *sa = NULL, *sb = NULL;
        rugo_collide_context* ctx = NULL;
        int ok = rugo_shape_create(&sd, &sa, NULL) == RUGO_OK;
        sd.points = ball;
        sd.count = NB;
        sd.tolerances = lam_b;
        ok = ok && rugo_shape_create(&sd, &sb, NULL) == RUGO_OK &&
             rugo_collide_context_create(NULL, &ctx) == RUGO_OK;
        sample_expect("built two rough shapes", ok);
        /* The ball just above the object's top, within the summed bands of their roughness. */
        rugo_transform xa = rugo_identity_transform(), xb = rugo_make_transform(0.0, 0.0, 0.0);
        if (ok) {
            rugo_contour top;
            rugo_shape_level(sa, J, &top);
            rugo_curve_point hit;
            rugo_contour_ray_cast(top, rugo_v2(0.0, 5.0), rugo_v2(0.0, -1.0), 10.0, NULL, &hit, NULL);
            xb = rugo_make_transform(0.0, hit.point.y + 0.5 + 0.01, 0.0);
        }
        rugo_contact contacts[16];
        rugo_contact_state state = RUGO_STATE_APART;
        rugo_contact_query q = rugo_default_contact_query();
        if (ok) {
            rugo_contact_output out = rugo_contact_output_of(contacts, 16);
            ok = rugo_collide_shapes(sa, xa, sb, xb, &q, ctx, &out) == RUGO_OK;
            contacts_fine = out.count;
            state = out.state;
            sample_expect("the rough shapes touch within their bands",
                          ok && state == RUGO_STATE_CONTACT && contacts_fine > 0);
            for (int i = 0; i < contacts_fine; ++i) {
                if (i == 0 || contacts[i].separation < min_sep) min_sep = contacts[i].separation;
                if (contacts[i].friction > max_mu) max_mu = contacts[i].friction;
            }
            rugo_contact coarse[16];
            q.lod = -1;
            rugo_contact_output coarse_out = rugo_contact_output_of(coarse, 16);
            ok = rugo_collide_shapes(sa, xa, sb, xb, &q, ctx, &coarse_out) == RUGO_OK;
            contacts_coarse = coarse_out.count;
            sample_expect("level -1 query ran", ok);
            /* The picture: both curves with their bands, contact points and normals. */
            rugo_contour ca, cb;
            rugo_shape_level(sa, J, &ca);
            rugo_shape_level(sb, rugo_shape_finest_level(sb), &cb);
            static rugo_vec2 moved[NB];
            for (int i = 0; i < NB; ++i)
                moved[i] = rugo_transform_point(xb, cb.points[i]);
            rugo_contour cbw = {moved, NB};
            rugo_vec2 lo2 = rugo_v2(-0.8, xb.p.y - 1.0), hi2 = rugo_v2(0.8, xb.p.y + 0.6);
            snprintf(path, sizeof path, "%s/contacts.svg", dir);
            if (svg_open(&svg, path, lo2, hi2, 600.0) != 0) return 1;
            svg_contour(&svg, ca, 24, "#1b9e77", 1.5, NULL);
            svg_contour(&svg, cbw, 24, "#7570b3", 1.5, NULL);
            for (int i = 0; i < contacts_fine; ++i) {
                svg_point(&svg, contacts[i].point_a, 3.0, "#d95f02");
                svg_point(&svg, contacts[i].point_b, 3.0, "#d95f02");
                svg_arrow(&svg, contacts[i].point_a,
                          rugo_v2_add(contacts[i].point_a, rugo_v2_scale(0.2, contacts[i].normal)),
                          "#e7298a");
            }
            svg_text(&svg, rugo_v2(lo2.x, hi2.y),
                     "rough object (tipo_3) and rough ball (tipo_5): contact within their summed bands, "
                     "normal A to B",
                     12.0);
            sample_expect("wrote contacts.svg", svg_close(&svg) == 0);
        }
        rugo_collide_context_destroy(ctx);
        rugo_shape_destroy(sa);
        rugo_shape_destroy(sb);
    }

    snprintf(path, sizeof path, "%s/results.json", dir);
    FILE* f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(f,
            "{\"control_points\": %d, \"area\": %.15g, \"centroid\": [%.15g, %.15g], \"inertia\": %.15g, "
            "\"perimeter\": %.15g,\n \"level_areas\": [%.10g, %.10g, %.10g, %.10g],\n"
            " \"deformation\": {\"delta\": [%.6g, %.6g], \"deviation_local_frames\": %.6g},\n"
            " \"fit\": {\"max_error\": %.6g, \"rms_error\": %.6g},\n"
            " \"rough_contact\": {\"contacts_finest\": %d, \"contacts_level_minus_1\": %d, "
            "\"min_separation\": %.6g, "
            "\"max_friction\": %.6g}}\n",
            N, mp.area, mp.centroid.x, mp.centroid.y, mp.inertia, perimeter, level_area[0], level_area[1],
            level_area[2], level_area[3], delta.x, delta.y, deviation, fit_max, fit_rms, contacts_fine,
            contacts_coarse, min_sep, max_mu);
    fclose(f);
    printf("rugo_demo: wrote %s/{object.json, levels.svg, deform.svg, fit.svg, contacts.svg, results.json}\n",
           dir);
    printf(
        "rough contact: %d contacts at the finest level (%d at level -1), closest %.4g, max friction %.3g\n",
        contacts_fine, contacts_coarse, min_sep, max_mu);
    printf("area %.6f, perimeter %.6f, inertia %.6f; fit max error %.4g, rms %.4g\n", mp.area, perimeter,
           mp.inertia, fit_max, fit_rms);
    return sample_finish();
}
