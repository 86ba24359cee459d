/* A roughness description's tolerances per segment (shape_file.h): presets, constants and lists as
 * they are given; arc-length ranges and profiles resampled onto a contour's segments by arc length.
 * With the checks of ranges and profiles (rough/internal.h), which the shape-file reader and writer
 * share, so that a source the reader accepts is one the resampling accepts. */
#include "rugo/shape_file.h"

#include "core/internal.h"
#include "rough/internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

rugo_status rugo__roughness_range_check(const rugo_roughness_range* g, int* member_index, char* msg,
                                        size_t size) {
    const rugo_real v[3] = {g->from, g->to, g->tolerance};
    static const char* const names[3] = {"from", "to", "tolerance"};
    for (int k = 0; k < 3; ++k)
        if (!isfinite(v[k])) {
            *member_index = k;
            snprintf(msg, size, "%s is not finite", names[k]);
            return RUGO_ERR_NOT_FINITE;
        }
    for (int k = 0; k < 2; ++k)
        if (!(v[k] >= 0.0 && v[k] <= 1.0)) {
            *member_index = k;
            snprintf(msg, size, "%s must be a fraction of the perimeter in [0, 1], found %.17g", names[k],
                     v[k]);
            return RUGO_ERR_BAD_FIELD;
        }
    if (g->from == g->to || (g->from == 1.0 && g->to == 0.0)) {
        *member_index = -1;
        snprintf(msg, size, "the range from %.17g to %.17g is empty (from 0 to 1 is the whole perimeter)",
                 g->from, g->to);
        return RUGO_ERR_BAD_FIELD;
    }
    rugo_status s = rugo_tolerances_check(&g->tolerance, 1, NULL);
    if (s != RUGO_OK) {
        *member_index = 2;
        snprintf(msg, size, "invalid tolerance %.17g: %s", g->tolerance, rugo_status_string(s));
    }
    return s;
}

rugo_status rugo__roughness_sample_check(const rugo_profile_sample* prev, const rugo_profile_sample* cur,
                                         int* column, char* msg, size_t size) {
    if (!isfinite(cur->s) || !isfinite(cur->tolerance)) {
        *column = isfinite(cur->s) ? 1 : 0;
        snprintf(msg, size, "%s is not finite", *column == 0 ? "s" : "the tolerance");
        return RUGO_ERR_NOT_FINITE;
    }
    *column = 0;
    if (!(cur->s >= 0.0 && cur->s <= 1.0)) {
        snprintf(msg, size, "s must be a fraction of the perimeter in [0, 1], found %.17g", cur->s);
        return RUGO_ERR_BAD_FIELD;
    }
    if (prev != NULL && !(cur->s > prev->s)) {
        snprintf(msg, size, "s must increase strictly from sample to sample: %.17g follows %.17g", cur->s,
                 prev->s);
        return RUGO_ERR_BAD_FIELD;
    }
    *column = 1;
    rugo_status s = rugo_tolerances_check(&cur->tolerance, 1, NULL);
    if (s != RUGO_OK)
        snprintf(msg, size, "invalid tolerance %.17g: %s", cur->tolerance, rugo_status_string(s));
    return s;
}

rugo_status rugo__roughness_arc_source_check(const rugo_roughness_desc* r) {
    char msg[160];
    int where = 0;
    rugo_status s = RUGO_OK;
    if (r->kind == RUGO_ROUGHNESS_RANGES) {
        if (r->range_count < 0) return RUGO_ERR_BAD_ARGUMENT;
        if (r->range_count > RUGO_MAX_ROUGHNESS_RANGES) return RUGO_ERR_TOO_MANY_POINTS;
        if (r->range_count > 0 && r->ranges == NULL) return RUGO_ERR_NULL_ARGUMENT;
        for (int i = 0; i < r->range_count && s == RUGO_OK; ++i)
            s = rugo__roughness_range_check(&r->ranges[i], &where, msg, sizeof msg);
        if (s == RUGO_OK) s = rugo_tolerances_check(&r->background, 1, NULL);
    } else {
        if (r->profile_count < 1) return RUGO_ERR_BAD_ARGUMENT;
        if (r->profile_count > RUGO_MAX_PROFILE_SAMPLES) return RUGO_ERR_TOO_MANY_POINTS;
        if (r->profile == NULL) return RUGO_ERR_NULL_ARGUMENT;
        for (int i = 0; i < r->profile_count && s == RUGO_OK; ++i)
            s = rugo__roughness_sample_check(i > 0 ? &r->profile[i - 1] : NULL, &r->profile[i], &where, msg,
                                             sizeof msg);
    }
    return s == RUGO_ERR_BAD_FIELD ? RUGO_ERR_BAD_ARGUMENT : s;
}

