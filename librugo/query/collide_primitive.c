/* A shape against a primitive B — a circle, a segment (a capsule; an edge for radius 0) or a convex
 * polygon grown by a radius — and the public entry points for them. The query follows the plan of
 * rugo_collide_shapes, stage by stage under the same names, with B's boundary made of edges and
 * vertex arcs (collide_primitive_boundary.c) and its own narrow phase (collide_primitive_narrow.c); an
 * edge has no inside, and its pieces inside A get contacts of their own. Separate from shape against
 * shape because B has no tree, no levels and no surface of its own. */
#include "query/collide_internal.h"

#include <string.h>

#define EDGE_SAMPLES 32 /* samples of an edge piece inside A */

/* What one query between a shape A and a primitive B holds from stage to stage. */
typedef struct primitive_query {
    rugo_collide_context* ctx;
    const rugo_contact_query* q;
    rugo_real override; /* the query's tolerance, or -1 */
    query_side A;
    primitive* P;
    primitive_pair g; /* A and P, for the narrow phase and the regions */
    contact_out o;
    tree_side ta, tb; /* the traversal's sides: A's tree, B's fixed box */
    size_t np;        /* candidate node pairs (A's segments against B) in ctx->pairs */
    size_t nx, ns;    /* hits: crossings in ctx->xs, stationary pairs in ctx->ss */
    size_t m;         /* crossings that survive deduplication: the first m of ctx->xs */
    rugo_real eps;    /* SAME_POINT of the shape's size */
    int want;         /* contacts or statistics asked for (else only the state) */
} primitive_query;

/* Region geometry of a shape and a primitive (region_io). */
static rugo_vec2 primitive_pair_point_a(void* u, rugo_real t) {
    return rugo_contour_point_at(((const primitive_pair*)u)->A->curve, t);
}
static rugo_vec2 primitive_pair_point_b(void* u, rugo_real w) {
    return rugo__primitive_point(((const primitive_pair*)u)->P, w);
}
static int primitive_pair_inside_b(void* u, rugo_vec2 p) {
    return rugo__primitive_signed_distance(((const primitive_pair*)u)->P, p, NULL, NULL) < 0.0;
}
static int primitive_pair_inside_a(void* u, rugo_vec2 p) {
    return rugo__query_side_contains(((const primitive_pair*)u)->A, p);
}

static rugo_obb grow_box(rugo_obb b, rugo_real d) {
    b.half[0] += d;
    b.half[1] += d;
    return b;
}

/* A's extreme point along dir (largest p·dir). */
static rugo_vec2 curve_support(const query_side* A, rugo_vec2 dir, int* seg, rugo_real* t) {
    shape_pair g;
    memset(&g, 0, sizeof g);
    g.A = A;
    g.B = A;
    return rugo__support_point(&g, 0, dir, +1, seg, t);
}

/* A contact at a hit: B's side is its feature of the boundary (for the id). */
static int emit_primitive_contact(contact_out* o, const hit* h, rugo_vec2 pa, rugo_vec2 pb, rugo_vec2 n,
                                  int region, int type, int index) {
    int feature = h->sb;
    return rugo__emit_contact(o, h->sa, h->ta, -1, 0.0, pa, pb, n, region, type, index,
                              0xFFF00 | (feature & 0xFF));
}

/* ---------------------------------------------------------------------------------------------------
 * The stages, in the order of collide_primitive. */

/* Frame and levels: B into A's frame, A at the query's level, and the output. */
static void primitive_frame_and_levels(primitive_query* s, rugo_collide_context* ctx, const rugo_shape* a,
                                       rugo_transform xa, primitive* P, const rugo_contact_query* q,
                                       rugo_query_stats* stats) {
    const rugo_real override = q->tolerance >= 0.0 ? q->tolerance : -1.0;
    s->ctx = ctx;
    s->q = q;
    s->override = override;
    s->P = P;
    rugo__primitive_into_frame(P, xa);

    rugo__query_side_init(&s->A, a, rugo__query_level(a, q, 0.0), override);
    primitive_pair* g = &s->g;
    memset(g, 0, sizeof *g);
    g->A = &s->A;
    g->P = P;
    /* the shape's size: a large primitive must not coarsen the tolerances */
    g->scale = rugo__box_size(rugo_mobb_tree_root(s->A.tree));
    g->stats = stats;
    contact_out* o = &s->o;
    memset(o, 0, sizeof *o);
    o->ctx = ctx;
    o->xa = xa;
    o->q = q;
    o->A = &s->A;
    o->B = NULL;
    o->override = override;
}

