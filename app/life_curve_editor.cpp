#include "app/life_curve_editor.h"

#include <algorithm>
#include <cmath>

#include <QColorDialog>
#include <QKeyEvent>
#include <QLinearGradient>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include "app/curve_plot.h"

namespace hs::app {

namespace {

constexpr double kPickPixels = 7.0;
constexpr double kMinGap = 1e-3;   // between neighbouring keys' x: strictly increasing
constexpr double kMaxSize = 1e4;   // the size multiplier's declared maximum (particles/emitter.cpp)
constexpr int kStrip = 12;         // the colour strip's height

// A linear HDR colour shown on screen: scaled into range by its largest
// component (fire's 4x orange shows as orange), then sRGB-ish gamma.
QColor displayColour(double r, double g, double b) {
  const double m = std::max({r, g, b, 1.0});
  auto c = [m](double v) { return int(std::lround(255.0 * std::pow(std::clamp(v / m, 0.0, 1.0), 1.0 / 2.2))); };
  return QColor(c(r), c(g), c(b));
}

}  // namespace

LifeCurveEditor::LifeCurveEditor(Kind kind, QWidget* parent) : QWidget(parent), kind_(kind) {
  setFocusPolicy(Qt::ClickFocus);
  setMouseTracking(false);
  setToolTip(kind == Kind::Size
                 ? "Size over life: click to add a key, drag to move, right-click or Delete to remove"
                 : "Colour and opacity over life: click to add a key, drag to move (height: opacity), "
                   "double-click to pick its colour, right-click or Delete to remove");
}

void LifeCurveEditor::setKeys(const Json& rows) {
  if (dragging_) return;  // the document's echo of our own drag: keep the gesture
  rows_.clear();
  const size_t n = kind_ == Kind::Size ? 2 : 5;
  if (rows.is_array())
    for (const Json& r : rows) {
      if (!r.is_array() || r.size() != n) continue;
      std::vector<double> row;
      for (const Json& v : r) row.push_back(v.is_number() ? v.get<double>() : 0.0);
      rows_.push_back(std::move(row));
    }
  if (selected_ >= int(rows_.size())) selected_ = -1;
  fitRange();
  update();
}

Json LifeCurveEditor::keys() const {
  Json out = Json::array();
  for (const auto& r : rows_) {
    Json row = Json::array();
    for (double v : r) row.push_back(v);
    out.push_back(std::move(row));
  }
  return out;
}

void LifeCurveEditor::fitRange() {
  if (kind_ == Kind::Colour) {
    top_ = 1.0;
    return;
  }
  double m = 1.0;
  for (const auto& r : rows_) m = std::max(m, r[1]);
  top_ = std::max(1.5, 1.25 * m);
}

QRectF LifeCurveEditor::plot() const {
  const double bottom = kind_ == Kind::Colour ? kStrip + 4 : 0;
  return QRectF(8, 6, width() - 16, height() - 12 - bottom);
}

QPointF LifeCurveEditor::pointAt(double x, double value) const {
  const QRectF r = plot();
  return {r.left() + x * r.width(), r.bottom() - value / top_ * r.height()};
}

QPointF LifeCurveEditor::keyPoint(int i) const { return pointAt(rows_[size_t(i)][0], valueOf(rows_[size_t(i)])); }

std::vector<double> LifeCurveEditor::sample(double x) const {
  if (rows_.empty()) return kind_ == Kind::Size ? std::vector<double>{x, 1.0} : std::vector<double>{x, 1, 1, 1, 1};
  return rowAt(rows_, x);
}

int LifeCurveEditor::keyNear(const QPointF& p) const {
  int best = -1;
  double bestD = kPickPixels;
  for (int i = 0; i < int(rows_.size()); ++i) {
    const double d = std::hypot(keyPoint(i).x() - p.x(), keyPoint(i).y() - p.y());
    if (d <= bestD) best = i, bestD = d;
  }
  return best;
}

void LifeCurveEditor::moveKey(int i, const QPointF& p) {
  const QRectF r = plot();
  auto& row = rows_[size_t(i)];
  const double lo = i > 0 ? rows_[size_t(i) - 1][0] + kMinGap : 0.0;
  const double hi = i + 1 < int(rows_.size()) ? rows_[size_t(i) + 1][0] - kMinGap : 1.0;
  row[0] = std::clamp((p.x() - r.left()) / r.width(), lo, std::max(lo, hi));
  const double v = (r.bottom() - p.y()) / r.height() * top_;
  row.back() = std::clamp(v, 0.0, kind_ == Kind::Size ? kMaxSize : 1.0);
  update();
}

void LifeCurveEditor::removeKey(int i) {
  rows_.erase(rows_.begin() + i);
  selected_ = -1;
  emit edited(keys());
  update();
}

void LifeCurveEditor::mousePressEvent(QMouseEvent* e) {
  const QPointF p = e->position();
  const int k = keyNear(p);
  if (e->button() == Qt::RightButton) {
    if (k >= 0) removeKey(k);
    return;
  }
  if (e->button() != Qt::LeftButton) return;
  if (k >= 0) {
    selected_ = k;
  } else {
    // A new key at the click's x with the curve's value there, then dragged.
    const QRectF r = plot();
    const double x = std::clamp((p.x() - r.left()) / r.width(), 0.0, 1.0);
    for (const auto& row : rows_)
      if (std::abs(row[0] - x) < kMinGap) return;  // on top of a key's x: that key is not here
    std::vector<double> row = sample(x);
    const auto at = std::lower_bound(rows_.begin(), rows_.end(), x,
                                     [](const std::vector<double>& a, double v) { return a[0] < v; });
    selected_ = int(at - rows_.begin());
    rows_.insert(at, std::move(row));
    moveKey(selected_, p);
  }
  dragging_ = true;
  update();
}

void LifeCurveEditor::mouseMoveEvent(QMouseEvent* e) {
  if (!dragging_ || selected_ < 0) return;
  moveKey(selected_, e->position());
  const auto& row = rows_[size_t(selected_)];
  setToolTip(QString("x %1, %2 %3")
                 .arg(row[0], 0, 'f', 3)
                 .arg(kind_ == Kind::Size ? "size" : "opacity")
                 .arg(row.back(), 0, 'f', 3));
}

void LifeCurveEditor::mouseReleaseEvent(QMouseEvent* e) {
  if (!dragging_ || e->button() != Qt::LeftButton) return;
  dragging_ = false;
  emit edited(keys());
  fitRange();
  update();
}

void LifeCurveEditor::mouseDoubleClickEvent(QMouseEvent* e) {
  if (kind_ != Kind::Colour) return mousePressEvent(e);
  const int k = keyNear(e->position());
  if (k < 0) return mousePressEvent(e);
  dragging_ = false;
  auto& row = rows_[size_t(k)];
  const double scale = std::max({row[1], row[2], row[3], 1.0});
  const QColor c = QColorDialog::getColor(
      QColor::fromRgbF(float(row[1] / scale), float(row[2] / scale), float(row[3] / scale)), this, "Key colour");
  if (!c.isValid()) return;
  row[1] = double(c.redF()) * scale, row[2] = double(c.greenF()) * scale, row[3] = double(c.blueF()) * scale;
  emit edited(keys());
  update();
}

void LifeCurveEditor::keyPressEvent(QKeyEvent* e) {
  if (isDeleteKey(e) && selected_ >= 0) return removeKey(selected_);
  QWidget::keyPressEvent(e);
}

void LifeCurveEditor::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QRectF r = plot();
  paintPlotBackground(p, *this, r);
  p.drawLine(pointAt(0, 1.0), pointAt(1, 1.0));  // multiplier 1 / opacity 1

