/* The strict JSON reader (io/json.h): a read-only tree of values in an arena, for hostile input, and
 * the message helpers every reader of io shares (line and column of an offset, printable quotations).
 * See json.h for the rules it keeps. */
#include "io/json.h"

#include "core/internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Value offsets and counts are 32-bit: texts are limited to far less. */
typedef char rugo__json_offsets_fit_32_bits[(RUGO_MAX_JSON_BYTES <= (size_t)0xFFFFFFFFu) ? 1 : -1];

/* ------------------------------------------------------------------------------------------------ */
/* Arena: values and strings of one document, freed at once. */

typedef struct rugo__json_block {
    struct rugo__json_block* next;
    size_t size, used;
} rugo__json_block;

#define ARENA_ALIGN 16
#define ARENA_HEADER ((sizeof(rugo__json_block) + ARENA_ALIGN - 1) / ARENA_ALIGN * ARENA_ALIGN)
#define ARENA_FIRST_BLOCK ((size_t)4096)
#define ARENA_MAX_BLOCK ((size_t)1 << 20)

typedef struct arena {
    rugo__json_block* blocks;
    size_t next_size;
    rugo_allocator allocator;
} arena;

static void* arena_alloc(arena* a, size_t size) {
    if (size > SIZE_MAX - 2 * ARENA_ALIGN - ARENA_HEADER) return NULL;
    size = (size + ARENA_ALIGN - 1) / ARENA_ALIGN * ARENA_ALIGN;
    rugo__json_block* b = a->blocks;
    if (b == NULL || b->size - b->used < size) {
        /* Blocks double up to 1 MiB so that small documents stay small and large ones take few
         * blocks; an oversized request gets a block of its own. */
        size_t block = a->next_size < size ? size : a->next_size;
        if (a->next_size < ARENA_MAX_BLOCK) a->next_size *= 2;
        b = (rugo__json_block*)a->allocator.alloc(ARENA_HEADER + block, a->allocator.ctx);
        if (b == NULL) return NULL;
        b->size = block;
        b->used = 0;
        b->next = a->blocks;
        a->blocks = b;
    }
    void* p = (char*)b + ARENA_HEADER + b->used;
    b->used += size;
    return p;
}

static void arena_release(rugo__json_block* blocks, const rugo_allocator* allocator) {
    while (blocks != NULL) {
        rugo__json_block* next = blocks->next;
        allocator->free(blocks, allocator->ctx);
        blocks = next;
    }
}

/* ------------------------------------------------------------------------------------------------ */
/* Messages */

static void copy_truncated(char* out, size_t size, const char* s) {
    size_t n = strlen(s);
    if (n >= size) n = size - 1;
    memcpy(out, s, n);
    out[n] = '\0';
}

void rugo__json_quote_for_message(const char* s, size_t n, char* out, size_t size) {
    static const char hex[] = "0123456789abcdef";
    size_t j = 0;
    if (out == NULL || size == 0) return;
    if (s == NULL) n = 0;
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = (unsigned char)s[i];
        size_t need = (c >= 0x20 && c < 0x7f) ? 1 : 4;
        /* Leave room for "..." and the NUL when more follows. */
        size_t reserve = (i + 1 < n) ? 4 : 1;
        if (j + need + reserve > size) {
            if (j + 4 <= size) {
                memcpy(out + j, "...", 3);
                j += 3;
            }
            break;
        }
        if (need == 1) {
            out[j++] = (char)c;
        } else {
            out[j++] = '\\';
            out[j++] = 'x';
            out[j++] = hex[c >> 4];
            out[j++] = hex[c & 15];
        }
    }
    out[j] = '\0';
}

const char* rugo__json_type_name(rugo__json_type type) {
    switch (type) {
    case RUGO__JSON_NULL:
        return "null";
    case RUGO__JSON_BOOL:
        return "boolean";
    case RUGO__JSON_NUMBER:
        return "number";
    case RUGO__JSON_STRING:
        return "string";
    case RUGO__JSON_ARRAY:
        return "array";
    case RUGO__JSON_OBJECT:
        return "object";
    }
    return "value";
}

