/* librugo — the thesis' own simulator (SPEC 7, 9, 10; thesis chapters 6-7). docs/simulator.md explains
 * the step; the short version:
 *
 *  1. symplectic Euler: gravity into the velocities (explicit Euler: at the end of the step instead);
 *  2. contacts at the current poses (cached from the end of the previous step when nothing moved the
 *     bodies since) and impulses at every contact point, one after another (7.4), in up to
 *     CONTACT_SWEEPS sweeps over the contacts (later sweeps only touch points that approach again);
 *  3. the poses advance with the velocities; if that ends with a penetration beyond the tolerance,
 *     the advance is bisected toward the time of contact (SPEC 9), the bodies stop at the last safe
 *     time, impulses are applied there, and the rest of the step is advanced (at most TOI_EVENTS such
 *     events a step). When the limits are reached the penetration is left for the next step, whose
 *     contacts handle it with the separating normal of the overlap, and stats.unresolved is set.
 * Contacts of one pair with agreeing normals form a group (a face contact) that gets one impulse at
 * its centre of pressure; support probing adds the patch's ends (see below and docs/simulator.md).
 * Micro-collisions (7.3): a point inside its band approaching slower than sqrt(2 g λ) counts its
 * incoming speed as at most sqrt(2 g δ) and leaves with ε_c(δ) times it (dissipative). */
#include "rugo/world.h"

#include "core/array.h"
#include "core/internal.h"
#include "sim/internal.h"

#include <string.h>

#define WORLD_DEF_COOKIE 0x52554757 /* "RUGW" */
#define BODY_DEF_COOKIE 0x52554742  /* "RUGB" */
#define CONTACT_SWEEPS 4  /* enough for small stacks; each sweep after the first is usually empty */
#define TOI_EVENTS 8      /* bisected contact events per step */
#define MAX_PAIR_CONTACTS 64
#define MAX_BODIES (1 << 24)

typedef struct body {
    const rugo_shape* shape;
    rugo_body_type type;
    rugo_transform xf; /* of the shape's local frame */
    rugo_real angle;   /* of xf.q, integrated (the rotation is recomputed from it) */
    rugo_vec2 c_local; /* centre of mass in the shape's frame */
    rugo_vec2 v;
    rugo_real w;
    rugo_real mass, inertia, inv_mass, inv_inertia;
    rugo_obb root;     /* local */
    rugo_real size;    /* root half-diagonal */
    rugo_restitution restitution;
    void* user_data;
} body;

typedef struct pose {
    rugo_vec2 c; /* world centre of mass */
    rugo_real angle;
    rugo_transform xf;
} pose;

typedef struct saved_body {
    rugo_transform xf;
    rugo_real angle;
    rugo_vec2 v;
    rugo_real w;
} saved_body;

typedef struct pair_depth {
    int a, b;
    rugo_real depth;
} pair_depth;

typedef struct world_contact {
    int a, b;
    int group; /* index of the first contact of its group (same pair, similar normal) */
    rugo_contact c;
} world_contact;

struct rugo_world {
    rugo_world_def def;
    rugo_allocator allocator;
    rugo_real g;        /* |gravity| for micro-collisions */
    rugo__array bodies; /* body: count of them */
    int count;
    /* per body */
    rugo__array start; /* pose: poses at the start of a move */
    rugo__array boxes; /* rugo_aabb */
    rugo__array saved; /* saved_body: the step's initial state, restored if the step fails */
    /* pair_depth: deepest overlap of each pair at the start of the step, by (a, b) */
    rugo__array pair_depth0;
    int pair_depth_count;
    rugo_sweep_prune* sap;
    rugo_collide_context* ctx;
    rugo_contact_query query;
    rugo__array scratch;  /* rugo_contact: one query's contacts (its capacity is the query's room) */
    rugo__array contacts; /* world_contact */
    int contact_count;
    int contacts_valid;  /* contacts describe the current poses */
    rugo__array records; /* rugo_contact_record */
    int record_count;
    rugo_step_stats stats;
};

/* The world's arrays as their elements. */
static body* bodies_of(const rugo_world* w) { return (body*)w->bodies.data; }
static pose* start_of(const rugo_world* w) { return (pose*)w->start.data; }
static rugo_aabb* boxes_of(const rugo_world* w) { return (rugo_aabb*)w->boxes.data; }
static saved_body* saved_of(const rugo_world* w) { return (saved_body*)w->saved.data; }
static pair_depth* pair_depth0_of(const rugo_world* w) { return (pair_depth*)w->pair_depth0.data; }
static rugo_contact* scratch_of(const rugo_world* w) { return (rugo_contact*)w->scratch.data; }
static world_contact* contacts_of(const rugo_world* w) { return (world_contact*)w->contacts.data; }
static rugo_contact_record* records_of(const rugo_world* w) { return (rugo_contact_record*)w->records.data; }

/* Room for `need` elements of `elem` bytes in one of the world's arrays: the capacity doubles from 8,
 * up to 2^29 elements (counts stay ints). 0 on failure, the array then unchanged. */
static int world_reserve(rugo_world* w, rugo__array* a, int need, size_t elem) {
    if (need > (1 << 29)) return 0;
    return rugo__array_reserve(a, &w->allocator, (size_t)need, elem, 8) == RUGO_OK;
}

