/* Importing outlines (import.h): SVG path data and transforms, a bounded scan of SVG documents,
 * arc-length sampling of one closed subpath, and plain point lists.
 *
 * Everything reads hostile text: no read past `length`, explicit size and nesting limits, no
 * recursion, every number checked finite. Positions in errors are byte offsets turned into line and
 * column by rugo__json_locate (the same convention as the JSON reader). */
#include "rugo/import.h"

#include "core/array.h"
#include "core/internal.h"
#include "io/json.h" /* rugo__json_locate */

#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* "RSmp" — marks a def that came from rugo_default_outline_sample_def. */
#define SAMPLE_DEF_COOKIE 0x52536d70

/* ---- errors --------------------------------------------------------------------------------------- */

static void clear_error(rugo_parse_error* e) {
    if (e != NULL) memset(e, 0, sizeof *e);
}

/* Where errors are reported: offsets into the text being read are mapped into `doc` (the whole
 * document, for a d or transform attribute) as base + offset when `exact`, or to base otherwise (an
 * attribute whose entities were decoded, so offsets no longer match the document's bytes). */
typedef struct locator {
    const char* doc;
    size_t doc_length;
    size_t base;
    int exact;
    const char* path; /* e.g. "d" or "path#rock/d" */
} locator;

#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
static rugo_status
fail_at(rugo_parse_error* e, rugo_status st, const locator* loc, size_t offset, const char* fmt, ...) {
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

/* A short printable description of the byte at p: "'x'", "byte 0xNN" or "the end". */
static const char* describe(const char* p, const char* end, char* buf, size_t size) {
    if (p >= end) return "the end";
    unsigned char c = (unsigned char)*p;
    if (c >= 0x20 && c < 0x7f)
        snprintf(buf, size, "'%c'", (char)c);
    else
        snprintf(buf, size, "byte 0x%02X", (unsigned)c);
    return buf;
}

/* ---- lexical helpers ------------------------------------------------------------------------------ */

static int is_digit(char c) { return c >= '0' && c <= '9'; }
/* SVG 2 whitespace: space, tab, LF, CR, FF. */
static int is_wsp(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
static int starts_number(char c) { return is_digit(c) || c == '.' || c == '+' || c == '-'; }

/* Length of the number (SVG grammar: sign? (digits ('.' digits?)? | '.' digits) exponent?) at s, 0 if
 * there is none. An 'e' not followed by digits ends the number before it. */
static size_t number_span(const char* s, const char* end) {
    const char* q = s;
    if (q < end && (*q == '+' || *q == '-')) ++q;
    const char* int_start = q;
    while (q < end && is_digit(*q))
        ++q;
    size_t int_digits = (size_t)(q - int_start);
    if (q < end && *q == '.') {
        const char* f = q + 1;
        while (f < end && is_digit(*f))
            ++f;
        if (int_digits == 0 && f == q + 1) return 0;
        q = f;
    } else if (int_digits == 0) {
        return 0;
    }
    if (q < end && (*q == 'e' || *q == 'E')) {
        const char* x = q + 1;
        if (x < end && (*x == '+' || *x == '-')) ++x;
        if (x < end && is_digit(*x)) {
            while (x < end && is_digit(*x))
                ++x;
            q = x;
        }
    }
    return (size_t)(q - s);
}

/* A cursor over text[0, length) with its error locator. */
typedef struct scanner {
    const char* text;
    const char* p;
    const char* end;
    locator loc;
    rugo_parse_error* err;
} scanner;

static size_t sc_offset(const scanner* sc, const char* p) { return (size_t)(p - sc->text); }

static void skip_wsp(scanner* sc) {
    while (sc->p < sc->end && is_wsp(*sc->p))
        ++sc->p;
}

/* comma-wsp? : wsp* (',' wsp*)?. Returns 1 if a comma was consumed. */
static int skip_comma_wsp(scanner* sc) {
    skip_wsp(sc);
    if (sc->p < sc->end && *sc->p == ',') {
        ++sc->p;
        skip_wsp(sc);
        return 1;
    }
    return 0;
}

/* Reads a number at the cursor. `what` names it for messages ("number 3 of 'C'"). */
static rugo_status read_number(scanner* sc, double* out, const char* what) {
    char buf[16];
    size_t n = number_span(sc->p, sc->end);
    if (n == 0)
        return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p), "expected %s, found %s", what,
                       describe(sc->p, sc->end, buf, sizeof buf));
    if (n > RUGO_SVG_MAX_NUMBER_CHARS)
        return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p),
                       "number longer than %d characters", RUGO_SVG_MAX_NUMBER_CHARS);
    double x = 0.0;
    if (!rugo__strtod_c(sc->p, n, &x))
        return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p), "malformed number");
    if (!isfinite(x)) {
        char shown[40];
        rugo__json_quote_for_message(sc->p, n, shown, sizeof shown);
        return fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, sc_offset(sc, sc->p),
                       "number %s is beyond the range of a double", shown);
    }
    *out = x;
    sc->p += n;
    return RUGO_OK;
}

/* Room for one more element after `count` in a (room for 16 first, then doubling). 0 on success, -1
 * out of memory. */
static int grow(const rugo_allocator* al, rugo__array* a, int count, size_t elem) {
    return rugo__array_reserve(a, al, (size_t)count + 1, elem, 16) == RUGO_OK ? 0 : -1;
}

/* ---- transforms ------------------------------------------------------------------------------------ */

/* cos and sin of an angle in degrees, exact for multiples of 90 degrees (rotate(90) is common). */
static void cos_sin_deg(double deg, double* c, double* s) {
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
        *c = cos(r * (PI / 180.0));
        *s = sin(r * (PI / 180.0));
    }
}

static int affine_finite(const rugo_affine* m) {
    return isfinite(m->a) && isfinite(m->b) && isfinite(m->c) && isfinite(m->d) && isfinite(m->e) &&
           isfinite(m->f);
}

static rugo_affine affine_make(double a, double b, double c, double d, double e, double f) {
    rugo_affine m;
    m.a = a;
    m.b = b;
    m.c = c;
    m.d = d;
    m.e = e;
    m.f = f;
    return m;
}

static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

static rugo_status parse_transform_list(scanner* sc, rugo_affine* out) {
    static const struct {
        const char* name;
        int min_args, max_args, alt_args;
    } fns[] = {{"matrix", 6, 6, 6}, {"translate", 1, 2, 2}, {"scale", 1, 2, 2},
               {"rotate", 1, 1, 3}, {"skewX", 1, 1, 1},     {"skewY", 1, 1, 1}};
    rugo_affine total = rugo_affine_identity();
    char buf[16];
    skip_wsp(sc);
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
                return fail_at(
                    sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, name),
                    "expected a transform (matrix, translate, scale, rotate, skewX, skewY), found %s",
                    describe(name, sc->end, buf, sizeof buf));
            char shown[40];
            rugo__json_quote_for_message(name, nlen, shown, sizeof shown);
            return fail_at(
                sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, name),
                "unknown transform '%s' (expected matrix, translate, scale, rotate, skewX or skewY)", shown);
        }
        skip_wsp(sc);
        if (sc->p >= sc->end || *sc->p != '(')
            return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p),
                           "expected '(' after %s, found %s", fns[fn].name,
                           describe(sc->p, sc->end, buf, sizeof buf));
        ++sc->p;
        skip_wsp(sc);
        double v[6];
        int n = 0;
        while (sc->p < sc->end && *sc->p != ')') {
            if (n > 0) {
                const char* before = sc->p;
                (void)skip_comma_wsp(sc);
                if (sc->p < sc->end && *sc->p == ')')
                    return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, before),
                                   "a comma must be followed by a number");
            }
            if (n == 6)
                return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p),
                               "too many arguments to %s", fns[fn].name);
            rugo_status st = read_number(sc, &v[n], "a number");
            if (st != RUGO_OK) return st;
            ++n;
            skip_wsp(sc);
        }
        if (sc->p >= sc->end)
            return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p),
                           "%s( is not closed by ')'", fns[fn].name);
        if (!((n >= fns[fn].min_args && n <= fns[fn].max_args) || n == fns[fn].alt_args))
            return fail_at(
                sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, name), "%s takes %s, found %d", fns[fn].name,
                fn == 0
                    ? "6 numbers"
                    : (fn == 3 ? "1 or 3 numbers" : (fns[fn].max_args == 2 ? "1 or 2 numbers" : "1 number")),
                n);
        ++sc->p; /* ')' */
        rugo_affine t = rugo_affine_identity();
        double c, s;
        switch (fn) {
        case 0:
            t = affine_make(v[0], v[1], v[2], v[3], v[4], v[5]);
            break;
        case 1:
            t = affine_make(1.0, 0.0, 0.0, 1.0, v[0], n == 2 ? v[1] : 0.0);
            break;
        case 2:
            t = affine_make(v[0], 0.0, 0.0, n == 2 ? v[1] : v[0], 0.0, 0.0);
            break;
        case 3:
            cos_sin_deg(v[0], &c, &s);
            t = affine_make(c, s, -s, c, 0.0, 0.0);
            if (n == 3) /* translate(cx, cy) rotate(a) translate(-cx, -cy) */
                t = rugo_affine_multiply(
                    affine_make(1.0, 0.0, 0.0, 1.0, v[1], v[2]),
                    rugo_affine_multiply(t, affine_make(1.0, 0.0, 0.0, 1.0, -v[1], -v[2])));
            break;
        case 4:
            cos_sin_deg(v[0], &c, &s);
            t = affine_make(1.0, 0.0, s / c, 1.0, 0.0, 0.0);
            break;
        default:
            cos_sin_deg(v[0], &c, &s);
            t = affine_make(1.0, s / c, 0.0, 1.0, 0.0, 0.0);
            break;
        }
        total = rugo_affine_multiply(total, t);
        if (!affine_finite(&total))
            return fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, sc_offset(sc, name),
                           "the transform overflows (or %s is infinite)", fns[fn].name);
        const char* before = sc->p;
        if (skip_comma_wsp(sc) && sc->p >= sc->end)
            return fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, before),
                           "a comma must be followed by a transform");
    }
    *out = total;
    return RUGO_OK;
}

