#pragma once
// Stable LSD radix sort of packed (key << 32 | payload) items by key. Spatial
// orders (Morton codes of millions of faces or samples) are sorted in a few
// linear passes instead of an n log n comparison sort.
#include <array>
#include <cstdint>
#include <vector>

namespace hs::mesh {

// Sorts `items` by bits [32, 32 + keyBits) (the key), keeping the order of
// equal keys. `scratch` is reused between calls to avoid a reallocation.
inline void radixSortByKey(std::vector<uint64_t>& items, int keyBits, std::vector<uint64_t>& scratch) {
  constexpr int kBits = 11;
  constexpr size_t kBuckets = size_t(1) << kBits;
  scratch.resize(items.size());
  for (int shift = 0; shift < keyBits; shift += kBits) {
    std::array<size_t, kBuckets> count{};
    for (uint64_t it : items) ++count[(it >> (32 + shift)) & (kBuckets - 1)];
    size_t sum = 0;
    for (auto& c : count) {
      const size_t n = c;
      c = sum;
      sum += n;
    }
    for (uint64_t it : items) scratch[count[(it >> (32 + shift)) & (kBuckets - 1)]++] = it;
    items.swap(scratch);
  }
}

inline void radixSortByKey(std::vector<uint64_t>& items, int keyBits) {
  std::vector<uint64_t> scratch;
  radixSortByKey(items, keyBits, scratch);
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
