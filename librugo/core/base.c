#include "core/internal.h"

#include "rugo/shape_file.h" /* rugo_parse_error */

#include <stdarg.h>
#include <stdio.h>

#include <stdint.h>
#include <locale.h>
#include <stdlib.h>
#include <string.h>

const char* rugo_status_string(rugo_status status) {
    switch (status) {
    case RUGO_OK:
        return "ok";
    case RUGO_ERR_NULL_ARGUMENT:
        return "a required argument is NULL";
    case RUGO_ERR_OUT_OF_MEMORY:
        return "out of memory";
    case RUGO_ERR_TOO_FEW_POINTS:
        return "fewer than 4 control points";
    case RUGO_ERR_NOT_FINITE:
        return "non-finite value (NaN or infinity)";
    case RUGO_ERR_ZERO_AREA:
        return "outline encloses zero area";
    case RUGO_ERR_SELF_INTERSECTING:
        return "self-intersecting outline";
    case RUGO_ERR_NOT_POWER_OF_TWO:
        return "count is not a power of two";
    case RUGO_ERR_BAD_ARGUMENT:
        return "argument out of range";
    case RUGO_ERR_BAD_FILTER:
        return "unknown wavelet filter";
    case RUGO_ERR_BAD_LEVEL:
        return "level out of range";
    case RUGO_ERR_TOO_MANY_POINTS:
        return "too many control points";
    case RUGO_ERR_PARSE:
        return "malformed input text";
    case RUGO_ERR_BAD_FIELD:
        return "missing or wrongly typed field";
    case RUGO_ERR_SINGULAR:
        return "singular linear system";
    case RUGO_ERR_NOT_CONVERGED:
        return "iteration did not converge";
    case RUGO_ERR_UNSUPPORTED:
        return "not supported by this build";
    case RUGO_ERR_IO:
        return "file input/output error";
    case RUGO_ERR_NEGATIVE_TOLERANCE:
        return "negative tolerance";
    case RUGO_ERR_EMPTY_RANGE:
        return "empty range (lower end above upper end)";
    case RUGO_ERR_BAD_QUANTILE:
        return "band factor q must be > 0";
    case RUGO_ERR_WORLD_LOCKED:
        return "world is locked (inside a step or callback)";
    case RUGO_ERR_NOT_ATTACHED:
        return "body has no rough shape attached";
    case RUGO_ERR_ALREADY_ATTACHED:
        return "body already has a rough shape attached";
    case RUGO_ERR_BAD_FORMAT:
        return "not a baked shape file, or a field out of range";
    case RUGO_ERR_BAD_VERSION:
        return "unsupported baked file version";
    case RUGO_ERR_CHECKSUM:
        return "checksum mismatch (corrupted data)";
    case RUGO_ERR_TRUNCATED:
        return "data shorter than its header says (truncated)";
    case RUGO_ERR_TOO_LARGE:
        return "input beyond the size limit";
    case RUGO_ERR_BAD_SIZE:
        return "outline too small or too large for a shape";
    case RUGO_ERR_CACHE_MISMATCH:
        return "contact cache holds another pair of shapes or context (clear it)";
    case RUGO_STATUS_COUNT:
        break;
    }
    return "unknown status";
}

const char* rugo_version_string(void) { return RUGO_VERSION_STRING; }

static void* default_alloc(size_t size, void* ctx) {
    (void)ctx;
    return malloc(size);
}

static void default_free(void* p, void* ctx) {
    (void)ctx;
    free(p);
}

rugo_allocator rugo_default_allocator(void) {
    rugo_allocator a;
    a.alloc = default_alloc;
    a.free = default_free;
    a.ctx = NULL;
    return a;
}

int rugo__strtod_c(const char* text, size_t n, double* out) {
    if (n > RUGO__MAX_DECIMAL_CHARS) return 0;
    char buf[RUGO__MAX_DECIMAL_CHARS + 16];
    memcpy(buf, text, n);
    buf[n] = '\0';
    char* endp = NULL;
    double x = strtod(buf, &endp);
    if (endp == buf + n) {
        *out = x;
        return 1;
    }
    const char* dot = strchr(buf, '.');
    const struct lconv* lc = localeconv();
    const char* dp = (lc != NULL && lc->decimal_point != NULL) ? lc->decimal_point : ".";
    size_t dplen = strlen(dp);
    if (dot == NULL || dplen == 0 || dplen > 8 || strcmp(dp, ".") == 0) return 0;
    char alt[RUGO__MAX_DECIMAL_CHARS + 16];
    size_t head = (size_t)(dot - buf);
    memcpy(alt, buf, head);
    memcpy(alt + head, dp, dplen);
    memcpy(alt + head + dplen, dot + 1, n - head - 1);
    size_t alen = n - 1 + dplen;
    alt[alen] = '\0';
    x = strtod(alt, &endp);
    if (endp != alt + alen) return 0;
    *out = x;
    return 1;
}

rugo_status rugo__parse_fail(rugo_parse_error* e, rugo_status st, const char* field, const char* fmt, ...) {
    if (e == NULL) return st;
    memset(e, 0, sizeof *e);
    snprintf(e->path, sizeof e->path, "%s", field);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}
