/* Shape against shape, rugo_collide_shapes: the plan that collide_internal.h describes (traversal, a
 * narrow pass on every candidate segment pair, crossings and the overlap regions they close, a second
 * narrow pass inside each region for its deepest penetration pair, the minima within the band,
 * containment), cut into its stages, with the helpers only it needs: support points and closest pairs
 * of two curves, the normal and the facing test of a minimum. Separate from the primitives because
 * both sides here are shapes, with trees, levels and surfaces. */
#include "query/collide_internal.h"

#include "curve/poly.h"
#include "query/narrow_resolved.h"
#include "rough/internal.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static rugo_vec2 normal_on_a(const shape_pair* g, int seg, rugo_real t) {
    return rugo__curve_normal(g->A->curve, seg, t);
}
static rugo_vec2 normal_on_b(const shape_pair* g, int seg, rugo_real t) {
    return rugo_rotate(g->rel.q, rugo__curve_normal(g->B->curve, seg, t));
}

/* What a narrow call is asked for: the first pass's crossings and minima within the band, an overlap
 * region's penetration pairs (saddles), or the closest pair of two curves one inside the other. */
typedef enum narrow_ask { ASK_FIRST_PASS, ASK_DEPTHS, ASK_CLOSEST } narrow_ask;

/* A side's segment k as a piece with its band (λ's two cubic halves, or the query's constant band). */
static void banded_piece(const shape_pair* g, const query_side* s, int k, const rugo_vec2 p[4],
                         rugo__banded_piece* out) {
    for (int i = 0; i < 4; ++i)
        out->p[i] = p[i];
    if (g->thesis_rule) { /* minima of the distance itself: no band in the narrow phase */
        memset(out->band, 0, sizeof out->band);
    } else if (g->override >= 0.0) {
        for (int h = 0; h < 2; ++h)
            for (int i = 0; i < 4; ++i)
                out->band[h][i] = g->override;
    } else {
        rugo__tolerance_halves(s->lambda, s->n, k, out->band);
    }
}

/* The round-off narrow phase finds the minima of the distance; with bands that vary (the shapes' own,
 * not a constant override) the band-adjusted rule wants those of φ = d - λ_A - λ_B. Where
 * band_minima_at_round_off (below) could not search for them (its box budget ran out), each minimum of
 * d is moved to the minimum of φ that Newton reaches from it on the two pieces (left where Newton does
 * not converge): a minimum of φ whose basin holds no minimum of d is then missed. */
static void polish_to_bands(const shape_pair* g, int ka, const rugo_vec2 fl[4], int kb, const rugo_vec2 gl[4],
                            rugo__narrow_result* r) {
    rugo__banded_piece bf, bg;
    banded_piece(g, g->A, ka, fl, &bf);
    banded_piece(g, g->B, kb, gl, &bg);
    int banded = 0;
    for (int h = 0; h < 2 && !banded; ++h)
        for (int i = 0; i < 4 && !banded; ++i)
            banded = bf.band[h][i] != bf.band[0][0] || bg.band[h][i] != bg.band[0][0];
    if (!banded) return;
    for (int i = 0; i < r->stationary_count; ++i) {
        rugo__pair_point* p = &r->stationary[i];
        if (p->kind != RUGO__MINIMUM) continue;
        rugo_real s = p->s, t = p->t, phi = 0.0;
        if (!rugo__polish_band_minimum(&bf, &bg, &s, &t, &phi)) continue;
        p->s = s;
        p->t = t;
        p->pa = rugo__bezier_point(fl, s);
        p->pb = rugo__bezier_point(gl, t);
        p->distance = rugo__v2_length(rugo_v2_sub(p->pb, p->pa));
    }
}

/* The resolution at which a query at δ = 0 with the band-adjusted rule searches for the basins of φ on
 * pieces whose bands vary, as a fraction of the pair's size: every minimum it reports is polished to
 * round-off by Newton on the true pieces and bands (narrow_resolved.h). */
#define BAND_BASIN_SEARCH 1e-6

/* At δ = 0 with the band-adjusted rule and bands that vary, the minima of φ, not of d: the round-off
 * phase's minima in r are replaced by those of the resolved phase on φ (cutoff raised by its search
 * resolution, so that no minimum with φ <= cutoff is pruned), whose minima are polished by Newton to
 * round-off; a minimum of φ whose basin holds no minimum of d is found too. 0 (r unchanged) where the
 * pieces carry no varying band or the resolved phase ran out of room. */
static int band_minima_at_round_off(const shape_pair* g, int ka, const rugo_vec2 fl[4], int kb,
                                    const rugo_vec2 gl[4], rugo_real band_cutoff, rugo__narrow_result* r) {
    rugo__banded_piece bf, bg;
    banded_piece(g, g->A, ka, fl, &bf);
    banded_piece(g, g->B, kb, gl, &bg);
    int banded = 0;
    for (int h = 0; h < 2 && !banded; ++h)
        for (int i = 0; i < 4 && !banded; ++i)
            banded = bf.band[h][i] != bf.band[0][0] || bg.band[h][i] != bg.band[0][0];
    if (!banded) return 0;
    const rugo_real search = BAND_BASIN_SEARCH * g->scale;
    rugo__narrow_result m;
    rugo__narrow_resolved(&bf, &bg, band_cutoff + search, NAN, search, RUGO__RESOLVED_MINIMA, &m);
    if (m.overflow) return 0;
    int w = 0;
    for (int i = 0; i < r->stationary_count; ++i)
        if (!rugo__is_minimum_candidate(r->stationary[i].kind)) r->stationary[w++] = r->stationary[i];
    for (int i = 0; i < m.stationary_count; ++i) {
        if (w >= RUGO__NARROW_MAX_STATIONARY) {
            r->overflow = 1;
            break;
        }
        r->stationary[w++] = m.stationary[i];
    }
    r->stationary_count = w;
    r->newton_iterations += m.newton_iterations;
    r->fallback += m.fallback;
    return 1;
}

