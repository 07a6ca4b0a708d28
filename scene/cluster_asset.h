#pragma once
// A huge scan in the document as a cluster hierarchy (issue 38; built by
// meshproc/cluster_hierarchy.h, paged by meshproc/cluster_pages.h): its
// index (every cluster's bounds and LOD tests, always in memory, enough to
// choose a cut) and its pages, read on demand through a ClusterPageStore.
//
// In the .hscene file every page and the index are blobs keyed by their own
// content hash, "clusters/<hash>" and "clusters/index/<hash>" (as "lut/<hash>"): a save writes only the
// pages the file lacks (none after the first save of a scan), two assets
// with the same pages share them, and a page read back is checked against
// the hash its key names. The description keeps the index blob's hash
// (MeshAsset::clustersHash); the index blob holds every page's hash.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/json.h"
#include "mesh/mesh_data.h"
#include "meshproc/cluster_build_streamed.h"
#include "meshproc/cluster_pages.h"

namespace hs::scene {

// Where a hierarchy's pages come from: memory right after a build, the
// scene file once it is saved or loaded. Thread-safe: the renderer's
// streaming worker reads while the UI thread saves.
class ClusterPageStore {
 public:
  // Pages held in memory (a fresh build), with their hashes; or in the
  // scene file `path` (blobs "clusters/<hash>"). Use inMemory / inFile.
  ClusterPageStore(std::vector<std::vector<uint8_t>> pages, std::vector<uint64_t> hashes, std::string path);
  ~ClusterPageStore();
  ClusterPageStore(const ClusterPageStore&) = delete;
  ClusterPageStore& operator=(const ClusterPageStore&) = delete;

  size_t pageCount() const { return hashes_.size(); }
  uint64_t pageHash(uint32_t page) const { return hashes_[page]; }
  const std::vector<uint64_t>& pageHashes() const { return hashes_; }

  // Page `page`'s bytes, checked against its hash; nullopt with `error`
  // naming the file (or "memory"), the page and what is wrong.
  std::optional<std::vector<uint8_t>> read(uint32_t page, std::string& error) const;
  // The scene file the pages are read from; "" while they are in memory.
  std::string file() const;
  // A save wrote every page to `path`: read them from there from now on
  // and drop the copy in memory (memory then holds only what the renderer
  // asks for, whatever the scan's size).
  void settle(const std::string& path);
  // The page hashes live stores still read from `path`: such blobs are
  // kept when a save no longer needs them (an undo may bring their asset
  // back).
  static std::unordered_set<uint64_t> inUse(const std::string& path);
  // Bytes of pages held in memory (0 once settled in a file).
  uint64_t memoryBytes() const;
  // Makes a store that inUse sees.
  static std::shared_ptr<ClusterPageStore> inMemory(std::vector<std::vector<uint8_t>> pages,
                                                    std::vector<uint64_t> hashes);
  static std::shared_ptr<ClusterPageStore> inFile(const std::string& path, std::vector<uint64_t> hashes);
  // Pages a streamed build wrote one after another into a scratch file
  // (`offsets`, `sizes`): read from there until a save settles them in a
  // scene file; the scratch file is removed then, or with the store.
  static std::shared_ptr<ClusterPageStore> inScratch(const std::string& scratchPath, std::vector<uint64_t> offsets,
                                                     std::vector<uint32_t> sizes, std::vector<uint64_t> hashes);
  // Bytes of pages in a scratch file (0 once settled).
  uint64_t scratchBytes() const;

