#pragma once
// The foliage tools in the viewport: Paint, Erase and Select brushes over the ground
// under the cursor (the terrain through scene::pickTerrain, scans through
// the ground's MeshGround::raycast; the nearer wins). A press-drag-release
// is one stroke: dabs every half radius along the drag, each a domain tool
// call (foliage::paint, erase, selectRegion) on the document's store, their
// undo data merged (FoliageUndo::merge) and recorded at release as ONE undo
// step (scene::pushFoliageEdit). Select keeps a foliage::Selection: a click
// takes the nearest instance within the radius, a drag adds every instance
// under the dabs (Shift adds to what was selected); Delete and Reapply act
// on it, each one undo step. Lasso and Fill draw a polygon on the ground
// along the drag (closed at release): Lasso selects what lies inside it
// (Shift adds), Fill paints the brush's types into it up to their density
// (foliage::paint over the polygon: one undo step). Move drags the selection
// over the ground by the ground offset under the cursor, each instance put
// back on the surface under its new place (foliage::moveSelection with
// snap: one undo step at release). The Foliage panel sets the tool, the
// brush and the types; the viewport forwards mouse events
// (viewport_foliage.cpp).
#include <optional>
#include <string>
#include <vector>

#include <QObject>

class QWidget;

#include "foliage/tools.h"
#include "render/overlay.h"
#include "scene/document.h"
#include "scene/foliage_ops.h"

namespace hs::app {

class FoliageGroundCache;

enum class FoliageToolKind { Off, Paint, Erase, Select, Lasso, Fill, Move };
const char* foliageToolLabel(FoliageToolKind k);
// Lasso and Fill draw a polygon; the others dab a disc (Move: neither).
bool foliageToolDrawsPolygon(FoliageToolKind k);

struct FoliageBrush {
  double radius = 10.0;        // metres (a dab's disc in XY)
  double densityFactor = 1.0;  // Paint: times each type's density (0..10, foliage::PaintParams)
  uint64_t seed = 1;           // Paint: strokes and dabs draw their seeds from it; Reapply uses it
};

class FoliageTool : public QObject {
  Q_OBJECT
 public:
  static constexpr double kMinRadius = 0.1, kMaxRadius = 10000.0;
  static constexpr double kMaxDensityFactor = 10.0;

  FoliageTool(scene::Document& doc, FoliageGroundCache& ground, QObject* parent = nullptr);
  ~FoliageTool() override;
  // Fill and Reapply run on a worker (foliage_work.h) under a progress
  // dialog over this window; no stroke starts while one runs.
  void setDialogParent(QWidget* w) { dialogParent_ = w; }
  bool working() const { return working_; }

  FoliageToolKind kind() const { return kind_; }
  void setKind(FoliageToolKind k);
  bool active() const { return kind_ != FoliageToolKind::Off; }
  const FoliageBrush& brush() const { return brush_; }
  void setBrush(const FoliageBrush& b);
  // The brush shortcuts ([ and ], with Shift: the density factor; they act
  // on whichever brush is active, terrain_panel.cpp).
  void scaleRadius(double factor);
  void scaleDensity(double factor);
  // The types the brush works on (indices into the store's types). Paint
  // needs one at least; Erase and Select with none act on every type.
  void setTypes(foliage::TypeSet types) { types_ = std::move(types); }
  const foliage::TypeSet& types() const { return types_; }

  // --- from the viewport (rays in world space) -----------------------------
  // Press: starts a stroke where the ray meets the ground. `extend`: Select
  // adds to the selection. False: not handled (no ground under the cursor).
  // `drawn`: the foliage instance the renderer drew under the cursor (its
  // id pass, ViewportWidget::foliagePress): Select's click takes that one
  // (a tree's crown against the sky or over ground far behind it), and
  // the nearest within the radius of the ground point only without one.
  bool begin(const glm::dvec3& origin, const glm::dvec3& direction, bool extend = false,
             std::optional<uint32_t> drawn = std::nullopt);
  void drag(const glm::dvec3& origin, const glm::dvec3& direction);
  void end();
  bool stroking() const { return stroking_; }
  // The brush circle follows the ground; true when it moved.
  bool hover(const glm::dvec3& origin, const glm::dvec3& direction);
  void clearHover() { hover_.reset(); }
  std::optional<glm::dvec3> hoverPoint() const;

  // --- the selection ---------------------------------------------------------
  const foliage::Selection& selection() const { return selection_; }
  void clearSelection();
  // Delete the selected instances; draw their rotation, scale and sink
  // again from their type's settings (those its filters now refuse go).
  // Each one undo step; false when nothing changed.
  // Moves the selection by exactly `offset` (with `snap` each back on the
  // ground under its new place), one undo step: the Move tool's drag at
  // release, and Move Selected Instances By….
  bool moveSelectionBy(const glm::dvec3& offset, bool snap);
  bool deleteSelection();
  bool reapplySelection();

  // The lasso or fill polygon being drawn (world points on the ground, in
  // drag order; empty between strokes), and Move's offset so far.
  const std::vector<glm::dvec3>& polygon() const { return polygon_; }
  glm::dvec3 moveOffset() const { return moveOffset_; }

  // The brush circle on the ground, ticks on the instances under it (what
  // a dab will touch) and on the selected instances (where Move would put
  // them while it drags), and the polygon being drawn.
  void drawOverlay(const scene::SceneState& state, render::Overlay& overlay) const;

 signals:
  void settingsChanged();
  void selectionChanged();
  // After a stroke or a selection edit: what happened (for Messages).
  void strokeFinished(const QString& summary, bool warning);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  struct GroundHit {
    glm::dvec3 point{0.0};
    scene::EntityId terrain = scene::kNoEntity;  // the terrain entity hit, else a mesh
  };
  std::optional<GroundHit> pick(const glm::dvec3& origin, const glm::dvec3& direction);
  void dab(const glm::dvec3& centre);
  void addToSelection(foliage::Selection more);
  void record(foliage::EditResult r, const QString& text, bool keepsSelection, const QString& done = {});
  // An edit's warnings to Messages: the first few, then how many more.
  void announceWarnings(const std::vector<std::string>& warnings, const QString& text);
  // A worker's outcome (foliage_work.h) to Messages: its warnings, then
  // `done` (or what refused or cancelled it).
  void announce(const scene::ops::FoliageOutcome& out, const QString& text, const QString& done);
  void endPolygon();
  void endMove();

  scene::Document& doc_;
  FoliageGroundCache& ground_;
  QWidget* dialogParent_ = nullptr;
  bool working_ = false;
  FoliageToolKind kind_ = FoliageToolKind::Off;
  FoliageBrush brush_;
  foliage::TypeSet types_;
  std::optional<GroundHit> hover_;
  foliage::Selection selection_;

  // The stroke in progress.
  bool stroking_ = false;
  glm::dvec3 lastDab_{0.0};
  foliage::FoliageUndo undo_;  // every dab's, merged
  foliage::OpStats stats_;     // summed
  std::vector<std::string> messages_;
  uint64_t strokes_ = 0;  // each stroke's dabs draw other seeds
  uint64_t dabs_ = 0;
  std::vector<glm::dvec3> polygon_;  // Lasso, Fill
  glm::dvec3 moveFrom_{0.0}, moveOffset_{0.0};
};

}  // namespace hs::app
