/* The boundary of a primitive B (a convex core — a point, a segment or a polygon — grown by a radius R):
 * set up in A's frame, walked by one parameter (vertex arcs and offset edges in turn), with signed
 * distances, normals, normal cones at corners and support points. Separate because the primitive's
 * narrow phase, its plan and the overlaps below the resolution all measure against this boundary. */
#include "query/collide_internal.h"

#include <float.h>

/* Distance from p to the segment ab, and the nearest point of it. */
static rugo_real point_segment(rugo_vec2 p, rugo_vec2 a, rugo_vec2 b, rugo_vec2* foot) {
    rugo_vec2 d = rugo_v2_sub(b, a);
    const rugo_real dd = rugo_v2_dot(d, d);
    rugo_real t = dd > 0.0 ? rugo_v2_dot(rugo_v2_sub(p, a), d) / dd : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    *foot = rugo__lerp2(a, b, t);
    return rugo__v2_length(rugo_v2_sub(p, *foot));
}

/* Signed distance to B (negative inside); optionally the nearest boundary point and its normal. */
rugo_real rugo__primitive_signed_distance(const primitive* P, rugo_vec2 p, rugo_vec2* q, rugo_vec2* nq) {
    rugo_vec2 foot = P->v[0];
    rugo_real dk;
    if (P->V == 1) {
        dk = rugo__v2_length(rugo_v2_sub(p, foot));
    } else if (P->V == 2) {
        dk = point_segment(p, P->v[0], P->v[1], &foot);
    } else {
        rugo_real s = -HUGE_VAL;
        int e = 0;
        for (int i = 0; i < P->V; ++i) {
            const rugo_real si = rugo_v2_dot(P->m[i], rugo_v2_sub(p, P->v[i]));
            if (si > s) {
                s = si;
                e = i;
            }
        }
        if (s <= 0.0) { /* inside the core: the nearest edge */
            if (q != NULL) *q = rugo_v2_add(p, rugo_v2_scale(P->R - s, P->m[e]));
            if (nq != NULL) *nq = P->m[e];
            return s - P->R;
        }
        dk = HUGE_VAL;
        for (int i = 0; i < P->V; ++i) {
            rugo_vec2 f;
            const rugo_real d = point_segment(p, P->v[i], P->v[(i + 1) % P->V], &f);
            if (d < dk) {
                dk = d;
                foot = f;
            }
        }
    }
    if (q != NULL || nq != NULL) {
        rugo_vec2 u = dk > 0.0 ? rugo_v2_scale(1.0 / dk, rugo_v2_sub(p, foot)) : rugo_v2(1.0, 0.0);
        if (q != NULL) *q = rugo_v2_add(foot, rugo_v2_scale(P->R, u));
        if (nq != NULL) *nq = u;
    }
    return dk - P->R;
}

/* The direction u as an angle in [0, 2 pi). */
static rugo_real angle_of(rugo_vec2 u) {
    rugo_real a = atan2(u.y, u.x);
    return a < 0.0 ? a + 2.0 * PI_VALUE : a;
}

/* P given in world coordinates into A's frame (xa): its vertices moved, then the edges' outward
 * normals, the vertex arcs between them, the boundary parameter's period and the bounds derived there. */
void rugo__primitive_into_frame(primitive* P, rugo_transform xa) {
    for (int i = 0; i < P->V; ++i)
        P->v[i] = rugo_inv_transform_point(xa, P->v[i]);
    if (P->V >= 2) {
        for (int i = 0; i < P->V; ++i) {
            const rugo_vec2 d = rugo_v2_sub(P->v[(i + 1) % P->V], P->v[i]);
            P->m[i] = rugo__v2_unit(rugo_v2(d.y, -d.x));
        }
        for (int i = 0; i < P->V; ++i) {
            const rugo_vec2 a0 = P->m[rugo__wrap(i - 1, P->V)], a1 = P->m[i];
            P->arc0[i] = angle_of(a0);
            rugo_real sp = angle_of(a1) - P->arc0[i];
            while (sp < 0.0)
                sp += 2.0 * PI_VALUE;
            if (sp >= 2.0 * PI_VALUE - 1e-15) sp = 0.0;
            P->span[i] = sp;
        }
        P->period = 2.0 * (rugo_real)P->V;
    } else {
        P->period = 1.0;
    }
    P->lo = P->hi = P->v[0];
    for (int i = 1; i < P->V; ++i) {
        P->lo = rugo_v2(fmin(P->lo.x, P->v[i].x), fmin(P->lo.y, P->v[i].y));
        P->hi = rugo_v2(fmax(P->hi.x, P->v[i].x), fmax(P->hi.y, P->v[i].y));
    }
    P->lo = rugo_v2(P->lo.x - P->R, P->lo.y - P->R);
    P->hi = rugo_v2(P->hi.x + P->R, P->hi.y + P->R);
}