/* One narrow call on pieces f (A, segment ka) and g (B, segment kb), results appended. At a resolution
 * (g->delta > 0) the first pass and the region depths run the narrow phase to that resolution, on the
 * band-adjusted distance (`cutoff` then bounds φ = d - λ_A - λ_B for minima: band_cutoff), falling back
 * to the round-off phase where that one ran out of its box budget; the closest pair of a containment
 * always runs the round-off phase. */
static int narrow_pair(rugo_collide_context* ctx, shape_pair* g, narrow_ask ask, int ka, const rugo_vec2 f[4],
                       int kb, const rugo_vec2 gb[4], rugo_real cutoff, rugo_real band_cutoff,
                       rugo__array* xs, size_t* nx, rugo__array* ss, size_t* ns) {
    const rugo_vec2 o = f[0];
    rugo_vec2 fl[4], gl[4];
    for (int i = 0; i < 4; ++i) {
        fl[i] = rugo_v2_sub(f[i], o);
        gl[i] = rugo_v2_sub(gb[i], o);
    }
    rugo__narrow_result r;
    int resolved = 0;
    if (g->delta > 0.0 && ask == ASK_FIRST_PASS) {
        rugo__banded_piece bf, bg;
        banded_piece(g, g->A, ka, fl, &bf);
        banded_piece(g, g->B, kb, gl, &bg);
        rugo__narrow_resolved(&bf, &bg, g->thesis_rule ? cutoff : band_cutoff, NAN, g->delta,
                              RUGO__RESOLVED_CROSSINGS | RUGO__RESOLVED_MINIMA, &r);
        resolved = !r.overflow;
    }
    if (!resolved) {
        rugo__narrow_pieces(fl, gl, cutoff, &r);
        if (ask == ASK_FIRST_PASS && !g->thesis_rule && g->override < 0.0 &&
            !(g->delta == 0.0 && band_minima_at_round_off(g, ka, fl, kb, gl, band_cutoff, &r)))
            polish_to_bands(g, ka, fl, kb, gl, &r);
    }
    const int src = g->src++;
    if (g->stats != NULL) {
        g->stats->segment_pairs += 1;
        g->stats->newton_iterations += r.newton_iterations;
        g->stats->fallbacks += r.fallback > 0;
    }
    if (r.overflow) g->coincident = 1;
    for (int pass = 0; pass < 2; ++pass) {
        const int cnt = pass == 0 ? r.crossing_count : r.stationary_count;
        const rugo__pair_point* pp = pass == 0 ? r.crossings : r.stationary;
        rugo__array* dst = pass == 0 ? xs : ss;
        size_t* nd = pass == 0 ? nx : ns;
        if (dst == NULL) continue;
        for (int i = 0; i < cnt; ++i) {
            hit h;
            memset(&h, 0, sizeof h);
            h.sa = ka;
            h.ta = pp[i].s;
            h.sb = kb;
            h.tb = pp[i].t;
            rugo__normalise_segment_param(&h.sa, &h.ta, g->A->n);
            rugo__normalise_segment_param(&h.sb, &h.tb, g->B->n);
            h.ua = (rugo_real)h.sa + h.ta;
            h.ub = (rugo_real)h.sb + h.tb;
            h.pa = rugo_v2_add(pp[i].pa, o);
            h.pb = rugo_v2_add(pp[i].pb, o);
            h.distance = pp[i].distance;
            h.kind = pp[i].kind;
            h.src = src;
            h.vertex = -1;
            h.coincident = r.overflow;
            h.flat = pp[i].flat;
            if (!rugo__push_hit(ctx, dst, nd, &h)) return 0;
        }
    }
    return 1;
}

/* Region geometry callbacks for two shapes. */
static rugo_vec2 shape_pair_point_a(void* u, rugo_real t) {
    const shape_pair* g = (const shape_pair*)u;
    return rugo_contour_point_at(g->A->curve, t);
}
static rugo_vec2 shape_pair_point_b(void* u, rugo_real t) {
    const shape_pair* g = (const shape_pair*)u;
    return rugo_transform_point(g->rel, rugo_contour_point_at(g->B->curve, t));
}
static int shape_pair_inside_b(void* u, rugo_vec2 p) {
    const shape_pair* g = (const shape_pair*)u;
    return rugo__query_side_contains(g->B, rugo_inv_transform_point(g->rel, p));
}
static int shape_pair_inside_a(void* u, rugo_vec2 p) {
    const shape_pair* g = (const shape_pair*)u;
    return rugo__query_side_contains(g->A, p);
}

/* Extreme point of a curve (A's frame pieces from `piece`) along direction d: the point maximising
 * p·d (sign = +1) or minimising it (sign = -1). Exact: ends and roots of the derivative. */
rugo_vec2 rugo__support_point(const shape_pair* g, int of_b, rugo_vec2 d, int sign, int* seg_out,
                              rugo_real* t_out) {
    const query_side* s = of_b ? g->B : g->A;
    rugo_real best = -HUGE_VAL;
    rugo_vec2 best_p = rugo_v2(0.0, 0.0);
    int best_k = 0;
    rugo_real best_t = 0.0;
    for (int k = 0; k < s->n; ++k) {
        rugo_vec2 b[4];
        if (of_b)
            rugo__piece_of_b(g, k, b);
        else
            rugo_contour_bezier(s->curve, k, b);
        rugo_real v[4];
        for (int i = 0; i < 4; ++i)
            v[i] = (rugo_real)sign * rugo_v2_dot(b[i], d);
        if (fmax(fmax(v[0], v[1]), fmax(v[2], v[3])) <= best) continue;
        /* derivative of the Bernstein cubic: 3[(v1-v0) B0 + (v2-v1) B1 + (v3-v2) B2], in power form */
        const rugo_real d0 = v[1] - v[0], d1 = v[2] - v[1], d2 = v[3] - v[2];
        rugo_real c[3] = {d0, 2.0 * (d1 - d0), d0 - 2.0 * d1 + d2};
        rugo_real roots[RUGO__POLY_MAX_ROOTS];
        int nr = rugo__poly_roots(c, 2, 0.0, 1.0, 0.0, roots);
        rugo_real ts[RUGO__POLY_MAX_ROOTS + 2];
        int nt = 0;
        ts[nt++] = 0.0;
        for (int i = 0; i < nr && nr > 0; ++i)
            ts[nt++] = roots[i];
        ts[nt++] = 1.0 - DBL_EPSILON; /* t = 1 is the next segment's start */
        for (int i = 0; i < nt; ++i) {
            rugo_vec2 p = rugo__bezier_point(b, ts[i]);
            const rugo_real val = (rugo_real)sign * rugo_v2_dot(p, d);
            if (val > best) {
                best = val;
                best_p = p;
                best_k = k;
                best_t = ts[i];
            }
        }
    }
    *seg_out = best_k;
    *t_out = best_t;
    return best_p;
}

