/* The narrow phase's search for stationary pairs of the distance between two pieces: the roots, with
 * f != g, of H1 = (f-g)·f' = 0, H2 = (f-g)·g' = 0 within the cutoff, each certified unique in its box
 * and found by Newton. Separate from the crossings' search because its system, its pruning tests and
 * its certificates are its own.
 *
 * The system is (6.14). A box is dropped when
 *   - the polygons' projections are farther apart than the cutoff;
 *   - C = cross(f', g') keeps one strict sign (at a stationary pair with f != g both tangents are
 *     normal to f - g, hence parallel; this removes transversal crossings and nearly parallel pieces);
 *   - the Bernstein coefficients of H1 (degree 5 x 3), H2 (3 x 5) or of either row of adj(J) (H1, H2)
 *     (J at the centre; degree 5 x 5; the rows remove the first-order dependence along a valley of
 *     nearly equidistant curves) keep one strict sign;
 *   - Krawczyk's operator excludes the box (system below).
 * The system solved: (C, H2) where g' != 0 on the box, else (C, H1) where f' != 0, else (H1, H2). Same
 * roots away from crossings (f' parallel to g' and (f-g)·g' = 0 give (f-g)·f' = 0), but the Jacobian
 * of (H1, H2) has determinant ~ d dk at a near-touching (distance d, curvature difference dk) while
 * that of (C, H) has ~ dk: it stays well conditioned down to touching curves. For (H1, H2):
 *   J = [[ |f'|^2 + (f-g)·f'', -g'·f' ], [ g'·f', -|g'|^2 + (f-g)·g'' ]]  (= dH/d(s,t); J u = -H).
 * Uniqueness: the interval Jacobian with rows at independent points of the box is non-singular (two roots
 * would make both gradients normal to the segment joining them, mean value theorem). Then Newton and the
 * existence ball of a crossing's (narrow_crossings.c). Boxes of side <= 2^-18 that are still not
 * certified (nearly degenerate pairs, e.g. almost touching curves) accept a Newton root inside the box
 * and resolve everything within R_MERGE of it; leaves keep a Newton root whose residual is near
 * round-off. */
#include "query/narrow_internal.h"

pair_eval rugo__eval_pair(const narrow_ctx* c, rugo_real s, rugo_real t) {
    pair_eval e;
    e.r = rugo_v2_sub(rugo__bezier_eval(c->f, 3, s), rugo__bezier_eval(c->g, 3, t));
    e.fp = rugo__bezier_eval(c->df, 2, s);
    e.gp = rugo__bezier_eval(c->dg, 2, t);
    e.fpp = rugo__bezier_eval(c->ddf, 1, s);
    e.gpp = rugo__bezier_eval(c->ddg, 1, t);
    e.h1 = rugo_v2_dot(e.r, e.fp);
    e.h2 = rugo_v2_dot(e.r, e.gp);
    rugo_real lr = rugo__v2_norm(e.r), lf = rugo__v2_norm(e.fp), lg = rugo__v2_norm(e.gp);
    e.n1 = 16.0 * EPS * lf * (1.0 + lr);
    e.n2 = 16.0 * EPS * lg * (1.0 + lr);
    rugo_real fg = rugo_v2_dot(e.fp, e.gp);
    e.j11 = rugo_v2_dot(e.fp, e.fp) + rugo_v2_dot(e.r, e.fpp);
    e.j12 = -fg;
    e.j21 = fg;
    e.j22 = -rugo_v2_dot(e.gp, e.gp) + rugo_v2_dot(e.r, e.gpp);
    e.cc = rugo_v2_cross(e.fp, e.gp);
    e.nc = 16.0 * EPS * lf * lg;
    e.cs = rugo_v2_cross(e.fpp, e.gp);
    e.ct = rugo_v2_cross(e.fp, e.gpp);
    return e;
}

