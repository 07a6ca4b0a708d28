#include "scene/import_pipeline.h"

#include <cmath>

#include <QJsonArray>
#include <QJsonDocument>

#include "mesh/tile_merge.h"
#include "meshproc/report_json.h"
#include "scene/import_isolation.h"
#include "scene/report_json.h"

namespace hs::scene {
namespace {

// Several tiles: one report with the counts summed, named after the first
// tile (each tile's own report is kept beside it).
mesh::ImportReport sumTileReports(const std::vector<mesh::ImportReport>& tiles, const mesh::MeshData& merged) {
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
    sum.normalsGenerated = sum.normalsGenerated || t.normalsGenerated;
    sum.upAxisConverted = sum.upAxisConverted || t.upAxisConverted;
    sum.warnings.insert(sum.warnings.end(), t.warnings.begin(), t.warnings.end());
    sum.seconds += t.seconds;
  }
  sum.verticesOut = merged.vertexCount();
  sum.trianglesOut = merged.triangleCount();
  return sum;
}

QJsonObject parseObject(const std::string& json) {
  return QJsonDocument::fromJson(QByteArray::fromStdString(json)).object();
}

std::string compact(const QJsonObject& o) { return QJsonDocument(o).toJson(QJsonDocument::Compact).toStdString(); }

QJsonObject tilesJson(const ImportedMesh& r, double tolerance) {
  QJsonObject t;
  t["files"] = double(r.tiles.size());
  t["weld_tolerance_m"] = tolerance;
  t["border_vertices"] = double(r.tileBorderVertices);
  t["border_vertices_snapped"] = double(r.tileBorderVerticesSnapped);
  t["border_vertices_merged"] = double(r.tileBorderVerticesMerged);
  return t;
}

// What the user asked for, so a reopened report says what it measured.
QJsonObject optionsJson(const mesh::ProcessOptions& o) {
  QJsonObject j;
  j["decimate"] = o.decimate;
  if (o.decimate) {
    j["target_ratio"] = o.decimation.targetTriangles ? QJsonValue() : QJsonValue(o.decimation.targetRatio);
    j["target_triangles"] = o.decimation.targetTriangles ? QJsonValue(double(o.decimation.targetTriangles)) : QJsonValue();
    j["max_error_m"] = std::isfinite(o.decimation.maxError) ? QJsonValue(o.decimation.maxError) : QJsonValue();
  }
  j["lod_levels"] = o.lodLevels;
  j["lod_ratio"] = o.lodRatio;
  j["samples_per_face"] = o.error.samplesPerFace;
  return j;
}

}  // namespace

ImportedMesh importMeshFiles(const MeshImportRequest& request, const Progress* progress) {
  ImportedMesh out;
  if (request.files.empty()) {
    out.error = "no mesh file given";
    return out;
  }
  const double readShare = request.process ? 0.35 : 1.0;
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
      t.readTile = importMeshIsolated;
      mesh::TileImportResult r = mesh::importTiles(request.files, t, &read);
      out.cancelled = r.cancelled;
      out.error = std::move(r.error);
      out.tiles = std::move(r.tiles);
      out.tileBorderVertices = r.borderVertices;
      out.tileBorderVerticesSnapped = r.borderVerticesSnapped;
      out.tileBorderVerticesMerged = r.borderVerticesMerged;
      if (r.mesh && !out.tiles.empty()) out.import = sumTileReports(out.tiles, *r.mesh);
      out.mesh = std::move(r.mesh);
    }
  }
  if (isCancelled(progress)) out.cancelled = true;
  if (!out.ok()) {
    if (out.error.empty() && !out.cancelled) out.error = request.files.front() + ": the file could not be read";
    out.mesh.reset();
    return out;
  }

  QJsonObject importJson = importReportToJsonObject(out.import);
  if (!out.tiles.empty()) {
    QJsonArray tiles;
    for (const auto& t : out.tiles) tiles.append(importReportToJsonObject(t));
    importJson["tiles"] = tiles;
  }
  out.importReportJson = compact(importJson);
  if (!request.process) return out;

  Progress work(progress, readShare, 1.0);
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

  QJsonObject report = parseObject(storedProcessReportJson(out.process, request.processing));
  if (!out.tiles.empty()) report["tiles"] = tilesJson(out, request.tileWeldTolerance);
  out.processReportJson = compact(report);
  return out;
}

std::string storedProcessReportJson(const mesh::ProcessReport& process, const mesh::ProcessOptions& options) {
  QJsonObject report = parseObject(mesh::processReportJson(process, nullptr));
  report.remove("import");  // stored beside it as the asset's import report
  report["options"] = optionsJson(options);
  return compact(report);
}

QJsonObject importReportFileJson(const ImportedMesh& r) {
  QJsonObject o = importReportToJsonObject(r.import);
  o["processing"] = r.processReportJson.empty() ? QJsonValue() : QJsonValue(parseObject(r.processReportJson));
  if (!r.tiles.empty()) {
    QJsonArray tiles;
    for (const auto& t : r.tiles) tiles.append(importReportToJsonObject(t));
    o["tiles"] = tiles;
  }
  if (!r.error.empty()) o["error"] = QString::fromStdString(r.error);
  return o;
}

}  // namespace hs::scene
