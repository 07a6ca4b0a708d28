#pragma once
// One undo step of a terrain edit: the "before" copies of exactly the tiles
// the edit touched (heights, holes, paint weights). Undo and redo are the
// same operation, a swap of tile storage between the step and the terrain:
// O(tiles) pointer swaps, bitwise exact, and the step's memory stays the same
// whether it holds the befores (undoable) or the afters (redoable).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "terrain/region.h"
#include "terrain/terrain.h"

namespace hs::terrain {

class UndoStep {
 public:
  UndoStep() = default;
  UndoStep(UndoStep&&) noexcept = default;
  UndoStep& operator=(UndoStep&&) noexcept = default;

  bool empty() const { return heights_.empty() && holes_.empty() && paint_.empty(); }
  size_t bytes() const;
  size_t tileCount() const { return heights_.size() + holes_.size() + paint_.size(); }
  // Samples covered by the stored tiles (what a renderer re-uploads after swap()).
  Region region() const { return region_; }
  const std::string& label() const { return label_; }
  void setLabel(std::string l) { label_ = std::move(l); }
  // Tile indices of the stored height tiles (what the scene file re-saves).
  std::vector<int> heightTiles() const;
  // Which kinds of tiles the edit touched (what a renderer re-uploads).
  bool touchesHeights() const { return !heights_.empty(); }
  bool touchesHoles() const { return !holes_.empty(); }
  bool touchesPaint() const { return !paint_.empty(); }

  // Edits that run on a worker thread work on a copy-on-write clone of the
  // live terrain (Terrain::clone() shares tiles). Then, on the thread that
  // owns the live terrain:
  //  - unchangedSince(live, base): none of the step's tiles was written in
  //    `live` since `base` (the clone's starting point, kept alive meanwhile)
  //    was taken, so the result still applies;
  //  - adopt(live, result): moves the step's tiles from `result` (the edited
  //    clone) into `live`, which then shows the edit, and this step (holding
  //    the befores) undoes it there. Returns the changed region.
  bool unchangedSince(const Terrain& live, const Terrain& base) const;
  Region adopt(Terrain& live, const Terrain& result) const;

  // Exchanges the stored tiles with the terrain's: the first call undoes the
  // edit, the second redoes it, and so on. Refreshes tile bounds; returns the
  // region that changed.
  Region swap(Terrain& terrain);

 private:
  friend class UndoRecorder;
  struct HeightTile { int tile; TileGrid<float>::TilePtr data; };
  struct HoleTile { int tile; TileGrid<uint8_t>::TilePtr data; };
  struct PaintTile { int layer; int tile; TileGrid<uint16_t>::TilePtr data; };
  std::vector<HeightTile> heights_;
  std::vector<HoleTile> holes_;
  std::vector<PaintTile> paint_;
  Region region_;
  std::string label_;
};

// Collects before-copies while an edit runs: call record*() for a region
// before writing to it; each tile is copied once, the first time.
class UndoRecorder {
 public:
  explicit UndoRecorder(Terrain& terrain);
  void recordHeights(const Region& r);
  void recordHoles(const Region& r);
  void recordPaint(const Region& r);  // every layer: a blend changes them all
  // The before-copy of height tile t if recorded, else nullptr.
  const float* heightsBefore(int t) const;
  size_t bytes() const { return bytes_; }
  Terrain& terrain() { return *terrain_; }
  UndoStep finish(std::string label);

 private:
  Terrain* terrain_;
  UndoStep step_;
  std::vector<int32_t> heightSlot_;          // per tile: index into step_.heights_ or -1
  std::vector<uint8_t> holeSeen_;
  std::vector<std::vector<uint8_t>> paintSeen_;  // per layer, per tile
  size_t bytes_ = 0;
};

}  // namespace hs::terrain
