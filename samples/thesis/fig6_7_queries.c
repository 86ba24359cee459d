/* Thesis Fig. 6.7: three objects of 512 segments in four situations, from apart to heavy contact:
 * boxes compared (OBB tests of the MOBBtree traversal, SPEC 7) and time per query, next to the
 * thesis' 35 / 171 / 343 / 459 boxes and 0.0001 / 0.003 / 0.007 / 0.01 s (Sun SPARCstation 20).
 *
 * Objects 0 and 1 sit side by side, object 2 comes down from above. Gaps are measured from the first
 * touching distance (bisections on the query's state): apart (all clear); contact (0 and 1 touch
 * within the tolerance band); overlap (0 and 1 overlap slightly, 2 comes down on the middle until it
 * touches one of them); heavy (0 and 1 overlap more, 2 comes down where it touches both at once and is
 * pressed into both). "Heavy" means many curve pieces close together, as in the thesis' picture,
 * rather than a deep penetration: deeper overlaps cross more steeply and test fewer boxes. Per
 * situation the program
 * sums over the three pairs (0-1, 1-2, 0-2) the box tests of rugo_tree_pairs down to the finest
 * level and the time of rugo_collide_shapes (mean of repeated queries, clock_gettime), and writes
 *   fig6_7_<situation>.svg   the three curves, contact points and normals;
 *   fig6_7.csv, fig6_7.json  the table (also printed).
 * Checks: box counts increase from apart to heavy contact; apart gives APART for every pair, contact
 * gives CONTACT for 0-1, overlap INTERSECTING for 0-1 and a contact of 2, heavy INTERSECTING for
 * every touching pair with deeper separations; every contact is finite. Absolute times depend on the machine;
 * only the trend is checked. */
#define _POSIX_C_SOURCE 200809L
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

enum { N = 512, OBJECTS = 3, SITUATIONS = 4, CAP = 256 };

static const char* SIT_NAME[SITUATIONS] = {"apart", "contact", "overlap", "heavy"};
static const int THESIS_BOXES[SITUATIONS] = {35, 171, 343, 459};
static const double THESIS_TIME[SITUATIONS] = {0.0001, 0.003, 0.007, 0.01};

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct object {
    rugo_shape* shape;
    rugo_transform x;
    double radius;
} object;

static rugo_contact_state state_of(rugo_collide_context* ctx, const object* a, const object* b) {
    /* placed by the round-off answer, whatever resolution the figure's queries run at */
    rugo_contact_query q = rugo_default_contact_query();
    q.resolution = 0.0;
    rugo_contact_output out = rugo_contact_output_of(NULL, 0); /* the state only */
    rugo_collide_shapes(a->shape, a->x, b->shape, b->x, &q, ctx, &out);
    return out.state;
}

/* Smallest distance d along dir from `from` at which b (placed at from + d dir) intersects none of
 * the objects a[0..na). */
static double touching(rugo_collide_context* ctx, const object* a, int na, object* b, rugo_vec2 from,
                       rugo_vec2 dir) {
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < na; ++i)
        hi = fmax(hi, 2.5 * (a[i].radius + b->radius) + hypot(a[i].x.p.x - from.x, a[i].x.p.y - from.y));
    for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        b->x.p = rugo_v2(from.x + mid * dir.x, from.y + mid * dir.y);
        int any = 0;
        for (int i = 0; i < na; ++i)
            any |= state_of(ctx, &a[i], b) == RUGO_STATE_INTERSECTING;
        if (any)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

