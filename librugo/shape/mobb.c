/* Oriented boxes and the MOBBtree (SPEC 5; thesis chapters 3-4).
 *
 * Boxes are (centre, axis[0], axis[1] = perp(axis[0]), half-extents). Every extent is computed
 * relative to a nearby point (a segment's start, a box's centre) rather than the origin, so that
 * shapes far from the origin keep their precision.
 *
 * Tree layout: one array, level by level from the coarsest: node (j, k) sits at
 * (2^j - 2^J_min) + k, so the tree has 2^(J+1) - 2^J_min nodes. The build is bottom-up, O(1) per node
 * (a leaf box, or one coarse segment box plus two enclosures), hence O(n). The tree header and its
 * nodes are one allocation.
 *
 * Speed (issue 7: at most 100 ns per segment at 4096 segments; fig4_5_build_time measures it and
 * docs/benchmarks.md has the figures). Every node costs one segment box, a chain of four square roots
 * and five divisions, so segments are boxed a block at a time, one step over the whole block after
 * the other, stored column-wise and without jumps (see "Leaf box of a segment"): the chains of
 * neighbouring segments overlap, and the steps' loops vectorise (the build gives this file
 * -fno-math-errno, without which no compiler may vectorise sqrt). The covariance of the 5 samples
 * comes in closed form from (3.8)'s coefficients; arc lengths are computed only where they decide
 * something (l_min > 0, method (a)'s weights); square roots of sums of squares replace hypot() where
 * the magnitudes make that safe; a parent encloses its children in one step. The boxes agree with the
 * straightforward computation's to a few ulps of their coordinates (test_tree_matches_reference and
 * test_leaf_box_matches_reference keep that computation and pin it), and are the same bits whether
 * the loops are vectorised or not.
 *
 * Upper boxes enclose their two children's boxes, so the tree is nested: a parent contains everything
 * its children contain (descendant leaves with their band, and the children's own coarse segments).
 * That containment, not Theorem 4.2 (heuristic with these filters, SPEC 5.3), is what makes the boxes
 * conservative.
 *
 * One concept, one file, though over 800 lines: the box primitives, the blocks of segment boxes and the
 * tree are the stages of one build, tied by static inline helpers (min_of/max_of, the covariance axes,
 * box_from_extents, the enclosure steps) that every stage calls and that must inline into the build's
 * hot loops, compiled with this file's -fno-math-errno so that they vectorise. The public box functions
 * (overlap, containment, corners, enclosure) are a few lines on the same helpers; moving them, or a
 * stage, elsewhere would only put those helpers in a header and spread the flag. */
#include "rugo/mobb.h"

#include "core/internal.h"
#include "shape/internal.h" /* rugo__mobb_tree_from_nodes */

#include <float.h>
#include <stddef.h> /* offsetof */
#include <string.h>

/* "RUGM": catches defs that did not come from rugo_default_mobb_tree_def. */
#define MOBB_DEF_COOKIE 0x5255474D

/* Covariances whose off-diagonal term (or eigenvalue gap) is this small relative to the trace are
 * treated as axis-aligned (or isotropic): the eigenvectors are then round-off noise, while any axes
 * give a valid box. */
#define COVARIANCE_DEGENERATE 1e-12

/* Relative slack of the separating-axis test: an axis separates only beyond the round-off of the
 * projections (a few ulps of the quantities compared, centres included: a box placed at x ~ 1e3 is only
 * known to ~1e-13), so touching boxes report an overlap. */
#define SAT_SLACK (16.0 * DBL_EPSILON)

/* Round-off pad of tree boxes, relative to the box's position and size: covers the few roundings of
 * building a box (centre shifts, projections) and of evaluating the curve elsewhere, so that the
 * tree's containment invariant holds for computed points without any slack. The public primitives
 * (rugo_segment_box, rugo_obb_enclose) stay exact, e.g. a straight axis-aligned segment has zero
 * thickness there. */
#define TREE_PAD (64.0 * DBL_EPSILON)

/* Covariance moments up to this size relative to 1 (squared lengths) have squares that neither overflow
 * nor underflow where they matter, so sqrt(x^2 + y^2) may replace hypot(x, y) (several times faster;
 * both are within about an ulp of the true value). Segments from ~1e-50 to ~1e50 units qualify. */
#define PLAIN_SQRT_RANGE 1e100

struct rugo_mobb_tree {
    rugo_allocator allocator;
    int finest, coarsest;
    rugo_box_method method;
    rugo_obb* nodes; /* 2^(finest+1) - 2^coarsest boxes, level by level from the coarsest; they follow
                        the header in the same allocation */
    rugo_obb root;
};

/* fmin and fmax for numbers (of two equal values, signed zeros included, the first is returned, as
 * glibc does), inline and without jumps (one minsd/maxsd): the library calls cost more than the
 * comparisons. A NaN second argument is skipped, as fmin/fmax do; a NaN first argument is returned. */
static inline rugo_real min_of(rugo_real a, rugo_real b) { return b < a ? b : a; }
static inline rugo_real max_of(rugo_real a, rugo_real b) { return b > a ? b : a; }

/* ---------------------------------------------------------------------------------------------------
 * Box primitives */

/* The major axis (ex, ey) of the symmetric matrix [[a, b], [b, c]] (SPEC 5.1) in the common case, a
 * non-degenerate matrix of moderate size: returns 1 then, else 0 (and (ex, ey) are meaningless). With
 * d = sqrt((a-c)^2 + 4b^2) and λ1 = (a + c + d)/2, the two cancellation-free eigenvectors (λ1 - c, b)
 * and (b, λ1 - a) point the same way once the second is multiplied by sign(b), so their sum is one too,
 * cancellation-free in both components, with the canonical sign (e.x > 0) built in. Selects of numbers
 * rather than && of conditions and sqrt of sums of squares rather than hypot: no jumps and no library
 * calls, so that block_axes' loop vectorises. In the plain range the squares neither overflow nor lose
 * the digits that count (|a - c|, |2b| <= trace, and past the test |b| > 1e-12 trace). NaN gives 0. */
static inline rugo_real plain_major_axis(rugo_real a, rugo_real b, rugo_real c, rugo_real* ex,
                                         rugo_real* ey) {
    rugo_real trace = a + c, p = a - c, b2 = 2.0 * b;
    rugo_real d = sqrt(p * p + b2 * b2);
    rugo_real plain = trace > 1.0 / PLAIN_SQRT_RANGE ? 1.0 : 0.0;
    plain = trace < PLAIN_SQRT_RANGE ? plain : 0.0;
    plain = fabs(b) > COVARIANCE_DEGENERATE * trace ? plain : 0.0;
    plain = d > COVARIANCE_DEGENERATE * trace ? plain : 0.0;
    rugo_real xx = 0.5 * (p + d) + fabs(b), xy = b + copysign(0.5 * (d - p), b);
    rugo_real inv = 1.0 / sqrt(xx * xx + xy * xy);
    *ex = xx * inv;
    *ey = xy * inv;
    return plain;
}

