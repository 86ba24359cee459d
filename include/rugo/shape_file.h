/* librugo — the shape description file (JSON) and point lists.
 *
 * A shape file is a JSON object {"control_points": [[x, y], ...]} with optional fields:
 *   "filter": "cdf4.2" | "cdf4.4" | "cdf4.6" | "cdf4.8" | "cdf4.12"   (default cdf4.8)
 *   "roughness": {...}   (see rugo_roughness_desc below and docs/roughness.md)
 * Unknown fields are ignored, at the top level and inside "roughness", so later versions and reports
 * spliced in by tools keep files readable. A points file for fitting is {"points": [[x, y], ...]}.
 * Input may be in either orientation; nothing here validates geometry (use rugo_contour_check /
 * rugo_pyramid_create for that). The parser never reads past `length`, limits nesting depth (64) and
 * the number of values (2^23), accepts one leading UTF-8 byte order mark, and reports where it failed
 * (lines end at '\n'; columns count bytes).
 * A repeated member ("control_points", "filter", "points", "roughness", or any member of the
 * roughness object) is BAD_FIELD, and so is null for an optional field.
 * An empty control_points list parses (count 0, NULL points); geometry checks reject it later. */
#ifndef RUGO_SHAPE_FILE_H
#define RUGO_SHAPE_FILE_H

#include "rugo/base.h"
#include "rugo/rough.h"
#include "rugo/tolerance.h"
#include "rugo/wavelet.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Where and why parsing failed: 1-based line and column (0 if not applicable), the JSON path of the
 * offending field (e.g. "control_points[3][1]") and a message. Always NUL-terminated. */
typedef struct rugo_parse_error {
    int line;
    int column;
    char path[96];
    char message[160];
} rugo_parse_error;

/* How the finest segments' tolerances are given (exactly one per roughness object). */
typedef enum rugo_roughness_kind {
    RUGO_ROUGHNESS_PRESET = 0,     /* "preset": "tipo_1" | "tipo_2" | "tipo_3" | "tipo_5" (rough.h) */
    RUGO_ROUGHNESS_TOLERANCES = 1, /* "tolerances": [λ_0, ..., λ_{n-1}], one per finest segment */
    RUGO_ROUGHNESS_CONSTANT = 2,   /* "constant": λ on every segment */
    RUGO_ROUGHNESS_KIND_COUNT
} rugo_roughness_kind;

/* Largest seed a file can carry: 2^53, the largest integer up to which every integer is a double, so
 * that any JSON reader (JavaScript's included) keeps it exact. */
#define RUGO_MAX_FILE_SEED ((uint64_t)1 << 53)
/* Largest "levels" of a stored perturbation (its point count is count << levels). */
#define RUGO_MAX_PERTURBATION_LEVELS 20

/* The "roughness" object of a shape file. Segment j is the segment of the file's own control points
 * (f_j runs from near c_j to near c_{j+1}); a tool that reverses a clockwise outline maps segment j to
 * n-2-j (mod n). Lengths are in the shape's units. */
typedef struct rugo_roughness_desc {
    rugo_roughness_kind kind;
    rugo_tolerance_preset preset; /* kind PRESET */
    rugo_real* tolerances;        /* kind TOLERANCES: tolerance_count values (= the control point count);
                                     owned by the shape desc, allocated with its allocator */
    int tolerance_count;
    rugo_real constant; /* kind CONSTANT */
    uint64_t seed;      /* "seed", 0..RUGO_MAX_FILE_SEED (default 0): tipo_2 and perturbations */
    rugo_real q;        /* "q", band factor of λ = q σ, > 0 (default RUGO_DEFAULT_Q) */
    rugo_tolerance_estimator estimator; /* "estimator": "detail" (default) | "coefficients" */
    rugo_friction_map friction;         /* "friction": {"alpha", "lambda_min"} (rugo_default_friction_map) */
    rugo_restitution restitution; /* "restitution": {"epsilon", "epsilon_max"} (rugo_default_restitution) */
    /* Optional display geometry (written by `rugo roughen`): "perturbation": {"method": "wavelet" |
     * "local", "levels": m, "control_points": [...]}, with exactly count << m control points. */
    int has_perturbation;
    rugo_roughen_method perturbation_method;
    int perturbation_levels;        /* 1..RUGO_MAX_PERTURBATION_LEVELS */
    rugo_vec2* perturbation_points; /* owned like tolerances */
    int perturbation_count;
} rugo_roughness_desc;

/* Preset tipo_1, seed 0, q = RUGO_DEFAULT_Q, the detail estimator, the default friction map and
 * restitution, no perturbation, no arrays. */
rugo_roughness_desc rugo_default_roughness_desc(void);

