#include "cli/time_arg.h"

#include <charconv>
#include <cmath>

namespace hs::cli {

bool parseTimeArg(const std::string& text, sequencer::FrameRate rate, double& t, std::string& error) {
  std::string s = text;
  const bool frame = !s.empty() && (s.back() == 'f' || s.back() == 'F');
  if (frame) s.pop_back();
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) {
    error = "time '" + text + "' is not seconds (2.5) or a frame (150f)";
    return false;
  }
  if (frame) {
    if (v != std::floor(v)) {
      error = "frame '" + text + "' is not a whole frame";
      return false;
    }
    t = sequencer::frameTime(int64_t(v), rate);
  } else {
    t = v;
  }
  return true;
}

}  // namespace hs::cli
