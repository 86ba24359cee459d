/* The contact cache: one pair's last answer, kept by the caller from step to step, and the rule by
 * which a query may give it back instead of searching.
 *
 * The rule. A query certified to δ spends at most three quarters of δ (collide_internal.h: a quarter
 * on coarser levels, half in the narrow phase). If B has moved relative to A by at most the last
 * quarter since the cached search (every point of B, bands included, by at most m), every band-adjusted
 * distance has changed by at most m: each cached separation is still within δ of the truth, and a
 * contact now deeper than its threshold by more than δ was deeper by more than 3δ/4 at the cached poses,
 * where the search could not miss it. The motion is measured from the poses of the search, never from
 * the last reuse, so reuses do not add up. At δ = 0 only the very same pair of poses is reused.
 *
 * Separate from the queries because it outlives them, as the context does. */
#include "query/collide_internal.h"

#include "shape/internal.h"

#include <math.h>
#include <string.h>

struct rugo_contact_cache {
    rugo_allocator al;
    rugo_contact* contacts;
    int capacity;
    /* the answer it holds (valid) and what it was asked */
    int valid;
    const rugo_shape* a;
    const rugo_shape* b;
    uint64_t fingerprint_a, fingerprint_b;
    const rugo_collide_context* ctx;
    rugo_contact_query query;
    rugo_transform xa, xb;
    rugo_real reach_b; /* farthest point of B's level and band from B's origin */
    int count;
    rugo_contact_state state;
};

static int capacity_ok(int capacity) { return capacity >= 0 && capacity <= RUGO_MAX_CONTROL_POINTS; }

