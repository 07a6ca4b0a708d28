#pragma once
// Baked impostors kept in the document (MeshAsset::impostor): which assets
// a bake should cover, and storing what the renderer baked
// (render::Renderer::bakeImpostor) as one undo step. The editor's
// Foliage > Bake Impostors and `hybridscape-cli foliage impostors` share
// these; the bake itself needs GL and lives in render/.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "foliage/impostor_images.h"
#include "scene/document.h"

namespace hs::scene::ops {

// The mesh assets that foliage types draw with an impostor level
// (FoliageType::impostor), each once, in id order: those whose stored
// impostor is missing or stale, or every one with `all`.
std::vector<AssetId> impostorsToBake(const SceneState& state, bool all);

using BakedImpostor = std::pair<AssetId, std::shared_ptr<const foliage::ImpostorImages>>;
struct StoredImpostors {
  size_t stored = 0;
  std::vector<std::string> skipped;  // an asset gone, or changed since its bake, named
};
// Stores `baked` in their assets as one undo step ("Bake impostors"),
// skipping (and naming) an asset that is gone or whose mesh or materials
// changed after the bake read them.
StoredImpostors storeImpostors(Document& doc, const std::vector<BakedImpostor>& baked);

}  // namespace hs::scene::ops
