#include "meshproc/cluster_build_streamed.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <unordered_map>

#include "core/scratch_files.h"
#include "mesh/tile_merge.h"
#include "meshproc/cluster_levels.h"
#include "meshproc/cluster_parts.h"
#include "meshproc/position_key.h"

namespace hs::mesh {

bool MeshTileSource::readTile(size_t i, MeshData& out, std::string& error) {
  if (i >= tiles_.size() || !tiles_[i]) {
    error = "tile " + std::to_string(i) + ": not there";
    return false;
  }
  out = *tiles_[i];
  return true;
}

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kScratchPrefix = "hs-clusters-";

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A scratch file of fixed-size records, written through a buffer and read
// back in chunks. Why not memory: the scan is larger than memory.
class RecordFile {
 public:
  RecordFile(fs::path path, size_t recordFloats) : path_(std::move(path)), record_(recordFloats) {}
  ~RecordFile() {
    if (file_) std::fclose(file_);
  }
  bool append(const float* r, std::string& error) {
    if (!file_ && !open("wb", error)) return false;
    if (std::fwrite(r, sizeof(float), record_, file_) != record_) {
      error = path_.string() + ": cannot write (disk full?)";
      return false;
    }
    ++count_;
    return true;
  }
  // Calls fn(record) for each record in order.
  template <class Fn>
  bool forEach(Fn&& fn, std::string& error) {
    if (file_) std::fclose(file_), file_ = nullptr;
    if (count_ == 0) return true;
    std::FILE* f = std::fopen(path_.string().c_str(), "rb");
    if (!f) {
      error = path_.string() + ": cannot read back";
      return false;
    }
    std::vector<float> chunk(record_ * 8192);
    size_t left = count_;
    while (left > 0) {
      const size_t n = std::min<size_t>(left, 8192);
      if (std::fread(chunk.data(), sizeof(float) * record_, n, f) != n) {
        std::fclose(f);
        error = path_.string() + ": truncated while reading back";
        return false;
      }
      for (size_t i = 0; i < n; ++i) fn(chunk.data() + i * record_);
      left -= n;
    }
    std::fclose(f);
    return true;
  }
  size_t count() const { return count_; }
  uint64_t bytes() const { return uint64_t(count_) * record_ * sizeof(float); }
  void remove() {
    if (file_) std::fclose(file_), file_ = nullptr;
    std::error_code ec;
    fs::remove(path_, ec);
    count_ = 0;
  }

