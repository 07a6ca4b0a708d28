#include "app/timeline_curve_view.h"

#include <algorithm>
#include <cmath>

#include <QContextMenuEvent>
#include <QKeyEvent>
#include <QMenu>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>

#include "app/timeline_rows.h"

namespace hs::app {

namespace {

constexpr double kHit = 6.0;
const QColor kComponentColors[3] = {QColor(230, 90, 80), QColor(110, 200, 90), QColor(90, 150, 240)};

double componentOf(const sequencer::Track& t, double time, int c) {
  if (const auto* s = std::get_if<sequencer::ScalarTrack>(&t)) return sequencer::evaluate(*s, time).value_or(0.0);
  if (const auto* v = std::get_if<sequencer::VectorTrack>(&t)) return sequencer::evaluate(*v, time).value_or(glm::dvec3(0.0))[c];
  if (const auto* b = std::get_if<sequencer::StepTrack>(&t)) return sequencer::evaluate(*b, time).value_or(false) ? 1.0 : 0.0;
  return 0.0;
}

}  // namespace

TimelineCurveView::TimelineCurveView(TimelineActions& actions, TimeWindow& window, QWidget* parent)
    : QWidget(parent), actions_(actions), window_(window) {
  setObjectName("timelineCurveView");
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(200, 120);
  connect(&actions_.document(), &scene::Document::changed, this, qOverload<>(&QWidget::update));
  connect(&actions_.clock(), &TimelineClock::frameChanged, this, qOverload<>(&QWidget::update));
  connect(&actions_.keys(), &KeySelection::changed, this, qOverload<>(&QWidget::update));
  connect(&window_, &TimeWindow::changed, this, qOverload<>(&QWidget::update));
}

void TimelineCurveView::setTrack(scene::EntityId entity, const std::string& property) {
  entity_ = entity;
  property_ = property;
  frameCurve();
}

std::optional<sequencer::Track> TimelineCurveView::track() const {
  const sequencer::Binding* b = actions_.document().state().sequence.findBinding(entity_);
  if (!b) return std::nullopt;
  if (property_ == sequencer::kPathProgress) {
    if (!b->path) return std::nullopt;
    return sequencer::Track(b->path->progress);
  }
  for (const sequencer::Track& t : b->tracks)
    if (sequencer::trackProperty(t) == property_) return t;
  return std::nullopt;
}

int TimelineCurveView::components() const {
  const auto t = track();
  if (!t) return 0;
  if (std::holds_alternative<sequencer::ScalarTrack>(*t)) return 1;
  if (std::holds_alternative<sequencer::VectorTrack>(*t)) return 3;
  return 0;
}

std::vector<sequencer::KeyRef> TimelineCurveView::trackKeys() const {
  std::vector<sequencer::KeyRef> out;
  const size_t n = sequencer::keyTimes(actions_.document().state().sequence, entity_, property_).size();
  for (size_t i = 0; i < n; ++i) out.push_back({entity_, property_, i});
  return out;
}

void TimelineCurveView::frameCurve() {
  const auto t = track();
  double lo = INFINITY, hi = -INFINITY;
  if (t) {
    const int n = std::max(1, components());
    for (int c = 0; c < n; ++c)
      for (int i = 0; i <= 200; ++i) {
        const double time = window_.start() + (window_.end() - window_.start()) * i / 200.0;
        const double v = componentOf(*t, time, c);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  }
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;
  const double pad = std::max((hi - lo) * 0.12, 1e-3 * std::max(1.0, std::abs(hi)));
  low_ = lo - pad;
  high_ = hi + pad;
  update();
}

TimeAxis TimelineCurveView::axis() const {
  return TimeAxis{window_.start(), window_.end(), kValueAxisWidth, std::max(1, width() - kValueAxisWidth)};
}

double TimelineCurveView::y(double v) const {
  const double top = kRulerHeight + 8.0, bottom = height() - 8.0;
  return bottom - (v - low_) / (high_ - low_) * (bottom - top);
}

double TimelineCurveView::value(double py) const {
  const double top = kRulerHeight + 8.0, bottom = height() - 8.0;
  return low_ + (bottom - py) / (bottom - top) * (high_ - low_);
}

std::optional<QPointF> TimelineCurveView::keyPoint(const sequencer::KeyRef& key, int component) const {
  const sequencer::Sequence& seq = actions_.document().state().sequence;
  const auto t = sequencer::keyTime(seq, key);
  const auto v = sequencer::keyComponent(seq, key, component);
  if (!t || !v) return std::nullopt;
  return QPointF(axis().x(*t), y(*v));
}

double TimelineCurveView::handleSpan(const sequencer::KeyRef& key, bool out) const {
  const std::vector<double> times = sequencer::keyTimes(actions_.document().state().sequence, key.entity, key.property);
  const double t = times[key.index];
  double span = 0.0;
  if (out && key.index + 1 < times.size()) span = (times[key.index + 1] - t) / 3.0;
  if (!out && key.index > 0) span = (t - times[key.index - 1]) / 3.0;
  // At least ~30 px on screen, so a handle can be grabbed when zoomed out.
  return std::max(span, 30.0 / axis().pixelsPerSecond());
}

std::optional<QPointF> TimelineCurveView::handlePoint(const sequencer::KeyRef& key, int component, bool out) const {
  const sequencer::Sequence& seq = actions_.document().state().sequence;
  const auto p = keyPoint(key, component);
  const auto slopes = sequencer::keySlopes(seq, key, component);
  if (!p || !slopes) return std::nullopt;
  const double span = handleSpan(key, out) * (out ? 1.0 : -1.0);
  const double slope = out ? slopes->second : slopes->first;
  const double t = *sequencer::keyTime(seq, key) + span;
  const double v = *sequencer::keyComponent(seq, key, component) + slope * span;
  return QPointF(axis().x(t), y(v));
}

void TimelineCurveView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(36, 37, 40));
  const TimeAxis ax = axis();
  TimelineClock& clock = actions_.clock();
  const sequencer::Sequence& seq = actions_.document().state().sequence;
  const RulerMarks m{clock.frame(), seq.startFrame, seq.endFrame, clock.loopFirst(), clock.loopLast(), clock.looping(), seq.rate};
  const QRect area(kValueAxisWidth, kRulerHeight, width() - kValueAxisWidth, height() - kRulerHeight);
  paintTimeBackground(p, area, ax, m);
  // Value grid and labels.
  p.setFont(QFont(p.font().family(), 8));
  const double span = high_ - low_;
  const double raw = span / std::max(1.0, area.height() / 40.0);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
  for (double v = std::ceil(low_ / step) * step; v <= high_; v += step) {
    p.setPen(QColor(255, 255, 255, 16));
    p.drawLine(QPointF(kValueAxisWidth, y(v)), QPointF(width(), y(v)));
    p.setPen(QColor(150, 152, 158));
    p.drawText(QRectF(0, y(v) - 7, kValueAxisWidth - 4, 14), Qt::AlignRight | Qt::AlignVCenter, QString::number(v, 'g', 4));
  }
  const auto t = track();
  const scene::Entity* e = actions_.document().state().find(entity_);
  QString title = t ? QString("%1 — %2").arg(QString::fromStdString(e ? e->name : "?"), propertyLabel(property_))
                    : QString("Click a track's name in the timeline to see its curve here.");
  if (t && std::holds_alternative<sequencer::RotationTrack>(*t))
    title += "  (quaternion keys: retime them in the dope sheet; set them with the Rotation field's key button)";
  p.setPen(QColor(205, 206, 210));
  p.drawText(QRect(kValueAxisWidth + 6, kRulerHeight + 2, width(), 16), Qt::AlignLeft | Qt::AlignVCenter, title);
  if (t) {
    const bool onOff = std::holds_alternative<sequencer::StepTrack>(*t);
    const int n = onOff ? 1 : components();
    p.setClipRect(area);
    for (int c = 0; c < n; ++c) {
      QPainterPath path;
      for (int x = area.left(); x <= area.right(); x += 2) {
        const QPointF pt(x, y(componentOf(*t, ax.time(x), c)));
        if (x == area.left()) path.moveTo(pt);
        else path.lineTo(pt);
      }
      p.setPen(QPen(n == 1 ? QColor(230, 230, 235) : kComponentColors[c], 1.5));
      p.setBrush(Qt::NoBrush);
      p.drawPath(path);
    }
    const KeySelection& sel = actions_.keys();
    for (const sequencer::KeyRef& k : trackKeys()) {
      const bool selected = sel.contains(k);
      for (int c = 0; c < std::max(1, n); ++c) {
        std::optional<QPointF> pt = keyPoint(k, c);
        if (!pt) pt = QPointF(ax.x(*sequencer::keyTime(seq, k)), y(componentOf(*t, *sequencer::keyTime(seq, k), c)));
        if (selected && components() > 0) {
          // The key's slopes, into the segments on either side.
          for (bool out : {false, true}) {
            const auto hp = handlePoint(k, c, out);
            if (!hp) continue;
            p.setPen(QPen(QColor(255, 200, 120), 1));
            p.drawLine(*pt, *hp);
            p.fillRect(QRectF(hp->x() - 3, hp->y() - 3, 6, 6), QColor(255, 200, 120));
          }
        }
        p.setPen(QColor(20, 20, 22));
        p.setBrush(selected ? QColor(255, 160, 40) : QColor(235, 236, 240));
        p.drawEllipse(*pt, 4.0, 4.0);
      }
    }
    p.setClipping(false);
  }
  paintRuler(p, QRect(kValueAxisWidth, 0, width() - kValueAxisWidth, kRulerHeight), ax, m);
  p.setClipRect(area.adjusted(0, -kRulerHeight, 0, 0));
  paintPlayhead(p, rect(), ax, m);
}

