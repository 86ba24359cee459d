/* Validation of a contour's control points (rugo_contour_check): counts, finite coordinates, an area
 * above round-off, and the self-intersection test, the only part of the contour code that takes
 * scratch memory (O(n)). */
#include "rugo/contour.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__contour_bezier_rel */

#include <stdlib.h>

/* ---------------------------------------------------------------------------------------------------
 * Validation and self-intersection.
 *
 * Segments are compared pairwise, candidates coming from a sweep over their Bezier hull boxes sorted
 * by x. A pair is decided by recursive de Casteljau halving of the larger piece:
 *  - boxes apart by more than touch_tol: no contact;
 *  - pieces sharing a joint (consecutive segments, or halves of one segment): no contact besides the
 *    joint if the control points of one piece, seen from the joint, and those of the other, seen
 *    reversed, fit in an open half-plane (a line through the joint separates the pieces);
 *  - both pieces flat (inner control points within flat_tol of the chord): contact iff the chords
 *    come within touch_tol.
 * A single segment loops only if its hodograph (derivative control points) is not in an open
 * half-plane, i.e. it is not monotone in any direction; then its halves are compared as above.
 *
 * Round-off behaviour, with D the diagonal of the curve's bounds: every real crossing or touching is
 * found (a crossing lies within flat_tol of both flat chords, and touch_tol >= 2 flat_tol), so there
 * are no false negatives beyond round-off, except loops smaller than ~1e-15 D inside one segment.
 * Parts of the curve closer than touch_tol + 2 flat_tol (5e-10 D) may be reported as touching
 * (false positive). A segment shrunk to a point (four equal control points) is skipped and its
 * neighbours count as consecutive. A cusp at a joint whose two branches leave in exactly the same
 * direction (the curve retraces itself) is reported, since the branches overlap. */

#define SI_FLAT_TOL 1e-10
#define SI_TOUCH_TOL 2.5e-10
#define SI_MAX_DEPTH 100 /* halvings of either piece; pieces end far below flat_tol long before */

typedef struct bez4 {
    rugo_vec2 p[4];
} bez4;

typedef struct si_ctx {
    rugo_real flat_tol, touch_tol;
    rugo_vec2 where; /* relative to the frame origin */
} si_ctx;

static void bez_split(const bez4* b, bez4* l, bez4* r) {
    rugo_vec2 p01 = rugo_v2_scale(0.5, rugo_v2_add(b->p[0], b->p[1]));
    rugo_vec2 p12 = rugo_v2_scale(0.5, rugo_v2_add(b->p[1], b->p[2]));
    rugo_vec2 p23 = rugo_v2_scale(0.5, rugo_v2_add(b->p[2], b->p[3]));
    rugo_vec2 a = rugo_v2_scale(0.5, rugo_v2_add(p01, p12));
    rugo_vec2 e = rugo_v2_scale(0.5, rugo_v2_add(p12, p23));
    rugo_vec2 m = rugo_v2_scale(0.5, rugo_v2_add(a, e));
    l->p[0] = b->p[0];
    l->p[1] = p01;
    l->p[2] = a;
    l->p[3] = m;
    r->p[0] = m;
    r->p[1] = e;
    r->p[2] = p23;
    r->p[3] = b->p[3];
}

static void bez_box(const bez4* b, rugo_vec2* lo, rugo_vec2* hi) {
    *lo = *hi = b->p[0];
    for (int i = 1; i < 4; ++i) {
        lo->x = fmin(lo->x, b->p[i].x);
        lo->y = fmin(lo->y, b->p[i].y);
        hi->x = fmax(hi->x, b->p[i].x);
        hi->y = fmax(hi->y, b->p[i].y);
    }
}

/* Distance from p to the segment [a, b]; the nearest point goes to *near. */
static rugo_real point_segment_distance(rugo_vec2 p, rugo_vec2 a, rugo_vec2 b, rugo_vec2* near) {
    rugo_vec2 ab = rugo_v2_sub(b, a);
    rugo_real l2 = rugo_v2_dot(ab, ab);
    rugo_real u = l2 > 0.0 ? rugo_v2_dot(rugo_v2_sub(p, a), ab) / l2 : 0.0;
    u = fmin(1.0, fmax(0.0, u));
    *near = rugo_v2_add(a, rugo_v2_scale(u, ab));
    return rugo__v2_length(rugo_v2_sub(p, *near));
}

