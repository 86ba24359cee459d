/** @file rugo/shape_file.h
 * librugo — the shape description file (JSON) and point lists.
 *
 * A shape file is a JSON object {"control_points": [[x, y], ...]} with optional fields:
 *   "filter": "cdf4.2" | "cdf4.4" | "cdf4.6" | "cdf4.8" | "cdf4.12"   (default cdf4.8)
 *   "roughness": {...}   (see rugo_roughness_desc below and docs/roughness.md), with exactly one of
 *       "preset": "tipo_1" | "tipo_2" | "tipo_3" | "tipo_5"
 *       "tolerances": [λ_0, ..., λ_{n-1}]            one per finest segment
 *       "constant": λ                                 every segment
 *       "ranges": [{"from": a, "to": b, "tolerance": λ}, ...]  plus optional "background": λ_0
 *                 a, b in [0, 1]: fractions of the perimeter by arc length from the start of
 *                 segment 0 along the file's own point order; b < a wraps through 0; overlapping
 *                 ranges take the largest λ; λ_0 (default 0) outside every range
 *       "profile": [[s, λ], ...]   λ(s) piecewise linear and periodic in s in [0, 1], s strictly
 *                 increasing (also from CSV text: rugo_roughness_profile_parse_csv)
 *     and optional "seed", "q", "estimator", "friction", "restitution", "perturbation".
 *     "ranges" and "profile" need the geometry to resolve: rugo_roughness_tolerances_on_contour
 *     gives every finest segment the maximum of λ over its arc (a band is a bound).
 * Unknown fields are ignored, at the top level and inside "roughness", so later versions and reports
 * spliced in by tools keep files readable. A points file for fitting is {"points": [[x, y], ...]}.
 * Input may be in either orientation; nothing here validates geometry (use rugo_contour_check /
 * rugo_pyramid_create for that). The parser never reads past `length`, limits nesting depth (64) and
 * the number of values (2^23), accepts one leading UTF-8 byte order mark, and reports where it failed
 * (lines end at "\n"; columns count bytes).
 * A repeated member ("control_points", "filter", "points", "roughness", or any member of the
 * roughness object) is BAD_FIELD, and so is null for an optional field.
 * An empty control_points list parses (count 0, NULL points); geometry checks reject it later.
 *
 * Units: coordinates and tolerances λ in the shape's length units; positions s, from and to are
 * dimensionless fractions of the perimeter. Ownership: every array a parser or writer returns sits in
 * a struct that records the allocator it came from (the one given; NULL or a zeroed one:
 * malloc/free), so the matching _free function takes just that struct; input text is only read and
 * need not be NUL-terminated. */
#ifndef RUGO_SHAPE_FILE_H
#define RUGO_SHAPE_FILE_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/rough.h"
#include "rugo/shape.h"
#include "rugo/tolerance.h"
#include "rugo/wavelet.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Where and why parsing failed: 1-based line and column (0 if not applicable), the JSON path of the
 * offending field (e.g. "control_points[3][1]") and a message. Always NUL-terminated. Every parser
 * here and in rugo/import.h clears it first; after success its message is empty. */
typedef struct rugo_parse_error {
    int line;          /**< 1-based line of the error in the text (lines end at "\n"); 0 if none */
    int column;        /**< 1-based column (bytes) in that line; 0 if none */
    char path[96];     /**< the offending field, e.g. "control_points[3][1]" (may be empty) */
    char message[160]; /**< what is wrong, in English */
} rugo_parse_error;

/** How the finest segments' tolerances are given (exactly one per roughness object). */
typedef enum rugo_roughness_kind {
    RUGO_ROUGHNESS_PRESET = 0,     /**< "preset": "tipo_1" | "tipo_2" | "tipo_3" | "tipo_5" (rough.h) */
    RUGO_ROUGHNESS_TOLERANCES = 1, /**< "tolerances": [λ_0, ..., λ_{n-1}], one per finest segment */
    RUGO_ROUGHNESS_CONSTANT = 2,   /**< "constant": λ on every segment */
    RUGO_ROUGHNESS_RANGES = 3,     /**< "ranges": λ per arc-length range of the perimeter (+ "background") */
    RUGO_ROUGHNESS_PROFILE = 4,    /**< "profile": λ(s) along the perimeter, piecewise linear */
    RUGO_ROUGHNESS_KIND_COUNT      /**< the number of kinds (not a kind) */
} rugo_roughness_kind;

