#include <charconv>
#include <cstdio>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"

namespace hs::cli {

int runSet(int argc, char** argv) {
  const char* cmd = "set";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {}, args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli set <entity> <component.field> <value> <scene.hscene>\n"
        "       hybridscape-cli set settings.<field> <value> <scene.hscene>\n\n"
        "Sets one property through the same undoable edit the editor's property panel\n"
        "uses, then saves. <entity> is a name or a numeric id. Vectors and colours are\n"
        "x,y,z. Examples:\n"
        "  set \"Main Camera\" camera.fov_deg 35 scene.hscene\n"
        "  set Bunny transform.translation 10,0,0 scene.hscene\n"
        "  set settings.antialiasing fxaa scene.hscene\n\n"
        "Fields:\n");
    for (const auto& c : scene::entityComponents())
      for (const auto& f : c.fields) std::printf("  %s.%s  (%s)\n", c.key.c_str(), f.key.c_str(), f.label.c_str());
    for (const auto& f : scene::settingsFields()) std::printf("  settings.%s  (%s)\n", f.key.c_str(), f.label.c_str());
    return 0;
  }
  const bool isSetting = !args.positional.empty() && args.positional[0].rfind("settings.", 0) == 0;
  if (args.positional.size() != (isSetting ? 3u : 4u))
    return usage(cmd, "expected <entity> <component.field> <value> <scene.hscene>");
  const std::string scenePath = args.positional.back();
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error);
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));

  bool changed = false;
  if (isSetting) {
    const std::string key = args.positional[0].substr(9);
    const scene::SettingsField* f = scene::findSettingsField(key);
    if (!f) return fail(cmd, "no scene setting '" + key + "' (see --help)");
    const auto v = scene::parseFieldValue(*f, args.positional[1], error);
    if (!v) return fail(cmd, "settings." + key + ": " + error);
    changed = scene::ops::setSettingsField(doc, *f, *v);
  } else {
    const std::string& who = args.positional[0];
    scene::EntityId id = doc.state().findByName(who);
    if (id == scene::kNoEntity) {
      // A number names an entity by id (from_chars: no exception on overflow).
      scene::EntityId n = 0;
      const auto r = std::from_chars(who.data(), who.data() + who.size(), n);
      if (r.ec == std::errc() && r.ptr == who.data() + who.size()) id = n;
    }
    if (!doc.state().find(id)) return fail(cmd, "no entity named or numbered '" + who + "' in " + scenePath);
    const scene::EntityField* f = scene::findEntityField(args.positional[1]);
    if (!f) return fail(cmd, "no property '" + args.positional[1] + "' (see --help)");
    const std::string comp = args.positional[1].substr(0, args.positional[1].find('.'));
    const scene::ComponentInfo* c = scene::findComponent(comp);
    if (c && c->optional && !c->has(*doc.state().find(id)))
      return fail(cmd, "entity '" + who + "' has no " + comp + " component");
    const auto v = scene::parseFieldValue(*f, args.positional[2], error);
    if (!v) return fail(cmd, args.positional[1] + ": " + error);
    if (f->type == scene::FieldType::AssetRef && std::get<int64_t>(*v) > 0 &&
        !doc.state().findAsset(scene::AssetId(std::get<int64_t>(*v))))
      return fail(cmd, args.positional[1] + ": no mesh asset " + args.positional[2] + " in " + scenePath);
    changed = scene::ops::setField(doc, id, *f, *v);
  }
  if (!changed) {
    std::printf("unchanged (the value was already %s)\n", args.positional[args.positional.size() - 2].c_str());
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return fail(cmd, error);
  std::printf("set %s in %s\n", args.positional[isSetting ? 0 : 1].c_str(), scenePath.c_str());
  return 0;
}

}  // namespace hs::cli
