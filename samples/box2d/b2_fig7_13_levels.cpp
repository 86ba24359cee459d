// Thesis Fig. 7.12-7.13 through the Box2D bridge: three objects of arbitrary geometry with fine detail
// (a toothed, a wavy and a noisy slab, 256 control points, tipo_3 roughness) thrown at 4 m/s along a
// fixed flat block (tipo_3), animated with contacts at levels of detail 0 (reference), -1 and -2
// (scenes.h, SCENE_LEVELS). Writes levels_<level>.csv, frames levels_<level>_<step>.svg, summary.csv
// and tolerances.csv (the per-level table below).
//
// Why it works (SPEC 6.2, thesis 5.3): the total tolerance of a coarse segment is its own estimate from
// the geometry the level cannot represent plus the mean of its two finer segments' totals,
//     λ^j_k = own^j_k + (λ^{j+1}_{2k} + λ^{j+1}_{2k+1}) / 2,
// so the mean λ of a level is the mean λ of the finer level plus the mean own^j. Smooth blobs (the
// scene's previous objects) have own^j ~ 0: the averaging only smooths λ(t), and under the thesis' max
// mixing of a pair's μ (7.2) a smoother λ lowers the expected max, so μ fell with the level (measured
// 0.405 / 0.399 / 0.380 at levels 0 / -1 / -2, predicted from the λ tables 0.405 / 0.395 / 0.382). The
// objects now carry millimetre detail at the scales of 1-8 control points, which levels -1 and -2 must
// absorb into λ (own^-1 ~ 2 mm, own^-2 ~ 3 mm against λ = 5 mm at the finest level).
//
// For each level the sample prints, per body: the mean λ and mean own^j over the segments at that level
// (the block: its top face, at least 1 m from the ends, where the objects slide), the mean μ(λ) over
// those segments, the μ predicted at the object's contacts (mean over object segment x block segment of
// max(μ_object, μ_block): uniformly spread contacts) and the mean μ measured at the object's contacts.
//
// Checks, each with its reason:
//  - the objects' detail is absorbed: every object's mean own^j at levels -1 and -2 is at least 1 mm
//    (20% of the finest λ), else the scene would not test (5.3);
//  - coarser is rougher (the thesis' observation): mean μ over all rough contacts at level -1 exceeds
//    level 0's by at least 0.04 and level -2's exceeds level -1's by at least 0.08 (the λ tables predict
//    ~0.10 and ~0.20: α = 65.6 /m times the added own^j, diluted by the block's μ under max mixing;
//    the margins are ~40% of that, above the ~0.03 that contact sampling moves the mean);
//  - more friction, shorter slides (a slab sliding to rest travels v0^2 / (2 μ g)): the objects' mean
//    slide distance is smaller at -1 than at 0, and smaller at -2 than at -1;
//  - nothing falls through; energy never grows (0.1% of the initial per step for position correction);
//    the objects come to rest (final kinetic energy < 1% of the initial kinetic energy).
#include "b2_sample.hpp"

