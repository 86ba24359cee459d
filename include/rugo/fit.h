/* librugo — least-squares fitting and simultaneous multi-point manipulation.
 *
 * These functions live in the Eigen shim (CMake target rugo::fit, C++17 inside, this C API outside).
 * The core library rugo::rugo does not depend on it. When the project is configured with
 * RUGO_WITH_EIGEN=OFF the target does not exist. */
#ifndef RUGO_FIT_H
#define RUGO_FIT_H

#include "rugo/base.h"
#include "rugo/multires.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rugo_parameterization {
    RUGO_PARAM_CHORD_LENGTH = 0, /* parameters proportional to cumulative chord length (default) */
    RUGO_PARAM_UNIFORM = 1       /* sample k of m at u = k * n / m (n control points) */
} rugo_parameterization;

typedef struct rugo_fit_def {
    const rugo_vec2* samples; /* ordered points around a closed outline; the last need not repeat the first */
    int sample_count;         /* >= control_count */
    int control_count;        /* 2^J >= 4 */
    rugo_parameterization parameterization;
    rugo_allocator allocator;
    int cookie;
} rugo_fit_def;

rugo_fit_def rugo_default_fit_def(void);

typedef struct rugo_fit_result {
    rugo_real max_error;  /* largest distance from a sample to the curve point at its parameter */
    rugo_real rms_error;  /* root mean square of those distances */
} rugo_fit_result;

/* Least-squares fit of a closed uniform cubic B-spline with control_count control points to the
 * samples. control_points receives control_count points (caller-owned). The result keeps the
 * samples' orientation; normalise with rugo_contour_orient_ccw if needed. Parameters stay as chosen
 * (no parameter correction), so the errors are distances to the curve point at each sample's own
 * parameter. Samples are scaled into [-1, 1]^2 internally, so any scale and offset works.
 * result may be NULL; on error control_points and result are untouched.
 * Errors: NULL_ARGUMENT, TOO_FEW_POINTS, NOT_POWER_OF_TWO, NOT_FINITE (input, or a fitted point that
 * would overflow), TOO_MANY_POINTS (either count beyond RUGO_MAX_CONTROL_POINTS), BAD_ARGUMENT
 * (sample_count < control_count, bad parameterization, repeated consecutive samples making chord
 * length zero), SINGULAR (a control point no sample influences, or a pivot showing the system may be singular
 * (condition number beyond about 1e11):
 * with chord-length parameters and about as many samples as control points this happens often),
 * OUT_OF_MEMORY. Buffers of its own use def->allocator; Eigen's containers use the default heap. */
rugo_status rugo_fit_contour(const rugo_fit_def* def, rugo_vec2* control_points, rugo_fit_result* result);

/* Simultaneous direct manipulation of several points of one level (2.30-2.31 generalised): move
 * f^level_{segments[i]}(ts[i]) by deltas[i] for all i with the least-norm change of that level's
 * control points, then rebuild the pyramid as rugo_pyramid_move_point does. Constraints that share
 * control points are solved together (rank-revealing, so consistent duplicates are fine); the cost
 * grows with the cube of the largest such cluster: meant for an editor's handful of points.
 * Errors: NULL_ARGUMENT, BAD_LEVEL, BAD_ARGUMENT (segment out of range, t outside [0,1] or NaN, bad
 * mode, count < 1), NOT_FINITE, TOO_MANY_POINTS, OUT_OF_MEMORY, and SINGULAR if the constraints
 * conflict (e.g. the same point twice with different deltas); on error the pyramid is unchanged. */
rugo_status rugo_pyramid_move_points(rugo_pyramid* p, int level, int count, const int* segments,
                                     const rugo_real* ts, const rugo_vec2* deltas, rugo_detail_mode mode);

#ifdef __cplusplus
}
#endif

#endif
