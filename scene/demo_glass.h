#pragma once
// The demo's translucent samples (issue 13, docs/rendering.md
// "Transparency"): glass-like spheres by the bunnies and a pond of
// translucent water in the valley, drawn by the transparency path.
#include "scene/scene_state.h"

namespace hs::scene {

void addDemoTranslucentSamples(SceneState& state);

}  // namespace hs::scene
