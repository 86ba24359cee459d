#define _POSIX_C_SOURCE 200809L
/* Thesis Fig. 4.5: MOBBtree build time (a) against the segment count of one object (32, 64, ...,
 * 8192 segments) and (b) against the number of objects of 256 segments (2..12). The build is O(n)
 * (thesis 4.3: 2n - 1 boxes, each in constant time); this benchmark measures it, and issue 7's goal:
 * the tree build at most 100 ns per segment at 4096 segments.
 *
 * Usage: fig4_5_build_time [--quick] OUTDIR
 * Two times per case, each the minimum over repetitions (as the thesis did):
 *   tree  = rugo_mobb_tree_create alone (pyramid and tolerances prebuilt), method (b) and (a);
 *   full  = pyramid (with its outline check) + tolerances (tipo_3) + tree (b): what a shape costs.
 * Prints CSV, the least-squares line time = a + b n with its R^2, and a one-line summary with the
 * cost per segment at 4096 segments and its ratio to the 100 ns goal (an absolute time: build in
 * Release and run on a quiet machine); writes fig4_5a.csv, fig4_5b.csv and fig4_5_summary.json into
 * OUTDIR. --quick runs one repetition (the test registration): it checks that everything ran and that
 * every tree has 2n - 4 nodes; timings are not asserted (no timed tests on shared machines).
 * A full run takes about a minute on an idle machine (at least 15 repetitions of every phase). */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One object ready for tree building. */
typedef struct object {
    int n;
    rugo_vec2* points;
    double* lambda;
    rugo_pyramid* pyramid;
    rugo_tolerances* tolerances;
} object;

static int make_object(object* o, int n, int index) {
    memset(o, 0, sizeof *o);
    o->n = n;
    o->points = malloc((size_t)n * sizeof *o->points);
    o->lambda = malloc((size_t)n * sizeof *o->lambda);
    if (o->points == NULL || o->lambda == NULL) return 0;
    /* Objects of one scene differ in place and size. */
    sample_object(n, rugo_v2(300.0 + 500.0 * index, 300.0 - 120.0 * index), 200.0 + 15.0 * index, o->points);
    rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, n, o->lambda);
    return 1;
}

static rugo_status build_levels(object* o) {
    rugo_pyramid_def pd = rugo_default_pyramid_def();
    pd.points = o->points;
    pd.count = o->n;
    rugo_status st = rugo_pyramid_create(&pd, &o->pyramid, NULL);
    if (st != RUGO_OK) return st;
    rugo_tolerance_def td = rugo_default_tolerance_def();
    td.pyramid = o->pyramid;
    td.finest = o->lambda;
    td.count = o->n;
    return rugo_tolerances_create(&td, &o->tolerances);
}

static void free_levels(object* o) {
    rugo_tolerances_destroy(o->tolerances);
    rugo_pyramid_destroy(o->pyramid);
    o->tolerances = NULL;
    o->pyramid = NULL;
}

static void free_object(object* o) {
    free_levels(o);
    free(o->points);
    free(o->lambda);
}

static rugo_status build_tree(const object* o, rugo_box_method m, rugo_mobb_tree** out) {
    rugo_mobb_tree_def def = rugo_default_mobb_tree_def();
    def.pyramid = o->pyramid;
    def.tolerances = o->tolerances;
    def.method = m;
    return rugo_mobb_tree_create(&def, out);
}

static long count_nodes(const rugo_mobb_tree* t) {
    long c = 0;
    for (int j = 0; j <= 31 && j <= rugo_mobb_tree_finest_level(t) + 1; ++j)
        for (long k = 0; k < (1L << j); ++k)
            c += rugo_mobb_tree_node(t, j, (int)k) != NULL;
    return c;
}

/* Least squares y = a + b x; R^2. */
static void fit_line(const double* x, const double* y, int n, double* a, double* b, double* r2) {
    double mx = 0.0, my = 0.0;
    for (int i = 0; i < n; ++i) {
        mx += x[i] / n;
        my += y[i] / n;
    }
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (int i = 0; i < n; ++i) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
        syy += (y[i] - my) * (y[i] - my);
    }
    *b = sxx > 0.0 ? sxy / sxx : 0.0;
    *a = my - *b * mx;
    *r2 = sxx > 0.0 && syy > 0.0 ? sxy * sxy / (sxx * syy) : 1.0;
}

typedef struct timing {
    double tree_b, tree_a, full;
} timing;

/* Times building the trees of objects[0..count): the minimum over repetitions of each phase. The
 * full build (pyramid + tolerances + tree) and the tree alone repeat separately, each at least
 * min_reps times and then until min_total seconds were spent on it, at most max_reps times: on a
 * shared machine the minimum of many short runs is the figure that excludes other processes. */
