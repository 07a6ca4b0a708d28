// ViewportWidget's camera-path side: mouse and keys for the path points
// (PathPointDrag picks and drags them; PathEditor edits the document), and
// their overlay. Kept apart from viewport_widget.cpp, which handles the view.
#include <QKeyEvent>

#include "app/path_editor.h"
#include "app/path_point_drag.h"
#include "app/viewport_widget.h"

namespace hs::app {

void ViewportWidget::setPathEditor(PathEditor* editor) {
  delete pathDrag_;
  pathDrag_ = editor ? new PathPointDrag(*editor, this) : nullptr;
  if (editor) connect(editor, &PathEditor::changed, this, qOverload<>(&ViewportWidget::update));
  update();
}

bool ViewportWidget::pathOwnsGizmo() const { return pathDrag_ && pathDrag_->showsHandles(); }

bool ViewportWidget::pathPress(const QPointF& pos) {
  if (!pathDrag_ || !pathDrag_->begin(camera_.view(), toPixel(pos), gizmo_.snap())) return false;
  drag_ = Drag::PathPoint;
  update();
  return true;
}

void ViewportWidget::pathMove(const QPointF& pos, Qt::KeyboardModifiers modifiers) {
  if (!pathDrag_) return;
  if (drag_ == Drag::PathPoint) pathDrag_->drag(camera_.view(), toPixel(pos), modifiers & Qt::ControlModifier);
  else if (drag_ == Drag::None && pathDrag_->hover(camera_.view(), toPixel(pos))) update();
}

void ViewportWidget::pathEnd() {
  if (pathDrag_) pathDrag_->end();
}

bool ViewportWidget::pathKey(QKeyEvent* e, bool shortcutOverride) {
  if (!pathDrag_) return false;
  const int key = e->key();
  if (drag_ == Drag::PathPoint && key == Qt::Key_Escape) {
    if (shortcutOverride) return true;
    pathDrag_->cancel();
    drag_ = Drag::None;
    update();
    return true;
  }
  // With a point selected, Delete removes the point (not the camera, as the
  // window's Delete would) and Esc lets go of the point: as in Blender's
  // curve edit mode.
  const bool forPoint = drag_ == Drag::None && pathDrag_->showsHandles() && e->modifiers() == Qt::NoModifier &&
                        (key == Qt::Key_Delete || key == Qt::Key_Backspace || key == Qt::Key_Escape);
  if (!forPoint || shortcutOverride) return forPoint;
  PathEditor& editor = pathDrag_->editor();
  if (key == Qt::Key_Escape) editor.selectPoint(-1);
  else editor.deleteSelectedPoint();
  update();
  return true;
}

void ViewportWidget::drawPathOverlay(const scene::SceneState& state, const render::RenderView& view,
                                     render::Overlay& overlay) {
  if (pathDrag_) pathDrag_->draw(state.settings, view, overlay);
}

}  // namespace hs::app