 private:
  bool open(const char* mode, std::string& error) {
    file_ = std::fopen(path_.string().c_str(), mode);
    if (!file_) {
      error = path_.string() + ": cannot create a scratch file";
      return false;
    }
    std::setvbuf(file_, nullptr, _IOFBF, size_t(1) << 16);
    return true;
  }
  fs::path path_;
  size_t record_;
  size_t count_ = 0;
  std::FILE* file_ = nullptr;
};

// The scratch folder, removed with everything in it however the build ends.
struct ScratchDir {
  fs::path path;
  explicit ScratchDir(const std::string& base) {
    const fs::path root = base.empty() ? fs::temp_directory_path() : fs::path(base);
    // What a crashed or killed build left here goes first (it can be the
    // size of the scan).
    sweepStaleScratch(root, kScratchPrefix);
    path = root / scratchName(kScratchPrefix);
    std::error_code ec;
    fs::create_directories(path, ec);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// The k-d tree of cells: a node splits on one axis at a value (below: the
// first child); leaves are cells, numbered left to right, so any node's
// cells are one range.
struct CellTree {
  struct Node {
    int axis = -1;  // -1: a leaf
    float split = 0.0f;
    int child[2] = {-1, -1};
    uint32_t firstCell = 0, endCell = 0;
  };
  std::vector<Node> nodes;

  uint32_t cellOf(const glm::vec3& p) const {
    int n = 0;
    while (nodes[size_t(n)].axis >= 0) n = nodes[size_t(n)].child[p[nodes[size_t(n)].axis] < nodes[size_t(n)].split ? 0 : 1];
    return nodes[size_t(n)].firstCell;
  }
  uint32_t cells() const { return nodes.empty() ? 0 : nodes[0].endCell; }

  // Medians on the longest axis of the samples until a node holds at most
  // `perCell` of them.
  int build(std::vector<glm::vec3>& s, size_t begin, size_t end, size_t perCell, uint32_t& nextCell) {
    const int id = int(nodes.size());
    nodes.push_back({});
    Node n;
    n.firstCell = nextCell;
    if (end - begin > perCell) {
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (size_t i = begin; i < end; ++i) lo = glm::min(lo, s[i]), hi = glm::max(hi, s[i]);
      const glm::vec3 e = hi - lo;
      const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
      const size_t mid = begin + (end - begin) / 2;
      std::nth_element(s.begin() + long(begin), s.begin() + long(mid), s.begin() + long(end),
                       [axis](const glm::vec3& a, const glm::vec3& b) { return a[axis] < b[axis]; });
      const float split = s[mid][axis];
      // The rule cellOf follows: below the split, the first child.
      const auto at = std::partition(s.begin() + long(begin), s.begin() + long(end),
                                     [&](const glm::vec3& p) { return p[axis] < split; });
      const size_t cut = size_t(at - s.begin());
      if (cut > begin && cut < end) {
        n.axis = axis;
        n.split = split;
        n.child[0] = build(s, begin, cut, perCell, nextCell);
        n.child[1] = build(s, cut, end, perCell, nextCell);
        n.endCell = nextCell;
        nodes[size_t(id)] = n;
        return id;
      }
    }
    n.endCell = ++nextCell;
    nodes[size_t(id)] = n;
    return id;
  }
};

// Which cells use a position that more than one uses: (key, cell) pairs,
// sorted. A position not listed is used by one cell only.
struct BorderList {
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  // Whether a cell outside [first, end) uses `p`.
  bool usedOutside(const glm::vec3& p, uint32_t first, uint32_t end) const {
    const uint64_t k = positionKey(p);
    auto it = std::lower_bound(entries.begin(), entries.end(), std::pair<uint64_t, uint32_t>(k, 0));
    for (; it != entries.end() && it->first == k; ++it)
      if (it->second < first || it->second >= end) return true;
    return false;
  }
};

// A cluster a finished cell leaves to its parent: written already (its
// global id), its tests but the parent's still open.
struct Leftover {
  uint32_t id = 0;
  Cluster cluster;                  // firstIndex unused
  std::vector<glm::vec3> corners;   // three a triangle
  std::vector<glm::vec2> uvs;       // three a triangle, or none
};

// A halo triangle: its corners and the cell it belongs to.
struct HaloFace {
  glm::vec3 p[3];
  uint32_t cell;
};

struct Builder {
  Builder(const StreamedClusterOptions& o_, const PageSink& sink_, const Progress* progress_, StreamedClusterReport& rep_,
          std::string& error_, const CellTree& tree_, const BorderList& border_, bool uvs_,
          std::vector<std::unique_ptr<RecordFile>>& cellFiles_, std::vector<std::unique_ptr<RecordFile>>& haloFiles_,
          size_t trianglesTotal_)
      : o(o_), sink(sink_), progress(progress_), rep(rep_), error(error_), tree(tree_), border(border_), uvs(uvs_),
        cellFiles(cellFiles_), haloFiles(haloFiles_), trianglesTotal(trianglesTotal_) {}
  const StreamedClusterOptions& o;
  const PageSink& sink;
  const Progress* progress;
  StreamedClusterReport& rep;
  std::string& error;
  const CellTree& tree;
  const BorderList& border;
  bool uvs;
  std::vector<std::unique_ptr<RecordFile>>& cellFiles;
  std::vector<std::unique_ptr<RecordFile>>& haloFiles;
  size_t trianglesTotal;

  std::vector<ClusterIndexEntry> entries;
  uint32_t groups = 0;
  size_t trianglesBuilt = 0;
  bool failed = false;
  ClusterPageWriter writer{uvs, o.pageBytes, [this](std::vector<uint8_t>&& page) {
                             std::string e;
                             if (!failed && !sink(std::move(page), e)) failed = true, error = e;
                           }};

  void countLevel(uint32_t level, size_t clusters, size_t triangles) {
    auto& c = rep.build.clustersPerLevel;
    auto& t = rep.build.trianglesPerLevel;
    if (c.size() <= level) c.resize(level + 1, 0), t.resize(level + 1, 0);
    c[level] += clusters, t[level] += triangles;
  }

  // Builds node `n` of the tree; its leftover clusters and the halo it
  // keeps in `out` / `outHalo`. False: failed or cancelled.
  bool build(int n, std::vector<Leftover>& out, std::vector<HaloFace>& outHalo) {
    const CellTree::Node& node = tree.nodes[size_t(n)];
    ClusterHierarchy h;
    std::vector<uint32_t> active;
    std::vector<HaloFace> halo;
    globalOf.clear();
    if (node.axis < 0) {
      if (!leaf(node.firstCell, h, active, halo)) return false;
    } else {
      std::vector<Leftover> a, b;
      std::vector<HaloFace> ha, hb;
      if (!build(node.child[0], a, ha) || !build(node.child[1], b, hb)) return false;
      globalOf.clear();
      PositionPool pool;
      join(h, a, active, pool);
      join(h, b, active, pool);
      // The children's halo faces that lie beyond this node, each once (a
      // face around a position both children use was copied to both).
      ha.insert(ha.end(), hb.begin(), hb.end());
      for (const HaloFace& f : ha)
        if (f.cell < node.firstCell || f.cell >= node.endCell) halo.push_back(f);
      auto less = [](const HaloFace& x, const HaloFace& y) { return std::memcmp(&x, &y, sizeof x) < 0; };
      auto same = [](const HaloFace& x, const HaloFace& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
      std::sort(halo.begin(), halo.end(), less);
      halo.erase(std::unique(halo.begin(), halo.end(), same), halo.end());
    }
    if (isCancelled(progress)) return false;
    if (!finishNode(node, h, active, halo, out)) return false;
    outHalo = std::move(halo);
    return true;
  }

  // A leaf cell: its triangles welded, in level-0 clusters.
  bool leaf(uint32_t cell, ClusterHierarchy& h, std::vector<uint32_t>& active, std::vector<HaloFace>& halo) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> cornerUvs;
    std::vector<uint32_t> indices;
    RecordFile& f = *cellFiles[cell];
    positions.reserve(f.count() * 3);
    if (!f.forEach(
            [&](const float* r) {
              for (int k = 0; k < 3; ++k) {
                indices.push_back(uint32_t(positions.size()));
                positions.emplace_back(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]);
                if (uvs) cornerUvs.emplace_back(r[9 + k * 2], r[10 + k * 2]);
              }
            },
            error))
      return false;
    f.remove();
    trianglesBuilt += indices.size() / 3;
    const std::vector<uint32_t> tris = weldForClusters(positions, cornerUvs, indices, h.positions, h.uvs);
    positions = {}, cornerUvs = {}, indices = {};
    if (!haloFiles[cell]->forEach(
            [&](const float* r) {
              HaloFace face;
              for (int k = 0; k < 3; ++k) face.p[k] = glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]);
              uint32_t c;
              std::memcpy(&c, &r[9], 4);
              face.cell = c;
              halo.push_back(face);
            },
            error))
      return false;
    haloFiles[cell]->remove();
    if (tris.empty()) return true;
    std::vector<uint32_t> sorted(tris.size());
    meshopt_spatialSortTriangles(sorted.data(), tris.data(), tris.size(), &h.positions[0].x, h.positions.size(),
                                 sizeof(glm::vec3));
    size_t triangles = 0;
    for (const std::vector<uint32_t>& c : meshletsOf(h.positions, sorted, o.clusters)) {
      active.push_back(uint32_t(h.clusters.size()));
      addCluster(h, c, 0, {}, 0.0f);
      triangles += c.size() / 3;
    }
    countLevel(0, active.size(), triangles);
    return true;
  }

