/* librugo — the thesis' own simulator: a small world of rough rigid bodies with impulse-based
 * dynamics (SPEC 7, 9, 10; thesis chapters 6-7), for programs that do not use Box2D.
 *
 * Bodies are rugo_shapes placed by a transform of their local frame (the shape's coordinates); the
 * body's position is the world position of the shape's local origin. Mass and inertia come from the
 * exact contour integrals times density. Each step: broad phase (sweep and prune on the root boxes'
 * axis-aligned bounds, SPEC 7), contacts by rugo_collide_shapes at the world's level of detail,
 * time of contact by bisection (SPEC 9), impulses at every contact point (SPEC 10) with per-point μ and
 * ε from the surfaces' friction maps, micro-collisions for resting contact (7.3), then integration.
 * No contact impulse ever adds kinetic energy (tested). Nothing per step allocates once the world's
 * buffers have grown to the scene. Deterministic: same defs and steps, same bits. */
#ifndef RUGO_WORLD_H
#define RUGO_WORLD_H
#include "rugo/base.h"
#include "rugo/collide.h"
#include "rugo/shape.h"
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif

typedef enum rugo_integrator {
    RUGO_INTEGRATE_SYMPLECTIC_EULER = 0, /* v += a h, then x += v h (default: stable resting contact) */
    RUGO_INTEGRATE_EXPLICIT_EULER = 1    /* the thesis' x += v h, v += a h */
} rugo_integrator;

typedef enum rugo_body_type {
    RUGO_BODY_STATIC = 0, /* infinite mass, never moves */
    RUGO_BODY_DYNAMIC = 1
} rugo_body_type;

typedef struct rugo_world_def {
    rugo_vec2 gravity;        /* m/s^2; default (0, -9.81) */
    rugo_real time_step;      /* s, > 0; default 1/60 */
    rugo_integrator integrator;
    int level;                /* level of detail of contacts (rugo_contact_query.level); default 0 */
    int max_bisections;       /* halvings of a step toward the time of contact; default 8, 0..30 */
    /* Penetration beyond the bands that triggers bisection, as a fraction of the smaller body's size
     * (root box half-diagonal); default 0.01. */
    rugo_real penetration_tolerance;
    int micro_collisions;     /* 1 (default): resting contact as micro-collisions with ε_c(δ) (7.3) */
    int friction;             /* 1 (default): per-point μ; 0: frictionless */
    int max_contacts_per_pair; /* default 8 */
    rugo_allocator allocator;
    int cookie;
} rugo_world_def;
rugo_world_def rugo_default_world_def(void);

typedef struct rugo_body_def {
    const rugo_shape* shape;    /* shared, not copied; must outlive the world */
    rugo_body_type type;        /* default RUGO_BODY_DYNAMIC */
    rugo_transform transform;   /* placement of the shape's local frame; default identity */
    rugo_vec2 linear_velocity;  /* of the centre of mass, m/s */
    rugo_real angular_velocity; /* rad/s */
    rugo_real density;          /* kg/m^2, > 0 for a dynamic body; default 1 */
    void* user_data;
    int cookie;
} rugo_body_def;
rugo_body_def rugo_default_body_def(void);

typedef struct rugo_world rugo_world;

/* Errors: NULL_ARGUMENT, BAD_ARGUMENT (cookie, time_step <= 0, integrator, max_bisections out of
 * range, ...), NOT_FINITE, OUT_OF_MEMORY. */
rugo_status rugo_world_create(const rugo_world_def* def, rugo_world** out);
void rugo_world_destroy(rugo_world* world);

/* Adds a body; *id is its index (0, 1, 2, ... in creation order). Errors: NULL_ARGUMENT,
 * BAD_ARGUMENT (cookie, type, density), NOT_FINITE, OUT_OF_MEMORY. */
rugo_status rugo_world_add_body(rugo_world* world, const rugo_body_def* def, int* id);
int rugo_world_body_count(const rugo_world* world);

typedef struct rugo_body_state {
    rugo_transform transform;   /* of the shape's local frame */
    rugo_vec2 center;           /* world centre of mass */
    rugo_vec2 linear_velocity;
    rugo_real angular_velocity;
    rugo_real mass, inertia;    /* inertia about the centre of mass; 0 for static bodies */
    rugo_body_type type;
    void* user_data;
} rugo_body_state;
/* BAD_ARGUMENT for an id out of range. */
rugo_status rugo_world_body(const rugo_world* world, int id, rugo_body_state* out);
rugo_status rugo_world_set_velocity(rugo_world* world, int id, rugo_vec2 linear, rugo_real angular);
rugo_status rugo_world_set_transform(rugo_world* world, int id, rugo_transform transform);

