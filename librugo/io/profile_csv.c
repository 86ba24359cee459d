/* Roughness profiles from CSV text (rugo_roughness_profile_parse_csv): "s,lambda" lines, '#'
 * comments, an optional header; each number read by the JSON reader, so that CSV and JSON read the
 * same text to the same bits. */
#include "rugo/shape_file.h"

#include "core/array.h"
#include "core/internal.h"
#include "io/json.h"
#include "rough/internal.h" /* rugo__roughness_sample_check */

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int csv_space(char ch) { return ch == ' ' || ch == '\t'; }

static int csv_lower(char ch) { return ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch; }

/* 1 if f[0, n) is nan, inf or infinity (any case, optional sign). */
static int csv_non_finite_word(const char* f, size_t n) {
    static const char* const words[3] = {"nan", "inf", "infinity"};
    if (n > 0 && (f[0] == '+' || f[0] == '-')) {
        ++f;
        --n;
    }
    for (int w = 0; w < 3; ++w) {
        size_t len = strlen(words[w]);
        if (len != n) continue;
        size_t i = 0;
        while (i < n && csv_lower(f[i]) == words[w][i])
            ++i;
        if (i == n) return 1;
    }
    return 0;
}

/* Rewrites a decimal number f[0, n) in JSON's grammar into buf (no '+', no leading zeros, digits on
 * both sides of the point); returns its length, or 0 if f is not a number or too long. */
static size_t csv_number_as_json(const char* f, size_t n, char* buf, size_t size) {
    size_t i = 0, o = 0;
    if (n + 4 > size) return 0;
    if (i < n && (f[i] == '+' || f[i] == '-')) {
        if (f[i] == '-') buf[o++] = '-';
        ++i;
    }
    size_t int_start = i;
    while (i < n && f[i] >= '0' && f[i] <= '9')
        ++i;
    size_t int_end = i, frac_start = i, frac_end = i;
    int point = 0;
    if (i < n && f[i] == '.') {
        point = 1;
        frac_start = ++i;
        while (i < n && f[i] >= '0' && f[i] <= '9')
            ++i;
        frac_end = i;
    }
    if (int_end == int_start && frac_end == frac_start) return 0; /* no digit */
    while (int_start + 1 < int_end && f[int_start] == '0')
        ++int_start;
    if (int_start == int_end)
        buf[o++] = '0';
    else
        for (size_t k = int_start; k < int_end; ++k)
            buf[o++] = f[k];
    if (point && frac_end > frac_start) {
        buf[o++] = '.';
        for (size_t k = frac_start; k < frac_end; ++k)
            buf[o++] = f[k];
    }
    if (i < n && (f[i] == 'e' || f[i] == 'E')) {
        buf[o++] = 'e';
        ++i;
        if (i < n && (f[i] == '+' || f[i] == '-')) buf[o++] = f[i++];
        size_t exp_start = i;
        while (i < n && f[i] >= '0' && f[i] <= '9')
            buf[o++] = f[i++];
        if (i == exp_start) return 0;
    }
    if (i != n) return 0;
    buf[o] = '\0';
    return o;
}

/* One numeric field: RUGO_OK with *value, or PARSE / NOT_FINITE / OUT_OF_MEMORY with a message. The
 * JSON reader converts it, so that CSV and JSON read the same text to the same bits. */
static rugo_status csv_number(const char* f, size_t n, const rugo_allocator* al, double* value, char* msg,
                              size_t size) {
    char quoted[48];
    rugo__json_quote_for_message(f, n, quoted, sizeof quoted);
    if (n == 0) {
        snprintf(msg, size, "empty field (expected a number)");
        return RUGO_ERR_PARSE;
    }
    if (csv_non_finite_word(f, n)) {
        snprintf(msg, size, "\"%s\" is not a finite number", quoted);
        return RUGO_ERR_NOT_FINITE;
    }
    char buf[RUGO__JSON_MAX_NUMBER_CHARS + 8];
    size_t len = csv_number_as_json(f, n, buf, sizeof buf);
    if (len == 0) {
        snprintf(msg, size, "expected a number, found \"%s\"", quoted);
        return RUGO_ERR_PARSE;
    }
    rugo__json_doc doc;
    rugo__json_error je;
    rugo_status s = rugo__json_parse(buf, len, al, NULL, &doc, &je);
    if (s == RUGO_OK && doc.root->type == RUGO__JSON_NUMBER) {
        *value = doc.root->u.number;
    } else if (s == RUGO_ERR_NOT_FINITE) {
        snprintf(msg, size, "\"%s\" overflows to infinity", quoted);
    } else if (s == RUGO_ERR_OUT_OF_MEMORY) {
        snprintf(msg, size, "out of memory");
    } else {
        snprintf(msg, size, "expected a number, found \"%s\"", quoted);
        s = RUGO_ERR_PARSE;
    }
    rugo__json_doc_free(&doc);
    return s;
}

/* The path of sample m, "profile[m]", or of its column, "profile[m][column]" (column >= 0). */
static void csv_path(rugo_parse_error* e, int m, int column) {
    if (e == NULL) return;
    if (column < 0)
        snprintf(e->path, sizeof e->path, "profile[%d]", m);
    else
        snprintf(e->path, sizeof e->path, "profile[%d][%d]", m, column);
}

