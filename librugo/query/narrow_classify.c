/* What kind a stationary pair of the distance is: a minimum (a contact candidate), a saddle or a
 * maximum, or a minimum seen from one side only, at an end where a piece stops (RUGO__END_MINIMUM, for
 * the caller to confirm with the neighbouring segment). Separate because classifying a pair is a
 * question about the distance around one point, whichever search found it.
 *
 * Classification by the Hessian of D = |f-g|^2/2 ([[J11, J12], [J12, -J22]]): eigenvalues beyond
 * round-off decide min / saddle / max; a semi-definite direction is probed along its eigenvector with
 * the smallest step that changes D beyond round-off (rising both ways, or flat: minimum side;
 * falling both ways: maximum side; else saddle). A pair at distance <= TAU_TOUCH is a minimum.
 * Sharp corners: a piece that stops at an end of its domain (zero speed there, as at three coincident
 * control points) gives a multiple root that is located only roughly, or none when rounding leaves the
 * speed a few ulps off zero; such roots are moved onto the end, and the end's point query against the
 * other piece adds the pairs the search missed (add_zero_speed_ends; the point query adds the end
 * itself). There the pair is classified by probing along each piece on its own, only into the domain
 * (its cubic continued past the end is not the curve), and a minimum is RUGO__END_MINIMUM, for the
 * caller to confirm with the neighbouring segment's piece. A point-like piece (four coincident points:
 * its polynomial is round-off) cannot classify its point and reports RUGO__END_MINIMUM too. */
#include "query/narrow_internal.h"

/* +1 if D rises both ways along v (or stays flat), -1 if it falls both ways, 0 otherwise; from the
 * smallest step that changes D beyond its round-off. Where one way leaves the parameter square, the way
 * that stays inside decides alone (+1 rising, -1 falling) and *one_sided is set: the other side belongs
 * to the neighbouring segment. */
static int probe_direction(const narrow_ctx* c, rugo_real s, rugo_real t, rugo_vec2 v, int* one_sided) {
    static const rugo_real delta[6] = {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2};
    rugo_real d0 = rugo__half_dist2(c, s, t);
    /* D = |r|^2/2 with |r| good to a few ulps of the O(1) coordinates */
    rugo_real noise = 16.0 * EPS * (sqrt(2.0 * d0) + EPS);
    for (int k = 0; k < 6; ++k) {
        const rugo_real sp = s + delta[k] * v.x, tp = t + delta[k] * v.y;
        const rugo_real sm = s - delta[k] * v.x, tm = t - delta[k] * v.y;
        const int inp = rugo__in_square(sp, tp), inm = rugo__in_square(sm, tm);
        if (inp != inm) {
            const rugo_real d1 = inp ? rugo__half_dist2(c, sp, tp) - d0 : rugo__half_dist2(c, sm, tm) - d0;
            if (fabs(d1) > noise) {
                *one_sided = 1;
                return d1 > 0.0 ? 1 : -1;
            }
            continue;
        }
        /* both ways inside (or both outside, at a corner of the square: extrapolated, as before) */
        rugo_real dp = rugo__half_dist2(c, sp, tp) - d0;
        rugo_real dm = rugo__half_dist2(c, sm, tm) - d0;
        if (fabs(dp) > noise && fabs(dm) > noise) {
            if (dp > 0.0 && dm > 0.0) return 1;
            if (dp < 0.0 && dm < 0.0) return -1;
            return 0;
        }
    }
    return 1;
}

/* Moves a stationary pair near an end where its piece stops onto that end (rugo__near_end). */
void rugo__snap_to_zero_speed_end(const narrow_ctx* c, rugo_real* s, rugo_real* t) {
    if (rugo__near_end(*s) && rugo__speed_vanishes(rugo__bezier_eval(c->df, 2, *s), c->df))
        *s = *s < 0.5 ? 0.0 : 1.0;
    if (rugo__near_end(*t) && rugo__speed_vanishes(rugo__bezier_eval(c->dg, 2, *t), c->dg))
        *t = *t < 0.5 ? 0.0 : 1.0;
}

