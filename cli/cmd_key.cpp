// `hybridscape-cli key`: sets one key on the timeline through the same
// undoable edit the editor's key buttons use (scene::ops::setKeys), then saves.
#include <cstdio>

#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/time_arg.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/sequence_edits.h"
#include "sequencer/sequencer_operations.h"

namespace hs::cli {

int runKey(int argc, char** argv) {
  OperationArgs args(sequencer::keyOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& positional = args.positionals();
  if (positional.size() != 5) return args.usage("expected <entity> <property> <time> <value> <scene.hscene>");
  const std::string& who = positional[0];
  const std::string& property = positional[1];
  const std::string scenePath = positional[4];
  std::optional<sequencer::Interpolation> interp;
  if (args.has("interp")) interp = sequencer::interpolationFromName(args.text("interp"));
  std::string error;
  const auto target = scene::animationTarget(property, error);
  if (!target) return args.fail(error + " (see hybridscape-cli set --help for the fields)");
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  const scene::EntityId id = findEntity(*state, who);
  if (id == scene::kNoEntity) return args.fail("no entity named or numbered '" + who + "' in " + scenePath);
  double t = 0.0;
  if (!parseTimeArg(positional[2], state->sequence.rate, t, error)) return args.usage(error);
  const auto value = scene::parseKeyValue(*target, positional[3], error);
  if (!value) return args.fail(property + ": " + error);

  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  if (!scene::ops::setKeys(doc, {{id, *target, *value}}, t, interp,
                           QString("Key %1").arg(QString::fromStdString(property)), {}, &error)) {
    if (!error.empty()) return args.fail(error);
    std::printf("unchanged (that key already has this value)\n");
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  const size_t keys = sequencer::keyTimes(doc.state().sequence, id, target->property).size();
  std::printf("keyed %s of '%s' at %.6g s (frame %lld) in %s; the track has %zu key(s)\n", target->property.c_str(),
              doc.state().find(id)->name.c_str(), t,
              static_cast<long long>(sequencer::frameAtTime(t, doc.state().sequence.rate)), scenePath.c_str(), keys);
  return 0;
}

}  // namespace hs::cli
