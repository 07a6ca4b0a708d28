// `hybridscape-cli sequence`: shows the timeline of a scene (rate, range,
// animated entities and their tracks) and sets its frame rate and range
// through undoable edits (scene::ops), then saves.
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/sequence_edits.h"

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
  std::printf("%s: %s, frames %lld-%lld (%lld frames, %.2f s), %zu animated entit%s\n", path.c_str(),
              rateText(q.rate).c_str(), static_cast<long long>(q.startFrame), static_cast<long long>(q.endFrame),
              static_cast<long long>(q.endFrame - q.startFrame + 1), seconds, q.bindings.size(),
              q.bindings.size() == 1 ? "y" : "ies");
  for (const sequencer::Binding& b : q.bindings) {
    const scene::Entity* e = s.find(b.entity);
    std::printf("  '%s' (#%llu)%s:", e ? e->name.c_str() : b.label.c_str(), static_cast<unsigned long long>(b.entity),
                e ? "" : " [missing]");
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
  const char* cmd = "sequence";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"fps"}, {"range"}}, args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli sequence <scene.hscene> [--fps RATE] [--range FIRST-LAST]\n\n"
        "Shows the scene's timeline: frame rate, playback/export range and the animated\n"
        "entities with their tracks. With options, changes them (undoable edits, as in the\n"
        "editor's timeline) and saves.\n\n"
        "  --fps RATE       60, 59.94, 60000/1001, 24 ... (keys stay at their times in seconds)\n"
        "  --range A-B      the inclusive frame range render and the timeline use, e.g. 0-35999\n");
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const std::string path = args.positional[0];
  std::optional<sequencer::FrameRate> rate;
  if (auto fps = args.get("fps")) {
    rate = sequencer::parseFrameRate(*fps, error);
    if (!rate) return usage(cmd, "--fps: " + error);
  }
  std::optional<std::pair<int64_t, int64_t>> range;
  if (auto text = args.get("range")) {
    const auto list = sequencer::FrameList::parse(*text, error);
    if (!list || list->spans().size() != 1 || list->spans()[0].step != 1)
      return usage(cmd, "--range '" + *text + "' is not one run of frames FIRST-LAST (for example 0-35999)");
    range = std::pair{list->first(), list->last()};
  }
  std::optional<scene::SceneState> state = scene::loadScene(path, error);
  if (!state) return fail(cmd, error);
  if (!rate && !range) {
    printSequence(*state, path);
    return 0;
  }
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(path));
  bool changed = false;
  if (rate) changed = scene::ops::setFrameRate(doc, *rate) || changed;
  if (range) changed = scene::ops::setFrameRange(doc, range->first, range->second) || changed;
  if (changed && !scene::saveScene(doc.state(), path, error)) return fail(cmd, error);
  printSequence(doc.state(), path);
  if (!changed) std::printf("unchanged\n");
  return 0;
}

}  // namespace hs::cli
