/* Shape description files (JSON: control points, filter, roughness) and JSON point lists read: strict,
 * with errors that name the offending value (rugo_shape_desc_parse, rugo_points_parse). */
#include "rugo/shape_file.h"

#include "core/internal.h"
#include "io/json.h"
#include "rough/internal.h" /* the checks of ranges and profiles */

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void clear_error(rugo_parse_error* e) {
    if (e != NULL) memset(e, 0, sizeof *e);
}

/* An error about a well-formed value: position from the value's offset in the text. */
#if defined(__GNUC__)
__attribute__((format(printf, 6, 7)))
#endif
static rugo_status
field_error(rugo_parse_error* e, rugo_status status, const char* text, size_t length,
            const rugo__json_value* at, const char* fmt, ...) {
    if (e == NULL) return status;
    if (at != NULL) rugo__json_locate(text, length, at->offset, &e->line, &e->column);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return status;
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void
set_path(rugo_parse_error* e, const char* fmt, ...) {
    if (e == NULL) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->path, sizeof e->path, fmt, ap);
    va_end(ap);
}

static void copy_json_error(rugo_parse_error* e, const rugo__json_error* je) {
    if (e == NULL) return;
    e->line = je->line;
    e->column = je->column;
    memcpy(e->path, je->path, sizeof e->path < sizeof je->path ? sizeof e->path : sizeof je->path);
    e->path[sizeof e->path - 1] = '\0';
    memcpy(e->message, je->message,
           sizeof e->message < sizeof je->message ? sizeof e->message : sizeof je->message);
    e->message[sizeof e->message - 1] = '\0';
}

/* "a number", "an array", "null", ... for "found ..." messages. */
static const char* a_type(rugo__json_type t) {
    switch (t) {
    case RUGO__JSON_NULL:
        return "null";
    case RUGO__JSON_BOOL:
        return "a boolean";
    case RUGO__JSON_NUMBER:
        return "a number";
    case RUGO__JSON_STRING:
        return "a string";
    case RUGO__JSON_ARRAY:
        return "an array";
    case RUGO__JSON_OBJECT:
        return "an object";
    }
    return "a value";
}

/* The JSON member `key` of the top-level object, which must occur exactly once unless optional. */
static rugo_status find_member(const rugo__json_doc* doc, const char* text, size_t length, const char* key,
                               int optional, const rugo__json_value** out, rugo_parse_error* e) {
    const rugo__json_value* root = doc->root;
    *out = NULL;
    if (root->type != RUGO__JSON_OBJECT)
        return field_error(e, RUGO_ERR_BAD_FIELD, text, length, root,
                           "expected a JSON object at the top level, found %s", a_type(root->type));
    int matches = 0;
    const rugo__json_value* v = rugo__json_object_get(root, key, &matches);
    if (matches > 1) {
        set_path(e, "%s", key);
        return field_error(e, RUGO_ERR_BAD_FIELD, text, length, v, "field \"%s\" appears %d times", key,
                           matches);
    }
    if (v == NULL && !optional) {
        set_path(e, "%s", key);
        return field_error(e, RUGO_ERR_BAD_FIELD, text, length, root, "missing field \"%s\"", key);
    }
    *out = v;
    return RUGO_OK;
}