/* Candidates: A's tree against B's box, grown by the band and the margin. */
static rugo_status primitive_candidates(primitive_query* s) {
    const query_side* A = &s->A;
    const primitive* P = s->P;
    const rugo_real override = s->override;
    tree_side* ta = &s->ta;
    tree_side* tb = &s->tb;
    memset(ta, 0, sizeof *ta);
    memset(tb, 0, sizeof *tb);
    ta->tree = A->tree;
    ta->jmin = A->jmin;
    ta->stop = A->level;
    ta->slack = A->slack;
    tb->tree = NULL;
    tb->box.center = rugo_v2(0.5 * (P->lo.x + P->hi.x), 0.5 * (P->lo.y + P->hi.y));
    tb->box.axis[0] = rugo_v2(1.0, 0.0);
    tb->box.axis[1] = rugo_v2(0.0, 1.0);
    const rugo_real pad = CUTOFF_PAD * s->g.scale;
    tb->box.half[0] = 0.5 * (P->hi.x - P->lo.x) + (override >= 0.0 ? override : 0.0) + s->q->margin + pad;
    tb->box.half[1] = 0.5 * (P->hi.y - P->lo.y) + (override >= 0.0 ? override : 0.0) + s->q->margin + pad;
    s->np = 0;
    long tests = 0;
    rugo_transform ident = rugo_identity_transform();
    rugo_status st = rugo__traverse(s->ctx, ta, tb, ident, &tests, &s->np);
    if (s->g.stats != NULL) s->g.stats->box_tests += tests;
    return st;
}

/* Narrow phase: each candidate piece of A against B's features, then each point once. */
static rugo_status primitive_narrow_phase(primitive_query* s) {
    rugo_collide_context* ctx = s->ctx;
    s->nx = 0;
    s->ns = 0;
    for (size_t i = 0; i < s->np; ++i) {
        const int ka = ((const rugo_node_pair*)ctx->pairs.data)[i].k_a;
        if (!rugo__primitive_narrow(ctx, &s->g, ka, &ctx->xs, &s->nx, &ctx->ss, &s->ns))
            return RUGO_ERR_OUT_OF_MEMORY;
    }
    s->eps = SAME_POINT * s->g.scale;
    rugo__dedupe_hits((hit*)ctx->xs.data, s->nx, (rugo_real)s->A.n, s->eps, 0);
    rugo__dedupe_hits((hit*)ctx->ss.data, s->ns, (rugo_real)s->A.n, s->eps, 1);
    return RUGO_OK;
}

/* Crossings: the ones that are no touching, first in ctx->xs. */
static void primitive_crossings(primitive_query* s) {
    hit* xs = (hit*)s->ctx->xs.data;
    size_t m = 0;
    for (size_t i = 0; i < s->nx; ++i)
        if (!xs[i].dead && xs[i].kind != 0) xs[m++] = xs[i];
    s->m = m;
}

