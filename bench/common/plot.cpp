#include "bench/common/plot.h"

#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace hs::bench {
namespace {

// QPainter needs fonts, and fonts need a QGuiApplication; a benchmark is a
// plain main(), so one is started here on the offscreen platform (no
// display needed) when the program has none.
void ensureGuiApplication() {
  if (QCoreApplication::instance()) return;
  static int argc = 3;
  static char arg0[] = "bench", arg1[] = "-platform", arg2[] = "offscreen";
  static char* argv[] = {arg0, arg1, arg2, nullptr};
  static std::unique_ptr<QGuiApplication> app(new QGuiApplication(argc, argv));
}

QColor qcolour(PlotColour c) { return QColor(c.r, c.g, c.b); }

// One axis: data range to pixels, and where the ticks go.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  // in data units (log: powers of ten)
  double p0 = 0, p1 = 1;  // pixels of lo and hi

  double pixel(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
  }
  bool shows(double v) const { return !log || v > 0; }

  // Log: whole decades around the data. Linear: a 1-2-5 step giving about
  // six ticks, the range widened to whole steps.
  void fit(double mn, double mx) {
    if (!(mn <= mx)) mn = mx = log ? 1.0 : 0.0;
    if (log) {
      lo = std::pow(10.0, std::floor(std::log10(mn)));
      hi = std::pow(10.0, std::ceil(std::log10(mx)));
      if (hi <= lo) hi = lo * 10.0;
      return;
    }
    if (mx == mn) mn -= 1.0, mx += 1.0;
    const double s = step(mn, mx);
    lo = std::floor(mn / s) * s;
    hi = std::ceil(mx / s) * s;
  }
  static double step(double mn, double mx) {
    const double raw = (mx - mn) / 6.0, p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
      if (m * p >= raw) return m * p;
    return 10.0 * p;
  }
  // (value, labelled) pairs: decades labelled and 2..9 between them, or the 1-2-5 steps.
  std::vector<std::pair<double, bool>> ticks() const {
    std::vector<std::pair<double, bool>> t;
    if (log) {
      for (double d = lo; d <= hi * 1.0000001; d *= 10.0)
        for (int k = 1; k < 10; ++k)
          if (k * d <= hi * 1.0000001) t.push_back({k * d, k == 1});
      return t;
    }
    const double s = step(lo, hi);
    for (double v = lo; v <= hi + 0.5 * s; v += s) t.push_back({std::abs(v) < 1e-12 * s ? 0.0 : v, true});
    return t;
  }
};

QString tickLabel(double v, bool log) {
  if (log) {
    const int e = int(std::lround(std::log10(v)));
    if (e >= -3 && e <= 4) return QString::number(v, 'g', 6);
    return QString("1e%1").arg(e);
  }
  return QString::number(v, 'g', 6);
}

void drawMarker(QPainter& p, QPointF c, PlotMarker m, double r) {
  switch (m) {
    case PlotMarker::Circle: p.drawEllipse(c, r, r); break;
    case PlotMarker::Square: p.drawRect(QRectF(c.x() - r, c.y() - r, 2 * r, 2 * r)); break;
    case PlotMarker::Triangle:
      p.drawPolygon(QPolygonF({QPointF(c.x(), c.y() - r * 1.2), QPointF(c.x() + r * 1.1, c.y() + r * 0.8),
                               QPointF(c.x() - r * 1.1, c.y() + r * 0.8)}));
      break;
    case PlotMarker::Diamond:
      p.drawPolygon(QPolygonF({QPointF(c.x(), c.y() - r * 1.3), QPointF(c.x() + r * 1.3, c.y()),
                               QPointF(c.x(), c.y() + r * 1.3), QPointF(c.x() - r * 1.3, c.y())}));
      break;
  }
}

