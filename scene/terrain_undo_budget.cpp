#include "scene/terrain_undo_budget.h"

#include <algorithm>

namespace hs::scene {

size_t TerrainUndoBudget::setCap(size_t bytes) {
  cap_ = bytes;
  return enforce();
}

void TerrainUndoBudget::add(TerrainUndoEntry* e) {
  live_.push_back(e);
  bytes_ += e->undoBytes();
}

void TerrainUndoBudget::remove(TerrainUndoEntry* e) {
  auto it = std::find(live_.begin(), live_.end(), e);
  if (it == live_.end()) return;
  bytes_ -= std::min(bytes_, e->undoBytes());
  live_.erase(it);
}

size_t TerrainUndoBudget::enforce(const TerrainUndoEntry* keep) {
  size_t n = 0;
  while (bytes_ > cap_ && !live_.empty()) {
    TerrainUndoEntry* oldest = live_.front();
    if (oldest == keep || !oldest->isApplied()) break;
    live_.pop_front();
    bytes_ -= std::min(bytes_, oldest->undoBytes());
    oldest->dropUndo();
    ++dropped_;
    ++n;
  }
  return n;
}

}  // namespace hs::scene