namespace {

struct LevelTable {
    double lambda = 0, own = 0, mu = 0; // means over the segments considered
    std::vector<double> mus;            // μ(λ) per segment
};

// Means over the shape's segments at `rel` levels below its finest; block_top: only the segments whose
// midpoint is on the top face of a block centred at the origin (upper half, outward normal within 8° of
// straight up), at least 1 m from its ends.
LevelTable Table(const rugo_shape* sh, int rel, bool block_top) {
    LevelTable t;
    int j = rugo_shape_finest_level(sh) + rel;
    if (j < rugo_shape_coarsest_level(sh)) j = rugo_shape_coarsest_level(sh);
    rugo_tolerance_level tl;
    rugo_contour c;
    if (rugo_shape_tolerance_level(sh, j, &tl) != RUGO_OK || rugo_shape_level(sh, j, &c) != RUGO_OK) return t;
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    const rugo_friction_map fm = rugo_shape_friction_map(sh);
    for (int k = 0; k < tl.count; ++k) {
        const rugo_vec2 m = rugo_contour_point(c, k, 0.5), nrm = rugo_contour_normal(c, k, 0.5);
        if (block_top && (nrm.y < 0.99 || m.y < 0.5 * (lo.y + hi.y) || m.x < lo.x + 1.0 || m.x > hi.x - 1.0))
            continue;
        t.lambda += tl.total[k];
        t.own += tl.own[k];
        t.mus.push_back(rugo_friction(&fm, tl.total[k]));
        t.mu += t.mus.back();
    }
    const double n = static_cast<double>(t.mus.size());
    t.lambda /= n;
    t.own /= n;
    t.mu /= n;
    return t;
}

double PredictedMaxMu(const LevelTable& a, const LevelTable& b) {
    double e = 0.0;
    for (double x : a.mus)
        for (double y : b.mus)
            e += std::max(x, y);
    return e / static_cast<double>(a.mus.size() * b.mus.size());
}

} // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : "out/b2_fig7_13_levels";
    if (sample_mkdir(dir.c_str()) != 0) return 1;
    static const int variants[3] = {2, 0, 1}; // levels 0, -1, -2
    double mu[3] = {NAN, NAN, NAN}, slide[3] = {NAN, NAN, NAN}, predicted[3] = {NAN, NAN, NAN};
    FILE* f = b2s::OpenOut(dir, "summary.csv");
    FILE* ft = b2s::OpenOut(dir, "tolerances.csv");
    if (f)
        std::fprintf(f, "level,mean_mu,predicted_mu,contact_samples,mean_slide,final_x0,final_x1,final_x2,"
                        "max_energy_growth,final_kinetic\n");
    if (ft)
        std::fprintf(ft, "level,body,mean_lambda,mean_own,mean_mu_of_lambda,predicted_contact_mu,measured_"
                         "contact_mu,contact_samples\n");
    for (int i = 0; i < 3; ++i) {
        b2s::Run run;
        if (!sample_expect("scene built", scene_table::Create("fig7_13_levels", variants[i], &run)))
            return sample_finish();
        const scene& s = *run.sc;
        b2s::Record rec;
        std::vector<double> bodyMu;
        std::vector<long> bodyMuCount;
        double k0 = 0.0;
        for (const b2Body* b : run.bodies)
            if (b->GetType() == b2_dynamicBody) k0 += 0.5 * b->GetMass() * b2s::Speed(b) * b2s::Speed(b);
        const bool ok =
            b2s::RunScene(run, dir, std::string("levels_") + s.label, {0, 30, 60, 120}, &rec,
                          [&](const b2s::Run& r) { b2s::AddContactMuPerBody(r, &bodyMu, &bodyMuCount); });
        if (!sample_expect("scene ran", ok)) return sample_finish();
        mu[i] = rec.MeanMu();
        const std::vector<b2Vec2>& fin = rec.pos.back();
        const int block = 0;
        const LevelTable tb = Table(s.bodies[block].shape, s.level, true);
        std::printf("level %2d                  mean lambda  mean own   mean mu(lambda)  predicted contact "
                    "mu  measured contact mu\n",
                    s.level);
        std::printf("  %-22s %7.3f mm   %7.3f mm  %.4f\n", "block (top)", 1e3 * tb.lambda, 1e3 * tb.own,
                    tb.mu);
        if (ft) std::fprintf(ft, "%d,block_top,%.7f,%.7f,%.5f,,,\n", s.level, tb.lambda, tb.own, tb.mu);
        double sumSlide = 0.0, predSum = 0.0;
        int nObj = 0;
        for (int b = 1; b < s.body_count; ++b) {
            const LevelTable to = Table(s.bodies[b].shape, s.level, false);
            const double pred = PredictedMaxMu(to, tb);
            const std::size_t ub = static_cast<std::size_t>(b);
            const double meas = bodyMuCount[ub] ? bodyMu[ub] / static_cast<double>(bodyMuCount[ub]) : NAN;
            std::printf("  %-22s %7.3f mm   %7.3f mm  %.4f           %.4f                %.4f (%ld)\n",
                        s.bodies[b].name, 1e3 * to.lambda, 1e3 * to.own, to.mu, pred, meas, bodyMuCount[ub]);
            if (ft)
                std::fprintf(ft, "%d,%s,%.7f,%.7f,%.5f,%.5f,%.5f,%ld\n", s.level, s.bodies[b].name, to.lambda,
                             to.own, to.mu, pred, meas, bodyMuCount[ub]);
            if (s.level != 0)
                sample_expect_le((std::string(s.label) + ": " + s.bodies[b].name +
                                  " absorbs real detail, -(mean own) [mm]")
                                     .c_str(),
                                 -1e3 * to.own, -1.0);
            sumSlide += fin[ub].x - rec.pos.front()[ub].x;
            predSum += pred;
            ++nObj;
        }
        slide[i] = sumSlide / nObj;
        predicted[i] = predSum / nObj;
        std::printf("  all contacts: mean mu %.4f over %ld contact-steps (predicted %.4f); mean slide %.3f "
                    "m; objects end at x = "
                    "%.3f, %.3f, %.3f\n",
                    mu[i], rec.muCount, predicted[i], slide[i], fin[1].x, fin[2].x, fin[3].x);
        if (f)
            std::fprintf(f, "%d,%.6f,%.6f,%ld,%.5f,%.5f,%.5f,%.5f,%.6g,%.6g\n", s.level, mu[i], predicted[i],
                         rec.muCount, slide[i], fin[1].x, fin[2].x, fin[3].x, rec.maxGrowth,
                         rec.finalKinetic);
        sample_expect_le((std::string(s.label) + ": nothing falls through, -(lowest centre y) [m]").c_str(),
                         -rec.minY, 0.0);
        sample_expect_le(
            (std::string(s.label) + ": energy never grows, largest step increase / initial").c_str(),
            rec.maxGrowth, 1e-3);
        sample_expect_le(
            (std::string(s.label) + ": objects come to rest, final kinetic / initial kinetic").c_str(),
            rec.finalKinetic / k0, 0.01);
    }
    if (f) std::fclose(f);
    if (ft) std::fclose(ft);
    sample_expect_le("coarser is rougher: mean mu at level -1 - at level 0 >= 0.04, -(difference - 0.04)",
                     -(mu[1] - mu[0] - 0.04), 0.0);
    sample_expect_le("coarser is rougher: mean mu at level -2 - at level -1 >= 0.08, -(difference - 0.08)",
                     -(mu[2] - mu[1] - 0.08), 0.0);
    sample_expect("more friction, shorter slides: mean slide at level -1 < at level 0", slide[1] < slide[0]);
    sample_expect("more friction, shorter slides: mean slide at level -2 < at level -1", slide[2] < slide[1]);
    return sample_finish();
}
