// rugo::LoadShape and rugo::AttachShapeFile (rugo/box2d_load.hpp): the C loader and Bridge::Attach
// behind one call each, with the checks a game wants before a body enters its world. Uses the bridge's
// public API only.
#include "rugo/box2d_load.hpp"

#include <cmath>
#include <cstdio>

namespace rugo {

namespace {

void set_error(std::string* error, const char* field, const char* message) {
    if (error == nullptr) return;
    *error = field[0] != '\0' ? std::string(field) + ": " + message : std::string(message);
}

} // namespace

ShapePtr LoadShape(const char* path, rugo_status* status, std::string* error) {
    rugo_shape* raw = nullptr;
    rugo_parse_error pe;
    const rugo_status st = rugo_shape_load_file(path, nullptr, &raw, &pe);
    if (status != nullptr) *status = st;
    if (st != RUGO_OK) {
        char where[48] = "";
        if (pe.line > 0) std::snprintf(where, sizeof where, "line %d, column %d: ", pe.line, pe.column);
        set_error(error, pe.path,
                  (std::string(where) + (pe.message[0] ? pe.message : rugo_status_string(st))).c_str());
        return ShapePtr();
    }
    return ShapePtr(raw);
}

rugo_status AttachShapeFile(Bridge& bridge, b2Body* body, const char* path, RoughBodyDef def, ShapePtr* shape,
                            std::string* error, double max_size) {
    if (body == nullptr || path == nullptr || shape == nullptr) {
        set_error(error, "", "body, path and shape must not be null");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    char msg[200];
    if (body->GetType() == b2_dynamicBody && !(std::isfinite(def.density) && def.density > 0.0)) {
        std::snprintf(msg, sizeof msg,
                      "is %.17g; a dynamic body needs a density > 0 in kg/m^2 (e.g. 2500 for rock, 1 for a "
                      "toy): set RoughBodyDef::density",
                      def.density);
        set_error(error, "density", msg);
        return RUGO_ERR_BAD_ARGUMENT;
    }
    rugo_status st = RUGO_OK;
    ShapePtr loaded = LoadShape(path, &st, error);
    if (!loaded) return st;
    rugo_contour c;
    rugo_shape_level(loaded.get(), rugo_shape_finest_level(loaded.get()), &c);
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    const double size = std::hypot(hi.x - lo.x, hi.y - lo.y);
    if (!(size <= max_size)) {
        std::snprintf(msg, sizeof msg,
                      "the shape in %s is %.6g m across, more than max_size %.6g m: import the drawing with "
                      "rugo import --px-per-metre (or pass a larger max_size)",
                      path, size, max_size);
        set_error(error, "size", msg);
        return RUGO_ERR_BAD_SIZE;
    }
    def.shape = loaded.get();
    st = bridge.Attach(body, def);
    if (st != RUGO_OK) {
        std::snprintf(msg, sizeof msg, "Bridge::Attach failed: %s", rugo_status_string(st));
        set_error(error, "", msg);
        return st;
    }
    *shape = std::move(loaded);
    return RUGO_OK;
}

} // namespace rugo
