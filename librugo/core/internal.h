/* Private helpers shared by librugo's sources. Not installed. */
#ifndef RUGO_INTERNAL_H
#define RUGO_INTERNAL_H

#include "rugo/base.h"

#include <math.h>
#include <stdint.h> /* rugo__decode_f64_le */
#include <string.h>

/* Internal invariants: on in debug and test builds (RUGO_ENABLE_ASSERT), off in release builds.
 * Never used for outside input, which gets a status instead. */
#ifdef RUGO_ENABLE_ASSERT
/* Not assert(): NDEBUG (set by release build types) must not silently turn these off. */
#include <stdio.h>
#include <stdlib.h>
#define RUGO_ASSERT(cond)                                                                                    \
    ((cond) ? (void)0                                                                                        \
            : (fprintf(stderr, "%s:%d: RUGO_ASSERT(%s) failed\n", __FILE__, __LINE__, #cond), abort()))
#else
#define RUGO_ASSERT(cond) ((void)0)
#endif

#ifdef __cplusplus
extern "C" { /* the Eigen shim includes this file too */
#endif

/* The allocation helpers are inline because the Eigen shim uses them too: in a shared build
 * librugo.so exports only the public API, so librugo_fit.so gets its own copies rather than calling
 * librugo's. */

/* A usable allocator from a possibly NULL or zeroed one. */
static inline rugo_allocator rugo__allocator_or_default(const rugo_allocator* a) {
    if (a == NULL || a->alloc == NULL || a->free == NULL) return rugo_default_allocator();
    return *a;
}

/* Allocate count * size bytes, checking the multiplication for overflow; NULL on failure. */
static inline void* rugo__alloc_array(const rugo_allocator* a, size_t count, size_t size) {
    rugo_allocator al = rugo__allocator_or_default(a);
    if (count == 0 || size == 0) count = size = 1; /* never ask for 0 bytes: malloc(0) may be NULL */
    if (count > SIZE_MAX / size) return NULL;
    return al.alloc(count * size, al.ctx);
}

static inline void rugo__free(const rugo_allocator* a, void* p) {
    rugo_allocator al = rugo__allocator_or_default(a);
    if (p != NULL) al.free(p, al.ctx);
}

/* The longest number text rugo__strtod_c converts (the JSON and SVG readers' limits are within it). */
#define RUGO__MAX_DECIMAL_CHARS 1024
/* strtod of text[0, n) (a number the caller's grammar already accepted), independent of the locale:
 * strtod reads the locale's decimal point, so when a first attempt stops at the '.', a second one uses
 * the locale's. Returns 1 on success, 0 if n > RUGO__MAX_DECIMAL_CHARS or neither attempt reads the
 * whole text (which a conforming C library never does for grammar-checked input). */
int rugo__strtod_c(const char* text, size_t n, double* out);

#ifdef __cplusplus
}
#endif

/* Cyclic index in [0, n). */
static inline int rugo__wrap(int i, int n) {
    int r = i % n;
    return r < 0 ? r + n : r;
}

static inline int rugo__is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

static inline int rugo__v2_finite(rugo_vec2 v) { return isfinite(v.x) && isfinite(v.y); }

static inline rugo_real rugo__v2_length(rugo_vec2 v) { return hypot(v.x, v.y); }

/* Little-endian binary64 (the baked format, docs/baked.md) into doubles, whatever the host's byte
 * order: 8 bytes assembled by shifts into a uint64, then its bit pattern. Compilers turn the shifts
 * into one load on little-endian hosts, so this is a plain copy there. */
static inline void rugo__decode_f64_le(double* dst, const unsigned char* src, size_t count) {
    for (size_t i = 0; i < count; ++i, src += 8) {
        const uint64_t bits = (uint64_t)src[0] | ((uint64_t)src[1] << 8) | ((uint64_t)src[2] << 16) |
                              ((uint64_t)src[3] << 24) | ((uint64_t)src[4] << 32) | ((uint64_t)src[5] << 40) |
                              ((uint64_t)src[6] << 48) | ((uint64_t)src[7] << 56);
        memcpy(dst + i, &bits, sizeof bits);
    }
}

/* Fills *e (if not NULL) with the field and a printf-formatted message, line and column 0, and returns
 * st: the one way parsers and loaders report a refusal (rugo_parse_error, rugo/shape_file.h). */
struct rugo_parse_error;
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
rugo_status
rugo__parse_fail(struct rugo_parse_error* e, rugo_status st, const char* field, const char* fmt, ...);

#endif