rugo_status rugo_svg_transform_parse(const char* text, size_t length, rugo_affine* out,
                                     rugo_parse_error* error) {
    clear_error(error);
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
    scanner sc;
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
    rugo_status st = parse_transform_list(&sc, &m);
    if (st == RUGO_OK) *out = m;
    return st;
}

/* ---- path data -------------------------------------------------------------------------------------- */

typedef struct path_builder {
    rugo_allocator al;
    rugo__array seg; /* rugo_path_segment */
    int nseg;
    rugo__array sub; /* rugo_subpath */
    int nsub;
} path_builder;

static rugo_path_segment* builder_segments(const path_builder* b) { return (rugo_path_segment*)b->seg.data; }
static rugo_subpath* builder_subpaths(const path_builder* b) { return (rugo_subpath*)b->sub.data; }

static void builder_free(path_builder* b) {
    rugo__array_free(&b->seg, &b->al);
    rugo__array_free(&b->sub, &b->al);
}

static rugo_vec2 segment_end(const rugo_path_segment* s) {
    switch (s->kind) {
    case RUGO_PATH_LINE:
    case RUGO_PATH_ARC:
        return s->p[1];
    case RUGO_PATH_QUADRATIC:
        return s->p[2];
    default:
        return s->p[3];
    }
}

static int segment_finite(const rugo_path_segment* s) {
    for (int i = 0; i < 4; ++i)
        if (!rugo__v2_finite(s->p[i])) return 0;
    if (s->kind == RUGO_PATH_ARC)
        return rugo__v2_finite(s->centre) && isfinite(s->rx) && isfinite(s->ry) && isfinite(s->phi) &&
               isfinite(s->theta1) && isfinite(s->dtheta);
    return 1;
}

/* Endpoint to centre parametrisation (SVG 1.1 implementation notes F.6.5, with the out-of-range
 * corrections of F.6.6). Works in coordinates scaled by the radii, where the ellipse is the unit
 * circle, so that nothing is squared at the input's magnitude. Returns 0: drop the arc (same end
 * points), 1: a straight line (a zero radius, or a chord negligible against the radii), 2: an arc. */
static int arc_to_centre(rugo_vec2 p0, rugo_vec2 p1, double rx, double ry, double phi_deg, int large,
                         int sweep, rugo_path_segment* s) {
    if (p0.x == p1.x && p0.y == p1.y) return 0;
    rx = fabs(rx);
    ry = fabs(ry);
    if (rx == 0.0 || ry == 0.0) return 1;
    double cphi, sphi;
    cos_sin_deg(phi_deg, &cphi, &sphi);
    const double dx2 = 0.5 * p0.x - 0.5 * p1.x, dy2 = 0.5 * p0.y - 0.5 * p1.y;
    const double x1p = cphi * dx2 + sphi * dy2, y1p = -sphi * dx2 + cphi * dy2;
    double X = x1p / rx, Y = y1p / ry;
    double L = hypot(X, Y);
    if (!(L > 0.0)) return 1;
    if (!isfinite(L))
        return 1;  /* radii negligible against the chord: F.6.6 scales them up to a half
                      ellipse whose radii overflow; the chord is the limit */
    if (L > 1.0) { /* radii too small: scale them up just enough (the centre is the chord's midpoint) */
        rx *= L;
        ry *= L;
        X /= L;
        Y /= L;
        L = 1.0;
    }
    double coef = sqrt(fmax(0.0, (1.0 - L) * (1.0 + L))) / L;
    if (large == sweep) coef = -coef;
    const double cu = coef * Y, cv = -coef * X; /* centre in scaled, rotated coordinates */
    const double ux = X - cu, uy = Y - cv, vx = -X - cu, vy = -Y - cv;
    double theta1 = atan2(uy, ux);
    double dtheta = atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    if (!sweep && dtheta > 0.0) dtheta -= 2.0 * PI;
    if (sweep && dtheta < 0.0) dtheta += 2.0 * PI;
    const double cxp = cu * rx, cyp = cv * ry;
    s->kind = RUGO_PATH_ARC;
    s->p[0] = p0;
    s->p[1] = p1;
    s->p[2] = p1;
    s->p[3] = p1;
    s->centre = rugo_v2(cphi * cxp - sphi * cyp + (0.5 * p0.x + 0.5 * p1.x),
                        sphi * cxp + cphi * cyp + (0.5 * p0.y + 0.5 * p1.y));
    s->rx = rx;
    s->ry = ry;
    s->phi = fmod(phi_deg, 360.0) * (PI / 180.0);
    s->theta1 = theta1;
    s->dtheta = dtheta;
    return 2;
}

/* Number of arguments of a path command. */
static int command_arity(char c) {
    switch (c) {
    case 'M':
    case 'm':
    case 'L':
    case 'l':
    case 'T':
    case 't':
        return 2;
    case 'H':
    case 'h':
    case 'V':
    case 'v':
        return 1;
    case 'C':
    case 'c':
        return 6;
    case 'S':
    case 's':
    case 'Q':
    case 'q':
        return 4;
    case 'A':
    case 'a':
        return 7;
    case 'Z':
    case 'z':
        return 0;
    default:
        return -1;
    }
}

typedef struct path_state {
    path_builder b;
    rugo_vec2 cur, start;
    rugo_vec2 last_cubic, last_quad; /* second control point of the last C/S, control of the last Q/T */
    char prev;                       /* 'C' after C/S, 'Q' after Q/T, 0 otherwise */
    int in_subpath;
} path_state;

static rugo_status begin_subpath(path_state* ps, scanner* sc, size_t at, rugo_vec2 start) {
    if (ps->b.nsub >= RUGO_MAX_PATH_SEGMENTS)
        return fail_at(sc->err, RUGO_ERR_TOO_LARGE, &sc->loc, at, "more than %d subpaths",
                       RUGO_MAX_PATH_SEGMENTS);
    if (grow(&ps->b.al, &ps->b.sub, ps->b.nsub, sizeof(rugo_subpath)) != 0)
        return fail_at(sc->err, RUGO_ERR_OUT_OF_MEMORY, &sc->loc, at, "out of memory");
    rugo_subpath* s = &builder_subpaths(&ps->b)[ps->b.nsub++];
    s->first = ps->b.nseg;
    s->count = 0;
    s->start = start;
    s->closed = 0;
    ps->in_subpath = 1;
    return RUGO_OK;
}

static rugo_status add_segment(path_state* ps, scanner* sc, size_t at, rugo_path_segment* s) {
    s->offset = at;
    if (!segment_finite(s))
        return fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
                       "coordinates overflow (beyond the range of a double)");
    if (ps->b.nseg >= RUGO_MAX_PATH_SEGMENTS)
        return fail_at(sc->err, RUGO_ERR_TOO_LARGE, &sc->loc, at, "more than %d segments",
                       RUGO_MAX_PATH_SEGMENTS);
    if (grow(&ps->b.al, &ps->b.seg, ps->b.nseg, sizeof(rugo_path_segment)) != 0)
        return fail_at(sc->err, RUGO_ERR_OUT_OF_MEMORY, &sc->loc, at, "out of memory");
    builder_segments(&ps->b)[ps->b.nseg++] = *s;
    builder_subpaths(&ps->b)[ps->b.nsub - 1].count++;
    ps->cur = segment_end(s);
    return RUGO_OK;
}

static rugo_path_segment line_segment(rugo_vec2 a, rugo_vec2 b) {
    rugo_path_segment s;
    memset(&s, 0, sizeof s);
    s.kind = RUGO_PATH_LINE;
    s.p[0] = a;
    s.p[1] = b;
    s.p[2] = b;
    s.p[3] = b;
    return s;
}

