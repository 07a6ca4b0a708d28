// core/exposure_meter: automatic exposure's metering (the luminance
// histogram, the percentile band's mean against exact values) and its
// adaptation over time against the exact solution of its equation (a step
// of the target: dE/dt = speed·(T − E) solved in closed form), its error
// against the grid step on a smooth target (first order), stiff and
// extreme speeds, bad pixels (NaN, infinite, negative, black), and purity:
// the adapted value at t reads only the targets of its window.
#include <QtTest>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "core/exposure_meter.h"

using namespace hs;

namespace {

// `n` grey pixels of luminance `nits` (R = G = B, so Rec. 709's Y is the value).
void addGrey(std::vector<float>& px, size_t n, double nits) {
  for (size_t i = 0; i < n; ++i) px.insert(px.end(), {float(nits), float(nits), float(nits), 1.0f});
}

double meter(const std::vector<float>& px, const ExposureMetering& m = {}) {
  return meteredEv100(luminanceHistogram(px.data(), px.size() / 4, 1.0), m);
}

// Half a bin of the default histogram: the most a bin centre is off.
constexpr double kHalfBin = 0.5 * 28.0 / ExposureHistogram::kBins;

}  // namespace

class TestExposureMeter : public QObject {
  Q_OBJECT
 private slots:
  void uniformImageMetersItsLuminance() {
    // A reflected-light meter: EV100 = log2(L · 100 / 12.5).
    for (double nits : {0.5, 12.5, 400.0, 9000.0}) {
      std::vector<float> px;
      addGrey(px, 1000, nits);
      QVERIFY2(std::abs(meter(px) - std::log2(nits * 8.0)) <= kHalfBin, qPrintable(QString::number(nits)));
    }
  }

  void percentileBandAveragesItsShare() {
    // 30 % dark (EV 2), 70 % bright (EV 12); the band 10..90 % holds 20 %
    // of the dark and 60 % of the bright: mean (0.2·2 + 0.6·12) / 0.8.
    std::vector<float> px;
    addGrey(px, 300, std::exp2(2.0) / 8.0);
    addGrey(px, 700, std::exp2(12.0) / 8.0);
    const double expected = (0.2 * 2.0 + 0.6 * 12.0) / 0.8;
    QVERIFY(std::abs(meter(px) - expected) <= kHalfBin);
    // 0..100 %: the plain mean.
    ExposureMetering all;
    all.lowPercent = 0.0;
    all.highPercent = 100.0;
    QVERIFY(std::abs(meter(px, all) - (0.3 * 2.0 + 0.7 * 12.0)) <= kHalfBin);
    // 0..30 %: the dark pixels alone; 30..100 %: the bright alone.
    ExposureMetering dark = all, bright = all;
    dark.highPercent = 30.0;
    bright.lowPercent = 30.0;
    QVERIFY(std::abs(meter(px, dark) - 2.0) <= kHalfBin);
    QVERIFY(std::abs(meter(px, bright) - 12.0) <= kHalfBin);
    // An empty band (low = high) still meters: the pixel at its place.
    ExposureMetering thin = all;
    thin.lowPercent = thin.highPercent = 50.0;
    QVERIFY(std::abs(meter(px, thin) - 12.0) <= kHalfBin);
  }

  void clampAndCompensation() {
    std::vector<float> px;
    addGrey(px, 100, std::exp2(25.0) / 8.0);  // brighter than the histogram's range
    ExposureMetering m;
    QCOMPARE(meter(px, m), m.maxEv100);
    m.compensationEv = 1.5;  // a brighter image: a lower EV
    QCOMPARE(meter(px, m), m.maxEv100 - 1.5);
    std::vector<float> black;
    addGrey(black, 100, 0.0);  // log2(0) = -inf: the first bin, then the minimum
    QCOMPARE(meter(black), ExposureMetering{}.minEv100);
  }

  void badPixelsAreLeftOut() {
    std::vector<float> px;
    addGrey(px, 100, 100.0);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    px.insert(px.end(), {nan, 0.0f, 0.0f, 1.0f, inf, inf, inf, 1.0f, -5.0f, -5.0f, -5.0f, 1.0f});
    const ExposureHistogram h = luminanceHistogram(px.data(), px.size() / 4, 1.0);
    QCOMPARE(h.rejected, uint64_t(3));
    QCOMPARE(h.total(), uint64_t(100));
    QVERIFY(std::abs(meteredEv100(h, {}) - std::log2(800.0)) <= kHalfBin);
    // Nothing usable: the middle of the range, not a NaN.
    std::vector<float> none = {nan, nan, nan, 1.0f};
    const double ev = meter(none);
    QVERIFY(std::isfinite(ev));
    QCOMPARE(ev, 0.5 * (ExposureMetering{}.minEv100 + ExposureMetering{}.maxEv100));
  }

  void stepOfTheTargetFollowsTheExactSolution() {
    // The target jumps from A to B at a grid step (t = 2 s); before, E = A.
    // The equation's exact solution: E(t) = B + (A − B)·e^(−speed·(t − 2)).
    ExposureAdaptation a;  // speeds 3 (up) and 1 (down), 4 probes a second
    for (auto [from, to] : {std::pair{12.0, 6.0}, std::pair{6.0, 12.0}}) {
      const double speed = to > from ? a.speedUp : a.speedDown;
      auto target = [&](int64_t g) { return double(g) * 0.25 < 2.0 ? from : to; };
      for (double t : {0.0, 1.0, 1.99, 2.0, 2.1, 2.5, 3.0, 3.7, 4.0}) {
        const double exact = t < 2.0 ? from : to + (from - to) * std::exp(-speed * (t - 2.0));
        QVERIFY2(std::abs(adaptedEv100(t, a, target) - exact) < 1e-9,
                 qPrintable(QString("t %1: %2 vs %3").arg(t).arg(adaptedEv100(t, a, target)).arg(exact)));
      }
    }
  }

