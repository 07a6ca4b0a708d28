#pragma once
// A CPU image for layouts, anaglyphs and writers: RGBA, top row first,
// either 8-bit sRGB display pixels or linear float (HDR, for EXR). The same
// shape as render::Image, which phase 2 moves its vectors into.
#include <cstdint>
#include <vector>

#include "sequencer/image_writer.h"

namespace hs::sequencer {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba8;  // sRGB, 4 bytes a pixel
  std::vector<float> rgbaF;    // linear, 4 floats a pixel

  static Image make8(int w, int h) { return Image{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4, 0), {}}; }
  static Image makeF(int w, int h) { return Image{w, h, {}, std::vector<float>(size_t(w) * size_t(h) * 4, 0.0f)}; }
  bool isFloat() const { return !rgbaF.empty(); }
  bool empty() const { return width <= 0 || height <= 0 || (rgba8.empty() && rgbaF.empty()); }
  size_t pixelCount() const { return size_t(width) * size_t(height); }
  ImageView view() const {
    return ImageView{width, height, rgba8.empty() ? nullptr : rgba8.data(), rgbaF.empty() ? nullptr : rgbaF.data()};
  }
  bool operator==(const Image&) const = default;
};

}  // namespace hs::sequencer
