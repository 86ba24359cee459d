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
    rugo_allocator allocator; /**< for the fit's own scratch buffers (zeroed: malloc/free) */
    int cookie;               /**< set by rugo_default_fit_def; catches uninitialised defs */
} rugo_fit_def;

/** A def with no samples, control_count 0, chord-length parameters, the malloc/free allocator and the
 * cookie that marks an initialised def. Never fails. */
RUGO_API rugo_fit_def rugo_default_fit_def(void);

/** How well rugo_fit_contour fitted, in length units. */
typedef struct rugo_fit_result {
    rugo_real max_error;  /**< largest distance from a sample to the curve point at its parameter */
    rugo_real rms_error;  /**< root mean square of those distances */
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
    rugo_vec2* control_points; /**< control_count points, counter-clockwise */
    int control_count;         /**< the count used (the one found, for the automatic search) */
    rugo_real max_error;       /**< largest distance from a sample to the fitted curve (closest point
                                    on the whole curve, rugo_contour_closest_point), length units */
    rugo_real rms_error;       /**< root mean square of those distances */
    rugo_real max_error_at_parameter; /**< rugo_fit_contour's error: distance to the curve point at the
                                           sample's own parameter (>= max_error) */
    bool tolerance_met;        /**< true if tolerance <= 0 or max_error <= tolerance; false when the
                                    automatic search stopped at its largest count without reaching it */
    bool reversed;             /**< true if the fit ran clockwise and the control points were reversed */
    rugo_allocator allocator;  /**< the allocator of control_points */
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

#ifdef __cplusplus
}
#endif

#endif
