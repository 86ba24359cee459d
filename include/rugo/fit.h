/** @file rugo/fit.h
 * librugo — least-squares fitting and simultaneous multi-point manipulation.
 *
 * These functions live in the Eigen shim (CMake target rugo::fit, C++17 inside, this C API outside).
 * The core library rugo::rugo does not depend on it. When the project is configured with
 * RUGO_WITH_EIGEN=OFF the target does not exist. No C++ exception crosses this API: an allocation
 * failure inside Eigen or the standard library is reported as RUGO_ERR_OUT_OF_MEMORY.
 *
 * Units: points, deltas and errors are in the caller's length units; curve parameters are
 * dimensionless. Memory: buffers of the shim's own go through the allocator of the def (or of the
 * pyramid); Eigen's containers use the default C++ heap (Eigen has no per-call allocator hook).
 * Deterministic: the same input gives the same bits. */
#ifndef RUGO_FIT_H
#define RUGO_FIT_H

#include "rugo/base.h"
#include "rugo/import.h"
#include "rugo/multires.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How rugo_fit_contour assigns a curve parameter to each sample (fixed; no parameter correction). */
typedef enum rugo_parameterization {
    RUGO_PARAM_CHORD_LENGTH = 0, /**< parameters proportional to cumulative chord length (default) */
    RUGO_PARAM_UNIFORM = 1       /**< sample k of m at u = k * n / m (n control points) */
} rugo_parameterization;

/** What rugo_fit_contour fits; fill from rugo_default_fit_def(). */
typedef struct rugo_fit_def {
    const rugo_vec2* samples; /**< ordered points around a closed outline (borrowed, length units); the last
                                   need not repeat the first */
    int sample_count;         /**< number of samples, >= control_count and <= RUGO_MAX_CONTROL_POINTS */
    int control_count;        /**< control points to fit, 2^J >= 4 */
    rugo_parameterization parameterization; /**< sample parameters (default chord length) */
    rugo_allocator allocator;               /**< for the fit's own scratch buffers (zeroed: malloc/free) */
    int cookie;                             /**< set by rugo_default_fit_def; catches uninitialised defs */
} rugo_fit_def;

/** A def with no samples, control_count 0, chord-length parameters, the malloc/free allocator and the
 * cookie that marks an initialised def. Never fails. */
RUGO_API rugo_fit_def rugo_default_fit_def(void);

/** How well rugo_fit_contour fitted, in length units. */
typedef struct rugo_fit_result {
    rugo_real max_error; /**< largest distance from a sample to the curve point at its parameter */
    rugo_real rms_error; /**< root mean square of those distances */
} rugo_fit_result;

/** Least-squares fit of a closed uniform cubic B-spline with control_count control points to the
 * samples. control_points receives control_count points (caller-owned). The result keeps the
 * samples' orientation; normalise with rugo_contour_orient_ccw if needed. Parameters stay as chosen
 * (no parameter correction), so the errors are distances to the curve point at each sample's own
 * parameter. Samples are scaled into [-1, 1]^2 internally, so any scale and offset works.
 * result may be NULL; on error control_points and result are untouched.
 * Errors: NULL_ARGUMENT (def, samples or control_points), TOO_FEW_POINTS (control_count < 4),
 * NOT_POWER_OF_TWO, NOT_FINITE (input, or a fitted point that would overflow), TOO_MANY_POINTS
 * (either count beyond RUGO_MAX_CONTROL_POINTS), BAD_ARGUMENT (def not from rugo_default_fit_def,
 * sample_count < control_count, bad parameterization, repeated consecutive samples making chord
 * length zero), SINGULAR (a control point no sample influences, or a pivot showing the system may be
 * singular (condition number beyond about 1e11): with chord-length parameters and about as many
 * samples as control points this happens often), OUT_OF_MEMORY. Buffers of its own use
 * def->allocator; Eigen's containers use the default heap. */
RUGO_API rugo_status rugo_fit_contour(const rugo_fit_def* def, rugo_vec2* control_points,
                                      rugo_fit_result* result);

/** Simultaneous direct manipulation of several points of one level (2.30-2.31 generalised): move
 * f^level_{segments[i]}(ts[i]) by deltas[i] for all i with the least-norm change of that level's
 * control points, then rebuild the pyramid as rugo_pyramid_move_point does. Constraints that share
 * control points are solved together (rank-revealing, so consistent duplicates are fine); the cost
 * grows with the cube of the largest such cluster: meant for an editor's handful of points.
 * segments, ts and deltas are caller-owned arrays of count entries, only read; ts in [0, 1], deltas
 * in length units. The pyramid is edited in place; bookkeeping allocates through the pyramid's
 * allocator, Eigen's dense blocks from the C++ heap.
 * Errors: NULL_ARGUMENT, BAD_LEVEL, BAD_ARGUMENT (segment out of range, t outside [0,1] or NaN, bad
 * mode, count < 1), NOT_FINITE (a delta, or a displacement that overflows in the rebuild),
 * TOO_MANY_POINTS, OUT_OF_MEMORY, and SINGULAR if the constraints conflict (e.g. the same point
 * twice with different deltas); on error the pyramid is unchanged. */
