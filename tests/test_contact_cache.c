/* The contact cache (rugo_contact_output.cache): an answer is given back while the shapes have moved
 * relative to each other by at most a quarter of the resolution, moved with them and within the
 * resolution of a fresh search; past that, or for another query, the query searches and keeps the new
 * answer; a cache of another pair or context is refused; no query allocates for it. */
#include "test_util.h"

#include "shape/internal.h" /* rugo__shape_fingerprint */

#include <stdlib.h>
#include <string.h>

enum { CAP = 32 };

static rugo_shape* rough_star(uint64_t seed, double band) {
    rugo_vec2 p[64];
    double tol[64];
    test_rng r = test_rng_seed(seed);
    test_random_star(&r, 64, rugo_v2(0.0, 0.0), 1.0, 0.3, p);
    for (int i = 0; i < 64; ++i)
        tol[i] = band * test_rng_uniform(&r, 0.2, 1.0);
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p;
    d.count = 64;
    d.tolerances = tol;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&d, &s, NULL), RUGO_OK);
    return s;
}

/* Two contacts field by field, bit for bit (memcmp would also compare their padding). */
static int same_contact(const rugo_contact* x, const rugo_contact* y) {
    const double a[] = {x->point_a.x,   x->point_a.y,  x->point_b.x,  x->point_b.y, x->normal.x,
                        x->normal.y,    x->separation, x->t_a,        x->t_b,       x->tolerance_a,
                        x->tolerance_b, x->friction,   x->restitution};
    const double b[] = {y->point_a.x,   y->point_a.y,  y->point_b.x,  y->point_b.y, y->normal.x,
                        y->normal.y,    y->separation, y->t_a,        y->t_b,       y->tolerance_a,
                        y->tolerance_b, y->friction,   y->restitution};
    return memcmp(a, b, sizeof a) == 0 && x->segment_a == y->segment_a && x->segment_b == y->segment_b &&
           x->level_a == y->level_a && x->level_b == y->level_b && x->region == y->region && x->id == y->id;
}

static rugo_transform pose(double x, double y, double angle) {
    rugo_transform t;
    t.p = rugo_v2(x, y);
    t.q = rugo_rot_from_angle(angle);
    return t;
}

/* Moves both frames by the same rigid motion (nothing moves relative to the other). */
static rugo_transform compose(rugo_transform m, rugo_transform x) {
    rugo_transform r;
    r.p = rugo_transform_point(m, x.p);
    r.q.c = m.q.c * x.q.c - m.q.s * x.q.s;
    r.q.s = m.q.s * x.q.c + m.q.c * x.q.s;
    return r;
}

static rugo_status query(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                         const rugo_shape* b, rugo_transform xb, const rugo_contact_query* q,
                         rugo_contact_cache* cache, rugo_contact* c, int capacity, rugo_contact_output* out) {
    *out = rugo_contact_output_of(c, capacity);
    out->cache = cache;
    return rugo_collide_shapes(a, xa, b, xb, q, ctx, out);
}

typedef struct fixture {
    rugo_shape *a, *b;
    rugo_collide_context* ctx;
    rugo_contact_query q;
    rugo_transform xa, xb; /* a pose with contacts */
} fixture;

static fixture setup(double resolution) {
    fixture f;
    f.a = rough_star(11, 0.02);
    f.b = rough_star(12, 0.02);
    ck_assert_int_eq(rugo_collide_context_create(NULL, &f.ctx), RUGO_OK);
    f.q = rugo_default_contact_query();
    f.q.resolution = resolution;
    f.xa = pose(0.0, 0.0, 0.3);
    /* B slides towards A until the pair has contacts */
    rugo_contact c[CAP];
    rugo_contact_output o;
    for (double x = 2.6; x > 1.0; x -= 0.01) {
        f.xb = pose(x, 0.15, -0.7);
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, NULL, c, CAP, &o), RUGO_OK);
        if (o.count > 0) return f;
    }
    ck_abort_msg("no pose with contacts");
    return f;
}

static void teardown(fixture* f) {
    rugo_collide_context_destroy(f->ctx);
    rugo_shape_destroy(f->a);
    rugo_shape_destroy(f->b);
}

/* Same state; every contact of either answer has one in the other near its point on A whose separation
 * is within delta of its own. */
