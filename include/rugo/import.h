/** @file rugo/import.h
 * librugo — importing outlines: SVG path data, SVG documents, plain point lists.
 *
 * The pipeline (docs/import.md): find a `<path>` in an SVG document (rugo_svg_find_path) -> parse its
 * path data into subpaths of line, quadratic, cubic and elliptical-arc segments (rugo_path_parse) ->
 * sample one closed subpath by arc length (rugo_outline_sample) -> fit a closed cubic B-spline to the
 * samples (rugo_fit_outline in the Eigen shim, rugo/fit.h). rugo_svg_import_outline does the first
 * three steps in one call; rugo_points_text_parse reads a plain list of points.
 *
 * Everything here is core C99 (no Eigen). Every entry point takes hostile text: it never reads past
 * `length` (the text need not be NUL-terminated), bounds sizes and nesting, rejects non-finite
 * numbers, and reports where it failed in a rugo_parse_error (rugo/shape_file.h): 1-based line and
 * column (lines end at "\n", columns count bytes), a short path naming the attribute (e.g.
 * "path#rock/d") and a message. Path data errors are reported at the offending byte.
 *
 * Frames and units: SVG user units with y pointing down go in; rugo_svg_import_outline composes the
 * element's and its ancestors' `transform` attributes, then flips y, (x, y) -> (x, -y), so that the
 * outline comes out in librugo's y-up frame, counter-clockwise, in the root element's user units.
 * Angles in SVG text are in degrees (as SVG writes them); angles stored in structs are in radians.
 *
 * Ownership: every array an output struct holds is allocated with the allocator it records and freed
 * by the matching _free function; inputs are only read. */
#ifndef RUGO_IMPORT_H
#define RUGO_IMPORT_H

#include "rugo/base.h"
#include "rugo/shape_file.h" /* rugo_parse_error, RUGO_MAX_JSON_BYTES */

