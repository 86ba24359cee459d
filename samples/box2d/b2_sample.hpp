// Helpers shared by the headless Box2D samples (b2_*.cpp): measure a scene of the scene table
// (scene_table.hpp) as it runs (energy, contacts, penetration, FNV-1a hash of transforms) and draw SVG
// frames with the samples' SVG writer. Header-only; C++17.
#ifndef RUGO_SAMPLES_B2_SAMPLE_HPP
#define RUGO_SAMPLES_B2_SAMPLE_HPP

#include "rugo/box2d.hpp"

#include "scene_table.hpp"
#include "scenes.h"
extern "C" {
#include "sample_check.h"
#include "svg.h"
}

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace b2s {

// A scene of the scene table living in a b2World (scene_table.hpp): what every helper here measures.
using Run = scene_table::World;

// Kinetic plus potential energy of the dynamic bodies (J), potential from the scene's gravity.
inline double Energy(const Run& r) {
    double e = 0.0;
    for (const b2Body* b : r.bodies) {
        if (b->GetType() != b2_dynamicBody) continue;
        const double m = b->GetMass();
        const b2Vec2 lc = b->GetLocalCenter();
        const double ic = b->GetInertia() - m * (lc.x * lc.x + lc.y * lc.y); // Box2D's is about the origin
        const b2Vec2 v = b->GetLinearVelocity(), c = b->GetWorldCenter();
        const double w = b->GetAngularVelocity();
        e += 0.5 * m * (v.x * v.x + v.y * v.y) + 0.5 * ic * w * w -
             m * (r.sc->gravity.x * c.x + r.sc->gravity.y * c.y);
    }
    return e;
}

inline double Speed(const b2Body* b) {
    const b2Vec2 v = b->GetLinearVelocity();
    return std::sqrt(static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y);
}

// The touching, enabled contacts after a step: counts, and the deepest penetration beyond what the
// bands allow: max over points of -(s + band_A + band_B), s the manifold's band-adjusted separation
// (curve distance minus bands): > 0 means the true curves overlap by that much.
struct ContactScan {
    int contacts = 0, rough = 0, points = 0;
    double minSeparation = 0.0;   // of the manifolds (band-adjusted)
    double worstExcess = -1e9;    // max of -(s + bands), see above
    int worstA = -1, worstB = -1; // scene indices of that pair
    double worstOrdinary = -1e9;  // the same for contacts between ordinary fixtures (Box2D's own)
    double frictionSum = 0.0;     // over rough contacts
    int frictionCount = 0;
};
inline ContactScan ScanContacts(const Run& r) {
    ContactScan cs;
    for (b2Contact* c = r.world->GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled()) continue;
        ++cs.contacts;
        b2Fixture *fa = c->GetFixtureA(), *fb = c->GetFixtureB();
        const bool rough = r.bridge->IsProxy(fa) || r.bridge->IsProxy(fb);
        if (!rough) {
            b2WorldManifold wm;
            c->GetWorldManifold(&wm);
            for (int k = 0; k < c->GetManifold()->pointCount; ++k)
                cs.worstOrdinary = std::max(cs.worstOrdinary, -static_cast<double>(wm.separations[k]));
            continue;
        }
        ++cs.rough;
        cs.frictionSum += c->GetFriction();
        ++cs.frictionCount;
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        const int ia = r.Index(fa->GetBody()), ib = r.Index(fb->GetBody());
        const double bands = (ia >= 0 ? r.bands[ia] : 0.0) + (ib >= 0 ? r.bands[ib] : 0.0);
        for (int k = 0; k < c->GetManifold()->pointCount; ++k) {
            ++cs.points;
            const double s = wm.separations[k];
            cs.minSeparation = std::min(cs.minSeparation, s);
            if (-(s + bands) > cs.worstExcess) {
                cs.worstExcess = -(s + bands);
                cs.worstA = ia;
                cs.worstB = ib;
            }
        }
    }
    return cs;
}

// Friction of the touching, enabled rough contacts after a step, per scene body: sum[i] and count[i]
// gain the contact's μ for each of its two bodies (a contact between two free bodies counts for both).
inline void AddContactMuPerBody(const Run& r, std::vector<double>* sum, std::vector<long>* count) {
    sum->resize(r.bodies.size(), 0.0);
    count->resize(r.bodies.size(), 0);
    for (b2Contact* c = r.world->GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled()) continue;
        b2Fixture *fa = c->GetFixtureA(), *fb = c->GetFixtureB();
        if (!r.bridge->IsProxy(fa) && !r.bridge->IsProxy(fb)) continue;
        for (const b2Body* b : {fa->GetBody(), fb->GetBody()}) {
            const int i = r.Index(b);
            if (i < 0) continue;
            (*sum)[static_cast<std::size_t>(i)] += c->GetFriction();
            ++(*count)[static_cast<std::size_t>(i)];
        }
    }
}