/* Closest pair of the two curves (a MINIMUM of the distance), searching pairs within `bound`. */
static rugo_status closest_pair(rugo_collide_context* ctx, shape_pair* g, const tree_side* ta,
                                const tree_side* tb, rugo_real bound, hit* best, int* found) {
    tree_side A = *ta, B = *tb;
    A.slack = 0.5 * bound;
    B.slack = 0.5 * bound;
    size_t np = 0;
    long tests = 0;
    rugo_status st = rugo__traverse(ctx, &A, &B, g->rel, &tests, &np);
    if (g->stats) g->stats->box_tests += tests;
    if (st != RUGO_OK) return st;
    *found = 0;
    size_t ns = 0;
    piece_cache pc;
    rugo__piece_cache_init(&pc);
    for (size_t i = 0; i < np; ++i) {
        const rugo_node_pair p = ((const rugo_node_pair*)ctx->pairs.data)[i];
        const rugo_vec2* f = rugo__cached_piece_a(&pc, g, p.k_a);
        const rugo_vec2* h = rugo__cached_piece_b(&pc, g, p.k_b);
        ns = 0;
        if (!narrow_pair(ctx, g, ASK_CLOSEST, p.k_a, f, p.k_b, h,
                         bound * (1.0 + CUTOFF_PAD) + CUTOFF_PAD * g->scale, NAN, NULL, NULL, &ctx->ss2, &ns))
            return RUGO_ERR_OUT_OF_MEMORY;
        const hit* hs = (const hit*)ctx->ss2.data;
        for (size_t j = 0; j < ns; ++j)
            if (rugo__is_minimum_candidate(hs[j].kind) && (!*found || hs[j].distance < best->distance)) {
                *best = hs[j];
                *found = 1;
            }
    }
    return RUGO_OK;
}

/* One curve inside the other without crossing: the way out through the closest pair. */
static rugo_status emit_containment_contact(rugo_collide_context* ctx, shape_pair* g, const tree_side* ta,
                                            const tree_side* tb, int b_inside_a, contact_out* o) {
    /* An upper bound of the smallest distance: from one point of the inner curve to the outer. */
    hit best;
    memset(&best, 0, sizeof best);
    int found = 0;
    rugo_vec2 p0;
    rugo_curve_point cp;
    if (b_inside_a) {
        p0 = shape_pair_point_b(g, 0.0);
        cp = rugo__query_side_closest(g->A, p0);
    } else {
        p0 = shape_pair_point_a(g, 0.0);
        cp = rugo__query_side_closest(g->B, rugo_inv_transform_point(g->rel, p0));
    }
    rugo_status st = closest_pair(ctx, g, ta, tb, cp.distance, &best, &found);
    if (st != RUGO_OK) return st;
    if (!found) { /* cannot happen with exact arithmetic; keep the point found above */
        if (b_inside_a) {
            best.sa = cp.segment;
            best.ta = cp.t;
            best.pa = cp.point;
            best.sb = 0;
            best.tb = 0.0;
            best.pb = p0;
        } else {
            best.sa = 0;
            best.ta = 0.0;
            best.pa = p0;
            best.sb = cp.segment;
            best.tb = cp.t;
            best.pb = rugo_transform_point(g->rel, cp.point);
        }
    }
    rugo_vec2 n;
    int seg;
    rugo_real t;
    if (b_inside_a) {
        /* B leaves A through A's curve at pa: along A's outward normal there. */
        n = normal_on_a(g, best.sa, best.ta);
        rugo_vec2 pb = rugo__support_point(g, 1, n, -1, &seg, &t);
        if (!rugo__emit_contact(o, best.sa, best.ta, seg, t, best.pa, pb, n, 0, 2, 0, seg))
            return RUGO_ERR_OUT_OF_MEMORY;
    } else {
        /* A leaves B through B's curve at pb, along B's outward normal m; B moves along n = -m. */
        const rugo_vec2 m = normal_on_b(g, best.sb, best.tb);
        n = rugo_v2_scale(-1.0, m);
        rugo_vec2 pa = rugo__support_point(g, 0, n, +1, &seg, &t);
        if (!rugo__emit_contact(o, seg, t, best.sb, best.tb, pa, best.pb, n, 0, 2, 0, best.sb))
            return RUGO_ERR_OUT_OF_MEMORY;
    }
    return RUGO_OK;
}

/* Normal of a minimum: from the points when they are far enough apart to give a direction to ~1e-9,
 * else A's outward normal (exact at a stationary pair), or rugo__overlap_normal's where either curve has a
 * sharp corner there (A's normal is then a flank's) or the two normals point the same way (a coarse
 * level's curl turns one of them back: the flatter curve's). Turned to follow pb - pa while the points
 * are apart beyond round-off (1e-12 of the size), where A's normal may still face the wrong way, but
 * not below: there pb behind A's tangent is an overlap below the resolution, and turning would point
 * the normal into A. */
static rugo_vec2 minimum_normal(const shape_pair* g, const hit* h) {
    rugo_vec2 d = rugo_v2_sub(h->pb, h->pa);
    const rugo_real len = rugo__v2_length(d);
    if (len > NORMAL_FROM_POINTS * g->scale) return rugo_v2_scale(1.0 / len, d);
    rugo_vec2 n = normal_on_a(g, h->sa, h->ta);
    const rugo_real near = OVERLAP_NEAR * g->scale;
    rugo_vec2 c;
    if (rugo__corner_near(g->A->curve, h->sa, h->pa, near, &c) ||
        rugo__corner_near(g->B->curve, h->sb, rugo_inv_transform_point(g->rel, h->pb), near, &c) ||
        rugo_v2_dot(n, normal_on_b(g, h->sb, h->tb)) > 0.0)
        n = rugo__overlap_normal(g->A, g, NULL, h->sa, h->ta, h->pa, h->sb, h->tb, h->pb, g->scale);
    if (len > 1e-12 * g->scale && rugo_v2_dot(n, d) < 0.0) n = rugo_v2_scale(-1.0, n);
    return n;
}

