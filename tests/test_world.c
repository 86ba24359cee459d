/* World suite (SPEC 7, 9, 10; thesis 6-7): the simulator's acceptance.
 *
 * Shapes: blocks are closed cubic B-splines with doubled control points at the corners and two more
 * on each side (exactly straight sides, tightly rounded corners; test_sharp_block_rests_in_band uses
 * tripled corners, sharp ones); discs are 32 control
 * points on a circle (a curve within 2e-4 of a circle of radius R0 (2 + cos(2π/32))/3).
 * Figures printed to stderr are the ones docs/simulator.md quotes. */
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct surface {
    double lambda; /* constant tolerance; 0 = smooth */
    double mu;     /* constant friction (α = 0) */
    double eps, eps_max;
} surface;

static rugo_shape* make_shape(const rugo_vec2* pts, int n, surface sf) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts;
    d.count = n;
    double lam[64];
    for (int i = 0; i < n; ++i)
        lam[i] = sf.lambda;
    d.tolerances = sf.lambda > 0.0 ? lam : NULL;
    d.friction.alpha = 0.0;
    d.friction.lambda_min = 0.0;
    d.friction.base = sf.mu;
    d.restitution.epsilon = sf.eps;
    d.restitution.epsilon_max = sf.eps_max;
    rugo_shape* s = NULL;
    ck_assert_int_eq(rugo_shape_create(&d, &s, NULL), RUGO_OK);
    return s;
}

static rugo_shape* make_block(double w, double h, surface sf) {
    double x = 0.5 * w, y = 0.5 * h;
    rugo_vec2 c[4] = {{x, -y}, {x, y}, {-x, y}, {-x, -y}};
    rugo_vec2 p[16];
    int k = 0;
    for (int i = 0; i < 4;
         ++i) { /* doubled corner, two points on the side: straight sides, tight round corners */
        rugo_vec2 n = c[(i + 1) % 4];
        p[k++] = c[i];
        p[k++] = c[i];
        p[k++] = rugo_v2(c[i].x + (n.x - c[i].x) / 3.0, c[i].y + (n.y - c[i].y) / 3.0);
        p[k++] = rugo_v2(c[i].x + 2.0 * (n.x - c[i].x) / 3.0, c[i].y + 2.0 * (n.y - c[i].y) / 3.0);
    }
    return make_shape(p, 16, sf);
}

static rugo_shape* make_disc(double r0, int n, surface sf) {
    rugo_vec2 p[64];
    for (int i = 0; i < n; ++i)
        p[i] = rugo_v2(r0 * cos(2 * PI * i / n), r0 * sin(2 * PI * i / n));
    return make_shape(p, n, sf);
}

static double disc_radius(double r0, int n) { return r0 * (2.0 + cos(2 * PI / n)) / 3.0; }

static rugo_world* make_world(rugo_world_def d) {
    rugo_world* w = NULL;
    ck_assert_int_eq(rugo_world_create(&d, &w), RUGO_OK);
    return w;
}

static int add(rugo_world* w, const rugo_shape* s, rugo_body_type type, double x, double y, double a,
               rugo_vec2 v, double omega) {
    rugo_body_def b = rugo_default_body_def();
    b.shape = s;
    b.type = type;
    b.transform = rugo_make_transform(x, y, a);
    b.linear_velocity = v;
    b.angular_velocity = omega;
    b.density = 2.0;
    int id = -1;
    ck_assert_int_eq(rugo_world_add_body(w, &b, &id), RUGO_OK);
    return id;
}

static rugo_body_state state(const rugo_world* w, int id) {
    rugo_body_state s;
    ck_assert_int_eq(rugo_world_body(w, id, &s), RUGO_OK);
    return s;
}

/* ---- friction: a thrown block stops at v²/(2 μ g) ---------------------------------------------- */

static double slide_distance(double lambda, double mu, double v0, double h, int* sticking_seen) {
    surface sf = {lambda, mu, 0.5, 0.9};
    rugo_shape* floor = make_block(40.0, 1.0, sf);
    rugo_shape* blk = make_block(0.5, 0.25, sf);
    rugo_world_def d = rugo_default_world_def();
    d.time_step = h;
    rugo_world* w = make_world(d);
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    /* resting inside the two bands (λ_A + λ_B = 2λ), half way */
    int b = add(w, blk, RUGO_BODY_DYNAMIC, -15.0, 0.125 + lambda, 0.0, rugo_v2(v0, 0), 0.0);
    double x0 = state(w, b).center.x;
    double t_expected = v0 / (mu * 9.81);
    int steps = (int)(2.0 * t_expected / h) + 60;
    *sticking_seen = 0;
    for (int i = 0; i < steps; ++i) {
        rugo_step_stats st;
        ck_assert_int_eq(rugo_world_step(w, &st), RUGO_OK);
        int nrec = 0;
        const rugo_contact_record* rec = rugo_world_contact_records(w, &nrec);
        for (int k = 0; k < nrec; ++k) {
            ck_assert(rec[k].impulse_normal >= 0.0);
            ck_assert(fabs(rec[k].impulse_tangent) <=
                      rec[k].friction * rec[k].impulse_normal * (1 + 1e-9) + 1e-15);
            if (rec[k].sticking) *sticking_seen = 1;
        }
    }
    rugo_body_state s = state(w, b);
    ck_assert_msg(fabs(s.linear_velocity.x) < 1e-3, "still sliding at %g m/s", s.linear_velocity.x);
    double dist = s.center.x - x0;
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
    return dist;
}

