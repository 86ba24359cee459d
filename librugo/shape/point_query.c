/* Point queries on a shape's level through its MOBBtree: containment, closest point and ray cast,
 * with the same answers, bit for bit, as the contour's passes over all segments (contour.c), at the
 * cost of the boxes near the point (or along its ray) and the few segments under them.
 *
 * All three rely on the tree holding the query level's segments: node (j, k) contains its
 * descendants' boxes down to that level, and each of those its own segment (mobb.h), with round-off
 * pads of their own. A box is skipped only when it keeps more than POINT_PAD (relative to the shape's
 * size and the distance of p, or of the ray's origin, from it) clear of what the query needs; the
 * contour's per-segment computations are relative to p with errors of a few ulps of the control
 * points' distances from p, far below the pad. */
#include "rugo/shape.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__contour_closest_among, rugo__contour_winding_segment, rugo__ray */
#include "shape/internal.h"

#define POINT_PAD 1e-8
/* Segments a closest-point query evaluates at most through the tree; beyond, it takes the pass over
 * all segments (same answer). A point near the curve needs a handful. */
#define MAX_CANDIDATES 64

static rugo_real box_size(const rugo_obb* b) { return 2.0 * hypot(b->half[0], b->half[1]); }

/* The round-off margin of box tests against p: relative to the shape's size and p's distance. */
static rugo_real point_pad(const rugo_obb* root, rugo_vec2 p) {
    return POINT_PAD * (box_size(root) + fabs(p.x - root->center.x) + fabs(p.y - root->center.y));
}

/* Depth-first walk over the tree's nodes from the coarsest level down, in increasing segment order at
 * every level: walk_next gives the next node to look at, and walk_descend queues its two children
 * (the caller decides which nodes to open). The stack holds at most one entry per level plus one. */
typedef struct node_walk {
    int jmin, next_root, top;
    int lv[64], kk[64];
} node_walk;

static void walk_start(node_walk* w, int jmin) {
    w->jmin = jmin;
    w->next_root = 0;
    w->top = 0;
}

static int walk_next(node_walk* w, int* l, int* k) {
    if (w->top == 0) {
        if (w->next_root >= (1 << w->jmin)) return 0;
        *l = w->jmin;
        *k = w->next_root++;
        return 1;
    }
    --w->top;
    *l = w->lv[w->top];
    *k = w->kk[w->top];
    return 1;
}

static void walk_descend(node_walk* w, int l, int k) {
    w->lv[w->top] = l + 1;
    w->kk[w->top++] = 2 * k + 1;
    w->lv[w->top] = l + 1;
    w->kk[w->top++] = 2 * k;
}

/* ---------------------------------------------------------------------------------------------------
 * Containment.
 *
 * rugo_contour_contains sums, over all segments, the changes of the curve between below and above the
 * horizontal line through p that happen right of p (the ray from p towards +x); p is inside iff the
 * sum is not 0 (contour.c). This computes the same sum but visits only the segments under tree boxes
 * that the ray may meet, and gets each one's term from the same function
 * (rugo__contour_winding_segment), so the answer is the same integer sum on every input. A skipped
 * segment's term is certainly 0: its curve lies in a box that keeps more than the pad above, below or
 * left of p. Above (below): every computed y - p.y is positive (negative), so no change is counted.
 * Left: every x at which a change is counted is negative, so none counts. */

/* 1 if box b keeps more than m above, below or left of p (its axis-aligned bounds). */
static int clear_of_ray(const rugo_obb* b, rugo_vec2 p, rugo_real m) {
    const rugo_real ex = b->half[0] * fabs(b->axis[0].x) + b->half[1] * fabs(b->axis[1].x);
    const rugo_real ey = b->half[0] * fabs(b->axis[0].y) + b->half[1] * fabs(b->axis[1].y);
    return b->center.y - ey > p.y + m || b->center.y + ey < p.y - m || b->center.x + ex < p.x - m;
}

