#include "scene/terrain_edits.h"

#include "foliage/ground_follow.h"
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

namespace {

// Moves the foliage standing on terrain `id` with its new ground (or
// removes it over new holes): the edit is in the tiles, `step` holds the
// befores. Returns the cells' befores (empty when no instance was there).
foliage::FoliageUndo followFoliage(Document& doc, TerrainId id, TerrainData& data, terrain::UndoStep& step) {
  const SceneState& state = doc.state();
  if (!state.foliage || state.foliage->store().cellCount() == 0) return {};
  if (!step.touchesHeights() && !step.touchesHoles()) return {};
  // Instances are in world coordinates: the heights go where the terrain's
  // entity puts them (copy-on-write clones: no samples copied).
  EntityId entity = kNoEntity;
  for (const auto& [eid, e] : state.entities)
    if (e.terrain && e.terrain->terrain == id) {
      entity = eid;
      break;
    }
  if (entity == kNoEntity) return {};
  const glm::dvec3 origin = terrainWorldOrigin(state, entity);
  terrain::Terrain after = data.terrain().clone();
  // The heights before: the step's tiles swapped into a clone, copied, and
  // swapped back (the step keeps its befores).
  terrain::Terrain scratch = data.terrain().clone();
  step.swap(scratch);
  terrain::Terrain before = scratch.clone();
  step.swap(scratch);
  after.height.setOrigin(origin);
  before.height.setOrigin(origin);
  foliage::FoliageUndo undo = foliage::followGround(doc.foliage().store(), before.height, after.height, step.region());
  if (!undo.empty()) doc.notifyFoliageChanged();
  return undo;
}

}  // namespace

TerrainPushResult pushTerrainStep(Document& doc, TerrainId id, terrain::UndoStep step, const QString& text) {
  TerrainPushResult r;
  if (step.empty()) return r;
  const TerrainAsset* t = doc.state().findTerrain(id);
  std::shared_ptr<TerrainData> data = t ? t->data : nullptr;
  if (!data) return r;
  foliage::FoliageUndo foliage = followFoliage(doc, id, *data, step);
  TerrainUndoBudget& budget = doc.terrainUndo();
  if (step.bytes() > budget.cap()) {
    // Kept applied, not undoable: the document is modified for good (its
    // saved state can no longer be reached by undo).
    r.kept = false;
    doc.undoStack()->resetClean();
    return r;
  }
  auto* cmd = new TerrainCommand(doc, id, std::move(data), std::move(step), text, std::move(foliage));
  doc.undoStack()->push(cmd);
  r.pushed = true;
  r.dropped = budget.enforce(cmd);
  return r;
}

}  // namespace hs::scene
