#pragma once
// Bakes the octahedral impostors a scene's foliage types draw
// (scene::ops::impostorsToBake: missing or stale, or every one with `all`)
// on a headless context (render::Renderer::bakeImpostor) and stores them in
// the document (scene::ops::storeImpostors), printing a line per asset:
// `foliage impostors` and `demo` share it.
#include <string>

#include "scene/document.h"

namespace hs::cli {

struct ImpostorBake {
  bool ok = true;
  std::string error;  // !ok: headless GL or a bake failed; the document is unchanged
  size_t baked = 0, stored = 0;  // baked 0: every one stored and current, nothing to do (no GL started)
};
ImpostorBake bakeImpostors(scene::Document& doc, bool all);

}  // namespace hs::cli
