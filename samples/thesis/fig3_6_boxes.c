/* Thesis Fig. 3.6 and Fig. 4.6: the levels of the MOBBtree of a 64-point and a 256-point object, for
 * both ways of building upper boxes — (a) box of boxes (covariance of the leaf boxes' centres) and
 * (b) multiresolution boxes (the coarse segment's own box, enlarged) — and the total box area per level
 * next to the areas the thesis printed for its 256-segment object (levels 7..3).
 *
 * Writes, into the directory given as the last argument:
 *   fig3_6_n<N>_<method>_level<j>.svg  boxes of level j over the finest curve (grey) and the level's
 *                                      own curve (dashed), for N = 64, 256 and method a / b;
 *   fig4_6_areas.csv, fig4_6_areas.json  the area table (also printed).
 * Checks the tree invariant (mobb.h) on both objects, both methods, smooth and rough (tipo_5 tolerances,
 * scaled), and reports where (b) is smaller than (a). The thesis' object is not available, so compare
 * trends (growth of the area towards coarse levels, the sign of (b) - (a)), not values. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "sample_shapes.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Fig. 4.6, 256-segment object: total box area per level, (a) box of boxes, (b) multiresolution. */
static const int THESIS_LEVELS[5] = {7, 6, 5, 4, 3};
static const double THESIS_A[5] = {898.001, 2461.882, 3595.044, 5302.826, 10161.296};
static const double THESIS_B[5] = {877.592, 2404.968, 3852.326, 5422.778, 9466.018};

static const char* method_tag(rugo_box_method m) { return m == RUGO_BOXES_OF_BOXES ? "a" : "b"; }

static double thesis_value(const double* values, int level) {
    for (int i = 0; i < 5; ++i)
        if (THESIS_LEVELS[i] == level) return values[i];
    return NAN;
}

static void svg_box(svg_canvas* c, const rugo_obb* b, const char* stroke) {
    rugo_vec2 q[4];
    rugo_obb_corners(b, q);
    fprintf(c->file, "<polygon fill=\"none\" stroke=\"%s\" stroke-width=\"0.8\" points=\"", stroke);
    for (int i = 0; i < 4; ++i)
        fprintf(c->file, "%.2f,%.2f ", (q[i].x - c->ox) * c->scale, c->height - (q[i].y - c->oy) * c->scale);
    fprintf(c->file, "\"/>\n");
}

/* The invariant of mobb.h on dense samples: node (j, k) contains every descendant finest segment
 * thickened by β^J (as discs) and its own coarse segment thickened by λ^j_k; parents contain their
 * children. Returns the largest violation (<= 0 when it holds). */
static double invariant_violation(const rugo_mobb_tree* tree, const rugo_pyramid* p,
                                  const rugo_tolerances* t) {
    enum { S = 24 };
    int J = rugo_pyramid_finest_level(p), J0 = rugo_pyramid_coarsest_level(p);
    rugo_contour fine;
    rugo_pyramid_level(p, J, &fine);
    rugo_tolerance_level fl;
    if (t) rugo_tolerances_level(t, J, &fl);
    double worst = -INFINITY;
    for (int j = J0; j <= J; ++j) {
        rugo_contour cj;
        rugo_pyramid_level(p, j, &cj);
        rugo_tolerance_level tl;
        if (t) rugo_tolerances_level(t, j, &tl);
        for (int k = 0; k < (1 << j); ++k) {
            const rugo_obb* b = rugo_mobb_tree_node(tree, j, k);
            /* excess of a disc of radius rad around q beyond the box */
            for (int i = k << (J - j); i < (k + 1) << (J - j); ++i)
                for (int s = 0; s <= S; ++s) {
                    rugo_vec2 d = rugo_v2_sub(rugo_contour_point(fine, i, (double)s / S), b->center);
                    double rad = t ? fl.bound[i] : 0.0;
                    for (int a = 0; a < 2; ++a)
                        worst = fmax(worst, fabs(rugo_v2_dot(d, b->axis[a])) + rad - b->half[a]);
                }
            for (int s = 0; s <= S; ++s) {
                rugo_vec2 d = rugo_v2_sub(rugo_contour_point(cj, k, (double)s / S), b->center);
                double rad = t ? tl.total[k] : 0.0;
                for (int a = 0; a < 2; ++a)
                    worst = fmax(worst, fabs(rugo_v2_dot(d, b->axis[a])) + rad - b->half[a]);
            }
            if (j < J)
                for (int c = 0; c < 2; ++c) {
                    rugo_vec2 q[4];
                    rugo_obb_corners(rugo_mobb_tree_node(tree, j + 1, 2 * k + c), q);
                    for (int i = 0; i < 4; ++i) {
                        rugo_vec2 d = rugo_v2_sub(q[i], b->center);
                        for (int a = 0; a < 2; ++a)
                            worst = fmax(worst, fabs(rugo_v2_dot(d, b->axis[a])) - b->half[a]);
                    }
                }
        }
    }
    return worst;
}

