#pragma once
// A synthetic photogrammetry tile, generated so the benchmark needs no
// download: a heightfield n x n quads over `size` metres with rolling
// ground (fractal noise), a few steep rock pillars, scan noise, occlusion
// holes, a slightly irregular vertex layout, and a texture atlas of
// chart x chart islands (so every chart border is a UV seam, as in
// RealityCapture/Metashape exports). Faces are grouped by chart, rows
// within a chart, like those exports.
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::bench {

namespace detail {
inline uint64_t hash3(int64_t x, int64_t y, uint64_t seed) {
  uint64_t h = uint64_t(x) * 0x9E3779B97F4A7C15ull ^ uint64_t(y) * 0xC2B2AE3D27D4EB4Full ^ seed;
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  return h;
}
inline double unit(uint64_t h) { return double(h >> 11) * 0x1.0p-53; }
// Smooth value noise in [-1, 1].
inline double valueNoise(double x, double y, uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const int64_t ix = int64_t(fx), iy = int64_t(fy);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  auto v = [&](int64_t a, int64_t b) { return unit(hash3(a, b, seed)) * 2 - 1; };
  const double a = v(ix, iy) + (v(ix + 1, iy) - v(ix, iy)) * sx;
  const double b = v(ix, iy + 1) + (v(ix + 1, iy + 1) - v(ix, iy + 1)) * sx;
  return a + (b - a) * sy;
}
}  // namespace detail

inline hs::mesh::MeshData scanTerrain(int n, double size, int charts = 8, uint64_t seed = 7) {
  using namespace detail;
  const double cell = size / n;
  auto height = [&](double x, double y) {
    double h = 0, amp = 18.0, freq = 1.0 / 160.0;
    for (int o = 0; o < 6; ++o, amp *= 0.5, freq *= 2.0) h += amp * valueNoise(x * freq, y * freq, seed + uint64_t(o));
    // Rock pillars: steep-sided, rounded tops (the Meteora kind).
    for (int p = 0; p < 5; ++p) {
      const double cx = size * (0.15 + 0.7 * unit(hash3(p, 1, seed))), cy = size * (0.15 + 0.7 * unit(hash3(p, 2, seed)));
      const double r = size * (0.04 + 0.05 * unit(hash3(p, 3, seed))), top = 40.0 + 50.0 * unit(hash3(p, 4, seed));
      const double d = std::hypot(x - cx, y - cy) / r;
      if (d < 1.3) h += top / (1.0 + std::exp((d - 1.0) * 14.0)) * (1.0 - 0.15 * d * d);
    }
    return h;
  };
  // Occlusion holes: faces whose centre falls in one of these disks are missing.
  struct Disk { double x, y, r; };
  std::vector<Disk> holes;
  for (int k = 0; k < 8; ++k)
    holes.push_back({size * unit(hash3(k, 10, seed)), size * unit(hash3(k, 11, seed)),
                     cell * (4.0 + 10.0 * unit(hash3(k, 12, seed)))});
  auto inHole = [&](double x, double y) {
    for (const auto& d : holes)
      if (std::hypot(x - d.x, y - d.y) < d.r) return true;
    return false;
  };

  hs::mesh::MeshData m;
  const int cs = (n + charts - 1) / charts;  // quads per chart side
  const size_t estimate = size_t(n + charts) * size_t(n + charts);
  m.positions.reserve(estimate);
  m.uvs.reserve(estimate);
  m.indices.reserve(size_t(n) * n * 6);
  std::vector<uint32_t> local;
  for (int cj = 0; cj < charts; ++cj)
    for (int ci = 0; ci < charts; ++ci) {
      const int i0 = ci * cs, j0 = cj * cs, i1 = std::min(n, i0 + cs), j1 = std::min(n, j0 + cs);
      if (i0 >= i1 || j0 >= j1) continue;
      const int w = i1 - i0 + 1;
      local.assign(size_t(w) * size_t(j1 - j0 + 1), UINT32_MAX);
      auto vertex = [&](int i, int j) {
        uint32_t& id = local[size_t(j - j0) * size_t(w) + size_t(i - i0)];
        if (id != UINT32_MAX) return id;
        // Irregular layout: interior vertices jitter by up to 0.2 cells;
        // tile borders stay straight so tiles can meet.
        const bool edge = i == 0 || j == 0 || i == n || j == n;
        const double jx = edge ? 0 : 0.2 * (unit(hash3(i, j, seed + 99)) * 2 - 1);
        const double jy = edge ? 0 : 0.2 * (unit(hash3(j, i, seed + 98)) * 2 - 1);
        const double x = (i + jx) * cell, y = (j + jy) * cell;
        const double z = height(x, y) + 0.02 * (unit(hash3(i, j, seed + 7)) * 2 - 1);  // scan noise
        m.positions.emplace_back(float(x), float(y), float(z));
        m.uvs.emplace_back(float((ci + 0.02 + 0.96 * double(i - i0) / cs) / charts),
                           float((cj + 0.02 + 0.96 * double(j - j0) / cs) / charts));
        return id = uint32_t(m.positions.size() - 1);
      };
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          if (inHole((i + 0.5) * cell, (j + 0.5) * cell)) continue;
          const uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
          m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    }
  // Vertices created for hole-only quads are unused: drop them.
  std::vector<uint32_t> remap(m.positions.size(), UINT32_MAX);
  uint32_t next = 0;
  for (uint32_t& i : m.indices) {
    if (remap[i] == UINT32_MAX) remap[i] = next++;
    i = remap[i];
  }
  std::vector<glm::vec3> p(next);
  std::vector<glm::vec2> t(next);
  for (size_t v = 0; v < remap.size(); ++v)
    if (remap[v] != UINT32_MAX) p[remap[v]] = m.positions[v], t[remap[v]] = m.uvs[v];
  m.positions = std::move(p);
  m.uvs = std::move(t);
  m.submeshes.push_back({0, uint32_t(m.indices.size()), 0});
  hs::mesh::Material mat;
  mat.name = "atlas";
  m.materials.push_back(mat);
  hs::mesh::computeVertexNormals(m);
  return m;
}

}  // namespace hs::bench