/* Reads an array of [x, y] pairs into a new point array (NULL when empty). */
static rugo_status read_points(const rugo__json_value* arr, const char* key, const char* text, size_t length,
                               const rugo_allocator* allocator, rugo_vec2** points, int* count,
                               rugo_parse_error* e) {
    *points = NULL;
    *count = 0;
    if (arr->type != RUGO__JSON_ARRAY) {
        set_path(e, "%s", key);
        return field_error(e, RUGO_ERR_BAD_FIELD, text, length, arr,
                           "expected an array of [x, y] pairs, found %s", a_type(arr->type));
    }
    if (arr->count > (uint32_t)RUGO_MAX_CONTROL_POINTS) {
        set_path(e, "%s", key);
        return field_error(e, RUGO_ERR_TOO_MANY_POINTS, text, length, arr,
                           "%lu points; at most %d are allowed", (unsigned long)arr->count,
                           RUGO_MAX_CONTROL_POINTS);
    }
    int n = (int)arr->count;
    rugo_vec2* pts = NULL;
    if (n > 0) {
        pts = (rugo_vec2*)rugo__alloc_array(allocator, (size_t)n, sizeof *pts);
        if (pts == NULL) return field_error(e, RUGO_ERR_OUT_OF_MEMORY, text, length, NULL, "out of memory");
    }
    int i = 0;
    for (const rugo__json_value* p = arr->u.first; p != NULL; p = p->next, ++i) {
        rugo_status s = RUGO_OK;
        if (p->type != RUGO__JSON_ARRAY) {
            set_path(e, "%s[%d]", key, i);
            s = field_error(e, RUGO_ERR_BAD_FIELD, text, length, p, "expected an [x, y] pair, found %s",
                            a_type(p->type));
        } else if (p->count != 2) {
            set_path(e, "%s[%d]", key, i);
            s = field_error(e, RUGO_ERR_BAD_FIELD, text, length, p,
                            "expected an [x, y] pair, found an array of %lu element%s",
                            (unsigned long)p->count, p->count == 1 ? "" : "s");
        } else {
            const rugo__json_value* c = p->u.first;
            for (int j = 0; j < 2 && s == RUGO_OK; ++j, c = c->next) {
                if (c->type != RUGO__JSON_NUMBER) {
                    set_path(e, "%s[%d][%d]", key, i, j);
                    s = field_error(e, RUGO_ERR_BAD_FIELD, text, length, c, "expected a number, found %s",
                                    a_type(c->type));
                } else if (!isfinite(c->u.number)) {
                    /* The reader refuses these already; kept so that this function stands on its own. */
                    set_path(e, "%s[%d][%d]", key, i, j);
                    s = field_error(e, RUGO_ERR_NOT_FINITE, text, length, c, "coordinate is not finite");
                }
            }
            if (s == RUGO_OK) {
                pts[i].x = p->u.first->u.number;
                pts[i].y = p->u.first->next->u.number;
            }
        }
        if (s != RUGO_OK) {
            rugo__free(allocator, pts);
            return s;
        }
    }
    RUGO_ASSERT(i == n);
    *points = pts;
    *count = n;
    return RUGO_OK;
}

static rugo_status parse_doc(const char* text, size_t length, const rugo_allocator* allocator,
                             rugo__json_doc* doc, rugo_parse_error* e) {
    rugo__json_error je;
    rugo_status s = rugo__json_parse(text, length, allocator, NULL, doc, &je);
    if (s != RUGO_OK) copy_json_error(e, &je);
    return s;
}

rugo_status rugo_points_parse(const char* text, size_t length, const char* key,
                              const rugo_allocator* allocator, rugo_point_list* out,
                              rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || key == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    rugo__json_doc doc;
    rugo_status s = parse_doc(text, length, allocator, &doc, error);
    if (s != RUGO_OK) return s;
    const rugo__json_value* arr = NULL;
    rugo_vec2* points = NULL;
    int count = 0;
    s = find_member(&doc, text, length, key, 0, &arr, error);
    if (s == RUGO_OK) s = read_points(arr, key, text, length, allocator, &points, &count, error);
    rugo__json_doc_free(&doc);
    if (s == RUGO_OK) {
        out->points = points;
        out->count = count;
        out->allocator = rugo__allocator_or_default(allocator);
    }
    return s;
}

void rugo_point_list_free(rugo_point_list* list) {
    if (list == NULL) return;
    rugo__free(&list->allocator, list->points);
    memset(list, 0, sizeof *list);
}

static void filter_list(char* out, size_t size) {
    size_t len = 0;
    out[0] = '\0';
    for (int f = 0; f < RUGO_FILTER_COUNT; ++f) {
        const char* name = rugo_filter_name((rugo_filter)f);
        if (name == NULL) continue;
        int n = snprintf(out + len, size - len, "%s%s", len > 0 ? ", " : "", name);
        if (n < 0 || (size_t)n >= size - len) break;
        len += (size_t)n;
    }
}

/* ---- roughness ------------------------------------------------------------------------------ */

rugo_roughness_desc rugo_default_roughness_desc(void) {
    rugo_roughness_desc r;
    memset(&r, 0, sizeof r);
    r.kind = RUGO_ROUGHNESS_PRESET;
    r.preset = RUGO_PRESET_TIPO_1;
    r.seed = 0;
    r.q = RUGO_DEFAULT_Q;
    r.estimator = RUGO_ESTIMATOR_DETAIL;
    r.friction = rugo_default_friction_map();
    r.restitution = rugo_default_restitution();
    r.has_perturbation = false;
    r.perturbation_method = RUGO_ROUGHEN_WAVELET;
    return r;
}

