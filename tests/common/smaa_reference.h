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

// SMAA's diagonal patterns, rebuilt here the MLAA way in the frame turned
// 45°: `p` on the lower side of a staircase of one-pixel steps (edges on
// its top and on its left, or with `mirror` on its right: a slope of +1 or
// -1), the run of such pixels followed along the diagonal both ways. A
// break at an end says how the line leaves the diagonal: a horizontal step
// (the line shallower than 45°) or a vertical one (steeper); the outline's
// offset from the staircase's midpoint line is +-0.5 there and, as in an
// orthogonal Z, goes linearly through 0 at the run's middle (one end
// known: from it to 0 at the other). Both ends the same way (a U: a bend,
// a curve's silhouette) are left to the orthogonal patterns: how far the
// outline bulges is not in the run (tested: on the post scene's spheres
// the orthogonal patterns alone are nearer to supersampling). Returns
// whether p is on such a run of at least kSmaaMinDiagonal pixels (shorter
// ones: the orthogonal patterns do as well); then `offset` holds the outline's height
// over the midpoint line (in pixels, -0.5..0.5) at p's corner triangle
// and at the pixel above's.
constexpr int kSmaaMinDiagonal = 3;
inline bool diagonalOffset(const Edges& e, int x, int y, bool mirror, int maxSearch, float* offset) {
  const int sx = mirror ? -1 : 1;
  // Edges in the mirrored frame: left is the right side when mirrored.
  const auto top = [&](int dx, int dy) { return e.t(x + sx * dx, y + dy); };
  const auto left = [&](int dx, int dy) { return mirror ? e.l(x - dx + 1, y + dy) : e.l(x + dx, y + dy); };
  const auto lower = [&](int dx, int dy) {
    return top(dx, dy) && left(dx, dy) && !left(dx + 1, dy) && !top(dx, dy - 1);
  };
  if (!lower(0, 0)) return false;
  int back = 0, ahead = 0;
  while (back < maxSearch && lower(-back - 1, -back - 1)) ++back;
  while (ahead < maxSearch && lower(ahead + 1, ahead + 1)) ++ahead;
  const int n = back + ahead + 1;
  if (n < kSmaaMinDiagonal) return false;
  const int a = -back, b = ahead;  // the run's first and last pixel, along the diagonal
  // Start: a horizontal step before it (the pixel before on the diagonal
  // has its top edge only) or a vertical one (the pixel below the first has
  // its left edge only). End: a horizontal step after (the pixel right of
  // the last, top only) or a vertical one (the next on the diagonal, left
  // only). A step counts only with the outline going on beyond it (another
  // run, or a line the same way): the picture's border says nothing.
  // A horizontal step is a column of its own, the last of the run before
  // it (the outline keeps falling through it): after one, the outline
  // reaches +0.5 a whole column before the run (a vertical step takes none).
  float h1 = 0.0f, h2 = 0.0f, start = 0.0f, end = float(n);
  if (back < maxSearch) {
    if (top(a - 1, a - 1) && !left(a - 1, a - 1) && (lower(a - 2, a - 1) || top(a - 2, a - 1)))
      h1 = 0.5f, start = -1.0f;
    else if (left(a, a - 1) && !top(a, a - 1) && (lower(a - 1, a - 2) || left(a, a - 2)))
      h1 = -0.5f;
  }
  if (ahead < maxSearch) {
    if (top(b + 1, b) && !left(b + 1, b) && (lower(b + 2, b + 1) || top(b + 2, b))) h2 = -0.5f;
    else if (left(b + 1, b + 1) && !top(b + 1, b + 1) && (lower(b + 1, b + 2) || left(b + 1, b + 2))) h2 = 0.5f;
  }
  // Both ends leaving the same way (a U: the outline bends, a curve's
  // silhouette): how far it bulges is not in the run; the orthogonal
  // patterns, which see the bend's own steps, do better there.
  if (h1 != 0.0f && h1 == h2) return false;
  const float mid = 0.5f * (start + end);
  const auto height = [&](float t) {
    if (h1 != 0.0f && h2 != 0.0f) return t < mid ? h1 * (mid - t) / (mid - start) : h2 * (t - mid) / (end - mid);
    if (h1 != 0.0f) return h1 * (end - t) / (end - start);
    if (h2 != 0.0f) return h2 * (t - start) / (end - start);
    return 0.0f;
  };
  // This pixel's corner triangle lies left of its centre, the pixel
  // above's right of it: the outline's height where each is.
  offset[0] = height(float(back) + 0.25f);
  offset[1] = height(float(back) + 0.75f);
  return true;
}

