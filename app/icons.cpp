#include "app/icons.h"

#include <cmath>
#include <map>

#include <QPainter>
#include <QPainterPath>
#include <QPixmap>

namespace hs::app {
namespace {

const QColor kInk(214, 216, 220);
const QColor kRed(232, 84, 84), kGreen(120, 200, 90), kBlue(90, 150, 240), kYellow(245, 200, 80);

void arrowHead(QPainter& p, QPointF tip, double angleDeg, double size) {
  const double a = angleDeg * M_PI / 180.0;
  const QPointF dir(std::cos(a), std::sin(a)), side(-dir.y(), dir.x());
  QPolygonF tri;
  tri << tip << tip - dir * size + side * size * 0.6 << tip - dir * size - side * size * 0.6;
  p.setBrush(p.pen().color());
  p.drawPolygon(tri);
  p.setBrush(Qt::NoBrush);
}

void draw(QPainter& p, Icon which) {
  QPen pen(kInk, 4.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin);
  p.setPen(pen);
  switch (which) {
    case Icon::Select: {
      QPolygonF cursor;
      cursor << QPointF(18, 8) << QPointF(18, 50) << QPointF(28, 40) << QPointF(36, 56) << QPointF(43, 53)
             << QPointF(35, 37) << QPointF(49, 37);
      p.setBrush(kInk);
      p.drawPolygon(cursor);
      break;
    }
    case Icon::Move: {
      p.setPen(QPen(kInk, 4.5, Qt::SolidLine, Qt::RoundCap));
      p.drawLine(QPointF(32, 12), QPointF(32, 52));
      p.drawLine(QPointF(12, 32), QPointF(52, 32));
      p.setPen(QPen(kInk, 1.0));
      arrowHead(p, {32, 5}, -90, 11);
      arrowHead(p, {32, 59}, 90, 11);
      arrowHead(p, {5, 32}, 180, 11);
      arrowHead(p, {59, 32}, 0, 11);
      break;
    }
    case Icon::Rotate: {
      p.setPen(QPen(kInk, 5.0, Qt::SolidLine, Qt::RoundCap));
      p.drawArc(QRectF(12, 12, 40, 40), 100 * 16, 280 * 16);
      p.setPen(QPen(kInk, 1.0));
      arrowHead(p, {30, 10}, 180, 13);
      break;
    }
    case Icon::Scale: {
      p.drawRect(QRectF(8, 26, 30, 30));
      p.drawLine(QPointF(28, 36), QPointF(52, 12));
      p.setPen(QPen(kInk, 1.0));
      arrowHead(p, {56, 8}, -45, 14);
      break;
    }
    case Icon::World: {
      p.drawEllipse(QRectF(8, 8, 48, 48));
      p.drawEllipse(QRectF(21, 8, 22, 48));
      p.drawLine(QPointF(8, 32), QPointF(56, 32));
      break;
    }
    case Icon::Local: {
      p.setPen(QPen(kRed, 5.0, Qt::SolidLine, Qt::RoundCap));
      p.drawLine(QPointF(14, 50), QPointF(54, 50));
      p.setPen(QPen(kGreen, 5.0, Qt::SolidLine, Qt::RoundCap));
      p.drawLine(QPointF(14, 50), QPointF(34, 30));
      p.setPen(QPen(kBlue, 5.0, Qt::SolidLine, Qt::RoundCap));
      p.drawLine(QPointF(14, 50), QPointF(14, 8));
      break;
    }
    case Icon::Snap: {
      // A magnet.
      p.setPen(QPen(kInk, 9.0, Qt::SolidLine, Qt::FlatCap));
      p.drawArc(QRectF(14, 14, 36, 36), 180 * 16, 180 * 16);
      p.drawLine(QPointF(14, 32), QPointF(14, 18));
      p.drawLine(QPointF(50, 32), QPointF(50, 18));
      p.setPen(QPen(kRed, 9.0, Qt::SolidLine, Qt::FlatCap));
      p.drawLine(QPointF(14, 18), QPointF(14, 8));
      p.drawLine(QPointF(50, 18), QPointF(50, 8));
      break;
    }
    case Icon::Frame: {
      for (int c = 0; c < 4; ++c) {
        const double x = (c & 1) ? 54 : 10, y = (c & 2) ? 54 : 10, sx = (c & 1) ? -1 : 1, sy = (c & 2) ? -1 : 1;
        p.drawLine(QPointF(x, y), QPointF(x + sx * 14, y));
        p.drawLine(QPointF(x, y), QPointF(x, y + sy * 14));
      }
      p.setBrush(kInk);
      p.drawEllipse(QPointF(32, 32), 7, 7);
      break;
    }
    case Icon::Grid: {
      p.setPen(QPen(kInk, 3.0));
      for (int i = 0; i < 4; ++i) {
        const double t = 10 + i * 14.67;
        p.drawLine(QPointF(t, 8), QPointF(t, 56));
        p.drawLine(QPointF(8, t), QPointF(56, t));
      }
      break;
    }
    case Icon::Mesh: {
      // An isometric cube.
      const QPointF top(32, 8), l(10, 20), r(54, 20), c(32, 32), bl(10, 44), br(54, 44), b(32, 56);
      p.setBrush(QColor(120, 170, 230, 90));
      QPolygonF outline;
      outline << top << r << br << b << bl << l;
      p.drawPolygon(outline);
      p.drawLine(l, c);
      p.drawLine(r, c);
      p.drawLine(c, b);
      break;
    }
    case Icon::Camera: {
      p.setBrush(QColor(200, 200, 210, 70));
      p.drawRoundedRect(QRectF(6, 20, 34, 26), 4, 4);
      QPolygonF lens;
      lens << QPointF(40, 28) << QPointF(58, 18) << QPointF(58, 48) << QPointF(40, 38);
      p.drawPolygon(lens);
      break;
    }
    case Icon::Sun: {
      p.setPen(QPen(kYellow, 4.0, Qt::SolidLine, Qt::RoundCap));
      p.setBrush(kYellow);
      p.drawEllipse(QPointF(32, 32), 10, 10);
      for (int i = 0; i < 8; ++i) {
        const double a = i * M_PI / 4;
        p.drawLine(QPointF(32 + 17 * std::cos(a), 32 + 17 * std::sin(a)),
                   QPointF(32 + 26 * std::cos(a), 32 + 26 * std::sin(a)));
      }
      break;
    }
    case Icon::PointLight: {
      p.setPen(QPen(kYellow, 4.0, Qt::SolidLine, Qt::RoundCap));
      p.setBrush(QColor(245, 200, 80, 120));
      p.drawEllipse(QPointF(32, 26), 15, 15);
      p.drawLine(QPointF(25, 46), QPointF(39, 46));
      p.drawLine(QPointF(27, 54), QPointF(37, 54));
      break;
    }
    case Icon::Empty: {
      p.setPen(QPen(kInk, 4.0, Qt::SolidLine, Qt::RoundCap));
      p.drawLine(QPointF(32, 10), QPointF(32, 54));
      p.drawLine(QPointF(10, 32), QPointF(54, 32));
      p.drawEllipse(QPointF(32, 32), 9, 9);
      break;
    }
    case Icon::Group: {
      p.setBrush(QColor(210, 180, 110, 110));
      QPolygonF folder;
      folder << QPointF(6, 16) << QPointF(24, 16) << QPointF(30, 22) << QPointF(58, 22) << QPointF(58, 52)
             << QPointF(6, 52);
      p.drawPolygon(folder);
      break;
    }
    case Icon::Import: {
      p.drawLine(QPointF(32, 6), QPointF(32, 38));
      p.setPen(QPen(kInk, 1.0));
      arrowHead(p, {32, 44}, 90, 14);
      p.setPen(pen);
      p.drawPolyline(QPolygonF() << QPointF(10, 36) << QPointF(10, 56) << QPointF(54, 56) << QPointF(54, 36));
      break;
    }
  }
}

}  // namespace

QIcon icon(Icon which) {
  static std::map<Icon, QIcon> cache;
  auto it = cache.find(which);
  if (it != cache.end()) return it->second;
  QIcon result;
  for (int size : {16, 24, 32, 64}) {
    QPixmap pm(size, size);
    pm.fill(Qt::transparent);
    QPainter p(&pm);
    p.setRenderHint(QPainter::Antialiasing);
    p.scale(size / 64.0, size / 64.0);
    draw(p, which);
    p.end();
    result.addPixmap(pm);
  }
  cache.emplace(which, result);
  return result;
}

}  // namespace hs::app
