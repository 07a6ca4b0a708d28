#pragma once
// The one task scheduler of Hybridscape: parallel loops on oneTBB's thread
// pool, for every library (mesh processing, terrain, sequencer, and later
// foliage and particles).
//
// Why oneTBB and not a pool of our own: a loop may run inside another
// loop's body (a parallel erosion inside a parallel job, a decimation
// region that measures its error), and TBB's work-stealing scheduler runs
// nested loops on the same threads without deadlock or oversubscription.
// Each loop here runs isolated (tbb::this_task_arena::isolate), so a thread
// that waits for its inner loop only helps with that loop and never starts
// an unrelated outer task on top of its own stack.
//
// Determinism: the loops split their range by index, never by timing, and
// `threads` only caps how many threads work on it. Every caller writes each
// output element from one index (gather, not scatter) or combines
// per-range partial results in range order, so results are the same bits
// for any thread count (tests/determinism checks the solvers).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/function_ref.h"

namespace hs {

// CPUs the calling thread may run on now: its affinity mask, which
// taskset, Slurm's task binding and container cpusets set; where the mask
// cannot be read, the machine's hardware threads. At least 1; asked anew at
// every call.
unsigned allowedCpus();

// The threads this process's loops may use: allowedCpus() of the first
// call, kept (solvers ask in every loop). Not hardware_concurrency(), which
// counts the machine's CPUs whatever the process may use: bound to one CPU
// of two, a CLI import asked oneTBB for a worker it could not have, and
// oneTBB (which reads the mask) printed a warning into the run's output;
// and a job bound to 2 CPUs of a 64-core farm node sized its import
// workers and tile threads by the node, not by the job.
unsigned availableThreads();

// Threads to use for a request: 0 (or negative) means every available
// thread; more than are available is capped to them.
template <class T>
T resolveThreads(T requested) {
  const auto hw = T(availableThreads());
  return requested <= T(0) ? hw : std::min(requested, hw);
}

namespace detail {
// Runs fn(c) for every chunk c in [0, chunks) on at most `threads` threads
// (the caller's included); returns when all have run. The first exception a
// chunk throws is rethrown here after the loop stops.
void runChunks(size_t chunks, unsigned threads, FunctionRef<void(size_t)> fn);
// Runs fn(task, slot) for every task in [0, count) on `workers` workers that
// take tasks one at a time from a shared counter.
void runTaskSlots(size_t count, unsigned workers, FunctionRef<void(size_t, unsigned)> fn);
}  // namespace detail

// fn(begin, end) over [0, n) in contiguous chunks of at least `minChunk`
// items, a few chunks per thread so uneven rows balance. Small loops run
// inline on the caller's thread.
template <class Fn>
void parallelFor(int64_t n, int threads, int64_t minChunk, Fn&& fn) {
  if (n <= 0) return;
  const unsigned t = resolveThreads(unsigned(std::max(threads, 0)));
  const int64_t maxChunks = std::max<int64_t>(1, n / std::max<int64_t>(1, minChunk));
  const int64_t chunks = std::min<int64_t>(maxChunks, t == 1 ? 1 : int64_t(t) * 4);
  if (chunks <= 1) {
    fn(decltype(n)(0), n);
    return;
  }
  detail::runChunks(size_t(chunks), t, [&](size_t c) {
    const int64_t b = n * int64_t(c) / chunks, e = n * int64_t(c + 1) / chunks;
    if (b < e) fn(b, e);
  });
}

// fn(begin, end, range) over [0, n) cut into one contiguous range per
// thread, numbered in order from 0, so a caller can keep one partial result
// per range and combine them in order. Loops under `minPerRange` items a
// range use fewer ranges; the range count is
// min(threads, max(1, n / minPerRange)).
template <class Fn>
void parallelRanges(size_t n, unsigned threads, Fn&& fn, size_t minPerRange = 4096) {
  const size_t maxRanges = std::max<size_t>(1, n / std::max<size_t>(1, minPerRange));
  const unsigned ranges = unsigned(std::min<size_t>(resolveThreads(threads), maxRanges));
  if (ranges <= 1) {
    if (n > 0) fn(size_t(0), n, 0u);
    return;
  }
  detail::runChunks(ranges, ranges, [&](size_t r) {
    const size_t begin = n * r / ranges, end = n * (r + 1) / ranges;
    if (begin < end) fn(begin, end, unsigned(r));
  });
}

// Sets n elements from `first` to `value` on every worker: each worker
// first-touches the part it will use first in the parallel passes after
// (and on 5M-element arrays the fill itself is worth splitting).
template <class It, class T>
void parallelFill(It first, size_t n, const T& value, unsigned threads) {
  parallelRanges(n, threads, [&](size_t b, size_t e, unsigned) { std::fill(first + b, first + e, value); });
}

// Where each range of parallelRanges(n, workers, ..., 1) starts in a
// compacted order: offsets[r] counts the i before range r's begin with
// keep(i), offsets[workers] all of them (ranges parallelRanges leaves
// unused count 0). A second parallelRanges(n, workers, ..., 1) over the
// same ranges then numbers each kept item offsets[r] + its rank in its
// range: the input order, for any number of workers.
template <class Keep>
std::vector<size_t> keptOffsets(size_t n, unsigned workers, Keep&& keep) {
  std::vector<size_t> offsets(size_t(workers) + 1, 0);
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned r) {
    size_t k = 0;
    for (size_t i = b; i < e; ++i) k += keep(i) ? 1 : 0;
    offsets[r + 1] = k;
  }, 1);
  for (unsigned r = 0; r < workers; ++r) offsets[r + 1] += offsets[r];
  return offsets;
}

// The i in [0, n) with keep(i), in increasing order, found in parallel (a
// count and a fill over the same ranges). For sparse selections out of a
// large array: n must fit 32 bits.
template <class Keep>
std::vector<uint32_t> keptIndices(size_t n, unsigned threads, Keep&& keep) {
  const unsigned workers = std::max(1u, resolveThreads(threads));
  const std::vector<size_t> offsets = keptOffsets(n, workers, keep);
  std::vector<uint32_t> kept(offsets[workers]);
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned r) {
    size_t next = offsets[r];
    for (size_t i = b; i < e; ++i)
      if (keep(i)) kept[next++] = uint32_t(i);
  }, 1);
  return kept;
}

// fn(task, slot) for every task in [0, count), handed out one at a time so
// uneven tasks balance. `slot` in [0, min(threads, count)) is never used by
// two tasks at once (per-slot scratch memory is safe); results must depend
// on the task, not on the slot.
template <class Fn>
void parallelTasks(size_t count, unsigned threads, Fn&& fn) {
  if (count == 0) return;
  const unsigned workers = unsigned(std::min<size_t>(resolveThreads(threads), count));
  if (workers <= 1) {
    for (size_t t = 0; t < count; ++t) fn(t, 0u);
    return;
  }
  detail::runTaskSlots(count, workers, [&](size_t task, unsigned slot) { fn(task, slot); });
}

}  // namespace hs