typedef struct rugo_step_stats {
    int candidate_pairs;   /* pairs from the sweep and prune */
    long box_tests;        /* OBB tests in the tree traversals */
    int contacts;          /* contact points handled */
    int impulses;          /* impulses applied (collisions + micro-collisions) */
    int bisections;        /* step halvings toward a time of contact */
    int unresolved;        /* 1 if the bisection limit was reached with penetration left (see docs) */
    rugo_real kinetic_energy; /* after the step, J */
} rugo_step_stats;

/* One impulse applied at a contact point during the last step. */
typedef struct rugo_contact_record {
    int body_a, body_b;
    rugo_vec2 point;           /* world, midway between the two curve points */
    rugo_vec2 normal;          /* unit, from A to B */
    rugo_real separation;      /* curve distance (negative: overlap), before the bands */
    rugo_real tolerance;       /* λ_A + λ_B at the points */
    rugo_real friction;        /* μ used */
    rugo_real restitution;     /* ε used (ε_c(δ) for micro-collisions) */
    rugo_real normal_velocity_before, normal_velocity_after; /* relative, along the normal */
    rugo_real impulse_normal, impulse_tangent; /* J_n >= 0 and |J_t| <= μ J_n */
    int sticking;              /* 1 sticking branch, 0 sliding/frictionless */
    int micro;                 /* 1 if a micro-collision (resting contact) */
} rugo_contact_record;

/* Advances one time step. stats may be NULL. Errors: NULL_ARGUMENT, OUT_OF_MEMORY (buffers could not
 * grow; the world is left as before the step). */
rugo_status rugo_world_step(rugo_world* world, rugo_step_stats* stats);
/* The impulses of the last step (valid until the next step). */
const rugo_contact_record* rugo_world_contact_records(const rugo_world* world, int* count);
rugo_real rugo_world_kinetic_energy(const rugo_world* world);

/* ---- the impulse at one contact (SPEC 10), exposed for tests and other solvers ---------------- */
typedef struct rugo_impulse_input {
    rugo_real inv_mass_a, inv_inertia_a, inv_mass_b, inv_inertia_b; /* 0 for static bodies */
    rugo_vec2 r_a, r_b;        /* contact point relative to each centre of mass */
    rugo_vec2 v_a, v_b;        /* velocities of the centres of mass */
    rugo_real w_a, w_b;        /* angular velocities */
    rugo_vec2 normal;          /* unit, from B to A (SPEC 10 convention) */
    rugo_real friction;        /* μ >= 0 */
    rugo_real restitution;     /* ε in [0, 1] */
} rugo_impulse_input;
typedef struct rugo_impulse_result {
    rugo_vec2 impulse;         /* J on A (B gets -J) */
    rugo_real impulse_normal, impulse_tangent;
    int branch;                /* 0 none (separating), 1 sticking, 2 sliding, 3 frictionless */
    rugo_real energy_change;   /* kinetic energy after minus before (<= 0 up to round-off) */
} rugo_impulse_result;
/* Errors: NULL_ARGUMENT, NOT_FINITE, BAD_ARGUMENT (μ < 0, ε outside [0, 1], normal not unit). */
rugo_status rugo_collision_impulse(const rugo_impulse_input* in, rugo_impulse_result* out);

/* ---- sweep and prune (SPEC 7), exposed for tests and the benchmarks --------------------------- */
typedef struct rugo_aabb {
    rugo_vec2 lower, upper;
} rugo_aabb;
typedef struct rugo_pair {
    int a, b; /* a < b */
} rugo_pair;
typedef struct rugo_sweep_prune rugo_sweep_prune;
rugo_status rugo_sweep_prune_create(const rugo_allocator* allocator, rugo_sweep_prune** out);
void rugo_sweep_prune_destroy(rugo_sweep_prune* sap);
/* Boxes of all n objects for this step. The first call (or a change of n) sorts and sweeps (general
 * algorithm); later calls insertion-sort the nearly sorted end points and add/remove pairs at each swap
 * (coherence algorithm), keeping pairs in a hash table. Errors: NULL_ARGUMENT, NOT_FINITE,
 * BAD_ARGUMENT (lower > upper), OUT_OF_MEMORY. */
rugo_status rugo_sweep_prune_update(rugo_sweep_prune* sap, const rugo_aabb* boxes, int n);
/* The overlapping pairs (boxes touching count), sorted by (a, b); valid until the next update. */
const rugo_pair* rugo_sweep_prune_pairs(const rugo_sweep_prune* sap, int* count);
/* Swaps done by the last update (0 for the general algorithm). */
long rugo_sweep_prune_swaps(const rugo_sweep_prune* sap);

#ifdef __cplusplus
}
#endif
#endif