rugo_status rugo_contact_cache_create(const rugo_allocator* allocator, int capacity,
                                      rugo_contact_cache** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (!capacity_ok(capacity)) return RUGO_ERR_BAD_ARGUMENT;
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_contact_cache* c = (rugo_contact_cache*)rugo__alloc_array(&al, 1, sizeof *c);
    if (c == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(c, 0, sizeof *c);
    c->al = al;
    rugo_status st = rugo_contact_cache_reserve(c, capacity);
    if (st != RUGO_OK) {
        rugo_contact_cache_destroy(c);
        return st;
    }
    *out = c;
    return RUGO_OK;
}

rugo_status rugo_contact_cache_reserve(rugo_contact_cache* c, int capacity) {
    if (c == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!capacity_ok(capacity)) return RUGO_ERR_BAD_ARGUMENT;
    if (capacity <= c->capacity) return RUGO_OK;
    rugo_contact* grown = (rugo_contact*)rugo__alloc_array(&c->al, (size_t)capacity, sizeof *grown);
    if (grown == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    if (c->count > 0) memcpy(grown, c->contacts, (size_t)c->count * sizeof *grown);
    rugo__free(&c->al, c->contacts);
    c->contacts = grown;
    c->capacity = capacity;
    return RUGO_OK;
}

void rugo_contact_cache_clear(rugo_contact_cache* c) {
    if (c == NULL) return;
    c->valid = 0;
    c->count = 0;
}

void rugo_contact_cache_destroy(rugo_contact_cache* c) {
    if (c == NULL) return;
    rugo_allocator al = c->al;
    rugo__free(&al, c->contacts);
    rugo__free(&al, c);
}

rugo_status rugo__cache_check(const rugo_contact_cache* c, const rugo_shape* a, const rugo_shape* b,
                              const rugo_collide_context* ctx) {
    if (!c->valid) return RUGO_OK;
    if (c->a != a || c->b != b || c->ctx != ctx || c->fingerprint_a != rugo__shape_fingerprint(a) ||
        c->fingerprint_b != rugo__shape_fingerprint(b))
        return RUGO_ERR_CACHE_MISMATCH;
    return RUGO_OK;
}

static int same_query(const rugo_contact_query* p, const rugo_contact_query* q) {
    return p->resolution == q->resolution && p->contact_rule == q->contact_rule && p->lod == q->lod &&
           p->lod_error_budget == q->lod_error_budget && p->tolerance == q->tolerance &&
           p->friction_mix == q->friction_mix && p->restitution_mix == q->restitution_mix &&
           p->margin == q->margin;
}

static int same_transform(rugo_transform x, rugo_transform y) {
    return x.p.x == y.p.x && x.p.y == y.p.y && x.q.c == y.q.c && x.q.s == y.q.s;
}

/* B's frame -> A's frame. */
static rugo_transform relative(rugo_transform xa, rugo_transform xb) {
    rugo_transform r;
    r.p = rugo_inv_rotate(xa.q, rugo_v2_sub(xb.p, xa.p));
    r.q.c = xa.q.c * xb.q.c + xa.q.s * xb.q.s;
    r.q.s = xa.q.c * xb.q.s - xa.q.s * xb.q.c;
    return r;
}

/* A point of frame x_old, carried to where frame x_new puts it. */
static rugo_vec2 carry(rugo_transform x_old, rugo_transform x_new, rugo_vec2 p) {
    return rugo_transform_point(x_new, rugo_inv_transform_point(x_old, p));
}

int rugo__cache_reuse(const rugo_contact_cache* c, rugo_transform xa, rugo_transform xb,
                      const rugo_contact_query* q, rugo_real delta, rugo_contact_output* out) {
    if (!c->valid || !same_query(&c->query, q)) return 0;
    const int unchanged = same_transform(c->xa, xa) && same_transform(c->xb, xb);
    if (!unchanged) {
        if (!(delta > 0.0)) return 0;
        /* every point of B moves in A's frame by at most |Δp| + |Δq| reach (|Δq|: the rotation's
         * change as a matrix norm, 2 sin(Δθ/2)) */
        const rugo_transform r0 = relative(c->xa, c->xb), r1 = relative(xa, xb);
        const rugo_real dp = hypot(r1.p.x - r0.p.x, r1.p.y - r0.p.y);
        const rugo_real dq = hypot(r1.q.c - r0.q.c, r1.q.s - r0.q.s);
        if (!(dp + dq * c->reach_b <= RESOLUTION_MOTION_SHARE * delta)) return 0;
    }
    const int n = c->count < out->capacity ? c->count : out->capacity;
    for (int i = 0; i < n; ++i) {
        rugo_contact k = c->contacts[i];
        if (!unchanged) {
            k.point_a = carry(c->xa, xa, k.point_a);
            k.point_b = carry(c->xb, xb, k.point_b);
            k.normal = rugo_rotate(xa.q, rugo_inv_rotate(c->xa.q, k.normal));
        }
        out->contacts[i] = k;
    }
    out->count = n;
    out->state = c->state;
    out->stats.contacts_found = c->count;
    out->stats.reused = 1;
    return 1;
}

void rugo__cache_store(rugo_contact_cache* c, const rugo_shape* a, rugo_transform xa, const rugo_shape* b,
                       rugo_transform xb, const rugo_contact_query* q, const rugo_collide_context* ctx,
                       const query_side* B, rugo_real override, const rugo_contact_output* out) {
    c->valid = 0;
    c->count = 0;
    /* only a whole answer: one cut short by the caller's room or the cache's is not kept */
    if (out->count != out->stats.contacts_found || out->count > c->capacity) return;
    if (out->capacity == 0) return; /* a search for the state alone may stop early */
    rugo_real reach2 = 0.0, band = override;
    for (int i = 0; i < B->n; ++i) {
        const rugo_vec2 p = B->curve.points[i];
        const rugo_real r2 = p.x * p.x + p.y * p.y;
        if (r2 > reach2) reach2 = r2;
        if (override < 0.0 && B->band[i] > band) band = B->band[i];
    }
    /* the control points' hull holds the curve; a point of the band is at most λ from it (a bound a
     * few ulps loose does not matter: the motion allowed is a share of δ) */
    c->reach_b = sqrt(reach2) + (band > 0.0 ? band : 0.0);
    if (out->count > 0) memcpy(c->contacts, out->contacts, (size_t)out->count * sizeof *c->contacts);
    c->count = out->count;
    c->state = out->state;
    c->a = a;
    c->b = b;
    c->fingerprint_a = rugo__shape_fingerprint(a);
    c->fingerprint_b = rugo__shape_fingerprint(b);
    c->ctx = ctx;
    c->query = *q;
    c->xa = xa;
    c->xb = xb;
    c->valid = 1;
}
