#pragma once
// The demo scene's particles (docs/particles.md): light snow falling over
// the clearing and the near valley (sticking where it lands), a fog bank
// drifting between the pillars, and a torch (flame and smoke) on top of the
// tallest pillar, where a monastery would stand. Rates are kept low enough
// that a frame evaluated cold (alone, on a farm node) costs about a second
// on two cores.
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

// Adds the emitters' entities to `s`, which must have its terrain already
// (scene/demo_terrain.h): the snow and fog stand on it, the torch on a pillar.
bool addDemoParticles(SceneState& s, std::string& error);

}  // namespace hs::scene
