#pragma once
// The camera-cut track checked against the scene's cameras (no Qt: the
// renderer's export path asks it too; the edits are camera_cut_ops.h).
#include <string>
#include <vector>

#include "scene/scene_state.h"
#include "sequencer/camera_cuts.h"

namespace hs::scene {

// Why `cuts` cannot be rendered in `state` (sequencer::cutsProblem with the
// state's cameras, named by their names), or "": an edit's candidate track
// is checked without copying the state.
std::string cutsProblem(const SceneState& state, const std::vector<sequencer::CameraCut>& cuts);
// The same for the state's own cuts.
inline std::string cutsProblem(const SceneState& state) { return cutsProblem(state, state.sequence.cuts); }

}  // namespace hs::scene
