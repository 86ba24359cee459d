/* Oriented boxes and the MOBBtree (SPEC 5; thesis chapters 3-4).
 *
 * Boxes are (centre, axis[0], axis[1] = perp(axis[0]), half-extents). Every extent is computed
 * relative to a nearby point (a segment's start, a box's centre) rather than the origin, so that
 * shapes far from the origin keep their precision.
 *
 * Tree layout: one array, level by level from the coarsest: node (j, k) sits at
 * (2^j - 2^J_min) + k, so the tree has 2^(J+1) - 2^J_min nodes. The build is bottom-up, O(1) per node
 * (a leaf box, or one coarse segment box plus two enclosures), hence O(n).
 *
 * Upper boxes enclose their two children's boxes, so the tree is nested: a parent contains everything
 * its children contain (descendant leaves with their band, and the children's own coarse segments).
 * That containment, not Theorem 4.2 (heuristic with these filters, SPEC 5.3), is what makes the boxes
 * conservative. */
#include "rugo/mobb.h"

#include "internal.h"
#include "shape_internal.h" /* rugo__mobb_tree_from_nodes */

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

struct rugo_mobb_tree {
    rugo_allocator allocator;
    int finest, coarsest;
    rugo_box_method method;
    rugo_obb* nodes; /* 2^(finest+1) - 2^coarsest boxes, level by level from the coarsest */
    rugo_obb root;
};

/* ---------------------------------------------------------------------------------------------------
 * Box primitives */

/* Unit major axis of the symmetric matrix [[a, b], [b, c]] (SPEC 5.1), coordinate axes when
 * degenerate. The eigenvector of λ1 = (a + c + d)/2, d = sqrt((a-c)^2 + 4b^2), is written in the form
 * that avoids cancellation: (λ1 - c, b) when a >= c, else (b, λ1 - a). */
static void axes_from_covariance(rugo_real a, rugo_real b, rugo_real c, rugo_vec2 axis[2]) {
    rugo_real trace = a + c;
    rugo_real d = hypot(a - c, 2.0 * b);
    rugo_vec2 e = rugo_v2(1.0, 0.0);
    if (isfinite(d) && trace > 0.0 && fabs(b) > COVARIANCE_DEGENERATE * trace && d > COVARIANCE_DEGENERATE * trace) {
        rugo_vec2 x = a >= c ? rugo_v2(0.5 * (a - c + d), b) : rugo_v2(b, 0.5 * (c - a + d));
        rugo_real len = rugo__v2_length(x);
        if (len > 0.0 && isfinite(len)) {
            e = rugo_v2(x.x / len, x.y / len);
            /* A canonical sign, so equal inputs give equal boxes whatever the sample order. */
            if (e.x < 0.0 || (e.x == 0.0 && e.y < 0.0)) e = rugo_v2(-e.x, -e.y);
        }
    }
    axis[0] = e;
    axis[1] = rugo_v2_perp(e);
}

void rugo_covariance_axes(const rugo_vec2* points, int n, rugo_vec2 axis[2]) {
    if (axis == NULL) return;
    if (points == NULL || n < 1) {
        axes_from_covariance(0.0, 0.0, 0.0, axis);
        return;
    }
    /* Mean (3.5: (1/n) Σ p_k), then the centred second moments (the 1/n factor does not change the
     * eigenvectors). Centring about the first point first keeps far-from-origin data precise. */
    rugo_vec2 o = points[0], mean = rugo_v2(0.0, 0.0);
    for (int i = 0; i < n; ++i) mean = rugo_v2_add(mean, rugo_v2_sub(points[i], o));
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

/* Extent interval [lo, hi] of a box along unit axis e, relative to the point o. */
static void box_interval(const rugo_obb* b, rugo_vec2 o, rugo_vec2 e, rugo_real* lo, rugo_real* hi) {
    rugo_real m = rugo_v2_dot(rugo_v2_sub(b->center, o), e);
    rugo_real r = b->half[0] * fabs(rugo_v2_dot(b->axis[0], e)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], e));
    *lo = m - r;
    *hi = m + r;
}

/* The box with axes `axis`, whose extents relative to o are [lo_i, hi_i] along axis i. */
static rugo_obb box_from_intervals(const rugo_vec2 axis[2], rugo_vec2 o, const rugo_real lo[2], const rugo_real hi[2]) {
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

/* Grows `box` (axes fixed; sides and centre move) until it also contains b. */
static void grow_to_contain(rugo_obb* box, const rugo_obb* b) {
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        rugo_real blo, bhi;
        box_interval(b, box->center, box->axis[i], &blo, &bhi);
        lo[i] = fmin(-box->half[i], blo);
        hi[i] = fmax(box->half[i], bhi);
    }
    if (lo[0] < -box->half[0] || hi[0] > box->half[0] || lo[1] < -box->half[1] || hi[1] > box->half[1])
        *box = box_from_intervals(box->axis, box->center, lo, hi);
}