static void assert_within(const rugo_contact_output* fresh, const rugo_contact_output* reused, double delta) {
    ck_assert_int_eq(reused->state, fresh->state);
    for (int pass = 0; pass < 2; ++pass) {
        const rugo_contact_output* x = pass == 0 ? fresh : reused;
        const rugo_contact_output* y = pass == 0 ? reused : fresh;
        for (int i = 0; i < x->count; ++i) {
            double best = INFINITY, best_point = INFINITY;
            for (int j = 0; j < y->count; ++j) {
                const double ds = fabs(x->contacts[i].separation - y->contacts[j].separation);
                const double dp = hypot(x->contacts[i].point_a.x - y->contacts[j].point_a.x,
                                        x->contacts[i].point_a.y - y->contacts[j].point_a.y);
                if (dp < best_point) {
                    best_point = dp;
                    best = ds;
                }
            }
            ck_assert_msg(best <= delta, "separation %g off by %g > delta %g", x->contacts[i].separation,
                          best, delta);
            ck_assert_msg(best_point <= 0.2, "no contact near a point (%g away)", best_point);
        }
    }
}

START_TEST(test_same_poses_give_the_same_bits) {
    fixture f = setup(1e-3);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, CAP, &cache), RUGO_OK);
    rugo_contact c1[CAP], c2[CAP];
    rugo_contact_output o1, o2;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c1, CAP, &o1), RUGO_OK);
    ck_assert_int_eq(o1.stats.reused, 0);
    ck_assert_int_gt(o1.count, 0);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c2, CAP, &o2), RUGO_OK);
    ck_assert_int_eq(o2.stats.reused, 1);
    ck_assert_int_eq(o2.stats.box_tests, 0);
    ck_assert_int_eq(o2.count, o1.count);
    ck_assert_int_eq(o2.state, o1.state);
    for (int i = 0; i < o1.count; ++i)
        ck_assert(same_contact(&c1[i], &c2[i]));
    /* capacity 0 asks for the state: the cached one */
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, NULL, 0, &o2), RUGO_OK);
    ck_assert_int_eq(o2.stats.reused, 1);
    ck_assert_int_eq(o2.state, o1.state);
    ck_assert_int_eq(o2.count, 0);
    /* a smaller room: the first contacts of the answer */
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c2, 1, &o2), RUGO_OK);
    ck_assert_int_eq(o2.count, 1);
    ck_assert_int_eq(o2.stats.contacts_found, o1.count);
    ck_assert(same_contact(&c1[0], &c2[0]));
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

/* Both bodies carried by one rigid motion: nothing moved relative to the other, so the answer is the
 * cached one moved with them, equal to a fresh search's to round-off. */
START_TEST(test_common_motion_moves_the_answer) {
    fixture f = setup(1e-3);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, CAP, &cache), RUGO_OK);
    rugo_contact c1[CAP], c2[CAP];
    rugo_contact_output o1, o2;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c1, CAP, &o1), RUGO_OK);
    const rugo_transform m = pose(40.0, -7.0, 2.1);
    const rugo_transform xa = compose(m, f.xa), xb = compose(m, f.xb);
    ck_assert_int_eq(query(f.ctx, f.a, xa, f.b, xb, &f.q, cache, c2, CAP, &o2), RUGO_OK);
    ck_assert_int_eq(o2.stats.reused, 1);
    rugo_contact c3[CAP];
    rugo_contact_output o3;
    ck_assert_int_eq(query(f.ctx, f.a, xa, f.b, xb, &f.q, NULL, c3, CAP, &o3), RUGO_OK);
    ck_assert_int_eq(o3.count, o2.count);
    for (int i = 0; i < o2.count; ++i) {
        ck_assert_double_eq_tol(c2[i].point_a.x, c3[i].point_a.x, 1e-9);
        ck_assert_double_eq_tol(c2[i].point_a.y, c3[i].point_a.y, 1e-9);
        ck_assert_double_eq_tol(c2[i].point_b.x, c3[i].point_b.x, 1e-9);
        ck_assert_double_eq_tol(c2[i].point_b.y, c3[i].point_b.y, 1e-9);
        ck_assert_double_eq_tol(c2[i].normal.x, c3[i].normal.x, 1e-9);
        ck_assert_double_eq_tol(c2[i].normal.y, c3[i].normal.y, 1e-9);
        ck_assert_double_eq_tol(c2[i].separation, c3[i].separation, 1e-12);
    }
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