typedef struct rugo_shape_desc {
    rugo_vec2* control_points; /* owned, allocated with `allocator` */
    int count;
    rugo_filter filter;
    rugo_allocator allocator;
    /* Added with roughness; zero (no roughness) when a caller leaves them out of an initializer. */
    int has_roughness;
    rugo_roughness_desc roughness; /* meaningful when has_roughness; its arrays are owned like
                                      control_points and freed by rugo_shape_desc_free */
} rugo_shape_desc;

/* Largest text the parser accepts (64 MiB). */
#define RUGO_MAX_JSON_BYTES ((size_t)64 << 20)

/* Parses a shape file. Errors: NULL_ARGUMENT, PARSE (syntax, depth, size), BAD_FIELD (missing or
 * wrong type, e.g. a point that is not a pair of numbers), NOT_FINITE (a number that overflows to
 * infinity), TOO_MANY_POINTS, BAD_FILTER, OUT_OF_MEMORY. error may be NULL. On error out is zeroed.
 * The roughness object adds: BAD_FIELD (not an object; none or several of preset / tolerances /
 * constant; an unknown preset or estimator; a tolerance list whose length is not the control point
 * count; a seed that is not an integer written in plain digits or exceeds RUGO_MAX_FILE_SEED; a
 * perturbation without method, levels in 1..RUGO_MAX_PERTURBATION_LEVELS or count << levels control
 * points), NEGATIVE_TOLERANCE (a tolerance or constant below zero, as rugo_tolerances_check),
 * BAD_QUANTILE (q <= 0), and the statuses of rugo_friction_map_check (BAD_ARGUMENT for alpha < 0,
 * NEGATIVE_TOLERANCE for lambda_min < 0) and rugo_restitution_check (BAD_ARGUMENT outside [0, 1],
 * EMPTY_RANGE for epsilon > epsilon_max). Absent optional members take the defaults of
 * rugo_default_roughness_desc. */
rugo_status rugo_shape_desc_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                  rugo_shape_desc* out, rugo_parse_error* error);
/* Frees the control points and the roughness arrays; leaves count 0 and has_roughness 0. */
void rugo_shape_desc_free(rugo_shape_desc* desc);

/* The tolerance of every finest segment, out[0..n) (n = the control point count, in the file's own
 * segment numbering): the preset (rugo_tolerances_preset with the seed), the constant, or a copy of
 * the list. Errors: NULL_ARGUMENT, BAD_ARGUMENT (unknown kind or preset, or a list whose length is
 * not n), TOO_FEW_POINTS (n < 1), TOO_MANY_POINTS, NOT_FINITE, NEGATIVE_TOLERANCE. */
rugo_status rugo_roughness_tolerances(const rugo_roughness_desc* desc, int n, rugo_real* out);

/* Parses the array under `key` ("points" or "control_points") of a JSON object into an owned point
 * array (free with the allocator given, via rugo_points_free). Same errors as above. */
rugo_status rugo_points_parse(const char* text, size_t length, const char* key,
                              const rugo_allocator* allocator, rugo_vec2** points, int* count,
                              rugo_parse_error* error);
void rugo_points_free(const rugo_allocator* allocator, rugo_vec2* points);

/* Writes a shape description as JSON into a newly allocated NUL-terminated string (*text, *length
 * without the NUL; both required; allocated with `allocator`, free with rugo_text_free). One point
 * (or tolerance) per line; numbers with 17 significant digits so that reading back gives the same
 * bits. With has_roughness, every roughness member is written (defaults included), so that
 * parse(write(d)) gives d back bit for bit and write(parse(write(d))) the same text.
 * The writer refuses what the reader would: NOT_FINITE, BAD_FILTER, TOO_MANY_POINTS, and for the
 * roughness BAD_ARGUMENT (kind, preset, estimator, method, levels, a count mismatch, a seed beyond
 * RUGO_MAX_FILE_SEED) and the value checks listed for parsing; TOO_MANY_POINTS also when the text
 * would exceed RUGO_MAX_JSON_BYTES (possible only with a large roughness object). */
rugo_status rugo_shape_desc_write(const rugo_shape_desc* desc, const rugo_allocator* allocator, char** text,
                                  size_t* length);
void rugo_text_free(const rugo_allocator* allocator, char* text);

/* Reads a whole file into a newly allocated NUL-terminated buffer (at most RUGO_MAX_JSON_BYTES).
 * RUGO_ERR_IO if it cannot be opened or read, RUGO_ERR_PARSE if it is too large. */
rugo_status rugo_read_file(const char* path, const rugo_allocator* allocator, char** text, size_t* length);

#ifdef __cplusplus
}
#endif

#endif
