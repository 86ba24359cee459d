/* SVG path data (the d attribute: every command, implicit repetitions, arcs as SVG defines them) into a
 * rugo_path of subpaths and segments, and a closed path from a polygon's points. */
#include "io/svg_internal.h"

#include "core/array.h"
#include "core/internal.h"
#include "curve/internal.h" /* rugo__path_segment_end */

#include <stdio.h>
#include <string.h>

/* Room for one more element after `count` in a (room for 16 first, then doubling). 0 on success, -1
 * out of memory. */
static int grow(const rugo_allocator* al, rugo__array* a, int count, size_t elem) {
    return rugo__array_reserve(a, al, (size_t)count + 1, elem, 16) == RUGO_OK ? 0 : -1;
}

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
    rugo__svg_cos_sin_deg(phi_deg, &cphi, &sphi);
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
    if (!sweep && dtheta > 0.0) dtheta -= 2.0 * RUGO__SVG_PI;
    if (sweep && dtheta < 0.0) dtheta += 2.0 * RUGO__SVG_PI;
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
    s->phi = fmod(phi_deg, 360.0) * (RUGO__SVG_PI / 180.0);
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

static rugo_status begin_subpath(path_state* ps, rugo__svg_scanner* sc, size_t at, rugo_vec2 start) {
    if (ps->b.nsub >= RUGO_MAX_PATH_SEGMENTS)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_TOO_LARGE, &sc->loc, at, "more than %d subpaths",
                                 RUGO_MAX_PATH_SEGMENTS);
    if (grow(&ps->b.al, &ps->b.sub, ps->b.nsub, sizeof(rugo_subpath)) != 0)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_OUT_OF_MEMORY, &sc->loc, at, "out of memory");
    rugo_subpath* s = &builder_subpaths(&ps->b)[ps->b.nsub++];
    s->first = ps->b.nseg;
    s->count = 0;
    s->start = start;
    s->closed = false;
    ps->in_subpath = 1;
    return RUGO_OK;
}

