// ViewportWidget's timeline side: the scene shown at the timeline's current
// time, the stereo preview through the active camera (with the comfort
// readout), and the fields a gizmo drag changed, for keying. Kept apart from
// viewport_widget.cpp, which handles the view and the mouse.
#include <cmath>

#include "app/selection.h"
#include "app/stereo_preview.h"
#include "app/timeline_clock.h"
#include "app/viewport_widget.h"
#include "scene/animation.h"

namespace hs::app {

void ViewportWidget::setTimeline(TimelineClock* clock, StereoPreviewSettings* stereo) {
  clock_ = clock;
  stereo_ = stereo;
  if (clock_) connect(clock_, &TimelineClock::stateChanged, this, qOverload<>(&ViewportWidget::update));
  if (stereo_) connect(stereo_, &StereoPreviewSettings::changed, this, [this] {
    if (!stereoPreviewActive() && comfortReadout_) comfortReadout_->hide();
    update();
  });
  update();
}

const scene::SceneState& ViewportWidget::displayedState() const { return clock_ ? clock_->state() : doc_.state(); }

bool ViewportWidget::stereoPreviewActive() const { return stereo_ && stereo_->mode() != StereoPreviewMode::Off; }

bool ViewportWidget::paintStereo() {
  if (!stereoPreviewActive()) return false;
  const scene::SceneState& shown = displayedState();
  scene::EntityId cam = stereo_->activeCamera(shown, selection_);
  // During a camera cuts' transition both shots, combined as the export does.
  const std::optional<sequencer::Shot> shot = stereo_->activeShot(shown, selection_);
  std::optional<render::PreviewTransition> transition;
  if (shot && shot->incoming) {
    transition = render::PreviewTransition{scene::EntityId(shot->incoming), *shot, shown.time.frame};
    cam = scene::EntityId(shot->camera);
  }
  // Automatic exposure adapted over the shot's probes as the export's
  // (render/auto_exposure.h): the same frame shows the same exposure.
  const bool autoExposure = cam != scene::kNoEntity && render::autoExposureOn(shown, cam, shot);
  scene::SceneState exposed;
  if (autoExposure) {
    const render::StateAtTime stateAt = [this, &shown](double t) {
      return clock_ ? scene::animatedState(doc_.state(), clock_->compiled(), t, nullptr) : shown;
    };
    exposed = shown;
    exposed.settings.exposureEv100 =
        float(exposure_.frameEv100(renderer_, stateAt, shown, cam, shot, shown.sequence.rate, shown.time.seconds,
                                   stereo_->outputAspect()));
  }
  const scene::SceneState& state = autoExposure ? exposed : shown;
  if (cam == scene::kNoEntity) {
    if (comfortReadout_) comfortReadout_->hide();
    return false;  // no camera to look through: the free view
  }
  if (collectGarbage_) {
    renderer_.collectGarbage(state);
    collectGarbage_ = false;
  }
  const qreal dpr = devicePixelRatioF();
  const int w = int(std::lround(width() * dpr)), h = int(std::lround(height() * dpr));
  render::StereoPreviewMode mode = render::StereoPreviewMode::Left;
  switch (stereo_->mode()) {
    case StereoPreviewMode::Right: mode = render::StereoPreviewMode::Right; break;
    case StereoPreviewMode::SideBySide: mode = render::StereoPreviewMode::SideBySide; break;
    case StereoPreviewMode::Anaglyph: mode = render::StereoPreviewMode::Anaglyph; break;
    default: break;
  }
  sequencer::ComfortOptions comfort;
  comfort.budget = stereo_->budget();
  const render::StereoPreviewResult r =
      stereoRenderer_.draw(renderer_, state, cam, mode, stereo_->outputAspect(), defaultFramebufferObject(), w, h,
                           &comfort, transition ? &*transition : nullptr);
  stats_ = r.stats;
  ++frames_;
  lastComfort_ = r.comfort;
  if (!comfortReadout_) {
    comfortReadout_ = new ComfortReadout(this);
    comfortReadout_->move(8, 8);
  }
  const scene::Entity* camera = state.find(stereo_->activeCamera(state, selection_));
  if (r.comfort) comfortReadout_->showResult(*r.comfort, stereo_->budget(), camera && camera->camera &&
                                                 camera->camera->stereo != scene::Camera::Stereo::Mono);
  emit frameRendered(stats_);
  return true;
}

void ViewportWidget::emitTransformsEdited() {
  std::vector<std::string> fields;
  const bool several = selection_.size() > 1;  // rotating or scaling about their centre moves them too
  switch (gizmo_.mode()) {
    case GizmoMode::Translate: fields = {"transform.translation"}; break;
    case GizmoMode::Rotate: fields = {"transform.rotation_deg"}; break;
    case GizmoMode::Scale: fields = {"transform.scale"}; break;
    case GizmoMode::Select: return;
  }
  if (several && gizmo_.mode() != GizmoMode::Translate) fields.push_back("transform.translation");
  emit transformsEdited(selection_.ids(), fields, gizmo_.mergeKey());
}

}  // namespace hs::app
