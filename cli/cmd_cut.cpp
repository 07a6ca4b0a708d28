// `hybridscape-cli cut add|list|remove`: the camera-cut track
// (sequencer/camera_cuts.h, scene/camera_cut_ops.h): which camera is live
// over which frames, and the transition into each cut.
#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"
#include "cli/cut_info.h"
#include "cli/entity_lookup.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/subcommands.h"
#include "cli/time_arg.h"
#include "scene/camera_cut_ops.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {
namespace {

const OperationDecl& cutAddDecl() {
  static const OperationDecl op{
      .name = "cut add",
      .summary = "make a camera live over a frame range, with a transition into it",
      .usage = "<camera> <start> <end> <scene.hscene> [--transition KIND --duration T] [--ease E]",
      .description = "Adds a section to the camera-cut track: the camera (or stereo rig) is the one rendered "
                     "from <start> to <end> (inclusive; seconds, or frames as 150f). With --transition the cut "
                     "begins with a crossfade or a dip to black from the cut before it, which must end on the "
                     "frame before <start>: the transition's first frame is that shot exactly, its last (start "
                     "+ duration) this one exactly. Exports, the comfort check and farm runs follow the cuts; "
                     "frames outside every cut show the render's camera. docs/sequencer.md, \"Camera cuts\".",
      .notes = "Example: hybridscape-cli cut add \"Drone\" 0 10 film.hscene && hybridscape-cli cut add \"Crane\" "
               "601f 20 film.hscene --transition crossfade --duration 1",
      .positionals = {{.name = "camera", .help = "a camera entity's name or #id"},
                      {.name = "start", .help = "first frame: seconds or 150f"},
                      {.name = "end", .help = "last frame (inclusive): seconds or 150f"},
                      {.name = "scene.hscene", .help = "the scene file"}},
      .params = {{.key = "transition", .option = "transition", .label = "Transition", .type = ParamType::Choice,
                  .choices = sequencer::transitionNameList(), .help = "how the cut begins (default cut)"},
                 {.key = "duration", .option = "duration", .label = "Duration", .type = ParamType::Text,
                  .help = "the transition's length: seconds or frames (30f)", .valueName = "T"},
                 {.key = "ease", .option = "ease", .label = "Ease", .type = ParamType::Choice,
                  .choices = {"none", "in", "out", "in_out"}, .help = "the transition's progress (default in_out)"}},
  };
  return op;
}

const OperationDecl& cutListDecl() {
  static const OperationDecl op{
      .name = "cut list",
      .summary = "list the camera cuts and their transitions",
      .usage = "<scene.hscene> [--json]",
      .description = "Prints each cut (number, camera, frames, seconds, transition) and whether the track "
                     "is sound (a cut on a deleted camera, overlaps).",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
      .params = {{.key = "json", .option = "json", .label = "JSON", .type = ParamType::Flag, .help = "print JSON"}},
  };
  return op;
}

const OperationDecl& cutRemoveDecl() {
  static const OperationDecl op{
      .name = "cut remove",
      .summary = "remove a camera cut by its number",
      .usage = "<number> <scene.hscene>",
      .description = "Removes cut <number> (as `cut list` numbers them, from 1). A transition into the cut "
                     "after it becomes a plain cut when no cut ends right before that one.",
      .positionals = {{.name = "number", .help = "the cut's number"}, {.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

// Opens `path` into `doc` (a Document is not movable).
bool openDocument(scene::Document& doc, const std::string& path, std::string& error) {
  std::optional<scene::SceneState> state = openScene(path, error);
  if (!state) return false;
  doc.reset(std::move(*state), QString::fromStdString(path));
  return true;
}

int runCutAdd(int argc, char** argv) {
  OperationArgs args(cutAddDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 4) return args.usage("expected a camera, a start, an end and a scene file");
  const std::string path = args.positionals()[3];
  const std::optional<sequencer::Transition> transition =
      sequencer::transitionFromName(args.has("transition") ? args.text("transition") : "cut");
  if (transition != sequencer::Transition::Cut && !args.has("duration"))
    return args.usage("--transition " + args.text("transition") + " needs --duration");
  if (transition == sequencer::Transition::Cut && args.has("duration"))
    return args.usage("--duration is the length of a transition: give --transition too");
  std::string error;
  scene::Document doc;
  if (!openDocument(doc, path, error)) return args.fail(error);
  const sequencer::FrameRate rate = doc.state().sequence.rate;
  sequencer::CameraCut cut;
  const scene::EntityId camera = findEntity(doc.state(), args.positionals()[0]);
  if (camera == scene::kNoEntity) return args.fail("no entity named or numbered '" + args.positionals()[0] + "' in " + path);
  if (!doc.state().find(camera)->camera) return args.fail("'" + args.positionals()[0] + "' is not a camera");
  cut.camera = camera;
  double start = 0.0, end = 0.0;
  if (!parseTimeArg(args.positionals()[1], rate, start, error) || !parseTimeArg(args.positionals()[2], rate, end, error))
    return args.usage(error);
  cut.start = sequencer::frameAtTime(start, rate);
  cut.end = sequencer::frameAtTime(end, rate);
  cut.transition = *transition;
  if (args.has("duration")) {
    double d = 0.0;
    if (!parseTimeArg(args.text("duration"), rate, d, error)) return args.usage("--duration: " + error);
    cut.transitionFrames = sequencer::frameAtTime(d, rate);
  }
  if (args.has("ease")) cut.ease = *sequencer::easeFromName(args.text("ease"));
  if (!scene::ops::addCut(doc, cut, error)) return args.fail(error);
  if (!scene::saveScene(doc.state(), path, error)) return args.fail(error);
  std::printf("cut: '%s' live from frame %lld to %lld%s in %s\n", doc.state().find(camera)->name.c_str(),
              static_cast<long long>(cut.start), static_cast<long long>(cut.end),
              cut.transition == sequencer::Transition::Cut
                  ? ""
                  : (std::string(", after a ") + sequencer::transitionName(cut.transition) + " of " +
                     std::to_string(cut.transitionFrames) + " frames")
                        .c_str(),
              path.c_str());
  return 0;
}

int runCutList(int argc, char** argv) {
  OperationArgs args(cutListDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  std::string error;
  std::optional<scene::SceneState> s = openScene(args.positionals()[0], error);
  if (!s) return args.fail(error);
  if (args.flag("json")) {
    std::printf("%s\n", writeJson(cutsJson(*s)).c_str());
    return 0;
  }
  printCuts(*s);
  return 0;
}

int runCutRemove(int argc, char** argv) {
  OperationArgs args(cutRemoveDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a cut number and a scene file");
  const std::string& n = args.positionals()[0];
  char* end = nullptr;
  const long number = std::strtol(n.c_str(), &end, 10);
  if (n.empty() || *end || number < 1) return args.usage("the cut number must be 1 or more, not '" + n + "'");
  const std::string path = args.positionals()[1];
  std::string error;
  scene::Document doc;
  if (!openDocument(doc, path, error)) return args.fail(error);
  if (!scene::ops::removeCut(doc, size_t(number - 1), error)) return args.fail(error);
  if (!scene::saveScene(doc.state(), path, error)) return args.fail(error);
  std::printf("removed cut %ld from %s\n", number, path.c_str());
  return 0;
}

constexpr Subcommand kSubs[] = {
    {"add", cutAddDecl, runCutAdd},
    {"list", cutListDecl, runCutList},
    {"remove", cutRemoveDecl, runCutRemove},
};

}  // namespace

Json cutsJson(const scene::SceneState& s) {
  Json out = Json::array();
  const sequencer::FrameRate rate = s.sequence.rate;
  for (size_t i = 0; i < s.sequence.cuts.size(); ++i) {
    const sequencer::CameraCut& c = s.sequence.cuts[i];
    const scene::Entity* e = s.find(scene::EntityId(c.camera));
    Json j = {{"number", i + 1},
              {"camera_id", c.camera},
              {"camera", e ? Json(e->name) : Json(nullptr)},
              {"start_frame", c.start},
              {"end_frame", c.end},
              {"start_s", sequencer::frameTime(c.start, rate)},
              {"end_s", sequencer::frameTime(c.end, rate)},
              {"transition", sequencer::transitionName(c.transition)}};
    if (c.transition != sequencer::Transition::Cut) {
      j["transition_frames"] = c.transitionFrames;
      j["ease"] = sequencer::easeName(c.ease);
    }
    out.push_back(std::move(j));
  }
  return out;
}

void printCuts(const scene::SceneState& s) {
  const auto& cuts = s.sequence.cuts;
  if (cuts.empty()) {
    std::printf("cuts: none (renders use one camera throughout)\n");
    return;
  }
  std::printf("cuts: %zu\n", cuts.size());
  const sequencer::FrameRate rate = s.sequence.rate;
  for (size_t i = 0; i < cuts.size(); ++i) {
    const sequencer::CameraCut& c = cuts[i];
    const scene::Entity* e = s.find(scene::EntityId(c.camera));
    const std::string name = e ? e->name : "#" + std::to_string(c.camera) + " (missing)";
    std::printf("  %zu  %-16s frames %lld-%lld (%.3f-%.3f s)", i + 1, name.c_str(), static_cast<long long>(c.start),
                static_cast<long long>(c.end), sequencer::frameTime(c.start, rate), sequencer::frameTime(c.end, rate));
    if (c.transition != sequencer::Transition::Cut)
      std::printf(", %s of %lld frames (%s)", sequencer::transitionName(c.transition),
                  static_cast<long long>(c.transitionFrames), sequencer::easeName(c.ease));
    std::printf("\n");
  }
  if (const std::string p = scene::cutsProblem(s); !p.empty()) std::printf("  problem: %s\n", p.c_str());
}

int runCut(int argc, char** argv) { return runSubcommands("cut", "", kSubs, argc, argv); }

}  // namespace hs::cli
