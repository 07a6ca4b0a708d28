#include "cli/impostor_bake.h"

#include <chrono>
#include <cstdio>

#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/impostor_ops.h"

namespace hs::cli {

ImpostorBake bakeImpostors(scene::Document& doc, bool all) {
  ImpostorBake out;
  const std::vector<scene::AssetId> ids = scene::ops::impostorsToBake(doc.state(), all);
  if (ids.empty()) return out;
  render::OffscreenRenderer renderer;
  if (!renderer.initialize(out.error)) {
    out.ok = false;
    out.error = "cannot start headless OpenGL: " + out.error;
    return out;
  }
  std::vector<scene::ops::BakedImpostor> baked;
  for (scene::AssetId id : ids) {
    const auto start = std::chrono::steady_clock::now();
    auto images = renderer.renderer().bakeImpostor(doc.state(), id, out.error);
    if (!images) {
      out.ok = false;
      return out;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const size_t blob = foliage::encodeImpostor(*images).size();
    std::printf("impostor of \"%s\": %d x %d frames of %d px, %.0f KiB stored (%.2f s)\n",
                doc.state().findAsset(id)->name.c_str(), images->frames, images->frames, images->framePixels,
                double(blob) / 1024.0, seconds);
    baked.emplace_back(id, std::make_shared<const foliage::ImpostorImages>(std::move(*images)));
  }
  out.baked = baked.size();
  const scene::ops::StoredImpostors stored = scene::ops::storeImpostors(doc, baked);
  for (const std::string& s : stored.skipped) std::fprintf(stderr, "warning: %s\n", s.c_str());
  out.stored = stored.stored;
  return out;
}

}  // namespace hs::cli
