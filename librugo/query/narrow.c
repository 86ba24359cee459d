/* The narrow phase between two cubic Bezier pieces (narrow.h; SPEC 8; DESIGN "Contact semantics"): its
 * driver. It sets up the local frame, sends degenerate pairs to their own paths (a point-like piece to
 * the point query, straight parallel pieces to the end pairs of their overlap), runs the two searches
 * on the general case, merges what they found and writes the result; rugo__narrow_line is the same
 * with the second piece a straight segment. The parts, each in its own file: the bounds that prune a
 * box (narrow_bounds.c), the root lists and box stack (narrow_roots.c), the search for crossings
 * (narrow_crossings.c) and for stationary pairs (narrow_stationary.c), the kinds of stationary pairs
 * (narrow_classify.c), and a piece against a point (narrow_point.c); narrow_internal.h holds what they
 * share.
 *
 * Frame. Everything runs in a local frame: the centroid of the 8 control points is subtracted (exact,
 * by Sterbenz, for pieces far from the origin) and the result scaled by a power of two so that every
 * coordinate lies in [-1, 1]. Tolerances are in that frame, i.e. relative to the pieces' size;
 * results are mapped back at the end (parameters are frame-free; distances are exact rescalings).
 *
 * Subdivision. Both searches walk the parameter square depth first with a fixed stack of boxes
 * (s0,s1,t0,t1). On each box the sub-pieces, their hodographs and second derivatives are extracted
 * afresh from the original Bezier points (two de Casteljau splits; no round-off accumulates with
 * depth); the piece with the larger control polygon is split. Limits: boxes narrower than 2^-26 in
 * both parameters are leaves, at most BOX_BUDGET boxes per search (then overflow), at most
 * NEWTON_MAX steps per Newton run, and a Newton run stops when it leaves its box's neighbourhood.
 *
 * Transversal crossings are not reported as stationary pairs; a touching (kind 0) crossing is always
 * also a minimum, and a minimum at distance <= TAU_TOUCH always also a touching crossing.
 *
 * Degenerate input: a point-like piece (extent <= 1e-13 of the frame) reduces to the point query,
 * with parameter 0 for the point piece; straight parallel pieces (cross(f', g') zero within
 * round-off) get the two end pairs of the overlap of their ranges as minima (overflow only when they
 * coincide: infinitely many crossings, reported as the two end pairs of kind 0); coincident curved
 * pieces fill the root lists (or the box budget) and set overflow; the stationary search is then
 * skipped (every pair on the common stretch is a touching). `fallback` counts the decisions taken
 * without a uniqueness certificate: leaves, touchings, small-box acceptances, budget exhaustion.
 * Non-finite input gives an empty result; a NaN or negative cutoff gives crossings only.
 *
 * Speed: most pairs a contact query hands over are near each other but hold nothing. The whole
 * square is tested once for both searches (hulls apart: no crossing; then the tangent cones: no
 * stationary pair), and a pair decided there costs a frame and those two tests. The hull test stops
 * at the first separating direction, and near the cutoff it first checks whether two control points
 * are closer than the cutoff (then no direction can separate). The Bernstein tests of the stationary
 * search first look at their corner coefficients, which decide most failures. A box whose Newton run
 * ends at a certified root outside it is dropped when the Jacobian is regular on a box spanning both
 * (crossings: the tangent cones stay apart), because then that root is the only one there; otherwise
 * a minimum just across a segment joint would make the search subdivide toward the joint. Each
 * shortcut decides a box as the full tests would, or drops a box that provably holds no root, so the
 * results are the same bits with or without it (on all segment pairs of bench_queries; only the
 * number of Newton steps differs). Work is not repeated: a search keeps the sub-pieces of the last
 * box's parameter ranges (piece_memo: the next box usually keeps one of them), Newton starts from the
 * values the box tests already computed at the centre and hands back those at its root,
 * rugo__cone_sign skips the lengths when the cross products are not even of one sign, and the
 * stationary search runs its rarely pruning hull test last (the tests are pure: their order does not
 * change the answer). */
#include "query/narrow_internal.h"

#include "curve/poly.h"

#include <stdint.h>
#include <string.h>

