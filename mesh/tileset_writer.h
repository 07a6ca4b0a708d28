#pragma once
// Writing an OGC 3D Tiles 1.1 tileset (issue 38 item 5: `mesh export
// --format 3dtiles`, so Cesium and other viewers read what was prepared
// here): tileset.json and one glb per tile with content (tiles/<n>.glb
// beside it), refinement REPLACE, each tile's bounding box holding its
// content and its children's. The tile tree and its contents come from
// the caller (scene/tileset_export.h makes them from a cluster hierarchy
// or a LOD chain). Content is glTF 2.0 (y up, as 3D Tiles expects), each
// tile's vertices as floats about the tile's own origin (its node's
// translation), so kilometres of scan keep sub-millimetre steps.
//
// Files are written under temporary names and renamed when all are
// complete (mesh/export/export_geometry.h's PendingFiles): a failed or
// cancelled export leaves no tileset behind.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "mesh/mesh_export.h"

namespace hs::mesh {

struct TileToWrite {
  int parent = -1;             // index into the list (parents first); -1: the root (exactly one)
  double geometricError = 0.0; // metres: the error of drawing it and not its children
  MeshData content;            // in the tileset's frame (z up; origin + local positions); may be empty
};

struct TilesetWriteOptions {
  // The tileset frame to ECEF (the root's transform): an east-north-up
  // frame on the ellipsoid for a georeferenced tileset; identity for one
  // in a local frame.
  glm::dmat4 rootTransform{1.0};
  double tilesetError = 0.0;   // the tileset's geometricError (above the root's)
  std::string generator = "Hybridscape";
  int dracoBits = 0;           // content Draco-compressed, positions quantized to this many bits (0: exact)
};

// Writes `tiles` as `path` (tileset.json) and `tiles/<n>.glb` beside it.
// The result lists every file written (tileset.json first), counts the
// vertices and triangles of every tile, and with Draco gives the largest
// distance a position moved (quantizationError).
ExportResult writeTileset(const std::vector<TileToWrite>& tiles, const std::string& path,
                          const TilesetWriteOptions& options, const Progress* progress = nullptr);

}  // namespace hs::mesh
