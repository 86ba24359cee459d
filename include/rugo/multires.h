/* librugo — multiresolution pyramid of a contour, details in local frames, direct manipulation and
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
 * outline: a large edit can make it cross itself; check with rugo_contour_check if that matters. */
#ifndef RUGO_MULTIRES_H
#define RUGO_MULTIRES_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/wavelet.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rugo_pyramid rugo_pyramid;

typedef struct rugo_pyramid_def {
    const rugo_vec2* points; /* finest control points, copied; either orientation (normalised to CCW) */
    int count;               /* a power of two, >= 4 */
    rugo_filter filter;      /* default RUGO_FILTER_DEFAULT */
    int coarsest_level;      /* J_min >= 2 (4 points); 0 means "as coarse as possible" = 2 */
    int check_self_intersection; /* 1 (default) to reject crossing outlines */
    rugo_allocator allocator;    /* zeroed = malloc/free */
    int cookie;                  /* set by rugo_default_pyramid_def; catches uninitialised defs */
} rugo_pyramid_def;

rugo_pyramid_def rugo_default_pyramid_def(void);

/* Validates (rugo_contour_check with RUGO_CHECK_POWER_OF_TWO and, if asked, self-intersection),
 * normalises to counter-clockwise, and decomposes. problem may be NULL. On error *out is NULL. */
rugo_status rugo_pyramid_create(const rugo_pyramid_def* def, rugo_pyramid** out,
                                rugo_contour_problem* problem);
void rugo_pyramid_destroy(rugo_pyramid* p);

int rugo_pyramid_finest_level(const rugo_pyramid* p);   /* J */
int rugo_pyramid_coarsest_level(const rugo_pyramid* p); /* J_min */
rugo_filter rugo_pyramid_filter(const rugo_pyramid* p);
/* 1 if the input was clockwise and was reversed. */
int rugo_pyramid_was_reversed(const rugo_pyramid* p);
/* The allocator the pyramid was created with (so helpers can allocate scratch from the same heap). */
rugo_allocator rugo_pyramid_allocator(const rugo_pyramid* p);

/* The curve of level j (a view into the pyramid, valid until the next edit or destroy).
 * RUGO_ERR_BAD_LEVEL outside [J_min, J]. */
rugo_status rugo_pyramid_level(const rugo_pyramid* p, int level, rugo_contour* out);
/* Details D^j (2^j points), world coordinates or local frames (x = tangent, y = normal component).
 * Valid for J_min <= j < J. */
rugo_status rugo_pyramid_details(const rugo_pyramid* p, int level, const rugo_vec2** world,
                                 const rugo_vec2** local);

/* Parameter correspondence between levels: point (segment, t) on level `from` is the point
 * (segment', t') on level `to` that converges to it (segment alignment, SPEC 2.2). Going up, t = 1
 * stays in the last sub-segment with t' = 1. Levels outside 0..30 or a non-finite t are returned
 * unchanged (this function has no status; validate first). */
void rugo_level_parameter(int from, int segment, rugo_real t, int to, int* out_segment, rugo_real* out_t);

/* How details follow an edit of coarser points. */
typedef enum rugo_detail_mode {
    RUGO_DETAILS_FIXED = 0,   /* world-coordinate details held fixed (Theorem 2.1's setting: exact) */
    RUGO_DETAILS_LOCAL = 1    /* details re-oriented in the local frames of the edited curve */
} rugo_detail_mode;

/* Direct manipulation (2.30)-(2.31): move the point f^level_segment(t) by delta with the least-norm
 * change of the four control points of that level, then rebuild all finer levels (details per mode)
 * and all coarser levels by analysis. level in [J_min, J]. */
rugo_status rugo_pyramid_move_point(rugo_pyramid* p, int level, int segment, rugo_real t,
                                    rugo_vec2 delta, rugo_detail_mode mode);

/* Multiresolution deformation (2.3.2): move the finest-level point f^J_segment(t) by delta, spread over
 * levels J, J-1, ..., J - spread + 1 with weights of g(s) = e^{-w s} / A (w = 0: equal weights),
 * each piece applied by direct manipulation at the corresponding point of its level, then
 * reconstructed. spread in [1, J - J_min + 1]. weights_out (spread entries, finest first) may be NULL. */
rugo_status rugo_pyramid_deform(rugo_pyramid* p, int segment, rugo_real t, rugo_vec2 delta, int spread,
                                rugo_real w, rugo_detail_mode mode, rugo_real* weights_out);

/* The weights ∫_{i/m}^{(i+1)/m} g(s) ds, i = 0..m-1, of g(s) = e^{-w s}/A; they sum to 1. */
rugo_status rugo_deformation_weights(int m, rugo_real w, rugo_real* out);

/* Add delta[i] to the control points of `level` (2^level entries) and rebuild: finer levels by
 * synthesis with the details per mode, then every level again by analysis of the new finest points.
 * The building block of every edit. */
rugo_status rugo_pyramid_displace_level(rugo_pyramid* p, int level, const rugo_vec2* delta,
                                        rugo_detail_mode mode);

/* Replace the finest control points (count must match) and rebuild every level. The points are
 * checked with the flags used at creation and re-oriented to counter-clockwise (was_reversed is
 * updated). */
rugo_status rugo_pyramid_set_finest(rugo_pyramid* p, const rugo_vec2* points, int count);

#ifdef __cplusplus
}
#endif

#endif