void rugo__json_locate(const char* text, size_t length, size_t offset, int* line, int* column) {
    size_t ln = 1, line_start = 0;
    if (offset > length) offset = length;
    if (text != NULL) {
        for (size_t i = 0; i < offset; ++i) {
            if (text[i] == '\n') {
                ++ln;
                line_start = i + 1;
            }
        }
    }
    /* Texts are at most RUGO_MAX_JSON_BYTES, far below INT_MAX. */
    if (line != NULL) *line = (int)ln;
    if (column != NULL) *column = (int)(offset - line_start + 1);
}

/* ------------------------------------------------------------------------------------------------ */
/* Parser */

typedef struct frame {
    int is_object;
    int in_element;  /* array: reading element `index` (not between elements) */
    uint32_t index;  /* array: index of the element being read */
    const char* key; /* object: key of the member being read, or NULL */
    size_t key_length;
} frame;

typedef struct parser {
    const unsigned char* begin;
    const unsigned char* p;
    const unsigned char* end;
    arena arena;
    size_t values, max_values;
    int depth, max_depth;
    rugo_status status;
    size_t error_offset;
    char message[160];
    char path[96];
    frame frames[RUGO__JSON_DEPTH_CAP];
} parser;

static void path_append(char* out, size_t size, size_t* len, const char* s, size_t n) {
    if (*len + 1 >= size) return;
    size_t room = size - 1 - *len;
    if (n > room) n = room;
    memcpy(out + *len, s, n);
    *len += n;
    out[*len] = '\0';
}

