/* Plain point lists (rugo_points_text_parse): two numbers a line in SVG's number grammar, separated by
 * ',', ';' or blanks, with '#' comments and an optional CSV header; or a JSON object, which
 * rugo_points_parse reads. */
#include "io/svg_internal.h"

#include "core/array.h"
#include "core/internal.h"

#include <stdio.h>
#include <string.h>

rugo_status rugo_points_text_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                   rugo_point_list* out, rugo_parse_error* error) {
    rugo__svg_clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_JSON_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "text larger than %lu bytes",
                     (unsigned long)RUGO_MAX_JSON_BYTES);
        return RUGO_ERR_TOO_LARGE;
    }
    size_t p = 0;
    if (length >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        p = 3;
    size_t first = p;
    while (first < length && rugo__svg_is_wsp(text[first]))
        ++first;
    if (first < length && text[first] == '{')
        return rugo_points_parse(text, length, "points", allocator, out, error);

    const rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo__array pts = {NULL, 0}; /* rugo_vec2 */
    int n = 0;
    int seen_line = 0;
    rugo__svg_scanner sc;
    sc.text = text;
    sc.end = text + length;
    sc.loc.doc = text;
    sc.loc.doc_length = length;
    sc.loc.base = 0;
    sc.loc.exact = 1;
    sc.loc.path = "";
    sc.err = error;
    rugo_status st = RUGO_OK;
    char buf[16];
    while (p < length && st == RUGO_OK) {
        const char* nl = (const char*)memchr(text + p, '\n', length - p);
        const size_t eol = nl != NULL ? (size_t)(nl - text) : length;
        size_t q = p;
        while (q < eol && rugo__svg_is_wsp(text[q]))
            ++q;
        const size_t line_start = p;
        p = eol + 1;
        if (q >= eol || text[q] == '#') continue;
        if (!seen_line) {
            seen_line = 1;
            int digits = 0;
            for (size_t k = q; k < eol && !digits; ++k)
                digits = rugo__svg_is_digit(text[k]);
            if (!digits) continue; /* a CSV header such as "x,y" */
        }
        (void)line_start;
        sc.p = text + q;
        sc.end = text + eol;
        double v[2];
        st = rugo__svg_read_number(&sc, &v[0], "a number (x)");
        if (st != RUGO_OK) break;
        const char* before = sc.p;
        rugo__svg_skip_wsp(&sc);
        if (sc.p < sc.end && (*sc.p == ',' || *sc.p == ';')) {
            ++sc.p;
            rugo__svg_skip_wsp(&sc);
        } else if (sc.p == before) {
            st = rugo__svg_fail_at(error, RUGO_ERR_PARSE, &sc.loc, rugo__svg_offset(&sc, sc.p),
                                   "expected a separator (',', ';' or blanks) after x, found %s",
                                   rugo__svg_describe(sc.p, sc.end, buf, sizeof buf));
            break;
        }
        st = rugo__svg_read_number(&sc, &v[1], "a number (y)");
        if (st != RUGO_OK) break;
        rugo__svg_skip_wsp(&sc);
        if (sc.p < sc.end) {
            st = rugo__svg_fail_at(error, RUGO_ERR_PARSE, &sc.loc, rugo__svg_offset(&sc, sc.p),
                                   "expected two numbers per line, found %s after them",
                                   rugo__svg_describe(sc.p, sc.end, buf, sizeof buf));
            break;
        }
        if (n >= RUGO_MAX_CONTROL_POINTS) {
            st = rugo__svg_fail_at(error, RUGO_ERR_TOO_MANY_POINTS, &sc.loc, q, "more than %d points",
                                   RUGO_MAX_CONTROL_POINTS);
            break;
        }
        if (rugo__array_reserve(&pts, &al, (size_t)n + 1, sizeof(rugo_vec2), 16) != RUGO_OK) {
            st = rugo__svg_fail_at(error, RUGO_ERR_OUT_OF_MEMORY, &sc.loc, q, "out of memory");
            break;
        }
        ((rugo_vec2*)pts.data)[n++] = rugo_v2(v[0], v[1]);
    }
    if (st != RUGO_OK) {
        rugo__array_free(&pts, &al);
        return st;
    }
    out->points = (rugo_vec2*)pts.data;
    out->count = n;
    out->allocator = al;
    return RUGO_OK;
}
