/* Collide suite: shapes (shape.h) and contacts (collide.h) — the issue's acceptance.
 *
 * The reference is independent of the library: the curves are evaluated here from their control
 * points (the B-spline matrix form, SPEC 1), both whole curves are sampled densely (64 samples per
 * segment), local minima of the sampled distance matrix are refined by Newton's method on the true
 * curves, crossings come from sign changes of the sampled polylines refined by Newton on f = g, and
 * containment from point-in-polygon tests on the polylines. Only λ(t) (tolerance.c) is shared.
 *
 * Tolerances: separations to 1e-9 of the shapes' size, normals to 1e-7 rad. Poses where the reference
 * itself cannot decide (the curves within 1e-6 of the size of touching: near-tangency below the
 * sampling error; a local minimum whose Newton refinement fails) are counted and reported, not
 * compared. */
#include "core/internal.h"
#include "query/narrow.h" /* rugo__shape_contains: containment through the tree */
#include "test_util.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_SANITIZER 1
#endif
#endif
#ifndef UNDER_SANITIZER
#define UNDER_SANITIZER 0
#endif

#define PI 3.14159265358979323846
#define TWO_PI 6.283185307179586

/* ---- helpers ------------------------------------------------------------------------------------ */

static void* xmalloc(size_t n) {
    void* p = malloc(n);
    ck_assert_ptr_nonnull(p);
    return p;
}

/* Counting allocator that can fail the k-th allocation. */
typedef struct counting {
    long allocs, frees, fail_at;
} counting;
static void* cnt_alloc(size_t n, void* ctx) {
    counting* c = (counting*)ctx;
    if (c->fail_at >= 0 && c->allocs == c->fail_at) {
        c->allocs++;
        return NULL;
    }
    c->allocs++;
    return malloc(n);
}
static void cnt_free(void* p, void* ctx) {
    counting* c = (counting*)ctx;
    if (p != NULL) c->frees++;
    free(p);
}
static rugo_allocator counting_allocator(counting* c) {
    rugo_allocator a;
    a.alloc = cnt_alloc;
    a.free = cnt_free;
    a.ctx = c;
    return a;
}

/* ---- test shapes -------------------------------------------------------------------------------- */

typedef struct tshape {
    const char* name;
    rugo_shape* s;
    rugo_contour fine; /* finest level (counter-clockwise), the reference's curve */
    double radius;     /* max distance from the centroid to a control point */
    double size;       /* diagonal of the control points' bounds */
    double max_lambda;
} tshape;

enum { N_SHAPES = 6 };
static tshape g_shapes[N_SHAPES];
static int g_shapes_ready = 0;

static rugo_shape* make_shape(const rugo_vec2* pts, int n, const double* tol) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts;
    d.count = n;
    d.tolerances = tol;
    rugo_shape* s = NULL;
    rugo_status st = rugo_shape_create(&d, &s, NULL);
    ck_assert_msg(st == RUGO_OK, "rugo_shape_create: %s", rugo_status_string(st));
    return s;
}

static void finish_tshape(tshape* t, const char* name, rugo_shape* s) {
    t->name = name;
    t->s = s;
    rugo_shape_level(s, rugo_shape_finest_level(s), &t->fine);
    rugo_mass_properties m = rugo_shape_mass(s);
    rugo_vec2 lo = t->fine.points[0], hi = lo;
    t->radius = 0.0;
    for (int i = 0; i < t->fine.count; ++i) {
        rugo_vec2 p = t->fine.points[i];
        lo.x = fmin(lo.x, p.x);
        lo.y = fmin(lo.y, p.y);
        hi.x = fmax(hi.x, p.x);
        hi.y = fmax(hi.y, p.y);
        t->radius = fmax(t->radius, hypot(p.x - m.centroid.x, p.y - m.centroid.y));
    }
    t->size = hypot(hi.x - lo.x, hi.y - lo.y);
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(s, rugo_shape_finest_level(s), &tl);
    t->max_lambda = 0.0;
    for (int i = 0; i < tl.count; ++i)
        t->max_lambda = fmax(t->max_lambda, tl.total[i]);
}

/* Five kinds of shapes (plus a finer concave one): convex; concave; very rough; with straight
 * segments (collinear control points); degenerate (coincident control points: point-like segments
 * and sharp corners). */
static void build_shapes(void) {
    if (g_shapes_ready) return;
    test_rng r = test_rng_seed(20240601);
    rugo_vec2 p[64];
    double tol[64];
    /* 0: convex ellipse, smooth-ish band */
    for (int i = 0; i < 16; ++i) {
        double th = TWO_PI * i / 16;
        p[i] = rugo_v2(1.2 * cos(th), 0.7 * sin(th));
        tol[i] = 0.01;
    }
    finish_tshape(&g_shapes[0], "convex", make_shape(p, 16, tol));
    /* 1: concave star (deep bays) */
    test_random_star(&r, 32, rugo_v2(0.3, -0.2), 1.0, 0.45, p);
    for (int i = 0; i < 32; ++i)
        tol[i] = 0.02;
    finish_tshape(&g_shapes[1], "concave", make_shape(p, 32, tol));
    /* 2: very rough: tolerances up to a fifth of the radius */
    test_random_star(&r, 16, rugo_v2(0.0, 0.0), 0.9, 0.3, p);
    for (int i = 0; i < 16; ++i)
        tol[i] = test_rng_uniform(&r, 0.0, 0.2);
    finish_tshape(&g_shapes[2], "rough", make_shape(p, 16, tol));
    /* 3: straight sides: four collinear control points per side */
    for (int side = 0; side < 4; ++side)
        for (int i = 0; i < 4; ++i) {
            double a = -1.0 + 0.5 * i;
            rugo_vec2 q;
            switch (side) {
            case 0:
                q = rugo_v2(a, -0.8);
                break;
            case 1:
                q = rugo_v2(1.0, -0.8 + 0.4 * i);
                break;
            case 2:
                q = rugo_v2(-a, 0.8);
                break;
            default:
                q = rugo_v2(-1.0, 0.8 - 0.4 * i);
                break;
            }
            p[4 * side + i] = q;
            tol[4 * side + i] = 0.005;
        }
    finish_tshape(&g_shapes[3], "straight", make_shape(p, 16, tol));
    /* 4: degenerate: each corner repeated four times (point-like segments, straight segments,
     * zero-speed corners) */
    const rugo_vec2 corners[4] = {{-0.9, -0.6}, {0.9, -0.6}, {0.9, 0.6}, {-0.9, 0.6}};
    for (int i = 0; i < 16; ++i) {
        p[i] = corners[i / 4];
        tol[i] = 0.01;
    }
    finish_tshape(&g_shapes[4], "degenerate", make_shape(p, 16, tol));
    /* 5: a finer concave outline, 64 points, mixed band */
    test_random_star(&r, 64, rugo_v2(0.0, 0.0), 1.1, 0.4, p);
    for (int i = 0; i < 64; ++i)
        tol[i] = test_rng_uniform(&r, 0.0, 0.05);
    finish_tshape(&g_shapes[5], "concave64", make_shape(p, 64, tol));
    g_shapes_ready = 1;
}

/* ---- the independent reference ------------------------------------------------------------------ */

enum { S = 64, MAX_REF_MIN = 512 };

typedef struct curve {
    const rugo_vec2* c;
    int n;
    rugo_transform x;
} curve;

static rugo_vec2 cpt(const curve* k, int i) { return k->c[((i % k->n) + k->n) % k->n]; }

/* World point and derivatives (in the global parameter u in [0, n), wrapping) of the B-spline. */
static void ev(const curve* k, double u, rugo_vec2* p, rugo_vec2* d1, rugo_vec2* d2) {
    double fl = floor(u);
    int j = (int)fl;
    double t = u - fl, t2 = t * t, t3 = t2 * t, s = 1.0 - t;
    rugo_vec2 c[4] = {cpt(k, j - 1), cpt(k, j), cpt(k, j + 1), cpt(k, j + 2)};
    double b[4] = {s * s * s / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
                   (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, t3 / 6.0};
    double db[4] = {-s * s / 2.0, (3.0 * t2 - 4.0 * t) / 2.0, (-3.0 * t2 + 2.0 * t + 1.0) / 2.0, t2 / 2.0};
    double ddb[4] = {s, 3.0 * t - 2.0, -3.0 * t + 1.0, t};
    rugo_vec2 a = {0, 0}, da = {0, 0}, dda = {0, 0};
    for (int i = 0; i < 4; ++i) {
        a.x += b[i] * c[i].x;
        a.y += b[i] * c[i].y;
        da.x += db[i] * c[i].x;
        da.y += db[i] * c[i].y;
        dda.x += ddb[i] * c[i].x;
        dda.y += ddb[i] * c[i].y;
    }
    if (p) *p = rugo_transform_point(k->x, a);
    if (d1) *d1 = rugo_rotate(k->x.q, da);
    if (d2) *d2 = rugo_rotate(k->x.q, dda);
}

static double wrapu(double u, int n) {
    double r = fmod(u, (double)n);
    if (r < 0) r += n;
    if (r >= n) r = 0;
    return r;
}

/* Outward normal (counter-clockwise curve) at u, or zero where the speed vanishes. */
static rugo_vec2 ref_normal(const curve* k, double u) {
    rugo_vec2 d;
    ev(k, u, NULL, &d, NULL);
    double l = hypot(d.x, d.y);
    if (!(l > 1e-12)) {
        /* zero speed (a cusp or a point-like segment): the tangent is the limit direction; look
         * slightly ahead */
        rugo_vec2 a, b;
        ev(k, wrapu(u + 1e-6, k->n), &a, NULL, NULL);
        ev(k, wrapu(u - 1e-6, k->n), &b, NULL, NULL);
        d = rugo_v2_sub(a, b);
        l = hypot(d.x, d.y);
        if (!(l > 0)) return rugo_v2(0, 0);
    }
    return rugo_v2(d.y / l, -d.x / l);
}

typedef struct refmin {
    double ua, ub;
    rugo_vec2 pa, pb;
    double dist;
    double cond; /* det / (h11 h22) of the distance's Hessian: near 0 = a flat, ill-conditioned minimum */
} refmin;

typedef struct refres {
    int crossing;       /* a verified transversal crossing */
    int crossing_doubt; /* polylines cross but the curves could not be confirmed to */
    int contained;      /* no crossing and one polyline inside the other */
    int nmin;
    refmin m[MAX_REF_MIN];
    int newton_fail;
    double closest; /* smallest refined minimum distance found (or HUGE) */
} refres;

static double orient(rugo_vec2 a, rugo_vec2 b, rugo_vec2 c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/* Newton on f(s) = g(t) from (s, t); returns 1 with the converged point if transversal. */
static int refine_crossing(const curve* A, const curve* B, double s, double t, double size, double* so,
                           double* to) {
    for (int it = 0; it < 60; ++it) {
        rugo_vec2 f, fd, g, gd;
        ev(A, s, &f, &fd, NULL);
        ev(B, t, &g, &gd, NULL);
        rugo_vec2 F = rugo_v2_sub(f, g);
        /* [fd -gd] [ds dt]^T = -F */
        double det = fd.x * (-gd.y) - (-gd.x) * fd.y;
        if (!(fabs(det) > 0)) return 0;
        double ds = (-F.x * (-gd.y) - (-gd.x) * (-F.y)) / det;
        double dt = (fd.x * (-F.y) - fd.y * (-F.x)) / det;
        if (fabs(ds) > 0.25) ds = ds > 0 ? 0.25 : -0.25;
        if (fabs(dt) > 0.25) dt = dt > 0 ? 0.25 : -0.25;
        s = wrapu(s + ds, A->n);
        t = wrapu(t + dt, B->n);
        if (fabs(ds) < 1e-15 && fabs(dt) < 1e-15) break;
    }
    rugo_vec2 f, fd, g, gd;
    ev(A, s, &f, &fd, NULL);
    ev(B, t, &g, &gd, NULL);
    double e = hypot(f.x - g.x, f.y - g.y);
    double cr = fabs(rugo_v2_cross(fd, gd)), nn = hypot(fd.x, fd.y) * hypot(gd.x, gd.y);
    *so = s;
    *to = t;
    return e <= 1e-11 * size && cr > 1e-6 * nn;
}

/* Newton on the stationarity system (6.14) from (s, t): 1 and the point if it converges to a local
 * minimum of the distance; 0 if it fails. */
static int refine_min_at(const curve* A, const curve* B, double s, double t, refmin* out, int allow_search);
static int refine_min(const curve* A, const curve* B, double s, double t, refmin* out) {
    return refine_min_at(A, B, s, t, out, 1);
}
static int refine_min_at(const curve* A, const curve* B, double s, double t, refmin* out, int allow_search) {
    int conv = 0;
    const double s_in = s, t_in = t;
    for (int it = 0; it < 80; ++it) {
        rugo_vec2 f, f1, f2, g, g1, g2;
        ev(A, s, &f, &f1, &f2);
        ev(B, t, &g, &g1, &g2);
        rugo_vec2 d = rugo_v2_sub(f, g);
        double H1 = rugo_v2_dot(d, f1), H2 = rugo_v2_dot(d, g1);
        double J11 = rugo_v2_dot(f1, f1) + rugo_v2_dot(d, f2), J12 = -rugo_v2_dot(g1, f1);
        double J21 = rugo_v2_dot(f1, g1), J22 = -rugo_v2_dot(g1, g1) + rugo_v2_dot(d, g2);
        double det = J11 * J22 - J12 * J21;
        if (!(fabs(det) > 1e-300)) break;
        double ds = (-H1 * J22 + H2 * J12) / det;
        double dt = (-J11 * H2 + J21 * H1) / det;
        double m = fmax(fabs(ds), fabs(dt));
        if (m > 0.2) {
            ds *= 0.2 / m;
            dt *= 0.2 / m;
        }
        s = wrapu(s + ds, A->n);
        t = wrapu(t + dt, B->n);
        if (m < 1e-11) { /* converged: two more steps polish to round-off */
            if (++conv == 3) break;
        }
    }
    if (!conv && !allow_search) return 0;
    if (!conv) {
        /* Newton stalls where a curve has zero speed (coincident control points: a sharp corner is
         * a degenerate stationary point). A pattern search on the distance itself converges there. */
        s = s_in;
        t = t_in;
        rugo_vec2 f, g;
        ev(A, s, &f, NULL, NULL);
        ev(B, t, &g, NULL, NULL);
        double best = hypot(f.x - g.x, f.y - g.y);
        for (double h = 1.0 / S; h > 1e-15;) {
            int moved = 0;
            for (int di = -1; di <= 1; ++di)
                for (int dj = -1; dj <= 1; ++dj) {
                    if (!di && !dj) continue;
                    double s2 = wrapu(s + di * h, A->n), t2 = wrapu(t + dj * h, B->n);
                    ev(A, s2, &f, NULL, NULL);
                    ev(B, t2, &g, NULL, NULL);
                    double v = hypot(f.x - g.x, f.y - g.y);
                    if (v < best) {
                        best = v;
                        s = s2;
                        t = t2;
                        moved = 1;
                    }
                }
            if (!moved) h *= 0.5;
        }
        /* One side sits at a zero-speed corner: polish the other side's foot by 1-D Newton. */
        for (int round = 0; round < 60; ++round)
            for (int side = 0; side < 2; ++side) {
                const curve* k = side ? B : A;
                double* u = side ? &t : &s;
                rugo_vec2 d1;
                ev(k, *u, NULL, &d1, NULL);
                if (hypot(d1.x, d1.y) < 1e-6) continue; /* this side is the corner */
                rugo_vec2 P;
                ev(side ? A : B, side ? s : t, &P, NULL, NULL);
                for (int it = 0; it < 20; ++it) {
                    rugo_vec2 q, q1, q2;
                    ev(k, *u, &q, &q1, &q2);
                    rugo_vec2 dd = rugo_v2_sub(q, P);
                    double h = rugo_v2_dot(dd, q1), dh = rugo_v2_dot(q1, q1) + rugo_v2_dot(dd, q2);
                    if (!(dh > 0)) break;
                    double step = -h / dh;
                    if (fabs(step) > 0.01) break;
                    *u = wrapu(*u + step, k->n);
                    if (fabs(step) < 1e-16) break;
                }
            }
        /* Newton again from there (it converges unless a side is a corner). */
        if (refine_min_at(A, B, s, t, out, 0) == 1 && out->dist <= best + 1e-15) return 1;
        ev(A, s, &f, NULL, NULL);
        ev(B, t, &g, NULL, NULL);
        out->ua = s;
        out->ub = t;
        out->pa = f;
        out->pb = g;
        out->dist = hypot(f.x - g.x, f.y - g.y);
        out->cond = 1.0;
        return 1;
    }
    rugo_vec2 f, f1, f2, g, g1, g2;
    ev(A, s, &f, &f1, &f2);
    ev(B, t, &g, &g1, &g2);
    rugo_vec2 d = rugo_v2_sub(f, g);
    /* Hessian of |f - g|^2 / 2: a minimum needs it positive semi-definite. */
    double h11 = rugo_v2_dot(f1, f1) + rugo_v2_dot(d, f2), h12 = -rugo_v2_dot(f1, g1);
    double h22 = rugo_v2_dot(g1, g1) - rugo_v2_dot(d, g2);
    double sc = fmax(fabs(h11), fabs(h22)) + 1e-300;
    if (h11 < -1e-9 * sc || h22 < -1e-9 * sc || h11 * h22 - h12 * h12 < -1e-9 * sc * sc)
        return -1; /* not a minimum */
    out->ua = s;
    out->ub = t;
    out->pa = f;
    out->pb = g;
    out->dist = hypot(d.x, d.y);
    out->cond = h11 * h22 > 0 ? (h11 * h22 - h12 * h12) / (h11 * h22) : 0.0;
    return 1;
}

/* Geometric check of a minimum: moving either point along its curve (to the first point that differs,
 * which skips segments shrunk to a point) must not bring the curves closer. Catches the plateaus of
 * zero-speed corners, where the distance only starts to fall at third order. */
/* The point of curve k nearest along direction sg from parameter u that lies about 1e-9 of the size
 * from p0 (skipping segments shrunk to a point); 0 if there is none. */
static int first_distinct(const curve* k, double u, int sg, rugo_vec2 p0, double size, rugo_vec2* out) {
    rugo_vec2 q;
    double lo = 0.0, hi = 0.0;
    for (double h = 1e-7; h < 4.0; h *= 2) {
        ev(k, wrapu(u + sg * h, k->n), &q, NULL, NULL);
        if (hypot(q.x - p0.x, q.y - p0.y) > 1e-9 * size) {
            hi = h;
            break;
        }
        lo = h;
    }
    if (hi == 0.0) return 0;
    for (int it = 0; it < 60; ++it) {
        double mid = 0.5 * (lo + hi);
        ev(k, wrapu(u + sg * mid, k->n), &q, NULL, NULL);
        if (hypot(q.x - p0.x, q.y - p0.y) > 1e-9 * size)
            hi = mid;
        else
            lo = mid;
    }
    ev(k, wrapu(u + sg * hi, k->n), out, NULL, NULL);
    return 1;
}

/* Geometric check of a minimum: moving either point along its curve (to the first point that differs,
 * which skips segments shrunk to a point) must not bring the curves closer. Catches the plateaus of
 * zero-speed corners, where the distance only starts to fall at third order. */
static int geometric_min(const curve* A, const curve* B, const refmin* m, double size) {
    for (int which = 0; which < 2; ++which)
        for (int sg = -1; sg <= 1; sg += 2) {
            const curve* k = which ? B : A;
            rugo_vec2 other = which ? m->pa : m->pb, q;
            if (!first_distinct(k, which ? m->ub : m->ua, sg, which ? m->pb : m->pa, size, &q)) continue;
            if (hypot(q.x - other.x, q.y - other.y) < m->dist - 1e-13 * size) return 0;
        }
    return 1;
}

static int point_in_polyline(rugo_vec2 p, const rugo_vec2* poly, int m) {
    int c = 0;
    for (int i = 0, j = m - 1; i < m; j = i++) {
        if (((poly[i].y > p.y) != (poly[j].y > p.y)) &&
            (p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x))
            c = !c;
    }
    return c;
}

/* Sampling error bound of a segment's polyline: h^2/8 max|f''| with |f''| bounded by the Bezier
 * second differences (in the segment parameter), h = 1/S. */
static double seg_pad(const curve* k, int j) {
    rugo_vec2 c0 = cpt(k, j - 1), c1 = cpt(k, j), c2 = cpt(k, j + 1), c3 = cpt(k, j + 2);
    rugo_vec2 b[4];
    b[0] = rugo_v2((c0.x + 4 * c1.x + c2.x) / 6, (c0.y + 4 * c1.y + c2.y) / 6);
    b[1] = rugo_v2((4 * c1.x + 2 * c2.x) / 6, (4 * c1.y + 2 * c2.y) / 6);
    b[2] = rugo_v2((2 * c1.x + 4 * c2.x) / 6, (2 * c1.y + 4 * c2.y) / 6);
    b[3] = rugo_v2((c1.x + 4 * c2.x + c3.x) / 6, (c1.y + 4 * c2.y + c3.y) / 6);
    double m = 0;
    for (int i = 0; i < 2; ++i)
        m = fmax(m, 6.0 * hypot(b[i + 2].x - 2 * b[i + 1].x + b[i].x, b[i + 2].y - 2 * b[i + 1].y + b[i].y));
    return m / (8.0 * S * S) * 1.01 + 1e-14;
}

typedef struct box2 {
    rugo_vec2 lo, hi;
} box2;

static double box_gap(box2 a, box2 b) {
    double dx = fmax(0.0, fmax(a.lo.x - b.hi.x, b.lo.x - a.hi.x));
    double dy = fmax(0.0, fmax(a.lo.y - b.hi.y, b.lo.y - a.hi.y));
    return hypot(dx, dy);
}

static void add_min(refres* R, const refmin* m, double eps) {
    for (int i = 0; i < R->nmin; ++i)
        if (hypot(R->m[i].pa.x - m->pa.x, R->m[i].pa.y - m->pa.y) <= eps &&
            hypot(R->m[i].pb.x - m->pb.x, R->m[i].pb.y - m->pb.y) <= eps)
            return;
    if (R->nmin < MAX_REF_MIN) R->m[R->nmin++] = *m;
    if (m->dist < R->closest) R->closest = m->dist;
}

/* All local minima of the distance with distance <= cutoff, crossings (verified), containment.
 * stop_at_crossing: skip the minima once a crossing is verified. */
static void reference(const curve* A, const curve* B, double cutoff, double size, int stop_at_crossing,
                      refres* R) {
    memset(R, 0, sizeof *R);
    R->closest = HUGE_VAL;
    const int ma = A->n * S, mb = B->n * S;
    rugo_vec2* sa = xmalloc((size_t)(ma + 1) * sizeof *sa);
    rugo_vec2* sb = xmalloc((size_t)(mb + 1) * sizeof *sb);
    box2* ba = xmalloc((size_t)A->n * sizeof *ba);
    box2* bb = xmalloc((size_t)B->n * sizeof *bb);
    double *pa = xmalloc((size_t)A->n * sizeof(double)), *pb = xmalloc((size_t)B->n * sizeof(double));
    double stepa = 0, stepb = 0;
    for (int i = 0; i <= ma; ++i)
        ev(A, wrapu((double)i / S, A->n), &sa[i], NULL, NULL);
    for (int i = 0; i <= mb; ++i)
        ev(B, wrapu((double)i / S, B->n), &sb[i], NULL, NULL);
    for (int i = 0; i < ma; ++i)
        stepa = fmax(stepa, hypot(sa[i + 1].x - sa[i].x, sa[i + 1].y - sa[i].y));
    for (int i = 0; i < mb; ++i)
        stepb = fmax(stepb, hypot(sb[i + 1].x - sb[i].x, sb[i + 1].y - sb[i].y));
    for (int side = 0; side < 2; ++side) {
        const curve* k = side ? B : A;
        const rugo_vec2* sp = side ? sb : sa;
        box2* bx = side ? bb : ba;
        double* pd = side ? pb : pa;
        for (int j = 0; j < k->n; ++j) {
            pd[j] = seg_pad(k, j);
            box2 b = {sp[j * S], sp[j * S]};
            for (int i = 1; i <= S; ++i) {
                rugo_vec2 q = sp[j * S + i];
                b.lo.x = fmin(b.lo.x, q.x);
                b.lo.y = fmin(b.lo.y, q.y);
                b.hi.x = fmax(b.hi.x, q.x);
                b.hi.y = fmax(b.hi.y, q.y);
            }
            b.lo.x -= pd[j];
            b.lo.y -= pd[j];
            b.hi.x += pd[j];
            b.hi.y += pd[j];
            bx[j] = b;
        }
    }
    const double eps = 1e-9 * size;
    static double D[(S + 2) * (S + 2)];
    for (int ka = 0; ka < A->n; ++ka)
        for (int kb = 0; kb < B->n; ++kb) {
            double gap = box_gap(ba[ka], bb[kb]);
            if (gap == 0.0 && !R->crossing) {
                for (int i = 0; i < S && !R->crossing; ++i) {
                    rugo_vec2 a0 = sa[ka * S + i], a1 = sa[ka * S + i + 1];
                    for (int j = 0; j < S; ++j) {
                        rugo_vec2 b0 = sb[kb * S + j], b1 = sb[kb * S + j + 1];
                        double o1 = orient(a0, a1, b0), o2 = orient(a0, a1, b1);
                        if ((o1 > 0) == (o2 > 0) && o1 != 0 && o2 != 0) continue;
                        double o3 = orient(b0, b1, a0), o4 = orient(b0, b1, a1);
                        if ((o3 > 0) == (o4 > 0) && o3 != 0 && o4 != 0) continue;
                        double al = o3 / (o3 - o4), be = o1 / (o1 - o2);
                        if (!isfinite(al)) al = 0.5;
                        if (!isfinite(be)) be = 0.5;
                        double s, t;
                        if (refine_crossing(A, B, (ka * S + i + al) / S, (kb * S + j + be) / S, size, &s,
                                            &t)) {
                            R->crossing = 1;
                            break;
                        }
                        R->crossing_doubt = 1;
                    }
                }
            }
            if (R->crossing && stop_at_crossing) goto done;
            if (gap > cutoff + 0.5 * (stepa + stepb)) continue;
            /* Sampled distances on the pair's cells plus one neighbour cell each side. */
            for (int i = -1; i <= S; ++i)
                for (int j = -1; j <= S; ++j) {
                    int ia = ((ka * S + i) % ma + ma) % ma, jb = ((kb * S + j) % mb + mb) % mb;
                    D[(i + 1) * (S + 2) + (j + 1)] = hypot(sa[ia].x - sb[jb].x, sa[ia].y - sb[jb].y);
                }
            for (int i = 0; i < S; ++i)
                for (int j = 0; j < S; ++j) {
                    double v = D[(i + 1) * (S + 2) + (j + 1)];
                    if (v > cutoff + 0.5 * (stepa + stepb) + pa[ka] + pb[kb]) continue;
                    int ismin = 1;
                    for (int di = -1; di <= 1 && ismin; ++di)
                        for (int dj = -1; dj <= 1; ++dj)
                            if ((di || dj) && D[(i + 1 + di) * (S + 2) + (j + 1 + dj)] < v) {
                                ismin = 0;
                                break;
                            }
                    if (!ismin) continue;
                    refmin m;
                    int r = refine_min(A, B, (double)(ka * S + i) / S, (double)(kb * S + j) / S, &m);
                    if (r == 0) R->newton_fail++;
                    if (r == 1 && m.dist <= cutoff + 1e-6 * size && geometric_min(A, B, &m, size))
                        add_min(R, &m, eps);
                }
        }
    if (!R->crossing) {
        R->contained = point_in_polyline(sb[0], sa, ma) || point_in_polyline(sa[0], sb, mb);
    }
done:
    free(sa);
    free(sb);
    free(ba);
    free(bb);
    free(pa);
    free(pb);
}

/* λ(t) of a shape's finest level at global parameter u (or the override). */
static double lambda_at(const tshape* t, double u, double override) {
    if (override >= 0) return override;
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(t->s, rugo_shape_finest_level(t->s), &tl);
    int seg = (int)floor(u);
    return rugo_tolerance_at(tl.total, tl.count, seg, u - seg, 0.0);
}

static double angle_between(rugo_vec2 a, rugo_vec2 b) {
    return fabs(atan2(rugo_v2_cross(a, b), rugo_v2_dot(a, b)));
}

/* ---- acceptance: shapes against the reference on random poses ---------------------------------- */

typedef struct accept_stats {
    long poses, apart, contact, intersecting, contained_ref;
    long required, compared, missed, spurious, ambiguous, ref_fail, state_mismatch, borderline;
    long lib_contacts, pen_contacts, illcond, region_fallbacks;
    double max_sep_err, max_normal_err; /* relative to size, radians */
    long segment_pairs, fallbacks, box_tests;
} accept_stats;

static int g_verbose_failures = 0;

static void centroid_world(const tshape* t, rugo_transform x, rugo_vec2* c) {
    *c = rugo_transform_point(x, rugo_shape_mass(t->s).centroid);
}

/* Places B's centroid at distance d from A's centroid along dir, B rotated by angle. */
static rugo_transform place_b(const tshape* A, rugo_transform xa, const tshape* B, rugo_vec2 dir, double d,
                              double angle) {
    rugo_vec2 ca;
    centroid_world(A, xa, &ca);
    rugo_transform xb = rugo_make_transform(0, 0, angle);
    rugo_vec2 cb = rugo_rotate(xb.q, rugo_shape_mass(B->s).centroid);
    xb.p = rugo_v2(ca.x + d * dir.x - cb.x, ca.y + d * dir.y - cb.y);
    return xb;
}

static rugo_contact_state lib_state(rugo_collide_context* ctx, const tshape* A, rugo_transform xa,
                                    const tshape* B, rugo_transform xb, double override) {
    rugo_contact_query q = test_exact_query();
    q.tolerance = override;
    int n;
    rugo_contact_state s;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, NULL, 0, &n, &s, NULL), RUGO_OK);
    return s;
}

