/* Geometry of the curves that every stage of a query asks: outward normals (also at zero-speed
 * corners, where the derivative says nothing), the normal cones of such corners, whether a direction
 * leaves a curve on its outward side, and the cone of tangent directions of a Bezier piece. Separate
 * because shapes, primitives and the overlaps below the resolution all decide sides with it. */
#include "query/collide_internal.h"

/* The cone of tangent directions of a Bezier piece: the hodograph's control points span it. */
void rugo__tangent_cone(const rugo_vec2 b[4], rugo_vec2* centre, rugo_real* half) {
    rugo_vec2 u[3], d[3];
    rugo_real len[3];
    int m = 0;
    rugo_real size = 0.0;
    /* each length once */
    for (int i = 0; i < 3; ++i) {
        d[i] = rugo_v2_sub(b[i + 1], b[i]);
        len[i] = rugo__v2_length(d[i]);
        size = fmax(size, len[i]);
    }
    rugo_vec2 sum = rugo_v2(0.0, 0.0);
    for (int i = 0; i < 3; ++i) {
        if (len[i] > 1e-9 * size) {
            u[m] = rugo__v2_unit_len(d[i], len[i]);
            sum = rugo_v2_add(sum, u[m]);
            ++m;
        }
    }
    *centre = rugo_v2(1.0, 0.0);
    *half = 4.0; /* > pi: no information */
    const rugo_real ls = rugo__v2_length(sum);
    if (m == 0 || ls < 1e-6) return;
    *centre = rugo__v2_unit_len(sum, ls);
    rugo_real h = 0.0;
    for (int i = 0; i < m; ++i) {
        rugo_real c = rugo_v2_dot(*centre, u[i]);
        c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
        h = fmax(h, acos(c));
    }
    *half = h;
}

/* Size of the curve around segment seg (its control points and a few neighbours): chords shorter
 * than a tiny fraction of it are round-off, not directions. */
static rugo_real local_extent(rugo_contour c, int seg) {
    const rugo_vec2 o = c.points[rugo__wrap(seg, c.count)];
    rugo_real e = 0.0;
    for (int i = seg - 4; i <= seg + 5; ++i)
        e = fmax(e, rugo__v2_length(rugo_v2_sub(c.points[rugo__wrap(i, c.count)], o)));
    return e;
}

/* Whether len > 1e-9 (|v| + |w| + |r|) (the lengths as rugo__v2_length computes them), without the
 * three lengths when an upper bound of their sum already decides it: |a| <= |a.x| + |a.y|, so the sum
 * of the lengths is at most the sum of the absolute coordinates (padded against its rounding), and len
 * above 1e-9 times that is above 1e-9 times the sum. Otherwise the lengths decide. */
static int speed_regular(rugo_real len, rugo_vec2 v, rugo_vec2 w, rugo_vec2 r) {
    const rugo_real l1 = (fabs(v.x) + fabs(v.y)) + (fabs(w.x) + fabs(w.y)) + (fabs(r.x) + fabs(r.y));
    if (len > 1e-9 * (l1 * (1.0 + 1e-9))) return 1;
    return len > 1e-9 * (rugo__v2_length(v) + rugo__v2_length(w) + rugo__v2_length(r));
}

/* At a regular point of the curve (speed not vanishing against the segment's size), 1 and the
 * outward normal of the derivative in *n; 0 (n untouched) at a zero-speed point. */
static int regular_normal(rugo_contour c, int seg, rugo_real t, rugo_vec2* n) {
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, seg, &v, &w, &r);
    const rugo_vec2 d = rugo__first_derivative(v, w, r, t);
    const rugo_real len = rugo__v2_length(d);
    if (!(speed_regular(len, v, w, r) && len > 0.0)) return 0;
    *n = rugo_v2(d.y / len, -d.x / len);
    return 1;
}

/* Outward normal of a counter-clockwise curve at (seg, t). Where the speed vanishes (coincident
 * control points: a sharp corner, or a segment shrunk to a point) the normal is that of a chord
 * across the spot, i.e. the middle of the corner's normal cone. */
