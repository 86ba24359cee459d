/* libFuzzer target: the readers of outline files (rugo/import.h, and the CSV profile and point-list
 * readers of rugo/shape_file.h) on arbitrary text.
 *
 * The first byte chooses what reads the rest: kind = byte & 7 (5, 6, 7 wrap to 0, 1, 2), option
 * bits o = byte >> 3:
 *   0  an SVG document: rugo_svg_find_path (id by o & 3: NULL, "path1", "rock", "p"), then the path
 *      data of what it found, sampled; and rugo_svg_import_outline, which must agree with that pipeline
 *   1  SVG path data: rugo_path_parse, then rugo_outline_sample of the result (sample count by o & 3:
 *      automatic, 16, 64, 256; transform by (o >> 3) & 3: identity, y flip, rotation and scale, skew)
 *   2  an SVG transform list: rugo_svg_transform_parse
 *   3  a point list (JSON or plain lines): rugo_points_text_parse, then the closed polygon through the
 *      points, sampled
 *   4  a CSV roughness profile: rugo_roughness_profile_parse_csv, then resolved on a fixed contour
 * Seeds are prefixed with a printable selector: '@' (0x40) kind 0, 'A' kind 1, 'B' kind 2, 'C' kind 3,
 * 'D' kind 4 (all with o = 8); 'H', 'P', 'X' are kind 0 with o = 9, 10, 11 (ids "path1", "rock",
 * "p"), 'I', 'Q', 'Y' kind 1 with 16, 64, 256 samples; lower case adds 4 to o (the failing allocator).
 *
 * Properties: no crash, leak or sanitizer report; an error detail is NUL-terminated, says something,
 * and its line and column lie within the input (or are 0, 0); after success the message is empty;
 * outputs on failure are zeroed; accepted outputs are finite and within the documented counts;
 * samples are counter-clockwise with positive area and perimeter; CSV samples have s strictly
 * increasing in [0, 1] and λ finite >= 0, and resolve to segment tolerances between the smallest and
 * largest λ. With o & 4 each reader runs a second time with an allocator that fails after a few
 * allocations: the status is then the same or OUT_OF_MEMORY, the same output when it succeeds, and
 * nothing is left allocated. */
#include "fuzz_common.h"

#include <stdint.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* ---- allocator that fails after a budget, counting live blocks ---------------------------------- */

typedef struct budget {
    long left; /* allocations still allowed; < 0: unlimited */
    long live;
} budget;

static void* budget_alloc(size_t n, void* ctx) {
    budget* b = (budget*)ctx;
    if (b->left == 0) return NULL;
    if (b->left > 0) --b->left;
    void* p = malloc(n);
    if (p != NULL) ++b->live;
    return p;
}

static void budget_free(void* p, void* ctx) {
    budget* b = (budget*)ctx;
    if (p == NULL) return;
    --b->live;
    free(p);
}

static rugo_allocator budget_allocator(budget* b) {
    rugo_allocator a;
    a.alloc = budget_alloc;
    a.free = budget_free;
    a.ctx = b;
    return a;
}

/* ---- a digest of outputs, to compare two runs ------------------------------------------------------ */

static uint64_t mix(uint64_t h, const void* p, size_t n) {
    const unsigned char* c = (const unsigned char*)p;
    for (size_t i = 0; i < n; ++i) {
        h ^= c[i];
        h *= UINT64_C(0x100000001B3);
    }
    return h;
}

/* ---- shared checks ---------------------------------------------------------------------------------- */

/* The error detail after a call that returned st on text[0, n). */
static void check_error(const rugo_parse_error* e, rugo_status st, const char* text, size_t n) {
    FUZZ_CHECK(memchr(e->path, '\0', sizeof e->path) != NULL);
    FUZZ_CHECK(memchr(e->message, '\0', sizeof e->message) != NULL);
    if (st == RUGO_OK) {
        FUZZ_CHECK(e->message[0] == '\0');
        return;
    }
    FUZZ_CHECK(e->message[0] != '\0');
    if (e->line == 0) {
        FUZZ_CHECK(e->column == 0);
        return;
    }
    FUZZ_CHECK(e->line >= 1 && e->column >= 1);
    size_t start = 0;
    for (int l = 1; l < e->line; ++l) {
        const char* nl = (const char*)memchr(text + start, '\n', n - start);
        FUZZ_CHECK(nl != NULL); /* the line exists */
        start = (size_t)(nl - text) + 1;
    }
    const size_t at = start + (size_t)(e->column - 1);
    FUZZ_CHECK(at <= n);                                        /* within the input (or at its end) */
    FUZZ_CHECK(memchr(text + start, '\n', at - start) == NULL); /* and on that line */
}