  // A child's leftover clusters into the parent's hierarchy (vertices
  // welded where position and UV are the same, as the child had them).
  // The node's vertices by position key, for welding the two children's.
  using PositionPool = std::unordered_map<uint64_t, std::vector<uint32_t>>;
  void join(ClusterHierarchy& h, const std::vector<Leftover>& from, std::vector<uint32_t>& active,
            PositionPool& pool) {
    for (const Leftover& l : from) {
      std::vector<uint32_t> tris;
      for (size_t i = 0; i < l.corners.size(); ++i) {
        const glm::vec3& p = l.corners[i];
        std::vector<uint32_t>& same = pool[positionKey(p)];
        uint32_t v = UINT32_MAX;
        for (uint32_t s : same)
          if (h.positions[s] == p && (!uvs || h.uvs[s] == l.uvs[i])) v = s;
        if (v == UINT32_MAX) {
          v = uint32_t(h.positions.size());
          h.positions.push_back(p);
          if (uvs) h.uvs.push_back(l.uvs[i]);
          same.push_back(v);
        }
        tris.push_back(v);
      }
      Cluster c = l.cluster;
      c.firstIndex = uint32_t(h.indices.size());
      h.indices.insert(h.indices.end(), tris.begin(), tris.end());
      active.push_back(uint32_t(h.clusters.size()));
      h.clusters.push_back(c);
      globalOf.push_back(l.id);
    }
  }

