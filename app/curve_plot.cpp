#include "app/curve_plot.h"

#include <QKeyEvent>
#include <QPainter>
#include <QWidget>

namespace hs::app {

void paintPlotBackground(QPainter& p, const QWidget& w, const QRectF& r) {
  p.fillRect(w.rect(), w.palette().color(QPalette::Base));
  p.setPen(QPen(w.palette().color(QPalette::Mid), 1));
  for (int i = 0; i <= 4; ++i)
    p.drawLine(QPointF(r.left() + r.width() * i / 4, r.top()), QPointF(r.left() + r.width() * i / 4, r.bottom()));
  p.drawLine(r.bottomLeft(), r.bottomRight());
}

std::vector<double> rowAt(const std::vector<std::vector<double>>& rows, double x) {
  if (rows.empty() || rows.front().empty()) return {x};
  std::vector<double> r;
  if (x <= rows.front()[0]) {
    r = rows.front();
  } else if (x >= rows.back()[0]) {
    r = rows.back();
  } else {
    size_t i = 1;
    while (rows[i][0] < x) ++i;
    const auto &a = rows[i - 1], &b = rows[i];
    const double s = (x - a[0]) / (b[0] - a[0]);
    r = a;
    for (size_t c = 1; c < a.size() && c < b.size(); ++c) r[c] = a[c] + (b[c] - a[c]) * s;
  }
  if (!r.empty()) r[0] = x;
  return r;
}

bool isDeleteKey(const QKeyEvent* e) { return e->key() == Qt::Key_Delete || e->key() == Qt::Key_Backspace; }

}  // namespace hs::app
