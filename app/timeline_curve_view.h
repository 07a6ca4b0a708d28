#pragma once
// The curve view: one property's curve over time (a vector's x, y and z in
// red, green and blue), drawn by evaluating the track itself, so it is
// exactly what plays. Keys are points: drag one to change its time (snapped
// to frames) and value; a selected cubic key shows its tangent handles:
// dragging one sets the slope (the key becomes User: one slope both sides;
// with Alt, or on a Broken key, only that side moves). Right-click for
// interpolation, tangents and eases; F frames the curve; the ruler scrubs.
// Rotation tracks (quaternions) and on/off tracks show their keys here but
// are retimed in the dope sheet.
#include <optional>

#include <QWidget>

#include "app/timeline_actions.h"
#include "app/timeline_time_axis.h"

namespace hs::app {

class TimelineCurveView : public QWidget {
  Q_OBJECT
 public:
  static constexpr int kValueAxisWidth = 56;
  static constexpr int kRulerHeight = 24;

  TimelineCurveView(TimelineActions& actions, TimeWindow& window, QWidget* parent = nullptr);

  void setTrack(scene::EntityId entity, const std::string& property);
  scene::EntityId entity() const { return entity_; }
  const std::string& property() const { return property_; }
  // Fits the value range to the curve.
  void frameCurve();
  // Widget positions of a key's point and of its tangent handles (tests, tools).
  std::optional<QPointF> keyPoint(const sequencer::KeyRef& key, int component = 0) const;
  std::optional<QPointF> handlePoint(const sequencer::KeyRef& key, int component, bool out) const;

 protected:
  void paintEvent(QPaintEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;
  void contextMenuEvent(QContextMenuEvent* e) override;

 private:
  enum class Drag { None, Scrub, Key, Handle };
  TimeAxis axis() const;
  double y(double value) const;
  double value(double y) const;
  int components() const;  // 1, 3, or 0 for a track the view does not edit
  // A copy of the shown track (a camera path's progress as a scalar track).
  std::optional<sequencer::Track> track() const;
  std::vector<sequencer::KeyRef> trackKeys() const;
  // The time span a handle reaches: a third of the neighbouring segment.
  double handleSpan(const sequencer::KeyRef& key, bool out) const;

  TimelineActions& actions_;
  TimeWindow& window_;
  scene::EntityId entity_ = scene::kNoEntity;
  std::string property_;
  double low_ = 0.0, high_ = 1.0;

  Drag drag_ = Drag::None;
  QPointF pressPos_;
  sequencer::Sequence start_;  // the sequence when the gesture began
  sequencer::KeyRef dragKey_;
  int dragComponent_ = 0;
  bool dragOut_ = true;
  bool dragBroken_ = false;
  double startTime_ = 0.0, startValue_ = 0.0;
  QString gesture_;
  bool moved_ = false;
};

}  // namespace hs::app