/* Unit major axis of the symmetric matrix [[a, b], [b, c]] (SPEC 5.1), coordinate axes when
 * degenerate: plain_major_axis, or in general the eigenvector of λ1 = (a + c + d)/2,
 * d = hypot(a - c, 2b), written in the form that avoids cancellation: (λ1 - c, b) when a >= c, else
 * (b, λ1 - a). */
static void axes_from_covariance(rugo_real a, rugo_real b, rugo_real c, rugo_vec2 axis[2]) {
    rugo_vec2 e;
    if (!(plain_major_axis(a, b, c, &e.x, &e.y) > 0.0)) {
        rugo_real trace = a + c;
        rugo_real d = hypot(a - c, 2.0 * b);
        e = rugo_v2(1.0, 0.0);
        if (isfinite(d) && trace > 0.0 && fabs(b) > COVARIANCE_DEGENERATE * trace &&
            d > COVARIANCE_DEGENERATE * trace) {
            rugo_vec2 x = a >= c ? rugo_v2(0.5 * (a - c + d), b) : rugo_v2(b, 0.5 * (c - a + d));
            rugo_real len = rugo__v2_length(x);
            if (len > 0.0 && isfinite(len)) {
                e = rugo_v2(x.x / len, x.y / len);
                /* A canonical sign, so equal inputs give equal boxes whatever the sample order. */
                if (e.x < 0.0 || (e.x == 0.0 && e.y < 0.0)) e = rugo_v2(-e.x, -e.y);
            }
        }
    }
    axis[0] = e;
    axis[1] = rugo_v2_perp(e);
}

/* Covariance axes of n >= 1 points: the mean (3.5: (1/n) Σ p_k), then the centred second moments
 * (the 1/n factor does not change the eigenvectors). Centring about the first point first keeps
 * far-from-origin data precise. */
static void points_axes(const rugo_vec2* points, int n, rugo_vec2 axis[2]) {
    rugo_vec2 o = points[0], mean = rugo_v2(0.0, 0.0);
    for (int i = 0; i < n; ++i)
        mean = rugo_v2_add(mean, rugo_v2_sub(points[i], o));
    mean = rugo_v2_scale(1.0 / (rugo_real)n, mean);
    rugo_real a = 0.0, b = 0.0, c = 0.0;
    for (int i = 0; i < n; ++i) {
        rugo_vec2 q = rugo_v2_sub(rugo_v2_sub(points[i], o), mean);
        a += q.x * q.x;
        b += q.x * q.y;
        c += q.y * q.y;
    }
    axes_from_covariance(a, b, c, axis);
}

void rugo_covariance_axes(const rugo_vec2* points, int n, rugo_vec2 axis[2]) {
    if (axis == NULL) return;
    if (points == NULL || n < 1) {
        axes_from_covariance(0.0, 0.0, 0.0, axis);
        return;
    }
    points_axes(points, n, axis);
}

/* Extent interval [lo, hi] of a box along unit axis e, relative to the point o. */
static inline void box_interval(const rugo_obb* b, rugo_vec2 o, rugo_vec2 e, rugo_real* lo, rugo_real* hi) {
    rugo_real m = rugo_v2_dot(rugo_v2_sub(b->center, o), e);
    rugo_real r =
        b->half[0] * fabs(rugo_v2_dot(b->axis[0], e)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], e));
    *lo = m - r;
    *hi = m + r;
}

/* The box with axes `axis`, whose extents relative to o are [lo_i, hi_i] along axis i. */
static rugo_obb box_from_intervals(const rugo_vec2 axis[2], rugo_vec2 o, const rugo_real lo[2],
                                   const rugo_real hi[2]) {
    rugo_obb r;
    r.axis[0] = axis[0];
    r.axis[1] = axis[1];
    r.center = o;
    for (int i = 0; i < 2; ++i) {
        r.center = rugo_v2_add(r.center, rugo_v2_scale(0.5 * (lo[i] + hi[i]), axis[i]));
        r.half[i] = 0.5 * (hi[i] - lo[i]);
        if (!(r.half[i] >= 0.0)) r.half[i] = 0.0; /* only round-off can make hi < lo */
    }
    return r;
}

/* The same with axes (e, perp(e)) and the intervals as scalars, inline (the build's hot path: arrays
 * written as scalars and read back as vectors stall store forwarding). */
static inline rugo_obb box_from_extents(rugo_vec2 e, rugo_vec2 o, rugo_real lo0, rugo_real hi0, rugo_real lo1,
                                        rugo_real hi1, rugo_real zero) {
    rugo_obb r;
    r.axis[0] = e;
    r.axis[1] = rugo_v2_perp(e);
    rugo_real m0 = 0.5 * (lo0 + hi0), m1 = 0.5 * (lo1 + hi1);
    r.center = rugo_v2_add(rugo_v2_add(o, rugo_v2_scale(m0, r.axis[0])), rugo_v2_scale(m1, r.axis[1]));
    rugo_real h0 = 0.5 * (hi0 - lo0), h1 = 0.5 * (hi1 - lo1);
    r.half[0] = max_of(h0, zero); /* only round-off can make hi < lo */
    r.half[1] = max_of(h1, zero);
    return r;
}

/* Grows `box` (axes fixed; sides and centre move) until it also contains b. */
static inline void grow_to_contain(rugo_obb* box, const rugo_obb* b) {
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        rugo_real blo, bhi;
        box_interval(b, box->center, box->axis[i], &blo, &bhi);
        lo[i] = min_of(-box->half[i], blo);
        hi[i] = max_of(box->half[i], bhi);
    }
    if (lo[0] < -box->half[0] || hi[0] > box->half[0] || lo[1] < -box->half[1] || hi[1] > box->half[1])
        *box = box_from_intervals(box->axis, box->center, lo, hi);
}

/* Centre offset (m0, m1) and reach (r0, r1) of box b along e and perp(e), measured from o, for a box
 * whose axis[1] = perp(axis[0]) (the tree's are): then |axis[1]·e| = |axis[0]·perp(e)| and
 * |axis[1]·perp(e)| = |axis[0]·e|, the very same products, so box_interval's numbers come out of two
 * dot products instead of four. */
