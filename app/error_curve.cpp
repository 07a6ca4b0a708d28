#include "app/error_curve.h"

#include <algorithm>
#include <cmath>

#include <QPainter>
#include <QPainterPath>

namespace hs::app {
namespace {

QString compactCount(double n) {
  if (n >= 1e6) return QString::number(n / 1e6, 'g', 3) + "M";
  if (n >= 1e3) return QString::number(n / 1e3, 'g', 3) + "k";
  return QString::number(n, 'f', 0);
}

}  // namespace

ErrorCurve::ErrorCurve(QWidget* parent) : QWidget(parent) {
  setObjectName("previewCurve");
  setMinimumHeight(160);
}

void ErrorCurve::setPoints(std::vector<PreviewPoint> points, size_t trianglesIn) {
  points_ = std::move(points);
  trianglesIn_ = trianglesIn;
  update();
}

void ErrorCurve::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(0x2b, 0x2c, 0x2f));
  const QRectF plot = QRectF(rect()).adjusted(58, 10, -12, -30);
  p.setPen(QColor(0x8f, 0x90, 0x95));
  p.drawRect(plot);

  // Only points with an error can go on a log scale (a target at or above
  // the input's size changes nothing and measures 0).
  std::vector<const PreviewPoint*> pts;
  for (const PreviewPoint& pt : points_)
    if (pt.triangles > 0 && pt.hausdorffRel > 0) pts.push_back(&pt);
  if (pts.empty()) {
    p.drawText(plot, Qt::AlignCenter, points_.empty() ? "Run Preview to see triangles against error" : "No error to show");
    return;
  }
  double tMin = 1e300, tMax = 0, eMin = 1e300, eMax = 0;
  for (const PreviewPoint* pt : pts) {
    tMin = std::min(tMin, double(pt->triangles));
    tMax = std::max(tMax, double(pt->triangles));
    eMin = std::min(eMin, pt->hausdorffRel);
    eMax = std::max(eMax, pt->hausdorffRel);
  }
  if (trianglesIn_ > 0) tMax = std::max(tMax, double(trianglesIn_));
  // Whole decades around the data, so the axes read at a glance.
  const double lt0 = std::floor(std::log10(tMin)), lt1 = std::max(lt0 + 1, std::ceil(std::log10(tMax)));
  const double le0 = std::floor(std::log10(eMin)), le1 = std::max(le0 + 1, std::ceil(std::log10(eMax)));
  auto map = [&](double tris, double err) {
    const double x = (std::log10(tris) - lt0) / (lt1 - lt0);
    const double y = (std::log10(err) - le0) / (le1 - le0);
    return QPointF(plot.left() + x * plot.width(), plot.bottom() - y * plot.height());
  };

  QFont small = font();
  small.setPointSizeF(std::max(6.0, small.pointSizeF() - 1.5));
  p.setFont(small);
  for (double d = lt0; d <= lt1; d += 1) {
    const QPointF a = map(std::pow(10.0, d), std::pow(10.0, le0));
    p.setPen(QColor(0x44, 0x45, 0x49));
    p.drawLine(QPointF(a.x(), plot.top()), QPointF(a.x(), plot.bottom()));
    p.setPen(QColor(0xa9, 0xaa, 0xae));
    p.drawText(QRectF(a.x() - 30, plot.bottom() + 2, 60, 14), Qt::AlignHCenter | Qt::AlignTop, compactCount(std::pow(10.0, d)));
  }
  for (double d = le0; d <= le1; d += 1) {
    const QPointF a = map(std::pow(10.0, lt0), std::pow(10.0, d));
    p.setPen(QColor(0x44, 0x45, 0x49));
    p.drawLine(QPointF(plot.left(), a.y()), QPointF(plot.right(), a.y()));
    p.setPen(QColor(0xa9, 0xaa, 0xae));
    p.drawText(QRectF(0, a.y() - 7, plot.left() - 4, 14), Qt::AlignRight | Qt::AlignVCenter,
               QString::number(std::pow(10.0, d) * 100.0, 'g', 2) + "%");
  }
  p.drawText(QRectF(plot.left(), plot.bottom() + 14, plot.width(), 14), Qt::AlignHCenter,
             "triangles (log)   ·   Hausdorff error, % of the bounding-box diagonal (log)");

  std::vector<const PreviewPoint*> sorted = pts;
  std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->triangles < b->triangles; });
  QPainterPath line;
  for (size_t i = 0; i < sorted.size(); ++i) {
    const QPointF q = map(double(sorted[i]->triangles), sorted[i]->hausdorffRel);
    if (i == 0) line.moveTo(q);
    else line.lineTo(q);
  }
  p.setPen(QPen(QColor(0x5e, 0xa8, 0xff), 1.5));
  p.drawPath(line);
  for (const PreviewPoint* pt : sorted) {
    const QPointF q = map(double(pt->triangles), pt->hausdorffRel);
    p.setBrush(QColor(0x5e, 0xa8, 0xff));
    p.setPen(Qt::NoPen);
    p.drawEllipse(q, 3, 3);
    if (pt->chosen) {
      p.setBrush(Qt::NoBrush);
      p.setPen(QPen(QColor(0xff, 0xc8, 0x57), 2));
      p.drawEllipse(q, 7, 7);
    }
  }
}

}  // namespace hs::app
