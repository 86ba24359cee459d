/** @file rugo/multires.h
 * librugo — multiresolution pyramid of a contour, details in local frames, direct manipulation and
 * multiresolution deformation (SPEC 2.3, 3; thesis 2.2-2.3).
 *
 * Levels are numbered as in the thesis: the finest level J has 2^J control points, level j has 2^j.
 * The pyramid keeps the control points of every level C^j (J_min <= j <= J) and the details D^j
 * (J_min <= j < J, 2^j each, d_s centred at fine index 2s-1), both in world coordinates, and the
 * details in local frames: d = u * tangent + v * normal of the coarse curve f^j at the midpoint of
 * segment s-1 (the point of f^j that corresponds to fine index 2s-1); the frame is (unit tangent,
 * outward unit normal), so the local y component is the outward part.
 *
 * Errors common to the functions below: NULL_ARGUMENT; BAD_ARGUMENT for a def without the cookie of
 * rugo_default_pyramid_def, a segment outside [0, 2^level) (not wrapped, unlike the contour queries),
 * t outside [0, 1], or a wrong count; NOT_FINITE for a non-finite delta or w, or an edit whose result
 * would overflow (the pyramid is then left exactly as it was); BAD_LEVEL for a level or spread out of
 * range. Edits allocate nothing (working space is reserved at creation). Edits do not re-check the
 * outline: a large edit can make it cross itself; check with rugo_contour_check if that matters.
 *
 * Ownership: a pyramid is created by rugo_pyramid_create, owned by the caller and freed by
 * rugo_pyramid_destroy; it copies its input points and allocates only at creation, through the def's
 * allocator. Views it returns (levels, details) point into it. Coordinates are in the caller's length
 * units. */
#ifndef RUGO_MULTIRES_H
#define RUGO_MULTIRES_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/wavelet.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The multiresolution pyramid of a contour (opaque): control points of every level, details in world
 * coordinates and in local frames. Created by rugo_pyramid_create, freed by rugo_pyramid_destroy. */
typedef struct rugo_pyramid rugo_pyramid;

/** What rugo_pyramid_create needs. Start from rugo_default_pyramid_def(). */
typedef struct rugo_pyramid_def {
    const rugo_vec2* points; /**< finest control points, copied; either orientation (normalised to CCW) */
    int count;               /**< a power of two, >= 4 */
    rugo_filter filter;      /**< default RUGO_FILTER_DEFAULT */
    int coarsest_level;      /**< J_min >= 2 (4 points); 0 means "as coarse as possible" = 2 */
    bool check_self_intersection; /**< true (default) to reject crossing outlines */
    rugo_allocator allocator;     /**< zeroed = malloc/free */
    int cookie;                   /**< set by rugo_default_pyramid_def; catches uninitialised defs */
} rugo_pyramid_def;

/** A def with the defaults above and its cookie set; fill in points and count. Never fails. */
RUGO_API rugo_pyramid_def rugo_default_pyramid_def(void);

/** Validates (rugo_contour_check with RUGO_CHECK_POWER_OF_TWO and, if asked, self-intersection),
 * normalises to counter-clockwise, and decomposes into levels J_min..J. On success *out is a new
 * pyramid owned by the caller (free it with rugo_pyramid_destroy); the def and its points are not
 * kept. problem (may be NULL) receives what a failed check found. Errors: those of
 * rugo_contour_check, NULL_ARGUMENT, BAD_ARGUMENT (cookie), BAD_FILTER, BAD_LEVEL (coarsest level out
 * of range), OUT_OF_MEMORY. On error *out is NULL. */
RUGO_API rugo_status rugo_pyramid_create(const rugo_pyramid_def* def, rugo_pyramid** out,
                                         rugo_contour_problem* problem);
/** Frees the pyramid through its allocator; NULL is allowed. Views into it become invalid. */
RUGO_API void rugo_pyramid_destroy(rugo_pyramid* p);

/** The finest level J (2^J control points); -1 for NULL. */
RUGO_API int rugo_pyramid_finest_level(const rugo_pyramid* p);
/** The coarsest level J_min; -1 for NULL. */
RUGO_API int rugo_pyramid_coarsest_level(const rugo_pyramid* p);
/** The wavelet filter of the pyramid; RUGO_FILTER_COUNT for NULL. */
RUGO_API rugo_filter rugo_pyramid_filter(const rugo_pyramid* p);
/** true if the input was clockwise and was reversed (false for NULL). */
RUGO_API bool rugo_pyramid_was_reversed(const rugo_pyramid* p);
/** The allocator the pyramid was created with (so helpers can allocate scratch from the same heap);
 * the default allocator for NULL. */