// SMAA's corner module: where a line's end meets a crossing edge that goes
// on past the one-pixel step a staircase would make, the outline has a
// real corner there, not a shallow slope; MLAA's rebuild would round it.
// The part of the line that end shapes keeps kSmaaCornerKeep of its areas
// (SMAA's corner rounding, 25 %). Which end shapes pixel x: the nearer one
// of a Z or U, the known one of an L.
constexpr float kSmaaCornerKeep = 0.25f;
inline float cornerFactor(bool corner1, bool corner2, float h1, float h2, float s, float t, float x) {
  bool corner = false;
  if (h1 != 0.0f && h2 != 0.0f) corner = x + 0.5f < 0.5f * (s + t) ? corner1 : corner2;
  else if (h1 != 0.0f) corner = corner1;
  else if (h2 != 0.0f) corner = corner2;
  return corner ? kSmaaCornerKeep : 1.0f;
}

inline float q8(float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f; }

}  // namespace smaa_detail

// SMAA of `in` (8-bit) with a luma threshold and a search length in pixels.
inline Image smaaReference(const Image& in, float threshold = 0.1f, int maxSearch = 16, bool diagonal = true,
                           bool corners = true) {
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
      float offset[2] = {0.0f, 0.0f};
      if (diagonal && (diagonalOffset(e, x, y, false, maxSearch, offset) ||
                       diagonalOffset(e, x, y, true, maxSearch, offset))) {
        // The outline y = x + 0.5 + offset over this pixel (lower side) and
        // the one above: the corner triangles' areas. Only the vertical
        // pair blends; the side edge's weights stay 0.
        o[0] = q8(0.5f * (0.5f - offset[0]) * (0.5f - offset[0]));
        o[1] = q8(0.5f * (0.5f + offset[1]) * (0.5f + offset[1]));
        o[2] = 1.0f;  // the mark: on a diagonal run (no area reaches it)
        continue;
      }
      if (e.t(x, y)) {
        int left = 0, right = 0;
        while (left < maxSearch && e.t(x - left - 1, y) && !e.l(x - left, y) && !e.l(x - left, y + 1)) ++left;
        while (right < maxSearch && e.t(x + right + 1, y) && !e.l(x + right + 1, y) && !e.l(x + right + 1, y + 1))
          ++right;
        const int s = x - left, t = x + right + 1;
        const float h1 = endHeight(e.l(s, y), e.l(s, y + 1)), h2 = endHeight(e.l(t, y), e.l(t, y + 1));
        Areas a = lineArea(float(s), float(t), h1, h2, float(x));
        if (corners) {
          // A crossing edge going on past the step (below on this row's
          // side, above on the other's) is a corner of the shape.
          const auto corner = [&](int c, float hh) {
            return hh < 0.0f ? e.l(c, y - 1) : hh > 0.0f ? e.l(c, y + 2) : false;
          };
          const float k = cornerFactor(corner(s, h1), corner(t, h2), h1, h2, float(s), float(t), float(x));
          a.below *= k;
          a.above *= k;
        }
        o[0] = q8(a.below);
        o[1] = q8(a.above);
      }
      if (e.l(x, y)) {
        int down = 0, up = 0;
        while (down < maxSearch && e.l(x, y - down - 1) && !e.t(x, y - down - 1) && !e.t(x - 1, y - down - 1)) ++down;
        while (up < maxSearch && e.l(x, y + up + 1) && !e.t(x, y + up) && !e.t(x - 1, y + up)) ++up;
        const int s = y - down, t = y + up + 1;
        const float h1 = endHeight(e.t(x, s - 1), e.t(x - 1, s - 1)), h2 = endHeight(e.t(x, t - 1), e.t(x - 1, t - 1));
        Areas a = lineArea(float(s), float(t), h1, h2, float(y));
        if (corners) {
          // Right of this column on its side, left of the column before on the other's.
          const auto corner = [&](int r, float hh) {
            return hh < 0.0f ? e.t(x + 1, r - 1) : hh > 0.0f ? e.t(x - 2, r - 1) : false;
          };
          const float k = cornerFactor(corner(s, h1), corner(t, h2), h1, h2, float(s), float(t), float(y));
          a.below *= k;
          a.above *= k;
        }
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
      // A pixel marked as on a diagonal run blends vertically only, and the
      // pixel right of it not across to it.
      const bool onRun = weight(x, y, 2) > 0.75f;
      const float top0 = weight(x, y, 0), left0 = onRun || weight(x - 1, y, 2) > 0.75f ? 0.0f : weight(x, y, 2),
                  bottom0 = weight(x, y - 1, 1), right0 = onRun ? 0.0f : weight(x + 1, y, 3);
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
