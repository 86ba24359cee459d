/* The pictures of docs/guide.md, drawn from one rough "rock" (sample_object, 64 control points, mean
 * radius 1, the thesis' tipo_5 tolerances scaled by 0.1: blocks of 0.055, 0.004, 0.065, 0.004) and a
 * 32-point pebble (tipo_3 scaled by 0.1) resting on it.
 *
 * Writes, into the directory given as the last argument (docs/img for the checked-in copies:
 * ./build/samples/thesis/guide_figures docs/img):
 *   levels.svg    the wavelet pyramid: the curve of levels 6 (64 points) down to 2 (4 points);
 *   bands.svg     the tolerance band ±λ(t) at level 6 (with display asperities drawn by rugo_roughen)
 *                 and the accumulated band λ^4 at level 4;
 *   boxes.svg     the MOBBtree's boxes at levels 6, 5, 4 and 3;
 *   friction.svg  μ(λ(t)) along the contour, colour-coded, and as a graph over the segments;
 *   contacts.svg  the pebble on the rock: contacts at the finest level and two levels coarser.
 * Every element the checks count carries a class (level, band, box, mu, contact).
 * Checks (then re-reads every file and counts what it drew): 5 levels; the mean λ^j grows towards
 * coarse levels (5.3); 64 + 32 + 16 + 8 = 120 boxes, each containing its own segment's samples; μ runs
 * from the map's base 0.3 (smooth blocks) to exactly 0.9 at the middle of the 0.065 segments; the
 * pebble touches the rock at the finest level, every contact within the summed bands. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { N = 64, NB = 32, SAMPLES = 12, PERTURB_LEVELS = 2 };
static const double PANEL = 2.9; /* horizontal distance between panels, in shape units */

/* Pixel coordinates of a world point on the canvas (as svg.c maps them). */
static double pxx(const svg_canvas* c, double x) { return (x - c->ox) * c->scale; }
static double pxy(const svg_canvas* c, double y) { return c->height - (y - c->oy) * c->scale; }

/* A closed polyline through n points shifted by `off`, with an optional class and fill. */
static void polyline(svg_canvas* c, const rugo_vec2* p, int n, rugo_vec2 off, const char* cls,
                     const char* stroke, double width, const char* dash) {
    fprintf(c->file, "<polygon%s%s%s fill=\"none\" stroke=\"%s\" stroke-width=\"%.2f\"%s%s%s points=\"",
            cls ? " class=\"" : "", cls ? cls : "", cls ? "\"" : "", stroke, width,
            dash ? " stroke-dasharray=\"" : "", dash ? dash : "", dash ? "\"" : "");
    for (int i = 0; i < n; ++i)
        fprintf(c->file, "%.2f,%.2f ", pxx(c, p[i].x + off.x), pxy(c, p[i].y + off.y));
    fprintf(c->file, "\"/>\n");
}

/* Samples of a contour (SAMPLES per segment), transformed by x, into out (count * SAMPLES points). */
static void sample_curve(rugo_contour k, rugo_transform x, rugo_vec2* out) {
    for (int j = 0; j < k.count; ++j)
        for (int i = 0; i < SAMPLES; ++i)
            out[j * SAMPLES + i] = rugo_transform_point(x, rugo_contour_point(k, j, (double)i / SAMPLES));
}

/* The curve offset by sign * λ(t) along its outward normal (λ(t) from the level's accumulated λ). */
static void offset_curve(rugo_contour k, const rugo_tolerance_level* tl, rugo_transform x, double sign,
                         rugo_vec2* out) {
    for (int j = 0; j < k.count; ++j)
        for (int i = 0; i < SAMPLES; ++i) {
            const double t = (double)i / SAMPLES;
            const double lam = rugo_tolerance_at(tl->total, tl->count, j, t, 0.0);
            rugo_vec2 p = rugo_v2_add(rugo_contour_point(k, j, t),
                                      rugo_v2_scale(sign * lam, rugo_contour_normal(k, j, t)));
            out[j * SAMPLES + i] = rugo_transform_point(x, p);
        }
}