/* An edge (segment, R = 0) crossing A: each piece of it inside A gets its deepest point. */
static rugo_status primitive_edge_pieces(primitive_query* s) {
    rugo_collide_context* ctx = s->ctx;
    const primitive_pair* g = &s->g;
    contact_out* o = &s->o;
    const hit* xs = (const hit*)ctx->xs.data;
    const size_t m = s->m;
    const primitive* P = g->P;
    rugo_real ts[64];
    size_t nt = 0;
    /* Edge parameters of the crossings, sorted (feature 1 = the edge: w - 1). */
    if (m + 2 > 64 && !rugo__scratch_reserve(ctx, &ctx->marks, (m + 2) * sizeof(rugo_real), 1))
        return RUGO_ERR_OUT_OF_MEMORY;
    rugo_real* t = m + 2 <= 64 ? ts : (rugo_real*)ctx->marks.data;
    t[nt++] = 0.0;
    for (size_t i = 0; i < m; ++i)
        t[nt++] = fmin(fmax(xs[i].ub - 1.0, 0.0), 1.0);
    t[nt++] = 1.0;
    for (size_t i = 1; i < nt; ++i)
        for (size_t j = i; j > 0 && t[j] < t[j - 1]; --j) {
            const rugo_real x = t[j];
            t[j] = t[j - 1];
            t[j - 1] = x;
        }
    int region = 0;
    for (size_t i = 0; i + 1 < nt; ++i) {
        const rugo_real t0 = t[i], t1 = t[i + 1];
        if (!(t1 > t0)) continue;
        if (!rugo__query_side_contains(g->A, rugo__lerp2(P->v[0], P->v[1], 0.5 * (t0 + t1)))) continue;
        /* Depth along the piece: distance to A's curve, largest where the piece is deepest. */
        rugo_real best = -1.0, bt = t0;
        rugo_curve_point bcp;
        memset(&bcp, 0, sizeof bcp);
        for (int k = 0; k <= EDGE_SAMPLES; ++k) {
            const rugo_real tt = t0 + (t1 - t0) * (rugo_real)k / (rugo_real)EDGE_SAMPLES;
            rugo_curve_point cp = rugo__query_side_closest(g->A, rugo__lerp2(P->v[0], P->v[1], tt));
            if (cp.distance > best) {
                best = cp.distance;
                bt = tt;
                bcp = cp;
            }
        }
        /* Golden section around the best sample. */
        const rugo_real h = (t1 - t0) / (rugo_real)EDGE_SAMPLES;
        rugo_real lo = fmax(t0, bt - h), hi = fmin(t1, bt + h);
        const rugo_real gr = 0.6180339887498949;
        for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
            const rugo_real x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
            const rugo_real d1 = rugo__query_side_closest(g->A, rugo__lerp2(P->v[0], P->v[1], x1)).distance;
            const rugo_real d2 = rugo__query_side_closest(g->A, rugo__lerp2(P->v[0], P->v[1], x2)).distance;
            if (d1 >= d2)
                hi = x2;
            else
                lo = x1;
        }
        const rugo_real tm = 0.5 * (lo + hi);
        rugo_curve_point cp = rugo__query_side_closest(g->A, rugo__lerp2(P->v[0], P->v[1], tm));
        if (cp.distance >= best) {
            bcp = cp;
            bt = tm;
        }
        const rugo_vec2 pb = rugo__lerp2(P->v[0], P->v[1], bt);
        rugo_vec2 d = rugo_v2_sub(bcp.point, pb);
        rugo_vec2 n = rugo__v2_length(d) > SAME_POINT * g->scale
                          ? rugo__v2_unit(d)
                          : rugo__curve_normal(g->A->curve, bcp.segment, bcp.t);
        const int id_b = 0xFFF00 | region;
        if (!rugo__emit_contact(o, bcp.segment, bcp.t, -1, 0.0, bcp.point, pb, n, region, 1, 0, id_b))
            return RUGO_ERR_OUT_OF_MEMORY;
        ++region;
    }
    return RUGO_OK;
}

/* Crossings of an edge: the contacts of its pieces inside A, or, when none is found, of the overlaps
 * below the resolution. Nothing when only the state is asked for. */
static rugo_status primitive_edge_crossings(primitive_query* s) {
    if (!s->want) return RUGO_OK;
    rugo_status st = primitive_edge_pieces(s);
    if (st != RUGO_OK) return st;
    if (s->o.n == 0) {
        const hit* xs = (const hit*)s->ctx->xs.data;
        st = rugo__emit_unresolved_crossings(&s->o, NULL, s->P, xs, (int)s->m, s->g.scale, 0);
        if (st != RUGO_OK) return st;
    }
    return RUGO_OK;
}

/* The contact of region reg: its deepest penetration pair among the stationary pairs, else the
 * sampled point of its arcs farthest from the other boundary. */
