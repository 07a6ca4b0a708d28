#pragma once
// Undo/redo of terrain edits with a memory cap. Steps are UndoSteps (only the
// touched tiles); when the total exceeds the cap the oldest steps are dropped
// first, and a single step larger than the cap is applied but not kept (the
// caller is told, so the editor can say "this stroke cannot be undone").
//
// Phase 2: the scene's QUndoStack can hold one command per terrain edit whose
// undo()/redo() call UndoHistory::undo()/redo() on the terrain's history; the
// editor shows bytesUsed() / cap().
#include <cstddef>
#include <deque>

#include "terrain/undo_step.h"

namespace hs::terrain {

struct UndoPushResult {
  bool kept = true;          // false: the step alone exceeds the cap
  size_t droppedSteps = 0;   // oldest steps dropped to make room
};

class UndoHistory {
 public:
  explicit UndoHistory(size_t capBytes = size_t(512) << 20) : cap_(capBytes) {}

  // Adds a finished edit (already applied to the terrain); clears redo.
  UndoPushResult push(UndoStep step);
  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  // Return the region that changed (empty if there was nothing to do).
  Region undo(Terrain& terrain);
  Region redo(Terrain& terrain);
  void clear();

  size_t undoSteps() const { return undo_.size(); }
  size_t redoSteps() const { return redo_.size(); }
  size_t bytesUsed() const { return bytes_; }
  size_t cap() const { return cap_; }
  // Lowers or raises the cap; drops oldest undo steps (then redo steps) to fit.
  size_t setCap(size_t capBytes);
  size_t droppedTotal() const { return droppedTotal_; }
  const UndoStep* nextUndo() const { return undo_.empty() ? nullptr : &undo_.back(); }

 private:
  size_t trim();
  size_t cap_;
  size_t bytes_ = 0;
  size_t droppedTotal_ = 0;
  std::deque<UndoStep> undo_;  // front = oldest
  std::deque<UndoStep> redo_;  // back = next to redo
};

}  // namespace hs::terrain
