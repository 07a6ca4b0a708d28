#pragma once
// How far a simplified mesh is from its original: the reference that every
// decimation (and every benchmark against other decimators) reports next to
// its run time.
//
// Surface distance is estimated by seeded surface sampling in both
// directions (original -> simplified and back), with exact point-to-triangle
// distances through a BVH; the vertices of each mesh are added to its
// samples so the maximum sees the corners. Everything is in metres, in the
// original's frame (double), and relative to its bounding-box diagonal.
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "meshproc/closest_point_bvh.h"

namespace hs::mesh {

struct ErrorOptions {
  double samplesPerFace = 10.0;    // per original face; each direction draws that many in total
  uint64_t seed = 1;
  uint64_t maxSamples = 20'000'000;  // per direction; the report says when this capped the rate
  // Texture size for UV displacement in texels; 0 = the size of the
  // material's decoded texture (no texture: UV displacement not measured).
  int textureWidth = 0, textureHeight = 0;
  // Also bound the Hausdorff from above (hausdorffUpperBound, depth 10,
  // 1% slack), so the report says how far the sampled maximum can be off:
  // up to 3x the measurement's time at 50%, a fifth at 1% (docs/meshes.md).
  bool certify = false;
  unsigned threads = 0;
};

struct DistanceStats {
  double max = 0, mean = 0, rms = 0, p95 = 0;  // metres
  uint64_t samples = 0;                        // face samples (vertices come on top, for max)
};

struct NonManifoldCounts {
  size_t edges = 0;     // edges with 3+ faces or two faces running the same way
  size_t vertices = 0;  // bow-ties: faces around the vertex form 2+ fans
};

struct ErrorReport {
  double samplesPerFace = 0;  // effective rate after the cap
  uint64_t seed = 0;
  double bboxDiagonal = 0;    // metres, of the original
  DistanceStats forward;      // original -> simplified
  DistanceStats backward;     // simplified -> original
  // Symmetric: Hausdorff is the larger maximum; mean, RMS and 95th
  // percentile are over both directions' samples together.
  double hausdorff = 0, mean = 0, rms = 0, p95 = 0;

  // With ErrorOptions::certify: no point of either surface is further
  // from the other than hausdorffUpper (the sampled `hausdorff` is reached
  // by some point: the true Hausdorff lies between the two).
  bool certified = false;
  double hausdorffUpper = 0;
  uint64_t certifiedPieces = 0;
  double certifySeconds = 0;

  size_t flippedNormals = 0;  // simplified faces facing against the original surface at their centre
  size_t facesChecked = 0;

  bool uvMeasured = false;
  int textureWidth = 0, textureHeight = 0;
  double uvMaxTexels = 0, uvMeanTexels = 0, uvP95Texels = 0;
  size_t uvSamples = 0;

  // Vertices of the simplified mesh on a boundary or seam, and how many of
  // them are off the original's boundary/seam polylines (more than 1e-6 of
  // the diagonal), with the largest such distance.
  size_t constrainedVerticesOut = 0, constrainedVerticesMoved = 0;
  double constrainedMaxDeviation = 0;

  double areaIn = 0, areaOut = 0;      // m^2
  double volumeIn = 0, volumeOut = 0;  // m^3, signed (meaningful for closed meshes)
  NonManifoldCounts nonManifoldIn, nonManifoldOut;
  double seconds = 0;
  bool cancelled = false;

  double rel(double metres) const { return bboxDiagonal > 0 ? metres / bboxDiagonal : 0.0; }
  // Relative change of the area and of the volume's magnitude (0 when the original has none).
  double areaChangeRel() const { return areaIn > 0 ? (areaOut - areaIn) / areaIn : 0.0; }
  double volumeChangeRel() const { return volumeIn != 0 ? (volumeOut - volumeIn) / std::abs(volumeIn) : 0.0; }
};

// Non-manifold edges and vertices at welded-position level (UV seams do not
// count as cuts).
NonManifoldCounts countNonManifold(const MeshData& mesh, unsigned threads = 0);

struct HausdorffBound {
  double lower = 0, upper = 0;  // metres: lower <= Hausdorff <= upper
  uint64_t pieces = 0;          // face pieces examined, both directions
  double seconds = 0;
};

// Holds what depends on the original only (its BVH, polylines, area), so
// one original can be compared with many results (LOD chains, benchmarks).
class ErrorMeter {
 public:
  ErrorMeter(const MeshData& original, const ErrorOptions& options = {});
  // It keeps a reference to the original (original()): a temporary would
  // be gone before the first measurement.
  ErrorMeter(const MeshData&& original, const ErrorOptions& options = {}) = delete;
  ~ErrorMeter();
  // What a result's vertices alone say: the largest distance from a vertex
  // of the original to the result's surface (forward) and back, with the
  // result's BVH they were found through. measure() takes the same
  // distances into its maxima, so its Hausdorff is never below
  // hausdorff(); a fraction of its cost (no face samples), for telling
  // quickly that a result is over a bound.
  struct VertexCheck {
    ClosestPointBvh bvh;  // of the result
    double forward = 0, backward = 0;
    double hausdorff() const { return forward > backward ? forward : backward; }
  };
  VertexCheck checkVertices(const MeshData& simplified) const;
  // The whole report. `check`: checkVertices(simplified) made before,
  // whose BVH and vertex maxima are used instead of being found again.
  ErrorReport measure(const MeshData& simplified, const Progress* progress = nullptr,
                      const VertexCheck* check = nullptr) const;
  // A certified bracket of the Hausdorff distance: the sampled maximum
  // (measure()'s, passed as `lowerBound`) is reached by some point, and no
  // point of either surface is further from the other than `upper`. Each
  // face is bounded through the triangles nearest its corners (the
  // distance to one triangle is convex, so largest at a corner) and cut
  // into four where that bound is more than `slack` above the lower one,
  // down to `maxDepth` levels (4^maxDepth pieces a face at most): the
  // upper bound is then at most `slack` above the lower one wherever the
  // depth sufficed. `check`, as for measure(): its BVH of the result is
  // used instead of building one.
  HausdorffBound hausdorffUpperBound(const MeshData& simplified, double lowerBound, double slack = 0.01,
                                     int maxDepth = 8, const VertexCheck* check = nullptr) const;

  // The report's flip test of one face, corners in the original's frame:
  // the original's face nearest the face's centre (`hit`) and whether the
  // two normals point apart. A face without area, or with no original face
  // found, is not checked. measure() counts `flippedNormals` with it; the
  // refinement (max_error_refine.h) keeps faces from turning over with the
  // same test, to the bit. `hintFace` as for ClosestPointBvh::closest.
  struct Facing {
    bool checked = false, against = false;
    ClosestPointBvh::Hit hit;
  };
  Facing facing(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, uint32_t hintFace = UINT32_MAX) const;

  // The original it measures against, and its BVH (for passes that query
  // it too: max_error_refine.h).
  const MeshData& original() const;
  const ClosestPointBvh& originalBvh() const;

 private:
  struct Original;
  std::unique_ptr<Original> o_;
};

// One-off comparison.
ErrorReport measureError(const MeshData& original, const MeshData& simplified,
                         const ErrorOptions& options = {}, const Progress* progress = nullptr);

}  // namespace hs::mesh
