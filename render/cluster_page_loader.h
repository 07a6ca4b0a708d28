#pragma once
// Cluster pages (scene/cluster_asset.h) read and decoded off the render
// thread, kept in a CPU cache under a budget (issue 38 item 4). GL-free:
// the renderer (cluster_source.h) uploads what arrives.
//
// One worker thread reads the pages the latest frame asked for, in the
// order asked (most wanted first); a new ask replaces the old one, so a
// camera that moved on does not wait for pages it no longer needs. A
// decoded page stays in the cache until the least recently used pages
// have to make room for newer ones over the budget; a page that fails to
// read or decode is remembered with its message and not asked for again
// (the cut keeps its coarser level there).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "scene/cluster_asset.h"

namespace hs::render {

// One page ready to upload: its vertices and its triangles' indices (into
// the page's vertices), cluster by cluster in the page's order.
struct DecodedPage {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;  // one per vertex (zeros when the scan has none)
  std::vector<uint32_t> indices;
  std::vector<uint32_t> clusterFirstIndex;  // per cluster of the page, into `indices`
  size_t bytes() const {
    return positions.size() * 32 + indices.size() * 4 + clusterFirstIndex.size() * 4;
  }
};

// The page's vertices and triangles laid out for drawing.
DecodedPage layOutPage(const std::vector<mesh::PageCluster>& clusters);

struct PageKey {
  const scene::ClusterAsset* asset = nullptr;
  uint32_t page = 0;
  bool operator<(const PageKey& o) const { return asset != o.asset ? asset < o.asset : page < o.page; }
  bool operator==(const PageKey& o) const { return asset == o.asset && page == o.page; }
};

struct PageRequest {
  std::shared_ptr<const scene::ClusterAsset> asset;  // kept alive while asked for
  uint32_t page = 0;
  std::string what;  // names the asset in messages ("scene.hscene: mesh asset 3 ('Scan')")
};

class ClusterPageLoader {
 public:
  ClusterPageLoader();
  ~ClusterPageLoader();
  ClusterPageLoader(const ClusterPageLoader&) = delete;
  ClusterPageLoader& operator=(const ClusterPageLoader&) = delete;

  void setBudget(size_t bytes);
  // The pages to read, most wanted first; replaces the last ask. Cached
  // and failed pages are left out.
  void want(std::vector<PageRequest> pages);
  // A decoded page from the cache (marked as used), or null.
  std::shared_ptr<const DecodedPage> get(const PageKey& key);
  bool failed(const PageKey& key) const;
  // Messages of pages that failed since the last call.
  std::vector<std::string> takeProblems();
  // Blocks until every page asked for is cached or has failed.
  void waitIdle();
  // Drops every page of `asset` (it left the scene).
  void forget(const scene::ClusterAsset* asset);

  size_t cachedBytes() const;
  size_t cachedPages() const;
  size_t pending() const;

 private:
  void run();
  void trim();  // under the lock

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<PageRequest> queue_;
  bool working_ = false, stop_ = false;
  size_t budget_ = size_t(2048) << 20;
  struct Entry {
    std::shared_ptr<const DecodedPage> page;
    std::list<PageKey>::iterator lru;
  };
  std::map<PageKey, Entry> cache_;
  std::list<PageKey> lru_;  // front: most recently used
  size_t bytes_ = 0;
  std::map<PageKey, std::string> failed_;
  std::vector<std::string> problems_;
  std::thread worker_;
};

}  // namespace hs::render