/* B moves relative to A: within a quarter of δ the answer is reused and within δ of a fresh search;
 * past it the query searches (and the next small step from there is reused again). */
START_TEST(test_relative_motion_within_a_quarter_of_the_resolution) {
    const double delta = 2e-3;
    fixture f = setup(delta);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, CAP, &cache), RUGO_OK);
    rugo_contact c1[CAP], c2[CAP];
    rugo_contact_output o1, o2;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c1, CAP, &o1), RUGO_OK);
    int reused = 0, searched = 0;
    for (int k = 1; k <= 40; ++k) {
        /* steps of delta/40 along x: reused while the total stays within delta/4 (minus the rotation's
         * share, none here) */
        rugo_transform xb = f.xb;
        xb.p.x -= k * delta / 40.0;
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &f.q, cache, c2, CAP, &o2), RUGO_OK);
        rugo_contact c3[CAP];
        rugo_contact_output o3;
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &f.q, NULL, c3, CAP, &o3), RUGO_OK);
        if (o2.stats.reused) {
            ++reused;
            assert_within(&o3, &o2, delta);
        } else {
            ++searched;
            ck_assert_int_eq(o2.count, o3.count);
        }
    }
    /* moves of 1/40 .. 10/40 of delta since the search: reused; the 11th is past a quarter, searched
     * and kept; the cycle repeats from there (10 reuses per search) */
    ck_assert_int_eq(searched, 3);
    ck_assert_int_eq(reused, 37);
    /* a turn: |Δq| reach counts */
    rugo_transform xb = f.xb;
    xb.q = rugo_rot_from_angle(-0.7 + 0.1);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &f.q, cache, c2, CAP, &o2), RUGO_OK);
    ck_assert_int_eq(o2.stats.reused, 0);
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

START_TEST(test_resolution_zero_reuses_only_the_same_poses) {
    fixture f = setup(0.0);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, CAP, &cache), RUGO_OK);
    rugo_contact c[CAP];
    rugo_contact_output o;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 1);
    rugo_transform xb = f.xb;
    xb.p.x = nextafter(xb.p.x, 0.0);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 0);
    /* another query (here its margin) searches: no error */
    rugo_contact_query q2 = f.q;
    q2.margin = 0.01;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &q2, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 0);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &q2, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 1);
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

/* An answer larger than the cache's room, or cut short by the caller's, is not kept. */
START_TEST(test_partial_answers_are_not_kept) {
    fixture f = setup(1e-3);
    rugo_contact c[CAP];
    rugo_contact_output o;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, NULL, c, CAP, &o), RUGO_OK);
    const int n = o.count;
    ck_assert_int_gt(n, 0);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, n - 1, &cache), RUGO_OK);
    for (int k = 0; k < 2; ++k) {
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
        ck_assert_int_eq(o.stats.reused, 0);
    }
    ck_assert_int_eq(rugo_contact_cache_reserve(cache, n), RUGO_OK);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 0);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 1);
    ck_assert_int_eq(o.count, n);
    /* a search cut short by the caller's room (or asking for the state alone) is not kept */
    for (int room = 0; room<n; room += n - 1> 0 ? n - 1 : 1) {
        rugo_contact_cache_clear(cache);
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, room ? c : NULL, room, &o), RUGO_OK);
        ck_assert_int_eq(o.stats.reused, 0);
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
        ck_assert_int_eq(o.stats.reused, 0);
    }
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