static int build(const rugo_pyramid* p, const rugo_tolerances* t, rugo_box_method m, rugo_mobb_tree** out) {
    rugo_mobb_tree_def def = rugo_default_mobb_tree_def();
    def.pyramid = p;
    def.tolerances = t;
    def.method = m;
    rugo_status st = rugo_mobb_tree_create(&def, out);
    if (st != RUGO_OK) fprintf(stderr, "rugo_mobb_tree_create: %s\n", rugo_status_string(st));
    return st == RUGO_OK;
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[argc - 1] : "out/fig3_6_boxes";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    char path[1200];
    snprintf(path, sizeof path, "%s/fig4_6_areas.csv", dir);
    FILE* csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/fig4_6_areas.json", dir);
    FILE* json = fopen(path, "w");
    if (csv == NULL || json == NULL) {
        fprintf(stderr, "cannot write into %s\n", dir);
        return 1;
    }
    fprintf(csv, "object,level,boxes,area_a,area_b,b_over_a,thesis_a,thesis_b,thesis_b_over_a\n");
    fprintf(json, "{\"thesis_object_segments\": 256, \"objects\": [");

    const int sizes[2] = {64, 256};
    int svg_ok = 1, svg_count = 0;
    for (int oi = 0; oi < 2; ++oi) {
        int n = sizes[oi], J = n == 64 ? 6 : 8;
        rugo_vec2* pts = malloc((size_t)n * sizeof *pts);
        if (pts == NULL) return 1;
        sample_object(n, rugo_v2(300.0, 300.0), 200.0, pts);
        rugo_pyramid_def pd = rugo_default_pyramid_def();
        pd.points = pts;
        pd.count = n;
        rugo_pyramid* p = NULL;
        rugo_status st = rugo_pyramid_create(&pd, &p, NULL);
        if (st != RUGO_OK) {
            fprintf(stderr, "rugo_pyramid_create: %s\n", rugo_status_string(st));
            return 1;
        }
        int J0 = rugo_pyramid_coarsest_level(p);

        /* Rough version: the thesis' tipo_5 pattern, scaled to this object's size (radius 200). */
        double* lam = malloc((size_t)n * sizeof *lam);
        if (lam == NULL) return 1;
        rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, n, lam);
        for (int i = 0; i < n; ++i)
            lam[i] *= 4.0;
        rugo_tolerance_def td = rugo_default_tolerance_def();
        td.pyramid = p;
        td.finest = lam;
        td.count = n;
        rugo_tolerances* tol = NULL;
        st = rugo_tolerances_create(&td, &tol);
        if (st != RUGO_OK) {
            fprintf(stderr, "rugo_tolerances_create: %s\n", rugo_status_string(st));
            return 1;
        }

        rugo_mobb_tree* trees[2] = {NULL, NULL}; /* smooth, indexed by method */
        for (int m = 0; m < 2; ++m) {
            rugo_mobb_tree* rough = NULL;
            if (!build(p, NULL, (rugo_box_method)m, &trees[m]) || !build(p, tol, (rugo_box_method)m, &rough))
                return 1;
            char name[160];
            snprintf(name, sizeof name,
                     "%d-point object, method (%s), smooth: invariant holds (worst excess)", n,
                     method_tag((rugo_box_method)m));
            sample_expect_le(name, invariant_violation(trees[m], p, NULL), 0.0);
            snprintf(name, sizeof name,
                     "%d-point object, method (%s), rough (tipo_5 x4): invariant holds (worst excess)", n,
                     method_tag((rugo_box_method)m));
            sample_expect_le(name, invariant_violation(rough, p, tol), 0.0);
            rugo_mobb_tree_destroy(rough);
        }

        /* Pictures: one per method and level. */
        rugo_contour fine;
        rugo_pyramid_level(p, J, &fine);
        rugo_vec2 lo, hi;
        const rugo_obb* root = rugo_mobb_tree_root(trees[0]);
        rugo_vec2 rc[4];
        rugo_obb_corners(root, rc);
        lo = hi = rc[0];
        for (int i = 1; i < 4; ++i) {
            lo = rugo_v2(fmin(lo.x, rc[i].x), fmin(lo.y, rc[i].y));
            hi = rugo_v2(fmax(hi.x, rc[i].x), fmax(hi.y, rc[i].y));
        }
        for (int m = 0; m < 2; ++m)
            for (int j = J; j >= J0; --j) {
                snprintf(path, sizeof path, "%s/fig3_6_n%d_%s_level%d.svg", dir, n,
                         method_tag((rugo_box_method)m), j);
                svg_canvas svg;
                if (svg_open(&svg, path, lo, hi, 700.0) != 0) {
                    svg_ok = 0;
                    continue;
                }
                rugo_contour cj;
                rugo_pyramid_level(p, j, &cj);
                svg_contour(&svg, fine, 12, "#888888", 1.2, NULL);
                if (j < J) svg_contour(&svg, cj, 12, "#1b9e77", 1.0, "5,3");
                const char* colour = m == RUGO_BOXES_OF_BOXES ? "#d95f02" : "#7570b3";
                for (int k = 0; k < (1 << j); ++k)
                    svg_box(&svg, rugo_mobb_tree_node(trees[m], j, k), colour);
                char caption[200];
                snprintf(caption, sizeof caption,
                         "%d-point object, level %d, method (%s): total box area %.3f", n, j,
                         method_tag((rugo_box_method)m), rugo_mobb_tree_level_area(trees[m], j));
                svg_text(&svg, rugo_v2(lo.x, hi.y), caption, 13.0);
                svg_ok &= svg_close(&svg) == 0;
                ++svg_count;
            }

        /* The area table. */
        printf("\n%d-point object (levels %d..%d), total box area per level:\n", n, J, J0);
        printf("level boxes   area (a)       area (b)     (b)/(a) | thesis (a)  thesis (b)  (b)/(a)\n");
        fprintf(json, "%s\n {\"segments\": %d, \"levels\": [", oi ? "," : "", n);
        int b_smaller = 0, compared = 0;
        for (int j = J; j >= J0; --j) {
            double aa = rugo_mobb_tree_level_area(trees[RUGO_BOXES_OF_BOXES], j);
            double ab = rugo_mobb_tree_level_area(trees[RUGO_BOXES_MULTIRES], j);
            double ta = n == 256 ? thesis_value(THESIS_A, j) : NAN,
                   tb = n == 256 ? thesis_value(THESIS_B, j) : NAN;
            printf("%5d %5d %12.3f %14.3f %9.4f |", j, 1 << j, aa, ab, ab / aa);
            if (isnan(ta))
                printf("\n");
            else
                printf(" %10.3f %11.3f %8.4f\n", ta, tb, tb / ta);
            fprintf(csv, "%d,%d,%d,%.6f,%.6f,%.6f,", n, j, 1 << j, aa, ab, ab / aa);
            if (isnan(ta))
                fprintf(csv, ",,\n");
            else
                fprintf(csv, "%.3f,%.3f,%.6f\n", ta, tb, tb / ta);
            fprintf(json, "%s\n  {\"level\": %d, \"boxes\": %d, \"area_a\": %.6f, \"area_b\": %.6f",
                    j == J ? "" : ",", j, 1 << j, aa, ab);
            if (!isnan(ta)) fprintf(json, ", \"thesis_a\": %.3f, \"thesis_b\": %.3f", ta, tb);
            fprintf(json, "}");
            if (j < J) {
                ++compared;
                b_smaller += ab < aa;
            }
        }
        fprintf(json, "]}");
        printf("(b) smaller than (a) on %d of %d upper levels (thesis: 3 of 5, levels 7, 6 and 3)\n",
               b_smaller, compared);

        /* What holds for any object: equal leaves, and coarser levels need more area in total. */
        char name[160];
        snprintf(name, sizeof name, "%d-point object: both methods share the leaf level", n);
        sample_expect(name, rugo_mobb_tree_level_area(trees[0], J) == rugo_mobb_tree_level_area(trees[1], J));
        for (int m = 0; m < 2; ++m) {
            int grows = 1;
            for (int j = J0; j < J; ++j)
                grows &= rugo_mobb_tree_level_area(trees[m], j) > rugo_mobb_tree_level_area(trees[m], j + 1);
            snprintf(name, sizeof name,
                     "%d-point object, method (%s): total area grows towards coarse levels (as Fig. 4.6)", n,
                     method_tag((rugo_box_method)m));
            sample_expect(name, grows);
        }
        if (n == 256) {
            /* The thesis found (b) smaller at levels 7, 6 and 3 (and larger at 5 and 4). On this object
             * (b) is measured smaller at every upper level; asserted at the thesis' three levels, the
             * rest is reported in the table above. */
            static const int thesis_smaller[3] = {7, 6, 3};
            for (int i = 0; i < 3; ++i) {
                int j = thesis_smaller[i];
                snprintf(name, sizeof name,
                         "256-point object, level %d: area (b) < area (a), as in the thesis", j);
                sample_expect(name, rugo_mobb_tree_level_area(trees[RUGO_BOXES_MULTIRES], j) <
                                        rugo_mobb_tree_level_area(trees[RUGO_BOXES_OF_BOXES], j));
            }
        }
        for (int m = 0; m < 2; ++m)
            rugo_mobb_tree_destroy(trees[m]);
        rugo_tolerances_destroy(tol);
        rugo_pyramid_destroy(p);
        free(lam);
        free(pts);
    }
    fprintf(json, "\n]}\n");
    int files_ok = fclose(csv) == 0;
    files_ok &= fclose(json) == 0;
    sample_expect("wrote fig4_6_areas.csv and fig4_6_areas.json", files_ok);
    char name[80];
    snprintf(name, sizeof name, "wrote %d SVG pictures", svg_count);
    sample_expect(name, svg_ok && svg_count == 2 * (7 + 5));
    return sample_finish();
}
