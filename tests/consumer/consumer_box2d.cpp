// Uses the installed Box2D bridge (rugo::box2d or pkg-config rugo-box2d): an ordinary b2World with a
// static ground box, one rough body attached through rugo::Bridge, dropped from 1 m. After 3 s it must
// rest on the ground: centre above the ground by about its lowest radius, hardly moving, its curve
// resting on the box's skin through its band. Also checks the version macros against the package's version
// (RUGO_EXPECTED_VERSION). Exit code 0 on success.
#include <rugo/box2d.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

#ifndef RUGO_EXPECTED_VERSION
#error "build with -DRUGO_EXPECTED_VERSION=\"x.y.z\" (the installed package's version)"
#endif

int main() {
    if (std::strcmp(RUGO_VERSION_STRING, RUGO_EXPECTED_VERSION) != 0 ||
        std::strcmp(rugo_version_string(), RUGO_EXPECTED_VERSION) != 0) {
        std::fprintf(stderr, "version mismatch: headers %s, library %s, package %s\n", RUGO_VERSION_STRING,
                     rugo_version_string(), RUGO_EXPECTED_VERSION);
        return 1;
    }
    // A slightly lumpy disc of radius 0.25 m, 32 control points, a 2 mm roughness band.
    enum { N = 32 };
    rugo_vec2 points[N];
    double tolerances[N];
    for (int k = 0; k < N; ++k) {
        const double a = 6.283185307179586 * k / N;
        points[k] = rugo_v2(0.25 * std::cos(a) * (1.0 + 0.05 * std::sin(3 * a)), 0.25 * std::sin(a));
        tolerances[k] = 0.002;
    }
    rugo_shape_def def = rugo_default_shape_def();
    def.points = points;
    def.count = N;
    def.tolerances = tolerances;
    rugo_shape* shape = nullptr;
    rugo_status st = rugo_shape_create(&def, &shape, nullptr);
    if (st != RUGO_OK) {
        std::fprintf(stderr, "rugo_shape_create: %s\n", rugo_status_string(st));
        return 1;
    }

    b2World world(b2Vec2(0.0f, -9.8f));
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2PolygonShape box;
    box.SetAsBox(5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f); // top face at y = 0
    ground->CreateFixture(&box, 0.0f);

    int ok = 1;
    {
        rugo::Bridge bridge(&world);
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(0.0f, 1.0f);
        b2Body* body = world.CreateBody(&bd);
        rugo::RoughBodyDef rough;
        rough.shape = shape;
        rough.density = 2.0;
        st = bridge.Attach(body, rough);
        if (st != RUGO_OK) {
            std::fprintf(stderr, "Attach: %s\n", rugo_status_string(st));
            ok = 0;
        }
        for (int i = 0; i < 180 && ok; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);

        // Lowest point of the body's curve in world coordinates (dense samples of the finest level).
        rugo_contour curve;
        rugo_shape_level(shape, rugo_shape_finest_level(shape), &curve);
        const b2Transform& xf = body->GetTransform();
        double lowest = 1e300;
        for (int j = 0; j < curve.count; ++j)
            for (int s = 0; s < 16; ++s) {
                const rugo_vec2 p = rugo_contour_point(curve, j, s / 16.0);
                lowest = std::fmin(lowest, xf.p.y + xf.q.s * p.x + xf.q.c * p.y);
            }
        const double y = body->GetPosition().y, speed = body->GetLinearVelocity().Length();
        std::printf("consumer_box2d: y = %.4f m, lowest curve point %.5f m, speed %.2e m/s, mass %.4f kg, "
                    "rough %d, librugo %s\n",
                    y, lowest, speed, body->GetMass(), bridge.IsRough(body), rugo_version_string());
        // Resting on the ground: the curve above y = 0 by the box's skin (b2_polygonRadius, 1 cm) plus the
        // 2 mm band, within Box2D's linear slop (5 mm); nearly still. Measured: 1.10 cm, 3e-15 m/s.
        ok &= bridge.IsRough(body) && y > 0.15 && y < 0.35 && lowest > 0.012 - 0.005 &&
              lowest < 0.012 + 0.005 && speed < 0.05;
    }
    rugo_shape_destroy(shape);
    if (!ok) std::fprintf(stderr, "consumer_box2d: the rough body does not rest on the ground\n");
    return ok ? 0 : 1;
}
