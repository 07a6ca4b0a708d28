#pragma once
// A mesh named on the command line: an entity with a mesh (what the
// outliner shows) first, else a mesh asset by name. `mesh export` and
// `material assign` take it the same way.
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

struct MeshTarget {
  const MeshAsset* asset = nullptr;  // null when not found (then `error` says why)
  EntityId entity = kNoEntity;       // the entity named, if it was one
  std::string what;                  // "entity 'Bunny' (asset 'bunny')" or "asset 'bunny'"
};

// The mesh asset `name` means in `state`; asset null and `error` set (the
// message lists the scene's mesh assets) when nothing of that name has a mesh.
MeshTarget findMeshTarget(const SceneState& state, const std::string& name, std::string& error);

}  // namespace hs::scene
