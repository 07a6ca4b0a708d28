// ViewportWidget's foliage brush handling: mouse positions become world rays
// for the FoliageTool (foliage_tool.h), which picks the ground, runs the
// stroke and records it.
#include "app/foliage_tool.h"
#include "app/viewport_widget.h"

#include <cmath>

namespace hs::app {

bool ViewportWidget::foliagePress(const QPointF& pos, Qt::KeyboardModifiers modifiers) {
  if (!foliageTool_ || !foliageTool_->active()) return false;
  glm::dvec3 origin, direction;
  const glm::dvec2 px = toPixel(pos);
  camera_.view().pixelRay(px.x, px.y, origin, direction);
  // Select: the instance drawn under the cursor, from the renderer's id
  // pass (foliage instances carry no entity, only their id).
  std::optional<uint32_t> drawn;
  if (foliageTool_->kind() == FoliageToolKind::Select && renderer_.initialized()) {
    makeCurrent();
    const render::PickHit hit = renderer_.pickSurface(displayedState(), camera_.view(), int(std::floor(px.x)),
                                                      int(std::floor(px.y)));
    doneCurrent();
    if (hit.entity == scene::kNoEntity && hit.instance != UINT32_MAX) drawn = hit.instance;
  }
  if (!foliageTool_->begin(origin, direction, modifiers & Qt::ShiftModifier, drawn)) return false;
  // A press the tool refused (no type to paint) is handled without a stroke.
  drag_ = foliageTool_->stroking() ? Drag::Foliage : Drag::None;
  update();
  return true;
}

void ViewportWidget::foliageMove(const QPointF& pos) {
  if (!foliageTool_ || !foliageTool_->active()) return;
  glm::dvec3 origin, direction;
  const glm::dvec2 px = toPixel(pos);
  camera_.view().pixelRay(px.x, px.y, origin, direction);
  if (drag_ == Drag::Foliage) {
    foliageTool_->drag(origin, direction);
    update();
  } else if (foliageTool_->hover(origin, direction)) {
    update();
  }
}

void ViewportWidget::foliageEnd() {
  if (foliageTool_) foliageTool_->end();
  drag_ = Drag::None;
  update();
}

}  // namespace hs::app
