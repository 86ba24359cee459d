/* docs/bad_input.md as tests: every row of the bad-input table, with the status it must get. Rows
 * that another suite covers in depth are checked here once more by their representative input. */
#include "rugo/rugo.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Parses text and, if it parses, builds the shape (with its roughness): the first failing status. */
static rugo_status json_to_shape(const char* text) {
    rugo_shape_desc d;
    rugo_parse_error e;
    rugo_status st = rugo_shape_desc_parse(text, strlen(text), NULL, &d, &e);
    if (st != RUGO_OK) {
        ck_assert(e.message[0] != '\0'); /* every parse failure says why */
        return st;
    }
    rugo_real* lam = NULL;
    rugo_shape_def def = rugo_default_shape_def();
    def.points = d.control_points;
    def.count = d.count;
    def.filter = d.filter;
    if (d.has_roughness && d.count > 0) {
        lam = (rugo_real*)malloc(sizeof *lam * (size_t)d.count);
        rugo_contour c = {d.control_points, d.count}; /* arc-length roughness needs the curve */
        st = rugo_roughness_tolerances_on_contour(&d.roughness, c, NULL, lam);
        def.tolerances = lam;
        def.q = d.roughness.q;
        def.friction = d.roughness.friction;
        def.restitution = d.roughness.restitution;
    }
    rugo_shape* s = NULL;
    if (st == RUGO_OK) st = rugo_shape_create(&def, &s, NULL);
    rugo_shape_destroy(s);
    free(lam);
    rugo_shape_desc_free(&d);
    return st;
}

typedef struct row {
    const char* what;
    const char* json;
    rugo_status expect;
} row;

