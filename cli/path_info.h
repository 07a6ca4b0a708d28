#pragma once
// What `hybridscape-cli path` prints about a path: its points, aim,
// banking, length and timing (and the speed when it is constant).
#include <string>

#include "scene/scene_state.h"

namespace hs::cli {

// Several lines ending in '\n'; says so when the entity follows no path.
std::string describePath(const scene::SceneState& state, scene::EntityId id);

}  // namespace hs::cli
