// Thesis Fig. 7.10-7.11 through the Box2D bridge: the word "gráfica" as free letter bodies (g r á f i c a
// with the accent and the i's dot as bodies of their own) standing on a fixed block with a gently wavy
// top, hit by a heavy ball thrown at 6 m/s at the "g"; every surface tipo_2 (Fig. 7.10) or tipo_3
// (Fig. 7.11); the letters' restitution ranges from 0.1 (g) to 0.66 (c), the thesis' "diferentes
// coeficientes de restituição" (scenes.h, SCENE_GRAFICA variants 0 and 1).
// Writes grafica_<tipo>.csv (every body every 0.1 s), frames grafica_<tipo>_<step>.svg (every 0.5 s, as
// the thesis shows a sequence), summary.csv (start and final pose of every body per variant),
// outcome.csv (the figures checked below, per variant) and prints a summary.
//
// Checks, each with its reason:
//  - nothing falls through or off: every free body's centre stays above the block's lowest top point
//    (scene.ground_top) all the time, and at no contact point of any step do the true curves overlap by
//    more than 5 mm beyond the two bodies' widest bands (ContactScan::worstExcess; Box2D's position
//    correction resolves overlaps of a few mm between free bodies);
//  - energy does not grow: the largest increase in one step is below 1% of the initial energy (contacts
//    only remove energy; Box2D 2.4 has no continuous collision between free bodies, and pushing apart
//    two letters that overlap on impact can raise potential energy a little in one step, as in Fig. 7.9),
//    and the final energy is below the initial;
//  - the bodies come to rest: final kinetic energy below 0.5% of the energy released and no body faster
//    than 5 cm/s at the end;
//  - tipo_2 and tipo_3 give measurably different outcomes (the thesis: "um pouco diferente"):
//      the letters' final poses differ: mean over letters of |Δ centre| > 2 cm or of |Δ angle| > 0.1 rad,
//      the mean μ over all rough contacts is larger for tipo_2 than for tipo_3 by at least 0.05: the
//      library's presets give tipo_2 λ uniform in [0.04, 0.65] (mean 0.345) and tipo_3 0.32 0.24 0.20
//      0.24 (mean 0.25), i.e. μ 0.50 vs 0.375 on average through the scenes' friction map, and under
//      max mixing (7.2) of two surfaces E[max] = 0.65 vs 0.40 (computed here from the presets; the
//      margin is a quarter of that difference),
//      and, as less friction lets a push carry further, the letters' mean x displacement is larger for
//      tipo_3 than for tipo_2 by at least 0.1 m.
#include "b2_sample.hpp"

