/* Engine-neutral descriptions of the thesis' chapter-7 scenes (Figs. 7.4-7.13) and of the main demo,
 * shared by the Box2D samples (samples/box2d/b2_*.cpp) and the simulator samples (rugo_world).
 *
 * A scene is a list of bodies, gravity, a time step, a duration and the level of detail of its
 * contacts. Rough bodies carry a rugo_shape built here (with its roughness λ per segment, friction map
 * and restitution); the scene owns its shapes, and several bodies may share one. Only the demo also has
 * ordinary bodies (boxes, circles, a static chain ground) for engines that have them.
 *
 * Units: metres, kilograms, seconds. Bodies are 0.1-2 m across. The tolerance library's values (0.04
 * to 0.65, sized in the thesis for objects ~10 units across) are multiplied by SCENE_ROUGHNESS_SCALE,
 * so bands are 0.8 mm to 13 mm. Every rough shape uses scene_friction_map(): μ = 0.1 on a smooth
 * surface (λ <= 0.04 s) rising linearly to μ = 0.9 at the library's roughest λ = 0.65 s.
 *
 * Everything is deterministic (seeded roughness). Usage:
 *     scene s;
 *     if (scene_create(SCENE_THROWN, 1, &s) != RUGO_OK) ...;
 *     for (int i = 0; i < s.body_count; ++i) { const scene_body* b = &s.bodies[i]; ... }
 *     scene_destroy(&s);
 * A scene is a large struct (fixed arrays, no allocation besides the shapes): keep it static or on
 * the heap in small stacks. */
#ifndef RUGO_SAMPLES_SCENES_H
#define RUGO_SAMPLES_SCENES_H

#include "rugo/rugo.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Library tolerance units -> metres. */
#define SCENE_ROUGHNESS_SCALE 0.02

enum { SCENE_MAX_BODIES = 96, SCENE_MAX_SHAPES = 24, SCENE_MAX_CHAIN = 64 };

typedef enum scene_id {
    SCENE_BALL = 0,        /* Fig. 7.4-7.6; variant = tipo pair 0..5 (scene_ball_pair) */
    SCENE_THROWN = 1,      /* Fig. 7.7-7.8; variant 0 = (a) both tipo_2, 1 = (b) smooth body on a
                              rough / smooth / rough block */
    SCENE_FOUR_BODIES = 2, /* Fig. 7.9; variant 0 */
    SCENE_GRAFICA = 3,     /* Fig. 7.10-7.11; variant 0 = tipo_2, 1 = tipo_3 */
    SCENE_LEVELS = 4,      /* Fig. 7.12-7.13; variant 0 = level -1, 1 = level -2, 2 = level 0 (reference) */
    SCENE_DEMO = 5,        /* the README's main demo; variant 0 */
    SCENE_COUNT
} scene_id;

/* Number of variants of a scene (0 for an invalid id). */
int scene_variant_count(scene_id id);

typedef enum scene_body_kind {
    SCENE_ROUGH = 0,  /* a rugo_shape */
    SCENE_BOX = 1,    /* ordinary box (half_extents), demo only */
    SCENE_CIRCLE = 2, /* ordinary circle (radius), demo only */
    SCENE_CHAIN = 3   /* ordinary static open chain (chain points in body coordinates), demo only; the free
                         side is to the right of the direction of travel (Box2D 2.4's one-sided chains) */
} scene_body_kind;

/* What a body is for in its scene (the samples look bodies up by role). */
typedef enum scene_role {
    SCENE_ROLE_GROUND = 0,  /* fixed block / ground / container */
    SCENE_ROLE_MOVER = 1,   /* the body the figure follows (ball, thrown body, striking ball) */
    SCENE_ROLE_OBJECT = 2,  /* other free bodies (four bodies, letters, level objects, demo bodies) */
    SCENE_ROLE_OBSTACLE = 3 /* a second fixed body (Fig. 7.9) */
} scene_role;

typedef struct scene_body {
    char name[24];
    scene_body_kind kind;
    scene_role role;
    const rugo_shape* shape; /* SCENE_ROUGH: owned by the scene, possibly shared with other bodies */
    rugo_vec2 half_extents;  /* SCENE_BOX */
    rugo_real radius;        /* SCENE_CIRCLE */
    const rugo_vec2* chain;  /* SCENE_CHAIN: chain_count points (owned by the scene) */
    int chain_count;
    int is_static;                   /* 1: fixed (infinite mass) */
    rugo_transform transform;        /* placement of the shape's local frame (body origin) */
    rugo_vec2 linear_velocity;       /* of the centre of mass, m/s */
    rugo_real angular_velocity;      /* rad/s */
    rugo_real density;               /* kg/m^2 (dynamic bodies) */
    rugo_real friction, restitution; /* ordinary bodies' material (rough bodies: from the shape) */
    int level;                       /* contact level relative to the finest: 0, -1, -2 (= scene.level) */
} scene_body;

typedef struct scene {
    scene_id id;
    int variant;
    const char* name;           /* e.g. "ball tipo_1/tipo_2" (static storage or label below) */
    const char* figure;         /* e.g. "Fig. 7.5-7.6" */
    const char* measures;       /* one line: what the scene measures */
    char label[64];             /* variant label, e.g. "tipo_1-tipo_2", "level-1" */
    rugo_vec2 gravity;          /* m/s^2 */
    rugo_real time_step;        /* s */
    rugo_real duration;         /* s */
    int level;                  /* contact level of detail of every rough body (0, -1, -2) */
    rugo_vec2 view_lo, view_hi; /* a box that frames the scene (for pictures) */
    rugo_real ground_top;       /* height of the fixed block's top surface (bodies below it fell through) */
    /* SCENE_THROWN variant 1: the block's top is rough for x < stretch[0], smooth for stretch[0] <= x <
     * stretch[1] and rough again beyond; stretch_mu = the friction μ there (rough, smooth) predicted by
     * the friction map for a smooth mover. Zero elsewhere. */
    rugo_real stretch[2], stretch_mu[2];
    int body_count;
    scene_body bodies[SCENE_MAX_BODIES];
    int shape_count;
    rugo_shape* shapes[SCENE_MAX_SHAPES];
    rugo_vec2 chain[SCENE_MAX_CHAIN];
} scene;

/* Builds a scene. Errors: BAD_ARGUMENT (id or variant), those of rugo_shape_create (on error
 * everything built so far is freed and *out is zeroed). */
rugo_status scene_create(scene_id id, int variant, scene* out);
void scene_destroy(scene* s);

/* The friction map of every rough shape in the scenes (see above). */
rugo_friction_map scene_friction_map(void);

/* The six tipo pairs of Fig. 7.5, (a)..(f): ball preset and block preset of variant 0..5. */
void scene_ball_pair(int variant, rugo_tolerance_preset* ball, rugo_tolerance_preset* block);

/* Largest λ (total tolerance) of a shape at a contact level relative to its finest (0, -1, ...):
 * the widest band a body of the scene can rest on. */
rugo_real scene_max_band(const rugo_shape* shape, int level);

#ifdef __cplusplus
}
#endif

#endif
