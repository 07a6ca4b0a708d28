#pragma once
// The memory cap on terrain undo (DESIGN.md: undo of a stroke stores only
// the tiles it touched; the issue: undo memory has a cap, oldest steps
// dropped first, and the editor shows how much it uses).
//
// Terrain commands on the document's QUndoStack register here with the
// bytes their UndoStep holds. When the total passes the cap, the oldest
// commands free their tiles and become obsolete (QUndoCommand::setObsolete):
// QUndoStack then removes such a command when undo or redo reaches it
// without calling it, which is correct because every older terrain step has
// been dropped too, so nothing can need the tiles it held. Commands that
// leave the stack (cleared, or a redo branch replaced) unregister themselves.
#include <cstddef>
#include <list>

namespace hs::scene {

class TerrainUndoEntry {
 public:
  virtual ~TerrainUndoEntry() = default;
  virtual size_t undoBytes() const = 0;
  // Applied (on the undo side of the stack). Only those may be dropped: a
  // dropped step on the redo side would leave the newer steps after it
  // redoing from the wrong tiles.
  virtual bool isApplied() const = 0;
  // Frees the tiles and makes the command obsolete.
  virtual void dropUndo() = 0;
};

class TerrainUndoBudget {
 public:
  static constexpr size_t kDefaultCap = size_t(512) << 20;

  size_t cap() const { return cap_; }
  // Lowers or raises the cap; drops oldest steps to fit. Returns how many.
  size_t setCap(size_t bytes);
  size_t bytesUsed() const { return bytes_; }
  size_t steps() const { return live_.size(); }
  size_t droppedTotal() const { return dropped_; }

  // For TerrainCommand.
  void add(TerrainUndoEntry* e);
  void remove(TerrainUndoEntry* e);
  // Drops the oldest applied steps (never `keep`) until the total fits the cap.
  size_t enforce(const TerrainUndoEntry* keep = nullptr);

 private:
  size_t cap_ = kDefaultCap;
  size_t bytes_ = 0;
  size_t dropped_ = 0;
  std::list<TerrainUndoEntry*> live_;  // oldest first
};

}  // namespace hs::scene
