#pragma once
// What the timeline's views do to the keys, as undoable document edits: the
// selected keys are deleted, copied and pasted at the playhead, given an
// interpolation, tangents or an ease, and retimed by a drag (one undo step
// per drag, computed from where the drag started, snapped to frames; Esc
// puts them back). The dope sheet, the curve view and the context menu share
// one of these.
#include <QObject>
#include <QString>

#include "app/timeline_clock.h"
#include "app/timeline_selection.h"
#include "scene/document.h"

class QMenu;
class QWidget;

namespace hs::app {

class TimelineActions : public QObject {
  Q_OBJECT
 public:
  TimelineActions(scene::Document& doc, TimelineClock& clock, KeySelection& keys, QObject* parent = nullptr);

  scene::Document& document() { return doc_; }
  TimelineClock& clock() { return clock_; }
  KeySelection& keys() { return keys_; }

  bool deleteSelected();
  void copySelected();
  bool paste();  // at the playhead
  bool hasClipboard() const { return !clipboard_.empty(); }
  bool setShape(const sequencer::KeyShape& shape);

  // A drag of the selected keys: begin, then move by the total offset in
  // seconds (snapped to frames), then end, or cancel to put them back.
  void beginMove();
  bool moving() const { return moving_; }
  void moveBy(double seconds);
  void endMove();
  void cancelMove();

  // An edit of one key's value or slopes in the curve view, from the
  // sequence as it was when the gesture began (`start`), merged per gesture.
  QString newGestureKey();
  bool applyGesture(const sequencer::Sequence& edited, const QString& text, const QString& gestureKey);

  // Interpolation, tangents, ease, copy, paste, delete for the selection.
  QMenu* contextMenu(QWidget* parent);

 private:
  scene::Document& doc_;
  TimelineClock& clock_;
  KeySelection& keys_;
  sequencer::KeyClipboard clipboard_;
  bool moving_ = false;
  sequencer::Sequence moveStart_;
  std::vector<sequencer::KeyRef> moveKeys_;
  QString moveKey_;
};

}  // namespace hs::app
