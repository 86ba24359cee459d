/* librugo — sweep and prune on axis-aligned boxes (SPEC 7, thesis 6.2.1).
 *
 * Each axis keeps the 2n end points sorted by (value, begin before end, id): with begins first at equal
 * values, two boxes overlap on an axis iff each one's begin precedes the other's end in that order, so
 * touching boxes overlap, as the header promises.
 *
 * General algorithm (first update, or n changed): sort both axes, sweep x with an active list and test y.
 * Coherence algorithm (later updates): refresh the values and insertion-sort each axis. Insertion sort
 * swaps exactly the end-point pairs whose order changed, so a pair's overlap can only change at such a
 * swap: a begin moving left past another box's end may start an overlap (the pair is added if the two
 * boxes now overlap on both axes), an end moving left past another box's begin ends one (removed). A
 * pair whose order did not change on either axis keeps its state, so the table ends up exact.
 * Pairs live in a hash table of h buckets, bucket (s + t) mod h, chained through a pool with a free
 * list; nothing allocates unless the pool or n grows. */
#include "core/internal.h"
#include "sim/internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct endpoint {
    rugo_real value;
    int id;
    int end; /* 0 begin (lower), 1 end (upper) */
} endpoint;

typedef struct pair_entry {
    int a, b;
    int next; /* next in the bucket's chain or the free list; -1 ends */
} pair_entry;

struct rugo_sweep_prune {
    rugo_allocator allocator;
    int n;        /* boxes of the last successful update */
    int valid;    /* 0: the next update runs the general algorithm */
    int capacity; /* boxes the arrays hold */
    endpoint* axis[2];
    int* active;
    int* active_pos;
    int h;
    int* buckets;
    pair_entry* pool;
    int pool_capacity, pool_used, free_head, live;
    rugo_pair* out;
    int out_capacity, out_count;
    long swaps;
};

static int endpoint_less(const endpoint* x, const endpoint* y) {
    if (x->value != y->value) return x->value < y->value;
    if (x->end != y->end) return x->end < y->end;
    return x->id < y->id;
}

static int endpoint_cmp(const void* p, const void* q) {
    const endpoint* x = (const endpoint*)p;
    const endpoint* y = (const endpoint*)q;
    if (endpoint_less(x, y)) return -1;
    if (endpoint_less(y, x)) return 1;
    return 0;
}

static int pair_cmp(const void* p, const void* q) {
    const rugo_pair* x = (const rugo_pair*)p;
    const rugo_pair* y = (const rugo_pair*)q;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return 0;
}

static int overlap_axis(const rugo_aabb* p, const rugo_aabb* q, int axis) {
    if (axis == 0) return p->lower.x <= q->upper.x && q->lower.x <= p->upper.x;
    return p->lower.y <= q->upper.y && q->lower.y <= p->upper.y;
}

