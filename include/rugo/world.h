/** @file rugo/world.h
 * librugo — the thesis' own simulator: a small world of rough rigid bodies with impulse-based
 * dynamics (SPEC 7, 9, 10; thesis chapters 6-7), for programs that do not use Box2D.
 *
 * Bodies are rugo_shapes placed by a transform of their local frame (the shape's coordinates); the
 * body's position is the world position of the shape's local origin. Mass and inertia come from the
 * exact contour integrals times density. Each step: broad phase (sweep and prune on the root boxes'
 * axis-aligned bounds, SPEC 7), contacts by rugo_collide_shapes at the world's level of detail,
 * time of contact by bisection (SPEC 9), impulses at every contact point (SPEC 10) with per-point μ and
 * ε from the surfaces' friction maps, micro-collisions for resting contact (7.3), then integration.
 * No contact impulse ever adds kinetic energy (tested). Nothing per step allocates once the world's
 * buffers have grown to the scene. Deterministic: same defs and steps, same bits.
 *
 * Units: SI as in the defs below (metres, kilograms, seconds, radians); shapes are in metres.
 * Ownership: a world is created by rugo_world_create, owned by the caller and freed by
 * rugo_world_destroy; it allocates through its def's allocator. Bodies borrow their shapes, which must
 * outlive the world. Arrays it returns stay valid until the next step or destroy. */
#ifndef RUGO_WORLD_H
#define RUGO_WORLD_H
#include "rugo/base.h"
#include "rugo/collide.h"
#include "rugo/shape.h"
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif

/** The time integrator of rugo_world_step. */
typedef enum rugo_integrator {
    /** v += a h, then x += v h (default: no energy gained in flight, a resting body reports v = 0 on
     *  average; docs/simulator.md, "Integrators") */
    RUGO_INTEGRATE_SYMPLECTIC_EULER = 0,
    /** the thesis' x += v h, then v += a h (gains g²h²/2 per unit mass each step of flight; a resting
     *  body reports g h downwards) */
    RUGO_INTEGRATE_EXPLICIT_EULER = 1
} rugo_integrator;

/** Kinds of body in a rugo_world. */
typedef enum rugo_body_type {
    RUGO_BODY_STATIC = 0, /**< infinite mass, never moves */
    RUGO_BODY_DYNAMIC = 1 /**< moved by gravity and contact impulses */
} rugo_body_type;

/** What rugo_world_create needs. Start from rugo_default_world_def(). */
typedef struct rugo_world_def {
    rugo_vec2 gravity;          /**< m/s^2; default (0, -9.81) */
    rugo_real time_step;        /**< s, > 0; default 1/60 */
    rugo_integrator integrator; /**< default RUGO_INTEGRATE_SYMPLECTIC_EULER */
    int lod; /**< level of detail of contacts (rugo_contact_query.lod: 0 finest, < 0 coarser); default 0 */
    /** Resolution of contacts (rugo_contact_query.resolution); default 0, the round-off answers: the
     * thesis' simulator reproduces its experiments with its own contacts. */
    rugo_real resolution;
    /** Where contacts are (rugo_contact_query.contact_rule); default RUGO_CONTACT_THESIS (6.15). */
    rugo_contact_rule contact_rule;
    int max_bisections; /**< halvings of a step toward the time of contact; default 8, 0..30 */
    /** Penetration beyond the bands that triggers bisection, as a fraction of the smaller body's size
     * (root box half-diagonal); default 0.01. */
    rugo_real penetration_tolerance;
    bool micro_collisions;     /**< true (default): resting contact as micro-collisions with ε_c(δ) (7.3) */
    bool friction;             /**< true (default): per-point μ; false: frictionless */
    int max_contacts_per_pair; /**< contacts kept per body pair and step; 1..64, default 8 */
    rugo_allocator allocator;  /**< used for the world's lifetime; zeroed = malloc/free */
    int cookie;                /**< set by rugo_default_world_def; catches uninitialised defs */
} rugo_world_def;
/** A def with the defaults above and its cookie set. */
RUGO_API rugo_world_def rugo_default_world_def(void);

/** What rugo_world_add_body needs. Start from rugo_default_body_def(). */
typedef struct rugo_body_def {
    const rugo_shape* shape;    /**< shared, not copied; must outlive the world */
    rugo_body_type type;        /**< default RUGO_BODY_DYNAMIC */
    rugo_transform transform;   /**< placement of the shape's local frame; default identity */
    rugo_vec2 linear_velocity;  /**< of the centre of mass, m/s */
    rugo_real angular_velocity; /**< rad/s */
    rugo_real density;          /**< kg/m^2, > 0 for a dynamic body; default 1 */
    /** Rolling resistance from roughness (docs/roughness.md, "Rolling resistance"), >= 0, default 0
     * (off: the thesis' dynamics): at each impulse of a contact, an angular impulse of at most
     * k J_n (λ_A + λ_B) against the two bodies' relative turning (J_n the normal impulse, λ the bands at
     * the contact, k the larger of the two bodies' values), never more than stops it. Errors: NOT_FINITE,
     * BAD_ARGUMENT (negative). */
    rugo_real rolling_resistance;
    void* user_data; /**< the caller's, returned in rugo_body_state; never dereferenced */
    int cookie;      /**< set by rugo_default_body_def; catches uninitialised defs */
} rugo_body_def;
/** A def with the defaults above and its cookie set; fill in shape. */
RUGO_API rugo_body_def rugo_default_body_def(void);