static void free_roughness(const rugo_allocator* al, rugo_roughness_desc* r) {
    rugo__free(al, r->tolerances);
    rugo__free(al, r->perturbation_points);
    rugo__free(al, r->ranges);
    rugo__free(al, r->profile);
    r->tolerances = NULL;
    r->tolerance_count = 0;
    r->perturbation_points = NULL;
    r->perturbation_count = 0;
    r->ranges = NULL;
    r->range_count = 0;
    r->profile = NULL;
    r->profile_count = 0;
}

/* Everything a roughness reader needs to report errors. */
typedef struct rctx {
    const char* text;
    size_t length;
    const rugo_allocator* al;
    rugo_parse_error* e;
} rctx;

/* Member `key` of object `obj` (whose path is `prefix`), NULL if absent; a repeated member is
 * BAD_FIELD. */
static rugo_status member(const rctx* c, const rugo__json_value* obj, const char* prefix, const char* key,
                          const rugo__json_value** out) {
    int matches = 0;
    *out = rugo__json_object_get(obj, key, &matches);
    if (matches > 1) {
        set_path(c->e, "%s.%s", prefix, key);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, *out,
                           "field \"%s\" appears %d times", key, matches);
    }
    return RUGO_OK;
}

/* BAD_FIELD unless v has type t; `what` describes the expected value ("a number", ...). */
static rugo_status want_type(const rctx* c, const rugo__json_value* v, rugo__json_type t, const char* path,
                             const char* what) {
    if (v->type == t) return RUGO_OK;
    set_path(c->e, "%s", path);
    return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "expected %s, found %s", what,
                       a_type(v->type));
}

static rugo_status number_member(const rctx* c, const rugo__json_value* obj, const char* prefix,
                                 const char* key, rugo_real* out) {
    const rugo__json_value* v = NULL;
    rugo_status s = member(c, obj, prefix, key, &v);
    if (s != RUGO_OK || v == NULL) return s;
    char path[64];
    snprintf(path, sizeof path, "%s.%s", prefix, key);
    s = want_type(c, v, RUGO__JSON_NUMBER, path, "a number");
    if (s != RUGO_OK) return s;
    if (!isfinite(v->u.number)) { /* the reader refuses these already */
        set_path(c->e, "%s", path);
        return field_error(c->e, RUGO_ERR_NOT_FINITE, c->text, c->length, v, "value is not finite");
    }
    *out = v->u.number;
    return RUGO_OK;
}

/* A string member matched against names[0..count) (exact bytes; an embedded NUL never matches).
 * Unknown names are BAD_FIELD with the list of valid ones. *present tells whether it was there. */
static rugo_status name_member(const rctx* c, const rugo__json_value* obj, const char* prefix,
                               const char* key, const char* const* names, int count, int* index,
                               int* present) {
    const rugo__json_value* v = NULL;
    *present = 0;
    rugo_status s = member(c, obj, prefix, key, &v);
    if (s != RUGO_OK || v == NULL) return s;
    *present = 1;
    char path[64];
    snprintf(path, sizeof path, "%s.%s", prefix, key);
    s = want_type(c, v, RUGO__JSON_STRING, path, "a name string");
    if (s != RUGO_OK) return s;
    for (int i = 0; i < count; ++i)
        if (strlen(v->u.string) == v->count && strcmp(v->u.string, names[i]) == 0) {
            *index = i;
            return RUGO_OK;
        }
    char quoted[48], list[96];
    size_t len = 0;
    list[0] = '\0';
    for (int i = 0; i < count; ++i) {
        int n = snprintf(list + len, sizeof list - len, "%s%s", i > 0 ? ", " : "", names[i]);
        if (n < 0 || (size_t)n >= sizeof list - len) break;
        len += (size_t)n;
    }
    rugo__json_quote_for_message(v->u.string, v->count, quoted, sizeof quoted);
    set_path(c->e, "%s", path);
    return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v,
                       "unknown %s \"%s\" (expected one of %s)", key, quoted, list);
}

/* The seed: an integer in plain digits, 0..RUGO_MAX_FILE_SEED. Read from the text itself, because a
 * double cannot tell 9007199254740993 from 2^53 or 1e3 from 1000. */
