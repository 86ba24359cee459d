/* Baked shapes: the binary format of a built rugo_shape (docs/baked.md) and its validating loader;
 * baked_file.c writes and reads it as files.
 *
 * Byte order and floating point are fixed by the format, not the host: every integer is written
 * little-endian byte by byte, every double as the little-endian bytes of its IEEE-754 binary64 bit
 * pattern. The loader checks sizes against the header before reading anything else, the checksum
 * before parsing fields, and every field before it is used; nothing read from the file indexes
 * memory until the payload length has been proven equal to the length its levels imply. */
#include "rugo/baked.h"

#include "core/internal.h"
#include "shape/internal.h"

#include <float.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* The format stores binary64 bit patterns; a host with another double cannot read or write them. */
typedef char rugo__baked_needs_ieee_double[(DBL_MANT_DIG == 53 && DBL_MAX_EXP == 1024 && sizeof(double) == 8)
                                               ? 1
                                               : -1];

static const unsigned char MAGIC[RUGO_BAKED_MAGIC_SIZE] = {'R', 'U', 'G', 'O', 'B', 'A', 'K', 'E'};

#define HEADER_SIZE 64
#define FIXED_SIZE 160 /* the payload's fixed part, before the arrays */
/* Offsets in the header. */
#define H_VERSION 8
#define H_HEADER_SIZE 12
#define H_PAYLOAD_SIZE 16
#define H_CHECKSUM 24 /* u64 */
#define H_RESERVED 32 /* 32 bytes of zeros up to HEADER_SIZE */
/* Flag bits of the payload. */
#define FLAG_ROUGH 1u
#define FLAG_REVERSED 2u
/* Stored magnitudes are bounded like rugo_contour_check bounds coordinates: beyond this, products in
 * queries could overflow. */
#define VALUE_LIMIT 1e150
/* Box axes must be unit and perpendicular up to this (they are exactly so when built). */
#define AXIS_SLACK 1e-9

/* ---- error detail --------------------------------------------------------------------------------- */

void rugo__baked_detail(rugo_baked_error* d, size_t offset, const char* field, const char* fmt, ...) {
    if (d == NULL) return;
    d->offset = offset;
    d->field[0] = '\0';
    if (field != NULL) {
        strncpy(d->field, field, sizeof d->field - 1);
        d->field[sizeof d->field - 1] = '\0';
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->message, sizeof d->message, fmt, ap);
    va_end(ap);
}

void rugo__baked_clear_detail(rugo_baked_error* d) {
    if (d == NULL) return;
    d->offset = 0;
    d->field[0] = '\0';
    d->message[0] = '\0';
}

/* ---- little-endian encoding ------------------------------------------------------------------------ */

