/* Private declarations shared by io's SVG readers (svg_scanner.c, svg_transform.c, svg_path_data.c,
 * svg_document.c) and by point-list text (point_list.c), which reads numbers with SVG's grammar.
 * Not installed. May include: core, curve, io.
 *
 * Everything here reads hostile text: no read past the end of the text, explicit size and nesting
 * limits, no recursion, every number checked finite. Positions in errors are byte offsets turned into
 * line and column by rugo__json_locate (the same convention as the JSON reader). */
#ifndef RUGO_IO_SVG_INTERNAL_H
#define RUGO_IO_SVG_INTERNAL_H

#include "rugo/import.h"

#include <stddef.h>
#include <string.h>

#define RUGO__SVG_PI 3.14159265358979323846

static inline void rugo__svg_clear_error(rugo_parse_error* e) {
    if (e != NULL) memset(e, 0, sizeof *e);
}

/* ---- the scanner (svg_scanner.c) ------------------------------------------------------------------ */

/* Where errors are reported: offsets into the text being read are mapped into `doc` (the whole
 * document, for a d or transform attribute) as base + offset when `exact`, or to base otherwise (an
 * attribute whose entities were decoded, so offsets no longer match the document's bytes). */
typedef struct rugo__svg_locator {
    const char* doc;
    size_t doc_length;
    size_t base;
    int exact;
    const char* path; /* e.g. "d" or "path#rock/d" */
} rugo__svg_locator;

/* A cursor over text[0, length) with the locator of its errors. */
typedef struct rugo__svg_scanner {
    const char* text;
    const char* p;
    const char* end;
    rugo__svg_locator loc;
    rugo_parse_error* err;
} rugo__svg_scanner;

/* Fills *e (when not NULL) with the position of `offset` as loc maps it, loc's path and the message;
 * returns st. */
#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
rugo_status
rugo__svg_fail_at(rugo_parse_error* e, rugo_status st, const rugo__svg_locator* loc, size_t offset,
                  const char* fmt, ...);

/* A short printable description of the byte at p: "'x'", "byte 0xNN" or "the end". */
const char* rugo__svg_describe(const char* p, const char* end, char* buf, size_t size);

static inline int rugo__svg_is_digit(char c) { return c >= '0' && c <= '9'; }
/* SVG 2 whitespace: space, tab, LF, CR, FF. */
static inline int rugo__svg_is_wsp(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
}
static inline int rugo__svg_starts_number(char c) {
    return rugo__svg_is_digit(c) || c == '.' || c == '+' || c == '-';
}

static inline size_t rugo__svg_offset(const rugo__svg_scanner* sc, const char* p) {
    return (size_t)(p - sc->text);
}

void rugo__svg_skip_wsp(rugo__svg_scanner* sc);
/* comma-wsp? : wsp* (',' wsp*)?. Returns 1 if a comma was consumed. */
int rugo__svg_skip_comma_wsp(rugo__svg_scanner* sc);
/* Reads a number at the cursor. `what` names it for messages ("number 3 of 'C'"). */
rugo_status rugo__svg_read_number(rugo__svg_scanner* sc, double* out, const char* what);

/* ---- transforms (svg_transform.c) ----------------------------------------------------------------- */

/* cos and sin of an angle in degrees, exact for multiples of 90 degrees (rotate(90) is common). */
void rugo__svg_cos_sin_deg(double deg, double* c, double* s);

/* The map matrix(a b c d e f). */
static inline rugo_affine rugo__svg_affine(double a, double b, double c, double d, double e, double f) {
    rugo_affine m;
    m.a = a;
    m.b = b;
    m.c = c;
    m.d = d;
    m.e = e;
    m.f = f;
    return m;
}

/* A transform list (the value of a transform attribute) at the cursor, to the end of the text, into
 * *out (the functions' maps composed left to right). */
rugo_status rugo__svg_transform_list(rugo__svg_scanner* sc, rugo_affine* out);

/* ---- path data (svg_path_data.c) ------------------------------------------------------------------ */

/* rugo_path_parse with errors located by loc (the d attribute's place in its document). */
rugo_status rugo__svg_path_parse_located(const char* d, size_t length, const rugo_allocator* allocator,
                                         rugo_path* out, rugo_parse_error* error,
                                         const rugo__svg_locator* loc);

#endif