// FNV-1a over the float bits of (x, y, angle) of every body, in creation order (scene_table's hash),
// continued step after step.
struct Fnv1a {
    std::uint64_t h = SAMPLE_FNV_OFFSET;
    void Bodies(const Run& r) { h = scene_table::HashBodies(h, r); }
};

// ---- SVG frames ------------------------------------------------------------------------------
inline double Px(const svg_canvas& c, double x) { return (x - c.ox) * c.scale; }
inline double Py(const svg_canvas& c, double y) { return c.height - (y - c.oy) * c.scale; }

inline void PolyLine(svg_canvas& c, const std::vector<b2Vec2>& v, bool closed, const char* stroke,
                     const char* fill) {
    std::fprintf(c.file, "<%s fill=\"%s\" stroke=\"%s\" stroke-width=\"1.2\" points=\"",
                 closed ? "polygon" : "polyline", fill, stroke);
    for (const b2Vec2& p : v)
        std::fprintf(c.file, "%.2f,%.2f ", Px(c, p.x), Py(c, p.y));
    std::fprintf(c.file, "\"/>\n");
}

inline const char* Colour(int i) {
    static const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                                    "#66a61e", "#e6ab02", "#a6761d"};
    return colours[i % 7];
}

// Every body at its current transform: rough bodies as their curve at the contact level (and the band's
// outer offset dashed when show_band), ordinary fixtures as Box2D has them.
inline bool DrawFrame(const Run& r, const std::string& path, const char* title, bool show_band = false) {
    svg_canvas c;
    if (svg_open(&c, path.c_str(), r.sc->view_lo, r.sc->view_hi, 900.0) != 0) return false;
    for (std::size_t i = 0; i < r.bodies.size(); ++i) {
        const b2Body* b = r.bodies[i];
        const b2Transform xf = b->GetTransform();
        const scene_body& sb = r.sc->bodies[i];
        const char* col = sb.is_static ? "#555555" : Colour(static_cast<int>(i));
        if (sb.kind == SCENE_ROUGH) {
            rugo_contour k;
            rugo_shape_level(sb.shape, r.bridge->GetLevel(b), &k);
            std::vector<rugo_vec2> pts(static_cast<std::size_t>(k.count));
            const rugo_transform t = rugo_make_transform(xf.p.x, xf.p.y, b->GetAngle());
            for (int j = 0; j < k.count; ++j)
                pts[static_cast<std::size_t>(j)] = rugo_transform_point(t, k.points[j]);
            rugo_contour w = {pts.data(), k.count};
            svg_contour(&c, w, 6, col, 1.4, nullptr);
            if (show_band) {
                rugo_tolerance_level tl;
                rugo_shape_tolerance_level(sb.shape, r.bridge->GetLevel(b), &tl);
                std::vector<b2Vec2> band;
                for (int j = 0; j < k.count; ++j)
                    for (int s = 0; s < 4; ++s) {
                        const double tt = s / 4.0;
                        const rugo_vec2 p = rugo_contour_point(w, j, tt), n = rugo_contour_normal(w, j, tt);
                        const double lam = rugo_tolerance_at(tl.total, tl.count, j, tt, 0.0);
                        band.emplace_back(static_cast<float>(p.x + lam * n.x),
                                          static_cast<float>(p.y + lam * n.y));
                    }
                PolyLine(c, band, true, "#bbbbbb", "none");
            }
            continue;
        }
        for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
            std::vector<b2Vec2> v;
            if (f->GetType() == b2Shape::e_polygon) {
                const b2PolygonShape* p = static_cast<const b2PolygonShape*>(f->GetShape());
                for (int j = 0; j < p->m_count; ++j)
                    v.push_back(b2Mul(xf, p->m_vertices[j]));
                PolyLine(c, v, true, col, "none");
            } else if (f->GetType() == b2Shape::e_circle) {
                const b2CircleShape* p = static_cast<const b2CircleShape*>(f->GetShape());
                const b2Vec2 ctr = b2Mul(xf, p->m_p);
                for (int j = 0; j < 24; ++j) {
                    const float a = 6.2831853f * static_cast<float>(j) / 24.0f;
                    v.push_back(ctr + p->m_radius * b2Vec2(std::cos(a), std::sin(a)));
                }
                PolyLine(c, v, true, col, "none");
                std::vector<b2Vec2> spoke = {ctr, ctr + p->m_radius * b2Mul(xf.q, b2Vec2(1.0f, 0.0f))};
                PolyLine(c, spoke, false, col, "none");
            } else if (f->GetType() == b2Shape::e_chain) {
                const b2ChainShape* p = static_cast<const b2ChainShape*>(f->GetShape());
                for (int j = 0; j < p->m_count; ++j)
                    v.push_back(b2Mul(xf, p->m_vertices[j]));
                PolyLine(c, v, false, col, "none");
            }
        }
    }
    svg_text(&c, rugo_v2(r.sc->view_lo.x, r.sc->view_hi.y), title, 14.0);
    return svg_close(&c) == 0;
}