rugo_status rugo_sweep_prune_create(const rugo_allocator* allocator, rugo_sweep_prune** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    rugo_allocator a = rugo__allocator_or_default(allocator);
    rugo_sweep_prune* sap = (rugo_sweep_prune*)rugo__alloc_array(&a, 1, sizeof *sap);
    if (sap == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(sap, 0, sizeof *sap);
    sap->allocator = a;
    sap->free_head = -1;
    *out = sap;
    return RUGO_OK;
}

void rugo_sweep_prune_destroy(rugo_sweep_prune* sap) {
    if (sap == NULL) return;
    rugo_allocator a = sap->allocator;
    rugo__free(&a, sap->axis[0]);
    rugo__free(&a, sap->axis[1]);
    rugo__free(&a, sap->active);
    rugo__free(&a, sap->active_pos);
    rugo__free(&a, sap->buckets);
    rugo__free(&a, sap->pool);
    rugo__free(&a, sap->out);
    rugo__free(&a, sap);
}

static void table_clear(rugo_sweep_prune* sap) {
    for (int i = 0; i < sap->h; ++i) sap->buckets[i] = -1;
    sap->pool_used = 0;
    sap->free_head = -1;
    sap->live = 0;
}

static int bucket_of(const rugo_sweep_prune* sap, int a, int b) {
    return (int)(((unsigned)a + (unsigned)b) % (unsigned)sap->h);
}

/* Adds (a, b), a < b, if absent. 0 on out of memory. */
static int table_add(rugo_sweep_prune* sap, int a, int b) {
    int bk = bucket_of(sap, a, b);
    for (int e = sap->buckets[bk]; e >= 0; e = sap->pool[e].next)
        if (sap->pool[e].a == a && sap->pool[e].b == b) return 1;
    int slot;
    if (sap->free_head >= 0) {
        slot = sap->free_head;
        sap->free_head = sap->pool[slot].next;
    } else {
        if (sap->pool_used == sap->pool_capacity) {
            int cap = sap->pool_capacity < 64 ? 64 : sap->pool_capacity;
            if (cap > (1 << 29)) return 0;
            cap *= 2;
            pair_entry* p = (pair_entry*)rugo__alloc_array(&sap->allocator, (size_t)cap, sizeof *p);
            if (p == NULL) return 0;
            if (sap->pool_used > 0) memcpy(p, sap->pool, (size_t)sap->pool_used * sizeof *p);
            rugo__free(&sap->allocator, sap->pool);
            sap->pool = p;
            sap->pool_capacity = cap;
        }
        slot = sap->pool_used++;
    }
    sap->pool[slot].a = a;
    sap->pool[slot].b = b;
    sap->pool[slot].next = sap->buckets[bk];
    sap->buckets[bk] = slot;
    sap->live++;
    return 1;
}

static void table_remove(rugo_sweep_prune* sap, int a, int b) {
    int bk = bucket_of(sap, a, b);
    int* link = &sap->buckets[bk];
    while (*link >= 0) {
        int e = *link;
        if (sap->pool[e].a == a && sap->pool[e].b == b) {
            *link = sap->pool[e].next;
            sap->pool[e].next = sap->free_head;
            sap->free_head = e;
            sap->live--;
            return;
        }
        link = &sap->pool[e].next;
    }
}

static rugo_status reserve(rugo_sweep_prune* sap, int n) {
    if (n < 1) n = 1; /* the bucket array must exist even for no boxes */
    if (n <= sap->capacity) return RUGO_OK;
    rugo_allocator* a = &sap->allocator;
    endpoint* x = (endpoint*)rugo__alloc_array(a, (size_t)n * 2, sizeof *x);
    endpoint* y = (endpoint*)rugo__alloc_array(a, (size_t)n * 2, sizeof *y);
    int* act = (int*)rugo__alloc_array(a, (size_t)n, sizeof *act);
    int* pos = (int*)rugo__alloc_array(a, (size_t)n, sizeof *pos);
    int* bk = (int*)rugo__alloc_array(a, (size_t)n * 2 + 1, sizeof *bk);
    if (x == NULL || y == NULL || act == NULL || pos == NULL || bk == NULL) {
        rugo__free(a, x);
        rugo__free(a, y);
        rugo__free(a, act);
        rugo__free(a, pos);
        rugo__free(a, bk);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    rugo__free(a, sap->axis[0]);
    rugo__free(a, sap->axis[1]);
    rugo__free(a, sap->active);
    rugo__free(a, sap->active_pos);
    rugo__free(a, sap->buckets);
    sap->axis[0] = x;
    sap->axis[1] = y;
    sap->active = act;
    sap->active_pos = pos;
    sap->buckets = bk;
    sap->capacity = n;
    return RUGO_OK;
}

static rugo_status general(rugo_sweep_prune* sap, const rugo_aabb* boxes, int n) {
    sap->h = 2 * n + 1;
    table_clear(sap);
    for (int ax = 0; ax < 2; ++ax) {
        endpoint* e = sap->axis[ax];
        for (int i = 0; i < n; ++i) {
            e[2 * i].value = ax == 0 ? boxes[i].lower.x : boxes[i].lower.y;
            e[2 * i].id = i;
            e[2 * i].end = 0;
            e[2 * i + 1].value = ax == 0 ? boxes[i].upper.x : boxes[i].upper.y;
            e[2 * i + 1].id = i;
            e[2 * i + 1].end = 1;
        }
        if (n > 0) qsort(e, (size_t)n * 2, sizeof *e, endpoint_cmp);
    }
    int active = 0;
    const endpoint* e = sap->axis[0];
    for (int k = 0; k < 2 * n; ++k) {
        int i = e[k].id;
        if (e[k].end) {
            int p = sap->active_pos[i];
            sap->active[p] = sap->active[--active];
            sap->active_pos[sap->active[p]] = p;
        } else {
            for (int m = 0; m < active; ++m) {
                int j = sap->active[m];
                if (overlap_axis(&boxes[i], &boxes[j], 1) && !table_add(sap, i < j ? i : j, i < j ? j : i))
                    return RUGO_ERR_OUT_OF_MEMORY;
            }
            sap->active_pos[i] = active;
            sap->active[active++] = i;
        }
    }
    sap->swaps = 0;
    return RUGO_OK;
}

static rugo_status coherent(rugo_sweep_prune* sap, const rugo_aabb* boxes, int n) {
    long swaps = 0;
    for (int ax = 0; ax < 2; ++ax) {
        endpoint* e = sap->axis[ax];
        for (int k = 0; k < 2 * n; ++k) {
            const rugo_aabb* b = &boxes[e[k].id];
            e[k].value = ax == 0 ? (e[k].end ? b->upper.x : b->lower.x) : (e[k].end ? b->upper.y : b->lower.y);
        }
        for (int k = 1; k < 2 * n; ++k) {
            endpoint cur = e[k];
            int m = k - 1;
            while (m >= 0 && endpoint_less(&cur, &e[m])) {
                const endpoint* left = &e[m];
                int i = cur.id, j = left->id;
                int lo = i < j ? i : j, hi = i < j ? j : i;
                if (!cur.end && left->end) {
                    if (overlap_axis(&boxes[i], &boxes[j], 0) && overlap_axis(&boxes[i], &boxes[j], 1) &&
                        !table_add(sap, lo, hi)) {
                        /* Keep the sort consistent, then force a rebuild next time. */
                        e[m + 1] = e[m];
                        e[m] = cur;
                        sap->valid = 0;
                        return RUGO_ERR_OUT_OF_MEMORY;
                    }
                } else if (cur.end && !left->end) {
                    table_remove(sap, lo, hi);
                }
                e[m + 1] = e[m];
                --m;
                ++swaps;
            }
            e[m + 1] = cur;
        }
    }
    sap->swaps = swaps;
    return RUGO_OK;
}

rugo_status rugo_sweep_prune_update(rugo_sweep_prune* sap, const rugo_aabb* boxes, int n) {
    if (sap == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 0 || n > (1 << 26)) return RUGO_ERR_BAD_ARGUMENT;
    if (n > 0 && boxes == NULL) return RUGO_ERR_NULL_ARGUMENT;
    for (int i = 0; i < n; ++i)
        if (!rugo__v2_finite(boxes[i].lower) || !rugo__v2_finite(boxes[i].upper)) return RUGO_ERR_NOT_FINITE;
    for (int i = 0; i < n; ++i)
        if (boxes[i].lower.x > boxes[i].upper.x || boxes[i].lower.y > boxes[i].upper.y) return RUGO_ERR_BAD_ARGUMENT;

    rugo_status st = reserve(sap, n);
    if (st != RUGO_OK) return st;
    if (!sap->valid || n != sap->n) {
        sap->valid = 0;
        st = general(sap, boxes, n);
    } else {
        st = coherent(sap, boxes, n);
    }
    sap->out_count = 0;
    if (st != RUGO_OK) {
        sap->valid = 0;
        return st;
    }
    if (sap->live > sap->out_capacity) {
        int cap = sap->live + sap->live / 2 + 16;
        rugo_pair* p = (rugo_pair*)rugo__alloc_array(&sap->allocator, (size_t)cap, sizeof *p);
        if (p == NULL) {
            sap->valid = 0;
            return RUGO_ERR_OUT_OF_MEMORY;
        }
        rugo__free(&sap->allocator, sap->out);
        sap->out = p;
        sap->out_capacity = cap;
    }
    int c = 0;
    for (int bk = 0; bk < sap->h; ++bk)
        for (int e = sap->buckets[bk]; e >= 0; e = sap->pool[e].next) {
            sap->out[c].a = sap->pool[e].a;
            sap->out[c].b = sap->pool[e].b;
            ++c;
        }
    RUGO_ASSERT(c == sap->live);
    if (c > 1) qsort(sap->out, (size_t)c, sizeof *sap->out, pair_cmp);
    sap->out_count = c;
    sap->n = n;
    sap->valid = 1;
    return RUGO_OK;
}

const rugo_pair* rugo_sweep_prune_pairs(const rugo_sweep_prune* sap, int* count) {
    if (count != NULL) *count = sap != NULL ? sap->out_count : 0;
    if (sap == NULL) return NULL;
    return sap->out;
}

long rugo_sweep_prune_swaps(const rugo_sweep_prune* sap) { return sap != NULL ? sap->swaps : 0; }