START_TEST(test_block_stops) {
    /* 3% is the acceptance; the time discretisation alone (symplectic Euler) shortens the distance by
     * about v0 h / 2, 0.4% here. */
    const double mu = 0.5, v0 = 4.0, g = 9.81;
    double expected = v0 * v0 / (2 * mu * g);
    int sticking = 0;
    double rough = slide_distance(0.002, mu, v0, 1.0 / 120.0, &sticking);
    fprintf(stderr, "block, rough bands (λ = 2 mm): stopped after %.4f m, expected %.4f m (%.2f%%)\n", rough,
            expected, 100.0 * (rough - expected) / expected);
    ck_assert_msg(fabs(rough - expected) <= 0.03 * expected, "rough: %g vs %g", rough, expected);
    ck_assert_int_eq(sticking, 1); /* it stops by sticking */
    double smooth = slide_distance(0.0, mu, v0, 1.0 / 120.0, &sticking);
    fprintf(stderr, "block, smooth: stopped after %.4f m, expected %.4f m (%.2f%%)\n", smooth, expected,
            100.0 * (smooth - expected) / expected);
    ck_assert_msg(fabs(smooth - expected) <= 0.03 * expected, "smooth: %g vs %g", smooth, expected);
}
END_TEST

/* ---- rolling resistance: a rolling disc decelerates at (2/3) k g (λ_A + λ_B) / R ----------------- */

/* The disc's speed at 1 s and 3 s, rolling from v0 on a floor, with rolling resistance k on the disc. */
static void rolling_speeds(double k, double* v1, double* v3, double* slip) {
    surface sf = {0.002, 0.6, 0.5, 0.9};
    rugo_shape* floor = make_block(60.0, 1.0, sf);
    const double r0 = 0.25;
    const int n = 32;
    rugo_shape* disc = make_disc(r0, n, sf);
    const double R = disc_radius(r0, n), v0 = 1.5;
    rugo_world_def d = rugo_default_world_def();
    d.time_step = 1.0 / 120.0;
    rugo_world* w = make_world(d);
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    rugo_body_def b = rugo_default_body_def();
    b.shape = disc;
    b.transform = rugo_make_transform(-25.0, R + 0.002, 0.0);
    b.linear_velocity = rugo_v2(v0, 0.0);
    b.angular_velocity = -v0 / R;
    b.density = 2.0;
    b.rolling_resistance = k;
    int id = -1;
    ck_assert_int_eq(rugo_world_add_body(w, &b, &id), RUGO_OK);
    *slip = 0.0;
    for (int i = 1; i <= 360; ++i) {
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
        const rugo_body_state s = state(w, id);
        if (i == 120) *v1 = s.linear_velocity.x;
        if (i == 360) *v3 = s.linear_velocity.x;
        if (i >= 120) *slip = fmax(*slip, fabs(s.linear_velocity.x + s.angular_velocity * R));
    }
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(disc);
}

START_TEST(test_rolling_resistance) {
    const double R = disc_radius(0.25, 32), lam = 0.004, g = 9.81;
    double v1, v3, slip;
    rolling_speeds(0.0, &v1, &v3, &slip);
    const double free_decel = (v1 - v3) / 2.0;
    fprintf(stderr,
            "rolling resistance off: v(1 s) %.4f, v(3 s) %.4f m/s, deceleration %.4f m/s^2, slip %.1e\n", v1,
            v3, free_decel, slip);
    for (int k = 1; k <= 2; ++k) {
        rolling_speeds((double)k, &v1, &v3, &slip);
        /* what the resistance adds to the simulator's own losses (micro-collisions in the bands) */
        const double added = (v1 - v3) / 2.0 - free_decel, model = 2.0 / 3.0 * k * g * lam / R;
        fprintf(stderr,
                "rolling resistance %d: v(1 s) %.4f, v(3 s) %.4f m/s, added deceleration %.4f m/s^2 (model "
                "%.4f, %+.1f%%), slip %.1e\n",
                k, v1, v3, added, model, 100.0 * (added - model) / model, slip);
        /* 10 %: the impulses come in micro-collisions, whose mean normal impulse is m g h only on average,
         * and each angular impulse is undone into rolling by friction a step later */
        ck_assert_msg(fabs(added - model) <= 0.10 * model, "added deceleration %g, model %g", added, model);
        /* it keeps rolling: each angular impulse opens a slip that friction closes at the next impulses
         * (2.3 % of v at k = 2; test_disc_rolls allows 2 % without resistance) */
        ck_assert_msg(slip <= 0.04 * v3, "slips: %g", slip);
    }
    /* off: the thesis' dynamics, whose rough disc loses a little to micro-collisions (a quarter of the
     * k = 1 model here) */
    ck_assert_msg(free_decel >= 0.0 && free_decel <= 0.3 * (2.0 / 3.0 * g * lam / R), "off: %g", free_decel);
}
END_TEST

/* ---- rolling: a disc spins up to v = ωR and keeps rolling ------------------------------------- */

