#pragma once
// `mesh export ASSET out/tileset.json --format 3dtiles` (issue 38 item 5):
// a mesh asset as an OGC 3D Tiles 1.1 tileset (mesh/tileset_writer.h).
//
// A clustered asset (scene/cluster_asset.h) becomes a tile tree of
// uniform cuts: the root holds the hierarchy's roots (the cut at their
// largest error), each level below the cut at half the error of the one
// above, down to level 0 (error 0); a tile whose next cut would hold more
// than `maxTileTriangles` splits its square into four. Each uniform cut is
// crack-free (cluster_hierarchy.h), so a viewer drawing every tile at one
// depth shows a closed surface; where neighbouring tiles are drawn at
// different depths, 3D Tiles' replacement can show cracks along the tile
// border, as any tileset does. An asset without a hierarchy becomes a
// chain: its coarsest LOD at the root, each finer level a child, level 0
// the leaf; without LODs, one tile.
//
// Placement: vertices in a coordinate system PROJ knows (`crs`; "auto":
// the one the asset's import recorded, e.g. a tileset import's UTM zone)
// are converted to ECEF and written in the east-north-up frame at the
// asset's origin (the root's transform), as Cesium expects; "local"
// writes the asset's own frame, unplaced on the globe (said in a note).
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_export.h"
#include "scene/scene_state.h"

namespace hs::scene {

struct TilesetExportOptions {
  std::string crs = "auto";
  size_t maxTileTriangles = 65536;
  int dracoBits = 0;  // content Draco-compressed with positions on a 2^bits grid per primitive (0: exact)
};

// Notes (what was assumed) go to `notes`; the result names every file.
mesh::ExportResult exportTileset(const MeshAsset& asset, const std::string& path, const TilesetExportOptions& options,
                                 std::vector<std::string>& notes, const Progress* progress = nullptr);

}  // namespace hs::scene
