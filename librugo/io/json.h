/* Internal: a small strict JSON (RFC 8259) reader and writer for shape files and the rugo tool.
 * Not installed; the rugo tool and samples may include it from librugo/. Its names carry the internal
 * prefix (rugo__json_*, RUGO__JSON_*) because a shared build exports them without making them API.
 *
 * Reader. rugo__json_parse builds a read-only tree of values in an arena (a list of blocks taken from
 * the caller's allocator and freed at once by rugo__json_doc_free). It is meant for hostile input:
 *   - it never reads past `length` (the text need not be NUL-terminated) and refuses texts larger than
 *     RUGO_MAX_JSON_BYTES, nesting deeper than max_depth and more than max_values values (memory is
 *     about 32 bytes per value plus the strings, so the value limit bounds it);
 *   - it is strict: no trailing commas, comments, single quotes, leading zeros, '+' signs, NaN or
 *     Infinity, raw control characters in strings, invalid escapes, lone UTF-16 surrogates, or
 *     characters after the value. Strings must be valid UTF-8 (no overlong forms, no encoded
 *     surrogates, nothing above U+10FFFF); "\u0000" is allowed and decodes to a NUL byte inside the
 *     string (lengths are explicit). One leading UTF-8 byte order mark is skipped (RFC 8259 §8.1
 *     allows that). Duplicate object keys are kept in order; callers decide what they mean.
 *   - numbers are checked against the JSON grammar and converted with strtod on a bounded local copy,
 *     which is correctly rounded in glibc and other mainstream C libraries, so text written with 17
 *     significant digits reads back to the same bits. strtod follows LC_NUMERIC; if the program has
 *     set a locale whose decimal point is not '.', the reader retries with that locale's decimal point,
 *     so results do not depend on the locale (localeconv() is read then, which is not thread-safe
 *     against a concurrent setlocale). A number that overflows to infinity is RUGO_ERR_NOT_FINITE; one
 *     that underflows becomes a subnormal or zero. Numbers longer than RUGO__JSON_MAX_NUMBER_CHARS
 *     characters are refused (an implementation limit RFC 8259 §9 permits; no double needs more).
 * Errors: RUGO_ERR_PARSE (syntax, limits), RUGO_ERR_NOT_FINITE, RUGO_ERR_OUT_OF_MEMORY,
 * RUGO_ERR_NULL_ARGUMENT, with a 1-based line and column (columns count bytes; lines end at '\n'),
 * the JSON path of the value being read (e.g. "control_points[3][1]") and a message.
 *
 * Writer. rugo__json_writer appends to a growable buffer (through the allocator) with automatic commas
 * and optional indentation; numbers are written with "%.17g" (locale-independent: always '.'), and a
 * non-finite number is refused. Errors are sticky: the first one is kept and returned by finish, so a
 * caller writes everything and checks once. */
#ifndef RUGO_IO_JSON_H
#define RUGO_IO_JSON_H

#include "rugo/base.h"
#include "rugo/shape_file.h" /* RUGO_MAX_JSON_BYTES */

#include "core/array.h"

#include <stddef.h>
#include <stdint.h>

/* Default and largest nesting depth (arrays and objects; the outermost counts 1). */
#define RUGO__JSON_MAX_DEPTH 64
#define RUGO__JSON_DEPTH_CAP 256
/* Default largest number of values in one text (2^23: a shape file of RUGO_MAX_CONTROL_POINTS points
 * has about 3 * 2^20). */
#define RUGO__JSON_MAX_VALUES ((size_t)1 << 23)
/* Longest number token accepted. */
#define RUGO__JSON_MAX_NUMBER_CHARS 1024

typedef enum rugo__json_type {
    RUGO__JSON_NULL = 0,
    RUGO__JSON_BOOL,
    RUGO__JSON_NUMBER,
    RUGO__JSON_STRING,
    RUGO__JSON_ARRAY,
    RUGO__JSON_OBJECT
} rugo__json_type;

/* One value. Elements of an array are a list: first, then next, ... (count of them). An object's list
 * alternates keys and values: first is the first key (a STRING), key->next its value, value->next the
 * next key; count is the number of members. Use rugo__json_object_get or the member macros below. */
typedef struct rugo__json_value {
    struct rugo__json_value* next; /* next element (or key/value) of the enclosing container */
    rugo__json_type type;
    uint32_t offset; /* byte offset of the value's first character in the text (for error positions) */
    uint32_t count;  /* STRING: length in bytes (not counting the NUL); ARRAY: elements; OBJECT: members */
    union {
        int boolean;
        double number;
        const char* string; /* UTF-8, NUL-terminated, may contain NUL bytes ("\u0000") */
        struct rugo__json_value* first;
    } u;
} rugo__json_value;

#define RUGO__JSON_MEMBER_VALUE(key) ((key)->next)
#define RUGO__JSON_NEXT_MEMBER(key) ((key)->next->next)

typedef struct rugo__json_limits {
    int max_depth;     /* <= 0: RUGO__JSON_MAX_DEPTH; at most RUGO__JSON_DEPTH_CAP */
    size_t max_values; /* 0: RUGO__JSON_MAX_VALUES */
} rugo__json_limits;

