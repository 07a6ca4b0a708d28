// hybridscape-cli foliage impostors: bakes the octahedral impostors of the
// meshes foliage types draw with one (render::Renderer::bakeImpostor, on a
// headless context) and stores them in the scene (scene/impostor_ops.h),
// so the scene opens and renders without baking and every render node
// draws the same far level.
#include <cstdio>

#include "cli/commands.h"
#include "cli/impostor_bake.h"
#include "cli/operation_options.h"
#include "cli/terrain_cli.h"
#include "foliage/foliage_operations.h"
#include "scene/hscene_file.h"

namespace hs::cli {

int runFoliageImpostors(int argc, char** argv) {
  OperationArgs args(foliage::foliageImpostorsOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected a scene file");
  const std::string path = args.positionals()[0];
  std::string error;
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  const ImpostorBake bake = bakeImpostors(doc, args.flag("all"));
  if (!bake.ok) return args.fail(bake.error);
  if (bake.baked == 0) {
    std::printf("%s: every impostor a foliage type draws is stored and current; nothing baked\n", path.c_str());
    return 0;
  }
  scene::SaveReport r;
  if (!scene::saveScene(doc.state(), path, error, &r)) return args.fail(error);
  std::printf("saved %s: %zu impostor(s) stored\n", path.c_str(), bake.stored);
  return 0;
}

}  // namespace hs::cli
