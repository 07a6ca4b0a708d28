// `hybridscape-cli lut import|clear`: the scene's grading LUT
// (scene/color_lut.h), read and checked by OpenColorIO, stored in the scene.
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/subcommands.h"
#include "scene/color_lut.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {
namespace {

int runLutImport(int argc, char** argv) {
  OperationArgs args(scene::lutImportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a LUT file and a scene file");
  const std::string& lutPath = args.positionals()[0];
  const std::string& path = args.positionals()[1];
  std::string error;
  // The LUT first: a bad file leaves the scene untouched.
  const std::optional<scene::LutData> lut = scene::readLutFile(lutPath, error);
  if (!lut) return args.fail(error);
  bool changed = false;
  if (!editSceneFile(path, [&](scene::Document& doc) { return scene::ops::setLut(doc, *lut); }, changed, error))
    return args.fail(error);
  std::printf("graded %s with LUT '%s' (%zu bytes, stored in the scene)\n", path.c_str(), lut->fileName.c_str(),
              lut->bytes->size());
  return 0;
}

int runLutClear(int argc, char** argv) {
  OperationArgs args(scene::lutClearOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string& path = args.positionals()[0];
  std::string error;
  bool changed = false;
  if (!editSceneFile(path, [](scene::Document& doc) { return scene::ops::setLut(doc, {}); }, changed, error))
    return args.fail(error);
  if (!changed) {
    std::printf("unchanged (%s has no LUT)\n", path.c_str());
    return 0;
  }
  std::printf("removed the LUT from %s\n", path.c_str());
  return 0;
}

constexpr Subcommand kSubs[] = {
    {"import", scene::lutImportOperation, runLutImport},
    {"clear", scene::lutClearOperation, runLutClear},
};

}  // namespace

int runLut(int argc, char** argv) { return runSubcommands("lut", "", kSubs, argc, argv); }

}  // namespace hs::cli
