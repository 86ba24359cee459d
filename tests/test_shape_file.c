/* Shape files: the strict JSON reader and writer (librugo/io/json_read.c, json_write.c) and the shape
 * description layer (librugo/io/shape_file_read.c, shape_file_write.c, profile_csv.c, read_file.c;
 * rough/roughness_resample.c).
 * Inputs are copied into buffers of exactly their length, so that the sanitizer build catches any read
 * past `length`. */
#include "io/json.h"
#include "test_util.h"

#include <float.h>
#include <locale.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------------ */
/* Helpers */

/* A copy of s[0, n) in a buffer of exactly n bytes (no NUL after it). */
static char* exact_copy(const char* s, size_t n) {
    char* p = (char*)malloc(n > 0 ? n : 1);
    ck_assert_ptr_nonnull(p);
    if (n > 0) memcpy(p, s, n);
    return p;
}

static void data_path(const char* name, char* out, size_t size) {
    const char* file = __FILE__;
    const char* slash = strrchr(file, '/');
    int dir = slash != NULL ? (int)(slash - file + 1) : 0;
    snprintf(out, size, "%.*sdata/%s", dir, file, name);
}

static uint64_t bits_of(double x) {
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static double double_of(uint64_t u) {
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static int str_nul_terminated(const char* s, size_t size) { return memchr(s, '\0', size) != NULL; }

/* Parses s[0, n) from an exact-size copy. */
static rugo_status json_parse_n(const char* s, size_t n, rugo__json_doc* doc, rugo__json_error* err) {
    char* buf = exact_copy(s, n);
    rugo_status st = rugo__json_parse(buf, n, NULL, NULL, doc, err);
    free(buf);
    return st;
}

static rugo_status shape_parse_n(const char* s, size_t n, rugo_shape_desc* desc, rugo_parse_error* err) {
    char* buf = exact_copy(s, n);
    rugo_status st = rugo_shape_desc_parse(buf, n, NULL, desc, err);
    free(buf);
    return st;
}

/* Expects a JSON failure with the given status, position (0: not checked) and message fragment. */
static void expect_json_fail_n(const char* s, size_t n, rugo_status status, int line, int col,
                               const char* fragment) {
    rugo__json_doc doc;
    rugo__json_error err;
    rugo_status st = json_parse_n(s, n, &doc, &err);
    ck_assert_msg(st == status, "input <%.*s>: status %d (%s), expected %d; message: %s", (int)n, s, (int)st,
                  rugo_status_string(st), (int)status, err.message);
    ck_assert_ptr_null(doc.root);
    ck_assert_msg(str_nul_terminated(err.message, sizeof err.message) && err.message[0] != '\0',
                  "input <%.*s>: empty message", (int)n, s);
    ck_assert(str_nul_terminated(err.path, sizeof err.path));
    ck_assert_msg(err.line >= 1 && err.column >= 1, "input <%.*s>: no position", (int)n, s);
    if (line > 0)
        ck_assert_msg(err.line == line && err.column == col, "input <%.*s>: at %d:%d, expected %d:%d (%s)",
                      (int)n, s, err.line, err.column, line, col, err.message);
    if (fragment != NULL)
        ck_assert_msg(strstr(err.message, fragment) != NULL, "input <%.*s>: message \"%s\" lacks \"%s\"",
                      (int)n, s, err.message, fragment);
    rugo__json_doc_free(&doc);
}

static void expect_json_fail(const char* s, rugo_status status, int line, int col, const char* fragment) {
    expect_json_fail_n(s, strlen(s), status, line, col, fragment);
}

static void expect_shape_fail(const char* s, rugo_status status, const char* path, const char* fragment) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    rugo_status st = shape_parse_n(s, strlen(s), &desc, &err);
    ck_assert_msg(st == status, "input <%s>: status %d (%s), expected %d; message: %s", s, (int)st,
                  rugo_status_string(st), (int)status, err.message);
    ck_assert_ptr_null(desc.control_points);
    ck_assert_int_eq(desc.count, 0);
    ck_assert_msg(err.line >= 1 && err.column >= 1, "input <%s>: no position", s);
    ck_assert(err.message[0] != '\0');
    if (path != NULL)
        ck_assert_msg(strcmp(err.path, path) == 0, "input <%s>: path \"%s\", expected \"%s\"", s, err.path,
                      path);
    if (fragment != NULL)
        ck_assert_msg(strstr(err.message, fragment) != NULL, "input <%s>: message \"%s\" lacks \"%s\"", s,
                      err.message, fragment);
}

/* A caller-built description without roughness (the fields a caller sets; the rest zero). */
static rugo_shape_desc make_desc(rugo_vec2* pts, int n, rugo_filter filter) {
    rugo_shape_desc d;
    memset(&d, 0, sizeof d);
    d.control_points = pts;
    d.count = n;
    d.filter = filter;
    d.allocator = rugo_default_allocator();
    return d;
}

static rugo_text read_data(const char* name) {
    char path[1024];
    data_path(name, path, sizeof path);
    rugo_text text;
    rugo_status st = rugo_read_file(path, NULL, &text);
    ck_assert_msg(st == RUGO_OK, "%s: %s", path, rugo_status_string(st));
    return text;
}

/* ------------------------------------------------------------------------------------------------ */
/* JSON reader */

START_TEST(json_valid_values) {
    rugo__json_doc doc;
    rugo__json_error err;
    const char* text =
        " {\"n\": null, \"t\": true, \"f\": false, \"num\": [0, -0, 12.5e-1, 1E+2, -7],"
        " \"s\": \"a\\\"\\\\\\/\\b\\f\\n\\r\\tz\", \"u\": \"\\u00e9\\u20AC\\ud83d\\ude00\\u0000x\","
        " \"raw\": \"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\", \"o\": {}, \"a\": [], \"n\": 1}\r\n\t";
    ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
    const rugo__json_value* root = doc.root;
    ck_assert_int_eq(root->type, RUGO__JSON_OBJECT);
    ck_assert_int_eq((int)root->count, 10);
    /* Members keep their order; duplicates are kept and counted. */
    const char* order[] = {"n", "t", "f", "num", "s", "u", "raw", "o", "a", "n"};
    int i = 0;
    for (const rugo__json_value* k = root->u.first; k != NULL; k = RUGO__JSON_NEXT_MEMBER(k), ++i) {
        ck_assert_int_eq(k->type, RUGO__JSON_STRING);
        ck_assert_str_eq(k->u.string, order[i]);
    }
    ck_assert_int_eq(i, 10);
    int matches = 0;
    const rugo__json_value* v = rugo__json_object_get(root, "n", &matches);
    ck_assert_int_eq(matches, 2);
    ck_assert_int_eq(v->type, RUGO__JSON_NULL);
    ck_assert_int_eq(rugo__json_object_get(root, "t", NULL)->u.boolean, 1);
    ck_assert_int_eq(rugo__json_object_get(root, "f", NULL)->u.boolean, 0);
    ck_assert_ptr_null(rugo__json_object_get(root, "missing", &matches));
    ck_assert_int_eq(matches, 0);

    v = rugo__json_object_get(root, "num", NULL);
    ck_assert_int_eq((int)v->count, 5);
    const double nums[] = {0.0, -0.0, 1.25, 100.0, -7.0};
    i = 0;
    for (const rugo__json_value* e = v->u.first; e != NULL; e = e->next, ++i) {
        ck_assert_int_eq(e->type, RUGO__JSON_NUMBER);
        ck_assert(bits_of(e->u.number) == bits_of(nums[i]));
    }

    v = rugo__json_object_get(root, "s", NULL);
    ck_assert_int_eq((int)v->count, 10);
    ck_assert(memcmp(v->u.string, "a\"\\/\b\f\n\r\tz", 11) == 0);
    v = rugo__json_object_get(root, "u", NULL);
    /* é (2 bytes), € (3), U+1F600 from a surrogate pair (4), NUL, x */
    ck_assert_int_eq((int)v->count, 11);
    ck_assert(memcmp(v->u.string, "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\0x", 12) == 0);
    const rugo__json_value* raw = rugo__json_object_get(root, "raw", NULL);
    ck_assert_int_eq((int)raw->count, 9);
    ck_assert(memcmp(raw->u.string, v->u.string, 9) == 0);
    ck_assert_int_eq((int)rugo__json_object_get(root, "o", NULL)->count, 0);
    ck_assert_int_eq(rugo__json_object_get(root, "a", NULL)->type, RUGO__JSON_ARRAY);
    /* A key with an embedded NUL never matches a C string. */
    rugo__json_doc_free(&doc);
    ck_assert_ptr_null(doc.root);
    rugo__json_doc_free(&doc); /* twice is harmless */

    const char* keynul = "{\"a\\u0000b\": 1}";
    ck_assert_int_eq(json_parse_n(keynul, strlen(keynul), &doc, &err), RUGO_OK);
    ck_assert_ptr_null(rugo__json_object_get(doc.root, "a", NULL));
    rugo__json_doc_free(&doc);

    /* Scalars at the top level, a byte order mark, and the edges of the number range. */
    struct {
        const char* text;
        double value;
    } scalars[] = {
        {"0", 0.0},
        {"-0.0e0", -0.0},
        {"\xef\xbb\xbf 42 ", 42.0},
        {"1.7976931348623157e308", DBL_MAX},
        {"-1.7976931348623157e308", -DBL_MAX},
        {"2.2250738585072014e-308", DBL_MIN},
        {"4.9406564584124654e-324", 4.9406564584124654e-324},
        {"2.4703282292062328e-324", 4.9406564584124654e-324}, /* rounds up to the smallest subnormal */
        {"1e-400", 0.0},                                      /* underflow is not an error */
        {"-1e-400", -0.0},
        {"2.2250738585072011e-308", 2.2250738585072011e-308},
        {"9007199254740993", 9007199254740992.0}, /* ties to even */
        {"1e23", 1e23},
        {"123456789012345678901234567890", 123456789012345678901234567890.0},
    };
    for (size_t k = 0; k < sizeof scalars / sizeof scalars[0]; ++k) {
        ck_assert_int_eq(json_parse_n(scalars[k].text, strlen(scalars[k].text), &doc, &err), RUGO_OK);
        ck_assert_int_eq(doc.root->type, RUGO__JSON_NUMBER);
        ck_assert_msg(bits_of(doc.root->u.number) == bits_of(scalars[k].value), "%s -> %.17g",
                      scalars[k].text, doc.root->u.number);
        rugo__json_doc_free(&doc);
    }
    ck_assert_str_eq(rugo__json_type_name(RUGO__JSON_OBJECT), "object");
    ck_assert_str_eq(rugo__json_type_name(RUGO__JSON_BOOL), "boolean");
}
END_TEST

START_TEST(json_rejects_malformed) {
    /* Truncation */
    expect_json_fail("", RUGO_ERR_PARSE, 1, 1, "empty");
    expect_json_fail("  \n ", RUGO_ERR_PARSE, 2, 2, "empty");
    expect_json_fail("\xef\xbb\xbf", RUGO_ERR_PARSE, 1, 4, "empty");
    expect_json_fail("[", RUGO_ERR_PARSE, 1, 2, "end of input");
    expect_json_fail("[1,", RUGO_ERR_PARSE, 1, 4, "end of input");
    expect_json_fail("[1", RUGO_ERR_PARSE, 1, 3, "missing ']'");
    expect_json_fail("{\"a\":1", RUGO_ERR_PARSE, 1, 7, "missing '}'");
    expect_json_fail("{\"a\"", RUGO_ERR_PARSE, 1, 5, "':'");
    expect_json_fail("{", RUGO_ERR_PARSE, 1, 2, "end of input");
    expect_json_fail("nul", RUGO_ERR_PARSE, 1, 1, "null");
    expect_json_fail("tru", RUGO_ERR_PARSE, 1, 1, "true");
    expect_json_fail("-", RUGO_ERR_PARSE, 1, 2, "digit");
    /* Unterminated strings (reported where they start) */
    expect_json_fail("\"abc", RUGO_ERR_PARSE, 1, 1, "unterminated string");
    expect_json_fail("[\"abc\\\"]", RUGO_ERR_PARSE, 1, 2, "unterminated string");
    expect_json_fail("\"abc\\", RUGO_ERR_PARSE, 1, 1, "unterminated string");
    /* Trailing garbage and separators */
    expect_json_fail("[1] x", RUGO_ERR_PARSE, 1, 5, "after the JSON value");
    expect_json_fail("[1]]", RUGO_ERR_PARSE, 1, 4, "after the JSON value");
    expect_json_fail("{}{}", RUGO_ERR_PARSE, 1, 3, "after the JSON value");
    expect_json_fail("truex", RUGO_ERR_PARSE, 1, 5, "after the JSON value");
    expect_json_fail("0x10", RUGO_ERR_PARSE, 1, 2, "after the JSON value");
    expect_json_fail("1.5e3.2", RUGO_ERR_PARSE, 1, 6, "after the JSON value");
    expect_json_fail("[1,]", RUGO_ERR_PARSE, 1, 4, "trailing comma");
    expect_json_fail("{\"a\":1,}", RUGO_ERR_PARSE, 1, 8, "trailing comma");
    expect_json_fail("[1 2]", RUGO_ERR_PARSE, 1, 4, "expected ',' or ']'");
    expect_json_fail("{\"a\":1 \"b\":2}", RUGO_ERR_PARSE, 1, 8, "expected ',' or '}'");
    expect_json_fail("{\"a\" 1}", RUGO_ERR_PARSE, 1, 6, "':'");
    expect_json_fail("{a:1}", RUGO_ERR_PARSE, 1, 2, "member name");
    expect_json_fail("{\"a\":}", RUGO_ERR_PARSE, 1, 6, "expected a value");
    expect_json_fail("[,1]", RUGO_ERR_PARSE, 1, 2, "expected a value");
    expect_json_fail("'a'", RUGO_ERR_PARSE, 1, 1, "double quotes");
    expect_json_fail("/*c*/1", RUGO_ERR_PARSE, 1, 1, "comments");
    expect_json_fail_n("\0", 1, RUGO_ERR_PARSE, 1, 1, "0x00");
    expect_json_fail_n("[1,\0]", 5, RUGO_ERR_PARSE, 1, 4, "0x00");
    /* Numbers */
    expect_json_fail("01", RUGO_ERR_PARSE, 1, 1, "leading zero");
    expect_json_fail("-01", RUGO_ERR_PARSE, 1, 1, "leading zero");
    expect_json_fail("[00]", RUGO_ERR_PARSE, 1, 2, "leading zero");
    expect_json_fail("1.", RUGO_ERR_PARSE, 1, 3, "decimal point");
    expect_json_fail("1.e5", RUGO_ERR_PARSE, 1, 3, "decimal point");
    expect_json_fail(".5", RUGO_ERR_PARSE, 1, 1, "digit");
    expect_json_fail("+1", RUGO_ERR_PARSE, 1, 1, "'+'");
    expect_json_fail("1e", RUGO_ERR_PARSE, 1, 3, "exponent");
    expect_json_fail("1e+", RUGO_ERR_PARSE, 1, 4, "exponent");
    expect_json_fail("NaN", RUGO_ERR_PARSE, 1, 1, "NaN");
    expect_json_fail("[Infinity]", RUGO_ERR_PARSE, 1, 2, "Infinity");
    expect_json_fail("-Infinity", RUGO_ERR_PARSE, 1, 1, "Infinity");
    expect_json_fail("nan", RUGO_ERR_PARSE, 1, 1, NULL);
    expect_json_fail("1e999", RUGO_ERR_NOT_FINITE, 1, 1, "infinity");
    expect_json_fail("[0, -1e999]", RUGO_ERR_NOT_FINITE, 1, 5, "-infinity");
    expect_json_fail("1.8e308", RUGO_ERR_NOT_FINITE, 1, 1, "infinity");
    expect_json_fail("1e99999999999999999999999", RUGO_ERR_NOT_FINITE, 1, 1, NULL);
    /* Escapes, control characters, surrogates, UTF-8 */
    expect_json_fail("\"\\x\"", RUGO_ERR_PARSE, 1, 2, "invalid escape");
    expect_json_fail("\"\\U0041\"", RUGO_ERR_PARSE, 1, 2, "invalid escape");
    expect_json_fail("\"\\u12\"", RUGO_ERR_PARSE, 1, 2, "four hex digits");
    expect_json_fail("\"\\u12G4\"", RUGO_ERR_PARSE, 1, 2, "four hex digits");
    expect_json_fail("\"ab\\u\"", RUGO_ERR_PARSE, 1, 4, "four hex digits");
    expect_json_fail("\"\\ud800\"", RUGO_ERR_PARSE, 1, 2, "surrogate");
    expect_json_fail("\"\\udc00\"", RUGO_ERR_PARSE, 1, 2, "surrogate");
    expect_json_fail("\"\\ud800\\u0041\"", RUGO_ERR_PARSE, 1, 2, "surrogate");
    expect_json_fail("\"\\ud800\\ud800\"", RUGO_ERR_PARSE, 1, 2, "surrogate");
    expect_json_fail("\"\\ud800\\\"", RUGO_ERR_PARSE, 1, 1, "unterminated");
    expect_json_fail("\"a\tb\"", RUGO_ERR_PARSE, 1, 3, "control character");
    expect_json_fail("\"a\nb\"", RUGO_ERR_PARSE, 1, 3, "control character");
    expect_json_fail_n("\"a\0b\"", 5, RUGO_ERR_PARSE, 1, 3, "control character");
    expect_json_fail("\"\x01\"", RUGO_ERR_PARSE, 1, 2, "control character");
    expect_json_fail("\"\xc0\xaf\"", RUGO_ERR_PARSE, 1, 2, "UTF-8");         /* overlong '/' */
    expect_json_fail("\"\xe0\x80\xaf\"", RUGO_ERR_PARSE, 1, 2, "UTF-8");     /* overlong */
    expect_json_fail("\"\xed\xa0\x80\"", RUGO_ERR_PARSE, 1, 2, "UTF-8");     /* encoded surrogate */
    expect_json_fail("\"\xf4\x90\x80\x80\"", RUGO_ERR_PARSE, 1, 2, "UTF-8"); /* above U+10FFFF */
    expect_json_fail("\"\xe2\x82\"", RUGO_ERR_PARSE, 1, 2, "UTF-8");         /* cut sequence */
    expect_json_fail("\"x\x80\"", RUGO_ERR_PARSE, 1, 3, "UTF-8");            /* lone continuation */
    expect_json_fail("\"\xff\"", RUGO_ERR_PARSE, 1, 2, "UTF-8");
    expect_json_fail("\xef\xbb\xbf\xef\xbb\xbf{}", RUGO_ERR_PARSE, 1, 4, NULL); /* only one BOM */
    /* Positions on later lines: columns count bytes from 1. */
    expect_json_fail("[\n  1,\n  2,,\n]", RUGO_ERR_PARSE, 3, 5, "expected a value");
    expect_json_fail("{\r\n\"a\": [true,\r\n\tfals]}", RUGO_ERR_PARSE, 3, 2, "false");
}
END_TEST

START_TEST(json_error_paths) {
    rugo__json_doc doc;
    rugo__json_error err;
    const char* t1 = "{\"a\": [1, {\"b\": [true, 1e999]}]}";
    ck_assert_int_eq(json_parse_n(t1, strlen(t1), &doc, &err), RUGO_ERR_NOT_FINITE);
    ck_assert_str_eq(err.path, "a[1].b[1]");
    ck_assert_int_eq(err.column, 24);
    ck_assert_int_eq((int)err.offset, 23);
    const char* t2 = "{\n  \"control_points\": [\n    [0, 0],\n    [1, ]\n  ]\n}\n";
    ck_assert_int_eq(json_parse_n(t2, strlen(t2), &doc, &err), RUGO_ERR_PARSE);
    ck_assert_str_eq(err.path, "control_points[1][1]");
    ck_assert_int_eq(err.line, 4);
    ck_assert_int_eq(err.column, 9);
    /* A failing key has the enclosing path only. */
    const char* t3 = "{\"x\": {\"ok\": 1, \"bad\\q\": 2}}";
    ck_assert_int_eq(json_parse_n(t3, strlen(t3), &doc, &err), RUGO_ERR_PARSE);
    ck_assert_str_eq(err.path, "x");
    ck_assert_ptr_null(doc.root);
    /* Odd key bytes become '?', and a long path is cut with "...". */
    const char* t4 = "{\"a\\nb\": [[[nope]]]}";
    ck_assert_int_eq(json_parse_n(t4, strlen(t4), &doc, &err), RUGO_ERR_PARSE);
    ck_assert_str_eq(err.path, "a?b[0][0][0]");
    char deep[400];
    size_t n = 0;
    for (int i = 0; i < 60; ++i)
        deep[n++] = '[';
    deep[n++] = 'x';
    ck_assert_int_eq(json_parse_n(deep, n, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq((int)strlen(err.path), (int)sizeof err.path - 1);
    ck_assert_str_eq(err.path + strlen(err.path) - 3, "...");
    /* NULL arguments and a text over the size limit */
    ck_assert_int_eq(rugo__json_parse(NULL, 0, NULL, NULL, &doc, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__json_parse("1", 1, NULL, NULL, NULL, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__json_parse("1", 1, NULL, NULL, &doc, NULL), RUGO_OK);
    rugo__json_doc_free(&doc);
    ck_assert_int_eq(rugo__json_parse("1", RUGO_MAX_JSON_BYTES + 1, NULL, NULL, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.line, 0);
    ck_assert_ptr_nonnull(strstr(err.message, "larger"));
}
END_TEST

START_TEST(json_nesting_and_value_limits) {
    enum { N = 100000 };
    char* buf = (char*)malloc(2 * N);
    rugo__json_doc doc;
    rugo__json_error err;
    for (int depth = 63; depth <= 65; ++depth) {
        for (int obj = 0; obj < 2; ++obj) {
            size_t n = 0;
            for (int i = 0; i < depth; ++i) {
                if (obj) {
                    memcpy(buf + n, "{\"k\":", 5);
                    n += 5;
                } else {
                    buf[n++] = '[';
                }
            }
            for (int i = 0; i < depth; ++i)
                buf[n++] = obj ? '}' : ']';
            rugo_status st = json_parse_n(buf, n, &doc, &err);
            if (obj) { /* the innermost object is {"k":} */
                ck_assert_int_eq(st, RUGO_ERR_PARSE);
                if (depth <= RUGO__JSON_MAX_DEPTH) ck_assert_ptr_null(strstr(err.message, "nesting"));
            } else if (depth <= RUGO__JSON_MAX_DEPTH) {
                ck_assert_int_eq(st, RUGO_OK);
                rugo__json_doc_free(&doc);
            } else {
                ck_assert_int_eq(st, RUGO_ERR_PARSE);
                ck_assert_ptr_nonnull(strstr(err.message, "nesting deeper than 64"));
                ck_assert_int_eq(err.column, depth);
            }
        }
    }
    /* Very deep input fails fast at the limit, without deep recursion. */
    memset(buf, '[', N);
    ck_assert_int_eq(json_parse_n(buf, N, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, RUGO__JSON_MAX_DEPTH + 1);
    /* A lower or higher depth limit on request (capped at RUGO__JSON_DEPTH_CAP). */
    rugo__json_limits lim = {3, 0};
    ck_assert_int_eq(rugo__json_parse("[[[]]]", 6, NULL, &lim, &doc, &err), RUGO_OK);
    rugo__json_doc_free(&doc);
    ck_assert_int_eq(rugo__json_parse("[[[[]]]]", 8, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    lim.max_depth = 100000;
    ck_assert_int_eq(rugo__json_parse(buf, N, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, RUGO__JSON_DEPTH_CAP + 1);
    for (int i = 0; i < RUGO__JSON_DEPTH_CAP; ++i)
        buf[RUGO__JSON_DEPTH_CAP + i] = ']';
    ck_assert_int_eq(rugo__json_parse(buf, 2 * RUGO__JSON_DEPTH_CAP, NULL, &lim, &doc, &err), RUGO_OK);
    rugo__json_doc_free(&doc);
    /* The value limit: [1,2,...,9] is 10 values (strings and keys count too). */
    lim.max_depth = 0;
    lim.max_values = 10;
    ck_assert_int_eq(rugo__json_parse("[1,2,3,4,5,6,7,8,9]", 19, NULL, &lim, &doc, &err), RUGO_OK);
    ck_assert_int_eq((int)doc.value_count, 10);
    rugo__json_doc_free(&doc);
    ck_assert_int_eq(rugo__json_parse("[1,2,3,4,5,6,7,8,9,0]", 21, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_ptr_nonnull(strstr(err.message, "more than 10 values"));
    ck_assert_int_eq(
        rugo__json_parse("{\"a\":1,\"b\":2,\"c\":3,\"d\":4,\"e\":5}", 31, NULL, &lim, &doc, &err),
        RUGO_ERR_PARSE);
    free(buf);
}
END_TEST

START_TEST(json_number_length_limit) {
    char buf[RUGO__JSON_MAX_NUMBER_CHARS + 8];
    rugo__json_doc doc;
    rugo__json_error err;
    /* "0." + 1016 zeros + "1e+999" (exactly the limit in characters) = 1e-1017 * 1e999. */
    size_t n = RUGO__JSON_MAX_NUMBER_CHARS;
    memset(buf, '0', n);
    buf[1] = '.';
    memcpy(buf + n - 6, "1e+999", 6);
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(bits_of(doc.root->u.number) == bits_of(1e-18));
    rugo__json_doc_free(&doc);
    /* Correct rounding decided by a digit a thousand places in: 1 + 2^-53 is halfway between 1 and
     * 1 + 2^-52 and rounds to even (1); any nonzero digit after it rounds up. */
    const char* half = "1.00000000000000011102230246251565404236316680908203125";
    memset(buf, '0', n);
    memcpy(buf, half, strlen(half));
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 1.0);
    rugo__json_doc_free(&doc);
    buf[n - 1] = '1';
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 1.0 + DBL_EPSILON);
    rugo__json_doc_free(&doc);
    buf[n] = '0';
    expect_json_fail_n(buf, n + 1, RUGO_ERR_PARSE, 1, 1, "longer than 1024");
}
END_TEST

START_TEST(json_not_nul_terminated) {
    rugo__json_doc doc;
    rugo__json_error err;
    /* Only the first `length` bytes count: a number cut by the length ends there. */
    ck_assert_int_eq(json_parse_n("123456", 3, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 123.0);
    rugo__json_doc_free(&doc);
    ck_assert_int_eq(json_parse_n("-1.5e3x", 6, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == -1500.0);
    rugo__json_doc_free(&doc);
    ck_assert_int_eq(json_parse_n("[1, 23]", 5, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, 6);
    ck_assert_int_eq(json_parse_n("\"abc\"", 4, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("\"\\u0041\"", 6, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("true", 3, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("\"\xe2\x82\xac\"", 3, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("{\"a\":1}garbage", 7, &doc, &err), RUGO_OK);
    rugo__json_doc_free(&doc);
}
END_TEST

START_TEST(json_out_of_memory) {
    rugo_text text = read_data("star32.json");
    /* Every allocation failure is reported, leaves nothing allocated, and enough budget succeeds. */
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo__json_doc doc;
        rugo__json_error err;
        rugo_status st = rugo__json_parse(text.data, text.length, &a, NULL, &doc, &err);
        if (st == RUGO_OK) {
            ck_assert_int_gt(ctx.live, 0);
            rugo__json_doc_free(&doc);
            ck_assert_int_eq(ctx.live, 0);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 100);
    }
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo_shape_desc desc;
        rugo_status st = rugo_shape_desc_parse(text.data, text.length, &a, &desc, NULL);
        if (st == RUGO_OK) {
            ck_assert_int_eq(desc.count, 32);
            rugo_shape_desc_free(&desc);
            ck_assert_int_eq(ctx.live, 0);
            rugo_text out;
            /* The writer too. */
            for (long wb = 0;; ++wb) {
                test_budget_ctx wctx = {wb, 0};
                rugo_allocator wa = {test_budget_alloc, test_budget_free, &wctx};
                rugo_shape_desc d2 = desc;
                rugo_vec2 pts[32];
                test_rng r = test_rng_seed(5);
                test_random_star(&r, 32, rugo_v2(0, 0), 1.0, 0.3, pts);
                d2.control_points = pts;
                d2.count = 32;
                st = rugo_shape_desc_write(&d2, &wa, &out);
                if (st == RUGO_OK) {
                    ck_assert_int_eq(wctx.live, 1);
                    rugo_text_free(&out);
                    ck_assert_int_eq(wctx.live, 0);
                    break;
                }
                ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
                ck_assert_ptr_null(out.data);
                ck_assert_int_eq(wctx.live, 0);
                ck_assert_int_lt(wb, 100);
            }
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_ptr_null(desc.control_points);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 100);
    }
    rugo_text_free(&text);
}
END_TEST

START_TEST(json_locale_decimal_point) {
    /* strtod and printf follow LC_NUMERIC. With a ',' locale the reader and writer must still use
     * '.'. Runs only where such a locale is installed. */
    const char* names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "de_DE", "ru_RU.UTF-8"};
    const char* got = NULL;
    for (size_t i = 0; i < sizeof names / sizeof names[0] && got == NULL; ++i)
        got = setlocale(LC_NUMERIC, names[i]);
    if (got == NULL || strcmp(localeconv()->decimal_point, ".") == 0) {
        setlocale(LC_NUMERIC, "C");
        return;
    }
    rugo__json_doc doc;
    rugo__json_error err;
    rugo_status st = json_parse_n("[1.5, -0.25e1]", 14, &doc, &err);
    char buf[40];
    rugo__json_format_number(0.1, buf, sizeof buf);
    setlocale(LC_NUMERIC, "C");
    ck_assert_int_eq(st, RUGO_OK);
    ck_assert(doc.root->u.first->u.number == 1.5);
    ck_assert(doc.root->u.first->next->u.number == -2.5);
    rugo__json_doc_free(&doc);
    ck_assert_str_eq(buf, "0.10000000000000001");
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* JSON writer */

/* The writer's text (the default allocator's: free() it). */
static char* finish_ok(rugo__json_writer* w) {
    char* text = NULL;
    size_t n = 0;
    rugo_status st = rugo__json_writer_finish(w, &text, &n);
    ck_assert_msg(st == RUGO_OK, "finish: %s", rugo_status_string(st));
    ck_assert_int_eq((int)strlen(text), (int)n);
    return text;
}

START_TEST(json_writer_layout) {
    for (int indent = 0; indent <= 2; indent += 2) {
        rugo__json_writer w;
        rugo__json_writer_init(&w, NULL, indent);
        rugo__json_begin_object(&w, 0);
        rugo__json_key(&w, "a");
        rugo__json_begin_array(&w, 0);
        rugo__json_integer(&w, 1);
        rugo__json_number(&w, 2.5);
        rugo__json_begin_array(&w, RUGO__JSON_INLINE);
        rugo__json_number(&w, -0.0);
        rugo__json_string(&w, "x\n");
        rugo__json_end_array(&w);
        rugo__json_end_array(&w);
        rugo__json_key(&w, "b");
        rugo__json_begin_object(&w, 0);
        rugo__json_end_object(&w);
        rugo__json_key(&w, "c");
        rugo__json_begin_array(&w, 0);
        rugo__json_end_array(&w);
        rugo__json_key(&w, "d");
        rugo__json_bool(&w, 1);
        rugo__json_key(&w, "e");
        rugo__json_null(&w);
        rugo__json_key(&w, "f");
        rugo__json_begin_object(&w, RUGO__JSON_INLINE);
        rugo__json_key(&w, "g");
        rugo__json_bool(&w, 0);
        rugo__json_key(&w, "h");
        rugo__json_integer(&w, -9000000000LL);
        rugo__json_end_object(&w);
        rugo__json_end_object(&w);
        char* text = finish_ok(&w);
        if (indent == 0)
            ck_assert_str_eq(
                text, "{\"a\": [1, 2.5, [-0, \"x\\n\"]], \"b\": {}, \"c\": [], \"d\": true, \"e\": null, "
                      "\"f\": {\"g\": false, \"h\": -9000000000}}");
        else
            ck_assert_str_eq(
                text,
                "{\n  \"a\": [\n    1,\n    2.5,\n    [-0, \"x\\n\"]\n  ],\n  \"b\": {},\n  \"c\": [],\n"
                "  \"d\": true,\n  \"e\": null,\n  \"f\": {\"g\": false, \"h\": -9000000000}\n}");
        /* What it writes reads back. */
        rugo__json_doc doc;
        rugo__json_error err;
        ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
        ck_assert(
            bits_of(rugo__json_object_get(doc.root, "a", NULL)->u.first->next->next->u.first->u.number) ==
            bits_of(-0.0));
        rugo__json_doc_free(&doc);
        free(text);
    }
    /* An empty text is an empty string, not NULL. */
    rugo__json_writer w;
    rugo__json_writer_init(&w, NULL, 0);
    char* text = finish_ok(&w);
    ck_assert_str_eq(text, "");
    free(text);
}
END_TEST

START_TEST(json_writer_strings_round_trip) {
    char all[256 + 8];
    for (int i = 0; i < 128; ++i)
        all[i] = (char)i; /* every ASCII byte, NUL and controls included */
    memcpy(all + 128, "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80", 9);
    size_t n = 137;
    rugo__json_writer w;
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_begin_array(&w, 0);
    rugo__json_string_n(&w, all, n);
    rugo__json_string(&w, "\"\\/");
    rugo__json_end_array(&w);
    char* text = finish_ok(&w);
    ck_assert_ptr_nonnull(strstr(text, "\"\\u0000\\u0001"));
    ck_assert_ptr_nonnull(strstr(text, "\\b\\t\\n\\u000b\\f\\r"));
    ck_assert_ptr_nonnull(strstr(text, "\"\\\"\\\\/\""));
    rugo__json_doc doc;
    rugo__json_error err;
    ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
    ck_assert_int_eq((int)doc.root->u.first->count, (int)n);
    ck_assert(memcmp(doc.root->u.first->u.string, all, n) == 0);
    ck_assert_str_eq(doc.root->u.first->next->u.string, "\"\\/");
    rugo__json_doc_free(&doc);
    free(text);
}
END_TEST

START_TEST(json_writer_errors) {
    char* text = (char*)1;
    size_t n = 99;
    rugo__json_writer w;
    /* Non-finite numbers are refused, and the error sticks. */
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 3; ++i) {
        rugo__json_writer_init(&w, NULL, 2);
        rugo__json_begin_array(&w, 0);
        rugo__json_number(&w, 1.0);
        rugo__json_number(&w, bad[i]);
        rugo__json_number(&w, 2.0);
        rugo__json_end_array(&w);
        ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_NOT_FINITE);
        ck_assert_ptr_null(text);
        ck_assert_int_eq((int)n, 0);
    }
    /* Misuse */
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_begin_object(&w, 0);
    rugo__json_number(&w, 1.0); /* no key */
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_begin_object(&w, 0);
    rugo__json_end_array(&w);
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_begin_array(&w, 0);
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_key(&w, "top");
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_begin_object(&w, 0);
    rugo__json_key(&w, "k");
    rugo__json_end_object(&w); /* key without a value */
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    for (int i = 0; i <= RUGO__JSON_WRITER_MAX_DEPTH; ++i)
        rugo__json_begin_array(&w, 0);
    ck_assert_int_eq(w.status, RUGO_ERR_BAD_ARGUMENT);
    rugo__json_writer_discard(&w);
    rugo__json_writer_init(&w, NULL, 0);
    rugo__json_string(&w, NULL);
    ck_assert_int_eq(rugo__json_writer_finish(&w, &text, &n), RUGO_ERR_NULL_ARGUMENT);
    rugo__json_writer_init(&w, NULL, 0);
    ck_assert_int_eq(rugo__json_writer_finish(&w, NULL, &n), RUGO_ERR_NULL_ARGUMENT);

    char buf[40];
    ck_assert_int_eq(rugo__json_format_number(0.1, buf, sizeof buf), 19);
    ck_assert_str_eq(buf, "0.10000000000000001");
    rugo__json_format_number(-0.0, buf, sizeof buf);
    ck_assert_str_eq(buf, "-0");
    rugo__json_format_number(1e300, buf, sizeof buf);
    ck_assert_str_eq(buf, "1.0000000000000001e+300");
    rugo__json_format_number(-2.2250738585072014e-308, buf, sizeof buf);
    ck_assert_str_eq(buf, "-2.2250738585072014e-308");
    rugo__json_format_number(NAN, buf, sizeof buf);
    ck_assert_str_eq(buf, "nan");
    rugo__json_format_number(-INFINITY, buf, sizeof buf);
    ck_assert_str_eq(buf, "-inf");
    rugo__json_format_number(123.0, buf, 3); /* cut, still terminated */
    ck_assert_str_eq(buf, "12");
}
END_TEST

/* Random doubles of every magnitude: uniform bit patterns (finite ones), subnormals, and specials. */
static double random_double(test_rng* r) {
    static const double specials[] = {0.0,
                                      -0.0,
                                      1e300,
                                      -1e300,
                                      DBL_MAX,
                                      -DBL_MAX,
                                      DBL_MIN,
                                      -DBL_MIN,
                                      4.9406564584124654e-324,
                                      -4.9406564584124654e-324,
                                      2.2250738585072009e-308,
                                      0.1,
                                      1.0 / 3.0,
                                      9007199254740993.0,
                                      1e23,
                                      5e-324 * 3,
                                      1.0,
                                      -1.0};
    uint64_t u = test_rng_next(r);
    switch (u % 4) {
    case 0:
        return specials[(u >> 8) % (sizeof specials / sizeof specials[0])];
    case 1:
        return double_of(test_rng_next(r) & 0x800FFFFFFFFFFFFFull); /* subnormal or zero */
    case 2:
        return test_rng_uniform(r, -1000.0, 1000.0);
    default: {
        double x;
        do
            x = double_of(test_rng_next(r));
        while (!isfinite(x));
        return x;
    }
    }
}

START_TEST(json_number_round_trip) {
    test_rng r = test_rng_seed(0x5eed);
    rugo__json_doc doc;
    rugo__json_error err;
    for (int i = 0; i < 20000; ++i) {
        double x = random_double(&r);
        char buf[40];
        int n = rugo__json_format_number(x, buf, sizeof buf);
        ck_assert_int_le(n, 24);
        ck_assert_int_eq(json_parse_n(buf, (size_t)n, &doc, &err), RUGO_OK);
        ck_assert_msg(bits_of(doc.root->u.number) == bits_of(x), "%s -> %.17g", buf, doc.root->u.number);
        rugo__json_doc_free(&doc);
    }
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* Shape descriptions */

START_TEST(shape_parse_valid) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t =
        "{\"name\": \"sq\", \"roughness\": {\"constant\": 0.5, \"levels\": [1, 2, {\"x\": null}]},"
        " \"control_points\": [[0, 0], [1, 0.5], [-1e-3, 2E2], [0, 1]], \"extra\": [[[]]]}";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 4);
    ck_assert_int_eq(desc.filter, RUGO_FILTER_DEFAULT);
    ck_assert(desc.control_points[1].y == 0.5);
    ck_assert(desc.control_points[2].x == -1e-3);
    ck_assert(desc.control_points[2].y == 200.0);
    ck_assert(desc.allocator.alloc != NULL);
    ck_assert(desc.has_roughness);
    ck_assert_int_eq(desc.roughness.kind, RUGO_ROUGHNESS_CONSTANT);
    ck_assert(desc.roughness.constant == 0.5);
    rugo_shape_desc_free(&desc);
    ck_assert_ptr_null(desc.control_points);
    rugo_shape_desc_free(&desc);
    rugo_shape_desc_free(NULL);

    /* Every filter name */
    for (int f = 0; f < RUGO_FILTER_COUNT; ++f) {
        char buf[128];
        snprintf(buf, sizeof buf, "{\"filter\": \"%s\", \"control_points\": [[1, 2]]}",
                 rugo_filter_name((rugo_filter)f));
        ck_assert_int_eq(shape_parse_n(buf, strlen(buf), &desc, &err), RUGO_OK);
        ck_assert_int_eq(desc.filter, f);
        rugo_shape_desc_free(&desc);
    }
    /* Geometry is not checked here: an empty list is fine. */
    ck_assert_int_eq(shape_parse_n("{\"control_points\": []}", 22, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 0);
    ck_assert_ptr_null(desc.control_points);
    rugo_shape_desc_free(&desc);

    /* The sample files */
    rugo_text text = read_data("square4.json");
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 4);
    ck_assert(desc.control_points[0].x == -1.0 && desc.control_points[2].y == 1.0);
    rugo_shape_desc_free(&desc);
    rugo_text_free(&text);
    text = read_data("star32.json");
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 32);
    ck_assert_int_eq(desc.filter, RUGO_FILTER_CDF4_8);
    ck_assert(desc.control_points[0].x == 1.3);
    rugo_shape_desc_free(&desc);
    rugo_text_free(&text);

    /* A custom allocator is recorded and used to free. */
    test_budget_ctx ctx = {1000, 0};
    rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
    ck_assert_int_eq(rugo_shape_desc_parse(t, strlen(t), &a, &desc, NULL), RUGO_OK);
    ck_assert_int_eq(ctx.live, 1);
    ck_assert_ptr_eq(desc.allocator.ctx, &ctx);
    rugo_shape_desc_free(&desc);
    ck_assert_int_eq(ctx.live, 0);
}
END_TEST

START_TEST(shape_parse_errors) {
    /* Syntax */
    expect_shape_fail("{\"control_points\": [[1, 2]", RUGO_ERR_PARSE, "control_points", "missing ']'");
    expect_shape_fail("{\"control_points\": [[1, 2], [3, ]]}", RUGO_ERR_PARSE, "control_points[1][1]", NULL);
    expect_shape_fail("{\"control_points\": [[1, NaN]]}", RUGO_ERR_PARSE, "control_points[0][1]", "NaN");
    expect_shape_fail("{\"control_points\": [[1, 2]]} {}", RUGO_ERR_PARSE, "", "after the JSON value");
    expect_shape_fail("", RUGO_ERR_PARSE, "", "empty");
    /* Numbers out of range */
    expect_shape_fail("{\"control_points\": [[1, 1e400]]}", RUGO_ERR_NOT_FINITE, "control_points[0][1]",
                      "infinity");
    expect_shape_fail("{\"control_points\": [[-2e308, 0]]}", RUGO_ERR_NOT_FINITE, "control_points[0][0]",
                      NULL);
    /* Missing or wrongly typed fields */
    expect_shape_fail("{}", RUGO_ERR_BAD_FIELD, "control_points", "missing field \"control_points\"");
    expect_shape_fail("{\"points\": [[1, 2]]}", RUGO_ERR_BAD_FIELD, "control_points", "missing");
    expect_shape_fail("[[1, 2]]", RUGO_ERR_BAD_FIELD, "",
                      "expected a JSON object at the top level, found an array");
    expect_shape_fail("7", RUGO_ERR_BAD_FIELD, "", "found a number");
    expect_shape_fail("{\"control_points\": 5}", RUGO_ERR_BAD_FIELD, "control_points", "found a number");
    expect_shape_fail("{\"control_points\": {\"0\": [1, 2]}}", RUGO_ERR_BAD_FIELD, "control_points",
                      "found an object");
    expect_shape_fail("{\"control_points\": null}", RUGO_ERR_BAD_FIELD, "control_points", "found null");
    expect_shape_fail("{\"control_points\": [5]}", RUGO_ERR_BAD_FIELD, "control_points[0]", "found a number");
    expect_shape_fail("{\"control_points\": [[1]]}", RUGO_ERR_BAD_FIELD, "control_points[0]",
                      "array of 1 element");
    expect_shape_fail("{\"control_points\": [[1, 2], [1, 2, 3]]}", RUGO_ERR_BAD_FIELD, "control_points[1]",
                      "array of 3 elements");
    expect_shape_fail("{\"control_points\": [[1, 2], []]}", RUGO_ERR_BAD_FIELD, "control_points[1]",
                      "0 elements");
    expect_shape_fail("{\"control_points\": [[1, 2], [\"3\", 4]]}", RUGO_ERR_BAD_FIELD,
                      "control_points[1][0]", "expected a number, found a string");
    expect_shape_fail("{\"control_points\": [[1, null]]}", RUGO_ERR_BAD_FIELD, "control_points[0][1]",
                      "null");
    expect_shape_fail("{\"control_points\": [[1, true]]}", RUGO_ERR_BAD_FIELD, "control_points[0][1]",
                      "boolean");
    expect_shape_fail("{\"control_points\": [[1, [2]]]}", RUGO_ERR_BAD_FIELD, "control_points[0][1]",
                      "array");
    expect_shape_fail("{\"control_points\": [[1, 2]], \"control_points\": [[3, 4]]}", RUGO_ERR_BAD_FIELD,
                      "control_points", "appears 2 times");
    /* The filter */
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": 8}", RUGO_ERR_BAD_FIELD, "filter",
                      "found a number");
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": null}", RUGO_ERR_BAD_FIELD, "filter", NULL);
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": \"cdf4.3\"}", RUGO_ERR_BAD_FILTER, "filter",
                      "unknown filter \"cdf4.3\" (expected one of cdf4.2, cdf4.4, cdf4.6, cdf4.8, cdf4.12)");
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": \"\"}", RUGO_ERR_BAD_FILTER, "filter",
                      NULL);
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": \"cdf4.8 \"}", RUGO_ERR_BAD_FILTER,
                      "filter", NULL);
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": \"cdf4.8\\u0000x\"}", RUGO_ERR_BAD_FILTER,
                      "filter", "cdf4.8\\x00x");
    expect_shape_fail("{\"control_points\": [[1, 2]], \"filter\": \"cdf4.8\", \"filter\": \"cdf4.8\"}",
                      RUGO_ERR_BAD_FIELD, "filter", "appears 2 times");
    /* A hostile filter name is quoted safely and cut. */
    char big[600];
    int n = snprintf(big, sizeof big, "{\"control_points\": [], \"filter\": \"");
    for (int i = 0; i < 300; ++i)
        big[n++] = (i % 2) ? 'A' : '\x7f';
    memcpy(big + n, "\"}", 3);
    rugo_shape_desc desc;
    rugo_parse_error err;
    ck_assert_int_eq(shape_parse_n(big, strlen(big), &desc, &err), RUGO_ERR_BAD_FILTER);
    ck_assert_ptr_nonnull(strstr(err.message, "\\x7fA\\x7fA"));
    ck_assert_ptr_nonnull(strstr(err.message, "...\""));
    ck_assert(str_nul_terminated(err.message, sizeof err.message));

    /* NULL arguments; error may be NULL. */
    ck_assert_int_eq(rugo_shape_desc_parse(NULL, 0, NULL, &desc, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_parse("{}", 2, NULL, NULL, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_parse("{}", 2, NULL, &desc, NULL), RUGO_ERR_BAD_FIELD);
    rugo_point_list pts;
    pts.points = (rugo_vec2*)1;
    pts.count = 7;
    ck_assert_int_eq(rugo_points_parse("{}", 2, NULL, NULL, &pts, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_ptr_null(pts.points);
    ck_assert_int_eq(pts.count, 0);
    ck_assert_int_eq(rugo_points_parse("{}", 2, "points", NULL, NULL, &err), RUGO_ERR_NULL_ARGUMENT);
}
END_TEST

START_TEST(shape_error_positions) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\n  \"control_points\": [\n    [0, 0],\n    [1, \"x\"]\n  ]\n}\n";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "control_points[1][1]");
    ck_assert_int_eq(err.line, 4);
    ck_assert_int_eq(err.column, 9);
    const char* t2 = "{\n  \"control_points\": [\n    [0, 0],\n    [1, 2, 3]\n  ]\n}\n";
    ck_assert_int_eq(shape_parse_n(t2, strlen(t2), &desc, &err), RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "control_points[1]");
    ck_assert_int_eq(err.line, 4);
    ck_assert_int_eq(err.column, 5);
    const char* t3 = "{\"control_points\": [],\n \"filter\": \"haar\"}";
    ck_assert_int_eq(shape_parse_n(t3, strlen(t3), &desc, &err), RUGO_ERR_BAD_FILTER);
    ck_assert_int_eq(err.line, 2);
    ck_assert_int_eq(err.column, 12);
    const char* t4 = "\n\n  {\"name\": 1}";
    ck_assert_int_eq(shape_parse_n(t4, strlen(t4), &desc, &err), RUGO_ERR_BAD_FIELD);
    ck_assert_int_eq(err.line, 3);
    ck_assert_int_eq(err.column, 3);
}
END_TEST

START_TEST(shape_not_nul_terminated) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\"control_points\": [[1, 2], [3, 4], [5, 6], [7, 8]]}garbage";
    size_t n = strlen(t) - strlen("garbage");
    ck_assert_int_eq(shape_parse_n(t, n, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 4);
    ck_assert(desc.control_points[3].y == 8.0);
    rugo_shape_desc_free(&desc);
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_ERR_PARSE);
    /* A prefix without the closing "]}". */
    ck_assert_int_eq(shape_parse_n(t, n - 2, &desc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, (int)n - 1);
}
END_TEST

static char* points_text(int count, size_t* length) {
    const char* head = "{\"control_points\":[";
    size_t n = strlen(head) + 6 * (size_t)count + 2;
    char* t = (char*)malloc(n);
    ck_assert_ptr_nonnull(t);
    size_t k = strlen(head);
    memcpy(t, head, k);
    for (int i = 0; i < count; ++i) {
        memcpy(t + k, "[0,1],", 6);
        k += 6;
    }
    k -= 1; /* last comma */
    memcpy(t + k, "]}", 2);
    k += 2;
    *length = k;
    return t;
}

START_TEST(shape_too_many_points) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    size_t n = 0;
    char* t = points_text(RUGO_MAX_CONTROL_POINTS + 1, &n);
    ck_assert_int_eq(rugo_shape_desc_parse(t, n, NULL, &desc, &err), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_str_eq(err.path, "control_points");
    ck_assert_ptr_nonnull(strstr(err.message, "1048577 points"));
    ck_assert_int_eq(err.column, 19);
    rugo_point_list pts;
    ck_assert_int_eq(rugo_points_parse(t, n, "control_points", NULL, &pts, &err), RUGO_ERR_TOO_MANY_POINTS);
    free(t);
    t = points_text(RUGO_MAX_CONTROL_POINTS, &n);
    ck_assert_int_eq(rugo_shape_desc_parse(t, n, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, RUGO_MAX_CONTROL_POINTS);
    ck_assert(desc.control_points[RUGO_MAX_CONTROL_POINTS - 1].y == 1.0);
    rugo_shape_desc_free(&desc);
    free(t);

    /* The writer refuses what the reader would. */
    rugo_shape_desc big = make_desc(NULL, RUGO_MAX_CONTROL_POINTS + 1, RUGO_FILTER_DEFAULT);
    rugo_text text;
    rugo_vec2 dummy = {0, 0};
    big.control_points = &dummy;
    ck_assert_int_eq(rugo_shape_desc_write(&big, NULL, &text), RUGO_ERR_TOO_MANY_POINTS);
}
END_TEST

START_TEST(shape_max_size_file_fits) {
    /* The longest shape the writer can produce (2^20 points, every coordinate 24 characters) is within
     * RUGO_MAX_JSON_BYTES and reads back. */
    int n = RUGO_MAX_CONTROL_POINTS;
    rugo_vec2* pts = (rugo_vec2*)malloc(sizeof *pts * (size_t)n);
    for (int i = 0; i < n; ++i)
        pts[i] = rugo_v2(-2.2250738585072014e-308, -1.2345678901234567e-300);
    rugo_shape_desc desc = make_desc(pts, n, RUGO_FILTER_CDF4_12);
    rugo_text text;
    ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
    ck_assert_uint_le(text.length, RUGO_MAX_JSON_BYTES);
    rugo_shape_desc back;
    rugo_parse_error err;
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err), RUGO_OK);
    ck_assert_int_eq(back.count, n);
    ck_assert(memcmp(back.control_points, pts, sizeof *pts * (size_t)n) == 0);
    rugo_shape_desc_free(&back);
    rugo_text_free(&text);
    free(pts);
}
END_TEST

START_TEST(shape_round_trip_bits) {
    test_rng r = test_rng_seed(20240601);
    for (int iter = 0; iter < 300; ++iter) {
        int n = (int)(test_rng_next(&r) % 64);
        rugo_vec2 pts[64];
        for (int i = 0; i < n; ++i) {
            pts[i].x = random_double(&r);
            pts[i].y = random_double(&r);
        }
        rugo_shape_desc desc = make_desc(pts, n, (rugo_filter)(test_rng_next(&r) % RUGO_FILTER_COUNT));
        rugo_text text;
        ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
        ck_assert_int_eq((int)strlen(text.data), (int)text.length);
        ck_assert_int_eq(text.data[text.length - 1], '\n');
        rugo_shape_desc back;
        rugo_parse_error err;
        ck_assert_msg(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err) == RUGO_OK,
                      "%s at %d:%d", err.message, err.line, err.column);
        ck_assert_int_eq(back.count, n);
        ck_assert_int_eq(back.filter, desc.filter);
        for (int i = 0; i < n; ++i) {
            ck_assert(bits_of(back.control_points[i].x) == bits_of(pts[i].x));
            ck_assert(bits_of(back.control_points[i].y) == bits_of(pts[i].y));
        }
        /* Writing again gives the same text. */
        rugo_text text2;
        ck_assert_int_eq(rugo_shape_desc_write(&back, NULL, &text2), RUGO_OK);
        ck_assert_int_eq((int)text2.length, (int)text.length);
        ck_assert(memcmp(text.data, text2.data, text.length) == 0);
        rugo_text_free(&text2);
        rugo_shape_desc_free(&back);
        rugo_text_free(&text);
    }
    /* The layout, once */
    rugo_vec2 two[2] = {{0.5, -0.0}, {1e300, 5e-324}};
    rugo_shape_desc d = make_desc(two, 2, RUGO_FILTER_CDF4_4);
    rugo_text text;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_str_eq(text.data, "{\n  \"control_points\": [\n    [0.5, -0],\n    [1.0000000000000001e+300, "
                                "4.9406564584124654e-324]\n  ],\n  \"filter\": \"cdf4.4\"\n}\n");
    rugo_text_free(&text);
    d.count = 0;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_str_eq(text.data, "{\n  \"control_points\": [],\n  \"filter\": \"cdf4.4\"\n}\n");
    rugo_text_free(&text);
}
END_TEST

START_TEST(shape_write_errors) {
    rugo_vec2 pts[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_shape_desc d = make_desc(pts, 4, RUGO_FILTER_DEFAULT);
    rugo_text text;
    text.data = (char*)1;
    text.length = 5;
    pts[2].y = NAN;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_NOT_FINITE);
    ck_assert_ptr_null(text.data);
    ck_assert_int_eq((int)text.length, 0);
    pts[2].y = -INFINITY;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_NOT_FINITE);
    pts[2].y = 1.0;
    d.filter = RUGO_FILTER_COUNT;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_BAD_FILTER);
    d.filter = (rugo_filter)-1;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_BAD_FILTER);
    d.filter = RUGO_FILTER_DEFAULT;
    d.count = -1;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_BAD_ARGUMENT);
    d.count = 4;
    d.control_points = NULL;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_NULL_ARGUMENT);
    d.control_points = pts;
    ck_assert_int_eq(rugo_shape_desc_write(NULL, NULL, &text), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert(text.allocator.alloc != NULL); /* the default allocator, recorded */
    rugo_text_free(&text);
    ck_assert(text.data == NULL && text.length == 0);
    rugo_text_free(&text); /* a zeroed text, and NULL, are fine */
    rugo_text_free(NULL);
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* Roughness in shape descriptions */

static const char* const SQUARE4 = "\"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]]";

/* {SQUARE4, "roughness": {<body>}} */
static void rough_text(const char* body, char* out, size_t size) {
    snprintf(out, size, "{%s, \"roughness\": {%s}}", SQUARE4, body);
}

static void expect_rough_fail(const char* body, rugo_status status, const char* path, const char* fragment) {
    char buf[1024];
    rough_text(body, buf, sizeof buf);
    expect_shape_fail(buf, status, path, fragment);
}

static rugo_shape_desc parse_rough_ok(const char* body) {
    char buf[1024];
    rough_text(body, buf, sizeof buf);
    rugo_shape_desc desc;
    rugo_parse_error err;
    rugo_status st = shape_parse_n(buf, strlen(buf), &desc, &err);
    ck_assert_msg(st == RUGO_OK, "input <%s>: status %d (%s) at %s: %s", buf, (int)st, rugo_status_string(st),
                  err.path, err.message);
    ck_assert_int_eq(desc.count, 4);
    ck_assert(desc.has_roughness);
    return desc;
}

/* Every member of two roughness descriptions, bit for bit. */
static void assert_same_roughness(const rugo_roughness_desc* a, const rugo_roughness_desc* b) {
    ck_assert_int_eq(a->kind, b->kind);
    if (a->kind == RUGO_ROUGHNESS_PRESET) ck_assert_int_eq(a->preset, b->preset);
    if (a->kind == RUGO_ROUGHNESS_CONSTANT) ck_assert(bits_of(a->constant) == bits_of(b->constant));
    if (a->kind == RUGO_ROUGHNESS_TOLERANCES) {
        ck_assert_int_eq(a->tolerance_count, b->tolerance_count);
        for (int i = 0; i < a->tolerance_count; ++i)
            ck_assert(bits_of(a->tolerances[i]) == bits_of(b->tolerances[i]));
    }
    if (a->kind == RUGO_ROUGHNESS_RANGES) {
        ck_assert_int_eq(a->range_count, b->range_count);
        ck_assert(bits_of(a->background) == bits_of(b->background));
        for (int i = 0; i < a->range_count; ++i) {
            ck_assert(bits_of(a->ranges[i].from) == bits_of(b->ranges[i].from));
            ck_assert(bits_of(a->ranges[i].to) == bits_of(b->ranges[i].to));
            ck_assert(bits_of(a->ranges[i].tolerance) == bits_of(b->ranges[i].tolerance));
        }
    }
    if (a->kind == RUGO_ROUGHNESS_PROFILE) {
        ck_assert_int_eq(a->profile_count, b->profile_count);
        for (int i = 0; i < a->profile_count; ++i) {
            ck_assert(bits_of(a->profile[i].s) == bits_of(b->profile[i].s));
            ck_assert(bits_of(a->profile[i].tolerance) == bits_of(b->profile[i].tolerance));
        }
    }
    ck_assert(a->seed == b->seed);
    ck_assert(bits_of(a->q) == bits_of(b->q));
    ck_assert_int_eq(a->estimator, b->estimator);
    ck_assert(bits_of(a->friction.alpha) == bits_of(b->friction.alpha));
    ck_assert(bits_of(a->friction.lambda_min) == bits_of(b->friction.lambda_min));
    ck_assert(bits_of(a->friction.base) == bits_of(b->friction.base));
    ck_assert(bits_of(a->restitution.epsilon) == bits_of(b->restitution.epsilon));
    ck_assert(bits_of(a->restitution.epsilon_max) == bits_of(b->restitution.epsilon_max));
    ck_assert_int_eq(a->has_perturbation, b->has_perturbation);
    if (a->has_perturbation) {
        ck_assert_int_eq(a->perturbation_method, b->perturbation_method);
        ck_assert_int_eq(a->perturbation_levels, b->perturbation_levels);
        ck_assert_int_eq(a->perturbation_count, b->perturbation_count);
        for (int i = 0; i < a->perturbation_count; ++i) {
            ck_assert(bits_of(a->perturbation_points[i].x) == bits_of(b->perturbation_points[i].x));
            ck_assert(bits_of(a->perturbation_points[i].y) == bits_of(b->perturbation_points[i].y));
        }
    }
}

static void assert_default_settings(const rugo_roughness_desc* r) {
    rugo_roughness_desc d = rugo_default_roughness_desc();
    ck_assert(r->seed == 0);
    ck_assert(bits_of(r->q) == bits_of(RUGO_DEFAULT_Q));
    ck_assert_int_eq(r->estimator, RUGO_ESTIMATOR_DETAIL);
    ck_assert(r->friction.alpha == d.friction.alpha && r->friction.lambda_min == d.friction.lambda_min);
    ck_assert(r->restitution.epsilon == d.restitution.epsilon &&
              r->restitution.epsilon_max == d.restitution.epsilon_max);
    ck_assert_int_eq(r->has_perturbation, 0);
    ck_assert_ptr_null(r->perturbation_points);
}

START_TEST(roughness_defaults) {
    rugo_roughness_desc d = rugo_default_roughness_desc();
    ck_assert_int_eq(d.kind, RUGO_ROUGHNESS_PRESET);
    ck_assert_int_eq(d.preset, RUGO_PRESET_TIPO_1);
    ck_assert(d.seed == 0);
    ck_assert(d.q == RUGO_DEFAULT_Q);
    ck_assert_int_eq(d.estimator, RUGO_ESTIMATOR_DETAIL);
    rugo_friction_map fm = rugo_default_friction_map();
    rugo_restitution rs = rugo_default_restitution();
    ck_assert(d.friction.alpha == fm.alpha && d.friction.lambda_min == fm.lambda_min);
    ck_assert(d.restitution.epsilon == rs.epsilon && d.restitution.epsilon_max == rs.epsilon_max);
    ck_assert_ptr_null(d.tolerances);
    ck_assert(!d.has_perturbation);
    /* A shape without roughness says so. */
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]]}";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_OK);
    ck_assert(!desc.has_roughness);
    rugo_shape_desc_free(&desc);
}
END_TEST

