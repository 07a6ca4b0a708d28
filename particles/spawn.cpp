#include "particles/spawn.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "particles/rng.h"

namespace hs::particles {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

SpawnSchedule::SpawnSchedule(const EmitterDesc& e) : seed_(e.seed) {
  const double a = e.start, b = e.start + e.duration;
  if (!(b > a)) return;
  at_.push_back(a);
  for (const CurveKey& k : e.rateKeys.keys)
    if (k.t > a && k.t < b) at_.push_back(k.t);
  at_.push_back(b);
  for (double t : at_) rate_.push_back(std::max(0.0, e.rateKeys.eval(t, e.rate)));
  cum_.push_back(0.0);
  for (size_t i = 1; i < at_.size(); ++i)
    cum_.push_back(cum_.back() + 0.5 * (rate_[i - 1] + rate_[i]) * (at_[i] - at_[i - 1]));
}

double SpawnSchedule::integral(double t) const {
  if (at_.empty() || t <= at_.front()) return 0.0;
  if (t >= at_.back()) return cum_.back();
  const size_t i = size_t(std::upper_bound(at_.begin(), at_.end(), t) - at_.begin()) - 1;
  const double x = t - at_[i], len = at_[i + 1] - at_[i];
  const double s = (rate_[i + 1] - rate_[i]) / len;
  return cum_[i] + x * (rate_[i] + 0.5 * s * x);
}

double SpawnSchedule::invert(double n) const {
  if (at_.empty() || !(n <= cum_.back())) return kInf;
  if (n <= 0.0) return at_.front();
  // The last boundary with cum <= n whose segment still adds something.
  size_t i = size_t(std::upper_bound(cum_.begin(), cum_.end(), n) - cum_.begin());
  i = i == 0 ? 0 : i - 1;
  if (i >= at_.size() - 1) {
    // n == total: the end of the last segment that makes particles.
    i = at_.size() - 2;
    while (i > 0 && cum_[i] >= n) --i;
  }
  const double len = at_[i + 1] - at_[i];
  const double r0 = rate_[i], s = (rate_[i + 1] - rate_[i]) / len, d = n - cum_[i];
  const double disc = std::max(0.0, r0 * r0 + 2.0 * s * d);
  const double den = r0 + std::sqrt(disc);
  const double x = den > 0.0 ? 2.0 * d / den : 0.0;
  return at_[i] + std::clamp(x, 0.0, len);
}

double SpawnSchedule::jitter(uint64_t k) const {
  return unitFromHash(hashKey(seed_, uint32_t(k >> 32) * 0x9e3779b9U, uint32_t(k), uint32_t(Attr::BirthJitter)));
}

double SpawnSchedule::birth(uint64_t k) const {
  const double target = double(k) + jitter(k);
  if (at_.empty() || !(target < cum_.back())) return kInf;
  return invert(target);
}

uint64_t SpawnSchedule::bornBy(double t) const {
  if (at_.empty() || !(t >= at_.front())) return 0;
  const double n = integral(t);
  // First guess from N(t), then settle on births as birth() computes them,
  // so bornBy and birth never disagree by a rounding.
  uint64_t c = uint64_t(std::floor(n));
  if (jitter(c) <= n - double(c)) ++c;
  while (c > 0 && !(birth(c - 1) <= t)) --c;
  while (birth(c) <= t) ++c;
  return c;
}

}  // namespace hs::particles