/* Facing test of a minimum: B lies on A's outward side at pa and A on B's outward side at pb (at
 * corners: within their normal cones). */
static int minimum_faces(const shape_pair* g, const hit* h) {
    rugo_vec2 d = rugo_v2_sub(h->pb, h->pa);
    if (rugo__v2_length(d) <= SAME_POINT * g->scale) return 1;
    rugo_rot id;
    id.c = 1.0;
    id.s = 0.0;
    return rugo__faces_outward(g->A->curve, h->sa, h->ta, d, id) &&
           rugo__faces_outward(g->B->curve, h->sb, h->tb, rugo_v2_scale(-1.0, d), g->rel.q);
}

/* Along a segment index that wraps at n: are u and v within `reach` of each other? */
static int near_cyclic(rugo_real u, rugo_real v, rugo_real n, rugo_real reach) {
    rugo_real d = fabs(u - v);
    if (d > 0.5 * n) d = n - d;
    return d <= reach;
}

/* The normal of a point of a stretch flat to the resolution: located only to δ along the stretch, its
 * two points need not face each other exactly, but both curves' normals there do (to the stretch's
 * flatness); their mean, A's outward one and B's inward one. */
static rugo_vec2 flat_normal(const shape_pair* g, const hit* h) {
    /* at a sharp corner of either curve its own normal is a flank's: the minimum's rule decides */
    const rugo_real near = OVERLAP_NEAR * g->scale;
    rugo_vec2 corner;
    if (rugo__corner_near(g->A->curve, h->sa, h->pa, near, &corner) ||
        rugo__corner_near(g->B->curve, h->sb, rugo_inv_transform_point(g->rel, h->pb), near, &corner))
        return minimum_normal(g, h);
    const rugo_vec2 na = normal_on_a(g, h->sa, h->ta), nb = normal_on_b(g, h->sb, h->tb);
    const rugo_vec2 m = rugo_v2_sub(na, nb);
    const rugo_real len = rugo__v2_length(m);
    return len > 0.0 ? rugo_v2_scale(1.0 / len, m) : minimum_normal(g, h);
}

/* A conforming stretch reported as many points (one or two per segment pair, each within δ of the
 * others): its region keeps its first and last point along A and its deepest one. The contacts of
 * [from, o->n) are in emission order, so a region's points are consecutive. */
static void reduce_stretches(contact_out* o, size_t from) {
    rugo_contact* c = (rugo_contact*)o->ctx->out.data;
    size_t w = from;
    for (size_t i = from; i < o->n;) {
        size_t j = i + 1;
        while (j < o->n && c[j].region == c[i].region)
            ++j;
        size_t deep = i;
        for (size_t k = i + 1; k < j; ++k)
            if (c[k].separation - c[k].tolerance_a - c[k].tolerance_b <
                c[deep].separation - c[deep].tolerance_a - c[deep].tolerance_b)
                deep = k;
        const rugo_contact first = c[i], last = c[j - 1], deepest = c[deep];
        c[w++] = first;
        if (deep != i && deep != j - 1) c[w++] = deepest;
        if (j - 1 != i) c[w++] = last;
        i = j;
    }
    o->n = w;
}

/* Minima within the band (not inside a region if regs != NULL), regions numbered from `first`: each an
 * own region, but for the points of a stretch flat to the resolution, which share one (consecutive
 * along both curves, within δ of each other's band-adjusted separation) and are then reduced to its
 * ends and deepest point. */
static rugo_status emit_minima(contact_out* o, shape_pair* g, hit* hs, size_t ns, const regions* regs,
                               int first, rugo_real override) {
    int region = first;
    const size_t from = o->n;
    const hit* prev = NULL; /* the last minimum emitted */
    rugo_real prev_phi = 0.0;
    int stretches = 0;
    for (size_t i = 0; i < ns; ++i) {
        const hit* h = &hs[i];
        if (h->dead || h->kind != RUGO__MINIMUM) continue;
        if (regs != NULL && regs->m > 0) {
            if (h->distance <= SAME_POINT * g->scale) continue; /* a crossing point */
            if (rugo__in_any_region(regs, h->ua, h->ub)) continue;
        }
        const rugo_real lambda = rugo__query_side_tolerance(g->A, h->sa, h->ta, override) +
                                 rugo__query_side_tolerance(g->B, h->sb, h->tb, override);
        if (!(h->distance <= lambda + g->margin)) continue;
        if (!minimum_faces(g, h)) continue;
        /* Index within its segment pair: minima of one pair are sorted by A's parameter already. */
        int index = 0;
        for (size_t j = 0; j < i; ++j)
            if (!hs[j].dead && hs[j].kind == RUGO__MINIMUM && hs[j].sa == h->sa && hs[j].sb == h->sb) ++index;
        const rugo_vec2 n = h->flat ? flat_normal(g, h) : minimum_normal(g, h);
        const rugo_real phi = rugo_v2_dot(rugo_v2_sub(h->pb, h->pa), n) - lambda;
        const int joins = prev != NULL && (h->flat || prev->flat) &&
                          near_cyclic(h->ua, prev->ua, g->A->n, 1.5) &&
                          near_cyclic(h->ub, prev->ub, g->B->n, 1.5) && fabs(phi - prev_phi) <= g->delta;
        if (!joins && prev != NULL) ++region;
        stretches |= joins;
        if (!rugo__emit_contact(o, h->sa, h->ta, h->sb, h->tb, h->pa, h->pb, n, region, 0, index, h->sb))
            return RUGO_ERR_OUT_OF_MEMORY;
        prev = h;
        prev_phi = phi;
    }
    if (stretches) reduce_stretches(o, from);
    return RUGO_OK;
}