 private:
  struct File;
  mutable std::mutex mutex_;
  std::vector<uint64_t> hashes_;
  std::vector<std::vector<uint8_t>> memory_;  // empty once settled
  std::string scratch_;                       // a streamed build's page file ("" once settled)
  std::vector<uint64_t> scratchOffsets_;
  std::vector<uint32_t> scratchSizes_;
  std::string path_;
  mutable std::unique_ptr<File> file_;        // the open connection, made on first read
};

struct ClusterAsset {
  mesh::ClusterIndex index;
  std::vector<uint32_t> pageBytes;               // each page's encoded size
  std::shared_ptr<ClusterPageStore> pages;       // shared by every copy of the asset (undo)
  size_t levels() const;
  size_t triangles(uint32_t level) const;        // of every cluster of that level
  uint64_t totalPageBytes() const;
  // Page `page` decoded and checked against the index; `what` names the asset.
  std::optional<std::vector<mesh::PageCluster>> loadPage(uint32_t page, const std::string& what,
                                                         std::string& error) const;
};

// A page's blob, and an index's (its own prefix, so a save counts it apart).
std::string clusterBlobKey(uint64_t hash);
std::string clusterIndexBlobKey(uint64_t hash);

// What `info` and the editor show of a hierarchy: "levels", "clusters",
// "triangles" (level 0's), "pages", "page_bytes" (all pages), "index_bytes"
// (always in memory), "pages_in_memory_bytes" (before the first save),
// "pages_in_scratch_bytes" (a streamed build's, before the first save),
// "per_level": [{"level", "clusters", "triangles"}], "file" (where the
// pages are read from; null: memory).
Json clusterSummaryJson(const ClusterAsset& asset);

// The index blob: the cluster index (cluster_pages.h) and every page's hash
// and size. Its content hash is MeshAsset::clustersHash.
std::vector<uint8_t> encodeClusterAssetIndex(const ClusterAsset& asset);
// The asset from its index blob, with no page store yet; nullopt with
// `error` (starting with `what`) when the bytes are damaged or the index is
// not sound (mesh::clusterIndexProblem: errors not monotonic, ...).
std::optional<ClusterAsset> decodeClusterAssetIndex(const std::vector<uint8_t>& bytes, const std::string& what,
                                                    std::string& error, std::vector<uint64_t>& pageHashes);

// A freshly built hierarchy's pages as an asset (pages held in memory until
// the first save settles them).
ClusterAsset clusterAssetOf(mesh::ClusterPages pages);

// The content hash of the asset's index blob (MeshAsset::clustersHash).
uint64_t clusterIndexHash(const ClusterAsset& asset);

// A mesh made a cluster hierarchy, as `import --clusters` stores it (and
// the demo, the tests and bench_clusters_render): the asset with its hash,
// and its coarse stand-in, the uniform cut of at most `proxyTriangles`
// triangles (mesh::uniformClusterCut) with vertex normals, one submesh and
// no materials or textures yet (the caller moves or copies the input's).
struct ClusterBuild {
  std::shared_ptr<const ClusterAsset> clusters;  // null when cancelled
  uint64_t clustersHash = 0;
  mesh::MeshData proxy;
  float proxyError = 0.0f;  // metres: the stand-in's error
  mesh::ClusterBuildReport report;
};
ClusterBuild buildClusterAsset(const mesh::MeshData& input, const mesh::ClusterOptions& options,
                               size_t proxyTriangles, const Progress* progress = nullptr);
// The same from a hierarchy built elsewhere (a 3D Tiles import:
// meshproc/cluster_from_tiles.h); `report` is left empty.
ClusterBuild clusterAssetOfHierarchy(const mesh::ClusterHierarchy& h, size_t proxyTriangles);
// The same built out of core from tiles read one at a time
// (meshproc/cluster_build_streamed.h): pages go to a scratch file in
// options.scratchDir (or the system's temp folder) as they are made, so
// memory holds the index and one cell's build whatever the scan's size;
// the stand-in is read back from the pages (their normals). Null clusters
// with `error` when it failed, without when cancelled.
ClusterBuild buildClusterAssetStreamed(mesh::ScanTileSource& tiles, const mesh::StreamedClusterOptions& options,
                                       size_t proxyTriangles, mesh::StreamedClusterReport* report,
                                       const Progress* progress, std::string& error);

}  // namespace hs::scene