/* Applies one argument set of command c (arguments v) at offset `at`. */
static rugo_status apply_command(path_state* ps, scanner* sc, size_t at, char c, const double* v) {
    const int rel = c >= 'a' && c <= 'z';
    const rugo_vec2 cur = ps->cur;
    const double ox = rel ? cur.x : 0.0, oy = rel ? cur.y : 0.0;
    rugo_path_segment s;
    memset(&s, 0, sizeof s);
    rugo_status st;
    char prev = 0;
    if (c != 'M' && c != 'm' && !ps->in_subpath) {
        /* A drawing command right after Z: a new subpath at the same start point. */
        st = begin_subpath(ps, sc, at, ps->start);
        if (st != RUGO_OK) return st;
    }
    switch (c) {
    case 'M':
    case 'm': {
        rugo_vec2 p = rugo_v2(ox + v[0], oy + v[1]);
        if (!rugo__v2_finite(p))
            return fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
                           "coordinates overflow (beyond the range of a double)");
        st = begin_subpath(ps, sc, at, p);
        if (st != RUGO_OK) return st;
        ps->cur = ps->start = p;
        break;
    }
    case 'L':
    case 'l':
        s = line_segment(cur, rugo_v2(ox + v[0], oy + v[1]));
        st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
        break;
    case 'H':
    case 'h':
        s = line_segment(cur, rugo_v2(ox + v[0], cur.y));
        st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
        break;
    case 'V':
    case 'v':
        s = line_segment(cur, rugo_v2(cur.x, oy + v[0]));
        st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
        break;
    case 'C':
    case 'c':
    case 'S':
    case 's': {
        const int smooth = c == 'S' || c == 's';
        s.kind = RUGO_PATH_CUBIC;
        s.p[0] = cur;
        if (smooth) {
            s.p[1] = ps->prev == 'C' ? rugo_v2(2.0 * cur.x - ps->last_cubic.x, 2.0 * cur.y - ps->last_cubic.y)
                                     : cur;
            s.p[2] = rugo_v2(ox + v[0], oy + v[1]);
            s.p[3] = rugo_v2(ox + v[2], oy + v[3]);
        } else {
            s.p[1] = rugo_v2(ox + v[0], oy + v[1]);
            s.p[2] = rugo_v2(ox + v[2], oy + v[3]);
            s.p[3] = rugo_v2(ox + v[4], oy + v[5]);
        }
        st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
        ps->last_cubic = s.p[2];
        prev = 'C';
        break;
    }
    case 'Q':
    case 'q':
    case 'T':
    case 't': {
        const int smooth = c == 'T' || c == 't';
        s.kind = RUGO_PATH_QUADRATIC;
        s.p[0] = cur;
        if (smooth) {
            s.p[1] =
                ps->prev == 'Q' ? rugo_v2(2.0 * cur.x - ps->last_quad.x, 2.0 * cur.y - ps->last_quad.y) : cur;
            s.p[2] = rugo_v2(ox + v[0], oy + v[1]);
        } else {
            s.p[1] = rugo_v2(ox + v[0], oy + v[1]);
            s.p[2] = rugo_v2(ox + v[2], oy + v[3]);
        }
        s.p[3] = s.p[2];
        st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
        ps->last_quad = s.p[1];
        prev = 'Q';
        break;
    }
    default: { /* A, a */
        rugo_vec2 end = rugo_v2(ox + v[5], oy + v[6]);
        if (!rugo__v2_finite(end))
            return fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
                           "coordinates overflow (beyond the range of a double)");
        int kind = arc_to_centre(cur, end, v[0], v[1], v[2], v[3] != 0.0, v[4] != 0.0, &s);
        if (kind == 1) s = line_segment(cur, end);
        if (kind != 0) {
            st = add_segment(ps, sc, at, &s);
            if (st != RUGO_OK) return st;
        }
        break;
    }
    }
    ps->prev = prev;
    return RUGO_OK;
}

static rugo_status close_subpath(path_state* ps, scanner* sc, size_t at) {
    if (!ps->in_subpath) {
        rugo_status st = begin_subpath(ps, sc, at, ps->start);
        if (st != RUGO_OK) return st;
    }
    if (ps->cur.x != ps->start.x || ps->cur.y != ps->start.y) {
        rugo_path_segment s = line_segment(ps->cur, ps->start);
        rugo_status st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
    }
    builder_subpaths(&ps->b)[ps->b.nsub - 1].closed = 1;
    ps->cur = ps->start;
    ps->in_subpath = 0;
    ps->prev = 0;
    return RUGO_OK;
}

static rugo_status parse_path_data(scanner* sc, const rugo_allocator* allocator, rugo_path* out) {
    path_state ps;
    memset(&ps, 0, sizeof ps);
    ps.b.al = rugo__allocator_or_default(allocator);
    char buf[16];
    char cmd = 0;
    rugo_status st = RUGO_OK;
    skip_wsp(sc);
    while (sc->p < sc->end) {
        const char* at = sc->p;
        const char ch = *sc->p;
        if (command_arity(ch) >= 0) {
            if (cmd == 0 && ch != 'M' && ch != 'm') {
                st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, at),
                             "path data must start with a moveto (M or m), found '%c'", ch);
                break;
            }
            cmd = ch;
            ++sc->p;
            if (cmd == 'Z' || cmd == 'z') {
                st = close_subpath(&ps, sc, sc_offset(sc, at));
                if (st != RUGO_OK) break;
                skip_wsp(sc);
                continue;
            }
            skip_wsp(sc);
        } else if (starts_number(ch)) {
            if (cmd == 0) {
                st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, at),
                             "path data must start with a moveto (M or m), found a number");
                break;
            }
            if (cmd == 'Z' || cmd == 'z') {
                st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, at),
                             "'%c' takes no numbers: expected a command letter", cmd);
                break;
            }
            /* An implicit repetition of cmd (M's further pairs are lineto, set below). */
        } else if (ch == ',') {
            st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, at), "unexpected ','");
            break;
        } else {
            st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, at), "unknown path command %s",
                         describe(at, sc->end, buf, sizeof buf));
            break;
        }
        const int n = command_arity(cmd);
        double v[7];
        for (int i = 0; i < n && st == RUGO_OK; ++i) {
            if (i > 0) (void)skip_comma_wsp(sc);
            if ((cmd == 'A' || cmd == 'a') && (i == 3 || i == 4)) {
                /* Flags are single characters; "a1 1 0 00 1 1" has them without separators. */
                if (sc->p < sc->end && (*sc->p == '0' || *sc->p == '1')) {
                    v[i] = *sc->p == '1' ? 1.0 : 0.0;
                    ++sc->p;
                } else {
                    st = fail_at(
                        sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, sc->p),
                        "'%c' needs 7 numbers: argument %d is the %s flag and must be 0 or 1, found %s", cmd,
                        i + 1, i == 3 ? "large-arc" : "sweep", describe(sc->p, sc->end, buf, sizeof buf));
                }
            } else {
                char what[64];
                snprintf(what, sizeof what, "a number (argument %d of the %d of '%c')", i + 1, n, cmd);
                st = read_number(sc, &v[i], what);
            }
        }
        if (st != RUGO_OK) break;
        st = apply_command(&ps, sc, sc_offset(sc, at), cmd, v);
        if (st != RUGO_OK) break;
        if (cmd == 'M') cmd = 'L';
        if (cmd == 'm') cmd = 'l';
        const char* before = sc->p;
        if (skip_comma_wsp(sc) && !(sc->p < sc->end && starts_number(*sc->p))) {
            st = fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, sc_offset(sc, before),
                         "a comma must be followed by a number");
            break;
        }
    }
    if (st != RUGO_OK) {
        builder_free(&ps.b);
        return st;
    }
    out->segments = builder_segments(&ps.b);
    out->segment_count = ps.b.nseg;
    out->subpaths = builder_subpaths(&ps.b);
    out->subpath_count = ps.b.nsub;
    out->allocator = ps.b.al;
    return RUGO_OK;
}

static rugo_status path_parse_located(const char* d, size_t length, const rugo_allocator* allocator,
                                      rugo_path* out, rugo_parse_error* error, const locator* loc) {
    scanner sc;
    sc.text = d;
    sc.p = d;
    sc.end = d + length;
    sc.loc = *loc;
    sc.err = error;
    return parse_path_data(&sc, allocator, out);
}

rugo_status rugo_path_parse(const char* d, size_t length, const rugo_allocator* allocator, rugo_path* out,
                            rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (d == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_SVG_BYTES) {
        if (error != NULL) {
            snprintf(error->path, sizeof error->path, "d");
            snprintf(error->message, sizeof error->message, "path data longer than %lu bytes",
                     (unsigned long)RUGO_MAX_SVG_BYTES);
        }
        return RUGO_ERR_TOO_LARGE;
    }
    locator loc;
    loc.doc = d;
    loc.doc_length = length;
    loc.base = 0;
    loc.exact = 1;
    loc.path = "d";
    return path_parse_located(d, length, allocator, out, error, &loc);
}

void rugo_path_free(rugo_path* path) {
    if (path == NULL) return;
    rugo__free(&path->allocator, path->segments);
    rugo__free(&path->allocator, path->subpaths);
    memset(path, 0, sizeof *path);
}

