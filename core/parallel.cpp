#include "core/parallel.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <memory>
#include <mutex>
#include <thread>

#include <sched.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace hs {
namespace {

// One arena per thread cap, made on first use and kept: an arena is cheap
// to enter but not to make, and solvers call a loop per iteration. All
// arenas share TBB's one pool of worker threads.
tbb::task_arena& arenaFor(unsigned threads) {
  static constexpr unsigned kMaxArenas = 256;
  static std::array<std::unique_ptr<tbb::task_arena>, kMaxArenas> arenas;
  static std::mutex m;
  threads = std::min(threads, kMaxArenas - 1);
  std::lock_guard lock(m);
  auto& a = arenas[threads];
  if (!a) a = std::make_unique<tbb::task_arena>(int(threads));
  return *a;
}

}  // namespace

unsigned allowedCpus() {
#ifdef __linux__
  // The mask's size grows until the kernel accepts it (EINVAL: the machine
  // has more CPUs than the set holds).
  for (int cpus = 1024; cpus <= (1 << 16); cpus *= 2) {
    cpu_set_t* set = CPU_ALLOC(cpus);
    if (!set) break;
    const size_t bytes = CPU_ALLOC_SIZE(cpus);
    CPU_ZERO_S(bytes, set);
    const int rc = sched_getaffinity(0, bytes, set);
    const int count = rc == 0 ? CPU_COUNT_S(bytes, set) : 0;
    const int err = errno;
    CPU_FREE(set);
    if (rc == 0 && count > 0) return unsigned(count);
    if (rc != 0 && err != EINVAL) break;
  }
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

unsigned availableThreads() {
  static const unsigned n = allowedCpus();
  return n;
}

namespace detail {

void runChunks(size_t chunks, unsigned threads, FunctionRef<void(size_t)> fn) {
  if (chunks == 0) return;
  threads = resolveThreads(threads);
  if (threads <= 1 || chunks == 1) {
    for (size_t c = 0; c < chunks; ++c) fn(c);
    return;
  }
  auto loop = [&] {
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(0, chunks, 1),
          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t c = r.begin(); c != r.end(); ++c) fn(c);
          },
          tbb::simple_partitioner());
    });
  };
  // Inside an arena that already allows this many threads (a nested loop),
  // stay in it; otherwise enter the arena of this cap.
  if (tbb::this_task_arena::max_concurrency() == int(threads)) loop();
  else arenaFor(threads).execute(loop);
}

void runTaskSlots(size_t count, unsigned workers, FunctionRef<void(size_t, unsigned)> fn) {
  std::atomic<size_t> next{0};
  runChunks(workers, workers, [&](size_t slot) {
    for (size_t t = next.fetch_add(1); t < count; t = next.fetch_add(1)) fn(t, unsigned(slot));
  });
}

}  // namespace detail
}  // namespace hs
