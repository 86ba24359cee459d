/* Arc-length sampling of one closed subpath of a path (rugo_outline_sample, import.h): adaptive
 * Gauss-Kronrod arc length per segment (rugo__arc_length), samples shared among the segments by
 * largest remainders, each placed by inverting the arc length, then the sample polygon's orientation
 * and area, all under the def's affine map. */
#include "rugo/import.h"

#include "core/internal.h"
#include "curve/internal.h" /* path segments, rugo__affine_finite, RUGO__OUTLINE_SAMPLE_DEF_COOKIE */

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void clear_error(rugo_parse_error* e) {
    if (e != NULL) memset(e, 0, sizeof *e);
}

/* A segment seen through an affine map. */
typedef struct mapped {
    const rugo_path_segment* s;
    rugo_affine m;
} mapped;

static rugo_vec2 mapped_point(const mapped* g, double t) {
    return rugo_affine_apply(g->m, rugo__path_segment_point(g->s, t));
}

static double mapped_speed(const mapped* g, double t) {
    rugo_vec2 d = rugo__path_segment_derivative(g->s, t);
    return hypot(g->m.a * d.x + g->m.c * d.y, g->m.b * d.x + g->m.d * d.y);
}

/* 8-point Gauss-Legendre on [-1, 1]: nodes ±x_i, weights w_i. */
static const double kGLx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
static const double kGLw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};

static double speed_of(const void* g, double t) { return mapped_speed((const mapped*)g, t); }

/* A segment's arc length by rugo__arc_length (curve/internal.h), to RUGO__ARC_REL_TOL, its pieces
 * kept for placing samples. Lines, quadratics and cubics have a quadratic derivative (under the map
 * too): fitted through t = 0, 1/2, 1, it gives the speed's near-zero minima to split at; an arc's
 * speed never comes near zero. */
static void mapped_arc(const mapped* g, rugo__arc* arc) {
    double breaks[RUGO__ARC_MAX_BREAKS];
    int nb = 0;
    if (g->s->kind != RUGO_PATH_ARC) {
        rugo_vec2 d[3];
        for (int i = 0; i < 3; ++i) {
            const rugo_vec2 u = rugo__path_segment_derivative(g->s, 0.5 * i);
            d[i] = rugo_v2(g->m.a * u.x + g->m.c * u.y, g->m.b * u.x + g->m.d * u.y);
        }
        /* d(t) = d0 + b t + c t^2 with d(1/2) = d0 + b/2 + c/4 and d(1) = d0 + b + c. */
        const rugo_vec2 c =
            rugo_v2(2.0 * (d[0].x - 2.0 * d[1].x + d[2].x), 2.0 * (d[0].y - 2.0 * d[1].y + d[2].y));
        const rugo_vec2 bb = rugo_v2(d[2].x - d[0].x - c.x, d[2].y - d[0].y - c.y);
        if (rugo__v2_finite(c) && rugo__v2_finite(bb) && rugo__v2_finite(d[0]))
            nb = rugo__arc_speed_breaks(d[0], bb, c, breaks);
    }
    rugo__arc_length(speed_of, g, breaks, nb, RUGO__ARC_REL_TOL, 0.0, arc);
}

static double mapped_length(const mapped* g) {
    rugo__arc arc;
    mapped_arc(g, &arc);
    return arc.length;
}

/* The parameter t in [a, b] where the arc length from the segment's start reaches target, given the
 * length s_a at a: safeguarded Newton on s_a + L(a, t) - target (bisection when a step leaves the
 * bracket or the speed vanishes). */
static double invert_arc_length(const mapped* g, double a, double b, double s_a, double len, double target) {
    double lo = a, hi = b;
    double frac = len > 0.0 ? (target - s_a) / len : 0.5;
    frac = frac < 0.0 ? 0.0 : (frac > 1.0 ? 1.0 : frac);
    double t = a + (b - a) * frac;
    for (int it = 0; it < 200; ++it) {
        const double f = s_a + rugo__arc_gk15(speed_of, g, a, t, NULL) - target;
        if (f == 0.0) break;
        if (f > 0.0)
            hi = t;
        else
            lo = t;
        const double v = mapped_speed(g, t);
        double tn = v > 0.0 ? t - f / v : 0.5 * (lo + hi);
        if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
        const double step = fabs(tn - t);
        t = tn;
        if (step <= 1e-15 || hi - lo <= 1e-15) break;
    }
    return t;
}