static rugo_status primitive_region_contact(primitive_query* s, const regions* r, int reg) {
    const query_side* A = &s->A;
    const primitive* P = s->P;
    const rugo_real eps = s->eps;
    const hit* hs = (const hit*)s->ctx->ss.data;
    const hit* best = NULL;
    rugo_real depth = -1.0;
    for (size_t i = 0; i < s->ns; ++i) {
        const hit* h = &hs[i];
        if (h->dead || rugo__region_of_pair(r, h->ua, h->ub) != reg) continue;
        const rugo_vec2 d = rugo_v2_sub(h->pa, h->pb);
        const rugo_real len = rugo__v2_length(d);
        if (len <= eps) continue;
        const rugo_vec2 n = rugo_v2_scale(1.0 / len, d);
        if (!(rugo_v2_dot(rugo__curve_normal(A->curve, h->sa, h->ta), n) > 0.0)) continue;
        if (!rugo__primitive_normal_fits(P, h, n)) continue;
        if (len > depth || (len == depth && rugo__hit_cmp(h, best) < 0)) {
            /* a depth, as for two shapes: pb is B's closest point to pa, or pa is A's to pb */
            const rugo_real slack = len * 1e-9 + eps;
            if (fabs(rugo__primitive_signed_distance(P, h->pa, NULL, NULL)) < len - slack &&
                rugo__query_side_closest(A, h->pb).distance < len - slack)
                continue;
            depth = len;
            best = h;
        }
    }
    if (best != NULL) {
        const rugo_vec2 n = rugo_v2_scale(1.0 / depth, rugo_v2_sub(best->pa, best->pb));
        if (!emit_primitive_contact(&s->o, best, best->pa, best->pb, n, reg, 1, 0))
            return RUGO_ERR_OUT_OF_MEMORY;
        return RUGO_OK;
    }
    /* Fallback: the sampled point of the region's arcs farthest from the other boundary. */
    rugo_real far = -1.0;
    rugo_vec2 fpa = r->x[0].pa, fpb = r->x[0].pa;
    int fsa = r->x[0].sa;
    rugo_real fta = r->x[0].ta;
    for (int which = 0; which < 2; ++which)
        for (int i = 0; i < r->m; ++i) {
            if ((which == 0 ? r->reg_a[i] : r->reg_b[i]) != reg) continue;
            const int j = which == 0 ? rugo__next_along_a(r, i) : rugo__next_along_b(r, i);
            const rugo_real u0 = which == 0 ? r->x[i].ua : r->x[i].ub;
            const rugo_real u1 = which == 0 ? r->x[j].ua : r->x[j].ub;
            const rugo_real period = which == 0 ? (rugo_real)A->n : P->period;
            const rugo_real len = rugo__param_arc(u0, u1, period, r->m == 1);
            const int samples = FALLBACK_SAMPLES * (1 + (int)ceil(len));
            for (int k = 1; k < samples; ++k) {
                const rugo_real u = rugo__wrap_param(u0 + len * (rugo_real)k / (rugo_real)samples, period);
                if (which == 0) {
                    const rugo_vec2 p = rugo_contour_point_at(A->curve, u);
                    rugo_vec2 qb;
                    const rugo_real sd = rugo__primitive_signed_distance(P, p, &qb, NULL);
                    if (-sd > far) {
                        far = -sd;
                        fpa = p;
                        fpb = qb;
                        fsa = (int)floor(u);
                        fta = u - floor(u);
                    }
                } else {
                    const rugo_vec2 p = rugo__primitive_point(P, u);
                    rugo_curve_point cp = rugo__query_side_closest(A, p);
                    if (cp.distance > far) {
                        far = cp.distance;
                        fpb = p;
                        fpa = cp.point;
                        fsa = cp.segment;
                        fta = cp.t;
                    }
                }
            }
        }
    rugo__normalise_segment_param(&fsa, &fta, A->n);
    const rugo_vec2 d = rugo_v2_sub(fpa, fpb);
    const rugo_vec2 n = rugo__v2_length(d) > eps
                            ? rugo__v2_unit(d)
                            : rugo__overlap_normal(A, NULL, P, fsa, fta, fpa, -1, 0.0, fpb, s->g.scale);
    if (!rugo__emit_contact(&s->o, fsa, fta, -1, 0.0, fpa, fpb, n, reg, 1, 1, 0xFFF00 | reg))
        return RUGO_ERR_OUT_OF_MEMORY;
    return RUGO_OK;
}

