#pragma once
// The OpenColorIO processors of the colour data held by the document (a
// LUT, color_lut.h; a config's view transform, ocio_config.h): what the
// renderer builds its GPU shaders from and what the tests apply on the CPU
// to check them. Separate from color_lut.h so that only the code that
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

// A stored config as OpenColorIO reads it from its bundle (written to the
// cache folder), its search paths pointed at the bundle's copies. Null
// with `error` (naming the config) when it cannot be read.
OCIO_NAMESPACE::ConstConfigRcPtr ocioConfigOf(const OcioConfigData& config, std::string& error);

// The processor from the renderer's linear Rec.709 light to `display`'s
// `view` (empty: the config's defaults) of a stored config: through
// ACES2065-1 into its 'aces_interchange' colour space where it has one,
// else as its 'scene_linear' role. Null with `error` naming the config and
// the display or view at fault.
OCIO_NAMESPACE::ConstProcessorRcPtr viewTransformProcessor(const OcioConfigData& config, const std::string& display,
                                                           const std::string& view, std::string& error);

}  // namespace hs::scene
