#pragma once
// The camera-cut track as `cut list` and `info` show it (cmd_cut.cpp).
#include "core/json.h"
#include "scene/scene_state.h"

namespace hs::cli {

// One object per cut: number, camera (name and id), frames, seconds, transition.
Json cutsJson(const scene::SceneState& state);
// One line per cut, then the track's problem when it has one.
void printCuts(const scene::SceneState& state);

}  // namespace hs::cli