/* Minima within the band outside every region, each its own region from r->count. */
static rugo_status primitive_minima_outside_regions(primitive_query* s, const regions* r) {
    const query_side* A = &s->A;
    const primitive* P = s->P;
    const rugo_real override = s->override;
    const hit* hs = (const hit*)s->ctx->ss.data;
    rugo_transform ident = rugo_identity_transform();
    int region = r->count;
    for (size_t i = 0; i < s->ns; ++i) {
        const hit* h = &hs[i];
        if (h->dead || h->kind != RUGO__MINIMUM || h->distance <= s->eps) continue;
        if (rugo__in_any_region(r, h->ua, h->ub)) continue;
        const rugo_vec2 d = rugo_v2_sub(h->pb, h->pa);
        const rugo_real band = rugo__query_side_tolerance(A, h->sa, h->ta, override) +
                               (override >= 0.0 ? override : 0.0) + s->q->margin;
        if (!(h->distance <= band)) continue;
        const rugo_vec2 n = rugo__v2_unit(d);
        if (!rugo__faces_outward(A->curve, h->sa, h->ta, d, ident.q) || !rugo__primitive_normal_fits(P, h, n))
            continue;
        if (rugo__primitive_signed_distance(P, h->pa, NULL, NULL) < 0.0) continue;
        if (!emit_primitive_contact(&s->o, h, h->pa, h->pb, n, region++, 0, 0)) return RUGO_ERR_OUT_OF_MEMORY;
    }
    return RUGO_OK;
}

/* Crossings and regions: the regions of the crossings, the contact of each, the minima outside them,
 * and, when none of that gave a contact, the overlaps below the resolution. */
static rugo_status primitive_regions(primitive_query* s) {
    rugo_collide_context* ctx = s->ctx;
    const size_t m = s->m;
    rugo_status st;
    if (!rugo__scratch_reserve(ctx, &ctx->ints, 6 * m, sizeof(int))) return RUGO_ERR_OUT_OF_MEMORY;
    region_io io;
    io.user = &s->g;
    io.period_a = (rugo_real)s->A.n;
    io.period_b = s->P->period;
    io.point_a = primitive_pair_point_a;
    io.point_b = primitive_pair_point_b;
    io.inside_b = primitive_pair_inside_b;
    io.inside_a = primitive_pair_inside_a;
    regions r;
    rugo__build_regions(&r, (const hit*)ctx->xs.data, (int)m, (int*)ctx->ints.data, &io);
    if (!s->want) r.count = 0;
    for (int reg = 0; reg < r.count; ++reg) {
        st = primitive_region_contact(s, &r, reg);
        if (st != RUGO_OK) return st;
    }
    st = primitive_minima_outside_regions(s, &r);
    if (st != RUGO_OK) return st;
    if (s->o.n == 0 && s->want) {
        st = rugo__emit_unresolved_crossings(&s->o, NULL, s->P, (const hit*)ctx->xs.data, (int)m, s->g.scale,
                                             0);
        if (st != RUGO_OK) return st;
    }
    return RUGO_OK;
}

/* B inside A: the closest pair of A's curve and B's boundary, searched within the distance from one
 * point pb0 of B to A, gives the way out along A's outward normal; B's support point the depth. */
