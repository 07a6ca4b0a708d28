#pragma once
// Multi-tile scans: photogrammetry tools cut large sites into tiles (files)
// that share one coordinate frame. They import as one asset: every tile is
// read with the same options (its own sidecar offset when the mode is
// Auto), brought to one common double origin, and the tiles' open borders
// are welded: border vertices of different tiles closer than the
// tolerance are snapped onto one position (and merged where their UV and
// normal agree too), so the decimator sees one connected surface.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh_import.h"

namespace hs::mesh {

struct TileImportOptions {
  ImportOptions import;           // applied to every tile
  double weldTolerance = 1e-3;    // metres: border vertices this close are the same point
  // Reads one tile; empty: importMesh. (The document's pipeline reads
  // Assimp's formats in a worker process: scene/import_isolation.h.)
  std::function<ImportResult(const std::string& path, const ImportOptions&, const Progress*)> readTile;
};

struct TileImportResult {
  std::optional<MeshData> mesh;   // set on success
  std::vector<ImportReport> tiles;  // one per file, in the order given
  size_t borderVertices = 0;      // open-boundary vertices over all tiles
  size_t borderVerticesSnapped = 0;  // moved onto a vertex of another tile
  size_t borderVerticesMerged = 0;   // and merged with it (same UV and normal)
  std::string error;              // names the tile that failed
  bool cancelled = false;
  bool ok() const { return mesh.has_value(); }
};

TileImportResult importTiles(const std::vector<std::string>& paths, const TileImportOptions& options,
                             const Progress* progress = nullptr);

// The welding step on its own, for meshes already in memory (each with its
// own origin): returns the merged mesh.
MeshData mergeTiles(std::vector<MeshData>&& tiles, double weldTolerance, TileImportResult* stats = nullptr);

}  // namespace hs::mesh
