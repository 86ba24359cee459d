/* The scanner every SVG reader of io shares (io/svg_internal.h): whitespace, separators and numbers in
 * SVG's grammar, and errors placed at the offending byte of the document. */
#include "io/svg_internal.h"

#include "core/internal.h"
#include "io/json.h" /* rugo__json_locate, rugo__json_quote_for_message */

#include <stdarg.h>
#include <stdio.h>

rugo_status rugo__svg_fail_at(rugo_parse_error* e, rugo_status st, const rugo__svg_locator* loc,
                              size_t offset, const char* fmt, ...) {
    if (e == NULL) return st;
    if (loc != NULL && loc->doc != NULL) {
        size_t at = loc->exact ? loc->base + offset : loc->base;
        rugo__json_locate(loc->doc, loc->doc_length, at, &e->line, &e->column);
    }
    snprintf(e->path, sizeof e->path, "%s", loc != NULL && loc->path != NULL ? loc->path : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

const char* rugo__svg_describe(const char* p, const char* end, char* buf, size_t size) {
    if (p >= end) return "the end";
    unsigned char c = (unsigned char)*p;
    if (c >= 0x20 && c < 0x7f)
        snprintf(buf, size, "'%c'", (char)c);
    else
        snprintf(buf, size, "byte 0x%02X", (unsigned)c);
    return buf;
}

/* Length of the number (SVG grammar: sign? (digits ('.' digits?)? | '.' digits) exponent?) at s, 0 if
 * there is none. An 'e' not followed by digits ends the number before it. */
static size_t number_span(const char* s, const char* end) {
    const char* q = s;
    if (q < end && (*q == '+' || *q == '-')) ++q;
    const char* int_start = q;
    while (q < end && rugo__svg_is_digit(*q))
        ++q;
    size_t int_digits = (size_t)(q - int_start);
    if (q < end && *q == '.') {
        const char* f = q + 1;
        while (f < end && rugo__svg_is_digit(*f))
            ++f;
        if (int_digits == 0 && f == q + 1) return 0;
        q = f;
    } else if (int_digits == 0) {
        return 0;
    }
    if (q < end && (*q == 'e' || *q == 'E')) {
        const char* x = q + 1;
        if (x < end && (*x == '+' || *x == '-')) ++x;
        if (x < end && rugo__svg_is_digit(*x)) {
            while (x < end && rugo__svg_is_digit(*x))
                ++x;
            q = x;
        }
    }
    return (size_t)(q - s);
}

void rugo__svg_skip_wsp(rugo__svg_scanner* sc) {
    while (sc->p < sc->end && rugo__svg_is_wsp(*sc->p))
        ++sc->p;
}

int rugo__svg_skip_comma_wsp(rugo__svg_scanner* sc) {
    rugo__svg_skip_wsp(sc);
    if (sc->p < sc->end && *sc->p == ',') {
        ++sc->p;
        rugo__svg_skip_wsp(sc);
        return 1;
    }
    return 0;
}

rugo_status rugo__svg_read_number(rugo__svg_scanner* sc, double* out, const char* what) {
    char buf[16];
    size_t n = number_span(sc->p, sc->end);
    if (n == 0)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                 "expected %s, found %s", what,
                                 rugo__svg_describe(sc->p, sc->end, buf, sizeof buf));
    if (n > RUGO_SVG_MAX_NUMBER_CHARS)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                 "number longer than %d characters", RUGO_SVG_MAX_NUMBER_CHARS);
    double x = 0.0;
    if (!rugo__strtod_c(sc->p, n, &x))
        return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                 "malformed number");
    if (!isfinite(x)) {
        char shown[40];
        rugo__json_quote_for_message(sc->p, n, shown, sizeof shown);
        return rugo__svg_fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                 "number %s is beyond the range of a double", shown);
    }
    *out = x;
    sc->p += n;
    return RUGO_OK;
}
