/* Internal: the narrow phase between two cubic pieces at a resolution δ > 0 (docs/contacts.md,
 * "Resolution"). Not installed. May include: core, curve, rough, shape.
 *
 * The round-off narrow phase (narrow.h) proves every root it reports, which costs most where the
 * curves run close together for long (conforming contacts: a disc in a matching bowl, flat on flat).
 * This one stops subdividing a pair of sub-pieces as soon as each is within δ/2 of its chord (the
 * band λ, carried as a third coordinate, within δ/2 of linear too): below that, the chords are the
 * curves to the query's resolution, and the work is bounded by the number of δ-flat pieces.
 *
 * On each pair of flat sub-pieces (a leaf):
 *  - a crossing of the chords is a crossing of the curves, polished by Newton on the true pieces
 *    (f(s) = g(t)); its kind is the sign of cross(f', g') (narrow.h's convention);
 *  - the band-adjusted distance φ = |f - g| - λ_f - λ_g of the chords is convex on the leaf's square,
 *    and its minimum (closed form on the square's four edges) is a candidate minimum of φ when the
 *    true curves' gradient of φ there points into the leaf (so that of neighbouring leaves exactly one
 *    owns a minimum); it is then walked to the leaf's minimum of φ on the true pieces and bands and
 *    polished by Newton; a walk that leaves the leaf where φ falls across its edge reports nothing there
 *    (the minimum is the neighbour's), and only a stretch flat to round-off (parallel straight pieces)
 *    keeps unpolished points;
 *  - with RUGO__RESOLVED_SADDLES, chords that face each other across an overlap (anti-parallel)
 *    start a Newton run on the stationarity system (f-g)·f' = (f-g)·g' = 0; a root in the leaf whose
 *    distance Hessian is indefinite is a saddle: an overlap's depth pair (collide.c's regions).
 * Guarantees: every minimum of φ over the pieces with φ <= cutoff - δ has a reported minimum within
 * the same leaf (its φ within δ of the true one); every reported minimum's φ is within δ of a local
 * minimum of φ, exact (round-off) where Newton converged; crossings of curves that overlap by more
 * than δ are found. Overlaps shallower than δ may be reported as a touching minimum instead.
 * Results follow narrow.h's conventions: s, t in [0, 1], pa = f(s), pb = g(t), distance |pb - pa|,
 * crossings and stationary pairs sorted by s, and minima of one call at most a few per conforming
 * stretch (its two ends and its deepest point). */
#ifndef RUGO_NARROW_RESOLVED_H
#define RUGO_NARROW_RESOLVED_H

#include "query/narrow.h"

#include <stdbool.h>

/* A cubic piece with its band: λ over [0, 1/2] and [1/2, 1] as the Bernstein coefficients of each
 * half's cubic (the band interpolation of SPEC 6.3 has a knot at 1/2). */
typedef struct rugo__banded_piece {
    rugo_vec2 p[4];
    rugo_real band[2][4];
} rugo__banded_piece;

enum {
    RUGO__RESOLVED_CROSSINGS = 1, /* crossings of the curves */
    RUGO__RESOLVED_MINIMA = 2,    /* minima of φ with φ <= cutoff */
    RUGO__RESOLVED_SADDLES =
        4 /* stationary pairs of the distance with indefinite Hessian, distance <= saddle_cutoff */
};

/* The results of the two pieces at resolution delta > 0 (`want`: a set of the flags above). cutoff
 * bounds the band-adjusted distance of minima, saddle_cutoff the distance of saddles. Non-finite
 * input, or delta <= 0, gives an empty result. */
void rugo__narrow_resolved(const rugo__banded_piece* f, const rugo__banded_piece* g, rugo_real cutoff,
                           rugo_real saddle_cutoff, rugo_real delta, int want, rugo__narrow_result* out);

/* Newton on the gradient of φ from (s, t) (the pieces' own domain; φ must not rise): 1 and the minimum
 * of φ it converged to, with *phi; 0 where it did not converge, leaving s and t. The round-off queries
 * move the distance's minima to the band-adjusted ones this way. */
int rugo__polish_band_minimum(const rugo__banded_piece* f, const rugo__banded_piece* g, rugo_real* s,
                              rugo_real* t, rugo_real* phi);

/* A smooth piece (λ = 0) from four Bezier points. */
void rugo__banded_piece_smooth(const rugo_vec2 p[4], rugo__banded_piece* out);

#endif
