#pragma once
// A CPU image read back from the renderer: top row first.
#include <cstdint>
#include <vector>

namespace hs::render {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 4;
  // Exactly one of these holds the pixels.
  std::vector<uint8_t> rgba8;   // sRGB-encoded display image
  std::vector<float> rgbaF;     // linear HDR (for EXR)
  bool isFloat() const { return !rgbaF.empty(); }
};

}  // namespace hs::render
