#include "app/timeline_time_axis.h"

#include <algorithm>
#include <cmath>

#include <QPainter>

namespace hs::app {

void TimeWindow::setWindow(double start, double end) {
  if (!(end - start > 1e-3) || !std::isfinite(start) || !std::isfinite(end)) return;
  if (start == start_ && end == end_) return;
  start_ = start;
  end_ = end;
  emit changed();
}

void TimeWindow::zoom(double factor, double anchor) {
  const double span = std::clamp((end_ - start_) * factor, 0.05, 1e7);
  const double a = (anchor - start_) / (end_ - start_);
  setWindow(anchor - a * span, anchor - a * span + span);
}

namespace {

// A tick spacing in frames that leaves at least ~60 px between labels.
int64_t labelStep(const TimeAxis& axis, double fps) {
  const double pxPerFrame = axis.pixelsPerSecond() / fps;
  static const int64_t steps[] = {1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 1200, 3000, 6000, 18000, 36000};
  for (int64_t s : steps)
    if (s * pxPerFrame >= 60.0) return s;
  return 108000;
}

}  // namespace

void paintTimeBackground(QPainter& p, const QRect& area, const TimeAxis& axis, const RulerMarks& m) {
  const double fps = m.rate.fps();
  auto xf = [&](int64_t f) { return axis.x(sequencer::frameTime(f, m.rate)); };
  // Outside the sequence's range: darker.
  const double a = xf(m.rangeFirst), b = xf(m.rangeLast);
  p.fillRect(QRectF(area.left(), area.top(), std::max(0.0, a - area.left()), area.height()), QColor(0, 0, 0, 60));
  p.fillRect(QRectF(b, area.top(), std::max(0.0, area.right() - b), area.height()), QColor(0, 0, 0, 60));
  if (m.looping && (m.loopFirst != m.rangeFirst || m.loopLast != m.rangeLast))
    p.fillRect(QRectF(xf(m.loopFirst), area.top(), xf(m.loopLast) - xf(m.loopFirst), area.height()),
               QColor(90, 140, 220, 28));
  // Faint lines at the label ticks.
  const int64_t step = labelStep(axis, fps);
  const int64_t first = int64_t(std::floor(axis.start * fps / double(step))) * step;
  p.setPen(QColor(255, 255, 255, 14));
  for (int64_t f = first; sequencer::frameTime(f, m.rate) <= axis.end; f += step) p.drawLine(QPointF(xf(f), area.top()), QPointF(xf(f), area.bottom()));
}

void paintRuler(QPainter& p, const QRect& ruler, const TimeAxis& axis, const RulerMarks& m) {
  const double fps = m.rate.fps();
  p.fillRect(ruler, QColor(44, 45, 48));
  const int64_t step = labelStep(axis, fps);
  const int64_t minor = std::max<int64_t>(1, step / 5);
  const int64_t first = int64_t(std::floor(axis.start * fps / double(minor))) * minor;
  p.setFont(QFont(p.font().family(), 8));
  for (int64_t f = first;; f += minor) {
    const double t = sequencer::frameTime(f, m.rate);
    if (t > axis.end) break;
    const double x = axis.x(t);
    if (x < ruler.left()) continue;
    const bool label = f % step == 0;
    p.setPen(QColor(150, 152, 158));
    p.drawLine(QPointF(x, ruler.bottom() - (label ? 8 : 4)), QPointF(x, ruler.bottom()));
    if (label) p.drawText(QPointF(x + 3, ruler.top() + 11), QString::number(f));
  }
  if (m.looping) {
    p.setPen(QPen(QColor(90, 140, 220), 2));
    const double a = axis.x(sequencer::frameTime(m.loopFirst, m.rate)), b = axis.x(sequencer::frameTime(m.loopLast, m.rate));
    p.drawLine(QPointF(a, ruler.bottom() - 1), QPointF(b, ruler.bottom() - 1));
  }
}

void paintPlayhead(QPainter& p, const QRect& all, const TimeAxis& axis, const RulerMarks& m) {
  const double x = axis.x(sequencer::frameTime(m.currentFrame, m.rate));
  if (x < axis.left || x > axis.left + axis.width) return;
  p.setPen(QPen(QColor(230, 80, 60), 1.5));
  p.drawLine(QPointF(x, all.top()), QPointF(x, all.bottom()));
  const QString label = QString::number(m.currentFrame);
  const QRectF box(x - 18, all.top() + 1, 36, 14);
  p.fillRect(box, QColor(230, 80, 60));
  p.setPen(Qt::white);
  p.drawText(box, Qt::AlignCenter, label);
}

}  // namespace hs::app
