#pragma once
// How the two eyes become output frames: side by side (full or squeezed),
// top and bottom (full or squeezed), separate left/right files, an
// anaglyph, or one mono view. CPU functions; the export loop runs them on
// its writer threads.
#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "sequencer/anaglyph.h"

namespace hs::sequencer {

enum class StereoLayout : uint8_t {
  SideBySide,          // "sbs":      left | right, 2W x H (3840x1080 for 1920x1080 eyes)
  SideBySideSqueezed,  // "sbs-half": left | right each squeezed to half width, W x H
  TopBottom,           // "tb":       left over right, W x 2H
  TopBottomSqueezed,   // "tb-half":  left over right each squeezed to half height, W x H
  Separate,            // "separate": two files a frame, W x H each (names: output_pattern.h)
  Anaglyph,            // "anaglyph": red/cyan, W x H
  Mono                 // "mono":     the mono camera only, W x H
};

const char* layoutName(StereoLayout l);
std::optional<StereoLayout> layoutFromName(std::string_view s);  // also "sbs-full", "side-by-side", ...

// Mono renders one view (the rig's mono camera); every other layout two.
bool layoutRendersBothEyes(StereoLayout l);
// Size of each output image for eyes of eyeWidth x eyeHeight.
glm::ivec2 layoutFrameSize(StereoLayout l, int eyeWidth, int eyeHeight);
// Output images per frame: 2 for Separate, 1 otherwise.
int layoutFilesPerFrame(StereoLayout l);

// The output image(s) of one frame. `right` is ignored for Mono. Squeezing
// averages pixels in linear light (an area filter), so a squeezed frame
// keeps the brightness of fine detail; for odd sizes the left eye gets the
// smaller half. Empty result if the eyes differ in size or pixel kind.
std::vector<Image> composeLayout(StereoLayout layout, const Image& left, const Image& right,
                                 AnaglyphMethod anaglyph = AnaglyphMethod::Dubois);

// Area-filter resampling of one axis (linear light), used by the squeezed layouts.
Image resampleWidth(const Image& in, int width);
Image resampleHeight(const Image& in, int height);

}  // namespace hs::sequencer