static int bez_flat(const bez4* b, rugo_real tol) {
    rugo_vec2 n;
    return point_segment_distance(b->p[1], b->p[0], b->p[3], &n) <= tol &&
           point_segment_distance(b->p[2], b->p[0], b->p[3], &n) <= tol;
}

/* Distance between segments [a0, a1] and [b0, b1]; an approximate meeting point to *where. */
static rugo_real segment_distance(rugo_vec2 a0, rugo_vec2 a1, rugo_vec2 b0, rugo_vec2 b1, rugo_vec2* where) {
    rugo_vec2 ea = rugo_v2_sub(a1, a0), eb = rugo_v2_sub(b1, b0);
    rugo_real d0 = rugo_v2_cross(ea, rugo_v2_sub(b0, a0)), d1 = rugo_v2_cross(ea, rugo_v2_sub(b1, a0));
    rugo_real d2 = rugo_v2_cross(eb, rugo_v2_sub(a0, b0)), d3 = rugo_v2_cross(eb, rugo_v2_sub(a1, b0));
    if (((d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0)) &&
        ((d2 > 0.0 && d3 < 0.0) || (d2 < 0.0 && d3 > 0.0))) {
        *where = rugo_v2_add(b0, rugo_v2_scale(d0 / (d0 - d1), eb));
        return 0.0;
    }
    rugo_vec2 n, best_n = a0, best_p = a0;
    rugo_real best = HUGE_VAL, dist;
    if ((dist = point_segment_distance(a0, b0, b1, &n)) < best) best = dist, best_p = a0, best_n = n;
    if ((dist = point_segment_distance(a1, b0, b1, &n)) < best) best = dist, best_p = a1, best_n = n;
    if ((dist = point_segment_distance(b0, a0, a1, &n)) < best) best = dist, best_p = b0, best_n = n;
    if ((dist = point_segment_distance(b1, a0, a1, &n)) < best) best = dist, best_p = b1, best_n = n;
    *where = rugo_v2_scale(0.5, rugo_v2_add(best_p, best_n));
    return best;
}

static rugo_real norm_inf(rugo_vec2 u) { return fmax(fabs(u.x), fabs(u.y)); }

/* Whether the non-negligible vectors u[0..m) lie in an open half-plane (their directions span an
 * angle below pi). Vectors shorter than 1e-12 of the longest (max-norm) are round-off of a zero (a
 * cusp, or a piece's shared end) and are ignored. `hint` is a likely direction inside the
 * half-plane: if every vector has a clearly positive component along it, that settles it without
 * trigonometry (the common case: smooth, gently curved pieces). */
static int in_open_half_plane(const rugo_vec2* u, int m, rugo_vec2 hint) {
    rugo_real lmax = 0.0;
    for (int i = 0; i < m; ++i)
        lmax = fmax(lmax, norm_inf(u[i]));
    if (!(lmax > 0.0)) return 1;
    rugo_real cut = 1e-12 * lmax, hn = norm_inf(hint);
    int fast = hn > 0.0;
    for (int i = 0; i < m && fast; ++i) {
        rugo_real ln = norm_inf(u[i]);
        /* component along the hint above 1e-9 of the lengths: an angle below pi/2 - 1e-9 */
        if (ln > cut && !(rugo_v2_dot(u[i], hint) > 1e-9 * 2.0 * ln * hn)) fast = 0;
    }
    if (fast) return 1;
    rugo_real ang[8];
    int na = 0;
    for (int i = 0; i < m && na < 8; ++i) {
        if (norm_inf(u[i]) > cut) ang[na++] = atan2(u[i].y, u[i].x);
    }
    for (int i = 1; i < na; ++i) { /* insertion sort: at most 8 angles */
        rugo_real v = ang[i];
        int k = i - 1;
        for (; k >= 0 && ang[k] > v; --k)
            ang[k + 1] = ang[k];
        ang[k + 1] = v;
    }
    const rugo_real two_pi = 6.283185307179586476925;
    rugo_real gap = ang[0] + two_pi - ang[na - 1];
    for (int i = 1; i < na; ++i)
        gap = fmax(gap, ang[i] - ang[i - 1]);
    /* The largest empty angular sector must exceed a half turn, by a margin above atan2's round-off. */
    return gap > 0.5 * two_pi + 1e-9;
}

