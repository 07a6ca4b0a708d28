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
#include <span>
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

  // closest(), except that the walk ends at the first triangle found
  // within sqrt(stopSq): a distance at least stopSq is exact, one below it
  // an upper bound (still below stopSq). For screenings that only need
  // the large distances exactly (max_error_refine.cpp): the walk that
  // confirms a small distance is most of a query's work.
  Hit closestUnless(const glm::dvec3& q, uint32_t hintFace, double stopSq) const;

  // Nearest points of several points close together (the samples of one
  // face): hits[k] is what closest(points[k]) returns, bit for bit (the
  // least squared distance, ties to the lowest face index). The error
  // report's queries come in such groups. The points are taken in the
  // order of a Morton curve through their box (a face's samples come in
  // random order), in chunks of kChunk consecutive ones: a chunk's first
  // point is looked up, its triangle bounds every other point's distance,
  // and when few leaves (kMaxLeaves) lie within that bound of the chunk's
  // box, one walk collects them and each point scans only those instead of
  // walking from the root; otherwise each point walks, hinted by the one
  // before. Returns the last point's face (a hint for the next group).
  // `scratch` keeps its memory from one call to the next, and counts the
  // chunks each way (for tests and benchmarks).
  struct ManyScratch {
    std::vector<uint32_t> leaves, order;
    std::vector<uint64_t> keys;
    std::vector<double> boxes;
    size_t scannedChunks = 0, walkedChunks = 0;
  };
  uint32_t closestMany(std::span<const glm::dvec3> points, uint32_t hintFace, std::span<Hit> hits,
                       ManyScratch& scratch) const;
  static constexpr size_t kChunk = 16;
  static constexpr size_t kMaxLeaves = 32;  // past this, a walk per point is cheaper (bench_error_measure)
  static constexpr size_t kOrderFrom = 8;   // fewer points are taken as they come

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
  template <bool kStop>
  Hit walk(const glm::dvec3& q, uint32_t hintFace, double stopSq) const;
  uint32_t closestChunk(std::span<const glm::dvec3> points, std::span<const uint32_t> order, uint32_t hintFace,
                        std::span<Hit> hits, ManyScratch& scratch) const;
  void build(uint32_t slot, uint32_t begin, uint32_t end, const std::vector<uint32_t>& codes, int bit);

  std::vector<Node> nodes_;
  // A slot's triangle: its corners, and its unit normal for the plane
  // bound testSlot tries first (zero where the cross product is too ill-
  // conditioned to trust in float: slivers are then only boxed).
  struct SlotTriangle {
    glm::vec3 v[3];
    glm::vec3 n;
  };
  std::vector<SlotTriangle> tris_;     // one per slot, in tree order
  std::vector<uint32_t> faceOfSlot_;   // slot -> mesh face
  std::vector<uint32_t> slotOfFace_;   // mesh face -> slot (for hints)
};

// Closest point on triangle (a, b, c) to p; returns the squared distance and
// the barycentric coordinates of the closest point (Ericson, Real-Time
// Collision Detection, 5.1.5).
double closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                              const glm::dvec3& c, glm::dvec3& closest, glm::dvec3& bary);

}  // namespace hs::mesh