START_TEST(roughness_parse_valid) {
    /* Every preset, with the defaults for everything else. */
    for (int p = 0; p < RUGO_PRESET_COUNT; ++p) {
        char body[64];
        snprintf(body, sizeof body, "\"preset\": \"%s\"", rugo_preset_name((rugo_tolerance_preset)p));
        rugo_shape_desc d = parse_rough_ok(body);
        ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_PRESET);
        ck_assert_int_eq(d.roughness.preset, p);
        ck_assert_ptr_null(d.roughness.tolerances);
        assert_default_settings(&d.roughness);
        rugo_shape_desc_free(&d);
        ck_assert(!d.has_roughness);
    }
    /* Per-segment values (zero and negative zero are tolerances too). */
    rugo_shape_desc d = parse_rough_ok("\"tolerances\": [0.25, 0, -0, 1e-300]");
    ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_TOLERANCES);
    ck_assert_int_eq(d.roughness.tolerance_count, 4);
    ck_assert(d.roughness.tolerances[0] == 0.25 && d.roughness.tolerances[3] == 1e-300);
    ck_assert(bits_of(d.roughness.tolerances[2]) == bits_of(-0.0));
    assert_default_settings(&d.roughness);
    rugo_shape_desc_free(&d);
    ck_assert_ptr_null(d.roughness.tolerances);
    d = parse_rough_ok("\"constant\": 0.125");
    ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_CONSTANT);
    ck_assert(d.roughness.constant == 0.125);
    rugo_shape_desc_free(&d);

    /* Everything given; unknown members are ignored; members in any order. */
    d = parse_rough_ok(
        "\"note\": {\"x\": [null]}, \"seed\": 9007199254740992, \"q\": 1.96, \"estimator\": "
        "\"coefficients\", \"friction\": {\"lambda_min\": 0.1, \"alpha\": 2, \"base\": 0.25, \"unit\": "
        "\"m\"}, "
        "\"restitution\": {\"epsilon\": 0.3, \"epsilon_max\": 0.8}, \"perturbation\": "
        "{\"method\": \"local\", \"levels\": 1, \"control_points\": [[0, 0], [0.5, 0], [1, 0], "
        "[1, 0.5], [1, 1], [0.5, 1], [0, 1], [0, 0.5]]}, \"preset\": \"tipo_2\"");
    const rugo_roughness_desc* r = &d.roughness;
    ck_assert_int_eq(r->preset, RUGO_PRESET_TIPO_2);
    ck_assert(r->seed == ((uint64_t)1 << 53));
    ck_assert(r->q == 1.96);
    ck_assert_int_eq(r->estimator, RUGO_ESTIMATOR_COEFFICIENTS);
    ck_assert(r->friction.alpha == 2.0 && r->friction.lambda_min == 0.1 && r->friction.base == 0.25);
    ck_assert(r->restitution.epsilon == 0.3 && r->restitution.epsilon_max == 0.8);
    ck_assert_int_eq(r->has_perturbation, 1);
    ck_assert_int_eq(r->perturbation_method, RUGO_ROUGHEN_LOCAL);
    ck_assert_int_eq(r->perturbation_levels, 1);
    ck_assert_int_eq(r->perturbation_count, 8);
    ck_assert(r->perturbation_points[3].x == 1.0 && r->perturbation_points[3].y == 0.5);
    rugo_shape_desc_free(&d);
    ck_assert_ptr_null(d.roughness.perturbation_points);

    /* Partial sub-objects keep the other defaults; seeds in digits of any length up to 2^53. */
    d = parse_rough_ok(
        "\"constant\": 0, \"seed\": 12345678901234, \"friction\": {\"alpha\": 3}, "
        "\"restitution\": {\"epsilon_max\": 1}, \"estimator\": \"detail\", \"perturbation\": "
        "{\"method\": \"wavelet\", \"levels\": 2.0, \"control_points\": [" /* 16 points */
        "[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],"
        "[0,0]]}");
    ck_assert(d.roughness.seed == 12345678901234ull);
    ck_assert(d.roughness.friction.alpha == 3.0);
    ck_assert(d.roughness.friction.lambda_min == rugo_default_friction_map().lambda_min);
    ck_assert(d.roughness.restitution.epsilon == rugo_default_restitution().epsilon);
    ck_assert(d.roughness.restitution.epsilon_max == 1.0);
    ck_assert_int_eq(d.roughness.perturbation_method, RUGO_ROUGHEN_WAVELET);
    ck_assert_int_eq(d.roughness.perturbation_levels, 2);
    ck_assert_int_eq(d.roughness.perturbation_count, 16);
    rugo_shape_desc_free(&d);
    d = parse_rough_ok("\"preset\": \"tipo_1\", \"seed\": 0, \"q\": 1e-300");
    ck_assert(d.roughness.seed == 0 && d.roughness.q == 1e-300);
    rugo_shape_desc_free(&d);

    /* No control points: an empty list of tolerances matches. */
    rugo_parse_error err;
    const char* e = "{\"control_points\": [], \"roughness\": {\"tolerances\": []}}";
    ck_assert_int_eq(shape_parse_n(e, strlen(e), &d, &err), RUGO_OK);
    ck_assert(d.has_roughness);
    ck_assert_int_eq(d.roughness.tolerance_count, 0);
    rugo_shape_desc_free(&d);

    /* A custom allocator holds the points, the tolerances and the perturbation, and frees them. */
    test_budget_ctx ctx = {1000, 0};
    rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
    char buf[1024];
    rough_text("\"tolerances\": [1, 2, 3, 4], \"perturbation\": {\"method\": \"local\", \"levels\": 1, "
               "\"control_points\": [[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]]}",
               buf, sizeof buf);
    ck_assert_int_eq(rugo_shape_desc_parse(buf, strlen(buf), &a, &d, &err), RUGO_OK);
    ck_assert_int_eq(ctx.live, 3);
    rugo_shape_desc_free(&d);
    ck_assert_int_eq(ctx.live, 0);

    /* The sample files */
    rugo_text text = read_data("star32_tipo5.json");
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &d, &err), RUGO_OK);
    ck_assert_int_eq(d.count, 32);
    ck_assert(d.has_roughness);
    ck_assert_int_eq(d.roughness.preset, RUGO_PRESET_TIPO_5);
    ck_assert(d.roughness.seed == 7 && d.roughness.friction.alpha == 1.5 &&
              d.roughness.restitution.epsilon == 0.4);
    rugo_shape_desc_free(&d);
    rugo_text_free(&text);
    text = read_data("square8_cw_tolerances.json");
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &d, &err), RUGO_OK);
    ck_assert_int_eq(d.count, 8);
    ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_TOLERANCES);
    ck_assert(d.roughness.tolerances[7] == 0.8 && d.roughness.seed == 42);
    rugo_shape_desc_free(&d);
    rugo_text_free(&text);
}
END_TEST