rugo_status rugo_roughness_tolerances(const rugo_roughness_desc* desc, int n, rugo_real* out) {
    if (desc == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 1) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    switch (desc->kind) {
    case RUGO_ROUGHNESS_PRESET:
        return rugo_tolerances_preset(desc->preset, desc->seed, n, out);
    case RUGO_ROUGHNESS_CONSTANT:
        return rugo_tolerances_constant(desc->constant, n, out);
    case RUGO_ROUGHNESS_TOLERANCES: {
        if (desc->tolerance_count != n) return RUGO_ERR_BAD_ARGUMENT;
        if (desc->tolerances == NULL) return RUGO_ERR_NULL_ARGUMENT;
        rugo_status s = rugo_tolerances_check(desc->tolerances, n, NULL);
        if (s != RUGO_OK) return s;
        memcpy(out, desc->tolerances, sizeof *out * (size_t)n);
        return RUGO_OK;
    }
    default:
        return RUGO_ERR_BAD_ARGUMENT;
    }
}

/* A range restricted to [0, 1]: a wrapping range gives two. */
typedef struct range_piece {
    rugo_real lo, hi, tolerance;
} range_piece;

static int piece_cmp(const void* pa, const void* pb) {
    const range_piece* a = (const range_piece*)pa;
    const range_piece* b = (const range_piece*)pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    if (a->tolerance != b->tolerance) return a->tolerance < b->tolerance ? -1 : 1;
    return 0;
}

/* Max-heap of piece indices keyed by tolerance. */
static void heap_push(int* heap, int* size, int item, const range_piece* p) {
    int i = (*size)++;
    heap[i] = item;
    while (i > 0) {
        int parent = (i - 1) / 2;
        if (!(p[heap[parent]].tolerance < p[heap[i]].tolerance)) break;
        int t = heap[parent];
        heap[parent] = heap[i];
        heap[i] = t;
        i = parent;
    }
}

static void heap_pop(int* heap, int* size, const range_piece* p) {
    heap[0] = heap[--*size];
    int i = 0;
    for (;;) {
        int l = 2 * i + 1, r = l + 1, top = i;
        if (l < *size && p[heap[top]].tolerance < p[heap[l]].tolerance) top = l;
        if (r < *size && p[heap[top]].tolerance < p[heap[r]].tolerance) top = r;
        if (top == i) break;
        int t = heap[top];
        heap[top] = heap[i];
        heap[i] = t;
        i = top;
    }
}

/* out[j] holds the arc length of segment j on entry (total: their sum, > 0) and its tolerance on
 * return. The segments' intervals, shrunk by the slack, move forward monotonically, so one sweep
 * serves them all: pieces enter the heap when they start before the interval's end, and leave it
 * (lazily, from the top) once they end before its start, which no later interval reaches again. */
static rugo_status ranges_on_segments(const rugo_roughness_desc* r, const rugo_allocator* al, int n,
                                      rugo_real total, rugo_real* out) {
    int m = 0;
    range_piece* piece = NULL;
    range_piece* cover = NULL;
    int* heap = NULL;
    if (r->range_count > 0) {
        size_t cap = (size_t)r->range_count * 2;
        piece = (range_piece*)rugo__alloc_array(al, cap, sizeof *piece);
        cover = (range_piece*)rugo__alloc_array(al, cap, sizeof *cover);
        heap = (int*)rugo__alloc_array(al, cap, sizeof *heap);
        if (piece == NULL || cover == NULL || heap == NULL) {
            rugo__free(al, piece);
            rugo__free(al, cover);
            rugo__free(al, heap);
            return RUGO_ERR_OUT_OF_MEMORY;
        }
        for (int i = 0; i < r->range_count; ++i) {
            const rugo_roughness_range* g = &r->ranges[i];
            if (g->from < g->to) {
                piece[m].lo = g->from;
                piece[m].hi = g->to;
                piece[m++].tolerance = g->tolerance;
            } else {
                piece[m].lo = g->from;
                piece[m].hi = 1.0;
                piece[m++].tolerance = g->tolerance;
                piece[m].lo = 0.0;
                piece[m].hi = g->to;
                piece[m++].tolerance = g->tolerance;
            }
        }
        qsort(piece, (size_t)m, sizeof *piece, piece_cmp);
    }
    /* The union of the (closed) pieces as disjoint intervals in increasing order. */
    int nc = 0;
    for (int i = 0; i < m; ++i) {
        if (nc > 0 && piece[i].lo <= cover[nc - 1].hi) {
            if (piece[i].hi > cover[nc - 1].hi) cover[nc - 1].hi = piece[i].hi;
        } else {
            cover[nc++] = piece[i];
        }
    }
    const rugo_real slack = RUGO_ROUGHNESS_RANGE_SLACK;
    int next = 0, size = 0, cv = 0;
    rugo_real before = 0.0; /* arc length before segment j */
    for (int j = 0; j < n; ++j) {
        rugo_real len = out[j];
        rugo_real a = before / total;
        before += len;
        rugo_real b = j == n - 1 ? 1.0 : before / total;
        rugo_real p, q;
        if (b - a > 2.0 * slack) {
            p = a + slack;
            q = b - slack;
        } else {
            p = q = a + 0.5 * (b - a);
        }
        while (next < m && piece[next].lo <= q)
            heap_push(heap, &size, next++, piece);
        while (size > 0 && piece[heap[0]].hi < p)
            heap_pop(heap, &size, piece);
        while (cv < nc && cover[cv].hi < p)
            ++cv;
        int covered = cv < nc && cover[cv].lo <= p && cover[cv].hi >= q;
        rugo_real lam = size > 0 ? piece[heap[0]].tolerance : r->background;
        if (!covered && r->background > lam) lam = r->background;
        out[j] = lam;
    }
    rugo__free(al, piece);
    rugo__free(al, cover);
    rugo__free(al, heap);
    return RUGO_OK;
}

