// `hybridscape-cli ocio import|clear|list`: the scene's OpenColorIO config
// and its view transform (scene/ocio_config.h), read and checked by
// OpenColorIO, stored in the scene with its LUT files.
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/subcommands.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/ocio_config.h"

namespace hs::cli {
namespace {

int runOcioImport(int argc, char** argv) {
  OperationArgs args(scene::ocioImportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected a config file and a scene file");
  const std::string& configPath = args.positionals()[0];
  const std::string& path = args.positionals()[1];
  std::string error;
  // The config first: a bad one leaves the scene untouched.
  const std::optional<scene::OcioConfigData> config = scene::readOcioConfig(configPath, error);
  if (!config) return args.fail(error);
  bool changed = false;
  if (!editSceneFile(path, [&](scene::Document& doc) { return scene::ops::setOcioConfig(doc, *config); }, changed,
                     error))
    return args.fail(error);
  size_t bytes = 0;
  for (const scene::OcioFile& f : config->files) bytes += f.bytes->size();
  const scene::DisplayView dv = scene::resolveDisplayView(*config, "", "", error);
  std::printf("%s views through OpenColorIO config '%s' (%zu files, %zu bytes, stored in the scene): display '%s', "
              "view '%s'\n",
              path.c_str(), config->fileName.c_str(), config->files.size(), bytes, dv.display.c_str(),
              dv.view.c_str());
  return 0;
}

int runOcioClear(int argc, char** argv) {
  OperationArgs args(scene::ocioClearOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string& path = args.positionals()[0];
  std::string error;
  bool changed = false;
  if (!editSceneFile(path, [](scene::Document& doc) { return scene::ops::setOcioConfig(doc, {}); }, changed, error))
    return args.fail(error);
  if (!changed) {
    std::printf("unchanged (%s has no OpenColorIO config)\n", path.c_str());
    return 0;
  }
  std::printf("removed the OpenColorIO config from %s\n", path.c_str());
  return 0;
}

int runOcioList(int argc, char** argv) {
  OperationArgs args(scene::ocioListOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string& path = args.positionals()[0];
  std::string error;
  std::optional<scene::SceneState> state = openScene(path, error);
  if (!state) return args.fail(error);
  const scene::PostSettings& post = state->settings.post;
  if (post.ocioConfig.empty()) {
    std::printf("%s stores no OpenColorIO config (`hybridscape-cli ocio import CONFIG %s`)\n", path.c_str(),
                path.c_str());
    return 0;
  }
  const scene::OcioConfigSummary s = scene::ocioSummary(post.ocioConfig);
  if (!s.error.empty()) return args.fail(s.error);
  const scene::DisplayView chosen = scene::resolveDisplayView(post.ocioConfig, post.display, post.view, error);
  std::printf("OpenColorIO config '%s': the renderer's light enters as '%s'; view transform %s\n",
              post.ocioConfig.fileName.c_str(), s.sourceRole.c_str(), post.viewTransform ? "on" : "off");
  if (!error.empty()) std::printf("  (the chosen pair is not in the config: %s)\n", error.c_str());
  for (const scene::OcioDisplay& d : s.displays) {
    std::printf("display '%s'%s\n", d.name.c_str(), d.name == s.defaultDisplay ? " (default)" : "");
    for (const std::string& v : d.views) {
      const bool isChosen = error.empty() && d.name == chosen.display && v == chosen.view;
      std::printf("  view '%s'%s%s\n", v.c_str(), v == d.defaultView ? " (default)" : "", isChosen ? "  <- chosen" : "");
    }
  }
  std::printf("files:\n");
  for (const scene::OcioFile& f : post.ocioConfig.files)
    std::printf("  %s (%zu bytes)\n", f.path.c_str(), f.bytes ? f.bytes->size() : size_t(0));
  return 0;
}

constexpr Subcommand kSubs[] = {
    {"import", scene::ocioImportOperation, runOcioImport},
    {"clear", scene::ocioClearOperation, runOcioClear},
    {"list", scene::ocioListOperation, runOcioList},
};

}  // namespace

int runOcio(int argc, char** argv) { return runSubcommands("ocio", "", kSubs, argc, argv); }

}  // namespace hs::cli
