/** @file rugo/contour.h
 * librugo — closed uniform cubic B-spline contours (SPEC 1).
 *
 * A contour is a view of n >= 4 control points c_0..c_{n-1} (cyclic). Segment j, t in [0,1):
 *   f_j(t) = 1/6 [t^3 t^2 t 1] M [c_{j-1} c_j c_{j+1} c_{j+2}]^T        (thesis 2.4-2.5)
 * so f_j(1) = f_{j+1}(0) and the curve is C2. A point with t = 1 belongs to segment j+1.
 * The view borrows its points; the caller keeps them alive. Query functions expect a contour that
 * passed rugo_contour_check (they do not re-validate; segment indices wrap cyclically).
 * Lengths are in the caller's units; the library is unit-free. Parameters t are dimensionless in
 * [0, 1) per segment; segment indices count from 0.
 *
 * Ownership: nothing here allocates except rugo_contour_check (through its allocator, freed before it
 * returns); results are returned by value or written into caller-owned memory. Query functions have no
 * status: they give zeros (count < 1) or NaN (non-finite parameters) instead. */
#ifndef RUGO_CONTOUR_H
#define RUGO_CONTOUR_H

#include "rugo/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A closed contour: a view of its control points (borrowed, never copied or freed by librugo; the
 * caller keeps them alive while the view is used). Segment j runs from near c_j to near c_{j+1}. */
typedef struct rugo_contour {
    const rugo_vec2* points; /**< borrowed, count entries, in length units */
    int count;               /**< number of control points = number of segments (>= 4 for a valid contour) */
} rugo_contour;

/** Flags for rugo_contour_check (bitwise or). */
enum {
    RUGO_CHECK_POWER_OF_TWO = 1 << 0,      /**< require count to be a power of two */
    RUGO_CHECK_SELF_INTERSECTION = 1 << 1, /**< test the curve for crossings (O(n log n) typical) */
    RUGO_CHECK_ALL = RUGO_CHECK_POWER_OF_TWO | RUGO_CHECK_SELF_INTERSECTION /**< both checks */
};

/** What a failed check found, for messages: the offending index or segment pair. */
typedef struct rugo_contour_problem {
    int index;       /**< first non-finite point index, or -1 */
    int segment_a;   /**< for RUGO_ERR_SELF_INTERSECTING: two segments that cross (segment_a <= segment_b), */
    int segment_b;   /**< possibly equal for a loop inside one segment; -1 otherwise */
    rugo_vec2 where; /**< an approximate crossing point */
} rugo_contour_problem;

/** Validates control points, in this order: NULL, count < 4 (TOO_FEW_POINTS), count > max
 * (TOO_MANY_POINTS), power of two if asked (NOT_POWER_OF_TWO), non-finite coordinate (NOT_FINITE),
 * coordinates so large (beyond ~1e150) that the area overflows (NOT_FINITE),
 * |area| <= 1e-12 * (diagonal of the curve's bounds)^2 (ZERO_AREA — or SELF_INTERSECTING when the
 * crossing test is asked for and finds one, e.g. a figure eight with equal lobes), crossings if asked
 * (SELF_INTERSECTING; OUT_OF_MEMORY if its ~60 bytes per point cannot be had from `allocator`,
 * which may be NULL for malloc/free). problem may be NULL.
 * Crossing test: parts of the curve closer than about 5e-10 of the bounds diagonal count as
 * touching; real crossings are found beyond round-off, except loops inside one segment smaller than
 * about 1e-15 of the diagonal. Segments shrunk to a point are allowed (their neighbours count as
 * adjacent); a spike where the curve retraces itself counts as self-intersecting, a cusp does not.
 * Cost: about 3 ms for 4096 points, 0.65 s for 2^20 (optimised build). */
RUGO_API rugo_status rugo_contour_check(const rugo_vec2* points, int count, int flags,
                                        rugo_contour_problem* problem, const rugo_allocator* allocator);

/** Signed area of the region bounded by the curve (squared length units; positive when
 * counter-clockwise), exact for the cubic curve (not the control polygon). 0 for an empty contour. */
RUGO_API rugo_real rugo_contour_signed_area(rugo_contour c);

/** Reverses points in place if the curve is clockwise, so it becomes counter-clockwise.
 * Returns true if it reversed, false if not (also for NULL or count < 2). Reversal maps segment j to
 * segment n-2-j, t to 1-t. The caller owns points. */
RUGO_API bool rugo_contour_orient_ccw(rugo_vec2* points, int count);

/** The point f_segment(t) in the matrix form (2.4), in length units. The segment index wraps
 * cyclically; t in [0, 1] (other values extrapolate the segment's cubic). Zeros for count < 1. */
RUGO_API rugo_vec2 rugo_contour_point(rugo_contour c, int segment, rugo_real t);
/** First derivative f'_segment(t) with respect to t (2.6), in length units per unit of t. As
 * rugo_contour_point for the arguments. */
RUGO_API rugo_vec2 rugo_contour_d1(rugo_contour c, int segment, rugo_real t);
/** Second derivative f''_segment(t) with respect to t (2.7), in length units per unit of t squared. As
 * rugo_contour_point for the arguments. */
RUGO_API rugo_vec2 rugo_contour_d2(rugo_contour c, int segment, rugo_real t);
/** Point at a global parameter u in [0, n): segment floor(u), t = u - floor(u) (wraps cyclically).
 * NaN for a non-finite u or an empty contour. Query functions given count < 1 return zeros. */
RUGO_API rugo_vec2 rugo_contour_point_at(rugo_contour c, rugo_real u);

/** The four cubic Bezier control points of segment j into out (caller-owned; a uniform cubic
 * B-spline segment is a cubic Bezier curve; the convex hull of these points contains the segment).
 * The segment index wraps; zeros for count < 1. */