rugo_status rugo_path_from_points(const rugo_vec2* points, int count, const rugo_allocator* allocator,
                                  rugo_path* out) {
    if (out != NULL) memset(out, 0, sizeof *out);
    if (points == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (count < 3) return RUGO_ERR_TOO_FEW_POINTS;
    if (count > RUGO_MAX_PATH_SEGMENTS) return RUGO_ERR_TOO_LARGE;
    for (int i = 0; i < count; ++i)
        if (!rugo__v2_finite(points[i])) return RUGO_ERR_NOT_FINITE;
    const rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_path_segment* seg = (rugo_path_segment*)rugo__alloc_array(&al, (size_t)count, sizeof *seg);
    rugo_subpath* sub = (rugo_subpath*)rugo__alloc_array(&al, 1, sizeof *sub);
    if (seg == NULL || sub == NULL) {
        rugo__free(&al, seg);
        rugo__free(&al, sub);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    int n = 0;
    for (int i = 0; i < count; ++i) {
        rugo_vec2 a = points[i], b = points[i + 1 < count ? i + 1 : 0];
        if (a.x == b.x && a.y == b.y) continue; /* repeated point (or last = first): no segment */
        seg[n] = line_segment(a, b);
        seg[n].offset = (size_t)i;
        ++n;
    }
    if (n == 0) { /* every point the same: no segments, and no array (as for a bare moveto) */
        rugo__free(&al, seg);
        seg = NULL;
    }
    sub->first = 0;
    sub->count = n;
    sub->start = n > 0 ? seg[0].p[0] : points[0];
    sub->closed = 1;
    out->segments = seg;
    out->segment_count = n;
    out->subpaths = sub;
    out->subpath_count = 1;
    out->allocator = al;
    return RUGO_OK;
}

/* ---- segment evaluation ------------------------------------------------------------------------------ */

static rugo_vec2 segment_point(const rugo_path_segment* s, double t) {
    if (t == 0.0) return s->p[0];
    if (t == 1.0) return segment_end(s);
    const double u = 1.0 - t;
    switch (s->kind) {
    case RUGO_PATH_LINE:
        return rugo_v2(s->p[0].x + t * (s->p[1].x - s->p[0].x), s->p[0].y + t * (s->p[1].y - s->p[0].y));
    case RUGO_PATH_QUADRATIC: {
        const double b0 = u * u, b1 = 2.0 * u * t, b2 = t * t;
        return rugo_v2(b0 * s->p[0].x + b1 * s->p[1].x + b2 * s->p[2].x,
                       b0 * s->p[0].y + b1 * s->p[1].y + b2 * s->p[2].y);
    }
    case RUGO_PATH_CUBIC: {
        const double b0 = u * u * u, b1 = 3.0 * u * u * t, b2 = 3.0 * u * t * t, b3 = t * t * t;
        return rugo_v2(b0 * s->p[0].x + b1 * s->p[1].x + b2 * s->p[2].x + b3 * s->p[3].x,
                       b0 * s->p[0].y + b1 * s->p[1].y + b2 * s->p[2].y + b3 * s->p[3].y);
    }
    default: {
        const double th = s->theta1 + t * s->dtheta;
        const double ex = s->rx * cos(th), ey = s->ry * sin(th);
        const double c = cos(s->phi), sn = sin(s->phi);
        return rugo_v2(s->centre.x + c * ex - sn * ey, s->centre.y + sn * ex + c * ey);
    }
    }
}

static rugo_vec2 segment_derivative(const rugo_path_segment* s, double t) {
    const double u = 1.0 - t;
    switch (s->kind) {
    case RUGO_PATH_LINE:
        return rugo_v2_sub(s->p[1], s->p[0]);
    case RUGO_PATH_QUADRATIC: {
        rugo_vec2 d0 = rugo_v2_sub(s->p[1], s->p[0]), d1 = rugo_v2_sub(s->p[2], s->p[1]);
        return rugo_v2(2.0 * (u * d0.x + t * d1.x), 2.0 * (u * d0.y + t * d1.y));
    }
    case RUGO_PATH_CUBIC: {
        rugo_vec2 d0 = rugo_v2_sub(s->p[1], s->p[0]), d1 = rugo_v2_sub(s->p[2], s->p[1]),
                  d2 = rugo_v2_sub(s->p[3], s->p[2]);
        const double b0 = 3.0 * u * u, b1 = 6.0 * u * t, b2 = 3.0 * t * t;
        return rugo_v2(b0 * d0.x + b1 * d1.x + b2 * d2.x, b0 * d0.y + b1 * d1.y + b2 * d2.y);
    }
    default: {
        const double th = s->theta1 + t * s->dtheta;
        const double ex = -s->rx * sin(th) * s->dtheta, ey = s->ry * cos(th) * s->dtheta;
        const double c = cos(s->phi), sn = sin(s->phi);
        return rugo_v2(c * ex - sn * ey, sn * ex + c * ey);
    }
    }
}

rugo_vec2 rugo_path_segment_point(const rugo_path_segment* segment, rugo_real t) {
    if (segment == NULL) return rugo_v2(NAN, NAN);
    return segment_point(segment, t);
}

rugo_vec2 rugo_path_segment_derivative(const rugo_path_segment* segment, rugo_real t) {
    if (segment == NULL) return rugo_v2(NAN, NAN);
    return segment_derivative(segment, t);
}

/* A segment seen through an affine map. */
typedef struct mapped {
    const rugo_path_segment* s;
    rugo_affine m;
} mapped;

static rugo_vec2 mapped_point(const mapped* g, double t) {
    return rugo_affine_apply(g->m, segment_point(g->s, t));
}

static double mapped_speed(const mapped* g, double t) {
    rugo_vec2 d = segment_derivative(g->s, t);
    return hypot(g->m.a * d.x + g->m.c * d.y, g->m.b * d.x + g->m.d * d.y);
}

/* 8-point Gauss-Legendre on [-1, 1]: nodes ±x_i, weights w_i. */
static const double kGLx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
static const double kGLw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};

static double gl_length(const mapped* g, double a, double b) {
    const double h = 0.5 * (b - a), c = 0.5 * (a + b);
    double sum = 0.0;
    for (int i = 0; i < 4; ++i)
        sum += kGLw[i] * (mapped_speed(g, c - h * kGLx[i]) + mapped_speed(g, c + h * kGLx[i]));
    return h * sum;
}

/* Adaptive arc length, as a left-to-right walk over accepted intervals ("leaves"), so that the same
 * walk both measures a segment and, repeated, places samples in it: an interval is accepted when its
 * halves agree with it to kLeafTolerance of the segment's length per unit of parameter, or at depth
 * kLeafDepth (a cusp or a kink of the speed refines only the intervals next to it). */
#define LEAF_DEPTH 16
static const double kLeafTolerance = 1e-12;

typedef struct leaf_walk {
    const mapped* g;
    double scale; /* the segment's length estimate, for the relative test */
    int top;
    struct {
        double a, b, whole;
        int depth;
    } stack[LEAF_DEPTH + 2];
} leaf_walk;

static void leaf_walk_init(leaf_walk* w, const mapped* g) {
    w->g = g;
    w->stack[0].a = 0.0;
    w->stack[0].b = 1.0;
    w->stack[0].whole = gl_length(g, 0.0, 1.0);
    w->stack[0].depth = 0;
    w->scale = fabs(w->stack[0].whole);
    w->top = 1;
}

/* Next leaf [*a, *b] and its length; 0 when the walk is over. */
static int leaf_walk_next(leaf_walk* w, double* a, double* b, double* len) {
    while (w->top > 0) {
        --w->top;
        const double la = w->stack[w->top].a, lb = w->stack[w->top].b, whole = w->stack[w->top].whole;
        const int depth = w->stack[w->top].depth;
        const double mid = 0.5 * (la + lb);
        const double left = gl_length(w->g, la, mid), right = gl_length(w->g, mid, lb);
        /* A length that overflows (a speed beyond doubles, or inf - inf in the derivative of control
         * points near DBL_MAX) can never pass the test: without the isfinite stop every such segment
         * was split to the full depth, 2^LEAF_DEPTH leaves, only for the sampling to refuse the
         * non-finite total afterwards (found while writing fuzz_import: 600 such segments, 24 s). */
        if (depth >= LEAF_DEPTH || !isfinite(left + right) ||
            fabs(left + right - whole) <= kLeafTolerance * w->scale * (lb - la)) {
            *a = la;
            *b = lb;
            *len = left + right;
            return 1;
        }
        /* Right half below the left one, so the left one comes out first. */
        w->stack[w->top].a = mid;
        w->stack[w->top].b = lb;
        w->stack[w->top].whole = right;
        w->stack[w->top].depth = depth + 1;
        ++w->top;
        w->stack[w->top].a = la;
        w->stack[w->top].b = mid;
        w->stack[w->top].whole = left;
        w->stack[w->top].depth = depth + 1;
        ++w->top;
    }
    return 0;
}

static double mapped_length(const mapped* g) {
    leaf_walk w;
    leaf_walk_init(&w, g);
    double a, b, len, total = 0.0;
    while (leaf_walk_next(&w, &a, &b, &len))
        total += len;
    return total;
}

/* The parameter t in [a, b] where the arc length from the segment's start reaches target, given the
 * length s_a at a: safeguarded Newton on s_a + L(a, t) - target (bisection when a step leaves the
 * bracket or the speed vanishes). */
static double invert_arc_length(const mapped* g, double a, double b, double s_a, double len, double target) {
    double lo = a, hi = b;
    double frac = len > 0.0 ? (target - s_a) / len : 0.5;
    frac = frac < 0.0 ? 0.0 : (frac > 1.0 ? 1.0 : frac);
    double t = a + (b - a) * frac;
    for (int it = 0; it < 200; ++it) {
        const double f = s_a + gl_length(g, a, t) - target;
        if (f == 0.0) break;
        if (f > 0.0)
            hi = t;
        else
            lo = t;
        const double v = mapped_speed(g, t);
        double tn = v > 0.0 ? t - f / v : 0.5 * (lo + hi);
        if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
        const double step = fabs(tn - t);
        t = tn;
        if (step <= 1e-15 || hi - lo <= 1e-15) break;
    }
    return t;
}

/* Signed area of a subpath under m (for choosing the outer boundary): (1/2) ∮ x dy - y dx relative to
 * the start point, each segment by 8-point Gauss-Legendre on four pieces. */
static double subpath_area(const rugo_path* path, const rugo_subpath* sp, const rugo_affine* m) {
    const rugo_vec2 o = rugo_affine_apply(*m, sp->start);
    double area = 0.0;
    for (int k = 0; k < sp->count; ++k) {
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = *m;
        for (int piece = 0; piece < 4; ++piece) {
            const double a = 0.25 * piece, h = 0.125, c = a + h;
            for (int i = 0; i < 8; ++i) {
                const double x = i < 4 ? -kGLx[i] : kGLx[i - 4], w = kGLw[i < 4 ? i : i - 4];
                const double t = c + h * x;
                const rugo_vec2 p = rugo_v2_sub(mapped_point(&g, t), o);
                const rugo_vec2 d0 = segment_derivative(g.s, t);
                const rugo_vec2 d = rugo_v2(m->a * d0.x + m->c * d0.y, m->b * d0.x + m->d * d0.y);
                area += 0.5 * w * h * (p.x * d.y - p.y * d.x);
            }
        }
    }
    return area;
}

/* Closed: ended by Z, or its last point within 1e-9 of its control points' bounds diagonal of its
 * start (path coordinates). */
static int subpath_closed(const rugo_path* path, const rugo_subpath* sp) {
    if (sp->count < 1) return 0;
    if (sp->closed) return 1;
    rugo_vec2 lo = sp->start, hi = sp->start;
    for (int k = 0; k < sp->count; ++k) {
        const rugo_path_segment* s = &path->segments[sp->first + k];
        const int np = s->kind == RUGO_PATH_CUBIC ? 4 : (s->kind == RUGO_PATH_QUADRATIC ? 3 : 2);
        for (int i = 0; i < np; ++i) {
            lo.x = fmin(lo.x, s->p[i].x);
            lo.y = fmin(lo.y, s->p[i].y);
            hi.x = fmax(hi.x, s->p[i].x);
            hi.y = fmax(hi.y, s->p[i].y);
        }
        if (s->kind == RUGO_PATH_ARC) { /* the arc's extent is within centre ± max radius */
            const double r = fmax(s->rx, s->ry);
            lo.x = fmin(lo.x, s->centre.x - r);
            lo.y = fmin(lo.y, s->centre.y - r);
            hi.x = fmax(hi.x, s->centre.x + r);
            hi.y = fmax(hi.y, s->centre.y + r);
        }
    }
    const rugo_vec2 end = segment_end(&path->segments[sp->first + sp->count - 1]);
    const double diag = hypot(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y) * 2.0;
    return hypot(end.x - sp->start.x, end.y - sp->start.y) <= 1e-9 * diag;
}

rugo_outline_sample_def rugo_default_outline_sample_def(void) {
    rugo_outline_sample_def d;
    memset(&d, 0, sizeof d);
    d.path = NULL;
    d.subpath = -1;
    d.transform = rugo_affine_identity();
    d.sample_count = 0;
    d.allocator.alloc = NULL;
    d.allocator.free = NULL;
    d.allocator.ctx = NULL;
    d.cookie = SAMPLE_DEF_COOKIE;
    return d;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static rugo_status
sample_fail(rugo_parse_error* e, rugo_status st, const char* fmt, ...) {
    if (e == NULL) return st;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

/* For the largest-remainder distribution: segment index and fractional share, ordered by share
 * (descending), then index (ascending), so that the order is total and the result deterministic. */
typedef struct share {
    double frac;
    int index;
} share;

static int share_cmp(const void* pa, const void* pb) {
    const share* a = (const share*)pa;
    const share* b = (const share*)pb;
    if (a->frac > b->frac) return -1;
    if (a->frac < b->frac) return 1;
    return (a->index > b->index) - (a->index < b->index);
}

rugo_status rugo_outline_sample(const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (def == NULL || out == NULL)
        return sample_fail(error, RUGO_ERR_NULL_ARGUMENT, "a required argument is NULL");
    if (def->cookie != SAMPLE_DEF_COOKIE)
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "def not from rugo_default_outline_sample_def");
    const rugo_path* path = def->path;
    if (path == NULL) return sample_fail(error, RUGO_ERR_NULL_ARGUMENT, "def->path is NULL");
    if (path->subpath_count < 0 || path->segment_count < 0 ||
        (path->subpath_count > 0 && path->subpaths == NULL) ||
        (path->segment_count > 0 && path->segments == NULL))
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "the path's arrays and counts disagree");
    if (!affine_finite(&def->transform))
        return sample_fail(error, RUGO_ERR_NOT_FINITE, "the transform has a non-finite entry");
    if (def->sample_count < 0 || (def->sample_count > 0 && def->sample_count < 3))
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "sample_count %d: 0 (automatic) or at least 3",
                           def->sample_count);
    if (def->sample_count > RUGO_MAX_CONTROL_POINTS)
        return sample_fail(error, RUGO_ERR_TOO_MANY_POINTS, "sample_count %d beyond %d", def->sample_count,
                           RUGO_MAX_CONTROL_POINTS);
    if (def->subpath < -1 || def->subpath >= path->subpath_count) {
        if (def->subpath == -1 || path->subpath_count == 0)
            return sample_fail(error, RUGO_ERR_BAD_FIELD,
                               "the path has no closed subpath (a closed outline ends with Z)");
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "subpath %d out of range (the path has %d)",
                           def->subpath, path->subpath_count);
    }
    for (int k = 0; k < path->subpath_count; ++k) {
        const rugo_subpath* sp = &path->subpaths[k];
        if (sp->first < 0 || sp->count < 0 || sp->first > path->segment_count - sp->count)
            return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "subpath %d refers to segments beyond the path",
                               k);
    }
    for (int k = 0; k < path->segment_count; ++k) {
        const int kind = (int)path->segments[k].kind;
        if (kind < (int)RUGO_PATH_LINE || kind > (int)RUGO_PATH_ARC)
            return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "segment %d has an unknown kind %d", k, kind);
    }
    const rugo_affine m = def->transform;

    int chosen = def->subpath;
    if (chosen < 0) {
        double best = -1.0;
        for (int k = 0; k < path->subpath_count; ++k) {
            if (!subpath_closed(path, &path->subpaths[k])) continue;
            const double a = fabs(subpath_area(path, &path->subpaths[k], &m));
            if (a > best || (isnan(a) && best < 0.0)) {
                best = isnan(a) ? 0.0 : a;
                chosen = k;
            }
        }
        if (chosen < 0)
            return sample_fail(error, RUGO_ERR_BAD_FIELD,
                               "the path has no closed subpath (a closed outline ends with Z)");
    } else if (!subpath_closed(path, &path->subpaths[chosen])) {
        return sample_fail(error, RUGO_ERR_BAD_FIELD, "subpath %d is %s", chosen,
                           path->subpaths[chosen].count == 0 ? "empty"
                                                             : "open (a closed outline ends with Z)");
    }
    const rugo_subpath* sp = &path->subpaths[chosen];
    const int S = sp->count;
    const rugo_allocator al = rugo__allocator_or_default(&def->allocator);

    double* len = (double*)rugo__alloc_array(&al, (size_t)S, sizeof *len);
    share* shares = (share*)rugo__alloc_array(&al, (size_t)S, sizeof *shares);
    int* extra = (int*)rugo__alloc_array(&al, (size_t)S, sizeof *extra);
    rugo_vec2* pts = NULL;
    rugo_status st = RUGO_OK;
    if (len == NULL || shares == NULL || extra == NULL) {
        st = sample_fail(error, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
        goto done;
    }
    double total = 0.0;
    for (int k = 0; k < S; ++k) {
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = m;
        len[k] = mapped_length(&g);
        total += len[k];
    }
    if (!isfinite(total)) {
        st = sample_fail(error, RUGO_ERR_NOT_FINITE, "the outline's length overflows under the transform");
        goto done;
    }
    if (!(total > 0.0)) {
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d has zero length", chosen);
        goto done;
    }
    /* Segments too short to matter are skipped (their start would be a near-duplicate sample). */
    int kept = 0;
    double kept_total = 0.0;
    for (int k = 0; k < S; ++k) {
        if (len[k] <= 1e-12 * total) {
            len[k] = -1.0;
        } else {
            ++kept;
            kept_total += len[k];
        }
    }
    if (kept > RUGO_MAX_CONTROL_POINTS) {
        st = sample_fail(error, RUGO_ERR_TOO_MANY_POINTS, "subpath %d has %d segments, beyond %d samples",
                         chosen, kept, RUGO_MAX_CONTROL_POINTS);
        goto done;
    }
    int M = def->sample_count;
    if (M == 0) {
        M = RUGO_DEFAULT_OUTLINE_SAMPLES;
        if (kept > M / 4) M = kept > RUGO_MAX_CONTROL_POINTS / 4 ? RUGO_MAX_CONTROL_POINTS : 4 * kept;
    }
    if (M < kept) {
        st = sample_fail(error, RUGO_ERR_BAD_ARGUMENT,
                         "sample_count %d is below the %d segments of subpath %d", M, kept, chosen);
        goto done;
    }

    /* Largest remainders: segment k gets floor(E len_k / L) interior samples, and the E - sum left go
     * one each to the largest fractional parts. */
    {
        const int E = M - kept;
        int given = 0, ns = 0;
        for (int k = 0; k < S; ++k) {
            extra[k] = 0;
            if (len[k] < 0.0) continue;
            const double q = (double)E * (len[k] / kept_total);
            double fl = floor(q);
            if (fl > (double)E) fl = (double)E;
            extra[k] = (int)fl;
            given += extra[k];
            shares[ns].frac = q - fl;
            shares[ns].index = k;
            ++ns;
        }
        if (given > E) { /* only by rounding; take back from the end */
            for (int k = S - 1; k >= 0 && given > E; --k)
                while (extra[k] > 0 && given > E) {
                    --extra[k];
                    --given;
                }
        }
        qsort(shares, (size_t)ns, sizeof *shares, share_cmp);
        for (int i = 0; given < E; i = (i + 1) % ns) {
            ++extra[shares[i].index];
            ++given;
        }
    }

    pts = (rugo_vec2*)rugo__alloc_array(&al, (size_t)M, sizeof *pts);
    if (pts == NULL) {
        st = sample_fail(error, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
        goto done;
    }
    int w = 0;
    for (int k = 0; k < S; ++k) {
        if (len[k] < 0.0) continue;
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = m;
        pts[w++] = mapped_point(&g, 0.0);
        const int e = extra[k];
        if (e == 0) continue;
        /* Targets j len_k / (e + 1), j = 1..e, placed during a second identical walk. */
        leaf_walk lw;
        leaf_walk_init(&lw, &g);
        double a, b, l, s_a = 0.0;
        int j = 1;
        int more = leaf_walk_next(&lw, &a, &b, &l);
        while (more && j <= e) {
            double na, nb, nl;
            const int next = leaf_walk_next(&lw, &na, &nb, &nl);
            const double s_b = s_a + l;
            for (; j <= e; ++j) {
                const double target = len[k] * ((double)j / (double)(e + 1));
                if (target >= s_b && next) break;
                pts[w++] = mapped_point(&g, invert_arc_length(&g, a, b, s_a, l, target));
            }
            s_a = s_b;
            a = na;
            b = nb;
            l = nl;
            more = next;
        }
        RUGO_ASSERT(j == e + 1);
    }
    RUGO_ASSERT(w == M);
    for (int i = 0; i < w; ++i)
        if (!rugo__v2_finite(pts[i])) {
            st = sample_fail(error, RUGO_ERR_NOT_FINITE, "a sample overflows under the transform");
            goto done;
        }
    /* Exact repeats (possible only at round-off scale) would give zero chords. */
    {
        int n = 0;
        for (int i = 0; i < w; ++i)
            if (n == 0 || pts[i].x != pts[n - 1].x || pts[i].y != pts[n - 1].y) pts[n++] = pts[i];
        while (n > 1 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
            --n;
        w = n;
    }
    /* Orientation and area of the sample polygon, in coordinates relative to the first sample and
     * scaled by the bounds (halves first), so that nothing overflows for any finite samples. */
    rugo_vec2 lo = pts[0], hi = pts[0];
    for (int i = 0; i < w; ++i) {
        lo.x = fmin(lo.x, pts[i].x);
        lo.y = fmin(lo.y, pts[i].y);
        hi.x = fmax(hi.x, pts[i].x);
        hi.y = fmax(hi.y, pts[i].y);
    }
    double half = fmax(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y);
    if (!(half > 0.0)) half = 1.0;
    double area2 = 0.0; /* twice the area, in units of (2 half)^2 */
    for (int i = 0; i < w; ++i) {
        const rugo_vec2 a = pts[i], b = pts[i + 1 < w ? i + 1 : 0];
        const double px = (0.5 * a.x - 0.5 * pts[0].x) / half, py = (0.5 * a.y - 0.5 * pts[0].y) / half;
        const double qx = (0.5 * b.x - 0.5 * pts[0].x) / half, qy = (0.5 * b.y - 0.5 * pts[0].y) / half;
        area2 += px * qy - py * qx;
    }
    const double diag_n = hypot(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y) / half; /* <= sqrt(2) */
    if (w < 3 || !(fabs(0.5 * area2) > 1e-12 * diag_n * diag_n)) {
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d encloses no area (under the transform)",
                         chosen);
        goto done;
    }
    const double area = 0.5 * fabs(area2) * (2.0 * half) * (2.0 * half);
    if (!isfinite(area)) {
        st = sample_fail(error, RUGO_ERR_NOT_FINITE, "the outline's area overflows under the transform");
        goto done;
    }
    if (!(area > 0.0)) { /* a shape, but so small that its area underflows (e.g. 1e-300 across) */
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d: its area underflows (under the transform)",
                         chosen);
        goto done;
    }
    int reversed = 0;
    if (area2 < 0.0) {
        for (int i = 1, k = w - 1; i < k; ++i, --k) {
            rugo_vec2 t = pts[i];
            pts[i] = pts[k];
            pts[k] = t;
        }
        reversed = 1;
    }
    out->points = pts;
    pts = NULL;
    out->count = w;
    out->perimeter = total;
    out->area = area;
    out->subpath = chosen;
    out->segment_count = kept;
    out->reversed = reversed;
    out->allocator = al;
done:
    rugo__free(&al, len);
    rugo__free(&al, shares);
    rugo__free(&al, extra);
    rugo__free(&al, pts);
    return st;
}

