#pragma once
// The tiles of one terrain in the document: a hs::terrain::Terrain (heights,
// holes, paint weights in 128^2 tiles) that edits change in place.
//
// Why not a value like everything else in SceneState: an 8k terrain is
// hundreds of megabytes, and a ScenePatch holds whole before/after values.
// So the document refers to the tiles through a shared pointer (copies of
// SceneState and of TerrainAsset share them), and tile edits are undone by
// hs::terrain::UndoStep swaps inside a TerrainCommand (terrain_command.h).
//
// Threads: the tiles are written on one thread (the editor's UI thread, or
// the CLI's only one). Other threads work on snapshot(): the tiles are
// copy-on-write (terrain/tile_grid.h), so a snapshot costs O(tiles) and later
// edits never touch what it holds (saves and erosion jobs run on one).
//
// Views learn what changed from a change log: each edit notes its region and
// kind; a renderer remembers the serial it has seen and uploads only what
// came after (or everything, once the log no longer reaches back).
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "terrain/terrain.h"
#include "terrain/tile_blob.h"

namespace hs::scene {

// What an edit changed, for uploads.
enum TerrainChangeKind : uint8_t {
  kTerrainHeights = 1,
  kTerrainHoles = 2,
  kTerrainPaint = 4,
  kTerrainAll = 7,
};

struct TerrainChange {
  uint64_t serial = 0;
  hs::terrain::Region region;
  uint8_t kinds = kTerrainAll;
};

// Content hashes of tiles, remembered by (tile, revision) so an unchanged
// tile is hashed once. Shared between a terrain and its snapshots (a
// revision names the same content in both: snapshots never write).
class TileHashCache {
 public:
  // Hash of the tile's samples (hs::terrain::tileContentHash). A sparse tile
  // (holes, paint: `fill` given, `sampleBytes` wide) that is unallocated or
  // holds only the fill value hashes to 0: it is not saved, and a file
  // round trip (which leaves it unallocated) keeps the document's hash.
  uint64_t get(hs::terrain::TileKind kind, int layer, int tile, uint64_t revision, const void* data, size_t bytes,
               const void* fill = nullptr, size_t sampleBytes = 0);
  // The same rule with another hash function and no caching (checking the
  // tiles of files before format 4, scene/legacy_hashes.h).
  using HashFunction = uint64_t (*)(hs::terrain::TileKind kind, int layer, int tile, const void* data, size_t bytes);
  static uint64_t compute(HashFunction hash, hs::terrain::TileKind kind, int layer, int tile, const void* data,
                          size_t bytes, const void* fill = nullptr, size_t sampleBytes = 0);
  // Records a hash already known (the file's, checked at load).
  void put(hs::terrain::TileKind kind, int layer, int tile, uint64_t revision, uint64_t hash);

 private:
  struct Entry {
    uint64_t revision = ~uint64_t(0);
    uint64_t hash = 0;
  };
  std::vector<Entry>& entriesFor(hs::terrain::TileKind kind, int layer, int tile);
  std::mutex mutex_;
  std::vector<std::vector<Entry>> grids_;  // [0] heights, [1] holes, [2 + layer] paint
};

class TerrainData {
 public:
  explicit TerrainData(hs::terrain::Terrain t);
  TerrainData(const TerrainData&) = delete;
  TerrainData& operator=(const TerrainData&) = delete;

  hs::terrain::Terrain& terrain() { return terrain_; }
  const hs::terrain::Terrain& terrain() const { return terrain_; }
  const hs::terrain::Heightfield& heights() const { return terrain_.height; }

  // Unique per object for the process's life (renderer caches key on it).
  uint64_t instance() const { return instance_; }

  // --- change log (owning thread only) -------------------------------------
  uint64_t serial() const { return serial_; }
  void noteChanged(const hs::terrain::Region& region, uint8_t kinds);
  // Changes after `since`, oldest first. False if the log no longer reaches
  // back that far (the caller refreshes everything).
  bool changesSince(uint64_t since, std::vector<TerrainChange>& out) const;

  // --- snapshots and hashes -------------------------------------------------
  // A frozen copy sharing tiles (copy-on-write) and the hash cache.
  std::shared_ptr<TerrainData> snapshot() const;
  TileHashCache& hashCache() const { return *hashes_; }
  // Hash of one tile's current content (0 for an unallocated sparse tile);
  // with `legacy`, by that function instead of the current one, uncached.
  uint64_t tileHash(hs::terrain::TileKind kind, int layer, int tile,
                    TileHashCache::HashFunction legacy = nullptr) const;
  // All tile hashes combined in order: the terrain's content, in one number.
  uint64_t contentHash(TileHashCache::HashFunction legacy = nullptr) const;

  // What a scene description says the tiles hold (terrain_json.h), kept
  // from sceneFromJson until the file loader has read and checked the
  // tiles; the description of such a terrain repeats it (as a mesh asset
  // without its data keeps its hash). Any edit drops it.
  struct DescribedTiles {
    uint64_t contentHash = 0;
    std::string holes;                // presence bitmap (base64)
    std::vector<std::string> paint;   // per layer
  };
  const std::optional<DescribedTiles>& described() const { return described_; }
  void setDescribed(std::optional<DescribedTiles> d) { described_ = std::move(d); }

  // A long operation (erosion, paint rules, DEM import) is running on a
  // snapshot of this terrain: the editor does not start brush strokes.
  std::atomic<bool> jobRunning{false};

 private:
  hs::terrain::Terrain terrain_;
  uint64_t instance_;
  uint64_t serial_ = 0;
  std::deque<TerrainChange> log_;
  std::optional<DescribedTiles> described_;
  std::shared_ptr<TileHashCache> hashes_;
};

}  // namespace hs::scene