/* Twice the signed area of a polygon, in coordinates relative to p[0] scaled by the bounds, in long
 * double: only its sign is used. */
static long double polygon_area2(const rugo_vec2* p, int n) {
    double lo_x = p[0].x, lo_y = p[0].y, hi_x = p[0].x, hi_y = p[0].y;
    for (int i = 1; i < n; ++i) {
        lo_x = fmin(lo_x, p[i].x);
        lo_y = fmin(lo_y, p[i].y);
        hi_x = fmax(hi_x, p[i].x);
        hi_y = fmax(hi_y, p[i].y);
    }
    long double half = fmaxl((long double)hi_x - lo_x, (long double)hi_y - lo_y);
    if (!(half > 0)) half = 1;
    long double a = 0;
    for (int i = 0; i < n; ++i) {
        const rugo_vec2 u = p[i], v = p[(i + 1) % n];
        const long double ux = ((long double)u.x - p[0].x) / half, uy = ((long double)u.y - p[0].y) / half;
        const long double vx = ((long double)v.x - p[0].x) / half, vy = ((long double)v.y - p[0].y) / half;
        a += ux * vy - uy * vx;
    }
    return a;
}

/* A successful sampling: M requested samples (0: automatic), from a path with the given subpaths. */
static uint64_t check_samples(const rugo_outline_samples* s, int M, const rugo_path* path, uint64_t h) {
    FUZZ_CHECK(s->points != NULL);
    FUZZ_CHECK(s->count >= 3 && s->count <= RUGO_MAX_CONTROL_POINTS);
    if (M > 0) FUZZ_CHECK(s->count <= M);
    for (int i = 0; i < s->count; ++i)
        FUZZ_CHECK(isfinite(s->points[i].x) && isfinite(s->points[i].y));
    for (int i = 0; i < s->count; ++i) {
        const rugo_vec2 a = s->points[i], b = s->points[(i + 1) % s->count];
        FUZZ_CHECK(a.x != b.x || a.y != b.y); /* repeats removed */
    }
    FUZZ_CHECK(isfinite(s->perimeter) && s->perimeter > 0.0);
    FUZZ_CHECK(isfinite(s->area) && s->area > 0.0);
    FUZZ_CHECK(s->reversed == 0 || s->reversed == 1);
    if (path != NULL) {
        FUZZ_CHECK(s->subpath >= 0 && s->subpath < path->subpath_count);
        FUZZ_CHECK(s->segment_count >= 1 && s->segment_count <= path->subpaths[s->subpath].count);
    }
    if (M > 0) FUZZ_CHECK(s->segment_count <= M);
    FUZZ_CHECK(polygon_area2(s->points, s->count) > 0); /* counter-clockwise */
    h = mix(h, s->points, (size_t)s->count * sizeof *s->points);
    h = mix(h, &s->perimeter, sizeof s->perimeter);
    h = mix(h, &s->area, sizeof s->area);
    h = mix(h, &s->subpath, sizeof s->subpath);
    return mix(h, &s->reversed, sizeof s->reversed);
}

