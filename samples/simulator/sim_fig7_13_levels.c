/* Thesis Fig. 7.12-7.13 in librugo's own simulator (rugo_world): three objects of arbitrary geometry with
 * fine detail (toothed, wavy, noisy slabs, tipo_3) thrown at 4 m/s along a fixed flat block (tipo_3),
 * with contacts at levels of detail 0 (reference), -1 and -2 (scenes.h, SCENE_LEVELS). Mirrors
 * samples/box2d/b2_fig7_13_levels.cpp: writes levels_<level>.csv, frames levels_<level>_<step>.svg and
 * summary.csv with the Box2D sample's columns (the λ table of that sample is the library's, not the
 * engine's: see its tolerances.csv).
 *
 * Checks, each with its reason:
 *  - coarser is rougher (the thesis' observation; coarse levels absorb the detail they cannot represent
 *    into λ, 5.3, and μ grows with λ): mean μ over all impulses at level -1 exceeds level 0's by at least
 *    0.04 and level -2's exceeds level -1's by at least 0.08 (the Box2D sample's margins: ~40% of what
 *    the λ tables predict);
 *  - more friction, shorter slides (v0^2 / (2 μ g)): mean slide at -1 < at 0, at -2 < at -1;
 *  - nothing falls through (centres above the top, curves above the top minus the block's band);
 *    impulses never add kinetic energy; energy grows in a step by no more than the bounce
 *    discretisation bound (sim_micro_growth_bound); the objects come to rest (final kinetic < 1% of the
 *    initial kinetic). */
#include "sample_check.h"
#include "sim_sample.h"

#include <math.h>

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/sim_fig7_13_levels";
    if (sample_mkdir(dir) != 0) return 1;
    static const int variants[3] = {2, 0, 1}; /* levels 0, -1, -2 */
    static const long frames[] = {0, 30, 60, 120};
    double mu[3] = {NAN, NAN, NAN}, slide[3] = {NAN, NAN, NAN};
    FILE* f = sim_open_out(dir, "summary.csv");
    if (f)
        fprintf(f, "level,mean_mu,predicted_mu,contact_samples,mean_slide,final_x0,final_x1,final_x2,max_"
                   "energy_growth,"
                   "final_kinetic,hash\n");
    for (int i = 0; i < 3; ++i) {
        static scene s;
        static sim_record rec;
        if (!sample_expect("scene built", scene_create(SCENE_LEVELS, variants[i], &s) == RUGO_OK))
            return sample_finish();
        sim_run run;
        int ok = sim_build(&run, &s, NULL) == 0;
        double k0 = 0.0, bound = 0.0, ground_band = 0.0;
        if (ok) {
            k0 = sim_kinetic(&run);
            bound = sim_micro_growth_bound(&run);
            ground_band = run.band[sim_find(&s, SCENE_ROLE_GROUND, 0)];
        }
        char prefix[96];
        snprintf(prefix, sizeof prefix, "levels_%.63s", s.label);
        ok = ok && sim_run_scene(&run, dir, prefix, frames, 4, &rec, NULL, NULL) == 0;
        if (!sample_expect("scene ran", ok)) return sample_finish();
        mu[i] = sim_record_mean_mu(&rec);
        double sum = 0.0;
        int nobj = 0;
        printf("level %2d: %ld impulses (%ld micro, %ld sticking), %ld bisections, %ld steps unresolved, "
               "hash %016llx\n",
               s.level, rec.impulses, rec.micro, rec.sticking, run.bisections, run.unresolved_steps,
               (unsigned long long)rec.hash);
        for (int b = 1; b < s.body_count; ++b) {
            const double m = rec.body_mu_count[b] ? rec.body_mu_sum[b] / (double)rec.body_mu_count[b] : NAN;
            printf("  %-8s mean mu %.4f over %ld impulses, slides %.3f m\n", s.bodies[b].name, m,
                   rec.body_mu_count[b], rec.final[b][0] - rec.start[b][0]);
            sum += rec.final[b][0] - rec.start[b][0];
            ++nobj;
        }
        slide[i] = sum / nobj;
        printf(
            "  all impulses: mean mu %.4f over %ld; mean slide %.3f m; objects end at x = %.3f, %.3f, %.3f\n",
            mu[i], rec.mu_count, slide[i], rec.final[1][0], rec.final[2][0], rec.final[3][0]);
        if (f)
            fprintf(f, "%d,%.6f,,%ld,%.5f,%.5f,%.5f,%.5f,%.6g,%.6g,%016llx\n", s.level, mu[i], rec.mu_count,
                    slide[i], rec.final[1][0], rec.final[2][0], rec.final[3][0], rec.max_growth,
                    rec.final_kinetic, (unsigned long long)rec.hash);
        char name[256];
        snprintf(name, sizeof name, "%.63s: nothing falls through, -(lowest centre y) [m]", s.label);
        sample_expect_le(name, -rec.min_y, 0.0);
        snprintf(name, sizeof name,
                 "%.63s: no curve below the top minus the block's band, -(lowest point - (top - band)) [m]",
                 s.label);
        sample_expect_le(name, -(rec.min_curve_above + ground_band), 0.0);
        snprintf(name, sizeof name, "%.63s: impulses never add kinetic energy, largest gain of a step [J]",
                 s.label);
        sample_expect_le(name, rec.max_impulse_gain, 1e-9 * fabs(rec.e0));
        snprintf(name, sizeof name,
                 "%.63s: energy grows only by the bounce discretisation, largest step increase [J]", s.label);
        sample_expect_le(name, rec.max_growth_abs, bound);
        snprintf(name, sizeof name, "%.63s: objects come to rest, final kinetic / initial kinetic", s.label);
        sample_expect_le(name, rec.final_kinetic / k0, 0.01);
        sim_destroy(&run);
        scene_destroy(&s);
    }
    if (f) fclose(f);
    sample_expect_le("coarser is rougher: mean mu at level -1 - at level 0 >= 0.04, -(difference - 0.04)",
                     -(mu[1] - mu[0] - 0.04), 0.0);
    sample_expect_le("coarser is rougher: mean mu at level -2 - at level -1 >= 0.08, -(difference - 0.08)",
                     -(mu[2] - mu[1] - 0.08), 0.0);
    sample_expect("more friction, shorter slides: mean slide at level -1 < at level 0", slide[1] < slide[0]);
    sample_expect("more friction, shorter slides: mean slide at level -2 < at level -1", slide[2] < slide[1]);
    return sample_finish();
}