struct rugo__json_block;
/* A parsed text. The values live until rugo__json_doc_free; they do not point into the text. */
typedef struct rugo__json_doc {
    const rugo__json_value* root; /* NULL after a failed parse */
    size_t value_count;
    struct rugo__json_block* blocks;
    rugo_allocator allocator;
} rugo__json_doc;

typedef struct rugo__json_error {
    size_t offset;    /* byte offset of the problem; equals the length at an unexpected end */
    int line, column; /* 1-based; 0 when there is no position (NULL argument, text too large) */
    char path[96];    /* where in the document, e.g. "control_points[3][1]"; "" at the top level */
    char message[160];
} rugo__json_error;

/* Parses text[0, length). limits may be NULL (defaults), error may be NULL. On success doc->root is the
 * top-level value; on failure doc holds nothing (rugo__json_doc_free is still safe). */
rugo_status rugo__json_parse(const char* text, size_t length, const rugo_allocator* allocator,
                             const rugo__json_limits* limits, rugo__json_doc* doc, rugo__json_error* error);
void rugo__json_doc_free(rugo__json_doc* doc);

/* 1-based line and column (bytes) of byte `offset` of text (offset is clamped to length). */
void rugo__json_locate(const char* text, size_t length, size_t offset, int* line, int* column);

/* The value of the first member named key (NUL-terminated; a key containing NUL bytes never matches),
 * or NULL if object is not an object or has no such member. *matches (may be NULL) receives how many
 * members have that name, so that callers can refuse duplicates. */
const rugo__json_value* rugo__json_object_get(const rugo__json_value* object, const char* key, int* matches);

/* "null", "boolean", "number", "string", "array", "object". */
const char* rugo__json_type_name(rugo__json_type type);

/* Writes a short printable quotation of s[0, n) into out (size bytes, NUL-terminated): printable ASCII
 * is copied, other bytes become \xNN, and a long string is cut with "...". For error messages. */
void rugo__json_quote_for_message(const char* s, size_t n, char* out, size_t size);

/* ------------------------------------------------------------------------------------------------ */
/* Writer */

#define RUGO__JSON_WRITER_MAX_DEPTH 64
/* begin_array/begin_object flag: keep this container's elements on one line even when indenting. */
#define RUGO__JSON_INLINE 1

typedef struct rugo__json_writer {
    rugo_allocator allocator;
    rugo__array text;   /* chars: the text and the NUL that always follows it; NULL before the first write */
    size_t length;      /* of the text, not counting the NUL */
    rugo_status status; /* first error, sticky */
    int indent;         /* spaces per level; 0: everything on one line */
    int depth;
    int after_key;
    uint32_t count[RUGO__JSON_WRITER_MAX_DEPTH]; /* elements written so far at each open level */
    unsigned char is_object[RUGO__JSON_WRITER_MAX_DEPTH];
    unsigned char is_inline[RUGO__JSON_WRITER_MAX_DEPTH];
} rugo__json_writer;

/* Starts an empty text. allocator may be NULL (malloc/free); indent is spaces per nesting level
 * (0 writes one line with ", " and ": " separators). */
void rugo__json_writer_init(rugo__json_writer* w, const rugo_allocator* allocator, int indent);
/* Containers; flags is 0 or RUGO__JSON_INLINE. Misuse (unbalanced, a value without a key inside an
 * object, nesting beyond RUGO__JSON_WRITER_MAX_DEPTH) sets RUGO_ERR_BAD_ARGUMENT. */
void rugo__json_begin_object(rugo__json_writer* w, int flags);
void rugo__json_end_object(rugo__json_writer* w);
void rugo__json_begin_array(rugo__json_writer* w, int flags);
void rugo__json_end_array(rugo__json_writer* w);
/* The name of the next member of the current object (NUL-terminated UTF-8; escaped as needed). */
void rugo__json_key(rugo__json_writer* w, const char* key);
/* Values. number: "%.17g" (same bits when read back); NaN or infinity sets RUGO_ERR_NOT_FINITE. */
void rugo__json_number(rugo__json_writer* w, double x);
void rugo__json_integer(rugo__json_writer* w, long long x);
void rugo__json_string(rugo__json_writer* w, const char* s);
void rugo__json_string_n(rugo__json_writer* w, const char* s, size_t n);
void rugo__json_bool(rugo__json_writer* w, int b);
void rugo__json_null(rugo__json_writer* w);
/* Appends bytes as they are (e.g. a final newline); no comma or indentation is added. */
void rugo__json_raw(rugo__json_writer* w, const char* s, size_t n);
/* Hands over the text: *text is NUL-terminated, *length excludes the NUL; free it with the writer's
 * allocator (rugo__free). On a sticky error, or if containers are still open (BAD_ARGUMENT), frees
 * the buffer, sets *text = NULL, *length = 0 and returns the error. The writer is empty afterwards. */
rugo_status rugo__json_writer_finish(rugo__json_writer* w, char** text, size_t* length);
/* Frees the buffer without handing it over. */
void rugo__json_writer_discard(rugo__json_writer* w);

/* Formats a finite double with "%.17g" into buf (at least 32 bytes), always with '.' as the decimal
 * point; returns the length. For non-finite x writes "nan", "inf" or "-inf" (not JSON). */
int rugo__json_format_number(double x, char* buf, size_t size);

#endif