START_TEST(test_disc_rolls) {
    surface sf = {0.002, 0.3, 0.5, 0.9};
    rugo_shape* floor = make_block(60.0, 1.0, sf);
    const double r0 = 0.25;
    const int n = 32;
    rugo_shape* disc = make_disc(r0, n, sf);
    double R = disc_radius(r0, n);
    rugo_world_def d = rugo_default_world_def();
    d.time_step = 1.0 / 120.0;
    rugo_world* w = make_world(d);
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    const double v0 = 3.0;
    int b = add(w, disc, RUGO_BODY_DYNAMIC, -25.0, R + 0.002, 0.0, rugo_v2(v0, 0), 0.0);
    /* a sliding block with the same μ stops after v0/(μ g) = 1.02 s; the disc is checked at 4 s */
    const double t_block = v0 / (0.3 * 9.81);
    int steps = (int)(4.0 / d.time_step);
    for (int i = 0; i < steps; ++i)
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
    rugo_body_state s = state(w, b);
    double v = s.linear_velocity.x, om = s.angular_velocity;
    fprintf(stderr,
            "disc after 4 s (%.1fx the block's stopping time): v = %.4f m/s (2/3 v0 = %.4f), -ωR = %.4f, "
            "|v + ωR|/v = %.2e\n",
            4.0 / t_block, v, 2.0 * v0 / 3.0, -om * R, fabs(v + om * R) / v);
    /* rolling without slipping: v = -ωR (clockwise spin for motion to +x) to 2% (the curve is within
     * 2e-4 of the circle; micro-collision hops leave a small residual slip) */
    ck_assert_msg(fabs(v + om * R) <= 0.02 * v, "v = %g, ωR = %g", v, om * R);
    /* a uniform disc ends at 2/3 v0 once it rolls; still moving far past the block's stopping time */
    ck_assert_msg(v > 0.6 * v0, "v = %g", v);
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(disc);
}
END_TEST

/* ---- energy: frictionless, ε = 1, no gravity ---------------------------------------------------- */

START_TEST(test_energy_elastic) {
    surface sf = {0.0, 0.0, 1.0, 1.0};
    rugo_shape* wall_h = make_block(6.0, 0.5, sf);
    rugo_shape* wall_v = make_block(0.5, 6.0, sf);
    rugo_shape* disc = make_disc(0.3, 16, sf);
    rugo_shape* blk = make_block(0.5, 0.3, sf);
    rugo_world_def d = rugo_default_world_def();
    d.gravity = rugo_v2(0, 0);
    d.friction = false;
    rugo_world* w = make_world(d);
    add(w, wall_h, RUGO_BODY_STATIC, 0.0, -3.0, 0.0, rugo_v2(0, 0), 0.0);
    add(w, wall_h, RUGO_BODY_STATIC, 0.0, 3.0, 0.0, rugo_v2(0, 0), 0.0);
    add(w, wall_v, RUGO_BODY_STATIC, -3.0, 0.0, 0.0, rugo_v2(0, 0), 0.0);
    add(w, wall_v, RUGO_BODY_STATIC, 3.0, 0.0, 0.0, rugo_v2(0, 0), 0.0);
    add(w, disc, RUGO_BODY_DYNAMIC, -1.0, -1.0, 0.0, rugo_v2(1.5, 0.7), 0.0);
    add(w, disc, RUGO_BODY_DYNAMIC, 1.0, 0.5, 0.0, rugo_v2(-1.1, 1.3), 0.0);
    add(w, disc, RUGO_BODY_DYNAMIC, 0.0, 1.5, 0.0, rugo_v2(0.4, -1.6), 0.0);
    add(w, blk, RUGO_BODY_DYNAMIC, 1.2, -1.5, 0.3, rugo_v2(-0.8, 0.9), 1.0);
    double e0 = rugo_world_kinetic_energy(w), emin = e0, emax = e0;
    long impulses = 0, bisections = 0;
    int unresolved = 0;
    for (int i = 0; i < 10000; ++i) {
        rugo_step_stats st;
        ck_assert_int_eq(rugo_world_step(w, &st), RUGO_OK);
        impulses += st.impulses;
        bisections += st.bisections;
        unresolved += st.unresolved;
        if (st.kinetic_energy < emin) emin = st.kinetic_energy;
        if (st.kinetic_energy > emax) emax = st.kinetic_energy;
    }
    /* every body still inside the box */
    for (int i = 4; i < 8; ++i) {
        rugo_body_state s = state(w, i);
        ck_assert(fabs(s.center.x) < 2.75 && fabs(s.center.y) < 2.75);
    }
    fprintf(stderr,
            "elastic scene, 10000 steps: energy in [%.6f, %.6f] of the initial; %ld impulses, %ld "
            "bisections, %d unresolved steps\n",
            emin / e0, emax / e0, impulses, bisections, unresolved);
    ck_assert_int_gt(impulses, 100);
    /* 1% is the acceptance; frictionless ε = 1 impulses conserve energy exactly (up to round-off),
     * and with several points of one pair treated one after another the energy cannot grow */
    ck_assert_msg(emax <= 1.01 * e0 && emin >= 0.99 * e0, "energy range [%g, %g] of %g", emin, emax, e0);
    rugo_world_destroy(w);
    rugo_shape_destroy(wall_h);
    rugo_shape_destroy(wall_v);
    rugo_shape_destroy(disc);
    rugo_shape_destroy(blk);
}
END_TEST

/* ---- rest: bodies at rest on a rough block stay there ------------------------------------------ */