/** A simulator world (opaque): bodies, broad phase, contact scratch. */
typedef struct rugo_world rugo_world;

/** Creates an empty world into *out (owned by the caller; free with rugo_world_destroy). Errors:
 * NULL_ARGUMENT, BAD_ARGUMENT (cookie, time_step <= 0, integrator, max_bisections out of
 * range, ...), NOT_FINITE (also when gravity times time_step overflows), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_world_create(const rugo_world_def* def, rugo_world** out);
/** Frees the world and its buffers (not the shapes); NULL is allowed. */
RUGO_API void rugo_world_destroy(rugo_world* world);

/** Adds a body; *id is its index (0, 1, 2, ... in creation order). Errors: NULL_ARGUMENT,
 * BAD_ARGUMENT (cookie, type, density, a rotation that is not unit), NOT_FINITE (also a density that
 * makes the mass, the inertia or their inverses overflow), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_world_add_body(rugo_world* world, const rugo_body_def* def, int* id);
/** Number of bodies (0 for NULL). */
RUGO_API int rugo_world_body_count(const rugo_world* world);

/** A body's state after the last step (SI units). */
typedef struct rugo_body_state {
    rugo_transform transform;   /**< of the shape's local frame */
    rugo_vec2 center;           /**< world centre of mass */
    rugo_vec2 linear_velocity;  /**< of the centre of mass, m/s */
    rugo_real angular_velocity; /**< rad/s */
    /** Mass (kg) and moment of inertia about the centre of mass (kg m^2); 0 for static bodies. @{ */
    rugo_real mass, inertia;
    /** @} */
    rugo_body_type type; /**< as created */
    void* user_data;     /**< as given in the body def */
} rugo_body_state;
/** The state of body `id` into *out. Errors: NULL_ARGUMENT, BAD_ARGUMENT (id out of range). */
RUGO_API rugo_status rugo_world_body(const rugo_world* world, int id, rugo_body_state* out);
/** Sets a body's linear (m/s, of the centre of mass) and angular (rad/s) velocity. Errors:
 * NULL_ARGUMENT, BAD_ARGUMENT (id out of range, or a non-zero velocity for a static body),
 * NOT_FINITE. */
RUGO_API rugo_status rugo_world_set_velocity(rugo_world* world, int id, rugo_vec2 linear, rugo_real angular);
/** Moves a body (placement of its shape's local frame; the rotation must be unit within 1e-6).
 * Errors: NULL_ARGUMENT, BAD_ARGUMENT (id out of range, rotation not unit), NOT_FINITE. */
RUGO_API rugo_status rugo_world_set_transform(rugo_world* world, int id, rugo_transform transform);

/** What one step did. */
typedef struct rugo_step_stats {
    int candidate_pairs;      /**< pairs from the sweep and prune */
    long box_tests;           /**< OBB tests in the tree traversals */
    int contacts;             /**< contact points handled */
    int impulses;             /**< impulses applied (collisions + micro-collisions) */
    int bisections;           /**< step halvings toward a time of contact */
    bool unresolved;          /**< true if the bisection limit was reached with penetration left (see docs) */
    rugo_real kinetic_energy; /**< after the step, J */
} rugo_step_stats;

/** One impulse applied at a contact point during the last step. */
typedef struct rugo_contact_record {
    /** The two bodies' ids. @{ */
    int body_a, body_b;
    /** @} */
    rugo_vec2 point;       /**< world, midway between the two curve points */
    rugo_vec2 normal;      /**< unit, from A to B */
    rugo_real separation;  /**< curve distance (negative: overlap), before the bands */
    rugo_real tolerance;   /**< λ_A + λ_B at the points */
    rugo_real friction;    /**< μ used */
    rugo_real restitution; /**< ε used (ε_c(δ) for micro-collisions) */
    /** Relative velocity along the normal before and after the impulse, m/s. @{ */
    rugo_real normal_velocity_before, normal_velocity_after;
    /** @} */
    /** Normal and tangential impulse, N s: J_n >= 0 and |J_t| <= μ J_n. @{ */
    rugo_real impulse_normal, impulse_tangent;
    /** @} */
    bool sticking; /**< true: the sticking branch; false: sliding or frictionless */
    bool micro;    /**< true if a micro-collision (resting contact) */
} rugo_contact_record;

/** Advances one time step. stats may be NULL. Errors (the world is then left as before the step):
 * NULL_ARGUMENT, OUT_OF_MEMORY (buffers could not grow), NOT_FINITE (a pose, velocity or impulse
 * overflowed, e.g. bodies thrown at speeds near the largest double). */
RUGO_API rugo_status rugo_world_step(rugo_world* world, rugo_step_stats* stats);
/** The impulses of the last step (owned by the world, valid until the next step); their number goes
 * to *count (count may be NULL). NULL and 0 for a NULL world. */
RUGO_API const rugo_contact_record* rugo_world_contact_records(const rugo_world* world, int* count);
/** Total kinetic energy of the dynamic bodies, J (NaN for NULL). */
RUGO_API rugo_real rugo_world_kinetic_energy(const rugo_world* world);

#ifdef __cplusplus
}
#endif
#endif
