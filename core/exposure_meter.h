#pragma once
// Automatic exposure's arithmetic (docs/rendering.md "Automatic exposure"),
// no GL: metering an HDR image through a histogram of its luminance, and the
// eye's adaptation over time as a pure function of the time (DESIGN.md "Time
// and determinism"). The exposure at time t is computed from targets metered
// at fixed times of a grid (the shot's start + g·h), never from the frame
// before, so a frame rendered alone equals the same frame in a sequence, a
// farm chunk or a scrub. render/auto_exposure.h renders the probes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace hs {

// A histogram of log2 luminance as EV100 (the exposure a reflected-light
// meter would set: EV100 = log2(L · 100 / 12.5), L in cd/m²). Pixels below
// the range count in the first bin, above it in the last; NaN, infinite or
// negative pixels are left out (`rejected`).
struct ExposureHistogram {
  static constexpr int kBins = 128;
  std::array<uint64_t, kBins> counts{};
  uint64_t rejected = 0;
  double minEv100 = -4.0;
  double maxEv100 = 24.0;
  uint64_t total() const;
  double binCentreEv(int bin) const;
  bool operator==(const ExposureHistogram&) const = default;
};

// The EV100 of luminance `nits` (log2(nits · 8)); -inf at 0.
double ev100OfLuminance(double nits);

// Rec. 709 luminance of linear RGBA pixels (`pixels` of 4 floats) times
// `nitsPerValue`, binned over [minEv100, maxEv100].
ExposureHistogram luminanceHistogram(const float* rgba, size_t pixels, double nitsPerValue, double minEv100 = -4.0,
                                     double maxEv100 = 24.0);

// How a histogram becomes the exposure to set (PostSettings's
// post.auto_exposure.*): the mean EV of the pixels between the
// `lowPercent` darkest and the `highPercent` brightest (the sky's sun and
// the deepest shadows do not swing it), clamped to [minEv100, maxEv100],
// then `compensationEv` subtracted (positive: a brighter image).
struct ExposureMetering {
  double minEv100 = -2.0;
  double maxEv100 = 20.0;
  double lowPercent = 10.0;
  double highPercent = 90.0;
  double compensationEv = 0.0;
};
// The EV100 to set; with no pixel counted (all rejected) the middle of the range.
double meteredEv100(const ExposureHistogram& h, const ExposureMetering& m);

// Adaptation (Unreal's eye adaptation, without its dependence on the frame
// before): the exposure E follows the metered target T by
// dE/dt = speed · (T − E), `speedUp` while T is above E (the scene got
// brighter), `speedDown` below. T is sampled on a grid of step
// h = 1 / probesPerSecond from the shot's start and held over each step
// (sample and hold), and each step is integrated exactly
// (E ← T + (E − T)·e^(−speed·h)), so any speed is stable: a stiff one
// simply follows the target. The history starts at the shot's start, or
// `windowTimeConstants` / min(speed) before t (at most `maxProbes` steps),
// from the target there: what it leaves out weighs at most
// e^(−min(speed)·window) of the difference it had.
struct ExposureAdaptation {
  double speedUp = 3.0;          // per second
  double speedDown = 1.0;        // per second
  double probesPerSecond = 4.0;  // the grid
  double windowTimeConstants = 5.0;
  int maxProbes = 64;
};

// The grid steps that adaptation at `t` (seconds after the shot began)
// reads: targets at g·h for g in [first, last].
struct AdaptationWindow {
  int64_t first = 0;
  int64_t last = 0;
  double step = 0.25;  // h, seconds
  // How much of the difference between the true history and the assumed
  // start (E = T at `first`) can remain at t: e^(−min(speed)·(t − first·h)),
  // 0 when the window reaches the shot's start.
  double residualWeight = 0.0;
};
AdaptationWindow adaptationWindow(double sinceShotStart, const ExposureAdaptation& a);

// The adapted EV100 at `sinceShotStart` seconds into the shot, from the
// targets at the window's grid steps (`targetAt(g)`: the metered EV100 at
// the shot's start + g·h).
double adaptedEv100(double sinceShotStart, const ExposureAdaptation& a, const std::function<double(int64_t)>& targetAt);

}  // namespace hs
