#pragma once
// Wellons' lowbias32, a 32-bit integer hash: the CPU side of
// shaders/lowbias32.glsl, so what the CPU computes from it (particles,
// the wind's phase, the tests' twins) matches the GPU bit for bit.
#include <cstdint>

namespace hs {

constexpr uint32_t lowbias32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace hs