static rugo_status add_segment(path_state* ps, rugo__svg_scanner* sc, size_t at, rugo_path_segment* s) {
    s->offset = at;
    if (!segment_finite(s))
        return rugo__svg_fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
                                 "coordinates overflow (beyond the range of a double)");
    if (ps->b.nseg >= RUGO_MAX_PATH_SEGMENTS)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_TOO_LARGE, &sc->loc, at, "more than %d segments",
                                 RUGO_MAX_PATH_SEGMENTS);
    if (grow(&ps->b.al, &ps->b.seg, ps->b.nseg, sizeof(rugo_path_segment)) != 0)
        return rugo__svg_fail_at(sc->err, RUGO_ERR_OUT_OF_MEMORY, &sc->loc, at, "out of memory");
    builder_segments(&ps->b)[ps->b.nseg++] = *s;
    builder_subpaths(&ps->b)[ps->b.nsub - 1].count++;
    ps->cur = rugo__path_segment_end(s);
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
static rugo_status apply_command(path_state* ps, rugo__svg_scanner* sc, size_t at, char c, const double* v) {
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
            return rugo__svg_fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
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
            return rugo__svg_fail_at(sc->err, RUGO_ERR_NOT_FINITE, &sc->loc, at,
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

static rugo_status close_subpath(path_state* ps, rugo__svg_scanner* sc, size_t at) {
    if (!ps->in_subpath) {
        rugo_status st = begin_subpath(ps, sc, at, ps->start);
        if (st != RUGO_OK) return st;
    }
    if (ps->cur.x != ps->start.x || ps->cur.y != ps->start.y) {
        rugo_path_segment s = line_segment(ps->cur, ps->start);
        rugo_status st = add_segment(ps, sc, at, &s);
        if (st != RUGO_OK) return st;
    }
    builder_subpaths(&ps->b)[ps->b.nsub - 1].closed = true;
    ps->cur = ps->start;
    ps->in_subpath = 0;
    ps->prev = 0;
    return RUGO_OK;
}

static rugo_status parse_path_data(rugo__svg_scanner* sc, const rugo_allocator* allocator, rugo_path* out) {
    path_state ps;
    memset(&ps, 0, sizeof ps);
    ps.b.al = rugo__allocator_or_default(allocator);
    char buf[16];
    char cmd = 0;
    rugo_status st = RUGO_OK;
    rugo__svg_skip_wsp(sc);
    while (sc->p < sc->end) {
        const char* at = sc->p;
        const char ch = *sc->p;
        if (command_arity(ch) >= 0) {
            if (cmd == 0 && ch != 'M' && ch != 'm') {
                st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, at),
                                       "path data must start with a moveto (M or m), found '%c'", ch);
                break;
            }
            cmd = ch;
            ++sc->p;
            if (cmd == 'Z' || cmd == 'z') {
                st = close_subpath(&ps, sc, rugo__svg_offset(sc, at));
                if (st != RUGO_OK) break;
                rugo__svg_skip_wsp(sc);
                continue;
            }
            rugo__svg_skip_wsp(sc);
        } else if (rugo__svg_starts_number(ch)) {
            if (cmd == 0) {
                st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, at),
                                       "path data must start with a moveto (M or m), found a number");
                break;
            }
            if (cmd == 'Z' || cmd == 'z') {
                st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, at),
                                       "'%c' takes no numbers: expected a command letter", cmd);
                break;
            }
            /* An implicit repetition of cmd (M's further pairs are lineto, set below). */
        } else if (ch == ',') {
            st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, at),
                                   "unexpected ','");
            break;
        } else {
            st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, at),
                                   "unknown path command %s",
                                   rugo__svg_describe(at, sc->end, buf, sizeof buf));
            break;
        }
        const int n = command_arity(cmd);
        double v[7];
        for (int i = 0; i < n && st == RUGO_OK; ++i) {
            if (i > 0) (void)rugo__svg_skip_comma_wsp(sc);
            if ((cmd == 'A' || cmd == 'a') && (i == 3 || i == 4)) {
                /* Flags are single characters; "a1 1 0 00 1 1" has them without separators. */
                if (sc->p < sc->end && (*sc->p == '0' || *sc->p == '1')) {
                    v[i] = *sc->p == '1' ? 1.0 : 0.0;
                    ++sc->p;
                } else {
                    st = rugo__svg_fail_at(
                        sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, sc->p),
                        "'%c' needs 7 numbers: argument %d is the %s flag and must be 0 or 1, found %s", cmd,
                        i + 1, i == 3 ? "large-arc" : "sweep",
                        rugo__svg_describe(sc->p, sc->end, buf, sizeof buf));
                }
            } else {
                char what[64];
                snprintf(what, sizeof what, "a number (argument %d of the %d of '%c')", i + 1, n, cmd);
                st = rugo__svg_read_number(sc, &v[i], what);
            }
        }
        if (st != RUGO_OK) break;
        st = apply_command(&ps, sc, rugo__svg_offset(sc, at), cmd, v);
        if (st != RUGO_OK) break;
        if (cmd == 'M') cmd = 'L';
        if (cmd == 'm') cmd = 'l';
        const char* before = sc->p;
        if (rugo__svg_skip_comma_wsp(sc) && !(sc->p < sc->end && rugo__svg_starts_number(*sc->p))) {
            st = rugo__svg_fail_at(sc->err, RUGO_ERR_PARSE, &sc->loc, rugo__svg_offset(sc, before),
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

rugo_status rugo__svg_path_parse_located(const char* d, size_t length, const rugo_allocator* allocator,
                                         rugo_path* out, rugo_parse_error* error,
                                         const rugo__svg_locator* loc) {
    rugo__svg_scanner sc;
    sc.text = d;
    sc.p = d;
    sc.end = d + length;
    sc.loc = *loc;
    sc.err = error;
    return parse_path_data(&sc, allocator, out);
}

rugo_status rugo_path_parse(const char* d, size_t length, const rugo_allocator* allocator, rugo_path* out,
                            rugo_parse_error* error) {
    rugo__svg_clear_error(error);
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
    rugo__svg_locator loc;
    loc.doc = d;
    loc.doc_length = length;
    loc.base = 0;
    loc.exact = 1;
    loc.path = "d";
    return rugo__svg_path_parse_located(d, length, allocator, out, error, &loc);
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
    sub->closed = true;
    out->segments = seg;
    out->segment_count = n;
    out->subpaths = sub;
    out->subpath_count = 1;
    out->allocator = al;
    return RUGO_OK;
}
