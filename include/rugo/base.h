/* librugo — base types: reals, 2-D vectors, status codes, allocator hooks, version.
 *
 * Every public function that takes outside input returns a rugo_status and never aborts, prints or
 * exits. Memory goes through a rugo_allocator carried by the def of each object that allocates; a NULL
 * or zeroed allocator means the C library's malloc/free. There is no global mutable state. */
#ifndef RUGO_BASE_H
#define RUGO_BASE_H

#include <math.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RUGO_VERSION_MAJOR 0
#define RUGO_VERSION_MINOR 1
#define RUGO_VERSION_PATCH 0
#define RUGO_VERSION_STRING "0.1.0"

/* Double precision everywhere inside librugo. */
typedef double rugo_real;

typedef struct rugo_vec2 {
    rugo_real x, y;
} rugo_vec2;

/* Status codes. Values are stable (files and tools may print them); add new codes at the end. */
typedef enum rugo_status {
    RUGO_OK = 0,
    RUGO_ERR_NULL_ARGUMENT = 1,     /* a required pointer was NULL */
    RUGO_ERR_OUT_OF_MEMORY = 2,     /* the allocator returned NULL */
    RUGO_ERR_TOO_FEW_POINTS = 3,    /* a closed cubic contour needs at least 4 control points */
    RUGO_ERR_NOT_FINITE = 4,        /* a NaN or infinite value in the input */
    RUGO_ERR_ZERO_AREA = 5,         /* the outline encloses no area (collinear or coincident points) */
    RUGO_ERR_SELF_INTERSECTING = 6, /* the outline crosses itself (see rugo_contour_problem) */
    RUGO_ERR_NOT_POWER_OF_TWO = 7,  /* the count must be a power of two here */
    RUGO_ERR_BAD_ARGUMENT = 8,      /* a parameter out of its documented range */
    RUGO_ERR_BAD_FILTER = 9,        /* unknown wavelet filter */
    RUGO_ERR_BAD_LEVEL = 10,        /* a level outside the pyramid, or a coarsest level below 4 points */
    RUGO_ERR_TOO_MANY_POINTS = 11,  /* a count beyond RUGO_MAX_CONTROL_POINTS */
    RUGO_ERR_PARSE = 12,            /* malformed text (JSON syntax) */
    RUGO_ERR_BAD_FIELD = 13,        /* well-formed text with a missing or wrongly typed field */
    RUGO_ERR_SINGULAR = 14,         /* a linear system has no unique solution (e.g. too few fit points) */
    RUGO_ERR_NOT_CONVERGED = 15,    /* an iteration did not reach its tolerance */
    RUGO_ERR_UNSUPPORTED = 16,      /* the feature was left out of this build (e.g. no Eigen shim) */
    RUGO_ERR_IO = 17,               /* a file could not be read or written */
    RUGO_ERR_NEGATIVE_TOLERANCE = 18, /* a tolerance (roughness band) below zero */
    RUGO_ERR_EMPTY_RANGE = 19,      /* a range whose lower end exceeds its upper end (e.g. λ_min > λ_max) */
    RUGO_ERR_BAD_QUANTILE = 20,     /* the band factor q of λ = q σ is not > 0 */
    RUGO_ERR_WORLD_LOCKED = 21,     /* the physics world is inside a step or callback; retry after the step */
    RUGO_ERR_NOT_ATTACHED = 22,     /* the body has no rough shape attached */
    RUGO_ERR_ALREADY_ATTACHED = 23, /* the body already has a rough shape attached */
    RUGO_ERR_BAD_FORMAT = 24,       /* not a baked shape file (wrong magic) or a field out of range */
    RUGO_ERR_BAD_VERSION = 25,      /* a baked file of a version this library does not read */
    RUGO_ERR_CHECKSUM = 26,         /* a baked file whose checksum does not match (corrupted) */
    RUGO_ERR_TRUNCATED = 27,        /* a file or buffer shorter than its header says */
    RUGO_ERR_TOO_LARGE = 28,        /* an input beyond the documented size limit */
    RUGO_STATUS_COUNT
} rugo_status;

/* A short constant English name for a status, e.g. "self-intersecting outline". Never NULL. */
const char* rugo_status_string(rugo_status status);

/* Largest control-point count any function accepts (2^20): bounds memory use on hostile input. */
#define RUGO_MAX_CONTROL_POINTS (1 << 20)

/* User-replaceable allocation. alloc(size, ctx) returns NULL on failure; free(ptr, ctx) accepts NULL.
 * Objects keep a copy of the allocator they were created with and free through it. */
typedef struct rugo_allocator {
    void* (*alloc)(size_t size, void* ctx);
    void (*free)(void* ptr, void* ctx);
    void* ctx;
} rugo_allocator;

/* The malloc/free allocator. */
rugo_allocator rugo_default_allocator(void);

/* Runtime version, for checking that headers and library agree. */
const char* rugo_version_string(void);

/* Small vector helpers (inline so that hot loops stay cheap). */
static inline rugo_vec2 rugo_v2(rugo_real x, rugo_real y) {
    rugo_vec2 v;
    v.x = x;
    v.y = y;
    return v;
}
static inline rugo_vec2 rugo_v2_add(rugo_vec2 a, rugo_vec2 b) { return rugo_v2(a.x + b.x, a.y + b.y); }
static inline rugo_vec2 rugo_v2_sub(rugo_vec2 a, rugo_vec2 b) { return rugo_v2(a.x - b.x, a.y - b.y); }
static inline rugo_vec2 rugo_v2_scale(rugo_real s, rugo_vec2 a) { return rugo_v2(s * a.x, s * a.y); }
static inline rugo_real rugo_v2_dot(rugo_vec2 a, rugo_vec2 b) { return a.x * b.x + a.y * b.y; }
static inline rugo_real rugo_v2_cross(rugo_vec2 a, rugo_vec2 b) { return a.x * b.y - a.y * b.x; }
/* Counter-clockwise perpendicular (-y, x). */
static inline rugo_vec2 rugo_v2_perp(rugo_vec2 a) { return rugo_v2(-a.y, a.x); }

/* Rotation (cosine, sine) and rigid transform p + R v: a body's pose. */
typedef struct rugo_rot {
    rugo_real c, s;
} rugo_rot;

typedef struct rugo_transform {
    rugo_vec2 p;
    rugo_rot q;
} rugo_transform;

static inline rugo_rot rugo_rot_from_angle(rugo_real radians) {
    rugo_rot q;
    q.c = cos(radians);
    q.s = sin(radians);
    return q;
}
static inline rugo_vec2 rugo_rotate(rugo_rot q, rugo_vec2 v) { return rugo_v2(q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y); }
static inline rugo_vec2 rugo_inv_rotate(rugo_rot q, rugo_vec2 v) { return rugo_v2(q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y); }
static inline rugo_transform rugo_make_transform(rugo_real x, rugo_real y, rugo_real radians) {
    rugo_transform t;
    t.p = rugo_v2(x, y);
    t.q = rugo_rot_from_angle(radians);
    return t;
}
static inline rugo_transform rugo_identity_transform(void) { return rugo_make_transform(0.0, 0.0, 0.0); }
static inline rugo_vec2 rugo_transform_point(rugo_transform t, rugo_vec2 v) { return rugo_v2_add(t.p, rugo_rotate(t.q, v)); }
static inline rugo_vec2 rugo_inv_transform_point(rugo_transform t, rugo_vec2 v) {
    return rugo_inv_rotate(t.q, rugo_v2_sub(v, t.p));
}

#ifdef __cplusplus
}
#endif

#endif
