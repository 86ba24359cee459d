/* Suite "import": SVG path data, transforms and documents, outline sampling and point lists
 * (rugo/import.h); with the Eigen shim also the outline fit (rugo_fit_outline, rugo/fit.h).
 *
 * Golden numbers: the rock of tests/data/rock_inkscape.svg and the circles below were cross-checked
 * once by an independent Python script (xml.etree for the document, its own parser for the path data,
 * composite 8-point Gauss-Legendre arc length with 256 pieces per segment, a dense least-squares
 * solve, and closest points by a local grid and golden-section search): its samples matched these to
 * 7e-12, its control points to 3e-12 and its errors to 3e-13 (rock) and 2e-14 (circle); see each test. */
#include "rugo/import.h"
#ifdef RUGO_HAVE_FIT
#include "rugo/fit.h"
#endif
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static void data_path(const char* name, char* out, size_t size) {
    const char* file = __FILE__;
    const char* slash = strrchr(file, '/');
    int dir = slash != NULL ? (int)(slash - file + 1) : 0;
    snprintf(out, size, "%.*sdata/%s", dir, file, name);
}

static char* read_data(const char* name, size_t* length) {
    char path[1024];
    data_path(name, path, sizeof path);
    rugo_text text;
    rugo_status st = rugo_read_file(path, NULL, &text);
    ck_assert_msg(st == RUGO_OK, "%s: %s", path, rugo_status_string(st));
    *length = text.length;
    return text.data; /* the default allocator's: free() */
}

static void parse_ok(const char* d, rugo_path* p) {
    rugo_parse_error e;
    rugo_status st = rugo_path_parse(d, strlen(d), NULL, p, &e);
    ck_assert_msg(st == RUGO_OK, "<%s>: status %d, %d:%d %s", d, st, e.line, e.column, e.message);
}

/* Parsing d fails with `status` at `column` (0: do not check) with `fragment` in the message. */
static void parse_fails(const char* d, rugo_status status, int column, const char* fragment) {
    rugo_path p;
    rugo_parse_error e;
    rugo_status st = rugo_path_parse(d, strlen(d), NULL, &p, &e);
    ck_assert_msg(st == status, "<%s>: status %d (%s), expected %d; %s", d, st, rugo_status_string(st),
                  status, e.message);
    ck_assert_ptr_null(p.segments);
    ck_assert_int_eq(p.segment_count, 0);
    ck_assert_ptr_null(p.subpaths);
    ck_assert_str_eq(e.path, "d");
    if (column > 0) ck_assert_int_eq(e.line, 1);
    if (column > 0)
        ck_assert_msg(e.column == column, "<%s>: column %d, expected %d (%s)", d, e.column, column,
                      e.message);
    if (fragment != NULL)
        ck_assert_msg(strstr(e.message, fragment) != NULL, "<%s>: message \"%s\" lacks \"%s\"", d, e.message,
                      fragment);
}

#define ck_assert_vec_near(v, X, Y, tol)                                                                     \
    do {                                                                                                     \
        rugo_vec2 ck_v_ = (v);                                                                               \
        ck_assert_near(ck_v_.x, (X), (tol));                                                                 \
        ck_assert_near(ck_v_.y, (Y), (tol));                                                                 \
    } while (0)

static rugo_vec2 seg_point(const rugo_path* p, int k, double t) {
    return rugo_path_segment_point(&p->segments[k], t);
}

/* ---- path data: every command -------------------------------------------------------------------- */

/* One path using every absolute command; each segment's points against hand-computed values. */
START_TEST(absolute_commands) {
    rugo_path p;
    parse_ok("M 10 20 L 30 40 H 50 V 60 C 50 70 40 80 30 80 S 10 70 10 60 Q 10 50 20 50 T 30 40 "
             "A 5 5 0 0 1 30 30 Z",
             &p);
    ck_assert_int_eq(p.subpath_count, 1);
    ck_assert_int_eq(p.subpaths[0].first, 0);
    ck_assert_int_eq(p.subpaths[0].count, 9);
    ck_assert(p.subpaths[0].closed);
    ck_assert_vec_near(p.subpaths[0].start, 10, 20, 0);
    ck_assert_int_eq(p.segment_count, 9);
    const rugo_path_segment* s = p.segments;
    ck_assert_int_eq(s[0].kind, RUGO_PATH_LINE);
    ck_assert_vec_near(s[0].p[0], 10, 20, 0);
    ck_assert_vec_near(s[0].p[1], 30, 40, 0);
    ck_assert_int_eq(s[1].kind, RUGO_PATH_LINE); /* H keeps y */
    ck_assert_vec_near(s[1].p[1], 50, 40, 0);
    ck_assert_int_eq(s[2].kind, RUGO_PATH_LINE); /* V keeps x */
    ck_assert_vec_near(s[2].p[1], 50, 60, 0);
    ck_assert_int_eq(s[3].kind, RUGO_PATH_CUBIC);
    ck_assert_vec_near(s[3].p[0], 50, 60, 0);
    ck_assert_vec_near(s[3].p[1], 50, 70, 0);
    ck_assert_vec_near(s[3].p[2], 40, 80, 0);
    ck_assert_vec_near(s[3].p[3], 30, 80, 0);
    /* S: first control = (40, 80) reflected about (30, 80) = (20, 80). */
    ck_assert_int_eq(s[4].kind, RUGO_PATH_CUBIC);
    ck_assert_vec_near(s[4].p[1], 20, 80, 0);
    ck_assert_vec_near(s[4].p[2], 10, 70, 0);
    ck_assert_vec_near(s[4].p[3], 10, 60, 0);
    ck_assert_int_eq(s[5].kind, RUGO_PATH_QUADRATIC);
    ck_assert_vec_near(s[5].p[1], 10, 50, 0);
    ck_assert_vec_near(s[5].p[2], 20, 50, 0);
    /* T: control = (10, 50) reflected about (20, 50) = (30, 50). */
    ck_assert_int_eq(s[6].kind, RUGO_PATH_QUADRATIC);
    ck_assert_vec_near(s[6].p[1], 30, 50, 0);
    ck_assert_vec_near(s[6].p[2], 30, 40, 0);
    /* A from (30, 40) to (30, 30), r = 5: the chord is a diameter, centre (30, 35), half circle. Sweep
     * 1 = the positive-angle direction: θ from π/2 up to 3π/2, through θ = π, i.e. via (25, 35). */
    ck_assert_int_eq(s[7].kind, RUGO_PATH_ARC);
    ck_assert_vec_near(s[7].centre, 30, 35, 1e-14);
    ck_assert_near(s[7].rx, 5, 1e-14);
    ck_assert_near(s[7].dtheta, PI, 1e-14);
    ck_assert_vec_near(seg_point(&p, 7, 0.5), 25, 35, 1e-13);
    ck_assert_vec_near(seg_point(&p, 7, 1.0), 30, 30, 0);
    /* Z: a line back to the start. */
    ck_assert_int_eq(s[8].kind, RUGO_PATH_LINE);
    ck_assert_vec_near(s[8].p[0], 30, 30, 0);
    ck_assert_vec_near(s[8].p[1], 10, 20, 0);
    /* Offsets name the command that made each segment. */
    ck_assert_uint_eq(s[0].offset, 8);
    ck_assert_uint_eq(s[1].offset, 16);
    rugo_path_free(&p);
    ck_assert_ptr_null(p.segments);
    rugo_path_free(&p); /* twice is fine */
    rugo_path_free(NULL);
}
END_TEST

/* The same drawing in relative commands gives the same segments (to round-off of the sums). */
START_TEST(relative_commands) {
    rugo_path a, r;
    parse_ok("M 10 20 L 30 40 H 50 V 60 C 50 70 40 80 30 80 S 10 70 10 60 Q 10 50 20 50 T 30 40 "
             "A 5 5 0 0 1 30 30 Z",
             &a);
    parse_ok("m 10 20 l 20 20 h 20 v 20 c 0 10 -10 20 -20 20 s -20 -10 -20 -20 q 0 -10 10 -10 t 10 -10 "
             "a 5 5 0 0 1 0 -10 z",
             &r);
    ck_assert_int_eq(a.segment_count, r.segment_count);
    for (int k = 0; k < a.segment_count; ++k) {
        ck_assert_int_eq(a.segments[k].kind, r.segments[k].kind);
        for (int i = 0; i < 4; ++i)
            ck_assert_vec_near(r.segments[k].p[i], a.segments[k].p[i].x, a.segments[k].p[i].y, 1e-12);
        for (int i = 0; i <= 4; ++i) {
            rugo_vec2 q = seg_point(&a, k, i / 4.0);
            ck_assert_vec_near(seg_point(&r, k, i / 4.0), q.x, q.y, 1e-12);
        }
    }
    rugo_path_free(&a);
    rugo_path_free(&r);
}
END_TEST

/* Midpoints of a quadratic and a cubic, and the derivative, from the Bernstein forms. */
START_TEST(curve_points) {
    rugo_path p;
    parse_ok("M0 0 Q 1 2 2 0 M0 0 C 0 1 1 1 1 0", &p);
    ck_assert_int_eq(p.subpath_count, 2);
    ck_assert(!p.subpaths[1].closed);
    /* Q: 1/4 (0,0) + 1/2 (1,2) + 1/4 (2,0) = (1, 1); derivative at 1/2 = (2 - 0, 0 - 0) = (2, 0). */
    ck_assert_vec_near(seg_point(&p, 0, 0.5), 1, 1, 1e-15);
    ck_assert_vec_near(rugo_path_segment_derivative(&p.segments[0], 0.5), 2, 0, 1e-15);
    /* C: 1/8 (0,0) + 3/8 (0,1) + 3/8 (1,1) + 1/8 (1,0) = (1/2, 3/4); derivative at 0 = 3 (p1 - p0). */
    ck_assert_vec_near(seg_point(&p, 1, 0.5), 0.5, 0.75, 1e-15);
    ck_assert_vec_near(rugo_path_segment_derivative(&p.segments[1], 0.0), 0, 3, 1e-15);
    rugo_vec2 nan_point = rugo_path_segment_point(NULL, 0.5);
    ck_assert(isnan(nan_point.x) && isnan(nan_point.y));
    rugo_path_free(&p);
}
END_TEST

/* S and T reflect only after C/S and Q/T; otherwise the first control point is the current point. */
START_TEST(smooth_reflection_rules) {
    rugo_path p;
    parse_ok("M0 0 C 1 1 2 1 3 0 S 5 -1 6 0 s 1 1 2 0", &p);
    ck_assert_vec_near(p.segments[1].p[1], 4, -1, 0); /* (2,1) about (3,0) */
    ck_assert_vec_near(p.segments[2].p[1], 7, 1, 0);  /* (5,-1) about (6,0): S after S */
    ck_assert_vec_near(p.segments[2].p[2], 7, 1, 0);  /* relative to (6,0) */
    rugo_path_free(&p);
    parse_ok("M0 0 L 1 0 S 2 1 3 0", &p); /* after L: the current point */
    ck_assert_vec_near(p.segments[1].p[1], 1, 0, 0);
    rugo_path_free(&p);
    parse_ok("M0 0 Q 1 1 2 0 T 4 0 T 6 0 t 2 0", &p);
    ck_assert_vec_near(p.segments[1].p[1], 3, -1, 0); /* (1,1) about (2,0) */
    ck_assert_vec_near(p.segments[2].p[1], 5, 1, 0);  /* (3,-1) about (4,0): T after T */
    ck_assert_vec_near(p.segments[3].p[1], 7, -1, 0);
    ck_assert_vec_near(p.segments[3].p[2], 8, 0, 0);
    rugo_path_free(&p);
    parse_ok("M0 0 L 1 0 T 2 0", &p);
    ck_assert_vec_near(p.segments[1].p[1], 1, 0, 0);
    rugo_path_free(&p);
    /* A quadratic does not feed S, nor a cubic T. */
    parse_ok("M0 0 Q 1 1 2 0 S 3 1 4 0 M0 0 C 1 1 2 1 3 0 T 5 0", &p);
    ck_assert_vec_near(p.segments[1].p[1], 2, 0, 0);
    ck_assert_vec_near(p.segments[3].p[1], 3, 0, 0);
    rugo_path_free(&p);
    /* After Z the reflection is reset too. */
    parse_ok("M0 0 C 1 1 2 1 3 0 Z S 1 1 2 2", &p);
    ck_assert_vec_near(p.segments[2].p[1], 0, 0, 0);
    rugo_path_free(&p);
}
END_TEST

/* Arcs by the SVG implementation notes: both centres of a chord, sweep direction, radius scaling,
 * rotation, zero radius, same end points, negative radii, relative form, flags without separators. */
