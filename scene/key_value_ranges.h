#pragma once
// Keyed values read from a file, held to their fields' declared ranges
// (scene/fields.cpp), as the loader holds the static values: a key whose
// value breaks its field's range or rule is clamped (or repaired) the way
// the field's setter does it, and named in a warning with the entity, the
// field and the frame. Without this a file could animate a camera to a
// field of view of 0 or a scale of 0 that no edit can set.
#include <string>
#include <vector>

#include "scene/scene_state.h"

namespace hs::scene {

// Clamps every out-of-range key value of `state.sequence` in place; one
// warning per key changed ("entity 3 'Cam': camera.fov_deg key at frame 120:
// 0 must be ...; now 1"), appended to `warnings` when it is not null.
void clampKeyValues(SceneState& state, std::vector<std::string>* warnings);

}  // namespace hs::scene