static rugo_status seed_value(const rctx* c, const rugo__json_value* v, uint64_t* out) {
    rugo_status s = want_type(c, v, RUGO__JSON_NUMBER, "roughness.seed", "an integer");
    if (s != RUGO_OK) return s;
    size_t i = v->offset;
    uint64_t x = 0;
    int digits = 0, too_big = 0;
    while (i < c->length && c->text[i] >= '0' && c->text[i] <= '9') {
        uint64_t d = (uint64_t)(c->text[i] - '0');
        if (x > (RUGO_MAX_FILE_SEED - d) / 10)
            too_big = 1;
        else
            x = x * 10 + d;
        ++digits;
        ++i;
    }
    int plain =
        digits > 0 && !(i < c->length && (c->text[i] == '.' || c->text[i] == 'e' || c->text[i] == 'E'));
    set_path(c->e, "roughness.seed");
    if (!plain)
        return field_error(
            c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v,
            "the seed must be a non-negative integer written in digits, without sign, fraction or "
            "exponent");
    if (too_big)
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v,
                           "the seed exceeds 2^53 = 9007199254740992");
    RUGO_ASSERT((double)x == v->u.number);
    if (c->e != NULL) c->e->path[0] = '\0';
    *out = x;
    return RUGO_OK;
}

/* "ranges": an array of {"from", "to", "tolerance"} objects (unknown members ignored). */
static rugo_status read_ranges(const rctx* c, const rugo__json_value* arr, rugo_roughness_desc* r) {
    rugo_status s = want_type(c, arr, RUGO__JSON_ARRAY, "roughness.ranges",
                              "an array of {\"from\", \"to\", \"tolerance\"} objects");
    if (s != RUGO_OK) return s;
    if (arr->count > (uint32_t)RUGO_MAX_ROUGHNESS_RANGES) {
        set_path(c->e, "roughness.ranges");
        return field_error(c->e, RUGO_ERR_TOO_MANY_POINTS, c->text, c->length, arr,
                           "%lu ranges; at most %d are allowed", (unsigned long)arr->count,
                           RUGO_MAX_ROUGHNESS_RANGES);
    }
    int m = (int)arr->count;
    rugo_roughness_range* g = NULL;
    if (m > 0) {
        g = (rugo_roughness_range*)rugo__alloc_array(c->al, (size_t)m, sizeof *g);
        if (g == NULL)
            return field_error(c->e, RUGO_ERR_OUT_OF_MEMORY, c->text, c->length, NULL, "out of memory");
    }
    static const char* const names[3] = {"from", "to", "tolerance"};
    int i = 0;
    for (const rugo__json_value* x = arr->u.first; x != NULL && s == RUGO_OK; x = x->next, ++i) {
        char prefix[48];
        snprintf(prefix, sizeof prefix, "roughness.ranges[%d]", i);
        s = want_type(c, x, RUGO__JSON_OBJECT, prefix, "a range {\"from\", \"to\", \"tolerance\"}");
        rugo_real v[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < 3 && s == RUGO_OK; ++k) {
            const rugo__json_value* mv = NULL;
            s = member(c, x, prefix, names[k], &mv);
            if (s == RUGO_OK && mv == NULL) {
                set_path(c->e, "%s.%s", prefix, names[k]);
                s = field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, x, "missing field \"%s\"",
                                names[k]);
            }
            if (s == RUGO_OK) s = number_member(c, x, prefix, names[k], &v[k]);
        }
        if (s != RUGO_OK) break;
        g[i].from = v[0];
        g[i].to = v[1];
        g[i].tolerance = v[2];
        char msg[160];
        int which = -1;
        s = rugo__roughness_range_check(&g[i], &which, msg, sizeof msg);
        if (s != RUGO_OK) {
            const rugo__json_value* at = x;
            if (which >= 0) {
                member(c, x, prefix, names[which], &at);
                set_path(c->e, "%s.%s", prefix, names[which]);
            } else {
                set_path(c->e, "%s", prefix);
            }
            s = field_error(c->e, s, c->text, c->length, at, "%s", msg);
        }
    }
    if (s != RUGO_OK) {
        rugo__free(c->al, g);
        return s;
    }
    r->kind = RUGO_ROUGHNESS_RANGES;
    r->ranges = g;
    r->range_count = m;
    return RUGO_OK;
}