START_TEST(roughness_parse_errors) {
    char buf[1024];
    /* The member itself */
    snprintf(buf, sizeof buf, "{%s, \"roughness\": null}", SQUARE4);
    expect_shape_fail(buf, RUGO_ERR_BAD_FIELD, "roughness", "found null");
    snprintf(buf, sizeof buf, "{%s, \"roughness\": [\"tipo_1\"]}", SQUARE4);
    expect_shape_fail(buf, RUGO_ERR_BAD_FIELD, "roughness", "found an array");
    snprintf(buf, sizeof buf, "{%s, \"roughness\": \"tipo_1\"}", SQUARE4);
    expect_shape_fail(buf, RUGO_ERR_BAD_FIELD, "roughness", "found a string");
    snprintf(buf, sizeof buf, "{%s, \"roughness\": {\"constant\": 1}, \"roughness\": {\"constant\": 1}}",
             SQUARE4);
    expect_shape_fail(buf, RUGO_ERR_BAD_FIELD, "roughness", "appears 2 times");
    /* Exactly one source of tolerances */
    expect_rough_fail("", RUGO_ERR_BAD_FIELD, "roughness", "needs one of");
    expect_rough_fail("\"seed\": 3", RUGO_ERR_BAD_FIELD, "roughness", "needs one of");
    expect_rough_fail("\"preset\": \"tipo_1\", \"constant\": 1", RUGO_ERR_BAD_FIELD, "roughness",
                      "found \"preset\" and \"constant\"");
    expect_rough_fail("\"tolerances\": [1, 1, 1, 1], \"preset\": \"tipo_1\"", RUGO_ERR_BAD_FIELD, "roughness",
                      "only one of");
    expect_rough_fail("\"preset\": \"tipo_1\", \"tolerances\": [1, 1, 1, 1], \"constant\": 1",
                      RUGO_ERR_BAD_FIELD, "roughness", "only one of");
    /* preset */
    expect_rough_fail("\"preset\": \"tipo_4\"", RUGO_ERR_BAD_FIELD, "roughness.preset",
                      "unknown preset \"tipo_4\" (expected one of tipo_1, tipo_2, tipo_3, tipo_5)");
    expect_rough_fail("\"preset\": \"TIPO_1\"", RUGO_ERR_BAD_FIELD, "roughness.preset", NULL);
    expect_rough_fail("\"preset\": \"tipo_1\\u0000\"", RUGO_ERR_BAD_FIELD, "roughness.preset", "tipo_1\\x00");
    expect_rough_fail("\"preset\": 1", RUGO_ERR_BAD_FIELD, "roughness.preset", "found a number");
    expect_rough_fail("\"preset\": null", RUGO_ERR_BAD_FIELD, "roughness.preset", "found null");
    expect_rough_fail("\"preset\": \"tipo_1\", \"preset\": \"tipo_1\"", RUGO_ERR_BAD_FIELD,
                      "roughness.preset", "appears 2 times");
    /* tolerances */
    expect_rough_fail("\"tolerances\": 0.5", RUGO_ERR_BAD_FIELD, "roughness.tolerances", "found a number");
    expect_rough_fail("\"tolerances\": [1, 1, 1]", RUGO_ERR_BAD_FIELD, "roughness.tolerances",
                      "3 tolerances for 4 control points");
    expect_rough_fail("\"tolerances\": [1, 1, 1, 1, 1]", RUGO_ERR_BAD_FIELD, "roughness.tolerances",
                      "5 tolerances");
    expect_rough_fail("\"tolerances\": []", RUGO_ERR_BAD_FIELD, "roughness.tolerances", "0 tolerances");
    expect_rough_fail("\"tolerances\": [1, 1, \"1\", 1]", RUGO_ERR_BAD_FIELD, "roughness.tolerances[2]",
                      "found a string");
    expect_rough_fail("\"tolerances\": [1, [1], 1, 1]", RUGO_ERR_BAD_FIELD, "roughness.tolerances[1]",
                      "array");
    expect_rough_fail("\"tolerances\": [1, -0.5, 1, 1]", RUGO_ERR_NEGATIVE_TOLERANCE,
                      "roughness.tolerances[1]", "-0.5");
    expect_rough_fail("\"tolerances\": [1, 1, 1, -4.9406564584124654e-324]", RUGO_ERR_NEGATIVE_TOLERANCE,
                      "roughness.tolerances[3]", NULL);
    expect_rough_fail("\"tolerances\": [1, 1e999, 1, 1]", RUGO_ERR_NOT_FINITE, "roughness.tolerances[1]",
                      NULL);
    /* constant */
    expect_rough_fail("\"constant\": -1", RUGO_ERR_NEGATIVE_TOLERANCE, "roughness.constant", NULL);
    expect_rough_fail("\"constant\": \"0.25\"", RUGO_ERR_BAD_FIELD, "roughness.constant", "found a string");
    expect_rough_fail("\"constant\": -1e400", RUGO_ERR_NOT_FINITE, "roughness.constant", NULL);
    expect_rough_fail("\"constant\": true", RUGO_ERR_BAD_FIELD, "roughness.constant", "boolean");
    /* seed: an integer in digits, 0..2^53 */
    expect_rough_fail("\"constant\": 1, \"seed\": -1", RUGO_ERR_BAD_FIELD, "roughness.seed", "non-negative");
    expect_rough_fail("\"constant\": 1, \"seed\": -0", RUGO_ERR_BAD_FIELD, "roughness.seed", NULL);
    expect_rough_fail("\"constant\": 1, \"seed\": 1.5", RUGO_ERR_BAD_FIELD, "roughness.seed", "fraction");
    expect_rough_fail("\"constant\": 1, \"seed\": 1.0", RUGO_ERR_BAD_FIELD, "roughness.seed", NULL);
    expect_rough_fail("\"constant\": 1, \"seed\": 1e3", RUGO_ERR_BAD_FIELD, "roughness.seed", "exponent");
    expect_rough_fail("\"constant\": 1, \"seed\": 1E3", RUGO_ERR_BAD_FIELD, "roughness.seed", NULL);
    expect_rough_fail("\"constant\": 1, \"seed\": 9007199254740993", RUGO_ERR_BAD_FIELD, "roughness.seed",
                      "exceeds 2^53");
    expect_rough_fail("\"constant\": 1, \"seed\": 18446744073709551616", RUGO_ERR_BAD_FIELD, "roughness.seed",
                      "exceeds");
    expect_rough_fail("\"constant\": 1, \"seed\": "
                      "123456789012345678901234567890123456789012345678901234567890",
                      RUGO_ERR_BAD_FIELD, "roughness.seed", "exceeds");
    expect_rough_fail("\"constant\": 1, \"seed\": \"5\"", RUGO_ERR_BAD_FIELD, "roughness.seed",
                      "found a string");
    expect_rough_fail("\"constant\": 1, \"seed\": null", RUGO_ERR_BAD_FIELD, "roughness.seed", "found null");
    expect_rough_fail("\"constant\": 1, \"seed\": 1, \"seed\": 1", RUGO_ERR_BAD_FIELD, "roughness.seed",
                      "appears 2 times");
    /* q */
    expect_rough_fail("\"constant\": 1, \"q\": 0", RUGO_ERR_BAD_QUANTILE, "roughness.q", "> 0");
    expect_rough_fail("\"constant\": 1, \"q\": -0", RUGO_ERR_BAD_QUANTILE, "roughness.q", NULL);
    expect_rough_fail("\"constant\": 1, \"q\": -1.96", RUGO_ERR_BAD_QUANTILE, "roughness.q", NULL);
    expect_rough_fail("\"constant\": 1, \"q\": \"0.95\"", RUGO_ERR_BAD_FIELD, "roughness.q",
                      "found a string");
    expect_rough_fail("\"constant\": 1, \"q\": 1e999", RUGO_ERR_NOT_FINITE, "roughness.q", NULL);
    /* estimator */
    expect_rough_fail("\"constant\": 1, \"estimator\": \"mean\"", RUGO_ERR_BAD_FIELD, "roughness.estimator",
                      "unknown estimator \"mean\" (expected one of coefficients, detail)");
    expect_rough_fail("\"constant\": 1, \"estimator\": 0", RUGO_ERR_BAD_FIELD, "roughness.estimator",
                      "number");
    /* friction */
    expect_rough_fail("\"constant\": 1, \"friction\": [1, 0.04]", RUGO_ERR_BAD_FIELD, "roughness.friction",
                      "found an array");
    expect_rough_fail("\"constant\": 1, \"friction\": null", RUGO_ERR_BAD_FIELD, "roughness.friction",
                      "null");
    expect_rough_fail("\"constant\": 1, \"friction\": {\"alpha\": -1}", RUGO_ERR_BAD_ARGUMENT,
                      "roughness.friction", "alpha -1");
    expect_rough_fail("\"constant\": 1, \"friction\": {\"lambda_min\": -0.1}", RUGO_ERR_NEGATIVE_TOLERANCE,
                      "roughness.friction", NULL);
    expect_rough_fail("\"constant\": 1, \"friction\": {\"alpha\": \"1\"}", RUGO_ERR_BAD_FIELD,
                      "roughness.friction.alpha", "found a string");
    expect_rough_fail("\"constant\": 1, \"friction\": {\"alpha\": 1, \"alpha\": 1}", RUGO_ERR_BAD_FIELD,
                      "roughness.friction.alpha", "appears 2 times");
    expect_rough_fail("\"constant\": 1, \"friction\": {\"alpha\": 1e999}", RUGO_ERR_NOT_FINITE,
                      "roughness.friction.alpha", NULL);
    /* restitution */
    expect_rough_fail("\"constant\": 1, \"restitution\": 0.5", RUGO_ERR_BAD_FIELD, "roughness.restitution",
                      "found a number");
    expect_rough_fail("\"constant\": 1, \"restitution\": {\"epsilon\": 1.5}", RUGO_ERR_BAD_ARGUMENT,
                      "roughness.restitution", NULL);
    expect_rough_fail("\"constant\": 1, \"restitution\": {\"epsilon_max\": -0.1}", RUGO_ERR_BAD_ARGUMENT,
                      "roughness.restitution", NULL);
    expect_rough_fail("\"constant\": 1, \"restitution\": {\"epsilon\": 0.95}", RUGO_ERR_EMPTY_RANGE,
                      "roughness.restitution", "epsilon 0.94999999999999996");
    expect_rough_fail("\"constant\": 1, \"restitution\": {\"epsilon\": 0.6, \"epsilon_max\": 0.5}",
                      RUGO_ERR_EMPTY_RANGE, "roughness.restitution", NULL);
    expect_rough_fail("\"constant\": 1, \"restitution\": {\"epsilon\": null}", RUGO_ERR_BAD_FIELD,
                      "roughness.restitution.epsilon", "null");
    /* perturbation */
    static const char* const eight = "[[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]]";
    expect_rough_fail("\"constant\": 1, \"perturbation\": 1", RUGO_ERR_BAD_FIELD, "roughness.perturbation",
                      "found a number");
    expect_rough_fail("\"constant\": 1, \"perturbation\": {}", RUGO_ERR_BAD_FIELD,
                      "roughness.perturbation.method", "missing field \"method\"");
    char body[512];
    snprintf(body, sizeof body,
             "\"constant\": 1, \"perturbation\": {\"method\": \"fourier\", \"levels\": 1, "
             "\"control_points\": %s}",
             eight);
    expect_rough_fail(body, RUGO_ERR_BAD_FIELD, "roughness.perturbation.method",
                      "unknown method \"fourier\" (expected one of wavelet, local)");
    snprintf(body, sizeof body,
             "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"control_points\": %s}", eight);
    expect_rough_fail(body, RUGO_ERR_BAD_FIELD, "roughness.perturbation.levels", "missing field \"levels\"");
    static const char* const bad_levels[] = {"0", "-1", "21", "1.5", "\"1\"", "null", "1e999"};
    for (size_t i = 0; i < sizeof bad_levels / sizeof bad_levels[0]; ++i) {
        snprintf(
            body, sizeof body,
            "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": %s, \"control_points\": "
            "%s}",
            bad_levels[i], eight);
        expect_rough_fail(body,
                          strcmp(bad_levels[i], "1e999") == 0 ? RUGO_ERR_NOT_FINITE : RUGO_ERR_BAD_FIELD,
                          "roughness.perturbation.levels", NULL);
    }
    expect_rough_fail("\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 1}",
                      RUGO_ERR_BAD_FIELD, "roughness.perturbation.control_points",
                      "missing field \"control_points\"");
    expect_rough_fail(
        "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 2, \"control_points\": "
        "[[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]]}",
        RUGO_ERR_BAD_FIELD, "roughness.perturbation.control_points",
        "8 control points; 2 levels above 4 control points need 16");
    expect_rough_fail(
        "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 1, \"control_points\": "
        "[[0,0],[0,0],[0,0],[0],[0,0],[0,0],[0,0],[0,0]]}",
        RUGO_ERR_BAD_FIELD, "roughness.perturbation.control_points[3]", "array of 1 element");
    expect_rough_fail(
        "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 1, \"control_points\": "
        "[[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,1e999]]}",
        RUGO_ERR_NOT_FINITE, "roughness.perturbation.control_points[7][1]", NULL);
    expect_rough_fail(
        "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 1, \"control_points\": "
        "{}}",
        RUGO_ERR_BAD_FIELD, "roughness.perturbation.control_points", "found an object");
    snprintf(body, sizeof body,
             "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"method\": \"local\", "
             "\"levels\": 1, \"control_points\": %s}",
             eight);
    expect_rough_fail(body, RUGO_ERR_BAD_FIELD, "roughness.perturbation.method", "appears 2 times");
    snprintf(body, sizeof body,
             "\"constant\": 1, \"perturbation\": {\"method\": \"local\", \"levels\": 1, "
             "\"control_points\": %s}, \"perturbation\": null",
             eight);
    expect_rough_fail(body, RUGO_ERR_BAD_FIELD, "roughness.perturbation", "appears 2 times");

    /* Positions: line and column of the offending value. */
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\n  \"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]],\n  \"roughness\": {\n"
                    "    \"tolerances\": [0.1, 0.2,\n                   -0.3, 0.4]\n  }\n}\n";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_str_eq(err.path, "roughness.tolerances[2]");
    ck_assert_int_eq(err.line, 5);
    ck_assert_int_eq(err.column, 20);
    const char* t2 = "{\"control_points\": [],\n \"roughness\": {\"constant\": 0,\n \"seed\": 2.5}}";
    ck_assert_int_eq(shape_parse_n(t2, strlen(t2), &desc, &err), RUGO_ERR_BAD_FIELD);
    ck_assert_int_eq(err.line, 3);
    ck_assert_int_eq(err.column, 10);
    /* error may be NULL; nothing leaks on any error (the sanitizer build checks). */
    rough_text("\"tolerances\": [1, 2, 3, 4], \"q\": 0", buf, sizeof buf);
    ck_assert_int_eq(rugo_shape_desc_parse(buf, strlen(buf), NULL, &desc, NULL), RUGO_ERR_BAD_QUANTILE);
    ck_assert(!desc.has_roughness);
    ck_assert_ptr_null(desc.roughness.tolerances);
}
END_TEST

