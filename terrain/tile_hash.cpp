#include "terrain/tile_hash.h"

#include <cstring>

namespace hs::terrain {
namespace {

// 64-bit multiply-xorshift mixing (the finaliser of MurmurHash3/SplitMix64),
// applied per 8-byte word: not cryptographic, but every bit of every sample
// reaches the result, at memory speed.
inline uint64_t mix(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  x ^= x >> 33;
  return x;
}

}  // namespace

uint64_t tileContentHash(TileKind kind, int layer, int tile, const void* data, size_t bytes) {
  uint64_t h = mix(0x48535454ull ^ (uint64_t(kind) << 40) ^ (uint64_t(uint32_t(layer)) << 20) ^ uint64_t(uint32_t(tile)));
  const auto* p = static_cast<const unsigned char*>(data);
  // Four independent lanes keep the multiplier pipeline busy.
  uint64_t lane[4] = {h, h ^ 1, h ^ 2, h ^ 3};
  size_t i = 0;
  for (; i + 32 <= bytes; i += 32)
    for (int k = 0; k < 4; ++k) {
      uint64_t w;
      std::memcpy(&w, p + i + 8 * size_t(k), 8);
      lane[k] = (lane[k] ^ w) * 0x9e3779b97f4a7c15ull;
      lane[k] ^= lane[k] >> 29;
    }
  for (; i < bytes; ++i) lane[0] = (lane[0] ^ p[i]) * 0x100000001b3ull;
  h = mix(lane[0]) ^ mix(lane[1] + 1) ^ mix(lane[2] + 2) ^ mix(lane[3] + 3);
  return mix(h ^ bytes);
}

}  // namespace hs::terrain