void TimelineCurveView::mousePressEvent(QMouseEvent* e) {
  setFocus(Qt::MouseFocusReason);
  if (e->button() != Qt::LeftButton) return;
  const QPointF pos = e->position();
  pressPos_ = pos;
  moved_ = false;
  if (pos.y() < kRulerHeight && pos.x() >= kValueAxisWidth) {
    drag_ = Drag::Scrub;
    actions_.clock().setFrame(sequencer::frameAtTime(axis().time(pos.x()), actions_.document().state().sequence.rate));
    return;
  }
  const int n = components();
  start_ = actions_.document().state().sequence;
  gesture_ = actions_.newGestureKey();
  KeySelection& sel = actions_.keys();
  // Handles of selected keys first: they sit beside the keys.
  for (const sequencer::KeyRef& k : trackKeys()) {
    if (!sel.contains(k)) continue;
    for (int c = 0; c < n; ++c)
      for (bool out : {false, true})
        if (const auto hp = handlePoint(k, c, out); hp && QLineF(*hp, pos).length() <= kHit) {
          drag_ = Drag::Handle;
          dragKey_ = k;
          dragComponent_ = c;
          dragOut_ = out;
          dragBroken_ = (e->modifiers() & Qt::AltModifier) != 0;
          return;
        }
  }
  for (const sequencer::KeyRef& k : trackKeys())
    for (int c = 0; c < std::max(1, n); ++c) {
      const auto kp = keyPoint(k, c);
      const double kx = axis().x(*sequencer::keyTime(start_, k));
      const bool hit = kp ? QLineF(*kp, pos).length() <= kHit : std::abs(kx - pos.x()) <= kHit;
      if (!hit) continue;
      if (e->modifiers() & Qt::ShiftModifier) sel.toggle(k);
      else if (!sel.contains(k)) sel.set({k});
      drag_ = Drag::Key;
      dragKey_ = k;
      dragComponent_ = c;
      startTime_ = *sequencer::keyTime(start_, k);
      startValue_ = sequencer::keyComponent(start_, k, c).value_or(0.0);
      return;
    }
  if (!(e->modifiers() & Qt::ShiftModifier)) sel.clear();
  drag_ = Drag::None;
}

