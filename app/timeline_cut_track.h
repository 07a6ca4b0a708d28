#pragma once
// The camera-cut track of the timeline (docs/sequencer.md "Camera cuts"),
// a strip over the dope sheet on the same time axis: each cut a bar named
// by its camera, its transition a ramp at its start. Drag a bar to move
// it, its ends to trim it, the ramp's right end to lengthen the
// transition; right-click for Add Cut (the selected camera from the
// playhead), the transition, its ease and Remove. Each gesture is one undo step; a
// position that would leave the track unsound (an overlap, a transition
// longer than its shots) is not taken: the bar stays at the last sound one.
#include <optional>

#include <QWidget>

#include "app/timeline_time_axis.h"
#include "scene/document.h"
#include "sequencer/camera_cuts.h"

namespace hs::app {

class Selection;
class TimelineClock;

class TimelineCutTrack : public QWidget {
  Q_OBJECT
 public:
  static constexpr int kHeight = 26;
  TimelineCutTrack(scene::Document& doc, TimeWindow& window, TimelineClock& clock, Selection& selection,
                   QWidget* parent = nullptr);

  TimeAxis axis() const;
  // Where cut `i` is drawn (widget coordinates); empty if there is none.
  QRectF cutRect(size_t i) const;
  // The context menu's actions, for the editor and tests. Add Cut: the
  // selected camera from the playhead to the next cut's start (or 5 s on).
  bool addCutAtPlayhead();
  bool setTransition(size_t i, sequencer::Transition kind, int64_t frames);
  bool setEase(size_t i, sequencer::Ease ease);  // a transition's progress over its frames
  bool removeCut(size_t i);

 protected:
  void paintEvent(QPaintEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void contextMenuEvent(QContextMenuEvent* e) override;

 private:
  enum class Part { Body, Start, End, Ramp };
  struct Hit {
    size_t cut;
    Part part;
  };
  std::optional<Hit> hitAt(const QPointF& pos) const;
  // Applies `cuts` as the gesture's step if the track stays sound.
  bool apply(std::vector<sequencer::CameraCut> cuts, const QString& text, const QString& mergeKey = {});

  scene::Document& doc_;
  TimeWindow& window_;
  TimelineClock& clock_;
  Selection& selection_;
  std::optional<Hit> drag_;
  std::vector<sequencer::CameraCut> dragStart_;
  double pressX_ = 0.0;
  int gesture_ = 0;
};

}  // namespace hs::app