/* "profile": an array of [s, tolerance] pairs. */
static rugo_status read_profile(const rctx* c, const rugo__json_value* arr, rugo_roughness_desc* r) {
    rugo_status s =
        want_type(c, arr, RUGO__JSON_ARRAY, "roughness.profile", "an array of [s, tolerance] pairs");
    if (s != RUGO_OK) return s;
    if (arr->count > (uint32_t)RUGO_MAX_PROFILE_SAMPLES) {
        set_path(c->e, "roughness.profile");
        return field_error(c->e, RUGO_ERR_TOO_MANY_POINTS, c->text, c->length, arr,
                           "%lu samples; at most %d are allowed", (unsigned long)arr->count,
                           RUGO_MAX_PROFILE_SAMPLES);
    }
    if (arr->count == 0) {
        set_path(c->e, "roughness.profile");
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, arr,
                           "a profile needs at least one [s, tolerance] sample");
    }
    int m = (int)arr->count;
    rugo_profile_sample* p = (rugo_profile_sample*)rugo__alloc_array(c->al, (size_t)m, sizeof *p);
    if (p == NULL)
        return field_error(c->e, RUGO_ERR_OUT_OF_MEMORY, c->text, c->length, NULL, "out of memory");
    int i = 0;
    for (const rugo__json_value* x = arr->u.first; x != NULL && s == RUGO_OK; x = x->next, ++i) {
        if (x->type != RUGO__JSON_ARRAY || x->count != 2) {
            set_path(c->e, "roughness.profile[%d]", i);
            if (x->type != RUGO__JSON_ARRAY)
                s = field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, x,
                                "expected an [s, tolerance] pair, found %s", a_type(x->type));
            else
                s = field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, x,
                                "expected an [s, tolerance] pair, found an array of %lu element%s",
                                (unsigned long)x->count, x->count == 1 ? "" : "s");
            break;
        }
        const rugo__json_value* e2[2] = {x->u.first, x->u.first->next};
        for (int k = 0; k < 2 && s == RUGO_OK; ++k)
            if (e2[k]->type != RUGO__JSON_NUMBER) {
                set_path(c->e, "roughness.profile[%d][%d]", i, k);
                s = field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, e2[k],
                                "expected a number, found %s", a_type(e2[k]->type));
            }
        if (s != RUGO_OK) break;
        p[i].s = e2[0]->u.number;
        p[i].tolerance = e2[1]->u.number;
        char msg[160];
        int column = 0;
        s = rugo__roughness_sample_check(i > 0 ? &p[i - 1] : NULL, &p[i], &column, msg, sizeof msg);
        if (s != RUGO_OK) {
            set_path(c->e, "roughness.profile[%d][%d]", i, column);
            s = field_error(c->e, s, c->text, c->length, e2[column], "%s", msg);
        }
    }
    if (s != RUGO_OK) {
        rugo__free(c->al, p);
        return s;
    }
    r->kind = RUGO_ROUGHNESS_PROFILE;
    r->profile = p;
    r->profile_count = m;
    return RUGO_OK;
}