#ifdef __cplusplus
extern "C" {
#endif

/** Largest SVG document or path data string accepted, in bytes (64 MiB, as for JSON). */
#define RUGO_MAX_SVG_BYTES RUGO_MAX_JSON_BYTES
/** Largest number of segments (and of subpaths) in one parsed path (2^20); beyond it: TOO_LARGE. */
#define RUGO_MAX_PATH_SEGMENTS (1 << 20)
/** Deepest element nesting the SVG document scan follows (beyond it: PARSE). */
#define RUGO_SVG_MAX_DEPTH 256
/** Longest number token accepted in path data, transforms and point lists, in characters. */
#define RUGO_SVG_MAX_NUMBER_CHARS 512
/** Default sample count of rugo_outline_sample (when the def's sample_count is 0; raised to 4 samples
 * per segment for paths with more than 1024 segments). */
#define RUGO_DEFAULT_OUTLINE_SAMPLES 4096

/* ---- affine transforms ------------------------------------------------------------------------ */

/** A 2x3 affine map in SVG's matrix(a b c d e f) order: x' = a x + c y + e, y' = b x + d y + f. */
typedef struct rugo_affine {
    rugo_real a; /**< x' coefficient of x */
    rugo_real b; /**< y' coefficient of x */
    rugo_real c; /**< x' coefficient of y */
    rugo_real d; /**< y' coefficient of y */
    rugo_real e; /**< x' offset (length units) */
    rugo_real f; /**< y' offset (length units) */
} rugo_affine;

/** The identity map. */
static inline rugo_affine rugo_affine_identity(void) {
    rugo_affine m;
    m.a = 1.0;
    m.b = 0.0;
    m.c = 0.0;
    m.d = 1.0;
    m.e = 0.0;
    m.f = 0.0;
    return m;
}
/** The product m n: apply n first, then m (what SVG's transform="m n" means). No checks (NaN in,
 * NaN out). */
static inline rugo_affine rugo_affine_multiply(rugo_affine m, rugo_affine n) {
    rugo_affine r;
    r.a = m.a * n.a + m.c * n.b;
    r.b = m.b * n.a + m.d * n.b;
    r.c = m.a * n.c + m.c * n.d;
    r.d = m.b * n.c + m.d * n.d;
    r.e = m.a * n.e + m.c * n.f + m.e;
    r.f = m.b * n.e + m.d * n.f + m.f;
    return r;
}
/** m applied to the point p. */
static inline rugo_vec2 rugo_affine_apply(rugo_affine m, rugo_vec2 p) {
    return rugo_v2(m.a * p.x + m.c * p.y + m.e, m.b * p.x + m.d * p.y + m.f);
}

/** Parses an SVG `transform` attribute value of `length` bytes into *out: a transform list of
 * matrix(a b c d e f), translate(tx [ty]), scale(sx [sy]), rotate(deg [cx cy]), skewX(deg) and
 * skewY(deg), separated by whitespace and/or one comma; angles in degrees; "A B" means apply B first.
 * An empty or all-whitespace list is the identity.
 * Errors (*out is the identity then; error may be NULL, its line and column are within the text):
 * NULL_ARGUMENT, TOO_LARGE (beyond RUGO_MAX_SVG_BYTES), PARSE (unknown function, wrong argument
 * count, syntax), NOT_FINITE (a number that overflows, or a product that does). */
RUGO_API rugo_status rugo_svg_transform_parse(const char* text, size_t length, rugo_affine* out,
                                              rugo_parse_error* error);

/* ---- path data -------------------------------------------------------------------------------- */

/** The kind of a path segment. */
typedef enum rugo_path_segment_kind {
    RUGO_PATH_LINE = 0,      /**< straight line p[0] -> p[1] */
    RUGO_PATH_QUADRATIC = 1, /**< quadratic Bezier p[0], p[1], p[2] */
    RUGO_PATH_CUBIC = 2,     /**< cubic Bezier p[0], p[1], p[2], p[3] */
    RUGO_PATH_ARC = 3        /**< elliptical arc from p[0] to p[1] in centre form (rugo_path_segment) */
} rugo_path_segment_kind;

/** One segment in the path's own (untransformed) coordinates. An arc is
 *   q(t) = centre + R(phi) (rx cos θ, ry sin θ),  θ = theta1 + t dtheta,  t in [0, 1],
 * after the SVG implementation notes' endpoint-to-centre conversion (radii scaled up when too small);
 * its exact end points are p[0] and p[1] (rugo_path_segment_point returns them at t = 0 and 1). */
typedef struct rugo_path_segment {
    rugo_path_segment_kind kind; /**< which of the forms below */
    rugo_vec2 p[4];   /**< end and control points as listed for each kind (unused ones repeat the end) */
    rugo_vec2 centre; /**< ARC: centre of the ellipse */
    rugo_real rx;     /**< ARC: first radius (> 0, after scaling) */
    rugo_real ry;     /**< ARC: second radius (> 0, after scaling) */
    rugo_real phi;    /**< ARC: rotation of the ellipse's x axis, radians */
    rugo_real theta1; /**< ARC: start angle, radians */
    rugo_real dtheta; /**< ARC: signed sweep, radians, |dtheta| <= 2 pi (positive: +y from +x) */
    size_t offset;    /**< byte offset in the path data of the command that made it (point
                           index for rugo_path_from_points) */
} rugo_path_segment;

/** A subpath: segments[first .. first + count) of its path, starting at `start`. */
typedef struct rugo_subpath {
    int first;       /**< index of its first segment */
    int count;       /**< number of segments (0 for a lone moveto) */
    rugo_vec2 start; /**< its initial point (the moveto's) */
    bool closed;     /**< true if ended by Z/z */
} rugo_subpath;

/** A parsed path; owns its arrays (allocated with `allocator`, freed by rugo_path_free). */
typedef struct rugo_path {
    rugo_path_segment* segments; /**< all segments, subpath after subpath */
    int segment_count;           /**< number of segments */
    rugo_subpath* subpaths;      /**< the subpaths in drawing order */
    int subpath_count;           /**< number of subpaths */
    rugo_allocator allocator;    /**< the allocator of both arrays */
} rugo_path;

/** Parses SVG path data (the `d` attribute, SVG 1.1 / SVG 2 grammar) of `length` bytes: commands
 * M m L l H h V v C c S s Q q T t A a Z z, absolute and relative; implicit repetition of a command's
 * arguments; implicit lineto after a moveto's first pair; numbers with sign, fraction and exponent
 * ("-.5.5" is -0.5 and 0.5, "1e-3"); arc flags written without separators ("a1 1 0 00 1 1");
 * whitespace (space, tab, CR, LF, FF) and single commas between numbers. S and T reflect the previous
 * C/S (Q/T) control point about the current point, or use the current point after any other command.
 * Arcs: negative radii count as their absolute values, a zero radius makes a line, an arc to its own
 * start point is dropped, radii too small to reach the end point are scaled up. Z adds a line back to
 * the start when the current point is elsewhere; after Z the current point is the subpath's start and
 * a command other than M starts a new subpath there. Empty or all-whitespace data gives no subpaths.
 * Strict where browsers render "up to the error": any error fails the whole parse.
 * Errors (out zeroed; error gets line, column, path "d" and a message; may be NULL): NULL_ARGUMENT,
 * TOO_LARGE (text beyond RUGO_MAX_SVG_BYTES, more than RUGO_MAX_PATH_SEGMENTS segments or subpaths),
 * PARSE (no initial moveto, unknown command, missing or malformed number, a flag not 0 or 1, a stray
 * comma, numbers after Z, a number longer than RUGO_SVG_MAX_NUMBER_CHARS), NOT_FINITE (a number that
 * overflows such as 1e999, or coordinates whose sums overflow), OUT_OF_MEMORY. allocator may be NULL
 * (malloc/free); free the path with rugo_path_free. */
RUGO_API rugo_status rugo_path_parse(const char* d, size_t length, const rugo_allocator* allocator,
                                     rugo_path* out, rugo_parse_error* error);

/** Frees the path's arrays and zeroes it (NULL and a zeroed path are fine). */
RUGO_API void rugo_path_free(rugo_path* path);

/** A closed polygon path (one closed subpath of lines) through points[0..count), copied: what a point
 * list means as an outline. Repeated consecutive points (and a last point equal to the first) give no
 * segment. allocator may be NULL. Errors (out zeroed): NULL_ARGUMENT, TOO_FEW_POINTS (count < 3),
 * TOO_LARGE (count beyond RUGO_MAX_PATH_SEGMENTS), NOT_FINITE, OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_path_from_points(const rugo_vec2* points, int count,
                                           const rugo_allocator* allocator, rugo_path* out);

/** The point at t in [0, 1] of a segment, in the path's coordinates (t = 0 and t = 1 give the exact
 * end points). Pure evaluation of a parsed segment, no validation; (NaN, NaN) for a NULL segment. */
RUGO_API rugo_vec2 rugo_path_segment_point(const rugo_path_segment* segment, rugo_real t);
/** The derivative d/dt of the same parametrisation, in length units per unit t (for an arc, dtheta
 * times the derivative in θ). (NaN, NaN) for a NULL segment. */
RUGO_API rugo_vec2 rugo_path_segment_derivative(const rugo_path_segment* segment, rugo_real t);

/* ---- sampling an outline ---------------------------------------------------------------------- */

/** What to sample; fill from rugo_default_outline_sample_def(). */
typedef struct rugo_outline_sample_def {
    const rugo_path* path; /**< the parsed path (borrowed) */
    int subpath;           /**< index of the subpath to sample, or -1 (default): the closed subpath of largest
                                enclosed area, so that an outline with holes gives its outer boundary */
    rugo_affine transform; /**< applied to the path before sampling (default identity) */
    int sample_count;      /**< samples M; 0 (default): max(RUGO_DEFAULT_OUTLINE_SAMPLES, 4 S) for a
                                subpath of S segments, at most RUGO_MAX_CONTROL_POINTS; else S <= M */
    rugo_allocator allocator; /**< for the output points and scratch (zeroed: malloc/free) */
    int cookie;               /**< set by rugo_default_outline_sample_def; catches uninitialised defs */
} rugo_outline_sample_def;

/** The defaults described in rugo_outline_sample_def, with the cookie that marks an initialised def. */
RUGO_API rugo_outline_sample_def rugo_default_outline_sample_def(void);

/** Samples of one closed outline; owns `points` (allocated with `allocator`). */
typedef struct rugo_outline_samples {
    rugo_vec2* points;   /**< counter-clockwise in the transformed frame; points[0] is the subpath's start */
    int count;           /**< M, less any exactly repeated points removed */
    rugo_real perimeter; /**< arc length of the transformed subpath (adaptive Gauss-Kronrod, relative
                              error below 1e-13), length units */
    rugo_real area;      /**< area of the sample polygon (> 0), squared length units */
    int subpath;         /**< index of the subpath sampled */
    int segment_count;   /**< its segments S (segments shorter than 1e-12 of the perimeter not counted) */
    bool reversed;       /**< true if the transformed subpath ran clockwise and the samples were reversed */
    rugo_allocator allocator; /**< the allocator of points */
} rugo_outline_samples;

/** Samples the chosen closed subpath of def->path, transformed by def->transform, into M points: one
 * at the start of every segment (so corners are always sampled) and the other M - S spread over the
 * segments in proportion to their arc lengths (largest remainders), equally spaced in arc length
 * inside each segment. The spacing is thus nearly uniform in arc length (at most perimeter / (M - S))
 * and the points lie on the curve (arc-length inversion to ~1e-12 of the segment's length). Segments
 * shorter than 1e-12 of the perimeter are skipped; exactly repeated consecutive points are removed.
 * The samples are ordered counter-clockwise (a transform with negative determinant, such as SVG's y
 * flip, reverses the drawing direction). A subpath counts as closed if it ends with Z or its last
 * point lies within 1e-9 of its bounds' diagonal from its start. Deterministic.
 * Errors (out zeroed; error gets a message, may be NULL): NULL_ARGUMENT, BAD_ARGUMENT (def not from
 * rugo_default_outline_sample_def, a path whose counts and arrays disagree or with a segment of unknown
 * kind, subpath index out of range, sample_count negative, 1, 2 or below S), TOO_MANY_POINTS (M or S beyond
 * RUGO_MAX_CONTROL_POINTS), NOT_FINITE (a non-finite transform, or lengths or points that overflow
 * under it), BAD_FIELD (no closed subpath, also for any index into a path without subpaths; the
 * chosen one is open or empty), ZERO_AREA (zero length, or the samples enclose no area, e.g. under a
 * degenerate transform, or an area so small that it underflows to 0), OUT_OF_MEMORY.
 * Free the result with rugo_outline_samples_free. */
RUGO_API rugo_status rugo_outline_sample(const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                         rugo_parse_error* error);

/** Frees the points and zeroes the struct (NULL and a zeroed struct are fine). */
RUGO_API void rugo_outline_samples_free(rugo_outline_samples* samples);

/* ---- SVG documents ---------------------------------------------------------------------------- */

/** A `<path>` element found in a document. Owns `d` (allocated with `allocator`). */
typedef struct rugo_svg_path_element {
    char* d;                  /**< the decoded `d` attribute (entities replaced), NUL-terminated */
    size_t d_length;          /**< bytes of d, without the NUL */
    size_t d_offset;          /**< byte offset of the raw attribute value in the document */
    bool d_has_entities;      /**< true if decoding changed the value (positions inside d are then
                                   approximate) */
    rugo_affine transform;    /**< the element's transform composed with those of all its ancestors (root
                                   first): path coordinates to the root's user units, y down */
    int line;                 /**< 1-based line of the element's '<' in the document */
    int column;               /**< 1-based column (bytes) of the element's '<' */
    rugo_allocator allocator; /**< the allocator of d */
} rugo_svg_path_element;

/** Finds the element whose `id` attribute is `id` (NUL-terminated) in an SVG (XML) document of
 * `length` bytes and returns its decoded `d` and composed `transform`; id NULL: the document's only
 * `<path>` element. This is a bounded scan, not an XML parser: it skips the XML declaration, processing
 * instructions, comments, CDATA sections and a DOCTYPE (entity declarations are not expanded); reads
 * start and end tags with attributes in any order, single or double quotes and namespace prefixes
 * on element names (svg:path); decodes &lt; &gt; &amp; &quot; &apos; and numeric character
 * references in attribute values; checks that end tags match (up to the element found) and that
 * nesting stays within RUGO_SVG_MAX_DEPTH. It applies the `transform` attributes of the element and
 * of every enclosing element (`<g>`, `<a>`, `<svg>`, ...); it does not apply the root's viewBox, nested
 * `<svg>` viewports, CSS transforms or `<use>` references: coordinates are the root element's user
 * units. The first element with the id wins; the rest of the document is not read.
 * Errors (out zeroed; error gets the line and column in the document — 0 and 0 when nothing was
 * found — and a message; may be NULL):
 * NULL_ARGUMENT, TOO_LARGE (document beyond RUGO_MAX_SVG_BYTES), PARSE (malformed markup before or
 * at the element: unterminated comment, quote or tag, mismatched end tag, unknown entity, an
 * attribute given twice, nesting too deep; a malformed transform of the element or an ancestor),
 * NOT_FINITE (a transform that overflows), BAD_FIELD (no element with that id; the element is not a
 * `<path>` or has no `d`; id NULL and none or several `<path>` elements), OUT_OF_MEMORY.
 * allocator may be NULL; free the result with rugo_svg_path_element_free. */
RUGO_API rugo_status rugo_svg_find_path(const char* text, size_t length, const char* id,
                                        const rugo_allocator* allocator, rugo_svg_path_element* out,
                                        rugo_parse_error* error);

/** Frees `d` and zeroes the struct (NULL and a zeroed struct are fine). */
RUGO_API void rugo_svg_path_element_free(rugo_svg_path_element* element);

/** The SVG import up to the samples: rugo_svg_find_path (id as there), rugo_path_parse of its d
 * (errors reported at their line and column in the document), then rugo_outline_sample with the
 * transform def->transform * flip_y * (the element's composed transform), flip_y = (x, y) -> (x, -y):
 * the outline in a y-up frame, counter-clockwise, in the document's user units (def->transform,
 * identity by default, may scale or move it further). def->path is ignored (may be NULL);
 * def->subpath, def->sample_count and def->allocator are used as in rugo_outline_sample.
 * Errors: NULL_ARGUMENT, BAD_ARGUMENT (def not from rugo_default_outline_sample_def), and those of the
 * three steps; sampling errors point at the d attribute. An outline whose samples enclose no area
 * because it crosses itself (a bow-tie, a figure eight with equal lobes) is SELF_INTERSECTING, with
 * the crossing in the drawing's coordinates (the root's user units, y down) in the message. Free the
 * result with rugo_outline_samples_free. */
RUGO_API rugo_status rugo_svg_import_outline(const char* text, size_t length, const char* id,
                                             const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                             rugo_parse_error* error);

/** The root `<svg>` element's viewport: what its viewBox, width and height say about the size of a user
 * unit (docs/import.md, "Units and placement"). */
typedef struct rugo_svg_viewport {
    int has_viewbox;        /**< 1 if the root has a viewBox */
    rugo_real viewbox[4];   /**< min-x, min-y, width, height of the viewBox (user units) */
    int has_width;          /**< 1 if the root's width is an absolute length (px, in, cm, mm, Q, pt, pc or
                                 a bare number); 0 when absent or relative (%, em, ...) */
    int has_height;         /**< as has_width, for height */
    rugo_real width;        /**< the width in CSS px (96 per inch), when has_width */
    rugo_real height;       /**< the height in CSS px, when has_height */
    rugo_affine user_to_px; /**< user units (y down) to CSS px (y down): the viewBox mapped onto the
                                 width and height as preserveAspectRatio's default (xMidYMid meet) does, a
                                 missing width or height following the viewBox's aspect ratio; the
                                 identity without a viewBox (then a user unit is a px) */
} rugo_svg_viewport;

/** Reads the viewport of an SVG document of `length` bytes: skips the prolog (XML declaration,
 * comments, processing instructions, DOCTYPE) and reads the root element's viewBox, width and height.
 * A drawing's user units times user_to_px are CSS px; divide by the px per metre of a game to get
 * metres. Errors (out zeroed with an identity map; error gets line, column, the attribute, e.g.
 * "svg/viewBox", and a message): NULL_ARGUMENT, TOO_LARGE, PARSE (unterminated markup, a malformed
 * number), NOT_FINITE, BAD_FIELD (no root `<svg>`; a viewBox width or height <= 0; a width or height
 * <= 0). */
RUGO_API rugo_status rugo_svg_read_viewport(const char* text, size_t length, rugo_svg_viewport* out,
                                            rugo_parse_error* error);

/** Where a subpath of `path`, mapped by `transform`, crosses itself: a polyline through its segments
 * (16 points per curved segment) is searched for two edges that cross (O(N^2): meant for the error
 * path of an import whose samples enclose no area, such as a bow-tie). subpath -1: every subpath.
 * Returns 1 and the crossing point in the transformed frame in *where, or 0 when none is found (also
 * for NULL arguments, an index out of range and polylines beyond 16384 points). */
RUGO_API int rugo_path_find_crossing(const rugo_path* path, int subpath, rugo_affine transform,
                                     rugo_vec2* where);

/* ---- point lists ------------------------------------------------------------------------------ */

/** Reads a list of outline points of `length` bytes (one leading UTF-8 byte order mark is skipped),
 * told apart by content: text whose first non-blank character is '{' is a JSON points file
 * {"points": [[x, y], ...]} (rugo_points_parse); anything else is plain text with one point per line:
 * "x,y", "x y", "x;y" or "x<TAB>y" (blanks around the separator allowed, CR LF line ends fine); lines
 * that are blank or start with '#' are skipped, and so is a first line without any digit (a CSV
 * header such as "x,y"). Numbers use the SVG decimal syntax (sign, fraction, exponent; no hex, inf
 * or nan). out->points is allocated with `allocator` (may be NULL: malloc/free; free the list with
 * rugo_point_list_free); an empty list gives count 0 and NULL.
 * Errors (*out zeroed; error gets line, column and a message): NULL_ARGUMENT,
 * TOO_LARGE (beyond RUGO_MAX_JSON_BYTES), PARSE (a line that is not two numbers), NOT_FINITE (a number
 * that overflows, e.g. 1e999), TOO_MANY_POINTS (beyond RUGO_MAX_CONTROL_POINTS), OUT_OF_MEMORY, and
 * the errors of rugo_points_parse for JSON. */
RUGO_API rugo_status rugo_points_text_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                            rugo_point_list* out, rugo_parse_error* error);

#ifdef __cplusplus
}
#endif

#endif