RUGO_API void rugo_contour_bezier(rugo_contour c, int segment, rugo_vec2 out[4]);

/** The coefficients of (3.8): f'_j(t) = 1/2 (v t^2 + w t + r), written to v, w and r (caller-owned;
 * each may be NULL). The segment index wraps; zeros for count < 1. */
RUGO_API void rugo_contour_derivative_coefficients(rugo_contour c, int segment, rugo_vec2* v, rugo_vec2* w,
                                                   rugo_vec2* r);

/** Arc length of one segment (length units) to a relative error below 1e-13: adaptive 7-15 point
 * Gauss-Kronrod with its error estimate, the segment split first where its speed nearly vanishes (a
 * cusp, a tripled control point), bisecting until the estimates sum to at most 1e-13 of the length
 * (docs/accuracy.md). The segment index wraps; 0 for count < 1. */
RUGO_API rugo_real rugo_contour_segment_length(rugo_contour c, int segment);
/** Arc length of one segment by the same adaptive Gauss-Kronrod to |error| <= tolerance (absolute);
 * the estimate of the error actually reached, round-off included, goes to *error_bound (may be NULL).
 * Returns RUGO_ERR_NOT_CONVERGED (with the best estimate in *length) if 256 pieces do not reach it,
 * e.g. for a tolerance tighter than double precision allows; NULL_ARGUMENT, TOO_FEW_POINTS,
 * BAD_ARGUMENT (tolerance not finite and > 0). */
RUGO_API rugo_status rugo_contour_segment_length_adaptive(rugo_contour c, int segment, rugo_real tolerance,
                                                          rugo_real* length, rugo_real* error_bound);
/** Whole perimeter (length units): the sum of rugo_contour_segment_length (compensated), so within
 * 1e-13 relative. 0 for count < 1. */
RUGO_API rugo_real rugo_contour_perimeter(rugo_contour c);

/** Exact mass properties of the enclosed region for unit density, by Green's theorem with Gauss
 * quadrature exact for the polynomial integrands (no sampling), evaluated about an interior
 * reference point for precision far from the origin. Multiply area and inertia by a density
 * (mass per area) for a body's mass and moment. */
typedef struct rugo_mass_properties {
    rugo_real area;     /**< length²; > 0 for a counter-clockwise contour, negative for clockwise */
    rugo_vec2 centroid; /**< centre of the region (length units) */
    rugo_real inertia;  /**< polar moment of the region about the centroid, unit density: ∫∫|p-c|^2 dA
                           (length⁴); has the sign of area (negative for a clockwise contour) */
} rugo_mass_properties;
/** The mass properties of the region bounded by the curve (see rugo_mass_properties). All zero for
 * count < 1; NaN or infinite values propagate. Never fails otherwise. */
RUGO_API rugo_mass_properties rugo_contour_mass_properties(rugo_contour c);

/** Axis-aligned bounds of the curve itself (exact, from the derivative's roots) into *lower and *upper
 * (caller-owned, not NULL); both (0, 0) for count < 1. */
RUGO_API void rugo_contour_bounds(rugo_contour c, rugo_vec2* lower, rugo_vec2* upper);

/** A point on a curve: where, and how far from a query point or ray origin. */
typedef struct rugo_curve_point {
    int segment;        /**< segment index, in [0, count) */
    rugo_real t;        /**< in [0,1) */
    rugo_vec2 point;    /**< the curve point f_segment(t) */
    rugo_real distance; /**< distance from the query point (length units) */
} rugo_curve_point;
/** Closest point on the curve to p (global minimum of the distance over all segments). For count < 1
 * the result is p itself with distance HUGE_VAL. p must lie within about 1e150 of the curve: farther,
 * squared distances overflow (distance inf; rugo_shape_closest_point says NOT_FINITE). */
RUGO_API rugo_curve_point rugo_contour_closest_point(rugo_contour c, rugo_vec2 p);

/** true if p is inside the region bounded by the curve (non-zero winding), false if outside. Points on
 * the curve itself (within round-off) may go either way. */
RUGO_API bool rugo_contour_contains(rugo_contour c, rugo_vec2 p);

/** First intersection of the ray origin + s * direction, s in [0, max_fraction], with the curve.
 * Returns true and fills hit (s in *fraction, unit outward normal in *normal, hit->distance = s |d|)
 * or false for no hit. direction must be non-zero; fraction, hit and normal may be NULL. An origin on the
 * curve hits at s = 0; a ray along a straight segment hits its first point; a hit at a joint is
 * reported as t = 0 of the next segment. */
RUGO_API bool rugo_contour_ray_cast(rugo_contour c, rugo_vec2 origin, rugo_vec2 direction,
                                    rugo_real max_fraction, rugo_real* fraction, rugo_curve_point* hit,
                                    rugo_vec2* normal);

/** Unit tangent at f_j(t), in the direction of increasing t. Degenerate (zero-speed) points take the
 * direction of the second, then third derivative. The segment index wraps. */
RUGO_API rugo_vec2 rugo_contour_tangent(rugo_contour c, int segment, rugo_real t);
/** Outward unit normal (for a counter-clockwise contour; inward for a clockwise one) at f_j(t): the
 * tangent turned clockwise. Degenerate points as rugo_contour_tangent. */
RUGO_API rugo_vec2 rugo_contour_normal(rugo_contour c, int segment, rugo_real t);

/** Uniform cubic B-spline basis values N_1..N_4 at t into out (caller-owned; weights of c_{j-1}, c_j,
 * c_{j+1}, c_{j+2}); they sum to 1. */
RUGO_API void rugo_bspline_basis(rugo_real t, rugo_real out[4]);

#ifdef __cplusplus
}
#endif

#endif
