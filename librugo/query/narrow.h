/* Internal: the narrow phase between two cubic curve pieces (SPEC 8, DESIGN "Contact semantics").
 * Not installed. Both pieces are cubic Bezier curves given by their 4 control points in a common
 * frame (a uniform cubic B-spline segment is one: rugo_contour_bezier). Parameters s (first piece)
 * and t (second) run over [0, 1].
 *
 * The solver is certified, not seeded by luck: it subdivides the parameter square, prunes every
 * sub-square where the Bernstein (Bezier) coefficients prove there is nothing (distance lower bound
 * above the cutoff, or a component of the system keeps one sign), and polishes each surviving
 * isolated root with Newton (J u = -H, thesis 6.11-6.14). So no crossing and no stationary pair
 * within the cutoff is missed.
 *
 * Conventions (narrow.c describes the searches, their pruning tests and limits):
 *  - `fallback` counts every decision made without a uniqueness proof: size-limit leaves (2^-26 in
 *    parameter), touchings, small-box acceptances, and the box limit (6000) being hit; `overflow`
 *    is also set when the box limit is hit.
 *  - A touching (tangential contact, no crossing) is reported as a kind-0 crossing AND a minimum;
 *    transversal crossings never appear as stationary pairs. Stationary pairs are sorted by s.
 *  - The cutoff also filters saddles: pass at least the penetration depth wanted. A NaN or negative
 *    cutoff gives crossings only; non-finite input gives an empty result.
 *  - A point-like piece reports parameter 0 for itself; parallel straight pieces report the two end
 *    pairs of their overlap as minima (overflow only when they coincide).
 *  - A minimum exactly at a piece end that is not stationary for that piece is left to the
 *    neighbouring segment; one at an end where the piece stops (a sharp corner) is RUGO__END_MINIMUM; a
 * crossing at a joint can come back as s = 1 from one segment and s = 0 from the next (callers deduplicate).
 *  - Cost: ~0.1 µs for a pair decided on the whole parameter square (hulls apart, or tangents nowhere
 *    parallel: most pairs a contact query hands over), ~0.5 µs when one box of each search settles
 *    it, a few µs when a search subdivides (0.7 µs on average over the pairs of bench_queries), 10-50
 *    µs overlapping, ~0.4 ms near-tangent, up to ~13 ms for long near-concentric arcs (a wheel in a
 *    matching groove). */
#ifndef RUGO_NARROW_H
#define RUGO_NARROW_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/shape.h"

enum { RUGO__NARROW_MAX_CROSSINGS = 9, RUGO__NARROW_MAX_STATIONARY = 16 };

typedef enum rugo__stationary_kind {
    RUGO__MINIMUM = 0, /* local minimum of |f(s) - g(t)|: a contact candidate */
    RUGO__SADDLE = 1,  /* saddle: e.g. the deepest pair inside an overlap (the centre line of two discs) */
    RUGO__MAXIMUM = 2,
    /* a minimum on this piece's side of an end of its domain, where the piece cannot see past the end:
     * at a zero-speed joint (a corner of coincident control points) its polynomial does not continue
     * as the curve does. A minimum of the curve only if the neighbouring segment's piece agrees (or
     * holds the point inside); callers decide (collide_hits.c, rugo__dedupe_hits) */
    RUGO__END_MINIMUM = 3
} rugo__stationary_kind;

typedef struct rugo__pair_point {
    rugo_real s, t;
    rugo_vec2 pa, pb;   /* f(s), g(t) */
    rugo_real distance; /* |pb - pa| */
    int kind;           /* rugo__stationary_kind for stationary pairs; for crossings: +1 if g crosses f
                           from f's outside (right of f' for a CCW f: the outward side) to its inside
                           as t increases, -1 the other way, 0 a touching (tangential, no crossing) */
    int flat;           /* a minimum on a stretch where the band-adjusted distance is flat to the
                           resolution (narrow_resolved.h): located to the resolution, not polished */
} rugo__pair_point;

typedef struct rugo__narrow_result {
    int crossing_count;
    rugo__pair_point crossings[RUGO__NARROW_MAX_CROSSINGS]; /* f(s) = g(t), sorted by s */
    int stationary_count;
    rugo__pair_point
        stationary[RUGO__NARROW_MAX_STATIONARY]; /* (f-g)·f' = (f-g)·g' = 0, distance <= cutoff */
    int newton_iterations;
    int fallback;
    int overflow; /* more roots than the arrays hold (degenerate input such as overlapping curves) */
} rugo__narrow_result;

/* All crossings of the two pieces and all stationary pairs of their distance with distance <= cutoff,
 * for s, t in [0, 1] (the caller assigns s = 1 or t = 1 to the next segment and removes duplicates).
 * Coincident pieces (infinitely many roots) set overflow and report what fits. Tolerances are
 * relative to the pieces' size; works at any scale and far from the origin (callers pass pieces
 * already moved near the origin for best precision). */
void rugo__narrow_pieces(const rugo_vec2 f[4], const rugo_vec2 g[4], rugo_real cutoff,
                         rugo__narrow_result* out);

/* Stationary pairs of the distance from a piece to a point c (circle centre): roots in [0,1] of
 * (f(s) - c)·f'(s) (degree 5), each classified as minimum/maximum of |f - c| (SADDLE for an
 * inflection of the distance), with distance <= cutoff; t = 0, pb = c. Returns the count (<= 6). */
int rugo__narrow_point(const rugo_vec2 f[4], rugo_vec2 c, rugo_real cutoff, rugo__pair_point out[6]);

/* Crossings and stationary pairs between a piece and the straight segment q0 + t (q1 - q0), t in
 * [0,1]. Same conventions as rugo__narrow_pieces. */
void rugo__narrow_line(const rugo_vec2 f[4], rugo_vec2 q0, rugo_vec2 q1, rugo_real cutoff,
                       rugo__narrow_result* out);

/* rugo__level_contains (shape/internal.h) with the level as rugo_contact_query.level (0 finest, < 0
 * coarser, > 0 absolute; collide_levels.c). */
int rugo__shape_contains(const rugo_shape* shape, int level, rugo_vec2 p, int* visited);

#endif