rugo_obb rugo_obb_enclose(rugo_obb box_with_axes, const rugo_obb* b) {
    if (b == NULL) return box_with_axes;
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i) box_interval(b, b->center, box_with_axes.axis[i], &lo[i], &hi[i]);
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

int rugo_obb_overlap(const rugo_obb* a, const rugo_obb* b) {
    if (a == NULL || b == NULL) return 0;
    rugo_vec2 t = rugo_v2_sub(b->center, a->center);
    rugo_real position = fmax(fmax(fabs(a->center.x), fabs(a->center.y)), fmax(fabs(b->center.x), fabs(b->center.y)));
    const rugo_vec2 axes[4] = {a->axis[0], a->axis[1], b->axis[0], b->axis[1]};
    for (int i = 0; i < 4; ++i) {
        rugo_real dist = fabs(rugo_v2_dot(t, axes[i]));
        rugo_real reach = projected_radius(a, axes[i]) + projected_radius(b, axes[i]);
        /* Disjoint iff |T·L| > r_A + r_B (6.7); the slack keeps exact touching (and touching up to
         * round-off) an overlap. Written so that NaN never separates. */
        if (dist - reach > SAT_SLACK * (dist + reach + position)) return 0;
    }
    /* The four axes are the edge normals of both rectangles (also when a side has zero length, as
     * for a straight segment's box or a point's box), which suffices for convex polygons. */
    return 1;
}

