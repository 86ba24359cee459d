/* The world's contacts at the current poses: the broad phase on the bodies' boxes, a contact query
 * per candidate pair (rugo_collide_shapes at the world's level, reduced to a few per region), support
 * probing for the ends of a resting face, the contact groups, and the overlaps a pair may keep. Separate
 * because the step gathers contacts many times (each sample and bisection of an advance) and reads
 * them in several ways. */
#include "sim/world_internal.h"

static rugo_aabb body_aabb(const body* b) {
    rugo_obb o = rugo_obb_transform(b->xf, &b->root);
    rugo_real ex = fabs(o.axis[0].x) * o.half[0] + fabs(o.axis[1].x) * o.half[1];
    rugo_real ey = fabs(o.axis[0].y) * o.half[0] + fabs(o.axis[1].y) * o.half[1];
    rugo_aabb r;
    r.lower = rugo_v2(o.center.x - ex, o.center.y - ey);
    r.upper = rugo_v2(o.center.x + ex, o.center.y + ey);
    return r;
}

/* Support probing (docs/simulator.md, "Contact groups"): collide reports one contact per local minimum
 * of the distance, so a flat face lying slightly tilted on another within the band gives only its
 * lower end, and an overlap only its deepest point; a rigid block supported at one end each step
 * rocks and sinks. Points of the smaller body's curve near a contact (PROBE_SEGMENTS segments either
 * side, PROBE_SAMPLES each) whose signed distance to the other curve is within the band and whose
 * normals face each other mark the extent of the supporting patch; its two extreme points along the
 * tangent become contacts of the same group. */
#define PROBE_SEGMENTS 2
#define PROBE_SAMPLES 4
/* 1°: the faces of a patch are parallel; a curved body (a disc) gets a narrow patch, so the centre
 * of pressure moving ahead of a rolling contact costs little rolling resistance. */
#define FACE_COS 0.99985

static int probe_supports(const rugo_world* w, int ia, int ib, const rugo_contact* c, world_contact out[2]) {
    const body* A = &rugo__world_bodies(w)[ia];
    const body* B = &rugo__world_bodies(w)[ib];
    int s_is_a = A->size <= B->size;
    const body* S = s_is_a ? A : B;
    const body* O = s_is_a ? B : A;
    int seg = s_is_a ? c->segment_a : c->segment_b;
    int lev_s = s_is_a ? c->level_a : c->level_b, lev_o = s_is_a ? c->level_b : c->level_a;
    if (seg < 0) return 0;
    rugo_contour cs, co;
    if (rugo_shape_level(S->shape, lev_s, &cs) != RUGO_OK ||
        rugo_shape_level(O->shape, lev_o, &co) != RUGO_OK)
        return 0;
    rugo_vec2 n_out = s_is_a ? c->normal : rugo_v2_scale(-1.0, c->normal); /* from S toward O */
    rugo_vec2 tau = rugo_v2_perp(c->normal);
    rugo_vec2 p0 = s_is_a ? c->point_a : c->point_b;
    rugo_real band =
        (c->tolerance_a > 0.0 ? c->tolerance_a : 0.0) + (c->tolerance_b > 0.0 ? c->tolerance_b : 0.0);
    rugo_real umin = 0.0, umax = 0.0;
    int found[2] = {0, 0};
    rugo_vec2 qs[2], qo[2];
    rugo_real sd[2] = {0.0, 0.0};
    for (int dj = -PROBE_SEGMENTS; dj <= PROBE_SEGMENTS; ++dj) {
        int j = rugo__wrap(seg + dj, cs.count);
        for (int k = 0; k < PROBE_SAMPLES; ++k) {
            rugo_real t = (rugo_real)k / (rugo_real)PROBE_SAMPLES;
            rugo_vec2 ns = rugo_rotate(S->xf.q, rugo_contour_normal(cs, j, t));
            if (rugo_v2_dot(ns, n_out) < FACE_COS) continue;
            rugo_vec2 q = rugo_transform_point(S->xf, rugo_contour_point(cs, j, t));
            rugo_curve_point cp; /* rugo_contour_closest_point on co, through the tree */
            if (rugo_shape_closest_point(O->shape, lev_o, rugo_inv_transform_point(O->xf, q), &cp) != RUGO_OK)
                continue;
            rugo_vec2 no = rugo_rotate(O->xf.q, rugo_contour_normal(co, cp.segment, cp.t));
            if (rugo_v2_dot(no, n_out) > -FACE_COS) continue;
            rugo_vec2 cw = rugo_transform_point(O->xf, cp.point);
            rugo_real signed_d = rugo_v2_dot(rugo_v2_sub(q, cw), no);
            if (!(signed_d <= band)) continue;
            rugo_real u = rugo_v2_dot(rugo_v2_sub(q, p0), tau);
            int side = u < 0.0 ? 0 : 1;
            if ((side == 0 && u < umin) || (side == 1 && u > umax)) {
                if (side == 0)
                    umin = u;
                else
                    umax = u;
                found[side] = 1;
                qs[side] = q;
                qo[side] = cw;
                sd[side] = signed_d;
            }
        }
    }
    int n = 0;
    for (int side = 0; side < 2; ++side) {
        if (!found[side]) continue;
        world_contact* wc = &out[n++];
        wc->a = ia;
        wc->b = ib;
        wc->c = *c;
        wc->c.point_a = s_is_a ? qs[side] : qo[side];
        wc->c.point_b = s_is_a ? qo[side] : qs[side];
        wc->c.separation = sd[side];
    }
    return n;
}

