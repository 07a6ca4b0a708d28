#pragma once
// One terrain tile edit on the document's QUndoStack: a stroke, an erosion
// run, a paint-rule run, a DEM import into an existing terrain. It holds the
// edit's terrain::UndoStep (the before-copies of exactly the touched tiles);
// undo and redo both swap them with the terrain's (UndoStep::swap: O(tiles),
// bitwise exact). The edit is already applied when the command is pushed,
// so its first redo does nothing. Its memory counts against the document's
// TerrainUndoBudget, which may drop it (oldest first).
//
// Foliage standing on the terrain follows its ground (foliage/
// ground_follow.h): the instances the edit moved or removed are part of the
// same step (their cells' befores, swapped with the store's alongside).
#include <memory>

#include <QUndoCommand>

#include "foliage/store.h"
#include "scene/document.h"
#include "terrain/undo_step.h"

namespace hs::scene {

class TerrainCommand : public QUndoCommand, public TerrainUndoEntry {
 public:
  TerrainCommand(Document& doc, TerrainId id, std::shared_ptr<TerrainData> data, terrain::UndoStep step,
                 const QString& text, foliage::FoliageUndo foliage = {});
  ~TerrainCommand() override;

  void redo() override;
  void undo() override;

  size_t undoBytes() const override { return bytes_; }
  bool isApplied() const override { return applied_; }
  void dropUndo() override;
  TerrainId terrain() const { return id_; }

 private:
  void swap();
  Document& doc_;
  TerrainId id_;
  std::shared_ptr<TerrainData> data_;  // keeps the tiles alive if the terrain is deleted meanwhile
  terrain::UndoStep step_;
  std::shared_ptr<FoliageData> foliageData_;  // the store `foliage_` belongs to
  foliage::FoliageUndo foliage_;
  size_t bytes_;
  bool applied_ = true;  // the edit was made before the push
  bool registered_ = false;
};

}  // namespace hs::scene
