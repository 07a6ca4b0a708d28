#pragma once
// The camera-cut track checked against the scene's cameras (no Qt: the
// renderer's export path asks it too; the edits are camera_cut_ops.h).
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

// Why the state's cuts cannot be rendered (sequencer::cutsProblem with the
// state's cameras, named by their names), or "".
std::string cutsProblem(const SceneState& state);

}  // namespace hs::scene
