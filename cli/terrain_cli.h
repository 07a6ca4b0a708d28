#pragma once
// `hybridscape-cli terrain <subcommand>`: terrain commands, one file each
// (cmd_terrain_*.cpp), sharing the helpers below. Every subcommand loads
// the scene into a Document, changes it through the same scene operations
// the editor uses (one undo step each), and saves it (only changed tiles).
#include <optional>
#include <string>

#include "cli/operation_options.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {

int runTerrainNew(int argc, char** argv);
int runTerrainImport(int argc, char** argv);
int runTerrainErode(int argc, char** argv);
int runTerrainPaintRules(int argc, char** argv);
int runTerrainExport(int argc, char** argv);
int runTerrainLayer(int argc, char** argv);

namespace terrain_cli {

// Opens `path` into `doc`; false with a one-line reason in `error`.
bool openScene(const std::string& path, scene::Document& doc, std::string& error);
// Opens `path` into `doc` and finds the terrain named `name` (any name when
// the scene has one terrain); kNoTerrain with a one-line reason in `error`.
scene::TerrainId openTerrain(const std::string& path, const std::string& name, scene::Document& doc,
                             std::string& error);
// Saves and describes what was written ("saved x.hscene: 4 tiles (230 KB) written, 4221 unchanged").
bool saveScene(const scene::Document& doc, const std::string& path, std::string& error, std::string& summary);

}  // namespace terrain_cli
}  // namespace hs::cli
