#pragma once
// The 3D viewport: a QOpenGLWidget (4.5 core, see app_settings.h) that owns
// an hs::render::Renderer and turns mouse and keys into camera moves,
// selection and gizmo drags. It includes no GL headers itself: the renderer
// works on whatever context is current, which is this widget's inside
// initializeGL/paintGL and after makeCurrent().
#include <QAction>
#include <QElapsedTimer>
#include <QOpenGLWidget>
#include <QTimer>

#include <limits>

#include "app/camera_controller.h"
#include "app/gizmo.h"
#include "render/auto_exposure.h"
#include "render/renderer.h"
#include "render/stereo_preview_renderer.h"
#include "scene/document.h"

class QLabel;

namespace hs::app {

class ComfortReadout;
class FoliageTool;
class PathEditor;
class PathPointDrag;
class Selection;
class TerrainTool;
class StereoPreviewSettings;
class TimelineClock;

class ViewportWidget : public QOpenGLWidget {
  Q_OBJECT
 public:
  ViewportWidget(scene::Document& doc, Selection& selection, QWidget* parent = nullptr);
  ~ViewportWidget() override;

  CameraController& camera() { return camera_; }
  Gizmo& gizmo() { return gizmo_; }
  bool rendererReady() const { return renderer_.initialized(); }
  QString rendererError() const { return error_; }
  QString glDescription() const { return glDescription_; }
  int framesRendered() const { return frames_; }
  const render::FrameStats& lastStats() const { return stats_; }
  // Terrain material textures the renderer could not read, found since the
  // last call (the Terrain panel passes them to Messages after each frame).
  std::vector<std::string> takeTerrainMaterialProblems() { return renderer_.takeTerrainMaterialProblems(); }
  // OpenGL's debug output and what the renderer refused or clamped
  // (render/render_problems.h) since the last call.
  std::vector<std::string> takeRendererMessages();
  bool showGrid() const { return showGrid_; }
  void setShowGrid(bool show);
  // The depth-complexity view mode (RenderOptions::depthComplexity).
  bool showDepthComplexity() const { return showDepthComplexity_; }
  void setShowDepthComplexity(bool show);
  // Cluster hierarchies coloured by level (RenderOptions::clusterLevels).
  bool showClusterLevels() const { return showClusterLevels_; }
  void setShowClusterLevels(bool show);
  // The before/after split of the post chain: the left half without effects.
  bool postSplit() const { return postSplit_; }
  // Automatic exposure's meterings so far: the stereo preview's probe
  // renders and the free view's frames (render/auto_exposure.h).
  size_t exposureMeterings() const { return exposure_.probesRendered() + freeViewMeterings_; }
  void setPostSplit(bool on);

  // The entity under a widget position (logical pixels): a camera/light
  // glyph, else a mesh through the renderer's id pass. Makes the context
  // current, so it works outside paintGL.
  scene::EntityId pickAt(const QPoint& pos);
  // Click selection as the mouse does it: plain replaces, Shift adds, Ctrl toggles.
  void clickSelect(const QPoint& pos, Qt::KeyboardModifiers modifiers);

  void frameSelection();
  void frameAll();
  // After New/Open: look through the scene's first camera, else frame it all.
  void resetViewForDocument();
  // Window pixel of a world point in this view (for tests and tools).
  bool projectToWidget(const glm::dvec3& world, QPoint& pos) const;
  render::RenderView currentView() const;

  // The timeline (the viewport then shows the scene at its current time,
  // draws camera paths and motion, and can preview stereo through a camera).
  void setTimeline(TimelineClock* clock, StereoPreviewSettings* stereo);
  // The terrain brush: while it has a tool, left-mouse strokes sculpt and
  // paint the terrain under the cursor (viewport_terrain.cpp).
  void setTerrainTool(TerrainTool* tool) { terrainTool_ = tool; }
  // The foliage brush: while it has a tool, left-mouse strokes paint,
  // erase or select foliage on the ground under the cursor
  // (viewport_foliage.cpp). The panels keep one of the two brushes active.
  void setFoliageTool(FoliageTool* tool) { foliageTool_ = tool; }
  // Camera paths: the drawn points can be picked and dragged, the selected
  // point with move handles (viewport_path.cpp).
  void setPathEditor(PathEditor* editor);
  PathPointDrag* pathPointDrag() const { return pathDrag_; }
  // Focus picking (depth of field; viewport_focus.cpp): while on, the next
  // left click sets the active camera's focus distance to the depth of the
  // surface under it (one undo step, keyed like any edit), then turns off.
  // The action is the View menu's "Pick Focus Distance" (Ctrl+Alt+F).
  QAction* focusPickAction() const { return focusPickAction_; }
  void setFocusPicking(bool on);
  bool focusPicking() const { return focusPicking_; }
  // The click itself: false (nothing changed) where no surface is under
  // `pos`, there is no camera, or the surface is behind the camera.
  bool pickFocus(const QPoint& pos);
  // What the viewport shows: the document at the timeline's current time.
  const scene::SceneState& displayedState() const;
  bool stereoPreviewActive() const;
  // The comfort check of the last stereo preview frame.
  const std::optional<sequencer::ComfortResult>& lastComfort() const { return lastComfort_; }

