#pragma once
// Stable LSD radix sort of packed (key << 32 | payload) items by key. Spatial
// orders (Morton codes of millions of faces or samples) are sorted in a few
// linear passes instead of an n log n comparison sort.
//
// Hand-written because oneTBB has no radix sort and its parallel_sort is a
// comparison sort (n log n, unstable); the sort must be stable so that the
// order of equal keys, and with it everything numbered from this order, is
// the same for any thread count.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.h"
#include "core/uninit_array.h"

namespace hs::mesh {

// Sorts `items` by bits [32, 32 + keyBits) (the key), keeping the order of
// equal keys. With threads > 1 each pass counts and scatters per contiguous
// range on its own thread; the ranges' buckets are laid out bucket by
// bucket, range by range, so the result is the serial sort's, bit for bit.
inline void radixSortByKey(std::span<uint64_t> items, int keyBits, unsigned threads = 1) {
  constexpr int kBits = 11;
  constexpr size_t kBuckets = size_t(1) << kBits;
  const size_t n = items.size();
  // Passes alternate between the items and an uninitialised buffer (a
  // zero-filled one would be written twice).
  UninitArray<uint64_t> buffer(n);
  uint64_t* from = items.data();
  uint64_t* to = buffer.data();
  // Below ~64k items per range a pass is shorter than waking a thread.
  const unsigned ranges = unsigned(std::clamp<size_t>(n / 65536, 1, resolveThreads(threads)));
  std::vector<std::array<size_t, kBuckets>> count(ranges);
  for (int shift = 0; shift < keyBits; shift += kBits) {
    const int at = 32 + shift;
    parallelRanges(n, ranges, [&](size_t b, size_t e, unsigned r) {
      auto& c = count[r];
      c.fill(0);
      for (size_t i = b; i < e; ++i) ++c[(from[i] >> at) & (kBuckets - 1)];
    }, 65536);
    size_t sum = 0;
    for (size_t k = 0; k < kBuckets; ++k)
      for (unsigned r = 0; r < ranges; ++r) {
        const size_t m = count[r][k];
        count[r][k] = sum;
        sum += m;
      }
    parallelRanges(n, ranges, [&](size_t b, size_t e, unsigned r) {
      auto& c = count[r];
      for (size_t i = b; i < e; ++i) to[c[(from[i] >> at) & (kBuckets - 1)]++] = from[i];
    }, 65536);
    std::swap(from, to);
  }
  if (from != items.data())
    parallelRanges(n, ranges, [&](size_t b, size_t e, unsigned) { std::copy(from + b, from + e, items.data() + b); },
                   65536);
}

// 10 bits per axis interleaved into a 30-bit Morton (Z-order) code.
inline uint32_t mortonCode10(uint32_t x, uint32_t y, uint32_t z) {
  auto spread = [](uint32_t v) {
    v &= 0x3ff;
    v = (v | (v << 16)) & 0x030000FF;
    v = (v | (v << 8)) & 0x0300F00F;
    v = (v | (v << 4)) & 0x030C30C3;
    v = (v | (v << 2)) & 0x09249249;
    return v;
  };
  return spread(x) | (spread(y) << 1) | (spread(z) << 2);
}

}  // namespace hs::mesh