static void fill_point(const narrow_ctx* c, rugo_real s, rugo_real t, int kind, rugo__pair_point* p) {
    rugo_vec2 a = rugo__bezier_eval(c->f, 3, s), b = rugo__bezier_eval(c->g, 3, t);
    memset(p, 0, sizeof *p); /* padding too: results compare bytewise (the arrays are not cleared) */
    p->s = s;
    p->t = t;
    p->pa = rugo_v2_add(c->origin, rugo_v2_scale(c->scale, a));
    p->pb = rugo_v2_add(c->origin, rugo_v2_scale(c->scale, b));
    p->distance = c->scale * rugo__v2_norm(rugo_v2_sub(a, b));
    p->kind = kind;
}

static void sort_roots(root* p, int n) {
    for (int i = 1; i < n; ++i) {
        root x = p[i];
        int j = i - 1;
        while (j >= 0 && (p[j].s > x.s || (p[j].s == x.s && p[j].t > x.t))) {
            p[j + 1] = p[j];
            --j;
        }
        p[j + 1] = x;
    }
}

static void emit_crossing(const narrow_ctx* c, rugo__narrow_result* out, rugo_real s, rugo_real t, int kind) {
    if (out->crossing_count >= RUGO__NARROW_MAX_CROSSINGS) {
        out->overflow = 1;
        return;
    }
    fill_point(c, s, t, kind, &out->crossings[out->crossing_count++]);
}

static void emit_stationary(const narrow_ctx* c, rugo__narrow_result* out, rugo_real s, rugo_real t,
                            int kind) {
    if (out->stationary_count >= RUGO__NARROW_MAX_STATIONARY) {
        out->overflow = 1;
        return;
    }
    fill_point(c, s, t, kind, &out->stationary[out->stationary_count++]);
}

/* One piece (index `which`: 0 = f, 1 = g) is a point: the point query against the other. */
static void point_piece_path(narrow_ctx* c, int which, rugo__narrow_result* out) {
    const rugo_vec2* curve = which == 0 ? c->g : c->f;
    rugo_vec2 pt = which == 0 ? c->f[0] : c->g[0];
    rugo_vec2 a[4];
    for (int i = 0; i < 4; ++i)
        a[i] = rugo_v2_sub(curve[i], pt);
    rugo_real ps[6], pd[6];
    int pk[6];
    rugo_real cutoff = c->cutoff >= TAU_TOUCH ? c->cutoff : TAU_TOUCH;
    int n = rugo__point_stationary(a, cutoff, ps, pd, pk);
    for (int i = 0; i < n; ++i) {
        rugo_real s = which == 0 ? 0.0 : ps[i], t = which == 0 ? ps[i] : 0.0;
        if (pd[i] <= TAU_TOUCH) emit_crossing(c, out, s, t, 0);
        /* The point piece's own curve continues in the neighbouring segments: a minimum along the other
         * piece is one-sided as far as this call can see (rugo__point_stationary's point-like case). */
        const int kind = pk[i] == RUGO__MINIMUM && pd[i] > TAU_TOUCH ? RUGO__END_MINIMUM : pk[i];
        if (c->cutoff >= 0.0 && pd[i] <= c->cutoff) emit_stationary(c, out, s, t, kind);
    }
}

/* Parameters in [0,1] where the scalar cubic with Bezier coefficients b[] takes the value x; the
 * first one, or the end whose value is nearest if round-off put x just outside the range. */
static rugo_real solve_cubic_value(const rugo_real b[4], rugo_real x) {
    rugo_real q[4];
    q[0] = b[0] - x;
    q[1] = 3.0 * (b[1] - b[0]);
    q[2] = 3.0 * (b[2] - 2.0 * b[1] + b[0]);
    q[3] = b[3] - 3.0 * b[2] + 3.0 * b[1] - b[0];
    rugo_real roots[RUGO__POLY_MAX_ROOTS];
    rugo_real tol = 8.0 * EPS * (fabs(b[0]) + fabs(b[1]) + fabs(b[2]) + fabs(b[3]) + fabs(x));
    int n = rugo__poly_roots(q, 3, 0.0, 1.0, tol, roots);
    if (n > 0) return roots[0];
    return fabs(b[0] - x) <= fabs(b[3] - x) ? 0.0 : 1.0;
}

