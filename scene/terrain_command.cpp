#include "scene/terrain_command.h"

#include "scene/terrain_edits.h"

namespace hs::scene {

TerrainCommand::TerrainCommand(Document& doc, TerrainId id, std::shared_ptr<TerrainData> data,
                               terrain::UndoStep step, const QString& text, foliage::FoliageUndo foliage)
    : QUndoCommand(text),
      doc_(doc),
      id_(id),
      data_(std::move(data)),
      step_(std::move(step)),
      foliageData_(foliage.empty() ? nullptr : doc.state().foliage),
      foliage_(std::move(foliage)),
      bytes_(step_.bytes() + foliage_.bytes()) {
  doc_.terrainUndo().add(this);
  registered_ = true;
}

TerrainCommand::~TerrainCommand() {
  if (registered_) doc_.terrainUndo().remove(this);
}

void TerrainCommand::swap() {
  const uint8_t kinds = changeKindsOf(step_);
  const terrain::Region r = step_.swap(data_->terrain());
  noteTerrainChange(doc_, id_, *data_, r, kinds);
  if (foliageData_) {
    foliage_.swap(foliageData_->store());
    doc_.notifyFoliageChanged();
  }
}

void TerrainCommand::redo() {
  if (applied_) return;  // first push: the edit is already in the tiles
  swap();
  applied_ = true;
}

void TerrainCommand::undo() {
  if (!applied_) return;
  swap();
  applied_ = false;
}

void TerrainCommand::dropUndo() {
  // The budget already took this command off its list.
  registered_ = false;
  step_ = terrain::UndoStep{};
  foliage_ = foliage::FoliageUndo{};
  foliageData_.reset();
  bytes_ = 0;
  setText(text() + " (undo memory freed)");
  setObsolete(true);
}

}  // namespace hs::scene