/* Signed area of a subpath under m (for choosing the outer boundary): (1/2) ∮ x dy - y dx relative to
 * the start point, each segment by 8-point Gauss-Legendre on four pieces. */
static double subpath_area(const rugo_path* path, const rugo_subpath* sp, const rugo_affine* m) {
    const rugo_vec2 o = rugo_affine_apply(*m, sp->start);
    double area = 0.0;
    for (int k = 0; k < sp->count; ++k) {
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = *m;
        for (int piece = 0; piece < 4; ++piece) {
            const double a = 0.25 * piece, h = 0.125, c = a + h;
            for (int i = 0; i < 8; ++i) {
                const double x = i < 4 ? -kGLx[i] : kGLx[i - 4], w = kGLw[i < 4 ? i : i - 4];
                const double t = c + h * x;
                const rugo_vec2 p = rugo_v2_sub(mapped_point(&g, t), o);
                const rugo_vec2 d0 = rugo__path_segment_derivative(g.s, t);
                const rugo_vec2 d = rugo_v2(m->a * d0.x + m->c * d0.y, m->b * d0.x + m->d * d0.y);
                area += 0.5 * w * h * (p.x * d.y - p.y * d.x);
            }
        }
    }
    return area;
}

/* Closed: ended by Z, or its last point within 1e-9 of its control points' bounds diagonal of its
 * start (path coordinates). */
static int subpath_closed(const rugo_path* path, const rugo_subpath* sp) {
    if (sp->count < 1) return 0;
    if (sp->closed) return 1;
    rugo_vec2 lo = sp->start, hi = sp->start;
    for (int k = 0; k < sp->count; ++k) {
        const rugo_path_segment* s = &path->segments[sp->first + k];
        const int np = s->kind == RUGO_PATH_CUBIC ? 4 : (s->kind == RUGO_PATH_QUADRATIC ? 3 : 2);
        for (int i = 0; i < np; ++i) {
            lo.x = fmin(lo.x, s->p[i].x);
            lo.y = fmin(lo.y, s->p[i].y);
            hi.x = fmax(hi.x, s->p[i].x);
            hi.y = fmax(hi.y, s->p[i].y);
        }
        if (s->kind == RUGO_PATH_ARC) { /* the arc's extent is within centre ± max radius */
            const double r = fmax(s->rx, s->ry);
            lo.x = fmin(lo.x, s->centre.x - r);
            lo.y = fmin(lo.y, s->centre.y - r);
            hi.x = fmax(hi.x, s->centre.x + r);
            hi.y = fmax(hi.y, s->centre.y + r);
        }
    }
    const rugo_vec2 end = rugo__path_segment_end(&path->segments[sp->first + sp->count - 1]);
    const double diag = hypot(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y) * 2.0;
    return hypot(end.x - sp->start.x, end.y - sp->start.y) <= 1e-9 * diag;
}