/* Range of a scalar cubic (Bezier coefficients) over [0,1]. */
static void cubic_range(const rugo_real b[4], rugo_real* lo, rugo_real* hi) {
    rugo_real d[3];
    d[0] = 3.0 * (b[1] - b[0]);
    d[1] = 6.0 * (b[2] - 2.0 * b[1] + b[0]);
    d[2] = 3.0 * (b[3] - 3.0 * b[2] + 3.0 * b[1] - b[0]);
    rugo_real roots[RUGO__POLY_MAX_ROOTS];
    int n = rugo__poly_roots(d, 2, 0.0, 1.0, 0.0, roots);
    *lo = rugo__min(b[0], b[3]);
    *hi = rugo__max(b[0], b[3]);
    for (int i = 0; i < n; ++i) {
        rugo_real u = roots[i], v = 1.0 - u;
        rugo_real val = v * v * v * b[0] + 3.0 * v * v * u * b[1] + 3.0 * v * u * u * b[2] + u * u * u * b[3];
        *lo = rugo__min(*lo, val);
        *hi = rugo__max(*hi, val);
    }
}

/* Straight parallel pieces: the pairs at both ends of the overlap of their ranges along the common
 * line (a continuum of stationary pairs in between; infinitely many crossings if they coincide). */
static void parallel_path(narrow_ctx* c, rugo__narrow_result* out) {
    const rugo_vec2* p = rugo__piece_extent(c->f) >= rugo__piece_extent(c->g) ? c->f : c->g;
    rugo_vec2 u = rugo_v2(1.0, 0.0);
    rugo_real best = -1.0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            rugo_vec2 d = rugo_v2_sub(p[j], p[i]);
            rugo_real l = rugo__v2_norm(d);
            if (l > best) {
                best = l;
                u = rugo_v2(d.x / l, d.y / l);
            }
        }
    rugo_real a[4], b[4];
    for (int i = 0; i < 4; ++i) {
        a[i] = rugo_v2_dot(u, c->f[i]);
        b[i] = rugo_v2_dot(u, c->g[i]);
    }
    rugo_real alo, ahi, blo, bhi;
    cubic_range(a, &alo, &ahi);
    cubic_range(b, &blo, &bhi);
    rugo_real lo = rugo__max(alo, blo), hi = rugo__min(ahi, bhi);
    if (lo > hi + TAU_F) return; /* side by side without overlap: no stationary pair, no crossing */
    if (hi < lo) lo = hi = 0.5 * (lo + hi);
    rugo_real ends[2] = {lo, hi};
    int nend = hi - lo > TAU_F ? 2 : 1;
    rugo_real ss[2], ts[2], dmax = 0.0;
    for (int k = 0; k < nend; ++k) {
        ss[k] = solve_cubic_value(a, ends[k]);
        ts[k] = solve_cubic_value(b, ends[k]);
        const rugo_vec2 d = rugo_v2_sub(rugo__bezier_eval(c->f, 3, ss[k]), rugo__bezier_eval(c->g, 3, ts[k]));
        dmax = rugo__max(dmax, rugo__v2_norm(d));
    }
    if (dmax <= TAU_TOUCH) {
        if (nend == 2) out->overflow = 1; /* coincident: infinitely many crossings */
        for (int k = 0; k < nend; ++k)
            emit_crossing(c, out, ss[k], ts[k], 0);
    }
    if (c->cutoff >= 0.0 && dmax <= c->cutoff)
        for (int k = 0; k < nend; ++k)
            emit_stationary(c, out, ss[k], ts[k], RUGO__MINIMUM);
}

/* An end where a piece stops (zero speed: a sharp corner, three coincident control points) is
 * stationary in that piece's parameter whatever the other piece does, so its stationary pairs are the
 * end against the other piece's stationary points to it (the point query). The search can miss them:
 * the root is multiple and need not change sign, or, when rounding leaves the end's speed a few ulps
 * off zero, there is no exact root at all. They are added here unless the search has one there; the
 * classification then looks along the pieces (rugo__classify_stationary). */
static void add_zero_speed_ends(narrow_ctx* c) {
    for (int which = 0; which < 2; ++which) {
        const rugo_vec2* p = which == 0 ? c->f : c->g;
        const rugo_vec2* h = which == 0 ? c->df : c->dg;
        const rugo_vec2* other = which == 0 ? c->g : c->f;
        for (int end = 0; end < 2; ++end) {
            if (!rugo__speed_vanishes(h[end ? 2 : 0], h)) continue;
            rugo_vec2 a[4];
            for (int i = 0; i < 4; ++i)
                a[i] = rugo_v2_sub(other[i], p[end ? 3 : 0]);
            rugo_real us[6], ds[6];
            int ks[6];
            const int n = rugo__point_stationary(a, c->cutoff, us, ds, ks);
            for (int i = 0; i < n; ++i) {
                const rugo_real s = which == 0 ? (rugo_real)end : us[i],
                                t = which == 0 ? us[i] : (rugo_real)end;
                if (rugo__near_root(c->stat, c->nstat, s, t, END_ZONE)) continue;
                if (!rugo__add_root(c->stat, &c->nstat, TMP_STAT, s, t, R_MERGE, 0, 1)) {
                    c->overflow = 1;
                    return;
                }
            }
        }
    }
}

