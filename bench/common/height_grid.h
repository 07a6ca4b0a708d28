#pragma once
// A terrain-like test mesh for the render benchmarks: n x n vertices over a
// size x size square centred on the origin, heights from `height(x, y)`,
// two triangles per cell, vertex normals, one submesh. (The terrain
// renderer draws heightfields its own way; this is a plain mesh, for
// benchmarks that need one, e.g. translucent or shadow-casting.)
#include <cstdint>
#include <memory>

#include "mesh/mesh_data.h"

namespace hs::bench {

template <class Height>
std::shared_ptr<const mesh::MeshData> heightGridMesh(int n, float size, Height height) {
  auto m = std::make_shared<mesh::MeshData>();
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float fx = size * (float(x) / float(n - 1) - 0.5f), fy = size * (float(y) / float(n - 1) - 0.5f);
      m->positions.emplace_back(fx, fy, height(fx, fy));
    }
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const uint32_t i = uint32_t(y * n + x);
      m->indices.insert(m->indices.end(), {i, i + 1, i + uint32_t(n), i + 1, i + uint32_t(n) + 1, i + uint32_t(n)});
    }
  mesh::computeVertexNormals(*m);
  m->submeshes.push_back({0, uint32_t(m->indices.size()), -1});
  return m;
}

}  // namespace hs::bench
