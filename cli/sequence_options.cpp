#include "cli/sequence_options.h"

#include <cmath>
#include <cstdio>

#include "render/stereo_views.h"
#include "scene/render_operation.h"

namespace hs::cli {

bool isSequenceRender(const OperationArgs& args) {
  for (const ParamDecl& p : args.operation().params)
    if (p.group == "sequence" && args.has(p.key)) return true;
  return false;
}

bool parseFrames(const OperationArgs& args, const scene::SceneState* scene, sequencer::FrameList& out,
                 std::string& error) {
  if (args.has("frames")) {
    auto list = sequencer::FrameList::parse(args.text("frames"), error);
    if (!list) {
      error = "--frames: " + error;
      return false;
    }
    if (!sequencer::checkFrameBounds(*list, "--frames", error)) return false;
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

sequencer::StereoLayout layoutOf(const OperationArgs& args) {
  return sequencer::layoutFromName(args.text("layout")).value_or(sequencer::StereoLayout::SideBySide);
}

void eyeSizeOf(const OperationArgs& args, int& width, int& height) {
  const std::vector<double> size = args.numbers("size_px");
  width = int(size.at(0));
  height = int(size.at(1));
}

void budgetOf(const OperationArgs& args, sequencer::ComfortBudget& out) {
  const std::vector<double> v = args.numbers("budget_pct");  // NEAR <= 0 <= FAR: checked on parsing
  out.nearest = v.at(0) / 100.0;
  out.farthest = v.at(1) / 100.0;
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

void applyAntialiasing(const OperationArgs& args, scene::SceneState& scene) {
  if (args.has("aa")) scene.settings.antialiasing = scene::antialiasingFromChoice(args.text("aa"));
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