/* creep, drop, spin: largest drift of the centres, sink and block tilt over 10 s; mean_vy: the vertical
 * velocity the bodies REPORT, averaged over the last 5 s and the three bodies (a resting body that
 * micro-collides in its band reports up and down velocities; their mean should be 0). */
static void rest_scene(rugo_integrator integ, double* creep, double* drop, double* spin, double* mean_vy) {
    surface rough = {0.004, 0.6, 0.5, 0.9};
    rugo_shape* floor = make_block(20.0, 1.0, rough);
    rugo_shape* blk = make_block(0.6, 0.3, rough);
    rugo_shape* disc = make_disc(0.2, 32, rough);
    rugo_world_def d = rugo_default_world_def();
    d.integrator = integ;
    rugo_world* w = make_world(d);
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    int ids[3];
    ids[0] = add(w, blk, RUGO_BODY_DYNAMIC, -2.0, 0.15 + 0.004, 0.0, rugo_v2(0, 0), 0.0);
    ids[1] = add(w, blk, RUGO_BODY_DYNAMIC, 2.0, 0.15 + 0.002, 0.0, rugo_v2(0, 0), 0.0);
    ids[2] = add(w, disc, RUGO_BODY_DYNAMIC, 0.0, disc_radius(0.2, 32) + 0.004, 0.0, rugo_v2(0, 0), 0.0);
    rugo_vec2 c0[3];
    for (int i = 0; i < 3; ++i)
        c0[i] = state(w, ids[i]).center;
    *creep = *drop = *spin = *mean_vy = 0.0;
    for (int step = 0; step < 600; ++step) { /* 10 s */
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
        for (int i = 0; i < 3; ++i) {
            rugo_body_state s = state(w, ids[i]);
            if (step >= 300) *mean_vy += s.linear_velocity.y / (300.0 * 3.0);
            double dx = fabs(s.center.x - c0[i].x), dy = c0[i].y - s.center.y;
            double a = fabs(atan2(s.transform.q.s, s.transform.q.c));
            if (dx > *creep) *creep = dx;
            if (dy > *drop) *drop = dy;
            if (i < 2 && a > *spin) *spin = a;
        }
    }
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
    rugo_shape_destroy(disc);
}

/* A block with sharp corners: three coincident control points at each corner, five more per side. */
static rugo_shape* make_sharp_block(double w, double h, surface sf) {
    double x = 0.5 * w, y = 0.5 * h;
    rugo_vec2 c[4] = {{x, -y}, {x, y}, {-x, y}, {-x, -y}};
    rugo_vec2 p[32];
    int k = 0;
    for (int i = 0; i < 4; ++i) {
        rugo_vec2 n = c[(i + 1) % 4];
        for (int m = 0; m < 3; ++m)
            p[k++] = c[i];
        for (int j = 1; j <= 5; ++j)
            p[k++] = rugo_v2(c[i].x + j * (n.x - c[i].x) / 6.0, c[i].y + j * (n.y - c[i].y) / 6.0);
    }
    return make_shape(p, 32, sf);
}

/* A sharp-cornered block dropped corner first (tilted 0.05 rad, 5 cm) onto a sharp-cornered floor comes
 * to rest inside the bands. Until 2026-11-22 collide.c missed a tilted sharp corner's in-band contact
 * (docs/simulator.md): the block then sank until its curve crossed the floor's (about 4-6 mm into it)
 * and rocked there. Measured over the last 2 of 4 s: the block's lowest curve point (32 samples per
 * segment) stays above the floor's curve and within the two bands (8 mm), and the block lies flat. */
START_TEST(test_sharp_block_rests_in_band) {
    surface rough = {0.004, 0.5, 0.3, 0.9};
    rugo_shape* floor = make_sharp_block(40.0, 1.0, rough);
    rugo_shape* blk = make_sharp_block(0.6, 0.3, rough);
    rugo_world* w = make_world(rugo_default_world_def());
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    const double tilt = 0.05;
    int b = add(w, blk, RUGO_BODY_DYNAMIC, 0.0, 0.15 + 0.3 * sin(tilt) + 0.05, tilt, rugo_v2(0, 0), 0.0);
    rugo_contour c;
    rugo_shape_level(blk, rugo_shape_finest_level(blk), &c);
    double low_min = INFINITY, low_max = -INFINITY, spin = 0.0;
    for (int step = 0; step < 240; ++step) {
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
        if (step < 120) continue;
        rugo_body_state s = state(w, b);
        double low = INFINITY;
        for (int k = 0; k < c.count; ++k)
            for (int i = 0; i <= 32; ++i)
                low = fmin(low, rugo_transform_point(s.transform, rugo_contour_point(c, k, i / 32.0)).y);
        low_min = fmin(low_min, low);
        low_max = fmax(low_max, low);
        spin = fmax(spin, fabs(atan2(s.transform.q.s, s.transform.q.c)));
    }
    fprintf(
        stderr,
        "sharp block at rest: lowest curve point %.4f..%.4f m above the floor's curve, tilt <= %.4f rad\n",
        low_min, low_max, spin);
    ck_assert_msg(low_min > 0.0 && low_max <= 0.008, "lowest point %g..%g", low_min, low_max);
    ck_assert_msg(spin <= 0.01, "tilt %g", spin);
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
}
END_TEST

