#include "app/terrain_tool.h"

#include <algorithm>
#include <cmath>

#include <QCoreApplication>
#include <QKeyEvent>
#include <QKeySequence>

#include "scene/terrain_edits.h"

namespace hs::app {
namespace {

constexpr int kCircleSegments = 96;

}  // namespace

const char* terrainToolLabel(TerrainToolKind k) {
  switch (k) {
    case TerrainToolKind::Off: return "Select";
    case TerrainToolKind::Raise: return "Raise";
    case TerrainToolKind::Lower: return "Lower";
    case TerrainToolKind::Smooth: return "Smooth";
    case TerrainToolKind::Flatten: return "Flatten";
    case TerrainToolKind::Ramp: return "Ramp";
    case TerrainToolKind::Noise: return "Noise";
    case TerrainToolKind::Terrace: return "Terrace";
    case TerrainToolKind::ThermalErosion: return "Thermal";
    case TerrainToolKind::HydraulicErosion: return "Hydraulic";
    case TerrainToolKind::Paint: return "Paint";
    case TerrainToolKind::Holes: return "Holes";
  }
  return "?";
}

TerrainTool::TerrainTool(scene::Document& doc, QObject* parent) : QObject(parent), doc_(doc) {
  settings_.radius = 20.0;
  settings_.strength = 0.5f;
}

TerrainTool::~TerrainTool() {
  if (stroking()) QCoreApplication::instance()->removeEventFilter(this);
}

void TerrainTool::setKind(TerrainToolKind k) {
  if (k == kind_) return;
  if (stroking()) end();
  kind_ = k;
  if (!active()) hover_.reset();
  emit settingsChanged();
}

void TerrainTool::setSettings(const terrain::BrushSettings& s) {
  settings_ = s;
  emit settingsChanged();
}

void TerrainTool::scaleRadius(double factor) {
  settings_.radius = std::clamp(settings_.radius * factor, 0.05, 100000.0);
  emit settingsChanged();
}

void TerrainTool::scaleStrength(double factor) {
  // Raise/Lower/Noise strengths are metres; the others fractions of 1.
  const bool metres = kind_ == TerrainToolKind::Raise || kind_ == TerrainToolKind::Lower || kind_ == TerrainToolKind::Noise;
  settings_.strength = std::clamp(float(double(settings_.strength) * factor), 0.001f, metres ? 1000.0f : 1.0f);
  emit settingsChanged();
}

terrain::BrushTool TerrainTool::brushTool() const {
  switch (kind_) {
    case TerrainToolKind::Lower: return terrain::BrushTool::Lower;
    case TerrainToolKind::Smooth: return terrain::BrushTool::Smooth;
    case TerrainToolKind::Flatten: return terrain::BrushTool::Flatten;
    case TerrainToolKind::Noise: return terrain::BrushTool::Noise;
    case TerrainToolKind::Terrace: return terrain::BrushTool::Terrace;
    case TerrainToolKind::ThermalErosion: return terrain::BrushTool::ThermalErosion;
    case TerrainToolKind::HydraulicErosion: return terrain::BrushTool::HydraulicErosion;
    case TerrainToolKind::Paint: return terrain::BrushTool::Paint;
    case TerrainToolKind::Holes: return terrain::BrushTool::Holes;
    default: return terrain::BrushTool::Raise;
  }
}

bool TerrainTool::hover(const glm::dvec3& origin, const glm::dvec3& direction) {
  if (!active()) return false;
  const auto pick = scene::pickTerrain(doc_.state(), origin, direction);
  const bool changed = pick.has_value() != hover_.has_value() ||
                       (pick && glm::length(pick->hit.world - hover_->hit.world) > 1e-9);
  hover_ = pick;
  return changed;
}

void TerrainTool::clearHover() { hover_.reset(); }

bool TerrainTool::begin(const glm::dvec3& origin, const glm::dvec3& direction, float pressure) {
  if (!active() || stroking()) return false;
  const auto pick = scene::pickTerrain(doc_.state(), origin, direction);
  hover_ = pick;
  if (!pick) return false;
  const scene::TerrainAsset* t = doc_.state().findTerrain(pick->terrain);
  if (!t || !t->data) return false;
  if (t->data->jobRunning) {
    emit strokeFinished(QString("Terrain '%1' is busy with another operation; the stroke was not made.")
                            .arg(QString::fromStdString(t->name)),
                        true);
    return true;  // handled: no selection click either
  }
  strokeEntity_ = pick->entity;
  strokeTerrain_ = pick->terrain;
  strokeData_ = t->data;
  // Undo/Redo must wait for the stroke: its tiles are being written.
  QCoreApplication::instance()->installEventFilter(this);
  if (kind_ == TerrainToolKind::Ramp) {
    const glm::dvec2 l = pick->hit.local;
    rampStart_ = glm::dvec3(l, strokeData_->heights().heightAtLocal(l));
    rampEnd_ = rampStart_;
    return true;
  }
  terrain::BrushSettings s = settings_;
  s.tool = brushTool();
  stroke_ = std::make_unique<terrain::Stroke>(strokeData_->terrain(), s);
  noteDab(stroke_->moveTo(pick->hit.local, pressure));
  return true;
}

void TerrainTool::drag(const glm::dvec3& origin, const glm::dvec3& direction, float pressure) {
  if (!stroking()) return;
  // Only the terrain the stroke started on; a ray that misses it keeps the
  // last position (the pen left the terrain).
  const auto pick = scene::pickTerrain(doc_.state(), origin, direction);
  if (!pick || pick->entity != strokeEntity_) return;
  hover_ = pick;
  if (rampStart_) {
    const glm::dvec2 l = pick->hit.local;
    rampEnd_ = glm::dvec3(l, strokeData_->heights().heightAtLocal(l));
    return;
  }
  noteDab(stroke_->moveTo(pick->hit.local, pressure));
}

void TerrainTool::noteDab(const terrain::StrokeUpdate& u) {
  if (u.changed.empty()) return;
  scene::noteTerrainChange(doc_, strokeTerrain_, *strokeData_, u.changed, scene::changeKindsOf(brushTool()));
}

void TerrainTool::end() {
  if (!stroking()) return;
  QCoreApplication::instance()->removeEventFilter(this);
  if (rampStart_) {
    const glm::dvec3 a = *rampStart_, b = *rampEnd_;
    rampStart_.reset();
    rampEnd_.reset();
    if (glm::length(glm::dvec2(b - a)) < 1e-6) {
      strokeData_.reset();
      return;
    }
    terrain::RampSettings r;
    r.a = a;
    r.b = b;
    r.width = settings_.radius * 2.0;
    r.falloff = settings_.falloff.falloff;
    r.strength = std::clamp(settings_.strength, 0.0f, 1.0f);
    terrain::RampResult res = terrain::applyRamp(strokeData_->terrain(), r);
    if (!res.ok()) {
      emit strokeFinished("Ramp: " + QString::fromStdString(res.error), true);
      strokeData_.reset();
      return;
    }
    scene::noteTerrainChange(doc_, strokeTerrain_, *strokeData_, res.changed, scene::kTerrainHeights);
    res.undo.setLabel("Ramp");
    finishStep(std::move(res.undo), res.warnings);
    return;
  }
  terrain::UndoStep step = stroke_->finish();
  const std::vector<std::string> warnings = stroke_->warnings();
  stroke_.reset();
  finishStep(std::move(step), warnings);
}

void TerrainTool::finishStep(terrain::UndoStep step, const std::vector<std::string>& warnings) {
  const QString label = QString::fromUtf8(terrainToolLabel(kind_));
  const size_t bytes = step.bytes(), tiles = step.tileCount();
  const scene::TerrainPushResult r = scene::pushTerrainStep(doc_, strokeTerrain_, std::move(step), label);
  strokeData_.reset();
  for (const std::string& w : warnings) emit strokeFinished(label + ": " + QString::fromStdString(w), true);
  if (!r.kept)
    emit strokeFinished(QString("%1: this stroke touched %2 tiles (%3 MiB), more than the whole terrain undo "
                                "memory; it was applied but cannot be undone.")
                            .arg(label)
                            .arg(tiles)
                            .arg(double(bytes) / 1048576.0, 0, 'f', 1),
                        true);
  else if (r.dropped)
    emit strokeFinished(QString("Terrain undo memory is full: the %1 oldest terrain step(s) can no longer be undone.")
                            .arg(r.dropped),
                        false);
  else if (r.pushed)
    emit strokeFinished(QString(), false);
}

bool TerrainTool::eventFilter(QObject* watched, QEvent* event) {
  if (stroking() && (event->type() == QEvent::ShortcutOverride || event->type() == QEvent::KeyPress)) {
    auto* k = static_cast<QKeyEvent*>(event);
    if (k->matches(QKeySequence::Undo) || k->matches(QKeySequence::Redo) ||
        k->keyCombination() == QKeyCombination(Qt::CTRL | Qt::Key_Y)) {
      event->accept();
      return true;
    }
  }
  return QObject::eventFilter(watched, event);
}

void TerrainTool::drawOverlay(const scene::SceneState& state, render::Overlay& overlay) const {
  if (!active() || !hover_) return;
  const scene::TerrainAsset* t = scene::terrainOf(state, hover_->entity);
  if (!t) return;
  const terrain::Heightfield& hf = t->data->heights();
  const glm::dvec3 base = scene::terrainWorldOrigin(state, hover_->entity);
  const glm::dvec2 c = hover_->hit.local;
  // Lifted by a fraction of the radius so the line is not buried in the
  // ground between the points that follow it.
  const double lift = std::max(0.02, settings_.radius * 0.01);
  auto ring = [&](double radius, const glm::vec4& colour) {
    glm::dvec3 prev{};
    for (int i = 0; i <= kCircleSegments; ++i) {
      const double a = 2.0 * M_PI * i / kCircleSegments;
      const glm::dvec2 p = c + radius * glm::dvec2(std::cos(a), std::sin(a));
      const glm::dvec3 w = base + glm::dvec3(p, double(hf.heightAtLocal(p)) + lift);
      if (i) overlay.line(prev, w, colour);
      prev = w;
    }
  };
  const bool erase = settings_.erase && (kind_ == TerrainToolKind::Paint || kind_ == TerrainToolKind::Holes);
  const glm::vec4 outer = erase ? glm::vec4(1.0f, 0.45f, 0.3f, 0.95f) : glm::vec4(1.0f, 0.85f, 0.2f, 0.95f);
  ring(settings_.radius, outer);
  const double inner = settings_.radius * (1.0 - double(settings_.falloff.falloff));
  if (inner > settings_.radius * 0.02) ring(inner, glm::vec4(outer.r, outer.g, outer.b, 0.45f));
  // The centre, and the ramp's line while it is dragged.
  const glm::dvec3 centre = base + glm::dvec3(c, double(hf.heightAtLocal(c)) + lift);
  overlay.line(centre - glm::dvec3(0, 0, settings_.radius * 0.05), centre + glm::dvec3(0, 0, settings_.radius * 0.15), outer);
  if (rampStart_ && rampEnd_) {
    overlay.line(base + *rampStart_ + glm::dvec3(0, 0, lift), base + *rampEnd_ + glm::dvec3(0, 0, lift),
                 glm::vec4(0.3f, 0.9f, 1.0f, 1.0f));
  }
}

}  // namespace hs::app
