#pragma once
// Path points in the viewport: picking the drawn points (orange diamonds) of
// any camera path, and moving the selected point with the same move handles
// as entities (Gizmo in Translate mode, world axes, planes and a view-plane
// centre, with the same snapping), placed on a one-entity stand-in scene at
// the point. Pressing a point selects it (and its camera) and drags it in the
// view plane at once; its handles constrain the move to an axis or a plane.
// A drag is one undo step (scene::ops::movePathPoint with one merge key); Esc
// puts the point back and leaves no step.
#include <optional>

#include <QObject>

#include "app/gizmo.h"
#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/scene_state.h"

namespace hs::app {

class PathEditor;

class PathPointDrag : public QObject {
  Q_OBJECT
 public:
  static constexpr double kPickPixels = 9.0;

  PathPointDrag(PathEditor& editor, QObject* parent = nullptr);

  struct PointRef {
    scene::EntityId entity = scene::kNoEntity;
    int index = -1;
  };
  // The path point drawn nearest `pixel` within kPickPixels: the edited
  // path's points first, then every other path's.
  std::optional<PointRef> pointAt(const render::RenderView& view, const glm::dvec2& pixel) const;
  // Whether a point is selected: its handles then replace the entity gizmo.
  bool showsHandles() const;
  GizmoHandle handleAt(const render::RenderView& view, const glm::dvec2& pixel) const;
  // Hover highlight of the handles; true when it changed (repaint).
  bool hover(const render::RenderView& view, const glm::dvec2& pixel);

  // Press: on a handle of the selected point, or on any point (which is
  // selected, with its camera). False: not for the path tool.
  bool begin(const render::RenderView& view, const glm::dvec2& pixel, const SnapSettings& snap);
  bool dragging() const { return gizmo_.dragging(); }
  // `invertSnap`: Ctrl held, as for the entity gizmo.
  void drag(const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap);
  void cancel();
  void end();

  // The selected point, highlighted, with its handles.
  void draw(const scene::SceneSettings& settings, const render::RenderView& view, render::Overlay& out) const;

  Gizmo& gizmo() { return gizmo_; }
  PathEditor& editor() { return editor_; }

 private:
  // One entity (id 1) at `point`: what the gizmo measures and drags.
  scene::SceneState standIn(const glm::dvec3& point) const;
  std::optional<glm::dvec3> selectedPosition() const;

  PathEditor& editor_;
  Gizmo gizmo_;
  PointRef dragged_;
  glm::dvec3 start_{0.0};
};

}  // namespace hs::app
