#include "scene/cluster_file.h"

#include <set>
#include <stdexcept>
#include <string_view>

#include "core/content_hash.h"
#include "scene/blob_parts.h"
#include "scene/cluster_asset.h"

namespace hs::scene {
namespace {

constexpr const char* kPrefix = "clusters/";


std::string assetName(const std::string& path, const MeshAsset& a) {
  return path + ": mesh asset " + std::to_string(a.id) + " ('" + a.name + "')";
}

}  // namespace

void addClusterBlobs(const SceneState& state, std::map<std::string, BlobSource>& out) {
  for (const auto& [id, a] : state.assets) {
    if (!a.clusters) continue;
    const auto c = a.clusters;
    out[clusterIndexBlobKey(a.clustersHash)] = {toHex(a.clustersHash), [c] { return encodeClusterAssetIndex(*c); }};
    for (uint32_t p = 0; p < c->pages->pageCount(); ++p) {
      const uint64_t h = c->pages->pageHash(p);
      BlobSource s{toHex(h), [c, p, name = a.name] {
                     std::string error;
                     auto bytes = c->pages->read(p, error);
                     // The file lacks a page and its store cannot give it:
                     // the save fails (writeContent) and changes nothing.
                     if (!bytes) throw std::runtime_error("mesh asset '" + name + "': " + error);
                     return std::move(*bytes);
                   }};
      s.clusterPage = true;
      out[clusterBlobKey(h)] = std::move(s);
    }
  }
}

bool keepClusterBlob(const std::string& path, const std::string& key,
                     std::optional<std::unordered_set<uint64_t>>& live) {
  if (key.rfind(kPrefix, 0) != 0) return false;
  if (!live) live = ClusterPageStore::inUse(path);
  uint64_t v = 0;
  return fromHex(std::string_view(key).substr(std::string_view(kPrefix).size()), v) && live->count(v) > 0;
}

void settleClusterPages(const SceneState& state, const std::string& path) {
  for (const auto& [id, a] : state.assets)
    if (a.clusters && a.clusters->pages) a.clusters->pages->settle(path);
}

bool loadClusterIndexes(SqliteDb& db, SceneState& state, const std::string& path, std::vector<std::string>& warnings,
                        std::string& error) {
  // Which cluster blobs the file has (keys only: no page is read).
  std::set<std::string> present;
  {
    SqliteStmt q(db, "SELECT key FROM blobs WHERE part = 0 AND key >= 'clusters/' AND key < 'clusters0'");
    std::string e;
    while (q.step(e)) present.insert(q.text(0));
    if (!e.empty()) {
      error = path + ": the scene file is damaged (" + e + ")";
      return false;
    }
  }
  std::set<std::string> used;
  SqliteStmt q(db, kReadBlobPartsSql);
  for (auto& [id, a] : state.assets) {
    if (a.clustersHash == 0) continue;
    const std::string what = assetName(path, a);
    const std::string key = clusterIndexBlobKey(a.clustersHash);
    std::string problem, e;
    std::vector<uint8_t> bytes;
    switch (readBlobParts(q, key, bytes, e)) {
      case BlobRead::Ok: break;
      case BlobRead::PartMissing: problem = what + ": a part of its cluster index is missing (damaged file)"; break;
      case BlobRead::Failed: problem = what + ": the scene file is damaged (" + e + ")"; break;
      case BlobRead::Missing: problem = what + ": its cluster index is missing from the file"; break;
    }
    if (problem.empty() && contentHash(bytes.data(), bytes.size()) != a.clustersHash)
      problem = what + ": its cluster index does not match its checksum (damaged file)";
    std::vector<uint64_t> hashes;
    std::optional<ClusterAsset> c;
    if (problem.empty() && !(c = decodeClusterAssetIndex(bytes, what, problem, hashes))) {
    }
    if (!problem.empty()) {
      warnings.push_back(problem + "; its cluster hierarchy was dropped and it draws its coarse mesh (import the "
                                   "scan again with --clusters to rebuild it)");
      a.clustersHash = 0;
      continue;
    }
    used.insert(key);
    size_t missing = 0;
    std::string firstMissing;
    for (size_t p = 0; p < hashes.size(); ++p) {
      const std::string pk = clusterBlobKey(hashes[p]);
      used.insert(pk);
      if (!present.count(pk) && missing++ == 0) firstMissing = std::to_string(p);
    }
    if (missing)
      warnings.push_back(what + ": " + std::to_string(missing) + " of its " + std::to_string(hashes.size()) +
                         " cluster pages are missing from the file (first: page " + firstMissing +
                         "); where they are needed the coarser level is drawn");
    c->pages = ClusterPageStore::inFile(path, std::move(hashes));
    a.clusters = std::make_shared<const ClusterAsset>(std::move(*c));
  }
  size_t unused = 0;
  for (const std::string& k : present) unused += !used.count(k);
  if (unused)
    warnings.push_back(path + ": " + std::to_string(unused) +
                       " stored cluster block(s) belong to no asset; they were ignored and the next save removes "
                       "them");
  return true;
}

}  // namespace hs::scene
