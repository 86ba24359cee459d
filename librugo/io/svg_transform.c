/* SVG's transform grammar (a transform attribute: matrix, translate, scale, rotate, skewX, skewY) into
 * an affine map: rugo_svg_transform_parse, and the list reader the document scan uses. */
#include "io/svg_internal.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__affine_finite */
#include "io/json.h"        /* rugo__json_quote_for_message */

#include <stdio.h>
#include <string.h>

void rugo__svg_cos_sin_deg(double deg, double* c, double* s) {
    double r = fmod(deg, 360.0);
    if (r < 0.0) r += 360.0;
    if (r == 0.0) {
        *c = 1.0;
        *s = 0.0;
    } else if (r == 90.0) {
        *c = 0.0;
        *s = 1.0;
    } else if (r == 180.0) {
        *c = -1.0;
        *s = 0.0;
    } else if (r == 270.0) {
        *c = 0.0;
        *s = -1.0;
    } else {
        *c = cos(r * (RUGO__SVG_PI / 180.0));
        *s = sin(r * (RUGO__SVG_PI / 180.0));
    }
}

static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

rugo_status rugo__svg_transform_list(rugo__svg_scanner* sc, rugo_affine* out) {
    static const struct {
        const char* name;
        int min_args, max_args, alt_args;
    } fns[] = {{"matrix", 6, 6, 6}, {"translate", 1, 2, 2}, {"scale", 1, 2, 2},
               {"rotate", 1, 1, 3}, {"skewX", 1, 1, 1},     {"skewY", 1, 1, 1}};
    rugo_affine total = rugo_affine_identity();
    char buf[16];
    rugo__svg_skip_wsp(sc);
    while (sc->p < sc->end) {
        const char* name = sc->p;
        while (sc->p < sc->end && is_alpha(*sc->p))
            ++sc->p;
        size_t nlen = (size_t)(sc->p - name);
        int fn = -1;
        for (int i = 0; i < (int)(sizeof fns / sizeof fns[0]); ++i)
            if (strlen(fns[i].name) == nlen && memcmp(fns[i].name, name, nlen) == 0) fn = i;
        if (fn < 0) {
            if (nlen == 0)
                return rugo__svg_fail_at(
                    sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, name),
                    "expected a transform (matrix, translate, scale, rotate, skewX, skewY), found %s",
                    rugo__svg_describe(name, sc->end, buf, sizeof buf));
            char shown[40];
            rugo__json_quote_for_message(name, nlen, shown, sizeof shown);
            return rugo__svg_fail_at(
                sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, name),
                "unknown transform '%s' (expected matrix, translate, scale, rotate, skewX or skewY)", shown);
        }
        rugo__svg_skip_wsp(sc);
        if (sc->p >= sc->end || *sc->p != '(')
            return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                     "expected '(' after %s, found %s", fns[fn].name,
                                     rugo__svg_describe(sc->p, sc->end, buf, sizeof buf));
        ++sc->p;
        rugo__svg_skip_wsp(sc);
        double v[6];
        int n = 0;
        while (sc->p < sc->end && *sc->p != ')') {
            if (n > 0) {
                const char* before = sc->p;
                (void)rugo__svg_skip_comma_wsp(sc);
                if (sc->p < sc->end && *sc->p == ')')
                    return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, before),
                                             "a comma must be followed by a number");
            }
            if (n == 6)
                return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                         "too many arguments to %s", fns[fn].name);
            rugo_status st = rugo__svg_read_number(sc, &v[n], "a number");
            if (st != RUGO_OK) return st;
            ++n;
            rugo__svg_skip_wsp(sc);
        }
        if (sc->p >= sc->end)
            return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                                     "%s( is not closed by ')'", fns[fn].name);
        if (!((n >= fns[fn].min_args && n <= fns[fn].max_args) || n == fns[fn].alt_args))
            return rugo__svg_fail_at(
                sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, name), "%s takes %s, found %d",
                fns[fn].name,
                fn == 0
                    ? "6 numbers"
                    : (fn == 3 ? "1 or 3 numbers" : (fns[fn].max_args == 2 ? "1 or 2 numbers" : "1 number")),
                n);
        ++sc->p; /* ')' */
        rugo_affine t = rugo_affine_identity();
        double c, s;
        switch (fn) {
        case 0:
            t = rugo__svg_affine(v[0], v[1], v[2], v[3], v[4], v[5]);
            break;
        case 1:
            t = rugo__svg_affine(1.0, 0.0, 0.0, 1.0, v[0], n == 2 ? v[1] : 0.0);
            break;
        case 2:
            t = rugo__svg_affine(v[0], 0.0, 0.0, n == 2 ? v[1] : v[0], 0.0, 0.0);
            break;
        case 3:
            rugo__svg_cos_sin_deg(v[0], &c, &s);
            t = rugo__svg_affine(c, s, -s, c, 0.0, 0.0);
            if (n == 3) /* translate(cx, cy) rotate(a) translate(-cx, -cy) */
                t = rugo_affine_multiply(
                    rugo__svg_affine(1.0, 0.0, 0.0, 1.0, v[1], v[2]),
                    rugo_affine_multiply(t, rugo__svg_affine(1.0, 0.0, 0.0, 1.0, -v[1], -v[2])));
            break;
        case 4:
            rugo__svg_cos_sin_deg(v[0], &c, &s);
            t = rugo__svg_affine(1.0, 0.0, s / c, 1.0, 0.0, 0.0);
            break;
        default:
            rugo__svg_cos_sin_deg(v[0], &c, &s);
            t = rugo__svg_affine(1.0, s / c, 0.0, 1.0, 0.0, 0.0);
            break;
        }
        total = rugo_affine_multiply(total, t);
        if (!rugo__affine_finite(&total))
            return rugo__svg_fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, rugo__svg_offset(sc, name),
                                     "the transform overflows (or %s is infinite)", fns[fn].name);
        const char* before = sc->p;
        if (rugo__svg_skip_comma_wsp(sc) && sc->p >= sc->end)
            return rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, before),
                                     "a comma must be followed by a transform");
    }
    *out = total;
    return RUGO_OK;
}

rugo_status rugo_svg_transform_parse(const char* text, size_t length, rugo_affine* out,
                                     rugo_parse_error* error) {
    rugo__svg_clear_error(error);
    if (out != NULL) *out = rugo_affine_identity();
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_SVG_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "transform longer than %lu bytes",
                     (unsigned long)RUGO_MAX_SVG_BYTES);
        return RUGO_ERR_TOO_LARGE;
    }
    rugo__svg_scanner sc;
    sc.text = text;
    sc.p = text;
    sc.end = text + length;
    sc.loc.doc = text;
    sc.loc.doc_length = length;
    sc.loc.base = 0;
    sc.loc.exact = 1;
    sc.loc.path = "transform";
    sc.err = error;
    rugo_affine m;
    rugo_status st = rugo__svg_transform_list(&sc, &m);
    if (st == RUGO_OK) *out = m;
    return st;
}
