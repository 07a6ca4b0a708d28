#include "app/time_keys_editor.h"

#include <algorithm>
#include <cmath>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include "app/curve_plot.h"

#include "core/params.h"
#include "particles/emitter.h"

namespace hs::app {

namespace {

constexpr double kPickPixels = 7.0;
constexpr double kNewBurst = 10.0;  // a new burst's count

// The value limits, from the declarations the file's reader checks with.
const ParamDecl& valueDecl(TimeKeysEditor::Kind kind) {
  switch (kind) {
    case TimeKeysEditor::Kind::Rate: return paramIn(particles::emitterParamDecls(), "rate_per_s");
    case TimeKeysEditor::Kind::Wind: return paramIn(particles::emitterParamDecls(), "wind_m_per_s");
    case TimeKeysEditor::Kind::Bursts: break;
  }
  return particles::burstCountDecl();
}

// The wind's components, in the viewport's axis colours.
QColor channelColour(int c) {
  static const QColor colours[3] = {QColor(220, 70, 60), QColor(70, 170, 70), QColor(70, 110, 230)};
  return colours[std::clamp(c, 0, 2)];
}

}  // namespace

TimeKeysEditor::TimeKeysEditor(Kind kind, QWidget* parent) : QWidget(parent), kind_(kind) {
  setFocusPolicy(Qt::ClickFocus);
  const char* what = kind == Kind::Rate   ? "Rate over scene time (particles per second)"
                     : kind == Kind::Wind ? "Wind over scene time (x red, y green, z blue; m/s)"
                                          : "Bursts over scene time (particles at once)";
  setToolTip(QString("%1: click to add a key, drag to move, right-click or Delete to remove").arg(what));
}

void TimeKeysEditor::setKeys(const Json& rows, const std::vector<double>& constant) {
  if (dragging_) return;  // the document's echo of our own drag: keep the gesture
  rows_.clear();
  const size_t n = kind_ == Kind::Wind ? 4 : 2;
  if (rows.is_array())
    for (const Json& r : rows) {
      if (!r.is_array() || r.size() != n) continue;
      std::vector<double> row;
      for (const Json& v : r) row.push_back(v.is_number() ? v.get<double>() : 0.0);
      rows_.push_back(std::move(row));
    }
  constant_ = constant;
  constant_.resize(size_t(channels()), 0.0);
  if (selected_ >= int(rows_.size())) selected_ = -1;
  fitRange();
  update();
}

Json TimeKeysEditor::keys() const {
  Json out = Json::array();
  for (const auto& r : rows_) {
    Json row = Json::array();
    for (size_t c = 0; c < r.size(); ++c) {
      if (kind_ == Kind::Bursts && c == 1)
        row.push_back(int64_t(std::llround(r[c])));
      else
        row.push_back(r[c]);
    }
    out.push_back(std::move(row));
  }
  return out;
}

void TimeKeysEditor::setSpan(double t0, double t1) {
  if (!(t1 > t0) || dragging_) return;
  t0_ = t0, t1_ = t1;
  update();
}

void TimeKeysEditor::setPlayhead(double t) {
  playhead_ = t;
  update();
}

void TimeKeysEditor::fitRange() {
  double m = 0.0;
  for (const auto& r : rows_)
    for (size_t c = 1; c < r.size(); ++c) m = std::max(m, std::abs(r[c]));
  if (kind_ != Kind::Bursts)
    for (double v : constant_) m = std::max(m, std::abs(v));
  const double top = std::max(kind_ == Kind::Bursts ? 10.0 : 1.0, 1.25 * m);
  hi_ = top;
  lo_ = kind_ == Kind::Wind ? -top : 0.0;
}

QRectF TimeKeysEditor::plot() const { return QRectF(8, 6, width() - 16, height() - 12); }

QPointF TimeKeysEditor::pointAt(double t, double value) const {
  const QRectF r = plot();
  return {r.left() + (t - t0_) / (t1_ - t0_) * r.width(), r.bottom() - (value - lo_) / (hi_ - lo_) * r.height()};
}

double TimeKeysEditor::timeAt(double x) const {
  const QRectF r = plot();
  return t0_ + (x - r.left()) / r.width() * (t1_ - t0_);
}

double TimeKeysEditor::valueAt(double y) const {
  const QRectF r = plot();
  return lo_ + (r.bottom() - y) / r.height() * (hi_ - lo_);
}

QPointF TimeKeysEditor::keyPoint(int i, int channel) const {
  const auto& row = rows_[size_t(i)];
  return pointAt(row[0], row[size_t(1 + std::clamp(channel, 0, channels() - 1))]);
}

std::vector<double> TimeKeysEditor::sample(double t) const {
  if (kind_ == Kind::Bursts) return {t, kNewBurst};
  if (!rows_.empty()) return rowAt(rows_, t);
  std::vector<double> r{t};
  r.insert(r.end(), constant_.begin(), constant_.end());  // no keys: the constant
  return r;
}

bool TimeKeysEditor::keyNear(const QPointF& p, int& key, int& channel) const {
  double best = kPickPixels;
  key = -1;
  for (int i = 0; i < int(rows_.size()); ++i)
    for (int c = 0; c < channels(); ++c) {
      const QPointF k = keyPoint(i, c);
      const double d = std::hypot(k.x() - p.x(), k.y() - p.y());
      if (d <= best) best = d, key = i, channel = c;
    }
  return key >= 0;
}

void TimeKeysEditor::moveKey(int i, const QPointF& p) {
  const ParamDecl& time = particles::keyTimeDecl();
  const ParamDecl& value = valueDecl(kind_);
  auto& row = rows_[size_t(i)];
  double t = std::clamp(timeAt(p.x()), time.min, time.max);
  if (kind_ != Kind::Bursts) {
    // Strictly between the neighbours: the reader refuses coincident times.
    const double gap = 1e-3 * (t1_ - t0_) / std::max(1.0, plot().width());
    if (i > 0) t = std::max(t, rows_[size_t(i) - 1][0] + gap);
    if (i + 1 < int(rows_.size())) t = std::min(t, rows_[size_t(i) + 1][0] - gap);
  }
  row[0] = t;
  double v = std::clamp(valueAt(p.y()), value.min, value.max);
  if (kind_ == Kind::Bursts) v = std::round(v);
  row[size_t(1 + channel_)] = v;
  update();
}

void TimeKeysEditor::removeKey(int i) {
  rows_.erase(rows_.begin() + i);
  selected_ = -1;
  emit edited(keys());
  fitRange();
  update();
}

void TimeKeysEditor::mousePressEvent(QMouseEvent* e) {
  const QPointF p = e->position();
  int k = -1, c = 0;
  const bool hit = keyNear(p, k, c);
  if (e->button() == Qt::RightButton) {
    if (hit) removeKey(k);
    return;
  }
  if (e->button() != Qt::LeftButton) return;
  if (hit) {
    selected_ = k;
    channel_ = c;
  } else {
    // A new key at the click's time with the list's value there, then dragged.
    const double t = timeAt(p.x());
    std::vector<double> row = sample(t);
    // The wind's component nearest the click is the one dragged.
    channel_ = 0;
    if (kind_ == Kind::Wind) {
      double best = 1e300;
      for (int ch = 0; ch < 3; ++ch) {
        const double d = std::abs(pointAt(t, row[size_t(1 + ch)]).y() - p.y());
        if (d < best) best = d, channel_ = ch;
      }
    }
    // Bursts keep their order (a burst's place is its particles' stream:
    // moving one would change the others' particles): a new one goes last.
    const auto at = kind_ == Kind::Bursts
                        ? rows_.end()
                        : std::lower_bound(rows_.begin(), rows_.end(), t,
                                           [](const std::vector<double>& a, double v) { return a[0] < v; });
    if (kind_ != Kind::Bursts && at != rows_.end() && (*at)[0] == t) return;  // on a key's time
    selected_ = int(at - rows_.begin());
    rows_.insert(at, std::move(row));
    moveKey(selected_, p);
  }
  dragging_ = true;
  update();
}

void TimeKeysEditor::mouseMoveEvent(QMouseEvent* e) {
  if (!dragging_ || selected_ < 0) return;
  moveKey(selected_, e->position());
  const auto& row = rows_[size_t(selected_)];
  setToolTip(QString("t %1 s, %2").arg(row[0], 0, 'f', 3).arg(row[size_t(1 + channel_)], 0, 'f', 3));
}

void TimeKeysEditor::mouseReleaseEvent(QMouseEvent* e) {
  if (!dragging_ || e->button() != Qt::LeftButton) return;
  dragging_ = false;
  emit edited(keys());
  fitRange();
  update();
}

void TimeKeysEditor::keyPressEvent(QKeyEvent* e) {
  if (isDeleteKey(e) && selected_ >= 0) return removeKey(selected_);
  QWidget::keyPressEvent(e);
}

void TimeKeysEditor::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QRectF r = plot();
  paintPlotBackground(p, *this, r);
  p.drawLine(pointAt(t0_, 0.0), pointAt(t1_, 0.0));  // zero
  p.setPen(palette().color(QPalette::PlaceholderText));
  p.drawText(r.adjusted(2, 0, -2, 0), Qt::AlignTop | Qt::AlignRight, QString::number(hi_, 'g', 3));
  p.drawText(r.adjusted(2, 0, -2, 0), Qt::AlignBottom | Qt::AlignLeft, QString("%1 s").arg(t0_, 0, 'g', 4));
  p.drawText(r.adjusted(2, 0, -2, 0), Qt::AlignBottom | Qt::AlignRight, QString("%1 s").arg(t1_, 0, 'g', 4));

