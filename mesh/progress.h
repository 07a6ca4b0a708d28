#pragma once
// Progress and cancellation for long work that runs off the UI thread.
// The domain libraries know nothing of Qt: the editor adapts this to a
// progress dialog, the CLI to a line on stderr.
#include <atomic>
#include <functional>
#include <string_view>

namespace hs {

class Progress {
 public:
  using Callback = std::function<void(double fraction, std::string_view stage)>;

  Progress() = default;
  explicit Progress(Callback cb) : callback_(std::move(cb)) {}

  // fraction in [0,1]; called from the worker thread.
  void report(double fraction, std::string_view stage) const {
    if (callback_) callback_(fraction, stage);
  }
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

 private:
  Callback callback_;
  std::atomic<bool> cancelled_{false};
};

// Report progress on a null-able pointer without checking at every call site.
inline void reportProgress(const Progress* p, double fraction, std::string_view stage) {
  if (p) p->report(fraction, stage);
}
inline bool isCancelled(const Progress* p) { return p && p->cancelled(); }

}  // namespace hs
