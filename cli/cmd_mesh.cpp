// `hybridscape-cli mesh`: mesh subcommands (export).
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/subcommands.h"
#include "scene/mesh_export_operation.h"

namespace hs::cli {
namespace {

int runMeshExport(int argc, char** argv) {
  OperationArgs args(scene::meshExportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 3) return args.usage("expected a scene, an asset or entity name, and a file");
  const std::string& path = args.positionals()[0];
  scene::MeshExportRequest request = scene::MeshExportRequest::fromParams(
      Json{{"lod", args.integer("lod")}, {"world", args.flag("world")}, {"format", args.text("format")},
           {"up", args.text("up")}, {"crs", args.text("crs")}, {"draco_bits", args.integer("draco_bits")}});
  request.target = args.positionals()[1];
  request.out = args.positionals()[2];
  std::string error;
  std::optional<scene::SceneState> s = openScene(path, error);
  if (!s) return args.fail(error);
  Progress progress = terminalProgress("Exporting " + request.target);
  const scene::MeshExportOutcome o = scene::exportSceneMesh(*s, request, &progress);
  if (!o.result.ok()) return args.fail(o.result.error);
  std::printf("wrote %s as %s: %zu triangles, %zu vertices%s\n", o.what.c_str(),
              o.tiles3d ? "3dtiles" : mesh::exportFormatName(o.format), o.result.triangles, o.result.vertices,
              request.world && !o.tiles3d ? ", world coordinates" : "");
  for (const std::string& n : o.notes) std::printf("%s\n", n.c_str());
  for (const std::string& f : o.result.written) std::printf("  %s\n", f.c_str());
  for (const std::string& w : o.result.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return 0;
}

const Subcommand kSubs[] = {
    {"export", scene::meshExportOperation, runMeshExport},
};

}  // namespace

int runMesh(int argc, char** argv) { return runSubcommands("mesh", "", kSubs, argc, argv); }

}  // namespace hs::cli
