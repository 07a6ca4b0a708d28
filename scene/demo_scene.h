#pragma once
// The built-in demo scene: what the editor opens with no file and what
// `hybridscape-cli demo` writes. It grows with every capability so a
// newcomer sees each feature in it.
#include <optional>
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

// What File > New and `hybridscape-cli new` start from: a sun and a camera
// (as Blender's default scene has), no geometry.
SceneState buildStarterScene();

// Builds the demo from the files compiled into the binary. Fails (nullopt,
// `error` set) only if those resources are missing from the build.
std::optional<SceneState> buildDemoScene(std::string& error);

}  // namespace hs::scene
