#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/impostor_bake.h"
#include "cli/operation_options.h"
#include "scene/demo_scene.h"
#include "scene/hscene_file.h"

namespace hs::cli {
namespace {

OperationDecl writeDecl(const char* name, const char* summary, const char* description) {
  return {.name = name,
          .summary = summary,
          .usage = "<scene.hscene> [--force]",
          .description = description,
          .positionals = {{.name = "scene.hscene", .help = "the file to write"}},
          .params = {{.key = "force", .option = "force", .label = "Replace", .type = ParamType::Flag,
                      .help = "replace the file if it exists"}}};
}

int writeNew(const OperationDecl& decl, int argc, char** argv, bool demo) {
  OperationArgs args(decl);
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file name");
  const std::string path = args.positionals()[0];
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !args.flag("force"))
    return args.fail(path + " already exists (use --force to replace it)");
  std::string error;
  std::optional<scene::SceneState> state;
  if (demo)
    state = scene::buildDemoScene(error);
  else
    state = scene::buildStarterScene();
  if (!state) return args.fail(error);
  if (demo && !args.flag("no_impostors")) {
    // The foliage's far level stored in the file, so opening it or
    // rendering a frame of it on a farm node bakes nothing.
    scene::Document doc;
    doc.reset(std::move(*state), QString());
    const ImpostorBake bake = bakeImpostors(doc, false);
    if (!bake.ok)
      std::fprintf(stderr, "warning: impostors not stored (%s); a frame that needs one bakes it\n",
                   bake.error.c_str());
    state = doc.state();
  }
  if (!scene::saveScene(*state, path, error)) return args.fail(error);
  std::printf("wrote %s (%zu entities, %zu assets)\n", path.c_str(), state->entities.size(), state->assets.size());
  return 0;
}

}  // namespace

int runNew(int argc, char** argv) {
  static const OperationDecl decl = writeDecl(
      "new", "create a scene with a sun and a camera",
      "Creates a scene holding a sun and a camera. Refuses to replace an existing file unless --force is given.");
  return writeNew(decl, argc, argv, false);
}

int runDemo(int argc, char** argv) {
  static const OperationDecl decl = [] {
    OperationDecl d = writeDecl(
        "demo", "write the built-in demo scene",
        "Writes the built-in demo scene (the one the editor opens with no file): the Stanford bunny scan in a "
        "terrain valley with foliage, particle emitters, lights and a stereo camera flight; the foliage's "
        "impostors are baked on a headless context and stored (as `foliage impostors` does).");
    d.usage = "<scene.hscene> [--force] [--no-impostors]";
    d.params.push_back({.key = "no_impostors", .option = "no-impostors", .label = "No impostors",
                        .type = ParamType::Flag,
                        .help = "store no baked impostors (a frame that needs one bakes it)"});
    return d;
  }();
  return writeNew(decl, argc, argv, true);
}

}  // namespace hs::cli