void rugo_outline_samples_free(rugo_outline_samples* samples) {
    if (samples == NULL) return;
    rugo__free(&samples->allocator, samples->points);
    memset(samples, 0, sizeof *samples);
}

/* ---- SVG documents ------------------------------------------------------------------------------------ */

/* Position of the first occurrence of the NUL-terminated needle in text[from, length), or length. */
static size_t find_seq(const char* text, size_t from, size_t length, const char* needle) {
    const size_t n = strlen(needle);
    while (from + n <= length) {
        const char* c = (const char*)memchr(text + from, needle[0], length - from - n + 1);
        if (c == NULL) return length;
        size_t at = (size_t)(c - text);
        if (memcmp(c, needle, n) == 0) return at;
        from = at + 1;
    }
    return length;
}

static int starts_with(const char* text, size_t at, size_t length, const char* s) {
    const size_t n = strlen(s);
    return at + n <= length && memcmp(text + at, s, n) == 0;
}

/* UTF-8 bytes of code point cp into out; returns the count. */
static size_t utf8_encode(unsigned long cp, char* out) {
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6));
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12));
        out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18));
    out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* Decodes the entities of an attribute value raw[0, n) into out (room for n + 1 bytes: decoding never
 * lengthens). On a bad entity returns its offset in raw via *bad and 0; 1 on success. */
