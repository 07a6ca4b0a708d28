#pragma once
// The demo scene's terrain: a small Meteora-like valley made from the
// terrain library alone (deterministic, no files): a valley floor of
// fractal hills, sandstone pillars with terraced flanks standing north of a
// flat clearing where the bunnies stand (z = 0 within 16 m of the origin),
// a pass of thermal erosion for scree aprons, and the default slope/altitude
// paint rules. About 320 x 320 m at 1.25 m, built in well under a second.
#include "scene/scene_state.h"

namespace hs::scene {

// Adds the terrain and an entity "Valley Terrain" showing it to `s`
// (after everything else, so existing ids stay). False with `error` if the
// terrain library refused (it does not, for these fixed values).
bool addDemoTerrain(SceneState& s, std::string& error);

}  // namespace hs::scene
