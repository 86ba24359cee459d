/* Private helpers of the curve layer (contour.c, contour_check.c, multires.c, path_segment.c,
 * outline_sample.c) for its own files and the layers above it. Not installed.
 * May include: core. */
#ifndef RUGO_CURVE_INTERNAL_H
#define RUGO_CURVE_INTERNAL_H

#include "rugo/contour.h"
#include "rugo/import.h" /* paths and affine maps: the outline sampler is geometry */
#include "rugo/multires.h"

#include <math.h>

/* Containment helper (contour.c, used by the shape's tree walk, shape/point_query.c): the signed count of the
 * changes of segment j of c between "below" (y < p.y) and "up" (y >= p.y) that happen right of p (x > p.x),
 * exactly as rugo_contour_contains counts them; the winding number of c around p is their sum over
 * all segments, and p is inside iff it is not 0. A segment whose curve keeps more than the round-off
 * of its evaluation (relative to its control points' distance from p) above, below or left of p
 * counts 0. */
int rugo__contour_winding_segment(rugo_contour c, int j, rugo_vec2 p);

/* The Bezier points of segment j relative to o (rugo_contour_bezier of the control points minus o),
 * for the self-intersection test (contour_check.c): far from the origin, differences keep their
 * digits. */
void rugo__contour_bezier_rel(rugo_contour c, int j, rugo_vec2 o, rugo_vec2 out[4]);

/* rugo_contour_closest_point restricted to the segments segs[0 .. count) (increasing; NULL: all
 * count = c.count segments), computed by the same passes in the same order (contour.c). Given every
 * segment that could hold a point at most as far from p as the nearest joint, it is the same answer,
 * bit for bit, as over all segments: the others can neither lower the bound nor win (point_query.c). */
rugo_curve_point rugo__contour_closest_among(rugo_contour c, rugo_vec2 p, const int* segs, int count);

/* rugo_contour_ray_cast in steps (contour.c), so that the shape's tree walk (shape/point_query.c) can
 * run it over some of the segments: rugo__ray_begin sets up a ray (false where rugo_contour_ray_cast
 * answers "no hit" for its arguments alone), rugo__ray_segment takes segment j into the running best
 * hit, rugo__ray_finish reports it as rugo_contour_ray_cast does. rugo_contour_ray_cast is begin, every
 * segment in increasing order, finish. A segment can only change the state through a candidate point
 * on the ray's line (within round-off relative to its control points' distances from the origin) with
 * s in [0, max_fraction] and below the best s so far; leaving out segments that have none, the others
 * taken in the same order, gives the same answer bit for bit. */
typedef struct rugo__ray {
    rugo_vec2 origin, d;
    rugo_real dd, dmax, max_fraction;
    bool found;
    int best_j;
    rugo_real best_s, best_t; /* best_s is max_fraction until found */
} rugo__ray;
bool rugo__ray_begin(rugo__ray* r, rugo_vec2 origin, rugo_vec2 direction, rugo_real max_fraction);
void rugo__ray_segment(rugo__ray* r, rugo_contour c, int j);
bool rugo__ray_finish(const rugo__ray* r, rugo_contour c, rugo_real* fraction, rugo_curve_point* hit,
                      rugo_vec2* normal);

/* For the baked-shape loader (shape/baked.c, through rugo__shape_create_from_parts): a pyramid holding the
 * stored levels (points: levels J_min..J; world, local: levels J_min..J-1; both encoded as in
 * rugo__shape_parts), without the analysis. Validates the decoded finest level with an O(n) outline check:
 * exact signed area of the closed B-spline in closed form, finite (NOT_FINITE), positive (BAD_ARGUMENT when
 * clockwise) and above 1e-13 times the squared diagonal of the joints' bounds (ZERO_AREA; rugo_contour_check
 * demands 1e-12 of the curve's bounds, which contain the joints, so every outline a build accepts passes). No
 * crossing test. `reversed` is what rugo_pyramid_was_reversed reports. Also BAD_FILTER, BAD_LEVEL,
 * OUT_OF_MEMORY. */
