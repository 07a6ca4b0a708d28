#pragma once
// A CPU image, RGBA, top row first: either 8-bit sRGB display pixels or
// linear float (HDR, for EXR). What the renderer reads back, the stereo
// layouts and anaglyphs compose, and the image writers encode.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hs {

// Pixels someone else owns, in the same layout as Image.
struct ImageView {
  int width = 0;
  int height = 0;
  const uint8_t* rgba8 = nullptr;  // sRGB display pixels, top row first, or
  const float* rgbaF = nullptr;    // linear HDR pixels, top row first
};

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

// Copies `rows` rows of `rowBytes` bytes from `src` to `dst` in reverse row
// order: OpenGL reads images bottom row first, everything else here keeps
// the top row first. In place when src == dst.
void copyRowsFlipped(const void* src, void* dst, size_t rowBytes, size_t rows);
inline void flipRows(void* data, size_t rowBytes, size_t rows) { copyRowsFlipped(data, data, rowBytes, rows); }

}  // namespace hs