START_TEST(arcs) {
    rugo_path p;
    /* (1,0) -> (0,1), r = 1. Small arc, sweep 1: centre (0,0), θ from 0 to π/2. */
    parse_ok("M 1 0 A 1 1 0 0 1 0 1", &p);
    ck_assert_int_eq(p.segments[0].kind, RUGO_PATH_ARC);
    ck_assert_vec_near(p.segments[0].centre, 0, 0, 1e-15);
    ck_assert_near(p.segments[0].theta1, 0, 1e-15);
    ck_assert_near(p.segments[0].dtheta, PI / 2, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 0.5), sqrt(0.5), sqrt(0.5), 1e-15);
    rugo_path_free(&p);
    /* Large arc, sweep 1: centre (1,1), θ from -π/2 through 0 to π (3π/2). */
    parse_ok("M 1 0 A 1 1 0 1 1 0 1", &p);
    ck_assert_vec_near(p.segments[0].centre, 1, 1, 1e-15);
    ck_assert_near(p.segments[0].theta1, -PI / 2, 1e-15);
    ck_assert_near(p.segments[0].dtheta, 1.5 * PI, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 1.0 / 3.0), 2, 1, 1e-14); /* θ = 0 */
    rugo_path_free(&p);
    /* Small arc, sweep 0: centre (1,1) again, the short way round (negative). */
    parse_ok("M 1 0 A 1 1 0 0 0 0 1", &p);
    ck_assert_vec_near(p.segments[0].centre, 1, 1, 1e-15);
    ck_assert_near(p.segments[0].dtheta, -PI / 2, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 0.5), 1 - sqrt(0.5), 1 - sqrt(0.5), 1e-15);
    rugo_path_free(&p);
    /* Radius 1 cannot span a chord of 4: scaled to 2, centre at the midpoint, through (2, -2). */
    parse_ok("M 0 0 A 1 1 0 0 1 4 0", &p);
    ck_assert_near(p.segments[0].rx, 2, 1e-15);
    ck_assert_near(p.segments[0].ry, 2, 1e-15);
    ck_assert_vec_near(p.segments[0].centre, 2, 0, 1e-15);
    ck_assert_near(p.segments[0].dtheta, PI, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 0.5), 2, -2, 1e-15);
    rugo_path_free(&p);
    /* An ellipse rx = 2, ry = 1 rotated 90°: its long axis is vertical; (0,0) -> (0,4) is that axis,
     * centre (0,2), and the half ellipse passes (1, 2) (sweep 1). */
    parse_ok("M 0 0 A 2 1 90 0 1 0 4", &p);
    ck_assert_vec_near(p.segments[0].centre, 0, 2, 1e-15);
    ck_assert_near(p.segments[0].phi, PI / 2, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 0.5), 1, 2, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 1.0), 0, 4, 0);
    rugo_path_free(&p);
    /* A zero radius is a straight line; an arc to its own start is dropped. */
    parse_ok("M0 0 A 0 5 0 0 1 3 4 A 5 5 0 0 1 3 4 L 5 5", &p);
    ck_assert_int_eq(p.segment_count, 2);
    ck_assert_int_eq(p.segments[0].kind, RUGO_PATH_LINE);
    ck_assert_vec_near(p.segments[0].p[1], 3, 4, 0);
    ck_assert_int_eq(p.segments[1].kind, RUGO_PATH_LINE);
    rugo_path_free(&p);
    /* Negative radii count as positive; the relative form is relative to the current point. */
    rugo_path q;
    parse_ok("M 1 0 A -1 -1 0 0 1 0 1", &p);
    parse_ok("M 1 0 a 1 1 0 0 1 -1 1", &q);
    ck_assert_vec_near(p.segments[0].centre, 0, 0, 1e-15);
    ck_assert_vec_near(q.segments[0].centre, 0, 0, 1e-15);
    ck_assert_near(q.segments[0].dtheta, PI / 2, 1e-15);
    rugo_path_free(&p);
    rugo_path_free(&q);
    /* Flags without separators: "a1 1 0 00 1 1" is rx 1, ry 1, rotation 0, large 0, sweep 0, to +(1,1):
     * centre (1,0) (sweep 0 from (0,0) to (1,1) turns the negative way), through (1-√½, √½). */
    parse_ok("M0 0a1 1 0 00 1 1", &p);
    ck_assert_int_eq(p.segments[0].kind, RUGO_PATH_ARC);
    ck_assert_vec_near(p.segments[0].p[1], 1, 1, 0);
    ck_assert_vec_near(p.segments[0].centre, 1, 0, 1e-15);
    ck_assert_near(p.segments[0].dtheta, -PI / 2, 1e-15);
    ck_assert_vec_near(seg_point(&p, 0, 0.5), 1 - sqrt(0.5), sqrt(0.5), 1e-15);
    rugo_path_free(&p);
    parse_ok("M0 0a1,1,0,0,1,1,1", &p); /* commas everywhere */
    ck_assert_near(p.segments[0].dtheta, PI / 2, 1e-15);
    rugo_path_free(&p);
    parse_ok("M0 0a1 1 0 1110 0", &p); /* large 1, sweep 1, then "10" and "0" */
    ck_assert_vec_near(p.segments[0].p[1], 10, 0, 0);
    ck_assert_near(p.segments[0].rx, 5, 1e-15); /* scaled up to half the chord */
    rugo_path_free(&p);
}
END_TEST

/* Implicit commands: further pairs after M are lines (m: relative lines); repeated argument sets
 * repeat the command; a drawing command after Z starts a new subpath at the old start. */
START_TEST(implicit_commands) {
    rugo_path p;
    parse_ok("M 0 0 1 0 1 1 0 1 z", &p);
    ck_assert_int_eq(p.subpath_count, 1);
    ck_assert_int_eq(p.segment_count, 4);
    ck_assert_vec_near(p.segments[2].p[1], 0, 1, 0);
    ck_assert_vec_near(p.segments[3].p[1], 0, 0, 0); /* the closing line */
    rugo_path_free(&p);
    parse_ok("m 1 1 2 0 0 2", &p);
    ck_assert_int_eq(p.segment_count, 2);
    ck_assert_vec_near(p.segments[0].p[1], 3, 1, 0);
    ck_assert_vec_near(p.segments[1].p[1], 3, 3, 0);
    rugo_path_free(&p);
    parse_ok("M0 0 C 0 1 1 1 1 0 1 -1 2 -1 2 0 h 1 2 v 1", &p);
    ck_assert_int_eq(p.segment_count, 5);
    ck_assert_int_eq(p.segments[1].kind, RUGO_PATH_CUBIC);
    ck_assert_vec_near(p.segments[1].p[3], 2, 0, 0);
    ck_assert_vec_near(p.segments[3].p[1], 5, 0, 0);
    ck_assert_vec_near(p.segments[4].p[1], 5, 1, 0);
    rugo_path_free(&p);
    parse_ok("M 0 0 L 1 0 1 1 Z L 5 5 Z", &p);
    ck_assert_int_eq(p.subpath_count, 2);
    ck_assert_vec_near(p.subpaths[1].start, 0, 0, 0);
    ck_assert_int_eq(p.subpaths[1].count, 2);
    ck_assert_vec_near(p.segments[p.subpaths[1].first].p[0], 0, 0, 0);
    ck_assert(p.subpaths[0].closed);
    ck_assert(p.subpaths[1].closed);
    rugo_path_free(&p);
    /* A second moveto (relative to the end of the first subpath's closing point). */
    parse_ok("M 1 1 h 1 z m 2 0 h 1", &p);
    ck_assert_int_eq(p.subpath_count, 2);
    ck_assert_vec_near(p.subpaths[1].start, 3, 1, 0);
    ck_assert(!p.subpaths[1].closed);
    rugo_path_free(&p);
    /* Empty data: no subpaths, not an error. */
    parse_ok("", &p);
    ck_assert_int_eq(p.subpath_count, 0);
    rugo_path_free(&p);
    parse_ok(" \t\r\n\f", &p);
    ck_assert_int_eq(p.subpath_count, 0);
    rugo_path_free(&p);
}
END_TEST

/* Number syntax of SVG: signs and points separate numbers, exponents, "1." and ".5", whitespace and
 * commas. */
START_TEST(number_syntax) {
    rugo_path p;
    parse_ok("M-.5.5L1e-3-2E+1", &p);
    ck_assert_vec_near(p.subpaths[0].start, -0.5, 0.5, 0);
    ck_assert_vec_near(p.segments[0].p[1], 0.001, -20, 0);
    rugo_path_free(&p);
    parse_ok("M1.5.5.25-1L1.e1+2", &p);
    ck_assert_vec_near(p.subpaths[0].start, 1.5, 0.5, 0);
    ck_assert_vec_near(p.segments[0].p[1], 0.25, -1, 0);
    ck_assert_vec_near(p.segments[1].p[1], 10, 2, 0);
    rugo_path_free(&p);
    parse_ok("M+1,+2\tL\n3 ,4,5\f,6", &p);
    ck_assert_vec_near(p.subpaths[0].start, 1, 2, 0);
    ck_assert_vec_near(p.segments[0].p[1], 3, 4, 0);
    ck_assert_vec_near(p.segments[1].p[1], 5, 6, 0);
    rugo_path_free(&p);
    parse_ok("M 0 0 L 1e-400 12345678901234567890", &p); /* underflow to 0 is fine */
    ck_assert_vec_near(p.segments[0].p[1], 0, 12345678901234567890.0, 0);
    rugo_path_free(&p);
    parse_ok("M0 0L1 1z", &p);
    ck_assert_int_eq(p.segment_count, 2);
    rugo_path_free(&p);
    /* "1e" is the number 1 followed by an unknown command 'e'. */
    parse_fails("M 1e 2", RUGO_ERR_PARSE, 4, "expected a number (argument 2 of the 2 of 'M'), found 'e'");
}
END_TEST

