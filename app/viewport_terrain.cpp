// ViewportWidget's terrain brush handling: mouse positions become world rays
// for the TerrainTool (terrain_tool.h), which does the picking and strokes.
#include "app/terrain_tool.h"
#include "app/viewport_widget.h"

namespace hs::app {

bool ViewportWidget::terrainPress(const QPointF& pos) {
  if (!terrainTool_ || !terrainTool_->active()) return false;
  glm::dvec3 origin, direction;
  const glm::dvec2 px = toPixel(pos);
  camera_.view().pixelRay(px.x, px.y, origin, direction);
  if (!terrainTool_->begin(origin, direction)) return false;
  drag_ = Drag::Terrain;
  update();
  return true;
}

void ViewportWidget::terrainMove(const QPointF& pos) {
  if (!terrainTool_ || !terrainTool_->active()) return;
  glm::dvec3 origin, direction;
  const glm::dvec2 px = toPixel(pos);
  camera_.view().pixelRay(px.x, px.y, origin, direction);
  if (drag_ == Drag::Terrain) {
    terrainTool_->drag(origin, direction);
    update();
  } else if (terrainTool_->hover(origin, direction)) {
    update();
  }
}

void ViewportWidget::terrainEnd() {
  if (terrainTool_) terrainTool_->end();
  drag_ = Drag::None;
  update();
}

}  // namespace hs::app
