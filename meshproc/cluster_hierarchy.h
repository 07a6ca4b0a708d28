#pragma once
// Hierarchical cluster LOD for huge scans (issue 38, item 1; the in-core
// builder): the mesh cut into clusters of about 128 triangles
// (meshoptimizer's meshlet builder), neighbouring clusters grouped by four,
// each group simplified to half by the project's own decimator with the
// group's outer border locked, the result cut into clusters again; level by
// level to a root. As in Nanite, every cluster carries two LOD tests: its
// own (the error of the simplification that made it, over the sphere of
// the group it came from) and its parent's (the error and sphere of the
// group it was simplified in). A group's error is its children's largest
// plus a certified upper bound of the Hausdorff distance its own
// simplification made (meshproc/error_metrics.h): by the triangle
// inequality no point of a cluster is further than its error from the
// input's surface, nor the other way round. Errors only grow up the hierarchy and each
// group's sphere holds its children's, so the projected error is monotonic
// and a cut (selectClusterCut: a cluster drawn where its own test passes
// and its parent's fails) takes, for every piece of surface, exactly one
// level: group borders were locked, so clusters of different levels meet
// on the same vertices (no crack; tests/meshproc/test_meshproc_clusters).
// Deterministic: groups are simplified in parallel but merged in a fixed
// order; the result depends on the input and the options only.
// Pages: cluster_pages.h; the cut with pages missing: cluster_cut.h; in
// the scene file: scene/cluster_file.h; a scan larger than memory, built
// cell by cell from tiles: cluster_build_streamed.h. Not here yet:
// textures paged per region, the GPU cut.
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "core/progress.h"
#include "mesh/mesh_data.h"

namespace hs::mesh {

struct ClusterOptions {
  size_t maxTriangles = 128;  // per cluster (meshoptimizer allows 512, a multiple of 4)
  size_t maxVertices = 128;   // per cluster (at most 255)
  size_t groupSize = 4;       // clusters simplified together
  // A group its locked border keeps from losing this share of its
  // triangles is left as it is: its clusters wait for the next level's
  // grouping (with other neighbours, other borders).
  double minReduction = 0.15;
  // A group's own error: a certified upper bound of the Hausdorff distance
  // its simplification made (a true bound, at most a quarter loose; the
  // build takes 7-11x as long), or with false the decimator's quadric
  // estimate (cheap, but some clusters end up further from the input than
  // it says; bench_clusters compares).
  bool certifyErrors = true;
  unsigned threads = 0;  // 0: every available thread; the result is the same for any count
};

inline constexpr uint32_t kNoGroup = 0xFFFFFFFFu;

struct LodSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

struct Cluster {
  uint32_t firstIndex = 0;     // into ClusterHierarchy::indices
  uint32_t triangleCount = 0;
  uint32_t level = 0;          // 0: the input's triangles
  LodSphere bounds;            // its triangles (culling)
  // Its own LOD test: the error (metres) of the simplification that made
  // it and the sphere of the group it was made in (level 0: 0 and its own
  // bounds). The same for every cluster made by one group.
  LodSphere lodBounds;
  float error = 0.0f;
  // Its parent's: the group it was simplified in; a root's error is
  // infinite (no coarser level).
  LodSphere parentBounds;
  float parentError = std::numeric_limits<float>::infinity();
  // The groups of those two tests (ids 0 .. ClusterHierarchy::groups-1):
  // the one that made it (level 0: kNoGroup) and the one it was simplified
  // in (a root: kNoGroup). A group's children and the clusters it made
  // cover the same surface, inside the same locked border: a cut swaps
  // the one set for the other (selectClusterCut), or, while the finer set
  // is not all in memory, keeps the coarser (cluster_cut.h).
  uint32_t group = kNoGroup;
  uint32_t parentGroup = kNoGroup;
};

struct ClusterHierarchy {
  glm::dvec3 origin{0.0};            // world position of local (0, 0, 0), as MeshData's
  std::vector<glm::vec3> positions;  // one pool for every level: a locked border vertex is one entry
  std::vector<glm::vec2> uvs;        // one per position, or empty (the input had none)
  std::vector<uint32_t> indices;     // triangles, cluster by cluster
  std::vector<Cluster> clusters;     // level by level
  uint32_t levels = 0;
  uint32_t groups = 0;               // groups that made clusters (Cluster::group)
};

struct ClusterBuildReport {
  std::vector<size_t> clustersPerLevel, trianglesPerLevel;
  size_t groups = 0;
  size_t groupsKept = 0;  // simplified less than minReduction: left for the next level
  size_t roots = 0;
  double seconds = 0.0;
};

// The hierarchy of `mesh` (its triangles and UVs; vertices welded where
// position and UV are the same, so a UV seam stays two vertices a side,
// which the decimator keeps in place along their polylines). Group
// borders are locked by position, so both sides of a seam that runs along
// one stay. An empty mesh gives no cluster.
// Cancelled through `progress`: an empty hierarchy.
ClusterHierarchy buildClusterHierarchy(const MeshData& mesh, const ClusterOptions& options = {},
                                       ClusterBuildReport* report = nullptr, const Progress* progress = nullptr);

// Whether a simplification of `error` metres over `sphere` shows under
// `pixelBound` pixels to a viewer at `eye` (local coordinates) whose focal
// length is `focalPx` pixels: error * focal / distance to the sphere's
// nearest point. No error always passes; inside the sphere only none does.
bool lodFineEnough(const LodSphere& sphere, float error, const glm::vec3& eye, float focalPx, float pixelBound);

// How many triangles `cut` draws and the largest error among its clusters
// (no point of the cut is further than that from the input).
struct CutSummary {
  size_t triangles = 0;
  float maxError = 0.0f;
};
CutSummary summariseCut(const ClusterHierarchy& h, const std::vector<uint32_t>& cut);

// The triangles of `cut` as a mesh of their own vertices (with UVs where
// the hierarchy has them): what a view of the cut shows, for measuring.
MeshData meshOfCut(const ClusterHierarchy& h, const std::vector<uint32_t>& cut);

// The clusters of the cut for that viewer: each one whose own test passes
// and whose parent's fails, in the hierarchy's order.
std::vector<uint32_t> selectClusterCut(const ClusterHierarchy& h, const glm::vec3& eye, float focalPx,
                                       float pixelBound);

// The cut one bound of `error` metres takes everywhere (each cluster whose
// own error is at most that and whose parent's is over it; crack-free like
// any cut), for the smallest error whose cut has at most `maxTriangles`
// (the roots when none has): a coarse stand-in for the whole scan.
std::vector<uint32_t> uniformClusterCut(const ClusterHierarchy& h, size_t maxTriangles, float* error = nullptr);

}  // namespace hs::mesh
