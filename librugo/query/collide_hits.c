/* The narrow phase's results as a query keeps them: hits in global parameters (a point at t = 1
 * belongs to the next segment), ordered along A, and each point that several narrow calls found (a
 * joint, a point-like segment, a sharp corner) kept once with the kind the calls agree on. Separate
 * because shapes and primitives record and merge their results the same way. */
#include "query/collide_internal.h"

#include <stdlib.h>

int rugo__push_hit(rugo_collide_context* ctx, rugo__array* b, size_t* n, const hit* h) {
    if (!rugo__scratch_reserve(ctx, b, *n + 1, sizeof(hit))) return 0;
    ((hit*)b->data)[(*n)++] = *h;
    return 1;
}

/* Segment and parameter with t = 1 moved to the next segment. */
void rugo__normalise_segment_param(int* seg, rugo_real* t, int n) {
    if (!(*t > 0.0)) *t = 0.0;
    if (*t >= 1.0) {
        *seg += 1;
        *t = 0.0;
    }
    *seg = rugo__wrap(*seg, n);
}

int rugo__hit_cmp(const void* pa, const void* pb) {
    const hit* a = (const hit*)pa;
    const hit* b = (const hit*)pb;
    if (a->ua != b->ua) return a->ua < b->ua ? -1 : 1;
    if (a->ub != b->ub) return a->ub < b->ub ? -1 : 1;
    if (a->src != b->src) return a->src < b->src ? -1 : 1;
    if (a->kind != b->kind) return a->kind < b->kind ? -1 : 1;
    return 0;
}

/* A stationary pair that may be the closest pair of two curves: a minimum, or a one-sided one (the
 * smallest distance overall is a minimum on every side, so a one-sided minimum that is not one loses
 * to a smaller distance reported elsewhere). */
int rugo__is_minimum_candidate(int kind) { return kind == RUGO__MINIMUM || kind == RUGO__END_MINIMUM; }

/* Sorts by A's parameter and marks as dead every hit that repeats an earlier one found by another
 * narrow call (same points within `eps`, A parameters within one segment, cyclically). A crossing
 * beats a touching; for stationary pairs a minimum beats other kinds: at a joint next to a point-like
 * segment, the piece that holds the point inside its domain classifies it. Pieces that reach the point
 * only at an end of their domain where they stop (a zero-speed corner of three coincident control
 * points) see one side of it (RUGO__END_MINIMUM when it rises there): it is a minimum when no other
 * piece reports the same point as a saddle or maximum, i.e. when it rises on every side seen. */
void rugo__dedupe_hits(hit* h, size_t n, rugo_real period_a, rugo_real eps, int stationary) {
    if (n == 0) return;
    qsort(h, n, sizeof(hit), rugo__hit_cmp);
    for (size_t i = 0; i < n; ++i) {
        if (h[i].dead) continue;
        int any_min = h[i].kind == RUGO__MINIMUM, any_end = h[i].kind == RUGO__END_MINIMUM;
        int any_other = h[i].kind == RUGO__SADDLE || h[i].kind == RUGO__MAXIMUM;
        for (size_t jj = 1; jj < n; ++jj) {
            const size_t j = (i + jj) % n;
            rugo_real du = h[j].ua - h[i].ua;
            if (du < 0.0) du += period_a;
            if (du > 3.0 + 1e-9) break; /* a point-like segment or two may lie between duplicates */
            /* One call reports distinct roots, except stationary points spread over a zero-speed plateau
             * (a corner made by coincident control points): those merge by position too. */
            if (h[j].dead || (h[j].src == h[i].src && !stationary)) continue;
            int same = rugo__v2_length(rugo_v2_sub(h[j].pa, h[i].pa)) <= eps &&
                       rugo__v2_length(rugo_v2_sub(h[j].pb, h[i].pb)) <= eps;
            /* Flat minima (straight or nearly straight pieces facing each other) are located only to
             * ~sqrt(eps) at joints; at the same distance to round-off, points that close are one. */
            if (!same && stationary && fabs(h[j].distance - h[i].distance) <= 1e-3 * eps)
                same = rugo__v2_length(rugo_v2_sub(h[j].pa, h[i].pa)) <= 1e3 * eps &&
                       rugo__v2_length(rugo_v2_sub(h[j].pb, h[i].pb)) <= 1e3 * eps;
            if (same) {
                h[i].coincident |= h[j].coincident;
                if (stationary) {
                    any_min |= h[j].kind == RUGO__MINIMUM;
                    any_end |= h[j].kind == RUGO__END_MINIMUM;
                    any_other |= h[j].kind == RUGO__SADDLE || h[j].kind == RUGO__MAXIMUM;
                } else if (h[i].kind == 0 && h[j].kind != 0) {
                    h[i].kind = h[j].kind;
                }
                h[j].dead = 1;
            }
        }
        if (stationary && (any_min || any_end))
            h[i].kind = any_min || !any_other ? RUGO__MINIMUM : RUGO__SADDLE;
    }
}
