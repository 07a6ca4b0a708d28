#pragma once
// Counter-based random numbers for particles (docs/particles.md,
// "Determinism"): every random number a particle uses is a pure function of
// (emitter seed, stream, particle index, attribute), never of a generator's
// state, so particle i is the same whether it is evaluated alone, after
// others, on another thread or on the GPU.
//
// Only 32-bit unsigned integer operations (xor, shift, wrap-around multiply,
// add) are used, all of which GLSL's uint has with the same results, so a
// shader ports them exactly:
//
//   uint hsHash(uint x) {            // "lowbias32", C. Wellons (2018)
//     x ^= x >> 16; x *= 0x7feb352dU;
//     x ^= x >> 15; x *= 0x846ca68bU;
//     x ^= x >> 16; return x;
//   }
//   uint hsKey(uint seed, uint stream, uint index, uint attr) {
//     return hsHash(hsHash(hsHash(hsHash(seed) ^ stream) ^ index) ^ attr);
//   }
//   float hsUnit(uint h) { return float(h >> 8) * (1.0 / 16777216.0); }  // [0, 1), exact in float
//
// hsUnit keeps the 24 high bits, so the value is exactly representable as a
// float and the CPU (which computes in double from the same integer) and the
// GPU agree bit for bit on it.
#include <cstdint>

#include "core/lowbias32.h"

namespace hs::particles {

constexpr uint32_t hashU32(uint32_t x) { return lowbias32(x); }

constexpr uint32_t hashKey(uint32_t seed, uint32_t stream, uint32_t index, uint32_t attr) {
  return hashU32(hashU32(hashU32(hashU32(seed) ^ stream) ^ index) ^ attr);
}

// [0, 1) with 24 bits: exactly a float.
constexpr double unitFromHash(uint32_t h) { return double(h >> 8) * (1.0 / 16777216.0); }

// What each random number of a particle is for (the `attr` of hashKey).
// Fixed numbers: changing one changes every particle of every scene.
enum class Attr : uint32_t {
  BirthJitter = 1,
  Lifetime = 2,
  Speed = 3,
  SpreadA = 4,
  SpreadB = 5,
  ShapeA = 6,
  ShapeB = 7,
  ShapeC = 8,
  Size = 9,
  Rotation = 10,
  Spin = 11,
  Variant = 12,  // e.g. a flipbook's start frame, a sprite variant
};

// One particle's random numbers: (seed, stream, index) fixed, attribute varying.
struct ParticleRng {
  uint32_t seed = 0, stream = 0, index = 0;
  double unit(Attr a) const { return unitFromHash(hashKey(seed, stream, index, uint32_t(a))); }
  double range(Attr a, double lo, double hi) const { return lo + (hi - lo) * unit(a); }
};

}  // namespace hs::particles
