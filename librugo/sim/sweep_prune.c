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
#include "sim/internal.h"

#include "core/array.h"
#include "core/internal.h"

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

struct rugo__sweep_prune {
    rugo_allocator allocator;
    int n;                  /* boxes of the last successful update */
    int valid;              /* 0: the next update runs the general algorithm */
    rugo__array axis[2];    /* endpoint: 2 n per axis */
    rugo__array active;     /* int: the active list of the sweep, n */
    rugo__array active_pos; /* int: each box's place in it, n */
    int h;
    rugo__array buckets; /* int: h = 2 n + 1 */
    rugo__array pool;    /* pair_entry */
    int pool_used, free_head, live;
    rugo__array out; /* rugo__pair */
    int out_count;
    long swaps;
};

/* The pair pool's first capacity (it then doubles), and its largest size (pool indices are ints). */
#define POOL_FIRST 128
#define POOL_MAX (1 << 30)
/* The pair list's first capacity (it then doubles). */
#define OUT_FIRST 16

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
    const rugo__pair* x = (const rugo__pair*)p;
    const rugo__pair* y = (const rugo__pair*)q;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return 0;
}

static int overlap_axis(const rugo_aabb* p, const rugo_aabb* q, int axis) {
    if (axis == 0) return p->lower.x <= q->upper.x && q->lower.x <= p->upper.x;
    return p->lower.y <= q->upper.y && q->lower.y <= p->upper.y;
}