/* Segments under the arcs of region reg (which = 0: A's, 1: B's), appended to ctx->segs. */
static int collect_segments(rugo_collide_context* ctx, const shape_pair* g, const regions* r, int reg,
                            int which, unsigned char* mark, size_t* nseg) {
    const query_side* s = which == 0 ? g->A : g->B;
    for (int i = 0; i < r->m; ++i) {
        if ((which == 0 ? r->reg_a[i] : r->reg_b[i]) != reg) continue;
        const int j = which == 0 ? rugo__next_along_a(r, i) : rugo__next_along_b(r, i);
        const rugo_real u0 = which == 0 ? r->x[i].ua : r->x[i].ub, u1 = which == 0 ? r->x[j].ua : r->x[j].ub;
        const rugo_real len = rugo__param_arc(u0, u1, (rugo_real)s->n, r->m == 1);
        const int k0 = (int)floor(u0);
        const int k1 = (int)floor(u0 + len);
        for (int k = k0; k <= k1 && k - k0 < s->n; ++k) {
            const int kk = rugo__wrap(k, s->n);
            if (mark[kk]) continue;
            mark[kk] = 1;
            if (!rugo__scratch_reserve(ctx, &ctx->segs, *nseg + 1, sizeof(seginfo))) return 0;
            seginfo* si = (seginfo*)ctx->segs.data + (*nseg)++;
            si->k = kk;
            if (g->tab != NULL)
                memcpy(si->b, which == 0 ? rugo__table_piece_a(g, kk) : rugo__table_piece_b(g, kk),
                       sizeof si->b);
            else if (which == 0)
                rugo_contour_bezier(s->curve, kk, si->b);
            else
                rugo__piece_of_b(g, kk, si->b);
            rugo__bezier_bounds(si->b, &si->lo, &si->hi);
            rugo__tangent_cone(si->b, &si->cone, &si->half);
        }
    }
    return 1;
}

/* 1 if the pair (pa, pb) at distance len is a depth: pb is B's closest point to pa, or pa is A's
 * closest point to pb (within round-off). A stationary pair need not be one: a zero-speed corner of A
 * (where (f - g)·f' vanishes for every g) pairs with every foot on B, up to B's far side. */
static int pair_is_depth(const shape_pair* g, rugo_vec2 pa, rugo_vec2 pb, rugo_real len) {
    const rugo_real slack = len * 1e-9 + SAME_POINT * g->scale;
    const rugo_vec2 pa_in_b = rugo_inv_transform_point(g->rel, pa);
    if (rugo__query_side_closest(g->B, pa_in_b).distance >= len - slack) return 1;
    return rugo__query_side_closest(g->A, pb).distance >= len - slack;
}

/* Deepest penetration pair of region reg; 0 if none. */
static rugo_status emit_region_contact(rugo_collide_context* ctx, shape_pair* g, const regions* r, int reg,
                                       contact_out* o) {
    const size_t na = (size_t)g->A->n, nb = (size_t)g->B->n;
    if (!rugo__scratch_reserve(ctx, &ctx->marks, na + nb, 1)) return RUGO_ERR_OUT_OF_MEMORY;
    unsigned char* marks = (unsigned char*)ctx->marks.data;
    memset(marks, 0, na + nb);
    size_t nseg = 0;
    if (!collect_segments(ctx, g, r, reg, 0, marks, &nseg)) return RUGO_ERR_OUT_OF_MEMORY;
    const size_t n_a = nseg;
    if (!collect_segments(ctx, g, r, reg, 1, marks + na, &nseg)) return RUGO_ERR_OUT_OF_MEMORY;
    seginfo* segs = (seginfo*)ctx->segs.data;
    rugo_vec2 lo = segs[0].lo, hi = segs[0].hi;
    for (size_t i = 1; i < nseg; ++i) {
        lo = rugo_v2(fmin(lo.x, segs[i].lo.x), fmin(lo.y, segs[i].lo.y));
        hi = rugo_v2(fmax(hi.x, segs[i].hi.x), fmax(hi.y, segs[i].hi.y));
    }
    const rugo_real cutoff = rugo__v2_length(rugo_v2_sub(hi, lo)) * (1.0 + 1e-9) + CUTOFF_PAD * g->scale;

    hit best;
    int have = 0;
    memset(&best, 0, sizeof best);
    for (size_t i = 0; i < n_a; ++i)
        for (size_t j = n_a; j < nseg; ++j) {
            const seginfo* sa = &segs[i];
            const seginfo* sb = &segs[j];
            /* A penetration pair has anti-parallel tangents: skip pieces whose cones exclude it. */
            if (sa->half < PI_VALUE && sb->half < PI_VALUE) {
                rugo_real c = -rugo_v2_dot(sa->cone, sb->cone);
                c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
                if (acos(c) > sa->half + sb->half + 1e-9) continue;
            }
            size_t ns = 0;
            if (!narrow_pair(ctx, g, ASK_DEPTHS, sa->k, sa->b, sb->k, sb->b, cutoff, NAN, NULL, NULL,
                             &ctx->ss2, &ns))
                return RUGO_ERR_OUT_OF_MEMORY;
            const hit* hs = (const hit*)ctx->ss2.data;
            for (size_t k = 0; k < ns; ++k) {
                const hit* h = &hs[k];
                if (rugo__region_of_pair(r, h->ua, h->ub) != reg) continue;
                rugo_vec2 d = rugo_v2_sub(h->pa, h->pb);
                const rugo_real len = rugo__v2_length(d);
                if (len <= SAME_POINT * g->scale) continue;
                if (!(rugo_v2_dot(normal_on_a(g, h->sa, h->ta), d) > 0.0)) continue;
                if (!(rugo_v2_dot(normal_on_b(g, h->sb, h->tb), d) < 0.0)) continue;
                if (!have || len > best.distance || (len == best.distance && rugo__hit_cmp(h, &best) < 0)) {
                    if (!pair_is_depth(g, h->pa, h->pb, len)) continue;
                    best = *h;
                    best.distance = len;
                    have = 1;
                }
            }
        }
    if (have) {
        rugo_vec2 d = rugo_v2_sub(best.pa, best.pb);
        if (!rugo__emit_contact(o, best.sa, best.ta, best.sb, best.tb, best.pa, best.pb,
                                rugo_v2_scale(1.0 / best.distance, d), reg, 1, 0, best.sb))
            return RUGO_ERR_OUT_OF_MEMORY;
        return RUGO_OK;
    }

    /* Fallback: the point of the region's arcs farthest from the other curve. */
    rugo_real far = -1.0;
    rugo_vec2 fpa = r->x[0].pa, fpb = r->x[0].pa;
    int fsa = r->x[0].sa, fsb = r->x[0].sb;
    rugo_real fta = r->x[0].ta, ftb = r->x[0].tb;
    for (int which = 0; which < 2; ++which)
        for (int i = 0; i < r->m; ++i) {
            if ((which == 0 ? r->reg_a[i] : r->reg_b[i]) != reg) continue;
            const int j = which == 0 ? rugo__next_along_a(r, i) : rugo__next_along_b(r, i);
            const rugo_real u0 = which == 0 ? r->x[i].ua : r->x[i].ub,
                            u1 = which == 0 ? r->x[j].ua : r->x[j].ub;
            const rugo_real period = (rugo_real)(which == 0 ? g->A->n : g->B->n);
            const rugo_real len = rugo__param_arc(u0, u1, period, r->m == 1);
            const int samples = FALLBACK_SAMPLES * (1 + (int)ceil(len));
            for (int s = 1; s < samples; ++s) {
                const rugo_real u = rugo__wrap_param(u0 + len * (rugo_real)s / (rugo_real)samples, period);
                if (which == 0) {
                    const rugo_vec2 p = shape_pair_point_a(g, u);
                    rugo_curve_point cp = rugo__query_side_closest(g->B, rugo_inv_transform_point(g->rel, p));
                    if (cp.distance > far) {
                        far = cp.distance;
                        fpa = p;
                        fpb = rugo_transform_point(g->rel, cp.point);
                        fsa = (int)floor(u);
                        fta = u - floor(u);
                        fsb = cp.segment;
                        ftb = cp.t;
                    }
                } else {
                    const rugo_vec2 p = shape_pair_point_b(g, u);
                    rugo_curve_point cp = rugo__query_side_closest(g->A, p);
                    if (cp.distance > far) {
                        far = cp.distance;
                        fpb = p;
                        fpa = cp.point;
                        fsb = (int)floor(u);
                        ftb = u - floor(u);
                        fsa = cp.segment;
                        fta = cp.t;
                    }
                }
            }
        }
    rugo__normalise_segment_param(&fsa, &fta, g->A->n);
    rugo__normalise_segment_param(&fsb, &ftb, g->B->n);
    rugo_vec2 d = rugo_v2_sub(fpa, fpb);
    rugo_vec2 n = rugo__v2_length(d) > SAME_POINT * g->scale
                      ? rugo__v2_unit(d)
                      : rugo__overlap_normal(g->A, g, NULL, fsa, fta, fpa, fsb, ftb, fpb, g->scale);
    if (!rugo__emit_contact(o, fsa, fta, fsb, ftb, fpa, fpb, n, reg, 1, 1, fsb))
        return RUGO_ERR_OUT_OF_MEMORY;
    return RUGO_OK;
}

