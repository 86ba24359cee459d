/* Where an imported outline crosses itself (rugo_path_find_crossing): the diagnosis behind "the outline
 * crosses itself near (x, y)" when sampling finds a bow-tie or figure eight, whose lobes cancel to zero
 * area. A plain O(N^2) test of a polyline through the segments: it runs only on that error path. */
#include "rugo/import.h"

#include "core/internal.h"

/* Points per curved segment of the polyline: enough to resolve a crossing of two cubics unless they
 * graze each other. */
#define CROSSING_POINTS_PER_CURVE 16
/* Polylines longer than this are not searched (the test is quadratic). */
#define CROSSING_MAX_POINTS 16384

static double cross3(rugo_vec2 o, rugo_vec2 a, rugo_vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/* Edges p0p1 and q0q1 cross properly (each one's ends strictly on both sides of the other). */
static int proper_crossing(rugo_vec2 p0, rugo_vec2 p1, rugo_vec2 q0, rugo_vec2 q1, rugo_vec2* where) {
    const double d0 = cross3(p0, p1, q0), d1 = cross3(p0, p1, q1);
    const double d2 = cross3(q0, q1, p0), d3 = cross3(q0, q1, p1);
    if (!((d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0))) return 0;
    if (!((d2 > 0.0 && d3 < 0.0) || (d2 < 0.0 && d3 > 0.0))) return 0;
    const double t = d0 / (d0 - d1);
    *where = rugo_v2(q0.x + t * (q1.x - q0.x), q0.y + t * (q1.y - q0.y));
    return 1;
}

static int subpath_crossing(const rugo_path* path, int s, rugo_affine transform, rugo_vec2* where) {
    const rugo_subpath* sp = &path->subpaths[s];
    if (sp->count <= 0 || sp->first < 0 || sp->first + sp->count > path->segment_count) return 0;
    long n = 0;
    for (int k = 0; k < sp->count; ++k)
        n += path->segments[sp->first + k].kind == RUGO_PATH_LINE ? 1 : CROSSING_POINTS_PER_CURVE;
    if (n < 3 || n > CROSSING_MAX_POINTS) return 0;
    rugo_allocator al = rugo_default_allocator();
    rugo_vec2* pts = (rugo_vec2*)rugo__alloc_array(&al, (size_t)n + 1, sizeof *pts);
    if (pts == NULL) return 0;
    long m = 0;
    for (int k = 0; k < sp->count; ++k) {
        const rugo_path_segment* seg = &path->segments[sp->first + k];
        const int steps = seg->kind == RUGO_PATH_LINE ? 1 : CROSSING_POINTS_PER_CURVE;
        for (int i = 0; i < steps; ++i)
            pts[m++] = rugo_affine_apply(transform, rugo_path_segment_point(seg, (double)i / steps));
    }
    pts[m] = pts[0]; /* closed */
    int found = 0;
    for (long i = 0; i < m && !found; ++i)
        for (long j = i + 2; j < m && !found; ++j) {
            if (i == 0 && j == m - 1) continue; /* the closing edge meets the first at pts[0] */
            found = proper_crossing(pts[i], pts[i + 1], pts[j], pts[j + 1], where);
        }
    rugo__free(&al, pts);
    return found;
}

int rugo_path_find_crossing(const rugo_path* path, int subpath, rugo_affine transform, rugo_vec2* where) {
    if (path == NULL || where == NULL || path->subpaths == NULL || path->segments == NULL) return 0;
    if (subpath >= path->subpath_count) return 0;
    for (int s = subpath < 0 ? 0 : subpath; s < (subpath < 0 ? path->subpath_count : subpath + 1); ++s)
        if (subpath_crossing(path, s, transform, where)) return 1;
    return 0;
}
