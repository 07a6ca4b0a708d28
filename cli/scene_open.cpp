#include "cli/scene_open.h"

#include <cstdio>

#include "core/escape_control.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {

std::optional<scene::SceneState> openScene(const std::string& path, std::string& error) {
  scene::LoadReport report;
  std::optional<scene::SceneState> state = scene::loadScene(path, error, nullptr, &report);
  for (const std::string& w : report.warnings)
    std::fprintf(stderr, "warning: %s\n", escapeControlCharacters(w).c_str());
  return state;
}

bool editSceneFile(const std::string& path, const std::function<bool(scene::Document&)>& edit, bool& changed,
                   std::string& error) {
  std::optional<scene::SceneState> state = openScene(path, error);
  if (!state) return false;
  scene::Document doc;
  doc.reset(std::move(*state), QString::fromStdString(path));
  changed = edit(doc);
  return !changed || scene::saveScene(doc.state(), path, error);
}

}  // namespace hs::cli