/* A random valid roughness for n control points; arrays from malloc (free with free_random_roughness). */
static rugo_roughness_desc random_roughness(test_rng* r, int n) {
    rugo_roughness_desc d = rugo_default_roughness_desc();
    d.kind = (rugo_roughness_kind)(test_rng_next(r) % RUGO_ROUGHNESS_KIND_COUNT);
    d.preset = (rugo_tolerance_preset)(test_rng_next(r) % RUGO_PRESET_COUNT);
    if (d.kind == RUGO_ROUGHNESS_TOLERANCES) {
        d.tolerances = (rugo_real*)malloc(sizeof(rugo_real) * (size_t)(n > 0 ? n : 1));
        for (int i = 0; i < n; ++i) {
            double x = fabs(random_double(r));
            d.tolerances[i] = (test_rng_next(r) % 8 == 0) ? -0.0 : x;
        }
        d.tolerance_count = n;
    }
    if (d.kind == RUGO_ROUGHNESS_RANGES) { /* 0 to 3 ranges, any bits in [0, 1] */
        d.range_count = (int)(test_rng_next(r) % 4);
        d.ranges = (rugo_roughness_range*)malloc(sizeof(rugo_roughness_range) * 4);
        for (int i = 0; i < d.range_count; ++i) {
            d.ranges[i].from = test_rng_uniform(r, 0.0, 1.0);
            d.ranges[i].to = test_rng_next(r) % 4 == 0 ? 1.0 : test_rng_uniform(r, 0.0, 1.0);
            d.ranges[i].tolerance = fabs(random_double(r));
        }
        d.background = fabs(random_double(r));
    }
    if (d.kind == RUGO_ROUGHNESS_PROFILE) { /* 1 to 4 samples, strictly increasing s */
        d.profile_count = 1 + (int)(test_rng_next(r) % 4);
        d.profile = (rugo_profile_sample*)malloc(sizeof(rugo_profile_sample) * 4);
        for (int i = 0; i < d.profile_count; ++i) {
            d.profile[i].s = (i + test_rng_uniform(r, 0.0, 1.0)) / 4.0;
            d.profile[i].tolerance = fabs(random_double(r));
        }
    }
    d.constant = fabs(random_double(r));
    switch (test_rng_next(r) % 4) {
    case 0:
        d.seed = 0;
        break;
    case 1:
        d.seed = RUGO_MAX_FILE_SEED;
        break;
    case 2:
        d.seed = test_rng_next(r) % 1000;
        break;
    default:
        d.seed = test_rng_next(r) % (RUGO_MAX_FILE_SEED + 1);
        break;
    }
    do
        d.q = fabs(random_double(r));
    while (!(d.q > 0.0));
    d.estimator = (test_rng_next(r) % 2) ? RUGO_ESTIMATOR_COEFFICIENTS : RUGO_ESTIMATOR_DETAIL;
    d.friction.alpha = fabs(random_double(r));
    d.friction.lambda_min = fabs(random_double(r));
    double e1 = test_rng_uniform(r, 0.0, 1.0), e2 = test_rng_uniform(r, 0.0, 1.0);
    d.restitution.epsilon = e1 < e2 ? e1 : e2;
    d.restitution.epsilon_max = e1 < e2 ? e2 : e1;
    if (test_rng_next(r) % 2 && n <= 16) {
        d.has_perturbation = true;
        d.perturbation_method = (rugo_roughen_method)(test_rng_next(r) % 2);
        d.perturbation_levels = 1 + (int)(test_rng_next(r) % 3);
        d.perturbation_count = n << d.perturbation_levels;
        d.perturbation_points = (rugo_vec2*)malloc(sizeof(rugo_vec2) * (size_t)(d.perturbation_count + 1));
        for (int i = 0; i < d.perturbation_count; ++i)
            d.perturbation_points[i] = rugo_v2(random_double(r), random_double(r));
    }
    return d;
}

static void free_random_roughness(rugo_roughness_desc* d) {
    free(d->tolerances);
    free(d->perturbation_points);
    free(d->ranges);
    free(d->profile);
}

