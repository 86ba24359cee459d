/* The narrow phase of a shape against a primitive: one of A's pieces against every feature of B's
 * boundary — each edge (offset by R) through rugo__narrow_line, each vertex through rugo__narrow_point,
 * with the crossings of a vertex arc bracketed between the stationary points of the distance to the
 * vertex — recorded as hits in global parameters. Separate because it is the primitive's counterpart of
 * the piece-against-piece narrow phase that shape pairs call directly. */
#include "query/collide_internal.h"

#include <float.h>
#include <string.h>

/* |f(s) - v| - R: the distance from the piece (local frame, fl) to the vertex arc about vl. */
static rugo_real vertex_arc_gap(const rugo_vec2 fl[4], rugo_vec2 vl, rugo_real R, rugo_real s) {
    return rugo__v2_length(rugo_v2_sub(rugo__bezier_point(fl, s), vl)) - R;
}

/* A's side of a hit: segment ka at s, normalised, and its global parameter. */
static void hit_set_a(hit* h, int ka, rugo_real s, const primitive_pair* g) {
    h->sa = ka;
    h->ta = s;
    rugo__normalise_segment_param(&h->sa, &h->ta, g->A->n);
    h->ua = (rugo_real)h->sa + h->ta;
}

/* B's side of a hit: the boundary parameter w, wrapped, as feature sb (an arc or an edge) and t. */
static void hit_set_b(hit* h, rugo_real w, const primitive* P) {
    w = rugo__wrap_param(w, P->period);
    h->ub = w;
    h->sb = (int)floor(w);
    h->tb = w - floor(w);
}

/* The piece f of A's segment ka (fl: shifted by -o) against B's edges: their crossings into xs (if not
 * NULL) and stationary pairs into ss. */
static int piece_against_edges(rugo_collide_context* ctx, primitive_pair* g, int ka, const rugo_vec2 f[4],
                               const rugo_vec2 fl[4], rugo_vec2 o, rugo__array* xs, size_t* nx,
                               rugo__array* ss, size_t* ns) {
    const primitive* P = g->P;
    rugo_vec2 flo, fhi;
    rugo__bezier_bounds(f, &flo, &fhi);
    /* the bounds of the piece and B together: no pair of their points lies farther apart */
    const rugo_vec2 both_hi = rugo_v2(fmax(fhi.x, P->hi.x), fmax(fhi.y, P->hi.y));
    const rugo_vec2 both_lo = rugo_v2(fmin(flo.x, P->lo.x), fmin(flo.y, P->lo.y));
    const rugo_real reach =
        rugo__v2_length(rugo_v2_sub(both_hi, both_lo)) * (1.0 + 1e-9) + CUTOFF_PAD * g->scale;
    /* Edges (offset by R along their normals). A segment with R = 0 is one edge seen from both sides. */
    const int edges = P->V == 1 ? 0 : (P->V == 2 && P->R == 0.0 ? 1 : P->V);
    for (int e = 0; e < edges; ++e) {
        const rugo_vec2 off = rugo_v2_scale(P->R, P->m[e]);
        const rugo_vec2 q0 = rugo_v2_add(P->v[e], off), q1 = rugo_v2_add(P->v[(e + 1) % P->V], off);
        /* Only the part of the edge the piece projects onto can hold a crossing or a foot of the
         * piece's points (the piece lies in its control points' hull): the narrow phase gets that part
         * (padded), so that its frame, and with it its resolution, is the shape's size and not the
         * edge's (a long ground edge hid overlaps up to ~4e-14 W^2 deep, W its half-length in the
         * shape's units). Parameters map back onto the edge. */
        const rugo_vec2 ev = rugo_v2_sub(q1, q0);
        const rugo_real ee = rugo_v2_dot(ev, ev);
        rugo_real t0 = 0.0, t1 = 1.0;
        if (ee > 0.0) {
            rugo_real lo = HUGE_VAL, hi = -HUGE_VAL;
            for (int i = 0; i < 4; ++i) {
                const rugo_real t = rugo_v2_dot(rugo_v2_sub(f[i], q0), ev) / ee;
                lo = fmin(lo, t);
                hi = fmax(hi, t);
            }
            /* padded by the piece's projection and the shape's size on each side, so that every foot
             * lies well inside the part (classification probes along it) and the frame is the
             * shape's size even for a point-like piece */
            const rugo_real pad = (hi - lo) + g->scale / sqrt(ee);
            t0 = fmax(0.0, lo - pad);
            t1 = fmin(1.0, hi + pad);
            if (!(t0 < t1)) continue; /* the piece lies beyond the edge's ends: the vertices decide */
        }
        const rugo_vec2 c0 = t0 == 0.0 ? q0 : rugo_v2_add(q0, rugo_v2_scale(t0, ev));
        const rugo_vec2 c1 = t1 == 1.0 ? q1 : rugo_v2_add(q0, rugo_v2_scale(t1, ev));
        rugo__narrow_result r;
        rugo__narrow_line(fl, rugo_v2_sub(c0, o), rugo_v2_sub(c1, o), reach, &r);
        const int src = g->src++;
        if (g->stats != NULL) {
            g->stats->segment_pairs += 1;
            g->stats->newton_iterations += r.newton_iterations;
            g->stats->fallbacks += r.fallback > 0;
        }
        for (int pass = 0; pass < 2; ++pass) {
            const int cnt = pass == 0 ? r.crossing_count : r.stationary_count;
            const rugo__pair_point* pp = pass == 0 ? r.crossings : r.stationary;
            if (pass == 0 && xs == NULL) continue;
            for (int i = 0; i < cnt; ++i) {
                hit h;
                memset(&h, 0, sizeof h);
                hit_set_a(&h, ka, pp[i].s, g);
                /* the parameter on the whole edge */
                const rugo_real te = t0 == 0.0 && t1 == 1.0 ? pp[i].t : t0 + (t1 - t0) * pp[i].t;
                hit_set_b(&h, 2.0 * (rugo_real)e + 1.0 + te, P);
                h.pa = rugo_v2_add(pp[i].pa, o);
                h.pb = rugo_v2_add(pp[i].pb, o);
                h.nb = P->m[e];
                h.distance = pp[i].distance;
                h.kind = pp[i].kind;
                h.src = src;
                h.vertex = -1;
                if (!rugo__push_hit(ctx, pass == 0 ? xs : ss, pass == 0 ? nx : ns, &h)) return 0;
            }
        }
    }
    return 1;
}

