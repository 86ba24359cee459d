/* The root <svg> element's viewport (rugo_svg_read_viewport): its viewBox, width and height, and the
 * map from user units to CSS pixels that they make, so that an import can measure a drawing in the
 * units its author chose (docs/import.md, "Units and placement"). A bounded scan up to the first start
 * tag: prolog comments, processing instructions and a DOCTYPE are skipped as rugo_svg_find_path skips
 * them. */
#include "io/svg_internal.h"

#include "core/internal.h"
#include "io/json.h" /* rugo__json_locate */

#include <stdio.h>
#include <string.h>

/* CSS pixels per unit of an SVG length's unit suffix; 0 for units that need a context this scan does
 * not have (%, em, ex, ...). An empty suffix is px. */
static double px_per_unit(const char* u, size_t n) {
    static const struct {
        const char* name;
        double px;
    } units[] = {{"", 1.0},           {"px", 1.0},         {"in", 96.0},
                 {"cm", 96.0 / 2.54}, {"mm", 96.0 / 25.4}, {"q", 96.0 / 101.6},
                 {"Q", 96.0 / 101.6}, {"pt", 96.0 / 72.0}, {"pc", 16.0}};
    for (size_t i = 0; i < sizeof units / sizeof units[0]; ++i)
        if (strlen(units[i].name) == n && memcmp(units[i].name, u, n) == 0) return units[i].px;
    return 0.0;
}

static int is_wsp(char c) { return rugo__svg_is_wsp(c); }

/* A length attribute value ("250", "210mm", " 3in "): *px in CSS px and 1, or 0 when the value is a
 * relative length (%, em) that has no size without a context. Errors: PARSE, NOT_FINITE, BAD_FIELD
 * (a length <= 0). */
static rugo_status read_length(const char* doc, size_t doc_len, size_t off, size_t len, const char* name,
                               double* px, int* known, rugo_parse_error* error) {
    rugo__svg_locator loc = {doc, doc_len, off, 1, name};
    rugo__svg_scanner sc = {doc + off, doc + off, doc + off + len, loc, error};
    rugo__svg_skip_wsp(&sc);
    double v = 0.0;
    rugo_status st = rugo__svg_read_number(&sc, &v, "a length");
    if (st != RUGO_OK) return st;
    const char* u = sc.p;
    while (sc.p < sc.end && !is_wsp(*sc.p))
        ++sc.p;
    const size_t ulen = (size_t)(sc.p - u);
    rugo__svg_skip_wsp(&sc);
    if (sc.p != sc.end)
        return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &loc, (size_t)(sc.p - sc.text),
                                 "%s: unexpected text after the length", name);
    const double k = px_per_unit(u, ulen);
    *known = k > 0.0;
    if (!*known) return RUGO_OK; /* %, em, ex, vw ...: the size depends on where the SVG is shown */
    if (!(v > 0.0))
        return rugo__svg_fail_at(error, RUGO_ERR_BAD_FIELD, &loc, 0,
                                 "%s is %.17g: a document's size must be > 0; fix the attribute or import "
                                 "without the viewBox",
                                 name, v);
    *px = v * k;
    if (!isfinite(*px))
        return rugo__svg_fail_at(error, RUGO_ERR_NOT_FINITE, &loc, 0, "%s overflows in pixels", name);
    return RUGO_OK;
}

/* viewBox="min-x min-y width height" (comma or whitespace separated). */
static rugo_status read_viewbox(const char* doc, size_t doc_len, size_t off, size_t len, double vb[4],
                                rugo_parse_error* error) {
    rugo__svg_locator loc = {doc, doc_len, off, 1, "svg/viewBox"};
    rugo__svg_scanner sc = {doc + off, doc + off, doc + off + len, loc, error};
    static const char* const names[4] = {"min-x of the viewBox", "min-y of the viewBox",
                                         "width of the viewBox", "height of the viewBox"};
    rugo__svg_skip_wsp(&sc);
    for (int i = 0; i < 4; ++i) {
        if (i > 0) rugo__svg_skip_comma_wsp(&sc);
        rugo_status st = rugo__svg_read_number(&sc, &vb[i], names[i]);
        if (st != RUGO_OK) return st;
    }
    rugo__svg_skip_wsp(&sc);
    if (sc.p != sc.end)
        return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &loc, (size_t)(sc.p - sc.text),
                                 "more than four numbers in the viewBox");
    if (!(vb[2] > 0.0) || !(vb[3] > 0.0))
        return rugo__svg_fail_at(error, RUGO_ERR_BAD_FIELD, &loc, 0,
                                 "viewBox width %.17g and height %.17g must both be > 0; fix the attribute "
                                 "or import without the viewBox",
                                 vb[2], vb[3]);
    return RUGO_OK;
}

static size_t skip_past(const char* text, size_t from, size_t length, const char* end) {
    const size_t n = strlen(end);
    for (size_t i = from; i + n <= length; ++i)
        if (memcmp(text + i, end, n) == 0) return i + n;
    return length + 1;
}