static int decode_attribute(const char* raw, size_t n, char* out, size_t* out_len, size_t* bad) {
    static const struct {
        const char* name;
        char c;
    } named[] = {{"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
    size_t w = 0;
    for (size_t i = 0; i < n;) {
        if (raw[i] != '&') {
            out[w++] = raw[i++];
            continue;
        }
        size_t semi = i + 1;
        while (semi < n && semi - i <= 12 && raw[semi] != ';')
            ++semi;
        if (semi >= n || raw[semi] != ';') {
            *bad = i;
            return 0;
        }
        const char* name = raw + i + 1;
        const size_t nl = semi - i - 1;
        int done = 0;
        for (size_t k = 0; k < sizeof named / sizeof named[0] && !done; ++k)
            if (strlen(named[k].name) == nl && memcmp(named[k].name, name, nl) == 0) {
                out[w++] = named[k].c;
                done = 1;
            }
        if (!done && nl >= 2 && name[0] == '#') {
            unsigned long cp = 0;
            const int hex = name[1] == 'x';
            size_t k = hex ? 2 : 1;
            if (k >= nl) {
                *bad = i;
                return 0;
            }
            for (; k < nl; ++k) {
                const char c = name[k];
                unsigned d;
                if (is_digit(c))
                    d = (unsigned)(c - '0');
                else if (hex && c >= 'a' && c <= 'f')
                    d = (unsigned)(c - 'a' + 10);
                else if (hex && c >= 'A' && c <= 'F')
                    d = (unsigned)(c - 'A' + 10);
                else {
                    *bad = i;
                    return 0;
                }
                cp = cp * (hex ? 16u : 10u) + d;
                if (cp > 0x10FFFF) {
                    *bad = i;
                    return 0;
                }
            }
            if (cp == 0 || (cp >= 0xD800 && cp <= 0xDFFF)) {
                *bad = i;
                return 0;
            }
            w += utf8_encode(cp, out + w);
            done = 1;
        }
        if (!done) {
            *bad = i;
            return 0;
        }
        i = semi + 1;
    }
    out[w] = '\0';
    *out_len = w;
    return 1;
}

/* An attribute value's raw extent in the document. */
typedef struct attr_span {
    size_t off, len;
    int present;
} attr_span;

/* An open element on the scan's stack. */
typedef struct open_element {
    size_t name_off, name_len;
    size_t tag_off;
    attr_span id, transform;
} open_element;

typedef struct doc_scan {
    const char* text;
    size_t length;
    rugo_allocator al;
    rugo_parse_error* err;
} doc_scan;

#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
static rugo_status
doc_fail(const doc_scan* d, rugo_status st, size_t offset, const char* path, const char* fmt, ...) {
    rugo_parse_error* e = d->err;
    if (e == NULL) return st;
    rugo__json_locate(d->text, d->length, offset, &e->line, &e->column);
    snprintf(e->path, sizeof e->path, "%s", path != NULL ? path : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

/* "g#layer1/transform" or "g/transform" for messages (name and id shortened to fit). */
static void element_label(const doc_scan* d, const open_element* el, const char* attr, char* out,
                          size_t size) {
    char name[32], id[40];
    rugo__json_quote_for_message(d->text + el->name_off, el->name_len, name, sizeof name);
    if (el->id.present) {
        rugo__json_quote_for_message(d->text + el->id.off, el->id.len, id, sizeof id);
        snprintf(out, size, "%s#%s/%s", name, id, attr);
    } else {
        snprintf(out, size, "%s/%s", name, attr);
    }
}

/* Decodes an attribute into a new NUL-terminated buffer (*out, *out_len). */
static rugo_status decode_span(const doc_scan* d, const attr_span* a, const char* label, char** out,
                               size_t* out_len) {
    char* buf = (char*)rugo__alloc_array(&d->al, a->len + 1, 1);
    if (buf == NULL) return doc_fail(d, RUGO_ERR_OUT_OF_MEMORY, a->off, label, "out of memory");
    size_t bad = 0;
    if (!decode_attribute(d->text + a->off, a->len, buf, out_len, &bad)) {
        rugo__free(&d->al, buf);
        return doc_fail(
            d, RUGO_ERR_PARSE, a->off + bad, label,
            "unknown or malformed entity (only &lt; &gt; &amp; &quot; &apos; and &#...; are read)");
    }
    *out = buf;
    return RUGO_OK;
}

/* The transform attribute of el composed into *m (m = m * T_el). */
static rugo_status apply_element_transform(const doc_scan* d, const open_element* el, rugo_affine* m) {
    if (!el->transform.present) return RUGO_OK;
    char label[96];
    element_label(d, el, "transform", label, sizeof label);
    char* buf = NULL;
    size_t n = 0;
    rugo_status st = decode_span(d, &el->transform, label, &buf, &n);
    if (st != RUGO_OK) return st;
    scanner sc;
    sc.text = buf;
    sc.p = buf;
    sc.end = buf + n;
    sc.loc.doc = d->text;
    sc.loc.doc_length = d->length;
    sc.loc.base = el->transform.off;
    sc.loc.exact = n == el->transform.len;
    sc.loc.path = label;
    sc.err = d->err;
    rugo_affine t;
    st = parse_transform_list(&sc, &t);
    rugo__free(&d->al, buf);
    if (st != RUGO_OK) return st;
    *m = rugo_affine_multiply(*m, t);
    if (!affine_finite(m))
        return doc_fail(d, RUGO_ERR_NOT_FINITE, el->transform.off, label, "the composed transform overflows");
    return RUGO_OK;
}

/* 1 if the attribute's decoded value equals s. */
static int attribute_equals(const doc_scan* d, const attr_span* a, const char* s, rugo_status* st) {
    const size_t n = strlen(s);
    const char* raw = d->text + a->off;
    if (memchr(raw, '&', a->len) == NULL) return a->len == n && memcmp(raw, s, n) == 0;
    char* buf = NULL;
    size_t len = 0;
    *st = decode_span(d, a, "id", &buf, &len);
    if (*st != RUGO_OK) return 0;
    const int eq = len == n && memcmp(buf, s, n) == 0;
    rugo__free(&d->al, buf);
    return eq;
}

static int local_name_is(const char* name, size_t len, const char* want) {
    const char* colon = NULL;
    for (size_t i = 0; i < len; ++i)
        if (name[i] == ':') colon = name + i;
    const char* local = colon != NULL ? colon + 1 : name;
    const size_t ll = len - (size_t)(local - name);
    return ll == strlen(want) && memcmp(local, want, ll) == 0;
}

static int is_name_char(char c) {
    return !is_wsp(c) && c != '>' && c != '/' && c != '=' && c != '"' && c != '\'' && c != '<';
}

rugo_status rugo_svg_find_path(const char* text, size_t length, const char* id,
                               const rugo_allocator* allocator, rugo_svg_path_element* out,
                               rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
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
    doc_scan d;
    d.text = text;
    d.length = length;
    d.al = rugo__allocator_or_default(allocator);
    d.err = error;
    open_element* stack = (open_element*)rugo__alloc_array(&d.al, RUGO_SVG_MAX_DEPTH, sizeof *stack);
    if (stack == NULL) return doc_fail(&d, RUGO_ERR_OUT_OF_MEMORY, 0, "", "out of memory");
    int depth = 0;
    rugo_svg_path_element found;
    memset(&found, 0, sizeof found);
    int nfound = 0;
    rugo_status st = RUGO_OK;
    char buf[16];
    size_t p = 0;
    if (length >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        p = 3;
    int done = 0;
    while (!done && st == RUGO_OK) {
        const char* lt = p < length ? (const char*)memchr(text + p, '<', length - p) : NULL;
        if (lt == NULL) break;
        const size_t at = (size_t)(lt - text);
        if (starts_with(text, at, length, "<!--")) {
            const size_t e = find_seq(text, at + 4, length, "-->");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated comment");
                break;
            }
            p = e + 3;
            continue;
        }
        if (starts_with(text, at, length, "<![CDATA[")) {
            const size_t e = find_seq(text, at + 9, length, "]]>");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated CDATA section");
                break;
            }
            p = e + 3;
            continue;
        }
        if (starts_with(text, at, length, "<?")) {
            const size_t e = find_seq(text, at + 2, length, "?>");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated processing instruction");
                break;
            }
            p = e + 2;
            continue;
        }
        if (starts_with(text, at, length, "<!")) {
            /* A DOCTYPE or other declaration: up to the '>' outside quotes and the internal subset. */
            size_t q = at + 2;
            int bracket = 0;
            char quote = 0;
            for (; q < length; ++q) {
                const char c = text[q];
                if (quote) {
                    if (c == quote) quote = 0;
                } else if (c == '"' || c == '\'') {
                    quote = c;
                } else if (c == '[') {
                    ++bracket;
                } else if (c == ']') {
                    if (bracket > 0) --bracket;
                } else if (c == '>' && bracket == 0) {
                    break;
                }
            }
            if (q >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated declaration");
                break;
            }
            p = q + 1;
            continue;
        }
        if (starts_with(text, at, length, "</")) {
            size_t q = at + 2;
            const size_t name = q;
            while (q < length && is_name_char(text[q]))
                ++q;
            const size_t nlen = q - name;
            while (q < length && is_wsp(text[q]))
                ++q;
            if (nlen == 0 || q >= length || text[q] != '>') {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "malformed end tag");
                break;
            }
            if (depth == 0) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "end tag without a matching start tag");
                break;
            }
            const open_element* top = &stack[depth - 1];
            if (top->name_len != nlen || memcmp(text + top->name_off, text + name, nlen) != 0) {
                char want[40], got[40];
                rugo__json_quote_for_message(text + top->name_off, top->name_len, want, sizeof want);
                rugo__json_quote_for_message(text + name, nlen, got, sizeof got);
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "end tag </%s> does not match <%s>", got, want);
                break;
            }
            --depth;
            p = q + 1;
            continue;
        }
        /* A start tag. */
        open_element el;
        memset(&el, 0, sizeof el);
        el.tag_off = at;
        size_t q = at + 1;
        el.name_off = q;
        while (q < length && is_name_char(text[q]))
            ++q;
        el.name_len = q - el.name_off;
        if (el.name_len == 0) {
            st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "expected an element name after '<', found %s",
                          describe(text + q, text + length, buf, sizeof buf));
            break;
        }
        attr_span dspan;
        memset(&dspan, 0, sizeof dspan);
        int self_closing = 0;
        while (st == RUGO_OK) {
            while (q < length && is_wsp(text[q]))
                ++q;
            if (q >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated tag");
                break;
            }
            if (text[q] == '>') {
                ++q;
                break;
            }
            if (text[q] == '/') {
                if (q + 1 < length && text[q + 1] == '>') {
                    q += 2;
                    self_closing = 1;
                    break;
                }
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected '>' after '/'");
                break;
            }
            const size_t an = q;
            while (q < length && is_name_char(text[q]))
                ++q;
            const size_t alen = q - an;
            if (alen == 0) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected an attribute name, found %s",
                              describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            while (q < length && is_wsp(text[q]))
                ++q;
            if (q >= length || text[q] != '=') {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected '=' after an attribute name, found %s",
                              describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            ++q;
            while (q < length && is_wsp(text[q]))
                ++q;
            if (q >= length || (text[q] != '"' && text[q] != '\'')) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected a quoted attribute value, found %s",
                              describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            const char quote = text[q];
            const size_t vstart = q + 1;
            size_t v = vstart;
            while (v < length && text[v] != quote && text[v] != '<')
                ++v;
            if (v >= length || text[v] != quote) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "unterminated attribute value");
                break;
            }
            attr_span span;
            span.off = vstart;
            span.len = v - vstart;
            span.present = 1;
            attr_span* slot = NULL;
            if (alen == 2 && memcmp(text + an, "id", 2) == 0)
                slot = &el.id;
            else if (alen == 9 && memcmp(text + an, "transform", 9) == 0)
                slot = &el.transform;
            else if (alen == 1 && text[an] == 'd')
                slot = &dspan;
            if (slot != NULL) {
                if (slot->present) {
                    char name[16];
                    rugo__json_quote_for_message(text + an, alen, name, sizeof name);
                    st = doc_fail(&d, RUGO_ERR_PARSE, an, "", "attribute %s given twice", name);
                    break;
                }
                *slot = span;
            }
            q = v + 1;
        }
        if (st != RUGO_OK) break;
        const int is_path = local_name_is(text + el.name_off, el.name_len, "path");
        int target = 0;
        if (id != NULL) {
            if (el.id.present) target = attribute_equals(&d, &el.id, id, &st);
            if (st != RUGO_OK) break;
        } else {
            target = is_path;
        }
        if (target) {
            char label[96];
            element_label(&d, &el, "d", label, sizeof label);
            if (!is_path) {
                char name[32], shown[40];
                rugo__json_quote_for_message(text + el.name_off, el.name_len, name, sizeof name);
                rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, "", "the element with id '%s' is <%s>, not <path>",
                              shown, name);
                break;
            }
            if (!dspan.present) {
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, label, "the <path> has no d attribute");
                break;
            }
            if (nfound > 0) {
                int line = 0, col = 0;
                rugo__json_locate(text, length, found.d_offset, &line, &col);
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, "",
                              "the document has more than one <path> (another at line %d): choose one by id",
                              line);
                break;
            }
            rugo_affine m = rugo_affine_identity();
            for (int k = 0; k < depth && st == RUGO_OK; ++k)
                st = apply_element_transform(&d, &stack[k], &m);
            if (st == RUGO_OK) st = apply_element_transform(&d, &el, &m);
            if (st != RUGO_OK) break;
            size_t dlen = 0;
            st = decode_span(&d, &dspan, label, &found.d, &dlen);
            if (st != RUGO_OK) break;
            found.d_length = dlen;
            found.d_offset = dspan.off;
            found.d_has_entities = dlen != dspan.len;
            found.transform = m;
            rugo__json_locate(text, length, at, &found.line, &found.column);
            found.allocator = d.al;
            ++nfound;
            if (id != NULL) done = 1; /* the first element with the id wins; the rest is not read */
        }
        if (!self_closing && !done) {
            if (depth >= RUGO_SVG_MAX_DEPTH) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "elements nested deeper than %d",
                              RUGO_SVG_MAX_DEPTH);
                break;
            }
            stack[depth++] = el;
        }
        p = q;
    }
    rugo__free(&d.al, stack);
    if (st == RUGO_OK && nfound == 0) {
        if (id != NULL) {
            char shown[64];
            rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
            st = doc_fail(&d, RUGO_ERR_BAD_FIELD, length, "", "no element with id '%s'", shown);
        } else {
            st = doc_fail(&d, RUGO_ERR_BAD_FIELD, length, "", "the document has no <path> element");
        }
        if (error != NULL) error->line = error->column = 0;
    }
    if (st != RUGO_OK) {
        rugo_svg_path_element_free(&found);
        return st;
    }
    *out = found;
    return RUGO_OK;
}

