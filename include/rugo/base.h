/** @file rugo/base.h
 * librugo — base types: reals, 2-D vectors, transforms, axis-aligned boxes, status codes, allocator hooks,
 * version.
 *
 * Every public function that takes outside input returns a rugo_status and never aborts, prints or
 * exits. Memory goes through a rugo_allocator carried by the def of each object that allocates; a NULL
 * or zeroed allocator means the C library's malloc/free. There is no global mutable state.
 *
 * Units: librugo is unit-free; lengths are in the caller's units (the Box2D bridge and the simulator
 * use metres, kilograms and seconds). Angles are in radians. */
#ifndef RUGO_BASE_H
#define RUGO_BASE_H

/** @mainpage librugo API reference
 *
 * librugo turns an outline into a rough curved shape — a closed cubic B-spline contour with a wavelet
 * pyramid of coarser levels, roughness tolerances per segment at every level, exact mass properties and
 * a MOBBtree — and finds contacts between such shapes at a chosen level of detail, with the friction and
 * restitution of the surfaces at each contact point. Start with the guide, docs/guide.md (concepts with
 * pictures, the API by example); docs/box2d.md covers the Box2D bridge.
 *
 * One header per concept (rugo/rugo.h includes the C ones):
 * - rugo/base.h: reals, vectors, transforms, axis-aligned boxes, status codes, allocator hooks, version
 *   macros
 * - rugo/contour.h: closed cubic B-spline contours: evaluation, arc length, mass, queries, validation
 * - rugo/wavelet.h: CDF(4, m~) wavelet filters, analysis and synthesis
 * - rugo/multires.h: the multiresolution pyramid, direct manipulation and deformation
 * - rugo/random.h, rugo/rough.h: the seeded generator, the tolerance library, perturbations
 * - rugo/tolerance.h: tolerances at every level, λ(t), friction and restitution
 * - rugo/mobb.h: oriented boxes and the MOBBtree
 * - rugo/shape.h, rugo/baked.h: the immutable rough shape and its binary file
 * - rugo/collide.h: contacts at a level of detail
 * - rugo/shape_file.h: JSON shape files, roughness descriptions; rugo/fit.h: least-squares fitting
 *   and the outline fit (Eigen shim)
 * - rugo/import.h: outlines from SVG path data and point lists
 * - rugo/world.h: the thesis' impulse-based simulator
 * - rugo/box2d.hpp: the Box2D 2.4 bridge (C++)
 *
 * Conventions: the prefix rugo_ / RUGO_; objects are created from a def filled by
 * rugo_default_xxx_def(); every function that takes outside input returns a rugo_status and never
 * aborts, prints or exits; memory goes through a rugo_allocator; doubles; deterministic results;
 * yes/no answers, flag out-parameters and flag fields are C99 `bool` (stdbool.h, which base.h
 * includes); counts, indices, levels and kinds are int. */

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

/** Marks the public API: every function declared in include/rugo/ and the Box2D bridge's class
 * carry it. librugo, rugo::fit and rugo::box2d are compiled with hidden default visibility, so a shared
 * library exports exactly what is marked so and none of the internals (the rugo__ helpers): its symbol
 * table is the documented API, and calls between internals need no dynamic lookup. With GCC and clang
 * it is the default-visibility attribute; elsewhere it is empty, and the libraries are meant to be
 * built static there. */
#if defined(__GNUC__) || defined(__clang__)
#define RUGO_API __attribute__((visibility("default")))
#else
#define RUGO_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Major version of these headers (incompatible API changes). The four version macros are checked
 * against the CMake project version at configure time, so they cannot drift from the package's. */
#define RUGO_VERSION_MAJOR 0
/** Minor version of these headers (compatible additions). */
#define RUGO_VERSION_MINOR 2
/** Patch version of these headers (fixes). */
#define RUGO_VERSION_PATCH 0
/** The version of these headers as text, "MAJOR.MINOR.PATCH". */
#define RUGO_VERSION_STRING "0.2.0"
/** The version of these headers as one integer, MAJOR * 10000 + MINOR * 100 + PATCH (0.2.0 is 200),
 * for comparisons in the preprocessor; components stay below 100. */
#define RUGO_VERSION_NUMBER (RUGO_VERSION_MAJOR * 10000 + RUGO_VERSION_MINOR * 100 + RUGO_VERSION_PATCH)
/** 1 if these headers are version major.minor.patch or newer, else 0; usable in `#if`, e.g.
 * `#if RUGO_VERSION_AT_LEAST(0, 2, 0)`. Compares the components in order, so it holds for any
 * component values. For the library actually linked, compare rugo_version_string(). */
#define RUGO_VERSION_AT_LEAST(major, minor, patch)                                                           \
    (RUGO_VERSION_MAJOR > (major) ||                                                                         \
     (RUGO_VERSION_MAJOR == (major) &&                                                                       \
      (RUGO_VERSION_MINOR > (minor) || (RUGO_VERSION_MINOR == (minor) && RUGO_VERSION_PATCH >= (patch)))))

