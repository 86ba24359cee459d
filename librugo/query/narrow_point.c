/* A piece against a point: the stationary points of the distance from a cubic piece to a point, the
 * roots in [0, 1] of (f(s) - c)·f'(s) (a quintic, curve/poly.c), each classified (with one-sided
 * minima at ends where the piece stops, and point-like pieces that cannot see their own kind).
 * rugo__narrow_point is the primitives' vertex query; the piece-against-piece driver uses the same
 * core when a piece is a point and at zero-speed ends. Separate because it needs no subdivision: one
 * polynomial, solved directly. */
#include "query/narrow_internal.h"

#include "curve/poly.h"

/* The point query in a local frame: a[] are the Bezier points of f - c (already scaled). Writes
 * parameters, local distances and kinds; returns the count (<= 6). */
int rugo__point_stationary(const rugo_vec2 a[4], rugo_real cutoff, rugo_real* s_out, rugo_real* d_out,
                           int* k_out) {
    /* f(s) - c = A0 + A1 s + A2 s^2 + A3 s^3 */
    rugo_vec2 A0 = a[0];
    rugo_vec2 A1 = rugo_v2_scale(3.0, rugo_v2_sub(a[1], a[0]));
    rugo_vec2 A2 = rugo_v2_scale(3.0, rugo_v2_add(rugo_v2_sub(a[2], rugo_v2_scale(2.0, a[1])), a[0]));
    rugo_vec2 A3 =
        rugo_v2_sub(rugo_v2_add(rugo_v2_sub(a[3], rugo_v2_scale(3.0, a[2])), rugo_v2_scale(3.0, a[1])), a[0]);
    rugo_real p[6];
    p[0] = rugo_v2_dot(A0, A1);
    p[1] = 2.0 * rugo_v2_dot(A0, A2) + rugo_v2_dot(A1, A1);
    p[2] = 3.0 * rugo_v2_dot(A0, A3) + 3.0 * rugo_v2_dot(A1, A2);
    p[3] = 4.0 * rugo_v2_dot(A1, A3) + 2.0 * rugo_v2_dot(A2, A2);
    p[4] = 5.0 * rugo_v2_dot(A2, A3);
    p[5] = 3.0 * rugo_v2_dot(A3, A3);
    rugo_real sa = rugo__v2_norm(A0) + rugo__v2_norm(A1) + rugo__v2_norm(A2) + rugo__v2_norm(A3);
    rugo_real sd = rugo__v2_norm(A1) + 2.0 * rugo__v2_norm(A2) + 3.0 * rugo__v2_norm(A3);
    rugo_real roots[RUGO__POLY_MAX_ROOTS];
    int n = rugo__poly_roots(p, 5, 0.0, 1.0, 16.0 * EPS * sa * sd, roots);
    int count = 0;
    /* A point-like piece (a segment of four or more coincident control points, to round-off of the
     * caller's coordinates, or a piece a billion times smaller than its distance to c): one stationary
     * point, s = 0, whose kind the piece cannot see (its polynomial is round-off): a minimum unless the
     * neighbouring segments, which reach the point at their ends, say otherwise (RUGO__END_MINIMUM), or
     * a touching. */
    const rugo_real extent = rugo__piece_extent(a);
    if (n == RUGO__POLY_ALL || extent <= POINT_TOL || extent <= 1e-9 * rugo__v2_max_abs(a[0])) {
        rugo_real d = rugo__v2_norm(A0);
        if (d <= cutoff) {
            s_out[0] = 0.0;
            d_out[0] = d;
            k_out[0] = d <= TAU_TOUCH ? RUGO__MINIMUM : RUGO__END_MINIMUM;
            count = 1;
        }
        return count;
    }
    /* An end where the piece stops (zero speed: a corner) is stationary whatever the rest of the
     * polynomial does, but it is a multiple root there, which need not change sign: make sure it is a
     * candidate. */
    {
        const rugo_vec2 fp1 = rugo_v2_add(A1, rugo_v2_add(rugo_v2_scale(2.0, A2), rugo_v2_scale(3.0, A3)));
        const int zero0 = rugo__zero_speed(A1, sd), zero1 = rugo__zero_speed(fp1, sd);
        /* roots near such an end are that end (rugo__near_end); then one each */
        int m = 0;
        for (int i = 0; i < n; ++i) {
            rugo_real u = roots[i];
            if (zero0 && u <= END_ZONE) u = 0.0;
            if (zero1 && u >= 1.0 - END_ZONE) u = 1.0;
            if (m == 0 || u != roots[m - 1]) roots[m++] = u;
        }
        n = m;
        if (zero0 && (n == 0 || roots[0] != 0.0) && n < RUGO__POLY_MAX_ROOTS) {
            for (int i = n; i > 0; --i)
                roots[i] = roots[i - 1];
            roots[0] = 0.0;
            ++n;
        }
        if (zero1 && (n == 0 || roots[n - 1] != 1.0) && n < RUGO__POLY_MAX_ROOTS) roots[n++] = 1.0;
    }
    for (int i = 0; i < n && count < 6; ++i) {
        rugo_real s = roots[i];
        rugo_vec2 r = rugo__bezier_eval(a, 3, s);
        rugo_real d = rugo__v2_norm(r);
        if (!(d <= cutoff)) continue;
        rugo_vec2 fp = rugo_v2_add(
            A1, rugo_v2_scale(s, rugo_v2_add(rugo_v2_scale(2.0, A2), rugo_v2_scale(3.0 * s, A3))));
        rugo_vec2 fpp = rugo_v2_add(rugo_v2_scale(2.0, A2), rugo_v2_scale(6.0 * s, A3));
        rugo_real second = rugo_v2_dot(fp, fp) + rugo_v2_dot(r, fpp);
        rugo_real scale = rugo_v2_dot(fp, fp) + d * rugo__v2_norm(fpp);
        int kind;
        /* At an end where the piece stops (zero speed: a corner of coincident control points) a minimum is
         * one-sided (rugo__classify_stationary), and f' and f'' are round-off there (of the coordinates,
         * which can be much larger than the piece): the probe decides, looking along the piece only. */
        const int end = rugo__near_end(s) && rugo__zero_speed(fp, sd);
        if (d <= TAU_TOUCH) {
            kind = RUGO__MINIMUM;
        } else if (!end && second > 1e3 * EPS * scale) {
            kind = RUGO__MINIMUM;
        } else if (!end && second < -1e3 * EPS * scale) {
            kind = RUGO__MAXIMUM;
        } else {
            /* Degenerate: compare the distance a little to both sides (smallest telling step); where one
             * side leaves [0, 1], the side inside decides alone (probe_direction). */
            static const rugo_real delta[6] = {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2};
            kind = end ? RUGO__END_MINIMUM : RUGO__MINIMUM;
            rugo_real d0 = rugo_v2_dot(r, r);
            for (int k = 0; k < 6; ++k) {
                const rugo_real sp = s + delta[k], sm = s - delta[k];
                rugo_vec2 rp = rugo__bezier_eval(a, 3, sp), rm = rugo__bezier_eval(a, 3, sm);
                rugo_real up = rugo_v2_dot(rp, rp) - d0, um = rugo_v2_dot(rm, rm) - d0;
                rugo_real noise = 32.0 * EPS * sa * (d + EPS * sa);
                const int inp = rugo__in_unit(sp), inm = rugo__in_unit(sm);
                if (inp != inm) {
                    const rugo_real u1 = inp ? up : um;
                    if (fabs(u1) > noise) {
                        kind = u1 > 0.0 ? RUGO__END_MINIMUM : RUGO__SADDLE;
                        break;
                    }
                    continue;
                }
                if (fabs(up) > noise && fabs(um) > noise) {
                    kind = up > 0.0 && um > 0.0 ? (end ? RUGO__END_MINIMUM : RUGO__MINIMUM)
                                                : (up < 0.0 && um < 0.0 ? RUGO__MAXIMUM : RUGO__SADDLE);
                    break;
                }
            }
        }
        s_out[count] = s;
        d_out[count] = d;
        k_out[count] = kind;
        ++count;
    }
    return count;
}

