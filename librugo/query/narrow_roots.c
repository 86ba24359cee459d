/* The bookkeeping both searches of the narrow phase share: the lists of roots found (merged within
 * their uncertainty radii, a certified root replacing one accepted without a certificate), the stack
 * of parameter boxes and how a box is split, and the box that spans a box and a root found outside it
 * (for the proof that the box holds no root). Separate from the searches because crossings and
 * stationary pairs keep their roots and boxes the same way. */
#include "query/narrow_internal.h"

/* Adds a root unless one within the larger of the two radii exists (a Newton root replaces a leaf
 * root). Returns 0 when the list is full (overflow). */
int rugo__add_root(root* list, int* n, int cap, rugo_real s, rugo_real t, rugo_real radius, int kind,
                   int fb) {
    for (int i = 0; i < *n; ++i) {
        rugo_real r = rugo__max(radius, list[i].radius);
        if (fabs(list[i].s - s) <= r && fabs(list[i].t - t) <= r) {
            if (list[i].fallback && !fb) {
                list[i].s = s;
                list[i].t = t;
                list[i].radius = rugo__max(radius, list[i].radius);
                list[i].kind = kind;
                list[i].fallback = 0;
            }
            return 1;
        }
    }
    if (*n >= cap) return 0;
    list[*n].s = s;
    list[*n].t = t;
    list[*n].radius = radius;
    list[*n].kind = kind;
    list[*n].fallback = fb;
    ++*n;
    return 1;
}

int rugo__near_root(const root* list, int n, rugo_real s, rugo_real t, rugo_real r) {
    for (int i = 0; i < n; ++i)
        if (fabs(list[i].s - s) <= r && fabs(list[i].t - t) <= r) return 1;
    return 0;
}

/* Whether the box lies within the merge radius of a root accepted without a certificate. */
int rugo__box_covered(const root* list, int n, box b) {
    for (int i = 0; i < n; ++i) {
        if (!list[i].fallback) continue;
        rugo_real r = list[i].radius;
        if (fabs(b.s0 - list[i].s) <= r && fabs(b.s1 - list[i].s) <= r && fabs(b.t0 - list[i].t) <= r &&
            fabs(b.t1 - list[i].t) <= r)
            return 1;
    }
    return 0;
}

/* Dedupe radius from a condition estimate (uncertainty of a root ~ eps * condition). */
rugo_real rugo__root_radius(rugo_real cond) {
    rugo_real r = 64.0 * EPS * cond;
    if (!(r > R_ROOT)) r = R_ROOT;
    if (r > R_FALLBACK) r = R_FALLBACK;
    return r;
}

/* For a root (s, t) found outside box b (widened as rugo__in_box): the box E spanning b and the square of
 * half-width *r0 about the root, r0 half the root's max-norm distance to the widened box. 0 if the
 * root is not clearly outside. */
int rugo__exclusion_box(box b, rugo_real s, rugo_real t, box* e, rugo_real* r0) {
    rugo_real sl = b.s0 == 0.0 ? DOM_SLACK : SLACK, sh = b.s1 == 1.0 ? DOM_SLACK : SLACK;
    rugo_real tl = b.t0 == 0.0 ? DOM_SLACK : SLACK, th = b.t1 == 1.0 ? DOM_SLACK : SLACK;
    rugo_real d =
        rugo__max(rugo__max((b.s0 - sl) - s, s - (b.s1 + sh)), rugo__max((b.t0 - tl) - t, t - (b.t1 + th)));
    if (!(d > 0.0) || !isfinite(d)) return 0;
    *r0 = 0.5 * d;
    e->s0 = rugo__min(b.s0, s - *r0);
    e->s1 = rugo__max(b.s1, s + *r0);
    e->t0 = rugo__min(b.t0, t - *r0);
    e->t1 = rugo__max(b.t1, t + *r0);
    return e->s1 > 0.0 && e->t1 > 0.0; /* (always: b lies in [0,1]^2 and has positive width) */
}

int rugo__push_box(box* st, int* ns, rugo_real s0, rugo_real s1, rugo_real t0, rugo_real t1) {
    if (*ns >= STACK_MAX) return 0;
    st[*ns].s0 = s0;
    st[*ns].s1 = s1;
    st[*ns].t0 = t0;
    st[*ns].t1 = t1;
    ++*ns;
    return 1;
}

/* Splits b into two halves on the stack (first half on top). Returns 0 if nothing can be split. */
int rugo__split_box(box* st, int* ns, box b, rugo_real diam_f, rugo_real diam_g) {
    int can_s = b.s1 - b.s0 > H_MIN && diam_f > D_MIN;
    int can_t = b.t1 - b.t0 > H_MIN && diam_g > D_MIN;
    if (!can_s && !can_t) return 0;
    if (can_s && (!can_t || diam_f >= diam_g)) {
        rugo_real m = 0.5 * (b.s0 + b.s1);
        rugo__push_box(st, ns, m, b.s1, b.t0, b.t1);
        rugo__push_box(st, ns, b.s0, m, b.t0, b.t1);
    } else {
        rugo_real m = 0.5 * (b.t0 + b.t1);
        rugo__push_box(st, ns, b.s0, b.s1, m, b.t1);
        rugo__push_box(st, ns, b.s0, b.s1, b.t0, m);
    }
    return 1;
}
