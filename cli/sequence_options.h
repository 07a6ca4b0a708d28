#pragma once
// Options shared by the commands that render or check frame sequences:
// `render --frames ...`, `farm slurm` (which hands them on to its array
// tasks) and `farm verify`. Each parser returns false with a one-line
// reason that names the option.
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_args.h"
#include "scene/scene_state.h"
#include "sequencer/comfort_check.h"
#include "sequencer/frame_range.h"
#include "sequencer/stereo_layout.h"

namespace hs::cli {

// The options of `render` that make it a sequence render (any of them
// present, or --frames): without them `render` writes one frame as before.
const std::vector<std::string>& sequenceOnlyOptions();
bool isSequenceRender(const Args& args);

// --frames "0-35999", "10,20-30", "0-100x10"; without it the scene's
// playback range (`fallback`), when given.
bool parseFrames(const Args& args, const scene::SceneState* scene, sequencer::FrameList& out, std::string& error);
// --layout sbs|sbs-squeezed|tb|tb-squeezed|separate|anaglyph|mono (default sbs).
bool parseLayout(const Args& args, sequencer::StereoLayout& out, std::string& error);
// --size WxH, per eye (default 1920x1080).
bool parseEyeSize(const Args& args, int& width, int& height, std::string& error);
// --budget NEAR,FAR in percent of the image width ("-1,2": the default).
bool parseBudget(const Args& args, sequencer::ComfortBudget& out, std::string& error);
// A whole number option within [min, max].
bool parseIntOption(const Args& args, const std::string& name, int min, int max, int& out, std::string& error);

// The camera named `name` (an entity with a camera), or, with an empty name,
// the shot camera (render::shotCamera). An error lists the scene's cameras.
scene::EntityId findCamera(const scene::SceneState& scene, const std::string& name, const std::string& scenePath,
                           std::string& error);

// --aa none|fxaa|msaa4 overrides the scene's anti-aliasing.
bool applyAntialiasing(const Args& args, scene::SceneState& scene, std::string& error);

// "1:02:03" or "42 s" for progress lines.
std::string formatDuration(double seconds);

}  // namespace hs::cli
