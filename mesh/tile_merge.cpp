#include "mesh/tile_merge.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mesh/nonmanifold_split.h"
#include "mesh/weld.h"

namespace hs::mesh {
namespace {

// Vertices on an open boundary of `m` (a corner with no twin at
// position-welded level), as a flag per vertex.
std::vector<uint8_t> boundaryVertices(const MeshData& m) {
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

}  // namespace

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
    const std::vector<uint8_t> border = boundaryVertices(t);
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

  // Border vertices into a grid of cells the size of the tolerance; a
  // vertex looks at its cell and the 26 around it for an earlier vertex of
  // another tile within the tolerance and takes its position.
  size_t border = 0, snapped = 0;
  const double cell = std::max(tol, 1e-9);
  auto key = [&](const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x)) * 73856093u) ^ (uint64_t(uint32_t(c.y)) * 19349663u) ^
           (uint64_t(uint32_t(c.z)) * 83492791u);
  };
  std::unordered_multimap<uint64_t, uint32_t> grid;
  for (uint32_t v = 0; v < out.positions.size(); ++v) {
    if (!onBorder[v]) continue;
    ++border;
    const glm::dvec3 p(out.positions[v]);
    const glm::ivec3 c(glm::floor(p / cell));
    uint32_t best = UINT32_MAX;
    double bestD = tol * tol;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto range = grid.equal_range(key(c + glm::ivec3(dx, dy, dz)));
          for (auto it = range.first; it != range.second; ++it) {
            const uint32_t o = it->second;
            if (tileOf[o] == tileOf[v]) continue;
            const glm::dvec3 d = glm::dvec3(out.positions[o]) - p;
            const double dd = glm::dot(d, d);
            if (dd <= bestD && (best == UINT32_MAX || dd < bestD || o < best)) best = o, bestD = dd;
          }
        }
    if (best != UINT32_MAX) {
      if (out.positions[v] != out.positions[best]) ++snapped;
      out.positions[v] = out.positions[best];
      // Two tiles' normals at one border point: their average, so the weld
      // below can merge the vertices where the UVs agree too.
      const glm::vec3 n = out.normals[v] + out.normals[best];
      if (glm::length(n) > 0) out.normals[v] = out.normals[best] = glm::normalize(n);
    } else {
      grid.emplace(key(c), v);
    }
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
  std::vector<MeshData> tiles;
  for (size_t i = 0; i < paths.size(); ++i) {
    Progress* self = nullptr;
    Progress sub([&](double f, std::string_view stage) {
      reportProgress(progress, 0.9 * (double(i) + f) / double(paths.size()), stage);
      if (self && isCancelled(progress)) self->cancel();
    });
    self = &sub;
    ImportResult r = options.readTile ? options.readTile(paths[i], options.import, progress ? &sub : nullptr)
                                      : importMesh(paths[i], options.import, progress ? &sub : nullptr);
    result.tiles.push_back(r.report);
    if (!r.ok()) {
      result.cancelled = r.cancelled || isCancelled(progress);
      result.error = "tile " + std::to_string(i + 1) + " of " + std::to_string(paths.size()) + ": " + r.error;
      return result;
    }
    tiles.push_back(std::move(*r.mesh));
  }
  reportProgress(progress, 0.92, "Welding tile borders");
  result.mesh = mergeTiles(std::move(tiles), options.weldTolerance, &result);
  if (options.import.recenter) recenter(*result.mesh);
  reportProgress(progress, 1.0, "Done");
  return result;
}

}  // namespace hs::mesh
