#include "scene/terrain_edits.h"

#include "scene/terrain_command.h"

namespace hs::scene {

uint8_t changeKindsOf(const terrain::UndoStep& step) {
  return uint8_t((step.touchesHeights() ? kTerrainHeights : 0) | (step.touchesHoles() ? kTerrainHoles : 0) |
                 (step.touchesPaint() ? kTerrainPaint : 0));
}

uint8_t changeKindsOf(terrain::BrushTool tool) {
  switch (tool) {
    case terrain::BrushTool::Paint: return kTerrainPaint;
    case terrain::BrushTool::Holes: return kTerrainHoles;
    default: return kTerrainHeights;
  }
}

void noteTerrainChange(Document& doc, TerrainId id, TerrainData& data, const terrain::Region& region, uint8_t kinds) {
  if (region.empty()) return;
  data.noteChanged(region, kinds);
  doc.notifyTerrainChanged(id);
}

TerrainPushResult pushTerrainStep(Document& doc, TerrainId id, terrain::UndoStep step, const QString& text) {
  TerrainPushResult r;
  if (step.empty()) return r;
  const TerrainAsset* t = doc.state().findTerrain(id);
  std::shared_ptr<TerrainData> data = t ? t->data : nullptr;
  if (!data) return r;
  TerrainUndoBudget& budget = doc.terrainUndo();
  if (step.bytes() > budget.cap()) {
    // Kept applied, not undoable: the document is modified for good (its
    // saved state can no longer be reached by undo).
    r.kept = false;
    doc.undoStack()->resetClean();
    return r;
  }
  auto* cmd = new TerrainCommand(doc, id, std::move(data), std::move(step), text);
  doc.undoStack()->push(cmd);
  r.pushed = true;
  r.dropped = budget.enforce(cmd);
  return r;
}

}  // namespace hs::scene
