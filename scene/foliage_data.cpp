#include "scene/foliage_data.h"

#include "scene/scene_state.h"

namespace hs::scene {

std::shared_ptr<FoliageData> FoliageData::snapshot() const {
  auto copy = std::make_shared<FoliageData>(store_);
  copy->revision_ = revision_;
  copy->pendingManifest = pendingManifest;
  return copy;
}

FoliageData& foliageOf(SceneState& state) {
  if (!state.foliage) state.foliage = std::make_shared<FoliageData>();
  return *state.foliage;
}

const foliage::FoliageStore* foliageStoreOf(const SceneState& state) {
  return state.foliage ? &state.foliage->store() : nullptr;
}

AssetId foliageTypeAsset(const SceneState& state, const foliage::FoliageType& type) {
  for (const auto& [id, a] : state.assets)
    if (a.name == type.mesh) return id;
  return kNoAsset;
}

}  // namespace hs::scene
