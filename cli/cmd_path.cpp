// `hybridscape-cli path`: makes a camera follow a path at constant speed
// (arc-length parameterised), changes its points, aim, banking or timing,
// or removes it, through the same undoable edits as the editor's path tools
// (scene/camera_path_edits.h), then saves. Without options it shows the path.
#include <charconv>
#include <cmath>
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/path_info.h"
#include "cli/time_arg.h"
#include "scene/camera_path_edits.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {

namespace {

const char* kHelp =
    "usage: hybridscape-cli path <entity> <scene.hscene> [options]\n\n"
    "Makes a camera (or any entity) follow a path at constant speed, changes the path or\n"
    "removes it, then saves: one undoable edit, as the editor's path tools make. The path is\n"
    "a smooth curve (natural cubic spline) through the points, travelled by arc length, so\n"
    "the speed is constant between the start and end times. It drives the entity's location\n"
    "and rotation (location and rotation keys it had are removed). Without options, shows\n"
    "the path. <entity> is a name or an id.\n\n"
    "  --points \"X,Y,Z;X,Y,Z;...\"  the points in world metres, two or more (quote the ';');\n"
    "                             a new path, or new points for the path the entity has\n"
    "  --look-at X,Y,Z            aim at a point\n"
    "  --look-at-entity NAME      aim at an entity (a name or an id), following it as it moves\n"
    "  --look-along               aim along the direction of travel (a new path's default)\n"
    "  --bank MAXDEG              bank into turns like an aircraft, at most MAXDEG degrees\n"
    "                             (0 < MAXDEG <= 90; 0 turns banking off)\n"
    "  --bank-scale K             banking strength (default 1: a coordinated turn)\n"
    "  --start T, --end T         cover the path at constant speed from T to T: seconds (2.5)\n"
    "                             or a frame (150f); a new path's default is the sequence's range\n"
    "  --ease                     with the times: start and stop softly (ease in and out)\n"
    "  --clear                    stop following the path (the entity keeps its own transform)\n\n"
    "Examples:\n"
    "  path \"Main Camera\" valley.hscene --points \"0,-20,3;10,0,4;0,20,5\" --look-at 0,0,1\n"
    "  path \"Main Camera\" valley.hscene --points \"0,-20,3;10,0,4;0,20,5\" --bank 25 --start 0 --end 600f\n"
    "  path \"Main Camera\" valley.hscene --look-at-entity Bunny\n"
    "  path \"Main Camera\" valley.hscene --clear\n";

// "x,y,z;x,y,z;..." (spaces around the parts are allowed).
bool parsePoints(const std::string& text, std::vector<glm::dvec3>& out, std::string& error) {
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    std::string part = text.substr(start, end - start);
    part.erase(0, part.find_first_not_of(" \t"));
    part.erase(part.find_last_not_of(" \t") + 1);
    const bool trailing = part.empty() && end == text.size() && !out.empty();
    if (!trailing) {
      double v[3];
      std::string why;
      if (!parseVec3(part, v, why)) {
        error = "--points: point " + std::to_string(out.size() + 1) + ": " + why;
        return false;
      }
      out.emplace_back(v[0], v[1], v[2]);
    }
    start = end + 1;
  }
  if (out.size() < 2) {
    error = "--points needs at least two points X,Y,Z;X,Y,Z (got " + std::to_string(out.size()) + ")";
    return false;
  }
  return true;
}

}  // namespace

