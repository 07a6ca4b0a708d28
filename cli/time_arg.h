#pragma once
// Times typed on the command line: seconds ("2.5") or a frame at the
// scene's rate ("150f"). `key` and `path` read them alike.
#include <string>

#include "sequencer/frame_range.h"

namespace hs::cli {

// False with a one-line `error` naming the text.
bool parseTimeArg(const std::string& text, sequencer::FrameRate rate, double& seconds, std::string& error);

}  // namespace hs::cli