int rugo__narrow_point(const rugo_vec2 f[4], rugo_vec2 c, rugo_real cutoff, rugo__pair_point out[6]) {
    RUGO_ASSERT(f && out);
    if (!f || !out) return 0;
    if (!rugo__v2_finite(c) || !(cutoff >= 0.0)) return 0;
    for (int i = 0; i < 4; ++i)
        if (!rugo__v2_finite(f[i])) return 0;
    /* Local frame: relative to c, scaled by a power of two. */
    rugo_real ext = 0.0;
    for (int i = 0; i < 4; ++i)
        ext = rugo__max(ext, rugo__v2_max_abs(rugo_v2_sub(f[i], c)));
    if (!isfinite(ext)) return 0;
    rugo_real scale = 1.0, inv = 1.0;
    if (ext > 0.0) {
        int e;
        frexp(ext, &e);
        scale = ldexp(1.0, e);
        inv = ldexp(1.0, -e);
    }
    rugo_vec2 a[4];
    for (int i = 0; i < 4; ++i)
        a[i] = rugo_v2_scale(inv, rugo_v2_sub(f[i], c));
    rugo_real ps[6], pd[6];
    int pk[6];
    int n = rugo__point_stationary(a, cutoff * inv, ps, pd, pk);
    for (int i = 0; i < n; ++i) {
        out[i].s = ps[i];
        out[i].t = 0.0;
        out[i].pa = rugo_v2_add(c, rugo_v2_scale(scale, rugo__bezier_eval(a, 3, ps[i])));
        out[i].pb = c;
        out[i].distance = scale * pd[i];
        out[i].kind = pk[i];
        out[i].flat = 0;
    }
    return n;
}
