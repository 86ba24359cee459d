#include "sample_check.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static int g_passed, g_failed;

uint64_t sample_fnv1a(uint64_t h, const void* p, size_t n) {
    const unsigned char* c = (const unsigned char*)p;
    for (size_t i = 0; i < n; ++i) {
        h ^= c[i];
        h *= 1099511628211ull;
    }
    return h;
}

int sample_expect_le(const char* name, double value, double limit) {
    int ok = value <= limit && !isnan(value);
    printf("%s %s: %.6g <= %.3g\n", ok ? "PASS" : "FAIL", name, value, limit);
    ok ? ++g_passed : ++g_failed;
    return ok;
}

int sample_expect(const char* name, int ok) {
    printf("%s %s\n", ok ? "PASS" : "FAIL", name);
    ok ? ++g_passed : ++g_failed;
    return ok;
}

int sample_finish(void) {
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}

double sample_max(double a, double b) { return (a != a || b != b) ? NAN : (a > b ? a : b); }

int sample_mkdir(const char* path) {
    char buf[1024];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; ++i)
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = c;
        }
    return 0;
}
