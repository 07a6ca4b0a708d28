#include "app/viewport_widget.h"

#include <algorithm>
#include <cmath>

#include <QCursor>
#include <QKeyEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QTimer>
#include <QVBoxLayout>
#include <QWheelEvent>

#include "app/foliage_tool.h"
#include "app/overlay_builder.h"
#include "app/selection.h"
#include "app/terrain_tool.h"
#include "app/timeline_clock.h"
#include "app/timeline_path_overlay.h"
#include "render/render_problems.h"
#include "scene/sequence_edits.h"
#include "scene/world_bounds.h"

namespace hs::app {
namespace {

constexpr double kClickSlopPixels = 4.0;
// While flying the cursor is warped back once it strays this far, so mouse
// look never runs into the screen edge.
constexpr double kWarpPixels = 120.0;

}  // namespace

ViewportWidget::ViewportWidget(scene::Document& doc, Selection& selection, QWidget* parent)
    : QOpenGLWidget(parent), doc_(doc), selection_(selection) {
  setObjectName("viewport");
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);  // gizmo hover highlight
  setMinimumSize(320, 200);
  connect(&doc_, &scene::Document::changed, this, &ViewportWidget::onDocumentChanged);
  connect(&selection_, &Selection::changed, this, qOverload<>(&ViewportWidget::update));
  // Runs only while a fly key is held: an idle viewport costs no CPU.
  flyTimer_.setInterval(16);
  flyTimer_.setTimerType(Qt::PreciseTimer);
  connect(&flyTimer_, &QTimer::timeout, this, &ViewportWidget::tickFly);
  createFocusPickAction();
}

ViewportWidget::~ViewportWidget() {
  releaseGl();
  // ~QOpenGLWidget destroys the context after this object's members are
  // gone: the aboutToBeDestroyed hook must not reach them.
  disconnect(contextConnection_);
}

void ViewportWidget::releaseGl() {
  if (!renderer_.initialized()) return;
  const bool haveContext = context() && context()->isValid();
  if (haveContext) makeCurrent();
  // Without a current context there is nothing left to free GL objects in.
  if (haveContext) stereoRenderer_.release();
  if (haveContext) exposure_.release();
  if (haveContext) renderer_.shutdown();
  if (haveContext) doneCurrent();
}

void ViewportWidget::showError(const QString& text) {
  error_ = text;
  if (!errorLabel_) {
    errorLabel_ = new QLabel(this);
    errorLabel_->setObjectName("viewportError");
    errorLabel_->setWordWrap(true);
    errorLabel_->setAlignment(Qt::AlignCenter);
    errorLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    errorLabel_->setStyleSheet("QLabel { color: #ffb4a8; background: #2a1d1d; padding: 24px; font-size: 11pt; }");
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(errorLabel_);
  }
  errorLabel_->setText("<b>The 3D viewport is unavailable.</b><br><br>" + text.toHtmlEscaped() +
                       "<br><br>Hybridscape needs OpenGL 4.5 (core profile). Update the graphics driver, or "
                       "run with Mesa's llvmpipe (LIBGL_ALWAYS_SOFTWARE=1).");
  errorLabel_->show();
}

void ViewportWidget::initializeGL() {
  disconnect(contextConnection_);
  contextConnection_ = connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &ViewportWidget::releaseGl,
                               Qt::DirectConnection);
  const QSurfaceFormat f = context()->format();
  std::string error;
  if (f.majorVersion() * 10 + f.minorVersion() < 45) {
    error = QString("the window system gave an OpenGL %1.%2 context.").arg(f.majorVersion()).arg(f.minorVersion()).toStdString();
  } else if (!renderer_.initialize(error)) {
    // error set by the renderer
  } else {
    glDescription_ = QString::fromStdString(render::currentGlDescription());
    emit rendererStarted(glDescription_);
    return;
  }
  showError(QString::fromStdString(error));
  emit rendererFailed(error_);
}

void ViewportWidget::resizeGL(int, int) {
  const qreal dpr = devicePixelRatioF();
  camera_.setViewportSize(int(std::lround(width() * dpr)), int(std::lround(height() * dpr)));
}

