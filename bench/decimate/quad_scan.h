#pragma once
// A quad-dominant scan, generated so the benchmark needs no download (issue
// 11 item 5: a real one of 32k quads, triangulated on import, with a few
// hundred UV seam vertices, was where our decimator lost to meshopt and
// Blender). A regular grid of n x n quads over `size` metres, each quad
// cut along the same diagonal (as an importer triangulates quads), over a
// scan-like relief: rolling ground, a plinth with steep walls and a sharp
// ridge on top (the features a quad scan of a building or a rock has),
// millimetre scan noise; a 2 x 2 UV atlas (every chart border is a seam:
// about 4n seam vertices); and three fins, an extra triangle on an interior
// edge each (three faces on one edge: the non-manifold spots scans have).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/mesh_data.h"
#include "scan_terrain.h"

namespace hs::bench {

inline hs::mesh::MeshData quadScan(int n = 180, double size = 30.0, uint64_t seed = 11) {
  using namespace detail;
  const double cell = size / n;
  auto height = [&](double x, double y) {
    double h = 0.0, amp = 1.2, freq = 1.0 / 12.0;
    for (int o = 0; o < 4; ++o, amp *= 0.45, freq *= 2.0) h += amp * valueNoise(x * freq, y * freq, seed + uint64_t(o));
    // A plinth: steep walls (a few cells wide), flat top, a ridge along it.
    const double px = std::clamp((std::min(x - 0.3 * size, 0.7 * size - x)) / (2.5 * cell), -1.0, 1.0);
    const double py = std::clamp((std::min(y - 0.35 * size, 0.6 * size - y)) / (2.5 * cell), -1.0, 1.0);
    const double inside = std::min(px, py);
    if (inside > -1.0) h += 2.5 * 0.5 * (inside + 1.0);
    if (inside > 0.0) h += 1.5 * std::max(0.0, 1.0 - std::abs(y - 0.475 * size) / (0.06 * size));
    return h + 0.002 * (unit(hash3(int64_t(x * 1000), int64_t(y * 1000), seed)) - 0.5);
  };
  hs::mesh::MeshData m;
  // Vertices: one per grid point and chart (points on a chart border are
  // there twice or four times, with each chart's UV).
  const int half = n / 2;
  auto chartOf = [&](int i) { return i < half ? 0 : 1; };
  std::vector<uint32_t> id(size_t(n + 1) * size_t(n + 1) * 4, UINT32_MAX);
  auto vertex = [&](int i, int j, int cx, int cy) {
    uint32_t& v = id[(size_t(j) * size_t(n + 1) + size_t(i)) * 4 + size_t(cy * 2 + cx)];
    if (v == UINT32_MAX) {
      v = uint32_t(m.positions.size());
      const double x = i * cell, y = j * cell;
      m.positions.emplace_back(float(x), float(y), float(height(x, y)));
      // Each chart fills a quarter of the atlas with a 2% margin, mirrored
      // in the second column (charts that touch in space are apart in UV).
      const double u = double(i - cx * half) / double(cx ? n - half : half), w = double(j - cy * half) / double(cy ? n - half : half);
      m.uvs.emplace_back(float(0.5 * cx + 0.01 + 0.48 * (cx ? 1.0 - u : u)), float(0.5 * cy + 0.01 + 0.48 * w));
    }
    return v;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int cx = chartOf(i), cy = chartOf(j);
      const uint32_t a = vertex(i, j, cx, cy), b = vertex(i + 1, j, cx, cy), c = vertex(i + 1, j + 1, cx, cy),
                     d = vertex(i, j + 1, cx, cy);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  // Fins: a triangle standing on the diagonal of three quads.
  for (int k = 0; k < 3; ++k) {
    const int i = n / 5 + k * n / 4, j = n / 3 + k * n / 5;
    const uint32_t a = vertex(i, j, chartOf(i), chartOf(j)), c = vertex(i + 1, j + 1, chartOf(i), chartOf(j));
    const glm::vec3 top = 0.5f * (m.positions[a] + m.positions[c]) + glm::vec3(0.0f, 0.0f, float(2.0 * cell));
    m.positions.push_back(top);
    m.uvs.push_back(m.uvs[a]);
    m.indices.insert(m.indices.end(), {a, c, uint32_t(m.positions.size() - 1)});
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

}  // namespace hs::bench