/* x ends where y starts (at x->p[3] == y->p[0]): a line through that joint separates the pieces iff
 * x's control points seen from the joint and y's seen backwards lie in one open half-plane. */
static int joint_separates(const bez4* x, const bez4* y) {
    rugo_vec2 j = x->p[3], u[6];
    for (int i = 0; i < 3; ++i) {
        u[i] = rugo_v2_sub(x->p[i], j);
        u[3 + i] = rugo_v2_sub(j, y->p[i + 1]);
    }
    /* Likely separating direction (negated): from y's end back to x's start. */
    return in_open_half_plane(u, 6, rugo_v2_sub(x->p[0], y->p[3]));
}

/* Whether pieces a and b meet anywhere other than their shared joints. ab: a ends where b starts;
 * ba: b ends where a starts. */
static int pieces_meet(si_ctx* x, const bez4* a, const bez4* b, int ab, int ba, int depth) {
    rugo_vec2 alo, ahi, blo, bhi;
    bez_box(a, &alo, &ahi);
    bez_box(b, &blo, &bhi);
    if (!ab && !ba) {
        rugo_real t = x->touch_tol;
        if (alo.x > bhi.x + t || blo.x > ahi.x + t || alo.y > bhi.y + t || blo.y > ahi.y + t) return 0;
    }
    if (ab && !ba && joint_separates(a, b)) return 0;
    if (ba && !ab && joint_separates(b, a)) return 0;
    if (depth >= SI_MAX_DEPTH) {
        /* Pieces far below the tolerances: next to a joint that is their only contact; elsewhere
         * they touch. */
        if (ab || ba) return 0;
        x->where = rugo_v2_scale(0.5, rugo_v2_add(alo, ahi));
        return 1;
    }
    if (!ab && !ba && bez_flat(a, x->flat_tol) && bez_flat(b, x->flat_tol))
        return segment_distance(a->p[0], a->p[3], b->p[0], b->p[3], &x->where) <= x->touch_tol;
    rugo_vec2 ea = rugo_v2_sub(ahi, alo), eb = rugo_v2_sub(bhi, blo);
    bez4 h1, h2;
    if (fmax(ea.x, ea.y) >= fmax(eb.x, eb.y)) {
        bez_split(a, &h1, &h2); /* h1 keeps a's start, h2 its end */
        return pieces_meet(x, &h1, b, 0, ba, depth + 1) || pieces_meet(x, &h2, b, ab, 0, depth + 1);
    }
    bez_split(b, &h1, &h2);
    return pieces_meet(x, a, &h1, ab, 0, depth + 1) || pieces_meet(x, a, &h2, 0, ba, depth + 1);
}

/* Whether one piece crosses itself; closed: its end is its own start (a lone non-point segment). */
static int piece_loops(si_ctx* x, const bez4* b, int closed, int depth) {
    if (!closed) {
        rugo_vec2 u[3];
        for (int i = 0; i < 3; ++i)
            u[i] = rugo_v2_sub(b->p[i + 1], b->p[i]);
        if (in_open_half_plane(u, 3, rugo_v2_sub(b->p[3], b->p[0])))
            return 0; /* monotone along some direction */
    }
    if (depth >= SI_MAX_DEPTH / 2) return 0; /* a loop below 1e-15 of the segment is round-off */
    bez4 l, r;
    bez_split(b, &l, &r);
    return piece_loops(x, &l, 0, depth + 1) || piece_loops(x, &r, 0, depth + 1) ||
           pieces_meet(x, &l, &r, 1, closed, depth + 1);
}

