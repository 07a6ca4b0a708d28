#pragma once
// The tag an export writes into each frame's description and that resume
// compares (sequencer/frame_verify.h): a hash of everything that decides the
// files, so a changed scene or changed settings render again instead of
// keeping stale frames, and the CLI, the editor and every farm task compute
// the same tag for the same scene and settings.
#include <string>

#include "render/stereo_frame_source.h"

namespace hs::render {

// The scene's description (canonical JSON: every entity, setting and the
// timeline, with each asset named by its content hash), the camera, eye
// size, layout, anaglyph method, grid, pixel depth and encoder quality.
std::string exportJobTag(const scene::SceneState& scene, scene::EntityId camera,
                         const sequencer::ExportSettings& settings, const StereoFrameOptions& options);

}  // namespace hs::render