/* A successfully parsed path, read from n bytes of path data (n 0: offsets not checked). */
static uint64_t check_path(const rugo_path* p, size_t n, uint64_t h) {
    FUZZ_CHECK(p->segment_count >= 0 && p->segment_count <= RUGO_MAX_PATH_SEGMENTS);
    FUZZ_CHECK(p->subpath_count >= 0 && p->subpath_count <= RUGO_MAX_PATH_SEGMENTS);
    FUZZ_CHECK((p->segment_count == 0) == (p->segments == NULL));
    FUZZ_CHECK((p->subpath_count == 0) == (p->subpaths == NULL));
    int next = 0; /* subpaths tile the segments in order */
    for (int k = 0; k < p->subpath_count; ++k) {
        const rugo_subpath* sp = &p->subpaths[k];
        FUZZ_CHECK(sp->first == next && sp->count >= 0);
        FUZZ_CHECK(sp->closed == 0 || sp->closed == 1);
        FUZZ_CHECK(isfinite(sp->start.x) && isfinite(sp->start.y));
        next += sp->count;
    }
    FUZZ_CHECK(next == p->segment_count);
    for (int i = 0; i < p->segment_count; ++i) {
        const rugo_path_segment* s = &p->segments[i];
        FUZZ_CHECK(s->kind >= RUGO_PATH_LINE && s->kind <= RUGO_PATH_ARC);
        for (int k = 0; k < 4; ++k)
            FUZZ_CHECK(isfinite(s->p[k].x) && isfinite(s->p[k].y));
        if (s->kind == RUGO_PATH_ARC) {
            FUZZ_CHECK(isfinite(s->centre.x) && isfinite(s->centre.y));
            FUZZ_CHECK(isfinite(s->rx) && s->rx > 0.0 && isfinite(s->ry) && s->ry > 0.0);
            FUZZ_CHECK(isfinite(s->phi) && isfinite(s->theta1) && isfinite(s->dtheta));
            FUZZ_CHECK(fabs(s->dtheta) <= 2.0 * 3.14159265358979323846 + 1e-12);
        }
        if (n > 0) FUZZ_CHECK(s->offset < n);
        /* The exact end points at t = 0 and 1. */
        const rugo_vec2 a = rugo_path_segment_point(s, 0.0);
        FUZZ_CHECK(a.x == s->p[0].x && a.y == s->p[0].y);
        h = mix(h, &s->kind, sizeof s->kind);
        h = mix(h, s->p, sizeof s->p);
    }
    return h;
}

/* ---- the readers ---------------------------------------------------------------------------------- */

static const rugo_affine kTransforms[4] = {
    {1.0, 0.0, 0.0, 1.0, 0.0, 0.0},
    {1.0, 0.0, 0.0, -1.0, 0.0, 0.0},
    {0.0025980762113533, 0.0015, -0.0015, 0.0025980762113533, 7.0, -3.0},
    {1.0, 0.0, 0.75, 1.0, -100.0, 0.0},
};

/* Samples a parsed path with the options; returns the status and extends *h. */
static rugo_status sample_path(const rugo_path* path, int M, rugo_affine m, rugo_allocator al, uint64_t* h) {
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.path = path;
    sd.sample_count = M;
    sd.transform = m;
    sd.allocator = al;
    rugo_outline_samples s;
    rugo_parse_error e;
    rugo_status st = rugo_outline_sample(&sd, &s, &e);
    FUZZ_CHECK(e.line == 0); /* sampling has no text to point into */
    check_error(&e, st, NULL, 0);
    if (st == RUGO_OK)
        *h = check_samples(&s, M, path, *h);
    else
        FUZZ_CHECK(s.points == NULL && s.count == 0);
    *h = mix(*h, &st, sizeof st);
    rugo_outline_samples_free(&s);
    return st;
}

static const char* const kIds[4] = {NULL, "path1", "rock", "p"};

static rugo_status read_svg(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h) {
    const char* id = kIds[o & 3];
    rugo_svg_path_element el;
    rugo_parse_error e;
    rugo_status st = rugo_svg_find_path(t, n, id, &al, &el, &e);
    check_error(&e, st, t, n);
    rugo_status pipeline = st;
    rugo_outline_samples mine;
    memset(&mine, 0, sizeof mine);
    if (st != RUGO_OK) {
        FUZZ_CHECK(el.d == NULL && el.d_length == 0);
    } else {
        FUZZ_CHECK(el.d != NULL && el.d[el.d_length] == '\0');
        FUZZ_CHECK(el.d_offset <= n && el.d_length <= n - el.d_offset);
        if (!el.d_has_entities) FUZZ_CHECK(memcmp(t + el.d_offset, el.d, el.d_length) == 0);
        FUZZ_CHECK(isfinite(el.transform.a) && isfinite(el.transform.b) && isfinite(el.transform.c) &&
                   isfinite(el.transform.d) && isfinite(el.transform.e) && isfinite(el.transform.f));
        FUZZ_CHECK(el.line >= 1 && el.column >= 1);
        *h = mix(*h, el.d, el.d_length);
        *h = mix(*h, &el.transform, sizeof el.transform);
        rugo_path path;
        pipeline = rugo_path_parse(el.d, el.d_length, &al, &path, &e);
        check_error(&e, pipeline, el.d, el.d_length);
        if (pipeline == RUGO_OK) {
            *h = check_path(&path, el.d_length, *h);
            rugo_outline_sample_def sd = rugo_default_outline_sample_def();
            sd.path = &path;
            sd.allocator = al;
            sd.sample_count = 128;
            const rugo_affine flip = {1.0, 0.0, 0.0, -1.0, 0.0, 0.0};
            sd.transform = rugo_affine_multiply(flip, el.transform);
            pipeline = rugo_outline_sample(&sd, &mine, &e);
            FUZZ_CHECK(e.line == 0);
            check_error(&e, pipeline, NULL, 0);
            if (pipeline == RUGO_OK) *h = check_samples(&mine, 128, &path, *h);
        }
        rugo_path_free(&path);
    }
    rugo_svg_path_element_free(&el);
    /* The one-call import agrees with the steps. */
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.allocator = al;
    sd.sample_count = 128;
    rugo_outline_samples s;
    rugo_status all = rugo_svg_import_outline(t, n, id, &sd, &s, &e);
    check_error(&e, all, t, n);
    if (all != RUGO_ERR_OUT_OF_MEMORY && pipeline != RUGO_ERR_OUT_OF_MEMORY) {
        FUZZ_CHECK(all == pipeline);
        if (all == RUGO_OK) {
            FUZZ_CHECK(s.count == mine.count);
            FUZZ_CHECK(memcmp(s.points, mine.points, (size_t)s.count * sizeof *s.points) == 0);
        }
    }
    if (all != RUGO_OK) FUZZ_CHECK(s.points == NULL && s.count == 0);
    rugo_outline_samples_free(&s);
    rugo_outline_samples_free(&mine);
    *h = mix(*h, &pipeline, sizeof pipeline);
    return st != RUGO_OK ? st : (pipeline == RUGO_ERR_OUT_OF_MEMORY ? pipeline : all);
}

