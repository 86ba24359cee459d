/* Shared helpers for the Check suites: a seeded test RNG and random test contours.
 * (The library's own documented RNG arrives with the roughness module; tests keep theirs so that
 * test inputs do not change when the library's generator evolves.) */
#ifndef RUGO_TEST_UTIL_H
#define RUGO_TEST_UTIL_H

#include "rugo/rugo.h"

#include <check.h>
#include <math.h>
#include <stdint.h>

/* splitmix64: tiny, well-mixed, deterministic. */
typedef struct test_rng {
    uint64_t state;
} test_rng;

test_rng test_rng_seed(uint64_t seed);
uint64_t test_rng_next(test_rng* r);
double test_rng_uniform(test_rng* r, double lo, double hi); /* [lo, hi) */

/* A random star-shaped control polygon of n points around `centre` with mean radius `radius`:
 * radii 1 + a few random low harmonics of total amplitude <= `bumpiness` (< 0.5 keeps the curve
 * simple). Counter-clockwise. */
void test_random_star(test_rng* r, int n, rugo_vec2 centre, double radius, double bumpiness, rugo_vec2* out);

/* Fully random periodic 2-D data (not a valid outline; for transform tests). */
void test_random_points(test_rng* r, int n, double scale, rugo_vec2* out);

/* Largest |a_i - b_i| over both coordinates, and the largest |a_i|. */
double test_max_diff(const rugo_vec2* a, const rugo_vec2* b, int n);
double test_max_abs(const rugo_vec2* a, int n);

/* Check assertion that |a - b| <= tol, printing both values on failure. */
#define ck_assert_near(a, b, tol)                                                                            \
    do {                                                                                                     \
        double ck_a_ = (a), ck_b_ = (b), ck_t_ = (tol);                                                      \
        ck_assert_msg(fabs(ck_a_ - ck_b_) <= ck_t_, "%s = %.17g, %s = %.17g, |diff| = %.3g > %.3g", #a,      \
                      ck_a_, #b, ck_b_, fabs(ck_a_ - ck_b_), ck_t_);                                         \
    } while (0)

/* An allocator (ctx: a test_budget_ctx) that fails once `budget` allocations have been made and
 * counts the blocks still live: for out-of-memory paths and leak checks. */
typedef struct test_budget_ctx {
    long budget;
    long live;
} test_budget_ctx;
void* test_budget_alloc(size_t n, void* ctx);
void test_budget_free(void* p, void* ctx);

/* rugo_default_contact_query() at resolution 0 with the thesis' rule (minima of the distance): the
 * round-off answers the accuracy tests pin against their references. */
rugo_contact_query test_exact_query(void);

/* The contact queries as the suites assert on them (a NULL query: test_exact_query()): the caller's array and
 * room in, the count, state and statistics out (stats may be NULL), through rugo_contact_output. The
 * primitives as rugo_collide_primitive takes them, in world coordinates. */
rugo_status test_collide_shapes(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                const rugo_shape* b, rugo_transform xb, const rugo_contact_query* q,
                                rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                rugo_query_stats* stats);
rugo_status test_collide_circle(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                rugo_vec2 center, double radius, const rugo_contact_query* q,
                                rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                rugo_query_stats* stats);
rugo_status test_collide_segment(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                 rugo_vec2 p1, rugo_vec2 p2, double radius, const rugo_contact_query* q,
                                 rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                 rugo_query_stats* stats);
rugo_status test_collide_polygon(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                 const rugo_vec2* vertices, int vertex_count, double radius,
                                 const rugo_contact_query* q, rugo_contact* contacts, int capacity,
                                 int* count, rugo_contact_state* state, rugo_query_stats* stats);

/* Runs one suite and returns the process exit code. */
int test_run_suite(Suite* s);

#endif