/** One arc-length range of kind RANGES. Positions are fractions of the perimeter, measured by arc
 * length from the start of segment 0 (f_0(0)) along the order of the file's control points. The
 * range covers [from, to] when from < to, and [from, 1] with [0, to] (through 0) when from > to; it
 * must not be empty (from == to, or from 1 to 0, is refused; [0, 1] is the whole perimeter). */
typedef struct rugo_roughness_range {
    rugo_real from;      /**< start, a fraction of the perimeter in [0, 1] */
    rugo_real to;        /**< end, a fraction of the perimeter in [0, 1] */
    rugo_real tolerance; /**< λ >= 0 on the range (length) */
} rugo_roughness_range;

/** One sample of kind PROFILE: λ at position s (a fraction of the perimeter, as for ranges). */
typedef struct rugo_profile_sample {
    rugo_real s;         /**< in [0, 1], strictly increasing from one sample to the next */
    rugo_real tolerance; /**< λ(s) >= 0 (length) */
} rugo_profile_sample;

/** A profile λ(s) read from CSV text (rugo_roughness_profile_parse_csv); owns `samples` (allocated with
 * `allocator`, freed by rugo_roughness_profile_free). */
typedef struct rugo_roughness_profile {
    rugo_profile_sample* samples; /**< count samples, s strictly increasing */
    int count;                    /**< number of samples, 1..RUGO_MAX_PROFILE_SAMPLES (0 only when zeroed) */
    rugo_allocator allocator;     /**< the allocator of samples */
} rugo_roughness_profile;

/** Most ranges one roughness object may hold (2^16; more is TOO_MANY_POINTS). */
#define RUGO_MAX_ROUGHNESS_RANGES (1 << 16)
/** Most profile samples one roughness object or CSV profile may hold (2^20; more is TOO_MANY_POINTS). */
#define RUGO_MAX_PROFILE_SAMPLES (1 << 20)
/** A range counts for a segment only if it overlaps the segment's arc by more than this fraction of
 * the perimeter at either end, so that a range ending exactly on a segment boundary (0.25 of a square)
 * does not spill into the next segment through the round-off of the arc lengths. */
#define RUGO_ROUGHNESS_RANGE_SLACK 1e-12

/** Largest seed a file can carry: 2^53, the largest integer up to which every integer is a double, so
 * that any JSON reader (JavaScript's included) keeps it exact. */
#define RUGO_MAX_FILE_SEED ((uint64_t)1 << 53)
/** Largest "levels" of a stored perturbation (its point count is count << levels). */
#define RUGO_MAX_PERTURBATION_LEVELS 20

/** The "roughness" object of a shape file. Segment j is the segment of the file's own control points
 * (f_j runs from near c_j to near c_{j+1}); a tool that reverses a clockwise outline maps segment j to
 * n-2-j (mod n). Lengths are in the shape's units. Its arrays are owned by the rugo_shape_desc that
 * holds it (allocated with that desc's allocator, freed by rugo_shape_desc_free). */
