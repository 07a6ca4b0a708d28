#pragma once
// The terrain LOD's screen-space error, measured from a rendered frame (the
// test of the 1-pixel bound and bench_terrain_render both use it). For every
// pixel the terrain covers: the LOD surface point (unprojected from the
// reversed-Z depth buffer), the full-resolution mesh's height at the same
// x, y, and the distance in pixels between the two points on screen.
#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"
#include "render/terrain_lod.h"
#include "terrain/heightfield.h"

namespace hs::test {

struct TerrainScreenError {
  double maxPx = 0.0, p99 = 0.0, p999 = 0.0, mean = 0.0;
  size_t pixels = 0;  // pixels measured
};

// `depth`: the frame's depth buffer as read back (bottom row first);
// `origin`: the terrain's world origin.
inline TerrainScreenError terrainScreenError(const std::vector<float>& depth, const render::RenderView& v,
                                             const terrain::Heightfield& hf, const glm::dvec3& origin) {
  const glm::dmat4 p = v.projection();
  std::vector<double> errors;
  errors.reserve(depth.size());
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      const float d = depth[size_t(v.height - 1 - y) * size_t(v.width) + size_t(x)];
      if (d <= 0.0f) continue;
      // Reversed Z: depth = -p22 - p32 / zView.
      const double zView = -p[3][2] / (double(d) + p[2][2]);
      glm::dvec3 ro, dir;
      v.pixelRay(x + 0.5, y + 0.5, ro, dir);
      const glm::dvec3 hit = ro + dir * (-zView / glm::dot(dir, v.forward()));
      const glm::dvec2 sample = (glm::dvec2(hit) - glm::dvec2(origin)) / hf.spacing();
      if (sample.x < 0 || sample.y < 0 || sample.x > hf.samplesX() - 1 || sample.y > hf.samplesY() - 1) continue;
      const double full = origin.z + double(render::fullMeshHeightAt(hf, sample));
      glm::dvec2 a, b;
      if (!v.project(hit, a) || !v.project(glm::dvec3(hit.x, hit.y, full), b)) continue;
      errors.push_back(glm::length(a - b));
    }
  TerrainScreenError e;
  e.pixels = errors.size();
  if (errors.empty()) return e;
  std::sort(errors.begin(), errors.end());
  e.maxPx = errors.back();
  e.p99 = errors[size_t(double(errors.size() - 1) * 0.99)];
  e.p999 = errors[size_t(double(errors.size() - 1) * 0.999)];
  double sum = 0.0;
  for (double x : errors) sum += x;
  e.mean = sum / double(errors.size());
  return e;
}

}  // namespace hs::test
