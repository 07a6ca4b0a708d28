#include "terrain/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace hs::terrain {
namespace {

// Workers sleep on a condition variable; a job is a function over chunk
// indices taken from an atomic counter. One job at a time (a mutex serialises
// callers from different threads), which is what the editor needs: one
// brush or one erosion run at once.
class Pool {
 public:
  explicit Pool(int n) {
    for (int i = 0; i < n; ++i) workers_.emplace_back([this] { loop(); });
  }
  ~Pool() {
    {
      std::lock_guard lk(m_);
      stop_ = true;
    }
    cv_.notify_all();
    for (auto& w : workers_) w.join();
  }
  int size() const { return int(workers_.size()); }

  void run(int chunks, int helpers, const std::function<void(int)>& fn) {
    std::lock_guard serial(runMutex_);
    {
      std::lock_guard lk(m_);
      job_ = &fn;
      chunks_ = chunks;
      next_.store(0);
      active_ = helpers;
      wanted_ = helpers;
      ++generation_;
    }
    cv_.notify_all();
    work(fn, chunks);
    std::unique_lock lk(m_);
    done_.wait(lk, [&] { return active_ == 0; });
    job_ = nullptr;
  }

 private:
  void work(const std::function<void(int)>& fn, int chunks) {
    for (int c = next_.fetch_add(1); c < chunks; c = next_.fetch_add(1)) fn(c);
  }
  void loop() {
    uint64_t seen = 0;
    while (true) {
      const std::function<void(int)>* job;
      int chunks;
      {
        std::unique_lock lk(m_);
        cv_.wait(lk, [&] { return stop_ || (generation_ != seen && wanted_ > 0); });
        if (stop_) return;
        seen = generation_;
        --wanted_;
        job = job_;
        chunks = chunks_;
      }
      work(*job, chunks);
      {
        std::lock_guard lk(m_);
        if (--active_ == 0) done_.notify_all();
      }
    }
  }

  std::vector<std::thread> workers_;
  std::mutex m_, runMutex_;
  std::condition_variable cv_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int chunks_ = 0, active_ = 0, wanted_ = 0;
  uint64_t generation_ = 0;
  std::atomic<int> next_{0};
  bool stop_ = false;
};

// hardware_concurrency() is a system call (sched_getaffinity) on Linux:
// ask once, not in every loop of a 100,000-iteration solver.
int hardwareThreads() {
  static const int n = std::max(1, int(std::thread::hardware_concurrency()));
  return n;
}

Pool& pool() {
  static Pool p(hardwareThreads() - 1);
  return p;
}

}  // namespace

int resolveThreads(int requested) {
  const int hw = hardwareThreads();
  return requested <= 0 ? hw : std::min(requested, hw);
}

void parallelFor(int n, int threads, int minChunk, const std::function<void(int, int)>& fn) {
  if (n <= 0) return;
  threads = resolveThreads(threads);
  minChunk = std::max(1, minChunk);
  const int maxChunks = std::max(1, n / minChunk);
  // A few chunks per thread balance uneven rows without much overhead.
  const int chunks = std::min(maxChunks, threads == 1 ? 1 : threads * 4);
  if (chunks <= 1 || threads <= 1 || pool().size() == 0) {
    fn(0, n);
    return;
  }
  const int helpers = std::min(threads - 1, pool().size());
  pool().run(chunks, helpers, [&](int c) {
    const int b = int(int64_t(n) * c / chunks), e = int(int64_t(n) * (c + 1) / chunks);
    if (b < e) fn(b, e);
  });
}

}  // namespace hs::terrain