/* Whether (s, t) is at an end of a piece's domain where that piece's speed vanishes: a corner made by
 * coincident control points, which the piece reaches only from one side. */
static int at_zero_speed_end(const narrow_ctx* c, const pair_eval* e, rugo_real s, rugo_real t) {
    return (rugo__near_end(s) && rugo__speed_vanishes(e->fp, c->df)) ||
           (rugo__near_end(t) && rugo__speed_vanishes(e->gp, c->dg));
}

/* Minimum / saddle / maximum from the Hessian of D = |f-g|^2/2, whose entries are
 * D_ss = J11, D_st = J12 = -f'·g', D_tt = -J22. A minimum decided from one side only (a probe that
 * could not look past the end of the domain, or any minimum at a zero-speed end, where the piece's
 * polynomial does not continue as the curve does) is RUGO__END_MINIMUM: the caller confirms it with
 * the neighbouring segment's classification of the same point. */
int rugo__classify_stationary(const narrow_ctx* c, rugo_real s, rugo_real t, rugo_real dist) {
    if (dist <= TAU_TOUCH) return RUGO__MINIMUM;
    pair_eval e = rugo__eval_pair(c, s, t);
    rugo_real a = e.j11, b = e.j12, d = -e.j22;
    rugo_real scale = rugo_v2_dot(e.fp, e.fp) + rugo_v2_dot(e.gp, e.gp) +
                      rugo__v2_norm(e.r) * (rugo__v2_norm(e.fpp) + rugo__v2_norm(e.gpp));
    rugo_real m = 0.5 * (a + d), q = hypot(0.5 * (a - d), b);
    /* the entries are good to a few ulps of scale; so are the eigenvalues */
    rugo_real l1 = m - q, l2 = m + q, tol = 1e3 * EPS * scale;
    if (at_zero_speed_end(c, &e, s, t)) {
        /* Where a piece stops, its derivatives are round-off (both pieces' at two corners facing each
         * other), and so is the Hessian. Look along each piece on its own instead, only into the domain
         * where it stops (reparametrised by the arc from the corner, the distance is first-order in it
         * there, so rising along each piece is a minimum of the quadrant or half-plane). */
        int one_sided = 1;
        const int us = probe_direction(c, s, t, rugo_v2(1.0, 0.0), &one_sided);
        const int ut = probe_direction(c, s, t, rugo_v2(0.0, 1.0), &one_sided);
        if (us > 0 && ut > 0) return RUGO__END_MINIMUM;
        if (us < 0 && ut < 0) return RUGO__MAXIMUM;
        return RUGO__SADDLE;
    }
    if (l1 > tol) return RUGO__MINIMUM;
    if (l2 < -tol) return RUGO__MAXIMUM;
    if (l1 < -tol && l2 > tol) return RUGO__SADDLE;
    /* Semi-definite: decide the flat direction(s) by probing. Eigenvector of l1: (b, l1 - a) or
     * (l1 - d, b), whichever is longer. */
    rugo_vec2 v1 = rugo_v2(b, l1 - a), v1b = rugo_v2(l1 - d, b);
    if (rugo__v2_norm(v1b) > rugo__v2_norm(v1)) v1 = v1b;
    rugo_real lv = rugo__v2_norm(v1);
    v1 = lv > 0.0 ? rugo_v2(v1.x / lv, v1.y / lv) : rugo_v2(1.0, 0.0);
    rugo_vec2 v2 = rugo_v2_perp(v1);
    int one_sided = 0;
    int u1 = fabs(l1) <= tol ? probe_direction(c, s, t, v1, &one_sided) : rugo__sign(l1);
    int u2 = fabs(l2) <= tol ? probe_direction(c, s, t, v2, &one_sided) : rugo__sign(l2);
    if (u1 > 0 && u2 > 0) return one_sided ? RUGO__END_MINIMUM : RUGO__MINIMUM;
    if (u1 < 0 && u2 < 0) return RUGO__MAXIMUM;
    return RUGO__SADDLE;
}
