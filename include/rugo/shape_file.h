/* librugo — the shape description file (JSON) and point lists.
 *
 * A shape file is a JSON object {"control_points": [[x, y], ...]} with optional fields:
 *   "filter": "cdf4.2" | "cdf4.4" | "cdf4.6" | "cdf4.8" | "cdf4.12"   (default cdf4.8)
 * Unknown fields are ignored (later versions add e.g. "roughness"). A points file for fitting is
 * {"points": [[x, y], ...]}. Input may be in either orientation; nothing here validates geometry
 * (use rugo_contour_check / rugo_pyramid_create for that). The parser never reads past `length`,
 * limits nesting depth (64) and the number of values (2^23), accepts one leading UTF-8 byte order
 * mark, and reports where it failed (lines end at '\n'; columns count bytes).
 * A repeated "control_points", "filter" or "points" member is BAD_FIELD, and so is "filter": null.
 * An empty control_points list parses (count 0, NULL points); geometry checks reject it later. */
#ifndef RUGO_SHAPE_FILE_H
#define RUGO_SHAPE_FILE_H

#include "rugo/base.h"
#include "rugo/wavelet.h"

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

typedef struct rugo_shape_desc {
    rugo_vec2* control_points; /* owned, allocated with `allocator` */
    int count;
    rugo_filter filter;
    rugo_allocator allocator;
} rugo_shape_desc;

/* Largest text the parser accepts (64 MiB). */
#define RUGO_MAX_JSON_BYTES ((size_t)64 << 20)

/* Parses a shape file. Errors: NULL_ARGUMENT, PARSE (syntax, depth, size), BAD_FIELD (missing or
 * wrong type, e.g. a point that is not a pair of numbers), NOT_FINITE (a number that overflows to
 * infinity), TOO_MANY_POINTS, BAD_FILTER, OUT_OF_MEMORY. error may be NULL. On error out is zeroed. */
rugo_status rugo_shape_desc_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                  rugo_shape_desc* out, rugo_parse_error* error);
void rugo_shape_desc_free(rugo_shape_desc* desc);

/* Parses the array under `key` ("points" or "control_points") of a JSON object into an owned point
 * array (free with the allocator given, via rugo_points_free). Same errors as above. */
rugo_status rugo_points_parse(const char* text, size_t length, const char* key,
                              const rugo_allocator* allocator, rugo_vec2** points, int* count,
                              rugo_parse_error* error);
void rugo_points_free(const rugo_allocator* allocator, rugo_vec2* points);

/* Writes a shape description as JSON into a newly allocated NUL-terminated string (*text, *length
 * without the NUL; both required; allocated with `allocator`, free with rugo_text_free). One point
 * per line; numbers with 17 significant digits so that reading back gives the same bits. */
rugo_status rugo_shape_desc_write(const rugo_shape_desc* desc, const rugo_allocator* allocator,
                                  char** text, size_t* length);
void rugo_text_free(const rugo_allocator* allocator, char* text);

/* Reads a whole file into a newly allocated NUL-terminated buffer (at most RUGO_MAX_JSON_BYTES).
 * RUGO_ERR_IO if it cannot be opened or read, RUGO_ERR_PARSE if it is too large. */
rugo_status rugo_read_file(const char* path, const rugo_allocator* allocator, char** text, size_t* length);

#ifdef __cplusplus
}
#endif

#endif
