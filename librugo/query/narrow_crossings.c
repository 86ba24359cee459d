/* The narrow phase's search for crossings of two pieces, F = f(s) - g(t) = 0 (6.12), each certified
 * unique in its box and found by Newton, with the kind of each (which way g crosses f). Separate from
 * the stationary pairs' search because its system, its certificates and its fallbacks are its own.
 *
 * A box is dropped when
 *   - the projections of the two control polygons on x, y, both chord normals and the line between
 *     their centroids are disjoint (Bernstein coefficients of u·F of one strict sign), or
 *   - Krawczyk's interval-Newton operator (Y = J(centre)^-1, J = [f' -g'] bounded by the hodographs'
 *     control points) maps the box outside itself: no root.
 * Uniqueness: cross(f'_i, g'_j) of one strict sign over all hodograph control points (two meetings P != Q
 * would give, by Rolle on cross(f - P, Q - P) and on cross(g - P, Q - P), tangents of both parallel to
 * Q - P). Then Newton from the centre; its root is accepted if its uncertainty ball (round-off residual /
 * lower bound of |det J| over the box) lies in the box: a root certainly exists there, and a numerical
 * zero next to a touching (whose ball reaches the touching) is not taken for a crossing. kind = the
 * certified sign of cross(f', g'). Boxes of side <= 2^-20 whose tangents are not separated try the
 * touching hypothesis: Newton on the (C, H) form of the stationary system (narrow_stationary.c; well
 * conditioned at a touching) and, at distance <= TAU_TOUCH, a touching root that resolves everything
 * within R_FALLBACK. Leaves: Newton from the centre, best iterate, kept if |F| <= TAU_TOUCH. Uncertified
 * roots get their kind from the side of g(t -+ delta) relative to f (left of f' = inside = +1). */
#include "query/narrow_internal.h"

/* Newton on F = f(s) - g(t) (6.12). Returns 1 if it converged (residual at round-off or a step at
 * round-off); (s, t) is then the root. Otherwise (s, t) is the iterate with the smallest |F| and *res
 * its residual (max-norm, local frame). */
static int newton_cross(narrow_ctx* c, const box* lim, rugo_real* s, rugo_real* t, rugo_real* res,
                        const rugo_vec2* start) {
    rugo_real x = *s, y = *t, bx = x, by = y, bres = INFINITY, rr = INFINITY;
    int conv = 0, tiny = 0;
    for (int it = 0;; ++it) {
        /* start (may be NULL): F, f', g' already evaluated at the starting point, as below */
        rugo_vec2 r = it == 0 && start
                          ? start[0]
                          : rugo_v2_sub(rugo__bezier_eval(c->f, 3, x), rugo__bezier_eval(c->g, 3, y));
        rr = rugo__v2_max_abs(r);
        if (!(rr == rr)) break;
        if (rr < bres) {
            bres = rr;
            bx = x;
            by = y;
        }
        if (rr <= 4.0 * EPS || tiny) {
            conv = 1;
            break;
        }
        if (it >= NEWTON_MAX) break;
        rugo_vec2 a = it == 0 && start ? start[1] : rugo__bezier_eval(c->df, 2, x);
        rugo_vec2 b = rugo_v2_scale(-1.0, it == 0 && start ? start[2] : rugo__bezier_eval(c->dg, 2, y));
        rugo_real det = rugo_v2_cross(a, b);
        if (!(fabs(det) > 0.0)) break;
        rugo_vec2 m = rugo_v2_scale(-1.0, r);
        rugo_real ds = rugo_v2_cross(m, b) / det, dt = rugo_v2_cross(a, m) / det;
        if (!isfinite(ds) || !isfinite(dt)) break;
        x += ds;
        y += dt;
        ++c->newton;
        tiny = rugo__max(fabs(ds), fabs(dt)) <= 4.0 * EPS;
        if (rugo__newton_wandered(lim, x, y)) break;
    }
    if (conv) {
        /* (converged right after evaluating F at (x, y)) */
        *s = x;
        *t = y;
        *res = rr;
    } else {
        *s = bx;
        *t = by;
        *res = bres;
    }
    return conv;
}

/* Newton found a crossing (s, t) outside box b (residual res). If the tangents are not parallel
 * anywhere on a box E spanning b and a ball about the root, E holds at most one crossing (see the
 * top of the file), the certain one in the ball, which lies outside b: b holds none. */