  // The curve, held outside its keys; no keys: the fallback (1).
  QPainterPath path;
  if (rows_.empty()) {
    path.moveTo(pointAt(0, 1.0));
    path.lineTo(pointAt(1, 1.0));
  } else {
    path.moveTo(pointAt(0, valueOf(rows_.front())));
    for (int i = 0; i < int(rows_.size()); ++i) path.lineTo(keyPoint(i));
    path.lineTo(pointAt(1, valueOf(rows_.back())));
  }
  p.setPen(QPen(palette().color(QPalette::Highlight), 2, rows_.empty() ? Qt::DashLine : Qt::SolidLine));
  p.drawPath(path);

  if (kind_ == Kind::Colour) {
    const QRectF strip(r.left(), height() - kStrip - 3, r.width(), kStrip);
    QLinearGradient g(strip.topLeft(), strip.topRight());
    if (rows_.empty()) g.setColorAt(0, Qt::white);
    for (const auto& row : rows_) g.setColorAt(std::clamp(row[0], 0.0, 1.0), displayColour(row[1], row[2], row[3]));
    p.fillRect(strip, g);
    p.setPen(palette().color(QPalette::Mid));
    p.drawRect(strip);
  }
  for (int i = 0; i < int(rows_.size()); ++i) {
    const auto& row = rows_[size_t(i)];
    const QColor fill = kind_ == Kind::Colour ? displayColour(row[1], row[2], row[3]) : palette().color(QPalette::Text);
    p.setPen(QPen(i == selected_ ? palette().color(QPalette::Highlight) : palette().color(QPalette::Text), i == selected_ ? 2.5 : 1.2));
    p.setBrush(fill);
    p.drawEllipse(keyPoint(i), 4.5, 4.5);
  }
}

}  // namespace hs::app