/* Each kind of bad path data gives its status, the column of the problem and a message. */
START_TEST(bad_path_data) {
    parse_fails("L 1 1", RUGO_ERR_PARSE, 1, "must start with a moveto");
    parse_fails("  10 20", RUGO_ERR_PARSE, 3, "must start with a moveto");
    parse_fails("M 0 0 X 1 1", RUGO_ERR_PARSE, 7, "unknown path command 'X'");
    parse_fails("M 0 0 L 1", RUGO_ERR_PARSE, 10, "argument 2 of the 2 of 'L'");
    parse_fails("M 0 0 C 1 2 3 4 5", RUGO_ERR_PARSE, 18, "argument 6 of the 6 of 'C'");
    parse_fails("M 0 0 L 1 1 ,", RUGO_ERR_PARSE, 12, "comma must be followed by a number");
    parse_fails("M 0 0 L 1 1, L 2 2", RUGO_ERR_PARSE, 12, "comma must be followed by a number");
    parse_fails("M,0 0", RUGO_ERR_PARSE, 2, "expected a number");
    parse_fails("M 0,,0", RUGO_ERR_PARSE, 5, "expected a number");
    parse_fails(", M 0 0", RUGO_ERR_PARSE, 1, "unexpected ','");
    parse_fails("M 0 0 Z 1 1", RUGO_ERR_PARSE, 9, "takes no numbers");
    parse_fails("M 0 0 A 1 1 0 2 1 3 3", RUGO_ERR_PARSE, 15, "large-arc flag and must be 0 or 1");
    parse_fails("M 0 0 A 1 1 0 0 -1 3 3", RUGO_ERR_PARSE, 17, "sweep flag and must be 0 or 1");
    parse_fails("M 0 0 L nan 0", RUGO_ERR_PARSE, 9,
                "expected a number (argument 1 of the 2 of 'L'), found 'n'");
    parse_fails("M 0 0 L 1 inf", RUGO_ERR_PARSE, 11, "expected a number");
    parse_fails("M 0 0 L 0x10 0", RUGO_ERR_PARSE, 10, "expected a number");
    parse_fails("M 0 0 L . 1", RUGO_ERR_PARSE, 9, "expected a number");
    parse_fails("M 0 0 1e999 0", RUGO_ERR_NOT_FINITE, 7, "beyond the range of a double");
    parse_fails("M 0 0 L 1 -1e400000", RUGO_ERR_NOT_FINITE, 11, "beyond the range");
    parse_fails("M 1e308 0 l 1e308 0", RUGO_ERR_NOT_FINITE, 11, "overflow");
    parse_fails("M 0 0 a 1 1 0 0 1 1.7e308 0 a 1 1 0 0 1 1.7e308 0", RUGO_ERR_NOT_FINITE, 29, "overflow");
    parse_fails("M 0 0 L 1 1\n L 2 2 \n Y", RUGO_ERR_PARSE, 0, "unknown path command 'Y'");
    {
        rugo_path p;
        rugo_parse_error e;
        ck_assert_int_eq(rugo_path_parse("M 0 0 L 1 1\n L 2 2 \n Y", 22, NULL, &p, &e), RUGO_ERR_PARSE);
        ck_assert_int_eq(e.line, 3);
        ck_assert_int_eq(e.column, 2);
        /* Non-ASCII bytes are shown as hex. */
        ck_assert_int_eq(rugo_path_parse("M 0 0 \xC3\xA9", 8, NULL, &p, &e), RUGO_ERR_PARSE);
        ck_assert_ptr_nonnull(strstr(e.message, "byte 0xC3"));
        /* The text need not be NUL-terminated: length is obeyed (here it cuts the data short). */
        ck_assert_int_eq(rugo_path_parse("M 0 0 L 1 1", 9, NULL, &p, &e), RUGO_ERR_PARSE);
        ck_assert_int_eq(e.column, 10);
        /* A number too long to be reasonable. */
        char longnum[700];
        memset(longnum, '1', sizeof longnum);
        memcpy(longnum, "M 0 ", 4);
        ck_assert_int_eq(rugo_path_parse(longnum, sizeof longnum, NULL, &p, &e), RUGO_ERR_PARSE);
        ck_assert_ptr_nonnull(strstr(e.message, "longer than"));
        /* Size limit (refused before reading) and NULL arguments. */
        ck_assert_int_eq(rugo_path_parse("M 0 0", RUGO_MAX_SVG_BYTES + 1, NULL, &p, &e), RUGO_ERR_TOO_LARGE);
        ck_assert_int_eq(rugo_path_parse(NULL, 0, NULL, &p, &e), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_path_parse("M 0 0", 5, NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_path_parse("M 0 0 X", 7, NULL, &p, NULL),
                         RUGO_ERR_PARSE); /* error may be NULL */
    }
}
END_TEST

/* Every allocation failure is OUT_OF_MEMORY with nothing leaked, for parsing and sampling; the
 * allocator given is the one used. */
START_TEST(allocation_failures) {
    /* 40 segments: several growths of the segment array. */
    char d[1024] = "M 0 0";
    for (int i = 1; i < 40; ++i)
        snprintf(d + strlen(d), sizeof d - strlen(d), " L %d %d", i, (i * 7) % 13);
    strcat(d, " Z");
    int ok_parse = 0, ok_sample = 0;
    for (long budget = 0; budget < 64 && !(ok_parse && ok_sample); ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo_path p;
        rugo_status st = rugo_path_parse(d, strlen(d), &a, &p, NULL);
        if (st != RUGO_OK) {
            ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
            ck_assert_int_eq(ctx.live, 0);
            continue;
        }
        ok_parse = 1;
        rugo_outline_sample_def sd = rugo_default_outline_sample_def();
        sd.path = &p;
        sd.sample_count = 100;
        sd.allocator = a;
        rugo_outline_samples s;
        st = rugo_outline_sample(&sd, &s, NULL);
        if (st == RUGO_OK) {
            ok_sample = 1;
            rugo_outline_samples_free(&s);
        } else {
            ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        }
        rugo_path_free(&p);
        ck_assert_int_eq(ctx.live, 0);
    }
    ck_assert(ok_parse && ok_sample);
}
END_TEST

/* ---- transforms ---------------------------------------------------------------------------------- */

static rugo_affine transform_ok(const char* s) {
    rugo_affine m;
    rugo_parse_error e;
    rugo_status st = rugo_svg_transform_parse(s, strlen(s), &m, &e);
    ck_assert_msg(st == RUGO_OK, "<%s>: %d %s", s, st, e.message);
    return m;
}

static void transform_fails(const char* s, rugo_status status, int column, const char* fragment) {
    rugo_affine m;
    rugo_parse_error e;
    rugo_status st = rugo_svg_transform_parse(s, strlen(s), &m, &e);
    ck_assert_msg(st == status, "<%s>: status %d, expected %d (%s)", s, st, status, e.message);
    ck_assert(m.a == 1 && m.b == 0 && m.c == 0 && m.d == 1 && m.e == 0 && m.f == 0);
    ck_assert_str_eq(e.path, "transform");
    if (column > 0) ck_assert_msg(e.column == column, "<%s>: column %d, expected %d", s, e.column, column);
    if (fragment != NULL) ck_assert_msg(strstr(e.message, fragment) != NULL, "<%s>: \"%s\"", s, e.message);
}

START_TEST(transform_lists) {
    rugo_affine m = transform_ok("matrix(1 2 3 4 5 6)");
    ck_assert(m.a == 1 && m.b == 2 && m.c == 3 && m.d == 4 && m.e == 5 && m.f == 6);
    m = transform_ok("translate(3)"); /* ty defaults to 0 */
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 1)), 4, 1, 0);
    m = transform_ok("scale(2)"); /* sy defaults to sx */
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 1)), 2, 2, 0);
    m = transform_ok("scale(2,-3)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 1)), 2, -3, 0);
    m = transform_ok("rotate(90)"); /* exact for multiples of 90 degrees */
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), 0, 1, 0);
    m = transform_ok("rotate(-450)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), 0, -1, 0);
    m = transform_ok("rotate(30)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), sqrt(3) / 2, 0.5, 1e-15);
    m = transform_ok("rotate(90 10 20)"); /* about (10, 20): (11, 20) -> (10, 21) */
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(11, 20)), 10, 21, 1e-14);
    m = transform_ok("skewX(45)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(0, 1)), 1, 1, 1e-15);
    m = transform_ok("skewY(45)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), 1, 1, 1e-15);
    /* A list applies right to left: translate(10) scale(2) maps 1 to 12. */
    m = transform_ok(" translate(10, 0) , scale(2)\n");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), 12, 0, 0);
    m = transform_ok("scale(2)translate(10)");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(1, 0)), 22, 0, 0);
    m = transform_ok("translate( 1e1 , -.5 )");
    ck_assert_vec_near(rugo_affine_apply(m, rugo_v2(0, 0)), 10, -0.5, 0);
    m = transform_ok("");
    ck_assert(m.a == 1 && m.d == 1 && m.e == 0);
    /* rugo_affine_multiply agrees with applying in turn. */
    rugo_affine r = transform_ok("rotate(30)"), t = transform_ok("translate(3,4)");
    rugo_vec2 p = rugo_v2(0.7, -1.3), q = rugo_affine_apply(r, rugo_affine_apply(t, p));
    ck_assert_vec_near(rugo_affine_apply(rugo_affine_multiply(r, t), p), q.x, q.y, 1e-15);
}
END_TEST

