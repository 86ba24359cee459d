/** @file rugo/shape.h
 * librugo — the rough curved shape: everything a body needs, built once and immutable.
 *
 * A rugo_shape owns the wavelet pyramid of its contour (levels J_min..J), the tolerances λ and hard
 * bounds β of every level, the MOBBtree, the exact mass properties (unit density) and the surface's
 * friction map and restitution. Once created it never changes, so one shape can be shared by many
 * bodies and threads; all queries on it are re-entrant. Everything is in the shape's local frame;
 * bodies place it with a rugo_transform. Lengths are in the caller's units (metres for the Box2D
 * bridge and the simulator).
 *
 * Ownership: rugo_shape_create (or rugo_shape_load_baked, baked.h) returns a shape owned by the caller,
 * freed by rugo_shape_destroy after every body, world or bridge that uses it. It copies its inputs;
 * all views and pointers it returns stay valid for its lifetime. Accessors given NULL return -1, 0,
 * NULL, false or NaN values (they have no status). */
#ifndef RUGO_SHAPE_H
#define RUGO_SHAPE_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/mobb.h"
#include "rugo/multires.h"
#include "rugo/tolerance.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Smallest size a shape may have (diagonal of its finest curve's bounds, length units; else
 * RUGO_ERR_BAD_SIZE): below, squared distances underflow and the polar inertia (at most size^4) leaves
 * the baked format's value range. Position is not limited (only by finiteness). */
#define RUGO_SHAPE_MIN_SIZE 1e-37
/** Largest size a shape may have (as RUGO_SHAPE_MIN_SIZE): above, the polar inertia exceeds the baked
 * format's value limit of 1e150. */
#define RUGO_SHAPE_MAX_SIZE 1e37

/** A built rough shape (opaque, immutable): pyramid, tolerances, MOBBtree, mass, surface. */
typedef struct rugo_shape rugo_shape;

/** What rugo_shape_create needs. Start from rugo_default_shape_def(); the arrays are borrowed for the
 * call only. */
typedef struct rugo_shape_def {
    const rugo_vec2* points;     /**< 2^J control points, either orientation (normalised to CCW) */
    int count;                   /**< number of control points: a power of two >= 4 */
    rugo_filter filter;          /**< default RUGO_FILTER_DEFAULT */
    int coarsest_level;          /**< J_min >= 2; 0 = as coarse as possible (2). With check_self_intersection
                                      set, J_min is raised above any level whose curve crosses or touches
                                      itself (a coarse level of sharp corners can loop): every level kept is
                                      a simple closed curve. rugo_shape_coarsest_level gives the result. */
    const rugo_real* tolerances; /**< λ per finest segment of the INPUT order (count values); NULL = smooth */
    rugo_real q;                 /**< default RUGO_DEFAULT_Q */
    rugo_tolerance_estimator estimator; /**< default RUGO_ESTIMATOR_DETAIL */
    rugo_friction_map friction;         /**< default rugo_default_friction_map() */
    rugo_restitution restitution;       /**< default rugo_default_restitution() */
    rugo_box_method box_method;         /**< default RUGO_BOXES_MULTIRES */
    bool check_self_intersection; /**< default true: reject a crossing outline, drop looping coarse levels */
    rugo_allocator allocator;     /**< used for the shape's lifetime; zeroed = malloc/free */
    int cookie;                   /**< set by rugo_default_shape_def; catches uninitialised defs */
} rugo_shape_def;

/** A def with the defaults above and its cookie set; fill in points and count (and tolerances). */
RUGO_API rugo_shape_def rugo_default_shape_def(void);

/** Validates and builds everything. A clockwise input is reversed, and its tolerances with it.
 * On success *out is a new shape owned by the caller (free with rugo_shape_destroy); on error NULL.
 * Errors: NULL_ARGUMENT, BAD_ARGUMENT (cookie), BAD_SIZE (the outline's size, the diagonal of the
 * finest curve's bounds, outside [RUGO_SHAPE_MIN_SIZE, RUGO_SHAPE_MAX_SIZE], or a tolerance above
 * RUGO_SHAPE_MAX_SIZE: either would leave the baked format's value range), those of rugo_pyramid_create,
 * rugo_tolerances_create, rugo_mobb_tree_create, rugo_friction_map_check and rugo_restitution_check.
 * problem may be NULL. */
RUGO_API rugo_status rugo_shape_create(const rugo_shape_def* def, rugo_shape** out,
                                       rugo_contour_problem* problem);
/** Frees the shape through its allocator; NULL is allowed. Nothing may use it afterwards. */
RUGO_API void rugo_shape_destroy(rugo_shape* shape);

/** The finest level J (2^J segments); -1 for NULL. */
RUGO_API int rugo_shape_finest_level(const rugo_shape* s);
/** The coarsest level J_min; -1 for NULL. */
RUGO_API int rugo_shape_coarsest_level(const rugo_shape* s);
/** The curve of a level (a view valid for the shape's lifetime), in the shape's local frame. Errors:
 * NULL_ARGUMENT, BAD_LEVEL (outside [J_min, J]). */
