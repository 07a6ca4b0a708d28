#pragma once
// `render` (one frame, or a frame sequence with any sequence option) and
// `farm slurm` (which hands render's options on to its array tasks),
// declared once (core/params.h). They live here, not in sequencer/,
// because they also override the scene's anti-aliasing (SceneSettings).
#include "core/params.h"
#include "scene/scene_state.h"

namespace hs::scene {

const OperationDecl& renderOperation();
const OperationDecl& farmSlurmOperation();

// --aa's choice as the scene's setting ("none", "fxaa", "msaa4").
Antialiasing antialiasingFromChoice(const std::string& name);

}  // namespace hs::scene