int rugo_obb_contains(const rugo_obb* b, rugo_vec2 p, rugo_real slack) {
    if (b == NULL) return 0;
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
 * Leaf box of a segment (SPEC 5.2, thesis 3.3) */

/* f(t) - f(0) = 1/2 (v t^3/3 + w t^2/2 + r t), the integral of (3.8). */
static rugo_vec2 offset_at(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r, rugo_real t) {
    rugo_real a = t * t * t / 6.0, b = t * t / 4.0, c = 0.5 * t;
    return rugo_v2(a * v.x + b * w.x + c * r.x, a * v.y + b * w.y + c * r.y);
}

/* The extremes of the projection h(t) = (f(t) - f(0))·e on [0, 1], e a unit axis: the ends and the
 * roots in [0, 1] of f'(t)·e = 1/2 (α t^2 + β t + γ), α = v·e, β = w·e, γ = r·e (3.9-3.10, with the
 * errata's correction). Every case of the quadratic comes out of one stable formula:
 *   α ≠ 0:          q = -(β + sign(β) sqrt(β^2 - 4αγ))/2, roots q/α and γ/q (no cancellation);
 *   α = 0, β ≠ 0:   LINEAR (the v·e = 0 case), q = -β, root γ/q = -γ/β (q/α is skipped);
 *   α = β = 0:      f'·e = γ is constant: no interior extreme, the ends decide;
 *   α = β = γ = 0:  a straight segment perpendicular to e (or a point): h ≡ 0, zero thickness.
 * A discriminant that is negative only by round-off is taken as 0 (a double root; harmless, since
 * any extra candidate is a point of the curve). Candidates outside [0, 1] or not finite are skipped. */
static void projection_extremes(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r, rugo_vec2 e, rugo_real* lo, rugo_real* hi) {
    rugo_real alpha = rugo_v2_dot(v, e), beta = rugo_v2_dot(w, e), gamma = rugo_v2_dot(r, e);
    rugo_real cand[4];
    int nc = 0;
    cand[nc++] = 0.0;
    cand[nc++] = 1.0;
    rugo_real disc = beta * beta - 4.0 * alpha * gamma;
    rugo_real disc_err = 8.0 * DBL_EPSILON * (beta * beta + fabs(4.0 * alpha * gamma));
    if (disc < 0.0 && disc >= -disc_err) disc = 0.0;
    if (disc >= 0.0 && (alpha != 0.0 || beta != 0.0)) {
        rugo_real s = sqrt(disc);
        rugo_real q = -0.5 * (beta + (beta >= 0.0 ? s : -s));
        if (q != 0.0) {
            if (alpha != 0.0) cand[nc++] = q / alpha;
            cand[nc++] = gamma / q;
        } else if (alpha != 0.0) {
            cand[nc++] = 0.0; /* β = 0 and αγ = 0: double root at 0, already an end */
        }
    }
    rugo_real mn = 0.0, mx = 0.0; /* h(0) = 0 */
    for (int i = 1; i < nc; ++i) {
        rugo_real t = cand[i];
        if (!(t >= 0.0 && t <= 1.0)) continue;
        rugo_real h = rugo_v2_dot(offset_at(v, w, r, t), e);
        mn = fmin(mn, h);
        mx = fmax(mx, h);
    }
    *lo = mn;
    *hi = mx;
}

/* The leaf box of segment j (band 0), and its arc length. */
static rugo_obb segment_box(rugo_contour c, int segment, rugo_real band, rugo_real min_length, rugo_real* length_out) {
    rugo_vec2 v, w, r, b[4];
    rugo_contour_derivative_coefficients(c, segment, &v, &w, &r);
    rugo_contour_bezier(c, segment, b);
    rugo_vec2 start = b[0]; /* f(0) */
    rugo_real length = rugo_contour_segment_length(c, segment);
    if (length_out) *length_out = length;

    /* Axes: covariance of 5 evenly spaced samples, ends included, or of the 2 ends for a segment
     * no longer than l_min (3.3.1). Offsets from f(0) suffice: covariance ignores translation. */
    rugo_vec2 samples[5];
    int ns = 0;
    if (length > min_length) {
        for (int i = 0; i < 5; ++i) samples[ns++] = offset_at(v, w, r, 0.25 * i);
    } else {
        samples[ns++] = rugo_v2(0.0, 0.0);
        samples[ns++] = offset_at(v, w, r, 1.0);
    }
    rugo_vec2 axis[2];
    rugo_covariance_axes(samples, ns, axis);

    /* Exact extents along each axis; the centre follows from them (the sample mean is not the box
     * centre, 3.3.2). */
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        projection_extremes(v, w, r, axis[i], &lo[i], &hi[i]);
        lo[i] -= band;
        hi[i] += band;
    }
    return box_from_intervals(axis, start, lo, hi);
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
    return segment_box(c, segment, band, min_length, NULL);
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

static rugo_obb padded(rugo_obb b) {
    rugo_real pad = TREE_PAD * (fmax(fabs(b.center.x), fabs(b.center.y)) + b.half[0] + b.half[1]);
    b.half[0] += pad;
    b.half[1] += pad;
    return b;
}

static size_t level_offset(int level, int coarsest) { return ((size_t)1 << level) - ((size_t)1 << coarsest); }

static rugo_obb box_enclosing_pair(const rugo_vec2 axis[2], const rugo_obb* a, const rugo_obb* b) {
    rugo_real lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        rugo_real alo, ahi, blo, bhi;
        box_interval(a, a->center, axis[i], &alo, &ahi);
        box_interval(b, a->center, axis[i], &blo, &bhi);
        lo[i] = fmin(alo, blo);
        hi[i] = fmax(ahi, bhi);
    }
    return box_from_intervals(axis, a->center, lo, hi);
}

static rugo_real value_or_zero(const rugo_real* values, int k) { return values != NULL && values[k] > 0.0 ? values[k] : 0.0; }