START_TEST(test_another_pair_or_context_is_refused) {
    fixture f = setup(1e-3);
    rugo_contact_cache* cache = NULL;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, CAP, &cache), RUGO_OK);
    rugo_contact c[CAP];
    rugo_contact_output o;
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    /* the pair swapped, another shape, another context */
    ck_assert_int_eq(query(f.ctx, f.b, f.xb, f.a, f.xa, &f.q, cache, c, CAP, &o), RUGO_ERR_CACHE_MISMATCH);
    ck_assert_int_eq(o.count, 0);
    rugo_shape* other = rough_star(13, 0.02);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, other, f.xb, &f.q, cache, c, CAP, &o), RUGO_ERR_CACHE_MISMATCH);
    rugo_collide_context* ctx2 = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx2), RUGO_OK);
    ck_assert_int_eq(query(ctx2, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_ERR_CACHE_MISMATCH);
    /* the refusals left the cache as it was */
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 1);
    /* B destroyed and another shape built (perhaps at the same address): refused either way */
    rugo_shape_destroy(f.b);
    f.b = rough_star(14, 0.03);
    ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, f.xb, &f.q, cache, c, CAP, &o), RUGO_ERR_CACHE_MISMATCH);
    /* cleared: any pair */
    rugo_contact_cache_clear(cache);
    ck_assert_int_eq(query(ctx2, f.a, f.xa, other, f.xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    ck_assert_int_eq(o.stats.reused, 0);
    rugo_collide_context_destroy(ctx2);
    rugo_shape_destroy(other);
    rugo_contact_cache_destroy(cache);
    teardown(&f);
}
END_TEST

START_TEST(test_fingerprints) {
    rugo_shape* a = rough_star(21, 0.02);
    rugo_shape* b = rough_star(21, 0.02);
    rugo_shape* c = rough_star(21, 0.03); /* same outline, other bands */
    ck_assert(rugo__shape_fingerprint(a) == rugo__shape_fingerprint(b));
    ck_assert(rugo__shape_fingerprint(a) != rugo__shape_fingerprint(c));
    ck_assert(rugo__shape_fingerprint(NULL) == 0);
    rugo_shape_destroy(a);
    rugo_shape_destroy(b);
    rugo_shape_destroy(c);
}
END_TEST

START_TEST(test_bad_input_and_no_allocation_per_query) {
    rugo_contact_cache* cache = (rugo_contact_cache*)&cache;
    ck_assert_int_eq(rugo_contact_cache_create(NULL, 4, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_contact_cache_create(NULL, -1, &cache), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_null(cache);
    ck_assert_int_eq(rugo_contact_cache_create(NULL, RUGO_MAX_CONTROL_POINTS + 1, &cache),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_contact_cache_reserve(NULL, 4), RUGO_ERR_NULL_ARGUMENT);
    rugo_contact_cache_clear(NULL);
    rugo_contact_cache_destroy(NULL);
    /* out of memory: create fails cleanly; then queries never allocate through the cache */
    test_budget_ctx bc = {0, 0};
    rugo_allocator al = {test_budget_alloc, test_budget_free, &bc};
    ck_assert_int_eq(rugo_contact_cache_create(&al, 8, &cache), RUGO_ERR_OUT_OF_MEMORY);
    ck_assert_int_eq(bc.live, 0);
    bc.budget = 2;
    ck_assert_int_eq(rugo_contact_cache_create(&al, 8, &cache), RUGO_OK);
    ck_assert_int_eq(rugo_contact_cache_reserve(cache, 16), RUGO_ERR_OUT_OF_MEMORY);
    ck_assert_int_eq(rugo_contact_cache_reserve(cache, 8), RUGO_OK);
    ck_assert_int_eq(rugo_contact_cache_reserve(cache, -2), RUGO_ERR_BAD_ARGUMENT);
    fixture f = setup(1e-3);
    rugo_contact c[CAP];
    rugo_contact_output o;
    for (int k = 0; k < 3; ++k) {
        rugo_transform xb = f.xb;
        xb.p.x -= 0.01 * k;
        ck_assert_int_eq(query(f.ctx, f.a, f.xa, f.b, xb, &f.q, cache, c, CAP, &o), RUGO_OK);
    }
    ck_assert_int_eq(bc.live, 2);
    rugo_contact_cache_destroy(cache);
    ck_assert_int_eq(bc.live, 0);
    teardown(&f);
}
END_TEST

int main(void) {
    Suite* s = suite_create("contact_cache");
    TCase* tc = tcase_create("cache");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_same_poses_give_the_same_bits);
    tcase_add_test(tc, test_common_motion_moves_the_answer);
    tcase_add_test(tc, test_relative_motion_within_a_quarter_of_the_resolution);
    tcase_add_test(tc, test_resolution_zero_reuses_only_the_same_poses);
    tcase_add_test(tc, test_partial_answers_are_not_kept);
    tcase_add_test(tc, test_another_pair_or_context_is_refused);
    tcase_add_test(tc, test_fingerprints);
    tcase_add_test(tc, test_bad_input_and_no_allocation_per_query);
    suite_add_tcase(s, tc);
    return test_run_suite(s);
}
