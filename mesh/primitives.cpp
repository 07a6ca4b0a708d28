#include "mesh/primitives.h"

#include <algorithm>
#include <cmath>

namespace hs::mesh {

MeshData uvSphere(float radius, int segments, int rings) {
  segments = std::max(segments, 3);
  rings = std::max(rings, 2);
  MeshData m;
  const float pi = 3.14159265358979f;
  // A seam column (u = 1 repeats u = 0) so UVs do not wrap back inside a triangle.
  for (int r = 0; r <= rings; ++r) {
    const float v = float(r) / float(rings);
    const float theta = v * pi;  // from the north pole
    for (int s = 0; s <= segments; ++s) {
      const float u = float(s) / float(segments);
      const float phi = u * 2.0f * pi;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      m.positions.push_back(n * radius);
      m.normals.push_back(n);
      m.uvs.emplace_back(u, v);
    }
  }
  const uint32_t row = uint32_t(segments + 1);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r) * row + uint32_t(s), b = a + row;
      // Counter-clockwise seen from outside. The pole rows' degenerate
      // triangles are left out.
      if (r > 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (r < rings - 1) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  m.materials.push_back(Material{"sphere"});
  m.submeshes.push_back({0, uint32_t(m.indices.size()), 0});
  return m;
}

MeshData gridPlane(float size, int cells, float uvRepeat) {
  cells = std::max(cells, 1);
  MeshData m;
  for (int y = 0; y <= cells; ++y)
    for (int x = 0; x <= cells; ++x) {
      const float fx = float(x) / float(cells), fy = float(y) / float(cells);
      m.positions.emplace_back((fx - 0.5f) * size, (0.5f - fy) * size, 0.0f);
      m.normals.emplace_back(0.0f, 0.0f, 1.0f);
      m.uvs.emplace_back(fx * uvRepeat, fy * uvRepeat);
    }
  const uint32_t row = uint32_t(cells + 1);
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x) {
      const uint32_t a = uint32_t(y) * row + uint32_t(x), b = a + row;
      // Rows run towards -Y: (a, b, a+1) is counter-clockwise seen from +Z.
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  m.materials.push_back(Material{"plane"});
  m.submeshes.push_back({0, uint32_t(m.indices.size()), 0});
  return m;
}

}  // namespace hs::mesh
