#pragma once
// The terrain brush in the viewport: picks the terrain under the cursor
// (scene::pickTerrain, the terrain library's ray cast: holes are not hit),
// runs a terrain::Stroke while the left button is held, tells the document
// about each dab (the renderer uploads just its region) and, on release,
// records the stroke as one undo step on the document's QUndoStack. Ramp is
// a press-drag-release from one point to the other. The brush circle follows
// the ground under the cursor. The viewport forwards mouse events here when
// a tool is chosen; the Terrain panel sets the tool and its settings.
#include <memory>
#include <optional>

#include <QObject>

#include "render/overlay.h"
#include "render/render_view.h"
#include "scene/document.h"
#include "scene/terrain_pick.h"
#include "terrain/brush.h"
#include "terrain/stroke.h"

namespace hs::app {

enum class TerrainToolKind {
  Off,  // the viewport selects and moves as usual
  Raise, Lower, Smooth, Flatten, Ramp, Noise, Terrace, ThermalErosion, HydraulicErosion, Paint, Holes,
};
const char* terrainToolLabel(TerrainToolKind k);

class TerrainTool : public QObject {
  Q_OBJECT
 public:
  explicit TerrainTool(scene::Document& doc, QObject* parent = nullptr);
  ~TerrainTool() override;

  TerrainToolKind kind() const { return kind_; }
  void setKind(TerrainToolKind k);
  bool active() const { return kind_ != TerrainToolKind::Off; }

  // Radius (metres), strength, falloff, spacing, layer, tool options. The
  // tool field is set from kind().
  const terrain::BrushSettings& settings() const { return settings_; }
  void setSettings(const terrain::BrushSettings& s);
  // [ and ]: radius down/up by a factor; Shift+[ and Shift+]: strength.
  void scaleRadius(double factor);
  void scaleStrength(double factor);

  // --- from the viewport (rays in world space) -----------------------------
  // Press: starts a stroke if the ray hits a terrain. False: not handled.
  bool begin(const glm::dvec3& origin, const glm::dvec3& direction, float pressure = 1.0f);
  void drag(const glm::dvec3& origin, const glm::dvec3& direction, float pressure = 1.0f);
  void end();
  bool stroking() const { return bool(stroke_) || rampStart_.has_value(); }
  // Mouse over the viewport without a button: moves the brush circle.
  // Returns whether it moved (the viewport repaints then).
  bool hover(const glm::dvec3& origin, const glm::dvec3& direction);
  void clearHover();
  const std::optional<scene::TerrainPick>& hoverPick() const { return hover_; }

  // The brush circle (outer radius, inner full-strength radius), draped on
  // the ground, and a ramp's line while it is dragged.
  void drawOverlay(const scene::SceneState& state, render::Overlay& overlay) const;

 signals:
  void settingsChanged();
  // After every stroke: what happened (for Messages; warnings, undo drops).
  void strokeFinished(const QString& summary, bool warning);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  terrain::BrushTool brushTool() const;
  void noteDab(const terrain::StrokeUpdate& u);
  void finishStep(terrain::UndoStep step, const std::vector<std::string>& warnings);

  scene::Document& doc_;
  TerrainToolKind kind_ = TerrainToolKind::Off;
  terrain::BrushSettings settings_;
  std::optional<scene::TerrainPick> hover_;
  // The stroke in progress (on one terrain, the one it started on).
  std::unique_ptr<terrain::Stroke> stroke_;
  scene::EntityId strokeEntity_ = scene::kNoEntity;
  scene::TerrainId strokeTerrain_ = scene::kNoTerrain;
  std::shared_ptr<scene::TerrainData> strokeData_;
  std::optional<glm::dvec3> rampStart_, rampEnd_;  // local x, y, height
};

}  // namespace hs::app
