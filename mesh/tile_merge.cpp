#include "mesh/tile_merge.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>

#include "core/parallel.h"
#include "mesh/nonmanifold_split.h"
#include "mesh/weld.h"

namespace hs::mesh {
namespace {

uint64_t cellKey(const glm::ivec3& c) {
  return (uint64_t(uint32_t(c.x)) * 73856093u) ^ (uint64_t(uint32_t(c.y)) * 19349663u) ^
         (uint64_t(uint32_t(c.z)) * 83492791u);
}

}  // namespace

// Vertices on an open boundary of `m` (a corner with no twin at
// position-welded level), as a flag per vertex.
std::vector<uint8_t> openBoundaryVertices(const MeshData& m) {
  uint32_t n = 0;
  const std::vector<uint32_t> posOf = weldMap(m.positions, {}, {}, n);
  std::vector<uint32_t> tris(m.indices.size());
  for (size_t c = 0; c < tris.size(); ++c) tris[c] = posOf[m.indices[c]];
  const CornerTopology t = analyzeCorners(tris, n);
  std::vector<uint8_t> onPos(n, 0);
  for (uint32_t c = 0; c < tris.size(); ++c)
    if (t.twin[c] == kNoCorner) onPos[tris[c]] = onPos[tris[nextCorner(c)]] = 1;
  std::vector<uint8_t> out(m.vertexCount(), 0);
  for (size_t v = 0; v < out.size(); ++v) out[v] = onPos[posOf[v]];
  return out;
}

BorderSnapGrid::BorderSnapGrid(double tolerance) : tol_(tolerance), cell_(std::max(tolerance, 1e-9)) {}

std::optional<BorderSnapGrid::Earlier> BorderSnapGrid::snapOrAdd(const glm::vec3& position, uint32_t id, uint32_t tile) {
  // A vertex looks at its cell (the size of the tolerance) and the 26
  // around it for an earlier vertex of another tile within the tolerance.
  const glm::dvec3 p(position);
  const glm::ivec3 c(glm::floor(p / cell_));
  const Entry* best = nullptr;
  double bestD = tol_ * tol_;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const auto range = grid_.equal_range(cellKey(c + glm::ivec3(dx, dy, dz)));
        for (auto it = range.first; it != range.second; ++it) {
          const Entry& o = it->second;
          if (o.tile == tile) continue;
          const glm::dvec3 d = glm::dvec3(o.position) - p;
          const double dd = glm::dot(d, d);
          if (dd <= bestD && (!best || dd < bestD || o.id < best->id)) best = &o, bestD = dd;
        }
      }
  if (best) return Earlier{best->id, best->position};
  grid_.emplace(cellKey(c), Entry{position, id, tile});
  return std::nullopt;
}

MeshData mergeTiles(std::vector<MeshData>&& tiles, double tol, TileImportResult* stats) {
  MeshData out;
  if (tiles.empty()) return out;
  // Common origin: the mean of the tiles' origins, to the metre. Each tile's
  // floats are re-expressed against it in double; tiles a few km apart keep
  // sub-millimetre floats.
  glm::dvec3 sum(0.0);
  for (const auto& t : tiles) sum += t.origin;
  out.origin = glm::round(sum / double(tiles.size()));
  bool anyUv = false;
  for (const auto& t : tiles) anyUv |= !t.uvs.empty();

  std::vector<uint32_t> tileOf;      // per output vertex
  std::vector<uint8_t> onBorder;     // per output vertex
  for (uint32_t ti = 0; ti < tiles.size(); ++ti) {
    MeshData& t = tiles[ti];
    const uint32_t base = uint32_t(out.positions.size());
    const glm::dvec3 shift = t.origin - out.origin;
    const std::vector<uint8_t> border = openBoundaryVertices(t);
    for (size_t v = 0; v < t.positions.size(); ++v) {
      out.positions.emplace_back(glm::dvec3(t.positions[v]) + shift);
      out.normals.push_back(v < t.normals.size() ? t.normals[v] : glm::vec3(0, 0, 1));
      if (anyUv) out.uvs.push_back(v < t.uvs.size() ? t.uvs[v] : glm::vec2(0.0f));
      tileOf.push_back(ti);
      onBorder.push_back(border[v]);
    }
    const int materialBase = int(out.materials.size()), textureBase = int(out.textures.size());
    for (Material m : t.materials) {
      if (m.diffuseTexture >= 0) m.diffuseTexture += textureBase;
      out.materials.push_back(std::move(m));
    }
    for (Texture& tex : t.textures) out.textures.push_back(std::move(tex));
    const uint32_t firstIndex = uint32_t(out.indices.size());
    for (uint32_t i : t.indices) out.indices.push_back(base + i);
    if (t.submeshes.empty() && !t.indices.empty()) t.submeshes.push_back({0, uint32_t(t.indices.size()), -1});
    for (Submesh s : t.submeshes) {
      s.firstIndex += firstIndex;
      if (s.material >= 0) s.material += materialBase;
      out.submeshes.push_back(s);
    }
    t = MeshData{};
  }

  size_t border = 0, snapped = 0;
  BorderSnapGrid grid(tol);
  for (uint32_t v = 0; v < out.positions.size(); ++v) {
    if (!onBorder[v]) continue;
    ++border;
    const auto earlier = grid.snapOrAdd(out.positions[v], v, tileOf[v]);
    if (!earlier) continue;
    const uint32_t best = earlier->id;
    if (out.positions[v] != out.positions[best]) ++snapped;
    out.positions[v] = out.positions[best];
    // Two tiles' normals at one border point: their average, so the weld
    // below can merge the vertices where the UVs agree too.
    const glm::vec3 n = out.normals[v] + out.normals[best];
    if (glm::length(n) > 0) out.normals[v] = out.normals[best] = glm::normalize(n);
  }
  const size_t before = out.positions.size();
  weldExactDuplicates(out);
  if (stats) {
    stats->borderVertices = border;
    stats->borderVerticesSnapped = snapped;
    stats->borderVerticesMerged = before - out.positions.size();
  }
  return out;
}

