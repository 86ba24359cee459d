/* Helpers shared by the headless simulator samples (sim_*.c): build a chapter-7 scene (scenes.h) in a
 * rugo_world, step it, measure it the way the Box2D samples do (b2_sample.hpp: energy, μ at contacts,
 * first contact and rebound, lowest centre, deepest true-curve overlap, FNV-1a hash of the transforms)
 * and draw SVG frames with the samples' SVG writer. Not part of the library.
 *
 * Differences from the Box2D helpers, all forced by what each engine exposes:
 *  - μ is the μ of every impulse the simulator applied in a step (rugo_world_contact_records: collisions
 *    and micro-collisions, each sweep), where Box2D gives one μ per touching manifold per step;
 *  - "in contact" means "received an impulse this step" (a body resting on its band still receives
 *    micro-collision impulses every step or two);
 *  - the hash runs over the double bits of (p.x, p.y, q.c, q.s) of every body, Box2D's over float
 *    (x, y, angle). */
#ifndef RUGO_SAMPLES_SIM_SAMPLE_H
#define RUGO_SAMPLES_SIM_SAMPLE_H

#include "rugo/rugo.h"
#include "rugo/world.h"
#include "scenes.h"

#include <stdint.h>
#include <stdio.h>

typedef struct sim_run {
    const scene* sc;
    rugo_world* world;
    int id[SCENE_MAX_BODIES];      /* world body id per scene body */
    double band[SCENE_MAX_BODIES]; /* widest band of each body at the scene's level */
    int level[SCENE_MAX_BODIES];   /* absolute level of each body's contacts */
    double time;
    long steps;
    uint64_t hash;        /* FNV-1a over every body's transform after every step (and at 0) */
    rugo_step_stats last; /* stats of the last step */
    long impulses, unresolved_steps, bisections;
} sim_run;

/* Builds every body of the scene in a new world (time step, gravity and level from the scene; def may
 * be NULL for rugo_default_world_def()). Only rough bodies: returns -1 with a message for a scene with
 * ordinary bodies (boxes, circles, chains: the demo) or if the world refuses one. 0 on success. */
int sim_build(sim_run* r, const scene* s, const rugo_world_def* def);
void sim_destroy(sim_run* r);
/* One step; 0 on success (a message and -1 otherwise). Updates time, steps, hash, stats. */
int sim_step(sim_run* r);

int sim_find(const scene* s, scene_role role, int nth);
rugo_body_state sim_body(const sim_run* r, int i);
double sim_speed(const rugo_body_state* b);
/* Kinetic plus potential energy (scene gravity) of the dynamic bodies, J. */
double sim_energy(const sim_run* r);
double sim_kinetic(const sim_run* r);
/* Kinetic energy right after gravity's kick of the next step (v += g h, symplectic Euler): the kinetic
 * energy the contact impulses of that step start from. Their net change, sim_kinetic() after the step
 * minus this, is <= 0 when no impulse adds energy (world.h's promise). */
double sim_kinetic_after_kick(const sim_run* r);
/* Bound on the mechanical energy one step can gain from the discretisation alone: symplectic Euler adds
 * gravity's kick m|g|h|v_in| to the kinetic energy of a body whose normal velocity an impulse then
 * reverses, while its potential energy follows the outgoing velocity, so a step with a bounce can gain
 * up to m|g|h(|v_in| + |v_out|) with no work done. For resting contact (micro-collisions, 7.3) both
 * speeds are below sqrt(2|g|Λ), Λ the body's band plus the widest band of the fixed bodies; summed over
 * the dynamic bodies: Σ m|g|h 2 sqrt(2|g|Λ). */
double sim_micro_growth_bound(const sim_run* r);
/* Lowest point of the body's curve at its contact level (world y). */
double sim_lowest_point(const sim_run* r, int i);

/* Every body at its current transform: its curve at the contact level, the band's outer offset dashed
 * when show_band, and the contact points of the last step as dots. 0 on success. */
int sim_draw_frame(const sim_run* r, const char* path, const char* title, int show_band);
/* Opens dir/name for writing (a message on failure). */
FILE* sim_open_out(const char* dir, const char* name);
/* Least-squares slope of y(x); NaN for fewer than 2 points. */
double sim_slope(const double* x, const double* y, int n);

/* Runs a scene to its end (as b2s::RunScene): writes <prefix>.csv (t,body,name,x,y,angle,vx,vy,w of every
 * body every 6th step), frames <prefix>_<step>.svg at the listed steps and the last, and gathers: */
typedef struct sim_record {
    int body_count;
    double start[SCENE_MAX_BODIES][3], final[SCENE_MAX_BODIES][3]; /* centre x, y, angle */
    double first_contact[SCENE_MAX_BODIES];                        /* time of the first impulse (NaN: none) */
    double impact_y[SCENE_MAX_BODIES], rebound_y[SCENE_MAX_BODIES]; /* centre y then; highest within 1 s */
    double e0, max_growth, final_kinetic, min_y; /* max_growth: largest step increase of energy / |e0| */
    double max_growth_abs;                       /* the same in J */
    double max_impulse_gain;                     /* largest kinetic energy the impulses of a step added, J */
    double min_curve_above;                      /* lowest curve point of a free body minus ground_top */
    double worst_overlap;                        /* deepest true-curve overlap at an impulse (-separation) */
    int worst_a, worst_b;
    double worst_time;                 /* when */
    double worst_separation_tolerance; /* that impulse's λ_A + λ_B */
    double mu_sum;                     /* over every impulse of the run */
    long mu_count;
    double body_mu_sum[SCENE_MAX_BODIES]; /* over the impulses each body took part in */
    long body_mu_count[SCENE_MAX_BODIES];
    long steps, impulses, micro, sticking, unresolved_steps;
    uint64_t hash;
} sim_record;
typedef void (*sim_after_step)(const sim_run* r, void* user);
/* frames: steps to draw (count n_frames); after (may be NULL) is called after every step. 0 on success. */
int sim_run_scene(sim_run* r, const char* dir, const char* prefix, const long* frames, int n_frames,
                  sim_record* rec, sim_after_step after, void* user);
double sim_record_mean_mu(const sim_record* rec);

#endif