/* The system of the given form at e: values a, b, their round-off levels na, nb, Jacobian rows. */
static void stat_system(const pair_eval* e, int mode, rugo_real v[2], rugo_real n[2], rugo_real j[4]) {
    if (mode == STAT_HH) {
        v[0] = e->h1, v[1] = e->h2, n[0] = e->n1, n[1] = e->n2;
        j[0] = e->j11, j[1] = e->j12, j[2] = e->j21, j[3] = e->j22;
    } else {
        v[0] = e->cc, n[0] = e->nc, j[0] = e->cs, j[1] = e->ct;
        if (mode == STAT_CH2) {
            v[1] = e->h2, n[1] = e->n2, j[2] = e->j21, j[3] = e->j22;
        } else {
            v[1] = e->h1, n[1] = e->n1, j[2] = e->j11, j[3] = e->j12;
        }
    }
}

/* Newton on the stationary system in the given form, J u = -H. Same contract as newton_cross; *res
 * is the residual in units of its round-off level (0 when converged). */
int rugo__newton_stat(narrow_ctx* c, int mode, const box* lim, rugo_real* s, rugo_real* t, rugo_real* res,
                      const pair_eval* start, pair_eval* last) {
    rugo_real x = *s, y = *t, bx = x, by = y, bres = INFINITY;
    int conv = 0, tiny = 0;
    for (int it = 0;; ++it) {
        /* start (may be NULL): rugo__eval_pair at the starting point; last (may be NULL): gets the values at
         * the root when converged (the loop stops right after evaluating there) */
        pair_eval e = it == 0 && start ? *start : rugo__eval_pair(c, x, y);
        if (last) *last = e;
        rugo_real v[2], n[2], j[4];
        stat_system(&e, mode, v, n, j);
        rugo_real rr =
            rugo__max(fabs(v[0]) / rugo__max(n[0], DBL_MIN), fabs(v[1]) / rugo__max(n[1], DBL_MIN));
        if (!(rr == rr)) break;
        if (rr < bres) {
            bres = rr;
            bx = x;
            by = y;
        }
        if (rr <= 1.0 || tiny) {
            conv = 1;
            break;
        }
        if (it >= NEWTON_MAX) break;
        rugo_real det = j[0] * j[3] - j[1] * j[2];
        if (!(fabs(det) > 0.0)) break;
        rugo_real ds = -(v[0] * j[3] - v[1] * j[1]) / det;
        rugo_real dt = -(j[0] * v[1] - j[2] * v[0]) / det;
        if (!isfinite(ds) || !isfinite(dt)) break;
        x += ds;
        y += dt;
        ++c->newton;
        tiny = rugo__max(fabs(ds), fabs(dt)) <= 4.0 * EPS;
        if (rugo__newton_wandered(lim, x, y)) break;
    }
    if (conv) {
        *s = x;
        *t = y;
    } else {
        *s = bx;
        *t = by;
    }
    *res = conv ? 0.0 : bres;
    return conv;
}

/* Interval bounds over the box of the Jacobian of the stationary system (form `mode`), rows (a b)
 * and (c d). */
static void stat_jacobian(int mode, const rugo_vec2 F[4], const rugo_vec2 G[4], const rugo_vec2 dF[3],
                          const rugo_vec2 dG[3], const rugo_vec2 ddF[2], const rugo_vec2 ddG[2], ival J[4]) {
    ival fx, fy, gx, gy, fpx, fpy, gpx, gpy, fppx, fppy, gppx, gppy;
    rugo__iv_range(F, 3, &fx, &fy);
    rugo__iv_range(G, 3, &gx, &gy);
    rugo__iv_range(dF, 2, &fpx, &fpy);
    rugo__iv_range(dG, 2, &gpx, &gpy);
    rugo__iv_range(ddF, 1, &fppx, &fppy);
    rugo__iv_range(ddG, 1, &gppx, &gppy);
    ival rx = rugo__iv_add(fx, rugo__iv_neg(gx)), ry = rugo__iv_add(fy, rugo__iv_neg(gy));
    ival h1s = rugo__iv_add(rugo__iv_add(rugo__iv_sq(fpx), rugo__iv_sq(fpy)),
                            rugo__iv_add(rugo__iv_mul(rx, fppx), rugo__iv_mul(ry, fppy)));
    ival fg = rugo__iv_add(rugo__iv_mul(fpx, gpx), rugo__iv_mul(fpy, gpy));
    ival h1t = rugo__iv_neg(fg), h2s = fg;
    ival h2t = rugo__iv_add(rugo__iv_neg(rugo__iv_add(rugo__iv_sq(gpx), rugo__iv_sq(gpy))),
                            rugo__iv_add(rugo__iv_mul(rx, gppx), rugo__iv_mul(ry, gppy)));
    if (mode == STAT_HH) {
        J[0] = h1s, J[1] = h1t, J[2] = h2s, J[3] = h2t;
    } else {
        /* dC/ds = cross(f'', g'), dC/dt = cross(f', g'') */
        J[0] = rugo__iv_add(rugo__iv_mul(fppx, gpy), rugo__iv_neg(rugo__iv_mul(fppy, gpx)));
        J[1] = rugo__iv_add(rugo__iv_mul(fpx, gppy), rugo__iv_neg(rugo__iv_mul(fpy, gppx)));
        if (mode == STAT_CH2)
            J[2] = h2s, J[3] = h2t;
        else
            J[2] = h1s, J[3] = h1t;
    }
}

