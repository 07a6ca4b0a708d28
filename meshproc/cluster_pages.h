#pragma once
// A cluster hierarchy (cluster_hierarchy.h) as pages, for storage and
// streaming (issue 38 item 2; scene/cluster_file.h stores them): a
// small index, always loaded, with every cluster's LOD tests, groups and
// bounds and the page it lives in (a cut is chosen from the index alone), and
// pages of about 16 KB, each holding whole clusters in the hierarchy's
// order (clusters of one level, neighbours along the grouping's Morton
// order) with their own vertices, so a page decodes without any other.
// Vertex normals are stored (octahedral, 4 bytes): each from the faces
// around its position among the clusters of its level, so neighbours of
// one level shade without a seam whatever page they sit in.
// Decoding checks everything it reads: a truncated or damaged page or
// index, a cluster with an index past its vertices, a non-finite number,
// or an index whose errors are not monotonic is refused with a message
// naming the page (or the cluster) and what is wrong.
#include <cstdint>
#include <functional>
#include <optional>
#include <unordered_map>
#include <string>
#include <vector>

#include "meshproc/cluster_hierarchy.h"

namespace hs::mesh {

struct ClusterIndexEntry {
  uint32_t page = 0;
  uint32_t level = 0;
  uint32_t triangleCount = 0;
  uint32_t vertexCount = 0;  // its own vertices in its page
  uint32_t group = kNoGroup, parentGroup = kNoGroup;  // as Cluster's
  LodSphere bounds, lodBounds, parentBounds;
  float error = 0.0f, parentError = 0.0f;
};

struct ClusterIndex {
  glm::dvec3 origin{0.0};
  bool hasUvs = false;
  uint32_t pageCount = 0;
  uint32_t groupCount = 0;
  std::vector<ClusterIndexEntry> clusters;  // the hierarchy's order, pages in order
  // Derived (not stored): page p holds clusters [pageFirst[p], pageFirst[p + 1]).
  std::vector<uint32_t> pageFirst;
};

// One cluster as a page holds it: its own vertices and triangles.
struct PageCluster {
  uint32_t cluster = 0;  // into ClusterIndex::clusters
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // one per position, unit (stored as 2x16-bit octahedral)
  std::vector<glm::vec2> uvs;       // one per position, or none
  std::vector<uint8_t> triangles;   // three local vertex indices a triangle
};

struct ClusterPages {
  ClusterIndex index;
  std::vector<std::vector<uint8_t>> pages;  // encoded (decodeClusterPage)
  // The index's order: entry i is the hierarchy's cluster order[i]
  // (level by level, siblings together; paginate).
  std::vector<uint32_t> order;
};

// Pages of about `pageBytes` (a cluster is never split; one larger than
// that has a page of its own). 16 KB (about seven clusters): a view's cut
// draws a few clusters of each page it touches, so small pages waste the
// least of a memory budget. Measured on test_cluster_render's survey
// flight (1.28M triangles, 160x120, 1 px): the cut drew from 4.3% of the
// scan's pages at 16 KB, 6.9% at 32 KB and 9.9% at 64 KB.
ClusterPages paginate(const ClusterHierarchy& h, size_t pageBytes = size_t(16) << 10);

// Vertex normals (not normalised) by position (position_key.h): the
// area-weighted faces of clusters `ids` around each position, so both sides
// of a UV seam get one normal.
std::unordered_map<uint64_t, glm::vec3> normalsByPosition(const ClusterHierarchy& h, const std::vector<uint32_t>& ids);

// Clusters into pages one after another (paginate; the streamed build
// pages each level as it is made): a page is closed and handed to `emit`
// when the next cluster would take it past `pageBytes`, or by finish().
class ClusterPageWriter {
 public:
  ClusterPageWriter(bool uvs, size_t pageBytes, std::function<void(std::vector<uint8_t>&&)> emit);
  // Cluster `id` of `h` as index entry `at`, its vertices' normals looked
  // up by position in `normals` (normalsByPosition); fills `entry` (its
  // page and counts, and the cluster's tests as they are now).
  void add(uint32_t at, const ClusterHierarchy& h, uint32_t id, const std::unordered_map<uint64_t, glm::vec3>& normals,
           ClusterIndexEntry& entry);
  void finish();
  uint32_t pages() const { return pages_; }  // emitted so far

 private:
  bool uvs_;
  size_t pageBytes_;
  std::function<void(std::vector<uint8_t>&&)> emit_;
  std::vector<uint8_t> page_;
  uint32_t inPage_ = 0, pages_ = 0;
};

// The most vertices and triangle corners any one page of `index` holds
// (what a slot holding any page needs).
struct PageExtent {
  size_t vertices = 0, indices = 0;
};
PageExtent largestPage(const ClusterIndex& index);

std::vector<uint8_t> encodeClusterIndex(const ClusterIndex& index);
// The index from its bytes; nullopt with `error` (starting with `what`)
// when the bytes are not a whole, sound index (clusterIndexProblem).
std::optional<ClusterIndex> decodeClusterIndex(const uint8_t* data, size_t size, const std::string& what,
                                               std::string& error);
// Why `index` cannot be drawn from: a page past the page count or out of
// order, a non-finite or negative bound, an error larger than its parent's,
// a sphere outside its parent's, a group id out of range or whose clusters
// disagree on its test; "" when sound. Fills index.pageFirst.
std::string clusterIndexProblem(ClusterIndex& index);


// Page `page` of `index` from its bytes: its clusters, checked against the
// index (the clusters it should hold, their triangle counts); nullopt with
// `error` (starting with `what` and naming the page) otherwise.
std::optional<std::vector<PageCluster>> decodeClusterPage(const uint8_t* data, size_t size, const ClusterIndex& index,
                                                          uint32_t page, const std::string& what, std::string& error);

}  // namespace hs::mesh
