#pragma once
// The scene at a time t: the document's state with the sequence's values
// written into it. A pure function of (state, t) (DESIGN.md, "Time and
// determinism"): scrubbing, playback, export and every farm chunk call this
// and see the same scene for the same t.
#include <string>
#include <vector>

#include "scene/scene_state.h"
#include "sequencer/sequence.h"

namespace hs::scene {

// Compiles state.sequence once; reuse it for every frame of a playback or export.
sequencer::CompiledSequence compileSequence(const SceneState& state);

// `base` with the values of `compiled` at time `t` applied: transforms,
// camera and light fields, visibility, any numeric field. Values for missing
// entities or unknown properties are skipped and reported in `warnings`.
SceneState animatedState(const SceneState& base, const sequencer::CompiledSequence& compiled, double t,
                         std::vector<std::string>* warnings = nullptr);

// Writes one sampled value into an entity; false (with `error`) if the
// property does not exist on it or the value has the wrong shape.
bool applyPropertyValue(Entity& entity, const std::string& property, const sequencer::PropertyValue& value,
                        std::string& error);

}  // namespace hs::scene
