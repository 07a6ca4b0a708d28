#pragma once
// Options shared by the commands that render or check frame sequences:
// `render --frames ...`, `farm slurm` (which hands them on to its array
// tasks) and `farm verify`, as their declarations (scene/render_operation.h,
// sequencer/sequencer_operations.h) name them. Each returns false with a
// one-line reason that names the option.
#include <optional>
#include <string>
#include <vector>

#include "cli/operation_options.h"
#include "scene/scene_state.h"
#include "sequencer/comfort_check.h"
#include "sequencer/frame_range.h"
#include "sequencer/stereo_layout.h"

namespace hs::cli {

// Whether any of `render`'s sequence options (the export's: --frames,
// --layout, --video, ...) was given: without them `render` writes one frame.
bool isSequenceRender(const OperationArgs& args);

// --frames "0-35999", "10,20-30", "0-100x10", each frame within the declared
// frame numbers; without it the scene's playback range, when `scene` is given.
bool parseFrames(const OperationArgs& args, const scene::SceneState* scene, sequencer::FrameList& out,
                 std::string& error);
// --layout (default sbs).
sequencer::StereoLayout layoutOf(const OperationArgs& args);
// --size WxH, per eye (default 1920x1080).
void eyeSizeOf(const OperationArgs& args, int& width, int& height);
// --budget NEAR,FAR in percent of the image width (default -1,2).
void budgetOf(const OperationArgs& args, sequencer::ComfortBudget& out);

// The camera named `name` (an entity with a camera), or, with an empty name,
// the shot camera (render::shotCamera). An error lists the scene's cameras.
scene::EntityId findCamera(const scene::SceneState& scene, const std::string& name, const std::string& scenePath,
                           std::string& error);

// --aa none|fxaa|msaa4 overrides the scene's anti-aliasing.
void applyAntialiasing(const OperationArgs& args, scene::SceneState& scene);

// "1:02:03" or "42 s" for progress lines.
std::string formatDuration(double seconds);

}  // namespace hs::cli
