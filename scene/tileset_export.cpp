#include "scene/tileset_export.h"

#include <algorithm>
#include <cmath>

#include "mesh/tileset_writer.h"
#include "scene/cluster_asset.h"
#include "terrain/gdal_door.h"

#include <glm/gtc/matrix_transform.hpp>

namespace hs::scene {
namespace {

// One cluster decoded, in the asset's local frame.
struct LoadedCluster {
  glm::vec2 centre;  // of its bounds, x/y (the tile squares)
  mesh::PageCluster data;
};

struct Square {
  glm::dvec2 lo, hi;
  bool holds(const glm::vec2& p) const {
    const glm::dvec2 q(p);
    return q.x >= lo.x && q.x < hi.x && q.y >= lo.y && q.y < hi.y;
  }
};

// The uniform cut at `error` (each cluster whose own error is at most it
// and whose parent's is over it) among `ids`.
std::vector<uint32_t> cutAt(const mesh::ClusterIndex& index, const std::vector<uint32_t>& ids, float error) {
  std::vector<uint32_t> out;
  for (uint32_t id : ids)
    if (index.clusters[id].error <= error && error < index.clusters[id].parentError) out.push_back(id);
  return out;
}

size_t trianglesOf(const mesh::ClusterIndex& index, const std::vector<uint32_t>& ids) {
  size_t n = 0;
  for (uint32_t id : ids) n += index.clusters[id].triangleCount;
  return n;
}

struct TreeBuilder {
  const mesh::ClusterIndex& index;
  const std::vector<LoadedCluster>& loaded;  // by cluster id
  const std::vector<float>& errors;          // the cut of each depth, largest first, 0 last
  size_t maxTriangles;
  std::vector<mesh::TileToWrite>& tiles;

  mesh::MeshData contentOf(const std::vector<uint32_t>& ids) const {
    mesh::MeshData m;
    m.origin = index.origin;
    for (uint32_t id : ids) {
      const mesh::PageCluster& c = loaded[id].data;
      const uint32_t first = uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), c.positions.begin(), c.positions.end());
      m.normals.insert(m.normals.end(), c.normals.begin(), c.normals.end());
      if (index.hasUvs) m.uvs.insert(m.uvs.end(), c.uvs.begin(), c.uvs.end());
      for (uint8_t v : c.triangles) m.indices.push_back(first + v);
    }
    m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
    return m;
  }

  // The tile over `square` at `depth` (its content: `ids`, the cut of
  // that depth inside the square), then its children.
  void build(const Square& square, size_t depth, const std::vector<uint32_t>& inSquare, int parent) {
    const std::vector<uint32_t> ids = cutAt(index, inSquare, errors[depth]);
    // Depths whose cut is the same here add nothing: go on to the next that differs.
    size_t next = depth + 1;
    while (next < errors.size() && cutAt(index, inSquare, errors[next]) == ids) ++next;
    mesh::TileToWrite t;
    t.parent = parent;
    // A depth that is the same as finer ones here carries their error.
    t.geometricError = next < errors.size() ? double(errors[next - 1]) : 0.0;
    t.content = contentOf(ids);
    const int self = int(tiles.size());
    tiles.push_back(std::move(t));
    if (next >= errors.size()) return;  // level 0 reached
    const std::vector<uint32_t> finer = cutAt(index, inSquare, errors[next]);
    if (trianglesOf(index, finer) <= maxTriangles) {
      build(square, next, inSquare, self);
      return;
    }
    const glm::dvec2 mid = 0.5 * (square.lo + square.hi);
    const Square quads[4] = {{square.lo, mid},
                             {{mid.x, square.lo.y}, {square.hi.x, mid.y}},
                             {{square.lo.x, mid.y}, {mid.x, square.hi.y}},
                             {mid, square.hi}};
    for (const Square& q : quads) {
      std::vector<uint32_t> inQuad;
      for (uint32_t id : inSquare)
        if (q.holds(loaded[id].centre)) inQuad.push_back(id);
      if (!cutAt(index, inQuad, errors[next]).empty()) build(q, next, inQuad, self);
    }
  }
};

