#pragma once
// A curve over a particle's life drawn and edited with the mouse
// (docs/editor.md, "Particles"): an emitter's size_over_life
// ([[x, multiplier], ...]) or colour_over_life ([[x, r, g, b, a], ...]),
// x = age / lifetime from 0 to 1, piecewise linear between keys and held
// outside them, as particles/emitter.h evaluates it.
//
//   click on the curve's field    adds a key there (its value the curve's
//                                 value at that x), then drags it
//   drag a key                    moves it, between its neighbours (keys
//                                 stay strictly increasing: the reader
//                                 refuses coincident ones)
//   right-click a key, Delete     removes it
//   double-click a colour key     picks its colour (HDR values keep their
//                                 intensity: the dialog edits the hue)
//
// The vertical axis is the size multiplier, or the opacity for colours
// (with the colours as a strip along the bottom). `edited` carries the
// whole list once per gesture (at the mouse's release), in the JSON the
// emitter reads, so the panel sets it as one undo step.
#include <vector>

#include <QWidget>

#include "core/json.h"

namespace hs::app {

class LifeCurveEditor : public QWidget {
  Q_OBJECT
 public:
  enum class Kind { Size, Colour };
  explicit LifeCurveEditor(Kind kind, QWidget* parent = nullptr);

  // The list as the emitter holds it (rows of 2 or 5 numbers); anything
  // else shows as no keys.
  void setKeys(const Json& rows);
  Json keys() const;
  int selectedKey() const { return selected_; }

  // Where key i is drawn (widget coordinates): what a user clicks.
  QPointF keyPoint(int i) const;
  // The widget point of (x, value) (value: size multiplier or opacity).
  QPointF pointAt(double x, double value) const;

  QSize sizeHint() const override { return {260, 110}; }
  QSize minimumSizeHint() const override { return {160, 80}; }

 signals:
  void edited(const Json& rows);

 protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void mouseDoubleClickEvent(QMouseEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;

 private:
  QRectF plot() const;
  double valueOf(const std::vector<double>& row) const { return row.back(); }  // multiplier or opacity
  std::vector<double> sample(double x) const;  // the curve's row at x (what a new key starts as)
  int keyNear(const QPointF& p) const;         // -1: none within a few pixels
  void moveKey(int i, const QPointF& p);
  void removeKey(int i);
  void fitRange();  // the vertical range: 0..1 for opacity, 0..a bit above the largest size

  Kind kind_;
  std::vector<std::vector<double>> rows_;
  double top_ = 1.0;  // the value at the plot's top edge
  int selected_ = -1;
  bool dragging_ = false;
};

}  // namespace hs::app
