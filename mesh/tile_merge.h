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
#include <unordered_map>
#include <vector>

#include "mesh/mesh_import.h"

namespace hs::mesh {

struct TileImportOptions {
  ImportOptions import;           // applied to every tile
  double weldTolerance = 1e-3;    // metres: border vertices this close are the same point
  // Reads one tile; empty: importMesh. (The document's pipeline reads
  // Assimp's formats in a worker process: scene/import_isolation.h.)
  std::function<ImportResult(const std::string& path, const ImportOptions&, const Progress*)> readTile;
  // Tiles read at once, each on a thread of its own (0: one per hardware
  // thread). The pipeline sets it from the cores and the import worker's
  // memory limit (scene::tileReadParallelism): a tile read by Assimp waits
  // on its own worker process, so tiles overlap their workers' start and
  // reading. The merged mesh, the reports and the error do not depend on it
  // nor on which tile finishes first: tiles are merged in the order given.
  unsigned maxParallel = 1;
};

struct TileImportResult {
  std::optional<MeshData> mesh;   // set on success
  std::vector<ImportReport> tiles;  // one per file, in the order given
  size_t borderVertices = 0;      // open-boundary vertices over all tiles
  size_t borderVerticesSnapped = 0;  // moved onto a vertex of another tile
  size_t borderVerticesMerged = 0;   // and merged with it (same UV and normal)
  std::string error;              // names the tile that failed (the first in the order given)
  bool cancelled = false;
  bool ok() const { return mesh.has_value(); }
};

TileImportResult importTiles(const std::vector<std::string>& paths, const TileImportOptions& options,
                             const Progress* progress = nullptr);

// The welding step on its own, for meshes already in memory (each with its
// own origin): returns the merged mesh.
MeshData mergeTiles(std::vector<MeshData>&& tiles, double weldTolerance, TileImportResult* stats = nullptr);

// Vertices on an open boundary of `m` (an edge with one face, positions
// welded), as a flag per vertex.
std::vector<uint8_t> openBoundaryVertices(const MeshData& m);

// Tiles' border vertices snapped one tile after another (mergeTiles; the
// streamed cluster build, which reads tiles one at a time and so keeps
// only their borders): a vertex within the tolerance of an earlier one of
// another tile takes its position (the nearest; the lowest id on a tie),
// else it is added for later tiles to find. Positions in one common frame.
class BorderSnapGrid {
 public:
  explicit BorderSnapGrid(double tolerance);
  struct Earlier {
    uint32_t id;
    glm::vec3 position;
  };
  std::optional<Earlier> snapOrAdd(const glm::vec3& position, uint32_t id, uint32_t tile);
  size_t size() const { return grid_.size(); }

 private:
  struct Entry {
    glm::vec3 position;
    uint32_t id, tile;
  };
  double tol_, cell_;
  std::unordered_multimap<uint64_t, Entry> grid_;
};

}  // namespace hs::mesh