static int cross_excluded(const narrow_ctx* c, box b, rugo_real s, rugo_real t, rugo_real res) {
    box e;
    rugo_real r0, unit;
    if (!rugo__exclusion_box(b, s, t, &e, &r0)) return 0;
    rugo_vec2 dF[3], dG[3];
    rugo__sub_bezier(c->df, 2, e.s0, e.s1, dF);
    rugo__sub_bezier(c->dg, 2, e.t0, e.t1, dG);
    if (rugo__cone_sign(dF, dG, &unit) == 0) return 0;
    /* rugo__cone_sign's radius holds for a residual of 16 eps; it scales with the residual */
    const rugo_real rho = unit * (res + 16.0 * EPS) / (16.0 * EPS);
    return rho < r0;
}

void rugo__search_crossings(narrow_ctx* c) {
    box st[STACK_MAX];
    int ns = 0, boxes = 0;
    piece_memo mf, mg;
    rugo__memo_init(&mf);
    rugo__memo_init(&mg);
    rugo__push_box(st, &ns, 0.0, 1.0, 0.0, 1.0);
    while (ns > 0) {
        box b = st[--ns];
        if (rugo__box_covered(c->cross, c->ncross, b)) continue;
        if (++boxes > BOX_BUDGET) {
            c->overflow = 1;
            ++c->fallback;
            return;
        }
        rugo__memo_range(&mf, c->f, c->df, b.s0, b.s1);
        rugo__memo_range(&mg, c->g, c->dg, b.t0, b.t1);
        const rugo_vec2 *F = mf.P, *G = mg.P;
        const int whole = rugo__is_whole_square(b);
        if (whole ? c->root_apart : rugo__hull_gap_above(F, G, TAU_F)) continue;
        rugo_real diam_f = rugo__polygon_diameter(F, 3), diam_g = rugo__polygon_diameter(G, 3);
        rugo_real sc = 0.5 * (b.s0 + b.s1), tc = 0.5 * (b.t0 + b.t1);
        const rugo_vec2 *dF = mf.dP, *dG = mg.dP;
        rugo_vec2 centre[3]; /* F, f', g' at the centre (sc, tc) */
        {
            /* interval Newton: J = [f' -g'] over the box */
            ival fpx, fpy, gpx, gpy;
            rugo__iv_range(dF, 2, &fpx, &fpy);
            rugo__iv_range(dG, 2, &gpx, &gpy);
            centre[0] = rugo_v2_sub(rugo__bezier_eval(c->f, 3, sc), rugo__bezier_eval(c->g, 3, tc));
            centre[1] = rugo__bezier_eval(c->df, 2, sc);
            centre[2] = rugo__bezier_eval(c->dg, 2, tc);
            const rugo_vec2 r = centre[0], fp = centre[1], gp = centre[2];
            rugo_real v[2] = {r.x, r.y}, n[2] = {8.0 * EPS, 8.0 * EPS};
            rugo_real jc[4] = {fp.x, -gp.x, fp.y, -gp.y};
            if (rugo__krawczyk_excludes(b, v, n, jc, fpx, rugo__iv_neg(gpx), fpy, rugo__iv_neg(gpy)))
                continue;
        }
        rugo_real rho;
        int sign;
        if (whole) {
            sign = rugo__whole_square_cone(c);
            rho = c->root_rho;
        } else {
            sign = rugo__cone_sign(dF, dG, &rho);
        }
        if (sign != 0) {
            rugo_real s = sc, t = tc, res;
            /* The root must be certain to exist in the box: its uncertainty ball inside the box (a
             * numerical zero next to a touching has a ball as large as its distance to it). */
            const int conv = newton_cross(c, &b, &s, &t, &res, centre);
            if (conv && rugo__in_box_ball(b, s, t, rho)) {
                rugo_vec2 fp = rugo__bezier_eval(c->df, 2, s), gp = rugo__bezier_eval(c->dg, 2, t);
                rugo_real cond = (rugo_v2_dot(fp, fp) + rugo_v2_dot(gp, gp)) / fabs(rugo_v2_cross(fp, gp));
                const rugo_real radius = rugo__root_radius(cond);
                if (!rugo__add_root(c->cross, &c->ncross, TMP_CROSS, s, t, radius, sign, 0)) {
                    c->overflow = 1;
                    return;
                }
                continue;
            }
            if (conv && cross_excluded(c, b, s, t, res)) continue;
        }
        if (sign == 0 && rugo__max(b.s1 - b.s0, b.t1 - b.t0) <= H_TOUCH) {
            /* Small, tangents not separated: maybe a touching. Its point is a well-conditioned root of
             * (C, H) (stationary forms), which Newton finds; at distance ~0 it is recorded (kind by
             * probing) and everything within R_FALLBACK of it is resolved. */
            int mode =
                rugo__hodograph_nonzero(dG) ? STAT_CH2 : (rugo__hodograph_nonzero(dF) ? STAT_CH1 : STAT_HH);
            rugo_real s = sc, t = tc, res;
            if (rugo__newton_stat(c, mode, &b, &s, &t, &res, NULL, NULL) && rugo__in_domain(s, t) &&
                rugo__v2_max_abs(rugo_v2_sub(rugo__bezier_eval(c->f, 3, s), rugo__bezier_eval(c->g, 3, t))) <=
                    TAU_TOUCH) {
                ++c->fallback;
                if (!rugo__add_root(c->cross, &c->ncross, TMP_CROSS, s, t, R_FALLBACK, KIND_PROBE, 1)) {
                    c->overflow = 1;
                    return;
                }
                if (rugo__box_covered(c->cross, c->ncross, b)) continue;
            }
        }
        if (rugo__split_box(st, &ns, b, diam_f, diam_g)) continue;
        /* A leaf: the root (if any) is tangential or degenerate. */
        ++c->fallback;
        if (rugo__near_root(c->cross, c->ncross, sc, tc, R_FALLBACK)) continue;
        rugo_real s = sc, t = tc, res;
        newton_cross(c, &b, &s, &t, &res, centre);
        if (res <= TAU_TOUCH && rugo__in_domain(s, t)) {
            if (!rugo__add_root(c->cross, &c->ncross, TMP_CROSS, s, t, R_FALLBACK, KIND_PROBE, 1)) {
                c->overflow = 1;
                return;
            }
        }
    }
}

