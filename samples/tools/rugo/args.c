/* The rugo tool's command line: numbers, pairs, seeds and poses as the commands accept them, the option
 * table every command parses its arguments into, and the messages for a wrong command line. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char* g_command = "rugo";

int usage_error(const char* fmt, const char* arg) {
    fprintf(stderr, "rugo %s: ", g_command);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(run 'rugo help' for usage)\n");
    return EXIT_USAGE;
}

int fail(const char* what, rugo_status st) {
    fprintf(stderr, "rugo %s: %s: %s (status %d)\n", g_command, what, rugo_status_string(st), (int)st);
    return EXIT_INPUT;
}

int parse_real(const char* s, double* out) {
    char* end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

int parse_int(const char* s, int lo, int hi, int* out) {
    char* end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

/* "X,Y" */
int parse_pair(const char* s, rugo_vec2* out) {
    char buf[128];
    const char* comma = strchr(s, ',');
    if (comma == NULL || (size_t)(comma - s) >= sizeof buf) return -1;
    memcpy(buf, s, (size_t)(comma - s));
    buf[comma - s] = '\0';
    if (parse_real(buf, &out->x) != 0 || parse_real(comma + 1, &out->y) != 0) return -1;
    return 0;
}

/* A seed: plain decimal digits, at most 2^53 (what a shape file can carry; see docs/roughness.md). */
int parse_seed(const char* s, uint64_t* out) {
    uint64_t x = 0;
    if (*s == '\0') return -1;
    for (; *s; ++s) {
        if (*s < '0' || *s > '9') return -1;
        uint64_t d = (uint64_t)(*s - '0');
        if (x > (RUGO_MAX_FILE_SEED - d) / 10) return -1;
        x = x * 10 + d;
    }
    *out = x;
    return 0;
}

/* Parses argv against the allowed option names; value_options take a value. */
int parse_args(int argc, char** argv, const char* const* value_options, const char* const* flag_options,
               args* a) {
    memset(a, 0, sizeof *a);
    for (int i = 0; i < argc; ++i) {
        const char* s = argv[i];
        if (s[0] == '-' && s[1] != '\0' && !(s[1] >= '0' && s[1] <= '9')) {
            int known = 0;
            for (const char* const* o = value_options; o && *o; ++o)
                if (strcmp(s, *o) == 0) {
                    if (i + 1 >= argc) return usage_error("option %s needs a value", s);
                    if (a->count >= 16) return usage_error("too many options%s", "");
                    a->names[a->count] = s;
                    a->values[a->count++] = argv[++i];
                    known = 1;
                    break;
                }
            for (const char* const* o = flag_options; !known && o && *o; ++o)
                if (strcmp(s, *o) == 0) {
                    if (a->count >= 16) return usage_error("too many options%s", "");
                    a->names[a->count] = s;
                    a->values[a->count++] = NULL;
                    known = 1;
                }
            if (!known) return usage_error("unknown option %s", s);
        } else {
            if (a->positional_count >= 4) return usage_error("unexpected argument %s", s);
            a->positional[a->positional_count++] = s;
        }
    }
    return 0;
}

/* Last value given for an option (NULL if absent); *present for flags. */
const char* opt(const args* a, const char* name, int* present) {
    const char* v = NULL;
    if (present) *present = 0;
    for (int i = 0; i < a->count; ++i)
        if (strcmp(a->names[i], name) == 0) {
            v = a->values[i];
            if (present) *present = 1;
        }
    return v;
}

/* "X,Y,THETA" (THETA in radians). */
int parse_pose(const char* s, rugo_transform* out) {
    char buf[256];
    size_t n = strlen(s);
    if (n >= sizeof buf) return -1;
    memcpy(buf, s, n + 1);
    char* last = strrchr(buf, ',');
    if (last == NULL) return -1;
    *last = '\0';
    rugo_vec2 xy;
    double theta;
    if (parse_pair(buf, &xy) != 0 || parse_real(last + 1, &theta) != 0) return -1;
    *out = rugo_make_transform(xy.x, xy.y, theta);
    return 0;
}