static inline void tree_box_interval(const rugo_obb* b, rugo_vec2 o, rugo_vec2 e, rugo_real* m0,
                                     rugo_real* r0, rugo_real* m1, rugo_real* r1) {
    rugo_vec2 d = rugo_v2_sub(b->center, o), f = rugo_v2_perp(e);
    rugo_real c0 = fabs(rugo_v2_dot(b->axis[0], e)), c1 = fabs(rugo_v2_dot(b->axis[0], f));
    *m0 = rugo_v2_dot(d, e);
    *m1 = rugo_v2_dot(d, f);
    *r0 = b->half[0] * c0 + b->half[1] * c1;
    *r1 = b->half[0] * c1 + b->half[1] * c0;
}

/* `box` grown (axes fixed; sides and centre move) until it also contains a and b: one enclosure of
 * three intervals per axis, measured from box's centre. zero: +0 (see projection_extremes). */
static inline rugo_obb box_grown_by_pair(const rugo_obb* box, const rugo_obb* a, const rugo_obb* b,
                                         rugo_real zero) {
    rugo_real am0, ar0, am1, ar1, bm0, br0, bm1, br1;
    tree_box_interval(a, box->center, box->axis[0], &am0, &ar0, &am1, &ar1);
    tree_box_interval(b, box->center, box->axis[0], &bm0, &br0, &bm1, &br1);
    rugo_real lo0 = min_of(min_of(-box->half[0], am0 - ar0), bm0 - br0);
    rugo_real hi0 = max_of(max_of(box->half[0], am0 + ar0), bm0 + br0);
    rugo_real lo1 = min_of(min_of(-box->half[1], am1 - ar1), bm1 - br1);
    rugo_real hi1 = max_of(max_of(box->half[1], am1 + ar1), bm1 + br1);
    return box_from_extents(box->axis[0], box->center, lo0, hi0, lo1, hi1, zero);
}

rugo_obb rugo_obb_enclose(rugo_obb box_with_axes, const rugo_obb* b) {
    if (b == NULL) return box_with_axes;
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i)
        box_interval(b, b->center, box_with_axes.axis[i], &lo[i], &hi[i]);
    return box_from_intervals(box_with_axes.axis, b->center, lo, hi);
}

rugo_obb rugo_obb_transform(rugo_transform t, const rugo_obb* b) {
    rugo_obb r;
    if (b == NULL) {
        memset(&r, 0, sizeof r);
        return r;
    }
    r.center = rugo_transform_point(t, b->center);
    r.axis[0] = rugo_rotate(t.q, b->axis[0]);
    r.axis[1] = rugo_rotate(t.q, b->axis[1]);
    r.half[0] = b->half[0];
    r.half[1] = b->half[1];
    return r;
}

/* Projected radius of a box on the unit axis l (6.8): the larger half-diagonal projection. */
static rugo_real projected_radius(const rugo_obb* b, rugo_vec2 l) {
    return b->half[0] * fabs(rugo_v2_dot(b->axis[0], l)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], l));
}

bool rugo_obb_overlap(const rugo_obb* a, const rugo_obb* b) {
    if (a == NULL || b == NULL) return false;
    rugo_vec2 t = rugo_v2_sub(b->center, a->center);
    rugo_real position =
        fmax(fmax(fabs(a->center.x), fabs(a->center.y)), fmax(fabs(b->center.x), fabs(b->center.y)));
    const rugo_vec2 axes[4] = {a->axis[0], a->axis[1], b->axis[0], b->axis[1]};
    for (int i = 0; i < 4; ++i) {
        rugo_real dist = fabs(rugo_v2_dot(t, axes[i]));
        rugo_real reach = projected_radius(a, axes[i]) + projected_radius(b, axes[i]);
        /* Disjoint iff |T·L| > r_A + r_B (6.7); the slack keeps exact touching (and touching up to
         * round-off) an overlap. Written so that NaN never separates. */
        if (dist - reach > SAT_SLACK * (dist + reach + position)) return false;
    }
    /* The four axes are the edge normals of both rectangles (also when a side has zero length, as
     * for a straight segment's box or a point's box), which suffices for convex polygons. */
    return true;
}

bool rugo_obb_contains(const rugo_obb* b, rugo_vec2 p, rugo_real slack) {
    if (b == NULL) return false;
    rugo_vec2 d = rugo_v2_sub(p, b->center);
    return fabs(rugo_v2_dot(d, b->axis[0])) <= b->half[0] + slack &&
           fabs(rugo_v2_dot(d, b->axis[1])) <= b->half[1] + slack;
}

rugo_real rugo_obb_area(const rugo_obb* b) { return b == NULL ? 0.0 : 4.0 * b->half[0] * b->half[1]; }

void rugo_obb_corners(const rugo_obb* b, rugo_vec2 out[4]) {
    if (b == NULL || out == NULL) return;
    rugo_vec2 u = rugo_v2_scale(b->half[0], b->axis[0]);
    rugo_vec2 v = rugo_v2_scale(b->half[1], b->axis[1]);
    /* Our boxes are right-handed; a caller's left-handed box still gets its corners counter-clockwise. */
    if (rugo_v2_cross(b->axis[0], b->axis[1]) < 0.0) v = rugo_v2_scale(-1.0, v);
    out[0] = rugo_v2_sub(rugo_v2_sub(b->center, u), v);
    out[1] = rugo_v2_sub(rugo_v2_add(b->center, u), v);
    out[2] = rugo_v2_add(rugo_v2_add(b->center, u), v);
    out[3] = rugo_v2_add(rugo_v2_sub(b->center, u), v);
}

/* ---------------------------------------------------------------------------------------------------
 * Leaf box of a segment (SPEC 5.2, thesis 3.3)
 *
 * Segments are boxed a block at a time, in steps that each run over the whole block: the coefficients
 * of (3.8), the start point f(0) and the covariance moments of the samples; the major axes; the
 * extents along both axes. The block is stored column-wise (one array per quantity), and every step
 * is written without jumps, so that the steps' loops are straight sequences of independent
 * arithmetic: the processor overlaps one segment's long chain of square roots and divisions with its
 * neighbours', and a compiler may vectorise them. rugo_segment_box runs the same steps on a block of
 * one segment, so its boxes are the tree's leaves to the bit (before the tree's round-off pad). */

/* Segments per block: enough independent work to hide latencies, little enough to stay in the
 * first-level cache (the block takes 22 numbers a segment). */
enum { SEG_BLOCK = 32 };

