/* Baked shapes: layout, round trips (bit-identical shapes and contacts), the loader's checks on
 * truncated, corrupted and crafted files, allocation failures, and the atomic file writer. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, opendir, getuid */

#include "rugo/rugo.h"
#include "test_util.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- helpers ---------------------------------------------------------------------------------- */

/* The checksum of docs/baked.md, written from the document byte by byte and word by word,
 * independently of the library's four-lane loop: 64-bit little-endian words (the last padded with
 * zeros, bytes 24..31 taken as zero), word i into lane i mod 4, the lanes into h = size, avalanche. */
static uint64_t ref_round(uint64_t acc, uint64_t w) {
    acc += w * UINT64_C(0xC2B2AE3D27D4EB4F);
    acc = (acc << 31) | (acc >> 33);
    return acc * UINT64_C(0x9E3779B185EBCA87);
}
static uint64_t ref_checksum(const unsigned char* p, size_t n) {
    uint64_t lane[4] = {UINT64_C(0x9E3779B185EBCA87), UINT64_C(0xC2B2AE3D27D4EB4F),
                        UINT64_C(0x165667B19E3779F9), UINT64_C(0x85EBCA77C2B2AE63)};
    for (size_t i = 0; 8 * i < n; ++i) {
        uint64_t w = 0;
        for (size_t k = 0; k < 8; ++k) {
            const size_t at = 8 * i + k;
            const unsigned char byte = at < n && (at < 24 || at >= 32) ? p[at] : 0;
            w |= (uint64_t)byte << (8 * k);
        }
        lane[i % 4] = ref_round(lane[i % 4], w);
    }
    uint64_t h = (uint64_t)n;
    for (int l = 0; l < 4; ++l)
        h = ref_round(h, lane[l]);
    h ^= h >> 33;
    h *= UINT64_C(0xC2B2AE3D27D4EB4F);
    h ^= h >> 29;
    h *= UINT64_C(0x165667B19E3779F9);
    h ^= h >> 32;
    return h;
}