void ViewportWidget::paintGL() {
  const qreal dpr = devicePixelRatioF();
  camera_.setViewportSize(int(std::lround(width() * dpr)), int(std::lround(height() * dpr)));
  if (!renderer_.initialized()) {
    render::Renderer::clearTarget(defaultFramebufferObject(), 0.1f, 0.08f, 0.08f);
    return;
  }
  if (paintStereo()) return;
  const scene::SceneState& shown = displayedState();
  // Automatic exposure: the free view is no camera's, so it has no history
  // to adapt over. It meters the picture it drew (a probe would cost a
  // frame's CPU work again) and shows that exposure from the next paint,
  // asking for one more when it moved (render/auto_exposure.h).
  const bool autoExposure = shown.settings.post.autoExposure;
  scene::SceneState exposed;
  if (autoExposure) {
    exposed = shown;
    if (std::isfinite(freeViewEv_)) exposed.settings.exposureEv100 = freeViewEv_;
  }
  const scene::SceneState& state = autoExposure ? exposed : shown;
  if (collectGarbage_) {
    renderer_.collectGarbage(state);
    collectGarbage_ = false;
  }
  const render::RenderView& view = camera_.view();
  render::Overlay overlay;
  buildSceneOverlay(state, selection_.ids(), view, overlay);
  if (clock_) buildTimelineOverlay(doc_.state(), clock_->compiled(), selection_.ids(), clock_->time(), view, overlay);
  drawPathOverlay(state, view, overlay);
  if (!pathOwnsGizmo()) gizmo_.draw(state, selection_.ids(), view, overlay);
  if (terrainTool_) terrainTool_->drawOverlay(state, overlay);
  if (foliageTool_) foliageTool_->drawOverlay(state, overlay);
  render::RenderOptions options;
  options.showGrid = showGrid_;
  options.overlay = overlay.empty() ? nullptr : &overlay;
  options.measureGpuTime = true;
  // Per-pass GPU timestamps wait for the GPU, so only one frame in 30 takes
  // them (the status bar's per-pass list keeps the last measured times).
  options.passTimings = frames_ % 30 == 0;
  options.oitCounts = options.passTimings;  // fragments per pixel for the status bar, with the timings
  options.depthComplexity = showDepthComplexity_;
  options.clusterLevels = showClusterLevels_;
  // Cluster pages stream in: this frame draws what is resident, and the
  // view draws again while pages are on their way (render/cluster_source.h).
  options.streamClusters = true;
  options.postSplit = postSplit_ ? 0.5f : 0.0f;
  options.keepHdr = autoExposure;
  stats_ = renderer_.render(state, view, defaultFramebufferObject(), options);
  if (autoExposure) {
    const float metered =
        float(render::meteredEv100Of(renderer_.readHdr(0), shown.settings.post));
    ++freeViewMeterings_;
    if (!(std::abs(metered - state.settings.exposureEv100) < 0.01f)) {
      freeViewEv_ = metered;
      update();
    }
  } else {
    freeViewEv_ = std::numeric_limits<float>::quiet_NaN();
  }
  ++frames_;
  if (stats_.clusters.pagesLoading > 0 && !stats_.clusters.budgetFull) QTimer::singleShot(30, this, [this] { update(); });
  emit frameRendered(stats_);
}

void ViewportWidget::setShowDepthComplexity(bool show) {
  if (show == showDepthComplexity_) return;
  showDepthComplexity_ = show;
  update();
}

std::vector<std::string> ViewportWidget::takeRendererMessages() {
  std::vector<std::string> out = renderer_.takeGlMessages();
  for (std::string& p : render::takeRenderProblems(renderer_)) out.push_back(std::move(p));
  return out;
}

void ViewportWidget::setShowClusterLevels(bool show) {
  if (show == showClusterLevels_) return;
  showClusterLevels_ = show;
  update();
}

void ViewportWidget::setPostSplit(bool on) {
  if (on == postSplit_) return;
  postSplit_ = on;
  update();
}

void ViewportWidget::setShowGrid(bool show) {
  if (show == showGrid_) return;
  showGrid_ = show;
  update();
}

void ViewportWidget::onDocumentChanged(const scene::ChangeSet& changes) {
  if (changes.reset) {
    gizmo_.endDrag();
    resetViewForDocument();
  }
  if (changes.assets) collectGarbage_ = true;
  exposure_.forget();
  update();
}

render::RenderView ViewportWidget::currentView() const { return camera_.view(); }

