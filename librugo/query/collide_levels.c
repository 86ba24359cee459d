/* A shape as one side of a query: its curve at the query's level of detail (levels as
 * rugo_contact_query.lod selects them), the tolerances and band bounds of that level, how much its
 * boxes grow, and containment and closest points through its tree. Separate because both kinds of
 * query (shapes, primitives) and their output read a side the same way. */
#include "query/collide_internal.h"

#include "shape/internal.h"

static int resolve_level(const rugo_shape* s, int level) {
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    int l = level <= 0 ? J + level : level;
    if (level <= 0 && level < -(J - Jmin)) l = Jmin; /* avoid overflow of J + level */
    if (l < Jmin) l = Jmin;
    if (l > J) l = J;
    return l;
}

int rugo__query_level(const rugo_shape* shape, const rugo_contact_query* q, rugo_real level_budget) {
    const int level = q->lod == RUGO_LOD_AUTO ? rugo_shape_level_for_error(shape, q->lod_error_budget)
                                              : resolve_level(shape, q->lod);
    /* A resolution allows a coarser level whose error against the finest, added to the chosen level's
     * own, stays within its share of the resolution: the answer moves by at most that much. */
    int j = level;
    const rugo_real own = rugo__shape_level_error(shape, level);
    while (j > rugo_shape_coarsest_level(shape) &&
           rugo__shape_level_error(shape, j - 1) + own <= level_budget)
        --j;
    return j;
}

void rugo__query_side_init(query_side* s, const rugo_shape* shape, int level, rugo_real override) {
    s->shape = shape;
    s->tree = rugo_shape_tree(shape);
    s->level = level;
    s->jmin = rugo_shape_coarsest_level(shape);
    rugo_shape_level(shape, s->level, &s->curve);
    s->n = s->curve.count;
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(shape, s->level, &tl);
    s->lambda = tl.total;
    s->band = rugo__shape_band_bounds(shape, s->level);
    s->slack = override >= 0.0 ? override : rugo__shape_band_excess(shape, s->level);
}

rugo_real rugo__query_side_tolerance(const query_side* s, int seg, rugo_real t, rugo_real override) {
    if (override >= 0.0) return override;
    return rugo_tolerance_at(s->lambda, s->n, seg, t, 0.0);
}

/* Containment through the tree (point_query.c): the same answer as rugo_contour_contains on the side's
 * curve, from the segments under the boxes the ray from p towards +x may meet. */
int rugo__query_side_contains(const query_side* s, rugo_vec2 p) {
    return rugo__level_contains(s->shape, s->level, p, NULL);
}

/* rugo_contour_closest_point on the side's curve, through the tree (point_query.c): the same answer
 * (non-finite p, which the tree version refuses, takes the pass over all segments). */
rugo_curve_point rugo__query_side_closest(const query_side* s, rugo_vec2 p) {
    rugo_curve_point cp;
    if (rugo_shape_closest_point(s->shape, s->level, p, &cp) != RUGO_OK)
        return rugo_contour_closest_point(s->curve, p);
    return cp;
}

/* Containment through the tree at a query level (declared in narrow.h, which the tests include). */
int rugo__shape_contains(const rugo_shape* shape, int level, rugo_vec2 p, int* visited) {
    if (visited != NULL) *visited = 0;
    if (shape == NULL) return 0;
    return rugo__level_contains(shape, resolve_level(shape, level), p, visited);
}