/* The piece f of A's segment ka (fl: shifted by -o) against B's vertices: the stationary points of
 * the distance to each vertex (corner candidates for R = 0, points of its arc otherwise) into ss, and
 * the crossings of its arc into xs (if not NULL). */
static int piece_against_vertices(rugo_collide_context* ctx, primitive_pair* g, int ka, const rugo_vec2 f[4],
                                  const rugo_vec2 fl[4], rugo_vec2 o, rugo__array* xs, size_t* nx,
                                  rugo__array* ss, size_t* ns) {
    const primitive* P = g->P;
    for (int vi = 0; vi < P->V; ++vi) {
        const rugo_vec2 vl = rugo_v2_sub(P->v[vi], o);
        rugo__pair_point pp[6];
        const int cnt = rugo__narrow_point(fl, vl, HUGE_VAL, pp);
        const int src = g->src++;
        if (g->stats != NULL) g->stats->segment_pairs += 1;
        rugo_real brk[8];
        int nb = 0;
        brk[nb++] = 0.0;
        for (int i = 0; i < cnt; ++i) {
            const rugo_vec2 pa = rugo_v2_add(pp[i].pa, o);
            const rugo_vec2 d = rugo_v2_sub(pa, P->v[vi]);
            const rugo_real rho = rugo__v2_length(d);
            if (pp[i].s > 0.0 && pp[i].s < 1.0) brk[nb++] = pp[i].s;
            hit h;
            memset(&h, 0, sizeof h);
            hit_set_a(&h, ka, pp[i].s, g);
            h.pa = pa;
            h.src = src;
            h.kind = pp[i].kind;
            if (P->R == 0.0) {
                if (P->V == 2 && P->R == 0.0 && !(rho > 0.0)) continue;
                hit_set_b(&h, P->V == 1 ? 0.0 : 2.0 * (rugo_real)vi, P);
                h.pb = P->v[vi];
                h.nb = rugo_v2(0.0, 0.0);
                h.vertex = vi;
                h.distance = rho;
                if (!rugo__push_hit(ctx, ss, ns, &h)) return 0;
                continue;
            }
            if (!(rho > 0.0)) continue; /* the vertex itself on A: its arc's crossings cover it */
            const rugo_vec2 u = rugo_v2_scale(1.0 / rho, d);
            for (int side_ = 0; side_ < 2; ++side_) { /* near point of the arc, far point */
                const rugo_vec2 nb_ = side_ == 0 ? u : rugo_v2_scale(-1.0, u);
                const rugo_real w = rugo__primitive_arc_param(P, vi, nb_);
                if (w < 0.0) continue;
                hit k = h;
                hit_set_b(&k, w, P);
                k.pb = rugo_v2_add(P->v[vi], rugo_v2_scale(P->R, nb_));
                k.nb = nb_;
                k.vertex = -1;
                k.distance = rugo__v2_length(rugo_v2_sub(k.pb, k.pa));
                if (side_ == 1) k.kind = RUGO__SADDLE; /* never a minimum of the distance to B */
                if (!rugo__push_hit(ctx, ss, ns, &k)) return 0;
            }
        }
        if (xs == NULL || !(P->R > 0.0)) continue;
        /* Crossings of the arc: |f - v| - R changes sign between consecutive stationary points. */
        brk[nb++] = 1.0;
        for (int i = 1; i < nb; ++i) /* sort the few breakpoints */
            for (int j = i; j > 0 && brk[j] < brk[j - 1]; --j) {
                const rugo_real t = brk[j];
                brk[j] = brk[j - 1];
                brk[j - 1] = t;
            }
        for (int i = 0; i + 1 < nb; ++i) {
            rugo_real s0 = brk[i], s1 = brk[i + 1];
            if (!(s1 > s0)) continue;
            /* End values from the unshifted end points, which neighbouring segments share. */
            const rugo_real g0 = s0 == 0.0 ? rugo__v2_length(rugo_v2_sub(f[0], P->v[vi])) - P->R
                                           : vertex_arc_gap(fl, vl, P->R, s0);
            const rugo_real g1 = s1 == 1.0 ? rugo__v2_length(rugo_v2_sub(f[3], P->v[vi])) - P->R
                                           : vertex_arc_gap(fl, vl, P->R, s1);
            if ((g0 > 0.0) == (g1 > 0.0)) continue;
            const int entering = g0 > 0.0;
            for (int it = 0; it < 200 && s1 - s0 > 4.0 * DBL_EPSILON; ++it) {
                const rugo_real sm = 0.5 * (s0 + s1);
                if ((vertex_arc_gap(fl, vl, P->R, sm) > 0.0) == entering)
                    s0 = sm;
                else
                    s1 = sm;
            }
            const rugo_real s = 0.5 * (s0 + s1);
            const rugo_vec2 p = rugo_v2_add(rugo__bezier_point(fl, s), o);
            const rugo_vec2 d = rugo_v2_sub(p, P->v[vi]);
            const rugo_real w = rugo__primitive_arc_param(P, vi, rugo__v2_unit(d));
            if (w < 0.0) continue; /* crosses the circle outside this vertex's arc */
            hit h;
            memset(&h, 0, sizeof h);
            hit_set_a(&h, ka, s, g);
            hit_set_b(&h, w, P);
            h.pa = p;
            h.pb = p;
            h.nb = rugo__v2_unit(d);
            h.kind = entering ? -1 : 1;
            h.src = src;
            h.vertex = -1;
            if (!rugo__push_hit(ctx, xs, nx, &h)) return 0;
        }
    }
    return 1;
}

/* The narrow phase of A's segment ka against every feature of B: crossings into xs (if not NULL) and
 * every stationary pair (with B's normal or corner) into ss. */
int rugo__primitive_narrow(rugo_collide_context* ctx, primitive_pair* g, int ka, rugo__array* xs, size_t* nx,
                           rugo__array* ss, size_t* ns) {
    rugo_vec2 f[4], fl[4];
    rugo_contour_bezier(g->A->curve, ka, f);
    const rugo_vec2 o = f[0];
    for (int i = 0; i < 4; ++i)
        fl[i] = rugo_v2_sub(f[i], o);
    return piece_against_edges(ctx, g, ka, f, fl, o, xs, nx, ss, ns) &&
           piece_against_vertices(ctx, g, ka, f, fl, o, xs, nx, ss, ns);
}