START_TEST(bad_transforms) {
    transform_fails("foo(1)", RUGO_ERR_PARSE, 1, "unknown transform 'foo'");
    transform_fails("translate(1) 7", RUGO_ERR_PARSE, 14, "expected a transform");
    transform_fails("translate(1,2,3)", RUGO_ERR_PARSE, 1, "translate takes 1 or 2 numbers, found 3");
    transform_fails("rotate(1,2)", RUGO_ERR_PARSE, 1, "rotate takes 1 or 3 numbers");
    transform_fails("matrix(1 2 3 4 5)", RUGO_ERR_PARSE, 1, "matrix takes 6 numbers");
    transform_fails("matrix(1 2 3 4 5 6 7)", RUGO_ERR_PARSE, 20, "too many arguments");
    transform_fails("skewX()", RUGO_ERR_PARSE, 1, "skewX takes 1 number, found 0");
    transform_fails("rotate(10", RUGO_ERR_PARSE, 10, "not closed");
    transform_fails("scale 2", RUGO_ERR_PARSE, 7, "expected '('");
    transform_fails("translate(1,)", RUGO_ERR_PARSE, 12, "comma must be followed by a number");
    transform_fails("scale(2),", RUGO_ERR_PARSE, 9, "comma must be followed by a transform");
    transform_fails("scale(1e999)", RUGO_ERR_NOT_FINITE, 7, "beyond the range");
    transform_fails("scale(1e300) scale(1e300)", RUGO_ERR_NOT_FINITE, 14, "overflows");
    transform_fails("translate(x)", RUGO_ERR_PARSE, 11, "expected a number");
    rugo_affine m;
    ck_assert_int_eq(rugo_svg_transform_parse(NULL, 0, &m, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_svg_transform_parse("", 0, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_svg_transform_parse("", RUGO_MAX_SVG_BYTES + 1, &m, NULL), RUGO_ERR_TOO_LARGE);
}
END_TEST

/* ---- SVG documents --------------------------------------------------------------------------------- */

static void find_fails(const char* doc, const char* id, rugo_status status, int line, const char* fragment) {
    rugo_svg_path_element el;
    rugo_parse_error e;
    rugo_status st = rugo_svg_find_path(doc, strlen(doc), id, NULL, &el, &e);
    ck_assert_msg(st == status, "id %s: status %d, expected %d (%s)", id ? id : "NULL", st, status,
                  e.message);
    ck_assert_ptr_null(el.d);
    if (line >= 0) ck_assert_msg(e.line == line, "line %d, expected %d (%s)", e.line, line, e.message);
    if (fragment != NULL)
        ck_assert_msg(strstr(e.message, fragment) != NULL, "\"%s\" lacks \"%s\"", e.message, fragment);
}

/* The scan finds the element by id whatever the attribute order and quotes, past comments, CDATA,
 * processing instructions and a DOCTYPE that mention the id, with entities decoded, and composes the
 * transforms of its ancestors (only those still open). */
START_TEST(find_path_in_document) {
    const char* doc =
        "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n"
        "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" \"x\" [ <!ENTITY e \"<path id='r'>\"> ]>\n"
        "<svg:svg xmlns:svg='http://www.w3.org/2000/svg'>\n"
        "<!-- <path id=\"r\" d=\"M 9 9\"/> -->\n"
        "<svg:g transform='translate(100,0)'><svg:path id='r' d='M 8 8'/></svg:g>\n"
        "<![CDATA[ <path id=\"r\"/> ]]>\n"
        "<g transform=\"translate(10,20)\">\n"
        "  <text>a &lt; b</text>\n"
        "  <g transform=\"scale(2)\" id=\"inner\">\n"
        "    <svg:path\n"
        "       transform='rotate(90)' d=\"M 1 0 H 2 &#x5A;\" style=\"x\" id=\"a&amp;b\" />\n"
        "  </g>\n"
        "</g>\n"
        "</svg:svg>\n";
    rugo_svg_path_element el;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_find_path(doc, strlen(doc), "a&b", NULL, &el, &e), RUGO_OK);
    ck_assert_str_eq(el.d, "M 1 0 H 2 Z");
    ck_assert_uint_eq(el.d_length, 11);
    ck_assert(el.d_has_entities);
    ck_assert_int_eq(el.line, 10);
    ck_assert_int_eq(el.column, 5);
    /* translate(10,20) scale(2) rotate(90): (1,0) -> (0,1) -> (0,2) -> (10,22). */
    ck_assert_vec_near(rugo_affine_apply(el.transform, rugo_v2(1, 0)), 10, 22, 0);
    rugo_svg_path_element_free(&el);
    ck_assert_ptr_null(el.d);
    rugo_svg_path_element_free(NULL);
    /* The first real element with the id "r" is inside the closed translate(100) group. */
    ck_assert_int_eq(rugo_svg_find_path(doc, strlen(doc), "r", NULL, &el, &e), RUGO_OK);
    ck_assert_str_eq(el.d, "M 8 8");
    ck_assert(!el.d_has_entities);
    ck_assert_vec_near(rugo_affine_apply(el.transform, rugo_v2(0, 0)), 100, 0, 0);
    rugo_svg_path_element_free(&el);
    /* An id that only occurs in comments or CDATA is not found. */
    find_fails("<svg><!-- <path id='x' d='M0 0'/> --><![CDATA[<path id='x'/>]]></svg>", "x",
               RUGO_ERR_BAD_FIELD, 0, "no element with id 'x'");
    /* Without an id: the only <path>. */
    const char* one = "<svg><g><rect id='r'/><path d='M 0 0 H 1 V 1 Z'/></g></svg>";
    ck_assert_int_eq(rugo_svg_find_path(one, strlen(one), NULL, NULL, &el, &e), RUGO_OK);
    ck_assert_str_eq(el.d, "M 0 0 H 1 V 1 Z");
    rugo_svg_path_element_free(&el);
}
END_TEST

START_TEST(bad_documents) {
    find_fails("<svg><rect id='x'/></svg>", "x", RUGO_ERR_BAD_FIELD, 1, "is <rect>, not <path>");
    find_fails("<svg>\n<path id='x'/></svg>", "x", RUGO_ERR_BAD_FIELD, 2, "no d attribute");
    find_fails("<svg><path d='M0 0'/><path d='M1 1'/></svg>", NULL, RUGO_ERR_BAD_FIELD, 1,
               "more than one <path>");
    find_fails("<svg><g/></svg>", NULL, RUGO_ERR_BAD_FIELD, 0, "no <path> element");
    find_fails("", "x", RUGO_ERR_BAD_FIELD, 0, "no element with id");
    find_fails("<svg>\n<g>\n</svg>\n<path id='x' d='M0 0'/>", "x", RUGO_ERR_PARSE, 3,
               "</svg> does not match <g>");
    find_fails("<svg></g>", "x", RUGO_ERR_PARSE, 1, "does not match");
    find_fails("</svg>", "x", RUGO_ERR_PARSE, 1, "without a matching start tag");
    find_fails("<svg><!-- never closed <path id='x' d='M0 0'/>", "x", RUGO_ERR_PARSE, 1,
               "unterminated comment");
    find_fails("<svg><![CDATA[ x", "x", RUGO_ERR_PARSE, 1, "unterminated CDATA");
    find_fails("<?xml version='1.0'", "x", RUGO_ERR_PARSE, 1, "unterminated processing instruction");
    find_fails("<!DOCTYPE svg [ <!ENTITY a 'b'>", "x", RUGO_ERR_PARSE, 1, "unterminated declaration");
    find_fails("<svg>\n  <path id='x' d='M0 0", "x", RUGO_ERR_PARSE, 2, "unterminated attribute value");
    find_fails("<svg><path id='x' d='M0 0'", "x", RUGO_ERR_PARSE, 1, "unterminated tag");
    find_fails("<svg><path id='x' d=M0></svg>", "x", RUGO_ERR_PARSE, 1, "expected a quoted attribute value");
    find_fails("<svg><path id='x' d></svg>", "x", RUGO_ERR_PARSE, 1, "expected '='");
    find_fails("<svg><path id='x' id='y' d='M0 0'/></svg>", "x", RUGO_ERR_PARSE, 1, "given twice");
    find_fails("<svg>< path/></svg>", "x", RUGO_ERR_PARSE, 1, "expected an element name");
    find_fails("<svg><path id='x' d='M 0 0 &foo; 1'/></svg>", "x", RUGO_ERR_PARSE, 1, "entity");
    find_fails("<svg><path id='x' d='M 0 0 &#0; 1'/></svg>", "x", RUGO_ERR_PARSE, 1, "entity");
    find_fails("<svg><path id='x' d='M 0 0 &#xD800; 1'/></svg>", "x", RUGO_ERR_PARSE, 1, "entity");
    find_fails("<svg><path id='x' d='M 0 0 &#x110000; 1'/></svg>", "x", RUGO_ERR_PARSE, 1, "entity");
    find_fails("<svg><path id='x' d='M 0 0 & 1'/></svg>", "x", RUGO_ERR_PARSE, 1, "entity");
    /* A bad transform of an ancestor is reported inside that attribute, with the element's name. */
    {
        const char* doc =
            "<svg>\n<g id='L' transform='translate(1) frob(2)'>\n<path id='x' d='M0 0'/></g></svg>";
        rugo_svg_path_element el;
        rugo_parse_error e;
        ck_assert_int_eq(rugo_svg_find_path(doc, strlen(doc), "x", NULL, &el, &e), RUGO_ERR_PARSE);
        ck_assert_int_eq(e.line, 2);
        ck_assert_int_eq(e.column, 35);
        ck_assert_str_eq(e.path, "g#L/transform");
        ck_assert_ptr_nonnull(strstr(e.message, "unknown transform 'frob'"));
        const char* big =
            "<svg><g transform='scale(1e200)'><path id='x' transform='scale(1e200)' d='M0 0'/></g></svg>";
        ck_assert_int_eq(rugo_svg_find_path(big, strlen(big), "x", NULL, &el, &e), RUGO_ERR_NOT_FINITE);
        /* Nesting beyond the limit. */
        size_t n = (RUGO_SVG_MAX_DEPTH + 1) * 3 + 32;
        char* deep = malloc(n);
        size_t w = 0;
        for (int i = 0; i <= RUGO_SVG_MAX_DEPTH; ++i)
            w += (size_t)sprintf(deep + w, "<g>");
        w += (size_t)sprintf(deep + w, "<path id='x' d='M0 0'/>");
        ck_assert_int_eq(rugo_svg_find_path(deep, w, "x", NULL, &el, &e), RUGO_ERR_PARSE);
        ck_assert_ptr_nonnull(strstr(e.message, "nested deeper"));
        /* Exactly at the limit is fine. */
        w = 0;
        for (int i = 0; i < RUGO_SVG_MAX_DEPTH; ++i)
            w += (size_t)sprintf(deep + w, "<g>");
        w += (size_t)sprintf(deep + w, "<path id='x' d='M0 0'/>");
        ck_assert_int_eq(rugo_svg_find_path(deep, w, "x", NULL, &el, &e), RUGO_OK);
        rugo_svg_path_element_free(&el);
        free(deep);
        ck_assert_int_eq(rugo_svg_find_path(NULL, 0, "x", NULL, &el, &e), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_svg_find_path("<svg/>", 6, "x", NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_svg_find_path("<svg/>", RUGO_MAX_SVG_BYTES + 1, "x", NULL, &el, &e),
                         RUGO_ERR_TOO_LARGE);
    }
}
END_TEST

/* Errors in the d attribute of a document are reported at their line and column in the document. */
START_TEST(document_error_positions) {
    const char* doc = "<svg>\n  <path id=\"p\"\n     d=\"M 0 0 L 1 1\n        Q 2 2 x\" />\n</svg>";
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_import_outline(doc, strlen(doc), "p", &sd, &s, &e), RUGO_ERR_PARSE);
    ck_assert_int_eq(e.line, 4);
    ck_assert_int_eq(e.column, 15);
    ck_assert_str_eq(e.path, "path#p/d");
    ck_assert_ptr_null(s.points);
    /* An open path: the error points at its d attribute. */
    const char* open = "<svg>\n<path id='o' d='M 0 0 L 1 1 L 0 1'/></svg>";
    ck_assert_int_eq(rugo_svg_import_outline(open, strlen(open), "o", &sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_int_eq(e.line, 2);
    ck_assert_int_eq(e.column, 17);
    ck_assert_ptr_nonnull(strstr(e.message, "no closed subpath"));
    rugo_outline_sample_def bad = sd;
    bad.cookie = 0;
    ck_assert_int_eq(rugo_svg_import_outline(open, strlen(open), "o", &bad, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_svg_import_outline(NULL, 0, "o", &sd, &s, &e), RUGO_ERR_NULL_ARGUMENT);
}
END_TEST

/* ---- sampling --------------------------------------------------------------------------------------- */

static void sample_ok(const rugo_path* p, int subpath, rugo_affine m, int count, rugo_outline_samples* s) {
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = p;
    sd.subpath = subpath;
    sd.transform = m;
    sd.sample_count = count;
    rugo_parse_error e;
    rugo_status st = rugo_outline_sample(&sd, s, &e);
    ck_assert_msg(st == RUGO_OK, "status %d: %s", st, e.message);
}

/* Speed of the cubic (0,0) (1,1) (0,1) (1,0), which has a cusp at t = 1/2, in long double. */
static long double cusp_speed(long double t) {
    const long double u = 1.0L - t;
    const long double dx = 3.0L * (u * u - 2.0L * u * t + t * t), dy = 3.0L * (u * u - t * t);
    return sqrtl(dx * dx + dy * dy);
}

static long double cusp_simpson(long double a, long double fa, long double m, long double fm, long double b,
                                long double fb, long double whole, long double tol, int depth) {
    const long double lm = 0.5L * (a + m), rm = 0.5L * (m + b), flm = cusp_speed(lm), frm = cusp_speed(rm);
    const long double left = (m - a) / 6.0L * (fa + 4.0L * flm + fm);
    const long double right = (b - m) / 6.0L * (fm + 4.0L * frm + fb);
    const long double delta = left + right - whole;
    if (depth >= 60 || fabsl(delta) <= 15.0L * tol) return left + right + delta / 15.0L;
    return cusp_simpson(a, fa, lm, flm, m, fm, left, 0.5L * tol, depth + 1) +
           cusp_simpson(m, fm, rm, frm, b, fb, right, 0.5L * tol, depth + 1);
}

/* Arc length of the cusp cubic from 0 to t, by adaptive Simpson (an independent reference). */
static long double cusp_length(long double t) {
    long double total = 0.0L, a = 0.0L;
    while (a < t) { /* pieces ending at the cusp, so that no piece straddles it */
        const long double b = a < 0.5L && t > 0.5L ? 0.5L : t, m = 0.5L * (a + b);
        const long double fa = cusp_speed(a), fm = cusp_speed(m), fb = cusp_speed(b);
        total += cusp_simpson(a, fa, m, fm, b, fb, (b - a) / 6.0L * (fa + 4.0L * fm + fb), 1e-17L, 0);
        a = b;
    }
    return total;
}

/* The outline sampler measures and places by the library's certified arc length: on a cubic with a
 * cusp, the perimeter is within 1e-12 of the reference, and every sample on the cubic sits at j L/(e+1)
 * of its arc length within 1e-12 L (its parameter recovered from y = 3 t (1 - t), exact near the cusp,
 * and the side of the cusp from x). */
START_TEST(sample_cusp_arc_length) {
    rugo_path p;
    parse_ok("M 0 0 C 1 1 0 1 1 0 Z", &p);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 41, &s);
    const long double L = cusp_length(1.0L);
    ck_assert_msg(fabsl(s.perimeter - (L + 1.0L)) <= 1e-12L * (L + 1.0L), "perimeter %.17g vs %.17Lg",
                  s.perimeter, L + 1.0L);
    double pos[64];
    int e = 0;
    for (int i = 0; i < s.count; ++i) {
        if (!(s.points[i].y > 0.0)) continue; /* the closing line and the cubic's ends */
        const long double u = (0.75L - (long double)s.points[i].y) / 3.0L; /* (t - 1/2)^2 */
        const long double t = 0.5L + (s.points[i].x < 0.5 ? -1.0L : 1.0L) * sqrtl(u > 0.0L ? u : 0.0L);
        ck_assert(e < 64);
        pos[e++] = (double)cusp_length(t);
    }
    ck_assert_int_ge(e, 20);
    for (int i = 0; i < e; ++i)
        for (int j = i + 1; j < e; ++j)
            if (pos[j] < pos[i]) {
                const double tmp = pos[i];
                pos[i] = pos[j];
                pos[j] = tmp;
            }
    for (int j = 0; j < e; ++j)
        ck_assert_msg(fabsl(pos[j] - L * (j + 1) / (e + 1)) <= 1e-12L * L, "sample %d of %d: %.17g vs %.17Lg",
                      j + 1, e, pos[j], L * (j + 1) / (e + 1));
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

static double polygon_area(const rugo_vec2* p, int n) {
    double a = 0.0;
    for (int i = 0; i < n; ++i)
        a += rugo_v2_cross(p[i], p[(i + 1) % n]);
    return 0.5 * a;
}

/* A square of side 10 with 10 samples: its 4 corners, and 6 more by largest remainders (1.5 per side:
 * one each, and the two left to the first two sides), equally spaced on each side. */
START_TEST(sample_square_by_hand) {
    rugo_path p;
    parse_ok("M0 0 H10 V10 H0 Z", &p);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 10, &s);
    static const double want[10][2] = {{0, 0},         {10.0 / 3, 0}, {20.0 / 3, 0}, {10, 0}, {10, 10.0 / 3},
                                       {10, 20.0 / 3}, {10, 10},      {5, 10},       {0, 10}, {0, 5}};
    ck_assert_int_eq(s.count, 10);
    for (int i = 0; i < 10; ++i)
        ck_assert_vec_near(s.points[i], want[i][0], want[i][1], 1e-13);
    ck_assert_near(s.perimeter, 40, 1e-13);
    ck_assert_near(s.area, 100, 1e-12);
    ck_assert(!s.reversed);
    ck_assert_int_eq(s.segment_count, 4);
    ck_assert_int_eq(s.subpath, 0);
    rugo_outline_samples_free(&s);
    ck_assert_ptr_null(s.points);
    rugo_outline_samples_free(&s);
    rugo_outline_samples_free(NULL);
    /* Under SVG's y flip the same drawing runs clockwise: the samples come out reversed, start kept. */
    rugo_affine flip = {1, 0, 0, -1, 0, 0};
    sample_ok(&p, -1, flip, 10, &s);
    ck_assert(s.reversed);
    ck_assert_vec_near(s.points[0], 0, 0, 0);
    ck_assert_vec_near(s.points[1], 0, -5, 1e-13);
    ck_assert_vec_near(s.points[9], 10.0 / 3, 0, 1e-13);
    ck_assert(polygon_area(s.points, s.count) > 0);
    rugo_outline_samples_free(&s);
    /* As many samples as segments: just the corners. */
    sample_ok(&p, -1, rugo_affine_identity(), 4, &s);
    ck_assert_int_eq(s.count, 4);
    ck_assert_vec_near(s.points[2], 10, 10, 0);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

/* A circle of radius 10 as four arcs: perimeter 2π r, every sample on the circle, spacing uniform
 * (1024 samples per quarter). */
START_TEST(sample_circle_of_arcs) {
    rugo_path p;
    parse_ok("M 10 0 A 10 10 0 0 1 0 10 A 10 10 0 0 1 -10 0 A 10 10 0 0 1 0 -10 A 10 10 0 0 1 10 0 Z", &p);
    ck_assert_int_eq(p.segment_count, 4); /* the arcs end exactly at the start: Z adds nothing */
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 0, &s);
    ck_assert_int_eq(s.count, RUGO_DEFAULT_OUTLINE_SAMPLES);
    ck_assert_near(s.perimeter, 2 * PI * 10, 1e-12);
    double step_min = 1e9, step_max = 0;
    for (int i = 0; i < s.count; ++i) {
        ck_assert_near(hypot(s.points[i].x, s.points[i].y), 10, 1e-13);
        const double step = hypot(s.points[(i + 1) % s.count].x - s.points[i].x,
                                  s.points[(i + 1) % s.count].y - s.points[i].y);
        step_min = fmin(step_min, step);
        step_max = fmax(step_max, step);
        /* sample k at angle 2π k / M */
        const double ang = 2 * PI * i / s.count;
        ck_assert_vec_near(s.points[i], 10 * cos(ang), 10 * sin(ang), 1e-12);
    }
    ck_assert_near(step_max / step_min, 1, 1e-10);
    ck_assert(!s.reversed);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

/* The usual four-cubic circle (k = 4(√2-1)/3 r) is not a circle: its perimeter is 2π r (1 + 1.40293e-4)
 * (independent value: 62.840667922954331 by composite Gauss-Legendre with 16384 pieces), and its
 * points lie between r and r (1 + 2.7253e-4). */
START_TEST(sample_circle_of_cubics) {
    rugo_path p;
    parse_ok("M 10 0 C 10 5.522847498307936 5.522847498307936 10 0 10 C -5.522847498307936 10 -10 "
             "5.522847498307936 "
             "-10 0 C -10 -5.522847498307936 -5.522847498307936 -10 0 -10 C 5.522847498307936 -10 10 "
             "-5.522847498307936 10 0 Z",
             &p);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 0, &s);
    ck_assert_near(s.perimeter, 62.840667922954331, 1e-11);
    ck_assert_near(s.perimeter / (2 * PI * 10) - 1, 1.40293e-4, 1e-9);
    double rmin = 1e9, rmax = 0;
    for (int i = 0; i < s.count; ++i) {
        const double r = hypot(s.points[i].x, s.points[i].y);
        rmin = fmin(rmin, r);
        rmax = fmax(rmax, r);
    }
    ck_assert_near(rmin, 10, 1e-12);
    ck_assert_near(rmax, 10.0027253, 1e-7);
    /* Consecutive samples are equally spaced in arc length, so their chords are nearly equal. */
    for (int i = 0; i < s.count; ++i) {
        const double step = hypot(s.points[(i + 1) % s.count].x - s.points[i].x,
                                  s.points[(i + 1) % s.count].y - s.points[i].y);
        ck_assert_near(step, s.perimeter / s.count, 1e-6);
    }
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

/* Which subpath: the closed one of largest area by default (an outline with a hole gives its outer
 * boundary), or the one asked for; errors for open, empty and missing subpaths. */
START_TEST(sample_subpath_choice) {
    rugo_path p;
    parse_ok("M 2 2 h 1 v 1 h -1 z M 0 0 h 10 v 10 h -10 z M 20 20 l 5 0 l 0 5 M 30 30 Z", &p);
    ck_assert_int_eq(p.subpath_count, 4);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 8, &s);
    ck_assert_int_eq(s.subpath, 1);
    ck_assert_near(s.area, 100, 1e-12);
    rugo_outline_samples_free(&s);
    sample_ok(&p, 0, rugo_affine_identity(), 8, &s);
    ck_assert_int_eq(s.subpath, 0);
    ck_assert_near(s.area, 1, 1e-12);
    rugo_outline_samples_free(&s);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = &p;
    rugo_parse_error e;
    sd.subpath = 2;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_ptr_nonnull(strstr(e.message, "subpath 2 is open"));
    sd.subpath = 3;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_ptr_nonnull(strstr(e.message, "subpath 3 is empty"));
    sd.subpath = 4;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    sd.subpath = -2;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    rugo_path_free(&p);
    /* No closed subpath at all; a subpath ending on its start without Z counts as closed. */
    parse_ok("M 0 0 L 1 0 L 1 1", &p);
    sd = rugo_default_outline_sample_def();
    sd.path = &p;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_ptr_nonnull(strstr(e.message, "no closed subpath"));
    rugo_path_free(&p);
    parse_ok("M 0 0 L 1 0 L 1 1 L 0 0", &p);
    sd.path = &p;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_OK);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
    parse_ok("", &p);
    sd.path = &p;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_FIELD);
    rugo_path_free(&p);
}
END_TEST

START_TEST(sample_bad_input) {
    rugo_path p;
    parse_ok("M0 0 H10 V10 H0 Z", &p);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    ck_assert_int_eq(sd.subpath, -1);
    ck_assert_int_eq(sd.sample_count, 0);
    ck_assert(sd.transform.a == 1 && sd.transform.d == 1);
    sd.path = &p;
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_outline_sample(NULL, &s, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_outline_sample(&sd, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    rugo_outline_sample_def d2 = sd;
    d2.cookie = 12345;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    d2 = sd;
    d2.path = NULL;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_NULL_ARGUMENT);
    d2 = sd;
    d2.sample_count = 3; /* below the 4 segments */
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(e.message, "below the 4 segments"));
    d2.sample_count = 2;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    d2.sample_count = -1;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    d2.sample_count = RUGO_MAX_CONTROL_POINTS + 1;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_TOO_MANY_POINTS);
    d2 = sd;
    d2.transform.c = NAN;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_NOT_FINITE);
    d2.transform = rugo_affine_identity();
    d2.transform.a = 1e300; /* finite points, but an area beyond doubles */
    d2.transform.d = 1e300;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_NOT_FINITE);
    ck_assert_ptr_nonnull(strstr(e.message, "area overflows"));
    d2.transform.a = 1e308; /* lengths beyond doubles */
    d2.transform.d = 1e308;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_NOT_FINITE);
    ck_assert_ptr_nonnull(strstr(e.message, "length overflows"));
    d2.transform = rugo_affine_identity();
    d2.transform.d = 0; /* everything onto the x axis */
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_ZERO_AREA);
    d2.transform.a = 0;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_ZERO_AREA);
    ck_assert_ptr_null(s.points);
    /* So small that the area underflows (it used to come back RUGO_OK with area 0). */
    d2.transform.a = 1e-320;
    d2.transform.d = 1e-320;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_ZERO_AREA);
    ck_assert_ptr_nonnull(strstr(e.message, "underflows"));
    ck_assert_ptr_null(s.points);
    /* A segment of a kind the enum does not have (a hand-built path). */
    d2 = sd;
    const rugo_path_segment_kind kept = p.segments[1].kind;
    p.segments[1].kind = (rugo_path_segment_kind)42;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(e.message, "unknown kind"));
    p.segments[1].kind = (rugo_path_segment_kind)-1;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    p.segments[1].kind = kept;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_OK);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
    /* A path whose counts disagree with its arrays. */
    rugo_path bogus;
    memset(&bogus, 0, sizeof bogus);
    bogus.subpath_count = 1;
    d2 = sd;
    d2.path = &bogus;
    ck_assert_int_eq(rugo_outline_sample(&d2, &s, &e), RUGO_ERR_BAD_ARGUMENT);
}
END_TEST

