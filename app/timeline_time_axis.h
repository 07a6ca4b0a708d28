#pragma once
// The time window the timeline's views share (the dope sheet and the curve
// view scroll and zoom together), and the ruler both draw: seconds and
// frames, the playback range, the loop range and the playhead.
#include <QObject>
#include <QRect>

#include "sequencer/frame_range.h"

class QPainter;

namespace hs::app {

class TimeWindow : public QObject {
  Q_OBJECT
 public:
  explicit TimeWindow(QObject* parent = nullptr) : QObject(parent) {}
  double start() const { return start_; }
  double end() const { return end_; }
  void setWindow(double start, double end);
  // Zooms by `factor` (< 1 in) keeping time `anchor` where it is.
  void zoom(double factor, double anchor);
  void pan(double seconds) { setWindow(start_ + seconds, end_ + seconds); }

 signals:
  void changed();

 private:
  double start_ = -0.5, end_ = 10.5;
};

// Pixel <-> time inside a view's key area (x from left to left + width).
struct TimeAxis {
  double start = 0.0, end = 1.0;
  int left = 0, width = 1;
  double x(double t) const { return left + (t - start) / (end - start) * width; }
  double time(double px) const { return start + (px - left) / double(width) * (end - start); }
  double pixelsPerSecond() const { return width / (end - start); }
};

struct RulerMarks {
  int64_t currentFrame = 0;
  int64_t rangeFirst = 0, rangeLast = 0;  // the sequence's range
  int64_t loopFirst = 0, loopLast = 0;
  bool looping = false;
  sequencer::FrameRate rate{60, 1};
};

// Shades outside the range and the loop range, draws the frame/second ticks
// in `ruler` and the playhead through `all`.
void paintTimeBackground(QPainter& p, const QRect& area, const TimeAxis& axis, const RulerMarks& marks);
void paintRuler(QPainter& p, const QRect& ruler, const TimeAxis& axis, const RulerMarks& marks);
void paintPlayhead(QPainter& p, const QRect& all, const TimeAxis& axis, const RulerMarks& marks);

}  // namespace hs::app
