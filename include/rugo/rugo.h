/** @file rugo/rugo.h
 * librugo — rough curved 2-D shapes. Include this for the whole C API: every C header of librugo
 * except rugo/fit.h, which belongs to the optional Eigen shim (CMake target rugo::fit) and is
 * included on its own. The Box2D bridge's C++ header is rugo/box2d.hpp. */
#ifndef RUGO_RUGO_H
#define RUGO_RUGO_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/wavelet.h"
#include "rugo/multires.h"
#include "rugo/random.h"
#include "rugo/rough.h"
#include "rugo/tolerance.h"
#include "rugo/mobb.h"
#include "rugo/shape.h"
#include "rugo/collide.h"
#include "rugo/shape_file.h"
#include "rugo/baked.h"
#include "rugo/world.h"
#include "rugo/import.h"

#endif
