/* Shape description files and point lists (JSON), and whole-file reading. */
#include "rugo/shape_file.h"

#include "internal.h"
#include "json.h"

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
            const rugo_json_value* at, const char* fmt, ...) {
    if (e == NULL) return status;
    if (at != NULL) rugo_json_locate(text, length, at->offset, &e->line, &e->column);
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

static void copy_json_error(rugo_parse_error* e, const rugo_json_error* je) {
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
static const char* a_type(rugo_json_type t) {
    switch (t) {
    case RUGO_JSON_NULL:
        return "null";
    case RUGO_JSON_BOOL:
        return "a boolean";
    case RUGO_JSON_NUMBER:
        return "a number";
    case RUGO_JSON_STRING:
        return "a string";
    case RUGO_JSON_ARRAY:
        return "an array";
    case RUGO_JSON_OBJECT:
        return "an object";
    }
    return "a value";
}

/* The JSON member `key` of the top-level object, which must occur exactly once unless optional. */
static rugo_status find_member(const rugo_json_doc* doc, const char* text, size_t length, const char* key,
                               int optional, const rugo_json_value** out, rugo_parse_error* e) {
    const rugo_json_value* root = doc->root;
    *out = NULL;
    if (root->type != RUGO_JSON_OBJECT)
        return field_error(e, RUGO_ERR_BAD_FIELD, text, length, root,
                           "expected a JSON object at the top level, found %s", a_type(root->type));
    int matches = 0;
    const rugo_json_value* v = rugo_json_object_get(root, key, &matches);
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
static rugo_status read_points(const rugo_json_value* arr, const char* key, const char* text, size_t length,
                               const rugo_allocator* allocator, rugo_vec2** points, int* count,
                               rugo_parse_error* e) {
    *points = NULL;
    *count = 0;
    if (arr->type != RUGO_JSON_ARRAY) {
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
    for (const rugo_json_value* p = arr->u.first; p != NULL; p = p->next, ++i) {
        rugo_status s = RUGO_OK;
        if (p->type != RUGO_JSON_ARRAY) {
            set_path(e, "%s[%d]", key, i);
            s = field_error(e, RUGO_ERR_BAD_FIELD, text, length, p, "expected an [x, y] pair, found %s",
                            a_type(p->type));
        } else if (p->count != 2) {
            set_path(e, "%s[%d]", key, i);
            s = field_error(e, RUGO_ERR_BAD_FIELD, text, length, p,
                            "expected an [x, y] pair, found an array of %lu element%s",
                            (unsigned long)p->count, p->count == 1 ? "" : "s");
        } else {
            const rugo_json_value* c = p->u.first;
            for (int j = 0; j < 2 && s == RUGO_OK; ++j, c = c->next) {
                if (c->type != RUGO_JSON_NUMBER) {
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
                             rugo_json_doc* doc, rugo_parse_error* e) {
    rugo_json_error je;
    rugo_status s = rugo_json_parse(text, length, allocator, NULL, doc, &je);
    if (s != RUGO_OK) copy_json_error(e, &je);
    return s;
}

rugo_status rugo_points_parse(const char* text, size_t length, const char* key,
                              const rugo_allocator* allocator, rugo_vec2** points, int* count,
                              rugo_parse_error* error) {
    clear_error(error);
    if (points != NULL) *points = NULL;
    if (count != NULL) *count = 0;
    if (text == NULL || key == NULL || points == NULL || count == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    rugo_json_doc doc;
    rugo_status s = parse_doc(text, length, allocator, &doc, error);
    if (s != RUGO_OK) return s;
    const rugo_json_value* arr = NULL;
    s = find_member(&doc, text, length, key, 0, &arr, error);
    if (s == RUGO_OK) s = read_points(arr, key, text, length, allocator, points, count, error);
    rugo_json_doc_free(&doc);
    return s;
}

void rugo_points_free(const rugo_allocator* allocator, rugo_vec2* points) { rugo__free(allocator, points); }

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
    r.has_perturbation = 0;
    r.perturbation_method = RUGO_ROUGHEN_WAVELET;
    return r;
}

static void free_roughness(const rugo_allocator* al, rugo_roughness_desc* r) {
    rugo__free(al, r->tolerances);
    rugo__free(al, r->perturbation_points);
    r->tolerances = NULL;
    r->tolerance_count = 0;
    r->perturbation_points = NULL;
    r->perturbation_count = 0;
}

static const char* estimator_name(rugo_tolerance_estimator est) {
    switch (est) {
    case RUGO_ESTIMATOR_COEFFICIENTS:
        return "coefficients";
    case RUGO_ESTIMATOR_DETAIL:
        return "detail";
    }
    return NULL;
}

static const char* method_name(rugo_roughen_method m) {
    switch (m) {
    case RUGO_ROUGHEN_WAVELET:
        return "wavelet";
    case RUGO_ROUGHEN_LOCAL:
        return "local";
    }
    return NULL;
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
static rugo_status member(const rctx* c, const rugo_json_value* obj, const char* prefix, const char* key,
                          const rugo_json_value** out) {
    int matches = 0;
    *out = rugo_json_object_get(obj, key, &matches);
    if (matches > 1) {
        set_path(c->e, "%s.%s", prefix, key);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, *out,
                           "field \"%s\" appears %d times", key, matches);
    }
    return RUGO_OK;
}

/* BAD_FIELD unless v has type t; `what` describes the expected value ("a number", ...). */
static rugo_status want_type(const rctx* c, const rugo_json_value* v, rugo_json_type t, const char* path,
                             const char* what) {
    if (v->type == t) return RUGO_OK;
    set_path(c->e, "%s", path);
    return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "expected %s, found %s", what,
                       a_type(v->type));
}

static rugo_status number_member(const rctx* c, const rugo_json_value* obj, const char* prefix,
                                 const char* key, rugo_real* out) {
    const rugo_json_value* v = NULL;
    rugo_status s = member(c, obj, prefix, key, &v);
    if (s != RUGO_OK || v == NULL) return s;
    char path[64];
    snprintf(path, sizeof path, "%s.%s", prefix, key);
    s = want_type(c, v, RUGO_JSON_NUMBER, path, "a number");
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
static rugo_status name_member(const rctx* c, const rugo_json_value* obj, const char* prefix, const char* key,
                               const char* const* names, int count, int* index, int* present) {
    const rugo_json_value* v = NULL;
    *present = 0;
    rugo_status s = member(c, obj, prefix, key, &v);
    if (s != RUGO_OK || v == NULL) return s;
    *present = 1;
    char path[64];
    snprintf(path, sizeof path, "%s.%s", prefix, key);
    s = want_type(c, v, RUGO_JSON_STRING, path, "a name string");
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
    rugo_json_quote_for_message(v->u.string, v->count, quoted, sizeof quoted);
    set_path(c->e, "%s", path);
    return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v,
                       "unknown %s \"%s\" (expected one of %s)", key, quoted, list);
}

/* The seed: an integer in plain digits, 0..RUGO_MAX_FILE_SEED. Read from the text itself, because a
 * double cannot tell 9007199254740993 from 2^53 or 1e3 from 1000. */
static rugo_status seed_value(const rctx* c, const rugo_json_value* v, uint64_t* out) {
    rugo_status s = want_type(c, v, RUGO_JSON_NUMBER, "roughness.seed", "an integer");
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

/* The finest tolerances: exactly one of "preset", "tolerances", "constant". */
static rugo_status read_tolerance_source(const rctx* c, const rugo_json_value* obj, int n,
                                         rugo_roughness_desc* r) {
    static const char* const keys[3] = {"preset", "tolerances", "constant"};
    const rugo_json_value* v[3];
    int found = 0, first = -1, second = -1;
    for (int k = 0; k < 3; ++k) {
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
                               "roughness needs one of \"preset\", \"tolerances\" or \"constant\"");
        return field_error(
            c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v[second],
            "roughness takes only one of \"preset\", \"tolerances\" or \"constant\" (found \"%s\" "
            "and \"%s\")",
            keys[first], keys[second]);
    }
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
    const rugo_json_value* arr = v[1];
    rugo_status s = want_type(c, arr, RUGO_JSON_ARRAY, "roughness.tolerances", "an array of tolerances");
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
    for (const rugo_json_value* x = arr->u.first; x != NULL; x = x->next, ++i) {
        if (x->type != RUGO_JSON_NUMBER) {
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

static rugo_status read_friction(const rctx* c, const rugo_json_value* obj, rugo_roughness_desc* r) {
    const rugo_json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "friction", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO_JSON_OBJECT, "roughness.friction", "an object {\"alpha\", \"lambda_min\", \"base\"}");
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

static rugo_status read_restitution(const rctx* c, const rugo_json_value* obj, rugo_roughness_desc* r) {
    const rugo_json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "restitution", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO_JSON_OBJECT, "roughness.restitution",
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

static rugo_status read_perturbation(const rctx* c, const rugo_json_value* obj, int n,
                                     rugo_roughness_desc* r) {
    static const char* const prefix = "roughness.perturbation";
    const rugo_json_value* v = NULL;
    rugo_status s = member(c, obj, "roughness", "perturbation", &v);
    if (s != RUGO_OK || v == NULL) return s;
    s = want_type(c, v, RUGO_JSON_OBJECT, prefix, "an object {\"method\", \"levels\", \"control_points\"}");
    if (s != RUGO_OK) return s;
    static const char* const methods[2] = {"wavelet", "local"};
    int index = 0, present = 0;
    s = name_member(c, v, prefix, "method", methods, 2, &index, &present);
    if (s != RUGO_OK) return s;
    if (!present) {
        set_path(c->e, "%s.method", prefix);
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "missing field \"method\"");
    }
    const rugo_json_value* lv = NULL;
    if ((s = member(c, v, prefix, "levels", &lv)) != RUGO_OK) return s;
    if (lv == NULL || lv->type != RUGO_JSON_NUMBER || !(lv->u.number >= 1.0) ||
        !(lv->u.number <= (double)RUGO_MAX_PERTURBATION_LEVELS) || lv->u.number != floor(lv->u.number)) {
        set_path(c->e, "%s.levels", prefix);
        if (lv == NULL)
            return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, v, "missing field \"levels\"");
        return field_error(c->e, RUGO_ERR_BAD_FIELD, c->text, c->length, lv,
                           "expected an integer from 1 to %d", RUGO_MAX_PERTURBATION_LEVELS);
    }
    int levels = (int)lv->u.number;
    const rugo_json_value* cp = NULL;
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
    r->has_perturbation = 1;
    r->perturbation_method = (rugo_roughen_method)index;
    r->perturbation_levels = levels;
    r->perturbation_points = pts;
    r->perturbation_count = count;
    return RUGO_OK;
}

/* The "roughness" member of a shape with n control points into *r (arrays allocated with c->al). */
static rugo_status read_roughness(const rctx* c, const rugo_json_value* obj, int n, rugo_roughness_desc* r) {
    *r = rugo_default_roughness_desc();
    rugo_status s = want_type(c, obj, RUGO_JSON_OBJECT, "roughness", "a roughness object");
    if (s == RUGO_OK) s = read_tolerance_source(c, obj, n, r);
    const rugo_json_value* v = NULL;
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

/* Checks a roughness desc for a shape of n control points, as the reader would. */
static rugo_status check_roughness(const rugo_roughness_desc* r, int n) {
    rugo_status s = RUGO_OK;
    switch (r->kind) {
    case RUGO_ROUGHNESS_PRESET:
        if ((int)r->preset < 0 || r->preset >= RUGO_PRESET_COUNT || rugo_preset_name(r->preset) == NULL)
            return RUGO_ERR_BAD_ARGUMENT;
        break;
    case RUGO_ROUGHNESS_CONSTANT:
        s = rugo_tolerances_check(&r->constant, 1, NULL);
        break;
    case RUGO_ROUGHNESS_TOLERANCES:
        if (r->tolerance_count != n) return RUGO_ERR_BAD_ARGUMENT;
        if (n > 0 && r->tolerances == NULL) return RUGO_ERR_NULL_ARGUMENT;
        if (n > 0) s = rugo_tolerances_check(r->tolerances, n, NULL);
        break;
    default:
        return RUGO_ERR_BAD_ARGUMENT;
    }
    if (s != RUGO_OK) return s;
    if (r->seed > RUGO_MAX_FILE_SEED) return RUGO_ERR_BAD_ARGUMENT;
    if (!(r->q > 0.0 && isfinite(r->q))) return RUGO_ERR_BAD_QUANTILE;
    if (estimator_name(r->estimator) == NULL) return RUGO_ERR_BAD_ARGUMENT;
    if ((s = rugo_friction_map_check(&r->friction)) != RUGO_OK) return s;
    if ((s = rugo_restitution_check(&r->restitution)) != RUGO_OK) return s;
    if (r->has_perturbation) {
        if (method_name(r->perturbation_method) == NULL) return RUGO_ERR_BAD_ARGUMENT;
        if (r->perturbation_levels < 1 || r->perturbation_levels > RUGO_MAX_PERTURBATION_LEVELS)
            return RUGO_ERR_BAD_ARGUMENT;
        if ((long long)r->perturbation_count != (long long)n << r->perturbation_levels)
            return RUGO_ERR_BAD_ARGUMENT;
        if (r->perturbation_count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
        if (r->perturbation_count > 0 && r->perturbation_points == NULL) return RUGO_ERR_NULL_ARGUMENT;
        for (int i = 0; i < r->perturbation_count; ++i)
            if (!rugo__v2_finite(r->perturbation_points[i])) return RUGO_ERR_NOT_FINITE;
    }
    return RUGO_OK;
}

rugo_status rugo_roughness_tolerances(const rugo_roughness_desc* desc, int n, rugo_real* out) {
    if (desc == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 1) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    switch (desc->kind) {
    case RUGO_ROUGHNESS_PRESET:
        return rugo_tolerances_preset(desc->preset, desc->seed, n, out);
    case RUGO_ROUGHNESS_CONSTANT:
        return rugo_tolerances_constant(desc->constant, n, out);
    case RUGO_ROUGHNESS_TOLERANCES: {
        if (desc->tolerance_count != n) return RUGO_ERR_BAD_ARGUMENT;
        if (desc->tolerances == NULL) return RUGO_ERR_NULL_ARGUMENT;
        rugo_status s = rugo_tolerances_check(desc->tolerances, n, NULL);
        if (s != RUGO_OK) return s;
        memcpy(out, desc->tolerances, sizeof *out * (size_t)n);
        return RUGO_OK;
    }
    default:
        return RUGO_ERR_BAD_ARGUMENT;
    }
}

static void write_roughness(rugo_json_writer* w, const rugo_roughness_desc* r) {
    rugo_json_key(w, "roughness");
    rugo_json_begin_object(w, 0);
    switch (r->kind) {
    case RUGO_ROUGHNESS_PRESET:
        rugo_json_key(w, "preset");
        rugo_json_string(w, rugo_preset_name(r->preset));
        break;
    case RUGO_ROUGHNESS_CONSTANT:
        rugo_json_key(w, "constant");
        rugo_json_number(w, r->constant);
        break;
    default:
        rugo_json_key(w, "tolerances");
        rugo_json_begin_array(w, 0);
        for (int i = 0; i < r->tolerance_count; ++i)
            rugo_json_number(w, r->tolerances[i]);
        rugo_json_end_array(w);
        break;
    }
    rugo_json_key(w, "seed");
    rugo_json_integer(w, (long long)r->seed);
    rugo_json_key(w, "q");
    rugo_json_number(w, r->q);
    rugo_json_key(w, "estimator");
    rugo_json_string(w, estimator_name(r->estimator));
    rugo_json_key(w, "friction");
    rugo_json_begin_object(w, RUGO_JSON_INLINE);
    rugo_json_key(w, "alpha");
    rugo_json_number(w, r->friction.alpha);
    rugo_json_key(w, "lambda_min");
    rugo_json_number(w, r->friction.lambda_min);
    rugo_json_key(w, "base");
    rugo_json_number(w, r->friction.base);
    rugo_json_end_object(w);
    rugo_json_key(w, "restitution");
    rugo_json_begin_object(w, RUGO_JSON_INLINE);
    rugo_json_key(w, "epsilon");
    rugo_json_number(w, r->restitution.epsilon);
    rugo_json_key(w, "epsilon_max");
    rugo_json_number(w, r->restitution.epsilon_max);
    rugo_json_end_object(w);
    if (r->has_perturbation) {
        rugo_json_key(w, "perturbation");
        rugo_json_begin_object(w, 0);
        rugo_json_key(w, "method");
        rugo_json_string(w, method_name(r->perturbation_method));
        rugo_json_key(w, "levels");
        rugo_json_integer(w, r->perturbation_levels);
        rugo_json_key(w, "control_points");
        rugo_json_begin_array(w, 0);
        for (int i = 0; i < r->perturbation_count; ++i) {
            rugo_json_begin_array(w, RUGO_JSON_INLINE);
            rugo_json_number(w, r->perturbation_points[i].x);
            rugo_json_number(w, r->perturbation_points[i].y);
            rugo_json_end_array(w);
        }
        rugo_json_end_array(w);
        rugo_json_end_object(w);
    }
    rugo_json_end_object(w);
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
    rugo_json_doc doc;
    rugo_status s = parse_doc(text, length, &al, &doc, error);
    if (s != RUGO_OK) return s;

    const rugo_json_value* cp = NULL;
    const rugo_json_value* fv = NULL;
    rugo_vec2* points = NULL;
    int count = 0;
    rugo_filter filter = RUGO_FILTER_DEFAULT;
    s = find_member(&doc, text, length, "control_points", 0, &cp, error);
    if (s == RUGO_OK) s = read_points(cp, "control_points", text, length, &al, &points, &count, error);
    if (s == RUGO_OK) s = find_member(&doc, text, length, "filter", 1, &fv, error);
    if (s == RUGO_OK && fv != NULL) {
        if (fv->type != RUGO_JSON_STRING) {
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
                rugo_json_quote_for_message(fv->u.string, fv->count, quoted, sizeof quoted);
                filter_list(names, sizeof names);
                set_path(error, "filter");
                s = field_error(error, RUGO_ERR_BAD_FILTER, text, length, fv,
                                "unknown filter \"%s\" (expected one of %s)", quoted, names);
            }
        }
    }
    const rugo_json_value* rv = NULL;
    rugo_roughness_desc roughness;
    memset(&roughness, 0, sizeof roughness);
    if (s == RUGO_OK) s = find_member(&doc, text, length, "roughness", 1, &rv, error);
    if (s == RUGO_OK && rv != NULL) {
        rctx c = {text, length, &al, error};
        s = read_roughness(&c, rv, count, &roughness);
    }
    rugo_json_doc_free(&doc);
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
    desc->has_roughness = 0;
    desc->roughness.has_perturbation = 0;
}

rugo_status rugo_shape_desc_write(const rugo_shape_desc* desc, const rugo_allocator* allocator, char** text,
                                  size_t* length) {
    if (text != NULL) *text = NULL;
    if (length != NULL) *length = 0;
    if (desc == NULL || text == NULL || length == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (desc->count < 0) return RUGO_ERR_BAD_ARGUMENT;
    if (desc->count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (desc->count > 0 && desc->control_points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const char* filter = rugo_filter_name(desc->filter);
    if (filter == NULL) return RUGO_ERR_BAD_FILTER;
    for (int i = 0; i < desc->count; ++i)
        if (!rugo__v2_finite(desc->control_points[i])) return RUGO_ERR_NOT_FINITE;
    if (desc->has_roughness) {
        rugo_status s = check_roughness(&desc->roughness, desc->count);
        if (s != RUGO_OK) return s;
    }

    /* One point per line: diffs stay readable and parse errors name a useful line. The longest
     * "%.17g" is 24 characters, so a file of RUGO_MAX_CONTROL_POINTS points stays below
     * RUGO_MAX_JSON_BYTES (at most 58 bytes a point) and can be read back. */
    rugo_json_writer w;
    rugo_json_writer_init(&w, allocator, 2);
    rugo_json_begin_object(&w, 0);
    rugo_json_key(&w, "control_points");
    rugo_json_begin_array(&w, 0);
    for (int i = 0; i < desc->count; ++i) {
        rugo_json_begin_array(&w, RUGO_JSON_INLINE);
        rugo_json_number(&w, desc->control_points[i].x);
        rugo_json_number(&w, desc->control_points[i].y);
        rugo_json_end_array(&w);
    }
    rugo_json_end_array(&w);
    rugo_json_key(&w, "filter");
    rugo_json_string(&w, filter);
    if (desc->has_roughness) write_roughness(&w, &desc->roughness);
    rugo_json_end_object(&w);
    rugo_json_raw(&w, "\n", 1);
    rugo_status s = rugo_json_writer_finish(&w, text, length);
    if (s == RUGO_OK && *length > RUGO_MAX_JSON_BYTES) {
        /* Only a large roughness object gets here: the reader would refuse the text. */
        rugo_text_free(allocator, *text);
        *text = NULL;
        *length = 0;
        s = RUGO_ERR_TOO_MANY_POINTS;
    }
    return s;
}

void rugo_text_free(const rugo_allocator* allocator, char* text) { rugo__free(allocator, text); }

rugo_status rugo_read_file(const char* path, const rugo_allocator* allocator, char** text, size_t* length) {
    if (text != NULL) *text = NULL;
    if (length != NULL) *length = 0;
    if (path == NULL || text == NULL || length == NULL) return RUGO_ERR_NULL_ARGUMENT;
    FILE* f = fopen(path, "rb");
    if (f == NULL) return RUGO_ERR_IO;

    /* The size, when the file can tell it, refuses a huge file before reading it and sizes the buffer;
     * pipes and special files cannot, and are read in growing chunks. */
    const size_t limit = RUGO_MAX_JSON_BYTES;
    size_t cap = 1 << 16;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && (unsigned long)n > (unsigned long)limit) {
            /* Some file systems report a huge size for a directory: tell that apart by reading. */
            rugo_status s = RUGO_ERR_PARSE;
            if (fseek(f, 0, SEEK_SET) != 0 || (fgetc(f) == EOF && ferror(f))) s = RUGO_ERR_IO;
            fclose(f);
            return s;
        }
        if (n >= 0) cap = (size_t)n + 1;
        if (fseek(f, 0, SEEK_SET) != 0) {
            fclose(f);
            return RUGO_ERR_IO;
        }
    }
    clearerr(f);

    char* buf = (char*)rugo__alloc_array(allocator, cap, 1);
    size_t len = 0;
    rugo_status s = RUGO_OK;
    if (buf == NULL) s = RUGO_ERR_OUT_OF_MEMORY;
    while (s == RUGO_OK) {
        if (len + 1 == cap) {
            /* Full (one byte stays for the NUL). A file whose size was known usually ends here: look
             * for one more byte before growing. */
            int c = fgetc(f);
            if (c == EOF) {
                if (ferror(f)) s = RUGO_ERR_IO;
                break;
            }
            if (len >= limit) {
                s = RUGO_ERR_PARSE;
                break;
            }
            size_t ncap = cap * 2;
            if (ncap > limit + 1) ncap = limit + 1;
            char* nbuf = (char*)rugo__alloc_array(allocator, ncap, 1);
            if (nbuf == NULL) {
                s = RUGO_ERR_OUT_OF_MEMORY;
                break;
            }
            memcpy(nbuf, buf, len);
            rugo__free(allocator, buf);
            buf = nbuf;
            cap = ncap;
            buf[len++] = (char)c;
            continue;
        }
        size_t got = fread(buf + len, 1, cap - 1 - len, f);
        len += got;
        if (got == 0) {
            if (ferror(f)) s = RUGO_ERR_IO;
            break;
        }
    }
    if (s == RUGO_OK && len > limit) s = RUGO_ERR_PARSE;
    fclose(f);
    if (s != RUGO_OK) {
        rugo__free(allocator, buf);
        return s;
    }
    buf[len] = '\0';
    *text = buf;
    *length = len;
    return RUGO_OK;
}
