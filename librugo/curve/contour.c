/* Closed uniform cubic B-spline contours (SPEC 1): evaluation, derivatives, orientation, arc length,
 * exact mass properties, bounds, closest point, containment and ray cast. Queries do not allocate.
 * Validation, with the self-intersection test, is in contour_check.c. */
#include "rugo/contour.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__contour_winding_segment, rugo__contour_bezier_rel */
#include "curve/poly.h"

#include <float.h>

/* The four control points c_{j-1}, c_j, c_{j+1}, c_{j+2} of segment j. */
/* Wraps j first so that j - 1 + i cannot overflow for j near INT_MIN / INT_MAX; an empty contour
 * gives zeros instead of a division by zero. */
static void segment_points(rugo_contour c, int j, rugo_vec2 q[4]) {
    int n = c.count;
    if (n < 1 || c.points == NULL) {
        for (int i = 0; i < 4; ++i)
            q[i] = rugo_v2(0.0, 0.0);
        return;
    }
    int base = rugo__wrap(j, n);
    for (int i = 0; i < 4; ++i)
        q[i] = c.points[rugo__wrap(base - 1 + i, n)];
}

/* ---------------------------------------------------------------------------------------------------
 * Segments relative to a reference point. Subtracting the reference from the control points before
 * combining them keeps full relative precision for contours far from the origin (a body at 1e6 with
 * features of size 1 would otherwise lose ten digits in every difference). */

static void segment_points_rel(rugo_contour c, int j, rugo_vec2 o, rugo_vec2 q[4]) {
    segment_points(c, j, q);
    for (int i = 0; i < 4; ++i)
        q[i] = rugo_v2_sub(q[i], o);
}

/* Power form f(t) = k3 t^3 + k2 t^2 + k1 t + k0 (k3 = v/6, k2 = w/4, k1 = r/2 in the terms of (3.8)).
 * k0 is computed exactly like Bezier b0, so it is the joint, bitwise. */
static void power_from_points(const rugo_vec2 q[4], rugo_vec2 k[4]) {
    k[0] = rugo_v2((q[0].x + 4.0 * q[1].x + q[2].x) / 6.0, (q[0].y + 4.0 * q[1].y + q[2].y) / 6.0);
    k[1] = rugo_v2(0.5 * (q[2].x - q[0].x), 0.5 * (q[2].y - q[0].y));
    k[2] = rugo_v2(0.5 * (q[0].x - 2.0 * q[1].x + q[2].x), 0.5 * (q[0].y - 2.0 * q[1].y + q[2].y));
    k[3] = rugo_v2((q[3].x - 3.0 * q[2].x + 3.0 * q[1].x - q[0].x) / 6.0,
                   (q[3].y - 3.0 * q[2].y + 3.0 * q[1].y - q[0].y) / 6.0);
}

static rugo_vec2 power_point(const rugo_vec2 k[4], rugo_real t) {
    return rugo_v2(((k[3].x * t + k[2].x) * t + k[1].x) * t + k[0].x,
                   ((k[3].y * t + k[2].y) * t + k[1].y) * t + k[0].y);
}

static rugo_vec2 power_d1(const rugo_vec2 k[4], rugo_real t) {
    return rugo_v2((3.0 * k[3].x * t + 2.0 * k[2].x) * t + k[1].x,
                   (3.0 * k[3].y * t + 2.0 * k[2].y) * t + k[1].y);
}

/* Neumaier's compensated sum: perimeters and areas of 2^20 segments keep their last digits. */
typedef struct ksum {
    rugo_real s, c;
} ksum;

static void ksum_add(ksum* k, rugo_real x) {
    rugo_real t = k->s + x;
    if (fabs(k->s) >= fabs(x))
        k->c += (k->s - t) + x;
    else
        k->c += (x - t) + k->s;
    k->s = t;
}

static rugo_real ksum_value(const ksum* k) { return k->s + k->c; }

