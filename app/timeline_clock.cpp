#include "app/timeline_clock.h"

#include <algorithm>
#include <cmath>

#include "scene/animation.h"

namespace hs::app {

TimelineClock::TimelineClock(scene::Document& doc, QObject* parent) : QObject(parent), doc_(doc) {
  // Ticks faster than any film rate; each tick shows the frame real time has
  // reached, so playback keeps the film's pace when drawing is slow.
  timer_.setTimerType(Qt::PreciseTimer);
  timer_.setInterval(8);
  connect(&timer_, &QTimer::timeout, this, &TimelineClock::tick);
  connect(&doc_, &scene::Document::changed, this, &TimelineClock::onDocumentChanged);
  frame_ = doc_.state().sequence.startFrame;
}

double TimelineClock::time() const { return sequencer::frameTime(frame_, rate()); }
sequencer::FrameRate TimelineClock::rate() const { return doc_.state().sequence.rate; }

const sequencer::CompiledSequence& TimelineClock::compiled() {
  if (compiledDirty_) {
    compiled_ = scene::compileSequence(doc_.state());
    compiledDirty_ = false;
  }
  return compiled_;
}

const scene::SceneState& TimelineClock::state() {
  if (dirty_) {
    warnings_.clear();
    state_ = scene::animatedState(doc_.state(), compiled(), time(), &warnings_);
    dirty_ = false;
  }
  return state_;
}

int64_t TimelineClock::loopFirst() const {
  const auto& s = doc_.state().sequence;
  return ownLoop_ ? std::clamp(loopFirst_, s.startFrame, s.endFrame) : s.startFrame;
}

int64_t TimelineClock::loopLast() const {
  const auto& s = doc_.state().sequence;
  return ownLoop_ ? std::clamp(loopLast_, loopFirst(), s.endFrame) : s.endFrame;
}

void TimelineClock::onDocumentChanged(const scene::ChangeSet& changes) {
  if (changes.sequence || changes.reset) compiledDirty_ = true;
  if (changes.reset) {
    pause();
    ownLoop_ = false;
    frame_ = doc_.state().sequence.startFrame;
    emit frameChanged(frame_);
    emit loopChanged();
  }
  dirty_ = true;
  emit stateChanged();
}

void TimelineClock::setFrame(int64_t frame) {
  if (frame == frame_) return;
  frame_ = frame;
  dirty_ = true;
  if (playing()) {
    // A scrub during playback continues from there.
    playStartFrame_ = frame;
    playClock_.restart();
  }
  emit frameChanged(frame_);
  emit stateChanged();
}

void TimelineClock::play() {
  if (playing()) return;
  if (frame_ < loopFirst() || frame_ >= loopLast()) setFrame(loopFirst());
  playStartFrame_ = frame_;
  playClock_.start();
  timer_.start();
  emit playingChanged(true);
}

void TimelineClock::pause() {
  if (!playing()) return;
  timer_.stop();
  emit playingChanged(false);
}

void TimelineClock::togglePlay() { playing() ? pause() : play(); }
void TimelineClock::stepFrames(int64_t delta) { setFrame(frame_ + delta); }
void TimelineClock::goToStart() { setFrame(loopFirst()); }
void TimelineClock::goToEnd() { setFrame(loopLast()); }

void TimelineClock::setLooping(bool on) {
  if (on == loop_) return;
  loop_ = on;
  emit loopChanged();
}

void TimelineClock::setLoopRange(int64_t first, int64_t last) {
  ownLoop_ = first <= last;
  loopFirst_ = first;
  loopLast_ = last;
  emit loopChanged();
}

void TimelineClock::setAutoKey(bool on) {
  if (on == autoKey_) return;
  autoKey_ = on;
  emit autoKeyChanged(on);
}

void TimelineClock::tick() {
  const double fps = rate().fps();
  const int64_t advanced = int64_t(std::floor(playClock_.nsecsElapsed() * 1e-9 * fps));
  int64_t f = playStartFrame_ + advanced;
  const int64_t first = loopFirst(), last = loopLast();
  if (f > last) {
    if (!loop_) {
      const int64_t end = last;
      pause();
      setFrame(end);
      return;
    }
    const int64_t span = last - first + 1;
    f = first + (f - first) % span;
  }
  if (f == frame_) return;
  frame_ = f;
  dirty_ = true;
  emit frameChanged(frame_);
  emit stateChanged();
}

}  // namespace hs::app