typedef struct rugo_roughness_desc {
    rugo_roughness_kind kind;     /**< which of the sources below gives the finest tolerances */
    rugo_tolerance_preset preset; /**< kind PRESET: the preset */
    rugo_real* tolerances;        /**< kind TOLERANCES: tolerance_count values (= the control point count);
                                     owned by the shape desc, allocated with its allocator */
    int tolerance_count;          /**< kind TOLERANCES: entries of tolerances */
    rugo_real constant;           /**< kind CONSTANT: λ >= 0 of every segment (length) */
    uint64_t seed;                /**< "seed", 0..RUGO_MAX_FILE_SEED (default 0): tipo_2 and perturbations */
    rugo_real q;                  /**< "q", band factor of λ = q σ, > 0 (default RUGO_DEFAULT_Q) */
    rugo_tolerance_estimator estimator; /**< "estimator": "detail" (default) | "coefficients" */
    rugo_friction_map friction;         /**< "friction": {"alpha", "lambda_min", "base"}
                                             (rugo_default_friction_map) */
    rugo_restitution restitution; /**< "restitution": {"epsilon", "epsilon_max"} (rugo_default_restitution) */
    /* Optional display geometry (written by `rugo roughen`): "perturbation": {"method": "wavelet" |
     * "local", "levels": m, "control_points": [...]}, with exactly count << m control points. */
    bool has_perturbation;                   /**< true if the "perturbation" members below are set */
    rugo_roughen_method perturbation_method; /**< "method": how the perturbed points were made */
    int perturbation_levels;                 /**< "levels" m, 1..RUGO_MAX_PERTURBATION_LEVELS */
    rugo_vec2* perturbation_points; /**< the perturbed outline's control points, owned like tolerances */
    int perturbation_count;         /**< entries of perturbation_points, count << perturbation_levels */
    /* Added with arc-length roughness; zero when a caller leaves them out of an initializer. */
    rugo_roughness_range* ranges; /**< kind RANGES: range_count ranges (0 allowed: background only),
                                     owned like tolerances; their order does not matter */
    int range_count;              /**< kind RANGES: entries of ranges, 0..RUGO_MAX_ROUGHNESS_RANGES */
    rugo_real background;         /**< kind RANGES: "background", λ outside every range (default 0) */
    rugo_profile_sample* profile; /**< kind PROFILE: profile_count >= 1 samples, owned like tolerances */
    int profile_count;            /**< kind PROFILE: entries of profile, 1..RUGO_MAX_PROFILE_SAMPLES */
} rugo_roughness_desc;

/** Preset tipo_1, seed 0, q = RUGO_DEFAULT_Q, the detail estimator, the default friction map and
 * restitution, no perturbation, no arrays, background 0. Never fails. */
RUGO_API rugo_roughness_desc rugo_default_roughness_desc(void);

/** A parsed shape file: its control points, filter and optional roughness. Owns its arrays. */
typedef struct rugo_shape_desc {
    rugo_vec2* control_points; /**< count points in the file's order (length units); owned, allocated
                                    with `allocator`; NULL when count is 0 */
    int count;                 /**< number of control points (0..RUGO_MAX_CONTROL_POINTS) */
    rugo_filter filter;        /**< "filter" (default RUGO_FILTER_DEFAULT) */
    rugo_allocator allocator;  /**< the allocator of every array of the desc */
    /* Added with roughness; zero (no roughness) when a caller leaves them out of an initializer. */
    bool has_roughness;            /**< true if the file has a "roughness" object */
    rugo_roughness_desc roughness; /**< meaningful when has_roughness; its arrays are owned like
                                      control_points and freed by rugo_shape_desc_free */
} rugo_shape_desc;

/** Largest text the parser accepts (64 MiB). */
#define RUGO_MAX_JSON_BYTES ((size_t)64 << 20)

