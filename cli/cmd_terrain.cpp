// `hybridscape-cli terrain`: dispatches to the terrain subcommands.
#include <cstdio>
#include <cstring>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {
namespace {

struct Sub {
  const char* name;
  const OperationDecl& (*decl)();  // its summary
  int (*run)(int, char**);
};

const Sub kSubs[] = {
    {"new", scene::ops::terrainNewOperation, runTerrainNew},
    {"import", terrain::terrainImportOperation, runTerrainImport},
    {"erode", terrain::terrainErodeOperation, runTerrainErode},
    {"paint-rules", terrain::terrainPaintRulesOperation, runTerrainPaintRules},
    {"export", terrain::terrainExportOperation, runTerrainExport},
};

void help() {
  std::printf(
      "usage: hybridscape-cli terrain <subcommand> [arguments] [--help]\n\n"
      "Terrains of a scene: made, imported, eroded, painted and exported through the\n"
      "same operations as the editor's Terrain panel. The scene file is saved after\n"
      "each command (only the tiles that changed are written).\n\n"
      "subcommands:\n");
  for (const Sub& s : kSubs) std::printf("  %-12s %s\n", s.name, s.decl().summary.c_str());
}

}  // namespace

int runTerrain(int argc, char** argv) {
  if (argc < 1 || !std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h")) {
    help();
    return argc < 1 ? 2 : 0;
  }
  for (const Sub& s : kSubs)
    if (!std::strcmp(argv[0], s.name)) return s.run(argc - 1, argv + 1);
  std::fprintf(stderr, "hybridscape-cli terrain: error: unknown subcommand '%s' (see hybridscape-cli terrain --help)\n",
               argv[0]);
  return 2;
}

}  // namespace hs::cli
