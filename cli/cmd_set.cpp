#include <cstdio>

#include "cli/commands.h"
#include "cli/entity_lookup.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "core/escape_control.h"
#include "scene/camera_post.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/particle_ops.h"
#include "particles/emitter.h"

namespace hs::cli {

namespace {

// The fields `set` can change, listed in its help.
std::string fieldList() {
  std::string out = "Fields:";
  for (const auto& c : scene::entityComponents())
    for (const auto& f : c.fields) out += "\n  " + c.key + "." + f.key + "  (" + f.label + ")";
  for (const auto& f : scene::settingsFields()) out += "\n  settings." + f.key + "  (" + f.label + ")";
  out += "\nA camera's own post settings (override the scene's; the value 'inherit' removes one):";
  for (const auto& f : scene::cameraPostFields()) out += "\n  camera." + f.key + "  (" + f.label + ")";
  // An emitter's own table (particles/emitter.h): declared fields and lists.
  for (const ParamDecl& d : particles::emitterParamDecls())
    out += "\n  particles." + d.key + "  (" + d.label + (d.count > 1 ? ", " + d.valueName : std::string()) + ")";
  for (const std::string& k : scene::ops::emitterListKeys()) out += "\n  particles." + k + "  (a JSON list)";
  return out;
}

// `set EMITTER particles.FIELD VALUE SCENE`: through scene/particle_ops.h,
// checked as a file's emitter is (the message names emitter and field).
int setEmitter(OperationArgs& args, scene::Document& doc, scene::EntityId id, const std::vector<std::string>& positional,
               const std::string& scenePath) {
  const std::string key = positional[1].substr(10);
  const scene::Entity& e = *doc.state().find(id);
  if (!e.particles) return args.fail("entity '" + positional[0] + "' has no particles component");
  std::string error;
  const std::optional<Json> v = scene::ops::parseEmitterValue(e.name, key, positional[2], error);
  if (!v) return args.fail(error.find(": no field") != std::string::npos ? error + " (see --help)" : error);
  bool changed = false;
  if (!scene::ops::setEmitterValue(doc, id, key, *v, error, {}, &changed)) return args.fail(error);
  if (!changed) {
    std::printf("unchanged (the value was already %s)\n", positional[2].c_str());
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  std::printf("set %s in %s\n", positional[1].c_str(), scenePath.c_str());
  return 0;
}

}  // namespace

int runSet(int argc, char** argv) {
  static const OperationDecl decl{
      .name = "set",
      .summary = "set an entity property or a scene setting",
      .usage = "<entity> <component.field> <value> <scene.hscene>\n"
               "       hybridscape-cli set settings.<field> <value> <scene.hscene>",
      .description = "Sets one property through the same undoable edit the editor's property panel uses, then "
                     "saves. <entity> is a name or a numeric id. Vectors and colours are x,y,z. Examples:\n"
                     "  set \"Main Camera\" camera.fov_deg 35 scene.hscene\n"
                     "  set Bunny transform.translation 10,0,0 scene.hscene\n"
                     "  set settings.antialiasing fxaa scene.hscene\n"
                     "  set \"Main Camera\" camera.post.tonemap agx scene.hscene\n"
                     "  set \"Main Camera\" camera.post.bloom.intensity inherit scene.hscene\n"
                     "  set Snow particles.rate_per_s 4000 scene.hscene\n"
                     "  set Snow particles.rate_keys \"[[0, 500], [30, 4000]]\" scene.hscene",
      .notes = fieldList(),
      .positionals = {{.name = "entity", .help = "a name or an id (not for settings)"},
                      {.name = "component.field", .help = "the property, or settings.<field>"},
                      {.name = "value", .help = "the new value"},
                      {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
  OperationArgs args(decl);
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& positional = args.positionals();
  std::string error;
  const bool isSetting = !positional.empty() && positional[0].rfind("settings.", 0) == 0;
  if (positional.size() != (isSetting ? 3u : 4u))
    return args.usage("expected <entity> <component.field> <value> <scene.hscene>");
  const std::string scenePath = positional.back();
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));

  bool changed = false;
  // What the field's setter made of the value, if not what was given (the
  // checks above refuse what they know; the setter has the last word).
  scene::ops::FieldChange change;
  if (isSetting) {
    const std::string key = positional[0].substr(9);
    const scene::SettingsField* f = scene::findSettingsField(key);
    if (!f) return args.fail("no scene setting '" + key + "' (see --help)");
    const auto v = scene::parseFieldValue(*f, positional[1], error);
    if (!v) return args.fail("settings." + key + ": " + error);
    // Rules against the scene's other settings (a display its OpenColorIO config lacks).
    if (const std::string problem = scene::fieldValueProblem(*f, *v, &doc.state().settings); !problem.empty())
      return args.fail("settings." + key + ": '" + positional[1] + "' is refused: " + f->label + " " + problem);
    changed = scene::ops::setSettingsField(doc, *f, *v, {}, &change);
  } else {
    const std::string& who = positional[0];
    const scene::EntityId id = findEntity(doc.state(), who);
    if (id == scene::kNoEntity) return args.fail("no entity named or numbered '" + who + "' in " + scenePath);
    if (positional[1].rfind("particles.", 0) == 0) return setEmitter(args, doc, id, positional, scenePath);
    const scene::EntityField* f = scene::findEntityField(positional[1]);
    if (!f) return args.fail("no property '" + positional[1] + "' (see --help)");
    const std::string comp = positional[1].substr(0, positional[1].find('.'));
    const scene::ComponentInfo* c = scene::findComponent(comp);
    if (c && c->optional && !c->has(*doc.state().find(id)))
      return args.fail("entity '" + who + "' has no " + comp + " component");
    // A camera's override removed: the scene's value shows through again.
    if (positional[1].rfind("camera.post.", 0) == 0 && positional[2] == "inherit") {
      if (!scene::ops::clearCameraPost(doc, id, positional[1].substr(12))) {
        std::printf("unchanged (camera '%s' did not override %s)\n", who.c_str(), positional[1].c_str());
        return 0;
      }
      if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
      std::printf("removed %s from %s in %s\n", positional[1].c_str(), who.c_str(), scenePath.c_str());
      return 0;
    }
    const auto v = scene::parseFieldValue(*f, positional[2], error);
    if (!v) return args.fail(positional[1] + ": " + error);
    // Rules between fields (far beyond near), against this entity's values.
    if (const std::string problem = scene::fieldValueProblem(*f, *v, doc.state().find(id)); !problem.empty())
      return args.fail(positional[1] + ": '" + positional[2] + "' is out of range: " + f->label + " " + problem);
    // A camera's post setting, against the scene's other settings too (a
    // display or view the scene's OpenColorIO config lacks).
    if (positional[1].rfind("camera.post.", 0) == 0)
      if (const scene::SettingsField* setting = scene::cameraPostSetting(positional[1].substr(12)))
        if (const std::string problem = scene::fieldValueProblem(*setting, *v, &doc.state().settings);
            !problem.empty())
          return args.fail(positional[1] + ": '" + positional[2] + "' is refused: " + f->label + " " + problem);
    if (f->type == scene::FieldType::AssetRef && std::get<int64_t>(*v) > 0 &&
        !doc.state().findAsset(scene::AssetId(std::get<int64_t>(*v))))
      return args.fail(positional[1] + ": no mesh asset " + positional[2] + " in " + scenePath);
    changed = scene::ops::setField(doc, id, *f, *v, {}, &change);
  }
  if (!change.message.empty())
    std::fprintf(stderr, "warning: %s\n", escapeControlCharacters(change.message).c_str());
  if (!changed) {
    std::printf("unchanged (the value was already %s)\n", positional[positional.size() - 2].c_str());
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  std::printf("set %s in %s\n", positional[isSetting ? 0 : 1].c_str(), scenePath.c_str());
  return 0;
}

}  // namespace hs::cli