typedef struct seg_block {
    /* f'(t) = 1/2 (v t^2 + w t + r) (3.8) */
    rugo_real vx[SEG_BLOCK], vy[SEG_BLOCK], wx[SEG_BLOCK], wy[SEG_BLOCK], rx[SEG_BLOCK], ry[SEG_BLOCK];
    /* the start point f(0) */
    rugo_real sx[SEG_BLOCK], sy[SEG_BLOCK];
    /* covariance moments of the samples */
    rugo_real a[SEG_BLOCK], b[SEG_BLOCK], c[SEG_BLOCK];
    /* unit major axis e (the minor one is perp(e)), and plain_major_axis' answer */
    rugo_real ex[SEG_BLOCK], ey[SEG_BLOCK], plain[SEG_BLOCK];
    /* extents of f(t) - f(0) along e and perp(e), without band */
    rugo_real lo0[SEG_BLOCK], hi0[SEG_BLOCK], lo1[SEG_BLOCK], hi1[SEG_BLOCK];
    /* the tree's boxes (block_tree_boxes): centre and half-extents, band and pad included */
    rugo_real cx[SEG_BLOCK], cy[SEG_BLOCK], h0[SEG_BLOCK], h1[SEG_BLOCK];
} seg_block;

/* Centred second moments S = Σ_i (c_i - c̄)(c_i - c̄)^T of c(t) = (t^3/6, t^2/4, t/2) over the five
 * samples t = 0, 1/4, 1/2, 3/4, 1 (exact fractions). A sample is f(t) - f(0) = [v w r] c(t), so the
 * samples' covariance matrix is [v w r] S [v w r]^T: no samples need to be evaluated. */
#define S_VV (1445.0 / 73728.0)
#define S_VW (175.0 / 6144.0)
#define S_VR (77.0 / 1536.0)
#define S_WW (87.0 / 2048.0)
#define S_WR (5.0 / 64.0)
#define S_RR (5.0 / 32.0)

/* Step 1, for segments whose control points c_{j-1} .. c_{j+2} are q[i .. i+3]: (3.8)'s coefficients
 * and the start point b0 = f(0), by the operations of rugo_contour_derivative_coefficients and
 * rugo_contour_bezier (so the same bits), and the moments of 5 evenly spaced samples, ends included
 * (3.3.1). */
static void block_coefficients(const rugo_vec2* q, int count, seg_block* s) {
    for (int i = 0; i < count; ++i) {
        rugo_vec2 q0 = q[i], q1 = q[i + 1], q2 = q[i + 2], q3 = q[i + 3];
        rugo_real vx = q3.x - 3.0 * q2.x + 3.0 * q1.x - q0.x, vy = q3.y - 3.0 * q2.y + 3.0 * q1.y - q0.y;
        rugo_real wx = 2.0 * q2.x - 4.0 * q1.x + 2.0 * q0.x, wy = 2.0 * q2.y - 4.0 * q1.y + 2.0 * q0.y;
        rugo_real rx = q2.x - q0.x, ry = q2.y - q0.y;
        s->vx[i] = vx;
        s->vy[i] = vy;
        s->wx[i] = wx;
        s->wy[i] = wy;
        s->rx[i] = rx;
        s->ry[i] = ry;
        s->sx[i] = (q0.x + 4.0 * q1.x + q2.x) / 6.0;
        s->sy[i] = (q0.y + 4.0 * q1.y + q2.y) / 6.0;
        rugo_real sx0 = S_VV * vx + S_VW * wx + S_VR * rx;
        rugo_real sx1 = S_VW * vx + S_WW * wx + S_WR * rx;
        rugo_real sx2 = S_VR * vx + S_WR * wx + S_RR * rx;
        rugo_real sy0 = S_VV * vy + S_VW * wy + S_VR * ry;
        rugo_real sy1 = S_VW * vy + S_WW * wy + S_WR * ry;
        rugo_real sy2 = S_VR * vy + S_WR * wy + S_RR * ry;
        s->a[i] = vx * sx0 + wx * sx1 + rx * sx2;
        s->b[i] = vy * sx0 + wy * sx1 + ry * sx2;
        s->c[i] = vy * sy0 + wy * sy1 + ry * sy2;
    }
}

/* Step 1 for a segment no longer than l_min: the moments of its 2 ends, 0 and p = f(1) - f(0)
 * (centred: p p^T / 2). */
static void block_two_samples(seg_block* s, int i) {
    rugo_real px = (1.0 / 6.0) * s->vx[i] + 0.25 * s->wx[i] + 0.5 * s->rx[i];
    rugo_real py = (1.0 / 6.0) * s->vy[i] + 0.25 * s->wy[i] + 0.5 * s->ry[i];
    s->a[i] = 0.5 * px * px;
    s->b[i] = 0.5 * px * py;
    s->c[i] = 0.5 * py * py;
}

/* Step 2: the major axes (plain_major_axis, vectorisable; the rare others afterwards). */
static void block_axes(seg_block* s, int count) {
    for (int i = 0; i < count; ++i)
        s->plain[i] = plain_major_axis(s->a[i], s->b[i], s->c[i], &s->ex[i], &s->ey[i]);
    for (int i = 0; i < count; ++i)
        if (!(s->plain[i] > 0.0)) {
            rugo_vec2 axis[2];
            axes_from_covariance(s->a[i], s->b[i], s->c[i], axis);
            s->ex[i] = axis[0].x;
            s->ey[i] = axis[0].y;
        }
}

/* The extremes of the projection h(t) = (f(t) - f(0))·e on [0, 1], e a unit axis: the ends and the
 * roots in [0, 1] of f'(t)·e = 1/2 (α t^2 + β t + γ), α = v·e, β = w·e, γ = r·e (3.9-3.10, with the
 * errata's correction), by one stable formula, q = -(β + sign(β) sqrt(β^2 - 4αγ))/2, roots q/α and
 * γ/q, whatever the case:
 *   α ≠ 0:          the two roots, without cancellation;
 *   α = 0, β ≠ 0:   LINEAR (the v·e = 0 case): q = -β, the root γ/q = -γ/β (and q/α = ±inf);
 *   α = β = 0:      f'·e = γ is constant: no interior extreme, the ends decide (0/0 and γ/0);
 *   α = β = γ = 0:  a straight segment perpendicular to e (or a point): h ≡ 0, zero thickness.
 * There are no jumps: a candidate outside [0, 1] or infinite is clamped to an end, where h is known
 * anyway, a NaN one gives h = NaN, which the comparisons skip, and a negative discriminant (complex
 * roots, or a double root perturbed by round-off) is taken as 0. That is safe because any t in
 * [0, 1] is a point of the curve: an extra candidate can never widen the extent, only a missed root
 * could narrow it, and real roots keep their discriminant. h(t) = ((α/6 t + β/4) t + γ/2) t,
 * h(0) = 0. `zero` is +0 computed at run time: given the constant, compilers turn the clamps into
 * jumps, which mispredict often here; with a variable they are one maxsd/minsd each. */