/* Same input, same bits; and the points lie on the curve (a cubic here: distance to the true curve
 * checked by dense bisection-free evaluation is below 1e-12). */
START_TEST(sample_deterministic_and_on_curve) {
    rugo_path p;
    parse_ok("M 0 0 C 10 -5 20 15 30 0 Q 40 -20 30 -30 A 15 10 30 0 1 0 0 Z", &p);
    rugo_outline_samples a, b;
    sample_ok(&p, -1, rugo_affine_identity(), 777, &a);
    sample_ok(&p, -1, rugo_affine_identity(), 777, &b);
    ck_assert_int_eq(a.count, 777);
    ck_assert_int_eq(memcmp(a.points, b.points, sizeof(rugo_vec2) * (size_t)a.count), 0);
    ck_assert(a.perimeter == b.perimeter);
    /* Arc lengths between consecutive samples inside one segment are equal: check on the arc, whose
     * samples lie on its ellipse. */
    const rugo_path_segment* arc = &p.segments[2];
    ck_assert_int_eq(arc->kind, RUGO_PATH_ARC);
    int on_ellipse = 0;
    for (int i = 0; i < a.count; ++i) {
        const rugo_vec2 q = rugo_v2_sub(a.points[i], arc->centre);
        const double c = cos(arc->phi), s = sin(arc->phi);
        const double u = (c * q.x + s * q.y) / arc->rx, v = (-s * q.x + c * q.y) / arc->ry;
        if (fabs(hypot(u, v) - 1) < 1e-12) ++on_ellipse;
    }
    /* the arc's share of the samples (its start included) */
    ck_assert_int_gt(on_ellipse, 200);
    rugo_outline_samples_free(&a);
    rugo_outline_samples_free(&b);
    rugo_path_free(&p);
}
END_TEST

/* Regression (found while writing fuzz/fuzz_import.c): segments whose finite control points near
 * DBL_MAX give an overflowing derivative (inf, or inf - inf = NaN) have no finite length; the adaptive
 * arc length split each of them to 2^16 leaves before the sampler refused the total (about 40 ms a
 * segment). Now the first non-finite leaf ends the walk: the status is NOT_FINITE as before, and
 * these 32768 segments (cubics with NaN speeds, lines with infinite ones) take milliseconds, where
 * the old walk needed over 20 minutes and the suite's CTest timeout would stop it. */
START_TEST(sample_overflowing_lengths) {
    enum { N = 32768 };
    static const char* const pieces[2] = {"C1.7e308 0 -1.7e308 0 1.7e308 0", "L-1.7e308 0 L1.7e308 0"};
    const size_t cap = (size_t)N * 40 + 64;
    char* d = (char*)malloc(cap);
    ck_assert_ptr_nonnull(d);
    for (int k = 0; k < 2; ++k) {
        size_t w = (size_t)snprintf(d, cap, "M-1.7e308 0");
        for (int i = 0; i < N / (k + 1); ++i)
            w += (size_t)snprintf(d + w, cap - w, "%s", pieces[k]);
        w += (size_t)snprintf(d + w, cap - w, "Z");
        rugo_path p;
        rugo_parse_error e;
        ck_assert_int_eq(rugo_path_parse(d, w, NULL, &p, &e), RUGO_OK);
        ck_assert_int_eq(p.segment_count, N + 1); /* the closing line too */
        rugo_outline_sample_def sd = rugo_default_outline_sample_def();
        sd.path = &p;
        rugo_outline_samples s;
        ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_NOT_FINITE);
        ck_assert_ptr_nonnull(strstr(e.message, "length overflows"));
        ck_assert_ptr_null(s.points);
        sd.subpath = 0;
        sd.sample_count = 2 * N + 2;
        ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_NOT_FINITE);
        rugo_path_free(&p);
    }
    free(d);
}
END_TEST

/* ---- point lists --------------------------------------------------------------------------------- */

