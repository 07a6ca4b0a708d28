// hybridscape-cli foliage impostors: bakes the octahedral impostors of the
// meshes foliage types draw with one (render::Renderer::bakeImpostor, on a
// headless context) and stores them in the scene (scene/impostor_ops.h),
// so the scene opens and renders without baking and every render node
// draws the same far level.
#include <chrono>
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/terrain_cli.h"
#include "foliage/foliage_operations.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/hscene_file.h"
#include "scene/impostor_ops.h"

namespace hs::cli {

int runFoliageImpostors(int argc, char** argv) {
  OperationArgs args(foliage::foliageImpostorsOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected a scene file");
  const std::string path = args.positionals()[0];
  std::string error;
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  const std::vector<scene::AssetId> ids = scene::ops::impostorsToBake(doc.state(), args.flag("all"));
  if (ids.empty()) {
    std::printf("%s: every impostor a foliage type draws is stored and current; nothing baked\n", path.c_str());
    return 0;
  }
  render::OffscreenRenderer renderer;
  if (!renderer.initialize(error)) return args.fail("cannot start headless OpenGL: " + error);
  std::vector<scene::ops::BakedImpostor> baked;
  for (scene::AssetId id : ids) {
    const auto start = std::chrono::steady_clock::now();
    auto images = renderer.renderer().bakeImpostor(doc.state(), id, error);
    if (!images) return args.fail(error);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const size_t blob = foliage::encodeImpostor(*images).size();
    std::printf("impostor of \"%s\": %d x %d frames of %d px, %.0f KiB stored (%.2f s)\n",
                doc.state().findAsset(id)->name.c_str(), images->frames, images->frames, images->framePixels,
                double(blob) / 1024.0, seconds);
    baked.emplace_back(id, std::make_shared<const foliage::ImpostorImages>(std::move(*images)));
  }
  const scene::ops::StoredImpostors stored = scene::ops::storeImpostors(doc, baked);
  for (const std::string& s : stored.skipped) std::fprintf(stderr, "warning: %s\n", s.c_str());
  scene::SaveReport r;
  if (!scene::saveScene(doc.state(), path, error, &r)) return args.fail(error);
  std::printf("saved %s: %zu impostor(s) stored\n", path.c_str(), stored.stored);
  return 0;
}

}  // namespace hs::cli
