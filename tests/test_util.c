#include "test_util.h"

#include <string.h>

#include <stdlib.h>

test_rng test_rng_seed(uint64_t seed) {
    test_rng r;
    r.state = seed;
    return r;
}

uint64_t test_rng_next(test_rng* r) {
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double test_rng_uniform(test_rng* r, double lo, double hi) {
    double u = (double)(test_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
    return lo + (hi - lo) * u;
}

void test_random_star(test_rng* r, int n, rugo_vec2 centre, double radius, double bumpiness, rugo_vec2* out) {
    enum { H = 4 };
    double amp[H], phase[H];
    double total = 0.0;
    for (int h = 0; h < H; ++h) {
        amp[h] = test_rng_uniform(r, 0.0, 1.0);
        phase[h] = test_rng_uniform(r, 0.0, 6.283185307179586);
        total += amp[h];
    }
    for (int k = 0; k < n; ++k) {
        double th = 6.283185307179586 * k / n;
        double rad = 1.0;
        for (int h = 0; h < H; ++h)
            rad += bumpiness * amp[h] / total * sin((h + 2) * th + phase[h]);
        out[k].x = centre.x + radius * rad * cos(th);
        out[k].y = centre.y + radius * rad * sin(th);
    }
}

void test_random_points(test_rng* r, int n, double scale, rugo_vec2* out) {
    for (int k = 0; k < n; ++k) {
        out[k].x = test_rng_uniform(r, -scale, scale);
        out[k].y = test_rng_uniform(r, -scale, scale);
    }
}

double test_max_diff(const rugo_vec2* a, const rugo_vec2* b, int n) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) {
        double dx = fabs(a[i].x - b[i].x), dy = fabs(a[i].y - b[i].y);
        /* Written as !(d <= m) so that a NaN difference wins and fails the caller's check. */
        if (!(dx <= m)) m = dx;
        if (!(dy <= m)) m = dy;
    }
    return m;
}

double test_max_abs(const rugo_vec2* a, int n) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) {
        if (!(fabs(a[i].x) <= m)) m = fabs(a[i].x);
        if (!(fabs(a[i].y) <= m)) m = fabs(a[i].y);
    }
    return m;
}

int test_run_suite(Suite* s) {
    SRunner* sr = srunner_create(s);
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

void* test_budget_alloc(size_t n, void* ctx) {
    test_budget_ctx* b = (test_budget_ctx*)ctx;
    if (b->budget <= 0) return NULL;
    --b->budget;
    void* p = malloc(n);
    if (p != NULL) ++b->live;
    return p;
}

void test_budget_free(void* p, void* ctx) {
    test_budget_ctx* b = (test_budget_ctx*)ctx;
    if (p != NULL) --b->live;
    free(p);
}

rugo_contact_query test_exact_query(void) {
    rugo_contact_query q = rugo_default_contact_query();
    q.resolution = 0.0;
    q.contact_rule = RUGO_CONTACT_THESIS;
    return q;
}

static rugo_status unpack(rugo_status st, const rugo_contact_output* out, int* count,
                          rugo_contact_state* state, rugo_query_stats* stats) {
    if (count != NULL) *count = out->count;
    if (state != NULL) *state = out->state;
    if (stats != NULL) *stats = out->stats;
    return st;
}

rugo_status test_collide_shapes(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                const rugo_shape* b, rugo_transform xb, const rugo_contact_query* q,
                                rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                rugo_query_stats* stats) {
    rugo_contact_output out = rugo_contact_output_of(contacts, capacity);
    const rugo_contact_query exact = test_exact_query();
    return unpack(rugo_collide_shapes(a, xa, b, xb, q != NULL ? q : &exact, ctx, &out), &out, count, state,
                  stats);
}

static rugo_status collide_primitive(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                     const rugo_primitive* p, const rugo_contact_query* q,
                                     rugo_contact* contacts, int capacity, int* count,
                                     rugo_contact_state* state, rugo_query_stats* stats) {
    rugo_contact_output out = rugo_contact_output_of(contacts, capacity);
    const rugo_contact_query exact = test_exact_query();
    return unpack(
        rugo_collide_primitive(a, xa, p, rugo_identity_transform(), q != NULL ? q : &exact, ctx, &out), &out,
        count, state, stats);
}

rugo_status test_collide_circle(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                rugo_vec2 center, double radius, const rugo_contact_query* q,
                                rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                rugo_query_stats* stats) {
    const rugo_primitive p = rugo_make_circle(center, radius);
    return collide_primitive(ctx, a, xa, &p, q, contacts, capacity, count, state, stats);
}

rugo_status test_collide_segment(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                 rugo_vec2 p1, rugo_vec2 p2, double radius, const rugo_contact_query* q,
                                 rugo_contact* contacts, int capacity, int* count, rugo_contact_state* state,
                                 rugo_query_stats* stats) {
    const rugo_primitive p = rugo_make_capsule(p1, p2, radius);
    return collide_primitive(ctx, a, xa, &p, q, contacts, capacity, count, state, stats);
}

rugo_status test_collide_polygon(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                 const rugo_vec2* vertices, int vertex_count, double radius,
                                 const rugo_contact_query* q, rugo_contact* contacts, int capacity,
                                 int* count, rugo_contact_state* state, rugo_query_stats* stats) {
    /* built field by field (not rugo_make_polygon) so that the query itself checks bad polygons */
    rugo_primitive p;
    memset(&p, 0, sizeof p);
    p.count = vertex_count;
    p.radius = radius;
    for (int i = 0; i < vertex_count && i < RUGO_PRIMITIVE_MAX_POINTS && vertices != NULL; ++i)
        p.points[i] = vertices[i];
    if (vertices == NULL) p.count = 0;
    return collide_primitive(ctx, a, xa, &p, q, contacts, capacity, count, state, stats);
}