void ViewportWidget::resetViewForDocument() {
  const scene::SceneState& state = doc_.state();
  const render::RenderView& cur = camera_.view();
  const scene::WorldBox box = scene::worldBounds(state);
  const std::vector<scene::EntityId> cams = state.cameras();
  if (!cams.empty()) {
    const render::RenderView v = render::viewFromCamera(state, cams.front(), cur.width, cur.height);
    double pivot = 10.0;
    if (!box.empty) pivot = std::max(glm::dot(box.centre() - v.eye, v.forward()), 1.0);
    camera_.setView(v, pivot);
    // From the distance to what the camera looks at, as framing does: the
    // whole scene's extent (a valley terrain) gave hundreds of m/s next to
    // a 2-metre scan.
    camera_.setFlySpeed(std::clamp(pivot * 0.5, 0.5, 5000.0));
  } else {
    const glm::dvec3 mn = box.empty ? glm::dvec3(-5.0, -5.0, 0.0) : box.min;
    const glm::dvec3 mx = box.empty ? glm::dvec3(5.0, 5.0, 3.0) : box.max;
    const render::RenderView v = render::frameBox(mn, mx, cur.width, cur.height);
    camera_.setView(v, glm::length((mn + mx) * 0.5 - v.eye));
    scene::WorldBox b;
    b.extend(mn);
    b.extend(mx);
    camera_.frame(b);
  }
  emit flySpeedChanged(camera_.flySpeed());
  update();
}

void ViewportWidget::frameSelection() {
  const scene::SceneState& state = displayedState();
  if (selection_.empty()) return frameAll();
  scene::WorldBox box = scene::worldBounds(state, selection_.ids());
  if (box.empty) {
    // Cameras and lights have no extent: frame a few metres around them.
    for (scene::EntityId id : selection_.ids()) {
      if (!state.find(id)) continue;
      const glm::dvec3 p(state.worldMatrix(id)[3]);
      box.extend(p - glm::dvec3(2.0));
      box.extend(p + glm::dvec3(2.0));
    }
  }
  camera_.frame(box);
  emit flySpeedChanged(camera_.flySpeed());
  update();
}

void ViewportWidget::frameAll() {
  const scene::WorldBox box = scene::worldBounds(doc_.state());
  if (box.empty) return;
  camera_.frame(box);
  emit flySpeedChanged(camera_.flySpeed());
  update();
}

glm::dvec2 ViewportWidget::toPixel(const QPointF& p) const {
  const qreal dpr = devicePixelRatioF();
  return {p.x() * dpr, p.y() * dpr};
}

bool ViewportWidget::projectToWidget(const glm::dvec3& world, QPoint& pos) const {
  glm::dvec2 px;
  if (!camera_.view().project(world, px)) return false;
  const qreal dpr = devicePixelRatioF();
  pos = QPoint(int(std::floor(px.x / dpr)), int(std::floor(px.y / dpr)));
  return rect().contains(pos);
}

scene::EntityId ViewportWidget::pickAt(const QPoint& pos) {
  const scene::SceneState& state = displayedState();
  const glm::dvec2 px = toPixel(QPointF(pos) + QPointF(0.5, 0.5));
  const render::RenderView& view = camera_.view();
  if (const scene::EntityId glyph = pickGlyph(state, view, px); glyph != scene::kNoEntity) return glyph;
  if (!renderer_.initialized()) return scene::kNoEntity;
  makeCurrent();
  const scene::EntityId id = renderer_.pick(state, view, int(px.x), int(px.y));
  doneCurrent();
  return id;
}

void ViewportWidget::clickSelect(const QPoint& pos, Qt::KeyboardModifiers modifiers) {
  const scene::EntityId id = pickAt(pos);
  if (modifiers & Qt::ControlModifier) {
    if (id != scene::kNoEntity) selection_.toggle(id);
  } else if (modifiers & Qt::ShiftModifier) {
    if (id != scene::kNoEntity) selection_.add(id);
  } else {
    selection_.select(id);
  }
}

bool ViewportWidget::moveKey(int key, CameraController::MoveKey& out) const {
  switch (key) {
    case Qt::Key_W: out = CameraController::Forward; return true;
    case Qt::Key_S: out = CameraController::Back; return true;
    case Qt::Key_A: out = CameraController::Left; return true;
    case Qt::Key_D: out = CameraController::Right; return true;
    case Qt::Key_E: out = CameraController::Up; return true;
    case Qt::Key_Q: out = CameraController::Down; return true;
    default: return false;
  }
}

