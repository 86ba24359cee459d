/* Sweep and prune suite (SPEC 7): the pairs agree exactly with brute force on every update of random
 * moving scenes (no tolerance: the overlap test is exact comparisons, touching counts), the
 * coherence algorithm is really used (swaps reported), and bad input gets a status. */
#include "sim/internal.h" /* sweep and prune, the simulator's broad phase */
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

static int brute(const rugo_aabb* b, int n, rugo__pair* out) {
    int c = 0;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (b[i].lower.x <= b[j].upper.x && b[j].lower.x <= b[i].upper.x &&
                b[i].lower.y <= b[j].upper.y && b[j].lower.y <= b[i].upper.y) {
                out[c].a = i;
                out[c].b = j;
                ++c;
            }
    return c;
}

static void check_against_brute(rugo__sweep_prune* sap, const rugo_aabb* boxes, int n, rugo__pair* ref) {
    ck_assert_int_eq(rugo__sweep_prune_update(sap, boxes, n), RUGO_OK);
    int count = -1;
    const rugo__pair* pairs = rugo__sweep_prune_pairs(sap, &count);
    int rc = brute(boxes, n, ref);
    ck_assert_int_eq(count, rc);
    if (rc > 0)
        ck_assert_int_eq(memcmp(pairs, ref, (size_t)rc * sizeof *ref), 0); /* same pairs, same order */
}

static void random_box(test_rng* r, rugo_aabb* b, double world, double max_half) {
    double cx = test_rng_uniform(r, 0.0, world), cy = test_rng_uniform(r, 0.0, world);
    double hx = test_rng_uniform(r, 0.0, max_half), hy = test_rng_uniform(r, 0.0, max_half);
    b->lower = rugo_v2(cx - hx, cy - hy);
    b->upper = rugo_v2(cx + hx, cy + hy);
}

START_TEST(test_random_moving_scenes) {
    const int max_n = 400;
    rugo_aabb* boxes = malloc((size_t)max_n * sizeof *boxes);
    rugo__pair* ref = malloc((size_t)max_n * max_n / 2 * sizeof *ref);
    long total_pairs = 0, total_swaps = 0;
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        test_rng r = test_rng_seed(seed);
        rugo__sweep_prune* sap = NULL;
        ck_assert_int_eq(rugo__sweep_prune_create(NULL, &sap), RUGO_OK);
        int n = 150 + (int)(seed * 50);
        for (int i = 0; i < n; ++i)
            random_box(&r, &boxes[i], 100.0, 3.0);
        for (int step = 0; step < 120; ++step) {
            /* n changes now and then: the general algorithm restarts */
            if (step % 40 == 39) {
                int nn = n + (int)test_rng_uniform(&r, -60.0, 60.0);
                if (nn < 2) nn = 2;
                if (nn > max_n) nn = max_n;
                for (int i = n; i < nn; ++i)
                    random_box(&r, &boxes[i], 100.0, 3.0);
                n = nn;
            }
            for (int i = 0; i < n; ++i) {
                double u = test_rng_uniform(&r, 0.0, 1.0);
                double s = u < 0.02 ? 30.0 : 0.4; /* mostly small moves, sometimes a jump */
                double dx = test_rng_uniform(&r, -s, s), dy = test_rng_uniform(&r, -s, s);
                boxes[i].lower.x += dx;
                boxes[i].upper.x += dx;
                boxes[i].lower.y += dy;
                boxes[i].upper.y += dy;
                if (u > 0.99) { /* resize, keeping lower <= upper */
                    double g = test_rng_uniform(&r, -0.3, 0.3);
                    boxes[i].upper.x =
                        boxes[i].upper.x + g < boxes[i].lower.x ? boxes[i].lower.x : boxes[i].upper.x + g;
                }
            }
            /* exact touching cases: box 0 abuts box 1 on x */
            if (step % 10 == 5 && n > 1) {
                double w0 = boxes[1].upper.x - boxes[1].lower.x;
                boxes[0].lower = rugo_v2(boxes[1].upper.x, boxes[1].lower.y);
                boxes[0].upper = rugo_v2(boxes[1].upper.x + w0, boxes[1].upper.y);
            }
            check_against_brute(sap, boxes, n, ref);
            int c = 0;
            rugo__sweep_prune_pairs(sap, &c);
            total_pairs += c;
            total_swaps += rugo__sweep_prune_swaps(sap);
        }
        rugo__sweep_prune_destroy(sap);
    }
    ck_assert_int_gt(total_pairs, 1000); /* the scenes do have many overlaps */
    ck_assert_int_gt(total_swaps, 1000); /* and the coherence algorithm did the work */
    free(boxes);
    free(ref);
}
END_TEST