/* The band between the two offset curves, filled (even-odd between the outer and inner curve). */
static void band(svg_canvas* c, const rugo_shape* s, int level, rugo_transform x, rugo_vec2 off,
                 const char* fill) {
    rugo_contour k;
    rugo_tolerance_level tl;
    if (rugo_shape_level(s, level, &k) != RUGO_OK || rugo_shape_tolerance_level(s, level, &tl) != RUGO_OK)
        return;
    const int n = k.count * SAMPLES;
    rugo_vec2* p = malloc((size_t)n * sizeof *p);
    if (p == NULL) return;
    fprintf(
        c->file,
        "<path class=\"band\" fill=\"%s\" fill-opacity=\"0.35\" fill-rule=\"evenodd\" stroke=\"none\" d=\"",
        fill);
    for (int side = 0; side < 2; ++side) {
        offset_curve(k, &tl, x, side ? -1.0 : 1.0, p);
        for (int i = 0; i < n; ++i)
            fprintf(c->file, "%s%.2f,%.2f ", i ? "L" : "M", pxx(c, p[i].x + off.x), pxy(c, p[i].y + off.y));
        fprintf(c->file, "Z ");
    }
    fprintf(c->file, "\"/>\n");
    free(p);
}

static void curve(svg_canvas* c, rugo_contour k, rugo_transform x, rugo_vec2 off, const char* stroke,
                  double width, const char* dash) {
    rugo_vec2* p = malloc((size_t)k.count * SAMPLES * sizeof *p);
    if (p == NULL) return;
    sample_curve(k, x, p);
    polyline(c, p, k.count * SAMPLES, off, NULL, stroke, width, dash);
    free(p);
}

static void box(svg_canvas* c, const rugo_obb* b, rugo_vec2 off, const char* stroke) {
    rugo_vec2 q[4];
    rugo_obb_corners(b, q);
    polyline(c, q, 4, off, "box", stroke, 0.8, NULL);
}

static void label(svg_canvas* c, rugo_vec2 at, const char* text) { svg_text(c, at, text, 13.0); }

/* Occurrences of needle in the file (0 if it cannot be read). */
static int count_in_file(const char* path, const char* needle) {
    FILE* f = fopen(path, "rb");
    if (f == NULL) return 0;
    static char buf[1 << 22];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    int count = 0;
    for (const char* p = strstr(buf, needle); p != NULL; p = strstr(p + 1, needle))
        ++count;
    return count;
}

/* Blue (μ = lo) to red (μ = hi). */
static void ramp(double mu, double lo, double hi, char out[8]) {
    double u = (mu - lo) / (hi - lo);
    u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
    const int r = (int)lround(44.0 + u * (215.0 - 44.0)), g = (int)lround(123.0 + u * (25.0 - 123.0)),
              b = (int)lround(182.0 + u * (28.0 - 182.0));
    snprintf(out, 8, "#%02x%02x%02x", r, g, b);
}

