#pragma once
// The demo's post chain (docs/rendering.md "Post-processing"): bloom on the
// torch's flames and the brightest sunlit surfaces, and a grade with a LUT
// stored in the scene ("meteora_dusk.cube", made here: warm highlights on
// the sandstone, slightly cooler shadows, a gentle S curve), mixed in at
// 70 %. It also stores an OpenColorIO config ("meteora_film.ocio", made
// here: a "Film" view whose curve is a 1D LUT under its search path, and
// "Raw"), its view transform off so the demo keeps its tone map; the Post
// dock's View transform box shows it. The other effects stay off.
#include "scene/scene_state.h"

namespace hs::scene {

// The demo's LUT as .cube text: `size` points per axis.
std::string demoLutCube(int size = 33);
// The demo's OpenColorIO config with its LUT, as `ocio import` would store it.
OcioConfigData demoOcioConfig();
void addDemoPost(SceneState& state);

}  // namespace hs::scene
