// Thesis Fig. 7.7-7.8 through the Box2D bridge: an irregular slab thrown at tangential speed 10 m/s on a
// fixed block. (a) both surfaces tipo_2; (b) a smooth slab on a block that is rough, smooth, rough along
// its length (scenes.h, SCENE_THROWN). Writes thrown_a.csv / thrown_b.csv (t, pose, velocity, tangential
// contact speed, μ of the contacts), frames thrown_<v>_<step>.svg and summary.json.
//
// Checks: the slab stays on the block and does not tip over; energy never grows; it comes to rest
// (tangential speed falls to 0, thesis 7.8); (b) each stretch decelerates at μ g within 20%. (b): the
// deceleration on each stretch is measured by a least-squares slope of the tangential speed while the whole
// slab is inside the stretch; Coulomb sliding decelerates at μ g, so the friction map predicts rough / smooth
// = μ_rough / μ_smooth (0.83 / 0.10 = 8.3). We require the measured ratio to be at least half of that
// (>= 4.2): the slab rocks (normal force varies), Box2D solves friction iteratively and λ(t) ramps over a
// segment at each stretch end.
#include "b2_sample.hpp"

#include <algorithm>

namespace {

struct Sample {
    double t, x, y, a, vx, vy, w, vt, mu, e;
    int contacts;
};

// desc receives the scene's description, for after the run.
bool RunVariant(int v, const std::string& dir, std::vector<Sample>* out, std::shared_ptr<const scene>* desc) {
    b2s::Run run;
    if (!scene_table::Create("fig7_8_thrown", v, &run)) return false;
    *desc = run.description;
    const scene* s = run.sc;
    const int im = run.Find(SCENE_ROLE_MOVER), ig = run.Find(SCENE_ROLE_GROUND);
    b2Body* body = run.bodies[static_cast<std::size_t>(im)];
    const long n = run.entry->stepCount;
    const std::string tag = v == 0 ? "a" : "b";
    FILE* f = b2s::OpenOut(dir, ("thrown_" + tag + ".csv").c_str());
    if (!f) return false;
    std::fprintf(f, "t,x,y,angle,vx,vy,w,tangential_speed,mu,contacts,energy\n");
    for (long k = 0; k <= n; ++k) {
        if (k == 0 || k == 30 || k == 60 || k == n) {
            char name[64], title[160];
            std::snprintf(name, sizeof name, "/thrown_%s_%04ld.svg", tag.c_str(), k);
            std::snprintf(title, sizeof title, "Fig. 7.7 (%s) t = %.2f s, vx = %.2f m/s", s->label, run.time,
                          static_cast<double>(body->GetLinearVelocity().x));
            b2s::DrawFrame(run, dir + name, title, true);
        }
        // Tangential speed at the contact: the body's velocity along the block's top at the contact
        // points (the block is fixed); μ: the bridge's per-contact friction.
        Sample smp{};
        smp.t = run.time;
        double vt = 0.0, mu = 0.0;
        for (b2ContactEdge* ce = body->GetContactList(); ce; ce = ce->next) {
            b2Contact* c = ce->contact;
            if (!c->IsTouching() || !c->IsEnabled() || ce->other != run.bodies[static_cast<std::size_t>(ig)])
                continue;
            b2WorldManifold wm;
            c->GetWorldManifold(&wm);
            for (int p = 0; p < c->GetManifold()->pointCount; ++p) {
                vt += body->GetLinearVelocityFromWorldPoint(wm.points[p]).x;
                mu += c->GetFriction();
                ++smp.contacts;
            }
        }
        const b2Vec2 c = body->GetWorldCenter(), vel = body->GetLinearVelocity();
        smp.x = c.x;
        smp.y = c.y;
        smp.a = body->GetAngle();
        smp.vx = vel.x;
        smp.vy = vel.y;
        smp.w = body->GetAngularVelocity();
        smp.vt = smp.contacts ? vt / smp.contacts : NAN;
        smp.mu = smp.contacts ? mu / smp.contacts : NAN;
        smp.e = b2s::Energy(run);
        std::fprintf(f, "%.5f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.5f,%d,%.6f\n", smp.t, smp.x, smp.y, smp.a,
                     smp.vx, smp.vy, smp.w, smp.vt, smp.mu, smp.contacts, smp.e);
        out->push_back(smp);
        if (k < n) run.Step();
    }
    return std::fclose(f) == 0;
}

// Deceleration (-dv/dt, least squares) of the tangential speed while the slab (half-length 0.6 m plus
// a 0.3 m margin for the λ ramp) lies wholly inside [x0, x1] and slides (v > 0.3 m/s).
double Deceleration(const std::vector<Sample>& s, double x0, double x1, int* count) {
    std::vector<double> t, v;
    for (const Sample& p : s)
        if (p.contacts > 0 && p.x - 0.9 >= x0 && p.x + 0.9 <= x1 && p.vx > 0.3) {
            t.push_back(p.t);
            v.push_back(p.vx);
        }
    *count = static_cast<int>(t.size());
    return -b2s::Slope(t, v);
}

} // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : "out/b2_fig7_8_thrown";
    if (sample_mkdir(dir.c_str()) != 0) return 1;
    std::vector<Sample> a, b;
    std::shared_ptr<const scene> sa, sb;
    const bool ok = RunVariant(0, dir, &a, &sa) && RunVariant(1, dir, &b, &sb);
    if (!sample_expect("both variants ran", ok)) return sample_finish();
    const double g = 9.81;
    double rough1 = 0, smooth = 0, rough2 = 0;
    int n1 = 0, n2 = 0, n3 = 0;
    rough1 = Deceleration(b, -10.0, sb->stretch[0], &n1);
    smooth = Deceleration(b, sb->stretch[0], sb->stretch[1], &n2);
    rough2 = Deceleration(b, sb->stretch[1], 10.0, &n3);
    const double predicted = sb->stretch_mu[0] / sb->stretch_mu[1];
    const double ratio = rough1 / smooth;
    std::printf(
        "Fig. 7.8(b): deceleration rough %.3f m/s^2 (%d samples), smooth %.3f (%d), rough again %.3f (%d)\n",
        rough1, n1, smooth, n2, rough2, n3);
    std::printf("  friction map: mu rough %.3f, smooth %.3f -> predicted decelerations %.3f, %.3f; ratio "
                "%.2f (predicted %.2f)\n",
                sb->stretch_mu[0], sb->stretch_mu[1], sb->stretch_mu[0] * g, sb->stretch_mu[1] * g, ratio,
                predicted);
    auto stopTime = [](const std::vector<Sample>& s) -> double {
        for (const Sample& p : s)
            if (std::fabs(p.vx) < 0.05 && p.t > 0.2) return p.t;
        return NAN;
    };
    auto maxAbs = [](const std::vector<Sample>& s, double Sample::*m) {
        double r = 0;
        for (const Sample& p : s)
            r = std::max(r, std::fabs(p.*m));
        return r;
    };
    auto minY = [](const std::vector<Sample>& s) {
        double r = 1e9;
        for (const Sample& p : s)
            r = std::min(r, p.y);
        return r;
    };
    std::printf("Fig. 7.8(a): stops at t = %.3f s at x = %.3f; (b) stops at t = %.3f s at x = %.3f\n",
                stopTime(a), a.back().x, stopTime(b), b.back().x);
    // The slab stops within a few cm of the second rough stretch: too few samples there for a slope.
    const std::string r2 = n3 >= 5 ? std::to_string(rough2) : "null";
    FILE* f = b2s::OpenOut(dir, "summary.json");
    if (f) {
        std::fprintf(f,
                     "{\"a\": {\"stop_time\": %.5f, \"stop_x\": %.5f},\n \"b\": {\"stop_time\": %.5f, "
                     "\"stop_x\": %.5f,\n"
                     "  \"deceleration\": {\"rough\": %.6f, \"smooth\": %.6f, \"rough_again\": %s},\n"
                     "  \"samples\": [%d, %d, %d], \"mu\": {\"rough\": %.5f, \"smooth\": %.5f},\n"
                     "  \"ratio\": %.5f, \"predicted_ratio\": %.5f}}\n",
                     stopTime(a), a.back().x, stopTime(b), b.back().x, rough1, smooth, r2.c_str(), n1, n2, n3,
                     sb->stretch_mu[0], sb->stretch_mu[1], ratio, predicted);
        std::fclose(f);
    }
    for (int v = 0; v < 2; ++v) {
        const std::vector<Sample>& s = v == 0 ? a : b;
        const char* tag = v == 0 ? "(a)" : "(b)";
        std::string p = std::string(tag) + " ";
        // The slab's centre rests ~0.2 m above the top (y = 0); below 0 it went through.
        sample_expect_le((p + "stays on the block: -(lowest centre y) [m]").c_str(), -minY(s), -0.1);
        sample_expect_le((p + "does not tip over: largest |angle| [rad]").c_str(), maxAbs(s, &Sample::a),
                         0.5);
        sample_expect((p + "tangential speed falls to 0 (stops within the run)").c_str(),
                      !std::isnan(stopTime(s)));
        sample_expect_le((p + "at rest at the end: |vx| [m/s]").c_str(), std::fabs(s.back().vx), 0.05);
        double grow = 0.0;
        for (std::size_t i = 1; i < s.size(); ++i)
            grow = std::max(grow, s[i].e - s[i - 1].e);
        // Friction only removes energy; allow 0.1% of the initial per step for Box2D's position correction.
        sample_expect_le((p + "energy never grows: largest step increase / initial energy").c_str(),
                         grow / s[0].e, 1e-3);
    }
    sample_expect("(b) enough samples on the first rough stretch and on the smooth one",
                  n1 >= 10 && n2 >= 10);
    sample_expect_le("(b) smooth stretch decelerates at mu_smooth g within 20%: |a/(mu g) - 1|",
                     std::fabs(smooth / (sb->stretch_mu[1] * g) - 1.0), 0.2);
    sample_expect_le("(b) rough stretch decelerates at mu_rough g within 20%: |a/(mu g) - 1|",
                     std::fabs(rough1 / (sb->stretch_mu[0] * g) - 1.0), 0.2);
    sample_expect_le(
        "(b) decelerates measurably faster on the rough stretch: -(rough/smooth) <= -predicted/2", -ratio,
        -0.5 * predicted);
    return sample_finish();
}