/* Entry k (0..K+1) of a profile's periodic extension: the last sample moved back by one period, the
 * samples, the first sample moved on by one period. Abscissae never decrease with k. */
static void profile_entry(const rugo_profile_sample* p, int K, int k, rugo_real* x, rugo_real* lam) {
    if (k == 0) {
        *x = p[K - 1].s - 1.0;
        *lam = p[K - 1].tolerance;
    } else if (k == K + 1) {
        *x = p[0].s + 1.0;
        *lam = p[0].tolerance;
    } else {
        *x = p[k - 1].s;
        *lam = p[k - 1].tolerance;
    }
}

/* λ at x, where entry k is the last one with abscissa <= x. */
static rugo_real profile_value(const rugo_profile_sample* p, int K, int k, rugo_real x) {
    rugo_real x0, l0, x1, l1;
    profile_entry(p, K, k, &x0, &l0);
    if (x == x0 || k == K + 1) return l0;
    profile_entry(p, K, k + 1, &x1, &l1);
    rugo_real v = l0 + (l1 - l0) * ((x - x0) / (x1 - x0));
    /* Round-off must not leave the chord's range. */
    rugo_real lo = l0 < l1 ? l0 : l1, hi = l0 < l1 ? l1 : l0;
    return v < lo ? lo : (v > hi ? hi : v);
}

/* As ranges_on_segments, for a profile: max of λ at both ends and at the samples between. */
static void profile_on_segments(const rugo_roughness_desc* r, int n, rugo_real total, rugo_real* out) {
    const rugo_profile_sample* p = r->profile;
    const int K = r->profile_count;
    int k = 0;
    rugo_real before = 0.0;
    for (int j = 0; j < n; ++j) {
        rugo_real a = before / total;
        before += out[j];
        rugo_real b = j == n - 1 ? 1.0 : before / total;
        rugo_real x, lam;
        for (;;) { /* the last entry at or before a */
            if (k + 1 > K + 1) break;
            profile_entry(p, K, k + 1, &x, &lam);
            if (!(x <= a)) break;
            ++k;
        }
        rugo_real best = profile_value(p, K, k, a);
        /* Two entries share an abscissa only at 0 or 1, when samples sit at both: take both. */
        for (int i = k - 1; i >= 0; --i) {
            profile_entry(p, K, i, &x, &lam);
            if (x != a) break;
            if (lam > best) best = lam;
        }
        int last = k;
        for (int i = k + 1; i <= K + 1; ++i) {
            profile_entry(p, K, i, &x, &lam);
            if (!(x <= b)) break;
            if (lam > best) best = lam;
            last = i;
        }
        rugo_real end = profile_value(p, K, last, b);
        out[j] = end > best ? end : best;
    }
}

rugo_status rugo_roughness_tolerances_on_contour(const rugo_roughness_desc* desc, rugo_contour contour,
                                                 const rugo_allocator* allocator, rugo_real* out) {
    if (desc == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (desc->kind != RUGO_ROUGHNESS_RANGES && desc->kind != RUGO_ROUGHNESS_PROFILE)
        return rugo_roughness_tolerances(desc, contour.count, out);
    const int n = contour.count;
    if (contour.points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    rugo_status s = rugo__roughness_arc_source_check(desc);
    if (s != RUGO_OK) return s;
    for (int i = 0; i < n; ++i)
        if (!rugo__v2_finite(contour.points[i])) return RUGO_ERR_NOT_FINITE;
    /* Lengths first, in a scratch array, so that out is untouched on error. */
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_real* len = (rugo_real*)rugo__alloc_array(&al, (size_t)n, sizeof *len);
    if (len == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    rugo_real total = 0.0;
    for (int j = 0; j < n; ++j) {
        len[j] = rugo_contour_segment_length(contour, j);
        total += len[j];
    }
    if (!isfinite(total))
        s = RUGO_ERR_NOT_FINITE;
    else if (!(total > 0.0))
        s = RUGO_ERR_ZERO_AREA;
    else if (desc->kind == RUGO_ROUGHNESS_RANGES)
        s = ranges_on_segments(desc, &al, n, total, len);
    else
        profile_on_segments(desc, n, total, len);
    if (s == RUGO_OK) memcpy(out, len, sizeof *out * (size_t)n);
    rugo__free(&al, len);
    return s;
}
