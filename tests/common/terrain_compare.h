#pragma once
// Bitwise comparison of terrains for the scene, file and GUI suites: every
// sample of heights, holes and paint weights (an unallocated tile compares as
// its fill value), plus spacing and origin.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>

#include "terrain/terrain.h"

namespace hs::test {

inline std::string terrainDifference(const terrain::Terrain& a, const terrain::Terrain& b) {
  const auto& ha = a.height;
  const auto& hb = b.height;
  if (ha.samplesX() != hb.samplesX() || ha.samplesY() != hb.samplesY()) return "sizes differ";
  if (ha.spacing() != hb.spacing()) return "spacing differs";
  if (ha.origin() != hb.origin()) return "origin differs";
  if (a.paint.layerCount() != b.paint.layerCount()) return "layer counts differ";
  for (int y = 0; y < ha.samplesY(); ++y)
    for (int x = 0; x < ha.samplesX(); ++x) {
      const float va = ha.at(x, y), vb = hb.at(x, y);
      if (std::memcmp(&va, &vb, sizeof va) != 0)
        return "height at " + std::to_string(x) + "," + std::to_string(y) + ": " + std::to_string(va) + " vs " +
               std::to_string(vb);
      if (ha.isHole(x, y) != hb.isHole(x, y)) return "hole at " + std::to_string(x) + "," + std::to_string(y);
      for (int l = 0; l < a.paint.layerCount(); ++l)
        if (a.paint.raw(l, x, y) != b.paint.raw(l, x, y))
          return "weight of layer " + std::to_string(l) + " at " + std::to_string(x) + "," + std::to_string(y);
    }
  return {};
}

// Largest |sum of the 16-bit weights - 65535| over every sample: 0 when
// weights sum to exactly 1 (PaintLayers::maxSumError sums floats, which
// round).
inline long paintSumError(const terrain::PaintLayers& p) {
  long worst = 0;
  for (int y = 0; y < p.samplesY(); ++y)
    for (int x = 0; x < p.samplesX(); ++x) {
      long sum = 0;
      for (int l = 0; l < p.layerCount(); ++l) sum += p.raw(l, x, y);
      worst = std::max(worst, std::abs(sum - long(terrain::kWeightOne)));
    }
  return worst;
}

}  // namespace hs::test