/* Unit tangent of f at s, or 0 for a point. Where f' is below 1e-9 of the hodograph (next to a
 * zero-speed end, as at three coincident control points) the direction of the chord over
 * [s - h, s + h] within the domain: f'' there points backwards on the side before the zero
 * (f' ~ (1 - s)^2 a, f'' ~ -2 (1 - s) a), which made crossings next to a sharp corner "touching";
 * the chord, the integral of f', does not turn. */
static rugo_vec2 tangent_f(const narrow_ctx* c, rugo_real s) {
    rugo_vec2 d = rugo__bezier_eval(c->df, 2, s);
    rugo_real scale = rugo__v2_max_abs(c->df[0]) + rugo__v2_max_abs(c->df[1]) + rugo__v2_max_abs(c->df[2]);
    rugo_real l = rugo__v2_norm(d);
    if (!(l > 1e-9 * scale)) {
        const rugo_real h = 1.0 / 1024.0;
        d = rugo_v2_sub(rugo__bezier_eval(c->f, 3, rugo__min(s + h, 1.0)),
                        rugo__bezier_eval(c->f, 3, rugo__max(s - h, 0.0)));
        l = rugo__v2_norm(d);
    }
    if (!(l > 0.0)) return rugo_v2(0.0, 0.0);
    return rugo_v2(d.x / l, d.y / l);
}

/* Signed distance of p from f near parameter s (positive: left of f', the inside of a CCW curve),
 * from a local projection of p on f. */
static rugo_real side_of(narrow_ctx* c, rugo_real s, rugo_vec2 p) {
    rugo_real x = s;
    for (int it = 0; it < 16; ++it) {
        rugo_vec2 r = rugo_v2_sub(rugo__bezier_eval(c->f, 3, x), p), fp = rugo__bezier_eval(c->df, 2, x),
                  fpp = rugo__bezier_eval(c->ddf, 1, x);
        rugo_real num = rugo_v2_dot(r, fp), den = rugo_v2_dot(fp, fp) + rugo_v2_dot(r, fpp);
        if (!(den > 0.0)) den = rugo_v2_dot(fp, fp);
        if (!(den > 0.0)) break;
        rugo_real step = -num / den;
        if (step > 0.05) step = 0.05;
        if (step < -0.05) step = -0.05;
        x += step;
        ++c->newton;
        if (fabs(step) <= 4.0 * EPS) break;
    }
    return rugo_v2_cross(tangent_f(c, x), rugo_v2_sub(p, rugo__bezier_eval(c->f, 3, x)));
}

/* Kind of a (near-)tangential crossing: on which side of f does g lie just before and after t. */
int rugo__probe_crossing_kind(narrow_ctx* c, rugo_real s, rugo_real t) {
    static const rugo_real delta[5] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2};
    for (int k = 0; k < 5; ++k) {
        rugo_real before = side_of(c, s, rugo__bezier_eval(c->g, 3, t - delta[k]));
        rugo_real after = side_of(c, s, rugo__bezier_eval(c->g, 3, t + delta[k]));
        if (fabs(before) > 64.0 * EPS && fabs(after) > 64.0 * EPS) {
            if (before < 0.0 && after > 0.0) return 1;
            if (before > 0.0 && after < 0.0) return -1;
            return 0;
        }
    }
    return 0;
}
