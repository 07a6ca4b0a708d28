// hybridscape-cli foliage: plants as mesh assets, foliage types, the
// rule-based scatter, paint-layer fill and clearing, through the operations the editor's
// Foliage panel uses (scene/foliage_ops.h; declared once in
// foliage/foliage_operations.h). The scene file is saved after each
// command (only the foliage cells that changed are written).
#include <cstdio>
#include <optional>
#include <thread>

#include "cli/commands.h"
#include "cli/subcommands.h"
#include "cli/terrain_cli.h"
#include "foliage/foliage_operations.h"
#include "scene/foliage_ops.h"

namespace hs::cli {
namespace {

// The values given on the command line, keyed by declaration.
Json givenValues(const OperationArgs& args) {
  Json j = Json::object();
  for (const ParamDecl& p : args.operation().params)
    if (args.has(p.key)) j[p.key] = args.value(p.key);
  return j;
}

bool save(const OperationArgs& args, const scene::Document& doc, const std::string& path, int& code) {
  scene::SaveReport r;
  std::string error;
  if (!scene::saveScene(doc.state(), path, error, &r)) {
    code = args.fail(error);
    return false;
  }
  std::printf("saved %s: %zu foliage cells written (%.1f KiB), %zu unchanged, %zu removed\n", path.c_str(),
              r.cellsWritten, double(r.cellBytesWritten) / 1024.0, r.cellsUnchanged, r.cellsRemoved);
  return true;
}

void printOutcome(const scene::ops::FoliageOutcome& out) {
  for (const std::string& m : out.messages) std::fprintf(stderr, "warning: %s\n", m.c_str());
  if (!out.summary.empty()) std::printf("%s\n", out.summary.c_str());
}

// What every command that changes the foliage ends with: a refusal, or its
// warnings and summary and the scene saved. The exit status.
int finish(const OperationArgs& args, const scene::Document& doc, const std::string& path,
           const scene::ops::FoliageOutcome& out) {
  if (!out.ok) return args.fail(out.error);
  printOutcome(out);
  int code = 0;
  return save(args, doc, path, code) ? 0 : code;
}

int typeIndex(const OperationArgs& args, const scene::Document& doc, const std::string& name, int& code) {
  const int t = doc.state().foliage ? doc.state().foliage->store().findType(name) : -1;
  if (t < 0) code = args.fail("no foliage type named \"" + name + "\" in the scene (see hybridscape-cli info)");
  return t;
}

// The commands on one type (`foliage scatter|fill|clear TYPE SCENE ...`):
// the options parsed, the scene opened and the type found. Returns the
// exit code when the command ends here (help, a usage error, no scene or
// no such type); else nullopt with `doc`, `path` and `type` set.
std::optional<int> openTypeCommand(OperationArgs& args, int argc, char** argv, scene::Document& doc,
                                   std::string& path, uint16_t& type) {
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a foliage type and a scene file");
  path = args.positionals()[1];
  std::string error;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  int code = 0;
  const int t = typeIndex(args, doc, args.positionals()[0], code);
  if (t < 0) return code;
  type = uint16_t(t);
  return std::nullopt;
}

int runTypeAdd(int argc, char** argv) {
  OperationArgs args(foliage::foliageTypeAddOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a type name and a scene file");
  const std::string name = args.positionals()[0], path = args.positionals()[1];
  // Each option was checked against its declaration by parse(). What is
  // left is how they go together (a fade longer than the cull distance),
  // which concerns the values, not the scene: still a usage error, but
  // found after the scene opened, so each option alone at its bound is
  // seen to be accepted (tests/cli/test_cli_params).
  std::string error;
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  foliage::FoliageType type;
  if (!foliage::typeFromValues(name, givenValues(args), type, error)) return args.usage(error);
  const scene::ops::FoliageOutcome out = scene::ops::addFoliageType(doc, type);
  return finish(args, doc, path, out);
}

int runType(int argc, char** argv) {
  static const Subcommand subs[] = {{"add", foliage::foliageTypeAddOperation, runTypeAdd}};
  return runSubcommands("foliage type", "", subs, argc, argv);
}

int runScatter(int argc, char** argv) {
  OperationArgs args(foliage::foliageScatterOperation());
  scene::Document doc;
  std::string path;
  uint16_t t = 0;
  if (auto done = openTypeCommand(args, argc, argv, doc, path, t)) return *done;
  const Json values = givenValues(args);
  const foliage::FoliageType rules = foliage::scatterRules(doc.state().foliage->store().type(t), values);
  if (const std::vector<std::string> problems = foliage::validate(rules); !problems.empty())
    return args.usage(problems.front());
  const bool meshes = rules.surface != foliage::SurfaceFilter::Terrain;
  const scene::FoliageGround ground(doc.state(), meshes);
  const scene::ops::FoliageOutcome out =
      scene::ops::scatterFoliage(doc, ground, {t}, uint64_t(args.integer("seed")), foliage::regionFromValues(values),
                                 rules);
  return finish(args, doc, path, out);
}

int runFill(int argc, char** argv) {
  OperationArgs args(foliage::foliageFillOperation());
  scene::Document doc;
  std::string path;
  uint16_t t = 0;
  if (auto done = openTypeCommand(args, argc, argv, doc, path, t)) return *done;
  const Json values = givenValues(args);
  const scene::FoliageGround ground(doc.state(), false);  // terrain only
  const scene::ops::FoliageOutcome out =
      scene::ops::fillFoliageLayer(doc, ground, {t}, args.text("layer"), args.number("min_weight"),
                                   uint64_t(args.integer("seed")),
                                   foliage::regionFromValues(values));
  return finish(args, doc, path, out);
}

int runClear(int argc, char** argv) {
  OperationArgs args(foliage::foliageClearOperation());
  scene::Document doc;
  std::string path;
  uint16_t t = 0;
  if (auto done = openTypeCommand(args, argc, argv, doc, path, t)) return *done;
  const scene::ops::FoliageOutcome out = scene::ops::eraseFoliage(doc, foliage::regionFromValues(givenValues(args)), {t});
  return finish(args, doc, path, out);
}

int runMove(int argc, char** argv) {
  OperationArgs args(foliage::foliageMoveOperation());
  scene::Document doc;
  std::string path;
  uint16_t t = 0;
  if (auto done = openTypeCommand(args, argc, argv, doc, path, t)) return *done;
  const std::vector<double> o = args.numbers("offset_m");
  const bool snap = !args.flag("keep_height");
  const scene::FoliageGround ground(doc.state(), snap && doc.foliage().store().type(t).surface !=
                                                              foliage::SurfaceFilter::Terrain);
  const scene::ops::FoliageOutcome out =
      scene::ops::moveFoliage(doc, ground, {t}, foliage::regionFromValues(givenValues(args)),
                              glm::dvec3(o.at(0), o.at(1), o.at(2)), snap);
  return finish(args, doc, path, out);
}

int runPlant(int argc, char** argv) {
  OperationArgs args(foliage::foliagePlantOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected an asset name and a scene file");
  const std::string name = args.positionals()[0], path = args.positionals()[1];
  std::string error;
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  const foliage::PlantParams params = foliage::plantFromValues(givenValues(args));
  foliage::PlantStats stats;
  const scene::AssetId id = scene::ops::addPlantAsset(doc, name, params, error, &stats);
  if (id == scene::kNoAsset) return args.fail(error);
  const scene::MeshAsset& a = *doc.state().findAsset(id);
  std::printf("mesh asset \"%s\": %s, %zu triangles (%zu stems, %zu leaves)\n", name.c_str(),
              foliage::plantKindName(params.kind), a.data->triangleCount(), stats.stems, stats.leaves);
  for (size_t k = 0; k < a.lods.size(); ++k)
    std::printf("  LOD %zu: %zu triangles, Hausdorff %.3g m\n", k + 1, a.lods[k].triangles, a.lods[k].hausdorff);
  int code = 0;
  return save(args, doc, path, code) ? 0 : code;
}

const Subcommand kSubs[] = {
    {"plant", foliage::foliagePlantOperation, runPlant},
    {"type", foliage::foliageTypeAddOperation, runType},
    {"scatter", foliage::foliageScatterOperation, runScatter},
    {"fill", foliage::foliageFillOperation, runFill},
    {"clear", foliage::foliageClearOperation, runClear},
    {"move", foliage::foliageMoveOperation, runMove},
    {"impostors", foliage::foliageImpostorsOperation, runFoliageImpostors},
};

}  // namespace

int runFoliage(int argc, char** argv) {
  return runSubcommands("foliage",
                        "Foliage of a scene: generated plants, foliage types drawing mesh assets, the\n"
                        "rule-based scatter and clearing, baked impostors, through the same operations as the editor's\n"
                        "Foliage panel. The scene file is saved after each command (only the foliage\n"
                        "cells that changed are written).\n",
                        kSubs, argc, argv);
}

}  // namespace hs::cli