/** Parses a shape file of `length` bytes into *out (its arrays allocated with `allocator`, NULL:
 * malloc/free; free with rugo_shape_desc_free). Errors: NULL_ARGUMENT, PARSE (syntax, depth, size),
 * BAD_FIELD (missing or wrong type, e.g. a point that is not a pair of numbers), NOT_FINITE (a number
 * that overflows to infinity), TOO_MANY_POINTS, BAD_FILTER, OUT_OF_MEMORY. error may be NULL. On
 * error out is zeroed.
 * The roughness object adds: BAD_FIELD (not an object; none or several of preset / tolerances /
 * constant / ranges / profile; an unknown preset or estimator; a tolerance list whose length is not
 * the control point count; a seed that is not an integer written in plain digits or exceeds
 * RUGO_MAX_FILE_SEED; a perturbation without method, levels in 1..RUGO_MAX_PERTURBATION_LEVELS or
 * count << levels control points), NEGATIVE_TOLERANCE (a tolerance or constant below zero, as
 * rugo_tolerances_check), BAD_QUANTILE (q <= 0), and the statuses of rugo_friction_map_check
 * (BAD_ARGUMENT for alpha or base < 0, NEGATIVE_TOLERANCE for lambda_min < 0) and
 * rugo_restitution_check (BAD_ARGUMENT outside [0, 1], EMPTY_RANGE for epsilon > epsilon_max).
 * Absent optional members take the defaults of rugo_default_roughness_desc.
 * "ranges" adds: BAD_FIELD (not an array of objects; a range without "from", "to" or "tolerance";
 * from or to outside [0, 1]; an empty range), TOO_MANY_POINTS (more than RUGO_MAX_ROUGHNESS_RANGES),
 * NEGATIVE_TOLERANCE (a range's tolerance or the background below zero), NOT_FINITE. "background"
 * is read only with "ranges" (ignored, like an unknown member, with the other kinds).
 * "profile" adds: BAD_FIELD (not an array of [s, tolerance] pairs; no sample; s outside [0, 1] or
 * not strictly increasing), TOO_MANY_POINTS (more than RUGO_MAX_PROFILE_SAMPLES),
 * NEGATIVE_TOLERANCE, NOT_FINITE. Paths name the value, e.g. "roughness.ranges[2].from",
 * "roughness.profile[5][0]". */
RUGO_API rugo_status rugo_shape_desc_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                           rugo_shape_desc* out, rugo_parse_error* error);
/** Frees the control points and the roughness arrays; leaves count 0 and has_roughness false (NULL
 * is fine; a zeroed desc is fine). */
RUGO_API void rugo_shape_desc_free(rugo_shape_desc* desc);

/** The tolerance of every finest segment, out[0..n) (caller-owned, n entries, length units; n = the
 * control point count, in the file's own
 * segment numbering): the preset (rugo_tolerances_preset with the seed), the constant, or a copy of
 * the list. Errors: NULL_ARGUMENT, BAD_ARGUMENT (unknown kind or preset, a list whose length is
 * not n, or kind RANGES or PROFILE, which need the geometry: use
 * rugo_roughness_tolerances_on_contour), TOO_FEW_POINTS (n < 1), TOO_MANY_POINTS, NOT_FINITE,
 * NEGATIVE_TOLERANCE. Allocates nothing. */
RUGO_API rugo_status rugo_roughness_tolerances(const rugo_roughness_desc* desc, int n, rugo_real* out);