#define SQ "[[0,0],[1,0],[1,1],[0,1]]"
static const row ROWS[] = {
    {"empty text", "", RUGO_ERR_PARSE},
    {"syntax error", "{\"control_points\": [[0,0] [1,0]]}", RUGO_ERR_PARSE},
    {"trailing garbage", "{\"control_points\": " SQ "} x", RUGO_ERR_PARSE},
    {"unterminated string", "{\"control_points", RUGO_ERR_PARSE},
    {"not an object", "[1, 2]", RUGO_ERR_BAD_FIELD},
    {"missing control_points", "{\"points\": " SQ "}", RUGO_ERR_BAD_FIELD},
    {"point of wrong type", "{\"control_points\": [[0,0],[1,\"x\"],[1,1],[0,1]]}", RUGO_ERR_BAD_FIELD},
    {"point with three numbers", "{\"control_points\": [[0,0,0],[1,0],[1,1],[0,1]]}", RUGO_ERR_BAD_FIELD},
    {"duplicate member", "{\"control_points\": " SQ ", \"control_points\": " SQ "}", RUGO_ERR_BAD_FIELD},
    {"NaN literal", "{\"control_points\": [[0,0],[NaN,0],[1,1],[0,1]]}", RUGO_ERR_PARSE},
    {"number overflowing to infinity", "{\"control_points\": [[0,0],[1e999,0],[1,1],[0,1]]}",
     RUGO_ERR_NOT_FINITE},
    {"coordinates whose area overflows", "{\"control_points\": [[0,0],[1e300,0],[1e300,1e300],[0,1e300]]}",
     RUGO_ERR_NOT_FINITE},
    {"unknown filter", "{\"control_points\": " SQ ", \"filter\": \"haar\"}", RUGO_ERR_BAD_FILTER},
    {"too few points", "{\"control_points\": [[0,0],[1,0],[0,1]]}", RUGO_ERR_TOO_FEW_POINTS},
    {"empty point list (parses as NULL, 0)", "{\"control_points\": []}", RUGO_ERR_NULL_ARGUMENT},
    {"count not a power of two", "{\"control_points\": [[0,0],[1,0],[2,1],[1,2],[0,1],[-1,1]]}",
     RUGO_ERR_NOT_POWER_OF_TWO},
    {"zero area (collinear)", "{\"control_points\": [[0,0],[1,1],[2,2],[3,3]]}", RUGO_ERR_ZERO_AREA},
    {"zero area (coincident)", "{\"control_points\": [[1,1],[1,1],[1,1],[1,1]]}", RUGO_ERR_ZERO_AREA},
    {"self-intersecting outline",
     "{\"control_points\": "
     "[[1,0],[0.92388,0.353553],[0.707107,0.5],[0.382683,0.353553],[0,0],[-0.191342,-0.176777],"
     "[-0.353553,-0.25],[-0.46194,-0.176777],[-0.5,0],[-0.46194,0.176777],[-0.353553,0.25],[-0.191342,0."
     "176777],"
     "[0,0],[0.382683,-0.353553],[0.707107,-0.5],[0.92388,-0.353553]]}",
     RUGO_ERR_SELF_INTERSECTING},
    {"negative tolerance", "{\"control_points\": " SQ ", \"roughness\": {\"constant\": -0.1}}",
     RUGO_ERR_NEGATIVE_TOLERANCE},
    {"tolerance list of wrong length", "{\"control_points\": " SQ ", \"roughness\": {\"tolerances\": [0.1]}}",
     RUGO_ERR_BAD_FIELD},
    {"q not positive", "{\"control_points\": " SQ ", \"roughness\": {\"constant\": 0.1, \"q\": 0}}",
     RUGO_ERR_BAD_QUANTILE},
    {"friction alpha negative",
     "{\"control_points\": " SQ ", \"roughness\": {\"constant\": 0.1, \"friction\": {\"alpha\": -1}}}",
     RUGO_ERR_BAD_ARGUMENT},
    {"restitution above 1",
     "{\"control_points\": " SQ ", \"roughness\": {\"constant\": 0.1, \"restitution\": {\"epsilon\": 2}}}",
     RUGO_ERR_BAD_ARGUMENT},
    {"restitution range empty",
     "{\"control_points\": " SQ
     ", \"roughness\": {\"constant\": 0.1, \"restitution\": {\"epsilon\": 0.9, \"epsilon_max\": 0.5}}}",
     RUGO_ERR_EMPTY_RANGE},
    {"seed beyond 2^53",
     "{\"control_points\": " SQ ", \"roughness\": {\"preset\": \"tipo_2\", \"seed\": 9007199254740993}}",
     RUGO_ERR_BAD_FIELD},
    {"unknown preset", "{\"control_points\": " SQ ", \"roughness\": {\"preset\": \"tipo_9\"}}",
     RUGO_ERR_BAD_FIELD},
    {"range from outside [0, 1]",
     "{\"control_points\": " SQ
     ", \"roughness\": {\"ranges\": [{\"from\": -0.1, \"to\": 0.5, \"tolerance\": 0.1}]}}",
     RUGO_ERR_BAD_FIELD},
    {"empty range",
     "{\"control_points\": " SQ
     ", \"roughness\": {\"ranges\": [{\"from\": 0.5, \"to\": 0.5, \"tolerance\": 0.1}]}}",
     RUGO_ERR_BAD_FIELD},
    {"range without tolerance",
     "{\"control_points\": " SQ ", \"roughness\": {\"ranges\": [{\"from\": 0.1, \"to\": 0.5}]}}",
     RUGO_ERR_BAD_FIELD},
    {"negative range tolerance",
     "{\"control_points\": " SQ
     ", \"roughness\": {\"ranges\": [{\"from\": 0.1, \"to\": 0.5, \"tolerance\": -0.1}]}}",
     RUGO_ERR_NEGATIVE_TOLERANCE},
    {"negative background",
     "{\"control_points\": " SQ ", \"roughness\": {\"ranges\": [], \"background\": -1}}",
     RUGO_ERR_NEGATIVE_TOLERANCE},
    {"empty profile", "{\"control_points\": " SQ ", \"roughness\": {\"profile\": []}}", RUGO_ERR_BAD_FIELD},
    {"profile s outside [0, 1]",
     "{\"control_points\": " SQ ", \"roughness\": {\"profile\": [[0, 0.1], [2, 0.1]]}}", RUGO_ERR_BAD_FIELD},
    {"profile s not increasing",
     "{\"control_points\": " SQ ", \"roughness\": {\"profile\": [[0.5, 0.1], [0.5, 0.2]]}}",
     RUGO_ERR_BAD_FIELD},
    {"negative profile tolerance",
     "{\"control_points\": " SQ ", \"roughness\": {\"profile\": [[0.5, -0.1]]}}",
     RUGO_ERR_NEGATIVE_TOLERANCE},
    {"ranges and profile both",
     "{\"control_points\": " SQ ", \"roughness\": {\"ranges\": [], \"profile\": [[0, 0]]}}",
     RUGO_ERR_BAD_FIELD},
    {"ranges on too few points", "{\"control_points\": [[0,0],[1,0],[0,1]], \"roughness\": {\"ranges\": []}}",
     RUGO_ERR_TOO_FEW_POINTS},
    {"ranges on a curve of no length",
     "{\"control_points\": [[1,1],[1,1],[1,1],[1,1]], \"roughness\": {\"ranges\": []}}", RUGO_ERR_ZERO_AREA},
    {"valid ranges (control row: builds)",
     "{\"control_points\": " SQ
     ", \"roughness\": {\"ranges\": [{\"from\": 0.9, \"to\": 0.1, \"tolerance\": 0.1}]}}",
     RUGO_OK},
    {"valid profile (control row: builds)",
     "{\"control_points\": " SQ ", \"roughness\": {\"profile\": [[0, 0], [0.5, 0.1]]}}", RUGO_OK},
};