/* ---------------------------------------------------------------------------------------------------
 * The stages of rugo_collide_shapes, in its order (collide_primitive.c has the same stages for a
 * primitive B). */

/* What one query between two shapes holds from stage to stage. */
typedef struct shape_query {
    rugo_collide_context* ctx;
    const rugo_contact_query* q;
    rugo_real override; /* the query's tolerance, or -1 */
    query_side A, B;
    shape_pair g; /* A, B and B's frame in A's, for the narrow passes and the regions */
    contact_out o;
    tree_side ta, tb; /* the traversal's sides */
    size_t np;        /* candidate node pairs (segment pairs) in ctx->pairs */
    size_t nx, ns;    /* hits: crossings in ctx->xs, stationary pairs in ctx->ss */
    size_t m;         /* crossings that survive: the first m of ctx->xs */
    rugo_real eps;    /* SAME_POINT of the larger shape's size */
    int want;         /* contacts or statistics asked for (else only the state) */
} shape_query;

/* Frame and levels: both shapes at the query's level, B's pieces in A's frame, the output. */
/* The query's resolution δ for the two shapes (length units). */
static rugo_real query_delta(const rugo_shape* a, const rugo_shape* b, const rugo_contact_query* q) {
    return rugo__query_resolution(q, rugo__box_size(rugo_mobb_tree_root(rugo_shape_tree(a))),
                                  rugo__box_size(rugo_mobb_tree_root(rugo_shape_tree(b))));
}

static rugo_status shapes_frame_and_levels(shape_query* s, rugo_collide_context* ctx, const rugo_shape* a,
                                           rugo_transform xa, const rugo_shape* b, rugo_transform xb,
                                           const rugo_contact_query* q, rugo_query_stats* stats) {
    const rugo_real override = q->tolerance >= 0.0 ? q->tolerance : -1.0;
    s->ctx = ctx;
    s->q = q;
    s->override = override;
    const rugo_real delta = query_delta(a, b, q);
    rugo__query_side_init(&s->A, a, rugo__query_level(a, q, RESOLUTION_LEVEL_SHARE * delta), override);
    rugo__query_side_init(&s->B, b, rugo__query_level(b, q, RESOLUTION_LEVEL_SHARE * delta), override);
    shape_pair* g = &s->g;
    memset(g, 0, sizeof *g);
    g->A = &s->A;
    g->B = &s->B;
    g->rel = rugo__relative_transform(xa, xb);
    /* the larger shape's size */
    g->scale =
        fmax(rugo__box_size(rugo_mobb_tree_root(s->A.tree)), rugo__box_size(rugo_mobb_tree_root(s->B.tree)));
    g->stats = stats;
    g->margin = q->margin;
    g->override = override;
    g->thesis_rule = q->contact_rule == RUGO_CONTACT_THESIS;
    g->delta = RESOLUTION_NARROW_SHARE * delta;
    if (!rugo__piece_table_setup(ctx, g)) return RUGO_ERR_OUT_OF_MEMORY;
    contact_out* o = &s->o;
    memset(o, 0, sizeof *o);
    o->ctx = ctx;
    o->xa = xa;
    o->q = q;
    o->A = &s->A;
    o->B = &s->B;
    o->override = override;
    return RUGO_OK;
}