START_TEST(test_rest) {
    double creep, drop, spin, vy;
    rest_scene(RUGO_INTEGRATE_SYMPLECTIC_EULER, &creep, &drop, &spin, &vy);
    fprintf(stderr,
            "rest 10 s, symplectic: creep %.3e m, largest sink %.3e m, block tilt %.3e rad, mean reported "
            "v_y %.3e m/s\n",
            creep, drop, spin, vy);
    /* acceptance: no creep beyond 1 mm; they stay within their bands (8 mm) and upright */
    ck_assert_msg(creep <= 1e-3, "creep %g", creep);
    ck_assert_msg(drop <= 0.008, "sank %g", drop);
    ck_assert_msg(spin <= 0.01, "tilt %g", spin);
    /* At rest the reported velocities average to zero: each is the velocity the body moved with. */
    ck_assert_msg(fabs(vy) <= 1e-4, "symplectic mean resting v_y %g", vy);
    rest_scene(RUGO_INTEGRATE_EXPLICIT_EULER, &creep, &drop, &spin, &vy);
    fprintf(stderr,
            "rest 10 s, explicit: creep %.3e m, largest sink %.3e m, block tilt %.3e rad, mean reported v_y "
            "%.3e m/s\n",
            creep, drop, spin, vy);
    ck_assert_msg(creep <= 1e-3, "creep %g", creep);
    ck_assert_msg(drop <= 0.008, "sank %g", drop);
    /* Explicit Euler adds gravity after the move: a resting body reports g h downwards on average. */
    ck_assert_msg(fabs(vy + 9.81 / 60.0) <= 0.01 * 9.81 / 60.0, "explicit mean resting v_y %g", vy);
}
END_TEST

/* ---- integrators: energy of the reported state in free flight ----------------------------------- */

/* Per unit mass, E = |v|²/2 + g y. Under constant gravity each step changes it by exactly -g²h²/2
 * (symplectic: x moves with the new velocity) or +g²h²/2 (explicit: with the old one). Explicit Euler
 * thus adds energy every step of flight (a bouncing elastic body climbs), symplectic takes it away:
 * one reason the default is symplectic (docs/simulator.md, "Integrators"). */
static double flight_energy_change(rugo_integrator integ, double h) {
    surface sf = {0.0, 0.5, 0.5, 0.9};
    rugo_shape* disc = make_disc(0.2, 16, sf);
    rugo_world_def d = rugo_default_world_def();
    d.integrator = integ;
    d.time_step = h;
    rugo_world* w = make_world(d);
    int b = add(w, disc, RUGO_BODY_DYNAMIC, 0.0, 100.0, 0.0, rugo_v2(3.0, 5.0), 0.0);
    rugo_body_state s = state(w, b);
    const double e0 =
        0.5 * (s.linear_velocity.x * s.linear_velocity.x + s.linear_velocity.y * s.linear_velocity.y) +
        9.81 * s.center.y;
    const int steps = 120;
    for (int i = 0; i < steps; ++i)
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
    s = state(w, b);
    const double e1 =
        0.5 * (s.linear_velocity.x * s.linear_velocity.x + s.linear_velocity.y * s.linear_velocity.y) +
        9.81 * s.center.y;
    rugo_world_destroy(w);
    rugo_shape_destroy(disc);
    return (e1 - e0) / steps;
}

START_TEST(test_integrators_flight_energy) {
    const double h = 1.0 / 60.0, per_step = 0.5 * 9.81 * 9.81 * h * h;
    const double sym = flight_energy_change(RUGO_INTEGRATE_SYMPLECTIC_EULER, h);
    const double exp_ = flight_energy_change(RUGO_INTEGRATE_EXPLICIT_EULER, h);
    fprintf(stderr,
            "free flight, energy change per step and unit mass: symplectic %.6e, explicit %.6e (g²h²/2 = "
            "%.6e) J/kg\n",
            sym, exp_, per_step);
    ck_assert_msg(fabs(sym + per_step) <= 1e-6 * per_step, "symplectic %g", sym);
    ck_assert_msg(fabs(exp_ - per_step) <= 1e-6 * per_step, "explicit %g", exp_);
}
END_TEST

/* ---- overlap projection: bodies created pressed into each other come apart and stay apart ------- */

/* Deepest true-curve overlap (-separation) between two bodies at their current poses; 0 if apart. */
static double overlap_of(const rugo_world* w, const rugo_shape* sa, int a, const rugo_shape* sb, int b) {
    rugo_collide_context* ctx = NULL;
    ck_assert_int_eq(rugo_collide_context_create(NULL, &ctx), RUGO_OK);
    rugo_contact c[32];
    int n = 0;
    rugo_contact_state st = RUGO_STATE_APART;
    rugo_contact_query q = test_exact_query();
    ck_assert_int_eq(test_collide_shapes(ctx, sa, state(w, a).transform, sb, state(w, b).transform, &q, c, 32,
                                         &n, &st, NULL),
                     RUGO_OK);
    rugo_collide_context_destroy(ctx);
    double deepest = 0.0;
    for (int k = 0; k < n; ++k)
        if (-c[k].separation > deepest) deepest = -c[k].separation;
    return deepest;
}