/* Boundary parameter of the point of vertex arc i in direction u, or -1 if u is outside the arc. */
rugo_real rugo__primitive_arc_param(const primitive* P, int i, rugo_vec2 u) {
    if (P->V == 1) return rugo__wrap_param(angle_of(u) / (2.0 * PI_VALUE), 1.0);
    rugo_real th = angle_of(u) - P->arc0[i];
    while (th < 0.0)
        th += 2.0 * PI_VALUE;
    while (th >= 2.0 * PI_VALUE)
        th -= 2.0 * PI_VALUE;
    if (th > P->span[i] + 1e-12) {
        if (th > 2.0 * PI_VALUE - 1e-12) return 2.0 * (rugo_real)i; /* just before the arc's start */
        return -1.0;
    }
    return 2.0 * (rugo_real)i + (P->span[i] > 0.0 ? fmin(th / P->span[i], 1.0 - DBL_EPSILON) : 0.0);
}

/* Is direction u within the normal cone of corner i (between m_{i-1} and m_i)? */
static int in_cone(const primitive* P, int i, rugo_vec2 u) {
    if (P->V == 1) return 1;
    const rugo_vec2 a = P->m[rugo__wrap(i - 1, P->V)], b = P->m[i];
    return rugo_v2_cross(a, u) >= -1e-9 && rugo_v2_cross(u, b) >= -1e-9;
}

rugo_vec2 rugo__primitive_point(const primitive* P, rugo_real w) {
    if (P->V == 1) {
        const rugo_real th = 2.0 * PI_VALUE * w;
        return rugo_v2(P->v[0].x + P->R * cos(th), P->v[0].y + P->R * sin(th));
    }
    const int f = (int)floor(w);
    const rugo_real t = w - floor(w);
    const int i = rugo__wrap(f / 2, P->V);
    if (f % 2 == 1) {
        const rugo_vec2 off = rugo_v2_scale(P->R, P->m[i]);
        return rugo__lerp2(rugo_v2_add(P->v[i], off), rugo_v2_add(P->v[(i + 1) % P->V], off), t);
    }
    const rugo_real th = P->arc0[i] + t * P->span[i];
    return rugo_v2(P->v[i].x + P->R * cos(th), P->v[i].y + P->R * sin(th));
}

rugo_vec2 rugo__primitive_support(const primitive* P, rugo_vec2 dir) { /* point of B maximising p·dir */
    int best = 0;
    for (int i = 1; i < P->V; ++i)
        if (rugo_v2_dot(P->v[i], dir) > rugo_v2_dot(P->v[best], dir)) best = i;
    return rugo_v2_add(P->v[best], rugo_v2_scale(P->R, dir));
}

/* Outward normal of a primitive's boundary at (or next to) p: the direction from the core on the
 * rounded skin, else the nearest edge's normal (an edge, R = 0, faces both ways: the caller orients). */
rugo_vec2 rugo__primitive_normal_at(const primitive* P, rugo_vec2 p) {
    if (P->V == 1) {
        const rugo_vec2 d = rugo_v2_sub(p, P->v[0]);
        return rugo__v2_length(d) > 0.0 ? rugo__v2_unit(d) : rugo_v2(1.0, 0.0);
    }
    const int edges = P->V == 2 ? 1 : P->V;
    rugo_real dk = HUGE_VAL;
    rugo_vec2 foot = P->v[0];
    int e = 0;
    for (int i = 0; i < edges; ++i) {
        rugo_vec2 f;
        const rugo_real d = point_segment(p, P->v[i], P->v[(i + 1) % P->V], &f);
        if (d < dk) {
            dk = d;
            foot = f;
            e = i;
        }
    }
    if (P->R > 0.0 && dk > 0.5 * P->R) return rugo__v2_unit(rugo_v2_sub(p, foot));
    return P->m[e];
}

/* B's side of a pair: is n (from A to B) compatible with B's outward normal at pb? */
int rugo__primitive_normal_fits(const primitive* P, const hit* h, rugo_vec2 n) {
    if (h->vertex >= 0) return in_cone(P, h->vertex, rugo_v2_scale(-1.0, n));
    if (P->V == 2 && P->R == 0.0) return 1; /* an edge faces both ways */
    return rugo_v2_dot(h->nb, n) < 0.0;
}