bool ViewportWidget::event(QEvent* e) {
  if (e->type() == QEvent::ShortcutOverride) {
    // While flying, W/E/... steer the camera instead of switching gizmo
    // modes; during a drag Esc cancels it instead of anything else.
    auto* k = static_cast<QKeyEvent*>(e);
    CameraController::MoveKey unused;
    if ((drag_ == Drag::Fly && (moveKey(k->key(), unused) || k->key() == Qt::Key_Shift)) ||
        (drag_ == Drag::Gizmo && k->key() == Qt::Key_Escape) || pathKey(k, true)) {
      e->accept();
      return true;
    }
  }
  return QOpenGLWidget::event(e);
}

void ViewportWidget::mousePressEvent(QMouseEvent* e) {
  setFocus(Qt::MouseFocusReason);
  if (drag_ != Drag::None) return;  // a second button during a drag changes nothing
  if (stereoPreviewActive()) return;  // looking through a camera: turn the preview off to move or edit
  pressPos_ = lastPos_ = e->position();
  pressModifiers_ = e->modifiers();
  const bool alt = e->modifiers() & Qt::AltModifier;
  switch (e->button()) {
    case Qt::RightButton:
      if (alt) {
        drag_ = Drag::Dolly;
      } else {
        drag_ = Drag::Fly;
        camera_.beginFly();
        camera_.setFast(e->modifiers() & Qt::ShiftModifier);
        setCursor(Qt::BlankCursor);
      }
      break;
    case Qt::MiddleButton: drag_ = Drag::Pan; break;
    case Qt::LeftButton:
      if (alt) {
        drag_ = Drag::Orbit;
      } else {
        const glm::dvec2 px = toPixel(e->position());
        if (terrainPress(e->position())) break;  // a terrain brush stroke begins
        if (foliagePress(e->position(), e->modifiers())) break;  // a foliage brush stroke begins
        if (pathPress(e->position())) break;     // a camera path's point is grabbed
        const GizmoHandle h =
            pathOwnsGizmo() ? GizmoHandle::None : gizmo_.hitTest(displayedState(), selection_.ids(), camera_.view(), px);
        if (h != GizmoHandle::None && gizmo_.beginDrag(displayedState(), selection_.ids(), camera_.view(), h, px)) {
          drag_ = Drag::Gizmo;
          gizmoStartSequence_ = doc_.state().sequence;
          update();
        } else {
          drag_ = Drag::Click;
        }
      }
      break;
    default: break;
  }
}

void ViewportWidget::mouseMoveEvent(QMouseEvent* e) {
  const QPointF pos = e->position();
  const QPointF d = pos - lastPos_;
  const qreal dpr = devicePixelRatioF();
  lastPos_ = pos;
  switch (drag_) {
    case Drag::Fly:
      camera_.look(d.x(), d.y());
      if (QLineF(pos, pressPos_).length() > kWarpPixels) {
        QCursor::setPos(mapToGlobal(pressPos_.toPoint()));
        lastPos_ = pressPos_;
      }
      update();
      break;
    case Drag::Orbit:
      camera_.orbit(d.x(), d.y());
      update();
      break;
    case Drag::Pan:
      camera_.pan(d.x() * dpr, d.y() * dpr);
      update();
      break;
    case Drag::Dolly:
      camera_.dollyDrag(d.y());
      update();
      break;
    case Drag::Gizmo:
      if (gizmo_.dragTo(doc_, camera_.view(), toPixel(pos), e->modifiers() & Qt::ControlModifier)) emitTransformsEdited();
      break;
    case Drag::Click: break;
    case Drag::Terrain: terrainMove(pos); break;
    case Drag::Foliage: foliageMove(pos); break;
    case Drag::PathPoint: pathMove(pos, e->modifiers()); break;
    case Drag::None: {
      terrainMove(pos);  // the brush circle follows the cursor
      foliageMove(pos);
      pathMove(pos, e->modifiers());  // the path point handles' highlight
      const GizmoHandle h = pathOwnsGizmo() ? GizmoHandle::None
                                            : gizmo_.hitTest(displayedState(), selection_.ids(), camera_.view(), toPixel(pos));
      if (h != gizmo_.hover()) {
        gizmo_.setHover(h);
        update();
      }
      break;
    }
  }
}

