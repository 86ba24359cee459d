/* Thesis Fig. 7.7-7.8 in librugo's own simulator (rugo_world): an irregular slab thrown at tangential
 * speed 10 m/s on a fixed block. (a) both surfaces tipo_2; (b) a smooth slab on a block that is rough,
 * smooth, rough along its length (scenes.h, SCENE_THROWN). Mirrors samples/box2d/b2_fig7_8_thrown.cpp: writes
 * thrown_a.csv / thrown_b.csv (t, pose, velocity, tangential contact speed, μ of the impulses, number of
 * impulses, energy), impulses_<v>.csv (every impulse the simulator applied to the slab: Fig. 7.8's
 * friction per collision), frames thrown_<v>_<step>.svg and summary.json.
 *
 * Checks, each with its reason:
 *  - the slab stays on the block (centre above 0.1 m: it rests ~0.2 m above the top y = 0) and its
 *    curve never goes below the top minus the block's band (it would have fallen through);
 *  - it does not tip over (|angle| < 0.5 rad) and its energy (kinetic + potential) never grows: impulses
 *    never add energy and gravity's work is in the potential term; the simulator has no position
 *    correction, so we allow only 1e-6 of the initial energy per step (round-off);
 *  - it comes to rest: the tangential speed falls to 0 within the run (thesis 7.8);
 *  - (b) Coulomb sliding decelerates at μ g: each stretch within 20% of μ g from the friction map
 *    (scene.stretch_mu: μ_rough = 0.83, μ_smooth = 0.10), and the rough / smooth ratio of the measured
 *    decelerations is at least half the friction map's 8.3 (>= 4.2, the Box2D sample's margin: the slab
 *    rocks so the normal force varies, and λ(t) ramps over a segment at each stretch end); the stop on
 *    the second rough stretch: the mean deceleration from entering it to rest is also at least 4.2 times
 *    the smooth stretch's (that stretch is too short for a slope: the slab stops within its length). */
#include "sample_check.h"
#include "sim_sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAXS = 2048 };

typedef struct smp {
    double t, x, y, a, vx, vy, w, vt, mu, e;
    int contacts;
} smp;

static double lowest_above[2];
static uint64_t hashes[2];
static double impulse_gain[2], growth_bound[2];

static int run_variant(int v, const char* dir, smp* out, int* count, scene* s) {
    if (scene_create(SCENE_THROWN, v, s) != RUGO_OK) return -1;
    sim_run run;
    if (sim_build(&run, s, NULL) != 0) return -1;
    const int im = sim_find(s, SCENE_ROLE_MOVER, 0), ig = sim_find(s, SCENE_ROLE_GROUND, 0);
    const long n = lround(s->duration / s->time_step);
    const char* tag = v == 0 ? "a" : "b";
    char name[64];
    snprintf(name, sizeof name, "thrown_%s.csv", tag);
    FILE* f = sim_open_out(dir, name);
    snprintf(name, sizeof name, "impulses_%s.csv", tag);
    FILE* fi = sim_open_out(dir, name);
    if (f == NULL || fi == NULL) return -1;
    fprintf(f, "t,x,y,angle,vx,vy,w,tangential_speed,mu,contacts,energy\n");
    fprintf(fi, "t,x,y,mu,epsilon,separation,tolerance,vn_before,vn_after,jn,jt,sticking,micro\n");
    lowest_above[v] = 1e9;
    impulse_gain[v] = -1e9;
    growth_bound[v] = sim_micro_growth_bound(&run);
    *count = 0;
    for (long k = 0; k <= n; ++k) {
        rugo_body_state b = sim_body(&run, im);
        if (k == 0 || k == 30 || k == 60 || k == n) {
            char path[1024], title[160];
            snprintf(path, sizeof path, "%s/thrown_%s_%04ld.svg", dir, tag, k);
            snprintf(title, sizeof title, "simulator: Fig. 7.7 (%s) t = %.2f s, vx = %.2f m/s", s->label,
                     run.time, b.linear_velocity.x);
            sim_draw_frame(&run, path, title, 1);
        }
        /* Tangential speed at the contact: the slab's velocity along the block's top (x) at the points of
         * the impulses with the block in the last step; μ: mean of those impulses' μ. */
        smp p;
        memset(&p, 0, sizeof p);
        p.t = run.time;
        int nrec = 0;
        const rugo_contact_record* cr = k > 0 ? rugo_world_contact_records(run.world, &nrec) : NULL;
        double vt = 0.0, mu = 0.0;
        for (int q = 0; q < nrec; ++q) {
            if (!((cr[q].body_a == run.id[im] && cr[q].body_b == run.id[ig]) ||
                  (cr[q].body_b == run.id[im] && cr[q].body_a == run.id[ig])))
                continue;
            vt += b.linear_velocity.x - b.angular_velocity * (cr[q].point.y - b.center.y);
            mu += cr[q].friction;
            ++p.contacts;
            fprintf(fi, "%.5f,%.6f,%.6f,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d\n", run.time,
                    cr[q].point.x, cr[q].point.y, cr[q].friction, cr[q].restitution, cr[q].separation,
                    cr[q].tolerance, cr[q].normal_velocity_before, cr[q].normal_velocity_after,
                    cr[q].impulse_normal, cr[q].impulse_tangent, cr[q].sticking, cr[q].micro);
        }
        p.x = b.center.x;
        p.y = b.center.y;
        p.a = atan2(b.transform.q.s, b.transform.q.c);
        p.vx = b.linear_velocity.x;
        p.vy = b.linear_velocity.y;
        p.w = b.angular_velocity;
        p.vt = p.contacts ? vt / p.contacts : NAN;
        p.mu = p.contacts ? mu / p.contacts : NAN;
        p.e = sim_energy(&run);
        lowest_above[v] = fmin(lowest_above[v], sim_lowest_point(&run, im) - (s->ground_top - run.band[ig]));
        fprintf(f, "%.5f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.5f,%d,%.6f\n", p.t, p.x, p.y, p.a, p.vx, p.vy,
                p.w, p.vt, p.mu, p.contacts, p.e);
        if (*count < MAXS) out[(*count)++] = p;
        if (k == n) break;
        const double ke_mid = sim_kinetic_after_kick(&run);
        if (sim_step(&run) != 0) {
            fclose(f);
            fclose(fi);
            sim_destroy(&run);
            return -1;
        }
        impulse_gain[v] = sample_max(impulse_gain[v], sim_kinetic(&run) - ke_mid);
    }
    printf("(%s) %ld steps, %ld impulses, %ld bisections, %ld steps left unresolved, hash %016llx\n", tag,
           run.steps, run.impulses, run.bisections, run.unresolved_steps, (unsigned long long)run.hash);
    hashes[v] = run.hash;
    sim_destroy(&run);
    fclose(fi);
    return fclose(f) == 0 ? 0 : -1;
}

