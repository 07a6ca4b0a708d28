#pragma once
// A leaf texture for alpha cut-out tests: soft-edged discs of green over
// transparent black (a one-texel edge), placed at random from `seed`.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::test {

inline mesh::Texture leafTexture(int w, int h, double radius, int count, uint32_t seed) {
  mesh::Texture t;
  t.name = "leaves";
  t.width = w;
  t.height = h;
  t.rgba.assign(size_t(w) * size_t(h) * 4, 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, w), uy(0.0, h);
  std::vector<std::pair<double, double>> centres;
  for (int i = 0; i < count; ++i) centres.emplace_back(ux(rng), uy(rng));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double a = 0.0;
      for (const auto& [cx, cy] : centres) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        a = std::max(a, std::clamp(radius + 0.5 - d, 0.0, 1.0));
      }
      uint8_t* p = &t.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
      if (a > 0.0) p[0] = 40, p[1] = 150, p[2] = 30;
      p[3] = uint8_t(std::lround(a * 255.0));
    }
  return t;
}

}  // namespace hs::test