/* The finest tolerances: exactly one of "preset", "tolerances", "constant", "ranges", "profile". */
static rugo_status read_tolerance_source(const rctx* c, const rugo__json_value* obj, int n,
                                         rugo_roughness_desc* r) {
    static const char* const keys[5] = {"preset", "tolerances", "constant", "ranges", "profile"};
    const rugo__json_value* v[5];
    int found = 0, first = -1, second = -1;
    for (int k = 0; k < 5; ++k) {
        rugo_status s = member(c, obj, "roughness", keys[k], &v[k]);
        if (s != RUGO_OK) return s;
        if (v[k] != NULL) {
            if (first < 0)
                first = k;
            else if (second < 0)
                second = k;
            ++found;
        }
    }
    if (found != 1) {
        set_path(c->e, "roughness");
        if (found == 0)
            return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, obj,
                               "roughness needs one of \"preset\", \"tolerances\", \"constant\", "
                               "\"ranges\" or \"profile\"");
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v[second],
                           "roughness takes only one of \"preset\", \"tolerances\", \"constant\", "
                           "\"ranges\" or \"profile\" (found \"%s\" and \"%s\")",
                           keys[first], keys[second]);
    }
    if (first == 3) return read_ranges(c, v[3], r);
    if (first == 4) return read_profile(c, v[4], r);
    if (first == 0) {
        const char* names[RUGO_PRESET_COUNT];
        for (int p = 0; p < RUGO_PRESET_COUNT; ++p) {
            names[p] = rugo_preset_name((rugo_tolerance_preset)p);
            if (names[p] == NULL) names[p] = "?";
        }
        int index = 0, present = 0;
        rugo_status s =
            name_member(c, obj, "roughness", "preset", names, RUGO_PRESET_COUNT, &index, &present);
        if (s != RUGO_OK) return s;
        r->kind = RUGO_ROUGHNESS_PRESET;
        r->preset = (rugo_tolerance_preset)index;
        return RUGO_OK;
    }
    if (first == 2) {
        rugo_real x = 0.0;
        rugo_status s = number_member(c, obj, "roughness", "constant", &x);
        if (s != RUGO_OK) return s;
        s = rugo_tolerances_check(&x, 1, NULL);
        if (s != RUGO_OK) {
            set_path(c->e, "roughness.constant");
            return field_error(c->e, s, c->text, c->length, v[2], "invalid tolerance %.17g: %s", x,
                               rugo_status_string(s));
        }
        r->kind = RUGO_ROUGHNESS_CONSTANT;
        r->constant = x;
        return RUGO_OK;
    }
    const rugo__json_value* arr = v[1];
    rugo_status s = want_type(c, arr, RUGO__JSON_ARRAY, "roughness.tolerances", "an array of tolerances");
    if (s != RUGO_OK) return s;
    if ((long)arr->count != (long)n) {
        set_path(c->e, "roughness.tolerances");
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, arr,
                           "%lu tolerances for %d control points (one per segment)",
                           (unsigned long)arr->count, n);
    }
    rugo_real* vals = NULL;
    if (n > 0) {
        vals = (rugo_real*)rugo__alloc_array(c->al, (size_t)n, sizeof *vals);
        if (vals == NULL)
            return field_error(c->e, RUGO_ERR_OUT_OF_MEMORY, c->text, c->length, NULL, "out of memory");
    }
    int i = 0;
    for (const rugo__json_value* x = arr->u.first; x != NULL; x = x->next, ++i) {
        if (x->type != RUGO__JSON_NUMBER) {
            set_path(c->e, "roughness.tolerances[%d]", i);
            s = field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, x, "expected a number, found %s",
                            a_type(x->type));
        } else {
            vals[i] = x->u.number;
            s = rugo_tolerances_check(&vals[i], 1, NULL);
            if (s != RUGO_OK) {
                set_path(c->e, "roughness.tolerances[%d]", i);
                s = field_error(c->e, s, c->text, c->length, x, "invalid tolerance %.17g: %s", vals[i],
                                rugo_status_string(s));
            }
        }
        if (s != RUGO_OK) {
            rugo__free(c->al, vals);
            return s;
        }
    }
    r->kind = RUGO_ROUGHNESS_TOLERANCES;
    r->tolerances = vals;
    r->tolerance_count = n;
    return RUGO_OK;
}

static rugo_status read_friction(const rctx* c, const rugo__json_value* obj, rugo_roughness_desc* r) {
    const rugo__json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "friction", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO__JSON_OBJECT, "roughness.friction",
                  "an object {\"alpha\", \"lambda_min\", \"base\"}");
    if (s == RUGO_OK) s = number_member(c, v, "roughness.friction", "alpha", &r->friction.alpha);
    if (s == RUGO_OK) s = number_member(c, v, "roughness.friction", "lambda_min", &r->friction.lambda_min);
    if (s == RUGO_OK) s = number_member(c, v, "roughness.friction", "base", &r->friction.base);
    if (s != RUGO_OK) return s;
    s = rugo_friction_map_check(&r->friction);
    if (s != RUGO_OK) {
        set_path(c->e, "roughness.friction");
        return field_error(
            c->e, s, c->text, c->length, v,
            "invalid friction map (alpha %.17g, lambda_min %.17g, base %.17g): %s; alpha, lambda_min "
            "and base must be >= 0",
            r->friction.alpha, r->friction.lambda_min, r->friction.base, rugo_status_string(s));
    }
    return RUGO_OK;
}