/** The tolerance of every finest segment, out[0..contour.count), for a shape whose control points are
 * `contour` in the file's own order (not reversed; the caller keeps them alive). Any kind: the
 * geometry-free ones as rugo_roughness_tolerances(desc, contour.count, out). For RANGES and PROFILE,
 * segment j covers the arc [a_j, b_j] of the perimeter (a fraction; arc lengths by
 * rugo_contour_segment_length, a_0 = 0, b_{n-1} = 1) and gets the MAXIMUM of λ over it, because a
 * tolerance is a band that must bound the roughness anywhere on its segment (a mean would let a
 * narrow rough patch slip under a smooth neighbour):
 *  - RANGES: the largest tolerance of the ranges that overlap [a_j, b_j] (an overlap of at most
 *    RUGO_ROUGHNESS_RANGE_SLACK at the segment's ends does not count; a segment shorter than twice
 *    that is taken at its midpoint), and the background too unless the ranges cover the whole arc.
 *    Exact: no sampling.
 *  - PROFILE: λ is linear between consecutive samples and periodic (from the last sample through
 *    s = 1 ≡ 0 to the first); the maximum over [a_j, b_j] is that of λ(a_j), λ(b_j) and the samples
 *    inside, exact up to round-off. With samples at both s = 0 and s = 1 the point 0 ≡ 1 takes the
 *    larger of their values.
 * O(n + m log m) for m ranges, O(n + m) for m samples. allocator (NULL: malloc/free) serves the
 * scratch of RANGES and PROFILE (the segment lengths, and about 48 bytes a range); out is
 * caller-owned and untouched on error.
 * Errors: NULL_ARGUMENT, and for RANGES and PROFILE: TOO_FEW_POINTS (count < 4), TOO_MANY_POINTS,
 * NOT_FINITE (a point or the perimeter), ZERO_AREA (perimeter 0), the value errors the parser
 * reports (BAD_ARGUMENT for a range or sample out of its range, NEGATIVE_TOLERANCE, NOT_FINITE,
 * TOO_MANY_POINTS, NULL_ARGUMENT for a missing array, BAD_ARGUMENT for an empty profile),
 * OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_roughness_tolerances_on_contour(const rugo_roughness_desc* desc,
                                                          rugo_contour contour,
                                                          const rugo_allocator* allocator, rugo_real* out);

/** Parses a profile λ(s) from CSV text of `length` bytes (need not be NUL-terminated; one leading
 * UTF-8 byte order mark is skipped): one sample per line, "s,lambda" (two numbers separated by a
 * comma; spaces and tabs around them are ignored; lines end with "\n" or "\r\n"). Blank lines and
 * lines starting with '#' are skipped; the first other line may be a header (two names, e.g.
 * "s,lambda"): it is one when its first field does not start like a number (a digit, a sign or '.')
 * and is not nan or inf. Numbers are decimal (an optional sign,
 * digits with an optional '.', an optional exponent; ".5" and "5." are accepted) and read exactly as
 * JSON numbers are, whatever the locale. No quoting. The samples are checked as the JSON "profile"
 * (s in [0, 1], strictly increasing, λ >= 0). On success out->samples (allocated with `allocator`,
 * NULL: malloc/free; free the profile with rugo_roughness_profile_free) holds out->count >= 1
 * samples.
 * Errors (error may be NULL; it gets the 1-based line and column, the path "profile[i][0]" for s or
 * "profile[i][1]" for λ of sample i, and a message): NULL_ARGUMENT; PARSE (text over
 * RUGO_MAX_JSON_BYTES, a line without exactly two fields, an empty field, a field that is not a
 * number, a header with other than two fields); NOT_FINITE (nan, inf, infinity in any case, or a
 * number overflowing to infinity); BAD_FIELD (no samples; s outside [0, 1] or not strictly
 * increasing); NEGATIVE_TOLERANCE (λ < 0); TOO_MANY_POINTS (more than RUGO_MAX_PROFILE_SAMPLES
 * rows); OUT_OF_MEMORY. On error *out is zeroed. */
RUGO_API rugo_status rugo_roughness_profile_parse_csv(const char* text, size_t length,
                                                      const rugo_allocator* allocator,
                                                      rugo_roughness_profile* out, rugo_parse_error* error);
/** Frees the samples and zeroes the profile (NULL and a zeroed profile are fine). */
RUGO_API void rugo_roughness_profile_free(rugo_roughness_profile* profile);

/** A list of points read from text; owns `points` (allocated with `allocator`, freed by
 * rugo_point_list_free). */
typedef struct rugo_point_list {
    rugo_vec2* points;        /**< count points in the text's order (length units); NULL when count is 0 */
    int count;                /**< number of points, 0..RUGO_MAX_CONTROL_POINTS */
    rugo_allocator allocator; /**< the allocator of points */
} rugo_point_list;

