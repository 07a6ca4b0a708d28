// Focus picking for depth of field (docs/rendering.md "Depth of field"):
// a click in the viewport sets the active camera's focus distance to the
// depth of the surface under the cursor, through the renderer's id pass
// (Renderer::pickSurface, which reads the depth the selection pick draws).
// The active camera is the selected camera, else the shot camera
// (StereoPreviewSettings::activeCamera): the picked point is measured
// along that camera's axis, so picking from the free view focuses the
// camera on what the user clicked, wherever the view is.
#include <glm/glm.hpp>

#include "app/stereo_preview.h"
#include "app/viewport_widget.h"
#include "render/stereo_views.h"
#include "scene/fields.h"
#include "scene/operations.h"

namespace hs::app {

void ViewportWidget::createFocusPickAction() {
  focusPickAction_ = new QAction("Pick &Focus Distance", this);
  focusPickAction_->setObjectName("pickFocusAction");
  focusPickAction_->setCheckable(true);
  focusPickAction_->setShortcut(QKeySequence(Qt::CTRL | Qt::ALT | Qt::Key_F));
  focusPickAction_->setStatusTip(
      "Click a surface in the viewport: the active camera focuses at its distance (depth of field)");
  connect(focusPickAction_, &QAction::toggled, this, &ViewportWidget::setFocusPicking);
}

void ViewportWidget::setFocusPicking(bool on) {
  focusPicking_ = on;
  if (focusPickAction_->isChecked() != on) focusPickAction_->setChecked(on);
  if (on) setCursor(Qt::CrossCursor);
  else unsetCursor();
}

bool ViewportWidget::pickFocus(const QPoint& pos) {
  const scene::SceneState& state = displayedState();
  const scene::EntityId camera = stereo_ ? stereo_->activeCamera(state, selection_) : render::shotCamera(state);
  const scene::Entity* e = state.find(camera);
  if (!e || !e->camera || !renderer_.initialized()) return false;
  const glm::dvec2 px = toPixel(QPointF(pos) + QPointF(0.5, 0.5));
  const render::RenderView& view = camera_.view();
  makeCurrent();
  const render::PickHit hit = renderer_.pickSurface(state, view, int(px.x), int(px.y));
  doneCurrent();
  if (hit.viewDepth <= 0.0) return false;  // the sky
  glm::dvec3 origin, dir;
  view.pixelRay(px.x, px.y, origin, dir);
  const glm::dvec3 point = origin + dir * (hit.viewDepth / glm::dot(dir, view.forward()));
  const render::RenderView cam = render::viewFromCamera(state, camera, 1, 1);
  const double focus = glm::dot(point - cam.eye, cam.forward());
  if (focus <= 0.0) return false;  // behind the camera
  const QString key = QString("focus-pick-%1").arg(++focusPicks_);
  if (!scene::ops::setField(doc_, camera, *scene::findEntityField("camera.focus_distance_m"), scene::FieldValue(focus), key))
    return false;
  emit focusPicked(camera, key);
  return true;
}

}  // namespace hs::app