int rugo__level_contains(const rugo_shape* shape, int level, rugo_vec2 p, int* visited) {
    if (visited != NULL) *visited = 0;
    rugo_contour curve;
    if (shape == NULL || rugo_shape_level(shape, level, &curve) != RUGO_OK) return 0;
    const rugo_mobb_tree* tree = rugo_shape_tree(shape);
    const int jmin = rugo_shape_coarsest_level(shape);
    const rugo_obb* root = rugo_mobb_tree_root(tree);
    const rugo_real m = point_pad(root, p);
    /* Non-finite input goes the long way (which decides it the same way); a level range that the
     * fixed stack below cannot hold cannot happen (a level has 2^level segments). */
    if (!(m < HUGE_VAL) || level - jmin > 60) {
        if (visited != NULL) *visited = curve.count;
        return rugo_contour_contains(curve, p);
    }
    if (clear_of_ray(root, p, m)) return 0;
    int winding = 0, seen = 0, l, k;
    node_walk w;
    walk_start(&w, jmin);
    while (walk_next(&w, &l, &k)) {
        if (clear_of_ray(rugo_mobb_tree_node(tree, l, k), p, m)) continue;
        if (l == level) {
            winding += rugo__contour_winding_segment(curve, k, p);
            ++seen;
        } else {
            walk_descend(&w, l, k);
        }
    }
    if (visited != NULL) *visited = seen;
    return winding != 0;
}

/* ---------------------------------------------------------------------------------------------------
 * Closest point.
 *
 * rugo_contour_closest_point takes the nearest joint as a bound, then solves every segment whose
 * Bezier hull's box is nearer than the best so far (contour.c). Here a greedy descent to one segment
 * gives a bound r (the nearer of its joints); every segment whose tree box is within r (plus the pad)
 * becomes a candidate, and the same passes run over the candidates in increasing order
 * (rugo__contour_closest_among). The nearest joint lies within r, so it is a candidate, and so is
 * every joint tied with it: the first pass ends with the same bound and segment. A segment left out
 * has no point within r of p, so in the second pass over all segments it could neither beat the bound
 * (which never exceeds r²) nor change anything: the same answer. */

/* Squared distance from p to box b (0 inside). */
static rugo_real box_distance2(const rugo_obb* b, rugo_vec2 p) {
    const rugo_vec2 d = rugo_v2_sub(p, b->center);
    rugo_real u = fabs(rugo_v2_dot(d, b->axis[0])) - b->half[0];
    rugo_real v = fabs(rugo_v2_dot(d, b->axis[1])) - b->half[1];
    u = u > 0.0 ? u : 0.0;
    v = v > 0.0 ? v : 0.0;
    return u * u + v * v;
}

static rugo_real joint_distance2(rugo_contour c, int j, rugo_vec2 p) {
    const rugo_vec2 d = rugo_v2_sub(rugo_contour_point(c, j, 0.0), p);
    return rugo_v2_dot(d, d);
}

/* Fills segs with the segments of `level` whose boxes come within r2 of p, in increasing order;
 * returns their number, or -1 when there are more than MAX_CANDIDATES. */
static int near_segments(const rugo_mobb_tree* tree, int jmin, int level, rugo_vec2 p, rugo_real r2,
                         int* segs) {
    int count = 0, l, k;
    node_walk w;
    walk_start(&w, jmin);
    while (walk_next(&w, &l, &k)) {
        if (!(box_distance2(rugo_mobb_tree_node(tree, l, k), p) <= r2)) continue;
        if (l < level) {
            walk_descend(&w, l, k);
        } else {
            if (count == MAX_CANDIDATES) return -1;
            segs[count++] = k;
        }
    }
    return count;
}