RUGO_API rugo_status rugo_pyramid_move_points(rugo_pyramid* p, int level, int count, const int* segments,
                                              const rugo_real* ts, const rugo_vec2* deltas,
                                              rugo_detail_mode mode);

/* ---- fitting an imported outline (rugo/import.h, docs/import.md) ------------------------------- */

/** Largest control count the automatic search of rugo_fit_outline tries by default. */
#define RUGO_DEFAULT_MAX_FIT_CONTROL_POINTS 1024

/** What rugo_fit_outline fits; fill from rugo_default_outline_fit_def(). */
typedef struct rugo_outline_fit_def {
    const rugo_vec2* samples; /**< ordered outline points (borrowed), e.g. rugo_outline_samples.points */
    int sample_count;         /**< number of samples */
    int control_count;        /**< 2^J >= 4; or 0 (default): the smallest power of two whose max_error is
                                   <= tolerance */
    rugo_real tolerance;      /**< control_count 0: the max_error to reach, > 0, in length units */
    int max_control_count;    /**< control_count 0: largest count tried, a power of two in
                                   [4, RUGO_MAX_CONTROL_POINTS] (default RUGO_DEFAULT_MAX_FIT_CONTROL_POINTS);
                                   the search also stops at sample_count / 4 */
    rugo_parameterization parameterization; /**< as in rugo_fit_def (default chord length) */
    rugo_allocator allocator; /**< for the result's control points and scratch (zeroed: malloc/free) */
    int cookie;               /**< set by rugo_default_outline_fit_def; catches uninitialised defs */
} rugo_outline_fit_def;

/** The defaults described in rugo_outline_fit_def (tolerance 0: set it for the automatic count). */
RUGO_API rugo_outline_fit_def rugo_default_outline_fit_def(void);

/** A fitted outline; owns control_points (allocated with `allocator`). */
typedef struct rugo_outline_fit {
    rugo_vec2* control_points;        /**< control_count points, counter-clockwise */
    int control_count;                /**< the count used (the one found, for the automatic search) */
    rugo_real max_error;              /**< largest distance from a sample to the fitted curve (closest point
                                           on the whole curve, rugo_contour_closest_point), length units */
    rugo_real rms_error;              /**< root mean square of those distances */
    rugo_real max_error_at_parameter; /**< rugo_fit_contour's error: distance to the curve point at the
                                           sample's own parameter (>= max_error) */
    bool tolerance_met;               /**< true if tolerance <= 0 or max_error <= tolerance; false when the
                                           automatic search stopped at its largest count without reaching it */
    bool reversed;            /**< true if the fit ran clockwise and the control points were reversed */
    rugo_allocator allocator; /**< the allocator of control_points */
} rugo_outline_fit;

/** Fits a closed cubic B-spline to outline samples: rugo_fit_contour with def->control_count control
 * points, or, for control_count 0, with 4, 8, 16, ... until max_error <= tolerance or the largest
 * count allowed (min(max_control_count, sample_count / 4), rounded down to a power of two) has been
 * tried (then tolerance_met is false and out holds that largest fit: not an error). The result is turned
 * counter-clockwise; its errors are measured as distances from every sample to the closest point of
 * the fitted curve, not only at the sample's parameter. Cost: O(sample_count x control_count) per
 * count tried, for the closest points. Deterministic.
 * Errors (out zeroed): NULL_ARGUMENT, BAD_ARGUMENT (def not from rugo_default_outline_fit_def;
 * control_count 0 with a tolerance that is not finite and > 0, or max_control_count below 4),
 * NOT_POWER_OF_TWO and TOO_MANY_POINTS (max_control_count; a sample_count beyond
 * RUGO_MAX_CONTROL_POINTS), TOO_FEW_POINTS (control_count 0 with fewer than 16 samples), and those of
 * rugo_fit_contour for the counts tried (including SINGULAR, also when one count of the search is
 * singular), OUT_OF_MEMORY.
 * Free the result with rugo_outline_fit_free. */
RUGO_API rugo_status rugo_fit_outline(const rugo_outline_fit_def* def, rugo_outline_fit* out);

/** Frees the control points and zeroes the struct (NULL and a zeroed struct are fine). */
RUGO_API void rugo_outline_fit_free(rugo_outline_fit* fit);

/* ---- importing at game scale: units, placement, the fit in one call (docs/import.md) ----------- */

