/* Shape files: the strict JSON reader and writer (librugo/json.c) and the shape description layer
 * (librugo/shape_file.c). Inputs are copied into buffers of exactly their length, so that the
 * sanitizer build catches any read past `length`. */
#include "json.h"
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
static rugo_status json_parse_n(const char* s, size_t n, rugo_json_doc* doc, rugo_json_error* err) {
    char* buf = exact_copy(s, n);
    rugo_status st = rugo_json_parse(buf, n, NULL, NULL, doc, err);
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
    rugo_json_doc doc;
    rugo_json_error err;
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
    rugo_json_doc_free(&doc);
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

static char* read_data(const char* name, size_t* length) {
    char path[1024];
    data_path(name, path, sizeof path);
    char* text = NULL;
    rugo_status st = rugo_read_file(path, NULL, &text, length);
    ck_assert_msg(st == RUGO_OK, "%s: %s", path, rugo_status_string(st));
    return text;
}

/* An allocator that fails after `budget` allocations and counts live blocks. */
typedef struct budget_ctx {
    long budget;
    long live;
} budget_ctx;

static void* budget_alloc(size_t n, void* ctx) {
    budget_ctx* b = (budget_ctx*)ctx;
    if (b->budget <= 0) return NULL;
    --b->budget;
    void* p = malloc(n);
    if (p != NULL) ++b->live;
    return p;
}

static void budget_free(void* p, void* ctx) {
    budget_ctx* b = (budget_ctx*)ctx;
    if (p != NULL) --b->live;
    free(p);
}

/* ------------------------------------------------------------------------------------------------ */
/* JSON reader */

START_TEST(json_valid_values) {
    rugo_json_doc doc;
    rugo_json_error err;
    const char* text =
        " {\"n\": null, \"t\": true, \"f\": false, \"num\": [0, -0, 12.5e-1, 1E+2, -7],"
        " \"s\": \"a\\\"\\\\\\/\\b\\f\\n\\r\\tz\", \"u\": \"\\u00e9\\u20AC\\ud83d\\ude00\\u0000x\","
        " \"raw\": \"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\", \"o\": {}, \"a\": [], \"n\": 1}\r\n\t";
    ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
    const rugo_json_value* root = doc.root;
    ck_assert_int_eq(root->type, RUGO_JSON_OBJECT);
    ck_assert_int_eq((int)root->count, 10);
    /* Members keep their order; duplicates are kept and counted. */
    const char* order[] = {"n", "t", "f", "num", "s", "u", "raw", "o", "a", "n"};
    int i = 0;
    for (const rugo_json_value* k = root->u.first; k != NULL; k = RUGO_JSON_NEXT_MEMBER(k), ++i) {
        ck_assert_int_eq(k->type, RUGO_JSON_STRING);
        ck_assert_str_eq(k->u.string, order[i]);
    }
    ck_assert_int_eq(i, 10);
    int matches = 0;
    const rugo_json_value* v = rugo_json_object_get(root, "n", &matches);
    ck_assert_int_eq(matches, 2);
    ck_assert_int_eq(v->type, RUGO_JSON_NULL);
    ck_assert_int_eq(rugo_json_object_get(root, "t", NULL)->u.boolean, 1);
    ck_assert_int_eq(rugo_json_object_get(root, "f", NULL)->u.boolean, 0);
    ck_assert_ptr_null(rugo_json_object_get(root, "missing", &matches));
    ck_assert_int_eq(matches, 0);

    v = rugo_json_object_get(root, "num", NULL);
    ck_assert_int_eq((int)v->count, 5);
    const double nums[] = {0.0, -0.0, 1.25, 100.0, -7.0};
    i = 0;
    for (const rugo_json_value* e = v->u.first; e != NULL; e = e->next, ++i) {
        ck_assert_int_eq(e->type, RUGO_JSON_NUMBER);
        ck_assert(bits_of(e->u.number) == bits_of(nums[i]));
    }

    v = rugo_json_object_get(root, "s", NULL);
    ck_assert_int_eq((int)v->count, 10);
    ck_assert(memcmp(v->u.string, "a\"\\/\b\f\n\r\tz", 11) == 0);
    v = rugo_json_object_get(root, "u", NULL);
    /* é (2 bytes), € (3), U+1F600 from a surrogate pair (4), NUL, x */
    ck_assert_int_eq((int)v->count, 11);
    ck_assert(memcmp(v->u.string, "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\0x", 12) == 0);
    const rugo_json_value* raw = rugo_json_object_get(root, "raw", NULL);
    ck_assert_int_eq((int)raw->count, 9);
    ck_assert(memcmp(raw->u.string, v->u.string, 9) == 0);
    ck_assert_int_eq((int)rugo_json_object_get(root, "o", NULL)->count, 0);
    ck_assert_int_eq(rugo_json_object_get(root, "a", NULL)->type, RUGO_JSON_ARRAY);
    /* A key with an embedded NUL never matches a C string. */
    rugo_json_doc_free(&doc);
    ck_assert_ptr_null(doc.root);
    rugo_json_doc_free(&doc); /* twice is harmless */

    const char* keynul = "{\"a\\u0000b\": 1}";
    ck_assert_int_eq(json_parse_n(keynul, strlen(keynul), &doc, &err), RUGO_OK);
    ck_assert_ptr_null(rugo_json_object_get(doc.root, "a", NULL));
    rugo_json_doc_free(&doc);

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
        ck_assert_int_eq(doc.root->type, RUGO_JSON_NUMBER);
        ck_assert_msg(bits_of(doc.root->u.number) == bits_of(scalars[k].value), "%s -> %.17g",
                      scalars[k].text, doc.root->u.number);
        rugo_json_doc_free(&doc);
    }
    ck_assert_str_eq(rugo_json_type_name(RUGO_JSON_OBJECT), "object");
    ck_assert_str_eq(rugo_json_type_name(RUGO_JSON_BOOL), "boolean");
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
    rugo_json_doc doc;
    rugo_json_error err;
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
    ck_assert_int_eq(rugo_json_parse(NULL, 0, NULL, NULL, &doc, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_json_parse("1", 1, NULL, NULL, NULL, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_json_parse("1", 1, NULL, NULL, &doc, NULL), RUGO_OK);
    rugo_json_doc_free(&doc);
    ck_assert_int_eq(rugo_json_parse("1", RUGO_MAX_JSON_BYTES + 1, NULL, NULL, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.line, 0);
    ck_assert_ptr_nonnull(strstr(err.message, "larger"));
}
END_TEST

START_TEST(json_nesting_and_value_limits) {
    enum { N = 100000 };
    char* buf = (char*)malloc(2 * N);
    rugo_json_doc doc;
    rugo_json_error err;
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
                if (depth <= RUGO_JSON_MAX_DEPTH) ck_assert_ptr_null(strstr(err.message, "nesting"));
            } else if (depth <= RUGO_JSON_MAX_DEPTH) {
                ck_assert_int_eq(st, RUGO_OK);
                rugo_json_doc_free(&doc);
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
    ck_assert_int_eq(err.column, RUGO_JSON_MAX_DEPTH + 1);
    /* A lower or higher depth limit on request (capped at RUGO_JSON_DEPTH_CAP). */
    rugo_json_limits lim = {3, 0};
    ck_assert_int_eq(rugo_json_parse("[[[]]]", 6, NULL, &lim, &doc, &err), RUGO_OK);
    rugo_json_doc_free(&doc);
    ck_assert_int_eq(rugo_json_parse("[[[[]]]]", 8, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    lim.max_depth = 100000;
    ck_assert_int_eq(rugo_json_parse(buf, N, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, RUGO_JSON_DEPTH_CAP + 1);
    for (int i = 0; i < RUGO_JSON_DEPTH_CAP; ++i)
        buf[RUGO_JSON_DEPTH_CAP + i] = ']';
    ck_assert_int_eq(rugo_json_parse(buf, 2 * RUGO_JSON_DEPTH_CAP, NULL, &lim, &doc, &err), RUGO_OK);
    rugo_json_doc_free(&doc);
    /* The value limit: [1,2,...,9] is 10 values (strings and keys count too). */
    lim.max_depth = 0;
    lim.max_values = 10;
    ck_assert_int_eq(rugo_json_parse("[1,2,3,4,5,6,7,8,9]", 19, NULL, &lim, &doc, &err), RUGO_OK);
    ck_assert_int_eq((int)doc.value_count, 10);
    rugo_json_doc_free(&doc);
    ck_assert_int_eq(rugo_json_parse("[1,2,3,4,5,6,7,8,9,0]", 21, NULL, &lim, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_ptr_nonnull(strstr(err.message, "more than 10 values"));
    ck_assert_int_eq(rugo_json_parse("{\"a\":1,\"b\":2,\"c\":3,\"d\":4,\"e\":5}", 31, NULL, &lim, &doc, &err),
                     RUGO_ERR_PARSE);
    free(buf);
}
END_TEST

START_TEST(json_number_length_limit) {
    char buf[RUGO_JSON_MAX_NUMBER_CHARS + 8];
    rugo_json_doc doc;
    rugo_json_error err;
    /* "0." + 1016 zeros + "1e+999" (exactly the limit in characters) = 1e-1017 * 1e999. */
    size_t n = RUGO_JSON_MAX_NUMBER_CHARS;
    memset(buf, '0', n);
    buf[1] = '.';
    memcpy(buf + n - 6, "1e+999", 6);
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(bits_of(doc.root->u.number) == bits_of(1e-18));
    rugo_json_doc_free(&doc);
    /* Correct rounding decided by a digit a thousand places in: 1 + 2^-53 is halfway between 1 and
     * 1 + 2^-52 and rounds to even (1); any nonzero digit after it rounds up. */
    const char* half = "1.00000000000000011102230246251565404236316680908203125";
    memset(buf, '0', n);
    memcpy(buf, half, strlen(half));
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 1.0);
    rugo_json_doc_free(&doc);
    buf[n - 1] = '1';
    ck_assert_int_eq(json_parse_n(buf, n, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 1.0 + DBL_EPSILON);
    rugo_json_doc_free(&doc);
    buf[n] = '0';
    expect_json_fail_n(buf, n + 1, RUGO_ERR_PARSE, 1, 1, "longer than 1024");
}
END_TEST

START_TEST(json_not_nul_terminated) {
    rugo_json_doc doc;
    rugo_json_error err;
    /* Only the first `length` bytes count: a number cut by the length ends there. */
    ck_assert_int_eq(json_parse_n("123456", 3, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == 123.0);
    rugo_json_doc_free(&doc);
    ck_assert_int_eq(json_parse_n("-1.5e3x", 6, &doc, &err), RUGO_OK);
    ck_assert(doc.root->u.number == -1500.0);
    rugo_json_doc_free(&doc);
    ck_assert_int_eq(json_parse_n("[1, 23]", 5, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(err.column, 6);
    ck_assert_int_eq(json_parse_n("\"abc\"", 4, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("\"\\u0041\"", 6, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("true", 3, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("\"\xe2\x82\xac\"", 3, &doc, &err), RUGO_ERR_PARSE);
    ck_assert_int_eq(json_parse_n("{\"a\":1}garbage", 7, &doc, &err), RUGO_OK);
    rugo_json_doc_free(&doc);
}
END_TEST

START_TEST(json_out_of_memory) {
    size_t length = 0;
    char* text = read_data("star32.json", &length);
    /* Every allocation failure is reported, leaves nothing allocated, and enough budget succeeds. */
    for (long budget = 0;; ++budget) {
        budget_ctx ctx = {budget, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_json_doc doc;
        rugo_json_error err;
        rugo_status st = rugo_json_parse(text, length, &a, NULL, &doc, &err);
        if (st == RUGO_OK) {
            ck_assert_int_gt(ctx.live, 0);
            rugo_json_doc_free(&doc);
            ck_assert_int_eq(ctx.live, 0);
            break;
        }
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_int_eq(ctx.live, 0);
        ck_assert_int_lt(budget, 100);
    }
    for (long budget = 0;; ++budget) {
        budget_ctx ctx = {budget, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_shape_desc desc;
        rugo_status st = rugo_shape_desc_parse(text, length, &a, &desc, NULL);
        if (st == RUGO_OK) {
            ck_assert_int_eq(desc.count, 32);
            rugo_shape_desc_free(&desc);
            ck_assert_int_eq(ctx.live, 0);
            char* out = NULL;
            size_t out_len = 0;
            /* The writer too. */
            for (long wb = 0;; ++wb) {
                budget_ctx wctx = {wb, 0};
                rugo_allocator wa = {budget_alloc, budget_free, &wctx};
                rugo_shape_desc d2 = desc;
                rugo_vec2 pts[32];
                test_rng r = test_rng_seed(5);
                test_random_star(&r, 32, rugo_v2(0, 0), 1.0, 0.3, pts);
                d2.control_points = pts;
                d2.count = 32;
                st = rugo_shape_desc_write(&d2, &wa, &out, &out_len);
                if (st == RUGO_OK) {
                    ck_assert_int_eq(wctx.live, 1);
                    rugo_text_free(&wa, out);
                    ck_assert_int_eq(wctx.live, 0);
                    break;
                }
                ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
                ck_assert_ptr_null(out);
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
    rugo_text_free(NULL, text);
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
    rugo_json_doc doc;
    rugo_json_error err;
    rugo_status st = json_parse_n("[1.5, -0.25e1]", 14, &doc, &err);
    char buf[40];
    rugo_json_format_number(0.1, buf, sizeof buf);
    setlocale(LC_NUMERIC, "C");
    ck_assert_int_eq(st, RUGO_OK);
    ck_assert(doc.root->u.first->u.number == 1.5);
    ck_assert(doc.root->u.first->next->u.number == -2.5);
    rugo_json_doc_free(&doc);
    ck_assert_str_eq(buf, "0.10000000000000001");
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* JSON writer */

static char* finish_ok(rugo_json_writer* w) {
    char* text = NULL;
    size_t n = 0;
    rugo_status st = rugo_json_writer_finish(w, &text, &n);
    ck_assert_msg(st == RUGO_OK, "finish: %s", rugo_status_string(st));
    ck_assert_int_eq((int)strlen(text), (int)n);
    return text;
}

START_TEST(json_writer_layout) {
    for (int indent = 0; indent <= 2; indent += 2) {
        rugo_json_writer w;
        rugo_json_writer_init(&w, NULL, indent);
        rugo_json_begin_object(&w, 0);
        rugo_json_key(&w, "a");
        rugo_json_begin_array(&w, 0);
        rugo_json_integer(&w, 1);
        rugo_json_number(&w, 2.5);
        rugo_json_begin_array(&w, RUGO_JSON_INLINE);
        rugo_json_number(&w, -0.0);
        rugo_json_string(&w, "x\n");
        rugo_json_end_array(&w);
        rugo_json_end_array(&w);
        rugo_json_key(&w, "b");
        rugo_json_begin_object(&w, 0);
        rugo_json_end_object(&w);
        rugo_json_key(&w, "c");
        rugo_json_begin_array(&w, 0);
        rugo_json_end_array(&w);
        rugo_json_key(&w, "d");
        rugo_json_bool(&w, 1);
        rugo_json_key(&w, "e");
        rugo_json_null(&w);
        rugo_json_key(&w, "f");
        rugo_json_begin_object(&w, RUGO_JSON_INLINE);
        rugo_json_key(&w, "g");
        rugo_json_bool(&w, 0);
        rugo_json_key(&w, "h");
        rugo_json_integer(&w, -9000000000LL);
        rugo_json_end_object(&w);
        rugo_json_end_object(&w);
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
        rugo_json_doc doc;
        rugo_json_error err;
        ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
        ck_assert(
            bits_of(rugo_json_object_get(doc.root, "a", NULL)->u.first->next->next->u.first->u.number) ==
            bits_of(-0.0));
        rugo_json_doc_free(&doc);
        rugo_text_free(NULL, text);
    }
    /* An empty text is an empty string, not NULL. */
    rugo_json_writer w;
    rugo_json_writer_init(&w, NULL, 0);
    char* text = finish_ok(&w);
    ck_assert_str_eq(text, "");
    rugo_text_free(NULL, text);
}
END_TEST

START_TEST(json_writer_strings_round_trip) {
    char all[256 + 8];
    for (int i = 0; i < 128; ++i)
        all[i] = (char)i; /* every ASCII byte, NUL and controls included */
    memcpy(all + 128, "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80", 9);
    size_t n = 137;
    rugo_json_writer w;
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_begin_array(&w, 0);
    rugo_json_string_n(&w, all, n);
    rugo_json_string(&w, "\"\\/");
    rugo_json_end_array(&w);
    char* text = finish_ok(&w);
    ck_assert_ptr_nonnull(strstr(text, "\"\\u0000\\u0001"));
    ck_assert_ptr_nonnull(strstr(text, "\\b\\t\\n\\u000b\\f\\r"));
    ck_assert_ptr_nonnull(strstr(text, "\"\\\"\\\\/\""));
    rugo_json_doc doc;
    rugo_json_error err;
    ck_assert_int_eq(json_parse_n(text, strlen(text), &doc, &err), RUGO_OK);
    ck_assert_int_eq((int)doc.root->u.first->count, (int)n);
    ck_assert(memcmp(doc.root->u.first->u.string, all, n) == 0);
    ck_assert_str_eq(doc.root->u.first->next->u.string, "\"\\/");
    rugo_json_doc_free(&doc);
    rugo_text_free(NULL, text);
}
END_TEST

START_TEST(json_writer_errors) {
    char* text = (char*)1;
    size_t n = 99;
    rugo_json_writer w;
    /* Non-finite numbers are refused, and the error sticks. */
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 3; ++i) {
        rugo_json_writer_init(&w, NULL, 2);
        rugo_json_begin_array(&w, 0);
        rugo_json_number(&w, 1.0);
        rugo_json_number(&w, bad[i]);
        rugo_json_number(&w, 2.0);
        rugo_json_end_array(&w);
        ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_NOT_FINITE);
        ck_assert_ptr_null(text);
        ck_assert_int_eq((int)n, 0);
    }
    /* Misuse */
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_begin_object(&w, 0);
    rugo_json_number(&w, 1.0); /* no key */
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_begin_object(&w, 0);
    rugo_json_end_array(&w);
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_begin_array(&w, 0);
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_key(&w, "top");
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_begin_object(&w, 0);
    rugo_json_key(&w, "k");
    rugo_json_end_object(&w); /* key without a value */
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    for (int i = 0; i <= RUGO_JSON_WRITER_MAX_DEPTH; ++i)
        rugo_json_begin_array(&w, 0);
    ck_assert_int_eq(w.status, RUGO_ERR_BAD_ARGUMENT);
    rugo_json_writer_discard(&w);
    rugo_json_writer_init(&w, NULL, 0);
    rugo_json_string(&w, NULL);
    ck_assert_int_eq(rugo_json_writer_finish(&w, &text, &n), RUGO_ERR_NULL_ARGUMENT);
    rugo_json_writer_init(&w, NULL, 0);
    ck_assert_int_eq(rugo_json_writer_finish(&w, NULL, &n), RUGO_ERR_NULL_ARGUMENT);

    char buf[40];
    ck_assert_int_eq(rugo_json_format_number(0.1, buf, sizeof buf), 19);
    ck_assert_str_eq(buf, "0.10000000000000001");
    rugo_json_format_number(-0.0, buf, sizeof buf);
    ck_assert_str_eq(buf, "-0");
    rugo_json_format_number(1e300, buf, sizeof buf);
    ck_assert_str_eq(buf, "1.0000000000000001e+300");
    rugo_json_format_number(-2.2250738585072014e-308, buf, sizeof buf);
    ck_assert_str_eq(buf, "-2.2250738585072014e-308");
    rugo_json_format_number(NAN, buf, sizeof buf);
    ck_assert_str_eq(buf, "nan");
    rugo_json_format_number(-INFINITY, buf, sizeof buf);
    ck_assert_str_eq(buf, "-inf");
    rugo_json_format_number(123.0, buf, 3); /* cut, still terminated */
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
    rugo_json_doc doc;
    rugo_json_error err;
    for (int i = 0; i < 20000; ++i) {
        double x = random_double(&r);
        char buf[40];
        int n = rugo_json_format_number(x, buf, sizeof buf);
        ck_assert_int_le(n, 24);
        ck_assert_int_eq(json_parse_n(buf, (size_t)n, &doc, &err), RUGO_OK);
        ck_assert_msg(bits_of(doc.root->u.number) == bits_of(x), "%s -> %.17g", buf, doc.root->u.number);
        rugo_json_doc_free(&doc);
    }
}
END_TEST

/* ------------------------------------------------------------------------------------------------ */
/* Shape descriptions */

START_TEST(shape_parse_valid) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    const char* t = "{\"name\": \"sq\", \"roughness\": {\"levels\": [1, 2, {\"x\": null}]},"
                    " \"control_points\": [[0, 0], [1, 0.5], [-1e-3, 2E2], [0, 1]], \"extra\": [[[]]]}";
    ck_assert_int_eq(shape_parse_n(t, strlen(t), &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 4);
    ck_assert_int_eq(desc.filter, RUGO_FILTER_DEFAULT);
    ck_assert(desc.control_points[1].y == 0.5);
    ck_assert(desc.control_points[2].x == -1e-3);
    ck_assert(desc.control_points[2].y == 200.0);
    ck_assert(desc.allocator.alloc != NULL);
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
    size_t length = 0;
    char* text = read_data("square4.json", &length);
    ck_assert_int_eq(rugo_shape_desc_parse(text, length, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 4);
    ck_assert(desc.control_points[0].x == -1.0 && desc.control_points[2].y == 1.0);
    rugo_shape_desc_free(&desc);
    rugo_text_free(NULL, text);
    text = read_data("star32.json", &length);
    ck_assert_int_eq(rugo_shape_desc_parse(text, length, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, 32);
    ck_assert_int_eq(desc.filter, RUGO_FILTER_CDF4_8);
    ck_assert(desc.control_points[0].x == 1.3);
    rugo_shape_desc_free(&desc);
    rugo_text_free(NULL, text);

    /* A custom allocator is recorded and used to free. */
    budget_ctx ctx = {1000, 0};
    rugo_allocator a = {budget_alloc, budget_free, &ctx};
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
    rugo_vec2* pts = (rugo_vec2*)1;
    int count = 7;
    ck_assert_int_eq(rugo_points_parse("{}", 2, NULL, NULL, &pts, &count, &err), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_ptr_null(pts);
    ck_assert_int_eq(count, 0);
    ck_assert_int_eq(rugo_points_parse("{}", 2, "points", NULL, NULL, &count, &err), RUGO_ERR_NULL_ARGUMENT);
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
    rugo_vec2* pts = NULL;
    int count = 0;
    ck_assert_int_eq(rugo_points_parse(t, n, "control_points", NULL, &pts, &count, &err),
                     RUGO_ERR_TOO_MANY_POINTS);
    free(t);
    t = points_text(RUGO_MAX_CONTROL_POINTS, &n);
    ck_assert_int_eq(rugo_shape_desc_parse(t, n, NULL, &desc, &err), RUGO_OK);
    ck_assert_int_eq(desc.count, RUGO_MAX_CONTROL_POINTS);
    ck_assert(desc.control_points[RUGO_MAX_CONTROL_POINTS - 1].y == 1.0);
    rugo_shape_desc_free(&desc);
    free(t);

    /* The writer refuses what the reader would. */
    rugo_shape_desc big = {NULL, RUGO_MAX_CONTROL_POINTS + 1, RUGO_FILTER_DEFAULT, rugo_default_allocator()};
    char* text = NULL;
    size_t len = 0;
    rugo_vec2 dummy = {0, 0};
    big.control_points = &dummy;
    ck_assert_int_eq(rugo_shape_desc_write(&big, NULL, &text, &len), RUGO_ERR_TOO_MANY_POINTS);
}
END_TEST

START_TEST(shape_max_size_file_fits) {
    /* The longest shape the writer can produce (2^20 points, every coordinate 24 characters) is within
     * RUGO_MAX_JSON_BYTES and reads back. */
    int n = RUGO_MAX_CONTROL_POINTS;
    rugo_vec2* pts = (rugo_vec2*)malloc(sizeof *pts * (size_t)n);
    for (int i = 0; i < n; ++i)
        pts[i] = rugo_v2(-2.2250738585072014e-308, -1.2345678901234567e-300);
    rugo_shape_desc desc = {pts, n, RUGO_FILTER_CDF4_12, rugo_default_allocator()};
    char* text = NULL;
    size_t len = 0;
    ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text, &len), RUGO_OK);
    ck_assert_uint_le(len, RUGO_MAX_JSON_BYTES);
    rugo_shape_desc back;
    rugo_parse_error err;
    ck_assert_int_eq(rugo_shape_desc_parse(text, len, NULL, &back, &err), RUGO_OK);
    ck_assert_int_eq(back.count, n);
    ck_assert(memcmp(back.control_points, pts, sizeof *pts * (size_t)n) == 0);
    rugo_shape_desc_free(&back);
    rugo_text_free(NULL, text);
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
        rugo_shape_desc desc = {pts, n, (rugo_filter)(test_rng_next(&r) % RUGO_FILTER_COUNT),
                                rugo_default_allocator()};
        char* text = NULL;
        size_t len = 0;
        ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text, &len), RUGO_OK);
        ck_assert_int_eq((int)strlen(text), (int)len);
        ck_assert_int_eq(text[len - 1], '\n');
        rugo_shape_desc back;
        rugo_parse_error err;
        ck_assert_msg(rugo_shape_desc_parse(text, len, NULL, &back, &err) == RUGO_OK, "%s at %d:%d",
                      err.message, err.line, err.column);
        ck_assert_int_eq(back.count, n);
        ck_assert_int_eq(back.filter, desc.filter);
        for (int i = 0; i < n; ++i) {
            ck_assert(bits_of(back.control_points[i].x) == bits_of(pts[i].x));
            ck_assert(bits_of(back.control_points[i].y) == bits_of(pts[i].y));
        }
        /* Writing again gives the same text. */
        char* text2 = NULL;
        size_t len2 = 0;
        ck_assert_int_eq(rugo_shape_desc_write(&back, NULL, &text2, &len2), RUGO_OK);
        ck_assert_int_eq((int)len2, (int)len);
        ck_assert(memcmp(text, text2, len) == 0);
        rugo_text_free(NULL, text2);
        rugo_shape_desc_free(&back);
        rugo_text_free(NULL, text);
    }
    /* The layout, once */
    rugo_vec2 two[2] = {{0.5, -0.0}, {1e300, 5e-324}};
    rugo_shape_desc d = {two, 2, RUGO_FILTER_CDF4_4, rugo_default_allocator()};
    char* text = NULL;
    size_t len = 0;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_OK);
    ck_assert_str_eq(text, "{\n  \"control_points\": [\n    [0.5, -0],\n    [1.0000000000000001e+300, "
                           "4.9406564584124654e-324]\n  ],\n  \"filter\": \"cdf4.4\"\n}\n");
    rugo_text_free(NULL, text);
    d.count = 0;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_OK);
    ck_assert_str_eq(text, "{\n  \"control_points\": [],\n  \"filter\": \"cdf4.4\"\n}\n");
    rugo_text_free(NULL, text);
}
END_TEST

START_TEST(shape_write_errors) {
    rugo_vec2 pts[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    rugo_shape_desc d = {pts, 4, RUGO_FILTER_DEFAULT, rugo_default_allocator()};
    char* text = (char*)1;
    size_t len = 5;
    pts[2].y = NAN;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_NOT_FINITE);
    ck_assert_ptr_null(text);
    ck_assert_int_eq((int)len, 0);
    pts[2].y = -INFINITY;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_NOT_FINITE);
    pts[2].y = 1.0;
    d.filter = RUGO_FILTER_COUNT;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_BAD_FILTER);
    d.filter = (rugo_filter)-1;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_BAD_FILTER);
    d.filter = RUGO_FILTER_DEFAULT;
    d.count = -1;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_BAD_ARGUMENT);
    d.count = 4;
    d.control_points = NULL;
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_ERR_NULL_ARGUMENT);
    d.control_points = pts;
    ck_assert_int_eq(rugo_shape_desc_write(NULL, NULL, &text, &len), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, NULL, &len), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_desc_write(&d, NULL, &text, &len), RUGO_OK);
    rugo_text_free(NULL, text);
    rugo_text_free(NULL, NULL);
}
END_TEST

START_TEST(points_parse_keys) {
    rugo_vec2* pts = NULL;
    int count = 0;
    rugo_parse_error err;
    size_t length = 0;
    char* text = read_data("circle64_points.json", &length);
    ck_assert_int_eq(rugo_points_parse(text, length, "points", NULL, &pts, &count, &err), RUGO_OK);
    ck_assert_int_eq(count, 64);
    ck_assert(pts[0].x == 2.0 && pts[0].y == 0.0);
    rugo_points_free(NULL, pts);
    ck_assert_int_eq(rugo_points_parse(text, length, "control_points", NULL, &pts, &count, &err),
                     RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "control_points");
    ck_assert_ptr_null(pts);
    rugo_text_free(NULL, text);
    text = read_data("star32.json", &length);
    ck_assert_int_eq(rugo_points_parse(text, length, "control_points", NULL, &pts, &count, &err), RUGO_OK);
    ck_assert_int_eq(count, 32);
    rugo_points_free(NULL, pts);
    rugo_text_free(NULL, text);
    const char* bad = "{\"points\": [[1, 2], [3, \"4\"]]}";
    char* buf = exact_copy(bad, strlen(bad));
    ck_assert_int_eq(rugo_points_parse(buf, strlen(bad), "points", NULL, &pts, &count, &err),
                     RUGO_ERR_BAD_FIELD);
    ck_assert_str_eq(err.path, "points[1][1]");
    ck_assert_ptr_null(pts);
    ck_assert_int_eq(count, 0);
    free(buf);
    ck_assert_int_eq(rugo_points_parse("{\"points\": [[1e999, 0]]}", 24, "points", NULL, &pts, &count, &err),
                     RUGO_ERR_NOT_FINITE);
    ck_assert_str_eq(err.path, "points[0][0]");
    rugo_points_free(NULL, NULL);
}
END_TEST

START_TEST(read_file_cases) {
    char path[1024];
    char* text = (char*)1;
    size_t len = 9;
    data_path("square4.json", path, sizeof path);
    ck_assert_int_eq(rugo_read_file(path, NULL, &text, &len), RUGO_OK);
    ck_assert_int_eq((int)strlen(text), (int)len);
    ck_assert_int_eq(strncmp(text, "{\n  \"control_points\"", 20), 0);
    rugo_text_free(NULL, text);

    data_path("no_such_file.json", path, sizeof path);
    ck_assert_int_eq(rugo_read_file(path, NULL, &text, &len), RUGO_ERR_IO);
    ck_assert_ptr_null(text);
    ck_assert_int_eq((int)len, 0);
    data_path("", path, sizeof path); /* the directory itself */
    ck_assert_int_eq(rugo_read_file(path, NULL, &text, &len), RUGO_ERR_IO);
    ck_assert_ptr_null(text);
    ck_assert_int_eq(rugo_read_file(NULL, NULL, &text, &len), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_read_file("x", NULL, NULL, &len), RUGO_ERR_NULL_ARGUMENT);

    /* Files that cannot tell their size are read in growing chunks. */
    FILE* probe = fopen("/proc/self/status", "rb");
    if (probe != NULL) {
        fclose(probe);
        ck_assert_int_eq(rugo_read_file("/proc/self/status", NULL, &text, &len), RUGO_OK);
        ck_assert_int_gt((int)len, 0);
        ck_assert_int_eq((int)strlen(text), (int)len);
        rugo_text_free(NULL, text);
    }

    /* Size limit: a sparse file of exactly the limit reads; one byte more is refused. */
    const char* big = "test_shape_file_big.tmp";
    FILE* f = fopen(big, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, (long)RUGO_MAX_JSON_BYTES - 1, SEEK_SET), 0);
    fputc(' ', f);
    fclose(f);
    ck_assert_int_eq(rugo_read_file(big, NULL, &text, &len), RUGO_OK);
    ck_assert(len == RUGO_MAX_JSON_BYTES);
    ck_assert_int_eq(text[len], '\0');
    rugo_text_free(NULL, text);
    f = fopen(big, "ab");
    fputc(' ', f);
    fclose(f);
    ck_assert_int_eq(rugo_read_file(big, NULL, &text, &len), RUGO_ERR_PARSE);
    ck_assert_ptr_null(text);
    remove(big);

    /* Allocation failures while reading */
    data_path("star32.json", path, sizeof path);
    for (long budget = 0;; ++budget) {
        budget_ctx ctx = {budget, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_status st = rugo_read_file(path, &a, &text, &len);
        if (st == RUGO_OK) {
            rugo_text_free(&a, text);
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
                      st == RUGO_ERR_TOO_MANY_POINTS,
                  "status %d for input <%.*s>", (int)st, (int)n, input);
    ck_assert(str_nul_terminated(err->path, sizeof err->path));
    ck_assert(str_nul_terminated(err->message, sizeof err->message));
    if (st == RUGO_OK) {
        ck_assert(desc->count >= 0);
        ck_assert((int)desc->filter >= 0 && desc->filter < RUGO_FILTER_COUNT);
        for (int i = 0; i < desc->count; ++i)
            ck_assert(isfinite(desc->control_points[i].x) && isfinite(desc->control_points[i].y));
    } else {
        ck_assert_ptr_null(desc->control_points);
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
    size_t len_star = 0;
    char* star = read_data("star32.json", &len_star);
    const char* seeds[] = {
        star,
        "{\"control_points\": [[0, 0], [1, 0], [1, 1], [0, 1]], \"filter\": \"cdf4.2\"}",
        "{\"name\": \"x\\u00e9\\ud83d\\ude00\", \"control_points\": [[-1.5e-3, 2E+2], [0.25, -0]], \"r\": "
        "{\"a\": [true, "
        "false, null]}}",
        "{\"points\": [[1, 2], [3, 4]], \"control_points\": [], \"filter\": \"cdf4.12\"}",
    };
    size_t seed_len[4];
    for (int i = 0; i < 4; ++i)
        seed_len[i] = strlen(seeds[i]);
    enum { CAP = 4096 };
    char work[CAP];
    test_rng r = test_rng_seed(0xf022);
    int counts[RUGO_STATUS_COUNT] = {0};
    for (int iter = 0; iter < 30000; ++iter) {
        int s = (int)(test_rng_next(&r) % 4);
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
            char* text = NULL;
            size_t len = 0;
            ck_assert_int_eq(rugo_shape_desc_write(&desc, NULL, &text, &len), RUGO_OK);
            rugo_shape_desc back;
            ck_assert_int_eq(rugo_shape_desc_parse(text, len, NULL, &back, &err), RUGO_OK);
            ck_assert_int_eq(back.count, desc.count);
            ck_assert(desc.count == 0 || memcmp(back.control_points, desc.control_points,
                                                sizeof(rugo_vec2) * (size_t)desc.count) == 0);
            rugo_shape_desc_free(&back);
            rugo_text_free(NULL, text);
        } else if (iter % 16 == 0) {
            /* Deterministic: the same input gives the same error, byte for byte. */
            rugo_parse_error err2;
            rugo_shape_desc d2;
            ck_assert_int_eq(rugo_shape_desc_parse(input, n, NULL, &d2, &err2), st);
            ck_assert(memcmp(&err, &err2, sizeof err) == 0);
        }
        rugo_shape_desc_free(&desc);
        /* The other entry points on the same bytes */
        rugo_vec2* pts = NULL;
        int count = 0;
        st = rugo_points_parse(input, n, "points", NULL, &pts, &count, &err);
        ck_assert(st == RUGO_OK || st == RUGO_ERR_PARSE || st == RUGO_ERR_BAD_FIELD ||
                  st == RUGO_ERR_NOT_FINITE);
        rugo_points_free(NULL, pts);
        free(input);
    }
    /* The mutations reach every kind of outcome. */
    ck_assert_int_gt(counts[RUGO_OK], 100);
    ck_assert_int_gt(counts[RUGO_ERR_PARSE], 100);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_FIELD], 100);
    ck_assert_int_gt(counts[RUGO_ERR_NOT_FINITE], 10);
    ck_assert_int_gt(counts[RUGO_ERR_BAD_FILTER], 10);
    rugo_text_free(NULL, star);
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
        rugo_json_doc doc;
        rugo_json_error err;
        rugo_status st = json_parse_n(work, n, &doc, &err);
        ck_assert(st == RUGO_OK || st == RUGO_ERR_PARSE || st == RUGO_ERR_NOT_FINITE); /* "1e5" "1" -> 1e51 */
        if (st == RUGO_OK) {
            ++ok;
            ck_assert_ptr_nonnull(doc.root);
        } else {
            ck_assert(err.message[0] != '\0');
            ck_assert(err.offset <= n);
        }
        rugo_json_doc_free(&doc);
    }
    ck_assert_int_gt(ok, 100);
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

    TCase* fuzz = tcase_create("fuzz");
    tcase_set_timeout(fuzz, 600);
    tcase_add_test(fuzz, fuzz_mutations);
    tcase_add_test(fuzz, fuzz_token_soup);
    suite_add_tcase(s, fuzz);
    return test_run_suite(s);
}