void TimelineCurveView::mouseMoveEvent(QMouseEvent* e) {
  const QPointF pos = e->position();
  if (drag_ == Drag::Scrub) {
    actions_.clock().setFrame(sequencer::frameAtTime(axis().time(pos.x()), actions_.document().state().sequence.rate));
    return;
  }
  if (drag_ == Drag::None) return;
  if (!moved_ && (pos - pressPos_).manhattanLength() <= 3.0) return;
  moved_ = true;
  sequencer::Sequence s = start_;
  if (drag_ == Drag::Key) {
    const double dt = (pos.x() - pressPos_.x()) / axis().pixelsPerSecond();
    const std::vector<sequencer::KeyRef> moved = sequencer::moveKeysSnapped(s, {dragKey_}, dt, s.rate);
    if (moved.empty()) return;
    if (components() > 0) sequencer::setKeyComponent(s, moved[0], dragComponent_, startValue_ + value(pos.y()) - value(pressPos_.y()));
    actions_.applyGesture(s, "Edit key", gesture_);
    actions_.keys().set(moved);
  } else {
    const double kt = *sequencer::keyTime(s, dragKey_);
    const double kv = sequencer::keyComponent(s, dragKey_, dragComponent_).value_or(0.0);
    double dt = axis().time(pos.x()) - kt;
    // A handle stays on its own side of the key.
    const double minDt = 2.0 / axis().pixelsPerSecond();
    dt = dragOut_ ? std::max(dt, minDt) : std::min(dt, -minDt);
    const double slope = (value(pos.y()) - kv) / dt;
    sequencer::setKeySlope(s, dragKey_, dragComponent_, dragOut_ ? std::nullopt : std::optional(slope),
                           dragOut_ ? std::optional(slope) : std::nullopt, dragBroken_);
    actions_.applyGesture(s, "Edit tangent", gesture_);
  }
}

