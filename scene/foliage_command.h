#pragma once
// Foliage edits on the document's QUndoStack. A tool (paint, erase, fill,
// scatter, a selection's move, delete or reapply: foliage/tools.h) changes
// the store in place and returns a foliage::FoliageUndo holding the cells
// it touched as they were; the command swaps them with the store's on undo
// and again on redo (bitwise exact, O(touched cells)). A change to the
// types list keeps the list before and after beside the cells (a changed
// scale mode re-encodes records). The edit is already applied when the
// command is pushed, so its first redo does nothing.
#include <optional>
#include <string>
#include <vector>

#include <QString>
#include <QUndoCommand>

#include "foliage/store.h"
#include "scene/document.h"

namespace hs::scene {

class FoliageCommand : public QUndoCommand {
 public:
  FoliageCommand(Document& doc, foliage::FoliageUndo cells, const QString& text,
                 std::optional<std::vector<foliage::FoliageType>> typesBefore = std::nullopt);
  void redo() override;
  void undo() override;

 private:
  void swap();
  Document& doc_;
  std::shared_ptr<FoliageData> data_;  // the store the edit changed
  foliage::FoliageUndo cells_;
  std::optional<std::vector<foliage::FoliageType>> types_;  // the other side's list
  bool applied_ = true;
};

// Records an edit already applied to the document's foliage; `cells` holds
// the befores. Nothing is pushed for an empty edit (false). Views are told.
bool pushFoliageEdit(Document& doc, foliage::FoliageUndo cells, const QString& text);

// Records a change to the types list already made (FoliageStore::addType,
// setType) as one undo step: `typesBefore` is the list before it, `cells`
// what re-encoding a changed type's scale mode touched. False (nothing
// pushed) when nothing changed.
bool pushFoliageTypes(Document& doc, std::vector<foliage::FoliageType> typesBefore, foliage::FoliageUndo cells,
                      const QString& text);

}  // namespace hs::scene
