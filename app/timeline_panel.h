#pragma once
// The Timeline dock: transport (start, step, play/pause at the sequence's
// frame rate, end), the current frame, the frame rate and range (undoable
// edits of the document), the loop range, Auto Key and Key Transform, the
// stereo preview mode, and below them the dope sheet beside the curve view.
#include <QWidget>

#include "app/timeline_actions.h"
#include "app/timeline_clock.h"
#include "app/timeline_curve_view.h"
#include "app/timeline_dope_sheet.h"
#include "app/timeline_keying.h"
#include "app/timeline_selection.h"
#include "app/timeline_time_axis.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QSpinBox;
class QToolButton;

namespace hs::app {

class Selection;
class StereoPreviewSettings;
class TimelineCutTrack;

class TimelinePanel : public QWidget {
  Q_OBJECT
 public:
  TimelinePanel(scene::Document& doc, TimelineClock& clock, Keying& keying, Selection& selection,
                StereoPreviewSettings& stereo, QWidget* parent = nullptr);

  TimelineDopeSheet* dopeSheet() const { return dopeSheet_; }
  TimelineCutTrack* cutTrack() const { return cutTrack_; }
  TimelineCurveView* curveView() const { return curveView_; }
  TimelineActions& actions() { return *actions_; }
  KeySelection& keySelection() { return *keys_; }
  TimeWindow& window() { return *window_; }
  // Keys the selected entities' location, rotation and scale at the playhead.
  bool keyTransform();
  // Shows the sequence's range (after New/Open).
  void frameRange();

 signals:
  // "Follow Path" was pressed: the window makes the selected camera follow
  // a path (if it has none) and shows the Camera Path panel.
  void followPathRequested();

 private:
  void refreshFields();
  void applyRate();
  void applyRange();

  scene::Document& doc_;
  TimelineClock& clock_;
  Keying& keying_;
  Selection& selection_;
  KeySelection* keys_ = nullptr;
  TimelineActions* actions_ = nullptr;
  TimeWindow* window_ = nullptr;
  TimelineDopeSheet* dopeSheet_ = nullptr;
  TimelineCutTrack* cutTrack_ = nullptr;
  TimelineCurveView* curveView_ = nullptr;
  QToolButton* play_ = nullptr;
  QSpinBox* frame_ = nullptr;
  QLabel* time_ = nullptr;
  QComboBox* rate_ = nullptr;
  QSpinBox *first_ = nullptr, *last_ = nullptr;
  QCheckBox* loop_ = nullptr;
  QSpinBox *loopFirst_ = nullptr, *loopLast_ = nullptr;
  QToolButton* autoKey_ = nullptr;
  QComboBox* stereoMode_ = nullptr;
};

}  // namespace hs::app