static int time_case(object* objs, int count, int min_reps, int max_reps, double min_total, timing* out,
                     long* nodes_ok) {
    out->tree_b = out->tree_a = out->full = INFINITY;
    double spent = 0.0;
    for (int rep = 0; rep < max_reps && (rep < min_reps || spent < min_total); ++rep) {
        double t0 = now();
        for (int i = 0; i < count; ++i) {
            free_levels(&objs[i]);
            rugo_mobb_tree* tree = NULL;
            if (build_levels(&objs[i]) != RUGO_OK ||
                build_tree(&objs[i], RUGO_BOXES_MULTIRES, &tree) != RUGO_OK)
                return 0;
            rugo_mobb_tree_destroy(tree);
        }
        double t1 = now();
        out->full = fmin(out->full, t1 - t0);
        spent += t1 - t0;
    }
    for (int m = 0; m < 2; ++m) {
        spent = 0.0;
        for (int rep = 0; rep < max_reps && (rep < min_reps || spent < min_total); ++rep) {
            rugo_mobb_tree* trees[16];
            double s0 = now();
            for (int i = 0; i < count; ++i)
                if (build_tree(&objs[i], (rugo_box_method)m, &trees[i]) != RUGO_OK) return 0;
            double s1 = now();
            for (int i = 0; i < count; ++i) {
                if (rep == 0) *nodes_ok &= count_nodes(trees[i]) == 2L * objs[i].n - 4;
                rugo_mobb_tree_destroy(trees[i]);
            }
            double dt = s1 - s0;
            if (m == RUGO_BOXES_MULTIRES)
                out->tree_b = fmin(out->tree_b, dt);
            else
                out->tree_a = fmin(out->tree_a, dt);
            spent += dt;
        }
    }
    return 1;
}