static rugo_status primitive_inside_shape(primitive_query* s, rugo_vec2 pb0) {
    rugo_collide_context* ctx = s->ctx;
    const query_side* A = &s->A;
    const primitive* P = s->P;
    rugo_curve_point cp = rugo__query_side_closest(A, pb0);
    tree_side tb2 = s->tb;
    tb2.box = grow_box(s->tb.box, cp.distance * (1.0 + 1e-9) + CUTOFF_PAD * s->g.scale);
    size_t np2 = 0;
    long tests2 = 0;
    rugo_transform ident = rugo_identity_transform();
    rugo_status st = rugo__traverse(ctx, &s->ta, &tb2, ident, &tests2, &np2);
    if (s->g.stats != NULL) s->g.stats->box_tests += tests2;
    if (st != RUGO_OK) return st;
    size_t n2 = 0;
    for (size_t i = 0; i < np2; ++i) {
        const int ka = ((const rugo_node_pair*)ctx->pairs.data)[i].k_a;
        if (!rugo__primitive_narrow(ctx, &s->g, ka, NULL, NULL, &ctx->ss2, &n2))
            return RUGO_ERR_OUT_OF_MEMORY;
    }
    const hit* h2 = (const hit*)ctx->ss2.data;
    hit best;
    memset(&best, 0, sizeof best);
    best.sa = cp.segment;
    best.ta = cp.t;
    best.pa = cp.point;
    best.pb = pb0;
    best.distance = cp.distance;
    for (size_t i = 0; i < n2; ++i)
        if (rugo__is_minimum_candidate(h2[i].kind) && h2[i].distance < best.distance) best = h2[i];
    const rugo_vec2 n = rugo__curve_normal(A->curve, best.sa, best.ta);
    const rugo_vec2 pb = rugo__primitive_support(P, rugo_v2_scale(-1.0, n));
    if (!rugo__emit_contact(&s->o, best.sa, best.ta, -1, 0.0, best.pa, pb, n, 0, 2, 0, 0xFFF00))
        return RUGO_ERR_OUT_OF_MEMORY;
    return RUGO_OK;
}

/* A inside B: A leaves B through B's boundary where they are closest; A's support point the depth. */
static rugo_status shape_inside_primitive(primitive_query* s) {
    const query_side* A = &s->A;
    const hit* hs = (const hit*)s->ctx->ss.data;
    const hit* best = NULL;
    for (size_t i = 0; i < s->ns; ++i) {
        const hit* h = &hs[i];
        if (h->dead || h->vertex >= 0) continue;
        if (best == NULL || h->distance < best->distance) best = h;
    }
    rugo_vec2 pb, mb;
    if (best != NULL) {
        pb = best->pb;
        mb = best->nb;
    } else {
        rugo__primitive_signed_distance(s->P, rugo_contour_point_at(A->curve, 0.0), &pb, &mb);
    }
    const rugo_vec2 n = rugo_v2_scale(-1.0, mb);
    int seg;
    rugo_real t;
    const rugo_vec2 pa = curve_support(A, n, &seg, &t);
    if (!rugo__emit_contact(&s->o, seg, t, -1, 0.0, pa, pb, n, 0, 2, 0, 0xFFF00))
        return RUGO_ERR_OUT_OF_MEMORY;
    return RUGO_OK;
}

/* Minima: each local minimum of the distance within the band, facing B, a contact of its own region. */
static rugo_status primitive_minima(primitive_query* s) {
    const query_side* A = &s->A;
    const primitive* P = s->P;
    const rugo_real override = s->override;
    const hit* hs = (const hit*)s->ctx->ss.data;
    rugo_transform ident = rugo_identity_transform();
    int region = 0;
    for (size_t i = 0; i < s->ns; ++i) {
        const hit* h = &hs[i];
        if (h->dead || h->kind != RUGO__MINIMUM) continue;
        const rugo_vec2 d = rugo_v2_sub(h->pb, h->pa);
        const rugo_real len = rugo__v2_length(d);
        const rugo_real band = rugo__query_side_tolerance(A, h->sa, h->ta, override) +
                               (override >= 0.0 ? override : 0.0) + s->q->margin;
        if (!(len <= band)) continue;
        const rugo_vec2 na = rugo__curve_normal(A->curve, h->sa, h->ta);
        rugo_vec2 n;
        if (len > NORMAL_FROM_POINTS * s->g.scale) {
            n = rugo_v2_scale(1.0 / len, d);
            if (!rugo__faces_outward(A->curve, h->sa, h->ta, d, ident.q) ||
                !rugo__primitive_normal_fits(P, h, n))
                continue;
        } else {
            n = na;
        }
        if (!emit_primitive_contact(&s->o, h, h->pa, h->pb, n, region++, 0, 0)) return RUGO_ERR_OUT_OF_MEMORY;
    }
    return RUGO_OK;
}

