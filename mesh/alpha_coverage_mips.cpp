#include "mesh/alpha_coverage_mips.h"

#include <algorithm>
#include <cmath>

#include "core/srgb.h"

namespace hs::mesh {
namespace {

// The level below `src`: each texel the mean of its 2x2 block (the last
// row or column of an odd size folded into its neighbour's block, as the
// block is clamped at the edge). `weighted`: colour weighted by alpha.
MipLevel halve(const MipLevel& src, bool weighted) {
  MipLevel out;
  out.width = std::max(1, src.width / 2);
  out.height = std::max(1, src.height / 2);
  out.rgba.resize(size_t(out.width) * size_t(out.height) * 4);
  // Blocks cover 2x2 texels, 3 where the source's size is odd and this is
  // the last block (so no texel of the source is skipped).
  auto span = [](int o, int outSize, int srcSize, int& first, int& last) {
    first = std::min(2 * o, srcSize - 1);
    last = o == outSize - 1 ? srcSize - 1 : std::min(2 * o + 1, srcSize - 1);
  };
  for (int y = 0; y < out.height; ++y) {
    int y0, y1;
    span(y, out.height, src.height, y0, y1);
    for (int x = 0; x < out.width; ++x) {
      int x0, x1;
      span(x, out.width, src.width, x0, x1);
      double c[3] = {0, 0, 0}, cw[3] = {0, 0, 0}, a = 0.0;
      int n = 0;
      for (int sy = y0; sy <= y1; ++sy)
        for (int sx = x0; sx <= x1; ++sx) {
          const uint8_t* p = &src.rgba[(size_t(sy) * size_t(src.width) + size_t(sx)) * 4];
          const double alpha = p[3] / 255.0;
          for (int k = 0; k < 3; ++k) {
            const double lin = srgb8ToLinear(p[k]);
            c[k] += lin;
            cw[k] += lin * alpha;
          }
          a += alpha;
          ++n;
        }
      uint8_t* q = &out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4];
      for (int k = 0; k < 3; ++k)
        q[k] = linearToSrgb8(float(weighted && a > 1e-9 ? cw[k] / a : c[k] / double(n)));
      q[3] = uint8_t(std::lround(255.0 * a / double(n)));
    }
  }
  return out;
}

// The level's alpha (0..255) where bilinear filtering reads it: four
// samples a texel, a quarter texel off its centre each way, between it and
// its neighbours (wrapping, as GL_REPEAT does).
std::vector<float> filteredAlphas(const MipLevel& level) {
  const int w = level.width, h = level.height;
  auto at = [&](int x, int y) {
    x = ((x % w) + w) % w, y = ((y % h) + h) % h;
    return float(level.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4 + 3]);
  };
  std::vector<float> out;
  out.reserve(size_t(w) * size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int dy : {-1, 1})
        for (int dx : {-1, 1}) {
          // A quarter texel towards (dx, dy): 3/4 this texel, 1/4 the neighbour, per axis.
          const float a = 0.75f * at(x, y) + 0.25f * at(x + dx, y);
          const float b = 0.75f * at(x, y + dy) + 0.25f * at(x + dx, y + dy);
          out.push_back(0.75f * a + 0.25f * b);
        }
  return out;
}

// `level` with its alpha scaled by `scale` (clamped, rounded up: a sample
// made of texels on the edge stays on it).
std::vector<uint8_t> scaledAlpha(const MipLevel& level, double scale) {
  std::vector<uint8_t> rgba = level.rgba;
  for (size_t i = 3; i < rgba.size(); i += 4)
    rgba[i] = uint8_t(std::min(255.0, std::ceil(double(rgba[i]) * scale - 1e-9)));
  return rgba;
}

// Scales `level`'s alpha so that as near `targetShare` of its filtered
// samples (filteredAlphas) as can be reach threshold x 255. Measured where
// the sampler reads, not per texel: a needle one texel wide passes as a
// texel but is averaged with the gaps beside it by the filter. The share
// grows with the scale (clamped at 255 it grows more slowly than the
// scale), so the scale is found by bisection, in octaves from 1/256 to 256.
void scaleToCoverage(MipLevel& level, float threshold, double targetShare) {
  const size_t n = size_t(level.width) * size_t(level.height) * 4;
  const double target = targetShare * double(n);
  auto passing = [&](double scale) {
    return filteredAlphaCoverage(MipLevel{level.width, level.height, scaledAlpha(level, scale)}, threshold) *
           double(n);
  };
  const double asIs = passing(1.0);
  if (std::abs(asIs - target) < 0.5) return;  // as near as can be (an opaque texture): left alone
  // The smallest scale (octaves lo..hi) whose samples reach the target.
  double lo = -8.0, hi = 8.0;
  for (int i = 0; i < 24; ++i) {
    const double mid = 0.5 * (lo + hi);
    (passing(std::exp2(mid)) >= target ? hi : lo) = mid;
  }
  // That scale or the one just under it, whichever comes nearer.
  const double above = passing(std::exp2(hi)), below = passing(std::exp2(lo));
  const double scale = std::exp2(std::abs(above - target) <= std::abs(below - target) ? hi : lo);
  if (std::abs(asIs - target) <= std::min(std::abs(above - target), std::abs(below - target))) return;
  level.rgba = scaledAlpha(level, scale);
}

}  // namespace

double alphaCoverage(const std::vector<uint8_t>& rgba, float threshold) {
  const size_t n = rgba.size() / 4;
  if (n == 0) return 0.0;
  const double edge = double(threshold) * 255.0;
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) kept += double(rgba[i * 4 + 3]) >= edge;
  return double(kept) / double(n);
}

double filteredAlphaCoverage(const MipLevel& level, float threshold) {
  const std::vector<float> samples = filteredAlphas(level);
  if (samples.empty()) return 0.0;
  const double edge = double(threshold) * 255.0;
  size_t kept = 0;
  for (float v : samples) kept += double(v) >= edge;
  return double(kept) / double(samples.size());
}

std::vector<MipLevel> coveragePreservingMips(const Texture& level0, float threshold) {
  std::vector<MipLevel> out;
  if (level0.width <= 0 || level0.height <= 0 || level0.rgba.size() != size_t(level0.width) * size_t(level0.height) * 4)
    return out;
  const bool scale = threshold > 0.0f && threshold < 1.0f;
  const double coverage = scale ? alphaCoverage(level0.rgba, threshold) : 0.0;
  MipLevel above{level0.width, level0.height, level0.rgba};
  while (above.width > 1 || above.height > 1) {
    // Each level from the box filter of the one above before its scaling
    // (the scaled alpha of one level is not an average of the next's).
    MipLevel next = halve(above, true);
    MipLevel scaled = next;
    if (scale) scaleToCoverage(scaled, threshold, coverage);
    out.push_back(std::move(scaled));
    above = std::move(next);
  }
  return out;
}

std::vector<MipLevel> boxFilteredMips(const Texture& level0) {
  std::vector<MipLevel> out;
  if (level0.width <= 0 || level0.height <= 0 || level0.rgba.size() != size_t(level0.width) * size_t(level0.height) * 4)
    return out;
  MipLevel above{level0.width, level0.height, level0.rgba};
  while (above.width > 1 || above.height > 1) {
    out.push_back(halve(above, false));
    above = out.back();
  }
  return out;
}

}  // namespace hs::mesh
