#pragma once
// The cluster hierarchy of a scan larger than memory (issue 38 item 1's
// out-of-core build): the scan's tiles are read one at a time, its
// triangles sorted into the cells of a spatial partition on disk, and the
// hierarchy built cell by cell, pages written out as each level is made.
//
//  1. Tiles are read once (one in memory at a time) into a scratch file of
//     triangles in one local frame (their open borders snapped onto earlier
//     tiles' within a tolerance, as an in-memory tile import welds them;
//     only border vertices are kept for that), keeping every 16th
//     triangle's centre. A k-d tree over those centres cuts the scan into
//     cells of about `cellTriangles` (medians on the longest axis).
//  2. Each triangle goes to the cell holding its centre. A triangle whose
//     corners lie in other cells crosses a cell border: for each corner,
//     the cells using that position are recorded (a sorted list, as big
//     as the cells' borders, not the scan). Every triangle around such a
//     position is also copied to the other cells using it (their "halo"),
//     so vertex normals along a cell border see the faces on both sides.
//  3. Cells are built in the k-d tree's post-order: a leaf cell with the
//     in-core steps (cluster_levels.h) and every position another cell
//     uses locked, level by level until nothing more simplifies; what is
//     left (the cell's top clusters, about as many triangles as its
//     border holds) goes up, and two siblings' leftovers are grouped and
//     simplified together with only the positions shared with cells
//     outside both locked; up to one root. A level's clusters are paged
//     as soon as they are grouped (siblings side by side) and handed to
//     the page sink; only the index (every cluster's tests, ~80 bytes a
//     cluster) and the leftovers stay in memory.
// Memory: one tile, the centre samples, the border list, the index and
// one cell's build (about 300 bytes a triangle of the cell). Deterministic:
// cells are built one after another (each cell's groups in parallel, merged
// in order, as in core); the pages and the index depend on the tiles and
// the options only, not on the thread count.
// Unlike the in-core build, cell borders stay at full resolution until
// their cells meet: with cells of 512k triangles this costs a few more
// levels near the borders, not detail anywhere.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "meshproc/cluster_pages.h"

namespace hs::mesh {

// Where the scan's tiles come from: read one at a time, in order; each in
// its own origin (brought to the first tile's).
class ScanTileSource {
 public:
  virtual ~ScanTileSource() = default;
  virtual size_t tileCount() const = 0;
  // Tile `i` (positions, UVs, triangles; other attributes are ignored);
  // false with `error` naming the tile when it cannot be read.
  virtual bool readTile(size_t i, MeshData& out, std::string& error) = 0;
};

struct StreamedClusterOptions {
  ClusterOptions clusters;
  size_t cellTriangles = size_t(1) << 19;  // a leaf cell of the partition holds about this many
  size_t pageBytes = size_t(16) << 10;     // as paginate's
  std::string scratchDir;                  // for the triangle files (deleted after); "": the system's temp folder
  // Metres: an open-border vertex of a tile this close to one of an earlier
  // tile takes its position (mesh/tile_merge.h); 0: tiles join only where
  // their vertices are the same.
  double weldTolerance = 1e-3;
};

struct StreamedClusterReport {
  ClusterBuildReport build;  // per level: clusters and triangles made at it, over every cell
  size_t tiles = 0, triangles = 0, cells = 0;
  size_t tileBorderVertices = 0, tileBorderVerticesSnapped = 0;  // tiles' open borders, and those moved onto another tile's
  size_t borderPositions = 0;  // positions two or more cells use
  size_t haloTriangles = 0;    // copied beside their cell for border normals
  uint64_t scratchBytes = 0;   // largest size of the scratch files at once
  double readSeconds = 0.0, partitionSeconds = 0.0, buildSeconds = 0.0;
  bool uvsDropped = false;     // some tiles had UVs, others none: none kept
};

// Receives each page as it is written, in page order; false with `error`
// stops the build.
using PageSink = std::function<bool(std::vector<uint8_t>&& page, std::string& error)>;

// The hierarchy of the tiles, as its index (pages counted in it) with its
// pages handed to `sink`; nullopt with `error` (a tile that cannot be
// read, a scratch file that cannot be written, no triangle at all) or when
// cancelled through `progress` (error empty).
std::optional<ClusterIndex> buildClusterPagesStreamed(ScanTileSource& tiles, const StreamedClusterOptions& options,
                                                      const PageSink& sink, StreamedClusterReport* report,
                                                      const Progress* progress, std::string& error);

// Tiles held in memory (tests, the bench, one mesh read whole).
class MeshTileSource : public ScanTileSource {
 public:
  explicit MeshTileSource(std::vector<const MeshData*> tiles) : tiles_(std::move(tiles)) {}
  size_t tileCount() const override { return tiles_.size(); }
  bool readTile(size_t i, MeshData& out, std::string& error) override;

 private:
  std::vector<const MeshData*> tiles_;
};

}  // namespace hs::mesh