void rugo_bspline_basis(rugo_real t, rugo_real out[4]) {
    /* Rows of 1/6 [t^3 t^2 t 1] M (2.4)-(2.5). */
    rugo_real s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    out[0] = s * s * s / 6.0;
    out[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    out[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    out[3] = t3 / 6.0;
}

rugo_vec2 rugo_contour_point(rugo_contour c, int segment, rugo_real t) {
    rugo_vec2 q[4];
    rugo_real b[4];
    segment_points(c, segment, q);
    rugo_bspline_basis(t, b);
    return rugo_v2(b[0] * q[0].x + b[1] * q[1].x + b[2] * q[2].x + b[3] * q[3].x,
                   b[0] * q[0].y + b[1] * q[1].y + b[2] * q[2].y + b[3] * q[3].y);
}

void rugo_contour_derivative_coefficients(rugo_contour c, int segment, rugo_vec2* v, rugo_vec2* w,
                                          rugo_vec2* r) {
    rugo_vec2 q[4];
    segment_points(c, segment, q);
    /* (3.8) with c_{j-1} = q0, c_j = q1, c_{j+1} = q2, c_{j+2} = q3. */
    rugo_vec2 vv =
        rugo_v2(q[3].x - 3.0 * q[2].x + 3.0 * q[1].x - q[0].x, q[3].y - 3.0 * q[2].y + 3.0 * q[1].y - q[0].y);
    rugo_vec2 ww =
        rugo_v2(2.0 * q[2].x - 4.0 * q[1].x + 2.0 * q[0].x, 2.0 * q[2].y - 4.0 * q[1].y + 2.0 * q[0].y);
    rugo_vec2 rr = rugo_v2_sub(q[2], q[0]);
    if (v) *v = vv;
    if (w) *w = ww;
    if (r) *r = rr;
}

rugo_vec2 rugo_contour_d1(rugo_contour c, int segment, rugo_real t) {
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, segment, &v, &w, &r);
    return rugo_v2(0.5 * ((v.x * t + w.x) * t + r.x), 0.5 * ((v.y * t + w.y) * t + r.y));
}

rugo_vec2 rugo_contour_d2(rugo_contour c, int segment, rugo_real t) {
    rugo_vec2 v, w;
    rugo_contour_derivative_coefficients(c, segment, &v, &w, NULL);
    return rugo_v2(v.x * t + 0.5 * w.x, v.y * t + 0.5 * w.y);
}

rugo_vec2 rugo_contour_point_at(rugo_contour c, rugo_real u) {
    if (!isfinite(u) || c.count < 1) return rugo_v2(NAN, NAN); /* no segment to cast NaN/inf into */
    rugo_real f = floor(u);
    int seg = rugo__wrap((int)fmod(f, (rugo_real)c.count), c.count);
    return rugo_contour_point(c, seg, u - f);
}

/* Uniform cubic B-spline to Bezier: b0 = (q0 + 4 q1 + q2)/6, b1 = (2 q1 + q2)/3,
 * b2 = (q1 + 2 q2)/3, b3 = (q1 + 4 q2 + q3)/6. b3 of segment j and b0 of segment j+1 come from the
 * same three numbers by the same operations, so joints are bitwise shared: the containment test's
 * consistency relies on that. */
static void bezier_from_points(const rugo_vec2 q[4], rugo_vec2 out[4]) {
    out[0] = rugo_v2((q[0].x + 4.0 * q[1].x + q[2].x) / 6.0, (q[0].y + 4.0 * q[1].y + q[2].y) / 6.0);
    out[1] = rugo_v2((2.0 * q[1].x + q[2].x) / 3.0, (2.0 * q[1].y + q[2].y) / 3.0);
    out[2] = rugo_v2((q[1].x + 2.0 * q[2].x) / 3.0, (q[1].y + 2.0 * q[2].y) / 3.0);
    out[3] = rugo_v2((q[1].x + 4.0 * q[2].x + q[3].x) / 6.0, (q[1].y + 4.0 * q[2].y + q[3].y) / 6.0);
}

void rugo_contour_bezier(rugo_contour c, int segment, rugo_vec2 out[4]) {
    rugo_vec2 q[4];
    segment_points(c, segment, q);
    bezier_from_points(q, out);
}

void rugo__contour_bezier_rel(rugo_contour c, int j, rugo_vec2 o, rugo_vec2 out[4]) {
    rugo_vec2 q[4];
    segment_points_rel(c, j, o, q);
    bezier_from_points(q, out);
}

rugo_vec2 rugo_contour_tangent(rugo_contour c, int segment, rugo_real t) {
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, segment, &v, &w, &r);
    rugo_vec2 d = rugo_v2(0.5 * ((v.x * t + w.x) * t + r.x), 0.5 * ((v.y * t + w.y) * t + r.y));
    rugo_real len = rugo__v2_length(d);
    /* Scale of the segment, so that "zero speed" is judged relative to its size. */
    rugo_real scale = rugo__v2_length(v) + rugo__v2_length(w) + rugo__v2_length(r);
    if (!(len > 1e-12 * scale)) {
        /* A cusp or a point-like spot: the direction of the curve is that of the first non-vanishing
         * higher derivative (f'' then f'''). */
        d = rugo_v2(v.x * t + 0.5 * w.x, v.y * t + 0.5 * w.y);
        len = rugo__v2_length(d);
        if (!(len > 1e-12 * scale)) {
            d = v;
            len = rugo__v2_length(d);
        }
        if (!(len > 0.0)) return rugo_v2(1.0, 0.0); /* a segment shrunk to a point has no direction */
    }
    return rugo_v2(d.x / len, d.y / len);
}

