#pragma once
// A generated plant (foliage/plants.h) as mesh asset `id` of a
// render suite's or benchmark's scene, with its LOD chain and a material per
// slot; `plantLook` gives the leaves the editor's look (two-sided, cut-out,
// transmission: scene::ops::applyPlantLook). Exits the process on failure:
// a suite's setup has nothing to fall back to.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "foliage/plants.h"
#include "scene/foliage_ops.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

namespace hs::test {

inline void addPlantAsset(scene::SceneState& s, scene::AssetId id, const std::string& name,
                          const foliage::PlantParams& params, bool plantLook = false) {
  std::string error;
  std::optional<scene::MeshAsset> a = scene::ops::makePlantAsset(name, params, error);
  if (!a) {
    std::fprintf(stderr, "plant %s: %s\n", name.c_str(), error.c_str());
    std::exit(1);
  }
  a->id = id;
  s.assets.emplace(id, std::move(*a));
  scene::addMeshMaterials(s, id);
  if (plantLook)
    for (scene::MaterialId m : s.assets.at(id).materialSlots) scene::ops::applyPlantLook(s.materials.at(m));
}

}  // namespace hs::test
