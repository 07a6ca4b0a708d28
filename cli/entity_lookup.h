#pragma once
// Entities named on the command line: by name, or by numeric id.
#include <string>

#include "scene/scene_state.h"

namespace hs::cli {

// The entity named `who` (exact name first, then a number as an id), or kNoEntity.
scene::EntityId findEntity(const scene::SceneState& scene, const std::string& who);

}  // namespace hs::cli
