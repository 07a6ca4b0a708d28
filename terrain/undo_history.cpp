#include "terrain/undo_history.h"

namespace hs::terrain {

UndoPushResult UndoHistory::push(UndoStep step) {
  UndoPushResult r;
  for (auto& s : redo_) bytes_ -= s.bytes();
  redo_.clear();
  if (step.empty()) return r;
  const size_t b = step.bytes();
  if (b > cap_) {
    // Keeping it would need every other step gone and still exceed the cap.
    r.kept = false;
    ++droppedTotal_;
    return r;
  }
  bytes_ += b;
  undo_.push_back(std::move(step));
  r.droppedSteps = trim();
  return r;
}

size_t UndoHistory::trim() {
  size_t dropped = 0;
  while (bytes_ > cap_ && !undo_.empty()) {
    bytes_ -= undo_.front().bytes();
    undo_.pop_front();
    ++dropped;
  }
  while (bytes_ > cap_ && !redo_.empty()) {
    bytes_ -= redo_.front().bytes();
    redo_.pop_front();
    ++dropped;
  }
  droppedTotal_ += dropped;
  return dropped;
}

Region UndoHistory::undo(Terrain& terrain) {
  if (undo_.empty()) return {};
  UndoStep s = std::move(undo_.back());
  undo_.pop_back();
  // A swap can change a step's size (a paint tile that was unallocated
  // before the edit holds data after it), so account before and after.
  bytes_ -= s.bytes();
  const Region r = s.swap(terrain);
  bytes_ += s.bytes();
  redo_.push_back(std::move(s));
  trim();
  return r;
}

Region UndoHistory::redo(Terrain& terrain) {
  if (redo_.empty()) return {};
  UndoStep s = std::move(redo_.back());
  redo_.pop_back();
  bytes_ -= s.bytes();
  const Region r = s.swap(terrain);
  bytes_ += s.bytes();
  undo_.push_back(std::move(s));
  trim();
  return r;
}

void UndoHistory::clear() {
  undo_.clear();
  redo_.clear();
  bytes_ = 0;
}

size_t UndoHistory::setCap(size_t capBytes) {
  cap_ = capBytes;
  return trim();
}

}  // namespace hs::terrain
