#pragma once
// The CPU twin of the renderer's SMAA (render/passes/smaa_passes.h,
// shaders/smaa_*.frag) for test_smaa: the same edges, line searches,
// outline areas and blending, on an 8-bit picture (top row first, as
// images are here; the shaders' rows grow upwards, so row r of the image
// is the shaders' y = height - 1 - r). The weights are rounded to 8 bits
// as the renderer's RGBA8 weight texture holds them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace hs::test {

namespace smaa_detail {

struct Picture {
  const Image& img;
  int w, h;
  const uint8_t* texel(int x, int y) const {  // y grows upwards; clamped
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return &img.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
  }
  float luma(int x, int y) const {
    const uint8_t* t = texel(x, y);
    return 0.2126f * (float(t[0]) / 255.0f) + 0.7152f * (float(t[1]) / 255.0f) + 0.0722f * (float(t[2]) / 255.0f);
  }
};

struct Edges {
  int w, h;
  std::vector<uint8_t> left, top;  // 0 or 1, y upwards
  bool l(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h && left[size_t(y) * size_t(w) + size_t(x)]; }
  bool t(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h && top[size_t(y) * size_t(w) + size_t(x)]; }
};

inline float endHeight(bool mine, bool other) { return mine == other ? 0.0f : (mine ? -0.5f : 0.5f); }

struct Areas {
  float below = 0.0f, above = 0.0f;
  Areas& operator+=(const Areas& o) {
    below += o.below;
    above += o.above;
    return *this;
  }
};

inline Areas segmentArea(float x0, float h0, float x1, float h1, float a, float b) {
  const float u = std::max(a, x0), v = std::min(b, x1);
  if (v <= u || x1 <= x0) return {};
  const float hu = h0 + (h1 - h0) * ((u - x0) / (x1 - x0)), hv = h0 + (h1 - h0) * ((v - x0) / (x1 - x0));
  if (hu * hv >= 0.0f) {
    const float area = 0.5f * (hu + hv) * (v - u);
    return area < 0.0f ? Areas{-area, 0.0f} : Areas{0.0f, area};
  }
  const float z = u + (v - u) * hu / (hu - hv);
  const float first = 0.5f * hu * (z - u), second = 0.5f * hv * (v - z);
  return {std::max(-first, 0.0f) + std::max(-second, 0.0f), std::max(first, 0.0f) + std::max(second, 0.0f)};
}

inline Areas lineArea(float s, float t, float h1, float h2, float x) {
  if (h1 == 0.0f && h2 == 0.0f) return {};
  if (h1 != 0.0f && h2 != 0.0f) {
    const float m = 0.5f * (s + t);
    Areas a = segmentArea(s, h1, m, 0.0f, x, x + 1.0f);
    a += segmentArea(m, 0.0f, t, h2, x, x + 1.0f);
    return a;
  }
  return segmentArea(s, h1, t, h2, x, x + 1.0f);
}

inline float q8(float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f; }

}  // namespace smaa_detail

// SMAA of `in` (8-bit) with a luma threshold and a search length in pixels.
inline Image smaaReference(const Image& in, float threshold = 0.1f, int maxSearch = 16) {
  using namespace smaa_detail;
  const int w = in.width, h = in.height;
  const Picture pic{in, w, h};
  Edges e{w, h, std::vector<uint8_t>(size_t(w) * size_t(h)), std::vector<uint8_t>(size_t(w) * size_t(h))};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float l = pic.luma(x, y);
      const float nearL = pic.luma(x - 1, y), nearT = pic.luma(x, y + 1);
      const float dL = std::abs(l - nearL), dT = std::abs(l - nearT);
      float eL = dL >= threshold ? 1.0f : 0.0f, eT = dT >= threshold ? 1.0f : 0.0f;
      if (eL + eT == 0.0f) continue;
      const float aL = std::abs(l - pic.luma(x + 1, y)), aT = std::abs(l - pic.luma(x, y - 1));
      const float bL = std::abs(nearL - pic.luma(x - 2, y)), bT = std::abs(nearT - pic.luma(x, y + 2));
      const float strongest = std::max(std::max(std::max(dL, aL), bL), std::max(std::max(dT, aT), bT));
      if (!(strongest <= 2.0f * dL)) eL = 0.0f;
      if (!(strongest <= 2.0f * dT)) eT = 0.0f;
      e.left[size_t(y) * size_t(w) + size_t(x)] = eL > 0.0f;
      e.top[size_t(y) * size_t(w) + size_t(x)] = eT > 0.0f;
    }
  // Weights: r, g (the line on the top side), b, a (the left side).
  std::vector<float> wts(size_t(w) * size_t(h) * 4, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* o = &wts[(size_t(y) * size_t(w) + size_t(x)) * 4];
      if (e.t(x, y)) {
        int left = 0, right = 0;
        while (left < maxSearch && e.t(x - left - 1, y) && !e.l(x - left, y) && !e.l(x - left, y + 1)) ++left;
        while (right < maxSearch && e.t(x + right + 1, y) && !e.l(x + right + 1, y) && !e.l(x + right + 1, y + 1))
          ++right;
        const int s = x - left, t = x + right + 1;
        const Areas a = lineArea(float(s), float(t), endHeight(e.l(s, y), e.l(s, y + 1)),
                                 endHeight(e.l(t, y), e.l(t, y + 1)), float(x));
        o[0] = q8(a.below);
        o[1] = q8(a.above);
      }
      if (e.l(x, y)) {
        int down = 0, up = 0;
        while (down < maxSearch && e.l(x, y - down - 1) && !e.t(x, y - down - 1) && !e.t(x - 1, y - down - 1)) ++down;
        while (up < maxSearch && e.l(x, y + up + 1) && !e.t(x, y + up) && !e.t(x - 1, y + up)) ++up;
        const int s = y - down, t = y + up + 1;
        const Areas a = lineArea(float(s), float(t), endHeight(e.t(x, s - 1), e.t(x - 1, s - 1)),
                                 endHeight(e.t(x, t - 1), e.t(x - 1, t - 1)), float(y));
        o[2] = q8(a.below);
        o[3] = q8(a.above);
      }
    }
  Image out = Image::make8(w, h);
  const auto weight = [&](int x, int y, int c) {
    return x >= 0 && y >= 0 && x < w && y < h ? wts[(size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(c)] : 0.0f;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float top0 = weight(x, y, 0), left0 = weight(x, y, 2), bottom0 = weight(x, y - 1, 1),
                  right0 = weight(x + 1, y, 3);
      // The stronger direction's pair alone, as the renderer (and SMAA) blends.
      float top = top0, bottom = bottom0, left = left0, right = right0;
      if (std::max(left, right) > std::max(top, bottom)) top = bottom = 0.0f;
      else left = right = 0.0f;
      const float sum = top + bottom + left + right;
      const float k = sum > 1.0f ? 1.0f / sum : 1.0f;
      uint8_t* dst = &out.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      for (int c = 0; c < 4; ++c) {
        const auto v = [&](int px, int py) { return float(pic.texel(px, py)[c]) / 255.0f; };
        float r = v(x, y);
        if (sum > 0.0f)
          r = r * (1.0f - sum * k) +
              k * (top * v(x, y + 1) + bottom * v(x, y - 1) + left * v(x - 1, y) + right * v(x + 1, y));
        dst[c] = uint8_t(std::lround(std::clamp(r, 0.0f, 1.0f) * 255.0f));
      }
    }
  return out;
}

}  // namespace hs::test