RUGO_API rugo_status rugo_shape_level(const rugo_shape* s, int level, rugo_contour* out);
/** The tolerances λ, own estimates and hard bounds β of a level (views valid for the shape's
 * lifetime, length units; all zero for a smooth shape). Errors: NULL_ARGUMENT, BAD_LEVEL. */
RUGO_API rugo_status rugo_shape_tolerance_level(const rugo_shape* s, int level, rugo_tolerance_level* out);
/** The certified level-of-detail error of `level` against the finest level (rugo_tolerance_level_error
 * on the shape's curves and λ): *max_error bounds how far the level's curve-plus-band lies from the
 * finest one's anywhere, so a contact computed at this level has a band-adjusted separation within the
 * sum of the two bodies' values of the finest level's. per_segment (may be NULL) gets 2^level values.
 * 0 at the finest level. Errors (then *max_error is NaN): NULL_ARGUMENT, BAD_LEVEL. */
RUGO_API rugo_status rugo_shape_level_error(const rugo_shape* s, int level, rugo_real* per_segment,
                                            rugo_real* max_error);
/** The level of detail a certified error budget allows: the coarsest level j whose
 * rugo_shape_level_error is at most `budget` (length units) at j and at every finer level (computed once,
 * when the shape is built). The finest level for a negative or NaN budget; -1 for NULL. */
RUGO_API int rugo_shape_level_for_error(const rugo_shape* s, rugo_real budget);
/** Closest point on the curve of `level` (J_min..J) to p (shape's local frame) into *out: the same
 * answer, bit for bit, as rugo_contour_closest_point on that level's curve, computed through the
 * MOBBtree (the boxes near p and the few segments under them instead of a pass over all segments).
 * Re-entrant, no allocation. On error *out (if not NULL) is p itself with distance HUGE_VAL. Errors:
 * NULL_ARGUMENT, BAD_LEVEL, NOT_FINITE (p not finite, or a coordinate beyond 1e150, where squared
 * distances overflow). */
RUGO_API rugo_status rugo_shape_closest_point(const rugo_shape* s, int level, rugo_vec2 p,
                                              rugo_curve_point* out);
/** *inside = rugo_contour_contains on the curve of `level` (J_min..J) at p (shape's local frame): the
 * same answer on every input, computed through the MOBBtree (the boxes along the ray from p towards
 * +x and the segments under them). Re-entrant, no allocation. On error *inside (if not NULL) is
 * false. Errors: NULL_ARGUMENT, BAD_LEVEL, NOT_FINITE (p). */
RUGO_API rugo_status rugo_shape_contains(const rugo_shape* s, int level, rugo_vec2 p, bool* inside);
/** The first hit of the ray origin + s * direction, s in [0, max_fraction], on the curve of `level`
 * (J_min..J; shape's local frame): the same answer, bit for bit, as rugo_contour_ray_cast on that
 * level's curve, computed through the MOBBtree (only the segments under the boxes the ray segment
 * meets, taken in the same order, and none beyond the best hit so far). *found says whether it hit;
 * on a hit *fraction = s, *hit (segment, t, point, distance = s |direction|) and *normal (unit,
 * outward) are filled as there; fraction, hit and normal may be NULL, and are left untouched without
 * a hit or on error. An origin on the curve hits at s = 0; a hit at a joint is t = 0 of the next
 * segment. Re-entrant, no allocation. Errors (then *found, if not NULL, is false): NULL_ARGUMENT (s
 * or found), BAD_LEVEL, NOT_FINITE (origin, direction or max_fraction not finite, or a coordinate of
 * origin or direction beyond 1e150, where squared lengths overflow), BAD_ARGUMENT (max_fraction < 0,
 * or a direction of zero length or too short to square). */
RUGO_API rugo_status rugo_shape_ray_cast(const rugo_shape* s, int level, rugo_vec2 origin,
                                         rugo_vec2 direction, rugo_real max_fraction, rugo_real* fraction,
                                         rugo_curve_point* hit, rugo_vec2* normal, bool* found);
/** The shape's MOBBtree (owned by the shape); NULL for NULL. */
RUGO_API const rugo_mobb_tree* rugo_shape_tree(const rugo_shape* s);
/** The shape's wavelet pyramid (owned by the shape; read only); NULL for NULL. */
RUGO_API const rugo_pyramid* rugo_shape_pyramid(const rugo_shape* s);
/** Area, centroid and polar inertia about the centroid for unit density (positive: the shape is
 * counter-clockwise); multiply by a density for mass and moment. NaN values for NULL. */
RUGO_API rugo_mass_properties rugo_shape_mass(const rugo_shape* s);
/** The surface's friction map (NaN values for NULL). */
RUGO_API rugo_friction_map rugo_shape_friction_map(const rugo_shape* s);
/** The surface's restitution (NaN values for NULL). */
RUGO_API rugo_restitution rugo_shape_restitution(const rugo_shape* s);
/** true if any finest tolerance is > 0 (false for NULL). */
RUGO_API bool rugo_shape_is_rough(const rugo_shape* s);
/** true if the input was clockwise and was reversed (segment j of the input is segment n-2-j here;
 * false for NULL). */
RUGO_API bool rugo_shape_was_reversed(const rugo_shape* s);

#ifdef __cplusplus
}
#endif

#endif
