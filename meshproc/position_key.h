#pragma once
// A hash of a vertex position's exact float bits (a vertex that did not
// move keeps them), mixed for hash maps: the cluster hierarchy finds shared
// group borders with it and its pages find each level's vertex normals by
// position (so both sides of a UV seam count as one point). Two positions
// colliding count as one: a border locked more, a normal averaged wider.
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

namespace hs::mesh {

inline uint64_t positionKey(const glm::vec3& p) {
  uint32_t b[3];
  std::memcpy(b, &p, sizeof b);
  return (uint64_t(b[0]) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(b[1]) * 0xC2B2AE3D27D4EB4Full) ^
         (uint64_t(b[2]) * 0x165667B19E3779F9ull);
}

}  // namespace hs::mesh