/* A column of four blocks created 15 mm into each other on a floor, and a disc created 15 mm into the
 * top corners of two static posts it rests between: bisection alone cannot undo an overlap that exists
 * at the start of a step (before the position projection such overlaps persisted and ratcheted deeper).
 * After 0.5 s every overlap must be within what a resting contact may keep: the penetration allowance,
 * penetration tolerance x the smaller body's size (world.c: the half diagonal of its root box), never
 * more again, and the column must stand. */
START_TEST(test_pressed_together) {
    surface sf = {0.002, 0.5, 0.2, 0.5};
    rugo_shape* floor = make_block(6.0, 1.0, sf);
    rugo_shape* blk = make_block(0.4, 0.2, sf);
    rugo_shape* post = make_block(0.3, 0.4, sf);
    rugo_shape* disc = make_disc(0.2, 32, sf);
    rugo_world* w = make_world(rugo_default_world_def());
    const int fl = add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    int col[4];
    for (int i = 0; i < 4; ++i)
        col[i] = add(w, blk, RUGO_BODY_DYNAMIC, -1.5, 0.1 + i * (0.2 - 0.015), 0.0, rugo_v2(0, 0), 0.0);
    /* posts' inner top corners at (1.5 -+ 0.1, 0.4); the disc's centre r - 15 mm from both */
    const double r = disc_radius(0.2, 32);
    const int p0 = add(w, post, RUGO_BODY_STATIC, 1.5 - 0.1 - 0.15, 0.2, 0.0, rugo_v2(0, 0), 0.0);
    const int p1 = add(w, post, RUGO_BODY_STATIC, 1.5 + 0.1 + 0.15, 0.2, 0.0, rugo_v2(0, 0), 0.0);
    const int d = add(w, disc, RUGO_BODY_DYNAMIC, 1.5, 0.4 + sqrt((r - 0.015) * (r - 0.015) - 0.01), 0.0,
                      rugo_v2(0, 0), 0.0);
    const double allow_col = 0.01 * hypot(0.2 + 0.002, 0.1 + 0.002),
                 allow_disc = 0.01 * sqrt(2.0) * (r + 0.002);
    const double start_col = overlap_of(w, blk, col[0], blk, col[1]),
                 start_disc = overlap_of(w, disc, d, post, p0);
    double late_col = 0.0, late_disc = 0.0;
    for (int step = 0; step < 120; ++step) {
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
        if (step < 30) continue;
        for (int i = 0; i < 3; ++i)
            late_col = fmax(late_col, overlap_of(w, blk, col[i], blk, col[i + 1]));
        late_col = fmax(late_col, overlap_of(w, floor, fl, blk, col[0]));
        late_disc = fmax(late_disc, fmax(overlap_of(w, disc, d, post, p0), overlap_of(w, disc, d, post, p1)));
    }
    double drift = 0.0;
    for (int i = 0; i < 4; ++i)
        drift = fmax(drift, fabs(state(w, col[i]).center.x + 1.5));
    const rugo_body_state ds = state(w, d);
    fprintf(
        stderr,
        "pressed together: column overlap %.2f mm at start, largest after 0.5 s %.3f mm (allowance %.3f mm), "
        "drift %.3e m; disc on two corners %.2f mm at start, largest after 0.5 s %.3f mm (allowance %.3f "
        "mm), at x %.2e\n",
        1e3 * start_col, 1e3 * late_col, 1e3 * allow_col, drift, 1e3 * start_disc, 1e3 * late_disc,
        1e3 * allow_disc, ds.center.x - 1.5);
    ck_assert(start_col > 0.01 && start_disc > 0.01);
    /* 1 % on the allowance: the sizes above are the root boxes' half diagonals up to the band's rounding */
    ck_assert_msg(late_col <= 1.01 * allow_col, "column overlap %g > allowance %g", late_col, allow_col);
    ck_assert_msg(late_disc <= 1.01 * allow_disc, "disc overlap %g > allowance %g", late_disc, allow_disc);
    ck_assert_msg(drift <= 0.01, "column drifted %g m", drift);
    ck_assert_msg(fabs(ds.center.x - 1.5) <= 0.01, "disc left the notch: x %g", ds.center.x);
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
    rugo_shape_destroy(post);
    rugo_shape_destroy(disc);
}
END_TEST

/* ---- bisection: a fast block does not tunnel through a thin one -------------------------------- */

START_TEST(test_fast_body) {
    surface sf = {0.001, 0.3, 0.3, 0.5};
    rugo_shape* thin = make_block(4.0, 0.05, sf);
    rugo_shape* blk = make_block(0.3, 0.3, sf);
    rugo_world_def d = rugo_default_world_def();
    rugo_world* w = make_world(d);
    add(w, thin, RUGO_BODY_STATIC, 0.0, 0.0, 0.0, rugo_v2(0, 0), 0.0);
    /* 30 m/s: 0.5 m a step, ten times the thin block's thickness */
    int b = add(w, blk, RUGO_BODY_DYNAMIC, 0.0, 1.2, 0.0, rugo_v2(0, -30.0), 0.0);
    long bis = 0;
    for (int i = 0; i < 60; ++i) {
        rugo_step_stats st;
        ck_assert_int_eq(rugo_world_step(w, &st), RUGO_OK);
        bis += st.bisections;
        ck_assert(!st.unresolved);
    }
    rugo_body_state s = state(w, b);
    fprintf(stderr, "fast block: %ld bisections, ends at y = %.4f\n", bis, s.center.y);
    ck_assert_int_gt(bis, 0);
    ck_assert(s.center.y > 0.0); /* above the thin block: it bounced, no tunnelling */
    rugo_world_destroy(w);
    rugo_shape_destroy(thin);
    rugo_shape_destroy(blk);
}
END_TEST