void rugo_svg_path_element_free(rugo_svg_path_element* element) {
    if (element == NULL) return;
    rugo__free(&element->allocator, element->d);
    memset(element, 0, sizeof *element);
}

rugo_status rugo_svg_import_outline(const char* text, size_t length, const char* id,
                                    const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                    rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || def == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (def->cookie != SAMPLE_DEF_COOKIE) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "def not from rugo_default_outline_sample_def");
        return RUGO_ERR_BAD_ARGUMENT;
    }
    rugo_svg_path_element el;
    rugo_status st = rugo_svg_find_path(text, length, id, &def->allocator, &el, error);
    if (st != RUGO_OK) return st;
    char label[96];
    if (id != NULL) {
        char shown[64];
        rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
        snprintf(label, sizeof label, "path#%s/d", shown);
    } else {
        snprintf(label, sizeof label, "path/d");
    }
    locator loc;
    loc.doc = text;
    loc.doc_length = length;
    loc.base = el.d_offset;
    loc.exact = !el.d_has_entities;
    loc.path = label;
    rugo_path path;
    memset(&path, 0, sizeof path);
    st = path_parse_located(el.d, el.d_length, &def->allocator, &path, error, &loc);
    if (st == RUGO_OK) {
        rugo_outline_sample_def sd = *def;
        sd.path = &path;
        const rugo_affine flip = affine_make(1.0, 0.0, 0.0, -1.0, 0.0, 0.0);
        sd.transform = rugo_affine_multiply(def->transform, rugo_affine_multiply(flip, el.transform));
        if (!affine_finite(&sd.transform)) {
            st = RUGO_ERR_NOT_FINITE;
            if (error != NULL)
                snprintf(error->message, sizeof error->message, "the composed transform overflows");
        } else {
            st = rugo_outline_sample(&sd, out, error);
        }
        if (st != RUGO_OK && error != NULL) {
            /* Sampling errors concern the path as a whole: point at its d attribute. */
            rugo__json_locate(text, length, el.d_offset, &error->line, &error->column);
            snprintf(error->path, sizeof error->path, "%s", label);
        }
    }
    rugo_path_free(&path);
    rugo_svg_path_element_free(&el);
    return st;
}

