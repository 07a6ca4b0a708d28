#pragma once
// The demo's surface-detail samples: brick paving with a normal map and a
// rock slab with a height map drawn with parallax occlusion mapping, both
// from textures made in code (mesh/procedural_textures.h, nothing to
// attribute), lying in the clearing south of the bunnies (behind the
// demo's first camera and its flight, whose pictures stay as they were). Added to `state` as assets, materials, textures and entities.
#include "scene/scene_state.h"

namespace hs::scene {

void addDemoDetailSamples(SceneState& state);

}  // namespace hs::scene