typedef struct si_box {
    rugo_real x0, x1, y0, y1;
    int seg;
} si_box;

/* Sort keys kept small (the sort moves them, not the boxes); ties broken by box index so the order,
 * hence the pair reported, does not depend on the sort algorithm. */
typedef struct si_key {
    rugo_real x0;
    int box;
} si_key;

static int si_key_cmp(const void* pa, const void* pb) {
    const si_key* a = (const si_key*)pa;
    const si_key* b = (const si_key*)pb;
    if (a->x0 < b->x0) return -1;
    if (a->x0 > b->x0) return 1;
    return (a->box > b->box) - (a->box < b->box);
}

static int point_like(rugo_contour c, int j) {
    const rugo_vec2* p = c.points;
    int n = c.count;
    rugo_vec2 a = p[rugo__wrap(j - 1, n)];
    for (int i = 0; i < 3; ++i) {
        rugo_vec2 b = p[rugo__wrap(j + i, n)];
        if (b.x != a.x || b.y != a.y) return 0;
    }
    return 1;
}

static void segment_bez_rel(rugo_contour c, int j, rugo_vec2 o, bez4* b) {
    rugo__contour_bezier_rel(c, j, o, b->p);
}

static void report_crossing(rugo_contour_problem* problem, int a, int b, rugo_vec2 o, rugo_vec2 where) {
    if (problem == NULL) return;
    problem->segment_a = a < b ? a : b;
    problem->segment_b = a < b ? b : a;
    problem->where = rugo_v2_add(o, where);
}