/* 1 if the interval Jacobian is non-singular between any two points of the box (rows taken at
 * independent points), so the box holds at most one root: two roots would give, by the mean value
 * theorem on the segment between them, gradients of both equations normal to it. Also a lower bound
 * of |det| and an upper bound of the entries, for the existence radius. */
static int jacobian_regular(const ival J[4], rugo_real* detmin, rugo_real* jmax) {
    ival det = rugo__iv_add(rugo__iv_mul(J[0], J[3]), rugo__iv_neg(rugo__iv_mul(J[1], J[2])));
    rugo_real margin =
        64.0 * EPS * (rugo__iv_mag(J[0]) * rugo__iv_mag(J[3]) + rugo__iv_mag(J[1]) * rugo__iv_mag(J[2]));
    *detmin = rugo__min(fabs(det.lo), fabs(det.hi));
    *jmax = rugo__max(rugo__max(rugo__iv_mag(J[0]), rugo__iv_mag(J[1])),
                      rugo__max(rugo__iv_mag(J[2]), rugo__iv_mag(J[3])));
    return det.lo > margin || det.hi < -margin;
}

/* W[i][k] = C(3,i) C(2,k) / C(5,i+k): the product of degree-3 and degree-2 Bernstein polynomials. */
static const rugo_real W32[4][3] = {{1.0, 0.4, 0.1}, {0.6, 0.6, 0.3}, {0.3, 0.6, 0.6}, {0.1, 0.4, 1.0}};

/* The last test of stat_prune: 1 if the hulls keep more than the cutoff apart (never for the whole
 * square, whose hull test solve has already made). */
static int hull_left(const narrow_ctx* c, int whole, const rugo_vec2 F[4], const rugo_vec2 G[4]) {
    return !whole && rugo__hull_gap_above(F, G, c->cutoff + TAU_F);
}

/* Whether four values are all above tau or all below -tau (as rugo__one_sign would find them). */
static int corners_one_sign(rugo_real a, rugo_real b, rugo_real c, rugo_real d, rugo_real tau) {
    return (a > tau && b > tau && c > tau && d > tau) || (a < -tau && b < -tau && c < -tau && d < -tau);
}

/* 1 if the box provably holds no stationary pair (with f != g) within the cutoff. When it returns 0,
 * *ec holds the values at the box's centre (the Jacobian of (H1, H2) there preconditions the last
 * tests; the caller needs them too). */