static void put_u32(unsigned char* p, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}
static void put_u64(unsigned char* p, uint64_t v) {
    for (int i = 0; i < 8; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}
/* Written out, not as loops: compilers recognise these forms as one load on little-endian hosts. */
static uint32_t get_u32(const unsigned char* p) {
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
static uint64_t get_u64(const unsigned char* p) {
    return (uint64_t)p[0] | ((uint64_t)p[1] << 8) | ((uint64_t)p[2] << 16) | ((uint64_t)p[3] << 24) |
           ((uint64_t)p[4] << 32) | ((uint64_t)p[5] << 40) | ((uint64_t)p[6] << 48) | ((uint64_t)p[7] << 56);
}
static void put_f64(unsigned char* p, double x) {
    uint64_t bits;
    memcpy(&bits, &x, 8);
    put_u64(p, bits);
}
static double get_f64(const unsigned char* p) {
    const uint64_t bits = get_u64(p);
    double x;
    memcpy(&x, &bits, 8);
    return x;
}

/* ---- checksum (docs/baked.md) --------------------------------------------------------------------
 * Word-wise, 64 bits: the file is read as little-endian 64-bit words (the last one padded with zero
 * bytes, the checksum field taken as zero); word i goes into lane i mod 4 by
 * round(acc, w) = rotl(acc + w P2, 31) P1 (xxHash64's round), then the lanes into h = size the same
 * way, then xxHash64's avalanche. Every step is a bijection of the word, the lane and h, so any change
 * confined to one aligned 8-byte word (every single-bit error among them) changes the checksum; other
 * corruptions go undetected with probability about 2^-64. Four independent lanes keep the multiplier
 * busy (two multiplications per 8 bytes): about 10x the speed of the table-driven CRC-32 it replaced. */

#define CK_P1 UINT64_C(0x9E3779B185EBCA87)
#define CK_P2 UINT64_C(0xC2B2AE3D27D4EB4F)
#define CK_P3 UINT64_C(0x165667B19E3779F9)
#define CK_P4 UINT64_C(0x85EBCA77C2B2AE63)

static uint64_t ck_round(uint64_t acc, uint64_t w) {
    acc += w * CK_P2;
    acc = (acc << 31) | (acc >> 33);
    return acc * CK_P1;
}

/* Word i of the file as the checksum sees it: zero-padded past the end, zero for the checksum field. */
static uint64_t ck_word(const unsigned char* f, size_t size, size_t i) {
    if (i == H_CHECKSUM / 8) return 0;
    if (8 * i + 8 <= size) return get_u64(f + 8 * i);
    unsigned char last[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    memcpy(last, f + 8 * i, size - 8 * i);
    return get_u64(last);
}

static uint64_t file_checksum(const unsigned char* f, size_t size) {
    uint64_t v0 = CK_P1, v1 = CK_P2, v2 = CK_P3, v3 = CK_P4;
    const size_t words = (size + 7) / 8, full = size / 8;
    size_t i = 0;
    /* The header's first four words (the checksum field is word 3), then the body four by four. */
    if (full >= 4) {
        v0 = ck_round(v0, get_u64(f));
        v1 = ck_round(v1, get_u64(f + 8));
        v2 = ck_round(v2, get_u64(f + 16));
        v3 = ck_round(v3, 0);
        for (i = 4; i + 4 <= full; i += 4) {
            const unsigned char* p = f + 8 * i;
            v0 = ck_round(v0, get_u64(p));
            v1 = ck_round(v1, get_u64(p + 8));
            v2 = ck_round(v2, get_u64(p + 16));
            v3 = ck_round(v3, get_u64(p + 24));
        }
    }
    uint64_t lane[4];
    lane[0] = v0;
    lane[1] = v1;
    lane[2] = v2;
    lane[3] = v3;
    for (; i < words; ++i)
        lane[i % 4] = ck_round(lane[i % 4], ck_word(f, size, i));
    uint64_t h = (uint64_t)size;
    for (int l = 0; l < 4; ++l)
        h = ck_round(h, lane[l]);
    h ^= h >> 33;
    h *= CK_P2;
    h ^= h >> 29;
    h *= CK_P3;
    h ^= h >> 32;
    return h;
}

/* ---- sizes ------------------------------------------------------------------------------------------ */

typedef struct layout {
    size_t per;    /* entries of levels J_min..J: 2^(J+1) - 2^J_min */
    size_t det;    /* details, levels J_min..J-1: 2^J - 2^J_min */
    size_t levels; /* J - J_min + 1 */
    /* Payload offsets of the arrays. */
    size_t points, world, local, tol, band, excess, nodes, end;
} layout;

#define OBB_BYTES 64 /* centre, two axes, two half-extents: 8 doubles */

/* Valid for 2 <= J_min <= J <= 20: at most ~2^21 entries, no overflow of size_t even on 32 bits. */
static layout make_layout(int J, int Jmin) {
    layout L;
    L.per = ((size_t)1 << (J + 1)) - ((size_t)1 << Jmin);
    L.det = ((size_t)1 << J) - ((size_t)1 << Jmin);
    L.levels = (size_t)(J - Jmin + 1);
    L.points = FIXED_SIZE;
    L.world = L.points + 16 * L.per;
    L.local = L.world + 16 * L.det;
    L.tol = L.local + 16 * L.det;
    L.band = L.tol + 3 * 8 * L.per;
    L.excess = L.band + 8 * L.per;
    L.nodes = L.excess + 8 * L.levels;
    L.end = L.nodes + OBB_BYTES * L.per;
    return L;
}

/* Levels a shape can have: 2^J <= RUGO_MAX_CONTROL_POINTS = 2^20. */
static int levels_ok(int J, int Jmin) { return Jmin >= 2 && J >= Jmin && J <= 20; }

bool rugo_is_baked(const void* buffer, size_t size) {
    return buffer != NULL && size >= RUGO_BAKED_MAGIC_SIZE &&
           memcmp(buffer, MAGIC, RUGO_BAKED_MAGIC_SIZE) == 0;
}

rugo_status rugo_shape_bake_size(const rugo_shape* shape, size_t* size) {
    if (size != NULL) *size = 0;
    if (shape == NULL || size == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const int J = rugo_shape_finest_level(shape), Jmin = rugo_shape_coarsest_level(shape);
    if (!levels_ok(J, Jmin)) return RUGO_ERR_TOO_LARGE; /* cannot happen for a built shape */
    const size_t total = HEADER_SIZE + make_layout(J, Jmin).end;
    *size = total;
    return total > RUGO_MAX_BAKED_BYTES ? RUGO_ERR_TOO_LARGE : RUGO_OK;
}

/* ---- writing ---------------------------------------------------------------------------------------- */

static unsigned char* put_obb(unsigned char* p, const rugo_obb* b) {
    put_f64(p + 0, b->center.x);
    put_f64(p + 8, b->center.y);
    put_f64(p + 16, b->axis[0].x);
    put_f64(p + 24, b->axis[0].y);
    put_f64(p + 32, b->axis[1].x);
    put_f64(p + 40, b->axis[1].y);
    put_f64(p + 48, b->half[0]);
    put_f64(p + 56, b->half[1]);
    return p + OBB_BYTES;
}

rugo_status rugo_shape_bake(const rugo_shape* shape, void* buffer, size_t capacity, size_t* written) {
    if (written != NULL) *written = 0;
    if (shape == NULL || buffer == NULL || written == NULL) return RUGO_ERR_NULL_ARGUMENT;
    size_t size = 0;
    rugo_status st = rugo_shape_bake_size(shape, &size);
    *written = size;
    if (st != RUGO_OK) return st;
    if (capacity < size) return RUGO_ERR_TOO_LARGE;

    const int J = rugo_shape_finest_level(shape), Jmin = rugo_shape_coarsest_level(shape);
    const layout L = make_layout(J, Jmin);
    unsigned char* f = (unsigned char*)buffer;
    memset(f, 0, HEADER_SIZE);
    memcpy(f, MAGIC, RUGO_BAKED_MAGIC_SIZE);
    put_u32(f + H_VERSION, RUGO_BAKED_VERSION);
    put_u32(f + H_HEADER_SIZE, HEADER_SIZE);
    put_u64(f + H_PAYLOAD_SIZE, (uint64_t)L.end);

    unsigned char* p = f + HEADER_SIZE;
    const rugo_pyramid* pyr = rugo_shape_pyramid(shape);
    const rugo_mobb_tree* tree = rugo_shape_tree(shape);
    put_u32(p + 0, (uint32_t)J);
    put_u32(p + 4, (uint32_t)Jmin);
    put_u32(p + 8, (uint32_t)rugo_pyramid_filter(pyr));
    put_u32(p + 12, (uint32_t)rugo_mobb_tree_method(tree));
    put_u32(p + 16, (rugo_shape_is_rough(shape) ? FLAG_ROUGH : 0u) |
                        (rugo_shape_was_reversed(shape) ? FLAG_REVERSED : 0u));
    put_u32(p + 20, 0);
    const rugo_mass_properties m = rugo_shape_mass(shape);
    put_f64(p + 24, m.area);
    put_f64(p + 32, m.centroid.x);
    put_f64(p + 40, m.centroid.y);
    put_f64(p + 48, m.inertia);
    const rugo_friction_map fr = rugo_shape_friction_map(shape);
    put_f64(p + 56, fr.alpha);
    put_f64(p + 64, fr.lambda_min);
    put_f64(p + 72, fr.base);
    const rugo_restitution re = rugo_shape_restitution(shape);
    put_f64(p + 80, re.epsilon);
    put_f64(p + 88, re.epsilon_max);
    put_obb(p + 96, rugo_mobb_tree_root(tree));

    unsigned char *q_pts = p + L.points, *q_world = p + L.world, *q_local = p + L.local;
    unsigned char *q_tol = p + L.tol, *q_band = p + L.band, *q_nodes = p + L.nodes;
    for (int j = Jmin; j <= J; ++j) {
        const int n = 1 << j;
        rugo_contour c;
        rugo_shape_level(shape, j, &c);
        for (int k = 0; k < n; ++k, q_pts += 16) {
            put_f64(q_pts, c.points[k].x);
            put_f64(q_pts + 8, c.points[k].y);
        }
        if (j < J) {
            const rugo_vec2 *w = NULL, *l = NULL;
            rugo_pyramid_details(pyr, j, &w, &l);
            for (int k = 0; k < n; ++k, q_world += 16, q_local += 16) {
                put_f64(q_world, w[k].x);
                put_f64(q_world + 8, w[k].y);
                put_f64(q_local, l[k].x);
                put_f64(q_local + 8, l[k].y);
            }
        }
        rugo_tolerance_level tl;
        rugo_shape_tolerance_level(shape, j, &tl);
        const rugo_real* bb = rugo__shape_band_bounds(shape, j);
        const size_t o = ((size_t)1 << j) - ((size_t)1 << Jmin);
        for (int k = 0; k < n; ++k) {
            put_f64(q_tol + 8 * (o + (size_t)k), tl.own[k]);
            put_f64(q_tol + 8 * (L.per + o + (size_t)k), tl.total[k]);
            put_f64(q_tol + 8 * (2 * L.per + o + (size_t)k), tl.bound[k]);
            put_f64(q_band + 8 * (o + (size_t)k), bb[k]);
            q_nodes = put_obb(q_nodes, rugo_mobb_tree_node(tree, j, k));
        }
        put_f64(p + L.excess + 8 * (size_t)(j - Jmin), rugo__shape_band_excess(shape, j));
    }
    put_u64(f + H_CHECKSUM, file_checksum(f, size));
    return RUGO_OK;
}

/* ---- loading ---------------------------------------------------------------------------------------- */

/* Reads and checks values; the first failure sets st and the detail, later checks are skipped. */
typedef struct reader {
    const unsigned char* file;
    rugo_baked_error* detail;
    rugo_status st;
} reader;

static int failed(const reader* r) { return r->st != RUGO_OK; }

static void fail(reader* r, size_t offset, const char* field, const char* message, double value) {
    if (failed(r)) return;
    r->st = RUGO_ERR_BAD_FORMAT;
    if (r->detail != NULL) {
        rugo__baked_detail(r->detail, offset, field, "%s (%.17g) at byte %lu", message, value,
                           (unsigned long)offset);
    }
}

/* A bounded finite double, >= lo when nonneg is set. */
static double read_real(reader* r, size_t offset, const char* field, int nonneg) {
    const double x = get_f64(r->file + offset);
    if (!isfinite(x))
        fail(r, offset, field, "not finite", x);
    else if (fabs(x) > VALUE_LIMIT)
        fail(r, offset, field, "magnitude beyond 1e150", x);
    else if (nonneg && x < 0.0)
        fail(r, offset, field, "negative", x);
    return x;
}

/* Field names with an index, only built on failure. */
static void fail_indexed(reader* r, size_t offset, const char* array, size_t index, const char* member,
                         const char* message, double value) {
    char name[64];
    if (index == (size_t)-1) /* a single record, e.g. the root box */
        snprintf(name, sizeof name, "%s%s", array, member);
    else
        snprintf(name, sizeof name, "%s[%lu]%s", array, (unsigned long)index, member);
    fail(r, offset, name, message, value);
}

static double read_indexed(reader* r, size_t offset, const char* array, size_t index, const char* member,
                           int nonneg) {
    const double x = get_f64(r->file + offset);
    if (!isfinite(x))
        fail_indexed(r, offset, array, index, member, "not finite", x);
    else if (fabs(x) > VALUE_LIMIT)
        fail_indexed(r, offset, array, index, member, "magnitude beyond 1e150", x);
    else if (nonneg && x < 0.0)
        fail_indexed(r, offset, array, index, member, "negative", x);
    return x;
}

/* A box's axes (v: its 8 values): 0 if axis 0 is unit and axis 1 is perp(axis 0) within AXIS_SLACK,
 * 1 if axis 0 is not unit, 2 if axis 1 is not perpendicular. Shared by both paths of the loader. */
static int axes_status(const double v[8]) {
    const double len2 = v[2] * v[2] + v[3] * v[3];
    if (!(fabs(len2 - 1.0) <= AXIS_SLACK)) return 1;
    if (!(fabs(v[4] + v[3]) <= AXIS_SLACK && fabs(v[5] - v[2]) <= AXIS_SLACK)) return 2;
    return 0;
}

static rugo_obb read_obb(reader* r, size_t offset, const char* array, size_t index) {
    static const char* const names[8] = {".center.x",  ".center.y",  ".axis[0].x", ".axis[0].y",
                                         ".axis[1].x", ".axis[1].y", ".half[0]",   ".half[1]"};
    double v[8];
    for (int i = 0; i < 8; ++i)
        v[i] = read_indexed(r, offset + 8 * (size_t)i, array, index, names[i], i >= 6);
    rugo_obb b;
    b.center = rugo_v2(v[0], v[1]);
    b.axis[0] = rugo_v2(v[2], v[3]);
    b.axis[1] = rugo_v2(v[4], v[5]);
    b.half[0] = v[6];
    b.half[1] = v[7];
    if (!failed(r)) {
        const int axes = axes_status(v);
        if (axes == 1)
            fail_indexed(r, offset + 16, array, index, ".axis[0]", "not a unit vector, squared length",
                         v[2] * v[2] + v[3] * v[3]);
        else if (axes == 2)
            fail_indexed(r, offset + 32, array, index, ".axis[1]", "not perp(axis[0]), x =", v[4]);
    }
    return b;
}

/* ---- the arrays: a fast pass that only says whether all is well, and the reporting pass ---------- */

/* Bit patterns compared as integers: |x| <= VALUE_LIMIT <=> (bits & ~sign) <= bits(VALUE_LIMIT), which
 * also refuses NaN and infinities (their exponent is all ones); x < 0 <=> bits > sign bit alone
 * (negative zero passes, as x < 0.0 is false for it). */
#define SIGN_BIT UINT64_C(0x8000000000000000)

static uint64_t limit_bits(void) {
    const double lim = VALUE_LIMIT;
    uint64_t u;
    memcpy(&u, &lim, 8);
    return u;
}

/* 1 if the count stored reals at p all pass read_indexed's checks (nonneg: also not negative). */
static int reals_ok(const unsigned char* p, size_t count, int nonneg) {
    const uint64_t lim = limit_bits(), neg = nonneg ? SIGN_BIT : UINT64_MAX;
    uint64_t bad = 0;
    for (size_t i = 0; i < count; ++i) {
        const uint64_t u = get_u64(p + 8 * i);
        bad |= (uint64_t)((u & ~SIGN_BIT) > lim) | (uint64_t)(u > neg);
    }
    return bad == 0;
}

/* 1 if the count stored boxes at p all pass read_obb's checks. */
static int boxes_ok(const unsigned char* p, size_t count) {
    const uint64_t lim = limit_bits();
    uint64_t bad = 0;
    for (size_t k = 0; k < count; ++k, p += OBB_BYTES) {
        double v[8];
        for (int i = 0; i < 8; ++i) {
            const uint64_t u = get_u64(p + 8 * i);
            bad |= (uint64_t)((u & ~SIGN_BIT) > lim) | (uint64_t)(i >= 6 && u > SIGN_BIT);
            memcpy(&v[i], &u, 8);
        }
        bad |= (uint64_t)(axes_status(v) != 0);
    }
    return bad == 0;
}

/* Reads every array value in file order with the reporting checks: the first failure sets r. */
static void report_arrays(reader* r, const layout* L) {
    for (size_t i = 0; i < L->per && !failed(r); ++i) {
        read_indexed(r, L->points + 16 * i, "pyramid.points", i, ".x", 0);
        read_indexed(r, L->points + 16 * i + 8, "pyramid.points", i, ".y", 0);
    }
    for (size_t i = 0; i < L->det && !failed(r); ++i) {
        read_indexed(r, L->world + 16 * i, "pyramid.details", i, ".x", 0);
        read_indexed(r, L->world + 16 * i + 8, "pyramid.details", i, ".y", 0);
    }
    for (size_t i = 0; i < L->det && !failed(r); ++i) {
        read_indexed(r, L->local + 16 * i, "pyramid.local_details", i, ".x", 0);
        read_indexed(r, L->local + 16 * i + 8, "pyramid.local_details", i, ".y", 0);
    }
    static const char* const tol_names[3] = {"tolerances.own", "tolerances.total", "tolerances.bound"};
    for (size_t i = 0; i < 3 * L->per && !failed(r); ++i)
        read_indexed(r, L->tol + 8 * i, tol_names[i / L->per], i % L->per, "", 1);
    for (size_t i = 0; i < L->per && !failed(r); ++i)
        read_indexed(r, L->band + 8 * i, "band_bound", i, "", 1);
    for (size_t i = 0; i < L->levels && !failed(r); ++i)
        read_indexed(r, L->excess + 8 * i, "band_excess", i, "", 1);
    for (size_t i = 0; i < L->per && !failed(r); ++i)
        (void)read_obb(r, L->nodes + OBB_BYTES * i, "tree.nodes", i);
}

/* Checks every array value: the fast pass, and only when it finds something the reporting pass,
 * which names the first bad value in file order. The arrays are contiguous: points and details (any
 * bounded value) up to L->tol, then tolerances, band bounds and excesses (also >= 0) up to L->nodes,
 * then the boxes. */
static void check_arrays(reader* r, const layout* L) {
    if (reals_ok(r->file + L->points, (L->tol - L->points) / 8, 0) &&
        reals_ok(r->file + L->tol, (L->nodes - L->tol) / 8, 1) && boxes_ok(r->file + L->nodes, L->per))
        return;
    report_arrays(r, L);
    /* Both passes test the same conditions (axes_status is shared), so the reporting pass always
     * finds what the fast one did; should they ever disagree, the reporting pass decides. */
}

static rugo_status check_header(const unsigned char* f, size_t size, size_t* payload, rugo_baked_error* d) {
    if (size < RUGO_BAKED_MAGIC_SIZE || memcmp(f, MAGIC, RUGO_BAKED_MAGIC_SIZE) != 0) {
        if (size < RUGO_BAKED_MAGIC_SIZE && memcmp(f, MAGIC, size) == 0) {
            rugo__baked_detail(d, size, "header", "only %lu bytes, a header has %d", (unsigned long)size,
                               HEADER_SIZE);
            return RUGO_ERR_TRUNCATED;
        }
        rugo__baked_detail(d, 0, "magic", "not a baked shape file (the first 8 bytes are not \"RUGOBAKE\")");
        return RUGO_ERR_BAD_FORMAT;
    }
    if (size < HEADER_SIZE) {
        rugo__baked_detail(d, size, "header", "only %lu bytes, a header has %d", (unsigned long)size,
                           HEADER_SIZE);
        return RUGO_ERR_TRUNCATED;
    }
    const uint32_t version = get_u32(f + H_VERSION);
    if (version != RUGO_BAKED_VERSION) {
        rugo__baked_detail(d, H_VERSION, "version", "format version %lu; this library reads version %d",
                           (unsigned long)version, RUGO_BAKED_VERSION);
        return RUGO_ERR_BAD_VERSION;
    }
    const uint32_t hsize = get_u32(f + H_HEADER_SIZE);
    if (hsize != HEADER_SIZE) {
        rugo__baked_detail(d, H_HEADER_SIZE, "header_size", "%lu, must be %d", (unsigned long)hsize,
                           HEADER_SIZE);
        return RUGO_ERR_BAD_FORMAT;
    }
    for (size_t i = H_RESERVED; i < HEADER_SIZE; ++i)
        if (f[i] != 0) {
            rugo__baked_detail(d, i, "reserved", "byte %lu of the header is %u, must be 0", (unsigned long)i,
                               (unsigned)f[i]);
            return RUGO_ERR_BAD_FORMAT;
        }
    const uint64_t psize = get_u64(f + H_PAYLOAD_SIZE);
    if (psize > (uint64_t)(RUGO_MAX_BAKED_BYTES - HEADER_SIZE)) {
        rugo__baked_detail(d, H_PAYLOAD_SIZE, "payload_size", "%.0f bytes, beyond the limit of %lu",
                           (double)psize, (unsigned long)RUGO_MAX_BAKED_BYTES);
        return RUGO_ERR_TOO_LARGE;
    }
    if (psize > (uint64_t)(size - HEADER_SIZE)) {
        rugo__baked_detail(d, size, "payload_size", "the header gives %lu payload bytes, the file has %lu",
                           (unsigned long)psize, (unsigned long)(size - HEADER_SIZE));
        return RUGO_ERR_TRUNCATED;
    }
    if (psize < (uint64_t)(size - HEADER_SIZE)) {
        rugo__baked_detail(d, HEADER_SIZE + (size_t)psize, "payload_size", "%lu bytes after the payload",
                           (unsigned long)(size - HEADER_SIZE - (size_t)psize));
        return RUGO_ERR_BAD_FORMAT;
    }
    const uint64_t stored = get_u64(f + H_CHECKSUM), actual = file_checksum(f, size);
    if (stored != actual) {
        rugo__baked_detail(d, H_CHECKSUM, "checksum",
                           "stored 0x%08lx%08lx, computed 0x%08lx%08lx: the file is corrupted",
                           (unsigned long)(stored >> 32), (unsigned long)(stored & 0xFFFFFFFFu),
                           (unsigned long)(actual >> 32), (unsigned long)(actual & 0xFFFFFFFFu));
        return RUGO_ERR_CHECKSUM;
    }
    *payload = (size_t)psize;
    return RUGO_OK;
}

rugo_status rugo_shape_load_baked(const void* buffer, size_t size, const rugo_allocator* allocator,
                                  rugo_shape** out, rugo_baked_error* detail) {
    rugo__baked_clear_detail(detail);
    if (out != NULL) *out = NULL;
    if (buffer == NULL || out == NULL) {
        rugo__baked_detail(detail, 0, NULL, "NULL buffer or output");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    const unsigned char* f = (const unsigned char*)buffer;
    size_t psize = 0;
    rugo_status st = check_header(f, size, &psize, detail);
    if (st != RUGO_OK) return st;

    reader r;
    r.file = f + HEADER_SIZE;
    r.detail = detail;
    r.st = RUGO_OK;
    /* Offsets in messages are file offsets: the reader works in payload offsets, so shift on output. */
    if (psize < FIXED_SIZE) {
        rugo__baked_detail(detail, size, "payload", "%lu bytes, the fixed part alone has %d",
                           (unsigned long)psize, FIXED_SIZE);
        return RUGO_ERR_BAD_FORMAT;
    }
    const uint32_t J = get_u32(r.file + 0), Jmin = get_u32(r.file + 4);
    if (J > 20 || Jmin > 20 || !levels_ok((int)J, (int)Jmin)) {
        rugo__baked_detail(
            detail, HEADER_SIZE, "levels",
            "finest %lu, coarsest %lu: need 2 <= coarsest <= finest <= 20 (2^20 = RUGO_MAX_CONTROL_POINTS)",
            (unsigned long)J, (unsigned long)Jmin);
        return RUGO_ERR_BAD_FORMAT;
    }
    const layout L = make_layout((int)J, (int)Jmin);
    if (psize != L.end) {
        rugo__baked_detail(detail, H_PAYLOAD_SIZE, "payload_size", "%lu bytes, levels %lu..%lu need %lu",
                           (unsigned long)psize, (unsigned long)Jmin, (unsigned long)J, (unsigned long)L.end);
        return RUGO_ERR_BAD_FORMAT;
    }
    const uint32_t filter = get_u32(r.file + 8), method = get_u32(r.file + 12), flags = get_u32(r.file + 16);
    if (filter >= (uint32_t)RUGO_FILTER_COUNT || rugo_filter_name((rugo_filter)filter) == NULL) {
        rugo__baked_detail(detail, HEADER_SIZE + 8, "filter", "unknown filter %lu", (unsigned long)filter);
        return RUGO_ERR_BAD_FORMAT;
    }
    if (method != (uint32_t)RUGO_BOXES_MULTIRES && method != (uint32_t)RUGO_BOXES_OF_BOXES) {
        rugo__baked_detail(detail, HEADER_SIZE + 12, "box_method", "unknown box method %lu",
                           (unsigned long)method);
        return RUGO_ERR_BAD_FORMAT;
    }
    if ((flags & ~(FLAG_ROUGH | FLAG_REVERSED)) != 0 || get_u32(r.file + 20) != 0) {
        rugo__baked_detail(detail, HEADER_SIZE + 16, "flags", "unknown flag bits 0x%lx",
                           (unsigned long)flags);
        return RUGO_ERR_BAD_FORMAT;
    }

    rugo__shape_parts parts;
    memset(&parts, 0, sizeof parts);
    parts.finest = (int)J;
    parts.coarsest = (int)Jmin;
    parts.filter = (rugo_filter)filter;
    parts.box_method = (rugo_box_method)method;
    parts.rough = (flags & FLAG_ROUGH) != 0;
    parts.reversed = (flags & FLAG_REVERSED) != 0;
    parts.allocator = rugo__allocator_or_default(allocator);
    parts.mass.area = read_real(&r, 24, "mass.area", 1);
    parts.mass.centroid.x = read_real(&r, 32, "mass.centroid.x", 0);
    parts.mass.centroid.y = read_real(&r, 40, "mass.centroid.y", 0);
    parts.mass.inertia = read_real(&r, 48, "mass.inertia", 1);
    if (!failed(&r) && !(parts.mass.area > 0.0 && parts.mass.inertia > 0.0))
        fail(&r, 24, "mass", "area and inertia must be > 0, area", parts.mass.area);
    parts.friction.alpha = read_real(&r, 56, "friction.alpha", 1);
    parts.friction.lambda_min = read_real(&r, 64, "friction.lambda_min", 1);
    parts.friction.base = read_real(&r, 72, "friction.base", 1);
    parts.restitution.epsilon = read_real(&r, 80, "restitution.epsilon", 1);
    parts.restitution.epsilon_max = read_real(&r, 88, "restitution.epsilon_max", 1);
    if (!failed(&r) && rugo_restitution_check(&parts.restitution) != RUGO_OK)
        fail(&r, 80, "restitution", "needs 0 <= epsilon <= epsilon_max <= 1, epsilon",
             parts.restitution.epsilon);
    parts.root = read_obb(&r, 96, "tree.root", (size_t)-1);
    if (failed(&r)) {
        if (detail != NULL) detail->offset += HEADER_SIZE;
        return r.st;
    }

    /* Every array value, then what the flags and the finest level say about them. */
    check_arrays(&r, &L);
    if (!failed(&r)) {
        /* The rough flag must say what the finest λ says: is_rough would lie otherwise. */
        bool rough = false;
        const size_t fine = L.per - ((size_t)1 << J);
        for (size_t k = 0; k < ((size_t)1 << J); ++k)
            rough |= get_f64(r.file + L.tol + 8 * (L.per + fine + k)) > 0.0;
        const double finest_excess = get_f64(r.file + L.excess + 8 * (L.levels - 1));
        if (rough != parts.rough)
            fail(&r, 16, "flags", "rough flag disagrees with the finest tolerances, flag", parts.rough);
        else if (finest_excess != 0.0)
            fail(&r, L.excess + 8 * (L.levels - 1), "band_excess", "must be 0 at the finest level",
                 finest_excess);
    }
    if (failed(&r)) {
        if (detail != NULL) detail->offset += HEADER_SIZE;
        return r.st;
    }
    /* Validated: the shape decodes the arrays straight from the file into its own memory. */
    parts.points = r.file + L.points;
    parts.world = L.det > 0 ? r.file + L.world : NULL;
    parts.local = L.det > 0 ? r.file + L.local : NULL;
    parts.tolerances = r.file + L.tol;
    parts.band_bound = r.file + L.band;
    parts.band_excess = r.file + L.excess;
    parts.nodes = r.file + L.nodes;
    st = rugo__shape_create_from_parts(&parts, out);
    if (st == RUGO_ERR_OUT_OF_MEMORY) {
        rugo__baked_detail(detail, 0, NULL, "out of memory building the shape");
        return st;
    }
    if (st != RUGO_OK) {
        if (st == RUGO_ERR_BAD_SIZE)
            rugo__baked_detail(detail, HEADER_SIZE + L.points + 16 * (L.per - ((size_t)1 << J)),
                               "pyramid.points", "the finest level's size is outside [%g, %g]",
                               RUGO_SHAPE_MIN_SIZE, RUGO_SHAPE_MAX_SIZE);
        else
            rugo__baked_detail(detail, HEADER_SIZE + L.points + 16 * (L.per - ((size_t)1 << J)),
                               "pyramid.points",
                               "the finest level is not a valid counter-clockwise outline (%s)",
                               st == RUGO_ERR_BAD_ARGUMENT ? "clockwise" : rugo_status_string(st));
        return RUGO_ERR_BAD_FORMAT;
    }
    return RUGO_OK;
}