RUGO_API rugo_allocator rugo_pyramid_allocator(const rugo_pyramid* p);

/** The curve of level j (a view into the pyramid, valid until the next edit or destroy).
 * Errors: NULL_ARGUMENT, BAD_LEVEL (outside [J_min, J]). */
RUGO_API rugo_status rugo_pyramid_level(const rugo_pyramid* p, int level, rugo_contour* out);
/** Details D^j (2^j points), world coordinates or local frames (x = tangent, y = normal component),
 * as views into the pyramid (valid until the next edit or destroy); world and local may each be NULL.
 * Valid for J_min <= j < J. Errors: NULL_ARGUMENT (p), BAD_LEVEL. */
RUGO_API rugo_status rugo_pyramid_details(const rugo_pyramid* p, int level, const rugo_vec2** world,
                                          const rugo_vec2** local);

/** Parameter correspondence between levels: point (segment, t) on level `from` is the point
 * (segment', t') on level `to` that converges to it (segment alignment, SPEC 2.2). Going up, t = 1
 * stays in the last sub-segment with t' = 1. Levels outside 0..30 or a non-finite t are returned
 * unchanged (this function has no status; validate first). */
RUGO_API void rugo_level_parameter(int from, int segment, rugo_real t, int to, int* out_segment,
                                   rugo_real* out_t);

/** How details follow an edit of coarser points. */
typedef enum rugo_detail_mode {
    RUGO_DETAILS_FIXED = 0, /**< world-coordinate details held fixed (Theorem 2.1's setting: exact) */
    RUGO_DETAILS_LOCAL = 1  /**< details re-oriented in the local frames of the edited curve */
} rugo_detail_mode;

/** Direct manipulation (2.30)-(2.31): move the point f^level_segment(t) by delta (length units) with
 * the least-norm change of the four control points of that level, then rebuild all finer levels
 * (details per mode) and all coarser levels by analysis. level in [J_min, J]. Errors: see the top of
 * this file; on error the pyramid is unchanged. */
RUGO_API rugo_status rugo_pyramid_move_point(rugo_pyramid* p, int level, int segment, rugo_real t,
                                             rugo_vec2 delta, rugo_detail_mode mode);

/** Multiresolution deformation (2.3.2): move the finest-level point f^J_segment(t) by delta, spread over
 * levels J, J-1, ..., J - spread + 1 with weights of g(s) = e^{-w s} / A (w = 0: equal weights),
 * each piece applied by direct manipulation at the corresponding point of its level, then
 * reconstructed. spread in [1, J - J_min + 1]. weights_out (caller-owned, spread entries, finest first) may
 * be NULL. Errors: see the top of this file; on error the pyramid is unchanged. */
RUGO_API rugo_status rugo_pyramid_deform(rugo_pyramid* p, int segment, rugo_real t, rugo_vec2 delta,
                                         int spread, rugo_real w, rugo_detail_mode mode,
                                         rugo_real* weights_out);

/** The weights ∫_{i/m}^{(i+1)/m} g(s) ds, i = 0..m-1, of g(s) = e^{-w s}/A into out (caller-owned, m
 * entries); they sum to 1. Errors: NULL_ARGUMENT, BAD_ARGUMENT (m < 1), NOT_FINITE (w). */
RUGO_API rugo_status rugo_deformation_weights(int m, rugo_real w, rugo_real* out);

/** Add delta[i] to the control points of `level` (2^level entries) and rebuild: finer levels by
 * synthesis with the details per mode, then every level again by analysis of the new finest points.
 * The building block of every edit. delta is caller-owned, 2^level entries in length units. Errors:
 * see the top of this file; on error the pyramid is unchanged. */
RUGO_API rugo_status rugo_pyramid_displace_level(rugo_pyramid* p, int level, const rugo_vec2* delta,
                                                 rugo_detail_mode mode);

/** Replace the finest control points (count must match; the points are copied) and rebuild every
 * level. The points are checked with the flags used at creation and re-oriented to counter-clockwise
 * (was_reversed is updated). Errors: NULL_ARGUMENT, BAD_ARGUMENT (count), those of rugo_contour_check;
 * on error the pyramid is unchanged. */
RUGO_API rugo_status rugo_pyramid_set_finest(rugo_pyramid* p, const rugo_vec2* points, int count);

#ifdef __cplusplus
}
#endif

#endif
