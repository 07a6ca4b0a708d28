#include "scene/cluster_asset.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "core/content_hash.h"
#include "core/scratch_files.h"
#include "meshproc/cluster_cut.h"
#include "scene/blob_parts.h"
#include "scene/sqlite_db.h"

namespace hs::scene {
namespace {

constexpr char kMagic[4] = {'H', 'S', 'C', 'A'};
constexpr uint32_t kVersion = 1;


// One spelling per file, so "a/../s.hscene" and "s.hscene" are one file.
std::string samePathKey(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

// Every live store, so a save can ask whether a blob it no longer needs is
// still read by one (undo history).
std::mutex& registryMutex() {
  static std::mutex m;
  return m;
}
std::vector<std::weak_ptr<ClusterPageStore>>& registry() {
  static std::vector<std::weak_ptr<ClusterPageStore>> r;
  return r;
}

}  // namespace

struct ClusterPageStore::File {
  SqliteDb db;
  std::unique_ptr<SqliteStmt> read;
};

ClusterPageStore::ClusterPageStore(std::vector<std::vector<uint8_t>> pages, std::vector<uint64_t> hashes,
                                   std::string path)
    : hashes_(std::move(hashes)), memory_(std::move(pages)), path_(std::move(path)) {}

std::shared_ptr<ClusterPageStore> ClusterPageStore::inMemory(std::vector<std::vector<uint8_t>> pages,
                                                             std::vector<uint64_t> hashes) {
  auto s = std::make_shared<ClusterPageStore>(std::move(pages), std::move(hashes), std::string());
  std::lock_guard lock(registryMutex());
  registry().push_back(s);
  return s;
}

std::shared_ptr<ClusterPageStore> ClusterPageStore::inFile(const std::string& path, std::vector<uint64_t> hashes) {
  auto s = std::make_shared<ClusterPageStore>(std::vector<std::vector<uint8_t>>{}, std::move(hashes),
                                              samePathKey(path));
  std::lock_guard lock(registryMutex());
  registry().push_back(s);
  return s;
}

std::shared_ptr<ClusterPageStore> ClusterPageStore::inScratch(const std::string& scratchPath,
                                                              std::vector<uint64_t> offsets,
                                                              std::vector<uint32_t> sizes,
                                                              std::vector<uint64_t> hashes) {
  auto s = std::make_shared<ClusterPageStore>(std::vector<std::vector<uint8_t>>{}, std::move(hashes), std::string());
  s->scratch_ = scratchPath;
  s->scratchOffsets_ = std::move(offsets);
  s->scratchSizes_ = std::move(sizes);
  std::lock_guard lock(registryMutex());
  registry().push_back(s);
  return s;
}

ClusterPageStore::~ClusterPageStore() {
  if (!scratch_.empty()) {
    std::error_code ec;
    std::filesystem::remove(scratch_, ec);
  }
}

uint64_t ClusterPageStore::scratchBytes() const {
  std::lock_guard lock(mutex_);
  return scratch_.empty() ? 0 : std::accumulate(scratchSizes_.begin(), scratchSizes_.end(), uint64_t(0));
}

uint64_t ClusterPageStore::memoryBytes() const {
  std::lock_guard lock(mutex_);
  uint64_t n = 0;
  for (const auto& p : memory_) n += p.size();
  return n;
}

std::string ClusterPageStore::file() const {
  std::lock_guard lock(mutex_);
  return path_;
}

void ClusterPageStore::settle(const std::string& path) {
  std::lock_guard lock(mutex_);
  memory_.clear();
  memory_.shrink_to_fit();
  if (!scratch_.empty()) {
    std::error_code ec;
    std::filesystem::remove(scratch_, ec);
    scratch_.clear();
    scratchOffsets_ = {};
    scratchSizes_ = {};
  }
  const std::string key = samePathKey(path);
  if (path_ != key) file_.reset();  // the next read opens the new file
  path_ = key;
}

std::unordered_set<uint64_t> ClusterPageStore::inUse(const std::string& path) {
  const std::string key = samePathKey(path);
  std::unordered_set<uint64_t> out;
  std::lock_guard lock(registryMutex());
  auto& r = registry();
  r.erase(std::remove_if(r.begin(), r.end(), [](const auto& w) { return w.expired(); }), r.end());
  for (const auto& w : r)
    if (auto s = w.lock(); s && s->file() == key) out.insert(s->hashes_.begin(), s->hashes_.end());
  return out;
}

std::optional<std::vector<uint8_t>> ClusterPageStore::read(uint32_t page, std::string& error) const {
  std::lock_guard lock(mutex_);
  const std::string where = (!scratch_.empty() ? scratch_ : path_.empty() ? std::string("memory") : path_) +
                            ": cluster page " +
                            std::to_string(page);
  if (page >= hashes_.size()) {
    error = where + ": there is no such page (" + std::to_string(hashes_.size()) + " pages)";
    return std::nullopt;
  }
  std::vector<uint8_t> bytes;
  if (!memory_.empty()) {
    bytes = memory_[page];
  } else if (!scratch_.empty()) {
    std::FILE* f = std::fopen(scratch_.c_str(), "rb");
    bytes.resize(scratchSizes_[page]);
    const bool ok = f && std::fseek(f, long(scratchOffsets_[page]), SEEK_SET) == 0 &&
                    std::fread(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (f) std::fclose(f);
    if (!ok) {
      error = where + ": cannot read the build's page file";
      return std::nullopt;
    }
  } else {
    if (!file_) {
      auto f = std::make_unique<File>();
      if (!f->db.open(path_, true, false, error)) {
        error = where + ": cannot open the scene file (" + error + ")";
        return std::nullopt;
      }
      f->read = std::make_unique<SqliteStmt>(f->db, kReadBlobPartsSql);
      if (!f->read->ok()) {
        error = where + ": the scene file has no readable blob table (" + f->db.lastError() + ")";
        return std::nullopt;
      }
      file_ = std::move(f);
    }
    std::string e;
    if (const BlobRead r = readBlobParts(*file_->read, clusterBlobKey(hashes_[page]), bytes, e); r != BlobRead::Ok) {
      error = where + ": " + blobReadProblem(r, e);
      return std::nullopt;
    }
  }
  if (contentHash(bytes.data(), bytes.size()) != hashes_[page]) {
    error = where + ": its data does not match its checksum (damaged file)";
    return std::nullopt;
  }
  return bytes;
}

size_t ClusterAsset::levels() const {
  uint32_t n = 0;
  for (const auto& c : index.clusters) n = std::max(n, c.level + 1);
  return n;
}

size_t ClusterAsset::triangles(uint32_t level) const {
  size_t n = 0;
  for (const auto& c : index.clusters)
    if (c.level == level) n += c.triangleCount;
  return n;
}

uint64_t ClusterAsset::totalPageBytes() const {
  return std::accumulate(pageBytes.begin(), pageBytes.end(), uint64_t(0));
}

std::optional<std::vector<mesh::PageCluster>> ClusterAsset::loadPage(uint32_t page, const std::string& what,
                                                                     std::string& error) const {
  if (!pages) {
    error = what + ": its cluster pages are not available";
    return std::nullopt;
  }
  std::string e;
  const auto bytes = pages->read(page, e);
  if (!bytes) {
    error = what + ": " + e;
    return std::nullopt;
  }
  return mesh::decodeClusterPage(bytes->data(), bytes->size(), index, page, what, error);
}

Json clusterSummaryJson(const ClusterAsset& a) {
  Json o = Json::object();
  const size_t levels = a.levels();
  o["levels"] = levels;
  o["clusters"] = a.index.clusters.size();
  o["pages"] = a.pageBytes.size();
  o["page_bytes"] = a.totalPageBytes();
  o["index_bytes"] = a.index.clusters.size() * sizeof(mesh::ClusterIndexEntry) + a.pageBytes.size() * 12;
  o["pages_in_memory_bytes"] = a.pages ? a.pages->memoryBytes() : 0;
  o["pages_in_scratch_bytes"] = a.pages ? a.pages->scratchBytes() : 0;
  const std::string file = a.pages ? a.pages->file() : std::string();
  o["file"] = file.empty() ? Json(nullptr) : Json(file);
  std::vector<size_t> clusters(levels, 0), triangles(levels, 0);
  for (const auto& c : a.index.clusters) ++clusters[c.level], triangles[c.level] += c.triangleCount;
  o["triangles"] = levels ? triangles[0] : 0;  // level 0: the scan's own
  Json per = Json::array();
  for (size_t l = 0; l < levels; ++l)
    per.push_back(Json{{"level", l}, {"clusters", clusters[l]}, {"triangles", triangles[l]}});
  o["per_level"] = std::move(per);
  return o;
}

std::string clusterBlobKey(uint64_t hash) { return "clusters/" + toHex(hash); }

std::string clusterIndexBlobKey(uint64_t hash) { return "clusters/index/" + toHex(hash); }

std::vector<uint8_t> encodeClusterAssetIndex(const ClusterAsset& asset) {
  const std::vector<uint8_t> index = mesh::encodeClusterIndex(asset.index);
  const auto& hashes = asset.pages->pageHashes();
  std::vector<uint8_t> out(4 + 4 + 4 + hashes.size() * 12 + 8);
  uint8_t* p = out.data();
  auto put = [&](const void* v, size_t n) {
    std::memcpy(p, v, n);
    p += n;
  };
  put(kMagic, 4);
  put(&kVersion, 4);
  const uint32_t count = uint32_t(hashes.size());
  put(&count, 4);
  for (size_t i = 0; i < hashes.size(); ++i) {
    put(&hashes[i], 8);
    put(&asset.pageBytes[i], 4);
  }
  const uint64_t n = index.size();
  put(&n, 8);
  out.insert(out.end(), index.begin(), index.end());
  return out;
}

std::optional<ClusterAsset> decodeClusterAssetIndex(const std::vector<uint8_t>& bytes, const std::string& what,
                                                    std::string& error, std::vector<uint64_t>& pageHashes) {
  const uint8_t* p = bytes.data();
  size_t left = bytes.size();
  auto get = [&](void* v, size_t n) {
    if (left < n) return false;
    std::memcpy(v, p, n);
    p += n, left -= n;
    return true;
  };
  char magic[4];
  uint32_t version = 0, count = 0;
  if (!get(magic, 4) || std::memcmp(magic, kMagic, 4) != 0 || !get(&version, 4)) {
    error = what + ": its cluster index is damaged (not a cluster index)";
    return std::nullopt;
  }
  if (version != kVersion) {
    error = what + ": its cluster index is of version " + std::to_string(version) + ", this build reads " +
            std::to_string(kVersion);
    return std::nullopt;
  }
  if (!get(&count, 4) || left / 12 < count) {
    error = what + ": its cluster index is damaged (truncated page table)";
    return std::nullopt;
  }
  ClusterAsset a;
  pageHashes.assign(count, 0);
  a.pageBytes.assign(count, 0);
  for (uint32_t i = 0; i < count; ++i) get(&pageHashes[i], 8), get(&a.pageBytes[i], 4);
  uint64_t n = 0;
  if (!get(&n, 8) || n != left) {
    error = what + ": its cluster index is damaged (truncated)";
    return std::nullopt;
  }
  auto index = mesh::decodeClusterIndex(p, left, what, error);
  if (!index) return std::nullopt;
  if (index->pageCount != count) {
    error = what + ": its cluster index names " + std::to_string(index->pageCount) + " pages but lists " +
            std::to_string(count);
    return std::nullopt;
  }
  a.index = std::move(*index);
  return a;
}

uint64_t clusterIndexHash(const ClusterAsset& asset) {
  const std::vector<uint8_t> bytes = encodeClusterAssetIndex(asset);
  return contentHash(bytes.data(), bytes.size());
}

ClusterBuild buildClusterAsset(const mesh::MeshData& input, const mesh::ClusterOptions& options,
                               size_t proxyTriangles, const Progress* progress) {
  mesh::ClusterBuildReport report;
  mesh::ClusterHierarchy h = mesh::buildClusterHierarchy(input, options, &report, progress);
  if (isCancelled(progress)) {
    ClusterBuild b;
    b.report = report;
    return b;
  }
  ClusterBuild b = clusterAssetOfHierarchy(h, proxyTriangles);
  b.report = report;
  return b;
}

ClusterBuild clusterAssetOfHierarchy(const mesh::ClusterHierarchy& h, size_t proxyTriangles) {
  ClusterBuild b;
  b.proxy = mesh::meshOfCut(h, mesh::uniformClusterCut(h, proxyTriangles, &b.proxyError));
  mesh::computeVertexNormals(b.proxy);
  ClusterAsset c = clusterAssetOf(mesh::paginate(h));
  b.clustersHash = clusterIndexHash(c);
  b.clusters = std::make_shared<const ClusterAsset>(std::move(c));
  return b;
}

ClusterAsset clusterAssetOf(mesh::ClusterPages built) {
  ClusterAsset a;
  a.index = std::move(built.index);
  std::vector<uint64_t> hashes;
  for (const auto& page : built.pages) {
    hashes.push_back(contentHash(page.data(), page.size()));
    a.pageBytes.push_back(uint32_t(page.size()));
  }
  a.pages = ClusterPageStore::inMemory(std::move(built.pages), std::move(hashes));
  return a;
}

namespace {

// The stand-in of a paged hierarchy: the uniform cut's clusters read back
// from their pages, with the pages' normals (each cluster its own vertices).
mesh::MeshData proxyFromPages(const ClusterAsset& a, size_t proxyTriangles, float& error, std::string& problem) {
  mesh::MeshData m;
  m.origin = a.index.origin;
  const std::vector<uint32_t> cut = mesh::uniformIndexCut(a.index, proxyTriangles, &error);
  std::vector<uint32_t> pages;
  for (uint32_t id : cut) pages.push_back(a.index.clusters[id].page);
  std::sort(pages.begin(), pages.end());
  pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
  std::vector<bool> wanted(a.index.clusters.size(), false);
  for (uint32_t id : cut) wanted[id] = true;
  for (uint32_t p : pages) {
    auto clusters = a.loadPage(p, "the streamed build", problem);
    if (!clusters) return {};
    for (const mesh::PageCluster& c : *clusters) {
      if (!wanted[c.cluster]) continue;
      const uint32_t base = uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), c.positions.begin(), c.positions.end());
      m.normals.insert(m.normals.end(), c.normals.begin(), c.normals.end());
      m.uvs.insert(m.uvs.end(), c.uvs.begin(), c.uvs.end());
      for (uint8_t t : c.triangles) m.indices.push_back(base + t);
    }
  }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

}  // namespace

ClusterBuild buildClusterAssetStreamed(mesh::ScanTileSource& tiles, const mesh::StreamedClusterOptions& options,
                                       size_t proxyTriangles, mesh::StreamedClusterReport* report,
                                       const Progress* progress, std::string& error) {
  ClusterBuild b;
  const std::filesystem::path dir =
      options.scratchDir.empty() ? std::filesystem::temp_directory_path() : std::filesystem::path(options.scratchDir);
  // Page files of builds that crashed or were killed before their scene was saved.
  sweepStaleScratch(dir, "hs-cluster-pages-");
  const std::string path = (dir / scratchName("hs-cluster-pages-", ".bin")).string();
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) {
    error = path + ": cannot create the page file";
    return b;
  }
  std::vector<uint64_t> offsets, hashes;
  std::vector<uint32_t> sizes;
  uint64_t at = 0;
  const mesh::PageSink sink = [&](std::vector<uint8_t>&& page, std::string& e) {
    if (std::fwrite(page.data(), 1, page.size(), out) != page.size()) {
      e = path + ": cannot write a page (disk full?)";
      return false;
    }
    offsets.push_back(at);
    sizes.push_back(uint32_t(page.size()));
    hashes.push_back(contentHash(page.data(), page.size()));
    at += page.size();
    return true;
  };
  mesh::StreamedClusterReport rep;
  std::optional<mesh::ClusterIndex> index = mesh::buildClusterPagesStreamed(tiles, options, sink, &rep, progress, error);
  const bool closed = std::fclose(out) == 0;
  if (report) *report = rep;
  b.report = rep.build;
  if (!index || !closed) {
    if (index) error = path + ": cannot write the page file (disk full?)";
    std::error_code ec;
    std::filesystem::remove(path, ec);
    return b;
  }
  ClusterAsset a;
  a.index = std::move(*index);
  a.pageBytes = sizes;
  a.pages = ClusterPageStore::inScratch(path, std::move(offsets), std::move(sizes), std::move(hashes));
  std::string problem;
  b.proxy = proxyFromPages(a, proxyTriangles, b.proxyError, problem);
  if (!problem.empty()) {
    error = problem;
    return b;
  }
  b.clustersHash = clusterIndexHash(a);
  b.clusters = std::make_shared<const ClusterAsset>(std::move(a));
  return b;
}

}  // namespace hs::scene
