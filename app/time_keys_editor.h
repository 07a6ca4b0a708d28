#pragma once
// An emitter's keyed list over scene time drawn and edited with the mouse
// (docs/editor.md, "Particles"), as LifeCurveEditor does for the curves
// over a particle's life: rate_keys ([[t, rate], ...], particles per
// second, linear between keys and held outside them), wind_keys
// ([[t, x, y, z], ...], m/s, each component a line of its own colour) or
// bursts ([[t, count], ...], drawn as stems). The horizontal axis is scene
// time over the span the panel sets (the playback range, widened to the
// keys and the playhead), with the playhead drawn.
//
//   click on the field            adds a key there (its value the list's
//                                 value at that time, a burst 10 particles),
//                                 then drags it (a new burst goes last:
//                                 a burst's place is its particles' stream)
//   drag a key                    moves it in time (between its neighbours
//                                 for rate and wind: the reader refuses
//                                 coincident times) and value; a wind key's
//                                 grabbed component changes
//   right-click a key, Delete     removes it
//
// With no keys the constant (the emitter's rate or wind) shows dashed.
// `edited` carries the whole list once per gesture (at the mouse's release)
// in the JSON the emitter reads, so the panel sets it as one undo step.
#include <vector>

#include <QWidget>

#include "core/json.h"

namespace hs::app {

class TimeKeysEditor : public QWidget {
  Q_OBJECT
 public:
  enum class Kind { Rate, Wind, Bursts };
  explicit TimeKeysEditor(Kind kind, QWidget* parent = nullptr);

  // The list as the emitter holds it (rows of 2, or 4 for wind); anything
  // else shows as no keys. `constant`: the value without keys (1 number, or
  // 3 for wind; ignored for bursts).
  void setKeys(const Json& rows, const std::vector<double>& constant = {});
  Json keys() const;
  // The time axis, [t0, t1] (t1 > t0), and the playhead.
  void setSpan(double t0, double t1);
  void setPlayhead(double t);
  double spanStart() const { return t0_; }
  double spanEnd() const { return t1_; }
  int selectedKey() const { return selected_; }

  // Where key i's channel c is drawn (c: 0, or the wind's 0..2): what a user clicks.
  QPointF keyPoint(int i, int channel = 0) const;
  // The widget point of (time, value).
  QPointF pointAt(double t, double value) const;

  QSize sizeHint() const override { return {260, 100}; }
  QSize minimumSizeHint() const override { return {160, 70}; }

 signals:
  void edited(const Json& rows);

 protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;

 private:
  QRectF plot() const;
  int channels() const { return kind_ == Kind::Wind ? 3 : 1; }
  std::vector<double> sample(double t) const;  // the list's row at t (what a new key starts as)
  bool keyNear(const QPointF& p, int& key, int& channel) const;
  void moveKey(int i, const QPointF& p);
  void removeKey(int i);
  void fitRange();  // the vertical range from the keys and the constant
  double timeAt(double x) const;
  double valueAt(double y) const;

  Kind kind_;
  std::vector<std::vector<double>> rows_;
  std::vector<double> constant_;
  double t0_ = 0.0, t1_ = 10.0, playhead_ = 0.0;
  double lo_ = 0.0, hi_ = 1.0;  // the values at the plot's bottom and top
  int selected_ = -1, channel_ = 0;
  bool dragging_ = false;
};

}  // namespace hs::app