static rugo_status read_path_data(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h) {
    static const int counts[4] = {0, 16, 64, 256};
    rugo_path p;
    rugo_parse_error e;
    rugo_status st = rugo_path_parse(t, n, &al, &p, &e);
    check_error(&e, st, t, n);
    if (st != RUGO_OK) {
        FUZZ_CHECK(p.segments == NULL && p.subpaths == NULL && p.segment_count == 0 && p.subpath_count == 0);
        FUZZ_CHECK(strcmp(e.path, "d") == 0);
        return st;
    }
    *h = check_path(&p, n, *h);
    /* The automatic count samples up to 4 per segment: keep it for small paths (time per input). */
    int M = counts[o & 3];
    if (M == 0 && p.segment_count > 256) M = 256;
    st = sample_path(&p, M, kTransforms[(o >> 3) & 3], al, h);
    rugo_path_free(&p);
    return st == RUGO_ERR_OUT_OF_MEMORY ? st : RUGO_OK;
}

static rugo_status read_transform(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h) {
    (void)o;
    (void)al;
    rugo_affine m;
    rugo_parse_error e;
    rugo_status st = rugo_svg_transform_parse(t, n, &m, &e);
    check_error(&e, st, t, n);
    if (st == RUGO_OK) {
        FUZZ_CHECK(isfinite(m.a) && isfinite(m.b) && isfinite(m.c) && isfinite(m.d) && isfinite(m.e) &&
                   isfinite(m.f));
        *h = mix(*h, &m, sizeof m);
    } else {
        FUZZ_CHECK(m.a == 1.0 && m.b == 0.0 && m.c == 0.0 && m.d == 1.0 && m.e == 0.0 && m.f == 0.0);
    }
    return st;
}

static rugo_status read_points(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h) {
    rugo_point_list list;
    rugo_parse_error e;
    rugo_status st = rugo_points_text_parse(t, n, &al, &list, &e);
    check_error(&e, st, t, n);
    if (st != RUGO_OK) {
        FUZZ_CHECK(list.points == NULL && list.count == 0);
        return st;
    }
    const rugo_vec2* pts = list.points;
    const int count = list.count;
    FUZZ_CHECK(list.allocator.alloc == al.alloc && list.allocator.ctx == al.ctx);
    FUZZ_CHECK(count >= 0 && count <= RUGO_MAX_CONTROL_POINTS);
    FUZZ_CHECK((count == 0) == (pts == NULL));
    for (int i = 0; i < count; ++i)
        FUZZ_CHECK(isfinite(pts[i].x) && isfinite(pts[i].y));
    *h = mix(*h, pts, (size_t)count * sizeof *pts);
    if (count >= 3) {
        rugo_path p;
        st = rugo_path_from_points(pts, count, &al, &p);
        FUZZ_CHECK(st == RUGO_OK || st == RUGO_ERR_OUT_OF_MEMORY);
        if (st == RUGO_OK) {
            FUZZ_CHECK(p.subpath_count == 1 && p.subpaths[0].closed);
            FUZZ_CHECK(p.segment_count <= count);
            *h = check_path(&p, 0, *h);
            st = sample_path(&p, (o & 1) ? 0 : 64, kTransforms[(o >> 1) & 3], al, h);
            if (st != RUGO_ERR_OUT_OF_MEMORY) st = RUGO_OK;
        }
        rugo_path_free(&p);
    }
    rugo_point_list_free(&list);
    return st;
}

