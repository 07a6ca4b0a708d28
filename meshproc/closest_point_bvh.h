#pragma once
// Closest point on a triangle mesh: a bounding volume hierarchy over its
// triangles, built from a Morton order (linear time after a radix sort) and
// queried depth-first, nearer child first, with the best distance so far
// pruning the rest. Distances are computed in double from the mesh's float
// vertices, so a plane moved by d measures exactly d.
//
// Queries are const and may run from any number of threads at once.
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "mesh/mesh_data.h"

namespace hs::mesh {

class ClosestPointBvh {
 public:
  ClosestPointBvh() = default;
  // Indexes the triangles of `mesh`. Query points are in the mesh's local
  // frame (relative to mesh.origin), in double.
  explicit ClosestPointBvh(const MeshData& mesh, unsigned threads = 0);

  struct Hit {
    double distanceSq = std::numeric_limits<double>::infinity();
    uint32_t face = UINT32_MAX;  // triangle index in the mesh
    glm::dvec3 point{0.0};       // closest point
    glm::dvec3 bary{0.0};        // its barycentric coordinates in `face`
    bool found() const { return face != UINT32_MAX; }
  };

  // Nearest point to `q`. `hintFace` (a face likely to be near, e.g. the
  // previous query's) gives an early bound that prunes most of the tree.
  Hit closest(const glm::dvec3& q, uint32_t hintFace = UINT32_MAX) const;

  // Does a triangle cross the segment from `origin` along `direction` (not
  // necessarily unit) for parameters t in [tMin, tMax]? An any-hit query
  // (shadow rays): the first triangle found ends it. Both sides of a
  // triangle count. Uses the same tree, boxes tested with slabs, triangles
  // with Moller-Trumbore in double.
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const;

  size_t triangleCount() const { return faceOfSlot_.size(); }
  bool empty() const { return nodes_.empty(); }

 private:
  struct Node {
    float lo[3], hi[3];
    uint32_t first;  // leaf: first slot; inner: left child (right = left + 1)
    uint32_t count;  // leaf: triangles; inner: 0
  };
  void testSlot(uint32_t slot, const glm::dvec3& q, Hit& best) const;
  void build(uint32_t slot, uint32_t begin, uint32_t end, const std::vector<uint32_t>& codes, int bit);

  std::vector<Node> nodes_;
  std::vector<glm::vec3> corners_;     // 3 per slot, in tree order
  std::vector<uint32_t> faceOfSlot_;   // slot -> mesh face
  std::vector<uint32_t> slotOfFace_;   // mesh face -> slot (for hints)
};

// Closest point on triangle (a, b, c) to p; returns the squared distance and
// the barycentric coordinates of the closest point (Ericson, Real-Time
// Collision Detection, 5.1.5).
double closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, glm::dvec3& closest, glm::dvec3& bary);

}  // namespace hs::mesh
