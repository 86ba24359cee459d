/* The bounds the narrow phase's searches prune with. On a box of the parameter square the Bernstein
 * (Bezier) coefficients of the sub-pieces bound what the pieces can do there: the gap between their
 * convex hulls (projections on a few directions), the sign of cross(f', g') over the hodographs'
 * control points (the tangent cones), whether a hodograph keeps away from zero; and Krawczyk's
 * interval Newton operator bounds where a root of a 2 x 2 system can lie. Separate because both
 * searches, the crossings' and the stationary pairs', prune with them, and each is a certificate: it
 * drops a box only when the box provably holds no root. */
#include "query/narrow_internal.h"

/* Unit normal of the chord of a control polygon (or of its middle leg for a closed loop), or 0. */
static rugo_vec2 chord_normal(const rugo_vec2* p) {
    rugo_vec2 d = rugo_v2_sub(p[3], p[0]);
    rugo_real l = rugo__v2_norm(d);
    if (!(l > 0.25 * rugo__polygon_diameter(p, 3)) || !(l > 0.0)) {
        d = rugo_v2_sub(p[2], p[1]);
        l = rugo__v2_norm(d);
        if (!(l > 0.0)) return rugo_v2(0.0, 0.0);
    }
    return rugo_v2(-d.y / l, d.x / l);
}

/* The gap between the projections of F and G (4 points each) on direction d. */
static rugo_real projection_gap(rugo_vec2 d, const rugo_vec2 F[4], const rugo_vec2 G[4]) {
    rugo_real flo = INFINITY, fhi = -INFINITY, glo = INFINITY, ghi = -INFINITY;
    for (int i = 0; i < 4; ++i) {
        rugo_real a = rugo_v2_dot(d, F[i]), b = rugo_v2_dot(d, G[i]);
        flo = rugo__min(flo, a);
        fhi = rugo__max(fhi, a);
        glo = rugo__min(glo, b);
        ghi = rugo__max(ghi, b);
    }
    return rugo__max(flo - ghi, glo - fhi);
}

/* Whether a lower bound of the distance between the convex hulls of F and G exceeds thr: the largest
 * gap between their projections on x, y, the two chord normals and the line between the polygons'
 * centres. The directions are tried in that order and the first gap above thr decides (the max of the
 * gaps exceeds thr iff one of them does), so the square roots of the later ones are often saved. */
int rugo__hull_gap_above(const rugo_vec2 F[4], const rugo_vec2 G[4], rugo_real thr) {
    if (thr > 64.0 * EPS) {
        /* No projection gap exceeds the distance of any point of F from any point of G. With the
         * coordinates in [-1, 1] (the local frame), a computed gap is within ~8 eps of the true one
         * for its (unit up to 4 eps) direction; so two control points closer than thr by a margin
         * decide "not above" without the five projections (the usual case near a contact, where
         * this test rarely prunes). */
        const rugo_real lim = thr - 64.0 * EPS;
        rugo_real d2 = INFINITY;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const rugo_vec2 d = rugo_v2_sub(F[i], G[j]);
                d2 = rugo__min(d2, rugo_v2_dot(d, d));
            }
        if (d2 <= lim * lim * (1.0 - 64.0 * EPS)) return 0;
    }
    if (projection_gap(rugo_v2(1.0, 0.0), F, G) > thr) return 1;
    if (projection_gap(rugo_v2(0.0, 1.0), F, G) > thr) return 1;
    rugo_vec2 nf = chord_normal(F);
    if ((nf.x != 0.0 || nf.y != 0.0) && projection_gap(nf, F, G) > thr) return 1;
    rugo_vec2 ng = chord_normal(G);
    if ((ng.x != 0.0 || ng.y != 0.0) && projection_gap(ng, F, G) > thr) return 1;
    rugo_vec2 cf =
        rugo_v2(0.25 * (F[0].x + F[1].x + F[2].x + F[3].x), 0.25 * (F[0].y + F[1].y + F[2].y + F[3].y));
    rugo_vec2 cg =
        rugo_v2(0.25 * (G[0].x + G[1].x + G[2].x + G[3].x), 0.25 * (G[0].y + G[1].y + G[2].y + G[3].y));
    rugo_vec2 dc = rugo_v2_sub(cf, cg);
    rugo_real lc = rugo__v2_norm(dc);
    return lc > 0.0 && projection_gap(rugo_v2(dc.x / lc, dc.y / lc), F, G) > thr;
}

/* Sign of cross(f', g') certified over a box from the control points of the two sub-hodographs
 * (0 if not one-signed). */
int rugo__cone_sign_of(const rugo_real c[9], const rugo_vec2 dF[3], const rugo_vec2 dG[3],
                       rugo_real* radius) {
    rugo_real mf = 0.0, mg = 0.0, cmin = INFINITY;
    int pos = 0, neg = 0;
    for (int i = 0; i < 9; ++i) {
        pos += c[i] > 0.0;
        neg += c[i] < 0.0;
    }
    /* Not all of one strict sign: rugo__one_sign below gives 0 for any tau >= 0, without the lengths. */
    if (pos != 9 && neg != 9) {
        if (radius) *radius = INFINITY;
        return 0;
    }
    for (int i = 0; i < 3; ++i) {
        /* squared lengths: sqrt is monotone and correctly rounded, so the max of the roots is the
         * root of the max, bit for bit */
        mf = rugo__max(mf, rugo_v2_dot(dF[i], dF[i]));
        mg = rugo__max(mg, rugo_v2_dot(dG[i], dG[i]));
        for (int j = 0; j < 3; ++j)
            cmin = rugo__min(cmin, fabs(c[3 * i + j]));
    }
    mf = sqrt(mf);
    mg = sqrt(mg);
    int sign = rugo__one_sign(c, 9, 16.0 * EPS * mf * mg);
    /* Over the box |det J| = |cross(f', g')| >= cmin and |J| <= mf + mg, so a point with |F| <= 16 eps
     * (computed residual plus evaluation error) has a root within 2 * 16 eps (mf + mg) / cmin. */
    if (radius) *radius = sign ? 32.0 * EPS * (mf + mg) / cmin : INFINITY;
    return sign;
}