rugo_status rugo_mobb_tree_create(const rugo_mobb_tree_def* def, rugo_mobb_tree** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (def == NULL || def->pyramid == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != MOBB_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (def->method != RUGO_BOXES_MULTIRES && def->method != RUGO_BOXES_OF_BOXES) return RUGO_ERR_BAD_ARGUMENT;
    if (!isfinite(def->min_length) || def->min_length < 0.0) return RUGO_ERR_BAD_ARGUMENT;

    const rugo_pyramid* pyr = def->pyramid;
    int fine = rugo_pyramid_finest_level(pyr), coarse = rugo_pyramid_coarsest_level(pyr);
    if (coarse < 0 || fine < coarse || fine > 30) return RUGO_ERR_BAD_LEVEL;
    const rugo_tolerances* tol = def->tolerances;
    if (tol != NULL &&
        (rugo_tolerances_finest_level(tol) != fine || rugo_tolerances_coarsest_level(tol) != coarse))
        return RUGO_ERR_BAD_LEVEL;

    rugo_allocator alloc = rugo__allocator_or_default(&def->allocator);
    size_t count = level_offset(fine + 1, coarse);
    size_t n = (size_t)1 << fine;
    rugo_mobb_tree* tree = (rugo_mobb_tree*)rugo__alloc_array(&alloc, 1, sizeof *tree);
    if (tree == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(tree, 0, sizeof *tree);
    tree->allocator = alloc;
    tree->finest = fine;
    tree->coarsest = coarse;
    tree->method = def->method;
    tree->nodes = (rugo_obb*)rugo__alloc_array(&alloc, count, sizeof *tree->nodes);
    /* Method (a) keeps the centre statistics of one level at a time, merged in place (k <= 2k). */
    centre_moments* mom = NULL;
    if (def->method == RUGO_BOXES_OF_BOXES) mom = (centre_moments*)rugo__alloc_array(&alloc, n, sizeof *mom);
    if (tree->nodes == NULL || (def->method == RUGO_BOXES_OF_BOXES && mom == NULL)) {
        rugo__free(&alloc, mom);
        rugo_mobb_tree_destroy(tree);
        return RUGO_ERR_OUT_OF_MEMORY;
    }

    rugo_status st = RUGO_OK;
    /* Leaves: the basic boxes, each thickened by the finest hard bound β^J_k (never below λ^J_k, so
     * that invariant (ii) holds at the finest level too). */
    {
        rugo_contour c;
        rugo_tolerance_level tl;
        memset(&tl, 0, sizeof tl);
        st = rugo_pyramid_level(pyr, fine, &c);
        if (st == RUGO_OK && tol != NULL) st = rugo_tolerances_level(tol, fine, &tl);
        if (st != RUGO_OK) goto fail;
        rugo_obb* leaves = tree->nodes + level_offset(fine, coarse);
        for (size_t k = 0; k < n; ++k) {
            int ki = (int)k;
            rugo_real band = fmax(value_or_zero(tl.bound, ki), value_or_zero(tl.total, ki));
            rugo_real length;
            leaves[k] = padded(segment_box(c, ki, band, def->min_length, &length));
            if (mom != NULL) {
                mom[k].weight = length > 0.0 ? length : 0.0;
                mom[k].mean = leaves[k].center;
                mom[k].sxx = mom[k].sxy = mom[k].syy = 0.0;
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
        for (size_t k = 0; k < m; ++k) {
            const rugo_obb* left = &below[2 * k];
            const rugo_obb* right = &below[2 * k + 1];
            /* The level's own coarse segment f^j_k thickened by its total tolerance λ^j_k, computed
             * exactly like a leaf box of level j. */
            rugo_obb own = padded(segment_box(c, (int)k, value_or_zero(tl.total, (int)k), def->min_length, NULL));
            rugo_obb box;
            if (def->method == RUGO_BOXES_MULTIRES) {
                /* (b) the coarse segment's box, enlarged with its axes fixed until it contains both
                 * children's boxes, hence every descendant leaf box (Figure 4.4). */
                box = own;
                grow_to_contain(&box, left);
                grow_to_contain(&box, right);
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
                 * (levels of detail) stay conservative. */
                mom[k] = merge_moments(&mom[2 * k], &mom[2 * k + 1]);
                rugo_vec2 axis[2];
                axes_from_covariance(mom[k].sxx, mom[k].sxy, mom[k].syy, axis);
                box = box_enclosing_pair(axis, left, right);
                grow_to_contain(&box, &own);
            }
            level[k] = padded(box);
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
        for (size_t k = 1; k < m; ++k) grow_to_contain(&root, &top[k]);
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
    rugo__free(&alloc, tree->nodes);
    rugo__free(&alloc, tree);
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
    for (size_t k = 0; k < m; ++k) sum += rugo_obb_area(&nodes[k]);
    return sum;
}

/* ---- internal (baked shapes): a tree from stored boxes (shape_internal.h) ------------------------- */

/* Stored boxes are decoded as 8 doubles each straight into the node array, in rugo_obb's member order. */
#define RUGO__OBB_IS_EIGHT_DOUBLES \
    (sizeof(rugo_obb) == 8 * sizeof(double) && offsetof(rugo_obb, axis) == 16 && offsetof(rugo_obb, half) == 48)
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
    rugo_mobb_tree* tree = (rugo_mobb_tree*)rugo__alloc_array(&alloc, 1, sizeof *tree);
    if (tree == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(tree, 0, sizeof *tree);
    tree->allocator = alloc;
    tree->finest = finest;
    tree->coarsest = coarsest;
    tree->method = method;
    tree->nodes = (rugo_obb*)rugo__alloc_array(&alloc, count, sizeof *tree->nodes);
    if (tree->nodes == NULL) {
        rugo__free(&alloc, tree);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    rugo__decode_f64_le((double*)(void*)tree->nodes, nodes, 8 * count);
    tree->root = *root;
    *out = tree;
    return RUGO_OK;
}
