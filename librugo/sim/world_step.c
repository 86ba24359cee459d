/* The step of the thesis' own simulator, rugo_world_step (SPEC 7, 9, 10; thesis chapters 6-7): what
 * moves the bodies, with the contacts (world_contacts.c) and impulses (world_impulses.c) it applies on
 * the way. docs/simulator.md explains the step; the short version:
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
 * its centre of pressure; support probing adds the patch's ends (world_contacts.c, docs/simulator.md).
 * Micro-collisions (7.3): a point inside its band approaching slower than sqrt(2 g λ) counts its
 * incoming speed as at most sqrt(2 g δ) and leaves with ε_c(δ) times it (dissipative). */
#include "sim/world_internal.h"

#include <string.h>

#define TOI_EVENTS 8 /* bisected contact events per step */
/* The bisection stops an advance where every overlap is within STOP_FRAC of its allowance (it is found
 * penetrating at 1), so that impulses act on overlaps well inside the tolerance, not at its edge. */
#define STOP_FRAC 0.5

static void save_poses(rugo_world* w) {
    for (int i = 0; i < w->count; ++i) {
        const body* b = &rugo__world_bodies(w)[i];
        rugo__world_start(w)[i].c = rugo__body_center(b);
        rugo__world_start(w)[i].angle = b->angle;
        rugo__world_start(w)[i].xf = b->xf;
    }
}

/* Poses start + (velocities) * dt; dt = 0 restores the start exactly. */
static void move_from_start(rugo_world* w, rugo_real dt) {
    for (int i = 0; i < w->count; ++i) {
        body* b = &rugo__world_bodies(w)[i];
        if (b->type != RUGO_BODY_DYNAMIC || dt == 0.0) {
            b->xf = rugo__world_start(w)[i].xf;
            b->angle = rugo__world_start(w)[i].angle;
            continue;
        }
        rugo_vec2 c = rugo_v2_add(rugo__world_start(w)[i].c, rugo_v2_scale(dt, b->v));
        b->angle = rugo__world_start(w)[i].angle + b->w * dt;
        b->xf.q = rugo_rot_from_angle(b->angle);
        b->xf.p = rugo_v2_sub(c, rugo_rotate(b->xf.q, b->c_local));
    }
    w->contacts_valid = 0;
}

/* Samples of the advance needed so that no body moves more than a quarter of its size between two
 * samples (a fast body cannot pass through a thin one unseen). */
static int advance_samples(const rugo_world* w, rugo_real dt) {
    rugo_real worst = 0.0;
    for (int i = 0; i < w->count; ++i) {
        const body* b = &rugo__world_bodies(w)[i];
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
        rugo__group_contacts(w);
        /* the contacts until they are gathered again at the end of the pass */
        const world_contact* contacts = rugo__world_contacts(w);
        int moved = 0;
        for (int g = 0; g < w->contact_count; ++g) {
            const world_contact* lead = &contacts[g];
            if (lead->group != g) continue;
            body* A = &rugo__world_bodies(w)[lead->a];
            body* B = &rugo__world_bodies(w)[lead->b];
            rugo_real im = A->inv_mass + B->inv_mass;
            if (!(im > 0.0)) continue;
            rugo_real deepest = 0.0;
            rugo_vec2 n = lead->c.normal;
            for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b;
                 ++k) {
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
        rugo_status st = rugo__gather_contacts(w);
        if (st != RUGO_OK) return st;
    }
    return RUGO_OK;
}

/* The part of the step after the gravity of symplectic Euler: contacts, advance, bisection. */
static rugo_status step_contacts_and_move(rugo_world* w) {
    rugo_real h = w->def.time_step;
    rugo_status st;
    if (!w->contacts_valid) {
        st = rugo__gather_contacts(w);
        if (st != RUGO_OK) return st;
    }
    st = project_overlaps(w);
    if (st != RUGO_OK) return st;
    /* Overlaps that remain at the start (after the projection) may persist, per pair, but not deepen
     * beyond the tolerance: bisection cannot undo them. */
    w->pair_depth_count = 0;
    for (int k = 0; k < w->contact_count; ++k) {
        const world_contact* c = &rugo__world_contacts(w)[k];
        rugo_real d = -c->c.separation;
        if (!(d > 0.0)) continue;
        pair_depth* depths = rugo__world_pair_depth0(w);
        pair_depth* last = w->pair_depth_count > 0 ? &depths[w->pair_depth_count - 1] : NULL;
        if (last != NULL && last->a == c->a && last->b == c->b) {
            if (d > last->depth) last->depth = d;
            continue;
        }
        if (!rugo__world_reserve(w, &w->pair_depth0, w->pair_depth_count + 1, sizeof(pair_depth)))
            return RUGO_ERR_OUT_OF_MEMORY;
        pair_depth* pd = &rugo__world_pair_depth0(w)[w->pair_depth_count++];
        pd->a = c->a;
        pd->b = c->b;
        pd->depth = d;
    }
    st = rugo__resolve_contacts(w);
    if (st != RUGO_OK) return st;

    rugo_real left = h; /* time still to advance */
    for (int event = 0;; ++event) {
        save_poses(w);
        int samples = advance_samples(w, left), hit = 0;
        rugo_real lo = 0.0, hi = left;
        for (int j = 1; j <= samples; ++j) {
            rugo_real t = j == samples ? left : left * (rugo_real)j / (rugo_real)samples;
            move_from_start(w, t);
            st = rugo__gather_contacts(w);
            if (st != RUGO_OK) return st;
            if (rugo__penetrating(w, 1.0)) {
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
                st = rugo__gather_contacts(w);
                if (st != RUGO_OK) return st;
            }
            w->stats.unresolved = true;
            break;
        }
        if (lo > 0.0) { /* the last sample may be safe for the trigger but not for the stop */
            move_from_start(w, lo);
            st = rugo__gather_contacts(w);
            if (st != RUGO_OK) return st;
            if (rugo__penetrating(w, STOP_FRAC)) lo = 0.0;
        }
        for (int k = 0; k < w->def.max_bisections; ++k) {
            rugo_real mid = 0.5 * (lo + hi);
            move_from_start(w, mid);
            st = rugo__gather_contacts(w);
            if (st != RUGO_OK) return st;
            w->stats.bisections++;
            if (rugo__penetrating(w, STOP_FRAC))
                hi = mid;
            else
                lo = mid;
        }
        move_from_start(w, lo);
        st = rugo__gather_contacts(w);
        if (st != RUGO_OK) return st;
        int before = w->stats.impulses;
        st = rugo__resolve_contacts(w);
        if (st != RUGO_OK) return st;
        left -= lo;
        if (lo == 0.0 && w->stats.impulses == before) {
            /* Nothing approaches at the start yet the advance penetrates at once: cannot resolve. */
            move_from_start(w, left);
            st = rugo__gather_contacts(w);
            if (st != RUGO_OK) return st;
            w->stats.unresolved = true;
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
    body* bodies = rugo__world_bodies(w); /* no body is added during a step */
    saved_body* saved = rugo__world_saved(w);

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