static void draw_object(svg_canvas* c, const object* o, const char* stroke) {
    rugo_contour k;
    rugo_shape_level(o->shape, rugo_shape_finest_level(o->shape), &k);
    static rugo_vec2 w[N];
    for (int i = 0; i < k.count; ++i)
        w[i] = rugo_transform_point(o->x, k.points[i]);
    rugo_contour kw = {w, k.count};
    svg_contour(c, kw, 4, stroke, 1.2, NULL);
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[argc - 1] : "out/fig6_7_queries";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    /* Three irregular rough objects of 512 segments (the thesis' objects are not available). */
    object obj[OBJECTS];
    static rugo_vec2 pts[N];
    static double tol[N];
    const double radius[OBJECTS] = {100.0, 80.0, 120.0};
    for (int o = 0; o < OBJECTS; ++o) {
        sample_object(N, rugo_v2(0.0, 0.0), radius[o], pts);
        rugo_status st = rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, N, tol);
        if (st != RUGO_OK) return 1;
        for (int i = 0; i < N; ++i)
            tol[i] *= 0.01 * radius[o]; /* 0.2 .. 0.32 % of the size */
        rugo_shape_def d = rugo_default_shape_def();
        d.points = pts;
        d.count = N;
        d.tolerances = tol;
        st = rugo_shape_create(&d, &obj[o].shape, NULL);
        if (st != RUGO_OK) {
            fprintf(stderr, "rugo_shape_create: %s\n", rugo_status_string(st));
            return 1;
        }
        obj[o].x = rugo_make_transform(0.0, 0.0, 0.7 * o);
        obj[o].radius = 1.3 * radius[o];
    }
    rugo_collide_context* ctx = NULL;
    if (rugo_collide_context_create(NULL, &ctx) != RUGO_OK) return 1;

    /* Touching offsets, then the four situations' gaps (0-1, and 2 above). */
    object tmp = obj[1];
    obj[0].x.p = rugo_v2(0.0, 0.0);
    const double t01 = touching(ctx, &obj[0], 1, &tmp, obj[0].x.p, rugo_v2(1.0, 0.0));
    const double band = 0.01 * radius[0]; /* well inside the summed bands of the objects */
    const double gap01[SITUATIONS] = {0.25 * radius[0], 0.2 * band, -0.03 * radius[0], -0.05 * radius[0]};
    const double gap2[SITUATIONS] = {0.25 * radius[0], 0.25 * radius[0], 0.2 * band, -0.03 * radius[0]};
    long boxes[SITUATIONS];
    double times[SITUATIONS];
    int states[SITUATIONS][3];
    double min_sep[SITUATIONS];
    int all_finite = 1;
    char path[1200];
    snprintf(path, sizeof path, "%s/fig6_7.csv", dir);
    FILE* csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/fig6_7.json", dir);
    FILE* js = fopen(path, "w");
    if (csv == NULL || js == NULL) return 1;
    fprintf(csv, "situation,boxes_compared,thesis_boxes,seconds_per_situation,thesis_seconds,segment_pairs,"
                 "contacts,states\n");
    fprintf(js, "{\"objects\": %d, \"segments_per_object\": %d, \"situations\": [", OBJECTS, N);
    printf("%-8s %8s %8s %12s %10s %8s %8s  %s\n", "", "boxes", "thesis", "time [s]", "thesis", "pairs",
           "contacts", "states (0-1, 1-2, 0-2)");
    fflush(stdout);
    for (int s = 0; s < SITUATIONS; ++s) {
        /* 0 at the origin, 1 right of it, 2 above them. */
        obj[1].x.p = rugo_v2(t01 + gap01[s], 0.0);
        object o2 = obj[2];
        rugo_vec2 mid = rugo_v2(0.5 * obj[1].x.p.x, 0.0);
        if (s == SITUATIONS - 1) {
            /* Where 2 coming straight down touches 0 and 1 at once: bisection on the lateral offset
             * between "touches 0 first" and "touches 1 first". */
            double lo = -radius[0], hi = obj[1].x.p.x + radius[1];
            for (int it = 0; it < 40; ++it) {
                const double x = 0.5 * (lo + hi);
                const double h = touching(ctx, obj, 2, &o2, rugo_v2(x, 0.0), rugo_v2(0.0, 1.0));
                o2.x.p = rugo_v2(x, h - 1e-9 * radius[0]);
                if (state_of(ctx, &obj[0], &o2) == RUGO_STATE_INTERSECTING)
                    lo = x;
                else
                    hi = x;
            }
            mid = rugo_v2(0.5 * (lo + hi), 0.0);
        }
        const double t2 = touching(ctx, obj, 2, &o2, mid, rugo_v2(0.0, 1.0));
        obj[2].x.p = rugo_v2(mid.x, t2 + gap2[s]);
        const int pa[3] = {0, 1, 0}, pb[3] = {1, 2, 2};
        long tests_total = 0, pairs_total = 0;
        int contacts_total = 0;
        double secs = 0.0;
        min_sep[s] = HUGE_VAL;
        static rugo_contact c[3][CAP];
        int nc[3];
        for (int k = 0; k < 3; ++k) {
            const object* A = &obj[pa[k]];
            const object* B = &obj[pb[k]];
            int np = 0;
            long tests = 0;
            rugo_tree_pairs(rugo_shape_tree(A->shape), A->x, rugo_shape_finest_level(A->shape),
                            rugo_shape_tree(B->shape), B->x, rugo_shape_finest_level(B->shape), ctx, NULL, 0,
                            &np, &tests);
            tests_total += tests;
            rugo_contact_output out = rugo_contact_output_of(c[k], CAP);
            int reps = 0;
            double t0 = now(), t1 = t0;
            do { /* repeat until 20 ms have passed (at least 3 times) for a stable mean */
                rugo_collide_shapes(A->shape, A->x, B->shape, B->x, NULL, ctx, &out);
                ++reps;
                t1 = now();
            } while (reps < 3 || t1 - t0 < 0.02);
            secs += (t1 - t0) / reps;
            nc[k] = out.count;
            states[s][k] = (int)out.state;
            pairs_total += out.stats.segment_pairs;
            contacts_total += nc[k];
            for (int i = 0; i < nc[k]; ++i) {
                all_finite &= isfinite(c[k][i].separation) && isfinite(c[k][i].normal.x) &&
                              isfinite(c[k][i].normal.y) && isfinite(c[k][i].point_a.x) &&
                              isfinite(c[k][i].point_b.y);
                if (c[k][i].separation < min_sep[s]) min_sep[s] = c[k][i].separation;
            }
        }
        boxes[s] = tests_total;
        times[s] = secs;
        printf("%-8s %8ld %8d %12.6f %10.4f %8ld %8d  %s, %s, %s\n", SIT_NAME[s], tests_total,
               THESIS_BOXES[s], secs, THESIS_TIME[s], pairs_total, contacts_total,
               rugo_contact_state_name((rugo_contact_state)states[s][0]),
               rugo_contact_state_name((rugo_contact_state)states[s][1]),
               rugo_contact_state_name((rugo_contact_state)states[s][2]));
        fprintf(csv, "%s,%ld,%d,%.9f,%.4f,%ld,%d,%s;%s;%s\n", SIT_NAME[s], tests_total, THESIS_BOXES[s], secs,
                THESIS_TIME[s], pairs_total, contacts_total,
                rugo_contact_state_name((rugo_contact_state)states[s][0]),
                rugo_contact_state_name((rugo_contact_state)states[s][1]),
                rugo_contact_state_name((rugo_contact_state)states[s][2]));
        fprintf(js,
                "%s\n  {\"situation\": \"%s\", \"gaps\": [%.6g, %.6g], \"boxes_compared\": %ld, "
                "\"thesis_boxes\": %d, \"seconds\": %.9f, "
                "\"thesis_seconds\": %.4f, \"segment_pairs\": %ld, \"contacts\": %d, \"states\": [\"%s\", "
                "\"%s\", \"%s\"]}",
                s ? "," : "", SIT_NAME[s], gap01[s], gap2[s], tests_total, THESIS_BOXES[s], secs,
                THESIS_TIME[s], pairs_total, contacts_total,
                rugo_contact_state_name((rugo_contact_state)states[s][0]),
                rugo_contact_state_name((rugo_contact_state)states[s][1]),
                rugo_contact_state_name((rugo_contact_state)states[s][2]));

        /* The picture: curves, contact points (A red, B blue) and normals. */
        rugo_vec2 lo = rugo_v2(-1.6 * radius[0], -1.6 * radius[0]);
        rugo_vec2 hi = rugo_v2(obj[1].x.p.x + 1.6 * radius[1], obj[2].x.p.y + 1.6 * radius[2]);
        snprintf(path, sizeof path, "%s/fig6_7_%s.svg", dir, SIT_NAME[s]);
        svg_canvas cv;
        if (svg_open(&cv, path, lo, hi, 900.0) != 0) return 1;
        const char* colours[OBJECTS] = {"#333", "#2a6", "#a52"};
        for (int o = 0; o < OBJECTS; ++o)
            draw_object(&cv, &obj[o], colours[o]);
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < nc[k]; ++i) {
                svg_point(&cv, c[k][i].point_a, 2.5, "red");
                svg_point(&cv, c[k][i].point_b, 2.5, "blue");
                svg_arrow(&cv, c[k][i].point_a,
                          rugo_v2_add(c[k][i].point_a, rugo_v2_scale(0.15 * radius[0], c[k][i].normal)),
                          "red");
            }
        char label[200];
        snprintf(label, sizeof label, "%s: %ld boxes compared (thesis %d), %.3g ms", SIT_NAME[s], tests_total,
                 THESIS_BOXES[s], 1e3 * secs);
        svg_text(&cv, rugo_v2(lo.x, hi.y), label, 14.0);
        if (svg_close(&cv) != 0) return 1;
    }
    fprintf(js, "\n]}\n");
    int io_ok = fclose(csv) == 0;
    io_ok &= fclose(js) == 0;

    sample_expect("files written", io_ok);
    for (int s = 1; s < SITUATIONS; ++s) {
        char name[120];
        snprintf(name, sizeof name, "boxes compared increase: %s (%ld) > %s (%ld)", SIT_NAME[s], boxes[s],
                 SIT_NAME[s - 1], boxes[s - 1]);
        sample_expect(name, boxes[s] > boxes[s - 1]);
    }
    sample_expect("apart: every pair APART", states[0][0] == RUGO_STATE_APART &&
                                                 states[0][1] == RUGO_STATE_APART &&
                                                 states[0][2] == RUGO_STATE_APART);
    sample_expect("contact: 0-1 in CONTACT, the others APART, positive separations",
                  states[1][0] == RUGO_STATE_CONTACT && states[1][1] == RUGO_STATE_APART &&
                      states[1][2] == RUGO_STATE_APART && min_sep[1] >= 0.0);
    sample_expect("overlap: 0-1 INTERSECTING, 2 in CONTACT with one of them",
                  states[2][0] == RUGO_STATE_INTERSECTING && min_sep[2] < 0.0 &&
                      (states[2][1] == RUGO_STATE_CONTACT || states[2][2] == RUGO_STATE_CONTACT));
    sample_expect("heavy: every pair INTERSECTING, deeper than the overlap",
                  states[3][0] == RUGO_STATE_INTERSECTING && states[3][1] == RUGO_STATE_INTERSECTING &&
                      states[3][2] == RUGO_STATE_INTERSECTING && min_sep[3] < min_sep[2]);
    sample_expect("every contact finite", all_finite);
    printf("time ratios (machine-independent): contact/apart %.1f, overlap/apart %.1f, heavy/apart %.1f "
           "(thesis: 30, 70, 100)\n",
           times[1] / times[0], times[2] / times[0], times[3] / times[0]);
    for (int o = 0; o < OBJECTS; ++o)
        rugo_shape_destroy(obj[o].shape);
    rugo_collide_context_destroy(ctx);
    return sample_finish();
}
