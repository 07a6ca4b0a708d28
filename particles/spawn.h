#pragma once
// When particles are born (docs/particles.md, "Birth times"). The rate r(t)
// is piecewise linear between its keys (held outside them) and zero outside
// [start, start + duration], so its integral N(t) is piecewise quadratic.
// Particle k of the rate's stream is born when N(t) = k + u_k, u_k in [0, 1)
// from the counter-based hash (rng.h): births stay in index order, and no
// two frames or machines can disagree on them. The inversion is exact per
// segment: with r0 the rate at the segment's start, s its slope and D the
// count still to go in it, the time into the segment is
//     x = 2 D / (r0 + sqrt(r0^2 + 2 s D))
// (the root of r0 x + s x^2 / 2 = D written without cancellation, also for
// s < 0 and r0 = 0). Bursts are streams of their own: burst b's particles
// are stream b + 1, all born at its time.
#include <cstdint>
#include <vector>

#include "particles/emitter.h"

namespace hs::particles {

class SpawnSchedule {
 public:
  explicit SpawnSchedule(const EmitterDesc& e);

  // N(t): particles the rate has made by scene time t (a real number).
  double integral(double t) const;
  // The scene time at which N reaches `n` (n in [0, total()]); +inf above.
  double invert(double n) const;
  double total() const { return cum_.empty() ? 0.0 : cum_.back(); }

  // Birth time of the rate's particle k (+inf if never born).
  double birth(uint64_t k) const;
  // Rate particles born at or before t: the k with birth(k) <= t are
  // exactly [0, bornBy(t)).
  uint64_t bornBy(double t) const;
  // The jitter u_k of particle k.
  double jitter(uint64_t k) const;

 private:
  uint32_t seed_ = 0;
  std::vector<double> at_;    // segment boundaries (scene time)
  std::vector<double> rate_;  // rate at each boundary
  std::vector<double> cum_;   // N at each boundary
};

}  // namespace hs::particles
