// The Box2D scenes benchmark's scene, "rock_pile" in the scene table (docs/benchmarks.md, "Box2D
// scenes"): a static container of three boxes and N rough bodies dropped in a grid (seeded x jitter and
// angles), falling and settling at 60 Hz with 8/3 iterations, sleeping off so that every step pays for
// every contact. The bodies share kShapes star-shaped rocks of S control points. The same scene is built
// four ways (Variant): through the bridge at its automatic level or at the finest, as Box2D polygon
// compounds of the same geometric error, or as native circles.
#ifndef RUGO_SAMPLES_PILE_SCENE_HPP
#define RUGO_SAMPLES_PILE_SCENE_HPP

#include "scene_table.hpp"

#include <cstdint>
#include <vector>

namespace pile {

constexpr float kDt = 1.0f / 60.0f;
constexpr int kVelIt = 8, kPosIt = 3;
constexpr int kShapes = 4;             // distinct shapes shared by the bodies
constexpr double kRadius = 0.25;       // mean radius of the outlines (m)
constexpr double kBudget = 0.005;      // BridgeDef::errorBudget, and the polygons' chord deviation (m)
constexpr double kDensity = 1.0;       // kg/m^2
constexpr int kSamplesPerSegment = 32; // finest-curve samples per segment for the polygon fit

// The scene's variants (scene_table::Args::variant).
enum Variant { kAuto = 0, kFinest = 1, kPolygon = 2, kCircle = 3, kVariants = 4 };
extern const char* const kVariantName[kVariants]; // as the benchmark's CSV names them

struct Piece {
    std::vector<b2Vec2> v; // convex, counter-clockwise, 3..8 vertices
};

// The kShapes shapes of S segments every variant is built from, with what the variants need of them.
struct ShapeSet {
    int segments = 0;
    std::vector<rugo_shape*> shapes;
    std::vector<double> boundRadius; // max distance of the finest curve from the centroid (m)
    std::vector<rugo_vec2> centroid;
    std::vector<double> mass;               // kg, at kDensity
    std::vector<std::vector<Piece>> pieces; // polygon variant
    std::vector<int> polyVertices;          // vertices of the fitted polygon
    std::vector<double> polyDeviation;      // largest distance of the finest curve from its chords (m)
    ShapeSet() = default;
    ShapeSet(const ShapeSet&) = delete;
    ShapeSet& operator=(const ShapeSet&) = delete;
    ~ShapeSet() {
        for (rugo_shape* s : shapes)
            rugo_shape_destroy(s);
    }
};

// The finest curve of s as a polygon whose chords deviate from it by at most eps (checked 4x denser
// than fitted; *dev the largest deviation found, *nverts its vertices), cut into convex pieces of at
// most b2_maxPolygonVertices vertices (a fan from apex). false if the polygon is not star-shaped about
// apex.
bool FitPolygon(const rugo_shape* s, rugo_vec2 apex, double eps, std::vector<Piece>* pieces, int* nverts,
                double* dev);

// Builds the shapes of `segments` control points; false with a message if one fails.
bool BuildShapes(int segments, ShapeSet* set);

// Where N bodies go: a grid of cols x rows cells of `spacing`, in a container of that half-width.
struct Layout {
    int cols = 0, rows = 0;
    double spacing = 0.0, halfWidth = 0.0, wallHeight = 0.0;
};
Layout MakeLayout(int n, const ShapeSet& set);
// Which of the kShapes shapes body i is.
int ShapeOf(int i, const Layout& layout);

// The scene table's create and step for the pile: args.bodies bodies of args.segments control points
// (args.pileShapes when built before for that count), variant args.variant. The container is not one of
// world->bodies. false if the bridge refuses a body.
bool Create(const scene_table::Args& args, scene_table::World* world);
void Step(scene_table::World* world);

} // namespace pile

#endif