rugo_status rugo__pyramid_from_levels(rugo_filter filter, int finest, int coarsest, bool reversed,
                                      const unsigned char* points, const unsigned char* world,
                                      const unsigned char* local, const rugo_allocator* allocator,
                                      rugo_pyramid** out);

/* ---- arc length (arc_length.c): the one arc-length integrator of the library ---------------------- */

/* The speed |c'(t)| of a curve piece on [0, 1], for ctx. */
typedef double (*rugo__speed_fn)(const void* ctx, double t);

/* Relative error bound every length the library reports or places samples by is computed to:
 * perimeters, segment lengths (roughness ranges and profiles), outline sampling. */
#define RUGO__ARC_REL_TOL 1e-13
#define RUGO__ARC_MAX_PIECES 256
#define RUGO__ARC_MAX_BREAKS 4

/* An accepted piece [a, b] of the parameter interval, its length and the bound on that length's error. */
typedef struct rugo__arc_piece {
    double a, b, length, error;
} rugo__arc_piece;

/* The result: the pieces in order of a (covering [0, 1]), their total length and total error bound
 * (compensated sums); converged = 0 when the bound could not be brought within the tolerance in
 * RUGO__ARC_MAX_PIECES pieces, or a length is not finite. */
typedef struct rugo__arc {
    double length, error;
    int count, converged;
    rugo__arc_piece piece[RUGO__ARC_MAX_PIECES];
} rugo__arc;

/* The arc length of a curve on [0, 1] to error <= max(abs_tol, rel_tol * length): 7-15 point
 * Gauss-Kronrod on the pieces between the breaks (interior points where the speed nearly vanishes,
 * e.g. from rugo__arc_speed_breaks; any order, those outside (0, 1) ignored), bisecting the piece of
 * largest error estimate (|K15 - G7| plus round-off) until the sum of the estimates meets the
 * tolerance. Deterministic: the same calls in the same order. */
void rugo__arc_length(rugo__speed_fn speed, const void* ctx, const double* breaks, int break_count,
                      double rel_tol, double abs_tol, rugo__arc* out);
/* 15-point Kronrod on [a, b]; *error (may be NULL) gets |K15 - G7| plus round-off. */
double rugo__arc_gk15(rugo__speed_fn speed, const void* ctx, double a, double b, double* error);
/* The interior minima of |d(t)| on (0, 1) for a quadratic derivative d(t) = a + b t + c t^2 that lie
 * below a quarter of its largest value there (cusps and near-cusps), into breaks (room for
 * RUGO__ARC_MAX_BREAKS); returns their count. */
int rugo__arc_speed_breaks(rugo_vec2 a, rugo_vec2 b, rugo_vec2 c, double* breaks);

/* ---- paths (path_segment.c) and the outline sampler (outline_sample.c), also for io's SVG readers --- */

/* "RSmp": marks a def that came from rugo_default_outline_sample_def (the sampler and
 * rugo_svg_import_outline refuse others). */
#define RUGO__OUTLINE_SAMPLE_DEF_COOKIE 0x52536d70

static inline int rugo__affine_finite(const rugo_affine* m) {
    return isfinite(m->a) && isfinite(m->b) && isfinite(m->c) && isfinite(m->d) && isfinite(m->e) &&
           isfinite(m->f);
}

/* A segment's end point (p[1] of lines and arcs, p[2] of quadratics, p[3] of cubics). */
rugo_vec2 rugo__path_segment_end(const rugo_path_segment* s);
/* rugo_path_segment_point and rugo_path_segment_derivative for a segment known not to be NULL. */
rugo_vec2 rugo__path_segment_point(const rugo_path_segment* s, double t);
rugo_vec2 rugo__path_segment_derivative(const rugo_path_segment* s, double t);

#endif