  std::vector<uint32_t> globalOf;  // per cluster of the node being built: its index entry, or UINT32_MAX

  // Levels until nothing simplifies (or one root); pages written as each
  // level is grouped; what is left goes to `out`.
  bool finishNode(const CellTree::Node& node, ClusterHierarchy& h, std::vector<uint32_t>& active,
                  const std::vector<HaloFace>& halo, std::vector<Leftover>& out) {
    globalOf.resize(h.clusters.size(), UINT32_MAX);
    const bool root = node.firstCell == 0 && node.endCell == tree.cells();
    const ExternalLock lock = root ? ExternalLock{} : ExternalLock([&](const glm::vec3& p) {
      return border.usedOutside(p, node.firstCell, node.endCell);
    });
    auto normals = [&] {
      std::unordered_map<uint64_t, glm::vec3> n = normalsByPosition(h, active);
      // Faces beyond the node's border, around the positions it shares.
      for (const HaloFace& f : halo) {
        const glm::vec3 fn = glm::cross(f.p[1] - f.p[0], f.p[2] - f.p[0]);
        for (const glm::vec3& p : f.p)
          if (auto it = n.find(positionKey(p)); it != n.end()) it->second += fn;
      }
      return n;
    };
    auto write = [&](uint32_t id, const std::unordered_map<uint64_t, glm::vec3>& n) {
      if (globalOf[id] != UINT32_MAX) return;
      globalOf[id] = uint32_t(entries.size());
      ClusterIndexEntry e;
      writer.add(uint32_t(entries.size()), h, id, n, e);
      entries.push_back(e);
    };
    uint32_t level = 0;
    for (uint32_t id : active) level = std::max(level, h.clusters[id].level);
    h.groups = groups;
    while (active.size() > 1 && !failed && level < 250) {
      ++level;
      const GroupedHook paged = [&](const std::vector<std::vector<uint32_t>>& grouped) {
        const auto n = normals();
        for (const auto& g : grouped)
          for (uint32_t id : g) write(id, n);
      };
      const size_t before = h.clusters.size();
      LevelStep step = simplifyLevel(h, active, level, o.clusters, lock, paged, rep.build, progress);
      if (step.cancelled) return false;
      globalOf.resize(h.clusters.size(), UINT32_MAX);
      for (uint32_t id : active) {
        const Cluster& c = h.clusters[id];
        if (c.parentGroup == kNoGroup) continue;
        ClusterIndexEntry& e = entries[globalOf[id]];
        e.parentBounds = c.parentBounds, e.parentError = c.parentError, e.parentGroup = c.parentGroup;
      }
      if (step.simplified == 0) break;
      countLevel(level, h.clusters.size() - before, step.triangles);
      active = std::move(step.next);
      reportProgress(progress, 0.15 + 0.85 * double(trianglesBuilt) / double(std::max<size_t>(1, trianglesTotal)),
                     "Building the cluster hierarchy");
    }
    groups = h.groups;
    if (failed) return false;
    const auto n = normals();
    for (uint32_t id : active) write(id, n);
    if (root) {
      rep.build.roots = active.size();
      return !failed;
    }
    // Up to the parent: the clusters left, as triangles of their own.
    for (uint32_t id : active) {
      const Cluster& c = h.clusters[id];
      Leftover l;
      l.id = globalOf[id];
      l.cluster = c;
      for (uint32_t i = 0; i < c.triangleCount * 3; ++i) {
        const uint32_t v = h.indices[c.firstIndex + i];
        l.corners.push_back(h.positions[v]);
        if (uvs) l.uvs.push_back(h.uvs[v]);
      }
      out.push_back(std::move(l));
    }
    return !failed;
  }
};

}  // namespace

