// `hybridscape-cli key`: sets one key on the timeline through the same
// undoable edit the editor's key buttons use (scene::ops::setKeys), then saves.
// The key goes on an entity's field, or with --material / --settings on a
// material's or the scene settings' field (scene/object_tracks.h).
#include <cstdio>

#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/time_arg.h"
#include "scene/document.h"
#include "scene/emitter_tracks.h"
#include "scene/hscene_file.h"
#include "scene/object_tracks.h"
#include "scene/particle_ops.h"
#include "scene/sequence_edits.h"
#include "sequencer/sequencer_operations.h"

namespace hs::cli {
namespace {

// "roughness" or "material.roughness" -> "material.roughness".
std::string withPrefix(std::string_view prefix, const std::string& field) {
  return field.rfind(prefix, 0) == 0 ? field : std::string(prefix) + field;
}

// `key EMITTER particles.rate_per_s T VALUE SCENE` (or wind_m_per_s).
int keyEmitterList(OperationArgs& args, const std::string& who, const std::string& field, const std::string& timeText,
                   const std::string& valueText, const std::string& scenePath) {
  if (args.has("interp")) return args.usage("--interp: the emitter's " + field + " keys are linear between keys");
  std::string error;
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  const uint64_t id = findEntity(*state, who);
  if (id == scene::kNoEntity) return args.fail("no entity named or numbered '" + who + "' in " + scenePath);
  double t = 0.0;
  if (!parseTimeArg(timeText, state->sequence.rate, t, error)) return args.usage(error);
  const scene::Entity* e = state->find(id);
  const std::optional<Json> value =
      scene::ops::parseEmitterValue(e ? e->name : who, field, valueText, error);
  if (!value) return args.fail(error);
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  bool changed = false;
  if (!scene::ops::keyEmitterField(doc, id, field, t, *value, error, &changed)) return args.fail(error);
  if (!changed) {
    std::printf("unchanged (that key already has this value)\n");
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  const std::string list(scene::ops::keyedListOf(field));
  const particles::EmitterDesc& d = doc.state().find(id)->particles->desc;
  const size_t keys = list == "rate_keys" ? d.rateKeys.keys.size() : d.windKeys.size();
  std::printf("keyed %s of '%s' at %.6g s (frame %lld) in %s; %s has %zu key(s)\n", field.c_str(),
              doc.state().find(id)->name.c_str(), t,
              static_cast<long long>(sequencer::frameAtTime(t, doc.state().sequence.rate)), scenePath.c_str(),
              list.c_str(), keys);
  return 0;
}

}  // namespace

int runKey(int argc, char** argv) {
  OperationArgs args(sequencer::keyOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  const bool onMaterial = args.has("material");
  const bool onSettings = args.flag("settings");
  if (onMaterial && onSettings) return args.usage("--material and --settings name different targets; give one");
  const bool onObject = onMaterial || onSettings;
  const std::vector<std::string>& positional = args.positionals();
  if (onObject && positional.size() != 4)
    return args.usage(std::string("expected ") + (onMaterial ? "--material <material>" : "--settings") +
                      " <field> <time> <value> <scene.hscene>");
  if (!onObject && positional.size() != 5)
    return args.usage("expected <entity> <property> <time> <value> <scene.hscene>");
  const size_t first = onObject ? 0 : 1;  // where <property> is
  const std::string property =
      onMaterial   ? withPrefix(scene::kMaterialTrackPrefix, positional[first])
      : onSettings ? withPrefix(scene::kSettingsTrackPrefix, positional[first])
                   : positional[first];
  const std::string& timeText = positional[first + 1];
  const std::string& valueText = positional[first + 2];
  const std::string scenePath = positional[first + 3];
  std::optional<sequencer::Interpolation> interp;
  if (args.has("interp")) interp = sequencer::interpolationFromName(args.text("interp"));
  std::string error;
  // An emitter's rate and wind: keys of its own lists (rate_keys,
  // wind_keys), the editor's Key at Playhead for them.
  const std::string_view emitterPrefix = scene::kEmitterTrackPrefix;
  if (!onObject && property.rfind(emitterPrefix, 0) == 0 &&
      !scene::ops::keyedListOf(property.substr(emitterPrefix.size())).empty())
    return keyEmitterList(args, positional[0], property.substr(emitterPrefix.size()), timeText, valueText, scenePath);
  const auto target = scene::animationTarget(property, error);
  if (!target)
    return args.fail(error + (onMaterial   ? " (see hybridscape-cli material list for the fields)"
                              : onSettings ? " (see hybridscape-cli set --help for the settings fields)"
                                           : " (see hybridscape-cli set --help for the fields)"));
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  uint64_t id = scene::kNoEntity;
  if (onMaterial) {
    const scene::MaterialId m = state->findMaterialByName(args.text("material"));
    if (m == scene::kNoMaterial)
      return args.fail("--material: no material named '" + args.text("material") + "' in " + scenePath +
                       " (hybridscape-cli material list shows them)");
    id = scene::materialTarget(m);
  } else if (onSettings) {
    id = scene::settingsTarget();
  } else {
    id = findEntity(*state, positional[0]);
    if (id == scene::kNoEntity) return args.fail("no entity named or numbered '" + positional[0] + "' in " + scenePath);
  }
  double t = 0.0;
  if (!parseTimeArg(timeText, state->sequence.rate, t, error)) return args.usage(error);
  const auto value = scene::parseKeyValue(*target, valueText, error);
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
  const std::string who = onSettings ? std::string("the settings")
                          : onMaterial ? "material '" + scene::targetLabel(doc.state(), id) + "'"
                                       : "'" + scene::targetLabel(doc.state(), id) + "'";
  std::printf("keyed %s of %s at %.6g s (frame %lld) in %s; the track has %zu key(s)\n", target->property.c_str(),
              who.c_str(), t, static_cast<long long>(sequencer::frameAtTime(t, doc.state().sequence.rate)),
              scenePath.c_str(), keys);
  return 0;
}

}  // namespace hs::cli
