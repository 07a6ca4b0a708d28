#pragma once
// `hybridscape-cli render SCENE --frames ...`: a frame sequence through the
// scene's timeline and a camera's stereo rig, with layouts, resume, direct
// video, a comfort report and progress with an ETA. runRender (one frame)
// hands over here when a sequence option is present.
#include "cli/cli_args.h"

namespace hs::cli {

// The options `render` accepts in sequence mode (added to its own).
std::vector<OptionSpec> renderFramesOptionSpecs();
// The help section for them.
const char* renderFramesHelp();
// Runs the sequence render for parsed arguments; returns the exit code.
int renderFrames(const Args& args);

}  // namespace hs::cli
