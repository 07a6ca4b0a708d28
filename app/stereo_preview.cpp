#include "app/stereo_preview.h"

#include <cmath>

#include <QSettings>

#include "app/selection.h"
#include "render/stereo_views.h"

namespace hs::app {

StereoPreviewSettings::StereoPreviewSettings(QObject* parent) : QObject(parent) {
  QSettings s;
  const int w = s.value("export/eyeWidth", 1920).toInt(), h = s.value("export/eyeHeight", 1080).toInt();
  if (w > 0 && h > 0) aspect_ = double(w) / double(h);
  budget_.nearest = s.value("stereo/budgetNearest", budget_.nearest).toDouble();
  budget_.farthest = s.value("stereo/budgetFarthest", budget_.farthest).toDouble();
}

QString StereoPreviewSettings::modeName(StereoPreviewMode m) {
  switch (m) {
    case StereoPreviewMode::Off: return "Off (free view)";
    case StereoPreviewMode::Left: return "Left Eye";
    case StereoPreviewMode::Right: return "Right Eye";
    case StereoPreviewMode::SideBySide: return "Side by Side";
    case StereoPreviewMode::Anaglyph: return "Anaglyph (Red/Cyan)";
  }
  return {};
}

scene::EntityId StereoPreviewSettings::activeCamera(const scene::SceneState& state, const Selection& selection) const {
  const scene::Entity* e = state.find(selection.primary());
  if (e && e->camera) return e->id;
  // The camera cuts' camera at the shown frame (`state` is the timeline's);
  // during a transition the stronger shot (the one the comfort readout
  // speaks of; the preview combines both, activeTransition).
  if (const auto shot = sequencer::shotAt(state.sequence.cuts, state.time.frame)) {
    const auto [outgoing, incoming] = shot->weights();
    const scene::Entity* c = state.find(scene::EntityId(shot->incoming && incoming > outgoing ? shot->incoming : shot->camera));
    if (c && c->camera) return c->id;
  }
  return render::shotCamera(state);
}

std::optional<sequencer::Shot> StereoPreviewSettings::activeShot(const scene::SceneState& state,
                                                                 const Selection& selection) const {
  const scene::Entity* e = state.find(selection.primary());
  if (e && e->camera) return std::nullopt;
  const auto shot = sequencer::shotAt(state.sequence.cuts, state.time.frame);
  if (!shot) return std::nullopt;
  auto isCamera = [&](uint64_t id) {
    const scene::Entity* c = state.find(scene::EntityId(id));
    return c && c->camera;
  };
  if (!isCamera(shot->camera) || (shot->incoming && !isCamera(shot->incoming))) return std::nullopt;
  return shot;
}

std::optional<sequencer::Shot> StereoPreviewSettings::activeTransition(const scene::SceneState& state,
                                                                       const Selection& selection) const {
  const auto shot = activeShot(state, selection);
  return shot && shot->incoming ? shot : std::nullopt;
}

void StereoPreviewSettings::setMode(StereoPreviewMode mode) {
  if (mode == mode_) return;
  mode_ = mode;
  emit changed();
}

void StereoPreviewSettings::setBudget(const sequencer::ComfortBudget& budget) {
  budget_ = budget;
  QSettings s;
  s.setValue("stereo/budgetNearest", budget.nearest);
  s.setValue("stereo/budgetFarthest", budget.farthest);
  emit changed();
}

void StereoPreviewSettings::setOutputSize(int width, int height) {
  if (width <= 0 || height <= 0) return;
  aspect_ = double(width) / double(height);
  QSettings s;
  s.setValue("export/eyeWidth", width);
  s.setValue("export/eyeHeight", height);
  emit changed();
}

QString formatParallax(double share) { return QString::asprintf("%+.2f%%", share * 100.0); }

ComfortReadout::ComfortReadout(QWidget* parent) : QLabel(parent) {
  setObjectName("comfortReadout");
  setTextFormat(Qt::RichText);
  setMargin(6);
  setAttribute(Qt::WA_TransparentForMouseEvents);
  hide();
}

void ComfortReadout::showResult(const sequencer::ComfortResult& r, const sequencer::ComfortBudget& budget, bool stereo) {
  outside_ = !r.withinBudget;
  QString text;
  if (!stereo) {
    text = "Mono camera: no parallax (set its Stereo field for a stereo rig)";
  } else if (!r.hasPixels) {
    text = "Parallax: nothing visible";
  } else {
    auto depth = [](double d) { return std::isfinite(d) ? QString::asprintf("%.2f m", d) : QString("sky"); };
    text = QString("Parallax nearest <b>%1</b> (%2) · farthest <b>%3</b> (%4) · budget %5 .. %6")
               .arg(formatParallax(r.nearestParallax), depth(r.nearestDepth), formatParallax(r.farthestParallax),
                    depth(r.farthestDepth), formatParallax(budget.nearest), formatParallax(budget.farthest));
  }
  setStyleSheet(outside_ ? "QLabel { background: rgba(170, 30, 30, 220); color: white; border-radius: 3px; }"
                         : "QLabel { background: rgba(20, 20, 22, 190); color: #e0e0e4; border-radius: 3px; }");
  setToolTip(outside_ ? QString::fromStdString(r.message) : QString());
  setText(text);
  adjustSize();
  show();
}

}  // namespace hs::app