START_TEST(test_first_update_is_general) {
    rugo__sweep_prune* sap = NULL;
    ck_assert_int_eq(rugo__sweep_prune_create(NULL, &sap), RUGO_OK);
    rugo_aabb b[3];
    b[0].lower = rugo_v2(0, 0);
    b[0].upper = rugo_v2(1, 1);
    b[1].lower = rugo_v2(1, 1); /* touches box 0 at a corner: counts */
    b[1].upper = rugo_v2(2, 2);
    b[2].lower = rugo_v2(5, 5);
    b[2].upper = rugo_v2(5, 5); /* a point box */
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, 3), RUGO_OK);
    ck_assert_int_eq(rugo__sweep_prune_swaps(sap), 0);
    int c = 0;
    const rugo__pair* p = rugo__sweep_prune_pairs(sap, &c);
    ck_assert_int_eq(c, 1);
    ck_assert_int_eq(p[0].a, 0);
    ck_assert_int_eq(p[0].b, 1);
    /* move box 2 onto box 0: the coherence algorithm swaps end points */
    b[2].lower = rugo_v2(0.5, 0.5);
    b[2].upper = rugo_v2(0.5, 0.5);
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, 3), RUGO_OK);
    ck_assert_int_gt(rugo__sweep_prune_swaps(sap), 0);
    p = rugo__sweep_prune_pairs(sap, &c);
    ck_assert_int_eq(c, 2);
    ck_assert_int_eq(p[1].a, 0);
    ck_assert_int_eq(p[1].b, 2);
    /* empty scene */
    ck_assert_int_eq(rugo__sweep_prune_update(sap, NULL, 0), RUGO_OK);
    rugo__sweep_prune_pairs(sap, &c);
    ck_assert_int_eq(c, 0);
    rugo__sweep_prune_destroy(sap);
}
END_TEST

START_TEST(test_bad_input) {
    rugo__sweep_prune* sap = NULL;
    ck_assert_int_eq(rugo__sweep_prune_create(NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__sweep_prune_create(NULL, &sap), RUGO_OK);
    rugo_aabb b[2];
    b[0].lower = rugo_v2(0, 0);
    b[0].upper = rugo_v2(1, 1);
    b[1] = b[0];
    ck_assert_int_eq(rugo__sweep_prune_update(NULL, b, 2), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__sweep_prune_update(sap, NULL, 2), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, -1), RUGO_ERR_BAD_ARGUMENT);
    b[1].lower.x = NAN;
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, 2), RUGO_ERR_NOT_FINITE);
    b[1].lower.x = 2.0; /* lower > upper */
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, 2), RUGO_ERR_BAD_ARGUMENT);
    b[1].lower.x = 0.0;
    ck_assert_int_eq(rugo__sweep_prune_update(sap, b, 2), RUGO_OK);
    int c = -1;
    ck_assert_ptr_null(rugo__sweep_prune_pairs(NULL, &c));
    ck_assert_int_eq(c, 0);
    ck_assert_int_eq(rugo__sweep_prune_swaps(NULL), 0);
    rugo__sweep_prune_destroy(NULL);
    rugo__sweep_prune_destroy(sap);
}
END_TEST

static Suite* sweep_prune_suite(void) {
    Suite* s = suite_create("sweep_prune");
    TCase* t = tcase_create("core");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_random_moving_scenes);
    tcase_add_test(t, test_first_update_is_general);
    tcase_add_test(t, test_bad_input);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return test_run_suite(sweep_prune_suite()); }
