#include "scene/foliage_command.h"

namespace hs::scene {

FoliageCommand::FoliageCommand(Document& doc, foliage::FoliageUndo cells, const QString& text,
                               std::optional<std::vector<foliage::FoliageType>> typesBefore)
    : QUndoCommand(text), doc_(doc), cells_(std::move(cells)), types_(std::move(typesBefore)) {
  data_ = doc_.state().foliage;
}

void FoliageCommand::swap() {
  if (!data_) return;
  foliage::FoliageStore& store = data_->store();
  cells_.swap(store);
  if (types_) {
    std::vector<foliage::FoliageType> current = store.types();
    store.setTypes(std::move(*types_));
    types_ = std::move(current);
  }
  doc_.notifyFoliageChanged();
}

void FoliageCommand::redo() {
  if (applied_) return;  // first push: the edit is already in the store
  swap();
  applied_ = true;
}

void FoliageCommand::undo() {
  if (!applied_) return;
  swap();
  applied_ = false;
}

bool pushFoliageEdit(Document& doc, foliage::FoliageUndo cells, const QString& text) {
  if (cells.empty()) return false;
  doc.undoStack()->push(new FoliageCommand(doc, std::move(cells), text));
  doc.notifyFoliageChanged();
  return true;
}

bool pushFoliageTypes(Document& doc, std::vector<foliage::FoliageType> typesBefore, foliage::FoliageUndo cells,
                      const QString& text) {
  if (typesBefore == doc.foliage().store().types() && cells.empty()) return false;
  doc.undoStack()->push(new FoliageCommand(doc, std::move(cells), text, std::move(typesBefore)));
  doc.notifyFoliageChanged();
  return true;
}

}  // namespace hs::scene
