#include "scene/tileset_import_streamed.h"

#include <chrono>
#include <limits>

#include "mesh/tileset_finest.h"
#include "scene/asset_reports.h"
#include "scene/cluster_asset.h"
#include "scene/tileset_import.h"
#include "terrain/gdal_door.h"

namespace hs::scene {
namespace {

// The finest contents, decoded one at a time and placed in the scene's
// CRS; every tile shares one origin (the first tile's centre), so the
// build's common frame is exact.
class TilesetTiles : public mesh::ScanTileSource {
 public:
  TilesetTiles(const std::string& path, const std::vector<mesh::TilesetContentRef>& contents,
               const std::vector<size_t>& finest, std::string crs, mesh::Tileset& log)
      : path_(path), contents_(contents), finest_(finest), crs_(std::move(crs)), log_(log) {}
  size_t tileCount() const override { return finest_.size(); }

  bool readTile(size_t i, mesh::MeshData& out, std::string& error) override {
    mesh::TilesetTile t;
    // A content that does not decode is left out, said in the log; the
    // build goes on (its place stays open: it was not known before now).
    mesh::readTilesetContent(contents_[finest_[i]], t, log_);
    out = mesh::MeshData{};
    if (t.positions.empty()) {
      out.origin = origin_;
      ++emptyTiles;
      return true;
    }
    if (!placed_) {
      glm::dvec3 mean(0.0);
      for (const glm::dvec3& p : t.positions) mean += p;
      mean /= double(t.positions.size());
      ecef = nearEarthSurfaceEcef(glm::length(mean));
      if (crs_ == "auto") crs_ = ecef ? "utm" : "local";
      if (crs_ != "local" && !ecef)
        warnings.push_back(path_ + ": its vertices are not near the Earth's surface in ECEF; converted to " + crs_ +
                           " as if they were");
    }
    if (crs_ != "local") {
      std::string doorError, wkt, name;
      const terrain::gdal_door::Backend* gdal = terrain::gdal_door::backend(doorError);
      if (!gdal) {
        error = path_ + ": converting from ECEF needs " + doorError;
        return false;
      }
      if (!gdal->transformPoints("EPSG:4978", crs_, t.positions, wkt, name, doorError)) {
        error = contents_[finest_[i]].file + ": from ECEF (EPSG:4978) to " + crs_ + ": " + doorError;
        return false;
      }
      // "utm" picks the zone of the first tile's centre; every later tile
      // goes to that zone, not its own.
      crs_ = wkt;
      crsDefinition = wkt;
      crsName = name;
    }
    if (!placed_) {
      glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
      for (const glm::dvec3& p : t.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
      origin_ = glm::round(0.5 * (lo + hi));
      placed_ = true;
    }
    out.origin = origin_;
    out.positions.reserve(t.positions.size());
    for (const glm::dvec3& p : t.positions) out.positions.emplace_back(p - origin_);
    out.uvs = std::move(t.uvs);
    out.indices = std::move(t.indices);
    verticesIn += out.positions.size();
    trianglesIn += out.indices.size() / 3;
    return true;
  }

  bool ecef = false;
  std::string crsDefinition, crsName;  // set when converted
  size_t verticesIn = 0, trianglesIn = 0, emptyTiles = 0;
  std::vector<std::string> warnings;

 private:
  const std::string& path_;
  const std::vector<mesh::TilesetContentRef>& contents_;
  const std::vector<size_t>& finest_;
  std::string crs_;
  mesh::Tileset& log_;
  glm::dvec3 origin_{0.0};
  bool placed_ = false;
};

}  // namespace

ImportedMesh importTilesetStreamed(const std::string& path, const MeshImportRequest& request, mesh::Tileset tree,
                                   const std::vector<mesh::TilesetContentRef>& contents, const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ImportedMesh out;
  out.import.file = path;
  out.import.reader = "3dtiles";
  mesh::ImportReport& rep = out.import;
  rep.warnings = std::move(tree.warnings);
  tree.warnings.clear();
  if (request.process)
    rep.warnings.push_back(path + ": cleaning and decimation do not apply to a tileset; not done");
  const mesh::FinestContents finest = mesh::finestContents(tree, contents);
  for (const std::string& w : finest.warnings) rep.warnings.push_back(path + ": " + w);
  if (finest.refs.empty()) {
    out.error = path + ": no tile content is left to build from";
    return out;
  }
  mesh::Tileset log;  // the decoding's warnings and counts
  TilesetTiles tiles(path, contents, finest.refs, request.tilesetCrs.empty() ? "auto" : request.tilesetCrs, log);
  mesh::StreamedClusterReport streamed;
  ClusterBuild b = buildClusterAssetStreamed(tiles, streamedClusterOptions(request), kClusterProxyTriangles, &streamed, progress, out.error);
  for (std::string& w : log.warnings) rep.warnings.push_back(std::move(w));
  for (std::string& w : tiles.warnings) rep.warnings.push_back(std::move(w));
  if (!b.clusters) {
    if (out.error.empty()) out.cancelled = true;
    return out;
  }
  out.streamed = streamed;
  out.clusterReport = b.report;
  out.tileBorderVertices = streamed.tileBorderVertices;
  out.tileBorderVerticesSnapped = streamed.tileBorderVerticesSnapped;
  rep.warnings.push_back(path + ": built out of core from the " + std::to_string(finest.refs.size()) +
                         " contents of its full detail (" + std::to_string(finest.contentsLeftOut) +
                         " coarser contents not used: the levels of detail are built here, with locked borders)");
  if (tiles.emptyTiles)
    rep.warnings.push_back(path + ": " + std::to_string(tiles.emptyTiles) +
                           " of its finest contents did not come in (see above); their places stay open");
  if (!tiles.crsName.empty()) {
    rep.geoOffsetCrs = tiles.crsDefinition;
    rep.geoOffsetSource = "3D Tiles ECEF (EPSG:4978) converted by PROJ to " + tiles.crsName;
    rep.geoOffset = b.clusters->index.origin;
  }
  rep.verticesIn = tiles.verticesIn;
  rep.trianglesIn = tiles.trianglesIn;
  rep.declaredTriangles = log.trianglesDeclared;
  rep.declaredBy = "the triangle primitives of the " + std::to_string(log.contentsRead) + " finest tile contents read";
  rep.verticesOut = tiles.verticesIn;
  rep.trianglesOut = streamed.triangles;
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.clusterReport.seconds = rep.seconds;
  out.importReport = toJson(AssetImportReport{out.import, {}});
  out.proxyError = b.proxyError;
  out.clustersHash = b.clustersHash;
  out.clusters = std::move(b.clusters);
  out.mesh = std::move(b.proxy);
  return out;
}

}  // namespace hs::scene