void TimelineCurveView::mouseReleaseEvent(QMouseEvent*) { drag_ = Drag::None; }

void TimelineCurveView::wheelEvent(QWheelEvent* e) {
  const double steps = e->angleDelta().y() / 120.0;
  if (steps == 0.0) return;
  if (e->modifiers() & Qt::ControlModifier) {
    const double anchor = value(e->position().y()), f = std::pow(0.85, steps);
    low_ = anchor - (anchor - low_) * f;
    high_ = anchor + (high_ - anchor) * f;
    update();
  } else if (e->modifiers() & Qt::ShiftModifier) {
    window_.pan(-steps * 0.1 * (window_.end() - window_.start()));
  } else {
    window_.zoom(std::pow(0.85, steps), axis().time(e->position().x()));
  }
  e->accept();
}

void TimelineCurveView::keyPressEvent(QKeyEvent* e) {
  if (e->matches(QKeySequence::Copy)) return actions_.copySelected();
  if (e->matches(QKeySequence::Paste)) return void(actions_.paste());
  switch (e->key()) {
    case Qt::Key_F: frameCurve(); return;
    case Qt::Key_Delete:
    case Qt::Key_Backspace: actions_.deleteSelected(); return;
    case Qt::Key_Left: actions_.clock().stepFrames(-1); return;
    case Qt::Key_Right: actions_.clock().stepFrames(1); return;
    case Qt::Key_Space: actions_.clock().togglePlay(); return;
    case Qt::Key_Escape:
      if (drag_ == Drag::Key || drag_ == Drag::Handle) {
        actions_.applyGesture(start_, "Edit key", gesture_);  // back to the start: the step disappears
        drag_ = Drag::None;
      }
      return;
    default: QWidget::keyPressEvent(e);
  }
}

void TimelineCurveView::contextMenuEvent(QContextMenuEvent* e) {
  QMenu* menu = actions_.contextMenu(this);
  menu->addSeparator();
  menu->addAction("&Frame Curve (F)", this, [this] { frameCurve(); });
  menu->setAttribute(Qt::WA_DeleteOnClose);
  menu->popup(e->globalPos());
}

}  // namespace hs::app
