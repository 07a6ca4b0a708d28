#include "terrain/noise.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {
namespace {

inline uint32_t hash(int64_t ix, int64_t iy, uint64_t seed, uint32_t salt) {
  // splitmix64-style finaliser over the lattice point, seed and octave.
  uint64_t h = uint64_t(ix) * 0x9E3779B97F4A7C15ull ^ (uint64_t(iy) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
  h ^= seed + 0x165667B19E3779F9ull + (uint64_t(salt) << 32);
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBull;
  h ^= h >> 31;
  return uint32_t(h);
}

// 16 unit gradient directions: enough isotropy, no trig at run time.
struct Grad {
  float x, y;
};
constexpr Grad kGrads[16] = {{1.0f, 0.0f},         {0.9238795f, 0.3826834f},  {0.7071068f, 0.7071068f},
                             {0.3826834f, 0.9238795f}, {0.0f, 1.0f},         {-0.3826834f, 0.9238795f},
                             {-0.7071068f, 0.7071068f}, {-0.9238795f, 0.3826834f}, {-1.0f, 0.0f},
                             {-0.9238795f, -0.3826834f}, {-0.7071068f, -0.7071068f}, {-0.3826834f, -0.9238795f},
                             {0.0f, -1.0f},        {0.3826834f, -0.9238795f}, {0.7071068f, -0.7071068f},
                             {0.9238795f, -0.3826834f}};
inline const Grad& grad(int64_t ix, int64_t iy, uint64_t seed, uint32_t salt) { return kGrads[hash(ix, iy, seed, salt) & 15u]; }
inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
// 2D gradient noise peaks near +-0.7; scale to about +-1.
constexpr float kNorm = 1.41f;

}  // namespace

float GradientNoise::at(double x, double y, uint32_t salt) const {
  const double fx = std::floor(x), fy = std::floor(y);
  const int64_t ix = int64_t(fx), iy = int64_t(fy);
  const float tx = float(x - fx), ty = float(y - fy);
  const Grad &g00 = grad(ix, iy, seed_, salt), &g10 = grad(ix + 1, iy, seed_, salt);
  const Grad &g01 = grad(ix, iy + 1, seed_, salt), &g11 = grad(ix + 1, iy + 1, seed_, salt);
  const float n00 = g00.x * tx + g00.y * ty, n10 = g10.x * (tx - 1) + g10.y * ty;
  const float n01 = g01.x * tx + g01.y * (ty - 1), n11 = g11.x * (tx - 1) + g11.y * (ty - 1);
  const float u = fade(tx), v = fade(ty);
  const float a = n00 + (n10 - n00) * u, b = n01 + (n11 - n01) * u;
  return (a + (b - a) * v) * kNorm;
}

void GradientNoise::addRow(double x0, double dx, double y, int count, float amplitude, uint32_t salt,
                           float* out) const {
  const double fy = std::floor(y);
  const int64_t iy = int64_t(fy);
  const float ty = float(y - fy), v = fade(ty);
  int64_t cached = INT64_MIN;
  Grad g00{}, g10{}, g01{}, g11{};
  for (int i = 0; i < count; ++i) {
    const double x = x0 + dx * i;
    const double fx = std::floor(x);
    const int64_t ix = int64_t(fx);
    if (ix != cached) {
      g00 = grad(ix, iy, seed_, salt);
      g10 = grad(ix + 1, iy, seed_, salt);
      g01 = grad(ix, iy + 1, seed_, salt);
      g11 = grad(ix + 1, iy + 1, seed_, salt);
      cached = ix;
    }
    const float tx = float(x - fx);
    const float n00 = g00.x * tx + g00.y * ty, n10 = g10.x * (tx - 1) + g10.y * ty;
    const float n01 = g01.x * tx + g01.y * (ty - 1), n11 = g11.x * (tx - 1) + g11.y * (ty - 1);
    const float u = fade(tx);
    const float a = n00 + (n10 - n00) * u, b = n01 + (n11 - n01) * u;
    out[i] += (a + (b - a) * v) * kNorm * amplitude;
  }
}

float FractalNoise::at(double x, double y) const {
  float v = 0.0f;
  row(x, 1.0, y, 1, &v);
  return v;
}

void FractalNoise::row(double x0, double dx, double y, int count, float* out) const {
  std::fill(out, out + count, 0.0f);
  const GradientNoise n(seed);
  const int oct = std::clamp(octaves, 1, 12);
  const double s = std::isfinite(scale) && scale > 1e-6 ? scale : 32.0;
  const float gn = std::isfinite(gain) ? std::clamp(gain, 0.0f, 1.0f) : 0.5f;
  const float lac = std::isfinite(lacunarity) ? std::clamp(lacunarity, 1.0f, 8.0f) : 2.0f;
  double freq = 1.0 / s;
  float amp = 1.0f, norm = 0.0f;
  for (int o = 0; o < oct; ++o) {
    n.addRow(x0 * freq, dx * freq, y * freq, count, amp, uint32_t(o), out);
    norm += amp;
    amp *= gn;
    freq *= double(lac);
  }
  if (norm > 0.0f)
    for (int i = 0; i < count; ++i) out[i] /= norm;
}

}  // namespace hs::terrain
