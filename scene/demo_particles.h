#pragma once
// The demo scene's particles (docs/particles.md): snow falling around the
// clearing (sticking where it lands), a fog bank drifting in front of and
// between the pillars, and a torch (flame and smoke) on top of the tallest
// pillar, where a monastery would stand. Rates are kept low enough that a
// frame evaluated cold (alone, on a farm node) costs well under a second on
// two cores.
#include <string>

#include "scene/scene_state.h"

namespace hs::scene {

// Adds the emitters' entities to `s`, which must have its terrain already
// (scene/demo_terrain.h): the snow and fog stand on it, the torch on a pillar.
bool addDemoParticles(SceneState& s, std::string& error);

}  // namespace hs::scene