START_TEST(roughness_round_trip_bits) {
    test_rng r = test_rng_seed(0x70ff);
    for (int iter = 0; iter < 400; ++iter) {
        int n = (int)(test_rng_next(&r) % 40);
        rugo_vec2 pts[40];
        for (int i = 0; i < n; ++i)
            pts[i] = rugo_v2(random_double(&r), random_double(&r));
        rugo_shape_desc desc = make_desc(pts, n, (rugo_filter)(test_rng_next(&r) % RUGO_FILTER_COUNT));
        desc.has_roughness = true;
        desc.roughness = random_roughness(&r, n);
        rugo_text text;
        ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
        ck_assert_int_eq((int)strlen(text.data), (int)text.length);
        rugo_shape_desc back;
        rugo_parse_error err;
        ck_assert_msg(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err) == RUGO_OK,
                      "%s: %s at %d:%d\n%s", err.path, err.message, err.line, err.column, text.data);
        ck_assert_int_eq(back.count, n);
        ck_assert(back.has_roughness);
        for (int i = 0; i < n; ++i) {
            ck_assert(bits_of(back.control_points[i].x) == bits_of(pts[i].x));
            ck_assert(bits_of(back.control_points[i].y) == bits_of(pts[i].y));
        }
        assert_same_roughness(&desc.roughness, &back.roughness);
        rugo_text text2;
        ck_assert_int_eq(rugo_shape_desc_write(&back, NULL, &text2), RUGO_OK);
        ck_assert_int_eq((int)text2.length, (int)text.length);
        ck_assert(memcmp(text.data, text2.data, text.length) == 0);
        rugo_text_free(&text2);
        rugo_shape_desc_free(&back);
        rugo_text_free(&text);
        free_random_roughness(&desc.roughness);
    }
    /* The layout, once */
    rugo_vec2 four[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_real tol[4] = {0.25, 0.5, 0, 1};
    rugo_vec2 pert[8] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5}, {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};
    rugo_shape_desc d = make_desc(four, 4, RUGO_FILTER_CDF4_8);
    d.has_roughness = true;
    d.roughness = rugo_default_roughness_desc();
    d.roughness.kind = RUGO_ROUGHNESS_TOLERANCES;
    d.roughness.tolerances = tol;
    d.roughness.tolerance_count = 4;
    d.roughness.seed = 42;
    d.roughness.has_perturbation = true;
    d.roughness.perturbation_method = RUGO_ROUGHEN_LOCAL;
    d.roughness.perturbation_levels = 1;
    d.roughness.perturbation_points = pert;
    d.roughness.perturbation_count = 8;
    rugo_text text;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_str_eq(
        text.data,
        "{\n  \"control_points\": [\n    [0, 0],\n    [1, 0],\n    [1, 1],\n    [0, 1]\n  ],\n"
        "  \"filter\": \"cdf4.8\",\n  \"roughness\": {\n    \"tolerances\": [\n      0.25,\n"
        "      0.5,\n      0,\n      1\n    ],\n    \"seed\": 42,\n"
        "    \"q\": 0.94999999999999996,\n    \"estimator\": \"detail\",\n"
        "    \"friction\": {\"alpha\": 109.09090909090911, \"lambda_min\": 0.00050000000000000001, "
        "\"base\": 0.29999999999999999},\n"
        "    \"restitution\": {\"epsilon\": 0.5, \"epsilon_max\": 0.90000000000000002},\n"
        "    \"perturbation\": {\n      \"method\": \"local\",\n      \"levels\": 1,\n"
        "      \"control_points\": [\n        [0, 0],\n        [0.5, 0],\n        [1, 0],\n"
        "        [1, 0.5],\n        [1, 1],\n        [0.5, 1],\n        [0, 1],\n"
        "        [0, 0.5]\n      ]\n    }\n  }\n}\n");
    rugo_text_free(&text);
    d.roughness.has_perturbation = false;
    d.roughness.kind = RUGO_ROUGHNESS_PRESET;
    d.roughness.preset = RUGO_PRESET_TIPO_5;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_ptr_nonnull(
        strstr(text.data, "  \"roughness\": {\n    \"preset\": \"tipo_5\",\n    \"seed\": 42,\n"));
    ck_assert_ptr_null(strstr(text.data, "perturbation"));
    rugo_text_free(&text);
    d.roughness.kind = RUGO_ROUGHNESS_CONSTANT;
    d.roughness.constant = 0.125;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_ptr_nonnull(strstr(text.data, "  \"roughness\": {\n    \"constant\": 0.125,\n"));
    rugo_text_free(&text);
    /* The sample file: read, write, read gives the same description. */
    rugo_text sample = read_data("star32_tipo5.json");
    rugo_shape_desc a, b;
    rugo_parse_error err;
    ck_assert_int_eq(rugo_shape_desc_parse(sample.data, sample.length, NULL, &a, &err), RUGO_OK);
    ck_assert_int_eq(rugo_shape_desc_write(&a, NULL, &text), RUGO_OK);
    ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &b, &err), RUGO_OK);
    assert_same_roughness(&a.roughness, &b.roughness);
    rugo_shape_desc_free(&a);
    rugo_shape_desc_free(&b);
    rugo_text_free(&text);
    rugo_text_free(&sample);
}
END_TEST

START_TEST(roughness_write_errors) {
    rugo_vec2 pts[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_real tol[4] = {1, 1, 1, 1};
    rugo_vec2 pert[8] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}};
    rugo_shape_desc d = make_desc(pts, 4, RUGO_FILTER_DEFAULT);
    d.has_roughness = true;
    rugo_text text;
    text.data = (char*)1;
    text.length = 5;
    /* Each case: break one member of a valid description, expect the status, restore. */
    struct {
        rugo_status status;
        int which;
    } cases[] = {
        {RUGO_ERR_BAD_ARGUMENT, 0},       {RUGO_ERR_BAD_ARGUMENT, 1},       {RUGO_ERR_BAD_ARGUMENT, 2},
        {RUGO_ERR_NULL_ARGUMENT, 3},      {RUGO_ERR_NEGATIVE_TOLERANCE, 4}, {RUGO_ERR_NOT_FINITE, 5},
        {RUGO_ERR_NEGATIVE_TOLERANCE, 6}, {RUGO_ERR_NOT_FINITE, 7},         {RUGO_ERR_BAD_ARGUMENT, 8},
        {RUGO_ERR_BAD_QUANTILE, 9},       {RUGO_ERR_BAD_QUANTILE, 10},      {RUGO_ERR_BAD_QUANTILE, 11},
        {RUGO_ERR_BAD_ARGUMENT, 12},      {RUGO_ERR_BAD_ARGUMENT, 13},      {RUGO_ERR_NEGATIVE_TOLERANCE, 14},
        {RUGO_ERR_NOT_FINITE, 15},        {RUGO_ERR_EMPTY_RANGE, 16},       {RUGO_ERR_BAD_ARGUMENT, 17},
        {RUGO_ERR_BAD_ARGUMENT, 18},      {RUGO_ERR_BAD_ARGUMENT, 19},      {RUGO_ERR_BAD_ARGUMENT, 20},
        {RUGO_ERR_BAD_ARGUMENT, 21},      {RUGO_ERR_NULL_ARGUMENT, 22},     {RUGO_ERR_NOT_FINITE, 23},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        rugo_roughness_desc* r = &d.roughness;
        *r = rugo_default_roughness_desc();
        r->kind = RUGO_ROUGHNESS_TOLERANCES;
        r->tolerances = tol;
        r->tolerance_count = 4;
        r->has_perturbation = true;
        r->perturbation_levels = 1;
        r->perturbation_count = 8;
        r->perturbation_points = pert;
        for (int i = 0; i < 4; ++i)
            tol[i] = 1.0;
        pert[7] = rugo_v2(0, 0);
        ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
        rugo_text_free(&text);
        switch (cases[c].which) {
        case 0:
            r->kind = RUGO_ROUGHNESS_KIND_COUNT;
            break;
        case 1:
            r->kind = RUGO_ROUGHNESS_PRESET;
            r->preset = RUGO_PRESET_COUNT;
            break;
        case 2:
            r->tolerance_count = 3;
            break;
        case 3:
            r->tolerances = NULL;
            break;
        case 4:
            tol[2] = -1e-9;
            break;
        case 5:
            tol[1] = NAN;
            break;
        case 6:
            r->kind = RUGO_ROUGHNESS_CONSTANT;
            r->constant = -0.5;
            break;
        case 7:
            r->kind = RUGO_ROUGHNESS_CONSTANT;
            r->constant = INFINITY;
            break;
        case 8:
            r->seed = RUGO_MAX_FILE_SEED + 1;
            break;
        case 9:
            r->q = 0.0;
            break;
        case 10:
            r->q = NAN;
            break;
        case 11:
            r->q = INFINITY;
            break;
        case 12:
            r->estimator = (rugo_tolerance_estimator)7;
            break;
        case 13:
            r->friction.alpha = -1.0;
            break;
        case 14:
            r->friction.lambda_min = -1.0;
            break;
        case 15:
            r->friction.alpha = NAN;
            break;
        case 16:
            r->restitution.epsilon = 0.95;
            break;
        case 17:
            r->restitution.epsilon_max = 1.5;
            break;
        case 18:
            r->perturbation_method = (rugo_roughen_method)2;
            break;
        case 19:
            r->perturbation_levels = 0;
            break;
        case 20:
            r->perturbation_levels = RUGO_MAX_PERTURBATION_LEVELS + 1;
            break;
        case 21:
            r->perturbation_count = 7;
            break;
        case 22:
            r->perturbation_points = NULL;
            break;
        default:
            pert[7].y = -INFINITY;
            break;
        }
        text.data = (char*)1;
        text.length = 5;
        rugo_status st = rugo_shape_desc_write(&d, NULL, &text);
        ck_assert_msg(st == cases[c].status, "case %d: status %d (%s), expected %d", cases[c].which, (int)st,
                      rugo_status_string(st), (int)cases[c].status);
        ck_assert_ptr_null(text.data);
        ck_assert_int_eq((int)text.length, 0);
        /* Without has_roughness the roughness is not looked at. */
        d.has_roughness = false;
        ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
        ck_assert_ptr_null(strstr(text.data, "roughness"));
        rugo_text_free(&text);
        d.has_roughness = true;
    }
}
END_TEST

START_TEST(roughness_write_size_limit) {
    /* 2^20 long coordinates fit the reader's 64 MiB (shape_max_size_file_fits); 2^20 long tolerances on
     * top do not, and the writer says so instead of writing a file nobody can read. */
    int n = RUGO_MAX_CONTROL_POINTS;
    rugo_vec2* pts = (rugo_vec2*)malloc(sizeof *pts * (size_t)n);
    rugo_real* tol = (rugo_real*)malloc(sizeof *tol * (size_t)n);
    ck_assert_ptr_nonnull(pts);
    ck_assert_ptr_nonnull(tol);
    for (int i = 0; i < n; ++i) {
        pts[i] = rugo_v2(-2.2250738585072014e-308, -1.2345678901234567e-300);
        tol[i] = 1.2345678901234567e-300;
    }
    rugo_shape_desc d = make_desc(pts, n, RUGO_FILTER_DEFAULT);
    d.has_roughness = true;
    d.roughness = rugo_default_roughness_desc();
    d.roughness.kind = RUGO_ROUGHNESS_TOLERANCES;
    d.roughness.tolerances = tol;
    d.roughness.tolerance_count = n;
    rugo_text text;
    text.data = (char*)1;
    text.length = 5;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_ptr_null(text.data);
    ck_assert_int_eq((int)text.length, 0);
    /* A preset instead of the list fits. */
    d.roughness.kind = RUGO_ROUGHNESS_PRESET;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_uint_le(text.length, RUGO_MAX_JSON_BYTES);
    rugo_text_free(&text);
    free(tol);
    free(pts);
}
END_TEST

START_TEST(roughness_tolerances_resolve) {
    rugo_roughness_desc r = rugo_default_roughness_desc();
    rugo_real out[40], expect[40];
    /* Presets go through rugo_tolerances_preset with the seed. */
    for (int p = 0; p < RUGO_PRESET_COUNT; ++p) {
        r.kind = RUGO_ROUGHNESS_PRESET;
        r.preset = (rugo_tolerance_preset)p;
        r.seed = 1234;
        ck_assert_int_eq(rugo_roughness_tolerances(&r, 40, out), RUGO_OK);
        ck_assert_int_eq(rugo_tolerances_preset(r.preset, 1234, 40, expect), RUGO_OK);
        ck_assert(memcmp(out, expect, sizeof out) == 0);
    }
    r.preset = RUGO_PRESET_TIPO_3;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 8, out), RUGO_OK);
    ck_assert(out[0] == 0.32 && out[1] == 0.24 && out[2] == 0.20 && out[3] == 0.24 && out[4] == 0.32);
    /* tipo_2 depends on the seed, deterministically. */
    r.preset = RUGO_PRESET_TIPO_2;
    r.seed = 5;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 40, out), RUGO_OK);
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 40, expect), RUGO_OK);
    ck_assert(memcmp(out, expect, sizeof out) == 0);
    r.seed = 6;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 40, expect), RUGO_OK);
    ck_assert(memcmp(out, expect, sizeof out) != 0);
    /* Constant and list */
    r.kind = RUGO_ROUGHNESS_CONSTANT;
    r.constant = 0.75;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 5, out), RUGO_OK);
    ck_assert(out[0] == 0.75 && out[4] == 0.75);
    r.constant = -1.0;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 5, out), RUGO_ERR_NEGATIVE_TOLERANCE);
    rugo_real list[4] = {0.1, 0.2, 0.3, 0.4};
    r.kind = RUGO_ROUGHNESS_TOLERANCES;
    r.tolerances = list;
    r.tolerance_count = 4;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_OK);
    ck_assert(memcmp(out, list, sizeof list) == 0);
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 5, out), RUGO_ERR_BAD_ARGUMENT);
    list[1] = NAN;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_ERR_NOT_FINITE);
    r.tolerances = NULL;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_ERR_NULL_ARGUMENT);
    /* Arguments */
    r.kind = RUGO_ROUGHNESS_KIND_COUNT;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_ERR_BAD_ARGUMENT);
    r.kind = RUGO_ROUGHNESS_PRESET;
    r.preset = RUGO_PRESET_COUNT;
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_ERR_BAD_ARGUMENT);
    r.preset = RUGO_PRESET_TIPO_1;
    ck_assert_int_eq(rugo_roughness_tolerances(NULL, 4, out), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 0, out), RUGO_ERR_TOO_FEW_POINTS);
    ck_assert_int_eq(rugo_roughness_tolerances(&r, RUGO_MAX_CONTROL_POINTS + 1, out),
                     RUGO_ERR_TOO_MANY_POINTS);
}
END_TEST

START_TEST(roughness_out_of_memory) {
    char buf[1024];
    rough_text("\"tolerances\": [1, 2, 3, 4], \"perturbation\": {\"method\": \"wavelet\", \"levels\": 1, "
               "\"control_points\": [[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]]}",
               buf, sizeof buf);
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo_shape_desc desc;
        rugo_parse_error err;
        rugo_status st = rugo_shape_desc_parse(buf, strlen(buf), &a, &desc, &err);
        if (st == RUGO_OK) {
            ck_assert_int_eq(ctx.live, 3);
            rugo_shape_desc_free(&desc);
            ck_assert_int_eq(ctx.live, 0);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert(!desc.has_roughness);
        ck_assert_ptr_null(desc.roughness.tolerances);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 100);
    }
}
END_TEST

START_TEST(points_parse_keys) {
    rugo_point_list pts;
    rugo_parse_error err;
    rugo_text text = read_data("circle64_points.json");
    ck_assert_int_eq(rugo_points_parse(text.data, text.length, "points", NULL, &pts, &err), RUGO_OK);
    ck_assert_int_eq(pts.count, 64);
    ck_assert(pts.points[0].x == 2.0 && pts.points[0].y == 0.0);
    ck_assert(pts.allocator.alloc != NULL); /* the default allocator, recorded */
    rugo_point_list_free(&pts);
    ck_assert(pts.points == NULL && pts.count == 0);
    ck_assert_int_eq(rugo_points_parse(text.data, text.length, "control_points", NULL, &pts, &err),
                     RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "control_points");
    ck_assert_ptr_null(pts.points);
    rugo_text_free(&text);
    text = read_data("star32.json");
    ck_assert_int_eq(rugo_points_parse(text.data, text.length, "control_points", NULL, &pts, &err), RUGO_OK);
    ck_assert_int_eq(pts.count, 32);
    rugo_point_list_free(&pts);
    rugo_text_free(&text);
    const char* bad = "{\"points\": [[1, 2], [3, \"4\"]]}";
    char* buf = exact_copy(bad, strlen(bad));
    ck_assert_int_eq(rugo_points_parse(buf, strlen(bad), "points", NULL, &pts, &err), RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "points[1][1]");
    ck_assert_ptr_null(pts.points);
    ck_assert_int_eq(pts.count, 0);
    free(buf);
    ck_assert_int_eq(rugo_points_parse("{\"points\": [[1e999, 0]]}", 24, "points", NULL, &pts, &err),
                     RUGO_ERR_NOT_FINITE);
    ck_assert_str_eq(err.path, "points[0][0]");
    rugo_point_list_free(&pts); /* a zeroed list, and NULL, are fine */
    rugo_point_list_free(NULL);
    /* A custom allocator is recorded and frees the points. */
    test_budget_ctx ctx = {1000, 0};
    rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
    const char* two = "{\"points\": [[1, 2], [3, 4]]}";
    ck_assert_int_eq(rugo_points_parse(two, strlen(two), "points", &a, &pts, &err), RUGO_OK);
    ck_assert(pts.allocator.ctx == &ctx);
    ck_assert_int_eq(ctx.live, 1);
    rugo_point_list_free(&pts);
    ck_assert_int_eq(ctx.live, 0);
}
END_TEST

START_TEST(read_file_cases) {
    char path[1024];
    rugo_text text;
    text.data = (char*)1;
    text.length = 9;
    data_path("square4.json", path, sizeof path);
    ck_assert_int_eq(rugo_read_file(path, NULL, &text), RUGO_OK);
    ck_assert_int_eq((int)strlen(text.data), (int)text.length);
    ck_assert_int_eq(strncmp(text.data, "{\n  \"control_points\"", 20), 0);
    rugo_text_free(&text);

    data_path("no_such_file.json", path, sizeof path);
    text.data = (char*)1;
    text.length = 9;
    ck_assert_int_eq(rugo_read_file(path, NULL, &text), RUGO_ERR_IO);
    ck_assert_ptr_null(text.data);
    ck_assert_int_eq((int)text.length, 0);
    data_path("", path, sizeof path); /* the directory itself */
    ck_assert_int_eq(rugo_read_file(path, NULL, &text), RUGO_ERR_IO);
    ck_assert_ptr_null(text.data);
    ck_assert_int_eq(rugo_read_file(NULL, NULL, &text), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_read_file("x", NULL, NULL), RUGO_ERR_NULL_ARGUMENT);

    /* Files that cannot tell their size are read in growing chunks. */
    FILE* probe = fopen("/proc/self/status", "rb");
    if (probe != NULL) {
        fclose(probe);
        ck_assert_int_eq(rugo_read_file("/proc/self/status", NULL, &text), RUGO_OK);
        ck_assert_int_gt((int)text.length, 0);
        ck_assert_int_eq((int)strlen(text.data), (int)text.length);
        rugo_text_free(&text);
    }

    /* Size limit: a sparse file of exactly the limit reads; one byte more is refused. */
    const char* big = "test_shape_file_big.tmp";
    FILE* f = fopen(big, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, (long)RUGO_MAX_JSON_BYTES - 1, SEEK_SET), 0);
    fputc(' ', f);
    fclose(f);
    ck_assert_int_eq(rugo_read_file(big, NULL, &text), RUGO_OK);
    ck_assert(text.length == RUGO_MAX_JSON_BYTES);
    ck_assert_int_eq(text.data[text.length], '\0');
    rugo_text_free(&text);
    f = fopen(big, "ab");
    fputc(' ', f);
    fclose(f);
    ck_assert_int_eq(rugo_read_file(big, NULL, &text), RUGO_ERR_PARSE);
    ck_assert_ptr_null(text.data);
    remove(big);

    /* Allocation failures while reading; the text records the allocator and frees through it. */
    data_path("star32.json", path, sizeof path);
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo_status st = rugo_read_file(path, &a, &text);
        if (st == RUGO_OK) {
            ck_assert(text.allocator.ctx == &ctx);
            rugo_text_free(&text);
            ck_assert_int_eq(ctx.live, 0);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 10);
    }
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* Mini-fuzz: seeded random mutations of valid files never crash, never read past the length (the
 * sanitizer build checks that), and always give a documented status with a usable error. */

static const char* const snippets[] = {
    "1e999",
    "-1e999",
    "\\u",
    "\\ud800",
    "\\udc00\\ud800",
    "[[[[",
    "]]]]",
    "\"",
    "\\",
    "NaN",
    "-0",
    "1e-400",
    "{}",
    "[]",
    "null",
    "true",
    ",",
    ":",
    "\"filter\": \"cdf4.2\",",
    "\"control_points\": ",
    "\"filter\": \"cdf4.9\",",
    "\"roughness\": {\"preset\": \"tipo_3\"},",
    "\"roughness\": {\"constant\": -1},",
    "\"preset\": \"tipo_2\",",
    "\"constant\": 0.5,",
    "\"seed\": 9007199254740993,",
    "\"seed\": 12,",
    "\"q\": 0,",
    "\"estimator\": \"coefficients\",",
    "\"friction\": {\"alpha\": -1},",
    "\"restitution\": {\"epsilon\": 0.95},",
    "\"levels\": 2,",
    "-0.25",
    "-",
    "[1, 2],",
    "[1, 2, 3],",
    "0.5e+3",
    "\xef\xbb\xbf",
    "\xc3\xa9",
    "\xff",
    "00",
    "\t",
    "\n",
    "\"\\u0000\"",
    "{\"control_points\": [",
    "1.",
    ".5",
    "+1",
    "e5",
};

static size_t mutate(test_rng* r, char* buf, size_t n, size_t cap) {
    int ops = 1 + (int)(test_rng_next(r) % 4);
    for (int k = 0; k < ops; ++k) {
        uint64_t u = test_rng_next(r);
        size_t pos = n > 0 ? (size_t)((u >> 8) % n) : 0;
        switch (u % 7) {
        case 0: /* random byte */
            if (n > 0) buf[pos] = (char)(test_rng_next(r) & 0xff);
            break;
        case 1: /* bit flip */
            if (n > 0) buf[pos] ^= (char)(1u << ((u >> 40) % 8));
            break;
        case 2: { /* delete a range */
            size_t len = 1 + (size_t)((u >> 32) % 8);
            if (pos + len > n) len = n - pos;
            memmove(buf + pos, buf + pos + len, n - pos - len);
            n -= len;
            break;
        }
        case 3:
        case 4: { /* insert a snippet */
            const char* s = snippets[test_rng_next(r) % (sizeof snippets / sizeof snippets[0])];
            size_t len = strlen(s);
            if (n + len > cap) break;
            memmove(buf + pos + len, buf + pos, n - pos);
            memcpy(buf + pos, s, len);
            n += len;
            break;
        }
        case 5: /* truncate */
            n = pos;
            break;
        default: { /* duplicate a chunk elsewhere */
            size_t len = 1 + (size_t)((u >> 32) % 16);
            if (n == 0 || pos + len > n || n + len > cap) break;
            size_t to = (size_t)(test_rng_next(r) % (n + 1));
            char tmp[16];
            memcpy(tmp, buf + pos, len);
            memmove(buf + to + len, buf + to, n - to);
            memcpy(buf + to, tmp, len);
            n += len;
            break;
        }
        }
    }
    return n;
}