/** The real type: double precision everywhere inside librugo (the Box2D bridge converts to float at
 * the boundary). */
typedef double rugo_real;

/** A 2-D vector or point, in the caller's length units. A plain value; see rugo_v2() and the helpers
 * below. */
typedef struct rugo_vec2 {
    /** Cartesian coordinates. @{ */
    rugo_real x, y;
    /** @} */
} rugo_vec2;

/** Status codes returned by every function that can fail on its input. Values are stable (files and
 * tools may print them); new codes are added at the end. rugo_status_string() names each one. */
typedef enum rugo_status {
    RUGO_OK = 0,                      /**< success */
    RUGO_ERR_NULL_ARGUMENT = 1,       /**< a required pointer was NULL */
    RUGO_ERR_OUT_OF_MEMORY = 2,       /**< the allocator returned NULL */
    RUGO_ERR_TOO_FEW_POINTS = 3,      /**< a closed cubic contour needs at least 4 control points */
    RUGO_ERR_NOT_FINITE = 4,          /**< a NaN or infinite value in the input */
    RUGO_ERR_ZERO_AREA = 5,           /**< the outline encloses no area (collinear or coincident points) */
    RUGO_ERR_SELF_INTERSECTING = 6,   /**< the outline crosses itself (see rugo_contour_problem) */
    RUGO_ERR_NOT_POWER_OF_TWO = 7,    /**< the count must be a power of two here */
    RUGO_ERR_BAD_ARGUMENT = 8,        /**< a parameter out of its documented range */
    RUGO_ERR_BAD_FILTER = 9,          /**< unknown wavelet filter */
    RUGO_ERR_BAD_LEVEL = 10,          /**< a level outside the pyramid, or a coarsest level below 4 points */
    RUGO_ERR_TOO_MANY_POINTS = 11,    /**< a count beyond RUGO_MAX_CONTROL_POINTS */
    RUGO_ERR_PARSE = 12,              /**< malformed text (JSON syntax) */
    RUGO_ERR_BAD_FIELD = 13,          /**< well-formed text with a missing or wrongly typed field */
    RUGO_ERR_SINGULAR = 14,           /**< a linear system has no unique solution (e.g. too few fit points) */
    RUGO_ERR_NOT_CONVERGED = 15,      /**< an iteration did not reach its tolerance */
    RUGO_ERR_UNSUPPORTED = 16,        /**< the feature was left out of this build (e.g. no Eigen shim) */
    RUGO_ERR_IO = 17,                 /**< a file could not be read or written */
    RUGO_ERR_NEGATIVE_TOLERANCE = 18, /**< a tolerance (roughness band) below zero */
    RUGO_ERR_EMPTY_RANGE = 19,  /**< a range whose lower end exceeds its upper end (e.g. λ_min > λ_max) */
    RUGO_ERR_BAD_QUANTILE = 20, /**< the band factor q of λ = q σ is not > 0 */
    RUGO_ERR_WORLD_LOCKED = 21, /**< the physics world is inside a step or callback; retry after the step */
    RUGO_ERR_NOT_ATTACHED = 22, /**< the body has no rough shape attached */
    RUGO_ERR_ALREADY_ATTACHED = 23, /**< the body already has a rough shape attached */
    RUGO_ERR_BAD_FORMAT = 24,       /**< not a baked shape file (wrong magic) or a field out of range */
    RUGO_ERR_BAD_VERSION = 25,      /**< a baked file of a version this library does not read */
    RUGO_ERR_CHECKSUM = 26,         /**< a baked file whose checksum does not match (corrupted) */
    RUGO_ERR_TRUNCATED = 27,        /**< a file or buffer shorter than its header says */
    RUGO_ERR_TOO_LARGE = 28,        /**< an input beyond the documented size limit */
    RUGO_ERR_BAD_SIZE =
        29, /**< an outline too small or too large for a shape (RUGO_SHAPE_MIN_SIZE..MAX_SIZE) */
    RUGO_ERR_CACHE_MISMATCH =
        30,           /**< a contact cache holding another pair's answer (clear it, or keep one per pair) */
    RUGO_STATUS_COUNT /**< the number of codes (not a status) */
} rugo_status;

/** A short constant English name for a status, e.g. "self-intersecting outline". The string is static
 * (never free it); an unknown value gives a generic name. Never NULL, never fails. */
RUGO_API const char* rugo_status_string(rugo_status status);

/** Largest control-point count any function accepts (2^20): bounds memory use on hostile input
 * (RUGO_ERR_TOO_MANY_POINTS beyond it). */
#define RUGO_MAX_CONTROL_POINTS (1 << 20)