/* Candidates: the two trees descended together down to the query's levels. */
static rugo_status shapes_candidates(shape_query* s) {
    tree_side* ta = &s->ta;
    tree_side* tb = &s->tb;
    memset(ta, 0, sizeof *ta);
    memset(tb, 0, sizeof *tb);
    ta->tree = s->A.tree;
    ta->jmin = s->A.jmin;
    ta->stop = s->A.level;
    /* The margin is split between the two sides: boxes within margin of each other then overlap. */
    ta->slack = s->A.slack + 0.5 * s->q->margin;
    tb->tree = s->B.tree;
    tb->jmin = s->B.jmin;
    tb->stop = s->B.level;
    tb->slack = s->B.slack + 0.5 * s->q->margin;
    s->np = 0;
    long tests = 0;
    rugo_status st = rugo__traverse(s->ctx, ta, tb, s->g.rel, &tests, &s->np);
    if (s->g.stats != NULL) s->g.stats->box_tests += tests;
    return st;
}

/* Narrow phase, the first pass: crossings and stationary pairs within the band of every candidate
 * segment pair (cutoff: the bounds of λ(t) on both segments, or twice the override, plus the margin),
 * then each point once. */
static rugo_status shapes_narrow_phase(shape_query* s) {
    rugo_collide_context* ctx = s->ctx;
    shape_pair* g = &s->g;
    const rugo_real override = s->override;
    s->nx = 0;
    s->ns = 0;
    piece_cache pc;
    rugo__piece_cache_init(&pc);
    for (size_t i = 0; i < s->np; ++i) {
        const rugo_node_pair p = ((const rugo_node_pair*)ctx->pairs.data)[i];
        const rugo_vec2* f = rugo__cached_piece_a(&pc, g, p.k_a);
        const rugo_vec2* h = rugo__cached_piece_b(&pc, g, p.k_b);
        const rugo_real band = override >= 0.0 ? 2.0 * override : s->A.band[p.k_a] + s->B.band[p.k_b];
        const rugo_real cut = band + s->q->margin;
        const rugo_real cutoff = cut * (1.0 + CUTOFF_PAD) + CUTOFF_PAD * g->scale;
        const rugo_real band_cutoff = s->q->margin + CUTOFF_PAD * g->scale;
        if (!narrow_pair(ctx, g, ASK_FIRST_PASS, p.k_a, f, p.k_b, h, cutoff, band_cutoff, &ctx->xs, &s->nx,
                         &ctx->ss, &s->ns))
            return RUGO_ERR_OUT_OF_MEMORY;
    }
    s->eps = SAME_POINT * g->scale;
    rugo__dedupe_hits((hit*)ctx->xs.data, s->nx, (rugo_real)s->A.n, s->eps, 0);
    rugo__dedupe_hits((hit*)ctx->ss.data, s->ns, (rugo_real)s->A.n, s->eps, 1);
    return RUGO_OK;
}

/* Crossings: the ones that cross, first in ctx->xs; touchings and coincident stretches join the
 * stationary pairs as zero-distance minima, which are then sorted. */
static rugo_status shapes_crossings(shape_query* s) {
    rugo_collide_context* ctx = s->ctx;
    const size_t nx = s->nx;
    size_t ns = s->ns;
    const rugo_real eps = s->eps;
    hit* xs = (hit*)ctx->xs.data;
    hit* hs = (hit*)ctx->ss.data;
    /* Where pieces coincide the curves run together: their "crossings" (and the tangential meetings
     * next to them that the adjacent pieces report as crossings) are no crossing. */
    if (s->g.coincident)
        for (size_t i = 0; i < nx; ++i) {
            if (xs[i].dead || xs[i].coincident) continue;
            for (size_t j = 0; j < nx + ns && !xs[i].coincident; ++j) {
                const hit* oh = j < nx ? &xs[j] : &hs[j - nx];
                if (oh->dead || !oh->coincident) continue;
                xs[i].coincident = rugo__v2_length(rugo_v2_sub(oh->pa, xs[i].pa)) <= 1e-6 * s->g.scale;
            }
        }
    /* Crossings that only touch are zero-distance minima, and so are the coincident points. */
    size_t m = 0;
    for (size_t i = 0; i < nx; ++i) {
        if (xs[i].dead) continue;
        if (xs[i].kind != 0 && !xs[i].coincident) {
            xs[m++] = xs[i];
            continue;
        }
        int dup = 0;
        for (size_t j = 0; j < ns && !dup; ++j)
            dup = !hs[j].dead && rugo__v2_length(rugo_v2_sub(hs[j].pa, xs[i].pa)) <= eps &&
                  rugo__v2_length(rugo_v2_sub(hs[j].pb, xs[i].pb)) <= eps;
        if (!dup) {
            hit t = xs[i];
            t.kind = RUGO__MINIMUM;
            t.distance = rugo__v2_length(rugo_v2_sub(t.pb, t.pa));
            if (!rugo__push_hit(ctx, &ctx->ss, &ns, &t)) return RUGO_ERR_OUT_OF_MEMORY;
            xs = (hit*)ctx->xs.data;
            hs = (hit*)ctx->ss.data;
        }
    }
    if (ns > 1) qsort(hs, ns, sizeof(hit), rugo__hit_cmp);
    s->ns = ns;
    s->m = m;
    return RUGO_OK;
}

/* Crossings and regions: the regions traced through the crossings, the deepest penetration pair of
 * each, the minima outside them, and, when none of that gave a contact, the overlaps below the
 * resolution. */
