// `hybridscape-cli material list|set`: the document's materials by name,
// their fields as scene::materialFields() declares them.
#include <cstdio>
#include <cstring>

#include "cli/commands.h"
#include "cli/material_info.h"
#include "cli/operation_options.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/material_ops.h"

namespace hs::cli {
namespace {

std::string fieldList() {
  std::string out = "Fields:";
  for (const auto& f : scene::materialFields()) {
    out += "\n  " + f.key + "  (" + f.label;
    if (f.type == scene::FieldType::Double) out += ", " + scene::formatFieldValue(f.type, f.min) + " to " +
                                                   scene::formatFieldValue(f.type, f.max) + (f.unit.empty() ? "" : " " + f.unit);
    if (f.type == scene::FieldType::Enum) {
      out += ":";
      for (const auto& n : f.enumNames) out += " " + n;
    }
    if (f.type == scene::FieldType::AssetRef) out += ", a texture id, 0 for none";
    out += ")";
  }
  return out;
}

const OperationDecl& listDecl() {
  static const OperationDecl decl{
      .name = "material list",
      .summary = "list the scene's materials with every field (--json for JSON)",
      .usage = "<scene.hscene> [--json]",
      .description = "Lists every material of the scene by name, with the mesh asset it came with and each of its "
                     "fields under the key `material set` takes. JSON: {\"materials\": [{\"name\": ..., \"asset\": "
                     "..., <field>: <value>, ...}]}.",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
      .params = {{.key = "json", .option = "json", .label = "JSON", .type = ParamType::Flag,
                  .help = "print it as JSON"}}};
  return decl;
}

const OperationDecl& setDecl() {
  static const OperationDecl decl{
      .name = "material set",
      .summary = "set one field of a material by name",
      .usage = "<material> <field> <value> <scene.hscene>",
      .description = "Sets one field of the material named <material> (as `material list` prints it) through the "
                     "same undoable edit the editor's Materials panel uses, then saves. A value outside the "
                     "field's range is refused. Colours are r,g,b (linear). Examples:\n"
                     "  material set \"Bunny / default\" roughness 0.3 scene.hscene\n"
                     "  material set \"Bunny / default\" model blinn_phong scene.hscene",
      .notes = fieldList(),
      .positionals = {{.name = "material", .help = "the material's name"},
                      {.name = "field", .help = "the field's key"},
                      {.name = "value", .help = "the new value"},
                      {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
  return decl;
}

int runList(int argc, char** argv) {
  OperationArgs args(listDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  std::string error;
  std::optional<scene::SceneState> s = scene::loadScene(args.positionals()[0], error);
  if (!s) return args.fail(error);
  if (args.flag("json")) {
    std::printf("%s\n", writeJson(materialsInfoJson(*s)).c_str());
    return 0;
  }
  if (s->materials.empty()) std::printf("no materials\n");
  printMaterials(*s);
  return 0;
}

int runSetField(int argc, char** argv) {
  OperationArgs args(setDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& p = args.positionals();
  if (p.size() != 4) return args.usage("expected <material> <field> <value> <scene.hscene>");
  const std::string& scenePath = p[3];
  std::string error;
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return args.fail(error);
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(scenePath));
  const scene::MaterialId id = doc.state().findMaterialByName(p[0]);
  if (id == scene::kNoMaterial)
    return args.fail("no material named '" + p[0] + "' in " + scenePath + " (see `hybridscape-cli material list`)");
  const scene::MaterialField* f = scene::findMaterialField(p[1]);
  if (!f) return args.fail("material '" + p[0] + "': no field '" + p[1] + "' (see --help)");
  const auto v = scene::parseFieldValue(*f, p[2], error);
  if (!v) return args.fail("material '" + p[0] + "': " + p[1] + ": " + error);
  if (!scene::ops::setMaterialField(doc, id, *f, *v, error)) {
    if (!error.empty()) return args.fail(error);
    std::printf("unchanged (the value was already %s)\n", p[2].c_str());
    return 0;
  }
  if (!scene::saveScene(doc.state(), scenePath, error)) return args.fail(error);
  std::printf("set %s of %s in %s\n", p[1].c_str(), p[0].c_str(), scenePath.c_str());
  return 0;
}

}  // namespace

int runMaterial(int argc, char** argv) {
  if (argc < 1 || !std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h")) {
    std::printf("usage: hybridscape-cli material <subcommand> [arguments] [--help]\n\nsubcommands:\n");
    std::printf("  %-6s %s\n  %-6s %s\n", "list", listDecl().summary.c_str(), "set", setDecl().summary.c_str());
    return argc < 1 ? 2 : 0;
  }
  if (!std::strcmp(argv[0], "list")) return runList(argc - 1, argv + 1);
  if (!std::strcmp(argv[0], "set")) return runSetField(argc - 1, argv + 1);
  return usageCommand("material", std::string("unknown subcommand '") + argv[0] + "' (expected list or set)");
}

}  // namespace hs::cli