static void render_path(const parser* P, char* out, size_t size) {
    size_t len = 0;
    out[0] = '\0';
    for (int i = 0; i < P->depth; ++i) {
        const frame* f = &P->frames[i];
        if (f->is_object) {
            if (f->key == NULL) break;
            if (len > 0) path_append(out, size, &len, ".", 1);
            for (size_t k = 0; k < f->key_length; ++k) {
                unsigned char c = (unsigned char)f->key[k];
                char ch = (c >= 0x20 && c < 0x7f) ? (char)c : '?';
                path_append(out, size, &len, &ch, 1);
            }
        } else {
            if (!f->in_element) break;
            char buf[16];
            int n = snprintf(buf, sizeof buf, "[%lu]", (unsigned long)f->index);
            if (n > 0) path_append(out, size, &len, buf, (size_t)n);
        }
    }
    /* A cut path says so. */
    if (len + 1 >= size && size > 4) memcpy(out + size - 4, "...", 4);
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void*
fail(parser* P, const unsigned char* at, rugo_status status, const char* fmt, ...) {
    if (P->status != RUGO_OK) return NULL;
    P->status = status;
    P->error_offset = (size_t)(at - P->begin);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(P->message, sizeof P->message, fmt, ap);
    va_end(ap);
    render_path(P, P->path, sizeof P->path);
    return NULL;
}

/* "'x'", "byte 0xNN" or "the end of the input", for messages about what was found. */
static const char* describe(const parser* P, const unsigned char* at, char* buf, size_t size) {
    if (at >= P->end) return "the end of the input";
    unsigned char c = *at;
    if (c >= 0x21 && c < 0x7f)
        snprintf(buf, size, "'%c'", (char)c);
    else
        snprintf(buf, size, "byte 0x%02x", (unsigned)c);
    return buf;
}

static void skip_ws(parser* P) {
    const unsigned char* p = P->p;
    while (p < P->end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r'))
        ++p;
    P->p = p;
}

static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

static rugo__json_value* new_value(parser* P, rugo__json_type type, const unsigned char* at) {
    if (++P->values > P->max_values)
        return (rugo__json_value*)fail(P, at, RUGO_ERR_PARSE, "more than %lu values in the text",
                                       (unsigned long)P->max_values);
    rugo__json_value* v = (rugo__json_value*)arena_alloc(&P->arena, sizeof *v);
    if (v == NULL) return (rugo__json_value*)fail(P, at, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
    v->next = NULL;
    v->type = type;
    v->offset = (uint32_t)(at - P->begin);
    v->count = 0;
    v->u.first = NULL;
    return v;
}

static rugo__json_value* parse_value(parser* P);

/* Length of the valid UTF-8 sequence at s (before stop), or 0. Refuses overlong forms, encoded UTF-16
 * surrogates and code points above U+10FFFF (RFC 3629). */
static size_t utf8_sequence(const unsigned char* s, const unsigned char* stop) {
    unsigned c = s[0];
    unsigned lo = 0x80, hi = 0xBF;
    size_t n;
    if (c >= 0xC2 && c <= 0xDF) {
        n = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else {
        return 0;
    }
    if ((size_t)(stop - s) < n) return 0;
    if (s[1] < lo || s[1] > hi) return 0;
    for (size_t i = 2; i < n; ++i)
        if (s[i] < 0x80 || s[i] > 0xBF) return 0;
    return n;
}

/* Four hex digits at s (the caller checked they are inside the string); -1 if not hex. */
static long hex4(const unsigned char* s) {
    long v = 0;
    for (int i = 0; i < 4; ++i) {
        unsigned c = s[i];
        long d;
        if (c >= '0' && c <= '9')
            d = (long)(c - '0');
        else if (c >= 'a' && c <= 'f')
            d = (long)(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F')
            d = (long)(c - 'A' + 10);
        else
            return -1;
        v = v * 16 + d;
    }
    return v;
}

static size_t utf8_encode(unsigned long cp, unsigned char* out) {
    if (cp < 0x80) {
        out[0] = (unsigned char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (unsigned char)(0xC0 | (cp >> 6));
        out[1] = (unsigned char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (unsigned char)(0xE0 | (cp >> 12));
        out[1] = (unsigned char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (unsigned char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (unsigned char)(0xF0 | (cp >> 18));
    out[1] = (unsigned char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (unsigned char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (unsigned char)(0x80 | (cp & 0x3F));
    return 4;
}

static rugo__json_value* parse_string(parser* P) {
    const unsigned char* open = P->p; /* at '"' */
    const unsigned char* stop = open + 1;
    /* First find the closing quote, so that the decoded string can be allocated once: escapes never
     * decode to more bytes than they take. */
    while (stop < P->end && *stop != '"') {
        if (*stop == '\\' && stop + 1 < P->end) ++stop;
        ++stop;
    }
    if (stop >= P->end) return (rugo__json_value*)fail(P, open, RUGO_ERR_PARSE, "unterminated string");
    rugo__json_value* v = new_value(P, RUGO__JSON_STRING, open);
    if (v == NULL) return NULL;
    unsigned char* out = (unsigned char*)arena_alloc(&P->arena, (size_t)(stop - open));
    if (out == NULL) return (rugo__json_value*)fail(P, open, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
    size_t n = 0;
    const unsigned char* s = open + 1;
    while (s < stop) {
        unsigned c = *s;
        if (c == '\\') {
            /* The scan above guarantees s + 1 < stop. */
            unsigned e = s[1];
            switch (e) {
            case '"':
                out[n++] = '"';
                break;
            case '\\':
                out[n++] = '\\';
                break;
            case '/':
                out[n++] = '/';
                break;
            case 'b':
                out[n++] = '\b';
                break;
            case 'f':
                out[n++] = '\f';
                break;
            case 'n':
                out[n++] = '\n';
                break;
            case 'r':
                out[n++] = '\r';
                break;
            case 't':
                out[n++] = '\t';
                break;
            case 'u': {
                long cp = (stop - s >= 6) ? hex4(s + 2) : -1;
                if (cp < 0) return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "\\u needs four hex digits");
                if (cp >= 0xDC00 && cp <= 0xDFFF)
                    return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "lone UTF-16 low surrogate \\u%04lX",
                                                   (unsigned long)cp);
                if (cp >= 0xD800 && cp <= 0xDBFF) {
                    long lo = (stop - s >= 12 && s[6] == '\\' && s[7] == 'u') ? hex4(s + 8) : -1;
                    if (lo < 0xDC00 || lo > 0xDFFF)
                        return (rugo__json_value*)fail(
                            P, s, RUGO_ERR_PARSE, "UTF-16 high surrogate \\u%04lX without a low surrogate",
                            (unsigned long)cp);
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    s += 6;
                }
                n += utf8_encode((unsigned long)cp, out + n);
                s += 6;
                continue;
            }
            default: {
                char buf[16];
                return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "invalid escape '\\' followed by %s",
                                               describe(P, s + 1, buf, sizeof buf));
            }
            }
            s += 2;
        } else if (c < 0x20) {
            return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE,
                                           "control character 0x%02x in a string (escape it, e.g. \\n)", c);
        } else if (c < 0x80) {
            out[n++] = (unsigned char)c;
            ++s;
        } else {
            size_t k = utf8_sequence(s, stop);
            if (k == 0) return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "invalid UTF-8 in a string");
            memcpy(out + n, s, k);
            n += k;
            s += k;
        }
    }
    out[n] = '\0';
    v->u.string = (const char*)out;
    v->count = (uint32_t)n;
    P->p = stop + 1;
    return v;
}

static rugo__json_value* parse_number(parser* P) {
    const unsigned char* s = P->p;
    const unsigned char* q = s;
    const unsigned char* end = P->end;
    if (*q == '-') ++q;
    if (q == end || !is_digit(*q)) {
        char buf[16];
        return (rugo__json_value*)fail(P, q, RUGO_ERR_PARSE, "expected a digit after '-', found %s",
                                       describe(P, q, buf, sizeof buf));
    }
    if (*q == '0') {
        ++q;
        if (q < end && is_digit(*q))
            return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "leading zeros are not allowed in numbers");
    } else {
        while (q < end && is_digit(*q))
            ++q;
    }
    if (q < end && *q == '.') {
        ++q;
        if (q == end || !is_digit(*q))
            return (rugo__json_value*)fail(P, q, RUGO_ERR_PARSE, "expected a digit after the decimal point");
        while (q < end && is_digit(*q))
            ++q;
    }
    if (q < end && (*q == 'e' || *q == 'E')) {
        ++q;
        if (q < end && (*q == '+' || *q == '-')) ++q;
        if (q == end || !is_digit(*q))
            return (rugo__json_value*)fail(P, q, RUGO_ERR_PARSE, "expected a digit in the exponent");
        while (q < end && is_digit(*q))
            ++q;
    }
    size_t len = (size_t)(q - s);
    if (len > RUGO__JSON_MAX_NUMBER_CHARS)
        return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "number longer than %d characters",
                                       RUGO__JSON_MAX_NUMBER_CHARS);
    char buf[RUGO__JSON_MAX_NUMBER_CHARS + 1];
    memcpy(buf, s, len);
    buf[len] = '\0';
    double x = 0.0;
    if (!rugo__strtod_c(buf, len, &x))
        return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "cannot convert the number");
    if (!isfinite(x)) {
        char quoted[40];
        rugo__json_quote_for_message(buf, len, quoted, sizeof quoted);
        return (rugo__json_value*)fail(P, s, RUGO_ERR_NOT_FINITE,
                                       "number %s is out of range (overflows to %s)", quoted,
                                       x < 0 ? "-infinity" : "infinity");
    }
    rugo__json_value* v = new_value(P, RUGO__JSON_NUMBER, s);
    if (v == NULL) return NULL;
    v->u.number = x;
    P->p = q;
    return v;
}

static rugo__json_value* parse_literal(parser* P, const char* word, rugo__json_type type, int boolean) {
    size_t n = strlen(word);
    const unsigned char* s = P->p;
    if ((size_t)(P->end - s) < n || memcmp(s, word, n) != 0)
        return (rugo__json_value*)fail(P, s, RUGO_ERR_PARSE, "invalid literal (expected '%s')", word);
    rugo__json_value* v = new_value(P, type, s);
    if (v == NULL) return NULL;
    v->u.boolean = boolean;
    P->p = s + n;
    return v;
}

static frame* push_frame(parser* P, int is_object, const unsigned char* at) {
    if (P->depth >= P->max_depth)
        return (frame*)fail(P, at, RUGO_ERR_PARSE, "nesting deeper than %d levels", P->max_depth);
    frame* f = &P->frames[P->depth++];
    f->is_object = is_object;
    f->in_element = 0;
    f->index = 0;
    f->key = NULL;
    f->key_length = 0;
    return f;
}

static rugo__json_value* parse_array(parser* P) {
    const unsigned char* open = P->p;
    rugo__json_value* v = new_value(P, RUGO__JSON_ARRAY, open);
    if (v == NULL) return NULL;
    frame* f = push_frame(P, 0, open);
    if (f == NULL) return NULL;
    ++P->p;
    skip_ws(P);
    if (P->p < P->end && *P->p == ']') {
        ++P->p;
        --P->depth;
        return v;
    }
    rugo__json_value* tail = NULL;
    for (;;) {
        /* The path names the element while it is read, and the array itself between elements. */
        f->in_element = 1;
        rugo__json_value* e = parse_value(P);
        if (e == NULL) return NULL;
        f->in_element = 0;
        if (tail == NULL)
            v->u.first = e;
        else
            tail->next = e;
        tail = e;
        ++v->count;
        skip_ws(P);
        if (P->p < P->end && *P->p == ',') {
            ++P->p;
            ++f->index;
            f->in_element = 1;
            skip_ws(P);
            if (P->p < P->end && *P->p == ']')
                return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "trailing comma before ']'");
            continue;
        }
        if (P->p < P->end && *P->p == ']') {
            ++P->p;
            break;
        }
        if (P->p >= P->end)
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                           "unexpected end of input in an array (missing ']')");
        char buf[16];
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                       "expected ',' or ']' after an array element, found %s",
                                       describe(P, P->p, buf, sizeof buf));
    }
    --P->depth;
    return v;
}

static rugo__json_value* parse_object(parser* P) {
    const unsigned char* open = P->p;
    rugo__json_value* v = new_value(P, RUGO__JSON_OBJECT, open);
    if (v == NULL) return NULL;
    frame* f = push_frame(P, 1, open);
    if (f == NULL) return NULL;
    ++P->p;
    skip_ws(P);
    if (P->p < P->end && *P->p == '}') {
        ++P->p;
        --P->depth;
        return v;
    }
    rugo__json_value* tail = NULL;
    char buf[16];
    for (;;) {
        f->key = NULL;
        if (P->p >= P->end)
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                           "unexpected end of input in an object (missing '}')");
        if (*P->p != '"')
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                           "expected a member name in double quotes, found %s",
                                           describe(P, P->p, buf, sizeof buf));
        rugo__json_value* key = parse_string(P);
        if (key == NULL) return NULL;
        f->key = key->u.string;
        f->key_length = key->count;
        skip_ws(P);
        if (P->p >= P->end || *P->p != ':')
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                           "expected ':' after the member name, found %s",
                                           describe(P, P->p, buf, sizeof buf));
        ++P->p;
        rugo__json_value* val = parse_value(P);
        if (val == NULL) return NULL;
        if (tail == NULL)
            v->u.first = key;
        else
            tail->next = key;
        key->next = val;
        tail = val;
        ++v->count;
        f->key = NULL;
        skip_ws(P);
        if (P->p < P->end && *P->p == ',') {
            ++P->p;
            skip_ws(P);
            if (P->p < P->end && *P->p == '}')
                return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "trailing comma before '}'");
            continue;
        }
        if (P->p < P->end && *P->p == '}') {
            ++P->p;
            break;
        }
        if (P->p >= P->end)
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                           "unexpected end of input in an object (missing '}')");
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE,
                                       "expected ',' or '}' after an object member, found %s",
                                       describe(P, P->p, buf, sizeof buf));
    }
    --P->depth;
    return v;
}