/* ---- determinism -------------------------------------------------------------------------------- */

static uint64_t run_hash(void) {
    surface sf = {0.003, 0.4, 0.4, 0.8};
    rugo_shape* floor = make_block(10.0, 1.0, sf);
    rugo_shape* blk = make_block(0.4, 0.3, sf);
    rugo_shape* disc = make_disc(0.2, 16, sf);
    rugo_world* w = make_world(rugo_default_world_def());
    add(w, floor, RUGO_BODY_STATIC, 0.0, -0.5, 0.0, rugo_v2(0, 0), 0.0);
    for (int i = 0; i < 6; ++i)
        add(w, (i & 1) ? disc : blk, RUGO_BODY_DYNAMIC, -2.0 + 0.7 * i, 0.5 + 0.45 * i, 0.3 * i,
            rugo_v2(0.5 - 0.2 * i, 0.0), 0.5 * i - 1.0);
    uint64_t hsh = 1469598103934665603ull;
    for (int step = 0; step < 240; ++step) {
        ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
        for (int i = 0; i < rugo_world_body_count(w); ++i) {
            rugo_body_state s = state(w, i);
            const unsigned char* p = (const unsigned char*)&s.transform;
            for (size_t k = 0; k < sizeof s.transform; ++k)
                hsh = (hsh ^ p[k]) * 1099511628211ull;
        }
    }
    rugo_world_destroy(w);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
    rugo_shape_destroy(disc);
    return hsh;
}

START_TEST(test_determinism) {
    uint64_t a = run_hash(), b = run_hash();
    ck_assert_msg(a == b, "%llx != %llx", (unsigned long long)a, (unsigned long long)b);
}
END_TEST

/* ---- bad input ---------------------------------------------------------------------------------- */

