#pragma once
// The demo's depth of field (docs/rendering.md "Depth of field"): the
// flight camera at f/2.8 with its focus pulled on the timeline, from the
// bunnies it circles (8.1 m) to the valley behind them (30 m) and back.
// settings.depth_of_field stays off in the demo: on llvmpipe the layered
// pass costs more than the frame it would blur (bench/render/README.md,
// bench_dof), and the demo's goldens are rendered without it; turn it on
// in Scene Settings to see the focus pull.
#include "scene/scene_state.h"

namespace hs::scene {

void addDemoFocusPull(SceneState& state);

}  // namespace hs::scene
