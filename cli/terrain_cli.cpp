#include "cli/terrain_cli.h"

#include <cstdio>
#include <filesystem>

#include "cli/scene_open.h"
#include "scene/terrain_ops.h"

namespace hs::cli::terrain_cli {

bool openScene(const std::string& path, scene::Document& doc, std::string& error) {
  std::optional<scene::SceneState> s = hs::cli::openScene(path, error);
  if (!s) {
    if (!std::filesystem::exists(path)) error += " (create it with: hybridscape-cli new " + path + ")";
    return false;
  }
  doc.reset(std::move(*s), QString::fromStdString(path));
  return true;
}

scene::TerrainId openTerrain(const std::string& path, const std::string& name, scene::Document& doc,
                             std::string& error) {
  if (!openScene(path, doc, error)) return scene::kNoTerrain;
  const scene::EntityId e = scene::ops::findTerrainEntity(doc.state(), name, error);
  return e == scene::kNoEntity ? scene::kNoTerrain : doc.state().find(e)->terrain->terrain;
}

bool saveScene(const scene::Document& doc, const std::string& path, std::string& error, std::string& summary) {
  scene::SaveReport r;
  if (!scene::saveScene(doc.state(), path, error, &r)) return false;
  char buf[256];
  std::snprintf(buf, sizeof buf, "saved %s: %zu terrain tiles written (%.1f KiB), %zu unchanged, %zu removed", path.c_str(),
                r.tilesWritten, double(r.tileBytesWritten) / 1024.0, r.tilesUnchanged, r.tilesRemoved);
  summary = buf;
  return true;
}

}  // namespace hs::cli::terrain_cli