static void check_shape_result(rugo_status st, const rugo_shape_desc* desc, const rugo_parse_error* err,
                               const char* input, size_t n) {
    ck_assert_msg(st == RUGO_OK || st == RUGO_ERR_PARSE || st == RUGO_ERR_BAD_FIELD ||
                      st == RUGO_ERR_NOT_FINITE || st == RUGO_ERR_BAD_FILTER ||
                      st == RUGO_ERR_TOO_MANY_POINTS || st == RUGO_ERR_NEGATIVE_TOLERANCE ||
                      st == RUGO_ERR_BAD_QUANTILE || st == RUGO_ERR_BAD_ARGUMENT ||
                      st == RUGO_ERR_EMPTY_RANGE,
                  "status %d for input <%.*s>", (int)st, (int)n, input);
    ck_assert(str_nul_terminated(err->path, sizeof err->path));
    ck_assert(str_nul_terminated(err->message, sizeof err->message));
    if (st == RUGO_OK) {
        ck_assert(desc->count >= 0);
        ck_assert((int)desc->filter >= 0 && desc->filter < RUGO_FILTER_COUNT);
        for (int i = 0; i < desc->count; ++i)
            ck_assert(isfinite(desc->control_points[i].x) && isfinite(desc->control_points[i].y));
        if (desc->has_roughness) {
            const rugo_roughness_desc* r = &desc->roughness;
            ck_assert((int)r->kind >= 0 && r->kind < RUGO_ROUGHNESS_KIND_COUNT);
            if (r->kind == RUGO_ROUGHNESS_TOLERANCES) ck_assert_int_eq(r->tolerance_count, desc->count);
            ck_assert(r->seed <= RUGO_MAX_FILE_SEED);
            ck_assert(r->q > 0.0);
            ck_assert(!r->has_perturbation || r->perturbation_count == desc->count << r->perturbation_levels);
        }
    } else {
        ck_assert_ptr_null(desc->control_points);
        ck_assert_int_eq(desc->has_roughness, 0);
        ck_assert_ptr_null(desc->roughness.tolerances);
        ck_assert_ptr_null(desc->roughness.perturbation_points);
        ck_assert_msg(err->message[0] != '\0', "no message for input <%.*s>", (int)n, input);
        ck_assert_msg(err->line >= 1 && err->column >= 1, "no position for input <%.*s>", (int)n, input);
        /* The position is inside the text (or just past its end). */
        int line = 1;
        for (size_t i = 0; i < n; ++i)
            line += input[i] == '\n';
        ck_assert_int_le(err->line, line);
    }
}

START_TEST(fuzz_mutations) {
    rugo_text star = read_data("star32.json");
    rugo_text rough = read_data("star32_tipo5.json");
    const char* seeds[] = {
        star.data,
        "{\"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]], \"filter\": \"cdf4.2\"}",
        "{\"name\": \"x\\u00e9\\ud83d\\ude00\", \"control_points\": [[-1.5e-3, 2E+2], [0.25, -0]], \"r\": "
        "{\"a\": [true, "
        "false, null]}}",
        "{\"points\": [[1, 2], [3, 4]], \"control_points\": [], \"filter\": \"cdf4.12\"}",
        rough.data,
        "{\"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]], \"roughness\": {\"tolerances\": [0.1, 0.2, "
        "0, 1e-3], "
        "\"seed\": 7, \"q\": 1.96, \"estimator\": \"coefficients\", \"friction\": {\"alpha\": 2, "
        "\"lambda_min\": "
        "0.1}, \"restitution\": {\"epsilon\": 0.3, \"epsilon_max\": 0.8}, \"perturbation\": {\"method\": "
        "\"local\", \"levels\": 1, \"control_points\": [[0, 0], [0.5, 0], [1, 0], [1, 0.5], [1, 1], [0.5, "
        "1], [0, 1], "
        "[0, 0.5]]}}}",
        "{\"roughness\": {\"constant\": 0.25, \"seed\": 3}, \"control_points\": [[0, 0], [1, 0], [0, 1], [1, "
        "1]]}",
    };
    enum { SEEDS = sizeof seeds / sizeof seeds[0] };
    size_t seed_len[SEEDS];
    for (int i = 0; i < SEEDS; ++i)
        seed_len[i] = strlen(seeds[i]);
    enum { CAP = 4096 };
    char work[CAP];
    test_rng r = test_rng_seed(0xf022);
    int counts[RUGO_STATUS_COUNT] = {0};
    for (int iter = 0; iter < 40000; ++iter) {
        int s = (int)(test_rng_next(&r) % SEEDS);
        size_t n = seed_len[s] < CAP ? seed_len[s] : CAP;
        memcpy(work, seeds[s], n);
        n = mutate(&r, work, n, CAP);
        char* input = exact_copy(work, n);
        rugo_shape_desc desc;
        rugo_parse_error err;
        rugo_status st = rugo_shape_desc_parse(input, n, NULL, &desc, &err);
        check_shape_result(st, &desc, &err, input, n);
        ++counts[st];
        if (st == RUGO_OK) {
            /* Whatever reads also writes and reads back to the same bits. */
            rugo_text text;
            ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
            rugo_shape_desc back;
            ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err), RUGO_OK);
            ck_assert_int_eq(back.count, desc.count);
            ck_assert(desc.count == 0 || memcmp(back.control_points, desc.control_points,
                                                sizeof(rugo_vec2) * (size_t)desc.count) == 0);
            ck_assert_int_eq(back.has_roughness, desc.has_roughness);
            if (desc.has_roughness) assert_same_roughness(&desc.roughness, &back.roughness);
            rugo_shape_desc_free(&back);
            rugo_text_free(&text);
        } else if (iter % 16 == 0) {
            /* Deterministic: the same input gives the same error, byte for byte. */
            rugo_parse_error err2;
            rugo_shape_desc d2;
            ck_assert_int_eq(rugo_shape_desc_parse(input, n, NULL, &d2, &err2), st);
            ck_assert(memcmp(&err, &err2, sizeof err) == 0);
        }
        rugo_shape_desc_free(&desc);
        /* The other entry points on the same bytes */
        rugo_point_list pts;
        st = rugo_points_parse(input, n, "points", NULL, &pts, &err);
        ck_assert(st == RUGO_OK || st == RUGO_ERR_PARSE || st == RUGO_ERR_BAD_FIELD ||
                  st == RUGO_ERR_NOT_FINITE);
        rugo_point_list_free(&pts);
        free(input);
    }
    /* The mutations reach every kind of outcome. */
    ck_assert_int_gt(counts[RUGO_OK], 100);
    ck_assert_int_gt(counts[RUGO_ERR_PARSE], 100);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_FIELD], 100);
    ck_assert_int_gt(counts[RUGO_ERR_NOT_FINITE], 10);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_FILTER], 10);
    rugo_text_free(&star);
    rugo_text_free(&rough);
}
END_TEST

/* Roughness objects assembled from random members — valid values, wrong types, out-of-range values,
 * repeats — then sometimes mutated bytewise: the semantic checks get the traffic that byte mutations
 * of whole files rarely reach. */
START_TEST(fuzz_roughness_members) {
    static const char* const sources[] = {"\"preset\": \"tipo_1\"",
                                          "\"preset\": \"tipo_2\"",
                                          "\"preset\": \"tipo_5\"",
                                          "\"preset\": \"tipo_9\"",
                                          "\"preset\": 3",
                                          "\"tolerances\": [0.1, 0.2, 0.3, 0.4]",
                                          "\"tolerances\": [0.1, -0.2, 0.3, 0.4]",
                                          "\"tolerances\": [0.1, 0.2, 0.3]",
                                          "\"tolerances\": [0, -0, 1e-300, 1e300]",
                                          "\"tolerances\": \"x\"",
                                          "\"constant\": 0.25",
                                          "\"constant\": -0.25",
                                          "\"constant\": 0",
                                          "\"constant\": [1]"};
    static const char* const others[] = {
        "\"seed\": 0",
        "\"seed\": 9007199254740992",
        "\"seed\": 9007199254740993",
        "\"seed\": 1.5",
        "\"seed\": -3",
        "\"seed\": 2e2",
        "\"q\": 1.96",
        "\"q\": 0",
        "\"q\": -1",
        "\"q\": \"1\"",
        "\"estimator\": \"detail\"",
        "\"estimator\": \"coefficients\"",
        "\"estimator\": \"max\"",
        "\"friction\": {\"alpha\": 2, \"lambda_min\": 0.1}",
        "\"friction\": {\"alpha\": -2}",
        "\"friction\": {\"lambda_min\": -1}",
        "\"friction\": []",
        "\"restitution\": {\"epsilon\": 0.2}",
        "\"restitution\": {\"epsilon\": 0.95}",
        "\"restitution\": {\"epsilon_max\": 2}",
        "\"restitution\": {\"epsilon\": 0.7, \"epsilon_max\": 0.6}",
        "\"restitution\": true",
        "\"perturbation\": {\"method\": \"wavelet\", \"levels\": 1, \"control_points\": "
        "[[0,0],[1,0],[2,0],[2,1],[2,2],[1,2],[0,2],[0,1]]}",
        "\"perturbation\": {\"method\": \"local\", \"levels\": 2, \"control_points\": [[0,0],[1,0]]}",
        "\"perturbation\": {\"method\": \"x\", \"levels\": 1, \"control_points\": []}",
        "\"perturbation\": {\"levels\": 1}",
        "\"unknown\": [1, {\"a\": null}]"};
    enum { NS = sizeof sources / sizeof sources[0], NO = sizeof others / sizeof others[0], CAP = 2048 };
    test_rng r = test_rng_seed(0xb0b);
    int counts[RUGO_STATUS_COUNT] = {0};
    char work[CAP];
    for (int iter = 0; iter < 20000; ++iter) {
        int n =
            snprintf(work, CAP, "{\"control_points\": [[0, 0], [2, 0], [2, 2], [0, 2]], \"roughness\": {");
        int members = (int)(test_rng_next(&r) % 5);
        int first = 1;
        /* Usually one source, sometimes none or two. */
        int nsrc = (int)(test_rng_next(&r) % 8);
        nsrc = nsrc == 0 ? 0 : (nsrc == 1 ? 2 : 1);
        for (int k = 0; k < nsrc + members; ++k) {
            const char* m = k < nsrc ? sources[test_rng_next(&r) % NS] : others[test_rng_next(&r) % NO];
            n += snprintf(work + n, CAP - (size_t)n, "%s%s", first ? "" : ", ", m);
            first = 0;
        }
        n += snprintf(work + n, CAP - (size_t)n, "}}");
        ck_assert_int_lt(n, CAP);
        size_t len = (size_t)n;
        if (test_rng_next(&r) % 4 == 0) len = mutate(&r, work, len, CAP);
        char* input = exact_copy(work, len);
        rugo_shape_desc desc;
        rugo_parse_error err;
        rugo_status st = rugo_shape_desc_parse(input, len, NULL, &desc, &err);
        check_shape_result(st, &desc, &err, input, len);
        ++counts[st];
        if (st == RUGO_OK) {
            rugo_text text;
            ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
            rugo_shape_desc back;
            ck_assert_int_eq(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err), RUGO_OK);
            ck_assert_int_eq(back.has_roughness, desc.has_roughness);
            if (desc.has_roughness) assert_same_roughness(&desc.roughness, &back.roughness);
            rugo_shape_desc_free(&back);
            rugo_text_free(&text);
        } else if (iter % 8 == 0) {
            rugo_parse_error err2;
            rugo_shape_desc d2;
            ck_assert_int_eq(rugo_shape_desc_parse(input, len, NULL, &d2, &err2), st);
            ck_assert(memcmp(&err, &err2, sizeof err) == 0);
        }
        rugo_shape_desc_free(&desc);
        free(input);
    }
    ck_assert_int_gt(counts[RUGO_OK], 500);
    ck_assert_int_gt(counts[RUGO_ERR_PARSE], 100);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_FIELD], 500);
    ck_assert_int_gt(counts[RUGO_ERR_NEGATIVE_TOLERANCE], 100);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_QUANTILE], 100);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_ARGUMENT], 100);
    ck_assert_int_gt(counts[RUGO_ERR_EMPTY_RANGE], 100);
}
END_TEST

START_TEST(fuzz_token_soup) {
    /* Random sequences of JSON-ish tokens, for the reader alone. */
    static const char* const tokens[] = {
        "[",    "]",   "{",    "}",    ",", ":",  "\"k\"", "\"\\n\"",      "\"\\u00", "1",
        "-0.5", "1e5", "true", "null", " ", "\"", "\\",    "\xe2\x82\xac", "\x01",    "0"};
    test_rng r = test_rng_seed(77);
    char work[512];
    int ok = 0;
    for (int iter = 0; iter < 20000; ++iter) {
        size_t n = 0;
        int count = (int)(test_rng_next(&r) % 40);
        for (int k = 0; k < count; ++k) {
            const char* t = tokens[test_rng_next(&r) % (sizeof tokens / sizeof tokens[0])];
            size_t len = strlen(t);
            if (n + len > sizeof work) break;
            memcpy(work + n, t, len);
            n += len;
        }
        rugo__json_doc doc;
        rugo__json_error err;
        rugo_status st = json_parse_n(work, n, &doc, &err);
        ck_assert(st == RUGO_OK || st == RUGO_ERR_PARSE || st == RUGO_ERR_NOT_FINITE); /* "1e5" "1" -> 1e51 */
        if (st == RUGO_OK) {
            ++ok;
            ck_assert_ptr_nonnull(doc.root);
        } else {
            ck_assert(err.message[0] != '\0');
            ck_assert(err.offset <= n);
        }
        rugo__json_doc_free(&doc);
    }
    ck_assert_int_gt(ok, 100);
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* Roughness by arc length: "ranges" and "profile", resampled onto the segments */

/* The unit square's control polygon: its B-spline has four segments of equal length (a quarter turn
 * maps segment j onto j+1), so segment j covers [j/4, (j+1)/4] of the perimeter. */
static const rugo_vec2 SQ4[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

static rugo_roughness_desc ranges_desc(rugo_roughness_range* g, int m, double background) {
    rugo_roughness_desc r = rugo_default_roughness_desc();
    r.kind = RUGO_ROUGHNESS_RANGES;
    r.ranges = g;
    r.range_count = m;
    r.background = background;
    return r;
}

static rugo_roughness_desc profile_desc(rugo_profile_sample* p, int m) {
    rugo_roughness_desc r = rugo_default_roughness_desc();
    r.kind = RUGO_ROUGHNESS_PROFILE;
    r.profile = p;
    r.profile_count = m;
    return r;
}

/* Resolves r on the square; every |out_j - expect_j| <= tol. */
static void expect_on_square(const char* what, const rugo_roughness_desc* r, const double expect[4],
                             double tol) {
    rugo_contour c = {SQ4, 4};
    rugo_real out[4];
    rugo_status st = rugo_roughness_tolerances_on_contour(r, c, NULL, out);
    ck_assert_msg(st == RUGO_OK, "%s: status %d", what, (int)st);
    for (int j = 0; j < 4; ++j)
        ck_assert_msg(fabs(out[j] - expect[j]) <= tol, "%s: segment %d: %.17g, expected %.17g", what, j,
                      out[j], expect[j]);
}

START_TEST(arc_square_quarters) {
    /* What the hand-computed cases below stand on: four equal arcs. */
    rugo_contour c = {SQ4, 4};
    double l0 = rugo_contour_segment_length(c, 0);
    ck_assert(l0 > 0.73 && l0 < 0.731);
    for (int j = 1; j < 4; ++j)
        ck_assert_near(rugo_contour_segment_length(c, j), l0, 1e-15);
}
END_TEST

START_TEST(arc_ranges_hand_computed) {
    /* 0.2..0.4 touches segments 0 ([0, 0.25]) and 1 ([0.25, 0.5]); both are partly outside the range,
     * but max(0.3, 0.05) = 0.3. */
    rugo_roughness_range a[1] = {{0.2, 0.4, 0.3}};
    rugo_roughness_desc r = ranges_desc(a, 1, 0.05);
    static const double ea[4] = {0.3, 0.3, 0.05, 0.05};
    expect_on_square("0.2-0.4", &r, ea, 0.0);
    /* A background above the range wins wherever the range does not cover the whole segment. */
    rugo_roughness_range b[1] = {{0.2, 0.4, 0.1}};
    r = ranges_desc(b, 1, 0.5);
    static const double eb[4] = {0.5, 0.5, 0.5, 0.5};
    expect_on_square("low range, high background", &r, eb, 0.0);
    /* A smooth patch exactly on segment 1: its ends on the segment boundaries do not spill over. */
    rugo_roughness_range c[1] = {{0.25, 0.5, 0.1}};
    r = ranges_desc(c, 1, 0.5);
    static const double ec[4] = {0.5, 0.1, 0.5, 0.5};
    expect_on_square("patch on segment 1", &r, ec, 0.0);
    /* Wrap-around: from 0.9 through 0 to 0.1 touches segments 3 and 0. */
    rugo_roughness_range d[1] = {{0.9, 0.1, 0.4}};
    r = ranges_desc(d, 1, 0.0);
    static const double ed[4] = {0.4, 0.0, 0.0, 0.4};
    expect_on_square("wrap", &r, ed, 0.0);
    /* From 1 (= 0) to 0.3: [0, 0.3]. */
    rugo_roughness_range e[1] = {{1.0, 0.3, 0.6}};
    r = ranges_desc(e, 1, 0.0);
    static const double ee[4] = {0.6, 0.6, 0.0, 0.0};
    expect_on_square("from 1", &r, ee, 0.0);
    /* Overlap: the larger tolerance, in either order. */
    rugo_roughness_range f[2] = {{0.1, 0.6, 0.2}, {0.3, 0.4, 0.7}};
    r = ranges_desc(f, 2, 0.0);
    static const double ef[4] = {0.2, 0.7, 0.2, 0.0};
    expect_on_square("overlap", &r, ef, 0.0);
    rugo_roughness_range f2[2] = {{0.3, 0.4, 0.7}, {0.1, 0.6, 0.2}};
    r = ranges_desc(f2, 2, 0.0);
    expect_on_square("overlap, other order", &r, ef, 0.0);
    /* Two touching ranges cover segment 1 together, so the background stays out of it. */
    rugo_roughness_range g[2] = {{0.2, 0.3, 0.1}, {0.3, 0.55, 0.2}};
    r = ranges_desc(g, 2, 0.9);
    static const double eg[4] = {0.9, 0.2, 0.9, 0.9};
    expect_on_square("union covers", &r, eg, 0.0);
    /* The whole perimeter; no ranges at all; a tiny range inside segment 2. */
    rugo_roughness_range h[1] = {{0.0, 1.0, 0.15}};
    r = ranges_desc(h, 1, 0.9);
    static const double eh[4] = {0.15, 0.15, 0.15, 0.15};
    expect_on_square("whole", &r, eh, 0.0);
    r = ranges_desc(NULL, 0, 0.07);
    static const double ei[4] = {0.07, 0.07, 0.07, 0.07};
    expect_on_square("background only", &r, ei, 0.0);
    rugo_roughness_range k[1] = {{0.6, 0.6000001, 1.0}};
    r = ranges_desc(k, 1, 0.0);
    static const double ek[4] = {0.0, 0.0, 1.0, 0.0};
    expect_on_square("narrow", &r, ek, 0.0);
    /* Through the file: the same as the struct. */
    char buf[1024];
    rough_text("\"ranges\": [{\"from\": 0.2, \"to\": 0.4, \"tolerance\": 0.3}], \"background\": 0.05", buf,
               sizeof buf);
    rugo_shape_desc desc;
    rugo_parse_error err;
    ck_assert_int_eq(shape_parse_n(buf, strlen(buf), &desc, &err), RUGO_OK);
    expect_on_square("parsed", &desc.roughness, ea, 0.0);
    rugo_shape_desc_free(&desc);
}
END_TEST

START_TEST(arc_profile_hand_computed) {
    /* A peak inside segment 0 is its tolerance; the profile is 0 elsewhere (periodic through 1). */
    rugo_profile_sample a[3] = {{0.1, 0.0}, {0.125, 1.0}, {0.15, 0.0}};
    rugo_roughness_desc r = profile_desc(a, 3);
    static const double ea[4] = {1.0, 0.0, 0.0, 0.0};
    expect_on_square("peak", &r, ea, 0.0);
    /* λ = 2 (s - 0.125) up to s = 0.625, then down to 0 at 1.125 (= 0.125): the maxima are at the
     * segments' ends, except on segment 2, which holds the peak. λ(0) = λ(1) = 0.25. */
    rugo_profile_sample b[2] = {{0.125, 0.0}, {0.625, 1.0}};
    r = profile_desc(b, 2);
    static const double eb[4] = {0.25, 0.75, 1.0, 0.75};
    expect_on_square("linear", &r, eb, 1e-12);
    /* Samples at 0 and 1 with different values: the seam takes the larger (0.6) on both sides. */
    rugo_profile_sample c[3] = {{0.0, 0.2}, {0.5, 0.2}, {1.0, 0.6}};
    r = profile_desc(c, 3);
    static const double ec[4] = {0.6, 0.2, 0.4, 0.6};
    expect_on_square("seam", &r, ec, 1e-12);
    /* One sample is a constant. */
    rugo_profile_sample d[1] = {{0.3, 0.12}};
    r = profile_desc(d, 1);
    static const double ed[4] = {0.12, 0.12, 0.12, 0.12};
    expect_on_square("one sample", &r, ed, 0.0);
    /* Inline in the file. */
    char buf[1024];
    rough_text("\"profile\": [[0.1, 0], [0.125, 1], [0.15, 0]]", buf, sizeof buf);
    rugo_shape_desc desc;
    rugo_parse_error err;
    ck_assert_int_eq(shape_parse_n(buf, strlen(buf), &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.roughness.kind, RUGO_ROUGHNESS_PROFILE);
    expect_on_square("parsed", &desc.roughness, ea, 0.0);
    rugo_shape_desc_free(&desc);
}
END_TEST

/* Arc fractions of a contour's segments: a[j], a[j+1] bound segment j (a[0] = 0, a[n] = 1). */
static void arc_fractions(rugo_contour c, double* a) {
    double total = 0.0;
    for (int j = 0; j < c.count; ++j)
        total += rugo_contour_segment_length(c, j);
    double before = 0.0;
    a[0] = 0.0;
    for (int j = 0; j < c.count; ++j) {
        before += rugo_contour_segment_length(c, j);
        a[j + 1] = j == c.count - 1 ? 1.0 : before / total;
    }
}

/* λ(x) of ranges at a point: the largest range containing x (closed), else the background. */
static double ranges_at(const rugo_roughness_range* g, int m, double background, double x) {
    double best = -1.0;
    for (int i = 0; i < m; ++i) {
        int in = g[i].from < g[i].to ? (x >= g[i].from && x <= g[i].to) : (x >= g[i].from || x <= g[i].to);
        if (in && g[i].tolerance > best) best = g[i].tolerance;
    }
    return best >= 0.0 ? best : background;
}

static int cmp_double(const void* a, const void* b) {
    double x = *(const double*)a, y = *(const double*)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

START_TEST(arc_ranges_brute_force) {
    /* On random outlines with uneven segments: the maximum of λ over each segment's arc, found
     * independently from the breakpoints of λ and a point between each two of them. */
    test_rng r = test_rng_seed(0xa7c);
    enum { N = 32, M = 8 };
    rugo_vec2 pts[N];
    double frac[N + 1];
    for (int iter = 0; iter < 300; ++iter) {
        test_random_star(&r, N, rugo_v2(3.0, -1.0), 2.0, 0.45, pts);
        rugo_contour c = {pts, N};
        arc_fractions(c, frac);
        int m = (int)(test_rng_next(&r) % (M + 1));
        rugo_roughness_range g[M], shuffled[M];
        for (int i = 0; i < m; ++i) {
            do {
                g[i].from = test_rng_uniform(&r, 0.0, 1.0);
                g[i].to = test_rng_next(&r) % 3 == 0 ? test_rng_uniform(&r, 0.0, 1.0)
                                                     : fmod(g[i].from + test_rng_uniform(&r, 0.0, 0.2), 1.0);
            } while (g[i].from == g[i].to);
            g[i].tolerance = test_rng_uniform(&r, 0.0, 1.0);
        }
        double background = test_rng_uniform(&r, 0.0, 0.6);
        rugo_roughness_desc d = ranges_desc(g, m, background);
        rugo_real out[N], again[N];
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&d, c, NULL, out), RUGO_OK);
        for (int j = 0; j < N; ++j) {
            double p = frac[j] + RUGO_ROUGHNESS_RANGE_SLACK, q = frac[j + 1] - RUGO_ROUGHNESS_RANGE_SLACK;
            double cand[2 * M + 2];
            int nc = 0;
            cand[nc++] = p;
            cand[nc++] = q;
            for (int i = 0; i < m; ++i) {
                if (g[i].from > p && g[i].from < q) cand[nc++] = g[i].from;
                if (g[i].to > p && g[i].to < q) cand[nc++] = g[i].to;
            }
            qsort(cand, (size_t)nc, sizeof cand[0], cmp_double);
            double expect = 0.0;
            for (int k = 0; k < nc; ++k) {
                expect = fmax(expect, ranges_at(g, m, background, cand[k]));
                if (k + 1 < nc)
                    expect = fmax(expect, ranges_at(g, m, background, 0.5 * (cand[k] + cand[k + 1])));
            }
            ck_assert_msg(out[j] == expect, "iter %d segment %d: %.17g, expected %.17g", iter, j, out[j],
                          expect);
        }
        /* The order of the ranges does not matter. */
        for (int i = 0; i < m; ++i)
            shuffled[i] = g[m - 1 - i];
        d.ranges = shuffled;
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&d, c, NULL, again), RUGO_OK);
        ck_assert(memcmp(out, again, sizeof out) == 0);
    }
}
END_TEST

