#pragma once
// A deterministic stand-in for the renderer (the sequencer's tests run without GL):
// each eye's pixels are a pure function of (frame, eye, x, y), like a real
// render of a pure sequence, so runs can be compared byte for byte.
#include <cstdint>
#include <string>

#include "sequencer/export_loop.h"

namespace hs::test {

inline void syntheticEye(const sequencer::FrameJob& job, int eye, hs::Image& out) {
  const int w = job.eyeWidth, h = job.eyeHeight;
  out = job.floatPixels ? hs::Image::makeF(w, h) : hs::Image::make8(w, h);
  const int64_t f = job.frame;
  const int bar = int((f * 7 + eye * 3) % w);  // a bar that moves with the frame, offset per eye
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 4;
      uint8_t r = uint8_t((x * 255) / std::max(1, w - 1));
      uint8_t g = uint8_t((y * 255) / std::max(1, h - 1));
      uint8_t b = uint8_t((f * 13 + eye * 90) & 255);
      if (x == bar || x == bar + 1) r = g = b = 255;
      if (job.floatPixels) {
        out.rgbaF[i + 0] = float(r) / 255.0f;
        out.rgbaF[i + 1] = float(g) / 255.0f;
        out.rgbaF[i + 2] = float(b) / 255.0f;
        out.rgbaF[i + 3] = 1.0f;
      } else {
        out.rgba8[i + 0] = r;
        out.rgba8[i + 1] = g;
        out.rgba8[i + 2] = b;
        out.rgba8[i + 3] = 255;
      }
    }
}

inline bool syntheticRender(const sequencer::FrameJob& job, sequencer::EyeImages& out, std::string&) {
  syntheticEye(job, 0, out.left);
  if (job.bothEyes) syntheticEye(job, 1, out.right);
  return true;
}

}  // namespace hs::test