/** Default largest size (bounds diagonal, output units) rugo_import_outline accepts: 1e4, i.e. 10 km
 * when the output is in metres. Far beyond what a physics engine simulates well; it catches a missing
 * scale (a 1e30-unit drawing, or pixels taken for metres at survey scale). */
#define RUGO_DEFAULT_IMPORT_MAX_SIZE 1e4

/** What rugo_import_outline imports; fill from rugo_default_import_def(). */
typedef struct rugo_import_def {
    const char* text;         /**< an SVG document (first non-blank character '<') or a point list
                                   (rugo_points_text_parse); borrowed */
    size_t length;            /**< bytes of text */
    const char* path_id;      /**< SVG: id of the `<path>`; NULL: the document's only `<path>` */
    int use_viewbox;          /**< SVG: 1 to map user units to CSS px through the root's viewBox, width and
                                   height first (rugo_svg_read_viewport); 0 (default): user units as they are */
    rugo_real scale;          /**< output units per drawing unit (per CSS px with use_viewbox), > 0: e.g.
                                   1 / 100 for a game at 100 px per metre; default 1 */
    int recentre;             /**< 1: translate the result so that the centroid of the fitted curve's area is
                                   at the origin (a b2Body's origin at its centre of mass); default 0 */
    int sample_count;         /**< samples of the outline; 0 (default): rugo_outline_sample's default for
                                   SVG, the points themselves for a point list */
    int control_count;        /**< 2^J >= 4; 0 (default): the smallest that meets `tolerance` */
    rugo_real tolerance;      /**< control_count 0: the max_error to reach, in OUTPUT units; 0 (default):
                                   1e-3 of the output outline's bounds diagonal */
    rugo_real max_size;       /**< largest bounds diagonal of the output accepted, output units (default
                                   RUGO_DEFAULT_IMPORT_MAX_SIZE); larger: BAD_SIZE */
    rugo_allocator allocator; /**< for the result and scratch (zeroed: malloc/free) */
    int cookie;               /**< set by rugo_default_import_def; catches uninitialised defs */
} rugo_import_def;

/** The defaults described in rugo_import_def. */
RUGO_API rugo_import_def rugo_default_import_def(void);

/** An imported outline; owns fit.control_points (free with rugo_import_result_free). */
typedef struct rugo_import_result {
    rugo_outline_fit fit; /**< the fitted outline in output units (counter-clockwise, recentred when asked);
                               its max_error and rms_error are in output units */
    int from_svg;         /**< 1 for an SVG document, 0 for a point list */
    int sample_count;     /**< samples fitted */
    rugo_real perimeter;  /**< of the sampled outline, output units */
    rugo_real tolerance;  /**< the tolerance used (output units), 0 for an explicit control_count */
    rugo_real size;       /**< bounds diagonal of the samples, output units */
    rugo_vec2 offset;     /**< translation applied by recentring (minus the centroid before it), output
                               units; (0, 0) without recentre */
    rugo_affine drawing_to_output; /**< the drawing's coordinates (SVG: the root's user units, y down;
                                        a point list: its own frame) to the output, recentring included */
    rugo_affine output_to_drawing; /**< its inverse: where to look in the drawing for an output point */
} rugo_import_result;

/** An outline from an SVG `<path>` or a point list, in the units a game wants, in one call:
 * rugo_svg_import_outline (or rugo_points_text_parse and rugo_outline_sample) with the transform
 * scale * flip_y * (viewBox map when asked), rugo_fit_outline at control_count or the tolerance (both
 * in output units, so the reported error is in output units), a check that the fitted curve does not
 * cross itself, and recentring. A fit that does not reach the tolerance is returned with
 * fit.tolerance_met 0 (not an error). Deterministic.
 * Errors (out zeroed; error gets line, column, a field and a message naming the value and a way out;
 * error may be NULL): NULL_ARGUMENT, BAD_ARGUMENT (def not from rugo_default_import_def; scale or
 * max_size not finite and > 0; a negative tolerance or sample_count; path_id or use_viewbox for a point
 * list), NOT_POWER_OF_TWO (control_count not a power of two >= 4: the message says which counts work),
 * BAD_SIZE (the output larger than max_size: the message gives the size and a scale that fixes it),
 * SELF_INTERSECTING (the outline, or its fit, crosses itself: the message gives the crossing in the
 * drawing's coordinates), and those of rugo_svg_read_viewport, rugo_svg_import_outline,
 * rugo_points_text_parse, rugo_outline_sample and rugo_fit_outline. */
RUGO_API rugo_status rugo_import_outline(const rugo_import_def* def, rugo_import_result* out,
                                         rugo_parse_error* error);

/** Frees the result's control points and zeroes it (NULL and a zeroed result are fine). */
RUGO_API void rugo_import_result_free(rugo_import_result* result);

#ifdef __cplusplus
}
#endif

#endif