/** Parses the array under `key` (NUL-terminated, e.g. "points" or "control_points") of a JSON object
 * of `length` bytes into *out: its points (allocated with `allocator`, NULL: malloc/free; NULL for
 * an empty list) and their count; free it with rugo_point_list_free. Errors (*out zeroed; error may
 * be NULL): NULL_ARGUMENT, PARSE (JSON syntax, depth, size), BAD_FIELD (not an object, the key
 * missing or repeated, not an array of [x, y] pairs of numbers), NOT_FINITE (a number that
 * overflows), TOO_MANY_POINTS (beyond RUGO_MAX_CONTROL_POINTS), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_points_parse(const char* text, size_t length, const char* key,
                                       const rugo_allocator* allocator, rugo_point_list* out,
                                       rugo_parse_error* error);
/** Frees the points of a list from rugo_points_parse or rugo_points_text_parse and zeroes the list
 * (NULL and a zeroed list are fine). */
RUGO_API void rugo_point_list_free(rugo_point_list* list);

/** A text librugo allocated (a JSON document written, a file read); owns `data` (allocated with
 * `allocator`, freed by rugo_text_free). */
typedef struct rugo_text {
    char* data;               /**< length bytes followed by a NUL */
    size_t length;            /**< bytes of data, without the NUL */
    rugo_allocator allocator; /**< the allocator of data */
} rugo_text;

/** Frees the data of a text from rugo_shape_desc_write or rugo_read_file and zeroes the text (NULL and
 * a zeroed text are fine). */
RUGO_API void rugo_text_free(rugo_text* text);

/** Writes a shape description as JSON into *out, a newly allocated NUL-terminated string (allocated
 * with `allocator`, NULL: malloc/free; free with rugo_text_free). One point (or tolerance) per line;
 * numbers with 17 significant digits so that reading back gives the same bits. With has_roughness,
 * every roughness member is written (defaults included), so that parse(write(d)) gives d back bit
 * for bit and write(parse(write(d))) the same text.
 * The writer refuses what the reader would (*out is zeroed then): NULL_ARGUMENT, BAD_ARGUMENT
 * (count < 0), NOT_FINITE, BAD_FILTER, TOO_MANY_POINTS, and for the roughness BAD_ARGUMENT (kind,
 * preset, estimator, method, levels, a count mismatch, a seed beyond RUGO_MAX_FILE_SEED, a range or
 * profile sample out of its range, an empty profile) and the value checks listed for parsing
 * (NULL_ARGUMENT for a missing ranges or profile array); TOO_MANY_POINTS also when the text would
 * exceed RUGO_MAX_JSON_BYTES (possible only with a large roughness object); OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_shape_desc_write(const rugo_shape_desc* desc, const rugo_allocator* allocator,
                                           rugo_text* out);
/** One call from an asset to a shape: loads a shape file — a JSON shape file (with its roughness, if
 * any) or a baked file (rugo bake), told apart by content, never by name — and builds the rugo_shape
 * (for JSON: the roughness resolved on the outline as rugo_roughness_tolerances_on_contour does, then
 * rugo_shape_create with the file's filter, q, estimator, friction map and restitution). A game loads
 * baked files (no build at run time); JSON works too. On success *out is a new shape (destroy with
 * rugo_shape_destroy). error (may be NULL) gets the position and field of a JSON error, the byte
 * offset (as "byte N", in path) and field of a baked one, or for a shape that cannot be built the
 * field, the value and a way out (e.g. "control_points has 5 points ... refit with 8").
 * Errors: NULL_ARGUMENT, IO (cannot open or read), those of rugo_shape_desc_parse,
 * rugo_shape_read_baked_file, rugo_roughness_tolerances_on_contour and rugo_shape_create. allocator
 * may be NULL (malloc/free). */
RUGO_API rugo_status rugo_shape_load_file(const char* path, const rugo_allocator* allocator, rugo_shape** out,
                                          rugo_parse_error* error);

/** Reads a whole file (at most RUGO_MAX_JSON_BYTES) into *out, a newly allocated NUL-terminated
 * buffer (allocated with `allocator`, NULL: malloc/free; free with rugo_text_free). Errors (*out
 * zeroed): NULL_ARGUMENT, IO if it cannot be opened or read, PARSE if it is too large,
 * OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_read_file(const char* path, const rugo_allocator* allocator, rugo_text* out);

#ifdef __cplusplus
}
#endif

#endif
