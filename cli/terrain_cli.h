#pragma once
// `hybridscape-cli terrain <subcommand>`: terrain commands, one file each
// (cmd_terrain_*.cpp), sharing the helpers below. Every subcommand loads
// the scene into a Document, changes it through the same scene operations
// the editor uses (one undo step each), and saves it (only changed tiles).
#include <optional>
#include <string>

#include "cli/cli_args.h"
#include "scene/document.h"
#include "scene/hscene_file.h"

namespace hs::cli {

int runTerrainNew(int argc, char** argv);
int runTerrainImport(int argc, char** argv);
int runTerrainErode(int argc, char** argv);
int runTerrainPaintRules(int argc, char** argv);
int runTerrainExport(int argc, char** argv);

namespace terrain_cli {

// Opens `path` into `doc`; false with a one-line reason in `error`.
bool openScene(const std::string& path, scene::Document& doc, std::string& error);
// Saves and describes what was written ("saved x.hscene: 4 tiles (230 KB) written, 4221 unchanged").
bool saveScene(const scene::Document& doc, const std::string& path, std::string& error, std::string& summary);
// "2000x1500" or "2000" (square) -> metres (finite, > 0).
bool parseMetres(const std::string& text, double& x, double& y, std::string& error);
// "2049" or "2049x1025" -> samples (2..8193).
bool parseSamples(const std::string& text, int& x, int& y, std::string& error);
// "a,b" -> two finite numbers.
bool parsePair(const std::string& text, double& a, double& b, std::string& error);
// An integer option in [lo, hi].
bool intOption(const Args& args, const std::string& name, int lo, int hi, int& out, std::string& error);
bool doubleOption(const Args& args, const std::string& name, double lo, double hi, double& out, std::string& error);

}  // namespace terrain_cli
}  // namespace hs::cli