static rugo_status read_csv(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h) {
    (void)o;
    rugo_roughness_profile profile;
    rugo_parse_error e;
    rugo_status st = rugo_roughness_profile_parse_csv(t, n, &al, &profile, &e);
    check_error(&e, st, t, n);
    if (st != RUGO_OK) {
        FUZZ_CHECK(profile.samples == NULL && profile.count == 0);
        return st;
    }
    rugo_profile_sample* p = profile.samples;
    const int count = profile.count;
    FUZZ_CHECK(profile.allocator.alloc == al.alloc && profile.allocator.ctx == al.ctx);
    FUZZ_CHECK(p != NULL && count >= 1 && count <= RUGO_MAX_PROFILE_SAMPLES);
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < count; ++i) {
        FUZZ_CHECK(isfinite(p[i].s) && p[i].s >= 0.0 && p[i].s <= 1.0);
        if (i > 0) FUZZ_CHECK(p[i].s > p[i - 1].s);
        FUZZ_CHECK(isfinite(p[i].tolerance) && p[i].tolerance >= 0.0);
        lo = fmin(lo, p[i].tolerance);
        hi = fmax(hi, p[i].tolerance);
    }
    *h = mix(*h, p, (size_t)count * sizeof *p);
    /* Resolved on an octagon: every segment's λ is a value of the piecewise-linear profile. */
    static const rugo_vec2 oct[8] = {{1, 0},  {0.7, 0.7},   {0, 1},  {-0.7, 0.7},
                                     {-1, 0}, {-0.7, -0.7}, {0, -1}, {0.7, -0.7}};
    rugo_roughness_desc r = rugo_default_roughness_desc();
    r.kind = RUGO_ROUGHNESS_PROFILE;
    r.profile = p;
    r.profile_count = count;
    rugo_contour c = {oct, 8};
    rugo_real lam[8];
    st = rugo_roughness_tolerances_on_contour(&r, c, &al, lam);
    FUZZ_CHECK(st == RUGO_OK || st == RUGO_ERR_OUT_OF_MEMORY);
    if (st == RUGO_OK) {
        for (int j = 0; j < 8; ++j)
            FUZZ_CHECK(isfinite(lam[j]) && lam[j] >= lo && lam[j] <= hi);
        *h = mix(*h, lam, sizeof lam);
    }
    rugo_roughness_profile_free(&profile);
    return st;
}

typedef rugo_status (*reader)(const char* t, size_t n, int o, rugo_allocator al, uint64_t* h);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const reader readers[5] = {read_svg, read_path_data, read_transform, read_points, read_csv};
    if (size < 1) return 0;
    const int kind = (data[0] & 7) % 5;
    const int o = data[0] >> 3;
    const char* t = (const char*)data + 1;
    const size_t n = size - 1;

    budget b1 = {-1, 0};
    uint64_t h1 = UINT64_C(0xCBF29CE484222325);
    const rugo_status s1 = readers[kind](t, n, o, budget_allocator(&b1), &h1);
    FUZZ_CHECK(b1.live == 0);
    if (s1 == RUGO_ERR_OUT_OF_MEMORY) return 0; /* malloc itself failed: nothing to compare */
    if (o & 4) {
        /* The same reader with an allocator that fails after a few allocations (how many: from the
         * input's length, so that different inputs reach different allocations). */
        budget b2 = {(long)(n % 7), 0};
        uint64_t h2 = UINT64_C(0xCBF29CE484222325);
        const rugo_status s2 = readers[kind](t, n, o, budget_allocator(&b2), &h2);
        FUZZ_CHECK(b2.live == 0);
        FUZZ_CHECK(s2 == s1 || s2 == RUGO_ERR_OUT_OF_MEMORY);
        if (s2 == s1) FUZZ_CHECK(h2 == h1);
    }
    return 0;
}