int rugo__cone_sign(const rugo_vec2 dF[3], const rugo_vec2 dG[3], rugo_real* radius) {
    rugo_real c[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            c[3 * i + j] = rugo_v2_cross(dF[i], dG[j]);
    return rugo__cone_sign_of(c, dF, dG, radius);
}

/* rugo__cone_sign of the whole pieces, computed once for both searches (the sub-hodographs of the whole
 * square are the hodographs themselves). */
int rugo__whole_square_cone(narrow_ctx* c) {
    if (!c->root_cone_done) {
        c->root_cone = rugo__cone_sign_of(c->root_cross, c->df, c->dg, &c->root_rho);
        c->root_cone_done = 1;
    }
    return c->root_cone;
}

/* Krawczyk's exclusion test (interval Newton). Every root in the box lies in
 *   K = m - Y v(m) + (I - Y J(box)) (box - m),
 * m the centre, v(m) the system there (round-off n), Y the inverse of the point Jacobian jc at m,
 * J(box) the interval Jacobian with rows (a b) and (c d). Returns 1 if K misses the box. */
int rugo__krawczyk_excludes(box bx, const rugo_real v[2], const rugo_real n[2], const rugo_real jc[4], ival a,
                            ival b, ival c, ival d) {
    rugo_real det = jc[0] * jc[3] - jc[1] * jc[2];
    if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
    rugo_real y11 = jc[3] / det, y12 = -jc[1] / det, y21 = -jc[2] / det, y22 = jc[0] / det;
    if (!isfinite(y11) || !isfinite(y12) || !isfinite(y21) || !isfinite(y22)) return 0;
    ival m11 = rugo__iv_add(rugo__iv(1.0, 1.0),
                            rugo__iv_neg(rugo__iv_add(rugo__iv_scale(y11, a), rugo__iv_scale(y12, c))));
    ival m12 = rugo__iv_neg(rugo__iv_add(rugo__iv_scale(y11, b), rugo__iv_scale(y12, d)));
    ival m21 = rugo__iv_neg(rugo__iv_add(rugo__iv_scale(y21, a), rugo__iv_scale(y22, c)));
    ival m22 = rugo__iv_add(rugo__iv(1.0, 1.0),
                            rugo__iv_neg(rugo__iv_add(rugo__iv_scale(y21, b), rugo__iv_scale(y22, d))));
    rugo_real rs = 0.5 * (bx.s1 - bx.s0), rt = 0.5 * (bx.t1 - bx.t0);
    rugo_real ms = bx.s0 + rs, mt = bx.t0 + rt;
    rugo_real ps = y11 * v[0] + y12 * v[1], pt = y21 * v[0] + y22 * v[1];
    rugo_real jm =
        rugo__max(rugo__max(rugo__iv_mag(a), rugo__iv_mag(b)), rugo__max(rugo__iv_mag(c), rugo__iv_mag(d)));
    rugo_real ys = fabs(y11) + fabs(y12), yt = fabs(y21) + fabs(y22);
    /* widths, with the round-off of v, of the products and of the centre */
    rugo_real ws = rugo__iv_mag(m11) * rs + rugo__iv_mag(m12) * rt + fabs(y11) * n[0] + fabs(y12) * n[1] +
                   16.0 * EPS * (fabs(y11 * v[0]) + fabs(y12 * v[1]) + ys * jm * (rs + rt) + 1.0);
    rugo_real wt = rugo__iv_mag(m21) * rs + rugo__iv_mag(m22) * rt + fabs(y21) * n[0] + fabs(y22) * n[1] +
                   16.0 * EPS * (fabs(y21 * v[0]) + fabs(y22 * v[1]) + yt * jm * (rs + rt) + 1.0);
    rugo_real ks = ms - ps, kt = mt - pt;
    if (!isfinite(ks) || !isfinite(kt) || !isfinite(ws) || !isfinite(wt)) return 0;
    return ks - ws > bx.s1 || ks + ws < bx.s0 || kt - wt > bx.t1 || kt + wt < bx.t0;
}

/* 1 if the hull of a hodograph's control points (3) keeps away from the origin. */
int rugo__hodograph_nonzero(const rugo_vec2 d[3]) {
    rugo_real m = rugo__max(rugo__max(rugo__v2_norm(d[0]), rugo__v2_norm(d[1])), rugo__v2_norm(d[2]));
    rugo_vec2 dirs[4] = {d[0], d[1], d[2], rugo_v2_add(d[0], d[2])};
    for (int k = 0; k < 4; ++k) {
        rugo_real l = rugo__v2_norm(dirs[k]);
        if (!(l > 0.0)) continue;
        /* min_i (x_i / l) = (min_i x_i) / l for l > 0, as rounded division is monotone: one division
         * instead of three, the same value (up to the sign of an underflowed zero, which the test
         * below cannot see) */
        rugo_real lo = INFINITY;
        for (int i = 0; i < 3; ++i)
            lo = rugo__min(lo, rugo_v2_dot(dirs[k], d[i]));
        lo = lo / l;
        if (lo > 1e-9 * m) return 1;
    }
    return 0;
}