int main(int argc, char** argv) {
    int quick = 0;
    const char* dir = "out/fig4_5_build_time";
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (argv[i][0] == '-') { /* an unknown option, --help included: not a directory name */
            fprintf(stderr, "usage: %s [--quick] [OUTDIR]\n", argv[0]);
            return 2;
        } else
            dir = argv[i];
    }
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    const int min_reps = quick ? 1 : 15, max_reps = quick ? 1 : 2000;
    const double min_total = quick ? 0.0 : 0.3;
    char path[1200];
    long nodes_ok = 1;

    /* (a) one object, 32 .. 8192 segments. */
    enum { SIZES = 9 };
    double xs[SIZES], tb[SIZES], ta[SIZES], tf[SIZES];
    snprintf(path, sizeof path, "%s/fig4_5a.csv", dir);
    FILE* fa = fopen(path, "w");
    if (fa == NULL) return 1;
    printf("# Fig. 4.5(a): one object, build time in seconds (minimum of repetitions)\n");
    printf("segments,boxes,tree_b_s,tree_a_s,full_s,tree_b_ns_per_segment\n");
    fprintf(fa, "segments,boxes,tree_b_s,tree_a_s,full_s\n");
    int ran = 1;
    for (int s = 0; s < SIZES; ++s) {
        int n = 32 << s;
        object o;
        timing t;
        ran &= make_object(&o, n, 0) && time_case(&o, 1, min_reps, max_reps, min_total, &t, &nodes_ok);
        free_object(&o);
        if (!ran) break;
        xs[s] = n;
        tb[s] = t.tree_b;
        ta[s] = t.tree_a;
        tf[s] = t.full;
        printf("%d,%d,%.9f,%.9f,%.9f,%.1f\n", n, 2 * n - 4, t.tree_b, t.tree_a, t.full, 1e9 * t.tree_b / n);
        fprintf(fa, "%d,%d,%.9f,%.9f,%.9f\n", n, 2 * n - 4, t.tree_b, t.tree_a, t.full);
    }
    fclose(fa);
    sample_expect("Fig. 4.5(a): every size built", ran);

    /* (b) 2 .. 12 objects of 256 segments. */
    enum { COUNTS = 11 };
    double xo[COUNTS], ob[COUNTS], oa[COUNTS], of[COUNTS];
    object objs[12];
    int made = 1;
    for (int i = 0; i < 12; ++i)
        made &= make_object(&objs[i], 256, i);
    snprintf(path, sizeof path, "%s/fig4_5b.csv", dir);
    FILE* fb = fopen(path, "w");
    if (fb == NULL || !made) return 1;
    printf("# Fig. 4.5(b): objects of 256 segments, total build time in seconds (minimum of repetitions)\n");
    printf("objects,segments,tree_b_s,tree_a_s,full_s\n");
    fprintf(fb, "objects,segments,tree_b_s,tree_a_s,full_s\n");
    int ran_b = 1;
    for (int c = 2; c <= 12 && ran_b; ++c) {
        timing t;
        ran_b &= time_case(objs, c, min_reps, max_reps, min_total, &t, &nodes_ok);
        if (!ran_b) break;
        xo[c - 2] = c;
        ob[c - 2] = t.tree_b;
        oa[c - 2] = t.tree_a;
        of[c - 2] = t.full;
        printf("%d,%d,%.9f,%.9f,%.9f\n", c, 256 * c, t.tree_b, t.tree_a, t.full);
        fprintf(fb, "%d,%d,%.9f,%.9f,%.9f\n", c, 256 * c, t.tree_b, t.tree_a, t.full);
    }
    for (int i = 0; i < 12; ++i)
        free_object(&objs[i]);
    fclose(fb);
    sample_expect("Fig. 4.5(b): every object count built", ran_b);
    sample_expect("every tree has 2n - 4 nodes (levels 2..J)", nodes_ok != 0);
    if (!ran || !ran_b) return sample_finish();

    /* Linear fits. */
    double a1, b1, r1, a2, b2, r2, a3, b3, r3, a4, b4, r4, a5, b5, r5, a6, b6, r6;
    fit_line(xs, tb, SIZES, &a1, &b1, &r1);
    fit_line(xs, ta, SIZES, &a2, &b2, &r2);
    fit_line(xs, tf, SIZES, &a3, &b3, &r3);
    fit_line(xo, ob, COUNTS, &a4, &b4, &r4);
    fit_line(xo, of, COUNTS, &a5, &b5, &r5);
    fit_line(xo, oa, COUNTS, &a6, &b6, &r6);
    printf("# least squares, time = a + b x%s\n", quick ? " (--quick: one repetition, noisy)" : "");
    printf("fit,slope,intercept_s,r2\n");
    printf("(a) tree (b) vs segments,%.4g s/segment,%.3g,%.6f\n", b1, a1, r1);
    printf("(a) tree (a) vs segments,%.4g s/segment,%.3g,%.6f\n", b2, a2, r2);
    printf("(a) full vs segments,%.4g s/segment,%.3g,%.6f\n", b3, a3, r3);
    printf("(b) tree (b) vs objects,%.4g s/object,%.3g,%.6f\n", b4, a4, r4);
    printf("(b) tree (a) vs objects,%.4g s/object,%.3g,%.6f\n", b6, a6, r6);
    printf("(b) full vs objects,%.4g s/object,%.3g,%.6f\n", b5, a5, r5);
    /* Issue 7's point: 4096 segments, the tree alone, method (b) (the default). */
    enum { GOAL_SIZE = 4096 };
    const double goal_ns = 100.0;
    int g = 0;
    while (g < SIZES - 1 && xs[g] < GOAL_SIZE)
        ++g;
    const double tb_ns = 1e9 * tb[g] / xs[g], ta_ns = 1e9 * ta[g] / xs[g], tf_ns = 1e9 * tf[g] / xs[g];
    printf(
        "summary: at %d segments the tree costs %.1f ns/segment (method (b); %.2f x the %.0f ns goal, %s), "
        "%.1f ns with method (a), %.1f ns with pyramid and tolerances; slopes %.1f / %.1f ns/segment "
        "(R^2 %.4f / %.4f); per 256-segment object %.3g s (R^2 %.4f)%s\n",
        (int)xs[g], tb_ns, tb_ns / goal_ns, goal_ns,
        quick              ? "not judged in --quick"
        : tb_ns <= goal_ns ? "met"
                           : "NOT met",
        ta_ns, tf_ns, 1e9 * b1, 1e9 * b3, r1, r3, b4, r4, quick ? " (--quick: one repetition, noisy)" : "");

    snprintf(path, sizeof path, "%s/fig4_5_summary.json", dir);
    FILE* fj = fopen(path, "w");
    if (fj == NULL) return 1;
    fprintf(
        fj,
        "{\"quick\": %s, \"segments\": {\"tree_b_slope_s_per_segment\": %.6g, \"tree_b_r2\": %.6f, "
        "\"tree_a_slope_s_per_segment\": %.6g, \"tree_a_r2\": %.6f, \"full_slope_s_per_segment\": %.6g, "
        "\"full_r2\": %.6f},\n \"objects\": {\"tree_b_slope_s_per_object\": %.6g, \"tree_b_r2\": %.6f, "
        "\"tree_a_slope_s_per_object\": %.6g, \"tree_a_r2\": %.6f, \"full_slope_s_per_object\": %.6g, "
        "\"full_r2\": %.6f},\n"
        " \"at_%d_segments\": {\"tree_b_ns_per_segment\": %.2f, \"tree_a_ns_per_segment\": %.2f, "
        "\"full_ns_per_segment\": %.2f, \"goal_ns_per_segment\": %.0f, \"tree_b_ratio_to_goal\": %.4f}}\n",
        quick ? "true" : "false", b1, r1, b2, r2, b3, r3, b4, r4, b6, r6, b5, r5, (int)xs[g], tb_ns, ta_ns,
        tf_ns, goal_ns, tb_ns / goal_ns);
    sample_expect("wrote fig4_5a.csv, fig4_5b.csv, fig4_5_summary.json", fclose(fj) == 0);
    sample_expect("timings are finite and positive",
                  isfinite(b1) && tb[SIZES - 1] > 0.0 && ob[COUNTS - 1] > 0.0);
    sample_expect("the goal's size (4096 segments) was measured", xs[g] == GOAL_SIZE && tb[g] > 0.0);
    return sample_finish();
}