inline FILE* OpenOut(const std::string& dir, const char* name) {
    const std::string p = dir + "/" + name;
    FILE* f = std::fopen(p.c_str(), "w");
    if (!f) std::fprintf(stderr, "cannot write %s\n", p.c_str());
    return f;
}

// Least-squares slope of y(x).
inline double Slope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    if (n < 2) return NAN;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
    }
    const double dn = static_cast<double>(n), d = dn * sxx - sx * sx;
    return d != 0.0 ? (dn * sxy - sx * sy) / d : NAN;
}

// Runs a scene to its end, writing <prefix>.csv (every body every 6th step) and frames <prefix>_<step>.svg
// at the given steps; gathers what the chapter-7 samples check.
struct Record {
    std::vector<std::vector<b2Vec2>> pos;  // per step, per body: world centre
    std::vector<double> firstContact;      // per body: time of its first touching contact (NAN: none)
    std::vector<double> impactY, reboundY; // centre height at first contact; highest within 1 s after
    double e0 = 0, maxGrowth = 0, finalKinetic = 0, minY = 1e9;
    double muSum = 0;
    long muCount = 0;
    double MeanMu() const { return muCount ? muSum / static_cast<double>(muCount) : NAN; }
};
// after_step (optional) is called after every step, e.g. to gather more per-contact figures.
inline bool RunScene(Run& run, const std::string& dir, const std::string& prefix,
                     const std::vector<long>& frames, Record* rec,
                     const std::function<void(const Run&)>& after_step = nullptr) {
    const scene& s = *run.sc;
    const std::size_t nb = run.bodies.size();
    rec->firstContact.assign(nb, NAN);
    rec->impactY.assign(nb, NAN);
    rec->reboundY.assign(nb, NAN);
    FILE* f = OpenOut(dir, (prefix + ".csv").c_str());
    if (!f) return false;
    std::fprintf(f, "t,body,name,x,y,angle,vx,vy,w\n");
    const long n = run.entry->stepCount;
    rec->e0 = Energy(run);
    double ePrev = rec->e0;
    for (long k = 0; k <= n; ++k) {
        if (std::find(frames.begin(), frames.end(), k) != frames.end() || k == n) {
            char name[128], title[160];
            std::snprintf(name, sizeof name, "/%s_%04ld.svg", prefix.c_str(), k);
            std::snprintf(title, sizeof title, "%s %s (%s), t = %.2f s", s.figure, s.name, s.label, run.time);
            DrawFrame(run, dir + name, title);
        }
        std::vector<b2Vec2> p(nb);
        for (std::size_t i = 0; i < nb; ++i) {
            const b2Body* b = run.bodies[i];
            p[i] = b->GetWorldCenter();
            if (k % 6 == 0)
                std::fprintf(f, "%.4f,%zu,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", run.time, i, s.bodies[i].name,
                             p[i].x, p[i].y, b->GetAngle(), b->GetLinearVelocity().x,
                             b->GetLinearVelocity().y, b->GetAngularVelocity());
            if (b->GetType() != b2_dynamicBody) continue;
            rec->minY = std::min(rec->minY, static_cast<double>(p[i].y));
            if (std::isnan(rec->firstContact[i]))
                for (const b2ContactEdge* ce = b->GetContactList(); ce; ce = ce->next)
                    if (ce->contact->IsTouching() && ce->contact->IsEnabled()) {
                        rec->firstContact[i] = run.time;
                        rec->impactY[i] = rec->reboundY[i] = p[i].y;
                        break;
                    }
            if (!std::isnan(rec->firstContact[i]) && run.time <= rec->firstContact[i] + 1.0)
                rec->reboundY[i] = std::max(rec->reboundY[i], static_cast<double>(p[i].y));
        }
        rec->pos.push_back(p);
        if (k == n) break;
        run.Step();
        const ContactScan cs = ScanContacts(run);
        rec->muSum += cs.frictionSum;
        rec->muCount += cs.frictionCount;
        if (after_step) after_step(run);
        const double e = Energy(run);
        rec->maxGrowth = std::max(rec->maxGrowth, (e - ePrev) / std::fabs(rec->e0));
        ePrev = e;
    }
    for (const b2Body* b : run.bodies) {
        if (b->GetType() != b2_dynamicBody) continue;
        const double v = Speed(b), w = b->GetAngularVelocity();
        const b2Vec2 lc = b->GetLocalCenter();
        rec->finalKinetic += 0.5 * b->GetMass() * v * v +
                             0.5 * (b->GetInertia() - b->GetMass() * (lc.x * lc.x + lc.y * lc.y)) * w * w;
    }
    return std::fclose(f) == 0;
}

} // namespace b2s

#endif