/* The general case on a prepared context. */
static void solve(narrow_ctx* c, rugo__narrow_result* out) {
    rugo_real mf = 0.0, mg = 0.0, cmax = 0.0;
    for (int i = 0; i < 3; ++i) {
        mf = rugo__max(mf, rugo__v2_max_abs(c->df[i]));
        mg = rugo__max(mg, rugo__v2_max_abs(c->dg[i]));
        for (int j = 0; j < 3; ++j) {
            c->root_cross[3 * i + j] = rugo_v2_cross(c->df[i], c->dg[j]);
            cmax = rugo__max(cmax, fabs(c->root_cross[3 * i + j]));
        }
    }
    {
        /* Both pieces points at this distance (two segments of four or more coincident control points,
         * whose Bezier points differ by round-off of the caller's coordinates, which can be far larger
         * than this frame): one pair, which neither piece can classify (rugo__point_stationary's
         * point-like case). */
        const rugo_real ef = rugo__piece_extent(c->f), eg = rugo__piece_extent(c->g);
        const rugo_real gap = rugo__v2_max_abs(rugo_v2_sub(c->f[0], c->g[0]));
        if (ef <= 1e-9 * gap && eg <= 1e-9 * gap) {
            const rugo_real d = rugo__v2_norm(rugo_v2_sub(c->f[0], c->g[0]));
            if (c->cutoff >= 0.0 && d <= c->cutoff) emit_stationary(c, out, 0.0, 0.0, RUGO__END_MINIMUM);
            return;
        }
    }
    if (rugo__piece_extent(c->g) <= POINT_TOL) {
        point_piece_path(c, 1, out);
        return;
    }
    if (rugo__piece_extent(c->f) <= POINT_TOL) {
        point_piece_path(c, 0, out);
        return;
    }
    if (cmax <= 1024.0 * EPS * mf * mg) {
        parallel_path(c, out);
        return;
    }

    /* The whole square first: both searches start there with the hull test (crossings: gap > TAU_F;
     * stationary pairs: gap > cutoff + TAU_F, then the tangent cones). When it decides everything,
     * the searches are skipped; when a search runs, the hull test of the stationary search on the
     * whole square is known to fail (gap <= TAU_F, or it was tested below), so stat_prune skips it. */
    c->root_apart = rugo__hull_gap_above(c->f, c->g, TAU_F);
    if (c->root_apart) {
        if (!(c->cutoff >= 0.0)) return;                                 /* no stationary search */
        if (rugo__whole_square_cone(c) != 0) return;                     /* tangents nowhere parallel */
        if (rugo__hull_gap_above(c->f, c->g, c->cutoff + TAU_F)) return; /* apart beyond the cutoff */
    }

    rugo__search_crossings(c);
    /* Classify the leaf roots by probing; certified roots carry the sign of their cone. */
    for (int i = 0; i < c->ncross; ++i)
        if (c->cross[i].kind == KIND_PROBE)
            c->cross[i].kind = rugo__probe_crossing_kind(c, c->cross[i].s, c->cross[i].t);

    /* Crossings beyond count mean (nearly) coincident curves: every pair on the common stretch is a
     * touching, so the stationary search would only fill up with them; the touching crossings below
     * stand for them. */
    if (c->cutoff >= 0.0 && !c->overflow) {
        rugo__search_stationary(c);
        add_zero_speed_ends(c);
    }

    /* Touching crossings are minima too. */
    for (int i = 0; i < c->ncross; ++i) {
        if (c->cross[i].kind != 0) continue;
        int found = 0;
        for (int k = 0; k < c->nstat && !found; ++k) {
            rugo_real r = rugo__max(R_FALLBACK, c->stat[k].radius);
            found = fabs(c->stat[k].s - c->cross[i].s) <= r && fabs(c->stat[k].t - c->cross[i].t) <= r;
            if (found) {
                /* keep the better-resolved point of the two: the one with the smaller distance */
                rugo_real dc = rugo__half_dist2(c, c->cross[i].s, c->cross[i].t);
                rugo_real ds = rugo__half_dist2(c, c->stat[k].s, c->stat[k].t);
                if (dc < ds) {
                    c->stat[k].s = c->cross[i].s;
                    c->stat[k].t = c->cross[i].t;
                }
            }
        }
        if (!found && c->cutoff >= 0.0) {
            if (c->nstat < TMP_STAT) {
                c->stat[c->nstat].s = c->cross[i].s;
                c->stat[c->nstat].t = c->cross[i].t;
                c->stat[c->nstat].radius = R_FALLBACK;
                c->stat[c->nstat].kind = 0;
                c->stat[c->nstat].fallback = 1;
                ++c->nstat;
            } else {
                c->overflow = 1;
            }
        }
    }

    /* Stationary pairs: distance, kind; drop transversal crossings; minima at distance ~0 are
     * touching crossings. */
    int ncross_found = c->ncross;
    for (int k = 0; k < c->nstat; ++k) {
        rugo_real s = rugo__clamp01(c->stat[k].s), t = rugo__clamp01(c->stat[k].t);
        rugo__snap_to_zero_speed_end(c, &s, &t);
        c->stat[k].s = s;
        c->stat[k].t = t;
        rugo_real dist =
            rugo__v2_norm(rugo_v2_sub(rugo__bezier_eval(c->f, 3, s), rugo__bezier_eval(c->g, 3, t)));
        c->stat[k].kind = -1; /* dropped */
        if (!(dist <= c->cutoff)) continue;
        if (dist <= TAU_TOUCH) {
            int match = -1;
            for (int i = 0; i < ncross_found && match < 0; ++i) {
                rugo_real r = rugo__max(R_FALLBACK, c->cross[i].radius);
                if (fabs(c->cross[i].s - s) <= r && fabs(c->cross[i].t - t) <= r) match = i;
            }
            if (match >= 0 && c->cross[match].kind != 0) continue;
            if (match < 0 && !rugo__add_root(c->cross, &c->ncross, TMP_CROSS, s, t, R_FALLBACK, 0, 1))
                c->overflow = 1;
        }
        c->stat[k].kind = rugo__classify_stationary(c, s, t, dist);
    }

    sort_roots(c->cross, c->ncross);
    for (int i = 0; i < c->ncross; ++i)
        emit_crossing(c, out, rugo__clamp01(c->cross[i].s), rugo__clamp01(c->cross[i].t), c->cross[i].kind);
    sort_roots(c->stat, c->nstat);
    for (int k = 0; k < c->nstat; ++k)
        if (c->stat[k].kind >= 0) emit_stationary(c, out, c->stat[k].s, c->stat[k].t, c->stat[k].kind);
}