/* No crossing: B inside A, A inside B (B's point 0 in the other, A's point 0 in B), or apart / in
 * contact through the minima. */
static rugo_status primitive_no_crossing(primitive_query* s, int is_edge, rugo_contact_state* state) {
    const query_side* A = &s->A;
    const primitive* P = s->P;
    const rugo_vec2 pb0 = is_edge ? P->v[0] : rugo__primitive_point(P, 0.0);
    int b_in_a = 0, a_in_b = 0;
    if (rugo_obb_contains(rugo_mobb_tree_root(A->tree), pb0, 0.0)) b_in_a = rugo__query_side_contains(A, pb0);
    if (!b_in_a && !is_edge && P->R + (P->V >= 3 ? 1.0 : 0.0) > 0.0)
        a_in_b = rugo__primitive_signed_distance(P, rugo_contour_point_at(A->curve, 0.0), NULL, NULL) < 0.0;
    if (b_in_a && !s->want) {
        *state = RUGO_STATE_INTERSECTING;
        return RUGO_OK;
    }
    if (b_in_a) {
        *state = RUGO_STATE_INTERSECTING;
        return primitive_inside_shape(s, pb0);
    }
    if (a_in_b) {
        *state = RUGO_STATE_INTERSECTING;
        return shape_inside_primitive(s);
    }
    rugo_status st = primitive_minima(s);
    if (st != RUGO_OK) return st;
    *state = s->o.n > 0 ? RUGO_STATE_CONTACT : RUGO_STATE_APART;
    return RUGO_OK;
}

/* The query: the plan of rugo_collide_shapes (collide_internal.h) with B's boundary for B's curve. The
 * state is INTERSECTING as soon as crossings are found, whatever their contacts. */
static rugo_status collide_primitive(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                                     primitive* P, const rugo_contact_query* q, rugo_contact_output* out) {
    /* frame and levels */
    primitive_query s;
    primitive_frame_and_levels(&s, ctx, a, xa, P, q, &out->stats);
    s.want = out->capacity > 0;
    const int is_edge = P->V == 2 && P->R == 0.0;
    /* traversal: A's candidate pieces */
    rugo_status st = primitive_candidates(&s);
    /* narrow phase */
    if (st == RUGO_OK) st = primitive_narrow_phase(&s);
    if (st != RUGO_OK) return st;
    /* crossings and regions (for an edge, its pieces inside A), with the minima outside them and the
     * overlaps below the resolution; without crossings, containment or the minima */
    primitive_crossings(&s);
    rugo_contact_state state = RUGO_STATE_APART;
    if (s.m > 0) {
        state = RUGO_STATE_INTERSECTING;
        st = is_edge ? primitive_edge_crossings(&s) : primitive_regions(&s);
    } else {
        st = primitive_no_crossing(&s, is_edge, &state);
    }
    if (st != RUGO_OK) return st;
    /* finish */
    out->state = state;
    rugo__finish_contacts(&s.o, out->contacts, out->capacity, &out->count, &out->stats);
    return RUGO_OK;
}

/* ---------------------------------------------------------------------------------------------------
 * The primitive's constructors and the public entry point: argument checks, then the query. */

rugo_primitive rugo_make_circle(rugo_vec2 center, rugo_real radius) {
    rugo_primitive p;
    memset(&p, 0, sizeof p);
    p.points[0] = center;
    p.count = 1;
    p.radius = radius;
    return p;
}

rugo_primitive rugo_make_capsule(rugo_vec2 p1, rugo_vec2 p2, rugo_real radius) {
    rugo_primitive p;
    memset(&p, 0, sizeof p);
    p.points[0] = p1;
    p.points[1] = p2;
    p.count = 2;
    p.radius = radius;
    return p;
}

rugo_primitive rugo_make_segment(rugo_vec2 p1, rugo_vec2 p2) { return rugo_make_capsule(p1, p2, 0.0); }

