#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/import_request.h"
#include "cli/import_summary.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/import_pipeline.h"
#include "scene/operations.h"

namespace hs::cli {

int runImport(int argc, char** argv) {
  const char* cmd = "import";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, importOptionSpecs(), args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli import <mesh-file> [more tiles ...] <scene.hscene> [options]\n\n"
        "Imports a mesh (OBJ, FBX, PLY, glTF/GLB, DAE, 3DS, STL) into an existing scene\n"
        "as a new asset and an entity showing it, and saves the scene. Several files\n"
        "are the tiles of one scan: they share one origin, their borders are welded\n"
        "and they become one asset.\n\n"
        "  --at x,y,z         put the centre of the mesh's base here (default: where\n"
        "                     the file's coordinates put it, e.g. at UTM coordinates)\n"
        "  --up auto|y|z      the file's up axis (default auto: FBX says, glTF is Y,\n"
        "                     OBJ/PLY are taken as Y-up; scans in UTM are Z-up)\n"
        "  --reader auto|obj|assimp   force a reader (default: own OBJ reader for .obj)\n"
        "  --name NAME        entity and asset name (default: the file's base name)\n"
        "  --origin auto|none|x,y,z|FILE   georeferencing offset added to the file's\n"
        "                     coordinates: auto reads a sidecar beside each file (Pix4D\n"
        "                     *_offset.xyz, OpenDroneMap, offset.xyz), none (default)\n"
        "                     takes them as they are, x,y,z sets it by hand\n"
        "  --decimate-to N    decimate to a triangle count (500k, 2M, 120000) or a\n"
        "                     share of the triangles (10%%)\n"
        "  --max-error M      decimate as far as a Hausdorff error of M metres allows\n"
        "                     (with --decimate-to: whichever comes first)\n"
        "  --lods N           build N coarser levels of detail (a quarter each) with\n"
        "                     their measured error; the renderer picks one per instance\n"
        "  --clean            clean without decimating (implied by the three above):\n"
        "                     weld duplicates, remove degenerate faces, split non-manifold\n"
        "  --report FILE      write the import and processing report as JSON\n"
        "                     (hausdorff_m, hausdorff_rel, mean_m, rms_m, p95_m, ...)\n"
        "  --strict-textures  fail if a texture cannot be loaded (default: warn)\n");
    return 0;
  }
  if (args.positional.size() < 2) return usage(cmd, "expected <mesh-file> [more tiles ...] <scene.hscene>");
  const std::vector<std::string> meshPaths(args.positional.begin(), args.positional.end() - 1);
  const std::string meshPath = meshPaths.front();
  const std::string scenePath = args.positional.back();

  scene::MeshImportRequest request;
  request.files = meshPaths;
  if (!parseImportRequest(args, request, error)) return usage(cmd, error);
  scene::ops::Placement placement;
  if (auto at = args.get("at")) {
    double v[3];
    if (!parseVec3(*at, v, error)) return usage(cmd, "--at: " + error);
    placement.at = glm::dvec3(v[0], v[1], v[2]);
  }

  // Open the scene first: a bad scene path should not cost a long import.
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error + (std::filesystem::exists(scenePath) ? "" : " (create it with: hybridscape-cli new " + scenePath + ")"));

  Progress progress = terminalProgress("Importing " + std::filesystem::path(meshPath).filename().string() +
                                       (meshPaths.size() > 1 ? " and " + std::to_string(meshPaths.size() - 1) + " more" : ""));
  scene::ImportedMesh result = scene::importMeshFiles(request, &progress);
  if (auto reportPath = args.get("report")) {
    std::ofstream out(*reportPath);
    out << writeJson(scene::importReportFileJson(result)) << "\n";
    if (!out) return fail(cmd, *reportPath + ": cannot write the report");
  }
  if (!result.ok()) return fail(cmd, result.error.empty() ? meshPath + ": the import did not finish" : result.error);
  for (const auto& w : result.import.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const std::string name = args.get("name").value_or(std::filesystem::path(meshPath).stem().string());
  const size_t tris = result.mesh->triangleCount(), verts = result.mesh->vertexCount();
  const glm::dvec3 origin = result.mesh->origin;
  const mesh::ImportReport importReport = result.import;
  const Json processReport = result.processReport;
  const scene::EntityId id = scene::ops::addImportedMesh(doc, std::move(result), name, meshPath, placement);
  if (!scene::saveScene(doc.state(), scenePath, error)) return fail(cmd, error);
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
  return 0;
}

}  // namespace hs::cli