rugo_vec2 rugo_contour_normal(rugo_contour c, int segment, rugo_real t) {
    /* Outward for a counter-clockwise curve: the tangent turned clockwise. */
    rugo_vec2 tg = rugo_contour_tangent(c, segment, t);
    return rugo_v2(tg.y, -tg.x);
}

rugo_real rugo_contour_signed_area(rugo_contour c) {
    /* 1/2 ∮ (x y' - y x') dt, exact: per segment a quintic, integrated by 3-point Gauss-Legendre
     * (exact to degree 5), relative to the first control point for precision far from the origin
     * (the control points are shifted before they are combined, so no digits are lost). */
    static const rugo_real gx[3] = {0.1127016653792583115, 0.5, 0.8872983346207416885};
    static const rugo_real gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    if (c.count < 1 || c.points == NULL) return 0.0;
    rugo_vec2 o = c.points[0];
    ksum sum = {0.0, 0.0};
    for (int j = 0; j < c.count; ++j) {
        rugo_vec2 q[4], k[4];
        segment_points_rel(c, j, o, q);
        power_from_points(q, k);
        rugo_real seg = 0.0;
        for (int g = 0; g < 3; ++g)
            seg += gw[g] * rugo_v2_cross(power_point(k, gx[g]), power_d1(k, gx[g]));
        ksum_add(&sum, seg);
    }
    return 0.5 * ksum_value(&sum);
}

bool rugo_contour_orient_ccw(rugo_vec2* points, int count) {
    if (points == NULL || count < 2) return false;
    rugo_contour c;
    c.points = points;
    c.count = count;
    if (!(rugo_contour_signed_area(c) < 0.0)) return false;
    for (int i = 0, k = count - 1; i < k; ++i, --k) {
        rugo_vec2 tmp = points[i];
        points[i] = points[k];
        points[k] = tmp;
    }
    return true;
}

/* Power form of segment j about its own control point c_j: derivatives are translation invariant,
 * so this is the most precise frame for lengths. */
static void segment_power_local(rugo_contour c, int j, rugo_vec2 k[4]) {
    rugo_vec2 q[4];
    segment_points_rel(c, j, c.points[rugo__wrap(j, c.count)], q);
    power_from_points(q, k);
}

/* ---------------------------------------------------------------------------------------------------
 * Arc length (3.6)-(3.7). */

/* Gauss-Legendre rule on [0, 1] (6 points, for the mass properties): nodes and weights (sum 1). */
static const rugo_real gl6_x[6] = {0.03376524289842398609384922, 0.1693953067668677431693002,
                                   0.3806904069584015456847491,  0.6193095930415984543152509,
                                   0.8306046932331322568306998,  0.9662347571015760139061508};
static const rugo_real gl6_w[6] = {0.08566224618958517252014807, 0.1803807865240693037849168,
                                   0.2339569672863455236949352,  0.2339569672863455236949352,
                                   0.1803807865240693037849168,  0.08566224618958517252014807};

static double power_speed(const void* ctx, double t) {
    return rugo__v2_length(power_d1((const rugo_vec2*)ctx, t));
}

/* Segment j's length by rugo__arc_length (curve/internal.h), split where f' nearly vanishes: with
 * f'(t) = k1 + 2 k2 t + 3 k3 t^2. */