/* CSV roughness profiles (rugo_roughness_profile_parse_csv). */
static const row CSV_ROWS[] = {
    {"no samples", "s,lambda\n", RUGO_ERR_BAD_FIELD},
    {"one field", "0.1\n", RUGO_ERR_PARSE},
    {"three fields", "0.1,0.2,0.3\n", RUGO_ERR_PARSE},
    {"not a number", "0.1,abc\n", RUGO_ERR_PARSE},
    {"empty field", "0.1,\n", RUGO_ERR_PARSE},
    {"NaN", "nan,0.1\n", RUGO_ERR_NOT_FINITE},
    {"infinity", "0.1,inf\n", RUGO_ERR_NOT_FINITE},
    {"overflow", "0.1,1e999\n", RUGO_ERR_NOT_FINITE},
    {"s outside [0, 1]", "1.5,0.1\n", RUGO_ERR_BAD_FIELD},
    {"s not increasing", "0.5,0.1\n0.25,0.1\n", RUGO_ERR_BAD_FIELD},
    {"negative tolerance", "0.5,-0.1\n", RUGO_ERR_NEGATIVE_TOLERANCE},
    {"valid (control row)", "s,lambda\n0,0.1\n0.5,0.2\n", RUGO_OK},
};

START_TEST(json_rows) {
    for (size_t i = 0; i < sizeof ROWS / sizeof ROWS[0]; ++i) {
        rugo_status st = json_to_shape(ROWS[i].json);
        ck_assert_msg(st == ROWS[i].expect, "%s: got %d (%s), expected %d (%s)", ROWS[i].what, st,
                      rugo_status_string(st), ROWS[i].expect, rugo_status_string(ROWS[i].expect));
        ck_assert(strlen(rugo_status_string(st)) > 0);
    }
}
END_TEST

START_TEST(csv_rows) {
    for (size_t i = 0; i < sizeof CSV_ROWS / sizeof CSV_ROWS[0]; ++i) {
        rugo_roughness_profile p;
        rugo_parse_error e;
        const char* t = CSV_ROWS[i].json;
        rugo_status st = rugo_roughness_profile_parse_csv(t, strlen(t), NULL, &p, &e);
        ck_assert_msg(st == CSV_ROWS[i].expect, "csv %s: got %d (%s), expected %d (%s)", CSV_ROWS[i].what, st,
                      rugo_status_string(st), CSV_ROWS[i].expect, rugo_status_string(CSV_ROWS[i].expect));
        if (st != RUGO_OK) ck_assert(e.message[0] != '\0' && e.line >= 1);
        rugo_roughness_profile_free(&p);
    }
}
END_TEST

START_TEST(huge_counts) {
    /* More control points than RUGO_MAX_CONTROL_POINTS: refused before any allocation of that size. */
    rugo_shape_def def = rugo_default_shape_def();
    rugo_vec2 p[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    def.points = p;
    def.count = RUGO_MAX_CONTROL_POINTS * 2;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_ERR_TOO_MANY_POINTS);
    def.count = -4;
    ck_assert_int_ne(rugo_shape_create(&def, &s, NULL), RUGO_OK);
    ck_assert_ptr_null(s);
    /* Nesting deeper than 64 is a parse error, not a stack overflow. */
    char deep[200];
    memset(deep, '[', 150);
    deep[150] = '\0';
    rugo_shape_desc d;
    ck_assert_int_eq(rugo_shape_desc_parse(deep, 150, NULL, &d, NULL), RUGO_ERR_PARSE);
    /* More than 2^16 ranges in a roughness object. */
    size_t cap = ((size_t)RUGO_MAX_ROUGHNESS_RANGES + 1) * 40 + 128, len = 0;
    char* big = (char*)malloc(cap);
    ck_assert_ptr_nonnull(big);
    len += (size_t)snprintf(big, cap, "{\"control_points\": %s, \"roughness\": {\"ranges\": [", SQ);
    for (int i = 0; i <= RUGO_MAX_ROUGHNESS_RANGES; ++i)
        len +=
            (size_t)snprintf(big + len, cap - len, "%s{\"from\":0,\"to\":1,\"tolerance\":0}", i ? "," : "");
    len += (size_t)snprintf(big + len, cap - len, "]}}");
    ck_assert_int_eq(rugo_shape_desc_parse(big, len, NULL, &d, NULL), RUGO_ERR_TOO_MANY_POINTS);
    free(big);
}
END_TEST

