#include "cli/sequence_options.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "render/stereo_views.h"

namespace hs::cli {

const std::vector<std::string>& sequenceOnlyOptions() {
  static const std::vector<std::string> names = {"frames", "layout",  "fps",    "png16",   "video",  "codec",
                                                 "crf",    "preset",  "comfort", "budget", "overwrite",
                                                 "writers"};
  return names;
}

bool isSequenceRender(const Args& args) {
  for (const std::string& n : sequenceOnlyOptions())
    if (args.has(n)) return true;
  return false;
}

bool parseFrames(const Args& args, const scene::SceneState* scene, sequencer::FrameList& out, std::string& error) {
  if (auto text = args.get("frames")) {
    auto list = sequencer::FrameList::parse(*text, error);
    if (!list) {
      error = "--frames: " + error;
      return false;
    }
    out = *list;
    return true;
  }
  if (!scene) {
    error = "--frames is required (for example --frames 0-35999)";
    return false;
  }
  out = sequencer::FrameList::range(scene->sequence.startFrame, scene->sequence.endFrame);
  return true;
}

bool parseLayout(const Args& args, sequencer::StereoLayout& out, std::string& error) {
  const std::string name = args.get("layout").value_or("sbs");
  const auto layout = sequencer::layoutFromName(name);
  if (!layout) {
    error = "--layout '" + name + "' is not a layout (sbs, sbs-squeezed, tb, tb-squeezed, separate, anaglyph, mono)";
    return false;
  }
  out = *layout;
  return true;
}

bool parseEyeSize(const Args& args, int& width, int& height, std::string& error) {
  width = 1920;
  height = 1080;
  if (auto size = args.get("size")) return parseSize(*size, width, height, error);
  return true;
}

bool parseBudget(const Args& args, sequencer::ComfortBudget& out, std::string& error) {
  out = {};
  const auto text = args.get("budget");
  if (!text) return true;
  const size_t comma = text->find(',');
  double v[2];
  bool ok = comma != std::string::npos;
  for (int i = 0; ok && i < 2; ++i) {
    std::string part = i == 0 ? text->substr(0, comma) : text->substr(comma + 1);
    if (!part.empty() && part[0] == '+') part.erase(0, 1);
    const auto r = std::from_chars(part.data(), part.data() + part.size(), v[i]);
    ok = r.ec == std::errc() && r.ptr == part.data() + part.size() && std::isfinite(v[i]);
  }
  if (!ok || v[0] > 0.0 || v[1] < 0.0) {
    error = "--budget '" + *text + "' is not NEAR,FAR in percent of the width with NEAR <= 0 <= FAR (for example -1,2)";
    return false;
  }
  out.nearest = v[0] / 100.0;
  out.farthest = v[1] / 100.0;
  return true;
}

bool parseIntOption(const Args& args, const std::string& name, int min, int max, int& out, std::string& error) {
  const auto text = args.get(name);
  if (!text) return true;
  int v = 0;
  const auto r = std::from_chars(text->data(), text->data() + text->size(), v);
  if (r.ec != std::errc() || r.ptr != text->data() + text->size() || v < min || v > max) {
    error = "--" + name + " '" + *text + "' is not a whole number from " + std::to_string(min) + " to " +
            std::to_string(max);
    return false;
  }
  out = v;
  return true;
}

scene::EntityId findCamera(const scene::SceneState& scene, const std::string& name, const std::string& scenePath,
                           std::string& error) {
  std::string known;
  for (scene::EntityId c : scene.cameras()) known += (known.empty() ? "" : ", ") + ("'" + scene.find(c)->name + "'");
  if (name.empty()) {
    const scene::EntityId id = render::shotCamera(scene);
    if (id == scene::kNoEntity) error = scenePath + " has no camera to render a sequence through (add one)";
    return id;
  }
  const scene::EntityId id = scene.findByName(name);
  if (id == scene::kNoEntity || !scene.find(id)->camera) {
    error = "no camera named '" + name + "' in " + scenePath +
            (known.empty() ? " (it has no cameras)" : " (cameras: " + known + ")");
    return scene::kNoEntity;
  }
  return id;
}

bool applyAntialiasing(const Args& args, scene::SceneState& scene, std::string& error) {
  const auto aa = args.get("aa");
  if (!aa) return true;
  if (*aa == "none") scene.settings.antialiasing = scene::Antialiasing::None;
  else if (*aa == "fxaa") scene.settings.antialiasing = scene::Antialiasing::Fxaa;
  else if (*aa == "msaa4") scene.settings.antialiasing = scene::Antialiasing::Msaa4;
  else {
    error = "--aa takes none, fxaa or msaa4";
    return false;
  }
  return true;
}

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%ld s", s);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

}  // namespace hs::cli