/** User-replaceable allocation. Objects keep a copy of the allocator they were created with and free
 * through it, so the functions and ctx must stay valid until every object created with them is
 * destroyed. A zeroed allocator (alloc == NULL) means the C library's malloc/free. librugo never
 * allocates per simulation step or query once its buffers have grown. */
typedef struct rugo_allocator {
    /** Returns size bytes aligned for any type, or NULL on failure (the caller then reports
     * RUGO_ERR_OUT_OF_MEMORY). */
    void* (*alloc)(size_t size, void* ctx);
    /** Releases a block from alloc; must accept NULL. */
    void (*free)(void* ptr, void* ctx);
    /** Passed unchanged to alloc and free; not owned by librugo. */
    void* ctx;
} rugo_allocator;

/** The malloc/free allocator (ctx NULL). Never fails. */
RUGO_API rugo_allocator rugo_default_allocator(void);

/** The version of the linked library, "MAJOR.MINOR.PATCH" (a static string; never NULL), for checking
 * that headers and library agree: compare with RUGO_VERSION_STRING. */
RUGO_API const char* rugo_version_string(void);

/** The vector (x, y). Inline, like the small vector helpers below, so that hot loops stay cheap;
 * none of them checks for NaN (NaN in, NaN out). */
static inline rugo_vec2 rugo_v2(rugo_real x, rugo_real y) {
    rugo_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}
/** a + b. */
static inline rugo_vec2 rugo_v2_add(rugo_vec2 a, rugo_vec2 b) { return rugo_v2(a.x + b.x, a.y + b.y); }
/** a - b. */
static inline rugo_vec2 rugo_v2_sub(rugo_vec2 a, rugo_vec2 b) { return rugo_v2(a.x - b.x, a.y - b.y); }
/** s a. */
static inline rugo_vec2 rugo_v2_scale(rugo_real s, rugo_vec2 a) { return rugo_v2(s * a.x, s * a.y); }
/** Dot product a·b. */
static inline rugo_real rugo_v2_dot(rugo_vec2 a, rugo_vec2 b) { return a.x * b.x + a.y * b.y; }
/** 2-D cross product a × b = a.x b.y - a.y b.x (positive when b is counter-clockwise from a). */
static inline rugo_real rugo_v2_cross(rugo_vec2 a, rugo_vec2 b) { return a.x * b.y - a.y * b.x; }
/** Counter-clockwise perpendicular (-y, x). */
static inline rugo_vec2 rugo_v2_perp(rugo_vec2 a) { return rugo_v2(-a.y, a.x); }

/** A rotation stored as (cosine, sine) of its angle; unit length for a proper rotation. */
typedef struct rugo_rot {
    /** Cosine and sine of the angle. @{ */
    rugo_real c, s;
    /** @} */
} rugo_rot;

/** A rigid transform v -> p + R v: a body's pose (translation in length units, rotation). */
typedef struct rugo_transform {
    rugo_vec2 p; /**< translation: where the local origin goes */
    rugo_rot q;  /**< rotation */
} rugo_transform;

/** The rotation by an angle in radians (counter-clockwise). */
static inline rugo_rot rugo_rot_from_angle(rugo_real radians) {
    rugo_rot q;
    q.c = cos(radians);
    q.s = sin(radians);
    return q;
}
/** R v. */
static inline rugo_vec2 rugo_rotate(rugo_rot q, rugo_vec2 v) {
    return rugo_v2(q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y);
}
/** R^T v (the inverse rotation for a unit q). */
static inline rugo_vec2 rugo_inv_rotate(rugo_rot q, rugo_vec2 v) {
    return rugo_v2(q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y);
}
/** The transform with translation (x, y) and rotation angle `radians`. */
static inline rugo_transform rugo_make_transform(rugo_real x, rugo_real y, rugo_real radians) {
    rugo_transform t;
    t.p = rugo_v2(x, y);
    t.q = rugo_rot_from_angle(radians);
    return t;
}
/** The identity transform. */
static inline rugo_transform rugo_identity_transform(void) { return rugo_make_transform(0.0, 0.0, 0.0); }
/** t applied to a point: p + R v (local to world). */
static inline rugo_vec2 rugo_transform_point(rugo_transform t, rugo_vec2 v) {
    return rugo_v2_add(t.p, rugo_rotate(t.q, v));
}
/** The inverse of t applied to a point: R^T (v - p) (world to local, for a unit rotation). */
static inline rugo_vec2 rugo_inv_transform_point(rugo_transform t, rugo_vec2 v) {
    return rugo_inv_rotate(t.q, rugo_v2_sub(v, t.p));
}

/** An axis-aligned box, in the caller's length units. */
typedef struct rugo_aabb {
    /** Lower and upper corners (lower <= upper on both axes). @{ */
    rugo_vec2 lower, upper;
    /** @} */
} rugo_aabb;

#ifdef __cplusplus
}
#endif

#endif
