#pragma once
// Move / rotate / scale handles. Drawn through render::Overlay at a constant
// size in screen pixels; handles are picked on the CPU against their screen
// projections (RenderView::project / pixelRay), so picking costs no GPU
// round trip. A drag always recomputes the transforms from the values at its
// start and pushes them with one merge key, so a whole drag is one undo step
// and never accumulates rounding.
#include <utility>
#include <vector>

#include <QString>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/document.h"

namespace hs::app {

enum class GizmoMode { Select, Translate, Rotate, Scale };
enum class GizmoSpace { World, Local };
enum class GizmoHandle { None, X, Y, Z, XY, YZ, ZX, View };

struct SnapSettings {
  bool enabled = false;
  double move = 1.0;        // metres
  double rotateDeg = 15.0;  // degrees
  double scale = 0.1;       // factor step
};

// Where the gizmo is and how big, for one view.
struct GizmoFrame {
  glm::dvec3 origin{0.0};
  glm::dmat3 axes{1.0};  // columns: the X, Y, Z handle directions (unit)
  double length = 1.0;   // world length of an axis handle
};

using TransformList = std::vector<std::pair<scene::EntityId, scene::Transform>>;

class Gizmo {
 public:
  static constexpr double kSizePixels = 110.0;
  static constexpr double kHitPixels = 9.0;

  GizmoMode mode() const { return mode_; }
  void setMode(GizmoMode m) { mode_ = m; }
  GizmoSpace space() const { return space_; }
  void setSpace(GizmoSpace s) { space_ = s; }
  SnapSettings& snap() { return snap_; }
  const SnapSettings& snap() const { return snap_; }
  GizmoHandle hover() const { return hover_; }
  void setHover(GizmoHandle h) { hover_ = h; }

  // False when there is nothing to show (no selection, Select mode, pivot
  // behind the camera).
  bool frame(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
             const render::RenderView& view, GizmoFrame& out) const;
  void draw(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
            const render::RenderView& view, render::Overlay& out) const;
  GizmoHandle hitTest(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                      const render::RenderView& view, const glm::dvec2& pixel) const;

  bool beginDrag(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                 const render::RenderView& view, GizmoHandle handle, const glm::dvec2& pixel);
  bool dragging() const { return drag_.active; }
  GizmoHandle activeHandle() const { return drag_.active ? drag_.handle : GizmoHandle::None; }
  // The transforms for the mouse at `pixel`; `invertSnap` (Ctrl held) flips
  // the snap toggle for this move.
  TransformList dragTransforms(const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap);
  // Computes and pushes them (scene::ops::setTransforms with this drag's key).
  bool dragTo(scene::Document& doc, const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap);
  // Puts everything back where the drag started (Esc); the drag's undo step
  // then holds no change and disappears.
  void cancelDrag(scene::Document& doc);
  void endDrag() { drag_ = {}; }
  QString undoText() const;
  QString mergeKey() const { return drag_.key; }

 private:
  struct Item {
    scene::EntityId id;
    scene::Transform local;
    glm::dmat4 world;
    glm::dmat4 parentWorld;
  };
  struct Drag {
    bool active = false;
    GizmoHandle handle = GizmoHandle::None;
    GizmoMode mode = GizmoMode::Select;
    GizmoFrame frame;
    glm::dvec2 startPixel{0.0}, centrePixel{0.0};
    glm::dvec3 startHit{0.0};
    double startT = 0.0;
    double lastAngle = 0.0, angle = 0.0;
    std::vector<Item> items;
    QString key;
  };

  bool axisParam(const render::RenderView& view, const glm::dvec2& pixel, const glm::dvec3& axis, double& t) const;
  bool planeHit(const render::RenderView& view, const glm::dvec2& pixel, const glm::dvec3& normal,
                glm::dvec3& hit) const;

  GizmoMode mode_ = GizmoMode::Translate;
  GizmoSpace space_ = GizmoSpace::World;
  SnapSettings snap_;
  GizmoHandle hover_ = GizmoHandle::None;
  Drag drag_;
};

}  // namespace hs::app