static inline void projection_extremes(rugo_real alpha, rugo_real beta, rugo_real gamma, rugo_real zero,
                                       rugo_real* lo, rugo_real* hi) {
    rugo_real one = zero + 1.0;
    rugo_real a6 = alpha * (1.0 / 6.0), b4 = 0.25 * beta, g2 = 0.5 * gamma;
    rugo_real s2 = sqrt(max_of(beta * beta - 4.0 * alpha * gamma, zero));
    rugo_real q = -0.5 * (beta + copysign(s2, beta));
    rugo_real t1 = min_of(max_of(q / alpha, zero), one), t2 = min_of(max_of(gamma / q, zero), one);
    rugo_real h1 = (a6 + b4) + g2;
    rugo_real ht1 = ((a6 * t1 + b4) * t1 + g2) * t1;
    rugo_real ht2 = ((a6 * t2 + b4) * t2 + g2) * t2;
    *lo = min_of(min_of(min_of(zero, h1), ht1), ht2);
    *hi = max_of(max_of(max_of(zero, h1), ht1), ht2);
}

/* Step 3: the extents along e and perp(e) = (-e.y, e.x). */
static void block_extents(seg_block* s, int count, rugo_real zero) {
    for (int i = 0; i < count; ++i) {
        rugo_real ex = s->ex[i], ey = s->ey[i];
        rugo_real vx = s->vx[i], vy = s->vy[i], wx = s->wx[i], wy = s->wy[i], rx = s->rx[i], ry = s->ry[i];
        rugo_real lo0, hi0, lo1, hi1;
        projection_extremes(vx * ex + vy * ey, wx * ex + wy * ey, rx * ex + ry * ey, zero, &lo0, &hi0);
        projection_extremes(vy * ex - vx * ey, wy * ex - wx * ey, ry * ex - rx * ey, zero, &lo1, &hi1);
        s->lo0[i] = lo0;
        s->hi0[i] = hi0;
        s->lo1[i] = lo1;
        s->hi1[i] = hi1;
    }
}

/* Gauss-Legendre nodes and weights on [0, 1], 4 points: the rule (3.6)-(3.7) for method (a)'s weights. */
static const rugo_real GL4_X[4] = {0.06943184420297371238802676, 0.3300094782075718675986671,
                                   0.6699905217924281324013329, 0.9305681557970262876119732};
static const rugo_real GL4_W[4] = {0.173927422568726928686532, 0.326072577431273071313468,
                                   0.326072577431273071313468, 0.173927422568726928686532};

/* Arc lengths of the block's segments for method (a)'s weights, which are neither reported nor used to
 * place anything (the certified length, rugo_contour_segment_length, costs 40 times as much on a rough
 * outline): the thesis' rule (3.6)-(3.7), ∫ |f'| by 4-point Gauss-Legendre with
 * f' = 1/2 (v t^2 + w t + r), sqrt of a sum of squares instead of hypot (a weight needs no more). */
static void block_lengths(const seg_block* s, int count, rugo_real* lengths) {
    for (int i = 0; i < count; ++i) {
        rugo_real sum = 0.0;
        for (int g = 0; g < 4; ++g) {
            rugo_real t = GL4_X[g];
            rugo_real dx = (s->vx[i] * t + s->wx[i]) * t + s->rx[i],
                      dy = (s->vy[i] * t + s->wy[i]) * t + s->ry[i];
            sum += GL4_W[g] * sqrt(dx * dx + dy * dy);
        }
        lengths[i] = 0.5 * sum;
    }
}

/* Whether a segment of arc length `length` gets 5 samples: it exceeds l_min. At l_min = 0 the answer
 * is yes without computing the length: a zero length means a segment shrunk to a point, whose 5 and 2
 * samples are the same zeros (and a length that underflows to 0, below 1e-308, is no real case). */
static inline int five_samples(rugo_real length, rugo_real min_length) {
    return !(min_length > 0.0) || length > min_length;
}

/* Steps 1-3 for segments k0 .. k0 + count - 1 of c (count <= SEG_BLOCK, k0 in [0, c.count)). When
 * `lengths` is not NULL it receives their arc lengths (block_lengths). zero: +0 (see
 * projection_extremes). */
static void segment_block(rugo_contour c, int k0, int count, rugo_real min_length, rugo_real zero,
                          seg_block* s, rugo_real* lengths) {
    /* The control points c_{k0-1} .. c_{k0+count+1}, wrapped around, in a row. */
    rugo_vec2 q[SEG_BLOCK + 3];
    const int m = c.count;
    if (k0 >= 1 && k0 + count + 1 < m) {
        memcpy(q, c.points + (k0 - 1), (size_t)(count + 3) * sizeof *q);
    } else {
        for (int i = 0; i < count + 3; ++i)
            q[i] = c.points[rugo__wrap(k0 - 1 + i, m)];
    }
    block_coefficients(q, count, s);
    /* l_min is compared with rugo_contour_segment_length itself: the same decision as rugo_segment_box's
     * at any l_min. */
    if (min_length > 0.0)
        for (int i = 0; i < count; ++i)
            if (!five_samples(rugo_contour_segment_length(c, k0 + i), min_length)) block_two_samples(s, i);
    if (lengths != NULL) block_lengths(s, count, lengths);
    block_axes(s, count);
    block_extents(s, count, zero);
}

/* The box of segment i of the block: its extents grown by band on every side, the centre following from
 * them (the sample mean is not the box centre, 3.3.2). */
static inline rugo_obb block_box(const seg_block* s, int i, rugo_real band, rugo_real zero) {
    return box_from_extents(rugo_v2(s->ex[i], s->ey[i]), rugo_v2(s->sx[i], s->sy[i]), s->lo0[i] - band,
                            s->hi0[i] + band, s->lo1[i] - band, s->hi1[i] + band, zero);
}

/* Step 4, the tree's: the boxes of the whole block (block_box's operations, so the same bits), segment
 * i grown by band[i], then by the tree's round-off pad (padded's operations), column-wise. */
