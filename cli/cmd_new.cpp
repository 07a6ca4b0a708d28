#include <cstdio>
#include <filesystem>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "scene/demo_scene.h"
#include "scene/hscene_file.h"

namespace hs::cli {
namespace {

int writeNew(const char* cmd, const char* help, int argc, char** argv, bool demo) {
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"force", false}}, args, error)) return usage(cmd, error);
  if (args.help) {
    std::printf("%s", help);
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file name");
  const std::string path = args.positional[0];
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !args.has("force"))
    return fail(cmd, path + " already exists (use --force to replace it)");
  std::optional<scene::SceneState> state;
  if (demo)
    state = scene::buildDemoScene(error);
  else
    state = scene::buildStarterScene();
  if (!state) return fail(cmd, error);
  if (!scene::saveScene(*state, path, error)) return fail(cmd, error);
  std::printf("wrote %s (%zu entities, %zu assets)\n", path.c_str(), state->entities.size(), state->assets.size());
  return 0;
}

}  // namespace

int runNew(int argc, char** argv) {
  return writeNew("new",
                  "usage: hybridscape-cli new <scene.hscene> [--force]\n\n"
                  "Creates a scene holding a sun and a camera. Refuses to replace an\n"
                  "existing file unless --force is given.\n",
                  argc, argv, false);
}

int runDemo(int argc, char** argv) {
  return writeNew("demo",
                  "usage: hybridscape-cli demo <scene.hscene> [--force]\n\n"
                  "Writes the built-in demo scene (the one the editor opens with no file):\n"
                  "the Stanford bunny scan as three instances of one asset, a sun and a camera.\n",
                  argc, argv, true);
}

}  // namespace hs::cli