/* scale = 2^e and inv = 2^-e with ext = m 2^e, m in [0.5, 1) (frexp), from the exponent bits when both
 * are normal numbers (the library calls frexp and ldexp cost as much as a hull test). */
static void pow2_frame(rugo_real ext, rugo_real* scale, rugo_real* inv) {
    uint64_t bits;
    memcpy(&bits, &ext, sizeof bits);
    const int biased = (int)((bits >> 52) & 0x7FF);
    const int e = biased - 1022;
    if (biased > 0 && e + 1023 >= 1 && e + 1023 <= 2046 && 1023 - e >= 1 && 1023 - e <= 2046) {
        const uint64_t bs = (uint64_t)(e + 1023) << 52, bi = (uint64_t)(1023 - e) << 52;
        memcpy(scale, &bs, sizeof *scale);
        memcpy(inv, &bi, sizeof *inv);
        return;
    }
    int ee;
    frexp(ext, &ee);
    *scale = ldexp(1.0, ee);
    *inv = ldexp(1.0, -ee);
}

/* Counts and flags only: the root arrays are written (padding included, fill_point) before they are
 * counted, and nobody reads past the counts (clearing ~1.4 kB per call was a tenth of the cost of an
 * apart pair). */
static void clear_result(rugo__narrow_result* out) {
    out->crossing_count = 0;
    out->stationary_count = 0;
    out->newton_iterations = 0;
    out->fallback = 0;
    out->overflow = 0;
}