/* λ(x) of a periodic piecewise-linear profile, by a plain search (x in [0, 1]). */
static double profile_at(const rugo_profile_sample* p, int k, double x) {
    if (x <= p[0].s || x >= p[k - 1].s) { /* between the last sample and the first, through 1 = 0 */
        double x0 = p[k - 1].s - 1.0, x1 = p[0].s;
        double xx = x >= p[k - 1].s ? x - 1.0 : x;
        if (x1 == x0) return p[0].tolerance;
        return p[k - 1].tolerance + (p[0].tolerance - p[k - 1].tolerance) * (xx - x0) / (x1 - x0);
    }
    for (int i = 0; i + 1 < k; ++i)
        if (x >= p[i].s && x <= p[i + 1].s)
            return p[i].tolerance +
                   (p[i + 1].tolerance - p[i].tolerance) * (x - p[i].s) / (p[i + 1].s - p[i].s);
    return -1.0;
}

START_TEST(arc_profile_brute_force) {
    test_rng r = test_rng_seed(0x9f0);
    enum { N = 16, K = 12 };
    rugo_vec2 pts[N];
    double frac[N + 1];
    for (int iter = 0; iter < 300; ++iter) {
        test_random_star(&r, N, rugo_v2(0.0, 0.0), 1.0, 0.4, pts);
        rugo_contour c = {pts, N};
        arc_fractions(c, frac);
        int k = 1 + (int)(test_rng_next(&r) % K);
        double s[K];
        for (int i = 0; i < k; ++i)
            s[i] = test_rng_uniform(&r, 0.0, 1.0);
        qsort(s, (size_t)k, sizeof s[0], cmp_double);
        rugo_profile_sample p[K];
        int kk = 0;
        for (int i = 0; i < k; ++i)
            if (kk == 0 || s[i] > p[kk - 1].s) {
                p[kk].s = s[i];
                p[kk++].tolerance = test_rng_uniform(&r, 0.0, 1.0);
            }
        rugo_roughness_desc d = profile_desc(p, kk);
        rugo_real out[N];
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&d, c, NULL, out), RUGO_OK);
        for (int j = 0; j < N; ++j) {
            double a = frac[j], b = frac[j + 1];
            double expect = fmax(profile_at(p, kk, a), profile_at(p, kk, b));
            for (int i = 0; i < kk; ++i)
                if (p[i].s >= a && p[i].s <= b) expect = fmax(expect, p[i].tolerance);
            ck_assert_msg(fabs(out[j] - expect) <= 1e-12, "iter %d segment %d: %.17g, expected %.17g", iter,
                          j, out[j], expect);
            /* A bound: no point of the arc is above it. */
            for (int t = 0; t <= 64; ++t)
                ck_assert(profile_at(p, kk, a + (b - a) * t / 64.0) <= out[j] + 1e-12);
        }
    }
}
END_TEST

START_TEST(arc_parse_and_write) {
    rugo_shape_desc d = parse_rough_ok("\"background\": 0.01, \"ranges\": [{\"from\": 0.9, \"to\": 0.1, "
                                       "\"tolerance\": 0.5, \"note\": \"x\"}, {\"tolerance\": 0, \"to\": 1, "
                                       "\"from\": 0}], \"seed\": 3");
    const rugo_roughness_desc* r = &d.roughness;
    ck_assert_int_eq(r->kind, RUGO_ROUGHNESS_RANGES);
    ck_assert_int_eq(r->range_count, 2);
    ck_assert(r->ranges[0].from == 0.9 && r->ranges[0].to == 0.1 && r->ranges[0].tolerance == 0.5);
    ck_assert(r->ranges[1].from == 0.0 && r->ranges[1].to == 1.0 && r->ranges[1].tolerance == 0.0);
    ck_assert(r->background == 0.01 && r->seed == 3);
    ck_assert_ptr_null(r->profile);
    rugo_text text;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_ptr_nonnull(strstr(text.data,
                                 "  \"roughness\": {\n    \"ranges\": [\n"
                                 "      {\"from\": 0.90000000000000002, \"to\": 0.10000000000000001, "
                                 "\"tolerance\": 0.5},\n"
                                 "      {\"from\": 0, \"to\": 1, \"tolerance\": 0}\n    ],\n"
                                 "    \"background\": 0.01,\n    \"seed\": 3,\n"));
    rugo_text_free(&text);
    rugo_shape_desc_free(&d);
    ck_assert_ptr_null(d.roughness.ranges);
    /* An empty list is the background alone; the background defaults to 0. */
    d = parse_rough_ok("\"ranges\": []");
    ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_RANGES);
    ck_assert_int_eq(d.roughness.range_count, 0);
    ck_assert(d.roughness.background == 0.0);
    rugo_shape_desc_free(&d);
    /* "background" belongs to ranges: with another kind it is ignored like an unknown member. */
    d = parse_rough_ok("\"constant\": 0.5, \"background\": -1");
    ck_assert(d.roughness.background == 0.0);
    rugo_shape_desc_free(&d);
    d = parse_rough_ok("\"profile\": [[0, 0.5], [0.25, 1e-300], [1, -0]]");
    ck_assert_int_eq(d.roughness.kind, RUGO_ROUGHNESS_PROFILE);
    ck_assert_int_eq(d.roughness.profile_count, 3);
    ck_assert(d.roughness.profile[1].s == 0.25 && d.roughness.profile[1].tolerance == 1e-300);
    ck_assert(bits_of(d.roughness.profile[2].tolerance) == bits_of(-0.0));
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text), RUGO_OK);
    ck_assert_ptr_nonnull(strstr(text.data, "  \"roughness\": {\n    \"profile\": [\n      [0, 0.5],\n"
                                            "      [0.25, 1e-300],\n      [1, -0]\n    ],\n"
                                            "    \"seed\": 0,\n"));
    rugo_text_free(&text);
    rugo_shape_desc_free(&d);
    /* A custom allocator holds the arrays and frees them. */
    test_budget_ctx ctx = {1000, 0};
    rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
    char buf[1024];
    rugo_parse_error err;
    rough_text("\"ranges\": [{\"from\": 0, \"to\": 0.5, \"tolerance\": 1}]", buf, sizeof buf);
    ck_assert_int_eq(rugo_shape_desc_parse(buf, strlen(buf), &a, &d, &err), RUGO_OK);
    ck_assert_int_eq(ctx.live, 2);
    rugo_shape_desc_free(&d);
    ck_assert_int_eq(ctx.live, 0);
    rough_text("\"profile\": [[0, 1]]", buf, sizeof buf);
    ck_assert_int_eq(rugo_shape_desc_parse(buf, strlen(buf), &a, &d, &err), RUGO_OK);
    ck_assert_int_eq(ctx.live, 2);
    rugo_shape_desc_free(&d);
    ck_assert_int_eq(ctx.live, 0);
}
END_TEST

/* A random fraction with all its bits: 0, 1 or uniform. */
static double random_fraction(test_rng* r) {
    uint64_t u = test_rng_next(r);
    if (u % 10 == 0) return 0.0;
    if (u % 10 == 1) return 1.0;
    return test_rng_uniform(r, 0.0, 1.0);
}

START_TEST(arc_round_trip_bits) {
    test_rng r = test_rng_seed(0x3a3a);
    rugo_vec2 four[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int iter = 0; iter < 400; ++iter) {
        rugo_shape_desc desc = make_desc(four, 4, RUGO_FILTER_CDF4_8);
        desc.has_roughness = true;
        rugo_roughness_range g[12];
        rugo_profile_sample p[12];
        int m = (int)(test_rng_next(&r) % 12);
        if (iter % 2 == 0) {
            for (int i = 0; i < m; ++i) {
                do {
                    g[i].from = random_fraction(&r);
                    g[i].to = random_fraction(&r);
                } while (g[i].from == g[i].to || (g[i].from == 1.0 && g[i].to == 0.0));
                g[i].tolerance = test_rng_uniform(&r, 0.0, 1e3) * (test_rng_next(&r) % 2 ? 1e-200 : 1.0);
            }
            desc.roughness = ranges_desc(g, m, test_rng_uniform(&r, 0.0, 2.0));
        } else {
            double s = 0.0;
            int k = 0;
            for (int i = 0; i <= m; ++i) {
                s = k == 0 ? random_fraction(&r) * 0.5 : s + (1.0 - s) * test_rng_uniform(&r, 0.01, 1.0);
                if (k > 0 && !(s > p[k - 1].s && s <= 1.0)) break;
                p[k].s = s;
                p[k++].tolerance = test_rng_uniform(&r, 0.0, 5.0);
            }
            desc.roughness = profile_desc(p, k);
        }
        desc.roughness.seed = test_rng_next(&r) % (RUGO_MAX_FILE_SEED + 1);
        rugo_text text;
        ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text), RUGO_OK);
        rugo_shape_desc back;
        rugo_parse_error err;
        ck_assert_msg(rugo_shape_desc_parse(text.data, text.length, NULL, &back, &err) == RUGO_OK,
                      "%s: %s\n%s", err.path, err.message, text.data);
        const rugo_roughness_desc *a = &desc.roughness, *b = &back.roughness;
        assert_same_roughness(a, b); /* every member, the ranges or samples included, bit for bit */
        rugo_text text2;
        ck_assert_int_eq(rugo_shape_desc_write(&back, NULL, &text2), RUGO_OK);
        ck_assert(text2.length == text.length && memcmp(text.data, text2.data, text.length) == 0);
        /* The resolved tolerances agree too. */
        rugo_real t1[4], t2[4];
        rugo_contour c = {four, 4};
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(a, c, NULL, t1), RUGO_OK);
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(b, c, NULL, t2), RUGO_OK);
        ck_assert(memcmp(t1, t2, sizeof t1) == 0);
        rugo_text_free(&text2);
        rugo_text_free(&text);
        rugo_shape_desc_free(&back);
    }
}
END_TEST

START_TEST(arc_parse_errors) {
    /* one source */
    expect_rough_fail("\"ranges\": [], \"constant\": 1", RUGO_ERR_BAD_FIELD, "roughness",
                      "found \"constant\" and \"ranges\"");
    expect_rough_fail("\"profile\": [[0, 1]], \"preset\": \"tipo_1\"", RUGO_ERR_BAD_FIELD, "roughness",
                      "found \"preset\" and \"profile\"");
    expect_rough_fail("\"seed\": 1", RUGO_ERR_BAD_FIELD, "roughness", "\"ranges\" or \"profile\"");
    /* ranges */
    expect_rough_fail("\"ranges\": {}", RUGO_ERR_BAD_FIELD, "roughness.ranges", "found an object");
    expect_rough_fail("\"ranges\": null", RUGO_ERR_BAD_FIELD, "roughness.ranges", "found null");
    expect_rough_fail("\"ranges\": [[0, 1, 2]]", RUGO_ERR_BAD_FIELD, "roughness.ranges[0]", "found an array");
    expect_rough_fail(
        "\"ranges\": [{\"from\": 0, \"to\": 1, \"tolerance\": 1}, {\"to\": 1, \"tolerance\": 1}]",
        RUGO_ERR_BAD_FIELD, "roughness.ranges[1].from", "missing field \"from\"");
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"tolerance\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0].to", "missing field \"to\"");
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"to\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0].tolerance", "missing field \"tolerance\"");
    expect_rough_fail("\"ranges\": [{\"from\": -0.1, \"to\": 1, \"tolerance\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0].from", "in [0, 1]");
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"to\": 1.5, \"tolerance\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0].to", "found 1.5");
    expect_rough_fail("\"ranges\": [{\"from\": 0.3, \"to\": 0.3, \"tolerance\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0]", "is empty");
    expect_rough_fail("\"ranges\": [{\"from\": 1, \"to\": 0, \"tolerance\": 1}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0]", "is empty");
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"to\": 1, \"tolerance\": -0.5}]",
                      RUGO_ERR_NEGATIVE_TOLERANCE, "roughness.ranges[0].tolerance", "-0.5");
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"to\": 1, \"tolerance\": \"1\"}]", RUGO_ERR_BAD_FIELD,
                      "roughness.ranges[0].tolerance", "found a string");
    expect_rough_fail("\"ranges\": [{\"from\": 1e999, \"to\": 1, \"tolerance\": 1}]", RUGO_ERR_NOT_FINITE,
                      "roughness.ranges[0].from", NULL);
    expect_rough_fail("\"ranges\": [{\"from\": 0, \"from\": 0, \"to\": 1, \"tolerance\": 1}]",
                      RUGO_ERR_BAD_FIELD, "roughness.ranges[0].from", "appears 2 times");
    expect_rough_fail("\"ranges\": [], \"background\": -0.01", RUGO_ERR_NEGATIVE_TOLERANCE,
                      "roughness.background", NULL);
    expect_rough_fail("\"ranges\": [], \"background\": \"0\"", RUGO_ERR_BAD_FIELD, "roughness.background",
                      "found a string");
    expect_rough_fail("\"ranges\": [], \"background\": 0, \"background\": 0", RUGO_ERR_BAD_FIELD,
                      "roughness.background", "appears 2 times");
    /* profile */
    expect_rough_fail("\"profile\": 1", RUGO_ERR_BAD_FIELD, "roughness.profile", "found a number");
    expect_rough_fail("\"profile\": []", RUGO_ERR_BAD_FIELD, "roughness.profile", "at least one");
    expect_rough_fail("\"profile\": [[0, 1], 2]", RUGO_ERR_BAD_FIELD, "roughness.profile[1]",
                      "found a number");
    expect_rough_fail("\"profile\": [[0, 1, 2]]", RUGO_ERR_BAD_FIELD, "roughness.profile[0]", "array of 3");
    expect_rough_fail("\"profile\": [[0, \"1\"]]", RUGO_ERR_BAD_FIELD, "roughness.profile[0][1]",
                      "found a string");
    expect_rough_fail("\"profile\": [[0, 1], [1.5, 1]]", RUGO_ERR_BAD_FIELD, "roughness.profile[1][0]",
                      "in [0, 1]");
    expect_rough_fail("\"profile\": [[-1e-300, 1]]", RUGO_ERR_BAD_FIELD, "roughness.profile[0][0]", NULL);
    expect_rough_fail("\"profile\": [[0.5, 1], [0.5, 2]]", RUGO_ERR_BAD_FIELD, "roughness.profile[1][0]",
                      "increase strictly");
    expect_rough_fail("\"profile\": [[0.5, 1], [0.75, 2], [0.25, 2]]", RUGO_ERR_BAD_FIELD,
                      "roughness.profile[2][0]", "0.25 follows 0.75");
    expect_rough_fail("\"profile\": [[0.5, -1]]", RUGO_ERR_NEGATIVE_TOLERANCE, "roughness.profile[0][1]",
                      NULL);
    expect_rough_fail("\"profile\": [[0.5, 1e999]]", RUGO_ERR_NOT_FINITE, "roughness.profile[0][1]", NULL);
    /* Positions */
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\"control_points\": [],\n \"roughness\": {\"profile\": [[0, 1],\n    [0.5, -2]]}}";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_str_eq(err.path, "roughness.profile[1][1]");
    ck_assert_int_eq(err.line, 3);
    ck_assert_int_eq(err.column, 11);
    /* Size limits */
    size_t cap = (size_t)(RUGO_MAX_ROUGHNESS_RANGES + 1) * 40 + 256;
    char* big = (char*)malloc(cap);
    ck_assert_ptr_nonnull(big);
    size_t n = (size_t)snprintf(big, cap, "{%s, \"roughness\": {\"ranges\": [", SQUARE4);
    for (int i = 0; i <= RUGO_MAX_ROUGHNESS_RANGES; ++i)
        n += (size_t)snprintf(big + n, cap - n, "%s{\"from\":0,\"to\":1,\"tolerance\":0}", i ? "," : "");
    n += (size_t)snprintf(big + n, cap - n, "]}}");
    ck_assert_int_eq(shape_parse_n(big, n, &desc, &err), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_str_eq(err.path, "roughness.ranges");
    free(big);
    cap = (size_t)(RUGO_MAX_PROFILE_SAMPLES + 1) * 6 + 256;
    big = (char*)malloc(cap);
    ck_assert_ptr_nonnull(big);
    n = (size_t)snprintf(big, cap, "{%s, \"roughness\": {\"profile\": [", SQUARE4);
    for (int i = 0; i <= RUGO_MAX_PROFILE_SAMPLES; ++i) {
        memcpy(big + n, i ? ",[0,0]" : "[0,0]", i ? 6 : 5);
        n += i ? 6 : 5;
    }
    n += (size_t)snprintf(big + n, cap - n, "]}}");
    ck_assert_int_eq(shape_parse_n(big, n, &desc, &err), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_str_eq(err.path, "roughness.profile");
    free(big);
}
END_TEST

START_TEST(arc_resolve_errors) {
    rugo_contour c = {SQ4, 4};
    rugo_real out[4];
    rugo_roughness_range g[2] = {{0.2, 0.4, 0.3}, {0.5, 0.6, 0.1}};
    rugo_profile_sample p[2] = {{0.2, 0.3}, {0.5, 0.1}};
    rugo_roughness_desc r = ranges_desc(g, 2, 0.0);
    rugo_roughness_desc q = profile_desc(p, 2);
    /* The geometry-free function refuses the kinds that need geometry. */
    ck_assert_int_eq(rugo_roughness_tolerances(&r, 4, out), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_tolerances(&q, 4, out), RUGO_ERR_BAD_ARGUMENT);
    /* The old kinds pass through. */
    rugo_roughness_desc t = rugo_default_roughness_desc();
    t.kind = RUGO_ROUGHNESS_PRESET;
    t.preset = RUGO_PRESET_TIPO_3;
    rugo_real expect[4];
    ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&t, c, NULL, out), RUGO_OK);
    ck_assert_int_eq(rugo_roughness_tolerances(&t, 4, expect), RUGO_OK);
    ck_assert(memcmp(out, expect, sizeof out) == 0);
    rugo_contour none = {NULL, 4};
    ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&t, none, NULL, out), RUGO_OK); /* count only */
    /* Every error leaves out untouched. */
    struct {
        const char* what;
        rugo_roughness_desc d;
        rugo_contour c;
        rugo_status expect;
    } cases[32];
    int nc = 0;
    rugo_vec2 nan_pts[4] = {{0, 0}, {1, 0}, {1, NAN}, {0, 1}};
    rugo_vec2 same[4] = {{2, 2}, {2, 2}, {2, 2}, {2, 2}};
    rugo_vec2 huge[4] = {{0, 0}, {1e308, 0}, {1e308, 1e308}, {0, 1e308}};
    rugo_contour three = {SQ4, 3}, nanc = {nan_pts, 4}, zero = {same, 4}, big = {huge, 4};
    rugo_contour many = {SQ4, RUGO_MAX_CONTROL_POINTS + 1};
    rugo_roughness_range bad_from[1] = {{1.5, 0.4, 0.3}}, empty[1] = {{0.4, 0.4, 0.3}},
                         neg[1] = {{0.1, 0.4, -0.3}}, inf_to[1] = {{0.1, INFINITY, 0.3}};
    rugo_profile_sample down[2] = {{0.5, 0.3}, {0.4, 0.1}}, negp[1] = {{0.5, -0.1}}, nanp[1] = {{NAN, 0.1}};