static rugo__json_value* parse_value(parser* P) {
    skip_ws(P);
    if (P->p >= P->end)
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "unexpected end of input (expected a value)");
    char buf[16];
    switch (*P->p) {
    case '{':
        return parse_object(P);
    case '[':
        return parse_array(P);
    case '"':
        return parse_string(P);
    case 't':
        return parse_literal(P, "true", RUGO__JSON_BOOL, 1);
    case 'f':
        return parse_literal(P, "false", RUGO__JSON_BOOL, 0);
    case 'n':
        return parse_literal(P, "null", RUGO__JSON_NULL, 0);
    case '-':
        if (P->end - P->p > 1 && (P->p[1] == 'I' || P->p[1] == 'N'))
            return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "NaN and Infinity are not JSON numbers");
        return parse_number(P);
    case 'N':
    case 'I':
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "NaN and Infinity are not JSON numbers");
    case '+':
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "a number may not start with '+'");
    case '.':
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "a number must start with a digit");
    case '\'':
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "strings must use double quotes");
    case '/':
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "comments are not allowed in JSON");
    default:
        if (is_digit(*P->p)) return parse_number(P);
        return (rugo__json_value*)fail(P, P->p, RUGO_ERR_PARSE, "unexpected %s (expected a value)",
                                       describe(P, P->p, buf, sizeof buf));
    }
}

