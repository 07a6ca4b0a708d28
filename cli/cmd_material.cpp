// `hybridscape-cli material list|set|add|assign|delete`: the document's
// materials by name, their fields as scene::materialFields() declares them,
// and which mesh slot draws with which.
#include <cstdio>
#include <cstring>

#include "cli/commands.h"
#include "cli/material_info.h"
#include "cli/operation_options.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/material_ops.h"
#include "scene/mesh_target.h"

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

const OperationDecl& addDecl() {
  static const OperationDecl decl{
      .name = "material add",
      .summary = "add a material (a copy of another with --like)",
      .usage = "<name> <scene.hscene> [--like <material>]",
      .description = "Adds a material named <name>, owned by the scene (it stays when mesh assets go), with the "
                     "default fields or a copy of --like's, then saves. `material assign` puts it on a mesh's "
                     "slot. Example:\n  material add Glass scene.hscene --like \"Bunny / default\"",
      .positionals = {{.name = "name", .help = "the new material's name (not taken)"},
                      {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}},
      .params = {{.key = "like", .option = "like", .label = "Like", .type = ParamType::Text,
                  .help = "copy the fields of this material"}}};
  return decl;
}

const OperationDecl& assignDecl() {
  static const OperationDecl decl{
      .name = "material assign",
      .summary = "make a mesh's material slot draw with a material",
      .usage = "<entity-or-asset> <slot> <material> <scene.hscene>",
      .description = "Makes slot <slot> (0-based, as `material list` and the Properties panel number them) of the "
                     "mesh of <entity-or-asset> (an entity with a mesh, else a mesh asset by name) draw with "
                     "<material>, then saves. Every entity showing that mesh asset follows.",
      .positionals = {{.name = "entity-or-asset", .help = "an entity with a mesh, or a mesh asset"},
                      {.name = "slot", .help = "the slot's number, from 0"},
                      {.name = "material", .help = "the material's name"},
                      {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
  return decl;
}

const OperationDecl& deleteDecl() {
  static const OperationDecl decl{
      .name = "material delete",
      .summary = "delete a material no mesh slot uses",
      .usage = "<material> <scene.hscene>",
      .description = "Deletes the material named <material> with its timeline tracks, then saves. A material "
                     "that a mesh slot still draws with is refused with the asset and slot named (assign another "
                     "one first).",
      .positionals = {{.name = "material", .help = "the material's name"},
                      {.name = "scene.hscene", .help = "the scene file (saved afterwards)"}}};
  return decl;
}

// Loads `path` into `doc`; false with the message printed (through `args`).
bool openScene(OperationArgs& args, const std::string& path, scene::Document& doc, int& code) {
  std::string error;
  std::optional<scene::SceneState> state = scene::loadScene(path, error);
  if (!state) {
    code = args.fail(error);
    return false;
  }
  doc.reset(std::move(*state), QString::fromStdString(path));
  return true;
}

scene::MaterialId materialNamed(const scene::Document& doc, const std::string& name, const std::string& path,
                                std::string& error) {
  const scene::MaterialId id = doc.state().findMaterialByName(name);
  if (id == scene::kNoMaterial)
    error = "no material named '" + name + "' in " + path + " (see `hybridscape-cli material list`)";
  return id;
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
  scene::Document doc;
  int code = 0;
  if (!openScene(args, scenePath, doc, code)) return code;
  std::string error;
  const scene::MaterialId id = materialNamed(doc, p[0], scenePath, error);
  if (id == scene::kNoMaterial) return args.fail(error);
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

int runAdd(int argc, char** argv) {
  OperationArgs args(addDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& p = args.positionals();
  if (p.size() != 2) return args.usage("expected <name> <scene.hscene>");
  scene::Document doc;
  int code = 0;
  if (!openScene(args, p[1], doc, code)) return code;
  std::string error;
  scene::MaterialId like = scene::kNoMaterial;
  if (const std::optional<std::string> from = args.given("like")) {
    like = materialNamed(doc, *from, p[1], error);
    if (like == scene::kNoMaterial) return args.fail("--like: " + error);
  }
  if (scene::ops::addMaterial(doc, p[0], like, error) == scene::kNoMaterial) return args.fail(error);
  if (!scene::saveScene(doc.state(), p[1], error)) return args.fail(error);
  std::printf("added material %s to %s\n", p[0].c_str(), p[1].c_str());
  return 0;
}

int runAssign(int argc, char** argv) {
  OperationArgs args(assignDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& p = args.positionals();
  if (p.size() != 4) return args.usage("expected <entity-or-asset> <slot> <material> <scene.hscene>");
  scene::Document doc;
  int code = 0;
  if (!openScene(args, p[3], doc, code)) return code;
  std::string error;
  const scene::MeshTarget target = scene::findMeshTarget(doc.state(), p[0], error);
  if (!target.asset) return args.fail(error);
  size_t slot = 0;
  try {
    size_t used = 0;
    const long long v = std::stoll(p[1], &used);
    if (used != p[1].size() || v < 0) throw std::invalid_argument(p[1]);
    slot = size_t(v);
  } catch (const std::exception&) {
    return args.fail("slot: '" + p[1] + "' is not a slot number (0, 1, ...)");
  }
  const scene::MaterialId material = materialNamed(doc, p[2], p[3], error);
  if (material == scene::kNoMaterial) return args.fail(error);
  const std::string assetName = target.asset->name;
  if (!scene::ops::assignMaterial(doc, target.asset->id, slot, material, error)) {
    if (!error.empty()) return args.fail(error);
    std::printf("unchanged (slot %zu of %s already draws with %s)\n", slot, assetName.c_str(), p[2].c_str());
    return 0;
  }
  if (!scene::saveScene(doc.state(), p[3], error)) return args.fail(error);
  std::printf("slot %zu of %s now draws with %s\n", slot, target.what.c_str(), p[2].c_str());
  return 0;
}

int runDelete(int argc, char** argv) {
  OperationArgs args(deleteDecl());
  if (auto code = args.parse(argc, argv)) return *code;
  const std::vector<std::string>& p = args.positionals();
  if (p.size() != 2) return args.usage("expected <material> <scene.hscene>");
  scene::Document doc;
  int code = 0;
  if (!openScene(args, p[1], doc, code)) return code;
  std::string error;
  const scene::MaterialId id = materialNamed(doc, p[0], p[1], error);
  if (id == scene::kNoMaterial) return args.fail(error);
  if (!scene::ops::removeMaterial(doc, id, error)) return args.fail(error);
  if (!scene::saveScene(doc.state(), p[1], error)) return args.fail(error);
  std::printf("deleted material %s from %s\n", p[0].c_str(), p[1].c_str());
  return 0;
}

}  // namespace

int runMaterial(int argc, char** argv) {
  if (argc < 1 || !std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h")) {
    std::printf("usage: hybridscape-cli material <subcommand> [arguments] [--help]\n\nsubcommands:\n");
    for (const OperationDecl* d : {&listDecl(), &setDecl(), &addDecl(), &assignDecl(), &deleteDecl()})
      std::printf("  %-7s %s\n", d->name.substr(d->name.find(' ') + 1).c_str(), d->summary.c_str());
    return argc < 1 ? 2 : 0;
  }
  if (!std::strcmp(argv[0], "list")) return runList(argc - 1, argv + 1);
  if (!std::strcmp(argv[0], "set")) return runSetField(argc - 1, argv + 1);
  if (!std::strcmp(argv[0], "add")) return runAdd(argc - 1, argv + 1);
  if (!std::strcmp(argv[0], "assign")) return runAssign(argc - 1, argv + 1);
  if (!std::strcmp(argv[0], "delete")) return runDelete(argc - 1, argv + 1);
  return usageCommand("material", std::string("unknown subcommand '") + argv[0] +
                                      "' (expected list, set, add, assign or delete)");
}

}  // namespace hs::cli
