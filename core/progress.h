#pragma once
// Progress and cancellation for long work that runs off the UI thread: the
// one convention of every library (mesh, terrain, sequencer, and later
// foliage and particles). The libraries know nothing of Qt: the editor
// adapts this to a progress dialog with Cancel, the CLI to a line on stderr
// and Ctrl-C.
//
// Work takes a `const Progress*` (nullptr: nobody watches), reports a
// fraction in [0,1] with a stage name now and then, and polls cancelled()
// at points where stopping leaves nothing half-done. A step of a larger
// job reports through a slice of its parent's bar (the constructor with a
// parent), and a Cancel on the parent reaches every slice under it.
#include <atomic>
#include <functional>
#include <string_view>

namespace hs {

class Progress {
 public:
  using Callback = std::function<void(double fraction, std::string_view stage)>;

  Progress() = default;
  explicit Progress(Callback cb) : callback_(std::move(cb)) {}
  // The part [from, to] of `parent`'s bar (parent may be nullptr).
  Progress(const Progress* parent, double from, double to) : parent_(parent), from_(from), to_(to) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // fraction in [0,1]; may be called from any thread.
  void report(double fraction, std::string_view stage) const {
    if (callback_) callback_(fraction, stage);
    if (parent_) parent_->report(from_ + (to_ - from_) * fraction, stage);
  }
  // Safe to call from a signal handler (a lock-free atomic store).
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const {
    return cancelled_.load(std::memory_order_relaxed) || (parent_ && parent_->cancelled());
  }

 private:
  Callback callback_;
  const Progress* parent_ = nullptr;
  double from_ = 0.0, to_ = 1.0;
  std::atomic<bool> cancelled_{false};
};

// Report progress on a null-able pointer without checking at every call site.
inline void reportProgress(const Progress* p, double fraction, std::string_view stage) {
  if (p) p->report(fraction, stage);
}
inline bool isCancelled(const Progress* p) { return p && p->cancelled(); }

}  // namespace hs