int runPath(int argc, char** argv) {
  const char* cmd = "path";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"points"}, {"look-at"}, {"look-at-entity"}, {"look-along", false}, {"bank"}, {"bank-scale"},
                  {"start"}, {"end"}, {"ease", false}, {"clear", false}},
                 args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf("%s", kHelp);
    return 0;
  }
  if (args.positional.size() != 2) return usage(cmd, "expected <entity> <scene.hscene>");
  const int aims = int(args.has("look-at")) + int(args.has("look-at-entity")) + int(args.has("look-along"));
  if (aims > 1) return usage(cmd, "give one of --look-at, --look-at-entity and --look-along");
  if (args.has("clear") && args.options.size() > 1) return usage(cmd, "--clear takes no other options");
  if (args.has("ease") && !args.has("start") && !args.has("end") && !args.has("points"))
    return usage(cmd, "--ease goes with --start/--end or --points");
  const std::string& who = args.positional[0];
  const std::string scenePath = args.positional[1];

  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error);
  const scene::EntityId id = findEntity(*state, who);
  if (id == scene::kNoEntity) return fail(cmd, "no entity named or numbered '" + who + "' in " + scenePath);
  const std::string name = state->find(id)->name;

  if (args.options.empty()) {
    std::printf("%s", describePath(*state, id).c_str());
    return 0;
  }
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const scene::SceneState& s = doc.state();

  if (args.has("clear")) {
    if (!scene::ops::removePath(doc, id, &error)) return fail(cmd, error);
    if (!scene::saveScene(s, scenePath, error)) return fail(cmd, error);
    std::printf("'%s' no longer follows a path; saved %s\n", name.c_str(), scenePath.c_str());
    return 0;
  }

  const sequencer::PathFollow* existing = scene::findPath(s, id);
  if (!existing && !args.has("points"))
    return fail(cmd, "'" + name + "' follows no path yet: give its points with --points");
  const auto [rangeStart, rangeEnd] = scene::playbackTimes(s.sequence);
  // A range of one frame would give no time to travel: one second then.
  sequencer::PathFollow follow =
      existing ? *existing
               : sequencer::makePathFollow({}, rangeStart, rangeEnd > rangeStart ? rangeEnd : rangeStart + 1.0);

  if (auto text = args.get("points")) {
    std::vector<glm::dvec3> points;
    if (!parsePoints(*text, points, error)) return usage(cmd, error);
    follow.path.points = std::move(points);
  }
  if (auto text = args.get("look-at")) {
    double v[3];
    if (!parseVec3(*text, v, error)) return usage(cmd, "--look-at: " + error);
    follow.aim = sequencer::PathAim::Point;
    follow.targetPoint = glm::dvec3(v[0], v[1], v[2]);
  }
  if (auto target = args.get("look-at-entity")) {
    const scene::EntityId t = findEntity(s, *target);
    if (t == scene::kNoEntity)
      return fail(cmd, "--look-at-entity: no entity named or numbered '" + *target + "' in " + scenePath);
    follow.aim = sequencer::PathAim::Entity;
    follow.targetEntity = t;
  }
  if (args.has("look-along")) follow.aim = sequencer::PathAim::Tangent;
  auto number = [&](const char* option, double& out) {
    const std::string text = *args.get(option);
    const auto r = std::from_chars(text.data(), text.data() + text.size(), out);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(out)) {
      error = std::string("--") + option + " takes a number, not '" + text + "'";
      return false;
    }
    return true;
  };
  if (args.has("bank")) {
    double deg = 0.0;
    if (!number("bank", deg)) return usage(cmd, error);
    if (deg < 0.0 || deg > 90.0) return usage(cmd, "--bank takes the largest bank angle in degrees, 0 to 90");
    follow.bank = deg > 0.0;
    if (deg > 0.0) follow.maxBankDeg = deg;
  }
  if (args.has("bank-scale")) {
    if (!number("bank-scale", follow.bankScale)) return usage(cmd, error);
    if (!(follow.bankScale > 0.0)) return usage(cmd, "--bank-scale must be above 0");
  }
  if (args.has("start") || args.has("end") || args.has("ease")) {
    // Times not given keep the path's own (its first and last progress
    // keys), else the sequence's range.
    const auto& keys = follow.progress.keys;
    const bool own = existing && keys.size() >= 2;
    double t0 = own ? keys.front().time : rangeStart, t1 = own ? keys.back().time : rangeEnd;
    if (auto t = args.get("start"); t && !parseTimeArg(*t, s.sequence.rate, t0, error))
      return usage(cmd, "--start: " + error);
    if (auto t = args.get("end"); t && !parseTimeArg(*t, s.sequence.rate, t1, error))
      return usage(cmd, "--end: " + error);
    if (!(t1 > t0)) return usage(cmd, "--end must be after --start");
    const sequencer::Ease ease = args.has("ease") ? sequencer::Ease::InOut : sequencer::Ease::None;
    follow.progress = sequencer::constantSpeedProgress(t0, t1, ease);
  }

  const QString text = existing ? "Edit path" : "Create path";
  const bool changed = scene::ops::setPath(doc, id, std::move(follow), text, &error);
  if (!changed && !error.empty()) return fail(cmd, error);
  if (changed && !scene::saveScene(s, scenePath, error)) return fail(cmd, error);
  std::printf("%s", describePath(s, id).c_str());
  std::printf(changed ? "saved %s\n" : "unchanged: %s\n", scenePath.c_str());
  return 0;
}

}  // namespace hs::cli