rugo_status rugo__sweep_prune_create(const rugo_allocator* allocator, rugo__sweep_prune** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    rugo_allocator a = rugo__allocator_or_default(allocator);
    rugo__sweep_prune* sap = (rugo__sweep_prune*)rugo__alloc_array(&a, 1, sizeof *sap);
    if (sap == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(sap, 0, sizeof *sap);
    sap->allocator = a;
    sap->free_head = -1;
    *out = sap;
    return RUGO_OK;
}

void rugo__sweep_prune_destroy(rugo__sweep_prune* sap) {
    if (sap == NULL) return;
    rugo_allocator a = sap->allocator;
    rugo__array* all[] = {&sap->axis[0], &sap->axis[1], &sap->active, &sap->active_pos,
                          &sap->buckets, &sap->pool,    &sap->out};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        rugo__array_free(all[i], &a);
    rugo__free(&a, sap);
}

static void table_clear(rugo__sweep_prune* sap) {
    int* buckets = (int*)sap->buckets.data;
    for (int i = 0; i < sap->h; ++i)
        buckets[i] = -1;
    sap->pool_used = 0;
    sap->free_head = -1;
    sap->live = 0;
}

static int bucket_of(const rugo__sweep_prune* sap, int a, int b) {
    return (int)(((unsigned)a + (unsigned)b) % (unsigned)sap->h);
}

/* Adds (a, b), a < b, if absent. 0 on out of memory. */
static int table_add(rugo__sweep_prune* sap, int a, int b) {
    int bk = bucket_of(sap, a, b);
    int* buckets = (int*)sap->buckets.data;
    pair_entry* pool = (pair_entry*)sap->pool.data;
    for (int e = buckets[bk]; e >= 0; e = pool[e].next)
        if (pool[e].a == a && pool[e].b == b) return 1;
    int slot;
    if (sap->free_head >= 0) {
        slot = sap->free_head;
        sap->free_head = pool[slot].next;
    } else {
        if (sap->pool_used >= POOL_MAX ||
            rugo__array_reserve(&sap->pool, &sap->allocator, (size_t)sap->pool_used + 1, sizeof(pair_entry),
                                POOL_FIRST) != RUGO_OK)
            return 0;
        pool = (pair_entry*)sap->pool.data;
        slot = sap->pool_used++;
    }
    pool[slot].a = a;
    pool[slot].b = b;
    pool[slot].next = buckets[bk];
    buckets[bk] = slot;
    sap->live++;
    return 1;
}

static void table_remove(rugo__sweep_prune* sap, int a, int b) {
    int bk = bucket_of(sap, a, b);
    pair_entry* pool = (pair_entry*)sap->pool.data;
    int* link = (int*)sap->buckets.data + bk;
    while (*link >= 0) {
        int e = *link;
        if (pool[e].a == a && pool[e].b == b) {
            *link = pool[e].next;
            pool[e].next = sap->free_head;
            sap->free_head = e;
            sap->live--;
            return;
        }
        link = &pool[e].next;
    }
}

/* Room for n boxes: their end points on both axes, the sweep's active list and the hash table's
 * 2 n + 1 buckets (the bucket array must exist even for no boxes). Sized to n the first time; the
 * contents are rebuilt by the general algorithm whenever n changes. */
static rugo_status reserve_boxes(rugo__sweep_prune* sap, int n) {
    if (n < 1) n = 1;
    const size_t m = (size_t)n;
    const rugo_allocator* a = &sap->allocator;
    if (rugo__array_reserve(&sap->axis[0], a, 2 * m, sizeof(endpoint), 2 * m) != RUGO_OK ||
        rugo__array_reserve(&sap->axis[1], a, 2 * m, sizeof(endpoint), 2 * m) != RUGO_OK ||
        rugo__array_reserve(&sap->active, a, m, sizeof(int), m) != RUGO_OK ||
        rugo__array_reserve(&sap->active_pos, a, m, sizeof(int), m) != RUGO_OK ||
        rugo__array_reserve(&sap->buckets, a, 2 * m + 1, sizeof(int), 2 * m + 1) != RUGO_OK)
        return RUGO_ERR_OUT_OF_MEMORY;
    return RUGO_OK;
}

static rugo_status general(rugo__sweep_prune* sap, const rugo_aabb* boxes, int n) {
    sap->h = 2 * n + 1;
    table_clear(sap);
    for (int ax = 0; ax < 2; ++ax) {
        endpoint* e = (endpoint*)sap->axis[ax].data;
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
    int* act = (int*)sap->active.data;
    int* act_pos = (int*)sap->active_pos.data;
    const endpoint* e = (const endpoint*)sap->axis[0].data;
    for (int k = 0; k < 2 * n; ++k) {
        int i = e[k].id;
        if (e[k].end) {
            int p = act_pos[i];
            act[p] = act[--active];
            act_pos[act[p]] = p;
        } else {
            for (int m = 0; m < active; ++m) {
                int j = act[m];
                if (overlap_axis(&boxes[i], &boxes[j], 1) && !table_add(sap, i < j ? i : j, i < j ? j : i))
                    return RUGO_ERR_OUT_OF_MEMORY;
            }
            act_pos[i] = active;
            act[active++] = i;
        }
    }
    sap->swaps = 0;
    return RUGO_OK;
}

static rugo_status coherent(rugo__sweep_prune* sap, const rugo_aabb* boxes, int n) {
    long swaps = 0;
    for (int ax = 0; ax < 2; ++ax) {
        endpoint* e = (endpoint*)sap->axis[ax].data;
        for (int k = 0; k < 2 * n; ++k) {
            const rugo_aabb* b = &boxes[e[k].id];
            e[k].value =
                ax == 0 ? (e[k].end ? b->upper.x : b->lower.x) : (e[k].end ? b->upper.y : b->lower.y);
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

rugo_status rugo__sweep_prune_update(rugo__sweep_prune* sap, const rugo_aabb* boxes, int n) {
    if (sap == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 0 || n > (1 << 26)) return RUGO_ERR_BAD_ARGUMENT;
    if (n > 0 && boxes == NULL) return RUGO_ERR_NULL_ARGUMENT;
    for (int i = 0; i < n; ++i)
        if (!rugo__v2_finite(boxes[i].lower) || !rugo__v2_finite(boxes[i].upper)) return RUGO_ERR_NOT_FINITE;
    for (int i = 0; i < n; ++i)
        if (boxes[i].lower.x > boxes[i].upper.x || boxes[i].lower.y > boxes[i].upper.y)
            return RUGO_ERR_BAD_ARGUMENT;

    rugo_status st = reserve_boxes(sap, n);
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
    if (rugo__array_reserve(&sap->out, &sap->allocator, (size_t)sap->live, sizeof(rugo__pair), OUT_FIRST) !=
        RUGO_OK) {
        sap->valid = 0;
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    rugo__pair* out = (rugo__pair*)sap->out.data;
    const int* buckets = (const int*)sap->buckets.data;
    const pair_entry* pool = (const pair_entry*)sap->pool.data;
    int c = 0;
    for (int bk = 0; bk < sap->h; ++bk)
        for (int e = buckets[bk]; e >= 0; e = pool[e].next) {
            out[c].a = pool[e].a;
            out[c].b = pool[e].b;
            ++c;
        }
    RUGO_ASSERT(c == sap->live);
    if (c > 1) qsort(out, (size_t)c, sizeof *out, pair_cmp);
    sap->out_count = c;
    sap->n = n;
    sap->valid = 1;
    return RUGO_OK;
}

const rugo__pair* rugo__sweep_prune_pairs(const rugo__sweep_prune* sap, int* count) {
    if (count != NULL) *count = sap != NULL ? sap->out_count : 0;
    if (sap == NULL) return NULL;
    return (const rugo__pair*)sap->out.data;
}

long rugo__sweep_prune_swaps(const rugo__sweep_prune* sap) { return sap != NULL ? sap->swaps : 0; }