static rugo_curve_point level_closest_point(const rugo_shape* shape, int level, rugo_contour curve,
                                            rugo_vec2 p) {
    const rugo_mobb_tree* tree = rugo_shape_tree(shape);
    const int jmin = rugo_shape_coarsest_level(shape);
    const rugo_real m = point_pad(rugo_mobb_tree_root(tree), p);
    if (!(m < HUGE_VAL) || level - jmin > 60) return rugo_contour_closest_point(curve, p);
    /* Greedy descent: the coarsest box nearest to p, then the nearer child down to the level. */
    int k = 0;
    rugo_real dk = HUGE_VAL;
    for (int k0 = 0; k0 < (1 << jmin); ++k0) {
        const rugo_real d = box_distance2(rugo_mobb_tree_node(tree, jmin, k0), p);
        if (d < dk) {
            dk = d;
            k = k0;
        }
    }
    for (int l = jmin; l < level; ++l) {
        const rugo_real d0 = box_distance2(rugo_mobb_tree_node(tree, l + 1, 2 * k), p);
        const rugo_real d1 = box_distance2(rugo_mobb_tree_node(tree, l + 1, 2 * k + 1), p);
        k = d1 < d0 ? 2 * k + 1 : 2 * k;
    }
    const rugo_real r2j = fmin(joint_distance2(curve, k, p), joint_distance2(curve, k + 1, p));
    const rugo_real r = sqrt(r2j) * (1.0 + POINT_PAD) + m;
    int segs[MAX_CANDIDATES];
    const int count = near_segments(tree, jmin, level, p, r * r, segs);
    if (count < 1) return rugo_contour_closest_point(curve, p); /* too many (or, by round-off, none) */
    return rugo__contour_closest_among(curve, p, segs, count);
}

/* ---------------------------------------------------------------------------------------------------
 * Ray cast.
 *
 * rugo_contour_ray_cast takes the segments in increasing order, each either pruned or solved for its
 * crossings with the ray's line, and keeps the first hit (rugo__ray_segment). This takes the same steps
 * over the segments under the tree boxes that the ray segment s in [0, s1] meets, in the same order,
 * with s1 the best s so far (max_fraction before a hit). A segment left out lies in a box that keeps
 * more than the pad clear of that ray segment; each of its candidate points (on the curve, found
 * within 1e-12 of the segment's parameter range, within round-off of the ray's line) is then off the
 * line, behind the origin or beyond s1, so it could not have changed the running hit. Each visited
 * segment therefore starts from the state the pass over all segments has there, and the answer is
 * the same. */

/* true if box b grown by m (a length) misses the ray segment origin + s d, s in [0, s1], of r
 * (len = |d|). Computed relative to the origin, so that a shape far from (0, 0) keeps its digits;
 * infinite products (a huge s1) only make the box look nearer. */
static bool clear_of_ray_segment(const rugo_obb* b, const rugo__ray* r, rugo_real len, rugo_real s1,
                                 rugo_real m) {
    const rugo_vec2 c = rugo_v2_sub(b->center, r->origin), d = r->d;
    /* Along d, in units of s |d|^2: the box's extent against [0, s1]. */
    const rugo_real cd = rugo_v2_dot(c, d);
    const rugo_real rd =
        b->half[0] * fabs(rugo_v2_dot(b->axis[0], d)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], d));
    if (cd + rd < -m * len || cd - rd > s1 * r->dd + m * len) return true;
    /* Across d: the distance from the ray's line. */
    const rugo_vec2 n = rugo_v2_scale(1.0 / len, rugo_v2_perp(d));
    const rugo_real rn =
        b->half[0] * fabs(rugo_v2_dot(b->axis[0], n)) + b->half[1] * fabs(rugo_v2_dot(b->axis[1], n));
    if (fabs(rugo_v2_dot(c, n)) - rn > m) return true;
    /* The box's own axes. */
    for (int i = 0; i < 2; ++i) {
        const rugo_real e = s1 * rugo_v2_dot(d, b->axis[i]);
        const rugo_real ca = rugo_v2_dot(c, b->axis[i]);
        if (ca - b->half[i] > fmax(0.0, e) + m || ca + b->half[i] < fmin(0.0, e) - m) return true;
    }
    return false;
}