START_TEST(points_text) {
    const char* t = "x,y\r\n# a comment\r\n1,2\r\n\r\n 3 4 \n5;6\n7\t8\n-1e1 , +.5\n";
    rugo_point_list pts;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_points_text_parse(t, strlen(t), NULL, &pts, &e), RUGO_OK);
    ck_assert_int_eq(pts.count, 5);
    ck_assert_vec_near(pts.points[0], 1, 2, 0);
    ck_assert_vec_near(pts.points[1], 3, 4, 0);
    ck_assert_vec_near(pts.points[2], 5, 6, 0);
    ck_assert_vec_near(pts.points[3], 7, 8, 0);
    ck_assert_vec_near(pts.points[4], -10, 0.5, 0);
    rugo_point_list_free(&pts);
    ck_assert(pts.points == NULL && pts.count == 0);
    rugo_point_list_free(&pts); /* a zeroed list, and NULL, are fine */
    rugo_point_list_free(NULL);
    /* JSON is told by its '{'. */
    const char* j = "  {\"points\": [[1, 2], [3, 4], [5, 7]]}";
    ck_assert_int_eq(rugo_points_text_parse(j, strlen(j), NULL, &pts, &e), RUGO_OK);
    ck_assert_int_eq(pts.count, 3);
    ck_assert_vec_near(pts.points[2], 5, 7, 0);
    rugo_point_list_free(&pts);
    const char* jbad = "{\"points\": [[1, 2], [3]]}";
    ck_assert_int_eq(rugo_points_text_parse(jbad, strlen(jbad), NULL, &pts, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_ptr_null(pts.points);
    /* The data file rugo fit reads. */
    size_t len = 0;
    char* c64 = read_data("circle64_points.json", &len);
    ck_assert_int_eq(rugo_points_text_parse(c64, len, NULL, &pts, &e), RUGO_OK);
    ck_assert_int_eq(pts.count, 64);
    rugo_point_list_free(&pts);
    free(c64);
    /* Empty text: no points. */
    ck_assert_int_eq(rugo_points_text_parse("", 0, NULL, &pts, &e), RUGO_OK);
    ck_assert_int_eq(pts.count, 0);
    ck_assert_ptr_null(pts.points);
}
END_TEST

static void points_fail(const char* t, rugo_status status, int line, int column, const char* fragment) {
    rugo_point_list pts;
    pts.points = (rugo_vec2*)&pts;
    pts.count = -1;
    rugo_parse_error e;
    rugo_status st = rugo_points_text_parse(t, strlen(t), NULL, &pts, &e);
    ck_assert_msg(st == status, "<%s>: status %d, expected %d (%s)", t, st, status, e.message);
    ck_assert_ptr_null(pts.points);
    ck_assert_int_eq(pts.count, 0);
    ck_assert_msg(e.line == line && e.column == column, "<%s>: at %d:%d, expected %d:%d", t, e.line, e.column,
                  line, column);
    if (fragment != NULL) ck_assert_msg(strstr(e.message, fragment) != NULL, "<%s>: \"%s\"", t, e.message);
}

START_TEST(bad_points_text) {
    points_fail("1,2\n3,4,5\n", RUGO_ERR_PARSE, 2, 4, "two numbers per line");
    points_fail("1,2\n3\n", RUGO_ERR_PARSE, 2, 2, "expected a separator");
    points_fail("1,2\n3,\n", RUGO_ERR_PARSE, 2, 3, "expected a number (y)");
    points_fail("1,2\nx,y\n", RUGO_ERR_PARSE, 2, 1, "expected a number (x)"); /* a header only comes first */
    points_fail("nan,1\n", RUGO_ERR_PARSE, 1, 1, "expected a number");        /* has a digit: not a header */
    points_fail("0x10,1\n", RUGO_ERR_PARSE, 1, 2, "separator");
    points_fail("1,2\n1e999,0\n", RUGO_ERR_NOT_FINITE, 2, 1, "beyond the range");
    points_fail("1,2\n3-4\n", RUGO_ERR_PARSE, 2, 2, "separator");
    rugo_point_list pts;
    ck_assert_int_eq(rugo_points_text_parse(NULL, 0, NULL, &pts, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_points_text_parse("1 2", 3, NULL, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_points_text_parse("1 2", RUGO_MAX_JSON_BYTES + 1, NULL, &pts, NULL),
                     RUGO_ERR_TOO_LARGE);
}
END_TEST

START_TEST(path_from_points) {
    const rugo_vec2 pts[] = {{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
    rugo_path p;
    ck_assert_int_eq(rugo_path_from_points(pts, 6, NULL, &p), RUGO_OK);
    ck_assert_int_eq(p.subpath_count, 1);
    ck_assert(p.subpaths[0].closed);
    ck_assert_int_eq(p.segment_count, 4); /* the repeat and the closing repeat give no segment */
    ck_assert_vec_near(p.segments[3].p[1], 0, 0, 0);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 4, &s); /* M = S: the points themselves */
    ck_assert_int_eq(s.count, 4);
    ck_assert_vec_near(s.points[1], 1, 0, 0);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
    const rugo_vec2 bad[] = {{0, 0}, {NAN, 0}, {1, 1}};
    ck_assert_int_eq(rugo_path_from_points(bad, 3, NULL, &p), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_path_from_points(pts, 2, NULL, &p), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_path_from_points(NULL, 3, NULL, &p), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_path_from_points(pts, RUGO_MAX_PATH_SEGMENTS + 1, NULL, &p), RUGO_ERR_TOO_LARGE);
    ck_assert_ptr_null(p.segments);
}
END_TEST

/* Found by fuzz_import in CI: points that are all the same made no segment but kept the array, breaking
 * "segment_count == 0 exactly when segments == NULL", which every path reader relies on. */
START_TEST(path_from_points_all_equal) {
    const rugo_vec2 pts[] = {{0, 1}, {0, 1}, {0, 1}, {0, 1}};
    rugo_path p;
    ck_assert_int_eq(rugo_path_from_points(pts, 4, NULL, &p), RUGO_OK);
    ck_assert_int_eq(p.segment_count, 0);
    ck_assert_ptr_null(p.segments);
    ck_assert_int_eq(p.subpath_count, 1);
    ck_assert_int_eq(p.subpaths[0].count, 0);
    ck_assert_vec_near(p.subpaths[0].start, 0, 1, 0);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = &p;
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_ne(rugo_outline_sample(&sd, &s, &e), RUGO_OK); /* nothing to sample: an error, */
    ck_assert_ptr_null(s.points);                                /* not a crash */
    ck_assert_int_eq(s.count, 0);
    rugo_path_free(&p);
}
END_TEST

/* ---- the Inkscape rock ------------------------------------------------------------------------------ */

/* tests/data/rock_inkscape.svg: a path of relative c/s/l commands closed by z, inside a layer with
 * translate() and a group with a rotation matrix; also an open path (crack) and an ellipse. */
START_TEST(rock_samples) {
    size_t len = 0;
    char* text = read_data("rock_inkscape.svg", &len);
    rugo_svg_path_element el;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_find_path(text, len, "rock", NULL, &el, &e), RUGO_OK);
    ck_assert_int_eq(el.line, 46);
    /* translate(-12.5,-30.25) matrix(0.97629601,-0.21643961,0.21643961,0.97629601,-29.530157,27.335921) */
    ck_assert_near(el.transform.a, 0.97629601, 1e-15);
    ck_assert_near(el.transform.b, -0.21643961, 1e-15);
    ck_assert_near(el.transform.e, -29.530157 - 12.5, 1e-13);
    ck_assert_near(el.transform.f, 27.335921 - 30.25, 1e-13);
    rugo_path p;
    ck_assert_int_eq(rugo_path_parse(el.d, el.d_length, NULL, &p, &e), RUGO_OK);
    ck_assert_int_eq(p.subpath_count, 1);
    ck_assert(p.subpaths[0].closed);
    rugo_path_free(&p);
    rugo_svg_path_element_free(&el);

    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    rugo_outline_samples s;
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "rock", &sd, &s, &e), RUGO_OK);
    ck_assert_int_eq(s.count, 4096);
    ck_assert_int_eq(s.segment_count, 9);
    ck_assert(s.reversed); /* drawn clockwise as seen on screen, which stays clockwise in the
                              y-up frame: the samples were reversed */
    /* Independent values (Python cross-check): perimeter 259.835191015432, area 5286.30072137481. */
    ck_assert_near(s.perimeter, 259.835191015432, 1e-9);
    ck_assert_near(s.area, 5286.30072137481, 1e-8);
    ck_assert(polygon_area(s.points, s.count) > 0);
    /* y up: every point below the x axis (the drawing lies at positive SVG y). */
    for (int i = 0; i < s.count; ++i)
        ck_assert(s.points[i].y < 0);
    /* Spacing at most perimeter / (M - S). */
    for (int i = 0; i < s.count; ++i) {
        const double step = hypot(s.points[(i + 1) % s.count].x - s.points[i].x,
                                  s.points[(i + 1) % s.count].y - s.points[i].y);
        ck_assert(step <= s.perimeter / (s.count - s.segment_count) * (1 + 1e-9));
    }
    rugo_outline_samples_free(&s);
    /* The other elements: an open path and an ellipse. */
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "crack", &sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "shadow", &sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_ptr_nonnull(strstr(e.message, "<ellipse>"));
    ck_assert_int_eq(rugo_svg_import_outline(text, len, NULL, &sd, &s, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "layer1", &sd, &s, &e), RUGO_ERR_BAD_FIELD);
    free(text);
}
END_TEST

#ifdef RUGO_HAVE_FIT

static void fit_samples(const rugo_vec2* pts, int m, int n, rugo_outline_fit* f) {
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    fd.samples = pts;
    fd.sample_count = m;
    fd.control_count = n;
    rugo_status st = rugo_fit_outline(&fd, f);
    ck_assert_msg(st == RUGO_OK, "fit n=%d: %s", n, rugo_status_string(st));
}

/* tests/data/rock_inkscape_made.svg was made by Inkscape 1.2 (Debian bookworm), not by hand: from the
 * 24-vertex polygon of rock_inkscape_made.src.svg with
 *   inkscape rock_inkscape_made.src.svg --actions="select-by-id:rock;object-to-path;path-simplify;
 *            export-filename:rock_inkscape_made.svg;export-type:svg;export-do"
 * (Inkscape's own path data: 23 relative cubics closed by z, its namespaces and metadata). Perimeter
 * cross-checked once by an independent Python polyline of 2000 chords per cubic: 303.549721486 (the
 * chords fall short by O(1/N^2)). Fit errors pinned at 32 and 64 control points. */
START_TEST(inkscape_made_fit_error) {
    size_t len = 0;
    char* text = read_data("rock_inkscape_made.svg", &len);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "rock", &sd, &s, &e), RUGO_OK);
    free(text);
    ck_assert_near(s.perimeter, 303.549721486, 1e-6);
    rugo_outline_fit f32, f64;
    fit_samples(s.points, s.count, 32, &f32);
    fit_samples(s.points, s.count, 64, &f64);
    printf(
        "import: Inkscape-made rock, perimeter %.17g; n=32 max %.17g rms %.17g; n=64 max %.17g rms %.17g\n",
        s.perimeter, f32.max_error, f32.rms_error, f64.max_error, f64.rms_error);
    ck_assert_near(f32.max_error, 1.0599460193729771, 1e-9);
    ck_assert_near(f32.rms_error, 0.24871679163716404, 1e-9);
    ck_assert_near(f64.max_error, 0.37179376109272083, 1e-9);
    ck_assert_near(f64.rms_error, 0.069877479741542875, 1e-9);
    rugo_outline_fit_free(&f32);
    rugo_outline_fit_free(&f64);
    rugo_outline_samples_free(&s);
}
END_TEST

/* The rock at 32 and 64 control points: errors pinned to the independent Python values (which agree
 * with these to 3e-13); corners make the error fall as 1/n. */
START_TEST(rock_fit_error) {
    size_t len = 0;
    char* text = read_data("rock_inkscape.svg", &len);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_import_outline(text, len, "rock", &sd, &s, &e), RUGO_OK);
    free(text);
    rugo_outline_fit f32, f64;
    fit_samples(s.points, s.count, 32, &f32);
    fit_samples(s.points, s.count, 64, &f64);
    printf("import: rock n=32 max %.17g rms %.17g; n=64 max %.17g rms %.17g\n", f32.max_error, f32.rms_error,
           f64.max_error, f64.rms_error);
    ck_assert_near(f32.max_error, 0.318609779069381, 1e-9);
    ck_assert_near(f32.rms_error, 0.060787653237868, 1e-9);
    ck_assert_near(f64.max_error, 0.159069876479946, 1e-9);
    ck_assert_near(f64.rms_error, 0.0187383065573883, 1e-9);
    ck_assert_int_eq(f32.control_count, 32);
    ck_assert(f32.max_error <= f32.max_error_at_parameter);
    ck_assert(f32.rms_error <= f32.max_error);
    ck_assert(f32.tolerance_met);
    ck_assert(!f32.reversed); /* the samples were counter-clockwise already */
    rugo_contour c = {f64.control_points, 64};
    ck_assert(rugo_contour_signed_area(c) > 0);
    ck_assert_int_eq(rugo_contour_check(f64.control_points, 64, RUGO_CHECK_ALL, NULL, NULL), RUGO_OK);
    /* The fitted area is the outline's within the band the errors allow. */
    ck_assert_near(rugo_contour_signed_area(c), s.area, s.perimeter * f64.max_error);
    rugo_outline_fit_free(&f32);
    rugo_outline_fit_free(&f64);
    ck_assert_ptr_null(f64.control_points);
    rugo_outline_fit_free(NULL);
    rugo_outline_samples_free(&s);
}
END_TEST

