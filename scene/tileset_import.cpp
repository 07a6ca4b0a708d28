#include "scene/tileset_import.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include "mesh/tileset_reader.h"
#include "meshproc/cluster_from_tiles.h"
#include "scene/asset_reports.h"
#include "scene/cluster_asset.h"
#include "scene/tileset_import_streamed.h"
#include "terrain/gdal_door.h"

namespace hs::scene {

ImportedMesh importTileset(const std::string& path, const MeshImportRequest& request, const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ImportedMesh out;
  out.import.file = path;
  out.import.reader = "3dtiles";
  if (request.clusters == MeshImportRequest::Clusters::Off) {
    out.error = path + ": a 3D Tiles tileset comes in as a cluster hierarchy (its levels of detail); it cannot be "
                "imported with --clusters off";
    return out;
  }
  // Too large to hold decoded (or asked to): built out of core from its
  // full detail (tileset_import_streamed.h). The tree alone is cheap to read.
  if (request.clusters != MeshImportRequest::Clusters::On) {
    mesh::Tileset tree;
    std::vector<mesh::TilesetContentRef> contents;
    if (!mesh::readTilesetTree(path, tree, contents, out.error, progress)) {
      if (out.error.empty()) out.cancelled = true;
      return out;
    }
    uint64_t bytes = 0;
    for (const mesh::TilesetContentRef& c : contents) bytes += c.bytes;
    if (request.clusters == MeshImportRequest::Clusters::Streamed || bytes >= kClusterStreamedAutoBytes)
      return importTilesetStreamed(path, request, std::move(tree), contents, progress);
  }
  mesh::Tileset tileset;
  {
    Progress read(progress, 0.0, 0.6);
    if (!mesh::readTileset(path, tileset, out.error, &read)) {
      if (out.error.empty()) out.cancelled = true;
      return out;
    }
  }
  mesh::ImportReport& rep = out.import;
  rep.warnings = std::move(tileset.warnings);
  if (request.process)
    rep.warnings.push_back(path + ": cleaning and decimation do not apply to a tileset (its levels of detail come "
                                  "with it); not done");
  // Where it is: ECEF, or a frame of its own.
  glm::dvec3 mean(0.0);
  size_t count = 0;
  for (const mesh::TilesetTile& t : tileset.tiles) {
    for (const glm::dvec3& p : t.positions) mean += p;
    count += t.positions.size();
  }
  mean /= double(std::max<size_t>(count, 1));
  const bool ecef = nearEarthSurfaceEcef(glm::length(mean));
  std::string crs = request.tilesetCrs.empty() ? "auto" : request.tilesetCrs;
  if (crs == "auto") crs = ecef ? "utm" : "local";
  if (crs != "local") {
    if (!ecef)
      rep.warnings.push_back(path + ": its vertices are not near the Earth's surface in ECEF; converted to " + crs +
                             " as if they were");
    std::vector<glm::dvec3> all;
    all.reserve(count);
    for (const mesh::TilesetTile& t : tileset.tiles) all.insert(all.end(), t.positions.begin(), t.positions.end());
    std::string doorError, wkt, name;
    const terrain::gdal_door::Backend* gdal = terrain::gdal_door::backend(doorError);
    if (!gdal) {
      out.error = path + ": converting from ECEF needs " + doorError;
      return out;
    }
    if (!gdal->transformPoints("EPSG:4978", crs, all, wkt, name, doorError)) {
      out.error = path + ": from ECEF (EPSG:4978) to " + crs + ": " + doorError;
      return out;
    }
    size_t at = 0;
    for (mesh::TilesetTile& t : tileset.tiles)
      for (glm::dvec3& p : t.positions) p = all[at++];
    rep.geoOffsetCrs = wkt;  // "EPSG:n" where it has one: what `mesh export --format 3dtiles` reads back
    rep.geoOffsetSource = "3D Tiles ECEF (EPSG:4978) converted by PROJ to " + name;
  }
  if (isCancelled(progress)) {
    out.cancelled = true;
    return out;
  }
  // The origin: the middle of its bounds, so float positions about it keep
  // sub-millimetre steps across tens of kilometres.
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const mesh::TilesetTile& t : tileset.tiles)
    for (uint32_t i : t.indices) lo = glm::min(lo, t.positions[i]), hi = glm::max(hi, t.positions[i]);
  const glm::dvec3 origin = 0.5 * (lo + hi);
  if (!rep.geoOffsetSource.empty()) rep.geoOffset = origin;
  std::vector<mesh::LodTile> tiles(tileset.tiles.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    mesh::TilesetTile& src = tileset.tiles[i];
    mesh::LodTile& t = tiles[i];
    t.parent = src.parent;
    t.error = float(src.geometricError);
    t.additive = src.additive;
    t.name = src.content;
    t.missing = src.contentMissing;
    t.positions.reserve(src.positions.size());
    for (const glm::dvec3& p : src.positions) t.positions.emplace_back(p - origin);
    t.uvs = std::move(src.uvs);
    t.indices = std::move(src.indices);
    rep.verticesIn += src.positions.size();
    rep.trianglesIn += t.indices.size() / 3;
    std::vector<glm::dvec3>().swap(src.positions);
  }
  reportProgress(progress, 0.7, "Clustering the tiles");
  mesh::TileHierarchyReport tileReport;
  const mesh::ClusterHierarchy h = mesh::clusterHierarchyOfTiles(tiles, origin, request.clusterOptions, &tileReport);
  tiles.clear();
  for (std::string& w : tileReport.warnings) rep.warnings.push_back(path + ": " + std::move(w));
  if (tileReport.additiveCopies)
    rep.warnings.push_back(path + ": " + std::to_string(tileReport.additiveCopies) +
                           " tiles refine by ADD: their content is stored twice (drawn alone, and with their children)");
  ClusterBuild b = clusterAssetOfHierarchy(h, kClusterProxyTriangles);
  for (const mesh::Cluster& c : h.clusters) {
    if (out.clusterReport.clustersPerLevel.size() <= c.level) {
      out.clusterReport.clustersPerLevel.resize(c.level + 1, 0);
      out.clusterReport.trianglesPerLevel.resize(c.level + 1, 0);
    }
    ++out.clusterReport.clustersPerLevel[c.level];
    out.clusterReport.trianglesPerLevel[c.level] += c.triangleCount;
    if (!std::isfinite(c.parentError)) ++out.clusterReport.roots;
  }
  out.clusterReport.groups = h.groups;
  rep.declaredTriangles = tileset.trianglesDeclared;
  rep.declaredBy = "the triangle primitives of the " + std::to_string(tileset.contentsRead) + " tile contents read";
  // What came in: every tile's triangles (each level), against what was declared.
  rep.verticesOut = h.positions.size();
  rep.trianglesOut = h.indices.size() / 3 - tileReport.additiveCopyTriangles;  // ADD copies are not in the file twice
  if (tileset.contentsRead < tileset.contentsDeclared)
    rep.warnings.push_back(path + ": " + std::to_string(tileset.contentsRead) + " of " +
                           std::to_string(tileset.contentsDeclared) + " tile contents came in (see above)");
  out.proxyError = b.proxyError;
  out.clustersHash = b.clustersHash;
  out.clusters = std::move(b.clusters);
  out.mesh = std::move(b.proxy);
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.clusterReport.seconds = rep.seconds;
  out.importReport = toJson(AssetImportReport{out.import, {}});
  return out;
}

std::string importedMeshName(const std::string& path) {
  const std::filesystem::path file = std::filesystem::absolute(path);
  if (file.stem() == "tileset" && file.extension() == ".json") return file.parent_path().filename().string();
  return file.stem().string();
}

}  // namespace hs::scene
