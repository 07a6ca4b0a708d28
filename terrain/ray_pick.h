#pragma once
// Ray against heightfield, for brush picking. Walks the tiles along the ray
// with a 2D DDA, skips every tile whose height bounds the ray's height range
// does not meet, and inside a tile walks the cells, testing the same two
// triangles the full-resolution mesh draws. Hole cells are not hit.
#include <limits>
#include <optional>

#include <glm/glm.hpp>

#include "terrain/heightfield.h"

namespace hs::terrain {

struct RayHit {
  glm::dvec3 world{0.0};   // hit point, world coordinates
  glm::dvec2 local{0.0};   // hit point XY relative to the terrain origin (brush centre)
  double distance = 0.0;   // along the normalised ray direction, metres
  glm::vec3 normal{0, 0, 1};
  int cellX = 0, cellY = 0;
};

std::optional<RayHit> intersectRay(const Heightfield& hf, const glm::dvec3& worldOrigin,
                                   const glm::dvec3& direction,
                                   double maxDistance = std::numeric_limits<double>::infinity());

}  // namespace hs::terrain
