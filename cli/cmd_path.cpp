// `hybridscape-cli path`: makes a camera follow a path at constant speed
// (arc-length parameterised), changes its points, aim, banking or timing,
// or removes it, through the same undoable edits as the editor's path tools
// (scene/camera_path_edits.h), then saves. Without options it shows the path.
#include <cstdio>

#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/operation_options.h"
#include "cli/path_info.h"
#include "cli/scene_open.h"
#include "cli/time_arg.h"
#include "scene/camera_path_edits.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "sequencer/sequencer_operations.h"

namespace hs::cli {

namespace {

// "x,y,z;x,y,z;..." (spaces around the parts are allowed), each point read
// as --look-at's point is (within the world extent).
bool parsePoints(const std::string& text, std::vector<glm::dvec3>& out, std::string& error) {
  ParamDecl point = paramIn(sequencer::pathFollowParamDecls(), "look_at_m");
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    std::string part = text.substr(start, end - start);
    part.erase(0, part.find_first_not_of(" \t"));
    part.erase(part.find_last_not_of(" \t") + 1);
    const bool trailing = part.empty() && end == text.size() && !out.empty();
    if (!trailing) {
      point.option = "points: point " + std::to_string(out.size() + 1);
      const std::optional<Json> v = parseParam(point, part, error);
      if (!v) return false;
      out.emplace_back((*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>());
    }
    start = end + 1;
  }
  if (out.size() < 2) {
    error = "--points needs at least two points X,Y,Z;X,Y,Z (got " + std::to_string(out.size()) + ")";
    return false;
  }
  return true;
}

glm::dvec3 vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

int runPath(int argc, char** argv) {
  OperationArgs args(sequencer::pathOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected <entity> <scene.hscene>");
  const int aims = int(args.has("look_at_m")) + int(args.has("look_at_entity")) + int(args.has("look_along"));
  if (aims > 1) return args.usage("give one of --look-at, --look-at-entity and --look-along");
  if (args.has("clear") && args.givenCount() > 1) return args.usage("--clear takes no other options");
  if (args.has("ease") && !args.has("start") && !args.has("end") && !args.has("points"))
    return args.usage("--ease goes with --start/--end or --points");
  const std::string& who = args.positionals()[0];
  const std::string scenePath = args.positionals()[1];
  std::string error;

  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  const scene::EntityId id = findEntity(*state, who);
  if (id == scene::kNoEntity) return args.fail("no entity named or numbered '" + who + "' in " + scenePath);
  const std::string name = state->find(id)->name;

  if (args.givenCount() == 0) {
    std::printf("%s", describePath(*state, id).c_str());
    return 0;
  }
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const scene::SceneState& s = doc.state();

  if (args.has("clear")) {
    if (!scene::ops::removePath(doc, id, &error)) return args.fail(error);
    if (!scene::saveScene(s, scenePath, error)) return args.fail(error);
    std::printf("'%s' no longer follows a path; saved %s\n", name.c_str(), scenePath.c_str());
    return 0;
  }

  const sequencer::PathFollow* existing = scene::findPath(s, id);
  if (!existing && !args.has("points"))
    return args.fail("'" + name + "' follows no path yet: give its points with --points");
  const auto [rangeStart, rangeEnd] = scene::playbackTimes(s.sequence);
  // A range of one frame would give no time to travel: one second then.
  sequencer::PathFollow follow =
      existing ? *existing
               : sequencer::makePathFollow({}, rangeStart, rangeEnd > rangeStart ? rangeEnd : rangeStart + 1.0);

  if (args.has("points")) {
    std::vector<glm::dvec3> points;
    if (!parsePoints(args.text("points"), points, error)) return args.usage(error);
    follow.path.points = std::move(points);
  }
  if (args.has("look_at_m")) {
    follow.aim = sequencer::PathAim::Point;
    follow.targetPoint = vec3(args.numbers("look_at_m"));
  }
  if (args.has("look_at_entity")) {
    const std::string target = args.text("look_at_entity");
    const scene::EntityId t = findEntity(s, target);
    if (t == scene::kNoEntity)
      return args.fail("--look-at-entity: no entity named or numbered '" + target + "' in " + scenePath);
    follow.aim = sequencer::PathAim::Entity;
    follow.targetEntity = t;
  }
  if (args.has("look_along")) follow.aim = sequencer::PathAim::Tangent;
  if (args.has("bank_deg")) {
    // 0 turns banking off; a limit keeps the one the path had.
    const double deg = args.number("bank_deg");
    follow.bank = deg > 0.0;
    if (deg > 0.0) follow.maxBankDeg = deg;
  }
  if (args.has("bank_scale")) follow.bankScale = args.number("bank_scale");
  if (args.has("start") || args.has("end") || args.has("ease")) {
    // Times not given keep the path's own (its first and last progress
    // keys), else the sequence's range.
    const auto& keys = follow.progress.keys;
    const bool own = existing && keys.size() >= 2;
    double t0 = own ? keys.front().time : rangeStart, t1 = own ? keys.back().time : rangeEnd;
    if (args.has("start") && !parseTimeArg(args.text("start"), s.sequence.rate, t0, error))
      return args.usage("--start: " + error);
    if (args.has("end") && !parseTimeArg(args.text("end"), s.sequence.rate, t1, error))
      return args.usage("--end: " + error);
    if (!(t1 > t0)) return args.usage("--end must be after --start");
    const sequencer::Ease ease = args.has("ease") ? sequencer::Ease::InOut : sequencer::Ease::None;
    follow.progress = sequencer::constantSpeedProgress(t0, t1, ease);
  }

  const QString text = existing ? "Edit path" : "Create path";
  const bool changed = scene::ops::setPath(doc, id, std::move(follow), text, &error);
  if (!changed && !error.empty()) return args.fail(error);
  if (changed && !scene::saveScene(s, scenePath, error)) return args.fail(error);
  std::printf("%s", describePath(s, id).c_str());
  std::printf(changed ? "saved %s\n" : "unchanged: %s\n", scenePath.c_str());
  return 0;
}

}  // namespace hs::cli
