#include "scene/asset_reports.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "meshproc/report_json.h"

namespace hs::scene {
namespace {

// What the user asked for, so a reopened report says what it measured.
Json optionsJson(const mesh::ProcessOptions& o) {
  Json j = Json::object();
  j["decimate"] = o.decimate;
  if (o.decimate) {
    // The target is a ratio or a count, whichever was given; no maximum
    // error is null (JSON has no infinity).
    j["target_ratio"] = o.decimation.targetTriangles ? Json() : Json(o.decimation.targetRatio);
    j["target_triangles"] = o.decimation.targetTriangles ? Json(o.decimation.targetTriangles) : Json();
    j["max_error_m"] = std::isfinite(o.decimation.maxError) ? Json(o.decimation.maxError) : Json();
  }
  j["refine"] = o.refine;
  j["certify"] = o.error.certify;
  j["lod_levels"] = o.lodLevels;
  j["lod_ratio"] = o.lodRatio;
  j["samples_per_face"] = o.error.samplesPerFace;
  j["lod_samples_per_face"] = o.lodSamplesPerFace;
  return j;
}

bool readOptions(JsonReader& r, const Json& j, const std::string& path, mesh::ProcessOptions& o) {
  o.refine = false;  // reports written before the refinement existed have no "refine": none ran
  if (!r.object(j, path) || !r.optBoolean(j, path, "decimate", o.decimate) ||
      !r.optNumber(j, path, "target_ratio", o.decimation.targetRatio) ||
      !r.optBoolean(j, path, "refine", o.refine) || !r.optBoolean(j, path, "certify", o.error.certify) ||
      !r.optInteger(j, path, "lod_levels", o.lodLevels, 0, 1000) || !r.optNumber(j, path, "lod_ratio", o.lodRatio) ||
      !r.optNumber(j, path, "samples_per_face", o.error.samplesPerFace))
    return false;
  // Reports written before LOD levels had their own rate measured them at
  // the result's.
  o.lodSamplesPerFace = o.error.samplesPerFace;
  if (!r.optNumber(j, path, "lod_samples_per_face", o.lodSamplesPerFace)) return false;
  if (const Json* t = JsonReader::member(j, "target_triangles"); t && !t->is_null()) {
    int64_t n = 0;
    if (!r.integer(*t, jsonPath(path, "target_triangles"), n, 0, int64_t(1) << 53)) return false;
    o.decimation.targetTriangles = size_t(n);
  }
  if (const Json* m = JsonReader::member(j, "max_error_m")) {
    if (m->is_null()) o.decimation.maxError = std::numeric_limits<double>::infinity();
    else if (!r.number(*m, jsonPath(path, "max_error_m"), o.decimation.maxError)) return false;
  }
  return true;
}

Json tilesJson(const TileWeldReport& t) {
  Json j = Json::object();
  j["files"] = t.files;
  j["weld_tolerance_m"] = t.weldTolerance;
  j["border_vertices"] = t.borderVertices;
  j["border_vertices_snapped"] = t.borderVerticesSnapped;
  j["border_vertices_merged"] = t.borderVerticesMerged;
  return j;
}

bool readTiles(JsonReader& r, const Json& j, const std::string& path, TileWeldReport& t) {
  if (!r.object(j, path) || !r.optNumber(j, path, "weld_tolerance_m", t.weldTolerance)) return false;
  for (auto [key, out] : {std::pair{"files", &t.files}, {"border_vertices", &t.borderVertices},
                          {"border_vertices_snapped", &t.borderVerticesSnapped},
                          {"border_vertices_merged", &t.borderVerticesMerged}}) {
    const Json* m = JsonReader::member(j, key);
    int64_t n = 0;
    if (m && !r.integer(*m, jsonPath(path, key), n, 0, INT64_MAX)) return false;
    if (m) *out = size_t(n);
  }
  return true;
}

}  // namespace

Json toJson(const AssetImportReport& r) {
  Json j = mesh::toJson(r.report);
  if (!r.tiles.empty()) {
    Json tiles = Json::array();
    for (const auto& t : r.tiles) tiles.push_back(mesh::toJson(t));
    j["tiles"] = std::move(tiles);
  }
  return j;
}

bool fromJson(JsonReader& r, const Json& j, const std::string& path, AssetImportReport& out) {
  if (!mesh::fromJson(r, j, path, out.report)) return false;
  const Json* tiles = JsonReader::member(j, "tiles");
  if (!tiles) return true;
  const std::string tp = jsonPath(path, "tiles");
  if (!r.array(*tiles, tp)) return false;
  for (size_t i = 0; i < tiles->size(); ++i) {
    mesh::ImportReport t;
    if (!mesh::fromJson(r, (*tiles)[i], jsonIndex(tp, i), t)) return false;
    out.tiles.push_back(std::move(t));
  }
  return true;
}

Json toJson(const AssetProcessReport& r) {
  Json j = mesh::toJson(r.report);
  j["options"] = optionsJson(r.options);
  if (r.tiles) j["tiles"] = tilesJson(*r.tiles);
  return j;
}

bool fromJson(JsonReader& r, const Json& j, const std::string& path, AssetProcessReport& out) {
  if (!mesh::fromJson(r, j, path, out.report)) return false;
  const Json* options = JsonReader::member(j, "options");
  if (options && !readOptions(r, *options, jsonPath(path, "options"), out.options)) return false;
  if (const Json* t = JsonReader::member(j, "tiles"); t && !t->is_null()) {
    TileWeldReport tiles;
    if (!readTiles(r, *t, jsonPath(path, "tiles"), tiles)) return false;
    out.tiles = tiles;
  }
  return true;
}

std::optional<AssetProcessReport> readProcessReport(const Json& json) {
  if (json.is_null()) return std::nullopt;
  std::string error;
  JsonReader r(error);
  AssetProcessReport report;
  if (!fromJson(r, json, "", report)) return std::nullopt;
  return report;
}

}  // namespace hs::scene