/* The circle of four arcs (r = 10, 4096 samples at equal angles): max and rms distance at 16 and 32
 * control points, pinned to the Python values (3.42586344810131e-4 / 2.24767141639678e-4 and
 * 2.08337941103309e-5 / 1.36464781677137e-5; the Python closest points are a golden-section search,
 * good to ~1e-13 here). */
START_TEST(circle_fit_error) {
    rugo_path p;
    parse_ok("M 10 0 A 10 10 0 0 1 0 10 A 10 10 0 0 1 -10 0 A 10 10 0 0 1 0 -10 A 10 10 0 0 1 10 0 Z", &p);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 0, &s);
    rugo_outline_fit f16, f32;
    fit_samples(s.points, s.count, 16, &f16);
    fit_samples(s.points, s.count, 32, &f32);
    ck_assert_near(f16.max_error, 3.42586344810131e-4, 1e-13);
    ck_assert_near(f16.rms_error, 2.24767141639678e-4, 1e-13);
    ck_assert_near(f32.max_error, 2.08337941103309e-5, 1e-13);
    ck_assert_near(f32.rms_error, 1.36464781677137e-5, 1e-13);
    /* A smooth outline: the error falls as n^-4 (16x per doubling), unlike the rock's corners. */
    ck_assert(f16.max_error / f32.max_error > 14 && f16.max_error / f32.max_error < 18);
    rugo_outline_fit_free(&f16);
    rugo_outline_fit_free(&f32);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

/* The automatic count is the smallest power of two that meets the tolerance; a tolerance out of reach
 * stops at the largest count allowed with tolerance_met 0. */
START_TEST(automatic_control_count) {
    rugo_path p;
    parse_ok("M 10 0 A 10 10 0 0 1 0 10 A 10 10 0 0 1 -10 0 A 10 10 0 0 1 0 -10 A 10 10 0 0 1 10 0 Z", &p);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), 0, &s);
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    ck_assert_int_eq(fd.max_control_count, RUGO_DEFAULT_MAX_FIT_CONTROL_POINTS);
    fd.samples = s.points;
    fd.sample_count = s.count;
    fd.tolerance = 1e-4; /* between the 16- and 32-point errors */
    rugo_outline_fit f;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
    ck_assert_int_eq(f.control_count, 32);
    ck_assert(f.tolerance_met);
    ck_assert(f.max_error <= 1e-4);
    rugo_outline_fit_free(&f);
    fd.tolerance = 1e-30;
    fd.max_control_count = 64;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
    ck_assert_int_eq(f.control_count, 64);
    ck_assert(!f.tolerance_met);
    rugo_outline_fit_free(&f);
    /* The search also stops at sample_count / 4 (100 samples: 16). */
    rugo_outline_samples_free(&s);
    sample_ok(&p, -1, rugo_affine_identity(), 100, &s);
    fd.samples = s.points;
    fd.sample_count = s.count;
    fd.max_control_count = 1 << 20;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
    ck_assert_int_eq(f.control_count, 16);
    ck_assert(!f.tolerance_met);
    rugo_outline_fit_free(&f);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
}
END_TEST

/* A circle of radius 1e-300 (and 1e300): every squared distance underflowed (overflowed) and the fit
 * reported an error of 0. The fit runs on the samples scaled by a power of two, so its errors are
 * those of the unit circle's fit times the radius, and a power-of-two radius gives exactly the scaled
 * control points. */
START_TEST(fit_outline_extreme_radius) {
    enum { M = 64, N = 16 };
    rugo_vec2 unit[M], tiny[M];
    for (int i = 0; i < M; ++i)
        unit[i] = rugo_v2(cos(2 * PI * i / M), sin(2 * PI * i / M));
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    fd.samples = unit;
    fd.sample_count = M;
    fd.control_count = N;
    rugo_outline_fit ref, f;
    ck_assert_int_eq(rugo_fit_outline(&fd, &ref), RUGO_OK);
    ck_assert(ref.max_error > 1e-6 && ref.max_error < 1e-2); /* the cubic's deviation from a circle */
    const double radii[4] = {1e-300, 1e300, 0x1p-997, 0x1p+997};
    for (int v = 0; v < 4; ++v) {
        for (int i = 0; i < M; ++i)
            tiny[i] = rugo_v2_scale(radii[v], unit[i]);
        fd.samples = tiny;
        ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
        ck_assert_int_eq(f.control_count, N);
        ck_assert_msg(fabs(f.max_error / radii[v] - ref.max_error) <= 1e-9 * ref.max_error,
                      "radius %g: max_error %g", radii[v], f.max_error);
        ck_assert(fabs(f.rms_error / radii[v] - ref.rms_error) <= 1e-9 * ref.rms_error);
        ck_assert(fabs(f.max_error_at_parameter / radii[v] - ref.max_error_at_parameter) <=
                  1e-9 * ref.max_error_at_parameter);
        for (int j = 0; j < N; ++j) {
            if (v >= 2) { /* a power of two: the same bits, scaled */
                ck_assert(f.control_points[j].x == radii[v] * ref.control_points[j].x);
                ck_assert(f.control_points[j].y == radii[v] * ref.control_points[j].y);
            } else {
                ck_assert(fabs(f.control_points[j].x / radii[v] - ref.control_points[j].x) <= 1e-12);
                ck_assert(fabs(f.control_points[j].y / radii[v] - ref.control_points[j].y) <= 1e-12);
            }
        }
        rugo_outline_fit_free(&f);
    }
    /* The automatic search on the tiny circle finds the count the unit circle's would. */
    rugo_outline_fit_free(&ref);
    fd.control_count = 0;
    fd.samples = unit;
    fd.tolerance = 1e-4;
    ck_assert_int_eq(rugo_fit_outline(&fd, &ref), RUGO_OK);
    for (int i = 0; i < M; ++i)
        tiny[i] = rugo_v2_scale(1e-300, unit[i]);
    fd.samples = tiny;
    fd.tolerance = 1e-304;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
    ck_assert_int_eq(f.control_count, ref.control_count);
    ck_assert_int_eq(f.tolerance_met, ref.tolerance_met);
    rugo_outline_fit_free(&f);
    rugo_outline_fit_free(&ref);
}
END_TEST

START_TEST(fit_bad_input) {
    rugo_vec2 pts[64];
    for (int i = 0; i < 64; ++i)
        pts[i] = rugo_v2(cos(2 * PI * i / 64), sin(2 * PI * i / 64));
    rugo_outline_fit f;
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    fd.samples = pts;
    fd.sample_count = 64;
    ck_assert_int_eq(rugo_fit_outline(NULL, &f), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_fit_outline(&fd, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_BAD_ARGUMENT); /* automatic without a tolerance */
    fd.tolerance = NAN;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_BAD_ARGUMENT);
    fd.tolerance = 1e-3;
    fd.max_control_count = 48;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_NOT_POWER_OF_TWO);
    fd.max_control_count = 2;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_BAD_ARGUMENT);
    fd.max_control_count = 2 * RUGO_MAX_CONTROL_POINTS;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_TOO_MANY_POINTS);
    fd.max_control_count = 64;
    fd.sample_count = 15;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_TOO_FEW_POINTS);
    fd.sample_count = 64;
    fd.control_count = 12;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_NOT_POWER_OF_TWO);
    fd.control_count = -8;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_TOO_FEW_POINTS);
    fd.control_count = 128; /* more than the samples */
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_BAD_ARGUMENT);
    fd.control_count = 8;
    pts[5] = pts[4]; /* a repeated sample: zero chord */
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_BAD_ARGUMENT);
    pts[5].x = INFINITY;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_ERR_NOT_FINITE);
    ck_assert_ptr_null(f.control_points);
    rugo_outline_fit_def bad = fd;
    bad.cookie = 1;
    ck_assert_int_eq(rugo_fit_outline(&bad, &f), RUGO_ERR_BAD_ARGUMENT);
    bad = fd;
    bad.samples = NULL;
    ck_assert_int_eq(rugo_fit_outline(&bad, &f), RUGO_ERR_NULL_ARGUMENT);
    /* A clockwise input comes out counter-clockwise, flagged. */
    for (int i = 0; i < 64; ++i)
        pts[i] = rugo_v2(cos(-2 * PI * i / 64), sin(-2 * PI * i / 64));
    fd.control_count = 8;
    ck_assert_int_eq(rugo_fit_outline(&fd, &f), RUGO_OK);
    ck_assert(f.reversed);
    rugo_contour c = {f.control_points, 8};
    ck_assert(rugo_contour_signed_area(c) > 0);
    rugo_outline_fit_free(&f);
}
END_TEST

/* A point list through the same pipeline: the 64 points of circle64_points.json as samples (M = the
 * point count keeps them as they are) give exactly the fit `rugo fit` computes from them. */
START_TEST(points_pipeline_matches_fit_contour) {
    size_t len = 0;
    char* text = read_data("circle64_points.json", &len);
    rugo_point_list list;
    ck_assert_int_eq(rugo_points_text_parse(text, len, NULL, &list, NULL), RUGO_OK);
    free(text);
    const rugo_vec2* pts = list.points;
    const int n = list.count;
    rugo_path p;
    ck_assert_int_eq(rugo_path_from_points(pts, n, NULL, &p), RUGO_OK);
    rugo_outline_samples s;
    sample_ok(&p, -1, rugo_affine_identity(), n, &s);
    ck_assert_int_eq(s.count, n);
    const bool flip = s.reversed;
    for (int i = 0; i < n; ++i) {
        const rugo_vec2 q = pts[flip ? (n - i) % n : i];
        ck_assert(s.points[i].x == q.x && s.points[i].y == q.y);
    }
    rugo_outline_fit f;
    fit_samples(s.points, s.count, 16, &f);
    rugo_fit_def fd = rugo_default_fit_def();
    fd.samples = s.points;
    fd.sample_count = s.count;
    fd.control_count = 16;
    rugo_vec2 ctrl[16];
    rugo_fit_result r;
    ck_assert_int_eq(rugo_fit_contour(&fd, ctrl, &r), RUGO_OK);
    rugo_contour_orient_ccw(ctrl, 16);
    ck_assert_int_eq(memcmp(ctrl, f.control_points, sizeof ctrl), 0);
    ck_assert(f.max_error_at_parameter == r.max_error);
    ck_assert(f.max_error <= r.max_error);
    rugo_outline_fit_free(&f);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
    rugo_point_list_free(&list);
}
END_TEST

#endif /* RUGO_HAVE_FIT */

/* ---- units and placement (rugo_svg_read_viewport, rugo_import_outline) ------------------------ */

START_TEST(viewport_maps_user_units_to_px) {
    rugo_svg_viewport vp;
    rugo_parse_error e;
    /* Inkscape's A4 page: 210 mm wide, a viewBox of 210 user units: 1 unit = 1 mm = 96 / 25.4 px */
    size_t len = 0;
    char* text = read_data("rock_inkscape.svg", &len);
    ck_assert_int_eq(rugo_svg_read_viewport(text, len, &vp, &e), RUGO_OK);
    free(text);
    ck_assert(vp.has_viewbox && vp.has_width && vp.has_height);
    ck_assert_near(vp.width, 210.0 * 96.0 / 25.4, 1e-9);
    ck_assert_near(vp.user_to_px.a, 96.0 / 25.4, 1e-12);
    ck_assert(vp.user_to_px.b == 0.0 && vp.user_to_px.c == 0.0);
    ck_assert_near(vp.user_to_px.d, 96.0 / 25.4, 1e-12);
    /* an offset viewBox, letterboxed (meet) into a wider viewport: centred in x */
    const char* doc =
        "<?xml version='1.0'?><!-- c --><svg width='400' height='100' viewBox='10 20 100 100'/>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_OK);
    rugo_vec2 q = rugo_affine_apply(vp.user_to_px, rugo_v2(10.0, 20.0));
    ck_assert_near(q.x, 150.0, 1e-12);
    ck_assert_near(q.y, 0.0, 1e-12);
    /* no viewBox: user units are px; relative sizes are reported as unknown */
    doc = "<svg width='50%' height='3in'><path d='M0 0'/></svg>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_OK);
    ck_assert(!vp.has_viewbox && !vp.has_width && vp.has_height && vp.height == 288.0);
    ck_assert(vp.user_to_px.a == 1.0 && vp.user_to_px.e == 0.0);
}
END_TEST