static void block_tree_boxes(seg_block* s, int count, const rugo_real* band, rugo_real zero) {
    for (int i = 0; i < count; ++i) {
        rugo_real lo0 = s->lo0[i] - band[i], hi0 = s->hi0[i] + band[i];
        rugo_real lo1 = s->lo1[i] - band[i], hi1 = s->hi1[i] + band[i];
        rugo_real ex = s->ex[i], ey = s->ey[i];
        rugo_real m0 = 0.5 * (lo0 + hi0), m1 = 0.5 * (lo1 + hi1);
        rugo_real cx = (s->sx[i] + m0 * ex) + m1 * -ey, cy = (s->sy[i] + m0 * ey) + m1 * ex;
        rugo_real h0 = max_of(0.5 * (hi0 - lo0), zero), h1 = max_of(0.5 * (hi1 - lo1), zero);
        rugo_real pad = TREE_PAD * ((max_of(fabs(cx), fabs(cy)) + h0) + h1);
        s->cx[i] = cx;
        s->cy[i] = cy;
        s->h0[i] = h0 + pad;
        s->h1[i] = h1 + pad;
    }
}

/* Box i of block_tree_boxes. */
static inline rugo_obb block_tree_box(const seg_block* s, int i) {
    rugo_obb b;
    b.center = rugo_v2(s->cx[i], s->cy[i]);
    b.axis[0] = rugo_v2(s->ex[i], s->ey[i]);
    b.axis[1] = rugo_v2_perp(b.axis[0]);
    b.half[0] = s->h0[i];
    b.half[1] = s->h1[i];
    return b;
}

rugo_obb rugo_segment_box(rugo_contour c, int segment, rugo_real band, rugo_real min_length) {
    if (c.points == NULL || c.count < 1) {
        rugo_obb z;
        memset(&z, 0, sizeof z);
        z.axis[0] = rugo_v2(1.0, 0.0);
        z.axis[1] = rugo_v2(0.0, 1.0);
        return z;
    }
    if (!(band >= 0.0)) band = 0.0;
    /* l_min < 0 means 5 samples, as 0 does; NaN means 2 (no length exceeds it), as infinity does */
    if (isnan(min_length)) min_length = INFINITY;
    if (min_length < 0.0) min_length = 0.0;
    seg_block s;
    segment_block(c, rugo__wrap(segment, c.count), 1, min_length, 0.0, &s, NULL);
    return block_box(&s, 0, band, 0.0);
}

/* ---------------------------------------------------------------------------------------------------
 * The tree */

rugo_mobb_tree_def rugo_default_mobb_tree_def(void) {
    rugo_mobb_tree_def d;
    memset(&d, 0, sizeof d);
    d.pyramid = NULL;
    d.tolerances = NULL;
    d.method = RUGO_BOXES_MULTIRES;
    d.min_length = 0.0;
    d.cookie = MOBB_DEF_COOKIE;
    return d;
}

/* Arc-length weighted centroid statistics of the descendant leaf boxes' centres (3.11-3.12):
 * total weight, weighted mean and the centred second moments Σ l (p - μ)(p - μ)^T. Merged pairwise
 * (Chan et al.'s update), so each node costs O(1) and stays precise far from the origin. */
typedef struct centre_moments {
    rugo_real weight;
    rugo_vec2 mean;
    rugo_real sxx, sxy, syy;
} centre_moments;

static centre_moments merge_moments(const centre_moments* a, const centre_moments* b) {
    centre_moments m;
    rugo_real wsum = a->weight + b->weight;
    rugo_vec2 d = rugo_v2_sub(b->mean, a->mean);
    /* Zero total weight (every leaf a point): equal weights, whose covariance is still that of points. */
    rugo_real fb = wsum > 0.0 ? b->weight / wsum : 0.5;
    rugo_real cross = wsum > 0.0 ? a->weight * b->weight / wsum : 0.0;
    m.weight = wsum;
    m.mean = rugo_v2_add(a->mean, rugo_v2_scale(fb, d));
    m.sxx = a->sxx + b->sxx + cross * d.x * d.x;
    m.sxy = a->sxy + b->sxy + cross * d.x * d.y;
    m.syy = a->syy + b->syy + cross * d.y * d.y;
    return m;
}

static inline rugo_obb padded(rugo_obb b) {
    rugo_real pad = TREE_PAD * (max_of(fabs(b.center.x), fabs(b.center.y)) + b.half[0] + b.half[1]);
    b.half[0] += pad;
    b.half[1] += pad;
    return b;
}

static size_t level_offset(int level, int coarsest) { return ((size_t)1 << level) - ((size_t)1 << coarsest); }

/* The box with axes (e, perp(e)) enclosing the boxes a, b and c (axes perp-paired, as the tree's are),
 * measured from a's centre. zero: +0 (see projection_extremes). */
static rugo_obb box_enclosing_three(rugo_vec2 e, const rugo_obb* a, const rugo_obb* b, const rugo_obb* c,
                                    rugo_real zero) {
    rugo_real am0, ar0, am1, ar1, bm0, br0, bm1, br1, cm0, cr0, cm1, cr1;
    tree_box_interval(a, a->center, e, &am0, &ar0, &am1, &ar1);
    tree_box_interval(b, a->center, e, &bm0, &br0, &bm1, &br1);
    tree_box_interval(c, a->center, e, &cm0, &cr0, &cm1, &cr1);
    rugo_real lo0 = min_of(min_of(am0 - ar0, bm0 - br0), cm0 - cr0);
    rugo_real hi0 = max_of(max_of(am0 + ar0, bm0 + br0), cm0 + cr0);
    rugo_real lo1 = min_of(min_of(am1 - ar1, bm1 - br1), cm1 - cr1);
    rugo_real hi1 = max_of(max_of(am1 + ar1, bm1 + br1), cm1 + cr1);
    return box_from_extents(e, a->center, lo0, hi0, lo1, hi1, zero);
}

static rugo_real value_or_zero(const rugo_real* values, int k) {
    return values != NULL && values[k] > 0.0 ? values[k] : 0.0;
}

/* The tree's boxes of segments k0 .. k0 + count - 1 (count <= SEG_BLOCK, within the level) of a level's
 * contour c into s (block_tree_boxes; block_tree_box reads them), padded, segment k thickened by
 * max(bound[k], total[k]) (either may be NULL = 0). l_min decides the samples as in rugo_segment_box;
 * when `lengths` is not NULL it receives the segments' arc lengths. zero: +0, see projection_extremes. */
static void level_boxes(rugo_contour c, int k0, int count, const rugo_real* bound, const rugo_real* total,
                        rugo_real min_length, rugo_real zero, seg_block* s, rugo_real* lengths) {
    rugo_real band[SEG_BLOCK];
    for (int i = 0; i < count; ++i)
        band[i] = max_of(value_or_zero(bound, k0 + i), value_or_zero(total, k0 + i));
    segment_block(c, k0, count, min_length, zero, s, lengths);
    block_tree_boxes(s, count, band, zero);
}