rugo_status rugo__json_parse(const char* text, size_t length, const rugo_allocator* allocator,
                             const rugo__json_limits* limits, rugo__json_doc* doc, rugo__json_error* error) {
    if (error != NULL) memset(error, 0, sizeof *error);
    if (doc == NULL || text == NULL) {
        if (doc != NULL) memset(doc, 0, sizeof *doc);
        if (error != NULL)
            copy_truncated(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    memset(doc, 0, sizeof *doc);
    doc->allocator = rugo__allocator_or_default(allocator);
    if (length > RUGO_MAX_JSON_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message,
                     "text of %lu bytes is larger than the limit of %lu", (unsigned long)length,
                     (unsigned long)RUGO_MAX_JSON_BYTES);
        return RUGO_ERR_PARSE;
    }

    parser* P = (parser*)doc->allocator.alloc(sizeof(parser), doc->allocator.ctx);
    if (P == NULL) {
        if (error != NULL) copy_truncated(error->message, sizeof error->message, "out of memory");
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    P->begin = (const unsigned char*)text;
    P->p = P->begin;
    P->end = P->begin + length;
    P->arena.blocks = NULL;
    P->arena.next_size = ARENA_FIRST_BLOCK;
    P->arena.allocator = doc->allocator;
    P->values = 0;
    P->max_values = (limits != NULL && limits->max_values > 0) ? limits->max_values : RUGO__JSON_MAX_VALUES;
    P->depth = 0;
    P->max_depth = (limits != NULL && limits->max_depth > 0) ? limits->max_depth : RUGO__JSON_MAX_DEPTH;
    if (P->max_depth > RUGO__JSON_DEPTH_CAP) P->max_depth = RUGO__JSON_DEPTH_CAP;
    P->status = RUGO_OK;
    P->error_offset = 0;
    P->message[0] = '\0';
    P->path[0] = '\0';

    /* RFC 8259 §8.1: a parser may ignore a byte order mark. Editors on some systems add one. */
    if (length >= 3 && P->p[0] == 0xEF && P->p[1] == 0xBB && P->p[2] == 0xBF) P->p += 3;
    skip_ws(P);
    rugo__json_value* root = NULL;
    if (P->p >= P->end) {
        fail(P, P->p, RUGO_ERR_PARSE, "empty input (no JSON value)");
    } else {
        root = parse_value(P);
        if (root != NULL) {
            skip_ws(P);
            if (P->p < P->end) {
                char buf[16];
                fail(P, P->p, RUGO_ERR_PARSE, "unexpected %s after the JSON value",
                     describe(P, P->p, buf, sizeof buf));
            }
        }
    }

    rugo_status status = P->status;
    if (status == RUGO_OK) {
        doc->root = root;
        doc->value_count = P->values;
        doc->blocks = P->arena.blocks;
    } else {
        arena_release(P->arena.blocks, &doc->allocator);
        if (error != NULL) {
            error->offset = P->error_offset;
            rugo__json_locate(text, length, P->error_offset, &error->line, &error->column);
            copy_truncated(error->path, sizeof error->path, P->path);
            copy_truncated(error->message, sizeof error->message, P->message);
        }
    }
    doc->allocator.free(P, doc->allocator.ctx);
    return status;
}

void rugo__json_doc_free(rugo__json_doc* doc) {
    if (doc == NULL) return;
    if (doc->blocks != NULL) arena_release(doc->blocks, &doc->allocator);
    doc->blocks = NULL;
    doc->root = NULL;
    doc->value_count = 0;
}

const rugo__json_value* rugo__json_object_get(const rugo__json_value* object, const char* key, int* matches) {
    const rugo__json_value* found = NULL;
    int n = 0;
    if (object != NULL && key != NULL && object->type == RUGO__JSON_OBJECT) {
        size_t len = strlen(key);
        for (const rugo__json_value* k = object->u.first; k != NULL; k = RUGO__JSON_NEXT_MEMBER(k)) {
            if (k->count == len && memcmp(k->u.string, key, len) == 0) {
                if (found == NULL) found = RUGO__JSON_MEMBER_VALUE(k);
                ++n;
            }
        }
    }
    if (matches != NULL) *matches = n;
    return found;
}
