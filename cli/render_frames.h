#pragma once
// `hybridscape-cli render SCENE --frames ...`: a frame sequence through the
// scene's timeline and a camera's stereo rig, with layouts, resume, direct
// video, a comfort report and progress with an ETA. runRender (one frame)
// hands over here when a sequence option is present.
#include "cli/operation_options.h"

namespace hs::cli {

// Runs the sequence render for parsed arguments; returns the exit code.
int renderFrames(const OperationArgs& args);

}  // namespace hs::cli