/* A tree with room for its nodes, header and nodes in one block (the header padded to whole boxes, so
 * the nodes are aligned like any rugo_obb array). Fields other than the levels, method and allocator
 * are zero. NULL when out of memory. */
static rugo_mobb_tree* tree_alloc(const rugo_allocator* alloc, int finest, int coarsest,
                                  rugo_box_method method) {
    const size_t header = (sizeof(rugo_mobb_tree) + sizeof(rugo_obb) - 1) / sizeof(rugo_obb);
    const size_t count = level_offset(finest + 1, coarsest);
    rugo_obb* block = (rugo_obb*)rugo__alloc_array(alloc, header + count, sizeof(rugo_obb));
    if (block == NULL) return NULL;
    rugo_mobb_tree* tree = (rugo_mobb_tree*)(void*)block;
    memset(tree, 0, sizeof *tree);
    tree->allocator = *alloc;
    tree->finest = finest;
    tree->coarsest = coarsest;
    tree->method = method;
    tree->nodes = block + header;
    return tree;
}

rugo_status rugo_mobb_tree_create(const rugo_mobb_tree_def* def, rugo_mobb_tree** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (def == NULL || def->pyramid == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != MOBB_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (def->method != RUGO_BOXES_MULTIRES && def->method != RUGO_BOXES_OF_BOXES)
        return RUGO_ERR_BAD_ARGUMENT;
    if (!isfinite(def->min_length) || def->min_length < 0.0) return RUGO_ERR_BAD_ARGUMENT;

    const rugo_pyramid* pyr = def->pyramid;
    int fine = rugo_pyramid_finest_level(pyr), coarse = rugo_pyramid_coarsest_level(pyr);
    if (coarse < 0 || fine < coarse || fine > 30) return RUGO_ERR_BAD_LEVEL;
    const rugo_tolerances* tol = def->tolerances;
    if (tol != NULL &&
        (rugo_tolerances_finest_level(tol) != fine || rugo_tolerances_coarsest_level(tol) != coarse))
        return RUGO_ERR_BAD_LEVEL;

    rugo_allocator alloc = rugo__allocator_or_default(&def->allocator);
    const size_t n = (size_t)1 << fine;
    const rugo_real min_length = def->min_length;
    const rugo_real zero = min_length * 0.0; /* +0: min_length is finite and >= 0 */
    rugo_mobb_tree* tree = tree_alloc(&alloc, fine, coarse, def->method);
    if (tree == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    /* Method (a) keeps the centre statistics of one level at a time, merged in place (k <= 2k). */
    centre_moments* mom = NULL;
    if (def->method == RUGO_BOXES_OF_BOXES) {
        mom = (centre_moments*)rugo__alloc_array(&alloc, n, sizeof *mom);
        if (mom == NULL) {
            rugo_mobb_tree_destroy(tree);
            return RUGO_ERR_OUT_OF_MEMORY;
        }
    }

    rugo_status st = RUGO_OK;
    seg_block s; /* one block of segments in the making */
    /* Leaves: the basic boxes, each thickened by the finest hard bound β^J_k (never below λ^J_k, so
     * that invariant (ii) holds at the finest level too). Arc lengths are computed only where they
     * are used: against a positive l_min, and as method (a)'s weights. */
    {
        rugo_contour c;
        rugo_tolerance_level tl;
        memset(&tl, 0, sizeof tl);
        st = rugo_pyramid_level(pyr, fine, &c);
        if (st == RUGO_OK && tol != NULL) st = rugo_tolerances_level(tol, fine, &tl);
        if (st != RUGO_OK) goto fail;
        rugo_obb* leaves = tree->nodes + level_offset(fine, coarse);
        for (size_t k0 = 0; k0 < n; k0 += SEG_BLOCK) {
            int count = n - k0 < SEG_BLOCK ? (int)(n - k0) : SEG_BLOCK;
            rugo_real lengths[SEG_BLOCK];
            level_boxes(c, (int)k0, count, tl.bound, tl.total, min_length, zero, &s,
                        mom != NULL ? lengths : NULL);
            for (int i = 0; i < count; ++i)
                leaves[k0 + (size_t)i] = block_tree_box(&s, i);
            if (mom != NULL)
                for (int i = 0; i < count; ++i) {
                    centre_moments* mk = &mom[k0 + (size_t)i];
                    mk->weight = lengths[i] > 0.0 ? lengths[i] : 0.0;
                    mk->mean = leaves[k0 + (size_t)i].center;
                    mk->sxx = mk->sxy = mk->syy = 0.0;
                }
        }
    }

    /* Upper levels, bottom-up. */
    for (int j = fine - 1; j >= coarse; --j) {
        rugo_contour c;
        rugo_tolerance_level tl;
        memset(&tl, 0, sizeof tl);
        st = rugo_pyramid_level(pyr, j, &c);
        if (st == RUGO_OK && tol != NULL) st = rugo_tolerances_level(tol, j, &tl);
        if (st != RUGO_OK) goto fail;
        rugo_obb* level = tree->nodes + level_offset(j, coarse);
        const rugo_obb* below = tree->nodes + level_offset(j + 1, coarse);
        size_t m = (size_t)1 << j;
        for (size_t k0 = 0; k0 < m; k0 += SEG_BLOCK) {
            int count = m - k0 < SEG_BLOCK ? (int)(m - k0) : SEG_BLOCK;
            /* The level's own coarse segments f^j_k thickened by their total tolerance λ^j_k,
             * computed exactly like leaf boxes of level j. */
            level_boxes(c, (int)k0, count, NULL, tl.total, min_length, zero, &s, NULL);
            if (def->method == RUGO_BOXES_MULTIRES) {
                /* (b) the coarse segment's box, enlarged with its axes fixed until it contains both
                 * children's boxes, hence every descendant leaf box (Figure 4.4). */
                for (int i = 0; i < count; ++i) {
                    size_t k = k0 + (size_t)i;
                    rugo_obb own = block_tree_box(&s, i);
                    level[k] = padded(box_grown_by_pair(&own, &below[2 * k], &below[2 * k + 1], zero));
                }
            } else {
                /* (a) box of boxes: axes from the arc-length weighted covariance of the centres of ALL
                 * descendant leaf boxes, as (3.11)-(3.12) define it (the two children's centres alone
                 * would only give the line through them; measured on the Fig. 4.6 sample that makes
                 * coarse (a) boxes up to 6% larger). Extents enclose the two children's boxes, which
                 * hold every descendant leaf box (SPEC 5.3's cheaper equivalent: projecting every leaf
                 * would cost O(n log n)). Then the coarse segment f^j_k thickened by λ^j_k is added:
                 * the thesis' chapter 3 method covers the finest curve only, and chapter 4.2 says its
                 * Fig. 4.6 (a) boxes then include the level's segment; the thickening by λ^j_k is
                 * beyond the thesis, required by invariant (ii) so that queries stopped at level j
                 * (levels of detail) stay conservative. In steps over the block, as the leaves'. */
                rugo_real sxx[SEG_BLOCK], sxy[SEG_BLOCK], syy[SEG_BLOCK], ex[SEG_BLOCK], ey[SEG_BLOCK],
                    plain[SEG_BLOCK];
                for (int i = 0; i < count; ++i) {
                    size_t k = k0 + (size_t)i;
                    mom[k] = merge_moments(&mom[2 * k], &mom[2 * k + 1]); /* k <= 2k: in place */
                    sxx[i] = mom[k].sxx;
                    sxy[i] = mom[k].sxy;
                    syy[i] = mom[k].syy;
                }
                for (int i = 0; i < count; ++i)
                    plain[i] = plain_major_axis(sxx[i], sxy[i], syy[i], &ex[i], &ey[i]);
                for (int i = 0; i < count; ++i) {
                    size_t k = k0 + (size_t)i;
                    rugo_vec2 axis[2] = {rugo_v2(ex[i], ey[i]), rugo_v2(0.0, 0.0)};
                    if (!(plain[i] > 0.0)) axes_from_covariance(sxx[i], sxy[i], syy[i], axis);
                    rugo_obb own = block_tree_box(&s, i);
                    level[k] =
                        padded(box_enclosing_three(axis[0], &below[2 * k], &below[2 * k + 1], &own, zero));
                }
            }
        }
    }

    /* Root: covariance axes of the coarsest level's box corners, enclosing every coarsest node. */
    {
        size_t m = (size_t)1 << coarse;
        const rugo_obb* top = tree->nodes;
        rugo_vec2 o = top[0].center;
        rugo_vec2 mean = rugo_v2(0.0, 0.0);
        rugo_real sxx = 0.0, sxy = 0.0, syy = 0.0;
        for (int pass = 0; pass < 2; ++pass) {
            for (size_t k = 0; k < m; ++k) {
                rugo_vec2 corner[4];
                rugo_obb_corners(&top[k], corner);
                for (int i = 0; i < 4; ++i) {
                    rugo_vec2 q = rugo_v2_sub(corner[i], o);
                    if (pass == 0) {
                        mean = rugo_v2_add(mean, q);
                    } else {
                        q = rugo_v2_sub(q, mean);
                        sxx += q.x * q.x;
                        sxy += q.x * q.y;
                        syy += q.y * q.y;
                    }
                }
            }
            if (pass == 0) mean = rugo_v2_scale(1.0 / (4.0 * (rugo_real)m), mean);
        }
        rugo_obb root;
        axes_from_covariance(sxx, sxy, syy, root.axis);
        root.center = top[0].center;
        root.half[0] = root.half[1] = 0.0;
        root = rugo_obb_enclose(root, &top[0]);
        for (size_t k = 1; k < m; ++k)
            grow_to_contain(&root, &top[k]);
        tree->root = padded(root);
    }

    rugo__free(&alloc, mom);
    *out = tree;
    return RUGO_OK;

fail:
    rugo__free(&alloc, mom);
    rugo_mobb_tree_destroy(tree);
    return st;
}

void rugo_mobb_tree_destroy(rugo_mobb_tree* tree) {
    if (tree == NULL) return;
    rugo_allocator alloc = tree->allocator;
    rugo__free(&alloc, tree); /* the nodes live in the same block */
}

int rugo_mobb_tree_finest_level(const rugo_mobb_tree* tree) { return tree == NULL ? -1 : tree->finest; }

int rugo_mobb_tree_coarsest_level(const rugo_mobb_tree* tree) { return tree == NULL ? -1 : tree->coarsest; }

rugo_box_method rugo_mobb_tree_method(const rugo_mobb_tree* tree) {
    return tree == NULL ? RUGO_BOXES_MULTIRES : tree->method;
}

const rugo_obb* rugo_mobb_tree_node(const rugo_mobb_tree* tree, int level, int k) {
    if (tree == NULL || level < tree->coarsest || level > tree->finest) return NULL;
    if (k < 0 || (size_t)k >= ((size_t)1 << level)) return NULL;
    return tree->nodes + level_offset(level, tree->coarsest) + (size_t)k;
}

const rugo_obb* rugo_mobb_tree_root(const rugo_mobb_tree* tree) { return tree == NULL ? NULL : &tree->root; }

rugo_real rugo_mobb_tree_level_area(const rugo_mobb_tree* tree, int level) {
    if (tree == NULL || level < tree->coarsest || level > tree->finest) return NAN;
    const rugo_obb* nodes = tree->nodes + level_offset(level, tree->coarsest);
    size_t m = (size_t)1 << level;
    rugo_real sum = 0.0;
    for (size_t k = 0; k < m; ++k)
        sum += rugo_obb_area(&nodes[k]);
    return sum;
}

/* ---- internal (baked shapes): a tree from stored boxes (shape_internal.h) ------------------------- */

/* Stored boxes are decoded as 8 doubles each straight into the node array, in rugo_obb's member order. */
#define RUGO__OBB_IS_EIGHT_DOUBLES                                                                           \
    (sizeof(rugo_obb) == 8 * sizeof(double) && offsetof(rugo_obb, axis) == 16 &&                             \
     offsetof(rugo_obb, half) == 48)
typedef char rugo__obb_is_eight_doubles[RUGO__OBB_IS_EIGHT_DOUBLES ? 1 : -1];

rugo_status rugo__mobb_tree_from_nodes(int finest, int coarsest, rugo_box_method method,
                                       const unsigned char* nodes, const rugo_obb* root,
                                       const rugo_allocator* allocator, rugo_mobb_tree** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (nodes == NULL || root == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (coarsest < 2 || finest < coarsest || finest > 30 || (1 << finest) > RUGO_MAX_CONTROL_POINTS)
        return RUGO_ERR_BAD_LEVEL;
    if (method != RUGO_BOXES_MULTIRES && method != RUGO_BOXES_OF_BOXES) return RUGO_ERR_BAD_ARGUMENT;
    rugo_allocator alloc = rugo__allocator_or_default(allocator);
    const size_t count = level_offset(finest + 1, coarsest);
    rugo_mobb_tree* tree = tree_alloc(&alloc, finest, coarsest, method);
    if (tree == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    rugo__decode_f64_le((double*)(void*)tree->nodes, nodes, 8 * count);
    tree->root = *root;
    *out = tree;
    return RUGO_OK;
}