rugo_status rugo_svg_read_viewport(const char* text, size_t length, rugo_svg_viewport* out,
                                   rugo_parse_error* error) {
    rugo__svg_clear_error(error);
    if (out != NULL) {
        memset(out, 0, sizeof *out);
        out->user_to_px = rugo_affine_identity();
    }
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_SVG_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "document larger than %lu bytes",
                     (unsigned long)RUGO_MAX_SVG_BYTES);
        return RUGO_ERR_TOO_LARGE;
    }
    rugo__svg_locator doc_loc = {text, length, 0, 1, "svg"};
    size_t p = 0;
    if (length >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        p = 3;
    for (;;) { /* the prolog, up to the first start tag */
        const char* lt = p < length ? (const char*)memchr(text + p, '<', length - p) : NULL;
        if (lt == NULL)
            return rugo__svg_fail_at(error, RUGO_ERR_BAD_FIELD, &doc_loc, length,
                                     "no <svg> element: the text is not an SVG document");
        p = (size_t)(lt - text);
        size_t next = 0;
        if (p + 4 <= length && memcmp(text + p, "<!--", 4) == 0)
            next = skip_past(text, p + 4, length, "-->");
        else if (p + 2 <= length && memcmp(text + p, "<?", 2) == 0)
            next = skip_past(text, p + 2, length, "?>");
        else if (p + 2 <= length && memcmp(text + p, "<!", 2) == 0) {
            int bracket = 0;
            size_t q = p + 2;
            for (; q < length && !(text[q] == '>' && bracket == 0); ++q)
                bracket += text[q] == '[' ? 1 : text[q] == ']' ? -1 : 0;
            next = q + 1;
        } else {
            break;
        }
        if (next > length)
            return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &doc_loc, p,
                                     "unterminated markup before the <svg> element");
        p = next;
    }
    /* The root start tag: its name, then attributes until '>' or '/>'. */
    size_t q = p + 1;
    const size_t name = q;
    while (q < length && !is_wsp(text[q]) && text[q] != '>' && text[q] != '/')
        ++q;
    const size_t nlen = q - name;
    const char* local = text + name;
    for (size_t i = 0; i < nlen; ++i)
        if (text[name + i] == ':') local = text + name + i + 1;
    const size_t llen = nlen - (size_t)(local - (text + name));
    if (!(llen == 3 && memcmp(local, "svg", 3) == 0))
        return rugo__svg_fail_at(error, RUGO_ERR_BAD_FIELD, &doc_loc, p,
                                 "the root element is not <svg>: the text is not an SVG document");
    size_t w_off = 0, w_len = 0, h_off = 0, h_len = 0, v_off = 0, v_len = 0;
    int has_w = 0, has_h = 0, has_v = 0;
    while (q < length && text[q] != '>') {
        while (q < length && (is_wsp(text[q]) || text[q] == '/'))
            ++q;
        if (q >= length || text[q] == '>') break;
        const size_t an = q;
        while (q < length && !is_wsp(text[q]) && text[q] != '=' && text[q] != '>')
            ++q;
        const size_t alen = q - an;
        while (q < length && is_wsp(text[q]))
            ++q;
        if (q >= length || text[q] != '=')
            return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &doc_loc, q,
                                     "expected '=' after an attribute name");
        ++q;
        while (q < length && is_wsp(text[q]))
            ++q;
        if (q >= length || (text[q] != '"' && text[q] != '\''))
            return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &doc_loc, q, "expected a quoted attribute value");
        const char quote = text[q];
        const size_t v = q + 1;
        size_t e = v;
        while (e < length && text[e] != quote)
            ++e;
        if (e >= length)
            return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &doc_loc, q, "unterminated attribute value");
        if (alen == 5 && memcmp(text + an, "width", 5) == 0)
            has_w = 1, w_off = v, w_len = e - v;
        else if (alen == 6 && memcmp(text + an, "height", 6) == 0)
            has_h = 1, h_off = v, h_len = e - v;
        else if (alen == 7 && memcmp(text + an, "viewBox", 7) == 0)
            has_v = 1, v_off = v, v_len = e - v;
        q = e + 1;
    }
    if (q >= length) return rugo__svg_fail_at(error, RUGO_ERR_PARSE, &doc_loc, p, "unterminated <svg> tag");
    rugo_status st = RUGO_OK;
    int wk = 0, hk = 0;
    double w = 0.0, h = 0.0;
    if (has_v) st = read_viewbox(text, length, v_off, v_len, out->viewbox, error);
    if (st == RUGO_OK && has_w) st = read_length(text, length, w_off, w_len, "svg/width", &w, &wk, error);
    if (st == RUGO_OK && has_h) st = read_length(text, length, h_off, h_len, "svg/height", &h, &hk, error);
    if (st != RUGO_OK) {
        memset(out, 0, sizeof *out);
        out->user_to_px = rugo_affine_identity();
        return st;
    }
    out->has_viewbox = has_v;
    out->has_width = wk;
    out->has_height = hk;
    out->width = wk ? w : 0.0;
    out->height = hk ? h : 0.0;
    if (has_v) {
        /* The viewport's size: width and height as given; a missing one follows the viewBox's aspect
         * ratio; both missing: the viewBox's own size (1 user unit = 1 px). */
        const double* vb = out->viewbox;
        double vw = wk ? w : (hk ? h * vb[2] / vb[3] : vb[2]);
        double vh = hk ? h : (wk ? w * vb[3] / vb[2] : vb[3]);
        /* preserveAspectRatio's default, xMidYMid meet: one uniform scale, the viewBox centred. */
        const double s = fmin(vw / vb[2], vh / vb[3]);
        const double tx = -vb[0] * s + 0.5 * (vw - vb[2] * s);
        const double ty = -vb[1] * s + 0.5 * (vh - vb[3] * s);
        out->user_to_px = rugo__svg_affine(s, 0.0, 0.0, s, tx, ty);
        if (!isfinite(s) || !isfinite(tx) || !isfinite(ty) || !(s > 0.0)) {
            memset(out, 0, sizeof *out);
            out->user_to_px = rugo_affine_identity();
            return rugo__svg_fail_at(error, RUGO_ERR_NOT_FINITE, &doc_loc, v_off,
                                     "the viewBox's scale to the width and height overflows");
        }
    }
    return RUGO_OK;
}
