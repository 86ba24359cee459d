/// @file rugo/box2d_load.hpp
/// librugo — loading a shape file straight into a Box2D body: rugo::LoadShape (a shape file, JSON or
/// baked, to an owned shape) and rugo::AttachShapeFile (that, checked for game scale, attached to a
/// b2Body through rugo::Bridge). Built on the bridge's public API only (rugo/box2d.hpp).
#ifndef RUGO_BOX2D_LOAD_HPP
#define RUGO_BOX2D_LOAD_HPP

#include "rugo/box2d.hpp"
#include "rugo/shape_file.h"

#include <memory>
#include <string>

namespace rugo {

/// Destroys a rugo_shape (for std::unique_ptr).
struct ShapeDeleter {
    /// Destroys the shape (NULL is fine).
    void operator()(rugo_shape* shape) const { rugo_shape_destroy(shape); }
};
/// An owned shape.
using ShapePtr = std::unique_ptr<rugo_shape, ShapeDeleter>;

/// Largest rough body AttachShapeFile accepts by default: 1000 m across (the diagonal of its bounds).
/// Box2D is tuned for moving bodies of 0.1 to 10 m; a body far beyond is almost always a drawing
/// imported without a scale (pixels taken for metres).
constexpr double kDefaultMaxBodySize = 1000.0;

/// rugo_shape_load_file (rugo/shape_file.h) into an owned shape: nullptr on error, with the status in
/// *status and "FIELD: message" in *error (either may be nullptr).
RUGO_API ShapePtr LoadShape(const char* path, rugo_status* status = nullptr, std::string* error = nullptr);

/// One call from an asset to a rough body: loads `path` (JSON or baked) into *shape (which must then
/// outlive the attachment: keep it next to the body), checks it for game scale, and attaches it to
/// `body` with `def` (def.shape is ignored: the loaded shape is used).
/// Errors (*shape empty, the body untouched; *error, if given, names the argument, its value and a way
/// out): NULL_ARGUMENT (body, path or shape), BAD_ARGUMENT (def.density not finite and > 0 for a
/// dynamic body), BAD_SIZE (the shape larger than max_size metres: import it with a px-per-metre),
/// those of LoadShape, and those of Bridge::Attach.
RUGO_API rugo_status AttachShapeFile(Bridge& bridge, b2Body* body, const char* path, RoughBodyDef def,
                                     ShapePtr* shape, std::string* error = nullptr,
                                     double max_size = kDefaultMaxBodySize);

} // namespace rugo

#endif