std::optional<ClusterIndex> buildClusterPagesStreamed(ScanTileSource& tiles, const StreamedClusterOptions& options,
                                                      const PageSink& sink, StreamedClusterReport* reportOut,
                                                      const Progress* progress, std::string& error) {
  StreamedClusterReport rep;
  error.clear();
  ScratchDir scratch(options.scratchDir);
  if (!fs::is_directory(scratch.path)) {
    error = scratch.path.string() + ": cannot create the scratch folder";
    return std::nullopt;
  }
  auto fail = [&](const std::string& e) -> std::optional<ClusterIndex> {
    if (!e.empty()) error = e;
    if (reportOut) *reportOut = rep;
    return std::nullopt;
  };

  // 1. Every tile once, into one scratch file of triangles (corners and
  // UVs, in the first tile's frame).
  Clock::time_point t0 = Clock::now();
  constexpr size_t kRecord = 9 + 6;
  RecordFile soup(scratch.path / "triangles", kRecord);
  glm::dvec3 origin(0.0);
  std::vector<glm::vec3> samples;
  bool anyUvs = false, allUvs = true;
  BorderSnapGrid snap(options.weldTolerance);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  rep.tiles = tiles.tileCount();
  for (size_t t = 0; t < tiles.tileCount(); ++t) {
    MeshData m;
    std::string e;
    if (!tiles.readTile(t, m, e)) return fail(e);
    if (t == 0) origin = m.origin;
    const glm::dvec3 shift = m.origin - origin;
    // The tile in the common frame, its open border snapped onto earlier
    // tiles' (as an in-memory multi-tile import welds them).
    std::vector<glm::vec3> local(m.positions.size());
    for (size_t v = 0; v < local.size(); ++v) local[v] = glm::vec3(glm::dvec3(m.positions[v]) + shift);
    if (tiles.tileCount() > 1 && options.weldTolerance > 0.0) {
      const std::vector<uint8_t> open = openBoundaryVertices(m);
      for (size_t v = 0; v < local.size(); ++v) {
        if (!open[v]) continue;
        ++rep.tileBorderVertices;
        if (const auto earlier = snap.snapOrAdd(local[v], uint32_t(rep.tileBorderVertices), uint32_t(t))) {
          if (earlier->position != local[v]) ++rep.tileBorderVerticesSnapped;
          local[v] = earlier->position;
        }
      }
    }
    const bool hasUvs = m.uvs.size() == m.positions.size() && !m.positions.empty();
    anyUvs = anyUvs || hasUvs;
    allUvs = allUvs && (hasUvs || m.indices.empty());
    float r[kRecord] = {};
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = m.indices[i + size_t(k)];
        if (v >= m.positions.size()) {
          ok = false;
          break;
        }
        const glm::vec3 p = local[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ok = false;
        r[k * 3] = p.x, r[k * 3 + 1] = p.y, r[k * 3 + 2] = p.z;
        const glm::vec2 uv = hasUvs ? m.uvs[v] : glm::vec2(0.0f);
        r[9 + k * 2] = uv.x, r[10 + k * 2] = uv.y;
      }
      if (!ok) continue;
      for (int k = 0; k < 3; ++k) lo = glm::min(lo, glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2])),
                                  hi = glm::max(hi, glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]));
      if (soup.count() % 16 == 0)
        samples.emplace_back((r[0] + r[3] + r[6]) / 3.0f, (r[1] + r[4] + r[7]) / 3.0f, (r[2] + r[5] + r[8]) / 3.0f);
      if (!soup.append(r, e)) return fail(e);
    }
    reportProgress(progress, 0.1 * double(t + 1) / double(tiles.tileCount()), "Reading the scan's tiles");
    if (isCancelled(progress)) return fail("");
  }
  rep.triangles = soup.count();
  rep.readSeconds = secondsSince(t0);
  if (rep.triangles == 0) return fail("the tiles hold no triangle");
  const bool uvs = allUvs && anyUvs;
  rep.uvsDropped = anyUvs && !allUvs;

  // The frame from here on: centred on the scan's box (to the metre), so
  // floats keep the most precision over the whole scan whichever tile came
  // first. Every pass below reads the triangles through `centred`: one
  // position always maps to one float.
  const glm::dvec3 centre = glm::round(0.5 * (glm::dvec3(lo) + glm::dvec3(hi)));
  auto centred = [&](auto&& fn) {
    return [&, fn](const float* r) {
      float c[kRecord];
      std::copy(r, r + kRecord, c);
      for (int k = 0; k < 9; ++k) c[k] = float(double(r[k]) - centre[k % 3]);
      fn(static_cast<const float*>(c));
    };
  };
  for (glm::vec3& p : samples) p = glm::vec3(glm::dvec3(p) - centre);

  // 2. Cells: a k-d tree of the centres (at most 480 cells: two files
  // open for each).
  t0 = Clock::now();
  CellTree tree;
  {
    const size_t perCell = std::max<size_t>({1, options.cellTriangles / 16, samples.size() / 480 + 1});
    uint32_t cells = 0;
    tree.build(samples, 0, samples.size(), perCell, cells);
    samples = {};
  }
  rep.cells = tree.cells();
  const size_t cellRecord = uvs ? 15 : 9;
  std::vector<std::unique_ptr<RecordFile>> cellFiles, haloFiles;
  for (uint32_t c = 0; c < tree.cells(); ++c) {
    cellFiles.push_back(std::make_unique<RecordFile>(scratch.path / ("cell" + std::to_string(c)), cellRecord));
    haloFiles.push_back(std::make_unique<RecordFile>(scratch.path / ("halo" + std::to_string(c)), 10));
  }
  BorderList border;
  auto centreCell = [&](const float* r) {
    return tree.cellOf(glm::vec3((r[0] + r[3] + r[6]) / 3.0f, (r[1] + r[4] + r[7]) / 3.0f, (r[2] + r[5] + r[8]) / 3.0f));
  };
  std::string e;
  bool ok = soup.forEach(
      centred([&](const float* r) {
        if (!e.empty()) return;
        const uint32_t cell = centreCell(r);
        float rec[15];
        std::copy(r, r + 9, rec);
        if (uvs) std::copy(r + 9, r + 15, rec + 9);
        if (!cellFiles[cell]->append(rec, e)) return;
        uint32_t corner[3];
        for (int k = 0; k < 3; ++k) corner[k] = tree.cellOf(glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]));
        if (corner[0] == cell && corner[1] == cell && corner[2] == cell) return;
        // Crosses a border: each corner is used by this cell and the one
        // it lies in (every other cell using it records itself the same way).
        for (int k = 0; k < 3; ++k) {
          const uint64_t key = positionKey(glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]));
          border.entries.push_back({key, cell});
          border.entries.push_back({key, corner[k]});
        }
      }),
      e);
  if (!ok || !e.empty()) return fail(e);
  std::sort(border.entries.begin(), border.entries.end());
  border.entries.erase(std::unique(border.entries.begin(), border.entries.end()), border.entries.end());
  {
    size_t positions = 0;
    for (size_t i = 0; i < border.entries.size(); ++i)
      if (i == 0 || border.entries[i].first != border.entries[i - 1].first) ++positions;
    rep.borderPositions = positions;
  }
  std::vector<uint32_t> haloCells;
  // Halo: each triangle around a border position, for the other cells using it.
  ok = soup.forEach(
      centred([&](const float* r) {
        if (!e.empty()) return;
        const uint32_t cell = centreCell(r);
        // Every other cell using a corner (usually one to three; a long
        // triangle's corner can be used by more than eight).
        std::vector<uint32_t>& to = haloCells;
        to.clear();
        for (int k = 0; k < 3; ++k) {
          const uint64_t key = positionKey(glm::vec3(r[k * 3], r[k * 3 + 1], r[k * 3 + 2]));
          auto it = std::lower_bound(border.entries.begin(), border.entries.end(), std::pair<uint64_t, uint32_t>(key, 0));
          for (; it != border.entries.end() && it->first == key; ++it)
            if (it->second != cell && std::find(to.begin(), to.end(), it->second) == to.end()) to.push_back(it->second);
        }
        float rec[10];
        std::copy(r, r + 9, rec);
        std::memcpy(&rec[9], &cell, 4);
        for (uint32_t c : to) {
          if (!haloFiles[c]->append(rec, e)) return;
          ++rep.haloTriangles;
        }
      }),
      e);
  if (!ok || !e.empty()) return fail(e);
  for (uint32_t c = 0; c < tree.cells(); ++c)
    rep.scratchBytes += cellFiles[c]->bytes() + haloFiles[c]->bytes();
  rep.scratchBytes += soup.bytes();
  soup.remove();
  rep.partitionSeconds = secondsSince(t0);
  reportProgress(progress, 0.15, "Building the cluster hierarchy");

  // 3. The cells, in the tree's post-order.
  t0 = Clock::now();
  Builder b(options, sink, progress, rep, error, tree, border, uvs, cellFiles, haloFiles, rep.triangles);
  std::vector<Leftover> top;
  std::vector<HaloFace> topHalo;
  const bool built = b.build(0, top, topHalo);
  if (!built || b.failed) return fail(isCancelled(progress) ? "" : error);
  b.writer.finish();
  if (b.failed) return fail(error);
  rep.buildSeconds = secondsSince(t0);
  rep.build.seconds = rep.readSeconds + rep.partitionSeconds + rep.buildSeconds;

  ClusterIndex index;
  index.origin = origin + centre;
  index.hasUvs = uvs;
  index.pageCount = b.writer.pages();
  index.groupCount = b.groups;
  index.clusters = std::move(b.entries);
  // The index as a reader would check it: a build that breaks a rule of
  // the hierarchy (monotonic errors, groups in order) is a bug, said here.
  if (std::string p = clusterIndexProblem(index); !p.empty()) return fail("the streamed build made an unsound index: " + p);
  if (reportOut) *reportOut = rep;
  return index;
}

}  // namespace hs::mesh