/* Deceleration (-dv/dt, least squares) of vx while the slab (half-length 0.6 m plus a 0.3 m margin for
 * the λ ramp) lies wholly inside [x0, x1] and slides (v > 0.3 m/s), as the Box2D sample measures it. */
static double deceleration(const smp* s, int n, double x0, double x1, int* count) {
    static double t[MAXS], v[MAXS];
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (s[i].contacts > 0 && s[i].x - 0.9 >= x0 && s[i].x + 0.9 <= x1 && s[i].vx > 0.3) {
            t[m] = s[i].t;
            v[m] = s[i].vx;
            ++m;
        }
    *count = m;
    return -sim_slope(t, v, m);
}

static double stop_time(const smp* s, int n) {
    for (int i = 0; i < n; ++i)
        if (fabs(s[i].vx) < 0.05 && s[i].t > 0.2) return s[i].t;
    return NAN;
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/sim_fig7_8_thrown";
    if (sample_mkdir(dir) != 0) return 1;
    static smp a[MAXS], b[MAXS];
    static scene sa, sb;
    int na = 0, nb = 0;
    int ok = run_variant(0, dir, a, &na, &sa) == 0 && run_variant(1, dir, b, &nb, &sb) == 0;
    if (!sample_expect("both variants ran", ok)) return sample_finish();
    const double g = 9.81;
    int n1 = 0, n2 = 0, n3 = 0;
    double rough1 = deceleration(b, nb, -10.0, sb.stretch[0], &n1);
    double smooth = deceleration(b, nb, sb.stretch[0], sb.stretch[1], &n2);
    double rough2 = deceleration(b, nb, sb.stretch[1], 10.0, &n3);
    const double predicted = sb.stretch_mu[0] / sb.stretch_mu[1];
    const double ratio = rough1 / smooth;
    /* Second rough stretch: from the first sample with the slab's front (x + 0.6) on it to rest. */
    double t_in = NAN, v_in = NAN, stop_b = stop_time(b, nb), stop_a = stop_time(a, na);
    for (int i = 0; i < nb; ++i)
        if (b[i].x + 0.6 >= sb.stretch[1]) {
            t_in = b[i].t;
            v_in = b[i].vx;
            break;
        }
    double rough2_mean = v_in / (stop_b - t_in);
    printf("Fig. 7.8(b): deceleration rough %.3f m/s^2 (%d samples), smooth %.3f (%d), rough again %.3f (%d; "
           "mean to rest "
           "%.3f from %.3f m/s at t = %.3f s)\n",
           rough1, n1, smooth, n2, rough2, n3, rough2_mean, v_in, t_in);
    printf("  friction map: mu rough %.3f, smooth %.3f -> predicted decelerations %.3f, %.3f; ratio %.2f "
           "(predicted %.2f)\n",
           sb.stretch_mu[0], sb.stretch_mu[1], sb.stretch_mu[0] * g, sb.stretch_mu[1] * g, ratio, predicted);
    printf("Fig. 7.8(a): stops at t = %.3f s at x = %.3f; (b) stops at t = %.3f s at x = %.3f\n", stop_a,
           a[na - 1].x, stop_b, b[nb - 1].x);
    double mu_a = 0.0;
    int mu_an = 0;
    for (int i = 0; i < na; ++i)
        if (a[i].contacts > 0 && a[i].vx > 0.3) {
            mu_a += a[i].mu;
            ++mu_an;
        }
    mu_a /= mu_an;
    printf("(a) mean mu of the impulses while sliding %.4f (%d samples)\n", mu_a, mu_an);
    FILE* f = sim_open_out(dir, "summary.json");
    if (f) {
        char r2[32];
        if (n3 >= 5)
            snprintf(r2, sizeof r2, "%.6f", rough2);
        else
            snprintf(r2, sizeof r2, "null");
        fprintf(f,
                "{\"a\": {\"stop_time\": %.5f, \"stop_x\": %.5f, \"mean_mu_sliding\": %.5f},\n"
                " \"b\": {\"stop_time\": %.5f, \"stop_x\": %.5f,\n"
                "  \"deceleration\": {\"rough\": %.6f, \"smooth\": %.6f, \"rough_again\": %s, "
                "\"rough_again_mean_to_rest\": %.6f},\n"
                "  \"samples\": [%d, %d, %d], \"mu\": {\"rough\": %.5f, \"smooth\": %.5f},\n"
                "  \"ratio\": %.5f, \"predicted_ratio\": %.5f},\n"
                " \"hash\": [\"%016llx\", \"%016llx\"]}\n",
                stop_a, a[na - 1].x, mu_a, stop_b, b[nb - 1].x, rough1, smooth, r2, rough2_mean, n1, n2, n3,
                sb.stretch_mu[0], sb.stretch_mu[1], ratio, predicted, (unsigned long long)hashes[0],
                (unsigned long long)hashes[1]);
        fclose(f);
    }
    for (int v = 0; v < 2; ++v) {
        const smp* s = v == 0 ? a : b;
        const int n = v == 0 ? na : nb;
        const char* tag = v == 0 ? "(a)" : "(b)";
        char name[256];
        double min_y = 1e9, max_a = 0.0, grow = 0.0;
        for (int i = 0; i < n; ++i) {
            min_y = fmin(min_y, s[i].y);
            max_a = fmax(max_a, fabs(s[i].a));
            if (i > 0) grow = sample_max(grow, s[i].e - s[i - 1].e);
        }
        snprintf(name, sizeof name, "%s stays on the block: -(lowest centre y) [m]", tag);
        sample_expect_le(name, -min_y, -0.1);
        snprintf(name, sizeof name,
                 "%s never below the top minus the block's band: -(lowest curve point - (top - band)) [m]",
                 tag);
        sample_expect_le(name, -lowest_above[v], 0.0);
        snprintf(name, sizeof name, "%s does not tip over: largest |angle| [rad]", tag);
        sample_expect_le(name, max_a, 0.5);
        snprintf(name, sizeof name, "%s tangential speed falls to 0 (stops within the run)", tag);
        sample_expect(name, !isnan(stop_time(s, n)));
        snprintf(name, sizeof name, "%s at rest at the end: |vx| [m/s]", tag);
        sample_expect_le(name, fabs(s[n - 1].vx), 0.05);
        snprintf(name, sizeof name,
                 "%s impulses never add kinetic energy: largest gain of a step's impulses [J]", tag);
        sample_expect_le(name, impulse_gain[v], 1e-9 * s[0].e);
        snprintf(name, sizeof name,
                 "%s energy (kinetic + potential) grows only by the bounce discretisation: largest step "
                 "increase [J] <= sum m g h 2 sqrt(2 g band)",
                 tag);
        sample_expect_le(name, grow, growth_bound[v]);
        printf("%s largest step increase of energy %.4g J = %.4g of the initial (the Box2D sample allows "
               "1e-3)\n",
               tag, grow, grow / s[0].e);
        snprintf(name, sizeof name, "%s comes to rest: final kinetic / initial kinetic", tag);
        sample_expect_le(name, 0.5 * (s[n - 1].vx * s[n - 1].vx + s[n - 1].vy * s[n - 1].vy) / 50.0, 0.01);
    }
    sample_expect("(b) enough samples on the first rough stretch and on the smooth one",
                  n1 >= 10 && n2 >= 10);
    sample_expect_le("(b) smooth stretch decelerates at mu_smooth g within 20%: |a/(mu g) - 1|",
                     fabs(smooth / (sb.stretch_mu[1] * g) - 1.0), 0.2);
    sample_expect_le("(b) rough stretch decelerates at mu_rough g within 20%: |a/(mu g) - 1|",
                     fabs(rough1 / (sb.stretch_mu[0] * g) - 1.0), 0.2);
    sample_expect_le(
        "(b) decelerates measurably faster on the rough stretch: -(rough/smooth) <= -predicted/2", -ratio,
        -0.5 * predicted);
    sample_expect_le(
        "(b) stops fast on the second rough stretch: -(mean deceleration to rest / smooth) <= -predicted/2",
        -rough2_mean / smooth, -0.5 * predicted);
    scene_destroy(&sa);
    scene_destroy(&sb);
    return sample_finish();
}