/* A random pose pair: mode 0 anywhere from deep overlap to apart; mode 1 near the boundary between
 * intersecting and apart (found by bisection on the library's state; the reference judges the result). */
static void random_poses(test_rng* r, const tshape* A, const tshape* B, int mode, double override,
                         rugo_collide_context* ctx, rugo_transform* xa, rugo_transform* xb) {
    *xa = rugo_make_transform(test_rng_uniform(r, -1, 1), test_rng_uniform(r, -1, 1),
                              test_rng_uniform(r, 0, TWO_PI));
    double th = test_rng_uniform(r, 0, TWO_PI), ang = test_rng_uniform(r, 0, TWO_PI);
    rugo_vec2 dir = rugo_v2(cos(th), sin(th));
    double reach = A->radius + B->radius;
    if (mode == 0) {
        *xb = place_b(A, *xa, B, dir, reach * test_rng_uniform(r, 0.45, 1.1), ang);
        return;
    }
    double lo = 0.0, hi = reach * 1.2;
    for (int it = 0; it < 18; ++it) {
        double mid = 0.5 * (lo + hi);
        if (lib_state(ctx, A, *xa, B, place_b(A, *xa, B, dir, mid, ang), -1.0) == RUGO_STATE_INTERSECTING)
            lo = mid;
        else
            hi = mid;
    }
    double band = fmax(override >= 0 ? 2 * override : A->max_lambda + B->max_lambda, 1e-3 * reach);
    *xb = place_b(A, *xa, B, dir, hi + band * test_rng_uniform(r, -0.3, 1.3), ang);
}

static void check_pose(rugo_collide_context* ctx, const tshape* A, rugo_transform xa, const tshape* B,
                       rugo_transform xb, double override, accept_stats* st) {
    enum { CAP = 256 };
    static rugo_contact c[CAP];
    static refres R;
    rugo_contact_query q = test_exact_query();
    q.tolerance = override;
    int n = 0;
    rugo_contact_state state;
    rugo_query_stats qs;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c, CAP, &n, &state, &qs), RUGO_OK);
    ck_assert_int_eq(n, qs.contacts_found);
    st->poses++;
    st->segment_pairs += qs.segment_pairs;
    st->fallbacks += qs.fallbacks;
    st->box_tests += qs.box_tests;
    st->lib_contacts += n;
    for (int i = 0; i < n; ++i) {
        ck_assert(isfinite(c[i].separation) && isfinite(c[i].normal.x) && isfinite(c[i].normal.y));
        ck_assert(isfinite(c[i].point_a.x) && isfinite(c[i].point_b.y) && isfinite(c[i].friction));
        ck_assert_msg(fabs(hypot(c[i].normal.x, c[i].normal.y) - 1.0) < 1e-12, "normal not unit");
        ck_assert(c[i].t_a >= 0.0 && c[i].t_a < 1.0 && c[i].t_b >= 0.0 && c[i].t_b < 1.0);
    }
    if (state == RUGO_STATE_APART) st->apart++;
    if (state == RUGO_STATE_CONTACT) st->contact++;
    if (state == RUGO_STATE_INTERSECTING) {
        st->intersecting++;
        ck_assert_msg(n >= 1, "intersecting without a contact");
        /* Overlap-region contacts (kind 1 in the id, see docs/contacts.md): penetrating; index 1 marks
         * the sampling fallback. */
        for (int i = 0; i < n; ++i)
            if (((c[i].id >> 12) & 3) == 1) {
                st->pen_contacts++;
                st->region_fallbacks += (c[i].id & 0xFFF) == 1;
                ck_assert_msg(c[i].separation <= 0.0, "overlap contact with positive separation");
            }
    }
    if (state == RUGO_STATE_APART) ck_assert_int_eq(n, 0);

    const double size = fmax(A->size, B->size);
    curve ca = {A->fine.points, A->fine.count, xa}, cb = {B->fine.points, B->fine.count, xb};
    const double cutoff = override >= 0 ? 2.0 * override : 1.3 * (A->max_lambda + B->max_lambda) + 1e-12;
    reference(&ca, &cb, cutoff, size, 1, &R);
    const int ref_int = R.crossing || R.contained;
    st->contained_ref += R.contained;
    const int ambiguous = !R.crossing && (R.closest <= 1e-6 * size || R.crossing_doubt);
    if (ambiguous) st->ambiguous++;
    if (ref_int != (state == RUGO_STATE_INTERSECTING) && !ambiguous) {
        st->state_mismatch++;
        if (g_verbose_failures++ < 10)
            printf("state mismatch %s/%s: lib %s, ref crossing %d contained %d closest %.3g\n", A->name,
                   B->name, rugo_contact_state_name(state), R.crossing, R.contained, R.closest);
    }
    if (ref_int || state == RUGO_STATE_INTERSECTING || ambiguous) return;
    if (R.newton_fail > 0) {
        st->ref_fail++;
        return;
    }
    for (int i = 0; i < n; ++i) {
        ck_assert_msg(c[i].separation >= 0.0, "negative separation outside intersection");
        ck_assert_msg(c[i].separation <= c[i].tolerance_a + c[i].tolerance_b, "contact outside the band");
    }
    /* Reference -> library: no contact missed, accuracy. */
    for (int k = 0; k < R.nmin; ++k) {
        const refmin* m = &R.m[k];
        double band = lambda_at(A, m->ua, override) + lambda_at(B, m->ub, override);
        if (fabs(m->dist - band) <= 1e-9 * size) {
            st->borderline++;
            continue;
        }
        if (m->dist > band) continue;
        rugo_vec2 d = rugo_v2_sub(m->pb, m->pa);
        if (m->dist > 1e-9 * size) {
            rugo_vec2 na = ref_normal(&ca, m->ua), nb = ref_normal(&cb, m->ub);
            double fa = rugo_v2_dot(d, na) / m->dist, fb = rugo_v2_dot(d, nb) / m->dist;
            if (fabs(fa) < 1e-6 || fabs(fb) < 1e-6) {
                st->borderline++;
                continue;
            }
            if (fa < 0 || fb > 0) continue; /* not facing: through material, not a contact */
        }
        st->required++;
        /* Matched by position: the nearest contact within 1e-4 of the size (a flat minimum, e.g. near
         * an inflection facing a straight piece, is located only to ~sqrt(eps) while its distance is
         * exact). */
        int found = -1;
        double bestd = 1e-4 * size;
        for (int i = 0; i < n; ++i) {
            double e = fmax(hypot(c[i].point_a.x - m->pa.x, c[i].point_a.y - m->pa.y),
                            hypot(c[i].point_b.x - m->pb.x, c[i].point_b.y - m->pb.y));
            if (e <= bestd) {
                bestd = e;
                found = i;
            }
        }
        if (found < 0) {
            st->missed++;
            continue;
        }
        st->compared++;
        double e = fabs(c[found].separation - m->dist) / size;
        if (e > st->max_sep_err) st->max_sep_err = e;
        rugo_vec2 nref = m->dist > 1e-6 * size ? rugo_v2_scale(1.0 / m->dist, d) : ref_normal(&ca, m->ua);
        double an = angle_between(nref, c[found].normal);
        if (an > 1e-7 && m->cond < 1e-3) {
            /* A flat minimum (curvatures nearly matching): its points, hence the direction between
             * them, are only known to ~sqrt(eps) by any method. The library's pair must then be
             * stationary itself: its normal is A's normal at its own point. */
            st->illcond++;
            rugo_vec2 na = ref_normal(&ca, c[found].segment_a + c[found].t_a);
            an = fmin(an, angle_between(na, c[found].normal));
        }
        if (an > st->max_normal_err) st->max_normal_err = an;
    }
    /* Library -> reference: nothing spurious. */
    for (int i = 0; i < n; ++i) {
        int found = 0;
        for (int k = 0; k < R.nmin && !found; ++k)
            found = hypot(c[i].point_a.x - R.m[k].pa.x, c[i].point_a.y - R.m[k].pa.y) <= 1e-4 * size &&
                    hypot(c[i].point_b.x - R.m[k].pb.x, c[i].point_b.y - R.m[k].pb.y) <= 1e-4 * size;
        if (!found) {
            st->spurious++;
            if (g_verbose_failures++ < 10)
                printf("spurious %s/%s: sep %.9g seg %d/%d t %.6f/%.6f\n", A->name, B->name, c[i].separation,
                       c[i].segment_a, c[i].segment_b, c[i].t_a, c[i].t_b);
        }
    }
}

START_TEST(test_acceptance_random_poses) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    long N = 10000; /* also under the sanitizers: about 70 s there */
    if (getenv("RUGO_TEST_POSES") != NULL) N = atol(getenv("RUGO_TEST_POSES")); /* development runs */
    test_rng r = test_rng_seed(77);
    accept_stats st;
    memset(&st, 0, sizeof st);
    clock_t t0 = clock();
    for (long k = 0; k < N; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        double override = (k / 36) % 2 ? 0.02 * fmax(A->size, B->size) : -1.0;
        rugo_transform xa, xb;
        random_poses(&r, A, B, (int)(k % 3 == 0 ? 0 : 1), override, ctx, &xa, &xb);
        check_pose(ctx, A, xa, B, xb, override, &st);
    }
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    printf("acceptance: %ld poses (%s) in %.1f s: apart %ld, contact %ld, intersecting %ld (reference: %ld "
           "contained)\n",
           st.poses, UNDER_SANITIZER ? "sanitizer build" : "normal build", secs, st.apart, st.contact,
           st.intersecting, st.contained_ref);
    printf("acceptance: %ld overlap-region contacts, %ld of them from the sampling fallback\n",
           st.pen_contacts, st.region_fallbacks);
    printf("acceptance: contacts required by the reference %ld, compared %ld, missed %ld, spurious %ld; "
           "state mismatches %ld; ambiguous poses %ld, reference failures %ld, borderline minima %ld\n",
           st.required, st.compared, st.missed, st.spurious, st.state_mismatch, st.ambiguous, st.ref_fail,
           st.borderline);
    printf(
        "acceptance: max separation error %.3g x size, max normal error %.3g rad (%ld flat minima judged by "
        "stationarity); narrow-phase fallback rate %ld / %ld segment pairs = %.3g%%; %.1f box tests per "
        "query\n",
        st.max_sep_err, st.max_normal_err, st.illcond, st.fallbacks, st.segment_pairs,
        st.segment_pairs ? 100.0 * (double)st.fallbacks / (double)st.segment_pairs : 0.0,
        (double)st.box_tests / (double)st.poses);
    ck_assert_int_eq(st.missed, 0);
    ck_assert_int_eq(st.spurious, 0);
    ck_assert_int_eq(st.state_mismatch, 0);
    ck_assert(st.max_sep_err <= 1e-9);
    ck_assert(st.max_normal_err <= 1e-7);
    ck_assert(st.compared > N / 10);
    ck_assert(st.intersecting > N / 10);
    ck_assert(st.ambiguous + st.ref_fail <= N / 100);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- symmetry and invariance --------------------------------------------------------------------- */

static int query(rugo_collide_context* ctx, const tshape* A, rugo_transform xa, const tshape* B,
                 rugo_transform xb, double override, int level, rugo_contact* c, int cap,
                 rugo_contact_state* state) {
    rugo_contact_query q = test_exact_query();
    q.tolerance = override;
    q.lod = level;
    int n = -1;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c, cap, &n, state, NULL), RUGO_OK);
    return n;
}

START_TEST(test_swap_mirrors) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(123);
    enum { CAP = 64 };
    rugo_contact c1[CAP], c2[CAP];
    const int N = UNDER_SANITIZER ? 300 : 1500;
    int compared = 0;
    double worst = 0, worst_n = 0;
    for (int k = 0; k < N; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES + 1) % N_SHAPES];
        double override = k % 2 ? 0.02 * fmax(A->size, B->size) : -1.0;
        rugo_transform xa, xb;
        random_poses(&r, A, B, k % 3 == 0 ? 0 : 1, override, ctx, &xa, &xb);
        rugo_contact_state s1, s2;
        int n1 = query(ctx, A, xa, B, xb, override, 0, c1, CAP, &s1);
        int n2 = query(ctx, B, xb, A, xa, override, 0, c2, CAP, &s2);
        ck_assert_int_eq(s1, s2);
        ck_assert_int_eq(n1, n2);
        const double size = fmax(A->size, B->size);
        for (int i = 0; i < n1; ++i) {
            int j, found = -1;
            double best = 1e-6 * size;
            for (j = 0; j < n2; ++j) {
                double e = fmax(hypot(c1[i].point_a.x - c2[j].point_b.x, c1[i].point_a.y - c2[j].point_b.y),
                                hypot(c1[i].point_b.x - c2[j].point_a.x, c1[i].point_b.y - c2[j].point_a.y));
                if (e <= best) {
                    best = e;
                    found = j;
                }
            }
            ck_assert_msg(found >= 0, "swap: contact %d of %s/%s (%s, sep %g) has no mirror", i, A->name,
                          B->name, rugo_contact_state_name(s1), c1[i].separation);
            worst = fmax(worst, fabs(c1[i].separation - c2[found].separation) / size);
            worst_n = fmax(worst_n, angle_between(c1[i].normal, rugo_v2_scale(-1.0, c2[found].normal)));
            ck_assert(c1[i].segment_a == c2[found].segment_b || c1[i].t_a == 0.0 || c1[i].t_a > 0.999 ||
                      best > 0);
            ++compared;
        }
    }
    printf("swap: %d contacts mirrored, separation difference <= %.3g x size, normals antiparallel within "
           "%.3g rad\n",
           compared, worst, worst_n);
    ck_assert(worst <= 1e-9);
    ck_assert(worst_n <= 1e-7);
    rugo_collide_context_destroy(ctx);
}
END_TEST

static rugo_transform compose(rugo_transform t, rugo_transform x) {
    rugo_transform r;
    r.q.c = t.q.c * x.q.c - t.q.s * x.q.s;
    r.q.s = t.q.s * x.q.c + t.q.c * x.q.s;
    r.p = rugo_transform_point(t, x.p);
    return r;
}

