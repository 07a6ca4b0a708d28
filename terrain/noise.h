#pragma once
// Seeded 2D gradient noise (Perlin-style, quintic fade) and its fractal sum.
// Integer hashing of lattice points with the seed: the same seed gives the
// same terrain on every machine and every run (no global random state).
// Rows are evaluated in one go, reusing the lattice gradients while the row
// stays inside a lattice cell, which makes large noise dabs cheap.
#include <cstdint>

namespace hs::terrain {

class GradientNoise {
 public:
  explicit GradientNoise(uint64_t seed = 1) : seed_(seed) {}
  // About [-1, 1].
  float at(double x, double y, uint32_t octaveSalt = 0) const;
  // Adds amplitude * noise(x0 + i * dx, y) for i in [0, count) to out[i].
  void addRow(double x0, double dx, double y, int count, float amplitude, uint32_t octaveSalt, float* out) const;

 private:
  uint64_t seed_;
};

struct FractalNoise {
  uint64_t seed = 1;
  double scale = 32.0;      // feature size of the first octave, metres
  int octaves = 4;          // 1..12
  float gain = 0.5f;        // amplitude ratio between octaves (roughness)
  float lacunarity = 2.0f;  // frequency ratio between octaves

  // Fractal sum at local metres (x, y), normalised to about [-1, 1].
  float at(double x, double y) const;
  // out[i] = sum at (x0 + i * dx, y) for i in [0, count).
  void row(double x0, double dx, double y, int count, float* out) const;
};

}  // namespace hs::terrain
