/* Overlaps below the resolution: where two boundaries overlap too shallowly for the crossings to
 * close a region (entry and exit within round-off of each other), or a penetration pair's points are
 * too close to give a direction, the normal comes from the two curves' normals and corners instead,
 * and the crossings still get contacts. Separate because shape pairs and primitives reach these cases
 * from several stages. */
#include "query/collide_internal.h"

/* Curvature |f' x f''| / |f'|^3 of curve c at (seg, t); infinite where the speed vanishes. */
static rugo_real curvature_at(rugo_contour c, int seg, rugo_real t) {
    rugo_vec2 v, w, r;
    rugo_contour_derivative_coefficients(c, seg, &v, &w, &r);
    const rugo_vec2 d1 = rugo__first_derivative(v, w, r, t);
    const rugo_vec2 d2 = rugo_v2(0.5 * (2.0 * v.x * t + w.x), 0.5 * (2.0 * v.y * t + w.y));
    const rugo_real l = rugo__v2_length(d1);
    return l > 0.0 ? fabs(rugo_v2_cross(d1, d2)) / (l * l * l) : HUGE_VAL;
}

/* The normal (from A to B) that takes apart an overlap too shallow to be resolved, at pa on A
 * (segment sa) and pb on B (segment sb at tb, or a primitive P's boundary), A's frame. At a sharp
 * corner of one curve the overlap is the corner poking through the other's face, and a point found on
 * the corner's flank has the flank's normal, up to 90 degrees off (at a triangle's corner, one pointing
 * into A): the other curve's normal decides. At corners of both, their chord normals; elsewhere the
 * mean of A's outward and B's inward normals, or, where those point the same way (one curve turns back
 * on itself, as a coarse level of a point-like corner does), the flatter curve's. */
rugo_vec2 rugo__overlap_normal(const query_side* A, const shape_pair* g, const primitive* P, int sa,
                               rugo_real ta, rugo_vec2 pa, int sb, rugo_real tb, rugo_vec2 pb,
                               rugo_real scale) {
    const rugo_real near = OVERLAP_NEAR * scale;
    const rugo_vec2 na = rugo__curve_normal(A->curve, sa, ta);
    rugo_vec2 nb, ca = na, cb = rugo_v2_scale(-1.0, na);
    const int corner_a = rugo__corner_near(A->curve, sa, pa, near, &ca);
    int corner_b = 0;
    if (P == NULL) {
        nb = rugo_rotate(g->rel.q, rugo__curve_normal(g->B->curve, sb, tb));
        corner_b = rugo__corner_near(g->B->curve, sb, rugo_inv_transform_point(g->rel, pb), near, &cb);
        if (corner_b) cb = rugo_rotate(g->rel.q, cb);
    } else {
        nb = rugo__primitive_normal_at(P, pb);
        /* an edge faces both ways: the way A comes from (its corner's middle normal, at a corner) */
        if (P->V == 2 && P->R == 0.0 && rugo_v2_dot(nb, ca) > 0.0) nb = rugo_v2_scale(-1.0, nb);
        for (int v = 0; P->V >= 2 && P->R == 0.0 && v < P->V && !corner_b; ++v)
            corner_b = rugo__v2_length(rugo_v2_sub(P->v[v], pb)) <= near;
        if (corner_b) cb = rugo_v2_scale(-1.0, ca); /* a vertex has no normal of its own: A's decides */
    }
    rugo_vec2 n;
    if (corner_a && !corner_b)
        n = rugo_v2_scale(-1.0, nb);
    else if (corner_b && !corner_a)
        n = na;
    else if (corner_a && corner_b)
        n = rugo_v2_sub(ca, cb);
    else if (rugo_v2_dot(na, nb) <= 0.0) /* facing each other, as at a touching */
        n = rugo_v2_sub(na, nb);
    else /* one of them turns back on itself there (a coarse level's curl): the flatter curve decides */
        n = P != NULL || curvature_at(g->B->curve, sb, tb) <= curvature_at(A->curve, sa, ta)
                ? rugo_v2_scale(-1.0, nb)
                : na;
    return rugo__v2_length(n) > 0.0 ? rugo__v2_unit(n) : na;
}

/* Crossings that closed no region: an overlap below the resolution of its crossings (entry and exit
 * within SAME_POINT of the size of each other, merged, or one of them taken for a touching), so that
 * no arc between them is seen inside. The curves do cross, the state is INTERSECTING, and the caller
 * must get a contact: one per cluster of such crossings (within OVERLAP_NEAR of each other), at the
 * curves' common point (separation 0 to round-off: the overlap is shallower than the resolution), with
 * the normal of rugo__overlap_normal. Id index 2 + cluster. */
rugo_status rugo__emit_unresolved_crossings(contact_out* o, const shape_pair* g, const primitive* P,
                                            const hit* x, int m, rugo_real scale, int first_region) {
    const rugo_real near = OVERLAP_NEAR * scale;
    int cluster = 0;
    for (int i = 0; i < m; ++i) {
        int seen = 0;
        for (int j = 0; j < i && !seen; ++j)
            seen = rugo__v2_length(rugo_v2_sub(x[j].pa, x[i].pa)) <= near;
        if (seen) continue;
        const rugo_vec2 n =
            rugo__overlap_normal(o->A, g, P, x[i].sa, x[i].ta, x[i].pa, x[i].sb, x[i].tb, x[i].pb, scale);
        const int id_b = P != NULL ? (0xFFF00 | (x[i].sb & 0xFF)) : x[i].sb;
        const int sb = P != NULL ? -1 : x[i].sb;
        const rugo_real tb = P != NULL ? 0.0 : x[i].tb;
        if (!rugo__emit_contact(o, x[i].sa, x[i].ta, sb, tb, x[i].pa, x[i].pb, n, first_region + cluster, 1,
                                2 + cluster, id_b))
            return RUGO_ERR_OUT_OF_MEMORY;
        ++cluster;
    }
    return RUGO_OK;
}
