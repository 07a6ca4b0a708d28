#pragma once
// The OpenColorIO processor of a LUT held by the document (color_lut.h):
// what the renderer builds its GPU shader from and what the tests apply on
// the CPU to check it. Separate from color_lut.h so that only the code that
// applies a LUT includes OpenColorIO's headers.
#include <string>

#include <OpenColorIO/OpenColorIO.h>

#include "scene/scene_state.h"

namespace hs::scene {

// The forward processor of `lut` with its best interpolation (tetrahedral
// for 3D tables, linear for 1D), built from the raw configuration (no
// colour space conversion: the table is applied to the values as they
// are). Null with `error` (naming the LUT's file name) when OpenColorIO
// cannot read it.
OCIO_NAMESPACE::ConstProcessorRcPtr lutProcessor(const LutData& lut, std::string& error);

}  // namespace hs::scene