#define CASE(w, dd, cc, st)                                                                                  \
    (cases[nc].what = (w), cases[nc].d = (dd), cases[nc].c = (cc), cases[nc++].expect = (st))
    CASE("no points", r, none, RUGO_ERR_NULL_ARGUMENT);
    CASE("three points", r, three, RUGO_ERR_TOO_FEW_POINTS);
    CASE("too many points", r, many, RUGO_ERR_TOO_MANY_POINTS);
    CASE("NaN point", q, nanc, RUGO_ERR_NOT_FINITE);
    CASE("zero perimeter", r, zero, RUGO_ERR_ZERO_AREA);
    CASE("overflowing perimeter", q, big, RUGO_ERR_NOT_FINITE);
    CASE("from out of range", ranges_desc(bad_from, 1, 0.0), c, RUGO_ERR_BAD_ARGUMENT);
    CASE("empty range", ranges_desc(empty, 1, 0.0), c, RUGO_ERR_BAD_ARGUMENT);
    CASE("negative range tolerance", ranges_desc(neg, 1, 0.0), c, RUGO_ERR_NEGATIVE_TOLERANCE);
    CASE("infinite to", ranges_desc(inf_to, 1, 0.0), c, RUGO_ERR_NOT_FINITE);
    CASE("negative background", ranges_desc(g, 2, -1.0), c, RUGO_ERR_NEGATIVE_TOLERANCE);
    CASE("NaN background", ranges_desc(g, 2, NAN), c, RUGO_ERR_NOT_FINITE);
    CASE("ranges NULL", ranges_desc(NULL, 2, 0.0), c, RUGO_ERR_NULL_ARGUMENT);
    CASE("negative range count", ranges_desc(g, -1, 0.0), c, RUGO_ERR_BAD_ARGUMENT);
    CASE("too many ranges", ranges_desc(g, RUGO_MAX_ROUGHNESS_RANGES + 1, 0.0), c, RUGO_ERR_TOO_MANY_POINTS);
    CASE("empty profile", profile_desc(p, 0), c, RUGO_ERR_BAD_ARGUMENT);
    CASE("profile NULL", profile_desc(NULL, 2), c, RUGO_ERR_NULL_ARGUMENT);
    CASE("too many samples", profile_desc(p, RUGO_MAX_PROFILE_SAMPLES + 1), c, RUGO_ERR_TOO_MANY_POINTS);
    CASE("s decreasing", profile_desc(down, 2), c, RUGO_ERR_BAD_ARGUMENT);
    CASE("negative sample", profile_desc(negp, 1), c, RUGO_ERR_NEGATIVE_TOLERANCE);
    CASE("NaN s", profile_desc(nanp, 1), c, RUGO_ERR_NOT_FINITE);
#undef CASE
    for (int i = 0; i < nc; ++i) {
        for (int j = 0; j < 4; ++j)
            out[j] = -7.0;
        rugo_status st = rugo_roughness_tolerances_on_contour(&cases[i].d, cases[i].c, NULL, out);
        ck_assert_msg(st == cases[i].expect, "%s: status %d, expected %d", cases[i].what, (int)st,
                      (int)cases[i].expect);
        for (int j = 0; j < 4; ++j)
            ck_assert(out[j] == -7.0);
        /* The writer refuses the same descriptions (ones that need points aside). */
        if (cases[i].c.points == SQ4 && cases[i].c.count == 4) {
            rugo_vec2 four[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            rugo_shape_desc d = make_desc(four, 4, RUGO_FILTER_CDF4_8);
            d.has_roughness = true;
            d.roughness = cases[i].d;
            rugo_text text;
            ck_assert_msg(rugo_shape_desc_write(&d, NULL, &text) == cases[i].expect, "write: %s",
                          cases[i].what);
            ck_assert_ptr_null(text.data);
        }
    }
    ck_assert_int_eq(rugo_roughness_tolerances_on_contour(NULL, c, NULL, out), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&r, c, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    /* Out of memory at every allocation: the status, nothing leaked, then success. */
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        for (int j = 0; j < 4; ++j)
            out[j] = -7.0;
        rugo_status st = rugo_roughness_tolerances_on_contour(&r, c, &a, out);
        ck_assert_int_eq(ctx.live, 0);
        if (st == RUGO_OK) {
            ck_assert(out[0] == 0.3 && out[2] == 0.1);
            ck_assert_int_ge(budget, 2);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert(out[0] == -7.0);
        ck_assert_int_lt(budget, 10);
    }
}
END_TEST

START_TEST(arc_shape_from_ranges) {
    /* A regular octagon: eight equal arcs, segment j on [j/8, (j+1)/8]. 0.3..0.45 touches segments 2 and
     * 3; the built shape carries exactly these tolerances at its finest level. */
    rugo_vec2 ccw[8], cw[8];
    for (int i = 0; i < 8; ++i)
        ccw[i] = rugo_v2(2.0 * cos(i * M_PI / 4.0), 2.0 * sin(i * M_PI / 4.0));
    for (int i = 0; i < 8; ++i)
        cw[i] = ccw[7 - i];
    static const double expect[8] = {0.01, 0.01, 0.2, 0.2, 0.01, 0.01, 0.01, 0.01};
    for (int orient = 0; orient < 2; ++orient) {
        rugo_vec2* pts = orient == 0 ? ccw : cw;
        char text[2048];
        int len = snprintf(text, sizeof text, "{\"control_points\": [");
        for (int i = 0; i < 8; ++i)
            len += snprintf(text + len, sizeof text - (size_t)len, "%s[%.17g, %.17g]", i ? ", " : "",
                            pts[i].x, pts[i].y);
        len += snprintf(text + len, sizeof text - (size_t)len,
                        "], \"roughness\": {\"ranges\": [{\"from\": 0.3, \"to\": 0.45, \"tolerance\": 0.2}], "
                        "\"background\": 0.01}}");
        rugo_shape_desc d;
        rugo_parse_error err;
        ck_assert_int_eq(shape_parse_n(text, (size_t)len, &d, &err), RUGO_OK);
        rugo_real lam[8];
        rugo_contour c = {d.control_points, d.count};
        ck_assert_int_eq(rugo_roughness_tolerances_on_contour(&d.roughness, c, NULL, lam), RUGO_OK);
        for (int j = 0; j < 8; ++j)
            ck_assert_msg(lam[j] == expect[j], "orient %d segment %d: %g", orient, j, lam[j]);
        rugo_shape_def def = rugo_default_shape_def();
        def.points = d.control_points;
        def.count = d.count;
        def.filter = d.filter;
        def.tolerances = lam;
        rugo_shape* s = NULL;
        ck_assert_int_eq(rugo_shape_create(&def, &s, NULL), RUGO_OK);
        ck_assert_int_eq(rugo_shape_was_reversed(s), orient);
        rugo_tolerance_level L;
        ck_assert_int_eq(rugo_shape_tolerance_level(s, rugo_shape_finest_level(s), &L), RUGO_OK);
        ck_assert_int_eq(L.count, 8);
        /* A clockwise file's segment j is the shape's segment n-2-j. */
        for (int k = 0; k < 8; ++k)
            ck_assert(L.total[k] == (orient == 0 ? expect[k] : expect[(8 - 2 - k + 8) % 8]));
        rugo_shape_destroy(s);
        rugo_shape_desc_free(&d);
    }
}
END_TEST

/* ---- profiles from CSV ---- */

static rugo_status csv_parse_n(const char* s, size_t n, rugo_roughness_profile* p, rugo_parse_error* e) {
    char* buf = exact_copy(s, n);
    rugo_status st = rugo_roughness_profile_parse_csv(buf, n, NULL, p, e);
    free(buf);
    return st;
}

static void expect_csv_fail(const char* s, rugo_status status, const char* path, int line,
                            const char* fragment) {
    rugo_roughness_profile p;
    p.samples = (rugo_profile_sample*)&p; /* must come back NULL */
    p.count = -1;
    rugo_parse_error e;
    rugo_status st = csv_parse_n(s, strlen(s), &p, &e);
    ck_assert_msg(st == status, "csv <%s>: status %d (%s), expected %d; %s", s, (int)st,
                  rugo_status_string(st), (int)status, e.message);
    ck_assert_ptr_null(p.samples);
    ck_assert_int_eq(p.count, 0);
    ck_assert(e.message[0] != '\0' && str_nul_terminated(e.message, sizeof e.message));
    if (path != NULL)
        ck_assert_msg(strcmp(e.path, path) == 0, "csv <%s>: path \"%s\", expected \"%s\"", s, e.path, path);
    if (line > 0) ck_assert_msg(e.line == line, "csv <%s>: line %d, expected %d", s, e.line, line);
    if (fragment != NULL)
        ck_assert_msg(strstr(e.message, fragment) != NULL, "csv <%s>: message \"%s\" lacks \"%s\"", s,
                      e.message, fragment);
}

START_TEST(profile_csv_good) {
    struct {
        const char* text;
        int count;
        double s1, lam1; /* the second sample (or the first if there is one) */
    } good[] = {
        {"s,lambda\n0,0.1\n0.5,0.2\n", 2, 0.5, 0.2},
        {"0,0.1\n0.5,0.2", 2, 0.5, 0.2}, /* no header, no final newline */
        {"\xEF\xBB\xBF"
         "s,lambda\r\n0,0.1\r\n0.5,0.2\r\n",
         2, 0.5, 0.2}, /* BOM, CRLF */
        {"# measured\n\n  s , lambda \n\t0 ,\t0.1  \n# mid\n\n 0.5, 0.2\n\n", 2, 0.5, 0.2},
        {".25,5.\n+0.5,-0\n", 2, 0.5, -0.0},
        {"0.1,1e-1\n00.5,2E+0\n", 2, 0.5, 2.0},
        {"\"s\",\"lambda\"\n0.7,0.1\n", 1, 0.7, 0.1}, /* any header names */
        {"0.1,0.30000000000000004\n", 1, 0.1, 0.30000000000000004},
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
        rugo_roughness_profile p;
        rugo_parse_error e;
        rugo_status st = csv_parse_n(good[i].text, strlen(good[i].text), &p, &e);
        ck_assert_msg(st == RUGO_OK, "csv %d: %s at %d:%d %s", (int)i, rugo_status_string(st), e.line,
                      e.column, e.message);
        ck_assert_int_eq(p.count, good[i].count);
        const rugo_profile_sample* x = &p.samples[p.count > 1 ? 1 : 0];
        ck_assert(bits_of(x->s) == bits_of(good[i].s1));
        ck_assert(bits_of(x->tolerance) == bits_of(good[i].lam1));
        rugo_roughness_profile_free(&p);
    }
    /* The same bits as the JSON reader for every number it writes. */
    test_rng r = test_rng_seed(0xc5f);
    char text[64];
    for (int i = 0; i < 2000; ++i) {
        double s = test_rng_uniform(&r, 0.0, 1.0),
               lam = test_rng_uniform(&r, 0.0, 1e3) * pow(10.0, -(i % 300));
        snprintf(text, sizeof text, "%.17g,%.17g\n", s, lam);
        rugo_roughness_profile p;
        ck_assert_int_eq(csv_parse_n(text, strlen(text), &p, NULL), RUGO_OK);
        ck_assert(bits_of(p.samples[0].s) == bits_of(s) && bits_of(p.samples[0].tolerance) == bits_of(lam));
        rugo_roughness_profile_free(&p);
    }
    /* A profile read from CSV resolves like the same profile inline. */
    const char* csv = "s,lambda\n0.1,0\n0.125,1\n0.15,0\n";
    rugo_roughness_profile p;
    ck_assert_int_eq(csv_parse_n(csv, strlen(csv), &p, NULL), RUGO_OK);
    rugo_roughness_desc d = profile_desc(p.samples, p.count);
    static const double expect[4] = {1.0, 0.0, 0.0, 0.0};
    expect_on_square("csv", &d, expect, 0.0);
    rugo_roughness_profile_free(&p);
    ck_assert(p.samples == NULL && p.count == 0);
    rugo_roughness_profile_free(&p); /* a zeroed profile, and NULL, are fine */
    rugo_roughness_profile_free(NULL);
}
END_TEST

START_TEST(profile_csv_bad) {
    expect_csv_fail("", RUGO_ERR_BAD_FIELD, "", 0, "no samples");
    expect_csv_fail("s,lambda\n", RUGO_ERR_BAD_FIELD, "", 0, "no samples");
    expect_csv_fail("# nothing\n\n", RUGO_ERR_BAD_FIELD, NULL, 0, "no samples");
    expect_csv_fail("0.1\n", RUGO_ERR_PARSE, "profile[0]", 1, "1 field");
    expect_csv_fail("0.1,0.2,0.3\n", RUGO_ERR_PARSE, "profile[0]", 1, "3 fields");
    expect_csv_fail("0.1;0.2\n", RUGO_ERR_PARSE, "profile[0]", 1, NULL);
    expect_csv_fail("s,lambda,x\n0.1,0.2\n", RUGO_ERR_PARSE, "", 1, "header");
    expect_csv_fail("0.1,0.2\n0.2,abc\n", RUGO_ERR_PARSE, "profile[1][1]", 2, "\"abc\"");
    expect_csv_fail("0.1,\n", RUGO_ERR_PARSE, "profile[0][1]", 1, "empty field");
    expect_csv_fail("0.1,0.2\ns,lambda\n", RUGO_ERR_PARSE, "profile[1][0]", 2,
                    NULL); /* a header only first */
    expect_csv_fail("0.1,0x10\n", RUGO_ERR_PARSE, "profile[0][1]", 1, NULL);
    expect_csv_fail("0.1,1e\n", RUGO_ERR_PARSE, "profile[0][1]", 1, NULL);
    expect_csv_fail("0.1,-\n", RUGO_ERR_PARSE, "profile[0][1]", 1, NULL);
    expect_csv_fail("0.1,0.2\r\r\n", RUGO_ERR_PARSE, "profile[0][1]", 1, NULL);
    expect_csv_fail("nan,0.1\n", RUGO_ERR_NOT_FINITE, "profile[0][0]", 1, "not a finite number");
    expect_csv_fail("s,lambda\n0.1,inf\n", RUGO_ERR_NOT_FINITE, "profile[0][1]", 2, NULL);
    expect_csv_fail("0.1,-Infinity\n", RUGO_ERR_NOT_FINITE, "profile[0][1]", 1, NULL);
    expect_csv_fail("0.1,NaN\n", RUGO_ERR_NOT_FINITE, "profile[0][1]", 1, NULL);
    expect_csv_fail("0.1,1e999\n", RUGO_ERR_NOT_FINITE, "profile[0][1]", 1, "overflows");
    expect_csv_fail("-0.1,0.2\n", RUGO_ERR_BAD_FIELD, "profile[0][0]", 1, "in [0, 1]");
    expect_csv_fail("0.5,0\n1.5,0\n", RUGO_ERR_BAD_FIELD, "profile[1][0]", 2, "found 1.5");
    expect_csv_fail("0.5,0\n0.5,1\n", RUGO_ERR_BAD_FIELD, "profile[1][0]", 2, "increase strictly");
    expect_csv_fail("0.5,0\n\n0.4,1\n", RUGO_ERR_BAD_FIELD, "profile[1][0]", 3,
                    "0.40000000000000002 follows 0.5");
    expect_csv_fail("0.1,-0.2\n", RUGO_ERR_NEGATIVE_TOLERANCE, "profile[0][1]", 1, NULL);
    /* The column of the offending field. */
    rugo_roughness_profile p;
    rugo_parse_error e;
    const char* t = "s,lambda\n0.1, 0.2\n0.3,  -4\n";
    ck_assert_int_eq(csv_parse_n(t, strlen(t), &p, &e), RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_int_eq(e.line, 3);
    ck_assert_int_eq(e.column, 7);
    /* Arguments; error may be NULL. */
    ck_assert_int_eq(rugo_roughness_profile_parse_csv(NULL, 0, NULL, &p, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_profile_parse_csv("0,0", 3, NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_roughness_profile_parse_csv("0,-1", 4, NULL, &p, NULL),
                     RUGO_ERR_NEGATIVE_TOLERANCE);
    ck_assert_ptr_null(p.samples);
}
END_TEST

START_TEST(profile_csv_limits_and_memory) {
    /* Larger than the text limit: refused before reading. */
    rugo_roughness_profile p;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_roughness_profile_parse_csv("0,0", RUGO_MAX_JSON_BYTES + 1, NULL, &p, &e),
                     RUGO_ERR_PARSE);
    /* RUGO_MAX_PROFILE_SAMPLES rows are read; one more is too many. */
    size_t cap = (size_t)(RUGO_MAX_PROFILE_SAMPLES + 1) * 12 + 64;
    char* big = (char*)malloc(cap);
    ck_assert_ptr_nonnull(big);
    size_t n = 0;
    for (int i = 0; i < RUGO_MAX_PROFILE_SAMPLES; ++i)
        n += (size_t)snprintf(big + n, cap - n, "%d.%07d,0\n", 0, i); /* strictly increasing below 0.105 */
    ck_assert_int_eq(csv_parse_n(big, n, &p, &e), RUGO_OK);
    ck_assert_int_eq(p.count, RUGO_MAX_PROFILE_SAMPLES);
    ck_assert(p.samples[p.count - 1].s == 0.1048575);
    rugo_roughness_profile_free(&p);
    n += (size_t)snprintf(big + n, cap - n, "0.5,0\n");
    ck_assert_int_eq(csv_parse_n(big, n, &p, &e), RUGO_ERR_TOO_MANY_POINTS);
    ck_assert_int_eq(e.line, RUGO_MAX_PROFILE_SAMPLES + 1);
    ck_assert_ptr_null(p.samples);
    free(big);
    /* Out of memory at every allocation, nothing leaks. */
    const char* t = "s,lambda\n0,0.1\n0.25,0.2\n0.5,0.3\n";
    for (long budget = 0;; ++budget) {
        test_budget_ctx ctx = {budget, 0};
        rugo_allocator a = {test_budget_alloc, test_budget_free, &ctx};
        rugo_status st = rugo_roughness_profile_parse_csv(t, strlen(t), &a, &p, &e);
        if (st == RUGO_OK) {
            ck_assert_int_eq(p.count, 3);
            ck_assert_int_eq(ctx.live, 1);
            ck_assert(p.allocator.ctx == &ctx); /* recorded, and freed through */
            rugo_roughness_profile_free(&p);
            ck_assert_int_eq(ctx.live, 0);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_ptr_null(p.samples);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 50);
    }
}
END_TEST

int main(void) {
    Suite* s = suite_create("shape_file");
    TCase* json = tcase_create("json");
    tcase_set_timeout(json, 120);
    tcase_add_test(json, json_valid_values);
    tcase_add_test(json, json_rejects_malformed);
    tcase_add_test(json, json_error_paths);
    tcase_add_test(json, json_nesting_and_value_limits);
    tcase_add_test(json, json_number_length_limit);
    tcase_add_test(json, json_not_nul_terminated);
    tcase_add_test(json, json_out_of_memory);
    tcase_add_test(json, json_locale_decimal_point);
    tcase_add_test(json, json_writer_layout);
    tcase_add_test(json, json_writer_strings_round_trip);
    tcase_add_test(json, json_writer_errors);
    tcase_add_test(json, json_number_round_trip);
    suite_add_tcase(s, json);

    TCase* shape = tcase_create("shape");
    tcase_set_timeout(shape, 300);
    tcase_add_test(shape, shape_parse_valid);
    tcase_add_test(shape, shape_parse_errors);
    tcase_add_test(shape, shape_error_positions);
    tcase_add_test(shape, shape_not_nul_terminated);
    tcase_add_test(shape, shape_too_many_points);
    tcase_add_test(shape, shape_max_size_file_fits);
    tcase_add_test(shape, shape_round_trip_bits);
    tcase_add_test(shape, shape_write_errors);
    tcase_add_test(shape, points_parse_keys);
    tcase_add_test(shape, read_file_cases);
    suite_add_tcase(s, shape);

    TCase* rough = tcase_create("roughness");
    tcase_set_timeout(rough, 300);
    tcase_add_test(rough, roughness_defaults);
    tcase_add_test(rough, roughness_parse_valid);
    tcase_add_test(rough, roughness_parse_errors);
    tcase_add_test(rough, roughness_round_trip_bits);
    tcase_add_test(rough, roughness_write_errors);
    tcase_add_test(rough, roughness_write_size_limit);
    tcase_add_test(rough, roughness_tolerances_resolve);
    tcase_add_test(rough, roughness_out_of_memory);
    tcase_add_test(rough, arc_square_quarters);
    tcase_add_test(rough, arc_ranges_hand_computed);
    tcase_add_test(rough, arc_profile_hand_computed);
    tcase_add_test(rough, arc_ranges_brute_force);
    tcase_add_test(rough, arc_profile_brute_force);
    tcase_add_test(rough, arc_parse_and_write);
    tcase_add_test(rough, arc_round_trip_bits);
    tcase_add_test(rough, arc_parse_errors);
    tcase_add_test(rough, arc_resolve_errors);
    tcase_add_test(rough, arc_shape_from_ranges);
    tcase_add_test(rough, profile_csv_good);
    tcase_add_test(rough, profile_csv_bad);
    tcase_add_test(rough, profile_csv_limits_and_memory);
    suite_add_tcase(s, rough);

    TCase* fuzz = tcase_create("fuzz");
    tcase_set_timeout(fuzz, 600);
    tcase_add_test(fuzz, fuzz_mutations);
    tcase_add_test(fuzz, fuzz_roughness_members);
    tcase_add_test(fuzz, fuzz_token_soup);
    suite_add_tcase(s, fuzz);
    return test_run_suite(s);
}