static int stat_prune(narrow_ctx* c, box bx, const rugo_vec2 F[4], const rugo_vec2 G[4],
                      const rugo_vec2 dF[3], const rugo_vec2 dG[3], pair_eval* ec) {
    /* The box is pruned if any test below proves it empty; they are pure, so their order does not
     * change the answer. The cone test prunes most sub-boxes and is cheap: first. The hull test
     * (cutoff) rarely prunes: it runs last, only for a box that the others leave (hull_left). (The
     * hull test of the whole square is known to fail when the search runs: see solve.) */
    const int whole = rugo__is_whole_square(bx);
    if (whole ? rugo__whole_square_cone(c) != 0 : rugo__cone_sign(dF, dG, NULL) != 0) return 1;
    rugo_vec2 D[4][4];
    rugo_real md = 0.0, mf = 0.0, mg = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            D[i][j] = rugo_v2_sub(F[i], G[j]);
            md = rugo__max(md, rugo__v2_max_abs(D[i][j]));
        }
    for (int k = 0; k < 3; ++k) {
        mf = rugo__max(mf, rugo__v2_max_abs(dF[k]));
        mg = rugo__max(mg, rugo__v2_max_abs(dG[k]));
    }
    rugo_real tau1 = 32.0 * EPS * mf * (1.0 + md);
    rugo_real tau2 = 32.0 * EPS * mg * (1.0 + md);
    {
        /* The four tests below need all their coefficients of one strict sign; the corner
         * coefficients (the values at the box's corners, one product each, computed here with the same
         * operations as below) decide most failures. When every test already fails at its corners the
         * box is not pruned, without the ~200 products of the full coefficient arrays. */
        const rugo_real a0 = rugo_v2_dot(D[0][0], dF[0]), a1 = rugo_v2_dot(D[0][3], dF[0]);
        const rugo_real a2 = rugo_v2_dot(D[3][0], dF[2]), a3 = rugo_v2_dot(D[3][3], dF[2]);
        const rugo_real b0 = rugo_v2_dot(D[0][0], dG[0]), b1 = rugo_v2_dot(D[0][3], dG[2]);
        const rugo_real b2 = rugo_v2_dot(D[3][0], dG[0]), b3 = rugo_v2_dot(D[3][3], dG[2]);
        if (!corners_one_sign(a0, a1, a2, a3, tau1) && !corners_one_sign(b0, b1, b2, b3, tau2)) {
            *ec = rugo__eval_pair(c, 0.5 * (bx.s0 + bx.s1), 0.5 * (bx.t0 + bx.t1));
            int maybe = 0;
            for (int r = 0; r < 2 && !maybe; ++r) {
                const rugo_real a = r == 0 ? ec->j22 : -ec->j21, b = r == 0 ? -ec->j12 : ec->j11;
                /* e1 and e2 at the corners (m, n) = (0,0), (0,5), (5,0), (5,5) are the corners of H1
                 * and H2 (degree elevation keeps end coefficients) */
                maybe = corners_one_sign(a * a0 + b * b0, a * a1 + b * b1, a * a2 + b * b2, a * a3 + b * b3,
                                         2.0 * (fabs(a) * tau1 + fabs(b) * tau2));
            }
            if (!maybe) return hull_left(c, whole, F, G);
        }
    }
    /* Bernstein products: coefficient m = i + k collects W32[i][k] x_i y_k, summed in increasing i
     * (the loops below run i outside k, so each sum is accumulated in that order). */
    rugo_real h1[24], h2[24];
    /* H1: index m (s, degree 5) * 4 + j (t, degree 3). */
    for (int q = 0; q < 24; ++q)
        h1[q] = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            const rugo_real w = W32[i][k];
            rugo_real* row = h1 + 4 * (i + k);
            for (int j = 0; j < 4; ++j)
                row[j] += w * rugo_v2_dot(D[i][j], dF[k]);
        }
    if (rugo__one_sign(h1, 24, tau1) != 0) return 1;
    /* H2: index i (s, degree 3) * 6 + n (t, degree 5). */
    for (int q = 0; q < 24; ++q)
        h2[q] = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 3; ++k)
                h2[6 * i + j + k] += W32[j][k] * rugo_v2_dot(D[i][j], dG[k]);
    if (rugo__one_sign(h2, 24, tau2) != 0) return 1;
    /* Preconditioned: the rows of adj(J) (H1, H2), J the Jacobian at the centre, in the common degree
     * (5, 5). Each is H1 or H2 with its first-order dependence on one parameter removed, so it keeps
     * one sign on boxes that are far from a root only along a valley of nearly parallel curves, where
     * H1 and H2 alone vanish all along. (Degree elevation by 2 is the product with 1 = sum B^2_k.) */
    rugo_real e1[36], e2[36];
    for (int q = 0; q < 36; ++q)
        e1[q] = e2[q] = 0.0;
    for (int m = 0; m < 6; ++m)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 3; ++k)
                e1[6 * m + j + k] += W32[j][k] * h1[4 * m + j];
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            const rugo_real w = W32[i][k];
            rugo_real* row = e2 + 6 * (i + k);
            for (int n = 0; n < 6; ++n)
                row[n] += w * h2[6 * i + n];
        }
    /* (the centre's values are needed from here on only) */
    *ec = rugo__eval_pair(c, 0.5 * (bx.s0 + bx.s1), 0.5 * (bx.t0 + bx.t1));
    const rugo_real jc[4] = {ec->j11, ec->j12, ec->j21, ec->j22};
    rugo_real p[36];
    for (int r = 0; r < 2; ++r) {
        rugo_real a = r == 0 ? jc[3] : -jc[2], b = r == 0 ? -jc[1] : jc[0];
        for (int k = 0; k < 36; ++k)
            p[k] = a * e1[k] + b * e2[k];
        if (rugo__one_sign(p, 36, 2.0 * (fabs(a) * tau1 + fabs(b) * tau2)) != 0) return 1;
    }
    return hull_left(c, whole, F, G);
}

