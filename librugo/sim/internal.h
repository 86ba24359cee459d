/* Private to the simulator (librugo/sim) and its tests: the broad phase, sweep and prune on
 * axis-aligned boxes, and the impulse at one contact point. The world (world.h) is built on them; they
 * are not part of what a user of the simulator needs, but each is tested on its own. Not installed. */
#ifndef RUGO_SIM_INTERNAL_H
#define RUGO_SIM_INTERNAL_H

#include "rugo/base.h"

/* ---------------------------------------------------------------------------------------------------
 * The impulse at one contact (SPEC 10; impulse.c). */

/* Two bodies at one contact point, for rugo__collision_impulse (SI units). */
typedef struct rugo__impulse_input {
    /* Inverse masses (1/kg) and inverse moments of inertia (1/(kg m^2)); 0 for static bodies. */
    rugo_real inv_mass_a, inv_inertia_a, inv_mass_b, inv_inertia_b;
    /* Contact point relative to each centre of mass, m. */
    rugo_vec2 r_a, r_b;
    /* Velocities of the centres of mass, m/s. */
    rugo_vec2 v_a, v_b;
    /* Angular velocities, rad/s. */
    rugo_real w_a, w_b;
    rugo_vec2 normal;      /* unit, from B to A (SPEC 10 convention) */
    rugo_real friction;    /* μ >= 0 */
    rugo_real restitution; /* ε in [0, 1] */
} rugo__impulse_input;
/* The impulse of one collision. */
typedef struct rugo__impulse_result {
    rugo_vec2 impulse; /* J on A (B gets -J), N s */
    /* Its components along the normal and the tangent, N s. */
    rugo_real impulse_normal, impulse_tangent;
    int branch;              /* 0 none (separating), 1 sticking, 2 sliding, 3 frictionless */
    rugo_real energy_change; /* kinetic energy after minus before (<= 0 up to round-off), J */
} rugo__impulse_result;
/* The collision impulse at one contact (SPEC 10) into *out; never adds kinetic energy. Errors:
 * NULL_ARGUMENT, NOT_FINITE, BAD_ARGUMENT (μ < 0, ε outside [0, 1], normal not unit). */
rugo_status rugo__collision_impulse(const rugo__impulse_input* in, rugo__impulse_result* out);

/* ---------------------------------------------------------------------------------------------------
 * Sweep and prune (SPEC 7; sweep_prune.c). */

/* A pair of overlapping boxes, by index. */
typedef struct rugo__pair {
    /* Indices of the two boxes, a < b. */
    int a, b;
} rugo__pair;
/* Sweep-and-prune broad phase (opaque). */
typedef struct rugo__sweep_prune rugo__sweep_prune;
/* Creates an empty sweep and prune into *out (owned by the caller; free with
 * rugo__sweep_prune_destroy); it allocates through `allocator` (NULL = malloc/free) as it grows.
 * Errors: NULL_ARGUMENT, OUT_OF_MEMORY. */
rugo_status rugo__sweep_prune_create(const rugo_allocator* allocator, rugo__sweep_prune** out);
/* Frees it; NULL is allowed. */
void rugo__sweep_prune_destroy(rugo__sweep_prune* sap);
/* Boxes of all n objects for this step. The first call (or a change of n) sorts and sweeps (general
 * algorithm); later calls insertion-sort the nearly sorted end points and add/remove pairs at each swap
 * (coherence algorithm), keeping pairs in a hash table. Errors: NULL_ARGUMENT, NOT_FINITE,
 * BAD_ARGUMENT (lower > upper), OUT_OF_MEMORY. */
rugo_status rugo__sweep_prune_update(rugo__sweep_prune* sap, const rugo_aabb* boxes, int n);
/* The overlapping pairs (boxes touching count), sorted by (a, b), owned by sap and valid until the
 * next update; their number goes to *count (count may be NULL). NULL and 0 for NULL. */
const rugo__pair* rugo__sweep_prune_pairs(const rugo__sweep_prune* sap, int* count);
/* Swaps done by the last update (0 for the general algorithm or NULL). */
long rugo__sweep_prune_swaps(const rugo__sweep_prune* sap);

#endif