/* The primitive's points and radius: finite, a radius >= 0, 1..8 points, 3..8 convex and
 * counter-clockwise (every turn strictly left, total turning one revolution). */
static rugo_status check_primitive(const rugo_vec2* points, int count, rugo_real radius) {
    if (count < 1 || count > RUGO_PRIMITIVE_MAX_POINTS) return RUGO_ERR_BAD_ARGUMENT;
    for (int i = 0; i < count; ++i)
        if (!rugo__v2_finite(points[i])) return RUGO_ERR_NOT_FINITE;
    if (!isfinite(radius)) return RUGO_ERR_NOT_FINITE;
    if (radius < 0.0) return RUGO_ERR_BAD_ARGUMENT;
    if (count < 3) return RUGO_OK;
    rugo_real size = 0.0, turning = 0.0;
    for (int i = 0; i < count; ++i)
        size = fmax(size, rugo__v2_length(rugo_v2_sub(points[(i + 1) % count], points[i])));
    if (!(size > 0.0)) return RUGO_ERR_BAD_ARGUMENT;
    for (int i = 0; i < count; ++i) {
        const rugo_vec2 e0 = rugo_v2_sub(points[(i + 1) % count], points[i]);
        const rugo_vec2 e1 = rugo_v2_sub(points[(i + 2) % count], points[(i + 1) % count]);
        if (!(rugo__v2_length(e0) > 1e-12 * size)) return RUGO_ERR_BAD_ARGUMENT;
        if (!(rugo_v2_cross(e0, e1) > 1e-12 * size * size)) return RUGO_ERR_BAD_ARGUMENT;
        turning += atan2(rugo_v2_cross(e0, e1), rugo_v2_dot(e0, e1));
    }
    if (fabs(turning - 2.0 * PI_VALUE) > 1e-6) return RUGO_ERR_BAD_ARGUMENT;
    return RUGO_OK;
}

rugo_status rugo_make_polygon(const rugo_vec2* points, int count, rugo_real radius, rugo_primitive* out) {
    if (out == NULL || points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (count < 3) return RUGO_ERR_BAD_ARGUMENT;
    const rugo_status st = check_primitive(points, count, radius);
    if (st != RUGO_OK) return st;
    for (int i = 0; i < count; ++i)
        out->points[i] = points[i];
    out->count = count;
    out->radius = radius;
    return RUGO_OK;
}

rugo_status rugo_collide_primitive(const rugo_shape* a, rugo_transform xa, const rugo_primitive* b,
                                   rugo_transform xb, const rugo_contact_query* query,
                                   rugo_collide_context* ctx, rugo_contact_output* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    out->count = 0;
    out->state = RUGO_STATE_APART;
    memset(&out->stats, 0, sizeof out->stats);
    if (ctx == NULL || a == NULL || b == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_primitive(b->points, b->count, b->radius);
    if (st != RUGO_OK) return st;
    rugo_contact_query defq = rugo_default_contact_query();
    const rugo_contact_query* q = query != NULL ? query : &defq;
    st = rugo__check_query(q, out);
    if (st != RUGO_OK) return st;
    if (!rugo__transform_finite(xa) || !rugo__transform_finite(xb)) return RUGO_ERR_NOT_FINITE;
    /* B's points in the world (the identity leaves them as they are, bit for bit); a segment of zero
     * length is a circle (or a point). */
    primitive P;
    memset(&P, 0, sizeof P);
    P.V = b->count;
    for (int i = 0; i < b->count; ++i)
        P.v[i] = rugo_transform_point(xb, b->points[i]);
    for (int i = 0; i < P.V; ++i)
        if (!rugo__v2_finite(P.v[i])) return RUGO_ERR_NOT_FINITE;
    if (P.V == 2 && P.v[0].x == P.v[1].x && P.v[0].y == P.v[1].y) P.V = 1;
    P.R = b->radius;
    st = collide_primitive(ctx, a, xa, &P, q, out);
    if (st != RUGO_OK) {
        out->count = 0;
        out->state = RUGO_STATE_APART;
        memset(&out->stats, 0, sizeof out->stats);
    }
    return st;
}