START_TEST(viewport_bad_input) {
    rugo_svg_viewport vp;
    rugo_parse_error e;
    const char* doc = "<svg viewBox='0 0 0 10'/>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(e.path, "svg/viewBox");
    ck_assert_ptr_nonnull(strstr(e.message, "width 0"));
    doc = "<svg viewBox='0 0 10'/>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_ERR_PARSE);
    ck_assert_int_eq(e.line, 1);
    doc = "<svg width='-3mm'/>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(e.path, "svg/width");
    doc = "<html/>";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_ERR_BAD_FIELD);
    doc = "<!-- unterminated";
    ck_assert_int_eq(rugo_svg_read_viewport(doc, strlen(doc), &vp, &e), RUGO_ERR_PARSE);
    ck_assert_int_eq(rugo_svg_read_viewport(NULL, 0, &vp, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert(vp.user_to_px.a == 1.0); /* zeroed with an identity map */
}
END_TEST

/* A symmetric bow-tie encloses no area: the import says it crosses itself, where the artist drew it. */
START_TEST(bow_tie_is_self_intersecting) {
    const char* doc = "<svg><g transform='translate(100 50)'><path d='M0 0 L20 20 L20 0 L0 20 Z'/></g></svg>";
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    rugo_outline_samples s;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_svg_import_outline(doc, strlen(doc), NULL, &sd, &s, &e),
                     RUGO_ERR_SELF_INTERSECTING);
    ck_assert_ptr_nonnull(strstr(e.message, "self-intersecting"));
    ck_assert_ptr_nonnull(strstr(e.message, "(110, 60)")); /* the crossing in the drawing's user units */
    rugo_path p;
    parse_ok("M0 0 L20 20 L20 0 L0 20 Z", &p);
    rugo_vec2 w;
    ck_assert_int_eq(rugo_path_find_crossing(&p, -1, rugo_affine_identity(), &w), 1);
    ck_assert(w.x == 10.0 && w.y == 10.0);
    ck_assert_int_eq(rugo_path_find_crossing(&p, 1, rugo_affine_identity(), &w), 0); /* no subpath 1 */
    rugo_path_free(&p);
    parse_ok("M0 0 L20 0 L20 20 L0 20 Z", &p); /* a square: no crossing */
    ck_assert_int_eq(rugo_path_find_crossing(&p, 0, rugo_affine_identity(), &w), 0);
    rugo_path_free(&p);
    ck_assert_int_eq(rugo_path_find_crossing(NULL, 0, rugo_affine_identity(), &w), 0);
}
END_TEST

#ifdef RUGO_HAVE_FIT
/* The pebble: 250 px across, a game at 100 px per metre: a 2.5 m shape at the origin, with the
 * fit error in metres. */
START_TEST(import_with_units_and_recentring) {
    static const char svg[] =
        "<svg><path d='M 300 200 A 125 125 0 0 1 550 200 A 125 125 0 0 1 300 200 Z'/></svg>";
    rugo_import_def def = rugo_default_import_def();
    ck_assert(def.scale == 1.0 && def.max_size == RUGO_DEFAULT_IMPORT_MAX_SIZE && !def.recentre);
    def.text = svg;
    def.length = strlen(svg);
    rugo_import_result px, m;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_import_outline(&def, &px, &e), RUGO_OK);
    def.scale = 0.01;
    def.recentre = 1;
    ck_assert_int_eq(rugo_import_outline(&def, &m, &e), RUGO_OK);
    ck_assert_int_eq(px.fit.control_count, m.fit.control_count);
    ck_assert(px.from_svg == 1);
    rugo_contour cm = {m.fit.control_points, m.fit.control_count};
    rugo_mass_properties mp = rugo_contour_mass_properties(cm);
    ck_assert_near(mp.area, PI * 1.25 * 1.25, 2e-4);
    ck_assert(fabs(mp.centroid.x) < 1e-12 && fabs(mp.centroid.y) < 1e-12);
    /* the offset moved the centre (425, -200) px = (4.25, -2) m to the origin */
    ck_assert_near(m.offset.x, -4.25, 1e-6);
    ck_assert_near(m.offset.y, 2.0, 1e-6);
    /* errors and sizes in output units: the metres run is the pixels run scaled by 1/100 */
    ck_assert_near(m.size, px.size / 100.0, 1e-12 * px.size);
    ck_assert_near(m.tolerance, px.tolerance / 100.0, 1e-12 * px.tolerance);
    ck_assert_near(m.fit.max_error, px.fit.max_error / 100.0, 1e-6 * px.fit.max_error);
    ck_assert(m.fit.max_error <= m.tolerance && m.fit.tolerance_met);
    /* the maps: the drawing's top point (425, 75), y down, is the output's top (0, 1.25) */
    rugo_vec2 top = rugo_affine_apply(m.drawing_to_output, rugo_v2(425.0, 75.0));
    ck_assert_near(top.x, 0.0, 1e-6);
    ck_assert_near(top.y, 1.25, 1e-6);
    rugo_vec2 back = rugo_affine_apply(m.output_to_drawing, top);
    ck_assert_near(back.x, 425.0, 1e-9);
    ck_assert_near(back.y, 75.0, 1e-9);
    rugo_import_result_free(&px);
    rugo_import_result_free(&m);
    ck_assert_ptr_null(m.fit.control_points);
}
END_TEST

/* --viewbox: the A4 Inkscape rock measured in mm, at 1000 px per metre... via the px of the viewport. */
START_TEST(import_honours_viewbox) {
    size_t len = 0;
    char* text = read_data("rock_inkscape.svg", &len);
    rugo_import_def def = rugo_default_import_def();
    def.text = text;
    def.length = len;
    def.path_id = "rock";
    rugo_import_result user, vb;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_import_outline(&def, &user, &e), RUGO_OK);
    def.use_viewbox = 1;
    ck_assert_int_eq(rugo_import_outline(&def, &vb, &e), RUGO_OK);
    ck_assert_near(vb.size, user.size * 96.0 / 25.4, 1e-9 * vb.size);
    /* with --viewbox and a scale of 25.4 / 96 / 1000 the output is in metres: mm / 1000 */
    rugo_import_result mm;
    def.scale = 25.4 / 96.0 / 1000.0;
    ck_assert_int_eq(rugo_import_outline(&def, &mm, &e), RUGO_OK);
    ck_assert_near(mm.size, user.size / 1000.0, 1e-9 * mm.size);
    rugo_import_result_free(&user);
    rugo_import_result_free(&vb);
    rugo_import_result_free(&mm);
    free(text);
}
END_TEST

START_TEST(import_errors_name_field_value_and_way_out) {
    static const char svg[] = "<svg><path d='M 0 0 L 100 0 L 100 100 L 0 100 Z'/></svg>";
    rugo_import_def def = rugo_default_import_def();
    def.text = svg;
    def.length = strlen(svg);
    rugo_import_result r;
    rugo_parse_error e;
    /* a control count that is not a power of two: the message says which counts work */
    def.control_count = 5;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_NOT_POWER_OF_TWO);
    ck_assert_str_eq(e.path, "control_count");
    ck_assert_ptr_nonnull(strstr(e.message, "is 5"));
    ck_assert_ptr_nonnull(strstr(e.message, "use 4 or 8"));
    def.control_count = 0;
    /* a bad scale */
    def.scale = 0.0;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_str_eq(e.path, "scale");
    ck_assert_ptr_nonnull(strstr(e.message, "is 0"));
    def.scale = NAN;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    /* an absurd size: refused with a status, the size and a scale that fixes it */
    def.scale = 1e28;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_SIZE);
    ck_assert_str_eq(e.path, "scale");
    ck_assert_ptr_nonnull(strstr(e.message, "1.41421e+30 units across"));
    ck_assert_ptr_nonnull(strstr(e.message, "max_size"));
    def.scale = 1.0;
    def.max_size = 100.0; /* the 141-unit square exceeds it */
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_SIZE);
    def.max_size = RUGO_DEFAULT_IMPORT_MAX_SIZE;
    def.tolerance = -1.0;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_str_eq(e.path, "tolerance");
    def.tolerance = 0.0;
    /* a bow-tie: self-intersecting, in the drawing's coordinates */
    static const char bow[] = "<svg><path d='M0 0 L20 20 L20 0 L0 20 Z'/></svg>";
    def.text = bow;
    def.length = strlen(bow);
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_SELF_INTERSECTING);
    ck_assert_ptr_nonnull(strstr(e.message, "(10, 10)"));
    /* the same as a point list */
    static const char pts[] = "0,0\n20,20\n20,0\n0,20\n";
    def.text = pts;
    def.length = strlen(pts);
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_SELF_INTERSECTING);
    ck_assert_ptr_nonnull(strstr(e.message, "(10, 10)"));
    /* SVG-only options on a point list */
    def.use_viewbox = 1;
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_str_eq(e.path, "use_viewbox");
    def.use_viewbox = 0;
    def.path_id = "rock";
    ck_assert_int_eq(rugo_import_outline(&def, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_str_eq(e.path, "path_id");
    /* NULLs and an uninitialised def */
    ck_assert_int_eq(rugo_import_outline(NULL, &r, &e), RUGO_ERR_NULL_ARGUMENT);
    rugo_import_def raw;
    memset(&raw, 0, sizeof raw);
    raw.text = pts;
    ck_assert_int_eq(rugo_import_outline(&raw, &r, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_null(r.fit.control_points);
    rugo_import_result_free(NULL);
}
END_TEST
#endif

static Suite* import_suite(void) {
    Suite* s = suite_create("import");
    TCase* tp = tcase_create("path_data");
    tcase_add_test(tp, absolute_commands);
    tcase_add_test(tp, relative_commands);
    tcase_add_test(tp, curve_points);
    tcase_add_test(tp, smooth_reflection_rules);
    tcase_add_test(tp, arcs);
    tcase_add_test(tp, implicit_commands);
    tcase_add_test(tp, number_syntax);
    tcase_add_test(tp, bad_path_data);
    tcase_add_test(tp, allocation_failures);
    tcase_add_test(tp, transform_lists);
    tcase_add_test(tp, bad_transforms);
    suite_add_tcase(s, tp);

    TCase* td = tcase_create("svg_document");
    tcase_add_test(td, find_path_in_document);
    tcase_add_test(td, bad_documents);
    tcase_add_test(td, document_error_positions);
    tcase_add_test(td, rock_samples);
    suite_add_tcase(s, td);

    TCase* ts = tcase_create("sampling");
    tcase_add_test(ts, sample_square_by_hand);
    tcase_add_test(ts, sample_cusp_arc_length);
    tcase_add_test(ts, sample_circle_of_arcs);
    tcase_add_test(ts, sample_circle_of_cubics);
    tcase_add_test(ts, sample_subpath_choice);
    tcase_add_test(ts, sample_bad_input);
    tcase_add_test(ts, sample_deterministic_and_on_curve);
    tcase_add_test(ts, sample_overflowing_lengths);
    tcase_add_test(ts, points_text);
    tcase_add_test(ts, bad_points_text);
    tcase_add_test(ts, path_from_points);
    tcase_add_test(ts, path_from_points_all_equal);
    tcase_add_test(ts, viewport_maps_user_units_to_px);
    tcase_add_test(ts, viewport_bad_input);
    tcase_add_test(ts, bow_tie_is_self_intersecting);
    suite_add_tcase(s, ts);

#ifdef RUGO_HAVE_FIT
    TCase* tf = tcase_create("fit");
    tcase_set_timeout(tf, 120);
    tcase_add_test(tf, rock_fit_error);
    tcase_add_test(tf, inkscape_made_fit_error);
    tcase_add_test(tf, circle_fit_error);
    tcase_add_test(tf, automatic_control_count);
    tcase_add_test(tf, fit_bad_input);
    tcase_add_test(tf, fit_outline_extreme_radius);
    tcase_add_test(tf, points_pipeline_matches_fit_contour);
    tcase_add_test(tf, import_with_units_and_recentring);
    tcase_add_test(tf, import_honours_viewbox);
    tcase_add_test(tf, import_errors_name_field_value_and_way_out);
    suite_add_tcase(s, tf);
#endif
    return s;
}

int main(void) { return test_run_suite(import_suite()); }