static rugo_status check_crossings(rugo_contour c, rugo_vec2 lower, rugo_vec2 upper,
                                   rugo_contour_problem* problem, const rugo_allocator* allocator) {
    int n = c.count;
    rugo_allocator al = rugo__allocator_or_default(allocator);
    int* next = (int*)rugo__alloc_array(&al, (size_t)n, sizeof(int));
    si_box* boxes = (si_box*)rugo__alloc_array(&al, (size_t)n, sizeof(si_box));
    si_key* keys = (si_key*)rugo__alloc_array(&al, (size_t)n, sizeof(si_key));
    if (next == NULL || boxes == NULL || keys == NULL) {
        rugo__free(&al, next);
        rugo__free(&al, boxes);
        rugo__free(&al, keys);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    /* The frame's origin at the box centre keeps coordinates small; tolerances scale with the box. */
    rugo_vec2 o = rugo_v2_scale(0.5, rugo_v2_add(lower, upper));
    rugo_real diag = rugo__v2_length(rugo_v2_sub(upper, lower));
    si_ctx x;
    x.flat_tol = SI_FLAT_TOL * diag;
    x.touch_tol = SI_TOUCH_TOL * diag;
    x.where = rugo_v2(0.0, 0.0);

    /* next[j]: the next segment after j that is not a point; consecutive in that sense share a
     * joint. Two passes around the cycle settle the wrap. */
    int last = -1;
    for (int pass = 0; pass < 2; ++pass) {
        for (int j = n - 1; j >= 0; --j) {
            next[j] = last;
            if (!point_like(c, j)) last = j;
        }
    }
    rugo_status st = RUGO_OK;
    int m = 0;
    if (last >= 0) {
        for (int j = 0; j < n && st == RUGO_OK; ++j) {
            if (point_like(c, j)) continue;
            bez4 b;
            segment_bez_rel(c, j, o, &b);
            if (piece_loops(&x, &b, next[j] == j, 0)) {
                report_crossing(problem, j, j, o, x.where);
                st = RUGO_ERR_SELF_INTERSECTING;
            }
            rugo_vec2 lo, hi;
            bez_box(&b, &lo, &hi);
            rugo_real h = 0.5 * x.touch_tol;
            boxes[m].x0 = lo.x - h;
            boxes[m].x1 = hi.x + h;
            boxes[m].y0 = lo.y - h;
            boxes[m].y1 = hi.y + h;
            boxes[m].seg = j;
            keys[m].x0 = boxes[m].x0;
            keys[m].box = m;
            ++m;
        }
    }
    if (st == RUGO_OK) {
        qsort(keys, (size_t)m, sizeof(si_key), si_key_cmp);
        for (int i = 0; i < m && st == RUGO_OK; ++i) {
            const si_box* bi = &boxes[keys[i].box];
            for (int k = i + 1; k < m && keys[k].x0 <= bi->x1; ++k) {
                const si_box* bk = &boxes[keys[k].box];
                if (bk->y0 > bi->y1 || bi->y0 > bk->y1) continue;
                int a = bi->seg, b = bk->seg;
                bez4 ba, bb;
                segment_bez_rel(c, a, o, &ba);
                segment_bez_rel(c, b, o, &bb);
                if (pieces_meet(&x, &ba, &bb, next[a] == b, next[b] == a, 0)) {
                    report_crossing(problem, a, b, o, x.where);
                    st = RUGO_ERR_SELF_INTERSECTING;
                    break;
                }
            }
        }
    }
    rugo__free(&al, next);
    rugo__free(&al, boxes);
    rugo__free(&al, keys);
    return st;
}

/* 1 if every control point lies within 1e-9 of the bounds diagonal of one line (a flat outline,
 * which retraces itself but does not cross). */
static int collinear(const rugo_vec2* points, int count, rugo_real diag2) {
    int far = 0;
    rugo_real best = 0.0;
    for (int i = 1; i < count; ++i) {
        rugo_vec2 d = rugo_v2_sub(points[i], points[0]);
        if (rugo_v2_dot(d, d) > best) {
            best = rugo_v2_dot(d, d);
            far = i;
        }
    }
    if (!(best > 0.0)) return 1;
    rugo_vec2 axis = rugo_v2_sub(points[far], points[0]);
    rugo_real len = sqrt(best), limit = 1e-9 * sqrt(diag2);
    for (int i = 1; i < count; ++i)
        if (fabs(rugo_v2_cross(rugo_v2_sub(points[i], points[0]), axis)) / len > limit) return 0;
    return 1;
}

rugo_status rugo_contour_check(const rugo_vec2* points, int count, int flags, rugo_contour_problem* problem,
                               const rugo_allocator* allocator) {
    if (problem) {
        problem->index = -1;
        problem->segment_a = -1;
        problem->segment_b = -1;
        problem->where = rugo_v2(0.0, 0.0);
    }
    if (points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (count < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if ((flags & RUGO_CHECK_POWER_OF_TWO) && !rugo__is_power_of_two(count)) return RUGO_ERR_NOT_POWER_OF_TWO;
    for (int i = 0; i < count; ++i) {
        if (!rugo__v2_finite(points[i])) {
            if (problem) problem->index = i;
            return RUGO_ERR_NOT_FINITE;
        }
    }
    rugo_contour c;
    c.points = points;
    c.count = count;
    rugo_vec2 lower, upper;
    rugo_contour_bounds(c, &lower, &upper);
    rugo_vec2 e = rugo_v2_sub(upper, lower);
    rugo_real diag2 = rugo_v2_dot(e, e);
    rugo_real area = rugo_contour_signed_area(c);
    /* Coordinates beyond ~1e150 have no representable area: that is an overflow, not a flat outline. */
    if (!isfinite(diag2) || !isfinite(area)) return RUGO_ERR_NOT_FINITE;
    if (!(fabs(area) > 1e-12 * diag2)) {
        /* A figure eight with equal lobes has zero net area but is really a crossing outline: say so
         * when the crossing test was asked for and the outline is not flat. */
        if ((flags & RUGO_CHECK_SELF_INTERSECTION) && !collinear(points, count, diag2)) {
            rugo_status st = check_crossings(c, lower, upper, problem, allocator);
            if (st != RUGO_OK) return st;
        }
        return RUGO_ERR_ZERO_AREA;
    }
    if (flags & RUGO_CHECK_SELF_INTERSECTION) return check_crossings(c, lower, upper, problem, allocator);
    return RUGO_OK;
}