void drawPanel(QPainter& p, const PlotPanel& panel, QRectF area) {
  const QColor ink(30, 30, 30), grid(225, 225, 225), minorGrid(240, 240, 240);
  QFont font = p.font();
  font.setPixelSize(14);
  p.setFont(font);
  const QFontMetricsF fm(font);
  const QRectF plot(area.left() + 90, area.top() + 40, area.width() - 90 - 24, area.height() - 40 - 64);

  Axis x{panel.logX}, y{panel.logY};
  double xmn = HUGE_VAL, xmx = -HUGE_VAL, ymn = HUGE_VAL, ymx = -HUGE_VAL;
  for (const PlotSeries& s : panel.series)
    for (const auto& [px, py] : s.points)
      if (std::isfinite(px) && std::isfinite(py) && x.shows(px) && y.shows(py)) {
        xmn = std::min(xmn, px), xmx = std::max(xmx, px);
        ymn = std::min(ymn, py), ymx = std::max(ymx, py);
      }
  x.fit(xmn, xmx);
  y.fit(ymn, ymx);
  x.p0 = plot.left(), x.p1 = plot.right();
  y.p0 = plot.bottom(), y.p1 = plot.top();

  // Grid and tick labels.
  for (const auto& [v, major] : x.ticks()) {
    const double px = x.pixel(v);
    p.setPen(QPen(major ? grid : minorGrid, 1));
    p.drawLine(QPointF(px, plot.top()), QPointF(px, plot.bottom()));
    p.setPen(QPen(ink, 1));
    p.drawLine(QPointF(px, plot.bottom()), QPointF(px, plot.bottom() + (major ? 6 : 3)));
    if (major) {
      const QString s = tickLabel(v, x.log);
      p.drawText(QPointF(px - fm.horizontalAdvance(s) / 2, plot.bottom() + 8 + fm.ascent()), s);
    }
  }
  for (const auto& [v, major] : y.ticks()) {
    const double py = y.pixel(v);
    p.setPen(QPen(major ? grid : minorGrid, 1));
    p.drawLine(QPointF(plot.left(), py), QPointF(plot.right(), py));
    p.setPen(QPen(ink, 1));
    p.drawLine(QPointF(plot.left() - (major ? 6 : 3), py), QPointF(plot.left(), py));
    if (major) {
      const QString s = tickLabel(v, y.log);
      p.drawText(QPointF(plot.left() - 10 - fm.horizontalAdvance(s), py + fm.ascent() / 2 - 1), s);
    }
  }
  p.setPen(QPen(ink, 1.5));
  p.drawLine(plot.bottomLeft(), plot.bottomRight());
  p.drawLine(plot.bottomLeft(), plot.topLeft());

  // Title and axis labels.
  QFont bold = font;
  bold.setPixelSize(16);
  bold.setBold(true);
  p.setFont(bold);
  p.drawText(QRectF(area.left(), area.top() + 6, area.width(), 28), Qt::AlignHCenter | Qt::AlignVCenter,
             QString::fromStdString(panel.title));
  p.setFont(font);
  p.drawText(QRectF(plot.left(), plot.bottom() + 32, plot.width(), 26), Qt::AlignHCenter | Qt::AlignVCenter,
             QString::fromStdString(panel.xLabel));
  p.save();
  p.translate(area.left() + 18, plot.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-plot.height() / 2, -12, plot.height(), 26), Qt::AlignHCenter | Qt::AlignVCenter,
             QString::fromStdString(panel.yLabel));
  p.restore();

  // Series, clipped to the plot; their point labels small beside the points.
  p.save();
  p.setClipRect(plot.adjusted(-8, -8, 8, 8));
  QFont small = font;
  small.setPixelSize(11);
  for (const PlotSeries& s : panel.series) {
    const QColor c = qcolour(s.colour);
    std::vector<QPointF> pts;
    std::vector<size_t> index;  // into s.points, of each point shown
    for (size_t i = 0; i < s.points.size(); ++i) {
      const auto [px, py] = s.points[i];
      if (!std::isfinite(px) || !std::isfinite(py) || !x.shows(px) || !y.shows(py)) continue;
      pts.emplace_back(x.pixel(px), y.pixel(py));
      index.push_back(i);
    }
    p.setPen(QPen(c, 2.2, s.dashed ? Qt::DashLine : Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
    p.setBrush(Qt::NoBrush);
    if (pts.size() > 1) p.drawPolyline(pts.data(), int(pts.size()));
    p.setPen(QPen(c, 1));
    p.setBrush(c);
    for (const QPointF& q : pts) drawMarker(p, q, s.marker, 4.5);
    p.setFont(small);
    for (size_t k = 0; k < pts.size(); ++k)
      if (index[k] < s.pointLabels.size())
        p.drawText(pts[k] + QPointF(7, -7), QString::fromStdString(s.pointLabels[index[k]]));
    p.setFont(font);
  }
  p.restore();

  // Legend, upper right, on white.
  double w = 0;
  for (const PlotSeries& s : panel.series) w = std::max(w, fm.horizontalAdvance(QString::fromStdString(s.name)));
  const double rowH = 22, legendW = w + 56, legendH = rowH * double(panel.series.size()) + 10;
  const QRectF box(plot.right() - legendW - 10, plot.top() + 10, legendW, legendH);
  if (!panel.series.empty()) {
    p.setPen(QPen(grid, 1));
    p.setBrush(QColor(255, 255, 255, 230));
    p.drawRect(box);
  }
  double ly = box.top() + 5 + rowH / 2;
  for (const PlotSeries& s : panel.series) {
    const QColor c = qcolour(s.colour);
    p.setPen(QPen(c, 2.2, s.dashed ? Qt::DashLine : Qt::SolidLine));
    p.drawLine(QPointF(box.left() + 8, ly), QPointF(box.left() + 38, ly));
    p.setPen(QPen(c, 1));
    p.setBrush(c);
    drawMarker(p, QPointF(box.left() + 23, ly), s.marker, 4.5);
    p.setPen(QPen(ink, 1));
    p.drawText(QPointF(box.left() + 46, ly + fm.ascent() / 2 - 1), QString::fromStdString(s.name));
    ly += rowH;
  }
}

}  // namespace

std::string savePlotPng(const std::vector<PlotPanel>& panels, const std::string& path, int panelWidth, int height) {
  if (panels.empty()) return "nothing to plot";
  if (panelWidth < 200 || height < 150) return "a plot needs at least 200 x 150 pixels a panel";
  ensureGuiApplication();
  QImage image(panelWidth * int(panels.size()), height, QImage::Format_RGB32);
  image.fill(Qt::white);
  {
    QPainter p(&image);
    p.setRenderHint(QPainter::Antialiasing);
    p.setRenderHint(QPainter::TextAntialiasing);
    for (size_t i = 0; i < panels.size(); ++i)
      drawPanel(p, panels[i], QRectF(double(i) * panelWidth, 0, panelWidth, height));
  }
  if (!image.save(QString::fromStdString(path), "PNG")) return path + ": cannot write the PNG";
  return {};
}

}  // namespace hs::bench
