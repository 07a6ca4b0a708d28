#pragma once
// The reports a mesh asset keeps (MeshAsset::importReport, ::processReport),
// in the form the .hscene description, `info --json` and the editor's Mesh
// Report hold them, each with its one writer and reader:
//
//   import report   mesh::ImportReport's fields (meshproc/report_json.h), and
//                   "tiles": one import report per file for a scan of several
//   process report  mesh::ProcessReport's fields, "options" (what was asked)
//                   and "tiles" (how several files were welded into one)
//
// Write, read, write gives the same bytes. Reading keeps the defaults of
// members an older file lacks and names the JSON path of a bad one.
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "mesh/mesh_import.h"
#include "meshproc/mesh_process.h"

namespace hs::scene {

struct AssetImportReport {
  mesh::ImportReport report;              // for several tiles: the counts summed
  std::vector<mesh::ImportReport> tiles;  // one per file when there were several
};

// How the tiles of one scan were welded into one mesh (mesh/tile_merge.h).
struct TileWeldReport {
  size_t files = 0;
  double weldTolerance = 0.0;  // metres
  size_t borderVertices = 0, borderVerticesSnapped = 0, borderVerticesMerged = 0;
};

struct AssetProcessReport {
  mesh::ProcessReport report;
  // What was asked, written as "options": decimate, target_ratio,
  // target_triangles, max_error_m (null: no bound), lod_levels, lod_ratio,
  // samples_per_face, lod_samples_per_face. Only those members are kept.
  mesh::ProcessOptions options;
  std::optional<TileWeldReport> tiles;
};

Json toJson(const AssetImportReport& report);
Json toJson(const AssetProcessReport& report);
bool fromJson(JsonReader& reader, const Json& json, const std::string& path, AssetImportReport& out);
bool fromJson(JsonReader& reader, const Json& json, const std::string& path, AssetProcessReport& out);

// A stored process report read back, for what shows it (the CLI, the
// editor); nullopt when there is none (null) or it is not one.
std::optional<AssetProcessReport> readProcessReport(const Json& json);

}  // namespace hs::scene
