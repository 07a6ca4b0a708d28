#pragma once
// Minimal fork-join helpers for the mesh-processing code. The work here is a
// few large parallel loops per operation (not thousands of tiny tasks), so a
// thread per worker per call costs microseconds against milliseconds of work
// and needs no pool that outlives the call. Ranges are split by index, never
// by timing, so every result that depends only on the index is deterministic.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace hs::mesh {

// Worker count for a request of `requested` (0 = one per hardware thread).
inline unsigned resolveThreads(unsigned requested) {
  if (requested) return requested;
  const unsigned n = std::thread::hardware_concurrency();
  return n ? n : 1;
}

namespace detail {
// Runs body(worker) on `workers` threads (the caller is worker 0) and
// rethrows the first exception after every thread has joined.
template <class Body>
void runWorkers(unsigned workers, Body&& body) {
  if (workers <= 1) {
    body(0u);
    return;
  }
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto guarded = [&](unsigned w) {
    try {
      body(w);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(guarded, w);
  guarded(0);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}
}  // namespace detail

// fn(begin, end, worker) over [0, n) cut into one contiguous range per worker.
// Small loops (under `minPerWorker` items a worker) use fewer workers.
template <class Fn>
void parallelRanges(size_t n, unsigned threads, Fn&& fn, size_t minPerWorker = 4096) {
  const size_t maxWorkers = std::max<size_t>(1, n / std::max<size_t>(1, minPerWorker));
  const unsigned workers = unsigned(std::min<size_t>(std::max(1u, threads), maxWorkers));
  detail::runWorkers(workers, [&](unsigned w) {
    const size_t begin = n * w / workers, end = n * (w + 1) / workers;
    if (begin < end) fn(begin, end, w);
  });
}

// fn(task, worker) for every task in [0, count), handed out one at a time so
// uneven tasks balance. Results must depend on the task, not on the worker.
template <class Fn>
void parallelTasks(size_t count, unsigned threads, Fn&& fn) {
  const unsigned workers = unsigned(std::min<size_t>(std::max(1u, threads), std::max<size_t>(1, count)));
  std::atomic<size_t> next{0};
  detail::runWorkers(workers, [&](unsigned w) {
    for (size_t t = next.fetch_add(1); t < count; t = next.fetch_add(1)) fn(t, w);
  });
}

}  // namespace hs::mesh