  // The playhead.
  p.setPen(QPen(QColor(230, 160, 40), 1.5));
  p.drawLine(pointAt(playhead_, lo_), pointAt(playhead_, hi_));

  const QColor highlight = palette().color(QPalette::Highlight), text = palette().color(QPalette::Text);
  if (kind_ == Kind::Bursts) {
    for (int i = 0; i < int(rows_.size()); ++i) {
      p.setPen(QPen(i == selected_ ? highlight : text, i == selected_ ? 2.5 : 1.5));
      p.drawLine(pointAt(rows_[size_t(i)][0], 0.0), keyPoint(i));
      p.setBrush(text);
      p.drawEllipse(keyPoint(i), 4.0, 4.0);
    }
    return;
  }
  // Each channel's line, held outside its keys; no keys: the constant, dashed.
  for (int c = 0; c < channels(); ++c) {
    const QColor colour = kind_ == Kind::Wind ? channelColour(c) : highlight;
    QPainterPath path;
    if (rows_.empty()) {
      path.moveTo(pointAt(t0_, constant_[size_t(c)]));
      path.lineTo(pointAt(t1_, constant_[size_t(c)]));
    } else {
      path.moveTo(pointAt(std::min(t0_, rows_.front()[0]), rows_.front()[size_t(1 + c)]));
      for (int i = 0; i < int(rows_.size()); ++i) path.lineTo(keyPoint(i, c));
      path.lineTo(pointAt(std::max(t1_, rows_.back()[0]), rows_.back()[size_t(1 + c)]));
    }
    p.setPen(QPen(colour, 2, rows_.empty() ? Qt::DashLine : Qt::SolidLine));
    p.setBrush(Qt::NoBrush);
    p.drawPath(path);
    for (int i = 0; i < int(rows_.size()); ++i) {
      const bool sel = i == selected_ && (kind_ != Kind::Wind || c == channel_);
      p.setPen(QPen(sel ? highlight : text, sel ? 2.5 : 1.2));
      p.setBrush(colour);
      p.drawEllipse(keyPoint(i, c), 4.0, 4.0);
    }
  }
}

}  // namespace hs::app