  void smoothTargetErrorIsFirstOrderInTheStep() {
    // T(t) = 10 + 3 sin(2t), one speed: the reference integrates the
    // equation with 1000 steps a second. Halving the grid step halves the
    // error (sample and hold is first order); the figures are the ones
    // bench_post prints.
    auto errorAt = [](double probesPerSecond) {
      ExposureAdaptation a;
      a.speedUp = a.speedDown = 2.0;
      a.maxProbes = 100000;
      ExposureAdaptation fine = a;
      a.probesPerSecond = probesPerSecond;
      fine.probesPerSecond = 1000.0;
      double worst = 0.0;
      for (double t = 3.0; t <= 6.0; t += 0.05) {
        auto target = [](const ExposureAdaptation& x) {
          return [&x](int64_t g) { return 10.0 + 3.0 * std::sin(2.0 * double(g) / x.probesPerSecond); };
        };
        worst = std::max(worst, std::abs(adaptedEv100(t, a, target(a)) - adaptedEv100(t, fine, target(fine))));
      }
      return worst;
    };
    const double e4 = errorAt(4.0), e8 = errorAt(8.0), e16 = errorAt(16.0);
    QVERIFY2(e4 > e8 && e8 > e16, qPrintable(QString("%1 %2 %3").arg(e4).arg(e8).arg(e16)));
    QVERIFY(e4 / e8 > 1.6 && e4 / e8 < 2.5);
    QVERIFY(e8 / e16 > 1.6 && e8 / e16 < 2.5);
    QVERIFY(e4 < 1.0);  // under an EV at 4 probes a second for a swing of ±3 EV every 3 s
  }

  void stiffAndExtremeSpeedsStayFinite() {
    auto target = [](int64_t g) { return g % 2 ? 14.0 : 4.0; };  // the worst: a jump every step
    for (double speed : {0.01, 1.0, 1e3, 1e9, 1e300}) {
      ExposureAdaptation a;
      a.speedUp = a.speedDown = speed;
      for (double t : {0.0, 0.3, 10.0, 1e6}) {
        const double e = adaptedEv100(t, a, target);
        QVERIFY2(std::isfinite(e) && e >= 4.0 - 1e-9 && e <= 14.0 + 1e-9,
                 qPrintable(QString("speed %1 t %2: %3").arg(speed).arg(t).arg(e)));
      }
      // Stiff: follows the held target (the last step's) exactly.
      if (speed >= 1e3) QCOMPARE(adaptedEv100(10.1, a, target), target(40));
    }
    // A zero speed stays where the window began; a negative one is no speed.
    ExposureAdaptation still;
    still.speedUp = still.speedDown = 0.0;
    QVERIFY(std::isfinite(adaptedEv100(5.0, still, target)));
    still.speedUp = still.speedDown = -4.0;
    QVERIFY(std::isfinite(adaptedEv100(5.0, still, target)));
  }

  void windowIsBoundedAndSaysWhatItLeavesOut() {
    ExposureAdaptation a;  // min speed 1, 5 time constants: 5 s = 20 steps
    const AdaptationWindow early = adaptationWindow(2.0, a);
    QCOMPARE(early.first, int64_t(0));
    QCOMPARE(early.last, int64_t(8));
    QCOMPARE(early.residualWeight, 0.0);  // reaches the shot's start
    const AdaptationWindow late = adaptationWindow(100.0, a);
    QCOMPARE(late.last, int64_t(400));
    QCOMPARE(late.first, int64_t(380));
    QVERIFY(std::abs(late.residualWeight - std::exp(-5.0)) < 1e-12);
    // A slow speed wants a long window: capped at maxProbes.
    a.speedDown = 0.01;
    const AdaptationWindow capped = adaptationWindow(1000.0, a);
    QCOMPARE(capped.last - capped.first, int64_t(a.maxProbes - 1));
    QVERIFY(capped.residualWeight > 0.5);
    // Frame times a rounding error short of a step count as on it.
    QCOMPARE(adaptationWindow(0.75 - 1e-13, ExposureAdaptation{}).last, int64_t(3));
  }

  void adaptationReadsOnlyItsWindow() {
    // A pure function of t: the targets asked are exactly the window's grid
    // steps, and asking again gives the same value bit for bit.
    ExposureAdaptation a;
    std::set<int64_t> asked;
    auto target = [&](int64_t g) {
      asked.insert(g);
      return 8.0 + double(g % 7);
    };
    const double first = adaptedEv100(30.4, a, target);
    const AdaptationWindow w = adaptationWindow(30.4, a);
    QCOMPARE(int64_t(asked.size()), w.last - w.first + 1);
    QCOMPARE(*asked.begin(), w.first);
    QCOMPARE(*asked.rbegin(), w.last);
    QCOMPARE(adaptedEv100(30.4, a, target), first);
    // Before the shot's start (negative time): its start.
    QCOMPARE(adaptedEv100(-3.0, a, target), target(0));
  }
};

QTEST_GUILESS_MAIN(TestExposureMeter)
#include "test_exposure_meter.moc"