/* Broad phase and contacts at the current poses into w->contacts. */
rugo_status rugo__gather_contacts(rugo_world* w) {
    for (int i = 0; i < w->count; ++i)
        rugo__world_boxes(w)[i] = body_aabb(&rugo__world_bodies(w)[i]);
    rugo_status st = rugo__sweep_prune_update(w->sap, rugo__world_boxes(w), w->count);
    if (st != RUGO_OK) return st;
    int npairs = 0;
    const rugo__pair* pairs = rugo__sweep_prune_pairs(w->sap, &npairs);
    w->stats.candidate_pairs = npairs;
    w->contact_count = 0;
    if (w->scratch.capacity == 0 && !rugo__world_reserve(w, &w->scratch, 32, sizeof(rugo_contact)))
        return RUGO_ERR_OUT_OF_MEMORY;
    for (int p = 0; p < npairs; ++p) {
        const body* a = &rugo__world_bodies(w)[pairs[p].a];
        const body* b = &rugo__world_bodies(w)[pairs[p].b];
        if (a->type == RUGO_BODY_STATIC && b->type == RUGO_BODY_STATIC) continue;
        rugo_contact_output out = rugo_contact_output_of(rugo__world_scratch(w), (int)w->scratch.capacity);
        st = rugo_collide_shapes(a->shape, a->xf, b->shape, b->xf, &w->query, w->ctx, &out);
        if (st != RUGO_OK) return st;
        w->stats.box_tests += out.stats.box_tests;
        if ((size_t)out.stats.contacts_found > w->scratch.capacity) {
            if (!rugo__world_reserve(w, &w->scratch, out.stats.contacts_found, sizeof(rugo_contact)))
                return RUGO_ERR_OUT_OF_MEMORY;
            out = rugo_contact_output_of(rugo__world_scratch(w), (int)w->scratch.capacity);
            st = rugo_collide_shapes(a->shape, a->xf, b->shape, b->xf, &w->query, w->ctx, &out);
            if (st != RUGO_OK) return st;
        }
        int count = out.count;
        if (count == 0) continue;
        count = rugo_reduce_manifold(rugo__world_scratch(w), count, w->def.max_contacts_per_pair);
        if (count > w->def.max_contacts_per_pair) count = w->def.max_contacts_per_pair;
        if (!rugo__world_reserve(w, &w->contacts, w->contact_count + 3 * count, sizeof(world_contact)))
            return RUGO_ERR_OUT_OF_MEMORY;
        for (int k = 0; k < count; ++k) {
            world_contact* c = &rugo__world_contacts(w)[w->contact_count++];
            c->a = pairs[p].a;
            c->b = pairs[p].b;
            c->c = rugo__world_scratch(w)[k];
            world_contact* supports = &rugo__world_contacts(w)[w->contact_count];
            const rugo_contact* found = &rugo__world_scratch(w)[k];
            w->contact_count += probe_supports(w, pairs[p].a, pairs[p].b, found, supports);
        }
    }
    w->contacts_valid = 1;
    return RUGO_OK;
}

/* The overlap a pair had at the start of the step (0 if none): binary search in w->pair_depth0. */
static rugo_real pair_depth_at_start(const rugo_world* w, int a, int b) {
    int lo = 0, hi = w->pair_depth_count - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        const pair_depth* p = &rugo__world_pair_depth0(w)[mid];
        if (p->a == a && p->b == b) return p->depth;
        if (p->a < a || (p->a == a && p->b < b))
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return 0.0;
}

/* An overlap may deepen by frac × the tolerance beyond what this pair (not either body with some
 * third body) already had at the start of the step. */
static rugo_real pair_allowance(const rugo_world* w, int a, int b, rugo_real frac) {
    rugo_real sa = rugo__world_bodies(w)[a].size, sb = rugo__world_bodies(w)[b].size;
    return frac * w->def.penetration_tolerance * (sa < sb ? sa : sb) + pair_depth_at_start(w, a, b);
}

/* 1 if some contact overlaps deeper than frac × its pair's allowance: the step finds an advance
 * penetrating at frac = 1 and bisects it down to a fraction of that (world_step.c, STOP_FRAC). */
int rugo__penetrating(const rugo_world* w, rugo_real frac) {
    for (int k = 0; k < w->contact_count; ++k) {
        const world_contact* c = &rugo__world_contacts(w)[k];
        if (-c->c.separation > pair_allowance(w, c->a, c->b, frac)) return 1;
    }
    return 0;
}

/* Contacts of one pair whose normals agree within GROUP_COS form a group (a face contact: both ends
 * of a flat piece, its joints); opposite normals (a body wedged between two sides) stay apart. */
#define GROUP_COS 0.9

/* Assigns each contact's group: the index of the group's first contact. */
void rugo__group_contacts(rugo_world* w) {
    for (int k = 0; k < w->contact_count; ++k) {
        world_contact* c = &rugo__world_contacts(w)[k];
        c->group = k;
        for (int m = k - 1; m >= 0; --m) {
            const world_contact* o = &rugo__world_contacts(w)[m];
            if (o->a != c->a || o->b != c->b) break;
            if (o->group == m && rugo_v2_dot(o->c.normal, c->c.normal) > GROUP_COS) c->group = m;
        }
    }
}
