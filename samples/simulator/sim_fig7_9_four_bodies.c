/* Thesis Fig. 7.9 in librugo's own simulator (rugo_world): four irregular bodies (tipo_2 roughness,
 * restitution 0.10, 0.35, 0.60, 0.85) dropped on a fixed irregular block between two fixed rocks
 * (scenes.h, SCENE_FOUR_BODIES). Mirrors samples/box2d/b2_fig7_9_four_bodies.cpp: writes four_bodies.csv
 * (every body every 0.1 s), frames four_bodies_<step>.svg and summary.json. Also the simulator's
 * determinism test: the scene is run a second time in the same process and the FNV-1a hash over the
 * double bits of every body's transform after every step (sim_sample.h) must be identical; the hash is
 * printed (tests/test_determinism.cpp pins it).
 *
 * Checks, each with its reason:
 *  - nothing falls through: no centre below the block's lowest valley (scene.ground_top) and no free
 *    body's curve below ground_top minus the block's band;
 *  - impulses never add kinetic energy (world.h's promise: exact up to round-off), and the energy
 *    (kinetic + potential: gravity's work accounted) never grows in a step by more than the bounce
 *    discretisation of symplectic Euler allows for resting contact (sim_micro_growth_bound);
 *  - the bodies come to rest: final kinetic energy < 1% of the energy released;
 *  - restitution shows: the ε = 0.85 body rebounds higher after its first impact than the ε = 0.10 body;
 *  - determinism: two runs give the same hash; with --expect-hash HEX (a check by hand) it must also equal
 *    HEX. */
#include "sample_check.h"
#include "sim_sample.h"

#include <math.h>
#include <string.h>

int main(int argc, char** argv) {
    const char* dir = "out/sim_fig7_9_four_bodies";
    const char* expect_hash = NULL;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--expect-hash") == 0 && i + 1 < argc)
            expect_hash = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: %s [DIR] [--expect-hash HEX]\n", argv[0]);
            return 2;
        } else
            dir = argv[i];
    }
    if (sample_mkdir(dir) != 0) return 1;
    static scene s;
    static sim_record rec;
    if (!sample_expect("scene built", scene_create(SCENE_FOUR_BODIES, 0, &s) == RUGO_OK))
        return sample_finish();
    static const long frames[] = {0, 30, 60, 90, 120, 150, 180, 240, 300};
    double released = NAN, bound = NAN, ground_band = 0.0;
    {
        sim_run run;
        int ok = sim_build(&run, &s, NULL) == 0;
        if (ok) {
            bound = sim_micro_growth_bound(&run);
            ground_band = run.band[sim_find(&s, SCENE_ROLE_GROUND, 0)];
        }
        ok = ok && sim_run_scene(&run, dir, "four_bodies", frames, 9, &rec, NULL, NULL) == 0;
        if (!sample_expect("scene ran", ok)) return sample_finish();
        released = rec.e0 - sim_energy(&run);
        printf(
            "%ld steps, %ld impulses (%ld micro, %ld sticking), %ld bisections, %ld steps left unresolved\n",
            run.steps, rec.impulses, rec.micro, rec.sticking, run.bisections, run.unresolved_steps);
        sim_destroy(&run);
    }
    /* Determinism: the same scene again, same process, no output. */
    uint64_t hash2 = 0;
    {
        sim_run run;
        int ok = sim_build(&run, &s, NULL) == 0;
        const long n = lround(s.duration / s.time_step);
        for (long k = 0; ok && k < n; ++k)
            ok = sim_step(&run) == 0;
        if (!sample_expect("scene ran again", ok)) return sample_finish();
        hash2 = run.hash;
        sim_destroy(&run);
    }
    printf("determinism: hash of all transforms every step %016llx, second run %016llx\n",
           (unsigned long long)rec.hash, (unsigned long long)hash2);
    double rebound[4];
    FILE* f = sim_open_out(dir, "summary.json");
    if (f) fprintf(f, "{\"bodies\": [");
    for (int i = 0; i < 4; ++i) {
        const int b = 3 + i;
        rebound[i] = rec.rebound_y[b] - rec.impact_y[b];
        printf("%-12s first impact t = %.3f s, rebound %.4f m, final (%.3f, %.3f)\n", s.bodies[b].name,
               rec.first_contact[b], rebound[i], rec.final[b][0], rec.final[b][1]);
        if (f)
            fprintf(
                f, "%s{\"name\": \"%s\", \"first_impact\": %.5f, \"rebound\": %.6f, \"final\": [%.6f, %.6f]}",
                i ? ", " : "", s.bodies[b].name, rec.first_contact[b], rebound[i], rec.final[b][0],
                rec.final[b][1]);
    }
    printf("energy: initial %.4f J, released %.4f J, final kinetic %.6f J, mean mu %.4f; largest step growth "
           "%.4g J (%.3g of "
           "initial; bound %.4g J), impulses' largest kinetic gain %.3g J\n",
           rec.e0, released, rec.final_kinetic, sim_record_mean_mu(&rec), rec.max_growth_abs, rec.max_growth,
           bound, rec.max_impulse_gain);
    if (f) {
        fprintf(f,
                "],\n \"energy_initial\": %.6f, \"released\": %.6f, \"final_kinetic\": %.9f, \"max_growth\": "
                "%.9g, \"mean_mu\": %.6f,"
                " \"impulses\": %ld, \"hash\": \"%016llx\"}\n",
                rec.e0, released, rec.final_kinetic, rec.max_growth, sim_record_mean_mu(&rec), rec.impulses,
                (unsigned long long)rec.hash);
        fclose(f);
    }
    sample_expect_le("nothing falls through: -(lowest centre y - lowest valley of the block) [m]",
                     -(rec.min_y - s.ground_top), 0.0);
    sample_expect_le("nothing falls through: -(lowest curve point - (lowest valley - block's band)) [m]",
                     -(rec.min_curve_above + ground_band), 0.0);
    sample_expect_le("impulses never add kinetic energy: largest gain of a step's impulses [J]",
                     rec.max_impulse_gain, 1e-9 * fabs(rec.e0));
    sample_expect_le("energy grows only by the bounce discretisation: largest step increase [J]",
                     rec.max_growth_abs, bound);
    sample_expect_le("bodies come to rest: final kinetic / released", rec.final_kinetic / released, 0.01);
    sample_expect("restitution: the e = 0.85 body rebounds higher than the e = 0.10 body",
                  rebound[3] > rebound[0]);
    sample_expect("determinism: a second run in the same process gives the same hash of all transforms",
                  rec.hash == hash2);
    if (expect_hash != NULL) {
        char got[17];
        snprintf(got, sizeof got, "%016llx", (unsigned long long)rec.hash);
        printf("pinned hash %s, this run %s\n", expect_hash, got);
        sample_expect("determinism: the hash equals the pinned one (same bits across processes and builds)",
                      strcmp(got, expect_hash) == 0);
    }
    scene_destroy(&s);
    return sample_finish();
}