/* ---- point lists ----------------------------------------------------------------------------------- */

rugo_status rugo_points_text_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                   rugo_vec2** points, int* count, rugo_parse_error* error) {
    clear_error(error);
    if (points != NULL) *points = NULL;
    if (count != NULL) *count = 0;
    if (text == NULL || points == NULL || count == NULL) {
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
    while (first < length && is_wsp(text[first]))
        ++first;
    if (first < length && text[first] == '{')
        return rugo_points_parse(text, length, "points", allocator, points, count, error);

    const rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo__array pts = {NULL, 0}; /* rugo_vec2 */
    int n = 0;
    int seen_line = 0;
    scanner sc;
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
        while (q < eol && is_wsp(text[q]))
            ++q;
        const size_t line_start = p;
        p = eol + 1;
        if (q >= eol || text[q] == '#') continue;
        if (!seen_line) {
            seen_line = 1;
            int digits = 0;
            for (size_t k = q; k < eol && !digits; ++k)
                digits = is_digit(text[k]);
            if (!digits) continue; /* a CSV header such as "x,y" */
        }
        (void)line_start;
        sc.p = text + q;
        sc.end = text + eol;
        double v[2];
        st = read_number(&sc, &v[0], "a number (x)");
        if (st != RUGO_OK) break;
        const char* before = sc.p;
        skip_wsp(&sc);
        if (sc.p < sc.end && (*sc.p == ',' || *sc.p == ';')) {
            ++sc.p;
            skip_wsp(&sc);
        } else if (sc.p == before) {
            st = fail_at(error, RUGO_ERR_PARSE, &sc.loc, sc_offset(&sc, sc.p),
                         "expected a separator (',', ';' or blanks) after x, found %s",
                         describe(sc.p, sc.end, buf, sizeof buf));
            break;
        }
        st = read_number(&sc, &v[1], "a number (y)");
        if (st != RUGO_OK) break;
        skip_wsp(&sc);
        if (sc.p < sc.end) {
            st = fail_at(error, RUGO_ERR_PARSE, &sc.loc, sc_offset(&sc, sc.p),
                         "expected two numbers per line, found %s after them",
                         describe(sc.p, sc.end, buf, sizeof buf));
            break;
        }
        if (n >= RUGO_MAX_CONTROL_POINTS) {
            st = fail_at(error, RUGO_ERR_TOO_MANY_POINTS, &sc.loc, q, "more than %d points",
                         RUGO_MAX_CONTROL_POINTS);
            break;
        }
        if (grow(&al, &pts, n, sizeof(rugo_vec2)) != 0) {
            st = fail_at(error, RUGO_ERR_OUT_OF_MEMORY, &sc.loc, q, "out of memory");
            break;
        }
        ((rugo_vec2*)pts.data)[n++] = rugo_v2(v[0], v[1]);
    }
    if (st != RUGO_OK) {
        rugo__array_free(&pts, &al);
        return st;
    }
    *points = (rugo_vec2*)pts.data;
    *count = n;
    return RUGO_OK;
}
