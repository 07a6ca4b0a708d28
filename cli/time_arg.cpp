#include "cli/time_arg.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/params.h"

namespace hs::cli {

bool parseTimeArg(const std::string& text, sequencer::FrameRate rate, double& t, std::string& error) {
  // Keys and path times may lie before 0 (a pre-roll), within ±2^31 frames
  // or seconds: a frame number beyond that would wrap round in the file.
  constexpr double kLimit = double(std::numeric_limits<int32_t>::max());
  static const ParamDecl kTime{.key = "time", .label = "time", .min = -kLimit, .max = kLimit};
  const bool frame = !text.empty() && (text.back() == 'f' || text.back() == 'F');
  const std::string number = frame ? text.substr(0, text.size() - 1) : text;
  std::string why;
  const std::optional<Json> v = parseParam(kTime, number, why);
  if (!v) {
    error = why.find("out of range") != std::string::npos
                ? "time '" + text + "' is out of range (" + rangeText(kTime) + (frame ? " frames)" : " seconds)")
                : "time '" + text + "' is not seconds (2.5) or a frame (150f)";
    return false;
  }
  if (frame && v->get<double>() != std::floor(v->get<double>())) {
    error = "frame '" + text + "' is not a whole frame";
    return false;
  }
  t = frame ? sequencer::frameTime(int64_t(v->get<double>()), rate) : v->get<double>();
  return true;
}

}  // namespace hs::cli
