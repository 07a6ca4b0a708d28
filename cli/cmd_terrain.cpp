// `hybridscape-cli terrain`: dispatches to the terrain subcommands.
#include "cli/commands.h"
#include "cli/subcommands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_ops.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {
namespace {

const Subcommand kSubs[] = {
    {"new", scene::ops::terrainNewOperation, runTerrainNew},
    {"import", terrain::terrainImportOperation, runTerrainImport},
    {"erode", terrain::terrainErodeOperation, runTerrainErode},
    {"paint-rules", terrain::terrainPaintRulesOperation, runTerrainPaintRules},
    {"export", terrain::terrainExportOperation, runTerrainExport},
    {"layer", terrain::terrainLayerOperation, runTerrainLayer},
};

}  // namespace

int runTerrain(int argc, char** argv) {
  return runSubcommands("terrain",
                        "Terrains of a scene: made, imported, eroded, painted and exported through the\n"
                        "same operations as the editor's Terrain panel. The scene file is saved after\n"
                        "each command (only the tiles that changed are written).\n",
                        kSubs, argc, argv);
}

}  // namespace hs::cli