// The tile tree of a clustered asset (as the header says).
bool clusterTiles(const ClusterAsset& c, const std::string& name, size_t maxTriangles, std::vector<mesh::TileToWrite>& tiles,
                  std::string& error, const Progress* progress) {
  const mesh::ClusterIndex& index = c.index;
  std::vector<LoadedCluster> loaded(index.clusters.size());
  for (uint32_t p = 0; p < index.pageCount; ++p) {
    if (isCancelled(progress)) return false;
    reportProgress(progress, 0.5 * p / std::max<uint32_t>(index.pageCount, 1), "Reading cluster pages");
    auto page = c.loadPage(p, "'" + name + "'", error);
    if (!page) return false;
    for (mesh::PageCluster& pc : *page) {
      const mesh::LodSphere& b = index.clusters[pc.cluster].bounds;
      const uint32_t id = pc.cluster;
      loaded[id].centre = glm::vec2(b.centre.x, b.centre.y);
      loaded[id].data = std::move(pc);
    }
  }
  // Errors of the depths: the roots' largest, then halving down to the
  // smallest non-zero error of any cluster, then 0 (level 0).
  float top = 0.0f, smallest = std::numeric_limits<float>::max();
  for (const mesh::ClusterIndexEntry& e : index.clusters) {
    if (!std::isfinite(e.parentError)) top = std::max(top, e.error);
    if (e.error > 0.0f) smallest = std::min(smallest, e.error);
  }
  std::vector<float> errors;
  for (float e = top; e > 0.0f && e >= smallest && errors.size() < 40; e *= 0.5f) errors.push_back(e);
  errors.push_back(0.0f);
  std::vector<uint32_t> all(index.clusters.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const LoadedCluster& l : loaded) lo = glm::min(lo, glm::dvec2(l.centre)), hi = glm::max(hi, glm::dvec2(l.centre));
  hi += glm::dvec2(1e-3);  // the square holds its upper edge's centres too
  TreeBuilder{index, loaded, errors, maxTriangles, tiles}.build({lo, hi}, 0, all, -1);
  return true;
}

// The chain of an asset without a hierarchy: coarsest LOD first.
void lodChainTiles(const MeshAsset& asset, std::vector<mesh::TileToWrite>& tiles) {
  for (size_t k = asset.lods.size(); k-- > 0;) {
    mesh::TileToWrite t;
    t.parent = int(tiles.size()) - 1;
    t.geometricError = asset.lods[k].hausdorff;
    t.content = *asset.lods[k].data;
    tiles.push_back(std::move(t));
  }
  mesh::TileToWrite leaf;
  leaf.parent = int(tiles.size()) - 1;
  leaf.content = *asset.data;
  tiles.push_back(std::move(leaf));
}

// The WGS 84 east-north-up frame at ECEF point `p` (lon/lat in degrees).
glm::dmat4 enuFrame(const glm::dvec3& ecef, double lonDeg, double latDeg) {
  const double lon = glm::radians(lonDeg), lat = glm::radians(latDeg);
  glm::dmat4 m(1.0);
  m[0] = {-std::sin(lon), std::cos(lon), 0.0, 0.0};
  m[1] = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat), 0.0};
  m[2] = {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat), 0.0};
  m[3] = glm::dvec4(ecef, 1.0);
  return m;
}

