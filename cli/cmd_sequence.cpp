// `hybridscape-cli sequence`: shows the timeline of a scene (rate, range,
// animated entities and their tracks) and sets its frame rate and range
// through undoable edits (scene::ops), then saves.
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/object_tracks.h"
#include "scene/sequence_edits.h"
#include "sequencer/sequencer_operations.h"

namespace hs::cli {

namespace {

std::string rateText(sequencer::FrameRate r) {
  char buf[48];
  if (r.den == 1) std::snprintf(buf, sizeof buf, "%lld fps", static_cast<long long>(r.num));
  else std::snprintf(buf, sizeof buf, "%.5g fps (%lld/%lld)", r.fps(), static_cast<long long>(r.num),
                     static_cast<long long>(r.den));
  return buf;
}

void printSequence(const scene::SceneState& s, const std::string& path) {
  const sequencer::Sequence& q = s.sequence;
  const double seconds = double(q.endFrame - q.startFrame + 1) / q.rate.fps();
  size_t entities = 0, materials = 0, settings = 0;
  for (const sequencer::Binding& b : q.bindings) {
    const sequencer::TargetKind kind = sequencer::targetKind(b.entity);
    (kind == sequencer::TargetKind::Entity ? entities : kind == sequencer::TargetKind::Material ? materials : settings)++;
  }
  std::printf("%s: %s, frames %lld-%lld (%lld frames, %.2f s), %zu animated entit%s", path.c_str(),
              rateText(q.rate).c_str(), static_cast<long long>(q.startFrame), static_cast<long long>(q.endFrame),
              static_cast<long long>(q.endFrame - q.startFrame + 1), seconds, entities, entities == 1 ? "y" : "ies");
  // Material and settings tracks (scene/object_tracks.h), named only when there are any.
  if (materials) std::printf(", %zu animated material%s", materials, materials == 1 ? "" : "s");
  if (settings) std::printf(", animated settings");
  std::printf("\n");
  for (const sequencer::Binding& b : q.bindings) {
    const std::string name = scene::targetLabel(s, b.entity);
    const sequencer::TargetKind kind = sequencer::targetKind(b.entity);
    if (kind == sequencer::TargetKind::Settings)
      std::printf("  settings:");
    else
      std::printf("  '%s' (%s#%llu)%s:", name.empty() ? b.label.c_str() : name.c_str(),
                  kind == sequencer::TargetKind::Material ? "material " : "",
                  static_cast<unsigned long long>(b.entity & ~sequencer::kMaterialTargetTag),
                  name.empty() ? " [missing]" : "");
    const char* sep = " ";
    if (b.path) {
      std::printf("%scamera path through %zu points (path.progress: %zu keys)", sep, b.path->path.points.size(),
                  b.path->progress.keys.size());
      sep = ", ";
    }
    for (const sequencer::Track& t : b.tracks) {
      std::printf("%s%s: %zu key%s", sep, sequencer::trackProperty(t).c_str(), sequencer::trackKeyCount(t),
                  sequencer::trackKeyCount(t) == 1 ? "" : "s");
      sep = ", ";
    }
    std::printf("\n");
  }
}

}  // namespace

int runSequence(int argc, char** argv) {
  OperationArgs args(sequencer::sequenceOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string path = args.positionals()[0];
  std::string error;
  std::optional<sequencer::FrameRate> rate;
  if (args.has("fps")) {
    rate = sequencer::parseFrameRate(args.text("fps"), error);
    if (!rate) return args.usage("--fps: " + error);
  }
  // --range: two frame numbers, in order (checked on parsing).
  std::optional<std::pair<int64_t, int64_t>> range;
  if (args.has("range")) {
    const std::vector<double> r = args.numbers("range");
    range = std::pair{int64_t(r[0]), int64_t(r[1])};
  }
  std::optional<scene::SceneState> state = openScene(path, error);
  if (!state) return args.fail(error);
  if (!rate && !range) {
    printSequence(*state, path);
    return 0;
  }
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(path));
  bool changed = false;
  if (rate) changed = scene::ops::setFrameRate(doc, *rate) || changed;
  if (range) changed = scene::ops::setFrameRange(doc, range->first, range->second) || changed;
  if (changed && !scene::saveScene(doc.state(), path, error)) return args.fail(error);
  printSequence(doc.state(), path);
  if (!changed) std::printf("unchanged\n");
  return 0;
}

}  // namespace hs::cli