static rugo_status shapes_regions(shape_query* s) {
    rugo_collide_context* ctx = s->ctx;
    const size_t m = s->m;
    rugo_status st;
    if (!rugo__scratch_reserve(ctx, &ctx->ints, 6 * m, sizeof(int))) return RUGO_ERR_OUT_OF_MEMORY;
    region_io io;
    io.user = &s->g;
    io.period_a = (rugo_real)s->A.n;
    io.period_b = (rugo_real)s->B.n;
    io.point_a = shape_pair_point_a;
    io.point_b = shape_pair_point_b;
    io.inside_b = shape_pair_inside_b;
    io.inside_a = shape_pair_inside_a;
    regions r;
    rugo__build_regions(&r, (const hit*)ctx->xs.data, (int)m, (int*)ctx->ints.data, &io);
    /* A caller that only asks for the state (no room for contacts, no statistics) is done. */
    if (!s->want) r.count = 0;
    for (int reg = 0; reg < r.count; ++reg) {
        st = emit_region_contact(ctx, &s->g, &r, reg, &s->o);
        if (st != RUGO_OK) return st;
    }
    /* Local minima within the band away from every overlap region are contacts too. */
    st = emit_minima(&s->o, &s->g, (hit*)ctx->ss.data, s->ns, &r, r.count, s->override);
    if (st != RUGO_OK) return st;
    /* Crossings that closed no region are an overlap below the resolution of the crossings: a contact
     * when the query found no other; at a resolution δ > 0 also beside other contacts, since there a
     * shallow overlap whose second crossing the resolved phase did not separate (it lies within δ)
     * closes no region, and would otherwise have no contact at all. */
    if (s->want && (s->o.n == 0 || (s->g.delta > 0.0 && r.count == 0))) {
        const hit* xs = (const hit*)ctx->xs.data;
        const rugo_contact* c = (const rugo_contact*)ctx->out.data;
        int first = 0;
        for (size_t i = 0; i < s->o.n; ++i)
            if (c[i].region >= first) first = c[i].region + 1;
        st = rugo__emit_unresolved_crossings(&s->o, &s->g, NULL, xs, (int)m, s->g.scale, first);
        if (st != RUGO_OK) return st;
    }
    return RUGO_OK;
}

/* No crossing: one curve inside the other (a point of each inside the other; cheap rejections first:
 * a point outside the other's root box) gives one contact, the way out; else the minima. */
static rugo_status shapes_no_crossing(shape_query* s, rugo_contact_state* state) {
    shape_pair* g = &s->g;
    int b_in_a = 0, a_in_b = 0;
    const rugo_vec2 pb0 = shape_pair_point_b(g, 0.0), pa0 = shape_pair_point_a(g, 0.0);
    if (!g->coincident && rugo_obb_contains(rugo_mobb_tree_root(s->A.tree), pb0, 0.0))
        b_in_a = rugo__query_side_contains(&s->A, pb0);
    if (!b_in_a && !g->coincident) {
        const rugo_vec2 pa0b = rugo_inv_transform_point(g->rel, pa0);
        if (rugo_obb_contains(rugo_mobb_tree_root(s->B.tree), pa0b, 0.0))
            a_in_b = rugo__query_side_contains(&s->B, pa0b);
    }
    if (b_in_a || a_in_b) {
        *state = RUGO_STATE_INTERSECTING;
        if (!s->want) return RUGO_OK;
        return emit_containment_contact(s->ctx, g, &s->ta, &s->tb, b_in_a, &s->o);
    }
    rugo_status st = emit_minima(&s->o, g, (hit*)s->ctx->ss.data, s->ns, NULL, 0, s->override);
    if (st != RUGO_OK) return st;
    *state = s->o.n > 0 ? RUGO_STATE_CONTACT : RUGO_STATE_APART;
    return RUGO_OK;
}

/* The plan (collide_internal.h): checks, frame and levels, candidates, narrow phase, crossings, then
 * the regions or, without crossings, containment or the minima, then finish. The state is
 * INTERSECTING as soon as crossings are found, whatever their contacts. */
rugo_status rugo_collide_shapes(const rugo_shape* a, rugo_transform xa, const rugo_shape* b,
                                rugo_transform xb, const rugo_contact_query* query, rugo_collide_context* ctx,
                                rugo_contact_output* out) {
    /* checks */
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    out->count = 0;
    out->state = RUGO_STATE_APART;
    memset(&out->stats, 0, sizeof out->stats);
    if (ctx == NULL || a == NULL || b == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_contact_query defq = rugo_default_contact_query();
    const rugo_contact_query* q = query != NULL ? query : &defq;
    rugo_status st = rugo__check_query(q, out);
    if (st != RUGO_OK) return st;
    if (!rugo__transform_finite(xa) || !rugo__transform_finite(xb)) return RUGO_ERR_NOT_FINITE;
    /* the pair's cached answer, if the shapes have hardly moved since (contact_cache.c) */
    if (out->cache != NULL) {
        st = rugo__cache_check(out->cache, a, b, ctx);
        if (st != RUGO_OK) return st;
        if (rugo__cache_reuse(out->cache, xa, xb, q, query_delta(a, b, q), out)) return RUGO_OK;
    }

    /* frame and levels */
    shape_query s;
    st = shapes_frame_and_levels(&s, ctx, a, xa, b, xb, q, &out->stats);
    if (st != RUGO_OK) return st;
    s.want = out->capacity > 0;
    /* traversal: candidate segment pairs */
    st = shapes_candidates(&s);
    /* narrow phase */
    if (st == RUGO_OK) st = shapes_narrow_phase(&s);
    /* crossings and regions, with the minima outside them and the overlaps below the resolution;
     * without crossings, containment or the minima */
    if (st == RUGO_OK) st = shapes_crossings(&s);
    rugo_contact_state state = RUGO_STATE_APART;
    if (st == RUGO_OK && s.m > 0) {
        state = RUGO_STATE_INTERSECTING;
        st = shapes_regions(&s);
    } else if (st == RUGO_OK) {
        st = shapes_no_crossing(&s, &state);
    }
    if (st != RUGO_OK) {
        memset(&out->stats, 0, sizeof out->stats);
        return st;
    }
    /* finish */
    out->state = state;
    rugo__finish_contacts(&s.o, out->contacts, out->capacity, &out->count, &out->stats);
    if (out->cache != NULL) rugo__cache_store(out->cache, a, xa, b, xb, q, ctx, &s.B, s.override, out);
    return RUGO_OK;
}