START_TEST(test_bad_input) {
    surface sf = {0.0, 0.5, 0.5, 0.9};
    rugo_shape* blk = make_block(1.0, 1.0, sf);
    rugo_world* w = NULL;
    rugo_world_def d = rugo_default_world_def();
    ck_assert_int_eq(rugo_world_create(NULL, &w), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_create(&d, NULL), RUGO_ERR_NULL_ARGUMENT);
    rugo_world_def bad = d;
    bad.cookie = 0;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.time_step = 0.0;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.time_step = NAN;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_NOT_FINITE);
    bad = d;
    bad.gravity.y = INFINITY;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_NOT_FINITE);
    bad = d;
    bad.time_step = 1e300; /* finite, but g h overflows */
    bad.gravity.y = -1e300;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_NOT_FINITE);
    bad = d;
    bad.integrator = (rugo_integrator)7;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.max_bisections = 31;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.penetration_tolerance = -1.0;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    bad = d;
    bad.max_contacts_per_pair = 0;
    ck_assert_int_eq(rugo_world_create(&bad, &w), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_ptr_null(w);
    ck_assert_int_eq(rugo_world_create(&d, &w), RUGO_OK);

    rugo_body_def b = rugo_default_body_def();
    int id = -1;
    ck_assert_int_eq(rugo_world_add_body(w, &b, &id), RUGO_ERR_NULL_ARGUMENT); /* no shape */
    b.shape = blk;
    ck_assert_int_eq(rugo_world_add_body(NULL, &b, &id), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_add_body(w, NULL, &id), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_add_body(w, &b, NULL), RUGO_ERR_NULL_ARGUMENT);
    rugo_body_def bb = b;
    bb.cookie = 1;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_BAD_ARGUMENT);
    bb = b;
    bb.type = (rugo_body_type)5;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_BAD_ARGUMENT);
    bb = b;
    bb.density = 0.0;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_BAD_ARGUMENT);
    bb = b;
    bb.density = NAN;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    bb = b;
    bb.rolling_resistance = -0.5;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_BAD_ARGUMENT);
    bb.rolling_resistance = INFINITY;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    bb = b;
    rugo_shape* wide = make_block(40.0, 1.0, sf); /* area ~40 */
    bb.shape = wide;
    bb.density = 1e308; /* the mass overflows */
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    bb.density = 4.9e-324; /* the inverse inertia overflows */
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    bb.shape = blk;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    rugo_shape_destroy(wide);
    bb = b;
    bb.transform.p.x = NAN;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    bb = b;
    bb.transform.q.c = 2.0; /* not a rotation */
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_BAD_ARGUMENT);
    bb = b;
    bb.linear_velocity.y = INFINITY;
    ck_assert_int_eq(rugo_world_add_body(w, &bb, &id), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_world_body_count(w), 0);
    ck_assert_int_eq(rugo_world_add_body(w, &b, &id), RUGO_OK);
    ck_assert_int_eq(id, 0);
    b.type = RUGO_BODY_STATIC;
    b.density = 0.0; /* ignored for a static body */
    b.transform = rugo_make_transform(0, -5, 0);
    ck_assert_int_eq(rugo_world_add_body(w, &b, &id), RUGO_OK);
    ck_assert_int_eq(id, 1);
    ck_assert_int_eq(rugo_world_body_count(w), 2);
    ck_assert_int_eq(rugo_world_body_count(NULL), 0);

    rugo_body_state s;
    ck_assert_int_eq(rugo_world_body(NULL, 0, &s), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_body(w, 0, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_body(w, -1, &s), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_world_body(w, 2, &s), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_world_body(w, 0, &s), RUGO_OK);
    /* density 1: the mass is the exact area of the rounded 1 m x 1 m block */
    ck_assert_near(s.mass, rugo_shape_mass(blk).area, 1e-12);
    ck_assert_near(s.mass, 1.0, 1e-3);
    ck_assert_int_eq(rugo_world_set_velocity(NULL, 0, rugo_v2(0, 0), 0), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_set_velocity(w, 5, rugo_v2(0, 0), 0), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo_world_set_velocity(w, 0, rugo_v2(NAN, 0), 0), RUGO_ERR_NOT_FINITE);
    ck_assert_int_eq(rugo_world_set_velocity(w, 1, rugo_v2(1, 0), 0), RUGO_ERR_BAD_ARGUMENT); /* static */
    ck_assert_int_eq(rugo_world_set_velocity(w, 0, rugo_v2(1, 0), 0.5), RUGO_OK);
    ck_assert_int_eq(rugo_world_set_transform(NULL, 0, rugo_identity_transform()), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_set_transform(w, -3, rugo_identity_transform()), RUGO_ERR_BAD_ARGUMENT);
    rugo_transform t = rugo_make_transform(0, 0, 0);
    t.q.s = NAN;
    ck_assert_int_eq(rugo_world_set_transform(w, 0, t), RUGO_ERR_NOT_FINITE);
    t = rugo_make_transform(1, 2, 0.3);
    ck_assert_int_eq(rugo_world_set_transform(w, 0, t), RUGO_OK);
    ck_assert_int_eq(rugo_world_body(w, 0, &s), RUGO_OK);
    ck_assert(memcmp(&s.transform, &t, sizeof t) == 0);

    ck_assert_int_eq(rugo_world_step(NULL, NULL), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
    int nrec = -1;
    ck_assert_ptr_null(rugo_world_contact_records(NULL, &nrec));
    ck_assert_int_eq(nrec, 0);
    ck_assert(isnan(rugo_world_kinetic_energy(NULL)));
    rugo_world_destroy(NULL);
    rugo_world_destroy(w);
    rugo_shape_destroy(blk);
}
END_TEST

/* ---- out of memory: every allocation failing in turn leaves a usable world or a clean error ----- */

typedef struct counting {
    long allocs, fail_at;
} counting;
static void* cnt_alloc(size_t n, void* ctx) {
    counting* c = (counting*)ctx;
    if (c->allocs++ == c->fail_at) return NULL;
    return malloc(n);
}
static void cnt_free(void* p, void* ctx) {
    (void)ctx;
    free(p);
}

START_TEST(test_out_of_memory) {
    surface sf = {0.002, 0.5, 0.5, 0.9};
    rugo_shape* floor = make_block(10.0, 1.0, sf);
    rugo_shape* blk = make_block(0.5, 0.5, sf);
    int failures = 0;
    for (long k = 0; k < 200; ++k) {
        counting c = {0, k};
        rugo_world_def d = rugo_default_world_def();
        d.allocator.alloc = cnt_alloc;
        d.allocator.free = cnt_free;
        d.allocator.ctx = &c;
        rugo_world* w = NULL;
        rugo_status st = rugo_world_create(&d, &w);
        if (st != RUGO_OK) {
            ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
            ++failures;
            continue;
        }
        rugo_body_def b = rugo_default_body_def();
        b.shape = floor;
        b.type = RUGO_BODY_STATIC;
        b.transform = rugo_make_transform(0, -0.5, 0);
        int id;
        int ok = rugo_world_add_body(w, &b, &id) == RUGO_OK;
        b.shape = blk;
        b.type = RUGO_BODY_DYNAMIC;
        b.transform = rugo_make_transform(0, 0.3, 0);
        ok = ok && rugo_world_add_body(w, &b, &id) == RUGO_OK;
        for (int i = 0; ok && i < 20; ++i) {
            st = rugo_world_step(w, NULL);
            if (st != RUGO_OK) {
                ck_assert_int_eq(st, RUGO_ERR_OUT_OF_MEMORY);
                ++failures;
                c.fail_at = -1; /* the world must recover */
                ck_assert_int_eq(rugo_world_step(w, NULL), RUGO_OK);
            }
        }
        rugo_world_destroy(w);
    }
    ck_assert_int_gt(failures, 3);
    rugo_shape_destroy(floor);
    rugo_shape_destroy(blk);
}
END_TEST

static Suite* world_suite(void) {
    Suite* s = suite_create("world");
    TCase* t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, test_bad_input);
    tcase_add_test(t, test_out_of_memory);
    tcase_add_test(t, test_determinism);
    tcase_add_test(t, test_block_stops);
    tcase_add_test(t, test_disc_rolls);
    tcase_add_test(t, test_rolling_resistance);
    tcase_add_test(t, test_rest);
    tcase_add_test(t, test_sharp_block_rests_in_band);
    tcase_add_test(t, test_integrators_flight_energy);
    tcase_add_test(t, test_fast_body);
    tcase_add_test(t, test_pressed_together);
    tcase_add_test(t, test_energy_elastic);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return test_run_suite(world_suite()); }