void rugo__level_ray_cast(const rugo_shape* shape, int level, rugo__ray* r, int* visited) {
    if (visited != NULL) *visited = 0;
    rugo_contour curve;
    if (shape == NULL || rugo_shape_level(shape, level, &curve) != RUGO_OK) return;
    const rugo_mobb_tree* tree = rugo_shape_tree(shape);
    const int jmin = rugo_shape_coarsest_level(shape);
    const rugo_obb* root = rugo_mobb_tree_root(tree);
    const rugo_real m = point_pad(root, r->origin), len = sqrt(r->dd);
    if (!(m < HUGE_VAL) || !(len > 0.0) || level - jmin > 60) {
        for (int j = 0; j < curve.count; ++j)
            rugo__ray_segment(r, curve, j);
        if (visited != NULL) *visited = curve.count;
        return;
    }
    if (clear_of_ray_segment(root, r, len, r->best_s, m)) return;
    int seen = 0, l, k;
    node_walk w;
    walk_start(&w, jmin);
    while (walk_next(&w, &l, &k)) {
        if (clear_of_ray_segment(rugo_mobb_tree_node(tree, l, k), r, len, r->best_s, m)) continue;
        if (l == level) {
            rugo__ray_segment(r, curve, k);
            ++seen;
        } else {
            walk_descend(&w, l, k);
        }
    }
    if (visited != NULL) *visited = seen;
}

/* ---------------------------------------------------------------------------------------------------
 * Public API. */

/* The checks every entry point makes: a shape, a level it has (its curve into *curve), a finite point. */
static rugo_status check_query(const rugo_shape* s, int level, rugo_vec2 p, rugo_contour* curve) {
    if (s == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const rugo_status st = rugo_shape_level(s, level, curve);
    if (st != RUGO_OK) return st;
    return rugo__v2_finite(p) ? RUGO_OK : RUGO_ERR_NOT_FINITE;
}

rugo_status rugo_shape_contains(const rugo_shape* s, int level, rugo_vec2 p, bool* inside) {
    if (inside == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *inside = false;
    rugo_contour curve;
    const rugo_status st = check_query(s, level, p, &curve);
    if (st != RUGO_OK) return st;
    *inside = rugo__level_contains(s, level, p, NULL) != 0;
    return RUGO_OK;
}

rugo_status rugo_shape_closest_point(const rugo_shape* s, int level, rugo_vec2 p, rugo_curve_point* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    out->segment = 0;
    out->t = 0.0;
    out->point = p;
    out->distance = HUGE_VAL;
    rugo_contour curve;
    const rugo_status st = check_query(s, level, p, &curve);
    if (st != RUGO_OK) return st;
    /* Farther out, squared distances overflow and every segment looks infinitely far (shapes are at
     * most RUGO_SHAPE_MAX_SIZE across). */
    if (fabs(p.x) > 1e150 || fabs(p.y) > 1e150) return RUGO_ERR_NOT_FINITE;
    *out = level_closest_point(s, level, curve, p);
    return RUGO_OK;
}

rugo_status rugo_shape_ray_cast(const rugo_shape* s, int level, rugo_vec2 origin, rugo_vec2 direction,
                                rugo_real max_fraction, rugo_real* fraction, rugo_curve_point* hit,
                                rugo_vec2* normal, bool* found) {
    if (found == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *found = false;
    rugo_contour curve;
    const rugo_status st = check_query(s, level, origin, &curve);
    if (st != RUGO_OK) return st;
    if (!rugo__v2_finite(direction) || !isfinite(max_fraction)) return RUGO_ERR_NOT_FINITE;
    /* Beyond, squared lengths overflow (shapes are at most RUGO_SHAPE_MAX_SIZE across). */
    if (fabs(origin.x) > 1e150 || fabs(origin.y) > 1e150 || fabs(direction.x) > 1e150 ||
        fabs(direction.y) > 1e150)
        return RUGO_ERR_NOT_FINITE;
    if (!(max_fraction >= 0.0)) return RUGO_ERR_BAD_ARGUMENT;
    rugo__ray r;
    if (!rugo__ray_begin(&r, origin, direction, max_fraction)) return RUGO_ERR_BAD_ARGUMENT; /* |d|^2 = 0 */
    rugo__level_ray_cast(s, level, &r, NULL);
    *found = rugo__ray_finish(&r, curve, fraction, hit, normal);
    return RUGO_OK;
}
