#include "app/path_point_drag.h"

#include "app/overlay_builder.h"
#include "app/path_editor.h"

namespace hs::app {

namespace {

constexpr scene::EntityId kStandIn = 1;
const std::vector<scene::EntityId> kStandInSelection{kStandIn};

}  // namespace

PathPointDrag::PathPointDrag(PathEditor& editor, QObject* parent) : QObject(parent), editor_(editor) {
  // Points only move: their handles are always the translate gizmo's, in
  // world axes (path points are world positions), whatever the entity
  // gizmo's mode.
  gizmo_.setMode(GizmoMode::Translate);
  gizmo_.setSpace(GizmoSpace::World);
}

scene::SceneState PathPointDrag::standIn(const glm::dvec3& point) const {
  scene::SceneState s;
  s.settings = editor_.document().state().settings;  // overlay colours follow the scene's exposure
  scene::Entity e;
  e.id = kStandIn;
  e.name = "path point";
  e.transform.translation = point;
  s.entities.emplace(kStandIn, e);
  s.roots.push_back(kStandIn);
  return s;
}

std::optional<glm::dvec3> PathPointDrag::selectedPosition() const {
  const sequencer::PathFollow* p = editor_.path();
  const int i = editor_.selectedPoint();
  if (!p || i < 0) return std::nullopt;
  return p->path.points[size_t(i)];
}

std::optional<PathPointDrag::PointRef> PathPointDrag::pointAt(const render::RenderView& view,
                                                              const glm::dvec2& pixel) const {
  const scene::SceneState& state = editor_.document().state();
  std::optional<PointRef> best;
  double bestDistance = kPickPixels;
  auto consider = [&](const sequencer::Binding& b) {
    if (!b.path || !state.find(b.entity)) return;
    for (size_t i = 0; i < b.path->path.points.size(); ++i) {
      glm::dvec2 px;
      if (!view.project(b.path->path.points[i], px)) continue;
      const double d = glm::length(px - pixel);
      if (d < bestDistance) {
        bestDistance = d;
        best = PointRef{b.entity, int(i)};
      }
    }
  };
  // The edited path wins where paths overlap: it is the one being worked on.
  if (const sequencer::Binding* b = state.sequence.findBinding(editor_.entity())) consider(*b);
  if (best) return best;
  for (const sequencer::Binding& b : state.sequence.bindings) consider(b);
  return best;
}

bool PathPointDrag::showsHandles() const { return selectedPosition().has_value(); }

GizmoHandle PathPointDrag::handleAt(const render::RenderView& view, const glm::dvec2& pixel) const {
  const auto p = selectedPosition();
  if (!p) return GizmoHandle::None;
  return gizmo_.hitTest(standIn(*p), kStandInSelection, view, pixel);
}

bool PathPointDrag::hover(const render::RenderView& view, const glm::dvec2& pixel) {
  const GizmoHandle h = handleAt(view, pixel);
  if (h == gizmo_.hover()) return false;
  gizmo_.setHover(h);
  return true;
}

bool PathPointDrag::begin(const render::RenderView& view, const glm::dvec2& pixel, const SnapSettings& snap) {
  gizmo_.snap() = snap;
  GizmoHandle handle = handleAt(view, pixel);
  if (handle == GizmoHandle::None) {
    const auto hit = pointAt(view, pixel);
    if (!hit) return false;
    editor_.selectPoint(hit->entity, hit->index);
    // Grabbing a point drags it in the view plane, like the gizmo's centre.
    handle = GizmoHandle::View;
  }
  const auto p = selectedPosition();
  if (!p || !gizmo_.beginDrag(standIn(*p), kStandInSelection, view, handle, pixel)) return false;
  dragged_ = PointRef{editor_.entity(), editor_.selectedPoint()};
  start_ = *p;
  return true;
}

void PathPointDrag::drag(const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap) {
  if (!gizmo_.dragging()) return;
  const TransformList moved = gizmo_.dragTransforms(view, pixel, invertSnap);
  if (moved.empty() || editor_.entity() != dragged_.entity) return;
  editor_.movePoint(dragged_.index, moved.front().second.translation, gizmo_.mergeKey());
}

void PathPointDrag::cancel() {
  if (!gizmo_.dragging()) return;
  // Back to the start with the drag's merge key: the step then holds no
  // change and the undo stack drops it.
  if (editor_.entity() == dragged_.entity) editor_.movePoint(dragged_.index, start_, gizmo_.mergeKey());
  end();
}

void PathPointDrag::end() {
  gizmo_.endDrag();
  dragged_ = {};
}

void PathPointDrag::draw(const scene::SceneSettings& settings, const render::RenderView& view,
                         render::Overlay& out) const {
  const auto p = selectedPosition();
  if (!p) return;
  // A white diamond over the orange one marks the selected point.
  const double depth = glm::dot(*p - view.eye, view.forward());
  if (depth > view.nearClip) {
    const double s = view.pixelSizeAt(depth) * 8.0;
    const glm::dvec3 r = view.right() * s, u = view.up() * s;
    const glm::vec4 c = overlayColor({1.0f, 1.0f, 1.0f}, 1.0f, settings);
    out.triangle(*p + u, *p - r, *p - u, c);
    out.triangle(*p + u, *p - u, *p + r, c);
  }
  gizmo_.draw(standIn(*p), kStandInSelection, view, out);
}

}  // namespace hs::app