rugo_outline_sample_def rugo_default_outline_sample_def(void) {
    rugo_outline_sample_def d;
    memset(&d, 0, sizeof d);
    d.path = NULL;
    d.subpath = -1;
    d.transform = rugo_affine_identity();
    d.sample_count = 0;
    d.allocator.alloc = NULL;
    d.allocator.free = NULL;
    d.allocator.ctx = NULL;
    d.cookie = RUGO__OUTLINE_SAMPLE_DEF_COOKIE;
    return d;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static rugo_status
sample_fail(rugo_parse_error* e, rugo_status st, const char* fmt, ...) {
    if (e == NULL) return st;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

/* For the largest-remainder distribution: segment index and fractional share, ordered by share
 * (descending), then index (ascending), so that the order is total and the result deterministic. */
typedef struct share {
    double frac;
    int index;
} share;

static int share_cmp(const void* pa, const void* pb) {
    const share* a = (const share*)pa;
    const share* b = (const share*)pb;
    if (a->frac > b->frac) return -1;
    if (a->frac < b->frac) return 1;
    return (a->index > b->index) - (a->index < b->index);
}

rugo_status rugo_outline_sample(const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                rugo_parse_error* error) {
    clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (def == NULL || out == NULL)
        return sample_fail(error, RUGO_ERR_NULL_ARGUMENT, "a required argument is NULL");
    if (def->cookie != RUGO__OUTLINE_SAMPLE_DEF_COOKIE)
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "def not from rugo_default_outline_sample_def");
    const rugo_path* path = def->path;
    if (path == NULL) return sample_fail(error, RUGO_ERR_NULL_ARGUMENT, "def->path is NULL");
    if (path->subpath_count < 0 || path->segment_count < 0 ||
        (path->subpath_count > 0 && path->subpaths == NULL) ||
        (path->segment_count > 0 && path->segments == NULL))
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "the path's arrays and counts disagree");
    if (!rugo__affine_finite(&def->transform))
        return sample_fail(error, RUGO_ERR_NOT_FINITE, "the transform has a non-finite entry");
    if (def->sample_count < 0 || (def->sample_count > 0 && def->sample_count < 3))
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "sample_count %d: 0 (automatic) or at least 3",
                           def->sample_count);
    if (def->sample_count > RUGO_MAX_CONTROL_POINTS)
        return sample_fail(error, RUGO_ERR_TOO_MANY_POINTS, "sample_count %d beyond %d", def->sample_count,
                           RUGO_MAX_CONTROL_POINTS);
    if (def->subpath < -1 || def->subpath >= path->subpath_count) {
        if (def->subpath == -1 || path->subpath_count == 0)
            return sample_fail(error, RUGO_ERR_BAD_FIELD,
                               "the path has no closed subpath (a closed outline ends with Z)");
        return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "subpath %d out of range (the path has %d)",
                           def->subpath, path->subpath_count);
    }
    for (int k = 0; k < path->subpath_count; ++k) {
        const rugo_subpath* sp = &path->subpaths[k];
        if (sp->first < 0 || sp->count < 0 || sp->first > path->segment_count - sp->count)
            return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "subpath %d refers to segments beyond the path",
                               k);
    }
    for (int k = 0; k < path->segment_count; ++k) {
        const int kind = (int)path->segments[k].kind;
        if (kind < (int)RUGO_PATH_LINE || kind > (int)RUGO_PATH_ARC)
            return sample_fail(error, RUGO_ERR_BAD_ARGUMENT, "segment %d has an unknown kind %d", k, kind);
    }
    const rugo_affine m = def->transform;

    int chosen = def->subpath;
    if (chosen < 0) {
        double best = -1.0;
        for (int k = 0; k < path->subpath_count; ++k) {
            if (!subpath_closed(path, &path->subpaths[k])) continue;
            const double a = fabs(subpath_area(path, &path->subpaths[k], &m));
            if (a > best || (isnan(a) && best < 0.0)) {
                best = isnan(a) ? 0.0 : a;
                chosen = k;
            }
        }
        if (chosen < 0)
            return sample_fail(error, RUGO_ERR_BAD_FIELD,
                               "the path has no closed subpath (a closed outline ends with Z)");
    } else if (!subpath_closed(path, &path->subpaths[chosen])) {
        return sample_fail(error, RUGO_ERR_BAD_FIELD, "subpath %d is %s", chosen,
                           path->subpaths[chosen].count == 0 ? "empty"
                                                             : "open (a closed outline ends with Z)");
    }
    const rugo_subpath* sp = &path->subpaths[chosen];
    const int S = sp->count;
    const rugo_allocator al = rugo__allocator_or_default(&def->allocator);

    double* len = (double*)rugo__alloc_array(&al, (size_t)S, sizeof *len);
    share* shares = (share*)rugo__alloc_array(&al, (size_t)S, sizeof *shares);
    int* extra = (int*)rugo__alloc_array(&al, (size_t)S, sizeof *extra);
    rugo_vec2* pts = NULL;
    rugo_status st = RUGO_OK;
    if (len == NULL || shares == NULL || extra == NULL) {
        st = sample_fail(error, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
        goto done;
    }
    double total = 0.0;
    for (int k = 0; k < S; ++k) {
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = m;
        len[k] = mapped_length(&g);
        total += len[k];
    }
    if (!isfinite(total)) {
        st = sample_fail(error, RUGO_ERR_NOT_FINITE, "the outline's length overflows under the transform");
        goto done;
    }
    if (!(total > 0.0)) {
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d has zero length", chosen);
        goto done;
    }
    /* Segments too short to matter are skipped (their start would be a near-duplicate sample). */
    int kept = 0;
    double kept_total = 0.0;
    for (int k = 0; k < S; ++k) {
        if (len[k] <= 1e-12 * total) {
            len[k] = -1.0;
        } else {
            ++kept;
            kept_total += len[k];
        }
    }
    if (kept > RUGO_MAX_CONTROL_POINTS) {
        st = sample_fail(error, RUGO_ERR_TOO_MANY_POINTS, "subpath %d has %d segments, beyond %d samples",
                         chosen, kept, RUGO_MAX_CONTROL_POINTS);
        goto done;
    }
    int M = def->sample_count;
    if (M == 0) {
        M = RUGO_DEFAULT_OUTLINE_SAMPLES;
        if (kept > M / 4) M = kept > RUGO_MAX_CONTROL_POINTS / 4 ? RUGO_MAX_CONTROL_POINTS : 4 * kept;
    }
    if (M < kept) {
        st = sample_fail(error, RUGO_ERR_BAD_ARGUMENT,
                         "sample_count %d is below the %d segments of subpath %d", M, kept, chosen);
        goto done;
    }

    /* Largest remainders: segment k gets floor(E len_k / L) interior samples, and the E - sum left go
     * one each to the largest fractional parts. */
    {
        const int E = M - kept;
        int given = 0, ns = 0;
        for (int k = 0; k < S; ++k) {
            extra[k] = 0;
            if (len[k] < 0.0) continue;
            const double q = (double)E * (len[k] / kept_total);
            double fl = floor(q);
            if (fl > (double)E) fl = (double)E;
            extra[k] = (int)fl;
            given += extra[k];
            shares[ns].frac = q - fl;
            shares[ns].index = k;
            ++ns;
        }
        if (given > E) { /* only by rounding; take back from the end */
            for (int k = S - 1; k >= 0 && given > E; --k)
                while (extra[k] > 0 && given > E) {
                    --extra[k];
                    --given;
                }
        }
        qsort(shares, (size_t)ns, sizeof *shares, share_cmp);
        for (int i = 0; given < E; i = (i + 1) % ns) {
            ++extra[shares[i].index];
            ++given;
        }
    }

    pts = (rugo_vec2*)rugo__alloc_array(&al, (size_t)M, sizeof *pts);
    if (pts == NULL) {
        st = sample_fail(error, RUGO_ERR_OUT_OF_MEMORY, "out of memory");
        goto done;
    }
    int w = 0;
    for (int k = 0; k < S; ++k) {
        if (len[k] < 0.0) continue;
        mapped g;
        g.s = &path->segments[sp->first + k];
        g.m = m;
        pts[w++] = mapped_point(&g, 0.0);
        const int e = extra[k];
        if (e == 0) continue;
        /* Targets j len_k / (e + 1), j = 1..e, each placed in the piece of the segment's arc length
         * (the same computation as len[k], so the same pieces) that holds it. */
        rugo__arc arc;
        mapped_arc(&g, &arc);
        double s_a = 0.0;
        int j = 1;
        for (int p = 0; p < arc.count && j <= e; ++p) {
            const rugo__arc_piece* pc = &arc.piece[p];
            const double s_b = s_a + pc->length;
            for (; j <= e; ++j) {
                const double target = len[k] * ((double)j / (double)(e + 1));
                if (target >= s_b && p + 1 < arc.count) break;
                pts[w++] = mapped_point(&g, invert_arc_length(&g, pc->a, pc->b, s_a, pc->length, target));
            }
            s_a = s_b;
        }
        RUGO_ASSERT(j == e + 1);
    }
    RUGO_ASSERT(w == M);
    for (int i = 0; i < w; ++i)
        if (!rugo__v2_finite(pts[i])) {
            st = sample_fail(error, RUGO_ERR_NOT_FINITE, "a sample overflows under the transform");
            goto done;
        }
    /* Exact repeats (possible only at round-off scale) would give zero chords. */
    {
        int n = 0;
        for (int i = 0; i < w; ++i)
            if (n == 0 || pts[i].x != pts[n - 1].x || pts[i].y != pts[n - 1].y) pts[n++] = pts[i];
        while (n > 1 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
            --n;
        w = n;
    }
    /* Orientation and area of the sample polygon, in coordinates relative to the first sample and
     * scaled by the bounds (halves first), so that nothing overflows for any finite samples. */
    rugo_vec2 lo = pts[0], hi = pts[0];
    for (int i = 0; i < w; ++i) {
        lo.x = fmin(lo.x, pts[i].x);
        lo.y = fmin(lo.y, pts[i].y);
        hi.x = fmax(hi.x, pts[i].x);
        hi.y = fmax(hi.y, pts[i].y);
    }
    double half = fmax(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y);
    if (!(half > 0.0)) half = 1.0;
    double area2 = 0.0; /* twice the area, in units of (2 half)^2 */
    for (int i = 0; i < w; ++i) {
        const rugo_vec2 a = pts[i], b = pts[i + 1 < w ? i + 1 : 0];
        const double px = (0.5 * a.x - 0.5 * pts[0].x) / half, py = (0.5 * a.y - 0.5 * pts[0].y) / half;
        const double qx = (0.5 * b.x - 0.5 * pts[0].x) / half, qy = (0.5 * b.y - 0.5 * pts[0].y) / half;
        area2 += px * qy - py * qx;
    }
    const double diag_n = hypot(0.5 * hi.x - 0.5 * lo.x, 0.5 * hi.y - 0.5 * lo.y) / half; /* <= sqrt(2) */
    if (w < 3 || !(fabs(0.5 * area2) > 1e-12 * diag_n * diag_n)) {
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d encloses no area (under the transform)",
                         chosen);
        goto done;
    }
    const double area = 0.5 * fabs(area2) * (2.0 * half) * (2.0 * half);
    if (!isfinite(area)) {
        st = sample_fail(error, RUGO_ERR_NOT_FINITE, "the outline's area overflows under the transform");
        goto done;
    }
    if (!(area > 0.0)) { /* a shape, but so small that its area underflows (e.g. 1e-300 across) */
        st = sample_fail(error, RUGO_ERR_ZERO_AREA, "subpath %d: its area underflows (under the transform)",
                         chosen);
        goto done;
    }
    bool reversed = false;
    if (area2 < 0.0) {
        for (int i = 1, k = w - 1; i < k; ++i, --k) {
            rugo_vec2 t = pts[i];
            pts[i] = pts[k];
            pts[k] = t;
        }
        reversed = true;
    }
    out->points = pts;
    pts = NULL;
    out->count = w;
    out->perimeter = total;
    out->area = area;
    out->subpath = chosen;
    out->segment_count = kept;
    out->reversed = reversed;
    out->allocator = al;
done:
    rugo__free(&al, len);
    rugo__free(&al, shares);
    rugo__free(&al, extra);
    rugo__free(&al, pts);
    return st;
}

void rugo_outline_samples_free(rugo_outline_samples* samples) {
    if (samples == NULL) return;
    rugo__free(&samples->allocator, samples->points);
    memset(samples, 0, sizeof *samples);
}
