// `hybridscape-cli key`: sets one key on the timeline through the same
// undoable edit the editor's key buttons use (scene::ops::setKeys), then saves.
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/time_arg.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/sequence_edits.h"

namespace hs::cli {

int runKey(int argc, char** argv) {
  const char* cmd = "key";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"interp"}}, args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli key <entity> <property> <time> <value> <scene.hscene> [--interp I]\n\n"
        "Sets a key on the timeline (an undoable edit, as the editor's key buttons make), then\n"
        "saves. A key already at that time gets the new value. <entity> is a name or an id;\n"
        "<time> is seconds (2.5) or a frame at the scene's rate (150f); <property> is an\n"
        "animatable field (see `hybridscape-cli set --help`): numbers, vectors x,y,z, colours,\n"
        "true/false for entity.visible; transform.rotation_deg takes Euler degrees and keys the\n"
        "rotation as a quaternion (turns take the short way).\n\n"
        "  --interp I       constant, linear or cubic (default cubic, with clamped auto tangents)\n\n"
        "Examples:\n"
        "  key \"Main Camera\" camera.fov_deg 0 50 scene.hscene\n"
        "  key \"Main Camera\" camera.fov_deg 120f 30 scene.hscene --interp linear\n"
        "  key Bunny transform.translation 2.5 1,0,0 scene.hscene\n"
        "  key Bunny transform.rotation_deg 5 0,0,90 scene.hscene\n");
    return 0;
  }
  if (args.positional.size() != 5) return usage(cmd, "expected <entity> <property> <time> <value> <scene.hscene>");
  const std::string& who = args.positional[0];
  const std::string& property = args.positional[1];
  const std::string scenePath = args.positional[4];
  std::optional<sequencer::Interpolation> interp;
  if (auto i = args.get("interp")) {
    interp = sequencer::interpolationFromName(*i);
    if (!interp) return usage(cmd, "--interp takes constant, linear or cubic, not '" + *i + "'");
  }
  const auto target = scene::animationTarget(property, error);
  if (!target) return fail(cmd, error + " (see hybridscape-cli set --help for the fields)");
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error);
  const scene::EntityId id = findEntity(*state, who);
  if (id == scene::kNoEntity) return fail(cmd, "no entity named or numbered '" + who + "' in " + scenePath);
  double t = 0.0;
  if (!parseTimeArg(args.positional[2], state->sequence.rate, t, error)) return usage(cmd, error);
  const auto value = scene::parseKeyValue(*target, args.positional[3], error);
  if (!value) return fail(cmd, property + ": " + error);

  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  if (!scene::ops::setKeys(doc, {{id, *target, *value}}, t, interp,
                           QString("Key %1").arg(QString::fromStdString(property)), {}, &error)) {
    if (!error.empty()) return fail(cmd, error);
    std::printf("unchanged (that key already has this value)\n");
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return fail(cmd, error);
  const size_t keys = sequencer::keyTimes(doc.state().sequence, id, target->property).size();
  std::printf("keyed %s of '%s' at %.6g s (frame %lld) in %s; the track has %zu key(s)\n", target->property.c_str(),
              doc.state().find(id)->name.c_str(), t,
              static_cast<long long>(sequencer::frameAtTime(t, doc.state().sequence.rate)), scenePath.c_str(), keys);
  return 0;
}

}  // namespace hs::cli
