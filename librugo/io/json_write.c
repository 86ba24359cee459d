/* The strict JSON writer (io/json.h): a growable text with automatic commas and indentation, numbers
 * written so that they read back to the same bits, and sticky errors checked once at the end. */
#include "io/json.h"

#include "core/internal.h"

#include <stdio.h>
#include <string.h>

void rugo__json_writer_init(rugo__json_writer* w, const rugo_allocator* allocator, int indent) {
    if (w == NULL) return;
    memset(w, 0, sizeof *w);
    w->allocator = rugo__allocator_or_default(allocator);
    w->status = RUGO_OK;
    w->indent = indent < 0 ? 0 : (indent > 16 ? 16 : indent);
}

static void w_set_error(rugo__json_writer* w, rugo_status s) {
    if (w->status == RUGO_OK) w->status = s;
}

/* Room for n more bytes plus the NUL that always follows the text: a text starts with room for 256
 * bytes, which doubles as needed; a new buffer starts as the empty string. */
static int w_reserve(rugo__json_writer* w, size_t n) {
    if (w->status != RUGO_OK) return 0;
    if (n > SIZE_MAX - 1 - w->length) {
        w_set_error(w, RUGO_ERR_OUT_OF_MEMORY);
        return 0;
    }
    const int fresh = w->text.data == NULL;
    if (rugo__array_reserve(&w->text, &w->allocator, w->length + n + 1, 1, 256) != RUGO_OK) {
        w_set_error(w, RUGO_ERR_OUT_OF_MEMORY);
        return 0;
    }
    if (fresh) ((char*)w->text.data)[0] = '\0';
    return 1;
}

static void w_put(rugo__json_writer* w, const char* s, size_t n) {
    if (!w_reserve(w, n)) return;
    char* data = (char*)w->text.data;
    memcpy(data + w->length, s, n);
    w->length += n;
    data[w->length] = '\0';
}

static void w_newline(rugo__json_writer* w, int level) {
    size_t n = (size_t)w->indent * (size_t)level;
    if (!w_reserve(w, n + 1)) return;
    char* data = (char*)w->text.data;
    data[w->length++] = '\n';
    memset(data + w->length, ' ', n);
    w->length += n;
    data[w->length] = '\0';
}

/* Comma and line break before an element of the innermost container. */
static void w_separator(rugo__json_writer* w) {
    int d = w->depth - 1;
    if (w->count[d] > 0) w_put(w, ",", 1);
    if (!w->is_inline[d] && w->indent > 0)
        w_newline(w, d + 1);
    else if (w->count[d] > 0)
        w_put(w, " ", 1);
    ++w->count[d];
}

static int w_value_prefix(rugo__json_writer* w) {
    if (w == NULL || w->status != RUGO_OK) return 0;
    if (w->depth == 0) return 1;
    if (w->is_object[w->depth - 1]) {
        if (!w->after_key) {
            w_set_error(w, RUGO_ERR_BAD_ARGUMENT);
            return 0;
        }
        w->after_key = 0;
        return 1;
    }
    w_separator(w);
    return w->status == RUGO_OK;
}

static void w_begin(rugo__json_writer* w, int is_object, int flags) {
    if (!w_value_prefix(w)) return;
    if (w->depth >= RUGO__JSON_WRITER_MAX_DEPTH) {
        w_set_error(w, RUGO_ERR_BAD_ARGUMENT);
        return;
    }
    int inline_ =
        (flags & RUGO__JSON_INLINE) != 0 || w->indent == 0 || (w->depth > 0 && w->is_inline[w->depth - 1]);
    w_put(w, is_object ? "{" : "[", 1);
    w->is_object[w->depth] = (unsigned char)is_object;
    w->is_inline[w->depth] = (unsigned char)inline_;
    w->count[w->depth] = 0;
    ++w->depth;
}

static void w_end(rugo__json_writer* w, int is_object) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (w->depth == 0 || w->is_object[w->depth - 1] != is_object || w->after_key) {
        w_set_error(w, RUGO_ERR_BAD_ARGUMENT);
        return;
    }
    int d = w->depth - 1;
    if (w->count[d] > 0 && !w->is_inline[d] && w->indent > 0) w_newline(w, d);
    w_put(w, is_object ? "}" : "]", 1);
    --w->depth;
}

void rugo__json_begin_object(rugo__json_writer* w, int flags) { w_begin(w, 1, flags); }
void rugo__json_end_object(rugo__json_writer* w) { w_end(w, 1); }
void rugo__json_begin_array(rugo__json_writer* w, int flags) { w_begin(w, 0, flags); }
void rugo__json_end_array(rugo__json_writer* w) { w_end(w, 0); }

static void w_quoted(rugo__json_writer* w, const char* s, size_t n) {
    static const char hex[] = "0123456789abcdef";
    w_put(w, "\"", 1);
    size_t run = 0; /* start of a stretch of bytes copied as they are */
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = (unsigned char)s[i];
        const char* esc = NULL;
        char u[7];
        switch (c) {
        case '"':
            esc = "\\\"";
            break;
        case '\\':
            esc = "\\\\";
            break;
        case '\b':
            esc = "\\b";
            break;
        case '\f':
            esc = "\\f";
            break;
        case '\n':
            esc = "\\n";
            break;
        case '\r':
            esc = "\\r";
            break;
        case '\t':
            esc = "\\t";
            break;
        default:
            if (c < 0x20) {
                memcpy(u, "\\u00", 4);
                u[4] = hex[c >> 4];
                u[5] = hex[c & 15];
                u[6] = '\0';
                esc = u;
            }
        }
        if (esc != NULL) {
            w_put(w, s + run, i - run);
            w_put(w, esc, strlen(esc));
            run = i + 1;
        }
    }
    w_put(w, s + run, n - run);
    w_put(w, "\"", 1);
}

