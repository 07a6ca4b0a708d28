#pragma once
// A patch is the before and after value of everything one edit touched.
// Applying `after` redoes the edit, applying `before` undoes it; because both
// are whole values, undo restores the document exactly, whatever the edit.
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "scene/scene_state.h"

namespace hs::scene {

template <class T>
struct BeforeAfter {
  std::optional<T> before;  // nullopt: did not exist
  std::optional<T> after;   // nullopt: removed
};

struct ScenePatch {
  std::map<EntityId, BeforeAfter<Entity>> entities;
  std::optional<std::pair<std::vector<EntityId>, std::vector<EntityId>>> roots;  // before, after
  std::map<AssetId, BeforeAfter<MeshAsset>> assets;
  // Terrains' small values and which tiles they point to (not the tiles'
  // content: stroke-like edits are TerrainCommands, terrain_command.h).
  std::map<TerrainId, BeforeAfter<TerrainAsset>> terrains;
  std::map<MaterialId, BeforeAfter<Material>> materials;
  std::map<TextureId, BeforeAfter<TextureAsset>> textures;
  std::optional<std::pair<SceneSettings, SceneSettings>> settings;
  std::optional<std::pair<sequencer::Sequence, sequencer::Sequence>> sequence;  // before, after

  bool empty() const {
    return entities.empty() && !roots && assets.empty() && terrains.empty() && materials.empty() && textures.empty() &&
           !settings && !sequence;
  }
  // Folds a later patch into this one (gizmo drags merge into one undo step).
  void mergeLater(const ScenePatch& later);
  // Drops entries whose before equals after.
  void prune();
};

// Writes the patch's `after` (forward) or `before` (!forward) into `state`.
void applyPatch(SceneState& state, const ScenePatch& patch, bool forward);

}  // namespace hs::scene
