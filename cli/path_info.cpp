#include "cli/path_info.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "scene/camera_path_edits.h"

namespace hs::cli {

namespace {

// printf into a string; the attribute lets the compiler check each call.
[[gnu::format(printf, 1, 2)]] std::string format(const char* fmt, ...) {
  char buf[256];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

std::string timeText(double t, sequencer::FrameRate rate) {
  return format("%.6g s (frame %lld)", t, static_cast<long long>(sequencer::frameAtTime(t, rate)));
}

}  // namespace

std::string describePath(const scene::SceneState& state, scene::EntityId id) {
  const scene::Entity* e = state.find(id);
  const std::string name = e ? e->name : "#" + std::to_string(id);
  const sequencer::PathFollow* f = scene::findPath(state, id);
  if (!f) return "'" + name + "' follows no path\n";
  const sequencer::PathSampler sampler(f->path.points);
  std::string out = format("'%s' follows a path: %zu points, %.6g m\n", name.c_str(), f->path.points.size(),
                           sampler.length());
  for (size_t i = 0; i < f->path.points.size(); ++i) {
    const glm::dvec3& p = f->path.points[i];
    out += format("  %zu  %.6g,%.6g,%.6g\n", i + 1, p.x, p.y, p.z);
  }
  switch (f->aim) {
    case sequencer::PathAim::Tangent: out += "  aim: along the path\n"; break;
    case sequencer::PathAim::Point:
      out += format("  aim: at the point %.6g,%.6g,%.6g\n", f->targetPoint.x, f->targetPoint.y, f->targetPoint.z);
      break;
    case sequencer::PathAim::Entity: {
      const scene::Entity* t = state.find(f->targetEntity);
      out += "  aim: at '" + (t ? t->name : "#" + std::to_string(f->targetEntity) + " [missing]") + "'\n";
      break;
    }
  }
  out += f->bank ? format("  banking: into turns, up to %.6g degrees (strength %.6g)\n", f->maxBankDeg, f->bankScale)
                 : std::string("  banking: off\n");
  const auto& keys = f->progress.keys;
  const sequencer::FrameRate rate = state.sequence.rate;
  if (keys.empty()) {
    out += "  progress: no keys (the camera stays at the start)\n";
  } else {
    out += format("  progress: %zu key(s), %.6g at ", keys.size(), keys.front().value) + timeText(keys.front().time, rate);
    if (keys.size() > 1) out += format(" ... %.6g at ", keys.back().value) + timeText(keys.back().time, rate);
    const bool constant = keys.size() == 2 && keys[0].interpolation == sequencer::Interpolation::Linear &&
                          keys[0].ease == sequencer::Ease::None && keys[1].time > keys[0].time;
    if (constant)
      out += format("; constant speed %.6g m/s",
                    sampler.length() * std::abs(keys[1].value - keys[0].value) / (keys[1].time - keys[0].time));
    out += "\n";
  }
  return out;
}

}  // namespace hs::cli
