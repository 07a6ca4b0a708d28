// `hybridscape-cli light add`: a light entity of a type with its fields
// (scene/light_add_operation.h), added as an undoable edit, then saved.
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/subcommands.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/light_add_operation.h"
#include "scene/operations.h"

namespace hs::cli {
namespace {

int runLightAdd(int argc, char** argv) {
  const OperationDecl& op = scene::lightAddOperation();
  OperationArgs args(op);
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string path = args.positionals()[0];
  Json values = Json::object();
  for (const ParamDecl& p : op.params) values[p.key] = args.value(p.key);
  std::string error;
  const std::optional<scene::LightAddRequest> request = scene::lightAddRequest(values, error);
  if (!request) return args.usage(error);
  std::optional<scene::SceneState> state = openScene(path, error);
  if (!state) return args.fail(error);
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(path));
  const scene::EntityId id = scene::ops::addLight(doc, request->name, request->transform, request->light);
  if (!scene::saveScene(doc.state(), path, error)) return args.fail(error);
  std::printf("added %s light '%s' (#%llu) to %s\n", args.text("type").c_str(), request->name.c_str(),
              static_cast<unsigned long long>(id), path.c_str());
  return 0;
}

constexpr Subcommand kSubs[] = {
    {"add", scene::lightAddOperation, runLightAdd},
};

}  // namespace

int runLight(int argc, char** argv) { return runSubcommands("light", "", kSubs, argc, argv); }

}  // namespace hs::cli
