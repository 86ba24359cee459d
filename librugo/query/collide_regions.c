/* Overlap regions: the boundary of A ∩ B traced through the crossings. Sorted along A and along B,
 * each crossing starts an arc of one curve inside the other, and following those arcs from crossing
 * to crossing closes each region. Separate because it is pure bookkeeping on parameters, shared by
 * shapes and primitives through region_io. */
#include "query/collide_internal.h"

/* Index of the arc (of A if which == 0, of B otherwise) holding parameter u. */
static int arc_of(const regions* r, rugo_real u, int which) {
    int lo = 0, hi = r->m - 1, best = -1;
    while (lo <= hi) { /* last rank whose start <= u */
        const int mid = (lo + hi) / 2;
        const rugo_real start = which == 0 ? r->x[mid].ua : r->x[r->order_b[mid]].ub;
        if (start <= u) {
            best = mid;
            lo = mid + 1;
        } else {
            hi = mid - 1;
        }
    }
    if (best < 0) best = r->m - 1; /* before the first crossing: the arc that wraps around */
    return which == 0 ? best : r->order_b[best];
}

/* Region of a pair (ua on A, ub on B) if both lie on arcs of the same region, else -1. */
int rugo__region_of_pair(const regions* r, rugo_real ua, rugo_real ub) {
    if (r->m == 0) return -1;
    const int ra = r->reg_a[arc_of(r, ua, 0)], rb = r->reg_b[arc_of(r, ub, 1)];
    return ra >= 0 && ra == rb ? ra : -1;
}

/* Region touching a point of A or B (either arc), for filtering minima. */
int rugo__in_any_region(const regions* r, rugo_real ua, rugo_real ub) {
    if (r->m == 0) return 0;
    return r->reg_a[arc_of(r, ua, 0)] >= 0 || r->reg_b[arc_of(r, ub, 1)] >= 0;
}

static void sort_order_b(regions* r) {
    /* Insertion sort by (ub, index): m is small, and this keeps the order deterministic without a
     * global comparator context. */
    for (int i = 0; i < r->m; ++i)
        r->order_b[i] = i;
    for (int i = 1; i < r->m; ++i) {
        const int v = r->order_b[i];
        int j = i - 1;
        while (j >= 0 && (r->x[r->order_b[j]].ub > r->x[v].ub ||
                          (r->x[r->order_b[j]].ub == r->x[v].ub && r->order_b[j] > v))) {
            r->order_b[j + 1] = r->order_b[j];
            --j;
        }
        r->order_b[j + 1] = v;
    }
    for (int i = 0; i < r->m; ++i)
        r->pos_b[r->order_b[i]] = i;
}

static int kinds_consistent(const regions* r) {
    if (r->m % 2 != 0) return 0;
    for (int i = 0; i < r->m; ++i) {
        if (r->a_in[i] == r->b_in[i]) return 0;
        if (r->a_in[i] == r->a_in[rugo__next_along_a(r, i)]) return 0;
        if (r->b_in[i] == r->b_in[rugo__next_along_b(r, i)]) return 0;
    }
    return 1;
}

/* Builds the regions of the m crossings x (sorted by ua; ctx->ints must hold 6 m ints). */
void rugo__build_regions(regions* r, const hit* x, int m, int* ints, const region_io* io) {
    r->m = m;
    r->x = x;
    r->order_b = ints;
    r->pos_b = ints + m;
    r->a_in = ints + 2 * m;
    r->b_in = ints + 3 * m;
    r->reg_a = ints + 4 * m;
    r->reg_b = ints + 5 * m;
    r->count = 0;
    r->period_a = io->period_a;
    r->period_b = io->period_b;
    if (m == 0) return;
    sort_order_b(r);
    for (int i = 0; i < m; ++i) {
        r->a_in[i] = x[i].kind < 0;
        r->b_in[i] = x[i].kind > 0;
        r->reg_a[i] = r->reg_b[i] = -1;
    }
    if (!kinds_consistent(r)) {
        /* Orientation of some crossing not trustworthy (near-tangent, or a crossing lost to a
         * duplicate): decide each arc by a containment test of its midpoint. */
        for (int i = 0; i < m; ++i) {
            const int j = rugo__next_along_a(r, i);
            const rugo_real la = rugo__param_arc(x[i].ua, x[j].ua, io->period_a, m == 1);
            const rugo_real mid_a = rugo__wrap_param(x[i].ua + 0.5 * la, io->period_a);
            r->a_in[i] = io->inside_b(io->user, io->point_a(io->user, mid_a));
            const int k = rugo__next_along_b(r, i);
            const rugo_real lb = rugo__param_arc(x[i].ub, x[k].ub, io->period_b, m == 1);
            const rugo_real mid_b = rugo__wrap_param(x[i].ub + 0.5 * lb, io->period_b);
            r->b_in[i] = io->inside_a(io->user, io->point_b(io->user, mid_b));
        }
    }
    for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < m; ++i) {
            /* Regions start from A's arcs; B's arcs no A-arc reached (inconsistent data) start their own. */
            const int start_ok =
                pass == 0 ? (r->a_in[i] && r->reg_a[i] < 0) : (r->b_in[i] && r->reg_b[i] < 0);
            if (!start_ok) continue;
            const int reg = r->count++;
            int cur = i, use_a = pass == 0;
            for (int steps = 0; steps < 2 * m + 2; ++steps) {
                if (use_a && r->a_in[cur] && r->reg_a[cur] < 0) {
                    r->reg_a[cur] = reg;
                    cur = rugo__next_along_a(r, cur);
                } else if (r->b_in[cur] && r->reg_b[cur] < 0) {
                    r->reg_b[cur] = reg;
                    cur = rugo__next_along_b(r, cur);
                } else if (r->a_in[cur] && r->reg_a[cur] < 0) {
                    r->reg_a[cur] = reg;
                    cur = rugo__next_along_a(r, cur);
                } else {
                    break;
                }
                use_a = 1;
            }
        }
}