TileImportResult importTiles(const std::vector<std::string>& paths, const TileImportOptions& options,
                             const Progress* progress) {
  TileImportResult result;
  if (paths.empty()) {
    result.error = "no tile files given";
    return result;
  }
  // Tiles are read on threads of their own (std::thread, not the oneTBB
  // pool: a tile read by Assimp blocks on its worker process for its whole
  // read, which would take a pool thread from the parallel loops of the
  // tiles read here). This thread supervises: it passes a Cancel on to every
  // tile within 20 ms, also to a worker that reports no progress. Tiles are
  // taken in order; when tile i fails, only tiles after i are stopped and
  // skipped, so the error and the reports are those of reading one by one.
  const size_t n = paths.size();
  const unsigned slots = unsigned(std::min<size_t>(n, options.maxParallel == 0 ? availableThreads()
                                                                                 : options.maxParallel));
  std::vector<ImportResult> results(n);
  std::vector<std::atomic<double>> fraction(n);
  for (auto& f : fraction) f.store(0.0, std::memory_order_relaxed);
  std::atomic<size_t> next{0}, firstFailed{n};
  std::vector<std::unique_ptr<Progress>> bars(n);
  for (size_t i = 0; i < n; ++i)
    bars[i] = std::make_unique<Progress>([&, i](double f, std::string_view stage) {
      fraction[i].store(f, std::memory_order_relaxed);
      double sum = 0.0;
      for (const auto& x : fraction) sum += x.load(std::memory_order_relaxed);
      reportProgress(progress, 0.9 * sum / double(n), stage);
      if (isCancelled(progress) || i > firstFailed.load()) bars[i]->cancel();
    });
  std::mutex m;
  std::condition_variable cv;
  unsigned running = slots;
  std::exception_ptr thrown;
  size_t thrownBy = n;
  auto reader = [&] {
    for (;;) {
      const size_t i = next.fetch_add(1);
      if (i >= n || i > firstFailed.load() || isCancelled(progress)) break;
      ImportResult r;
      try {
        r = options.readTile ? options.readTile(paths[i], options.import, bars[i].get())
                             : importMesh(paths[i], options.import, bars[i].get());
      } catch (...) {  // rethrown on the caller's thread, as when tiles were read there
        std::lock_guard lock(m);
        if (!thrown || i < thrownBy) thrown = std::current_exception(), thrownBy = i;
        r.error = "an exception was thrown";
      }
      if (!r.ok()) {
        size_t f = firstFailed.load();
        while (i < f && !firstFailed.compare_exchange_weak(f, i)) {
        }
      }
      results[i] = std::move(r);
    }
    std::lock_guard lock(m);
    if (--running == 0) cv.notify_all();
  };
  {
    std::vector<std::thread> threads;
    threads.reserve(slots);
    for (unsigned t = 0; t < slots; ++t) threads.emplace_back(reader);
    std::unique_lock lock(m);
    while (running > 0) {
      cv.wait_for(lock, std::chrono::milliseconds(20));
      const bool cancel = isCancelled(progress);
      const size_t failed = firstFailed.load();
      for (size_t i = 0; i < n; ++i)
        if (cancel || i > failed) bars[i]->cancel();
    }
    lock.unlock();
    for (auto& t : threads) t.join();
  }
  // Reading one by one would have thrown only if no earlier tile failed.
  if (thrown && thrownBy == firstFailed.load()) std::rethrow_exception(thrown);
  // Reports of every tile read up to the first that failed, in order.
  const size_t failed = firstFailed.load();
  const size_t last = failed < n ? failed : n - 1;
  for (size_t i = 0; i <= last; ++i) result.tiles.push_back(results[i].report);
  if (failed < n || isCancelled(progress)) {
    // A Cancel can stop tiles anywhere: name the first tile that did not finish.
    size_t i = failed;
    if (i == n)
      for (i = 0; i + 1 < n && results[i].ok(); ++i) {
      }
    const ImportResult& r = results[i];
    result.cancelled = r.cancelled || isCancelled(progress);
    result.error = "tile " + std::to_string(i + 1) + " of " + std::to_string(n) + ": " +
                   (r.error.empty() ? std::string("import cancelled") : r.error);
    result.tiles.resize(std::min(result.tiles.size(), i + 1));
    return result;
  }
  std::vector<MeshData> tiles;
  tiles.reserve(n);
  for (auto& r : results) tiles.push_back(std::move(*r.mesh));
  results.clear();
  reportProgress(progress, 0.92, "Welding tile borders");
  result.mesh = mergeTiles(std::move(tiles), options.weldTolerance, &result);
  if (options.import.recenter) recenter(*result.mesh);
  reportProgress(progress, 1.0, "Done");
  return result;
}

}  // namespace hs::mesh
