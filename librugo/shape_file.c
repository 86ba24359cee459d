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
    rugo_json_doc_free(&doc);
    if (s != RUGO_OK) {
        rugo__free(&al, points);
        return s;
    }
    out->control_points = points;
    out->count = count;
    out->filter = filter;
    out->allocator = al;
    return RUGO_OK;
}

void rugo_shape_desc_free(rugo_shape_desc* desc) {
    if (desc == NULL) return;
    rugo__free(&desc->allocator, desc->control_points);
    desc->control_points = NULL;
    desc->count = 0;
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
    rugo_json_end_object(&w);
    rugo_json_raw(&w, "\n", 1);
    return rugo_json_writer_finish(&w, text, length);
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