void ViewportWidget::mouseReleaseEvent(QMouseEvent* e) {
  const Qt::MouseButton b = e->button();
  const bool ends = (b == Qt::RightButton && (drag_ == Drag::Fly || drag_ == Drag::Dolly)) ||
                    (b == Qt::MiddleButton && drag_ == Drag::Pan) ||
                    (b == Qt::LeftButton && (drag_ == Drag::Orbit || drag_ == Drag::Gizmo || drag_ == Drag::Click ||
                                             drag_ == Drag::Terrain || drag_ == Drag::Foliage ||
                                             drag_ == Drag::PathPoint));
  if (!ends) return;
  if (drag_ == Drag::Terrain) terrainEnd();
  if (drag_ == Drag::Foliage) foliageEnd();
  if (drag_ == Drag::Fly) endFly();
  if (drag_ == Drag::Gizmo) gizmo_.endDrag();
  if (drag_ == Drag::PathPoint) pathEnd();
  if (drag_ == Drag::Click && QLineF(e->position(), pressPos_).length() <= kClickSlopPixels) {
    if (focusPicking_) {  // depth of field: this click picks the focus (viewport_focus.cpp)
      pickFocus(e->position().toPoint());
      setFocusPicking(false);
    } else {
      clickSelect(e->position().toPoint(), pressModifiers_ | e->modifiers());
    }
  }
  drag_ = Drag::None;
  update();
}

void ViewportWidget::wheelEvent(QWheelEvent* e) {
  const double steps = e->angleDelta().y() / 120.0;
  if (steps == 0.0) return;
  if (drag_ == Drag::Fly) {
    camera_.changeFlySpeed(steps);
    emit flySpeedChanged(camera_.flySpeed());
  } else {
    camera_.dolly(steps);
  }
  update();
  e->accept();
}

void ViewportWidget::keyPressEvent(QKeyEvent* e) {
  CameraController::MoveKey k;
  if (drag_ == Drag::Fly) {
    if (e->key() == Qt::Key_Shift) {
      camera_.setFast(true);
      return;
    }
    if (moveKey(e->key(), k)) {
      if (!e->isAutoRepeat()) camera_.setMoveKey(k, true);
      if (!flyTimer_.isActive()) {
        flyClock_.restart();
        flyTimer_.start();
      }
      return;
    }
  }
  if (pathKey(e, false)) return;  // Esc during a point drag, Delete on a selected point
  if (drag_ == Drag::Gizmo && e->key() == Qt::Key_Escape) {
    const QString key = gizmo_.mergeKey();
    gizmo_.cancelDrag(doc_);
    // Keys the drag set go too: the whole step then holds no change.
    if (clock_) scene::ops::replaceSequence(doc_, gizmoStartSequence_, gizmo_.undoText(), key);
    drag_ = Drag::None;
    update();
    return;
  }
  QOpenGLWidget::keyPressEvent(e);
}

void ViewportWidget::keyReleaseEvent(QKeyEvent* e) {
  CameraController::MoveKey k;
  if (drag_ == Drag::Fly && !e->isAutoRepeat()) {
    if (e->key() == Qt::Key_Shift) {
      camera_.setFast(false);
      return;
    }
    if (moveKey(e->key(), k)) {
      camera_.setMoveKey(k, false);
      return;
    }
  }
  QOpenGLWidget::keyReleaseEvent(e);
}

void ViewportWidget::focusOutEvent(QFocusEvent* e) {
  if (drag_ == Drag::Terrain) terrainEnd();
  if (drag_ == Drag::Foliage) foliageEnd();
  if (drag_ == Drag::Fly) {
    endFly();
    drag_ = Drag::None;
  }
  QOpenGLWidget::focusOutEvent(e);
}

void ViewportWidget::tickFly() {
  const double dt = flyClock_.restart() / 1000.0;
  if (camera_.tick(dt)) update();
  if (!camera_.moving()) flyTimer_.stop();
}

void ViewportWidget::endFly() {
  camera_.endFly();
  flyTimer_.stop();
  unsetCursor();
}

}  // namespace hs::app