rugo_vec2 rugo__curve_normal(rugo_contour c, int seg, rugo_real t) {
    rugo_vec2 nr;
    if (regular_normal(c, seg, t, &nr)) return nr;
    const rugo_real u = (rugo_real)rugo__wrap(seg, c.count) + t, tiny = 1e-8 * local_extent(c, seg);
    for (rugo_real h = 1e-4; h < (rugo_real)c.count; h *= 2.0) {
        const rugo_vec2 p1 = rugo_contour_point_at(c, u + h);
        const rugo_vec2 p0 = rugo_contour_point_at(c, u - h + (rugo_real)c.count);
        const rugo_vec2 ch = rugo_v2_sub(p1, p0);
        const rugo_real l = rugo__v2_length(ch);
        if (l > tiny && l > 0.0) return rugo_v2(ch.y / l, -ch.x / l);
    }
    return rugo_contour_normal(c, seg, t);
}

/* At a zero-speed point of the curve (a sharp corner made by coincident control points), the normals
 * of the curve just before and just after it (one-sided chords); 0 at a regular point. */
int rugo__corner_normals(rugo_contour c, int seg, rugo_real t, rugo_vec2* n_in, rugo_vec2* n_out) {
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, seg, &v, &w, &r);
    const rugo_vec2 d = rugo__first_derivative(v, w, r, t);
    const rugo_real scale = rugo__v2_length(v) + rugo__v2_length(w) + rugo__v2_length(r);
    if (rugo__v2_length(d) > 1e-9 * scale && rugo__v2_length(d) > 0.0) return 0;
    const rugo_real u = (rugo_real)rugo__wrap(seg, c.count) + t, n = (rugo_real)c.count;
    const rugo_vec2 p = rugo_contour_point_at(c, u);
    const rugo_real tiny = 1e-8 * local_extent(c, seg);
    int got = 0;
    /* Chords long enough to be directions (1e-8 of the local size) yet short: the flank's tangent
     * to ~1e-4 where the corner's neighbours are cubic ramps. */
    for (int side = 0; side < 2; ++side)
        for (rugo_real h = 1e-4; h < n; h *= 2.0) {
            const rugo_vec2 q = rugo_contour_point_at(c, side ? u + h : u - h + n);
            const rugo_vec2 ch = side ? rugo_v2_sub(q, p) : rugo_v2_sub(p, q);
            const rugo_real l = rugo__v2_length(ch);
            if (l > tiny && l > 0.0) {
                *(side ? n_out : n_in) = rugo_v2(ch.y / l, -ch.x / l);
                ++got;
                break;
            }
        }
    return got == 2;
}

/* Does direction d (from the curve's point toward the other body) leave the curve on its outward
 * side? At a regular point: d·n >= 0. At a corner: d must lie in the corner's normal cone (a local
 * minimum of the distance cannot sit at a corner otherwise: one of its flanks comes closer); a reflex
 * corner has no such direction. rot turns the curve's frame into the query's. */
int rugo__faces_outward(rugo_contour c, int seg, rugo_real t, rugo_vec2 d, rugo_rot rot) {
    rugo_vec2 a, b;
    /* A regular point (the usual case): rugo__corner_normals would return 0 and rugo__curve_normal
     * this normal. */
    if (regular_normal(c, seg, t, &a)) return rugo_v2_dot(rugo_rotate(rot, a), d) >= 0.0;
    if (!rugo__corner_normals(c, seg, t, &a, &b))
        return rugo_v2_dot(rugo_rotate(rot, rugo__curve_normal(c, seg, t)), d) >= 0.0;
    a = rugo_rotate(rot, a);
    b = rugo_rotate(rot, b);
    const rugo_real turn = rugo_v2_cross(a, b), tol = 1e-9 * rugo__v2_length(d);
    if (turn < -1e-12) return 0;                                                    /* reflex */
    if (turn <= 1e-12) return rugo_v2_dot(a, d) >= 0.0 && rugo_v2_dot(b, d) >= 0.0; /* no turn */
    return rugo_v2_cross(a, d) >= -tol && rugo_v2_cross(d, b) >= -tol;
}

/* A sharp corner (zero-speed joint) of curve c at one of segment seg's two joints, within `near` of x
 * (c's frame): 1 and the corner's chord normal in *n. */
int rugo__corner_near(rugo_contour c, int seg, rugo_vec2 x, rugo_real near, rugo_vec2* n) {
    for (int j = 0; j < 2; ++j) {
        const int k = rugo__wrap(seg + j, c.count);
        rugo_vec2 nin, nout;
        if (!rugo__corner_normals(c, k, 0.0, &nin, &nout)) continue;
        if (rugo__v2_length(rugo_v2_sub(rugo_contour_point(c, k, 0.0), x)) > near) continue;
        *n = rugo__curve_normal(c, k, 0.0);
        return 1;
    }
    return 0;
}