START_TEST(test_rigid_motion_invariance) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(321);
    enum { CAP = 64 };
    rugo_contact c1[CAP], c2[CAP];
    const int N = UNDER_SANITIZER ? 300 : 1500;
    double worst_p = 0, worst_s = 0, worst_n = 0;
    int compared = 0, id_changes = 0;
    for (int k = 0; k < N; ++k) {
        const tshape* A = &g_shapes[(k + 2) % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        double override = k % 2 ? 0.02 * fmax(A->size, B->size) : -1.0;
        rugo_transform xa, xb;
        random_poses(&r, A, B, k % 3 == 0 ? 0 : 1, override, ctx, &xa, &xb);
        rugo_transform T = rugo_make_transform(test_rng_uniform(&r, -10, 10), test_rng_uniform(&r, -10, 10),
                                               test_rng_uniform(&r, 0, TWO_PI));
        rugo_contact_state s1, s2;
        int n1 = query(ctx, A, xa, B, xb, override, 0, c1, CAP, &s1);
        int n2 = query(ctx, A, compose(T, xa), B, compose(T, xb), override, 0, c2, CAP, &s2);
        ck_assert_int_eq(s1, s2);
        ck_assert_int_eq(n1, n2);
        const double size = fmax(A->size, B->size);
        for (int i = 0; i < n1; ++i) {
            /* Same order: sorting keys are identical up to round-off; match by id, else by position. */
            rugo_vec2 pa = rugo_transform_point(T, c1[i].point_a),
                      pb = rugo_transform_point(T, c1[i].point_b);
            int j = -1;
            double bd = HUGE_VAL;
            for (int m = 0; m < n2; ++m) {
                double e = hypot(pa.x - c2[m].point_a.x, pa.y - c2[m].point_a.y);
                if (e < bd) {
                    bd = e;
                    j = m;
                }
            }
            ck_assert_int_ge(j, 0);
            if (c1[i].id != c2[j].id)
                ++id_changes; /* a point at a joint may change segment under round-off */
            worst_p = fmax(worst_p, fmax(hypot(pa.x - c2[j].point_a.x, pa.y - c2[j].point_a.y),
                                         hypot(pb.x - c2[j].point_b.x, pb.y - c2[j].point_b.y)) /
                                        size);
            worst_s = fmax(worst_s, fabs(c1[i].separation - c2[j].separation) / size);
            worst_n = fmax(worst_n, angle_between(rugo_rotate(T.q, c1[i].normal), c2[j].normal));
            ++compared;
        }
    }
    printf("rigid motion: %d contacts (%d changed id), points within %.3g x size, separations within %.3g x "
           "size, normals "
           "within %.3g rad\n",
           compared, id_changes, worst_p, worst_s, worst_n);
    ck_assert(worst_p <= 1e-9 && worst_s <= 1e-9 && worst_n <= 1e-7);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- levels of detail ------------------------------------------------------------------------------ */

START_TEST(test_levels_of_detail_bound) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(555);
    enum { CAP = 64 };
    rugo_contact cf[CAP], cl[CAP];
    const int idx[3] = {1, 2, 5}; /* shapes with levels to spare */
    const int N = UNDER_SANITIZER ? 200 : 1000;
    for (int L = -1; L >= -2; --L) {
        long matched = 0, only_coarse = 0, only_fine = 0;
        double worst_ratio = 0;
        for (int k = 0; k < N; ++k) {
            const tshape* A = &g_shapes[idx[k % 3]];
            const tshape* B = &g_shapes[idx[(k / 3) % 3]];
            rugo_transform xa, xb;
            random_poses(&r, A, B, 1, -1.0, ctx, &xa, &xb);
            rugo_contact_state sf, sl;
            int nf = query(ctx, A, xa, B, xb, -1.0, 0, cf, CAP, &sf);
            int nl = query(ctx, A, xa, B, xb, -1.0, L, cl, CAP, &sl);
            if (sf != RUGO_STATE_CONTACT || sl != RUGO_STATE_CONTACT) {
                only_coarse += sl == RUGO_STATE_CONTACT ? nl : 0;
                only_fine += sf == RUGO_STATE_CONTACT ? nf : 0;
                continue;
            }
            for (int i = 0; i < nl; ++i) {
                rugo_tolerance_level ta, tb;
                rugo_shape_tolerance_level(A->s, cl[i].level_a, &ta);
                rugo_shape_tolerance_level(B->s, cl[i].level_b, &tb);
                const double beta = ta.bound[cl[i].segment_a] + tb.bound[cl[i].segment_b];
                /* The same contact at the finest level: the nearest one within the bound's reach. */
                int best = -1;
                double bd = 2.0 * beta + 0.05 * fmax(A->size, B->size);
                for (int j = 0; j < nf; ++j) {
                    double e = hypot(cf[j].point_a.x - cl[i].point_a.x, cf[j].point_a.y - cl[i].point_a.y);
                    if (e < bd) {
                        bd = e;
                        best = j;
                    }
                }
                if (best < 0) {
                    ++only_coarse;
                    continue;
                }
                ++matched;
                const double diff = fabs(cl[i].separation - cf[best].separation);
                worst_ratio = fmax(worst_ratio, diff / beta);
                ck_assert_msg(diff <= beta * (1 + 1e-9), "level %d: separation %g vs finest %g, bound %g", L,
                              cl[i].separation, cf[best].separation, beta);
            }
            for (int j = 0; j < nf; ++j) {
                int any = 0;
                for (int i = 0; i < nl && !any; ++i)
                    any = hypot(cf[j].point_a.x - cl[i].point_a.x, cf[j].point_a.y - cl[i].point_a.y) <
                          0.05 * fmax(A->size, B->size) + 2.0 * (A->max_lambda + B->max_lambda);
                only_fine += !any;
            }
        }
        printf("level %d vs finest: %ld contacts matched, |separation difference| <= %.3f of the summed hard "
               "bound "
               "beta; %ld contacts only at level %d, %ld only at the finest level\n",
               L, matched, worst_ratio, only_coarse, L, only_fine);
        ck_assert(matched > 0);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- hard cases ---------------------------------------------------------------------------------- */

static void assert_finite_contacts(const rugo_contact* c, int n) {
    for (int i = 0; i < n; ++i) {
        ck_assert(isfinite(c[i].separation) && isfinite(c[i].normal.x) && isfinite(c[i].normal.y));
        ck_assert(isfinite(c[i].point_a.x) && isfinite(c[i].point_a.y) && isfinite(c[i].point_b.x) &&
                  isfinite(c[i].point_b.y));
        ck_assert(isfinite(c[i].tolerance_a) && isfinite(c[i].friction) && isfinite(c[i].restitution));
        ck_assert(fabs(hypot(c[i].normal.x, c[i].normal.y) - 1.0) < 1e-12);
    }
}

/* Two ellipses tip to tip at gap delta (negative: overlap), down to round-off. */
START_TEST(test_near_tangent) {
    build_shapes();
    const tshape* E = &g_shapes[0];
    rugo_vec2 lo, hi;
    rugo_contour_bounds(E->fine, &lo, &hi);
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const double size = E->size, band = 1e-5 * size;
    const double deltas[] = {1e-3, 1e-5, 1e-6, 1e-9, 1e-12, 0.0, -1e-12, -1e-9, -1e-6, -1e-3};
    for (size_t k = 0; k < sizeof deltas / sizeof deltas[0]; ++k) {
        const double d = deltas[k] * size;
        rugo_contact c[16];
        rugo_contact_state st;
        int n = query(ctx, E, rugo_identity_transform(), E, rugo_make_transform(hi.x - lo.x + d, 0, 0),
                      band / 2, 0, c, 16, &st);
        assert_finite_contacts(c, n);
        printf("near tangent: gap %+.0e x size -> %s, %d contact(s)%s", deltas[k],
               rugo_contact_state_name(st), n, n ? "," : "\n");
        if (n) printf(" separation %+.3e x size\n", c[0].separation / size);
        if (d > band)
            ck_assert_int_eq(st, RUGO_STATE_APART);
        else if (d >= 1e-9 * size)
            ck_assert_int_eq(st, RUGO_STATE_CONTACT);
        else if (d <= -1e-9 * size)
            ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        else
            ck_assert_int_ne(st, RUGO_STATE_APART);
        if (n > 0) ck_assert_near(c[0].separation, d, 1e-9 * size);
        if (n > 0) ck_assert(angle_between(c[0].normal, rugo_v2(1, 0)) < 1e-6);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* Straight sides facing each other: infinitely many closest pairs. */
START_TEST(test_parallel_straight_segments) {
    build_shapes();
    const tshape* Q = &g_shapes[3];
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const double deltas[] = {0.004, -0.004};
    for (int k = 0; k < 2; ++k) {
        const double d = deltas[k];
        rugo_transform xb = rugo_make_transform(0.2, 1.6 + d, PI);
        rugo_contact c[32];
        rugo_contact_state st;
        int n = query(ctx, Q, rugo_identity_transform(), Q, xb, 0.005, 0, c, 32, &st);
        assert_finite_contacts(c, n);
        printf("parallel straight sides at %+g: %s, %d contact(s)\n", d, rugo_contact_state_name(st), n);
        ck_assert_int_eq(st, d > 0 ? RUGO_STATE_CONTACT : RUGO_STATE_INTERSECTING);
        ck_assert_int_ge(n, 1);
        for (int i = 0; i < n; ++i) {
            ck_assert_near(c[i].separation, d, 1e-9);
            ck_assert(angle_between(c[i].normal, rugo_v2(0, 1)) < 1e-9);
            ck_assert(c[i].point_a.x >= -0.3 - 1e-6 && c[i].point_a.x <= 0.5 + 1e-6);
        }
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* A sharp corner made by a segment shrunk to a point, against a smooth curve. */
START_TEST(test_point_like_segments) {
    build_shapes();
    const tshape* D = &g_shapes[4];
    const tshape* E = &g_shapes[0];
    rugo_vec2 lo, hi;
    rugo_contour_bounds(E->fine, &lo, &hi);
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const rugo_vec2 corner = rugo_v2(0.9, 0.6), dir = rugo_v2(sqrt(0.5), sqrt(0.5));
    for (int k = 0; k < 2; ++k) {
        const double d = k == 0 ? 0.005 : -0.005;
        /* E's leftmost point (lo.x, 0), outward normal (-1, 0), turned to face the corner. */
        rugo_transform xb = rugo_make_transform(0, 0, PI / 4);
        rugo_vec2 tip = rugo_rotate(xb.q, rugo_v2(lo.x, 0));
        xb.p = rugo_v2(corner.x + d * dir.x - tip.x, corner.y + d * dir.y - tip.y);
        rugo_contact c[16];
        rugo_contact_state st;
        int n = query(ctx, D, rugo_identity_transform(), E, xb, 0.01, 0, c, 16, &st);
        assert_finite_contacts(c, n);
        printf("point-like corner at %+g: %s, %d contact(s), separation %.12g, normal (%.9f, %.9f)\n", d,
               rugo_contact_state_name(st), n, n ? c[0].separation : 0.0, n ? c[0].normal.x : 0.0,
               n ? c[0].normal.y : 0.0);
        ck_assert_int_eq(st, d > 0 ? RUGO_STATE_CONTACT : RUGO_STATE_INTERSECTING);
        ck_assert_int_eq(n, 1);
        ck_assert_near(c[0].separation, d, 1e-9);
        ck_assert(angle_between(c[0].normal, dir) < 1e-7);
        ck_assert_near(c[0].point_a.x, corner.x, 1e-9);
        ck_assert_near(c[0].point_a.y, corner.y, 1e-9);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* A polygon whose vertices are `mult` coincident control points each (3: sharp corners, zero speed
 * there; 4: a point-like segment at each), with inner[i] more points evenly spaced on the side from
 * vertex i to the next, and a constant band lam. */
/* The control points of sharp_polygon into p (at most 64); returns their count. */
static int sharp_points(const rugo_vec2* v, int nv, int mult, const int* inner, rugo_vec2* p) {
    int k = 0;
    for (int i = 0; i < nv; ++i) {
        const rugo_vec2 a = v[i], b = v[(i + 1) % nv];
        for (int m = 0; m < mult; ++m)
            p[k++] = a;
        for (int j = 1; j <= inner[i]; ++j)
            p[k++] = rugo_v2(a.x + j * (b.x - a.x) / (inner[i] + 1), a.y + j * (b.y - a.y) / (inner[i] + 1));
    }
    return k;
}

static rugo_shape* sharp_polygon(const rugo_vec2* v, int nv, int mult, const int* inner, double lam) {
    rugo_vec2 p[64];
    double tol[64];
    const int k = sharp_points(v, nv, mult, inner, p);
    for (int i = 0; i < k; ++i)
        tol[i] = lam;
    return make_shape(p, k, tol);
}

/* A w x h block of 32 points: `mult` coincident points a corner and 8 - mult more on each side. */
static rugo_shape* sharp_block(double w, double h, double lam, int mult) {
    const double x = 0.5 * w, y = 0.5 * h;
    const rugo_vec2 c[4] = {{x, -y}, {x, y}, {-x, y}, {-x, -y}};
    const int inner[4] = {8 - mult, 8 - mult, 8 - mult, 8 - mult};
    return sharp_polygon(c, 4, mult, inner, lam);
}

/* Coarse levels are simple closed curves (regression, found by a review's symmetry sweep on
 * 2026-11-22). A triangle whose corners are four coincident control points has a level (8 points) that
 * loops at a corner; queries at it reported INTERSECTING with a contact 0.4-0.9 of the body's size deep
 * between bodies that were apart, and a different state when the shapes were swapped. rugo_shape_create
 * now keeps only the levels from the coarsest simple one up (shape.h). Checked: every level a shape
 * keeps passes rugo_contour_check's crossing test, for triangles and blocks with 1 to 4 coincident
 * points per corner; the triangle built without the crossing check keeps a looping level (so the rule
 * is what removes it); and the triangle 1 cm above a polygon floor, turned through 72 angles, is
 * APART at levels 0 to -3. */
static double lowest_height(rugo_contour c, double angle, rugo_vec2* at);

/* The depth of an overlap region is a pair whose one point is the other curve's closest point to the
 * other (regression, found by a review's cross-check of shapes against primitives on 2026-11-22). At a
 * corner of four coincident control points, (f - g)·f' vanishes for every g, so the corner paired with
 * feet all over B, and the region's "deepest" stationary pair ran across B: -0.1745 where the overlap is
 * 0.0036 deep. Checked: a block with four-point corners poking into an octagon, at the review's pose
 * and turned by up to ±0.05 rad about it: rugo_collide_shapes against the octagon as a shape (three
 * coincident points per vertex, straight sides: the same curve) gives the same deepest separation as
 * rugo_collide_polygon against the octagon, to 1e-9. */
START_TEST(test_region_depth_is_a_closest_pair) {
    rugo_shape* block = sharp_block(0.7, 0.6, 0.0, 4);
    const rugo_vec2 V[8] = {
        {-0x1.a46189f35bb37p+2, -0x1.6ae1dfff6bba6p+2}, {-0x1.aefe530186882p+2, -0x1.6eff56b7d9c0bp+2},
        {-0x1.b558e542eb394p+2, -0x1.79007a55904e7p+2}, {-0x1.b440324a83ff9p+2, -0x1.8515d11221a23p+2},
        {-0x1.a1ae67611e4b8p+2, -0x1.8ffd3dd76ce8fp+2}, {-0x1.95708316490b5p+2, -0x1.89e1d802e4131p+2},
        {-0x1.927112f9315dap+2, -0x1.855b905ccb4efp+2}, {-0x1.92a4124739f72p+2, -0x1.7523ab2c64008p+2}};
    rugo_vec2 cen = {0.0, 0.0}, loc[8];
    for (int i = 0; i < 8; ++i)
        cen = rugo_v2_add(cen, rugo_v2_scale(0.125, V[i]));
    for (int i = 0; i < 8; ++i)
        loc[i] = rugo_v2_sub(V[i], cen);
    const int inner[8] = {13, 13, 13, 13, 13, 13, 13, 13};
    rugo_vec2 pts[128];
    double tol[128] = {0};
    const int nb = sharp_points(loc, 8, 3, inner, pts);
    ck_assert_int_eq(nb, 128);
    rugo_shape* octagon = make_shape(pts, nb, tol);
    const rugo_transform xb = {cen, {1.0, 0.0}};
    const rugo_transform x0 = {{-0x1.80ac5b71448b1p+2, -0x1.65b9d92093a3ep+2},
                               {-0x1.f8d85e4b03c2bp-2, -0x1.bd73866c3d051p-1}};
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    rugo_contact_query q = test_exact_query();
    q.margin = 0x1.1e27bd9c8656p-6;
    int overlapping = 0;
    for (int k = -5; k <= 5; ++k) {
        const double turn = 0.01 * k, c = cos(turn), sn = sin(turn);
        rugo_transform xa = x0;
        xa.q.c = c * x0.q.c - sn * x0.q.s;
        xa.q.s = sn * x0.q.c + c * x0.q.s;
        rugo_contact cs[16], cp[16];
        int ns = -1, np = -1;
        rugo_contact_state ss, sp;
        ck_assert_int_eq(test_collide_shapes(ctx, block, xa, octagon, xb, &q, cs, 16, &ns, &ss, NULL),
                         RUGO_OK);
        ck_assert_int_eq(test_collide_polygon(ctx, block, xa, V, 8, 0.0, &q, cp, 16, &np, &sp, NULL),
                         RUGO_OK);
        ck_assert_int_eq(ss, sp);
        double ds = HUGE_VAL, dp = HUGE_VAL;
        for (int i = 0; i < ns; ++i)
            ds = fmin(ds, cs[i].separation);
        for (int i = 0; i < np; ++i)
            dp = fmin(dp, cp[i].separation);
        overlapping += sp == RUGO_STATE_INTERSECTING;
        ck_assert_msg(fabs(ds - dp) <= 1e-9, "turn %g: deepest %.9e as a shape, %.9e as a polygon", turn, ds,
                      dp);
    }
    ck_assert_int_gt(overlapping, 5);
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(octagon);
    rugo_shape_destroy(block);
}
END_TEST

/* A primitive much longer than the shape keeps the shape's resolution (regression, found by a review
 * of the primitive queries on 2026-11-22). The resolution was the larger of the two sizes and the
 * narrow phase ran each piece against the whole edge: an overlap shallower than ~4e-14 W^2 of a ground
 * box or capsule of half-length W was APART (1e-10 at W = 50, 1e-4 at W = 50 000). Now each edge is
 * clipped to the piece's projection first. Checked: an ellipse (size ~2.8) pushed 1e-4 .. 1e-10 into a
 * box, a capsule and an edge of half-length 5 .. 50 000 is INTERSECTING with that depth (to 1e-6 of it,
 * plus the round-off of placing the floor) and the floor's normal; held 1e-6 above, it is APART. */
START_TEST(test_long_primitives_keep_resolution) {
    rugo_vec2 p[16];
    for (int i = 0; i < 16; ++i)
        p[i] = rugo_v2(1.2 * cos(2.0 * M_PI * i / 16), 0.7 * sin(2.0 * M_PI * i / 16));
    rugo_shape* s = make_shape(p, 16, NULL);
    rugo_contour c;
    rugo_shape_level(s, rugo_shape_finest_level(s), &c);
    rugo_vec2 at;
    const double ymin = lowest_height(c, 0.0, &at);
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const rugo_transform x = rugo_make_transform(0.0, 0.0, 0.0);
    const double Ws[5] = {5.0, 50.0, 500.0, 5000.0, 50000.0};
    for (int w = 0; w < 5; ++w)
        for (int k = 4; k <= 11; ++k) {
            const double W = Ws[w], dep = k <= 10 ? pow(10.0, -k) : -1e-6; /* the last: 1e-6 apart */
            const double top = ymin + dep;
            for (int kind = 0; kind < 3; ++kind) {
                rugo_contact ct[16];
                int n = -1;
                rugo_contact_state st;
                rugo_status status;
                if (kind == 0) {
                    const rugo_vec2 box[4] = {{-W, top - 1.0}, {W, top - 1.0}, {W, top}, {-W, top}};
                    status = test_collide_polygon(ctx, s, x, box, 4, 0.0, NULL, ct, 16, &n, &st, NULL);
                } else {
                    const double r = kind == 1 ? 0.05 : 0.0;
                    status = test_collide_segment(ctx, s, x, rugo_v2(-W, top - r), rugo_v2(W, top - r), r,
                                                  NULL, ct, 16, &n, &st, NULL);
                }
                ck_assert_int_eq(status, RUGO_OK);
                if (dep < 0.0) {
                    ck_assert_msg(st == RUGO_STATE_APART && n == 0, "W %g kind %d apart: state %d", W, kind,
                                  (int)st);
                    continue;
                }
                ck_assert_msg(st == RUGO_STATE_INTERSECTING && n >= 1, "W %g depth %g kind %d: state %d", W,
                              dep, kind, (int)st);
                double deepest = 0.0;
                int di = 0;
                for (int i = 0; i < n; ++i)
                    if (ct[i].separation < deepest) deepest = ct[i].separation, di = i;
                /* (1e-15: the round-off of top = ymin + dep itself, ymin ~ -0.7) */
                ck_assert_msg(fabs(deepest + dep) <= 1e-6 * dep + 1e-15,
                              "W %g depth %g kind %d: separation %.6e", W, dep, kind, deepest);
                ck_assert_msg(ct[di].normal.y < -0.999999, "W %g depth %g kind %d: normal (%g, %g)", W, dep,
                              kind, ct[di].normal.x, ct[di].normal.y);
            }
        }
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(s);
}
END_TEST

START_TEST(test_coarse_levels_are_simple_curves) {
    const rugo_vec2 tri[3] = {{-0.8, -0.5}, {0.9, -0.4}, {-0.1, 0.8}};
    const int tri_inner[3] = {2, 1, 1};
    int raised = 0;
    for (int mult = 1; mult <= 4; ++mult) {
        const int inner[3] = {tri_inner[0] + 4 - mult, tri_inner[1] + 4 - mult, tri_inner[2] + 4 - mult};
        rugo_shape* shapes[2] = {sharp_polygon(tri, 3, mult, mult == 4 ? tri_inner : inner, 0.0),
                                 sharp_block(1.0, 0.6, 0.0, mult)};
        for (int k = 0; k < 2; ++k) {
            rugo_shape* sh = shapes[k];
            for (int j = rugo_shape_coarsest_level(sh); j <= rugo_shape_finest_level(sh); ++j) {
                rugo_contour c;
                ck_assert_int_eq(rugo_shape_level(sh, j, &c), RUGO_OK);
                ck_assert_msg(rugo_contour_check(c.points, c.count, RUGO_CHECK_SELF_INTERSECTION, NULL,
                                                 NULL) == RUGO_OK,
                              "mult %d shape %d level %d", mult, k, j);
            }
            raised += rugo_shape_coarsest_level(sh) > 2;
            rugo_shape_destroy(sh);
        }
    }
    ck_assert_int_gt(raised, 0); /* the rule did drop levels somewhere */

    /* The four-point triangle without the crossing check keeps level 2 and a looping level. */
    rugo_vec2 p[64];
    const int n = sharp_points(tri, 3, 4, tri_inner, p);
    ck_assert_int_eq(n, 16);
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p;
    d.count = n;
    d.check_self_intersection = false;
    rugo_shape* unchecked = NULL;
    ck_assert_int_eq(rugo_shape_create(&d, &unchecked, NULL), RUGO_OK);
    ck_assert_int_eq(rugo_shape_coarsest_level(unchecked), 2);
    int loops = 0;
    for (int j = 2; j < rugo_shape_finest_level(unchecked); ++j) {
        rugo_contour c;
        rugo_shape_level(unchecked, j, &c);
        loops += rugo_contour_check(c.points, c.count, RUGO_CHECK_SELF_INTERSECTION, NULL, NULL) ==
                 RUGO_ERR_SELF_INTERSECTING;
    }
    ck_assert_int_gt(loops, 0);
    rugo_shape_destroy(unchecked);
    rugo_shape* t4 = make_shape(p, n, NULL);
    ck_assert_int_gt(rugo_shape_coarsest_level(t4), 3);

    /* Apart stays apart at every level asked for (against a polygon floor, which has no levels). */
    const rugo_vec2 floor[4] = {{-20.0, -0.5}, {20.0, -0.5}, {20.0, 0.5}, {-20.0, 0.5}};
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    rugo_contour fine;
    rugo_shape_level(t4, rugo_shape_finest_level(t4), &fine);
    for (int a = 0; a < 72; ++a) {
        const double angle = 2.0 * M_PI * a / 72.0;
        rugo_vec2 at;
        const double low = lowest_height(fine, angle, &at);
        const rugo_transform xt = rugo_make_transform(0.0, 0.5 + 0.01 - low, angle);
        for (int level = 0; level >= -3; --level) {
            rugo_contact_query q = test_exact_query();
            q.lod = level;
            rugo_contact c[8];
            int count = -1;
            rugo_contact_state st;
            ck_assert_int_eq(test_collide_polygon(ctx, t4, xt, floor, 4, 0.0, &q, c, 8, &count, &st, NULL),
                             RUGO_OK);
            ck_assert_msg(st == RUGO_STATE_APART && count == 0, "angle %d level %d: state %d", a, level,
                          (int)st);
        }
    }
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(t4);
}
END_TEST

/* Regression (docs/simulator.md listed it as a known limit until 2026-11-22): a sharp corner tilted
 * over a flat face, within the bands, was reported APART, because the two segments meeting at the
 * corner each classified it by extrapolating their cubic past the corner (where it runs on along the
 * same side) and called it a saddle. Now each piece looks at its own side only and the corner is a
 * minimum when every piece that reaches it rises there. Checked against a floor shape and the
 * primitives (segment, polygon, polygon with a radius, circle), both tilt directions, gaps within the
 * bands: exactly one contact, at the lowest corner, at the right separation; the block's other bottom
 * corner (also within the bands, but not a minimum: the bottom edge falls away from it) is not one. A
 * gap beyond the bands (5.5 mm against a smooth primitive, which has no band) is APART. Blocks 0.6 and
 * 0.7 wide: at x = ±0.35 the corner's Bezier points differ by round-off, so the corner's speed is a few
 * ulps, not zero, and the search finds no root there (the review of the first fix found that); with
 * three and with four coincident points (a point-like segment, whose classification is round-off). */
START_TEST(test_sharp_corner_tilted) {
    const double lam = 0.004; /* bands of both bodies: 8 mm together */
    int cases = 0;
    for (int variant = 0; variant < 4; ++variant) {
        const double width = variant % 2 ? 0.7 : 0.6;
        const int mult = variant < 2 ? 3 : 4;
        rugo_shape* blk = sharp_block(width, 0.3, lam, mult);
        rugo_shape* floor = sharp_block(40.0, 1.0, lam, mult);
        rugo_collide_context* ctx = NULL;
        rugo_collide_context_create(NULL, &ctx);
        const double tilts[] = {0.0005, 0.0036, 0.02, -0.0005, -0.0036, -0.02};
        const double gaps[] = {0.0005, 0.0029, 0.0055};
        for (size_t it = 0; it < sizeof tilts / sizeof tilts[0]; ++it)
            for (size_t ig = 0; ig < sizeof gaps / sizeof gaps[0]; ++ig) {
                const double tilt = tilts[it], gap = gaps[ig];
                rugo_transform xb = rugo_make_transform(0.0, 0.0, tilt);
                /* the lower bottom corner: left for a counter-clockwise tilt */
                const rugo_vec2 low =
                    rugo_transform_point(xb, rugo_v2(tilt > 0 ? -0.5 * width : 0.5 * width, -0.15));
                xb.p.y = gap - low.y;
                const rugo_vec2 corner = rugo_v2(low.x, gap);
                for (int kind = 0; kind < 5; ++kind) {
                    rugo_contact c[16];
                    rugo_contact_state st = RUGO_STATE_APART;
                    int n = -1;
                    rugo_contact_query q = test_exact_query();
                    const rugo_vec2 box[4] = {{-5, -1}, {5, -1}, {5, 0}, {-5, 0}};
                    const rugo_vec2 raised[4] = {{-5, -1}, {5, -1}, {5, -0.001}, {-5, -0.001}};
                    rugo_status r = RUGO_OK;
                    if (kind == 0)
                        r = test_collide_shapes(ctx, blk, xb, floor, rugo_make_transform(0, -0.5, 0), &q, c,
                                                16, &n, &st, NULL);
                    else if (kind == 1)
                        r = test_collide_segment(ctx, blk, xb, rugo_v2(-5, 0), rugo_v2(5, 0), 0.0, &q, c, 16,
                                                 &n, &st, NULL);
                    else if (kind == 2)
                        r = test_collide_polygon(ctx, blk, xb, box, 4, 0.0, &q, c, 16, &n, &st, NULL);
                    else if (kind == 3) /* the same face as a polygon 1 mm lower grown by 1 mm */
                        r = test_collide_polygon(ctx, blk, xb, raised, 4, 0.001, &q, c, 16, &n, &st, NULL);
                    else /* a circle of radius 100 whose top is at y = 0 under the corner */
                        r = test_collide_circle(ctx, blk, xb, rugo_v2(corner.x, -100.0), 100.0, &q, c, 16, &n,
                                                &st, NULL);
                    ck_assert_int_eq(r, RUGO_OK);
                    /* the primitives are smooth (no band): only the block's band reaches them */
                    const double reach = kind == 0 ? 2.0 * lam : lam;
                    if (gap > reach) {
                        ck_assert_msg(st == RUGO_STATE_APART && n == 0,
                                      "tilt %g gap %g against %d: state %s, %d contacts", tilt, gap, kind,
                                      rugo_contact_state_name(st), n);
                        continue;
                    }
                    ck_assert_msg(
                        st == RUGO_STATE_CONTACT && n == 1,
                        "%g wide, %d points a corner, tilt %g gap %g against %d: state %s, %d contacts",
                        width, mult, tilt, gap, kind, rugo_contact_state_name(st), n);
                    ck_assert_near(c[0].point_a.x, corner.x, 1e-9);
                    ck_assert_near(c[0].point_a.y, corner.y, 1e-9);
                    ck_assert_near(c[0].separation, gap, 1e-9);
                    ++cases;
                }
            }
        /* Corner over corner: the block's lowest corner 1 mm straight above the floor block's top corner,
         * both turned so that no side comes nearer (a minimum of the distance between the two corners). */
        for (int k = 0; k < 3; ++k) {
            const double aa = 0.3354 + 0.2 * k, ab = aa + 0.07 + 0.06 * k;
            rugo_transform xa = rugo_make_transform(0, 0, aa), xb = rugo_make_transform(0, 0, ab);
            const rugo_vec2 lo = rugo_transform_point(xa, rugo_v2(-0.5 * width, -0.15));
            const rugo_vec2 hi = rugo_transform_point(xb, rugo_v2(0.5 * width, 0.15));
            xa.p = rugo_v2(-lo.x, 0.001 - lo.y);
            xb.p = rugo_v2(-hi.x, -hi.y);
            rugo_contact c[8];
            rugo_contact_state st;
            int n = -1;
            ck_assert_int_eq(test_collide_shapes(ctx, blk, xa, blk, xb, NULL, c, 8, &n, &st, NULL), RUGO_OK);
            ck_assert_msg(st == RUGO_STATE_CONTACT && n == 1,
                          "corner over corner, %g wide, %d points: state %s, %d contacts", width, mult,
                          rugo_contact_state_name(st), n);
            ck_assert_near(c[0].point_a.x, 0.0, 1e-9);
            ck_assert_near(c[0].point_a.y, 0.001, 1e-9);
            ck_assert_near(c[0].separation, 0.001, 1e-9);
            ++cases;
        }
        rugo_collide_context_destroy(ctx);
        rugo_shape_destroy(blk);
        rugo_shape_destroy(floor);
    }
    /* per variant: 90 poses and kinds less the 24 that the gap of 5.5 mm puts beyond a primitive's reach,
     * and 3 corner-over-corner poses */
    ck_assert_int_eq(cases, 4 * (90 - 6 * 4 + 3));
}
END_TEST

/* The lowest point of a curve (after a turn by `angle`), refined by golden section from dense samples:
 * on a smooth curve its height is exact to round-off (the height is flat there). */
static double lowest_height(rugo_contour c, double angle, rugo_vec2* at) {
    const rugo_transform x = rugo_make_transform(0.0, 0.0, angle);
    const int per = 256;
    double best = HUGE_VAL, bu = 0.0;
    for (int i = 0; i < c.count * per; ++i) {
        const double u = (double)i / per;
        const double y = rugo_transform_point(x, rugo_contour_point_at(c, u)).y;
        if (y < best) best = y, bu = u;
    }
    double lo = bu - 1.0 / per, hi = bu + 1.0 / per;
    for (int it = 0; it < 200; ++it) {
        const double u1 = hi - 0.6180339887498949 * (hi - lo), u2 = lo + 0.6180339887498949 * (hi - lo);
        const double y1 = rugo_transform_point(x, rugo_contour_point_at(c, fmod(u1 + c.count, c.count))).y;
        const double y2 = rugo_transform_point(x, rugo_contour_point_at(c, fmod(u2 + c.count, c.count))).y;
        if (y1 <= y2)
            hi = u2;
        else
            lo = u1;
    }
    const rugo_vec2 p =
        rugo_transform_point(x, rugo_contour_point_at(c, fmod(0.5 * (lo + hi) + c.count, c.count)));
    if (p.y < best) best = p.y, bu = 0.5 * (lo + hi);
    *at = rugo_transform_point(x, rugo_contour_point_at(c, fmod(bu + c.count, c.count)));
    return best;
}

/* An overlap so shallow that its two crossings lie within the resolution of each other (SAME_POINT of
 * the size: 4e-8 against a 40-unit floor) still gets a contact. Before 2026-11-22 a sharp corner or
 * the lowest point of an ellipse pushed 1e-8 to 1e-12 into a floor shape, a segment or a polygon was
 * often INTERSECTING with no contact at all: the two crossings merged into one, or the crossing next
 * to the corner was taken for a touching (the narrow phase's tangent there pointed backwards), and one
 * crossing closes no region. Every contact lies at the overlap, no deeper than it, with a normal that
 * takes it apart (the floor's, within 15 degrees: the review of the first version found the normal of
 * the corner's other face, up to 90 degrees off, and at a triangle's corner one pointing into A), also
 * with the floor as A; no two contacts at one point; a resolved overlap (1e-6) reports its depth. */
START_TEST(test_shallow_overlap_has_contact) {
    rugo_shape* blk = sharp_block(0.6, 0.3, 0.004, 3);
    const rugo_vec2 tv[3] = {{0.0, 0.3}, {-0.25, -0.15}, {0.3, -0.2}};
    const int tin[3] = {8, 7, 8};
    rugo_shape* tri = sharp_polygon(tv, 3, 3, tin, 0.004);
    rugo_shape* floor = sharp_block(40.0, 1.0, 0.004, 3);
    rugo_vec2 ep[32];
    double et[32];
    for (int i = 0; i < 32; ++i) {
        ep[i] = rugo_v2(0.3 * cos(2.0 * M_PI * i / 32), 0.2 * sin(2.0 * M_PI * i / 32));
        et[i] = 0.004;
    }
    rugo_shape* ell = make_shape(ep, 32, et);
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const char* names[3] = {"block", "triangle", "ellipse"};
    rugo_shape* shapes[3] = {blk, tri, ell};
    const double angles[] = {0.013, 0.231166, 0.7, -0.4, 0.1439, 0.8420, 4.1897902047863909};
    const double depths[] = {1e-6, 1e-8, 1e-10, 1e-12};
    const rugo_transform xf = rugo_make_transform(0, -0.5, 0);
    int cases = 0;
    for (int which = 0; which < 3; ++which) {
        rugo_shape* A = shapes[which];
        rugo_contour c;
        rugo_shape_level(A, rugo_shape_finest_level(A), &c);
        for (size_t ia = 0; ia < sizeof angles / sizeof angles[0]; ++ia) {
            rugo_vec2 low;
            const double ymin = lowest_height(c, angles[ia], &low);
            for (size_t id = 0; id < sizeof depths / sizeof depths[0]; ++id) {
                const double depth = depths[id];
                rugo_transform xa = rugo_make_transform(0.05, -depth - ymin, angles[ia]);
                const rugo_vec2 lowest = rugo_v2(low.x + 0.05, -depth);
                for (int kind = 0; kind < 4; ++kind) { /* floor shape, segment, polygon, floor shape as A */
                    rugo_contact k[16];
                    rugo_contact_state st = RUGO_STATE_APART;
                    int n = -1;
                    rugo_contact_query q = test_exact_query();
                    const rugo_vec2 box[4] = {{-5, -1}, {5, -1}, {5, 0}, {-5, 0}};
                    rugo_status r;
                    if (kind == 0)
                        r = test_collide_shapes(ctx, A, xa, floor, xf, &q, k, 16, &n, &st, NULL);
                    else if (kind == 1)
                        r = test_collide_segment(ctx, A, xa, rugo_v2(-5, 0), rugo_v2(5, 0), 0.0, &q, k, 16,
                                                 &n, &st, NULL);
                    else if (kind == 2)
                        r = test_collide_polygon(ctx, A, xa, box, 4, 0.0, &q, k, 16, &n, &st, NULL);
                    else
                        r = test_collide_shapes(ctx, floor, xf, A, xa, &q, k, 16, &n, &st, NULL);
                    ck_assert_int_eq(r, RUGO_OK);
                    /* 1e-12 is below the resolution of near-tangent smooth curves against a 40-unit floor
                     * (2.5e-14 of its size: crossings that close merge into a touching): CONTACT there */
                    ck_assert_msg(
                        (st == RUGO_STATE_INTERSECTING || (depth < 1e-11 && st == RUGO_STATE_CONTACT)) &&
                            n >= 1,
                        "%s at %g rad, %g deep into %d: state %s, %d contacts", names[which], angles[ia],
                        depth, kind, rugo_contact_state_name(st), n);
                    double deepest = 0.0;
                    for (int i = 0; i < n; ++i) {
                        ck_assert_msg(k[i].separation <= 1e-12 && k[i].separation >= -1.01 * depth - 1e-14,
                                      "%s at %g rad, %g deep into %d: separation %g", names[which],
                                      angles[ia], depth, kind, k[i].separation);
                        ck_assert_near(hypot(k[i].normal.x, k[i].normal.y), 1.0, 1e-12);
                        /* from the shape down into the floor (from the floor up when it is A); not for an
                         * edge's resolved piece (id index 0): it takes the normal of A's boundary nearest its
                         * deepest point, the shortest way out of A (contacts.md, "Primitives"), which at a
                         * sharp corner is one of its flanks */
                        const double down = kind == 3 ? k[i].normal.y : -k[i].normal.y;
                        const int edge_piece = kind == 1 && (k[i].id & 0xFFF) == 0;
                        ck_assert_msg(edge_piece || down >= cos(15.0 * M_PI / 180.0),
                                      "%s at %g rad, %g deep into %d: normal (%g, %g)", names[which],
                                      angles[ia], depth, kind, k[i].normal.x, k[i].normal.y);
                        /* at the overlap: its crossings lie within sqrt(2 depth R) (ellipse), depth / tan
                         * (corner) of the lowest point */
                        const rugo_vec2 on = kind == 3 ? k[i].point_b : k[i].point_a;
                        ck_assert_msg(hypot(on.x - lowest.x, on.y - lowest.y) <= 1e-4,
                                      "%s at %g rad, %g deep into %d: point (%g, %g), lowest (%g, %g)",
                                      names[which], angles[ia], depth, kind, on.x, on.y, lowest.x, lowest.y);
                        for (int j = 0; j < i; ++j)
                            ck_assert_msg(hypot(k[j].point_a.x - k[i].point_a.x,
                                                k[j].point_a.y - k[i].point_a.y) > 1e-9,
                                          "%s at %g rad, %g deep into %d: contacts %d and %d at one point",
                                          names[which], angles[ia], depth, kind, j, i);
                        if (k[i].separation < deepest) deepest = k[i].separation;
                    }
                    /* resolved: the depth along the normal of A's face or of the floor; an edge reports
                     * the deepest point of its chord through A, nearer A's boundary than the corner is to
                     * the edge (0.71-0.99 of the depth here) */
                    if (depth >= 1e-6)
                        ck_assert_msg(deepest <= (kind == 1 ? -0.5 : -0.98) * depth,
                                      "%s at %g rad into %d: depth %g reported %g", names[which], angles[ia],
                                      kind, depth, deepest);
                    ++cases;
                }
            }
        }
    }
    ck_assert_int_eq(cases, 3 * 7 * 4 * 4);
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(blk);
    rugo_shape_destroy(tri);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(ell);
}
END_TEST

/* Documented: coincident curves are CONTACT at separation 0 (what the narrow phase reports fits). */
START_TEST(test_coincident_curves) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    for (int k = 0; k < N_SHAPES; ++k) {
        const tshape* A = &g_shapes[k];
        rugo_transform x = rugo_make_transform(0.3, -0.2, 0.4);
        rugo_contact c[64];
        rugo_contact_state st;
        rugo_query_stats qs;
        rugo_contact_query q = test_exact_query();
        int n = 0;
        clock_t t0 = clock();
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, x, A->s, x, &q, c, 64, &n, &st, &qs), RUGO_OK);
        double ms = 1e3 * (double)(clock() - t0) / CLOCKS_PER_SEC;
        assert_finite_contacts(c, n);
        printf("coincident %s: %s, %d contacts (found %d), %ld segment pairs, %.1f ms\n", A->name,
               rugo_contact_state_name(st), n, qs.contacts_found, qs.segment_pairs, ms);
        ck_assert_int_ne(st, RUGO_STATE_APART);
        for (int i = 0; i < n; ++i)
            ck_assert(fabs(c[i].separation) <= 1e-9 * A->size);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

static rugo_shape* scaled_copy(const tshape* t, double scale, rugo_vec2 shift) {
    rugo_vec2 p[64];
    double tol[64];
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(t->s, rugo_shape_finest_level(t->s), &tl);
    for (int i = 0; i < t->fine.count; ++i) {
        p[i] = rugo_v2(scale * t->fine.points[i].x + shift.x, scale * t->fine.points[i].y + shift.y);
        tol[i] = scale * tl.total[i];
    }
    return make_shape(p, t->fine.count, tol);
}

/* One body inside the other without crossing: one contact, the way out through the closest pair. */
START_TEST(test_containment) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    rugo_shape* big = scaled_copy(&g_shapes[0], 3.0, rugo_v2(0, 0));   /* convex, 7.2 x 4.2 */
    rugo_shape* small = scaled_copy(&g_shapes[1], 0.2, rugo_v2(0, 0)); /* concave, ~0.5 across */
    tshape B = g_shapes[0], S0 = g_shapes[1];
    finish_tshape(&B, "big", big);
    finish_tshape(&S0, "small", small);
    test_rng r = test_rng_seed(4);
    for (int k = 0; k < 50; ++k) {
        rugo_transform xb = rugo_make_transform(test_rng_uniform(&r, -1, 1), test_rng_uniform(&r, -1, 1),
                                                test_rng_uniform(&r, 0, 6));
        /* well inside: within (±2, ±0.8) of the big ellipse's centre, in its own frame */
        rugo_vec2 off =
            rugo_transform_point(xb, rugo_v2(test_rng_uniform(&r, -2, 2), test_rng_uniform(&r, -0.8, 0.8)));
        rugo_transform xs = rugo_make_transform(off.x, off.y, test_rng_uniform(&r, 0, 6));
        rugo_contact c1[8], c2[8];
        rugo_contact_state s1, s2;
        int n1 = query(ctx, &B, xb, &S0, xs, -1.0, 0, c1, 8, &s1);
        int n2 = query(ctx, &S0, xs, &B, xb, -1.0, 0, c2, 8, &s2);
        assert_finite_contacts(c1, n1);
        assert_finite_contacts(c2, n2);
        ck_assert_int_eq(s1, RUGO_STATE_INTERSECTING);
        ck_assert_int_eq(s2, RUGO_STATE_INTERSECTING);
        ck_assert_int_eq(n1, 1);
        ck_assert_int_eq(n2, 1);
        ck_assert(c1[0].separation < 0);
        ck_assert_near(c1[0].separation, c2[0].separation, 1e-12);
        ck_assert(angle_between(c1[0].normal, rugo_v2_scale(-1.0, c2[0].normal)) < 1e-9);
        ck_assert(hypot(c1[0].point_a.x - c2[0].point_b.x, c1[0].point_a.y - c2[0].point_b.y) < 1e-9);
        /* Moving the inner body by the depth along the normal takes it out of the convex outer one. */
        rugo_transform moved_s = xs;
        moved_s.p = rugo_v2_add(xs.p, rugo_v2_scale(-c1[0].separation * (1 + 1e-9) + 1e-9, c1[0].normal));
        rugo_contact_state s3;
        rugo_contact c3[8];
        query(ctx, &B, xb, &S0, moved_s, 0.0, 0, c3, 8, &s3);
        ck_assert_int_ne(s3, RUGO_STATE_INTERSECTING);
    }
    rugo_shape_destroy(big);
    rugo_shape_destroy(small);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* Far from the origin (poses, or the shapes' own coordinates) and at 1e-3 and 1e3 scale: the same
 * contacts, scaled. */
START_TEST(test_far_and_scaled) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(99);
    const double scales[] = {1.0, 1.0, 1e-3, 1e3};
    const rugo_vec2 shifts[] = {{1e6, -1e6}, {0, 0}, {0, 0}, {0, 0}};
    const char* what[] = {"poses 1e6 from the origin", "shapes defined 1e6 from the origin",
                          "shapes 1e-3 in size", "shapes 1e3 in size"};
    for (int v = 0; v < 4; ++v) {
        double worst = 0, worst_n = 0;
        int compared = 0;
        for (int k = 0; k < 120; ++k) {
            const tshape* A = &g_shapes[k % N_SHAPES];
            const tshape* B = &g_shapes[(k / N_SHAPES + 2) % N_SHAPES];
            double override = k % 2 ? 0.02 * fmax(A->size, B->size) : -1.0;
            rugo_transform xa, xb;
            random_poses(&r, A, B, 1, override, ctx, &xa, &xb);
            rugo_contact c1[64], c2[64];
            rugo_contact_state s1, s2;
            int n1 = query(ctx, A, xa, B, xb, override, 0, c1, 64, &s1);
            int n2;
            const double sc = scales[v];
            rugo_contact_query q = test_exact_query();
            q.tolerance = override >= 0 ? override * sc : -1.0;
            if (v == 0) {
                rugo_transform ya = xa, yb = xb;
                ya.p = rugo_v2_add(xa.p, shifts[0]);
                yb.p = rugo_v2_add(xb.p, shifts[0]);
                ck_assert_int_eq(test_collide_shapes(ctx, A->s, ya, B->s, yb, &q, c2, 64, &n2, &s2, NULL),
                                 RUGO_OK);
                for (int i = 0; i < n2; ++i) {
                    c2[i].point_a = rugo_v2_sub(c2[i].point_a, shifts[0]);
                    c2[i].point_b = rugo_v2_sub(c2[i].point_b, shifts[0]);
                }
            } else {
                const rugo_vec2 sh = v == 1 ? rugo_v2(1e6, 1e6) : rugo_v2(0, 0);
                rugo_shape* sa = scaled_copy(A, sc, sh);
                rugo_shape* sb = scaled_copy(B, sc, sh);
                /* world point = x(local) = x'(local') with local' = sc local + sh: x' = x o (scale, shift)^-1
                 */
                rugo_transform ya = xa, yb = xb;
                ya.p = rugo_v2_sub(rugo_v2_scale(sc, xa.p), rugo_rotate(xa.q, sh));
                yb.p = rugo_v2_sub(rugo_v2_scale(sc, xb.p), rugo_rotate(xb.q, sh));
                ck_assert_int_eq(test_collide_shapes(ctx, sa, ya, sb, yb, &q, c2, 64, &n2, &s2, NULL),
                                 RUGO_OK);
                for (int i = 0; i < n2; ++i) {
                    c2[i].point_a = rugo_v2_scale(1.0 / sc, c2[i].point_a);
                    c2[i].point_b = rugo_v2_scale(1.0 / sc, c2[i].point_b);
                    c2[i].separation /= sc;
                }
                rugo_shape_destroy(sa);
                rugo_shape_destroy(sb);
            }
            assert_finite_contacts(c2, n2);
            ck_assert_int_eq(s1, s2);
            ck_assert_int_eq(n1, n2);
            const double size = fmax(A->size, B->size);
            for (int i = 0; i < n1; ++i) {
                int j = -1;
                double bd = 1e-6 * size;
                for (int m = 0; m < n2; ++m) {
                    double e = hypot(c1[i].point_a.x - c2[m].point_a.x, c1[i].point_a.y - c2[m].point_a.y);
                    if (e <= bd) {
                        bd = e;
                        j = m;
                    }
                }
                ck_assert_msg(j >= 0, "%s: contact %d not found", what[v], i);
                worst = fmax(worst, fabs(c1[i].separation - c2[j].separation) / size);
                worst_n = fmax(worst_n, angle_between(c1[i].normal, c2[j].normal));
                ++compared;
            }
        }
        printf("%s: %d contacts as at the origin and unit size, separations within %.3g x size, normals "
               "within %.3g rad\n",
               what[v], compared, worst, worst_n);
        ck_assert(worst <= 1e-9);
        ck_assert(worst_n <= 1e-6);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- primitives against brute force ------------------------------------------------------------- */

/* B = convex core (a point, a segment, a convex counter-clockwise polygon) grown by R. */
typedef struct tprim {
    int nv;
    rugo_vec2 v[8];
    double R;
} tprim;

static double seg_dist(rugo_vec2 p, rugo_vec2 a, rugo_vec2 b, rugo_vec2* foot) {
    rugo_vec2 d = rugo_v2_sub(b, a);
    double t = rugo_v2_dot(rugo_v2_sub(p, a), d) / rugo_v2_dot(d, d);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    *foot = rugo_v2(a.x + t * d.x, a.y + t * d.y);
    return hypot(p.x - foot->x, p.y - foot->y);
}

/* Distance from p to the core (0 inside a polygon core) and the nearest core point; *inside for a
 * point inside a polygon core. */
static double core_dist(const tprim* P, rugo_vec2 p, rugo_vec2* q, int* inside) {
    *inside = 0;
    if (P->nv == 1) {
        *q = P->v[0];
        return hypot(p.x - q->x, p.y - q->y);
    }
    if (P->nv == 2) return seg_dist(p, P->v[0], P->v[1], q);
    int in = 1;
    for (int i = 0; i < P->nv; ++i)
        in &= orient(P->v[i], P->v[(i + 1) % P->nv], p) > 0;
    double best = HUGE_VAL;
    for (int i = 0; i < P->nv; ++i) {
        rugo_vec2 f;
        double d = seg_dist(p, P->v[i], P->v[(i + 1) % P->nv], &f);
        if (d < best) {
            best = d;
            *q = f;
        }
    }
    if (in) {
        *inside = 1;
        return 0.0;
    }
    return best;
}

static double prim_sd_ref(const tprim* P, rugo_vec2 p) {
    rugo_vec2 q;
    int in;
    double d = core_dist(P, p, &q, &in);
    if (in) {
        double best = HUGE_VAL;
        for (int i = 0; i < P->nv; ++i) {
            rugo_vec2 f;
            best = fmin(best, seg_dist(p, P->v[i], P->v[(i + 1) % P->nv], &f));
        }
        return -best - P->R;
    }
    return d - P->R;
}

typedef struct pref {
    int crossing, contained, n, ambiguous;
    double u[64], dist[64];
    rugo_vec2 pa[64], q[64];
} pref;

/* 1-D refinement of a local minimum of the distance from A's curve to the core near u. */
static double phi_at(const curve* A, const tprim* P, double u) {
    rugo_vec2 f, c;
    int in;
    ev(A, wrapu(u, A->n), &f, NULL, NULL);
    return core_dist(P, f, &c, &in);
}

static double prim_refine(const curve* A, const tprim* P, double u, rugo_vec2* pa, rugo_vec2* q) {
    /* Golden section on the sampled bracket first (robust whatever the nearest feature), then Newton
     * on the nearest feature polishes to round-off. */
    double lo = u - 1.0 / S, hi = u + 1.0 / S;
    const double gr = 0.6180339887498949;
    for (int it = 0; it < 80; ++it) {
        double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
        if (phi_at(A, P, x1) <= phi_at(A, P, x2))
            hi = x2;
        else
            lo = x1;
    }
    u = wrapu(0.5 * (lo + hi), A->n);
    for (int it = 0; it < 60; ++it) {
        rugo_vec2 f, f1, f2, c;
        ev(A, u, &f, &f1, &f2);
        int in;
        core_dist(P, f, &c, &in);
        /* Nearest core feature: a vertex (c equals one) or an edge (a line). */
        int vert = -1;
        for (int i = 0; i < P->nv; ++i)
            if (hypot(c.x - P->v[i].x, c.y - P->v[i].y) <= 1e-12) vert = i;
        double g, dg;
        if (vert >= 0 || P->nv == 1) {
            rugo_vec2 d = rugo_v2_sub(f, vert >= 0 ? P->v[vert] : P->v[0]);
            g = rugo_v2_dot(d, f1);
            dg = rugo_v2_dot(f1, f1) + rugo_v2_dot(d, f2);
        } else {
            rugo_vec2 m = rugo_v2_sub(f, c);
            double l = hypot(m.x, m.y);
            if (!(l > 0)) break;
            m = rugo_v2_scale(1.0 / l, m);
            g = rugo_v2_dot(f1, m);
            dg = rugo_v2_dot(f2, m);
        }
        if (!(dg > 0)) break;
        double step = -g / dg;
        if (fabs(step) > 0.05) step = step > 0 ? 0.05 : -0.05;
        u = wrapu(u + step, A->n);
        if (fabs(step) < 1e-15) break;
    }
    int in;
    ev(A, u, pa, NULL, NULL);
    core_dist(P, *pa, q, &in);
    return u;
}

static void prim_reference(const curve* A, const tprim* P, double cutoff, double size, pref* R) {
    memset(R, 0, sizeof *R);
    const int m = A->n * S;
    double* phi = xmalloc((size_t)m * sizeof(double));
    rugo_vec2* pts = xmalloc((size_t)(m + 1) * sizeof(rugo_vec2));
    double minabs = HUGE_VAL;
    for (int i = 0; i <= m; ++i)
        ev(A, wrapu((double)i / S, A->n), &pts[i], NULL, NULL);
    for (int i = 0; i < m; ++i) {
        phi[i] = prim_sd_ref(P, pts[i]);
        minabs = fmin(minabs, fabs(phi[i]));
    }
    for (int i = 0; i < m; ++i)
        if ((phi[i] > 0) != (phi[(i + 1) % m] > 0)) R->crossing = 1;
    if (P->nv == 2 && P->R == 0) /* an edge: the polyline crossing it */
        for (int i = 0; i < m && !R->crossing; ++i) {
            double o1 = orient(pts[i], pts[i + 1], P->v[0]), o2 = orient(pts[i], pts[i + 1], P->v[1]);
            double o3 = orient(P->v[0], P->v[1], pts[i]), o4 = orient(P->v[0], P->v[1], pts[i + 1]);
            if ((o1 > 0) != (o2 > 0) && (o3 > 0) != (o4 > 0)) R->crossing = 1;
        }
    if (!R->crossing) R->contained = point_in_polyline(P->v[0], pts, m) || phi[0] < 0;
    /* Near-tangency below the sampling error, or a curve through a vertex: not decidable here. */
    if (!R->crossing && minabs < 1e-4 * size) R->ambiguous = 1;
    for (int i = 0; i < m; ++i) {
        double a = phi[(i + m - 1) % m], b = phi[i], c = phi[(i + 1) % m];
        if (!(b <= a && b <= c) || b > cutoff + 1e-3 * size || b < 0) continue;
        rugo_vec2 pa, q;
        double u = prim_refine(A, P, (double)i / S, &pa, &q);
        double d = hypot(pa.x - q.x, pa.y - q.y) - P->R;
        int dup = 0;
        for (int k = 0; k < R->n && !dup; ++k)
            dup = hypot(R->pa[k].x - pa.x, R->pa[k].y - pa.y) <= 1e-9 * size;
        if (dup || R->n >= 64) continue;
        /* Plateau corners: moving along A (to the first distinct point) must not come closer. */
        int ismin = 1;
        for (int sg = -1; sg <= 1 && ismin; sg += 2) {
            rugo_vec2 x, qq;
            int in;
            if (first_distinct(A, u, sg, pa, size, &x) && core_dist(P, x, &qq, &in) - P->R < d - 1e-13 * size)
                ismin = 0;
        }
        if (!ismin) continue;
        R->u[R->n] = u;
        R->dist[R->n] = d;
        R->pa[R->n] = pa;
        R->q[R->n] = q;
        R->n++;
    }
    free(phi);
    free(pts);
}

static rugo_status prim_query(rugo_collide_context* ctx, const tshape* A, rugo_transform xa, const tprim* P,
                              double override, rugo_contact* c, int cap, int* n, rugo_contact_state* st) {
    rugo_contact_query q = test_exact_query();
    q.tolerance = override;
    if (P->nv == 1) return test_collide_circle(ctx, A->s, xa, P->v[0], P->R, &q, c, cap, n, st, NULL);
    if (P->nv == 2)
        return test_collide_segment(ctx, A->s, xa, P->v[0], P->v[1], P->R, &q, c, cap, n, st, NULL);
    return test_collide_polygon(ctx, A->s, xa, P->v, P->nv, P->R, &q, c, cap, n, st, NULL);
}

static void random_prim(test_rng* r, int kind, double scale, tprim* P) {
    memset(P, 0, sizeof *P);
    if (kind == 0) {
        P->nv = 1;
        P->R = scale * test_rng_uniform(r, 0.05, 0.8);
    } else if (kind == 1) {
        P->nv = 2;
        double len = scale * test_rng_uniform(r, 0.2, 2.0), th = test_rng_uniform(r, 0, TWO_PI);
        P->v[0] = rugo_v2(-0.5 * len * cos(th), -0.5 * len * sin(th));
        P->v[1] = rugo_v2(0.5 * len * cos(th), 0.5 * len * sin(th));
        P->R = test_rng_next(r) % 3 == 0 ? 0.0 : scale * test_rng_uniform(r, 0.01, 0.3);
    } else {
        P->nv = 3 + (int)(test_rng_next(r) % 6);
        double rho = scale * test_rng_uniform(r, 0.2, 0.9), th0 = test_rng_uniform(r, 0, TWO_PI);
        for (int i = 0; i < P->nv; ++i) {
            double th = th0 + TWO_PI * (i + test_rng_uniform(r, 0.15, 0.85)) / P->nv;
            P->v[i] = rugo_v2(rho * cos(th), rho * sin(th));
        }
        P->R = test_rng_next(r) % 2 ? 0.0 : scale * test_rng_uniform(r, 0.01, 0.2);
    }
}

static tprim moved(const tprim* P, rugo_vec2 at) {
    tprim Q = *P;
    for (int i = 0; i < Q.nv; ++i)
        Q.v[i] = rugo_v2_add(Q.v[i], at);
    return Q;
}

START_TEST(test_primitives_against_brute_force) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(2024);
    const int N = UNDER_SANITIZER ? 600 : 3000;
    const char* names[3] = {"circle", "segment", "polygon"};
    for (int kind = 0; kind < 3; ++kind) {
        long states[3] = {0, 0, 0}, required = 0, compared = 0, missed = 0, spurious = 0, mismatch = 0,
             ambiguous = 0;
        double worst_s = 0, worst_n = 0;
        for (int k = 0; k < N; ++k) {
            const tshape* A = &g_shapes[k % N_SHAPES];
            const double size = A->size;
            const double override = k % 2 ? 0.02 * size : -1.0;
            rugo_transform xa = rugo_make_transform(test_rng_uniform(&r, -1, 1), test_rng_uniform(&r, -1, 1),
                                                    test_rng_uniform(&r, 0, TWO_PI));
            tprim P0;
            random_prim(&r, kind, A->radius, &P0);
            double th = test_rng_uniform(&r, 0, TWO_PI);
            rugo_vec2 dir = rugo_v2(cos(th), sin(th)), ca;
            centroid_world(A, xa, &ca);
            /* Near the boundary between intersecting and apart (bisection on the library's state),
             * or anywhere. */
            double lo = 0, hi = 2.5 * A->radius + 2.0 * P0.R + 2.0 * size, dist;
            if (k % 3) {
                for (int it = 0; it < 18; ++it) {
                    double mid = 0.5 * (lo + hi);
                    tprim P = moved(&P0, rugo_v2(ca.x + mid * dir.x, ca.y + mid * dir.y));
                    int n;
                    rugo_contact_state st;
                    ck_assert_int_eq(prim_query(ctx, A, xa, &P, -1.0, NULL, 0, &n, &st), RUGO_OK);
                    if (st == RUGO_STATE_INTERSECTING)
                        lo = mid;
                    else
                        hi = mid;
                }
                dist = hi + 0.04 * size * test_rng_uniform(&r, -0.3, 1.3);
            } else {
                dist = test_rng_uniform(&r, 0, 1.5) * A->radius;
            }
            tprim P = moved(&P0, rugo_v2(ca.x + dist * dir.x, ca.y + dist * dir.y));
            rugo_contact c[64];
            int n;
            rugo_contact_state st;
            ck_assert_int_eq(prim_query(ctx, A, xa, &P, override, c, 64, &n, &st), RUGO_OK);
            assert_finite_contacts(c, n);
            states[st]++;
            if (st == RUGO_STATE_INTERSECTING) ck_assert_int_ge(n, 1);
            curve cv = {A->fine.points, A->fine.count, xa};
            pref R;
            const double band_max = override >= 0 ? 2 * override : 1.3 * A->max_lambda;
            prim_reference(&cv, &P, band_max, size, &R);
            if (R.ambiguous) {
                ambiguous++;
                continue;
            }
            int ref_int = R.crossing || R.contained;
            if (ref_int != (st == RUGO_STATE_INTERSECTING)) {
                mismatch++;
                if (mismatch < 5)
                    printf("%s: state %s, reference crossing %d contained %d (%s)\n", names[kind],
                           rugo_contact_state_name(st), R.crossing, R.contained, A->name);
                continue;
            }
            if (ref_int) continue;
            for (int i = 0; i < n; ++i)
                ck_assert(c[i].separation >= 0 && c[i].segment_b == -1);
            for (int j = 0; j < R.n; ++j) {
                double band = lambda_at(A, R.u[j], override) + (override >= 0 ? override : 0.0);
                if (fabs(R.dist[j] - band) <= 1e-9 * size) continue;
                if (R.dist[j] > band) continue;
                rugo_vec2 d = rugo_v2_sub(R.q[j], R.pa[j]);
                double dl = hypot(d.x, d.y);
                rugo_vec2 na = ref_normal(&cv, R.u[j]);
                if (dl > 1e-9 * size && rugo_v2_dot(na, d) < 1e-6 * dl) continue; /* not facing */
                required++;
                int f = -1;
                double bd = 1e-4 * size;
                for (int i = 0; i < n; ++i) {
                    double e = hypot(c[i].point_a.x - R.pa[j].x, c[i].point_a.y - R.pa[j].y);
                    if (e <= bd) {
                        bd = e;
                        f = i;
                    }
                }
                if (f < 0) {
                    missed++;
                    if (missed < 5) {
                        printf("%s: missed dist %.9g band %.3g on %s at u %.6f (%d contacts) override %g\n",
                               names[kind], R.dist[j], band, A->name, R.u[j], n, override);
                        printf("  xa %.17g %.17g %.17g %.17g R %.17g v0 %.17g %.17g v1 %.17g %.17g nv %d\n",
                               xa.p.x, xa.p.y, xa.q.c, xa.q.s, P.R, P.v[0].x, P.v[0].y, P.v[1].x, P.v[1].y,
                               P.nv);
                        printf("  ref pa %.17g %.17g q %.17g %.17g\n", R.pa[j].x, R.pa[j].y, R.q[j].x,
                               R.q[j].y);
                        for (int i = 0; i < n; ++i)
                            printf("  lib pa %.17g %.17g pb %.17g %.17g sep %.17g\n", c[i].point_a.x,
                                   c[i].point_a.y, c[i].point_b.x, c[i].point_b.y, c[i].separation);
                    }
                    continue;
                }
                compared++;
                worst_s = fmax(worst_s, fabs(c[f].separation - R.dist[j]) / size);
                if (dl > 1e-6 * size)
                    worst_n = fmax(worst_n, angle_between(c[f].normal, rugo_v2_scale(1.0 / dl, d)));
            }
            for (int i = 0; i < n; ++i) {
                int f = 0;
                for (int j = 0; j < R.n && !f; ++j)
                    f = hypot(c[i].point_a.x - R.pa[j].x, c[i].point_a.y - R.pa[j].y) <= 1e-4 * size;
                if (!f) {
                    spurious++;
                    if (spurious < 5) {
                        printf("%s: spurious sep %.9g on %s seg %d t %.17g override %g\n", names[kind],
                               c[i].separation, A->name, c[i].segment_a, c[i].t_a, override);
                        printf("  xa %.17g %.17g %.17g %.17g R %.17g v0 %.17g %.17g v1 %.17g %.17g nv %d\n",
                               xa.p.x, xa.p.y, xa.q.c, xa.q.s, P.R, P.v[0].x, P.v[0].y, P.v[1].x, P.v[1].y,
                               P.nv);
                        printf("  lib pa %.17g %.17g pb %.17g %.17g\n", c[i].point_a.x, c[i].point_a.y,
                               c[i].point_b.x, c[i].point_b.y);
                        for (int j = 0; j < R.n; ++j)
                            printf("  ref pa %.17g %.17g q %.17g %.17g d %.9g\n", R.pa[j].x, R.pa[j].y,
                                   R.q[j].x, R.q[j].y, R.dist[j]);
                        for (int t = -10; t <= 10; ++t) {
                            double u = c[i].segment_a + c[i].t_a + t * 1e-3;
                            rugo_vec2 x;
                            ev(&cv, u, &x, NULL, NULL);
                            printf("    u %.6f phi %.12g\n", u, prim_sd_ref(&P, x));
                        }
                    }
                }
            }
        }
        printf("%s: %d poses: apart %ld, contact %ld, intersecting %ld; contacts required %ld, compared %ld, "
               "missed %ld, "
               "spurious %ld; state mismatches %ld, ambiguous %ld; separation error <= %.3g x size, normals "
               "<= %.3g rad\n",
               names[kind], N, states[0], states[1], states[2], required, compared, missed, spurious,
               mismatch, ambiguous, worst_s, worst_n);
        ck_assert_int_eq(missed, 0);
        ck_assert_int_eq(spurious, 0);
        ck_assert_int_eq(mismatch, 0);
        ck_assert(worst_s <= 1e-9 && worst_n <= 1e-7);
        ck_assert(compared > N / 20);
    }
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* Penetration contacts of primitives: the depth of a circle pushed into a straight side is exact. */
START_TEST(test_primitive_penetration) {
    build_shapes();
    const tshape* Q = &g_shapes[3]; /* top side straight for x in [-0.5, 0.5] at y = 0.8 */
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    rugo_contact c[16];
    int n;
    rugo_contact_state st;
    rugo_contact_query q = test_exact_query();
    for (int k = 0; k < 4; ++k) {
        const double depth = 0.05 * (k + 1);
        /* circle */
        ck_assert_int_eq(test_collide_circle(ctx, Q->s, rugo_identity_transform(),
                                             rugo_v2(0.1, 0.8 + 0.3 - depth), 0.3, &q, c, 16, &n, &st, NULL),
                         RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        ck_assert_int_eq(n, 1);
        ck_assert_near(c[0].separation, -depth, 1e-12);
        ck_assert(angle_between(c[0].normal, rugo_v2(0, 1)) < 1e-12);
        /* box pressed flat: depth from its bottom side */
        rugo_vec2 box[4] = {{-0.2, 0.8 - depth}, {0.3, 0.8 - depth}, {0.3, 1.2}, {-0.2, 1.2}};
        ck_assert_int_eq(
            test_collide_polygon(ctx, Q->s, rugo_identity_transform(), box, 4, 0.0, &q, c, 16, &n, &st, NULL),
            RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        ck_assert_int_ge(n, 1);
        ck_assert_near(c[0].separation, -depth, 1e-12);
        ck_assert(angle_between(c[0].normal, rugo_v2(0, 1)) < 1e-12);
        /* a corner poking in */
        rugo_vec2 tri[3] = {{0.0, 0.8 - depth}, {0.3, 1.3}, {-0.3, 1.3}};
        ck_assert_int_eq(
            test_collide_polygon(ctx, Q->s, rugo_identity_transform(), tri, 3, 0.0, &q, c, 16, &n, &st, NULL),
            RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        ck_assert_near(c[0].separation, -depth, 1e-12);
        ck_assert_near(c[0].point_b.x, 0.0, 1e-12);
        /* an edge through the side: its deepest point inside */
        ck_assert_int_eq(test_collide_segment(ctx, Q->s, rugo_identity_transform(), rugo_v2(0.1, 0.8 - depth),
                                              rugo_v2(0.1, 2.0), 0.0, &q, c, 16, &n, &st, NULL),
                         RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        ck_assert_int_eq(n, 1);
        ck_assert_near(c[0].separation, -depth, 1e-9);
        ck_assert(angle_between(c[0].normal, rugo_v2(0, 1)) < 1e-7);
        /* a capsule lying on the side */
        ck_assert_int_eq(test_collide_segment(ctx, Q->s, rugo_identity_transform(),
                                              rugo_v2(-0.2, 0.9 - depth), rugo_v2(0.2, 0.9 - depth), 0.1, &q,
                                              c, 16, &n, &st, NULL),
                         RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
        ck_assert_near(c[0].separation, -depth, 1e-12);
    }
    /* A circle inside the shape, a shape inside a big circle: the shortest way out. */
    ck_assert_int_eq(test_collide_circle(ctx, Q->s, rugo_identity_transform(), rugo_v2(0.1, 0.5), 0.1, &q, c,
                                         16, &n, &st, NULL),
                     RUGO_OK);
    ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
    ck_assert_int_eq(n, 1);
    ck_assert_near(c[0].separation, -(0.3 + 0.1), 1e-12);
    ck_assert(angle_between(c[0].normal, rugo_v2(0, 1)) < 1e-12);
    ck_assert_int_eq(test_collide_circle(ctx, Q->s, rugo_identity_transform(), rugo_v2(0, 0), 10.0, &q, c, 16,
                                         &n, &st, NULL),
                     RUGO_OK);
    ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
    ck_assert_int_eq(n, 1);
    ck_assert(c[0].separation < -10.0);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- tree traversal ----------------------------------------------------------------------------- */

START_TEST(test_tree_pairs_against_all_pairs) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(31);
    enum { CAP = 4096 };
    rugo_node_pair* pairs = xmalloc(CAP * sizeof *pairs);
    long total_pairs = 0, total_tests = 0, total_brute = 0;
    for (int k = 0; k < 400; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        rugo_transform xa, xb;
        random_poses(&r, A, B, 0, -1.0, ctx, &xa, &xb);
        const rugo_mobb_tree* ta = rugo_shape_tree(A->s);
        const rugo_mobb_tree* tb = rugo_shape_tree(B->s);
        int la =
            rugo_shape_coarsest_level(A->s) + (int)(test_rng_next(&r) % 8) - 1; /* sometimes out of range */
        int lb = rugo_shape_coarsest_level(B->s) + (int)(test_rng_next(&r) % 8) - 1;
        int n = -1;
        long tests = -1;
        ck_assert_int_eq(rugo_tree_pairs(ta, xa, la, tb, xb, lb, ctx, pairs, CAP, &n, &tests), RUGO_OK);
        ck_assert_int_le(n, CAP);
        /* Brute force at the clamped levels, same frame (B's boxes into A's). */
        int ca = la < rugo_mobb_tree_coarsest_level(ta)
                     ? rugo_mobb_tree_coarsest_level(ta)
                     : (la > rugo_mobb_tree_finest_level(ta) ? rugo_mobb_tree_finest_level(ta) : la);
        int cb = lb < rugo_mobb_tree_coarsest_level(tb)
                     ? rugo_mobb_tree_coarsest_level(tb)
                     : (lb > rugo_mobb_tree_finest_level(tb) ? rugo_mobb_tree_finest_level(tb) : lb);
        rugo_transform rel;
        rel.q.c = xa.q.c * xb.q.c + xa.q.s * xb.q.s;
        rel.q.s = xa.q.c * xb.q.s - xa.q.s * xb.q.c;
        rel.p = rugo_inv_rotate(xa.q, rugo_v2_sub(xb.p, xa.p));
        int brute = 0;
        for (int i = 0; i < (1 << ca); ++i)
            for (int j = 0; j < (1 << cb); ++j) {
                rugo_obb bb = rugo_obb_transform(rel, rugo_mobb_tree_node(tb, cb, j));
                if (!rugo_obb_overlap(rugo_mobb_tree_node(ta, ca, i), &bb)) continue;
                ++brute;
                int found = 0;
                for (int m = 0; m < n && !found; ++m)
                    found = pairs[m].k_a == i && pairs[m].k_b == j;
                ck_assert_msg(found, "pair (%d, %d) at levels %d/%d missing", i, j, ca, cb);
            }
        ck_assert_int_eq(n, brute);
        ck_assert(tests >= 1);
        total_pairs += n;
        total_tests += tests;
        total_brute += (1L << ca) * (1L << cb);
    }
    printf("tree pairs: %ld pairs found with %ld box tests (all-pairs at the same levels: %ld tests)\n",
           total_pairs, total_tests, total_brute);
    /* capacity smaller than the count: count still the total */
    {
        const tshape* A = &g_shapes[5];
        int n_all = 0, n_few = 0;
        long t1, t2;
        rugo_transform x = rugo_identity_transform();
        ck_assert_int_eq(rugo_tree_pairs(rugo_shape_tree(A->s), x, 6, rugo_shape_tree(A->s), x, 6, ctx, pairs,
                                         CAP, &n_all, &t1),
                         RUGO_OK);
        ck_assert_int_eq(rugo_tree_pairs(rugo_shape_tree(A->s), x, 6, rugo_shape_tree(A->s), x, 6, ctx, pairs,
                                         3, &n_few, &t2),
                         RUGO_OK);
        ck_assert_int_eq(n_all, n_few);
        ck_assert_int_gt(n_all, 3);
        ck_assert_int_eq(t1, t2);
    }
    free(pairs);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* The traversal as it was first written (collide.c before issue 7's speed work): depth first from the
 * roots, each node pair tested with rugo_obb_overlap when it is popped, B's boxes moved by
 * rugo_obb_transform, both trees descended when their heights are equal, children pushed in reverse.
 * rugo_tree_pairs must give the same pairs in the same order with the same number of tests (its test
 * shares work between the four axes but computes each axis's distance and reach with the same
 * operations). */
static int ref_tree_pairs(const rugo_mobb_tree* ta, int stop_a, const rugo_mobb_tree* tb, int stop_b,
                          rugo_transform rel, rugo_node_pair* out, int cap, long* tests) {
    typedef struct {
        int la, ka, lb, kb;
    } rn;
    enum { STACK = 4096 };
    static rn st[STACK];
    const int ja = rugo_mobb_tree_coarsest_level(ta), jb = rugo_mobb_tree_coarsest_level(tb);
    int top = 0, n = 0;
    st[top++] = (rn){-1, 0, -1, 0};
    *tests = 0;
    while (top > 0) {
        const rn t = st[--top];
        ++*tests;
        const rugo_obb* a = t.la < 0 ? rugo_mobb_tree_root(ta) : rugo_mobb_tree_node(ta, t.la, t.ka);
        const rugo_obb bb =
            rugo_obb_transform(rel, t.lb < 0 ? rugo_mobb_tree_root(tb) : rugo_mobb_tree_node(tb, t.lb, t.kb));
        if (!rugo_obb_overlap(a, &bb)) continue;
        const int ha = t.la < 0 ? stop_a - ja + 1 : stop_a - t.la,
                  hb = t.lb < 0 ? stop_b - jb + 1 : stop_b - t.lb;
        if (ha == 0 && hb == 0) {
            if (n < cap) out[n] = (rugo_node_pair){t.ka, t.kb};
            ++n;
            continue;
        }
        int cla = t.la, ka0 = t.ka, nka = 1, clb = t.lb, kb0 = t.kb, nkb = 1;
        if (ha >= hb) {
            cla = t.la < 0 ? ja : t.la + 1;
            ka0 = t.la < 0 ? 0 : 2 * t.ka;
            nka = t.la < 0 ? 1 << ja : 2;
        }
        if (hb >= ha) {
            clb = t.lb < 0 ? jb : t.lb + 1;
            kb0 = t.lb < 0 ? 0 : 2 * t.kb;
            nkb = t.lb < 0 ? 1 << jb : 2;
        }
        for (int i = nka - 1; i >= 0; --i)
            for (int j = nkb - 1; j >= 0; --j) {
                ck_assert_int_lt(top, STACK);
                st[top++] = (rn){cla, ka0 + i, clb, kb0 + j};
            }
    }
    return n;
}

START_TEST(test_tree_pairs_match_reference_traversal) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    test_rng r = test_rng_seed(77);
    enum { CAP = 8192 };
    rugo_node_pair* pairs = xmalloc(CAP * sizeof *pairs);
    rugo_node_pair* ref = xmalloc(CAP * sizeof *ref);
    long total_tests = 0, total_pairs = 0;
    for (int k = 0; k < 300; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        rugo_transform xa, xb;
        random_poses(&r, A, B, 0, -1.0, ctx, &xa, &xb);
        /* far from the origin too: the overlap test's slack grows with the position */
        const double far = k % 3 == 0 ? 0.0 : (k % 3 == 1 ? 1e3 : 1e7);
        xa.p = rugo_v2(xa.p.x + far, xa.p.y - 0.5 * far);
        xb.p = rugo_v2(xb.p.x + far, xb.p.y - 0.5 * far);
        const rugo_mobb_tree* ta = rugo_shape_tree(A->s);
        const rugo_mobb_tree* tb = rugo_shape_tree(B->s);
        const int la = rugo_mobb_tree_coarsest_level(ta) + (int)(test_rng_next(&r) % 7);
        const int lb = rugo_mobb_tree_coarsest_level(tb) + (int)(test_rng_next(&r) % 7);
        const int sa = la > rugo_mobb_tree_finest_level(ta) ? rugo_mobb_tree_finest_level(ta) : la;
        const int sb = lb > rugo_mobb_tree_finest_level(tb) ? rugo_mobb_tree_finest_level(tb) : lb;
        rugo_transform rel;
        rel.q.c = xa.q.c * xb.q.c + xa.q.s * xb.q.s;
        rel.q.s = xa.q.c * xb.q.s - xa.q.s * xb.q.c;
        rel.p = rugo_inv_rotate(xa.q, rugo_v2_sub(xb.p, xa.p));
        int n = -1;
        long tests = -1, ref_tests = -1;
        ck_assert_int_eq(rugo_tree_pairs(ta, xa, la, tb, xb, lb, ctx, pairs, CAP, &n, &tests), RUGO_OK);
        const int nr = ref_tree_pairs(ta, sa, tb, sb, rel, ref, CAP, &ref_tests);
        ck_assert_int_eq(n, nr);
        ck_assert_int_eq(tests, ref_tests);
        for (int m = 0; m < n && m < CAP; ++m) {
            ck_assert_int_eq(pairs[m].k_a, ref[m].k_a);
            ck_assert_int_eq(pairs[m].k_b, ref[m].k_b);
        }
        total_tests += tests;
        total_pairs += n;
    }
    printf("tree pairs against the reference traversal: %ld pairs, %ld box tests, same order\n", total_pairs,
           total_tests);
    free(ref);
    free(pairs);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* rugo_collide_context_reserve: reserved for each test shape (as the bridge does when it attaches a
 * body), near-contact queries between them at levels 0..-2 allocate nothing; the same queries on a
 * context without the reserve do allocate (so the count can fail). */
START_TEST(test_context_reserve) {
    build_shapes();
    rugo_collide_context* pose_ctx = NULL; /* random_poses queries too: its own context */
    ck_assert_int_eq(rugo_collide_context_create(NULL, &pose_ctx), RUGO_OK);
    test_budget_ctx with = {1L << 40, 0}, without = {1L << 40, 0};
    const rugo_allocator aw = {test_budget_alloc, test_budget_free, &with};
    const rugo_allocator ao = {test_budget_alloc, test_budget_free, &without};
    rugo_collide_context *cw = NULL, *co = NULL;
    ck_assert_int_eq(rugo_collide_context_create(&aw, &cw), RUGO_OK);
    ck_assert_int_eq(rugo_collide_context_create(&ao, &co), RUGO_OK);
    enum { CONTACTS = 16 };
    for (int k = 0; k < N_SHAPES; ++k)
        ck_assert_int_eq(rugo_collide_context_reserve(cw, g_shapes[k].s, CONTACTS), RUGO_OK);
    const long reserved = (1L << 40) - with.budget, base_without = (1L << 40) - without.budget;
    test_rng r = test_rng_seed(2026);
    int most = 0, touching = 0;
    for (int k = 0; k < 300; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        rugo_transform xa, xb;
        random_poses(&r, A, B, 0, -1.0, pose_ctx, &xa, &xb);
        rugo_contact_query q = test_exact_query();
        q.lod = -(k % 3);
        rugo_contact cs[CONTACTS];
        int n = 0;
        rugo_contact_state state;
        rugo_query_stats st;
        ck_assert_int_eq(test_collide_shapes(cw, A->s, xa, B->s, xb, &q, cs, CONTACTS, &n, &state, &st),
                         RUGO_OK);
        most = st.contacts_found > most ? st.contacts_found : most;
        touching += n > 0;
        ck_assert_int_eq(test_collide_shapes(co, A->s, xa, B->s, xb, &q, cs, CONTACTS, &n, &state, NULL),
                         RUGO_OK);
    }
    const long after_reserve = (1L << 40) - with.budget - reserved;
    const long grown = (1L << 40) - without.budget - base_without;
    printf("context reserve: %ld allocations to reserve for %d shapes; 300 queries (%d touching, at most %d "
           "contacts): %ld allocations after the reserve, %ld without it\n",
           reserved, N_SHAPES, touching, most, after_reserve, grown);
    ck_assert_int_ge(touching, 150);
    ck_assert_int_le(most, CONTACTS);
    ck_assert_int_eq(after_reserve, 0);
    ck_assert_int_gt(grown, 0);
    rugo_collide_context_destroy(cw);
    rugo_collide_context_destroy(co);
    ck_assert_int_eq(with.live, 0);
    ck_assert_int_eq(without.live, 0);

    /* Shapes of 512 segments: the reserve holds every segment pair (2^18, 2 MB). Two discs whose bands
     * (0.5 on radius 1) make each leaf box reach a good part of the other's: more than the 8192 pairs
     * reserved until 2026-11-22, which two falling 512-segment bodies exceeded in benchmark 3 (their
     * speculative margins grow the boxes), so that the pair list grew during a step. */
    {
        enum { BIG = 512 };
        rugo_vec2 bp[BIG];
        double bt[BIG];
        for (int i = 0; i < BIG; ++i) {
            bp[i] = rugo_v2(cos(2.0 * M_PI * i / BIG), sin(2.0 * M_PI * i / BIG));
            bt[i] = 0.5;
        }
        rugo_shape* big = make_shape(bp, BIG, bt);
        test_budget_ctx bb = {1L << 40, 0};
        const rugo_allocator ab = {test_budget_alloc, test_budget_free, &bb};
        rugo_collide_context* cb = NULL;
        ck_assert_int_eq(rugo_collide_context_create(&ab, &cb), RUGO_OK);
        ck_assert_int_eq(rugo_collide_context_reserve(cb, big, CONTACTS), RUGO_OK);
        const long res = (1L << 40) - bb.budget;
        const rugo_mobb_tree* tr = rugo_shape_tree(big);
        const int fine = rugo_shape_finest_level(big);
        int cnt = 0;
        long tests = 0;
        ck_assert_int_eq(rugo_tree_pairs(tr, rugo_identity_transform(), fine, tr,
                                         rugo_make_transform(0.01, 0.0, 0.1), fine, cb, NULL, 0, &cnt,
                                         &tests),
                         RUGO_OK);
        printf("context reserve, 512 segments: %d segment pairs, %ld allocations after the reserve\n", cnt,
               (1L << 40) - bb.budget - res);
        ck_assert_int_gt(cnt, 8192);
        ck_assert_int_eq((1L << 40) - bb.budget - res, 0);
        rugo_collide_context_destroy(cb);
        rugo_shape_destroy(big);
        ck_assert_int_eq(bb.live, 0);
    }

    /* bad input, and out of memory: the context keeps what it had and still answers */
    ck_assert_int_eq(rugo_collide_context_reserve(NULL, g_shapes[0].s, 1), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_collide_context_reserve(pose_ctx, NULL, 1), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_collide_context_reserve(pose_ctx, g_shapes[0].s, -1), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_collide_context_reserve(pose_ctx, g_shapes[0].s, RUGO_MAX_CONTROL_POINTS + 1),
                     RUGO_ERR_BAD_ARGUMENT);
    test_budget_ctx tight = {1, 0};
    const rugo_allocator at = {test_budget_alloc, test_budget_free, &tight};
    rugo_collide_context* ct = NULL;
    ck_assert_int_eq(rugo_collide_context_create(&at, &ct), RUGO_OK); /* the one allocation */
    ck_assert_int_eq(rugo_collide_context_reserve(ct, g_shapes[0].s, CONTACTS), RUGO_ERR_OUT_OF_MEMORY);
    tight.budget = 1L << 40;
    rugo_contact cs[CONTACTS];
    int n = -1;
    rugo_contact_state state;
    rugo_contact_query q = test_exact_query();
    ck_assert_int_eq(test_collide_shapes(ct, g_shapes[0].s, rugo_make_transform(0, 0, 0), g_shapes[0].s,
                                         rugo_make_transform(0.5, 0, 0), &q, cs, CONTACTS, &n, &state, NULL),
                     RUGO_OK);
    rugo_collide_context_destroy(ct);
    ck_assert_int_eq(tight.live, 0);
    rugo_collide_context_destroy(pose_ctx);
}
END_TEST

/* ---- manifold reduction ---------------------------------------------------------------------------- */

static rugo_contact mk(double x, double sep, int region) {
    rugo_contact c;
    memset(&c, 0, sizeof c);
    c.point_a = c.point_b = rugo_v2(x, 0);
    c.separation = sep;
    c.region = region;
    c.id = (uint64_t)(x * 10 + 100 * region);
    return c;
}

START_TEST(test_reduce_manifold) {
    rugo_contact c[8];
    c[0] = mk(0, -0.1, 0);
    c[1] = mk(1, -0.3, 0); /* deepest of region 0 */
    c[2] = mk(5, -0.05, 1);
    c[3] = mk(2, -0.2, 0);
    c[4] = mk(4, -0.01, 0); /* farthest from the deepest */
    c[5] = mk(3, -0.02, 0);
    int n = rugo_reduce_manifold(c, 6, 2);
    ck_assert_int_eq(n, 3);
    /* order preserved: region 0's kept (x = 1, x = 4) and region 1's */
    ck_assert(c[0].point_a.x == 1 && c[1].point_a.x == 5 && c[2].point_a.x == 4);
    ck_assert_int_eq(c[0].region, 0);
    ck_assert_int_eq(c[1].region, 1);
    c[0] = mk(0, -0.1, 0);
    c[1] = mk(1, -0.3, 0);
    c[2] = mk(2, -0.2, 0);
    c[3] = mk(7, -0.2, 0);
    n = rugo_reduce_manifold(c, 4, 3);
    ck_assert_int_eq(n, 3); /* deepest (1), farthest (7), then farthest from both (0, at 1 from x=1) vs 2 (1
                               from 1): first wins */
    ck_assert(c[0].point_a.x == 0 && c[1].point_a.x == 1 && c[2].point_a.x == 7);
    c[0] = mk(0, -0.1, 0);
    c[1] = mk(1, -0.3, 0);
    ck_assert_int_eq(rugo_reduce_manifold(c, 2, 1), 1);
    ck_assert(c[0].point_a.x == 1);
    c[0] = mk(0, -0.1, 0);
    c[1] = mk(1, -0.3, 1);
    ck_assert_int_eq(rugo_reduce_manifold(c, 2, 5), 2);
    ck_assert(c[0].point_a.x == 0 && c[1].point_a.x == 1 && c[0].region == 0 && c[1].region == 1);
    ck_assert_int_eq(rugo_reduce_manifold(c, 2, 0), 2); /* k < 1 acts as 1: one per region */
    ck_assert_int_eq(rugo_reduce_manifold(NULL, 2, 1), 0);
    ck_assert_int_eq(rugo_reduce_manifold(c, 0, 1), 0);
    c[0].region = -3; /* not from a query: left alone */
    c[1] = c[0];
    ck_assert_int_eq(rugo_reduce_manifold(c, 2, 1), 2);
}
END_TEST

/* ---- contexts, truncation, bad input ------------------------------------------------------------- */

START_TEST(test_context_and_truncation) {
    build_shapes();
    ck_assert_int_eq(rugo_collide_context_create(NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    counting fail = {0, 0, 0};
    rugo_allocator bad = counting_allocator(&fail);
    rugo_collide_context* ctx = (rugo_collide_context*)0x1;
    ck_assert_int_eq(rugo_collide_context_create(&bad, &ctx), RUGO_ERR_OUT_OF_MEMORY);
    ck_assert_ptr_null(ctx);
    rugo_collide_context_destroy(NULL);

    /* The context grows on the first queries, then a repeated query allocates nothing. */
    counting cnt = {0, 0, -1};
    rugo_allocator al = counting_allocator(&cnt);
    ck_assert_int_eq(rugo_collide_context_create(&al, &ctx), RUGO_OK);
    const tshape* A = &g_shapes[1];
    const tshape* B = &g_shapes[5];
    rugo_transform xa = rugo_identity_transform(), xb = rugo_make_transform(0.9, 0.3, 1.0);
    rugo_contact c[64];
    int n;
    rugo_contact_state st;
    rugo_query_stats qs;
    rugo_contact_query q = test_exact_query();
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c, 64, &n, &st, &qs), RUGO_OK);
    ck_assert_int_eq(st, RUGO_STATE_INTERSECTING);
    const long before = cnt.allocs;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c, 64, &n, &st, &qs), RUGO_OK);
    ck_assert_int_eq(cnt.allocs, before);
    /* NULL query = the defaults */
    int n2;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, NULL, c, 64, &n2, &st, NULL), RUGO_OK);
    ck_assert_int_eq(n, n2);
    /* Truncation: count <= capacity, contacts_found the total, deepest first within a region. */
    q.tolerance = 0.05;
    xb = rugo_make_transform(2.4, 0.0, 0.3);
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, A->s, xb, &q, c, 64, &n, &st, &qs), RUGO_OK);
    for (int i = 1; i < n; ++i)
        ck_assert(c[i].region > c[i - 1].region ||
                  (c[i].region == c[i - 1].region && c[i].separation >= c[i - 1].separation));
    if (qs.contacts_found > 1) {
        int n1;
        rugo_query_stats q1;
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, A->s, xb, &q, c + 32, 1, &n1, &st, &q1), RUGO_OK);
        ck_assert_int_eq(n1, 1);
        ck_assert_int_eq(q1.contacts_found, qs.contacts_found);
        ck_assert(c[32].id == c[0].id);
    }
    rugo_collide_context_destroy(ctx);
    ck_assert_int_eq(cnt.allocs, cnt.frees);

    /* A context that cannot grow: OUT_OF_MEMORY, no crash, nothing leaked. */
    for (long k = 1; k < 6; ++k) {
        counting c2 = {0, 0, k};
        rugo_allocator a2 = counting_allocator(&c2);
        rugo_collide_context* x2 = NULL;
        ck_assert_int_eq(rugo_collide_context_create(&a2, &x2), RUGO_OK);
        rugo_status s2 = test_collide_shapes(x2, A->s, rugo_identity_transform(), B->s,
                                             rugo_make_transform(0.9, 0.3, 1.0), NULL, c, 64, &n, &st, NULL);
        ck_assert(s2 == RUGO_OK || s2 == RUGO_ERR_OUT_OF_MEMORY);
        rugo_collide_context_destroy(x2);
        ck_assert_int_eq(c2.allocs - (c2.fail_at < c2.allocs ? 1 : 0), c2.frees);
    }
}
END_TEST

START_TEST(test_bad_inputs) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const rugo_shape* a = g_shapes[0].s;
    rugo_transform x = rugo_identity_transform(), nanx = x;
    nanx.p.x = NAN;
    rugo_contact c[4];
    int n = 7;
    rugo_contact_state st = RUGO_STATE_CONTACT;
    const rugo_contact_query defaults = rugo_default_contact_query();
    ck_assert(defaults.resolution == RUGO_RESOLUTION_AUTO);
    ck_assert_int_eq(defaults.lod, 0);
    rugo_contact_query q = test_exact_query();
    ck_assert_int_eq(q.lod, 0);
    ck_assert(q.tolerance < 0);
    ck_assert_int_eq(q.friction_mix, RUGO_MIX_MAX);
    ck_assert_int_eq(q.restitution_mix, RUGO_MIX_MIN);
    ck_assert_int_eq(test_collide_shapes(NULL, a, x, a, x, &q, c, 4, &n, &st, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(n, 0);
    ck_assert_int_eq(st, RUGO_STATE_APART);
    ck_assert_int_eq(test_collide_shapes(ctx, NULL, x, a, x, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, NULL, x, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_collide_shapes(a, x, a, x, &q, ctx, NULL), RUGO_ERR_NULL_ARGUMENT);
    {
        rugo_contact_output o = rugo_contact_output_of(c, 4);
        o.count = 5;
        o.state = RUGO_STATE_CONTACT;
        o.stats.box_tests = 3;
        ck_assert_int_eq(rugo_collide_shapes(a, x, NULL, x, &q, ctx, &o), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(o.count, 0);
        ck_assert_int_eq(o.state, RUGO_STATE_APART);
        ck_assert_int_eq(o.stats.box_tests, 0);
    }
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &q, NULL, 4, &n, &st, NULL),
                     RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &q, c, -1, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_shapes(ctx, a, nanx, a, x, &q, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, nanx, &q, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    rugo_contact_query bq = q;
    bq.cookie = 0;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    bq = q;
    bq.tolerance = NAN;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    bq.tolerance = INFINITY;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    bq = q;
    bq.resolution = NAN;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    bq.resolution = INFINITY;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    bq.resolution = -0.5;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    bq.resolution = RUGO_RESOLUTION_AUTO;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_OK);
    bq = q;
    bq.friction_mix = (rugo_mix_rule)9;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    bq = q;
    bq.restitution_mix = (rugo_mix_rule)-1;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    /* levels of detail beyond the coarsest are clamped, not errors; a positive one (an absolute level,
     * the thesis' numbering) is not a level of detail */
    bq = q;
    bq.lod = -100;
    ck_assert_int_eq(
        test_collide_shapes(ctx, a, x, a, rugo_make_transform(5, 0, 0), &bq, c, 4, &n, &st, NULL), RUGO_OK);
    bq.lod = 100;
    ck_assert_int_eq(
        test_collide_shapes(ctx, a, x, a, rugo_make_transform(5, 0, 0), &bq, c, 4, &n, &st, NULL),
        RUGO_ERR_BAD_ARGUMENT);
    bq.lod = RUGO_LOD_AUTO;
    bq.lod_error_budget = 1e-3;
    ck_assert_int_eq(
        test_collide_shapes(ctx, a, x, a, rugo_make_transform(5, 0, 0), &bq, c, 4, &n, &st, NULL), RUGO_OK);
    bq.lod_error_budget = -1.0;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_BAD_ARGUMENT);
    bq.lod_error_budget = NAN;
    ck_assert_int_eq(test_collide_shapes(ctx, a, x, a, x, &bq, c, 4, &n, &st, NULL), RUGO_ERR_NOT_FINITE);
    /* primitives */
    ck_assert_int_eq(test_collide_circle(ctx, a, x, rugo_v2(0, 0), -1, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_circle(ctx, a, x, rugo_v2(0, 0), NAN, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(test_collide_circle(ctx, a, x, rugo_v2(INFINITY, 0), 1, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(test_collide_circle(NULL, a, x, rugo_v2(0, 0), 1, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(test_collide_circle(ctx, a, nanx, rugo_v2(0, 0), 1, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(test_collide_circle(ctx, a, x, rugo_v2(0, 0), 1, &bq, c, -1, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(
        test_collide_segment(ctx, a, x, rugo_v2(0, 0), rugo_v2(1, 0), -0.1, &q, c, 4, &n, &st, NULL),
        RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(
        test_collide_segment(ctx, a, x, rugo_v2(0, NAN), rugo_v2(1, 0), 0.1, &q, c, 4, &n, &st, NULL),
        RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(
        test_collide_segment(ctx, a, x, rugo_v2(3, 3), rugo_v2(3, 3), 0.1, &q, c, 4, &n, &st, NULL), RUGO_OK);
    rugo_vec2 sq[9] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 1.5}, {0, 0}, {0, 0}, {0, 0}, {0, 0}};
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 4, 0.0, &q, c, 4, &n, &st, NULL), RUGO_OK);
    {
        rugo_contact_output o = rugo_contact_output_of(c, 4);
        const rugo_primitive circle = rugo_make_circle(rugo_v2(0, 0), 1.0);
        ck_assert_int_eq(rugo_collide_primitive(a, x, NULL, x, &q, ctx, &o), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_collide_primitive(a, x, &circle, x, &q, ctx, NULL), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_collide_primitive(a, x, &circle, nanx, &q, ctx, &o), RUGO_ERR_NOT_FINITE);
        rugo_primitive poly;
        ck_assert_int_eq(rugo_make_polygon(NULL, 4, 0.0, &poly), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_make_polygon(sq, 4, 0.0, NULL), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_int_eq(rugo_make_polygon(sq, 2, 0.0, &poly), RUGO_ERR_BAD_ARGUMENT);
        ck_assert_int_eq(rugo_make_polygon(sq, 5, 0.0, &poly), RUGO_ERR_BAD_ARGUMENT); /* not convex */
        ck_assert_int_eq(rugo_make_polygon(sq, 4, 0.01, &poly), RUGO_OK);
        ck_assert_int_eq(poly.count, 4);
        /* a primitive placed by a transform: the same contacts as its points moved to the world */
        const rugo_transform xb = rugo_make_transform(0.3, -0.2, 0.7);
        rugo_primitive moved = poly;
        for (int i = 0; i < 4; ++i)
            moved.points[i] = rugo_transform_point(xb, poly.points[i]);
        rugo_contact c1[4], c2[4];
        rugo_contact_output o1 = rugo_contact_output_of(c1, 4), o2 = rugo_contact_output_of(c2, 4);
        ck_assert_int_eq(rugo_collide_primitive(a, x, &poly, xb, &q, ctx, &o1), RUGO_OK);
        ck_assert_int_eq(rugo_collide_primitive(a, x, &moved, x, &q, ctx, &o2), RUGO_OK);
        ck_assert_int_eq(o1.state, o2.state);
        ck_assert_int_eq(o1.count, o2.count);
        for (int i = 0; i < o1.count; ++i)
            ck_assert_near(c1[i].separation, c2[i].separation, 1e-12);
    }
    /* two points are a segment (a primitive of any count 1..8), not an error */
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 2, 0.0, &q, c, 4, &n, &st, NULL), RUGO_OK);
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 0, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 9, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 4, -1.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 5, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT); /* not convex */
    rugo_vec2 cw[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, cw, 4, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    rugo_vec2 col[4] = {{0, 0}, {1, 0}, {2, 0}, {1, 1}};
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, col, 4, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    rugo_vec2 star[5];
    for (int i = 0; i < 5; ++i)
        star[i] = rugo_v2(cos(TWO_PI * 2 * i / 5), sin(TWO_PI * 2 * i / 5)); /* winds twice */
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, star, 5, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    sq[1].x = NAN;
    ck_assert_int_eq(test_collide_polygon(ctx, a, x, sq, 4, 0.0, &q, c, 4, &n, &st, NULL),
                     RUGO_ERR_NOT_FINITE);
    /* tree pairs */
    rugo_node_pair p[4];
    long t;
    const rugo_mobb_tree* tr = rugo_shape_tree(a);
    ck_assert_int_eq(rugo_tree_pairs(tr, x, 3, tr, x, 3, NULL, p, 4, &n, &t), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tree_pairs(NULL, x, 3, tr, x, 3, ctx, p, 4, &n, &t), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tree_pairs(tr, x, 3, tr, x, 3, ctx, p, 4, NULL, &t), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tree_pairs(tr, x, 3, tr, x, 3, ctx, NULL, 4, &n, &t), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_tree_pairs(tr, x, 3, tr, x, 3, ctx, p, -1, &n, &t), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_tree_pairs(tr, nanx, 3, tr, x, 3, ctx, p, 4, &n, &t), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_tree_pairs(tr, x, 3, tr, x, 3, ctx, NULL, 0, &n, NULL), RUGO_OK);
    ck_assert_str_eq(rugo_contact_state_name(RUGO_STATE_APART), "apart");
    ck_assert_str_eq(rugo_contact_state_name(RUGO_STATE_CONTACT), "contact");
    ck_assert_str_eq(rugo_contact_state_name(RUGO_STATE_INTERSECTING), "intersecting");
    ck_assert_str_eq(rugo_contact_state_name((rugo_contact_state)7), "unknown");
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* Surface values at the points: λ(t), μ from each shape's friction map and the mix rule, ε mixed. */
START_TEST(test_surface_values) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    rugo_collide_context_create(NULL, &ctx);
    const tshape* A = &g_shapes[2]; /* rough */
    const tshape* B = &g_shapes[0];
    test_rng r = test_rng_seed(8);
    int checked = 0;
    for (int k = 0; k < 200; ++k) {
        rugo_transform xa, xb;
        random_poses(&r, A, B, 1, -1.0, ctx, &xa, &xb);
        rugo_contact c[32];
        rugo_contact_state st;
        rugo_contact_query q = test_exact_query();
        q.friction_mix = (rugo_mix_rule)(k % 4);
        q.restitution_mix = (rugo_mix_rule)((k / 4) % 4);
        int n;
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c, 32, &n, &st, NULL), RUGO_OK);
        for (int i = 0; i < n; ++i) {
            rugo_tolerance_level ta, tb;
            rugo_shape_tolerance_level(A->s, c[i].level_a, &ta);
            rugo_shape_tolerance_level(B->s, c[i].level_b, &tb);
            double la = rugo_tolerance_at(ta.total, ta.count, c[i].segment_a, c[i].t_a, 0.0);
            double lb = rugo_tolerance_at(tb.total, tb.count, c[i].segment_b, c[i].t_b, 0.0);
            ck_assert(c[i].tolerance_a == la && c[i].tolerance_b == lb);
            rugo_friction_map fa = rugo_shape_friction_map(A->s), fb = rugo_shape_friction_map(B->s);
            ck_assert(c[i].friction ==
                      rugo_mix(q.friction_mix, rugo_friction(&fa, la), rugo_friction(&fb, lb)));
            ck_assert(c[i].restitution == rugo_mix(q.restitution_mix, rugo_shape_restitution(A->s).epsilon,
                                                   rugo_shape_restitution(B->s).epsilon));
            ck_assert_int_eq(c[i].level_a, rugo_shape_finest_level(A->s));
            ++checked;
        }
    }
    ck_assert_int_gt(checked, 20);
    /* the override replaces both bands */
    rugo_contact c[32];
    rugo_contact_state st;
    int n;
    rugo_contact_query q = test_exact_query();
    q.tolerance = 0.3;
    ck_assert_int_eq(test_collide_shapes(ctx, A->s, rugo_identity_transform(), B->s,
                                         rugo_make_transform(3.0, 0, 0), &q, c, 32, &n, &st, NULL),
                     RUGO_OK);
    for (int i = 0; i < n; ++i)
        ck_assert(c[i].tolerance_a == 0.3 && c[i].tolerance_b == 0.3 && c[i].separation <= 0.6);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- shapes -------------------------------------------------------------------------------------- */

START_TEST(test_shape_defaults_and_accessors) {
    rugo_shape_def d = rugo_default_shape_def();
    ck_assert_int_eq(d.filter, RUGO_FILTER_DEFAULT);
    ck_assert_int_eq(d.coarsest_level, 0);
    ck_assert_ptr_null(d.tolerances);
    ck_assert(d.q == RUGO_DEFAULT_Q);
    ck_assert_int_eq(d.estimator, RUGO_ESTIMATOR_DETAIL);
    ck_assert_int_eq(d.box_method, RUGO_BOXES_MULTIRES);
    ck_assert_int_eq(d.check_self_intersection, 1);
    ck_assert(d.friction.alpha == rugo_default_friction_map().alpha);
    ck_assert(d.restitution.epsilon == rugo_default_restitution().epsilon);
    rugo_vec2 p[32];
    test_rng r = test_rng_seed(5);
    test_random_star(&r, 32, rugo_v2(1, 2), 3.0, 0.3, p);
    d.points = p;
    d.count = 32;
    d.coarsest_level = 3;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&d, &s, NULL), RUGO_OK);
    ck_assert_int_eq(rugo_shape_finest_level(s), 5);
    ck_assert_int_eq(rugo_shape_coarsest_level(s), 3);
    ck_assert(!rugo_shape_is_rough(s));
    ck_assert(!rugo_shape_was_reversed(s));
    ck_assert_ptr_nonnull(rugo_shape_tree(s));
    ck_assert_ptr_nonnull(rugo_shape_pyramid(s));
    rugo_contour c;
    ck_assert_int_eq(rugo_shape_level(s, 4, &c), RUGO_OK);
    ck_assert_int_eq(c.count, 16);
    ck_assert_int_eq(rugo_shape_level(s, 2, &c), RUGO_ERR_BAD_LEVEL);
    ck_assert_int_eq(rugo_shape_level(s, 6, &c), RUGO_ERR_BAD_LEVEL);
    rugo_tolerance_level tl;
    ck_assert_int_eq(rugo_shape_tolerance_level(s, 5, &tl), RUGO_OK);
    for (int i = 0; i < 32; ++i)
        ck_assert(tl.total[i] == 0.0);
    ck_assert_int_eq(rugo_shape_tolerance_level(s, 1, &tl), RUGO_ERR_BAD_LEVEL);
    rugo_contour fine = {p, 32};
    rugo_mass_properties m0 = rugo_contour_mass_properties(fine), m = rugo_shape_mass(s);
    ck_assert_near(m.area, m0.area, 1e-12 * fabs(m0.area));
    ck_assert_near(m.centroid.x, m0.centroid.x, 1e-12);
    ck_assert_near(m.inertia, m0.inertia, 1e-12 * fabs(m0.inertia));
    ck_assert(rugo_shape_friction_map(s).lambda_min == d.friction.lambda_min);
    ck_assert(rugo_shape_restitution(s).epsilon_max == d.restitution.epsilon_max);
    ck_assert_int_eq(rugo_shape_level(NULL, 4, &c), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_level(s, 4, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_ptr_null(rugo_shape_tree(NULL));
    ck_assert_int_eq(rugo_shape_finest_level(NULL), -1);
    ck_assert(isnan(rugo_shape_mass(NULL).area));
    rugo_shape_destroy(s);
    rugo_shape_destroy(NULL);
}
END_TEST

/* A clockwise input is reversed and its tolerances with it: input segment j is stored segment n-2-j. */
START_TEST(test_shape_reversed_tolerances) {
    enum { N = 16 };
    rugo_vec2 p[N], q[N];
    double tol[N], tolq[N];
    test_rng r = test_rng_seed(9);
    test_random_star(&r, N, rugo_v2(0, 0), 1.0, 0.3, p);
    for (int i = 0; i < N; ++i) {
        tol[i] = 0.01 * (i + 1);
        q[i] = p[N - 1 - i]; /* clockwise */
    }
    /* Input segment j of q (control points q_j, q_{j+1}) is segment N-2-j of p. */
    for (int j = 0; j < N; ++j)
        tolq[j] = tol[rugo__wrap(N - 2 - j, N)];
    rugo_shape_def d = rugo_default_shape_def();
    d.points = q;
    d.count = N;
    d.tolerances = tolq;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&d, &s, NULL), RUGO_OK);
    ck_assert(rugo_shape_was_reversed(s));
    ck_assert(rugo_shape_is_rough(s));
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(s, 4, &tl);
    rugo_contour c;
    rugo_shape_level(s, 4, &c);
    /* The stored curve is p (up to the rotation of indices the reversal gives); find the offset. */
    int off = -1;
    for (int k = 0; k < N && off < 0; ++k)
        if (c.points[0].x == p[k].x && c.points[0].y == p[k].y) off = k;
    ck_assert_int_ge(off, 0);
    for (int j = 0; j < N; ++j) {
        /* stored segment j has control points c_j, c_{j+1} = p_{j+off}, p_{j+off+1} */
        ck_assert_msg(tl.total[j] == tol[rugo__wrap(j + off, N)], "segment %d: %g vs %g", j, tl.total[j],
                      tol[rugo__wrap(j + off, N)]);
    }
    rugo_shape_destroy(s);
}
END_TEST

START_TEST(test_shape_bad_inputs_and_leaks) {
    rugo_vec2 p[16];
    test_rng r = test_rng_seed(11);
    test_random_star(&r, 16, rugo_v2(0, 0), 1.0, 0.3, p);
    double tol[16];
    for (int i = 0; i < 16; ++i)
        tol[i] = 0.05;
    rugo_shape* s = (rugo_shape*)0x1;
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p;
    d.count = 16;
    d.tolerances = tol;
    ck_assert_int_eq(rugo_shape_create(NULL, &s, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_create(&d, NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    /* Sizes: the star (size ~2) scaled to the ends of [RUGO_SHAPE_MIN_SIZE, RUGO_SHAPE_MAX_SIZE] builds,
     * with a finite positive inertia; a factor 100 beyond either end is BAD_SIZE. */
    const double factors[4] = {8e-38, 2e36, 1e-40, 1e39};
    for (int f = 0; f < 4; ++f) {
        rugo_vec2 q[16];
        double qt[16];
        for (int i = 0; i < 16; ++i) {
            q[i] = rugo_v2_scale(factors[f], p[i]);
            qt[i] = factors[f] * tol[i];
        }
        rugo_shape_def sd = d;
        sd.points = q;
        sd.tolerances = qt;
        rugo_shape* t = (rugo_shape*)0x1;
        const rugo_status st = rugo_shape_create(&sd, &t, NULL);
        if (f < 2) {
            ck_assert_int_eq(st, RUGO_OK);
            const rugo_mass_properties m = rugo_shape_mass(t);
            ck_assert(m.inertia > 0.0 && m.inertia < 1e150 && isfinite(m.area) && m.area > 0.0);
            rugo_shape_destroy(t);
        } else {
            ck_assert_int_eq(st, RUGO_ERR_BAD_SIZE);
            ck_assert_ptr_null(t);
        }
    }
    /* Tolerances: up to RUGO_SHAPE_MAX_SIZE a shape builds and its bake loads back (every stored value
     * within the format's 1e150); above, BAD_SIZE (a 1e150 band used to build, then its bake was
     * refused by the loader). */
    const double bands[3] = {RUGO_SHAPE_MAX_SIZE, 1e38, 1e150};
    for (int f = 0; f < 3; ++f) {
        double qt[16];
        for (int i = 0; i < 16; ++i)
            qt[i] = i % 3 == 0 ? bands[f] : tol[i];
        rugo_shape_def sd = d;
        sd.tolerances = qt;
        rugo_shape* t = (rugo_shape*)0x1;
        const rugo_status st = rugo_shape_create(&sd, &t, NULL);
        if (f > 0) {
            ck_assert_int_eq(st, RUGO_ERR_BAD_SIZE);
            ck_assert_ptr_null(t);
            continue;
        }
        ck_assert_int_eq(st, RUGO_OK);
        size_t size = 0, written = 0;
        ck_assert_int_eq(rugo_shape_bake_size(t, &size), RUGO_OK);
        void* buf = malloc(size);
        ck_assert_ptr_nonnull(buf);
        ck_assert_int_eq(rugo_shape_bake(t, buf, size, &written), RUGO_OK);
        rugo_shape* back = NULL;
        ck_assert_int_eq(rugo_shape_load_baked(buf, written, NULL, &back, NULL), RUGO_OK);
        rugo_shape_destroy(back);
        free(buf);
        rugo_shape_destroy(t);
    }
    rugo_shape_def bad = d;
    bad.cookie = 0;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_null(s);
    bad = d;
    bad.friction.alpha = -1;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.friction.lambda_min = NAN;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NOT_FINITE);
    bad = d;
    bad.restitution.epsilon = 0.95;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_EMPTY_RANGE);
    bad = d;
    bad.restitution.epsilon_max = 2;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.count = 12;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NOT_POWER_OF_TWO);
    bad = d;
    bad.points = NULL;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NULL_ARGUMENT);
    bad = d;
    bad.q = 0;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_QUANTILE);
    bad = d;
    bad.estimator = (rugo_tolerance_estimator)7;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.box_method = (rugo_box_method)7;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.coarsest_level = 9;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_BAD_LEVEL);
    double badtol[16];
    memcpy(badtol, tol, sizeof tol);
    badtol[3] = -1;
    bad = d;
    bad.tolerances = badtol;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NEGATIVE_TOLERANCE);
    badtol[3] = NAN;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NOT_FINITE);
    rugo_vec2 pn[16];
    memcpy(pn, p, sizeof p);
    pn[2].x = INFINITY;
    bad = d;
    bad.points = pn;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, NULL), RUGO_ERR_NOT_FINITE);
    rugo_vec2 cross[16];
    for (int i = 0; i < 16; ++i)
        cross[i] = p[(i * 5) % 16]; /* a star polygon: crosses itself */
    bad = d;
    bad.points = cross;
    rugo_contour_problem pr;
    ck_assert_int_eq(rugo_shape_create(&bad, &s, &pr), RUGO_ERR_SELF_INTERSECTING);

    /* Every allocation failing in turn: OUT_OF_MEMORY, nothing leaked. */
    counting c0 = {0, 0, -1};
    d.allocator = counting_allocator(&c0);
    ck_assert_int_eq(rugo_shape_create(&d, &s, NULL), RUGO_OK);
    rugo_shape_destroy(s);
    ck_assert_int_eq(c0.allocs, c0.frees);
    for (long k = 0; k < c0.allocs; ++k) {
        counting c = {0, 0, k};
        d.allocator = counting_allocator(&c);
        s = (rugo_shape*)0x1;
        rugo_status st = rugo_shape_create(&d, &s, NULL);
        ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
        ck_assert_ptr_null(s);
        ck_assert_int_eq(c.allocs - 1, c.frees);
    }
}
END_TEST

/* ---- query margin (speculative contacts, used by the Box2D bridge) ------------------------------ */

/* margin m: every local minimum of the distance within λ_A + λ_B + m, facing, is reported (against the
 * brute-force reference); margin 0 changes nothing; contacts within the band are bit-identical with and
 * without a margin; NOT_FINITE / BAD_ARGUMENT for bad margins. */
START_TEST(test_query_margin) {
    build_shapes();
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    enum { CAP = 256 };
    static rugo_contact c0[CAP], c1[CAP], cm[CAP];
    static refres R;
    test_rng r = test_rng_seed(909);
    long required = 0, missed = 0, spurious = 0, extra = 0;
    for (int k = 0; k < 300; ++k) {
        const tshape* A = &g_shapes[k % N_SHAPES];
        const tshape* B = &g_shapes[(k / N_SHAPES) % N_SHAPES];
        const double size = fmax(A->size, B->size), margin = 0.05 * size;
        rugo_transform xa, xb;
        random_poses(&r, A, B, 0, -1.0, ctx, &xa, &xb);
        rugo_contact_query q = test_exact_query();
        int n0 = 0, n1 = 0, nm = 0;
        rugo_contact_state s0, s1, sm;
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c0, CAP, &n0, &s0, NULL), RUGO_OK);
        q.margin = 0.0;
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, c1, CAP, &n1, &s1, NULL), RUGO_OK);
        ck_assert_int_eq(n0, n1);
        ck_assert_int_eq(s0, s1);
        ck_assert(memcmp(c0, c1, (size_t)n0 * sizeof(rugo_contact)) == 0);
        q.margin = margin;
        ck_assert_int_eq(test_collide_shapes(ctx, A->s, xa, B->s, xb, &q, cm, CAP, &nm, &sm, NULL), RUGO_OK);
        if (s0 == RUGO_STATE_INTERSECTING) {
            ck_assert_int_eq(sm, RUGO_STATE_INTERSECTING);
            continue;
        }
        /* Every margin-0 contact is among the margin contacts, with the same values. */
        for (int i = 0; i < n0; ++i) {
            int found = 0;
            for (int j = 0; j < nm && !found; ++j)
                found = c0[i].id == cm[j].id && c0[i].separation == cm[j].separation &&
                        c0[i].point_a.x == cm[j].point_a.x && c0[i].point_b.y == cm[j].point_b.y;
            ck_assert_msg(found, "margin lost a contact");
        }
        extra += nm - n0;
        for (int j = 0; j < nm; ++j)
            ck_assert(cm[j].separation <= cm[j].tolerance_a + cm[j].tolerance_b + margin * (1 + 1e-9));
        /* Against the reference: minima within band + margin, facing. */
        curve ca = {A->fine.points, A->fine.count, xa}, cb = {B->fine.points, B->fine.count, xb};
        reference(&ca, &cb, 1.3 * (A->max_lambda + B->max_lambda) + margin * 1.3 + 1e-12, size, 1, &R);
        if (R.crossing || R.contained || R.newton_fail > 0 || R.crossing_doubt) continue;
        for (int m = 0; m < R.nmin; ++m) {
            const refmin* mm = &R.m[m];
            double band = lambda_at(A, mm->ua, -1.0) + lambda_at(B, mm->ub, -1.0) + margin;
            if (fabs(mm->dist - band) <= 1e-9 * size || mm->dist > band) continue;
            rugo_vec2 d = rugo_v2_sub(mm->pb, mm->pa);
            if (mm->dist > 1e-9 * size) {
                rugo_vec2 na = ref_normal(&ca, mm->ua), nb = ref_normal(&cb, mm->ub);
                double fa = rugo_v2_dot(d, na) / mm->dist, fb = rugo_v2_dot(d, nb) / mm->dist;
                if (fabs(fa) < 1e-6 || fabs(fb) < 1e-6 || fa < 0 || fb > 0) continue;
            }
            ++required;
            int found = 0;
            for (int i = 0; i < nm && !found; ++i)
                found = hypot(cm[i].point_a.x - mm->pa.x, cm[i].point_a.y - mm->pa.y) <= 1e-4 * size &&
                        fabs(cm[i].separation - mm->dist) <= 1e-9 * size;
            missed += !found;
        }
        for (int i = 0; i < nm; ++i) {
            int found = 0;
            for (int m = 0; m < R.nmin && !found; ++m)
                found = hypot(cm[i].point_a.x - R.m[m].pa.x, cm[i].point_a.y - R.m[m].pa.y) <= 1e-4 * size;
            spurious += !found;
        }
    }
    printf("margin: %ld minima required by the reference, %ld missed, %ld spurious; %ld contacts beyond the "
           "band\n",
           required, missed, spurious, extra);
    ck_assert_int_eq(missed, 0);
    ck_assert_int_eq(spurious, 0);
    ck_assert(extra > 0);
    /* Bad margins. */
    rugo_contact_query q = test_exact_query();
    int n;
    rugo_contact_state st;
    q.margin = -1e-3;
    ck_assert_int_eq(test_collide_shapes(ctx, g_shapes[0].s, rugo_identity_transform(), g_shapes[1].s,
                                         rugo_make_transform(5, 0, 0), &q, c0, CAP, &n, &st, NULL),
                     RUGO_ERR_BAD_ARGUMENT);
    q.margin = NAN;
    ck_assert_int_eq(test_collide_circle(ctx, g_shapes[0].s, rugo_identity_transform(), rugo_v2(5, 0), 1.0,
                                         &q, c0, CAP, &n, &st, NULL),
                     RUGO_ERR_NOT_FINITE);
    /* Primitives: a circle just beyond the band is reported with the margin only. */
    const tshape* A = &g_shapes[0];
    rugo_transform xa = rugo_identity_transform();
    q = test_exact_query();
    q.tolerance = 0.0;
    rugo_vec2 far = rugo_v2(A->radius * 3.0, 0.0);
    rugo_curve_point cp = rugo_contour_closest_point(A->fine, far);
    const double radius = cp.distance - 0.01 * A->size; /* gap 1% of the size */
    ck_assert_int_eq(test_collide_circle(ctx, A->s, xa, far, radius, &q, c0, CAP, &n, &st, NULL), RUGO_OK);
    ck_assert_int_eq(n, 0);
    q.margin = 0.02 * A->size;
    ck_assert_int_eq(test_collide_circle(ctx, A->s, xa, far, radius, &q, c0, CAP, &n, &st, NULL), RUGO_OK);
    ck_assert_int_ge(n, 1);
    ck_assert(fabs(c0[0].separation - 0.01 * A->size) <= 1e-9 * A->size);
    rugo_collide_context_destroy(ctx);
}
END_TEST

/* ---- containment through the tree (collide_levels.c, "Containment through the tree") ------------ */

typedef struct contain_tally {
    long cases, inside, mismatches, closest_mismatches;
} contain_tally;

/* The tree walks (point_query.c) against the passes over all segments (rugo_contour_contains,
 * rugo_contour_closest_point): the same answers are required, bit for bit, not just close ones. */
static void contain_check(const rugo_shape* s, int level, rugo_contour c, rugo_vec2 p, contain_tally* T) {
    int visited = -1;
    const int tree = rugo__shape_contains(s, level, p, &visited);
    const int all = rugo_contour_contains(c, p);
    ck_assert_int_ge(visited, 0);
    ck_assert_int_le(visited, c.count);
    bool pub = !all;
    ck_assert_int_eq(rugo_shape_contains(s, level, p, &pub), RUGO_OK);
    T->cases++;
    T->inside += all != 0;
    if ((tree != 0) != (all != 0) || (pub != 0) != (all != 0)) {
        if (T->mismatches < 5)
            printf(
                "containment mismatch: level %d, p = (%.17g, %.17g): tree %d, public %d, all segments %d\n",
                level, p.x, p.y, tree, pub, all);
        T->mismatches++;
    }
    const rugo_curve_point ref = rugo_contour_closest_point(c, p);
    rugo_curve_point cp;
    ck_assert_int_eq(rugo_shape_closest_point(s, level, p, &cp), RUGO_OK);
    if (cp.segment != ref.segment || cp.t != ref.t || cp.point.x != ref.point.x ||
        cp.point.y != ref.point.y || cp.distance != ref.distance) {
        if (T->closest_mismatches < 5)
            printf(
                "closest point mismatch: level %d, p = (%.17g, %.17g): tree (%d, %.17g, %.17g), all segments "
                "(%d, %.17g, %.17g)\n",
                level, p.x, p.y, cp.segment, cp.t, cp.distance, ref.segment, ref.t, ref.distance);
        T->closest_mismatches++;
    }
}

/* Points that stress the count: random ones around the curve; the Bezier points of every segment
 * (joints included) and control points, and points on the same horizontal line left and right of them
 * (rays through joints and hull corners); a random point of every segment, points 1e-15 .. 1e-3 of
 * the size off it on both sides, and rays through it; the points where the curve has a horizontal
 * tangent and rays touching the curve there (also one ulp above and below). Every level. */
static void contain_stress(const rugo_shape* s, test_rng* r, contain_tally* T) {
    for (int L = rugo_shape_coarsest_level(s); L <= rugo_shape_finest_level(s); ++L) {
        rugo_contour c;
        rugo_shape_level(s, L, &c);
        rugo_vec2 lo, hi;
        rugo_contour_bounds(c, &lo, &hi);
        const double w = hi.x - lo.x, h = hi.y - lo.y;
        for (int i = 0; i < 200; ++i)
            contain_check(s, L, c,
                          rugo_v2(test_rng_uniform(r, lo.x - 0.2 * w, hi.x + 0.2 * w),
                                  test_rng_uniform(r, lo.y - 0.2 * h, hi.y + 0.2 * h)),
                          T);
        for (int k = 0; k < c.count; ++k) {
            rugo_vec2 b[4];
            rugo_contour_bezier(c, k, b);
            for (int i = 0; i < 4; ++i) {
                contain_check(s, L, c, b[i], T);
                contain_check(s, L, c, rugo_v2(b[i].x - test_rng_uniform(r, 0, w), b[i].y), T);
                contain_check(s, L, c, rugo_v2(b[i].x + test_rng_uniform(r, 0, w), b[i].y), T);
            }
            contain_check(s, L, c, c.points[k], T);
            contain_check(s, L, c, rugo_v2(c.points[k].x - test_rng_uniform(r, 0, w), c.points[k].y), T);
            const double t = test_rng_uniform(r, 0, 1);
            const rugo_vec2 q = rugo_contour_point(c, k, t), n = rugo_contour_normal(c, k, t);
            contain_check(s, L, c, q, T);
            contain_check(s, L, c, rugo_v2(q.x - test_rng_uniform(r, 0, w), q.y), T);
            const double e = pow(10.0, -test_rng_uniform(r, 3, 15)) * w;
            contain_check(s, L, c, rugo_v2(q.x + e * n.x, q.y + e * n.y), T);
            contain_check(s, L, c, rugo_v2(q.x - e * n.x, q.y - e * n.y), T);
            /* horizontal tangents: y'(t) = (v t^2 + w t + r).y / 2 = 0 */
            rugo_vec2 cv, cw, cr;
            rugo_contour_derivative_coefficients(c, k, &cv, &cw, &cr);
            const double A = cv.y, B = cw.y, C = cr.y, disc = B * B - 4.0 * A * C;
            if (A == 0.0 || disc < 0.0) continue;
            for (int sg = -1; sg <= 1; sg += 2) {
                const double tt = (-B + sg * sqrt(disc)) / (2.0 * A);
                if (!(tt >= 0.0 && tt < 1.0)) continue;
                const rugo_vec2 qq = rugo_contour_point(c, k, tt);
                const double x = qq.x - test_rng_uniform(r, 0, w);
                contain_check(s, L, c, qq, T);
                contain_check(s, L, c, rugo_v2(x, qq.y), T);
                contain_check(s, L, c, rugo_v2(x, nextafter(qq.y, HUGE_VAL)), T);
                contain_check(s, L, c, rugo_v2(x, nextafter(qq.y, -HUGE_VAL)), T);
            }
        }
    }
}

START_TEST(test_tree_containment_matches_winding) {
    build_shapes();
    test_rng r = test_rng_seed(0x636f6e74);
    contain_tally T;
    memset(&T, 0, sizeof T);
    /* the suite's six kinds (convex, concave, very rough, straight sides, coincident control points) */
    for (int i = 0; i < N_SHAPES; ++i)
        contain_stress(g_shapes[i].s, &r, &T);
    rugo_vec2* p = (rugo_vec2*)xmalloc(1024 * sizeof *p);
    double* tol = (double*)xmalloc(1024 * sizeof *tol);
    /* wavy stars of 16 .. 1024 points, with tolerances (coarse levels of their own) and without */
    for (int n = 16; n <= 1024; n *= 4)
        for (int rep = 0; rep < 2; ++rep) {
            test_random_star(&r, n, rugo_v2(0.3, -0.1), 1.0, 0.45, p);
            for (int i = 0; i < n; ++i)
                tol[i] = test_rng_uniform(&r, 0.0, 0.01);
            rugo_shape* s = make_shape(p, n, rep ? tol : NULL);
            contain_stress(s, &r, &T);
            rugo_shape_destroy(s);
        }
    /* a staircase: horizontal pieces on the rays of their own joints */
    for (int i = 0; i < 64; ++i) {
        const int step = i / 8, j = i % 8;
        const double x = step < 4 ? -1.0 + 0.5 * step + 0.0625 * j : 1.0 - 0.5 * (step - 4) - 0.0625 * j;
        const double y = (step < 4 ? 0.25 * step : 1.5 - 0.25 * (step - 4)) + (j < 4 ? 0.0 : 0.1);
        p[i] = rugo_v2(x, y);
    }
    rugo_shape* stairs = make_shape(p, 64, NULL);
    contain_stress(stairs, &r, &T);
    rugo_shape_destroy(stairs);
    /* repeated corners (point-like segments, horizontal sides), at the origin and 1e6 away */
    const rugo_vec2 corners[4] = {{-0.9, -0.6}, {0.9, -0.6}, {0.9, 0.6}, {-0.9, 0.6}};
    for (int far = 0; far < 2; ++far) {
        for (int i = 0; i < 16; ++i)
            p[i] = rugo_v2(corners[i / 4].x + (far ? 1e6 : 0.0), corners[i / 4].y - (far ? 3e5 : 0.0));
        rugo_shape* sq = make_shape(p, 16, NULL);
        contain_stress(sq, &r, &T);
        rugo_shape_destroy(sq);
    }
    free(p);
    free(tol);
    printf("tree containment: %ld points (%ld inside), %ld answers differ from the winding count over all "
           "segments; closest point through the tree: %ld differ from the pass over all segments\n",
           T.cases, T.inside, T.mismatches, T.closest_mismatches);
    ck_assert_int_ge(T.cases, 50000);
    ck_assert(T.inside > T.cases / 5 && T.inside < T.cases - T.cases / 5);
    ck_assert_int_eq(T.mismatches, 0);
    ck_assert_int_eq(T.closest_mismatches, 0);
}
END_TEST

/* rugo_shape_closest_point and rugo_shape_contains: statuses and outputs on bad input. */
START_TEST(test_point_queries_bad_input) {
    build_shapes();
    const rugo_shape* s = g_shapes[1].s;
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    rugo_curve_point cp;
    bool in = true;
    const rugo_vec2 p = rugo_v2(0.1, 0.2);
    ck_assert_int_eq(rugo_shape_closest_point(NULL, J, p, &cp), RUGO_ERR_NULL_ARGUMENT);
    ck_assert(cp.distance == HUGE_VAL && cp.point.x == p.x && cp.point.y == p.y && cp.segment == 0);
    ck_assert_int_eq(rugo_shape_closest_point(s, J, p, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_shape_contains(NULL, J, p, &in), RUGO_ERR_NULL_ARGUMENT);
    ck_assert(!in);
    ck_assert_int_eq(rugo_shape_contains(s, J, p, NULL), RUGO_ERR_NULL_ARGUMENT);
    const int bad_levels[4] = {J + 1, Jmin - 1, 0, -1};
    for (int i = 0; i < 4; ++i) {
        cp.distance = 0.0;
        in = true;
        ck_assert_int_eq(rugo_shape_closest_point(s, bad_levels[i], p, &cp), RUGO_ERR_BAD_LEVEL);
        ck_assert(cp.distance == HUGE_VAL);
        ck_assert_int_eq(rugo_shape_contains(s, bad_levels[i], p, &in), RUGO_ERR_BAD_LEVEL);
        ck_assert(!in);
    }
    const rugo_vec2 bad_points[3] = {{NAN, 0.0}, {0.0, INFINITY}, {-INFINITY, NAN}};
    for (int i = 0; i < 3; ++i) {
        ck_assert_int_eq(rugo_shape_closest_point(s, J, bad_points[i], &cp), RUGO_ERR_NOT_FINITE);
        ck_assert(cp.distance == HUGE_VAL);
        ck_assert_int_eq(rugo_shape_contains(s, J, bad_points[i], &in), RUGO_ERR_NOT_FINITE);
        ck_assert(!in);
    }
    /* and valid input still answers: a point far outside, the centroid inside */
    ck_assert_int_eq(rugo_shape_contains(s, J, rugo_v2(1e3, 0.0), &in), RUGO_OK);
    ck_assert(!in);
    ck_assert_int_eq(rugo_shape_contains(s, J, rugo_shape_mass(s).centroid, &in), RUGO_OK);
    ck_assert(in);
    ck_assert_int_eq(rugo_shape_closest_point(s, Jmin, rugo_v2(1e3, 0.0), &cp), RUGO_OK);
    ck_assert(cp.distance > 900.0 && cp.distance < 1e3 + 10.0);
    /* up to 1e150 a distance; beyond, squared distances overflow: NOT_FINITE (was OK with distance inf) */
    ck_assert_int_eq(rugo_shape_closest_point(s, J, rugo_v2(1e150, -1e150), &cp), RUGO_OK);
    ck_assert(isfinite(cp.distance) && cp.distance > 1.4e150);
    ck_assert_int_eq(rugo_shape_closest_point(s, J, rugo_v2(1e154, 1e154), &cp), RUGO_ERR_NOT_FINITE);
    ck_assert(cp.distance == HUGE_VAL);
}
END_TEST

/* Work against segments: one contact between two ellipses of 32 .. 4096 segments. The segment pairs
 * stay a handful, the box tests grow by about the tree's depth per doubling, and the containment test
 * evaluates a few segments (those the ray crosses), not all of them. */
START_TEST(test_work_against_segments) {
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    rugo_vec2* p = (rugo_vec2*)xmalloc(4096 * sizeof *p);
    test_rng r = test_rng_seed(0x776f726b);
    long prev_tests = 0;
    int max_visited = 0;
    for (int n = 32; n <= 4096; n *= 2) {
        for (int k = 0; k < n; ++k) {
            const double th = TWO_PI * k / n;
            p[k] = rugo_v2(0.5 * cos(th), 0.35 * sin(th));
        }
        rugo_shape* a = make_shape(p, n, NULL);
        rugo_shape* b = make_shape(p, n, NULL);
        const rugo_transform xa = rugo_make_transform(0.0, 0.0, 0.3);
        rugo_transform xb = rugo_make_transform(0.0, 0.0, 2.0);
        const rugo_vec2 u = rugo_v2(cos(0.7), sin(0.7));
        double lo = 0.0, hi = 3.0; /* first touch along u, by bisection on the state */
        for (int it = 0; it < 64; ++it) {
            const double mid = 0.5 * (lo + hi);
            xb.p = rugo_v2(mid * u.x, mid * u.y);
            int cnt = 0;
            rugo_contact_state st;
            ck_assert_int_eq(test_collide_shapes(ctx, a, xa, b, xb, NULL, NULL, 0, &cnt, &st, NULL), RUGO_OK);
            if (st == RUGO_STATE_INTERSECTING)
                lo = mid;
            else
                hi = mid;
        }
        xb.p = rugo_v2((hi + 1e-7) * u.x, (hi + 1e-7) * u.y);
        rugo_contact_query q = test_exact_query();
        q.margin = 2e-7;
        rugo_contact c[8];
        int cnt = 0;
        rugo_contact_state st;
        rugo_query_stats qs;
        ck_assert_int_eq(test_collide_shapes(ctx, a, xa, b, xb, &q, c, 8, &cnt, &st, &qs), RUGO_OK);
        ck_assert_int_eq(st, RUGO_STATE_CONTACT);
        ck_assert_int_eq(cnt, 1);
        ck_assert_near(c[0].separation, 1e-7, 1e-9);
        ck_assert_int_le(qs.segment_pairs, 4);
        if (prev_tests > 0) ck_assert_int_le(qs.box_tests, prev_tests + 24);
        prev_tests = qs.box_tests;
        /* containment from points of B's curve (B's point 0 is what a query tests) and random points */
        rugo_contour ca;
        rugo_shape_level(a, rugo_shape_finest_level(a), &ca);
        for (int i = 0; i < 200; ++i) {
            const rugo_vec2 pt = rugo_v2(test_rng_uniform(&r, -0.6, 0.6), test_rng_uniform(&r, -0.45, 0.45));
            int visited = 0;
            const int in = rugo__shape_contains(a, 0, pt, &visited);
            ck_assert_int_eq(in != 0, rugo_contour_contains(ca, pt) != 0);
            max_visited = visited > max_visited ? visited : max_visited;
        }
        printf("one contact, %d segments: %ld box tests, %ld segment pairs\n", n, qs.box_tests,
               qs.segment_pairs);
        rugo_shape_destroy(a);
        rugo_shape_destroy(b);
    }
    printf("containment through the tree: at most %d segments evaluated per point (up to 4096 segments)\n",
           max_visited);
    ck_assert_int_le(max_visited, 16);
    free(p);
    rugo_collide_context_destroy(ctx);
}
END_TEST

int main(void) {
    Suite* s = suite_create("collide");
    TCase* tsh = tcase_create("shape");
    tcase_add_test(tsh, test_shape_defaults_and_accessors);
    tcase_add_test(tsh, test_shape_reversed_tolerances);
    tcase_add_test(tsh, test_shape_bad_inputs_and_leaks);
    suite_add_tcase(s, tsh);
    TCase* tp = tcase_create("properties");
    tcase_set_timeout(tp, 1200);
    tcase_add_test(tp, test_swap_mirrors);
    tcase_add_test(tp, test_rigid_motion_invariance);
    tcase_add_test(tp, test_levels_of_detail_bound);
    suite_add_tcase(s, tp);
    TCase* th = tcase_create("hard cases");
    tcase_set_timeout(th, 600);
    tcase_add_test(th, test_near_tangent);
    tcase_add_test(th, test_parallel_straight_segments);
    tcase_add_test(th, test_point_like_segments);
    tcase_add_test(th, test_sharp_corner_tilted);
    tcase_add_test(th, test_coarse_levels_are_simple_curves);
    tcase_add_test(th, test_long_primitives_keep_resolution);
    tcase_add_test(th, test_region_depth_is_a_closest_pair);
    tcase_add_test(th, test_shallow_overlap_has_contact);
    tcase_add_test(th, test_coincident_curves);
    tcase_add_test(th, test_containment);
    tcase_add_test(th, test_far_and_scaled);
    suite_add_tcase(s, th);
    TCase* tq = tcase_create("primitives");
    tcase_set_timeout(tq, 1200);
    tcase_add_test(tq, test_primitives_against_brute_force);
    tcase_add_test(tq, test_primitive_penetration);
    suite_add_tcase(s, tq);
    TCase* tm = tcase_create("misc");
    tcase_set_timeout(tm, 600);
    tcase_add_test(tm, test_tree_pairs_against_all_pairs);
    tcase_add_test(tm, test_tree_pairs_match_reference_traversal);
    tcase_add_test(tm, test_context_reserve);
    tcase_add_test(tm, test_reduce_manifold);
    tcase_add_test(tm, test_context_and_truncation);
    tcase_add_test(tm, test_bad_inputs);
    tcase_add_test(tm, test_surface_values);
    tcase_add_test(tm, test_query_margin);
    tcase_add_test(tm, test_tree_containment_matches_winding);
    tcase_add_test(tm, test_point_queries_bad_input);
    tcase_add_test(tm, test_work_against_segments);
    suite_add_tcase(s, tm);
    TCase* ta = tcase_create("acceptance");
    tcase_set_timeout(ta, 3600);
    tcase_add_test(ta, test_acceptance_random_poses);
    suite_add_tcase(s, ta);
    return test_run_suite(s);
}