static uint32_t le32(const unsigned char* p) {
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
static uint64_t le64(const unsigned char* p) { return (uint64_t)le32(p) | ((uint64_t)le32(p + 4) << 32); }
static void put32(unsigned char* p, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}
static void put64(unsigned char* p, uint64_t v) {
    for (int i = 0; i < 8; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}
static void putf64(unsigned char* p, double x) {
    uint64_t b;
    memcpy(&b, &x, 8);
    put64(p, b);
}
static double getf64(const unsigned char* p) {
    uint64_t b = le64(p);
    double x;
    memcpy(&x, &b, 8);
    return x;
}

/* Rewrites the checksum field so that a deliberately edited file reaches the field checks. */
static void refresh_checksum(unsigned char* f, size_t size) { put64(f + 24, ref_checksum(f, size)); }

/* A random rough (or smooth) star with n points; CW if asked. */
static rugo_shape* make_shape(uint64_t seed, int n, int rough, int cw, rugo_filter filter,
                              rugo_box_method method, int coarsest) {
    test_rng r = test_rng_seed(seed);
    rugo_vec2* p = (rugo_vec2*)malloc(sizeof *p * (size_t)n);
    rugo_real* lam = (rugo_real*)malloc(sizeof *lam * (size_t)n);
    test_random_star(&r, n, rugo_v2(test_rng_uniform(&r, -3, 3), test_rng_uniform(&r, -3, 3)), 1.0, 0.3, p);
    for (int i = 0; i < n; ++i)
        lam[i] = rough ? test_rng_uniform(&r, 0.0, 0.02) : 0.0;
    if (cw)
        for (int i = 0; i < n / 2; ++i) {
            rugo_vec2 t = p[i];
            p[i] = p[n - 1 - i];
            p[n - 1 - i] = t;
        }
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p;
    d.count = n;
    d.tolerances = lam;
    d.filter = filter;
    d.box_method = method;
    d.coarsest_level = coarsest;
    d.friction.alpha = 0.5 + (double)(seed % 7);
    d.restitution.epsilon = 0.25;
    rugo_shape* s = NULL;
    rugo_status st = rugo_shape_create(&d, &s, NULL);
    ck_assert_msg(st == RUGO_OK, "create: %s", rugo_status_string(st));
    free(p);
    free(lam);
    return s;
}

static unsigned char* bake(const rugo_shape* s, size_t* size) {
    ck_assert_int_eq(rugo_shape_bake_size(s, size), RUGO_OK);
    unsigned char* b = (unsigned char*)malloc(*size);
    size_t written = 0;
    ck_assert_int_eq(rugo_shape_bake(s, b, *size, &written), RUGO_OK);
    ck_assert_uint_eq(written, *size);
    return b;
}

static rugo_status load(const unsigned char* b, size_t size, rugo_baked_error* e) {
    rugo_shape* s = (rugo_shape*)&s; /* must be reset to NULL on failure */
    rugo_status st = rugo_shape_load_baked(b, size, NULL, &s, e);
    if (st == RUGO_OK)
        rugo_shape_destroy(s);
    else
        ck_assert_ptr_null(s);
    return st;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void assert_same_contacts(const rugo_contact* a, const rugo_contact* b, int n) {
    for (int i = 0; i < n; ++i) {
        ck_assert(same_bits(a[i].point_a.x, b[i].point_a.x) && same_bits(a[i].point_a.y, b[i].point_a.y));
        ck_assert(same_bits(a[i].point_b.x, b[i].point_b.x) && same_bits(a[i].point_b.y, b[i].point_b.y));
        ck_assert(same_bits(a[i].normal.x, b[i].normal.x) && same_bits(a[i].normal.y, b[i].normal.y));
        ck_assert(same_bits(a[i].separation, b[i].separation));
        ck_assert(a[i].segment_a == b[i].segment_a && a[i].segment_b == b[i].segment_b);
        ck_assert(same_bits(a[i].t_a, b[i].t_a) && same_bits(a[i].t_b, b[i].t_b));
        ck_assert(a[i].level_a == b[i].level_a && a[i].level_b == b[i].level_b);
        ck_assert(same_bits(a[i].tolerance_a, b[i].tolerance_a) &&
                  same_bits(a[i].tolerance_b, b[i].tolerance_b));
        ck_assert(same_bits(a[i].friction, b[i].friction) && same_bits(a[i].restitution, b[i].restitution));
        ck_assert(a[i].region == b[i].region && a[i].id == b[i].id);
    }
}

/* ---- layout ----------------------------------------------------------------------------------- */

START_TEST(checksum_reference) {
    /* The check values of docs/baked.md, so the reference itself is right. */
    ck_assert(ref_checksum((const unsigned char*)"123456789", 9) == UINT64_C(0x9E8530C65D0C8881));
    ck_assert(ref_checksum((const unsigned char*)"", 0) == UINT64_C(0x0E41CE6A01433AAB));
    unsigned char bytes[64];
    for (int i = 0; i < 64; ++i)
        bytes[i] = (unsigned char)i;
    ck_assert(ref_checksum(bytes, 64) == UINT64_C(0x017C827F175649C9));
}
END_TEST

START_TEST(header_layout) {
    rugo_shape* s = make_shape(1, 8, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    ck_assert_int_eq(memcmp(b, "RUGOBAKE", 8), 0);
    ck_assert_uint_eq(le32(b + 8), RUGO_BAKED_VERSION);
    ck_assert_uint_eq(le32(b + 12), 64);
    ck_assert_uint_eq(le64(b + 16), size - 64);
    for (int i = 32; i < 64; ++i)
        ck_assert_uint_eq(b[i], 0);
    /* Checksum: the whole file with its own field taken as zero (so setting it changes nothing). */
    unsigned char* c = (unsigned char*)malloc(size);
    memcpy(c, b, size);
    memset(c + 24, 0, 8);
    ck_assert(le64(b + 24) == ref_checksum(c, size));
    ck_assert(le64(b + 24) == ref_checksum(b, size));
    /* Payload: levels, filter, method, flags; then mass (docs/baked.md). */
    ck_assert_uint_eq(le32(b + 64), 3);
    ck_assert_uint_eq(le32(b + 68), 2);
    ck_assert_uint_eq(le32(b + 72), RUGO_FILTER_DEFAULT);
    ck_assert_uint_eq(le32(b + 76), RUGO_BOXES_MULTIRES);
    ck_assert_uint_eq(le32(b + 80), 1); /* rough, not reversed */
    ck_assert(same_bits(getf64(b + 64 + 24), rugo_shape_mass(s).area));
    /* Size: header 64 + fixed 160 + 112 per + 32 per detail + 8 per level (docs/baked.md). */
    const size_t per = 16 - 4, det = 8 - 4;
    ck_assert_uint_eq(size, 64 + 160 + 112 * per + 32 * det + 8 * 2);
    ck_assert(rugo_is_baked(b, size));
    ck_assert(!rugo_is_baked(b, 7));
    ck_assert(!rugo_is_baked("{\"control_points\"", 17));
    ck_assert(!rugo_is_baked(NULL, 100));
    free(c);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

/* ---- round trips -------------------------------------------------------------------------------- */

static void check_round_trip(rugo_shape* s, uint64_t seed) {
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    /* The library's four-lane checksum agrees with the word-by-word reference at every size. */
    ck_assert(le64(b + 24) == ref_checksum(b, size));
    rugo_shape* t = NULL;
    rugo_baked_error e;
    rugo_status st = rugo_shape_load_baked(b, size, NULL, &t, &e);
    ck_assert_msg(st == RUGO_OK, "load: %s: %s %s", rugo_status_string(st), e.field, e.message);
    /* Same bytes again: nothing lost, nothing invented. */
    size_t size2 = 0;
    unsigned char* b2 = bake(t, &size2);
    ck_assert_uint_eq(size, size2);
    ck_assert_int_eq(memcmp(b, b2, size), 0);
    /* Accessors, bit for bit. */
    ck_assert_int_eq(rugo_shape_finest_level(s), rugo_shape_finest_level(t));
    ck_assert_int_eq(rugo_shape_coarsest_level(s), rugo_shape_coarsest_level(t));
    ck_assert_int_eq(rugo_shape_is_rough(s), rugo_shape_is_rough(t));
    ck_assert_int_eq(rugo_shape_was_reversed(s), rugo_shape_was_reversed(t));
    ck_assert_int_eq(rugo_pyramid_was_reversed(rugo_shape_pyramid(s)),
                     rugo_pyramid_was_reversed(rugo_shape_pyramid(t)));
    rugo_mass_properties ms = rugo_shape_mass(s), mt = rugo_shape_mass(t);
    ck_assert(same_bits(ms.area, mt.area) && same_bits(ms.inertia, mt.inertia));
    ck_assert(same_bits(ms.centroid.x, mt.centroid.x) && same_bits(ms.centroid.y, mt.centroid.y));
    rugo_friction_map fs = rugo_shape_friction_map(s), ft = rugo_shape_friction_map(t);
    ck_assert(same_bits(fs.alpha, ft.alpha) && same_bits(fs.lambda_min, ft.lambda_min) &&
              same_bits(fs.base, ft.base));
    rugo_restitution rs = rugo_shape_restitution(s), rt = rugo_shape_restitution(t);
    ck_assert(same_bits(rs.epsilon, rt.epsilon) && same_bits(rs.epsilon_max, rt.epsilon_max));
    ck_assert_int_eq(rugo_pyramid_filter(rugo_shape_pyramid(s)), rugo_pyramid_filter(rugo_shape_pyramid(t)));
    ck_assert_int_eq(rugo_mobb_tree_method(rugo_shape_tree(s)), rugo_mobb_tree_method(rugo_shape_tree(t)));
    for (int j = rugo_shape_coarsest_level(s); j <= rugo_shape_finest_level(s); ++j) {
        rugo_contour cs, ct;
        rugo_shape_level(s, j, &cs);
        rugo_shape_level(t, j, &ct);
        ck_assert_int_eq(memcmp(cs.points, ct.points, sizeof(rugo_vec2) * (size_t)cs.count), 0);
        rugo_tolerance_level ls, lt;
        rugo_shape_tolerance_level(s, j, &ls);
        rugo_shape_tolerance_level(t, j, &lt);
        ck_assert_int_eq(ls.count, lt.count);
        ck_assert_int_eq(ls.level, lt.level);
        ck_assert_int_eq(memcmp(ls.own, lt.own, sizeof(rugo_real) * (size_t)ls.count), 0);
        ck_assert_int_eq(memcmp(ls.total, lt.total, sizeof(rugo_real) * (size_t)ls.count), 0);
        ck_assert_int_eq(memcmp(ls.bound, lt.bound, sizeof(rugo_real) * (size_t)ls.count), 0);
        ck_assert(same_bits(rugo_mobb_tree_level_area(rugo_shape_tree(s), j),
                            rugo_mobb_tree_level_area(rugo_shape_tree(t), j)));
    }
    ck_assert_int_eq(rugo_shape_tolerance_level(t, 1, &(rugo_tolerance_level){0}), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_shape_tolerance_level(t, 31, &(rugo_tolerance_level){0}), RUGO_ERR_BAD_LEVEL);

    /* Contacts: built and loaded shapes give the same answers, at every level and against primitives. */
    rugo_shape* other = make_shape(seed + 1000, 16, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    test_rng r = test_rng_seed(seed * 31 + 7);
    const rugo_vec2 c0 = rugo_shape_mass(s).centroid, c1 = rugo_shape_mass(other).centroid;
    int touching = 0;
    for (int trial = 0; trial < 24; ++trial) {
        const double d = test_rng_uniform(&r, 0.8, 2.4), a = test_rng_uniform(&r, 0, 6.3);
        rugo_transform xa = rugo_make_transform(-c0.x, -c0.y, 0.0);
        rugo_transform xb =
            rugo_make_transform(d * cos(a) - c1.x, d * sin(a) - c1.y, test_rng_uniform(&r, 0, 6.3));
        rugo_contact_query q = test_exact_query();
        q.lod = (trial % 3 == 2) ? -1 : 0;
        rugo_contact ca[16], cb[16];
        int na = 0, nb = 0;
        rugo_contact_state sa, sb;
        rugo_query_stats qa, qb;
        ck_assert_int_eq(test_collide_shapes(ctx, s, xa, other, xb, &q, ca, 16, &na, &sa, &qa), RUGO_OK);
        ck_assert_int_eq(test_collide_shapes(ctx, t, xa, other, xb, &q, cb, 16, &nb, &sb, &qb), RUGO_OK);
        ck_assert_int_eq(sa, sb);
        ck_assert_int_eq(na, nb);
        ck_assert_int_eq(qa.box_tests, qb.box_tests);
        ck_assert_int_eq(qa.newton_iterations, qb.newton_iterations);
        assert_same_contacts(ca, cb, na);
        touching += sa != RUGO_STATE_APART;
        ck_assert_int_eq(
            test_collide_circle(ctx, s, xa, rugo_v2(d * cos(a), d * sin(a)), 0.5, &q, ca, 16, &na, &sa, NULL),
            RUGO_OK);
        ck_assert_int_eq(
            test_collide_circle(ctx, t, xa, rugo_v2(d * cos(a), d * sin(a)), 0.5, &q, cb, 16, &nb, &sb, NULL),
            RUGO_OK);
        ck_assert_int_eq(sa, sb);
        ck_assert_int_eq(na, nb);
        assert_same_contacts(ca, cb, na);
    }
    ck_assert_int_gt(touching, 0); /* the poses do exercise contacts */
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(other);
    free(b);
    free(b2);
    rugo_shape_destroy(t);
}

START_TEST(round_trip_variants) {
    static const int counts[] = {4, 8, 16, 64, 256};
    uint64_t seed = 10;
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; ++i)
        for (int variant = 0; variant < 4; ++variant, ++seed) {
            const int n = counts[i];
            const rugo_filter f = (rugo_filter)(seed % RUGO_FILTER_COUNT);
            const rugo_box_method m = (variant & 1) ? RUGO_BOXES_OF_BOXES : RUGO_BOXES_MULTIRES;
            const int coarsest = (variant == 3 && n >= 16) ? 3 : 0;
            rugo_shape* s = make_shape(seed, n, variant != 0, variant == 2, f, m, coarsest);
            check_round_trip(s, seed);
            rugo_shape_destroy(s);
        }
}
END_TEST

START_TEST(round_trip_custom_allocator_and_file) {
    char dir[] = "/tmp/rugo_baked_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/shape.rugo", dir);
    rugo_shape* s = make_shape(77, 32, 1, 1, RUGO_FILTER_CDF4_8, RUGO_BOXES_MULTIRES, 0);
    rugo_baked_error e;
    ck_assert_int_eq(rugo_shape_write_baked_file(s, path, NULL, NULL, &e), RUGO_OK);
    struct stat stt;
    ck_assert_int_eq(stat(path, &stt), 0);
    ck_assert_int_eq(stt.st_mode & 0777, 0644);
    rugo_shape* t = NULL;
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_OK);
    size_t n1 = 0, n2 = 0;
    unsigned char *b1 = bake(s, &n1), *b2 = bake(t, &n2);
    ck_assert_uint_eq(n1, (size_t)stt.st_size);
    ck_assert_int_eq(memcmp(b1, b2, n1), 0);
    /* Writing the same shape again replaces the file with identical bytes (deterministic). */
    ck_assert_int_eq(rugo_shape_write_baked_file(t, path, NULL, NULL, &e), RUGO_OK);
    rugo_shape_destroy(t);
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_OK);
    rugo_shape_destroy(t);
    remove(path);
    rmdir(dir);
    free(b1);
    free(b2);
    rugo_shape_destroy(s);
}
END_TEST

/* ---- the loader refuses bad input -------------------------------------------------------------- */

START_TEST(load_null_and_bake_errors) {
    rugo_shape* s = make_shape(3, 8, 0, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    rugo_shape* out = NULL;
    rugo_baked_error e;
    ck_assert_int_eq(rugo_shape_load_baked(NULL, 10, NULL, &out, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_load_baked("x", 1, NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    size_t size = 0, written = 0;
    ck_assert_int_eq(rugo_shape_bake_size(NULL, &size), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_bake_size(s, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_bake_size(s, &size), RUGO_OK);
    unsigned char* b = (unsigned char*)malloc(size);
    ck_assert_int_eq(rugo_shape_bake(NULL, b, size, &written), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_bake(s, NULL, size, &written), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_bake(s, b, size, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_bake(s, b, size - 1, &written), RUGO_ERR_TOO_LARGE);
    ck_assert_uint_eq(written, size); /* tells the capacity needed */
    ck_assert_int_eq(rugo_shape_write_baked_file(NULL, "x", NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_write_baked_file(s, NULL, NULL, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_read_baked_file(NULL, NULL, &out, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_read_baked_file("x", NULL, NULL, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_read_baked_file("/nonexistent/dir/shape.rugo", NULL, &out, &e), RUGO_ERR_IO);
    ck_assert_ptr_null(out);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

START_TEST(load_truncated_every_length) {
    rugo_shape* s = make_shape(4, 8, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    rugo_baked_error e;
    for (size_t n = 0; n < size; ++n) {
        /* A fresh copy of exactly n bytes, so that ASan sees any read past the end. */
        unsigned char* c = (unsigned char*)malloc(n > 0 ? n : 1);
        memcpy(c, b, n);
        rugo_status st = load(c, n, &e);
        ck_assert_msg(st == RUGO_ERR_TRUNCATED, "length %zu: %s", n, rugo_status_string(st));
        free(c);
    }
    ck_assert_int_eq(load(b, size, &e), RUGO_OK);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

START_TEST(load_every_bit_flip_refused) {
    rugo_shape* s = make_shape(5, 4, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    rugo_baked_error e;
    for (size_t i = 0; i < size; ++i)
        for (int bit = 0; bit < 8; ++bit) {
            b[i] ^= (unsigned char)(1u << bit);
            rugo_status st = load(b, size, &e);
            ck_assert_msg(st != RUGO_OK, "byte %zu bit %d accepted", i, bit);
            /* The checksum detects every error within one 8-byte word, so past the header checks it is
             * CHECKSUM. */
            if (i >= 64 || (i >= 24 && i < 32)) ck_assert_int_eq(st, RUGO_ERR_CHECKSUM);
            b[i] ^= (unsigned char)(1u << bit);
        }
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

START_TEST(load_header_errors) {
    rugo_shape* s = make_shape(6, 8, 0, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    unsigned char* c = (unsigned char*)malloc(size + 8);
    rugo_baked_error e;
#define RESET() memcpy(c, b, size)
    RESET();
    c[0] = '{';
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "magic");
    ck_assert_int_eq(load((const unsigned char*)"{\"control_points\": []}", 22, &e), RUGO_ERR_BAD_FORMAT);
    RESET();
    put32(c + 8, 2);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_VERSION);
    ck_assert_str_eq(e.field, "version");
    ck_assert_uint_eq(e.offset, 8);
    RESET();
    put32(c + 8, 0);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_VERSION);
    RESET();
    put32(c + 12, 65);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "header_size");
    RESET();
    c[40] = 1;
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "reserved");
    ck_assert_uint_eq(e.offset, 40);
    RESET();
    put64(c + 16, (uint64_t)1 << 40);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_TOO_LARGE);
    RESET();
    put64(c + 16, UINT64_MAX);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_TOO_LARGE);
    RESET();
    put64(c + 16, le64(b + 16) + 1);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_TRUNCATED);
    /* Bytes after the payload. */
    RESET();
    memset(c + size, 0, 8);
    ck_assert_int_eq(load(c, size + 8, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "payload_size");
    /* A consistent header with a shorter payload than the levels need (checksum refreshed). */
    RESET();
    put64(c + 16, le64(b + 16) - 8);
    refresh_checksum(c, size - 8);
    ck_assert_int_eq(load(c, size - 8, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "payload_size");
    RESET();
    put64(c + 24, le64(b + 24) ^ ((uint64_t)1 << 63));
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_CHECKSUM);
    ck_assert_str_eq(e.field, "checksum");
#undef RESET
    free(c);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

/* Each case edits one field of a valid 8-point rough file, refreshes the checksum and expects
 * BAD_FORMAT naming the field (prefix) at the given file offset (0: not checked). */
typedef struct field_case {
    const char* name;
    size_t offset; /* where to write */
    int is_u32;
    uint32_t u;
    double x;
    const char* field; /* expected prefix of detail.field */
} field_case;

START_TEST(load_field_errors) {
    rugo_shape* s = make_shape(8, 8, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    /* Layout for J = 3, J_min = 2: per = 12, det = 4 (docs/baked.md). */
    const size_t P = 64, per = 12, det = 4;
    const size_t points = P + 160, world = points + 16 * per, local = world + 16 * det,
                 tol = local + 16 * det;
    const size_t band = tol + 24 * per, excess = band + 8 * per, nodes = excess + 16;
    ck_assert_uint_eq(nodes + 64 * per, size);
    const field_case cases[] = {
        {"finest 21", P + 0, 1, 21, 0, "levels"},
        {"finest 1", P + 0, 1, 1, 0, "levels"},
        {"coarsest 1", P + 4, 1, 1, 0, "levels"},
        {"coarsest > finest", P + 4, 1, 4, 0, "levels"},
        {"huge finest", P + 0, 1, 0xFFFFFFFFu, 0, "levels"},
        {"filter", P + 8, 1, RUGO_FILTER_COUNT, 0, "filter"},
        {"box method", P + 12, 1, 2, 0, "box_method"},
        {"unknown flag", P + 16, 1, 1u | 4u, 0, "flags"},
        {"rough flag wrong", P + 16, 1, 0, 0, "flags"},
        {"reserved word", P + 20, 1, 1, 0, "flags"},
        {"area NaN", P + 24, 0, 0, NAN, "mass.area"},
        {"area negative", P + 24, 0, 0, -1.0, "mass.area"},
        {"area zero", P + 24, 0, 0, 0.0, "mass"},
        {"centroid inf", P + 32, 0, 0, INFINITY, "mass.centroid.x"},
        {"inertia huge", P + 48, 0, 0, 1e200, "mass.inertia"},
        {"alpha negative", P + 56, 0, 0, -0.5, "friction.alpha"},
        {"lambda_min NaN", P + 64, 0, 0, NAN, "friction.lambda_min"},
        {"base negative", P + 72, 0, 0, -1.0, "friction.base"},
        {"epsilon > 1", P + 80, 0, 0, 1.5, "restitution"},
        {"epsilon > epsilon_max", P + 80, 0, 0, 0.95, "restitution"},
        {"root axis not unit", P + 96 + 16, 0, 0, 0.5, "tree.root"},
        {"root half negative", P + 96 + 48, 0, 0, -1.0, "tree.root.half"},
        {"point NaN", points + 16 * 5 + 8, 0, 0, NAN, "pyramid.points[5].y"},
        {"point huge", points, 0, 0, 1e151, "pyramid.points[0].x"},
        {"detail inf", world + 16, 0, 0, -INFINITY, "pyramid.details[1].x"},
        {"local detail NaN", local + 8, 0, 0, NAN, "pyramid.local_details[0].y"},
        {"own negative", tol + 8 * 2, 0, 0, -1e-9, "tolerances.own[2]"},
        {"total NaN", tol + 8 * (per + 3), 0, 0, NAN, "tolerances.total[3]"},
        {"bound negative", tol + 8 * (2 * per + 11), 0, 0, -0.1, "tolerances.bound[11]"},
        {"band bound NaN", band + 8 * 7, 0, 0, NAN, "band_bound[7]"},
        {"band excess negative", excess, 0, 0, -1.0, "band_excess[0]"},
        {"finest band excess", excess + 8, 0, 0, 0.5, "band_excess"},
        {"node centre NaN", nodes + 64 * 3, 0, 0, NAN, "tree.nodes[3].center.x"},
        {"node axis not unit", nodes + 64 * 4 + 16, 0, 0, 2.0, "tree.nodes[4].axis[0]"},
        {"node axes not perpendicular", nodes + 64 * 4 + 32, 0, 0, 0.25, "tree.nodes[4].axis[1]"},
        {"node half negative", nodes + 64 * 11 + 56, 0, 0, -1e-300, "tree.nodes[11].half[1]"},
    };
    unsigned char* c = (unsigned char*)malloc(size);
    rugo_baked_error e;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const field_case* k = &cases[i];
        memcpy(c, b, size);
        if (k->is_u32)
            put32(c + k->offset, k->u);
        else
            putf64(c + k->offset, k->x);
        refresh_checksum(c, size);
        rugo_status st = load(c, size, &e);
        ck_assert_msg(st == RUGO_ERR_BAD_FORMAT, "%s: %s", k->name, rugo_status_string(st));
        ck_assert_msg(strncmp(e.field, k->field, strlen(k->field)) == 0, "%s: field '%s', expected '%s'",
                      k->name, e.field, k->field);
        ck_assert_msg(e.message[0] != '\0', "%s: no message", k->name);
        if (!k->is_u32 && strcmp(k->name, "area zero") != 0 &&
            strcmp(k->name, "epsilon > epsilon_max") != 0 && strcmp(k->name, "epsilon > 1") != 0 &&
            strstr(k->name, "axis") == NULL && strstr(k->name, "perp") == NULL &&
            strcmp(k->name, "finest band excess") != 0)
            ck_assert_msg(e.offset == k->offset, "%s: offset %zu, expected %zu", k->name, e.offset,
                          k->offset);
    }
    /* A clockwise finest level (reversed in place, coarse levels left) and a collinear one: both are
     * caught by the outline check of the loader. */
    memcpy(c, b, size);
    const size_t fine = points + 16 * 4;
    for (int i = 0; i < 4; ++i) {
        unsigned char t[16];
        memcpy(t, c + fine + 16 * (size_t)i, 16);
        memcpy(c + fine + 16 * (size_t)i, c + fine + 16 * (size_t)(7 - i), 16);
        memcpy(c + fine + 16 * (size_t)(7 - i), t, 16);
    }
    refresh_checksum(c, size);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_str_eq(e.field, "pyramid.points");
    memcpy(c, b, size);
    for (int i = 0; i < 8; ++i) {
        putf64(c + fine + 16 * (size_t)i, (double)i);
        putf64(c + fine + 16 * (size_t)i + 8, 2.0 * i);
    }
    refresh_checksum(c, size);
    ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert(strstr(e.message, "zero area") != NULL || strstr(e.message, "area") != NULL);
    /* A finest level scaled below RUGO_SHAPE_MIN_SIZE or above RUGO_SHAPE_MAX_SIZE (the rest left as it
     * is): refused by the shape's size check, which rugo_shape_create makes too. */
    const double factors[2] = {1e-40, 1e40};
    for (int f = 0; f < 2; ++f) {
        memcpy(c, b, size);
        for (size_t i = 0; i < 16; ++i)
            putf64(c + fine + 8 * i, factors[f] * getf64(b + fine + 8 * i));
        refresh_checksum(c, size);
        ck_assert_int_eq(load(c, size, &e), RUGO_ERR_BAD_FORMAT);
        ck_assert_str_eq(e.field, "pyramid.points");
        ck_assert_msg(strstr(e.message, "size is outside") != NULL, "%s", e.message);
    }
    free(c);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

/* An allocator that fails after `budget` allocations and counts live blocks. */
typedef struct budget {
    int budget;
    int live;
} budget;
static void* budget_alloc(size_t n, void* ctx) {
    budget* b = (budget*)ctx;
    if (b->budget-- <= 0) return NULL;
    void* p = malloc(n);
    if (p != NULL) ++b->live;
    return p;
}
static void budget_free(void* p, void* ctx) {
    if (p != NULL) --((budget*)ctx)->live;
    free(p);
}

START_TEST(load_out_of_memory) {
    rugo_shape* s = make_shape(9, 16, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_OF_BOXES, 0);
    size_t size = 0;
    unsigned char* b = bake(s, &size);
    int ok_at = -1;
    for (int k = 0; k < 64 && ok_at < 0; ++k) {
        budget ctx = {k, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_shape* t = NULL;
        rugo_baked_error e;
        rugo_status st = rugo_shape_load_baked(b, size, &a, &t, &e);
        if (st == RUGO_OK) {
            ok_at = k;
            rugo_shape_destroy(t);
        } else {
            ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
            ck_assert_ptr_null(t);
        }
        ck_assert_int_eq(ctx.live, 0);
    }
    ck_assert_int_gt(ok_at, 0);
    /* The file functions too. */
    char dir[] = "/tmp/rugo_baked_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/s.rugo", dir);
    for (int k = 0; k < 3; ++k) {
        budget ctx = {k, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_status st = rugo_shape_write_baked_file(s, path, &a, NULL, NULL);
        ck_assert(st == RUGO_ERR_OUT_OF_MEMORY || (k >= 2 && st == RUGO_OK));
        ck_assert_int_eq(ctx.live, 0);
    }
    ck_assert_int_eq(rugo_shape_write_baked_file(s, path, NULL, NULL, NULL), RUGO_OK);
    for (int k = 0; k < 64; ++k) {
        budget ctx = {k, 0};
        rugo_allocator a = {budget_alloc, budget_free, &ctx};
        rugo_shape* t = NULL;
        rugo_status st = rugo_shape_read_baked_file(path, &a, &t, NULL);
        ck_assert(st == RUGO_ERR_OUT_OF_MEMORY || st == RUGO_OK);
        if (st == RUGO_OK) {
            ck_assert_int_gt(ctx.live, 0);
            rugo_shape_destroy(t);
        }
        ck_assert_int_eq(ctx.live, 0);
        if (st == RUGO_OK) break;
    }
    remove(path);
    rmdir(dir);
    free(b);
    rugo_shape_destroy(s);
}
END_TEST

/* ---- atomic writes ------------------------------------------------------------------------------ */

static int count_entries(const char* dir) {
    DIR* d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    int n = 0;
    struct dirent* e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) ++n;
    closedir(d);
    return n;
}

static unsigned char* slurp(const char* path, size_t* n) {
    FILE* f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    unsigned char* buf = (unsigned char*)malloc(1 << 20);
    *n = fread(buf, 1, 1 << 20, f);
    fclose(f);
    return buf;
}

typedef struct full_disk {
    size_t left; /* bytes still accepted */
    int calls;
} full_disk;
static size_t full_disk_write(const void* data, size_t size, void* ctx) {
    (void)data;
    full_disk* d = (full_disk*)ctx;
    ++d->calls;
    const size_t n = size < d->left ? size : d->left;
    d->left -= n;
    return n;
}

START_TEST(write_failure_leaves_destination) {
    char dir[] = "/tmp/rugo_baked_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/shape.rugo", dir);
    rugo_shape* old_shape = make_shape(11, 8, 0, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    rugo_shape* big = make_shape(12, 1024, 1, 0, RUGO_FILTER_DEFAULT, RUGO_BOXES_MULTIRES, 0);
    rugo_baked_error e;
    ck_assert_int_eq(rugo_shape_write_baked_file(old_shape, path, NULL, NULL, &e), RUGO_OK);
    size_t n_old = 0;
    unsigned char* before = slurp(path, &n_old);
    /* A disk that fills after 0, 100 and 70000 bytes (mid-chunk, second chunk): IO, destination intact,
     * no temporary file left. */
    const size_t fills[] = {0, 100, 70000};
    for (size_t i = 0; i < 3; ++i) {
        full_disk d = {fills[i], 0};
        rugo_baked_write_hook hook = {full_disk_write, &d};
        ck_assert_int_eq(rugo_shape_write_baked_file(big, path, NULL, &hook, &e), RUGO_ERR_IO);
        ck_assert_ptr_nonnull(strstr(e.message, "write failed"));
        ck_assert_int_gt(d.calls, 0);
        size_t n_now = 0;
        unsigned char* now = slurp(path, &n_now);
        ck_assert_uint_eq(n_now, n_old);
        ck_assert_int_eq(memcmp(now, before, n_old), 0);
        free(now);
        ck_assert_int_eq(count_entries(dir), 1);
    }
    /* A hook that accepts everything: the write goes through. */
    full_disk d = {(size_t)1 << 30, 0};
    rugo_baked_write_hook hook = {full_disk_write, &d};
    ck_assert_int_eq(rugo_shape_write_baked_file(big, path, NULL, &hook, &e), RUGO_OK);
    ck_assert_int_eq(count_entries(dir), 1);
    rugo_shape* t = NULL;
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_OK);
    ck_assert_int_eq(rugo_shape_finest_level(t), 10);
    rugo_shape_destroy(t);

    /* Destination is a directory: rename fails, the temporary file is removed. */
    char sub[300];
    snprintf(sub, sizeof sub, "%s/adir", dir);
    ck_assert_int_eq(mkdir(sub, 0755), 0);
    ck_assert_int_eq(rugo_shape_write_baked_file(big, sub, NULL, NULL, &e), RUGO_ERR_IO);
    ck_assert_int_eq(count_entries(dir), 2);
    rmdir(sub);
    /* A directory that does not exist, and a path through a regular file. */
    char bad[300];
    snprintf(bad, sizeof bad, "%s/missing/shape.rugo", dir);
    ck_assert_int_eq(rugo_shape_write_baked_file(big, bad, NULL, NULL, &e), RUGO_ERR_IO);
    ck_assert_ptr_nonnull(strstr(e.message, "temporary"));
    snprintf(bad, sizeof bad, "%s/x", path);
    ck_assert_int_eq(rugo_shape_write_baked_file(big, bad, NULL, NULL, &e), RUGO_ERR_IO);
    /* An unwritable directory (root ignores permissions, so only as another user). */
    if (geteuid() != 0) {
        ck_assert_int_eq(chmod(dir, 0555), 0);
        ck_assert_int_eq(rugo_shape_write_baked_file(big, path, NULL, NULL, &e), RUGO_ERR_IO);
        ck_assert_int_eq(chmod(dir, 0755), 0);
        size_t n_now = 0;
        unsigned char* now = slurp(path, &n_now);
        ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_OK);
        rugo_shape_destroy(t);
        free(now);
    }
    ck_assert_int_eq(count_entries(dir), 1);
    remove(path);
    rmdir(dir);
    free(before);
    rugo_shape_destroy(old_shape);
    rugo_shape_destroy(big);
}
END_TEST

START_TEST(read_file_errors) {
    char dir[] = "/tmp/rugo_baked_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/junk.rugo", dir);
    FILE* f = fopen(path, "wb");
    fputs("{\"control_points\": [[0,0],[1,0],[1,1],[0,1]]}", f);
    fclose(f);
    rugo_shape* t = NULL;
    rugo_baked_error e;
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_ERR_BAD_FORMAT);
    ck_assert_ptr_null(t);
    f = fopen(path, "wb"); /* empty: shorter than a header */
    fclose(f);
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_ERR_TRUNCATED);
    f = fopen(path, "wb");
    fputs("RUGOBA", f);
    fclose(f);
    ck_assert_int_eq(rugo_shape_read_baked_file(path, NULL, &t, &e), RUGO_ERR_TRUNCATED);
    ck_assert_int_eq(rugo_shape_read_baked_file(dir, NULL, &t, &e) != RUGO_OK, 1); /* a directory */
    remove(path);
    rmdir(dir);
}
END_TEST

/* rugo_shape_load_file: one call from a JSON or baked asset to a shape, with errors that name the
 * field, the value and a way out. */
static void write_text(const char* path, const char* text) {
    FILE* f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
}

START_TEST(load_file_json_and_baked) {
    char dir[] = "/tmp/rugo_load_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char json[256], baked[256], npot[256], big[256], bad[256];
    snprintf(json, sizeof json, "%s/rock.json", dir);
    snprintf(baked, sizeof baked, "%s/rock.rugo", dir);
    snprintf(npot, sizeof npot, "%s/five.json", dir);
    snprintf(big, sizeof big, "%s/overflow.json", dir);
    snprintf(bad, sizeof bad, "%s/syntax.json", dir);
    write_text(json, "{\"control_points\": [[1, 0], [0.7, 0.7], [0, 1], [-0.7, 0.7], [-1, 0], [-0.7, -0.7], "
                     "[0, -1], [0.7, -0.7]], \"roughness\": {\"constant\": 0.002}}");
    rugo_shape* s = NULL;
    rugo_parse_error e;
    ck_assert_int_eq(rugo_shape_load_file(json, NULL, &s, &e), RUGO_OK);
    ck_assert_int_eq(rugo_shape_finest_level(s), 3);
    rugo_tolerance_level t;
    rugo_shape_tolerance_level(s, 3, &t);
    ck_assert(t.total[0] == 0.002);
    /* the default friction map (metres): a 2 mm band is not frictionless */
    const rugo_friction_map fm = rugo_shape_friction_map(s);
    ck_assert_near(rugo_friction(&fm, 0.002), 0.3 + 0.6 * 1.5 / 5.5, 1e-12);
    rugo_baked_error be;
    ck_assert_int_eq(rugo_shape_write_baked_file(s, baked, NULL, NULL, &be), RUGO_OK);
    rugo_shape* b = NULL;
    ck_assert_int_eq(rugo_shape_load_file(baked, NULL, &b, &e), RUGO_OK);
    ck_assert(rugo_shape_mass(b).area == rugo_shape_mass(s).area);
    rugo_shape_destroy(b);
    rugo_shape_destroy(s);
    /* 5 control points: the count, and which counts to refit with */
    write_text(npot, "{\"control_points\": [[1, 0], [0.3, 0.9], [-0.8, 0.6], [-0.8, -0.6], [0.3, -0.9]]}");
    s = (rugo_shape*)1;
    ck_assert_int_eq(rugo_shape_load_file(npot, NULL, &s, &e), RUGO_ERR_NOT_POWER_OF_TWO);
    ck_assert_ptr_null(s);
    ck_assert_str_eq(e.path, "control_points");
    ck_assert_ptr_nonnull(strstr(e.message, "has 5 points"));
    ck_assert_ptr_nonnull(strstr(e.message, "refit the outline with 4 or 8"));
    /* coordinates whose area overflows: the field and a way out */
    write_text(big, "{\"control_points\": [[1e300, 0], [0, 1e300], [-1e300, 0], [0, -1e300]]}");
    ck_assert_int_eq(rugo_shape_load_file(big, NULL, &s, &e), RUGO_ERR_NOT_FINITE);
    ck_assert_str_eq(e.path, "control_points");
    ck_assert_ptr_nonnull(strstr(e.message, "area overflows"));
    /* a JSON error keeps its position */
    write_text(bad, "{\"control_points\": [[0, 0],\n [1, 0] [1, 1]]}");
    ck_assert_int_eq(rugo_shape_load_file(bad, NULL, &s, &e), RUGO_ERR_PARSE);
    ck_assert_int_eq(e.line, 2);
    /* a corrupted baked file: the byte and the field */
    FILE* f = fopen(baked, "r+b");
    fseek(f, 100, SEEK_SET);
    fputc(0x55, f);
    fclose(f);
    ck_assert_int_ne(rugo_shape_load_file(baked, NULL, &s, &e), RUGO_OK);
    ck_assert_ptr_nonnull(strstr(e.message, "byte "));
    /* no file; NULLs */
    char missing[300];
    snprintf(missing, sizeof missing, "%s/missing.json", dir);
    ck_assert_int_eq(rugo_shape_load_file(missing, NULL, &s, &e), RUGO_ERR_IO);
    ck_assert_int_eq(rugo_shape_load_file(NULL, NULL, &s, &e), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_load_file(json, NULL, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    remove(json);
    remove(baked);
    remove(npot);
    remove(big);
    remove(bad);
    rmdir(dir);
}
END_TEST

int main(void) {
    Suite* s = suite_create("baked");
    TCase* layout = tcase_create("layout");
    tcase_add_test(layout, checksum_reference);
    tcase_add_test(layout, header_layout);
    suite_add_tcase(s, layout);
    TCase* rt = tcase_create("round_trip");
    tcase_set_timeout(rt, 300);
    tcase_add_test(rt, round_trip_variants);
    tcase_add_test(rt, round_trip_custom_allocator_and_file);
    suite_add_tcase(s, rt);
    TCase* bad = tcase_create("bad_input");
    tcase_set_timeout(bad, 300);
    tcase_add_test(bad, load_null_and_bake_errors);
    tcase_add_test(bad, load_truncated_every_length);
    tcase_add_test(bad, load_every_bit_flip_refused);
    tcase_add_test(bad, load_header_errors);
    tcase_add_test(bad, load_field_errors);
    tcase_add_test(bad, load_out_of_memory);
    tcase_add_test(bad, read_file_errors);
    suite_add_tcase(s, bad);
    TCase* files = tcase_create("files");
    tcase_add_test(files, write_failure_leaves_destination);
    tcase_add_test(files, load_file_json_and_baked);
    suite_add_tcase(s, files);
    return test_run_suite(s);
}
