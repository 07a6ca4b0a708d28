// `hybridscape-cli terrain`: dispatches to the terrain subcommands.
#include <cstdio>
#include <cstring>

#include "cli/commands.h"
#include "cli/terrain_cli.h"

namespace hs::cli {
namespace {

struct Sub {
  const char* name;
  const char* summary;
  int (*run)(int, char**);
};

const Sub kSubs[] = {
    {"new", "add a terrain (flat, or hills within a height range)", runTerrainNew},
    {"import", "import a DEM (GeoTIFF, DTED, .hgt, ASCII grid, ...) as a terrain", runTerrainImport},
    {"erode", "thermal or hydraulic erosion over a terrain; prints the mass error", runTerrainErode},
    {"paint-rules", "paint a terrain's layers by slope and altitude", runTerrainPaintRules},
    {"export", "write heights (16-bit PNG, EXR, GeoTIFF, RAW r16) and paint weights", runTerrainExport},
};

void help() {
  std::printf(
      "usage: hybridscape-cli terrain <subcommand> [arguments] [--help]\n\n"
      "Terrains of a scene: made, imported, eroded, painted and exported through the\n"
      "same operations as the editor's Terrain panel. The scene file is saved after\n"
      "each command (only the tiles that changed are written).\n\n"
      "subcommands:\n");
  for (const Sub& s : kSubs) std::printf("  %-12s %s\n", s.name, s.summary);
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
