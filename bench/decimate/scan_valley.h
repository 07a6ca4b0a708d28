#pragma once
// A generated valley of scan tiles for the out-of-core benchmarks, as a
// photogrammetry tool delivers a large site: a grid of tiles of 500 m, each
// its own file with its own UV chart, that meet along their borders. The
// ground is one height function over the whole valley (fractal noise as
// scan_terrain.h, and a sandstone pillar, steep-sided with a rounded top,
// in most 600 m cells: the Meteora kind), interior vertices jittered by a
// hash of their valley-wide grid index, scan noise, and two occlusion holes
// a tile. Tile borders are straight, so neighbouring tiles share them.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mesh/mesh_data.h"
#include "scan_terrain.h"

namespace hs::bench {

struct ValleyLayout {
  int tilesX = 1, tilesY = 1;
  int n = 1;                 // quads per tile side
  double tileSize = 500.0;   // metres
  uint64_t seed = 11;

  double cell() const { return tileSize / n; }

  double height(double x, double y) const {
    using namespace detail;
    double h = 0, amp = 25.0, freq = 1.0 / 400.0;
    for (int o = 0; o < 7; ++o, amp *= 0.5, freq *= 2.0) h += amp * valueNoise(x * freq, y * freq, seed + uint64_t(o));
    // A pillar in most 600 m cells (and its neighbours' reach).
    const int64_t ci = int64_t(std::floor(x / 600.0)), cj = int64_t(std::floor(y / 600.0));
    for (int64_t a = ci - 1; a <= ci + 1; ++a)
      for (int64_t b = cj - 1; b <= cj + 1; ++b) {
        if (unit(hash3(a, b, seed + 50)) < 0.25) continue;
        const double cx = (double(a) + 0.2 + 0.6 * unit(hash3(a, b, seed + 51))) * 600.0;
        const double cy = (double(b) + 0.2 + 0.6 * unit(hash3(a, b, seed + 52))) * 600.0;
        const double r = 40.0 + 60.0 * unit(hash3(a, b, seed + 53)), top = 60.0 + 160.0 * unit(hash3(a, b, seed + 54));
        const double d = std::hypot(x - cx, y - cy) / r;
        if (d < 1.3) h += top / (1.0 + std::exp((d - 1.0) * 14.0)) * (1.0 - 0.15 * d * d);
      }
    return h;
  }

  // A point at fractions (fx, fy) of the valley, `above` metres over the ground.
  glm::dvec3 pointAt(double fx, double fy, double above) const {
    const double x = fx * tilesX * tileSize, y = fy * tilesY * tileSize;
    return {x, y, height(x, y) + above};
  }
};

// Tiles of about `tileMillions` triangles, as square a grid as fits.
inline ValleyLayout valleyLayout(double millions, double tileMillions) {
  ValleyLayout v;
  const int tiles = std::max(1, int(std::lround(millions / tileMillions)));
  v.tilesX = int(std::ceil(std::sqrt(double(tiles))));
  v.tilesY = (tiles + v.tilesX - 1) / v.tilesX;
  v.n = std::max(2, int(std::lround(std::sqrt(millions * 1e6 / (2.0 * v.tilesX * v.tilesY)))));
  return v;
}

// Tile (ti, tj) in the valley's frame (origin at its corner).
inline mesh::MeshData valleyTile(const ValleyLayout& v, int ti, int tj) {
  using namespace detail;
  mesh::MeshData m;
  const int n = v.n;
  const double cell = v.cell();
  const double x0 = ti * v.tileSize, y0 = tj * v.tileSize;
  struct Disk {
    double x, y, r;
  };
  Disk holes[2];
  for (int k = 0; k < 2; ++k)
    holes[k] = {x0 + v.tileSize * unit(hash3(ti * 7 + k, tj, v.seed + 60)),
                y0 + v.tileSize * unit(hash3(ti * 7 + k, tj, v.seed + 61)), cell * (3.0 + 8.0 * unit(hash3(ti, tj * 5 + k, v.seed + 62)))};
  m.positions.reserve(size_t(n + 1) * size_t(n + 1));
  m.uvs.reserve(size_t(n + 1) * size_t(n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const int64_t gi = int64_t(ti) * n + i, gj = int64_t(tj) * n + j;
      const bool edge = i == 0 || j == 0 || i == n || j == n;
      const double jx = edge ? 0 : 0.2 * (unit(hash3(gi, gj, v.seed + 99)) * 2 - 1);
      const double jy = edge ? 0 : 0.2 * (unit(hash3(gj, gi, v.seed + 98)) * 2 - 1);
      const double x = x0 + (i + jx) * cell, y = y0 + (j + jy) * cell;
      const double z = v.height(x, y) + 0.02 * (unit(hash3(gi, gj, v.seed + 7)) * 2 - 1);
      m.positions.emplace_back(float(x), float(y), float(z));
      m.uvs.emplace_back(float(0.01 + 0.98 * i / n), float(0.01 + 0.98 * j / n));
    }
  m.indices.reserve(size_t(n) * size_t(n) * 6);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double cx = x0 + (i + 0.5) * cell, cy = y0 + (j + 0.5) * cell;
      bool hole = false;
      for (const Disk& d : holes) hole = hole || std::hypot(cx - d.x, cy - d.y) < d.r;
      if (hole) continue;
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1) + 1, d = a + uint32_t(n + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

}  // namespace hs::bench