namespace {

struct Pose {
    double x, y, a;
};

struct Outcome {
    std::string label;
    std::vector<Pose> start, final;
    double meanMu = NAN, e0 = NAN, eFinal = NAN, released = NAN, finalKinetic = NAN, maxGrowth = NAN,
           minAbove = 1e9;
    double worstOverlap = -1e9;
    int worstA = -1, worstB = -1;
    long muCount = 0;
    double ballSpeed = NAN, maxSpeed = NAN;
};

// desc receives the scene's description, for after the run.
bool RunVariant(int v, const std::string& dir, std::shared_ptr<const scene>* desc, Outcome* out) {
    Outcome o;
    b2s::Record rec;
    {
        b2s::Run run;
        if (!scene_table::Create("fig7_10_grafica", v, &run)) return false;
        *desc = run.description;
        const scene& s = *run.sc;
        o.label = s.label;
        for (const b2Body* b : run.bodies)
            o.start.push_back({b->GetPosition().x, b->GetPosition().y, b->GetAngle()});
        std::vector<long> frames;
        for (long k = 0; static_cast<double>(k) * s.time_step < s.duration; k += 30)
            frames.push_back(k);
        const bool ok = b2s::RunScene(run, dir, "grafica_" + o.label, frames, &rec, [&](const b2s::Run& r) {
            const b2s::ContactScan cs = b2s::ScanContacts(r);
            if (cs.worstExcess > o.worstOverlap) {
                o.worstOverlap = cs.worstExcess;
                o.worstA = cs.worstA;
                o.worstB = cs.worstB;
            }
        });
        if (!ok) return false;
        for (const b2Body* b : run.bodies)
            o.final.push_back({b->GetPosition().x, b->GetPosition().y, b->GetAngle()});
        o.eFinal = b2s::Energy(run);
        o.maxSpeed = 0.0;
        for (const b2Body* b : run.bodies)
            o.maxSpeed = std::max(o.maxSpeed, b2s::Speed(b));
        o.ballSpeed = b2s::Speed(run.bodies[static_cast<std::size_t>(run.Find(SCENE_ROLE_MOVER))]);
    }
    o.meanMu = rec.MeanMu();
    o.muCount = rec.muCount;
    o.e0 = rec.e0;
    o.released = rec.e0 - o.eFinal;
    o.finalKinetic = rec.finalKinetic;
    o.maxGrowth = rec.maxGrowth;
    o.minAbove = rec.minY - (*desc)->ground_top;
    *out = o;
    return true;
}

// The mean μ the library's presets predict at a contact between two independent surfaces of a preset
// under the thesis' max mixing (7.2): E[max(μ(λ_a), μ(λ_b))] over all pairs of 1024 segments' λ, μ from
// the scenes' friction map, λ in metres (library units times SCENE_ROUGHNESS_SCALE).
double PresetMaxMu(rugo_tolerance_preset p) {
    enum { N = 1024 };
    static double lam[N];
    rugo_tolerances_preset(p, 7, N, lam);
    const rugo_friction_map fm = scene_friction_map();
    std::vector<double> mu(N);
    for (int i = 0; i < N; ++i)
        mu[static_cast<std::size_t>(i)] = rugo_friction(&fm, lam[i] * SCENE_ROUGHNESS_SCALE);
    double e = 0.0;
    for (double a : mu)
        for (double b : mu)
            e += std::max(a, b);
    return e / (static_cast<double>(N) * N);
}

} // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : "out/b2_fig7_10_grafica";
    if (sample_mkdir(dir.c_str()) != 0) return 1;
    std::shared_ptr<const scene> s[2];
    Outcome o[2];
    for (int v = 0; v < 2; ++v)
        if (!sample_expect("variant ran", RunVariant(v, dir, &s[v], &o[v]))) return sample_finish();

    FILE* f = b2s::OpenOut(dir, "summary.csv");
    if (f) std::fprintf(f, "variant,body,name,x0,y0,angle0,x,y,angle\n");
    std::printf("body      start (x, y)        %-28s %-28s |dp| [m]  |da| [rad]\n",
                ("final " + o[0].label + " (x, y, angle)").c_str(),
                ("final " + o[1].label + " (x, y, angle)").c_str());
    double sumDp = 0.0, sumDa = 0.0, push[2] = {0.0, 0.0};
    int letters = 0;
    for (int i = 0; i < s[0]->body_count; ++i) {
        const std::size_t u = static_cast<std::size_t>(i);
        for (int v = 0; v < 2; ++v)
            if (f)
                std::fprintf(f, "%s,%d,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", o[v].label.c_str(), i,
                             s[v]->bodies[i].name, o[v].start[u].x, o[v].start[u].y, o[v].start[u].a,
                             o[v].final[u].x, o[v].final[u].y, o[v].final[u].a);
        if (s[0]->bodies[i].is_static) continue;
        const double dp = std::hypot(o[0].final[u].x - o[1].final[u].x, o[0].final[u].y - o[1].final[u].y);
        const double da = std::fabs(std::remainder(o[0].final[u].a - o[1].final[u].a, 6.283185307179586));
        std::printf("%-8s (%6.3f, %6.3f)   (%6.3f, %6.3f, %7.3f)    (%6.3f, %6.3f, %7.3f)    %.4f    %.4f\n",
                    s[0]->bodies[i].name, o[0].start[u].x, o[0].start[u].y, o[0].final[u].x, o[0].final[u].y,
                    o[0].final[u].a, o[1].final[u].x, o[1].final[u].y, o[1].final[u].a, dp, da);
        if (s[0]->bodies[i].role == SCENE_ROLE_OBJECT) {
            sumDp += dp;
            sumDa += da;
            for (int v = 0; v < 2; ++v)
                push[v] += o[v].final[u].x - o[v].start[u].x;
            ++letters;
        }
    }
    if (f) std::fclose(f);
    const double meanDp = sumDp / letters, meanDa = sumDa / letters;
    for (double& p : push)
        p /= letters;
    const double predicted[2] = {PresetMaxMu(RUGO_PRESET_TIPO_2), PresetMaxMu(RUGO_PRESET_TIPO_3)};
    for (const Outcome& r : o)
        std::printf("%s: mean mu %.4f over %ld contact-steps; energy %.3f J -> %.3f J (released %.3f J), "
                    "final kinetic %.3g J, "
                    "largest step growth %.3g of initial, lowest centre %.3f m above the block's lowest top, "
                    "deepest overlap beyond "
                    "bands %.4f m (%s-%s), ball ends at %.3f m/s\n",
                    r.label.c_str(), r.meanMu, r.muCount, r.e0, r.eFinal, r.released, r.finalKinetic,
                    r.maxGrowth, r.minAbove, r.worstOverlap,
                    r.worstA >= 0 ? s[0]->bodies[r.worstA].name : "-",
                    r.worstB >= 0 ? s[0]->bodies[r.worstB].name : "-", r.ballSpeed);
    std::printf("tipo_2 vs tipo_3: mean |d centre| %.4f m, mean |d angle| %.4f rad over %d letters; letters "
                "pushed %.4f m vs %.4f m "
                "on average\n",
                meanDp, meanDa, letters, push[0], push[1]);
    std::printf("mean mu at contacts: tipo_2 %.4f (presets predict %.4f), tipo_3 %.4f (predict %.4f); "
                "difference %.4f (predict %.4f)\n",
                o[0].meanMu, predicted[0], o[1].meanMu, predicted[1], o[0].meanMu - o[1].meanMu,
                predicted[0] - predicted[1]);
    if (FILE* fs = b2s::OpenOut(dir, "outcome.csv")) {
        std::fprintf(fs, "variant,mean_mu,predicted_mu,contact_samples,mean_push,energy_initial,energy_final,"
                         "final_kinetic,max_growth,"
                         "min_above_ground,worst_overlap\n");
        for (int v = 0; v < 2; ++v)
            std::fprintf(fs, "%s,%.6f,%.6f,%ld,%.6f,%.6f,%.6f,%.6g,%.6g,%.6f,%.6f\n", o[v].label.c_str(),
                         o[v].meanMu, predicted[v], o[v].muCount, push[v], o[v].e0, o[v].eFinal,
                         o[v].finalKinetic, o[v].maxGrowth, o[v].minAbove, o[v].worstOverlap);
        std::fclose(fs);
    }

    for (const Outcome& r : o) {
        sample_expect_le(
            (r.label + ": nothing falls through or off, -(lowest centre - block's lowest top) [m]").c_str(),
            -r.minAbove, 0.0);
        sample_expect_le((r.label + ": no true-curve overlap beyond the bands above 5 mm [m]").c_str(),
                         r.worstOverlap, 0.005);
        sample_expect_le((r.label + ": energy does not grow, largest step increase / initial").c_str(),
                         r.maxGrowth, 1e-2);
        sample_expect_le((r.label + ": energy does not grow, final - initial [J]").c_str(), r.eFinal - r.e0,
                         0.0);
        sample_expect_le((r.label + ": bodies come to rest, final kinetic / released").c_str(),
                         r.finalKinetic / r.released, 0.005);
        sample_expect_le((r.label + ": bodies come to rest, largest final speed [m/s]").c_str(), r.maxSpeed,
                         0.05);
    }
    sample_expect("tipo_2 vs tipo_3 differ: mean |d centre| > 0.02 m or mean |d angle| > 0.1 rad",
                  meanDp > 0.02 || meanDa > 0.1);
    sample_expect("the presets predict tipo_2 rougher than tipo_3 under max mixing",
                  predicted[0] > predicted[1]);
    sample_expect_le(
        "tipo_2 rougher than tipo_3: mean mu(tipo_2) - mean mu(tipo_3) >= 0.05, -(difference - 0.05)",
        -(o[0].meanMu - o[1].meanMu - 0.05), 0.0);
    sample_expect_le("less friction, longer pushes: letters' mean x displacement tipo_3 - tipo_2 >= 0.1 m, "
                     "-(difference - 0.1)",
                     -(push[1] - push[0] - 0.1), 0.0);
    return sample_finish();
}
