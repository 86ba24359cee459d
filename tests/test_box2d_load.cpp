// rugo::LoadShape and rugo::AttachShapeFile (rugo/box2d_load.hpp): a shape file to an attached rough
// body in one call, and the checks a game wants first (density, game scale), each naming the argument,
// its value and a way out.
#include <rugo/box2d_load.hpp>

#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <string>

static int failures = 0;

static void expect(bool ok, const char* what, const std::string& detail = "") {
    if (!ok) {
        std::fprintf(stderr, "FAIL %s %s\n", what, detail.c_str());
        ++failures;
    }
}

// An octagon of radius r (metres) with a constant band, as a JSON shape file.
static std::string write_octagon(const char* dir, const char* name, double r, double band) {
    const std::string path = std::string(dir) + "/" + name;
    FILE* f = std::fopen(path.c_str(), "w");
    const double h = 0.70710678118654757 * r;
    std::fprintf(f,
                 "{\"control_points\": [[%.17g, 0], [%.17g, %.17g], [0, %.17g], [%.17g, %.17g], [%.17g, 0], "
                 "[%.17g, %.17g], [0, %.17g], [%.17g, %.17g]], \"roughness\": {\"constant\": %.17g}}\n",
                 r, h, h, r, -h, h, -r, -h, -h, -r, h, -h, band);
    std::fclose(f);
    return path;
}

int main() {
    char dir[] = "/tmp/rugo_b2load_XXXXXX";
    if (mkdtemp(dir) == nullptr) return 1;
    const std::string pebble = write_octagon(dir, "pebble.json", 0.25, 0.002);
    const std::string huge = write_octagon(dir, "huge.json", 50000.0, 0.002);

    rugo_status st = RUGO_OK;
    std::string err;
    rugo::ShapePtr s = rugo::LoadShape(pebble.c_str(), &st, &err);
    expect(s != nullptr && st == RUGO_OK, "LoadShape of a JSON file", err);
    rugo::ShapePtr none = rugo::LoadShape((std::string(dir) + "/missing.json").c_str(), &st, &err);
    expect(none == nullptr && st == RUGO_ERR_IO, "LoadShape of a missing file", err);

    b2World world(b2Vec2(0.0f, -9.8f));
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    b2PolygonShape box;
    box.SetAsBox(5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f);
    ground->CreateFixture(&box, 0.0f);
    {
        rugo::Bridge bridge(&world);
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(0.0f, 1.0f);
        b2Body* body = world.CreateBody(&bd);
        rugo::RoughBodyDef def;
        rugo::ShapePtr shape;

        def.density = 0.0; // the argument is named, with its value and a way out
        st = rugo::AttachShapeFile(bridge, body, pebble.c_str(), def, &shape, &err);
        expect(st == RUGO_ERR_BAD_ARGUMENT && shape == nullptr, "density 0 refused");
        expect(err.find("density: is 0") != std::string::npos &&
                   err.find("RoughBodyDef::density") != std::string::npos,
               "density message", err);

        def.density = 2.0; // a 100 km body: refused with its size and the fix
        st = rugo::AttachShapeFile(bridge, body, huge.c_str(), def, &shape, &err);
        expect(st == RUGO_ERR_BAD_SIZE && shape == nullptr, "100 km body refused");
        expect(err.find("size: ") == 0 && err.find("127614 m across") != std::string::npos &&
                   err.find("max_size 1000 m") != std::string::npos &&
                   err.find("--px-per-metre") != std::string::npos,
               "size message", err);

        st = rugo::AttachShapeFile(bridge, body, pebble.c_str(), def, &shape, &err);
        expect(st == RUGO_OK && shape != nullptr, "AttachShapeFile", err);
        expect(bridge.IsRough(body), "the body is rough");
        for (int i = 0; i < 180; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        const b2Vec2 p = body->GetPosition();
        // An octagon's B-spline of radius 0.25 rests with its centre between its inner and outer radius.
        expect(p.y > 0.15f && p.y < 0.26f, "rests on the ground", std::to_string(p.y));
        st = rugo::AttachShapeFile(bridge, nullptr, pebble.c_str(), def, &shape, &err);
        expect(st == RUGO_ERR_NULL_ARGUMENT, "null body");
    }
    std::remove(pebble.c_str());
    std::remove(huge.c_str());
    rmdir(dir);
    std::printf("test_box2d_load: %d failures\n", failures);
    return failures == 0 ? 0 : 1;
}
