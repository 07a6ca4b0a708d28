#include "core/blue_noise.h"

#include <algorithm>
#include <cmath>

namespace hs {

namespace {

// Hand-written: no library in the project offers it, and it is small.
// Energies are sums of a toroidal Gaussian (sigma 1.5, as Ulichney) over
// the set pixels, kept up to date as pixels flip, so each flip costs
// side² and the whole map side⁴.
struct Field {
  int side;
  std::vector<double> kernel;  // by toroidal offset (dy * side + dx)
  std::vector<double> energy;
  std::vector<uint8_t> on;

  explicit Field(int s) : side(s), kernel(size_t(s) * size_t(s)), energy(kernel.size(), 0.0), on(kernel.size(), 0) {
    for (int dy = 0; dy < s; ++dy)
      for (int dx = 0; dx < s; ++dx) {
        const double x = std::min(dx, s - dx), y = std::min(dy, s - dy);
        kernel[size_t(dy) * size_t(s) + size_t(dx)] = std::exp(-(x * x + y * y) / (2.0 * 1.5 * 1.5));
      }
  }
  void flip(size_t i) {
    const double sign = on[i] ? -1.0 : 1.0;
    on[i] ^= 1;
    const int ix = int(i % size_t(side)), iy = int(i / size_t(side));
    for (int y = 0; y < side; ++y) {
      const int dy = (y - iy + side) % side;
      for (int x = 0; x < side; ++x) {
        const int dx = (x - ix + side) % side;
        energy[size_t(y) * size_t(side) + size_t(x)] += sign * kernel[size_t(dy) * size_t(side) + size_t(dx)];
      }
    }
  }
  // The set pixel with the most energy (the tightest cluster).
  size_t tightest() const {
    size_t best = energy.size();
    for (size_t i = 0; i < energy.size(); ++i)
      if (on[i] && (best == energy.size() || energy[i] > energy[best])) best = i;
    return best;
  }
  // The empty pixel with the least (the largest void).
  size_t largestVoid() const {
    size_t best = energy.size();
    for (size_t i = 0; i < energy.size(); ++i)
      if (!on[i] && (best == energy.size() || energy[i] < energy[best])) best = i;
    return best;
  }
};

uint32_t nextRandom(uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  uint32_t x = state;
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  return x;
}

}  // namespace

std::vector<uint32_t> blueNoiseRanks(int side, uint32_t seed) {
  side = std::max(side, 2);
  const size_t n = size_t(side) * size_t(side);
  Field f(side);
  // An initial pattern: a tenth of the pixels at random...
  uint32_t state = seed;
  const size_t initial = std::max<size_t>(1, n / 10);
  for (size_t placed = 0; placed < initial;) {
    const size_t i = nextRandom(state) % n;
    if (!f.on[i]) f.flip(i), ++placed;
  }
  // ...evened out: the tightest cluster moves to the largest void until
  // it would land where it came from.
  for (size_t guard = 0; guard < 4 * n; ++guard) {
    const size_t from = f.tightest();
    f.flip(from);
    const size_t to = f.largestVoid();
    f.flip(to);
    if (to == from) break;
  }
  const std::vector<uint8_t> prototype = f.on;
  const std::vector<double> prototypeEnergy = f.energy;
  std::vector<uint32_t> rank(n, 0);
  // Phase 1: the initial pixels ranked down by removing tightest clusters.
  for (size_t r = initial; r-- > 0;) {
    const size_t i = f.tightest();
    f.flip(i);
    rank[i] = uint32_t(r);
  }
  // Phases 2 and 3: the rest ranked up by filling the largest voids (the
  // empty pixel with the least energy of the set ones is the one with the
  // most of the empty ones, so one rule serves both halves).
  f.on = prototype;
  f.energy = prototypeEnergy;
  for (size_t r = initial; r < n; ++r) {
    const size_t i = f.largestVoid();
    f.flip(i);
    rank[i] = uint32_t(r);
  }
  return rank;
}

}  // namespace hs