static rugo_status read_restitution(const rctx* c, const rugo__json_value* obj, rugo_roughness_desc* r) {
    const rugo__json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "restitution", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO__JSON_OBJECT, "roughness.restitution",
                  "an object {\"epsilon\", \"epsilon_max\"}");
    if (s == RUGO_OK) s = number_member(c, v, "roughness.restitution", "epsilon", &r->restitution.epsilon);
    if (s == RUGO_OK)
        s = number_member(c, v, "roughness.restitution", "epsilon_max", &r->restitution.epsilon_max);
    if (s != RUGO_OK) return s;
    s = rugo_restitution_check(&r->restitution);
    if (s != RUGO_OK) {
        set_path(c->e, "roughness.restitution");
        return field_error(c->e, s, c->text, c->length, v,
                           "invalid restitution (epsilon %.17g, epsilon_max %.17g): %s; need 0 <= epsilon <= "
                           "epsilon_max <= 1",
                           r->restitution.epsilon, r->restitution.epsilon_max, rugo_status_string(s));
    }
    return RUGO_OK;
}

static rugo_status read_perturbation(const rctx* c, const rugo__json_value* obj, int n,
                                     rugo_roughness_desc* r) {
    static const char* const prefix = "roughness.perturbation";
    const rugo__json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "perturbation", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO__JSON_OBJECT, prefix, "an object {\"method\", \"levels\", \"control_points\"}");
    if (s != RUGO_OK) return s;
    static const char* const methods[2] = {"wavelet", "local"};
    int index = 0, present = 0;
    s = name_member(c, v, prefix, "method", methods, 2, &index, &present);
    if (s != RUGO_OK) return s;
    if (!present) {
        set_path(c->e, "%s.method", prefix);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "missing field \"method\"");
    }
    const rugo__json_value* lv = NULL;
    if ((s = member(c, v, prefix, "levels", &lv)) != RUGO_OK) return s;
    if (lv == NULL || lv->type != RUGO__JSON_NUMBER || !(lv->u.number >= 1.0) ||
        !(lv->u.number <= (double)RUGO_MAX_PERTURBATION_LEVELS) || lv->u.number != floor(lv->u.number)) {
        set_path(c->e, "%s.levels", prefix);
        if (lv == NULL)
            return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "missing field \"levels\"");
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, lv,
                           "expected an integer from 1 to %d", RUGO_MAX_PERTURBATION_LEVELS);
    }
    int levels = (int)lv->u.number;
    const rugo__json_value* cp = NULL;
    if ((s = member(c, v, prefix, "control_points", &cp)) != RUGO_OK) return s;
    if (cp == NULL) {
        set_path(c->e, "%s.control_points", prefix);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v,
                           "missing field \"control_points\"");
    }
    rugo_vec2* pts = NULL;
    int count = 0;
    s = read_points(cp, "roughness.perturbation.control_points", c->text, c->length, c->al, &pts, &count,
                    c->e);
    if (s != RUGO_OK) return s;
    if ((long long)count != (long long)n << levels) {
        rugo__free(c->al, pts);
        set_path(c->e, "%s.control_points", prefix);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, cp,
                           "%d control points; %d levels above %d control points need %lld", count, levels, n,
                           (long long)n << levels);
    }
    r->has_perturbation = true;
    r->perturbation_method = (rugo_roughen_method)index;
    r->perturbation_levels = levels;
    r->perturbation_points = pts;
    r->perturbation_count = count;
    return RUGO_OK;
}

