// The minimal program of docs/box2d.md: a rough pebble dropped on an ordinary Box2D ground box.
#include <rugo/box2d.hpp>

#include <cmath>
#include <cstdio>

int main() {
    // 1. A rough shape: 32 control points on a circle of radius 0.25 m, a 2 mm roughness band.
    rugo_vec2 points[32];
    double tolerances[32];
    for (int k = 0; k < 32; ++k) {
        const double a = 2.0 * 3.14159265358979 * k / 32;
        points[k] = rugo_v2(0.25 * std::cos(a) * (1.0 + 0.1 * std::sin(3 * a)), 0.25 * std::sin(a));
        tolerances[k] = 0.002;
    }
    rugo_shape_def def = rugo_default_shape_def();
    def.points = points;
    def.count = 32;
    def.tolerances = tolerances;
    rugo_shape* shape = nullptr;
    if (rugo_shape_create(&def, &shape, nullptr) != RUGO_OK) return 1;

    // 2. An ordinary Box2D world with a static ground box.
    b2World world(b2Vec2(0.0f, -9.8f));
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2PolygonShape box;
    box.SetAsBox(5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f);
    ground->CreateFixture(&box, 0.0f);

    // 3. The bridge (after any listener/filter you set on the world), then a rough body.
    int status = 0;
    {
        rugo::Bridge bridge(&world);
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(0.0f, 1.0f);
        b2Body* pebble = world.CreateBody(&bd);
        rugo::RoughBodyDef rough;
        rough.shape = shape;
        rough.density = 2.0; // kg/m^2
        if (bridge.Attach(pebble, rough) != RUGO_OK) status = 1;

        // 4. Step through the bridge (it repairs mass resets and re-chains replaced listeners).
        for (int i = 0; i < 180; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        const b2Vec2 p = pebble->GetPosition();
        std::printf("pebble at (%.3f, %.3f), mass %.4f kg, awake %d\n", p.x, p.y, pebble->GetMass(),
                    pebble->IsAwake());
        // It rests on the ground: its centre a little above its lowest radius (0.25 m).
        if (!(p.y > 0.15f && p.y < 0.35f)) status = 1;
    } // 5. The bridge goes before the world and the shape after both.
    rugo_shape_destroy(shape);
    return status;
}
