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
#include <map>
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

// The harder quad scan (issue 38: the real quad scan's worst case, a thin
// feature collapsed away, is not in quadScan any more): the same grid,
// atlas and non-manifold fins, with the features photogrammetry of rock
// and buildings has and decimation loses first: thin walls (a ridge one
// grid line wide, a metre high), spikes (single vertices raised 0.8 m),
// narrow bridges (a strip two quads wide between two holes) and folds (a
// sharp V crease) and two thin double-sided walls (two quad sheets 4 cm
// apart). Heights in metres over a `size` metre square.
inline hs::mesh::MeshData hardQuadScan(int n = 180, double size = 30.0, uint64_t seed = 23, bool irregular = false) {
  using namespace detail;
  hs::mesh::MeshData m = quadScan(n, size, seed);
  if (irregular) {
    // An irregular triangulation of irregular quads: each quad's diagonal
    // by a hash, grid points jittered by up to 0.35 of a cell.
    for (size_t t = 0; t + 5 < m.indices.size() - 9; t += 6) {
      if (unit(hash3(int64_t(t), 77, seed)) < 0.5) continue;
      const uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2], d = m.indices[t + 5];
      m.indices[t] = a; m.indices[t + 1] = b; m.indices[t + 2] = d;
      m.indices[t + 3] = b; m.indices[t + 4] = c; m.indices[t + 5] = d;
    }
    const double cellSize = size / n;
    std::map<std::pair<int64_t, int64_t>, glm::vec2> jitter;  // the same for a point's copies on seams
    for (size_t v = 0; v + 3 < m.positions.size(); ++v) {
      glm::vec3& p = m.positions[v];
      const int64_t i = std::lround(double(p.x) / cellSize), j = std::lround(double(p.y) / cellSize);
      if (i <= 0 || j <= 0 || i >= n || j >= n) continue;
      const glm::vec2 o(float(0.35 * cellSize * (2.0 * unit(hash3(i, j, seed + 5)) - 1.0)),
                        float(0.35 * cellSize * (2.0 * unit(hash3(i, j, seed + 6)) - 1.0)));
      p.x += o.x;
      p.y += o.y;
    }
  }
  const double cell = size / n;
  const size_t gridVertices = m.positions.size() - 3;  // the three non-manifold fins' tops come last
  for (size_t v = 0; v < gridVertices; ++v) {
    glm::vec3& p = m.positions[v];
    const int i = int(std::lround(double(p.x) / cell)), j = int(std::lround(double(p.y) / cell));
    double dz = 0.0;
    // Thin walls: three grid lines, a metre up, tapering at their ends.
    for (int w = 0; w < 3; ++w) {
      const int line = n / 6 + w * n / 3;
      const int from = n / 8 + w * 7, to = n / 2 + w * 11;
      if (i == line && j >= from && j <= to) dz += 1.0 * std::min(1.0, std::min(j - from, to - j) / 3.0);
    }
    // Folds: a sharp V crease across the grid (2 m deep over 6 m each side).
    dz += std::min(0.0, 2.0 * (std::abs(double(p.x) - 0.62 * size) / (0.2 * size)) - 2.0) * (double(p.y) > 0.7 * size ? 1.0 : 0.0);
    // Spikes: single vertices.
    for (int k = 0; k < 12; ++k) {
      const int si = int(double(n) * (0.08 + 0.84 * unit(hash3(k, 5, seed)))), sj = int(double(n) * (0.08 + 0.84 * unit(hash3(k, 6, seed))));
      if (i == si && j == sj) dz += 0.8;
    }
    p.z += float(dz);
  }
  // Narrow bridges: two holes side by side, a strip two quads wide between.
  std::vector<uint32_t> kept;
  const int bj0 = int(0.15 * n), bj1 = int(0.3 * n), bi = int(0.8 * n);
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 c = glm::dvec3(m.positions[m.indices[t]] + m.positions[m.indices[t + 1]] + m.positions[m.indices[t + 2]]) / 3.0;
    const int i = int(c.x / cell), j = int(c.y / cell);
    const bool hole = j >= bj0 && j < bj1 && ((i >= bi - 12 && i < bi - 1) || (i >= bi + 1 && i < bi + 12));
    if (!hole) kept.insert(kept.end(), {m.indices[t], m.indices[t + 1], m.indices[t + 2]});
  }
  // The holes' inner vertices go too (an error report samples every vertex).
  std::vector<uint32_t> remap(m.positions.size(), UINT32_MAX);
  hs::mesh::MeshData out;
  for (uint32_t& v : kept) {
    if (remap[v] == UINT32_MAX) {
      remap[v] = uint32_t(out.positions.size());
      out.positions.push_back(m.positions[v]);
      out.uvs.push_back(m.uvs[v]);
    }
    v = remap[v];
  }
  out.indices = std::move(kept);
  // Thin double-sided walls standing on the ground (a balustrade, a rock
  // flake): two quad sheets 4 cm apart, 1 m high, 3 m long, with a top and
  // ends, not joined to the ground (an open bottom); collapsing one onto
  // its other side costs its height.
  for (int w = 0; w < 2; ++w) {
    const double x0 = size * (0.3 + 0.35 * w), y0 = size * (0.55 - 0.3 * w), len = 3.0, thick = 0.04, high = 1.0;
    const int nl = 36, nh = 12;
    const double ground = double(out.positions[0].z) * 0.0 + 1.5;  // about the relief's height there
    const uint32_t base = uint32_t(out.positions.size());
    // A ring around the wall's section (two long sides, two ends) at each height.
    std::vector<glm::dvec2> ring;
    for (int k = 0; k <= nl; ++k) ring.push_back({x0 + len * k / nl, y0});
    ring.push_back({x0 + len, y0 + thick});
    for (int k = nl; k >= 0; --k) ring.push_back({x0 + len * k / nl, y0 + thick});
    const int rn = int(ring.size());
    for (int hgt = 0; hgt <= nh; ++hgt)
      for (int r = 0; r < rn; ++r) {
        out.positions.emplace_back(float(ring[size_t(r)].x), float(ring[size_t(r)].y), float(ground + high * hgt / nh));
        out.uvs.emplace_back(float(0.5 + 0.45 * r / rn), float(0.5 + 0.45 * hgt / nh));
      }
    auto at = [&](int hgt, int r) { return base + uint32_t(hgt * rn + (r % rn)); };
    for (int hgt = 0; hgt < nh; ++hgt)
      for (int r = 0; r < rn; ++r)
        out.indices.insert(out.indices.end(), {at(hgt, r), at(hgt, r + 1), at(hgt + 1, r + 1), at(hgt, r), at(hgt + 1, r + 1), at(hgt + 1, r)});
    // The top: quads between the two long sides.
    for (int k = 0; k < nl; ++k) {
      const uint32_t a = at(nh, k), b = at(nh, k + 1), c = at(nh, rn - 2 - k), d = at(nh, rn - 1 - k);
      out.indices.insert(out.indices.end(), {a, b, c, a, c, d});
    }
  }
  out.submeshes = {{0, uint32_t(out.indices.size()), -1}};
  return out;
}

}  // namespace hs::bench
