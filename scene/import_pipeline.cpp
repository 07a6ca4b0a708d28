#include "scene/import_pipeline.h"

#include <filesystem>

#include "mesh/tile_merge.h"
#include "mesh/tileset_reader.h"
#include "meshproc/report_json.h"
#include "scene/asset_reports.h"
#include "scene/cluster_asset.h"
#include "scene/import_isolation.h"
#include "scene/tileset_import.h"

namespace hs::scene {
namespace {

// Several tiles: one report with the counts summed, named after the first
// tile (each tile's own report is kept beside it).
mesh::ImportReport sumTileReports(const std::vector<mesh::ImportReport>& tiles, size_t verticesOut,
                                  size_t trianglesOut) {
  mesh::ImportReport sum = tiles.front();
  for (size_t i = 1; i < tiles.size(); ++i) {
    const mesh::ImportReport& t = tiles[i];
    sum.verticesIn += t.verticesIn;
    sum.trianglesIn += t.trianglesIn;
    sum.nonFiniteVertices += t.nonFiniteVertices;
    sum.outOfRangeFaces += t.outOfRangeFaces;
    sum.degenerateFaces += t.degenerateFaces;
    sum.polygonsTriangulated += t.polygonsTriangulated;
    sum.skippedLines += t.skippedLines;
    // Declared counts add up only when every tile declares one.
    sum.declaredTriangles += t.declaredTriangles;
    if (t.declaredBy.empty()) sum.declaredBy.clear();
    else if (!sum.declaredBy.empty()) sum.declaredBy = "the tiles' own declarations";
    sum.normalsGenerated = sum.normalsGenerated || t.normalsGenerated;
    sum.upAxisConverted = sum.upAxisConverted || t.upAxisConverted;
    sum.warnings.insert(sum.warnings.end(), t.warnings.begin(), t.warnings.end());
    sum.seconds += t.seconds;
  }
  sum.verticesOut = verticesOut;
  sum.trianglesOut = trianglesOut;
  return sum;
}

// The hierarchy of out.mesh when the request asks for one (or Auto finds
// it large enough); out.mesh becomes its coarse cut, with the input's
// materials and textures. False when cancelled.
bool buildClusters(ImportedMesh& out, const MeshImportRequest& request, const Progress* progress) {
  const bool wanted = request.clusters == MeshImportRequest::Clusters::On ||
                      (request.clusters == MeshImportRequest::Clusters::Auto &&
                       out.mesh->triangleCount() >= kClusterAutoTriangles);
  if (!wanted || out.mesh->triangleCount() == 0) return true;
  // One hierarchy draws with one material: a mesh with several is kept
  // whole by Auto and refused by On (per-material hierarchies: not yet).
  if (out.mesh->materials.size() > 1) {
    if (request.clusters == MeshImportRequest::Clusters::On)
      out.error = request.files.front() + ": a cluster hierarchy takes a mesh of one material; this one has " +
                  std::to_string(out.mesh->materials.size()) + " (import it without --clusters)";
    return true;
  }
  ClusterBuild b = buildClusterAsset(*out.mesh, request.clusterOptions, kClusterProxyTriangles, progress);
  out.clusterReport = b.report;
  if (!b.clusters) return false;
  b.proxy.materials = std::move(out.mesh->materials);
  b.proxy.textures = std::move(out.mesh->textures);
  if (!b.proxy.materials.empty()) b.proxy.submeshes.front().material = 0;
  out.proxyError = b.proxyError;
  out.clustersHash = b.clustersHash;
  out.clusters = std::move(b.clusters);
  out.mesh = std::move(b.proxy);
  out.lods.clear();  // the hierarchy is its levels of detail
  return true;
}

// Tiles read one at a time for the streamed build, each through the
// import worker like any file; their reports kept, the first tile's
// materials kept for the stand-in.
class FileTiles : public mesh::ScanTileSource {
 public:
  FileTiles(const MeshImportRequest& r) : request_(r) {}
  size_t tileCount() const override { return request_.files.size(); }
  bool readTile(size_t i, mesh::MeshData& out, std::string& error) override {
    mesh::ImportResult r = importMeshIsolated(request_.files[i], request_.import, nullptr);
    if (!r.mesh || !r.error.empty()) {
      error = r.error.empty() ? request_.files[i] + ": the file could not be read" : r.error;
      return false;
    }
    reports.push_back(std::move(r.report));
    if (r.mesh->materials.size() > 1) manyMaterials = true;
    if (i == 0) {
      materials = std::move(r.mesh->materials);
      textures = std::move(r.mesh->textures);
    }
    out = std::move(*r.mesh);
    return true;
  }
  std::vector<mesh::ImportReport> reports;
  std::vector<mesh::Material> materials;
  std::vector<mesh::Texture> textures;
  bool manyMaterials = false;