static rugo_shape* build(const rugo_vec2* pts, int n, rugo_tolerance_preset preset, rugo_friction_map map) {
    double lam[N];
    if (rugo_tolerances_preset(preset, 0, n, lam) != RUGO_OK) return NULL;
    for (int i = 0; i < n; ++i)
        lam[i] *= 0.1;
    rugo_shape_def def = rugo_default_shape_def();
    def.points = pts;
    def.count = n;
    def.tolerances = lam;
    def.friction = map;
    rugo_shape* s = NULL;
    rugo_status st = rugo_shape_create(&def, &s, NULL);
    if (st != RUGO_OK) fprintf(stderr, "rugo_shape_create: %s\n", rugo_status_string(st));
    return s;
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[argc - 1] : "out/guide_figures";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    char path[1200], text[200];

    /* The rock and its surface: μ = 0.3 on smooth parts, 0.9 where λ = 0.065. */
    rugo_friction_map map;
    if (rugo_friction_calibrate(0.004, 0.065, 0.3, 0.9, &map) != RUGO_OK) return 1;
    rugo_vec2 rock_pts[N], pebble_pts[NB];
    sample_object(N, rugo_v2(0.0, 0.0), 1.0, rock_pts);
    for (int k = 0; k < NB; ++k) {
        const double th = 6.283185307179586 * k / NB;
        pebble_pts[k] = rugo_v2(0.45 * cos(th) * (1.0 + 0.12 * cos(2.0 * th)), 0.3 * sin(th));
    }
    rugo_shape* rock = build(rock_pts, N, RUGO_PRESET_TIPO_5, map);
    rugo_shape* pebble = build(pebble_pts, NB, RUGO_PRESET_TIPO_3, rugo_thesis_friction_map());
    if (rock == NULL || pebble == NULL) return 1;
    const int J = rugo_shape_finest_level(rock), J0 = rugo_shape_coarsest_level(rock);
    const rugo_transform id = rugo_identity_transform();
    rugo_contour fine;
    rugo_shape_level(rock, J, &fine);
    const rugo_vec2 lo = rugo_v2(-1.35, -1.1), hi = rugo_v2(1.35, 1.05);

    /* ---- levels.svg: the pyramid, finest to coarsest -------------------------------------------- */
    {
        const int panels = J - J0 + 1;
        snprintf(path, sizeof path, "%s/levels.svg", dir);
        svg_canvas svg;
        if (svg_open(&svg, path, lo, rugo_v2(hi.x + PANEL * (panels - 1), hi.y + 0.25), 1100.0) != 0)
            return 1;
        for (int j = J; j >= J0; --j) {
            const rugo_vec2 off = rugo_v2(PANEL * (J - j), 0.0);
            rugo_contour cj;
            rugo_shape_level(rock, j, &cj);
            fprintf(svg.file, "<g class=\"level\" data-level=\"%d\">\n", j);
            if (j < J) curve(&svg, fine, id, off, "#bbbbbb", 1.0, NULL);
            curve(&svg, cj, id, off, "#1b9e77", 1.8, NULL);
            for (int k = 0; k < cj.count; ++k)
                svg_point(&svg, rugo_v2_add(cj.points[k], off), 2.0, "#d95f02");
            fprintf(svg.file, "</g>\n");
            snprintf(text, sizeof text, "level %d: %d points", j, cj.count);
            label(&svg, rugo_v2(lo.x + off.x + 0.1, hi.y + 0.15), text);
        }
        sample_expect("wrote levels.svg", svg_close(&svg) == 0);
        snprintf(text, sizeof text, "levels.svg shows the %d levels %d..%d", panels, J, J0);
        sample_expect(text, count_in_file(path, "class=\"level\"") == panels && panels == 5);
    }

    /* ---- bands.svg: λ at the finest level (with display asperities) and accumulated at level J-2 ---- */
    {
        double mean[8] = {0};
        for (int j = J0; j <= J; ++j) {
            rugo_tolerance_level tl;
            rugo_shape_tolerance_level(rock, j, &tl);
            for (int k = 0; k < tl.count; ++k)
                mean[j] += tl.total[k] / tl.count;
        }
        int grows = 1;
        for (int j = J0; j < J; ++j)
            grows &= mean[j] >= mean[j + 1];
        printf("mean accumulated tolerance per level:");
        for (int j = J; j >= J0; --j)
            printf(" λ^%d %.4f", j, mean[j]);
        printf("\n");
        sample_expect("the mean accumulated tolerance grows towards coarse levels (5.3)", grows);

        /* Display asperities: rugo_roughen's wavelet method, two levels above the finest. */
        static rugo_vec2 rough[N << PERTURB_LEVELS];
        double lam[N];
        rugo_tolerance_level tl;
        rugo_shape_tolerance_level(rock, J, &tl);
        memcpy(lam, tl.total, sizeof lam);
        rugo_roughen_def rd = rugo_default_roughen_def();
        rd.points = fine.points;
        rd.count = N;
        rd.tolerances = lam;
        rd.levels = PERTURB_LEVELS;
        rd.method = RUGO_ROUGHEN_LOCAL;
        rd.seed = 7;
        if (rugo_roughen(&rd, rough) != RUGO_OK) return 1;

        snprintf(path, sizeof path, "%s/bands.svg", dir);
        svg_canvas svg;
        if (svg_open(&svg, path, lo, rugo_v2(hi.x + PANEL, hi.y + 0.25), 900.0) != 0) return 1;
        const int levels[2] = {J, J - 2};
        for (int p = 0; p < 2; ++p) {
            const rugo_vec2 off = rugo_v2(PANEL * p, 0.0);
            rugo_contour cj;
            rugo_shape_level(rock, levels[p], &cj);
            band(&svg, rock, levels[p], id, off, "#1b9e77");
            if (p == 0) {
                rugo_contour rc = {rough, N << PERTURB_LEVELS};
                curve(&svg, rc, id, off, "#444444", 0.6, NULL);
            } else {
                curve(&svg, fine, id, off, "#999999", 0.8, "4,3");
            }
            curve(&svg, cj, id, off, "#1b5e20", 1.2, NULL);
            snprintf(text, sizeof text,
                     p == 0 ? "level %d: band ±λ(t), asperities for display"
                            : "level %d: accumulated band ±λ^%d(t)",
                     levels[p], levels[p]);
            label(&svg, rugo_v2(lo.x + off.x + 0.1, hi.y + 0.15), text);
        }
        sample_expect("wrote bands.svg", svg_close(&svg) == 0);
        sample_expect("bands.svg shows 2 bands", count_in_file(path, "class=\"band\"") == 2);
    }

    /* ---- boxes.svg: the MOBBtree, one box per segment of each level ------------------------------ */
    {
        const rugo_mobb_tree* tree = rugo_shape_tree(rock);
        snprintf(path, sizeof path, "%s/boxes.svg", dir);
        svg_canvas svg;
        if (svg_open(&svg, path, rugo_v2(lo.x - 0.1, lo.y - 0.1), rugo_v2(hi.x + 0.1 + 3 * PANEL, hi.y + 0.3),
                     1100.0) != 0)
            return 1;
        int drawn = 0, inside = 1;
        for (int j = J; j >= J - 3; --j) {
            const rugo_vec2 off = rugo_v2(PANEL * (J - j), 0.0);
            rugo_contour cj;
            rugo_shape_level(rock, j, &cj);
            curve(&svg, fine, id, off, "#888888", 1.0, NULL);
            if (j < J) curve(&svg, cj, id, off, "#1b9e77", 1.0, "5,3");
            for (int k = 0; k < (1 << j); ++k) {
                const rugo_obb* b = rugo_mobb_tree_node(tree, j, k);
                box(&svg, b, off, "#7570b3");
                ++drawn;
                for (int s = 0; s <= SAMPLES; ++s)
                    inside &= rugo_obb_contains(b, rugo_contour_point(cj, k, (double)s / SAMPLES), 1e-9);
            }
            snprintf(text, sizeof text, "level %d: %d boxes", j, 1 << j);
            label(&svg, rugo_v2(lo.x + off.x, hi.y + 0.2), text);
        }
        sample_expect("every box contains its own segment (samples)", inside);
        sample_expect("wrote boxes.svg", svg_close(&svg) == 0);
        snprintf(text, sizeof text, "boxes.svg shows %d boxes (64 + 32 + 16 + 8)", drawn);
        sample_expect(text, drawn == 120 && count_in_file(path, "class=\"box\"") == drawn);
    }

    /* ---- friction.svg: μ(λ(t)) along the contour ------------------------------------------------- */
    {
        rugo_tolerance_level tl;
        rugo_shape_tolerance_level(rock, J, &tl);
        const rugo_friction_map m = rugo_shape_friction_map(rock);
        snprintf(path, sizeof path, "%s/friction.svg", dir);
        svg_canvas svg;
        if (svg_open(&svg, path, rugo_v2(lo.x, -2.75), rugo_v2(hi.x, hi.y + 0.2), 560.0) != 0) return 1;
        double mu_min = INFINITY, mu_max = -INFINITY, mu_mid_max = -INFINITY;
        rugo_vec2 graph[N * SAMPLES];
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < SAMPLES; ++i) {
                const double t0 = (double)i / SAMPLES, t1 = (double)(i + 1) / SAMPLES;
                const double mu = rugo_friction(&m, rugo_tolerance_at(tl.total, tl.count, j, t0, 0.0));
                const double mu_mid = rugo_friction(&m, rugo_tolerance_at(tl.total, tl.count, j, 0.5, 0.0));
                mu_min = fmin(mu_min, mu);
                mu_max = fmax(mu_max, mu);
                mu_mid_max = fmax(mu_mid_max, mu_mid);
                char colour[8];
                ramp(mu, 0.3, 0.9, colour);
                const rugo_vec2 a = rugo_contour_point(fine, j, t0), b = rugo_contour_point(fine, j, t1);
                fprintf(svg.file,
                        "<line class=\"mu\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" "
                        "stroke-width=\"5\" stroke-linecap=\"round\"/>\n",
                        pxx(&svg, a.x), pxy(&svg, a.y), pxx(&svg, b.x), pxy(&svg, b.y), colour);
                graph[j * SAMPLES + i] = rugo_v2(-1.25 + 2.5 * (j + t0) / N, -2.6 + 1.0 * mu);
            }
        /* The graph: μ over the contour parameter (segments 0..63), axes at μ = 0 and guides at 0.3, 0.9. */
        for (int g = 0; g < 3; ++g) {
            static const double level_mu[3] = {0.0, 0.3, 0.9};
            const double y = -2.6 + level_mu[g];
            fprintf(svg.file,
                    "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#999999\"%s/>\n",
                    pxx(&svg, -1.25), pxy(&svg, y), pxx(&svg, 1.25), pxy(&svg, y),
                    g ? " stroke-dasharray=\"3,3\"" : "");
            snprintf(text, sizeof text, "%.1f", level_mu[g]);
            svg_text(&svg, rugo_v2(-1.36, y - 0.02), text, 10.0);
        }
        fprintf(svg.file, "<polyline fill=\"none\" stroke=\"#d7191c\" stroke-width=\"1.2\" points=\"");
        for (int i = 0; i < N * SAMPLES; ++i)
            fprintf(svg.file, "%.2f,%.2f ", pxx(&svg, graph[i].x), pxy(&svg, graph[i].y));
        fprintf(svg.file, "\"/>\n");
        label(&svg, rugo_v2(-1.25, -1.3), "μ along the contour, segment 0 to 63");
        label(&svg, rugo_v2(lo.x, hi.y + 0.1), "friction μ(λ(t)): 0.3 (blue) to 0.9 (red)");
        sample_expect("wrote friction.svg", svg_close(&svg) == 0);
        printf("friction along the contour: %.4f .. %.4f (at segment middles up to %.12f)\n", mu_min, mu_max,
               mu_mid_max);
        sample_expect("μ never below the smooth surface's base 0.3", mu_min == 0.3);
        sample_expect_le("|μ at the middle of a 0.065 segment - 0.9|", fabs(mu_mid_max - 0.9), 1e-9);
        sample_expect_le("μ anywhere (the cubic λ(t) may overshoot a little)", mu_max, 0.95);
        sample_expect("friction.svg shows 768 coloured pieces",
                      count_in_file(path, "class=\"mu\"") == N * SAMPLES);
    }

    /* ---- contacts.svg: the pebble lowered onto the rock until it touches at the finest level ------- */
    {
        rugo_collide_context* ctx = NULL;
        if (rugo_collide_context_create(NULL, &ctx) != RUGO_OK) return 1;
        enum { CAP = 16 };
        rugo_contact contacts[2][CAP];
        int count[2] = {0, 0};
        rugo_contact_state state[2] = {RUGO_STATE_APART, RUGO_STATE_APART};
        /* Lower the pebble at x = -0.6, -0.55, ..., 0.4 until it touches; keep the place where it also
         * touches at level -2 and the contact's friction is highest (a rough part of the rock). */
        rugo_transform xb = rugo_make_transform(0.0, 0.0, 0.35);
        rugo_contact_query q = rugo_default_contact_query();
        double best_mu = -1.0;
        for (int cx = 0; cx <= 20; ++cx) {
            rugo_transform x = rugo_make_transform(-0.6 + 0.05 * cx, 1.6, 0.35);
            rugo_contact c[CAP];
            rugo_contact_output out = rugo_contact_output_of(c, CAP);
            for (int step = 0; step < 2000 && out.state == RUGO_STATE_APART; ++step) {
                x.p.y -= 0.0005;
                if (rugo_collide_shapes(rock, id, pebble, x, &q, ctx, &out) != RUGO_OK) return 1;
            }
            rugo_contact_query coarse = q;
            coarse.lod = -2;
            rugo_contact cc[CAP];
            rugo_contact_output coarse_out = rugo_contact_output_of(cc, CAP);
            if (rugo_collide_shapes(rock, id, pebble, x, &coarse, ctx, &coarse_out) != RUGO_OK) return 1;
            if (out.state == RUGO_STATE_CONTACT && coarse_out.state == RUGO_STATE_CONTACT && out.count > 0 &&
                c[0].friction > best_mu) {
                best_mu = c[0].friction;
                xb = x;
            }
        }
        for (int k = 0; k < 2; ++k) {
            q.lod = k == 0 ? 0 : -2;
            rugo_contact_output out = rugo_contact_output_of(contacts[k], CAP);
            if (rugo_collide_shapes(rock, id, pebble, xb, &q, ctx, &out) != RUGO_OK) return 1;
            count[k] = out.count;
            state[k] = out.state;
        }
        rugo_collide_context_destroy(ctx);
        printf("pebble at (%.4f, %.4f): level 0 %s with %d contacts, level -2 %s with %d contacts\n", xb.p.x,
               xb.p.y, rugo_contact_state_name(state[0]), count[0], rugo_contact_state_name(state[1]),
               count[1]);
        int within = count[0] > 0;
        for (int i = 0; i < count[0]; ++i) {
            const rugo_contact* c = &contacts[0][i];
            printf("  finest: separation %.5f, bands %.5f + %.5f, μ %.3f, ε %.2f\n", c->separation,
                   c->tolerance_a, c->tolerance_b, c->friction, c->restitution);
            within &= c->separation <= c->tolerance_a + c->tolerance_b + 1e-12;
        }
        sample_expect("the pebble touches the rock at the finest level and at level -2 (state contact)",
                      state[0] == RUGO_STATE_CONTACT && state[1] == RUGO_STATE_CONTACT);
        sample_expect("every finest contact lies within the summed bands", within);

        snprintf(path, sizeof path, "%s/contacts.svg", dir);
        svg_canvas svg;
        /* Two panels around the pebble, each clipped to its own rectangle. */
        const double w = 1.6;
        const rugo_vec2 clo = rugo_v2(xb.p.x - 0.8, xb.p.y - 0.75),
                        chi = rugo_v2(xb.p.x + 0.8, xb.p.y + 0.55);
        if (svg_open(&svg, path, clo, rugo_v2(chi.x + w + 0.1, chi.y + 0.15), 900.0) != 0) return 1;
        int drawn = 0;
        for (int p = 0; p < 2; ++p) {
            const rugo_vec2 off = rugo_v2((w + 0.1) * p, 0.0);
            fprintf(svg.file,
                    "<clipPath id=\"panel%d\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" "
                    "height=\"%.2f\"/></clipPath>\n",
                    p, pxx(&svg, clo.x + off.x), pxy(&svg, chi.y), w * svg.scale,
                    (chi.y - clo.y) * svg.scale);
            fprintf(svg.file, "<g clip-path=\"url(#panel%d)\">\n", p);
            const int la = p ? J - 2 : J, lb = rugo_shape_finest_level(pebble) - (p ? 2 : 0);
            rugo_contour ca, cb;
            rugo_shape_level(rock, la, &ca);
            rugo_shape_level(pebble, lb, &cb);
            band(&svg, rock, la, id, off, "#1b9e77");
            band(&svg, pebble, lb, xb, off, "#7570b3");
            curve(&svg, ca, id, off, "#1b5e20", 1.2, NULL);
            curve(&svg, cb, xb, off, "#3f007d", 1.2, NULL);
            for (int i = 0; i < count[p]; ++i) {
                const rugo_contact* c = &contacts[p][i];
                const rugo_vec2 a = rugo_v2_add(c->point_a, off), b = rugo_v2_add(c->point_b, off);
                fprintf(svg.file, "<g class=\"contact\">\n");
                svg_point(&svg, a, 3.0, "#d95f02");
                svg_point(&svg, b, 3.0, "#d95f02");
                svg_arrow(&svg, a, rugo_v2_add(a, rugo_v2_scale(0.25, c->normal)), "#e7298a");
                fprintf(svg.file, "</g>\n");
                ++drawn;
            }
            fprintf(svg.file, "</g>\n");
            snprintf(text, sizeof text, "%s (%d and %d points): %s, μ %.2f", p ? "level -2" : "finest level",
                     ca.count, cb.count, rugo_contact_state_name(state[p]),
                     count[p] > 0 ? contacts[p][0].friction : 0.0);
            label(&svg, rugo_v2(clo.x + off.x, chi.y + 0.08), text);
        }
        sample_expect("wrote contacts.svg", svg_close(&svg) == 0);
        sample_expect("contacts.svg shows every contact of both levels",
                      count_in_file(path, "class=\"contact\"") == drawn && drawn == count[0] + count[1]);
    }

    rugo_shape_destroy(pebble);
    rugo_shape_destroy(rock);
    return sample_finish();
}
