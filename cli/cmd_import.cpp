#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli/commands.h"
#include "cli/import_request.h"
#include "cli/import_summary.h"
#include "cli/scene_open.h"
#include "core/escape_control.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/import_pipeline.h"
#include "scene/mesh_report_text.h"
#include "scene/operations.h"
#include "scene/tileset_import.h"

namespace hs::cli {

int runImport(int argc, char** argv) {
  OperationArgs args(scene::meshImportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& positional = args.positionals();
  if (positional.size() < 2) return args.usage("expected <mesh-file> [more tiles ...] <scene.hscene>");
  const std::vector<std::string> meshPaths(positional.begin(), positional.end() - 1);
  const std::string meshPath = meshPaths.front();
  const std::string scenePath = positional.back();

  std::string error;
  scene::MeshImportRequest request;
  request.files = meshPaths;
  if (!parseImportRequest(args, request, error)) return args.usage(error);
  // A streamed build's scratch and page files beside the scene (the system's
  // temp folder is often in memory).
  request.scratchDir = std::filesystem::absolute(scenePath).parent_path().string();
  scene::ops::Placement placement;
  if (args.has("at_m")) {
    const std::vector<double> at = args.numbers("at_m");
    placement.at = glm::dvec3(at[0], at[1], at[2]);
  }
  if (args.has("name") && args.text("name").empty()) return args.usage("--name must not be empty");

  // Open the scene first: a bad scene path should not cost a long import.
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error + (std::filesystem::exists(scenePath) ? "" : " (create it with: hybridscape-cli new " + scenePath + ")"));

  Progress progress = terminalProgress("Importing " + std::filesystem::path(meshPath).filename().string() +
                                       (meshPaths.size() > 1 ? " and " + std::to_string(meshPaths.size() - 1) + " more" : ""));
  scene::ImportedMesh result = scene::importMeshFiles(request, &progress);
  if (args.has("report")) {
    const std::string reportPath = args.text("report");
    std::ofstream out(reportPath);
    out << writeJson(scene::importReportFileJson(result)) << "\n";
    if (!out) return args.fail(reportPath + ": cannot write the report");
  }
  if (!result.ok()) return args.fail(result.error.empty() ? meshPath + ": the import did not finish" : result.error);
  // Reader warnings quote the file's lines: shown escaped (core/escape_control.h).
  for (const auto& w : result.import.warnings) std::fprintf(stderr, "warning: %s\n", escapeControlCharacters(w).c_str());

  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const std::string name = args.has("name") ? args.text("name") : scene::importedMeshName(meshPath);
  // A clustered scan keeps a coarse cut as its mesh: say what was read.
  const bool clustered = result.clusters != nullptr;
  const size_t tris = clustered ? result.clusterReport.trianglesPerLevel.front() : result.mesh->triangleCount();
  const size_t verts = clustered ? result.import.verticesOut : result.mesh->vertexCount();
  const mesh::ClusterBuildReport clusterReport = result.clusterReport;
  const std::optional<mesh::StreamedClusterReport> streamed = result.streamed;
  const size_t proxyTriangles = result.mesh->triangleCount();
  const float proxyError = result.proxyError;
  const glm::dvec3 origin = result.mesh->origin;
  const mesh::ImportReport importReport = result.import;
  const Json processReport = result.processReport;
  const scene::EntityId id = scene::ops::addImportedMesh(doc, std::move(result), name, meshPath, placement);
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  const auto& t = doc.state().find(id)->transform.translation;
  std::printf("imported %s%s: %zu triangles, %zu vertices in %.3f s (reader %s); entity %llu '%s' at %.3f,%.3f,%.3f "
              "(mesh origin %.3f,%.3f,%.3f)\n",
              meshPath.c_str(), meshPaths.size() > 1 ? (" and " + std::to_string(meshPaths.size() - 1) + " more tiles").c_str() : "",
              tris, verts, importReport.seconds, importReport.reader.c_str(),
              static_cast<unsigned long long>(id), name.c_str(), t.x, t.y, t.z, origin.x, origin.y, origin.z);
  if (!importReport.geoOffsetSource.empty())
    std::printf("georeferencing offset %.3f,%.3f,%.3f from %s\n", importReport.geoOffset.x, importReport.geoOffset.y,
                importReport.geoOffset.z, importReport.geoOffsetSource.c_str());
  printProcessReport(processReport);
  if (clustered) {
    std::printf("cluster hierarchy: %zu levels (", clusterReport.clustersPerLevel.size());
    for (size_t l = 0; l < clusterReport.clustersPerLevel.size(); ++l)
      std::printf("%s%zu clusters", l ? ", " : "", clusterReport.clustersPerLevel[l]);
    std::printf("), %zu roots, built in %.2f s; coarse mesh %zu triangles (error %.4g m)\n", clusterReport.roots,
                clusterReport.seconds, proxyTriangles, double(proxyError));
    if (streamed)
      std::printf("built out of core: %zu cells of the spatial partition, %zu border positions, %.1f MB of scratch "
                  "files; read %.2f s, partition %.2f s, build %.2f s\n",
                  streamed->cells, streamed->borderPositions, double(streamed->scratchBytes) / 1e6,
                  streamed->readSeconds, streamed->partitionSeconds, streamed->buildSeconds);
  }
  for (const std::string& w : scene::processWarnings(processReport)) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return 0;
}

}  // namespace hs::cli
