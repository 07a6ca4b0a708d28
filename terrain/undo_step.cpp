#include "terrain/undo_step.h"

namespace hs::terrain {

size_t UndoStep::bytes() const {
  size_t b = sizeof(UndoStep) + label_.capacity();
  for (const auto& t : heights_) b += sizeof(t) + (t.data ? TileGrid<float>::tileBytes() : 0);
  for (const auto& t : holes_) b += sizeof(t) + (t.data ? TileGrid<uint8_t>::tileBytes() : 0);
  for (const auto& t : paint_) b += sizeof(t) + (t.data ? TileGrid<uint16_t>::tileBytes() : 0);
  return b;
}

std::vector<int> UndoStep::heightTiles() const {
  std::vector<int> out;
  for (const auto& t : heights_) out.push_back(t.tile);
  return out;
}

Region UndoStep::swap(Terrain& terrain) {
  auto& hg = terrain.height.heights();
  for (auto& t : heights_) hg.swapTile(t.tile, t.data);
  for (auto& t : holes_) terrain.height.holes().swapTile(t.tile, t.data);
  for (auto& t : paint_)
    if (t.layer < terrain.paint.layerCount()) terrain.paint.grid(t.layer).swapTile(t.tile, t.data);
  if (!heights_.empty()) terrain.height.updateBounds(region_);
  return region_;
}

bool UndoStep::unchangedSince(const Terrain& live, const Terrain& base) const {
  // A write to a tile shared with `base` copies it, and a swap exchanges it:
  // either way the live tile is no longer the pointer `base` holds.
  for (const auto& t : heights_)
    if (live.height.heights().sharedTile(t.tile) != base.height.heights().sharedTile(t.tile)) return false;
  for (const auto& t : holes_)
    if (live.height.holes().sharedTile(t.tile) != base.height.holes().sharedTile(t.tile)) return false;
  for (const auto& t : paint_) {
    if (t.layer >= live.paint.layerCount() || t.layer >= base.paint.layerCount()) return false;
    if (live.paint.grid(t.layer).sharedTile(t.tile) != base.paint.grid(t.layer).sharedTile(t.tile)) return false;
  }
  return true;
}

Region UndoStep::adopt(Terrain& live, const Terrain& result) const {
  for (const auto& t : heights_) live.height.heights().setTile(t.tile, result.height.heights().sharedTile(t.tile));
  for (const auto& t : holes_) live.height.holes().setTile(t.tile, result.height.holes().sharedTile(t.tile));
  for (const auto& t : paint_)
    if (t.layer < live.paint.layerCount() && t.layer < result.paint.layerCount())
      live.paint.grid(t.layer).setTile(t.tile, result.paint.grid(t.layer).sharedTile(t.tile));
  if (!heights_.empty()) live.height.updateBounds(region_);
  return region_;
}

UndoRecorder::UndoRecorder(Terrain& terrain) : terrain_(&terrain) {
  const size_t tiles = size_t(terrain.height.heights().tileCount());
  heightSlot_.assign(tiles, -1);
  holeSeen_.assign(tiles, 0);
  paintSeen_.assign(size_t(terrain.paint.layerCount()), std::vector<uint8_t>(tiles, 0));
}

void UndoRecorder::recordHeights(const Region& r) {
  const auto& g = terrain_->height.heights();
  g.forEachTile(r, [&](int t, const Region&) {
    if (heightSlot_[size_t(t)] >= 0) return;
    heightSlot_[size_t(t)] = int32_t(step_.heights_.size());
    step_.heights_.push_back({t, g.copyTile(t)});
    step_.region_ = step_.region_.united(g.tileRegion(t));
    bytes_ += TileGrid<float>::tileBytes();
  });
}

void UndoRecorder::recordHoles(const Region& r) {
  const auto& g = terrain_->height.holes();
  g.forEachTile(r, [&](int t, const Region&) {
    if (holeSeen_[size_t(t)]) return;
    holeSeen_[size_t(t)] = 1;
    step_.holes_.push_back({t, g.copyTile(t)});
    step_.region_ = step_.region_.united(g.tileRegion(t));
    bytes_ += g.allocated(t) ? TileGrid<uint8_t>::tileBytes() : 0;
  });
}

void UndoRecorder::recordPaint(const Region& r) {
  auto& paint = terrain_->paint;
  for (int l = 0; l < paint.layerCount() && l < int(paintSeen_.size()); ++l) {
    const auto& g = paint.grid(l);
    g.forEachTile(r, [&](int t, const Region&) {
      if (paintSeen_[size_t(l)][size_t(t)]) return;
      paintSeen_[size_t(l)][size_t(t)] = 1;
      step_.paint_.push_back({l, t, g.copyTile(t)});
      step_.region_ = step_.region_.united(g.tileRegion(t));
      bytes_ += g.allocated(t) ? TileGrid<uint16_t>::tileBytes() : 0;
    });
  }
}

const float* UndoRecorder::heightsBefore(int t) const {
  const int32_t s = heightSlot_[size_t(t)];
  return s < 0 ? nullptr : step_.heights_[size_t(s)].data.get();
}

UndoStep UndoRecorder::finish(std::string label) {
  step_.label_ = std::move(label);
  UndoStep out = std::move(step_);
  step_ = UndoStep{};
  std::fill(heightSlot_.begin(), heightSlot_.end(), -1);
  std::fill(holeSeen_.begin(), holeSeen_.end(), 0);
  for (auto& v : paintSeen_) std::fill(v.begin(), v.end(), 0);
  bytes_ = 0;
  return out;
}

}  // namespace hs::terrain
