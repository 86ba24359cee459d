// The Box2D scenes benchmark's scene (pile_scene.hpp): its shapes, their polygon compounds, the
// container and the bodies of each variant.
#include "pile_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace pile {

const char* const kVariantName[kVariants] = {"bridge_auto", "bridge_finest", "polygon", "circle"};

namespace {

// A star-shaped rock: r(θ) = R (1 + Σ_{k=2..6} a_k sin(kθ + φ_k) + 0.012 sin(13θ + φ)), x stretched by
// `aspect`; seeded amplitudes. The k = 13 ripple (3 mm on R = 0.25 m) is of the size of the error
// budget, so the level of detail has something to decide.
void RockOutline(std::uint64_t seed, double aspect, int n, rugo_vec2* out) {
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    double amp[7], ph[7];
    for (int k = 2; k <= 6; ++k) {
        amp[k] = rugo_rng_range(&rng, 0.02, 0.10) / static_cast<double>(k - 1);
        ph[k] = rugo_rng_range(&rng, 0.0, 6.283185307179586);
    }
    const double ripple = rugo_rng_range(&rng, 0.0, 6.283185307179586);
    for (int i = 0; i < n; ++i) {
        const double th = 6.283185307179586 * i / n;
        double r = 1.0 + 0.012 * std::sin(13.0 * th + ripple);
        for (int k = 2; k <= 6; ++k)
            r += amp[k] * std::sin(k * th + ph[k]);
        out[i] = rugo_v2(aspect * kRadius * r * std::cos(th), kRadius * r * std::sin(th));
    }
}

double PointSegmentDistance(rugo_vec2 p, rugo_vec2 a, rugo_vec2 b) {
    const rugo_vec2 d = rugo_v2_sub(b, a), w = rugo_v2_sub(p, a);
    const double l2 = rugo_v2_dot(d, d);
    double t = l2 > 0.0 ? rugo_v2_dot(w, d) / l2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    return std::hypot(w.x - t * d.x, w.y - t * d.y);
}

inline double Cross(rugo_vec2 o, rugo_vec2 a, rugo_vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

} // namespace

// The polygon variant: vertices on the finest curve, each chord as long as the curve between its ends
// stays within eps of it (greedy over kSamplesPerSegment samples per segment), then a fan from the
// centroid merged greedily into convex pieces of at most b2_maxPolygonVertices vertices. The outlines
// are star-shaped about their centroid (checked), so the fan is a valid decomposition.
bool FitPolygon(const rugo_shape* s, rugo_vec2 apex, double eps, std::vector<Piece>* pieces, int* nverts,
                double* dev) {
    rugo_contour c;
    if (rugo_shape_level(s, rugo_shape_finest_level(s), &c) != RUGO_OK) return false;
    const int m = c.count * kSamplesPerSegment;
    std::vector<rugo_vec2> p(static_cast<size_t>(m));
    for (int i = 0; i < m; ++i)
        p[static_cast<size_t>(i)] = rugo_contour_point(
            c, i / kSamplesPerSegment, static_cast<double>(i % kSamplesPerSegment) / kSamplesPerSegment);
    std::vector<int> idx; // polygon vertices as sample indices
    int i = 0;
    while (i < m) {
        idx.push_back(i);
        int j = i + 1;
        // extend the chord i -> j+1 while every sample between stays within eps
        while (j + 1 <= m) {
            const rugo_vec2 b = p[static_cast<size_t>((j + 1) % m)];
            bool ok = true;
            for (int k = i + 1; k <= j && ok; ++k)
                ok = PointSegmentDistance(p[static_cast<size_t>(k)], p[static_cast<size_t>(i)], b) <= eps;
            if (!ok) break;
            ++j;
        }
        i = j;
    }
    const int n = static_cast<int>(idx.size());
    if (n < 3) return false;
    // Dense check of the deviation (4x the fitting samples) and of star-shapedness about the apex.
    double worst = 0.0;
    for (int e = 0; e < n; ++e) {
        const int i0 = idx[static_cast<size_t>(e)], i1 = e + 1 < n ? idx[static_cast<size_t>(e + 1)] : m;
        const rugo_vec2 a = p[static_cast<size_t>(i0)], b = p[static_cast<size_t>(i1 % m)];
        for (int k = 4 * i0; k <= 4 * i1; ++k) {
            const int kk = k % (4 * m);
            const rugo_vec2 q = rugo_contour_point(c, kk / (4 * kSamplesPerSegment),
                                                   static_cast<double>(kk % (4 * kSamplesPerSegment)) /
                                                       (4 * kSamplesPerSegment));
            worst = std::max(worst, PointSegmentDistance(q, a, b));
        }
        if (Cross(apex, a, b) <= 1e-9) return false; // not star-shaped about the apex
    }
    *dev = worst;
    *nverts = n;
    std::vector<rugo_vec2> v(static_cast<size_t>(n));
    for (int e = 0; e < n; ++e)
        v[static_cast<size_t>(e)] = p[static_cast<size_t>(idx[static_cast<size_t>(e)])];
    // Fan pieces: apex, v[a], v[a+1], ..., v[b] while convex and at most 8 vertices.
    pieces->clear();
    int a = 0;
    while (a < n) {
        int b = a + 1; // the piece (apex, v[a], v[b]) is a triangle, convex by star-shapedness
        while (b - a + 3 <= b2_maxPolygonVertices && b < n) {
            const rugo_vec2 nb = v[static_cast<size_t>((b + 1) % n)];
            // convex if v[b-1] -> v[b] -> nb turns left, v[b] -> nb -> apex turns left and
            // nb -> apex -> v[a] turns left
            if (Cross(v[static_cast<size_t>(b - 1)], v[static_cast<size_t>(b)], nb) <= 1e-12 ||
                Cross(v[static_cast<size_t>(b)], nb, apex) <= 1e-12 ||
                Cross(nb, apex, v[static_cast<size_t>(a)]) <= 1e-12)
                break;
            ++b;
        }
        Piece pc;
        pc.v.emplace_back(static_cast<float>(apex.x), static_cast<float>(apex.y));
        for (int k = a; k <= b; ++k) {
            const rugo_vec2 q = v[static_cast<size_t>(k % n)];
            pc.v.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
        }
        pieces->push_back(pc);
        a = b;
    }
    return true;
}

bool BuildShapes(int segments, ShapeSet* set) {
    set->segments = segments;
    static const rugo_tolerance_preset presets[kShapes] = {RUGO_PRESET_TIPO_2, RUGO_PRESET_TIPO_3,
                                                           RUGO_PRESET_TIPO_5, RUGO_PRESET_TIPO_1};
    static const double aspects[kShapes] = {1.0, 1.3, 1.15, 1.45};
    std::vector<rugo_vec2> pts(static_cast<size_t>(segments));
    std::vector<double> lam(static_cast<size_t>(segments));
    for (int k = 0; k < kShapes; ++k) {
        RockOutline(700 + static_cast<std::uint64_t>(k), aspects[k], segments, pts.data());
        if (rugo_tolerances_preset(presets[k], 710 + static_cast<std::uint64_t>(k), segments, lam.data()) !=
            RUGO_OK)
            return false;
        for (double& l : lam)
            l *= SCENE_ROUGHNESS_SCALE;
        rugo_shape_def d = rugo_default_shape_def();
        d.points = pts.data();
        d.count = segments;
        d.tolerances = lam.data();
        d.friction = scene_friction_map();
        rugo_shape* sh = nullptr;
        const rugo_status st = rugo_shape_create(&d, &sh, nullptr);
        if (st != RUGO_OK) {
            std::fprintf(stderr, "rock_pile: shape %d (S = %d): %s\n", k, segments, rugo_status_string(st));
            return false;
        }
        set->shapes.push_back(sh);
        const rugo_mass_properties mp = rugo_shape_mass(sh);
        set->centroid.push_back(mp.centroid);
        set->mass.push_back(mp.area * kDensity);
        rugo_contour c;
        rugo_shape_level(sh, rugo_shape_finest_level(sh), &c);
        double rb = 0.0;
        for (int i = 0; i < c.count; ++i)
            for (int t = 0; t < 16; ++t) {
                const rugo_vec2 q = rugo_contour_point(c, i, t / 16.0);
                rb = std::max(rb, std::hypot(q.x - mp.centroid.x, q.y - mp.centroid.y));
            }
        set->boundRadius.push_back(rb);
        std::vector<Piece> pcs;
        int nv = 0;
        double dev = 0.0;
        if (!FitPolygon(sh, mp.centroid, kBudget, &pcs, &nv, &dev)) {
            std::fprintf(stderr, "rock_pile: shape %d (S = %d) is not star-shaped about its centroid\n", k,
                         segments);
            return false;
        }
        set->pieces.push_back(pcs);
        set->polyVertices.push_back(nv);
        set->polyDeviation.push_back(dev);
    }
    return true;
}

Layout MakeLayout(int n, const ShapeSet& set) {
    Layout L;
    double rb = 0.0;
    for (double r : set.boundRadius)
        rb = std::max(rb, r);
    L.cols = std::max(4, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
    L.rows = (n + L.cols - 1) / L.cols;
    L.spacing = 2.0 * rb + 0.1;
    L.halfWidth = 0.5 * L.cols * L.spacing + 0.3;
    L.wallHeight = L.rows * L.spacing + 2.0;
    return L;
}

int ShapeOf(int i, const Layout& layout) { return (i * 7 + i / layout.cols) % kShapes; }

bool Create(const scene_table::Args& args, scene_table::World* world) {
    if (args.variant < 0 || args.variant >= kVariants || args.bodies < 1) {
        std::fprintf(stderr, "rock_pile: no variant %d with %d bodies\n", args.variant, args.bodies);
        return false;
    }
    std::shared_ptr<const ShapeSet> shared = args.pileShapes;
    if (!shared || shared->segments != args.segments) {
        auto built = std::make_shared<ShapeSet>();
        if (!BuildShapes(args.segments, built.get())) return false;
        shared = built;
    }
    world->pileShapes = shared;
    const ShapeSet& set = *shared;
    const Variant var = static_cast<Variant>(args.variant);
    const int n = args.bodies;
    const Layout L = MakeLayout(n, set);
    world->world = std::make_unique<b2World>(b2Vec2(0.0f, -9.8f));
    world->world->SetAllowSleeping(
        false); // every body stays awake: the cost of the contacts, not of sleeping
    world->world->SetContinuousPhysics(args.continuous);
    if (var == kAuto || var == kFinest) {
        rugo::BridgeDef bd;
        bd.errorBudget = kBudget;
        if (args.maxProxies > 0) bd.maxProxies = args.maxProxies;
        if (args.reuseDistance >= 0.0) bd.reuseDistance = args.reuseDistance;
        if (args.queryResolution >= 0.0) bd.queryResolution = args.queryResolution;
        world->bridge = std::make_unique<rugo::Bridge>(world->world.get(), bd);
    }
    // Container: floor and two walls (static boxes, two-sided).
    b2BodyDef gd;
    b2Body* ground = world->world->CreateBody(&gd);
    {
        const float hw = static_cast<float>(L.halfWidth), hh = static_cast<float>(0.5 * L.wallHeight);
        b2PolygonShape box;
        box.SetAsBox(hw + 0.5f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f);
        b2FixtureDef fd;
        fd.shape = &box;
        fd.friction = 0.6f;
        ground->CreateFixture(&fd);
        box.SetAsBox(0.5f, hh, b2Vec2(-hw - 0.5f, hh), 0.0f);
        ground->CreateFixture(&fd);
        box.SetAsBox(0.5f, hh, b2Vec2(hw + 0.5f, hh), 0.0f);
        ground->CreateFixture(&fd);
    }
    rugo_rng rng;
    rugo_rng_seed(&rng, 4242);
    for (int i = 0; i < n; ++i) {
        const int row = i / L.cols, col = i % L.cols;
        const int k = ShapeOf(i, L);
        const double x =
            -0.5 * (L.cols - 1) * L.spacing + col * L.spacing + rugo_rng_range(&rng, -0.05, 0.05);
        const double y = 0.5 * L.spacing + 0.05 + row * L.spacing;
        const double ang = rugo_rng_range(&rng, 0.0, 6.283185307179586);
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.angle = static_cast<float>(ang);
        // Body origin = the shape's frame; place the centroid at (x, y).
        const rugo_vec2 c = set.centroid[static_cast<size_t>(k)];
        const double ca = std::cos(ang), sa = std::sin(ang);
        bd.position.Set(static_cast<float>(x - (ca * c.x - sa * c.y)),
                        static_cast<float>(y - (sa * c.x + ca * c.y)));
        b2Body* b = world->world->CreateBody(&bd);
        if (var == kAuto || var == kFinest) {
            rugo::RoughBodyDef rd;
            rd.shape = set.shapes[static_cast<size_t>(k)];
            rd.density = kDensity;
            rd.lod = var == kAuto ? RUGO_LOD_AUTO : 0;
            if (world->bridge->Attach(b, rd) != RUGO_OK) return false;
        } else if (var == kPolygon) {
            for (const Piece& pc : set.pieces[static_cast<size_t>(k)]) {
                b2PolygonShape ps;
                ps.Set(pc.v.data(), static_cast<int32>(pc.v.size()));
                b2FixtureDef fd;
                fd.shape = &ps;
                fd.density = static_cast<float>(kDensity);
                fd.friction = 0.5f;
                b->CreateFixture(&fd);
            }
        } else {
            b2CircleShape cs;
            cs.m_p.Set(static_cast<float>(c.x), static_cast<float>(c.y));
            cs.m_radius = static_cast<float>(set.boundRadius[static_cast<size_t>(k)]);
            b2FixtureDef fd;
            fd.shape = &cs;
            // the rough body's mass in the larger circle
            fd.density =
                static_cast<float>(set.mass[static_cast<size_t>(k)] / (b2_pi * cs.m_radius * cs.m_radius));
            fd.friction = 0.5f;
            b->CreateFixture(&fd);
        }
        world->bodies.push_back(b);
    }
    return true;
}

void Step(scene_table::World* world) {
    if (world->bridge)
        world->bridge->Step(kDt, kVelIt, kPosIt);
    else
        world->world->Step(kDt, kVelIt, kPosIt);
    world->time += kDt;
    ++world->steps;
}

} // namespace pile
