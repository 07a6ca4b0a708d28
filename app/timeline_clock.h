#pragma once
// The editor's current time: the frame the timeline's playhead is on,
// playback at the sequence's frame rate (real time: frames are skipped when
// drawing is slower than the film), the loop range, the auto-key switch,
// and the scene as it is at that time, scene::animatedState() of the
// document, the same pure function the export calls. The viewport draws
// that state and the property panel shows its values, so what a scrub shows
// is exactly what export writes for that frame.
#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

#include "scene/document.h"
#include "sequencer/sequence.h"

namespace hs::app {

class TimelineClock : public QObject {
  Q_OBJECT
 public:
  explicit TimelineClock(scene::Document& doc, QObject* parent = nullptr);

  int64_t frame() const { return frame_; }
  double time() const;  // seconds: frameTime(frame, rate)
  sequencer::FrameRate rate() const;
  // The scene at the current time (recomputed lazily after an edit or a
  // move of the playhead).
  const scene::SceneState& state();
  const sequencer::CompiledSequence& compiled();
  // Warnings of the last evaluation (a track for a missing entity, ...).
  const std::vector<std::string>& warnings() const { return warnings_; }

  bool playing() const { return timer_.isActive(); }
  bool looping() const { return loop_; }
  int64_t loopFirst() const;
  int64_t loopLast() const;
  bool hasOwnLoopRange() const { return ownLoop_; }
  bool autoKey() const { return autoKey_; }

 public slots:
  void setFrame(int64_t frame);
  void play();
  void pause();
  void togglePlay();
  void stepFrames(int64_t delta);
  void goToStart();
  void goToEnd();
  void setLooping(bool on);
  // A loop range inside the sequence's range; first > last resets it to the
  // sequence's range.
  void setLoopRange(int64_t first, int64_t last);
  void setAutoKey(bool on);

 signals:
  void frameChanged(int64_t frame);
  // The state at the current time changed (playhead moved, or an edit).
  void stateChanged();
  void playingChanged(bool playing);
  void loopChanged();
  void autoKeyChanged(bool on);

 private:
  void onDocumentChanged(const scene::ChangeSet& changes);
  void tick();

  scene::Document& doc_;
  int64_t frame_ = 0;
  bool dirty_ = true;
  bool compiledDirty_ = true;
  scene::SceneState state_;
  sequencer::CompiledSequence compiled_;
  std::vector<std::string> warnings_;

  QTimer timer_;
  QElapsedTimer playClock_;
  int64_t playStartFrame_ = 0;
  bool loop_ = true;
  bool ownLoop_ = false;
  int64_t loopFirst_ = 0, loopLast_ = 0;
  bool autoKey_ = false;
};

}  // namespace hs::app
