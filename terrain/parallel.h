#pragma once
// A small persistent thread pool for row-parallel loops. Every parallel loop
// in the terrain library writes each output element from exactly one index
// and reads only inputs no other index writes (gather, never scatter), so a
// result does not depend on how rows are split: the same bits on 1 thread or
// 2. Reductions go through per-index partial results combined in index order.
#include <functional>

namespace hs::terrain {

// Threads to use for `requested` (0 = every hardware thread), at least 1.
int resolveThreads(int requested);

// Calls fn(begin, end) over [0, n) split into contiguous chunks on up to
// `threads` threads (the caller's thread included). Chunks smaller than
// `minChunk` are not split further, so small loops run inline.
void parallelFor(int n, int threads, int minChunk, const std::function<void(int, int)>& fn);

}  // namespace hs::terrain
