#pragma once
// Recording terrain tile edits in the document: the one place that turns a
// finished edit (its terrain::UndoStep) into an undo step, tells views what
// changed, and applies the undo memory cap. The editor's brush strokes and
// jobs and the CLI's commands all end here.
#include <QString>

#include "scene/document.h"
#include "terrain/brush.h"
#include "terrain/undo_step.h"

namespace hs::scene {

struct TerrainPushResult {
  bool pushed = false;      // an undo step was added
  bool kept = true;         // false: the edit alone exceeds the undo cap; it stays applied but cannot be undone
  size_t dropped = 0;       // oldest terrain steps dropped to make room
};

// Records an edit already applied to terrain `id`'s tiles; `step` holds the
// befores. An empty step records nothing.
TerrainPushResult pushTerrainStep(Document& doc, TerrainId id, terrain::UndoStep step, const QString& text);

// Notes a tile change on the data's change log (renderers upload it) and
// tells the document's views (they repaint).
void noteTerrainChange(Document& doc, TerrainId id, TerrainData& data, const terrain::Region& region, uint8_t kinds);

// Which tiles an edit touched (TerrainChangeKind bits).
uint8_t changeKindsOf(const terrain::UndoStep& step);
uint8_t changeKindsOf(terrain::BrushTool tool);

}  // namespace hs::scene
