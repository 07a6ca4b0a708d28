#pragma once
// The demo's lights beside its sun and its fog: a warm spot light on the big
// bunny, two point lights by the smaller ones, and depth-cued fog that
// reads on the valley behind them (docs/rendering.md "Lights and exposure",
// "Fog"). Values in physical units, for the demo's daylight exposure (the
// default EV100, 15.2 − log2 π), so the lights are as bright as floodlights.
#include "scene/scene_state.h"

namespace hs::scene {

void addDemoLights(SceneState& state);

}  // namespace hs::scene