/* Dedupe radius of a stationary root from the values e there. */
static rugo_real stat_radius_of(const pair_eval* e) {
    rugo_real det = fabs(e->j11 * e->j22 - e->j12 * e->j21);
    rugo_real fro = e->j11 * e->j11 + e->j12 * e->j12 + e->j21 * e->j21 + e->j22 * e->j22;
    return rugo__root_radius(det > 0.0 ? fro / det : INFINITY);
}

/* Newton found a root (s, t) of the stationary system (form mode) outside box b. If
 * the interval Jacobian is regular on a box E spanning b and a ball about the root, E holds at most
 * one root of that system, the certain one in the ball (existence as in rugo__search_stationary), which
 * lies outside b: b holds no stationary pair. (Every stationary pair in b is a root of the form, which
 * was chosen for b; what the form does outside b only matters through the uniqueness on E.) Without
 * this, a root just beyond a box edge (typically a minimum in the neighbouring segment) makes the
 * search subdivide toward that edge down to the root's distance. */
static int stat_excluded(const narrow_ctx* c, int mode, box b, rugo_real s, rugo_real t,
                         const pair_eval* ev) {
    box e;
    rugo_real r0;
    if (!rugo__exclusion_box(b, s, t, &e, &r0)) return 0;
    rugo_vec2 F[4], G[4], dF[3], dG[3], ddF[2], ddG[2];
    rugo__sub_bezier(c->f, 3, e.s0, e.s1, F);
    rugo__sub_bezier(c->g, 3, e.t0, e.t1, G);
    rugo__sub_bezier(c->df, 2, e.s0, e.s1, dF);
    rugo__sub_bezier(c->dg, 2, e.t0, e.t1, dG);
    rugo__sub_bezier(c->ddf, 1, e.s0, e.s1, ddF);
    rugo__sub_bezier(c->ddg, 1, e.t0, e.t1, ddG);
    ival J[4];
    stat_jacobian(mode, F, G, dF, dG, ddF, ddG, J);
    rugo_real detmin, jmax;
    if (!jacobian_regular(J, &detmin, &jmax)) return 0;
    rugo_real w[2], n[2], j[4];
    stat_system(ev, mode, w, n, j);
    /* distance to the root <= |system|_2 / sigma_min, sigma_min >= detmin / (2 jmax) */
    const rugo_real rho = 4.0 * (rugo__max(fabs(w[0]), fabs(w[1])) + rugo__max(n[0], n[1])) * jmax / detmin;
    return rho < r0;
}