static void segment_arc(rugo_contour c, int segment, rugo_real rel_tol, rugo_real abs_tol, rugo__arc* arc) {
    rugo_vec2 k[4];
    segment_power_local(c, segment, k);
    double breaks[RUGO__ARC_MAX_BREAKS];
    const int nb = rugo__arc_speed_breaks(k[1], rugo_v2(2.0 * k[2].x, 2.0 * k[2].y),
                                          rugo_v2(3.0 * k[3].x, 3.0 * k[3].y), breaks);
    rugo__arc_length(power_speed, k, breaks, nb, rel_tol, abs_tol, arc);
}

rugo_real rugo_contour_segment_length(rugo_contour c, int segment) {
    if (c.points == NULL || c.count < 1) return 0.0;
    rugo__arc arc;
    segment_arc(c, segment, RUGO__ARC_REL_TOL, 0.0, &arc);
    return arc.length;
}

rugo_status rugo_contour_segment_length_adaptive(rugo_contour c, int segment, rugo_real tolerance,
                                                 rugo_real* length, rugo_real* error_bound) {
    if (length == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *length = 0.0;
    if (error_bound) *error_bound = 0.0;
    if (c.points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (c.count < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (!(tolerance > 0.0) || !isfinite(tolerance)) return RUGO_ERR_BAD_ARGUMENT;
    rugo__arc arc;
    segment_arc(c, segment, 0.0, tolerance, &arc);
    *length = arc.length;
    if (error_bound) *error_bound = arc.error;
    return arc.converged ? RUGO_OK : RUGO_ERR_NOT_CONVERGED;
}

rugo_real rugo_contour_perimeter(rugo_contour c) {
    if (c.points == NULL || c.count < 1) return 0.0;
    ksum s = {0.0, 0.0};
    for (int j = 0; j < c.count; ++j)
        ksum_add(&s, rugo_contour_segment_length(c, j));
    return ksum_value(&s);
}

/* ---------------------------------------------------------------------------------------------------
 * Mass properties by Green's theorem. With P = f - o and cr = P x P':
 *   A = 1/2 ∮ cr dt,   ∫∫ (p - o) dA = 1/3 ∮ P cr dt,   ∫∫ |p - o|^2 dA = 1/4 ∮ |P|^2 cr dt.
 * Per segment the integrands are polynomials of degree 5, 8 and 11 in t, so 6-point Gauss-Legendre
 * (exact to degree 11) gives them exactly up to round-off. All three are signed: a clockwise contour
 * gives negative area and inertia, and the centroid (a ratio) is right either way. */

typedef struct green_sums {
    rugo_real area;  /* ∫∫ dA */
    rugo_vec2 first; /* ∫∫ (p - o) dA */
    rugo_real polar; /* ∫∫ |p - o|^2 dA */
} green_sums;

static green_sums green_integrals(rugo_contour c, rugo_vec2 o) {
    ksum sa = {0.0, 0.0}, sx = {0.0, 0.0}, sy = {0.0, 0.0}, sj = {0.0, 0.0};
    for (int j = 0; j < c.count; ++j) {
        rugo_vec2 q[4], k[4];
        segment_points_rel(c, j, o, q);
        power_from_points(q, k);
        rugo_real a = 0.0, mx = 0.0, my = 0.0, jj = 0.0;
        for (int i = 0; i < 6; ++i) {
            rugo_vec2 p = power_point(k, gl6_x[i]);
            rugo_real cr = gl6_w[i] * rugo_v2_cross(p, power_d1(k, gl6_x[i]));
            a += cr;
            mx += p.x * cr;
            my += p.y * cr;
            jj += (p.x * p.x + p.y * p.y) * cr;
        }
        ksum_add(&sa, a);
        ksum_add(&sx, mx);
        ksum_add(&sy, my);
        ksum_add(&sj, jj);
    }
    green_sums g;
    g.area = 0.5 * ksum_value(&sa);
    g.first = rugo_v2(ksum_value(&sx) / 3.0, ksum_value(&sy) / 3.0);
    g.polar = 0.25 * ksum_value(&sj);
    return g;
}

rugo_mass_properties rugo_contour_mass_properties(rugo_contour c) {
    rugo_mass_properties m;
    m.area = 0.0;
    m.centroid = rugo_v2(0.0, 0.0);
    m.inertia = 0.0;
    if (c.points == NULL || c.count < 1) return m;
    /* First pass about the mean control point (inside or near the region) finds the centroid; the
     * second pass about the centroid itself gives the polar moment without the cancellation of the
     * parallel-axis shift, and a last correction to the centroid. */
    ksum sx = {0.0, 0.0}, sy = {0.0, 0.0};
    for (int i = 0; i < c.count; ++i) {
        ksum_add(&sx, c.points[i].x);
        ksum_add(&sy, c.points[i].y);
    }
    rugo_vec2 o = rugo_v2(ksum_value(&sx) / c.count, ksum_value(&sy) / c.count);
    green_sums g = green_integrals(c, o);
    if (!(g.area != 0.0) || !isfinite(g.area)) {
        /* No region (the contour would fail rugo_contour_check): keep the output finite. */
        m.area = g.area;
        m.centroid = o;
        m.inertia = g.polar;
        return m;
    }
    rugo_vec2 c1 = rugo_v2_add(o, rugo_v2_scale(1.0 / g.area, g.first));
    green_sums h = green_integrals(c, c1);
    rugo_vec2 shift = rugo_v2_scale(1.0 / h.area, h.first);
    m.area = h.area;
    m.centroid = rugo_v2_add(c1, shift);
    /* Parallel axes: J_c = J_c1 - A |c - c1|^2 (tiny: c1 is already the centroid to round-off). */
    m.inertia = h.polar - h.area * rugo_v2_dot(shift, shift);
    return m;
}

/* ---------------------------------------------------------------------------------------------------
 * Bounds. */

void rugo_contour_bounds(rugo_contour c, rugo_vec2* lower, rugo_vec2* upper) {
    rugo_vec2 lo = rugo_v2(0.0, 0.0), hi = lo;
    if (c.points != NULL && c.count >= 1) {
        /* Joints first: they settle most of the box, so the hull test below skips most segments. */
        lo = hi = rugo_contour_point(c, 0, 0.0);
        for (int j = 1; j < c.count; ++j) {
            rugo_vec2 p = rugo_contour_point(c, j, 0.0);
            lo = rugo_v2(fmin(lo.x, p.x), fmin(lo.y, p.y));
            hi = rugo_v2(fmax(hi.x, p.x), fmax(hi.y, p.y));
        }
        for (int j = 0; j < c.count; ++j) {
            rugo_vec2 b[4];
            rugo_contour_bezier(c, j, b);
            for (int axis = 0; axis < 2; ++axis) {
                rugo_real e[4];
                for (int i = 0; i < 4; ++i)
                    e[i] = axis == 0 ? b[i].x : b[i].y;
                rugo_real blo = axis == 0 ? lo.x : lo.y, bhi = axis == 0 ? hi.x : hi.y;
                int inside = 1;
                for (int i = 0; i < 4; ++i)
                    inside &= e[i] >= blo && e[i] <= bhi;
                if (inside) continue; /* the hull, hence the segment, is within the box already */
                rugo_vec2 v, w, r;
                rugo_contour_derivative_coefficients(c, j, &v, &w, &r);
                rugo_real a[3];
                a[0] = axis == 0 ? r.x : r.y;
                a[1] = axis == 0 ? w.x : w.y;
                a[2] = axis == 0 ? v.x : v.y;
                rugo_real roots[RUGO__POLY_MAX_ROOTS];
                int nr = rugo__poly_roots(a, 2, 0.0, 1.0, 0.0, roots);
                for (int i = 0; i < nr; ++i) {
                    rugo_vec2 p = rugo_contour_point(c, j, roots[i]);
                    lo = rugo_v2(fmin(lo.x, p.x), fmin(lo.y, p.y));
                    hi = rugo_v2(fmax(hi.x, p.x), fmax(hi.y, p.y));
                }
            }
        }
    }
    if (lower) *lower = lo;
    if (upper) *upper = hi;
}

/* ---------------------------------------------------------------------------------------------------
 * Closest point. */

/* Segment j's index among the candidates: all segments (segs == NULL) or segs[i] (increasing). */
static int candidate_segment(const int* segs, int i) { return segs == NULL ? i : segs[i]; }

rugo_curve_point rugo__contour_closest_among(rugo_contour c, rugo_vec2 p, const int* segs, int count) {
    rugo_curve_point res;
    res.segment = 0;
    res.t = 0.0;
    res.point = p;
    res.distance = HUGE_VAL;
    if (c.points == NULL || c.count < 1 || count < 1) return res;
    /* Work relative to p. The joints give an upper bound quickly; then a segment is solved only if
     * its Bezier hull's box could hold a closer point. */
    rugo_real best = HUGE_VAL, best_t = 0.0;
    int best_j = 0;
    for (int i = 0; i < count; ++i) {
        const int j = candidate_segment(segs, i);
        rugo_vec2 q[4], k[4];
        segment_points_rel(c, j, p, q);
        power_from_points(q, k);
        rugo_real d2 = rugo_v2_dot(k[0], k[0]);
        if (d2 < best) {
            best = d2;
            best_j = j;
        }
    }
    for (int i = 0; i < count; ++i) {
        const int j = candidate_segment(segs, i);
        rugo_vec2 q[4], b[4], k[4];
        segment_points_rel(c, j, p, q);
        bezier_from_points(q, b);
        rugo_real x0 = fmin(fmin(b[0].x, b[1].x), fmin(b[2].x, b[3].x));
        rugo_real x1 = fmax(fmax(b[0].x, b[1].x), fmax(b[2].x, b[3].x));
        rugo_real y0 = fmin(fmin(b[0].y, b[1].y), fmin(b[2].y, b[3].y));
        rugo_real y1 = fmax(fmax(b[0].y, b[1].y), fmax(b[2].y, b[3].y));
        rugo_real dx = x0 > 0.0 ? x0 : (x1 < 0.0 ? -x1 : 0.0);
        rugo_real dy = y0 > 0.0 ? y0 : (y1 < 0.0 ? -y1 : 0.0);
        if (dx * dx + dy * dy >= best) continue;
        power_from_points(q, k);
        /* d/dt |f - p|^2 / 2 = (f - p)·f', with f - p = A t^3 + B t^2 + C t + D. */
        rugo_vec2 D = k[0], C = k[1], B = k[2], A = k[3];
        rugo_real g[6];
        g[0] = rugo_v2_dot(C, D);
        g[1] = 2.0 * rugo_v2_dot(B, D) + rugo_v2_dot(C, C);
        g[2] = 3.0 * (rugo_v2_dot(A, D) + rugo_v2_dot(B, C));
        g[3] = 4.0 * rugo_v2_dot(A, C) + 2.0 * rugo_v2_dot(B, B);
        g[4] = 5.0 * rugo_v2_dot(A, B);
        g[5] = 3.0 * rugo_v2_dot(A, A);
        rugo_real roots[RUGO__POLY_MAX_ROOTS];
        int nr = rugo__poly_roots(g, 5, 0.0, 1.0, 0.0, roots);
        for (int r = 0; r < nr; ++r) {
            if (!(roots[r] < 1.0)) continue; /* t = 1 is the next segment's start, seen as a joint */
            rugo_vec2 f = power_point(k, roots[r]);
            rugo_real d2 = rugo_v2_dot(f, f);
            if (d2 < best) {
                best = d2;
                best_j = j;
                best_t = roots[r];
            }
        }
    }
    res.segment = best_j;
    res.t = best_t;
    res.point = rugo_contour_point(c, best_j, best_t);
    res.distance = sqrt(best);
    return res;
}

rugo_curve_point rugo_contour_closest_point(rugo_contour c, rugo_vec2 p) {
    return rugo__contour_closest_among(c, p, NULL, c.count);
}

/* ---------------------------------------------------------------------------------------------------
 * Containment: winding number of the curve around p, counted on the ray from p towards +x.
 *
 * Each point of the curve is "up" (y >= p.y) or "down". Walking the curve, the winding number is the
 * signed count of down->up (+1) and up->down (-1) changes that happen right of p. Per segment the
 * state at its two joints is taken from the Bezier end points, which neighbouring segments share
 * bitwise, and the states in between from the sign of y(t) - p.y between its roots. So the changes
 * telescope around the closed curve whatever round-off does inside a segment: a tangency, a ray
 * through a joint or a horizontal piece on the ray yields canceling pairs of changes, never a lone
 * one. Only the x of a change (left or right of p) can be affected by round-off, which matters only
 * when p is within round-off of the curve.
 *
 * The count is a sum over segments of rugo__contour_winding_segment (curve/internal.h), so a caller
 * with a bounding-box tree may skip segments whose count is certainly 0 and get the same sum
 * (shape/point_query.c). */

int rugo__contour_winding_segment(rugo_contour c, int j, rugo_vec2 p) {
    rugo_vec2 q[4], b[4], k[4];
    segment_points_rel(c, j, p, q);
    bezier_from_points(q, b);
    int all_up = 1, all_down = 1, all_left = 1;
    for (int i = 0; i < 4; ++i) {
        all_up &= b[i].y > 0.0;
        all_down &= b[i].y < 0.0;
        all_left &= b[i].x < 0.0;
    }
    /* Hull strictly on one side of the ray's line: both joints agree, no change. Hull left of p:
     * every change happens left of p. */
    if (all_up || all_down || all_left) return 0;
    power_from_points(q, k);
    rugo_real a[4] = {k[0].y, k[1].y, k[2].y, k[3].y};
    rugo_real roots[RUGO__POLY_MAX_ROOTS];
    int nr = rugo__poly_roots(a, 3, 0.0, 1.0, 0.0, roots);
    rugo_real brk[RUGO__POLY_MAX_ROOTS + 2];
    int nb = 0;
    brk[nb++] = 0.0;
    for (int i = 0; i < nr; ++i)
        if (roots[i] > 0.0 && roots[i] < 1.0) brk[nb++] = roots[i];
    brk[nb++] = 1.0;
    int winding = 0;
    int state = b[0].y >= 0.0;
    for (int i = 0; i + 1 < nb; ++i) {
        rugo_real mid = 0.5 * (brk[i] + brk[i + 1]);
        int s = rugo__poly_eval(a, 3, mid) >= 0.0;
        if (s != state) {
            rugo_real x = i == 0 ? b[0].x : power_point(k, brk[i]).x;
            if (x > 0.0) winding += s - state;
            state = s;
        }
    }
    int s_end = b[3].y >= 0.0;
    if (s_end != state && b[3].x > 0.0) winding += s_end - state;
    return winding;
}

bool rugo_contour_contains(rugo_contour c, rugo_vec2 p) {
    if (c.points == NULL || c.count < 1) return false;
    int winding = 0;
    for (int j = 0; j < c.count; ++j)
        winding += rugo__contour_winding_segment(c, j, p);
    return winding != 0;
}

/* ---------------------------------------------------------------------------------------------------
 * Ray cast. */

#define RAY_JOINT_SLACK 1e-12

bool rugo__ray_begin(rugo__ray* r, rugo_vec2 origin, rugo_vec2 direction, rugo_real max_fraction) {
    r->origin = origin;
    r->d = direction;
    r->dd = rugo_v2_dot(direction, direction);
    r->dmax = fmax(fabs(direction.x), fabs(direction.y));
    r->max_fraction = max_fraction;
    r->found = false;
    r->best_j = 0;
    r->best_s = max_fraction;
    r->best_t = 0.0;
    return r->dd > 0.0 && isfinite(r->dd) && max_fraction >= 0.0;
}

/* Inlined into the loop of rugo_contour_ray_cast: most segments are pruned after a few operations,
 * so a call and the state in memory for each would cost about a tenth of a ray cast. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void
ray_segment(rugo__ray* r, rugo_contour c, int j) {
    const rugo_vec2 origin = r->origin, d = r->d;
    const rugo_real dd = r->dd, dmax = r->dmax, max_fraction = r->max_fraction;
    rugo_vec2 q[4], b[4], k[4];
    segment_points_rel(c, j, origin, q);
    bezier_from_points(q, b);
    /* Prune: hull strictly on one side of the ray's line, behind the origin, or beyond the
     * best hit so far (s * |d|^2 = (f - origin)·d). */
    int pos = 0, neg = 0, behind = 0, beyond = 0;
    rugo_real smax = r->best_s * dd;
    for (int i = 0; i < 4; ++i) {
        rugo_real h = rugo_v2_cross(d, b[i]), s = rugo_v2_dot(b[i], d);
        pos += h > 0.0;
        neg += h < 0.0;
        behind += s < 0.0;
        beyond += s > smax;
    }
    if (pos == 4 || neg == 4 || behind == 4 || beyond == 4) return;
    power_from_points(q, k);
    rugo_real h[4], sp[4];
    for (int i = 0; i < 4; ++i) {
        h[i] = rugo_v2_cross(d, k[i]);
        sp[i] = rugo_v2_dot(k[i], d);
    }
    /* Values of d x (f - origin) are uncertain by round-off of the products and of the shifted
     * coefficients; that tolerance lets a ray grazing the curve (a double root) hit, and makes
     * a straight segment lying on the ray's line report "every t". */
    rugo_real kmax = 0.0;
    for (int i = 0; i < 4; ++i)
        kmax = fmax(kmax, fmax(fabs(k[i].x), fabs(k[i].y)));
    rugo_real tol = 32.0 * DBL_EPSILON * dmax * kmax;
    rugo_real cand[2 * RUGO__POLY_MAX_ROOTS + 2];
    int nc = 0;
    rugo_real roots[RUGO__POLY_MAX_ROOTS];
    /* A crossing at a joint can land a hair outside [0, 1] in both segments that share it; the
     * slightly widened interval catches it. Outside [0, 1] the polynomial continues the
     * neighbouring segment to O(t^3) (the curve is C2), so s is still evaluated exactly there;
     * only the reported parameter is clamped. */
    int nr = rugo__poly_roots(h, 3, -RAY_JOINT_SLACK, 1.0 + RAY_JOINT_SLACK, tol, roots);
    if (nr == RUGO__POLY_ALL) {
        /* The segment lies on the ray's line: the first point with s >= 0 is an end, a point
         * where s = 0 (the origin), or a turning point of s. */
        cand[nc++] = 0.0;
        cand[nc++] = 1.0;
        nr = rugo__poly_roots(sp, 3, 0.0, 1.0, 0.0, roots);
        for (int i = 0; i < nr; ++i)
            cand[nc++] = roots[i];
        rugo_real ds[3] = {sp[1], 2.0 * sp[2], 3.0 * sp[3]};
        nr = rugo__poly_roots(ds, 2, 0.0, 1.0, 0.0, roots);
        for (int i = 0; i < nr; ++i)
            cand[nc++] = roots[i];
    } else {
        for (int i = 0; i < nr; ++i)
            cand[nc++] = roots[i];
    }
    /* An origin on the curve (within round-off) hits at s = 0 rather than at -1e-17 or never. */
    rugo_real s_slack = 32.0 * DBL_EPSILON * kmax / sqrt(dd);
    for (int i = 0; i < nc; ++i) {
        rugo_real s = rugo_v2_dot(power_point(k, cand[i]), d) / dd;
        if (s < 0.0 && s >= -s_slack) s = 0.0;
        if (s >= 0.0 && s <= max_fraction && (!r->found || s < r->best_s)) {
            r->found = true;
            r->best_s = s;
            r->best_j = j;
            r->best_t = fmin(1.0, fmax(0.0, cand[i]));
        }
    }
}

void rugo__ray_segment(rugo__ray* r, rugo_contour c, int j) { ray_segment(r, c, j); }

bool rugo__ray_finish(const rugo__ray* r, rugo_contour c, rugo_real* fraction, rugo_curve_point* hit,
                      rugo_vec2* normal) {
    if (!r->found) return false;
    int best_j = r->best_j;
    rugo_real best_t = r->best_t;
    if (best_t >= 1.0) { /* t = 1 belongs to the next segment */
        best_j = rugo__wrap(best_j + 1, c.count);
        best_t = 0.0;
    }
    if (fraction) *fraction = r->best_s;
    if (hit) {
        hit->segment = best_j;
        hit->t = best_t;
        hit->point = rugo_contour_point(c, best_j, best_t);
        hit->distance = r->best_s * sqrt(r->dd);
    }
    if (normal) *normal = rugo_contour_normal(c, best_j, best_t);
    return true;
}

bool rugo_contour_ray_cast(rugo_contour c, rugo_vec2 origin, rugo_vec2 direction, rugo_real max_fraction,
                           rugo_real* fraction, rugo_curve_point* hit, rugo_vec2* normal) {
    rugo__ray r;
    if (c.points == NULL || c.count < 1 || !rugo__ray_begin(&r, origin, direction, max_fraction))
        return false;
    for (int j = 0; j < c.count; ++j)
        ray_segment(&r, c, j);
    return rugo__ray_finish(&r, c, fraction, hit, normal);
}