/* Sets up the local frame from the 8 points (p: caller's frame) and runs the solver. */
static void run(const rugo_vec2 f[4], const rugo_vec2 g[4], int g_is_line, rugo_vec2 q0, rugo_vec2 q1,
                rugo_real cutoff, rugo__narrow_result* out) {
    clear_result(out);
    rugo_vec2 pts[8];
    for (int i = 0; i < 4; ++i)
        pts[i] = f[i];
    if (g_is_line) {
        pts[4] = q0;
        pts[5] = q1;
        pts[6] = q0;
        pts[7] = q1;
    } else {
        for (int i = 0; i < 4; ++i)
            pts[4 + i] = g[i];
    }
    for (int i = 0; i < 8; ++i)
        if (!rugo__v2_finite(pts[i])) return;
    narrow_ctx c; /* the root lists (~4 kB) are filled before they are counted: not cleared */
    c.newton = c.fallback = c.overflow = 0;
    c.ncross = c.nstat = 0;
    c.root_apart = 0;
    c.root_cone_done = c.root_cone = 0;
    c.root_rho = INFINITY;
    rugo_real ox = 0.0, oy = 0.0;
    for (int i = 0; i < 8; ++i) {
        ox += 0.125 * pts[i].x;
        oy += 0.125 * pts[i].y;
    }
    c.origin = rugo_v2(ox, oy);
    rugo_real ext = 0.0;
    for (int i = 0; i < 8; ++i)
        ext = rugo__max(ext, rugo__v2_max_abs(rugo_v2_sub(pts[i], c.origin)));
    if (!isfinite(ext)) return;
    if (ext == 0.0) {
        /* Both pieces are the same single point. */
        c.scale = 1.0;
        for (int i = 0; i < 4; ++i)
            c.f[i] = c.g[i] = rugo_v2(0.0, 0.0);
        c.cutoff = cutoff >= 0.0 ? 0.0 : -1.0;
        emit_crossing(&c, out, 0.0, 0.0, 0);
        if (cutoff >= 0.0) emit_stationary(&c, out, 0.0, 0.0, RUGO__MINIMUM);
        return;
    }
    rugo_real inv;
    pow2_frame(ext, &c.scale, &inv);
    for (int i = 0; i < 4; ++i)
        c.f[i] = rugo_v2_scale(inv, rugo_v2_sub(f[i], c.origin));
    if (g_is_line) {
        rugo_vec2 a = rugo_v2_scale(inv, rugo_v2_sub(q0, c.origin)),
                  b = rugo_v2_scale(inv, rugo_v2_sub(q1, c.origin));
        c.g[0] = a;
        c.g[1] = rugo__lerp(a, b, 1.0 / 3.0);
        c.g[2] = rugo__lerp(a, b, 2.0 / 3.0);
        c.g[3] = b;
    } else {
        for (int i = 0; i < 4; ++i)
            c.g[i] = rugo_v2_scale(inv, rugo_v2_sub(g[i], c.origin));
    }
    for (int i = 0; i < 3; ++i) {
        c.df[i] = rugo_v2_scale(3.0, rugo_v2_sub(c.f[i + 1], c.f[i]));
        c.dg[i] = rugo_v2_scale(3.0, rugo_v2_sub(c.g[i + 1], c.g[i]));
    }
    for (int i = 0; i < 2; ++i) {
        c.ddf[i] = rugo_v2_scale(2.0, rugo_v2_sub(c.df[i + 1], c.df[i]));
        c.ddg[i] = rugo_v2_scale(2.0, rugo_v2_sub(c.dg[i + 1], c.dg[i]));
    }
    c.cutoff = cutoff >= 0.0 ? cutoff * inv : -1.0; /* NaN: no stationary pairs */
    solve(&c, out);
    out->newton_iterations = c.newton;
    out->fallback = c.fallback;
    if (c.overflow) out->overflow = 1;
}

void rugo__narrow_pieces(const rugo_vec2 f[4], const rugo_vec2 g[4], rugo_real cutoff,
                         rugo__narrow_result* out) {
    RUGO_ASSERT(f && g && out);
    if (!out) return;
    if (!f || !g) {
        clear_result(out);
        return;
    }
    run(f, g, 0, rugo_v2(0.0, 0.0), rugo_v2(0.0, 0.0), cutoff, out);
}

void rugo__narrow_line(const rugo_vec2 f[4], rugo_vec2 q0, rugo_vec2 q1, rugo_real cutoff,
                       rugo__narrow_result* out) {
    RUGO_ASSERT(f && out);
    if (!out) return;
    if (!f) {
        clear_result(out);
        return;
    }
    run(f, NULL, 1, q0, q1, cutoff, out);
}