rugo_world_def rugo_default_world_def(void) {
    rugo_world_def d;
    memset(&d, 0, sizeof d);
    d.gravity = rugo_v2(0.0, -9.81);
    d.time_step = 1.0 / 60.0;
    d.integrator = RUGO_INTEGRATE_SYMPLECTIC_EULER;
    d.level = 0;
    d.max_bisections = 8;
    d.penetration_tolerance = 0.01;
    d.micro_collisions = 1;
    d.friction = 1;
    d.max_contacts_per_pair = 8;
    d.cookie = WORLD_DEF_COOKIE;
    return d;
}

rugo_body_def rugo_default_body_def(void) {
    rugo_body_def d;
    memset(&d, 0, sizeof d);
    d.shape = NULL;
    d.type = RUGO_BODY_DYNAMIC;
    d.transform = rugo_identity_transform();
    d.density = 1.0;
    d.cookie = BODY_DEF_COOKIE;
    return d;
}

rugo_status rugo_world_create(const rugo_world_def* def, rugo_world** out) {
    if (def == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (def->cookie != WORLD_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (!rugo__v2_finite(def->gravity) || !isfinite(def->time_step) || !isfinite(def->penetration_tolerance))
        return RUGO_ERR_NOT_FINITE;
    /* a step's velocity change by gravity, g h, must be a double too */
    if (!rugo__v2_finite(rugo_v2_scale(def->time_step, def->gravity))) return RUGO_ERR_NOT_FINITE;
    if (!(def->time_step > 0.0) || !(def->penetration_tolerance > 0.0)) return RUGO_ERR_BAD_ARGUMENT;
    if (def->integrator != RUGO_INTEGRATE_SYMPLECTIC_EULER && def->integrator != RUGO_INTEGRATE_EXPLICIT_EULER)
        return RUGO_ERR_BAD_ARGUMENT;
    if (def->max_bisections < 0 || def->max_bisections > 30) return RUGO_ERR_BAD_ARGUMENT;
    if ((def->micro_collisions != 0 && def->micro_collisions != 1) || (def->friction != 0 && def->friction != 1))
        return RUGO_ERR_BAD_ARGUMENT;
    if (def->max_contacts_per_pair < 1 || def->max_contacts_per_pair > MAX_PAIR_CONTACTS) return RUGO_ERR_BAD_ARGUMENT;

    rugo_allocator a = rugo__allocator_or_default(&def->allocator);
    rugo_world* w = (rugo_world*)rugo__alloc_array(&a, 1, sizeof *w);
    if (w == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(w, 0, sizeof *w);
    w->def = *def;
    w->allocator = a;
    w->g = rugo__v2_length(def->gravity);
    w->query = rugo_default_contact_query();
    w->query.level = def->level;
    if (rugo_sweep_prune_create(&a, &w->sap) != RUGO_OK || rugo_collide_context_create(&a, &w->ctx) != RUGO_OK) {
        rugo_world_destroy(w);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    *out = w;
    return RUGO_OK;
}

void rugo_world_destroy(rugo_world* w) {
    if (w == NULL) return;
    rugo_allocator a = w->allocator;
    rugo_sweep_prune_destroy(w->sap);
    rugo_collide_context_destroy(w->ctx);
    rugo__array* all[] = {&w->bodies,      &w->start,   &w->boxes,    &w->saved,
                          &w->pair_depth0, &w->scratch, &w->contacts, &w->records};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        rugo__array_free(all[i], &a);
    rugo__free(&a, w);
}

static int rot_ok(rugo_rot q) { return fabs(q.c * q.c + q.s * q.s - 1.0) <= 1e-6; }

static void body_set_transform(body* b, rugo_transform xf) {
    b->angle = atan2(xf.q.s, xf.q.c);
    b->xf = xf;
}

rugo_status rugo_world_add_body(rugo_world* w, const rugo_body_def* def, int* id) {
    if (w == NULL || def == NULL || id == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != BODY_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (def->shape == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->type != RUGO_BODY_STATIC && def->type != RUGO_BODY_DYNAMIC) return RUGO_ERR_BAD_ARGUMENT;
    if (!rugo__v2_finite(def->transform.p) || !isfinite(def->transform.q.c) || !isfinite(def->transform.q.s) ||
        !rugo__v2_finite(def->linear_velocity) || !isfinite(def->angular_velocity) || !isfinite(def->density))
        return RUGO_ERR_NOT_FINITE;
    if (!rot_ok(def->transform.q)) return RUGO_ERR_BAD_ARGUMENT;
    if (def->type == RUGO_BODY_DYNAMIC && !(def->density > 0.0)) return RUGO_ERR_BAD_ARGUMENT;
    if (w->count >= MAX_BODIES) return RUGO_ERR_TOO_LARGE;
    rugo_mass_properties mp = rugo_shape_mass(def->shape);
    const rugo_obb* root = rugo_mobb_tree_root(rugo_shape_tree(def->shape));
    if (root == NULL || !(mp.area > 0.0) || !(mp.inertia > 0.0)) return RUGO_ERR_BAD_ARGUMENT;
    /* A density so large or so small that the mass, the inertia or their inverses leave the doubles
     * would only fail later, in a step. */
    const rugo_real mass = def->density * mp.area, inertia = def->density * mp.inertia;
    if (def->type == RUGO_BODY_DYNAMIC &&
        (!isfinite(mass) || !isfinite(inertia) || !isfinite(1.0 / mass) || !isfinite(1.0 / inertia)))
        return RUGO_ERR_NOT_FINITE;

    /* Arrays grown before a failure keep their larger size. */
    const int need = w->count + 1;
    if (!world_reserve(w, &w->bodies, need, sizeof(body)) || !world_reserve(w, &w->start, need, sizeof(pose)) ||
        !world_reserve(w, &w->boxes, need, sizeof(rugo_aabb)) ||
        !world_reserve(w, &w->saved, need, sizeof(saved_body)))
        return RUGO_ERR_OUT_OF_MEMORY;

    body* b = &bodies_of(w)[w->count];
    memset(b, 0, sizeof *b);
    b->shape = def->shape;
    b->type = def->type;
    rugo_transform xf = def->transform;
    rugo_real qn = hypot(xf.q.c, xf.q.s);
    xf.q.c /= qn;
    xf.q.s /= qn;
    body_set_transform(b, xf);
    b->c_local = mp.centroid;
    b->root = *root;
    b->size = hypot(root->half[0], root->half[1]);
    b->restitution = rugo_shape_restitution(def->shape);
    b->user_data = def->user_data;
    if (def->type == RUGO_BODY_DYNAMIC) {
        b->mass = mass;
        b->inertia = inertia;
        b->inv_mass = 1.0 / b->mass;
        b->inv_inertia = 1.0 / b->inertia;
        b->v = def->linear_velocity;
        b->w = def->angular_velocity;
    }
    *id = w->count++;
    w->contacts_valid = 0;
    return RUGO_OK;
}

int rugo_world_body_count(const rugo_world* w) { return w != NULL ? w->count : 0; }

static rugo_vec2 body_center(const body* b) { return rugo_transform_point(b->xf, b->c_local); }

rugo_status rugo_world_body(const rugo_world* w, int id, rugo_body_state* out) {
    if (w == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (id < 0 || id >= w->count) return RUGO_ERR_BAD_ARGUMENT;
    const body* b = &bodies_of(w)[id];
    out->transform = b->xf;
    out->center = body_center(b);
    out->linear_velocity = b->v;
    out->angular_velocity = b->w;
    out->mass = b->mass;
    out->inertia = b->inertia;
    out->type = b->type;
    out->user_data = b->user_data;
    return RUGO_OK;
}

rugo_status rugo_world_set_velocity(rugo_world* w, int id, rugo_vec2 linear, rugo_real angular) {
    if (w == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (id < 0 || id >= w->count) return RUGO_ERR_BAD_ARGUMENT;
    if (!rugo__v2_finite(linear) || !isfinite(angular)) return RUGO_ERR_NOT_FINITE;
    body* b = &bodies_of(w)[id];
    if (b->type == RUGO_BODY_STATIC) {
        /* a static body never moves */
        if (linear.x != 0.0 || linear.y != 0.0 || angular != 0.0) return RUGO_ERR_BAD_ARGUMENT;
        return RUGO_OK;
    }
    b->v = linear;
    b->w = angular;
    return RUGO_OK;
}

rugo_status rugo_world_set_transform(rugo_world* w, int id, rugo_transform xf) {
    if (w == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (id < 0 || id >= w->count) return RUGO_ERR_BAD_ARGUMENT;
    if (!rugo__v2_finite(xf.p) || !isfinite(xf.q.c) || !isfinite(xf.q.s)) return RUGO_ERR_NOT_FINITE;
    if (!rot_ok(xf.q)) return RUGO_ERR_BAD_ARGUMENT;
    body_set_transform(&bodies_of(w)[id], xf);
    w->contacts_valid = 0;
    return RUGO_OK;
}

rugo_real rugo_world_kinetic_energy(const rugo_world* w) {
    if (w == NULL) return NAN;
    rugo_real e = 0.0;
    for (int i = 0; i < w->count; ++i) {
        const body* b = &bodies_of(w)[i];
        if (b->type != RUGO_BODY_DYNAMIC) continue;
        e += 0.5 * b->mass * rugo_v2_dot(b->v, b->v) + 0.5 * b->inertia * b->w * b->w;
    }
    return e;
}

const rugo_contact_record* rugo_world_contact_records(const rugo_world* w, int* count) {
    if (count != NULL) *count = w != NULL ? w->record_count : 0;
    return w != NULL ? records_of(w) : NULL;
}

/* ---- the step ----------------------------------------------------------------------------------- */

static void save_poses(rugo_world* w) {
    for (int i = 0; i < w->count; ++i) {
        const body* b = &bodies_of(w)[i];
        start_of(w)[i].c = body_center(b);
        start_of(w)[i].angle = b->angle;
        start_of(w)[i].xf = b->xf;
    }
}

/* Poses start + (velocities) * dt; dt = 0 restores the start exactly. */
static void move_from_start(rugo_world* w, rugo_real dt) {
    for (int i = 0; i < w->count; ++i) {
        body* b = &bodies_of(w)[i];
        if (b->type != RUGO_BODY_DYNAMIC || dt == 0.0) {
            b->xf = start_of(w)[i].xf;
            b->angle = start_of(w)[i].angle;
            continue;
        }
        rugo_vec2 c = rugo_v2_add(start_of(w)[i].c, rugo_v2_scale(dt, b->v));
        b->angle = start_of(w)[i].angle + b->w * dt;
        b->xf.q = rugo_rot_from_angle(b->angle);
        b->xf.p = rugo_v2_sub(c, rugo_rotate(b->xf.q, b->c_local));
    }
    w->contacts_valid = 0;
}

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
    const body* A = &bodies_of(w)[ia];
    const body* B = &bodies_of(w)[ib];
    int s_is_a = A->size <= B->size;
    const body* S = s_is_a ? A : B;
    const body* O = s_is_a ? B : A;
    int seg = s_is_a ? c->segment_a : c->segment_b;
    int lev_s = s_is_a ? c->level_a : c->level_b, lev_o = s_is_a ? c->level_b : c->level_a;
    if (seg < 0) return 0;
    rugo_contour cs, co;
    if (rugo_shape_level(S->shape, lev_s, &cs) != RUGO_OK || rugo_shape_level(O->shape, lev_o, &co) != RUGO_OK)
        return 0;
    rugo_vec2 n_out = s_is_a ? c->normal : rugo_v2_scale(-1.0, c->normal); /* from S toward O */
    rugo_vec2 tau = rugo_v2_perp(c->normal);
    rugo_vec2 p0 = s_is_a ? c->point_a : c->point_b;
    rugo_real band = (c->tolerance_a > 0.0 ? c->tolerance_a : 0.0) + (c->tolerance_b > 0.0 ? c->tolerance_b : 0.0);
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
            if (rugo_shape_closest_point(O->shape, lev_o, rugo_inv_transform_point(O->xf, q), &cp) != RUGO_OK) continue;
            rugo_vec2 no = rugo_rotate(O->xf.q, rugo_contour_normal(co, cp.segment, cp.t));
            if (rugo_v2_dot(no, n_out) > -FACE_COS) continue;
            rugo_vec2 cw = rugo_transform_point(O->xf, cp.point);
            rugo_real signed_d = rugo_v2_dot(rugo_v2_sub(q, cw), no);
            if (!(signed_d <= band)) continue;
            rugo_real u = rugo_v2_dot(rugo_v2_sub(q, p0), tau);
            int side = u < 0.0 ? 0 : 1;
            if ((side == 0 && u < umin) || (side == 1 && u > umax)) {
                if (side == 0) umin = u; else umax = u;
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
static rugo_status gather(rugo_world* w) {
    for (int i = 0; i < w->count; ++i) boxes_of(w)[i] = body_aabb(&bodies_of(w)[i]);
    rugo_status st = rugo_sweep_prune_update(w->sap, boxes_of(w), w->count);
    if (st != RUGO_OK) return st;
    int npairs = 0;
    const rugo_pair* pairs = rugo_sweep_prune_pairs(w->sap, &npairs);
    w->stats.candidate_pairs = npairs;
    w->contact_count = 0;
    if (w->scratch.capacity == 0 && !world_reserve(w, &w->scratch, 32, sizeof(rugo_contact)))
        return RUGO_ERR_OUT_OF_MEMORY;
    for (int p = 0; p < npairs; ++p) {
        const body* a = &bodies_of(w)[pairs[p].a];
        const body* b = &bodies_of(w)[pairs[p].b];
        if (a->type == RUGO_BODY_STATIC && b->type == RUGO_BODY_STATIC) continue;
        int count = 0;
        rugo_contact_state state;
        rugo_query_stats qs;
        st = rugo_collide_shapes(w->ctx, a->shape, a->xf, b->shape, b->xf, &w->query, scratch_of(w),
                                 (int)w->scratch.capacity, &count, &state, &qs);
        if (st != RUGO_OK) return st;
        w->stats.box_tests += qs.box_tests;
        if ((size_t)qs.contacts_found > w->scratch.capacity) {
            if (!world_reserve(w, &w->scratch, qs.contacts_found, sizeof(rugo_contact)))
                return RUGO_ERR_OUT_OF_MEMORY;
            st = rugo_collide_shapes(w->ctx, a->shape, a->xf, b->shape, b->xf, &w->query, scratch_of(w),
                                     (int)w->scratch.capacity, &count, &state, &qs);
            if (st != RUGO_OK) return st;
        }
        if (count == 0) continue;
        count = rugo_reduce_manifold(scratch_of(w), count, w->def.max_contacts_per_pair);
        if (count > w->def.max_contacts_per_pair) count = w->def.max_contacts_per_pair;
        if (!world_reserve(w, &w->contacts, w->contact_count + 3 * count, sizeof(world_contact)))
            return RUGO_ERR_OUT_OF_MEMORY;
        for (int k = 0; k < count; ++k) {
            world_contact* c = &contacts_of(w)[w->contact_count++];
            c->a = pairs[p].a;
            c->b = pairs[p].b;
            c->c = scratch_of(w)[k];
            world_contact* supports = &contacts_of(w)[w->contact_count];
            w->contact_count += probe_supports(w, pairs[p].a, pairs[p].b, &scratch_of(w)[k], supports);
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
        const pair_depth* p = &pair_depth0_of(w)[mid];
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
    rugo_real sa = bodies_of(w)[a].size, sb = bodies_of(w)[b].size;
    return frac * w->def.penetration_tolerance * (sa < sb ? sa : sb) + pair_depth_at_start(w, a, b);
}

/* 1 if some contact of the world's contacts overlaps deeper than frac × its allowance. The advance is found
 * penetrating at frac = 1; the bisection then stops it where the overlap is within STOP_FRAC of the
 * tolerance, so that impulses act on overlaps well inside it (not at its edge). */
#define STOP_FRAC 0.5
static int penetrating(const rugo_world* w, rugo_real frac) {
    for (int k = 0; k < w->contact_count; ++k) {
        const world_contact* c = &contacts_of(w)[k];
        if (-c->c.separation > pair_allowance(w, c->a, c->b, frac)) return 1;
    }
    return 0;
}

static rugo_vec2 point_velocity(const body* b, rugo_vec2 r) { return rugo_v2_add(b->v, rugo_v2_scale(b->w, rugo_v2_perp(r))); }

/* Contacts of one pair whose normals agree within GROUP_COS form a group (a face contact: both ends
 * of a flat piece, its joints); opposite normals (a body wedged between two sides) stay apart. */
#define GROUP_COS 0.9

/* Assigns each contact's group: the index of the group's first contact. */
static void group_contacts(rugo_world* w) {
    for (int k = 0; k < w->contact_count; ++k) {
        world_contact* c = &contacts_of(w)[k];
        c->group = k;
        for (int m = k - 1; m >= 0; --m) {
            const world_contact* o = &contacts_of(w)[m];
            if (o->a != c->a || o->b != c->b) break;
            if (o->group == m && rugo_v2_dot(o->c.normal, c->c.normal) > GROUP_COS) c->group = m;
        }
    }
}

/* Relative normal velocity (SPEC 10 sign: < 0 approaching) of a contact's midpoint. */
static rugo_real contact_vn(const rugo_world* w, const world_contact* wc, rugo_vec2* point) {
    const body* A = &bodies_of(w)[wc->a];
    const body* B = &bodies_of(w)[wc->b];
    *point = rugo_v2_scale(0.5, rugo_v2_add(wc->c.point_a, wc->c.point_b));
    rugo_vec2 va = point_velocity(A, rugo_v2_sub(*point, body_center(A)));
    rugo_vec2 vb = point_velocity(B, rugo_v2_sub(*point, body_center(B)));
    return -rugo_v2_dot(rugo_v2_sub(va, vb), wc->c.normal);
}

static rugo_real band_of(const rugo_contact* c) {
    return (c->tolerance_a > 0.0 ? c->tolerance_a : 0.0) + (c->tolerance_b > 0.0 ? c->tolerance_b : 0.0);
}

/* ε of a contact approaching at vn (< 0): the surfaces' ε, or for a micro-collision (7.3) ε_c(δ)
 * applied to an incoming speed of at most sqrt(2 g δ), the speed of a fall through the depth reached
 * (7.21-7.22): dissipative, so resting bodies settle. Never above 1 (no energy added). */
static rugo_real contact_restitution(const rugo_world* w, const body* A, const body* B, rugo_real vn, rugo_real lam,
                                     rugo_real la, rugo_real lb, rugo_real delta, rugo_real base_eps, int* micro) {
    rugo_real eps = base_eps;
    *micro = w->def.micro_collisions && w->g > 0.0 && lam > 0.0 && vn < 0.0 && -vn < sqrt(2.0 * w->g * lam);
    if (*micro) {
        /* ε_c = max over the bodies of ε_c(δ_i), each band taking its share δ λ_i/λ of the depth */
        rugo_real ea = rugo_restitution_in_band(&A->restitution, delta * la / lam, la);
        rugo_real eb = rugo_restitution_in_band(&B->restitution, delta * lb / lam, lb);
        rugo_real ec = ea > eb ? ea : eb;
        rugo_real fall = sqrt(2.0 * w->g * delta);
        eps = fall < -vn ? ec * fall / -vn : ec;
    }
    if (!(eps >= 0.0)) eps = 0.0;
    return eps > 1.0 ? 1.0 : eps;
}

/* One impulse for the group led by contact g (see docs/simulator.md, "Contact groups"): at the centre
 * of the approaching points weighted by approach speed × depth in the band, so that a flat face
 * resting on a flat face gets its impulse in the middle rather than at one end first. Returns 1 if an
 * impulse was applied. */
static int resolve_group(rugo_world* w, int g, rugo_status* status) {
    const world_contact* contacts = contacts_of(w); /* no contact is added here */
    const world_contact* lead = &contacts[g];
    body* A = &bodies_of(w)[lead->a];
    body* B = &bodies_of(w)[lead->b];
    rugo_real sw = 0.0, wmax = -1.0;
    rugo_vec2 sn = rugo_v2(0, 0);
    rugo_real sl = 0.0, sla = 0.0, sd = 0.0, ss = 0.0, smu = 0.0, seps = 0.0;
    int best = -1;
    for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b; ++k) {
        const world_contact* wc = &contacts[k];
        if (wc->group != g) continue;
        rugo_vec2 pt;
        rugo_real vn = contact_vn(w, wc, &pt);
        rugo_real lam = band_of(&wc->c);
        rugo_real depth = lam - wc->c.separation; /* into the combined band; beyond it if > λ */
        if (depth < 0.0) depth = 0.0;
        /* Depth, not speed: weighting by approach speed feeds rocking (the end coming down fastest
         * takes the impulse and flips the rotation). */
        rugo_real wt = depth + 0.1 * lam + 1e-9 * (A->size < B->size ? A->size : B->size);
        if (vn < 0.0 && wt > wmax) {
            wmax = wt;
            best = k;
        }
        sw += wt;

        sn = rugo_v2_add(sn, rugo_v2_scale(wt, wc->c.normal));
        sl += wt * lam;
        sla += wt * (wc->c.tolerance_a > 0.0 ? wc->c.tolerance_a : 0.0);
        sd += wt * (depth < lam ? depth : lam);
        ss += wt * wc->c.separation;
        smu += wt * wc->c.friction;
        seps += wt * wc->c.restitution;
    }
    if (best < 0 || !(sw > 0.0)) return 0;
    rugo_real nl = rugo__v2_length(sn);
    rugo_vec2 normal = nl > 0.0 ? rugo_v2_scale(1.0 / nl, sn) : contacts[best].c.normal;
    rugo_real lam = sl / sw, la = sla / sw, delta = sd / sw, sep = ss / sw;
    rugo_real mu = smu / sw, base_eps = seps / sw;
    rugo_real lb = lam - la;
    if (lb < 0.0) lb = 0.0;
    rugo_vec2 ca = body_center(A), cb = body_center(B);
    rugo_vec2 nba = rugo_v2_scale(-1.0, normal); /* SPEC 10: from B to A */

    /* The patch's two extreme points along the tangent, and the impulse pair that gives both the
     * restitution target simultaneously (2x2 normal system, compressive only). Its resultant acts at
     * their centre of pressure, where one impulse of SPEC 10 has the same effect on both bodies. */
    rugo_vec2 tau = rugo_v2_perp(normal);
    rugo_vec2 p1 = rugo_v2(0, 0), p2 = rugo_v2(0, 0);
    rugo_real u1 = INFINITY, u2 = -INFINITY;
    for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b; ++k) {
        if (contacts[k].group != g) continue;
        rugo_vec2 pt = rugo_v2_scale(0.5, rugo_v2_add(contacts[k].c.point_a, contacts[k].c.point_b));
        rugo_real u = rugo_v2_dot(pt, tau);
        if (u < u1) {
            u1 = u;
            p1 = pt;
        }
        if (u > u2) {
            u2 = u;
            p2 = pt;
        }
    }
    rugo_vec2 pts[2] = {p1, p2};
    rugo_real vns[2], arm_a[2], arm_b[2];
    for (int i = 0; i < 2; ++i) {
        rugo_vec2 ra = rugo_v2_sub(pts[i], ca), rb = rugo_v2_sub(pts[i], cb);
        vns[i] = rugo_v2_dot(rugo_v2_sub(point_velocity(A, ra), point_velocity(B, rb)), nba);
        arm_a[i] = rugo_v2_dot(rugo_v2_perp(ra), nba);
        arm_b[i] = rugo_v2_dot(rugo_v2_perp(rb), nba);
    }
    rugo_real vref = vns[0] < vns[1] ? vns[0] : vns[1];
    int micro = 0;
    rugo_real eps = contact_restitution(w, A, B, vref, lam, la, lb, delta, base_eps, &micro);
    rugo_real im = A->inv_mass + B->inv_mass;
    rugo_real m11 = im + A->inv_inertia * arm_a[0] * arm_a[0] + B->inv_inertia * arm_b[0] * arm_b[0];
    rugo_real m22 = im + A->inv_inertia * arm_a[1] * arm_a[1] + B->inv_inertia * arm_b[1] * arm_b[1];
    rugo_real m12 = im + A->inv_inertia * arm_a[0] * arm_a[1] + B->inv_inertia * arm_b[0] * arm_b[1];
    rugo_real t1 = vns[0] < 0.0 ? -(1.0 + eps) * vns[0] : 0.0;
    rugo_real t2 = vns[1] < 0.0 ? -(1.0 + eps) * vns[1] : 0.0;
    rugo_real det = m11 * m22 - m12 * m12;
    rugo_real l1 = -1.0, l2 = -1.0;
    if (u2 - u1 > 1e-9 * (A->size < B->size ? A->size : B->size) && det > 1e-12 * m11 * m22) {
        l1 = (m22 * t1 - m12 * t2) / det;
        l2 = (m11 * t2 - m12 * t1) / det;
    }
    rugo_vec2 point;
    if (l1 >= 0.0 && l2 >= 0.0 && l1 + l2 > 0.0) {
        point = rugo_v2_add(rugo_v2_scale(l1 / (l1 + l2), p1), rugo_v2_scale(l2 / (l1 + l2), p2));
    } else {
        /* one end alone: the one whose own impulse leaves the other end not approaching, else the
         * more approaching one */
        int i = vns[0] <= vns[1] ? 0 : 1;
        rugo_real li = (i == 0 ? t1 : t2) / (i == 0 ? m11 : m22);
        rugo_real other = vns[1 - i] + m12 * li;
        if (other < 0.0 && vns[1 - i] < 0.0) i = 1 - i;
        point = pts[i];
    }

    rugo_impulse_input in;
    in.inv_mass_a = A->inv_mass;
    in.inv_inertia_a = A->inv_inertia;
    in.inv_mass_b = B->inv_mass;
    in.inv_inertia_b = B->inv_inertia;
    in.r_a = rugo_v2_sub(point, ca);
    in.r_b = rugo_v2_sub(point, cb);
    in.v_a = A->v;
    in.v_b = B->v;
    in.w_a = A->w;
    in.w_b = B->w;
    in.normal = nba;
    rugo_real vn = rugo_v2_dot(rugo_v2_sub(point_velocity(A, in.r_a), point_velocity(B, in.r_b)), in.normal);
    if (!(vn < 0.0)) return 0;
    eps = contact_restitution(w, A, B, vn, lam, la, lb, delta, base_eps, &micro);
    in.restitution = eps;
    in.friction = w->def.friction && mu >= 0.0 && isfinite(mu) ? mu : 0.0;
    rugo_impulse_result r;
    if (rugo_collision_impulse(&in, &r) != RUGO_OK || r.branch == 0) return 0;
    A->v = rugo_v2_add(A->v, rugo_v2_scale(A->inv_mass, r.impulse));
    A->w += A->inv_inertia * rugo_v2_cross(in.r_a, r.impulse);
    B->v = rugo_v2_sub(B->v, rugo_v2_scale(B->inv_mass, r.impulse));
    B->w -= B->inv_inertia * rugo_v2_cross(in.r_b, r.impulse);
    w->stats.impulses++;
    if (!world_reserve(w, &w->records, w->record_count + 1, sizeof(rugo_contact_record))) {
        *status = RUGO_ERR_OUT_OF_MEMORY;
        return 1;
    }
    rugo_contact_record* rec = &records_of(w)[w->record_count++];
    rec->body_a = lead->a;
    rec->body_b = lead->b;
    rec->point = point;
    rec->normal = normal;
    rec->separation = sep;
    rec->tolerance = lam;
    rec->friction = in.friction;
    rec->restitution = eps;
    rec->normal_velocity_before = vn;
    rec->normal_velocity_after =
        rugo_v2_dot(rugo_v2_sub(point_velocity(A, in.r_a), point_velocity(B, in.r_b)), in.normal);
    rec->impulse_normal = r.impulse_normal;
    rec->impulse_tangent = r.impulse_tangent;
    rec->sticking = r.branch == 1;
    rec->micro = micro;
    return 1;
}

/* Impulses at every contact group of the world's contacts, one after another (7.4), in up to CONTACT_SWEEPS
 * sweeps (a sweep after the first only acts where points approach again). */
static rugo_status resolve(rugo_world* w) {
    w->stats.contacts += w->contact_count;
    group_contacts(w);
    for (int sweep = 0; sweep < CONTACT_SWEEPS; ++sweep) {
        int applied = 0;
        for (int k = 0; k < w->contact_count; ++k) {
            if (contacts_of(w)[k].group != k) continue;
            rugo_status st = RUGO_OK;
            applied += resolve_group(w, k, &st);
            if (st != RUGO_OK) return st;
        }
        if (applied == 0) break;
    }
    return RUGO_OK;
}

/* Samples of the advance needed so that no body moves more than a quarter of its size between two
 * samples (a fast body cannot pass through a thin one unseen). */
static int advance_samples(const rugo_world* w, rugo_real dt) {
    rugo_real worst = 0.0;
    for (int i = 0; i < w->count; ++i) {
        const body* b = &bodies_of(w)[i];
        if (b->type != RUGO_BODY_DYNAMIC) continue;
        rugo_real reach = b->size + rugo__v2_length(rugo_v2_sub(b->root.center, b->c_local));
        rugo_real travel = (rugo__v2_length(b->v) + fabs(b->w) * reach) * dt;
        rugo_real ratio = travel / (0.25 * b->size);
        if (ratio > worst) worst = ratio;
    }
    if (!(worst < 64.0)) return 64;
    int k = (int)ceil(worst);
    return k < 1 ? 1 : k;
}

/* Position projection of existing overlaps (docs/simulator.md, "Overlaps"): bisection only stops an
 * overlap from deepening and impulses only act on approaching points, so an overlap left by a step
 * (the TOI_EVENTS limit, several bodies pressed together, a body squeezed between two) would persist
 * for ever, and the allowance built on it let it ratchet deeper step after step. Each group whose true
 * curves overlap by more than PROJECT_SLOP × the tolerance allowance is translated apart along its
 * separating normal by the overlap beyond the slop, split by inverse mass, at most PROJECT_CAP × the
 * smaller body's size per pass. Only positions change: velocities (so kinetic energy) are untouched.
 * Up to PROJECT_PASSES passes (Gauss-Seidel over the groups), re-gathering the contacts between. */
#define PROJECT_PASSES 4
#define PROJECT_SLOP 0.5
#define PROJECT_CAP 0.05
static rugo_status project_overlaps(rugo_world* w) {
    for (int pass = 0; pass < PROJECT_PASSES; ++pass) {
        group_contacts(w);
        const world_contact* contacts = contacts_of(w); /* until the gather at the end of the pass */
        int moved = 0;
        for (int g = 0; g < w->contact_count; ++g) {
            const world_contact* lead = &contacts[g];
            if (lead->group != g) continue;
            body* A = &bodies_of(w)[lead->a];
            body* B = &bodies_of(w)[lead->b];
            rugo_real im = A->inv_mass + B->inv_mass;
            if (!(im > 0.0)) continue;
            rugo_real deepest = 0.0;
            rugo_vec2 n = lead->c.normal;
            for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b; ++k) {
                if (contacts[k].group != g) continue;
                if (-contacts[k].c.separation > deepest) {
                    deepest = -contacts[k].c.separation;
                    n = contacts[k].c.normal;
                }
            }
            rugo_real smin = A->size < B->size ? A->size : B->size;
            rugo_real slop = PROJECT_SLOP * w->def.penetration_tolerance * smin;
            rugo_real push = deepest - slop;
            if (!(push > 0.0)) continue;
            if (push > PROJECT_CAP * smin) push = PROJECT_CAP * smin;
            /* the normal points from A toward B */
            A->xf.p = rugo_v2_sub(A->xf.p, rugo_v2_scale(push * A->inv_mass / im, n));
            B->xf.p = rugo_v2_add(B->xf.p, rugo_v2_scale(push * B->inv_mass / im, n));
            moved = 1;
        }
        if (!moved) break;
        w->contacts_valid = 0;
        rugo_status st = gather(w);
        if (st != RUGO_OK) return st;
    }
    return RUGO_OK;
}

/* The part of the step after the gravity of symplectic Euler: contacts, advance, bisection. */
static rugo_status step_contacts_and_move(rugo_world* w) {
    rugo_real h = w->def.time_step;
    rugo_status st;
    if (!w->contacts_valid) {
        st = gather(w);
        if (st != RUGO_OK) return st;
    }
    st = project_overlaps(w);
    if (st != RUGO_OK) return st;
    /* Overlaps that remain at the start (after the projection) may persist, per pair, but not deepen
     * beyond the tolerance: bisection cannot undo them. */
    w->pair_depth_count = 0;
    for (int k = 0; k < w->contact_count; ++k) {
        const world_contact* c = &contacts_of(w)[k];
        rugo_real d = -c->c.separation;
        if (!(d > 0.0)) continue;
        pair_depth* last = w->pair_depth_count > 0 ? &pair_depth0_of(w)[w->pair_depth_count - 1] : NULL;
        if (last != NULL && last->a == c->a && last->b == c->b) {
            if (d > last->depth) last->depth = d;
            continue;
        }
        if (!world_reserve(w, &w->pair_depth0, w->pair_depth_count + 1, sizeof(pair_depth)))
            return RUGO_ERR_OUT_OF_MEMORY;
        pair_depth* pd = &pair_depth0_of(w)[w->pair_depth_count++];
        pd->a = c->a;
        pd->b = c->b;
        pd->depth = d;
    }
    st = resolve(w);
    if (st != RUGO_OK) return st;

    rugo_real left = h; /* time still to advance */
    for (int event = 0;; ++event) {
        save_poses(w);
        int samples = advance_samples(w, left), hit = 0;
        rugo_real lo = 0.0, hi = left;
        for (int j = 1; j <= samples; ++j) {
            rugo_real t = j == samples ? left : left * (rugo_real)j / (rugo_real)samples;
            move_from_start(w, t);
            st = gather(w);
            if (st != RUGO_OK) return st;
            if (penetrating(w, 1.0)) {
                hit = 1;
                hi = t;
                break;
            }
            lo = t;
        }
        if (!hit) break;
        if (w->def.max_bisections == 0 || event >= TOI_EVENTS) {
            if (lo != left || hi != left) { /* the end state is where the step must stop */
                move_from_start(w, left);
                st = gather(w);
                if (st != RUGO_OK) return st;
            }
            w->stats.unresolved = 1;
            break;
        }
        if (lo > 0.0) { /* the last sample may be safe for the trigger but not for the stop */
            move_from_start(w, lo);
            st = gather(w);
            if (st != RUGO_OK) return st;
            if (penetrating(w, STOP_FRAC)) lo = 0.0;
        }
        for (int k = 0; k < w->def.max_bisections; ++k) {
            rugo_real mid = 0.5 * (lo + hi);
            move_from_start(w, mid);
            st = gather(w);
            if (st != RUGO_OK) return st;
            w->stats.bisections++;
            if (penetrating(w, STOP_FRAC))
                hi = mid;
            else
                lo = mid;
        }
        move_from_start(w, lo);
        st = gather(w);
        if (st != RUGO_OK) return st;
        int before = w->stats.impulses;
        st = resolve(w);
        if (st != RUGO_OK) return st;
        left -= lo;
        if (lo == 0.0 && w->stats.impulses == before) {
            /* Nothing approaches at the start yet the advance penetrates at once: cannot resolve. */
            move_from_start(w, left);
            st = gather(w);
            if (st != RUGO_OK) return st;
            w->stats.unresolved = 1;
            break;
        }
    }
    return RUGO_OK;
}

rugo_status rugo_world_step(rugo_world* w, rugo_step_stats* stats) {
    if (w == NULL) return RUGO_ERR_NULL_ARGUMENT;
    memset(&w->stats, 0, sizeof w->stats);
    w->record_count = 0;
    rugo_real h = w->def.time_step;
    rugo_vec2 gh = rugo_v2_scale(h, w->def.gravity);
    int symplectic = w->def.integrator == RUGO_INTEGRATE_SYMPLECTIC_EULER;
    body* bodies = bodies_of(w); /* no body is added during a step */
    saved_body* saved = saved_of(w);

    for (int i = 0; i < w->count; ++i) {
        saved[i].xf = bodies[i].xf;
        saved[i].angle = bodies[i].angle;
        saved[i].v = bodies[i].v;
        saved[i].w = bodies[i].w;
    }
    if (symplectic)
        for (int i = 0; i < w->count; ++i)
            if (bodies[i].type == RUGO_BODY_DYNAMIC) bodies[i].v = rugo_v2_add(bodies[i].v, gh);
    rugo_status st = step_contacts_and_move(w);
    if (st != RUGO_OK) {
        for (int i = 0; i < w->count; ++i) {
            bodies[i].xf = saved[i].xf;
            bodies[i].angle = saved[i].angle;
            bodies[i].v = saved[i].v;
            bodies[i].w = saved[i].w;
        }
        w->contacts_valid = 0;
        w->record_count = 0;
        return st;
    }
    if (!symplectic)
        for (int i = 0; i < w->count; ++i)
            if (bodies[i].type == RUGO_BODY_DYNAMIC) bodies[i].v = rugo_v2_add(bodies[i].v, gh);
    w->stats.kinetic_energy = rugo_world_kinetic_energy(w);
    if (stats != NULL) *stats = w->stats;
    return RUGO_OK;
}
