#pragma once
// Bringing mesh files into a document the way the editor's Import dialog and
// `hybridscape-cli import` do it: read one file, or the tiles of one scan
// welded into one mesh (mesh/tile_merge.h), then optionally clean, decimate
// and build LODs (mesh/mesh_process.h), under one Progress. It runs on any
// thread and touches no document, so the editor runs it on a worker;
// ops::addImportedMesh then commits the result as one undo step.
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "core/params.h"
#include "core/progress.h"
#include "mesh/mesh_import.h"
#include "meshproc/cluster_build_streamed.h"
#include "meshproc/cluster_hierarchy.h"
#include "meshproc/mesh_process.h"
#include "scene/scene_state.h"

namespace hs::scene {

struct MeshImportRequest {
  std::vector<std::string> files;    // one file, or the tiles of one scan
  mesh::ImportOptions import;        // applied to every file (each finds its own sidecar)
  double tileWeldTolerance = 1e-3;   // metres: tile border vertices this close are one point
  // Off: the mesh is used as read (what a plain import always did). On: it
  // is cleaned, and decimated / given LODs as `processing` says.
  bool process = false;
  mesh::ProcessOptions processing;
  // A cluster hierarchy (scene/cluster_asset.h) built from the result:
  // Auto builds one for meshes of at least kClusterAutoTriangles, and
  // streams (Streamed) when the files hold kClusterStreamedAutoBytes or
  // more and no processing is asked for. Streamed: built out of core
  // (meshproc/cluster_build_streamed.h), the files read one at a time and
  // never merged in memory (tile borders snapped within tileWeldTolerance);
  // processing is refused (it needs the whole mesh).
  enum class Clusters { Auto, On, Streamed, Off } clusters = Clusters::Auto;
  mesh::ClusterOptions clusterOptions;
  std::string scratchDir;  // for a streamed build's scratch and page files; "": the system's temp folder
  // A 3D Tiles tileset (scene/tileset_import.h): the coordinate system its
  // ECEF frame is converted to ("auto": UTM for ECEF, else as it is;
  // "utm", "local", or any CRS PROJ knows).
  std::string tilesetCrs = "auto";
};

// Where `import` builds a cluster hierarchy unasked: a mesh this large
// drawn whole costs too much for one view (about 0.5 GB of GPU memory).
constexpr size_t kClusterAutoTriangles = 4'000'000;
// Where Auto builds the hierarchy out of core: files this large (about
// 35M triangles as binary PLY) would take ~10 GB to build in memory.
constexpr uint64_t kClusterStreamedAutoBytes = uint64_t(1) << 30;
// The coarse cut a clustered asset keeps as its mesh (MeshAsset::data).
constexpr size_t kClusterProxyTriangles = 65'536;

// `import` and the Import dialog, declared once (core/params.h): the
// reader's options (mesh::importOptionDecls), the processing ones
// (mesh::processOptionDecls), and where it goes: at_m, name, report.
const OperationDecl& meshImportOperation();
// The "clusters" choice (auto, on, streamed, off) as the request's mode.
MeshImportRequest::Clusters clustersMode(const std::string& choice);

// The out-of-core build's options as a request sets them (mesh files and
// tilesets streamed alike).
mesh::StreamedClusterOptions streamedClusterOptions(const MeshImportRequest& request);

struct ImportedMesh {
  std::optional<mesh::MeshData> mesh;  // level 0: as read, or cleaned and decimated
  std::vector<MeshLod> lods;           // coarser levels with their hashes and errors
  // The hierarchy when one was built; `mesh` is then its coarse cut.
  std::shared_ptr<const ClusterAsset> clusters;
  uint64_t clustersHash = 0;
  mesh::ClusterBuildReport clusterReport;
  std::optional<mesh::StreamedClusterReport> streamed;  // set when built out of core
  float proxyError = 0.0f;             // metres: the coarse cut's error
  mesh::ImportReport import;           // the file's; for tiles the counts summed (per tile in `tiles`)
  std::vector<mesh::ImportReport> tiles;  // one per file when there were several
  size_t tileBorderVertices = 0, tileBorderVerticesSnapped = 0, tileBorderVerticesMerged = 0;
  bool processed = false;
  mesh::ProcessReport process;
  Json importReport;                   // stored with the asset (MeshAsset::importReport)
  Json processReport;                  // stored with the asset; null when not processed
  std::string error;                   // names the file and the place
  bool cancelled = false;
  bool ok() const { return mesh.has_value() && error.empty() && !cancelled; }
};

// Never throws for bad input: `error` says what went wrong where.
ImportedMesh importMeshFiles(const MeshImportRequest& request, const Progress* progress = nullptr);

// What `hybridscape-cli import --report` writes: the import report's fields at
// the top (as before processing existed), "processing" (the processing
// report as the asset stores it, or null), "tiles" (one import report per
// file, when several) and, on failure, "error". Nothing reads it back: its
// parts are the asset's reports (scene/asset_reports.h), which have readers.
Json importReportFileJson(const ImportedMesh& result);

}  // namespace hs::scene
