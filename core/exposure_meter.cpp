#include "core/exposure_meter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs {

uint64_t ExposureHistogram::total() const {
  uint64_t n = 0;
  for (uint64_t c : counts) n += c;
  return n;
}

double ExposureHistogram::binCentreEv(int bin) const {
  return minEv100 + (double(bin) + 0.5) * (maxEv100 - minEv100) / kBins;
}

double ev100OfLuminance(double nits) {
  // A reflected-light meter's calibration K = 12.5 at ISO 100: EV100 = log2(L · S / K).
  return nits > 0.0 ? std::log2(nits * (100.0 / 12.5)) : -std::numeric_limits<double>::infinity();
}

ExposureHistogram luminanceHistogram(const float* rgba, size_t pixels, double nitsPerValue, double minEv100,
                                     double maxEv100) {
  ExposureHistogram h;
  h.minEv100 = minEv100;
  h.maxEv100 = std::max(maxEv100, minEv100 + 1e-6);
  const double binsPerEv = ExposureHistogram::kBins / (h.maxEv100 - h.minEv100);
  for (size_t i = 0; i < pixels; ++i) {
    const float* p = rgba + 4 * i;
    const double y = (0.2126 * double(p[0]) + 0.7152 * double(p[1]) + 0.0722 * double(p[2])) * nitsPerValue;
    if (!std::isfinite(y) || y < 0.0) {
      ++h.rejected;
      continue;
    }
    const double ev = ev100OfLuminance(y);  // -inf for black: the first bin
    const double b = std::floor((ev - h.minEv100) * binsPerEv);
    const int bin = b < 0.0 ? 0 : b >= ExposureHistogram::kBins ? ExposureHistogram::kBins - 1 : int(b);
    ++h.counts[size_t(bin)];
  }
  return h;
}

double meteredEv100(const ExposureHistogram& h, const ExposureMetering& m) {
  const double lo = std::min(m.minEv100, m.maxEv100), hi = std::max(m.minEv100, m.maxEv100);
  const uint64_t n = h.total();
  if (n == 0) return 0.5 * (lo + hi) - m.compensationEv;
  // The counted share of each bin between the low and high percentiles
  // (a bin straddling either counts in part), averaged at bin centres.
  const double lowP = std::clamp(m.lowPercent, 0.0, 100.0), highP = std::clamp(m.highPercent, lowP, 100.0);
  double from = double(n) * lowP / 100.0, to = double(n) * highP / 100.0;
  if (to - from < 1.0) {  // a band thinner than a pixel: the pixel at its middle
    const double mid = 0.5 * (from + to);
    from = std::max(0.0, mid - 0.5);
    to = from + 1.0;
  }
  double weight = 0.0, sum = 0.0, below = 0.0;
  for (int b = 0; b < ExposureHistogram::kBins; ++b) {
    const double c = double(h.counts[size_t(b)]);
    const double w = std::max(0.0, std::min(below + c, to) - std::max(below, from));
    weight += w;
    sum += w * h.binCentreEv(b);
    below += c;
  }
  const double mean = weight > 0.0 ? sum / weight : 0.5 * (lo + hi);
  return std::clamp(mean, lo, hi) - m.compensationEv;
}

namespace {

double minSpeed(const ExposureAdaptation& a) { return std::max(1e-6, std::min(a.speedUp, a.speedDown)); }
double stepOf(const ExposureAdaptation& a) { return 1.0 / std::clamp(a.probesPerSecond, 1e-3, 1e3); }

}  // namespace

AdaptationWindow adaptationWindow(double sinceShotStart, const ExposureAdaptation& a) {
  AdaptationWindow w;
  w.step = stepOf(a);
  const double t = std::max(0.0, sinceShotStart);
  // The last grid step at or before t; a t a rounding error short of a
  // step counts as on it (frame times are products of the frame rate).
  w.last = int64_t(std::floor(t / w.step + 1e-9));
  const double span = a.windowTimeConstants / minSpeed(a);
  const int64_t steps = std::clamp<int64_t>(int64_t(std::ceil(span / w.step)), 1, std::max(1, a.maxProbes) - 1);
  w.first = std::max<int64_t>(0, w.last - steps);
  w.residualWeight = w.first == 0 ? 0.0 : std::exp(-minSpeed(a) * (t - double(w.first) * w.step));
  return w;
}

double adaptedEv100(double sinceShotStart, const ExposureAdaptation& a, const std::function<double(int64_t)>& targetAt) {
  const AdaptationWindow w = adaptationWindow(sinceShotStart, a);
  const double up = std::max(0.0, a.speedUp), down = std::max(0.0, a.speedDown);
  // One exactly integrated step of length dt towards the held target T:
  // e^(−speed·dt) is in (0, 1] for any speed, so nothing can overshoot.
  auto toward = [&](double e, double target, double dt) {
    const double speed = target > e ? up : down;
    return target + (e - target) * std::exp(-speed * dt);
  };
  double e = targetAt(w.first);
  double held = e;  // the target held over the step that follows a grid point
  for (int64_t g = w.first + 1; g <= w.last; ++g) {
    e = toward(e, held, w.step);
    held = targetAt(g);
  }
  const double rest = std::max(0.0, sinceShotStart) - double(w.last) * w.step;
  if (rest > 0.0) e = toward(e, held, rest);
  return e;
}

}  // namespace hs