void rugo__json_key(rugo__json_writer* w, const char* key) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (key == NULL) {
        w_set_error(w, RUGO_ERR_NULL_ARGUMENT);
        return;
    }
    if (w->depth == 0 || !w->is_object[w->depth - 1] || w->after_key) {
        w_set_error(w, RUGO_ERR_BAD_ARGUMENT);
        return;
    }
    w_separator(w);
    w_quoted(w, key, strlen(key));
    w_put(w, ": ", 2);
    w->after_key = 1;
}

int rugo__json_format_number(double x, char* buf, size_t size) {
    char tmp[64];
    int n;
    if (buf == NULL || size == 0) return 0;
    if (isnan(x))
        n = snprintf(tmp, sizeof tmp, "nan");
    else if (isinf(x))
        n = snprintf(tmp, sizeof tmp, x < 0 ? "-inf" : "inf");
    else
        n = snprintf(tmp, sizeof tmp, "%.17g", x);
    if (n < 0) n = 0;
    if ((size_t)n >= sizeof tmp) n = (int)sizeof tmp - 1;
    /* printf writes the locale's decimal point, which may be ',' or several bytes: whatever is not a
     * digit, sign or exponent mark is that point, and becomes '.'. */
    size_t j = 0;
    int in_point = 0;
    for (int i = 0; i < n && j + 1 < size; ++i) {
        char c = tmp[i];
        int plain = (c >= '0' && c <= '9') || c == '-' || c == '+' || c == 'e' || c == 'E' || !isfinite(x);
        if (plain) {
            buf[j++] = c;
            in_point = 0;
        } else if (!in_point) {
            buf[j++] = '.';
            in_point = 1;
        }
    }
    buf[j] = '\0';
    return (int)j;
}

void rugo__json_number(rugo__json_writer* w, double x) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (!isfinite(x)) {
        w_set_error(w, RUGO_ERR_NOT_FINITE);
        return;
    }
    if (!w_value_prefix(w)) return;
    char buf[40];
    int n = rugo__json_format_number(x, buf, sizeof buf);
    w_put(w, buf, (size_t)n);
}

void rugo__json_integer(rugo__json_writer* w, long long x) {
    if (!w_value_prefix(w)) return;
    char buf[32];
    int n = snprintf(buf, sizeof buf, "%lld", x);
    if (n > 0) w_put(w, buf, (size_t)n);
}

void rugo__json_string_n(rugo__json_writer* w, const char* s, size_t n) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (s == NULL && n > 0) {
        w_set_error(w, RUGO_ERR_NULL_ARGUMENT);
        return;
    }
    if (!w_value_prefix(w)) return;
    w_quoted(w, s != NULL ? s : "", n);
}

void rugo__json_string(rugo__json_writer* w, const char* s) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (s == NULL) {
        w_set_error(w, RUGO_ERR_NULL_ARGUMENT);
        return;
    }
    rugo__json_string_n(w, s, strlen(s));
}

void rugo__json_bool(rugo__json_writer* w, int b) {
    if (!w_value_prefix(w)) return;
    if (b)
        w_put(w, "true", 4);
    else
        w_put(w, "false", 5);
}

void rugo__json_null(rugo__json_writer* w) {
    if (!w_value_prefix(w)) return;
    w_put(w, "null", 4);
}

void rugo__json_raw(rugo__json_writer* w, const char* s, size_t n) {
    if (w == NULL || w->status != RUGO_OK) return;
    if (s == NULL && n > 0) {
        w_set_error(w, RUGO_ERR_NULL_ARGUMENT);
        return;
    }
    if (n > 0) w_put(w, s, n);
}

void rugo__json_writer_discard(rugo__json_writer* w) {
    if (w == NULL) return;
    rugo__array_free(&w->text, &w->allocator);
    w->length = 0;
    w->depth = 0;
    w->after_key = 0;
}

rugo_status rugo__json_writer_finish(rugo__json_writer* w, char** text, size_t* length) {
    if (text != NULL) *text = NULL;
    if (length != NULL) *length = 0;
    if (w == NULL || text == NULL) {
        rugo__json_writer_discard(w);
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (w->status == RUGO_OK && (w->depth != 0 || w->after_key)) w->status = RUGO_ERR_BAD_ARGUMENT;
    if (w->status == RUGO_OK && w->text.data == NULL) w_reserve(w, 0); /* an empty text is still a string */
    rugo_status s = w->status;
    if (s != RUGO_OK) {
        rugo__json_writer_discard(w);
        return s;
    }
    *text = (char*)w->text.data;
    if (length != NULL) *length = w->length;
    w->text.data = NULL;
    w->text.capacity = 0;
    w->length = 0;
    return RUGO_OK;
}
