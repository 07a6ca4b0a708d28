#pragma once
// The timeline's dope sheet: a ruler to scrub, one row per animated entity
// (its keys summarised) with its tracks below, keys as diamonds. Click a key
// to select it (Shift toggles; a summary key selects the keys of all the
// entity's tracks at that time), drag in empty space for a box, drag keys to
// retime them (snapped to frames), Delete, Ctrl+C / Ctrl+V (at the
// playhead), right-click for interpolation, tangents and eases. Left/Right
// step a frame, Space plays. Wheel zooms time, Shift+wheel pans it, Ctrl+
// wheel scrolls the rows. Clicking a track's name shows it in the curve view.
#include <set>

#include <QWidget>

#include "app/timeline_actions.h"
#include "app/timeline_rows.h"
#include "app/timeline_time_axis.h"

namespace hs::app {

class Selection;

class TimelineDopeSheet : public QWidget {
  Q_OBJECT
 public:
  static constexpr int kNamesWidth = 190;
  static constexpr int kRulerHeight = 24;
  static constexpr int kRowHeight = 20;

  TimelineDopeSheet(TimelineActions& actions, TimeWindow& window, Selection& selection, QWidget* parent = nullptr);

  const std::vector<TimelineRow>& rows() const { return rows_; }
  TimeAxis axis() const;
  // Where key `k` is drawn (widget coordinates), if its row is visible.
  std::optional<QPointF> keyPosition(const sequencer::KeyRef& k) const;
  // The widget position of frame `f` on the ruler (for tests and tools).
  QPoint rulerPoint(int64_t frame) const;
  void setCollapsed(scene::EntityId id, bool collapsed);

 signals:
  // A track's name was clicked: show it in the curve view.
  void trackActivated(scene::EntityId entity, const QString& property);
  // A row of a material or of the scene settings was clicked (target as
  // sequencer/binding_target.h tags it): the window shows that object.
  void objectActivated(uint64_t target);

 protected:
  void paintEvent(QPaintEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;
  void contextMenuEvent(QContextMenuEvent* e) override;

 private:
  enum class Drag { None, Scrub, Keys, Box };
  void rebuild();
  int rowAt(int y) const;
  int rowTop(int index) const;
  // Keys under a point: one diamond (the nearest within a few pixels).
  std::vector<sequencer::KeyRef> keysAt(const QPointF& pos) const;
  RulerMarks marks() const;
  void scrubTo(double x);

  TimelineActions& actions_;
  TimeWindow& window_;
  Selection& selection_;
  std::vector<TimelineRow> rows_;
  std::set<scene::EntityId> collapsed_;
  int scrollRows_ = 0;
  Drag drag_ = Drag::None;
  QPointF pressPos_;
  bool dragStarted_ = false;
  QRectF box_;
};

}  // namespace hs::app