/* A CSV error at byte `offset` of the text (the caller sets the path). */
#if defined(__GNUC__)
__attribute__((format(printf, 6, 7)))
#endif
static rugo_status
csv_error(rugo_parse_error* e, rugo_status status, const char* text, size_t length, size_t offset,
          const char* fmt, ...) {
    if (e == NULL) return status;
    rugo__json_locate(text, length, offset, &e->line, &e->column);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return status;
}

rugo_status rugo_roughness_profile_parse_csv(const char* text, size_t length, const rugo_allocator* allocator,
                                             rugo_roughness_profile* out, rugo_parse_error* error) {
    if (error != NULL) memset(error, 0, sizeof *error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_JSON_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message,
                     "text of %lu bytes is larger than the limit of %lu", (unsigned long)length,
                     (unsigned long)RUGO_MAX_JSON_BYTES);
        return RUGO_ERR_PARSE;
    }
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo__array room = {NULL, 0};  /* rugo_profile_sample: room for 64 first, then doubling */
    rugo_profile_sample* p = NULL; /* room.data */
    int m = 0;
    int header_allowed = 1;
    rugo_status s = RUGO_OK;
    size_t pos = 0;
    if (length >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        pos = 3;
    while (pos < length && s == RUGO_OK) {
        const char* nl = (const char*)memchr(text + pos, '\n', length - pos);
        size_t end = nl != NULL ? (size_t)(nl - text) : length;
        size_t next = nl != NULL ? end + 1 : length;
        if (end > pos && text[end - 1] == '\r') --end;
        size_t b = pos;
        while (b < end && csv_space(text[b]))
            ++b;
        if (b == end || text[b] == '#') {
            pos = next;
            continue;
        }
        /* Fields: [start, stop) trimmed, at most 3 kept (a third means too many). */
        size_t fs[3], fe[3];
        int nf = 0;
        size_t f = pos;
        for (;;) {
            const char* comma = (const char*)memchr(text + f, ',', end - f);
            size_t stop = comma != NULL ? (size_t)(comma - text) : end;
            if (nf < 3) {
                size_t a0 = f, a1 = stop;
                while (a0 < a1 && csv_space(text[a0]))
                    ++a0;
                while (a1 > a0 && csv_space(text[a1 - 1]))
                    --a1;
                fs[nf] = a0;
                fe[nf] = a1;
            }
            ++nf;
            if (comma == NULL) break;
            f = stop + 1;
        }
        double v[2] = {0.0, 0.0};
        char msg[160];
        int is_header = 0;
        if (header_allowed) { /* a first field that cannot start a number: "s", "\"s\"", "position" */
            size_t n0 = fe[0] - fs[0];
            char c0 = n0 > 0 ? text[fs[0]] : '0';
            is_header = !((c0 >= '0' && c0 <= '9') || c0 == '+' || c0 == '-' || c0 == '.') &&
                        !csv_non_finite_word(text + fs[0], n0);
            header_allowed = 0;
        }
        if (nf != 2) {
            s = csv_error(error, RUGO_ERR_PARSE, text, length, b,
                          "%s has %d field%s; expected 2 (s, lambda) separated by a comma",
                          is_header ? "the header" : "the line", nf, nf == 1 ? "" : "s");
            if (!is_header) csv_path(error, m, -1);
            break;
        }
        if (is_header) {
            pos = next;
            continue;
        }
        if (m >= RUGO_MAX_PROFILE_SAMPLES) {
            s = csv_error(error, RUGO_ERR_TOO_MANY_POINTS, text, length, b, "more than %d samples",
                          RUGO_MAX_PROFILE_SAMPLES);
            break;
        }
        for (int k = 0; k < 2 && s == RUGO_OK; ++k) {
            s = csv_number(text + fs[k], fe[k] - fs[k], &al, &v[k], msg, sizeof msg);
            if (s != RUGO_OK) {
                csv_error(error, s, text, length, fs[k], "%s", msg);
                csv_path(error, m, k);
            }
        }
        if (s != RUGO_OK) break;
        if (rugo__array_reserve(&room, &al, (size_t)m + 1, sizeof *p, 64) != RUGO_OK) {
            s = csv_error(error, RUGO_ERR_OUT_OF_MEMORY, text, length, b, "out of memory");
            break;
        }
        p = (rugo_profile_sample*)room.data;
        p[m].s = v[0];
        p[m].tolerance = v[1];
        int column = 0;
        s = rugo__roughness_sample_check(m > 0 ? &p[m - 1] : NULL, &p[m], &column, msg, sizeof msg);
        if (s != RUGO_OK) {
            csv_error(error, s, text, length, fs[column], "%s", msg);
            csv_path(error, m, column);
            break;
        }
        ++m;
        pos = next;
    }
    if (s == RUGO_OK && m == 0)
        s = csv_error(error, RUGO_ERR_BAD_FIELD, text, length, length,
                      "no samples: a profile needs at least one line \"s,lambda\"");
    if (s != RUGO_OK) {
        rugo__array_free(&room, &al);
        return s;
    }
    out->samples = p;
    out->count = m;
    out->allocator = al;
    return RUGO_OK;
}

void rugo_roughness_profile_free(rugo_roughness_profile* profile) {
    if (profile == NULL) return;
    rugo__free(&profile->allocator, profile->samples);
    memset(profile, 0, sizeof *profile);
}