 signals:
  void frameRendered(const hs::render::FrameStats& stats);
  void rendererFailed(const QString& error);
  void rendererStarted(const QString& glDescription);
  void flySpeedChanged(double metresPerSecond);
  // A gizmo drag changed these transform fields ("transform.translation",
  // "transform.rotation_deg", "transform.scale") with this undo merge key:
  // the timeline keys them where they are animated or Auto Key is on.
  void transformsEdited(const std::vector<hs::scene::EntityId>& ids, const std::vector<std::string>& fields,
                        const QString& mergeKey);
  // Focus picking set this camera's focus_distance_m with this merge key
  // (the timeline keys it where it is animated or Auto Key is on).
  void focusPicked(hs::scene::EntityId camera, const QString& mergeKey);

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  bool event(QEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;
  void keyReleaseEvent(QKeyEvent* e) override;
  void focusOutEvent(QFocusEvent* e) override;

 private:
  enum class Drag { None, Click, Gizmo, Fly, Orbit, Pan, Dolly, Terrain, Foliage, PathPoint };
  void releaseGl();
  void onDocumentChanged(const scene::ChangeSet& changes);
  void tickFly();
  void endFly();
  glm::dvec2 toPixel(const QPointF& p) const;
  bool moveKey(int key, CameraController::MoveKey& out) const;
  void showError(const QString& text);

  scene::Document& doc_;
  Selection& selection_;
  render::Renderer renderer_;
  CameraController camera_;
  Gizmo gizmo_;
  QMetaObject::Connection contextConnection_;
  QString error_, glDescription_;
  QLabel* errorLabel_ = nullptr;
  render::FrameStats stats_;
  int frames_ = 0;
  bool showGrid_ = true;
  bool showDepthComplexity_ = false;
  bool showClusterLevels_ = false;
  bool postSplit_ = false;
  bool collectGarbage_ = false;
  // Automatic exposure (post.auto_exposure): the stereo preview adapts as
  // the export does (probes kept by camera and time; every document change
  // makes them stale); the free view meters what it drew (NaN: not yet).
  render::AutoExposure exposure_;
  float freeViewEv_ = std::numeric_limits<float>::quiet_NaN();
  size_t freeViewMeterings_ = 0;
  bool needsViewReset_ = true;

  Drag drag_ = Drag::None;
  QPointF pressPos_, lastPos_;
  Qt::KeyboardModifiers pressModifiers_;
  QTimer flyTimer_;
  TerrainTool* terrainTool_ = nullptr;
  bool terrainPress(const QPointF& pos);  // viewport_terrain.cpp
  void terrainMove(const QPointF& pos);
  void terrainEnd();
  FoliageTool* foliageTool_ = nullptr;
  bool foliagePress(const QPointF& pos, Qt::KeyboardModifiers modifiers);  // viewport_foliage.cpp
  void foliageMove(const QPointF& pos);
  void foliageEnd();
  QElapsedTimer flyClock_;

  TimelineClock* clock_ = nullptr;
  StereoPreviewSettings* stereo_ = nullptr;
  // Focus picking (viewport_focus.cpp).
  QAction* focusPickAction_ = nullptr;
  bool focusPicking_ = false;
  int focusPicks_ = 0;  // merge keys: each pick its own undo step
  void createFocusPickAction();
  render::StereoPreviewRenderer stereoRenderer_;
  ComfortReadout* comfortReadout_ = nullptr;
  std::optional<sequencer::ComfortResult> lastComfort_;
  sequencer::Sequence gizmoStartSequence_;  // put back when a drag is cancelled (auto keys included)
  bool paintStereo();
  void emitTransformsEdited();

  PathPointDrag* pathDrag_ = nullptr;  // viewport_path.cpp
  bool pathOwnsGizmo() const;          // a path point is selected: its handles replace the entity gizmo
  bool pathPress(const QPointF& pos);
  void pathMove(const QPointF& pos, Qt::KeyboardModifiers modifiers);
  void pathEnd();
  bool pathKey(QKeyEvent* e, bool shortcutOverride);
  void drawPathOverlay(const scene::SceneState& state, const render::RenderView& view, render::Overlay& overlay);
};

}  // namespace hs::app