START_TEST(parameters_out_of_range) {
    rugo_vec2 p[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_shape_def def = rugo_default_shape_def();
    def.points = p;
    def.count = 4;
    rugo_shape* s = NULL;
    def.coarsest_level = 5; /* beyond the finest level 2 */
    ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_ERR_BAD_LEVEL);
    def = rugo_default_shape_def();
    def.points = p;
    def.count = 4;
    def.filter = RUGO_FILTER_COUNT;
    ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_ERR_BAD_FILTER);
    rugo_shape_def raw;
    memset(&raw, 0, sizeof raw); /* not from rugo_default_shape_def */
    raw.points = p;
    raw.count = 4;
    ck_assert_int_eq(rugo_shape_create(&raw, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_shape_create(NULL, &s, NULL), RUGO_ERR_NULL_ARGUMENT);
    def = rugo_default_shape_def();
    def.points = p;
    def.count = 4;
    ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_OK);
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    rugo_contact c[4];
    int n = 0;
    rugo_contact_state state;
    rugo_transform bad = rugo_make_transform(NAN, 0, 0);
    ck_assert_int_eq(
        test_collide_shapes(ctx, s, bad, s, rugo_identity_transform(), NULL, c, 4, &n, &state, NULL),
        RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(test_collide_shapes(ctx, s, rugo_identity_transform(), s, rugo_identity_transform(),
                                         NULL, c, -1, &n, &state, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_circle(ctx, s, rugo_identity_transform(), rugo_v2(0, 0), -1.0, NULL, c, 4,
                                         &n, &state, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    rugo_contact_query q = test_exact_query();
    q.margin = -1.0;
    ck_assert_int_eq(test_collide_shapes(ctx, s, rugo_identity_transform(), s, rugo_identity_transform(), &q,
                                         c, 4, &n, &state, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(s);
}
END_TEST

/* ---- SVG import and point lists (rugo/import.h): what `rugo import` does, step by step ---------- */

/* Path data through the import pipeline: parse, then sample the outer closed subpath. */
static rugo_status path_to_samples(const char* d, rugo_parse_error* e) {
    rugo_path p;
    rugo_status st = rugo_path_parse(d, strlen(d), NULL, &p, e);
    if (st != RUGO_OK) return st;
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = &p;
    rugo_outline_samples s;
    st = rugo_outline_sample(&sd, &s, e);
    rugo_outline_samples_free(&s);
    rugo_path_free(&p);
    return st;
}

/* A point list as `rugo import` reads it: parse, the closed polygon through the points, its samples. */
static rugo_status points_to_samples(const char* text, rugo_parse_error* e) {
    rugo_point_list pts;
    rugo_status st = rugo_points_text_parse(text, strlen(text), NULL, &pts, e);
    if (st != RUGO_OK) {
        ck_assert(pts.points == NULL && pts.count == 0);
        return st;
    }
    rugo_path p;
    st = rugo_path_from_points(pts.points, pts.count, NULL, &p);
    if (st == RUGO_OK) {
        rugo_outline_sample_def sd = rugo_default_outline_sample_def();
        sd.path = &p;
        sd.sample_count = pts.count;
        rugo_outline_samples s;
        st = rugo_outline_sample(&sd, &s, e);
        rugo_outline_samples_free(&s);
    }
    rugo_path_free(&p);
    rugo_point_list_free(&pts);
    return st;
}

/* kind 'd': path data (path_to_samples); 's': an SVG document (rugo_svg_import_outline with id);
 * 't': a transform list (rugo_svg_transform_parse); 'p': a point list (points_to_samples). located: the
 * error must carry a line and column (an error at a place in the text). */
typedef struct import_row {
    const char* what;
    char kind;
    const char* id;
    const char* text;
    rugo_status expect;
    int located;
} import_row;

#define DOC(body) "<svg xmlns='http://www.w3.org/2000/svg'>\n" body "\n</svg>"
#define SQUARE_D "M 0 0 H 10 V 10 H 0 Z"
static const import_row IMPORT_ROWS[] = {
    /* path data */
    {"no initial moveto", 'd', NULL, "L 1 1", RUGO_ERR_PARSE, 1},
    {"missing number", 'd', NULL, "M 0 0 L 1", RUGO_ERR_PARSE, 1},
    {"stray comma", 'd', NULL, "M 0 0 L 1 1, L 2 2", RUGO_ERR_PARSE, 1},
    {"numbers after Z", 'd', NULL, "M 0 0 L 1 0 L 0 1 Z 1 1", RUGO_ERR_PARSE, 1},
    {"arc flag not 0 or 1", 'd', NULL, "M 0 0 A 1 1 0 2 1 3 3", RUGO_ERR_PARSE, 1},
    {"unknown command", 'd', NULL, "M 0 0 X 1 1", RUGO_ERR_PARSE, 1},
    {"NaN text", 'd', NULL, "M 0 0 L nan 0 L 0 1 Z", RUGO_ERR_PARSE, 1},
    {"inf text", 'd', NULL, "M 0 0 L inf 0 L 0 1 Z", RUGO_ERR_PARSE, 1},
    {"hexadecimal number", 'd', NULL, "M 0 0 L 0x10 0 L 0 1 Z", RUGO_ERR_PARSE, 1},
    {"number overflowing to infinity", 'd', NULL, "M 0 0 L 1e999 0 L 0 1 Z", RUGO_ERR_NOT_FINITE, 1},
    {"coordinates whose sum overflows", 'd', NULL, "M 1e308 0 l 1e308 0 l 0 1 z", RUGO_ERR_NOT_FINITE, 1},
    {"lengths that overflow", 'd', NULL, "M -1.7e308 0 L 1.7e308 0 L 0 1 Z", RUGO_ERR_NOT_FINITE, 0},
    {"open path (no Z)", 'd', NULL, "M 0 0 L 10 0 L 10 10", RUGO_ERR_BAD_FIELD, 0},
    {"lone moveto", 'd', NULL, "M 5 5", RUGO_ERR_BAD_FIELD, 0},
    {"empty path data", 'd', NULL, "", RUGO_ERR_BAD_FIELD, 0},
    {"closed path enclosing no area", 'd', NULL, "M 0 0 L 10 0 Z", RUGO_ERR_ZERO_AREA, 0},
    {"valid path (control row)", 'd', NULL, SQUARE_D, RUGO_OK, 0},
    /* documents */
    {"id not found", 's', "b", DOC("<path id='a' d='" SQUARE_D "'/>"), RUGO_ERR_BAD_FIELD, 0},
    {"no <path> (no id given)", 's', NULL, DOC("<rect width='1' height='1'/>"), RUGO_ERR_BAD_FIELD, 0},
    {"several <path> and no id", 's', NULL, DOC("<path d='" SQUARE_D "'/><path d='" SQUARE_D "'/>"),
     RUGO_ERR_BAD_FIELD, 1},
    {"id of an element that is not a <path>", 's', "r", DOC("<rect id='r'/>"), RUGO_ERR_BAD_FIELD, 1},
    {"<path> without d", 's', "p", DOC("<path id='p'/>"), RUGO_ERR_BAD_FIELD, 1},
    {"malformed d in a document", 's', "p", DOC("<path id='p' d='M 0 0 L 1 x'/>"), RUGO_ERR_PARSE, 1},
    {"no closed subpath in a document", 's', "p", DOC("<path id='p' d='M 0 0 L 1 1'/>"), RUGO_ERR_BAD_FIELD,
     1},
    {"unterminated comment", 's', "p", DOC("<!-- <path id='p' d='" SQUARE_D "'/>"), RUGO_ERR_PARSE, 1},
    {"mismatched end tag", 's', "p", DOC("<g></a><path id='p' d='" SQUARE_D "'/>"), RUGO_ERR_PARSE, 1},
    {"unknown entity", 's', "p", DOC("<path id='p' d='M 0 0 &nbsp; H 1 V 1 Z'/>"), RUGO_ERR_PARSE, 1},
    {"attribute given twice", 's', "p", DOC("<path id='p' d='" SQUARE_D "' d='" SQUARE_D "'/>"),
     RUGO_ERR_PARSE, 1},
    {"unterminated attribute value", 's', "p", DOC("<path id='p' d='" SQUARE_D "/>"), RUGO_ERR_PARSE, 1},
    {"bad transform of an ancestor", 's', "p",
     DOC("<g transform='rotate(1,2)'><path id='p' d='" SQUARE_D "'/></g>"), RUGO_ERR_PARSE, 1},
    {"unknown transform function", 's', "p", DOC("<path id='p' transform='spin(3)' d='" SQUARE_D "'/>"),
     RUGO_ERR_PARSE, 1},
    {"composed transforms overflowing", 's', "p",
     DOC("<g transform='scale(1e200)'><path id='p' transform='scale(1e200)' d='" SQUARE_D "'/></g>"),
     RUGO_ERR_NOT_FINITE, 1},
    {"degenerate transform (scale(1, 0))", 's', "p",
     DOC("<path id='p' transform='scale(1,0)' d='" SQUARE_D "'/>"), RUGO_ERR_ZERO_AREA, 1},
    {"valid document (control row)", 's', "p",
     DOC("<g transform='translate(5 5)'><path id='p' d='" SQUARE_D "'/></g>"), RUGO_OK, 0},
    /* transform lists */
    {"unknown transform", 't', NULL, "foo(1)", RUGO_ERR_PARSE, 1},
    {"wrong argument count", 't', NULL, "rotate(1,2)", RUGO_ERR_PARSE, 1},
    {"missing parenthesis", 't', NULL, "scale 2", RUGO_ERR_PARSE, 1},
    {"comma without a number", 't', NULL, "translate(1,)", RUGO_ERR_PARSE, 1},
    {"NaN in a transform", 't', NULL, "scale(nan)", RUGO_ERR_PARSE, 1},
    {"transform number overflowing", 't', NULL, "scale(1e999)", RUGO_ERR_NOT_FINITE, 1},
    {"transform product overflowing", 't', NULL, "scale(1e300) scale(1e300)", RUGO_ERR_NOT_FINITE, 1},
    {"valid transform (control row)", 't', NULL, "translate(1 2) rotate(90)", RUGO_OK, 0},
    /* point lists */
    {"three numbers on a line", 'p', NULL, "1,2\n3,4,5\n", RUGO_ERR_PARSE, 1},
    {"one number on a line", 'p', NULL, "1,2\n3\n", RUGO_ERR_PARSE, 1},
    {"words after the first line", 'p', NULL, "1,2\nx,y\n", RUGO_ERR_PARSE, 1},
    {"nan in a point list", 'p', NULL, "nan,1\n", RUGO_ERR_PARSE, 1},
    {"inf in a point list", 'p', NULL, "1,inf\n", RUGO_ERR_PARSE, 1},
    {"number overflowing in a point list", 'p', NULL, "1,2\n1e999,0\n", RUGO_ERR_NOT_FINITE, 1},
    {"JSON points file: syntax error", 'p', NULL, "{\"points\": [[0, 0] [1, 0]]}", RUGO_ERR_PARSE, 1},
    {"JSON points file: NaN literal", 'p', NULL, "{\"points\": [[0, NaN]]}", RUGO_ERR_PARSE, 1},
    {"JSON points file: number overflowing", 'p', NULL, "{\"points\": [[0, 1e999]]}", RUGO_ERR_NOT_FINITE, 1},
    {"JSON points file: no points member", 'p', NULL, "{\"control_points\": [[0, 0]]}", RUGO_ERR_BAD_FIELD,
     1},
    {"JSON points file: point not a pair", 'p', NULL, "{\"points\": [[0, 0], [1]]}", RUGO_ERR_BAD_FIELD, 1},
    {"two points", 'p', NULL, "0,0\n1,1\n", RUGO_ERR_TOO_FEW_POINTS, 0},
    {"empty point list (parses as NULL, 0)", 'p', NULL, "x,y\n", RUGO_ERR_NULL_ARGUMENT, 0},
    {"all points equal", 'p', NULL, "1,1\n1,1\n1,1\n1,1\n", RUGO_ERR_BAD_FIELD, 0},
    {"collinear points", 'p', NULL, "0,0\n1,1\n2,2\n", RUGO_ERR_ZERO_AREA, 0},
    {"valid point list (control row)", 'p', NULL, "x,y\n0,0\n4,0\n4,3\n0,3\n", RUGO_OK, 0},
};

START_TEST(import_rows) {
    for (size_t i = 0; i < sizeof IMPORT_ROWS / sizeof IMPORT_ROWS[0]; ++i) {
        const import_row* r = &IMPORT_ROWS[i];
        rugo_parse_error e;
        memset(&e, 0x55, sizeof e); /* every function clears it */
        rugo_status st = RUGO_OK;
        if (r->kind == 'd') {
            st = path_to_samples(r->text, &e);
        } else if (r->kind == 's') {
            rugo_outline_sample_def sd = rugo_default_outline_sample_def();
            rugo_outline_samples s;
            st = rugo_svg_import_outline(r->text, strlen(r->text), r->id, &sd, &s, &e);
            if (st != RUGO_OK) ck_assert(s.points == NULL && s.count == 0);
            rugo_outline_samples_free(&s);
        } else if (r->kind == 't') {
            rugo_affine m;
            st = rugo_svg_transform_parse(r->text, strlen(r->text), &m, &e);
            if (st != RUGO_OK)
                ck_assert(m.a == 1 && m.b == 0 && m.c == 0 && m.d == 1 && m.e == 0 && m.f == 0);
        } else {
            st = points_to_samples(r->text, &e);
        }
        ck_assert_msg(st == r->expect, "%s: got %d (%s: %s), expected %d (%s)", r->what, st,
                      rugo_status_string(st), e.message, r->expect, rugo_status_string(r->expect));
        ck_assert(memchr(e.message, '\0', sizeof e.message) != NULL &&
                  memchr(e.path, '\0', sizeof e.path) != NULL);
        if (st == RUGO_OK) continue;
        /* every failure says why, and a failure at a place in the text says where */
        if (r->kind != 'p' || r->located) ck_assert_msg(e.message[0] != '\0', "%s: no message", r->what);
        if (r->located)
            ck_assert_msg(e.line >= 1 && e.column >= 1, "%s: at %d:%d (%s)", r->what, e.line, e.column,
                          e.message);
    }
}
END_TEST

/* The size and count limits of the import readers, and bad sampling parameters. */
START_TEST(import_limits) {
    rugo_path p;
    rugo_parse_error e;
    rugo_svg_path_element el;
    rugo_point_list pts;
    /* Text over 64 MiB is refused by its length, before anything is read. */
    ck_assert_int_eq(rugo_path_parse("M 0 0", RUGO_MAX_SVG_BYTES + 1, NULL, &p, &e), RUGO_ERR_TOO_LARGE);
    ck_assert_int_eq(rugo_svg_find_path("<svg/>", RUGO_MAX_SVG_BYTES + 1, NULL, NULL, &el, &e),
                     RUGO_ERR_TOO_LARGE);
    ck_assert_int_eq(rugo_points_text_parse("1 2", RUGO_MAX_JSON_BYTES + 1, NULL, &pts, &e),
                     RUGO_ERR_TOO_LARGE);
    /* A number of more than 512 characters. */
    char longnum[600];
    memset(longnum, '1', sizeof longnum);
    memcpy(longnum, "M 0 ", 4);
    ck_assert_int_eq(rugo_path_parse(longnum, sizeof longnum, NULL, &p, &e), RUGO_ERR_PARSE);
    ck_assert_ptr_nonnull(strstr(e.message, "longer than 512"));
    /* More than 2^20 subpaths (lone movetos: 4 bytes of text each, refused at the limit). */
    const size_t nsub = (size_t)RUGO_MAX_PATH_SEGMENTS + 1;
    char* big = (char*)malloc(4 * nsub + 1);
    ck_assert_ptr_nonnull(big);
    for (size_t i = 0; i < nsub; ++i)
        memcpy(big + 4 * i, "M0 0", 4);
    ck_assert_int_eq(rugo_path_parse(big, 4 * nsub, NULL, &p, &e), RUGO_ERR_TOO_LARGE);
    ck_assert_ptr_nonnull(strstr(e.message, "subpaths"));
    ck_assert_ptr_null(p.subpaths);
    /* More than 2^20 points in a point list ("0 0" lines). */
    for (size_t i = 0; i < nsub; ++i)
        memcpy(big + 4 * i, "0 0\n", 4);
    ck_assert_int_eq(rugo_points_text_parse(big, 4 * nsub, NULL, &pts, &e), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert(pts.points == NULL && pts.count == 0);
    free(big);
    /* Elements nested deeper than 256. */
    char deep[(RUGO_SVG_MAX_DEPTH + 1) * 3 + 64];
    size_t w = 0;
    for (int i = 0; i <= RUGO_SVG_MAX_DEPTH; ++i)
        w += (size_t)sprintf(deep + w, "<g>");
    w += (size_t)sprintf(deep + w, "<path id='p' d='M0 0'/>");
    ck_assert_int_eq(rugo_svg_find_path(deep, w, "p", NULL, &el, &e), RUGO_ERR_PARSE);
    ck_assert_ptr_nonnull(strstr(e.message, "nested deeper"));
    /* Non-finite points given to the polygon builder by a program. */
    rugo_vec2 q[4] = {{0, 0}, {1, 0}, {1, NAN}, {0, 1}};
    ck_assert_int_eq(rugo_path_from_points(q, 4, NULL, &p), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_path_from_points(q, 2, NULL, &p), RUGO_ERR_TOO_FEW_POINTS);
    /* Sampling parameters: a count of 1, 2, negative or below the segments; a def not from the
     * default function; a subpath index out of range. */
    ck_assert_int_eq(rugo_path_parse(SQUARE_D, strlen(SQUARE_D), NULL, &p, &e), RUGO_OK);
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = &p;
    rugo_outline_samples s;
    const int bad_counts[4] = {1, 2, -5, 3};
    for (int i = 0; i < 4; ++i) {
        sd.sample_count = bad_counts[i];
        ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    }
    sd.sample_count = RUGO_MAX_CONTROL_POINTS + 1;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_TOO_MANY_POINTS);
    sd.sample_count = 0;
    sd.subpath = 1;
    ck_assert_int_eq(rugo_outline_sample(&sd, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    rugo_outline_sample_def raw;
    memset(&raw, 0, sizeof raw);
    raw.path = &p;
    ck_assert_int_eq(rugo_outline_sample(&raw, &s, &e), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_null(s.points);
    rugo_path_free(&p);
}
END_TEST

/* Baked rows: one representative each (test_baked covers every length, bit and field). */
START_TEST(baked_rows) {
    rugo_vec2 p[8] = {{1, 0}, {0.7, 0.7}, {0, 1}, {-0.7, 0.7}, {-1, 0}, {-0.7, -0.7}, {0, -1}, {0.7, -0.7}};
    rugo_shape_def def = rugo_default_shape_def();
    def.points = p;
    def.count = 8;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_OK);
    size_t size = 0, w = 0;
    rugo_shape_bake_size(s, &size);
    unsigned char* b = (unsigned char*)malloc(size);
    unsigned char* c = (unsigned char*)malloc(size);
    ck_assert_int_eq(rugo_shape_bake(s, b, size, &w), RUGO_OK);
    rugo_shape* t = NULL;
    rugo_baked_error e;
    ck_assert_int_eq(rugo_shape_load_baked(b, 100, NULL, &t, &e), RUGO_ERR_TRUNCATED);
    memcpy(c, b, size);
    c[200] ^= 4;
    ck_assert_int_eq(rugo_shape_load_baked(c, size, NULL, &t, &e), RUGO_ERR_CHECKSUM);
    memcpy(c, b, size);
    c[8] = 7;
    ck_assert_int_eq(rugo_shape_load_baked(c, size, NULL, &t, &e), RUGO_ERR_BAD_VERSION);
    memcpy(c, b, size);
    c[0] = 'X';
    ck_assert_int_eq(rugo_shape_load_baked(c, size, NULL, &t, &e), RUGO_ERR_BAD_FORMAT);
    memcpy(c, b, size);
    c[23] = 0x7f; /* payload size beyond the limit */
    ck_assert_int_eq(rugo_shape_load_baked(c, size, NULL, &t, &e), RUGO_ERR_TOO_LARGE);
    ck_assert_ptr_null(t);
    free(b);
    free(c);
    rugo_shape_destroy(s);
}
END_TEST

int main(void) {
    Suite* s = suite_create("bad_input");
    TCase* tc = tcase_create("table");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, json_rows);
    tcase_add_test(tc, huge_counts);
    tcase_add_test(tc, parameters_out_of_range);
    tcase_add_test(tc, baked_rows);
    tcase_add_test(tc, csv_rows);
    tcase_add_test(tc, import_rows);
    tcase_add_test(tc, import_limits);
    suite_add_tcase(s, tc);
    return test_run_suite(s);
}