/* The "roughness" member of a shape with n control points into *r (arrays allocated with c->al). */
static rugo_status read_roughness(const rctx* c, const rugo__json_value* obj, int n, rugo_roughness_desc* r) {
    *r = rugo_default_roughness_desc();
    rugo_status s = want_type(c, obj, RUGO__JSON_OBJECT, "roughness", "a roughness object");
    if (s == RUGO_OK) s = read_tolerance_source(c, obj, n, r);
    const rugo__json_value* v = NULL;
    if (s == RUGO_OK && r->kind == RUGO_ROUGHNESS_RANGES) {
        s = number_member(c, obj, "roughness", "background", &r->background);
        if (s == RUGO_OK && (s = rugo_tolerances_check(&r->background, 1, NULL)) != RUGO_OK) {
            member(c, obj, "roughness", "background", &v);
            set_path(c->e, "roughness.background");
            s = field_error(c->e, s, c->text, c->length, v, "invalid tolerance %.17g: %s", r->background,
                            rugo_status_string(s));
        }
    }
    if (s == RUGO_OK) s = member(c, obj, "roughness", "seed", &v);
    if (s == RUGO_OK && v != NULL) s = seed_value(c, v, &r->seed);
    if (s == RUGO_OK) s = number_member(c, obj, "roughness", "q", &r->q);
    if (s == RUGO_OK && !(r->q > 0.0 && isfinite(r->q))) {
        member(c, obj, "roughness", "q", &v);
        set_path(c->e, "roughness.q");
        s = field_error(c->e, RUGO_ERR_BAD_QUANTILE, c->text, c->length, v,
                        "the band factor q must be > 0, found %.17g", r->q);
    }
    if (s == RUGO_OK) {
        static const char* const names[2] = {"coefficients", "detail"};
        int index = 0, present = 0;
        s = name_member(c, obj, "roughness", "estimator", names, 2, &index, &present);
        if (s == RUGO_OK && present)
            r->estimator = index == 0 ? RUGO_ESTIMATOR_COEFFICIENTS : RUGO_ESTIMATOR_DETAIL;
    }
    if (s == RUGO_OK) s = read_friction(c, obj, r);
    if (s == RUGO_OK) s = read_restitution(c, obj, r);
    if (s == RUGO_OK) s = read_perturbation(c, obj, n, r);
    if (s != RUGO_OK) free_roughness(c->al, r);
    return s;
}

rugo_status rugo_shape_desc_parse(const char* text, size_t length, const rugo_allocator* allocator,
                                  rugo_shape_desc* out, rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo__json_doc doc;
    rugo_status s = parse_doc(text, length, &al, &doc, error);
    if (s != RUGO_OK) return s;

    const rugo__json_value* cp = NULL;
    const rugo__json_value* fv = NULL;
    rugo_vec2* points = NULL;
    int count = 0;
    rugo_filter filter = RUGO_FILTER_DEFAULT;
    s = find_member(&doc, text, length, "control_points", 0, &cp, error);
    if (s == RUGO_OK) s = read_points(cp, "control_points", text, length, &al, &points, &count, error);
    if (s == RUGO_OK) s = find_member(&doc, text, length, "filter", 1, &fv, error);
    if (s == RUGO_OK && fv != NULL) {
        if (fv->type != RUGO__JSON_STRING) {
            set_path(error, "filter");
            s = field_error(error, RUGO_ERR_BAD_FIELD, text, length, fv,
                            "expected a filter name string, found %s", a_type(fv->type));
        } else {
            rugo_filter f = RUGO_FILTER_DEFAULT;
            /* A name with an embedded NUL ("cdf4.8\u0000x") must not pass as its prefix. */
            int ok = strlen(fv->u.string) == fv->count &&
                     rugo_filter_from_name(fv->u.string, &f) == RUGO_OK && (int)f >= 0 &&
                     f < RUGO_FILTER_COUNT;
            if (ok) {
                filter = f;
            } else {
                char quoted[48], names[80];
                rugo__json_quote_for_message(fv->u.string, fv->count, quoted, sizeof quoted);
                filter_list(names, sizeof names);
                set_path(error, "filter");
                s = field_error(error, RUGO_ERR_BAD_FILTER, text, length, fv,
                                "unknown filter \"%s\" (expected one of %s)", quoted, names);
            }
        }
    }
    const rugo__json_value* rv = NULL;
    rugo_roughness_desc roughness;
    memset(&roughness, 0, sizeof roughness);
    if (s == RUGO_OK) s = find_member(&doc, text, length, "roughness", 1, &rv, error);
    if (s == RUGO_OK && rv != NULL) {
        rctx c = {text, length, &al, error};
        s = read_roughness(&c, rv, count, &roughness);
    }
    rugo__json_doc_free(&doc);
    if (s != RUGO_OK) {
        rugo__free(&al, points);
        return s;
    }
    out->control_points = points;
    out->count = count;
    out->filter = filter;
    out->allocator = al;
    out->has_roughness = rv != NULL;
    out->roughness = roughness;
    return RUGO_OK;
}

void rugo_shape_desc_free(rugo_shape_desc* desc) {
    if (desc == NULL) return;
    rugo__free(&desc->allocator, desc->control_points);
    desc->control_points = NULL;
    desc->count = 0;
    free_roughness(&desc->allocator, &desc->roughness);
    desc->has_roughness = false;
    desc->roughness.has_perturbation = false;
}
