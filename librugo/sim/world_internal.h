/* Private to the simulator's world (the world*.c files of librugo/sim): the world and its bodies as the
 * step sees them, and what the files of the step offer each other. Not installed; world.h is the
 * world's interface, sim/internal.h the broad phase and the impulse it is built on. */
#ifndef RUGO_SIM_WORLD_INTERNAL_H
#define RUGO_SIM_WORLD_INTERNAL_H

#include "rugo/world.h"

#include "core/array.h"
#include "core/internal.h"
#include "sim/internal.h"

/* A body: its shape, pose and velocities, and the mass properties and bounds the step reads. */
typedef struct body {
    const rugo_shape* shape;
    rugo_body_type type;
    rugo_transform xf; /* of the shape's local frame */
    rugo_real angle;   /* of xf.q, integrated (the rotation is recomputed from it) */
    rugo_vec2 c_local; /* centre of mass in the shape's frame */
    rugo_vec2 v;
    rugo_real w;
    rugo_real mass, inertia, inv_mass, inv_inertia;
    rugo_obb root;  /* local */
    rugo_real size; /* root half-diagonal */
    rugo_restitution restitution;
    rugo_real rolling_resistance; /* rugo_body_def.rolling_resistance */
    void* user_data;
} body;

/* A body's pose at the start of an advance, from which the advance moves it by its velocities. */
typedef struct pose {
    rugo_vec2 c; /* world centre of mass */
    rugo_real angle;
    rugo_transform xf;
} pose;

/* A body's state at the start of a step, restored when the step fails. */
typedef struct saved_body {
    rugo_transform xf;
    rugo_real angle;
    rugo_vec2 v;
    rugo_real w;
} saved_body;

/* The deepest overlap of the body pair (a, b) at the start of a step. */
typedef struct pair_depth {
    int a, b;
    rugo_real depth;
} pair_depth;

/* A contact of the body pair (a, b). */
typedef struct world_contact {
    int a, b;
    int group; /* index of the first contact of its group (same pair, similar normal) */
    rugo_contact c;
} world_contact;

/* The world: its def, its bodies (and their arrays), the broad phase, the contact query and its
 * scratch, the contacts at the current poses, and what the last step did. */
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
    rugo__sweep_prune* sap;
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

/* The world's arrays as their elements (the pointers change when an array grows). */
static inline body* rugo__world_bodies(const rugo_world* w) { return (body*)w->bodies.data; }
static inline pose* rugo__world_start(const rugo_world* w) { return (pose*)w->start.data; }
static inline rugo_aabb* rugo__world_boxes(const rugo_world* w) { return (rugo_aabb*)w->boxes.data; }
static inline saved_body* rugo__world_saved(const rugo_world* w) { return (saved_body*)w->saved.data; }
static inline pair_depth* rugo__world_pair_depth0(const rugo_world* w) {
    return (pair_depth*)w->pair_depth0.data;
}
static inline rugo_contact* rugo__world_scratch(const rugo_world* w) {
    return (rugo_contact*)w->scratch.data;
}
static inline world_contact* rugo__world_contacts(const rugo_world* w) {
    return (world_contact*)w->contacts.data;
}
static inline rugo_contact_record* rugo__world_records(const rugo_world* w) {
    return (rugo_contact_record*)w->records.data;
}

/* A body's centre of mass in world coordinates. */
static inline rugo_vec2 rugo__body_center(const body* b) { return rugo_transform_point(b->xf, b->c_local); }

/* Room for `need` elements of `elem` bytes in one of the world's arrays (world.c). */
int rugo__world_reserve(rugo_world* w, rugo__array* a, int need, size_t elem);

/* ---------------------------------------------------------------------------------------------------
 * Contacts at the current poses (world_contacts.c). */

/* Broad phase and contacts at the current poses into the world's contacts, with support probing. */
rugo_status rugo__gather_contacts(rugo_world* w);
/* 1 if some contact overlaps deeper than frac × its pair's allowance. */
int rugo__penetrating(const rugo_world* w, rugo_real frac);
/* Assigns each contact's group: the index of the group's first contact. */
void rugo__group_contacts(rugo_world* w);

/* ---------------------------------------------------------------------------------------------------
 * Impulses (world_impulses.c). */

/* Impulses at every contact group, one after another (7.4), in up to CONTACT_SWEEPS sweeps. */
rugo_status rugo__resolve_contacts(rugo_world* w);

#endif