 private:
  const MeshImportRequest& request_;
};

ImportedMesh importStreamed(const MeshImportRequest& request, const Progress* progress) {
  ImportedMesh out;
  if (request.process) {
    out.error = request.files.front() +
                ": a streamed cluster build takes the files as read; cleaning, decimation and LODs need the whole "
                "mesh in memory (import with --clusters on, or without the processing options)";
    return out;
  }
  FileTiles tiles(request);
  mesh::StreamedClusterReport rep;
  ClusterBuild b = buildClusterAssetStreamed(tiles, streamedClusterOptions(request), kClusterProxyTriangles, &rep, progress, out.error);
  out.streamed = rep;
  out.clusterReport = b.report;
  out.tileBorderVertices = rep.tileBorderVertices;
  out.tileBorderVerticesSnapped = rep.tileBorderVerticesSnapped;
  if (!b.clusters) {
    if (out.error.empty()) out.cancelled = true;
    return out;
  }
  const size_t triangles = rep.build.trianglesPerLevel.empty() ? 0 : rep.build.trianglesPerLevel.front();
  size_t vertices = 0;  // as read (tiles are joined in the hierarchy's pages, not counted)
  for (const auto& r : tiles.reports) vertices += r.verticesOut;
  if (tiles.reports.size() > 1) out.tiles = tiles.reports;
  out.import = sumTileReports(tiles.reports, vertices, triangles);
  if (tiles.manyMaterials || tiles.materials.size() > 1)
    out.import.warnings.push_back(request.files.front() +
                                  ": a cluster hierarchy draws with one material: the first tile's first is kept");
  if (rep.uvsDropped)
    out.import.warnings.push_back(request.files.front() + ": some tiles have no UVs: the hierarchy keeps none");
  b.proxy.materials = std::move(tiles.materials);
  if (b.proxy.materials.size() > 1) b.proxy.materials.resize(1);
  b.proxy.textures = std::move(tiles.textures);
  if (!b.proxy.materials.empty()) b.proxy.submeshes.front().material = 0;
  out.importReport = toJson(AssetImportReport{out.import, out.tiles});
  out.proxyError = b.proxyError;
  out.clustersHash = b.clustersHash;
  out.clusters = std::move(b.clusters);
  out.mesh = std::move(b.proxy);
  return out;
}

// Whether the files hold kClusterStreamedAutoBytes or more.
bool largeInput(const std::vector<std::string>& files) {
  uint64_t bytes = 0;
  for (const std::string& f : files) {
    std::error_code ec;
    const auto n = std::filesystem::file_size(f, ec);
    if (!ec) bytes += n;
  }
  return bytes >= kClusterStreamedAutoBytes;
}

}  // namespace

mesh::StreamedClusterOptions streamedClusterOptions(const MeshImportRequest& request) {
  mesh::StreamedClusterOptions o;
  o.clusters = request.clusterOptions;
  o.scratchDir = request.scratchDir;
  o.weldTolerance = request.tileWeldTolerance;
  return o;
}

ImportedMesh importMeshFiles(const MeshImportRequest& request, const Progress* progress) {
  ImportedMesh out;
  if (request.files.empty()) {
    out.error = "no mesh file given";
    return out;
  }
  // A 3D Tiles tileset brings its own levels of detail (tileset_import.h).
  if (request.files.size() == 1 && mesh::isTilesetFile(request.files.front()))
    return importTileset(request.files.front(), request, progress);
  if (request.clusters == MeshImportRequest::Clusters::Streamed ||
      (request.clusters == MeshImportRequest::Clusters::Auto && !request.process && largeInput(request.files)))
    return importStreamed(request, progress);
  const bool mayCluster = request.clusters != MeshImportRequest::Clusters::Off;
  const double readShare = request.process || mayCluster ? 0.35 : 1.0;
  const double processEnd = request.process && mayCluster ? 0.6 : 1.0;
  {
    Progress read(progress, 0.0, readShare);
    if (request.files.size() == 1) {
      mesh::ImportResult r = importMeshIsolated(request.files.front(), request.import, &read);
      out.import = std::move(r.report);
      out.cancelled = r.cancelled;
      out.error = std::move(r.error);
      out.mesh = std::move(r.mesh);
    } else {
      mesh::TileImportOptions t;
      t.import = request.import;
      t.weldTolerance = request.tileWeldTolerance;
      // One worker per tile read at once, kept for the next tile.
      ImportWorkerPool workers;
      t.readTile = [&workers](const std::string& path, const mesh::ImportOptions& o, const Progress* p) {
        return workers.read(path, o, p);
      };
      t.maxParallel = tileReadParallelism(request.files, request.import);
      mesh::TileImportResult r = mesh::importTiles(request.files, t, &read);
      out.cancelled = r.cancelled;
      out.error = std::move(r.error);
      out.tiles = std::move(r.tiles);
      out.tileBorderVertices = r.borderVertices;
      out.tileBorderVerticesSnapped = r.borderVerticesSnapped;
      out.tileBorderVerticesMerged = r.borderVerticesMerged;
      if (r.mesh && !out.tiles.empty()) out.import = sumTileReports(out.tiles, r.mesh->vertexCount(), r.mesh->triangleCount());
      out.mesh = std::move(r.mesh);
    }
  }
  if (isCancelled(progress)) out.cancelled = true;
  if (!out.ok()) {
    if (out.error.empty() && !out.cancelled) out.error = request.files.front() + ": the file could not be read";
    out.mesh.reset();
    return out;
  }

  out.importReport = toJson(AssetImportReport{out.import, out.tiles});
  if (!request.process) {
    Progress clusters(progress, readShare, 1.0);
    if (!buildClusters(out, request, &clusters)) out.cancelled = true;
    if (!out.ok()) out.mesh.reset();
    return out;
  }

  Progress work(progress, readShare, processEnd);
  mesh::ProcessResult p = mesh::processMesh(std::move(*out.mesh), request.processing, &work);
  out.mesh.reset();
  if (p.cancelled || isCancelled(progress)) {
    out.cancelled = true;
    return out;
  }
  if (!p.ok()) {
    out.error = request.files.front() + ": " + p.error;
    return out;
  }
  out.processed = true;
  out.process = std::move(p.report);
  // Level k's error is process.lods[k] (level 0 first); hashing here keeps
  // the UI thread free of work proportional to the mesh.
  for (size_t k = 0; k < p.lods.size(); ++k) {
    MeshLod l;
    l.contentHash = mesh::contentHash(p.lods[k]);
    l.triangles = p.lods[k].triangleCount();
    l.hausdorff = k + 1 < out.process.lods.size() ? out.process.lods[k + 1].hausdorff : 0.0;
    l.data = std::make_shared<const mesh::MeshData>(std::move(p.lods[k]));
    out.lods.push_back(std::move(l));
  }
  out.mesh = std::move(p.mesh);

  AssetProcessReport stored{out.process, request.processing, std::nullopt};
  if (!out.tiles.empty())
    stored.tiles = TileWeldReport{out.tiles.size(), request.tileWeldTolerance, out.tileBorderVertices,
                                  out.tileBorderVerticesSnapped, out.tileBorderVerticesMerged};
  out.processReport = toJson(stored);
  Progress clusters(progress, processEnd, 1.0);
  if (!buildClusters(out, request, &clusters)) out.cancelled = true;
  if (!out.ok()) out.mesh.reset();
  return out;
}

Json importReportFileJson(const ImportedMesh& r) {
  Json o = mesh::toJson(r.import);
  o["processing"] = r.processReport;
  if (!r.tiles.empty()) {
    Json tiles = Json::array();
    for (const auto& t : r.tiles) tiles.push_back(mesh::toJson(t));
    o["tiles"] = std::move(tiles);
  }
  if (!r.error.empty()) o["error"] = r.error;
  return o;
}

}  // namespace hs::scene