void rugo__search_stationary(narrow_ctx* c) {
    box st[STACK_MAX];
    int ns = 0, boxes = 0;
    piece_memo mf, mg;
    rugo__memo_init(&mf);
    rugo__memo_init(&mg);
    rugo__push_box(st, &ns, 0.0, 1.0, 0.0, 1.0);
    while (ns > 0) {
        box b = st[--ns];
        if (rugo__box_covered(c->stat, c->nstat, b)) continue;
        if (++boxes > BOX_BUDGET) {
            c->overflow = 1;
            ++c->fallback;
            return;
        }
        rugo__memo_range(&mf, c->f, c->df, b.s0, b.s1);
        rugo__memo_range(&mg, c->g, c->dg, b.t0, b.t1);
        const rugo_vec2 *F = mf.P, *G = mg.P, *dF = mf.dP, *dG = mg.dP;
        rugo_real sc = 0.5 * (b.s0 + b.s1), tc = 0.5 * (b.t0 + b.t1);
        pair_eval ec;
        if (stat_prune(c, b, F, G, dF, dG, &ec)) continue;
        rugo__memo_dd(&mf, c->ddf);
        rugo__memo_dd(&mg, c->ddg);
        const rugo_vec2 *ddF = mf.ddP, *ddG = mg.ddP;
        int mode =
            rugo__hodograph_nonzero(dG) ? STAT_CH2 : (rugo__hodograph_nonzero(dF) ? STAT_CH1 : STAT_HH);
        ival J[4];
        stat_jacobian(mode, F, G, dF, dG, ddF, ddG, J);
        {
            rugo_real v[2], n[2], jc[4];
            stat_system(&ec, mode, v, n, jc);
            if (rugo__krawczyk_excludes(b, v, n, jc, J[0], J[1], J[2], J[3])) continue;
        }
        rugo_real detmin, jmax;
        if (jacobian_regular(J, &detmin, &jmax)) {
            rugo_real s = sc, t = tc, res;
            pair_eval e; /* rugo__eval_pair(c, s, t) at the root */
            if (rugo__newton_stat(c, mode, &b, &s, &t, &res, &ec, &e)) {
                /* existence: |system| <= 2 n at the root and sigma_min(J) >= detmin / (2 jmax) */
                rugo_real v[2], n[2], j[4];
                stat_system(&e, mode, v, n, j);
                rugo_real rho = 4.0 * rugo__max(n[0], n[1]) * jmax / detmin;
                /* (a root on a box edge, e.g. by symmetry, with a ball larger than SLACK: accept when
                 * the ball is small against the box) */
                if (rugo__in_box_ball(b, s, t, rho) ||
                    (rugo__in_box(b, s, t) && rho <= 0.125 * rugo__min(b.s1 - b.s0, b.t1 - b.t0))) {
                    if (!rugo__add_root(c->stat, &c->nstat, TMP_STAT, s, t, stat_radius_of(&e), 0, 0)) {
                        c->overflow = 1;
                        return;
                    }
                    continue;
                }
                if (stat_excluded(c, mode, b, s, t, &e)) continue;
            }
        } else if (rugo__max(b.s1 - b.s0, b.t1 - b.t0) <= H_ACC) {
            /* Small but still not certified: a (nearly) degenerate stationary pair, e.g. curves almost
             * touching, where the Hessian is nearly singular along a long valley. Accept the Newton
             * root if it lies in the box, and consider everything within R_MERGE resolved. */
            rugo_real s = sc, t = tc, res;
            if (rugo__newton_stat(c, mode, &b, &s, &t, &res, &ec, NULL) && rugo__in_box(b, s, t)) {
                ++c->fallback;
                if (!rugo__add_root(c->stat, &c->nstat, TMP_STAT, s, t, R_MERGE, 0, 1)) {
                    c->overflow = 1;
                    return;
                }
                continue;
            }
        }
        if (rugo__split_box(st, &ns, b, rugo__polygon_diameter(F, 3), rugo__polygon_diameter(G, 3))) continue;
        /* A leaf. */
        ++c->fallback;
        rugo_real s = sc, t = tc, res;
        rugo__newton_stat(c, mode, &b, &s, &t, &res, &ec, NULL);
        if (res <= 1024.0 && rugo__in_domain(s, t)) {
            if (!rugo__add_root(c->stat, &c->nstat, TMP_STAT, s, t, R_MERGE, 0, 1)) {
                c->overflow = 1;
                return;
            }
        }
    }
}
