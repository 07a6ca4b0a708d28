#include <cstdio>
#include <filesystem>
#include <fstream>

#include <QJsonDocument>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "mesh/mesh_import.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/report_json.h"

namespace hs::cli {

int runImport(int argc, char** argv) {
  const char* cmd = "import";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"at"}, {"up"}, {"reader"}, {"name"}, {"report"}, {"strict-textures", false}}, args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli import <mesh-file> <scene.hscene> [options]\n\n"
        "Imports a mesh (OBJ, FBX, PLY, glTF/GLB, DAE, 3DS, STL) into an existing scene\n"
        "as a new asset and an entity showing it, and saves the scene.\n\n"
        "  --at x,y,z         put the centre of the mesh's base here (default: where\n"
        "                     the file's coordinates put it, e.g. at UTM coordinates)\n"
        "  --up auto|y|z      the file's up axis (default auto: FBX says, glTF is Y,\n"
        "                     OBJ/PLY are taken as Y-up; scans in UTM are Z-up)\n"
        "  --reader auto|obj|assimp   force a reader (default: own OBJ reader for .obj)\n"
        "  --name NAME        entity and asset name (default: the file's base name)\n"
        "  --report FILE      write the import report as JSON\n"
        "  --strict-textures  fail if a texture cannot be loaded (default: warn)\n");
    return 0;
  }
  if (args.positional.size() != 2) return usage(cmd, "expected <mesh-file> <scene.hscene>");
  const std::string meshPath = args.positional[0];
  const std::string scenePath = args.positional[1];

  mesh::ImportOptions options;
  if (auto up = args.get("up")) {
    if (*up == "y") options.up = mesh::UpAxis::Y;
    else if (*up == "z") options.up = mesh::UpAxis::Z;
    else if (*up != "auto") return usage(cmd, "--up takes auto, y or z");
  }
  if (auto r = args.get("reader")) {
    if (*r == "obj") options.reader = mesh::Reader::Obj;
    else if (*r == "assimp") options.reader = mesh::Reader::Assimp;
    else if (*r != "auto") return usage(cmd, "--reader takes auto, obj or assimp");
  }
  options.strictTextures = args.has("strict-textures");
  scene::ops::Placement placement;
  if (auto at = args.get("at")) {
    double v[3];
    if (!parseVec3(*at, v, error)) return usage(cmd, "--at: " + error);
    placement.at = glm::dvec3(v[0], v[1], v[2]);
  }

  // Open the scene first: a bad scene path should not cost a long import.
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error + (std::filesystem::exists(scenePath) ? "" : " (create it with: hybridscape-cli new " + scenePath + ")"));

  Progress progress = terminalProgress("Importing " + std::filesystem::path(meshPath).filename().string());
  mesh::ImportResult result = mesh::importMesh(meshPath, options, &progress);
  if (auto reportPath = args.get("report")) {
    std::ofstream out(*reportPath);
    QJsonObject o = scene::importReportToJsonObject(result.report);
    if (!result.ok()) o["error"] = QString::fromStdString(result.error);
    out << QJsonDocument(o).toJson().toStdString();
    if (!out) return fail(cmd, *reportPath + ": cannot write the report");
  }
  if (!result.ok()) return fail(cmd, result.error);
  for (const auto& w : result.report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const std::string name = args.get("name").value_or(std::filesystem::path(meshPath).stem().string());
  const size_t tris = result.mesh->triangleCount(), verts = result.mesh->vertexCount();
  const glm::dvec3 origin = result.mesh->origin;
  const scene::EntityId id =
      scene::ops::addImportedMesh(doc, std::move(*result.mesh), name, meshPath, result.report, placement);
  if (!scene::saveScene(doc.state(), scenePath, error)) return fail(cmd, error);
  const auto& t = doc.state().find(id)->transform.translation;
  std::printf("imported %s: %zu triangles, %zu vertices in %.3f s (reader %s); entity %llu '%s' at %.3f,%.3f,%.3f "
              "(mesh origin %.3f,%.3f,%.3f)\n",
              meshPath.c_str(), tris, verts, result.report.seconds, result.report.reader.c_str(),
              static_cast<unsigned long long>(id), name.c_str(), t.x, t.y, t.z, origin.x, origin.y, origin.z);
  return 0;
}

}  // namespace hs::cli
