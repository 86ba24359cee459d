/* The simulator's world and its bodies (world.h): defaults, creation, adding bodies, reading and setting
 * their state. Separate from the step (world_step.c), which is the part that moves them. */
#include "sim/world_internal.h"

#include <string.h>

#define WORLD_DEF_COOKIE 0x52554757 /* "RUGW" */
#define BODY_DEF_COOKIE 0x52554742  /* "RUGB" */
#define MAX_PAIR_CONTACTS 64
#define MAX_BODIES (1 << 24)

/* Room for `need` elements of `elem` bytes in one of the world's arrays: the capacity doubles from 8,
 * up to 2^29 elements (counts stay ints). 0 on failure, the array then unchanged. */
int rugo__world_reserve(rugo_world* w, rugo__array* a, int need, size_t elem) {
    if (need > (1 << 29)) return 0;
    return rugo__array_reserve(a, &w->allocator, (size_t)need, elem, 8) == RUGO_OK;
}

rugo_world_def rugo_default_world_def(void) {
    rugo_world_def d;
    memset(&d, 0, sizeof d);
    d.gravity = rugo_v2(0.0, -9.81);
    d.time_step = 1.0 / 60.0;
    d.integrator = RUGO_INTEGRATE_SYMPLECTIC_EULER;
    d.lod = 0;
    d.resolution = 0.0;
    d.contact_rule = RUGO_CONTACT_THESIS;
    d.max_bisections = 8;
    d.penetration_tolerance = 0.01;
    d.micro_collisions = true;
    d.friction = true;
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
    if (def->integrator != RUGO_INTEGRATE_SYMPLECTIC_EULER &&
        def->integrator != RUGO_INTEGRATE_EXPLICIT_EULER)
        return RUGO_ERR_BAD_ARGUMENT;
    if (def->max_bisections < 0 || def->max_bisections > 30) return RUGO_ERR_BAD_ARGUMENT;
    if (def->max_contacts_per_pair < 1 || def->max_contacts_per_pair > MAX_PAIR_CONTACTS)
        return RUGO_ERR_BAD_ARGUMENT;
    if (!isfinite(def->resolution)) return RUGO_ERR_NOT_FINITE;
    if (def->lod > 0 || (def->resolution < 0.0 && def->resolution != RUGO_RESOLUTION_AUTO) ||
        (unsigned)def->contact_rule > (unsigned)RUGO_CONTACT_THESIS)
        return RUGO_ERR_BAD_ARGUMENT;

    rugo_allocator a = rugo__allocator_or_default(&def->allocator);
    rugo_world* w = (rugo_world*)rugo__alloc_array(&a, 1, sizeof *w);
    if (w == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(w, 0, sizeof *w);
    w->def = *def;
    w->allocator = a;
    w->g = rugo__v2_length(def->gravity);
    w->query = rugo_default_contact_query();
    w->query.lod = def->lod;
    w->query.resolution = def->resolution;
    w->query.contact_rule = def->contact_rule;
    if (rugo__sweep_prune_create(&a, &w->sap) != RUGO_OK ||
        rugo_collide_context_create(&a, &w->ctx) != RUGO_OK) {
        rugo_world_destroy(w);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    *out = w;
    return RUGO_OK;
}

void rugo_world_destroy(rugo_world* w) {
    if (w == NULL) return;
    rugo_allocator a = w->allocator;
    rugo__sweep_prune_destroy(w->sap);
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
    if (!rugo__v2_finite(def->transform.p) || !isfinite(def->transform.q.c) ||
        !isfinite(def->transform.q.s) || !rugo__v2_finite(def->linear_velocity) ||
        !isfinite(def->angular_velocity) || !isfinite(def->density) || !isfinite(def->rolling_resistance))
        return RUGO_ERR_NOT_FINITE;
    if (def->rolling_resistance < 0.0) return RUGO_ERR_BAD_ARGUMENT;
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
    if (!rugo__world_reserve(w, &w->bodies, need, sizeof(body)) ||
        !rugo__world_reserve(w, &w->start, need, sizeof(pose)) ||
        !rugo__world_reserve(w, &w->boxes, need, sizeof(rugo_aabb)) ||
        !rugo__world_reserve(w, &w->saved, need, sizeof(saved_body)))
        return RUGO_ERR_OUT_OF_MEMORY;

    body* b = &rugo__world_bodies(w)[w->count];
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
    b->rolling_resistance = def->rolling_resistance;
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

rugo_status rugo_world_body(const rugo_world* w, int id, rugo_body_state* out) {
    if (w == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (id < 0 || id >= w->count) return RUGO_ERR_BAD_ARGUMENT;
    const body* b = &rugo__world_bodies(w)[id];
    out->transform = b->xf;
    out->center = rugo__body_center(b);
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
    body* b = &rugo__world_bodies(w)[id];
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
    body_set_transform(&rugo__world_bodies(w)[id], xf);
    w->contacts_valid = 0;
    return RUGO_OK;
}

rugo_real rugo_world_kinetic_energy(const rugo_world* w) {
    if (w == NULL) return NAN;
    rugo_real e = 0.0;
    for (int i = 0; i < w->count; ++i) {
        const body* b = &rugo__world_bodies(w)[i];
        if (b->type != RUGO_BODY_DYNAMIC) continue;
        e += 0.5 * b->mass * rugo_v2_dot(b->v, b->v) + 0.5 * b->inertia * b->w * b->w;
    }
    return e;
}

const rugo_contact_record* rugo_world_contact_records(const rugo_world* w, int* count) {
    if (count != NULL) *count = w != NULL ? w->record_count : 0;
    return w != NULL ? rugo__world_records(w) : NULL;
}

/* ---- the step ----------------------------------------------------------------------------------- */