// Every tile's vertices from `crs` into the east-north-up frame at the
// first tile's origin; false with `error`.
bool toEastNorthUp(std::vector<mesh::TileToWrite>& tiles, const std::string& crs, glm::dmat4& rootTransform,
                   std::string& error) {
  const terrain::gdal_door::Backend* gdal = terrain::gdal_door::backend(error);
  if (!gdal) return false;
  const glm::dvec3 anchor = tiles.front().content.origin;
  // The anchor and three steps of a metre from it (the frame's turn, for
  // the normals), then every vertex.
  std::vector<glm::dvec3> points = {anchor, anchor + glm::dvec3(1, 0, 0), anchor + glm::dvec3(0, 1, 0),
                                    anchor + glm::dvec3(0, 0, 1)};
  for (const mesh::TileToWrite& t : tiles)
    for (const glm::vec3& p : t.content.positions) points.push_back(t.content.origin + glm::dvec3(p));
  std::string wkt, name;
  if (!gdal->transformPoints(crs, "EPSG:4978", points, wkt, name, error)) return false;
  std::vector<glm::dvec3> geo = {points[0]};
  if (!gdal->transformPoints("EPSG:4978", "EPSG:4326", geo, wkt, name, error)) return false;
  rootTransform = enuFrame(points[0], geo[0].x, geo[0].y);
  const glm::dmat4 toLocal = glm::inverse(rootTransform);
  auto local = [&](const glm::dvec3& ecef) { return glm::dvec3(toLocal * glm::dvec4(ecef, 1.0)); };
  const glm::dvec3 o = local(points[0]);
  const glm::dmat3 jacobian(local(points[1]) - o, local(points[2]) - o, local(points[3]) - o);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(jacobian));
  size_t at = 4;
  for (mesh::TileToWrite& t : tiles) {
    mesh::MeshData& m = t.content;
    std::vector<glm::dvec3> enu;
    enu.reserve(m.positions.size());
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (size_t i = 0; i < m.positions.size(); ++i) {
      enu.push_back(local(points[at++]));
      lo = glm::min(lo, enu.back()), hi = glm::max(hi, enu.back());
    }
    m.origin = m.positions.empty() ? glm::dvec3(0.0) : 0.5 * (lo + hi);
    for (size_t i = 0; i < m.positions.size(); ++i) m.positions[i] = glm::vec3(enu[i] - m.origin);
    for (glm::vec3& n : m.normals) n = glm::vec3(glm::normalize(normalMatrix * glm::dvec3(n)));
  }
  return true;
}

// The CRS the asset's import recorded ("" when none).
std::string recordedCrs(const MeshAsset& asset) {
  const Json& r = asset.importReport;
  if (r.is_object() && r.contains("geo_offset") && r["geo_offset"].is_object() && r["geo_offset"].contains("crs") &&
      r["geo_offset"]["crs"].is_string())
    return r["geo_offset"]["crs"].get<std::string>();
  return "";
}

}  // namespace

mesh::ExportResult exportTileset(const MeshAsset& asset, const std::string& path, const TilesetExportOptions& options,
                                 std::vector<std::string>& notes, const Progress* progress) {
  mesh::ExportResult r;
  std::vector<mesh::TileToWrite> tiles;
  if (asset.clusters) {
    Progress read(progress, 0.0, 0.6);
    if (!clusterTiles(*asset.clusters, asset.name, std::max<size_t>(options.maxTileTriangles, 128), tiles, r.error,
                      &read)) {
      if (!r.error.empty()) r.error = path + ": " + r.error;
      return r;
    }
  } else {
    lodChainTiles(asset, tiles);
  }
  mesh::TilesetWriteOptions w;
  w.dracoBits = options.dracoBits;
  std::string crs = options.crs.empty() ? "auto" : options.crs;
  if (crs == "auto") {
    crs = recordedCrs(asset);
    if (crs.empty()) crs = "local";
  }
  if (crs == "local") {
    notes.push_back(path + ": written in the asset's own frame, not placed on the globe (name its coordinate "
                           "system with --crs to place it)");
    // Tiles about the asset's origin: the root's transform puts them back.
    const glm::dvec3 origin = tiles.front().content.origin;
    for (mesh::TileToWrite& t : tiles) t.content.origin -= origin;
    w.rootTransform = glm::translate(glm::dmat4(1.0), origin);
  } else {
    std::string error;
    if (!toEastNorthUp(tiles, crs, w.rootTransform, error)) {
      r.error = path + ": from " + crs + " to ECEF: " + error;
      return r;
    }
    notes.push_back(path + ": placed on the globe from " + crs + " (ECEF, an east-north-up frame at the asset's origin)");
  }
  w.tilesetError = tiles.front().geometricError * 2.0 + 1.0;
  Progress write(progress, 0.6, 1.0);
  return mesh::writeTileset(tiles, path, w, &write);
}

}  // namespace hs::scene
